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
