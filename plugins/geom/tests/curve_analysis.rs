//! Analysis of every curve kind: the continuity measured at each joint is
//! what the kind promises, seed 003's Bézier ↔ power-basis matrices, the
//! convex hull of each Bézier segment's control polygon holds the segment,
//! and the arc length of spans.

use glam::DVec3;
use hedra_geom::curves::analysis::arc_length;
use hedra_geom::curves::bezier::{
    PowerBasisSegment, bernstein_to_power_matrix, power_basis_segments, power_to_bernstein_matrix,
};
use hedra_geom::curves::hull::{ControlHull, segment_hulls};
use hedra_geom::curves::interpolating::Tbc;
use hedra_geom::curves::joints::{Joint, JointTolerance, both_sides};
use hedra_geom::curves::spans::{curve_length, span_length};
use hedra_geom::curves::{
    Bezier, CatmullRom, Chaikin, CubicHermite, CubicSpline, Curve, CurveError, CurveKind, Fractal,
    FractalRule, Join, KochanekBartels, Lagrange, NurbsCurve, Parameterization, PolyBezier,
    QuinticHermite, SplineEnds,
};

fn pts() -> Vec<DVec3> {
    vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 2.0, 0.5),
        DVec3::new(3.0, 2.5, -0.5),
        DVec3::new(4.0, 0.5, 0.0),
        DVec3::new(6.0, 1.0, 1.0),
    ]
}

fn keys() -> Vec<Tbc> {
    vec![
        Tbc::default(),
        Tbc {
            tension: 0.3,
            bias: -0.2,
            continuity: 0.4,
        },
        Tbc {
            tension: -0.5,
            bias: 0.5,
            continuity: 0.0,
        },
        Tbc {
            tension: 0.0,
            bias: 0.0,
            continuity: -0.6,
        },
        Tbc::default(),
    ]
}

/// A poly-Bézier of four segments: joint 0 C1, joint 1 G1 with handles of
/// different lengths, joint 2 a C0 corner.
fn poly_bezier(closed: bool) -> CurveKind {
    let mut points = vec![
        DVec3::ZERO,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(2.0, 1.0, 0.0),
        DVec3::new(3.0, 0.0, 0.0),
        DVec3::new(4.0, -1.0, 0.0),
        DVec3::new(5.0, -1.0, 0.5),
        DVec3::new(6.0, 0.0, 0.0),
        DVec3::new(6.5, 2.0, 0.0),
        DVec3::new(8.0, 2.0, 1.0),
        DVec3::new(9.0, 0.0, 0.0),
        DVec3::new(9.0, -2.0, 0.0),
        DVec3::new(11.0, -1.0, 0.0),
        DVec3::new(12.0, 1.0, 0.0),
    ];
    let mut joins = vec![Join::C1, Join::G1, Join::C0];
    if closed {
        // Back to the start: the closing joint (joint 0 of a closed chain)
        // is G1.
        points.extend([DVec3::new(13.0, 3.0, 0.0), DVec3::new(-1.0, -2.0, 0.0)]);
        joins.insert(0, Join::G1);
        joins.push(Join::C1);
    }
    let mut c = CurveKind::PolyBezier(PolyBezier {
        points,
        joins: joins.clone(),
        closed,
    });
    for (j, &join) in joins.iter().enumerate() {
        c = c.set_join(j, join).unwrap();
    }
    c
}

fn every_kind() -> Vec<CurveKind> {
    let p = pts();
    let tangents: Vec<DVec3> = (0..5)
        .map(|i| DVec3::new(1.0, (i as f64).sin(), 0.2))
        .collect();
    let mut out = vec![
        CurveKind::Nurbs(NurbsCurve::clamped(3, p.clone()).unwrap()),
        CurveKind::Nurbs(NurbsCurve::circle(DVec3::new(1.0, 0.0, -2.0), 2.5)),
        CurveKind::CubicHermite(CubicHermite {
            points: p.clone(),
            tangents: tangents.clone(),
        }),
        CurveKind::QuinticHermite(QuinticHermite {
            points: p.clone(),
            tangents: tangents.clone(),
            accelerations: tangents.iter().map(|t| t.cross(DVec3::Y)).collect(),
        }),
        CurveKind::KochanekBartels(KochanekBartels {
            points: p.clone(),
            keys: keys(),
            closed: false,
        }),
        CurveKind::KochanekBartels(KochanekBartels {
            points: p.clone(),
            keys: keys(),
            closed: true,
        }),
        CurveKind::CubicSpline(CubicSpline {
            points: p.clone(),
            parameterization: Parameterization::Chord,
            ends: SplineEnds::Clamped {
                start: DVec3::X,
                end: DVec3::Y,
            },
        }),
        CurveKind::Chaikin(Chaikin {
            points: p.clone(),
            level: 3,
            closed: false,
        }),
        CurveKind::Chaikin(Chaikin {
            points: p.clone(),
            level: 2,
            closed: true,
        }),
        poly_bezier(false),
        poly_bezier(true),
        CurveKind::Fractal(Fractal {
            rule: FractalRule::Koch,
            points: vec![DVec3::ZERO, DVec3::X],
            level: 3,
            closed: false,
            normal: DVec3::Z,
        }),
        CurveKind::Fractal(Fractal {
            rule: FractalRule::QuadraticKoch,
            points: vec![DVec3::ZERO, DVec3::new(0.5, 0.8, 0.0), DVec3::X],
            level: 2,
            closed: true,
            normal: DVec3::Z,
        }),
    ];
    for param in [
        Parameterization::Uniform,
        Parameterization::Chord,
        Parameterization::Centripetal,
    ] {
        out.push(CurveKind::Lagrange(Lagrange {
            points: p.clone(),
            parameterization: param,
        }));
        for closed in [false, true] {
            out.push(CurveKind::CatmullRom(CatmullRom {
                points: p.clone(),
                parameterization: param,
                closed,
            }));
        }
        for ends in [SplineEnds::Natural, SplineEnds::Closed] {
            out.push(CurveKind::CubicSpline(CubicSpline {
                points: p.clone(),
                parameterization: param,
                ends,
            }));
        }
    }
    out
}

fn joints_of(kind: &CurveKind) -> Vec<Joint> {
    let form = kind.to_nurbs().unwrap().curve;
    kind.joints(&form, &JointTolerance::default())
}

/// The index of the key a joint stands at (interpolating kinds).
fn key_index(kind: &CurveKind, j: &Joint) -> usize {
    if j.closing {
        return 0;
    }
    let keys = kind.key_parameters().unwrap();
    keys.iter().position(|&k| k == j.parameter).expect("a key")
}

#[test]
fn every_kind_has_the_continuity_it_promises_at_each_joint() {
    for kind in every_kind() {
        let name = kind.name();
        let joints = joints_of(&kind);
        let form = kind.to_nurbs().unwrap().curve;
        // Where the joints are: every interior knot, the closing one last.
        let expected = form.interior_knots().len() + usize::from(kind.is_closed());
        match &kind {
            CurveKind::Lagrange(_) => assert!(joints.is_empty(), "{name}: one polynomial"),
            _ => assert_eq!(joints.len(), expected, "{name}"),
        }
        assert_eq!(
            joints.iter().filter(|j| j.closing).count(),
            usize::from(kind.is_closed() && !matches!(kind, CurveKind::Lagrange(_)))
        );
        for j in &joints {
            let c = j.continuity;
            let at = format!("{name} at t = {} ({})", j.parameter, c.label());
            assert!(c.c0, "{at}: the pieces meet");
            assert!(
                (j.before[0] - j.after[0]).length() < 1e-9,
                "{at}: positions from both sides"
            );
            match &kind {
                CurveKind::Nurbs(n) if n.degree() == 3 => assert_eq!(c.label(), "C2", "{at}"),
                // The circle's double knots are C0 by their multiplicity,
                // but its quarters meet with the same tangent and the same
                // curvature 1/r.
                CurveKind::Nurbs(_) => {
                    assert!(c.g2, "{at}");
                    assert_eq!(j.multiplicity, if j.closing { 0 } else { 2 });
                }
                CurveKind::QuinticHermite(_) | CurveKind::CubicSpline(_) => {
                    assert_eq!(c.label(), "C2", "{at}")
                }
                CurveKind::CubicHermite(_) | CurveKind::CatmullRom(_) => {
                    assert!(c.c1 && c.g1, "{at}");
                }
                CurveKind::KochanekBartels(KochanekBartels { keys, .. }) => {
                    let k = keys[key_index(&kind, j)];
                    if k.continuity == 0.0 {
                        assert!(c.c1, "{at}: C1 where continuity is 0");
                    } else {
                        assert!(!c.c1 && !c.g1, "{at}: only C0 where continuity ≠ 0");
                    }
                }
                CurveKind::PolyBezier(PolyBezier { joins, closed, .. }) => {
                    // Joint j of an open chain is at t = j + 1, of a closed
                    // one at t = j (the closing joint at t = 0).
                    let index = j.parameter as usize - usize::from(!closed);
                    match joins[index] {
                        Join::C1 => assert!(c.c1 && !c.c2, "{at}: C1"),
                        Join::G1 => assert!(c.g1 && !c.c1, "{at}: G1 with unequal handles"),
                        Join::Auto => assert!(c.g1, "{at}: auto handles are aligned"),
                        Join::C0 => assert_eq!(c.label(), "C0", "{at}: a corner"),
                    }
                    let anchor = kind.points()[3 * index + 3 * usize::from(!closed)];
                    assert!((j.position - anchor).length() < 1e-12, "{at}: the anchor");
                }
                CurveKind::Chaikin(_) | CurveKind::Fractal(_) => {
                    // A polygon's vertex: smooth only where its two edges
                    // continue each other, seen on the polygon itself.
                    let poly = form.points();
                    let m = poly.len();
                    let k = if j.closing {
                        0
                    } else {
                        form.interior_knots()
                            .iter()
                            .position(|x| x.0 == j.parameter)
                            .unwrap()
                            + 1
                    };
                    let (prev, next) = if j.closing {
                        (poly[m - 2], poly[1])
                    } else {
                        (poly[k - 1], poly[k + 1])
                    };
                    assert_eq!(poly[k], j.position, "{at}");
                    let straight = ((poly[k] - prev).normalize() - (next - poly[k]).normalize())
                        .length()
                        < 1e-9;
                    assert_eq!(c.g1, straight, "{at}");
                    if matches!(
                        kind,
                        CurveKind::Fractal(Fractal {
                            rule: FractalRule::Koch,
                            ..
                        })
                    ) {
                        assert!(!c.g1, "{at}: every Koch vertex is a corner");
                    }
                }
                _ => {}
            }
        }
    }
    // The measurement can fail: Catmull-Rom is not C2 everywhere, and
    // quadratic Koch has straight vertices (C2 between equal edges).
    let cr = CurveKind::CatmullRom(CatmullRom {
        points: pts(),
        parameterization: Parameterization::Uniform,
        closed: false,
    });
    assert!(joints_of(&cr).iter().any(|j| !j.continuity.c2));
    let quad = CurveKind::Fractal(Fractal {
        rule: FractalRule::QuadraticKoch,
        points: vec![DVec3::ZERO, DVec3::X],
        level: 1,
        closed: false,
        normal: DVec3::Z,
    });
    let labels: Vec<&str> = joints_of(&quad)
        .iter()
        .map(|j| j.continuity.label())
        .collect();
    assert_eq!(labels, ["C0", "C0", "C0", "C2", "C0", "C0", "C0"]);
}

#[test]
fn a_gap_and_a_kink_are_told_apart_from_rounding() {
    // Two cubic Bézier pieces as a NURBS with a triple knot, the second
    // piece moved off by 1e-6: a gap. Back in place with a kinked handle:
    // C0 only. Then with the handle mirrored: C1, and G1 when only its
    // length changes.
    let mk = |b: [DVec3; 7]| {
        let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0];
        NurbsCurve::new(3, knots, b.to_vec(), vec![1.0; 7]).unwrap()
    };
    let p = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    let smooth = [
        p(0.0, 0.0),
        p(1.0, 1.0),
        p(2.0, 1.0),
        p(3.0, 0.0),
        p(4.0, -1.0),
        p(5.0, 0.0),
        p(6.0, 0.0),
    ];
    let t = JointTolerance::default();
    let label = |c: &NurbsCurve| {
        hedra_geom::curves::joints::curve_joints(c, false, &t)[0]
            .continuity
            .label()
    };
    assert_eq!(label(&mk(smooth)), "C1");
    let mut longer = smooth;
    longer[4] = p(5.0, -2.0);
    assert_eq!(label(&mk(longer)), "G1");
    let mut kinked = smooth;
    kinked[4] = p(4.0, -1.001);
    assert_eq!(label(&mk(kinked)), "C0");
    // A gap needs two curves: the joint of a single NURBS always closes,
    // so test the classification directly.
    let c = mk(smooth);
    let (before, after) = both_sides(&c, false, 1.0);
    let (mut before, after) = (before.unwrap(), after.unwrap());
    before[0] += DVec3::new(0.0, 1e-6, 0.0);
    let size = 7.0;
    let cont = hedra_geom::curves::joints::classify(before, after, size, 1.0, &t);
    assert_eq!(cont.label(), "gap");
}

#[test]
fn both_sides_at_a_kochanek_bartels_corner_differ_and_open_ends_have_one() {
    let kb = CurveKind::KochanekBartels(KochanekBartels {
        points: pts(),
        keys: keys(),
        closed: false,
    });
    let form = kb.to_nurbs().unwrap().curve;
    let (before, after) = both_sides(&form, false, 1.0);
    let (b, a) = (before.unwrap(), after.unwrap());
    assert_eq!(b[0], pts()[1]);
    assert!((b[0] - a[0]).length() < 1e-12);
    assert!(
        (b[1] - a[1]).length() > 0.1,
        "the tangents differ at C = 0.4"
    );
    assert!(both_sides(&form, false, 0.0).0.is_none());
    assert!(both_sides(&form, false, 4.0).1.is_none());
    // A closed curve wraps: before its start is its end.
    let closed = CurveKind::KochanekBartels(KochanekBartels {
        points: pts(),
        keys: keys(),
        closed: true,
    });
    let form = closed.to_nurbs().unwrap().curve;
    let (b, a) = both_sides(&form, true, 0.0);
    assert!((b.unwrap()[0] - a.unwrap()[0]).length() < 1e-12);
    assert!((b.unwrap()[1] - form.derivatives(5.0)[1]).length() < 1e-12);
}

fn assert_matrix(m: &[Vec<f64>], want: &[&[f64]]) {
    assert_eq!(m.len(), want.len());
    for (row, w) in m.iter().zip(want) {
        assert_eq!(row.len(), w.len());
        for (x, y) in row.iter().zip(w.iter()) {
            assert!((x - y).abs() < 1e-15, "{m:?} vs {want:?}");
        }
    }
}

fn mul(a: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<Vec<f64>> {
    (0..a.len())
        .map(|i| {
            (0..b[0].len())
                .map(|j| (0..b.len()).map(|k| a[i][k] * b[k][j]).sum())
                .collect()
        })
        .collect()
}

#[test]
fn the_seed_003_matrices_and_its_parabola() {
    // Seed 003: [u², u, 1] M = [B₂², B₁², B₀²] and its inverse.
    assert_matrix(
        &bernstein_to_power_matrix(2),
        &[&[1.0, -2.0, 1.0], &[0.0, 2.0, -2.0], &[0.0, 0.0, 1.0]],
    );
    assert_matrix(
        &power_to_bernstein_matrix(2),
        &[&[1.0, 1.0, 1.0], &[0.0, 0.5, 1.0], &[0.0, 0.0, 1.0]],
    );
    // The cubic one, in the same order.
    assert_matrix(
        &bernstein_to_power_matrix(3),
        &[
            &[1.0, -3.0, 3.0, -1.0],
            &[0.0, 3.0, -6.0, 3.0],
            &[0.0, 0.0, 3.0, -3.0],
            &[0.0, 0.0, 0.0, 1.0],
        ],
    );
    // M M⁻¹ = I for every degree a curve kind makes.
    for n in 1..=11 {
        let p = mul(&bernstein_to_power_matrix(n), &power_to_bernstein_matrix(n));
        for (i, row) in p.iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((x - want).abs() < 1e-9, "degree {n}: ({i}, {j}) = {x}");
            }
        }
    }
    // The seed's parabola a₂ = (0, 1), a₁ = (1, 0), a₀ = (0, 0) on [0, 1]:
    // b₀ = (0, 0), b₁ = (½, 0), b₂ = (1, 1).
    let a = [DVec3::Y, DVec3::X, DVec3::ZERO];
    let inv = power_to_bernstein_matrix(2);
    let b: Vec<DVec3> = inv
        .iter()
        .map(|row| row.iter().zip(&a).map(|(&m, &v)| v * m).sum())
        .collect();
    assert_eq!(
        b,
        [
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.5, 0.0, 0.0),
            DVec3::ZERO
        ]
    );
    // And back through a segment: the coefficients are the parabola's.
    let seg = PowerBasisSegment::new((0.0, 1.0), &[b[2], b[1], b[0]], &[1.0; 3]);
    assert_eq!(seg.coefficients, a);
    assert_eq!(seg.weight_coefficients, [0.0, 0.0, 1.0]);
    assert_eq!(seg.control_points_from_coefficients(), b);
}

#[test]
fn the_seed_003_cubic_hermite_matrix_converts_to_bezier_points() {
    // Seed 003's cubic Hermite matrix (rows u³, u², u, 1; columns r₀, r₁,
    // t₀, t₁) and its conversion X = M_B⁻¹ M_H G: the Bézier points of a
    // Hermite segment are r₁, r₁ − t₁/3, r₀ + t₀/3, r₀ (descending).
    let hermite: Vec<Vec<f64>> = vec![
        vec![2.0, -2.0, 1.0, 1.0],
        vec![-3.0, 3.0, -2.0, -1.0],
        vec![0.0, 0.0, 1.0, 0.0],
        vec![1.0, 0.0, 0.0, 0.0],
    ];
    let conversion = mul(&power_to_bernstein_matrix(3), &hermite);
    assert_matrix(
        &conversion,
        &[
            &[0.0, 1.0, 0.0, 0.0],
            &[0.0, 1.0, 0.0, -1.0 / 3.0],
            &[1.0, 0.0, 1.0 / 3.0, 0.0],
            &[1.0, 0.0, 0.0, 0.0],
        ],
    );
    // The same segment through a cubic Hermite curve kind's NURBS form.
    let (r0, r1) = (DVec3::new(1.0, 2.0, 3.0), DVec3::new(4.0, 0.0, -1.0));
    let (t0, t1) = (DVec3::new(3.0, 3.0, 0.0), DVec3::new(0.0, -6.0, 3.0));
    let kind = CurveKind::CubicHermite(CubicHermite {
        points: vec![r0, r1],
        tangents: vec![t0, t1],
    });
    let segs = power_basis_segments(&kind.to_nurbs().unwrap().curve).unwrap();
    assert_eq!(segs.len(), 1);
    let g = [r0, r1, t0, t1];
    let want: Vec<DVec3> = conversion
        .iter()
        .map(|row| row.iter().zip(&g).map(|(&m, &v)| v * m).sum())
        .collect();
    for (x, y) in segs[0].control_points.iter().zip(&want) {
        assert!((*x - *y).length() < 1e-14, "{x} vs {y}");
    }
    // Its power form is the Hermite polynomial: A = M_H G.
    let a: Vec<DVec3> = hermite
        .iter()
        .map(|row| row.iter().zip(&g).map(|(&m, &v)| v * m).sum())
        .collect();
    for (x, y) in segs[0].coefficients.iter().zip(&a) {
        assert!((*x - *y).length() < 1e-13, "{x} vs {y}");
    }
}

#[test]
fn every_segment_in_power_form_traces_the_curve_and_converts_back() {
    for kind in every_kind() {
        let form = kind.to_nurbs().unwrap().curve;
        let scale = form.points().iter().map(|p| p.length()).fold(1.0, f64::max);
        let segs = power_basis_segments(&form).unwrap();
        assert_eq!(
            segs.len(),
            form.interior_knots().len() + 1,
            "{}",
            kind.name()
        );
        for s in segs.iter().take(40) {
            let (t0, t1) = s.interval;
            for i in 0..=8 {
                let u = i as f64 / 8.0;
                let p = s.point(u);
                let q = form.point(t0 + u * (t1 - t0));
                assert!(
                    (p - q).length() < 1e-10 * scale,
                    "{}: {p} vs {q}",
                    kind.name()
                );
            }
            for (x, y) in s
                .control_points_from_coefficients()
                .iter()
                .zip(&s.control_points)
            {
                assert!((*x - *y).length() < 1e-9 * scale, "{}", kind.name());
            }
            // Polynomial segments agree with Bezier::to_power_basis
            // (ascending order there).
            if s.weights.iter().all(|&w| w == 1.0) {
                let mut asc = s.control_points.clone();
                asc.reverse();
                let mut power = Bezier::new(asc).unwrap().to_power_basis();
                power.reverse();
                for (x, y) in power.iter().zip(&s.coefficients) {
                    assert!((*x - *y).length() < 1e-9 * scale);
                }
            }
        }
    }
}

#[test]
fn every_curve_sample_lies_in_its_segment_hull() {
    for kind in every_kind() {
        let form = kind.to_nurbs().unwrap().curve;
        let hulls = segment_hulls(&form).unwrap();
        let size = form
            .points()
            .iter()
            .fold(0.0f64, |m, p| m.max((*p - form.points()[0]).length()));
        for h in hulls.iter().take(60) {
            let (t0, t1) = h.interval;
            for i in 0..=50 {
                let t = t0 + (t1 - t0) * i as f64 / 50.0;
                let p = form.point(t);
                assert!(
                    h.hull.contains(p, 1e-9 * size),
                    "{}: t = {t} ({p}) outside {:?}",
                    kind.name(),
                    h.hull
                );
            }
            for &q in &h.control_points {
                assert!(h.hull.contains(q, 1e-9 * size));
            }
            // A point well outside is refused.
            let far = h.control_points[0] + DVec3::new(0.0, 0.0, 10.0 * size + 1.0);
            assert!(!h.hull.contains(far, 1e-9 * size), "{}", kind.name());
        }
        // The kinds' hulls by dimension: a degree-1 piece is a segment, a
        // planar cubic a polygon, a twisted one a solid.
        if let CurveKind::Fractal(_) | CurveKind::Chaikin(_) = kind {
            assert!(
                hulls
                    .iter()
                    .all(|h| matches!(h.hull, ControlHull::Segment(_)))
            );
        }
    }
    let planar = segment_hulls(&poly_bezier(false).to_nurbs().unwrap().curve).unwrap();
    assert!(matches!(planar[0].hull, ControlHull::Polygon { .. }));
    assert!(matches!(planar[1].hull, ControlHull::Polyhedron { .. }));
}

#[test]
fn span_lengths_of_parameters_and_of_selected_points() {
    // The exact circle: 2πr to 1e-12, also as a selection of all its points.
    let r = 2.5;
    let circle = NurbsCurve::circle(DVec3::new(1.0, 0.0, -2.0), r);
    let exact = std::f64::consts::TAU * r;
    assert!((curve_length(&circle) - exact).abs() <= 1e-12 * exact);
    let kind = CurveKind::Nurbs(circle.clone());
    let all: Vec<usize> = (0..9).collect();
    let span = kind.selection_span(&circle, &all).unwrap();
    assert_eq!((span.start, span.end), (0.0, 1.0));
    assert!((span.length - exact).abs() <= 1e-12 * exact);
    // Points 2 and 4 (corners' middles of the square) are a quarter apart.
    let quarter = kind.selection_span(&circle, &[4, 2]).unwrap();
    assert!((quarter.length - exact / 4.0).abs() <= 1e-12 * exact);

    // Catmull-Rom points 1 and 3: the curve between their keys.
    let cr = CurveKind::CatmullRom(CatmullRom {
        points: pts(),
        parameterization: Parameterization::Chord,
        closed: false,
    });
    let form = cr.to_nurbs().unwrap().curve;
    let keys = cr.key_parameters().unwrap();
    let s = cr.selection_span(&form, &[3, 1]).unwrap();
    assert_eq!((s.start, s.end), (keys[1], keys[3]));
    assert!((s.ends[0] - pts()[1]).length() < 1e-12);
    assert!((s.ends[1] - pts()[3]).length() < 1e-12);
    let pieces = span_length(&form, keys[1], keys[2]).unwrap()
        + span_length(&form, keys[2], keys[3]).unwrap();
    assert!((s.length - pieces).abs() < 1e-12 * pieces);
    // One point: no length.
    assert_eq!(cr.selection_span(&form, &[2]).unwrap().length, 0.0);

    // Poly-Bézier anchors 0 and 3: the first Bézier segment's length.
    let pb = poly_bezier(false);
    let form = pb.to_nurbs().unwrap().curve;
    let seg = Bezier::new(pb.points()[..4].to_vec()).unwrap();
    let s = pb.selection_span(&form, &[0, 3]).unwrap();
    assert_eq!((s.start, s.end), (0.0, 1.0));
    assert!((s.length - arc_length(&seg, 0.0, 1.0)).abs() < 1e-12 * s.length);

    // Koch level 2 on a unit initiator: its two points span (4/3)² in all.
    let koch = CurveKind::Fractal(Fractal {
        rule: FractalRule::Koch,
        points: vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0)],
        level: 2,
        closed: false,
        normal: DVec3::Z,
    });
    let form = koch.to_nurbs().unwrap().curve;
    let s = koch.selection_span(&form, &[0, 1]).unwrap();
    assert!((s.length - 16.0 / 9.0).abs() < 1e-12);
    assert!((s.ends[1] - DVec3::X).length() < 1e-12);

    // Refusals name the problem.
    let form = cr.to_nurbs().unwrap().curve;
    assert_eq!(
        cr.selection_span(&form, &[7]),
        Err(CurveError::NoSuchPoint { index: 7, count: 5 })
    );
    assert!(cr.selection_span(&form, &[]).is_err());
}
