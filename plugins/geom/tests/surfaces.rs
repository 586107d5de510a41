//! Surfaces against known values: the exact NURBS sphere and cylinder,
//! Bézier surfaces as NURBS, derivatives against finite differences, knot
//! insertion, Bézier triangles (partition of unity, elevation, split,
//! directional derivatives), ray picking, tessellation tolerance, and the
//! continuity of curve joints.

use hedra_geom::DVec3;
use hedra_geom::curves::analysis::continuity;
use hedra_geom::curves::{Bezier, NurbsCurve};
use hedra_geom::surfaces::intersect::ray_surface;
use hedra_geom::surfaces::tessellate::{curve_parameters, tessellate};
use hedra_geom::surfaces::{BezierSurface, BezierTriangle, BilinearPatch, NurbsSurface, Surface};

fn close(a: DVec3, b: DVec3, tol: f64) -> bool {
    (a - b).length() <= tol
}

fn grid(surface: &dyn Surface, n: usize) -> Vec<(f64, f64)> {
    let ((u0, u1), (v0, v1)) = surface.domain();
    (0..=n)
        .flat_map(|i| {
            (0..=n).map(move |j| {
                (
                    u0 + (u1 - u0) * i as f64 / n as f64,
                    v0 + (v1 - v0) * j as f64 / n as f64,
                )
            })
        })
        .collect()
}

#[test]
fn the_nurbs_sphere_and_cylinder_are_exact() {
    let c = DVec3::new(1.0, -2.0, 0.5);
    let s = NurbsSurface::sphere(c, 2.0);
    for (u, v) in grid(&s, 40) {
        let e = s.evaluate(u, v);
        assert!(
            ((e.p - c).length() - 2.0).abs() < 1e-12,
            "radius at ({u}, {v})"
        );
        let n = e.normal();
        if n != DVec3::ZERO {
            // Away from the poles the normal points outward, along the radius.
            assert!(close(n, (e.p - c) / 2.0, 1e-9), "normal {n} at ({u}, {v})");
        }
    }
    let cyl = NurbsSurface::cylinder(0.5, 3.0);
    for (u, v) in grid(&cyl, 20) {
        let p = cyl.point(u, v);
        assert!((p.x.hypot(p.z) - 0.5).abs() < 1e-12 && (-1e-12..=3.0 + 1e-12).contains(&p.y));
    }
}

fn bezier_net() -> BezierSurface {
    let mut pts = Vec::new();
    for i in 0..4 {
        for j in 0..3 {
            pts.push(DVec3::new(
                i as f64,
                ((i * j) as f64).sin(),
                j as f64 + 0.3 * i as f64,
            ));
        }
    }
    BezierSurface::new(4, 3, pts).unwrap()
}

#[test]
fn a_bezier_surface_is_a_nurbs_surface_with_clamped_knots() {
    let b = bezier_net();
    let n = NurbsSurface::from_bezier(4, 3, b.points.clone()).unwrap();
    for (u, v) in grid(&b, 12) {
        let (x, y) = (b.evaluate(u, v), n.evaluate(u, v));
        for (p, q) in [
            (x.p, y.p),
            (x.du, y.du),
            (x.dv, y.dv),
            (x.duu, y.duu),
            (x.duv, y.duv),
            (x.dvv, y.dvv),
        ] {
            assert!(close(p, q, 1e-12), "({u}, {v}): {p} vs {q}");
        }
    }
    // Its boundary is the Bézier curve of the boundary points.
    let edge = b.boundary_u0();
    for k in 0..=10 {
        let t = k as f64 / 10.0;
        assert!(close(b.point(0.0, t), edge.de_casteljau(t), 1e-14));
    }
}

/// Partial derivatives against central differences.
fn check_partials(s: &dyn Surface) {
    let h = 1e-5;
    let ((u0, u1), (v0, v1)) = s.domain();
    for (u, v) in grid(s, 9) {
        let (u, v) = (
            u.clamp(u0 + 2.0 * h, u1 - 2.0 * h),
            v.clamp(v0 + 2.0 * h, v1 - 2.0 * h),
        );
        let e = s.evaluate(u, v);
        let fu = (s.point(u + h, v) - s.point(u - h, v)) / (2.0 * h);
        let fv = (s.point(u, v + h) - s.point(u, v - h)) / (2.0 * h);
        let fuv = (s.point(u + h, v + h) - s.point(u + h, v - h) - s.point(u - h, v + h)
            + s.point(u - h, v - h))
            / (4.0 * h * h);
        let fuu = (s.point(u + h, v) - 2.0 * e.p + s.point(u - h, v)) / (h * h);
        assert!(
            close(e.du, fu, 1e-6 * (1.0 + fu.length())),
            "S_u at ({u}, {v}): {} vs {fu}",
            e.du
        );
        assert!(
            close(e.dv, fv, 1e-6 * (1.0 + fv.length())),
            "S_v at ({u}, {v})"
        );
        assert!(
            close(e.duv, fuv, 1e-3 * (1.0 + fuv.length())),
            "S_uv at ({u}, {v}): {} vs {fuv}",
            e.duv
        );
        assert!(
            close(e.duu, fuu, 1e-3 * (1.0 + fuu.length())),
            "S_uu at ({u}, {v}): {} vs {fuu}",
            e.duu
        );
    }
}

#[test]
fn partial_derivatives_match_finite_differences() {
    check_partials(&bezier_net());
    check_partials(&NurbsSurface::sphere(DVec3::ZERO, 1.0));
    let mut wavy = NurbsSurface::from_bezier(4, 3, bezier_net().points).unwrap();
    wavy.set_weight(1, 1, 3.0).unwrap();
    wavy.set_weight(2, 0, 0.4).unwrap();
    check_partials(&wavy);
    check_partials(&BilinearPatch {
        corners: [DVec3::ZERO, DVec3::X, DVec3::Z, DVec3::new(1.0, 1.0, 1.0)],
    });
}

#[test]
fn surface_knot_insertion_and_weights() {
    let s = NurbsSurface::sphere(DVec3::ZERO, 1.0);
    let r = s
        .insert_knot_u(0.1)
        .unwrap()
        .insert_knot_v(0.3)
        .unwrap()
        .insert_knot_u(0.6)
        .unwrap();
    assert_eq!(r.size(), (s.size().0 + 2, s.size().1 + 1));
    for (u, v) in grid(&s, 25) {
        assert!(
            close(s.point(u, v), r.point(u, v), 1e-12),
            "({u}, {v}) moved"
        );
    }
    let mut w = s.clone();
    assert!(w.set_weight(0, 0, -1.0).is_err());
    assert!(w.set_weight(99, 0, 1.0).is_err());
    assert_eq!(w, s, "refused edits change nothing");
}

fn triangle() -> BezierTriangle {
    // Degree 3: 10 points with some height.
    let n = 3;
    let mut pts = Vec::new();
    for i in 0..=n {
        for j in 0..=n - i {
            let (x, z) = (i as f64, j as f64);
            pts.push(DVec3::new(x + 0.5 * z, (x * z) * 0.3 - 0.2 * x, z));
        }
    }
    BezierTriangle::new(3, pts).unwrap()
}

fn bary(n: usize) -> Vec<DVec3> {
    let mut out = Vec::new();
    for i in 0..=n {
        for j in 0..=n - i {
            let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
            out.push(DVec3::new(u, v, 1.0 - u - v));
        }
    }
    out
}

#[test]
fn bezier_triangles_de_casteljau_bernstein_elevation_and_split_agree() {
    let t = triangle();
    let up = t.elevate();
    assert_eq!(up.points.len(), 15);
    for b in bary(8) {
        let p = t.evaluate(b);
        assert!(close(p, t.bernstein_point(b), 1e-12));
        assert!(close(p, up.evaluate(b), 1e-12), "elevation moved {b}");
    }
    // Corners interpolate b_n00, b_0n0, b_00n.
    assert!(close(t.evaluate(DVec3::X), t.point(3, 0), 1e-15));
    assert!(close(t.evaluate(DVec3::Z), t.point(0, 0), 1e-15));
    // Split at an interior point: each part traces its share of the surface.
    let at = DVec3::new(0.2, 0.5, 0.3);
    let parts = t.split(at);
    let corners = [
        [DVec3::Y, DVec3::Z],
        [DVec3::Z, DVec3::X],
        [DVec3::X, DVec3::Y],
    ];
    for (part, [e1, e2]) in parts.iter().zip(corners) {
        for local in bary(6) {
            let global = local.x * at + local.y * e1 + local.z * e2;
            assert!(
                close(part.evaluate(local), t.evaluate(global), 1e-12),
                "split part at {local}"
            );
        }
    }
}

#[test]
fn bezier_triangle_directional_derivative_matches_differences() {
    let t = triangle();
    let d = DVec3::new(1.0, -0.5, -0.5);
    let h = 1e-6;
    for b in bary(5).into_iter().filter(|b| b.min_element() > 0.1) {
        let fd = (t.evaluate(b + h * d) - t.evaluate(b - h * d)) / (2.0 * h);
        let exact = t.directional_derivative(b, d);
        assert!(
            close(exact, fd, 1e-6 * (1.0 + fd.length())),
            "{exact} vs {fd}"
        );
    }
    // The partition of unity: a triangle whose points are all equal is that point.
    let flat = BezierTriangle::new(2, vec![DVec3::ONE; 6]).unwrap();
    assert!(close(
        flat.evaluate(DVec3::new(0.3, 0.3, 0.4)),
        DVec3::ONE,
        1e-15
    ));
}

#[test]
fn a_ray_picks_the_exact_surface_point() {
    let s = NurbsSurface::sphere(DVec3::ZERO, 1.0);
    let origin = DVec3::new(0.3, 5.0, -0.2);
    let hit = ray_surface(&s, origin, DVec3::NEG_Y).unwrap();
    let want_y = (1.0f64 - 0.09 - 0.04).sqrt();
    assert!(
        close(hit.point, DVec3::new(0.3, want_y, -0.2), 1e-10),
        "{:?}",
        hit
    );
    assert!((hit.t - (5.0 - want_y)).abs() < 1e-10);
    assert!(
        ray_surface(&s, DVec3::new(3.0, 5.0, 0.0), DVec3::NEG_Y).is_none(),
        "a miss is None"
    );
}

/// The distance from the origin to the triangle `abc` (its closest point
/// by Voronoi regions, Ericson, *Real-Time Collision Detection*, §5.1.5).
fn origin_distance(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let p = DVec3::ZERO;
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a.length();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return (a + ab * (d1 / (d1 - d3))).length();
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return (a + ac * (d2 / (d2 - d6))).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))).length();
    }
    let denom = va + vb + vc;
    if denom.abs() < 1e-300 {
        return a.length().min(b.length()).min(c.length());
    }
    (a + ab * (vb / denom) + ac * (vc / denom)).length()
}

/// The unit sphere's tessellation against the sphere, exactly and both
/// ways. Every triangle lies inside (no point further than 1 from the
/// centre) and its deepest point, its point nearest the centre, is at most
/// `tol` inside: so the mesh is within `tol` of the sphere. And the
/// triangles' solid angles (Van Oosterom & Strackee, IEEE Trans. Biomed.
/// Eng. 30(2), 1983) add up to 4π, so their radial projection covers the
/// sphere: every point of the sphere is the projection of a mesh point at
/// most `tol` below it, and the sphere is within `tol` of the mesh.
#[test]
fn tessellation_stays_within_its_tolerance() {
    let s = NurbsSurface::sphere(DVec3::ZERO, 1.0);
    for tol in [1e-2, 1e-3, 1e-4] {
        let m = tessellate(&s, tol);
        let (mut deepest, mut solid_angle) = (0.0f64, 0.0f64);
        for t in &m.triangles {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            for p in [a, b, c] {
                assert!((p.length() - 1.0).abs() < 1e-12, "a corner off the sphere");
            }
            deepest = deepest.max(1.0 - origin_distance(a, b, c));
            let (la, lb, lc) = (a.length(), b.length(), c.length());
            let num = a.dot(b.cross(c));
            let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
            solid_angle += 2.0 * num.atan2(den);
        }
        assert!(
            deepest <= tol,
            "tolerance {tol}: a triangle is {deepest} deep"
        );
        // And not needlessly fine: some triangle uses a good part of it.
        assert!(
            deepest >= 0.25 * tol,
            "tolerance {tol}: only {deepest} deep"
        );
        let four_pi = 4.0 * std::f64::consts::PI;
        assert!(
            (solid_angle.abs() - four_pi).abs() < 1e-9,
            "tolerance {tol}: the triangles cover {solid_angle} sr, not 4π"
        );
    }
    // A circle's chords: every chord is inside, its middle (its deepest
    // point) at most tol inside, and the chords cover every angle.
    let circle = NurbsCurve::circle(DVec3::ZERO, 1.0);
    for tol in [1e-2, 1e-4] {
        let ts = curve_parameters(&circle, tol);
        let mut turned = 0.0;
        for w in ts.windows(2) {
            use hedra_geom::curves::Curve;
            let (a, b) = (circle.point(w[0]), circle.point(w[1]));
            let sag = 1.0 - ((a + b) / 2.0).length();
            assert!(
                (0.0..=tol).contains(&sag),
                "tolerance {tol}: chord error {sag}"
            );
            turned += a.angle_between(b);
        }
        assert!((turned - std::f64::consts::TAU).abs() < 1e-9, "{turned}");
    }
}

#[test]
fn continuity_of_joined_bezier_segments() {
    let a = Bezier::new(vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::new(2.0, 1.0, 0.0),
        DVec3::new(3.0, 1.0, 0.0),
    ])
    .unwrap();
    // C1 continuation: b1 − b0 mirrors a3 − a2.
    let c1 = Bezier::new(vec![
        DVec3::new(3.0, 1.0, 0.0),
        DVec3::new(4.0, 1.0, 0.0),
        DVec3::new(5.0, 2.0, 0.0),
        DVec3::new(6.0, 2.0, 0.0),
    ])
    .unwrap();
    let k = continuity(&a, &c1, 1e-9);
    assert!(k.c0 && k.c1 && k.g1 && !k.c2, "{k:?}");
    // G1 only: same direction, twice the speed.
    let g1 = Bezier::new(vec![
        DVec3::new(3.0, 1.0, 0.0),
        DVec3::new(5.0, 1.0, 0.0),
        DVec3::new(6.0, 0.0, 0.0),
        DVec3::new(7.0, 0.0, 0.0),
    ])
    .unwrap();
    let k = continuity(&a, &g1, 1e-9);
    assert!(k.c0 && k.g1 && !k.c1, "{k:?}");
    // A corner.
    let corner = Bezier::new(vec![DVec3::new(3.0, 1.0, 0.0), DVec3::new(3.0, 2.0, 0.0)]).unwrap();
    let k = continuity(&a, &corner, 1e-9);
    assert!(k.c0 && !k.g1, "{k:?}");
    // The same curve split in half is C2 at the split; split elsewhere the
    // halves are reparameterised differently: G2 but not C1.
    let (l, r) = a.split(0.5);
    let k = continuity(&l, &r, 1e-9);
    assert!(k.c2 && k.g2, "{k:?}");
    let (l, r) = a.split(0.4);
    let k = continuity(&l, &r, 1e-9);
    assert!(k.g2 && !k.c1, "{k:?}");
}

mod fast_paths {
    use super::*;
    use hedra_geom::curves::Curve;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(32))]

        /// The batch evaluators give what the general ones give.
        #[test]
        fn batch_evaluation_equals_the_general_evaluator(
            coords in proptest::collection::vec(-3.0f64..3.0, 3 * 30),
            weights in proptest::collection::vec(0.2f64..4.0, 30),
            pu in 1usize..5,
            pv in 1usize..4,
            ts in proptest::collection::vec(0.0f64..=1.0, 12),
        ) {
            let pts: Vec<DVec3> = coords.chunks(3).map(|c| DVec3::new(c[0], c[1], c[2])).collect();
            // A curve on 8 points and a 6 × 5 surface from the same data.
            let knots = hedra_geom::curves::nurbs::clamped_uniform_knots(pu, 8);
            let c = NurbsCurve::new(pu, knots, pts[..8].to_vec(), weights[..8].to_vec()).unwrap();
            let fast = c.points_at(&ts);
            for (t, p) in ts.iter().zip(&fast) {
                prop_assert!(close(*p, c.point(*t), 1e-12), "curve at {}", t);
            }
            let s = NurbsSurface::new(
                pu, pv,
                hedra_geom::curves::nurbs::clamped_uniform_knots(pu, 6),
                hedra_geom::curves::nurbs::clamped_uniform_knots(pv, 5),
                6, 5, pts[..30].to_vec(), weights.clone(),
            ).unwrap();
            let (us, vs) = (&ts[..6], &ts[6..]);
            let (grid, normals) = s.grid(us, vs, true);
            for (a, &u) in us.iter().enumerate() {
                for (b, &v) in vs.iter().enumerate() {
                    let e = s.evaluate(u, v);
                    prop_assert!(close(grid[a * vs.len() + b], e.p, 1e-12), "surface at ({}, {})", u, v);
                    let n = e.normal();
                    if n.length() > 0.5 {
                        prop_assert!(close(normals[a * vs.len() + b], n, 1e-8), "normal at ({}, {})", u, v);
                    }
                }
            }
        }
    }
}

#[test]
fn a_bezier_triangle_and_a_quad_patch_join_with_g1_when_their_nets_line_up() {
    use hedra_geom::surfaces::joins::{Boundary, join, surface_boundary, triangle_boundary};
    // A quad patch in the plane y = 0 for x ∈ [0, 1], z ∈ [0, 1], bilinear
    // as a degree-2 Bézier net, whose edge x = 1 is shared with a triangle.
    let mut quad = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            quad.push(DVec3::new(i as f64 / 2.0, 0.0, j as f64 / 2.0));
        }
    }
    let quad = BezierSurface::new(3, 3, quad).unwrap();
    // The triangle's edge u = 0 (from w-corner to v-corner) is x = 1, z ∈ [0, 1].
    let flat_triangle = |lift: f64| {
        // b_ijk for degree 2: rows i = 0 (on the shared edge), 1, 2.
        BezierTriangle::new(
            2,
            vec![
                DVec3::new(1.0, 0.0, 0.0),   // b002 (w corner)
                DVec3::new(1.0, 0.0, 0.5),   // b011
                DVec3::new(1.0, 0.0, 1.0),   // b020 (v corner)
                DVec3::new(1.5, lift, 0.25), // b101: the row next to the edge
                DVec3::new(1.5, lift, 0.75), // b110
                DVec3::new(2.0, 0.0, 0.5),   // b200 (u corner)
            ],
        )
        .unwrap()
    };
    let check = |tri: &BezierTriangle| {
        join(
            |t| surface_boundary(&quad, Boundary::U1, false, t),
            |t| triangle_boundary(tri, Boundary::TriangleU0, false, t),
            16,
            1e-12,
            1e-9,
        )
    };
    // Next row coplanar with the quad's last row (the G1 condition of seed 002): G1.
    let j = check(&flat_triangle(0.0));
    assert!(j.c0 && j.g1, "{j:?}");
    // Lift that row out of the plane: still C0, no longer G1.
    let j = check(&flat_triangle(0.3));
    assert!(j.c0 && !j.g1, "{j:?}");
}

#[test]
fn a_plane_cuts_the_sphere_in_a_circle() {
    use hedra_geom::surfaces::tessellate::{plane_section, tessellate_nurbs};
    let s = NurbsSurface::sphere(DVec3::ZERO, 1.0);
    let mesh = tessellate_nurbs(&s, 1e-4);
    let cut = plane_section(&mesh, DVec3::new(0.0, 0.6, 0.0), DVec3::Y);
    assert!(cut.len() > 50);
    for [p, q] in cut {
        for x in [p, q] {
            assert!((x.y - 0.6).abs() < 1e-12);
            assert!((x.length() - 1.0).abs() < 2e-4, "{}", x.length());
        }
    }
}

#[test]
fn surface_degree_elevation_keeps_the_surface() {
    let s = NurbsSurface::sphere(DVec3::ZERO, 1.0);
    let u = s.elevate_u().unwrap();
    let uv = u.elevate_v().unwrap();
    assert_eq!(u.degrees(), (3, 2));
    assert_eq!(uv.degrees(), (3, 3));
    for (a, b) in grid(&s, 20) {
        assert!(
            close(s.point(a, b), uv.point(a, b), 1e-12),
            "({a}, {b}) moved"
        );
    }
}

#[test]
fn bezier_surface_bernstein_form_equals_de_casteljau() {
    let b = bezier_net();
    for (u, v) in grid(&b, 10) {
        assert!(close(b.bernstein_point(u, v), b.point(u, v), 1e-13));
    }
}

/// At the sphere's poles the partial derivatives are parallel: the normal
/// is the limit around the pole (its direction from the centre), in the
/// grid evaluator, the generic tessellation and `unit_normal`.
#[test]
fn the_sphere_has_unit_normals_at_its_poles() {
    use hedra_geom::surfaces::{NurbsSurface, Surface};
    let centre = glam::DVec3::new(1.0, 2.0, 3.0);
    let sphere = NurbsSurface::sphere(centre, 2.0);
    let ((u0, u1), (v0, v1)) = sphere.domain();
    let us: Vec<f64> = (0..=8).map(|i| u0 + (u1 - u0) * i as f64 / 8.0).collect();
    let vs: Vec<f64> = (0..=8).map(|j| v0 + (v1 - v0) * j as f64 / 8.0).collect();
    let (points, normals) = sphere.grid(&us, &vs, true);
    for (p, n) in points.iter().zip(&normals) {
        let outward = (*p - centre).normalize();
        assert!(n.is_normalized(), "a unit normal at {p}");
        assert!(
            n.dot(outward).abs() > 1.0 - 1e-6,
            "{n} along {outward} at {p}"
        );
    }
    let poles = [(u0, v0), (u1, v1), (u0, v1), (u1, v0)];
    for (u, v) in poles {
        let n = sphere.unit_normal(u, v);
        let outward = (sphere.point(u, v) - centre).normalize();
        assert!(n.dot(outward).abs() > 1.0 - 1e-6, "{n} at ({u}, {v})");
    }
    let mesh = hedra_geom::surfaces::tessellate::tessellate(&sphere, 0.01);
    assert!(mesh.normals.iter().all(|n| n.is_normalized()));
}

/// A clamped knot vector for `count` control points of degree `p` with
/// uneven interior knots and, when there is room, one doubled knot.
fn uneven_knots(p: usize, count: usize) -> Vec<f64> {
    let interior = count - p - 1;
    let mut inner: Vec<f64> = (1..=interior)
        .map(|i| (i as f64 / (interior + 1) as f64).powf(1.3))
        .collect();
    if interior >= 3 && p >= 2 {
        inner[interior / 2] = inner[interior / 2 - 1]; // a double knot
    }
    let mut knots = vec![0.0; p + 1];
    knots.extend(inner);
    knots.extend(vec![1.0; p + 1]);
    knots
}

/// A rational surface of degrees `(p, q)` on uneven knots, a wavy net with
/// weights from 0.3 to 2.
fn wavy_rational(p: usize, q: usize, nu: usize, nv: usize) -> NurbsSurface {
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let (x, z) = (i as f64, j as f64);
            points.push(DVec3::new(
                x,
                (0.7 * x).sin() * (0.4 * z).cos() + 0.1 * x * z,
                z,
            ));
            weights.push(0.3 + 1.7 * ((i * 5 + j * 3) % 8) as f64 / 7.0);
        }
    }
    NurbsSurface::new(
        p,
        q,
        uneven_knots(p, nu),
        uneven_knots(q, nv),
        nu,
        nv,
        points,
        weights,
    )
    .unwrap()
}

#[test]
fn the_fast_grid_matches_point_by_point_evaluation_on_rational_surfaces() {
    // Degrees with the unrolled v-loops (up to 5) and one above (the general
    // loop); parameters at knots, at the domain's ends, between, and
    // outside (clamped).
    for (p, q) in [(3, 3), (2, 3), (3, 1), (1, 2), (3, 5), (4, 2), (2, 7)] {
        let (nu, nv) = (p + 9, q + 11);
        let s = uneven_knots(q, nv);
        let surface = wavy_rational(p, q, nu, nv);
        let mut us: Vec<f64> = (0..=37).map(|i| i as f64 / 37.0).collect();
        us.insert(0, -0.25);
        us.push(1.5);
        let mut vs: Vec<f64> = (0..=53).map(|i| i as f64 / 53.0).collect();
        vs.extend(s[q + 1..s.len() - q - 1].iter().copied());
        vs.sort_by(f64::total_cmp);
        for normals in [false, true] {
            let (points, norms) = surface.grid(&us, &vs, normals);
            assert_eq!(points.len(), us.len() * vs.len());
            assert_eq!(norms.len(), if normals { points.len() } else { 0 });
            for (a, &u) in us.iter().enumerate() {
                for (b, &v) in vs.iter().enumerate() {
                    let k = a * vs.len() + b;
                    let e = surface.evaluate(u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
                    let scale = e.p.length().max(1.0);
                    assert!(
                        close(points[k], e.p, 1e-12 * scale),
                        "degrees ({p}, {q}) at ({u}, {v}): {} vs {}",
                        points[k],
                        e.p
                    );
                    if normals {
                        assert!(
                            close(norms[k], e.normal(), 1e-9),
                            "normal, degrees ({p}, {q}) at ({u}, {v}): {} vs {}",
                            norms[k],
                            e.normal()
                        );
                    }
                }
            }
        }
    }
}
