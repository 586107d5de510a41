//! Export speed (issue 36, item 2): the bytes of OBJ, binary STL and GLB
//! for a 500 × 500 grid, as its cage (250k quads: the writers alone) and
//! subdivided once (1M quads, 2M triangles: what `hedra export
//! --subdivide 1` does). Criterion reports the output's MB/s.
//!
//! `export_4m_quads`: the cage of a 2000 × 2000 grid (4M quads) written
//! to a file from memory, the mesh `bench/export-table` gives trimesh and
//! Blender (the writers alone, disk included, beside theirs).
//!
//! `cargo bench -p hedra_doc --bench export -- FILTER`

use criterion::{Criterion, Throughput, criterion_main};
use hedra_doc::export::{ExportOptions, ExportShape, export_bytes, export_to_path};
use hedra_doc::{Command, NodeTransform, Session};
use hedra_geom::Primitive;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

/// The allocator the app uses (see `src/main.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn grid_scene(segments: u32) -> Session {
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: Primitive::Grid {
            x_segments: segments,
            z_segments: segments,
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
    let scene = grid_scene(500);
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

/// Writing the 4M-quad cage to a file, as `hedra export` does: what
/// trimesh and Blender are timed doing in `bench/export-table`.
fn export_to_file(c: &mut Criterion) {
    let scene = grid_scene(2000);
    let folder = tempfile::tempdir().unwrap();
    let mut group = c.benchmark_group("export_4m_quads");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(20))
        .warm_up_time(Duration::from_secs(1));
    for ext in ["stl", "obj", "glb"] {
        let path = folder.path().join(format!("grid.{ext}"));
        let options = ExportOptions {
            shape: ExportShape::Cage,
            ..ExportOptions::default()
        };
        export_to_path(&scene.doc, &path, options).unwrap();
        group.throughput(Throughput::Bytes(std::fs::metadata(&path).unwrap().len()));
        group.bench_function(ext, |b| {
            b.iter(|| export_to_path(&scene.doc, black_box(&path), options).unwrap())
        });
    }
    group.finish();
}

// The macro's `benches` function is Criterion's, not an API to document.
#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::export, super::export_to_file);
}
criterion_main!(group::benches);
