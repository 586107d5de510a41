//! The CSG emblem sample (issue 17): `tests/scripts/csg.ron` builds
//! `assets/samples/csg.hedra.ron` (HEDRA_BLESS=1 writes it); the file
//! loads back to the same tree, its solid is the emblem, `hedra info`'s
//! report prints the tree and export writes the solid alone.

use hedra_doc::export::{ExportOptions, export_bytes};
use hedra_doc::report::SceneReport;
use hedra_doc::{Command, NodeContent, Session, csg, file, script};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(&std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"))
        .join("../..")
}

fn built() -> Session {
    let path = root().join("tests/scripts/csg.ron");
    let text = std::fs::read_to_string(&path).unwrap();
    let commands = script::parse(&text, &path).unwrap();
    let mut session = Session::new();
    script::run(&mut session, &commands, &path).unwrap_or_else(|e| panic!("{e}"));
    session
}

#[test]
fn the_script_builds_the_sample_file() {
    let session = built();
    let text = file::to_string(&session);
    let sample = root().join("assets/samples/csg.hedra.ron");
    if std::env::var_os("HEDRA_BLESS").is_some() {
        std::fs::write(&sample, &text).unwrap();
    }
    let stored = std::fs::read_to_string(&sample).expect("HEDRA_BLESS=1 writes the sample");
    assert_eq!(
        stored, text,
        "assets/samples/csg.hedra.ron is made by tests/scripts/csg.ron"
    );
    let loaded = file::from_str(&stored, &sample).unwrap();
    assert_eq!(
        loaded.session.doc, session.doc,
        "the tree loads back as saved"
    );
}

#[test]
fn the_emblem_is_a_genus_five_solid() {
    let session = built();
    let doc = &session.doc;
    let emblem = doc.find_by_name("Emblem").unwrap();
    assert!(matches!(emblem.content, NodeContent::Csg(_)));
    let solid = csg::evaluate(doc, emblem.id).unwrap();
    solid.validate().unwrap();
    let s = solid.stats();
    assert_eq!(
        (s.shells, s.genus, s.closed, s.manifold),
        (1, Some(5), true, true)
    );
    // Smaller than the rounded cube, larger than the cube minus the rods.
    let core = csg::evaluate(doc, doc.find_by_name("Rounded Cube").unwrap().id).unwrap();
    assert!(solid.volume() < core.volume() && core.volume() < 8.0);
    // Cached: a second evaluation hands back the same solid.
    let again = csg::evaluate(doc, emblem.id).unwrap();
    assert!(std::sync::Arc::ptr_eq(&solid, &again));
    // hedra info prints the tree.
    let text = SceneReport::new(&session).to_text();
    assert!(
        text.contains("csg: difference of #3, #4, #5, #6: solid V"),
        "{text}"
    );
    assert!(text.contains("genus 5"), "{text}");
    // Export writes the solid only: one object, no operands.
    let obj = export_bytes(doc, Path::new("emblem.obj"), ExportOptions::default()).unwrap();
    let obj = String::from_utf8(obj).unwrap();
    let objects: Vec<&str> = obj.lines().filter(|l| l.starts_with("o ")).collect();
    assert_eq!(objects, ["o Emblem"]);
    let faces = obj.lines().filter(|l| l.starts_with("f ")).count();
    assert_eq!(faces, s.faces);
}

#[test]
fn moving_one_cylinder_follows_and_undo_restores() {
    let mut session = built();
    let id = session.doc.find_by_name("Emblem").unwrap().id;
    let before = csg::evaluate(&session.doc, id).unwrap();
    session
        .execute(&Command::Translate {
            nodes: vec![hedra_doc::NodeRef::Name("Cylinder Z".into())],
            offset: glam::DVec3::new(0.3, 0.0, 0.0),
        })
        .unwrap();
    let moved = csg::evaluate(&session.doc, id).unwrap();
    assert!(moved.volume() != before.volume());
    assert_eq!(moved.stats().genus, Some(5));
    session.undo();
    let back = csg::evaluate(&session.doc, id).unwrap();
    assert!(
        std::sync::Arc::ptr_eq(&back, &before),
        "the cache hands the old solid back"
    );
}

#[test]
fn refusals_name_the_nodes_and_change_nothing() {
    let mut session = built();
    let before = session.doc.clone();
    // Move the sphere away: the intersection is an empty solid, not an
    // error (issue 35), and the emblem above it (the rounded cube minus the
    // rods) is empty too. Apply refuses to make a mesh without faces.
    session
        .execute(&Command::Translate {
            nodes: vec![hedra_doc::NodeRef::Name("Sphere".into())],
            offset: glam::DVec3::new(10.0, 0.0, 0.0),
        })
        .unwrap();
    let id = session.doc.find_by_name("Rounded Cube").unwrap().id;
    let empty = csg::evaluate(&session.doc, id).unwrap();
    assert_eq!((empty.face_count(), empty.vertex_count()), (0, 0));
    let emblem = session.doc.find_by_name("Emblem").unwrap().id;
    assert_eq!(csg::evaluate(&session.doc, emblem).unwrap().face_count(), 0);
    let e = session
        .execute(&Command::ApplyCsg {
            node: hedra_doc::NodeRef::Name("Rounded Cube".into()),
        })
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "the intersection of Cube and Sphere is empty"
    );
    // Exported as nothing, with a note; the report counts 0 faces.
    let exported = hedra_doc::export::export_file(
        &session.doc,
        Path::new("emblem.obj"),
        ExportOptions::default(),
    );
    match exported {
        Err(e) => assert!(e.to_string().contains("nothing"), "{e}"),
        Ok(x) => panic!("an OBJ of nothing: {} bytes, {:?}", x.bytes.len(), x.notes),
    }
    session
        .execute(&Command::AddPrimitive {
            primitive: hedra_geom::Primitive::Cube { size: 1.0 },
            name: Some("Spare".into()),
            parent: None,
            transform: Default::default(),
        })
        .unwrap();
    let exported = hedra_doc::export::export_file(
        &session.doc,
        Path::new("emblem.obj"),
        ExportOptions::default(),
    )
    .unwrap();
    let text = String::from_utf8(exported.bytes).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 6);
    assert!(
        exported
            .notes
            .iter()
            .any(|n| n.starts_with("'Emblem' is an empty solid")),
        "{:?}",
        exported.notes
    );
    let text = SceneReport::new(&session).to_text();
    assert!(
        text.contains("csg: intersection of #1, #2: empty solid (V 0 E 0 F 0)"),
        "{text}"
    );
    session.undo();
    session.undo();
    assert_eq!(session.doc, before);
    // An open operand.
    session
        .execute(&Command::AddPrimitive {
            primitive: hedra_geom::Primitive::Plane { size: 1.0 },
            name: Some("Sheet".into()),
            parent: None,
            transform: Default::default(),
        })
        .unwrap();
    let snapshot = session.doc.clone();
    let e = session
        .execute(&Command::AddCsg {
            op: hedra_geom::csg::BooleanOp::Union,
            name: Some("Bad".into()),
            operands: vec![
                hedra_doc::NodeRef::Name("Emblem".into()),
                hedra_doc::NodeRef::Name("Sheet".into()),
            ],
            parent: None,
            transform: Default::default(),
        })
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "'Bad': operand 'Sheet' is open: 4 border edges (a boolean needs closed meshes)"
    );
    assert_eq!(session.doc, snapshot, "nothing changed");
    // Setting an op that empties the result is refused too.
    let e = session
        .execute(&Command::SetCsgOp {
            node: hedra_doc::NodeRef::Name("Emblem".into()),
            op: hedra_geom::csg::BooleanOp::Intersection,
        })
        .map(|_| ())
        .err();
    // Rounded cube ∩ all three rods is the small core where they cross: not empty.
    assert!(e.is_none());
}

#[test]
fn a_one_shot_boolean_keeps_creases_of_untouched_edges_and_undoes_in_one_step() {
    let text = r#"[
        AddPrimitive(primitive: Cube(size: 2.0), name: Some("Box")),
        SetEdgeCrease(node: Name("Box"), edges: OfFaces(Facing(direction: (0.0, -1.0, 0.0), degrees: 1.0)), sharpness: 10.0),
        AddPrimitive(primitive: Cube(size: 1.0), name: Some("Bite"), transform: (translation: (1.0, 1.0, 1.0))),
        Boolean(node: Name("Box"), other: Name("Bite"), op: Difference),
    ]"#;
    let path = Path::new("test.ron");
    let commands = script::parse(text, path).unwrap();
    let mut session = Session::new();
    script::run(&mut session, &commands, path).unwrap_or_else(|e| panic!("{e}"));
    let doc = &session.doc;
    assert!(
        doc.find_by_name("Bite").is_none(),
        "the other node is deleted"
    );
    let NodeContent::Mesh(m) = &doc.find_by_name("Box").unwrap().content else {
        panic!("Box is a mesh");
    };
    m.mesh.validate().unwrap();
    assert!((m.mesh.volume() - (8.0 - 0.125)).abs() < 1e-12);
    // The bottom face's four edges are not touched by the bite at the top corner.
    assert_eq!(m.creases.edges.len(), 4);
    assert!(m.primitive.is_none());
    // One undo step brings both nodes back as they were.
    session.undo();
    assert!(session.doc.find_by_name("Bite").is_some());
    let NodeContent::Mesh(m) = &session.doc.find_by_name("Box").unwrap().content else {
        panic!("Box is a mesh");
    };
    assert_eq!(m.mesh.face_count(), 6);
    // The intersection of disjoint nodes is refused by name.
    let far = r#"[
        AddPrimitive(primitive: Cube(size: 1.0), name: Some("Far"), transform: (translation: (9.0, 0.0, 0.0))),
        Boolean(node: Name("Box"), other: Name("Far"), op: Intersection),
    ]"#;
    let commands = script::parse(far, path).unwrap();
    let e = script::run(&mut session, &commands, path).unwrap_err();
    assert!(
        e.to_string()
            .contains("the intersection of Box and Far is empty"),
        "{e}"
    );
}

/// Switching a CSG node's operation renames it when it still carries the
/// default name of the old one ("Union" → "Difference", "Union.001" →
/// "Difference.001" or the next free one); a name the user gave stays;
/// undo brings the old name back (issue 31).
#[test]
fn switching_the_operation_renames_only_a_default_name() {
    let text = r#"[
        AddPrimitive(primitive: Cube(size: 2.0), name: Some("A")),
        AddPrimitive(primitive: UvSphere(segments: 16, rings: 8, radius: 1.2), name: Some("B")),
        AddCsg(op: Union, operands: [Name("A"), Name("B")]),
        AddPrimitive(primitive: Cube(size: 2.0), name: Some("C")),
        AddPrimitive(primitive: UvSphere(segments: 16, rings: 8, radius: 1.2), name: Some("D")),
        AddCsg(op: Union, name: Some("Bracket"), operands: [Name("C"), Name("D")]),
    ]"#;
    let path = Path::new("test.ron");
    let commands = script::parse(text, path).unwrap();
    let mut session = Session::new();
    script::run(&mut session, &commands, path).unwrap_or_else(|e| panic!("{e}"));
    assert!(session.doc.find_by_name("Union").is_some());
    for (node, expected) in [("Union", "Difference"), ("Bracket", "Bracket")] {
        session
            .execute(&Command::SetCsgOp {
                node: hedra_doc::NodeRef::Name(node.into()),
                op: hedra_geom::csg::BooleanOp::Difference,
            })
            .unwrap();
        assert!(
            session.doc.find_by_name(expected).is_some(),
            "{node} is now called {expected}"
        );
    }
    assert!(session.doc.find_by_name("Union").is_none());
    session.undo();
    session.undo();
    assert!(
        session.doc.find_by_name("Union").is_some(),
        "undo renames back"
    );
}

/// Issue 35's repro through the document: a sphere minus the same sphere
/// turned by about 1e-4 rad (a one-shot Boolean), exported to STL, is
/// watertight: read back (`stl_io` welds equal corners), every edge is in
/// exactly two triangles and no triangle is without area. Before, 1 to 64
/// edges were in four triangles.
#[test]
fn a_near_coincident_difference_exports_a_watertight_stl() {
    let text = r#"[
        AddPrimitive(primitive: UvSphere(segments: 32, rings: 16, radius: 1.0), name: Some("A")),
        AddPrimitive(primitive: UvSphere(segments: 32, rings: 16, radius: 1.0), name: Some("B"),
            transform: (rotation: (2.4628014712012152e-05, 8.209338237337385e-05, 1.641867647467477e-05, 0.9999999961922823))),
        Boolean(node: Name("A"), other: Name("B"), op: Difference),
    ]"#;
    let path = Path::new("test.ron");
    let commands = script::parse(text, path).unwrap();
    let mut session = Session::new();
    script::run(&mut session, &commands, path).unwrap_or_else(|e| panic!("{e}"));
    let bytes = export_bytes(&session.doc, Path::new("d.stl"), ExportOptions::default()).unwrap();
    let stl = stl_io::read_stl(&mut std::io::Cursor::new(bytes)).unwrap();
    let mut uses: std::collections::HashMap<(usize, usize), usize> = Default::default();
    for face in &stl.faces {
        let [a, b, c] = face.vertices;
        let p = |i: usize| glam::DVec3::from(stl.vertices[i].0.map(f64::from));
        assert!(
            (p(b) - p(a)).cross(p(c) - p(a)).length() > 0.0,
            "a triangle without area"
        );
        for (x, y) in [(a, b), (b, c), (c, a)] {
            *uses.entry((x.min(y), x.max(y))).or_default() += 1;
        }
    }
    assert!(stl.faces.len() > 1000, "{}", stl.faces.len());
    let bad = uses.values().filter(|&&n| n != 2).count();
    assert_eq!(bad, 0, "edges not in exactly two triangles");
}
