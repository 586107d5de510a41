//! Rip (Blender's V): tearing a grid and a cube open along edges, with the
//! counts, the Euler–Poincaré formula and `validate()` after every step.

use hedra_geom::modeling::{self, ModelingError};
use hedra_geom::{DVec3, EdgeId, FaceId, HalfEdgeMesh, Primitive, TopologyCounts, VertexId};

/// 4 × 4 quads, corners at x, z ∈ {−2, −1, 0, 1, 2}, y = 0.
fn grid() -> HalfEdgeMesh {
    Primitive::Grid {
        x_segments: 4,
        z_segments: 4,
        size: 4.0,
    }
    .build()
    .unwrap()
}

fn vertex_at(m: &HalfEdgeMesh, x: f64, z: f64) -> VertexId {
    let p = DVec3::new(x, 0.0, z);
    m.vertices()
        .find(|&v| m.position(v).distance(p) < 1e-9)
        .unwrap_or_else(|| panic!("no vertex at {p}"))
}

fn edge_between(m: &HalfEdgeMesh, a: (f64, f64), b: (f64, f64)) -> EdgeId {
    m.find_edge(vertex_at(m, a.0, a.1), vertex_at(m, b.0, b.1))
        .expect("an edge")
}

fn counts(m: &HalfEdgeMesh) -> TopologyCounts {
    m.validate().unwrap();
    let c = TopologyCounts::of(m);
    assert!(c.euler_poincare_holds(), "{c}");
    c
}

/// (V, E, F, S, H, B)
fn short(c: TopologyCounts) -> (i64, i64, i64, i64, i64, i64) {
    (
        c.vertices,
        c.edges,
        c.faces,
        c.shells,
        c.holes,
        c.boundary_loops,
    )
}

#[test]
fn a_path_inside_a_grid_opens_a_slit_with_shared_ends() {
    let mut m = grid();
    assert_eq!(short(counts(&m)), (25, 40, 16, 1, 0, 1));
    let edges = [
        edge_between(&m, (-1.0, 0.0), (0.0, 0.0)),
        edge_between(&m, (0.0, 0.0), (1.0, 0.0)),
    ];
    let (left, mid, right) = (
        vertex_at(&m, -1.0, 0.0),
        vertex_at(&m, 0.0, 0.0),
        vertex_at(&m, 1.0, 0.0),
    );
    let r = modeling::rip_edges(&mut m, &edges).unwrap();
    // The middle vertex falls apart, the slit's ends stay one vertex each.
    assert_eq!(short(counts(&m)), (26, 42, 16, 1, 0, 2));
    assert_eq!(r.copies.len(), 1);
    assert_eq!(r.copies[0].0, mid);
    let copy = r.copies[0].1[0];
    assert_eq!(m.position(copy), DVec3::ZERO);
    assert_eq!(r.edges.len(), 2);
    for &(old, new) in &r.edges {
        assert!(m.is_boundary_edge(old) && m.is_boundary_edge(new));
    }
    // Each side runs left -> (mid or its copy) -> right; the ends are on both.
    let mut a = r.side_a.clone();
    let mut b = r.side_b.clone();
    a.retain(|v| ![left, right].contains(v));
    b.retain(|v| ![left, right].contains(v));
    assert!(r.side_a.contains(&left) && r.side_b.contains(&right));
    assert_eq!(a.len(), 1);
    assert_eq!(b.len(), 1);
    assert_ne!(a, b);
    let mut both = [a[0], b[0]];
    both.sort();
    assert_eq!(both, [mid, copy]);
    // The two copies of the middle each touch the faces of one side only.
    for v in [mid, copy] {
        let zs: Vec<f64> = m.vertex_faces(v).map(|f| m.face_centroid(f).z).collect();
        assert_eq!(zs.len(), 2);
        assert!(zs.iter().all(|z| *z > 0.0) || zs.iter().all(|z| *z < 0.0));
    }
    // The slit is one boundary loop of four edges through both ends.
    let slit: Vec<_> = m
        .boundary_loops()
        .into_iter()
        .filter(|l| l.len() == 4)
        .collect();
    assert_eq!(slit.len(), 1);
    assert_eq!(
        m.vertex_valence(left),
        5,
        "the tip has both copies of its edge"
    );
}

#[test]
fn a_line_across_the_grid_cuts_it_in_two() {
    let mut m = grid();
    let edges: Vec<EdgeId> = (0..4)
        .map(|i| {
            let x = -2.0 + f64::from(i);
            edge_between(&m, (x, 0.0), (x + 1.0, 0.0))
        })
        .collect();
    let r = modeling::rip_edges(&mut m, &edges).unwrap();
    assert_eq!(short(counts(&m)), (30, 44, 16, 2, 0, 2));
    assert_eq!(r.new_vertices().len(), 5);
    assert_eq!(r.side_a.len(), 5);
    assert_eq!(r.side_b.len(), 5);
    // Moving side B moves one half only: the sides are consistent along the path.
    let zs_of = |side: &[VertexId]| -> Vec<f64> {
        side.iter()
            .flat_map(|&v| m.vertex_faces(v).map(|f| m.face_centroid(f).z))
            .collect()
    };
    let (za, zb) = (zs_of(&r.side_a), zs_of(&r.side_b));
    assert!(za.iter().all(|z| *z > 0.0) || za.iter().all(|z| *z < 0.0));
    assert!(zb.iter().all(|z| z * za[0] < 0.0));
}

#[test]
fn a_rip_from_the_boundary_opens_a_notch() {
    let mut m = grid();
    let e = edge_between(&m, (-2.0, 0.0), (-1.0, 0.0));
    let r = modeling::rip_edges(&mut m, &[e]).unwrap();
    // The boundary end splits, the inner end is the tip of the notch.
    assert_eq!(short(counts(&m)), (26, 41, 16, 1, 0, 1));
    assert_eq!(r.copies.len(), 1);
    assert_eq!(m.boundary_loops()[0].len(), 16 + 2);
}

#[test]
fn ripping_a_closed_loop_around_a_cube_gives_two_open_halves() {
    let mut m = Primitive::Cube { size: 2.0 }.build().unwrap();
    let vertical = m
        .edges()
        .find(|&e| {
            let [a, b] = m.edge_vertices(e);
            (m.position(a) - m.position(b)).y.abs() > 1.0
        })
        .unwrap();
    modeling::loop_cut(&mut m, vertical, 1).unwrap();
    assert_eq!(short(counts(&m)), (12, 20, 10, 1, 0, 0));
    let ring: Vec<EdgeId> = m
        .edges()
        .filter(|&e| m.edge_vertices(e).iter().all(|&v| m.position(v).y == 0.0))
        .collect();
    assert_eq!(ring.len(), 4);
    let r = modeling::rip_edges(&mut m, &ring).unwrap();
    let after = counts(&m);
    assert_eq!(short(after), (16, 24, 10, 2, 0, 2));
    assert_eq!(after.loops, 10);
    assert_eq!(r.new_vertices().len(), 4);
    // Each half is an open box: 8 vertices, 12 edges, 5 faces, a disc.
    let (comp, n) = m.components();
    assert_eq!(n, 2);
    for c in 0..2 {
        let vs: Vec<VertexId> = m.vertices().filter(|v| comp[v.index()] == c).collect();
        assert_eq!(vs.len(), 8);
        let ys: Vec<f64> = vs
            .iter()
            .map(|&v| m.position(v).y)
            .filter(|y| *y != 0.0)
            .collect();
        assert!(ys.iter().all(|y| *y > 0.0) || ys.iter().all(|y| *y < 0.0));
    }
    // The sides are the two rims.
    for side in [&r.side_a, &r.side_b] {
        assert_eq!(side.len(), 4);
        let c0 = comp[side[0].index()];
        assert!(side.iter().all(|v| comp[v.index()] == c0));
    }
    assert_ne!(comp[r.side_a[0].index()], comp[r.side_b[0].index()]);
}

#[test]
fn refusals_name_the_edge_and_change_nothing() {
    let m0 = grid();
    let mut m = m0.clone();
    let lone = edge_between(&m, (0.0, 0.0), (1.0, 0.0));
    let err = modeling::rip_edges(&mut m, &[lone]).unwrap_err();
    assert_eq!(err, ModelingError::RipLoneEdge { edge: lone });
    assert!(
        err.to_string()
            .starts_with(&format!("{lone} is ripped alone"))
    );
    let open = edge_between(&m, (-2.0, -2.0), (-1.0, -2.0));
    let err = modeling::rip_edges(&mut m, &[open]).unwrap_err();
    assert_eq!(err, ModelingError::RipOpenEdge { edge: open });
    assert_eq!(
        err.to_string(),
        format!("{open} is already on a boundary: only edges between two faces can be ripped")
    );
    assert_eq!(
        modeling::rip_edges(&mut m, &[EdgeId(999)]).unwrap_err(),
        ModelingError::Missing(EdgeId(999).into())
    );
    assert_eq!(
        modeling::rip_edges(&mut m, &[]).unwrap_err(),
        ModelingError::Empty("no edges")
    );
    assert!(m.same_as(&m0));
}

#[test]
fn a_vertex_ripped_off_one_face_gets_a_corner_of_its_own() {
    let mut m = grid();
    let v = vertex_at(&m, 0.0, 0.0);
    let face = m
        .vertex_faces(v)
        .find(|&f| m.face_centroid(f).distance(DVec3::new(0.5, 0.0, 0.5)) < 1e-9)
        .unwrap();
    let w = modeling::rip_vertex(&mut m, v, face).unwrap();
    assert_ne!(w, v);
    assert_eq!(short(counts(&m)), (26, 42, 16, 1, 0, 2));
    assert_eq!(m.vertex_faces(w).collect::<Vec<FaceId>>(), vec![face]);
    assert_eq!(m.vertex_valence(w), 2);
    assert_eq!(m.vertex_faces(v).count(), 3);
    assert_eq!(m.position(w), m.position(v));
    // A corner whose edges are both on the boundary has nothing to rip.
    let corner = vertex_at(&m, -2.0, -2.0);
    let f = m.vertex_faces(corner).next().unwrap();
    let before = m.clone();
    let err = modeling::rip_vertex(&mut m, corner, f).unwrap_err();
    assert_eq!(
        err,
        ModelingError::RipCorner {
            vertex: corner,
            face: f
        }
    );
    assert!(m.same_as(&before));
}

#[test]
fn topology_deltas_read_as_the_change() {
    let m0 = grid();
    let before = TopologyCounts::of(&m0);
    let mut m = m0.clone();
    let e = edge_between(&m, (-2.0, 0.0), (-1.0, 0.0));
    modeling::rip_edges(&mut m, &[e]).unwrap();
    let d = TopologyCounts::of(&m).since(&before);
    assert_eq!(d.to_string(), "V +1, E +1");
    assert!(TopologyCounts::of(&m0).since(&before).is_zero());
    assert_eq!(
        TopologyCounts::of(&m0).since(&before).to_string(),
        "no change"
    );
    assert_eq!(before.to_string(), "V 25, E 40, F 16, L 16, S 1, H 0, B 1");
}

#[test]
fn ripping_every_edge_of_a_cube_leaves_six_loose_quads() {
    let mut m = Primitive::Cube { size: 2.0 }.build().unwrap();
    let all: Vec<EdgeId> = m.edges().collect();
    let r = modeling::rip_edges(&mut m, &all).unwrap();
    // Every corner had three ripped edges: three copies of it.
    assert_eq!(short(counts(&m)), (24, 24, 6, 6, 0, 6));
    assert_eq!(r.new_vertices().len(), 16);
    assert!(m.faces().all(|f| m.face_degree(f) == 4));
}

#[test]
fn any_set_of_edges_rips_into_a_valid_mesh_or_is_refused_unchanged() {
    // A small linear congruential generator: the same subsets every run.
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = move || {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        seed >> 33
    };
    let meshes = [
        grid(),
        Primitive::UvSphere {
            segments: 8,
            rings: 6,
            radius: 1.0,
        }
        .build()
        .unwrap(),
        Primitive::Cube { size: 2.0 }.build().unwrap(),
    ];
    let (mut ripped, mut refused) = (0, 0);
    for m0 in &meshes {
        let edges: Vec<EdgeId> = m0.edges().collect();
        for _ in 0..60 {
            let pick: Vec<EdgeId> = edges.iter().copied().filter(|_| next() % 4 == 0).collect();
            if pick.is_empty() {
                continue;
            }
            let mut m = m0.clone();
            match modeling::rip_edges(&mut m, &pick) {
                Ok(r) => {
                    let c = counts(&m);
                    let c0 = TopologyCounts::of(m0);
                    assert_eq!(c.edges - c0.edges, r.edges.len() as i64);
                    assert_eq!(c.vertices - c0.vertices, r.new_vertices().len() as i64);
                    assert_eq!(c.faces, c0.faces);
                    ripped += 1;
                }
                Err(ModelingError::RipLoneEdge { .. } | ModelingError::RipOpenEdge { .. }) => {
                    assert!(m.same_as(m0));
                    refused += 1;
                }
                Err(e) => panic!("unexpected refusal: {e}"),
            }
        }
    }
    assert!(
        ripped > 20 && refused > 20,
        "{ripped} ripped, {refused} refused"
    );
}
