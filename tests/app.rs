//! The app without a window: commands applied through the apply system
//! change the entities that mirror the document; undo restores them.

use bevy::prelude::*;
use hedra_doc::{Command, NodeRef, NodeTransform};
use hedra_geom::Primitive;
use hedra_scene::{
    DocRequest, DocState, NodeEntities, NodeEntity, NodeMesh, ShownMesh, ShownShape, StatusMessage,
};

fn send(app: &mut App, r: DocRequest) {
    app.world_mut().write_message(r);
    app.update();
    wait_for_files(app);
    app.update(); // commands from the sync system are applied
}

/// Frames go on while a file is opened or saved on its worker thread.
fn wait_for_files(app: &mut App) {
    for _ in 0..5000 {
        if !app.world().resource::<hedra_scene::FileJobs>().busy() {
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(1));
        app.update();
    }
    panic!("the file job did not finish");
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
            transform: NodeTransform::from_translation(hedra_geom::DVec3::new(0.0, 2.0, 0.0)),
        }),
    );
    send(
        &mut app,
        DocRequest::Execute(Command::AddPrimitive {
            primitive: Primitive::Cube { size: 2.0 },
            name: Some("Box".into()),
            parent: Some(NodeRef::Name("Group".into())),
            transform: NodeTransform::from_translation(hedra_geom::DVec3::new(1.0, 0.0, 0.0)),
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
                transform: NodeTransform::IDENTITY,
            }),
        );
    }
    let ents = node_entities(&mut app);
    let before_b = app.world().get::<ShownMesh>(ents[1].0).unwrap().clone();
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
        *app.world().get::<ShownMesh>(ents[1].0).unwrap(),
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
            transform: NodeTransform::IDENTITY,
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
        let mut patched = render_mesh(&old, shading, &Default::default());
        assert!(update_render_positions(&mut patched, &old, &new, shading).is_some());
        let rebuilt = render_mesh(&new, shading, &Default::default());
        for a in [Mesh::ATTRIBUTE_POSITION, Mesh::ATTRIBUTE_NORMAL] {
            let (p, r) = (attr(&patched, a), attr(&rebuilt, a));
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
        let mut m = render_mesh(&old, shading, &Default::default());
        assert!(update_render_positions(&mut m, &old, &cut, shading).is_none());
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
            transform: NodeTransform::IDENTITY,
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
            .get::<NodeMesh>(e)
            .unwrap()
            .active_modifier()
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
    // The positions and normals written in place are those of a preview
    // made from scratch for the moved cage (in both shadings).
    let attributes = |app: &mut App| {
        let e = node_entities(app)[0].0;
        let h = app.world().get::<Mesh3d>(e).unwrap().0.clone();
        let m = app.world().resource::<Assets<Mesh>>().get(&h).unwrap();
        let f = |id| match m.attribute(id) {
            Some(bevy::mesh::VertexAttributeValues::Float32x3(v)) => v.clone(),
            _ => panic!("f32x3 attribute"),
        };
        (f(Mesh::ATTRIBUTE_POSITION), f(Mesh::ATTRIBUTE_NORMAL))
    };
    for (step, shading) in [hedra_doc::Shading::Smooth, hedra_doc::Shading::Flat]
        .into_iter()
        .enumerate()
    {
        if step > 0 {
            send(
                &mut app,
                DocRequest::Execute(Command::SetShading {
                    nodes: vec![NodeRef::Name("Box".into())],
                    shading,
                }),
            );
        }
        // A move after the shading is set: the preview is rewritten in place.
        send(
            &mut app,
            DocRequest::Execute(Command::MoveVertices {
                node: NodeRef::Name("Box".into()),
                vertices: hedra_doc::elements::VertexSet::Ids(vec![step as u32 + 1]),
                offset: hedra_geom::DVec3::new(0.25, 0.0, 0.0),
            }),
        );
        let mut fresh = hedra::headless_app();
        fresh.update();
        let doc = app
            .world()
            .resource::<hedra_scene::DocState>()
            .session
            .doc
            .clone();
        let hedra_doc::NodeContent::Mesh(moved) = &doc.find_by_name("Box").unwrap().content else {
            panic!("a mesh")
        };
        send(
            &mut fresh,
            DocRequest::Execute(Command::AddMesh {
                name: "Box".into(),
                positions: moved
                    .mesh
                    .vertices()
                    .map(|v| moved.mesh.position(v))
                    .collect(),
                polygons: moved
                    .mesh
                    .faces()
                    .map(|f| moved.mesh.face_vertices(f).map(|v| v.0).collect())
                    .collect(),
                parent: None,
                transform: NodeTransform::IDENTITY,
            }),
        );
        for command in [
            Command::SetShading {
                nodes: vec![NodeRef::Name("Box".into())],
                shading,
            },
            Command::SetSubdivision {
                nodes: vec![NodeRef::Name("Box".into())],
                modifier: Some(hedra_doc::SubdivisionModifier::with_level(2)),
            },
        ] {
            send(&mut fresh, DocRequest::Execute(command));
        }
        // Equal up to rounding (stencils applied to the moved cage, or the
        // moved cage refined level by level).
        let (a, b) = (attributes(&mut app), attributes(&mut fresh));
        assert_eq!(
            (a.0.len(), a.1.len()),
            (b.0.len(), b.1.len()),
            "{shading:?}"
        );
        let close = |x: &[[f32; 3]], y: &[[f32; 3]]| {
            x.iter()
                .zip(y)
                .all(|(p, q)| (0..3).all(|k| (p[k] - q[k]).abs() < 1e-5))
        };
        assert!(close(&a.0, &b.0) && close(&a.1, &b.1), "{shading:?}");
    }
    send(
        &mut app,
        DocRequest::Execute(Command::SetShading {
            nodes: vec![NodeRef::Name("Box".into())],
            shading: hedra_doc::Shading::Smooth,
        }),
    );
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
            transform: NodeTransform::IDENTITY,
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
            transform: NodeTransform::IDENTITY,
        }),
    );
    send(
        &mut app,
        DocRequest::Execute(Command::AddCurve {
            name: "Ring".into(),
            curve: CurveSpec::Circle { radius: 3.0 },
            parent: None,
            transform: NodeTransform::IDENTITY,
        }),
    );
    let ents = node_entities(&mut app);
    let (ball, ring) = (ents[0].0, ents[1].0);
    let positions = |app: &mut App| {
        patch_meshes(app, ball)
            .into_iter()
            .flat_map(|(_, p)| p)
            .collect::<Vec<_>>()
    };
    assert!(
        app.world().get::<Mesh3d>(ball).is_none(),
        "a surface is drawn by its patches"
    );
    let points = control_point_entities(&mut app, ball);
    let doc_points = {
        let doc = &app.world().resource::<DocState>().session.doc;
        hedra_scene::control_points(&doc.find_by_name("Ball").unwrap().content)
    };
    assert_eq!(
        points.iter().map(|p| p.position).collect::<Vec<_>>(),
        doc_points,
        "one entity per control point, in order"
    );
    assert!(points.iter().enumerate().all(|(i, p)| p.index == i as u32));
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
        app.world().get::<ShownShape>(ring).is_some(),
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

/// The patch entities of a surface node: each patch's mesh handle and positions.
fn patch_meshes(app: &mut App, node: Entity) -> Vec<(Handle<Mesh>, Vec<[f32; 3]>)> {
    let world = app.world();
    let children: Vec<Entity> = world
        .get::<Children>(node)
        .map(|c| c.iter().collect())
        .unwrap_or_default();
    children
        .into_iter()
        .filter(|c| world.get::<hedra_scene::SurfacePatch>(*c).is_some())
        .map(|c| {
            let h = world.get::<Mesh3d>(c).unwrap().0.clone();
            let m = world.resource::<Assets<Mesh>>().get(&h).unwrap();
            let p = match m.attribute(Mesh::ATTRIBUTE_POSITION) {
                Some(bevy::mesh::VertexAttributeValues::Float32x3(p)) => p.clone(),
                _ => panic!("positions"),
            };
            (h, p)
        })
        .collect()
}

/// The input control points of each patch of a surface node.
fn patch_inputs(app: &mut App, node: Entity) -> Vec<Vec<u32>> {
    let world = app.world();
    world
        .get::<Children>(node)
        .into_iter()
        .flatten()
        .filter_map(|c| world.get::<hedra_scene::SurfacePatch>(*c))
        .map(|p| {
            p.tile
                .as_ref()
                .map(|t| t.inputs.clone())
                .unwrap_or_default()
        })
        .collect()
}

/// The control-point entities of a node, by index.
fn control_point_entities(app: &mut App, node: Entity) -> Vec<hedra_scene::ControlPoint> {
    let world = app.world();
    let mut points: Vec<hedra_scene::ControlPoint> = world
        .get::<Children>(node)
        .into_iter()
        .flatten()
        .filter_map(|c| world.get::<hedra_scene::ControlPoint>(*c).copied())
        .collect();
    points.sort_by_key(|p| p.index);
    points
}

/// A weight change moves the weight's control-point entity alone, and only
/// the patches that point shapes are re-tessellated (found by Bevy's change
/// detection); the surface shown equals the new surface everywhere.
#[test]
fn a_weight_change_re_tessellates_only_the_patches_it_can_reach() {
    use bevy::asset::AssetEvent;
    use hedra_doc::command::SurfaceSpec;
    let mut app = hedra::headless_app();
    app.update();
    send(
        &mut app,
        DocRequest::Execute(Command::AddSurface {
            name: "Sheet".into(),
            surface: SurfaceSpec::Nurbs {
                degree_u: 3,
                degree_v: 3,
                nu: 8,
                nv: 8,
                points: (0..64)
                    .map(|k| {
                        let (i, j) = ((k / 8) as f64, (k % 8) as f64);
                        hedra_geom::DVec3::new(i, ((i + j) * 0.7).sin(), j)
                    })
                    .collect(),
                weights: None,
                knots_u: None,
                knots_v: None,
            },
            parent: None,
            transform: NodeTransform::IDENTITY,
        }),
    );
    let sheet = node_entities(&mut app)[0].0;
    let before = patch_meshes(&mut app, sheet);
    assert_eq!(before.len(), 25, "a 8 × 8 cubic patch has 5 × 5 knot spans");
    let points_before = control_point_entities(&mut app, sheet);
    // A weight drag shows its surface as a preview, as the W tool does.
    let (id, surface) = {
        let doc = &app.world().resource::<DocState>().session.doc;
        let node = doc.find_by_name("Sheet").unwrap();
        let hedra_doc::NodeContent::Surface(s) = &node.content else {
            panic!("a surface")
        };
        let hedra_doc::SurfaceShape::Nurbs(n) = &**s else {
            panic!("NURBS")
        };
        let mut n = n.clone();
        n.set_weight(0, 0, 4.0).unwrap();
        (node.id, n)
    };
    {
        let mut previews = app.world_mut().resource_mut::<hedra_scene::Previews>();
        hedra_scene::Previews::show(
            &mut previews,
            hedra_scene::PreviewSource::ShapeTool,
            hedra_scene::ToolPreview {
                contents: [(
                    id,
                    hedra_scene::PreviewContent::Surface(std::sync::Arc::new(
                        hedra_doc::SurfaceShape::Nurbs(surface.clone()),
                    )),
                )]
                .into(),
                ..Default::default()
            },
        );
    }
    app.update();
    // The render meshes the frame rewrote.
    let rewritten: Vec<_> = app
        .world()
        .resource::<Messages<AssetEvent<Mesh>>>()
        .iter_current_update_messages()
        .filter_map(|e| match e {
            AssetEvent::Modified { id } => Some(*id),
            _ => None,
        })
        .collect();
    let after = patch_meshes(&mut app, sheet);
    assert_eq!(
        after.iter().map(|(h, _)| h.id()).collect::<Vec<_>>(),
        before.iter().map(|(h, _)| h.id()).collect::<Vec<_>>(),
        "the patches stay (only a weight changed)"
    );
    // Point 0 (a corner) shapes the corner's knot span: the patches that
    // list it as an input are rewritten, no others.
    let reached: Vec<_> = patch_inputs(&mut app, sheet)
        .into_iter()
        .zip(&after)
        .filter(|(inputs, _)| inputs.contains(&0))
        .map(|(_, (h, _))| h.id())
        .collect();
    assert!(!reached.is_empty() && reached.len() <= 4, "{reached:?}");
    assert_eq!(rewritten, reached);
    for ((h, a), (_, b)) in before.iter().zip(&after) {
        if !reached.contains(&h.id()) {
            assert_eq!(a, b, "untouched patches keep their triangles");
        }
    }
    let points_after = control_point_entities(&mut app, sheet);
    assert_eq!(points_after[0].weight, 4.0);
    assert_eq!(points_after[1..], points_before[1..]);
    // Each rewritten patch shows the previewed surface on the layout's
    // grid (made from the document's surface), as the Bevy-free tile
    // evaluation gives it.
    let original = {
        let doc = &app.world().resource::<DocState>().session.doc;
        match &doc.find_by_name("Sheet").unwrap().content {
            hedra_doc::NodeContent::Surface(s) => match &**s {
                hedra_doc::SurfaceShape::Nurbs(n) => n.clone(),
                _ => panic!("NURBS"),
            },
            _ => panic!("a surface"),
        }
    };
    let grid = hedra_scene::surface_grid(&original);
    let tiles = hedra_doc::render::surface_tiles(&original, &grid);
    for (tile, (h, shown)) in tiles.iter().zip(&after) {
        if reached.contains(&h.id()) {
            let want = hedra_doc::render::tile_buffers(&surface, &grid, tile);
            assert_eq!(shown, &want.positions);
        }
    }
}

fn add_cube(name: &str) -> DocRequest {
    DocRequest::Execute(Command::AddPrimitive {
        primitive: Primitive::Cube { size: 1.0 },
        name: Some(name.into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
}

/// A big file opens and saves on a worker thread: frames go on meanwhile,
/// requests sent while it opens apply to the opened scene, in order; edits
/// made while it saves go on, and the file holds the scene as it was when
/// the save began.
#[test]
fn big_files_open_and_save_off_the_frame() {
    let dir = tempfile::tempdir().unwrap();
    let big = dir.path().join("big.hedra.ron");
    let mut session = hedra_doc::Session::new();
    session
        .execute(&Command::AddPrimitive {
            primitive: Primitive::Grid {
                x_segments: 200,
                z_segments: 200,
                size: 10.0,
            },
            name: Some("Dense".into()),
            parent: None,
            transform: NodeTransform::IDENTITY,
        })
        .unwrap();
    hedra_doc::file::save(&mut session, &big).unwrap();

    let mut app = hedra::headless_app();
    app.update();
    app.world_mut().write_message(DocRequest::Open(big.clone()));
    app.world_mut().write_message(add_cube("After"));
    app.update();
    let jobs = app.world().resource::<hedra_scene::FileJobs>();
    assert!(jobs.busy(), "the file is read on a worker thread");
    assert!(
        jobs.describe().unwrap().starts_with("Opening"),
        "{:?}",
        jobs.describe()
    );
    let doc = &app.world().resource::<DocState>().session.doc;
    assert_eq!(
        doc.nodes().count(),
        0,
        "the cube waits for the opened scene"
    );
    wait_for_files(&mut app);
    app.update();
    let names = |app: &App| -> Vec<String> {
        let doc = &app.world().resource::<DocState>().session.doc;
        doc.nodes().map(|n| n.name.clone()).collect()
    };
    assert_eq!(names(&app), ["Dense", "After"]);
    assert_eq!(
        app.world().resource::<DocState>().path.as_deref(),
        Some(big.as_path())
    );

    // Save, and add a node in the same frame: the node is added at once,
    // the file gets the scene without it, and the scene stays unsaved.
    let copy = dir.path().join("copy.hedra.ron");
    app.world_mut()
        .write_message(DocRequest::Save(copy.clone()));
    app.world_mut().write_message(add_cube("During"));
    app.update();
    assert!(app.world().resource::<hedra_scene::FileJobs>().busy());
    assert_eq!(names(&app), ["Dense", "After", "During"], "edits go on");
    wait_for_files(&mut app);
    let saved = hedra_doc::file::load(&copy).unwrap().session;
    let saved_names: Vec<_> = saved.doc.nodes().map(|n| n.name.clone()).collect();
    assert_eq!(saved_names, ["Dense", "After"]);
    let state = app.world().resource::<DocState>();
    assert!(state.session.is_dirty(), "the last edit is not in the file");
    assert_eq!(state.path.as_deref(), Some(copy.as_path()));
    // Undo reaches back into the opened file's history.
    send(&mut app, DocRequest::Undo);
    send(&mut app, DocRequest::Undo);
    assert_eq!(names(&app), ["Dense"]);
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
            transform: NodeTransform::IDENTITY,
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
        .transform_edit = Some((node, NodeTransform::IDENTITY));
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
    while !meta.exists() || app.world().resource::<Recovery>().is_writing() {
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
                transform: NodeTransform::IDENTITY,
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

/// An infinitely sharp crease splits the normals of a smooth-shaded cage
/// too, not only of its subdivided surface (issue 31, item 9): a cube with
/// its top loop sharp is drawn with 12 render vertices (each top corner
/// once for the top, once for the sides), 8 again when the crease goes.
#[test]
fn a_sharp_crease_splits_the_cage_normals_on_screen() {
    let mut app = hedra::headless_app();
    app.update();
    send(
        &mut app,
        DocRequest::Execute(Command::AddPrimitive {
            primitive: Primitive::Cube { size: 2.0 },
            name: Some("Box".into()),
            parent: None,
            transform: NodeTransform::IDENTITY,
        }),
    );
    let render_vertices = |app: &mut App| {
        let entity = node_entities(app)[0].0;
        let handle = app.world().get::<Mesh3d>(entity).unwrap().0.clone();
        let meshes = app.world().resource::<Assets<Mesh>>();
        meshes.get(&handle).unwrap().count_vertices()
    };
    send(
        &mut app,
        DocRequest::Execute(Command::SetShading {
            nodes: vec![NodeRef::Name("Box".into())],
            shading: hedra_doc::Shading::Smooth,
        }),
    );
    assert_eq!(render_vertices(&mut app), 8, "smooth: corners shared");
    let crease = |sharpness: f64| -> Command {
        let text = format!(
            "[SetEdgeCrease(node: Name(\"Box\"), edges: OfFaces(Facing(direction: (0.0, 1.0, 0.0), degrees: 1.0)), sharpness: {sharpness:?})]"
        );
        hedra_doc::script::parse(&text, std::path::Path::new("crease.ron"))
            .unwrap()
            .remove(0)
    };
    send(&mut app, DocRequest::Execute(crease(10.0)));
    assert_eq!(render_vertices(&mut app), 12, "the sharp rim splits");
    send(&mut app, DocRequest::Execute(crease(0.0)));
    assert_eq!(render_vertices(&mut app), 8);
}
