//! Merging vertices: at centre / first / last, welding across seams, and
//! merge by distance.

use glam::DVec3;
use hedra_geom::modeling::{self, MergePoint, ModelingError};
use hedra_geom::{HalfEdgeMesh, Primitive, VertexId};

/// An open box: the cube [x0, x1] × [−1, 1]² without its face at `open_x`,
/// as a separate shell (its own vertices). Faces point outwards.
fn half_box(x0: f64, x1: f64, open_at_x0: bool) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let mut p = Vec::new();
    for &x in &[x0, x1] {
        for &(y, z) in &[(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            p.push(DVec3::new(x, y, z));
        }
    }
    // 0..4 at x0, 4..8 at x1 (same (y, z) order).
    let mut faces = vec![
        vec![0, 4, 5, 1], // z = −1
        vec![1, 5, 6, 2], // y = +1
        vec![2, 6, 7, 3], // z = +1
        vec![3, 7, 4, 0], // y = −1
    ];
    if open_at_x0 {
        faces.push(vec![4, 7, 6, 5]); // +X cap
    } else {
        faces.push(vec![0, 1, 2, 3]); // −X cap
    }
    (p, faces)
}

/// Two open boxes facing each other across x = 0, their rims at the same
/// places but not joined.
fn two_halves() -> HalfEdgeMesh {
    let (mut p, mut f) = half_box(-1.0, 0.0, false);
    let (p2, f2) = half_box(0.0, 1.0, true);
    let off = p.len() as u32;
    p.extend(p2);
    f.extend(
        f2.into_iter()
            .map(|face| face.into_iter().map(|i| i + off).collect()),
    );
    HalfEdgeMesh::from_polygons(&p, &f).unwrap()
}

#[test]
fn merge_by_distance_welds_a_seam_into_a_closed_box() {
    let mut mesh = two_halves();
    let before = mesh.stats();
    assert_eq!(
        (
            before.vertices,
            before.faces,
            before.shells,
            before.boundary_loops
        ),
        (16, 10, 2, 2)
    );
    let all: Vec<VertexId> = mesh.vertices().collect();
    let removed = modeling::merge_by_distance(&mut mesh, &all, 1e-4).unwrap();
    assert_eq!(removed, 4, "the four rim vertices of one side");
    mesh.validate().unwrap();
    let s = mesh.stats();
    assert_eq!((s.vertices, s.edges, s.faces), (12, 20, 10));
    assert_eq!((s.shells, s.boundary_loops, s.genus), (1, 0, Some(0)));
    // The kept rim vertices are the lower ids, at x = 0.
    for v in mesh.vertices().filter(|v| mesh.position(*v).x == 0.0) {
        assert!(v.0 < 8, "{v}");
    }
    // Faces away from the seam keep their ids: the two caps.
    assert!(mesh.is_face(hedra_geom::FaceId(4)) && mesh.is_face(hedra_geom::FaceId(9)));
}

#[test]
fn merge_by_distance_collapses_short_edges_and_refuses_when_nothing_is_close() {
    // Move one cube corner next to its neighbour: the edge between them is
    // 0.01 long; merging at 0.05 removes one vertex and the edge.
    let mut cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let (a, b) = {
        let e = cube.edges().next().unwrap();
        let [a, b] = cube.edge_vertices(e);
        (a, b)
    };
    let pa = cube.position(a);
    cube.set_position(b, pa + (cube.position(b) - pa).normalize() * 0.01);
    let all: Vec<VertexId> = cube.vertices().collect();
    let untouched = cube.clone();
    let e = modeling::merge_by_distance(&mut cube, &all, 0.005).unwrap_err();
    assert!(matches!(e, ModelingError::NothingToMerge { .. }), "{e}");
    assert!(e.to_string().contains("0.005"));
    assert!(cube.same_as(&untouched));
    let e = modeling::merge_by_distance(&mut cube, &all, -1.0).unwrap_err();
    assert!(matches!(e, ModelingError::Parameter { .. }));

    assert_eq!(
        modeling::merge_by_distance(&mut cube, &all, 0.05).unwrap(),
        1
    );
    cube.validate().unwrap();
    let s = cube.stats();
    assert_eq!((s.vertices, s.edges, s.faces), (7, 11, 6));
    assert!((cube.position(a.min(b)) - (pa + (untouched.position(b) - pa) * 0.5)).length() < 1e-12);
}

#[test]
fn merge_at_first_and_last_keep_the_chosen_position() {
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let e = cube.edges().next().unwrap();
    let [a, b] = cube.edge_vertices(e);
    for (point, expected) in [
        (MergePoint::First, cube.position(a)),
        (MergePoint::Last, cube.position(b)),
        (
            MergePoint::Center,
            (cube.position(a) + cube.position(b)) / 2.0,
        ),
    ] {
        let mut m = cube.clone();
        let kept = modeling::merge_vertices(&mut m, &[a, b], point).unwrap();
        m.validate().unwrap();
        assert_eq!(m.vertex_count(), 7);
        assert_eq!(m.position(kept), expected, "{point:?}");
    }
}

#[test]
fn merging_unjoined_vertices_welds_them_or_refuses_a_face_meeting_itself() {
    // Two rim corners of the two halves at the same place: welding them
    // joins the shells at a vertex only — a non-manifold vertex, refused.
    let halves = two_halves();
    let mut m = halves.clone();
    let e = modeling::merge_vertices(&mut m, &[VertexId(4), VertexId(8)], MergePoint::First)
        .unwrap_err();
    assert!(matches!(e, ModelingError::Invalid(_)), "{e}");
    assert!(m.same_as(&halves), "unchanged on error");

    // Opposite corners of one face: the face would meet itself.
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let f = cube.faces().next().unwrap();
    let corners: Vec<VertexId> = cube.face_vertices(f).collect();
    let mut m = cube.clone();
    let e = modeling::merge_vertices(&mut m, &[corners[0], corners[2]], MergePoint::Center)
        .unwrap_err();
    assert!(e.to_string().contains("meet itself"), "{e}");
    assert!(m.same_as(&cube));
}

// ----- vertex bevel ---------------------------------------------------------

use hedra_geom::modeling::bevel_vertices;

#[test]
fn beveling_a_cube_corner_cuts_it_off_with_an_outward_triangle() {
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let corner = cube
        .vertices()
        .find(|&v| cube.position(v) == DVec3::splat(1.0))
        .unwrap();
    let mut m = cube.clone();
    let caps = bevel_vertices(&mut m, &[corner], 0.25).unwrap();
    m.validate().unwrap();
    let s = m.stats();
    assert_eq!((s.vertices, s.edges, s.faces), (10, 15, 7));
    assert!(s.closed);
    assert_eq!(caps.len(), 1);
    let cap: Vec<DVec3> = m.face_vertices(caps[0]).map(|v| m.position(v)).collect();
    let mut got = cap.clone();
    got.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    assert_eq!(
        got,
        vec![
            DVec3::new(0.75, 1.0, 1.0),
            DVec3::new(1.0, 0.75, 1.0),
            DVec3::new(1.0, 1.0, 0.75)
        ]
    );
    assert!(
        m.face_normal(caps[0]).dot(DVec3::ONE) > 0.99 * 3f64.sqrt(),
        "faces outwards"
    );
    assert!(!m.is_vertex(corner));
    assert!(
        m.volume() < cube.volume()
            && (cube.volume() - m.volume() - 0.25f64.powi(3) / 6.0).abs() < 1e-12
    );
}

#[test]
fn beveling_both_ends_of_an_edge_and_a_valence_four_vertex() {
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let e = cube.edges().next().unwrap();
    let [a, b] = cube.edge_vertices(e);
    let mut m = cube.clone();
    assert_eq!(bevel_vertices(&mut m, &[a, b], 0.5).unwrap().len(), 2);
    m.validate().unwrap();
    let s = m.stats();
    assert_eq!((s.vertices, s.edges, s.faces), (12, 18, 8));
    // Wider than half the shared edge: refused, naming the edge, unchanged.
    let mut m = cube.clone();
    let err = bevel_vertices(&mut m, &[a, b], 1.0).unwrap_err();
    assert!(
        matches!(err, ModelingError::Parameter { .. }) && err.to_string().contains("long"),
        "{err}"
    );
    assert!(m.same_as(&cube));

    // The middle vertex of a 2 × 2 grid (valence 4) becomes a square; a
    // border corner (two edges) is just cut.
    let grid = Primitive::Grid {
        x_segments: 2,
        z_segments: 2,
        size: 2.0,
    }
    .build()
    .unwrap();
    let middle = grid
        .vertices()
        .find(|&v| grid.position(v) == DVec3::ZERO)
        .unwrap();
    let corner = grid
        .vertices()
        .find(|&v| grid.position(v) == DVec3::new(1.0, 0.0, 1.0))
        .unwrap();
    let mut g = grid.clone();
    let caps = bevel_vertices(&mut g, &[middle, corner], 0.5).unwrap();
    g.validate().unwrap();
    assert_eq!(caps.len(), 1, "the border corner gets no cap");
    assert_eq!(g.face_vertices(caps[0]).count(), 4);
    assert!(
        g.face_normal(caps[0]).y > 0.999,
        "the cap faces like the grid"
    );
    let s = g.stats();
    // 9 − 2 + 4 + 2 vertices; 4 + 1 faces; one border loop.
    assert_eq!((s.vertices, s.faces, s.boundary_loops), (13, 5, 1));
}

#[test]
fn vertex_bevel_refuses_bad_input_and_leaves_the_mesh() {
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let v = cube.vertices().next().unwrap();
    let mut m = cube.clone();
    assert!(matches!(
        bevel_vertices(&mut m, &[], 0.1),
        Err(ModelingError::Empty(_))
    ));
    assert!(matches!(
        bevel_vertices(&mut m, &[v], 0.0),
        Err(ModelingError::Parameter { .. })
    ));
    assert!(matches!(
        bevel_vertices(&mut m, &[v], f64::NAN),
        Err(ModelingError::Parameter { .. })
    ));
    assert!(matches!(
        bevel_vertices(&mut m, &[VertexId(99)], 0.1),
        Err(ModelingError::Missing(_))
    ));
    assert!(m.same_as(&cube));
}
