//! The menus that open at the pointer: Shift+S (snap), M (merge), and the
//! placement they share with Shift+A (`cursor_menu`).

use super::*;

/// The egui id of the Shift+S snap menu.
pub const SNAP_MENU: &str = "snap-menu";

/// Shift+S: Blender's snap menu at the pointer, for the 3D cursor and the
/// selected objects.
pub(super) fn snap_menu(
    ctx: &egui::Context,
    state: &mut UiState,
    model: &Model,
    cursor: &mut DVec3,
    events: &mut Vec<UiEvent>,
) {
    let Some(pos) = state.snap_menu_at else {
        return;
    };
    let doc = &model.state.session.doc;
    let selected = selection_center(doc, &model.selection);
    let object_mode = model.mode.node.is_none() && model.shape_edit.node.is_none();
    let close = cursor_menu(ctx, SNAP_MENU, pos, |ui| {
        ui.label(egui::RichText::new("Snap").strong());
        ui.separator();
        if ui.button("Cursor to World Origin").clicked() {
            *cursor = DVec3::ZERO;
            return true;
        }
        if ui
            .add_enabled(selected.is_some(), egui::Button::new("Cursor to Selected"))
            .clicked()
        {
            *cursor = selected.unwrap_or(*cursor);
            return true;
        }
        let movable = object_mode && selected.is_some();
        if ui
            .add_enabled(movable, egui::Button::new("Selection to Cursor"))
            .clicked()
        {
            // Each selected object's origin goes to the cursor, in its parent's space.
            let nodes = model
                .selection
                .nodes
                .iter()
                .filter_map(|&id| {
                    let node = doc.node(id)?;
                    let parent = node
                        .parent
                        .map_or(glam::DMat4::IDENTITY, |p| doc.world_matrix(p));
                    let transform = NodeTransform {
                        translation: parent.inverse().transform_point3(*cursor),
                        ..node.transform
                    };
                    Some((NodeRef::from(id), transform))
                })
                .collect();
            exec(events, Command::SetTransforms { nodes });
            return true;
        }
        false
    });
    if close {
        state.snap_menu_at = None;
    }
}

/// Z: Blender's shading pie as a menu at the pointer: solid, wireframe or
/// X-ray for the viewport, the overlays, and flat or smooth shading of the
/// selected objects.
pub(super) fn shading_menu(
    ctx: &egui::Context,
    state: &mut UiState,
    shading: &mut hedra_scene::ViewportShading,
    selection: &Selection,
    events: &mut Vec<UiEvent>,
) {
    use hedra_edit::bindings::{Action, KeyMode::Everywhere};
    let Some(pos) = state.shading_menu_at else {
        return;
    };
    let selected = selection.refs();
    let close = cursor_menu(ctx, "shading-menu", pos, |ui| {
        ui.label(egui::RichText::new("Shading").strong());
        ui.separator();
        let solid = !shading.wireframe && !shading.x_ray;
        if ui.radio(solid, "Solid").clicked() {
            (shading.wireframe, shading.x_ray) = (false, false);
            return true;
        }
        if ui
            .radio(
                shading.wireframe,
                keyed_in(Everywhere, "Wireframe", Action::Wireframe),
            )
            .clicked()
        {
            (shading.wireframe, shading.x_ray) = (true, false);
            return true;
        }
        if ui
            .radio(
                shading.x_ray && !shading.wireframe,
                keyed_in(Everywhere, "X-ray", Action::XRay),
            )
            .clicked()
        {
            (shading.wireframe, shading.x_ray) = (false, true);
            return true;
        }
        ui.separator();
        if ui
            .checkbox(&mut shading.face_orientation, "Face Orientation")
            .clicked()
            || ui.checkbox(&mut shading.cages, "Cages").clicked()
        {
            return true;
        }
        ui.separator();
        for (label, how) in [
            ("Shade Flat", Shading::Flat),
            ("Shade Smooth", Shading::Smooth),
        ] {
            if ui
                .add_enabled(!selected.is_empty(), egui::Button::new(label))
                .on_hover_text("the selected objects")
                .clicked()
            {
                exec(
                    events,
                    Command::SetShading {
                        nodes: selected.clone(),
                        shading: how,
                    },
                );
                return true;
            }
        }
        false
    });
    if close {
        state.shading_menu_at = None;
    }
}

/// The egui id of the M merge menu.
pub const MERGE_MENU: &str = "merge-menu";

/// M in vertex edit mode: Blender's merge menu at the cursor.
pub(super) fn merge_menu(ctx: &egui::Context, model: &Model, events: &mut Vec<UiEvent>) {
    let Some(pos) = model.mode.merge_menu_at else {
        return;
    };
    let Some(node) = model.mode.node else {
        events.push(UiEvent::Edit(hedra_edit::EditRequest::CloseMergeMenu));
        return;
    };
    let selection = &model.mode.selection;
    let close = cursor_menu(ctx, MERGE_MENU, egui::pos2(pos.x, pos.y), |ui| {
        ui.label(egui::RichText::new("Merge").strong());
        ui.separator();
        let before = events.len();
        merge_buttons(ui, node, selection, events);
        events.len() > before
    });
    if close {
        events.push(UiEvent::Edit(hedra_edit::EditRequest::CloseMergeMenu));
    }
}

/// A menu at the cursor (Shift+A, M), moved up and left as far as it must
/// to fit the window. `items` draws the items and says whether one was
/// chosen. Returns whether the menu closes: an item was chosen, a press
/// began outside the menu, or Esc.
///
/// The menu is placed where it fits before egui shows it, and "outside" is
/// tested against the rect egui laid it out in: when egui itself moves an
/// area to fit, the area's response keeps the unmoved rect, so a press on
/// an item of a menu opened near the bottom counted as outside and closed
/// the menu before the release could click the item (issue 11).
/// The egui memory key under which `draw_ui` leaves this frame's viewport
/// rect for the menus that open at the pointer.
pub(super) const VIEWPORT_RECT: &str = "hedra-viewport-rect";

pub(super) fn cursor_menu(
    ctx: &egui::Context,
    id: &str,
    at: egui::Pos2,
    items: impl FnOnce(&mut egui::Ui) -> bool,
) -> bool {
    let id = egui::Id::new(id);
    // Fitted into the viewport, so that a menu opened low stays above the
    // status bar and off the side panels.
    let screen = ctx
        .data(|d| d.get_temp::<egui::Rect>(egui::Id::new(VIEWPORT_RECT)))
        .unwrap_or_else(|| ctx.content_rect());
    let size = ctx
        .memory(|m| m.area_rect(id))
        .map_or(egui::Vec2::ZERO, |r| r.size());
    let fitted = egui::pos2(
        at.x.min(screen.right() - size.x).max(screen.left()),
        at.y.min(screen.bottom() - size.y).max(screen.top()),
    );
    let mut chosen = false;
    egui::Area::new(id)
        .fixed_pos(fitted)
        .order(egui::Order::Foreground)
        .show(ctx, |ui| {
            // Looks like the menu bar's menus: full-width items without frames.
            egui::containers::menu::menu_style(ui.style_mut());
            egui::Frame::menu(ui.style()).show(ui, |ui| {
                ui.with_layout(egui::Layout::top_down_justified(egui::Align::Min), |ui| {
                    chosen = items(ui);
                });
            });
        });
    let shown = ctx.memory(|m| m.area_rect(id));
    let pressed_outside = ctx.input(|i| {
        i.pointer.any_pressed()
            && i.pointer
                .press_origin()
                .is_some_and(|p| !shown.is_some_and(|r| r.contains(p)))
    });
    chosen || pressed_outside || ctx.input(|i| i.key_pressed(egui::Key::Escape))
}

/// At Center / At First / At Last / By Distance on the selected vertices
/// (First and Last: in the order they were clicked).
pub(super) fn merge_buttons(
    ui: &mut egui::Ui,
    node: NodeId,
    sel: &hedra_edit::ElementSelection,
    events: &mut Vec<UiEvent>,
) {
    use hedra_geom::modeling::MergePoint;
    let ordered =
        || hedra_doc::VertexSet::Ids(sel.ordered_vertices().iter().map(|v| v.0).collect());
    let enabled = sel.vertices.len() >= 2;
    for (label, at) in [
        ("At Center", MergePoint::Center),
        ("At First", MergePoint::First),
        ("At Last", MergePoint::Last),
    ] {
        if ui.add_enabled(enabled, egui::Button::new(label)).clicked() {
            exec(
                events,
                Command::MergeVertices {
                    node: NodeRef::from(node),
                    vertices: ordered(),
                    at,
                },
            );
            ui.close();
        }
    }
    if ui
        .add_enabled(enabled, egui::Button::new("By Distance"))
        .on_hover_text("Weld selected vertices closer than 0.0001 (change it in Adjust Last)")
        .clicked()
    {
        exec(
            events,
            Command::MergeByDistance {
                node: NodeRef::from(node),
                vertices: ordered(),
                distance: 0.0001,
            },
        );
        ui.close();
    }
}

/// The mean world origin of the selected nodes (Cursor to Selected).
pub(super) fn selection_center(doc: &Document, selection: &Selection) -> Option<DVec3> {
    let origins: Vec<DVec3> = selection
        .nodes
        .iter()
        .filter(|&&id| doc.node(id).is_some())
        .map(|&id| doc.world_matrix(id).w_axis.truncate())
        .collect();
    (!origins.is_empty()).then(|| origins.iter().sum::<DVec3>() / origins.len() as f64)
}
