//! Building, validating and storing half-edge meshes.

use hedra_geom::{BuildError, DVec3, HalfEdgeMesh, Primitive, VertexId};

fn all_primitives() -> Vec<Primitive> {
    Primitive::KINDS
        .iter()
        .map(|k| Primitive::default_of(k).unwrap())
        .collect()
}

#[test]
fn every_primitive_is_valid_outward_and_has_the_right_euler_characteristic() {
    for p in all_primitives() {
        let m = p.build().unwrap();
        m.validate().unwrap_or_else(|e| panic!("{}: {e}", p.kind()));
        let s = m.stats();
        match p.kind() {
            "plane" | "grid" => {
                assert_eq!(s.euler_characteristic, 1, "{}", p.kind());
                assert_eq!(s.boundary_loops, 1);
                assert!(!s.closed);
                assert_eq!(s.genus, Some(0));
            }
            "torus" => {
                assert_eq!(s.euler_characteristic, 0);
                assert!(s.closed);
                assert_eq!(s.genus, Some(1));
            }
            _ => {
                assert_eq!(s.euler_characteristic, 2, "{}", p.kind());
                assert!(s.closed, "{}", p.kind());
                assert_eq!(s.genus, Some(0));
                assert!(m.volume() > 0.0, "{} faces point inwards", p.kind());
            }
        }
        assert_eq!(s.shells, 1);
        // Every face normal points away from the centre for the convex closed ones.
        if ["cube", "uv_sphere", "ico_sphere", "cylinder"].contains(&p.kind()) {
            for f in m.faces() {
                assert!(
                    m.face_normal(f).dot(m.face_centroid(f)) > 0.0,
                    "{} {f}",
                    p.kind()
                );
            }
        }
    }
}

#[test]
fn primitive_counts_match_known_values() {
    let count = |p: Primitive| {
        let m = p.build().unwrap();
        (m.vertex_count(), m.edge_count(), m.face_count())
    };
    assert_eq!(count(Primitive::Cube { size: 2.0 }), (8, 12, 6));
    assert_eq!(count(Primitive::Plane { size: 2.0 }), (4, 4, 1));
    assert_eq!(
        count(Primitive::Grid {
            x_segments: 3,
            z_segments: 2,
            size: 1.0
        }),
        (12, 17, 6)
    );
    assert_eq!(
        count(Primitive::IcoSphere {
            subdivisions: 0,
            radius: 1.0
        }),
        (12, 30, 20)
    );
    assert_eq!(
        count(Primitive::IcoSphere {
            subdivisions: 1,
            radius: 1.0
        }),
        (42, 120, 80)
    );
    assert_eq!(
        count(Primitive::UvSphere {
            segments: 8,
            rings: 4,
            radius: 1.0
        }),
        (26, 56, 32)
    );
    assert_eq!(
        count(Primitive::Cylinder {
            segments: 6,
            radius: 1.0,
            depth: 1.0
        }),
        (12, 18, 8)
    );
    assert_eq!(
        count(Primitive::Cone {
            segments: 6,
            radius: 1.0,
            depth: 1.0
        }),
        (7, 12, 7)
    );
    assert_eq!(
        count(Primitive::Torus {
            major_segments: 8,
            minor_segments: 4,
            major_radius: 1.0,
            minor_radius: 0.2
        }),
        (32, 64, 32)
    );
}

#[test]
fn primitives_are_quads_where_the_shape_allows() {
    let sphere = Primitive::UvSphere {
        segments: 8,
        rings: 4,
        radius: 1.0,
    }
    .build()
    .unwrap();
    let quads = sphere
        .faces()
        .filter(|&f| sphere.face_degree(f) == 4)
        .count();
    assert_eq!(quads, 8 * 2, "two quad bands between the pole fans");
    let cyl = Primitive::Cylinder {
        segments: 6,
        radius: 1.0,
        depth: 1.0,
    }
    .build()
    .unwrap();
    let degrees: Vec<usize> = cyl.faces().map(|f| cyl.face_degree(f)).collect();
    assert_eq!(
        degrees.iter().filter(|&&d| d == 6).count(),
        2,
        "two hexagon caps"
    );
    assert_eq!(degrees.iter().filter(|&&d| d == 4).count(), 6);
}

#[test]
fn cube_positions_and_sizes() {
    let m = Primitive::Cube { size: 2.0 }.build().unwrap();
    let (lo, hi) = m.bounds().unwrap();
    assert_eq!(lo, DVec3::splat(-1.0));
    assert_eq!(hi, DVec3::splat(1.0));
    assert!((m.volume() - 8.0).abs() < 1e-12);
    let ico = Primitive::IcoSphere {
        subdivisions: 2,
        radius: 3.0,
    }
    .build()
    .unwrap();
    for v in ico.vertices() {
        assert!((ico.position(v).length() - 3.0).abs() < 1e-12);
    }
}

#[test]
fn bad_primitive_parameters_are_refused_by_name() {
    let e = Primitive::UvSphere {
        segments: 2,
        rings: 4,
        radius: 1.0,
    }
    .build()
    .unwrap_err();
    assert_eq!(e.parameter, "segments");
    let e = Primitive::Cube { size: f64::NAN }.build().unwrap_err();
    assert_eq!(e.parameter, "size");
    let e = Primitive::Torus {
        major_segments: 8,
        minor_segments: 8,
        major_radius: 1.0,
        minor_radius: 2.0,
    }
    .build()
    .unwrap_err();
    assert_eq!(e.parameter, "minor_radius");
    let e = Primitive::IcoSphere {
        subdivisions: 40,
        radius: 1.0,
    }
    .build()
    .unwrap_err();
    assert!(e.to_string().contains("subdivisions = 40"), "{e}");
}

fn square_positions() -> Vec<DVec3> {
    vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.5, 0.5, 1.0),
        DVec3::new(0.5, 0.5, -1.0),
        DVec3::new(2.0, 0.0, 0.0),
    ]
}

#[test]
fn from_polygons_names_the_problem() {
    let p = square_positions();
    assert_eq!(
        HalfEdgeMesh::from_polygons(&p, &[vec![0, 1, 9]]).unwrap_err(),
        BuildError::IndexOutOfRange {
            face: 0,
            index: 9,
            vertex_count: 7
        }
    );
    assert_eq!(
        HalfEdgeMesh::from_polygons(&p, &[vec![0, 1, 2], vec![0, 2, 2, 3]]).unwrap_err(),
        BuildError::RepeatedVertex { face: 1, vertex: 2 }
    );
    assert_eq!(
        HalfEdgeMesh::from_polygons(&p, &[vec![0, 1]]).unwrap_err(),
        BuildError::TooFewSides { face: 0, sides: 2 }
    );
    // Edge 0-1 used by three triangles.
    let e = HalfEdgeMesh::from_polygons(&p, &[vec![0, 1, 2], vec![1, 0, 4], vec![1, 0, 5]])
        .unwrap_err();
    assert!(
        matches!(e, BuildError::NonManifoldEdge { a: 0, b: 1, .. }),
        "{e:?}"
    );
    assert!(e.to_string().contains("more than two faces"));
    // Two faces running 0->1 the same way.
    let e = HalfEdgeMesh::from_polygons(&p, &[vec![0, 1, 2], vec![0, 1, 4]]).unwrap_err();
    assert_eq!(
        e,
        BuildError::InconsistentOrientation {
            a: 0,
            b: 1,
            faces: vec![0, 1]
        }
    );
    // Bow-tie: two triangles touching at vertex 1 only.
    let e = HalfEdgeMesh::from_polygons(&p, &[vec![0, 1, 3], vec![1, 6, 2]]).unwrap_err();
    assert_eq!(e, BuildError::NonManifoldVertex { vertex: 1 });
    let mut bad = p.clone();
    bad[2].y = f64::INFINITY;
    assert_eq!(
        HalfEdgeMesh::from_polygons(&bad, &[vec![0, 1, 2]]).unwrap_err(),
        BuildError::NonFinitePosition { vertex: 2 }
    );
}

#[test]
fn two_closed_fans_meeting_at_a_vertex_are_non_manifold() {
    // Two tetrahedra sharing only vertex 0.
    let p: Vec<DVec3> = [
        (0.0, 0.0, 0.0),
        (1.0, 0.0, 0.0),
        (0.0, 1.0, 0.0),
        (0.0, 0.0, 1.0),
        (-1.0, 0.0, 0.0),
        (0.0, -1.0, 0.0),
        (0.0, 0.0, -1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z))
    .collect();
    let tet = |a: u32, b: u32, c: u32, d: u32| {
        vec![vec![a, c, b], vec![a, b, d], vec![a, d, c], vec![b, c, d]]
    };
    let mut faces = tet(0, 1, 2, 3);
    faces.extend(tet(0, 4, 5, 6));
    assert_eq!(
        HalfEdgeMesh::from_polygons(&p, &faces).unwrap_err(),
        BuildError::NonManifoldVertex { vertex: 0 }
    );
    let (m, report) = HalfEdgeMesh::from_polygons_repaired(&p, &faces).unwrap();
    m.validate().unwrap();
    assert_eq!(report.split_vertices, vec![(0, 1)]);
    assert_eq!(m.vertex_count(), 8);
    assert_eq!(m.shell_count(), 2);
}

#[test]
fn repair_drops_the_offending_faces_and_splits_bowties() {
    let p = square_positions();
    let faces = vec![
        vec![0, 1, 2],
        vec![1, 0, 4],
        vec![1, 0, 5],
        vec![0, 1, 9],
        vec![1, 6, 5],
    ];
    let (m, report) = HalfEdgeMesh::from_polygons_repaired(&p, &faces).unwrap();
    m.validate().unwrap();
    let dropped: Vec<usize> = report.dropped_faces.iter().map(|(f, _)| *f).collect();
    assert_eq!(dropped, vec![2, 3]);
    assert_eq!(report.face_origin, vec![0, 1, 4]);
    assert_eq!(m.face_count(), 3);
    assert_eq!(
        report.split_vertices,
        vec![(1, 1)],
        "face 4 touches the others only at vertex 1"
    );
    assert_eq!(m.vertex_count(), 8);
    assert!(report.to_string().contains("dropped 2 face(s)"), "{report}");
    let clean = HalfEdgeMesh::from_polygons_repaired(&p, &[vec![0, 1, 2]])
        .unwrap()
        .1;
    assert!(clean.is_clean());
}

#[test]
fn traversal_of_the_cube() {
    let m = Primitive::Cube { size: 2.0 }.build().unwrap();
    for v in m.vertices() {
        assert_eq!(m.vertex_valence(v), 3);
        assert_eq!(m.vertex_faces(v).count(), 3);
        for w in m.vertex_neighbors(v) {
            // Neighbours of a cube corner differ in exactly one coordinate.
            let d = m.position(v) - m.position(w);
            assert_eq!(
                (d.x != 0.0) as u8 + (d.y != 0.0) as u8 + (d.z != 0.0) as u8,
                1
            );
        }
    }
    for f in m.faces() {
        assert_eq!(m.face_degree(f), 4);
        let mut n: Vec<_> = m.face_neighbors(f).collect();
        n.sort();
        n.dedup();
        assert_eq!(n.len(), 4);
        assert!(!n.contains(&f));
    }
    let e = m.find_edge(VertexId(0), VertexId(1)).unwrap();
    assert_eq!(m.edge_length(e), 2.0);
    assert!(m.find_edge(VertexId(0), VertexId(7)).is_none());
}

#[test]
fn ron_round_trip_keeps_every_id() {
    let m = Primitive::UvSphere {
        segments: 6,
        rings: 4,
        radius: 1.0,
    }
    .build()
    .unwrap();
    let text = ron::to_string(&m).unwrap();
    let back: HalfEdgeMesh = ron::from_str(&text).unwrap();
    assert_eq!(back, m);
}

#[test]
fn corrupted_stored_mesh_is_refused_with_the_element_named() {
    let m = Primitive::Cube { size: 2.0 }.build().unwrap();
    let mut data = hedra_geom::MeshData::from(m.clone());
    data.halfedges[3].1 = 999;
    let e = HalfEdgeMesh::try_from(data).unwrap_err().to_string();
    assert!(e.contains("h3: next refers to missing element 999"), "{e}");
    let mut data = hedra_geom::MeshData::from(m.clone());
    data.halfedges[0].1 = data.halfedges[5].1;
    let e = HalfEdgeMesh::try_from(data).unwrap_err().to_string();
    assert!(e.starts_with("invalid mesh"), "{e}");
    let mut data = hedra_geom::MeshData::from(m);
    data.positions.pop();
    assert!(
        HalfEdgeMesh::try_from(data)
            .unwrap_err()
            .to_string()
            .contains("positions")
    );
}

mod random_input {
    use hedra_geom::{DVec3, HalfEdgeMesh};
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        /// Arbitrary polygon soups: the strict builder gives a valid mesh or
        /// an error; the repairing builder always gives a valid mesh.
        #[test]
        fn any_polygon_soup_builds_valid_or_is_refused(
            n in 1usize..12,
            polys in prop::collection::vec(prop::collection::vec(0u32..14, 0..6), 0..14),
        ) {
            let positions: Vec<DVec3> = (0..n).map(|i| DVec3::new(i as f64, (i * i % 7) as f64, (i % 3) as f64)).collect();
            if let Ok(m) = HalfEdgeMesh::from_polygons(&positions, &polys) {
                prop_assert!(m.validate().is_ok());
                prop_assert_eq!(m.face_count(), polys.len());
            }
            let (m, report) = HalfEdgeMesh::from_polygons_repaired(&positions, &polys).unwrap();
            prop_assert!(m.validate().is_ok(), "{:?}", m.validate());
            // A face split at a repeated vertex counts once per loop kept.
            let extra: usize = report.split_faces.iter().map(|(_, loops)| loops - 1).sum();
            prop_assert_eq!(m.face_count() + report.dropped_faces.len(), polys.len() + extra);
        }
    }
}

/// A polygon pinched at a vertex (a keyhole outline that visits one
/// vertex twice, as other programs write) becomes its two simple loops
/// instead of being dropped; one that runs around its outline again and
/// again is still dropped.
#[test]
fn a_pinched_polygon_is_split_into_simple_faces() {
    use hedra_geom::{DVec3, HalfEdgeMesh};
    // Two triangles meeting at vertex 0, written as one face 0 1 2 0 3 4.
    let positions = vec![
        DVec3::ZERO,
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(-1.0, 0.0, 0.0),
        DVec3::new(-1.0, -1.0, 0.0),
    ];
    let (m, report) =
        HalfEdgeMesh::from_polygons_repaired(&positions, &[vec![0u32, 1, 2, 0, 3, 4]]).unwrap();
    m.validate().unwrap();
    assert_eq!(m.face_count(), 2);
    assert_eq!(report.split_faces, [(0, 2)]);
    assert!(report.dropped_faces.is_empty());
    assert_eq!(report.face_origin, [0, 0], "both loops come from face 0");
    let (m, report) =
        HalfEdgeMesh::from_polygons_repaired(&positions, &[vec![0u32, 1, 2, 0, 1, 2, 0, 1, 2]])
            .unwrap();
    assert_eq!(m.face_count(), 0);
    assert_eq!(report.dropped_faces.len(), 1);
    assert!(report.split_faces.is_empty());
}

/// The error names the bad edge whose first corner comes first, even when
/// a later edge's fault is the first one seen: edge 0-1 (faces 0, 1 and 5)
/// only shows its third face at face 5, edge 5-6 (faces 2, 3 and 4) at
/// face 2 already; and a mesh without faults builds with the same ids as
/// before the fault was added.
#[test]
fn from_polygons_reports_the_first_bad_edge_in_corner_order() {
    let p: Vec<DVec3> = (0..10)
        .map(|i| DVec3::new(i as f64, (i * i) as f64, 0.0))
        .collect();
    let good = [vec![0, 1, 2], vec![1, 0, 3], vec![5, 6, 7], vec![6, 5, 8]];
    let m = HalfEdgeMesh::from_polygons(&p, &good).unwrap();
    m.validate().unwrap();
    assert_eq!(m.edge_count(), 10);
    let mut bad = good.to_vec();
    bad.push(vec![6, 5, 9]);
    bad.push(vec![0, 1, 4]);
    assert_eq!(
        HalfEdgeMesh::from_polygons(&p, &bad).unwrap_err(),
        BuildError::NonManifoldEdge {
            a: 0,
            b: 1,
            faces: vec![0, 1, 5]
        }
    );
    // Without the third face on 0-1, edge 5-6 is named.
    bad.pop();
    assert_eq!(
        HalfEdgeMesh::from_polygons(&p, &bad).unwrap_err(),
        BuildError::NonManifoldEdge {
            a: 5,
            b: 6,
            faces: vec![2, 3, 4]
        }
    );
}

/// A keyhole polygon (issue 31, item 16): an outline that walks round a
/// square, across to an inner square, round that backwards and back, as
/// exporters write a face with a hole. It must become faces that all face
/// the outline's way and cover the ring (outer minus hole) once: before,
/// the inner square became a face of its own over the outer square, facing
/// the other way (area 16 + 4 instead of 12, normals cancelling).
#[test]
fn a_keyhole_polygon_keeps_its_outline_orientation_and_area() {
    use glam::DMat3;
    use hedra_geom::{DVec3, HalfEdgeMesh};
    let square = |r: f64| [(-r, -r), (r, -r), (r, r), (-r, r)].map(|(x, y)| DVec3::new(x, y, 0.0));
    // In the z = 0 plane and turned into a tilted plane: the same result.
    for turn in [
        DMat3::IDENTITY,
        DMat3::from_euler(glam::EulerRot::XYZ, 0.7, -0.4, 1.9),
    ] {
        let positions: Vec<DVec3> = square(2.0)
            .into_iter()
            .chain(square(1.0))
            .map(|p| turn * p + DVec3::new(3.0, -1.0, 0.5))
            .collect();
        let normal = turn * DVec3::Z;
        // Bridged at a corner pair (0-4): the ring, 16 - 4. Pinched at a
        // shared vertex (the hole's corner 4 replaced by the outline's 0,
        // making the hole (-2,-2) (1,-1) (1,1) (-1,1) of area 6): 16 - 6.
        for poly in [
            vec![0u32, 1, 2, 3, 0, 4, 7, 6, 5, 4],
            vec![1u32, 2, 3, 0, 7, 6, 5, 0],
        ] {
            let (m, report) = HalfEdgeMesh::from_polygons_repaired(&positions, &[&poly]).unwrap();
            m.validate().unwrap();
            assert!(report.dropped_faces.is_empty(), "{poly:?}: {report}");
            assert_eq!(report.split_faces, [(0, m.face_count())], "{poly:?}");
            let want = if poly.len() == 10 { 12.0 } else { 10.0 };
            let mut total = DVec3::ZERO;
            for f in m.faces() {
                let a = m.face_area_vector(f);
                assert!(
                    a.normalize().dot(normal) > 1.0 - 1e-9,
                    "{poly:?}: a face facing {a} against the outline's {normal}"
                );
                total += a;
            }
            assert!(
                (total.length() - want).abs() < 1e-9,
                "{poly:?}: area {} instead of {want}",
                total.length()
            );
        }
    }
}
