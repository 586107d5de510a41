//! NURBS speed (issue 5): a cubic curve with 50 control points at 1,000,000
//! parameters, a bicubic 20 × 20 surface on a 1000 × 1000 grid, and the
//! tessellation of that surface to 0.001. (`bench/curvo-compare` runs the
//! same cases against the `curvo` crate.) And what re-making a surface
//! from curves costs while an input is dragged (issue 20): a torus by
//! revolution (NURBS and a 64 × 32 mesh), a circle swept along a helix (24
//! stations), a loft through four circles.

use criterion::{Criterion, criterion_group, criterion_main};
use hedra_geom::DVec3;
use hedra_geom::curves::NurbsCurve;
use hedra_geom::curves::nurbs::clamped_uniform_knots;
use hedra_geom::surfaces::NurbsSurface;
use hedra_geom::surfaces::tessellate::tessellate_nurbs;
use std::hint::black_box;

/// The allocator the app uses (see `src/main.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn curve() -> NurbsCurve {
    let points: Vec<DVec3> = (0..50)
        .map(|i| {
            let t = i as f64 * 0.4;
            DVec3::new(t.cos() * (1.0 + 0.1 * t), 0.2 * t, t.sin())
        })
        .collect();
    let weights = (0..50)
        .map(|i| 0.5 + 1.5 * ((i * 7 % 11) as f64 / 10.0))
        .collect();
    NurbsCurve::new(3, clamped_uniform_knots(3, 50), points, weights).unwrap()
}

fn surface() -> NurbsSurface {
    let n = 20;
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (x, z) = (i as f64, j as f64);
            points.push(DVec3::new(x, (0.5 * x).sin() * (0.3 * z).cos(), z));
            weights.push(0.5 + ((i * 3 + j * 5) % 7) as f64 / 6.0);
        }
    }
    NurbsSurface::new(
        3,
        3,
        clamped_uniform_knots(3, n),
        clamped_uniform_knots(3, n),
        n,
        n,
        points,
        weights,
    )
    .unwrap()
}

fn nurbs(c: &mut Criterion) {
    let mut g = c.benchmark_group("nurbs");
    g.sample_size(10);
    let cv = curve();
    let params: Vec<f64> = (0..1_000_000).map(|i| i as f64 / 999_999.0).collect();
    g.bench_function("curve_1M_points", |b| {
        b.iter(|| cv.points_at(black_box(&params)))
    });
    let s = surface();
    let grid: Vec<f64> = (0..1000).map(|i| i as f64 / 999.0).collect();
    g.bench_function("surface_1000x1000_grid", |b| {
        b.iter(|| s.grid(black_box(&grid), &grid, false))
    });
    g.bench_function("surface_1000x1000_grid_with_normals", |b| {
        b.iter(|| s.grid(black_box(&grid), &grid, true))
    });
    g.bench_function("surface_tessellate_0.001", |b| {
        b.iter(|| tessellate_nurbs(black_box(&s), 0.001))
    });
    // What a weight drag re-tessellates every frame: the viewport's
    // tolerance, 5e-4 of the control net's size (hedra_scene::VIEW_TOLERANCE).
    let (lo, hi) = s
        .points()
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let size = (hi - lo).length();
    g.bench_function("surface_tessellate_viewport", |b| {
        b.iter(|| tessellate_nurbs(black_box(&s), 5e-4 * size))
    });
    g.finish();
}

fn sweeps(c: &mut Criterion) {
    use hedra_geom::surfaces::sweeps::{
        self, Axis, LoftOptions, SweepOptions, compatible_parameters,
    };
    use std::f64::consts::TAU;
    let mut g = c.benchmark_group("sweeps");
    g.sample_size(10);
    let minor = NurbsCurve::circle(DVec3::new(2.0, 0.0, 0.0), 0.5);
    let z = Axis {
        origin: DVec3::ZERO,
        direction: DVec3::Z,
    };
    g.bench_function("revolve_torus", |b| {
        b.iter(|| sweeps::revolve(black_box(&minor), z, TAU, 0.0).unwrap())
    });
    g.bench_function("revolve_torus_mesh_64x32", |b| {
        b.iter(|| sweeps::revolve_mesh(black_box(&minor), z, TAU, 0.0, 64, 32, false).unwrap())
    });
    let helix: Vec<DVec3> = (0..=100)
        .map(|k| {
            let t = 1.5 * TAU * k as f64 / 100.0;
            DVec3::new(3.0 * t.cos(), 3.0 * t.sin(), 2.0 * t / TAU)
        })
        .collect();
    let rail = NurbsCurve::clamped(3, helix).unwrap();
    let profile = NurbsCurve::circle(DVec3::new(3.0, 0.0, 0.0), 0.4);
    let options = SweepOptions::default();
    g.bench_function("sweep_circle_along_helix_24", |b| {
        b.iter(|| sweeps::sweep(black_box(&profile), &rail, options).unwrap())
    });
    let tube = sweeps::sweep(&profile, &rail, options).unwrap();
    let (us, closed) = compatible_parameters(&profile, 24);
    g.bench_function("sweep_mesh_24x64", |b| {
        b.iter(|| sweeps::surface_mesh(black_box(&tube), &us, closed, 64, false, false).unwrap())
    });
    let rings: Vec<NurbsCurve> = (0..4)
        .map(|k| NurbsCurve::circle(DVec3::new(0.0, k as f64, 0.0), 1.0 + 0.3 * k as f64))
        .collect();
    g.bench_function("loft_4_circles", |b| {
        b.iter(|| sweeps::loft(black_box(&rings), LoftOptions::default()).unwrap())
    });
    g.finish();
}

// In a private module: criterion_group! makes a pub fn it cannot document.
mod group {
    use super::*;
    criterion_group!(benches, nurbs, sweeps);
}
criterion_main!(group::benches);
