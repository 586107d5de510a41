//! Object ▸ Boolean (issue 17): a one-shot boolean of two selected
//! meshes (the active one kept, Blender's Ctrl+Numpad +, −, *), and a live
//! CSG node made of the selected objects; a CSG node's panel switches its
//! operation and applies it.

use super::menu_table::{MenuRow, When, item, keyed_item, with_hover};
use super::*;
use hedra_edit::bindings::{Action, KeyMode::Object};
use hedra_geom::csg::BooleanOp;

/// The three operations with their menu names.
const OPS: [(BooleanOp, &str); 3] = [
    (BooleanOp::Union, "Union"),
    (BooleanOp::Difference, "Difference"),
    (BooleanOp::Intersection, "Intersection"),
];

use hedra_edit::boolean_command;

/// Select two closed meshes for a one-shot boolean.
const TWO_CLOSED: &str = "Select two closed meshes; the active one is kept";

/// The one-shot boolean `op` of the selection, where there is one.
fn one_shot(s: &MenuState<'_>, op: BooleanOp) -> Result<(), &'static str> {
    boolean_command(s.selection, op)
        .map(|_| ())
        .ok_or(TWO_CLOSED)
}

/// Sends the one-shot boolean `op` of the selection.
fn send_one_shot(s: &MenuState<'_>, op: BooleanOp, events: &mut Vec<UiEvent>) {
    if let Some(cmd) = boolean_command(s.selection, op) {
        exec(events, cmd);
    }
}

/// A live CSG node `op` of the selected objects.
fn live(s: &MenuState<'_>, op: BooleanOp, events: &mut Vec<UiEvent>) {
    let name = OPS
        .iter()
        .find(|(o, _)| *o == op)
        .map(|(_, n)| n.to_string());
    exec(
        events,
        Command::AddCsg {
            op,
            name,
            operands: s.selection.refs(),
            parent: None,
            transform: Default::default(),
        },
    );
}

const TWO_OBJECTS: When = |s| match s.selection.nodes.len() >= 2 {
    true => Ok(()),
    false => Err("Select the objects to combine (two or more)"),
};

const LIVE_HOVER: &str = "A CSG node whose operands are the selected objects (editable later)";

/// Object ▸ Boolean: the one-shot operations and a live CSG node.
pub(super) const BOOLEAN_MENU: &[MenuRow] = &[
    keyed_item(
        "Union (apply)",
        Object,
        Action::BooleanUnion,
        |s| one_shot(s, BooleanOp::Union),
        |s, e| send_one_shot(s, BooleanOp::Union, e),
    ),
    keyed_item(
        "Difference (apply)",
        Object,
        Action::BooleanDifference,
        |s| one_shot(s, BooleanOp::Difference),
        |s, e| send_one_shot(s, BooleanOp::Difference, e),
    ),
    keyed_item(
        "Intersection (apply)",
        Object,
        Action::BooleanIntersection,
        |s| one_shot(s, BooleanOp::Intersection),
        |s, e| send_one_shot(s, BooleanOp::Intersection, e),
    ),
    MenuRow::Separator,
    with_hover(
        item("Live CSG Union", TWO_OBJECTS, |s, e| {
            live(s, BooleanOp::Union, e)
        }),
        LIVE_HOVER,
    ),
    with_hover(
        item("Live CSG Difference", TWO_OBJECTS, |s, e| {
            live(s, BooleanOp::Difference, e)
        }),
        LIVE_HOVER,
    ),
    with_hover(
        item("Live CSG Intersection", TWO_OBJECTS, |s, e| {
            live(s, BooleanOp::Intersection, e)
        }),
        LIVE_HOVER,
    ),
];

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
