//! The whole app used as a person uses it: keys, clicks held over several
//! frames, drags and the wheel go in through Bevy's input messages (see
//! `user.rs`), and the document, the selection, the status line and the
//! render meshes are checked after.

mod architecture_doc;
mod convert;
mod files;
mod gizmo;
mod kept;
mod modeling;
mod monkey;
mod slow_machine;
mod user;
mod writers;

use bevy::prelude::*;
use user::{HOLD, User};

/// Opens the Shift+A menu at the viewport's centre.
fn open_add_menu(user: &mut User) {
    let at = user.viewport_center();
    user.open_add_menu_at(at);
}

#[test]
fn shift_a_cube_takes_a_click_of_any_length() {
    // None: pressed and released within one frame.
    for hold in [None, Some(0), Some(1), Some(HOLD), Some(12), Some(30)] {
        let mut user = User::new();
        open_add_menu(&mut user);
        check_cube_added_by_a_click(&mut user, hold);
    }
    // Opened near each corner of the viewport (the menu moves to fit).
    for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
        let mut user = User::new();
        let inner = user.viewport().shrink(20.0);
        let corner = Vec2::new(inner.center().x, inner.center().y)
            + Vec2::new(sx * inner.width(), sy * inner.height()) / 2.0;
        user.open_add_menu_at(corner);
        check_cube_added_by_a_click(&mut user, Some(HOLD));
    }
}

/// Clicks Cube in the open Add menu, holding the button `hold` frames
/// (`None`: pressed and released in one frame), and checks the cube.
fn check_cube_added_by_a_click(user: &mut User, hold: Option<usize>) {
    let cube = user.find("Cube");
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
        user.app
            .world()
            .resource::<hedra_ui::UiState>()
            .add_menu_at
            .is_none(),
        "the menu closes after the click"
    );
}

/// Adds a cube through the Shift+A menu, as a person does.
fn add_cube(user: &mut User) {
    open_add_menu(user);
    user.click_on("Cube");
    assert_eq!(user.node_names(), ["Cube"]);
}

fn vertex_count(user: &User) -> usize {
    let node = user.doc().nodes().next().unwrap();
    node.content.mesh().unwrap().vertex_count()
}

#[test]
fn the_menu_bar_add_menu_takes_held_clicks() {
    let mut user = User::new();
    user.click_on("Add");
    user.click_on("Cube");
    assert_eq!(user.node_names(), ["Cube"]);
    assert!(!user.shows("Torus"), "the menu closed");
}

/// M in vertex mode: the merge menu at the cursor; a held click on At
/// Center merges the two clicked corners of the cube's top face. Then the
/// Adjust Last window's Merge at choice, a combo box, switches to First.
#[test]
fn the_merge_menu_and_adjust_last_take_held_clicks() {
    let mut user = User::new();
    add_cube(&mut user);
    user.tap(KeyCode::Tab);
    user.tap(KeyCode::Digit1);
    let a = user.screen_of(Vec3::new(1.0, 1.0, 1.0));
    let b = user.screen_of(Vec3::new(-1.0, 1.0, 1.0));
    user.click(a);
    user.key_down(KeyCode::ShiftLeft);
    user.click(b);
    user.key_up(KeyCode::ShiftLeft);
    // Near the bottom right corner the menu must move to fit the window.
    let corner = user.viewport().shrink(20.0).right_bottom();
    let corner = Vec2::new(corner.x, corner.y);
    user.move_to(corner);
    user.tap(KeyCode::KeyM);
    assert!(user.shows("At Center"), "M shows the merge menu");
    user.click_on("At Center");
    assert_eq!(vertex_count(&user), 7, "{}", user.status());
    assert!(!user.shows("At Center"), "the menu closed");
    let merged = user.doc().nodes().next().unwrap().content.mesh().unwrap();
    merged.validate().unwrap();
    let steps = user.undo_steps();

    // Adjust Last: open the combo box (it says "Center"), pick "First".
    user.click_on("Center");
    user.click_on("First");
    let mesh = user.doc().nodes().next().unwrap().content.mesh().unwrap();
    assert_eq!(mesh.vertex_count(), 7);
    assert!(
        mesh.positions()
            .iter()
            .any(|p| (p.x - 1.0).abs() < 1e-12 && p.y == 1.0 && p.z == 1.0),
        "merged at the first clicked corner (1, 1, 1)"
    );
    assert_eq!(user.undo_steps(), steps, "Adjust Last replaces the step");
}

/// Right click on a node in the outliner, then a held click on Delete.
#[test]
fn the_outliner_context_menu_takes_a_held_click() {
    let mut user = User::new();
    add_cube(&mut user);
    let row = user.find("▣ Cube");
    user.move_to(row);
    user.button_down(MouseButton::Right);
    user.frames(HOLD);
    user.button_up(MouseButton::Right);
    user.frames(2);
    user.click_on("Delete");
    assert!(user.node_names().is_empty(), "{}", user.status());
    assert_eq!(user.undo_steps(), 2);
}

/// Ctrl+N with unsaved changes asks first; a held click on Don't Save
/// starts the new scene.
#[test]
fn the_unsaved_changes_dialog_takes_a_held_click() {
    let mut user = User::new();
    add_cube(&mut user);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyN);
    assert!(
        user.shows("Don't Save"),
        "Ctrl+N asks about the unsaved cube"
    );
    assert_eq!(user.node_names(), ["Cube"], "nothing is lost while it asks");
    user.click_on("Don't Save");
    assert!(user.node_names().is_empty());
    assert!(!user.shows("Don't Save"));
}

/// A held click on a step of Edit ▸ Undo History goes back to it.
#[test]
fn the_undo_history_takes_a_held_click() {
    let mut user = User::new();
    add_cube(&mut user);
    add_cube_again(&mut user);
    user.click_on("Edit");
    user.click_on("Undo History");
    user.click_on("Original");
    assert!(user.node_names().is_empty(), "back to the original scene");
}

fn add_cube_again(user: &mut User) {
    open_add_menu(user);
    user.click_on("Cube");
    assert_eq!(user.node_names().len(), 2);
}

/// The Properties panel shows a fresh cube's rotation as 0, not "-0.0".
#[test]
fn properties_show_zero_angles_without_a_minus_sign() {
    let mut user = User::new();
    add_cube(&mut user);
    let texts: Vec<String> = user.widgets().iter().map(|w| w.text.clone()).collect();
    assert!(
        !texts.iter().any(|t| t.contains("-0.0")),
        "no negative zero shown: {texts:?}"
    );
    assert!(texts.iter().any(|t| t == "Z 0.0"), "{texts:?}");
}

/// The mesh material as the shading leaves it: (alpha, blended).
fn mesh_material(user: &User) -> (f32, bool) {
    let handle = user
        .app
        .world()
        .resource::<hedra_scene::MeshMaterial>()
        .0
        .clone();
    let materials = user.app.world().resource::<Assets<StandardMaterial>>();
    let m = materials.get(&handle).expect("the mesh material");
    (
        m.base_color.alpha(),
        matches!(m.alpha_mode, AlphaMode::Blend),
    )
}

/// Shift+Z and Alt+Z (Blender) and View ▸ Wireframe / X-ray switch the
/// shading: faces vanish in wireframe, turn see-through in X-ray and are
/// opaque again when both are off; inside a G move, Shift+Z is the axis key
/// and leaves the shading alone.
#[test]
fn shift_z_and_alt_z_switch_wireframe_and_x_ray() {
    let mut user = User::new();
    user.add("Cube");
    let shading = |user: &User| *user.app.world().resource::<hedra_scene::ViewportShading>();
    assert_eq!(mesh_material(&user), (1.0, false), "solid at start");
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::KeyZ);
    assert!(shading(&user).wireframe, "{}", user.status());
    assert_eq!(
        mesh_material(&user),
        (0.0, true),
        "wireframe hides the faces"
    );
    user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyZ);
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::KeyZ);
    assert_eq!(
        shading(&user),
        hedra_scene::ViewportShading {
            wireframe: false,
            x_ray: true,
            ..Default::default()
        }
    );
    assert_eq!(
        mesh_material(&user),
        (hedra_scene::X_RAY_ALPHA, true),
        "X-ray"
    );
    // The X-ray opacity (View ▸ X-ray's percent field) sets the faces'
    // alpha. Set on the resource: typing into a field inside an open menu
    // was timing-dependent when the whole suite ran in parallel.
    user.click_on("View");
    assert!(user.shows("35% opaque"), "the field shows the default");
    user.tap(KeyCode::Escape);
    let set_opacity = |user: &mut User, percent: u8| {
        user.app
            .world_mut()
            .resource_mut::<hedra_scene::ViewportShading>()
            .x_ray_opacity = percent;
        user.frames(2);
    };
    set_opacity(&mut user, 60);
    assert_eq!(mesh_material(&user), (0.6, true), "X-ray at 60 %");
    set_opacity(&mut user, 35);
    user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyZ);
    assert_eq!(mesh_material(&user), (1.0, false), "solid again");
    // The View menu says the same and sets the same.
    user.click_on("View");
    user.click_on("Wireframe\tShift+Z");
    assert!(shading(&user).wireframe);
    assert_eq!(mesh_material(&user), (0.0, true));
    user.tap(KeyCode::Escape);
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::KeyZ);
    assert_eq!(shading(&user), hedra_scene::ViewportShading::default());
    // G, Shift+Z (move on X and Y), Esc: the shading did not change.
    user.move_to(user.viewport_center());
    user.tap(KeyCode::KeyG);
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::KeyZ);
    user.tap(KeyCode::Escape);
    assert_eq!(shading(&user), hedra_scene::ViewportShading::default());
    // Z alone: Blender's shading choice at the pointer.
    user.tap(KeyCode::KeyZ);
    assert!(user.shows("Face Orientation"), "the Z menu is open");
    user.click_on("Wireframe\tShift+Z");
    assert!(shading(&user).wireframe);
    assert!(!user.shows("Face Orientation"), "a choice closes it");
    user.tap(KeyCode::KeyZ);
    user.click_on("Solid");
    assert_eq!(shading(&user), hedra_scene::ViewportShading::default());
    user.tap(KeyCode::KeyZ);
    user.click_on("Shade Smooth");
    let node = user.doc().nodes().next().unwrap();
    let hedra_doc::NodeContent::Mesh(content) = &node.content else {
        panic!("a mesh")
    };
    assert_eq!(
        content.shading,
        hedra_doc::Shading::Smooth,
        "the selected cube"
    );
    assert!(!user.shows("Face Orientation"), "closed after the choice");
    // While G runs, Z is the axis, not the menu.
    user.move_to(user.viewport_center());
    user.tap(KeyCode::KeyG);
    assert!(
        user.app
            .world()
            .resource::<hedra_edit::TransformTool>()
            .active
            .is_some()
    );
    user.tap(KeyCode::KeyZ);
    assert!(!user.shows("Face Orientation"));
    user.tap(KeyCode::Escape);
}

/// View ▸ Statistics shows Blender's counts in the viewport: objects and
/// the cages' vertices, edges, faces and triangles in object mode, the
/// selected and total elements in edit mode; they follow an edit.
#[test]
fn the_statistics_overlay_counts_the_scene_and_the_selection() {
    let mut user = User::new();
    user.add("Cube");
    assert!(!user.shows("Triangles 12"), "off by default");
    user.click_on("View");
    user.click_on("Statistics");
    user.tap(KeyCode::Escape);
    for line in [
        "Objects 1/1",
        "Vertices 8",
        "Edges 12",
        "Faces 6",
        "Triangles 12",
    ] {
        assert!(user.shows(line), "{line}");
    }
    // Smoothed to level 2 (Ctrl+2): what is shown is counted, not the cage
    // (issue 31: level 4 still counted 6 faces).
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::Digit2);
    for line in ["Vertices 98", "Edges 192", "Faces 96", "Triangles 192"] {
        assert!(user.shows(line), "{line} at level 2");
    }
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::Digit0);
    assert!(user.shows("Faces 6"), "Ctrl+0: the cage again");
    user.move_to(user.viewport_center());
    user.tap(KeyCode::Tab);
    user.tap(KeyCode::Digit3);
    user.tap(KeyCode::KeyA);
    for line in ["Vertices 8/8", "Edges 12/12", "Faces 6/6", "Triangles 12"] {
        assert!(user.shows(line), "{line}");
    }
    user.shortcut(&[KeyCode::AltLeft], KeyCode::KeyA);
    assert!(user.shows("Vertices 0/8"), "nothing selected");
    assert!(user.shows("Faces 0/6"));
    // One face, then its triangulation: the totals follow (13 edges, 7 faces).
    let top = user.screen_of(Vec3::Y);
    user.click(top);
    assert!(user.shows("Vertices 4/8") && user.shows("Edges 4/12") && user.shows("Faces 1/6"));
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyT);
    let shown = |user: &User, prefix: &str, total: &str| {
        user.widgets()
            .iter()
            .any(|w| w.text.starts_with(prefix) && w.text.ends_with(total))
    };
    assert!(shown(&user, "Edges ", "/13") && shown(&user, "Faces ", "/7"));
    assert!(
        user.shows("Triangles 12"),
        "a cube's triangle count does not change"
    );
}

/// Shift+right click on the cube's top puts the 3D cursor on that face; a
/// cube added next goes there; View ▸ Cursor to World Origin and Cursor to
/// Selected move it back and to the selected object.
#[test]
fn shift_right_click_places_the_3d_cursor_where_objects_are_added() {
    let cursor = |user: &User| user.app.world().resource::<hedra_scene::Cursor3d>().0;
    let mut user = User::new();
    user.add("Cube");
    let top = user.screen_of(Vec3::new(0.3, 1.0, 0.2));
    user.move_to(top);
    user.key_down(KeyCode::ShiftLeft);
    user.button_down(MouseButton::Right);
    user.frames(2);
    user.button_up(MouseButton::Right);
    user.key_up(KeyCode::ShiftLeft);
    user.frames(2);
    let at = cursor(&user);
    assert!((at.y - 1.0).abs() < 1e-4, "on the top face: {at}");
    assert!(
        (at.x - 0.3).abs() < 0.02 && (at.z - 0.2).abs() < 0.02,
        "{at}"
    );
    user.add("Cube");
    let added = user.doc().nodes().last().unwrap().transform.translation;
    assert_eq!(added, at, "the new cube is at the cursor");
    user.click_on("View");
    user.click_on("Cursor to World Origin");
    assert_eq!(cursor(&user), hedra_geom::DVec3::ZERO);
    // The new cube is selected: Cursor to Selected puts it back there.
    user.click_on("View");
    user.click_on("Cursor to Selected");
    assert_eq!(cursor(&user), at);
}

/// View ▸ Face Orientation: the cube's render mesh takes the blue front
/// material and gets a child drawing the same mesh in red on back faces;
/// turned off, the shared material comes back and the child goes.
#[test]
fn face_orientation_colours_front_and_back_faces() {
    let mut user = User::new();
    user.add("Cube");
    let materials = user
        .app
        .world()
        .resource::<hedra_scene::FaceOrientationMaterials>()
        .clone();
    let shared = user
        .app
        .world()
        .resource::<hedra_scene::MeshMaterial>()
        .0
        .clone();
    let look = |user: &mut User| {
        let world = user.app.world_mut();
        let mut meshes = world
            .query_filtered::<(Entity, &Mesh3d, &MeshMaterial3d<StandardMaterial>), (
                With<hedra_scene::NodeEntity>,
                Without<hedra_scene::BackFaces>,
            )>();
        let (e, mesh, material) = meshes.single(world).unwrap();
        let (e, mesh, material) = (e, mesh.0.clone(), material.0.clone());
        let mut backs = world.query_filtered::<(&Mesh3d, &MeshMaterial3d<StandardMaterial>, &ChildOf), With<hedra_scene::BackFaces>>();
        let backs: Vec<_> = backs
            .iter(world)
            .map(|(m, mat, p)| (m.0.clone(), mat.0.clone(), p.parent()))
            .collect();
        (e, mesh, material, backs)
    };
    user.click_on("View");
    user.click_on("Face Orientation");
    user.frames(2);
    let (cube, mesh, material, backs) = look(&mut user);
    assert_eq!(material, materials.front, "blue on the front faces");
    assert_eq!(
        backs,
        vec![(mesh, materials.back.clone(), cube)],
        "red behind, same mesh"
    );
    user.tap(KeyCode::Escape);
    user.click_on("View");
    user.click_on("Face Orientation");
    user.frames(2);
    let (_, _, material, backs) = look(&mut user);
    assert_eq!(material, shared);
    assert!(backs.is_empty());
}

/// Shift+S opens the snap menu at the pointer: Selection to Cursor moves
/// the selected cube's origin onto the 3D cursor in one undo step, Cursor
/// to World Origin puts the cursor back.
#[test]
fn shift_s_snaps_the_selection_to_the_cursor_and_back() {
    let cursor = |user: &User| user.app.world().resource::<hedra_scene::Cursor3d>().0;
    let mut user = User::new();
    user.add("Cube");
    user.app
        .world_mut()
        .resource_mut::<hedra_scene::Cursor3d>()
        .0 = hedra_geom::DVec3::new(2.0, 0.5, -1.0);
    let steps = user.undo_steps();
    user.move_to(user.viewport_center());
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::KeyS);
    assert!(
        user.shows("Selection to Cursor"),
        "Shift+S shows the snap menu"
    );
    user.click_on("Selection to Cursor");
    let t = user.doc().nodes().next().unwrap().transform.translation;
    assert_eq!(t, hedra_geom::DVec3::new(2.0, 0.5, -1.0));
    assert_eq!(user.undo_steps(), steps + 1);
    assert!(!user.shows("Selection to Cursor"), "the menu closed");
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::KeyS);
    user.click_on("Cursor to World Origin");
    assert_eq!(cursor(&user), hedra_geom::DVec3::ZERO);
}

/// F1 shows the keys of the current mode, from the keymap the shortcuts
/// use: object mode lists Shift+D, edit mode the knife on K; Esc closes it;
/// the Mesh menu's items carry the same table's keys.
#[test]
fn f1_lists_the_keys_of_the_current_mode() {
    let mut user = User::new();
    user.add("Cube");
    user.tap(KeyCode::F1);
    assert!(user.shows("Keys: Object mode"));
    assert!(user.shows("Shift+D") && user.shows("duplicate and move"));
    assert!(!user.shows("K"), "no edit-mode keys in object mode");
    user.tap(KeyCode::Escape);
    assert!(!user.shows("Keys: Object mode"), "Esc closes it");
    user.shortcut(&[KeyCode::ShiftLeft], KeyCode::Slash);
    assert!(user.shows("Keys: Object mode"), "? opens it too");
    user.tap(KeyCode::Escape);
    user.tap(KeyCode::Tab);
    user.tap(KeyCode::F1);
    assert!(user.shows("Keys: Edit mode"));
    assert!(user.shows("K") && user.shows("knife: click points, Enter cuts"));
    assert!(user.shows("X, Delete"), "an action's chords on one row");
    user.tap(KeyCode::F1);
    assert!(!user.shows("Keys: Edit mode"), "F1 again closes it");
    let bar = user
        .find_all("Mesh")
        .into_iter()
        .min_by(|a, b| a.min.y.total_cmp(&b.min.y))
        .expect("the Mesh menu");
    user.click(Vec2::new(bar.center().x, bar.center().y));
    assert!(user.shows("Triangulate Faces\tCtrl+T"));
    assert!(user.shows("Dissolve Edges\tCtrl+X"));
    user.tap(KeyCode::Escape);
    // Every menu's keys come from the same table.
    user.click_on("View");
    assert!(user.shows("Quad View\tCtrl+Alt+Q"));
    user.tap(KeyCode::Escape);
    user.click_on("Edit");
    assert!(user.shows("Redo\tCtrl+Shift+Z, Ctrl+Y"));
    user.tap(KeyCode::Escape);

    // The keys that work in every mode are listed under the mode's own;
    // while a tool runs, its keys come first.
    user.tap(KeyCode::Tab);
    user.tap(KeyCode::F1);
    assert!(user.shows("quad view: top, front, right and perspective"));
    // A heading is two widgets (its text run and its label) at one place.
    let y = |user: &User, text: &str| user.find_all(text)[0].center().y;
    assert!(
        y(&user, "Everywhere") > y(&user, "select all"),
        "the mode's own keys come first"
    );
    user.tap(KeyCode::F1);
    user.move_to(user.viewport_center());
    user.tap(KeyCode::KeyG);
    user.tap(KeyCode::F1);
    assert!(
        y(&user, "While a tool runs") < y(&user, "Everywhere"),
        "G runs: its keys come first"
    );
    assert!(user.shows("only along X (again: free)"));
    user.tap(KeyCode::Escape);

    // Control-point mode has its own table.
    let mut user = User::new();
    user.add("NURBS Surface");
    user.tap(KeyCode::Tab);
    user.tap(KeyCode::F1);
    assert!(user.shows("Keys: Control-point mode"));
    assert!(user.shows("insert a knot where the pointer is (the shape stays)"));
}

/// `.` makes the 3D cursor the pivot: S 2 on a cube at the origin with the
/// cursor at (2, 0, 0) doubles its size and moves it to (−2, 0, 0), as
/// Blender's 3D Cursor pivot does; `.` again gives the median back.
#[test]
fn the_3d_cursor_as_pivot_scales_about_the_cursor() {
    let mut user = User::new();
    user.add("Cube");
    user.app
        .world_mut()
        .resource_mut::<hedra_scene::Cursor3d>()
        .0 = hedra_geom::DVec3::new(2.0, 0.0, 0.0);
    user.tap(KeyCode::Period);
    assert!(user.status().contains("3D Cursor"), "{}", user.status());
    let center = user.viewport_center();
    user.move_to(center + Vec2::new(60.0, 0.0));
    user.tap(KeyCode::KeyS);
    user.type_text("2");
    user.tap(KeyCode::Enter);
    let t = user.doc().nodes().next().unwrap().transform;
    assert_eq!(t.scale, hedra_geom::DVec3::splat(2.0));
    assert!(
        (t.translation - hedra_geom::DVec3::new(-2.0, 0.0, 0.0)).length() < 1e-12,
        "{t:?}"
    );
    user.tap(KeyCode::Period);
    assert!(user.status().contains("Median Point"), "{}", user.status());
}

/// Ctrl+Alt+Q splits the viewport: the perspective camera takes the
/// bottom-right quarter and the top, front and right cameras (active only
/// now, orthographic) the other three; it does not quit (Ctrl+Q does);
/// again gives one view.
#[test]
fn ctrl_alt_q_shows_the_quad_view() {
    let mut user = User::new();
    user.add("Cube");
    let viewport = |user: &mut User| {
        let world = user.app.world_mut();
        let mut q = world.query_filtered::<&Camera, With<hedra_scene::ViewportCamera>>();
        q.single(world).unwrap().viewport.clone().unwrap()
    };
    let whole = viewport(&mut user);
    user.shortcut(&[KeyCode::ControlLeft, KeyCode::AltLeft], KeyCode::KeyQ);
    user.frames(2);
    assert!(user.app.world().resource::<hedra_scene::QuadView>().0);
    let main = viewport(&mut user);
    assert_eq!(main.physical_size, whole.physical_size / 2);
    assert_eq!(
        main.physical_position,
        whole.physical_position + whole.physical_size / 2
    );
    let world = user.app.world_mut();
    let mut q = world.query::<(&hedra_viewport::QuadViewCamera, &Camera, &Projection)>();
    let quads: Vec<_> = q
        .iter(world)
        .map(|(v, c, p)| {
            (
                *v,
                c.is_active,
                c.viewport.clone().unwrap().physical_position,
                matches!(p, Projection::Orthographic(_)),
            )
        })
        .collect();
    assert_eq!(quads.len(), 3);
    assert!(quads.iter().all(|q| q.1 && q.3), "{quads:?}");
    let top = quads
        .iter()
        .find(|q| q.0 == hedra_viewport::QuadViewCamera::Top)
        .unwrap();
    assert_eq!(
        top.2, whole.physical_position,
        "top view in the top-left quarter"
    );
    user.shortcut(&[KeyCode::ControlLeft, KeyCode::AltLeft], KeyCode::KeyQ);
    user.frames(2);
    assert_eq!(viewport(&mut user).physical_size, whole.physical_size);
}

/// The cube's edge overlay: how many line segments it draws.
fn overlay_segments(user: &mut User) -> usize {
    let world = user.app.world_mut();
    let mut q = world.query::<(&hedra_viewport::EdgeOverlay, &bevy::gizmos::retained::Gizmo)>();
    let handle = q.single(world).expect("one mesh overlay").1.handle.clone();
    let assets = world.resource::<Assets<bevy::gizmos::GizmoAsset>>();
    assets.get(&handle).unwrap().buffer().list_positions.len() / 2
}

/// View ▸ Cages: the cage's edges over a subdivided cube go and come back;
/// a plain mesh keeps its edges either way.
#[test]
fn view_cages_hides_the_cage_over_smoothed_meshes() {
    let mut user = User::new();
    user.add("Cube");
    user.tap(KeyCode::Escape);
    user.frames(2);
    assert_eq!(overlay_segments(&mut user), 12, "a plain cube's 12 edges");
    user.click_on("View");
    user.click_on("Cages (over smoothed and modified meshes)");
    user.tap(KeyCode::Escape);
    user.frames(2);
    assert_eq!(
        overlay_segments(&mut user),
        12,
        "a plain mesh keeps its edges"
    );
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::Digit1);
    user.frames(3);
    assert_eq!(
        overlay_segments(&mut user),
        0,
        "the cage over the smooth cube is hidden"
    );
    user.click_on("View");
    user.click_on("Cages (over smoothed and modified meshes)");
    user.tap(KeyCode::Escape);
    user.frames(2);
    assert_eq!(overlay_segments(&mut user), 12, "and shown again");
}
