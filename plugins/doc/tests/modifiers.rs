//! The modifier stack on mesh nodes: the commands with undo and redo, the
//! evaluated mesh (export, `hedra info`), subdivision's place in the stack,
//! saving and loading, clipping.

use glam::DVec3;
use hedra_doc::export::{ExportOptions, ExportShape, export_bytes};
use hedra_doc::file;
use hedra_doc::{
    ArrayModifier, Command, CommandError, MeshContent, MeshModifier, MirrorModifier, NodeContent,
    NodeRef, Session, SubdivisionModifier,
};
use std::path::Path;

/// A session with "HalfBox" (x in 0..1, open on x = 0) and "Tube" (a cube
/// of side 2 without its ±X faces).
fn session() -> Session {
    let script = r#"[
        AddMesh(name: "HalfBox", positions: [(0.0, -1.0, -1.0), (1.0, -1.0, -1.0), (1.0, 1.0, -1.0), (0.0, 1.0, -1.0), (0.0, -1.0, 1.0), (1.0, -1.0, 1.0), (1.0, 1.0, 1.0), (0.0, 1.0, 1.0)], polygons: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5]]),
        AddPrimitive(primitive: Cube(size: 2.0), name: "Tube"),
        DeleteFaces(node: Name("Tube"), faces: Facing(direction: (1.0, 0.0, 0.0), degrees: 1.0)),
        DeleteFaces(node: Name("Tube"), faces: Facing(direction: (-1.0, 0.0, 0.0), degrees: 1.0)),
    ]"#;
    let commands = hedra_doc::script::parse(script, Path::new("test.ron")).unwrap();
    let mut s = Session::new();
    hedra_doc::script::run(&mut s, &commands, Path::new("test.ron")).unwrap();
    s
}

fn content(s: &Session, name: &str) -> MeshContent {
    match &s.doc.find_by_name(name).unwrap().content {
        NodeContent::Mesh(m) => m.clone(),
        _ => panic!("{name} is a mesh"),
    }
}

fn node(name: &str) -> NodeRef {
    NodeRef::Name(name.into())
}

fn mirror_x() -> MeshModifier {
    MeshModifier::Mirror(MirrorModifier::default())
}

fn tube_array() -> MeshModifier {
    MeshModifier::Array(ArrayModifier {
        count: 3,
        merge: true,
        merge_distance: 0.001,
        ..ArrayModifier::default()
    })
}

fn counts(m: &hedra_geom::HalfEdgeMesh) -> (usize, usize, usize) {
    (m.vertex_count(), m.edge_count(), m.face_count())
}

#[test]
fn add_set_move_remove_and_apply_each_undo_and_redo() {
    let mut s = session();
    let cage = content(&s, "HalfBox");
    let add = |s: &mut Session, m: MeshModifier| {
        s.execute(&Command::AddModifier {
            node: node("HalfBox"),
            modifier: m,
        })
        .unwrap()
    };
    add(&mut s, mirror_x());
    assert_eq!(
        s.history.done().last().unwrap().label,
        "Add Mirror Modifier"
    );
    let c = content(&s, "HalfBox");
    assert_eq!(c.modifiers, vec![mirror_x()]);
    assert!(c.has_stack_modifiers());
    assert_eq!(counts(&c.evaluated(0).unwrap()), (12, 20, 10));
    assert_eq!(counts(&c.mesh), (8, 12, 5), "the cage is unchanged");

    // Set: without merge the halves stay apart.
    let apart = MeshModifier::Mirror(MirrorModifier {
        merge: false,
        ..MirrorModifier::default()
    });
    s.execute(&Command::SetModifier {
        node: node("HalfBox"),
        index: 0,
        modifier: apart,
    })
    .unwrap();
    assert_eq!(
        counts(&content(&s, "HalfBox").evaluated(0).unwrap()),
        (16, 24, 10)
    );
    s.undo().unwrap();
    assert_eq!(content(&s, "HalfBox").modifiers, vec![mirror_x()]);
    s.redo().unwrap();
    assert_eq!(content(&s, "HalfBox").modifiers, vec![apart]);
    s.undo().unwrap();

    // Move: an array along z added after the mirror, moved first.
    let along_z = MeshModifier::Array(ArrayModifier {
        relative_offset: Some(DVec3::Z),
        ..ArrayModifier::default()
    });
    add(&mut s, along_z);
    s.execute(&Command::MoveModifier {
        node: node("HalfBox"),
        from: 1,
        to: 0,
    })
    .unwrap();
    assert_eq!(content(&s, "HalfBox").modifiers, vec![along_z, mirror_x()]);
    s.undo().unwrap();
    assert_eq!(content(&s, "HalfBox").modifiers, vec![mirror_x(), along_z]);
    s.redo().unwrap();

    // Remove the array again.
    s.execute(&Command::RemoveModifier {
        node: node("HalfBox"),
        index: 0,
    })
    .unwrap();
    assert_eq!(content(&s, "HalfBox").modifiers, vec![mirror_x()]);
    s.undo().unwrap();
    assert_eq!(content(&s, "HalfBox").modifiers.len(), 2);
    s.redo().unwrap();

    // Apply: the cage becomes the closed box, in one step.
    let steps = s.history.done().len();
    s.execute(&Command::ApplyModifiers {
        node: node("HalfBox"),
        count: None,
    })
    .unwrap();
    assert_eq!(s.history.done().len(), steps + 1);
    let applied = content(&s, "HalfBox");
    assert!(applied.modifiers.is_empty());
    applied.mesh.validate().unwrap();
    assert_eq!(counts(&applied.mesh), (12, 20, 10));
    assert!(applied.mesh.stats().closed);
    s.undo().unwrap();
    let back = content(&s, "HalfBox");
    assert_eq!(back.mesh, cage.mesh);
    assert_eq!(back.modifiers, vec![mirror_x()]);
    s.redo().unwrap();
    assert_eq!(content(&s, "HalfBox"), applied);
}

#[test]
fn the_tube_array_evaluates_to_one_open_tube() {
    let mut s = session();
    s.execute(&Command::AddModifier {
        node: node("Tube"),
        modifier: tube_array(),
    })
    .unwrap();
    let c = content(&s, "Tube");
    let m = c.evaluated(0).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (16, 28, 12));
    let st = m.stats();
    assert_eq!((st.shells, st.boundary_loops, st.genus), (1, 2, Some(0)));
    // Export writes the evaluated mesh; the cage shape writes the cage
    // (the half box, without modifiers, is its cage in both: 8 v, 5 f).
    let obj = |shape| {
        let options = ExportOptions {
            shape,
            ..ExportOptions::default()
        };
        let bytes = export_bytes(&s.doc, Path::new("out.obj"), options).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        let count = |p: &str| text.lines().filter(|l| l.starts_with(p)).count();
        (count("v "), count("f "))
    };
    assert_eq!(obj(ExportShape::Evaluated), (8 + 16, 5 + 12));
    assert_eq!(obj(ExportShape::Cage), (8 + 8, 5 + 4));
    // `hedra info` lists the modifier and the evaluated counts.
    let info = hedra_doc::report::SceneReport::new(&s).to_text();
    assert!(
        info.contains("modifier 1: Array ×3, relative (1, 0, 0), merge 0.001"),
        "{info}"
    );
    assert!(
        info.contains("evaluated: V 16 E 28 F 12, boundary loops 2, shells 1, genus 0"),
        "{info}"
    );
    let json = hedra_doc::report::SceneReport::new(&s).to_json();
    assert!(json.contains("\"kind\": \"Array\""), "{json}");
}

#[test]
fn subdivision_runs_after_the_stack_unless_placed_before() {
    let mut s = session();
    s.execute(&Command::AddModifier {
        node: node("HalfBox"),
        modifier: mirror_x(),
    })
    .unwrap();
    s.execute(&Command::SetSubdivision {
        nodes: vec![node("HalfBox")],
        modifier: Some(SubdivisionModifier::with_level(1)),
    })
    .unwrap();
    let c = content(&s, "HalfBox");
    assert_eq!(c.subdivision_position(), 1);
    // Mirror → Subdivision: the welded box of 10 quads, subdivided once.
    let after = c.evaluated(1).unwrap();
    after.validate().unwrap();
    assert_eq!(after.face_count(), 40);
    assert!(after.stats().closed);
    assert!(
        c.smooth_cage().unwrap().is_some(),
        "the stencil path refines the mirrored cage"
    );
    assert_eq!(
        counts(&c.smooth_cage().unwrap().unwrap().mesh),
        (12, 20, 10)
    );
    // Subdivision → Mirror: the open half is smoothed, then mirrored.
    let mut first = SubdivisionModifier::with_level(1);
    first.stack_position = Some(0);
    s.execute(&Command::SetSubdivision {
        nodes: vec![node("HalfBox")],
        modifier: Some(first),
    })
    .unwrap();
    let c = content(&s, "HalfBox");
    assert_eq!(c.subdivision_position(), 0);
    assert!(
        c.smooth_cage().unwrap().is_none(),
        "no stencil path: draw evaluated()"
    );
    let before = c.evaluated(1).unwrap();
    before.validate().unwrap();
    assert_eq!(before.face_count(), 40);
    // Smoothing the open half (its seam by the boundary rule) and then
    // mirroring gives the same surface here: on this regular grid the
    // boundary rule is the interior rule restricted to the plane.
    assert!((before.volume() - after.volume()).abs() < 1e-12);
    // An array's relative offset sees the shape before it: subdividing
    // first shrinks the box, so the copies step by less.
    s.execute(&Command::AddPrimitive {
        primitive: hedra_geom::Primitive::Cube { size: 2.0 },
        name: Some("Row".into()),
        parent: None,
        transform: Default::default(),
    })
    .unwrap();
    s.execute(&Command::AddModifier {
        node: node("Row"),
        modifier: MeshModifier::Array(ArrayModifier::default()),
    })
    .unwrap();
    let width = |s: &Session| {
        let (lo, hi) = content(s, "Row").evaluated(2).unwrap().bounds().unwrap();
        hi.x - lo.x
    };
    s.execute(&Command::SetSubdivision {
        nodes: vec![node("Row")],
        modifier: Some(SubdivisionModifier::with_level(2)),
    })
    .unwrap();
    let array_then_smooth = width(&s);
    s.execute(&Command::SetSubdivision {
        nodes: vec![node("Row")],
        modifier: Some(SubdivisionModifier {
            stack_position: Some(0),
            ..SubdivisionModifier::with_level(2)
        }),
    })
    .unwrap();
    let smooth_then_array = width(&s);
    let cube = hedra_geom::Primitive::Cube { size: 2.0 }.build().unwrap();
    let (one, _) = hedra_geom::subdivision::Refiner::subdivide(
        &cube,
        &Default::default(),
        Default::default(),
        2,
    )
    .unwrap();
    let (lo, hi) = one.bounds().unwrap();
    let one_width = hi.x - lo.x;
    assert!(one_width < 2.0 - 1e-3, "{one_width}");
    // Two smoothed cubes, the second one smoothed width further: touching.
    assert!(
        (smooth_then_array - 2.0 * one_width).abs() < 1e-9,
        "{smooth_then_array}"
    );
    // Two cubes 2 apart, each smoothed: one cube width plus 2.
    assert!(
        (array_then_smooth - (2.0 + one_width)).abs() < 1e-9,
        "{array_then_smooth}"
    );
    // Applying the mirror now would change the result: refused.
    let e = s
        .execute(&Command::ApplyModifiers {
            node: node("HalfBox"),
            count: None,
        })
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "'HalfBox' (#1): subdivision runs after 0 of the stack's modifiers; apply only those, or move subdivision last"
    );
}

#[test]
fn bad_modifiers_are_refused_naming_the_node_and_the_modifier() {
    let mut s = session();
    let doc = s.doc.clone();
    let zero = MeshModifier::Array(ArrayModifier {
        count: 0,
        ..ArrayModifier::default()
    });
    let e = s
        .execute(&Command::AddModifier {
            node: node("Tube"),
            modifier: zero,
        })
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "'Tube' (#2): array count must be between 1 and 10000, got 0"
    );
    // Closed cubes welded face to face would not be manifold.
    s.execute(&Command::AddPrimitive {
        primitive: hedra_geom::Primitive::Cube { size: 2.0 },
        name: Some("Block".into()),
        parent: None,
        transform: Default::default(),
    })
    .unwrap();
    let e = s
        .execute(&Command::AddModifier {
            node: node("Block"),
            modifier: MeshModifier::Array(ArrayModifier {
                merge: true,
                ..ArrayModifier::default()
            }),
        })
        .unwrap_err();
    assert!(matches!(e, CommandError::Modifier { .. }), "{e:?}");
    assert!(
        e.to_string()
            .starts_with("'Block' (#3): modifier 1 (Array): the result would not be a valid mesh: the array would not make a manifold surface"),
        "{e}"
    );
    let e = s
        .execute(&Command::RemoveModifier {
            node: node("Tube"),
            index: 0,
        })
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "'Tube' (#2) has no modifier 1 (its stack has 0)"
    );
    let e = s
        .execute(&Command::ApplyModifiers {
            node: node("Tube"),
            count: None,
        })
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "nothing to do: the node has no modifiers to apply"
    );
    s.undo().unwrap();
    assert_eq!(s.doc, doc, "refused commands changed nothing");
}

#[test]
fn the_stack_is_saved_and_loaded_and_old_files_read_without_one() {
    let mut s = session();
    for (name, m) in [("HalfBox", mirror_x()), ("Tube", tube_array())] {
        s.execute(&Command::AddModifier {
            node: node(name),
            modifier: m,
        })
        .unwrap();
    }
    let mut sub = SubdivisionModifier::with_level(2);
    sub.stack_position = Some(0);
    s.execute(&Command::SetSubdivision {
        nodes: vec![node("Tube")],
        modifier: Some(sub),
    })
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("stack.hedra.ron");
    file::save(&mut s, &path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("modifiers: [Mirror("), "{text}");
    assert!(text.contains("stack_position: Some(0)"), "{text}");
    let mut back = file::load(&path).unwrap().session;
    assert_eq!(back.doc, s.doc);
    assert_eq!(content(&back, "Tube").subdivision, Some(sub));
    // The reopened history undoes the stack commands.
    back.undo().unwrap();
    assert_eq!(content(&back, "Tube").subdivision, None);
    back.undo().unwrap();
    assert!(content(&back, "Tube").modifiers.is_empty());
    back.undo().unwrap();
    assert!(content(&back, "HalfBox").modifiers.is_empty());
    // A scene without modifiers writes no `modifiers` field (old readers
    // see the same text as before).
    let plain = file::to_string(&session());
    assert!(!plain.contains("modifiers:"), "{plain}");
    // A stored modifier out of range is refused on load, by node and modifier.
    let bad = text.replace("count: 3", "count: 0");
    let e = file::from_str(&bad, &path).unwrap_err();
    assert!(
        e.to_string()
            .contains("modifier 1: array count must be between 1 and 10000, got 0"),
        "{e}"
    );
}

#[test]
fn creases_reach_every_copy_and_uvs_follow_apply() {
    let mut s = session();
    s.execute(&Command::SetEdgeCrease {
        node: node("HalfBox"),
        edges: hedra_doc::EdgeSet::Ids(vec![0]),
        sharpness: 3.0,
    })
    .unwrap();
    s.execute(&Command::AddModifier {
        node: node("HalfBox"),
        modifier: mirror_x(),
    })
    .unwrap();
    let c = content(&s, "HalfBox");
    let e = c.evaluate(0).unwrap();
    // Edge 0 (0 → 3, on the seam) is welded: one creased edge; otherwise two.
    let creased = e.creases.edges.len();
    assert!((1..=2).contains(&creased), "{creased}");
    assert!(e.creases.edges.values().all(|&v| v == 3.0));
    s.execute(&Command::ApplyModifiers {
        node: node("HalfBox"),
        count: Some(1),
    })
    .unwrap();
    assert_eq!(s.history.done().last().unwrap().label, "Apply Modifier");
    assert_eq!(content(&s, "HalfBox").creases.edges.len(), creased);
}

#[test]
fn clipping_keeps_vertices_on_the_mirror_plane() {
    let mut m = MirrorModifier {
        axes: [true, false, true],
        clipping: true,
        ..MirrorModifier::default()
    };
    // On the x plane (within 0.001): x stays 0; z is free (not near its plane).
    let p = m.clip(DVec3::new(0.0005, 1.0, 2.0), DVec3::new(0.3, 1.5, 2.5));
    assert_eq!(p, DVec3::new(0.0, 1.5, 2.5));
    // Crossing the z plane stops on it.
    let p = m.clip(DVec3::new(1.0, 0.0, 0.5), DVec3::new(1.2, 0.0, -0.5));
    assert_eq!(p, DVec3::new(1.2, 0.0, 0.0));
    // Away from the planes nothing changes.
    let p = m.clip(DVec3::new(1.0, 1.0, 1.0), DVec3::new(2.0, -1.0, 0.5));
    assert_eq!(p, DVec3::new(2.0, -1.0, 0.5));
    // Y is not a mirror axis: crossing it is free.
    m.clipping = false;
    let p = m.clip(DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.3, 0.3, 0.3));
    assert_eq!(p, DVec3::splat(0.3), "clipping off");
}

#[test]
fn applying_carries_uvs_to_every_copied_corner_and_drops_normals() {
    use std::collections::BTreeMap;
    use std::sync::Arc;
    let s = session();
    let mut c = content(&s, "HalfBox");
    // A UV per corner: the corner's vertex position projected on y, z.
    let m = c.mesh.clone();
    let uvs: BTreeMap<_, _> = m
        .halfedges()
        .filter(|&h| m.face(h).is_some())
        .map(|h| {
            let p = m.position(m.origin(h));
            (h, glam::DVec2::new(p.y, p.z))
        })
        .collect();
    assert_eq!(uvs.len(), 20);
    c.corners.uvs = Arc::new(uvs);
    c.modifiers.push(mirror_x());
    let applied = c.with_modifiers_applied(1).unwrap();
    assert!(applied.modifiers.is_empty());
    assert!(applied.corners.normals.is_empty());
    let am = &applied.mesh;
    assert_eq!(applied.corners.uvs.len(), 40, "every corner of both halves");
    for (h, uv) in applied.corners.uvs.iter() {
        let p = am.position(am.origin(*h));
        assert_eq!(
            *uv,
            glam::DVec2::new(p.y, p.z),
            "the UV of the mirrored corner"
        );
    }
}
