//! Hedra's NURBS against openNURBS (issue 35): the same control points,
//! weights and knots go to McNeel's openNURBS through its Python package
//! `rhino3dm` (pinned in `scripts/requirements.txt`, run by
//! `scripts/rhino_nurbs.py`), and the results must agree to 1e-12 of the
//! curve's size: points and first and second derivatives of a curve of
//! every kind whose NURBS form is exact (NURBS, circle, cubic and quintic
//! Hermite, Catmull-Rom, Kochanek-Bartels, cubic spline, poly-Bézier,
//! Lagrange), points and unit normals of surfaces (sphere, cylinder,
//! revolution, extrusion, a rational bicubic), and the control polygons
//! after a knot insertion and a degree elevation. The test fails when the
//! reference cannot run.

use hedra_geom::curves::{Curve, CurveKind};
use hedra_geom::surfaces::Surface;
use hedra_geom::{DVec3, NurbsCurve, NurbsSurface};
use serde_json::{Value, json};

mod reference;

fn v3(p: DVec3) -> [f64; 3] {
    [p.x, p.y, p.z]
}

fn from_json(v: &Value) -> DVec3 {
    let a: Vec<f64> = serde_json::from_value(v.clone()).unwrap();
    DVec3::new(a[0], a[1], a[2])
}

/// Seven parameters inside the domain, off the knots of uniform vectors.
fn params(a: f64, b: f64) -> Vec<f64> {
    (0..7)
        .map(|k| a + (b - a) * (k as f64 + 0.37) / 7.0)
        .collect()
}

/// The curves: NURBS ones made directly and the NURBS forms of the other
/// kinds (only those whose form is exact).
fn curves() -> Vec<(String, NurbsCurve)> {
    let mut out = vec![
        (
            "circle".to_string(),
            NurbsCurve::circle(DVec3::new(0.5, -1.0, 2.0), 1.5),
        ),
        (
            "clamped cubic B-spline".to_string(),
            NurbsCurve::clamped(
                3,
                vec![
                    DVec3::new(0.0, 0.0, 0.0),
                    DVec3::new(1.0, 2.0, 0.5),
                    DVec3::new(2.5, -1.0, 1.0),
                    DVec3::new(4.0, 0.5, -0.5),
                    DVec3::new(5.0, 2.0, 0.0),
                    DVec3::new(6.5, 1.0, 1.5),
                    DVec3::new(8.0, 0.0, 0.0),
                ],
            )
            .unwrap(),
        ),
        (
            "rational quartic, uneven knots".to_string(),
            NurbsCurve::new(
                4,
                vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.45, 1.2, 1.2, 1.2, 1.2, 1.2],
                vec![
                    DVec3::new(0.0, 0.0, 0.0),
                    DVec3::new(1.0, 1.0, 0.0),
                    DVec3::new(2.0, -0.5, 1.0),
                    DVec3::new(3.0, 2.0, 0.0),
                    DVec3::new(4.0, 0.0, -1.0),
                    DVec3::new(5.0, 1.0, 0.5),
                    DVec3::new(6.0, 0.0, 0.0),
                ],
                vec![1.0, 0.5, 2.0, 0.8, 1.5, 0.7, 1.0],
            )
            .unwrap(),
        ),
    ];
    let kinds = [
        "CubicHermite(points: [(0.0, 0.0, 0.0), (2.0, 1.0, 0.0), (4.0, -1.0, 1.0)], tangents: [(1.0, 2.0, 0.0), (2.0, 0.0, 1.0), (1.0, -1.0, 0.0)])",
        "QuinticHermite(points: [(0.0, 0.0, 0.0), (2.0, 1.0, 0.0), (4.0, -1.0, 1.0)], tangents: [(1.0, 2.0, 0.0), (2.0, 0.0, 1.0), (1.0, -1.0, 0.0)], accelerations: [(0.0, 1.0, 0.0), (-1.0, 0.0, 0.5), (0.0, 0.0, 0.0)])",
        "CatmullRom(points: [(0.0, 0.0, 0.0), (1.0, 2.0, 0.0), (3.0, 1.0, 1.0), (4.0, 3.0, 0.0), (6.0, 0.0, -1.0)])",
        "KochanekBartels(points: [(0.0, 0.0, 0.0), (1.0, 2.0, 0.0), (3.0, 1.0, 1.0), (4.0, 3.0, 0.0), (6.0, 0.0, -1.0)], keys: [(tension: 0.3, bias: -0.2, continuity: 0.1), (tension: 0.0, bias: 0.5, continuity: -0.4), (tension: -0.5, bias: 0.0, continuity: 0.2), (tension: 0.2, bias: 0.1, continuity: 0.0), (tension: 0.0, bias: 0.0, continuity: 0.0)])",
        "CubicSpline(points: [(0.0, 0.0, 0.0), (1.0, 2.0, 0.0), (3.0, 1.0, 1.0), (4.0, 3.0, 0.0), (6.0, 0.0, -1.0)])",
        "PolyBezier(points: [(0.0, 0.0, 0.0), (1.0, 2.0, 0.0), (2.0, 2.0, 1.0), (3.0, 0.0, 0.0), (4.0, -2.0, -1.0), (5.0, -1.0, 0.0), (6.0, 0.0, 0.0)], joins: [C0])",
        "Lagrange(points: [(0.0, 0.0, 0.0), (1.0, 2.0, 0.0), (3.0, 1.0, 1.0), (4.0, 3.0, 0.0)])",
    ];
    for text in kinds {
        let kind: CurveKind = ron::from_str(text).unwrap_or_else(|e| panic!("{text}: {e}"));
        let form = kind.to_nurbs().unwrap();
        assert!(form.tolerance.is_none(), "{text}: the NURBS form is exact");
        let name = text.split('(').next().unwrap().to_string();
        out.push((name, form.curve));
    }
    out
}

fn surfaces() -> Vec<(String, NurbsSurface)> {
    let profile = NurbsCurve::clamped(
        2,
        vec![
            DVec3::new(0.5, 0.0, 0.0),
            DVec3::new(1.5, 0.5, 0.0),
            DVec3::new(1.0, 1.5, 0.0),
            DVec3::new(0.3, 2.0, 0.0),
        ],
    )
    .unwrap();
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..5 {
        for j in 0..4 {
            let (x, y) = (i as f64, j as f64);
            points.push(DVec3::new(x, y, (x * 1.3).sin() * (y * 0.7).cos()));
            weights.push(1.0 + 0.3 * ((i + 2 * j) % 3) as f64);
        }
    }
    let knots_u = vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0];
    let knots_v = vec![0.0, 0.0, 0.0, 0.0, 2.0, 2.0, 2.0, 2.0];
    vec![
        (
            "sphere".into(),
            NurbsSurface::sphere(DVec3::new(1.0, 0.0, -0.5), 1.2),
        ),
        ("cylinder".into(), NurbsSurface::cylinder(0.8, 2.0)),
        (
            "revolution".into(),
            NurbsSurface::revolve(&profile).unwrap(),
        ),
        (
            "extrusion".into(),
            NurbsSurface::extrude(&profile, DVec3::new(0.2, 0.3, 1.5)).unwrap(),
        ),
        (
            "rational bicubic".into(),
            NurbsSurface::new(3, 3, knots_u, knots_v, 5, 4, points, weights).unwrap(),
        ),
    ]
}

fn run(input: &Value) -> Value {
    reference::run("rhino_nurbs.py", "rhino3dm", input)
}

/// A control polygon with its knots (openNURBS drops the first and last).
fn assert_same_net(
    label: &str,
    knots: &[f64],
    points: &[DVec3],
    weights: &[f64],
    theirs: &Value,
    knot_key: &str,
    size: f64,
) {
    let their_knots: Vec<f64> = serde_json::from_value(theirs[knot_key].clone()).unwrap();
    assert_eq!(their_knots.len(), knots.len() - 2, "{label}: knot count");
    for (a, b) in knots[1..knots.len() - 1].iter().zip(&their_knots) {
        assert!(
            (a - b).abs() < 1e-12,
            "{label}: knots {knots:?} vs {their_knots:?}"
        );
    }
    let their_points: Vec<DVec3> = theirs["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(from_json)
        .collect();
    let their_weights: Vec<f64> = serde_json::from_value(theirs["weights"].clone()).unwrap();
    assert_eq!(their_points.len(), points.len(), "{label}: point count");
    for (k, (p, q)) in points.iter().zip(&their_points).enumerate() {
        assert!(
            p.distance(*q) < 1e-12 * size,
            "{label}: point {k}: {p} vs {q}"
        );
        assert!(
            (weights[k] - their_weights[k]).abs() < 1e-12,
            "{label}: weight {k}: {} vs {}",
            weights[k],
            their_weights[k]
        );
    }
}

fn size_of(points: &[DVec3]) -> f64 {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    (hi - lo).length().max(1.0)
}

#[test]
fn curves_and_surfaces_agree_with_opennurbs() {
    let curves = curves();
    let surfaces = surfaces();
    let curve_input: Vec<Value> = curves
        .iter()
        .map(|(_, c)| {
            let (a, b) = c.domain();
            json!({
                "degree": c.degree(),
                "knots": c.knots(),
                "points": c.points().iter().map(|p| v3(*p)).collect::<Vec<_>>(),
                "weights": c.weights(),
                "params": params(a, b),
                "insert": a + (b - a) * 0.61,
            })
        })
        .collect();
    let surface_input: Vec<Value> = surfaces
        .iter()
        .map(|(_, s)| {
            let ((u0, u1), (v0, v1)) = s.domain();
            let pairs: Vec<[f64; 2]> = params(u0, u1)
                .into_iter()
                .zip(params(v0, v1).into_iter().rev())
                .map(|(u, v)| [u, v])
                .collect();
            let (ku, kv) = s.knots();
            json!({
                "degrees": [s.degrees().0, s.degrees().1],
                "knots_u": ku,
                "knots_v": kv,
                "size": [s.size().0, s.size().1],
                "points": s.points().iter().map(|p| v3(*p)).collect::<Vec<_>>(),
                "weights": s.weights(),
                "params": pairs,
                "insert_u": u0 + (u1 - u0) * 0.61,
            })
        })
        .collect();
    let reference = run(&json!({ "curves": curve_input, "surfaces": surface_input }));
    for ((label, c), theirs) in curves.iter().zip(reference["curves"].as_array().unwrap()) {
        let size = size_of(c.points());
        let (a, b) = c.domain();
        assert_same_values(label, c, theirs, size);
        let inserted = c.insert_knot(a + (b - a) * 0.61).unwrap();
        assert_same_net(
            &format!("{label}, knot inserted"),
            inserted.knots(),
            inserted.points(),
            inserted.weights(),
            &theirs["inserted"],
            "knots",
            size,
        );
        // openNURBS raises the degree through Bézier spans (more knots than
        // needed), so the two are compared by their values; Hedra's keeps
        // each knot with one more multiplicity.
        let elevated = c.elevate_degree().unwrap();
        assert_eq!(elevated.degree(), c.degree() + 1);
        assert_eq!(
            elevated.interior_knots(),
            c.interior_knots()
                .into_iter()
                .map(|(k, m)| (k, m + 1))
                .collect::<Vec<_>>(),
            "{label}"
        );
        assert_same_values(
            &format!("{label}, degree raised"),
            &elevated,
            &theirs["elevated"],
            size,
        );
    }
    for ((label, s), theirs) in surfaces
        .iter()
        .zip(reference["surfaces"].as_array().unwrap())
    {
        let size = size_of(s.points());
        let ((u0, u1), _) = s.domain();
        assert_same_surface_values(label, s, theirs, size);
        let check = |what: &str, net: &NurbsSurface, theirs: &Value| {
            let size_theirs: Vec<usize> = serde_json::from_value(theirs["size"].clone()).unwrap();
            assert_eq!(
                [net.size().0, net.size().1],
                [size_theirs[0], size_theirs[1]],
                "{label}, {what}: net size"
            );
            assert_same_net(
                &format!("{label}, {what}"),
                net.knots().0,
                net.points(),
                net.weights(),
                theirs,
                "knots_u",
                size,
            );
        };
        check(
            "knot inserted in u",
            &s.insert_knot_u(u0 + (u1 - u0) * 0.61).unwrap(),
            &theirs["inserted"],
        );
        assert_same_surface_values(
            &format!("{label}, degree raised in u"),
            &s.elevate_u().unwrap(),
            &theirs["elevated"],
            size,
        );
    }
}

/// The curve's points and first and second derivatives at [`params`]
/// equal openNURBS's to 1e-12 of the size (or of the vector).
fn assert_same_values(label: &str, c: &NurbsCurve, theirs: &Value, size: f64) {
    let (a, b) = c.domain();
    for (k, t) in params(a, b).into_iter().enumerate() {
        let [p, d1, d2] = c.derivatives(t);
        for (ours, key) in [(p, "points"), (d1, "d1"), (d2, "d2")] {
            let q = from_json(&theirs[key][k]);
            let scale = size.max(q.length());
            assert!(
                ours.distance(q) < 1e-12 * scale,
                "{label}: {key} at {t}: {ours} vs {q}"
            );
        }
    }
}

/// The surface's points and unit normals at the parameter pairs equal
/// openNURBS's.
fn assert_same_surface_values(label: &str, s: &NurbsSurface, theirs: &Value, size: f64) {
    let ((u0, u1), (v0, v1)) = s.domain();
    let pairs = params(u0, u1)
        .into_iter()
        .zip(params(v0, v1).into_iter().rev());
    for (k, (u, v)) in pairs.enumerate() {
        let e = s.evaluate(u, v);
        let q = from_json(&theirs["points"][k]);
        assert!(
            e.p.distance(q) < 1e-12 * size,
            "{label}: point at ({u}, {v}): {} vs {q}",
            e.p
        );
        let normal = e.du.cross(e.dv).normalize();
        let n = from_json(&theirs["normals"][k]);
        assert!(
            normal.distance(n) < 1e-12,
            "{label}: normal at ({u}, {v}): {normal} vs {n}"
        );
    }
}
