//! The 3D viewport: orbit camera (`camera`), ground grid and axes (`grid`),
//! edge overlays with the selection highlighted and the edit-mode overlay
//! (`overlays`), the transform gizmo on the active object, the selected
//! mesh elements or control points (`gizmo`), and
//! curve and surface analysis (`analysis`). The systems here draw what the
//! document and the tools left; they run in `SceneSystems::View`.

// Bevy systems take their world access as parameters: long parameter lists
// and nested query types are how Bevy code is written (Bevy allows both too).
#![allow(clippy::too_many_arguments, clippy::type_complexity)]

use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::input::mouse::{AccumulatedMouseScroll, MouseScrollUnit};
use bevy::prelude::*;
use glam::DVec3;
use hedra_doc::{NodeContent, NodeId, NodeTransform};
use hedra_edit::{EditMode, ElementKind, Selection, TransformTool};
use hedra_scene::modifiers;
use hedra_scene::{
    DocRequest, DocState, InputGate, NodeEntity, SceneSystems, SettingsApp, ViewportCamera,
};
use std::f32::consts::FRAC_PI_2;

mod analysis;
mod camera;
mod gizmo;
mod grid;
mod overlays;
mod shading;

pub use analysis::*;
pub use camera::*;
use gizmo::*;
pub use grid::*;
pub use overlays::*;
pub use shading::shading_keys;

/// Edit ▸ Gizmo: what the transform gizmo does from now on (a panel's
/// request; Bevy's `TransformGizmoSettings` is not a value to send whole).
#[derive(Message, Clone, Copy, Debug, PartialEq, Eq)]
pub struct SetGizmoMode(pub bevy::gizmos::transform_gizmo::TransformGizmoMode);

/// Applies [`SetGizmoMode`] to the gizmo's settings.
pub fn apply_gizmo_mode(
    mut requests: MessageReader<SetGizmoMode>,
    mut settings: ResMut<bevy::gizmos::transform_gizmo::TransformGizmoSettings>,
) {
    if let Some(SetGizmoMode(mode)) = requests.read().last()
        && settings.mode != *mode
    {
        settings.mode = *mode;
    }
}

/// The camera, grid, overlays, gizmo and analysis drawing, in
/// `SceneSystems::View` (the gizmo's drag is a tool: `SceneSystems::Tools`).
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub struct ViewportSystems;

/// The camera, grid, overlays, gizmo and analysis drawing.
pub struct ViewportPlugin;

impl Plugin for ViewportPlugin {
    fn build(&self, app: &mut App) {
        app.configure_sets(Update, ViewportSystems.in_set(SceneSystems::View));
        app.init_resource::<CurveAnalysis>();
        app.init_resource::<SurfaceAnalysis>();
        app.add_setting::<CurveAnalysis>()
            .add_setting::<SurfaceAnalysis>()
            .add_message::<SetGizmoMode>()
            .add_systems(Update, apply_gizmo_mode.in_set(SceneSystems::Requests));
        app.init_resource::<SurfaceAnalysisShown>();
        app.insert_resource(ClearColor(Color::srgb(0.23, 0.23, 0.25)))
            .insert_resource(GlobalAmbientLight {
                brightness: 400.0,
                ..default()
            })
            .add_plugins(TransformGizmoPlugin)
            .insert_gizmo_config(
                AxisGizmos,
                GizmoConfig {
                    line: GizmoLineConfig {
                        width: 2.0,
                        ..default()
                    },
                    depth_bias: -0.001,
                    ..default()
                },
            )
            .insert_gizmo_config(
                CursorGizmos,
                GizmoConfig {
                    line: GizmoLineConfig {
                        width: 2.0,
                        ..default()
                    },
                    depth_bias: -1.0,
                    ..default()
                },
            )
            .add_systems(
                Startup,
                (spawn_camera, spawn_quad_cameras, spawn_gizmo_proxy),
            )
            // The gizmo's drag is a tool: its command is applied this frame.
            .add_systems(
                Update,
                drive_gizmo_drag
                    .after(hedra_edit::EditSystems)
                    .in_set(SceneSystems::Tools),
            )
            .add_systems(PostStartup, overlay_cameras_keep_the_picture)
            .add_systems(
                Update,
                (
                    shading_keys,
                    quad_view_keys,
                    camera_controls,
                    follow_quad_cameras,
                    frame_selection,
                    draw_grid,
                    draw_cursor,
                    draw_snap_target,
                    draw_proportional_ring,
                    draw_axis_lock,
                    draw_knife_path,
                    draw_curve_drawing,
                )
                    .chain()
                    .in_set(ViewportSystems),
            )
            .add_systems(
                Update,
                (
                    update_edge_overlays,
                    place_gizmo_proxy,
                    update_edit_edges,
                    draw_edit_overlay,
                    draw_shape_edit,
                    draw_curve_analysis,
                    closest_point_to_pointer,
                    draw_surface_analysis,
                    draw_sweep_frames,
                    draw_csg_ghosts,
                )
                    .in_set(ViewportSystems),
            );
    }
}
