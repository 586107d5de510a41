//! Progressive meshes (issue 18): building the whole collapse sequence of
//! a ~1M-triangle torus (goal < 2 s), and moving the level across 10 % of
//! the levels of a 100k-triangle one (goal < 5 ms), alternately down and
//! up.

use criterion::{Criterion, criterion_group, criterion_main};

/// The allocator the app uses (see `src/main.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;
use hedra_geom::progressive::{DecimateOptions, ProgressiveMesh};
use hedra_geom::subdivision::Creases;
use hedra_geom::{DVec3, HalfEdgeMesh};
use std::hint::black_box;

/// A torus of `major × minor` quads, each cut into two triangles, with a
/// little deterministic noise so that the collapses are not all ties.
fn torus(major: u32, minor: u32) -> HalfEdgeMesh {
    let mut positions = Vec::new();
    for i in 0..major {
        for j in 0..minor {
            let u = i as f64 / major as f64 * std::f64::consts::TAU;
            let v = j as f64 / minor as f64 * std::f64::consts::TAU;
            let noise = 0.002 * ((i * 7919 + j * 104729) % 1000) as f64 / 1000.0;
            let r = 0.5 + noise;
            positions.push(DVec3::new(
                (2.0 + r * v.cos()) * u.cos(),
                r * v.sin(),
                (2.0 + r * v.cos()) * u.sin(),
            ));
        }
    }
    let id = |i: u32, j: u32| (i % major) * minor + (j % minor);
    let mut tris = Vec::new();
    for i in 0..major {
        for j in 0..minor {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            tris.push([a, d, c]);
            tris.push([a, c, b]);
        }
    }
    HalfEdgeMesh::from_polygons(&positions, &tris).unwrap()
}

fn build(c: &mut Criterion) {
    let mesh = torus(1000, 500);
    assert_eq!(mesh.face_count(), 1_000_000);
    let mut g = c.benchmark_group("progressive");
    g.sample_size(10);
    g.bench_function("build_1M_triangles", |b| {
        b.iter(|| {
            ProgressiveMesh::build(
                black_box(&mesh),
                &Creases::default(),
                &DecimateOptions::default(),
            )
            .unwrap()
        })
    });
    g.finish();
}

fn scrub(c: &mut Criterion) {
    let mesh = torus(250, 200);
    assert_eq!(mesh.face_count(), 100_000);
    let mut pm =
        ProgressiveMesh::build(&mesh, &Creases::default(), &DecimateOptions::default()).unwrap();
    let top = pm.max_level();
    let (high, low) = (top * 6 / 10, top * 5 / 10);
    pm.seek(high).unwrap();
    let mut g = c.benchmark_group("progressive");
    g.sample_size(50);
    g.bench_function("move_10_percent_of_levels_100k", |b| {
        b.iter(|| {
            let to = if pm.level() == high { low } else { high };
            pm.seek(black_box(to)).unwrap();
        })
    });
    g.finish();
}

// In a private module: criterion_group! makes a pub fn it cannot document.
mod group {
    use super::*;
    criterion_group!(benches, build, scrub);
}
criterion_main!(group::benches);
