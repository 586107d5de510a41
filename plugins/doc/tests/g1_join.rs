//! The G1 join of a Bézier triangle and a Bézier patch kept live (seed
//! 002's exercise, issue 20): after MakeG1Join the normals agree along the
//! joint and keep agreeing after random drags of free, shared and
//! dependent points of either patch, under node transforms; undo restores
//! both; save/load keeps the link; deleting or breaking ends it; the
//! sample scene is the script's result.

mod golden;

use glam::{DQuat, DVec3};
use hedra_doc::command::SurfaceSpec;
use hedra_doc::join::PointRole;
use hedra_doc::{Command, CommandError, NodeContent, NodeRef, NodeTransform, Session};
use std::path::{Path, PathBuf};

fn name(n: &str) -> NodeRef {
    NodeRef::Name(n.into())
}

fn repo() -> PathBuf {
    PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo test")).join("../..")
}

/// The world control points of the cubic triangle (edge i = 0 on the x
/// axis, the triangle towards −z).
fn triangle_points() -> Vec<DVec3> {
    let y = [
        [0.0, 0.0, 0.0, 0.0],
        [0.3, 0.6, 0.3, 0.0],
        [0.4, 0.4, 0.0, 0.0],
        [0.2, 0.0, 0.0, 0.0],
    ];
    let mut points = Vec::new();
    for (i, row) in y.iter().enumerate() {
        for (j, &h) in row.iter().take(4 - i).enumerate() {
            points.push(DVec3::new(j as f64 + 0.5 * i as f64, h, -(i as f64)));
        }
    }
    points
}

/// The world points of the bicubic patch towards +z, its side j = 0 near
/// the triangle's edge (the ends on it, the middle off by 0.1).
fn patch_points() -> Vec<DVec3> {
    let y = [
        [0.0, 0.2, 0.1, 0.0],
        [0.1, 0.5, 0.3, 0.0],
        [-0.1, 0.5, 0.3, 0.0],
        [0.0, 0.2, 0.1, 0.0],
    ];
    let mut points = Vec::new();
    for (i, row) in y.iter().enumerate() {
        for (j, &h) in row.iter().enumerate() {
            points.push(DVec3::new(i as f64, h, j as f64));
        }
    }
    points
}

fn transform(angle: f64, at: DVec3, scale: DVec3) -> NodeTransform {
    NodeTransform {
        translation: at,
        rotation: DQuat::from_axis_angle(DVec3::new(0.3, 1.0, -0.2).normalize(), angle),
        scale,
    }
}

/// The pair under different transforms (rotated, non-uniformly scaled),
/// joined.
fn joined() -> Session {
    let mut s = Session::new();
    let tt = transform(0.7, DVec3::new(1.0, -2.0, 0.5), DVec3::new(1.0, 2.0, 0.5));
    let qt = transform(-1.2, DVec3::new(-3.0, 0.0, 4.0), DVec3::new(0.8, 0.8, 1.3));
    let pull = |t: NodeTransform, ps: Vec<DVec3>| {
        let m = t.to_matrix().inverse();
        ps.into_iter().map(|p| m.transform_point3(p)).collect()
    };
    s.execute(&Command::AddSurface {
        name: "Triangle".into(),
        surface: SurfaceSpec::Triangle {
            degree: 3,
            points: pull(tt, triangle_points()),
        },
        parent: None,
        transform: tt,
    })
    .unwrap();
    s.execute(&Command::AddSurface {
        name: "Patch".into(),
        surface: SurfaceSpec::Bezier {
            nu: 4,
            nv: 4,
            points: pull(qt, patch_points()),
        },
        parent: None,
        transform: qt,
    })
    .unwrap();
    s.execute(&Command::MakeG1Join {
        triangle: name("Triangle"),
        quad: name("Patch"),
    })
    .unwrap();
    s
}

fn id(s: &Session, n: &str) -> hedra_doc::NodeId {
    s.doc.find_by_name(n).unwrap().id
}

fn points(s: &Session, n: &str) -> Vec<DVec3> {
    match &s.doc.find_by_name(n).unwrap().content {
        NodeContent::Surface(sf) => sf.control_points().to_vec(),
        _ => panic!("{n} is not a surface"),
    }
}

/// Asserts the join is G1 along the whole joint (101 points, world space).
fn assert_g1(s: &Session, when: &str) {
    let report = s.doc.g1_report(id(s, "Patch")).expect("joined");
    assert!(report.max_normal_angle < 1e-9, "{when}: {report:?}");
    assert!(report.max_gap < 1e-12, "{when}: {report:?}");
}

#[test]
fn make_g1_join_makes_the_normals_agree_along_the_joint_in_one_step() {
    let mut s = Session::new();
    let s2 = joined();
    // Before: the patch's side is off the edge by 0.1 and not tangent.
    let before = {
        for cmd in &s2.history.done()[..2] {
            s.execute(cmd.command.as_ref().unwrap()).unwrap();
        }
        hedra_geom::surfaces::patches::TriangleQuad::new(
            hedra_geom::surfaces::BezierTriangle::new(3, triangle_points()).unwrap(),
            hedra_geom::surfaces::BezierSurface::new(4, 4, patch_points()).unwrap(),
            1e-9,
        )
        .unwrap()
        .report(100)
    };
    assert!(
        before.max_normal_angle > 0.1 && before.max_gap > 0.02,
        "{before:?}"
    );
    let tri_before = points(&s, "Triangle");
    s.execute(&Command::MakeG1Join {
        triangle: name("Triangle"),
        quad: name("Patch"),
    })
    .unwrap();
    assert_g1(&s, "after MakeG1Join");
    assert_eq!(points(&s, "Triangle"), tri_before, "the triangle leads");
    assert_eq!(
        s.doc.g1_joins(),
        vec![(id(&s, "Patch"), id(&s, "Triangle"))]
    );
    assert_eq!(s.history.done().last().unwrap().label, "Make G1 Join");
    // Roles: 4 shared and 6 free on the triangle; 4 shared, 4 dependent,
    // 8 free on the patch.
    let count = |n: &str, r: PointRole| {
        let roles = s.doc.g1_roles(id(&s, n)).unwrap();
        roles.iter().filter(|&&x| x == r).count()
    };
    assert_eq!(
        (
            count("Triangle", PointRole::Shared),
            count("Triangle", PointRole::Free)
        ),
        (4, 6)
    );
    assert_eq!(
        (
            count("Patch", PointRole::Shared),
            count("Patch", PointRole::Dependent),
            count("Patch", PointRole::Free)
        ),
        (4, 4, 8)
    );
    // One undo restores both patches and the unjoined state.
    s.undo().unwrap();
    assert!(s.doc.g1_joins().is_empty());
    assert_eq!(points(&s, "Triangle"), tri_before);
    assert_eq!(
        s.doc.find_by_name("Patch").unwrap(),
        s2.history.done()[1].changes[0].after.as_ref().unwrap()
    );
}

/// A small seeded generator (xorshift), so the drags are the same on every run.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn offset(&mut self, size: f64) -> DVec3 {
        DVec3::new(self.next() - 0.5, self.next() - 0.5, self.next() - 0.5) * 2.0 * size
    }
}

#[test]
fn the_join_stays_g1_through_random_drags_of_every_kind_of_point() {
    let mut s = joined();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let kinds = [
        ("Triangle", PointRole::Free),
        ("Triangle", PointRole::Shared),
        ("Patch", PointRole::Free),
        ("Patch", PointRole::Shared),
        ("Patch", PointRole::Dependent),
    ];
    for step in 0..60 {
        let (node, role) = kinds[step % kinds.len()];
        let roles = s.doc.g1_roles(id(&s, node)).unwrap();
        let candidates: Vec<usize> = (0..roles.len()).filter(|&k| roles[k] == role).collect();
        let k = candidates[(rng.next() * candidates.len() as f64) as usize];
        let to = points(&s, node)[k] + rng.offset(0.15);
        let before = (points(&s, "Triangle"), points(&s, "Patch"));
        let steps = s.history.done().len();
        s.execute(&Command::SetControlPoints {
            node: name(node),
            points: vec![(k as u32, to)],
        })
        .unwrap_or_else(|e| panic!("step {step}: {e}"));
        assert_eq!(s.history.done().len(), steps + 1, "one undo step");
        let when = format!("step {step}: {node} point {k} ({role:?})");
        assert_g1(&s, &when);
        if role != PointRole::Dependent {
            // Free and shared points go where they were dragged.
            assert!(points(&s, node)[k].distance(to) < 1e-12, "{when}");
        }
        if role == PointRole::Shared {
            // ...and the other patch's copy follows (world space).
            let other = if node == "Triangle" {
                "Patch"
            } else {
                "Triangle"
            };
            assert_ne!(
                points(&s, other),
                if other == "Triangle" {
                    before.0.clone()
                } else {
                    before.1.clone()
                },
                "{when}"
            );
        }
        if step % 10 == 9 {
            // Undo restores both exactly; redo comes back.
            let after = (points(&s, "Triangle"), points(&s, "Patch"));
            s.undo().unwrap();
            assert_eq!(
                (points(&s, "Triangle"), points(&s, "Patch")),
                before,
                "{when}"
            );
            s.redo().unwrap();
            assert_eq!(
                (points(&s, "Triangle"), points(&s, "Patch")),
                after,
                "{when}"
            );
        }
    }
    // Moving the triangle node carries the joint; moving the patch node
    // leaves its joint on the triangle. Both stay G1.
    for node in ["Triangle", "Patch"] {
        s.execute(&Command::Rotate {
            nodes: vec![name(node)],
            axis: DVec3::new(1.0, 1.0, 0.0),
            degrees: 20.0,
        })
        .unwrap();
        assert_g1(&s, &format!("after rotating {node}"));
    }
    // Raising the triangle's degree raises the patch's along the edge.
    s.execute(&Command::ElevateDegree {
        node: name("Triangle"),
        direction: hedra_doc::command::ParameterDirection::U,
    })
    .unwrap();
    assert_g1(&s, "after ElevateDegree");
    assert_eq!(points(&s, "Patch").len(), 5 * 4);
}

#[test]
fn the_drag_preview_is_what_the_command_does() {
    let s = joined();
    let node = s.doc.find_by_name("Patch").unwrap();
    let roles = s.doc.g1_roles(node.id).unwrap();
    let k = roles
        .iter()
        .position(|&r| r == PointRole::Dependent)
        .unwrap();
    let to = points(&s, "Patch")[k] + DVec3::new(0.0, 0.3, 0.1);
    let mut dragged = node.clone();
    let NodeContent::Surface(sf) = &mut dragged.content else {
        panic!()
    };
    let hedra_doc::SurfaceShape::Nurbs(n) = std::sync::Arc::make_mut(sf) else {
        panic!()
    };
    let nv = n.size().1;
    n.set_point(k / nv, k % nv, to).unwrap();
    let preview = s.doc.g1_preview(&dragged);
    assert_eq!(preview.len(), 2, "both nodes");
    let mut s2 = s.clone();
    s2.execute(&Command::SetControlPoints {
        node: name("Patch"),
        points: vec![(k as u32, to)],
    })
    .unwrap();
    for (id, content) in preview {
        assert_eq!(&content, &s2.doc.node(id).unwrap().content);
    }
    let report = s.doc.g1_report(node.id).unwrap();
    assert!(report.max_normal_angle < 1e-9);
}

#[test]
fn save_and_load_keep_the_join() {
    let mut s = joined();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("join.hedra.ron");
    hedra_doc::file::save(&mut s, &path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("g1_join: Some((triangle: 1))"), "{text}");
    let mut loaded = hedra_doc::file::load(&path).unwrap();
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    assert_eq!(loaded.session.doc, s.doc);
    let s = &mut loaded.session;
    let k = s
        .doc
        .g1_roles(id(s, "Triangle"))
        .unwrap()
        .iter()
        .position(|&r| r == PointRole::Shared)
        .unwrap();
    let to = points(s, "Triangle")[k] + DVec3::new(0.1, 0.2, 0.0);
    s.execute(&Command::SetControlPoints {
        node: name("Triangle"),
        points: vec![(k as u32, to)],
    })
    .unwrap();
    assert_g1(s, "after a drag in the loaded file");
}

#[test]
fn deleting_or_breaking_ends_the_join_and_errors_name_the_nodes() {
    // Break: both keep their shapes, then move alone.
    let mut s = joined();
    s.execute(&Command::BreakG1Join {
        node: name("Triangle"),
    })
    .unwrap();
    assert!(s.doc.g1_joins().is_empty());
    assert!(s.doc.g1_roles(id(&s, "Patch")).is_none());
    let patch = points(&s, "Patch");
    s.execute(&Command::SetControlPoints {
        node: name("Triangle"),
        points: vec![(0, DVec3::new(0.0, 5.0, 0.0))],
    })
    .unwrap();
    assert_eq!(points(&s, "Patch"), patch, "no longer followed");
    let err = s
        .execute(&Command::BreakG1Join {
            node: name("Patch"),
        })
        .unwrap_err();
    assert_eq!(err.to_string(), "'Patch' (#2) is not in a G1 join");
    // Deleting the triangle ends it, saying so.
    let mut s = joined();
    let applied = s
        .execute(&Command::Delete {
            nodes: vec![name("Triangle")],
        })
        .unwrap();
    assert!(s.doc.find_by_name("Patch").unwrap().g1_join.is_none());
    let label = "Delete 1 node (ended the G1 join of 'Patch': its triangle was deleted)";
    // The step says so to the caller and in the history; it made nothing.
    assert_eq!(applied.label, label);
    assert!(applied.created.is_empty(), "{:?}", applied.created);
    assert_eq!(s.history.done().last().unwrap().label, label);
    s.undo().unwrap();
    assert_eq!(s.doc.g1_joins().len(), 1, "undo brings the join back");
    // A knot inserted into the patch makes it two spans: the join ends.
    s.execute(&Command::InsertKnot {
        node: name("Patch"),
        at: 0.5,
        direction: hedra_doc::command::ParameterDirection::U,
    })
    .unwrap();
    assert!(s.doc.g1_joins().is_empty());
    // Errors name the nodes.
    let mut s = joined();
    let err = s
        .execute(&Command::MakeG1Join {
            triangle: name("Triangle"),
            quad: name("Patch"),
        })
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "G1 join of 'Patch' (#2) and 'Triangle' (#1): 'Patch' (#2) is already joined to 'Triangle' (#1) (break that join first)"
    );
    let err = s
        .execute(&Command::MakeG1Join {
            triangle: name("Patch"),
            quad: name("Triangle"),
        })
        .unwrap_err();
    assert!(
        matches!(err, CommandError::Join { .. })
            && err
                .to_string()
                .ends_with("'Patch' (#2) is not a Bézier triangle"),
        "{err}"
    );
    s.execute(&Command::Translate {
        nodes: vec![name("Triangle")],
        offset: DVec3::new(0.0, 0.0, 0.0001),
    })
    .unwrap();
    // Far apart: no shared edge.
    s.execute(&Command::AddSurface {
        name: "Far".into(),
        surface: SurfaceSpec::Bezier {
            nu: 2,
            nv: 2,
            points: vec![
                DVec3::new(10.0, 0.0, 0.0),
                DVec3::new(10.0, 0.0, 1.0),
                DVec3::new(11.0, 0.0, 0.0),
                DVec3::new(11.0, 0.0, 1.0),
            ],
        },
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let err = s
        .execute(&Command::MakeG1Join {
            triangle: name("Triangle"),
            quad: name("Far"),
        })
        .unwrap_err();
    assert!(
        err.to_string().starts_with(
            "G1 join of 'Far' (#3) and 'Triangle' (#1): the triangle and the patch share no edge"
        ),
        "{err}"
    );
}

/// The sample scene is the script's result (`HEDRA_BLESS=1` writes it).
#[test]
fn the_g1_join_sample_is_the_scripts_result() {
    let script = repo().join("tests/scripts/g1-join.ron");
    let text = std::fs::read_to_string(&script).unwrap();
    let commands = hedra_doc::script::parse(&text, &script).unwrap();
    let mut s = Session::new();
    hedra_doc::script::run(&mut s, &commands, &script).unwrap_or_else(|e| panic!("{e}"));
    assert_g1(&s, "the sample");
    // The dragged shared point moved the patch's corner with it.
    assert!(points(&s, "Patch")[4].distance(DVec3::new(1.0, 0.4, 0.1)) < 1e-12);
    let written = hedra_doc::file::to_string(&s);
    let sample = repo().join("assets/samples/g1-join.hedra.ron");
    if std::env::var_os("HEDRA_BLESS").is_some() {
        std::fs::write(&sample, &written).unwrap();
    }
    assert_eq!(
        std::fs::read_to_string(&sample).unwrap_or_default(),
        written,
        "{} is not the script's result (HEDRA_BLESS=1 writes it)",
        Path::new("assets/samples/g1-join.hedra.ron").display()
    );
}

#[test]
fn a_file_whose_join_names_a_missing_triangle_is_refused_by_name() {
    let s = joined();
    let text = hedra_doc::file::to_string(&s);
    let bad = text.replacen(
        "g1_join: Some((triangle: 1))",
        "g1_join: Some((triangle: 9))",
        1,
    );
    assert_ne!(bad, text);
    let err = hedra_doc::file::from_str(&bad, Path::new("bad.hedra.ron")).unwrap_err();
    assert!(
        err.to_string().ends_with(
            "node #2 'Patch' is joined to node #9, but they are not a Bézier patch and a Bézier triangle"
        ),
        "{err}"
    );
}

/// Coons and Gordon nodes following their curves and a kept G1 join in one
/// scene: saved and loaded back equal, the whole history undone and redone
/// with the document valid at every step, and the same as the scene
/// corpus's copy.
#[test]
fn patches_and_joins_save_and_load_with_their_links() {
    use hedra_doc::command::CurveSpec;
    use hedra_doc::construction::{Construction, Output, Recipe};
    let mut s = joined();
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let curves = [
        (
            "A",
            vec![p(10.0, 0.0, 0.0), p(11.0, 0.5, 0.0), p(12.0, 0.0, 0.0)],
        ),
        ("B", vec![p(12.0, 0.0, 0.0), p(12.0, 0.0, 2.0)]),
        ("C", vec![p(10.0, 0.0, 2.0), p(12.0, 0.0, 2.0)]),
        (
            "D",
            vec![p(10.0, 0.0, 2.0), p(10.3, 0.3, 1.0), p(10.0, 0.0, 0.0)],
        ),
        ("Mid U", vec![p(10.0, 0.0, 1.0), p(12.0, 0.0, 1.0)]),
        ("Mid V", vec![p(11.0, 0.0, 0.0), p(11.0, 0.0, 2.0)]),
    ];
    for (n, points) in curves {
        s.execute(&Command::AddCurve {
            name: n.into(),
            curve: CurveSpec::Bezier { points },
            parent: None,
            transform: NodeTransform::from_translation(DVec3::new(0.0, 3.0, 0.0)),
        })
        .unwrap();
    }
    s.execute(&Command::MakeFromCurves {
        name: "Coons".into(),
        construction: Construction {
            recipe: Recipe::Coons {
                boundaries: ["A", "B", "C", "D"].map(name),
            },
            output: Output::Nurbs,
        },
    })
    .unwrap();
    s.execute(&Command::MakeFromCurves {
        name: "Gordon".into(),
        construction: Construction {
            recipe: Recipe::Gordon {
                u_curves: ["C", "Mid U"].map(name).to_vec(),
                v_curves: ["B", "Mid V"].map(name).to_vec(),
            },
            output: Output::Mesh {
                segments: 4,
                profile_segments: 4,
            },
        },
    })
    .unwrap();
    s.execute(&Command::SetControlPoints {
        node: name("A"),
        points: vec![(1, DVec3::new(11.0, 1.0, 0.2))],
    })
    .unwrap_or_else(|e| panic!("{e}"));
    let text = hedra_doc::file::to_string(&s);
    // The scene corpus keeps this file forever (tests/scene_corpus.rs), and
    // it is what today's commands make (never rewritten: a change to what
    // the commands make fails here).
    golden::assert_matches_corpus("v2-patches.hedra.ron", &text);
    let loaded = hedra_doc::file::from_str(&text, Path::new("p.hedra.ron")).unwrap();
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let mut back = loaded.session;
    assert_eq!(back.doc, s.doc);
    assert_eq!(back.doc.g1_joins().len(), 1);
    assert_eq!(
        back.doc
            .nodes()
            .filter(|n| n.construction.is_some())
            .count(),
        2
    );
    while back.undo().is_some() {
        back.doc.check().unwrap();
    }
    assert_eq!(back.doc.node_count(), 0);
    while back.redo().is_some() {}
    assert_eq!(back.doc, s.doc);
}
