//! The egui layout, drawn by one system ([`draw_ui`]) that collects what the
//! user decided as [`UiEvent`]s and applies them after drawing. One file per
//! part: `menus` (menu bar, Mesh menu, Shift+A and M at the cursor),
//! `outliner`, `properties`, `windows` (Adjust Last, undo history),
//! `dialogs`, `status_bar`, `inspector` (topology tables) and
//! `weight_labels`.

use crate::files::{self, FilePurpose, Pending, Preferences, SamplesDir};
use crate::{FileAction, UiState, begin_path, run_pending};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, egui};
use glam::{DQuat, DVec3, EulerRot};
use hedra_doc::{Command, Document, NodeContent, NodeId, NodeRef, NodeTransform, Shading};
use hedra_edit::{EditMode, ElementKind, Selection, TransformTool};
use hedra_geom::Primitive;
use hedra_scene::{
    ChangeSetting, DocRequest, DocState, PreviewRequest, PreviewSource, StatusMessage,
    StatusRequest,
};

mod add_menu;
mod construction_panel;
mod csg_menu;
mod curve_menu;
mod dialogs;
mod inspector;
mod menu_table;
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
use menu_table::{MenuState, draw_menu};
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
    /// The warnings dialog was acknowledged.
    ClearWarnings,
    /// Selection, tools started from a menu, the merge menu closed.
    Edit(hedra_edit::EditRequest),
    /// A panel field being dragged: the nodes' contents as they would become.
    PreviewContents(Vec<(NodeId, NodeContent)>),
}

/// What the panels asked for, sent as messages to the plugins that own the
/// state (`hedra_scene`'s settings, status and previews, `hedra_edit`'s
/// selection and tools, `hedra_viewport`'s gizmo and analysis). No panel
/// holds a `ResMut` of another crate's state: each plugin applies its own
/// messages in `SceneSystems::Requests` of the next frame.
#[derive(SystemParam)]
pub struct Writers<'w> {
    requests: MessageWriter<'w, DocRequest>,
    files: MessageWriter<'w, FileAction>,
    exit: MessageWriter<'w, AppExit>,
    edit: MessageWriter<'w, hedra_edit::EditRequest>,
    status: MessageWriter<'w, StatusRequest>,
    previews: MessageWriter<'w, PreviewRequest>,
    gizmo_mode: MessageWriter<'w, hedra_viewport::SetGizmoMode>,
    settings: SettingWriters<'w>,
}

/// The settings the panels change, one message kind each.
#[derive(SystemParam)]
pub struct SettingWriters<'w> {
    shading: MessageWriter<'w, ChangeSetting<hedra_scene::ViewportShading>>,
    quad_view: MessageWriter<'w, ChangeSetting<hedra_scene::QuadView>>,
    cursor: MessageWriter<'w, ChangeSetting<hedra_scene::Cursor3d>>,
    snapping: MessageWriter<'w, ChangeSetting<hedra_edit::Snapping>>,
    proportional: MessageWriter<'w, ChangeSetting<hedra_edit::Proportional>>,
    pivot: MessageWriter<'w, ChangeSetting<hedra_edit::PivotPoint>>,
    key_help: MessageWriter<'w, ChangeSetting<hedra_edit::bindings::KeyHelp>>,
    analysis: MessageWriter<'w, ChangeSetting<hedra_viewport::CurveAnalysis>>,
    surface_analysis: MessageWriter<'w, ChangeSetting<hedra_viewport::SurfaceAnalysis>>,
}

/// Sends `edited` as the new value of a setting when a panel changed it.
fn send_changed<T: hedra_scene::Setting>(
    writer: &mut MessageWriter<ChangeSetting<T>>,
    current: &T,
    edited: T,
) {
    if *current != edited {
        writer.write(ChangeSetting(edited));
    }
}

/// The settings the panels show, read only.
#[derive(SystemParam)]
pub struct Settings<'w> {
    gizmo: Res<'w, bevy::gizmos::transform_gizmo::TransformGizmoSettings>,
    quad_view: Res<'w, hedra_scene::QuadView>,
    snapping: Res<'w, hedra_edit::Snapping>,
    proportional: Res<'w, hedra_edit::Proportional>,
    pivot: Res<'w, hedra_edit::PivotPoint>,
    key_help: Res<'w, hedra_edit::bindings::KeyHelp>,
    analysis: Res<'w, hedra_viewport::CurveAnalysis>,
    surface_analysis: Res<'w, hedra_viewport::SurfaceAnalysis>,
}

/// The state the panels show, read only.
#[derive(SystemParam)]
pub struct Model<'w, 's> {
    state: Res<'w, DocState>,
    selection: Res<'w, Selection>,
    tool: Res<'w, TransformTool>,
    status: Res<'w, StatusMessage>,
    prefs: Res<'w, Preferences>,
    samples: Option<Res<'w, SamplesDir>>,
    mode: Res<'w, EditMode>,
    previews: Res<'w, hedra_scene::SmoothPreviews>,
    jobs: Res<'w, hedra_scene::FileJobs>,
    shape_edit: Res<'w, hedra_edit::ShapeEdit>,
    shading: Res<'w, hedra_scene::ViewportShading>,
    cursor: Res<'w, hedra_scene::Cursor3d>,
    /// What each node shows (a running tool's preview, else the document).
    shown: hedra_scene::Shown<'w, 's>,
}

/// Draws every panel, menu and dialog, then sends what the user decided
/// (see [`Writers`]); its only own state is [`UiState`].
#[allow(clippy::too_many_arguments)]
pub fn draw_ui(
    mut contexts: EguiContexts,
    mut ui_state: ResMut<UiState>,
    model: Model,
    settings: Settings,
    mut writers: Writers,
    tool_previews: Res<hedra_scene::Previews>,
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

    // The menus edit copies of the settings; what changed is sent below.
    let mut gizmo_mode = settings.gizmo.mode;
    let mut shading = *model.shading;
    let mut snapping = *settings.snapping;
    let mut proportional = *settings.proportional;
    let mut pivot = *settings.pivot;
    let mut quad_view = settings.quad_view.0;
    let mut cursor = model.cursor.0;
    let view_direction = camera
        .single()
        .ok()
        .map(|(_, t)| (t.rotation() * Vec3::NEG_Z).as_dvec3());
    // The view axis through the 3D cursor, for "Revolve about the view".
    ui_state.view_axis = view_direction.map(|d| (cursor, -d));
    let menu = MenuState::of(&model, view_direction);
    egui::Panel::top("menu").show(&mut root, |ui| {
        let view = ViewChoices {
            gizmo_mode: &mut gizmo_mode,
            shading: &mut shading,
            snapping: &mut snapping,
            proportional: &mut proportional,
            pivot: &mut pivot,
            quad_view: &mut quad_view,
            cursor: &mut cursor,
        };
        menu_bar(ui, &mut ui_state, &model, &menu, view, &mut events)
    });
    snap_menu(&ctx, &mut ui_state, &model, &mut cursor, &mut events);
    shading_menu(
        &ctx,
        &mut ui_state,
        &mut shading,
        &model.selection,
        &mut events,
    );
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
    let mut analysis = (settings.analysis.clone(), settings.surface_analysis.clone());
    if ui_state.show_properties {
        egui::Panel::right("properties")
            .resizable(true)
            .default_size(270.0)
            .show(&mut root, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    // A running gizmo drag or G shows in the fields as it goes.
                    let shown = model
                        .selection
                        .active()
                        .and_then(|id| tool_previews.transform(id).copied());
                    properties(ui, &model, shown, &mut ui_state, &mut events, &mut analysis);
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
            &settings.analysis,
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
    let mut key_help = *settings.key_help;
    key_help_window(&ctx, free, &model, &mut key_help);
    add_menu(&ctx, &mut ui_state, &menu, &mut events);
    merge_menu(&ctx, &model, &mut events);
    dialogs(&ctx, &mut ui_state, &model, &mut writers, &mut events);

    // Send what the panels changed and decided.
    if settings.gizmo.mode != gizmo_mode {
        writers
            .gizmo_mode
            .write(hedra_viewport::SetGizmoMode(gizmo_mode));
    }
    let to = &mut writers.settings;
    send_changed(&mut to.shading, &model.shading, shading);
    send_changed(&mut to.snapping, &settings.snapping, snapping);
    send_changed(&mut to.proportional, &settings.proportional, proportional);
    send_changed(&mut to.pivot, &settings.pivot, pivot);
    send_changed(
        &mut to.quad_view,
        &settings.quad_view,
        hedra_scene::QuadView(quad_view),
    );
    send_changed(&mut to.cursor, &model.cursor, hedra_scene::Cursor3d(cursor));
    send_changed(&mut to.key_help, &settings.key_help, key_help);
    send_changed(&mut to.analysis, &settings.analysis, analysis.0);
    send_changed(
        &mut to.surface_analysis,
        &settings.surface_analysis,
        analysis.1,
    );
    let mut properties_preview = false;
    for e in events {
        match e {
            UiEvent::Select(node, additive) => {
                writers
                    .edit
                    .write(hedra_edit::EditRequest::Select { node, additive });
            }
            UiEvent::Request(r) => {
                writers.requests.write(r);
            }
            UiEvent::File(f) => {
                writers.files.write(f);
            }
            UiEvent::Error(e) => {
                writers.status.write(StatusRequest::Error(e));
            }
            UiEvent::ClearWarnings => {
                writers.status.write(StatusRequest::ClearWarnings);
            }
            UiEvent::Edit(request) => {
                writers.edit.write(request);
            }
            UiEvent::PreviewContents(contents) => {
                let contents: std::collections::HashMap<_, _> = contents
                    .iter()
                    .filter_map(|(id, content)| {
                        Some((*id, hedra_scene::PreviewContent::of_shape(content)?))
                    })
                    .collect();
                if !contents.is_empty() {
                    properties_preview = true;
                    writers.previews.write(PreviewRequest::Show(
                        PreviewSource::Properties,
                        hedra_scene::ToolPreview {
                            contents: contents.into_iter().collect(),
                            ..default()
                        },
                    ));
                }
            }
            UiEvent::Preview(id, t) => {
                properties_preview = true;
                writers.previews.write(PreviewRequest::Show(
                    PreviewSource::Properties,
                    hedra_scene::ToolPreview {
                        transforms: [(id, t)].into(),
                        ..default()
                    },
                ));
            }
        }
    }
    // A field let go: its command (sent above) replaces the preview.
    if !properties_preview
        && ui_state.transform_edit.is_none()
        && ui_state.construction_edit.is_none()
        && tool_previews.has(PreviewSource::Properties)
    {
        writers
            .previews
            .write(PreviewRequest::Clear(PreviewSource::Properties));
    }
    Ok(())
}

fn exec(events: &mut Vec<UiEvent>, cmd: Command) {
    events.push(UiEvent::Request(DocRequest::Execute(cmd)));
}
