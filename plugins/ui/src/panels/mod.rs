//! The egui layout, drawn by one system ([`draw_ui`]) that collects what the
//! user decided as [`UiEvent`]s and applies them after drawing. One file per
//! part: `menus` (menu bar, Mesh menu, Shift+A and M at the cursor),
//! `outliner`, `properties`, `windows` (Adjust Last, undo history),
//! `dialogs`, `status_bar`, `inspector` (topology tables) and
//! `weight_labels`.

use crate::files::{self, FilePurpose, Pending, Preferences, SamplesDir};
use crate::{FileAction, UiState, begin_path, run_pending, use_path};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, egui};
use glam::{DQuat, DVec3, EulerRot};
use hedra_doc::{Command, Document, NodeContent, NodeId, NodeRef, NodeTransform, Shading};
use hedra_edit::{EditMode, ElementKind, Selection, TransformTool};
use hedra_geom::Primitive;
use hedra_scene::{DocRequest, DocState, InputGate, StatusMessage};

mod add_menu;
mod construction_panel;
mod csg_menu;
mod curve_menu;
mod dialogs;
mod inspector;
mod menus;
mod mesh_menu;
mod modifier_stack;
mod outliner;
mod pointer_menus;
mod properties;
mod shape_panel;
mod status_bar;
mod subdivision_panel;
mod weight_labels;
mod windows;

use add_menu::*;
pub use add_menu::{ADD_MENU, AddPage};
use construction_panel::*;
use csg_menu::*;
use curve_menu::*;
use dialogs::*;
use inspector::*;
use menus::*;
use mesh_menu::*;
use modifier_stack::*;
use outliner::*;
use pointer_menus::*;
pub use pointer_menus::{MERGE_MENU, SNAP_MENU};
use properties::*;
use shape_panel::*;
use status_bar::*;
use subdivision_panel::*;
use weight_labels::*;
use windows::*;

/// A menu item's text with its keys in `mode` from the keymap after a tab,
/// so a menu cannot show a key that does something else.
fn keyed_in(
    mode: hedra_edit::bindings::KeyMode,
    label: &str,
    action: hedra_edit::bindings::Action,
) -> String {
    format!(
        "{label}\t{}",
        hedra_edit::bindings::chord_label(mode, action)
    )
}

/// What the panels decided this frame; applied after drawing.
enum UiEvent {
    Select(NodeId, bool),
    Request(DocRequest),
    File(FileAction),
    Preview(NodeId, NodeTransform),
    Error(String),
    /// Mesh ▸ Bisect: arm the drag of the cutting line.
    StartBisect,
    /// A menu item that starts the same interactive tool as its keys.
    Start(hedra_edit::bindings::Action),
    /// Add ▸ Draw Curve: start drawing a curve by clicks.
    DrawCurve,
    /// A panel field being dragged: the nodes' contents as they would become.
    PreviewContents(Vec<(NodeId, NodeContent)>),
    /// The *Pick axis* button of a revolution: click its axis's two points.
    PickAxis(NodeId),
}

#[derive(SystemParam)]
pub struct Writers<'w> {
    requests: MessageWriter<'w, DocRequest>,
    files: MessageWriter<'w, FileAction>,
    exit: MessageWriter<'w, AppExit>,
    analysis: ResMut<'w, hedra_viewport::CurveAnalysis>,
    surface_analysis: ResMut<'w, hedra_viewport::SurfaceAnalysis>,
    gizmo: ResMut<'w, bevy::gizmos::transform_gizmo::TransformGizmoSettings>,
    bisect: ResMut<'w, hedra_edit::BisectDrag>,
    snapping: ResMut<'w, hedra_edit::Snapping>,
    proportional: ResMut<'w, hedra_edit::Proportional>,
    key_help: ResMut<'w, hedra_edit::bindings::KeyHelp>,
    requested: ResMut<'w, hedra_edit::bindings::RequestedAction>,
    curve_draw: ResMut<'w, hedra_edit::CurveDraw>,
    pivot: ResMut<'w, hedra_edit::PivotPoint>,
    quad_view: ResMut<'w, hedra_scene::QuadView>,
    cursor: ResMut<'w, hedra_scene::Cursor3d>,
}

#[derive(SystemParam)]
pub struct Model<'w> {
    state: Res<'w, DocState>,
    selection: ResMut<'w, Selection>,
    tool: Res<'w, TransformTool>,
    status: ResMut<'w, StatusMessage>,
    prefs: Res<'w, Preferences>,
    samples: Option<Res<'w, SamplesDir>>,
    mode: ResMut<'w, EditMode>,
    previews: Res<'w, hedra_scene::SmoothPreviews>,
    jobs: Res<'w, hedra_scene::FileJobs>,
    shape_edit: Res<'w, hedra_edit::ShapeEdit>,
    shading: ResMut<'w, hedra_scene::ViewportShading>,
}

#[allow(clippy::too_many_arguments)]
pub fn draw_ui(
    mut contexts: EguiContexts,
    mut ui_state: ResMut<UiState>,
    mut model: Model,
    mut writers: Writers,
    mut gate: ResMut<InputGate>,
    mut tool_previews: ResMut<hedra_scene::Previews>,
    control_points: Query<(&hedra_scene::ControlPoint, &ChildOf)>,
    entities: Res<hedra_scene::NodeEntities>,
    camera: Query<(&Camera, &GlobalTransform), With<hedra_scene::ViewportCamera>>,
) -> Result {
    let ctx = contexts.ctx_mut()?.clone();
    let mut events: Vec<UiEvent> = Vec::new();
    let mut root = egui::Ui::new(
        ctx.clone(),
        "hedra-root".into(),
        egui::UiBuilder::new()
            .layer_id(egui::LayerId::background())
            .max_rect(ctx.viewport_rect()),
    );
    let doc = &model.state.session.doc;

    // View ▸ Gizmo chooses what the transform gizmo does.
    // View ▸ Wireframe and X-ray choose the shading.
    let mut gizmo_mode = writers.gizmo.mode;
    let mut shading = *model.shading;
    let mut snapping = *writers.snapping;
    let mut proportional = *writers.proportional;
    let mut pivot = *writers.pivot;
    let mut quad_view = writers.quad_view.0;
    let mut cursor = writers.cursor.0;
    let view_direction = camera
        .single()
        .ok()
        .map(|(_, t)| (t.rotation() * Vec3::NEG_Z).as_dvec3());
    // The view axis through the 3D cursor, for "Revolve about the view".
    ui_state.view_axis = view_direction.map(|d| (cursor, -d));
    egui::Panel::top("menu").show(&mut root, |ui| {
        let view = ViewChoices {
            view_direction,
            gizmo_mode: &mut gizmo_mode,
            shading: &mut shading,
            snapping: &mut snapping,
            proportional: &mut proportional,
            pivot: &mut pivot,
            quad_view: &mut quad_view,
            cursor: &mut cursor,
        };
        menu_bar(ui, &mut ui_state, &model, view, &mut events)
    });
    if writers.gizmo.mode != gizmo_mode {
        writers.gizmo.mode = gizmo_mode;
    }
    if *writers.snapping != snapping {
        *writers.snapping = snapping;
    }
    if *writers.proportional != proportional {
        *writers.proportional = proportional;
    }
    if *writers.pivot != pivot {
        *writers.pivot = pivot;
    }
    if writers.quad_view.0 != quad_view {
        writers.quad_view.0 = quad_view;
    }
    snap_menu(&ctx, &mut ui_state, &model, &mut cursor, &mut events);
    shading_menu(
        &ctx,
        &mut ui_state,
        &mut shading,
        &model.selection,
        &mut events,
    );
    if *model.shading != shading {
        *model.shading = shading;
    }
    if writers.cursor.0 != cursor {
        writers.cursor.0 = cursor;
    }
    egui::Panel::bottom("status").show(&mut root, |ui| status_bar(ui, &model));
    if ui_state.show_outliner {
        egui::Panel::left("outliner")
            .resizable(true)
            .default_size(220.0)
            .show(&mut root, |ui| {
                ui.heading("Outliner");
                ui.separator();
                let revision = model.state.revision;
                outliner(
                    ui,
                    doc,
                    revision,
                    &model.selection,
                    &mut ui_state,
                    &mut events,
                );
            });
    }
    if ui_state.show_properties {
        egui::Panel::right("properties")
            .resizable(true)
            .default_size(270.0)
            .show(&mut root, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    let mut analysis = (writers.analysis.clone(), writers.surface_analysis.clone());
                    // A running gizmo drag or G shows in the fields as it goes.
                    let shown = model
                        .selection
                        .active()
                        .and_then(|id| tool_previews.transform(id).copied());
                    properties(ui, &model, shown, &mut ui_state, &mut events, &mut analysis);
                    if analysis.0 != *writers.analysis {
                        *writers.analysis = analysis.0;
                    }
                    if analysis.1 != *writers.surface_analysis {
                        *writers.surface_analysis = analysis.1;
                    }
                });
            });
    }
    let free = root.available_rect_before_wrap();
    ui_state.viewport_rect = Some(free);
    ctx.data_mut(|d| d.insert_temp(egui::Id::new(pointer_menus::VIEWPORT_RECT), free));
    if quad_view {
        // Quad view's quarters are named in their corners.
        let painter = root.painter_at(free);
        let half = free.size() / 2.0;
        for (label, at) in [
            ("Top", free.min),
            ("Front", free.min + egui::vec2(half.x, 0.0)),
            ("Right", free.min + egui::vec2(0.0, half.y)),
            ("Perspective", free.min + half),
        ] {
            painter.text(
                at + egui::vec2(8.0, 6.0),
                egui::Align2::LEFT_TOP,
                label,
                egui::FontId::proportional(13.0),
                egui::Color32::from_gray(220),
            );
        }
        let line = egui::Stroke::new(1.0, egui::Color32::from_gray(90));
        painter.line_segment([free.center_top(), free.center_bottom()], line);
        painter.line_segment([free.left_center(), free.right_center()], line);
    }
    if let Ok((cam, cam_t)) = camera.single() {
        let points = model
            .shape_edit
            .node
            .and_then(|n| entities.0.get(&n))
            .map(|e| hedra_scene::control_points_of(*e, &control_points))
            .unwrap_or_default();
        weight_labels(&root.painter_at(free), &model, &points, cam, cam_t);
        joint_labels(
            &root.painter_at(free),
            &model,
            &writers.analysis,
            cam,
            cam_t,
        );
    }
    if let Some((a, b)) = model.mode.box_select.or(model.shape_edit.box_select) {
        let rect = egui::Rect::from_two_pos(egui::pos2(a.x, a.y), egui::pos2(b.x, b.y));
        let painter = root.painter_at(free);
        painter.rect_filled(
            rect,
            0.0,
            egui::Color32::from_rgba_unmultiplied(255, 160, 60, 24),
        );
        painter.rect_stroke(
            rect,
            0.0,
            egui::Stroke::new(1.0, egui::Color32::from_rgb(255, 170, 80)),
            egui::StrokeKind::Inside,
        );
    }

    if ui_state.show_history {
        history_window(&ctx, free, &model, &mut ui_state, &mut events);
    }
    if ui_state.show_statistics {
        statistics_overlay(&ctx, free, &model, &mut ui_state);
    }
    adjust_last_window(&ctx, free, &model, &mut events);
    let mut key_help = *writers.key_help;
    key_help_window(&ctx, free, &model, &mut key_help);
    if *writers.key_help != key_help {
        *writers.key_help = key_help;
    }
    let curve = active_curve(&model.state.session.doc, model.selection.active());
    add_menu(&ctx, &mut ui_state, &mut events, curve, writers.cursor.0);
    merge_menu(&ctx, &mut model, &mut events);
    dialogs(&ctx, &mut ui_state, &mut model, &mut writers);

    // Whether the pointer is the viewport's is decided at the start of the
    // next frame, from where it is then (`egui_input::refresh_pointer_gate`).
    // Only text fields keep the keyboard. A clicked button would keep
    // egui's focus: every shortcut blocked until a click elsewhere, and
    // Enter or Space (a tool's confirm) would press it again.
    if let Some(id) = ctx.memory(|m| m.focused())
        && !ctx.text_edit_focused()
    {
        ctx.memory_mut(|m| m.surrender_focus(id));
    }
    // No shortcut runs while a text field has the keyboard or a dialog
    // that is typed into is open (the path prompt, unsaved changes).
    gate.keyboard_free =
        !ctx.text_edit_focused() && ui_state.path_prompt.is_none() && ui_state.confirm.is_none();

    // Apply what the panels decided.
    for e in events {
        match e {
            UiEvent::Select(id, additive) => {
                if additive {
                    model.selection.toggle(id);
                } else {
                    model.selection.set([id]);
                }
            }
            UiEvent::Request(r) => {
                writers.requests.write(r);
            }
            UiEvent::File(f) => {
                writers.files.write(f);
            }
            UiEvent::Error(e) => model.status.error(e),
            UiEvent::StartBisect => {
                hedra_edit::start_bisect(&mut writers.bisect, &model.mode, &mut model.status)
            }
            UiEvent::Start(action) => writers.requested.0 = Some(action),
            UiEvent::DrawCurve => {
                model.selection.nodes.clear();
                writers.curve_draw.start(&mut model.status);
            }
            UiEvent::PreviewContents(contents) => {
                let contents: std::collections::HashMap<_, _> = contents
                    .iter()
                    .filter_map(|(id, content)| {
                        Some((*id, hedra_scene::PreviewContent::of_shape(content)?))
                    })
                    .collect();
                if !contents.is_empty() {
                    hedra_scene::Previews::show(
                        &mut tool_previews,
                        hedra_scene::PreviewSource::Properties,
                        hedra_scene::ToolPreview {
                            contents: contents.into_iter().collect(),
                            ..default()
                        },
                    )
                }
            }
            UiEvent::PickAxis(id) => {
                model.selection.set([id]);
                writers.curve_draw.start_axis(id, &mut model.status);
            }
            UiEvent::Preview(id, t) => hedra_scene::Previews::show(
                &mut tool_previews,
                hedra_scene::PreviewSource::Properties,
                hedra_scene::ToolPreview {
                    transforms: [(id, t)].into(),
                    ..default()
                },
            ),
        }
    }
    // A field let go: its command (sent above) replaces the preview.
    if ui_state.transform_edit.is_none() && ui_state.construction_edit.is_none() {
        hedra_scene::Previews::clear(&mut tool_previews, hedra_scene::PreviewSource::Properties);
    }
    Ok(())
}

fn exec(events: &mut Vec<UiEvent>, cmd: Command) {
    events.push(UiEvent::Request(DocRequest::Execute(cmd)));
}
