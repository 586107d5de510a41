//! Catmull-Clark to NURBS (issue 33) on cages of about a thousand and ten
//! thousand faces: a box linearly split to 1,536 and 6,144 quads (eight
//! valence-3 corners, so the conversion refines their stars until the
//! approximated corner patches meet 1e-4 of the diagonal and 0.5°), a
//! 12-sided cylinder (two valence-12 cap centres, the cup's case, whose
//! stars are refined to about level 8, and 24 valence-3 rim corners), and
//! tori of 1,000 and 10,000 quads (all regular: one exact surface at level
//! 0). Each run includes the measurement against the limit surface. The
//! figures of each conversion are printed once before timing.

use criterion::{Criterion, criterion_group, criterion_main};

/// The allocator the app uses (see `src/main.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;
use hedra_geom::subdivision::to_nurbs::{ToNurbsOptions, to_nurbs};
use hedra_geom::subdivision::{Creases, Options, Refiner, Scheme};
use hedra_geom::{HalfEdgeMesh, Primitive};
use std::hint::black_box;

/// A cube cut `levels` times into quads (6·4^levels faces), eight
/// valence-3 vertices: the packed regular regions and the fitted corners.
fn split_box(levels: u32) -> HalfEdgeMesh {
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let linear = Options {
        scheme: Scheme::Linear,
        ..Options::default()
    };
    Refiner::subdivide(&cube, &Creases::default(), linear, levels)
        .unwrap()
        .0
}

/// A 100 × 100 torus: 10,000 regular quads, one exact surface.
fn big_torus() -> HalfEdgeMesh {
    Primitive::Torus {
        major_segments: 100,
        minor_segments: 100,
        major_radius: 2.0,
        minor_radius: 0.5,
    }
    .build()
    .unwrap()
}

fn torus() -> HalfEdgeMesh {
    Primitive::Torus {
        major_segments: 40,
        minor_segments: 25,
        major_radius: 2.0,
        minor_radius: 0.5,
    }
    .build()
    .unwrap()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("to_nurbs");
    group.sample_size(10);
    for (name, mesh) in [
        ("box 1536 quads", split_box(4)),
        ("torus 1000 quads", torus()),
        ("box 6144 quads", split_box(5)),
        (
            "cylinder 12 sides",
            Primitive::Cylinder {
                segments: 12,
                depth: 2.0,
                radius: 1.0,
            }
            .build()
            .unwrap(),
        ),
        ("torus 10000 quads", big_torus()),
        (
            "ico-sphere 5120 triangles",
            Primitive::IcoSphere {
                subdivisions: 4,
                radius: 1.0,
            }
            .build()
            .unwrap(),
        ),
    ] {
        let to = ToNurbsOptions::relative(&mesh, 1e-4);
        let start = std::time::Instant::now();
        let once = to_nurbs(&mesh, &Creases::default(), Options::default(), &to).unwrap();
        eprintln!(
            "{name}: {} faces, levels {}–{}, (exact, approximate) patches {:?}, {:?}, within: {}, {:.3} s",
            mesh.face_count(),
            once.level,
            once.deepest_level,
            once.counts(),
            once.report,
            once.within(&to),
            start.elapsed().as_secs_f64()
        );
        group.bench_function(name, |b| {
            b.iter(|| {
                to_nurbs(
                    black_box(&mesh),
                    &Creases::default(),
                    Options::default(),
                    &to,
                )
                .unwrap()
            })
        });
    }
    group.finish();
}

// In a private module: criterion_group! makes a pub fn it cannot document.
mod group {
    use super::*;
    criterion_group!(benches, bench);
}
criterion_main!(group::benches);
