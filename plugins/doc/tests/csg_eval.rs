//! Evaluating CSG trees (issue 17): a change re-runs only the booleans of
//! its branch (the rest comes from the cache), the drag preview with
//! simplified operands, self-intersecting operands refused by name, and
//! evaluation on a worker thread.

use glam::{DQuat, DVec3};
use hedra_doc::csg::{self, CsgError, CsgTree, Quality, Solid};
use hedra_doc::{Command, NodeRef, NodeTransform, Session};
use hedra_geom::{BooleanOp, HalfEdgeMesh, Primitive};
use std::sync::Arc;

fn name(n: &str) -> NodeRef {
    NodeRef::Name(n.into())
}

fn add_primitive(s: &mut Session, label: &str, primitive: Primitive, rotation: DQuat) {
    s.execute(&Command::AddPrimitive {
        primitive,
        name: Some(label.into()),
        parent: None,
        transform: NodeTransform {
            rotation,
            ..NodeTransform::IDENTITY
        },
    })
    .unwrap();
}

/// The emblem: (Cube ∩ Sphere) − Rod Y − Rod X − Rod Z, the core a nested
/// CSG node; `n` sets the resolution of the round operands.
fn emblem(n: u32, size: f64) -> Session {
    let mut s = Session::new();
    add_primitive(&mut s, "Cube", Primitive::Cube { size }, DQuat::IDENTITY);
    let sphere = Primitive::UvSphere {
        segments: 2 * n,
        rings: n,
        radius: 0.68 * size,
    };
    add_primitive(&mut s, "Sphere", sphere, DQuat::IDENTITY);
    s.execute(&Command::AddCsg {
        op: BooleanOp::Intersection,
        name: Some("Core".into()),
        operands: vec![name("Cube"), name("Sphere")],
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let rod = Primitive::Cylinder {
        segments: 2 * n,
        radius: 0.25 * size,
        depth: 1.5 * size,
    };
    for (label, axis) in [
        ("Rod Y", DVec3::Y),
        ("Rod X", DVec3::X),
        ("Rod Z", DVec3::Z),
    ] {
        add_primitive(
            &mut s,
            label,
            rod.clone(),
            DQuat::from_rotation_arc(DVec3::Y, axis),
        );
    }
    s.execute(&Command::AddCsg {
        op: BooleanOp::Difference,
        name: Some("Emblem".into()),
        operands: vec![name("Core"), name("Rod Y"), name("Rod X"), name("Rod Z")],
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s
}

fn id(s: &Session, n: &str) -> hedra_doc::NodeId {
    s.doc.find_by_name(n).unwrap().id
}

fn nudge(s: &mut Session, n: &str, dx: f64) {
    let node = id(s, n);
    let mut t = s.doc.node(node).unwrap().transform;
    t.translation.x += dx;
    s.execute(&Command::SetTransforms {
        nodes: vec![(NodeRef::Id(node.0), t)],
    })
    .unwrap();
}

/// Evaluates `node` and returns the solid and how many booleans ran.
fn counted(s: &Session, node: &str, quality: Quality) -> (Solid, u64) {
    let before = csg::booleans_computed();
    let solid = csg::evaluate_with(&s.doc, id(s, node), quality).unwrap();
    (solid, csg::booleans_computed() - before)
}

fn check(m: &HalfEdgeMesh) {
    m.validate().unwrap();
    let stats = m.stats();
    assert!(stats.closed && stats.manifold);
}

#[test]
fn a_change_reruns_only_the_booleans_of_its_branch() {
    // Adding the nodes evaluates them (a refused node is not added): the
    // core's intersection once, then the three differences on it.
    let before = csg::booleans_computed();
    let mut s = emblem(12, 1.0);
    assert_eq!(csg::booleans_computed() - before, 4);
    let (first, runs) = counted(&s, "Emblem", Quality::Exact);
    assert_eq!(runs, 0);
    check(&first);
    let core = csg::evaluate(&s.doc, id(&s, "Core")).unwrap();
    // Nothing changed: nothing runs, the same solid comes back.
    let (again, runs) = counted(&s, "Emblem", Quality::Exact);
    assert_eq!(runs, 0);
    assert!(Arc::ptr_eq(&first, &again));
    // The last rod moves: one difference re-runs; the intersection stays.
    nudge(&mut s, "Rod Z", 0.01);
    let (moved, runs) = counted(&s, "Emblem", Quality::Exact);
    assert_eq!(runs, 1);
    check(&moved);
    assert!(Arc::ptr_eq(
        &core,
        &csg::evaluate(&s.doc, id(&s, "Core")).unwrap()
    ));
    // The first rod moves: the three differences re-run, not the core.
    nudge(&mut s, "Rod Y", 0.01);
    assert_eq!(counted(&s, "Emblem", Quality::Exact).1, 3);
    // The sphere moves: the core and everything above it.
    nudge(&mut s, "Sphere", 0.01);
    assert_eq!(counted(&s, "Emblem", Quality::Exact).1, 4);
    // Undo brings back solids already computed.
    s.undo().unwrap();
    assert_eq!(counted(&s, "Emblem", Quality::Exact).1, 0);
}

#[test]
fn the_drag_preview_uses_simplified_operands_close_to_the_exact_solid() {
    let mut s = emblem(40, 1.0); // sphere 3,200 faces, rods 82 each side
    let (exact, _) = counted(&s, "Emblem", Quality::Exact);
    let preview_quality = Quality::Preview { faces: 400 };
    let (preview, runs) = counted(&s, "Emblem", preview_quality);
    assert_eq!(runs, 4, "the preview has its own booleans");
    check(&preview);
    assert!(
        preview.face_count() < exact.face_count(),
        "{} vs {}",
        preview.face_count(),
        exact.face_count()
    );
    let (ve, vp) = (exact.volume(), preview.volume());
    assert!((vp - ve).abs() < 0.03 * ve, "{vp} vs {ve}");
    // A drag frame of the preview re-runs the one boolean after the rod,
    // and the simplified operands are not made again.
    nudge(&mut s, "Rod Z", 0.02);
    assert_eq!(counted(&s, "Emblem", preview_quality).1, 1);
    // Dragging the first rod: the preview folds it last from the second
    // frame on, so each frame re-runs one boolean, not three.
    nudge(&mut s, "Rod Y", 0.02);
    counted(&s, "Emblem", preview_quality);
    for _ in 0..3 {
        nudge(&mut s, "Rod Y", 0.01);
        let (frame, runs) = counted(&s, "Emblem", preview_quality);
        assert_eq!(runs, 1);
        check(&frame);
        assert!((frame.volume() - vp).abs() < 0.03 * vp);
    }
    // The proxy of a small mesh is the mesh itself.
    let cube = Primitive::Cube { size: 1.0 }.build().unwrap();
    assert_eq!(csg::preview_proxy(&cube, 400), cube);
    let sphere = Primitive::UvSphere {
        segments: 80,
        rings: 40,
        radius: 1.0,
    }
    .build()
    .unwrap();
    // A finely divided cube simplifies too, as far as its sharp edges let
    // it (the vertices on them stay on them).
    let mut s2 = Session::new();
    let (positions, polygons) = fine_cube(20);
    s2.execute(&Command::AddMesh {
        name: "Fine".into(),
        positions,
        polygons,
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let fine = s2.doc.find_by_name("Fine").unwrap();
    let hedra_doc::NodeContent::Mesh(content) = &fine.content else {
        panic!()
    };
    assert_eq!(content.mesh.face_count(), 2400);
    let proxy = csg::preview_proxy(&content.mesh, 400);
    assert!(proxy.face_count() <= 400, "{}", proxy.face_count());
    check(&proxy);
    assert!((proxy.volume() - 8.0).abs() < 1e-9, "{}", proxy.volume());
    let proxy = csg::preview_proxy(&sphere, 400);
    assert!(proxy.face_count() <= 400, "{}", proxy.face_count());
    check(&proxy);
    assert!(hedra_geom::csg::self_intersections(&proxy).is_empty());
}

#[test]
fn a_self_intersecting_operand_is_refused_naming_the_node() {
    let mut s = Session::new();
    // Two overlapping cubes in one mesh: 6 pairs of faces cross.
    let (mut positions, mut polygons) =
        Primitive::Cube { size: 1.0 }.build().unwrap().to_polygons();
    let base = positions.len() as u32;
    positions.extend(
        positions
            .clone()
            .iter()
            .map(|p| *p + DVec3::new(0.5, 0.3, 0.4)),
    );
    polygons.extend(
        polygons
            .clone()
            .into_iter()
            .map(|f| f.into_iter().map(|v| v + base).collect::<Vec<_>>()),
    );
    s.execute(&Command::AddMesh {
        name: "Twin".into(),
        positions,
        polygons,
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    add_primitive(
        &mut s,
        "Box",
        Primitive::Cube { size: 3.0 },
        DQuat::IDENTITY,
    );
    let e = s
        .execute(&Command::AddCsg {
            op: BooleanOp::Union,
            name: Some("Merge".into()),
            operands: vec![name("Box"), name("Twin")],
            parent: None,
            transform: NodeTransform::IDENTITY,
        })
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "'Merge': operand 'Twin' intersects itself: 6 pairs of its faces cross"
    );
    assert!(s.doc.find_by_name("Merge").is_none(), "nothing changed");
    // The one-shot boolean names it the same way and changes nothing.
    let e = s
        .execute(&Command::Boolean {
            node: name("Box"),
            other: name("Twin"),
            op: BooleanOp::Difference,
        })
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "'Box': operand 'Twin' intersects itself: 6 pairs of its faces cross"
    );
    assert_eq!(s.doc.find_by_name("Box").map(|n| n.id), Some(id(&s, "Box")));
}

#[test]
fn a_tree_evaluates_on_a_worker_thread() {
    fn send<T: Send + 'static>() {}
    send::<CsgTree>();
    send::<Result<Solid, CsgError>>();
    let s = emblem(8, 2.0);
    let tree = CsgTree::of(&s.doc, id(&s, "Emblem")).unwrap();
    let worker = std::thread::spawn(move || tree.evaluate(Quality::Exact));
    let solid = worker.join().unwrap().unwrap();
    check(&solid);
    // The worker's solid is in the shared cache: the same one here.
    let here = csg::evaluate(&s.doc, id(&s, "Emblem")).unwrap();
    assert!(Arc::ptr_eq(&solid, &here));
    // Not a CSG node: a named refusal, not a panic.
    let e = CsgTree::of(&s.doc, id(&s, "Cube")).unwrap_err();
    assert_eq!(
        e.to_string(),
        "'Cube' has no operands (add meshes or CSG nodes under it)"
    );
}

/// A cube of side 2 with n × n quads on each face.
fn fine_cube(n: u32) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let mut positions = Vec::new();
    let mut index = std::collections::HashMap::new();
    let mut polygons = Vec::new();
    let mut at = |p: DVec3, positions: &mut Vec<DVec3>| {
        let key = (p * 1e6).round().as_i64vec3().to_array();
        *index.entry(key).or_insert_with(|| {
            positions.push(p);
            positions.len() as u32 - 1
        })
    };
    for axis in 0..3 {
        for side in [-1.0, 1.0] {
            let normal = DVec3::AXES[axis] * side;
            let u = DVec3::AXES[(axis + 1) % 3];
            let v = normal.cross(u);
            let corner = |i: u32, j: u32| {
                normal
                    + u * (2.0 * i as f64 / n as f64 - 1.0)
                    + v * (2.0 * j as f64 / n as f64 - 1.0)
            };
            for i in 0..n {
                for j in 0..n {
                    let q = [
                        corner(i, j),
                        corner(i + 1, j),
                        corner(i + 1, j + 1),
                        corner(i, j + 1),
                    ];
                    polygons.push(q.map(|p| at(p, &mut positions)).to_vec());
                }
            }
        }
    }
    (positions, polygons)
}

/// An empty result is an empty solid that takes part like any other
/// (issue 35): a nested intersection of parts moved apart is empty; a union
/// with it is the other operand, a difference minus it the first operand,
/// an intersection with it empty, and moving the part back brings the
/// solid back. Manifold gives the same (an empty manifold).
#[test]
fn an_empty_nested_result_is_an_empty_solid_in_the_tree() {
    let mut s = Session::new();
    add_primitive(&mut s, "A", Primitive::Cube { size: 1.0 }, DQuat::IDENTITY);
    add_primitive(&mut s, "B", Primitive::Cube { size: 1.0 }, DQuat::IDENTITY);
    s.execute(&Command::Translate {
        nodes: vec![name("B")],
        offset: DVec3::new(5.0, 0.0, 0.0),
    })
    .unwrap();
    s.execute(&Command::AddCsg {
        op: BooleanOp::Intersection,
        name: Some("Nothing".into()),
        operands: vec![name("A"), name("B")],
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let id = |s: &Session, n: &str| s.doc.find_by_name(n).unwrap().id;
    let nothing = csg::evaluate(&s.doc, id(&s, "Nothing")).unwrap();
    assert_eq!(nothing.face_count(), 0);
    add_primitive(&mut s, "C", Primitive::Cube { size: 2.0 }, DQuat::IDENTITY);
    for (op, faces) in [
        (BooleanOp::Union, 6),
        (BooleanOp::Difference, 0),
        (BooleanOp::Intersection, 0),
    ] {
        // The nested node first, then the cube: nothing ∪ C = C,
        // nothing − C = nothing, nothing ∩ C = nothing.
        let label = format!("{op}");
        s.execute(&Command::AddCsg {
            op,
            name: Some(label.clone()),
            operands: vec![name("Nothing"), name("C")],
            parent: None,
            transform: NodeTransform::IDENTITY,
        })
        .unwrap();
        let solid = csg::evaluate(&s.doc, id(&s, &label)).unwrap();
        assert_eq!(solid.face_count(), faces, "{op}");
        if faces > 0 {
            assert!((solid.volume() - 8.0).abs() < 1e-12, "{op}");
        }
        s.undo();
    }
    // C minus an empty solid made after it (operands go in id order) is C.
    add_primitive(&mut s, "E", Primitive::Cube { size: 1.0 }, DQuat::IDENTITY);
    add_primitive(&mut s, "F", Primitive::Cube { size: 1.0 }, DQuat::IDENTITY);
    s.execute(&Command::Translate {
        nodes: vec![name("F")],
        offset: DVec3::new(0.0, 7.0, 0.0),
    })
    .unwrap();
    s.execute(&Command::AddCsg {
        op: BooleanOp::Intersection,
        name: Some("Nothing Too".into()),
        operands: vec![name("E"), name("F")],
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s.execute(&Command::AddCsg {
        op: BooleanOp::Difference,
        name: Some("Minus".into()),
        operands: vec![name("C"), name("Nothing Too")],
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let minus = csg::evaluate(&s.doc, id(&s, "Minus")).unwrap();
    assert!((minus.volume() - 8.0).abs() < 1e-12, "{}", minus.volume());
    for _ in 0..5 {
        s.undo();
    }
    // B moved back over A: the intersection is a solid again.
    s.execute(&Command::Translate {
        nodes: vec![name("B")],
        offset: DVec3::new(-4.5, 0.0, 0.0),
    })
    .unwrap();
    let half = csg::evaluate(&s.doc, id(&s, "Nothing")).unwrap();
    assert!((half.volume() - 0.5).abs() < 1e-12, "{}", half.volume());
}
