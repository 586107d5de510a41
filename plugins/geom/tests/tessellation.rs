//! Curve and surface tessellation against the exact shapes: every
//! breakpoint of a curve is a vertex (no corner lost), straight pieces get
//! no others, the polyline and the triangles stay within the tolerance of
//! the curve and the surface measured both ways at dense samples, and the
//! counts follow the shape's curvature, not its parameterisation (a
//! rational patch with extreme weights stays bounded).

use hedra_geom::DVec3;
use hedra_geom::curves::{
    CatmullRom, Chaikin, CubicHermite, CubicSpline, Curve, CurveKind, Fractal, FractalRule, Join,
    KochanekBartels, Lagrange, NurbsCurve, Parameterization, PolyBezier, QuinticHermite,
};
use hedra_geom::surfaces::tessellate::{
    MAX_CELLS, SurfaceMesh, curve_parameters, surface_parameters, tessellate, tessellate_nurbs,
};
use hedra_geom::surfaces::{NurbsSurface, Surface};

fn v(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + t * ab)).length()
}

/// A curve of every kind (their NURBS forms are what is drawn and exported).
fn kinds() -> Vec<(&'static str, CurveKind)> {
    let zig = vec![
        v(0.0, 0.0),
        v(1.0, 1.0),
        v(2.0, 0.0),
        v(3.0, 1.0),
        v(4.0, 0.0),
    ];
    vec![
        (
            "Lagrange",
            CurveKind::Lagrange(Lagrange {
                points: zig.clone(),
                parameterization: Parameterization::Centripetal,
            }),
        ),
        (
            "CubicHermite",
            CurveKind::CubicHermite(CubicHermite {
                points: zig.clone(),
                tangents: vec![DVec3::X; 5],
            }),
        ),
        (
            "QuinticHermite",
            CurveKind::QuinticHermite(QuinticHermite {
                points: zig.clone(),
                tangents: vec![DVec3::X; 5],
                accelerations: vec![DVec3::Y; 5],
            }),
        ),
        (
            "CatmullRom",
            CurveKind::CatmullRom(CatmullRom {
                points: zig.clone(),
                parameterization: Parameterization::Chord,
                closed: true,
            }),
        ),
        (
            "KochanekBartels",
            CurveKind::KochanekBartels(KochanekBartels {
                points: zig.clone(),
                keys: vec![
                    hedra_geom::curves::interpolating::Tbc {
                        continuity: -0.8,
                        ..Default::default()
                    };
                    5
                ],
                closed: false,
            }),
        ),
        (
            "CubicSpline",
            CurveKind::CubicSpline(CubicSpline {
                points: zig.clone(),
                parameterization: Parameterization::Uniform,
                ends: Default::default(),
            }),
        ),
        (
            "Chaikin",
            CurveKind::Chaikin(Chaikin {
                points: zig.clone(),
                level: 5,
                closed: true,
            }),
        ),
        (
            "PolyBezier",
            CurveKind::PolyBezier(PolyBezier {
                points: vec![
                    v(0.0, 0.0),
                    v(1.0, 1.0),
                    v(2.0, 1.0),
                    v(3.0, 0.0),
                    v(3.0, 1.0),
                    v(4.0, 1.0),
                    v(4.2, 0.0),
                ],
                joins: vec![Join::C0],
                closed: false,
            }),
        ),
        (
            "Koch",
            CurveKind::Fractal(Fractal {
                rule: FractalRule::Koch,
                points: vec![v(0.0, 0.0), v(1.0, 0.0)],
                level: 4,
                closed: false,
                normal: DVec3::Z,
            }),
        ),
        (
            "QuadraticKoch",
            CurveKind::Fractal(Fractal {
                rule: FractalRule::QuadraticKoch,
                points: vec![v(0.0, 0.0), v(0.0, 2.0), v(2.0, 2.0), v(2.0, 0.0)],
                level: 2,
                closed: true,
                normal: DVec3::Z,
            }),
        ),
        (
            "Nurbs",
            CurveKind::Nurbs(
                NurbsCurve::new(
                    3,
                    hedra_geom::curves::nurbs::clamped_uniform_knots(3, 5),
                    zig.clone(),
                    vec![1.0, 2.0, 1.0, 0.5, 1.0],
                )
                .unwrap(),
            ),
        ),
    ]
}

/// The largest distance, at 32 samples per piece, from the curve to its
/// polyline (each sample to its own piece's chord: an upper bound of its
/// distance to the polyline), and from the polyline to the curve (each
/// point of a chord to the nearest of the 32 samples of its piece and the
/// piece's ends: an upper bound of its distance to the curve).
fn chord_errors(curve: &dyn Curve, ts: &[f64]) -> (f64, f64) {
    let (mut to_chord, mut to_curve) = (0.0f64, 0.0f64);
    for w in ts.windows(2) {
        let (a, b) = (curve.point(w[0]), curve.point(w[1]));
        let samples: Vec<DVec3> = (0..=32)
            .map(|k| curve.point(w[0] + (w[1] - w[0]) * k as f64 / 32.0))
            .collect();
        for p in &samples {
            to_chord = to_chord.max(distance_to_segment(*p, a, b));
        }
        for k in 0..=32 {
            let q = a.lerp(b, k as f64 / 32.0);
            // The nearest point of the curve's piece, by its samples and
            // then along the segments between them (the piece is within
            // `to_chord` of those anyway).
            let near = samples
                .windows(2)
                .map(|s| distance_to_segment(q, s[0], s[1]))
                .fold(f64::INFINITY, f64::min);
            to_curve = to_curve.max(near);
        }
    }
    (to_chord, to_curve)
}

#[test]
fn every_breakpoint_is_a_vertex_and_straight_pieces_get_no_others() {
    for (name, kind) in kinds() {
        let curve = kind.to_nurbs().unwrap().curve;
        let ts = curve_parameters(&curve, 1e-3);
        let breaks = curve.breakpoints();
        assert!(ts.windows(2).all(|w| w[0] < w[1]), "{name}: increasing");
        assert_eq!(
            (ts.first(), ts.last()),
            (breaks.first(), breaks.last()),
            "{name}"
        );
        for b in &breaks {
            assert!(ts.contains(b), "{name}: breakpoint {b} is not a vertex");
        }
        if curve.degree() == 1 {
            assert_eq!(ts, breaks, "{name}: a polyline is its own vertices");
        } else {
            assert!(ts.len() > breaks.len(), "{name}: curved spans are cut");
        }
        let (to_chord, to_curve) = chord_errors(&curve, &ts);
        assert!(
            to_chord <= 1e-3 && to_curve <= 1e-3,
            "{name}: {to_chord}, {to_curve}"
        );
    }
}

#[test]
fn the_koch_curve_of_level_four_is_its_257_points() {
    let kind = CurveKind::Fractal(Fractal {
        rule: FractalRule::Koch,
        points: vec![v(0.0, 0.0), v(1.0, 0.0)],
        level: 4,
        closed: false,
        normal: DVec3::Z,
    });
    let curve = kind.to_nurbs().unwrap().curve;
    let ts = curve_parameters(&curve, 1e-4);
    assert_eq!(ts.len(), 257);
    let points: Vec<DVec3> = ts.iter().map(|&t| curve.point(t)).collect();
    let exact = kind.level_polygon().unwrap();
    for (p, q) in points.iter().zip(&exact) {
        assert!((*p - *q).length() < 1e-14, "{p} vs {q}");
    }
    let length: f64 = points.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    assert!((length - (4.0f64 / 3.0).powi(4)).abs() < 1e-12, "{length}");
}

#[test]
fn a_circle_is_cut_within_the_tolerance_both_ways_and_no_finer_than_it_needs() {
    let circle = NurbsCurve::circle(DVec3::ZERO, 1.0);
    for tol in [1e-2, 1e-3, 1e-4, 1e-6] {
        let ts = curve_parameters(&circle, tol);
        let (to_chord, to_curve) = chord_errors(&circle, &ts);
        assert!(to_chord <= tol, "tol {tol}: curve to chord {to_chord}");
        assert!(to_curve <= tol, "tol {tol}: chord to curve {to_curve}");
        // Exactly: every chord's middle is `1 − cos(θ/2)` inside.
        let worst = ts
            .windows(2)
            .map(|w| 1.0 - ((circle.point(w[0]) + circle.point(w[1])) / 2.0).length())
            .fold(0.0, f64::max);
        assert!(worst <= tol, "tol {tol}: sag {worst}");
        // Not wasteful: the fewest equal chords within tol number
        // `2π / (2 acos(1 − tol))`; the spread keeps within half as many
        // again (its pieces equal only within the sampled spans).
        let fewest = (std::f64::consts::TAU / (2.0 * (1.0 - tol).acos())).ceil();
        let pieces = (ts.len() - 1) as f64;
        assert!(
            pieces >= fewest && pieces <= 1.5 * fewest + 4.0,
            "tol {tol}: {pieces} pieces, fewest {fewest}"
        );
        assert!(worst >= 0.25 * tol, "tol {tol}: sag {worst} is far inside");
    }
}

#[test]
fn extreme_weights_on_a_curve_do_not_blow_up_its_pieces() {
    // A quadratic arc with weights 1 : 1000 : 1: nearly the control
    // polygon's corner, its parameter racing through the corner.
    let arc = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![v(0.0, 0.0), v(1.0, 1.0), v(2.0, 0.0)],
        vec![1.0, 1000.0, 1.0],
    )
    .unwrap();
    let ts = curve_parameters(&arc, 1e-4);
    let (to_chord, to_curve) = chord_errors(&arc, &ts);
    assert!(
        to_chord <= 1e-4 && to_curve <= 1e-4,
        "{to_chord}, {to_curve}"
    );
    assert!(ts.len() < 400, "{} parameters", ts.len());
    // A rational straight line (degree 1, any weights) is one segment.
    let line = NurbsCurve::new(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![v(0.0, 0.0), v(1.0, 1.0)],
        vec![1.0, 50.0],
    )
    .unwrap();
    assert_eq!(curve_parameters(&line, 1e-6), vec![0.0, 1.0]);
}

/// The closest point on triangle `abc` to `p` (Ericson, *Real-Time
/// Collision Detection*, §5.1.5).
fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// The distance from `x` to the surface, as an upper bound: the nearest of
/// the surface points at `starts`, improved by Gauss-Newton steps on
/// `|S(u, v) − x|²` (each kept only when it brings the point nearer, so
/// the result is a distance to a point of the surface, never below the
/// true one's... nor, from a good start, much above it).
fn distance_to_surface(s: &dyn Surface, x: DVec3, starts: &[(f64, f64)]) -> f64 {
    let ((u0, u1), (v0, v1)) = s.domain();
    let (mut u, mut v) = starts
        .iter()
        .copied()
        .min_by(|a, b| {
            let da = (s.point(a.0, a.1) - x).length();
            let db = (s.point(b.0, b.1) - x).length();
            da.total_cmp(&db)
        })
        .unwrap();
    let mut best = (s.point(u, v) - x).length();
    for _ in 0..40 {
        let e = s.evaluate(u, v);
        let r = e.p - x;
        let (a, b, d) = (e.du.dot(e.du), e.du.dot(e.dv), e.dv.dot(e.dv));
        let det = a * d - b * b;
        if det.is_nan() || det.abs() <= 1e-300 {
            break;
        }
        let (fu, fv) = (r.dot(e.du), r.dot(e.dv));
        let (mut su, mut sv) = ((d * fu - b * fv) / det, (a * fv - b * fu) / det);
        let mut improved = false;
        if best == 0.0 || su.abs() + sv.abs() < 1e-15 {
            break;
        }
        for _ in 0..12 {
            let (nu, nv) = ((u - su).clamp(u0, u1), (v - sv).clamp(v0, v1));
            let dist = (s.point(nu, nv) - x).length();
            if dist < best {
                (u, v, best, improved) = (nu, nv, dist, true);
                break;
            }
            su *= 0.5;
            sv *= 0.5;
        }
        if !improved {
            break;
        }
    }
    best
}

/// Both one-sided distances between a grid tessellation (on `us × vs`)
/// and its surface, as upper bounds: each triangle at 10 barycentric
/// points (corners, edge thirds, centre) to the surface
/// ([`distance_to_surface`]); and the surface at 5 × 5 points of every
/// cell (its corners, edge quarters and inside) to the nearer of the
/// cell's two triangles.
fn surface_errors(s: &dyn Surface, m: &SurfaceMesh, us: &[f64], vs: &[f64]) -> (f64, f64) {
    let mut to_surface = 0.0f64;
    // The corners, edge thirds, and the centre.
    let bary: Vec<(f64, f64, f64)> = (0..=3)
        .flat_map(|i| (0..=3 - i).map(move |j| (i, j)))
        .map(|(i, j)| {
            let (a, b) = (i as f64 / 3.0, j as f64 / 3.0);
            (a, b, 1.0 - a - b)
        })
        .collect();
    let corners = [0, 3, 9];
    assert_eq!(
        corners.map(|k| bary[k]),
        [(0.0, 0.0, 1.0), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)]
    );
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| i as usize);
        let params: Vec<(f64, f64)> = bary
            .iter()
            .map(|&(x, y, z)| {
                (
                    x * m.params[a].0 + y * m.params[b].0 + z * m.params[c].0,
                    x * m.params[a].1 + y * m.params[b].1 + z * m.params[c].1,
                )
            })
            .collect();
        for (&(x, y, z), &uv) in bary.iter().zip(&params) {
            let p = x * m.positions[a] + y * m.positions[b] + z * m.positions[c];
            // From the surface at the point's own parameters and the
            // corners' (the corners are on the surface).
            let starts = [uv, params[0], params[3], params[9]];
            to_surface = to_surface.max(distance_to_surface(s, p, &starts));
        }
    }
    let mut to_mesh = 0.0f64;
    let cv = vs.len() - 1;
    for (i, wu) in us.windows(2).enumerate() {
        for (j, wv) in vs.windows(2).enumerate() {
            let tris = &m.triangles[2 * (i * cv + j)..2 * (i * cv + j) + 2];
            for a in 0..=4 {
                for b in 0..=4 {
                    let u = wu[0] + (wu[1] - wu[0]) * a as f64 / 4.0;
                    let w = wv[0] + (wv[1] - wv[0]) * b as f64 / 4.0;
                    let p = s.point(u, w);
                    let d = tris
                        .iter()
                        .map(|t| {
                            let [x, y, z] = t.map(|k| m.positions[k as usize]);
                            (closest_on_triangle(p, x, y, z) - p).length()
                        })
                        .fold(f64::INFINITY, f64::min);
                    to_mesh = to_mesh.max(d);
                }
            }
        }
    }
    (to_surface, to_mesh)
}

#[test]
fn a_sphere_is_tessellated_within_the_tolerance_both_ways() {
    let s = NurbsSurface::sphere(DVec3::ZERO, 1.0);
    for tol in [1e-2, 1e-3] {
        let (us, vs) = surface_parameters(&s, tol);
        let m = tessellate(&s, tol);
        assert_eq!(m.triangles.len(), 2 * (us.len() - 1) * (vs.len() - 1));
        // Exactly, for a sphere: every point of every triangle is at most
        // tol inside (a chord never bulges out), checked at 21 points each.
        let mut inside = 0.0f64;
        for t in &m.triangles {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            for i in 0..=5 {
                for j in 0..=5 - i {
                    let (x, y) = (i as f64 / 5.0, j as f64 / 5.0);
                    let p = x * a + y * b + (1.0 - x - y) * c;
                    let r = p.length();
                    assert!(r <= 1.0 + 1e-12, "tol {tol}: {p} bulges out");
                    inside = inside.max(1.0 - r);
                }
            }
        }
        assert!(inside <= tol, "tol {tol}: a triangle is {inside} inside");
        assert!(
            inside >= 0.25 * tol,
            "tol {tol}: {inside}, finer than needed"
        );
        let (to_surface, to_mesh) = surface_errors(&s, &m, &us, &vs);
        assert!(
            to_surface <= tol && to_mesh <= tol,
            "{to_surface}, {to_mesh}"
        );
        // The NURBS fast path makes the same grid.
        let fast = tessellate_nurbs(&s, tol);
        assert_eq!(fast.triangles, m.triangles);
        for (p, q) in fast.positions.iter().zip(&m.positions) {
            assert!((*p - *q).length() < 1e-12);
        }
    }
}

/// A 5 × 4 bicubic patch with the weights given, over a wavy net 4 × 3
/// units large.
fn wavy_patch(weights: Vec<f64>) -> NurbsSurface {
    let mut points = Vec::new();
    for i in 0..5 {
        for j in 0..4 {
            let y = ((i * 3 + j * 5) % 7) as f64 * 0.3;
            points.push(DVec3::new(i as f64, y, j as f64));
        }
    }
    NurbsSurface::new(
        3,
        3,
        hedra_geom::curves::nurbs::clamped_uniform_knots(3, 5),
        hedra_geom::curves::nurbs::clamped_uniform_knots(3, 4),
        5,
        4,
        points,
        weights,
    )
    .unwrap()
}

#[test]
fn a_rational_patch_with_extreme_weights_stays_bounded_and_within_tolerance() {
    let plain = wavy_patch(vec![1.0; 20]);
    let extreme = wavy_patch(
        (0..20)
            .map(|k| [0.01, 1.0, 100.0, 5.0, 0.2][k % 5])
            .collect(),
    );
    let one_heavy = wavy_patch((0..20).map(|k| if k == 7 { 1000.0 } else { 1.0 }).collect());
    // About 4e-4 of the patch's size (the export asks 1e-4; coarser here
    // to keep the dense check quick).
    let tol = 2e-3;
    let plain_cells = {
        let (us, vs) = surface_parameters(&plain, tol);
        (us.len() - 1) * (vs.len() - 1)
    };
    for (name, s) in [
        ("plain", &plain),
        ("extreme", &extreme),
        ("one heavy", &one_heavy),
    ] {
        let (us, vs) = surface_parameters(s, tol);
        let cells = (us.len() - 1) * (vs.len() - 1);
        // Bounded: the weights change the shape (a bump towards the
        // heavy point), not the size, so the count stays of the plain
        // patch's order; before, the parametric second derivatives asked
        // for hundreds of thousands of triangles.
        // Bounded: the weights change the shape (bumps towards the heavy
        // points, flats by the light ones), not the size, so the count
        // stays of the plain patch's order. Before, the parametric second
        // derivatives asked for 2048 × 2048 cells (at the export's
        // tolerance: 8,388,608 triangles for `extreme`, 29,212 plain).
        assert!(
            cells <= 8 * plain_cells && cells < MAX_CELLS / 16,
            "{name}: {cells} cells, plain {plain_cells}"
        );
        let m = tessellate_nurbs(s, tol);
        assert_eq!(m.triangles.len(), 2 * cells);
        let (to_surface, to_mesh) = surface_errors(s, &m, &us, &vs);
        assert!(
            to_surface <= tol && to_mesh <= tol,
            "{name}: {to_surface}, {to_mesh} (tol {tol}, {cells} cells)"
        );
        // Every knot is a grid line.
        let (ku, kv) = s.knots();
        assert!(ku.iter().all(|k| us.contains(k)) && kv.iter().all(|k| vs.contains(k)));
    }
}
