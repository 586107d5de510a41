//! Seed 000's worked tetrahedron: the winged-edge table and neighbour queries.

use hedra_geom::topology::{halfedge_record, tables, winged_edge_row};
use hedra_geom::{DVec3, EdgeId, FaceId, HalfEdgeMesh, VertexId};

fn tetrahedron() -> HalfEdgeMesh {
    let p = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
    ];
    HalfEdgeMesh::from_polygons(
        &p,
        &[vec![0, 2, 1], vec![0, 1, 3], vec![0, 3, 2], vec![1, 2, 3]],
    )
    .unwrap()
}

#[test]
fn winged_edge_rows_are_consistent_with_the_faces() {
    let m = tetrahedron();
    for e in m.edges() {
        let w = winged_edge_row(&m, e);
        let (l, r) = (w.left_face.unwrap(), w.right_face.unwrap());
        assert_ne!(l, r);
        // The left face runs start -> end, the right face end -> start.
        let lv: Vec<VertexId> = m.face_vertices(l).collect();
        let i = lv.iter().position(|&v| v == w.start).unwrap();
        assert_eq!(lv[(i + 1) % 3], w.end);
        let rv: Vec<VertexId> = m.face_vertices(r).collect();
        let j = rv.iter().position(|&v| v == w.end).unwrap();
        assert_eq!(rv[(j + 1) % 3], w.start);
        // In a triangle the predecessor and successor are the other two edges of that face.
        let mut left_edges: Vec<EdgeId> = m.face_halfedges(l).map(|h| h.edge()).collect();
        left_edges.sort();
        let mut wing = vec![e, w.left_predecessor, w.left_successor];
        wing.sort();
        assert_eq!(wing, left_edges);
    }
    // Edge 0 joins v0 and v2 (first side of face 0).
    let w = winged_edge_row(&m, EdgeId(0));
    assert_eq!(
        (w.start, w.end, w.left_face),
        (VertexId(0), VertexId(2), Some(FaceId(0)))
    );
}

#[test]
fn neighbour_queries_of_the_tetrahedron() {
    let m = tetrahedron();
    for v in m.vertices() {
        assert_eq!(
            m.vertex_faces(v).count(),
            3,
            "every vertex touches three faces"
        );
    }
    for f in m.faces() {
        let mut n: Vec<FaceId> = m.face_neighbors(f).collect();
        n.sort();
        let expected: Vec<FaceId> = m.faces().filter(|&g| g != f).collect();
        assert_eq!(n, expected, "every face neighbours the other three");
    }
    let r = halfedge_record(&m, m.face_halfedge(FaceId(0)));
    assert_eq!(r.face, Some(FaceId(0)));
    assert_eq!(m.prev(r.next), r.halfedge);
    let text = tables(&m);
    assert!(text.contains("winged edges: edge | start | end"));
    assert_eq!(text.lines().filter(|l| l.starts_with("  e")).count(), 6);
    assert_eq!(text.lines().filter(|l| l.starts_with("  h")).count(), 12);
}
