//! Object ▸ Boolean (issue 17): a one-shot boolean of two selected
//! meshes (the active one kept, Blender's Ctrl+Numpad +, −, *), and a live
//! CSG node made of the selected objects; a CSG node's panel switches its
//! operation and applies it.

use super::*;
use hedra_geom::csg::BooleanOp;

/// The three operations with their menu names.
const OPS: [(BooleanOp, &str); 3] = [
    (BooleanOp::Union, "Union"),
    (BooleanOp::Difference, "Difference"),
    (BooleanOp::Intersection, "Intersection"),
];

use hedra_edit::boolean_command;

/// Object ▸ Boolean: the one-shot operations and a live CSG node.
pub(super) fn boolean_menu(ui: &mut egui::Ui, selection: &Selection, events: &mut Vec<UiEvent>) {
    for ((op, label), action) in OPS.into_iter().zip([
        hedra_edit::bindings::Action::BooleanUnion,
        hedra_edit::bindings::Action::BooleanDifference,
        hedra_edit::bindings::Action::BooleanIntersection,
    ]) {
        let cmd = boolean_command(selection, op);
        if ui
            .add_enabled(
                cmd.is_some(),
                egui::Button::new(keyed_in(
                    hedra_edit::bindings::KeyMode::Object,
                    &format!("{label} (apply)"),
                    action,
                )),
            )
            .on_disabled_hover_text("Select two closed meshes; the active one is kept")
            .clicked()
            && let Some(cmd) = cmd
        {
            exec(events, cmd);
            ui.close();
        }
    }
    ui.separator();
    for (op, label) in OPS {
        if ui
            .add_enabled(
                selection.nodes.len() >= 2,
                egui::Button::new(format!("Live CSG {label}")),
            )
            .on_hover_text("A CSG node whose operands are the selected objects (editable later)")
            .clicked()
        {
            exec(
                events,
                Command::AddCsg {
                    op,
                    name: Some(label.into()),
                    operands: selection.refs(),
                    parent: None,
                    transform: Default::default(),
                },
            );
            ui.close();
        }
    }
}

/// A CSG node's section: its operation (switchable), its operands, its
/// solid's counts or why there is none, Apply.
pub(super) fn csg_panel(
    ui: &mut egui::Ui,
    doc: &Document,
    node: &hedra_doc::Node,
    events: &mut Vec<UiEvent>,
) {
    let NodeContent::Csg(c) = &node.content else {
        return;
    };
    ui.horizontal(|ui| {
        for (op, label) in OPS {
            if ui.selectable_label(c.op == op, label).clicked() && c.op != op {
                exec(
                    events,
                    Command::SetCsgOp {
                        node: node.id.into(),
                        op,
                    },
                );
            }
        }
    });
    let names: Vec<String> = hedra_doc::csg::operands(doc, node.id)
        .iter()
        .filter_map(|&o| doc.node(o).map(|n| format!("'{}'", n.name)))
        .collect();
    ui.label(format!("Operands (its children): {}", names.join(", ")));
    match hedra_doc::csg::evaluate(doc, node.id) {
        Ok(solid) if solid.face_count() == 0 => {
            ui.label(
                "Solid: empty (V 0 E 0 F 0): the operands do not overlap as the operation needs",
            );
        }
        Ok(solid) => {
            let s = solid.stats();
            ui.label(format!(
                "Solid: V {} E {} F {}",
                s.vertices, s.edges, s.faces
            ));
        }
        Err(e) => {
            ui.colored_label(egui::Color32::LIGHT_RED, e.to_string());
        }
    }
    if ui
        .button("Apply")
        .on_hover_text("Make the solid a plain mesh (the operands go)")
        .clicked()
    {
        exec(
            events,
            Command::ApplyCsg {
                node: node.id.into(),
            },
        );
    }
}
