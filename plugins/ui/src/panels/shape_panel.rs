//! The Properties panel's curve and surface section: kind, degree, knots,
//! knot insertion, degree elevation, analysis overlays and measures.

use super::*;

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
            if let hedra_geom::curves::CurveKind::Fractal(hedra_geom::curves::Fractal {
                rule,
                level,
                ..
            }) = content.kind()
            {
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
    // Knots only where the shape is a NURBS (other kinds insert points: K).
    // Rows of buttons wrap: a row wider than the panel would widen it (the
    // viewport jumped) or be clipped ("Insert knot in v at").
    if !directions.is_empty() {
        ui.horizontal_wrapped(|ui| {
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
    }
    let elevations: &[(ParameterDirection, &str)] = match content {
        NodeContent::Surface(s) if matches!(**s, hedra_doc::SurfaceShape::Nurbs(_)) => &[
            (ParameterDirection::U, "Elevate degree in u"),
            (ParameterDirection::V, "Elevate degree in v"),
        ],
        _ => &[(ParameterDirection::U, "Elevate degree")],
    };
    ui.horizontal_wrapped(|ui| {
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
        ui.checkbox(&mut analysis.joints, "Continuity at the joints");
        ui.checkbox(&mut analysis.hulls, "Convex hulls of the Bézier segments");
        if analysis.frame {
            ui.add(egui::Slider::new(&mut analysis.at, 0.0..=1.0).text("at"));
        }
        curve_measures(ui, id, content, model, state, analysis, events);
        if let NodeContent::Curve(c) = content {
            power_basis(ui, c, state);
        }
    }
    if matches!(content, NodeContent::Surface(_)) {
        ui.separator();
        ui.label(egui::RichText::new("Analysis").weak())
            .on_hover_text("Drawn on every selected surface: select both patches of a joint to see the section and the point on each");
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
    point_coordinates(ui, id, content, &selected, state, events);
    if let NodeContent::Curve(c) = content {
        span_length(ui, c, model.state.session.doc.world_matrix(id), &selected);
        key_tbc(ui, id, c.kind(), &selected, state, events);
    }
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

/// Tension, bias and continuity of the selected keys of a Kochanek-Bartels
/// curve (seed 001): the first selected key's values shown, a change sets
/// all selected keys, one undo step when the drag ends.
fn key_tbc(
    ui: &mut egui::Ui,
    id: NodeId,
    kind: &hedra_geom::curves::CurveKind,
    selected: &[u32],
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
) {
    let hedra_geom::curves::CurveKind::KochanekBartels(hedra_geom::curves::KochanekBartels {
        points,
        keys,
        closed,
    }) = kind
    else {
        return;
    };
    let chosen: Vec<usize> = selected
        .iter()
        .map(|&i| i as usize)
        .filter(|&i| i < keys.len())
        .collect();
    let Some(&first) = chosen.first() else {
        ui.label("Select keys to edit their tension, bias and continuity.");
        return;
    };
    let k = keys[first];
    let mut values = state.tbc_edit.unwrap_or([k.tension, k.bias, k.continuity]);
    ui.label(if chosen.len() == 1 {
        format!("Key {first}")
    } else {
        format!("{} keys", chosen.len())
    });
    let mut busy = false;
    let mut edited = false;
    ui.horizontal(|ui| {
        for (value, name) in values.iter_mut().zip(["T ", "B ", "C "]) {
            let r = ui.add(
                egui::DragValue::new(value)
                    .speed(0.01)
                    .range(-1.0..=1.0)
                    .max_decimals(3)
                    .prefix(name),
            );
            edited |= r.changed();
            busy |= r.dragged() || r.has_focus();
        }
    })
    .response
    .on_hover_text("Tension shortens the tangents, bias leans them, continuity ≠ 0 makes a corner");
    if edited {
        state.tbc_edit = Some(values);
    }
    if busy {
        return;
    }
    let Some([tension, bias, continuity]) = state.tbc_edit.take() else {
        return;
    };
    let mut keys = keys.clone();
    for &i in &chosen {
        keys[i] = hedra_geom::curves::interpolating::Tbc {
            tension,
            bias,
            continuity,
        };
    }
    exec(
        events,
        Command::SetCurve {
            node: id.into(),
            curve: hedra_doc::command::CurveSpec::KochanekBartels {
                points: points.clone(),
                keys: Some(keys),
                closed: *closed,
            },
        },
    );
}

/// The selected control points' median in the node's space, typed or
/// dragged (Blender's N panel): a change moves every selected point by the
/// same amount, one undo step when let go.
fn point_coordinates(
    ui: &mut egui::Ui,
    id: NodeId,
    content: &NodeContent,
    selected: &[u32],
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
) {
    let points = hedra_edit::shape_mode::control_points(content);
    let chosen: Vec<u32> = selected
        .iter()
        .copied()
        .filter(|&i| (i as usize) < points.len())
        .collect();
    if chosen.is_empty() {
        return;
    }
    let median = chosen.iter().map(|&i| points[i as usize]).sum::<DVec3>() / chosen.len() as f64;
    let mut at = state.point_edit.unwrap_or(median);
    let (mut edited, mut busy) = (false, false);
    // Wrapped: the fields follow a drag, and a longer number must not
    // widen the panel (the viewport would shrink under the pointer).
    ui.horizontal_wrapped(|ui| {
        ui.label(if chosen.len() == 1 {
            format!("Point {}", chosen[0])
        } else {
            "Median".to_string()
        });
        for (value, name) in [&mut at.x, &mut at.y, &mut at.z]
            .into_iter()
            .zip(["X ", "Y ", "Z "])
        {
            let r = ui.add(
                egui::DragValue::new(value)
                    .speed(0.01)
                    .max_decimals(6)
                    .prefix(name),
            );
            edited |= r.changed();
            busy |= r.dragged() || r.has_focus();
        }
    });
    if edited {
        state.point_edit = Some(at);
    }
    if busy {
        return;
    }
    let Some(to) = state.point_edit.take() else {
        return;
    };
    let delta = to - median;
    if delta.length() > 0.0 {
        exec(
            events,
            Command::SetControlPoints {
                node: id.into(),
                points: chosen
                    .iter()
                    .map(|&i| (i, points[i as usize] + delta))
                    .collect(),
            },
        );
    }
}

/// The arc length between two selected points the curve passes through
/// (world units; Gauss–Legendre on the world curve, as the whole length).
fn span_length(
    ui: &mut egui::Ui,
    content: &hedra_doc::CurveContent,
    world: glam::DMat4,
    selected: &[u32],
) {
    let [a, b] = selected[..] else { return };
    let kind = content.kind();
    let (Some(ta), Some(tb)) = (
        kind.on_curve_parameter(a as usize),
        kind.on_curve_parameter(b as usize),
    ) else {
        return;
    };
    if let Some(curve) = hedra_viewport::world_curve(content.nurbs(), world) {
        let length = hedra_geom::curves::analysis::arc_length(&curve, ta.min(tb), ta.max(tb));
        ui.label(format!("Span from point {a} to {b}: length {length:.6}"));
    }
}

/// Seed 003's power basis of one Bézier segment of the curve's NURBS form:
/// the matrix `M` with `A = M·G` (`r(u) = Σ aᵢ uⁱ`, `u` from 0 to 1 over
/// the segment) and the coefficients, as the seed prints them (highest
/// power first).
fn power_basis(ui: &mut egui::Ui, content: &hedra_doc::CurveContent, state: &mut UiState) {
    let Ok(segments) = hedra_geom::curves::bezier::power_basis_segments(content.nurbs()) else {
        return;
    };
    egui::CollapsingHeader::new("Power basis (Bézier to monomials)")
        .id_salt("power basis")
        .show(ui, |ui| {
            let last = segments.len().saturating_sub(1);
            state.power_segment = state.power_segment.min(last);
            ui.add(
                egui::Slider::new(&mut state.power_segment, 0..=last)
                    .text(format!("segment of {}", segments.len())),
            );
            let s = &segments[state.power_segment];
            let n = s.matrix.len() - 1;
            ui.label(format!(
                "t from {:.4} to {:.4}; r(u) = a_n u^n + … + a_0, A = M·G",
                s.interval.0, s.interval.1
            ));
            egui::Grid::new("power basis matrix")
                .striped(true)
                .show(ui, |ui| {
                    ui.label("M");
                    for j in 0..=n {
                        ui.label(egui::RichText::new(format!("b{}", n - j)).weak());
                    }
                    ui.end_row();
                    for (i, row) in s.matrix.iter().enumerate() {
                        ui.label(egui::RichText::new(format!("u^{}", n - i)).weak());
                        for x in row {
                            ui.label(format!("{x:.0}"));
                        }
                        ui.end_row();
                    }
                });
            // The coefficients below the matrix: a row beside it would
            // widen the panel past the viewport.
            for (i, a) in s.coefficients.iter().enumerate() {
                ui.label(format!("a{} = ({:.3}, {:.3}, {:.3})", n - i, a.x, a.y, a.z));
            }
            if s.weights.iter().any(|&w| (w - 1.0).abs() > 1e-12) {
                let w: Vec<String> = s
                    .weight_coefficients
                    .iter()
                    .map(|w| format!("{w:.3}"))
                    .collect();
                ui.label(format!(
                    "rational: denominator coefficients {}",
                    w.join(", ")
                ));
            }
        });
}
