//! The whole app used as a person uses it: keys, clicks held over several
//! frames, drags and the wheel go in through Bevy's input messages (see
//! `user.rs`), and the document, the selection, the status line and the
//! render meshes are checked after.

mod user;

use bevy::prelude::*;
use bevy_egui::{EguiContext, PrimaryEguiContext, egui};
use user::{HOLD, User};

/// egui's context of the main window.
fn egui_context(user: &mut User) -> egui::Context {
    let world = user.app.world_mut();
    let mut q = world.query_filtered::<&mut EguiContext, With<PrimaryEguiContext>>();
    q.single_mut(world).unwrap().get_mut().clone()
}

/// The clickable items of the egui area or window `id`, top to bottom, found
/// as a person finds them: by moving the pointer down its left side, where
/// every item begins, and seeing what lights up (the area's own background
/// is left out).
fn items_of(user: &mut User, id: &str) -> Vec<egui::Rect> {
    let area = area_rect(user, id);
    let mut found: Vec<(egui::Id, egui::Rect)> = Vec::new();
    let mut y = area.top() + 1.0;
    while y < area.bottom() {
        user.move_to(Vec2::new(area.left() + 12.0, y));
        let ctx = egui_context(user);
        let hovered: Vec<egui::Id> =
            ctx.interaction_snapshot(|i| i.hovered.iter().copied().collect());
        for id in hovered {
            if let Some(r) = ctx.read_response(id)
                && r.sense.senses_click()
                && !r.sense.senses_drag() // selectable labels drag to select text
                && r.rect.height() < area.height() - 2.0
                && !found.iter().any(|(f, _)| *f == id)
            {
                found.push((id, r.rect));
            }
        }
        y += 2.0;
    }
    found.into_iter().map(|(_, r)| r).collect()
}

/// The rect of an egui area or window by its id, as last laid out.
fn area_rect(user: &mut User, id: &str) -> egui::Rect {
    egui_context(user)
        .memory(|m| m.area_rect(egui::Id::new(id)))
        .unwrap_or_else(|| panic!("no egui area '{id}' is shown"))
}

fn center(r: egui::Rect) -> Vec2 {
    Vec2::new(r.center().x, r.center().y)
}

/// The items of the Shift+A menu, opened at the viewport's centre.
fn open_add_menu(user: &mut User) -> Vec<egui::Rect> {
    let at = user.viewport_center();
    user.move_to(at);
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::KeyA);
    items_of(user, hedra_ui::ADD_MENU)
}

/// Index of Cube among the Shift+A menu's clickable rows (after Plane).
const ADD_MENU_CUBE: usize = 1;

#[test]
fn shift_a_cube_takes_a_click_of_any_length() {
    // None: pressed and released within one frame.
    for hold in [None, Some(0), Some(1), Some(HOLD), Some(12), Some(30)] {
        let mut user = User::new();
        let items = open_add_menu(&mut user);
        assert!(items.len() > 8, "the Add menu lists primitives and shapes: {items:?}");
        let cube = center(items[ADD_MENU_CUBE]);
        match hold {
            None => user.click_instant(cube),
            Some(frames) => user.click_held(cube, frames),
        }
        assert_eq!(
            user.node_names(),
            ["Cube"],
            "a click held {hold:?} frames on Add ▸ Cube adds one cube"
        );
        let cube = user.doc().nodes().next().unwrap();
        let mesh = cube.content.mesh().unwrap();
        assert_eq!(
            (mesh.vertex_count(), mesh.edge_count(), mesh.face_count()),
            (8, 12, 6)
        );
        assert_eq!(user.undo_steps(), 1);
        assert!(
            user.app.world().resource::<hedra_ui::UiState>().add_menu_at.is_none(),
            "the menu closes after the click"
        );
    }
}
