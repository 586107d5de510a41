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

#[test]
fn edge_loops_go_straight_through_valence_four_vertices() {
    use hedra_geom::Primitive;
    use hedra_geom::topology::{edge_loop, linked_vertices};
    // Around a UV sphere's equator: a closed loop of `segments` edges.
    let m = Primitive::UvSphere {
        segments: 8,
        rings: 4,
        radius: 1.0,
    }
    .build()
    .unwrap();
    let e = m
        .edges()
        .find(|&e| {
            let [a, b] = m.edge_vertices(e);
            m.position(a).y.abs() < 1e-9 && m.position(b).y.abs() < 1e-9
        })
        .unwrap();
    let lp = edge_loop(&m, e);
    assert_eq!(lp.len(), 8);
    assert!(lp.iter().all(|&x| {
        m.edge_vertices(x)
            .iter()
            .all(|v| m.position(*v).y.abs() < 1e-9)
    }));
    // A meridian edge stops at the poles (valence 8).
    let e = m
        .edges()
        .find(|&e| {
            let [a, b] = m.edge_vertices(e);
            (m.position(a).y - m.position(b).y).abs() > 0.1
                && m.vertex_valence(a) == 4
                && m.vertex_valence(b) == 4
        })
        .unwrap();
    assert_eq!(edge_loop(&m, e).len(), 4, "pole to pole over 4 rings");
    // On a grid the loop runs to both boundaries.
    let g = Primitive::Grid {
        x_segments: 4,
        z_segments: 3,
        size: 1.0,
    }
    .build()
    .unwrap();
    let inner = g
        .edges()
        .find(|&e| {
            !g.is_boundary_edge(e) && g.edge_vertices(e).iter().all(|v| !g.is_boundary_vertex(*v))
        })
        .unwrap();
    let lp = edge_loop(&g, inner);
    assert!(lp.len() == 4 || lp.len() == 3, "{}", lp.len());
    assert_eq!(
        linked_vertices(&g, [hedra_geom::VertexId(0)]).len(),
        g.vertex_count()
    );
}
