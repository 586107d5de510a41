//! One writer per projected component (issue 12): node `Transform`s are
//! written only by `project_transforms`, render meshes only by
//! `project_render_meshes` (mesh nodes) and `project_surface_patches`
//! (surface patches). Checked with Bevy's change ticks while a person
//! uses every tool: each system run has its own tick, so a value written by
//! any other system carries a tick outside the projection's runs.

use crate::user::User;
use bevy::ecs::system::SystemChangeTick;
use bevy::prelude::*;
use hedra_scene::{
    NodeEntity, project_control_points, project_render_meshes, project_surface_patches,
    project_transforms, sync_entities,
};

/// The ticks between which each projection system ran, and what was
/// written outside them.
#[derive(Resource, Default)]
struct Audit {
    opened: u32,
    transforms: Vec<(u32, u32)>,
    meshes: Vec<(u32, u32)>,
    update_opened: u32,
    updates: Vec<(u32, u32)>,
    violations: Vec<String>,
}

fn open(ticks: SystemChangeTick, mut audit: ResMut<Audit>) {
    audit.opened = ticks.this_run().get();
}

fn close_transforms(ticks: SystemChangeTick, mut audit: ResMut<Audit>) {
    let opened = audit.opened;
    audit.transforms.push((opened, ticks.this_run().get()));
}

fn close_meshes(ticks: SystemChangeTick, mut audit: ResMut<Audit>) {
    let opened = audit.opened;
    audit.meshes.push((opened, ticks.this_run().get()));
}

fn open_patches(ticks: SystemChangeTick, mut audit: ResMut<Audit>) {
    audit.opened = ticks.this_run().get();
}

fn close_patches(ticks: SystemChangeTick, mut audit: ResMut<Audit>) {
    let opened = audit.opened;
    audit.meshes.push((opened, ticks.this_run().get()));
}

fn open_update(ticks: SystemChangeTick, mut audit: ResMut<Audit>) {
    audit.update_opened = ticks.this_run().get();
}

fn close_update(ticks: SystemChangeTick, mut audit: ResMut<Audit>) {
    let opened = audit.update_opened;
    audit.updates.push((opened, ticks.this_run().get()));
}

/// At the end of `Update`: were render meshes last written inside a run of
/// a projection system? (Render meshes share `Assets<Mesh>` with Bevy's
/// gizmo meshes, updated after transform propagation, and its asset
/// bookkeeping outside `Update`; this runs before those.)
fn check_meshes(world: &mut World) {
    let inside = |runs: &[(u32, u32)], tick: u32| runs.iter().any(|&(a, b)| a < tick && tick < b);
    let mut found = Vec::new();
    let audit = world.resource::<Audit>();
    if let Some(ticks) = world.get_resource_change_ticks::<Assets<Mesh>>() {
        let changed = ticks.changed.get();
        // Bevy's own asset bookkeeping and gizmo meshes write the store
        // outside `Update`; inside it, only the projection may.
        if ticks.added.get() != changed
            && inside(&audit.updates, changed)
            && !inside(&audit.meshes, changed)
        {
            found.push(format!(
                "render meshes were written outside the projection (tick {changed})"
            ));
        }
    }
    let mut audit = world.resource_mut::<Audit>();
    for f in found {
        if !audit.violations.contains(&f) {
            audit.violations.push(f);
        }
    }
}

/// At the end of every frame: was each node `Transform` last changed
/// inside a run of `project_transforms`?
fn check(world: &mut World) {
    let inside = |runs: &[(u32, u32)], tick: u32| runs.iter().any(|&(a, b)| a < tick && tick < b);
    let mut found = Vec::new();
    let mut nodes = world.query::<(Entity, &NodeEntity)>();
    let audit = world.resource::<Audit>();
    for (entity, node) in nodes.iter(world) {
        let ticks = world
            .entity(entity)
            .get_change_ticks::<Transform>()
            .expect("a node entity has a Transform");
        // Spawned with its document transform: not a second write.
        let changed = ticks.changed.get();
        if ticks.added.get() != changed && !inside(&audit.transforms, changed) {
            found.push(format!(
                "the Transform of node {} was written outside project_transforms (tick {changed})",
                node.0
            ));
        }
    }
    let mut audit = world.resource_mut::<Audit>();
    for f in found {
        if !audit.violations.contains(&f) {
            audit.violations.push(f);
        }
    }
}

fn audited() -> User {
    let mut user = User::new();
    user.app
        .init_resource::<Audit>()
        .add_systems(
            Update,
            (
                open.after(sync_entities).before(project_transforms),
                close_transforms
                    .after(project_transforms)
                    .before(project_render_meshes),
                open.after(close_transforms).before(project_render_meshes),
                close_meshes
                    .after(project_render_meshes)
                    .before(project_control_points),
                open_patches
                    .after(project_control_points)
                    .before(project_surface_patches),
                close_patches.after(project_surface_patches),
            ),
        )
        // Between PreUpdate (Bevy's asset bookkeeping) and Update.
        .add_systems(RunFixedMainLoop, open_update)
        // Before Bevy's gizmo meshes are updated (after transform propagation).
        .add_systems(
            PostUpdate,
            (close_update, check_meshes)
                .chain()
                .before(bevy::transform::TransformSystems::Propagate),
        )
        .add_systems(Last, check);
    user
}

fn violations(user: &User) -> Vec<String> {
    user.app.world().resource::<Audit>().violations.clone()
}

#[test]
fn only_the_projection_writes_node_transforms_and_render_meshes() {
    let mut user = audited();
    let centre = user.viewport_center();
    user.add("Cube");
    // G / R / S with the mouse and typed values, confirmed and cancelled.
    user.tap(KeyCode::KeyG);
    user.glide_to(centre + Vec2::new(40.0, 10.0), 4);
    user.click(centre + Vec2::new(40.0, 10.0));
    user.tap(KeyCode::KeyR);
    user.type_text("30");
    user.tap(KeyCode::Enter);
    user.tap(KeyCode::KeyS);
    user.glide_to(centre + Vec2::new(90.0, 40.0), 4);
    user.tap(KeyCode::Escape);
    // Edit mode: extrude the top face, crease, subdivision preview, undo.
    user.tap(KeyCode::Tab);
    user.tap(KeyCode::Digit3);
    user.tap(KeyCode::KeyA);
    user.tap(KeyCode::KeyE);
    user.glide_to(centre + Vec2::new(0.0, -50.0), 4);
    user.click(centre + Vec2::new(0.0, -50.0));
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::Digit2);
    user.tap(KeyCode::KeyG);
    user.glide_to(centre + Vec2::new(30.0, -20.0), 4);
    user.click(centre + Vec2::new(30.0, -20.0));
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    user.tap(KeyCode::Tab);
    // A NURBS surface: a control point moved, a weight dragged.
    user.add("NURBS Surface");
    user.tap(KeyCode::Tab);
    let node = user.doc().nodes().last().unwrap();
    let points = hedra_edit::shape_mode::control_points(&node.content);
    let world = user.doc().world_matrix(node.id);
    let first = user.screen_of(world.transform_point3(points[4]).as_vec3());
    user.click(first);
    user.tap(KeyCode::KeyW);
    user.glide_to(first + Vec2::new(80.0, 0.0), 4);
    user.click(first + Vec2::new(80.0, 0.0));
    user.tap(KeyCode::KeyG);
    user.glide_to(first + Vec2::new(0.0, -40.0), 4);
    user.click(first + Vec2::new(0.0, -40.0));
    user.tap(KeyCode::Tab);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::KeyZ);
    user.shortcut(&[KeyCode::ControlLeft, KeyCode::ShiftLeft], KeyCode::KeyZ);
    assert!(
        user.undo_steps() >= 7,
        "the tools did their work: {}",
        user.status()
    );
    user.tap(KeyCode::KeyX);
    user.frames(3);
    let audit = user.app.world().resource::<Audit>();
    assert!(
        audit.transforms.len() > 50 && audit.meshes.len() > 50,
        "the projection ran every frame"
    );
    assert_eq!(violations(&user), Vec::<String>::new());
}

/// The audit itself: a system that writes a node's `Transform`, or a
/// render mesh, is found.
#[test]
fn a_second_writer_is_found() {
    let mut user = audited();
    user.add("Cube");
    user.app.add_systems(
        Update,
        (|mut nodes: Query<&mut Transform, With<NodeEntity>>| {
            for mut t in &mut nodes {
                t.translation.x += 1.0;
            }
        })
        .after(hedra_scene::SceneSystems::Sync),
    );
    user.frames(2);
    let found = violations(&user);
    assert!(
        found
            .iter()
            .any(|v| v.contains("outside project_transforms")),
        "{found:?}"
    );

    let mut user = audited();
    user.add("Cube");
    user.app.add_systems(
        Update,
        |nodes: Query<&Mesh3d>, mut meshes: ResMut<Assets<Mesh>>| {
            for m in &nodes {
                meshes.get_mut(&m.0);
            }
        },
    );
    user.frames(2);
    let found = violations(&user);
    assert!(
        found.iter().any(|v| v.contains("outside the projection")),
        "{found:?}"
    );
}
