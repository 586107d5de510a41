//! One writer per projected component (issues 12 and 34): node
//! `Transform`s are written only by `project_transforms`, render meshes only
//! by `project_render_meshes` (mesh nodes) and `project_surface_patches`
//! (surface patches); a node's `MeshMaterial3d` only by
//! `project_render_meshes`, a patch's (and its `SurfacePatch`) only by
//! `project_surface_patches`, `ControlPoint`s only by
//! `project_control_points`, and the node components that mirror the
//! document (`Name`, `Visibility`, `NodeMesh`, `NodeCurve`, `NodeSurface`,
//! `NodeKeptMesh`)
//! only by `sync_entities`. Checked with Bevy's change ticks while a person
//! uses every tool: each system run has its own tick, so a value written by
//! any other system carries a tick outside the projection's runs.

use crate::user::User;
use bevy::ecs::change_detection::ComponentTicks;
use bevy::ecs::system::SystemChangeTick;

/// A component's name, its writer's runs and its change ticks.
type Check<'a> = (&'static str, &'a [(u32, u32)], Option<ComponentTicks>);
use bevy::prelude::*;
use hedra_scene::{
    ControlPoint, NodeCurve, NodeEntity, NodeKeptMesh, NodeMesh, NodeSurface, ShownMesh,
    ShownShape, SurfacePatch, project_control_points, project_render_meshes, project_shown_meshes,
    project_shown_shapes, project_surface_patches, project_transforms, sync_entities,
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
    /// The runs of `sync_entities`, `project_render_meshes`,
    /// `project_control_points` and `project_surface_patches`, by name.
    runs: std::collections::HashMap<&'static str, Vec<(u32, u32)>>,
    run_opened: std::collections::HashMap<&'static str, u32>,
    violations: Vec<String>,
}

/// A system that opens the audit window of the system named `name`.
fn open_run(name: &'static str) -> impl FnMut(SystemChangeTick, ResMut<Audit>) {
    move |ticks, mut audit| {
        audit.run_opened.insert(name, ticks.this_run().get());
    }
}

/// A system that closes the audit window of the system named `name`.
fn close_run(name: &'static str) -> impl FnMut(SystemChangeTick, ResMut<Audit>) {
    move |ticks, mut audit| {
        let opened = audit.run_opened[name];
        audit
            .runs
            .entry(name)
            .or_default()
            .push((opened, ticks.this_run().get()));
    }
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

/// At the end of every frame: was each projected component last changed
/// inside a run of its one writer?
fn check(world: &mut World) {
    let mut found = Vec::new();
    let mut nodes = world.query::<(Entity, &NodeEntity)>();
    let mut points = world.query_filtered::<Entity, With<ControlPoint>>();
    let mut patches = world.query_filtered::<Entity, With<SurfacePatch>>();
    let audit = world.resource::<Audit>();
    // A writer's commands (a material inserted) are applied by the sync
    // point right before its closing system and carry that system's tick:
    // the named windows include their closing tick.
    let inside_run =
        |runs: &[(u32, u32)], tick: u32| runs.iter().any(|&(a, b)| a < tick && tick <= b);
    let runs = |name: &str| audit.runs.get(name).map_or(&[][..], |r| r.as_slice());
    // Whether component `C` of `entity` was last changed outside `writer`'s
    // runs (spawning it with its first value is not a second write).
    let outside = |writer: &[(u32, u32)], ticks: Option<ComponentTicks>| {
        ticks.is_some_and(|t| {
            t.added.get() != t.changed.get() && !inside_run(writer, t.changed.get())
        })
    };
    for (entity, node) in nodes.iter(world) {
        let e = world.entity(entity);
        let node = node.0;
        let mut checks: Vec<Check> = vec![
            (
                "Transform",
                &audit.transforms[..],
                e.get_change_ticks::<Transform>(),
            ),
            (
                "MeshMaterial3d",
                runs("project_render_meshes"),
                e.get_change_ticks::<MeshMaterial3d<StandardMaterial>>(),
            ),
        ];
        checks.push((
            "ShownMesh",
            runs("project_shown_meshes"),
            e.get_change_ticks::<ShownMesh>(),
        ));
        checks.push((
            "ShownShape",
            runs("project_shown_shapes"),
            e.get_change_ticks::<ShownShape>(),
        ));
        for (component, ticks) in [
            ("Name", e.get_change_ticks::<Name>()),
            ("Visibility", e.get_change_ticks::<Visibility>()),
            ("NodeMesh", e.get_change_ticks::<NodeMesh>()),
            ("NodeCurve", e.get_change_ticks::<NodeCurve>()),
            ("NodeSurface", e.get_change_ticks::<NodeSurface>()),
            ("NodeKeptMesh", e.get_change_ticks::<NodeKeptMesh>()),
        ] {
            checks.push((component, runs("sync_entities"), ticks));
        }
        for (component, writer, ticks) in checks {
            if outside(writer, ticks) {
                found.push(format!(
                    "the {component} of node {node} was written outside its writer (tick {})",
                    ticks.unwrap().changed.get()
                ));
            }
        }
    }
    for entity in points.iter(world) {
        let ticks = world.entity(entity).get_change_ticks::<ControlPoint>();
        if outside(runs("project_control_points"), ticks) {
            found.push(format!(
                "a ControlPoint was written outside project_control_points (tick {})",
                ticks.unwrap().changed.get()
            ));
        }
    }
    for entity in patches.iter(world) {
        let e = world.entity(entity);
        for (component, ticks) in [
            ("SurfacePatch", e.get_change_ticks::<SurfacePatch>()),
            (
                "MeshMaterial3d",
                e.get_change_ticks::<MeshMaterial3d<StandardMaterial>>(),
            ),
        ] {
            if outside(runs("project_surface_patches"), ticks) {
                found.push(format!(
                    "the {component} of a surface patch was written outside project_surface_patches (tick {})",
                    ticks.unwrap().changed.get()
                ));
            }
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
        .add_systems(
            Update,
            (
                open_run("sync_entities").before(sync_entities),
                close_run("sync_entities")
                    .after(sync_entities)
                    .before(project_shown_meshes),
                open_run("project_shown_meshes")
                    .after(sync_entities)
                    .before(project_shown_meshes),
                close_run("project_shown_meshes")
                    .after(project_shown_meshes)
                    .before(project_shown_shapes),
                open_run("project_shown_shapes")
                    .after(project_shown_meshes)
                    .before(project_shown_shapes),
                close_run("project_shown_shapes")
                    .after(project_shown_shapes)
                    .before(project_transforms),
                open_run("project_render_meshes")
                    .after(close_transforms)
                    .before(project_render_meshes),
                close_run("project_render_meshes")
                    .after(project_render_meshes)
                    .before(project_control_points),
                open_run("project_control_points")
                    .after(close_meshes)
                    .before(project_control_points),
                close_run("project_control_points")
                    .after(project_control_points)
                    .before(project_surface_patches),
                open_run("project_surface_patches")
                    .after(open_patches)
                    .before(project_surface_patches),
                close_run("project_surface_patches").after(project_surface_patches),
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
    // A kept (non-manifold) mesh: added, smoothed with Ctrl+1, moved.
    user.app
        .world_mut()
        .write_message(hedra_scene::DocRequest::Execute(
            hedra_doc::Command::AddKeptMesh {
                name: "Flaps".into(),
                positions: [
                    [0.0, 0.0, 0.0],
                    [0.0, 0.0, 1.0],
                    [1.0, 0.0, 0.0],
                    [1.0, 0.0, 1.0],
                ]
                .into_iter()
                .chain([
                    [0.0, 1.0, 0.0],
                    [0.0, 1.0, 1.0],
                    [-1.0, 0.0, 0.0],
                    [-1.0, 0.0, 1.0],
                ])
                .map(hedra_geom::DVec3::from_array)
                .collect(),
                faces: vec![vec![0, 2, 3, 1], vec![1, 5, 4, 0], vec![0, 6, 7, 1]],
                parent: None,
                transform: hedra_doc::NodeTransform::IDENTITY,
            },
        ));
    user.frames(2);
    user.shortcut(&[KeyCode::ControlLeft], KeyCode::Digit1);
    user.tap(KeyCode::KeyG);
    user.glide_to(centre + Vec2::new(-40.0, 10.0), 4);
    user.click(centre + Vec2::new(-40.0, 10.0));
    assert!(
        matches!(
            user.doc().find_by_name("Flaps").map(|n| &n.content),
            Some(hedra_doc::NodeContent::Kept(k)) if k.subdivision.is_some()
        ),
        "a kept mesh, smoothed: {}",
        user.status()
    );
    assert!(
        user.undo_steps() >= 10,
        "the tools did their work: {}",
        user.status()
    );
    // The face orientation overlay on and off, with the surface shown.
    user.click_on("View");
    user.click_on("Face Orientation");
    user.frames(2);
    user.tap(KeyCode::Escape);
    user.click_on("View");
    user.click_on("Face Orientation");
    user.frames(2);
    user.tap(KeyCode::KeyX);
    user.frames(3);
    let audit = user.app.world().resource::<Audit>();
    assert!(
        audit.transforms.len() > 50 && audit.meshes.len() > 50,
        "the projection ran every frame"
    );
    for writer in [
        "sync_entities",
        "project_render_meshes",
        "project_control_points",
        "project_surface_patches",
    ] {
        assert!(audit.runs[writer].len() > 50, "{writer} ran every frame");
    }
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
        found.iter().any(|v| v.contains("the Transform of node")),
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

    // A node's material (as the face orientation overlay once swapped it)
    // and a control point.
    let mut user = audited();
    user.add("Cube");
    user.add("NURBS Surface");
    user.app.add_systems(
        Update,
        (|mut materials: Query<&mut MeshMaterial3d<StandardMaterial>, With<NodeEntity>>,
          mut points: Query<&mut ControlPoint>,
          mut shown: Query<&mut ShownMesh>,
          mut shapes: Query<&mut ShownShape>| {
            for mut m in &mut materials {
                m.set_changed();
            }
            for mut p in &mut points {
                p.set_changed();
            }
            for mut m in &mut shown {
                m.set_changed();
            }
            for mut s in &mut shapes {
                s.set_changed();
            }
        })
        .after(hedra_scene::SceneSystems::Sync),
    );
    user.frames(2);
    let found = violations(&user);
    for expected in [
        "the MeshMaterial3d of node",
        "a ControlPoint was written outside project_control_points",
        "the ShownMesh of node",
        "the ShownShape of node",
    ] {
        assert!(
            found.iter().any(|v| v.contains(expected)),
            "{expected}: {found:?}"
        );
    }
}
