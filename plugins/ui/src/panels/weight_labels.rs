//! Labels in the viewport: weights next to the control points, the
//! continuity of a curve's joints.

use super::*;

/// In shape edit mode, each control point's weight next to it (selected
/// points in orange), read from the control-point entities; only for
/// rational nets of up to 400 points.
pub(super) fn weight_labels(
    painter: &egui::Painter,
    model: &Model,
    points: &[hedra_scene::ControlPoint],
    cam: &Camera,
    cam_t: &GlobalTransform,
) {
    let edit = &model.shape_edit;
    let Some(id) = edit.node else { return };
    let doc = &model.state.session.doc;
    let rational = doc
        .node(id)
        .is_some_and(|n| hedra_edit::shape_mode::control_weights(&n.content).is_some());
    if !rational || points.len() > 400 {
        return;
    }
    let world = doc.world_matrix(id);
    // Selected points first: their labels win where labels would overlap.
    let mut ordered: Vec<&hedra_scene::ControlPoint> = points.iter().collect();
    ordered.sort_by_key(|p| !edit.selected.contains(&p.index));
    let mut placed: Vec<egui::Rect> = Vec::new();
    for p in ordered {
        let Ok(s) = cam.world_to_viewport(cam_t, world.transform_point3(p.position).as_vec3())
        else {
            continue;
        };
        let selected = edit.selected.contains(&p.index);
        let color = if selected {
            egui::Color32::from_rgb(255, 170, 80)
        } else {
            egui::Color32::from_gray(235)
        };
        let galley = painter.layout_no_wrap(
            format!("{:.2}", p.weight),
            egui::FontId::proportional(if selected { 14.0 } else { 12.0 }),
            color,
        );
        let rect = egui::Rect::from_min_size(
            egui::pos2(s.x + 8.0, s.y - 8.0 - galley.size().y),
            galley.size(),
        )
        .expand2(egui::vec2(3.0, 1.0));
        // A label that would cover one already drawn is left out.
        if placed.iter().any(|r| r.intersects(rect)) {
            continue;
        }
        placed.push(rect);
        // A dark plate keeps the label readable on a pale surface.
        painter.rect_filled(rect, 3.0, egui::Color32::from_black_alpha(170));
        painter.galley(rect.min + egui::vec2(3.0, 1.0), galley, color);
    }
}

/// With Analysis ▸ Continuity at the joints on, each joint of the active
/// curve labelled with what its two sides agree on (C0 … C2, G1, G2),
/// measured from one-sided derivatives of the NURBS form.
pub(super) fn joint_labels(
    painter: &egui::Painter,
    model: &Model,
    analysis: &hedra_viewport::CurveAnalysis,
    cam: &Camera,
    cam_t: &GlobalTransform,
) {
    if !analysis.joints {
        return;
    }
    let doc = &model.state.session.doc;
    let Some(id) = model.selection.active() else {
        return;
    };
    let Some(NodeContent::Curve(c)) = doc.node(id).map(|n| &n.content) else {
        return;
    };
    let world = doc.world_matrix(id);
    let tolerance = hedra_geom::curves::joints::JointTolerance::default();
    for joint in c.kind().joints(c.nurbs(), &tolerance).iter().take(200) {
        let Ok(s) = cam.world_to_viewport(cam_t, world.transform_point3(joint.position).as_vec3())
        else {
            continue;
        };
        let label = joint.continuity.label();
        let color = match label {
            "gap" | "C0" => egui::Color32::from_rgb(255, 110, 90),
            "G1" => egui::Color32::from_rgb(255, 210, 90),
            _ => egui::Color32::from_rgb(120, 230, 140),
        };
        painter.text(
            egui::pos2(s.x, s.y + 10.0),
            egui::Align2::CENTER_TOP,
            label,
            egui::FontId::proportional(12.0),
            color,
        );
    }
}
