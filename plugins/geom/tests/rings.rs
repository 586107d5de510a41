//! Mäntylä's operators on faces with several loops (issue 3): MVFS/KVFS,
//! KEMR/MEKR, KFMRH/MFKRH. Inverse pairs restore the mesh, refusals leave
//! it untouched, the Euler–Poincaré formula V − E + F − (L − F) = 2(S − H)
//! holds, a block with a square hole through it has genus 1, and the
//! consumers that cannot handle rings refuse them.

use hedra_geom::subdivision::{Creases, Options, Refiner, SubdivisionError};
use hedra_geom::{
    DVec3, EulerError, FaceId, HalfEdgeId, HalfEdgeMesh, LoopStart, MeshData, Primitive, VertexId,
};

fn cube() -> HalfEdgeMesh {
    Primitive::Cube { size: 2.0 }.build().unwrap()
}

fn primitives() -> Vec<HalfEdgeMesh> {
    vec![
        HalfEdgeMesh::new(),
        cube(),
        Primitive::Grid {
            x_segments: 3,
            z_segments: 2,
            size: 2.0,
        }
        .build()
        .unwrap(),
        Primitive::Torus {
            major_segments: 6,
            minor_segments: 4,
            major_radius: 1.0,
            minor_radius: 0.3,
        }
        .build()
        .unwrap(),
        Primitive::IcoSphere {
            subdivisions: 0,
            radius: 1.0,
        }
        .build()
        .unwrap(),
    ]
}

/// (V, E, F, L, S, H) with H from the stats.
fn counts(m: &HalfEdgeMesh) -> (usize, usize, usize, usize, usize, i64) {
    let s = m.stats();
    (
        m.vertex_count(),
        m.edge_count(),
        m.face_count(),
        m.loop_count(),
        s.shells,
        s.genus.expect("valid mesh with a whole genus"),
    )
}

/// V − E + F − (L − F) + b = 2(S − H), boundary loops counted as faces.
fn euler_poincare(m: &HalfEdgeMesh, shells: usize, holes: i64) -> bool {
    let (v, e, f, l) = (
        m.vertex_count() as i64,
        m.edge_count() as i64,
        m.face_count() as i64,
        m.loop_count() as i64,
    );
    let b = m.boundary_loops().len() as i64;
    v - e + f + b - (l - f) == 2 * (shells as i64 - holes)
}

fn face_up(m: &HalfEdgeMesh) -> FaceId {
    m.faces().find(|&f| m.face_normal(f).y > 0.9).unwrap()
}

/// A half-edge of `f`'s outer loop ending at `v`.
fn into(m: &HalfEdgeMesh, f: FaceId, v: VertexId) -> HalfEdgeId {
    m.face_halfedges(f).find(|&h| m.target(h) == v).unwrap()
}

/// The cube with a dangling edge into its top face, and that edge removed
/// by KEMR: the top face gets a lone-vertex ring. Returns the mesh, the
/// face, and KEMR's corners.
fn cube_with_lone_ring() -> (HalfEdgeMesh, FaceId, LoopStart, LoopStart) {
    let mut m = cube();
    let top = face_up(&m);
    let h = m.face_halfedges(top).next().unwrap();
    let (e, w) = m.make_edge_vertex(h, DVec3::new(0.0, 1.0, 0.0)).unwrap();
    let out = if m.target(e.halfedge(0)) == w {
        e.halfedge(0)
    } else {
        e.halfedge(1)
    };
    let (kept, ring) = m.kill_edge_make_ring(out).unwrap();
    m.validate().unwrap();
    assert_eq!(ring, LoopStart::Vertex(w));
    assert_eq!(m.face_rings(top), &[ring]);
    (m, top, kept, ring)
}

/// The cube with a square drawn inside its top face (bridge, MEVs, MEF) and
/// the bridge removed by KEMR: the top face's ring is the square's outline.
/// Returns the mesh, the top face, the inner square face and KEMR's corners.
fn cube_with_square_ring() -> (HalfEdgeMesh, FaceId, FaceId, LoopStart, LoopStart) {
    let mut m = cube();
    let top = face_up(&m);
    let corner = m
        .face_vertices(top)
        .find(|&v| {
            let p = m.position(v);
            p.x < 0.0 && p.z < 0.0
        })
        .unwrap();
    let q =
        [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)].map(|(x, z)| DVec3::new(x, 1.0, z));
    // MEV's new half-edge 0 runs from the corner to the new vertex.
    let (bridge, q0) = m.make_edge_vertex(into(&m, top, corner), q[0]).unwrap();
    let bridge_out = bridge.halfedge(0);
    assert_eq!(m.origin(bridge_out), corner);
    let mut h_in = bridge_out;
    for &p in &q[1..] {
        h_in = m.make_edge_vertex(h_in, p).unwrap().0.halfedge(0);
    }
    // Close the square q3 -> q0: from the half-edge ending at q3 to the one ending at q0.
    let q1_to_q0 = m
        .face_halfedges(top)
        .find(|&h| m.target(h) == q0 && m.origin(h) != corner)
        .unwrap();
    let (_, inner) = m.make_edge_face(h_in, q1_to_q0).unwrap();
    m.validate().unwrap();
    assert!(m.face_normal(inner).y > 0.9, "the inner square faces up");
    let (kept, ring) = m.kill_edge_make_ring(bridge_out).unwrap();
    m.validate().unwrap();
    assert_eq!(m.face_rings(top), &[ring]);
    assert_eq!(ring.vertex(&m), q0);
    assert_eq!(kept.vertex(&m), corner);
    (m, top, inner, kept, ring)
}

#[test]
fn mvfs_then_kvfs_restores_the_mesh() {
    for m0 in primitives() {
        let (v0, e0, f0, l0, s0, h0) = counts(&m0);
        let mut m = m0.clone();
        let (v, f) = m.make_vertex_face_shell(DVec3::new(5.0, 0.0, 0.0)).unwrap();
        m.validate().unwrap();
        assert_eq!(counts(&m), (v0 + 1, e0, f0 + 1, l0 + 1, s0 + 1, h0));
        assert_eq!(m.lone_vertex_face(f), Some(v));
        assert_eq!(m.outer_loop(f), LoopStart::Vertex(v));
        assert_eq!(m.face_halfedges(f).count(), 0);
        assert!(m.is_isolated_vertex(v) && m.has_edgeless_faces() && !m.has_rings());
        assert_eq!(m.first_non_polygon_face(), Some(f));
        assert_eq!(m.face_centroid(f), DVec3::new(5.0, 0.0, 0.0));
        assert_eq!(m.kill_vertex_face_shell(f).unwrap(), v);
        m.validate().unwrap();
        assert!(m.same_as(&m0));
        assert!(!m.is_face(f) && !m.is_vertex(v));
        assert_eq!(m.first_non_polygon_face(), None);
    }
}

#[test]
fn a_shell_grows_from_its_lone_vertex_into_a_lamina_and_back() {
    let mut m = HalfEdgeMesh::new();
    let (v0, f) = m.make_vertex_face_shell(DVec3::ZERO).unwrap();
    let start = m.clone();
    let (e01, v1) = m.make_edge_vertex_lone(v0, DVec3::X).unwrap();
    m.validate().unwrap();
    assert_eq!(m.edge_vertices(e01), [v0, v1]);
    assert_eq!(m.face_degree(f), 2, "a wire: v0 -> v1 -> v0");
    assert_eq!(m.lone_vertex_face(f), None);
    assert_eq!(counts(&m), (2, 1, 1, 1, 1, 0));
    // KEV of the wire leaves v0 alone again: the exact inverse.
    let mut back = m.clone();
    assert_eq!(back.kill_edge_vertex(e01).unwrap(), v1);
    back.validate().unwrap();
    assert!(back.same_as(&start));
    // Two more MEVs and an MEF make a square lamina of two faces.
    let h01 = e01.halfedge(0);
    let (e12, v2) = m.make_edge_vertex(h01, DVec3::new(1.0, 0.0, 1.0)).unwrap();
    let h12 = if m.origin(e12.halfedge(0)) == v1 {
        e12.halfedge(0)
    } else {
        e12.halfedge(1)
    };
    let (e23, v3) = m.make_edge_vertex(h12, DVec3::Z).unwrap();
    m.validate().unwrap();
    assert_eq!(m.face_degree(f), 6);
    let h23 = m.find_halfedge(v2, v3).unwrap();
    let h10 = m.find_halfedge(v1, v0).unwrap();
    let (_, g) = m.make_edge_face(h23, h10).unwrap();
    m.validate().unwrap();
    assert_eq!((m.face_degree(f), m.face_degree(g)), (4, 4));
    assert_eq!(counts(&m), (4, 4, 2, 2, 1, 0));
    assert!(m.stats().closed);
    // KEV on a wire of two edges leaves the wire of one edge.
    let mut wire = start.clone();
    let (a, _) = wire.make_edge_vertex_lone(v0, DVec3::X).unwrap();
    let one = wire.clone();
    let (b, _) = wire.make_edge_vertex(a.halfedge(0), DVec3::ONE).unwrap();
    wire.validate().unwrap();
    assert_eq!(wire.face_degree(f), 4);
    wire.kill_edge_vertex(b).unwrap();
    wire.validate().unwrap();
    assert!(wire.same_as(&one));
    // The lamina's edges split and join like any other.
    let mid = m.edge_midpoint(e23);
    let v = m.split_edge(e23, mid).unwrap();
    m.validate().unwrap();
    m.join_edges(v).unwrap();
    m.validate().unwrap();
}

#[test]
fn mekr_then_kemr_restores_the_mesh_with_a_lone_vertex_ring() {
    let (m0, top, kept, ring) = cube_with_lone_ring();
    let (v0, e0, f0, l0, s0, h0) = counts(&m0);
    assert_eq!((v0, e0, f0, l0, s0, h0), (9, 12, 6, 7, 1, 0));
    let mut m = m0.clone();
    let e = m.make_edge_kill_ring(kept, ring).unwrap();
    m.validate().unwrap();
    assert!(m.face_rings(top).is_empty() && !m.has_rings());
    assert_eq!(counts(&m), (9, 13, 6, 6, 1, 0));
    assert_eq!(m.edge_vertices(e), [kept.vertex(&m0), ring.vertex(&m0)]);
    assert_eq!(m.kill_edge_make_ring(e.halfedge(0)).unwrap(), (kept, ring));
    m.validate().unwrap();
    assert!(m.same_as(&m0));
}

#[test]
fn mekr_then_kemr_restores_the_mesh_with_a_square_ring() {
    let (m0, top, inner, kept, ring) = cube_with_square_ring();
    assert_eq!(counts(&m0), (12, 16, 7, 8, 1, 0));
    assert_eq!(m0.face_degree(top), 4);
    assert_eq!(m0.loop_halfedges(ring).count(), 4);
    // The ring runs the other way round from the square face inside it.
    let area = m0.face_area_vector(top);
    assert!(
        (area.y - (4.0 - 1.0)).abs() < 1e-12,
        "the hole subtracts: {area:?}"
    );
    assert!(m0.face_normal(inner).y > 0.9);
    // Any corner of the outer loop joins any corner of the ring.
    for a in m0.face_halfedges(top).collect::<Vec<_>>() {
        for b in m0.loop_halfedges(ring).collect::<Vec<_>>() {
            let mut m = m0.clone();
            let e = m
                .make_edge_kill_ring(LoopStart::HalfEdge(a), LoopStart::HalfEdge(b))
                .unwrap();
            m.validate().unwrap();
            assert_eq!(counts(&m), (12, 17, 7, 7, 1, 0));
            assert_eq!(m.face_degree(top), 4 + 4 + 2);
            let (k, r) = m.kill_edge_make_ring(e.halfedge(0)).unwrap();
            assert_eq!((k, r), (LoopStart::HalfEdge(a), LoopStart::HalfEdge(b)));
            m.validate().unwrap();
            assert!(m.same_as(&m0), "{a} {b}");
        }
    }
    // And KEMR then MEKR gives the same shape back with a new edge id.
    let mut m = m0.clone();
    let e = m.make_edge_kill_ring(kept, ring).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (12, 17, 7, 7, 1, 0));
    assert_eq!(m.face_rings(top), &[] as &[LoopStart]);
    assert_eq!(
        m.edge_vertices(e),
        [kept.vertex(&m0), ring.vertex(&m0)],
        "the bridge is back"
    );
}

#[test]
fn mfkrh_then_kfmrh_restores_the_mesh() {
    let (m0, top, _, _, ring) = cube_with_square_ring();
    let mut m = m0.clone();
    let g = m.make_face_kill_ring_hole(ring).unwrap();
    m.validate().unwrap();
    // The ring's outline becomes a face of its own (facing down): with the
    // square inside it, a closed pillow no longer held by the top: S + 1.
    assert_eq!(counts(&m), (12, 16, 8, 8, 2, 0));
    assert!(m.face_normal(g).y < -0.9);
    assert!(!m.has_rings());
    assert_eq!(m.kill_face_make_ring_hole(top, g).unwrap(), ring);
    m.validate().unwrap();
    assert!(m.same_as(&m0));
    // The lone-vertex ring becomes a face without edges: a shell of its own (S + 1).
    let (m0, top, _, ring) = cube_with_lone_ring();
    let mut m = m0.clone();
    let g = m.make_face_kill_ring_hole(ring).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (9, 12, 7, 7, 2, 0));
    assert_eq!(m.lone_vertex_face(g), Some(ring.vertex(&m0)));
    assert_eq!(m.kill_face_make_ring_hole(top, g).unwrap(), ring);
    m.validate().unwrap();
    assert!(m.same_as(&m0));
}

#[test]
fn kfmrh_glues_two_shells_and_mfkrh_separates_them() {
    // Two cubes side by side: the first's +x face and the second's -x face
    // are far apart topologically (two shells).
    let a = cube();
    let (pa, polys_a) = a.to_polygons();
    let mut positions = pa.clone();
    let mut polys = polys_a.clone();
    let n = pa.len() as u32;
    positions.extend(pa.iter().map(|p| *p + DVec3::new(4.0, 0.0, 0.0)));
    polys.extend(
        polys_a
            .iter()
            .map(|p| p.iter().map(|i| i + n).collect::<Vec<_>>()),
    );
    let m0 = HalfEdgeMesh::from_polygons(&positions, &polys).unwrap();
    assert_eq!(counts(&m0), (16, 24, 12, 12, 2, 0));
    let right = m0
        .faces()
        .find(|&f| m0.face_normal(f).x > 0.9 && m0.face_centroid(f).x < 2.0)
        .unwrap();
    let left = m0
        .faces()
        .find(|&f| m0.face_normal(f).x < -0.9 && m0.face_centroid(f).x > 2.0)
        .unwrap();
    let mut m = m0.clone();
    let ring = m.kill_face_make_ring_hole(right, left).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (16, 24, 11, 12, 1, 0), "S − 1, not H + 1");
    assert!(euler_poincare(&m, 1, 0));
    let g = m.make_face_kill_ring_hole(ring).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (16, 24, 12, 12, 2, 0));
    assert_eq!(m.kill_face_make_ring_hole(right, g).unwrap(), ring);
    let ring_mesh = m.clone();
    assert!(ring_mesh.validate().is_ok());
    // An MVFS shell glued into a face becomes a lone-vertex ring: S − 1.
    let mut m = cube();
    let (v, f) = m.make_vertex_face_shell(DVec3::new(0.0, 1.0, 0.0)).unwrap();
    let top = face_up(&m);
    assert_eq!(counts(&m), (9, 12, 7, 7, 2, 0));
    assert_eq!(
        m.kill_face_make_ring_hole(top, f).unwrap(),
        LoopStart::Vertex(v)
    );
    m.validate().unwrap();
    assert_eq!(counts(&m), (9, 12, 6, 7, 1, 0));
}

/// Mäntylä's block with a square hole through it: MVFS, MEVs and an MEF
/// make a square lamina, a sweep (MEVs and MEFs) makes a cube, a bridge,
/// MEVs and an MEF draw the hole's outline on the top, KEMR cuts the bridge,
/// a sweep takes the inner square down to the bottom, and KFMRH makes it a
/// ring of the bottom face: genus 1.
#[test]
fn block_with_a_square_hole_has_genus_one() {
    let mut m = HalfEdgeMesh::new();
    let (v0, f0) = m.make_vertex_face_shell(DVec3::ZERO).unwrap();
    assert_eq!(counts(&m), (1, 0, 1, 1, 1, 0));
    let (e01, v1) = m
        .make_edge_vertex_lone(v0, DVec3::new(2.0, 0.0, 0.0))
        .unwrap();
    let (_, v2) = m
        .make_edge_vertex(e01.halfedge(0), DVec3::new(2.0, 0.0, 2.0))
        .unwrap();
    let (_, v3) = m
        .make_edge_vertex(m.find_halfedge(v1, v2).unwrap(), DVec3::new(0.0, 0.0, 2.0))
        .unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (4, 3, 1, 1, 1, 0));
    let (_, top) = m
        .make_edge_face(
            m.find_halfedge(v2, v3).unwrap(),
            m.find_halfedge(v1, v0).unwrap(),
        )
        .unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (4, 4, 2, 2, 1, 0));
    let bottom = f0;
    assert!(m.face_normal(bottom).y < -0.9 && m.face_normal(top).y > 0.9);
    // Sweep the lamina up into a cube.
    m.extrude_face(top, DVec3::new(0.0, 2.0, 0.0)).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (8, 12, 6, 6, 1, 0));
    // The hole's outline on the top face, bridged to the corner above v0.
    let corner = m
        .face_vertices(top)
        .find(|&v| m.position(v) == DVec3::new(0.0, 2.0, 0.0))
        .unwrap();
    let q = [(0.5, 0.5), (1.5, 0.5), (1.5, 1.5), (0.5, 1.5)].map(|(x, z)| DVec3::new(x, 2.0, z));
    let (bridge, q0) = m.make_edge_vertex(into(&m, top, corner), q[0]).unwrap();
    let mut last = q0;
    let mut prev = corner;
    for &p in &q[1..] {
        let (_, w) = m
            .make_edge_vertex(m.find_halfedge(prev, last).unwrap(), p)
            .unwrap();
        prev = last;
        last = w;
    }
    let q1 = m.vertex_neighbors(q0).find(|&w| w != corner).unwrap();
    let (_, hole) = m
        .make_edge_face(
            m.find_halfedge(prev, last).unwrap(),
            m.find_halfedge(q1, q0).unwrap(),
        )
        .unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (12, 17, 7, 7, 1, 0));
    assert!(m.face_normal(hole).y > 0.9);
    let bridge_out = m.find_halfedge(corner, q0).unwrap();
    assert_eq!(bridge_out.edge(), bridge);
    m.kill_edge_make_ring(bridge_out).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (12, 16, 7, 8, 1, 0));
    assert_eq!(m.face_rings(top).len(), 1);
    // Sweep the inner square down through the block.
    m.extrude_face(hole, DVec3::new(0.0, -2.0, 0.0)).unwrap();
    m.validate().unwrap();
    assert_eq!(counts(&m), (16, 24, 11, 12, 1, 0));
    assert!(m.face_vertices(hole).all(|v| m.position(v).y == 0.0));
    assert!(m.face_normal(hole).y > 0.9, "it faces into the block, up");
    let before_glue = m.clone();
    let ring = m.kill_face_make_ring_hole(bottom, hole).unwrap();
    m.validate().unwrap();
    // V − E + F − (L − F) = 16 − 24 + 10 − 2 = 0 = 2(S − H) with S = H = 1.
    assert_eq!(counts(&m), (16, 24, 10, 12, 1, 1));
    let s = m.stats();
    assert_eq!(
        (s.rings, s.shells, s.genus, s.boundary_loops, s.closed),
        (2, 1, Some(1), 0, true)
    );
    assert!(euler_poincare(&m, 1, 1));
    assert_eq!(m.ring_count(), 2);
    assert!(m.face_rings(bottom).contains(&ring));
    assert!((m.volume() - (8.0 - 2.0)).abs() < 1e-12, "{}", m.volume());
    assert!((m.face_area_vector(bottom).y + 3.0).abs() < 1e-12);
    // Its inverse takes the bottom of the hole out again.
    let mut back = m.clone();
    let g = back.make_face_kill_ring_hole(ring).unwrap();
    back.validate().unwrap();
    assert_eq!(counts(&back), counts(&before_glue));
    assert_eq!(back.face_vertices(g).count(), 4);
    // Round trip through the stored form keeps the rings.
    let text = ron::to_string(&m).unwrap();
    assert!(text.contains("face_rings"));
    let read: HalfEdgeMesh = ron::from_str(&text).unwrap();
    assert_eq!(read, m);
    // compacted() renumbers the records and keeps the rings.
    let c = m.compacted();
    c.validate().unwrap();
    assert_eq!(counts(&c), counts(&m));
    assert_eq!(c.vertex_capacity(), 16);
    assert!((c.volume() - 6.0).abs() < 1e-12);
    // The tables name the rings.
    let tables = hedra_geom::topology::tables(&m);
    assert!(tables.contains("rings h"), "{tables}");
}

#[test]
fn files_without_rings_are_unchanged() {
    for m in primitives() {
        let text = ron::to_string(&m).unwrap();
        assert!(!text.contains("face_rings") && !text.contains("lone_vertex_faces"));
        let data = MeshData::from(m.clone());
        assert!(data.face_rings.is_empty() && data.lone_vertex_faces.is_empty());
        let back: HalfEdgeMesh = ron::from_str(&text).unwrap();
        assert_eq!(back, m);
        assert_eq!(ron::to_string(&back).unwrap(), text);
    }
    // A lone-vertex face round-trips too.
    let mut m = cube();
    m.make_vertex_face_shell(DVec3::ONE).unwrap();
    let text = ron::to_string(&m).unwrap();
    assert!(text.contains("lone_vertex_faces") && !text.contains("face_rings"));
    assert_eq!(ron::from_str::<HalfEdgeMesh>(&text).unwrap(), m);
}

#[test]
fn the_validator_checks_the_ring_tables() {
    let (m, top, _, _, ring) = cube_with_square_ring();
    let data = MeshData::from(m.clone());
    let load = |d: MeshData| HalfEdgeMesh::try_from(d).map_err(|e| e.to_string());
    assert!(load(data.clone()).is_ok());
    // A ring that starts on the outer loop.
    let mut d = data.clone();
    d.face_rings[0].1 = vec![LoopStart::HalfEdge(m.face_halfedge(top))];
    let err = load(d).unwrap_err();
    assert!(err.contains("lies on another loop"), "{err}");
    // A ring dropped: its half-edges name the face outside its loops.
    let mut d = data.clone();
    d.face_rings.clear();
    let err = load(d).unwrap_err();
    assert!(err.contains("outside its loops"), "{err}");
    // An empty ring list, and one for a dead face.
    let mut d = data.clone();
    d.face_rings[0].1.clear();
    assert!(load(d).unwrap_err().contains("ring list"));
    // A ring on a half-edge of another face.
    let mut d = data.clone();
    let other = m.faces().find(|&f| f != top).unwrap();
    d.face_rings[0].1 = vec![ring, LoopStart::HalfEdge(m.face_halfedge(other))];
    let err = load(d).unwrap_err();
    assert!(err.contains("lies on another loop"), "{err}");
    // A lone vertex that has edges, or is used twice.
    let mut d = data.clone();
    d.face_rings[0].1.push(LoopStart::Vertex(VertexId(0)));
    assert!(load(d).unwrap_err().contains("lone vertex v0"));
    let mut shell = cube();
    let (v, _) = shell.make_vertex_face_shell(DVec3::ONE).unwrap();
    let mut d = MeshData::from(shell.clone());
    d.face_rings.push((0, vec![LoopStart::Vertex(v)]));
    assert!(load(d).unwrap_err().contains("used twice"));
    // A face without a half-edge and without a lone vertex.
    let mut d = MeshData::from(shell);
    d.lone_vertex_faces.clear();
    assert!(load(d).is_err());
}

#[test]
fn precondition_failures_are_named_and_change_nothing() {
    let (m0, top, inner, kept, ring) = cube_with_square_ring();
    let check = |r: Result<(), EulerError>, expected: EulerError, m: &HalfEdgeMesh| {
        assert_eq!(r, Err(expected));
        assert_eq!(m, &m0, "a refusal changed the mesh");
    };
    let mut m = m0.clone();
    // MVFS / KVFS / MEV at a lone vertex.
    check(
        m.make_vertex_face_shell(DVec3::NAN).map(|_| ()),
        EulerError::NonFinite,
        &m,
    );
    check(
        m.kill_vertex_face_shell(top).map(|_| ()),
        EulerError::NotVertexFaceShell { face: top },
        &m,
    );
    check(
        m.kill_vertex_face_shell(FaceId(99)).map(|_| ()),
        EulerError::Missing(FaceId(99).into()),
        &m,
    );
    check(
        m.make_edge_vertex_lone(VertexId(0), DVec3::ZERO)
            .map(|_| ()),
        EulerError::NotLoneVertex {
            vertex: VertexId(0),
        },
        &m,
    );
    // KEMR: a boundary loop, and an edge between two faces.
    let e = m.face_halfedges(inner).next().unwrap();
    check(
        m.kill_edge_make_ring(e).map(|_| ()),
        EulerError::NotSameLoop { a: e, b: e.twin() },
        &m,
    );
    check(
        m.kill_edge_make_ring(HalfEdgeId(999)).map(|_| ()),
        EulerError::Missing(HalfEdgeId(999).into()),
        &m,
    );
    // MEKR: same loop, not a ring, different faces, a corner on a boundary.
    let outer: Vec<HalfEdgeId> = m.face_halfedges(top).collect();
    check(
        m.make_edge_kill_ring(LoopStart::HalfEdge(outer[0]), LoopStart::HalfEdge(outer[2]))
            .map(|_| ()),
        EulerError::SameLoop { face: top },
        &m,
    );
    check(
        m.make_edge_kill_ring(ring, kept).map(|_| ()),
        EulerError::NotARing { face: top },
        &m,
    );
    let side = m.face_halfedges(FaceId(0)).next().unwrap();
    let side_face = m.face(side).unwrap();
    check(
        m.make_edge_kill_ring(LoopStart::HalfEdge(side), ring)
            .map(|_| ()),
        EulerError::DifferentFaces {
            a: side_face,
            b: top,
        },
        &m,
    );
    check(
        m.make_edge_kill_ring(LoopStart::Vertex(VertexId(0)), ring)
            .map(|_| ()),
        EulerError::NotLoneVertex {
            vertex: VertexId(0),
        },
        &m,
    );
    // KFMRH: itself, a face with rings, faces that share a vertex.
    check(
        m.kill_face_make_ring_hole(top, top).map(|_| ()),
        EulerError::FaceWithItself { face: top },
        &m,
    );
    let bottom = m.faces().find(|&f| m.face_normal(f).y < -0.9).unwrap();
    check(
        m.kill_face_make_ring_hole(bottom, top).map(|_| ()),
        EulerError::HasRings { face: top },
        &m,
    );
    let r = m.kill_face_make_ring_hole(top, side_face);
    assert!(matches!(r, Err(EulerError::FacesTouch { a, b, .. }) if a == top && b == side_face));
    assert_eq!(m, m0);
    // The inner square touches the ring (it shares all its vertices).
    assert!(matches!(
        m.kill_face_make_ring_hole(top, inner),
        Err(EulerError::FacesTouch { .. })
    ));
    assert_eq!(m, m0);
    // MFKRH: the outer loop is not a ring.
    check(
        m.make_face_kill_ring_hole(kept).map(|_| ()),
        EulerError::NotARing { face: top },
        &m,
    );
    // Existing operators refuse faces with rings where they cannot keep them.
    check(
        m.make_hole(top).map(|_| ()),
        EulerError::HasRings { face: top },
        &m,
    );
    check(
        m.extrude_face(top, DVec3::Y).map(|_| ()),
        EulerError::HasRings { face: top },
        &m,
    );
    // And faces without edges.
    let mut m = cube();
    let (v, f) = m.make_vertex_face_shell(DVec3::ONE).unwrap();
    let m1 = m.clone();
    assert_eq!(m.make_hole(f), Err(EulerError::HasRings { face: f }));
    assert_eq!(
        m.extrude_face(f, DVec3::Y),
        Err(EulerError::HasRings { face: f })
    );
    assert_eq!(
        m.add_face(&[v, VertexId(0), VertexId(1)]),
        Err(EulerError::HasRings { face: f })
    );
    assert!(m.join_edges(v).is_err());
    assert_eq!(m, m1);
    // A wire cannot become a hole (a boundary of two edges).
    let (e, w) = m
        .make_edge_vertex_lone(v, DVec3::new(2.0, 2.0, 2.0))
        .unwrap();
    // The wire runs from the lone vertex to the new one, inside face f.
    let mut ends = m.edge_vertices(e);
    ends.sort();
    let mut want = [v, w];
    want.sort();
    assert_eq!(ends, want);
    assert_eq!(m.position(w), DVec3::new(2.0, 2.0, 2.0));
    assert_eq!(m.edge_faces(e), [Some(f), Some(f)]);
    let m2 = m.clone();
    assert_eq!(m.make_hole(f), Err(EulerError::Degenerate));
    assert_eq!(m, m2);
}

#[test]
fn existing_operators_keep_rings_in_their_place() {
    let (m0, top, inner, _, ring) = cube_with_square_ring();
    // MEF across the ring splits it; KEF joins it again.
    let r: Vec<HalfEdgeId> = m0.loop_halfedges(ring).collect();
    let mut m = m0.clone();
    let (e, g) = m.make_edge_face(r[0], r[2]).unwrap();
    m.validate().unwrap();
    assert_eq!(m.face_rings(top).len(), 1);
    assert_eq!(m.loop_halfedges(m.face_rings(top)[0]).count(), 3);
    assert_eq!(m.face_degree(g), 3);
    assert!(euler_poincare(&m, 1, 0));
    m.kill_edge_face(e).unwrap();
    m.validate().unwrap();
    assert!(m.same_as(&m0));
    // The square shares all its edges with the ring: KEF refuses.
    let mut m = m0.clone();
    let edge = m.loop_halfedges(ring).next().unwrap().edge();
    assert!(matches!(
        m.kill_edge_face(edge),
        Err(EulerError::SharedEdges { .. })
    ));
    assert_eq!(m, m0);
    // Sunk into a pit, KEF between the top and a wall of the pit merges the
    // ring and the wall's loop into one ring of the top.
    m.extrude_face(inner, DVec3::new(0.0, -0.5, 0.0)).unwrap();
    let pit = m.clone();
    let wall_edge = m.loop_halfedges(m.face_rings(top)[0]).next().unwrap();
    let wall = m.face(wall_edge.twin()).unwrap();
    assert_ne!(wall, inner);
    // Half-edge 0 of the edge on the top keeps the top.
    let e = wall_edge.edge();
    let top_side = if m.face(e.halfedge(0)) == Some(top) {
        0
    } else {
        1
    };
    let killed = m.kill_edge_face(e).unwrap();
    m.validate().unwrap();
    let (kept, gone) = if top_side == 0 {
        (top, wall)
    } else {
        (wall, top)
    };
    assert_eq!(killed, gone);
    assert!(m.is_face(kept));
    assert_eq!(m.face_rings(kept).len(), 1);
    assert_eq!(m.loop_halfedges(m.face_rings(kept)[0]).count(), 4 + 4 - 2);
    assert_eq!(m.face_degree(kept), 4, "the outer loop is the top's");
    assert!(euler_poincare(&m, 1, 0));
    assert!(pit.validate().is_ok());
    // Split and join edges on the ring, MEV into it.
    let mut m = m0.clone();
    let mid = m.edge_midpoint(r[1].edge());
    let v = m.split_edge(r[1].edge(), mid).unwrap();
    m.validate().unwrap();
    assert_eq!(m.loop_halfedges(m.face_rings(top)[0]).count(), 5);
    m.join_edges(v).unwrap();
    m.validate().unwrap();
    assert!(m.same_as(&m0));
    let (e, _) = m.make_edge_vertex(r[0], DVec3::new(0.0, 1.0, 0.1)).unwrap();
    m.validate().unwrap();
    m.kill_edge_vertex(e).unwrap();
    m.validate().unwrap();
    assert!(m.same_as(&m0));
    // Deleting the face takes its rings; compaction keeps the others.
    let mut m = m0.clone();
    m.delete_faces(&[top], false);
    m.validate().unwrap();
    assert!(!m.has_rings());
    assert_eq!(m.boundary_loops().len(), 2);
}

#[test]
fn consumers_refuse_faces_with_rings() {
    let (m, top, _, _, _) = cube_with_square_ring();
    assert_eq!(m.first_non_polygon_face(), Some(top));
    assert!(!m.is_polygon_face(top));
    assert!(hedra_geom::query::triangulate_face(&m, top).is_empty());
    let err = Refiner::new(&m, &Creases::default(), Options::default(), 1).unwrap_err();
    assert_eq!(err, SubdivisionError::FaceWithRings { face: top });
    assert!(err.to_string().contains(&top.to_string()));
    let mut shell = cube();
    let (_, f) = shell.make_vertex_face_shell(DVec3::ONE).unwrap();
    assert!(hedra_geom::query::triangulate_face(&shell, f).is_empty());
    assert_eq!(
        Refiner::new(&shell, &Creases::default(), Options::default(), 1).unwrap_err(),
        SubdivisionError::FaceWithRings { face: f }
    );
    // Ordinary meshes are not affected.
    assert!(Refiner::new(&cube(), &Creases::default(), Options::default(), 1).is_ok());
}
