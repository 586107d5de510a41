//! The app without a window: commands applied through the apply system
//! change the entities that mirror the document; undo restores them.

use bevy::prelude::*;
use hedra_doc::{Command, NodeRef, Transform as DocTransform};
use hedra_geom::Primitive;
use hedra_scene::{DocRequest, DocState, NodeEntities, NodeEntity, ProjectedMesh, StatusMessage};

fn send(app: &mut App, r: DocRequest) {
    app.world_mut().write_message(r);
    app.update();
    app.update(); // commands from the sync system are applied
}

fn node_entities(app: &mut App) -> Vec<(Entity, String)> {
    let world = app.world_mut();
    let mut q = world.query::<(Entity, &NodeEntity, &Name)>();
    let mut v: Vec<(Entity, String)> = q.iter(world).map(|(e, _, n)| (e, n.to_string())).collect();
    v.sort_by(|a, b| a.1.cmp(&b.1));
    v
}

#[test]
fn commands_spawn_entities_with_meshes_and_hierarchy_and_undo_removes_them() {
    let mut app = hedra::headless_app();
    app.update();
    send(
        &mut app,
        DocRequest::Execute(Command::AddEmpty {
            name: "Group".into(),
            parent: None,
            transform: DocTransform::from_translation(hedra_geom::DVec3::new(0.0, 2.0, 0.0)),
        }),
    );
    send(
        &mut app,
        DocRequest::Execute(Command::AddPrimitive {
            primitive: Primitive::Cube { size: 2.0 },
            name: Some("Box".into()),
            parent: Some(NodeRef::Name("Group".into())),
            transform: DocTransform::from_translation(hedra_geom::DVec3::new(1.0, 0.0, 0.0)),
        }),
    );
    let ents = node_entities(&mut app);
    assert_eq!(
        ents.iter().map(|e| e.1.as_str()).collect::<Vec<_>>(),
        ["Box", "Group"]
    );
    let (box_e, group_e) = (ents[0].0, ents[1].0);
    let world = app.world();
    assert_eq!(
        world.get::<ChildOf>(box_e).map(|c| c.parent()),
        Some(group_e)
    );
    assert_eq!(
        world.get::<GlobalTransform>(box_e).unwrap().translation(),
        Vec3::new(1.0, 2.0, 0.0)
    );
    let mesh = world
        .get::<Mesh3d>(box_e)
        .expect("mesh nodes get a render mesh");
    let render = world.resource::<Assets<Mesh>>().get(&mesh.0).unwrap();
    assert_eq!(
        render.count_vertices(),
        24,
        "a flat cube has split normals: 6 faces x 4 corners"
    );
    assert_eq!(render.indices().unwrap().len(), 36);
    assert!(world.get::<Mesh3d>(group_e).is_none());

    // Move, then undo: the entity follows the document both ways.
    send(
        &mut app,
        DocRequest::Execute(Command::Translate {
            nodes: vec![NodeRef::Name("Box".into())],
            offset: hedra_geom::DVec3::new(0.0, 0.0, 5.0),
        }),
    );
    assert_eq!(
        app.world().get::<Transform>(box_e).unwrap().translation,
        Vec3::new(1.0, 0.0, 5.0)
    );
    send(&mut app, DocRequest::Undo);
    assert_eq!(
        app.world().get::<Transform>(box_e).unwrap().translation,
        Vec3::new(1.0, 0.0, 0.0)
    );

    // Reparent to the root keeps the world position; the entity loses ChildOf.
    send(
        &mut app,
        DocRequest::Execute(Command::Reparent {
            node: NodeRef::Name("Box".into()),
            parent: None,
            keep_world: true,
        }),
    );
    assert!(app.world().get::<ChildOf>(box_e).is_none());
    assert_eq!(
        app.world().get::<Transform>(box_e).unwrap().translation,
        Vec3::new(1.0, 2.0, 0.0)
    );
    send(&mut app, DocRequest::Undo);
    assert_eq!(
        app.world().get::<ChildOf>(box_e).map(|c| c.parent()),
        Some(group_e)
    );

    // Delete the group: both entities go; undo brings both back.
    send(
        &mut app,
        DocRequest::Execute(Command::Delete {
            nodes: vec![NodeRef::Name("Group".into())],
        }),
    );
    assert!(node_entities(&mut app).is_empty());
    send(&mut app, DocRequest::Undo);
    assert_eq!(node_entities(&mut app).len(), 2);
    assert_eq!(app.world().resource::<NodeEntities>().0.len(), 2);
}

#[test]
fn changing_shading_or_primitive_rebuilds_only_that_render_mesh() {
    let mut app = hedra::headless_app();
    app.update();
    for name in ["A", "B"] {
        send(
            &mut app,
            DocRequest::Execute(Command::AddPrimitive {
                primitive: Primitive::UvSphere {
                    segments: 8,
                    rings: 4,
                    radius: 1.0,
                },
                name: Some(name.into()),
                parent: None,
                transform: DocTransform::IDENTITY,
            }),
        );
    }
    let ents = node_entities(&mut app);
    let before_b = *app.world().get::<ProjectedMesh>(ents[1].0).unwrap();
    send(
        &mut app,
        DocRequest::Execute(Command::SetShading {
            nodes: vec![NodeRef::Name("A".into())],
            shading: hedra_doc::Shading::Flat,
        }),
    );
    let a_mesh = app.world().get::<Mesh3d>(ents[0].0).unwrap().0.clone();
    let render = app.world().resource::<Assets<Mesh>>().get(&a_mesh).unwrap();
    // Flat: each of the 32 faces has its own corners (16 triangles x 3 + 16 quads x 4).
    assert_eq!(render.count_vertices(), 16 * 3 + 16 * 4);
    assert_eq!(
        *app.world().get::<ProjectedMesh>(ents[1].0).unwrap(),
        before_b,
        "B was not rebuilt"
    );
    send(
        &mut app,
        DocRequest::Execute(Command::SetPrimitive {
            node: NodeRef::Name("B".into()),
            primitive: Primitive::UvSphere {
                segments: 16,
                rings: 8,
                radius: 1.0,
            },
        }),
    );
    let b_mesh = app.world().get::<Mesh3d>(ents[1].0).unwrap().0.clone();
    let render = app.world().resource::<Assets<Mesh>>().get(&b_mesh).unwrap();
    assert_eq!(
        render.count_vertices(),
        16 * 7 + 2,
        "smooth shading shares corners"
    );
}

#[test]
fn a_failing_command_reports_an_error_and_changes_nothing() {
    let mut app = hedra::headless_app();
    app.update();
    let before = app.world().resource::<DocState>().revision;
    send(
        &mut app,
        DocRequest::Execute(Command::Delete {
            nodes: vec![NodeRef::Name("Nope".into())],
        }),
    );
    let status = app.world().resource::<StatusMessage>();
    assert!(status.is_error);
    assert_eq!(status.text, "node 'Nope' does not exist");
    assert_eq!(app.world().resource::<DocState>().revision, before);
    // Opening a missing file says so and keeps the document.
    send(
        &mut app,
        DocRequest::Open("/nonexistent/x.hedra.ron".into()),
    );
    let status = app.world().resource::<StatusMessage>();
    assert!(
        status.is_error && status.text.contains("/nonexistent/x.hedra.ron"),
        "{}",
        status.text
    );
}

#[test]
fn new_selection_follows_created_nodes() {
    let mut app = hedra::headless_app();
    app.update();
    send(
        &mut app,
        DocRequest::Execute(Command::AddPrimitive {
            primitive: Primitive::Cube { size: 1.0 },
            name: None,
            parent: None,
            transform: DocTransform::IDENTITY,
        }),
    );
    let sel = app.world().resource::<hedra_edit::Selection>().clone();
    assert_eq!(sel.nodes.len(), 1);
    send(
        &mut app,
        DocRequest::Execute(Command::Duplicate { nodes: sel.refs() }),
    );
    let sel2 = app.world().resource::<hedra_edit::Selection>().clone();
    assert_eq!(sel2.nodes.len(), 1);
    assert_ne!(sel2.nodes, sel.nodes, "the copy is selected");
    send(&mut app, DocRequest::Undo);
    assert!(
        app.world()
            .resource::<hedra_edit::Selection>()
            .nodes
            .is_empty(),
        "the undone copy left the selection"
    );
}

#[test]
fn patching_positions_gives_the_same_render_mesh_as_rebuilding() {
    use bevy::mesh::VertexAttributeValues;
    use hedra_doc::Shading;
    use hedra_scene::{render_mesh, update_render_positions};
    let attr = |m: &Mesh, a| match m.attribute(a) {
        Some(VertexAttributeValues::Float32x3(v)) => v.clone(),
        _ => panic!("missing attribute"),
    };
    for shading in [Shading::Flat, Shading::Smooth] {
        let old = Primitive::UvSphere {
            segments: 12,
            rings: 6,
            radius: 1.0,
        }
        .build()
        .unwrap();
        let mut new = old.clone();
        for v in new.vertices().filter(|v| v.0 % 3 == 0).collect::<Vec<_>>() {
            new.set_position(
                v,
                new.position(v) * 1.2 + hedra_geom::DVec3::new(0.1, 0.0, 0.0),
            );
        }
        let mut patched = render_mesh(&old, shading);
        assert!(update_render_positions(&mut patched, &old, &new, shading));
        let rebuilt = render_mesh(&new, shading);
        for a in [Mesh::ATTRIBUTE_POSITION, Mesh::ATTRIBUTE_NORMAL] {
            let (p, r) = (attr(&patched, a.clone()), attr(&rebuilt, a));
            assert_eq!(p.len(), r.len());
            for (x, y) in p.iter().zip(&r) {
                assert!(
                    (0..3).all(|k| (x[k] - y[k]).abs() < 1e-6),
                    "{shading:?}: {x:?} vs {y:?}"
                );
            }
        }
        // A change of connectivity is refused: the caller rebuilds.
        let mut cut = old.clone();
        hedra_geom::modeling::subdivide_edges(&mut cut, &[hedra_geom::EdgeId(0)], 1).unwrap();
        let mut m = render_mesh(&old, shading);
        assert!(!update_render_positions(&mut m, &old, &cut, shading));
    }
}

#[test]
fn a_subdivision_modifier_renders_the_refined_mesh_and_drags_keep_its_layout() {
    let mut app = hedra::headless_app();
    app.update();
    send(
        &mut app,
        DocRequest::Execute(Command::AddPrimitive {
            primitive: Primitive::Cube { size: 2.0 },
            name: Some("Box".into()),
            parent: None,
            transform: DocTransform::IDENTITY,
        }),
    );
    send(
        &mut app,
        DocRequest::Execute(Command::SetShading {
            nodes: vec![NodeRef::Name("Box".into())],
            shading: hedra_doc::Shading::Smooth,
        }),
    );
    let count = |app: &mut App| {
        let e = node_entities(app)[0].0;
        let h = app.world().get::<Mesh3d>(e).unwrap().0.clone();
        let m = app.world().resource::<Assets<Mesh>>().get(&h).unwrap();
        (m.count_vertices(), m.indices().unwrap().len() / 3)
    };
    assert_eq!(
        count(&mut app),
        (8, 12),
        "the cage: 8 shared corners, 12 triangles"
    );
    send(
        &mut app,
        DocRequest::Execute(Command::SetSubdivision {
            nodes: vec![NodeRef::Name("Box".into())],
            modifier: Some(hedra_doc::SubdivisionModifier::with_level(2)),
        }),
    );
    // Level 2: 96 quads (192 triangles) on 98 shared vertices.
    assert_eq!(count(&mut app), (98, 192));
    let e = node_entities(&mut app)[0].0;
    assert!(
        app.world()
            .get::<ProjectedMesh>(e)
            .unwrap()
            .smooth
            .is_some()
    );
    // Moving a cage vertex keeps the refined layout; the preview follows.
    send(
        &mut app,
        DocRequest::Execute(Command::MoveVertices {
            node: NodeRef::Name("Box".into()),
            vertices: hedra_doc::elements::VertexSet::Ids(vec![0]),
            offset: hedra_geom::DVec3::new(0.0, -1.0, 0.0),
        }),
    );
    assert_eq!(count(&mut app), (98, 192));
    // Creases change the shape, not the layout; Ctrl+0's level 0 shows the cage.
    send(
        &mut app,
        DocRequest::Execute(Command::SetSubdivision {
            nodes: vec![NodeRef::Name("Box".into())],
            modifier: Some(hedra_doc::SubdivisionModifier::with_level(0)),
        }),
    );
    assert_eq!(count(&mut app), (8, 12));
    // A scheme that does not fit shows the cage and says why.
    let mut loop_modifier = hedra_doc::SubdivisionModifier::with_level(1);
    loop_modifier.options.scheme = hedra_geom::subdivision::Scheme::Loop;
    send(
        &mut app,
        DocRequest::Execute(Command::SetSubdivision {
            nodes: vec![NodeRef::Name("Box".into())],
            modifier: Some(loop_modifier),
        }),
    );
    assert_eq!(count(&mut app), (8, 12));
    let status = app.world().resource::<StatusMessage>();
    assert!(
        status.is_error && status.text.contains("Loop subdivision needs triangles"),
        "{}",
        status.text
    );
}

/// Updates the app until no background subdivision runs (at most ~60 s).
fn wait_for_background(app: &mut App) {
    for _ in 0..6000 {
        app.update();
        if app
            .world()
            .resource::<hedra_scene::SmoothPreviews>()
            .progress()
            .is_empty()
        {
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    panic!("the background subdivision never finished");
}

#[test]
fn large_subdivision_levels_refine_in_the_background_and_can_be_cancelled() {
    let mut app = hedra::headless_app();
    app.update();
    send(
        &mut app,
        DocRequest::Execute(Command::AddPrimitive {
            primitive: Primitive::Torus {
                major_segments: 100,
                minor_segments: 100,
                major_radius: 2.0,
                minor_radius: 0.5,
            },
            name: Some("Ring".into()),
            parent: None,
            transform: DocTransform::IDENTITY,
        }),
    );
    let vertices = |app: &mut App| {
        let e = node_entities(app)[0].0;
        let h = app.world().get::<Mesh3d>(e).unwrap().0.clone();
        app.world()
            .resource::<Assets<Mesh>>()
            .get(&h)
            .unwrap()
            .count_vertices()
    };
    let cage = vertices(&mut app);
    // Level 2 of 10,000 quads is 160,000 faces: above the background limit.
    send(
        &mut app,
        DocRequest::Execute(Command::SetSubdivision {
            nodes: vec![NodeRef::Name("Ring".into())],
            modifier: Some(hedra_doc::SubdivisionModifier::with_level(2)),
        }),
    );
    let progress = app
        .world()
        .resource::<hedra_scene::SmoothPreviews>()
        .progress();
    assert_eq!(progress.len(), 1, "one job runs");
    assert!(
        progress[0].0.contains("Subdividing 'Ring' to level 2"),
        "{progress:?}"
    );
    assert_eq!(vertices(&mut app), cage, "the cage shows meanwhile");
    wait_for_background(&mut app);
    app.update();
    assert_eq!(
        vertices(&mut app),
        160_000,
        "the smooth torus replaced the cage"
    );

    // Level 3, cancelled at once: the cage shows, the user is told, and the
    // job is not started again until something changes.
    send(
        &mut app,
        DocRequest::Execute(Command::SetSubdivision {
            nodes: vec![NodeRef::Name("Ring".into())],
            modifier: Some(hedra_doc::SubdivisionModifier::with_level(3)),
        }),
    );
    app.world_mut()
        .resource_mut::<hedra_scene::SmoothPreviews>()
        .cancel_all();
    wait_for_background(&mut app);
    let status = app.world().resource::<StatusMessage>();
    assert!(status.text.contains("cancelled"), "{}", status.text);
    app.update();
    assert!(
        app.world()
            .resource::<hedra_scene::SmoothPreviews>()
            .progress()
            .is_empty()
    );
    assert_eq!(vertices(&mut app), cage);
}

#[test]
fn curves_and_surfaces_get_render_meshes_and_can_be_picked() {
    use hedra_doc::command::{CurveSpec, SurfaceSpec};
    let mut app = hedra::headless_app();
    app.update();
    send(
        &mut app,
        DocRequest::Execute(Command::AddSurface {
            name: "Ball".into(),
            surface: SurfaceSpec::Sphere { radius: 1.0 },
            parent: None,
            transform: DocTransform::IDENTITY,
        }),
    );
    send(
        &mut app,
        DocRequest::Execute(Command::AddCurve {
            name: "Ring".into(),
            curve: CurveSpec::Circle { radius: 3.0 },
            parent: None,
            transform: DocTransform::IDENTITY,
        }),
    );
    let ents = node_entities(&mut app);
    let (ball, ring) = (ents[0].0, ents[1].0);
    let positions = |app: &mut App| {
        let h = app.world().get::<Mesh3d>(ball).unwrap().0.clone();
        let m = app.world().resource::<Assets<Mesh>>().get(&h).unwrap();
        match m.attribute(Mesh::ATTRIBUTE_POSITION) {
            Some(bevy::mesh::VertexAttributeValues::Float32x3(p)) => p.clone(),
            _ => panic!("positions"),
        }
    };
    let before = positions(&mut app);
    assert!(
        before.len() > 100,
        "the sphere is tessellated: {}",
        before.len()
    );
    assert!(
        before
            .iter()
            .all(|p| (Vec3::from(*p).length() - 1.0).abs() < 1e-3),
        "on the sphere"
    );
    assert!(
        app.world().get::<Mesh3d>(ring).is_none(),
        "a curve has no surface"
    );
    assert!(
        app.world().get::<ProjectedMesh>(ring).is_some(),
        "but the overlays know it"
    );
    // Moving a control point changes the render mesh.
    send(
        &mut app,
        DocRequest::Execute(Command::SetControlPoints {
            node: NodeRef::Name("Ball".into()),
            points: vec![(22, hedra_geom::DVec3::new(3.0, 0.0, 0.0))],
        }),
    );
    let after = positions(&mut app);
    assert!(
        after.iter().any(|p| Vec3::from(*p).length() > 1.2),
        "the pulled point bulges the surface"
    );
    // Picking: a ray down the Z axis hits the (still unit near the pole) sphere at about z = 1.
    let doc = &app.world().resource::<DocState>().session.doc;
    let (id, dist) = hedra_edit::pick_node(
        doc,
        hedra_geom::DVec3::new(0.0, 0.0, 5.0),
        hedra_geom::DVec3::NEG_Z,
    )
    .unwrap();
    assert_eq!(doc.node(id).unwrap().name, "Ball");
    assert!((dist - 4.0).abs() < 0.05, "{dist}");
}

#[test]
fn a_weight_change_re_evaluates_only_the_surface_it_can_reach() {
    use bevy::mesh::VertexAttributeValues;
    use hedra_geom::surfaces::NurbsSurface;
    let mut points = Vec::new();
    for i in 0..8 {
        for j in 0..8 {
            points.push(hedra_geom::DVec3::new(
                i as f64,
                ((i + j) as f64 * 0.7).sin(),
                j as f64,
            ));
        }
    }
    let knots = hedra_geom::curves::nurbs::clamped_uniform_knots(3, 8);
    let old = NurbsSurface::new(3, 3, knots.clone(), knots, 8, 8, points, vec![1.0; 64]).unwrap();
    let mut new = old.clone();
    new.set_weight(1, 1, 4.0).unwrap();
    let grid = hedra_scene::surface_grid(&old);
    let mut render = hedra_scene::surface_render_mesh(&hedra_doc::SurfaceShape::Nurbs(old.clone()));
    let before = match render.attribute(Mesh::ATTRIBUTE_POSITION) {
        Some(VertexAttributeValues::Float32x3(p)) => p.clone(),
        _ => panic!("positions"),
    };
    assert!(hedra_scene::update_surface_render_mesh(
        &mut render,
        &grid,
        &old,
        &new
    ));
    let Some(VertexAttributeValues::Float32x3(after)) = render.attribute(Mesh::ATTRIBUTE_POSITION)
    else {
        panic!("positions");
    };
    // Every grid point equals the new surface evaluated there…
    let (exact, _) = new.grid(&grid.us, &grid.vs, false);
    for (got, want) in after.iter().zip(&exact) {
        assert!((Vec3::from(*got) - want.as_vec3()).length() < 1e-5);
    }
    // …and the points beyond the changed point's knot spans were not touched.
    let moved = before
        .iter()
        .zip(after.iter())
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        moved > 0 && moved < before.len() / 2,
        "{moved} of {} moved",
        before.len()
    );
    // A change of knots is not a drag: rebuild.
    let refined = new.insert_knot_u(0.5).unwrap();
    assert!(!hedra_scene::update_surface_render_mesh(
        &mut render,
        &grid,
        &new,
        &refined
    ));
}

/// Autosave in the app: only after a change, never while a tool runs, gone
/// after a save; the panic hook's snapshot follows; undo limits apply.
#[test]
fn autosave_waits_for_tools_writes_changes_and_is_removed_by_a_save() {
    use hedra_doc::recovery::{self, RecoveryKind};
    use hedra_ui::recovery::{Recovery, RecoveryPlugin};
    let dir = tempfile::tempdir().unwrap();
    let recovery_dir = dir.path().join("recovery");
    let mut app = hedra::headless_app();
    app.add_plugins(RecoveryPlugin)
        .insert_resource(hedra_ui::UiState::default())
        .insert_resource(hedra_ui::Preferences {
            autosave_seconds: 1,
            ..Default::default()
        })
        .insert_resource(Recovery::new(Some(recovery_dir.clone())));
    app.update();
    let paths = |app: &mut App| {
        app.world()
            .resource::<Recovery>()
            .point()
            .expect("the untitled document has a recovery point")
            .paths(RecoveryKind::Autosave)
    };
    let (scene, meta) = paths(&mut app);
    let cube = |name: &str| {
        DocRequest::Execute(Command::AddPrimitive {
            primitive: Primitive::Cube { size: 1.0 },
            name: Some(name.into()),
            parent: None,
            transform: DocTransform::IDENTITY,
        })
    };
    send(&mut app, cube("A"));
    let snapshot = app.world().resource::<Recovery>().snapshot.clone();
    assert!(
        snapshot.lock().unwrap().is_some(),
        "unsaved work is in the snapshot"
    );

    // A tool is running (a transform field being dragged): no autosave.
    let node = app
        .world()
        .resource::<DocState>()
        .session
        .doc
        .find_by_name("A")
        .unwrap()
        .id;
    app.world_mut()
        .resource_mut::<hedra_ui::UiState>()
        .transform_edit = Some((node, DocTransform::IDENTITY));
    std::thread::sleep(std::time::Duration::from_millis(1100));
    for _ in 0..3 {
        app.update();
    }
    assert!(!app.world().resource::<Recovery>().is_writing());
    assert!(!scene.exists(), "no autosave in the middle of a tool");

    // The tool ends: the autosave is written (on a worker thread).
    app.world_mut()
        .resource_mut::<hedra_ui::UiState>()
        .transform_edit = None;
    let start = std::time::Instant::now();
    while !(meta.exists() && !app.world().resource::<Recovery>().is_writing()) {
        assert!(start.elapsed().as_secs() < 10, "autosave not written");
        app.update();
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let offered = recovery::pending_with(&recovery_dir, &|_| false);
    assert_eq!(offered.len(), 1);
    assert_eq!(offered[0].meta.steps, 1);
    let saved = recovery::recover(&offered[0]).unwrap().session;
    assert!(saved.doc.find_by_name("A").is_some());

    // Nothing changed since: no second autosave even after the interval.
    std::thread::sleep(std::time::Duration::from_millis(1100));
    app.update();
    assert!(!app.world().resource::<Recovery>().is_writing());
    assert_eq!(app.world().resource::<Recovery>().autosaves, 1);

    // Saving removes the recovery point and empties the snapshot.
    let file = dir.path().join("saved.hedra.ron");
    send(&mut app, DocRequest::Save(file.clone()));
    app.update();
    assert!(
        !scene.exists() && !meta.exists(),
        "saved: the autosave is gone"
    );
    assert!(snapshot.lock().unwrap().is_none());

    // Undo limits from the preferences reach the history.
    send(&mut app, cube("B"));
    send(&mut app, cube("C"));
    app.world_mut()
        .resource_mut::<hedra_ui::Preferences>()
        .undo_steps = 1;
    app.update();
    app.update();
    let history = &app.world().resource::<DocState>().session.history;
    assert_eq!(history.done().len(), 1);
    assert_eq!(history.max_steps, 1);
    assert_eq!(history.dropped, 2);
}

/// An error exit (what Bevy does on a render error) saves the unsaved
/// document as an emergency recovery point; a normal exit removes the
/// session's recovery files.
#[test]
fn an_error_exit_saves_the_work_and_a_normal_exit_cleans_up() {
    use hedra_doc::recovery::{self, RecoveryKind};
    use hedra_ui::recovery::{Recovery, RecoveryPlugin};
    for error in [true, false] {
        let dir = tempfile::tempdir().unwrap();
        let mut app = hedra::headless_app();
        app.add_plugins(RecoveryPlugin)
            .insert_resource(hedra_ui::UiState::default())
            .insert_resource(hedra_ui::Preferences {
                autosave_seconds: 0,
                ..Default::default()
            })
            .insert_resource(Recovery::new(Some(dir.path().to_path_buf())));
        app.update();
        send(
            &mut app,
            DocRequest::Execute(Command::AddPrimitive {
                primitive: Primitive::Cube { size: 1.0 },
                name: Some("Unsaved".into()),
                parent: None,
                transform: DocTransform::IDENTITY,
            }),
        );
        let (emergency, _) = app
            .world()
            .resource::<Recovery>()
            .point()
            .unwrap()
            .paths(RecoveryKind::Emergency);
        app.world_mut().write_message(if error {
            AppExit::error()
        } else {
            AppExit::Success
        });
        app.update();
        let offered = recovery::pending_with(dir.path(), &|_| false);
        if error {
            assert!(emergency.is_file(), "emergency save written");
            assert_eq!(offered.len(), 1);
            assert_eq!(offered[0].meta.kind, RecoveryKind::Emergency);
            let s = recovery::recover(&offered[0]).unwrap().session;
            assert!(s.doc.find_by_name("Unsaved").is_some());
        } else {
            assert!(offered.is_empty() && !emergency.exists());
        }
    }
}
