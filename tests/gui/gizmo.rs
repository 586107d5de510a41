//! The transform gizmo dragged with the mouse, in object mode, mesh edit
//! mode and control-point mode (issue 12, part 5): one undo step per drag,
//! a preview while dragging, exact values for what the drag did not touch,
//! Esc or a right click puts everything back.

use crate::modeling::cube_in_edit_mode;
use crate::user::User;
use bevy::gizmos::transform_gizmo::{TransformGizmoAxis, TransformGizmoState};
use bevy::prelude::*;
use hedra_doc::NodeTransform;
use hedra_geom::DVec3;

fn gizmo(user: &User) -> &TransformGizmoState {
    user.app.world().resource::<TransformGizmoState>()
}

/// Where the gizmo's X arrow is under the pointer: searched along the
/// screen direction of world X from the gizmo's centre `centre`, as a
/// person moves the pointer onto the arrow until it lights up.
fn x_handle(user: &mut User, centre: Vec3) -> Vec2 {
    let from = user.screen_of(centre);
    let dir = (user.screen_of(centre + Vec3::X * 0.2) - from).normalize();
    for step in 4..60 {
        let at = from + dir * (step as f32 * 4.0);
        user.move_to(at);
        user.frame();
        if gizmo(user).hovered_axis == Some(TransformGizmoAxis::X) {
            return at + dir * 4.0;
        }
    }
    panic!("no X arrow of the gizmo near {from}");
}

/// Drags the X arrow `pixels` along its screen direction and checks that
/// the drag previews before it lets go. Returns without letting go when
/// `release` is false.
fn drag_x(user: &mut User, centre: Vec3, pixels: f32, release: bool) {
    let at = x_handle(user, centre);
    let dir = (user.screen_of(centre + Vec3::X * 0.2) - user.screen_of(centre)).normalize();
    user.button_down(MouseButton::Left);
    user.frames(2);
    assert!(gizmo(user).active, "the press grabs the arrow");
    user.glide_to(at + dir * pixels, 6);
    if release {
        user.button_up(MouseButton::Left);
        user.frames(2);
    }
}

fn first_node_transform(user: &User) -> NodeTransform {
    user.doc().nodes().next().unwrap().transform
}

fn first_entity_transform(user: &User) -> Transform {
    let world = user.app.world();
    let e = *world
        .resource::<hedra_scene::NodeEntities>()
        .0
        .values()
        .next()
        .unwrap();
    *world.get::<Transform>(e).unwrap()
}

#[test]
fn dragging_the_gizmo_moves_an_object_in_one_step_and_keeps_the_rest_exact() {
    let mut user = User::new();
    user.add("Cube");
    // A rotation and scale that f32 cannot hold exactly.
    let exact = NodeTransform {
        translation: DVec3::ZERO,
        rotation: hedra_geom::DQuat::from_rotation_y(0.1),
        scale: DVec3::splat(1.0 / 3.0),
    };
    user.app
        .world_mut()
        .write_message(hedra_scene::DocRequest::Execute(
            hedra_doc::Command::SetTransforms {
                nodes: vec![(hedra_doc::NodeRef::Name("Cube".into()), exact)],
            },
        ));
    user.frames(2);
    let steps = user.undo_steps();
    drag_x(&mut user, Vec3::ZERO, 80.0, false);
    assert_eq!(first_node_transform(&user), exact, "the document waits");
    assert!(
        first_entity_transform(&user).translation.x > 0.2,
        "the object follows the drag on screen: {:?}",
        first_entity_transform(&user)
    );
    // The Location field follows the drag too.
    let x = first_entity_transform(&user).translation.x;
    let shown: Vec<f32> = user
        .widgets()
        .iter()
        .filter_map(|w| w.text.strip_prefix("X ")?.parse().ok())
        .collect();
    assert!(
        shown.iter().any(|v| (v - x).abs() < 1e-3),
        "Location X shows {x} during the drag: {shown:?}"
    );
    user.button_up(MouseButton::Left);
    user.frames(2);
    let t = first_node_transform(&user);
    assert_eq!(user.undo_steps(), steps + 1, "one undo step");
    assert!(t.translation.x > 0.2, "moved along X: {t:?}");
    assert_eq!(
        t.translation.x,
        format!("{:.4}", t.translation.x).parse::<f64>().unwrap(),
        "lands on the 4 decimals the Location field shows, not f32 noise"
    );
    assert_eq!((t.translation.y, t.translation.z), (0.0, 0.0));
    assert_eq!(t.rotation, exact.rotation, "rotation stays exact");
    assert_eq!(t.scale, exact.scale, "scale stays exact");
    assert_eq!(
        first_entity_transform(&user),
        hedra_scene::bevy_transform(&t),
        "the screen shows the result"
    );
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    assert_eq!(first_node_transform(&user), exact);
}

#[test]
fn the_gizmo_moves_the_selected_vertices_in_edit_mode() {
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    let top = user.screen_of(Vec3::Y);
    user.click(top);
    assert_eq!(user.edit_mode().selection.faces.len(), 1);
    let before: Vec<DVec3> = user.first_mesh().positions().to_vec();
    let steps = user.undo_steps();
    // The gizmo sits on the centre of the top face.
    drag_x(&mut user, Vec3::Y, 60.0, true);
    user.first_mesh().validate().unwrap();
    assert_eq!(user.undo_steps(), steps + 1, "one undo step");
    let after = user.first_mesh().positions().to_vec();
    let mut moved = 0;
    let mut dx = None;
    for (a, b) in before.iter().zip(&after) {
        if a != b {
            moved += 1;
            let d = *b - *a;
            assert!(d.x > 0.1 && d.y.abs() < 1e-6 && d.z.abs() < 1e-6, "{d}");
            let first = *dx.get_or_insert(d.x);
            assert!((d.x - first).abs() < 1e-9, "all move alike");
        } else {
            assert!(a.y < 0.0, "only the top face's vertices move");
        }
    }
    assert_eq!(moved, 4, "the top face's four vertices moved");
    assert!(user.edit_mode().node.is_some(), "still in edit mode");
}

#[test]
fn the_gizmo_moves_a_control_point_and_escape_puts_it_back() {
    let mut user = User::new();
    user.add("NURBS Surface");
    user.tap(KeyCode::Tab);
    let node = user.doc().nodes().next().unwrap();
    let points = hedra_edit::shape_mode::control_points(&node.content);
    let target = (0..points.len())
        .min_by(|&a, &b| points[a].length().total_cmp(&points[b].length()))
        .unwrap();
    let p = points[target].as_vec3();
    let at = user.screen_of(p);
    user.click(at);
    let steps = user.undo_steps();
    let render_before = user.render_positions();

    // Esc in the middle of a drag: nothing changes.
    drag_x(&mut user, p, 60.0, false);
    assert_ne!(
        user.render_positions(),
        render_before,
        "the surface previews"
    );
    user.tap(KeyCode::Escape);
    user.button_up(MouseButton::Left);
    user.frames(2);
    assert_eq!(user.undo_steps(), steps, "Esc: no step");
    let node = user.doc().nodes().next().unwrap();
    assert_eq!(
        hedra_edit::shape_mode::control_points(&node.content),
        points
    );
    assert_eq!(
        user.render_positions(),
        render_before,
        "the surface is back"
    );

    // A drag to the end: one step, the point moved along X only.
    drag_x(&mut user, p, 60.0, true);
    assert_eq!(user.undo_steps(), steps + 1);
    let node = user.doc().nodes().next().unwrap();
    let after = hedra_edit::shape_mode::control_points(&node.content);
    let d = after[target] - points[target];
    assert!(d.x > 0.1 && d.y.abs() < 1e-6 && d.z.abs() < 1e-6, "{d}");
    for (i, (a, b)) in points.iter().zip(&after).enumerate() {
        if i != target {
            assert_eq!(a, b, "point {i} stays");
        }
    }
    assert_ne!(
        user.render_positions(),
        render_before,
        "the surface follows"
    );
}

/// View ▸ Gizmo: scale, then a drag of the X handle in edit mode widens
/// the selected face along X about its centre, in one step.
#[test]
fn the_view_menu_makes_a_scale_gizmo_that_scales_the_selection() {
    use bevy::gizmos::transform_gizmo::{TransformGizmoMode, TransformGizmoSettings};
    let mut user = cube_in_edit_mode(KeyCode::Digit3);
    let top = user.screen_of(Vec3::Y);
    user.click(top);
    user.click_on("View");
    user.click_on("Gizmo: scale");
    let mode = user.app.world().resource::<TransformGizmoSettings>().mode;
    assert_eq!(mode, TransformGizmoMode::Scale);
    let before: Vec<DVec3> = user.first_mesh().positions().to_vec();
    let steps = user.undo_steps();
    drag_x(&mut user, Vec3::Y, 60.0, true);
    assert_eq!(user.undo_steps(), steps + 1, "one undo step");
    let after = user.first_mesh().positions().to_vec();
    for (a, b) in before.iter().zip(&after) {
        if a.y > 0.0 {
            assert!(b.x.abs() > a.x.abs() + 0.05, "{a} -> {b}: wider along X");
            assert_eq!(b.x.signum(), a.x.signum(), "about the centre");
            assert!((b.y - a.y).abs() < 1e-9 && (b.z - a.z).abs() < 1e-9);
        } else {
            assert_eq!(a, b, "the bottom stays");
        }
    }
}
