//! The one validator of half-edge invariants (geometry-central's
//! `validateConnectivity`): called after every operator in the tests, and on
//! every mesh read from a file. It never panics, even on corrupted records.

use crate::ids::{ElementId, FaceId, HalfEdgeId, NONE, VertexId};
use crate::mesh::{HalfEdgeMesh, LoopStart};
use std::fmt;

/// One broken invariant, naming the elements involved.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Violation {
    /// A record refers to an id outside its array or to a dead element.
    DanglingReference {
        /// The record that holds the reference.
        element: ElementId,
        /// Which of its fields: `"half-edge"`, `"origin"`, `"next"`,
        /// `"prev"`, `"face"`, `"ring half-edge"`.
        field: &'static str,
        /// The raw id it holds.
        value: u32,
    },
    /// `next(prev(h)) != h` or `prev(next(h)) != h`.
    BrokenLink {
        /// The half-edge whose links disagree.
        halfedge: HalfEdgeId,
    },
    /// `origin(next(h)) != target(h)`.
    DisconnectedLoop {
        /// The half-edge whose successor starts elsewhere.
        halfedge: HalfEdgeId,
    },
    /// Consecutive half-edges of a loop disagree on their face.
    FaceMismatch {
        /// The half-edge whose successor names another face.
        halfedge: HalfEdgeId,
    },
    /// An edge from a vertex to itself.
    SelfLoop {
        /// One half-edge of the edge.
        halfedge: HalfEdgeId,
    },
    /// A face's loop does not come back to its start, or has fewer than 3 sides.
    BadFaceLoop {
        /// The face.
        face: FaceId,
        /// Half-edges walked before giving up or closing.
        len: usize,
    },
    /// A face's half-edge count differs from the half-edges that name it.
    StrayFaceHalfEdge {
        /// The face.
        face: FaceId,
    },
    /// A loop's lone vertex is dead, has edges, is used by another loop, or
    /// the face's outer half-edge and lone vertex disagree.
    BadLoneVertex {
        /// The face whose loop it is.
        face: FaceId,
        /// The lone vertex.
        vertex: VertexId,
    },
    /// A ring of a face starts on the outer loop or on another ring.
    RingOverlap {
        /// The face.
        face: FaceId,
        /// The ring's start half-edge.
        halfedge: HalfEdgeId,
    },
    /// A ring list for a dead face, or an empty one.
    BadRingTable {
        /// The face the list is stored for.
        face: FaceId,
    },
    /// `origin(vertex_halfedge(v)) != v`.
    WrongVertexHalfEdge {
        /// The vertex.
        vertex: VertexId,
    },
    /// The fan around a vertex misses some of its outgoing half-edges.
    NonManifoldVertex {
        /// The vertex.
        vertex: VertexId,
        /// Outgoing half-edges reached by walking its fan.
        fan: usize,
        /// Outgoing half-edges it has in all.
        outgoing: usize,
    },
    /// A boundary vertex whose stored half-edge is not a boundary one.
    BoundaryNotFirst {
        /// The vertex.
        vertex: VertexId,
    },
    /// A non-finite coordinate.
    NonFinitePosition {
        /// The vertex.
        vertex: VertexId,
    },
    /// Cached live counts disagree with the flags.
    WrongCount {
        /// Which count: `"vertex record"` or `"edge record"` (array
        /// lengths that disagree), or `"vertex"`, `"edge"`, `"face"` (live
        /// counts).
        what: &'static str,
        /// The stored count.
        cached: usize,
        /// The count found.
        actual: usize,
    },
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Violation::DanglingReference {
                element,
                field,
                value,
            } => {
                write!(
                    f,
                    "{}: {field} refers to missing element {value}",
                    element.short()
                )
            }
            Violation::BrokenLink { halfedge } => write!(f, "{halfedge}: next/prev links disagree"),
            Violation::DisconnectedLoop { halfedge } => {
                write!(f, "{halfedge}: next half-edge does not start at its target")
            }
            Violation::FaceMismatch { halfedge } => {
                write!(f, "{halfedge}: next half-edge lies on another face")
            }
            Violation::SelfLoop { halfedge } => {
                write!(f, "{halfedge}: edge joins a vertex to itself")
            }
            Violation::BadFaceLoop { face, len } => {
                write!(
                    f,
                    "{face}: loop is not a closed polygon ({len} half-edges walked)"
                )
            }
            Violation::StrayFaceHalfEdge { face } => {
                write!(f, "{face}: half-edges name this face outside its loops")
            }
            Violation::BadLoneVertex { face, vertex } => write!(
                f,
                "{face}: lone vertex {vertex} of a loop is dead, has edges or is used twice"
            ),
            Violation::RingOverlap { face, halfedge } => {
                write!(
                    f,
                    "{face}: ring at {halfedge} lies on another loop of the face"
                )
            }
            Violation::BadRingTable { face } => {
                write!(f, "{face}: ring list of a dead face, or an empty one")
            }
            Violation::WrongVertexHalfEdge { vertex } => {
                write!(f, "{vertex}: its half-edge does not start at it")
            }
            Violation::NonManifoldVertex {
                vertex,
                fan,
                outgoing,
            } => write!(
                f,
                "{vertex}: non-manifold, its fan reaches {fan} of {outgoing} outgoing half-edges"
            ),
            Violation::BoundaryNotFirst { vertex } => {
                write!(f, "{vertex}: on a boundary but its half-edge is interior")
            }
            Violation::NonFinitePosition { vertex } => {
                write!(f, "{vertex}: position is not finite")
            }
            Violation::WrongCount {
                what,
                cached,
                actual,
            } => {
                write!(f, "{what} count is {cached} but {actual} are live")
            }
        }
    }
}

/// The result of a failed [`HalfEdgeMesh::validate`]: every violation found
/// (at most [`ValidationError::LIMIT`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub struct ValidationError {
    /// The violations, in the order found (never empty).
    pub violations: Vec<Violation>,
}

impl ValidationError {
    /// At most this many violations are collected.
    pub const LIMIT: usize = 20;
}

impl fmt::Display for ValidationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid mesh: ")?;
        for (i, v) in self.violations.iter().enumerate() {
            if i > 0 {
                write!(f, "; ")?;
            }
            write!(f, "{v}")?;
        }
        Ok(())
    }
}

impl HalfEdgeMesh {
    /// Checks every connectivity invariant: references in range and live,
    /// twin/next/prev consistency, closed face loops of at least three sides
    /// (or two: the single edge of a wire in a face made by MVFS), every
    /// half-edge of a face on its outer loop or exactly one of its rings,
    /// lone-vertex loops on live vertices without edges,
    /// manifold vertex fans with the boundary half-edge first, finite positions
    /// and the cached counts.
    ///
    /// # Errors
    /// [`ValidationError`] listing the violations found.
    ///
    /// Complexity: O(V + E + F).
    pub fn validate(&self) -> Result<(), ValidationError> {
        let mut out = Vec::new();
        self.check_records(&mut out);
        if out.is_empty() {
            self.check_loops_and_fans(&mut out);
        }
        if out.is_empty() {
            Ok(())
        } else {
            out.truncate(ValidationError::LIMIT);
            Err(ValidationError { violations: out })
        }
    }

    /// Pass 1: array sizes, id ranges and liveness, so pass 2 can index freely.
    fn check_records(&self, out: &mut Vec<Violation>) {
        let nv = self.positions.len();
        let nh = self.topology.halfedges.len();
        let nf = self.topology.face_halfedge.len();
        if self.topology.vertex_out.len() != nv || self.topology.vertex_dead.len() != nv {
            out.push(Violation::WrongCount {
                what: "vertex record",
                cached: self.topology.vertex_out.len(),
                actual: nv,
            });
            return;
        }
        if self.topology.edge_dead.len() * 2 != nh || self.topology.face_dead.len() != nf {
            out.push(Violation::WrongCount {
                what: "edge record",
                cached: self.topology.edge_dead.len() * 2,
                actual: nh,
            });
            return;
        }
        let live_v = self.topology.vertex_dead.iter().filter(|d| !**d).count();
        let live_e = self.topology.edge_dead.iter().filter(|d| !**d).count();
        let live_f = self.topology.face_dead.iter().filter(|d| !**d).count();
        for (what, cached, actual) in [
            ("vertex", self.topology.live_vertices, live_v),
            ("edge", self.topology.live_edges, live_e),
            ("face", self.topology.live_faces, live_f),
        ] {
            if cached != actual {
                out.push(Violation::WrongCount {
                    what,
                    cached,
                    actual,
                });
            }
        }
        let live_vertex = |x: u32| (x as usize) < nv && !self.topology.vertex_dead[x as usize];
        let live_he = |x: u32| (x as usize) < nh && !self.topology.edge_dead[x as usize / 2];
        let live_face = |x: u32| (x as usize) < nf && !self.topology.face_dead[x as usize];
        let push = |out: &mut Vec<Violation>, element: ElementId, field, value| {
            if out.len() < ValidationError::LIMIT {
                out.push(Violation::DanglingReference {
                    element,
                    field,
                    value,
                });
            }
        };
        for v in self.vertices() {
            let h = self.topology.vertex_out[v.index()];
            if h != NONE && !live_he(h) {
                push(out, v.into(), "half-edge", h);
            }
            if !self.positions[v.index()].is_finite() {
                out.push(Violation::NonFinitePosition { vertex: v });
            }
        }
        for h in self.halfedges() {
            let r = &self.topology.halfedges[h.index()];
            if !live_vertex(r.origin) {
                push(out, h.into(), "origin", r.origin);
            }
            if !live_he(r.next) {
                push(out, h.into(), "next", r.next);
            }
            if !live_he(r.prev) {
                push(out, h.into(), "prev", r.prev);
            }
            if r.face != NONE && !live_face(r.face) {
                push(out, h.into(), "face", r.face);
            }
        }
        for f in self.faces() {
            let h = self.topology.face_halfedge[f.index()];
            let lone = self.topology.face_lone_vertex.get(&f);
            if let Some(&v) = lone.filter(|_| h != NONE) {
                out.push(Violation::BadLoneVertex { face: f, vertex: v });
            } else if lone.is_none() && !live_he(h) {
                push(out, f.into(), "half-edge", h);
            }
        }
        // Rings and lone vertices (side tables, empty for ordinary meshes).
        let mut lone_seen = std::collections::BTreeSet::new();
        let mut check_lone = |out: &mut Vec<Violation>, f: FaceId, v: VertexId| {
            if !live_vertex(v.0)
                || self.topology.vertex_out[v.index()] != NONE
                || !lone_seen.insert(v)
            {
                out.push(Violation::BadLoneVertex { face: f, vertex: v });
            }
        };
        for (&f, &v) in &self.topology.face_lone_vertex {
            if !live_face(f.0) {
                out.push(Violation::BadRingTable { face: f });
            } else {
                check_lone(out, f, v);
            }
        }
        for (&f, rings) in &self.topology.face_rings {
            if !live_face(f.0) || rings.is_empty() {
                out.push(Violation::BadRingTable { face: f });
                continue;
            }
            for &r in rings {
                match r {
                    LoopStart::HalfEdge(h) if !live_he(h.0) => {
                        push(out, f.into(), "ring half-edge", h.0);
                    }
                    LoopStart::HalfEdge(_) => {}
                    LoopStart::Vertex(v) => check_lone(out, f, v),
                }
            }
        }
    }

    /// Pass 2: links, loops and fans.
    fn check_loops_and_fans(&self, out: &mut Vec<Violation>) {
        let full = |out: &Vec<Violation>| out.len() >= ValidationError::LIMIT;
        for h in self.halfedges() {
            if full(out) {
                return;
            }
            let n = self.next(h);
            let p = self.prev(h);
            if self.prev(n) != h || self.next(p) != h {
                out.push(Violation::BrokenLink { halfedge: h });
            } else if self.origin(n) != self.target(h) {
                out.push(Violation::DisconnectedLoop { halfedge: h });
            } else if self.face(n) != self.face(h) {
                out.push(Violation::FaceMismatch { halfedge: h });
            }
            if self.origin(h) == self.target(h) {
                out.push(Violation::SelfLoop { halfedge: h });
            }
        }
        if !out.is_empty() {
            return;
        }
        // Face loops: closed, at least 3 sides, and own all half-edges naming them.
        let mut named = vec![0usize; self.topology.face_halfedge.len()];
        for h in self.halfedges() {
            if let Some(f) = self.face(h) {
                named[f.index()] += 1;
            }
        }
        // Half-edges already walked, to find rings lying on another loop.
        let mut seen = if self.topology.face_rings.is_empty() {
            Vec::new()
        } else {
            vec![false; self.topology.halfedges.len()]
        };
        'faces: for f in self.faces() {
            if full(out) {
                return;
            }
            let mut total = 0;
            for l in self.face_loops(f) {
                let LoopStart::HalfEdge(start) = l else {
                    continue;
                };
                if seen.get(start.index()) == Some(&true) {
                    out.push(Violation::RingOverlap {
                        face: f,
                        halfedge: start,
                    });
                    continue 'faces;
                }
                let mut len = 0;
                let mut h = start;
                let mut closed = false;
                while len <= self.topology.halfedges.len() {
                    if self.face(h) != Some(f) {
                        break;
                    }
                    if let Some(s) = seen.get_mut(h.index()) {
                        *s = true;
                    }
                    len += 1;
                    h = self.next(h);
                    if h == start {
                        closed = true;
                        break;
                    }
                }
                let wire = len == 2 && self.next(start) == start.twin();
                if !closed || (len < 3 && !wire) {
                    out.push(Violation::BadFaceLoop { face: f, len });
                    continue 'faces;
                }
                total += len;
            }
            if named[f.index()] != total {
                out.push(Violation::StrayFaceHalfEdge { face: f });
            }
        }
        // Vertex fans: the circulation reaches every outgoing half-edge.
        let mut outgoing = vec![0usize; self.positions.len()];
        let mut boundary_out = vec![0usize; self.positions.len()];
        for h in self.halfedges() {
            let o = self.origin(h).index();
            outgoing[o] += 1;
            if self.is_boundary_halfedge(h) {
                boundary_out[o] += 1;
            }
        }
        for v in self.vertices() {
            if full(out) {
                return;
            }
            let Some(start) = self.vertex_halfedge(v) else {
                if outgoing[v.index()] != 0 {
                    out.push(Violation::NonManifoldVertex {
                        vertex: v,
                        fan: 0,
                        outgoing: outgoing[v.index()],
                    });
                }
                continue;
            };
            if self.origin(start) != v {
                out.push(Violation::WrongVertexHalfEdge { vertex: v });
                continue;
            }
            let mut fan = 0;
            let mut h = start;
            loop {
                if self.origin(h) != v {
                    break;
                }
                fan += 1;
                h = self.prev(h).twin();
                if h == start || fan > outgoing[v.index()] {
                    break;
                }
            }
            if fan != outgoing[v.index()] || boundary_out[v.index()] > 1 {
                out.push(Violation::NonManifoldVertex {
                    vertex: v,
                    fan,
                    outgoing: outgoing[v.index()],
                });
            } else if boundary_out[v.index()] == 1 && !self.is_boundary_halfedge(start) {
                out.push(Violation::BoundaryNotFirst { vertex: v });
            }
        }
    }
}
