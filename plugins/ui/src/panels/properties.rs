//! The Properties panel: transform, primitive, subdivision, curve and surface settings.

use super::*;

pub(super) fn vec3_row(
    ui: &mut egui::Ui,
    label: &str,
    v: &mut DVec3,
    speed: f64,
) -> egui::Response {
    // Shown as 0, not "-0.0" (a quaternion's Euler angles give negative zeros).
    *v = v.map(|c| if c == 0.0 { 0.0 } else { c });
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

pub(super) fn properties(
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
            if !busy
                && let Some((eid, edited)) = state.transform_edit.take()
                && eid == id
                && edited != node.transform
            {
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
        egui::CollapsingHeader::new("Modifiers")
            .default_open(true)
            .show(ui, |ui| {
                modifier_stack_panel(ui, id, content, state, events)
            });
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
                topology_counts(ui, id, &content.mesh, model);
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

/// A curve's length (world units), its division into equal arc lengths as
/// a new polyline node, and the closest point to the pointer (seed 001's
/// curve operations).
fn curve_measures(
    ui: &mut egui::Ui,
    id: NodeId,
    content: &NodeContent,
    model: &Model,
    state: &mut UiState,
    analysis: &mut hedra_viewport::CurveAnalysis,
    events: &mut Vec<UiEvent>,
) {
    use hedra_geom::curves::{
        Curve,
        analysis::{arc_length, equal_arc_length_parameters},
    };
    let NodeContent::Curve(c) = content else {
        return;
    };
    let c = c.nurbs();
    let doc = &model.state.session.doc;
    if let Some(world) = hedra_viewport::world_curve(c, doc.world_matrix(id)) {
        let (a, b) = world.domain();
        ui.label(format!("Length {:.6}", arc_length(&world, a, b)));
    }
    ui.horizontal(|ui| {
        ui.add(
            egui::DragValue::new(&mut state.divide_count)
                .range(2..=10_000)
                .suffix(" points"),
        );
        if ui
            .button("Divide into equal lengths")
            .on_hover_text("A new polyline through points an equal arc length apart")
            .clicked()
        {
            let node = doc.node(id);
            let params = equal_arc_length_parameters(&**c, state.divide_count);
            exec(
                events,
                Command::AddCurve {
                    name: format!("{} divided", node.map_or("Curve", |n| n.name.as_str())),
                    curve: hedra_doc::command::CurveSpec::Nurbs {
                        degree: 1,
                        points: c.points_at(&params),
                        weights: None,
                        knots: None,
                    },
                    parent: node.and_then(|n| n.parent).map(NodeRef::from),
                    transform: node.map_or_else(NodeTransform::default, |n| n.transform),
                },
            );
        }
    });
    ui.checkbox(&mut analysis.closest, "Closest point to the pointer");
    if analysis.closest {
        ui.label(match analysis.closest_found {
            Some(p) => format!("t {:.6} · distance {:.6}", p.t, p.distance),
            None => "point into the viewport".to_string(),
        });
    }
}

/// A curve's or surface's degree, knots and control points; in edit mode
/// (Tab) the weight of the selected points; knot insertion and degree
/// elevation.
pub(super) fn shape_panel(
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
        NodeContent::Curve(content)
            if !matches!(content.kind(), hedra_geom::curves::CurveKind::Nurbs(_)) =>
        {
            // Other kinds: their name and points; the NURBS form they are drawn as.
            let c = content.nurbs();
            ui.label(format!(
                "{}, {} points (drawn as NURBS of degree {}, {} control points)",
                content.kind().name(),
                content.control_points().len(),
                c.degree(),
                c.points().len(),
            ));
            // The seed's Hausdorff dimension of a fractal, and how far an
            // approximated NURBS form may stray.
            if let hedra_geom::curves::CurveKind::Fractal { rule, level, .. } = content.kind() {
                ui.label(format!(
                    "level {level}, Hausdorff dimension {:.4}",
                    rule.dimension()
                ));
            }
            if let Some(t) = content.tolerance() {
                ui.label(format!("NURBS form within {t:.2e} of the curve"));
            }
        }
        NodeContent::Curve(content) => {
            let c = content.nurbs();
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
        curve_measures(ui, id, content, model, state, analysis, events);
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
pub(super) fn choice<T: Copy + PartialEq>(
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

/// Fields for a primitive's parameters; true when one changed.
pub fn primitive_editor(ui: &mut egui::Ui, p: &mut Primitive) -> bool {
    let mut changed = false;
    let mut len = |ui: &mut egui::Ui, label: &str, v: &mut f64| {
        ui.horizontal(|ui| {
            ui.label(label);
            changed |= ui
                .add(
                    // Above zero and below the kernel's limit.
                    egui::DragValue::new(v)
                        .speed(0.01)
                        .range(f64::EPSILON..=hedra_geom::primitives::MAX_LENGTH)
                        .max_decimals(4),
                )
                .changed();
        });
    };
    let mut count_changed = false;
    // The kernel's ranges, by parameter name.
    let mut count = |ui: &mut egui::Ui, label: &str, v: &mut u32, parameter: &str| {
        let (range, _) = hedra_geom::primitives::count_range(parameter);
        ui.horizontal(|ui| {
            ui.label(label);
            count_changed |= ui
                .add(egui::DragValue::new(v).speed(0.1).range(range))
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
            count(ui, "X subdivisions", x_segments, "x_segments");
            count(ui, "Z subdivisions", z_segments, "z_segments");
            len(ui, "Size", size);
        }
        Primitive::UvSphere {
            segments,
            rings,
            radius,
        } => {
            count(ui, "Segments", segments, "segments");
            count(ui, "Rings", rings, "rings");
            len(ui, "Radius", radius);
        }
        Primitive::IcoSphere {
            subdivisions,
            radius,
        } => {
            count(ui, "Subdivisions", subdivisions, "subdivisions");
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
            count(ui, "Vertices", segments, "segments");
            len(ui, "Radius", radius);
            len(ui, "Depth", depth);
        }
        Primitive::Torus {
            major_segments,
            minor_segments,
            major_radius,
            minor_radius,
        } => {
            count(ui, "Major segments", major_segments, "major_segments");
            count(ui, "Minor segments", minor_segments, "minor_segments");
            len(ui, "Major radius", major_radius);
            len(ui, "Minor radius", minor_radius);
        }
    }
    changed || count_changed
}
