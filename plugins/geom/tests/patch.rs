//! Adding and deleting whole faces.

use hedra_geom::{DVec3, FaceId, HalfEdgeMesh, Primitive, VertexId};
use proptest::prelude::*;

fn polygons(m: &HalfEdgeMesh) -> Vec<Vec<VertexId>> {
    m.faces().map(|f| m.face_vertices(f).collect()).collect()
}

/// A mesh with the same positions as `m` and no edges or faces.
fn vertices_only(m: &HalfEdgeMesh) -> HalfEdgeMesh {
    let mut out = HalfEdgeMesh::new();
    for v in m.vertices() {
        assert_eq!(out.add_vertex(m.position(v)).unwrap(), v);
    }
    out
}

#[test]
fn a_cube_built_face_by_face_is_valid_and_closed() {
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let mut m = vertices_only(&cube);
    for (i, p) in polygons(&cube).iter().enumerate() {
        m.add_face(p).unwrap();
        m.validate()
            .unwrap_or_else(|e| panic!("after face {i}: {e}"));
    }
    let s = m.stats();
    assert_eq!((s.vertices, s.edges, s.faces), (8, 12, 6));
    assert!(s.closed);
    assert!((m.volume() - 8.0).abs() < 1e-12);
}

#[test]
fn delete_then_add_gives_the_face_back() {
    let mut m = Primitive::Cube { size: 2.0 }.build().unwrap();
    let top: Vec<VertexId> = m.face_vertices(FaceId(3)).collect();
    m.delete_faces(&[FaceId(3)], false);
    m.validate().unwrap();
    assert_eq!(
        (m.vertex_count(), m.edge_count(), m.face_count()),
        (8, 12, 5)
    );
    assert_eq!(m.boundary_loops().len(), 1);
    let f = m.add_face(&top).unwrap();
    m.validate().unwrap();
    assert!(m.stats().closed);
    assert!(m.face_normal(f).abs_diff_eq(DVec3::Y, 1e-12));
    // Deleting two adjacent faces removes the edge between them.
    let mut m = Primitive::Cube { size: 2.0 }.build().unwrap();
    m.delete_faces(&[FaceId(0), FaceId(2)], false);
    m.validate().unwrap();
    assert_eq!(
        (m.vertex_count(), m.edge_count(), m.face_count()),
        (8, 11, 4)
    );
    // Deleting everything leaves nothing (or only the kept vertices).
    let mut m = Primitive::Cube { size: 2.0 }.build().unwrap();
    let all: Vec<FaceId> = m.faces().collect();
    let mut kept = m.clone();
    m.delete_faces(&all, false);
    m.validate().unwrap();
    assert_eq!(
        (m.vertex_count(), m.edge_count(), m.face_count()),
        (0, 0, 0)
    );
    kept.delete_faces(&all, true);
    kept.validate().unwrap();
    assert_eq!((kept.vertex_count(), kept.edge_count()), (8, 0));
}

#[test]
fn add_face_refuses_what_would_break_the_mesh() {
    let mut m = Primitive::Cube { size: 2.0 }.build().unwrap();
    let before = m.clone();
    let p: Vec<VertexId> = m.face_vertices(FaceId(0)).collect();
    assert!(
        m.add_face(&p).is_err(),
        "the face's edges already have a face on that side"
    );
    assert!(m.add_face(&[VertexId(0), VertexId(1)]).is_err());
    assert!(
        m.add_face(&[VertexId(0), VertexId(1), VertexId(0)])
            .is_err()
    );
    assert_eq!(m, before);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Any order of adding a primitive's faces that add_face accepts ends in
    /// a valid mesh with the primitive's counts.
    #[test]
    fn faces_added_in_any_order(kind in 0usize..4, seed in any::<u64>()) {
        let src = [
            Primitive::Cube { size: 2.0 },
            Primitive::Grid { x_segments: 3, z_segments: 3, size: 1.0 },
            Primitive::UvSphere { segments: 6, rings: 4, radius: 1.0 },
            Primitive::Torus { major_segments: 6, minor_segments: 4, major_radius: 1.0, minor_radius: 0.3 },
        ][kind].build().unwrap();
        let mut polys = polygons(&src);
        let mut state = seed | 1;
        for i in (1..polys.len()).rev() {
            state ^= state << 13; state ^= state >> 7; state ^= state << 17;
            polys.swap(i, (state % (i as u64 + 1)) as usize);
        }
        let mut m = vertices_only(&src);
        let mut ok = true;
        for p in &polys {
            if m.add_face(p).is_err() {
                ok = false;
                break;
            }
        }
        if ok {
            prop_assert!(m.validate().is_ok(), "{:?}", m.validate());
            prop_assert_eq!((m.vertex_count(), m.edge_count(), m.face_count()), (src.vertex_count(), src.edge_count(), src.face_count()));
            prop_assert_eq!(m.stats().closed, src.stats().closed);
        }
    }
}
