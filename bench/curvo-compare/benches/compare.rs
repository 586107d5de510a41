//! Hedra vs curvo on the same NURBS data, single thread (see README.md).
//!
//! 1. curve: a cubic 50-point NURBS curve at 1,000,000 evenly spaced parameters;
//! 2. surface: a bicubic 20 × 20 NURBS surface on a 1000 × 1000 parameter grid;
//! 3. tessellation of that surface to a chord tolerance of 0.001.
//!
//! Before timing, every group checks that both libraries computed the same
//! points (1e-9), and the tessellation group prints the vertex and triangle
//! counts and the measured chord error of every mesh.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use curvo::prelude::*;
use curvo_compare::*;
use hedra_geom::surfaces::tessellate::{cells_for_tolerance, tessellate_nurbs};
use nalgebra::Point3;
use std::hint::black_box;
use std::time::Duration;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

const CURVE_SAMPLES: usize = 1_000_000;
const GRID: usize = 1000;
const TOLERANCE: f64 = 0.001;

/// curvo has no distance tolerance; these normal tolerances were chosen by
/// measuring the chord error (`cargo run --release --example calibrate`).
/// With `grid: true` this is the cheapest setting tried whose max chord
/// error stays under 0.001 at the default `max_depth` 8.
const CURVO_NORM_TOL_GRID: f64 = 1e-3;
/// The same normal tolerance in curvo's default (non-grid) adaptive mode: at
/// the default `max_depth` 8 it cannot get under 0.001 (it saturates at
/// about 1.3e-3 when every cell is split to depth 8).
const CURVO_NORM_TOL: f64 = 1e-3;

fn max_dist(a: &[hedra_geom::DVec3], b: impl Iterator<Item = Point3<f64>>) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| p.distance(to_dvec3(&q)))
        .fold(0.0, f64::max)
}

fn curve(c: &mut Criterion) {
    let d = curve_data();
    let (h, cv) = (hedra_curve(&d), curvo_curve(&d));
    let ts = params(CURVE_SAMPLES);

    // Same curve: compare every 997th point of each curvo path with Hedra's.
    let hp = h.points_at(&ts);
    let picks: Vec<usize> = (0..CURVE_SAMPLES)
        .step_by(997)
        .chain([CURVE_SAMPLES - 1])
        .collect();
    let sampled = cv.sample_regular_range(0.0, 1.0, CURVE_SAMPLES);
    let err = picks
        .iter()
        .map(|&k| {
            let a = to_dvec3(&cv.point_at(ts[k]));
            hp[k].distance(a).max(hp[k].distance(to_dvec3(&sampled[k])))
        })
        .fold(0.0, f64::max);
    eprintln!(
        "curve: max |hedra - curvo| over {} checked points = {err:.1e}",
        picks.len()
    );
    assert!(err < 1e-9);

    let mut g = c.benchmark_group("curve_1M");
    g.throughput(Throughput::Elements(CURVE_SAMPLES as u64));
    g.sample_size(20);
    g.measurement_time(Duration::from_secs(8));
    g.bench_function("hedra/points_at", |b| {
        b.iter(|| black_box(&h).points_at(black_box(&ts)))
    });
    g.bench_function("curvo/point_at_loop", |b| {
        b.iter(|| {
            let cv = black_box(&cv);
            let mut out = Vec::with_capacity(ts.len());
            for &t in black_box(&ts) {
                out.push(cv.point_at(t));
            }
            out
        })
    });
    g.bench_function("curvo/evaluator_loop", |b| {
        b.iter(|| {
            let mut ev = black_box(&cv).evaluator();
            let mut out = Vec::with_capacity(ts.len());
            for &t in black_box(&ts) {
                out.push(ev.point_at(t));
            }
            out
        })
    });
    g.bench_function("curvo/sample_regular_range", |b| {
        b.iter(|| black_box(&cv).sample_regular_range(0.0, 1.0, black_box(CURVE_SAMPLES)))
    });
    g.finish();
}

fn surface(c: &mut Criterion) {
    let d = surface_data();
    let (h, cs) = (hedra_surface(&d), curvo_surface(&d));
    let us = params(GRID);
    let vs = params(GRID);

    let (hp, _) = h.grid(&us, &vs, false);
    let reg = cs.regular_sample_points(GRID - 1, GRID - 1);
    let mut err = max_dist(&hp, reg.iter().flatten().cloned());
    for i in (0..GRID).step_by(37).chain([GRID - 1]) {
        for j in (0..GRID).step_by(41).chain([GRID - 1]) {
            let p = to_dvec3(&cs.point_at(us[i], vs[j]));
            err = err.max(hp[i * GRID + j].distance(p));
        }
    }
    eprintln!(
        "surface: max |hedra - curvo| (all of regular_sample_points, a subgrid of point_at) = {err:.1e}"
    );
    assert!(err < 1e-9);

    let mut g = c.benchmark_group("surface_1000x1000");
    g.throughput(Throughput::Elements((GRID * GRID) as u64));
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(8));
    g.bench_function("hedra/grid", |b| {
        b.iter(|| black_box(&h).grid(black_box(&us), black_box(&vs), false))
    });
    g.bench_function("curvo/point_at_loop", |b| {
        b.iter(|| {
            let cs = black_box(&cs);
            let mut out = Vec::with_capacity(us.len() * vs.len());
            for &u in black_box(&us) {
                for &v in black_box(&vs) {
                    out.push(cs.point_at(u, v));
                }
            }
            out
        })
    });
    g.bench_function("curvo/evaluator_loop", |b| {
        b.iter(|| {
            let mut ev = black_box(&cs).evaluator();
            let mut out = Vec::with_capacity(us.len() * vs.len());
            for &u in black_box(&us) {
                for &v in black_box(&vs) {
                    out.push(ev.point_at(u, v));
                }
            }
            out
        })
    });
    g.bench_function("curvo/regular_sample_points", |b| {
        b.iter(|| black_box(&cs).regular_sample_points(black_box(GRID - 1), GRID - 1))
    });
    g.finish();
}

fn curvo_adaptive(norm_tol: f64, grid: bool) -> AdaptiveTessellationOptions<f64> {
    AdaptiveTessellationOptions::<f64>::default()
        .with_norm_tolerance(norm_tol)
        .with_grid(grid)
}

fn tessellation(c: &mut Criterion) {
    let d = surface_data();
    let (h, cs) = (hedra_surface(&d), curvo_surface(&d));
    let (cu, cv) = cells_for_tolerance(&h, TOLERANCE);

    let report = |name: &str, (p, uv, t): (Vec<_>, Vec<_>, Vec<_>)| {
        let (emax, emean) = chord_error(&h, &p, &uv, &t);
        eprintln!(
            "tessellation {name}: {} vertices, {} triangles, chord error max {emax:.2e}, mean {emean:.2e}",
            p.len(),
            t.len()
        );
    };
    eprintln!("tessellation: Hedra's grid for tolerance {TOLERANCE} is {cu} x {cv} cells");
    report(
        "hedra/tessellate_nurbs",
        hedra_mesh(&tessellate_nurbs(&h, TOLERANCE)),
    );
    report(
        "curvo/regular_tessellate",
        curvo_mesh(&cs.regular_tessellate(cu, cv)),
    );
    report(
        "curvo/adaptive_grid",
        curvo_mesh(&cs.tessellate(Some(curvo_adaptive(CURVO_NORM_TOL_GRID, true)))),
    );
    report(
        "curvo/adaptive",
        curvo_mesh(&cs.tessellate(Some(curvo_adaptive(CURVO_NORM_TOL, false)))),
    );

    let mut g = c.benchmark_group("tessellate_0.001");
    g.sample_size(10);
    g.measurement_time(Duration::from_secs(15));
    g.bench_function("hedra/tessellate_nurbs", |b| {
        b.iter(|| tessellate_nurbs(black_box(&h), black_box(TOLERANCE)))
    });
    g.bench_function("curvo/regular_tessellate", |b| {
        b.iter(|| black_box(&cs).regular_tessellate(black_box(cu), black_box(cv)))
    });
    g.bench_function("curvo/adaptive_grid", |b| {
        b.iter(|| black_box(&cs).tessellate(Some(curvo_adaptive(CURVO_NORM_TOL_GRID, true))))
    });
    g.bench_function("curvo/adaptive", |b| {
        b.iter(|| black_box(&cs).tessellate(Some(curvo_adaptive(CURVO_NORM_TOL, false))))
    });
    g.finish();
}

criterion_group!(benches, curve, surface, tessellation);
criterion_main!(benches);
