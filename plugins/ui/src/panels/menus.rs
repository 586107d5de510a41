//! The menu bar, the Mesh menu, and the menus at the cursor (Shift+A, M).

use super::*;

/// What the View menu changes in the viewport (written back after the menus).
pub(super) struct ViewChoices<'a> {
    /// What the transform gizmo does.
    pub gizmo_mode: &'a mut bevy::gizmos::transform_gizmo::TransformGizmoMode,
    /// Wireframe and X-ray.
    pub shading: &'a mut hedra_scene::ViewportShading,
    /// Increment snapping and its steps.
    pub snapping: &'a mut hedra_edit::Snapping,
    /// The 3D cursor's world position.
    pub cursor: &'a mut DVec3,
}

pub(super) fn menu_bar(
    ui: &mut egui::Ui,
    state: &mut UiState,
    model: &Model,
    view: ViewChoices,
    events: &mut Vec<UiEvent>,
) {
    let ViewChoices {
        gizmo_mode,
        shading,
        snapping,
        cursor,
    } = view;
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
            // The transform gizmo on objects, mesh elements and control points.
            {
                use bevy::gizmos::transform_gizmo::TransformGizmoMode as Mode;
                ui.radio_value(gizmo_mode, Mode::Translate, "Gizmo: move");
                ui.radio_value(gizmo_mode, Mode::Rotate, "Gizmo: rotate");
                ui.radio_value(gizmo_mode, Mode::Scale, "Gizmo: scale");
            }
            ui.separator();
            if ui.button("Preferences…").clicked() {
                state.show_preferences = true;
            }
        });
        let curve = active_curve(&model.state.session.doc, model.selection.active());
        let at = *cursor;
        ui.menu_button("Add", |ui| {
            add_primitive_buttons(ui, events, at);
            add_shape_buttons(ui, events, curve, at);
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
            ui.checkbox(&mut state.show_statistics, "Statistics");
            ui.checkbox(&mut shading.wireframe, "Wireframe\tShift+Z");
            ui.checkbox(&mut shading.x_ray, "X-ray\tAlt+Z");
            ui.checkbox(&mut shading.face_orientation, "Face Orientation");
            ui.separator();
            ui.checkbox(&mut snapping.enabled, "Snap\tShift+Tab");
            ui.horizontal(|ui| {
                use hedra_edit::SnapElement;
                ui.label("Snap to");
                ui.radio_value(&mut snapping.element, SnapElement::Increment, "Increment");
                ui.radio_value(&mut snapping.element, SnapElement::Vertex, "Vertex");
            });
            ui.horizontal(|ui| {
                ui.label("Snap step");
                ui.add(
                    egui::DragValue::new(&mut snapping.step)
                        .speed(0.01)
                        .range(0.001..=1000.0),
                );
                ui.label("angle°");
                ui.add(
                    egui::DragValue::new(&mut snapping.angle_step)
                        .speed(0.1)
                        .range(0.1..=180.0),
                );
            });
            ui.separator();
            // The transform gizmo on objects, mesh elements and control points.
            {
                use bevy::gizmos::transform_gizmo::TransformGizmoMode as Mode;
                ui.radio_value(gizmo_mode, Mode::Translate, "Gizmo: move");
                ui.radio_value(gizmo_mode, Mode::Rotate, "Gizmo: rotate");
                ui.radio_value(gizmo_mode, Mode::Scale, "Gizmo: scale");
            }
            ui.separator();
            if ui.button("Cursor to World Origin").clicked() {
                *cursor = DVec3::ZERO;
                ui.close();
            }
            let selected = selection_center(&model.state.session.doc, &model.selection);
            if ui
                .add_enabled(selected.is_some(), egui::Button::new("Cursor to Selected"))
                .clicked()
            {
                *cursor = selected.unwrap_or(*cursor);
                ui.close();
            }
            ui.label("Shift+right click: place the 3D cursor");
            ui.separator();
            ui.label("Frame selected: F or Numpad .");
            ui.label("Frame all: Home");
        });
    });
}

/// The transform of a new object: at the 3D cursor.
fn at_cursor(at: DVec3) -> NodeTransform {
    NodeTransform {
        translation: at,
        ..NodeTransform::IDENTITY
    }
}

pub(super) fn add_primitive_buttons(ui: &mut egui::Ui, events: &mut Vec<UiEvent>, at: DVec3) {
    for kind in Primitive::KINDS {
        let p = Primitive::default_of(kind).expect("listed kinds have defaults");
        if ui.button(p.display_name()).clicked() {
            exec(
                events,
                Command::AddPrimitive {
                    primitive: p,
                    name: None,
                    parent: None,
                    transform: at_cursor(at),
                },
            );
            ui.close();
        }
    }
}

/// The active node when it is a curve (for "revolve" / "extrude").
pub(super) fn active_curve(doc: &Document, active: Option<NodeId>) -> Option<NodeId> {
    active.filter(|&id| {
        matches!(
            doc.node(id).map(|n| &n.content),
            Some(NodeContent::Curve(_))
        )
    })
}

/// Curves and surfaces of the Add menu, with small default control nets.
pub(super) fn add_shape_buttons(
    ui: &mut egui::Ui,
    events: &mut Vec<UiEvent>,
    curve: Option<NodeId>,
    at: DVec3,
) {
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
        transform: at_cursor(at),
    };
    let surface_cmd = |name: &str, surface: SurfaceSpec| Command::AddSurface {
        name: name.into(),
        surface,
        parent: None,
        transform: at_cursor(at),
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
            transform: NodeTransform::IDENTITY,
        }),
    );
}

pub(super) fn add_menu(
    ctx: &egui::Context,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
    curve: Option<NodeId>,
    at: DVec3,
) {
    let Some(pos) = state.add_menu_at else { return };
    let close = cursor_menu(ctx, ADD_MENU, pos, |ui| {
        ui.label(egui::RichText::new("Add").strong());
        ui.separator();
        let before = events.len();
        add_primitive_buttons(ui, events, at);
        add_shape_buttons(ui, events, curve, at);
        events.len() > before
    });
    if close {
        state.add_menu_at = None;
    }
}

/// The egui id of the Shift+A menu.
pub const ADD_MENU: &str = "add-menu";

/// The egui id of the Shift+S snap menu.
pub const SNAP_MENU: &str = "snap-menu";

/// Shift+S: Blender's snap menu at the pointer, for the 3D cursor and the
/// selected objects.
pub(super) fn snap_menu(
    ctx: &egui::Context,
    state: &mut UiState,
    model: &Model,
    cursor: &mut DVec3,
    events: &mut Vec<UiEvent>,
) {
    let Some(pos) = state.snap_menu_at else {
        return;
    };
    let doc = &model.state.session.doc;
    let selected = selection_center(doc, &model.selection);
    let object_mode = model.mode.node.is_none() && model.shape_edit.node.is_none();
    let close = cursor_menu(ctx, SNAP_MENU, pos, |ui| {
        ui.label(egui::RichText::new("Snap").strong());
        ui.separator();
        if ui.button("Cursor to World Origin").clicked() {
            *cursor = DVec3::ZERO;
            return true;
        }
        if ui
            .add_enabled(selected.is_some(), egui::Button::new("Cursor to Selected"))
            .clicked()
        {
            *cursor = selected.unwrap_or(*cursor);
            return true;
        }
        let movable = object_mode && selected.is_some();
        if ui
            .add_enabled(movable, egui::Button::new("Selection to Cursor"))
            .clicked()
        {
            // Each selected object's origin goes to the cursor, in its parent's space.
            let nodes = model
                .selection
                .nodes
                .iter()
                .filter_map(|&id| {
                    let node = doc.node(id)?;
                    let parent = node
                        .parent
                        .map_or(glam::DMat4::IDENTITY, |p| doc.world_matrix(p));
                    let transform = NodeTransform {
                        translation: parent.inverse().transform_point3(*cursor),
                        ..node.transform
                    };
                    Some((NodeRef::from(id), transform))
                })
                .collect();
            exec(events, Command::SetTransforms { nodes });
            return true;
        }
        false
    });
    if close {
        state.snap_menu_at = None;
    }
}

/// The egui id of the M merge menu.
pub const MERGE_MENU: &str = "merge-menu";

/// M in vertex edit mode: Blender's merge menu at the cursor.
pub(super) fn merge_menu(ctx: &egui::Context, model: &mut Model, events: &mut Vec<UiEvent>) {
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
pub(super) fn cursor_menu(
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
pub(super) fn merge_buttons(
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

/// Edit mode's Mesh menu: every tool on the current selection. Amounts start
/// at sensible defaults and are changed in the Adjust Last window, as in
/// Blender; the keys run the same tools interactively.
pub(super) fn mesh_menu(
    ui: &mut egui::Ui,
    node: NodeId,
    mode: &EditMode,
    events: &mut Vec<UiEvent>,
) {
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
    let mut start_bisect = false;
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
    item(ui, "Triangulate Faces\tCtrl+T", has_f, &|| {
        Command::Triangulate {
            node: n.clone(),
            faces: faces(),
        }
    });
    item(ui, "Tris to Quads\tAlt+J", has_f, &|| {
        Command::TrisToQuads {
            node: n.clone(),
            faces: faces(),
            face_degrees: 40.0,
            shape_degrees: 40.0,
        }
    });
    if ui
        .add_enabled(has_f, egui::Button::new("Bisect (drag a line)"))
        .clicked()
    {
        // Pushed after the menu: `item` holds the event list until then.
        start_bisect = true;
        ui.close();
    }
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
    if start_bisect {
        events.push(UiEvent::StartBisect);
    }
}

/// The vertices a selection touches, of any element kind, as a command's set.
pub(super) fn selection_vertices(
    sel: &hedra_edit::ElementSelection,
) -> Option<hedra_doc::VertexSet> {
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

/// The mean world origin of the selected nodes (Cursor to Selected).
fn selection_center(doc: &Document, selection: &Selection) -> Option<DVec3> {
    let origins: Vec<DVec3> = selection
        .nodes
        .iter()
        .filter(|&&id| doc.node(id).is_some())
        .map(|&id| doc.world_matrix(id).w_axis.truncate())
        .collect();
    (!origins.is_empty()).then(|| origins.iter().sum::<DVec3>() / origins.len() as f64)
}
