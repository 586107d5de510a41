//! Mesh booleans (issue 17): the union of two offset UV spheres of about
//! 160k triangles each, Hedra's whole call (half-edge meshes in and out,
//! polygons merged back) against the engine alone on the same triangles
//! (building its input from flat arrays, then the boolean; and the
//! boolean alone). Goal: Hedra's call within 1.5× of the engine's from
//! the same arrays. The `stage_*` benches time the parts of Hedra's call
//! one by one: triangulating into arrays, the self-intersection check,
//! the engine (with face numbers), merging polygons back, building the
//! half-edge mesh with vertex provenance.
//!
//! `peers/*`: the cases of `bench/boolean-table` (issue 36, item 5: two
//! 200k-triangle spheres and the bunny, beside Manifold), read from the
//! JSON file that `HEDRA_BOOLEAN_CASES` names; left out when it is unset.

use boolmesh::prelude::{Manifold, OpType, compute_boolean};
use criterion::{Criterion, criterion_main};
use hedra_geom::csg::{BooleanOp, boolean, stages};
use hedra_geom::{DVec3, HalfEdgeMesh, Primitive};
use std::hint::black_box;

/// The allocator the app uses (see `src/main.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// 400 × 200 quads and triangle fans: 159,200 triangles once triangulated.
fn sphere(offset: DVec3) -> HalfEdgeMesh {
    let mut m = Primitive::UvSphere {
        segments: 400,
        rings: 200,
        radius: 1.0,
    }
    .build()
    .unwrap();
    for p in m.positions_mut() {
        *p += offset;
    }
    m
}

fn flat(m: &HalfEdgeMesh) -> (Vec<f64>, Vec<usize>) {
    let positions = m.positions().iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    let corners = m
        .faces()
        .flat_map(|f| hedra_geom::query::triangulate_face(m, f))
        .flat_map(|t| t.map(|v| v.index()))
        .collect();
    (positions, corners)
}

fn bench(c: &mut Criterion) {
    let a = sphere(DVec3::ZERO);
    let b = sphere(DVec3::new(0.3, 0.2, 0.1));
    let (pa, ia) = flat(&a);
    let (pb, ib) = flat(&b);
    assert_eq!(ia.len() / 3, 159_200);
    let mut g = c.benchmark_group("csg");
    g.sample_size(10);
    g.bench_function("union_spheres_160k_hedra", |bench| {
        bench.iter(|| black_box(boolean(&a, &b, BooleanOp::Union, 0.0).unwrap()))
    });
    g.bench_function("union_spheres_160k_engine_from_arrays", |bench| {
        bench.iter(|| {
            let ma = Manifold::new(&pa, &ia).unwrap();
            let mb = Manifold::new(&pb, &ib).unwrap();
            black_box(compute_boolean(&ma, &mb, OpType::Add).unwrap())
        })
    });
    // The same with a face number on every corner, as Hedra passes them.
    let va: Vec<f64> = (0..ia.len()).map(|c| (c / 3) as f64).collect();
    let vb: Vec<f64> = (0..ib.len()).map(|c| (c / 3) as f64).collect();
    g.bench_function(
        "union_spheres_160k_engine_from_arrays_with_face_numbers",
        |bench| {
            bench.iter(|| {
                let ma = Manifold::new_with_values(&pa, &ia, &va).unwrap();
                let mb = Manifold::new_with_values(&pb, &ib, &vb).unwrap();
                black_box(compute_boolean(&ma, &mb, OpType::Add).unwrap())
            })
        },
    );
    let ma = Manifold::new(&pa, &ia).unwrap();
    let mb = Manifold::new(&pb, &ib).unwrap();
    g.bench_function("union_spheres_160k_engine_boolean_only", |bench| {
        bench.iter(|| black_box(compute_boolean(&ma, &mb, OpType::Add).unwrap()))
    });
    let input = stages::to_arrays(&a, &b).unwrap();
    g.bench_function("stage_to_arrays", |bench| {
        bench.iter(|| black_box(stages::to_arrays(&a, &b).unwrap()))
    });
    g.bench_function("stage_check_crossings", |bench| {
        bench.iter(|| stages::check_crossings(black_box(&input), [true; 2]).unwrap())
    });
    g.bench_function("stage_engine", |bench| {
        bench.iter(|| black_box(stages::engine(&input, BooleanOp::Union, 0.0).unwrap()))
    });
    let out = stages::engine(&input, BooleanOp::Union, 0.0).unwrap();
    g.bench_function("stage_merge_back", |bench| {
        bench.iter(|| black_box(stages::merge_back(&out, &input, [&a, &b])))
    });
    g.bench_function("stage_build", |bench| {
        bench.iter_batched(
            || stages::merge_back(&out, &input, [&a, &b]),
            |merged| black_box(stages::build(merged, [&a, &b]).unwrap()),
            criterion::BatchSize::LargeInput,
        )
    });
    g.finish();
}

/// One case of `bench/boolean-table`: two triangle meshes and an operation.
fn peer_case(case: &serde_json::Value) -> (String, HalfEdgeMesh, HalfEdgeMesh, BooleanOp) {
    let mesh = |m: &serde_json::Value| {
        let number = |x: &serde_json::Value| x.as_f64().expect("a number");
        let positions: Vec<DVec3> = m["positions"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| DVec3::new(number(&p[0]), number(&p[1]), number(&p[2])))
            .collect();
        let triangles: Vec<Vec<u32>> = m["triangles"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| (0..3).map(|i| number(&t[i]) as u32).collect())
            .collect();
        HalfEdgeMesh::from_polygons(&positions, &triangles).expect("a manifold operand")
    };
    let op = match case["op"].as_str().unwrap() {
        "union" => BooleanOp::Union,
        "difference" => BooleanOp::Difference,
        "intersection" => BooleanOp::Intersection,
        other => panic!("unknown operation {other}"),
    };
    (
        case["name"].as_str().unwrap().to_string(),
        mesh(&case["a"]),
        mesh(&case["b"]),
        op,
    )
}

/// Hedra's whole call (half-edge meshes in and out) on the cases of
/// `bench/boolean-table`, which times Manifold on the same triangles.
fn peers(c: &mut Criterion) {
    let Ok(path) = std::env::var("HEDRA_BOOLEAN_CASES") else {
        return;
    };
    let text = std::fs::read_to_string(&path).expect("HEDRA_BOOLEAN_CASES names a readable file");
    let cases: serde_json::Value = serde_json::from_str(&text).expect("JSON cases");
    let mut g = c.benchmark_group("peers");
    g.sample_size(10);
    for case in cases.as_array().unwrap() {
        let (name, a, b, op) = peer_case(case);
        g.bench_function(name, |bench| {
            bench.iter(|| black_box(boolean(&a, &b, op, 0.0).unwrap()))
        });
    }
    g.finish();
}

// The macro's `benches` function is Criterion's, not an API to document.
#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::bench, super::peers);
}
criterion_main!(group::benches);
