//! One frame of dragging vertices on a 100,000-face mesh (issue 3), and one
//! frame of an extrude preview of 100 of its faces (issue 12): what the
//! edit tool does every frame — decide the move on a copy of the document
//! (`Document::decide`, as `hedra_edit` does for its preview) and patch the
//! render buffers in place (`render::patch_positions`, as `hedra_scene`
//! does) — against rebuilding the render buffers, which the patch avoids;
//! and the edit-mode edge overlay's lines (`render::edge_overlay`), rebuilt
//! on every preview frame. The GPU upload is not in here (no GPU on the
//! benchmark machine).

use criterion::{BatchSize, Criterion, criterion_main};
use glam::DVec3;
use hedra_doc::render::{OverlaySelection, edge_overlay, patch_positions, render_buffers};
use hedra_doc::{Command, NodeContent, NodeRef, NodeTransform, Session, Shading, VertexSet};
use hedra_geom::Primitive;
use std::hint::black_box;

/// The allocator the app uses (see `src/main.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn bench(c: &mut Criterion) {
    // As the window runs (a debug build's check of every edit is off there).
    hedra_doc::command::set_validate_edits(false);
    let mut session = Session::new();
    session
        .execute(&Command::AddPrimitive {
            primitive: Primitive::Grid {
                x_segments: 317,
                z_segments: 317,
                size: 10.0,
            },
            name: Some("Dense".into()),
            parent: None,
            transform: NodeTransform::IDENTITY,
        })
        .unwrap();
    let doc = &session.doc;
    let node = doc.find_by_name("Dense").unwrap();
    let NodeContent::Mesh(content) = &node.content else {
        unreachable!()
    };
    let mesh = content.mesh.clone();
    assert!(mesh.face_count() >= 100_000, "{}", mesh.face_count());
    // A brush-sized selection: the 100 vertices nearest the middle.
    let mut by_distance: Vec<_> = mesh.vertices().collect();
    by_distance.sort_by(|a, b| {
        mesh.position(*a)
            .length()
            .total_cmp(&mesh.position(*b).length())
    });
    let selected: Vec<u32> = by_distance[..100].iter().map(|v| v.0).collect();
    let drag = |dy: f64| Command::MoveVertices {
        node: NodeRef::Name("Dense".into()),
        vertices: VertexSet::Ids(selected.clone()),
        offset: DVec3::new(0.0, dy, 0.0),
    };
    let moved = {
        let t = doc.decide(&drag(0.25), 0).unwrap();
        match &t.changes[0].after.as_ref().unwrap().content {
            NodeContent::Mesh(m) => m.mesh.clone(),
            _ => unreachable!(),
        }
    };

    // A topology tool's preview frame: extrude the 100 faces nearest the
    // middle as one region (what E decides on every frame of its drag).
    let mut faces_by_distance: Vec<_> = mesh.faces().collect();
    faces_by_distance.sort_by(|a, b| {
        mesh.face_centroid(*a)
            .length()
            .total_cmp(&mesh.face_centroid(*b).length())
    });
    let extrude = Command::ExtrudeRegion {
        node: NodeRef::Name("Dense".into()),
        faces: hedra_doc::FaceSet::Ids(faces_by_distance[..100].iter().map(|f| f.0).collect()),
        distance: 0.25,
    };

    let mut g = c.benchmark_group("edit_frame_100k_faces");
    g.sample_size(30);
    g.bench_function("decide_extrude_100_faces", |b| {
        b.iter(|| black_box(doc.decide_with_result(black_box(&extrude), 0).unwrap()))
    });
    // What the extrude tool does instead (hedra_doc::preview): two decides
    // when the drag starts, then one copy and the moved positions a frame.
    g.bench_function("extrude_preview_start_100_faces", |b| {
        b.iter(|| black_box(doc.linear_preview(black_box(&extrude), node.id).unwrap()))
    });
    let linear = doc.linear_preview(&extrude, node.id).unwrap().unwrap();
    g.bench_function("extrude_preview_frame_100_faces", |b| {
        b.iter(|| black_box(std::sync::Arc::new(linear.mesh_at(black_box(0.25)))))
    });
    g.bench_function("decide_move_100_vertices", |b| {
        b.iter(|| black_box(doc.decide(black_box(&drag(0.25)), 0).unwrap()))
    });
    for shading in [Shading::Flat, Shading::Smooth] {
        let name = format!("{shading:?}").to_lowercase();
        let base = render_buffers(&mesh, shading);
        g.bench_function(format!("patch_render_{name}"), |b| {
            b.iter_batched_ref(
                || (base.positions.clone(), base.normals.clone()),
                |(p, n)| assert!(patch_positions(p, n, &mesh, &moved, shading).is_some()),
                BatchSize::LargeInput,
            )
        });
        g.bench_function(format!("rebuild_render_{name}"), |b| {
            b.iter(|| black_box(render_buffers(black_box(&moved), shading)))
        });
    }
    // The edit-mode edge overlay is rebuilt on every preview frame.
    let ids: std::collections::BTreeSet<_> = by_distance[..100].iter().copied().collect();
    let none = std::collections::BTreeSet::new();
    let no_faces = std::collections::BTreeSet::new();
    let sel = OverlaySelection {
        vertices: Some(&ids),
        edges: &none,
        faces: &no_faces,
        related_edges: &none,
        related_faces: &no_faces,
    };
    g.bench_function("edge_overlay", |b| {
        b.iter(|| black_box(edge_overlay(&moved, &sel, &content.creases)))
    });
    g.finish();

    // Render preparation for the viewport (hedra_doc::smooth, render):
    // one frame of dragging a cage vertex of a smooth preview, and one
    // frame of a weight drag on a NURBS surface (the tiles it reaches).
    let mut g = c.benchmark_group("render_prep");
    g.sample_size(30);
    let cage = std::sync::Arc::new(Primitive::Cube { size: 2.0 }.build().unwrap());
    let modifier = hedra_doc::SubdivisionModifier::with_level(5);
    let creases = hedra_geom::subdivision::Creases::default();
    let mut refinement =
        hedra_doc::smooth::SmoothRefinement::new(&cage, &creases, &modifier).unwrap();
    refinement.points(&cage);
    let v = cage.vertices().next().unwrap();
    let mut step = 0.0;
    g.bench_function("smooth_cube_level5_drag_frame", |b| {
        b.iter(|| {
            step += 0.001;
            let mut moved = (*cage).clone();
            moved.set_position(v, cage.position(v) + DVec3::splat(step));
            let moved = std::sync::Arc::new(moved);
            let points = refinement.points(&moved);
            black_box(refinement.attributes(&points, Shading::Smooth))
        })
    });
    let points: Vec<DVec3> = (0..32 * 32)
        .map(|k| {
            let (i, j) = ((k / 32) as f64, (k % 32) as f64);
            DVec3::new(i, ((i + j) * 0.3).sin(), j)
        })
        .collect();
    let knots = hedra_geom::curves::nurbs::clamped_uniform_knots(3, 32);
    let sheet = hedra_geom::surfaces::NurbsSurface::new(
        3,
        3,
        knots.clone(),
        knots,
        32,
        32,
        points,
        vec![1.0; 32 * 32],
    )
    .unwrap();
    let grid = hedra_doc::render::surface_grid(&sheet);
    let tiles = hedra_doc::render::surface_tiles(&sheet, &grid);
    let point = 16 * 32 + 16;
    g.bench_function("nurbs_32x32_weight_drag_frame", |b| {
        b.iter(|| {
            black_box(
                tiles
                    .iter()
                    .filter(|t| t.inputs.contains(&point))
                    .map(|t| hedra_doc::render::tile_buffers(&sheet, &grid, t))
                    .collect::<Vec<_>>(),
            )
        })
    });
    g.bench_function("nurbs_32x32_whole_tessellation", |b| {
        b.iter(|| {
            black_box(
                tiles
                    .iter()
                    .map(|t| hedra_doc::render::tile_buffers(&sheet, &grid, t))
                    .collect::<Vec<_>>(),
            )
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
