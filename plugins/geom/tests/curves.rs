//! Curves against known values: the exact NURBS circle, Bernstein partition
//! of unity, derivatives against finite differences, knot insertion and
//! degree elevation that do not move the curve, interpolation through the
//! given points, arc length, closest point, curvature.

use hedra_geom::DVec3;
use hedra_geom::curves::analysis::{
    arc_length, closest_parameter, curvature, equal_arc_length_parameters, frenet_frame,
    osculating_circle,
};
use hedra_geom::curves::bezier::bernstein;
use hedra_geom::curves::interpolating::{
    HermiteSpline, Polyline, PowerBasisCurve, Tbc, c2_cubic_spline, chaikin,
};
use hedra_geom::curves::{Bezier, Curve, CurveError, NurbsCurve};
use proptest::prelude::*;

fn close(a: DVec3, b: DVec3, tol: f64) -> bool {
    (a - b).length() <= tol
}

fn samples(curve: &dyn Curve, n: usize) -> impl Iterator<Item = f64> + '_ {
    let (a, b) = curve.domain();
    (0..=n).map(move |i| a + (b - a) * i as f64 / n as f64)
}

#[test]
fn the_nurbs_circle_is_exact() {
    let c = NurbsCurve::circle(DVec3::new(1.0, 2.0, 3.0), 1.0);
    for t in samples(&c, 1000) {
        let r = (c.point(t) - DVec3::new(1.0, 2.0, 3.0)).length();
        assert!((r - 1.0).abs() < 1e-12, "radius {r} at {t}");
        // Curvature of a unit circle is 1 everywhere.
        assert!(
            (curvature(&c, t) - 1.0).abs() < 1e-9,
            "κ = {} at {t}",
            curvature(&c, t)
        );
    }
    assert!((arc_length(&c, 0.0, 1.0) - std::f64::consts::TAU).abs() < 1e-10);
    let (centre, radius) = osculating_circle(&c, 0.3).unwrap();
    assert!(close(centre, DVec3::new(1.0, 2.0, 3.0), 1e-9) && (radius - 1.0).abs() < 1e-9);
}

#[test]
fn bernstein_polynomials_sum_to_one() {
    for n in 1..12 {
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            let s: f64 = (0..=n).map(|i| bernstein(n, i, t)).sum();
            assert!((s - 1.0).abs() < 1e-14, "n = {n}, t = {t}: {s}");
        }
    }
}

fn bezier() -> Bezier {
    Bezier::new(vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 2.0, 0.0),
        DVec3::new(3.0, 2.0, 1.0),
        DVec3::new(4.0, 0.0, -1.0),
    ])
    .unwrap()
}

#[test]
fn bezier_forms_agree_split_and_elevate_keep_the_curve() {
    let b = bezier();
    let (left, right) = b.split(0.3);
    let up = b.elevate();
    assert_eq!(up.degree(), 4);
    let power = Bezier::from_power_basis(&b.to_power_basis()).unwrap();
    for t in samples(&b, 50) {
        let p = b.de_casteljau(t);
        assert!(close(p, b.bernstein_point(t), 1e-13));
        assert!(close(p, up.de_casteljau(t), 1e-13));
        assert!(close(p, power.de_casteljau(t), 1e-12));
        let q = if t <= 0.3 {
            left.de_casteljau(t / 0.3)
        } else {
            right.de_casteljau((t - 0.3) / 0.7)
        };
        assert!(close(p, q, 1e-13), "split at {t}");
    }
    // Endpoint interpolation and end tangents n (b1 − b0), n (b3 − b2).
    let [p0, d0, _] = b.derivatives(0.0);
    assert_eq!(p0, b.points[0]);
    assert!(close(d0, 3.0 * (b.points[1] - b.points[0]), 1e-14));
}

/// First and second derivatives against central differences.
fn check_derivatives(curve: &dyn Curve, tol: f64) {
    let (a, b) = curve.domain();
    let h = 1e-5 * (b - a);
    for t in samples(curve, 37) {
        let t = t.clamp(a + 2.0 * h, b - 2.0 * h);
        let [_, d1, d2] = curve.derivatives(t);
        let fd1 = (curve.point(t + h) - curve.point(t - h)) / (2.0 * h);
        let fd2 = (curve.point(t + h) - 2.0 * curve.point(t) + curve.point(t - h)) / (h * h);
        assert!(
            close(d1, fd1, tol * (1.0 + d1.length())),
            "p'({t}) = {d1}, differences give {fd1}"
        );
        assert!(
            close(d2, fd2, 1e3 * tol * (1.0 + d2.length())),
            "p''({t}) = {d2}, differences give {fd2}"
        );
    }
}

fn wavy_nurbs() -> NurbsCurve {
    NurbsCurve::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0],
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, -1.0, 0.5),
            DVec3::new(3.0, 0.5, 1.0),
            DVec3::new(4.0, 2.0, 0.0),
            DVec3::new(5.0, 0.0, -1.0),
            DVec3::new(6.0, 1.0, 0.0),
        ],
        vec![1.0, 0.5, 2.0, 1.0, 0.7, 1.5, 1.0],
    )
    .unwrap()
}

#[test]
fn derivatives_match_finite_differences() {
    check_derivatives(&wavy_nurbs(), 1e-6);
    check_derivatives(&NurbsCurve::circle(DVec3::ZERO, 2.0), 1e-6);
    check_derivatives(&bezier(), 1e-6);
    let params = vec![0.0, 0.5, 1.5, 2.0, 3.0];
    let pts = vec![
        DVec3::ZERO,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(2.0, 0.0, 1.0),
        DVec3::new(3.0, 1.0, 1.0),
        DVec3::new(4.0, 0.0, 0.0),
    ];
    check_derivatives(&c2_cubic_spline(params.clone(), pts.clone()).unwrap(), 1e-6);
    check_derivatives(&PowerBasisCurve::interpolate(&params, &pts).unwrap(), 1e-6);
}

#[test]
fn knot_insertion_and_degree_elevation_keep_every_point() {
    let c = wavy_nurbs();
    let mut refined = c.clone();
    for u in [0.1, 0.3, 0.3, 0.77, 0.5] {
        refined = refined.insert_knot(u).unwrap();
    }
    assert_eq!(refined.points().len(), c.points().len() + 5);
    let up = c.elevate_degree().unwrap();
    assert_eq!(up.degree(), 4);
    let twice = up.elevate_degree().unwrap();
    for t in samples(&c, 200) {
        let p = c.point(t);
        assert!(close(p, refined.point(t), 1e-12), "insertion moved {t}");
        assert!(close(p, up.point(t), 1e-12), "elevation moved {t}");
        assert!(
            close(p, twice.point(t), 1e-12),
            "second elevation moved {t}"
        );
    }
    // Multiplicity 3 at 0.5 is full for a cubic.
    let full = refined.insert_knot(0.5).unwrap_err();
    assert!(
        matches!(
            full,
            CurveError::FullMultiplicity {
                multiplicity: 3,
                ..
            }
        ),
        "{full}"
    );
    let outside = c.insert_knot(1.0).unwrap_err();
    assert!(matches!(outside, CurveError::OutsideDomain { .. }));
}

#[test]
fn all_weights_one_is_the_b_spline_and_weights_pull_the_curve() {
    let pts = vec![
        DVec3::ZERO,
        DVec3::new(1.0, 2.0, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(3.0, 2.0, 0.0),
        DVec3::new(4.0, 0.0, 0.0),
    ];
    let b = NurbsCurve::clamped(3, pts.clone()).unwrap();
    assert!(b.is_polynomial());
    // A clamped cubic with 4 points is the Bézier curve of those points.
    let four = NurbsCurve::clamped(3, pts[..4].to_vec()).unwrap();
    let bez = Bezier::new(pts[..4].to_vec()).unwrap();
    for t in samples(&four, 30) {
        assert!(close(four.point(t), bez.point(t), 1e-13));
    }
    // Raising the middle weight moves the curve towards that point.
    let mut heavy = b.clone();
    heavy.set_weight(2, 5.0).unwrap();
    let t = closest_parameter(&b, pts[2]);
    assert!(heavy.point(t).distance(pts[2]) < b.point(t).distance(pts[2]));
    assert_eq!(
        heavy.set_weight(2, 0.0).unwrap_err(),
        CurveError::BadWeight {
            index: 2,
            value: 0.0
        }
    );
    assert!(matches!(
        heavy.set_weight(9, 1.0),
        Err(CurveError::NoSuchPoint { index: 9, count: 5 })
    ));
}

#[test]
fn bad_curve_data_is_refused_by_name() {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    let e = NurbsCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0], p.clone(), vec![1.0; 3]).unwrap_err();
    assert_eq!(
        e,
        CurveError::KnotCount {
            points: 3,
            degree: 2,
            needed: 6,
            got: 5
        }
    );
    let e = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 1.0, 0.5, 1.0, 1.0],
        p.clone(),
        vec![1.0; 3],
    )
    .unwrap_err();
    assert!(matches!(e, CurveError::DecreasingKnots { index: 3, .. }));
    let e = NurbsCurve::new(2, vec![0.0; 6], p.clone(), vec![1.0; 3]).unwrap_err();
    assert_eq!(e, CurveError::EmptyDomain);
    let e = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        p.clone(),
        vec![1.0, -1.0, 1.0],
    )
    .unwrap_err();
    assert!(e.to_string().contains("weights must be positive"), "{e}");
    let e = NurbsCurve::new(3, vec![0.0; 7], p.clone(), vec![1.0; 3]).unwrap_err();
    assert!(matches!(
        e,
        CurveError::TooFewPoints {
            needed: 4,
            got: 3,
            ..
        }
    ));
    let e = NurbsCurve::clamped(2, vec![DVec3::ZERO, DVec3::NAN, DVec3::X]).unwrap_err();
    assert_eq!(
        e,
        CurveError::NotFinite {
            what: "control point",
            index: 1
        }
    );
}

#[test]
fn a_periodic_b_spline_closes_smoothly() {
    let square = vec![
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(-1.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, -1.0),
    ];
    let c = NurbsCurve::periodic(3, square, vec![1.0; 4]).unwrap();
    let (a, b) = c.domain();
    let [p0, d0, s0] = c.derivatives(a);
    let [p1, d1, s1] = c.derivatives(b);
    assert!(
        close(p0, p1, 1e-12) && close(d0, d1, 1e-12) && close(s0, s1, 1e-12),
        "C2 closed"
    );
}

#[test]
fn interpolating_curves_pass_through_their_points() {
    let params = vec![0.0, 1.0, 2.5, 3.0, 4.0];
    let pts = vec![
        DVec3::ZERO,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(2.0, 0.0, 1.0),
        DVec3::new(3.0, 1.0, 1.0),
        DVec3::new(4.0, 0.0, 0.0),
    ];
    let cr = HermiteSpline::catmull_rom(params.clone(), pts.clone()).unwrap();
    let c2 = c2_cubic_spline(params.clone(), pts.clone()).unwrap();
    let lagrange = PowerBasisCurve::interpolate(&params, &pts).unwrap();
    let poly = Polyline::new(params.clone(), pts.clone()).unwrap();
    for (t, p) in params.iter().zip(&pts) {
        for (name, c) in [
            ("Catmull-Rom", &cr as &dyn Curve),
            ("C2", &c2),
            ("Lagrange", &lagrange),
            ("polyline", &poly),
        ] {
            assert!(close(c.point(*t), *p, 1e-10), "{name} misses {p} at {t}");
        }
    }
    // Catmull-Rom's tangent at an inner key: (p2 − p0)/(t2 − t0).
    let want = (pts[2] - pts[0]) / (params[2] - params[0]);
    assert!(close(cr.derivatives(1.0)[1], want, 1e-12));
    // C2: second derivatives agree across inner keys.
    for &t in &params[1..4] {
        let l = c2.derivatives(t - 1e-9)[2];
        let r = c2.derivatives(t + 1e-9)[2];
        assert!(close(l, r, 1e-5), "C2 breaks at {t}: {l} vs {r}");
    }
    // A Catmull-Rom segment as a Bézier curve traces the same points.
    let seg = cr.bezier_segment(1);
    for k in 0..=10 {
        let s = k as f64 / 10.0;
        let t = params[1] + s * (params[2] - params[1]);
        assert!(close(seg.point(s), cr.point(t), 1e-12));
    }
}

#[test]
fn kochanek_bartels_parameters_shape_the_tangents() {
    let params = vec![0.0, 1.0, 2.0];
    let pts = vec![
        DVec3::ZERO,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
    ];
    let zero = [Tbc::default(); 3];
    let kb = HermiteSpline::kochanek_bartels(params.clone(), pts.clone(), &zero).unwrap();
    let cr = HermiteSpline::catmull_rom(params.clone(), pts.clone()).unwrap();
    assert_eq!(kb, cr, "T = B = C = 0 is Catmull-Rom");
    // Tension 1: zero tangent at the middle key.
    let mut keys = zero;
    keys[1].tension = 1.0;
    let tight = HermiteSpline::kochanek_bartels(params.clone(), pts.clone(), &keys).unwrap();
    assert!(tight.derivatives(1.0)[1].length() < 1e-12);
    // Continuity −1: the curve has a corner at the key (incoming ≠ outgoing).
    let mut keys = zero;
    keys[1].continuity = -1.0;
    let corner = HermiteSpline::kochanek_bartels(params, pts, &keys).unwrap();
    let before = corner.derivatives(1.0 - 1e-9)[1];
    let after = corner.derivatives(1.0 + 1e-9)[1];
    assert!(
        !close(before.normalize(), after.normalize(), 1e-3),
        "{before} vs {after}"
    );
}

#[test]
fn chaikin_cuts_corners_towards_the_quadratic_b_spline() {
    let square = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    let once = chaikin(&square, 1, true);
    assert_eq!(once.len(), 8);
    assert!(close(once[0], DVec3::new(0.25, 0.0, 0.0), 1e-15));
    let open = chaikin(&square, 2, false);
    assert_eq!(open[0], square[0]);
    assert_eq!(*open.last().unwrap(), square[3]);
    // Many steps: the closed polygon converges to the quadratic uniform
    // B-spline, which passes through the edge midpoints and, at each
    // corner, through (p_prev + 6 p + p_next) / 8.
    let limit = chaikin(&square, 12, true);
    for want in [DVec3::new(0.5, 0.0, 0.0), DVec3::new(0.125, 0.125, 0.0)] {
        let nearest = limit
            .iter()
            .map(|p| p.distance(want))
            .fold(f64::INFINITY, f64::min);
        assert!(nearest < 1e-3, "{want}: {nearest}");
    }
}

#[test]
fn closest_point_frenet_frame_and_equal_spacing() {
    let c = NurbsCurve::circle(DVec3::ZERO, 2.0);
    // The closest point to (3, 0, 3) is on the diagonal at radius 2.
    let t = closest_parameter(&c, DVec3::new(3.0, 0.0, 3.0));
    assert!(
        close(
            c.point(t),
            DVec3::new(2.0, 0.0, 2.0).normalize() * 2.0,
            1e-9
        ),
        "{}",
        c.point(t)
    );
    let [tangent, normal, binormal] = frenet_frame(&c, t).unwrap();
    assert!(
        close(normal, -c.point(t).normalize(), 1e-9),
        "the normal points at the centre"
    );
    assert!(tangent.dot(normal).abs() < 1e-12 && close(binormal, tangent.cross(normal), 1e-12));
    // A straight line has no Frenet frame.
    let line = Bezier::new(vec![DVec3::ZERO, DVec3::X]).unwrap();
    assert!(frenet_frame(&line, 0.5).is_none());
    // Equal arc length on the wavy curve: equal pieces.
    let w = wavy_nurbs();
    let ts = equal_arc_length_parameters(&w, 6);
    let total = arc_length(&w, 0.0, 1.0);
    for pair in ts.windows(2) {
        assert!((arc_length(&w, pair[0], pair[1]) - total / 5.0).abs() < 1e-9);
    }
}

proptest! {
    /// Random clamped NURBS: knot insertion anywhere never moves the curve.
    #[test]
    fn random_knot_insertions_do_not_move_the_curve(
        coords in proptest::collection::vec(-5.0f64..5.0, 18),
        weights in proptest::collection::vec(0.2f64..4.0, 6),
        degree in 1usize..5,
        inserts in proptest::collection::vec(0.01f64..0.99, 1..6),
    ) {
        let pts: Vec<DVec3> = coords.chunks(3).map(|c| DVec3::new(c[0], c[1], c[2])).collect();
        let knots = hedra_geom::curves::nurbs::clamped_uniform_knots(degree, pts.len());
        let c = NurbsCurve::new(degree, knots, pts, weights).unwrap();
        let mut r = c.clone();
        let mut inserted = 0;
        for &u in &inserts {
            // The one refusal allowed: a knot already `degree` times there
            // (a repeated draw on a degree-1 curve). Anything else fails.
            match r.insert_knot(u) {
                Ok(next) => {
                    r = next;
                    inserted += 1;
                }
                Err(CurveError::FullMultiplicity { multiplicity, .. }) => {
                    prop_assert_eq!(multiplicity, degree);
                }
                Err(e) => prop_assert!(false, "inserting {} failed: {}", u, e),
            }
        }
        // Something was inserted, and it is there: the test compares two
        // different curves, not one with itself.
        prop_assert!(inserted >= 1);
        prop_assert_eq!(r.knots().len(), c.knots().len() + inserted);
        prop_assert_eq!(r.points().len(), c.points().len() + inserted);
        for &u in &inserts {
            prop_assert!(r.knots().contains(&u), "{} not in the knots", u);
        }
        let e = c.elevate_degree().unwrap();
        prop_assert_eq!(e.degree(), degree + 1);
        for t in samples(&c, 40) {
            prop_assert!(close(c.point(t), r.point(t), 1e-10));
            prop_assert!(close(c.point(t), e.point(t), 1e-10));
        }
    }
}

#[test]
fn splitting_a_nurbs_curve_keeps_both_halves_on_it() {
    let c = wavy_nurbs();
    for u in [0.2, 0.3, 0.5, 0.81] {
        let (l, r) = c.split(u).unwrap();
        assert!(l.is_clamped() && r.is_clamped());
        assert_eq!((l.domain(), r.domain()), ((0.0, u), (u, 1.0)));
        for k in 0..=40 {
            let t = k as f64 / 40.0;
            let p = c.point(t);
            let q = if t <= u { l.point(t) } else { r.point(t) };
            assert!(close(p, q, 1e-12), "split at {u}, t = {t}");
        }
    }
    assert!(matches!(
        c.split(1.0),
        Err(CurveError::OutsideDomain { .. })
    ));
}

#[test]
fn quintic_hermite_meets_its_end_conditions() {
    use hedra_geom::curves::interpolating::QuinticHermite;
    let q = QuinticHermite {
        points: [DVec3::ZERO, DVec3::new(3.0, 1.0, 0.0)],
        velocities: [DVec3::new(1.0, 2.0, 0.0), DVec3::new(0.0, -1.0, 1.0)],
        accelerations: [DVec3::new(0.0, 0.0, 4.0), DVec3::new(-2.0, 0.0, 0.0)],
    };
    let [p0, v0, a0] = q.derivatives(0.0);
    let [p1, v1, a1] = q.derivatives(1.0);
    for (got, want) in [
        (p0, q.points[0]),
        (v0, q.velocities[0]),
        (a0, q.accelerations[0]),
        (p1, q.points[1]),
        (v1, q.velocities[1]),
        (a1, q.accelerations[1]),
    ] {
        assert!(close(got, want, 1e-12), "{got} vs {want}");
    }
    check_derivatives(&q, 1e-6);
}

#[test]
fn knot_refinement_inserts_many_knots_and_keeps_the_curve() {
    let c = wavy_nurbs();
    let r = c.refine(&[0.1, 0.2, 0.3, 0.6, 0.9]).unwrap();
    assert_eq!(r.points().len(), c.points().len() + 5);
    for k in 0..=50 {
        let t = k as f64 / 50.0;
        assert!(close(c.point(t), r.point(t), 1e-12));
    }
    assert!(matches!(
        c.refine(&[0.5, 1.5]),
        Err(CurveError::OutsideDomain { .. })
    ));
}

/// Unclamped curves (uniform knots, as other CAD programs make them) can be
/// clamped, elevated and split without changing their shape on the domain
/// (openNURBS elevates them too).
#[test]
fn unclamped_curves_clamp_elevate_and_split_keeping_their_shape() {
    use hedra_geom::curves::{Curve, NurbsCurve};
    let points = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 2.0, 0.0),
        DVec3::new(2.0, -1.0, 1.0),
        DVec3::new(3.0, 2.0, 0.0),
        DVec3::new(4.0, 0.0, -1.0),
        DVec3::new(5.0, 1.0, 0.0),
    ];
    let knots: Vec<f64> = (0..10).map(f64::from).collect();
    let weights = vec![1.0, 2.0, 0.5, 1.0, 3.0, 1.0];
    let curve = NurbsCurve::new(3, knots, points, weights).unwrap();
    assert!(!curve.is_clamped());
    let (a, b) = curve.domain();
    let ts: Vec<f64> = (0..=40).map(|i| a + (b - a) * i as f64 / 40.0).collect();
    let same = |c: &NurbsCurve, what: &str| {
        assert_eq!(c.domain(), (a, b), "{what}");
        for &t in &ts {
            let d = c.point(t).distance(curve.point(t));
            assert!(d < 1e-10, "{what}: off by {d} at {t}");
        }
    };
    let clamped = curve.clamped_ends();
    assert!(clamped.is_clamped());
    same(&clamped, "clamped");
    assert!(
        clamped.points()[0].distance(curve.point(a)) < 1e-12,
        "the end is a control point"
    );
    let elevated = curve.elevate_degree().unwrap();
    assert_eq!(elevated.degree(), 4);
    same(&elevated, "elevated");
    let (left, right) = curve.split(4.5).unwrap();
    for &t in &ts {
        let piece = if t <= 4.5 { &left } else { &right };
        assert!(
            piece.point(t).distance(curve.point(t)) < 1e-10,
            "split at {t}"
        );
    }
}
