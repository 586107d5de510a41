//! Modeling as a person does it (issue 12, part 1): every edit mode and the
//! modal tools, driven by keys, clicks, drags and the wheel, then checked
//! on the document, the selection, the undo history and the render mesh.
//! These pin today's behaviour before the app side is reshaped.

use crate::user::User;
use bevy::prelude::*;
use hedra_doc::NodeContent;
use hedra_geom::DVec3;

/// A cube (size 2, corners at ±1) in edit mode, in `mode` (1, 2 or 3).
pub(crate) fn cube_in_edit_mode(mode: KeyCode) -> User {
    let mut user = User::new();
    user.add("Cube");
    user.tap(KeyCode::Tab);
    assert!(user.edit_mode().node.is_some(), "Tab enters edit mode");
    user.tap(mode);
    user
}

fn screen(user: &mut User, x: f32, y: f32, z: f32) -> Vec2 {
    user.screen_of(Vec3::new(x, y, z))
}

fn selected_faces(user: &User) -> usize {
    user.edit_mode().selection.faces.len()
}

/// Tab, 3, click the top face, E, move up, click: one region extrude, one
/// undo step, the cap stays selected; Ctrl+Z gives the cube back.
#[test]
fn extrude_the_top_face_and_undo() {
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    let top = screen(&mut user, 0.0, 1.0, 0.0);
    user.click(top);
    assert_eq!(selected_faces(&user), 1, "the click selects the top face");
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyE);
    user.glide_to(top - Vec2::new(0.0, 60.0), 6);
    user.click(top - Vec2::new(0.0, 60.0));
    assert_eq!(user.mesh_counts(), (12, 20, 10), "{}", user.status());
    user.first_mesh().validate().unwrap();
    assert_eq!(user.undo_steps(), steps + 1, "one undo step");
    assert_eq!(selected_faces(&user), 1, "the new cap stays selected");
    let cap = *user.edit_mode().selection.faces.iter().next().unwrap();
    let normal = user.first_mesh().face_normal(cap);
    assert!(
        normal.dot(DVec3::Y) > 0.999 && user.first_mesh().face_centroid(cap).y > 1.05,
        "the selected face is the raised cap"
    );
    let top_y = user
        .first_mesh()
        .positions()
        .iter()
        .map(|p| p.y)
        .fold(f64::MIN, f64::max);
    assert!(top_y > 1.05, "moving up raised the cap to y = {top_y}");
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    assert_eq!(user.mesh_counts(), (8, 12, 6));
}

/// Esc in the middle of a tool leaves the document as it was.
#[test]
fn escape_cancels_every_mesh_tool() {
    for (key, modifiers, kind) in [
        (KeyCode::KeyE, &[][..], KeyCode::Digit3),
        (KeyCode::KeyI, &[][..], KeyCode::Digit3),
        (KeyCode::KeyG, &[][..], KeyCode::Digit3),
        (KeyCode::KeyR, &[][..], KeyCode::Digit3),
        (KeyCode::KeyS, &[][..], KeyCode::Digit3),
        (KeyCode::KeyB, &[KeyCode::ControlLeft][..], KeyCode::Digit2),
    ] {
        let mut user = cube_in_edit_mode(kind);
        let target = if kind == KeyCode::Digit3 {
            screen(&mut user, 0.0, 1.0, 0.0)
        } else {
            screen(&mut user, 0.0, 1.0, 1.0)
        };
        user.click(target);
        let before = user.doc().clone();
        let steps = user.undo_steps();
        user.shortcut(modifiers, key);
        user.glide_to(target + Vec2::new(40.0, -50.0), 5);
        user.tap(KeyCode::Escape);
        assert_eq!(
            user.doc()
                .nodes()
                .map(|n| n.content.mesh().unwrap().positions().to_vec())
                .collect::<Vec<_>>(),
            before
                .nodes()
                .map(|n| n.content.mesh().unwrap().positions().to_vec())
                .collect::<Vec<_>>(),
            "{key:?} then Esc changes nothing"
        );
        assert_eq!(user.mesh_counts(), (8, 12, 6), "{key:?}");
        assert_eq!(user.undo_steps(), steps, "{key:?}: no undo step");
    }
}

/// I on the top face, move, click: an inset ring of four quads.
#[test]
fn inset_the_top_face() {
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    let top = screen(&mut user, 0.0, 1.0, 0.0);
    user.click(top);
    user.tap(KeyCode::KeyI);
    user.glide_to(top + Vec2::new(-30.0, 0.0), 5);
    user.click(top + Vec2::new(-30.0, 0.0));
    assert_eq!(user.mesh_counts(), (12, 20, 10), "{}", user.status());
    user.first_mesh().validate().unwrap();
}

/// Ctrl+R over a vertical edge, the wheel up once for two cuts, click: two
/// loops of four vertices around the sides.
#[test]
fn loop_cut_with_two_cuts_from_the_wheel() {
    let mut user = cube_in_edit_mode(KeyCode::Digit2);
    let side_edge = screen(&mut user, 1.0, 0.0, 1.0);
    user.move_to(side_edge);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyR);
    user.wheel(1.0);
    user.frames(2);
    user.click(side_edge);
    assert_eq!(user.mesh_counts(), (16, 28, 14), "{}", user.status());
    user.first_mesh().validate().unwrap();
}

/// Ctrl+B on the top front edge, width from the mouse, the wheel for a
/// second segment, click.
#[test]
fn bevel_an_edge_with_the_mouse_and_the_wheel() {
    let mut user = cube_in_edit_mode(KeyCode::Digit2);
    let edge = screen(&mut user, 0.0, 1.0, 1.0);
    user.click(edge);
    assert_eq!(user.edit_mode().selection.edges.len(), 1);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyB);
    // The width follows the mouse to the right.
    user.glide_to(edge + Vec2::new(40.0, 0.0), 5);
    let (v1, _, f1) = user_preview_counts(&user);
    user.wheel(1.0);
    user.frames(2);
    let (v2, _, f2) = user_preview_counts(&user);
    assert!(
        v2 > v1 && f2 > f1,
        "the wheel adds a segment: {v1}/{f1} -> {v2}/{f2}"
    );
    user.click(edge + Vec2::new(40.0, 0.0));
    let (v, _, f) = user.mesh_counts();
    assert_eq!(
        (v, f),
        (v2, f2),
        "the click applies what the preview showed"
    );
    user.first_mesh().validate().unwrap();
}

/// Bevel keeps a selection (the bevel face, shown as its edges in edge
/// mode) and Ctrl+Z gives the bevelled edge back selected (issue 31: the
/// selection was cleared and undo left it empty).
#[test]
fn bevel_selects_its_face_and_undo_restores_the_edge() {
    let mut user = cube_in_edit_mode(KeyCode::Digit2);
    let edge = screen(&mut user, 0.0, 1.0, 1.0);
    user.click(edge);
    let picked = user.edit_mode().selection.edges.clone();
    assert_eq!(picked.len(), 1);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyB);
    user.glide_to(edge + Vec2::new(40.0, 0.0), 5);
    user.click(edge + Vec2::new(40.0, 0.0));
    assert_eq!(user.mesh_counts().2, 7, "one bevel face: {}", user.status());
    let selection = &user.edit_mode().selection;
    assert_eq!(selection.faces.len(), 1, "the bevel face is selected");
    assert_eq!(selection.edges.len(), 4, "shown as its four edges");
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    assert_eq!(user.mesh_counts(), (8, 12, 6));
    assert_eq!(
        user.edit_mode().selection.edges,
        picked,
        "undo gives the edge back selected"
    );
}

fn user_preview_counts(user: &User) -> (usize, usize, usize) {
    let m = user
        .edit_mode()
        .preview
        .as_ref()
        .expect("the tool shows a preview");
    (m.vertex_count(), m.edge_count(), m.face_count())
}

/// A box over the whole cube in vertex mode takes the seven corners in
/// sight; with X-ray (Alt+Z) all eight.
#[test]
fn box_select_takes_what_is_in_sight_and_x_ray_takes_all() {
    for (x_ray, expected) in [(false, 7), (true, 8)] {
        let mut user = cube_in_edit_mode(KeyCode::Digit1);
        if x_ray {
            user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyZ);
        }
        user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyA);
        assert!(user.edit_mode().selection.vertices.is_empty());
        let corners: Vec<Vec2> = [-1.0, 1.0]
            .iter()
            .flat_map(|&x| [-1.0, 1.0].map(move |y| (x, y)))
            .flat_map(|(x, y)| [-1.0, 1.0].map(move |z| Vec3::new(x, y, z)))
            .map(|p| user.screen_of(p))
            .collect();
        let lo = corners.iter().fold(Vec2::MAX, |a, &b| a.min(b)) - Vec2::splat(30.0);
        let hi = corners.iter().fold(Vec2::MIN, |a, &b| a.max(b)) + Vec2::splat(30.0);
        user.drag(lo, hi, 8);
        assert_eq!(
            user.edit_mode().selection.vertices.len(),
            expected,
            "X-ray {x_ray}"
        );
    }
}

/// Click a corner, G Z 1 Enter: the corner moves up by exactly 1.
#[test]
fn move_a_vertex_by_a_typed_value() {
    let mut user = cube_in_edit_mode(KeyCode::Digit1);
    let corner = screen(&mut user, 1.0, 1.0, 1.0);
    user.click(corner);
    assert_eq!(user.edit_mode().selection.vertices.len(), 1);
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyG);
    user.glide_to(corner + Vec2::new(25.0, 10.0), 3);
    user.tap(KeyCode::KeyZ);
    user.type_text("1");
    user.tap(KeyCode::Enter);
    assert!(
        user.first_mesh()
            .positions()
            .contains(&DVec3::new(1.0, 1.0, 2.0)),
        "the corner is at (1, 1, 2) exactly: {:?}",
        user.first_mesh().positions()
    );
    assert_eq!(user.undo_steps(), steps + 1);
}

/// Shift+E on a selected edge, drag, click: the edge gets a crease.
#[test]
fn crease_an_edge_with_shift_e() {
    let mut user = cube_in_edit_mode(KeyCode::Digit2);
    let edge = screen(&mut user, 0.0, 1.0, 1.0);
    user.click(edge);
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::KeyE);
    user.glide_to(edge + Vec2::new(150.0, 0.0), 6);
    user.click(edge + Vec2::new(150.0, 0.0));
    let node = user.doc().nodes().next().unwrap();
    let NodeContent::Mesh(m) = &node.content else {
        panic!("a mesh")
    };
    assert_eq!(m.creases.edges.len(), 1, "{}", user.status());
    let crease = *m.creases.edges.values().next().unwrap();
    assert!(crease > 0.0, "crease {crease}");
}

/// Three cubes selected with A, Ctrl+2: each gets a level-2 subdivision
/// modifier in one undo step, and one Ctrl+Z takes all three off.
#[test]
fn ctrl_2_on_three_meshes_is_one_undo_step() {
    let mut user = User::new();
    for _ in 0..3 {
        user.add("Cube");
    }
    user.move_to(user.viewport_center() + Vec2::new(0.0, 150.0));
    user.tap(KeyCode::KeyA);
    let steps = user.undo_steps();
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::Digit2);
    let levels: Vec<Option<u32>> = user
        .doc()
        .nodes()
        .map(|n| match &n.content {
            NodeContent::Mesh(m) => m.subdivision.as_ref().map(|s| s.viewport_level),
            _ => None,
        })
        .collect();
    assert_eq!(levels, [Some(2), Some(2), Some(2)]);
    assert_eq!(user.undo_steps(), steps + 1);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    assert!(user.doc().nodes().all(|n| match &n.content {
        NodeContent::Mesh(m) => m.subdivision.is_none(),
        _ => false,
    }));
}

/// Object mode: G X 2 Enter moves the cube by exactly 2 in f64, R Z 90
/// Enter turns it a quarter, each one undo step.
#[test]
fn move_and_rotate_an_object_by_typed_values() {
    let mut user = User::new();
    user.add("Cube");
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyG);
    user.glide_to(user.viewport_center() + Vec2::new(37.0, 11.0), 3);
    user.tap(KeyCode::KeyX);
    user.type_text("2");
    user.tap(KeyCode::Enter);
    let t = user.doc().nodes().next().unwrap().transform;
    assert_eq!(t.translation, DVec3::new(2.0, 0.0, 0.0), "exact in f64");
    assert_eq!(user.undo_steps(), steps + 1);
    user.tap(KeyCode::KeyR);
    user.tap(KeyCode::KeyZ);
    user.type_text("90");
    user.tap(KeyCode::Enter);
    let t = user.doc().nodes().next().unwrap().transform;
    let x_axis = t.rotation * DVec3::X;
    assert!(
        (x_axis - DVec3::Y).length() < 1e-12,
        "x turned onto y: {x_axis}"
    );
    assert_eq!(user.undo_steps(), steps + 2);
}

/// Shift+D duplicates and moves; a click places the copy.
#[test]
fn duplicate_and_place_with_shift_d() {
    let mut user = User::new();
    user.add("Cube");
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::KeyD);
    user.tap(KeyCode::KeyX);
    user.type_text("3");
    user.tap(KeyCode::Enter);
    let xs: Vec<f64> = user
        .doc()
        .nodes()
        .map(|n| n.transform.translation.x)
        .collect();
    assert_eq!(xs, [0.0, 3.0], "{}", user.status());
}

/// X deletes the selected object, Ctrl+Z brings it back, Ctrl+Shift+Z
/// deletes it again.
#[test]
fn delete_undo_and_redo_with_keys() {
    let mut user = User::new();
    user.add("Cube");
    user.tap(KeyCode::KeyX);
    assert!(user.doc().nodes().next().is_none(), "{}", user.status());
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    assert_eq!(user.node_names(), ["Cube"]);
    user.shortcut(&[KeyCode::ControlLeft, KeyCode::ShiftLeft], KeyCode::KeyZ);
    assert!(user.doc().nodes().next().is_none());
}

/// H hides the selected object, Alt+H shows it again.
#[test]
fn hide_and_unhide() {
    let mut user = User::new();
    user.add("Cube");
    user.tap(KeyCode::KeyH);
    assert!(!user.doc().nodes().next().unwrap().visible);
    user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyH);
    assert!(user.doc().nodes().next().unwrap().visible);
}

/// Face mode: X deletes the clicked face, leaving an open box.
#[test]
fn delete_a_face_in_face_mode() {
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    let top = screen(&mut user, 0.0, 1.0, 0.0);
    user.click(top);
    user.tap(KeyCode::KeyX);
    assert_eq!(user.mesh_counts(), (8, 12, 5), "{}", user.status());
    user.first_mesh().validate().unwrap();
}

/// Alt+click on an edge of a loop-cut cube selects the loop: the four new
/// edges around the middle (a loop stops at the cube's valence-3 corners).
#[test]
fn alt_click_selects_an_edge_loop() {
    let mut user = cube_in_edit_mode(KeyCode::Digit2);
    let side_edge = screen(&mut user, 1.0, 0.0, 1.0);
    user.move_to(side_edge);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyR);
    user.click(side_edge);
    assert_eq!(user.mesh_counts(), (12, 20, 10));
    user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyA);
    let edge = screen(&mut user, 1.0, 0.0, 0.0);
    user.key_down(KeyCode::AltLeft);
    user.click(edge);
    user.key_up(KeyCode::AltLeft);
    assert_eq!(user.edit_mode().selection.edges.len(), 4);
}

/// A and Alt+A in face mode, and 1/2/3 switch what a click selects.
#[test]
fn select_all_none_and_element_modes() {
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    user.tap(KeyCode::KeyA);
    assert_eq!(selected_faces(&user), 6);
    user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyA);
    assert_eq!(selected_faces(&user), 0);
    user.tap(KeyCode::Digit1);
    let corner = screen(&mut user, 1.0, 1.0, 1.0);
    user.click(corner);
    assert_eq!(user.edit_mode().selection.vertices.len(), 1);
    user.tap(KeyCode::Tab);
    assert!(user.edit_mode().node.is_none(), "Tab leaves edit mode");
}

/// A NURBS surface: Tab, click a control point, W, drag right, click: its
/// weight grows and the surface moves toward it.
#[test]
fn a_weight_drag_pulls_a_nurbs_surface_toward_its_point() {
    let (mut user, target, at) = surface_with_its_middle_point_clicked();
    let (points, weights) = shape_points(&user);
    let selected = user
        .app
        .world()
        .resource::<hedra_edit::ShapeEdit>()
        .selected
        .clone();
    assert_eq!(selected.into_iter().collect::<Vec<_>>(), [target as u32]);
    let before = surface_point_near(&user, points[target]);
    user.tap(KeyCode::KeyW);
    user.glide_to(at + Vec2::new(120.0, 0.0), 6);
    // While dragging, the point's entity carries the previewed weight (the
    // viewport's dot and label read it); the document waits.
    let shown = user.control_point_entities();
    assert!(
        shown[target].weight > weights[target],
        "{:?}",
        shown[target]
    );
    assert_eq!(shape_points(&user).1[target], weights[target]);
    user.click(at + Vec2::new(120.0, 0.0));
    let (_, after_weights) = shape_points(&user);
    assert!(
        after_weights[target] > weights[target],
        "weight {} -> {}",
        weights[target],
        after_weights[target]
    );
    let after = surface_point_near(&user, points[target]);
    assert!(
        after.distance(points[target]) < before.distance(points[target]),
        "the surface came closer to its point: {before} -> {after}"
    );
}

/// Add ▸ NURBS Surface, Tab into control-point mode and a click on the
/// control point nearest the origin (an inner point of the net). Returns
/// the user, the point's index and where it was clicked.
fn surface_with_its_middle_point_clicked() -> (User, usize, Vec2) {
    let mut user = User::new();
    user.add("NURBS Surface");
    user.tap(KeyCode::Tab);
    let (points, _) = shape_points(&user);
    let target = (0..points.len())
        .min_by(|&a, &b| points[a].length().total_cmp(&points[b].length()))
        .unwrap();
    let at = user.screen_of(points[target].as_vec3());
    user.click(at);
    (user, target, at)
}

fn shape_points(user: &User) -> (Vec<DVec3>, Vec<f64>) {
    let node = user.doc().nodes().next().unwrap();
    (
        hedra_edit::shape_mode::control_points(&node.content),
        hedra_edit::shape_mode::control_weights(&node.content).unwrap(),
    )
}

/// The point of the surface's render mesh nearest to `p`.
fn surface_point_near(user: &User, p: DVec3) -> DVec3 {
    user.render_positions()
        .into_iter()
        .map(Vec3::as_dvec3)
        .min_by(|a, b| a.distance(p).total_cmp(&b.distance(p)))
        .unwrap()
}

/// The frame that confirms a tool already shows the result: the render
/// mesh of that very frame has the extruded vertices.
#[test]
fn the_confirming_frame_shows_the_result() {
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    let top = screen(&mut user, 0.0, 1.0, 0.0);
    user.click(top);
    user.tap(KeyCode::KeyE);
    user.glide_to(top - Vec2::new(0.0, 60.0), 6);
    user.move_to(top - Vec2::new(0.0, 60.0));
    // The release frame after the press confirms; look at each frame.
    user.button_down(MouseButton::Left);
    assert_eq!(user.mesh_counts(), (12, 20, 10), "the press confirms");
    let positions = user.render_positions();
    let top_y = positions.iter().map(|p| p.y).fold(f32::MIN, f32::max);
    assert!(
        top_y > 1.05,
        "the render mesh of the confirming frame shows the raised cap (top y = {top_y})"
    );
}

/// Ctrl+5 then Page Up twice stops at the viewport's highest level; Page
/// Down steps back.
#[test]
fn page_up_stops_at_the_highest_viewport_level() {
    let mut user = User::new();
    user.add("Cube");
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::Digit5);
    user.tap(KeyCode::PageUp);
    user.tap(KeyCode::PageUp);
    let level = |user: &User| match &user.doc().nodes().next().unwrap().content {
        NodeContent::Mesh(m) => m.subdivision.map(|s| s.viewport_level),
        _ => None,
    };
    assert_eq!(
        level(&user),
        Some(hedra_geom::subdivision::MAX_VIEWPORT_LEVEL)
    );
    user.tap(KeyCode::PageDown);
    assert_eq!(
        level(&user),
        Some(hedra_geom::subdivision::MAX_VIEWPORT_LEVEL - 1)
    );
}

/// Control-point mode shares the modal keys: G Z 1 Enter moves the clicked
/// point by exactly 1 along z; G then Esc leaves it where it was.
#[test]
fn move_a_control_point_by_a_typed_value_and_cancel() {
    let (mut user, target, at) = surface_with_its_middle_point_clicked();
    let (points, _) = shape_points(&user);
    user.tap(KeyCode::KeyG);
    user.glide_to(at + Vec2::new(30.0, 5.0), 3);
    user.tap(KeyCode::KeyZ);
    user.type_text("1");
    user.tap(KeyCode::Enter);
    let (moved, _) = shape_points(&user);
    assert_eq!(
        moved[target],
        points[target] + DVec3::Z,
        "{}",
        user.status()
    );
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyG);
    user.glide_to(at + Vec2::new(60.0, 40.0), 4);
    user.tap(KeyCode::Escape);
    assert_eq!(shape_points(&user).0, moved, "Esc leaves the points");
    assert_eq!(user.undo_steps(), steps);
}

/// Numpad 5 switches to a parallel projection and back; picking follows
/// (a click on the cube's top face still selects it).
#[test]
fn numpad_5_toggles_orthographic_and_picking_follows() {
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    let projection = |user: &mut User| {
        let world = user.app.world_mut();
        let mut q = world.query_filtered::<&Projection, With<hedra_scene::ViewportCamera>>();
        matches!(q.single(world).unwrap(), Projection::Orthographic(_))
    };
    assert!(!projection(&mut user));
    user.tap(KeyCode::Numpad5);
    assert!(projection(&mut user), "orthographic");
    assert!(user.status().contains("orthographic"), "{}", user.status());
    let top = screen(&mut user, 0.0, 1.0, 0.0);
    user.click(top);
    assert_eq!(selected_faces(&user), 1, "the click selects the top face");
    let face = *user.edit_mode().selection.faces.iter().next().unwrap();
    assert!(user.first_mesh().face_normal(face).y > 0.99, "the top face");
    user.tap(KeyCode::Numpad5);
    assert!(!projection(&mut user), "perspective again");
}

/// Ctrl+T on the cube's top face: two triangles, one undo step; the Mesh
/// menu offers the same.
#[test]
fn ctrl_t_triangulates_the_selected_faces() {
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    let top = screen(&mut user, 0.0, 1.0, 0.0);
    user.click(top);
    let steps = user.undo_steps();
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyT);
    assert_eq!(user.mesh_counts(), (8, 13, 7), "{}", user.status());
    user.first_mesh().validate().unwrap();
    assert_eq!(user.undo_steps(), steps + 1);
    // Ctrl+T uses Beauty; Adjust Last offers the other methods.
    assert!(user.shows("Beauty"), "Adjust Last shows the method");
    let last = user.doc_last_command();
    assert!(
        matches!(
            last,
            Some(hedra_doc::Command::Triangulate {
                method: hedra_geom::modeling::TriangulateMethod::Beauty,
                ..
            })
        ),
        "{last:?}"
    );
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    assert_eq!(user.mesh_counts(), (8, 12, 6));
}

/// Alt+J after Ctrl+T on every face: the triangles join back into the
/// cube's six quads, one undo step; with nothing selected the status says
/// what to do and the history does not move.
#[test]
fn alt_j_joins_the_selected_triangles_into_quads() {
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    user.tap(KeyCode::KeyA);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyT);
    assert_eq!(user.mesh_counts(), (8, 18, 12), "{}", user.status());
    user.tap(KeyCode::KeyA);
    let steps = user.undo_steps();
    user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyJ);
    assert_eq!(user.mesh_counts(), (8, 12, 6), "{}", user.status());
    let mesh = user.first_mesh();
    mesh.validate().unwrap();
    assert!(mesh.faces().all(|f| mesh.face_degree(f) == 4));
    assert_eq!(user.undo_steps(), steps + 1);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    assert_eq!(user.mesh_counts(), (8, 18, 12));
    user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyA);
    user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyJ);
    assert!(
        user.status().contains("Tris to Quads: select faces"),
        "{}",
        user.status()
    );
    assert_eq!(user.undo_steps(), steps);
}

/// Mesh ▸ Bisect, then a horizontal drag through the cube's middle in the
/// front view: the plane y = 0 cuts it (12/20/10, one undo step); with
/// Shift held at the release the part right of the line (below it) goes
/// and the cut is filled: the closed upper half (8/12/6). Esc cancels.
#[test]
fn bisect_cuts_along_a_dragged_line() {
    let (mut user, left, right) = cube_in_front_view_all_faces();
    let steps = user.undo_steps();
    open_mesh_menu(&mut user);
    user.click_on("Bisect (drag a line)");
    assert!(
        user.status().contains("Bisect: drag a line"),
        "{}",
        user.status()
    );
    user.drag(left, right, 6);
    assert_eq!(user.mesh_counts(), (12, 20, 10), "{}", user.status());
    let mesh = user.first_mesh();
    mesh.validate().unwrap();
    let cut: Vec<_> = mesh
        .vertices()
        .filter(|&v| mesh.position(v).y.abs() < 1e-9)
        .collect();
    assert_eq!(cut.len(), 4, "the new vertices lie on y = 0");
    assert_eq!(user.undo_steps(), steps + 1);
    assert!(!user.edit_mode().selection.faces.is_empty());

    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    user.tap(KeyCode::KeyA);
    open_mesh_menu(&mut user);
    user.click_on("Bisect (drag a line)");
    user.key_down(KeyCode::ShiftLeft);
    user.drag(left, right, 6);
    user.key_up(KeyCode::ShiftLeft);
    assert_eq!(user.mesh_counts(), (8, 12, 6), "{}", user.status());
    let mesh = user.first_mesh();
    mesh.validate().unwrap();
    assert!(mesh.stats().closed);
    assert!(
        mesh.vertices().all(|v| mesh.position(v).y >= -1e-9),
        "the upper half is kept"
    );

    // Esc before the drag: nothing is cut, and clicks select again.
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    open_mesh_menu(&mut user);
    user.click_on("Bisect (drag a line)");
    user.tap(KeyCode::Escape);
    assert!(
        user.status().contains("\"Bisect cancelled\""),
        "{}",
        user.status()
    );
    let steps = user.undo_steps();
    user.drag(left, right, 6);
    assert_eq!(user.undo_steps(), steps);
    assert_eq!(user.mesh_counts(), (8, 12, 6));
}

/// Face mode, Mesh ▸ Loop Cut (it was greyed out there though Ctrl+R
/// works): the tool starts on an edge of the selected face, follows the
/// pointer onto a side edge, and a click cuts the ring around the sides.
#[test]
fn the_mesh_menus_loop_cut_works_in_face_mode() {
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    let top = screen(&mut user, 0.0, 1.0, 0.0);
    user.click(top);
    assert_eq!(selected_faces(&user), 1);
    open_mesh_menu(&mut user);
    let item = user
        .widgets()
        .iter()
        .find(|w| w.text.starts_with("Loop Cut\t"))
        .map(|w| Vec2::new(w.rect.center().x, w.rect.center().y))
        .expect("Mesh ▸ Loop Cut is shown");
    user.click(item);
    assert!(
        user.edit_mode().tool.is_some(),
        "the loop cut runs: {}",
        user.status()
    );
    let side_edge = screen(&mut user, 1.0, 0.0, 1.0);
    user.glide_to(side_edge, 4);
    user.click(side_edge);
    assert_eq!(user.mesh_counts(), (12, 20, 10), "{}", user.status());
    user.first_mesh().validate().unwrap();
}

/// Opens the menu bar's Mesh menu (the properties panel has a Mesh button too).
fn open_mesh_menu(user: &mut User) {
    open_menu(user, "Mesh");
}

/// Opens the menu bar's menu `name` (the topmost widget with that text).
fn open_menu(user: &mut User, name: &str) {
    let bar = user
        .find_all(name)
        .into_iter()
        .min_by(|a, b| a.min.y.total_cmp(&b.min.y));
    let bar = bar.unwrap_or_else(|| panic!("a {name} menu"));
    user.click(Vec2::new(bar.center().x, bar.center().y));
}

/// After a plain bisect the Adjust Last panel offers Blender's options:
/// ticking Fill with the outer side cleared gives the closed upper half
/// without redoing the drag, still one undo step.
#[test]
fn adjust_last_bisect_clears_a_side_and_fills() {
    let (mut user, left, right) = cube_in_front_view_all_faces();
    let steps = user.undo_steps();
    open_mesh_menu(&mut user);
    user.click_on("Bisect (drag a line)");
    user.drag(left, right, 6);
    assert_eq!(user.mesh_counts(), (12, 20, 10), "{}", user.status());
    assert!(user.shows("Adjust Last: Bisect"));
    user.click_on("Neither side");
    user.click_on("Outer (right of the line)");
    user.click_on("Fill");
    assert_eq!(user.mesh_counts(), (8, 12, 6), "{}", user.status());
    let mesh = user.first_mesh();
    assert!(mesh.stats().closed);
    assert!(mesh.vertices().all(|v| mesh.position(v).y >= -1e-9));
    assert_eq!(user.undo_steps(), steps + 1, "adjusting replaces the step");
}

/// Shift+Tab turns increment snapping on: a G drag of the cube lands on
/// whole grid steps; with snapping off, Ctrl held during the drag snaps
/// too, and a plain drag does not. In edit mode the selected face moves by
/// whole steps as well, so its corners stay on integer coordinates.
#[test]
fn shift_tab_snaps_moves_to_whole_grid_steps() {
    let whole = |v: DVec3| v.to_array().iter().all(|c| c.fract() == 0.0);
    let drag_with_g = |user: &mut User, by: Vec2, ctrl: bool| {
        let start = user.viewport_center();
        user.move_to(start);
        user.tap(KeyCode::KeyG);
        if ctrl {
            user.key_down(KeyCode::ControlLeft);
        }
        user.glide_to(start + by, 5);
        user.click(start + by);
        if ctrl {
            user.key_up(KeyCode::ControlLeft);
        }
    };
    let translation = |user: &User| user.doc().nodes().next().unwrap().transform.translation;

    let mut user = User::new();
    user.add("Cube");
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::Tab);
    assert!(user.app.world().resource::<hedra_edit::Snapping>().enabled);
    assert_eq!(user.edit_mode().node, None, "Shift+Tab is not Tab");
    drag_with_g(&mut user, Vec2::new(137.0, -23.0), false);
    let t = translation(&user);
    assert!(t != DVec3::ZERO && whole(t), "{t}");

    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::Tab);
    let before = translation(&user);
    drag_with_g(&mut user, Vec2::new(-91.0, 57.0), true);
    let t = translation(&user);
    assert!(
        t != before && whole(t),
        "Ctrl snaps while snapping is off: {t}"
    );
    drag_with_g(&mut user, Vec2::new(43.0, 29.0), false);
    assert!(!whole(translation(&user)), "a plain drag is free");

    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    let top = user.screen_of(Vec3::Y);
    user.click(top);
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::Tab);
    drag_with_g(&mut user, Vec2::new(120.0, -70.0), false);
    let mesh = user.first_mesh();
    assert!(mesh.vertices().all(|v| whole(mesh.position(v))));
    assert!(
        mesh.vertices()
            .any(|v| mesh.position(v).y > 1.0 || mesh.position(v).x.abs() > 1.0)
    );
}

/// Snap to Vertex (View menu) with snapping on: G on one corner of the cube
/// and the pointer near another puts the first exactly on the second; the
/// target is published for the viewport to draw while the move runs.
#[test]
fn vertex_snapping_puts_a_vertex_exactly_on_another() {
    let mut user = cube_in_edit_mode(KeyCode::Digit1);
    let (from, onto) = (DVec3::new(1.0, 1.0, 1.0), DVec3::new(-1.0, 1.0, 1.0));
    let corner = user.screen_of(from.as_vec3());
    user.click(corner);
    let moved = user
        .edit_mode()
        .selection
        .vertices
        .iter()
        .next()
        .copied()
        .unwrap();
    assert_eq!(user.first_mesh().position(moved), from);
    choose_snap_element(&mut user, "Vertex");
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::Tab);
    user.move_to(corner);
    user.tap(KeyCode::KeyG);
    let near = user.screen_of(onto.as_vec3()) + Vec2::new(6.0, -5.0);
    user.glide_to(near, 5);
    let target = user.app.world().resource::<hedra_edit::SnapTarget>().0;
    assert_eq!(target, Some(onto), "the target is drawn");
    user.click(near);
    assert_eq!(
        user.first_mesh().position(moved),
        onto,
        "exactly on the other corner"
    );
    assert_eq!(
        user.app.world().resource::<hedra_edit::SnapTarget>().0,
        None
    );
}

/// With snapping on, R turns the object in whole 5° steps and S scales it
/// in steps of 0.1 (object mode).
#[test]
fn snapping_rotates_in_5_degree_and_scales_in_tenth_steps() {
    let mut user = User::new();
    user.add("Cube");
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::Tab);
    let center = user.viewport_center();
    let steps_of = |x: f64, step: f64| ((x / step) - (x / step).round()).abs() < 1e-9;

    user.move_to(center + Vec2::new(80.0, 0.0));
    user.tap(KeyCode::KeyR);
    user.glide_to(center + Vec2::new(50.0, -67.0), 5);
    user.click(center + Vec2::new(50.0, -67.0));
    let rotation = user.doc().nodes().next().unwrap().transform.rotation;
    let degrees = rotation.to_axis_angle().1.to_degrees();
    assert!(degrees > 1.0 && steps_of(degrees, 5.0), "{degrees}°");

    user.move_to(center + Vec2::new(80.0, 0.0));
    user.tap(KeyCode::KeyS);
    user.glide_to(center + Vec2::new(117.0, 9.0), 5);
    user.click(center + Vec2::new(117.0, 9.0));
    let scale = user.doc().nodes().next().unwrap().transform.scale;
    assert!(scale.x > 1.05 && steps_of(scale.x, 0.1), "{scale}");
    assert_eq!(scale.x, scale.y);
}

/// The cube in face edit mode, seen from the front (Numpad 1) with every
/// face selected, and the screen points of (-2, 0, 0) and (2, 0, 0): a
/// horizontal line through its middle.
fn cube_in_front_view_all_faces() -> (User, Vec2, Vec2) {
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    user.tap(KeyCode::Numpad1);
    user.tap(KeyCode::KeyA);
    let left = user.screen_of(Vec3::new(-2.0, 0.0, 0.0));
    let right = user.screen_of(Vec3::new(2.0, 0.0, 0.0));
    (user, left, right)
}

/// O turns proportional editing on; G Y 1 on the middle vertex of a grid
/// lifts every vertex within the radius by Blender's smooth falloff of its
/// distance, after one wheel notch grew the radius from 1 to 1.1; the
/// influence circle is published while the move runs.
#[test]
fn proportional_move_lifts_neighbours_by_the_smooth_falloff() {
    let mut user = User::new();
    user.add("Grid");
    user.tap(KeyCode::Tab);
    user.tap(KeyCode::Digit1);
    let middle = user.screen_of(Vec3::ZERO);
    user.click(middle);
    let picked = *user.edit_mode().selection.vertices.iter().next().unwrap();
    assert_eq!(user.first_mesh().position(picked), DVec3::ZERO);
    let before: Vec<DVec3> = user.first_mesh().positions().to_vec();
    user.tap(KeyCode::KeyO);
    assert!(
        user.status().contains("Proportional editing on"),
        "{}",
        user.status()
    );
    user.move_to(middle + Vec2::new(0.0, 40.0));
    user.tap(KeyCode::KeyG);
    user.wheel(1.0);
    user.frame();
    let ring = user
        .app
        .world()
        .resource::<hedra_edit::ProportionalRing>()
        .0;
    let (center, radius) = ring.expect("the circle is drawn during the move");
    assert!(
        center.length() < 1e-9 && (radius - 1.1).abs() < 1e-9,
        "{ring:?}"
    );
    user.tap(KeyCode::KeyY);
    user.type_text("1");
    user.tap(KeyCode::Enter);
    assert!(
        user.app
            .world()
            .resource::<hedra_edit::ProportionalRing>()
            .0
            .is_none()
    );
    let mesh = user.first_mesh();
    let mut lifted = 0;
    for v in mesh.vertices() {
        let was = before[v.index()];
        let d = DVec3::new(was.x, 0.0, was.z).length();
        let t = (1.0 - d / 1.1).max(0.0);
        let expected = if v == picked {
            1.0
        } else {
            3.0 * t * t - 2.0 * t * t * t
        };
        let now = mesh.position(v);
        assert!(
            (now.y - expected).abs() < 1e-9 && now.x == was.x && now.z == was.z,
            "vertex at ({:.1}, {:.1}) rose to {} (expected {expected})",
            was.x,
            was.z,
            now.y
        );
        lifted += (now.y > 0.0) as usize;
    }
    // Grid points within 1.1 of the middle, 0.2 apart: more than the cross.
    assert!(
        lifted > 20 && lifted < mesh.vertex_count(),
        "{lifted} lifted"
    );
    mesh.validate().unwrap();
}

/// The open half of a cube (x ≥ 0, its seam on x = 0), named "Cube".
fn half_cube() -> User {
    let mut user = User::new();
    user.add("Cube");
    user.app
        .world_mut()
        .write_message(hedra_scene::DocRequest::Execute(
            hedra_doc::Command::Bisect {
                node: hedra_doc::NodeRef::Name("Cube".into()),
                faces: hedra_doc::FaceSet::All,
                point: DVec3::ZERO,
                normal: DVec3::X,
                clear: hedra_geom::modeling::BisectClear::Inner,
                fill: false,
            },
        ));
    user.frames(2);
    assert_eq!(user.mesh_counts(), (8, 12, 5), "{}", user.status());
    user
}

fn mesh_content(user: &User) -> hedra_doc::MeshContent {
    match &user.doc().nodes().next().unwrap().content {
        NodeContent::Mesh(c) => c.clone(),
        _ => panic!("a mesh"),
    }
}

/// Properties ▸ Modifiers ▸ Mirror on a half cube: the viewport draws the
/// welded whole (both halves), the cage stays the half; with Clipping on,
/// a seam vertex dragged with G stays on x = 0 while it moves up.
#[test]
fn mirror_modifier_draws_both_halves_and_clipping_holds_the_seam() {
    let mut user = half_cube();
    user.click_on("Mirror");
    let content = mesh_content(&user);
    assert_eq!(content.modifiers.len(), 1, "{}", user.status());
    let drawn = user.render_positions();
    assert!(
        drawn.iter().any(|p| p.x < -0.9) && drawn.iter().any(|p| p.x > 0.9),
        "both halves are drawn"
    );
    let whole = content.evaluated(0).unwrap();
    assert_eq!(
        (whole.vertex_count(), whole.edge_count(), whole.face_count()),
        (12, 20, 10),
        "one closed box of two halves (the seam welded)"
    );
    assert_eq!(user.mesh_counts(), (8, 12, 5), "the cage stays the half");
    user.click_on("Clipping");
    assert!(matches!(
        mesh_content(&user).modifiers[0],
        hedra_doc::MeshModifier::Mirror(m) if m.clipping
    ));
    user.tap(KeyCode::Tab);
    user.tap(KeyCode::Digit1);
    let seam = Vec3::new(0.0, 1.0, 1.0);
    let at = user.screen_of(seam);
    user.click(at);
    let picked = *user.edit_mode().selection.vertices.iter().next().unwrap();
    assert_eq!(user.first_mesh().position(picked), seam.as_dvec3());
    user.move_to(at);
    user.tap(KeyCode::KeyG);
    let to = at + Vec2::new(50.0, -40.0);
    user.glide_to(to, 5);
    user.click(to);
    let moved = user.first_mesh().position(picked);
    assert_eq!(
        moved.x, 0.0,
        "clipping keeps the seam vertex on x = 0: {moved}"
    );
    assert!(moved.y > 1.05, "it moved up: {moved}");
    user.first_mesh().validate().unwrap();
}

/// A click on the mirrored half selects the object, as on the half that
/// is the cage: picking hits what is drawn.
#[test]
fn a_click_on_the_mirrored_half_selects_the_object() {
    let mut user = half_cube();
    user.click_on("Mirror");
    user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyA);
    let selection = |user: &User| {
        user.app
            .world()
            .resource::<hedra_edit::Selection>()
            .nodes
            .len()
    };
    assert_eq!(selection(&user), 0);
    let mirrored_top = user.screen_of(Vec3::new(-0.5, 1.0, 0.5));
    user.click(mirrored_top);
    assert_eq!(selection(&user), 1, "{}", user.status());
}

/// Properties ▸ Modifiers ▸ Array with Merge on a cube without its ±X
/// faces, count 3: the evaluated mesh is one open tube of 16/28/12 and
/// the viewport draws three cubes' length.
#[test]
fn array_modifier_with_merge_makes_one_tube() {
    let mut user = User::new();
    user.add("Cube");
    for x in [1.0, -1.0] {
        user.app
            .world_mut()
            .write_message(hedra_scene::DocRequest::Execute(
                hedra_doc::Command::DeleteFaces {
                    node: hedra_doc::NodeRef::Name("Cube".into()),
                    faces: hedra_doc::FaceSet::Facing {
                        direction: DVec3::new(x, 0.0, 0.0),
                        degrees: 1.0,
                    },
                },
            ));
        user.frames(2);
    }
    assert_eq!(user.mesh_counts(), (8, 12, 4));
    user.click_on("Array");
    let steps = user.undo_steps();
    // Count 2 → 3 (the first drag value is the count), then Merge.
    let count = user.find("2");
    user.click(count);
    user.type_text("3");
    user.tap(KeyCode::Enter);
    user.frames(2);
    user.click_on("Merge");
    let content = mesh_content(&user);
    let hedra_doc::MeshModifier::Array(a) = content.modifiers[0] else {
        panic!("an array")
    };
    assert_eq!((a.count, a.merge), (3, true), "{}", user.status());
    assert!(user.undo_steps() > steps);
    let tube = content.evaluated(0).unwrap();
    tube.validate().unwrap();
    assert_eq!(
        (tube.vertex_count(), tube.edge_count(), tube.face_count()),
        (16, 28, 12)
    );
    let s = tube.stats();
    assert_eq!((s.shells, s.boundary_loops), (1, 2));
    let drawn = user.render_positions();
    let right = drawn.iter().map(|p| p.x).fold(f32::MIN, f32::max);
    assert!((right - 5.0).abs() < 1e-5, "three cubes' length: {right}");
}

/// Mesh ▸ Spin on a plane seen from the front with the 3D cursor at
/// (2, 0, 0): a quarter turn in 9 steps (Blender's defaults), then Adjust
/// Last to 360° in 8 steps gives the closed torus of genus 1 (32/64/32).
#[test]
fn spin_a_square_a_full_turn_into_a_torus() {
    let mut user = User::new();
    user.add("Plane");
    user.app
        .world_mut()
        .resource_mut::<hedra_scene::Cursor3d>()
        .0 = DVec3::new(2.0, 0.0, 0.0);
    user.tap(KeyCode::Numpad1);
    user.tap(KeyCode::Tab);
    user.tap(KeyCode::Digit3);
    user.tap(KeyCode::KeyA);
    open_mesh_menu(&mut user);
    user.click_on("Spin (about the cursor, view axis)");
    assert_eq!(user.mesh_counts(), (40, 76, 38), "{}", user.status());
    user.first_mesh().validate().unwrap();
    let steps = user.undo_steps();
    for (from, to) in [("90", "360"), ("9", "8")] {
        user.click_on(from);
        user.type_text(to);
        user.tap(KeyCode::Enter);
        user.frames(2);
    }
    assert_eq!(user.undo_steps(), steps, "Adjust Last replaces the step");
    let torus = user.first_mesh();
    torus.validate().unwrap();
    let s = torus.stats();
    assert_eq!(
        (s.vertices, s.edges, s.faces),
        (32, 64, 32),
        "{}",
        user.status()
    );
    assert_eq!((s.closed, s.genus), (true, Some(1)));
    // The plane (side 2) reaches 1 and 3 from the axis through the cursor along z.
    for p in torus.vertices().map(|v| torus.position(v)) {
        let r = (p.truncate() - hedra_geom::DVec2::new(2.0, 0.0)).length();
        assert!((r - 1.0).abs() < 1e-9 || (r - 3.0).abs() < 1e-9, "{p}");
    }
}

/// K, click near the middles of the front face's top and bottom edges
/// (they snap there), a stray third click taken back with Backspace,
/// Enter: the front face is cut in two (8/12/6 → 10/15/7), the back face
/// is not, the cut edge is selected, one undo step.
#[test]
fn knife_across_the_front_face_of_a_cube() {
    let mut user = cube_in_edit_mode(KeyCode::Digit1);
    user.tap(KeyCode::Numpad1);
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyK);
    assert!(user.status().contains("Knife"), "{}", user.status());
    let top = user.screen_of(Vec3::new(0.0, 1.0, 1.0)) + Vec2::new(3.0, 4.0);
    let bottom = user.screen_of(Vec3::new(0.0, -1.0, 1.0)) + Vec2::new(-2.0, -4.0);
    user.click(top);
    user.click(bottom);
    let stray = user.screen_of(Vec3::new(0.5, 0.0, 1.0));
    user.click(stray);
    assert_eq!(
        user.app
            .world()
            .resource::<hedra_edit::KnifeTool>()
            .points
            .len(),
        3
    );
    user.tap(KeyCode::Backspace);
    user.tap(KeyCode::Enter);
    user.frames(2);
    assert_eq!(user.mesh_counts(), (10, 15, 7), "{}", user.status());
    let mesh = user.first_mesh();
    mesh.validate().unwrap();
    assert_eq!(user.undo_steps(), steps + 1);
    let front = mesh
        .faces()
        .filter(|&f| mesh.face_normal(f).z > 0.999)
        .count();
    let back = mesh
        .faces()
        .filter(|&f| mesh.face_normal(f).z < -0.999)
        .count();
    assert_eq!((front, back), (2, 1), "only the front face is cut");
    let selected: Vec<_> = user.edit_mode().selection.edges.iter().copied().collect();
    assert_eq!(selected.len(), 1, "the cut edge is selected");
    let [a, b] = mesh.edge_vertices(selected[0]).map(|v| mesh.position(v));
    let mut ends = [a, b];
    ends.sort_by(|p, q| p.y.total_cmp(&q.y));
    assert_eq!(
        ends,
        [DVec3::new(0.0, -1.0, 1.0), DVec3::new(0.0, 1.0, 1.0)]
    );
    assert!(!user.app.world().resource::<hedra_edit::KnifeTool>().active);
}

/// Two edges in the middle of a grid (top view), V, drag, click: the grid
/// is slit along them (the middle vertex doubled, the two edges doubled,
/// their ends shared), one copy of the middle vertex follows the pointer
/// and the other stays; one valid mesh.
#[test]
fn rip_two_edges_of_a_grid_and_pull_one_side() {
    let mut user = User::new();
    user.add("Grid");
    user.tap(KeyCode::Tab);
    user.tap(KeyCode::Digit2);
    user.tap(KeyCode::Numpad7);
    let (v0, e0, f0) = user.mesh_counts();
    // A box around the two edges (a second click would land on the
    // gizmo the first selection shows).
    let corner = user.screen_of(Vec3::new(-0.25, 0.0, -0.05));
    let opposite = user.screen_of(Vec3::new(0.25, 0.0, 0.05));
    user.drag(corner, opposite, 6);
    assert_eq!(user.edit_mode().selection.edges.len(), 2);
    let beside = user.screen_of(Vec3::new(0.0, 0.0, 0.1));
    user.move_to(beside);
    user.tap(KeyCode::KeyV);
    user.frames(2);
    assert_eq!(
        user.mesh_counts(),
        (v0 + 1, e0 + 2, f0),
        "{}",
        user.status()
    );
    let pulled = user.screen_of(Vec3::new(0.0, 0.0, 0.3));
    user.glide_to(pulled, 5);
    user.click(pulled);
    let mesh = user.first_mesh();
    mesh.validate().unwrap();
    assert_eq!(user.mesh_counts(), (v0 + 1, e0 + 2, f0));
    let middle: Vec<DVec3> = mesh
        .vertices()
        .map(|v| mesh.position(v))
        .filter(|p| p.x.abs() < 1e-9 && p.z.abs() < 0.5 && p.y == 0.0)
        .collect();
    assert!(
        middle.iter().any(|p| p.z == 0.0) && middle.iter().any(|p| p.z > 0.1),
        "one copy stays, the other was pulled toward +z: {middle:?}"
    );
    assert_eq!(mesh.boundary_loops().len(), 2, "the outline and the slit");
}

/// Alt+V splits the grid's middle vertex (seed 004's vertex split): the new
/// vertex follows the pointer and takes the edge on its side, joined to the
/// old one by a new edge (V +1, E +1, F same), one undo step; Mesh ▸ Split
/// Vertex starts the same tool, here pulled the other way.
#[test]
fn alt_v_splits_a_vertex_toward_the_pointer() {
    let mut user = User::new();
    user.add("Grid");
    user.tap(KeyCode::Tab);
    user.tap(KeyCode::Digit1);
    user.tap(KeyCode::Numpad7);
    let (v0, e0, f0) = user.mesh_counts();
    let middle = user.screen_of(Vec3::ZERO);
    user.click(middle);
    let v = *user.edit_mode().selection.vertices.iter().next().unwrap();
    assert_eq!(user.first_mesh().position(v), DVec3::ZERO);
    let steps = user.undo_steps();
    for (start_tool, side) in [(true, 1.0), (false, -1.0)] {
        if start_tool {
            user.move_to(middle);
            user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyV);
        } else {
            open_mesh_menu(&mut user);
            user.click_on("Split Vertex\tAlt+V");
        }
        let pulled = user.screen_of(Vec3::new(0.0, 0.0, 0.1 * side as f32));
        user.glide_to(pulled, 5);
        user.click(pulled);
        let mesh = user.first_mesh();
        mesh.validate().unwrap();
        assert_eq!(
            user.mesh_counts(),
            (v0 + 1, e0 + 1, f0),
            "{}",
            user.status()
        );
        assert_eq!(user.undo_steps(), steps + 1);
        let new = mesh.vertices().max_by_key(|v| v.0).unwrap();
        let p = mesh.position(new);
        assert!(
            (p.z * side - 0.1).abs() < 0.01 && p.x.abs() < 0.01 && p.y.abs() < 1e-3,
            "the new vertex is under the pointer: {p}"
        );
        let mut around: Vec<DVec3> = mesh
            .vertex_neighbors(new)
            .map(|w| mesh.position(w))
            .collect();
        around.sort_by(|a, b| a.z.total_cmp(&b.z));
        assert_eq!(
            around.len(),
            2,
            "joined to the old vertex and the edge on its side"
        );
        assert!(around.contains(&DVec3::ZERO), "{around:?}");
        assert!(
            around.iter().any(|q| q.x == 0.0 && q.z * side > 0.1),
            "the edge toward the pointer moved: {around:?}"
        );
        user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
        assert_eq!(user.mesh_counts(), (v0, e0, f0));
    }
}

/// Mesh ▸ Euler Operators on a cube: KEF on the clicked edge merges two
/// faces (E −1, F −1, L −1, shown in the topology inspector); after undo,
/// KFMRH with the top and bottom faces selected makes the bottom a ring
/// of the top: a through hole (F −1, H +1), a valid document mesh.
#[test]
fn euler_operators_from_the_mesh_menu_show_their_change() {
    let mut user = cube_in_edit_mode(KeyCode::Digit2);
    let edge = screen(&mut user, 0.0, 1.0, 1.0);
    user.click(edge);
    open_mesh_menu(&mut user);
    user.click_on("Euler Operators ⏵");
    user.click_on("KEF: kill the selected edge, merging its faces");
    assert_eq!(user.mesh_counts(), (8, 11, 5), "{}", user.status());
    assert!(
        user.shows("Euler KEF: E -1, F -1, L -1"),
        "the inspector shows the change"
    );
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    assert_eq!(user.mesh_counts(), (8, 12, 6));
    // Top and bottom faces: two boxes in X-ray from the front, where the
    // faces' centres are the middles of the top and bottom edges (a click
    // would land on the gizmo of the first selection).
    user.tap(KeyCode::Digit3);
    user.tap(KeyCode::Numpad1);
    user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyZ);
    user.key_down(KeyCode::ShiftLeft);
    for y in [1.0, -1.0] {
        let a = screen(&mut user, -0.3, y - 0.2, 0.0);
        let b = screen(&mut user, 0.3, y + 0.2, 0.0);
        user.drag(a, b, 4);
    }
    user.key_up(KeyCode::ShiftLeft);
    assert_eq!(user.edit_mode().selection.faces.len(), 2);
    open_mesh_menu(&mut user);
    user.click_on("Euler Operators ⏵");
    user.click_on("KFMRH: the smaller of 2 selected faces becomes a ring (hole) of the other");
    assert_eq!(user.mesh_counts(), (8, 12, 5), "{}", user.status());
    let mesh = user.first_mesh();
    mesh.validate().unwrap();
    assert_eq!(mesh.ring_count(), 1);
    assert!(user.shows("Euler KFMRH: F -1, H +1"), "{:?}", user.status());
}

/// View ▸ Snap to ▸ `element` (the combo box), menu closed again.
fn choose_snap_element(user: &mut User, element: &str) {
    user.click_on("View");
    user.click_on(element);
    user.tap(KeyCode::Escape);
}

/// Object mode snaps too: with Snap to Vertex on, G on a second cube at
/// x = 4 and the pointer near the first cube's corner (1, 1, 1) puts the
/// second cube's nearest corner (3, 1, 1) exactly on it, so the cube lands
/// at x = 2; the target is drawn while the move runs.
#[test]
fn object_mode_snaps_a_cube_corner_onto_another_cube() {
    let mut user = User::new();
    user.add("Cube");
    user.add("Cube");
    let second = user
        .app
        .world()
        .resource::<hedra_edit::Selection>()
        .active()
        .unwrap();
    user.app
        .world_mut()
        .write_message(hedra_scene::DocRequest::Execute(
            hedra_doc::Command::SetTransforms {
                nodes: vec![(
                    hedra_doc::NodeRef::from(second),
                    hedra_doc::NodeTransform::from_translation(DVec3::new(4.0, 0.0, 0.0)),
                )],
            },
        ));
    user.frames(2);
    choose_snap_element(&mut user, "Vertex");
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::Tab);
    let start = user.screen_of(Vec3::new(4.0, 0.0, 0.0));
    user.move_to(start);
    user.tap(KeyCode::KeyG);
    let corner = Vec3::new(1.0, 1.0, 1.0);
    let near = user.screen_of(corner) + Vec2::new(5.0, -4.0);
    user.glide_to(near, 5);
    let target = user.app.world().resource::<hedra_edit::SnapTarget>().0;
    assert_eq!(target, Some(corner.as_dvec3()), "the target is drawn");
    user.click(near);
    let moved = user.doc().node(second).unwrap().transform.translation;
    assert_eq!(moved, DVec3::new(2.0, 0.0, 0.0), "{}", user.status());
}

/// Control-point mode snaps onto the shape's other points: G on the
/// surface's middle point with Snap to Vertex on and the pointer near a
/// neighbour puts it exactly there.
#[test]
fn control_point_mode_snaps_a_point_onto_another() {
    let (mut user, target, at) = surface_with_its_middle_point_clicked();
    choose_snap_element(&mut user, "Vertex");
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::Tab);
    let (points, _) = shape_points(&user);
    let other = (0..points.len())
        .filter(|&i| i != target)
        .min_by(|&a, &b| {
            let d = |i: usize| points[i].distance(points[target]);
            d(a).total_cmp(&d(b))
        })
        .unwrap();
    user.move_to(at);
    user.tap(KeyCode::KeyG);
    let near = user.screen_of(points[other].as_vec3()) + Vec2::new(4.0, 3.0);
    user.glide_to(near, 5);
    assert_eq!(
        user.app.world().resource::<hedra_edit::SnapTarget>().0,
        Some(points[other]),
        "the target is drawn"
    );
    user.click(near);
    let (moved, _) = shape_points(&user);
    assert_eq!(moved[target], points[other], "{}", user.status());
}

/// Edge Center and Face snapping (View ▸ Snap to): G puts a cube corner
/// exactly on the middle of a far edge; then another corner onto the top
/// face under the pointer (on the plane y = 1).
#[test]
fn edge_center_and_face_snapping() {
    let mut user = cube_in_edit_mode(KeyCode::Digit1);
    choose_snap_element(&mut user, "Edge Center");
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::Tab);
    let corner = user.screen_of(Vec3::new(1.0, 1.0, 1.0));
    user.click(corner);
    let moved = *user.edit_mode().selection.vertices.iter().next().unwrap();
    user.move_to(corner);
    user.tap(KeyCode::KeyG);
    let middle = Vec3::new(-1.0, 1.0, 0.0);
    let near = user.screen_of(middle) + Vec2::new(5.0, 4.0);
    user.glide_to(near, 5);
    assert_eq!(
        user.app.world().resource::<hedra_edit::SnapTarget>().0,
        Some(middle.as_dvec3())
    );
    user.click(near);
    assert_eq!(user.first_mesh().position(moved), middle.as_dvec3());
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);

    choose_snap_element(&mut user, "Face");
    let low = user.screen_of(Vec3::new(1.0, -1.0, 1.0));
    user.click(low);
    let moved = *user.edit_mode().selection.vertices.iter().next().unwrap();
    assert_eq!(
        user.first_mesh().position(moved),
        DVec3::new(1.0, -1.0, 1.0)
    );
    user.move_to(low);
    user.tap(KeyCode::KeyG);
    let on_top = user.screen_of(Vec3::new(-0.3, 1.0, -0.2));
    user.glide_to(on_top, 5);
    user.click(on_top);
    let p = user.first_mesh().position(moved);
    assert!((p.y - 1.0).abs() < 1e-9, "on the top face's plane: {p}");
    assert!(
        (p.x + 0.3).abs() < 0.05 && (p.z + 0.2).abs() < 0.05,
        "under the pointer: {p}"
    );
    user.first_mesh().validate().unwrap();
}

/// Add ▸ Draw Curve in the top view with increment snapping on: four
/// clicks put four control points exactly on the grid's crossings (on the
/// ground plane through the 3D cursor), a fifth click and Backspace take
/// one back, Enter makes a cubic NURBS curve of those four points in one
/// undo step, selected.
#[test]
fn draw_a_curve_by_clicks_on_the_grid() {
    let mut user = User::new();
    user.tap(KeyCode::Numpad7);
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::Tab);
    let center = user.viewport_center();
    user.open_add_menu_at(center);
    user.choose_add("Draw Curve");
    assert!(user.app.world().resource::<hedra_edit::CurveDraw>().active);
    let wanted = [
        DVec3::new(-2.0, 0.0, 0.0),
        DVec3::new(-1.0, 0.0, 1.0),
        DVec3::new(1.0, 0.0, -1.0),
        DVec3::new(2.0, 0.0, 0.0),
    ];
    // A little off each crossing: the increments put it back.
    for p in wanted.iter().chain([DVec3::new(0.0, 0.0, 2.0)].iter()) {
        let at = user.screen_of(p.as_vec3()) + Vec2::new(3.0, -2.0);
        user.glide_to(at, 2);
        user.click(at);
    }
    assert_eq!(
        user.app
            .world()
            .resource::<hedra_edit::CurveDraw>()
            .points
            .len(),
        5
    );
    user.tap(KeyCode::Backspace);
    let steps = user.undo_steps();
    user.tap(KeyCode::Enter);
    assert_eq!(user.undo_steps(), steps + 1, "{}", user.status());
    let node = user.doc().nodes().next().expect("a curve node");
    assert_eq!(
        hedra_edit::shape_mode::control_points(&node.content),
        wanted
    );
    assert_eq!(
        user.app
            .world()
            .resource::<hedra_edit::Selection>()
            .active(),
        Some(node.id),
        "the new curve is selected"
    );
    assert!(!user.app.world().resource::<hedra_edit::CurveDraw>().active);
}

/// T while drawing steps through the kinds; a poly-Bézier is drawn through
/// the clicks, and a drag from the middle click pulls its handles out (the
/// joint smooth: the other handle mirrored). Another drawing starts with
/// the kind drawn last.
#[test]
fn draw_a_poly_bezier_pulling_a_handle_out() {
    use hedra_geom::curves::{CurveKind, PolyBezier};
    let mut user = User::new();
    user.tap(KeyCode::Numpad7);
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::Tab);
    let center = user.viewport_center();
    user.open_add_menu_at(center);
    user.choose_add("Draw Curve");
    for _ in 0..7 {
        user.tap(KeyCode::KeyT);
    }
    let kind = || user_draw_kind(&user);
    assert_eq!(kind(), hedra_edit::DrawKind::PolyBezier);
    assert!(user.status().contains("poly-Bézier"), "{}", user.status());
    let [a, b, c] = [-2.0, 0.0, 2.0].map(|x| DVec3::new(x, 0.0, 0.0));
    let at = |user: &mut User, p: DVec3| user.screen_of(p.as_vec3()) + Vec2::new(2.0, 2.0);
    let pa = at(&mut user, a);
    user.glide_to(pa, 2);
    user.click(pa);
    let (pb, pull) = (at(&mut user, b), at(&mut user, DVec3::new(1.0, 0.0, 0.0)));
    user.glide_to(pb, 2);
    user.drag(pb, pull, 6);
    let pc = at(&mut user, c);
    user.glide_to(pc, 2);
    user.click(pc);
    user.tap(KeyCode::Enter);
    let node = user.doc().nodes().next().expect("a curve node").clone();
    let NodeContent::Curve(curve) = &node.content else {
        panic!("a curve")
    };
    let CurveKind::PolyBezier(PolyBezier { points, .. }) = curve.kind() else {
        panic!("a poly-Bézier: {}", curve.kind().name())
    };
    assert_eq!(points.len(), 7);
    assert_eq!(
        [points[0], points[3], points[6]],
        [a, b, c],
        "anchors on the grid"
    );
    let handle = points[4] - points[3];
    assert!(
        handle.distance(DVec3::X) < 0.05,
        "the pulled handle reaches the pointer: {handle}"
    );
    assert!(
        (points[2] - (points[3] - handle)).length() < 1e-12,
        "mirrored"
    );
    user.open_add_menu_at(center);
    user.choose_add("Draw Curve");
    assert_eq!(user_draw_kind(&user), hedra_edit::DrawKind::PolyBezier);
}

fn user_draw_kind(user: &User) -> hedra_edit::DrawKind {
    user.app.world().resource::<hedra_edit::CurveDraw>().kind
}

/// Drawing snaps onto other objects too (Snap to Vertex): a click near the
/// cube's corner puts the point exactly on it; Esc drops the drawing.
#[test]
fn a_drawn_point_snaps_onto_a_cube_corner_and_esc_cancels() {
    let mut user = User::new();
    user.add("Cube");
    choose_snap_element(&mut user, "Vertex");
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::Tab);
    let corner = Vec3::new(1.0, 1.0, 1.0);
    user.open_add_menu_at(user.viewport_center() + Vec2::new(200.0, 150.0));
    user.choose_add("Draw Curve");
    let near = user.screen_of(corner) + Vec2::new(5.0, 4.0);
    user.glide_to(near, 3);
    user.click(near);
    let draw = user.app.world().resource::<hedra_edit::CurveDraw>();
    assert_eq!(draw.points, vec![corner.as_dvec3()]);
    user.tap(KeyCode::Escape);
    assert!(!user.app.world().resource::<hedra_edit::CurveDraw>().active);
    assert_eq!(user.doc().nodes().count(), 1, "nothing added");
}

/// R and S in control-point mode: A selects every point of the surface,
/// S 2 Enter doubles their distances from their median, R Y 90 Enter turns
/// them a quarter about the vertical through it; one undo step each.
#[test]
fn r_and_s_turn_and_scale_control_points_about_their_median() {
    let mut user = User::new();
    user.add("NURBS Surface");
    user.tap(KeyCode::Tab);
    user.move_to(user.viewport_center() + Vec2::new(120.0, 40.0));
    user.tap(KeyCode::KeyA);
    let (before, _) = shape_points(&user);
    let median = before.iter().sum::<DVec3>() / before.len() as f64;
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyS);
    user.type_text("2");
    user.tap(KeyCode::Enter);
    let (scaled, _) = shape_points(&user);
    for (p, q) in before.iter().zip(&scaled) {
        assert!(
            (*q - (median + (*p - median) * 2.0)).length() < 1e-12,
            "{p} → {q}"
        );
    }
    assert_eq!(user.undo_steps(), steps + 1);
    user.tap(KeyCode::KeyR);
    user.tap(KeyCode::KeyY);
    user.type_text("90");
    user.tap(KeyCode::Enter);
    let (turned, _) = shape_points(&user);
    let quarter = hedra_geom::DQuat::from_rotation_y(90f64.to_radians());
    for (p, q) in scaled.iter().zip(&turned) {
        assert!(
            (*q - (median + quarter * (*p - median))).length() < 1e-9,
            "{p} → {q}"
        );
    }
    assert_eq!(user.undo_steps(), steps + 2, "{}", user.status());
}

/// The curve panel shows what the viewport shows: while a control point is
/// dragged its length is the previewed curve's, and Esc gives the
/// document's back (it measured the document's curve during the drag once).
#[test]
fn the_curve_panel_follows_a_control_point_drag() {
    use hedra_geom::curves::Curve;
    use hedra_geom::curves::analysis::arc_length;
    let length = |c: &hedra_doc::CurveContent| {
        let n = c.nurbs();
        let (a, b) = n.domain();
        arc_length(&**n, a, b)
    };
    let mut user = User::new();
    user.add("NURBS Curve");
    let node = user.doc().nodes().next().unwrap().clone();
    let NodeContent::Curve(curve) = &node.content else {
        panic!("a curve")
    };
    let before = length(curve);
    assert!(user.shows(&format!("Length {before:.6}")));
    user.tap(KeyCode::Tab);
    let at = user.screen_of(curve.control_points()[2].as_vec3());
    user.click(at);
    let viewport = user.viewport();
    user.tap(KeyCode::KeyG);
    user.glide_to(at + Vec2::new(40.0, -30.0), 3);
    user.frames(2);
    // The point's fields follow the drag without widening the panel: the
    // viewport does not shrink under the pointer.
    assert_eq!(user.viewport(), viewport);
    let preview = user
        .app
        .world()
        .resource::<hedra_scene::Previews>()
        .content(node.id)
        .cloned();
    let Some(hedra_scene::PreviewContent::Curve(moving)) = preview else {
        panic!("G previews the curve: {}", user.status())
    };
    let during = length(&moving);
    assert!((during - before).abs() > 1e-3, "{before} → {during}");
    assert!(
        user.shows(&format!("Length {during:.6}")),
        "the panel measures the dragged curve ({during:.6})"
    );
    user.tap(KeyCode::Escape);
    user.frames(2);
    assert!(user.shows(&format!("Length {before:.6}")));
}

/// The curve panel measures the selected curve: its length (against the
/// kernel's arc length of the same curve), Divide makes a polyline whose
/// points are an equal arc length apart along it, and the closest point to
/// the pointer is no farther than any of 20 000 samples.
#[test]
fn the_curve_panel_measures_length_divides_and_finds_the_closest_point() {
    use hedra_geom::curves::Curve;
    use hedra_geom::curves::analysis::{arc_length, closest_parameter};
    let mut user = User::new();
    user.add("NURBS Curve");
    let node = user.doc().nodes().next().unwrap().clone();
    let NodeContent::Curve(curve) = &node.content else {
        panic!("a curve")
    };
    let curve = (**curve.nurbs()).clone();
    let (a, b) = curve.domain();
    let length = arc_length(&curve, a, b);
    assert!(
        user.shows(&format!("Length {length:.6}")),
        "the panel shows {length:.6}"
    );

    user.click_on("Divide into equal lengths");
    let divided = user.doc().nodes().last().unwrap().clone();
    assert_eq!(divided.name, "NURBS Curve divided");
    let points = hedra_edit::shape_mode::control_points(&divided.content);
    assert_eq!(points.len(), 10);
    let params: Vec<f64> = points
        .iter()
        .map(|&p| closest_parameter(&curve, p))
        .collect();
    for w in params.windows(2) {
        let piece = arc_length(&curve, w[0], w[1]);
        assert!(
            (piece - length / 9.0).abs() < 1e-9,
            "{piece} vs {}",
            length / 9.0
        );
    }

    // Back to the first curve alone: the closest point to the pointer.
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    assert_eq!(user.doc().nodes().count(), 1);
    let at = user.screen_of(curve.point(0.3).as_vec3()) + Vec2::new(25.0, 30.0);
    let on_curve = user.screen_of(curve.point(0.5).as_vec3());
    user.click(on_curve);
    assert_eq!(
        user.app
            .world()
            .resource::<hedra_edit::Selection>()
            .active(),
        Some(node.id)
    );
    user.click_on("Closest point to the pointer");
    user.move_to(at);
    user.frames(2);
    let found = user
        .app
        .world()
        .resource::<hedra_viewport::CurveAnalysis>()
        .closest_found
        .expect("a closest point");
    let nearest_sample = (0..=20_000)
        .map(|i| {
            curve
                .point(a + (b - a) * i as f64 / 20_000.0)
                .distance(found.from)
        })
        .fold(f64::INFINITY, f64::min);
    assert!(
        found.distance <= nearest_sample + 1e-9,
        "{} vs {nearest_sample}",
        found.distance
    );
    assert!((curve.point(found.t) - found.at).length() < 1e-12);
    assert!(user.shows(&format!(
        "t {:.6} · distance {:.6}",
        found.t, found.distance
    )));
}

/// Mesh ▸ Make Hole on the top face of a subdivided cube: the face is a
/// hole (saved in the document), the smooth surface has nothing above the
/// top's middle any more, the neighbours stay; Clear Hole brings it back.
/// The subdivision panel greys out what Doo-Sabin ignores and says why.
#[test]
fn make_hole_leaves_no_surface_and_doo_sabin_greys_out_its_options() {
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::Digit2);
    let top_middle = |user: &User| {
        user.render_positions()
            .iter()
            .any(|p| p.x.abs() < 0.1 && p.z.abs() < 0.1 && p.y > 0.5)
    };
    assert!(top_middle(&user), "the smooth top is drawn");
    let top = user.screen_of(Vec3::new(0.2, 1.0, 0.3));
    user.click(top);
    open_mesh_menu(&mut user);
    user.click_on("Make Hole (subdivision)");
    assert_eq!(
        mesh_content(&user).creases.holes.len(),
        1,
        "{}",
        user.status()
    );
    user.frames(3);
    assert!(!top_middle(&user), "no surface where the hole is");
    assert!(user.shows("1 hole face(s): no surface there (Mesh ▸ Clear Hole)"));
    open_mesh_menu(&mut user);
    user.click_on("Clear Hole");
    assert!(mesh_content(&user).creases.holes.is_empty());
    user.frames(3);
    assert!(top_middle(&user));

    let mut modifier = mesh_content(&user).subdivision.unwrap();
    modifier.options.scheme = hedra_geom::subdivision::Scheme::DooSabin;
    set_subdivision(&mut user, "Cube", Some(modifier));
    user.frames(2);
    assert!(
        user.shows(
            hedra_geom::subdivision::Scheme::DooSabin
                .applicable()
                .reason
        )
    );
}

/// The crease taper row: two edges of the cube's top in a chain, Set gives
/// one tapered chain from 0 at one end to 4 at the other.
#[test]
fn a_tapered_crease_from_the_panel() {
    let mut user = cube_in_edit_mode(KeyCode::Digit2);
    user.tap(KeyCode::Numpad7);
    // A click on the top's front edge, Shift+click on its right edge.
    let front = user.screen_of(Vec3::new(0.0, 1.0, 1.0));
    user.click(front);
    let right = user.screen_of(Vec3::new(1.0, 1.0, -0.3));
    user.key_down(KeyCode::ShiftLeft);
    user.click(right);
    user.key_up(KeyCode::ShiftLeft);
    let edges = user.edit_mode().selection.edges.clone();
    assert_eq!(edges.len(), 2, "two edges in a chain");
    user.click_on("Set");
    let creases = mesh_content(&user).creases;
    assert_eq!(creases.tapers.len(), 1, "{}", user.status());
    let taper = &creases.tapers[0];
    assert_eq!((taper.start, taper.end), (0.0, 4.0));
    assert_eq!(taper.edges.len(), 2);
}

/// Properties ▸ Modifiers ▸ Decimate on an icosphere: the level slider
/// scrubs the progressive mesh, the mesh following while it is dragged; let
/// go at the far left it sets the coarsest level (one undo step for the
/// whole drag) and the drawn mesh has that many faces.
#[test]
fn the_decimate_level_slider_scrubs_the_progressive_mesh() {
    let mut user = User::new();
    user.add("Icosphere");
    let faces = user.first_mesh().face_count();
    user.click_on("Decimate");
    let content = mesh_content(&user);
    assert!(matches!(
        content.modifiers[..],
        [hedra_doc::MeshModifier::Decimate(_)]
    ));
    let counts = content.decimate_face_counts(0).unwrap().unwrap();
    assert_eq!(
        *counts.last().unwrap(),
        faces,
        "the finest level is the input"
    );
    let label = user
        .widgets()
        .iter()
        .find(|w| w.text.starts_with("level · "))
        .expect("the level slider")
        .rect;
    let steps = user.undo_steps();
    let from = Vec2::new(label.min.x - 50.0, label.center().y);
    let to = Vec2::new(label.min.x - 400.0, label.center().y);
    // Halfway through the drag the viewport already shows a coarser level.
    let before = mesh_content(&user).evaluated(0).unwrap().face_count();
    user.move_to(from);
    user.button_down(MouseButton::Left);
    user.glide_to(from.lerp(to, 0.5), 4);
    let midway = mesh_content(&user).evaluated(0).unwrap().face_count();
    assert!(
        midway < before,
        "the level follows the drag: {midway} of {before}"
    );
    assert_eq!(user.undo_steps(), steps + 1, "one step so far");
    user.glide_to(to, 4);
    user.button_up(MouseButton::Left);
    user.frames(2);
    user.frames(3);
    assert_eq!(user.undo_steps(), steps + 1, "one step for the whole drag");
    let hedra_doc::MeshModifier::Decimate(d) = mesh_content(&user).modifiers[0] else {
        panic!("decimate")
    };
    assert_eq!(d.level, Some(0), "the coarsest level");
    let shown = mesh_content(&user).evaluated(0).unwrap().face_count();
    assert_eq!(shown, counts[0]);
    assert!(user.shows(&format!("level · {} faces", counts[0])));
}

/// Shift+A ▸ Curve ⏵ offers every curve kind of the lecture notes; each adds
/// a curve node of that kind. The Koch curve of level 3 on a segment of
/// length 4 is (4/3)³ times as long.
#[test]
fn every_curve_kind_is_in_the_add_menu() {
    use hedra_geom::curves::Curve;
    for item in [
        "Lagrange",
        "Cubic Hermite",
        "Quintic Hermite",
        "Catmull-Rom",
        "Kochanek-Bartels",
        "C2 Cubic Spline",
        "Chaikin",
        "Poly-Bézier",
        "Koch Curve",
        "Koch Snowflake",
        "Quadratic Koch",
    ] {
        let mut user = User::new();
        user.add(item);
        let node = user.doc().nodes().next().unwrap();
        let NodeContent::Curve(curve) = &node.content else {
            panic!("{item} adds a curve")
        };
        if item == "Koch Curve" {
            let c = curve.nurbs();
            let (a, b) = c.domain();
            let length = hedra_geom::curves::analysis::arc_length(&**c, a, b);
            assert!(
                (length - 4.0 * (4.0f64 / 3.0).powi(3)).abs() < 1e-9,
                "{length}"
            );
            assert!(
                user.shows("level 3, Hausdorff dimension 1.2619"),
                "log 4 / log 3 in the panel"
            );
        }
    }
}

/// Control-point mode on a Catmull-Rom curve: X deletes the clicked point
/// (the curve still passes through the others), Alt+C closes the curve;
/// each one undo step.
#[test]
fn x_deletes_a_curve_point_and_alt_c_closes_the_curve() {
    let mut user = User::new();
    user.add("Catmull-Rom");
    user.tap(KeyCode::Tab);
    let (points, _) = shape_points_of_curve(&user);
    assert_eq!(points.len(), 5);
    let middle = user.screen_of(points[2].as_vec3());
    user.click(middle);
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyX);
    let (left, closed) = shape_points_of_curve(&user);
    assert_eq!(
        left,
        [points[0], points[1], points[3], points[4]],
        "{}",
        user.status()
    );
    assert!(!closed);
    user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyC);
    assert!(shape_points_of_curve(&user).1, "closed");
    assert_eq!(user.undo_steps(), steps + 2);
}

fn shape_points_of_curve(user: &User) -> (Vec<DVec3>, bool) {
    let node = user.doc().nodes().next().unwrap();
    let NodeContent::Curve(c) = &node.content else {
        panic!("a curve")
    };
    (c.control_points().to_vec(), c.kind().is_closed())
}

/// Ctrl+click on a Catmull-Rom curve in control-point mode inserts a point
/// there: one more point, on the curve, the others unchanged.
#[test]
fn ctrl_click_inserts_a_point_on_the_curve() {
    use hedra_geom::curves::Curve;
    let mut user = User::new();
    user.add("Catmull-Rom");
    user.tap(KeyCode::Tab);
    let (points, _) = shape_points_of_curve(&user);
    let node = user.doc().nodes().next().unwrap().clone();
    let NodeContent::Curve(curve) = &node.content else {
        panic!("a curve")
    };
    let nurbs = curve.nurbs().clone();
    let (a, b) = nurbs.domain();
    let on_curve = nurbs.point(a + (b - a) * 0.375);
    let at = user.screen_of(on_curve.as_vec3());
    let steps = user.undo_steps();
    user.key_down(KeyCode::ControlLeft);
    user.click(at);
    user.key_up(KeyCode::ControlLeft);
    let (after, _) = shape_points_of_curve(&user);
    assert_eq!(after.len(), 6, "{}", user.status());
    assert_eq!(user.undo_steps(), steps + 1);
    let new: Vec<&DVec3> = after.iter().filter(|p| !points.contains(p)).collect();
    assert_eq!(new.len(), 1, "the others unchanged: {after:?}");
    assert!(
        new[0].distance(on_curve) < 0.05,
        "{} near {on_curve}",
        new[0]
    );
}

/// The selected control points of the curve being edited.
fn selected_points(user: &User) -> Vec<u32> {
    user.app
        .world()
        .resource::<hedra_edit::ShapeEdit>()
        .selected
        .iter()
        .copied()
        .collect()
}

/// The curves of the document, by name order of creation: their points.
fn curves(user: &User) -> Vec<Vec<DVec3>> {
    user.doc()
        .nodes()
        .filter_map(|n| match &n.content {
            NodeContent::Curve(c) => Some(c.control_points().to_vec()),
            _ => None,
        })
        .collect()
}

/// E on the last point of a Catmull-Rom curve adds a point that follows
/// the pointer (X and a typed 1 put it exactly one unit along X), selects
/// it, and a second E extrudes from it; one undo step each. E on a middle
/// point explains itself and changes nothing.
#[test]
fn e_extrudes_a_curve_from_its_selected_end() {
    let mut user = User::new();
    user.add("Catmull-Rom");
    user.tap(KeyCode::Tab);
    let (points, _) = shape_points_of_curve(&user);
    let middle = user.screen_of(points[2].as_vec3());
    user.click(middle);
    user.tap(KeyCode::KeyE);
    assert!(
        user.status().contains("select one end point"),
        "{}",
        user.status()
    );
    let end = user.screen_of(points[4].as_vec3());
    user.click(end);
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyE);
    user.glide_to(end + Vec2::new(60.0, -20.0), 4);
    user.tap(KeyCode::KeyX);
    user.type_text("1");
    user.tap(KeyCode::Enter);
    let (after, _) = shape_points_of_curve(&user);
    assert_eq!(after.len(), 6, "{}", user.status());
    assert_eq!(&after[..5], &points[..]);
    assert!(
        (after[5] - (points[4] + DVec3::X)).length() < 1e-12,
        "{}",
        after[5]
    );
    assert_eq!(selected_points(&user), [5], "the new point is selected");
    assert_eq!(user.undo_steps(), steps + 1);
    user.tap(KeyCode::KeyE);
    user.tap(KeyCode::KeyY);
    user.type_text("2");
    user.tap(KeyCode::Enter);
    let (twice, _) = shape_points_of_curve(&user);
    assert_eq!(twice.len(), 7);
    assert!((twice[6] - (after[5] + 2.0 * DVec3::Y)).length() < 1e-12);
    assert_eq!(user.undo_steps(), steps + 2);
}

/// Y on a selected middle point of a Catmull-Rom curve splits it there into
/// two curves sharing that point; in object mode Ctrl+J with the first
/// half active joins them back into the original five points.
#[test]
fn y_splits_a_curve_at_a_point_and_ctrl_j_joins_the_halves() {
    let mut user = User::new();
    user.add("Catmull-Rom");
    user.tap(KeyCode::Tab);
    let (points, _) = shape_points_of_curve(&user);
    let middle = user.screen_of(points[2].as_vec3());
    user.click(middle);
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyY);
    assert_eq!(
        curves(&user),
        [points[..3].to_vec(), points[2..].to_vec()],
        "{}",
        user.status()
    );
    assert_eq!(user.undo_steps(), steps + 1);
    user.tap(KeyCode::Tab);
    // The second half first, then the first half (Shift: it becomes active).
    let second = user.screen_of(points[3].as_vec3());
    let first = user.screen_of(points[1].as_vec3());
    user.click(second);
    user.key_down(KeyCode::ShiftLeft);
    user.click(first);
    user.key_up(KeyCode::ShiftLeft);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyJ);
    assert_eq!(curves(&user), vec![points], "{}", user.status());
    assert_eq!(user.undo_steps(), steps + 2);
}

/// The Curve menu of control-point mode: Reverse Direction reverses the
/// points; Extrude starts the same tool as E.
#[test]
fn the_curve_menu_reverses_and_extrudes() {
    let mut user = User::new();
    user.add("Catmull-Rom");
    user.tap(KeyCode::Tab);
    let (points, _) = shape_points_of_curve(&user);
    open_menu(&mut user, "Curve");
    user.click_on("Reverse Direction");
    let reversed: Vec<DVec3> = points.iter().rev().copied().collect();
    assert_eq!(shape_points_of_curve(&user).0, reversed);
    let first = user.screen_of(reversed[0].as_vec3());
    user.click(first);
    open_menu(&mut user, "Curve");
    user.click_on("Extrude\tE");
    user.tap(KeyCode::KeyZ);
    user.type_text("3");
    user.tap(KeyCode::Enter);
    let (after, _) = shape_points_of_curve(&user);
    assert_eq!(after.len(), 6, "{}", user.status());
    assert!((after[0] - (reversed[0] + 3.0 * DVec3::Z)).length() < 1e-12);
}

/// A cubic Hermite curve in control-point mode shows its tangents as
/// handles; clicking a handle's end and moving it (G X 1) turns its key's
/// tangent — the key stays, the handle ends exactly one unit further along
/// X, and the key's other handle mirrors it. One undo step.
#[test]
fn a_hermite_tangent_handle_is_dragged_like_a_point() {
    use hedra_geom::curves::CurveKind;
    let mut user = User::new();
    user.add("Cubic Hermite");
    user.tap(KeyCode::Tab);
    let kind = |user: &User| -> CurveKind {
        let node = user.doc().nodes().next().unwrap();
        let NodeContent::Curve(c) = &node.content else {
            panic!("a curve")
        };
        c.kind().clone()
    };
    let before = kind(&user);
    let keys = before.points().len();
    let handles = before.tangent_handles();
    assert_eq!(handles.len(), 2 * keys - 2);
    assert_eq!(
        user.control_point_entities().len(),
        keys + handles.len(),
        "each handle end is a point to pick"
    );
    // The middle key's outgoing handle.
    let k = handles
        .iter()
        .position(|h| h.point == 1 && !h.incoming)
        .unwrap();
    let end = user.screen_of(handles[k].end.as_vec3());
    user.click(end);
    assert_eq!(selected_points(&user), [(keys + k) as u32]);
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyG);
    user.tap(KeyCode::KeyX);
    user.type_text("1");
    user.tap(KeyCode::Enter);
    let after = kind(&user);
    assert_eq!(after.points(), before.points(), "the keys stay");
    let moved = after.tangent_handles();
    assert!(
        moved[k].end.distance(handles[k].end + DVec3::X) < 1e-12,
        "{} {}",
        moved[k].end,
        user.status()
    );
    let key = after.points()[1];
    assert!((moved[k - 1].end - key + (moved[k].end - key)).length() < 1e-12);
    assert_eq!(user.undo_steps(), steps + 1);
}

/// The Properties panel edits a Kochanek-Bartels key's tension, bias and
/// continuity: dragging T right on the selected middle key raises its
/// tension (one undo step when let go); the other keys keep theirs.
#[test]
fn the_panel_sets_a_kochanek_bartels_key_tension() {
    use hedra_geom::curves::{CurveKind, KochanekBartels};
    let mut user = User::new();
    user.add("Kochanek-Bartels");
    user.tap(KeyCode::Tab);
    let (points, _) = shape_points_of_curve(&user);
    let key = user.screen_of(points[2].as_vec3());
    user.click(key);
    user.frames(2);
    let field = user
        .widgets()
        .iter()
        .find(|w| w.text.starts_with("T "))
        .expect("the tension field")
        .rect;
    let steps = user.undo_steps();
    let from = Vec2::new(field.center().x, field.center().y);
    user.drag(from, from + Vec2::new(30.0, 0.0), 6);
    user.frames(3);
    let node = user.doc().nodes().next().unwrap().clone();
    let NodeContent::Curve(c) = &node.content else {
        panic!("a curve")
    };
    let CurveKind::KochanekBartels(KochanekBartels { keys, .. }) = c.kind() else {
        panic!("still Kochanek-Bartels")
    };
    assert!(keys[2].tension > 0.05, "{:?} {}", keys[2], user.status());
    for (i, k) in keys.iter().enumerate().filter(|(i, _)| *i != 2) {
        assert_eq!(k.tension, 0.0, "key {i}");
    }
    assert_eq!(user.undo_steps(), steps + 1);
}

/// The panel shows the selected point's coordinates: dragging its X field
/// moves only that point, only along X (one undo step); with two points
/// the curve passes through selected it gives the span's arc length.
#[test]
fn the_panel_moves_a_point_by_its_coordinates_and_measures_a_span() {
    let mut user = User::new();
    user.add("Catmull-Rom");
    user.tap(KeyCode::Tab);
    let (points, _) = shape_points_of_curve(&user);
    let at = user.screen_of(points[2].as_vec3());
    user.click(at);
    user.frames(2);
    assert!(user.shows("Point 2"));
    // The lowest X field: the point's (the object's location is above).
    let field = user
        .widgets()
        .iter()
        .filter(|w| w.text.starts_with("X "))
        .max_by(|a, b| a.rect.min.y.total_cmp(&b.rect.min.y))
        .expect("the X field")
        .rect;
    let steps = user.undo_steps();
    let from = Vec2::new(field.center().x, field.center().y);
    user.drag(from, from + Vec2::new(40.0, 0.0), 6);
    user.frames(3);
    let (after, _) = shape_points_of_curve(&user);
    let moved = after[2] - points[2];
    assert!(
        moved.x > 0.05 && moved.y == 0.0 && moved.z == 0.0,
        "{moved}"
    );
    for i in [0, 1, 3, 4] {
        assert_eq!(after[i], points[i]);
    }
    assert_eq!(user.undo_steps(), steps + 1);
    let other = user.screen_of(after[4].as_vec3());
    user.key_down(KeyCode::ShiftLeft);
    user.click(other);
    user.key_up(KeyCode::ShiftLeft);
    user.frames(2);
    let node = user.doc().nodes().next().unwrap().clone();
    let NodeContent::Curve(c) = &node.content else {
        panic!("a curve")
    };
    let keys = c.kind().key_parameters().unwrap();
    let length = hedra_geom::curves::analysis::arc_length(&**c.nurbs(), keys[2], keys[4]);
    assert!(
        user.shows(&format!("Span from point 2 to 4: length {length:.6}")),
        "the span's length {length:.6} is shown"
    );
}

/// The surface node of the document made from curves, if any.
fn made_from_curves(user: &User) -> Option<hedra_doc::Node> {
    user.doc()
        .nodes()
        .find(|n| n.construction.is_some())
        .cloned()
}

/// Object ▸ Surface from Curves ▸ Revolve on a Catmull-Rom curve makes a
/// surface that remembers it; moving a point of the curve (G Y 1) shows the
/// surface made again while the point moves, and the confirmed move
/// re-makes it in the same undo step (undo puts both back). The panel's
/// angle slider turns the revolution live and is one step when let go;
/// Apply freezes it.
#[test]
fn a_revolved_surface_follows_its_profile_and_its_panel() {
    use hedra_doc::construction::Recipe;
    let mut user = User::new();
    user.add("Catmull-Rom");
    open_menu(&mut user, "Object");
    user.click_on("Surface from Curves ⏵");
    user.click_on("Revolve");
    let surface = made_from_curves(&user).expect("a revolved surface");
    assert!(matches!(
        surface.construction.as_ref().unwrap().recipe,
        Recipe::Revolve { .. }
    ));
    assert_eq!(surface.name, "Revolution");
    let before = surface.content.clone();
    // Edit the profile: its last point up by one.
    let curve = user
        .doc()
        .nodes()
        .find(|n| n.construction.is_none())
        .unwrap()
        .id;
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set([curve]);
    user.tap(KeyCode::Tab);
    let (points, _) = shape_points_of_curve(&user);
    let end = user.screen_of(points[4].as_vec3());
    user.click(end);
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyG);
    user.glide_to(end + Vec2::new(0.0, -30.0), 3);
    let previewed = user
        .app
        .world()
        .resource::<hedra_scene::Previews>()
        .slot(hedra_scene::PreviewSource::ShapeTool)
        .map(|p| p.contents.contains_key(&surface.id));
    assert_eq!(previewed, Some(true), "the surface follows the drag");
    user.tap(KeyCode::KeyY);
    user.type_text("1");
    user.tap(KeyCode::Enter);
    assert_eq!(user.undo_steps(), steps + 1);
    let after = made_from_curves(&user).unwrap();
    assert_ne!(after.content, before, "made again from the moved profile");
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    assert_eq!(made_from_curves(&user).unwrap().content, before);
    // The panel: drag the angle slider left, let go.
    user.tap(KeyCode::Tab);
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set([surface.id]);
    user.frames(2);
    let label = user.find_all("angle°")[0];
    let steps = user.undo_steps();
    let from = Vec2::new(label.min.x - 20.0, label.center().y);
    user.drag(from, from - Vec2::new(80.0, 0.0), 6);
    user.frames(3);
    let Recipe::Revolve { degrees, .. } = made_from_curves(&user)
        .unwrap()
        .construction
        .unwrap()
        .recipe
    else {
        panic!("still a revolution")
    };
    assert!(degrees < 359.0, "{degrees}");
    assert_eq!(user.undo_steps(), steps + 1, "one step for the whole drag");
    user.click_on("Apply");
    assert!(made_from_curves(&user).is_none(), "frozen");
    assert_eq!(user.doc().nodes().count(), 2);
}

/// A poly-Bézier's aligned (G1) joint stays aligned while one of its
/// handles is dragged: G on the incoming handle of the middle anchor moves
/// it where the pointer goes, the outgoing handle turns to stay on the
/// same line through the anchor and keeps its length; the anchor stays.
#[test]
fn a_g1_joint_stays_aligned_while_a_handle_is_dragged() {
    let mut user = User::new();
    user.add("Poly-Bézier");
    user.tap(KeyCode::Tab);
    let (before, _) = shape_points_of_curve(&user);
    let handle = user.screen_of(before[2].as_vec3());
    user.click(handle);
    assert_eq!(selected_points(&user), [2]);
    user.tap(KeyCode::KeyG);
    for step in 1..=3 {
        user.glide_to(
            handle + Vec2::new(10.0 * step as f32, 25.0 * step as f32),
            2,
        );
    }
    user.tap(KeyCode::Enter);
    let (after, _) = shape_points_of_curve(&user);
    assert_ne!(after[2], before[2], "{}", user.status());
    assert_eq!(after[3], before[3], "the anchor stays");
    let incoming = (after[3] - after[2]).normalize();
    let outgoing = (after[4] - after[3]).normalize();
    assert!(
        (incoming - outgoing).length() < 1e-12,
        "{incoming} vs {outgoing}"
    );
    assert!(((after[4] - after[3]).length() - (before[4] - before[3]).length()).abs() < 1e-12);
}

/// Object ▸ Surface from Curves ▸ Loft through two circles (the second
/// moved up with G Y 2) makes a NURBS surface through both, following
/// them; Revolve's "View" button turns a revolution about the view axis
/// through the 3D cursor, in world space.
#[test]
fn loft_two_circles_and_revolve_about_the_view() {
    use hedra_doc::construction::{Recipe, Space};
    use hedra_geom::surfaces::Surface;
    let mut user = User::new();
    user.add("NURBS Circle");
    user.add("NURBS Circle");
    user.tap(KeyCode::KeyG);
    user.tap(KeyCode::KeyY);
    user.type_text("2");
    user.tap(KeyCode::Enter);
    user.tap(KeyCode::KeyA);
    open_menu(&mut user, "Object");
    user.click_on("Surface from Curves ⏵");
    user.click_on("Loft");
    let loft = made_from_curves(&user).expect("a loft");
    let Recipe::Loft { sections, .. } = &loft.construction.as_ref().unwrap().recipe else {
        panic!("a loft")
    };
    assert_eq!(sections.len(), 2);
    let NodeContent::Surface(s) = &loft.content else {
        panic!("a surface")
    };
    let hedra_doc::SurfaceShape::Nurbs(n) = &**s else {
        panic!("NURBS")
    };
    // Both ends are the unit circles (in the ground plane), at y = 0 and 2.
    let ((u0, u1), (v0, v1)) = n.domain();
    for (v, y) in [(v0, 0.0), (v1, 2.0)] {
        for i in 0..=8 {
            let p = n.point(u0 + (u1 - u0) * i as f64 / 8.0, v);
            let radius = DVec3::new(p.x, 0.0, p.z).length();
            assert!((p.y - y).abs() < 1e-9 && (radius - 1.0).abs() < 1e-9, "{p}");
        }
    }
    // A revolution of the first circle about the view axis.
    let first = user.doc().nodes().next().unwrap().id;
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set([first]);
    open_menu(&mut user, "Object");
    user.click_on("Surface from Curves ⏵");
    user.click_on("Revolve");
    user.tap(KeyCode::Numpad1);
    user.frames(2);
    user.click_on("View axis");
    let revolution = user
        .doc()
        .nodes()
        .find(|n| n.name == "Revolution")
        .cloned()
        .expect("a revolution");
    let Recipe::Revolve { axis, space, .. } = revolution.construction.unwrap().recipe else {
        panic!("a revolution")
    };
    assert_eq!(space, Space::World);
    // The front view looks along −Z: the axis points back at the viewer.
    assert!(axis.normalize().distance(DVec3::Z) < 1e-6, "{axis}");
}

/// Seed 002's exercise in the app: a cubic Bézier triangle and a bicubic
/// patch along its edge; Object ▸ Make G1 Join makes the normals agree
/// along the joint (one undo step), and they keep agreeing while points of
/// the patch are dragged with G in control-point mode — the dependent row
/// follows (and is coloured apart: roles published by the document).
#[test]
fn make_g1_join_and_keep_it_while_dragging() {
    let mut user = User::new();
    for cmd in [
        r#"AddSurface(name: "Triangle", surface: Triangle(degree: 3, points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (2.0, 0.0, 0.0), (3.0, 0.0, 0.0), (0.5, 0.3, -1.0), (1.5, 0.6, -1.0), (2.5, 0.3, -1.0), (1.0, 0.4, -2.0), (2.0, 0.4, -2.0), (1.5, 0.2, -3.0)]))"#,
        r#"AddSurface(name: "Patch", surface: Bezier(nu: 4, nv: 4, points: [(0.0, 0.0, 0.0), (0.0, 0.2, 1.0), (0.0, 0.1, 2.0), (0.0, 0.0, 3.0), (1.0, 0.1, 0.0), (1.0, 0.5, 1.0), (1.0, 0.3, 2.0), (1.0, 0.0, 3.0), (2.0, -0.1, 0.0), (2.0, 0.5, 1.0), (2.0, 0.3, 2.0), (2.0, 0.0, 3.0), (3.0, 0.0, 0.0), (3.0, 0.2, 1.0), (3.0, 0.1, 2.0), (3.0, 0.0, 3.0)]))"#,
    ] {
        let cmd: hedra_doc::Command = ron::from_str(cmd).unwrap();
        user.app
            .world_mut()
            .write_message(hedra_scene::DocRequest::Execute(cmd));
        user.frames(2);
    }
    let id = |user: &User, name: &str| user.doc().nodes().find(|n| n.name == name).unwrap().id;
    let (triangle, patch) = (id(&user, "Triangle"), id(&user, "Patch"));
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set([triangle, patch]);
    let angle = |user: &User| {
        user.doc()
            .g1_report(patch)
            .expect("joined")
            .max_normal_angle
    };
    let steps = user.undo_steps();
    open_menu(&mut user, "Object");
    user.click_on("Make G1 Join");
    assert_eq!(user.undo_steps(), steps + 1, "{}", user.status());
    assert!(angle(&user) < 1e-9, "{}", angle(&user));
    let roles = user.doc().g1_roles(patch).unwrap();
    assert!(roles.contains(&hedra_geom::surfaces::patches::PointRole::Dependent));
    let patch_points = |user: &User| {
        hedra_edit::shape_mode::control_points(&user.doc().node(patch).unwrap().content)
    };
    // Drag a free point, a dependent one and a shared one of the patch.
    user.tap(KeyCode::Tab);
    for (k, index) in [14usize, 5, 8].into_iter().enumerate() {
        let points = patch_points(&user);
        let at = user.screen_of(points[index].as_vec3());
        user.click(at);
        user.tap(KeyCode::KeyG);
        let off = Vec2::new(17.0 - 9.0 * k as f32, -23.0 + 11.0 * k as f32);
        user.glide_to(at + off, 3);
        user.tap(KeyCode::Enter);
        let moved = patch_points(&user);
        assert_ne!(moved, points, "point {index} moved: {}", user.status());
        assert!(
            angle(&user) < 1e-9,
            "after dragging point {index}: {}",
            angle(&user)
        );
    }
}

/// Object ▸ Surface from Curves ▸ Coons Patch on four curves closing a loop
/// (selected with A) makes a patch whose corners are the loop's corners.
#[test]
fn coons_patch_from_four_selected_curves() {
    use hedra_geom::surfaces::Surface;
    let mut user = User::new();
    let corners = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(2.0, 0.5, 2.0),
        DVec3::new(0.0, 0.0, 2.0),
    ];
    for i in 0..4 {
        let (a, b) = (corners[i], corners[(i + 1) % 4]);
        let mid = (a + b) / 2.0 + DVec3::Y * 0.3;
        user.app
            .world_mut()
            .write_message(hedra_scene::DocRequest::Execute(
                hedra_doc::Command::AddCurve {
                    name: format!("Side {i}"),
                    curve: hedra_doc::command::CurveSpec::Bezier {
                        points: vec![a, mid, b],
                    },
                    parent: None,
                    transform: Default::default(),
                },
            ));
        user.frames(2);
    }
    user.tap(KeyCode::KeyA);
    open_menu(&mut user, "Object");
    user.click_on("Surface from Curves ⏵");
    user.click_on("Coons Patch");
    let patch = made_from_curves(&user).expect("a Coons patch");
    let NodeContent::Surface(s) = &patch.content else {
        panic!("a surface")
    };
    let hedra_doc::SurfaceShape::Nurbs(n) = &**s else {
        panic!("NURBS")
    };
    let ((u0, u1), (v0, v1)) = n.domain();
    for (u, v) in [(u0, v0), (u1, v0), (u1, v1), (u0, v1)] {
        let p = n.point(u, v);
        assert!(
            corners.iter().any(|c| c.distance(p) < 1e-9),
            "corner {p} {}",
            user.status()
        );
    }
}

/// The curve panel's power basis of a cubic Bézier: seed 003's matrix
/// (rows u³…u⁰, columns b3…b0; its first row 1 −3 3 −1) and a0, the
/// curve's start point.
#[test]
fn the_curve_panel_shows_the_power_basis_matrix() {
    let mut user = User::new();
    user.add("Bézier Curve");
    user.click_on("Power basis (Bézier to monomials)");
    user.frames(2);
    let (points, _) = shape_points_of_curve(&user);
    let widgets = user.widgets();
    let row = widgets
        .iter()
        .find(|w| w.text == "u^3")
        .expect("the matrix")
        .rect;
    let mut cells: Vec<_> = widgets
        .iter()
        .filter(|w| (w.rect.center().y - row.center().y).abs() < 3.0 && w.rect.min.x > row.max.x)
        .collect();
    cells.sort_by(|a, b| a.rect.min.x.total_cmp(&b.rect.min.x));
    // A widget may be reported twice (two passes in a frame): one per place.
    cells.dedup_by(|a, b| a.rect == b.rect && a.text == b.text);
    let cells: Vec<&str> = cells.iter().map(|w| w.text.as_str()).collect();
    assert_eq!(cells, ["1", "-3", "3", "-1"]);
    let texts: Vec<String> = widgets.iter().map(|w| w.text.clone()).collect();
    let p = points[0];
    assert!(
        user.shows(&format!("a0 = ({:.3}, {:.3}, {:.3})", p.x, p.y, p.z)),
        "{texts:?}"
    );
}

/// Two overlapping cubes (the second moved G X 1): Ctrl+Numpad + unites
/// them into the active one — one closed, valid mesh spanning x from −1 to
/// 2, the other gone, one undo step that brings both back. Object ▸
/// Boolean ▸ Live CSG Difference makes a CSG node whose solid is drawn.
#[test]
fn ctrl_numpad_plus_unites_two_cubes_and_a_live_csg_node_is_drawn() {
    let mut user = User::new();
    user.add("Cube");
    user.add("Cube");
    user.tap(KeyCode::KeyG);
    user.tap(KeyCode::KeyX);
    user.type_text("1");
    user.tap(KeyCode::Enter);
    user.tap(KeyCode::KeyA);
    let steps = user.undo_steps();
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::NumpadAdd);
    assert_eq!(user.doc().nodes().count(), 1, "{}", user.status());
    let node = user.doc().nodes().next().unwrap().clone();
    let NodeContent::Mesh(m) = &node.content else {
        panic!("a mesh")
    };
    m.mesh.validate().unwrap();
    let stats = m.mesh.stats();
    assert!(stats.closed, "closed");
    let world = user.doc().world_matrix(node.id);
    let xs: Vec<f64> = m
        .mesh
        .vertices()
        .map(|v| world.transform_point3(m.mesh.position(v)).x)
        .collect();
    let (lo, hi) = xs
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    assert!(
        (lo + 1.0).abs() < 1e-9 && (hi - 2.0).abs() < 1e-9,
        "{lo} {hi}"
    );
    assert_eq!(user.undo_steps(), steps + 1);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    assert_eq!(user.doc().nodes().count(), 2);
    // A live CSG node of both: drawn as its solid.
    user.tap(KeyCode::KeyA);
    open_menu(&mut user, "Object");
    user.click_on("Live CSG Difference");
    let csg = user
        .doc()
        .nodes()
        .find(|n| matches!(n.content, NodeContent::Csg(_)))
        .cloned()
        .expect("a CSG node");
    let solid = hedra_doc::csg::evaluate(user.doc(), csg.id).expect("a solid");
    assert!(solid.stats().closed);
    user.frames(3);
    let entity = user.app.world().resource::<hedra_scene::NodeEntities>().0[&csg.id];
    assert!(
        user.app
            .world()
            .get::<hedra_scene::NodeMesh>(entity)
            .is_some(),
        "the CSG node draws its solid"
    );
}

fn execute(user: &mut User, cmd: &str) {
    let cmd: hedra_doc::Command = ron::from_str(cmd).unwrap();
    user.app
        .world_mut()
        .write_message(hedra_scene::DocRequest::Execute(cmd));
    user.frames(2);
}

fn node_named(user: &User, name: &str) -> Option<hedra_doc::Node> {
    user.doc().nodes().find(|n| n.name == name).cloned()
}

/// A revolution's *Pick axis* button: two clicks in the top view (Ctrl
/// held: whole grid steps) put the axis through both points, in world
/// space, one undo step. Then *Caps at a partial angle* on the NURBS
/// result makes two flat NURBS cap nodes under it, one at the profile and
/// one where the turn ends.
#[test]
fn pick_a_revolve_axis_by_two_points_and_cap_its_nurbs_ends() {
    use hedra_doc::construction::{Output, Recipe, Space};
    use hedra_geom::surfaces::Surface;
    let mut user = User::new();
    user.add("NURBS Circle");
    user.tap(KeyCode::KeyG);
    user.tap(KeyCode::KeyX);
    user.type_text("3");
    user.tap(KeyCode::Enter);
    open_menu(&mut user, "Object");
    user.click_on("Surface from Curves ⏵");
    user.click_on("Revolve");
    let id = made_from_curves(&user).expect("a revolution").id;
    user.tap(KeyCode::Numpad7);
    user.frames(3);
    let steps = user.undo_steps();
    user.click_on("Pick axis");
    assert!(user.status().contains("Pick axis"), "{}", user.status());
    // Inside the ring's hole, so the clicks land on the ground plane.
    for p in [Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0)] {
        let at = user.screen_of(p) + Vec2::new(3.0, -2.0);
        user.move_to(at);
        user.key_down(KeyCode::ControlLeft);
        user.frames(2);
        user.click(at);
        user.key_up(KeyCode::ControlLeft);
    }
    user.frames(2);
    assert_eq!(user.undo_steps(), steps + 1, "{}", user.status());
    let made = user.doc().node(id).unwrap().construction.clone().unwrap();
    let Recipe::Revolve {
        origin,
        axis,
        space,
        ..
    } = made.recipe
    else {
        panic!("a revolution")
    };
    assert_eq!(space, Space::World);
    assert!(origin.distance(DVec3::ZERO) < 1e-12, "{origin}");
    assert!(axis.distance(DVec3::NEG_Z) < 1e-12, "{axis}");
    // Half a turn, then the caps checkbox.
    let mut half = made
        .map_inputs(|i| Ok::<_, ()>(hedra_doc::NodeRef::from(*i)))
        .unwrap();
    if let Recipe::Revolve { degrees, .. } = &mut half.recipe {
        *degrees = 180.0;
    }
    assert_eq!(half.output, Output::Nurbs);
    user.app
        .world_mut()
        .write_message(hedra_scene::DocRequest::Execute(
            hedra_doc::Command::SetConstruction {
                node: id.into(),
                construction: half,
            },
        ));
    user.frames(3);
    let steps = user.undo_steps();
    user.click_on("Caps at a partial angle");
    user.frames(2);
    assert_eq!(user.undo_steps(), steps + 1, "{}", user.status());
    let caps: Vec<hedra_doc::Node> = user
        .doc()
        .nodes()
        .filter(|n| n.parent == Some(id))
        .cloned()
        .collect();
    assert_eq!(caps.len(), 2, "{:?}", user.node_names());
    // The start cap is the profile's disc: in the ground plane, within
    // the unit circle about (3, 0, 0); the end cap its mirror about the axis.
    for (cap, centre) in caps
        .iter()
        .zip([DVec3::new(3.0, 0.0, 0.0), DVec3::new(-3.0, 0.0, 0.0)])
    {
        let NodeContent::Surface(s) = &cap.content else {
            panic!("a surface")
        };
        let hedra_doc::SurfaceShape::Nurbs(n) = &**s else {
            panic!("NURBS")
        };
        let ((u0, u1), (v0, v1)) = n.domain();
        for i in 0..=6 {
            for j in 0..=6 {
                let p = n.point(
                    u0 + (u1 - u0) * i as f64 / 6.0,
                    v0 + (v1 - v0) * j as f64 / 6.0,
                );
                assert!(p.y.abs() < 1e-9, "{} {p}", cap.name);
                assert!(p.distance(centre) <= 1.0 + 1e-9, "{} {p}", cap.name);
            }
        }
    }
    user.key_down(KeyCode::ControlLeft);
    user.tap(KeyCode::KeyZ);
    user.key_up(KeyCode::ControlLeft);
    user.frames(2);
    assert!(user.doc().nodes().all(|n| n.parent != Some(id)));
}

/// A sweep along an S-shaped rail with the Frenet frame: the panel says
/// where the frame flips (the rail's inflection), the document reports the
/// same station; the rotation-minimising frame reports none.
#[test]
fn a_frenet_sweep_shows_where_its_frame_flips() {
    let mut user = User::new();
    let rail: Vec<String> = (0..=40)
        .map(|k| {
            let t = k as f64 / 40.0;
            format!(
                "({:.6}, {:.6}, 0.0)",
                4.0 * t,
                (std::f64::consts::TAU * t).sin()
            )
        })
        .collect();
    execute(
        &mut user,
        &format!(
            "AddCurve(name: \"Rail\", curve: Nurbs(degree: 3, points: [{}]))",
            rail.join(", ")
        ),
    );
    execute(
        &mut user,
        "AddCurve(name: \"Profile\", curve: Circle(radius: 0.2))",
    );
    execute(
        &mut user,
        "MakeFromCurves(name: \"Tube\", construction: (recipe: Sweep(profile: Name(\"Profile\"), rail: Name(\"Rail\"), frame: Frenet, stations: 21)))",
    );
    let tube = node_named(&user, "Tube").expect("a sweep").id;
    let found = user.doc().sweep_frames(tube).expect("frames");
    assert_eq!(found.flips.len(), 1, "{:?}", found.flips);
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set([tube]);
    user.frames(3);
    assert!(
        user.shows("The frame flips at 1 station (ringed in the viewport): the profile turns half a turn there; the rotation-minimising frame does not flip"),
        "the panel names the flip"
    );
    user.click_on("rotation-minimising");
    user.frames(2);
    assert!(user.doc().sweep_frames(tube).unwrap().flips.is_empty());
    assert!(user.shows("Frames at 21 stations: no flip"));
}

/// The seed 002 sample (a Bézier triangle G1-joined to a bicubic patch):
/// both selected, the panel's planar section and moving domain point are
/// drawn on each of them — the section cuts both patches with one plane,
/// meeting at the joint, and at the shared edge the two domain points'
/// normals agree.
#[test]
fn the_g1_sample_shows_sections_and_the_domain_point_on_both_patches() {
    let mut user = User::new();
    let sample = std::path::Path::new(
        &std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"),
    )
    .join("assets/samples/g1-join.hedra.ron");
    user.app
        .world_mut()
        .write_message(hedra_ui::FileAction::OpenPath(sample));
    for _ in 0..50 {
        user.frames(2);
        if user.doc().nodes().count() == 2 {
            break;
        }
    }
    user.frames(5);
    let ids: Vec<hedra_doc::NodeId> = user.doc().nodes().map(|n| n.id).collect();
    assert_eq!(ids.len(), 2, "the sample opened: {}", user.status());
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set(ids.clone());
    user.frames(3);
    user.click_on("Planar section");
    user.click_on("Moving domain point");
    user.frames(3);
    let shown = user
        .app
        .world()
        .resource::<hedra_viewport::SurfaceAnalysisShown>()
        .clone();
    assert_eq!(shown.sections.len(), 2);
    for (id, cut) in &shown.sections {
        assert!(
            cut.len() >= 4,
            "the section crosses node {id}: {} segments",
            cut.len()
        );
    }
    assert_eq!(shown.points.len(), 2);
    // At (u, v) = (0, 0) both points are the joint's shared corner, and
    // there the two patches' normals agree (G1).
    let (mut a, mut b) = (shown.points[0], shown.points[1]);
    assert!((a.2.length() - 1.0).abs() < 1e-9 && (b.2.length() - 1.0).abs() < 1e-9);
    assert!(a.1.distance(b.1) > 1e-3, "u = v = 0.5 are different points");
    {
        let mut analysis = user
            .app
            .world_mut()
            .resource_mut::<hedra_viewport::SurfaceAnalysis>();
        analysis.u = 0.0;
        analysis.v = 0.0;
    }
    user.frames(2);
    let shown = user
        .app
        .world()
        .resource::<hedra_viewport::SurfaceAnalysisShown>()
        .clone();
    (a, b) = (shown.points[0], shown.points[1]);
    assert!(
        a.1.length() < 1e-12 && b.1.length() < 1e-12,
        "{:?} {:?}",
        a.1,
        b.1
    );
    assert!(a.2.dot(b.2).abs() > 1.0 - 1e-9, "{:?} {:?}", a.2, b.2);
}

/// The CSG emblem built in the app (issue 17): a cube and a sphere (S 1.35)
/// made a live intersection, three cylinders (S 0.55, two turned with R)
/// taken from it as a live difference — a closed solid of genus 5. A click
/// on the solid selects the CSG node (its operands appear as ghosts); a
/// cylinder dragged with G changes the drawn solid while it moves (the
/// preview is the re-evaluated solid), and the confirmed move is one undo
/// step after which the document's solid is the previewed one. Dragging a
/// cylinder out of the CSG node in the outliner makes it an object of its
/// own again (the solid has one hole less).
#[test]
fn build_the_csg_emblem_in_the_app_and_drag_a_cylinder_through_it() {
    let mut user = User::new();
    user.add("Cube");
    user.add("Sphere");
    user.tap(KeyCode::KeyS);
    user.type_text("1.35");
    user.tap(KeyCode::Enter);
    user.tap(KeyCode::KeyA);
    open_menu(&mut user, "Object");
    user.click_on("Live CSG Intersection");
    let rounded = user
        .doc()
        .nodes()
        .find(|n| matches!(n.content, NodeContent::Csg(_)))
        .expect("the intersection")
        .id;
    let mut cylinders = Vec::new();
    for turn in [None, Some(KeyCode::KeyX), Some(KeyCode::KeyZ)] {
        user.add("Cylinder");
        user.tap(KeyCode::KeyS);
        user.type_text("0.55");
        user.tap(KeyCode::Enter);
        // Long enough to pass through: 1.5 times as long along its axis.
        user.tap(KeyCode::KeyS);
        user.tap(KeyCode::KeyY);
        user.type_text("2.7");
        user.tap(KeyCode::Enter);
        if let Some(axis) = turn {
            user.tap(KeyCode::KeyR);
            user.tap(axis);
            user.type_text("90");
            user.tap(KeyCode::Enter);
        }
        cylinders.push(
            user.app
                .world()
                .resource::<hedra_edit::Selection>()
                .active()
                .unwrap(),
        );
    }
    let mut operands = vec![rounded];
    operands.extend(&cylinders);
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set(operands);
    open_menu(&mut user, "Object");
    user.click_on("Live CSG Difference");
    let emblem = user
        .doc()
        .nodes()
        .find(|n| matches!(n.content, NodeContent::Csg(_)) && n.id != rounded)
        .expect("the difference")
        .id;
    let solid = hedra_doc::csg::evaluate(user.doc(), emblem).expect("a solid");
    solid.validate().unwrap();
    assert_eq!(solid.stats().genus, Some(5), "{:?}", solid.stats());
    user.frames(3);
    // A click on the solid (the middle of the cube's front face, between
    // the holes) selects the emblem, not the hidden operand under it.
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set([]);
    user.tap(KeyCode::Numpad1);
    user.frames(3);
    let on_face = user.screen_of(Vec3::new(0.75, 0.75, 1.0));
    user.click(on_face);
    assert_eq!(
        user.app
            .world()
            .resource::<hedra_edit::Selection>()
            .active(),
        Some(emblem)
    );
    // Drag the Y cylinder along X: the drawn solid follows before Enter.
    let cylinder = cylinders[0];
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set([cylinder]);
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyG);
    user.tap(KeyCode::KeyX);
    user.type_text("0.3");
    user.frames(3);
    let preview = user
        .app
        .world()
        .resource::<hedra_scene::Previews>()
        .content(emblem)
        .cloned();
    let Some(hedra_scene::PreviewContent::Mesh { mesh: moving, .. }) = preview else {
        panic!("the emblem's solid is re-evaluated during the drag")
    };
    assert!(!std::sync::Arc::ptr_eq(&moving, &solid));
    // What is shown of the emblem is the preview, for the render mesh and
    // for its edge lines alike (the overlay drew the document's solid once).
    let entity = user.app.world().resource::<hedra_scene::NodeEntities>().0[&emblem];
    let shown = user
        .app
        .world()
        .get::<hedra_scene::ShownMesh>(entity)
        .unwrap();
    assert!(shown.previewed && std::sync::Arc::ptr_eq(&shown.cage, &moving));
    let children = user.app.world().get::<Children>(entity).unwrap();
    let overlay = children
        .iter()
        .find_map(|c| user.app.world().get::<hedra_viewport::EdgeOverlay>(c))
        .expect("the emblem's edge overlay");
    assert!(matches!(
        &overlay.source,
        hedra_scene::ContentSource::Mesh(m) if std::sync::Arc::ptr_eq(m, &moving)
    ));
    // The Y hole's rim on the top face (y = 1): vertices 0.55 from its axis.
    let rim = |m: &hedra_geom::HalfEdgeMesh, x: f64| {
        m.vertices()
            .map(|v| m.position(v))
            .filter(|p| (p.y - 1.0).abs() < 1e-9 && ((p.x - x).hypot(p.z) - 0.55).abs() < 1e-6)
            .count()
    };
    // The preview (simplified operands while dragging) has the hole moved.
    assert!(rim(&moving, 0.3) >= 16, "{}", rim(&moving, 0.3));
    assert!(rim(&moving, 0.0) < 4);
    assert!(rim(&solid, 0.0) >= 16);
    user.tap(KeyCode::Enter);
    user.frames(2);
    assert_eq!(user.undo_steps(), steps + 1);
    let after = hedra_doc::csg::evaluate(user.doc(), emblem).unwrap();
    after.validate().unwrap();
    assert!(rim(&after, 0.3) >= 16);
    // Out of the CSG node by the outliner: drag the cylinder's row onto
    // the empty space below the tree.
    let name = user.doc().node(cylinder).unwrap().name.clone();
    let row = user.find(&format!("▣ {name}"));
    // Below the last of the tree's six rows.
    let below = row.y + 220.0;
    user.drag(row, Vec2::new(row.x, below), 8);
    user.frames(3);
    assert_eq!(
        user.doc().node(cylinder).unwrap().parent,
        None,
        "{}",
        user.status()
    );
    let fewer = hedra_doc::csg::evaluate(user.doc(), emblem).unwrap();
    assert_eq!(fewer.stats().genus, Some(3), "one hole less");
}

/// Asks, as the panel's menu would, for `modifier` on the node `name`.
fn set_subdivision(user: &mut User, name: &str, modifier: Option<hedra_doc::SubdivisionModifier>) {
    user.app
        .world_mut()
        .write_message(hedra_scene::DocRequest::Execute(
            hedra_doc::Command::SetSubdivision {
                nodes: vec![hedra_doc::NodeRef::Name(name.into())],
                modifier,
            },
        ));
}

/// Smooth previews being refined in the background.
fn smooth_refinements_running(user: &User) -> usize {
    user.app
        .world()
        .resource::<hedra_scene::SmoothPreviews>()
        .progress()
        .len()
}

/// Draws frames until no smooth preview is refined in the background (at
/// most about 20 s).
fn wait_for_smooth_refinements(user: &mut User) {
    for _ in 0..1000 {
        if smooth_refinements_running(user) == 0 {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
        user.frames(1);
    }
}

/// Draws frames until no background build runs (at most about 12 s).
fn wait_for_background_jobs(user: &mut User) {
    for _ in 0..600 {
        if user
            .app
            .world()
            .resource::<hedra_scene::FileJobs>()
            .progress()
            .is_none()
        {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
        user.frames(1);
    }
}

/// A Decimate modifier on a big mesh (a 260×260 grid, 67,600 quads)
/// builds its progressive record on a worker thread (issue 18): the
/// status bar shows a progress bar while later requests wait, then the
/// command lands as one undo step. Esc during a second build cancels it:
/// nothing changes.
#[test]
fn a_big_decimate_builds_in_the_background_with_progress_and_cancel() {
    let mut user = User::new();
    execute(
        &mut user,
        "AddPrimitive(primitive: Grid(x_segments: 260, z_segments: 260, size: 4.0), name: Some(\"Big\"))",
    );
    let steps = user.undo_steps();
    user.app
        .world_mut()
        .write_message(hedra_scene::DocRequest::Execute(
            ron::from_str("AddModifier(node: Name(\"Big\"), modifier: Decimate(()))").unwrap(),
        ));
    user.frames(1);
    let progress = user
        .app
        .world()
        .resource::<hedra_scene::FileJobs>()
        .progress();
    let (label, _) = progress.expect("a background build");
    // Quads are triangulated first: twice as many faces.
    assert!(label.contains("Decimating 135200 faces"), "{label}");
    assert_eq!(user.undo_steps(), steps, "the command waits for its record");
    // Later requests wait in order: a rename lands after the modifier.
    execute(
        &mut user,
        "Rename(node: Name(\"Big\"), name: \"Decimated\")",
    );
    wait_for_background_jobs(&mut user);
    user.frames(2);
    assert_eq!(user.undo_steps(), steps + 2, "{}", user.status());
    let node = node_named(&user, "Decimated").expect("renamed after the modifier");
    let NodeContent::Mesh(m) = &node.content else {
        panic!("a mesh")
    };
    assert_eq!(m.modifiers.len(), 1);
    assert_eq!(m.decimations.len(), 1, "the record came from the worker");
    // A second build (borders kept: another record), cancelled with Esc.
    user.app
        .world_mut()
        .write_message(hedra_scene::DocRequest::Execute(
            ron::from_str(
                "SetModifier(node: Name(\"Decimated\"), index: 0, modifier: Decimate((keep_borders: true)))",
            )
            .unwrap(),
        ));
    user.frames(1);
    assert!(
        user.app
            .world()
            .resource::<hedra_scene::FileJobs>()
            .progress()
            .is_some()
    );
    user.tap(KeyCode::Escape);
    wait_for_background_jobs(&mut user);
    user.frames(1);
    assert!(user.status().contains("cancelled"), "{}", user.status());
    assert_eq!(user.undo_steps(), steps + 2, "nothing changed");
}

/// Esc cancels a smooth preview that refines in the background (level 4
/// of a 10,000-quad torus): the cage stays on screen and the status line
/// says so. The refinement is held between its steps until Esc is read,
/// because on a loaded machine it finished before the key (at level 3 and
/// at level 4, with the whole suite and other work beside it). The key is
/// read with the other keys, in `SceneSystems::Tools` (issue 34), not by
/// the projection.
#[test]
fn escape_cancels_a_background_subdivision() {
    let mut user = User::new();
    user.app
        .world_mut()
        .resource_mut::<hedra_scene::SmoothPreviews>()
        .hold_background(true);
    execute(
        &mut user,
        "AddPrimitive(primitive: Torus(major_segments: 100, minor_segments: 100, major_radius: 2.0, minor_radius: 0.5), name: Some(\"Ring\"))",
    );
    set_subdivision(
        &mut user,
        "Ring",
        Some(hedra_doc::SubdivisionModifier::with_level(4)),
    );
    user.frames(2);
    assert_eq!(
        smooth_refinements_running(&user),
        1,
        "a background refinement runs: {}",
        user.status()
    );
    user.tap(KeyCode::Escape);
    wait_for_smooth_refinements(&mut user);
    assert_eq!(
        smooth_refinements_running(&user),
        0,
        "the refinement stopped"
    );
    assert!(user.status().contains("cancelled"), "{}", user.status());
}

/// Issue 16, no hitch when a drag starts: giving a mesh a subdivision
/// modifier (Ctrl+3) starts building its stencil table on a worker thread
/// at once, so it is ready before the first vertex is dragged (it used to
/// be built on the first drag frame); the drag then moves the smooth shape.
#[test]
fn the_stencils_of_a_smooth_preview_are_built_before_the_first_drag() {
    let mut user = User::new();
    execute(
        &mut user,
        "AddPrimitive(primitive: Torus(major_segments: 48, minor_segments: 24, major_radius: 1.0, minor_radius: 0.3), name: Some(\"Ring\"))",
    );
    let ring = node_named(&user, "Ring").unwrap().id;
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set([ring]);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::Digit3);
    user.frames(2);
    let mut ready = false;
    for _ in 0..500 {
        user.frames(1);
        if user
            .app
            .world()
            .resource::<hedra_scene::SmoothPreviews>()
            .stencils_ready(ring)
        {
            ready = true;
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    assert!(ready, "the stencils were built without a drag");
    user.tap(KeyCode::Tab);
    user.tap(KeyCode::KeyA);
    user.frames(2);
    let before = user.render_positions();
    user.tap(KeyCode::KeyG);
    user.tap(KeyCode::KeyY);
    user.type_text("1");
    user.frames(2);
    let moved = user.render_positions();
    assert_ne!(before, moved, "the smooth shape follows the drag");
    user.tap(KeyCode::Escape);
}

/// A live intersection whose operands are dragged apart is an empty solid
/// (issue 35): drawn as nothing while G runs and after Enter, its panel
/// says so, nothing is an error, and undo brings the solid back.
#[test]
fn dragging_the_operands_of_a_live_intersection_apart_leaves_an_empty_solid() {
    let mut user = User::new();
    user.add("Cube");
    user.add("Cube");
    user.tap(KeyCode::KeyA);
    open_menu(&mut user, "Object");
    user.click_on("Live CSG Intersection");
    let csg = user
        .doc()
        .nodes()
        .find(|n| matches!(n.content, NodeContent::Csg(_)))
        .expect("the intersection")
        .id;
    user.frames(3);
    let entity = user.app.world().resource::<hedra_scene::NodeEntities>().0[&csg];
    let drawn = |user: &User| user.app.world().get::<Mesh3d>(entity).is_some();
    assert!(drawn(&user), "the solid is drawn");
    // Drag the second cube out along X by typing 5.
    let second = user
        .doc()
        .nodes()
        .filter(|n| n.parent == Some(csg))
        .map(|n| n.id)
        .max()
        .unwrap();
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set([second]);
    let steps = user.undo_steps();
    user.tap(KeyCode::KeyG);
    user.tap(KeyCode::KeyX);
    user.type_text("5");
    user.frames(3);
    assert!(
        !drawn(&user),
        "nothing is drawn while the operands are apart"
    );
    user.tap(KeyCode::Enter);
    user.frames(3);
    assert_eq!(user.undo_steps(), steps + 1);
    let solid = hedra_doc::csg::evaluate(user.doc(), csg).expect("an empty solid, not an error");
    assert_eq!(solid.face_count(), 0);
    assert!(!drawn(&user));
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set([csg]);
    user.frames(2);
    assert!(
        user.shows(
            "Solid: empty (V 0 E 0 F 0): the operands do not overlap as the operation needs"
        ),
        "the panel says so"
    );
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    user.frames(3);
    assert!(drawn(&user), "undo brings the solid back");
    let solid = hedra_doc::csg::evaluate(user.doc(), csg).unwrap();
    assert!((solid.volume() - 8.0).abs() < 1e-9, "{}", solid.volume());
}

/// Tab on a CSG node says that its operands are what is edited (it said
/// "is an empty").
#[test]
fn tab_on_a_csg_node_points_at_its_operands() {
    let mut user = User::new();
    user.add("Cube");
    let command: hedra_doc::Command =
        ron::from_str(r#"AddCsg(op: Difference, operands: [Name("Cube")])"#).unwrap();
    user.app
        .world_mut()
        .write_message(hedra_scene::DocRequest::Execute(command));
    user.frames(2);
    let csg = user
        .doc()
        .nodes()
        .find(|n| matches!(n.content, NodeContent::Csg(_)))
        .expect("a CSG node")
        .id;
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::Selection>()
        .set([csg]);
    user.tap(KeyCode::Tab);
    assert!(user.edit_mode().node.is_none());
    let status = user.status();
    assert!(status.contains("is a CSG node"), "{status}");
}

/// The edit-mode edge lines as drawn.
fn edit_edge_lines(user: &mut User) -> Vec<Vec3> {
    let world = user.app.world_mut();
    let handle = world
        .query_filtered::<&bevy::gizmos::retained::Gizmo, With<hedra_viewport::EditEdges>>()
        .single(world)
        .expect("the edit edges")
        .handle
        .clone();
    world
        .resource::<Assets<bevy::gizmos::GizmoAsset>>()
        .get(&handle)
        .expect("their asset")
        .list_positions
        .clone()
}

/// Both ends of every live edge, in the overlay's order.
fn edge_ends(mesh: &hedra_geom::HalfEdgeMesh) -> Vec<Vec3> {
    mesh.edges()
        .flat_map(|e| mesh.edge_vertices(e).map(|v| mesh.position(v).as_vec3()))
        .collect()
}

/// G on one clicked vertex: the edges at it follow the drag frame by frame,
/// on a whole cube and on one with a deleted edge (a dead slot in the edge
/// ids, so that line `i` is no longer edge `i`).
#[test]
fn the_edit_edges_at_one_dragged_vertex_follow_it() {
    let mut user = User::new();
    user.add("Cube");
    for deleted_edge in [false, true] {
        if deleted_edge {
            user.app
                .world_mut()
                .write_message(hedra_scene::DocRequest::Execute(
                    hedra_doc::Command::DeleteEdges {
                        node: hedra_doc::NodeRef::Name("Cube".into()),
                        edges: hedra_doc::EdgeSet::Ids(vec![0]),
                    },
                ));
            user.frames(2);
            assert_eq!(user.first_mesh().edge_count(), 11);
        }
        user.tap(KeyCode::Tab);
        user.tap(KeyCode::Digit1);
        let cube = user.first_mesh().clone();
        let corner = cube
            .vertices()
            .max_by(|&a, &b| {
                let sum = |v| cube.position(v).element_sum();
                sum(a).total_cmp(&sum(b))
            })
            .unwrap();
        let at = user.screen_of(cube.position(corner).as_vec3());
        user.click(at);
        assert_eq!(
            user.edit_mode()
                .selection
                .vertices
                .iter()
                .copied()
                .collect::<Vec<_>>(),
            vec![corner]
        );
        user.tap(KeyCode::KeyG);
        for step in 1..=3 {
            user.move_to(at + Vec2::new(20.0 * step as f32, -15.0 * step as f32));
            let preview = user
                .edit_mode()
                .preview
                .clone()
                .expect("G previews the mesh");
            let moved: Vec<_> = preview
                .vertices()
                .filter(|&v| preview.position(v) != cube.position(v))
                .collect();
            assert_eq!(moved, vec![corner], "frame {step}: one vertex moves");
            assert_eq!(
                edit_edge_lines(&mut user),
                edge_ends(&preview),
                "frame {step} of the drag, deleted edge: {deleted_edge}"
            );
        }
        user.tap(KeyCode::Escape);
        assert_eq!(
            edit_edge_lines(&mut user),
            edge_ends(&cube),
            "back on the cube"
        );
        user.tap(KeyCode::Tab);
    }
}

/// The edit-mode edges follow a G drag frame by frame (written in place
/// while only positions change) and stay right after Escape.
#[test]
fn the_edit_edges_follow_a_g_drag() {
    let mut user = cube_in_edit_mode(KeyCode::Digit1);
    user.tap(KeyCode::KeyA);
    let centre = user.viewport_center();
    user.tap(KeyCode::KeyG);
    for step in 1..=4 {
        user.move_to(centre + Vec2::new(25.0 * step as f32, -10.0 * step as f32));
        let preview = user
            .edit_mode()
            .preview
            .clone()
            .expect("G previews the mesh");
        assert_eq!(
            edit_edge_lines(&mut user),
            edge_ends(&preview),
            "frame {step} of the drag"
        );
    }
    user.tap(KeyCode::Escape);
    let cube = user.first_mesh().clone();
    assert_eq!(
        edit_edge_lines(&mut user),
        edge_ends(&cube),
        "back on the cube"
    );
}

/// Issue 36, item 1: a drag on a cage whose level-2 preview is too large
/// for stencils (a 161 × 160 grid: 412,160 faces) recomputes and rewrites
/// only what the moved vertex reaches, and the viewport keeps the bounds
/// the mesh is culled by itself (Bevy no longer goes over every position).
/// While G runs, with the wheel turned in the middle of it, and after the
/// click that confirms it, the render mesh is a fresh refinement of the
/// shown cage, and its bounds hold every position.
#[test]
fn a_drag_on_a_large_smooth_preview_shows_the_moved_shape_within_its_bounds() {
    use bevy::camera::primitives::Aabb;
    use hedra_doc::smooth::SmoothRefinement;
    let mut user = User::new();
    execute(
        &mut user,
        "AddPrimitive(primitive: Grid(x_segments: 161, z_segments: 160, size: 4.0), name: Some(\"Sheet\"))",
    );
    set_subdivision(
        &mut user,
        "Sheet",
        Some(hedra_doc::SubdivisionModifier::with_level(2)),
    );
    user.frames(2);
    wait_for_smooth_refinements(&mut user);
    user.frames(2);
    let sheet = node_named(&user, "Sheet").unwrap().id;
    let entity = user.app.world().resource::<hedra_scene::NodeEntities>().0[&sheet];
    // The fresh refinement of what the node shows, flat shaded, and
    // whether the entity's bounds hold every drawn position.
    let check = |user: &mut User, when: &str| {
        let shown = user
            .app
            .world()
            .get::<hedra_scene::ShownMesh>(entity)
            .expect("shown")
            .cage
            .clone();
        let modifier = hedra_doc::SubdivisionModifier::with_level(2);
        let mut fresh = SmoothRefinement::new(
            &shown,
            &hedra_geom::subdivision::Creases::default(),
            &modifier,
        )
        .unwrap();
        let points = fresh.points(&shown);
        let (expected, _) = fresh.attributes(&points, hedra_doc::Shading::Flat);
        let drawn = user.render_positions();
        assert_eq!(
            drawn.len(),
            expected.len(),
            "{when}: the level-2 preview is drawn"
        );
        assert!(
            drawn
                .iter()
                .zip(&expected)
                .all(|(a, b)| *a == Vec3::from(*b)),
            "{when}: the drawn shape is the refinement of the shown cage"
        );
        let aabb = *user.app.world().get::<Aabb>(entity).expect("bounds");
        let (min, max) = (Vec3::from(aabb.min()), Vec3::from(aabb.max()));
        assert!(
            drawn
                .iter()
                .all(|p| p.cmpge(min).all() && p.cmple(max).all()),
            "{when}: a position lies outside the bounds {min} … {max}"
        );
    };
    check(&mut user, "before the drag");
    user.tap(KeyCode::Tab);
    let mesh = user.first_mesh().clone();
    let middle = mesh
        .vertices()
        .min_by(|a, b| {
            let (pa, pb) = (mesh.position(*a), mesh.position(*b));
            pa.length().total_cmp(&pb.length())
        })
        .unwrap();
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::EditMode>()
        .selection
        .vertices = [middle].into_iter().collect();
    user.frames(1);
    let centre = user.viewport_center();
    user.move_to(centre);
    // Up, off the sheet: the bounds must grow to hold the moved corners.
    user.tap(KeyCode::KeyG);
    user.tap(KeyCode::KeyY);
    user.glide_to(centre + Vec2::new(0.0, -120.0), 6);
    check(&mut user, "during G");
    user.wheel(2.0);
    user.glide_to(centre + Vec2::new(0.0, -200.0), 4);
    check(&mut user, "during G, after the wheel");
    user.click(user.cursor());
    user.frames(3);
    assert!(
        user.doc().nodes().any(|n| match &n.content {
            NodeContent::Mesh(m) => m.mesh.position(middle).length() > 1e-3,
            _ => false,
        }),
        "the vertex moved: {}",
        user.status()
    );
    check(&mut user, "after the click");
}

/// The bounds a cage's render mesh is culled by follow a drag that moves
/// its vertices off it (the viewport keeps them, growing them by the moved
/// vertices, instead of Bevy going over every position): while G runs and
/// after the click, every drawn position is within them.
#[test]
fn a_cage_drag_keeps_every_drawn_position_within_the_bounds() {
    use bevy::camera::primitives::Aabb;
    let mut user = User::new();
    execute(
        &mut user,
        "AddPrimitive(primitive: Grid(x_segments: 20, z_segments: 20, size: 4.0), name: Some(\"Sheet\"))",
    );
    user.frames(2);
    let sheet = node_named(&user, "Sheet").unwrap().id;
    let entity = user.app.world().resource::<hedra_scene::NodeEntities>().0[&sheet];
    let within = |user: &User, when: &str| {
        let aabb = *user.app.world().get::<Aabb>(entity).expect("bounds");
        let (min, max) = (Vec3::from(aabb.min()), Vec3::from(aabb.max()));
        let drawn = user.render_positions();
        assert!(
            drawn
                .iter()
                .all(|p| p.cmpge(min).all() && p.cmple(max).all()),
            "{when}: a position lies outside the bounds {min} … {max}"
        );
        max.y
    };
    assert_eq!(within(&user, "before"), 0.0, "a flat sheet");
    user.tap(KeyCode::Tab);
    let mesh = user.first_mesh().clone();
    let corner = mesh.vertices().next().unwrap();
    user.app
        .world_mut()
        .resource_mut::<hedra_edit::EditMode>()
        .selection
        .vertices = [corner].into_iter().collect();
    user.frames(1);
    let centre = user.viewport_center();
    user.move_to(centre);
    user.tap(KeyCode::KeyG);
    user.tap(KeyCode::KeyY);
    user.glide_to(centre + Vec2::new(0.0, -150.0), 5);
    assert!(within(&user, "during G") > 0.0, "the box grew upwards");
    user.click(user.cursor());
    user.frames(3);
    within(&user, "after the click");
}
