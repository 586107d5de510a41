//! The status bar: mode, selection, the keys of what you are doing, messages.

use super::*;
use hedra_edit::bindings::{
    Action as A,
    KeyMode::{self, ControlPoints, Edit, Everywhere, Object, Tool},
    hints,
};

/// What the status bar says while a modal tool runs, from the keymap.
fn tool_hint() -> String {
    hints(&[
        (Tool, &[A::AxisX, A::AxisY, A::AxisZ], "constrain (Y is up)"),
        (Tool, &[A::Confirm], "(or click) confirm"),
        (Tool, &[A::Cancel], "(or right-click) cancel"),
    ]) + " · type a value"
}

/// The keys a mode's status bar reminds of, from the keymap, ending with
/// the key that lists them all.
fn mode_hint(items: &[(KeyMode, &[A], &str)]) -> String {
    format!(
        "{} · {}",
        hints(items),
        hints(&[(Everywhere, &[A::KeyHelp], "all keys")])
    )
}

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
        // While a tool runs its readout matters more than an old message.
        let tool_runs = model.tool.active.is_some()
            || model.mode.tool.is_some()
            || model.shape_edit.tool.is_some();
        let most = ui.available_width() * if tool_runs { 0.3 } else { 0.6 };
        let mut progress = model.previews.progress();
        progress.extend(model.jobs.progress());
        if progress.is_empty() {
            ui.scope(|ui| {
                ui.set_max_width(most);
                ui.add(egui::Label::new(text).truncate())
                    .on_hover_text(&s.text);
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
                ui.label(
                    egui::RichText::new("Edit Mode · Control Points")
                        .strong()
                        .color(egui::Color32::from_rgb(255, 170, 80)),
                );
                ui.separator();
                ui.label(format!("{}: {} selected", node.name, se.selected.len()));
                ui.separator();
                if let Some(t) = &se.tool {
                    ui.add(
                        egui::Label::new(
                            egui::RichText::new(&t.readout)
                                .color(egui::Color32::from_rgb(255, 200, 80)),
                        )
                        .truncate(),
                    );
                    ui.add(egui::Label::new(tool_hint()).truncate());
                } else {
                    let hints: &[(_, &[A], &str)] = if matches!(node.content, NodeContent::Curve(_))
                    {
                        &[
                            (ControlPoints, &[A::Move], "move"),
                            (ControlPoints, &[A::Extrude], "extrude"),
                            (ControlPoints, &[A::InsertKnot], "insert"),
                            (ControlPoints, &[A::Delete], "delete"),
                            (ControlPoints, &[A::SplitCurve], "split"),
                            (ControlPoints, &[A::ToggleClosed], "open/close"),
                            (ControlPoints, &[A::Weight], "weight"),
                            (Everywhere, &[A::EditModeToggle], "exit"),
                        ]
                    } else {
                        &[
                            (ControlPoints, &[A::SelectAll], "all"),
                            (ControlPoints, &[A::Move], "move"),
                            (ControlPoints, &[A::Rotate], "rotate"),
                            (ControlPoints, &[A::Scale], "scale"),
                            (ControlPoints, &[A::Weight], "weight"),
                            (ControlPoints, &[A::InsertKnot], "insert knot"),
                            (Everywhere, &[A::EditModeToggle], "exit"),
                        ]
                    };
                    ui.add(egui::Label::new(mode_hint(hints)).truncate());
                }
            } else if let Some(node) = edit.node.and_then(|n| doc.node(n)) {
                let kind = match edit.kind {
                    ElementKind::Vertex => "Vertex",
                    ElementKind::Edge => "Edge",
                    ElementKind::Face => "Face",
                };
                ui.label(
                    egui::RichText::new(format!("Edit Mode · {kind}"))
                        .strong()
                        .color(egui::Color32::from_rgb(255, 170, 80)),
                );
                ui.separator();
                // The current kind's count, out of the mesh's: the same
                // figure View ▸ Statistics gives for that kind.
                let s = &edit.selection;
                let mesh = match &node.content {
                    NodeContent::Mesh(c) => Some(&c.mesh),
                    _ => None,
                };
                let (selected, total, what) = match edit.kind {
                    ElementKind::Vertex => (
                        s.vertices.len(),
                        mesh.map_or(0, |m| m.vertex_count()),
                        "vertices",
                    ),
                    ElementKind::Edge => {
                        (s.edges.len(), mesh.map_or(0, |m| m.edge_count()), "edges")
                    }
                    ElementKind::Face => {
                        (s.faces.len(), mesh.map_or(0, |m| m.face_count()), "faces")
                    }
                };
                ui.label(format!("{}: {selected}/{total} {what} selected", node.name));
                ui.separator();
                if let Some(t) = &edit.tool {
                    ui.add(
                        egui::Label::new(
                            egui::RichText::new(&t.readout)
                                .color(egui::Color32::from_rgb(255, 200, 80)),
                        )
                        .truncate(),
                    );
                    ui.add(egui::Label::new(tool_hint()).truncate());
                } else {
                    let x_ray = if model.shading.see_through() {
                        "X-ray off"
                    } else {
                        "X-ray"
                    };
                    ui.add(
                        egui::Label::new(mode_hint(&[
                            (Edit, &[A::VertexMode, A::EdgeMode, A::FaceMode], "kind"),
                            (Edit, &[A::Move], "move"),
                            (Edit, &[A::Extrude], "extrude"),
                            (Edit, &[A::Inset], "inset"),
                            (Edit, &[A::LoopCut], "loop cut"),
                            (Edit, &[A::Connect], "connect"),
                            (Edit, &[A::Delete], "delete"),
                            (Edit, &[A::Dissolve], "dissolve"),
                            (Everywhere, &[A::XRay], x_ray),
                            (Everywhere, &[A::EditModeToggle], "exit"),
                        ]))
                        .truncate(),
                    );
                }
            } else {
                ui.label(egui::RichText::new("Object Mode").strong());
                ui.separator();
                let sel = &model.selection.nodes;
                match (
                    sel.len(),
                    model.selection.active().and_then(|a| doc.node(a)),
                ) {
                    (0, _) | (_, None) => ui.label("Nothing selected"),
                    (1, Some(n)) => ui.label(format!("Selected: {}", n.name)),
                    (k, Some(n)) => ui.label(format!("{k} selected, active: {}", n.name)),
                };
                ui.separator();
                if let Some(m) = &model.tool.active {
                    ui.add(
                        egui::Label::new(
                            egui::RichText::new(&m.readout)
                                .color(egui::Color32::from_rgb(255, 200, 80)),
                        )
                        .truncate(),
                    );
                    ui.add(egui::Label::new(tool_hint()).truncate());
                } else {
                    ui.add(
                        egui::Label::new(
                            mode_hint(&[
                                (Object, &[A::Move], "move"),
                                (Object, &[A::Rotate], "rotate"),
                                (Object, &[A::Scale], "scale"),
                                (Object, &[A::Delete], "delete"),
                                (Object, &[A::Duplicate], "duplicate"),
                                (Everywhere, &[A::AddMenu], "add"),
                                (Everywhere, &[A::EditModeToggle], "edit"),
                                (Everywhere, &[A::Undo], "undo"),
                            ]) + " · MMB orbit",
                        )
                        .truncate(),
                    );
                }
            }
        });
    });
}
