//! The outliner: the scene tree, visibility, renaming, drag to parent, context menu.

use super::*;

pub(super) fn outliner(
    ui: &mut egui::Ui,
    doc: &Document,
    revision: u64,
    selection: &Selection,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
) {
    egui::ScrollArea::vertical().show(ui, |ui| {
        // The tree from one top-down walk, made again only when the
        // document changes (a recursion that scanned every node for each
        // one's children took seconds a frame on a 2,000-deep scene).
        let tree = match state.outliner_tree.take() {
            Some((seen, tree)) if seen == revision => tree,
            _ => doc.hierarchy(),
        };
        for &id in tree.order() {
            let depth = tree.facts(id).map_or(0, |f| f.depth);
            outliner_row(ui, doc, id, depth, selection, state, events);
        }
        state.outliner_tree = Some((revision, tree));
        // Dropping a node on the empty area below the tree moves it to the top level.
        let rest = ui.available_size().max(egui::vec2(10.0, 40.0));
        let (_, resp) = ui.allocate_exact_size(rest, egui::Sense::hover());
        if let Some(dragged) = resp.dnd_release_payload::<NodeId>() {
            exec(
                events,
                Command::Reparent {
                    node: NodeRef::from(*dragged),
                    parent: None,
                    keep_world: true,
                },
            );
        }
    });
}

pub(super) fn outliner_row(
    ui: &mut egui::Ui,
    doc: &Document,
    id: NodeId,
    depth: usize,
    selection: &Selection,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
) {
    let Some(node) = doc.node(id) else { return };
    ui.horizontal(|ui| {
        ui.add_space(indent(depth));
        let eye = if node.visible { "👁" } else { "–" };
        if ui.small_button(eye).on_hover_text("Show / hide").clicked() {
            exec(
                events,
                Command::SetVisible {
                    nodes: vec![id.into()],
                    visible: !node.visible,
                },
            );
        }
        // Glyphs egui's default fonts have (∿, ◠ and ✛ drew as boxes).
        let icon = match node.content {
            NodeContent::Mesh(_) => "▣",
            NodeContent::Curve(_) => "〰",
            NodeContent::Surface(_) => "🔳",
            NodeContent::Empty => "✚",
            NodeContent::Csg(_) => "➕",
            // Kept as imported, not manifold: a warning sign.
            NodeContent::Kept(_) => "⚠",
        };
        if let Some(rename) = state.rename.as_mut().filter(|r| r.node == id) {
            let mut output = egui::TextEdit::singleline(&mut rename.text).show(ui);
            let resp = output.response.clone();
            if !rename.started {
                // First frame: focus the field with the whole name selected.
                rename.started = true;
                resp.request_focus();
                let all = egui::text::CCursorRange::two(
                    egui::text::CCursor::new(0),
                    egui::text::CCursor::new(rename.text.chars().count()),
                );
                output.state.cursor.set_char_range(Some(all));
                output.state.store(ui.ctx(), resp.id);
            }
            let text = rename.text.clone();
            if resp.lost_focus() {
                let name = text.trim().to_string();
                if ui.input(|i| !i.key_pressed(egui::Key::Escape))
                    && !name.is_empty()
                    && name != node.name
                {
                    exec(
                        events,
                        Command::Rename {
                            node: id.into(),
                            name,
                        },
                    );
                }
                state.rename = None;
            }
            return;
        }
        let selected = selection.contains(id);
        let text = egui::RichText::new(format!("{icon} {}", node.name));
        let text = if selection.active() == Some(id) {
            text.strong()
        } else {
            text
        };
        let resp =
            ui.add(egui::Button::selectable(selected, text).sense(egui::Sense::click_and_drag()));
        resp.dnd_set_drag_payload(id);
        if resp.clicked() {
            // The click's own modifiers: under lag Shift may be let go
            // before the frame that reads the click.
            let held = crate::egui_input::click_modifiers(ui);
            let additive = held.shift || held.ctrl;
            events.push(UiEvent::Select(id, additive));
        }
        if resp.double_clicked() {
            state.rename = Some(crate::Rename::new(id, &node.name));
        }
        if let Some(dragged) = resp.dnd_release_payload::<NodeId>()
            && *dragged != id
        {
            exec(
                events,
                Command::Reparent {
                    node: NodeRef::from(*dragged),
                    parent: Some(id.into()),
                    keep_world: true,
                },
            );
        }
        resp.context_menu(|ui| {
            if ui.button("Rename").clicked() {
                state.rename = Some(crate::Rename::new(id, &node.name));
                ui.close();
            }
            if ui.button("Duplicate").clicked() {
                exec(
                    events,
                    Command::Duplicate {
                        nodes: vec![id.into()],
                    },
                );
                ui.close();
            }
            if node.parent.is_some() && ui.button("Clear Parent").clicked() {
                exec(
                    events,
                    Command::Reparent {
                        node: id.into(),
                        parent: None,
                        keep_world: true,
                    },
                );
                ui.close();
            }
            if ui.button("Delete").clicked() {
                exec(
                    events,
                    Command::Delete {
                        nodes: vec![id.into()],
                    },
                );
                ui.close();
            }
        });
    });
}

/// How far a row is indented: 14 px a level, up to [`MAX_INDENT_LEVELS`]
/// (a deep chain would push its rows out of the panel).
fn indent(depth: usize) -> f32 {
    depth.min(MAX_INDENT_LEVELS) as f32 * 14.0
}

/// Levels past which rows are not indented further.
const MAX_INDENT_LEVELS: usize = 16;
