//! Hedra and curvo evaluate the same curve and surface: points agree to 1e-9.

use curvo_compare::*;
use hedra_geom::curves::Curve;
use hedra_geom::surfaces::Surface;

const TOL: f64 = 1e-9;

#[test]
fn curves_agree() {
    let d = curve_data();
    let (h, c) = (hedra_curve(&d), curvo_curve(&d));
    let ts = params(10_001);
    let batch = h.points_at(&ts);
    let mut ev = c.evaluator();
    let sampled = c.sample_regular_range(0.0, 1.0, ts.len());
    let mut worst = 0.0f64;
    for (k, &t) in ts.iter().enumerate() {
        let a = to_dvec3(&c.point_at(t));
        let b = to_dvec3(&ev.point_at(t));
        worst = worst
            .max(batch[k].distance(a))
            .max(h.point(t).distance(a))
            .max(a.distance(b))
            .max(batch[k].distance(to_dvec3(&sampled[k])));
    }
    assert!(worst < TOL, "curve points differ by {worst}");
}

#[test]
fn surfaces_agree() {
    let d = surface_data();
    let (h, c) = (hedra_surface(&d), curvo_surface(&d));
    let (us, vs) = (params(101), params(77));
    let (grid, _) = h.grid(&us, &vs, false);
    let mut ev = c.evaluator();
    let mut worst = 0.0f64;
    for (a, &u) in us.iter().enumerate() {
        for (b, &v) in vs.iter().enumerate() {
            let p = to_dvec3(&c.point_at(u, v));
            let q = to_dvec3(&ev.point_at(u, v));
            worst = worst
                .max(grid[a * vs.len() + b].distance(p))
                .max(h.point(u, v).distance(p))
                .max(p.distance(q));
        }
    }
    // curvo's regular grid (divs + 1 points per direction) against Hedra's.
    let n = 64;
    let reg = c.regular_sample_points(n, n);
    let (g, _) = h.grid(&params(n + 1), &params(n + 1), false);
    for i in 0..=n {
        for j in 0..=n {
            worst = worst.max(g[i * (n + 1) + j].distance(to_dvec3(&reg[i][j])));
        }
    }
    assert!(worst < TOL, "surface points differ by {worst}");
    // The data is not symmetric in u and v, so a transposed layout would fail.
    let p = to_dvec3(&c.point_at(0.2, 0.7));
    assert!(p.distance(h.point(0.7, 0.2)) > 0.1);
}
