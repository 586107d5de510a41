//! Kernel speed (issue 3): build a half-edge mesh from 1,000,000 quads,
//! validate it, 100,000 random split/join operations, extrude 10,000 faces.

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};

/// The allocator the app uses (see `src/main.rs`), as the other benches.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;
use hedra_geom::{DVec3, EdgeId, HalfEdgeMesh};
use std::hint::black_box;

/// An n×n grid of quads as positions and polygons.
fn grid(n: u32) -> (Vec<DVec3>, Vec<[u32; 4]>) {
    let mut p = Vec::with_capacity(((n + 1) * (n + 1)) as usize);
    for j in 0..=n {
        for i in 0..=n {
            p.push(DVec3::new(i as f64, 0.0, j as f64));
        }
    }
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut f = Vec::with_capacity((n * n) as usize);
    for j in 0..n {
        for i in 0..n {
            f.push([id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)]);
        }
    }
    (p, f)
}

fn build_and_validate(c: &mut Criterion) {
    let (p, f) = grid(1000);
    let mut g = c.benchmark_group("million_quads");
    g.sample_size(10);
    g.bench_function("from_polygons", |b| {
        b.iter(|| HalfEdgeMesh::from_polygons(black_box(&p), black_box(&f)).unwrap())
    });
    let m = HalfEdgeMesh::from_polygons(&p, &f).unwrap();
    g.bench_function("validate", |b| b.iter(|| black_box(&m).validate().unwrap()));
    g.finish();
}

fn split_join(c: &mut Criterion) {
    let (p, f) = grid(300);
    let base = HalfEdgeMesh::from_polygons(&p, &f).unwrap();
    let mut g = c.benchmark_group("edits");
    g.sample_size(10);
    g.bench_function("100k_split_edge_then_join", |b| {
        b.iter_batched(
            || base.clone(),
            |mut m| {
                // A simple LCG picks edges; every split is undone by its join.
                let mut state = 12345u64;
                let ne = m.edge_capacity() as u64;
                for _ in 0..50_000 {
                    state = state
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    let e = EdgeId(((state >> 33) % ne) as u32);
                    let v = m.split_edge(e, m.edge_midpoint(e)).unwrap();
                    m.join_edges(v).unwrap();
                }
                m
            },
            BatchSize::LargeInput,
        )
    });
    let (p, f) = grid(100);
    let base = HalfEdgeMesh::from_polygons(&p, &f).unwrap();
    g.bench_function("extrude_10k_faces", |b| {
        b.iter_batched(
            || base.clone(),
            |mut m| {
                let faces: Vec<_> = m.faces().collect();
                hedra_geom::modeling::extrude_faces_individual(&mut m, &faces, 0.5).unwrap();
                m
            },
            BatchSize::LargeInput,
        )
    });
    g.finish();
}

// In a private module: criterion_group! makes a pub fn it cannot document.
mod group {
    use super::*;
    criterion_group!(benches, build_and_validate, split_join);
}
criterion_main!(group::benches);
