//! The Properties panel's subdivision section: the modifier's settings and,
//! in edit mode, the crease and taper of the selection.

use super::*;

/// The subdivision modifier of a mesh node and, in edit mode, the crease of
/// the selected edges or vertices.
pub(super) fn subdivision_panel(
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
            // What the chosen scheme honours; the rest is greyed out, with why.
            let applies = e.options.scheme.applicable();
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
                    ui.add_enabled_ui(applies.boundary, |ui| {
                        choice(
                            ui,
                            "boundary",
                            &mut e.options.boundary,
                            &BoundaryInterpolation::ALL,
                            BoundaryInterpolation::label,
                        )
                    });
                    ui.end_row();
                    ui.label("Creases");
                    ui.add_enabled_ui(applies.creases, |ui| {
                        choice(
                            ui,
                            "crease-method",
                            &mut e.options.crease_method,
                            &CreaseMethod::ALL,
                            CreaseMethod::label,
                        )
                    });
                    ui.end_row();
                });
            ui.add_enabled(
                applies.smooth_triangles,
                egui::Checkbox::new(&mut e.options.smooth_triangles, "Smooth triangles"),
            )
            .on_hover_text("OpenSubdiv's rule for triangles in Catmull-Clark: rounder results where a cage has triangles");
            if !applies.reason.is_empty() {
                ui.add(egui::Label::new(egui::RichText::new(applies.reason).weak()).wrap());
            }
            if !content.creases.holes.is_empty() {
                ui.label(format!(
                    "{} hole face(s): no surface there (Mesh ▸ Clear Hole)",
                    content.creases.holes.len()
                ));
            }
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
    if !vertex_mode {
        taper_row(ui, id, &content.mesh, &sel.edges, state, events);
    }
}

/// A crease whose sharpness runs from a start to an end value along the
/// selected chain of edges (Rhino's tapered SubD creases): the chain's ends
/// are the vertices with one selected edge (any vertex of a closed loop);
/// Reverse swaps which end starts.
fn taper_row(
    ui: &mut egui::Ui,
    id: NodeId,
    mesh: &hedra_geom::HalfEdgeMesh,
    edges: &std::collections::BTreeSet<hedra_geom::EdgeId>,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
) {
    let mut uses = std::collections::BTreeMap::<hedra_geom::VertexId, usize>::new();
    for &e in edges.iter().filter(|e| mesh.is_edge(**e)) {
        for v in mesh.edge_vertices(e) {
            *uses.entry(v).or_default() += 1;
        }
    }
    let mut ends: Vec<hedra_geom::VertexId> = uses
        .iter()
        .filter(|(_, n)| **n == 1)
        .map(|(v, _)| *v)
        .collect();
    if ends.is_empty() {
        ends.extend(uses.keys().next());
    }
    let Some(&first) = ends.first() else { return };
    let from = if state.taper.2 {
        *ends.last().unwrap_or(&first)
    } else {
        first
    };
    let (start, end, reversed) = &mut state.taper;
    ui.horizontal(|ui| {
        ui.label("Taper");
        ui.add(egui::DragValue::new(start).range(0.0..=10.0).speed(0.05).prefix("from "));
        ui.add(egui::DragValue::new(end).range(0.0..=10.0).speed(0.05).prefix("to "));
        ui.checkbox(reversed, "Reverse");
        if ui
            .button("Set")
            .on_hover_text(format!(
                "The crease runs from {start:.2} at vertex {from} to {end:.2} at the chain's other end"
            ))
            .clicked()
        {
            exec(
                events,
                Command::SetCreaseTaper {
                    node: id.into(),
                    edges: hedra_doc::elements::EdgeSet::Ids(edges.iter().map(|e| e.0).collect()),
                    from: hedra_doc::elements::VertexSet::Ids(vec![from.0]),
                    start: *start,
                    end: *end,
                },
            );
        }
    });
}
