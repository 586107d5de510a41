//! The knife (Blender's K): counts, positions and validity after each cut.

use hedra_geom::modeling::{KnifeResult, knife};
use hedra_geom::{DVec3, FaceId, HalfEdgeMesh, ModelingError, Primitive, VertexId};

fn cube() -> HalfEdgeMesh {
    Primitive::Cube { size: 2.0 }.build().unwrap()
}

/// A 3 × 3 grid of unit quads in the XZ plane, x and z from −1.5 to 1.5.
fn grid() -> HalfEdgeMesh {
    Primitive::Grid {
        x_segments: 3,
        z_segments: 3,
        size: 3.0,
    }
    .build()
    .unwrap()
}

fn counts(m: &HalfEdgeMesh) -> (usize, usize, usize) {
    (m.vertex_count(), m.edge_count(), m.face_count())
}

fn euler_characteristic(m: &HalfEdgeMesh) -> i64 {
    m.vertex_count() as i64 - m.edge_count() as i64 + m.face_count() as i64
}

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// The face whose normal points along `direction`, and its corners.
fn face_facing(m: &HalfEdgeMesh, direction: DVec3) -> (FaceId, Vec<VertexId>) {
    let f = m
        .faces()
        .find(|&f| m.face_normal(f).dot(direction) > 0.999)
        .unwrap();
    (f, m.face_vertices(f).collect())
}

/// Every new vertex is at one of `expected`, in order.
fn assert_positions(m: &HalfEdgeMesh, made: &KnifeResult, expected: &[DVec3]) {
    let got: Vec<DVec3> = made.new_vertices.iter().map(|&v| m.position(v)).collect();
    assert_eq!(got.len(), expected.len(), "{got:?}");
    for (g, e) in got.iter().zip(expected) {
        assert!(g.distance(*e) < 1e-12, "{g} instead of {e}");
    }
}

#[test]
fn a_cut_across_the_front_of_a_cube_leaves_the_back_whole() {
    let mut m = cube();
    let back = face_facing(&m, -DVec3::Z);
    let made = knife(&mut m, &[v(0.0, 1.0, 1.0), v(0.0, -1.0, 1.0)], -DVec3::Z).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (10, 15, 7));
    assert_eq!(euler_characteristic(&m), 2);
    assert_positions(&m, &made, &[v(0.0, 1.0, 1.0), v(0.0, -1.0, 1.0)]);
    assert_eq!(made.cut_edges.len(), 1);
    let [a, b] = m.edge_vertices(made.cut_edges[0]);
    assert_eq!(
        [a, b].map(|x| m.position(x)),
        [v(0.0, 1.0, 1.0), v(0.0, -1.0, 1.0)]
    );
    // The back face is the same quad; the front became two.
    assert_eq!(face_facing(&m, -DVec3::Z), back);
    let fronts: Vec<FaceId> = m.faces().filter(|&f| m.face_normal(f).z > 0.999).collect();
    assert_eq!(fronts.len(), 2);
    assert!(fronts.iter().all(|&f| m.face_degree(f) == 4));
    assert!((m.volume() - 8.0).abs() < 1e-12);
}

#[test]
fn a_three_point_path_bends_around_a_corner_edge() {
    let mut m = cube();
    // Seen from the front right: the front (z = 1) and right (x = 1) faces.
    let view = v(-1.0, 0.0, -1.0);
    let path = [v(-1.0, 0.0, 1.0), v(1.0, 0.0, 1.0), v(1.0, 0.0, -1.0)];
    let made = knife(&mut m, &path, view).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (11, 17, 8));
    assert_eq!(euler_characteristic(&m), 2);
    assert_positions(&m, &made, &path);
    assert_eq!(made.cut_edges.len(), 2);
    // Both cut edges lie at y = 0, one on each face.
    for &e in &made.cut_edges {
        assert!(m.edge_vertices(e).iter().all(|&x| m.position(x).y == 0.0));
    }
    // The left, back, top and bottom faces are untouched quads.
    for d in [-DVec3::X, -DVec3::Z, DVec3::Y, -DVec3::Y] {
        let faces = m.faces().filter(|&f| m.face_normal(f).dot(d) > 0.999);
        assert_eq!(faces.count(), 1, "{d}");
    }
}

#[test]
fn one_segment_walks_across_a_corner_edge_into_the_next_face() {
    let mut m = cube();
    let view = v(-1.0, 0.0, -1.0);
    let (a, b) = (v(-1.0, -0.5, 1.0), v(1.0, 0.5, -1.0));
    let made = knife(&mut m, &[a, b], view).unwrap();
    m.validate().unwrap();
    // Three edges split (start, the corner edge x = z = 1, end), two faces
    // split. The left face (turned away) also meets the curtain ahead of the
    // start, but the walk takes the face facing the viewer.
    assert_eq!(counts(&m), (11, 17, 8));
    assert_positions(&m, &made, &[a, v(1.0, 0.0, 1.0), b]);
    assert_eq!(made.cut_edges.len(), 2);
    assert_eq!(
        m.faces()
            .filter(|&f| m.face_normal(f).x < -0.999)
            .map(|f| m.face_degree(f))
            .collect::<Vec<_>>(),
        vec![5],
        "the left face only gained the start vertex"
    );
}

#[test]
fn a_cut_between_two_corners_of_a_face_adds_only_the_diagonal() {
    let mut m = cube();
    let made = knife(&mut m, &[v(-1.0, -1.0, 1.0), v(1.0, 1.0, 1.0)], -DVec3::Z).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (8, 13, 7));
    assert!(made.new_vertices.is_empty());
    assert_eq!(made.cut_edges.len(), 1);
    let ends = m.edge_vertices(made.cut_edges[0]).map(|x| m.position(x));
    assert_eq!(ends, [v(-1.0, -1.0, 1.0), v(1.0, 1.0, 1.0)]);
    assert!(m.faces().filter(|&f| m.face_degree(f) == 3).count() == 2);
}

#[test]
fn a_point_snapped_near_a_vertex_uses_the_vertex() {
    let mut m = cube();
    // 1e-7 off the corners: within the tolerance (1e-5 × the diagonal).
    let path = [v(-1.0 + 1e-7, -1.0, 1.0), v(1.0, 1.0 - 1e-7, 1.0)];
    let made = knife(&mut m, &path, -DVec3::Z).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (8, 13, 7));
    assert!(made.new_vertices.is_empty());
}

#[test]
fn an_end_inside_a_face_is_dropped_back_to_the_last_edge_crossed() {
    // From the top edge's midpoint to the middle of the front face: the
    // dangling edge Blender would keep is dropped; the edge split stays.
    let mut m = cube();
    let made = knife(&mut m, &[v(0.0, 1.0, 1.0), v(0.0, 0.0, 1.0)], -DVec3::Z).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (9, 13, 6));
    assert_positions(&m, &made, &[v(0.0, 1.0, 1.0)]);
    assert!(made.cut_edges.is_empty());
    assert!(m.vertices().all(|x| m.vertex_valence(x) >= 2));
}

#[test]
fn a_point_inside_a_face_between_two_edges_bends_the_cut() {
    let mut m = cube();
    let path = [v(0.0, 1.0, 1.0), v(0.5, 0.0, 1.0), v(0.0, -1.0, 1.0)];
    let made = knife(&mut m, &path, -DVec3::Z).unwrap();
    m.validate().unwrap();
    // Two edge splits, the inside vertex, two new edges, one new face.
    assert_eq!(counts(&m), (11, 16, 7));
    assert_positions(&m, &made, &path);
    assert_eq!(made.cut_edges.len(), 2);
    assert_eq!(m.vertex_valence(made.new_vertices[1]), 2);
    let fronts: Vec<usize> = m
        .faces()
        .filter(|&f| m.face_normal(f).z > 0.999)
        .map(|f| m.face_degree(f))
        .collect();
    assert_eq!(fronts, vec![5, 5]);
}

#[test]
fn a_path_from_inside_a_grid_cell_cuts_the_two_cells_it_crosses() {
    let mut m = grid();
    assert_eq!(counts(&m), (16, 24, 9));
    // From inside the middle left cell to the right boundary, across the
    // middle cell and the middle right cell.
    let (a, b) = (v(-1.0, 0.0, 0.2), v(1.5, 0.0, -0.3));
    let made = knife(&mut m, &[a, b], -DVec3::Y).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (19, 29, 11));
    // The new vertices are where the segment (the curtain, seen from above)
    // crosses x = −0.5 and x = 0.5, then the end on x = 1.5.
    let z_at = |x: f64| a.z + (b.z - a.z) * (x - a.x) / (b.x - a.x);
    assert_positions(
        &m,
        &made,
        &[v(-0.5, 0.0, z_at(-0.5)), v(0.5, 0.0, z_at(0.5)), b],
    );
    let curtain = (b - a).cross(DVec3::Y).normalize();
    for &x in &made.new_vertices {
        assert!((m.position(x) - a).dot(curtain).abs() < 1e-12);
    }
    assert_eq!(made.cut_edges.len(), 2);
    // The start cell is not split: it only gained a vertex on its side.
    let start_cell = m
        .faces()
        .find(|&f| {
            let c = m.face_centroid(f);
            c.x < -0.5 && c.z.abs() < 0.5
        })
        .unwrap();
    assert_eq!(m.face_degree(start_cell), 5);
}

#[test]
fn a_path_through_grid_vertices_uses_them() {
    let mut m = grid();
    let made = knife(&mut m, &[v(-1.5, 0.0, -1.5), v(1.5, 0.0, 1.5)], -DVec3::Y).unwrap();
    m.validate().unwrap();
    // The three diagonal cells each get a diagonal through existing corners.
    assert_eq!(counts(&m), (16, 27, 12));
    assert!(made.new_vertices.is_empty());
    assert_eq!(made.cut_edges.len(), 3);
    for &e in &made.cut_edges {
        let [p, q] = m.edge_vertices(e).map(|x| m.position(x));
        assert_eq!((p.x - p.z, q.x - q.z), (0.0, 0.0));
    }
}

#[test]
fn a_walk_stops_where_the_surface_ends() {
    let mut m = grid();
    let middle = m
        .faces()
        .find(|&f| m.face_centroid(f).length() < 1e-9)
        .unwrap();
    m.delete_faces(&[middle], true);
    m.validate().unwrap();
    let before = counts(&m);
    // Across the middle row, through the hole: only the left cell is cut.
    let (a, b) = (v(-1.5, 0.0, 0.0), v(1.5, 0.0, 0.0));
    let made = knife(&mut m, &[a, b], -DVec3::Y).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (before.0 + 2, before.1 + 3, before.2 + 1));
    assert_positions(&m, &made, &[a, v(-0.5, 0.0, 0.0)]);
    assert_eq!(made.cut_edges.len(), 1);
}

#[test]
fn a_later_segment_starts_afresh_after_a_boundary() {
    let mut m = grid();
    let middle = m
        .faces()
        .find(|&f| m.face_centroid(f).length() < 1e-9)
        .unwrap();
    m.delete_faces(&[middle], true);
    let before = counts(&m);
    // The first segment stops at the hole; the second starts at its own
    // first point, on the right cell's left side, and cuts that cell.
    let path = [v(-1.5, 0.0, 0.0), v(0.5, 0.0, 0.0), v(1.5, 0.0, 0.0)];
    let made = knife(&mut m, &path, -DVec3::Y).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (before.0 + 4, before.1 + 6, before.2 + 2));
    assert_eq!(made.cut_edges.len(), 2);
}

#[test]
fn refusals_name_the_point_and_leave_the_mesh_alone() {
    let cube = cube();
    let mut m = cube.clone();
    let err = knife(&mut m, &[v(0.0, 1.0, 1.0)], -DVec3::Z).unwrap_err();
    assert!(matches!(
        err,
        ModelingError::Parameter {
            what: "knife points",
            ..
        }
    ));
    let err = knife(&mut m, &[v(0.0, 1.0, 1.0), v(0.0, 0.0, 3.0)], -DVec3::Z).unwrap_err();
    assert_eq!(
        err,
        ModelingError::NotOnSurface {
            index: 1,
            point: v(0.0, 0.0, 3.0)
        }
    );
    assert_eq!(
        err.to_string(),
        "knife point 1 at [0, 0, 3] is not on the mesh surface"
    );
    let err = knife(&mut m, &[v(0.0, 1.0, 1.0), v(0.0, -1.0, 1.0)], DVec3::ZERO).unwrap_err();
    assert!(matches!(
        err,
        ModelingError::Parameter {
            what: "view direction",
            ..
        }
    ));
    let err = knife(
        &mut m,
        &[v(0.0, 1.0, 1.0), v(f64::NAN, 0.0, 1.0)],
        -DVec3::Z,
    )
    .unwrap_err();
    assert!(matches!(
        err,
        ModelingError::Parameter {
            what: "knife point",
            ..
        }
    ));
    // Two points inside the front face: no edge reached.
    let err = knife(&mut m, &[v(-0.5, 0.0, 1.0), v(0.5, 0.2, 1.0)], -DVec3::Z).unwrap_err();
    assert_eq!(err, ModelingError::NothingToCut);
    assert_eq!(
        err.to_string(),
        "the knife path crosses no edge: nothing to cut"
    );
    assert!(m.same_as(&cube));
}
