//! Object-mode editing: selection, picking in the viewport, Blender-style
//! shortcuts and the modal move/rotate/scale tool (G/R/S).
//!
//! Tools never touch the document directly: they preview on entities and
//! send one [`DocRequest`] when the user confirms, so a drag is one undo step.

// Bevy systems take their world access as parameters: long parameter lists
// and nested query types are how Bevy code is written (Bevy allows both too).
#![allow(clippy::too_many_arguments, clippy::type_complexity)]

use bevy::prelude::*;
use glam::{DMat4, DQuat, DVec3};
use hedra_doc::{Command, NodeId, NodeTransform};
use hedra_scene::modifiers::shift;
use hedra_scene::{DocRequest, DocState, InputGate, SceneSystems, SettingsApp};

pub mod bindings;
mod cursor;
mod curve_draw;
pub mod mesh_mode;
pub mod modal;
pub mod object_mode;
mod proportional;
mod requests;
pub mod shape_mode;
mod snapping;
pub mod typing;

pub use cursor::place_cursor;
pub use curve_draw::{CurveDraw, DrawKind, axis_command, construction_plane};
pub use hedra_doc::csg::{is_within, outermost_csg};
pub use mesh_mode::{
    BisectDrag, EditMode, ElementKind, ElementSelection, KnifeTool, MeshTool, MeshToolKind,
    start_bisect,
};
pub use modal::{Axis, ModalTransform, TransformKind, TransformTool};
pub use object_mode::{
    Selection, boolean_command, curve_near_cursor, follow_document_changes, join_curves_command,
    object_shortcuts, pick_node, visible,
};
pub use proportional::{Proportional, ProportionalRing, proportional_keys};
pub use requests::{EditRequest, apply_edit_requests};
pub use shape_mode::ShapeEdit;
pub use snapping::{
    MoveSnap, SnapElement, SnapMesh, SnapScene, SnapTarget, Snapping, drag_translation, move_snap,
    snap_translation, snapping_keys,
};

/// Tools, selection and shortcuts, in [`SceneSystems::Tools`]: they read
/// this frame's input and write requests, which [`SceneSystems::Apply`]
/// applies in the same frame, so the frame that confirms a tool already
/// shows its result.
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub struct EditSystems;

/// Selection, picking, shortcuts and the transform tool.
pub struct EditPlugin;

impl Plugin for EditPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<Selection>()
            .init_resource::<TransformTool>()
            .init_resource::<EditMode>()
            .init_resource::<mesh_mode::BisectDrag>()
            .init_resource::<mesh_mode::KnifeTool>()
            .init_resource::<Snapping>()
            .init_resource::<SnapTarget>()
            .init_resource::<Proportional>()
            .init_resource::<bindings::KeyHelp>()
            .init_resource::<bindings::RequestedAction>()
            .init_resource::<PivotPoint>()
            .init_resource::<ProportionalRing>()
            .init_resource::<AxisLock>()
            .init_resource::<ShapeEdit>()
            .init_resource::<CurveDraw>()
            .add_setting::<Snapping>()
            .add_setting::<Proportional>()
            .add_setting::<bindings::KeyHelp>()
            .add_setting::<PivotPoint>()
            .add_message::<EditRequest>()
            .add_systems(Update, apply_edit_requests.in_set(SceneSystems::Requests))
            .configure_sets(Update, EditSystems.in_set(SceneSystems::Tools))
            // What a command created is selected in the frame that applied
            // it, so that frame already draws it selected.
            .add_systems(
                Update,
                follow_document_changes
                    .in_set(SceneSystems::Apply)
                    .after(hedra_scene::apply_requests),
            )
            .add_systems(
                Update,
                (
                    (mesh_mode::follow_changes, mesh_mode::mode_keys).chain(),
                    snapping_keys,
                    proportional_keys,
                    bindings::key_help_keys,
                    pivot_keys,
                    undo_keys,
                    clear_tool_overlays,
                    modal::drive_transform_tool,
                    mesh_mode::drive_mesh_tool,
                    object_shortcuts,
                    subdivision_keys,
                    mesh_mode::edit_shortcuts,
                    mesh_mode::bisect_by_drag,
                    mesh_mode::start_knife,
                    mesh_mode::drive_knife,
                    place_cursor,
                    object_mode::pick_objects,
                    mesh_mode::select_elements,
                )
                    .chain()
                    .in_set(EditSystems),
            )
            .add_systems(
                Update,
                (
                    shape_mode::shape_follow_changes,
                    shape_mode::shape_mode_keys,
                    shape_mode::drive_shape_tool,
                    shape_mode::shape_select_and_shortcuts,
                    curve_draw::drive_curve_draw,
                    publish_axis_lock,
                )
                    .chain()
                    .after(mesh_mode::select_elements)
                    .in_set(EditSystems),
            );
    }
}

/// The axis a running move, rotate or scale is locked to (X, Y or Z) and
/// the pivot it passes through, for drawing the constraint line as Blender
/// does; `None` while no tool runs or its axis is free.
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq)]
pub struct AxisLock(pub Option<(DVec3, Axis)>);

/// Publishes [`AxisLock`] from whichever tool runs (object G/R/S, a mesh
/// tool, a control-point tool), after they have read this frame's keys.
fn publish_axis_lock(
    tool: Res<TransformTool>,
    mode: Res<EditMode>,
    shape_edit: Res<ShapeEdit>,
    mut lock: ResMut<AxisLock>,
) {
    let now = tool
        .active
        .as_ref()
        .and_then(|t| Some((t.pivot(), t.axis?)))
        .or_else(|| mode.tool.as_ref().and_then(|t| Some((t.pivot(), t.axis?))))
        .or_else(|| {
            shape_edit
                .tool
                .as_ref()
                .and_then(|t| Some((t.pivot, t.axis?)))
        });
    lock.set_if_neq(AxisLock(now));
}

/// Clears what the running tools drew last frame (the snap target and the
/// proportional ring); the tool still running publishes it again.
fn clear_tool_overlays(mut snap_target: ResMut<SnapTarget>, mut ring: ResMut<ProportionalRing>) {
    snap_target.0 = None;
    ring.0 = None;
}

/// Whether a modal tool runs (object G/R/S, a mesh tool, a control-point
/// tool): its keys and clicks are not shortcuts then.
pub fn modal_tool_running(tool: &TransformTool, mode: &EditMode, shape_edit: &ShapeEdit) -> bool {
    tool.active.is_some() || mode.tool.is_some() || shape_edit.tool.is_some()
}

/// Ctrl+Z / Ctrl+Shift+Z (and Ctrl+Y), in both modes, when no tool runs.
pub fn undo_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    tool: Res<TransformTool>,
    mode: Res<EditMode>,
    mut requests: MessageWriter<DocRequest>,
) {
    if !gate.keyboard_free || tool.active.is_some() || mode.tool.is_some() {
        return;
    }
    let pressed = |action| bindings::pressed(&keys, bindings::KeyMode::Everywhere, action);
    if pressed(bindings::Action::Undo) {
        requests.write(DocRequest::Undo);
    } else if pressed(bindings::Action::Redo) {
        requests.write(DocRequest::Redo);
    }
}

/// What R and S turn and scale about (Blender's Pivot Point).
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum PivotPoint {
    /// The median of the selected objects' origins, or of the selected
    /// vertices in edit mode.
    #[default]
    MedianPoint,
    /// The 3D cursor.
    Cursor,
}

impl PivotPoint {
    /// The name the View menu and the status line show.
    pub fn label(self) -> &'static str {
        match self {
            PivotPoint::MedianPoint => "Median Point",
            PivotPoint::Cursor => "3D Cursor",
        }
    }
}

/// `.` switches the pivot point between the median and the 3D cursor (in
/// Blender it opens the pivot menu).
pub fn pivot_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut pivot: ResMut<PivotPoint>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    if gate.keyboard_free
        && bindings::pressed(
            &keys,
            bindings::KeyMode::Everywhere,
            bindings::Action::PivotPoint,
        )
    {
        *pivot = match *pivot {
            PivotPoint::MedianPoint => PivotPoint::Cursor,
            PivotPoint::Cursor => PivotPoint::MedianPoint,
        };
        status.info(format!(
            "Pivot: {} (R and S turn and scale about it; . switches)",
            pivot.label()
        ));
    }
}

/// Ctrl+0…Ctrl+5 set the subdivision level of the selected meshes (or of
/// the mesh in edit mode), adding a Catmull-Clark modifier when there is
/// none, like Blender; Ctrl+0 shows the cage alone. Page Up / Page Down step
/// the level of meshes that have a modifier.
pub fn subdivision_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    tool: Res<TransformTool>,
    mode: Res<EditMode>,
    selection: Res<Selection>,
    state: Res<DocState>,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    if !gate.keyboard_free || tool.active.is_some() || mode.tool.is_some() {
        return;
    }
    const LEVEL_KEYS: [(KeyCode, u32); 6] = [
        (KeyCode::Digit0, 0),
        (KeyCode::Digit1, 1),
        (KeyCode::Digit2, 2),
        (KeyCode::Digit3, 3),
        (KeyCode::Digit4, 4),
        (KeyCode::Digit5, 5),
    ];
    use bindings::{Action, KeyMode::Everywhere};
    let set_level = bindings::pressed_key(&keys, Everywhere, Action::SubdivisionLevel)
        .and_then(|key| LEVEL_KEYS.iter().find(|(k, _)| *k == key))
        .map(|&(_, level)| level);
    let step: i64 = if bindings::pressed(&keys, Everywhere, Action::SubdivisionUp) {
        1
    } else if bindings::pressed(&keys, Everywhere, Action::SubdivisionDown) {
        -1
    } else {
        0
    };
    if set_level.is_none() && step == 0 {
        return;
    }
    let doc = &state.session.doc;
    let targets: Vec<NodeId> = match mode.node {
        Some(n) => vec![n],
        None => selection.nodes.to_vec(),
    };
    let mut changed = Vec::new();
    for id in targets {
        let Some(node) = doc.node(id) else { continue };
        // Meshes and kept (non-manifold) meshes both have the modifier.
        let subdivision = match &node.content {
            hedra_doc::NodeContent::Mesh(content) => content.subdivision,
            hedra_doc::NodeContent::Kept(content) => content.subdivision,
            _ => continue,
        };
        let modifier = match (set_level, subdivision) {
            (Some(level), Some(mut m)) => {
                m.viewport_level = level;
                m
            }
            (Some(level), None) => hedra_doc::SubdivisionModifier::with_level(level),
            (None, Some(mut m)) => {
                let level = (m.viewport_level as i64 + step)
                    .clamp(0, hedra_geom::subdivision::MAX_VIEWPORT_LEVEL as i64)
                    as u32;
                if level == m.viewport_level {
                    continue;
                }
                m.viewport_level = level;
                m
            }
            (None, None) => continue,
        };
        if subdivision != Some(modifier) {
            changed.push((id, modifier));
        }
    }
    if changed.is_empty() {
        status.error(if set_level.is_some() {
            "Subdivision: select a mesh first"
        } else {
            "Page Up/Down: no selected mesh has a subdivision modifier (Ctrl+1 adds one)"
        });
        return;
    }
    // One command (one undo step) per distinct modifier: Ctrl+2 on meshes
    // with no modifier, or with the same one, is a single step.
    let mut groups: Vec<(hedra_doc::SubdivisionModifier, Vec<hedra_doc::NodeRef>)> = Vec::new();
    for (id, modifier) in changed {
        match groups.iter_mut().find(|(m, _)| *m == modifier) {
            Some((_, nodes)) => nodes.push(id.into()),
            None => groups.push((modifier, vec![id.into()])),
        }
    }
    for (modifier, nodes) in groups {
        requests.write(DocRequest::Execute(Command::SetSubdivision {
            nodes,
            modifier: Some(modifier),
        }));
    }
}

/// Local transform that puts a node at `world` under a parent at `parent_world`.
pub fn local_from_world(parent_world: DMat4, world: DMat4) -> NodeTransform {
    NodeTransform::from_matrix(parent_world.inverse() * world)
}

/// True while the pointer is on a transform gizmo handle or drags one: a
/// click there belongs to the gizmo, not to selection.
pub fn gizmo_has_pointer(gizmo: Option<&TransformGizmoState>) -> bool {
    gizmo.is_some_and(|g| g.hovered_axis.is_some() || g.active)
}

/// Rotation about a pivot as a matrix.
pub fn rotation_about(pivot: DVec3, rotation: DQuat) -> DMat4 {
    DMat4::from_translation(pivot) * DMat4::from_quat(rotation) * DMat4::from_translation(-pivot)
}
