//! Commands, undo/redo and the scene graph.

use glam::{DQuat, DVec3};
use hedra_doc::{Command, CommandError, NodeContent, NodeRef, NodeTransform, Session};
use hedra_geom::Primitive;
use proptest::prelude::*;

fn name(n: &str) -> NodeRef {
    NodeRef::Name(n.into())
}

fn add(p: Primitive, n: &str) -> Command {
    Command::AddPrimitive {
        primitive: p,
        name: Some(n.into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    }
}

fn cube() -> Primitive {
    Primitive::Cube { size: 2.0 }
}

#[test]
fn add_undo_redo_restores_exact_documents() {
    let mut s = Session::new();
    let empty = s.doc.clone();
    s.execute(&add(cube(), "Box")).unwrap();
    let one = s.doc.clone();
    s.execute(&Command::Translate {
        nodes: vec![name("Box")],
        offset: DVec3::new(1.0, 2.0, 3.0),
    })
    .unwrap();
    let two = s.doc.clone();
    assert_eq!(s.undo().as_deref(), Some("Move 1 node"));
    assert_eq!(s.doc, one);
    assert_eq!(s.undo().as_deref(), Some("Add Cube"));
    assert_eq!(s.doc, empty);
    assert_eq!(s.undo(), None);
    s.redo();
    s.redo();
    assert_eq!(s.doc, two);
    let node = s.doc.find_by_name("Box").unwrap();
    assert_eq!(node.transform.translation, DVec3::new(1.0, 2.0, 3.0));
}

#[test]
fn names_are_made_unique_like_blender() {
    let mut s = Session::new();
    for _ in 0..3 {
        s.execute(&add(cube(), "Cube")).unwrap();
    }
    let names: Vec<_> = s.doc.nodes().map(|n| n.name.clone()).collect();
    assert_eq!(names, ["Cube", "Cube.001", "Cube.002"]);
    s.execute(&Command::Duplicate {
        nodes: vec![name("Cube.001")],
    })
    .unwrap();
    assert!(s.doc.find_by_name("Cube.003").is_some());
}

#[test]
fn world_transforms_compose_parents_and_reparent_keeps_world_position() {
    let mut s = Session::new();
    s.execute(&Command::AddEmpty {
        name: "Base".into(),
        parent: None,
        transform: NodeTransform {
            translation: DVec3::new(10.0, 0.0, 0.0),
            rotation: DQuat::from_rotation_y(90f64.to_radians()),
            scale: DVec3::splat(2.0),
        },
    })
    .unwrap();
    s.execute(&Command::AddPrimitive {
        primitive: cube(),
        name: Some("Arm".into()),
        parent: Some(name("Base")),
        transform: NodeTransform::from_translation(DVec3::new(1.0, 0.0, 0.0)),
    })
    .unwrap();
    let arm = s.doc.find_by_name("Arm").unwrap().id;
    // Base rotates +X to -Z and scales by 2: (1,0,0) -> (0,0,-2), then moves by 10 in X.
    let world = s.doc.world_transform(arm);
    assert!(
        world
            .translation
            .abs_diff_eq(DVec3::new(10.0, 0.0, -2.0), 1e-12),
        "{:?}",
        world.translation
    );
    assert!(world.scale.abs_diff_eq(DVec3::splat(2.0), 1e-12));
    s.execute(&Command::Reparent {
        node: name("Arm"),
        parent: None,
        keep_world: true,
    })
    .unwrap();
    let after = s.doc.world_transform(arm);
    assert!(
        after
            .translation
            .abs_diff_eq(DVec3::new(10.0, 0.0, -2.0), 1e-9)
    );
    assert!(after.scale.abs_diff_eq(DVec3::splat(2.0), 1e-9));
    assert_eq!(s.doc.node(arm).unwrap().parent, None);
    // Without keep_world the local transform (now (10, 0, -2)) stays and the
    // parent applies on top: rotate to (-2, 0, -10), scale to (-4, 0, -20), move by 10.
    s.execute(&Command::Reparent {
        node: name("Arm"),
        parent: Some(name("Base")),
        keep_world: false,
    })
    .unwrap();
    let t = s.doc.world_transform(arm).translation;
    assert!(t.abs_diff_eq(DVec3::new(6.0, 0.0, -20.0), 1e-9), "{t:?}");
}

#[test]
fn errors_name_the_culprit_and_change_nothing() {
    let mut s = Session::new();
    s.execute(&Command::AddEmpty {
        name: "A".into(),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s.execute(&Command::AddEmpty {
        name: "B".into(),
        parent: Some(name("A")),
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let before = s.clone();
    let e = s
        .execute(&Command::Reparent {
            node: name("A"),
            parent: Some(name("B")),
            keep_world: true,
        })
        .unwrap_err();
    assert!(matches!(e, CommandError::Cycle { .. }), "{e}");
    assert!(e.to_string().contains("its own ancestor"));
    let e = s
        .execute(&Command::Delete {
            nodes: vec![NodeRef::Id(99)],
        })
        .unwrap_err();
    assert_eq!(e.to_string(), "node #99 does not exist");
    let e = s
        .execute(&Command::Scale {
            nodes: vec![name("A")],
            factor: DVec3::new(1.0, 0.0, 1.0),
        })
        .unwrap_err();
    assert!(matches!(e, CommandError::BadTransform { .. }));
    let e = s
        .execute(&Command::AddMesh {
            name: "Bad".into(),
            positions: vec![DVec3::ZERO; 3],
            polygons: vec![vec![0, 1, 5]],
            parent: None,
            transform: NodeTransform::IDENTITY,
        })
        .unwrap_err();
    assert!(e.to_string().contains("face 0 refers to vertex 5"), "{e}");
    let e = s
        .execute(&add(
            Primitive::UvSphere {
                segments: 1,
                rings: 2,
                radius: 1.0,
            },
            "S",
        ))
        .unwrap_err();
    assert!(e.to_string().contains("segments"), "{e}");
    assert_eq!(s, before);
}

#[test]
fn delete_takes_descendants_and_undo_brings_them_back() {
    let mut s = Session::new();
    s.execute(&Command::AddEmpty {
        name: "A".into(),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s.execute(&add(cube(), "C")).unwrap();
    s.execute(&Command::Reparent {
        node: name("C"),
        parent: Some(name("A")),
        keep_world: true,
    })
    .unwrap();
    let full = s.doc.clone();
    s.execute(&Command::Delete {
        nodes: vec![name("A")],
    })
    .unwrap();
    assert_eq!(s.doc.node_count(), 0);
    s.undo();
    assert_eq!(s.doc, full);
}

#[test]
fn duplicate_copies_subtrees_with_new_ids_and_shared_meshes() {
    let mut s = Session::new();
    s.execute(&Command::AddEmpty {
        name: "A".into(),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s.execute(&Command::AddPrimitive {
        primitive: cube(),
        name: Some("C".into()),
        parent: Some(name("A")),
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let applied = s
        .execute(&Command::Duplicate {
            nodes: vec![name("A")],
        })
        .unwrap();
    assert_eq!(applied.created.len(), 2);
    let a1 = s.doc.find_by_name("A.001").unwrap();
    let c1 = s.doc.find_by_name("C.001").unwrap();
    assert_eq!(c1.parent, Some(a1.id));
    let (NodeContent::Mesh(m0), NodeContent::Mesh(m1)) =
        (&s.doc.find_by_name("C").unwrap().content, &c1.content)
    else {
        panic!()
    };
    assert!(
        std::sync::Arc::ptr_eq(&m0.mesh, &m1.mesh),
        "copies share the mesh until edited"
    );
}

#[test]
fn adjust_last_operation_rebuilds_the_primitive_in_one_step() {
    let mut s = Session::new();
    s.execute(&add(
        Primitive::UvSphere {
            segments: 8,
            rings: 4,
            radius: 1.0,
        },
        "S",
    ))
    .unwrap();
    s.adjust_last(&add(
        Primitive::UvSphere {
            segments: 16,
            rings: 8,
            radius: 2.0,
        },
        "S",
    ))
    .unwrap();
    assert_eq!(s.history.done().len(), 1);
    let m = s
        .doc
        .find_by_name("S")
        .unwrap()
        .content
        .mesh()
        .unwrap()
        .clone();
    assert_eq!(m.face_count(), 16 * 8);
    // A bad adjustment keeps the previous result.
    let e = s
        .adjust_last(&add(
            Primitive::UvSphere {
                segments: 0,
                rings: 8,
                radius: 2.0,
            },
            "S",
        ))
        .unwrap_err();
    assert!(e.to_string().contains("segments"));
    assert_eq!(
        s.doc
            .find_by_name("S")
            .unwrap()
            .content
            .mesh()
            .unwrap()
            .face_count(),
        128
    );
    assert_eq!(s.history.done().len(), 1);
    // SetPrimitive on a node made from another kind is refused.
    s.execute(&add(cube(), "C")).unwrap();
    let e = s
        .execute(&Command::SetPrimitive {
            node: name("C"),
            primitive: Primitive::Plane { size: 1.0 },
        })
        .unwrap_err();
    assert!(matches!(e, CommandError::NotAPrimitive { .. }));
}

#[test]
fn history_limits_drop_the_oldest_steps_and_the_rest_still_undo() {
    let mut s = Session::new();
    s.history.max_steps = 3;
    s.execute(&add(cube(), "C")).unwrap();
    let mut states = vec![s.doc.clone()];
    for i in 0..5 {
        s.execute(&Command::Translate {
            nodes: vec![name("C")],
            offset: DVec3::X * (i + 1) as f64,
        })
        .unwrap();
        states.push(s.doc.clone());
    }
    assert_eq!(s.history.done().len(), 3);
    assert_eq!(s.history.dropped, 3);
    for expected in states.iter().rev().skip(1).take(3) {
        s.undo();
        assert_eq!(&s.doc, expected);
    }
    assert_eq!(s.undo(), None);
    // Memory cap: a tiny cap keeps only the newest step.
    s.history.max_bytes = 1;
    s.execute(&add(cube(), "D")).unwrap();
    s.execute(&add(cube(), "E")).unwrap();
    assert_eq!(s.history.done().len(), 1);
}

#[test]
fn jump_to_moves_through_history() {
    let mut s = Session::new();
    let mut states = vec![s.doc.clone()];
    for k in Primitive::KINDS {
        s.execute(&add(Primitive::default_of(k).unwrap(), k))
            .unwrap();
        states.push(s.doc.clone());
    }
    s.jump_to(2);
    assert_eq!(s.doc, states[2]);
    s.jump_to(7);
    assert_eq!(s.doc, states[7]);
    assert!(s.is_dirty());
    s.jump_to(0);
    assert_eq!(s.doc, states[0]);
    assert!(!s.is_dirty(), "back at the saved (empty) state");
}

fn arb_command() -> impl Strategy<Value = Command> {
    let node = (0u64..8).prop_map(NodeRef::Id);
    let kinds = prop::sample::select(Primitive::KINDS.to_vec());
    prop_oneof![
        (kinds, prop::option::of(node.clone())).prop_map(|(k, parent)| Command::AddPrimitive {
            primitive: match Primitive::default_of(k).unwrap() {
                Primitive::UvSphere { .. } => Primitive::UvSphere {
                    segments: 6,
                    rings: 4,
                    radius: 1.0
                },
                Primitive::Torus { .. } => Primitive::Torus {
                    major_segments: 6,
                    minor_segments: 4,
                    major_radius: 1.0,
                    minor_radius: 0.3
                },
                Primitive::Cylinder { .. } => Primitive::Cylinder {
                    segments: 5,
                    radius: 1.0,
                    depth: 1.0
                },
                Primitive::Cone { .. } => Primitive::Cone {
                    segments: 5,
                    radius: 1.0,
                    depth: 1.0
                },
                Primitive::IcoSphere { .. } => Primitive::IcoSphere {
                    subdivisions: 0,
                    radius: 1.0
                },
                p => p,
            },
            name: None,
            parent,
            transform: NodeTransform::IDENTITY,
        }),
        (node.clone(), -5.0..5.0f64).prop_map(|(n, x)| Command::Translate {
            nodes: vec![n],
            offset: DVec3::new(x, 1.0, -x)
        }),
        (node.clone(), 0.0..360.0f64).prop_map(|(n, d)| Command::Rotate {
            nodes: vec![n],
            axis: DVec3::Y,
            degrees: d
        }),
        (node.clone(), prop::option::of(node.clone()), any::<bool>()).prop_map(
            |(n, p, keep_world)| Command::Reparent {
                node: n,
                parent: p,
                keep_world
            }
        ),
        node.clone()
            .prop_map(|n| Command::Delete { nodes: vec![n] }),
        node.clone()
            .prop_map(|n| Command::Duplicate { nodes: vec![n] }),
        (node.clone(), "[a-z]{1,6}").prop_map(|(n, name)| Command::Rename { node: n, name }),
        (node, any::<bool>()).prop_map(|(n, v)| Command::SetVisible {
            nodes: vec![n],
            visible: v
        }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_sequences_undo_to_the_start_and_redo_to_the_end(cmds in prop::collection::vec(arb_command(), 1..25)) {
        let mut s = Session::new();
        let initial = s.doc.clone();
        for c in &cmds {
            let before = s.clone();
            if s.execute(c).is_err() {
                prop_assert_eq!(&s, &before, "a failed command changed the session");
            }
            prop_assert!(s.doc.check().is_ok());
        }
        let fin = s.doc.clone();
        let steps = s.history.done().len();
        while s.undo().is_some() {}
        prop_assert_eq!(&s.doc, &initial);
        for _ in 0..steps { s.redo(); }
        prop_assert_eq!(&s.doc, &fin);
    }
}

#[test]
fn mesh_commands_edit_the_mesh_undo_exactly_and_name_bad_elements() {
    use hedra_doc::{EdgeSet, FaceSet, VertexSet};
    let mut s = Session::new();
    s.execute(&add(cube(), "C")).unwrap();
    let before = s.doc.clone();
    s.execute(&Command::ExtrudeFaces {
        node: name("C"),
        faces: FaceSet::Facing {
            direction: DVec3::Y,
            degrees: 1.0,
        },
        distance: 1.0,
    })
    .unwrap();
    let m = s
        .doc
        .find_by_name("C")
        .unwrap()
        .content
        .mesh()
        .unwrap()
        .clone();
    assert_eq!(m.face_count(), 10);
    assert!(
        matches!(&s.doc.find_by_name("C").unwrap().content, NodeContent::Mesh(c) if c.primitive.is_none()),
        "an edited primitive is a plain mesh"
    );
    s.execute(&Command::LoopCut {
        node: name("C"),
        edge: EdgeSet::Nearest(DVec3::new(1.0, 0.0, 1.0)),
        cuts: 1,
    })
    .unwrap();
    assert_eq!(
        s.doc
            .find_by_name("C")
            .unwrap()
            .content
            .mesh()
            .unwrap()
            .face_count(),
        14
    );
    s.undo();
    s.undo();
    assert_eq!(s.doc, before);

    let e = s
        .execute(&Command::ExtrudeFaces {
            node: name("C"),
            faces: FaceSet::Ids(vec![99]),
            distance: 1.0,
        })
        .unwrap_err();
    assert_eq!(e.to_string(), "'C' (#1): face f99 does not exist");
    let e = s
        .execute(&Command::ConnectVertices {
            node: name("C"),
            vertices: VertexSet::Ids(vec![0, 7]),
        })
        .unwrap_err();
    assert!(e.to_string().contains("do not share a face"), "{e}");
    let e = s
        .execute(&Command::LoopCut {
            node: name("C"),
            edge: EdgeSet::All,
            cuts: 1,
        })
        .unwrap_err();
    assert!(e.to_string().contains("exactly one edge"), "{e}");
    let e = s
        .execute(&Command::ExtrudeFaces {
            node: name("C"),
            faces: FaceSet::Facing {
                direction: DVec3::new(1.0, 1.0, 1.0),
                degrees: 5.0,
            },
            distance: 1.0,
        })
        .unwrap_err();
    assert!(e.to_string().contains("no face matches"), "{e}");
    s.execute(&Command::AddEmpty {
        name: "E".into(),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let e = s
        .execute(&Command::FlipNormals { node: name("E") })
        .unwrap_err();
    assert!(matches!(e, CommandError::NotAMesh { .. }));
}

/// A region extrude or inset reports the faces it made (issue 12: tools
/// select exactly those instead of guessing from face ids).
#[test]
fn region_extrude_and_inset_report_the_faces_they_make() {
    let mut s = Session::new();
    s.execute(&add(cube(), "Box")).unwrap();
    let top = hedra_doc::FaceSet::Facing {
        direction: DVec3::Y,
        degrees: 1.0,
    };
    for (cmd, centre_y) in [
        (
            Command::ExtrudeRegion {
                node: name("Box"),
                faces: top.clone(),
                distance: 0.5,
            },
            1.5,
        ),
        (
            Command::InsetRegion {
                node: name("Box"),
                faces: top.clone(),
                thickness: 0.25,
                depth: 0.0,
            },
            1.0,
        ),
    ] {
        let decision = s.doc.decide_with_result(&cmd, 1).unwrap();
        assert_eq!(decision.created_faces.len(), 1, "{cmd:?}");
        let node = decision.transaction.changes[0].after.as_ref().unwrap();
        let mesh = node.content.mesh().unwrap();
        let f = decision.created_faces[0];
        assert!(mesh.is_face(f));
        assert!(
            (mesh.face_centroid(f).y - centre_y).abs() < 1e-12,
            "{cmd:?}"
        );
        assert!(mesh.face_normal(f).dot(DVec3::Y) > 0.999, "{cmd:?}");
    }
    let move_cmd = Command::Translate {
        nodes: vec![name("Box")],
        offset: DVec3::X,
    };
    assert!(
        s.doc
            .decide_with_result(&move_cmd, 1)
            .unwrap()
            .created_faces
            .is_empty()
    );
}

/// Knife (K): a cut across a cube's front face, as the viewport gives it
/// (points in local space, the view direction), splits only the front
/// face, reports the cut edge, and undoes to the plain cube.
#[test]
fn knife_cuts_the_front_of_a_cube_and_reports_the_cut_edge() {
    let mut s = Session::new();
    s.execute(&add(cube(), "Box")).unwrap();
    let before = s.doc.clone();
    let knife = Command::Knife {
        node: name("Box"),
        points: vec![DVec3::new(0.0, 1.0, 1.0), DVec3::new(0.0, -1.0, 1.0)],
        view: DVec3::NEG_Z,
    };
    assert_eq!(knife.label(), "Knife");
    let decision = s.doc.decide_with_result(&knife, 1).unwrap();
    let node = decision.transaction.changes[0].after.as_ref().unwrap();
    let mesh = node.content.mesh().unwrap();
    mesh.validate().unwrap();
    assert_eq!(
        (mesh.vertex_count(), mesh.edge_count(), mesh.face_count()),
        (10, 15, 7)
    );
    let [e] = decision.created_edges[..] else {
        panic!("one cut edge: {:?}", decision.created_edges);
    };
    let ends = mesh.edge_vertices(e).map(|v| mesh.position(v));
    assert_eq!(
        ends,
        [DVec3::new(0.0, 1.0, 1.0), DVec3::new(0.0, -1.0, 1.0)]
    );
    assert!(decision.created_faces.is_empty());

    s.execute(&knife).unwrap();
    let mesh = s.doc.find_by_name("Box").unwrap().content.mesh().unwrap();
    assert_eq!(mesh.face_count(), 7);
    assert_eq!(s.undo().as_deref(), Some("Knife"));
    assert_eq!(s.doc, before);

    // A point off the surface is refused, naming the node and the point.
    let off = Command::Knife {
        node: name("Box"),
        points: vec![DVec3::new(0.0, 1.0, 1.0), DVec3::new(0.0, 0.0, 2.0)],
        view: DVec3::NEG_Z,
    };
    let err = s.execute(&off).unwrap_err();
    assert!(
        matches!(
            &err,
            CommandError::Modeling {
                error: hedra_geom::ModelingError::NotOnSurface { index: 1, .. },
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("knife point 1"), "{err}");
    assert_eq!(s.doc, before);
}
