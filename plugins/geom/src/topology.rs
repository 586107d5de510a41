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
