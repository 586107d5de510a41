//! Saving and loading a scene with a 1M-quad mesh (issue 16, part 5):
//! `file::to_string` and `file::from_str` (the disk is left out: it is
//! the same for every format), against serde_json writing and reading the
//! same mesh (its `MeshData` records, and positions with polygons) as a
//! reference for what a fast serde format costs on this machine.
//!
//! Two scenes: a 1000 × 1000 torus made by `AddPrimitive` (the history
//! step shares the scene's mesh), and the same mesh made by `AddMesh`,
//! whose command holds the positions and polygons again.
//!
//! `cargo bench -p hedra_doc --bench scene_file -- FILTER`

use criterion::{Criterion, criterion_main};
use glam::DVec3;
use hedra_doc::{Command, NodeContent, NodeTransform, Session, file};
use hedra_geom::{HalfEdgeMesh, Primitive};
use std::hint::black_box;
use std::path::Path;

/// The allocator the app uses (see `src/main.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

const TORUS: Primitive = Primitive::Torus {
    major_segments: 1000,
    minor_segments: 1000,
    major_radius: 1.0,
    minor_radius: 0.25,
};

fn torus_scene() -> Session {
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: TORUS,
        name: Some("Torus".into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s
}

fn mesh_of(s: &Session) -> &HalfEdgeMesh {
    match &s.doc.find_by_name("Torus").unwrap().content {
        NodeContent::Mesh(m) => &m.mesh,
        _ => unreachable!(),
    }
}

/// Positions and polygons of a mesh without dead elements.
fn polygons(m: &HalfEdgeMesh) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let positions = m.vertices().map(|v| m.position(v)).collect();
    let polygons = m
        .faces()
        .map(|f| m.face_vertices(f).map(|v| v.0).collect())
        .collect();
    (positions, polygons)
}

fn add_mesh_scene(positions: Vec<DVec3>, polygons: Vec<Vec<u32>>) -> Session {
    let mut s = Session::new();
    s.execute(&Command::AddMesh {
        name: "Torus".into(),
        positions,
        polygons,
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s
}

fn bench(c: &mut Criterion) {
    let torus = torus_scene();
    let mesh = mesh_of(&torus);
    assert_eq!(mesh.face_count(), 1_000_000);
    let (positions, polys) = polygons(mesh);
    let added = add_mesh_scene(positions.clone(), polys.clone());
    let path = Path::new("bench.hedra.ron");

    let mut g = c.benchmark_group("scene_file");
    g.sample_size(10);
    for (name, session) in [("torus_1m", &torus), ("add_mesh_1m", &added)] {
        let text = file::to_string(session);
        eprintln!("{name}: {} bytes", text.len());
        g.bench_function(format!("save/{name}"), |b| {
            b.iter(|| black_box(file::to_string(black_box(session))))
        });
        g.bench_function(format!("load/{name}"), |b| {
            b.iter(|| black_box(file::from_str(black_box(&text), path).unwrap()))
        });
    }

    // The reference: serde_json on the same mesh.
    let records = serde_json::to_string(mesh).unwrap();
    eprintln!("serde_json records: {} bytes", records.len());
    g.bench_function("serde_json_records/save", |b| {
        b.iter(|| black_box(serde_json::to_string(black_box(mesh)).unwrap()))
    });
    g.bench_function("serde_json_records/load", |b| {
        b.iter(|| black_box(serde_json::from_str::<HalfEdgeMesh>(black_box(&records)).unwrap()))
    });
    let pair = (positions, polys);
    let compact = serde_json::to_string(&pair).unwrap();
    eprintln!("serde_json polygons: {} bytes", compact.len());
    g.bench_function("serde_json_polygons/save", |b| {
        b.iter(|| black_box(serde_json::to_string(black_box(&pair)).unwrap()))
    });
    g.bench_function("serde_json_polygons/load", |b| {
        b.iter(|| {
            let (p, f): (Vec<DVec3>, Vec<Vec<u32>>) =
                serde_json::from_str(black_box(&compact)).unwrap();
            black_box(HalfEdgeMesh::from_polygons(&p, &f).unwrap())
        })
    });
    g.finish();
}

// The macro's `benches` function is Criterion's, not an API to document.
#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::bench);
}
criterion_main!(group::benches);
