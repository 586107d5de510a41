//! Subdivision speed (issues 4 and 16), single thread (`refine_serial`,
//! `apply_serial`) unless a row says otherwise: Catmull-Clark of the cube to level 7
//! (98,304 faces), of a 10,000-quad cage to levels 1–3 and of a 40,000-quad
//! torus (200 × 200) to level 1; Loop of the icosahedron to level 6 (81,920
//! triangles). Single thread and parallel; re-applying the stencils after a
//! cage drag; building the refined half-edge mesh; and a STREAM-like copy,
//! the machine's memory-bandwidth floor, measured in the same run.
//!
//! "full" = connectivity of every level plus positions (what a topology
//! change costs); "positions" = the masks on a built refiner; "stencil" =
//! the recorded weights (what a cage drag costs); "to_mesh" = the refined
//! positions made into a `HalfEdgeMesh` with its creases (Apply, export,
//! `--subdivide`), on a built refiner.

use criterion::{Criterion, criterion_group, criterion_main};

/// The allocator the app uses (see `src/main.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;
use hedra_geom::subdivision::{Creases, Options, Refiner, Scheme};
use hedra_geom::{HalfEdgeMesh, Primitive};
use std::hint::black_box;

fn torus(segments: u32) -> HalfEdgeMesh {
    Primitive::Torus {
        major_segments: segments,
        minor_segments: segments,
        major_radius: 2.0,
        minor_radius: 0.5,
    }
    .build()
    .unwrap()
}

/// Which of the benches to run on a mesh.
#[derive(Copy, Clone, PartialEq)]
enum Set {
    /// Every bench.
    All,
    /// Full refinement, positions and the half-edge build only.
    Refine,
}

fn bench_mesh(
    c: &mut Criterion,
    name: &str,
    mesh: &HalfEdgeMesh,
    opts: Options,
    levels: &[u32],
    set: Set,
) {
    let mut g = c.benchmark_group(name);
    g.sample_size(10);
    let creases = Creases::default();
    for &level in levels {
        let refiner = Refiner::new(mesh, &creases, opts, level).unwrap();
        let cage = refiner.cage_positions(mesh);
        g.bench_function(format!("level{level}/full"), |b| {
            b.iter(|| {
                let r = Refiner::new(black_box(mesh), &creases, opts, level).unwrap();
                r.refine_serial(&r.cage_positions(mesh))
            })
        });
        g.bench_function(format!("level{level}/positions"), |b| {
            b.iter(|| refiner.refine_serial(black_box(&cage)))
        });
        let points = refiner.refine_serial(&cage);
        g.bench_function(format!("level{level}/to_mesh"), |b| {
            b.iter(|| refiner.to_mesh(black_box(&points)).unwrap())
        });
        if set == Set::Refine {
            continue;
        }
        g.bench_function(format!("level{level}/full_parallel"), |b| {
            b.iter(|| {
                let r = Refiner::new(black_box(mesh), &creases, opts, level).unwrap();
                r.refine_parallel(&r.cage_positions(mesh))
            })
        });
        g.bench_function(format!("level{level}/positions_parallel"), |b| {
            b.iter(|| refiner.refine_parallel(black_box(&cage)))
        });
        g.bench_function(format!("level{level}/stencil_build"), |b| {
            b.iter(|| black_box(&refiner).stencils())
        });
        let stencils = refiner.stencils();
        g.bench_function(format!("level{level}/stencil"), |b| {
            b.iter(|| stencils.apply_serial(black_box(&cage)))
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
    let cc = Options::default();
    bench_mesh(c, "cc_cube", &cube, cc, &[7], Set::All);
    from_face_list(c, "cc_cube", &cube, cc, 7);
    bench_mesh(c, "cc_torus_10k", &torus(100), cc, &[1, 2, 3], Set::All);
    from_face_list(c, "cc_torus_10k", &torus(100), cc, 3);
    bench_mesh(c, "cc_torus_40k", &torus(200), cc, &[1], Set::Refine);
    from_face_list(c, "cc_torus_40k", &torus(200), cc, 1);
    two_cores(c, "cc_torus_10k", &torus(100), cc, 4);
}

/// One thread against all (issue 36 item 4) on a refinement of more than
/// 1M output faces (the 100 × 100 torus to level 4: 2,560,000 quads): the
/// whole refinement and the positions alone, serial and on the rayon pool.
fn two_cores(c: &mut Criterion, name: &str, mesh: &HalfEdgeMesh, opts: Options, level: u32) {
    let creases = Creases::default();
    let refiner = Refiner::new(mesh, &creases, opts, level).unwrap();
    assert!(refiner.face_count() > 1_000_000);
    let cage = refiner.cage_positions(mesh);
    let mut g = c.benchmark_group(name);
    g.sample_size(10);
    for (label, parallel) in [("serial", false), ("parallel", true)] {
        g.bench_function(format!("level{level}/full_{label}"), |b| {
            b.iter(|| {
                let r = Refiner::new(black_box(mesh), &creases, opts, level).unwrap();
                let cage = r.cage_positions(mesh);
                if parallel {
                    r.refine_parallel(&cage)
                } else {
                    r.refine(&cage)
                }
            })
        });
        g.bench_function(format!("level{level}/positions_{label}"), |b| {
            b.iter(|| {
                if parallel {
                    refiner.refine(black_box(&cage))
                } else {
                    refiner.refine_serial(black_box(&cage))
                }
            })
        });
    }
    g.finish();
}

/// Refinement from a face list, as OpenSubdiv starts (issue 36 item 3):
/// through the half-edge mesh (`HalfEdgeMesh::from_polygons`, then
/// `Refiner::new`), and straight from the polygons (`Refiner::from_polygons`,
/// which also takes non-manifold cages).
fn from_face_list(c: &mut Criterion, name: &str, mesh: &HalfEdgeMesh, opts: Options, level: u32) {
    let positions: Vec<_> = mesh.vertices().map(|v| mesh.position(v)).collect();
    let faces: Vec<Vec<u32>> = mesh
        .faces()
        .map(|f| mesh.face_vertices(f).map(|v| v.0).collect())
        .collect();
    let creases = Creases::default();
    let mut g = c.benchmark_group(name);
    g.sample_size(10);
    g.bench_function(format!("level{level}/from_faces_via_half_edges"), |b| {
        b.iter(|| {
            let m = HalfEdgeMesh::from_polygons(black_box(&positions), &faces).unwrap();
            let r = Refiner::new(&m, &creases, opts, level).unwrap();
            r.refine_serial(&r.cage_positions(&m))
        })
    });
    g.bench_function(format!("level{level}/from_faces_as_polygons"), |b| {
        b.iter(|| {
            let r =
                Refiner::from_polygons(positions.len(), black_box(&faces), opts, level).unwrap();
            r.refine_serial(&positions)
        })
    });
    g.finish();
}

fn loop_scheme(c: &mut Criterion) {
    let ico = Primitive::IcoSphere {
        subdivisions: 0,
        radius: 1.0,
    }
    .build()
    .unwrap();
    let opts = Options {
        scheme: Scheme::Loop,
        ..Options::default()
    };
    bench_mesh(c, "loop_icosahedron", &ico, opts, &[6], Set::Refine);
    from_face_list(c, "loop_icosahedron", &ico, opts, 6);
}

/// A STREAM-like copy of 64 MB of f64: the bandwidth floor that the
/// refinement's memory traffic is compared against (bytes read + written
/// per second; criterion's throughput counts the bytes copied once).
fn stream(c: &mut Criterion) {
    let n = 64 << 17; // 64 MB of f64
    let src: Vec<f64> = (0..n).map(|i| i as f64).collect();
    let mut dst = vec![0.0f64; n];
    let mut g = c.benchmark_group("memory");
    g.sample_size(20);
    g.throughput(criterion::Throughput::Bytes(2 * 8 * n as u64));
    g.bench_function("stream_copy_64MB", |b| {
        b.iter(|| {
            dst.copy_from_slice(black_box(&src));
            black_box(&mut dst);
        })
    });
    g.finish();
}

// In a private module: criterion_group! makes a pub fn it cannot document.
mod group {
    use super::*;
    criterion_group!(benches, stream, catmull_clark, loop_scheme);
}
criterion_main!(group::benches);
