//! The status bar: mode, selection, the keys of what you are doing, messages.

use super::*;

pub(super) fn status_bar(ui: &mut egui::Ui, model: &Model) {
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
                    let x_ray = if model.shading.see_through() { "X-ray on (Alt+Z)" } else { "Alt+Z X-ray" };
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
