//! Modeling operations: counts, positions and validity after each.

use hedra_geom::modeling::{
    connect_vertices, dissolve_edges, dissolve_vertices, edge_ring, extrude_faces_individual,
    flip_normals, inset_faces_individual, loop_cut, subdivide_edges,
};
use hedra_geom::{DVec3, EdgeId, FaceId, HalfEdgeMesh, ModelingError, Primitive, VertexId};

fn cube() -> HalfEdgeMesh {
    Primitive::Cube { size: 2.0 }.build().unwrap()
}

fn counts(m: &HalfEdgeMesh) -> (usize, usize, usize) {
    (m.vertex_count(), m.edge_count(), m.face_count())
}

fn top(m: &HalfEdgeMesh) -> FaceId {
    m.faces().find(|&f| m.face_normal(f).y > 0.9).unwrap()
}

#[test]
fn loop_cut_on_a_cube_adds_a_ring_of_edges_halfway() {
    let mut m = cube();
    // A vertical edge: its ring goes around the four side faces.
    let e = m
        .edges()
        .find(|&e| {
            let [a, b] = m.edge_vertices(e);
            (m.position(a) - m.position(b)).y.abs() > 1.0
        })
        .unwrap();
    let (ring, closed) = edge_ring(&m, e);
    assert_eq!((ring.len(), closed), (4, true));
    let new = loop_cut(&mut m, e, 1).unwrap();
    m.validate().unwrap();
    assert_eq!(new.len(), 4);
    assert_eq!(counts(&m), (12, 20, 10));
    for e in new {
        let [a, b] = m.edge_vertices(e);
        assert!(
            m.position(a).y.abs() < 1e-12 && m.position(b).y.abs() < 1e-12,
            "the cut lies at half height"
        );
    }
    // Three cuts: evenly spaced at y = -0.5, 0, 0.5 on the remaining ring.
    let mut m = cube();
    loop_cut(&mut m, e, 3).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (8 + 12, 12 + 24, 6 + 12));
    let mut ys: Vec<i64> = m
        .vertices()
        .map(|v| (m.position(v).y * 1000.0).round() as i64)
        .collect();
    ys.sort();
    ys.dedup();
    assert_eq!(ys, vec![-1000, -500, 0, 500, 1000]);
}

#[test]
fn loop_cut_on_an_open_grid_cuts_the_whole_strip() {
    let mut m = Primitive::Grid {
        x_segments: 3,
        z_segments: 2,
        size: 3.0,
    }
    .build()
    .unwrap();
    let e = m.edges().find(|&e| !m.is_boundary_edge(e)).unwrap();
    let before = counts(&m);
    loop_cut(&mut m, e, 1).unwrap();
    m.validate().unwrap();
    let after = counts(&m);
    assert!(
        after.2 > before.2 && after.2 - before.2 <= 3,
        "{before:?} -> {after:?}"
    );
    assert_eq!(m.stats().euler_characteristic, 1);
}

#[test]
fn loop_cut_refuses_triangles_and_bad_counts() {
    let mut ico = Primitive::IcoSphere {
        subdivisions: 0,
        radius: 1.0,
    }
    .build()
    .unwrap();
    let before = ico.clone();
    assert_eq!(
        loop_cut(&mut ico, EdgeId(0), 1),
        Err(ModelingError::NoRing { edge: EdgeId(0) })
    );
    assert_eq!(ico, before);
    let mut m = cube();
    assert!(matches!(
        loop_cut(&mut m, EdgeId(0), 0),
        Err(ModelingError::Parameter { .. })
    ));
    assert!(matches!(
        loop_cut(&mut m, EdgeId(77), 1),
        Err(ModelingError::Missing(_))
    ));
}

#[test]
fn extrude_and_inset_individual_faces() {
    let mut m = cube();
    let f = top(&m);
    let sides = extrude_faces_individual(&mut m, &[f], 0.5).unwrap();
    m.validate().unwrap();
    assert_eq!(sides.len(), 4);
    assert!(
        m.face_vertices(f)
            .all(|v| (m.position(v).y - 1.5).abs() < 1e-12)
    );

    let mut m = cube();
    let f = top(&m);
    inset_faces_individual(&mut m, &[f], 0.25, 0.0).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (12, 20, 10));
    let mut xs: Vec<f64> = m.face_vertices(f).map(|v| m.position(v).x.abs()).collect();
    xs.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    assert!(
        xs.iter().all(|x| (x - 0.75).abs() < 1e-12),
        "inner square at 0.75: {xs:?}"
    );
    assert!(
        m.face_vertices(f)
            .all(|v| (m.position(v).y - 1.0).abs() < 1e-12)
    );
    assert!(
        (m.volume() - 8.0).abs() < 1e-9,
        "an inset without depth keeps the volume"
    );

    let mut m = cube();
    let t = top(&m);
    assert!(inset_faces_individual(&mut m, &[t], -1.0, 0.0).is_err());
    assert!(matches!(
        extrude_faces_individual(&mut m, &[], 1.0),
        Err(ModelingError::Empty(_))
    ));
}

#[test]
fn subdivide_connect_and_dissolve() {
    let mut m = cube();
    let f = top(&m);
    let edges: Vec<EdgeId> = m.face_halfedges(f).map(|h| h.edge()).collect();
    let new = subdivide_edges(&mut m, &edges[..2], 1).unwrap();
    m.validate().unwrap();
    assert_eq!(new.len(), 2);
    assert_eq!(m.face_degree(f), 6);
    let e = connect_vertices(&mut m, new[0], new[1]).unwrap();
    m.validate().unwrap();
    assert_eq!(m.face_count(), 7);
    assert_eq!(
        connect_vertices(&mut m, new[0], new[1]),
        Err(ModelingError::NotConnectable {
            a: new[0],
            b: new[1]
        })
    );
    dissolve_edges(&mut m, &[e]).unwrap();
    m.validate().unwrap();
    assert_eq!(m.face_count(), 6);
    dissolve_vertices(&mut m, &new).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (8, 12, 6));
    let before = m.clone();
    assert!(dissolve_vertices(&mut m, &[VertexId(0)]).is_err());
    assert_eq!(m, before, "a refused dissolve changes nothing");
}

#[test]
fn flip_normals_twice_is_the_identity() {
    let mut m = Primitive::UvSphere {
        segments: 8,
        rings: 5,
        radius: 1.0,
    }
    .build()
    .unwrap();
    let m0 = m.clone();
    let v0 = m.volume();
    flip_normals(&mut m);
    m.validate().unwrap();
    assert!((m.volume() + v0).abs() < 1e-9, "inside out");
    flip_normals(&mut m);
    assert!(m.same_as(&m0));
    let mut grid = Primitive::Grid {
        x_segments: 2,
        z_segments: 2,
        size: 1.0,
    }
    .build()
    .unwrap();
    flip_normals(&mut grid);
    grid.validate().unwrap();
    assert!(
        grid.faces()
            .all(|f| grid.face_normal(f).abs_diff_eq(-DVec3::Y, 1e-12))
    );
}

#[test]
fn make_hole_then_fill_restores_and_counts_change_by_one_face() {
    use hedra_geom::modeling::{fill_holes, make_holes, recalculate_normals_outward};
    let m0 = cube();
    let mut m = m0.clone();
    let f = top(&m);
    let h = m.make_hole(f).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (8, 12, 5));
    assert_eq!(m.boundary_loops().len(), 1);
    let g = m.fill_hole(h).unwrap();
    m.validate().unwrap();
    assert_ne!(g, f, "ids are never reused: the filled face is new");
    assert_eq!(counts(&m), counts(&m0));
    assert!(
        m.face_normal(g).abs_diff_eq(DVec3::Y, 1e-12),
        "the fill faces the same way as the old face"
    );
    assert!(m.stats().closed);
    // A face next to the new hole is refused; the mesh is unchanged.
    let mut m = cube();
    let t = top(&m);
    let side = m.face_neighbors(t).next().unwrap();
    let before = m.clone();
    assert!(make_holes(&mut m, &[t, side]).is_err());
    assert_eq!(m, before);
    make_holes(&mut m, &[t]).unwrap();
    let e = m
        .face_halfedges(side)
        .map(|h| h.edge())
        .find(|&e| m.is_boundary_edge(e))
        .unwrap();
    let filled = fill_holes(&mut m, &[e]).unwrap();
    assert_eq!(filled.len(), 1);
    m.validate().unwrap();
    assert!(m.stats().closed);
    // Recalculate outward: an inside-out cube is turned back.
    flip_normals(&mut m);
    assert!(recalculate_normals_outward(&mut m));
    assert!(m.volume() > 0.0);
    assert!(!recalculate_normals_outward(&mut m));
}

#[test]
fn collapse_edges_merges_each_edge_into_its_midpoint() {
    use hedra_geom::modeling::collapse_edges;
    let mut g = Primitive::Grid {
        x_segments: 3,
        z_segments: 3,
        size: 3.0,
    }
    .build()
    .unwrap();
    let e = g
        .edges()
        .find(|&e| g.edge_vertices(e).iter().all(|&v| !g.is_boundary_vertex(v)))
        .unwrap();
    let mid = g.edge_midpoint(e);
    let kept = collapse_edges(&mut g, &[e]).unwrap();
    g.validate().unwrap();
    assert_eq!(g.vertex_count(), 15);
    assert_eq!(g.position(kept[0]), mid);
    // Triangles beside the edge vanish with it: an icosahedron loses 1 V, 3 E, 2 F.
    let mut ico = Primitive::IcoSphere {
        subdivisions: 0,
        radius: 1.0,
    }
    .build()
    .unwrap();
    collapse_edges(&mut ico, &[EdgeId(0)]).unwrap();
    ico.validate().unwrap();
    assert_eq!(counts(&ico), (11, 27, 18));
    // A tetrahedron cannot lose an edge (it would fold flat): refused, unchanged.
    let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    let mut tet = HalfEdgeMesh::from_polygons(
        &p,
        &[vec![0, 2, 1], vec![0, 1, 3], vec![0, 3, 2], vec![1, 2, 3]],
    )
    .unwrap();
    let before = tet.clone();
    assert!(collapse_edges(&mut tet, &[EdgeId(0)]).is_err());
    assert_eq!(tet, before);
}

#[test]
fn region_extrude_keeps_the_region_joined() {
    use hedra_geom::modeling::extrude_region;
    // The 3x3 top of a loop-cut cube: extrude the middle row of three faces as one.
    let mut g = Primitive::Grid {
        x_segments: 3,
        z_segments: 3,
        size: 3.0,
    }
    .build()
    .unwrap();
    let row: Vec<FaceId> = g
        .faces()
        .filter(|&f| g.face_centroid(f).z.abs() < 0.1)
        .collect();
    assert_eq!(row.len(), 3);
    let caps = extrude_region(&mut g, &row, DVec3::new(0.0, 1.0, 0.0)).unwrap();
    g.validate().unwrap();
    assert_eq!(caps.len(), 3);
    // 8 boundary vertices of the row get copies; the row's 4 inner edges stay inside.
    assert_eq!(g.vertex_count(), 16 + 8);
    assert_eq!(g.face_count(), 9 + 8, "8 side quads around the row");
    for &c in &caps {
        assert!(
            g.face_vertices(c)
                .all(|v| (g.position(v).y - 1.0).abs() < 1e-12)
        );
        assert!(g.face_normal(c).abs_diff_eq(DVec3::Y, 1e-12));
    }
    // The caps are joined: the middle cap shares edges with both neighbours.
    let shared = g
        .face_neighbors(caps[1])
        .filter(|n| caps.contains(n))
        .count();
    assert_eq!(shared, 2);
    // A 2x2 block has an inner vertex: it keeps its id and moves with the caps.
    let mut g = Primitive::Grid {
        x_segments: 3,
        z_segments: 3,
        size: 3.0,
    }
    .build()
    .unwrap();
    let block: Vec<FaceId> = g
        .faces()
        .filter(|&f| g.face_centroid(f).x < 0.1 && g.face_centroid(f).z < 0.1)
        .collect();
    assert_eq!(block.len(), 4);
    let inner = g
        .vertices()
        .find(|&v| block.iter().all(|&f| g.face_vertices(f).any(|x| x == v)))
        .unwrap();
    extrude_region(&mut g, &block, DVec3::new(0.0, 0.5, 0.0)).unwrap();
    g.validate().unwrap();
    assert!(
        (g.position(inner).y - 0.5).abs() < 1e-12,
        "the inner vertex moved with the region"
    );
    assert_eq!(
        g.vertex_count(),
        16 + 8,
        "the 8 boundary vertices of the block were copied"
    );
    // On a closed cube the whole top extrudes to a 2x2x3 box.
    let mut c = cube();
    let t = top(&c);
    extrude_region(&mut c, &[t], DVec3::Y).unwrap();
    c.validate().unwrap();
    assert!((c.volume() - 12.0).abs() < 1e-9);
    assert_eq!(counts(&c), (12, 20, 10));
}

#[test]
fn region_extrude_of_a_closed_mesh_stays_closed() {
    use hedra_geom::modeling::{extrude_region, loop_cut};
    let mut c = cube();
    let e = c
        .edges()
        .find(|&e| {
            let [a, b] = c.edge_vertices(e);
            (c.position(a) - c.position(b)).y.abs() > 1.0
        })
        .unwrap();
    loop_cut(&mut c, e, 2).unwrap();
    let side: Vec<FaceId> = c.faces().filter(|&f| c.face_normal(f).x > 0.9).collect();
    assert_eq!(side.len(), 3);
    extrude_region(&mut c, &side, DVec3::new(0.25, 0.0, 0.0)).unwrap();
    c.validate().unwrap();
    let s = c.stats();
    assert!(s.closed, "{s:?}");
    assert_eq!(s.euler_characteristic, 2);
}

#[test]
fn region_inset_keeps_a_border_of_the_given_width() {
    use hedra_geom::modeling::inset_region;
    // A 4x4 grid's central 2x2 block, inset by 0.1.
    let mut g = Primitive::Grid {
        x_segments: 4,
        z_segments: 4,
        size: 4.0,
    }
    .build()
    .unwrap();
    let block: Vec<FaceId> = g
        .faces()
        .filter(|&f| g.face_centroid(f).x.abs() < 1.0 && g.face_centroid(f).z.abs() < 1.0)
        .collect();
    assert_eq!(block.len(), 4);
    let caps = inset_region(&mut g, &block, 0.1, 0.0).unwrap();
    g.validate().unwrap();
    // The caps' outline is the square max(|x|, |z|) = 0.9; the centre vertex stays.
    for &c in &caps {
        for v in g.face_vertices(c) {
            let p = g.position(v);
            let d = p.x.abs().max(p.z.abs());
            assert!(
                d < 1e-12
                    || (d - 0.9).abs() < 1e-9
                    || ((p.x.abs() < 1e-12 || p.z.abs() < 1e-12) && (d - 0.9).abs() < 1e-9),
                "{p:?}"
            );
        }
    }
    assert_eq!(g.face_count(), 16 + 8, "8 border quads around the block");
    let area: f64 = g.faces().map(|f| g.face_area_vector(f).length()).sum();
    assert!(
        (area - 16.0).abs() < 1e-9,
        "an inset without depth keeps the area: {area}"
    );
}

#[test]
fn bridging_two_facing_squares_makes_a_closed_box() {
    use hedra_geom::modeling::bridge_loops;
    let p: Vec<DVec3> = [
        (-1.0, -1.0, -1.0),
        (1.0, -1.0, -1.0),
        (1.0, -1.0, 1.0),
        (-1.0, -1.0, 1.0),
        (-1.0, 1.0, -1.0),
        (1.0, 1.0, -1.0),
        (1.0, 1.0, 1.0),
        (-1.0, 1.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z))
    .collect();
    // Bottom faces down, top faces up: two shells with one hole each.
    let mut m = HalfEdgeMesh::from_polygons(&p, &[vec![0, 1, 2, 3], vec![4, 7, 6, 5]]).unwrap();
    assert_eq!(m.shell_count(), 2);
    let one_each: Vec<EdgeId> = m.boundary_loops().iter().map(|l| l[0].edge()).collect();
    let quads = bridge_loops(&mut m, &one_each).unwrap();
    m.validate().unwrap();
    assert_eq!(quads.len(), 4);
    let s = m.stats();
    assert!(s.closed);
    assert_eq!((s.vertices, s.edges, s.faces, s.shells), (8, 12, 6, 1));
    assert!(
        (m.volume() - 8.0).abs() < 1e-9,
        "the sides face outwards: {}",
        m.volume()
    );
    for &q in &quads {
        assert!(
            (m.face_area_vector(q).length() - 4.0).abs() < 1e-9,
            "vertical sides, not twisted"
        );
    }
    // Bridging needs two loops of equal length.
    let mut g = Primitive::Grid {
        x_segments: 2,
        z_segments: 2,
        size: 1.0,
    }
    .build()
    .unwrap();
    let e = g.edges().find(|&e| g.is_boundary_edge(e)).unwrap();
    assert!(matches!(
        bridge_loops(&mut g, &[e]),
        Err(ModelingError::Parameter { .. })
    ));
}

#[test]
fn merge_at_center_joins_a_patch_into_one_vertex() {
    use hedra_geom::modeling::merge_at_center;
    let mut g = Primitive::Grid {
        x_segments: 3,
        z_segments: 3,
        size: 3.0,
    }
    .build()
    .unwrap();
    let inner: Vec<VertexId> = g.vertices().filter(|&v| !g.is_boundary_vertex(v)).collect();
    assert_eq!(inner.len(), 4);
    let v = merge_at_center(&mut g, &inner).unwrap();
    g.validate().unwrap();
    assert!(g.position(v).length() < 1e-12, "at the centre");
    assert_eq!(g.vertex_count(), 13);
    assert_eq!(
        g.face_count(),
        8,
        "the middle quad is gone; its four neighbours became triangles"
    );
    assert_eq!(g.vertex_valence(v), 8);
    // Vertices that no edge joins are refused; nothing changes.
    let mut c = cube();
    let before = c.clone();
    assert!(matches!(
        merge_at_center(&mut c, &[VertexId(0), VertexId(7)]),
        Err(ModelingError::NotConnectable { .. })
    ));
    assert_eq!(c, before);
}

#[test]
fn extruding_the_border_of_a_plane_grows_a_wall() {
    use hedra_geom::modeling::extrude_boundary_edges;
    let mut p = Primitive::Plane { size: 2.0 }.build().unwrap();
    let border: Vec<EdgeId> = p.edges().collect();
    let walls = extrude_boundary_edges(&mut p, &border, DVec3::new(0.0, 1.0, 0.0)).unwrap();
    p.validate().unwrap();
    assert_eq!(walls.len(), 4);
    assert_eq!(
        counts(&p),
        (8, 12, 5),
        "an open box: the plane and four walls"
    );
    assert_eq!(p.boundary_loops().len(), 1);
    // The walls sit on the plane's open side: an open box whose inside faces up.
    for &w in &walls {
        assert!(p.face_normal(w).y.abs() < 1e-12);
    }
    // Interior edges are refused.
    let mut g = Primitive::Grid {
        x_segments: 2,
        z_segments: 2,
        size: 1.0,
    }
    .build()
    .unwrap();
    let inner = g.edges().find(|&e| !g.is_boundary_edge(e)).unwrap();
    assert_eq!(
        extrude_boundary_edges(&mut g, &[inner], DVec3::Y),
        Err(ModelingError::NotBoundary { edge: inner })
    );
}

#[test]
fn dissolving_a_block_of_faces_leaves_one_face() {
    use hedra_geom::modeling::dissolve_faces;
    let mut g = Primitive::Grid {
        x_segments: 3,
        z_segments: 3,
        size: 3.0,
    }
    .build()
    .unwrap();
    let all: Vec<FaceId> = g.faces().collect();
    let left = dissolve_faces(&mut g, &all).unwrap();
    g.validate().unwrap();
    assert_eq!(left.len(), 1, "one face");
    assert_eq!(g.face_count(), 1);
    assert_eq!(g.face_degree(left[0]), 12, "the outline of the grid");
    assert_eq!(
        g.vertex_count(),
        12,
        "the four inner vertices went with their edges"
    );
}

#[test]
fn dissolving_every_face_of_a_closed_shell_is_refused_and_changes_nothing() {
    use hedra_geom::modeling::dissolve_faces;
    let mut c = cube();
    let before = c.clone();
    let all: Vec<FaceId> = c.faces().collect();
    let err = dissolve_faces(&mut c, &all).unwrap_err();
    assert!(matches!(err, ModelingError::ClosedShell { .. }), "{err}");
    assert!(err.to_string().contains("whole shell"), "{err}");
    assert!(c.same_as(&before));
    // Five of six faces have an outline (the sixth face's), so they dissolve.
    let five: Vec<FaceId> = all[..5].to_vec();
    let left = dissolve_faces(&mut c, &five).unwrap();
    c.validate().unwrap();
    assert!(left.len() < 5, "{} faces left", left.len());
    assert_eq!(c.face_count(), left.len() + 1);
}

#[test]
fn deleting_faces_edges_and_vertices_cleans_up_loose_geometry() {
    use hedra_geom::modeling::{delete_faces, faces_around_vertices};
    let mut c = cube();
    let t = top(&c);
    delete_faces(&mut c, &[t]).unwrap();
    c.validate().unwrap();
    assert_eq!(counts(&c), (8, 12, 5));
    // Deleting a vertex takes the three faces around it, its three edges and itself.
    let mut c = cube();
    let fs = faces_around_vertices(&c, &[VertexId(0)]);
    delete_faces(&mut c, &fs).unwrap();
    c.validate().unwrap();
    assert_eq!(counts(&c), (7, 9, 3));
    assert!(!c.is_vertex(VertexId(0)));
}

#[test]
fn symmetrize_mirrors_the_positive_half() {
    use hedra_geom::modeling::{MirrorAxis, loop_cut, symmetrize};
    // A cube cut at x = 0, with the +X half pulled out: symmetrize copies it to −X.
    let mut c = cube();
    let e = c
        .edges()
        .find(|&e| {
            let [a, b] = c.edge_vertices(e);
            (c.position(a) - c.position(b)).x.abs() > 1.0
        })
        .unwrap();
    loop_cut(&mut c, e, 1).unwrap();
    for v in c.vertices().collect::<Vec<_>>() {
        if c.position(v).x > 0.5 {
            c.set_position(v, c.position(v) + DVec3::new(1.0, 0.0, 0.0));
        }
    }
    symmetrize(&mut c, MirrorAxis::X).unwrap();
    c.validate().unwrap();
    assert!(c.stats().closed);
    let (lo, hi) = c.bounds().unwrap();
    assert!(
        (lo.x + 2.0).abs() < 1e-12 && (hi.x - 2.0).abs() < 1e-12,
        "{lo:?} {hi:?}"
    );
    assert!(
        (c.volume() - 16.0).abs() < 1e-9,
        "two halves of 2x2x2: {}",
        c.volume()
    );
    assert_eq!(counts(&c), (12, 20, 10));
    // A plain cube is crossed by the plane: refused, unchanged.
    let mut c = cube();
    let before = c.clone();
    assert!(matches!(
        symmetrize(&mut c, MirrorAxis::X),
        Err(ModelingError::Parameter { .. })
    ));
    assert_eq!(c, before);
}

#[test]
fn mirroring_a_whole_part_keeps_it_facing_outwards() {
    use hedra_geom::modeling::{MirrorAxis, mirror_vertices};
    let mut c = Primitive::Cone {
        segments: 6,
        radius: 1.0,
        depth: 2.0,
    }
    .build()
    .unwrap();
    let all: Vec<VertexId> = c.vertices().collect();
    let v0 = c.volume();
    mirror_vertices(&mut c, &all, MirrorAxis::Y).unwrap();
    c.validate().unwrap();
    assert!(
        (c.volume() - v0).abs() < 1e-9,
        "still outward: {} vs {v0}",
        c.volume()
    );
    let apex = c.vertices().find(|&v| c.vertex_valence(v) == 6).unwrap();
    assert!(c.position(apex).y < 0.0, "the apex now points down");
}

#[test]
fn sliding_a_loop_cut_moves_it_along_its_rails() {
    use hedra_geom::modeling::{loop_cut, slide_edges};
    let mut c = cube();
    let e = c
        .edges()
        .find(|&e| {
            let [a, b] = c.edge_vertices(e);
            (c.position(a) - c.position(b)).y.abs() > 1.0
        })
        .unwrap();
    let ring = loop_cut(&mut c, e, 1).unwrap();
    // The loop lies at y = 0; sliding by ±0.5 moves it to y = ±0.5 (halfway to either end).
    let mut up = c.clone();
    slide_edges(&mut up, &ring, 0.5).unwrap();
    up.validate().unwrap();
    let ys: Vec<f64> = ring
        .iter()
        .flat_map(|&e| up.edge_vertices(e))
        .map(|v| up.position(v).y)
        .collect();
    assert!(ys.iter().all(|&y| (y.abs() - 0.5).abs() < 1e-12), "{ys:?}");
    let first = ys[0];
    assert!(
        ys.iter().all(|&y| (y - first).abs() < 1e-12),
        "all on one side: {ys:?}"
    );
    let mut down = c.clone();
    slide_edges(&mut down, &ring, -0.5).unwrap();
    let y_down = down.position(down.edge_vertices(ring[0])[0]).y;
    assert!(
        (y_down + first).abs() < 1e-12,
        "the other side: {y_down} vs {first}"
    );
    assert!(slide_edges(&mut c, &ring, 1.5).is_err());
}

#[test]
fn sliding_an_open_chain_keeps_one_side() {
    use hedra_geom::modeling::{loop_cut, slide_edges};
    let mut g = Primitive::Grid {
        x_segments: 2,
        z_segments: 3,
        size: 2.0,
    }
    .build()
    .unwrap();
    let e = g
        .edges()
        .find(|&e| {
            let [a, b] = g.edge_vertices(e);
            (g.position(a) - g.position(b)).z.abs() > 1e-9 && !g.is_boundary_edge(e)
        })
        .unwrap();
    let cut = loop_cut(&mut g, e, 1).unwrap();
    let zs = |m: &HalfEdgeMesh| -> Vec<f64> {
        cut.iter()
            .flat_map(|&e| m.edge_vertices(e))
            .map(|v| m.position(v).z)
            .collect()
    };
    let before = zs(&g);
    slide_edges(&mut g, &cut, 0.5).unwrap();
    g.validate().unwrap();
    let after = zs(&g);
    let moved: Vec<f64> = before.iter().zip(&after).map(|(a, b)| b - a).collect();
    assert!(
        moved.iter().all(|d| d.abs() > 1e-9),
        "every vertex of the chain moved, the ends too: {moved:?}"
    );
    assert!(
        moved.iter().all(|d| d.signum() == moved[0].signum()),
        "to the same side: {moved:?}"
    );
}

#[test]
fn beveling_a_cube_edge_makes_a_chamfer() {
    use hedra_geom::modeling::bevel_edges;
    let mut c = cube();
    let e = hedra_geom::EdgeId(0);
    let [a, b] = c.edge_vertices(e);
    let (pa, pb) = (c.position(a), c.position(b));
    let faces = bevel_edges(&mut c, &[e], 0.25, 1).unwrap();
    c.validate().unwrap();
    assert_eq!(
        counts(&c),
        (10, 15, 7),
        "one edge becomes a face: +2 V, +3 E, +1 F"
    );
    assert!(c.stats().closed);
    let f = faces[0];
    assert_eq!(c.face_degree(f), 4);
    // The chamfer's corners are 0.25 from the old corners along the faces' edges.
    for v in c.face_vertices(f) {
        let p = c.position(v);
        let d = p.distance(pa).min(p.distance(pb));
        assert!((d - 0.25).abs() < 1e-12, "{p:?}");
    }
    // The cut-off prism's volume: 2 * (0.25 * 0.25 / 2) * edge length 2.
    assert!((c.volume() - (8.0 - 0.0625)).abs() < 1e-9, "{}", c.volume());
    // Too wide, shared ends, border edges: refused, unchanged.
    let mut c = cube();
    let before = c.clone();
    assert!(bevel_edges(&mut c, &[EdgeId(0)], 2.5, 1).is_err());
    let shared = c
        .edges()
        .find(|&x| {
            x != EdgeId(0)
                && c.edge_vertices(x)
                    .iter()
                    .any(|v| c.edge_vertices(EdgeId(0)).contains(v))
        })
        .unwrap();
    assert_eq!(c, before);
    // Edges that meet can be beveled together, flat or rounded.
    for segments in [1, 2] {
        let mut m = cube();
        bevel_edges(&mut m, &[EdgeId(0), shared], 0.1, segments).unwrap();
        m.validate().unwrap();
        assert!(m.stats().closed);
    }
}

#[test]
fn rounding_every_edge_of_a_cube_keeps_it_closed_with_arc_patches() {
    use hedra_geom::modeling::bevel_edges;
    let mut c = cube();
    let all: Vec<EdgeId> = c.edges().collect();
    let faces = bevel_edges(&mut c, &all, 0.3, 3).unwrap();
    c.validate().unwrap();
    // Per corner 3 corner points, 3 arcs of 2 inner points and a centre;
    // faces: the 6 squares, 3 strips per edge, 9 triangles per corner.
    assert_eq!(counts(&c), (80, 192, 114));
    assert_eq!(faces.len(), 36 + 72);
    assert_eq!(faces.iter().filter(|&&f| c.face_degree(f) == 3).count(), 72);
    // Each corner's centre lies half-way from its corner points' centroid
    // to the old corner: at (1, 1, 1) the corner points are (1, 0.7, 0.7)
    // and its turns, centroid (0.8, 0.8, 0.8), so the centre is 0.9.
    assert!(
        c.vertices()
            .any(|v| (c.position(v) - glam::DVec3::splat(0.9)).length() < 1e-12)
    );
    assert!(c.stats().closed);
    // Rounded removes less than flat.
    let mut flat = cube();
    bevel_edges(&mut flat, &all, 0.3, 1).unwrap();
    assert!(c.volume() > flat.volume() && c.volume() < 8.0);
}

#[test]
fn chamfering_every_edge_of_a_cube_gives_the_classic_chamfered_cube() {
    use hedra_geom::modeling::bevel_edges;
    let mut c = cube();
    let all: Vec<EdgeId> = c.edges().collect();
    let faces = bevel_edges(&mut c, &all, 0.25, 1).unwrap();
    c.validate().unwrap();
    assert_eq!(
        counts(&c),
        (24, 48, 26),
        "6 octagons... no: 6 squares, 12 hexagon strips, 8 triangles"
    );
    assert_eq!(
        faces.len(),
        12 + 8,
        "a quad per edge, a triangle per corner"
    );
    assert_eq!(faces.iter().filter(|&&f| c.face_degree(f) == 3).count(), 8);
    assert!(c.stats().closed);
    // Every new point sits on a cube face, 0.25 in from both edges of its corner.
    for v in c.vertices() {
        let p = c.position(v).abs();
        let mut coords = [p.x, p.y, p.z];
        coords.sort_by(f64::total_cmp);
        assert!(
            (coords[2] - 1.0).abs() < 1e-12
                && (coords[0] - 0.75).abs() < 1e-12
                && (coords[1] - 0.75).abs() < 1e-12,
            "{p:?}"
        );
    }
    assert!(c.volume() > 0.0 && c.volume() < 8.0);
}

#[test]
fn chamfering_at_valence_four_vertices_patches_the_ends() {
    use hedra_geom::modeling::bevel_edges;
    let sphere = hedra_geom::Primitive::UvSphere {
        segments: 8,
        rings: 6,
        radius: 1.0,
    }
    .build()
    .unwrap();
    // A meridian edge between two valence-4 vertices off the poles.
    let e = sphere
        .edges()
        .find(|&e| {
            let [a, b] = sphere.edge_vertices(e);
            sphere.vertex_valence(a) == 4
                && sphere.vertex_valence(b) == 4
                && (sphere.position(a).y - sphere.position(b).y).abs() > 0.1
        })
        .unwrap();
    let (v0, e0, f0) = counts(&sphere);
    let mut m = sphere.clone();
    let faces = bevel_edges(&mut m, &[e], 0.05, 1).unwrap();
    m.validate().unwrap();
    // Each end: the vertex goes, three points come (one per other edge).
    assert_eq!(counts(&m).0, v0 - 2 + 6);
    assert_eq!(
        counts(&m).2,
        f0 + 1 + 2,
        "the bevel quad and a triangle at each end"
    );
    assert_eq!(faces.len(), 3);
    assert!(m.stats().closed);
    // Still a sphere (V − E + F = 2): the edges follow, seven more.
    assert_eq!(counts(&m).1, e0 + 7);

    // Two edges in line through a valence-4 vertex (part of a ring): no
    // patch where they meet, only at the two far ends.
    let [a, b] = sphere.edge_vertices(e);
    let along = (sphere.position(b) - sphere.position(a)).normalize();
    let next = sphere
        .edges()
        .find(|&x| {
            let [p, q] = sphere.edge_vertices(x);
            let other = match (p == b, q == b) {
                (true, _) => q,
                (_, true) => p,
                _ => return false,
            };
            other != a
                && sphere.vertex_valence(other) == 4
                && (sphere.position(other) - sphere.position(b))
                    .normalize()
                    .dot(along)
                    > 0.5
        })
        .unwrap();
    let mut m = sphere.clone();
    let faces = bevel_edges(&mut m, &[e, next], 0.05, 1).unwrap();
    m.validate().unwrap();
    assert_eq!(faces.len(), 2 + 2, "two quads, a patch at each far end");
    assert!(m.stats().closed);
}

#[test]
fn a_rounded_bevel_bends_its_segments_towards_the_old_corner() {
    use hedra_geom::modeling::bevel_edges;
    let mut c = cube();
    let e = hedra_geom::EdgeId(0);
    let [a, _] = c.edge_vertices(e);
    let pa = c.position(a);
    let strips = bevel_edges(&mut c, &[e], 0.5, 4).unwrap();
    c.validate().unwrap();
    assert_eq!(strips.len(), 4, "four strips");
    assert_eq!(counts(&c), (10 + 6, 15 + 9, 7 + 3));
    assert!(c.stats().closed);
    // The middle of the arc at the first end: Bézier(0.5) = a1/4 + corner/2 + a2/4,
    // 0.25 of the width nearer the corner than the flat chamfer's midpoint.
    let mid = c
        .vertices()
        .map(|v| c.position(v))
        .min_by(|p, q| p.distance(pa).total_cmp(&q.distance(pa)))
        .unwrap();
    let flat_mid_distance = (0.5f64 * 0.5 + 0.5 * 0.5).sqrt() / 2.0;
    assert!(
        mid.distance(pa) < flat_mid_distance,
        "rounded outwards: {} vs {flat_mid_distance}",
        mid.distance(pa)
    );
    // Rounding adds volume back compared with a flat chamfer.
    let mut flat = cube();
    bevel_edges(&mut flat, &[e], 0.5, 1).unwrap();
    assert!(c.volume() > flat.volume());
}

/// Ctrl+T: every face of a cube split into two triangles by Euler MEFs;
/// nothing moves, the mesh stays closed and valid; a concave face (an L)
/// triangulates inside its outline.
#[test]
fn triangulate_splits_faces_along_diagonals() {
    use hedra_geom::{DVec3, HalfEdgeMesh, Primitive, modeling};
    let mut cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let positions = cube.positions().to_vec();
    let faces: Vec<_> = cube.faces().collect();
    let made =
        modeling::triangulate_faces(&mut cube, &faces, modeling::TriangulateMethod::Clip).unwrap();
    cube.validate().unwrap();
    assert_eq!(made.len(), 6);
    assert_eq!(
        (cube.vertex_count(), cube.edge_count(), cube.face_count()),
        (8, 18, 12)
    );
    assert!(cube.faces().all(|f| cube.face_degree(f) == 3));
    assert_eq!(cube.positions(), &positions[..]);
    // An L-shaped hexagon: 4 triangles, all facing up (none outside the L).
    let l = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(2.0, 0.0, -1.0),
        DVec3::new(1.0, 0.0, -1.0),
        DVec3::new(1.0, 0.0, -2.0),
        DVec3::new(0.0, 0.0, -2.0),
    ];
    let mut m = HalfEdgeMesh::from_polygons(&l, &[vec![0u32, 1, 2, 3, 4, 5]]).unwrap();
    let f: Vec<_> = m.faces().collect();
    let up = m.face_normal(f[0]);
    let tris = hedra_geom::query::triangulate_face(&m, f[0]);
    modeling::triangulate_faces(&mut m, &f, modeling::TriangulateMethod::Clip).unwrap();
    m.validate().unwrap();
    assert_eq!(m.face_count(), 4, "{tris:?}");
    let area: f64 = m.faces().map(|g| m.face_area_vector(g).dot(up)).sum();
    assert!(
        (area - 3.0).abs() < 1e-12,
        "the triangles cover the L: {area}"
    );
    assert!(m.faces().all(|g| m.face_normal(g).dot(up) > 0.99));
    // Triangles stay as they are.
    let before = m.clone();
    let all: Vec<_> = m.faces().collect();
    assert!(
        modeling::triangulate_faces(&mut m, &all, modeling::TriangulateMethod::Clip)
            .unwrap()
            .is_empty()
    );
    assert_eq!(m, before);
}

#[test]
fn tris_to_quads_undoes_triangulate_on_a_cube() {
    use hedra_geom::{Primitive, modeling};
    let mut cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let positions = cube.positions().to_vec();
    let faces: Vec<_> = cube.faces().collect();
    modeling::triangulate_faces(&mut cube, &faces, modeling::TriangulateMethod::Clip).unwrap();
    let triangles: Vec<_> = cube.faces().collect();
    let limit = modeling::DEFAULT_JOIN_LIMIT;
    let quads = modeling::tris_to_quads(&mut cube, &triangles, limit, limit).unwrap();
    cube.validate().unwrap();
    assert_eq!(quads.len(), 6);
    // The 12 cube edges sit between triangles at 90°: only the 6 diagonals go.
    assert_eq!(
        (cube.vertex_count(), cube.edge_count(), cube.face_count()),
        (8, 12, 6)
    );
    assert!(cube.faces().all(|f| cube.face_degree(f) == 4));
    assert_eq!(cube.positions(), &positions[..]);
}

#[test]
fn tris_to_quads_respects_the_face_angle_shape_and_convexity() {
    use hedra_geom::{DVec3, HalfEdgeMesh, ModelingError, modeling};
    let limit = modeling::DEFAULT_JOIN_LIMIT;
    // Two triangles of a unit square folded by `fold` about the diagonal 0–2.
    let folded = |fold: f64| {
        let p = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, -1.0),
            DVec3::new(
                0.5 - 0.5 * fold.cos(),
                0.5_f64.sqrt() * fold.sin(),
                -0.5 - 0.5 * fold.cos(),
            ),
        ];
        HalfEdgeMesh::from_polygons(&p, &[vec![0u32, 1, 2], vec![0, 2, 3]]).unwrap()
    };
    let mut flat = folded(0.0);
    let all: Vec<_> = flat.faces().collect();
    assert_eq!(
        modeling::tris_to_quads(&mut flat, &all, limit, limit)
            .unwrap()
            .len(),
        1
    );
    flat.validate().unwrap();
    assert_eq!((flat.edge_count(), flat.face_count()), (4, 1));
    // Folded 60°: above the 40° face limit, joined under a 90° one.
    let mut bent = folded(60f64.to_radians());
    let all: Vec<_> = bent.faces().collect();
    assert!(
        modeling::tris_to_quads(&mut bent, &all, limit, limit)
            .unwrap()
            .is_empty()
    );
    assert_eq!(bent.face_count(), 2);
    let wide = 90f64.to_radians();
    assert_eq!(
        modeling::tris_to_quads(&mut bent, &all, wide, wide)
            .unwrap()
            .len(),
        1
    );
    bent.validate().unwrap();
    // A dart (concave quad) is never made, whatever the limits.
    let dart = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(2.0, 0.0, -1.0),
        DVec3::new(0.0, 0.0, -2.0),
        DVec3::new(0.5, 0.0, -1.0),
    ];
    let mut m = HalfEdgeMesh::from_polygons(&dart, &[vec![0u32, 1, 3], vec![1, 2, 3]]).unwrap();
    let all: Vec<_> = m.faces().collect();
    let pi = std::f64::consts::PI;
    assert!(
        modeling::tris_to_quads(&mut m, &all, pi, pi)
            .unwrap()
            .is_empty()
    );
    assert!(matches!(
        modeling::tris_to_quads(&mut m, &all, -1.0, limit),
        Err(ModelingError::Parameter {
            what: "face angle limit",
            ..
        })
    ));
}

#[test]
fn bisect_cuts_a_cube_and_can_clear_and_fill_one_half() {
    use hedra_geom::modeling::{self, BisectClear};
    use hedra_geom::{DVec3, Primitive};
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let all: Vec<_> = cube.faces().collect();
    let (origin, up) = (DVec3::ZERO, DVec3::Y);

    let mut cut = cube.clone();
    let made = modeling::bisect(&mut cut, &all, origin, up, BisectClear::Neither, false).unwrap();
    cut.validate().unwrap();
    assert_eq!(
        (cut.vertex_count(), cut.edge_count(), cut.face_count()),
        (12, 20, 10)
    );
    assert_eq!((made.new_vertices.len(), made.cut_edges.len()), (4, 4));
    assert!(made.new_vertices.iter().all(|&v| cut.position(v).y == 0.0));

    // Upper half cleared, the cut filled: a closed half cube.
    let mut half = cube.clone();
    let made = modeling::bisect(&mut half, &all, origin, up, BisectClear::Outer, true).unwrap();
    half.validate().unwrap();
    assert_eq!(
        (half.vertex_count(), half.edge_count(), half.face_count()),
        (8, 12, 6)
    );
    assert_eq!(made.fill_faces.len(), 1);
    assert!(half.stats().closed);
    assert!(half.vertices().all(|v| half.position(v).y <= 0.0));
    assert!((half.volume() - 4.0).abs() < 1e-12, "{}", half.volume());
    // The fill faces outwards: up, on the kept lower half.
    assert!(half.face_normal(made.fill_faces[0]).dot(up) > 0.99);

    // A plane through four corners (x = z) splits no edge: only the top and
    // bottom squares get a diagonal.
    let mut diagonal = cube.clone();
    let n = DVec3::new(1.0, 0.0, -1.0);
    let made =
        modeling::bisect(&mut diagonal, &all, origin, n, BisectClear::Neither, false).unwrap();
    diagonal.validate().unwrap();
    assert!(made.new_vertices.is_empty());
    assert_eq!(
        (
            diagonal.vertex_count(),
            diagonal.edge_count(),
            diagonal.face_count()
        ),
        (8, 14, 8)
    );

    // A plane that misses the mesh changes nothing; a zero normal is refused.
    let mut missed = cube.clone();
    modeling::bisect(
        &mut missed,
        &all,
        DVec3::Y * 5.0,
        up,
        BisectClear::Neither,
        false,
    )
    .unwrap();
    assert!(missed.same_as(&cube));
    let err = modeling::bisect(
        &mut missed,
        &all,
        origin,
        DVec3::ZERO,
        BisectClear::Neither,
        false,
    );
    assert!(err.unwrap_err().to_string().contains("non-zero normal"));
    assert!(missed.same_as(&cube));
}

/// Beauty cuts a long thin quad along its short diagonal (both triangles'
/// smallest angle larger than along the long one); the fixed fan cuts it
/// from its first corner whatever the shape; a concave face falls back to
/// ear clipping for the fan. Counts and validity for every method.
#[test]
fn triangulate_methods_choose_their_diagonals() {
    use hedra_geom::modeling::{self, TriangulateMethod};
    // A kite: corners 0 and 2 far apart, 1 and 3 close together.
    let kite = || {
        HalfEdgeMesh::from_polygons(
            &[
                DVec3::new(-3.0, 0.0, 0.0),
                DVec3::new(0.0, 0.0, 0.5),
                DVec3::new(3.0, 0.0, 0.0),
                DVec3::new(0.0, 0.0, -0.5),
            ],
            &[vec![0u32, 1, 2, 3]],
        )
        .unwrap()
    };
    let diagonal = |method: TriangulateMethod| {
        let mut m = kite();
        let f = m.faces().next().unwrap();
        modeling::triangulate_faces(&mut m, &[f], method).unwrap();
        m.validate().unwrap();
        assert_eq!(
            (m.vertex_count(), m.edge_count(), m.face_count()),
            (4, 5, 2)
        );
        let mut d: Vec<u32> = m
            .edges()
            .map(|e| m.edge_vertices(e))
            .find(|[a, b]| (a.0 + 2) % 4 == b.0 || (b.0 + 2) % 4 == a.0)
            .unwrap()
            .iter()
            .map(|v| v.0)
            .collect();
        d.sort();
        d
    };
    assert_eq!(
        diagonal(TriangulateMethod::Beauty),
        vec![1, 3],
        "the short diagonal"
    );
    assert_eq!(
        diagonal(TriangulateMethod::Fan),
        vec![0, 2],
        "from the first corner"
    );
    // An L-shaped hexagon whose first corner (2, 0) does not see the
    // corner (1, -2) past the inner corner: its fan would leave the face.
    let mut l = HalfEdgeMesh::from_polygons(
        &[
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, -2.0),
            DVec3::new(1.0, 0.0, -2.0),
            DVec3::new(1.0, 0.0, -1.0),
            DVec3::new(2.0, 0.0, -1.0),
            DVec3::new(2.0, 0.0, 0.0),
        ],
        &[vec![5u32, 4, 3, 2, 1, 0]],
    )
    .unwrap();
    let f = l.faces().next().unwrap();
    modeling::triangulate_faces(&mut l, &[f], TriangulateMethod::Fan).unwrap();
    l.validate().unwrap();
    assert_eq!(l.face_count(), 4);
    for f in l.faces() {
        assert!(
            l.face_normal(f).y > 0.99,
            "every triangle inside the outline, facing up"
        );
    }
}
