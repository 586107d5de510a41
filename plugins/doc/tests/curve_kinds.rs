//! Curve nodes of every kind: saved and loaded, undone and redone, edited
//! through commands, refused by name with nothing changed.

mod golden;

use glam::DVec3;
use hedra_doc::command::CurveSpec;
use hedra_doc::file;
use hedra_doc::{Command, NodeContent, NodeRef, NodeTransform, Session};
use hedra_geom::curves::{Curve, CurveKind, FractalRule, Join, Parameterization, SplineEnds};
use std::path::Path;

fn v(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

fn zigzag() -> Vec<DVec3> {
    vec![
        v(0.0, 0.0),
        v(1.0, 1.0),
        v(2.0, 0.0),
        v(3.0, 1.0),
        v(4.0, 0.0),
    ]
}

/// One spec of every kind, with a name.
fn specs() -> Vec<(&'static str, CurveSpec)> {
    let p = zigzag();
    vec![
        (
            "Lagrange",
            CurveSpec::Lagrange {
                points: p.clone(),
                parameterization: Parameterization::Centripetal,
            },
        ),
        (
            "Hermite",
            CurveSpec::Hermite {
                points: p.clone(),
                tangents: vec![DVec3::X; 5],
            },
        ),
        (
            "Quintic",
            CurveSpec::QuinticHermite {
                points: p.clone(),
                tangents: vec![DVec3::X; 5],
                accelerations: vec![DVec3::Y; 5],
            },
        ),
        (
            "CatmullRom",
            CurveSpec::CatmullRom {
                points: p.clone(),
                parameterization: Parameterization::Chord,
                closed: true,
            },
        ),
        (
            "KB",
            CurveSpec::KochanekBartels {
                points: p.clone(),
                keys: None,
                closed: false,
            },
        ),
        (
            "Spline",
            CurveSpec::CubicSpline {
                points: p.clone(),
                parameterization: Parameterization::Uniform,
                ends: SplineEnds::Clamped {
                    start: DVec3::Y,
                    end: DVec3::X,
                },
            },
        ),
        (
            "Chaikin",
            CurveSpec::Chaikin {
                points: p.clone(),
                level: 4,
                closed: false,
            },
        ),
        (
            "PolyBezier",
            CurveSpec::PolyBezier {
                points: vec![
                    v(0.0, 0.0),
                    v(1.0, 1.0),
                    v(2.0, 1.0),
                    v(3.0, 0.0),
                    v(4.0, -1.0),
                    v(5.0, 0.0),
                    v(6.0, 0.0),
                ],
                joins: Some(vec![Join::C1]),
                closed: false,
            },
        ),
        (
            "Koch",
            CurveSpec::Fractal {
                rule: FractalRule::Koch,
                points: vec![v(0.0, 0.0), v(3.0, 0.0)],
                level: 4,
                closed: false,
                normal: DVec3::Z,
            },
        ),
        (
            "Minkowski",
            CurveSpec::Fractal {
                rule: FractalRule::QuadraticKoch,
                points: vec![v(0.0, 0.0), v(0.0, 2.0), v(2.0, 2.0), v(2.0, 0.0)],
                level: 2,
                closed: true,
                normal: DVec3::Z,
            },
        ),
        (
            "Nurbs",
            CurveSpec::Nurbs {
                degree: 3,
                points: p,
                weights: Some(vec![1.0, 2.0, 1.0, 0.5, 1.0]),
                knots: None,
            },
        ),
    ]
}

fn add(name: &str, curve: CurveSpec) -> Command {
    Command::AddCurve {
        name: name.into(),
        curve,
        parent: None,
        transform: NodeTransform::from_translation(DVec3::new(1.0, 2.0, 3.0)),
    }
}

fn every_kind_session() -> Session {
    let mut s = Session::new();
    for (name, spec) in specs() {
        s.execute(&add(name, spec)).unwrap();
    }
    s
}

fn curve(s: &Session, name: &str) -> std::sync::Arc<hedra_doc::scene::CurveContent> {
    match &s.doc.find_by_name(name).unwrap().content {
        NodeContent::Curve(c) => c.clone(),
        other => panic!("{name}: {}", other.kind()),
    }
}

#[test]
fn every_kind_saves_and_loads_as_it_was() {
    let s = every_kind_session();
    let text = file::to_string(&s);
    // The scene corpus keeps this file forever (tests/scene_corpus.rs), and
    // it is what today's commands make (never rewritten: a change to what
    // the commands make fails here).
    golden::assert_matches_corpus("v2-curve-kinds.hedra.ron", &text);
    let loaded = file::from_str(&text, Path::new("kinds.hedra.ron")).unwrap();
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    assert_eq!(loaded.session.doc, s.doc, "same kinds, same NURBS forms");
    // Each kind is written as itself, NURBS as before.
    assert!(text.contains("CurveKind(CatmullRom("));
    assert!(text.contains("CurveKind(Fractal("));
    assert!(text.contains("Curve((degree: 3"));
    for (name, _) in specs() {
        let c = curve(&loaded.session, name);
        assert_eq!(c.kind().name() == "NURBS", name == "Nurbs", "{name}");
    }
    // And the history loads too: undo all, redo all.
    let mut back = loaded.session;
    while back.undo().is_some() {}
    assert_eq!(back.doc.node_count(), 0);
    while back.redo().is_some() {}
    assert_eq!(back.doc, s.doc);
}

#[test]
fn a_stored_kind_with_bad_data_is_refused_on_load() {
    let s = every_kind_session();
    let text = file::to_string(&s).replace("level: 4", "level: 99");
    let err = file::from_str(&text, Path::new("bad.hedra.ron")).unwrap_err();
    assert!(err.to_string().contains("level 99 is too high"), "{err}");
}

#[test]
fn edits_undo_and_redo_exactly() {
    let mut s = every_kind_session();
    let start = s.doc.clone();
    let edits = [
        Command::InsertCurvePoint {
            node: NodeRef::Name("Spline".into()),
            at: 1.5,
        },
        Command::DeleteCurvePoints {
            node: NodeRef::Name("Lagrange".into()),
            points: vec![0, 4],
        },
        Command::ExtrudeCurve {
            node: NodeRef::Name("PolyBezier".into()),
            end: hedra_geom::curves::CurveEnd::Start,
            to: v(-2.0, 0.0),
        },
        Command::SetCurveClosed {
            node: NodeRef::Name("Chaikin".into()),
            closed: true,
        },
        Command::ReverseCurve {
            node: NodeRef::Name("KB".into()),
        },
        Command::SetCurveJoin {
            node: NodeRef::Name("PolyBezier".into()),
            joint: 1,
            join: Join::C0,
        },
        Command::ConvertCurveToNurbs {
            node: NodeRef::Name("Koch".into()),
        },
        Command::SetControlPoints {
            node: NodeRef::Name("Hermite".into()),
            points: vec![(2, v(2.0, 5.0))],
        },
        Command::SplitCurve {
            node: NodeRef::Name("Quintic".into()),
            at: 2.5,
            name: None,
        },
    ];
    for e in &edits {
        s.execute(e).unwrap_or_else(|err| panic!("{e:?}: {err}"));
    }
    let end = s.doc.clone();
    assert_eq!(curve(&s, "Lagrange").control_points().len(), 3);
    assert_eq!(curve(&s, "Hermite").control_points()[2], v(2.0, 5.0));
    assert!(curve(&s, "Chaikin").kind().is_closed());
    assert!(matches!(curve(&s, "Koch").kind(), CurveKind::Nurbs(_)));
    assert_eq!(curve(&s, "Koch").nurbs().points().len(), 257);
    let q1 = curve(&s, "Quintic.001");
    assert!((q1.nurbs().point(0.0) - curve(&s, "Quintic").nurbs().point(3.0)).length() < 1e-12);
    for _ in &edits {
        s.undo().unwrap();
    }
    assert_eq!(s.doc, start);
    for _ in &edits {
        s.redo().unwrap();
    }
    assert_eq!(s.doc, end);
}

#[test]
fn refusals_name_the_problem_and_change_nothing() {
    let mut s = every_kind_session();
    let before = s.doc.clone();
    let refused = [
        (
            add(
                "One",
                CurveSpec::Lagrange {
                    points: vec![DVec3::ZERO],
                    parameterization: Parameterization::Uniform,
                },
            ),
            "curve 'One': Lagrange needs 2 points or more, got 1",
        ),
        (
            Command::SetCurveClosed {
                node: NodeRef::Name("Lagrange".into()),
                closed: true,
            },
            "closing is not possible on a Lagrange curve",
        ),
        (
            Command::DeleteCurvePoints {
                node: NodeRef::Name("PolyBezier".into()),
                points: vec![1],
            },
            "point 1 is a handle of the poly-Bézier",
        ),
        (
            Command::JoinCurves {
                first: NodeRef::Name("Lagrange".into()),
                second: NodeRef::Name("Hermite".into()),
            },
            "a Lagrange curve cannot be joined to a cubic Hermite curve",
        ),
        (
            Command::SetWeights {
                node: NodeRef::Name("KB".into()),
                weights: vec![(0, 2.0)],
            },
            "setting weights (convert it to NURBS first) is not possible on a Kochanek-Bartels curve",
        ),
        (
            Command::SetCurveJoin {
                node: NodeRef::Name("PolyBezier".into()),
                joint: 5,
                join: Join::G1,
            },
            "joint 5 does not exist (there are 1)",
        ),
        (
            Command::InsertCurvePoint {
                node: NodeRef::Name("Spline".into()),
                at: 9.0,
            },
            "parameter 9 is outside the domain [0, 4]",
        ),
        (
            Command::SplitCurve {
                node: NodeRef::Name("CatmullRom".into()),
                at: 1.0,
                name: None,
            },
            "splitting a closed curve (open it first)",
        ),
    ];
    for (cmd, message) in refused {
        let err = s.execute(&cmd).unwrap_err().to_string();
        assert!(err.contains(message), "{cmd:?}: {err}");
        assert_eq!(s.doc, before, "{cmd:?} changed the document");
    }
}

#[test]
fn join_takes_the_second_curve_into_the_first_ones_space() {
    let mut s = Session::new();
    let spec = |pts: Vec<DVec3>| CurveSpec::CatmullRom {
        points: pts,
        parameterization: Parameterization::Uniform,
        closed: false,
    };
    s.execute(&add("A", spec(vec![v(0.0, 0.0), v(1.0, 1.0), v(2.0, 0.0)])))
        .unwrap();
    // B's local (0, 0) is at world A's (3, 0): its transform is 2 further along x.
    s.execute(&Command::AddCurve {
        name: "B".into(),
        curve: spec(vec![v(0.0, 0.0), v(1.0, -1.0)]),
        parent: None,
        transform: NodeTransform::from_translation(DVec3::new(3.0, 2.0, 3.0)),
    })
    .unwrap();
    s.execute(&Command::JoinCurves {
        first: NodeRef::Name("A".into()),
        second: NodeRef::Name("B".into()),
    })
    .unwrap();
    assert!(s.doc.find_by_name("B").is_none());
    let a = curve(&s, "A");
    // B in A's space starts where A ends: the shared point is kept once.
    assert_eq!(
        a.control_points(),
        &[v(0.0, 0.0), v(1.0, 1.0), v(2.0, 0.0), v(3.0, -1.0)]
    );
    let f = a.nurbs();
    assert!((f.point(f.domain().1) - v(3.0, -1.0)).length() < 1e-12);
}

/// The command's curve specs and the kernel's curve kinds stay in step
/// (issue 34 item 6): every kind a spec makes (one of each, the shorthands
/// Bézier, circle and closed among them) maps back through
/// `CurveSpec::of_kind` to a spec that makes exactly that kind again.
#[test]
fn every_curve_kind_has_a_spec_that_makes_it_again() {
    let mut all = specs();
    all.push(("bezier", CurveSpec::Bezier { points: zigzag() }));
    all.push(("circle", CurveSpec::Circle { radius: 1.5 }));
    all.push((
        "closed",
        CurveSpec::Closed {
            degree: 3,
            points: zigzag(),
            weights: None,
        },
    ));
    let mut kinds = std::collections::HashSet::new();
    for (name, spec) in all {
        let kind = spec.curve().unwrap_or_else(|e| panic!("{name}: {e}"));
        kinds.insert(std::mem::discriminant(&kind));
        let again = CurveSpec::of_kind(&kind);
        assert_eq!(again.curve().as_ref(), Ok(&kind), "{name}: {again:?}");
    }
    // Nurbs, Lagrange, both Hermites, Catmull-Rom, Kochanek-Bartels, the
    // cubic spline, Chaikin, poly-Bézier and fractals: every kernel kind.
    assert_eq!(kinds.len(), 10);
}
