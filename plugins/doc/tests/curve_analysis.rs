//! `hedra eval` on every curve kind (both sides at a parameter, the
//! continuity at joints) and OBJ free-form curve export and import.

use glam::DVec3;
use hedra_doc::command::CurveSpec;
use hedra_doc::eval::{Evaluation, evaluate};
use hedra_doc::export::{CurveExport, ExportOptions, export_bytes};
use hedra_doc::import::{describe_repairs, obj_from_str};
use hedra_doc::{Command, NodeContent, NodeRef, NodeTransform, Session};
use hedra_geom::curves::interpolating::Tbc;
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

/// One spec of every kind, with a name, and what its interior joints
/// promise ("" for no promise beyond C0).
fn specs() -> Vec<(&'static str, CurveSpec)> {
    let p = zigzag();
    let mut corner = vec![Tbc::default(); 5];
    corner[2].continuity = 0.5;
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
                keys: Some(corner),
                closed: false,
            },
        ),
        (
            "Spline",
            CurveSpec::CubicSpline {
                points: p.clone(),
                parameterization: Parameterization::Uniform,
                ends: SplineEnds::Closed,
            },
        ),
        (
            "Chaikin",
            CurveSpec::Chaikin {
                points: p.clone(),
                level: 2,
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
                    v(6.0, 1.0),
                    v(8.0, 2.0),
                    v(9.0, 0.0),
                ],
                joins: Some(vec![Join::C1, Join::C0]),
                closed: false,
            },
        ),
        (
            "Koch",
            CurveSpec::Fractal {
                rule: FractalRule::Koch,
                points: vec![v(0.0, 0.0), v(3.0, 0.0)],
                level: 2,
                closed: false,
                normal: DVec3::Z,
            },
        ),
        (
            "Minkowski",
            CurveSpec::Fractal {
                rule: FractalRule::QuadraticKoch,
                points: vec![v(0.0, 0.0), v(0.0, 2.0), v(2.0, 2.0), v(2.0, 0.0)],
                level: 1,
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

fn add(name: &str, curve: CurveSpec, at: DVec3) -> Command {
    Command::AddCurve {
        name: name.into(),
        curve,
        parent: None,
        transform: NodeTransform::from_translation(at),
    }
}

fn every_kind_session() -> Session {
    let mut s = Session::new();
    for (name, spec) in specs() {
        s.execute(&add(name, spec, DVec3::new(1.0, 2.0, 3.0)))
            .unwrap();
    }
    s
}

fn eval(s: &Session, name: &str, t: f64) -> Evaluation {
    evaluate(&s.doc, &NodeRef::Name(name.into()), &[t]).unwrap()
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (DVec3::from_array(a) - DVec3::from_array(b)).length() <= tol
}

#[test]
fn eval_gives_both_sides_and_the_continuity_at_every_joint_of_every_kind() {
    let s = every_kind_session();
    for (name, _) in specs() {
        let mid = eval(&s, name, 0.0);
        let kind = mid.curve_kind.expect("a curve reports its kind");
        // Every joint evaluated at its parameter reports itself, and both
        // sides meet there.
        for j in &mid.joints {
            let e = eval(&s, name, j.parameter);
            let here = e.joint.as_ref().expect("a joint at its parameter");
            assert_eq!(here, j, "{name}");
            let sides = e.sides.as_ref().unwrap();
            let (b, a) = (
                sides.before.as_ref().unwrap(),
                sides.after.as_ref().unwrap(),
            );
            assert!(close(b.point, a.point, 1e-9), "{name} at {}", j.parameter);
            assert_eq!(
                close(b.first_derivative, a.first_derivative, 1e-6),
                j.c1,
                "{name} at {}: the printed derivatives show what the label says",
                j.parameter
            );
            let promise = match name {
                "Hermite" | "CatmullRom" => j.c1,
                "Quintic" | "Spline" | "Nurbs" => j.continuity == "C2",
                // Key 2 has continuity 0.5: a corner; the others C1.
                "KB" => {
                    if j.parameter == 2.0 {
                        j.continuity == "C0"
                    } else {
                        j.c1
                    }
                }
                "PolyBezier" => {
                    if j.parameter == 1.0 {
                        j.continuity == "C1"
                    } else {
                        j.continuity == "C0"
                    }
                }
                "Koch" => j.c0 && !j.g1,
                _ => j.c0,
            };
            assert!(
                promise,
                "{name} ({kind}) at {}: {}",
                j.parameter, j.continuity
            );
        }
        let closed = matches!(name, "CatmullRom" | "Spline" | "Minkowski");
        assert_eq!(
            mid.joints.last().is_some_and(|j| j.closing),
            closed,
            "{name}: the closing joint is listed last"
        );
        // The start of an open curve has no "before"; a closed one wraps.
        assert_eq!(
            mid.sides.as_ref().unwrap().before.is_some(),
            closed,
            "{name}"
        );
    }
    // The Lagrange curve is one polynomial: no joints.
    assert!(eval(&s, "Lagrange", 1.0).joints.is_empty());
    assert_eq!(eval(&s, "Lagrange", 1.0).curve_kind, Some("Lagrange"));
    // Joint counts: 3 inner keys; 5 + closing; Koch level 2 has 16
    // segments; quadratic Koch level 1 on a closed square 32 and closes.
    assert_eq!(eval(&s, "Hermite", 0.0).joints.len(), 3);
    assert_eq!(eval(&s, "CatmullRom", 0.0).joints.len(), 5);
    assert_eq!(eval(&s, "Koch", 0.0).joints.len(), 15);
    assert_eq!(eval(&s, "Minkowski", 0.0).joints.len(), 32);
    // Between joints both sides are one and the same piece.
    let e = eval(&s, "KB", 1.5);
    assert!(e.joint.is_none());
    let sides = e.sides.unwrap();
    assert_eq!(sides.before, sides.after);
}

#[test]
fn eval_text_and_json_name_the_kind_sides_and_joints() {
    let s = every_kind_session();
    let e = eval(&s, "KB", 2.0);
    let text = e.to_text();
    assert!(text.starts_with("KB [curve] at [2.0]"), "{text}");
    assert!(text.contains("  kind Kochanek-Bartels\n"), "{text}");
    assert!(text.contains("  before: point (2.000000000, 0.000000000, 0.000000000)"));
    assert!(text.contains("  joint here: C0\n"), "{text}");
    assert!(
        text.contains("  joints (3): t = 1 C1; t = 2 C0; t = 3 C1;"),
        "{text}"
    );
    let j: serde_json::Value = serde_json::to_value(&e).unwrap();
    assert_eq!(j["curve_kind"], "Kochanek-Bartels");
    assert_eq!(j["joint"]["continuity"], "C0");
    assert_eq!(j["joint"]["c1"], false);
    assert_eq!(j["joints"].as_array().unwrap().len(), 3);
    assert!(j["sides"]["before"]["first_derivative"].is_array());
    // At the end of an open curve: no "after".
    let end = eval(&s, "Hermite", 4.0).to_text();
    assert!(
        end.contains("  after: none (an end of the curve)\n"),
        "{end}"
    );
    // Koch level 2: 15 joints, the text lists 20 at most.
    let mut s2 = Session::new();
    s2.execute(&add(
        "K",
        CurveSpec::Fractal {
            rule: FractalRule::Koch,
            points: vec![v(0.0, 0.0), v(3.0, 0.0)],
            level: 3,
            closed: false,
            normal: DVec3::Z,
        },
        DVec3::ZERO,
    ))
    .unwrap();
    let text = evaluate(&s2.doc, &NodeRef::Name("K".into()), &[0.5])
        .unwrap()
        .to_text();
    assert!(text.contains("joints (63):"), "{text}");
    assert!(text.contains("… and 43 more"), "{text}");
    // A surface's JSON has no curve fields.
    let mut s3 = Session::new();
    s3.execute(&Command::AddSurface {
        name: "Ball".into(),
        surface: hedra_doc::command::SurfaceSpec::Sphere { radius: 1.0 },
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let e = evaluate(&s3.doc, &NodeRef::Name("Ball".into()), &[0.3, 0.6]).unwrap();
    let j = serde_json::to_value(&e).unwrap();
    assert!(j.get("joints").is_none() && j.get("sides").is_none(), "{j}");
}

fn curve_of(s: &Session, name: &str) -> std::sync::Arc<hedra_doc::scene::CurveContent> {
    match &s.doc.find_by_name(name).unwrap().content {
        NodeContent::Curve(c) => c.clone(),
        other => panic!("{name}: {}", other.kind()),
    }
}

#[test]
fn obj_free_form_curves_round_trip_exactly() {
    let mut s = every_kind_session();
    // A Lagrange curve of 13 points has an approximated NURBS form: it
    // goes out as a polyline.
    let many: Vec<DVec3> = (0..13).map(|i| v(i as f64, (i as f64).sin())).collect();
    s.execute(&add(
        "Long",
        CurveSpec::Lagrange {
            points: many,
            parameterization: Parameterization::Uniform,
        },
        DVec3::ZERO,
    ))
    .unwrap();
    assert!(curve_of(&s, "Long").tolerance().is_some());
    let path = Path::new("curves.obj");
    let options = ExportOptions {
        curves: CurveExport::FreeForm,
        ..ExportOptions::default()
    };
    let bytes = export_bytes(&s.doc, path, options).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    let count = |key: &str| {
        text.lines()
            .filter(|l| l.split_whitespace().next() == Some(key))
            .count()
    };
    let exact = specs().len();
    assert_eq!(count("curv"), exact);
    assert_eq!(count("end"), exact);
    assert_eq!(count("l"), 1, "the approximated Lagrange curve");
    // The rational NURBS writes weights; the others are plain B-splines.
    assert_eq!(count("cstype"), exact);
    assert_eq!(
        text.lines().filter(|l| *l == "cstype rat bspline").count(),
        1
    );
    assert!(
        text.contains("\nv 2 3 3 2\n"),
        "weight 2 on point (1, 1, 0) + (1, 2, 3)"
    );

    let imported = obj_from_str(&text, "curves.obj").unwrap();
    let curves: Vec<_> = imported.iter().filter(|m| m.curve.is_some()).collect();
    assert_eq!(curves.len(), exact);
    let offset = DVec3::new(1.0, 2.0, 3.0);
    for ((name, _), m) in specs().iter().zip(&curves) {
        assert_eq!(m.name, *name, "a curve is named after its object");
        let back = m.curve.as_ref().unwrap();
        let original = curve_of(&s, name);
        let original = original.nurbs();
        assert_eq!(back.knots(), original.knots(), "{name}");
        assert_eq!(back.weights(), original.weights(), "{name}");
        assert_eq!(back.degree(), original.degree());
        let (a, b) = original.domain();
        for i in 0..=200 {
            let t = a + (b - a) * i as f64 / 200.0;
            let d = (back.point(t) - (original.point(t) + offset)).length();
            assert!(d < 1e-12, "{name} at {t}: {d}");
        }
    }
    // Into a scene: curve nodes, NURBS kind, one undo step.
    let mut fresh = Session::new();
    fresh.import(&imported, "Import curves.obj");
    assert_eq!(fresh.doc.node_count(), exact);
    assert!(matches!(
        curve_of(&fresh, "Koch").kind(),
        CurveKind::Nurbs(_)
    ));
    assert!(
        describe_repairs(&imported)
            .iter()
            .any(|l| l.contains("1 polyline(s)"))
    );
    fresh.undo();
    assert_eq!(fresh.doc.node_count(), 0);

    // The default export keeps writing polylines only.
    let plain =
        String::from_utf8(export_bytes(&s.doc, path, ExportOptions::default()).unwrap()).unwrap();
    assert!(!plain.contains("curv "));
    assert_eq!(
        plain.lines().filter(|l| l.starts_with("l ")).count(),
        exact + 1
    );
}

#[test]
fn obj_free_form_records_from_other_programs() {
    // A B-spline trimmed by its `curv` range, a rational Bézier quarter
    // circle with negative vertex numbers, a parameter list continued
    // with `\`, and a Cardinal curve Hedra does not read.
    let obj = "\
o Trimmed
v 0 0 0
v 1 2 0
v 3 2 0
v 4 0 0
cstype bspline
deg 2
curv 0.25 0.75 1 2 3 4
parm u 0 0 0 \\
  0.5 1 1 1
end
o Quarter
v 1 0 0
v 1 1 0 0.7071067811865476
v 0 1 0
cstype rat bezier
deg 2
curv 0 1 -3 -2 -1
parm u 0 1
end
cstype cardinal
deg 3
curv 0 1 1 2 3 4
parm u 0 1
end
";
    let meshes = obj_from_str(obj, "free.obj").unwrap();
    assert_eq!(meshes.len(), 2);
    let trimmed = meshes[0].curve.as_ref().unwrap();
    assert_eq!(meshes[0].name, "Trimmed");
    assert_eq!(trimmed.domain(), (0.25, 0.75));
    let full = hedra_geom::NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        vec![DVec3::ZERO, v(1.0, 2.0), v(3.0, 2.0), v(4.0, 0.0)],
        vec![1.0; 4],
    )
    .unwrap();
    for i in 0..=10 {
        let t = 0.25 + 0.05 * i as f64;
        assert!((trimmed.point(t) - full.point(t)).length() < 1e-12);
    }
    let quarter = meshes[1].curve.as_ref().unwrap();
    for i in 0..=10 {
        let p = quarter.point(i as f64 / 10.0);
        assert!((p.length() - 1.0).abs() < 1e-12, "on the unit circle: {p}");
    }
    let notes = describe_repairs(&meshes).join("\n");
    assert!(
        notes.contains("1 free-form record(s) other than B-spline and Bézier curves"),
        "{notes}"
    );
    // Malformed records are refused by line.
    for (bad, message) in [
        (
            "v 0 0 0\nv 1 0 0\ncstype bspline\ndeg 1\ncurv 0 1 1 2\nend\n",
            "line 5: free-form curve: no 'parm u' knots",
        ),
        (
            "v 0 0 0\nv 1 0 0\ncstype bspline\ndeg 1\ncurv 0 1 1 5\nparm u 0 0 1 1\nend\n",
            "line 5: free-form curve: vertex 5 does not exist (2 come before)",
        ),
        (
            "v 0 0 0\nv 1 0 0\ncstype bspline\ndeg 1\ncurv 0 2 1 2\nparm u 0 0 1 1\nend\n",
            "line 5: free-form curve: the range [0, 2] is not inside the knots' domain [0, 1]",
        ),
        (
            "v 0 0 0\nv 1 0 0 -1\ncstype rat bspline\ndeg 1\ncurv 0 1 1 2\nparm u 0 0 1 1\nend\n",
            "line 5: free-form curve: weight 1 is -1: weights must be positive",
        ),
    ] {
        let e = obj_from_str(bad, "bad.obj").unwrap_err().to_string();
        assert_eq!(e, format!("bad.obj: {message}"));
    }
    // Hostile records are refused by name, never a panic (the fuzz body's
    // checks: errors name the file, curves are finite).
    let hostile = [
        "v 0 0 0\nv 1 0 0\ncstype bspline\ndeg 18446744073709551615\ncurv 0 1 1 2\nparm u 0 1\nend\n",
        "v 0 0 0\nv 1 0 0\ncstype bezier\ndeg 18446744073709551615\ncurv 0 1 1 2\nend\n",
        "v 0 0 0\nv 1 0 0\ncstype bezier\ndeg 0\ncurv 0 1 1 2\nend\n",
        "v 0 0 0\nv 1 0 0\ncstype bspline\ndeg 1\ncurv 0 1 -3 2\nparm u 0 0 1 1\nend\n",
        "v 0 0 0\nv 1 0 0\ncstype bspline\ndeg 1\ncurv nan 1 1 2\nparm u 0 0 1 1\nend\n",
        "v 0 0 0\nv 1 0 0 inf\ncstype rat bspline\ndeg 1\ncurv 0 1 1 2\nparm u 0 0 1 1\nend\n",
        "v 0 0 0\nv 1 0 0\ncstype bspline\ndeg 1\ncurv 0 1 1 2\nparm u 1 0 0 1\nend\n",
        "cstype bspline\ndeg 1\ncurv 0 1\nend\nend\nparm u \\",
    ];
    for text in hostile {
        hedra_doc::fuzz::obj(text.as_bytes());
        assert!(obj_from_str(text, "h.obj").is_err(), "{text}");
    }
    assert_eq!(
        obj_from_str(hostile[0], "h.obj").unwrap_err().to_string(),
        "h.obj: line 5: free-form curve: degree 18446744073709551615 does not fit 2 control points (degree 1 to 1)"
    );
}
