//! Export speed (issue 36, item 2): the bytes of OBJ, binary STL and GLB
//! for a 500 × 500 grid, as its cage (250k quads: the writers alone) and
//! subdivided once (1M quads, 2M triangles: what `hedra export
//! --subdivide 1` does). Criterion reports the output's MB/s.
//!
//! `cargo bench -p hedra_doc --bench export -- FILTER`

use criterion::{Criterion, Throughput, criterion_main};
use hedra_doc::export::{ExportOptions, ExportShape, export_bytes};
use hedra_doc::{Command, NodeTransform, Session};
use hedra_geom::Primitive;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

/// The allocator the app uses (see `src/main.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn grid_scene() -> Session {
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: Primitive::Grid {
            x_segments: 500,
            z_segments: 500,
            size: 2.0,
        },
        name: Some("Grid".into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s
}

fn export(c: &mut Criterion) {
    let scene = grid_scene();
    for (label, shape) in [
        ("cage", ExportShape::Cage),
        ("subdivided", ExportShape::Subdivided(1)),
    ] {
        let mut group = c.benchmark_group(format!("export/{label}"));
        group
            .sample_size(10)
            .measurement_time(Duration::from_secs(10))
            .warm_up_time(Duration::from_secs(1));
        for ext in ["stl", "obj", "glb"] {
            let path = format!("grid.{ext}");
            let options = ExportOptions {
                shape,
                ..ExportOptions::default()
            };
            let size = export_bytes(&scene.doc, Path::new(&path), options)
                .unwrap()
                .len();
            group.throughput(Throughput::Bytes(size as u64));
            group.bench_function(ext, |b| {
                b.iter(|| black_box(export_bytes(&scene.doc, Path::new(&path), options).unwrap()))
            });
        }
        group.finish();
    }
}

// The macro's `benches` function is Criterion's, not an API to document.
#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::export);
}
criterion_main!(group::benches);
