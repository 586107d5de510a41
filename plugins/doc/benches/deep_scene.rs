//! Deep hierarchies (issue 31, item 14): a chain of nested nodes opened
//! (`file::from_str`: parse, restore, `Document::check`), reported (`hedra
//! info`: `SceneReport::new`) and exported to OBJ, at 500, 2,000 and
//! 10,000 nodes, and a 10,000-deep glTF chain imported. Before the fix
//! world transforms, visibility and the parent-cycle check walked up to
//! the root from every node (a 10,000-deep chain: `info` 58 s, OBJ export
//! 110 s); they are now computed once per node, top down, so every step
//! grows linearly with the depth.
//!
//! Measured on the shared 2-core machine (release, under load), before →
//! after: 2,000 deep: open 52 → 30 ms, info 62 → 16 ms, OBJ export 144 →
//! 1.9 ms; 10,000 deep: open 205 ms, info 84 ms, OBJ export 17 ms, GLB
//! import 334 ms. A 10,000-deep chain imported from GLB and saved (its
//! history holds every node): open 3.8 s → 0.55 s, info 2.3 s → 43 ms, OBJ
//! export 7.4 s → 11 ms.
//!
//! `cargo bench -p hedra_doc --bench deep_scene -- FILTER`

use criterion::{BenchmarkId, Criterion, criterion_main};
use hedra_doc::export::{ExportOptions, export_bytes};
use hedra_doc::report::SceneReport;
use hedra_doc::{Session, file};
use std::hint::black_box;
use std::path::Path;

/// The allocator the app uses (see `src/main.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[path = "../tests/deep/mod.rs"]
mod deep;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("deep_scene");
    g.sample_size(10);
    let path = Path::new("chain.hedra.ron");
    for n in [500usize, 2_000, 10_000] {
        let text = deep::chain_text(n);
        g.bench_with_input(BenchmarkId::new("open", n), &text, |b, text| {
            b.iter(|| black_box(file::from_str(black_box(text), path).unwrap()))
        });
        let session = file::from_str(&text, path).unwrap().session;
        g.bench_with_input(BenchmarkId::new("info", n), &session, |b, s| {
            b.iter(|| black_box(SceneReport::new(black_box(s)).to_text()))
        });
        g.bench_with_input(BenchmarkId::new("export_obj", n), &session, |b, s| {
            b.iter(|| {
                black_box(
                    export_bytes(&s.doc, Path::new("x.obj"), ExportOptions::default()).unwrap(),
                )
            })
        });
        if n == 10_000 {
            let glb =
                export_bytes(&session.doc, Path::new("x.glb"), ExportOptions::default()).unwrap();
            g.bench_function(BenchmarkId::new("import_glb", n), |b| {
                b.iter(|| {
                    let meshes =
                        hedra_doc::gltf::gltf_from_bytes(black_box(&glb), None, "x.glb").unwrap();
                    let mut s = Session::new();
                    s.import(&meshes, "Import");
                    black_box(s)
                })
            });
        }
    }
    g.finish();
}

// The macro's `benches` function is Criterion's, not an API to document.
#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::bench);
}
criterion_main!(group::benches);
