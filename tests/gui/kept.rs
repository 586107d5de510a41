//! A mesh kept as imported (issue 37): a non-manifold OBJ dropped on the
//! window stays as the file has it, is drawn, picked, moved and smoothed;
//! Tab explains why edit mode is not available, and Mesh ▸ Make Manifold
//! repairs it so that Tab works; undo brings the kept mesh back.

use crate::user::User;
use bevy::prelude::*;
use hedra_doc::NodeContent;

/// Three quads on one edge (the z axis from 0 to 1), flaps along +x, +y
/// and −x.
const FIN: &str = "o Fin
v 0 0 0
v 0 0 1
v 1 0 0
v 1 0 1
v 0 1 0
v 0 1 1
v -1 0 0
v -1 0 1
f 1 3 4 2
f 2 6 5 1
f 1 7 8 2
";

fn fin_content(user: &User) -> NodeContent {
    user.doc()
        .find_by_name("Fin")
        .expect("the fin node")
        .content
        .clone()
}

/// Positions of the fin's render mesh.
fn render_corner_count(user: &User) -> usize {
    user.render_positions().len()
}

#[test]
fn a_non_manifold_file_is_kept_drawn_picked_smoothed_and_repaired_on_request() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fin.obj");
    std::fs::write(&path, FIN).unwrap();
    let mut user = User::new();
    user.drop_file(path);
    // Kept as in the file, with a note naming the edge in three faces.
    let NodeContent::Kept(kept) = fin_content(&user) else {
        panic!("the fin is kept: {}", user.status());
    };
    assert_eq!(kept.mesh.faces.len(), 3);
    let status = user.status();
    assert!(
        status.contains("kept as in the file") && status.contains("2–1 (3 faces)"),
        "{status}"
    );
    // Drawn flat: each quad its own 4 corners.
    assert_eq!(render_corner_count(&user), 12);

    // A click on the +x flap selects it.
    let flap = user.screen_of(Vec3::new(0.6, 0.0, 0.5));
    user.click(flap);
    let id = user.doc().find_by_name("Fin").unwrap().id;
    assert_eq!(
        user.app
            .world()
            .resource::<hedra_edit::Selection>()
            .active(),
        Some(id),
        "{}",
        user.status()
    );

    // Tab says why edit mode does not open, and what to do.
    user.tap(KeyCode::Tab);
    assert!(
        user.edit_mode().node.is_none(),
        "no edit mode on a kept mesh"
    );
    let status = user.status();
    assert!(
        status.contains("not manifold") && status.contains("Make Manifold"),
        "{status}"
    );

    // Ctrl+2: smoothed by OpenSubdiv's rules, 3 quads → 48 at level 2.
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::Digit2);
    let NodeContent::Kept(kept) = fin_content(&user) else {
        panic!("still kept");
    };
    assert_eq!(kept.subdivision.map(|m| m.viewport_level), Some(2));
    user.frames(2);
    assert_eq!(render_corner_count(&user), 48 * 4, "{}", user.status());
    // The spine stays straight (a non-manifold edge is infinitely sharp):
    // every render point on the z axis has x = y = 0 exactly there.
    let on_spine = user
        .render_positions()
        .iter()
        .filter(|p| p.x.abs() < 1e-6 && p.y.abs() < 1e-6)
        .count();
    assert!(on_spine > 0, "render points on the spine");

    // G, move, click: the kept mesh moves like any object.
    let from = user.viewport_center();
    user.move_to(from);
    user.tap(KeyCode::KeyG);
    user.glide_to(from + Vec2::new(80.0, 0.0), 4);
    user.click(from + Vec2::new(80.0, 0.0));
    let moved = user
        .doc()
        .find_by_name("Fin")
        .unwrap()
        .transform
        .translation;
    assert!(moved.length() > 0.1, "moved by G: {moved}");

    // Mesh ▸ Make Manifold: an editable mesh, Tab now opens edit mode.
    let steps = user.undo_steps();
    user.click_on("Mesh");
    // The menu's item (the properties panel has a button of its own).
    let item = user
        .find_all("Make Manifold")
        .into_iter()
        .min_by(|a, b| a.center().y.total_cmp(&b.center().y))
        .expect("Mesh ▸ Make Manifold is shown");
    user.click(Vec2::new(item.center().x, item.center().y));
    let NodeContent::Mesh(mesh) = fin_content(&user) else {
        panic!("Make Manifold gives a mesh: {}", user.status());
    };
    mesh.mesh.validate().unwrap();
    assert_eq!(
        mesh.mesh.face_count(),
        2,
        "the third face on the edge is dropped"
    );
    assert_eq!(
        mesh.subdivision.map(|m| m.viewport_level),
        Some(2),
        "the subdivision stays"
    );
    assert_eq!(user.undo_steps(), steps + 1);
    user.tap(KeyCode::Tab);
    assert_eq!(user.edit_mode().node, Some(id), "{}", user.status());
    user.tap(KeyCode::Tab);

    // Ctrl+Z: kept again, as the file has it.
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    let NodeContent::Kept(kept) = fin_content(&user) else {
        panic!("undo gives the kept mesh back");
    };
    assert_eq!(kept.mesh.faces.len(), 3);
}
