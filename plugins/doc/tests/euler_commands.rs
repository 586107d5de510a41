//! Rip, vertex split and the Euler operators as commands: their counts,
//! their refusals naming the element, and faces with rings through the
//! whole document (file round trip, undo and redo after reloading, export,
//! subdivision and render buffers).

use hedra_doc::command::{Corner, EulerOp};
use hedra_doc::export::{ExportError, ExportOptions, export_bytes};
use hedra_doc::render::render_buffers;
use hedra_doc::{Command, EdgeSet, FaceSet, NodeRef, Session, Shading, VertexSet};
use hedra_geom::{DVec3, HalfEdgeMesh, Primitive, TopologyCounts};
use std::path::Path;

fn at(x: f64, y: f64, z: f64) -> VertexSet {
    VertexSet::Nearest(DVec3::new(x, y, z))
}

fn node() -> NodeRef {
    NodeRef::Name("Cube".into())
}

fn cube_session() -> Session {
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: Primitive::Cube { size: 2.0 },
        name: Some("Cube".into()),
        parent: None,
        transform: hedra_doc::NodeTransform::IDENTITY,
    })
    .unwrap();
    s
}

fn mesh(s: &Session) -> &HalfEdgeMesh {
    s.doc.find_by_name("Cube").unwrap().content.mesh().unwrap()
}

/// Runs one Euler operator; checks validate() and Euler–Poincaré, returns
/// the change it made.
fn euler(s: &mut Session, op: EulerOp) -> String {
    let before = TopologyCounts::of(mesh(s));
    s.execute(&Command::Euler { node: node(), op }).unwrap();
    let m = mesh(s);
    m.validate().unwrap();
    let after = TopologyCounts::of(m);
    assert!(after.euler_poincare_holds(), "{after}");
    after.since(&before).to_string()
}

/// The KEMR chain of docs/commands.md: a square drawn in the top face and
/// made its ring.
fn ringed() -> Session {
    let mut s = cube_session();
    let steps = [
        ((-1.0, -1.0), (1.0, -1.0), (-0.5, -0.5)),
        ((-0.5, -0.5), (-1.0, -1.0), (0.5, -0.5)),
        ((0.5, -0.5), (-0.5, -0.5), (0.5, 0.5)),
        ((0.5, 0.5), (0.5, -0.5), (-0.5, 0.5)),
    ];
    for ((ax, az), (fx, fz), (px, pz)) in steps {
        let corner = Corner::At {
            at: at(ax, 1.0, az),
            from: at(fx, 1.0, fz),
        };
        let d = euler(
            &mut s,
            EulerOp::Mev {
                corner,
                position: DVec3::new(px, 1.0, pz),
            },
        );
        assert_eq!(d, "V +1, E +1");
    }
    let mef = EulerOp::Mef {
        a: Corner::At {
            at: at(-0.5, 1.0, 0.5),
            from: at(0.5, 1.0, 0.5),
        },
        b: Corner::At {
            at: at(-0.5, 1.0, -0.5),
            from: at(0.5, 1.0, -0.5),
        },
    };
    assert_eq!(euler(&mut s, mef), "E +1, F +1, L +1");
    let kemr = EulerOp::Kemr {
        from: at(-1.0, 1.0, -1.0),
        to: at(-0.5, 1.0, -0.5),
    };
    assert_eq!(euler(&mut s, kemr), "E -1, L +1");
    assert!(mesh(&s).has_rings());
    s
}

#[test]
fn the_kemr_chain_makes_a_ring_and_mekr_joins_it_back() {
    let mut s = ringed();
    assert_eq!(
        TopologyCounts::of(mesh(&s)).to_string(),
        "V 12, E 16, F 7, L 8, S 1, H 0, B 0"
    );
    let mekr = EulerOp::Mekr {
        a: Corner::At {
            at: at(-1.0, 1.0, -1.0),
            from: at(1.0, 1.0, -1.0),
        },
        ring: Corner::At {
            at: at(-0.5, 1.0, -0.5),
            from: at(-0.5, 1.0, 0.5),
        },
    };
    assert_eq!(euler(&mut s, mekr), "E +1, L -1");
    assert!(!mesh(&s).has_rings());
    // The inner square and the top share all four sides now: KEF refuses,
    // naming both faces.
    let err = s
        .execute(&Command::Euler {
            node: node(),
            op: EulerOp::Kef {
                edge: EdgeSet::Nearest(DVec3::new(0.0, 1.0, 0.5)),
            },
        })
        .unwrap_err()
        .to_string();
    assert!(
        err.starts_with("'Cube' (#1): faces f")
            && err.ends_with(
                "share more than one edge; joining them would not give a simple polygon"
            ),
        "{err}"
    );
}

#[test]
fn kfmrh_makes_a_through_hole_and_mfkrh_closes_it() {
    let mut s = cube_session();
    let kfmrh = EulerOp::Kfmrh {
        keep: FaceSet::Nearest(DVec3::Y),
        kill: FaceSet::Nearest(-DVec3::Y),
    };
    assert_eq!(euler(&mut s, kfmrh), "F -1, H +1");
    assert_eq!(mesh(&s).stats().genus, Some(1));
    let mfkrh = EulerOp::Mfkrh {
        ring: Corner::At {
            at: at(-1.0, -1.0, 1.0),
            from: at(1.0, -1.0, 1.0),
        },
    };
    assert_eq!(euler(&mut s, mfkrh), "F +1, H -1");
    let mvfs = EulerOp::Mvfs {
        position: DVec3::new(3.0, 0.0, 0.0),
    };
    assert_eq!(euler(&mut s, mvfs), "V +1, F +1, L +1, S +1");
    let kvfs = EulerOp::Kvfs {
        vertex: at(3.0, 0.0, 0.0),
    };
    assert_eq!(euler(&mut s, kvfs), "V -1, F -1, L -1, S -1");
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    assert_eq!(TopologyCounts::of(mesh(&s)), TopologyCounts::of(&cube));
    assert!(mesh(&s).stats().closed);
}

#[test]
fn refusals_name_the_element_and_change_nothing() {
    let mut s = cube_session();
    let before = mesh(&s).clone();
    let run = |s: &mut Session, op: EulerOp| {
        s.execute(&Command::Euler { node: node(), op })
            .unwrap_err()
            .to_string()
    };
    // KEV on an edge of the cube: no end of valence 1.
    let e = mesh(&s)
        .find_edge(
            mesh(&s).vertices().next().unwrap(),
            mesh(&s)
                .vertex_neighbors(mesh(&s).vertices().next().unwrap())
                .next()
                .unwrap(),
        )
        .unwrap();
    let msg = run(
        &mut s,
        EulerOp::Kev {
            edge: EdgeSet::Ids(vec![e.0]),
        },
    );
    assert_eq!(
        msg,
        format!("'Cube' (#1): {e} is not a dangling edge (no end of valence 1)")
    );
    // A corner along two vertices that share no edge.
    let msg = run(
        &mut s,
        EulerOp::Mev {
            corner: Corner::At {
                at: at(1.0, 1.0, 1.0),
                from: at(-1.0, -1.0, -1.0),
            },
            position: DVec3::ZERO,
        },
    );
    assert!(msg.contains("no edge runs from v"), "{msg}");
    // A set that names several elements.
    let msg = run(&mut s, EulerOp::Kef { edge: EdgeSet::All });
    assert_eq!(
        msg,
        "'Cube' (#1): `edge` must name exactly one element, it names 12"
    );
    // KVFS on a vertex with edges.
    let msg = run(
        &mut s,
        EulerOp::Kvfs {
            vertex: at(1.0, 1.0, 1.0),
        },
    );
    assert!(msg.ends_with("is not the lone vertex of a loop"), "{msg}");
    // Rip on a boundary-free cube edge alone: both ends inside.
    let msg = s
        .execute(&Command::Rip {
            node: node(),
            edges: EdgeSet::Nearest(DVec3::new(1.0, 1.0, 0.0)),
        })
        .unwrap_err()
        .to_string();
    assert!(msg.contains("is ripped alone"), "{msg}");
    assert!(mesh(&s).same_as(&before));
    assert_eq!(s.history.done().len(), 1);
}

#[test]
fn split_vertex_moves_a_range_of_the_fan() {
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: Primitive::Grid {
            x_segments: 4,
            z_segments: 4,
            size: 4.0,
        },
        name: Some("Grid".into()),
        parent: None,
        transform: hedra_doc::NodeTransform::IDENTITY,
    })
    .unwrap();
    let grid = NodeRef::Name("Grid".into());
    s.execute(&Command::SplitVertex {
        node: grid.clone(),
        vertex: at(0.0, 0.0, 0.0),
        first: at(1.0, 0.0, 0.0),
        last: at(0.0, 0.0, -1.0),
        position: DVec3::new(0.3, 0.0, -0.3),
    })
    .unwrap();
    let m = s.doc.find_by_name("Grid").unwrap().content.mesh().unwrap();
    m.validate().unwrap();
    let w = m
        .vertices()
        .find(|&v| m.position(v) == DVec3::new(0.3, 0.0, -0.3))
        .unwrap();
    // The new vertex has the two moved edges, the new one, and the quad
    // between the moved edges.
    let mut around: Vec<DVec3> = m.vertex_neighbors(w).map(|v| m.position(v)).collect();
    around.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.z.total_cmp(&b.z)));
    assert_eq!(around, [DVec3::new(0.0, 0.0, -1.0), DVec3::ZERO, DVec3::X]);
    // A range that takes every edge is refused by name.
    let err = s
        .execute(&Command::SplitVertex {
            node: grid,
            vertex: at(-2.0, 0.0, -2.0),
            first: at(-1.0, 0.0, -2.0),
            last: at(-2.0, 0.0, -1.0),
            position: DVec3::ZERO,
        })
        .unwrap_err()
        .to_string();
    assert!(err.ends_with("'s fan"), "{err}");
}

#[test]
fn a_face_with_a_ring_survives_the_file_undo_and_redo() {
    let s = ringed();
    let ringed_mesh = mesh(&s).clone();
    let text = hedra_doc::file::to_string(&s);
    let mut back = hedra_doc::file::from_str(&text, Path::new("ringed.hedra.ron"))
        .unwrap()
        .session;
    assert!(back.doc.check().is_ok());
    assert!(mesh(&back).same_as(&ringed_mesh));
    assert_eq!(
        mesh(&back)
            .face_rings(
                mesh(&back)
                    .faces()
                    .find(|&f| !mesh(&back).face_rings(f).is_empty())
                    .unwrap()
            )
            .len(),
        1
    );
    // Saving what was read gives the same text.
    assert_eq!(hedra_doc::file::to_string(&back), text);
    // Undo the KEMR: no ring; redo: the ring again, identical.
    assert_eq!(back.undo().as_deref(), Some("Euler KEMR"));
    assert!(!mesh(&back).has_rings());
    mesh(&back).validate().unwrap();
    assert_eq!(back.redo().as_deref(), Some("Euler KEMR"));
    assert!(mesh(&back).same_as(&ringed_mesh));
    // All the way back to the cube and forward again.
    while back.undo().is_some() {}
    assert!(back.doc.find_by_name("Cube").is_none());
    while back.redo().is_some() {}
    assert!(mesh(&back).same_as(&ringed_mesh));
}

#[test]
fn exports_and_subdivision_refuse_a_face_with_a_ring_by_name() {
    let mut s = ringed();
    let m = mesh(&s).clone();
    let face = m.first_non_polygon_face().unwrap();
    for file in ["out.obj", "out.stl", "out.gltf", "out.glb"] {
        let err = export_bytes(&s.doc, Path::new(file), ExportOptions::default()).unwrap_err();
        assert!(
            matches!(&err, ExportError::NotPolygon { node, face: f } if node == "Cube" && *f == face),
            "{file}: {err}"
        );
        assert_eq!(
            err.to_string(),
            format!(
                "node 'Cube': {face} has an inner ring or no edges; OBJ, STL and glTF hold plain polygons only (join the ring to the face's outer loop with MEKR first)"
            )
        );
    }
    let err = s
        .execute(&Command::ApplySubdivision {
            node: node(),
            levels: Some(1),
        })
        .unwrap_err()
        .to_string();
    assert!(err.contains(&face.to_string()), "{err}");
    // The viewport's smooth shape refuses too, instead of panicking.
    let smooth = hedra_doc::smooth::SmoothRefinement::new(
        &std::sync::Arc::new(m.clone()),
        &Default::default(),
        &hedra_doc::SubdivisionModifier::default(),
    );
    assert!(smooth.is_err());
}

#[test]
fn render_buffers_draw_a_face_with_a_ring_by_its_outer_loop() {
    let s = ringed();
    let m = mesh(&s);
    for shading in [Shading::Flat, Shading::Smooth] {
        let b = render_buffers(m, shading);
        // 6 cube faces and the inner square: 7 quads, 14 triangles; the
        // top is its outer square.
        assert_eq!(b.indices.len(), 14 * 3, "{shading:?}");
        assert!(b.indices.iter().all(|&i| (i as usize) < b.positions.len()));
    }
    // A shell of one vertex (MVFS) draws nothing and does not panic.
    let mut shell = HalfEdgeMesh::new();
    shell.make_vertex_face_shell(DVec3::ZERO).unwrap();
    assert!(render_buffers(&shell, Shading::Flat).indices.is_empty());
    assert!(render_buffers(&shell, Shading::Smooth).indices.is_empty());
}

#[test]
fn rip_as_a_command_tears_the_cube_in_two() {
    let mut s = cube_session();
    s.execute(&Command::LoopCut {
        node: node(),
        edge: EdgeSet::Nearest(DVec3::new(1.0, 0.0, 1.0)),
        cuts: 1,
    })
    .unwrap();
    let before = TopologyCounts::of(mesh(&s));
    s.execute(&Command::Rip {
        node: node(),
        edges: EdgeSet::NearestEach(vec![
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::new(-1.0, 0.0, 0.0),
        ]),
    })
    .unwrap();
    let after = TopologyCounts::of(mesh(&s));
    assert_eq!(after.since(&before).to_string(), "V +4, E +4, S +1, B +2");
    assert_eq!(s.history.done().last().unwrap().label, "Rip");
    s.undo();
    assert_eq!(TopologyCounts::of(mesh(&s)), before);
    // Rip one vertex off the top face.
    s.execute(&Command::RipVertex {
        node: node(),
        vertex: at(1.0, 1.0, 1.0),
        face: FaceSet::Nearest(DVec3::Y),
    })
    .unwrap();
    mesh(&s).validate().unwrap();
    assert_eq!(
        TopologyCounts::of(mesh(&s)).since(&before).to_string(),
        "V +1, E +2, B +1"
    );
}

#[test]
fn a_rip_keeps_every_corner_uv() {
    let path =
        Path::new(&std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"))
            .join("tests/corpus/scenes/v2-uv-panel.hedra.ron");
    let mut s = hedra_doc::file::load(&path).unwrap().session;
    let panel = NodeRef::Name("Panel".into());
    let content = |s: &Session| match &s.doc.find_by_name("Panel").unwrap().content {
        hedra_doc::NodeContent::Mesh(c) => c.clone(),
        _ => panic!("Panel is a mesh"),
    };
    assert_eq!(content(&s).corners.uvs.len(), 8);
    // Two quads sharing the edge x = 1: ripping it separates them.
    s.execute(&Command::Rip {
        node: panel,
        edges: EdgeSet::Nearest(DVec3::new(1.0, 0.5, 0.0)),
    })
    .unwrap();
    let c = content(&s);
    c.mesh.validate().unwrap();
    assert_eq!(c.mesh.shell_count(), 2);
    assert_eq!(c.corners.uvs.len(), 8, "every face corner keeps its UV");
    for (&h, uv) in c.corners.uvs.iter() {
        assert!(c.mesh.face(h).is_some());
        // The panel's UVs are its positions halved in x.
        let p = c.mesh.position(c.mesh.origin(h));
        assert_eq!((uv.x, uv.y), (p.x / 2.0, p.y), "{h}");
    }
}
