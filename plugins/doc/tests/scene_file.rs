//! The `.hedra.ron` file: round trips, history, versions, damage, atomic saves.

use glam::DVec3;
use hedra_doc::file::{self, FileError};
use hedra_doc::{Command, NodeRef, NodeTransform, Session};
use hedra_geom::Primitive;
use std::path::Path;

fn sample_session() -> Session {
    let mut s = Session::new();
    let cmds = vec![
        Command::AddEmpty {
            name: "Table".into(),
            parent: None,
            transform: NodeTransform::from_translation(DVec3::new(0.0, 1.0, 0.0)),
        },
        Command::AddPrimitive {
            primitive: Primitive::Cube { size: 2.0 },
            name: Some("Top".into()),
            parent: Some(NodeRef::Name("Table".into())),
            transform: NodeTransform::IDENTITY,
        },
        Command::AddPrimitive {
            primitive: Primitive::Cylinder {
                segments: 8,
                radius: 0.1,
                depth: 1.0,
            },
            name: Some("Leg".into()),
            parent: Some(NodeRef::Name("Table".into())),
            transform: NodeTransform::IDENTITY,
        },
        Command::Translate {
            nodes: vec![NodeRef::Name("Leg".into())],
            offset: DVec3::new(0.8, -0.5, 0.8),
        },
        Command::Duplicate {
            nodes: vec![NodeRef::Name("Leg".into())],
        },
        Command::Translate {
            nodes: vec![NodeRef::Name("Leg.001".into())],
            offset: DVec3::new(-1.6, 0.0, 0.0),
        },
        Command::AddPrimitive {
            primitive: Primitive::Torus {
                major_segments: 12,
                minor_segments: 6,
                major_radius: 1.0,
                minor_radius: 0.2,
            },
            name: None,
            parent: None,
            transform: NodeTransform::IDENTITY,
        },
    ];
    for c in &cmds {
        s.execute(c).unwrap();
    }
    s.undo(); // leave one step on the redo stack
    s
}

#[test]
fn save_load_save_gives_the_same_bytes_and_keeps_history() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("table.hedra.ron");
    let mut s = sample_session();
    file::save(&mut s, &path).unwrap();
    assert!(!s.is_dirty());
    let first = std::fs::read_to_string(&path).unwrap();
    assert!(
        first.starts_with("(\n    format: \"hedra-scene\",\n    version: 3,"),
        "{}",
        &first[..60]
    );

    let loaded = file::load(&path).unwrap();
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let mut back = loaded.session;
    assert_eq!(back.doc, s.doc);
    assert_eq!(back.history.done().len(), 6);
    assert_eq!(back.history.undone().len(), 1);
    assert!(!back.is_dirty());
    let again = file::to_string(&back);
    assert_eq!(again, first, "save -> load -> save changes bytes");

    // Undo after reopening walks the same states as in the original session.
    let mut original = s.clone();
    while original.undo().is_some() {
        back.undo().expect("reopened file can still undo");
        assert_eq!(back.doc, original.doc);
    }
    assert_eq!(back.doc.node_count(), 0);
    // And redo goes all the way, including the step that was undone before saving.
    while back.redo().is_some() {}
    assert!(back.doc.find_by_name("Torus").is_some());
}

#[test]
fn meshes_shared_between_history_steps_are_stored_once() {
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: Primitive::UvSphere {
            segments: 32,
            rings: 16,
            radius: 1.0,
        },
        name: None,
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    for i in 0..20 {
        s.execute(&Command::Translate {
            nodes: vec![NodeRef::Id(1)],
            offset: DVec3::X * (i + 1) as f64,
        })
        .unwrap();
    }
    let text = file::to_string(&s);
    let one_step = {
        let mut t = Session::new();
        t.execute(&Command::AddPrimitive {
            primitive: Primitive::UvSphere {
                segments: 32,
                rings: 16,
                radius: 1.0,
            },
            name: None,
            parent: None,
            transform: NodeTransform::IDENTITY,
        })
        .unwrap();
        file::to_string(&t).len()
    };
    assert!(
        text.len() < one_step * 2,
        "21 steps on one mesh cost {} bytes vs {} for one",
        text.len(),
        one_step
    );
}

#[test]
fn newer_versions_and_other_files_are_refused_clearly() {
    let p = Path::new("x.hedra.ron");
    let e = file::from_str("(\n    format: \"hedra-scene\",\n    version: 7,\n)", p).unwrap_err();
    assert!(matches!(e, FileError::NewerVersion { version: 7, .. }));
    assert!(
        e.to_string().contains("newer Hedra (format version 7)"),
        "{e}"
    );
    let e = file::from_str("(name: \"something else\")", p).unwrap_err();
    assert!(e.to_string().contains("not a Hedra scene file"), "{e}");
    let e = file::from_str("(\n    format: \"blender\",\n    version: 1,\n)", p).unwrap_err();
    assert!(e.to_string().contains("'blender'"), "{e}");
}

#[test]
fn syntax_errors_give_file_line_and_column() {
    let s = sample_session();
    let text = file::to_string(&s).replacen("scene: (", "scene: ((", 1);
    let e = file::from_str(&text, Path::new("broken.hedra.ron")).unwrap_err();
    let FileError::Parse { line, column, .. } = &e else {
        panic!("{e}")
    };
    assert!(*line > 1 && *column > 1);
    assert!(
        e.to_string()
            .starts_with(&format!("broken.hedra.ron:{line}:{column}: ")),
        "{e}"
    );
}

#[test]
fn damaged_history_still_opens_the_scene_with_a_warning() {
    let s = sample_session();
    let text = file::to_string(&s);
    let cut = text.find("\n    history:").unwrap();
    // Syntax damage inside the history.
    let broken = format!(
        "{}{}",
        &text[..cut],
        text[cut..].replacen("done: [", "done: [[[", 1)
    );
    let loaded = file::from_str(&broken, Path::new("t.hedra.ron")).unwrap();
    assert_eq!(loaded.session.doc, s.doc);
    assert!(!loaded.session.history.can_undo());
    assert_eq!(loaded.warnings.len(), 1);
    assert!(
        loaded.warnings[0].contains("undo history could not be read"),
        "{:?}",
        loaded.warnings
    );
    // Semantic damage: a step that refers to a mesh that is not stored.
    let bad_ref = format!(
        "{}{}",
        &text[..cut],
        text[cut..].replacen("mesh: 0", "mesh: 999", 1)
    );
    let loaded = file::from_str(&bad_ref, Path::new("t.hedra.ron")).unwrap();
    assert_eq!(loaded.session.doc, s.doc);
    assert!(
        loaded.warnings[0].contains("undo history is damaged"),
        "{:?}",
        loaded.warnings
    );
    // A step whose result does not match the scene.
    let wrong = format!(
        "{}{}",
        &text[..cut],
        text[cut..].replacen("name: \"Leg\",", "name: \"Log\",", 1)
    );
    let loaded = file::from_str(&wrong, Path::new("t.hedra.ron")).unwrap();
    assert!(!loaded.warnings.is_empty());
    assert!(!loaded.session.history.can_undo());
}

#[test]
fn damaged_scene_part_is_an_error_naming_the_problem() {
    let s = sample_session();
    let text = file::to_string(&s).replacen("parent: Some(1)", "parent: Some(42)", 1);
    let e = file::from_str(&text, Path::new("t.hedra.ron")).unwrap_err();
    assert!(e.to_string().contains("missing parent #42"), "{e}");
}

#[test]
fn atomic_save_keeps_a_backup_and_a_failed_save_loses_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("a.hedra.ron");
    let mut s = sample_session();
    file::save(&mut s, &path).unwrap();
    let v1 = std::fs::read_to_string(&path).unwrap();
    s.execute(&Command::AddEmpty {
        name: "New".into(),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    assert!(s.is_dirty());
    file::save(&mut s, &path).unwrap();
    let bak = dir.path().join("a.hedra.ron.bak");
    assert_eq!(std::fs::read_to_string(&bak).unwrap(), v1);
    assert_ne!(std::fs::read_to_string(&path).unwrap(), v1);
    // No temporary files are left behind.
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
    // Saving into a folder that does not exist fails, says where, and keeps the session dirty.
    s.execute(&Command::AddEmpty {
        name: "More".into(),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let e = file::save(&mut s, &dir.path().join("missing/b.hedra.ron")).unwrap_err();
    assert!(e.to_string().contains("missing"), "{e}");
    assert!(s.is_dirty());
}

#[test]
fn subdivision_modifiers_and_creases_are_saved_and_undone() {
    use hedra_doc::elements::{EdgeSet, VertexSet};
    use hedra_doc::{NodeContent, SubdivisionModifier};
    let mut s = Session::new();
    let run = |s: &mut Session, c: Command| s.execute(&c).unwrap();
    run(
        &mut s,
        Command::AddPrimitive {
            primitive: Primitive::Cube { size: 2.0 },
            name: Some("Box".into()),
            parent: None,
            transform: NodeTransform::IDENTITY,
        },
    );
    let node = || NodeRef::Name("Box".into());
    let mut modifier = SubdivisionModifier::with_level(3);
    modifier.options.crease_method = hedra_geom::subdivision::CreaseMethod::Chaikin;
    run(
        &mut s,
        Command::SetSubdivision {
            nodes: vec![node()],
            modifier: Some(modifier),
        },
    );
    run(
        &mut s,
        Command::SetEdgeCrease {
            node: node(),
            edges: EdgeSet::Ids(vec![0, 1]),
            sharpness: 2.5,
        },
    );
    run(
        &mut s,
        Command::SetVertexCrease {
            node: node(),
            vertices: VertexSet::Ids(vec![3]),
            sharpness: 10.0,
        },
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("creased.hedra.ron");
    file::save(&mut s, &path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("crease_method: Chaikin"), "{text}");
    let mut back = file::load(&path).unwrap().session;
    assert_eq!(back.doc, s.doc);
    let content = |s: &Session| match &s.doc.find_by_name("Box").unwrap().content {
        NodeContent::Mesh(m) => m.clone(),
        _ => panic!("Box is a mesh"),
    };
    let c = content(&back);
    assert_eq!(c.subdivision, Some(modifier));
    assert_eq!(c.creases.edges.len(), 2);
    assert_eq!(c.creases.vertex(hedra_geom::VertexId(3)), 10.0);
    // Undo in the reopened file: vertex crease, edge creases, then the modifier.
    back.undo().unwrap();
    assert!(content(&back).creases.vertices.is_empty());
    back.undo().unwrap();
    assert!(content(&back).creases.is_empty());
    back.undo().unwrap();
    assert_eq!(content(&back).subdivision, None);
    // Bad values are refused by name and change nothing.
    let before = s.doc.clone();
    for bad in [-1.0, 10.5, f64::NAN] {
        let e = s
            .execute(&Command::SetEdgeCrease {
                node: node(),
                edges: EdgeSet::All,
                sharpness: bad,
            })
            .unwrap_err();
        assert!(
            e.to_string().contains("sharpness must be between 0 and 10"),
            "{e}"
        );
    }
    let e = s
        .execute(&Command::SetSubdivision {
            nodes: vec![node()],
            modifier: Some(SubdivisionModifier::with_level(11)),
        })
        .unwrap_err();
    assert!(
        e.to_string().contains("level 11 is above the maximum"),
        "{e}"
    );
    let e = s
        .execute(&Command::ApplySubdivision {
            node: NodeRef::Name("Box".into()),
            levels: None,
        })
        .map(drop);
    assert!(e.is_ok(), "the modifier's level 3 applies");
    assert_eq!(content(&s).mesh.face_count(), 6 * 64);
    s.undo();
    assert_eq!(s.doc, before);
}

#[test]
fn curves_and_surfaces_round_trip_through_the_file_and_bad_data_is_refused() {
    use hedra_doc::command::{CurveSpec, SurfaceSpec};
    let mut s = Session::new();
    s.execute(&Command::AddCurve {
        name: "Ring".into(),
        curve: CurveSpec::Circle { radius: 2.0 },
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s.execute(&Command::AddSurface {
        name: "Ball".into(),
        surface: SurfaceSpec::Sphere { radius: 1.0 },
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s.execute(&Command::SetWeights {
        node: NodeRef::Name("Ring".into()),
        weights: vec![(3, 2.5)],
    })
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("shapes.hedra.ron");
    file::save(&mut s, &path).unwrap();
    let mut back = file::load(&path).unwrap().session;
    assert_eq!(back.doc, s.doc);
    back.undo().unwrap();
    let before = back.doc.clone();
    // A weight of zero, a knot outside the domain and a point that does not exist are refused by name.
    for (cmd, expected) in [
        (
            Command::SetWeights {
                node: NodeRef::Name("Ring".into()),
                weights: vec![(1, 0.0)],
            },
            "weight 1 is 0: weights must be positive",
        ),
        (
            Command::InsertKnot {
                node: NodeRef::Name("Ring".into()),
                at: 2.0,
                direction: Default::default(),
            },
            "parameter 2 is outside the domain [0, 1]",
        ),
        (
            Command::SetControlPoints {
                node: NodeRef::Name("Ball".into()),
                points: vec![(999, DVec3::ZERO)],
            },
            "control point 999 does not exist (there are 45)",
        ),
        (
            Command::AddCurve {
                name: "Bad".into(),
                curve: CurveSpec::Nurbs {
                    degree: 2,
                    points: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
                    weights: None,
                    knots: Some(vec![0.0, 0.0, 1.0, 0.5, 1.0, 1.0]),
                },
                parent: None,
                transform: NodeTransform::IDENTITY,
            },
            "knot 3 (0.5) is smaller than the one before it",
        ),
    ] {
        let e = back.execute(&cmd).unwrap_err().to_string();
        assert!(e.contains(expected), "{e}");
        assert_eq!(back.doc, before, "a refused edit changes nothing");
    }
    // A damaged curve in a file is an error naming the problem, not a panic.
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replacen("degree: 2,", "degree: 0,", 1);
    let e = file::from_str(&text, Path::new("shapes.hedra.ron")).unwrap_err();
    assert!(e.to_string().contains("degree must be at least 1"), "{e}");
}

/// Values a command would refuse are refused on load too, naming the node:
/// a NaN primitive size (found by fuzzing), a subdivision level above the
/// maximum (it would allocate without bound), a negative crease.
#[test]
fn out_of_range_parameters_in_a_file_are_refused_by_node() {
    let path = std::path::PathBuf::from(
        std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo test"),
    )
    .join("tests/corpus/scenes/v1-jar.hedra.ron");
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(file::from_str(&text, &path).is_ok());
    // The fuzzer's input: a node's cube primitive with size NaN.
    let nan = std::path::PathBuf::from(
        std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo test"),
    )
    .join("fuzz/regressions/scene/nan-cube-size-in-primitive.hedra.ron");
    let err = file::load(&nan).unwrap_err().to_string();
    assert!(
        err.contains("node #2 'Box'") && err.contains("size") && err.contains("NaN"),
        "{err}"
    );
    // The first occurrences are in the scene part (it precedes the history).
    for (from, to, expect) in [
        (
            "viewport_level: 3",
            "viewport_level: 99",
            "subdivision level 99",
        ),
        ("{13: 10.0,", "{13: -1.0,", "crease sharpness -1"),
    ] {
        assert!(text.contains(from), "{from}");
        let bad = text.replacen(from, to, 1);
        let err = file::from_str(&bad, Path::new("bad.hedra.ron"))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("bad.hedra.ron") && err.contains("node") && err.contains(expect),
            "{err}"
        );
    }
}

#[test]
fn face_holes_and_smooth_triangles_are_saved_undone_and_exported() {
    use hedra_doc::elements::FaceSet;
    use hedra_doc::export::{ExportOptions, export_bytes};
    use hedra_doc::{NodeContent, SubdivisionModifier};
    let mut s = Session::new();
    let run = |s: &mut Session, c: Command| s.execute(&c).unwrap();
    run(
        &mut s,
        Command::AddPrimitive {
            primitive: Primitive::Cube { size: 2.0 },
            name: Some("Box".into()),
            parent: None,
            transform: NodeTransform::IDENTITY,
        },
    );
    let node = || NodeRef::Name("Box".into());
    let mut modifier = SubdivisionModifier::with_level(2);
    modifier.options.smooth_triangles = true;
    run(
        &mut s,
        Command::SetSubdivision {
            nodes: vec![node()],
            modifier: Some(modifier),
        },
    );
    run(
        &mut s,
        Command::SetFaceHole {
            node: node(),
            faces: FaceSet::Ids(vec![0, 1]),
            hole: true,
        },
    );
    run(
        &mut s,
        Command::SetFaceHole {
            node: node(),
            faces: FaceSet::Ids(vec![1]),
            hole: false,
        },
    );
    assert_eq!(s.history.done().last().unwrap().label, "Clear Hole");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("holes.hedra.ron");
    file::save(&mut s, &path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("holes: [0]"), "{text}");
    assert!(text.contains("smooth_triangles: true"), "{text}");
    let mut back = file::load(&path).unwrap().session;
    assert_eq!(back.doc, s.doc);
    let content = |s: &Session| match &s.doc.find_by_name("Box").unwrap().content {
        NodeContent::Mesh(m) => m.clone(),
        _ => panic!("Box is a mesh"),
    };
    assert_eq!(content(&back).subdivision, Some(modifier));
    assert!(content(&back).creases.is_hole(hedra_geom::FaceId(0)));
    // Export at level 2 leaves 16 faces for the hole out: 5 × 16 quads.
    let obj = export_bytes(&back.doc, Path::new("box.obj"), ExportOptions::default()).unwrap();
    let faces = String::from_utf8(obj)
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("f "))
        .count();
    assert_eq!(faces, 5 * 16);
    // Undo: the cleared hole comes back, then both go.
    back.undo().unwrap();
    assert_eq!(content(&back).creases.holes.len(), 2);
    back.undo().unwrap();
    assert!(content(&back).creases.holes.is_empty());
    // A face the mesh does not have is refused and changes nothing.
    let before = s.doc.clone();
    let e = s
        .execute(&Command::SetFaceHole {
            node: node(),
            faces: FaceSet::Ids(vec![99]),
            hole: true,
        })
        .unwrap_err();
    assert!(e.to_string().contains("99"), "{e}");
    assert_eq!(s.doc, before);
}

#[test]
fn crease_tapers_are_saved_undone_and_refused_by_name() {
    use hedra_doc::NodeContent;
    use hedra_doc::elements::{EdgeSet, VertexSet};
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: Primitive::Cube { size: 2.0 },
        name: Some("Box".into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let node = || NodeRef::Name("Box".into());
    // Two bottom edges, from the corner (−1, −1, 1) round to (1, −1, −1).
    let edges =
        || EdgeSet::NearestEach(vec![DVec3::new(0.0, -1.0, 1.0), DVec3::new(1.0, -1.0, 0.0)]);
    let taper = |from: DVec3| Command::SetCreaseTaper {
        node: node(),
        edges: edges(),
        from: VertexSet::Nearest(from),
        start: 2.0,
        end: 6.0,
    };
    let before = s.doc.clone();
    // The middle vertex (1, −1, 1) is not an end.
    let e = s.execute(&taper(DVec3::new(1.0, -1.0, 1.0))).unwrap_err();
    assert!(e.to_string().contains("is not an end of the chain"), "{e}");
    assert_eq!(s.doc, before);
    s.execute(&taper(DVec3::new(-1.0, -1.0, 1.0))).unwrap();
    assert_eq!(
        s.history.done().last().unwrap().label,
        "Crease Taper 2.00 to 6.00"
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("taper.hedra.ron");
    file::save(&mut s, &path).unwrap();
    let mut back = file::load(&path).unwrap().session;
    assert_eq!(back.doc, s.doc);
    let creases = |s: &Session| match &s.doc.find_by_name("Box").unwrap().content {
        NodeContent::Mesh(m) => m.creases.clone(),
        _ => panic!("Box is a mesh"),
    };
    let mut values: Vec<f64> = creases(&back).edge_sharpness().into_values().collect();
    values.sort_by(f64::total_cmp);
    assert_eq!(values, [3.0, 5.0]);
    back.undo().unwrap();
    assert!(creases(&back).is_empty());
}

/// The positions and polygons of a torus primitive, for `AddMesh`.
fn torus_polygons(major: u32, minor: u32) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let m = Primitive::Torus {
        major_segments: major,
        minor_segments: minor,
        major_radius: 1.0,
        minor_radius: 0.3,
    }
    .build()
    .unwrap();
    let positions = m.vertices().map(|v| m.position(v)).collect();
    let polygons = m
        .faces()
        .map(|f| m.face_vertices(f).map(|v| v.0).collect())
        .collect();
    (positions, polygons)
}

fn add_mesh(name: &str, positions: Vec<DVec3>, polygons: Vec<Vec<u32>>) -> Command {
    Command::AddMesh {
        name: name.into(),
        positions,
        polygons,
        parent: None,
        transform: NodeTransform::IDENTITY,
    }
}

/// Issue 16: a mesh made by `AddMesh` is stored once, not again in its
/// command; the file with the step is hardly larger than the scene alone.
#[test]
fn a_mesh_made_by_add_mesh_is_stored_once() {
    let (positions, polygons) = torus_polygons(60, 40);
    let mut s = Session::new();
    s.execute(&add_mesh("Ring", positions.clone(), polygons.clone()))
        .unwrap();
    let with_history = file::to_string(&s);
    let scene_only = file::to_string(&Session {
        doc: s.doc.clone(),
        ..Session::new()
    });
    assert!(
        (with_history.len() as f64) < 1.2 * scene_only.len() as f64,
        "{} bytes with the AddMesh step, {} without",
        with_history.len(),
        scene_only.len()
    );
    assert!(with_history.contains("command: Some(AddMesh(name: \"Ring\", mesh: 0, "));
    // The command reads back whole: the same positions and polygons.
    let back = file::from_str(&with_history, Path::new("ring.hedra.ron")).unwrap();
    assert!(back.warnings.is_empty(), "{:?}", back.warnings);
    assert_eq!(back.session.history, s.history);
    assert_eq!(
        back.session.history.done()[0].command,
        Some(add_mesh("Ring", positions, polygons))
    );

    // Edited afterwards, the step keeps the mesh it made (a second mesh),
    // and the command still names it.
    s.execute(&Command::MoveVertices {
        node: NodeRef::Name("Ring".into()),
        vertices: hedra_doc::VertexSet::Ids(vec![0, 1, 2]),
        offset: DVec3::new(0.0, 0.5, 0.0),
    })
    .unwrap();
    let text = file::to_string(&s);
    assert!(text.contains("command: Some(AddMesh(name: \"Ring\", mesh: 1, "));
    let back = file::from_str(&text, Path::new("ring.hedra.ron")).unwrap();
    assert!(back.warnings.is_empty(), "{:?}", back.warnings);
    assert_eq!(back.session.doc, s.doc);
    assert_eq!(back.session.history, s.history);
}

/// A mesh stored as polygons keeps every id through edits: removed
/// elements, new ones out of order, and the commands that name ids redo
/// the same after a load.
#[test]
fn edited_meshes_keep_their_ids_through_a_save() {
    let mut s = sample_session();
    let cmds = [
        Command::ExtrudeFaces {
            node: NodeRef::Name("Top".into()),
            faces: hedra_doc::FaceSet::Ids(vec![2, 4]),
            distance: 0.3,
        },
        Command::DeleteFaces {
            node: NodeRef::Name("Top".into()),
            faces: hedra_doc::FaceSet::Ids(vec![0]),
        },
    ];
    for c in &cmds {
        s.execute(c).unwrap();
    }
    let text = file::to_string(&s);
    assert!(
        text.contains("dead_faces: ["),
        "the edits left removed faces"
    );
    let back = file::from_str(&text, Path::new("edited.hedra.ron"))
        .unwrap()
        .session;
    assert_eq!(back.doc, s.doc);
    assert_eq!(back.history, s.history);
    assert_eq!(file::to_string(&back), text, "saved again, the same bytes");
}

/// The mesh lists' own parser and the RON parser read the same meshes: a
/// field the fast parser does not know sends the lists to the RON parser
/// (which ignores it), and the scene and history are the same.
#[test]
fn the_fast_mesh_reader_and_the_ron_reader_agree() {
    let (positions, polygons) = torus_polygons(12, 8);
    let mut s = sample_session();
    s.execute(&add_mesh("Ring", positions, polygons)).unwrap();
    s.execute(&Command::DeleteFaces {
        node: NodeRef::Name("Ring".into()),
        faces: hedra_doc::FaceSet::Ids(vec![3, 4]),
    })
    .unwrap();
    let text = file::to_string(&s);
    let slow_text = text.replace("(positions: [", "(unknown: 0, positions: [");
    let slow_text = slow_text.replace(
        "\n            positions: [",
        "\n            unknown: 0, positions: [",
    );
    assert_ne!(slow_text, text);
    let fast = file::from_str(&text, Path::new("a.hedra.ron")).unwrap();
    let slow = file::from_str(&slow_text, Path::new("a.hedra.ron")).unwrap();
    assert!(fast.warnings.is_empty() && slow.warnings.is_empty());
    assert_eq!(fast.session.doc, slow.session.doc);
    assert_eq!(fast.session.history, slow.session.history);
    assert_eq!(fast.session.doc, s.doc);
    // A damaged mesh is an error with its place in the file either way.
    let bad = text.replacen("faces: [[", "faces: [[9999, ", 1);
    match file::from_str(&bad, Path::new("bad.hedra.ron")) {
        Err(FileError::Parse { line, message, .. }) => {
            assert!(line > 3, "{line}");
            assert!(message.contains("id 9999"), "{message}");
        }
        other => panic!("{other:?}"),
    }
}

/// Damaged mesh lists (a byte changed, removed or the text cut short) are
/// refused or read, never a panic, and what loads is sound
/// (`fuzz::scene` checks it and its history).
#[test]
fn damaged_mesh_lists_never_panic() {
    let (positions, polygons) = torus_polygons(6, 4);
    let mut s = Session::new();
    s.execute(&add_mesh("Ring", positions, polygons)).unwrap();
    s.execute(&Command::DeleteFaces {
        node: NodeRef::Name("Ring".into()),
        faces: hedra_doc::FaceSet::Ids(vec![3]),
    })
    .unwrap();
    let text = file::to_string(&s);
    let end = text.find("\n    scene:").unwrap();
    let bytes = text.as_bytes();
    let replacements = b"09-,])([ e./#\"";
    let mut seed: u64 = 0x2545_F491_4F6C_DD1D;
    let mut next = |n: usize| {
        seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
        (seed >> 33) as usize % n
    };
    for round in 0..600 {
        let at = 40 + next(end - 40);
        let mut damaged = bytes.to_vec();
        match round % 3 {
            0 => damaged[at] = replacements[next(replacements.len())],
            1 => {
                damaged.remove(at);
            }
            _ => damaged.truncate(at),
        }
        hedra_doc::fuzz::scene(&damaged);
    }
}
