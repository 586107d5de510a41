//! The Curve menu of control-point mode: the curve edits of its keys (E,
//! X, Alt+C, Y) and those without a key (reverse, joint continuity,
//! conversion to NURBS).

use super::*;
use hedra_edit::bindings::{Action, KeyMode};
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

/// The Curve menu for the curve `node` in control-point mode with the
/// points `selected`.
pub(super) fn curve_menu(
    ui: &mut egui::Ui,
    node: NodeId,
    curve: &hedra_doc::CurveContent,
    selected: &std::collections::BTreeSet<u32>,
    events: &mut Vec<UiEvent>,
) {
    let keyed = |label: &str, action: Action| keyed_in(KeyMode::ControlPoints, label, action);
    let mut start = |ui: &mut egui::Ui, label: String, enabled: bool, action: Action| {
        if ui.add_enabled(enabled, egui::Button::new(label)).clicked() {
            events.push(UiEvent::Edit(hedra_edit::EditRequest::Start(action)));
            ui.close();
        }
    };
    let kind = curve.kind();
    let last = curve.control_points().len() as u32 - 1;
    let one = match selected.iter().collect::<Vec<_>>()[..] {
        [&i] => Some(i),
        _ => None,
    };
    let at_end = !kind.is_closed() && matches!(one, Some(i) if i == 0 || i == last);
    start(
        ui,
        keyed("Extrude", Action::Extrude),
        at_end,
        Action::Extrude,
    );
    start(
        ui,
        keyed("Delete Points", Action::Delete),
        !selected.is_empty(),
        Action::Delete,
    );
    let closed = kind.is_closed();
    start(
        ui,
        keyed(if closed { "Open" } else { "Close" }, Action::ToggleClosed),
        true,
        Action::ToggleClosed,
    );
    let on_curve = one.is_some_and(|i| kind.on_curve_parameter(i as usize).is_some());
    start(
        ui,
        keyed("Split at Point", Action::SplitCurve),
        on_curve && !closed,
        Action::SplitCurve,
    );
    ui.separator();
    let n = NodeRef::from(node);
    if ui.button("Reverse Direction").clicked() {
        exec(events, Command::ReverseCurve { node: n.clone() });
        ui.close();
    }
    let is_nurbs = matches!(kind, CurveKind::Nurbs(_));
    if ui
        .add_enabled(!is_nurbs, egui::Button::new("Convert to NURBS"))
        .on_hover_text(match curve.tolerance() {
            Some(t) => format!("approximated within {t:.2e}"),
            None => "exact: the same shape".into(),
        })
        .clicked()
    {
        exec(events, Command::ConvertCurveToNurbs { node: n.clone() });
        ui.close();
    }
    if let CurveKind::PolyBezier(_) = kind {
        let joint = one.and_then(|i| joint_of_anchor(kind, i as usize));
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
            {
                exec(
                    events,
                    Command::SetCurveJoin {
                        node: n.clone(),
                        joint: joint.expect("enabled"),
                        join,
                    },
                );
                ui.close();
            }
        }
    }
}
