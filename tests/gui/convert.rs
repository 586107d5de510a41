//! Object ▸ Convert ▸ To NURBS as a person uses it: a cube, Ctrl+1 for a
//! subdivision modifier, the menu item, then Adjust Last and Ctrl+Z.

use crate::user::User;
use bevy::prelude::*;
use hedra_doc::NodeContent;

/// The surface nodes under the node named `group`.
fn surfaces_under(user: &User, group: &str) -> usize {
    let doc = user.doc();
    let Some(group) = doc.find_by_name(group) else {
        return 0;
    };
    doc.nodes()
        .filter(|n| n.parent == Some(group.id) && matches!(n.content, NodeContent::Surface(_)))
        .count()
}

#[test]
fn convert_to_nurbs_from_the_object_menu_then_adjust_last_and_undo() {
    let mut user = User::new();
    user.add("Cube");
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::Digit1);
    let has_subdivision = |user: &User| {
        matches!(&user.doc().find_by_name("Cube").unwrap().content,
            NodeContent::Mesh(m) if m.subdivision.is_some())
    };
    assert!(has_subdivision(&user), "Ctrl+1: {}", user.status());
    let steps = user.undo_steps();

    user.click_on("Object");
    let convert = user.find("Convert ⏵");
    user.move_to(convert);
    user.frames(2);
    user.click_on("To NURBS");
    user.frames(2);
    // Six faces of regular quads pack into few exact surfaces; the eight
    // corners (valence 3) get fitted patches: more than six in all.
    let patches = surfaces_under(&user, "Cube NURBS");
    assert!(patches > 6, "{patches} surfaces: {}", user.status());
    assert_eq!(user.undo_steps(), steps + 1, "one undo step");
    let cube = user.doc().find_by_name("Cube").expect("the cage is kept");
    assert!(!cube.visible, "the kept cage is hidden");

    // Adjust Last: not keeping the cage deletes it, still one step.
    assert!(user.shows("Adjust Last: Convert to NURBS"));
    // The measured figures, in the status line and the window.
    assert!(
        user.status().contains("NURBS patches ("),
        "{}",
        user.status()
    );
    assert!(
        user.widgets()
            .iter()
            .any(|w| w.text.contains(" exact, ") && w.text.contains("largest angle")),
        "Adjust Last shows the figures"
    );
    user.click_on("Keep the cage (hidden)");
    user.frames(2);
    assert!(
        user.doc().find_by_name("Cube").is_none(),
        "the cage is gone"
    );
    assert_eq!(surfaces_under(&user, "Cube NURBS"), patches);
    assert_eq!(
        user.undo_steps(),
        steps + 1,
        "Adjust Last replaces the step"
    );

    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    assert!(user.doc().find_by_name("Cube NURBS").is_none());
    let cube = user
        .doc()
        .find_by_name("Cube")
        .expect("undo brings the cage back");
    assert!(cube.visible);
    assert!(has_subdivision(&user));
}

/// The item is greyed out, saying why, unless the active object is a mesh
/// with a Catmull-Clark modifier: a click on it changes nothing.
#[test]
fn convert_to_nurbs_needs_a_catmull_clark_mesh() {
    let mut user = User::new();
    user.add("Cube");
    let steps = user.undo_steps();
    user.click_on("Object");
    let convert = user.find("Convert ⏵");
    user.move_to(convert);
    user.frames(2);
    user.click_on("To NURBS");
    user.frames(2);
    assert_eq!(user.undo_steps(), steps, "nothing converted");
    assert_eq!(user.doc().nodes().count(), 1);
}
