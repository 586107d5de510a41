//! Patches from curves and joins between patches (issue 20): the Coons
//! patch, the Gordon surface and seed 002's triangle–quad G1 join.

use hedra_geom::curves::analysis::closest_parameter;
use hedra_geom::surfaces::joins::Boundary;
use hedra_geom::surfaces::patches::{
    CoonsBoundaries, NetworkParams, PatchError, PatchPoint, PointRole, SharedEdge, TriangleQuad,
    coons, coons_report, gordon, gordon_report, unit_domain,
};
use hedra_geom::{BezierSurface, BezierTriangle, Curve, DVec3, NurbsCurve, Surface};

const SQ: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// A 90° circular arc from `a` to `b` bulging towards `side` (a unit
/// vector perpendicular to the chord): degree 2, middle weight √2/2. Its
/// centre and radius.
fn arc(a: DVec3, b: DVec3, side: DVec3) -> (NurbsCurve, DVec3, f64) {
    let half = 0.5 * a.distance(b);
    let mid = 0.5 * (a + b);
    let curve = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![a, mid + half * side, b],
        vec![1.0, SQ, 1.0],
    )
    .unwrap();
    (curve, mid - half * side, half * std::f64::consts::SQRT_2)
}

fn samples(n: usize) -> impl Iterator<Item = f64> {
    (0..=n).map(move |k| k as f64 / n as f64)
}

/// Mixed boundaries: a cubic with an inner knot, a quadratic, a rational
/// arc and a quadratic B-spline with an inner knot.
fn mixed_boundaries() -> (CoonsBoundaries, DVec3, f64) {
    let (p00, p10, p01, p11) = (
        DVec3::ZERO,
        DVec3::new(3.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 3.0),
        DVec3::new(3.0, 0.0, 3.0),
    );
    let v0 = NurbsCurve::clamped(
        3,
        vec![
            p00,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(1.5, -1.0, 0.2),
            DVec3::new(2.0, 0.5, 0.0),
            p10,
        ],
    )
    .unwrap();
    let v1 = NurbsCurve::clamped(2, vec![p01, DVec3::new(1.5, 2.0, 3.5), p11]).unwrap();
    let (u0, centre, radius) = arc(p00, p01, DVec3::Y);
    let u1 = NurbsCurve::clamped(
        2,
        vec![
            p10,
            DVec3::new(4.0, 1.0, 1.0),
            DVec3::new(3.5, -1.0, 2.0),
            p11,
        ],
    )
    .unwrap();
    (CoonsBoundaries { v0, v1, u0, u1 }, centre, radius)
}

#[test]
fn a_coons_patch_interpolates_its_four_boundaries() {
    let (b, centre, radius) = mixed_boundaries();
    let s = coons(&b, 1e-12).unwrap();
    assert_eq!(
        s.degrees(),
        (3, 2),
        "the highest degree of each opposite pair"
    );
    for t in samples(1000) {
        assert!(
            s.point(t, 0.0).distance(b.v0.point(t)) < 1e-12,
            "v = 0 at {t}"
        );
        assert!(
            s.point(t, 1.0).distance(b.v1.point(t)) < 1e-12,
            "v = 1 at {t}"
        );
        assert!(
            s.point(0.0, t).distance(b.u0.point(t)) < 1e-12,
            "u = 0 at {t}"
        );
        assert!(
            s.point(1.0, t).distance(b.u1.point(t)) < 1e-12,
            "u = 1 at {t}"
        );
        // The arc stays exactly circular on the patch.
        assert!((s.point(0.0, t).distance(centre) - radius).abs() < 1e-12);
    }
    let report = coons_report(&b, &s, 1000).unwrap();
    assert!(report.max_boundary_gap < 1e-12, "{report:?}");
    assert_eq!(report.corner_gaps, [0.0; 4]);
    assert_eq!(report.size, s.size());
}

#[test]
fn a_polynomial_coons_patch_is_the_coons_formula_inside() {
    let line = |a: DVec3, b: DVec3, bump: DVec3| {
        NurbsCurve::clamped(
            3,
            vec![
                a,
                a + (b - a) / 3.0 + bump,
                a + 2.0 * (b - a) / 3.0 - bump,
                b,
            ],
        )
        .unwrap()
    };
    let (p00, p10, p01, p11) = (
        DVec3::ZERO,
        DVec3::new(2.0, 0.3, 0.0),
        DVec3::new(0.0, -0.2, 2.0),
        DVec3::new(2.0, 0.5, 2.0),
    );
    let b = CoonsBoundaries {
        v0: line(p00, p10, DVec3::Y),
        v1: NurbsCurve::clamped(
            2,
            vec![
                p01,
                DVec3::new(1.0, 1.0, 2.5),
                DVec3::new(1.5, 0.0, 2.0),
                p11,
            ],
        )
        .unwrap(),
        u0: line(p00, p01, DVec3::new(0.5, 0.0, 0.0)),
        u1: NurbsCurve::clamped(1, vec![p10, p11]).unwrap(),
    };
    let s = coons(&b, 1e-12).unwrap();
    for u in samples(20) {
        for v in samples(20) {
            let bilinear = (1.0 - u) * (1.0 - v) * p00
                + u * (1.0 - v) * p10
                + (1.0 - u) * v * p01
                + u * v * p11;
            let expected = (1.0 - v) * b.v0.point(u)
                + v * b.v1.point(u)
                + (1.0 - u) * b.u0.point(v)
                + u * b.u1.point(v)
                - bilinear;
            assert!(s.point(u, v).distance(expected) < 1e-12, "({u}, {v})");
        }
    }
}

#[test]
fn a_planar_boundary_gives_a_planar_patch() {
    // Curves in the plane n·x = 1, one of them a rational arc.
    let n = DVec3::new(1.0, 2.0, 2.0) / 3.0;
    let (e1, e2) = (
        DVec3::new(2.0, -1.0, 0.0).normalize(),
        DVec3::new(2.0, -1.0, 0.0).normalize().cross(n),
    );
    let at = |x: f64, y: f64| n + x * e1 + y * e2;
    let (p00, p10, p01, p11) = (at(0.0, 0.0), at(2.0, 0.0), at(0.0, 2.0), at(2.5, 2.2));
    let (v0, _, _) = arc(p00, p10, -e2);
    let b = CoonsBoundaries {
        v0,
        v1: NurbsCurve::clamped(3, vec![p01, at(0.5, 3.0), at(1.5, 1.5), at(2.0, 2.5), p11])
            .unwrap(),
        u0: NurbsCurve::clamped(2, vec![p00, at(-0.3, 1.0), p01]).unwrap(),
        u1: NurbsCurve::clamped(1, vec![p10, p11]).unwrap(),
    };
    let s = coons(&b, 1e-12).unwrap();
    for p in s.points() {
        assert!(
            (p.dot(n) - 1.0).abs() < 1e-12,
            "control point {p} off the plane"
        );
    }
    for u in samples(30) {
        for v in samples(30) {
            let e = s.evaluate(u, v);
            assert!((e.p.dot(n) - 1.0).abs() < 1e-12, "({u}, {v}) off the plane");
            assert!(e.normal().cross(n).length() < 1e-9, "normal at ({u}, {v})");
        }
    }
}

#[test]
fn circle_arc_boundaries_stay_circles_and_unequal_end_weights_are_handled() {
    let (p00, p10, p01, p11) = (DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0));
    let (v0, c0, r0) = arc(p00, p10, DVec3::Z);
    let (v1, c1, r1) = arc(p01, p11, -DVec3::Z);
    let (u0, c2, r2) = arc(p00, p01, DVec3::new(-SQ, 0.0, SQ));
    let (u1, c3, r3) = arc(p10, p11, DVec3::new(SQ, 0.0, SQ));
    let b = CoonsBoundaries { v0, v1, u0, u1 };
    let s = coons(&b, 1e-12).unwrap();
    assert!(s.weights().iter().any(|&w| w != 1.0), "a rational patch");
    for t in samples(1000) {
        for (p, c, r) in [
            (s.point(t, 0.0), c0, r0),
            (s.point(t, 1.0), c1, r1),
            (s.point(0.0, t), c2, r2),
            (s.point(1.0, t), c3, r3),
        ] {
            assert!(
                (p.distance(c) - r).abs() < 1e-12,
                "{p} at {t} is off its circle"
            );
        }
        assert!(s.point(t, 0.0).distance(b.v0.point(t)) < 1e-12);
    }
    // A rational side whose end weights differ (2 and 0.5), on a domain
    // other than [0, 1]: the patch follows the same point set, through the
    // curve's normalised parameterisation.
    let odd = NurbsCurve::new(
        2,
        vec![1.0, 1.0, 1.0, 2.0, 3.0, 3.0, 3.0],
        vec![
            p10,
            DVec3::new(1.5, 0.3, 0.4),
            DVec3::new(1.2, 0.8, -0.3),
            p11,
        ],
        vec![2.0, 0.7, 1.3, 0.5],
    )
    .unwrap();
    let b = CoonsBoundaries {
        u1: odd.clone(),
        ..b
    };
    let s = coons(&b, 1e-12).unwrap();
    let normalized = b.normalized().unwrap();
    assert_eq!(normalized[3].weights()[0], 1.0);
    assert!((normalized[3].weights()[3] - 1.0).abs() < 1e-12);
    for t in samples(1000) {
        let p = s.point(1.0, t);
        assert!(p.distance(normalized[3].point(t)) < 1e-12);
        let nearest = odd.point(closest_parameter(&odd, p));
        assert!(
            p.distance(nearest) < 1e-10,
            "{p} is off the curve by {}",
            p.distance(nearest)
        );
    }
    assert!(coons_report(&b, &s, 200).unwrap().max_boundary_gap < 1e-12);
}

#[test]
fn coons_refuses_boundaries_that_miss_a_corner_by_name() {
    let (mut b, _, _) = mixed_boundaries();
    let mut pts = b.u1.points().to_vec();
    let last = pts.len() - 1;
    pts[last] += DVec3::new(0.0, 0.25, 0.0);
    b.u1 = NurbsCurve::clamped(2, pts).unwrap();
    let err = coons(&b, 1e-9).unwrap_err();
    assert_eq!(
        err,
        PatchError::CornerGap {
            corner: "(u=1, v=1)",
            gap: 0.25,
            tolerance: 1e-9
        }
    );
    assert!(
        err.to_string().contains("corner (u=1, v=1): gap 0.25"),
        "{err}"
    );
}

#[test]
fn four_curves_in_any_order_and_direction_make_the_same_patch() {
    let (b, _, _) = mixed_boundaries();
    let reverse = |c: &NurbsCurve| {
        let c = unit_domain(c).unwrap();
        NurbsCurve::new(
            c.degree(),
            c.knots().iter().rev().map(|k| 1.0 - k).collect(),
            c.points().iter().rev().copied().collect(),
            c.weights().iter().rev().copied().collect(),
        )
        .unwrap()
    };
    let shuffled = [b.v0.clone(), reverse(&b.v1), b.u1.clone(), reverse(&b.u0)];
    let again = CoonsBoundaries::from_loop(shuffled, 1e-12).unwrap();
    let (s, t) = (coons(&b, 1e-12).unwrap(), coons(&again, 1e-12).unwrap());
    for u in samples(10) {
        for v in samples(10) {
            assert!(s.point(u, v).distance(t.point(u, v)) < 1e-12);
        }
    }
    let apart = [
        b.v0.clone(),
        b.v1.clone(),
        b.u0.clone(),
        NurbsCurve::clamped(1, vec![DVec3::splat(9.0), DVec3::splat(10.0)]).unwrap(),
    ];
    assert!(matches!(
        CoonsBoundaries::from_loop(apart, 1e-9),
        Err(PatchError::NotALoop { .. })
    ));
}

/// A bicubic Bézier surface to cut iso-curves from.
fn reference_net() -> Vec<DVec3> {
    let mut net = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let (x, z) = (i as f64, j as f64);
            let y = ((i * 7 + j * 3) % 5) as f64 * 0.3 - 0.5 + 0.1 * x * z;
            net.push(DVec3::new(x + 0.2 * z, y, z - 0.1 * x));
        }
    }
    net
}

fn bernstein3(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t]
}

/// The iso-curve `F(u, v)` at fixed v (a u-curve) or fixed u.
fn iso(net: &[DVec3], at: f64, fixed_v: bool) -> NurbsCurve {
    let b = bernstein3(at);
    let pts = (0..4)
        .map(|a| {
            (0..4)
                .map(|c| {
                    let (i, j) = if fixed_v { (a, c) } else { (c, a) };
                    b[c] * net[i * 4 + j]
                })
                .sum()
        })
        .collect();
    NurbsCurve::clamped(3, pts).unwrap()
}

fn bicubic(net: &[DVec3], u: f64, v: f64) -> DVec3 {
    let (bu, bv) = (bernstein3(u), bernstein3(v));
    let mut p = DVec3::ZERO;
    for i in 0..4 {
        for j in 0..4 {
            p += bu[i] * bv[j] * net[i * 4 + j];
        }
    }
    p
}

#[test]
fn a_gordon_surface_interpolates_every_network_curve() {
    let net = reference_net();
    let vs = [0.0, 0.3, 0.65, 1.0];
    let us = [0.0, 0.4, 1.0];
    // Different representations of the same curves: elevated, refined.
    let mut u_curves: Vec<NurbsCurve> = vs.iter().map(|&v| iso(&net, v, true)).collect();
    u_curves[1] = u_curves[1].elevate_degree().unwrap();
    u_curves[2] = u_curves[2].refine(&[0.25, 0.7]).unwrap();
    let mut v_curves: Vec<NurbsCurve> = us.iter().map(|&u| iso(&net, u, false)).collect();
    v_curves[0] = v_curves[0]
        .elevate_degree()
        .unwrap()
        .refine(&[0.5])
        .unwrap();
    let given = NetworkParams {
        u: us.to_vec(),
        v: vs.to_vec(),
    };
    let g = gordon(&u_curves, &v_curves, Some(&given), 1e-9).unwrap();
    for t in samples(1000) {
        for (c, &v) in u_curves.iter().zip(&vs) {
            assert!(
                g.surface.point(t, v).distance(c.point(t)) < 1e-12,
                "u-curve at v = {v}, u = {t}"
            );
        }
        for (d, &u) in v_curves.iter().zip(&us) {
            assert!(
                g.surface.point(u, t).distance(d.point(t)) < 1e-12,
                "v-curve at u = {u}, v = {t}"
            );
        }
    }
    let report = gordon_report(&g, 1000);
    assert!(
        report.max_curve_gap < 1e-12 && report.max_crossing_gap < 1e-12,
        "{report:?}"
    );
    // Found crossings agree with the given ones.
    let found = gordon(&u_curves, &v_curves, None, 1e-9).unwrap();
    for (a, b) in found
        .params
        .u
        .iter()
        .zip(&us)
        .chain(found.params.v.iter().zip(&vs))
    {
        assert!((a - b).abs() < 1e-9, "{:?}", found.params);
    }
    assert_eq!(found.u_order, vec![0, 1, 2, 3]);
    assert!(gordon_report(&found, 200).max_curve_gap < 1e-9);
}

#[test]
fn a_four_by_four_network_of_a_bicubic_gives_the_bicubic_back() {
    let net = reference_net();
    let ps = [0.0, 0.35, 0.7, 1.0];
    let u_curves: Vec<NurbsCurve> = ps.iter().map(|&v| iso(&net, v, true)).collect();
    let v_curves: Vec<NurbsCurve> = ps.iter().map(|&u| iso(&net, u, false)).collect();
    let params = NetworkParams {
        u: ps.to_vec(),
        v: ps.to_vec(),
    };
    let g = gordon(&u_curves, &v_curves, Some(&params), 1e-9).unwrap();
    for u in samples(25) {
        for v in samples(25) {
            assert!(
                g.surface.point(u, v).distance(bicubic(&net, u, v)) < 1e-11,
                "({u}, {v})"
            );
        }
    }
}

#[test]
fn gordon_finds_the_order_and_direction_of_shuffled_curves() {
    let net = reference_net();
    let vs = [0.0, 0.5, 1.0];
    let us = [0.1, 0.45, 0.8];
    let reverse = |c: &NurbsCurve| {
        NurbsCurve::new(
            c.degree(),
            c.knots().iter().rev().map(|k| 1.0 - k).collect(),
            c.points().iter().rev().copied().collect(),
            c.weights().to_vec(),
        )
        .unwrap()
    };
    let u_curves = vec![
        iso(&net, vs[1], true),
        reverse(&iso(&net, vs[0], true)),
        iso(&net, vs[2], true),
    ];
    let v_curves = vec![
        iso(&net, us[2], false),
        iso(&net, us[0], false),
        reverse(&iso(&net, us[1], false)),
    ];
    let g = gordon(&u_curves, &v_curves, None, 1e-9).unwrap();
    assert_eq!(g.u_order, vec![1, 0, 2]);
    assert_eq!(g.v_order, vec![1, 2, 0]);
    assert_eq!(g.u_reversed, vec![false, true, false]);
    assert_eq!(g.v_reversed, vec![false, false, true]);
    for (a, b) in g.params.u.iter().zip(&us) {
        assert!((a - b).abs() < 1e-9);
    }
    let report = gordon_report(&g, 500);
    assert!(report.max_curve_gap < 1e-9, "{report:?}");
    // The network's curves lie on the surface, as given.
    for t in samples(100) {
        let p = u_curves[1].point(t);
        let q = g.surface.point(1.0 - t, g.params.v[0]);
        assert!(p.distance(q) < 1e-9);
    }
}

#[test]
fn gordon_refuses_an_inconsistent_network_by_name() {
    let net = reference_net();
    let vs = [0.0, 0.5, 1.0];
    let us = [0.0, 0.5, 1.0];
    let u_curves: Vec<NurbsCurve> = vs.iter().map(|&v| iso(&net, v, true)).collect();
    let mut v_curves: Vec<NurbsCurve> = us.iter().map(|&u| iso(&net, u, false)).collect();
    // Lift the middle v-curve off the network.
    let lifted: Vec<DVec3> = v_curves[1]
        .points()
        .iter()
        .map(|p| *p + DVec3::new(0.0, 0.05, 0.0))
        .collect();
    v_curves[1] = NurbsCurve::clamped(3, lifted).unwrap();
    let params = NetworkParams {
        u: us.to_vec(),
        v: vs.to_vec(),
    };
    match gordon(&u_curves, &v_curves, Some(&params), 1e-6).unwrap_err() {
        PatchError::NetworkGap {
            u_curve,
            v_curve,
            gap,
            ..
        } => {
            assert_eq!((u_curve, v_curve), (0, 1));
            assert!((gap - 0.05).abs() < 1e-12, "{gap}");
        }
        other => panic!("{other}"),
    }
    let err = gordon(&u_curves, &v_curves, None, 1e-6).unwrap_err();
    assert!(
        matches!(
            err,
            PatchError::CurvesDoNotMeet {
                u_curve: 0,
                v_curve: 1,
                ..
            }
        ),
        "{err}"
    );
    assert!(
        err.to_string()
            .contains("u-curve 0 and v-curve 1 do not meet"),
        "{err}"
    );
    // Wrong counts and orders of given parameters, too few curves.
    let bad = NetworkParams {
        u: vec![0.0, 1.0],
        v: vs.to_vec(),
    };
    assert!(matches!(
        gordon(&u_curves, &v_curves, Some(&bad), 1e-6),
        Err(PatchError::ParameterCount {
            direction: "u",
            curves: 3,
            got: 2
        })
    ));
    let bad = NetworkParams {
        u: vec![0.0, 0.6, 0.5],
        v: vs.to_vec(),
    };
    assert!(matches!(
        gordon(&u_curves, &v_curves, Some(&bad), 1e-6),
        Err(PatchError::ParametersOutOfOrder {
            direction: "u",
            index: 2,
            ..
        })
    ));
    assert!(matches!(
        gordon(&u_curves[..1], &v_curves, None, 1e-6),
        Err(PatchError::TooFewCurves {
            direction: "u",
            got: 1
        })
    ));
}

#[test]
fn a_network_of_circles_and_lines_gives_an_exact_cylinder() {
    let circles: Vec<NurbsCurve> = [0.0, 1.0, 2.5]
        .iter()
        .map(|&y| NurbsCurve::circle(DVec3::new(0.0, y, 0.0), 2.0))
        .collect();
    let us = [0.0, 0.25, 0.5, 0.75, 1.0];
    let lines: Vec<NurbsCurve> = us
        .iter()
        .map(|&u| {
            let p = circles[0].point(u);
            NurbsCurve::clamped(1, vec![p, p + DVec3::new(0.0, 2.5, 0.0)]).unwrap()
        })
        .collect();
    let params = NetworkParams {
        u: us.to_vec(),
        v: vec![0.0, 0.4, 1.0],
    };
    let g = gordon(&circles, &lines, Some(&params), 1e-12).unwrap();
    for u in samples(100) {
        for v in samples(20) {
            let p = g.surface.point(u, v);
            assert!((p.x.hypot(p.z) - 2.0).abs() < 1e-12, "({u}, {v}): {p}");
            assert!((p.y - 2.5 * v).abs() < 1e-12, "({u}, {v}): {p}");
        }
    }
    // Lines crossing where the circles' weight is not 1 cannot be blended
    // in homogeneous space.
    let mut lines = lines;
    let p = circles[0].point(0.1);
    lines[1] = NurbsCurve::clamped(1, vec![p, p + DVec3::new(0.0, 2.5, 0.0)]).unwrap();
    let params = NetworkParams {
        u: vec![0.0, 0.1, 0.5, 0.75, 1.0],
        v: vec![0.0, 0.4, 1.0],
    };
    assert!(matches!(
        gordon(&circles, &lines, Some(&params), 1e-12),
        Err(PatchError::WeightsDisagree {
            u_curve: 0,
            v_curve: 1,
            ..
        })
    ));
}

/// A deterministic pseudo-random sequence in [−1, 1).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    fn vec(&mut self) -> DVec3 {
        DVec3::new(self.next(), self.next(), self.next())
    }
}

/// A cubic Bézier triangle with corners (0,0,0) (w), (0,0,2) (v), (−2,0,1) (u),
/// bumpy, and a bi-quadratic patch on the other side of its edge u = 0
/// (x = 0), whose side V1 runs from (0,0,2) to (0,0,0) (reversed).
fn pair() -> (BezierTriangle, BezierSurface) {
    let mut rng = Lcg(7);
    let n = 3;
    let (cu, cv, cw) = (
        DVec3::new(-2.0, 0.0, 1.0),
        DVec3::new(0.0, 0.0, 2.0),
        DVec3::ZERO,
    );
    let mut points = Vec::new();
    for i in 0..=n {
        for j in 0..=n - i {
            let k = n - i - j;
            let p = (i as f64 * cu + j as f64 * cv + k as f64 * cw) / n as f64;
            let corner = i == n || j == n || k == n;
            points.push(if corner { p } else { p + 0.3 * rng.vec() });
        }
    }
    let triangle = BezierTriangle::new(n, points).unwrap();
    // The quad: u across x from 2 to 0 (side V1 is x = 0 … no: j is across).
    let mut quad = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            // i along the edge (z from 2 down to 0), j across (x from 2 to 0).
            let z = 2.0 - i as f64;
            let x = 2.0 - j as f64;
            quad.push(
                DVec3::new(x, 0.2 * (x * z).sin(), z)
                    + if j == 2 { DVec3::ZERO } else { 0.2 * rng.vec() },
            );
        }
    }
    (triangle, BezierSurface::new(3, 3, quad).unwrap())
}

#[test]
fn the_shared_edge_is_found_and_make_g1_makes_the_normals_agree() {
    let (triangle, quad) = pair();
    let pair = TriangleQuad::new(triangle.clone(), quad, 1e-9).unwrap();
    assert_eq!(
        pair.edge,
        SharedEdge {
            triangle: Boundary::TriangleU0,
            quad: Boundary::V1,
            reversed: true
        }
    );
    let c0 = pair.make_c0().unwrap();
    assert_eq!(
        c0.quad.nu, 4,
        "the patch is elevated to the triangle's degree along the edge"
    );
    assert_eq!(c0.triangle, triangle, "the triangle does not change");
    let r = c0.report(99);
    assert!(r.max_gap < 1e-12, "{r:?}");
    assert!(r.max_normal_angle > 1e-3, "not G1 yet: {r:?}");
    let g1 = pair.make_g1().unwrap();
    let r = g1.report(99);
    assert_eq!(r.samples, 100);
    assert!(r.max_gap < 1e-12 && r.max_normal_angle < 1e-9, "{r:?}");
    // Only the patch's two rows at the edge changed.
    for (k, (a, b)) in c0.quad.points.iter().zip(&g1.quad.points).enumerate() {
        if a != b {
            assert_eq!(g1.role(PatchPoint::Quad(k)), PointRole::Dependent);
        }
    }
    // Make G1 twice is Make G1 once.
    let again = g1.make_g1().unwrap();
    for (a, b) in again.quad.points.iter().zip(&g1.quad.points) {
        assert!(a.distance(*b) < 1e-12);
    }
    // The existing sampled check agrees.
    use hedra_geom::surfaces::joins::{join, surface_boundary, triangle_boundary};
    let j = join(
        |t| triangle_boundary(&g1.triangle, Boundary::TriangleU0, false, t),
        |t| surface_boundary(&g1.quad, Boundary::V1, true, t),
        64,
        1e-12,
        1e-7,
    );
    assert!(j.c0 && j.g1, "{j:?}");
}

#[test]
fn a_patch_of_higher_degree_elevates_the_triangle() {
    // The seed's test configuration with a quartic patch edge.
    let mut quad = Vec::new();
    for i in 0..2 {
        for j in 0..5 {
            quad.push(DVec3::new(
                i as f64,
                0.1 * (j as f64).powi(2) * (1.0 - i as f64),
                j as f64 / 4.0,
            ));
        }
    }
    let quad = BezierSurface::new(2, 5, quad).unwrap();
    let triangle = BezierTriangle::new(
        2,
        vec![
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 0.3, 0.5),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(1.5, 0.3, 0.25),
            DVec3::new(1.5, -0.2, 0.75),
            DVec3::new(2.0, 0.0, 0.5),
        ],
    )
    .unwrap();
    let pair = TriangleQuad::new(triangle, quad, 1e-12).unwrap();
    assert_eq!(pair.edge.quad, Boundary::U1);
    let g1 = pair.make_g1().unwrap();
    assert_eq!(g1.triangle.degree, 4);
    let r = g1.report(99);
    assert!(r.max_gap < 1e-12 && r.max_normal_angle < 1e-9, "{r:?}");
    // Across-degree 1: the "next row" is the patch's far side.
    assert_eq!(
        g1.roles()
            .iter()
            .filter(|(_, r)| *r == PointRole::Dependent)
            .count(),
        5
    );
}

#[test]
fn the_join_stays_g1_while_points_are_dragged() {
    let (triangle, quad) = pair();
    let mut pair = TriangleQuad::new(triangle, quad, 1e-9)
        .unwrap()
        .make_g1()
        .unwrap();
    let roles = pair.roles();
    let count = |role| roles.iter().filter(|(_, r)| *r == role).count();
    assert_eq!(
        (count(PointRole::Shared), count(PointRole::Dependent)),
        (8, 4)
    );
    assert_eq!(count(PointRole::Free), 10 + 12 - 8 - 4);
    let mut rng = Lcg(42);
    let mut kinds = [0usize; 3];
    for step in 0..300 {
        let (point, role) =
            roles[((rng.next() + 1.0) * 0.5 * roles.len() as f64) as usize % roles.len()];
        let to = pair.position(point).unwrap() + 0.1 * rng.vec();
        let (next, changed) = match pair.move_point(point, to) {
            Ok(x) => x,
            Err(PatchError::DegenerateEdge) => continue,
            Err(e) => panic!("{e}"),
        };
        kinds[role as usize] += 1;
        assert_eq!(changed[0], point);
        match role {
            PointRole::Free | PointRole::Shared => {
                assert_eq!(
                    next.position(point).unwrap(),
                    to,
                    "step {step}: {point:?} goes where dragged"
                )
            }
            PointRole::Dependent => {}
        }
        for p in &changed[1..] {
            let r = next.role(*p);
            assert!(
                r != PointRole::Free,
                "step {step}: a free point {p:?} followed a drag of {point:?}"
            );
        }
        if let (PatchPoint::Quad(_), PointRole::Free) = (point, role) {
            assert_eq!(changed.len(), 1, "a free patch point moves alone");
        }
        let r = next.report(99);
        assert!(r.max_gap < 1e-12, "step {step}: {r:?}");
        assert!(
            r.max_normal_angle < 1e-9,
            "step {step} ({point:?}, {role:?}): {r:?}"
        );
        pair = next;
    }
    assert!(
        kinds.iter().all(|&k| k > 20),
        "every role was dragged: {kinds:?}"
    );
}

#[test]
fn a_dragged_dependent_point_goes_to_the_nearest_place_that_keeps_g1() {
    let (triangle, quad) = pair();
    let pair = TriangleQuad::new(triangle, quad, 1e-9)
        .unwrap()
        .make_g1()
        .unwrap();
    let dependent = pair
        .roles()
        .into_iter()
        .find(|(_, r)| *r == PointRole::Dependent)
        .map(|(p, _)| p)
        .unwrap();
    let from = pair.position(dependent).unwrap();
    // Further from the edge, across it: λ grows, the point follows closely.
    let to = from + DVec3::new(0.3, 0.0, 0.0);
    let (next, changed) = pair.move_point(dependent, to).unwrap();
    let landed = next.position(dependent).unwrap();
    assert!(landed.distance(to) < 0.3 * 0.5, "{landed} vs {to}");
    assert!(landed.distance(from) > 0.1);
    assert!(changed.len() > 1, "the rest of the row follows");
    assert!(next.report(99).max_normal_angle < 1e-9);
}

#[test]
fn patches_that_share_no_edge_are_refused_by_name() {
    let (triangle, quad) = pair();
    let far = BezierSurface::new(
        3,
        3,
        quad.points
            .iter()
            .map(|p| *p + DVec3::new(5.0, 0.0, 0.0))
            .collect(),
    )
    .unwrap();
    let err = TriangleQuad::new(triangle.clone(), far, 1e-9).unwrap_err();
    assert!(matches!(err, PatchError::NoSharedEdge { .. }), "{err}");
    assert!(
        err.to_string()
            .starts_with("the triangle and the patch share no edge"),
        "{err}"
    );
    let wrong = SharedEdge {
        triangle: Boundary::U0,
        quad: Boundary::V1,
        reversed: true,
    };
    assert_eq!(
        TriangleQuad::with_edge(triangle.clone(), quad.clone(), wrong, 1e-9).unwrap_err(),
        PatchError::NotAnEdge {
            boundary: Boundary::U0,
            patch: "triangle"
        }
    );
    let apart = SharedEdge {
        triangle: Boundary::TriangleV0,
        quad: Boundary::V1,
        reversed: true,
    };
    assert!(matches!(
        TriangleQuad::with_edge(triangle.clone(), quad.clone(), apart, 1e-9),
        Err(PatchError::EdgeEndsApart { .. })
    ));
    let pair = TriangleQuad::new(triangle, quad, 1e-9).unwrap();
    assert_eq!(
        pair.move_point(PatchPoint::Quad(0), DVec3::ZERO)
            .unwrap_err(),
        PatchError::NotJoined {
            triangle: 3,
            quad: 2
        }
    );
    let g1 = pair.make_g1().unwrap();
    assert_eq!(
        g1.move_point(PatchPoint::Triangle(99), DVec3::ZERO)
            .unwrap_err(),
        PatchError::NoSuchPoint {
            patch: "triangle",
            index: 99,
            count: 10
        }
    );
    assert_eq!(
        g1.move_point(PatchPoint::Quad(0), DVec3::NAN).unwrap_err(),
        PatchError::NotFinite
    );
}
