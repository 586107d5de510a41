//! Subdivision speed (issue 4): Catmull-Clark of the cube to level 7 (98,304
//! faces) and of a 10,000-quad cage to levels 1–3, single thread and
//! parallel; re-applying the stencils after a cage drag at level 3.
//!
//! "full" = connectivity of every level plus positions (what a topology
//! change costs); "positions" = the masks on a built refiner; "stencil" =
//! the recorded weights (what a cage drag costs).

use criterion::{Criterion, criterion_group, criterion_main};

/// The allocator the app uses (see `src/main.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;
use hedra_geom::subdivision::{Creases, Options, Refiner};
use hedra_geom::{HalfEdgeMesh, Primitive};
use std::hint::black_box;

fn torus_10k() -> HalfEdgeMesh {
    Primitive::Torus {
        major_segments: 100,
        minor_segments: 100,
        major_radius: 2.0,
        minor_radius: 0.5,
    }
    .build()
    .unwrap()
}

fn bench_mesh(c: &mut Criterion, name: &str, mesh: &HalfEdgeMesh, levels: &[u32]) {
    let mut g = c.benchmark_group(name);
    g.sample_size(10);
    let creases = Creases::default();
    let opts = Options::default();
    for &level in levels {
        let refiner = Refiner::new(mesh, &creases, opts, level).unwrap();
        let cage = refiner.cage_positions(mesh);
        g.bench_function(format!("level{level}/full"), |b| {
            b.iter(|| {
                let r = Refiner::new(black_box(mesh), &creases, opts, level).unwrap();
                r.refine(&r.cage_positions(mesh))
            })
        });
        g.bench_function(format!("level{level}/full_parallel"), |b| {
            b.iter(|| {
                let r = Refiner::new(black_box(mesh), &creases, opts, level).unwrap();
                r.refine_parallel(&r.cage_positions(mesh))
            })
        });
        g.bench_function(format!("level{level}/positions"), |b| {
            b.iter(|| refiner.refine(black_box(&cage)))
        });
        g.bench_function(format!("level{level}/positions_parallel"), |b| {
            b.iter(|| refiner.refine_parallel(black_box(&cage)))
        });
        let stencils = refiner.stencils();
        g.bench_function(format!("level{level}/stencil"), |b| {
            b.iter(|| stencils.apply(black_box(&cage)))
        });
        g.bench_function(format!("level{level}/stencil_parallel"), |b| {
            b.iter(|| stencils.apply_parallel(black_box(&cage)))
        });
        // A drag: one cage vertex moves; only the points it influences are
        // recomputed.
        let mut eval = stencils.evaluate(&cage);
        let mut step = 0.0;
        g.bench_function(format!("level{level}/drag_one_vertex"), |b| {
            b.iter(|| {
                step += 1e-3;
                stencils.update(&mut eval, &[(0, cage[0] + hedra_geom::DVec3::splat(step))]);
                black_box(eval.points().len())
            })
        });
    }
    g.finish();
}

fn catmull_clark(c: &mut Criterion) {
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    bench_mesh(c, "cc_cube", &cube, &[7]);
    bench_mesh(c, "cc_torus_10k", &torus_10k(), &[1, 2, 3]);
}

// In a private module: criterion_group! makes a pub fn it cannot document.
mod group {
    use super::*;
    criterion_group!(benches, catmull_clark);
}
criterion_main!(group::benches);
