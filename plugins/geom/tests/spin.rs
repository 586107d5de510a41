//! Spin and screw (Blender's Spin and Screw): counts, genus, positions
//! against cos/sin, orientation and the refusals.

use hedra_geom::modeling::{SpinProfile, SpinResult, screw, spin};
use hedra_geom::{DVec3, EdgeId, FaceId, HalfEdgeMesh, ModelingError, Primitive};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

fn counts(m: &HalfEdgeMesh) -> (usize, usize, usize) {
    (m.vertex_count(), m.edge_count(), m.face_count())
}

/// The unit square in the XZ plane facing +Y (x, z in [-0.5, 0.5]).
fn plane() -> HalfEdgeMesh {
    Primitive::Plane { size: 1.0 }.build().unwrap()
}

fn only_face(m: &HalfEdgeMesh) -> Vec<FaceId> {
    m.faces().collect()
}

fn edge_nearest(m: &HalfEdgeMesh, p: DVec3) -> EdgeId {
    m.edges()
        .min_by(|a, b| {
            let (da, db) = (
                m.edge_midpoint(*a).distance(p),
                m.edge_midpoint(*b).distance(p),
            );
            da.total_cmp(&db)
        })
        .unwrap()
}

/// Where rotating `p` by `angle` about the Z axis through `c` puts it.
fn about_z(p: DVec3, c: DVec3, angle: f64) -> DVec3 {
    let r = p - c;
    c + DVec3::new(
        r.x * angle.cos() - r.y * angle.sin(),
        r.x * angle.sin() + r.y * angle.cos(),
        r.z,
    )
}

fn has_vertex_at(m: &HalfEdgeMesh, p: DVec3) -> bool {
    m.vertices().any(|v| m.position(v).distance(p) < 1e-12)
}

/// The torus of the brief: a square face offset from the axis, spun a full
/// turn in 8 steps.
#[test]
fn a_square_face_spun_a_full_turn_is_a_closed_torus() {
    let mut m = plane();
    let square: Vec<DVec3> = m.vertices().map(|v| m.position(v)).collect();
    let center = DVec3::new(2.0, 0.0, 0.0);
    let profile = SpinProfile::Faces(only_face(&m));
    let made = spin(&mut m, &profile, center, DVec3::Z, TAU, 8).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (32, 64, 32));
    let stats = m.stats();
    assert_eq!((stats.euler_characteristic, stats.genus), (0, Some(1)));
    assert!(stats.closed);
    assert_eq!(stats.shells, 1);
    assert!(made.closed);
    assert!(made.start_faces.is_empty() && made.end_faces.is_empty());
    assert_eq!(made.faces.len(), 32);
    assert_eq!(made.vertices.len(), 28, "the start ring keeps its ids");
    assert_eq!(made.end_vertices.len(), 4);
    assert_eq!(made.end_edges.len(), 4);
    // Every vertex is a corner of the square turned by k · 45° (all 32 of them).
    for k in 0..8 {
        for &p in &square {
            let at = about_z(p, center, k as f64 * TAU / 8.0);
            assert!(has_vertex_at(&m, at), "no vertex at {at} (step {k})");
        }
    }
    for v in m.vertices() {
        let p = m.position(v) - center;
        let r = (p.x * p.x + p.y * p.y).sqrt();
        assert!(
            (r - 1.5).abs() < 1e-12 || (r - 2.5).abs() < 1e-12,
            "radius {r}"
        );
        let steps = p.y.atan2(p.x) / (TAU / 8.0);
        assert!((steps - steps.round()).abs() < 1e-9, "angle {steps} steps");
    }
    // Outward normals: positive volume, every face pointing away from the
    // tube's centre line (radius 2 about the axis).
    assert!(m.volume() > 0.0);
    for f in m.faces() {
        let c = m.face_centroid(f) - center;
        let radial = DVec3::new(c.x, c.y, 0.0).normalize();
        let out = c - radial * 2.0;
        assert!(m.face_normal(f).dot(out) > 0.0, "{f} faces in");
    }
}

#[test]
fn a_screw_with_no_pitch_is_the_spin() {
    let mut m = plane();
    let faces = SpinProfile::Faces(only_face(&m));
    let made = screw(
        &mut m,
        &faces,
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::Z,
        1,
        8,
        0.0,
    )
    .unwrap();
    m.validate().unwrap();
    assert!(made.closed);
    assert_eq!(counts(&m), (32, 64, 32));
    assert_eq!(m.stats().genus, Some(1));
}

#[test]
fn a_face_spun_a_quarter_turn_in_three_steps_has_both_caps() {
    let mut m = plane();
    let square: Vec<DVec3> = m.vertices().map(|v| m.position(v)).collect();
    let center = DVec3::new(2.0, 0.0, 0.0);
    let profile = SpinProfile::Faces(only_face(&m));
    let made = spin(&mut m, &profile, center, DVec3::Z, FRAC_PI_2, 3).unwrap();
    m.validate().unwrap();
    // 4 rings of 4 vertices, 3 × 4 sides and the two caps.
    assert_eq!(counts(&m), (16, 28, 14));
    let stats = m.stats();
    assert!(stats.closed);
    assert_eq!(stats.genus, Some(0));
    assert!(!made.closed);
    assert_eq!((made.start_faces.len(), made.end_faces.len()), (1, 1));
    assert_eq!(made.faces.len(), 14);
    assert_eq!(made.vertices.len(), 12);
    // Step k turns each corner by k · 30°.
    for k in 0..=3 {
        for &p in &square {
            let at = about_z(p, center, k as f64 * FRAC_PI_2 / 3.0);
            assert!(has_vertex_at(&m, at), "no vertex at {at} (step {k})");
        }
    }
    // The start cap lies where the square was and faces back (+Y, against
    // the sweep, which starts towards -Y); the end cap is the square turned
    // by 90°, facing on (+X there).
    let start = made.start_faces[0];
    assert!(
        m.face_vertices(start)
            .all(|v| m.position(v).y.abs() < 1e-12)
    );
    assert!(m.face_normal(start).dot(DVec3::Y) > 0.999);
    let end = made.end_faces[0];
    for v in m.face_vertices(end) {
        let p = m.position(v);
        assert!((p.x - 2.0).abs() < 1e-12, "the end cap is at x = 2: {p}");
    }
    assert!(m.face_normal(end).dot(DVec3::X) > 0.999);
    assert!(
        made.end_vertices
            .iter()
            .all(|&v| (m.position(v).x - 2.0).abs() < 1e-12)
    );
    assert_eq!(made.end_edges.len(), 4);
    assert!(m.volume() > 0.0);
}

#[test]
fn a_face_of_a_cube_turned_about_its_own_edge_opens_like_a_lid() {
    // The top face (y = 1) hinged on its edge at x = 1: the two hinge
    // vertices lie on the axis and are shared, so the sides are triangles
    // there; the region is attached to the cube, so there is no start cap.
    let mut m = Primitive::Cube { size: 2.0 }.build().unwrap();
    let top = m.faces().find(|&f| m.face_normal(f).y > 0.9).unwrap();
    let made = spin(
        &mut m,
        &SpinProfile::Faces(vec![top]),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::Z,
        -FRAC_PI_2,
        3,
    )
    .unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (14, 27, 15));
    assert!(m.stats().closed);
    assert_eq!(m.stats().genus, Some(0));
    assert!(made.start_faces.is_empty());
    assert_eq!(made.end_faces.len(), 1);
    let triangles = made
        .faces
        .iter()
        .filter(|&&f| m.face_degree(f) == 3)
        .count();
    assert_eq!(triangles, 6);
    // Turned by -90° about the hinge, the lid stands at x = 1, facing +X.
    let lid = made.end_faces[0];
    assert!(
        m.face_vertices(lid)
            .all(|v| (m.position(v).x - 1.0).abs() < 1e-12)
    );
    assert!(m.face_normal(lid).dot(DVec3::X) > 0.999);
    assert!(m.volume() > 8.0);
}

#[test]
fn a_half_disc_spun_a_full_turn_is_a_sphere_with_poles_on_the_axis() {
    // The half disc x >= 0 in the XY plane, its diameter on the Y axis,
    // counter-clockwise seen from +Z: the poles and five points of the arc.
    let mut positions = vec![DVec3::new(0.0, -1.0, 0.0)];
    for i in 1..=5 {
        let t = PI * (i as f64) / 6.0; // from the south pole
        positions.push(DVec3::new(t.sin(), -t.cos(), 0.0));
    }
    positions.push(DVec3::new(0.0, 1.0, 0.0));
    let polygon: Vec<u32> = (0..7).collect();
    let mut m = HalfEdgeMesh::from_polygons(&positions, &[polygon]).unwrap();
    let profile = SpinProfile::Faces(only_face(&m));
    let made = spin(&mut m, &profile, DVec3::ZERO, DVec3::Y, TAU, 8).unwrap();
    m.validate().unwrap();
    // 5 arc vertices × 8 + 2 poles; 8 meridians of 6 edges and 5 rings of 8;
    // 8 × 4 quads and 8 triangles at each pole.
    assert_eq!(counts(&m), (42, 88, 48));
    let stats = m.stats();
    assert!(stats.closed);
    assert_eq!((stats.euler_characteristic, stats.genus), (2, Some(0)));
    assert!(made.closed);
    let triangles = m.faces().filter(|&f| m.face_degree(f) == 3).count();
    assert_eq!(triangles, 16);
    for v in m.vertices() {
        assert!((m.position(v).length() - 1.0).abs() < 1e-12);
    }
    assert!(m.volume() > 0.0, "normals point out");
}

#[test]
fn a_boundary_edge_spun_grows_a_curved_strip_from_the_face() {
    let mut m = plane();
    let e = edge_nearest(&m, DVec3::new(0.5, 0.0, 0.0));
    let center = DVec3::new(1.5, 0.0, 0.0);
    let made = spin(
        &mut m,
        &SpinProfile::Edges(vec![e]),
        center,
        DVec3::Z,
        FRAC_PI_2,
        4,
    )
    .unwrap();
    m.validate().unwrap();
    // 4 steps of one quad each, 2 new vertices per step.
    assert_eq!(counts(&m), (12, 16, 5));
    let stats = m.stats();
    assert_eq!((stats.euler_characteristic, stats.boundary_loops), (1, 1));
    assert_eq!(made.faces.len(), 4);
    assert!(made.start_faces.is_empty() && made.end_faces.is_empty());
    for k in 0..=4 {
        let angle = k as f64 * FRAC_PI_2 / 4.0;
        for z in [-0.5, 0.5] {
            // (0.5, 0, z) is 1 from the axis: it goes to (1.5 - cos, -sin, z).
            let at = DVec3::new(1.5 - angle.cos(), -angle.sin(), z);
            assert!(has_vertex_at(&m, at), "no vertex at {at} (step {k})");
        }
    }
    // The end of the sweep: the profile edge turned by 90°.
    assert_eq!(made.end_edges.len(), 1);
    let [a, b] = m.edge_vertices(made.end_edges[0]);
    for p in [m.position(a), m.position(b)] {
        assert!(p.distance(DVec3::new(1.5, -1.0, p.z)) < 1e-12, "{p}");
    }
    // The strip continues the face's orientation: its first quad faces +Y
    // like the plane (a consistent orientation is what validate checks; the
    // normal shows which side the quads took).
    let first = made.faces[0];
    assert!(m.face_normal(first).y > 0.0);
}

#[test]
fn a_boundary_edge_with_an_end_on_the_axis_sweeps_triangles() {
    let mut m = plane();
    let e = edge_nearest(&m, DVec3::new(0.0, 0.0, 0.5));
    let made = spin(
        &mut m,
        &SpinProfile::Edges(vec![e]),
        DVec3::new(0.5, 0.0, 0.5),
        DVec3::Z,
        FRAC_PI_2,
        3,
    )
    .unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (7, 10, 4));
    assert_eq!(made.vertices.len(), 3);
    assert!(made.faces.iter().all(|&f| m.face_degree(f) == 3));
}

#[test]
fn a_full_turn_of_boundary_edges_would_come_back_onto_their_face() {
    let mut m = plane();
    let before = m.clone();
    let e = edge_nearest(&m, DVec3::new(0.5, 0.0, 0.0));
    let err = spin(
        &mut m,
        &SpinProfile::Edges(vec![e]),
        DVec3::new(1.5, 0.0, 0.0),
        DVec3::Z,
        TAU,
        8,
    )
    .unwrap_err();
    assert!(matches!(err, ModelingError::FullTurnMeetsFace { edge, .. } if edge == e));
    assert!(err.to_string().contains(&e.to_string()), "{err}");
    assert!(m.same_as(&before));
    // So does a full turn of a face attached to the rest of the mesh.
    let mut cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let top = cube.faces().next().unwrap();
    let err = spin(
        &mut cube,
        &SpinProfile::Faces(vec![top]),
        DVec3::new(3.0, 0.0, 0.0),
        DVec3::Z,
        -TAU,
        8,
    )
    .unwrap_err();
    assert!(
        matches!(err, ModelingError::FullTurnMeetsFace { .. }),
        "{err}"
    );
}

#[test]
fn a_screw_advances_its_pitch_each_turn_and_stays_open() {
    // Edge profile: two turns of 8 steps, 1 along +Z per turn.
    let mut m = plane();
    let e = edge_nearest(&m, DVec3::new(0.5, 0.0, 0.0));
    let start: Vec<DVec3> = m.edge_vertices(e).iter().map(|&v| m.position(v)).collect();
    let center = DVec3::new(1.5, 0.0, 0.0);
    let made = screw(
        &mut m,
        &SpinProfile::Edges(vec![e]),
        center,
        DVec3::Z,
        2,
        8,
        1.0,
    )
    .unwrap();
    m.validate().unwrap();
    assert!(!made.closed);
    assert_eq!(counts(&m), (4 + 2 * 16, 4 + 3 * 16, 1 + 16));
    assert_eq!(m.stats().boundary_loops, 1);
    // The end profile is the start moved by turns × pitch along the axis.
    assert_eq!(made.end_vertices.len(), 2);
    for &v in &made.end_vertices {
        let p = m.position(v);
        assert!(
            start.iter().any(|s| p.distance(*s + DVec3::Z * 2.0) < 1e-9),
            "end vertex at {p}"
        );
    }
    // Step 3 of the first turn: 3/8 of a turn round, 3/8 of the pitch up.
    for s in &start {
        let at = about_z(*s, center, 3.0 * TAU / 8.0) + DVec3::Z * (3.0 / 8.0);
        assert!(
            m.vertices().any(|v| m.position(v).distance(at) < 1e-9),
            "{at}"
        );
    }

    // Face profile: one turn of 6 steps, 3 against the axis; both caps.
    let mut m = plane();
    let profile = SpinProfile::Faces(only_face(&m));
    let made = screw(
        &mut m,
        &profile,
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::Z,
        1,
        6,
        -3.0,
    )
    .unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (28, 52, 26));
    assert_eq!(m.stats().genus, Some(0));
    assert_eq!((made.start_faces.len(), made.end_faces.len()), (1, 1));
    let end_z: Vec<f64> = made.end_vertices.iter().map(|&v| m.position(v).z).collect();
    let mut sorted = end_z.clone();
    sorted.sort_by(f64::total_cmp);
    assert!(
        (sorted[0] + 3.5).abs() < 1e-9 && (sorted[3] + 2.5).abs() < 1e-9,
        "{end_z:?}"
    );
    assert!(m.volume() > 0.0);
}

#[test]
fn spin_refuses_bad_input_and_leaves_the_mesh_alone() {
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let faces = SpinProfile::Faces(vec![cube.faces().next().unwrap()]);
    let run = |profile: &SpinProfile, axis: DVec3, angle: f64, steps: u32| {
        let mut m = cube.clone();
        let r: Result<SpinResult, _> = spin(&mut m, profile, DVec3::X * 3.0, axis, angle, steps);
        assert!(m.same_as(&cube), "the mesh changed on {r:?}");
        r.unwrap_err()
    };
    let err = run(&faces, DVec3::ZERO, 1.0, 4);
    assert!(err.to_string().contains("non-zero axis"), "{err}");
    let err = run(&faces, DVec3::Z, 1.0, 0);
    assert!(
        matches!(err, ModelingError::Parameter { what: "steps", .. }),
        "{err}"
    );
    let err = run(&faces, DVec3::Z, TAU, 2);
    assert!(
        err.to_string().contains("at least 3 for a full turn"),
        "{err}"
    );
    let err = run(&faces, DVec3::Z, 0.0, 4);
    assert!(
        matches!(err, ModelingError::Parameter { what: "angle", .. }),
        "{err}"
    );
    let err = run(&faces, DVec3::Z, f64::NAN, 4);
    assert!(
        matches!(err, ModelingError::Parameter { what: "angle", .. }),
        "{err}"
    );
    assert_eq!(
        run(&SpinProfile::Faces(vec![]), DVec3::Z, 1.0, 4),
        ModelingError::Empty("no faces")
    );
    assert_eq!(
        run(&SpinProfile::Edges(vec![]), DVec3::Z, 1.0, 4),
        ModelingError::Empty("no edges")
    );
    let gone = FaceId(99);
    assert_eq!(
        run(&SpinProfile::Faces(vec![gone]), DVec3::Z, 1.0, 4),
        ModelingError::Missing(gone.into())
    );
    // Every edge of a closed cube has faces on both sides.
    let inner = cube.edges().nth(3).unwrap();
    let err = run(&SpinProfile::Edges(vec![inner]), DVec3::Z, 1.0, 4);
    assert_eq!(err, ModelingError::SpinEdgeNotBoundary { edge: inner });
    assert!(
        err.to_string()
            .starts_with(&format!("{inner} has faces on both sides")),
        "{err}"
    );
    // A screw: no turns, a non-finite pitch.
    let mut m = cube.clone();
    let err = screw(&mut m, &faces, DVec3::X * 3.0, DVec3::Z, 0, 8, 1.0).unwrap_err();
    assert!(
        matches!(err, ModelingError::Parameter { what: "turns", .. }),
        "{err}"
    );
    let err = screw(
        &mut m,
        &faces,
        DVec3::X * 3.0,
        DVec3::Z,
        1,
        8,
        f64::INFINITY,
    )
    .unwrap_err();
    assert!(
        matches!(err, ModelingError::Parameter { what: "pitch", .. }),
        "{err}"
    );
    let err = screw(&mut m, &faces, DVec3::X * 3.0, DVec3::Z, 1, 0, 1.0).unwrap_err();
    assert!(
        matches!(err, ModelingError::Parameter { what: "steps", .. }),
        "{err}"
    );
    assert!(m.same_as(&cube));
}

#[test]
fn a_region_with_an_inner_vertex_moves_it_to_the_end_cap() {
    // A 2 × 2 grid: 8 outline vertices and one inside.
    let grid = Primitive::Grid {
        x_segments: 2,
        z_segments: 2,
        size: 1.0,
    }
    .build()
    .unwrap();
    let inner = grid
        .vertices()
        .find(|&v| grid.position(v).length() < 1e-12)
        .unwrap();
    let center = DVec3::new(2.0, 0.0, 0.0);
    let mut m = grid.clone();
    let profile = SpinProfile::Faces(only_face(&m));
    let made = spin(&mut m, &profile, center, DVec3::Z, FRAC_PI_2, 3).unwrap();
    m.validate().unwrap();
    // 8 × 4 outline copies, the inner vertex at the end and its copy at the
    // start; 8 × 3 sides and two caps of 4.
    assert_eq!(counts(&m), (34, 64, 32));
    assert_eq!(m.stats().genus, Some(0));
    assert_eq!((made.start_faces.len(), made.end_faces.len()), (4, 4));
    let end = about_z(DVec3::ZERO, center, FRAC_PI_2);
    assert!(
        m.position(inner).distance(end) < 1e-12,
        "the inner vertex keeps its id at the end"
    );
    assert!(made.end_vertices.contains(&inner));
    assert!(
        made.end_faces
            .iter()
            .all(|&f| m.face_vertices(f).any(|v| v == inner))
    );
    assert!(
        has_vertex_at(&m, DVec3::ZERO),
        "its copy closes the start cap"
    );
    assert!(m.volume() > 0.0);

    // A full turn has no caps: the inner vertex goes.
    let mut m = grid.clone();
    let made = spin(&mut m, &profile, center, DVec3::Z, -TAU, 8).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (64, 128, 64));
    assert_eq!(m.stats().genus, Some(1));
    assert!(!m.is_vertex(inner));
    assert!(made.closed && made.end_faces.is_empty());
    assert!(m.volume() > 0.0);
}
