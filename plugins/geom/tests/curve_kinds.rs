//! Every curve kind: passes through its points, keeps the continuity it
//! promises at its joints, equals its NURBS form, and its edits keep what
//! they say they keep.

use glam::DVec3;
use hedra_geom::curves::analysis::closest_parameter;
use hedra_geom::curves::interpolating::{self, Tbc};
use hedra_geom::curves::kinds::lagrange_point;
use hedra_geom::curves::{
    Bezier, CatmullRom, Chaikin, CubicHermite, CubicSpline, Curve, CurveEnd, CurveError, CurveKind,
    Fractal, FractalRule, Join, KochanekBartels, Lagrange, NurbsCurve, Parameterization,
    PolyBezier, QuinticHermite, SplineEnds,
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

fn every_kind() -> Vec<CurveKind> {
    let p = pts();
    let tangents: Vec<DVec3> = (0..5)
        .map(|i| DVec3::new(1.0, (i as f64).sin(), 0.2))
        .collect();
    let keys = vec![
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
        Tbc::default(),
        Tbc::default(),
    ];
    let mut out = vec![
        CurveKind::Nurbs(NurbsCurve::clamped(3, p.clone()).unwrap()),
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
            keys: keys.clone(),
            closed: false,
        }),
        CurveKind::KochanekBartels(KochanekBartels {
            points: p.clone(),
            keys,
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
        poly_bezier(),
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

fn poly_bezier() -> CurveKind {
    CurveKind::PolyBezier(PolyBezier {
        points: vec![
            DVec3::ZERO,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::new(4.0, -1.0, 0.0),
            DVec3::new(5.0, -1.0, 0.0),
            DVec3::new(6.0, 0.0, 0.0),
            DVec3::new(6.0, 2.0, 0.0),
            DVec3::new(8.0, 2.0, 1.0),
            DVec3::new(9.0, 0.0, 0.0),
        ],
        joins: vec![Join::C1, Join::C0],
        closed: false,
    })
}

fn samples(c: &dyn Curve, n: usize) -> Vec<f64> {
    let (a, b) = c.domain();
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
        .collect()
}

#[test]
fn interpolating_kinds_pass_through_their_points() {
    for kind in every_kind().into_iter().filter(|k| k.interpolates()) {
        let form = kind.to_nurbs().unwrap();
        assert_eq!(form.tolerance, None, "{}", kind.name());
        let keys = kind.key_parameters().unwrap();
        let n = kind.points().len();
        assert_eq!(
            keys.len(),
            n + usize::from(kind.is_closed()),
            "{}",
            kind.name()
        );
        for (i, &t) in keys.iter().enumerate() {
            let want = kind.points()[i % n];
            let got = form.curve.point(t);
            assert!(
                (got - want).length() < 1e-9,
                "{} point {i}: {got} vs {want}",
                kind.name()
            );
        }
    }
}

#[test]
fn nurbs_forms_equal_the_kinds_at_1000_parameters() {
    let p = pts();
    // Lagrange: the barycentric polynomial.
    let lag = CurveKind::Lagrange(Lagrange {
        points: p.clone(),
        parameterization: Parameterization::Chord,
    });
    let form = lag.to_nurbs().unwrap().curve;
    let t = Parameterization::Chord.parameters(&p).unwrap();
    for x in samples(&form, 1000) {
        assert!((form.point(x) - lagrange_point(&t, &p, x)).length() < 1e-10);
    }
    // The Hermite family: the kernel's Hermite evaluation.
    for kind in every_kind() {
        if let Some(h) = kind.hermite().unwrap() {
            let form = kind.to_nurbs().unwrap().curve;
            assert_eq!(form.domain(), h.domain());
            for x in samples(&form, 1000) {
                let (a, b) = (form.derivatives(x), h.derivatives(x));
                assert!((a[0] - b[0]).length() < 1e-12, "{} at {x}", kind.name());
                assert!((a[1] - b[1]).length() < 1e-9, "{} d1 at {x}", kind.name());
            }
        }
    }
    // Quintic Hermite: the kernel's quintic segment on each unit span.
    let CurveKind::QuinticHermite(QuinticHermite {
        points,
        tangents,
        accelerations,
    }) = &every_kind()[2]
    else {
        panic!()
    };
    let q = every_kind()[2].to_nurbs().unwrap().curve;
    for x in samples(&q, 1000) {
        let i = (x.floor() as usize).min(points.len() - 2);
        let seg = interpolating::QuinticHermite {
            points: [points[i], points[i + 1]],
            velocities: [tangents[i], tangents[i + 1]],
            accelerations: [accelerations[i], accelerations[i + 1]],
        };
        let (a, b) = (q.derivatives(x), seg.derivatives(x - i as f64));
        assert!((a[0] - b[0]).length() < 1e-12, "quintic at {x}");
        assert!((a[2] - b[2]).length() < 1e-8, "quintic d2 at {x}");
    }
    // Poly-Bézier: de Casteljau on each segment.
    let pb = poly_bezier();
    let f = pb.to_nurbs().unwrap().curve;
    for x in samples(&f, 1000) {
        let i = (x.floor() as usize).min(2);
        let seg = Bezier {
            points: pb.points()[3 * i..3 * i + 4].to_vec(),
        };
        assert!((f.point(x) - seg.de_casteljau(x - i as f64)).length() < 1e-12);
    }
}

#[test]
fn high_degree_lagrange_is_approximated_with_a_stated_tolerance() {
    let p: Vec<DVec3> = (0..20)
        .map(|i| DVec3::new(i as f64, (i as f64 * 0.7).sin(), 0.0))
        .collect();
    let kind = CurveKind::Lagrange(Lagrange {
        points: p.clone(),
        parameterization: Parameterization::Uniform,
    });
    let form = kind.to_nurbs().unwrap();
    let tol = form.tolerance.expect("approximated");
    let t: Vec<f64> = (0..20).map(|i| i as f64).collect();
    // 20,000 samples, not aligned with the spline's 608 intervals: the
    // stated tolerance holds everywhere (to rounding) and is not a loose
    // bound either (the samples come within a few percent of it).
    let worst = samples(&form.curve, 19_999)
        .into_iter()
        .map(|x| (form.curve.point(x) - lagrange_point(&t, &p, x)).length())
        .fold(0.0, f64::max);
    assert!(tol > 0.0);
    assert!(worst <= tol * (1.0 + 1e-9), "worst {worst} vs stated {tol}");
    assert!(worst >= 0.95 * tol, "worst {worst} vs stated {tol}");
    for (i, &x) in t.iter().enumerate() {
        assert!((form.curve.point(x) - p[i]).length() < 1e-9);
    }
}

/// Derivatives just left and right of `t`.
fn sides(c: &NurbsCurve, t: f64) -> ([DVec3; 3], [DVec3; 3]) {
    (c.derivatives(t - 1e-9), c.derivatives(t + 1e-9))
}

#[test]
fn joints_have_the_continuity_they_promise() {
    for kind in every_kind() {
        let form = kind.to_nurbs().unwrap().curve;
        let keys = kind.key_parameters().unwrap();
        let inner = keys.iter().skip(1).take(keys.len().saturating_sub(2));
        for &t in inner {
            let (l, r) = sides(&form, t);
            assert!((l[0] - r[0]).length() < 1e-7, "{} C0 at {t}", kind.name());
            let c1 = (l[1] - r[1]).length() < 1e-6;
            let c2 = (l[2] - r[2]).length() < 1e-5;
            match &kind {
                CurveKind::CubicSpline(_) | CurveKind::QuinticHermite(_) => {
                    assert!(c1 && c2, "{} C2 at {t}: {l:?} {r:?}", kind.name())
                }
                CurveKind::CatmullRom(_) | CurveKind::CubicHermite(_) => {
                    assert!(c1, "{} C1 at {t}", kind.name())
                }
                CurveKind::KochanekBartels(KochanekBartels { keys, .. }) => {
                    // C1 where continuity is 0, a corner where it is not.
                    let k = keys[t.round() as usize % keys.len()];
                    assert_eq!(c1, k.continuity == 0.0, "{} at {t}", kind.name());
                }
                _ => {}
            }
        }
        // Closed C2 splines are C2 at the closing point too.
        if let CurveKind::CubicSpline(CubicSpline {
            ends: SplineEnds::Closed,
            ..
        }) = kind
        {
            let (a, b) = form.domain();
            let (s, e) = (form.derivatives(a), form.derivatives(b));
            for k in 0..3 {
                assert!((s[k] - e[k]).length() < 1e-9, "closing derivative {k}");
            }
        }
    }
    // Poly-Bézier: C1 at joint 0 (t = 1), C0 only at joint 1 (t = 2).
    let f = poly_bezier().to_nurbs().unwrap().curve;
    let (l, r) = sides(&f, 1.0);
    assert!((l[1] - r[1]).length() < 1e-6);
    let (l, r) = sides(&f, 2.0);
    assert!((l[1].normalize() - r[1].normalize()).length() > 0.1);
}

#[test]
fn poly_bezier_g1_join_holds_while_a_handle_moves() {
    let pb = poly_bezier().set_join(1, Join::G1).unwrap();
    let f = pb.to_nurbs().unwrap().curve;
    let (l, r) = sides(&f, 2.0);
    assert!((l[1].normalize() - r[1].normalize()).length() < 1e-6);
    // Drag the incoming handle of joint 1 (point 5) around: still G1, the
    // outgoing handle keeps its length; the anchor stays.
    let len = (pb.points()[7] - pb.points()[6]).length();
    for k in 0..8 {
        let angle = k as f64 * 0.7;
        let to = pb.points()[6] + DVec3::new(angle.cos(), angle.sin(), 0.3);
        let moved = pb.set_points(&[(5, to)]).unwrap();
        let q = moved.points();
        assert_eq!(q[5], to);
        assert_eq!(q[6], pb.points()[6]);
        assert!(((q[7] - q[6]).length() - len).abs() < 1e-12);
        let f = moved.to_nurbs().unwrap().curve;
        let (l, r) = sides(&f, 2.0);
        assert!((l[1].normalize() - r[1].normalize()).length() < 1e-6);
    }
    // C1 mirrors; moving the anchor carries both handles.
    let c1 = pb.set_join(0, Join::C1).unwrap();
    let moved = c1.set_points(&[(2, DVec3::new(2.0, 3.0, 0.0))]).unwrap();
    let q = moved.points();
    assert!((q[4] - (2.0 * q[3] - q[2])).length() < 1e-12);
    let moved = c1.set_points(&[(3, DVec3::new(3.0, 1.0, 0.0))]).unwrap();
    assert!((moved.points()[2] - (c1.points()[2] + DVec3::Y)).length() < 1e-12);
    assert!((moved.points()[4] - (c1.points()[4] + DVec3::Y)).length() < 1e-12);
}

#[test]
fn koch_level_n_has_4_to_the_n_segments_of_total_length_4_3_to_the_n() {
    for level in 0..=6 {
        let koch = CurveKind::Fractal(Fractal {
            rule: FractalRule::Koch,
            points: vec![DVec3::ZERO, DVec3::new(3.0, 0.0, 0.0)],
            level,
            closed: false,
            normal: DVec3::Z,
        });
        let poly = koch.to_nurbs().unwrap().curve.points().to_vec();
        assert_eq!(poly.len() - 1, 4usize.pow(level));
        let len: f64 = poly.windows(2).map(|w| (w[1] - w[0]).length()).sum();
        assert!((len - 3.0 * (4.0f64 / 3.0).powi(level as i32)).abs() < 1e-9);
        // Every segment is 3^-n long; the curve stays in the plane, bumps up.
        assert!(poly.iter().all(|p| p.z == 0.0 && p.y >= -1e-12));
    }
    let snow = CurveKind::Fractal(Fractal {
        rule: FractalRule::Koch,
        points: vec![
            DVec3::ZERO,
            DVec3::new(0.5, 3f64.sqrt() / 2.0, 0.0),
            DVec3::X,
        ],
        level: 4,
        closed: true,
        normal: DVec3::Z,
    });
    let poly = snow.to_nurbs().unwrap().curve.points().to_vec();
    assert_eq!(poly.len() - 1, 3 * 4usize.pow(4));
    assert_eq!(poly[0], poly[poly.len() - 1]);
    // Clockwise triangle: the bumps point away from the centre.
    let centre = DVec3::new(0.5, 3f64.sqrt() / 6.0, 0.0);
    let r_in = 3f64.sqrt() / 6.0;
    assert!(poly.iter().all(|p| (*p - centre).length() >= r_in - 1e-9));
    assert!(poly.iter().any(|p| (*p - centre).length() > 1.99 * r_in));
    assert!((FractalRule::Koch.dimension() - 4f64.ln() / 3f64.ln()).abs() < 1e-15);
    assert_eq!(FractalRule::QuadraticKoch.dimension(), 1.5);
    let quad = CurveKind::Fractal(Fractal {
        rule: FractalRule::QuadraticKoch,
        points: vec![DVec3::ZERO, DVec3::X],
        level: 3,
        closed: false,
        normal: DVec3::Z,
    });
    let poly = quad.to_nurbs().unwrap().curve.points().to_vec();
    assert_eq!(poly.len() - 1, 512);
    let len: f64 = poly.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    assert!((len - 8.0).abs() < 1e-9, "length 2^3: {len}");
    let too_deep = CurveKind::Fractal(Fractal {
        rule: FractalRule::QuadraticKoch,
        points: vec![DVec3::ZERO, DVec3::X],
        level: 40,
        closed: false,
        normal: DVec3::Z,
    });
    assert!(matches!(
        too_deep.check(),
        Err(CurveError::LevelTooHigh { level: 40, .. })
    ));
}

#[test]
fn insert_then_delete_gives_back_the_curve_and_keeps_the_others() {
    for kind in every_kind() {
        let form = kind.to_nurbs().unwrap().curve;
        let (a, b) = form.domain();
        let t = a + 0.37 * (b - a);
        let (with, i) = kind.insert_point(t).unwrap();
        let name = kind.name();
        match &kind {
            CurveKind::Nurbs(_) => {
                assert_eq!(with.points().len(), kind.points().len() + 1);
            }
            CurveKind::PolyBezier(_) => {
                // Exact: every point of the new curve is on the old one.
                let f2 = with.to_nurbs().unwrap().curve;
                for x in samples(&f2, 200) {
                    let p = f2.point(x);
                    let q = form.point(closest_parameter(&form, p));
                    assert!((p - q).length() < 1e-9, "{name} moved at {x}");
                }
                let back = with.delete_points(&[i]).unwrap();
                assert_eq!(back.points().len(), kind.points().len());
            }
            _ => {
                let old = kind.points();
                let new = with.points();
                assert_eq!(new.len(), old.len() + 1, "{name}");
                assert_eq!(&new[..i], &old[..i], "{name}");
                assert_eq!(&new[i + 1..], &old[i..], "{name}");
                if kind.interpolates() {
                    assert!((new[i] - form.point(t)).length() < 1e-9, "{name}");
                }
                assert_eq!(with.delete_points(&[i]).unwrap(), kind, "{name}");
            }
        }
    }
}

#[test]
fn refusals_are_named() {
    let one = CurveKind::Lagrange(Lagrange {
        points: vec![DVec3::ZERO],
        parameterization: Parameterization::Uniform,
    });
    assert_eq!(
        one.check().unwrap_err().to_string(),
        "Lagrange needs 2 points or more, got 1"
    );
    let two = CurveKind::Lagrange(Lagrange {
        points: vec![DVec3::ZERO, DVec3::X],
        parameterization: Parameterization::Chord,
    });
    assert_eq!(
        two.delete_points(&[0]).unwrap_err().to_string(),
        "Lagrange needs 2 points or more, got 1"
    );
    assert_eq!(
        two.set_closed(true).unwrap_err().to_string(),
        "closing is not possible on a Lagrange curve"
    );
    assert!(matches!(
        poly_bezier().delete_points(&[4]),
        Err(CurveError::HandleNotAnchor { index: 4 })
    ));
    let same = CurveKind::Lagrange(Lagrange {
        points: vec![DVec3::ZERO, DVec3::ZERO, DVec3::X],
        parameterization: Parameterization::Chord,
    });
    assert!(matches!(
        same.check(),
        Err(CurveError::CoincidentPoints { index: 0, next: 1 })
    ));
    let closed = CurveKind::CatmullRom(CatmullRom {
        points: pts(),
        parameterization: Parameterization::Uniform,
        closed: true,
    });
    assert!(matches!(
        closed.extrude(CurveEnd::End, DVec3::ONE),
        Err(CurveError::NotForKind { .. })
    ));
    assert!(matches!(
        two.join(&poly_bezier()),
        Err(CurveError::KindMismatch { .. })
    ));
}

#[test]
fn reverse_traces_the_same_curve_backwards_and_is_its_own_inverse() {
    for kind in every_kind() {
        let r = kind.reverse().unwrap();
        assert_eq!(r.reverse().unwrap(), kind, "{}", kind.name());
        let (f, g) = (kind.to_nurbs().unwrap().curve, r.to_nurbs().unwrap().curve);
        let (a, b) = f.domain();
        let (c, d) = g.domain();
        for s in samples(&f, 101) {
            let u = (s - a) / (b - a);
            let p = f.point(s);
            // A closed Chaikin polygon starts elsewhere when reversed: the
            // same loop, compared as a shape.
            let q = if matches!(kind, CurveKind::Chaikin(Chaikin { closed: true, .. })) {
                g.point(closest_parameter(&g, p))
            } else {
                g.point(c + (d - c) * (1.0 - u))
            };
            assert!(
                (p - q).length() < 1e-9,
                "{} at {s}: {p} vs {q}",
                kind.name()
            );
        }
    }
}

#[test]
fn split_then_join_keeps_the_shape() {
    for kind in every_kind().into_iter().filter(|k| !k.is_closed()) {
        let f = kind.to_nurbs().unwrap().curve;
        let (a, b) = f.domain();
        let t = a + 0.55 * (b - a);
        let (l, r) = kind.split(t).unwrap();
        let (fl, fr) = (l.to_nurbs().unwrap().curve, r.to_nurbs().unwrap().curve);
        let end = fl.point(fl.domain().1);
        assert!(
            (end - fr.point(fr.domain().0)).length() < 1e-9,
            "{}",
            kind.name()
        );
        if kind.level_polygon().is_none() {
            assert!((end - f.point(t)).length() < 1e-9, "{}", kind.name());
        }
        let joined = l.join(&r).unwrap();
        let expected = kind.insert_point(t).unwrap().0;
        match kind {
            CurveKind::Nurbs(_) => {
                let g = joined.to_nurbs().unwrap().curve;
                for x in samples(&g, 200) {
                    let p = g.point(x);
                    assert!((p - f.point(closest_parameter(&f, p))).length() < 1e-9);
                }
            }
            _ => assert_eq!(joined.points(), expected.points(), "{}", kind.name()),
        }
    }
}

#[test]
fn a_nurbs_circle_splits_into_two_arcs() {
    let circle = CurveKind::Nurbs(NurbsCurve::circle(DVec3::ZERO, 2.0));
    assert!(circle.is_closed());
    let (a, b) = circle.split(0.25).unwrap();
    let (fa, fb) = (a.to_nurbs().unwrap().curve, b.to_nurbs().unwrap().curve);
    for x in samples(&fa, 50).into_iter().chain(samples(&fb, 50)) {
        let p = if x <= 0.25 { fa.point(x) } else { fb.point(x) };
        assert!((p.length() - 2.0).abs() < 1e-12);
    }
    assert!((fa.point(0.25) - fb.point(0.25)).length() < 1e-12);
}

#[test]
fn open_and_close() {
    let pb = poly_bezier();
    let closed = pb.set_closed(true).unwrap();
    assert!(closed.is_closed());
    assert_eq!(closed.points().len(), pb.points().len() + 2);
    let f = closed.to_nurbs().unwrap().curve;
    let (a, b) = f.domain();
    assert!((f.point(a) - f.point(b)).length() < 1e-12);
    let open = closed.set_closed(false).unwrap();
    assert!(!open.is_closed());
    assert_eq!(open.points()[0], open.points()[open.points().len() - 1]);
    for kind in every_kind() {
        let flipped = kind.set_closed(!kind.is_closed());
        match kind {
            CurveKind::Nurbs(_)
            | CurveKind::Lagrange(_)
            | CurveKind::CubicHermite(_)
            | CurveKind::QuinticHermite(_) => assert!(flipped.is_err()),
            _ if kind.points().len() < 3 => assert!(matches!(
                flipped,
                Err(CurveError::KindTooFewPoints { needed: 3, .. })
            )),
            _ => assert_eq!(flipped.unwrap().is_closed(), !kind.is_closed()),
        }
    }
}

#[test]
fn extrude_adds_a_point_at_either_end() {
    for kind in every_kind().into_iter().filter(|k| !k.is_closed()) {
        let to = DVec3::new(-2.0, 1.0, 0.0);
        for end in [CurveEnd::Start, CurveEnd::End] {
            let e = kind.extrude(end, to).unwrap();
            let f = e.to_nurbs().unwrap().curve;
            let (a, b) = f.domain();
            let at = if end == CurveEnd::Start { a } else { b };
            assert!(
                (f.point(at) - to).length() < 1e-9,
                "{} {end:?}",
                kind.name()
            );
        }
    }
}

#[test]
fn splitting_at_a_point_on_the_curve_inserts_nothing() {
    for kind in every_kind().into_iter().filter(|k| !k.is_closed()) {
        // The middle point the curve passes through, if the kind has one.
        let n = kind.points().len();
        let Some((index, t)) = (1..n - 1).find_map(|i| Some((i, kind.on_curve_parameter(i)?)))
        else {
            continue;
        };
        assert_eq!(kind.point_at_parameter(t), Some(index), "{}", kind.name());
        let (l, r) = kind.split(t).unwrap();
        // The shared point is in both halves once; nothing else is added.
        assert_eq!(
            l.points().len() + r.points().len(),
            n + 1,
            "{}",
            kind.name()
        );
        assert_eq!(l.points().last(), Some(&kind.points()[index]));
        assert_eq!(r.points().first(), Some(&kind.points()[index]));
    }
}

#[test]
fn tangent_handles_end_at_the_bezier_points_beside_each_key() {
    for kind in every_kind() {
        let handles = kind.tangent_handles();
        let hermite_family = matches!(
            kind,
            CurveKind::CubicHermite(_)
                | CurveKind::QuinticHermite(_)
                | CurveKind::CatmullRom(_)
                | CurveKind::KochanekBartels(_)
                | CurveKind::CubicSpline(_)
        );
        assert_eq!(!handles.is_empty(), hermite_family, "{}", kind.name());
        if !hermite_family || kind.is_closed() {
            continue;
        }
        let n = kind.points().len();
        assert_eq!(handles.len(), 2 * n - 2, "{}", kind.name());
        // The NURBS form's control points are the Bézier polygon: each
        // handle's end is one of them (the control point beside its key).
        let form = kind.to_nurbs().unwrap().curve;
        for h in &handles {
            let nearest = form
                .points()
                .iter()
                .map(|c| c.distance(h.end))
                .fold(f64::MAX, f64::min);
            assert!(nearest < 1e-9, "{} handle {h:?}: {nearest}", kind.name());
        }
    }
}

#[test]
fn dragging_a_hermite_handle_sets_its_tangent() {
    for kind in every_kind().into_iter().filter(|k| k.handles_editable()) {
        let n = kind.points().len();
        let edit = kind.edit_points();
        assert_eq!(edit.len(), n + 2 * n - 2, "{}", kind.name());
        let k = 4; // key 2's outgoing handle (key 0 has only an outgoing one)
        let handle = kind.tangent_handles()[k];
        let target = handle.end + DVec3::new(0.3, -0.2, 0.1);
        let moved = kind.set_points(&[(n + k, target)]).unwrap();
        assert_eq!(moved.points(), kind.points(), "the keys stay");
        let after = moved.tangent_handles()[k];
        assert!(after.end.distance(target) < 1e-12, "{}", kind.name());
        // The incoming handle of the same key mirrors it (one tangent).
        let incoming = moved.tangent_handles()[k - 1];
        assert_eq!(incoming.point, handle.point);
        let p = moved.points()[handle.point];
        assert!((incoming.end - p + (target - p)).length() < 1e-12);
        // Moving the key carries its handles.
        let shift = DVec3::new(0.0, 1.0, 0.0);
        let carried = moved.set_points(&[(handle.point, p + shift)]).unwrap();
        assert!(carried.tangent_handles()[k].end.distance(target + shift) < 1e-12);
    }
}

#[test]
fn auto_joints_follow_their_neighbouring_anchors() {
    let pb = poly_bezier().set_join(1, Join::Auto).unwrap();
    let handles_on_chord = |k: &CurveKind| {
        let q = k.points();
        let dir = (q[9] - q[3]).normalize();
        assert!(((q[6] - q[5]).normalize() - dir).length() < 1e-12);
        assert!(((q[7] - q[6]).normalize() - dir).length() < 1e-12);
        assert!(((q[6] - q[5]).length() - (q[6] - q[3]).length() / 3.0).abs() < 1e-12);
        assert!(((q[7] - q[6]).length() - (q[9] - q[6]).length() / 3.0).abs() < 1e-12);
    };
    handles_on_chord(&pb);
    // A neighbouring anchor moves: the auto handles are placed again.
    let moved = pb.set_points(&[(9, DVec3::new(7.0, 3.0, 1.0))]).unwrap();
    handles_on_chord(&moved);
    let CurveKind::PolyBezier(PolyBezier { joins, .. }) = &moved else {
        panic!("poly-Bézier")
    };
    assert_eq!(joins[1], Join::Auto);
    // Dragging one of its handles makes the joint aligned (G1), as Blender.
    let to = moved.points()[7] + DVec3::new(0.0, 0.5, 0.0);
    let dragged = moved.set_points(&[(7, to)]).unwrap();
    let CurveKind::PolyBezier(PolyBezier { joins, .. }) = &dragged else {
        panic!("poly-Bézier")
    };
    assert_eq!(joins[1], Join::G1);
    let q = dragged.points();
    assert_eq!(q[7], to);
    assert!(((q[6] - q[5]).normalize() - (q[7] - q[6]).normalize()).length() < 1e-12);
}
