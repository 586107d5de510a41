//! The Mirror and Array modifiers' kernels: counts, positions, topology and
//! validity of the copies they build.

use hedra_geom::modeling::{
    ArrayOffset, InvalidResult, arrayed, arrayed_copies, delete_faces, mirrored, mirrored_copies,
};
use hedra_geom::subdivision::Creases;
use hedra_geom::{DVec3, HalfEdgeMesh, ModelingError, Primitive};

fn counts(m: &HalfEdgeMesh) -> (usize, usize, usize) {
    (m.vertex_count(), m.edge_count(), m.face_count())
}

fn cube() -> HalfEdgeMesh {
    Primitive::Cube { size: 2.0 }.build().unwrap()
}

/// Deletes the faces whose normal points along `dir`.
fn without_faces(mut m: HalfEdgeMesh, dir: DVec3) -> HalfEdgeMesh {
    let faces: Vec<_> = m
        .faces()
        .filter(|&f| m.face_normal(f).dot(dir) > 0.9)
        .collect();
    delete_faces(&mut m, &faces).unwrap();
    m.validate().unwrap();
    m
}

/// The half of a box of side 2 on x ≥ 0: x in 0..1, y and z in -1..1, with
/// its face on x = 0 removed (the seam a mirror closes).
fn half_box() -> HalfEdgeMesh {
    let mut m = cube();
    for v in m.vertices().collect::<Vec<_>>() {
        let p = m.position(v);
        m.set_position(v, DVec3::new((p.x + 1.0) / 2.0, p.y, p.z));
    }
    without_faces(m, DVec3::NEG_X)
}

#[test]
fn a_half_box_mirrored_in_x_with_merge_is_one_closed_box() {
    let half = half_box();
    assert_eq!(counts(&half), (8, 12, 5));
    let m = mirrored(&half, [true, false, false], Some(0.001)).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (12, 20, 10));
    let s = m.stats();
    assert!(s.closed);
    assert_eq!((s.shells, s.genus, s.euler_characteristic), (1, Some(0), 2));
    let (lo, hi) = m.bounds().unwrap();
    assert_eq!((lo, hi), (DVec3::splat(-1.0), DVec3::ONE));
    // Normals face outwards on both halves: the volume is the whole box's.
    assert!((m.volume() - 8.0).abs() < 1e-9, "{}", m.volume());
    for f in m.faces() {
        let c = m.face_centroid(f);
        assert!(m.face_normal(f).dot(c) > 0.0, "{f} faces inwards");
    }
}

#[test]
fn without_merge_the_mirror_images_stay_separate_open_pieces() {
    let m = mirrored(&half_box(), [true, false, false], None).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (16, 24, 10));
    let s = m.stats();
    assert_eq!((s.shells, s.boundary_loops, s.closed), (2, 2, false));
}

#[test]
fn seam_vertices_within_the_merge_distance_are_snapped_onto_the_plane() {
    let mut half = half_box();
    // One seam vertex slightly off the plane, inside the distance.
    let v = half
        .vertices()
        .find(|&v| half.position(v).x == 0.0)
        .unwrap();
    half.set_position(v, half.position(v) + DVec3::new(0.0005, 0.0, 0.0));
    let c = mirrored_copies(&half, [true, false, false], Some(0.001)).unwrap();
    assert_eq!(counts(&c.mesh), (12, 20, 10));
    let on_plane = c.mesh.vertices().filter(|&w| c.vertex_source(w) == v);
    for w in on_plane {
        assert_eq!(c.mesh.position(w).x, 0.0);
    }
    // Outside the distance the seam stays open.
    let open = mirrored(&half, [true, false, false], Some(0.0001)).unwrap();
    open.validate().unwrap();
    assert_eq!(open.stats().boundary_loops, 1);
    assert_eq!(counts(&open), (13, 22, 10));
}

#[test]
fn mirroring_in_x_y_and_z_makes_eight_outward_copies() {
    let mut m = cube();
    for v in m.vertices().collect::<Vec<_>>() {
        m.set_position(v, m.position(v) + DVec3::splat(2.0));
    }
    let all = mirrored(&m, [true, true, true], Some(0.001)).unwrap();
    all.validate().unwrap();
    assert_eq!(counts(&all), (64, 96, 48));
    assert_eq!(all.shell_count(), 8);
    assert!((all.volume() - 64.0).abs() < 1e-9, "{}", all.volume());
    // Each corner of the result is one copy: its eight points have the
    // signs of that octant.
    let (lo, hi) = all.bounds().unwrap();
    assert_eq!((lo, hi), (DVec3::splat(-3.0), DVec3::splat(3.0)));
    // Y alone: two copies, order of axes does not matter for counts.
    let y = mirrored(&m, [false, true, false], None).unwrap();
    assert_eq!(counts(&y), (16, 24, 12));
    assert!((y.volume() - 16.0).abs() < 1e-9);
}

#[test]
fn a_quarter_mirrored_in_x_and_y_with_merge_closes_into_one_box() {
    // The quarter x ≥ 0, y ≥ 0 of a box: its faces on x = 0 and y = 0 removed.
    let mut m = cube();
    for v in m.vertices().collect::<Vec<_>>() {
        let p = m.position(v);
        m.set_position(v, DVec3::new((p.x + 1.0) / 2.0, (p.y + 1.0) / 2.0, p.z));
    }
    let m = without_faces(without_faces(m, DVec3::NEG_X), DVec3::NEG_Y);
    let whole = mirrored(&m, [true, true, false], Some(1e-6)).unwrap();
    whole.validate().unwrap();
    let s = whole.stats();
    assert!(s.closed);
    assert_eq!((s.shells, s.genus), (1, Some(0)));
    // 4 quarters of 3 faces (+x or +y side, top, bottom) each.
    assert_eq!(whole.face_count(), 16);
    assert!((whole.volume() - 8.0).abs() < 1e-9);
}

#[test]
fn no_mirror_axis_copies_the_mesh_and_bad_input_is_refused() {
    let half = half_box();
    let same = mirrored(&half, [false; 3], Some(0.001)).unwrap();
    assert_eq!(counts(&same), counts(&half));
    let e = mirrored(&half, [true, false, false], Some(-1.0)).unwrap_err();
    assert_eq!(
        e.to_string(),
        "merge distance must be a finite distance ≥ 0, got -1"
    );
    assert_eq!(
        mirrored(&HalfEdgeMesh::new(), [true, false, false], None).unwrap_err(),
        ModelingError::Empty("no faces")
    );
}

#[test]
fn a_seam_face_left_on_the_mirror_plane_is_refused_naming_the_mirror() {
    // The half box with its face on x = 0 kept: welded, the seam edges
    // would each have four faces.
    let mut closed = cube();
    for v in closed.vertices().collect::<Vec<_>>() {
        let p = closed.position(v);
        closed.set_position(v, DVec3::new((p.x + 1.0) / 2.0, p.y, p.z));
    }
    let e = mirrored(&closed, [true, false, false], Some(0.001)).unwrap_err();
    assert!(
        matches!(
            e,
            ModelingError::Invalid(InvalidResult::Copies {
                operation: "the mirror",
                ..
            })
        ),
        "{e:?}"
    );
    assert!(
        e.to_string().starts_with(
            "the result would not be a valid mesh: the mirror would not make a manifold surface"
        ),
        "{e}"
    );
    // Without merge the two closed halves are separate and valid.
    let apart = mirrored(&closed, [true, false, false], None).unwrap();
    assert_eq!(apart.shell_count(), 2);
}

/// A cube of side 2 with its ±X faces removed: an open square tube, x in -1..1.
fn tube() -> HalfEdgeMesh {
    without_faces(without_faces(cube(), DVec3::X), DVec3::NEG_X)
}

#[test]
fn an_array_of_three_open_tubes_with_merge_is_one_open_tube() {
    let t = tube();
    assert_eq!(counts(&t), (8, 12, 4));
    let offset = ArrayOffset {
        relative: Some(DVec3::X),
        constant: None,
    };
    let m = arrayed(&t, 3, offset, Some(0.001)).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (16, 28, 12));
    let s = m.stats();
    assert_eq!(
        (s.shells, s.boundary_loops, s.genus, s.closed),
        (1, 2, Some(0), false)
    );
    let (lo, hi) = m.bounds().unwrap();
    assert_eq!((lo, hi), (DVec3::splat(-1.0), DVec3::new(5.0, 1.0, 1.0)));
    // Without merge: three separate tubes side by side.
    let apart = arrayed(&t, 3, offset, None).unwrap();
    apart.validate().unwrap();
    assert_eq!(counts(&apart), (24, 36, 12));
    assert_eq!(apart.stats().boundary_loops, 6);
}

#[test]
fn array_offsets_add_relative_times_the_box_size_and_constant() {
    let offset = ArrayOffset {
        relative: Some(DVec3::new(0.5, 0.0, 0.0)),
        constant: Some(DVec3::new(0.0, 0.0, 3.0)),
    };
    assert_eq!(offset.step(DVec3::splat(2.0)), DVec3::new(1.0, 0.0, 3.0));
    let c = arrayed_copies(&cube(), 4, offset, None).unwrap();
    c.mesh.validate().unwrap();
    assert_eq!(counts(&c.mesh), (32, 48, 24));
    let (lo, hi) = c.mesh.bounds().unwrap();
    assert_eq!(lo, DVec3::splat(-1.0));
    assert_eq!(hi, DVec3::new(4.0, 1.0, 10.0));
    // Every copy keeps the cube's orientation.
    assert!((c.mesh.volume() - 32.0).abs() < 1e-9);
    // One copy is the mesh itself.
    let one = arrayed(&cube(), 1, offset, Some(0.01)).unwrap();
    assert_eq!(counts(&one), (8, 12, 6));
}

#[test]
fn array_count_zero_and_overlapping_welds_are_refused() {
    let offset = ArrayOffset {
        relative: Some(DVec3::X),
        constant: None,
    };
    let e = arrayed(&tube(), 0, offset, None).unwrap_err();
    assert_eq!(
        e.to_string(),
        "array count must be between 1 and 10000, got 0"
    );
    // Closed cubes touching face to face: the welded face would be shared
    // by four faces.
    let e = arrayed(&cube(), 2, offset, Some(0.001)).unwrap_err();
    assert!(
        matches!(
            e,
            ModelingError::Invalid(InvalidResult::Copies {
                operation: "the array",
                ..
            })
        ),
        "{e:?}"
    );
}

#[test]
fn creases_and_corners_follow_every_copy() {
    let t = tube();
    let mut creases = Creases::default();
    // Crease one edge running along x (inside a copy, not on a seam) and a corner.
    let along = t
        .edges()
        .find(|&e| {
            let [a, b] = t.edge_vertices(e);
            (t.position(a) - t.position(b)).x.abs() > 1.0
        })
        .unwrap();
    creases.set_edge(along, 2.0);
    let corner = t.vertices().next().unwrap();
    creases.set_vertex(corner, 10.0);
    let offset = ArrayOffset {
        relative: Some(DVec3::X),
        constant: None,
    };
    let c = arrayed_copies(&t, 3, offset, Some(0.001)).unwrap();
    let carried = c.creases(&t, &creases);
    assert_eq!(carried.edges.len(), 3);
    assert!(carried.edges.values().all(|&s| s == 2.0));
    // One creased corner per copy (welded or not).
    assert_eq!(carried.vertices.len(), 3);
    assert!(carried.vertices.values().all(|&s| s == 10.0));
    // Every face corner of the result maps to a corner of its source face.
    for h in c.mesh.halfedges().filter(|&h| c.mesh.face(h).is_some()) {
        let s = c.corner_source(&t, h).expect("a corner has a source");
        assert_eq!(t.face(s), Some(c.face_source(c.mesh.face(h).unwrap())));
        // The corner sits at a copy of its source vertex: moved by whole steps along x.
        let d = c.mesh.position(c.mesh.origin(h)) - t.position(t.origin(s));
        assert!(
            d.y == 0.0 && d.z == 0.0 && [0.0, 2.0, 4.0].contains(&d.x),
            "{d}"
        );
    }
    // Mirrored copies run their faces backwards, but corners still map.
    let m = mirrored_copies(&half_box(), [true, false, false], Some(0.001)).unwrap();
    for h in m.mesh.halfedges().filter(|&h| m.mesh.face(h).is_some()) {
        assert!(m.corner_source(&half_box(), h).is_some());
    }
}

#[test]
fn a_mirrored_copy_of_a_hole_is_a_hole() {
    let half = half_box();
    let top = half.faces().find(|&f| half.face_normal(f).y > 0.9).unwrap();
    let mut creases = Creases::default();
    creases.set_hole(top, true);
    let c = mirrored_copies(&half, [true, false, false], Some(0.001)).unwrap();
    let carried = c.creases(&half, &creases);
    // Both halves' tops, and nothing else.
    assert_eq!(carried.holes.len(), 2);
    for &f in &carried.holes {
        assert_eq!(c.face_source(f), top);
        assert!(c.mesh.face_normal(f).y > 0.9);
    }
}
