//! The tables of seed 000 (Bán): the half-edge record (vertex, sym, face,
//! next) and the winged-edge row of an edge (start, end, left and right
//! face, predecessor and successor on each side), plus the neighbour queries
//! the notes teach. Used by `hedra info --topology` and the inspector panel.

use crate::ids::{EdgeId, FaceId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;
use std::fmt::Write;

/// One half-edge's links.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HalfEdgeRecord {
    /// The half-edge described.
    pub halfedge: HalfEdgeId,
    /// The vertex it starts at.
    pub origin: VertexId,
    /// The opposite half-edge of its edge.
    pub twin: HalfEdgeId,
    /// The following half-edge of its loop.
    pub next: HalfEdgeId,
    /// The preceding half-edge of its loop.
    pub prev: HalfEdgeId,
    /// The face on its left; `None` on a boundary.
    pub face: Option<FaceId>,
}

/// One edge's winged-edge row. The edge runs from `start` to `end` along its
/// half-edge 0; faces are counter-clockwise, so the left face is that
/// half-edge's face. "Predecessor" and "successor" are the edges before and
/// after it in the loop of each face.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WingedEdgeRow {
    /// The edge described.
    pub edge: EdgeId,
    /// Origin of its half-edge 0.
    pub start: VertexId,
    /// Target of its half-edge 0.
    pub end: VertexId,
    /// Face of half-edge 0; `None` on a boundary.
    pub left_face: Option<FaceId>,
    /// Face of half-edge 1; `None` on a boundary.
    pub right_face: Option<FaceId>,
    /// Edge before it in the left loop.
    pub left_predecessor: EdgeId,
    /// Edge after it in the left loop.
    pub left_successor: EdgeId,
    /// Edge before it in the right loop.
    pub right_predecessor: EdgeId,
    /// Edge after it in the right loop.
    pub right_successor: EdgeId,
}

/// The record of live half-edge `h`.
pub fn halfedge_record(m: &HalfEdgeMesh, h: HalfEdgeId) -> HalfEdgeRecord {
    HalfEdgeRecord {
        halfedge: h,
        origin: m.origin(h),
        twin: h.twin(),
        next: m.next(h),
        prev: m.prev(h),
        face: m.face(h),
    }
}

/// The winged-edge row of live edge `e`.
pub fn winged_edge_row(m: &HalfEdgeMesh, e: EdgeId) -> WingedEdgeRow {
    let (l, r) = (e.halfedge(0), e.halfedge(1));
    WingedEdgeRow {
        edge: e,
        start: m.origin(l),
        end: m.target(l),
        left_face: m.face(l),
        right_face: m.face(r),
        left_predecessor: m.prev(l).edge(),
        left_successor: m.next(l).edge(),
        right_predecessor: m.prev(r).edge(),
        right_successor: m.next(r).edge(),
    }
}

fn face_name(f: Option<FaceId>) -> String {
    f.map_or_else(|| "-".to_string(), |f| f.to_string())
}

fn list<T: std::fmt::Display>(items: impl Iterator<Item = T>) -> String {
    items.map(|x| x.to_string()).collect::<Vec<_>>().join(" ")
}

/// All the tables of a mesh as text: vertices (position, outgoing
/// half-edge, faces around), faces (half-edge, vertices, neighbours),
/// half-edges, and the winged-edge table.
pub fn tables(m: &HalfEdgeMesh) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "vertices: vertex | position | half-edge | faces around | neighbours"
    );
    for v in m.vertices() {
        let p = m.position(v);
        let _ = writeln!(
            out,
            "  {v} | ({:.4}, {:.4}, {:.4}) | {} | {} | {}",
            p.x,
            p.y,
            p.z,
            m.vertex_halfedge(v).map_or("-".into(), |h| h.to_string()),
            list(m.vertex_faces(v)),
            list(m.vertex_neighbors(v))
        );
    }
    let _ = writeln!(out, "faces: face | half-edge | vertices | neighbours");
    for f in m.faces() {
        let rings = m.face_rings(f);
        let _ = writeln!(
            out,
            "  {f} | {} | {} | {}{}",
            m.outer_loop(f),
            list(m.face_vertices(f)),
            list(m.face_neighbors(f)),
            if rings.is_empty() {
                String::new()
            } else {
                format!(" | rings {}", list(rings.iter()))
            }
        );
    }
    let _ = writeln!(
        out,
        "half-edges: half-edge | vertex | twin | next | prev | face"
    );
    for h in m.halfedges() {
        let r = halfedge_record(m, h);
        let _ = writeln!(
            out,
            "  {} | {} | {} | {} | {} | {}",
            r.halfedge,
            r.origin,
            r.twin,
            r.next,
            r.prev,
            face_name(r.face)
        );
    }
    let _ = writeln!(
        out,
        "winged edges: edge | start | end | left face | right face | left pred | left succ | right pred | right succ"
    );
    for e in m.edges() {
        let w = winged_edge_row(m, e);
        let _ = writeln!(
            out,
            "  {} | {} | {} | {} | {} | {} | {} | {} | {}",
            w.edge,
            w.start,
            w.end,
            face_name(w.left_face),
            face_name(w.right_face),
            w.left_predecessor,
            w.left_successor,
            w.right_predecessor,
            w.right_successor
        );
    }
    out
}

/// The edge loop through `edge`: continues straight across vertices of
/// valence 4 (the edge opposite in the fan) and stops at poles, boundaries
/// or when it closes. Blender's Alt+click.
pub fn edge_loop(m: &HalfEdgeMesh, edge: EdgeId) -> Vec<EdgeId> {
    let mut out = vec![edge];
    for start in [edge.halfedge(0), edge.halfedge(1)] {
        let mut h = start;
        loop {
            let v = m.target(h);
            if m.vertex_valence(v) != 4 || m.is_boundary_vertex(v) {
                break;
            }
            // Rotate twice around v from the way back: the opposite edge.
            let back = h.twin();
            let once = m.prev(back).twin();
            let opposite = m.prev(once).twin();
            let e = opposite.edge();
            if e == edge || out.contains(&e) {
                return out; // closed loop
            }
            out.push(e);
            h = opposite;
        }
    }
    out
}

/// Vertices reachable from `seeds` over edges (Blender's select linked).
pub fn linked_vertices(
    m: &HalfEdgeMesh,
    seeds: impl IntoIterator<Item = VertexId>,
) -> Vec<VertexId> {
    let mut seen = vec![false; m.vertex_capacity()];
    let mut stack: Vec<VertexId> = seeds.into_iter().filter(|v| m.is_vertex(*v)).collect();
    let mut out = Vec::new();
    while let Some(v) = stack.pop() {
        if std::mem::replace(&mut seen[v.index()], true) {
            continue;
        }
        out.push(v);
        stack.extend(m.vertex_neighbors(v).filter(|w| !seen[w.index()]));
    }
    out.sort();
    out
}

/// The topological counts of a mesh that the Euler operators change, as a
/// topology inspector shows them: V, E, F, loops L (outer loops plus
/// rings), shells S, holes H (genus) and boundary loops B.
///
/// They satisfy the Euler–Poincaré formula V − E + F − (L − F) = 2(S − H)
/// with each boundary loop counted as a face of one loop (Mäntylä, "An
/// Introduction to Solid Modeling", ch. 4), so H is computed from the
/// others: H = S − (V − E + F + B − (L − F)) / 2. See
/// [`euler_poincare_holds`](Self::euler_poincare_holds).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct TopologyCounts {
    /// Live vertices V.
    pub vertices: i64,
    /// Live edges E.
    pub edges: i64,
    /// Live faces F.
    pub faces: i64,
    /// Face loops L: one outer loop per face plus the inner rings.
    pub loops: i64,
    /// Shells S (connected components, the loops of a face in one shell).
    pub shells: i64,
    /// Holes H (handles, genus), from the formula; rounded down when the
    /// formula's left side is odd (an invalid mesh).
    pub holes: i64,
    /// Boundary loops B (holes in the surface, counted as faces).
    pub boundary_loops: i64,
}

impl TopologyCounts {
    /// The counts of `mesh`. Boundary loops are walked without validating;
    /// on an invalid mesh the numbers describe its records as they are.
    ///
    /// Complexity: O(V + E + F).
    pub fn of(mesh: &HalfEdgeMesh) -> Self {
        let vertices = mesh.vertex_count() as i64;
        let edges = mesh.edge_count() as i64;
        let faces = mesh.face_count() as i64;
        let loops = mesh.loop_count() as i64;
        let shells = mesh.shell_count() as i64;
        let boundary_loops = mesh.boundary_loops().len() as i64;
        let chi = vertices - edges + faces + boundary_loops - (loops - faces);
        TopologyCounts {
            vertices,
            edges,
            faces,
            loops,
            shells,
            holes: shells - chi.div_euclid(2),
            boundary_loops,
        }
    }

    /// V − E + F + B − (L − F) = 2(S − H) holds exactly (the left side is
    /// even); false points at broken records.
    pub fn euler_poincare_holds(&self) -> bool {
        let chi = self.vertices - self.edges + self.faces + self.boundary_loops
            - (self.loops - self.faces);
        chi == 2 * (self.shells - self.holes)
    }

    /// The change from `before` to `self`.
    pub fn since(&self, before: &TopologyCounts) -> TopologyDelta {
        TopologyDelta {
            vertices: self.vertices - before.vertices,
            edges: self.edges - before.edges,
            faces: self.faces - before.faces,
            loops: self.loops - before.loops,
            shells: self.shells - before.shells,
            holes: self.holes - before.holes,
            boundary_loops: self.boundary_loops - before.boundary_loops,
        }
    }
}

impl std::fmt::Display for TopologyCounts {
    /// `V 8, E 12, F 6, L 6, S 1, H 0, B 0`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "V {}, E {}, F {}, L {}, S {}, H {}, B {}",
            self.vertices,
            self.edges,
            self.faces,
            self.loops,
            self.shells,
            self.holes,
            self.boundary_loops
        )
    }
}

/// The difference of two [`TopologyCounts`] (after − before), what a
/// command did to the topology: MEV is `V +1, E +1`, KEMR `E -1, L +1`.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct TopologyDelta {
    /// Change of V.
    pub vertices: i64,
    /// Change of E.
    pub edges: i64,
    /// Change of F.
    pub faces: i64,
    /// Change of L.
    pub loops: i64,
    /// Change of S.
    pub shells: i64,
    /// Change of H.
    pub holes: i64,
    /// Change of B.
    pub boundary_loops: i64,
}

impl TopologyDelta {
    /// True when nothing changed.
    pub fn is_zero(&self) -> bool {
        *self == TopologyDelta::default()
    }
}

impl std::fmt::Display for TopologyDelta {
    /// The counts that changed, signed, in the order V, E, F, L, S, H, B
    /// (`V +1, E +1`); `no change` when none did.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let parts: Vec<String> = [
            ("V", self.vertices),
            ("E", self.edges),
            ("F", self.faces),
            ("L", self.loops),
            ("S", self.shells),
            ("H", self.holes),
            ("B", self.boundary_loops),
        ]
        .into_iter()
        .filter(|(_, d)| *d != 0)
        .map(|(name, d)| format!("{name} {d:+}"))
        .collect();
        if parts.is_empty() {
            write!(f, "no change")
        } else {
            write!(f, "{}", parts.join(", "))
        }
    }
}
