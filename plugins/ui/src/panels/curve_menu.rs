//! The Curve menu of control-point mode: the curve edits of its keys (E,
//! X, Alt+C, Y) and those without a key (reverse, joint continuity,
//! conversion to NURBS).

use super::menu_table::{ALWAYS, MenuRow, item, keyed_item, start_tool};
use super::*;
use hedra_edit::bindings::{Action, KeyMode::ControlPoints};
use hedra_geom::curves::{CurveKind, Join, PolyBezier};

/// The poly-Bézier joint at anchor `anchor`, as `SetCurveJoin` numbers
/// joints (an open chain's first joint is its second anchor); `None` for a
/// handle or an open chain's end.
pub(super) fn joint_of_anchor(kind: &CurveKind, anchor: usize) -> Option<u32> {
    let CurveKind::PolyBezier(PolyBezier { points, closed, .. }) = kind else {
        return None;
    };
    if !anchor.is_multiple_of(3) || anchor >= points.len() {
        return None;
    }
    let joint = if *closed {
        anchor / 3
    } else if anchor == 0 || anchor + 1 == points.len() {
        return None;
    } else {
        anchor / 3 - 1
    };
    Some(joint as u32)
}

/// The curve control-point mode edits, with its selected points.
fn edited_curve<'a>(s: &'a MenuState<'_>) -> Option<(NodeId, &'a hedra_doc::CurveContent)> {
    let node = s.shape_edit.node?;
    match &s.doc.node(node)?.content {
        NodeContent::Curve(curve) => Some((node, curve)),
        _ => None,
    }
}

/// The one selected point, if exactly one is.
fn one_selected(s: &MenuState<'_>) -> Option<u32> {
    match s.shape_edit.selected.iter().collect::<Vec<_>>()[..] {
        [&i] => Some(i),
        _ => None,
    }
}

/// The Curve menu of control-point mode.
pub(super) const CURVE_MENU: &[MenuRow] = &[
    keyed_item(
        "Extrude",
        ControlPoints,
        Action::Extrude,
        |s| {
            let (_, curve) = edited_curve(s).ok_or("")?;
            let last = curve.control_points().len() as u32 - 1;
            match one_selected(s) {
                Some(i) if !curve.kind().is_closed() && (i == 0 || i == last) => Ok(()),
                _ => Err("Select the first or last point of an open curve"),
            }
        },
        |_, e| start_tool(e, Action::Extrude),
    ),
    keyed_item(
        "Delete Points",
        ControlPoints,
        Action::Delete,
        |s| match s.shape_edit.selected.is_empty() {
            true => Err("Select the points to delete"),
            false => Ok(()),
        },
        |_, e| start_tool(e, Action::Delete),
    ),
    // Its label says what it does to this curve.
    MenuRow::Listed(|ui, s, e| {
        let closed = edited_curve(s).is_some_and(|(_, c)| c.kind().is_closed());
        let label = keyed_in(
            ControlPoints,
            if closed { "Open" } else { "Close" },
            Action::ToggleClosed,
        );
        if ui.button(label).clicked() {
            start_tool(e, Action::ToggleClosed);
            ui.close();
        }
    }),
    keyed_item(
        "Split at Point",
        ControlPoints,
        Action::SplitCurve,
        |s| {
            let (_, curve) = edited_curve(s).ok_or("")?;
            let kind = curve.kind();
            let on_curve =
                one_selected(s).is_some_and(|i| kind.on_curve_parameter(i as usize).is_some());
            match on_curve && !kind.is_closed() {
                true => Ok(()),
                false => Err("Select one point on an open curve"),
            }
        },
        |_, e| start_tool(e, Action::SplitCurve),
    ),
    MenuRow::Separator,
    item("Reverse Direction", ALWAYS, |s, e| {
        if let Some((node, _)) = edited_curve(s) {
            exec(e, Command::ReverseCurve { node: node.into() })
        }
    }),
    // Its hover text says how close the NURBS form is.
    MenuRow::Listed(|ui, s, e| {
        let Some((node, curve)) = edited_curve(s) else {
            return;
        };
        let is_nurbs = matches!(curve.kind(), CurveKind::Nurbs(_));
        if ui
            .add_enabled(!is_nurbs, egui::Button::new("Convert to NURBS"))
            .on_hover_text(match curve.tolerance() {
                Some(t) => format!("approximated within {t:.2e}"),
                None => "exact: the same shape".into(),
            })
            .clicked()
        {
            exec(e, Command::ConvertCurveToNurbs { node: node.into() });
            ui.close();
        }
    }),
    MenuRow::Listed(joint_items),
];

/// A poly-Bézier's joint at the selected anchor: corner, smooth, aligned or
/// auto.
fn joint_items(ui: &mut egui::Ui, s: &MenuState<'_>, events: &mut Vec<UiEvent>) {
    let Some((node, curve)) = edited_curve(s) else {
        return;
    };
    let kind = curve.kind();
    if !matches!(kind, CurveKind::PolyBezier(_)) {
        return;
    }
    let joint = one_selected(s).and_then(|i| joint_of_anchor(kind, i as usize));
    ui.separator();
    ui.label(egui::RichText::new("Joint at the selected anchor").weak());
    for (label, join) in [
        ("Corner (C0)", Join::C0),
        ("Smooth (C1)", Join::C1),
        ("Aligned (G1)", Join::G1),
        ("Auto (follows the anchors)", Join::Auto),
    ] {
        if ui
            .add_enabled(joint.is_some(), egui::Button::new(label))
            .clicked()
            && let Some(joint) = joint
        {
            exec(
                events,
                Command::SetCurveJoin {
                    node: node.into(),
                    joint,
                    join,
                },
            );
            ui.close();
        }
    }
}
