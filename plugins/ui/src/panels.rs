//! The egui layout: menu bar, outliner, properties, status bar, history,
//! "adjust last operation", the Shift+A menu and the dialogs.

use crate::files::{self, FilePurpose, Pending, Preferences, SamplesDir};
use crate::{FileAction, UiState, begin_path, run_pending, use_path};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, egui};
use glam::{DQuat, DVec3, EulerRot};
use hedra_doc::{
    Command, Document, NodeContent, NodeId, NodeRef, Shading, Transform as DocTransform,
};
use hedra_edit::{EditMode, ElementKind, Selection, TransformTool};
use hedra_geom::Primitive;
use hedra_scene::{DocRequest, DocState, InputGate, NodeEntities, StatusMessage};

/// What the panels decided this frame; applied after drawing.
enum UiEvent {
    Select(NodeId, bool),
    Request(DocRequest),
    File(FileAction),
    Preview(NodeId, DocTransform),
    Error(String),
}

#[derive(SystemParam)]
pub struct Writers<'w> {
    requests: MessageWriter<'w, DocRequest>,
    files: MessageWriter<'w, FileAction>,
    exit: MessageWriter<'w, AppExit>,
    analysis: ResMut<'w, hedra_viewport::CurveAnalysis>,
    surface_analysis: ResMut<'w, hedra_viewport::SurfaceAnalysis>,
}

#[derive(SystemParam)]
pub struct Model<'w> {
    state: Res<'w, DocState>,
    selection: ResMut<'w, Selection>,
    tool: Res<'w, TransformTool>,
    status: ResMut<'w, StatusMessage>,
    prefs: Res<'w, Preferences>,
    samples: Option<Res<'w, SamplesDir>>,
    entities: Res<'w, NodeEntities>,
    mode: ResMut<'w, EditMode>,
    previews: Res<'w, hedra_scene::SmoothPreviews>,
    shape_edit: Res<'w, hedra_edit::ShapeEdit>,
}

#[allow(clippy::too_many_arguments)]
pub fn draw_ui(
    mut contexts: EguiContexts,
    mut ui_state: ResMut<UiState>,
    mut model: Model,
    mut writers: Writers,
    mut gate: ResMut<InputGate>,
    mut transforms: Query<&mut Transform>,
    window: Single<&Window, With<bevy::window::PrimaryWindow>>,
    camera: Query<(&Camera, &GlobalTransform), With<hedra_scene::ViewportCamera>>,
) -> Result {
    let ctx = contexts.ctx_mut()?.clone();
    let mut events: Vec<UiEvent> = Vec::new();
    // Tab belongs to the viewport (edit mode) unless a field is being edited.
    let focus_before = ctx.memory(|m| m.focused());
    let mut root = egui::Ui::new(
        ctx.clone(),
        "hedra-root".into(),
        egui::UiBuilder::new()
            .layer_id(egui::LayerId::background())
            .max_rect(ctx.viewport_rect()),
    );
    let doc = &model.state.session.doc;

    egui::Panel::top("menu").show(&mut root, |ui| {
        menu_bar(ui, &mut ui_state, &model, &mut events)
    });
    egui::Panel::bottom("status").show(&mut root, |ui| status_bar(ui, &model));
    if ui_state.show_outliner {
        egui::Panel::left("outliner")
            .resizable(true)
            .default_size(220.0)
            .show(&mut root, |ui| {
                ui.heading("Outliner");
                ui.separator();
                outliner(ui, doc, &model.selection, &mut ui_state, &mut events);
            });
    }
    if ui_state.show_properties {
        egui::Panel::right("properties")
            .resizable(true)
            .default_size(270.0)
            .show(&mut root, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    let mut analysis = (writers.analysis.clone(), writers.surface_analysis.clone());
                    properties(ui, &model, &mut ui_state, &mut events, &mut analysis);
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
    if let Ok((cam, cam_t)) = camera.single() {
        weight_labels(&root.painter_at(free), &model, cam, cam_t);
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
        history_window(&ctx, &model, &mut ui_state, &mut events);
    }
    adjust_last_window(&ctx, free, &model, &mut events);
    let curve = active_curve(&model.state.session.doc, model.selection.active());
    add_menu(&ctx, &mut ui_state, &mut events, curve);
    merge_menu(&ctx, &mut model, &mut events);
    dialogs(&ctx, &mut ui_state, &mut model, &mut writers);

    // Viewport input is free when the pointer is over the 3D area and egui is not busy.
    let cursor = window.cursor_position().map(|c| egui::pos2(c.x, c.y));
    gate.pointer_free = cursor.is_some_and(|c| free.contains(c))
        && !ctx.egui_is_using_pointer()
        && !ctx.is_pointer_over_egui();
    if focus_before.is_none() && ctx.input(|i| i.key_pressed(egui::Key::Tab)) {
        if let Some(id) = ctx.memory(|m| m.focused()) {
            ctx.memory_mut(|m| m.surrender_focus(id));
        }
    }
    gate.keyboard_free = !ctx.egui_wants_keyboard_input();

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
            UiEvent::Preview(id, t) => {
                if let Some(mut et) = model
                    .entities
                    .0
                    .get(&id)
                    .and_then(|e| transforms.get_mut(*e).ok())
                {
                    *et = hedra_edit::modal::to_bevy(&t);
                }
            }
        }
    }
    Ok(())
}

fn exec(events: &mut Vec<UiEvent>, cmd: Command) {
    events.push(UiEvent::Request(DocRequest::Execute(cmd)));
}

fn menu_bar(ui: &mut egui::Ui, state: &mut UiState, model: &Model, events: &mut Vec<UiEvent>) {
    egui::MenuBar::new().ui(ui, |ui| {
        ui.menu_button("File", |ui| {
            if ui.button("New\tCtrl+N").clicked() {
                events.push(UiEvent::File(FileAction::New));
            }
            if ui.button("Open…\tCtrl+O").clicked() {
                events.push(UiEvent::File(FileAction::Open));
            }
            ui.menu_button("Open Recent", |ui| {
                if model.prefs.recent.is_empty() {
                    ui.label("(no recent files)");
                }
                for p in &model.prefs.recent {
                    if ui.button(p.display().to_string()).clicked() {
                        events.push(UiEvent::File(FileAction::OpenPath(p.clone())));
                    }
                }
            });
            ui.menu_button("Open Sample", |ui| {
                let samples = model
                    .samples
                    .as_ref()
                    .map(|d| files::list_samples(&d.0))
                    .unwrap_or_default();
                if samples.is_empty() {
                    ui.label("(no samples found)");
                }
                for p in samples {
                    let name = p
                        .file_name()
                        .map(|n| n.to_string_lossy().into_owned())
                        .unwrap_or_default();
                    if ui.button(name).clicked() {
                        events.push(UiEvent::File(FileAction::OpenPath(p)));
                    }
                }
            });
            ui.separator();
            if ui.button("Save\tCtrl+S").clicked() {
                events.push(UiEvent::File(FileAction::Save));
            }
            if ui.button("Save As…\tCtrl+Shift+S").clicked() {
                events.push(UiEvent::File(FileAction::SaveAs));
            }
            ui.separator();
            ui.menu_button("Import", |ui| {
                if ui
                    .button("OBJ, STL or glTF (.obj, .stl, .gltf, .glb)…")
                    .clicked()
                {
                    events.push(UiEvent::File(FileAction::ImportObj));
                }
            });
            ui.menu_button("Export", |ui| {
                if ui.button("Wavefront OBJ (.obj)…").clicked() {
                    events.push(UiEvent::File(FileAction::ExportObj));
                }
                if ui.button("STL, triangulated (.stl)…").clicked() {
                    events.push(UiEvent::File(FileAction::ExportStl));
                }
                if ui
                    .button("glTF 2.0 binary, with the hierarchy (.glb)…")
                    .clicked()
                {
                    events.push(UiEvent::File(FileAction::ExportGlb));
                }
            });
            ui.separator();
            if ui.button("Quit\tCtrl+Q").clicked() {
                events.push(UiEvent::File(FileAction::Quit));
            }
        });
        ui.menu_button("Edit", |ui| {
            let h = &model.state.session.history;
            if ui
                .add_enabled(h.can_undo(), egui::Button::new("Undo\tCtrl+Z"))
                .clicked()
            {
                events.push(UiEvent::Request(DocRequest::Undo));
            }
            if ui
                .add_enabled(h.can_redo(), egui::Button::new("Redo\tCtrl+Shift+Z"))
                .clicked()
            {
                events.push(UiEvent::Request(DocRequest::Redo));
            }
            ui.separator();
            ui.checkbox(&mut state.show_history, "Undo History");
            ui.separator();
            if ui.button("Preferences…").clicked() {
                state.show_preferences = true;
            }
        });
        let curve = active_curve(&model.state.session.doc, model.selection.active());
        ui.menu_button("Add", |ui| {
            add_primitive_buttons(ui, events);
            add_shape_buttons(ui, events, curve);
        });
        if let Some(node) = model.mode.node {
            ui.menu_button("Mesh", |ui| mesh_menu(ui, node, &model.mode, events));
        }
        ui.menu_button("Object", |ui| {
            let sel = model.selection.refs();
            let any = !sel.is_empty();
            if ui
                .add_enabled(any, egui::Button::new("Duplicate\tShift+D"))
                .clicked()
            {
                exec(events, Command::Duplicate { nodes: sel.clone() });
            }
            if ui
                .add_enabled(any, egui::Button::new("Delete\tX"))
                .clicked()
            {
                exec(events, Command::Delete { nodes: sel.clone() });
            }
            if ui.add_enabled(any, egui::Button::new("Hide\tH")).clicked() {
                exec(
                    events,
                    Command::SetVisible {
                        nodes: sel.clone(),
                        visible: false,
                    },
                );
            }
            if ui
                .add_enabled(any, egui::Button::new("Clear Parent"))
                .clicked()
            {
                for r in &sel {
                    exec(
                        events,
                        Command::Reparent {
                            node: r.clone(),
                            parent: None,
                            keep_world: true,
                        },
                    );
                }
            }
            ui.separator();
            if ui
                .add_enabled(any, egui::Button::new("Shade Flat"))
                .clicked()
            {
                exec(
                    events,
                    Command::SetShading {
                        nodes: sel.clone(),
                        shading: Shading::Flat,
                    },
                );
            }
            if ui
                .add_enabled(any, egui::Button::new("Shade Smooth"))
                .clicked()
            {
                exec(
                    events,
                    Command::SetShading {
                        nodes: sel,
                        shading: Shading::Smooth,
                    },
                );
            }
        });
        ui.menu_button("View", |ui| {
            ui.checkbox(&mut state.show_outliner, "Outliner");
            ui.checkbox(&mut state.show_properties, "Properties");
            ui.checkbox(&mut state.show_history, "Undo History");
            ui.separator();
            ui.label("Frame selected: F or Numpad .");
            ui.label("Frame all: Home");
        });
    });
}

fn add_primitive_buttons(ui: &mut egui::Ui, events: &mut Vec<UiEvent>) {
    for kind in Primitive::KINDS {
        let p = Primitive::default_of(kind).expect("listed kinds have defaults");
        if ui.button(p.display_name()).clicked() {
            exec(
                events,
                Command::AddPrimitive {
                    primitive: p,
                    name: None,
                    parent: None,
                    transform: DocTransform::IDENTITY,
                },
            );
            ui.close();
        }
    }
}

/// The active node when it is a curve (for "revolve" / "extrude").
fn active_curve(doc: &Document, active: Option<NodeId>) -> Option<NodeId> {
    active.filter(|&id| {
        matches!(
            doc.node(id).map(|n| &n.content),
            Some(NodeContent::Curve(_))
        )
    })
}

/// Curves and surfaces of the Add menu, with small default control nets.
fn add_shape_buttons(ui: &mut egui::Ui, events: &mut Vec<UiEvent>, curve: Option<NodeId>) {
    use hedra_doc::command::{CurveSpec, SurfaceSpec};
    let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let mut add = |ui: &mut egui::Ui, label: &str, enabled: bool, command: Command| {
        if ui.add_enabled(enabled, egui::Button::new(label)).clicked() {
            exec(events, command);
            ui.close();
        }
    };
    let curve_cmd = |name: &str, curve: CurveSpec| Command::AddCurve {
        name: name.into(),
        curve,
        parent: None,
        transform: DocTransform::IDENTITY,
    };
    let surface_cmd = |name: &str, surface: SurfaceSpec| Command::AddSurface {
        name: name.into(),
        surface,
        parent: None,
        transform: DocTransform::IDENTITY,
    };
    ui.separator();
    ui.label(egui::RichText::new("Curves").weak());
    let wave = vec![
        v(-2.0, 0.0, 0.0),
        v(-1.0, 1.5, 0.0),
        v(0.0, -1.0, 0.0),
        v(1.0, 1.5, 0.0),
        v(2.0, 0.0, 0.0),
    ];
    add(
        ui,
        "Bézier Curve",
        true,
        curve_cmd(
            "Bezier Curve",
            CurveSpec::Bezier {
                points: wave[..4].to_vec(),
            },
        ),
    );
    add(
        ui,
        "NURBS Curve",
        true,
        curve_cmd(
            "NURBS Curve",
            CurveSpec::Nurbs {
                degree: 3,
                points: wave,
                weights: None,
                knots: None,
            },
        ),
    );
    add(
        ui,
        "NURBS Circle",
        true,
        curve_cmd("Circle", CurveSpec::Circle { radius: 1.0 }),
    );
    ui.separator();
    ui.label(egui::RichText::new("Surfaces").weak());
    let mut net = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let (x, z) = (i as f64 - 1.5, j as f64 - 1.5);
            let bump = if (1..3).contains(&i) && (1..3).contains(&j) {
                1.0
            } else {
                0.0
            };
            net.push(v(x, bump, z));
        }
    }
    add(
        ui,
        "Bézier Patch",
        true,
        surface_cmd(
            "Bezier Patch",
            SurfaceSpec::Bezier {
                nu: 4,
                nv: 4,
                points: net.clone(),
            },
        ),
    );
    add(
        ui,
        "NURBS Surface",
        true,
        surface_cmd(
            "NURBS Surface",
            SurfaceSpec::Nurbs {
                degree_u: 3,
                degree_v: 3,
                nu: 4,
                nv: 4,
                points: net,
                weights: None,
                knots_u: None,
                knots_v: None,
            },
        ),
    );
    add(
        ui,
        "NURBS Plane",
        true,
        surface_cmd("Plane", SurfaceSpec::Plane { size: 2.0 }),
    );
    add(
        ui,
        "NURBS Sphere",
        true,
        surface_cmd("Sphere", SurfaceSpec::Sphere { radius: 1.0 }),
    );
    add(
        ui,
        "NURBS Cylinder",
        true,
        surface_cmd(
            "Cylinder",
            SurfaceSpec::Cylinder {
                radius: 1.0,
                height: 2.0,
            },
        ),
    );
    add(
        ui,
        "Bézier Triangle",
        true,
        surface_cmd(
            "Triangle",
            SurfaceSpec::Triangle {
                degree: 2,
                points: vec![
                    v(0.0, 0.0, 2.0),
                    v(-0.5, 0.6, 1.0),
                    v(-1.0, 0.0, 0.0),
                    v(0.5, 0.6, 1.0),
                    v(0.0, 0.6, 0.0),
                    v(1.0, 0.0, 0.0),
                ],
            },
        ),
    );
    let revolve =
        curve.map(|c| surface_cmd("Revolution", SurfaceSpec::Revolve { profile: c.into() }));
    let enabled = revolve.is_some();
    add(
        ui,
        "Revolve Selected Curve",
        enabled,
        revolve.unwrap_or(Command::AddEmpty {
            name: String::new(),
            parent: None,
            transform: DocTransform::IDENTITY,
        }),
    );
}

fn add_menu(
    ctx: &egui::Context,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
    curve: Option<NodeId>,
) {
    let Some(pos) = state.add_menu_at else { return };
    let close = cursor_menu(ctx, ADD_MENU, pos, |ui| {
        ui.label(egui::RichText::new("Add").strong());
        ui.separator();
        let before = events.len();
        add_primitive_buttons(ui, events);
        add_shape_buttons(ui, events, curve);
        events.len() > before
    });
    if close {
        state.add_menu_at = None;
    }
}

/// The egui id of the Shift+A menu.
pub const ADD_MENU: &str = "add-menu";
/// The egui id of the M merge menu.
pub const MERGE_MENU: &str = "merge-menu";

/// M in vertex edit mode: Blender's merge menu at the cursor.
fn merge_menu(ctx: &egui::Context, model: &mut Model, events: &mut Vec<UiEvent>) {
    let Some(pos) = model.mode.merge_menu_at else {
        return;
    };
    let Some(node) = model.mode.node else {
        model.mode.merge_menu_at = None;
        return;
    };
    let selection = &model.mode.selection;
    let close = cursor_menu(ctx, MERGE_MENU, egui::pos2(pos.x, pos.y), |ui| {
        ui.label(egui::RichText::new("Merge").strong());
        ui.separator();
        let before = events.len();
        merge_buttons(ui, node, selection, events);
        events.len() > before
    });
    if close {
        model.mode.merge_menu_at = None;
    }
}

/// A menu at the cursor (Shift+A, M), moved up and left as far as it must
/// to fit the window. `items` draws the items and says whether one was
/// chosen. Returns whether the menu closes: an item was chosen, a press
/// began outside the menu, or Esc.
///
/// The menu is placed where it fits before egui shows it, and "outside" is
/// tested against the rect egui laid it out in: when egui itself moves an
/// area to fit, the area's response keeps the unmoved rect, so a press on
/// an item of a menu opened near the bottom counted as outside and closed
/// the menu before the release could click the item (issue 11).
fn cursor_menu(
    ctx: &egui::Context,
    id: &str,
    at: egui::Pos2,
    items: impl FnOnce(&mut egui::Ui) -> bool,
) -> bool {
    let id = egui::Id::new(id);
    let screen = ctx.content_rect();
    let size = ctx
        .memory(|m| m.area_rect(id))
        .map_or(egui::Vec2::ZERO, |r| r.size());
    let fitted = egui::pos2(
        at.x.min(screen.right() - size.x).max(screen.left()),
        at.y.min(screen.bottom() - size.y).max(screen.top()),
    );
    let mut chosen = false;
    egui::Area::new(id)
        .fixed_pos(fitted)
        .order(egui::Order::Foreground)
        .show(ctx, |ui| {
            // Looks like the menu bar's menus: full-width items without frames.
            egui::containers::menu::menu_style(ui.style_mut());
            egui::Frame::menu(ui.style()).show(ui, |ui| {
                ui.with_layout(egui::Layout::top_down_justified(egui::Align::Min), |ui| {
                    chosen = items(ui);
                });
            });
        });
    let shown = ctx.memory(|m| m.area_rect(id));
    let pressed_outside = ctx.input(|i| {
        i.pointer.any_pressed()
            && i.pointer
                .press_origin()
                .is_some_and(|p| !shown.is_some_and(|r| r.contains(p)))
    });
    chosen || pressed_outside || ctx.input(|i| i.key_pressed(egui::Key::Escape))
}

/// At Center / At First / At Last / By Distance on the selected vertices
/// (First and Last: in the order they were clicked).
fn merge_buttons(
    ui: &mut egui::Ui,
    node: NodeId,
    sel: &hedra_edit::ElementSelection,
    events: &mut Vec<UiEvent>,
) {
    use hedra_geom::modeling::MergePoint;
    let ordered =
        || hedra_doc::VertexSet::Ids(sel.ordered_vertices().iter().map(|v| v.0).collect());
    let enabled = sel.vertices.len() >= 2;
    for (label, at) in [
        ("At Center", MergePoint::Center),
        ("At First", MergePoint::First),
        ("At Last", MergePoint::Last),
    ] {
        if ui.add_enabled(enabled, egui::Button::new(label)).clicked() {
            exec(
                events,
                Command::MergeVertices {
                    node: NodeRef::from(node),
                    vertices: ordered(),
                    at,
                },
            );
            ui.close();
        }
    }
    if ui
        .add_enabled(enabled, egui::Button::new("By Distance"))
        .on_hover_text("Weld selected vertices closer than 0.0001 (change it in Adjust Last)")
        .clicked()
    {
        exec(
            events,
            Command::MergeByDistance {
                node: NodeRef::from(node),
                vertices: ordered(),
                distance: 0.0001,
            },
        );
        ui.close();
    }
}

fn outliner(
    ui: &mut egui::Ui,
    doc: &Document,
    selection: &Selection,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
) {
    egui::ScrollArea::vertical().show(ui, |ui| {
        for root in doc.roots() {
            outliner_row(ui, doc, root.id, 0, selection, state, events);
        }
        // Dropping a node on the empty area below the tree moves it to the top level.
        let rest = ui.available_size().max(egui::vec2(10.0, 40.0));
        let (_, resp) = ui.allocate_exact_size(rest, egui::Sense::hover());
        if let Some(dragged) = resp.dnd_release_payload::<NodeId>() {
            exec(
                events,
                Command::Reparent {
                    node: NodeRef::from(*dragged),
                    parent: None,
                    keep_world: true,
                },
            );
        }
    });
}

fn outliner_row(
    ui: &mut egui::Ui,
    doc: &Document,
    id: NodeId,
    depth: usize,
    selection: &Selection,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
) {
    let Some(node) = doc.node(id) else { return };
    ui.horizontal(|ui| {
        ui.add_space(depth as f32 * 14.0);
        let eye = if node.visible { "👁" } else { "–" };
        if ui.small_button(eye).on_hover_text("Show / hide").clicked() {
            exec(
                events,
                Command::SetVisible {
                    nodes: vec![id.into()],
                    visible: !node.visible,
                },
            );
        }
        let icon = match node.content {
            NodeContent::Mesh(_) => "▣",
            NodeContent::Curve(_) => "∿",
            NodeContent::Surface(_) => "◠",
            NodeContent::Empty => "✛",
        };
        if let Some(rename) = state.rename.as_mut().filter(|r| r.node == id) {
            let mut output = egui::TextEdit::singleline(&mut rename.text).show(ui);
            let resp = output.response.clone();
            if !rename.started {
                // First frame: focus the field with the whole name selected.
                rename.started = true;
                resp.request_focus();
                let all = egui::text::CCursorRange::two(
                    egui::text::CCursor::new(0),
                    egui::text::CCursor::new(rename.text.chars().count()),
                );
                output.state.cursor.set_char_range(Some(all));
                output.state.store(ui.ctx(), resp.id);
            }
            let text = rename.text.clone();
            if resp.lost_focus() {
                let name = text.trim().to_string();
                if ui.input(|i| !i.key_pressed(egui::Key::Escape))
                    && !name.is_empty()
                    && name != node.name
                {
                    exec(
                        events,
                        Command::Rename {
                            node: id.into(),
                            name,
                        },
                    );
                }
                state.rename = None;
            }
            return;
        }
        let selected = selection.contains(id);
        let text = egui::RichText::new(format!("{icon} {}", node.name));
        let text = if selection.active() == Some(id) {
            text.strong()
        } else {
            text
        };
        let resp =
            ui.add(egui::Button::selectable(selected, text).sense(egui::Sense::click_and_drag()));
        resp.dnd_set_drag_payload(id);
        if resp.clicked() {
            let additive = ui.input(|i| i.modifiers.shift || i.modifiers.ctrl);
            events.push(UiEvent::Select(id, additive));
        }
        if resp.double_clicked() {
            state.rename = Some(crate::Rename::new(id, &node.name));
        }
        if let Some(dragged) = resp.dnd_release_payload::<NodeId>() {
            if *dragged != id {
                exec(
                    events,
                    Command::Reparent {
                        node: NodeRef::from(*dragged),
                        parent: Some(id.into()),
                        keep_world: true,
                    },
                );
            }
        }
        resp.context_menu(|ui| {
            if ui.button("Rename").clicked() {
                state.rename = Some(crate::Rename::new(id, &node.name));
                ui.close();
            }
            if ui.button("Duplicate").clicked() {
                exec(
                    events,
                    Command::Duplicate {
                        nodes: vec![id.into()],
                    },
                );
                ui.close();
            }
            if node.parent.is_some() && ui.button("Clear Parent").clicked() {
                exec(
                    events,
                    Command::Reparent {
                        node: id.into(),
                        parent: None,
                        keep_world: true,
                    },
                );
                ui.close();
            }
            if ui.button("Delete").clicked() {
                exec(
                    events,
                    Command::Delete {
                        nodes: vec![id.into()],
                    },
                );
                ui.close();
            }
        });
    });
    for child in doc.children(id) {
        outliner_row(ui, doc, child.id, depth + 1, selection, state, events);
    }
}

fn vec3_row(ui: &mut egui::Ui, label: &str, v: &mut DVec3, speed: f64) -> egui::Response {
    ui.horizontal(|ui| {
        ui.label(label);
        let mut r = ui.add(
            egui::DragValue::new(&mut v.x)
                .speed(speed)
                .prefix("X ")
                .max_decimals(4),
        );
        r |= ui.add(
            egui::DragValue::new(&mut v.y)
                .speed(speed)
                .prefix("Y ")
                .max_decimals(4),
        );
        r |= ui.add(
            egui::DragValue::new(&mut v.z)
                .speed(speed)
                .prefix("Z ")
                .max_decimals(4),
        );
        r
    })
    .inner
}

fn properties(
    ui: &mut egui::Ui,
    model: &Model,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
    analysis: &mut (
        hedra_viewport::CurveAnalysis,
        hedra_viewport::SurfaceAnalysis,
    ),
) {
    ui.heading("Properties");
    ui.separator();
    let doc = &model.state.session.doc;
    let Some(id) = model.selection.active() else {
        ui.label("Nothing selected.");
        ui.label("Click an object, or add one with Shift+A.");
        return;
    };
    let Some(node) = doc.node(id) else { return };
    ui.label(egui::RichText::new(&node.name).strong());
    ui.label(format!("{} {}", node.content.kind(), node.id));
    if let Some(p) = node.parent.and_then(|p| doc.node(p)) {
        ui.label(format!("Parent: {}", p.name));
    }
    ui.add_space(6.0);

    egui::CollapsingHeader::new("Transform")
        .default_open(true)
        .show(ui, |ui| {
            let mut t = match &state.transform_edit {
                Some((eid, t)) if *eid == id => *t,
                _ => node.transform,
            };
            let (ex, ey, ez) = t.rotation.to_euler(EulerRot::XYZ);
            let mut euler = DVec3::new(ex.to_degrees(), ey.to_degrees(), ez.to_degrees());
            let mut changed = false;
            let mut resp = vec3_row(ui, "Location", &mut t.translation, 0.01);
            changed |= resp.changed();
            let r = vec3_row(ui, "Rotation°", &mut euler, 0.5);
            if r.changed() {
                t.rotation = DQuat::from_euler(
                    EulerRot::XYZ,
                    euler.x.to_radians(),
                    euler.y.to_radians(),
                    euler.z.to_radians(),
                );
                changed = true;
            }
            resp |= r;
            let r = vec3_row(ui, "Scale", &mut t.scale, 0.01);
            changed |= r.changed();
            resp |= r;
            if changed {
                state.transform_edit = Some((id, t));
                events.push(UiEvent::Preview(id, t));
            }
            // A drag or a typed value becomes one step when the field is let go.
            let busy = resp.dragged() || resp.has_focus();
            if !busy {
                if let Some((eid, edited)) = state.transform_edit.take() {
                    if eid == id && edited != node.transform {
                        if edited.is_usable() {
                            exec(
                                events,
                                Command::SetTransforms {
                                    nodes: vec![(id.into(), edited)],
                                },
                            );
                        } else {
                            events.push(UiEvent::Preview(id, node.transform));
                            events.push(UiEvent::Error(
                                "A scale of zero (or a non-finite value) is not allowed".into(),
                            ));
                        }
                    }
                }
            }
        });

    if matches!(
        node.content,
        NodeContent::Curve(_) | NodeContent::Surface(_)
    ) {
        egui::CollapsingHeader::new(if matches!(node.content, NodeContent::Curve(_)) {
            "Curve"
        } else {
            "Surface"
        })
        .default_open(true)
        .show(ui, |ui| {
            shape_panel(ui, id, &node.content, model, state, events, analysis)
        });
    }
    if let NodeContent::Mesh(content) = &node.content {
        egui::CollapsingHeader::new("Subdivision")
            .default_open(true)
            .show(ui, |ui| {
                subdivision_panel(ui, id, content, model, state, events)
            });
    }
    if let (NodeContent::Mesh(content), Some(true)) =
        (&node.content, model.mode.node.map(|n| n == id))
    {
        egui::CollapsingHeader::new("Topology inspector")
            .default_open(true)
            .show(ui, |ui| {
                topology_inspector(ui, &content.mesh, &model.mode.selection)
            });
    }
    if let NodeContent::Mesh(content) = &node.content {
        egui::CollapsingHeader::new("Mesh")
            .default_open(true)
            .show(ui, |ui| {
                let s = content.mesh.stats();
                ui.label(format!(
                    "Vertices {}   Edges {}   Faces {}",
                    s.vertices, s.edges, s.faces
                ));
                ui.label(format!(
                    "Euler characteristic {}   {}   boundary loops {}",
                    s.euler_characteristic,
                    if s.closed { "closed" } else { "open" },
                    s.boundary_loops
                ));
                match &s.validation {
                    Ok(()) => ui.label("Half-edge structure valid"),
                    Err(e) => ui.colored_label(egui::Color32::LIGHT_RED, e),
                };
                ui.horizontal(|ui| {
                    ui.label("Shading");
                    for (sh, label) in [(Shading::Flat, "Flat"), (Shading::Smooth, "Smooth")] {
                        if ui.selectable_label(content.shading == sh, label).clicked()
                            && content.shading != sh
                        {
                            exec(
                                events,
                                Command::SetShading {
                                    nodes: vec![id.into()],
                                    shading: sh,
                                },
                            );
                        }
                    }
                });
            });
        if let Some(p) = &content.primitive {
            egui::CollapsingHeader::new(format!("{} parameters", p.display_name()))
                .default_open(true)
                .show(ui, |ui| {
                    let mut edited = p.clone();
                    if primitive_editor(ui, &mut edited) {
                        exec(
                            events,
                            Command::SetPrimitive {
                                node: id.into(),
                                primitive: edited,
                            },
                        );
                    }
                });
        }
    }
}

/// A curve's or surface's degree, knots and control points; in edit mode
/// (Tab) the weight of the selected points; knot insertion and degree
/// elevation.
fn shape_panel(
    ui: &mut egui::Ui,
    id: NodeId,
    content: &NodeContent,
    model: &Model,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
    analysis: &mut (
        hedra_viewport::CurveAnalysis,
        hedra_viewport::SurfaceAnalysis,
    ),
) {
    use hedra_doc::command::ParameterDirection;
    let (analysis, surface_analysis) = (&mut analysis.0, &mut analysis.1);
    use hedra_edit::shape_mode::control_weights;
    let knots_text = |k: &[f64]| {
        let text: Vec<String> = k.iter().map(|x| format!("{x:.3}")).collect();
        text.join(" ")
    };
    let mut directions: Vec<(ParameterDirection, &str)> = Vec::new();
    match content {
        NodeContent::Curve(c) => {
            ui.label(format!(
                "NURBS, degree {}, {} control points{}",
                c.degree(),
                c.points().len(),
                if c.is_polynomial() { "" } else { ", rational" }
            ));
            ui.add(egui::Label::new(format!("knots {}", knots_text(c.knots()))).wrap());
            directions.push((ParameterDirection::U, "Insert knot at"));
        }
        NodeContent::Surface(s) => match &**s {
            hedra_doc::SurfaceShape::Nurbs(n) => {
                let ((du, dv), (nu, nv)) = (n.degrees(), n.size());
                ui.label(format!(
                    "NURBS, degree {du} × {dv}, {nu} × {nv} control points"
                ));
                let (ku, kv) = n.knots();
                ui.add(egui::Label::new(format!("knots u {}", knots_text(ku))).wrap());
                ui.add(egui::Label::new(format!("knots v {}", knots_text(kv))).wrap());
                directions.push((ParameterDirection::U, "Insert knot in u at"));
                directions.push((ParameterDirection::V, "Insert knot in v at"));
            }
            hedra_doc::SurfaceShape::Triangle(t) => {
                ui.label(format!(
                    "Bézier triangle, degree {}, {} control points",
                    t.degree,
                    t.points.len()
                ));
            }
        },
        _ => return,
    }
    ui.horizontal(|ui| {
        ui.add(
            egui::DragValue::new(&mut state.knot_at)
                .speed(0.01)
                .range(0.0..=1.0)
                .max_decimals(4),
        );
        for (direction, label) in &directions {
            if ui
                .button(*label)
                .on_hover_text("Adds a control point; the shape does not move")
                .clicked()
            {
                exec(
                    events,
                    Command::InsertKnot {
                        node: id.into(),
                        at: state.knot_at,
                        direction: *direction,
                    },
                );
            }
        }
    });
    let elevations: &[(ParameterDirection, &str)] = match content {
        NodeContent::Surface(s) if matches!(**s, hedra_doc::SurfaceShape::Nurbs(_)) => &[
            (ParameterDirection::U, "Elevate degree in u"),
            (ParameterDirection::V, "Elevate degree in v"),
        ],
        _ => &[(ParameterDirection::U, "Elevate degree")],
    };
    ui.horizontal(|ui| {
        for (direction, label) in elevations {
            if ui.button(*label).clicked() {
                exec(
                    events,
                    Command::ElevateDegree {
                        node: id.into(),
                        direction: *direction,
                    },
                );
            }
        }
    });
    if matches!(content, NodeContent::Curve(_)) {
        ui.separator();
        ui.label(egui::RichText::new("Analysis").weak());
        ui.horizontal(|ui| {
            ui.checkbox(&mut analysis.comb, "Curvature comb");
            ui.add_enabled(
                analysis.comb,
                egui::DragValue::new(&mut analysis.comb_scale)
                    .speed(0.01)
                    .range(0.001..=100.0)
                    .prefix("× "),
            );
        });
        ui.checkbox(&mut analysis.colour_by_curvature, "Colour by curvature");
        ui.checkbox(&mut analysis.frame, "Frenet frame and osculating circle");
        if analysis.frame {
            ui.add(egui::Slider::new(&mut analysis.at, 0.0..=1.0).text("at"));
        }
    }
    if matches!(content, NodeContent::Surface(s) if matches!(**s, hedra_doc::SurfaceShape::Nurbs(_)))
    {
        ui.separator();
        ui.label(egui::RichText::new("Analysis").weak());
        let a = surface_analysis;
        ui.horizontal(|ui| {
            ui.checkbox(&mut a.section, "Planar section");
            for (axis, name) in ["X", "Y", "Z"].iter().enumerate() {
                ui.selectable_value(&mut a.section_axis, axis, *name);
            }
        });
        if a.section {
            ui.add(egui::Slider::new(&mut a.section_at, 0.0..=1.0).text("plane at"));
        }
        ui.checkbox(&mut a.domain_point, "Moving domain point");
        if a.domain_point {
            ui.add(egui::Slider::new(&mut a.u, 0.0..=1.0).text("u"));
            ui.add(egui::Slider::new(&mut a.v, 0.0..=1.0).text("v"));
        }
    }
    if model.shape_edit.node != Some(id) {
        ui.label("Tab edits the control points (G moves them, W drags their weight).");
        return;
    }
    let selected: Vec<u32> = model.shape_edit.selected.iter().copied().collect();
    let Some(weights) = control_weights(content) else {
        ui.label(format!("{} control point(s) selected", selected.len()));
        return;
    };
    if selected.is_empty() {
        ui.label("Select control points to edit their weight.");
        return;
    }
    let mean = selected.iter().map(|&i| weights[i as usize]).sum::<f64>() / selected.len() as f64;
    let mut w = state.weight_edit.unwrap_or(mean);
    ui.label(if selected.len() == 1 {
        format!("Weight of point {}", selected[0])
    } else {
        format!("Weight of {} points", selected.len())
    });
    ui.horizontal(|ui| {
        // Only changes the user made count: a logarithmic slider once
        // reported its own rounding as a change and set every selected
        // weight to their mean.
        let field = ui
            .add(
                egui::DragValue::new(&mut w)
                    .speed(0.01)
                    .range(0.001..=1000.0)
                    .max_decimals(4),
            )
            .on_hover_text("Larger pulls the shape towards the point; W drags it in the viewport");
        let slider = ui.add(egui::Slider::new(&mut w, 0.01..=10.0).show_value(false));
        let touched =
            |r: &egui::Response| r.dragged() || r.has_focus() || r.clicked() || r.drag_stopped();
        let edited = (field.changed() && touched(&field)) || (slider.changed() && touched(&slider));
        if edited && (w - mean).abs() > 1e-12 {
            state.weight_edit = Some(w);
        }
        let busy = field.dragged() || field.has_focus() || slider.dragged();
        if !busy && let Some(value) = state.weight_edit.take() {
            exec(
                events,
                Command::SetWeights {
                    node: id.into(),
                    weights: selected.iter().map(|&i| (i, value)).collect(),
                },
            );
        }
    });
}

/// A drop-down choosing one of `options` by its label.
fn choice<T: Copy + PartialEq>(
    ui: &mut egui::Ui,
    id: &str,
    value: &mut T,
    options: &[T],
    label: fn(T) -> &'static str,
) {
    egui::ComboBox::from_id_salt(id)
        .selected_text(label(*value))
        .show_ui(ui, |ui| {
            for &o in options {
                ui.selectable_value(value, o, label(o));
            }
        });
}

/// The subdivision modifier of a mesh node and, in edit mode, the crease of
/// the selected edges or vertices.
fn subdivision_panel(
    ui: &mut egui::Ui,
    id: NodeId,
    content: &hedra_doc::MeshContent,
    model: &Model,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
) {
    use hedra_geom::subdivision::{
        BoundaryInterpolation, CreaseMethod, MAX_LEVEL, MAX_VIEWPORT_LEVEL, Scheme,
    };
    let set = |events: &mut Vec<UiEvent>, m: Option<hedra_doc::SubdivisionModifier>| {
        exec(
            events,
            Command::SetSubdivision {
                nodes: vec![id.into()],
                modifier: m,
            },
        )
    };
    match content.subdivision {
        None => {
            ui.label("No subdivision modifier.");
            if ui
                .button("Add Subdivision Surface")
                .on_hover_text("Ctrl+1…Ctrl+5 add it with that level")
                .clicked()
            {
                set(events, Some(hedra_doc::SubdivisionModifier::with_level(1)));
            }
        }
        Some(m) => {
            let mut e = m;
            egui::Grid::new("subdivision-grid")
                .num_columns(2)
                .show(ui, |ui| {
                    ui.label("Scheme");
                    choice(
                        ui,
                        "scheme",
                        &mut e.options.scheme,
                        &Scheme::ALL,
                        Scheme::label,
                    );
                    ui.end_row();
                    ui.label("Viewport level");
                    ui.add(
                        egui::DragValue::new(&mut e.viewport_level).range(0..=MAX_VIEWPORT_LEVEL),
                    )
                    .on_hover_text("Ctrl+0…Ctrl+5, Page Up / Page Down");
                    ui.end_row();
                    ui.label("Export level");
                    ui.add(egui::DragValue::new(&mut e.export_level).range(0..=MAX_LEVEL));
                    ui.end_row();
                    ui.label("Boundary");
                    choice(
                        ui,
                        "boundary",
                        &mut e.options.boundary,
                        &BoundaryInterpolation::ALL,
                        BoundaryInterpolation::label,
                    );
                    ui.end_row();
                    ui.label("Creases");
                    choice(
                        ui,
                        "crease-method",
                        &mut e.options.crease_method,
                        &CreaseMethod::ALL,
                        CreaseMethod::label,
                    );
                    ui.end_row();
                });
            ui.checkbox(&mut e.show_cage, "Show cage");
            if e != m {
                set(events, Some(e));
            }
            if e.options.scheme == Scheme::Loop
                && let Some(f) = content
                    .mesh
                    .faces()
                    .find(|&f| content.mesh.face_degree(f) != 3)
            {
                ui.colored_label(
                    egui::Color32::LIGHT_RED,
                    format!(
                        "Loop needs triangles: face {f} has {} sides",
                        content.mesh.face_degree(f)
                    ),
                );
            }
            ui.horizontal(|ui| {
                if ui
                    .button("Apply")
                    .on_hover_text("Make the smooth shape the editable mesh")
                    .clicked()
                {
                    exec(
                        events,
                        Command::ApplySubdivision {
                            node: id.into(),
                            levels: None,
                        },
                    );
                }
                if ui
                    .button("Snap cage to limit")
                    .on_hover_text("Move the cage's vertices onto the smooth surface")
                    .clicked()
                {
                    exec(events, Command::SnapToLimit { node: id.into() });
                }
                if ui.button("Remove").clicked() {
                    set(events, None);
                }
            });
        }
    }
    // Crease of the selection, in edit mode.
    if model.mode.node != Some(id) {
        return;
    }
    let sel = &model.mode.selection;
    let vertex_mode = model.mode.kind == ElementKind::Vertex;
    let values: Vec<f64> = if vertex_mode {
        sel.vertices
            .iter()
            .map(|&v| content.creases.vertex(v))
            .collect()
    } else {
        sel.edges.iter().map(|&e| content.creases.edge(e)).collect()
    };
    let label = if vertex_mode {
        "Corner sharpness"
    } else {
        "Edge crease"
    };
    if values.is_empty() {
        ui.label(format!(
            "{label}: select {} (Shift+E drags it)",
            if vertex_mode { "vertices" } else { "edges" }
        ));
        return;
    }
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let mut v = state.crease_edit.unwrap_or(mean);
    ui.horizontal(|ui| {
        ui.label(label);
        let r = ui
            .add(egui::Slider::new(&mut v, 0.0..=10.0).max_decimals(2))
            .on_hover_text("0 smooth … 10 infinitely sharp; Shift+E drags it in the viewport");
        // Only a change the user made (a widget may round what it shows).
        let touched = r.dragged() || r.has_focus() || r.clicked() || r.drag_stopped();
        if r.changed() && touched {
            state.crease_edit = Some(v);
        }
        let busy = r.dragged() || r.has_focus();
        if !busy && let Some(value) = state.crease_edit.take() {
            exec(
                events,
                if vertex_mode {
                    Command::SetVertexCrease {
                        node: id.into(),
                        vertices: hedra_doc::elements::VertexSet::Ids(
                            sel.vertices.iter().map(|v| v.0).collect(),
                        ),
                        sharpness: value,
                    }
                } else {
                    Command::SetEdgeCrease {
                        node: id.into(),
                        edges: hedra_doc::elements::EdgeSet::Ids(
                            sel.edges.iter().map(|e| e.0).collect(),
                        ),
                        sharpness: value,
                    }
                },
            );
        }
    });
}

/// Fields for a primitive's parameters; true when one changed.
pub fn primitive_editor(ui: &mut egui::Ui, p: &mut Primitive) -> bool {
    let mut changed = false;
    let mut len = |ui: &mut egui::Ui, label: &str, v: &mut f64| {
        ui.horizontal(|ui| {
            ui.label(label);
            changed |= ui
                .add(
                    egui::DragValue::new(v)
                        .speed(0.01)
                        .range(0.001..=1e6)
                        .max_decimals(4),
                )
                .changed();
        });
    };
    let mut count_changed = false;
    let mut count = |ui: &mut egui::Ui, label: &str, v: &mut u32, min: u32, max: u32| {
        ui.horizontal(|ui| {
            ui.label(label);
            count_changed |= ui
                .add(egui::DragValue::new(v).speed(0.1).range(min..=max))
                .changed();
        });
    };
    match p {
        Primitive::Plane { size } | Primitive::Cube { size } => len(ui, "Size", size),
        Primitive::Grid {
            x_segments,
            z_segments,
            size,
        } => {
            count(ui, "X subdivisions", x_segments, 1, 1000);
            count(ui, "Z subdivisions", z_segments, 1, 1000);
            len(ui, "Size", size);
        }
        Primitive::UvSphere {
            segments,
            rings,
            radius,
        } => {
            count(ui, "Segments", segments, 3, 1000);
            count(ui, "Rings", rings, 2, 1000);
            len(ui, "Radius", radius);
        }
        Primitive::IcoSphere {
            subdivisions,
            radius,
        } => {
            count(ui, "Subdivisions", subdivisions, 0, 7);
            len(ui, "Radius", radius);
        }
        Primitive::Cylinder {
            segments,
            radius,
            depth,
        }
        | Primitive::Cone {
            segments,
            radius,
            depth,
        } => {
            count(ui, "Vertices", segments, 3, 1000);
            len(ui, "Radius", radius);
            len(ui, "Depth", depth);
        }
        Primitive::Torus {
            major_segments,
            minor_segments,
            major_radius,
            minor_radius,
        } => {
            count(ui, "Major segments", major_segments, 3, 1000);
            count(ui, "Minor segments", minor_segments, 3, 1000);
            len(ui, "Major radius", major_radius);
            len(ui, "Minor radius", minor_radius);
        }
    }
    changed || count_changed
}

/// Blender's "adjust last operation": the parameters of the last step, when
/// it added a primitive, editable in place.
fn adjust_last_window(
    ctx: &egui::Context,
    viewport: egui::Rect,
    model: &Model,
    events: &mut Vec<UiEvent>,
) {
    let Some(last) = model.state.session.history.done().last() else {
        return;
    };
    if last.serial <= model.state.opened_serial {
        return;
    }
    let Some(command) = &last.command else { return };
    let mut edited = command.clone();
    let editable = matches!(
        command,
        Command::AddPrimitive { .. }
            | Command::ExtrudeFaces { .. }
            | Command::ExtrudeRegion { .. }
            | Command::InsetFaces { .. }
            | Command::InsetRegion { .. }
            | Command::LoopCut { .. }
            | Command::SubdivideEdges { .. }
            | Command::BevelEdges { .. }
            | Command::SlideEdges { .. }
            | Command::MergeByDistance { .. }
            | Command::MergeVertices { .. }
            | Command::BevelVertices { .. }
    );
    if !editable {
        return;
    }
    egui::Window::new(format!("Adjust Last: {}", last.label))
        .id("adjust-last".into())
        .collapsible(true)
        .resizable(false)
        .pivot(egui::Align2::LEFT_BOTTOM)
        .fixed_pos(viewport.left_bottom() + egui::vec2(8.0, -8.0))
        .show(ctx, |ui| {
            let changed = match &mut edited {
                Command::AddPrimitive { primitive, .. } => primitive_editor(ui, primitive),
                Command::BevelEdges {
                    width, segments, ..
                } => {
                    let w = number_row(ui, "Width", width, 0.005, 0.0001..=1e6);
                    let s = ui.horizontal(|ui| {
                        ui.label("Segments");
                        ui.add(egui::DragValue::new(segments).speed(0.1).range(1..=32))
                            .changed()
                    });
                    w | s.inner
                }
                Command::SlideEdges { factor, .. } => {
                    number_row(ui, "Factor", factor, 0.01, -1.0..=1.0)
                }
                Command::MergeVertices { at, .. } => {
                    use hedra_geom::modeling::MergePoint;
                    let before = *at;
                    ui.horizontal(|ui| {
                        ui.label("Merge at");
                        choice(
                            ui,
                            "adjust-merge-at",
                            at,
                            &[MergePoint::Center, MergePoint::First, MergePoint::Last],
                            |p| match p {
                                MergePoint::Center => "Center",
                                MergePoint::First => "First",
                                MergePoint::Last => "Last",
                            },
                        )
                    });
                    *at != before
                }
                Command::BevelVertices { width, .. } => {
                    number_row(ui, "Width", width, 0.005, 0.0001..=1e6)
                }
                Command::MergeByDistance { distance, .. } => {
                    number_row(ui, "Distance", distance, 0.001, 0.0..=1e6)
                }
                Command::ExtrudeFaces { distance, .. }
                | Command::ExtrudeRegion { distance, .. } => {
                    number_row(ui, "Distance", distance, 0.01, -1e6..=1e6)
                }
                Command::InsetFaces {
                    thickness, depth, ..
                }
                | Command::InsetRegion {
                    thickness, depth, ..
                } => {
                    number_row(ui, "Thickness", thickness, 0.005, 0.0..=1e6)
                        | number_row(ui, "Depth", depth, 0.005, -1e6..=1e6)
                }
                Command::LoopCut { cuts, .. } | Command::SubdivideEdges { cuts, .. } => {
                    ui.horizontal(|ui| {
                        ui.label("Cuts");
                        ui.add(egui::DragValue::new(cuts).speed(0.1).range(1..=64))
                            .changed()
                    })
                    .inner
                }
                _ => false,
            };
            if changed {
                events.push(UiEvent::Request(DocRequest::AdjustLast(edited.clone())));
            }
        });
}

fn number_row(
    ui: &mut egui::Ui,
    label: &str,
    v: &mut f64,
    speed: f64,
    range: std::ops::RangeInclusive<f64>,
) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        ui.add(
            egui::DragValue::new(v)
                .speed(speed)
                .range(range)
                .max_decimals(4),
        )
        .changed()
    })
    .inner
}

fn history_window(
    ctx: &egui::Context,
    model: &Model,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
) {
    let h = &model.state.session.history;
    egui::Window::new("Undo History")
        .open(&mut state.show_history)
        .default_width(240.0)
        .show(ctx, |ui| {
            ui.label(crate::recovery::history_summary(h));
            ui.separator();
            egui::ScrollArea::vertical()
                .max_height(360.0)
                .show(ui, |ui| {
                    let done = h.done().len();
                    if ui.selectable_label(done == 0, "Original").clicked() {
                        events.push(UiEvent::Request(DocRequest::JumpTo(0)));
                    }
                    for (i, t) in h.done().iter().enumerate() {
                        if ui.selectable_label(i + 1 == done, &t.label).clicked() {
                            events.push(UiEvent::Request(DocRequest::JumpTo(i + 1)));
                        }
                    }
                    for (k, t) in h.undone().iter().rev().enumerate() {
                        let text = egui::RichText::new(&t.label).weak();
                        if ui.selectable_label(false, text).clicked() {
                            events.push(UiEvent::Request(DocRequest::JumpTo(done + k + 1)));
                        }
                    }
                });
        });
}

/// In shape edit mode, each control point's weight next to it (selected
/// points in orange); only for nets of up to 400 points.
fn weight_labels(painter: &egui::Painter, model: &Model, cam: &Camera, cam_t: &GlobalTransform) {
    use hedra_edit::shape_mode::{control_points, control_weights};
    let edit = &model.shape_edit;
    let Some(id) = edit.node else { return };
    let doc = &model.state.session.doc;
    let Some(content) = edit
        .preview
        .clone()
        .or_else(|| doc.node(id).map(|n| n.content.clone()))
    else {
        return;
    };
    let Some(weights) = control_weights(&content) else {
        return;
    };
    let points = control_points(&content);
    if points.len() > 400 {
        return;
    }
    let world = doc.world_matrix(id);
    for (i, (p, w)) in points.iter().zip(&weights).enumerate() {
        let Ok(s) = cam.world_to_viewport(cam_t, world.transform_point3(*p).as_vec3()) else {
            continue;
        };
        let selected = edit.selected.contains(&(i as u32));
        let color = if selected {
            egui::Color32::from_rgb(255, 170, 80)
        } else {
            egui::Color32::from_gray(200)
        };
        painter.text(
            egui::pos2(s.x + 8.0, s.y - 8.0),
            egui::Align2::LEFT_BOTTOM,
            format!("{w:.2}"),
            egui::FontId::proportional(if selected { 14.0 } else { 11.0 }),
            color,
        );
    }
}

fn status_bar(ui: &mut egui::Ui, model: &Model) {
    // The message is laid out first, from the right, so the key hints give
    // way (truncated) instead of being drawn under a long error.
    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
        let s = &model.status;
        let text = if s.is_error {
            egui::RichText::new(&s.text).color(egui::Color32::from_rgb(255, 110, 100))
        } else {
            egui::RichText::new(&s.text)
        };
        let most = ui.available_width() * 0.6;
        let progress = model.previews.progress();
        if progress.is_empty() {
            ui.scope(|ui| {
                ui.set_max_width(most);
                ui.add(egui::Label::new(text).truncate()).on_hover_text(&s.text);
            });
        } else {
            // Background subdivision: a bar per job, Esc cancels.
            for (label, fraction) in progress {
                ui.add(
                    egui::ProgressBar::new(fraction)
                        .desired_width(160.0)
                        .show_percentage(),
                );
                ui.label(format!("{label}… Esc cancels"));
            }
            ui.ctx().request_repaint();
        }
        ui.with_layout(egui::Layout::left_to_right(egui::Align::Center), |ui| {
            let doc = &model.state.session.doc;
            let edit = &model.mode;
            if let Some(node) = model.shape_edit.node.and_then(|n| doc.node(n)) {
                let se = &model.shape_edit;
                ui.label(egui::RichText::new("Edit Mode · Control Points").strong().color(egui::Color32::from_rgb(255, 170, 80)));
                ui.separator();
                ui.label(format!("{}: {} selected", node.name, se.selected.len()));
                ui.separator();
                if let Some(t) = &se.tool {
                    ui.label(egui::RichText::new(&t.readout).color(egui::Color32::from_rgb(255, 200, 80)));
                    ui.add(egui::Label::new("move the mouse · type a value · Enter/click confirm · Esc/right-click cancel").truncate());
                } else {
                    ui.add(egui::Label::new("click select · A all · G move · W weight · K insert knot · Tab exit").truncate());
                }
            } else if let Some(node) = edit.node.and_then(|n| doc.node(n)) {
                let kind = match edit.kind {
                    ElementKind::Vertex => "Vertex",
                    ElementKind::Edge => "Edge",
                    ElementKind::Face => "Face",
                };
                ui.label(egui::RichText::new(format!("Edit Mode · {kind}")).strong().color(egui::Color32::from_rgb(255, 170, 80)));
                ui.separator();
                let s = &edit.selection;
                ui.label(format!("{}: {} vertices, {} edges, {} faces selected", node.name, s.vertices.len(), s.edges.len(), s.faces.len()));
                ui.separator();
                if let Some(t) = &edit.tool {
                    ui.label(egui::RichText::new(&t.readout).color(egui::Color32::from_rgb(255, 200, 80)));
                    ui.add(egui::Label::new("move the mouse · type a value · Enter/click confirm · Esc/right-click cancel").truncate());
                } else {
                    let x_ray = if edit.x_ray { "X-ray on (Alt+Z)" } else { "Alt+Z X-ray" };
                    ui.add(egui::Label::new(format!("1/2/3 kind · G move · E extrude · I inset · Ctrl+R loop cut · J connect · X dissolve · {x_ray} · Tab exit")).truncate());
                }
            } else {
                ui.label(egui::RichText::new("Object Mode").strong());
                ui.separator();
                let sel = &model.selection.nodes;
                match (sel.len(), model.selection.active().and_then(|a| doc.node(a))) {
                    (0, _) | (_, None) => ui.label("Nothing selected"),
                    (1, Some(n)) => ui.label(format!("Selected: {}", n.name)),
                    (k, Some(n)) => ui.label(format!("{k} selected, active: {}", n.name)),
                };
                ui.separator();
                if let Some(m) = &model.tool.active {
                    ui.label(egui::RichText::new(&m.readout).color(egui::Color32::from_rgb(255, 200, 80)));
                    ui.add(egui::Label::new("X/Y/Z constrain · type a value · Enter/click confirm · Esc/right-click cancel").truncate());
                } else {
                    ui.add(egui::Label::new("G move · R rotate · S scale · X delete · Shift+D duplicate · Shift+A add · Tab edit · Ctrl+Z undo · MMB orbit").truncate());
                }
            }
        });
    });
}

fn dialogs(ctx: &egui::Context, state: &mut UiState, model: &mut Model, writers: &mut Writers) {
    // Unsaved changes.
    if let Some(pending) = state.confirm.clone() {
        let what = match &pending {
            Pending::Quit => "quitting",
            Pending::New => "starting a new scene",
            _ => "opening another scene",
        };
        egui::Window::new("Unsaved changes")
            .collapsible(false)
            .resizable(false)
            .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
            .show(ctx, |ui| {
                ui.label(format!(
                    "Save changes to {} before {what}?",
                    model.state.display_name()
                ));
                ui.horizontal(|ui| {
                    if ui.button("Save").clicked() {
                        state.confirm = None;
                        state.after_save = Some(pending.clone());
                        match &model.state.path {
                            Some(p) => {
                                writers.requests.write(DocRequest::Save(p.clone()));
                            }
                            None => begin_path(state, FilePurpose::SaveAs, &model.state),
                        }
                    }
                    if ui.button("Don't Save").clicked() {
                        state.confirm = None;
                        run_pending(
                            pending.clone(),
                            state,
                            &model.state,
                            &mut writers.requests,
                            &mut writers.exit,
                        );
                    }
                    if ui.button("Cancel").clicked() {
                        state.confirm = None;
                    }
                });
            });
    }
    // Path prompt (always available; the native dialog may run beside it).
    if let Some(mut prompt) = state.path_prompt.take() {
        let mut keep = true;
        egui::Window::new(prompt.purpose.title()).collapsible(false).resizable(false).anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0]).show(ctx, |ui| {
            if !state.dialog_backend {
                ui.colored_label(egui::Color32::from_rgb(255, 200, 80), "No file dialog is available here (no desktop portal or zenity). Type the path:");
            } else if state.dialog.is_some() {
                ui.label("A file dialog is open; you can also type the path here:");
            }
            let resp = ui.add(egui::TextEdit::singleline(&mut prompt.text).desired_width(420.0));
            let enter = resp.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            ui.horizontal(|ui| {
                let reading = matches!(prompt.purpose, FilePurpose::Open | FilePurpose::ImportObj);
                let verb = match prompt.purpose {
                    FilePurpose::Open => "Open",
                    FilePurpose::ImportObj => "Import",
                    FilePurpose::ExportObj | FilePurpose::ExportStl | FilePurpose::ExportGlb => {
                        "Export"
                    }
                    FilePurpose::SaveAs => "Save",
                };
                let ok = ui.button(verb).clicked() || enter;
                if ok && !prompt.text.trim().is_empty() {
                    let path = std::path::PathBuf::from(prompt.text.trim());
                    if reading && !path.exists() {
                        model.status.error(format!("{}: no such file", path.display()));
                    } else {
                        use_path(prompt.purpose, path, &model.state, &mut writers.requests, &mut model.status);
                        keep = false;
                    }
                }
                if state.dialog_backend && state.dialog.is_none() && ui.button("Browse…").clicked() {
                    state.dialog = Some(files::spawn_dialog(prompt.purpose, None));
                }
                if ui.button("Cancel").clicked() {
                    keep = false;
                    state.after_save = None;
                }
            });
        });
        if keep {
            state.path_prompt = Some(prompt);
        }
    }
    // Warnings that need acknowledging (damaged history, …).
    if !model.status.warnings.is_empty() {
        let mut ok = false;
        egui::Window::new("Warning")
            .collapsible(false)
            .resizable(false)
            .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
            .show(ctx, |ui| {
                for w in &model.status.warnings {
                    ui.label(w);
                }
                ok = ui.button("OK").clicked();
            });
        if ok {
            model.status.warnings.clear();
        }
    }
}

/// Seed 000's records for the one selected element: the half-edge record,
/// the winged-edge row, faces around a vertex, neighbours of a face.
fn topology_inspector(
    ui: &mut egui::Ui,
    m: &hedra_geom::HalfEdgeMesh,
    sel: &hedra_edit::ElementSelection,
) {
    use hedra_geom::topology::{halfedge_record, winged_edge_row};
    let opt = |f: Option<hedra_geom::FaceId>| f.map_or("-".to_string(), |f| f.to_string());
    let join = |v: Vec<String>| {
        if v.is_empty() {
            "-".to_string()
        } else {
            v.join(" ")
        }
    };
    let he_grid = |ui: &mut egui::Ui, hs: &[hedra_geom::HalfEdgeId], salt: &str| {
        // Its own horizontal scroll keeps the wide table from pushing the
        // panel (and with it the viewport) wider when something is picked.
        egui::ScrollArea::horizontal().id_salt(salt).show(ui, |ui| {
            egui::Grid::new(salt).striped(true).show(ui, |ui| {
                for t in ["half-edge", "vertex", "twin", "next", "prev", "face"] {
                    ui.label(egui::RichText::new(t).strong());
                }
                ui.end_row();
                for &h in hs {
                    let r = halfedge_record(m, h);
                    for t in [
                        r.halfedge.to_string(),
                        r.origin.to_string(),
                        r.twin.to_string(),
                        r.next.to_string(),
                        r.prev.to_string(),
                        opt(r.face),
                    ] {
                        ui.label(t);
                    }
                    ui.end_row();
                }
            });
        });
    };
    // The selection can briefly name elements of the next mesh (a tool that
    // just confirmed): show only what this mesh has.
    let mut live = sel.clone();
    live.retain_live(m);
    let sel = &live;
    let total = sel.vertices.len() + sel.edges.len() + sel.faces.len();
    if total != 1 {
        ui.label("Select exactly one vertex, edge or face to see its records; related elements are drawn in cyan.");
        return;
    }
    if let Some(&v) = sel.vertices.iter().next() {
        let p = m.position(v);
        ui.label(format!(
            "{v} at ({:.4}, {:.4}, {:.4}), valence {}",
            p.x,
            p.y,
            p.z,
            m.vertex_valence(v)
        ));
        ui.label(format!(
            "faces around: {}",
            join(m.vertex_faces(v).map(|f| f.to_string()).collect())
        ));
        ui.label(format!(
            "neighbours: {}",
            join(m.vertex_neighbors(v).map(|w| w.to_string()).collect())
        ));
        ui.label("outgoing half-edges:");
        he_grid(
            ui,
            &m.vertex_outgoing(v).collect::<Vec<_>>(),
            "inspector-vertex",
        );
    } else if let Some(&e) = sel.edges.iter().next() {
        let w = winged_edge_row(m, e);
        ui.label("winged-edge row:");
        egui::Grid::new("inspector-winged")
            .striped(true)
            .show(ui, |ui| {
                for (k, v) in [
                    ("edge", w.edge.to_string()),
                    ("start", w.start.to_string()),
                    ("end", w.end.to_string()),
                    ("left face", opt(w.left_face)),
                    ("right face", opt(w.right_face)),
                    ("left predecessor", w.left_predecessor.to_string()),
                    ("left successor", w.left_successor.to_string()),
                    ("right predecessor", w.right_predecessor.to_string()),
                    ("right successor", w.right_successor.to_string()),
                ] {
                    ui.label(k);
                    ui.label(v);
                    ui.end_row();
                }
            });
        ui.label("its half-edges:");
        he_grid(ui, &[e.halfedge(0), e.halfedge(1)], "inspector-edge");
    } else if let Some(&f) = sel.faces.iter().next() {
        ui.label(format!(
            "{f}: {} sides, half-edge {}",
            m.face_degree(f),
            m.face_halfedge(f)
        ));
        ui.label(format!(
            "vertices: {}",
            join(m.face_vertices(f).map(|v| v.to_string()).collect())
        ));
        ui.label(format!(
            "neighbours: {}",
            join(m.face_neighbors(f).map(|g| g.to_string()).collect())
        ));
        ui.label("loop:");
        he_grid(
            ui,
            &m.face_halfedges(f).collect::<Vec<_>>(),
            "inspector-face",
        );
    }
}

/// Edit mode's Mesh menu: every tool on the current selection. Amounts start
/// at sensible defaults and are changed in the Adjust Last window, as in
/// Blender; the keys run the same tools interactively.
fn mesh_menu(ui: &mut egui::Ui, node: NodeId, mode: &EditMode, events: &mut Vec<UiEvent>) {
    use hedra_doc::{EdgeSet, FaceSet, VertexSet};
    let sel = &mode.selection;
    let faces = || FaceSet::Ids(sel.faces.iter().map(|f| f.0).collect());
    let edges = || EdgeSet::Ids(sel.edges.iter().map(|e| e.0).collect());
    let vertices = || VertexSet::Ids(sel.vertices.iter().map(|v| v.0).collect());
    let n = NodeRef::from(node);
    let (has_f, has_e, has_v) = (
        !sel.faces.is_empty(),
        !sel.edges.is_empty(),
        !sel.vertices.is_empty(),
    );
    let mut merge_events = Vec::new();
    let mut item = |ui: &mut egui::Ui, label: &str, enabled: bool, cmd: &dyn Fn() -> Command| {
        if ui.add_enabled(enabled, egui::Button::new(label)).clicked() {
            exec(events, cmd());
            ui.close();
        }
    };
    ui.label(egui::RichText::new("Faces").weak());
    item(ui, "Extrude Region\tE", has_f, &|| Command::ExtrudeRegion {
        node: n.clone(),
        faces: faces(),
        distance: 0.5,
    });
    item(ui, "Extrude Individual\tAlt+E", has_f, &|| {
        Command::ExtrudeFaces {
            node: n.clone(),
            faces: faces(),
            distance: 0.5,
        }
    });
    item(ui, "Inset Region\tI", has_f, &|| Command::InsetRegion {
        node: n.clone(),
        faces: faces(),
        thickness: 0.1,
        depth: 0.0,
    });
    item(ui, "Inset Individual\tAlt+I", has_f, &|| {
        Command::InsetFaces {
            node: n.clone(),
            faces: faces(),
            thickness: 0.1,
            depth: 0.0,
        }
    });
    item(ui, "Delete Only Faces (keep edges)", has_f, &|| {
        Command::MakeHoles {
            node: n.clone(),
            faces: faces(),
        }
    });
    ui.separator();
    ui.label(egui::RichText::new("Edges").weak());
    item(ui, "Loop Cut\tCtrl+R", sel.edges.len() == 1, &|| {
        Command::LoopCut {
            node: n.clone(),
            edge: edges(),
            cuts: 1,
        }
    });
    item(ui, "Subdivide", has_e, &|| Command::SubdivideEdges {
        node: n.clone(),
        edges: edges(),
        cuts: 1,
    });
    item(ui, "Bridge Edge Loops", has_e, &|| Command::BridgeLoops {
        node: n.clone(),
        edges: edges(),
    });
    item(ui, "Fill\tF", has_e, &|| Command::FillHoles {
        node: n.clone(),
        edges: edges(),
    });
    item(ui, "Collapse\tM", has_e, &|| Command::CollapseEdges {
        node: n.clone(),
        edges: edges(),
    });
    item(ui, "Dissolve Edges\tX", has_e, &|| Command::DissolveEdges {
        node: n.clone(),
        edges: edges(),
    });
    ui.separator();
    ui.label(egui::RichText::new("Vertices").weak());
    item(ui, "Connect\tJ", sel.vertices.len() == 2, &|| {
        Command::ConnectVertices {
            node: n.clone(),
            vertices: vertices(),
        }
    });
    ui.menu_button("Merge\tM", |ui| {
        merge_buttons(ui, node, sel, &mut merge_events)
    });
    item(ui, "Bevel Vertices\tCtrl+Shift+B", has_v, &|| {
        Command::BevelVertices {
            node: n.clone(),
            vertices: vertices(),
            width: 0.1,
        }
    });
    item(ui, "Dissolve Vertices\tX", has_v, &|| {
        Command::DissolveVertices {
            node: n.clone(),
            vertices: vertices(),
        }
    });
    ui.separator();
    ui.label(egui::RichText::new("Symmetry").weak());
    for axis in [
        hedra_geom::modeling::MirrorAxis::X,
        hedra_geom::modeling::MirrorAxis::Y,
        hedra_geom::modeling::MirrorAxis::Z,
    ] {
        let set = selection_vertices(sel);
        item(ui, &format!("Mirror {axis:?}"), set.is_some(), &|| {
            Command::MirrorVertices {
                node: n.clone(),
                vertices: set.clone().unwrap_or(VertexSet::All),
                axis,
            }
        });
    }
    for axis in [
        hedra_geom::modeling::MirrorAxis::X,
        hedra_geom::modeling::MirrorAxis::Y,
        hedra_geom::modeling::MirrorAxis::Z,
    ] {
        item(
            ui,
            &format!("Symmetrize +{axis:?} to -{axis:?}"),
            true,
            &|| Command::Symmetrize {
                node: n.clone(),
                axis,
            },
        );
    }
    ui.separator();
    ui.label(egui::RichText::new("Normals").weak());
    item(ui, "Flip\tAlt+N", true, &|| Command::FlipNormals {
        node: n.clone(),
    });
    item(ui, "Recalculate Outside\tShift+N", true, &|| {
        Command::RecalculateNormals { node: n.clone() }
    });
    events.extend(merge_events);
}

/// The vertices a selection touches, of any element kind, as a command's set.
fn selection_vertices(sel: &hedra_edit::ElementSelection) -> Option<hedra_doc::VertexSet> {
    use hedra_doc::{EdgeSet, FaceSet, VertexSet};
    if !sel.faces.is_empty() {
        Some(VertexSet::OfFaces(Box::new(FaceSet::Ids(
            sel.faces.iter().map(|f| f.0).collect(),
        ))))
    } else if !sel.edges.is_empty() {
        Some(VertexSet::OfEdges(Box::new(EdgeSet::Ids(
            sel.edges.iter().map(|e| e.0).collect(),
        ))))
    } else if !sel.vertices.is_empty() {
        Some(VertexSet::Ids(sel.vertices.iter().map(|v| v.0).collect()))
    } else {
        None
    }
}
