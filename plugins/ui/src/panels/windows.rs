//! Floating windows: Adjust Last and the undo history.

use super::*;

/// The key help (F1): every key of the current mode with what it does,
/// read from the keymap the shortcuts use (`hedra_edit::bindings`).
pub(super) fn key_help_window(
    ctx: &egui::Context,
    viewport: egui::Rect,
    model: &Model,
    help: &mut hedra_edit::bindings::KeyHelp,
) {
    use hedra_edit::bindings::{KeyMode, TOOL_NOTES, bindings_of};
    if !help.0 {
        return;
    }
    let mode = if model.mode.active() {
        KeyMode::Edit
    } else if model.shape_edit.active() {
        KeyMode::ControlPoints
    } else {
        KeyMode::Object
    };
    let tool_running = hedra_edit::modal_tool_running(&model.tool, &model.mode, &model.shape_edit);
    let notes: Vec<(String, &str)> = TOOL_NOTES
        .iter()
        .map(|&(keys, what)| (keys.to_string(), what))
        .collect();
    let tool_rows: Vec<(String, &str)> = bindings_of(KeyMode::Tool)
        .into_iter()
        .chain(notes)
        .collect();
    // One table, a heading row per section; a running tool's keys first.
    let mut sections = vec![
        (mode.label(), bindings_of(mode)),
        (
            KeyMode::Everywhere.label(),
            bindings_of(KeyMode::Everywhere),
        ),
        (KeyMode::Tool.label(), tool_rows),
    ];
    if tool_running {
        sections.rotate_right(1);
    }
    egui::Window::new(format!("Keys: {}", mode.label()))
        .id("key-help".into())
        .open(&mut help.0)
        .collapsible(false)
        .resizable(false)
        .pivot(egui::Align2::CENTER_CENTER)
        .default_pos(viewport.center())
        .show(ctx, |ui| {
            ui.label(egui::RichText::new("F1 or Esc closes this").weak());
            egui::ScrollArea::vertical()
                .max_height(viewport.height() * 0.65)
                .show(ui, |ui| {
                    egui::Grid::new("key-help-grid")
                        .num_columns(2)
                        .striped(true)
                        .show(ui, |ui| {
                            for (heading, rows) in &sections {
                                ui.heading(*heading);
                                ui.end_row();
                                for (chord, what) in rows {
                                    ui.strong(chord);
                                    ui.label(*what);
                                    ui.end_row();
                                }
                            }
                        });
                });
        });
}

/// Blender's "adjust last operation": the parameters of the last step, when
/// it added a primitive, editable in place.
pub(super) fn adjust_last_window(
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
            | Command::Bisect { .. }
            | Command::TrisToQuads { .. }
            | Command::Triangulate { .. }
            | Command::Spin { .. }
            | Command::Screw { .. }
            | Command::ConvertSubdivisionToNurbs { .. }
    );
    if !editable {
        return;
    }
    // The title names the command; what the step's label adds (a
    // conversion's measured figures) is shown inside.
    let name = command.label();
    let notes = last
        .label
        .strip_prefix(name.as_str())
        .map(|rest| rest.trim().trim_start_matches('(').trim_end_matches(')'))
        .unwrap_or_default()
        .to_string();
    egui::Window::new(format!("Adjust Last: {name}"))
        .id("adjust-last".into())
        .collapsible(true)
        .resizable(false)
        .pivot(egui::Align2::LEFT_BOTTOM)
        .fixed_pos(viewport.left_bottom() + egui::vec2(8.0, -8.0))
        .show(ctx, |ui| {
            if !notes.is_empty() {
                ui.set_max_width(360.0);
                ui.label(egui::RichText::new(&notes).weak());
            }
            let changed = match &mut edited {
                Command::AddPrimitive { primitive, .. } => primitive_editor(ui, primitive),
                Command::BevelEdges {
                    width, segments, ..
                } => {
                    let w = number_row(ui, "Width", width, 0.005, 0.0001..=1e6);
                    w | count_row(ui, "Segments", segments, 1..=32)
                }
                Command::ConvertSubdivisionToNurbs {
                    tolerance,
                    keep_cage,
                    ..
                } => {
                    let mut fraction =
                        tolerance.unwrap_or(hedra_doc::command::DEFAULT_NURBS_TOLERANCE);
                    let before = (fraction, *keep_cage);
                    ui.horizontal(|ui| {
                        ui.label("Tolerance (of the size)");
                        ui.add(
                            egui::DragValue::new(&mut fraction)
                                .speed(1e-5)
                                .range(1e-7..=0.1)
                                .max_decimals(7),
                        )
                    });
                    ui.checkbox(keep_cage, "Keep the cage (hidden)");
                    *tolerance = Some(fraction);
                    (fraction, *keep_cage) != before
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
                // Blender's Bisect panel: which side to clear, and the fill.
                Command::Bisect { clear, fill, .. } => {
                    use hedra_geom::modeling::BisectClear;
                    let before = (*clear, *fill);
                    ui.horizontal(|ui| {
                        ui.label("Clear");
                        choice(
                            ui,
                            "adjust-bisect-clear",
                            clear,
                            &[BisectClear::Neither, BisectClear::Outer, BisectClear::Inner],
                            |c| match c {
                                BisectClear::Neither => "Neither side",
                                BisectClear::Outer => "Outer (right of the line)",
                                BisectClear::Inner => "Inner (left of the line)",
                            },
                        )
                    });
                    ui.checkbox(fill, "Fill");
                    (*clear, *fill) != before
                }
                Command::TrisToQuads {
                    face_degrees,
                    shape_degrees,
                    ..
                } => {
                    number_row(ui, "Max face angle°", face_degrees, 0.5, 0.0..=180.0)
                        | number_row(ui, "Max shape angle°", shape_degrees, 0.5, 0.0..=180.0)
                }
                Command::Triangulate { method, .. } => {
                    use hedra_geom::modeling::TriangulateMethod;
                    let before = *method;
                    ui.horizontal(|ui| {
                        ui.label("Method");
                        choice(
                            ui,
                            "adjust-triangulate",
                            method,
                            &TriangulateMethod::ALL,
                            TriangulateMethod::label,
                        )
                    });
                    *method != before
                }
                Command::Spin {
                    degrees,
                    steps,
                    center,
                    axis,
                    ..
                } => {
                    let d = number_row(ui, "Angle°", degrees, 1.0, -3600.0..=3600.0);
                    let s = count_row(ui, "Steps", steps, 1..=1024);
                    let c = vec3_row(ui, "Center", center, 0.01).changed();
                    let a = vec3_row(ui, "Axis", axis, 0.01).changed();
                    d | s | c | a
                }
                Command::Screw {
                    turns,
                    steps,
                    pitch,
                    ..
                } => {
                    count_row(ui, "Turns", turns, 1..=256)
                        | count_row(ui, "Steps per turn", steps, 3..=1024)
                        | number_row(ui, "Pitch", pitch, 0.01, -1e6..=1e6)
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

/// A labelled whole-number field (segments, steps, turns); true when it
/// changed.
fn count_row(
    ui: &mut egui::Ui,
    label: &str,
    v: &mut u32,
    range: std::ops::RangeInclusive<u32>,
) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        ui.add(egui::DragValue::new(v).speed(0.1).range(range))
            .changed()
    })
    .inner
}

pub(super) fn number_row(
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

pub(super) fn history_window(
    ctx: &egui::Context,
    viewport: egui::Rect,
    model: &Model,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
) {
    let h = &model.state.session.history;
    // Opens in the viewport's top right corner, off the outliner and the
    // properties.
    egui::Window::new("Undo History")
        .open(&mut state.show_history)
        .default_width(240.0)
        .default_pos(viewport.right_top() + egui::vec2(-260.0, 10.0))
        .constrain_to(viewport)
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

/// Blender's Statistics overlay in the viewport's top left corner: in
/// object mode the selected and total objects and the vertices, edges,
/// faces and triangles of the visible meshes' cages; in edit mode the
/// selected and total elements of the edited mesh.
pub(super) fn statistics_overlay(
    ctx: &egui::Context,
    viewport: egui::Rect,
    model: &Model,
    state: &mut UiState,
) {
    let revision = model.state.revision;
    let doc = &model.state.session.doc;
    let shown = match state.shown_counts {
        Some((r, counts)) if r == revision => counts,
        _ => {
            let counts = shown_counts(doc);
            state.shown_counts = Some((revision, counts));
            counts
        }
    };
    let lines = statistics_lines(doc, &model.selection, &model.mode, shown);
    egui::Area::new("statistics".into())
        .fixed_pos(viewport.left_top() + egui::vec2(10.0, 8.0))
        .interactable(false)
        .show(ctx, |ui| {
            for line in lines {
                ui.label(egui::RichText::new(line).color(egui::Color32::from_gray(225)));
            }
        });
}

/// Triangles of `m`'s faces when fanned (an n-gon makes n - 2).
fn triangles(m: &hedra_geom::HalfEdgeMesh) -> usize {
    m.faces().map(|f| m.face_degree(f).saturating_sub(2)).sum()
}

/// Vertices, edges, faces and triangles of the visible meshes as the
/// viewport shows them: the modifier stack applied and subdivision at its
/// viewport level (a cube at level 4 counts 1,536 faces, not the cage's 6);
/// a CSG node counts its solid.
fn shown_counts(doc: &Document) -> [usize; 4] {
    let tree = doc.hierarchy();
    let mut counts = [0; 4];
    let mut add = |m: &hedra_geom::HalfEdgeMesh| {
        counts[0] += m.vertex_count();
        counts[1] += m.edge_count();
        counts[2] += m.face_count();
        counts[3] += triangles(m);
    };
    // Operands are drawn through their CSG node's solid.
    for n in doc
        .nodes()
        .filter(|n| tree.is_visible(n.id) && !tree.inside_csg(n.id))
    {
        match &n.content {
            NodeContent::Mesh(c) => {
                let level = c.subdivision.map_or(0, |s| s.viewport_level);
                if let Ok(m) = c.evaluated(level) {
                    add(&m);
                }
            }
            NodeContent::Csg(_) => {
                if let Ok(solid) = hedra_doc::csg::evaluate(doc, n.id) {
                    add(&solid);
                }
            }
            _ => {}
        }
    }
    counts
}

/// The overlay's lines (see [`statistics_overlay`]).
fn statistics_lines(
    doc: &Document,
    selection: &Selection,
    mode: &EditMode,
    shown: [usize; 4],
) -> Vec<String> {
    if let Some(node) = mode.node
        && let Some(NodeContent::Mesh(c)) = doc.node(node).map(|n| &n.content)
    {
        let (m, s) = (&c.mesh, &mode.selection);
        // Counted as Blender flushes a selection: the vertices and edges of
        // selected faces and edges count as selected, and so do the edges
        // (vertex mode) and faces (vertex and edge modes) they close.
        let vertices = s.all_vertices(m);
        let mut edges: std::collections::BTreeSet<hedra_geom::EdgeId> =
            s.edges.iter().copied().filter(|&e| m.is_edge(e)).collect();
        for &f in s.faces.iter().filter(|&&f| m.is_face(f)) {
            edges.extend(m.face_halfedges(f).map(|h| h.edge()));
        }
        if mode.kind == ElementKind::Vertex {
            edges.extend(
                m.edges()
                    .filter(|&e| m.edge_vertices(e).iter().all(|v| vertices.contains(v))),
            );
        }
        let faces = match mode.kind {
            ElementKind::Face => s.faces.iter().filter(|&&f| m.is_face(f)).count(),
            _ => m
                .faces()
                .filter(|&f| m.face_halfedges(f).all(|h| edges.contains(&h.edge())))
                .count(),
        };
        return vec![
            format!("Vertices {}/{}", vertices.len(), m.vertex_count()),
            format!("Edges {}/{}", edges.len(), m.edge_count()),
            format!("Faces {faces}/{}", m.face_count()),
            format!("Triangles {}", triangles(m)),
        ];
    }
    let visible: Vec<&hedra_doc::Node> = doc
        .nodes()
        .filter(|n| hedra_edit::visible(doc, n.id))
        .collect();
    let selected = visible.iter().filter(|n| selection.contains(n.id)).count();
    let [v, e, f, t] = shown;
    vec![
        format!("Objects {selected}/{}", visible.len()),
        format!("Vertices {v}"),
        format!("Edges {e}"),
        format!("Faces {f}"),
        format!("Triangles {t}"),
    ]
}
