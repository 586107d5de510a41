//! Weight labels next to the control points in the viewport.

use super::*;

/// In shape edit mode, each control point's weight next to it (selected
/// points in orange); only for nets of up to 400 points.
pub(super) fn weight_labels(
    painter: &egui::Painter,
    model: &Model,
    cam: &Camera,
    cam_t: &GlobalTransform,
) {
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
