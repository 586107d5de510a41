//! Euler operators: inverse pairs restore the mesh, every precondition
//! failure leaves it untouched, and random sequences keep it valid with
//! V − E + F − (L − F) = 2(S − H).

use hedra_geom::{
    DVec3, EdgeId, EulerError, FaceId, HalfEdgeId, HalfEdgeMesh, LoopStart, MeshData, Primitive,
    VertexId,
};
use proptest::prelude::*;

fn cube() -> HalfEdgeMesh {
    Primitive::Cube { size: 2.0 }.build().unwrap()
}

fn meshes() -> Vec<HalfEdgeMesh> {
    vec![
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
        Primitive::Cylinder {
            segments: 5,
            radius: 1.0,
            depth: 1.0,
        }
        .build()
        .unwrap(),
    ]
}

/// χ = V − E + F, which every operator here preserves (no rings: L = F).
fn chi(m: &HalfEdgeMesh) -> i64 {
    m.vertex_count() as i64 - m.edge_count() as i64 + m.face_count() as i64
}

/// Genus H from χ = 2(S − H) − b per the stats; checked against the start.
fn euler_poincare_holds(
    m: &HalfEdgeMesh,
    shells: usize,
    genus: i64,
    boundary_loops: usize,
) -> bool {
    let (v, e, f) = (
        m.vertex_count() as i64,
        m.edge_count() as i64,
        m.face_count() as i64,
    );
    let loops = m.loop_count() as i64; // outer loops and inner rings
    // Boundary loops are holes of the surface: count them as faces of the closed-up surface.
    let b = boundary_loops as i64;
    v - e + (f + b) - (loops - f) == 2 * (shells as i64 - genus)
}

#[test]
fn mev_then_kev_restores_the_mesh() {
    for m0 in meshes() {
        for h in m0.halfedges().filter(|&h| m0.face(h).is_some()).take(12) {
            let mut m = m0.clone();
            let (e, w) = m.make_edge_vertex(h, DVec3::new(0.1, 0.2, 0.3)).unwrap();
            m.validate().unwrap();
            assert_eq!(
                (m.vertex_count(), m.edge_count(), m.face_count()),
                (m0.vertex_count() + 1, m0.edge_count() + 1, m0.face_count())
            );
            assert_eq!(m.vertex_valence(w), 1);
            assert_eq!(m.kill_edge_vertex(e).unwrap(), w);
            m.validate().unwrap();
            assert!(m.same_as(&m0));
            assert_eq!(
                m.vertex_capacity(),
                m0.vertex_capacity() + 1,
                "the freed id stays dead, never reused"
            );
            assert!(!m.is_vertex(w));
        }
    }
}

#[test]
fn mef_then_kef_restores_the_mesh() {
    for m0 in meshes() {
        for f in m0.faces().filter(|&f| m0.face_degree(f) >= 4) {
            let hs: Vec<HalfEdgeId> = m0.face_halfedges(f).collect();
            let mut m = m0.clone();
            let (e, g) = m.make_edge_face(hs[0], hs[2]).unwrap();
            m.validate().unwrap();
            assert_eq!(m.face_count(), m0.face_count() + 1);
            assert_eq!(m.face_degree(f) + m.face_degree(g), m0.face_degree(f) + 2);
            assert_eq!(m.edge_faces(e), [Some(f), Some(g)]);
            assert_eq!(m.kill_edge_face(e).unwrap(), g);
            m.validate().unwrap();
            assert!(m.same_as(&m0), "{f}");
        }
    }
}

#[test]
fn split_edge_then_join_edges_restores_the_mesh() {
    for m0 in meshes() {
        for e in m0.edges() {
            let mut m = m0.clone();
            let mid = m0.edge_midpoint(e);
            let v = m.split_edge(e, mid).unwrap();
            m.validate().unwrap();
            assert_eq!(m.vertex_valence(v), 2);
            assert_eq!(m.position(v), mid);
            assert_eq!(m.join_edges(v).unwrap(), e);
            m.validate().unwrap();
            assert!(m.same_as(&m0), "{e}");
        }
    }
}

#[test]
fn extrude_face_adds_the_known_counts_and_moves_the_cap() {
    let mut m = cube();
    let top = m.faces().find(|&f| m.face_normal(f).y > 0.9).unwrap();
    let sides = m.extrude_face(top, DVec3::new(0.0, 1.0, 0.0)).unwrap();
    m.validate().unwrap();
    assert_eq!(sides.len(), 4);
    assert_eq!(
        (m.vertex_count(), m.edge_count(), m.face_count()),
        (12, 20, 10)
    );
    assert_eq!(chi(&m), 2);
    assert!(
        m.face_vertices(top)
            .all(|v| (m.position(v).y - 2.0).abs() < 1e-12),
        "the cap moved up by 1"
    );
    assert!(m.face_normal(top).abs_diff_eq(DVec3::Y, 1e-12));
    for s in sides {
        assert_eq!(m.face_degree(s), 4);
        let n = m.face_normal(s);
        assert!(
            n.y.abs() < 1e-12 && (n.length() - 1.0).abs() < 1e-12,
            "side quads are vertical and outward: {n:?}"
        );
        assert!(n.dot(m.face_centroid(s)) > 0.0);
    }
    assert!((m.volume() - 12.0).abs() < 1e-9, "2x2x3 box");
}

#[test]
fn precondition_failures_are_named_and_change_nothing() {
    let m0 = cube();
    let mut m = m0.clone();
    let f = FaceId(0);
    let hs: Vec<HalfEdgeId> = m.face_halfedges(f).collect();
    assert_eq!(m.make_edge_face(hs[0], hs[1]), Err(EulerError::Degenerate));
    let other = m.face_halfedges(FaceId(1)).next().unwrap();
    assert_eq!(
        m.make_edge_face(hs[0], other),
        Err(EulerError::NotSameLoop { a: hs[0], b: other })
    );
    assert_eq!(
        m.kill_edge_vertex(EdgeId(0)),
        Err(EulerError::NotDangling { edge: EdgeId(0) })
    );
    assert!(matches!(
        m.join_edges(VertexId(0)),
        Err(EulerError::Valence { valence: 3, .. })
    ));
    assert_eq!(
        m.split_edge(EdgeId(99), DVec3::ZERO),
        Err(EulerError::Missing(EdgeId(99).into()))
    );
    assert_eq!(
        m.split_edge(EdgeId(0), DVec3::NAN),
        Err(EulerError::NonFinite)
    );
    // Joining two cube faces leaves a face whose neighbour shares two edges with it.
    let e = EdgeId(0);
    let g = m.kill_edge_face(e).unwrap();
    let shared = m.edges().find(|&x| {
        let [a, b] = m.edge_faces(x);
        a.is_some()
            && b.is_some()
            && a != b
            && m.face_halfedges(a.unwrap())
                .filter(|h| m.face(h.twin()) == b)
                .count()
                > 1
    });
    if let Some(x) = shared {
        let before = m.clone();
        assert!(matches!(
            m.kill_edge_face(x),
            Err(EulerError::SharedEdges { .. })
        ));
        assert_eq!(m, before);
    }
    let _ = g;
    // Boundary edges cannot be joined across; a triangle cannot lose a side.
    let mut grid = Primitive::Plane { size: 1.0 }.build().unwrap();
    let before = grid.clone();
    assert!(matches!(
        grid.kill_edge_face(EdgeId(0)),
        Err(EulerError::BoundaryEdge { .. })
    ));
    let h = grid.halfedges().find(|&h| grid.face(h).is_none()).unwrap();
    assert_eq!(
        grid.make_edge_vertex(h, DVec3::ZERO),
        Err(EulerError::NoFace { halfedge: h })
    );
    assert_eq!(grid, before);
    let mut ico = Primitive::IcoSphere {
        subdivisions: 0,
        radius: 1.0,
    }
    .build()
    .unwrap();
    let original = ico.clone();
    let ends = ico.edge_vertices(EdgeId(0));
    let v = ico.split_edge(EdgeId(0), DVec3::ZERO).unwrap();
    let split = ico.clone();
    // Both faces next to the split edge are triangles-with-a-midpoint (4 sides): joining is fine,
    // and undoes the split: edge 0 (the smaller id) spans both ends again.
    assert_eq!(ico.join_edges(v), Ok(EdgeId(0)));
    assert_ne!(ico, split);
    ico.validate().unwrap();
    assert!(!ico.is_vertex(v));
    assert_eq!(ico.edge_vertices(EdgeId(0)), ends);
    assert_eq!(
        (ico.vertex_count(), ico.edge_count(), ico.face_count()),
        (
            original.vertex_count(),
            original.edge_count(),
            original.face_count()
        )
    );
    for u in original.vertices() {
        assert_eq!(ico.position(u), original.position(u));
    }
    assert_eq!(
        m0.clone().make_edge_face(hs[0], hs[0]),
        Err(EulerError::Degenerate)
    );
}

#[derive(Clone, Debug)]
enum Op {
    Mev(usize, f64),
    Kev(usize),
    Mef(usize, usize, usize),
    Kef(usize),
    Mve(usize, f64),
    Kve(usize),
    Extrude(usize, f64),
    Hole(usize),
    Fill(usize),
    Collapse(usize),
    CollapseAny(usize),
    SplitVertex(usize, usize, usize),
    Mvfs(f64),
    Kvfs(usize),
    MevLone(usize, f64),
    Kemr(usize),
    Mekr(usize, usize, usize, usize),
    Kfmrh(usize, usize),
    Mfkrh(usize, usize),
    MefRing(usize, usize, usize),
}

fn arb_op() -> impl Strategy<Value = Op> {
    prop_oneof![
        (any::<usize>(), -1.0..1.0f64).prop_map(|(a, t)| Op::Mev(a, t)),
        any::<usize>().prop_map(Op::Kev),
        (any::<usize>(), any::<usize>(), any::<usize>()).prop_map(|(a, b, c)| Op::Mef(a, b, c)),
        any::<usize>().prop_map(Op::Kef),
        (any::<usize>(), 0.1..0.9f64).prop_map(|(a, t)| Op::Mve(a, t)),
        any::<usize>().prop_map(Op::Kve),
        (any::<usize>(), -1.0..1.0f64).prop_map(|(a, t)| Op::Extrude(a, t)),
        any::<usize>().prop_map(Op::Hole),
        any::<usize>().prop_map(Op::Fill),
        any::<usize>().prop_map(Op::Collapse),
        any::<usize>().prop_map(Op::CollapseAny),
        (any::<usize>(), any::<usize>(), any::<usize>())
            .prop_map(|(a, b, c)| Op::SplitVertex(a, b, c)),
        (-2.0..2.0f64).prop_map(Op::Mvfs),
        any::<usize>().prop_map(Op::Kvfs),
        (any::<usize>(), -1.0..1.0f64).prop_map(|(a, t)| Op::MevLone(a, t)),
        any::<usize>().prop_map(Op::Kemr),
        (
            any::<usize>(),
            any::<usize>(),
            any::<usize>(),
            any::<usize>()
        )
            .prop_map(|(a, b, c, d)| Op::Mekr(a, b, c, d)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Op::Kfmrh(a, b)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Op::Mfkrh(a, b)),
        (any::<usize>(), any::<usize>(), any::<usize>()).prop_map(|(a, b, c)| Op::MefRing(a, b, c)),
    ]
}

fn pick<T: Copy>(items: &[T], i: usize) -> Option<T> {
    (!items.is_empty()).then(|| items[i % items.len()])
}

fn apply(m: &mut HalfEdgeMesh, op: &Op) -> Result<(), EulerError> {
    let faces: Vec<FaceId> = m.faces().collect();
    if faces.is_empty() && !matches!(op, Op::Mvfs(_)) {
        return Err(EulerError::Degenerate);
    }
    let edges: Vec<EdgeId> = m.edges().collect();
    let verts: Vec<VertexId> = m.vertices().collect();
    let inner: Vec<HalfEdgeId> = m.halfedges().filter(|&h| m.face(h).is_some()).collect();
    match *op {
        Op::Mev(a, t) => {
            let Some(h) = pick(&inner, a) else {
                return Err(EulerError::Degenerate);
            };
            let p = m.position(m.target(h)) + DVec3::splat(t * 0.1);
            m.make_edge_vertex(h, p).map(|_| ())
        }
        Op::Kev(a) => match pick(&edges, a) {
            Some(e) => m.kill_edge_vertex(e).map(|_| ()),
            None => Err(EulerError::Degenerate),
        },
        Op::Mef(a, b, c) => {
            let f = pick(&faces, a).unwrap();
            let hs: Vec<HalfEdgeId> = m.face_halfedges(f).collect();
            if hs.is_empty() {
                return Err(EulerError::Degenerate); // a face without edges
            }
            m.make_edge_face(hs[b % hs.len()], hs[c % hs.len()])
                .map(|_| ())
        }
        Op::Kef(a) => match pick(&edges, a) {
            Some(e) => m.kill_edge_face(e).map(|_| ()),
            None => Err(EulerError::Degenerate),
        },
        Op::Mve(a, t) => {
            let Some(e) = pick(&edges, a) else {
                return Err(EulerError::Degenerate);
            };
            let [x, y] = m.edge_vertices(e);
            let p = m.position(x).lerp(m.position(y), t);
            m.split_edge(e, p).map(|_| ())
        }
        Op::Kve(a) => m.join_edges(pick(&verts, a).unwrap()).map(|_| ()),
        Op::Extrude(a, t) => {
            let f = pick(&faces, a).unwrap();
            let n = m.face_normal(f);
            m.extrude_face(f, n * t).map(|_| ())
        }
        Op::Hole(a) => m.make_hole(pick(&faces, a).unwrap()).map(|_| ()),
        Op::Collapse(a) => {
            let Some(h) = pick(&m.halfedges().collect::<Vec<_>>(), a) else {
                return Err(EulerError::Degenerate);
            };
            let p = m.edge_midpoint(h.edge());
            m.collapse_edge(h, p).map(|_| ())
        }
        Op::CollapseAny(a) => {
            let Some(h) = pick(&m.halfedges().collect::<Vec<_>>(), a) else {
                return Err(EulerError::Degenerate);
            };
            let p = m.edge_midpoint(h.edge());
            m.collapse_edge_removing_triangles(h, p).map(|_| ())
        }
        Op::SplitVertex(a, b, c) => {
            let v = pick(&verts, a).unwrap();
            let fan: Vec<HalfEdgeId> = m.vertex_outgoing(v).collect();
            match (pick(&fan, b), pick(&fan, c)) {
                (Some(x), Some(y)) => m
                    .split_vertex(v, x, y, m.position(v) + DVec3::splat(0.01))
                    .map(|_| ()),
                _ => Err(EulerError::Degenerate),
            }
        }
        Op::Mvfs(t) => m.make_vertex_face_shell(DVec3::splat(t)).map(|_| ()),
        Op::Kvfs(a) => m
            .kill_vertex_face_shell(pick(&faces, a).unwrap())
            .map(|_| ()),
        Op::MevLone(a, t) => {
            let lone: Vec<VertexId> = verts
                .iter()
                .copied()
                .filter(|&v| m.lone_vertex_loop(v).is_some())
                .collect();
            match pick(&lone, a) {
                Some(v) => m
                    .make_edge_vertex_lone(v, m.position(v) + DVec3::splat(t))
                    .map(|_| ()),
                None => Err(EulerError::Degenerate),
            }
        }
        Op::Kemr(a) => {
            // Mostly edges with the same face on both sides (dangling edges,
            // wires), where KEMR may apply.
            let same: Vec<HalfEdgeId> = inner
                .iter()
                .copied()
                .filter(|&h| m.face(h) == m.face(h.twin()))
                .collect();
            let h = pick(&same, a).or_else(|| pick(&inner, a));
            match h {
                Some(h) => m.kill_edge_make_ring(h).map(|_| ()),
                None => Err(EulerError::Degenerate),
            }
        }
        Op::Mekr(a, b, c, d) => {
            let ringed: Vec<FaceId> = faces
                .iter()
                .copied()
                .filter(|&f| !m.face_rings(f).is_empty())
                .collect();
            let Some(f) = pick(&ringed, a) else {
                return Err(EulerError::Degenerate);
            };
            let loops: Vec<LoopStart> = m.face_loops(f).collect();
            let corner = |l: LoopStart, i: usize| match l {
                LoopStart::HalfEdge(h) => {
                    let hs: Vec<HalfEdgeId> = m.loop_from(h).collect();
                    LoopStart::HalfEdge(hs[i % hs.len()])
                }
                v => v,
            };
            let (la, lb) = (loops[b % loops.len()], loops[1 + c % (loops.len() - 1)]);
            m.make_edge_kill_ring(corner(la, d), corner(lb, d / 7))
                .map(|_| ())
        }
        Op::Kfmrh(a, b) => {
            let (keep, kill) = (pick(&faces, a).unwrap(), pick(&faces, b).unwrap());
            m.kill_face_make_ring_hole(keep, kill).map(|_| ())
        }
        Op::Mfkrh(a, b) => {
            let rings: Vec<LoopStart> = faces
                .iter()
                .flat_map(|&f| m.face_rings(f).to_vec())
                .collect();
            match pick(&rings, a) {
                Some(LoopStart::HalfEdge(h)) => {
                    let hs: Vec<HalfEdgeId> = m.loop_from(h).collect();
                    m.make_face_kill_ring_hole(LoopStart::HalfEdge(hs[b % hs.len()]))
                        .map(|_| ())
                }
                Some(v) => m.make_face_kill_ring_hole(v).map(|_| ()),
                None => Err(EulerError::Degenerate),
            }
        }
        Op::MefRing(a, b, c) => {
            let rings: Vec<LoopStart> = faces
                .iter()
                .flat_map(|&f| m.face_rings(f).to_vec())
                .collect();
            match pick(&rings, a) {
                Some(LoopStart::HalfEdge(h)) => {
                    let hs: Vec<HalfEdgeId> = m.loop_from(h).collect();
                    m.make_edge_face(hs[b % hs.len()], hs[c % hs.len()])
                        .map(|_| ())
                }
                _ => Err(EulerError::Degenerate),
            }
        }
        Op::Fill(a) => {
            let boundary: Vec<HalfEdgeId> =
                m.halfedges().filter(|&h| m.face(h).is_none()).collect();
            match pick(&boundary, a) {
                Some(h) => m.fill_hole(h).map(|_| ()),
                None => Err(EulerError::Degenerate),
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    #[test]
    fn random_operator_sequences_keep_the_mesh_valid(start in 0usize..6, ops in prop::collection::vec(arb_op(), 1..40)) {
        let mut m = meshes().get(start).cloned().unwrap_or_default();
        let s0 = m.stats();
        // S and H are tracked from each operator's documented change; S is
        // also counted from the connectivity after every step.
        let (mut shells, mut genus) = (s0.shells, s0.genus.unwrap());
        for op in &ops {
            let before = m.clone();
            // A copy with records of its own, to check that the operator
            // changed `m` alone and not the connectivity `before` shares.
            let separate = HalfEdgeMesh::try_from(MeshData::from(before.clone())).unwrap();
            let same_shell = match *op {
                Op::Kfmrh(a, b) if before.faces().next().is_some() => {
                    let faces: Vec<FaceId> = before.faces().collect();
                    let (comp, _) = before.components();
                    let at = |f: FaceId| comp[before.outer_loop(f).vertex(&before).index()];
                    at(pick(&faces, a).unwrap()) == at(pick(&faces, b).unwrap())
                }
                _ => false,
            };
            match apply(&mut m, op) {
                Ok(()) => {
                    let v = m.validate();
                    prop_assert!(v.is_ok(), "{:?} broke the mesh: {}", op, v.unwrap_err());
                    let counted = m.shell_count();
                    match op {
                        Op::Mvfs(_) => shells += 1,
                        Op::Kvfs(_) => shells -= 1,
                        Op::Kfmrh(..) if same_shell => genus += 1,
                        Op::Kfmrh(..) => shells -= 1,
                        // The ring was all that held a shell to its face, or a handle closes.
                        Op::Mfkrh(..) if counted == shells + 1 => shells += 1,
                        Op::Mfkrh(..) => genus -= 1,
                        _ => {}
                    }
                    prop_assert_eq!(counted, shells, "{:?} changed the shells", op);
                }
                Err(_) => prop_assert_eq!(&m, &before, "a refused {:?} changed the mesh", op),
            }
            prop_assert_eq!(&before, &separate, "{:?} changed a copy of the mesh", op);
            let b = m.boundary_loops().len();
            prop_assert!(euler_poincare_holds(&m, shells, genus, b), "{:?}: V - E + F - (L - F) != 2(S - H)", op);
            let s = m.stats();
            prop_assert_eq!(s.rings, m.ring_count());
            if genus >= 0 {
                prop_assert_eq!(s.genus, Some(genus));
            }
        }
    }
}

/// Copies share their connectivity until one of them changes it: moving
/// vertices keeps it shared, an operator gives the changed copy its own.
#[test]
fn copies_share_connectivity_until_one_changes_it() {
    let original = cube();
    let mut moved = original.clone();
    let v = moved.vertices().next().unwrap();
    moved.set_position(v, DVec3::new(5.0, 5.0, 5.0));
    assert!(moved.same_connectivity(&original));
    assert_ne!(moved, original);
    let mut split = moved.clone();
    let e = split.edges().next().unwrap();
    split.split_edge(e, DVec3::ZERO).unwrap();
    split.validate().unwrap();
    assert!(!split.same_connectivity(&moved));
    assert_eq!((moved.vertex_count(), moved.edge_count()), (8, 12));
    assert_eq!((split.vertex_count(), split.edge_count()), (9, 13));
    // A copy built separately compares by its records, not by sharing.
    let rebuilt = HalfEdgeMesh::try_from(MeshData::from(moved.clone())).unwrap();
    assert!(rebuilt.same_connectivity(&original));
    assert_eq!(rebuilt, moved);
    original.validate().unwrap();
}

#[test]
fn split_vertex_then_collapse_restores_the_mesh() {
    let m0 = Primitive::Grid {
        x_segments: 3,
        z_segments: 3,
        size: 3.0,
    }
    .build()
    .unwrap();
    // An interior vertex of valence 4.
    let v = m0.vertices().find(|&v| !m0.is_boundary_vertex(v)).unwrap();
    let fan: Vec<HalfEdgeId> = m0.vertex_outgoing(v).collect();
    let mut m = m0.clone();
    let p0 = m.position(v);
    let e = m
        .split_vertex(v, fan[0], fan[1], p0 + DVec3::new(0.1, 0.0, 0.1))
        .unwrap();
    m.validate().unwrap();
    assert_eq!(
        (m.vertex_count(), m.edge_count(), m.face_count()),
        (m0.vertex_count() + 1, m0.edge_count() + 1, m0.face_count())
    );
    let h = if m.origin(e.halfedge(0)) == v {
        e.halfedge(0)
    } else {
        e.halfedge(1)
    };
    let rec = m.collapse_edge(h, p0).unwrap();
    m.validate().unwrap();
    assert!(m.same_as(&m0), "collapse undoes the split");
    assert_eq!(rec.kept, v);
}

#[test]
fn collapse_then_split_restores_the_shape() {
    let m0 = Primitive::Grid {
        x_segments: 3,
        z_segments: 3,
        size: 3.0,
    }
    .build()
    .unwrap();
    let e = m0
        .edges()
        .find(|&e| {
            m0.edge_vertices(e)
                .iter()
                .all(|&v| !m0.is_boundary_vertex(v))
        })
        .unwrap();
    let mut m = m0.clone();
    let h = e.halfedge(0);
    let mid = m.edge_midpoint(e);
    let rec = m.collapse_edge(h, mid).unwrap();
    m.validate().unwrap();
    assert_eq!(
        (m.vertex_count(), m.edge_count(), m.face_count()),
        (15, 23, 9)
    );
    assert_eq!(
        m.faces().filter(|&f| m.face_degree(f) == 3).count(),
        2,
        "the two quads beside the edge became triangles"
    );
    m.split_vertex(rec.kept, rec.first, rec.last, rec.removed_position)
        .unwrap();
    m.set_position(rec.kept, rec.kept_position);
    m.validate().unwrap();
    let shape = |m: &HalfEdgeMesh| {
        let mut polys: Vec<Vec<(i64, i64)>> = m
            .faces()
            .map(|f| {
                let mut p: Vec<(i64, i64)> = m
                    .face_vertices(f)
                    .map(|v| {
                        (
                            (m.position(v).x * 1e6).round() as i64,
                            (m.position(v).z * 1e6).round() as i64,
                        )
                    })
                    .collect();
                let k = p.iter().enumerate().min_by_key(|(_, x)| **x).unwrap().0;
                p.rotate_left(k);
                p
            })
            .collect();
        polys.sort();
        polys
    };
    assert_eq!(shape(&m), shape(&m0), "the same polygons again (new ids)");
    // Triangles beside an edge refuse; so does a pinch between two boundaries.
    let mut ico = Primitive::IcoSphere {
        subdivisions: 0,
        radius: 1.0,
    }
    .build()
    .unwrap();
    assert_eq!(
        ico.collapse_edge(EdgeId(0).halfedge(0), DVec3::ZERO),
        Err(EulerError::Degenerate)
    );
}

#[test]
fn collapse_removing_triangles_on_triangle_meshes() {
    let mut m = Primitive::IcoSphere {
        subdivisions: 1,
        radius: 1.0,
    }
    .build()
    .unwrap();
    let (v, e, f) = (m.vertex_count(), m.edge_count(), m.face_count());
    let h = m.halfedges().next().unwrap();
    let mid = m.edge_midpoint(h.edge());
    let kept = m.collapse_edge_removing_triangles(h, mid).unwrap();
    m.validate().unwrap();
    assert_eq!(
        (m.vertex_count(), m.edge_count(), m.face_count()),
        (v - 1, e - 3, f - 2)
    );
    assert_eq!(m.position(kept), mid);
    assert!(m.stats().closed);
    // Collapsing down to a tetrahedron is as far as it goes.
    let mut steps = 0;
    loop {
        let Some(h) = m.halfedges().find(|&h| {
            m.clone()
                .collapse_edge_removing_triangles(h, DVec3::ZERO)
                .is_ok()
        }) else {
            break;
        };
        let p = m.edge_midpoint(h.edge());
        m.collapse_edge_removing_triangles(h, p).unwrap();
        m.validate().unwrap();
        steps += 1;
        assert!(steps < 100);
    }
    assert_eq!(
        (m.vertex_count(), m.face_count()),
        (4, 4),
        "a tetrahedron is left"
    );
}
