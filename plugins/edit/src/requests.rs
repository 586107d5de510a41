//! What the panels ask of edit's state: the selection, the merge menu, and
//! tools started from a menu. The panels send [`EditRequest`] messages;
//! [`apply_edit_requests`] applies them in `SceneSystems::Requests`, before
//! the shortcut systems read this frame's keys, so a tool asked for from a
//! menu starts in the next frame exactly as its key would start it.

use crate::bindings::{Action, RequestedAction};
use crate::{BisectDrag, CurveDraw, EditMode, Selection};
use bevy::prelude::*;
use hedra_doc::NodeId;
use hedra_scene::StatusMessage;

/// A panel's request to edit.
#[derive(Message, Clone, Debug, PartialEq)]
pub enum EditRequest {
    /// Select `node` (the outliner): alone, or toggled in the selection
    /// when `additive` (Shift/Ctrl held).
    Select {
        /// The node clicked.
        node: NodeId,
        /// Add to (or take from) the selection instead of replacing it.
        additive: bool,
    },
    /// A menu item that starts the same interactive tool as its keys.
    Start(Action),
    /// Mesh ▸ Bisect: arm the drag of the cutting line.
    StartBisect,
    /// Add ▸ Draw Curve: start drawing a curve by clicks.
    DrawCurve,
    /// The *Pick axis* button of a revolution: select the node and click
    /// its axis's two points.
    PickAxis(NodeId),
    /// The M merge menu was closed (an item chosen, or clicked away).
    CloseMergeMenu,
}

/// Applies the panels' [`EditRequest`]s in the order they were sent.
pub fn apply_edit_requests(
    mut requests: MessageReader<EditRequest>,
    mut selection: ResMut<Selection>,
    mut mode: ResMut<EditMode>,
    mut bisect: ResMut<BisectDrag>,
    mut curve_draw: ResMut<CurveDraw>,
    mut requested: ResMut<RequestedAction>,
    mut status: ResMut<StatusMessage>,
) {
    for request in requests.read() {
        match request {
            EditRequest::Select { node, additive } => {
                if *additive {
                    selection.toggle(*node);
                } else {
                    selection.set([*node]);
                }
            }
            EditRequest::Start(action) => requested.0 = Some(*action),
            EditRequest::StartBisect => crate::start_bisect(&mut bisect, &mode, &mut status),
            EditRequest::DrawCurve => {
                selection.nodes.clear();
                curve_draw.start(&mut status);
            }
            EditRequest::PickAxis(node) => {
                selection.set([*node]);
                curve_draw.start_axis(*node, &mut status);
            }
            EditRequest::CloseMergeMenu => {
                if mode.merge_menu_at.is_some() {
                    mode.merge_menu_at = None;
                }
            }
        }
    }
}
