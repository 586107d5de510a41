//! Triangulation and ray casting.

use hedra_geom::query::{is_visible_from, ray_cast, triangulate_face};
use hedra_geom::{DVec3, FaceId, HalfEdgeMesh, Primitive};

fn area(m: &HalfEdgeMesh, tris: &[[hedra_geom::VertexId; 3]]) -> DVec3 {
    tris.iter()
        .map(|[a, b, c]| {
            (m.position(*b) - m.position(*a)).cross(m.position(*c) - m.position(*a)) * 0.5
        })
        .sum()
}

#[test]
fn concave_ngon_triangulates_inside_its_outline() {
    // An L-shaped hexagon in the XY plane (counter-clockwise): area 3.
    let p: Vec<DVec3> = [
        (0.0, 0.0),
        (2.0, 0.0),
        (2.0, 1.0),
        (1.0, 1.0),
        (1.0, 2.0),
        (0.0, 2.0),
    ]
    .iter()
    .map(|&(x, y)| DVec3::new(x, y, 0.0))
    .collect();
    let m = HalfEdgeMesh::from_polygons(&p, &[vec![0, 1, 2, 3, 4, 5]]).unwrap();
    let tris = triangulate_face(&m, FaceId(0));
    assert_eq!(tris.len(), 4);
    let a = area(&m, &tris);
    assert!(
        (a - DVec3::new(0.0, 0.0, 3.0)).length() < 1e-12,
        "{a:?}: every triangle keeps the orientation"
    );
    // No triangle covers the notch at (1.5, 1.5).
    for [a, b, c] in &tris {
        let centroid = (m.position(*a) + m.position(*b) + m.position(*c)) / 3.0;
        assert!(
            !(centroid.x > 1.0 && centroid.y > 1.0),
            "triangle in the notch"
        );
    }
}

#[test]
fn triangulated_primitives_keep_area_and_orientation() {
    for k in Primitive::KINDS {
        let m = Primitive::default_of(k).unwrap().build().unwrap();
        for f in m.faces() {
            let tris = triangulate_face(&m, f);
            assert_eq!(tris.len(), m.face_degree(f) - 2);
            let a = area(&m, &tris);
            assert!((a - m.face_area_vector(f)).length() < 1e-9, "{k} {f}");
        }
    }
}

#[test]
fn ray_cast_hits_the_nearest_face() {
    let m = Primitive::Cube { size: 2.0 }.build().unwrap();
    let (f, t) = ray_cast(&m, DVec3::new(0.2, 0.3, 10.0), DVec3::new(0.0, 0.0, -1.0)).unwrap();
    assert!((t - 9.0).abs() < 1e-12);
    assert!(
        m.face_normal(f).abs_diff_eq(DVec3::Z, 1e-12),
        "the +Z face is hit first"
    );
    assert!(ray_cast(&m, DVec3::new(5.0, 0.0, 10.0), DVec3::new(0.0, 0.0, -1.0)).is_none());
    assert!(
        ray_cast(&m, DVec3::new(0.0, 0.0, 10.0), DVec3::new(0.0, 0.0, 1.0)).is_none(),
        "behind the origin"
    );
}

#[test]
fn corners_behind_the_cube_are_hidden_from_the_eye() {
    let m = Primitive::Cube { size: 2.0 }.build().unwrap();
    let eye = DVec3::new(0.3, 0.2, 5.0);
    assert!(
        is_visible_from(&m, eye, DVec3::new(1.0, 1.0, 1.0)),
        "front corner"
    );
    assert!(
        is_visible_from(&m, eye, DVec3::new(0.0, 0.0, 1.0)),
        "front face centre"
    );
    assert!(
        !is_visible_from(&m, eye, DVec3::new(1.0, 1.0, -1.0)),
        "back corner"
    );
    assert!(
        !is_visible_from(&m, eye, DVec3::new(0.0, -1.0, 0.0)),
        "bottom face centre"
    );
    // Seen from above and to the side, a top back corner is in view.
    let eye = DVec3::new(0.0, 6.0, 0.5);
    assert!(is_visible_from(&m, eye, DVec3::new(1.0, 1.0, -1.0)));
    assert!(!is_visible_from(&m, eye, DVec3::new(1.0, -1.0, -1.0)));
}

/// The region normal weighs faces by area (Newell): on a box 6 wide, 2 tall
/// and 2/3 deep, the top (area 4) and the +z side (area 12) give
/// (0, 1, 3)/√10, not the (0, 1, 1)/√2 of unit normals; normals that cancel
/// give zero.
#[test]
fn region_normal_weighs_faces_by_area() {
    let mut m = hedra_geom::Primitive::Cube { size: 2.0 }.build().unwrap();
    for p in m.positions_mut() {
        p.x *= 3.0;
        p.z *= 1.0 / 3.0;
    }
    let facing = |d: hedra_geom::DVec3| {
        m.faces()
            .find(|&f| m.face_normal(f).dot(d) > 0.999)
            .unwrap()
    };
    let (top, front, bottom) = (
        facing(hedra_geom::DVec3::Y),
        facing(hedra_geom::DVec3::Z),
        facing(-hedra_geom::DVec3::Y),
    );
    let n = m.region_normal(&[top, front]);
    let expected = hedra_geom::DVec3::new(0.0, 4.0, 12.0).normalize();
    assert!((n - expected).length() < 1e-12, "{n}");
    assert_eq!(m.region_normal(&[top, bottom]), hedra_geom::DVec3::ZERO);
    assert_eq!(m.region_normal(&[top]), hedra_geom::DVec3::Y);
}

/// The area vector of a list of corners is the face's, bit for bit, on
/// non-planar faces of every size; a quad's equals the half cross product
/// of its diagonals.
#[test]
fn polygon_area_vector_equals_the_face_s() {
    use hedra_geom::query::polygon_area_vector;
    let mut m = Primitive::UvSphere {
        segments: 7,
        rings: 5,
        radius: 1.3,
    }
    .build()
    .unwrap();
    for (i, v) in m.vertices().collect::<Vec<_>>().into_iter().enumerate() {
        let p = m.position(v);
        m.set_position(v, p + DVec3::new(0.01 * i as f64, -0.003 * i as f64, 0.1));
    }
    let mut sizes = std::collections::BTreeSet::new();
    for f in m.faces() {
        let corners: Vec<DVec3> = m.face_vertices(f).map(|v| m.position(v)).collect();
        sizes.insert(corners.len());
        assert_eq!(
            polygon_area_vector(&corners),
            m.face_area_vector(f),
            "face {f}"
        );
    }
    assert_eq!(sizes.into_iter().collect::<Vec<_>>(), vec![3, 4]);
    let q = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(2.0, 0.0, 0.3),
        DVec3::new(2.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.5),
    ];
    let diagonals = (q[2] - q[0]).cross(q[3] - q[1]) * 0.5;
    assert!((polygon_area_vector(&q) - diagonals).length() < 1e-15);
}
