//! Euler operators: the normal way to change mesh connectivity, and the
//! allocation helpers the other writers inside [`crate::mesh`] share (see
//! that module for the few exceptions and why they exist).
//!
//! Each operator checks its preconditions first and leaves the mesh untouched
//! when one fails (a named [`EulerError`]), states its change of V, E, F, and
//! has a named inverse that restores the mesh (same ids, same links). The
//! names follow the B-rep literature used in seed 004 (Szirmay-Kalos: MEV,
//! MEF, edge split, face extrude with its V/E/F bookkeeping) and CGAL's
//! `Euler_operations.h` inverse pairs.
//!
//! The classical operators of Mäntylä's GWB ("An Introduction to Solid
//! Modeling") that need faces of several loops are here too: MVFS/KVFS,
//! KEMR/MEKR and KFMRH/MFKRH (see [`LoopStart`] for how rings and lone
//! vertices are stored). Each documents its change of V, E, F, rings
//! (L − F), shells S and holes H; all of them keep the Euler–Poincaré
//! formula V − E + F − (L − F) = 2(S − H), with each boundary loop counted
//! as a face of one loop.
//!
//! Elements are allocated at the end of the id space and freed by marking
//! them dead, so an id is never handed out twice (until an explicit
//! compaction): an inverse restores every live element with the same id and
//! links, leaving the freed slots dead at the end.

use crate::ids::{EdgeId, ElementId, FaceId, HalfEdgeId, NONE, VertexId};
use crate::mesh::{HalfEdgeMesh, HalfEdgeRecord, LoopStart};
use glam::DVec3;
use std::collections::BTreeSet;

/// Why an Euler operator refused; the mesh is unchanged.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum EulerError {
    /// An argument names an element that is not live in the mesh.
    #[error("{} does not exist", .0.short())]
    Missing(ElementId),
    /// The half-edge has no face (it lies on a boundary loop).
    #[error("{halfedge} lies on a boundary; the operator needs a face")]
    NoFace {
        /// The boundary half-edge.
        halfedge: HalfEdgeId,
    },
    /// Two half-edges that must share a face loop do not.
    #[error("{a} and {b} are not on the same face loop")]
    NotSameLoop {
        /// The first half-edge given.
        a: HalfEdgeId,
        /// The second half-edge given.
        b: HalfEdgeId,
    },
    /// The result would have a face of fewer than three sides.
    #[error("the new edge would make a face with fewer than 3 sides")]
    Degenerate,
    /// The vertex has the wrong number of edges for the operator.
    #[error("{vertex} has valence {valence}; the operator needs {needed}")]
    Valence {
        /// The vertex.
        vertex: VertexId,
        /// Its number of edges.
        valence: usize,
        /// What the operator needs, as words (`"exactly 2"`).
        needed: &'static str,
    },
    /// The edge has one face on both of its sides.
    #[error("{edge} has the same face on both sides")]
    SameFace {
        /// The edge.
        edge: EdgeId,
    },
    /// The operator needs an edge between two faces, or an interior edge.
    #[error("{edge} is a boundary edge")]
    BoundaryEdge {
        /// The edge.
        edge: EdgeId,
    },
    /// Joining the two faces would not give a simple polygon.
    #[error(
        "faces {a} and {b} share more than one edge; joining them would not give a simple polygon"
    )]
    SharedEdges {
        /// One face beside the edge.
        a: FaceId,
        /// The other face.
        b: FaceId,
    },
    /// Killing an edge and vertex needs an end of valence 1.
    #[error("{edge} is not a dangling edge (no end of valence 1)")]
    NotDangling {
        /// The edge.
        edge: EdgeId,
    },
    /// The new edge would start and end at one vertex.
    #[error("the new edge would join {vertex} to itself")]
    SelfLoop {
        /// The vertex at both ends.
        vertex: VertexId,
    },
    /// A new position has a NaN or infinite coordinate.
    #[error("position is not finite")]
    NonFinite,
    /// An edge collapse whose ends have a common neighbour.
    #[error("{a} and {b} share a neighbour; collapsing their edge would double an edge")]
    SharedNeighbours {
        /// The vertex that is kept.
        a: VertexId,
        /// The vertex that would be merged into it.
        b: VertexId,
    },
    /// The half-edges given do not bound a proper part of the vertex's fan
    /// (also: a new face would not fit into the boundary around the vertex).
    #[error("the half-edges do not delimit a part of {vertex}'s fan")]
    NotInFan {
        /// The vertex.
        vertex: VertexId,
    },
    /// The operator needs a face with one loop of edges.
    #[error("{face} has inner rings or no edges; the operator needs a plain polygon")]
    HasRings {
        /// The face.
        face: FaceId,
    },
    /// The vertex is not the lone vertex of a face loop (see [`LoopStart`]).
    #[error("{vertex} is not the lone vertex of a loop")]
    NotLoneVertex {
        /// The vertex.
        vertex: VertexId,
    },
    /// KVFS on a face that is more than one vertex and one face.
    #[error(
        "{face} is not a shell of one vertex and one face (KVFS needs a face whose only loop is a lone vertex)"
    )]
    NotVertexFaceShell {
        /// The face.
        face: FaceId,
    },
    /// Two corners that must share a face do not.
    #[error("the corners lie on different faces ({a} and {b})")]
    DifferentFaces {
        /// The first corner's face.
        a: FaceId,
        /// The second corner's face.
        b: FaceId,
    },
    /// MEKR on two corners of one loop, which MEF joins instead.
    #[error("the corners lie on the same loop of {face}; join them with make_edge_face")]
    SameLoop {
        /// The face.
        face: FaceId,
    },
    /// The loop given as a ring is the face's outer loop.
    #[error("the loop is the outer loop of {face}, not one of its rings")]
    NotARing {
        /// The face.
        face: FaceId,
    },
    /// KFMRH asked to make a face a ring of itself.
    #[error("{face} cannot become a ring of itself")]
    FaceWithItself {
        /// The face.
        face: FaceId,
    },
    /// KFMRH on faces that share a vertex.
    #[error("faces {a} and {b} share {vertex}; a ring must not touch the face's other loops")]
    FacesTouch {
        /// The face that keeps its loops.
        a: FaceId,
        /// The face that would become its ring.
        b: FaceId,
        /// A vertex on both.
        vertex: VertexId,
    },
}

/// Which loop of its face something lies on.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Role {
    Outer,
    Ring(usize),
}

/// What [`HalfEdgeMesh::collapse_edge`] needs to be undone by
/// [`HalfEdgeMesh::split_vertex`]: the kept vertex, the range of its fan
/// that belonged to the removed vertex, and both old positions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Collapse {
    /// The vertex that stays (the origin of the collapsed half-edge).
    pub kept: VertexId,
    /// First outgoing half-edge of `kept` that came from the removed vertex.
    pub first: HalfEdgeId,
    /// Last such half-edge, in fan order.
    pub last: HalfEdgeId,
    /// Where `kept` was before the collapse.
    pub kept_position: DVec3,
    /// Where the removed vertex was.
    pub removed_position: DVec3,
}

impl HalfEdgeMesh {
    // ----- allocation -------------------------------------------------------

    pub(super) fn alloc_vertex(&mut self, p: DVec3) -> VertexId {
        self.positions.push(p);
        self.vertex_out.push(NONE);
        self.vertex_dead.push(false);
        self.live_vertices += 1;
        VertexId(self.positions.len() as u32 - 1)
    }

    pub(super) fn alloc_edge(&mut self, a: VertexId, b: VertexId) -> HalfEdgeId {
        let h = self.halfedges.len() as u32;
        self.halfedges.push(HalfEdgeRecord {
            origin: a.0,
            next: NONE,
            prev: NONE,
            face: NONE,
        });
        self.halfedges.push(HalfEdgeRecord {
            origin: b.0,
            next: NONE,
            prev: NONE,
            face: NONE,
        });
        self.edge_dead.push(false);
        self.live_edges += 1;
        HalfEdgeId(h)
    }

    pub(super) fn alloc_face(&mut self, h: HalfEdgeId) -> FaceId {
        self.face_halfedge.push(h.0);
        self.face_dead.push(false);
        self.live_faces += 1;
        FaceId(self.face_halfedge.len() as u32 - 1)
    }

    /// Marks a vertex dead; its id is never handed out again.
    ///
    /// The one raw writer open to the whole crate: the modeling operations
    /// that take faces out and add them back (weld, vertex and edge bevel,
    /// a full-turn spin of a region with inner vertices)
    /// drop the old, now isolated, vertices with it and validate the result
    /// before it replaces the mesh. A vertex that still has edges leaves
    /// dangling records, which that validation reports.
    pub(crate) fn free_vertex(&mut self, v: VertexId) {
        self.live_vertices -= 1;
        self.vertex_dead[v.index()] = true;
        self.vertex_out[v.index()] = NONE;
    }

    /// Marks an edge dead; its ids are never handed out again.
    pub(super) fn free_edge(&mut self, e: EdgeId) {
        self.live_edges -= 1;
        self.edge_dead[e.index()] = true;
    }

    /// Marks a face dead; its id is never handed out again.
    pub(super) fn free_face(&mut self, f: FaceId) {
        self.live_faces -= 1;
        self.face_dead[f.index()] = true;
    }

    #[inline]
    pub(super) fn link(&mut self, h: HalfEdgeId, n: HalfEdgeId) {
        self.halfedges[h.index()].next = n.0;
        self.halfedges[n.index()].prev = h.0;
    }

    #[inline]
    pub(super) fn set_face(&mut self, h: HalfEdgeId, f: Option<FaceId>) {
        self.halfedges[h.index()].face = f.map_or(NONE, |f| f.0);
    }

    #[inline]
    pub(super) fn set_origin(&mut self, h: HalfEdgeId, v: VertexId) {
        self.halfedges[h.index()].origin = v.0;
    }

    /// Re-establishes the vertex's stored half-edge: a boundary one if any,
    /// else `preferred` (an outgoing half-edge known to be live).
    pub(super) fn fix_vertex_halfedge(&mut self, v: VertexId, preferred: HalfEdgeId) {
        self.vertex_out[v.index()] = preferred.0;
        let boundary = self
            .vertex_outgoing(v)
            .find(|&h| self.is_boundary_halfedge(h));
        if let Some(b) = boundary {
            self.vertex_out[v.index()] = b.0;
        }
    }

    fn check_halfedge(&self, h: HalfEdgeId) -> Result<(), EulerError> {
        if self.is_halfedge(h) {
            Ok(())
        } else {
            Err(EulerError::Missing(h.into()))
        }
    }

    pub(super) fn check_edge(&self, e: EdgeId) -> Result<(), EulerError> {
        if self.is_edge(e) {
            Ok(())
        } else {
            Err(EulerError::Missing(e.into()))
        }
    }

    // ----- loops of faces (rings and lone vertices) ------------------------------

    /// Which loop of `f` the loop through `l` is (`l` must lie on `f`).
    /// O(1) for a face without rings, else O(loop length · log).
    fn loop_role(&self, f: FaceId, l: LoopStart) -> Role {
        let Some(rings) = self.face_rings.get(&f) else {
            return Role::Outer;
        };
        match l {
            LoopStart::Vertex(v) => rings
                .iter()
                .position(|&r| r == LoopStart::Vertex(v))
                .map_or(Role::Outer, Role::Ring),
            LoopStart::HalfEdge(h) => {
                let on: BTreeSet<HalfEdgeId> = self.loop_from(h).collect();
                rings
                    .iter()
                    .position(|r| matches!(r, LoopStart::HalfEdge(x) if on.contains(x)))
                    .map_or(Role::Outer, Role::Ring)
            }
        }
    }

    /// Makes `l` the start of loop `role` of `f`.
    fn set_loop(&mut self, f: FaceId, role: Role, l: LoopStart) {
        match (role, l) {
            (Role::Outer, LoopStart::HalfEdge(h)) => {
                self.face_halfedge[f.index()] = h.0;
                self.face_lone_vertex.remove(&f);
            }
            (Role::Outer, LoopStart::Vertex(v)) => {
                self.face_halfedge[f.index()] = NONE;
                self.face_lone_vertex.insert(f, v);
            }
            (Role::Ring(i), _) => {
                self.face_rings.get_mut(&f).expect("a face with rings")[i] = l;
            }
        }
    }

    fn push_ring(&mut self, f: FaceId, l: LoopStart) {
        self.face_rings.entry(f).or_default().push(l);
    }

    fn remove_ring(&mut self, f: FaceId, i: usize) -> LoopStart {
        let rings = self.face_rings.get_mut(&f).expect("a face with rings");
        let r = rings.remove(i);
        if rings.is_empty() {
            self.face_rings.remove(&f);
        }
        r
    }

    /// After the half-edges `old` left a loop of `f`, any loop start on them
    /// moves to `new` (which lies on the same loop, or is its lone vertex).
    pub(super) fn replace_loop_start(
        &mut self,
        f: Option<FaceId>,
        old: &[HalfEdgeId],
        new: LoopStart,
    ) {
        let Some(f) = f else { return };
        let fh = self.face_halfedge[f.index()];
        if fh != NONE && old.contains(&HalfEdgeId(fh)) {
            self.set_loop(f, Role::Outer, new);
        }
        if let Some(rings) = self.face_rings.get_mut(&f) {
            for r in rings.iter_mut() {
                if matches!(r, LoopStart::HalfEdge(x) if old.contains(x)) {
                    *r = new;
                }
            }
        }
    }

    /// The face of a corner: a live half-edge on a face, or a lone vertex.
    fn corner_face(&self, c: LoopStart) -> Result<FaceId, EulerError> {
        match c {
            LoopStart::HalfEdge(h) => {
                self.check_halfedge(h)?;
                self.face(h).ok_or(EulerError::NoFace { halfedge: h })
            }
            LoopStart::Vertex(v) => {
                if !self.is_vertex(v) {
                    return Err(EulerError::Missing(v.into()));
                }
                self.lone_vertex_loop(v)
                    .ok_or(EulerError::NotLoneVertex { vertex: v })
            }
        }
    }

    /// Refuses faces with rings or without edges.
    fn check_polygon_face(&self, f: FaceId) -> Result<(), EulerError> {
        if self.face_rings.contains_key(&f) || self.face_lone_vertex.contains_key(&f) {
            Err(EulerError::HasRings { face: f })
        } else {
            Ok(())
        }
    }

    // ----- MEV / KEV ----------------------------------------------------------

    /// MEV, make edge and vertex: a new vertex at `p` joined by a new edge to
    /// `target(h_in)`, dangling into the face of `h_in` (inserted after `h_in`
    /// in its loop). ΔV = +1, ΔE = +1, ΔF = 0.
    ///
    /// Inverse: [`kill_edge_vertex`](Self::kill_edge_vertex).
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::NoFace`] on a boundary loop,
    /// [`EulerError::NonFinite`].
    ///
    /// Complexity: O(1).
    pub fn make_edge_vertex(
        &mut self,
        h_in: HalfEdgeId,
        p: DVec3,
    ) -> Result<(EdgeId, VertexId), EulerError> {
        self.check_halfedge(h_in)?;
        let face = self
            .face(h_in)
            .ok_or(EulerError::NoFace { halfedge: h_in })?;
        if !p.is_finite() {
            return Err(EulerError::NonFinite);
        }
        let v = self.target(h_in);
        let n = self.next(h_in);
        let w = self.alloc_vertex(p);
        let out = self.alloc_edge(v, w);
        let back = out.twin();
        self.set_face(out, Some(face));
        self.set_face(back, Some(face));
        self.link(h_in, out);
        self.link(out, back);
        self.link(back, n);
        self.vertex_out[w.index()] = back.0;
        Ok((out.edge(), w))
    }

    /// KEV, kill edge and vertex: removes a dangling edge and its end vertex
    /// of valence 1. ΔV = −1, ΔE = −1. An edge with both ends of valence 1
    /// (the wire of a face made by MVFS) leaves the origin of its half-edge 0
    /// as the lone vertex of its loop.
    ///
    /// Inverse: [`make_edge_vertex`](Self::make_edge_vertex), or
    /// [`make_edge_vertex_lone`](Self::make_edge_vertex_lone) for a wire.
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::NotDangling`] (also for an
    /// isolated edge without a face), [`EulerError::Degenerate`] when the
    /// face would keep fewer than 3 sides (and not be a wire).
    pub fn kill_edge_vertex(&mut self, e: EdgeId) -> Result<VertexId, EulerError> {
        self.check_edge(e)?;
        // `out` runs from the kept vertex to the one of valence 1.
        let (out, w) = [e.halfedge(0), e.halfedge(1)]
            .into_iter()
            .map(|h| (h, self.target(h)))
            .find(|&(h, w)| self.vertex_valence(w) == 1 && self.next(h) == h.twin())
            .ok_or(EulerError::NotDangling { edge: e })?;
        let back = out.twin();
        let v = self.origin(out);
        let face = self.face(out);
        if self.vertex_valence(v) == 1 {
            // An isolated edge: in a face it is a wire, which shrinks to v.
            if face.is_none() {
                return Err(EulerError::NotDangling { edge: e });
            }
            self.replace_loop_start(face, &[out, back], LoopStart::Vertex(v));
            self.free_edge(e);
            self.free_vertex(w);
            self.vertex_out[v.index()] = NONE;
            return Ok(w);
        }
        let h_in = self.prev(out);
        let n = self.next(back);
        let len = self.loop_from(out).count();
        // The face would keep fewer than 3 sides, unless what is left is the
        // single edge of a wire.
        if len < 5 && !(len == 4 && face.is_some() && n == h_in.twin()) {
            return Err(EulerError::Degenerate);
        }
        self.link(h_in, n);
        self.replace_loop_start(face, &[out, back], LoopStart::HalfEdge(h_in));
        self.free_edge(e);
        self.free_vertex(w);
        self.fix_vertex_halfedge(v, n);
        Ok(w)
    }

    // ----- MEF / KEF ----------------------------------------------------------

    /// MEF, make edge and face (split face): joins `target(h_a)` to
    /// `target(h_b)`, two corners of one face loop, with a new edge. The loop
    /// part after `h_a` keeps the face; the part after `h_b` becomes a new
    /// face. Half-edge 0 of the new edge runs from `target(h_a)` and lies on
    /// the kept face. ΔE = +1, ΔF = +1. On a ring the kept part stays a
    /// ring and the other part becomes the new face's outer loop (ΔL = +1);
    /// other rings stay with the kept face.
    ///
    /// Inverse: [`kill_edge_face`](Self::kill_edge_face).
    ///
    /// # Errors
    /// [`EulerError::NotSameLoop`], [`EulerError::NoFace`],
    /// [`EulerError::Degenerate`] when either new face would have fewer than
    /// three sides, [`EulerError::SelfLoop`].
    ///
    /// # Example
    /// Splitting a cube's face along a diagonal, then joining it back:
    /// ```
    /// use hedra_geom::{FaceId, HalfEdgeId, Primitive};
    /// let cube = Primitive::Cube { size: 2.0 }.build()?;
    /// let mut m = cube.clone();
    /// let loop_: Vec<HalfEdgeId> = m.face_halfedges(FaceId(0)).collect();
    /// // target(loop_[0]) and target(loop_[2]) are opposite corners.
    /// let (e, f) = m.make_edge_face(loop_[0], loop_[2])?;
    /// assert_eq!((m.vertex_count(), m.edge_count(), m.face_count()), (8, 13, 7));
    /// assert_eq!(m.face_halfedges(f).count(), 3);
    /// m.validate()?;
    ///
    /// assert_eq!(m.kill_edge_face(e)?, f);
    /// assert_eq!((m.vertex_count(), m.edge_count(), m.face_count()), (8, 12, 6));
    /// m.validate()?;
    /// assert!(m.same_as(&cube));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn make_edge_face(
        &mut self,
        h_a: HalfEdgeId,
        h_b: HalfEdgeId,
    ) -> Result<(EdgeId, FaceId), EulerError> {
        self.check_halfedge(h_a)?;
        self.check_halfedge(h_b)?;
        let f = self.face(h_a).ok_or(EulerError::NoFace { halfedge: h_a })?;
        let Some(steps) = self.loop_from(h_a).position(|h| h == h_b) else {
            return Err(EulerError::NotSameLoop { a: h_a, b: h_b });
        };
        let len = self.loop_from(h_a).count();
        // New loops: h_a..(before h_b) + new = steps + 1 sides, and the rest + 1.
        if steps < 2 || len - steps < 2 {
            return Err(EulerError::Degenerate);
        }
        let (v, u) = (self.target(h_a), self.target(h_b));
        if v == u {
            return Err(EulerError::SelfLoop { vertex: v });
        }
        let role = self.loop_role(f, LoopStart::HalfEdge(h_a));
        let na = self.next(h_a);
        let nb = self.next(h_b);
        let n = self.alloc_edge(v, u);
        let t = n.twin();
        self.link(h_a, n);
        self.link(n, nb);
        self.link(h_b, t);
        self.link(t, na);
        self.set_face(n, Some(f));
        // The kept part keeps the loop's place (outer loop or ring).
        self.set_loop(f, role, LoopStart::HalfEdge(n));
        let g = self.alloc_face(t);
        let mut h = t;
        loop {
            self.set_face(h, Some(g));
            h = self.next(h);
            if h == t {
                break;
            }
        }
        Ok((n.edge(), g))
    }

    /// KEF, kill edge and face (join faces): removes an edge between two
    /// different faces; the face of half-edge 0 absorbs the face of half-edge
    /// 1. ΔE = −1, ΔF = −1.
    ///
    /// The two loops become one (ΔL = −1), which is the outer loop when both
    /// were outer loops, else a ring; the absorbed face's other loops become
    /// rings (its outer loop the outer one when the kept face's loop was a
    /// ring inside it).
    ///
    /// Inverse: [`make_edge_face`](Self::make_edge_face).
    ///
    /// # Errors
    /// [`EulerError::BoundaryEdge`], [`EulerError::SameFace`],
    /// [`EulerError::SharedEdges`] when the faces share another edge.
    pub fn kill_edge_face(&mut self, e: EdgeId) -> Result<FaceId, EulerError> {
        self.check_edge(e)?;
        let (h0, h1) = (e.halfedge(0), e.halfedge(1));
        let (Some(f0), Some(f1)) = (self.face(h0), self.face(h1)) else {
            return Err(EulerError::BoundaryEdge { edge: e });
        };
        if f0 == f1 {
            return Err(EulerError::SameFace { edge: e });
        }
        if self
            .face_all_halfedges(f0)
            .any(|h| h != h0 && self.face(h.twin()) == Some(f1))
        {
            return Err(EulerError::SharedEdges { a: f0, b: f1 });
        }
        let (a, b) = (self.origin(h0), self.origin(h1));
        let (p0, n0, p1, n1) = (self.prev(h0), self.next(h0), self.prev(h1), self.next(h1));
        let rings = self.face_rings.contains_key(&f0) || self.face_rings.contains_key(&f1);
        let (role0, role1) = (
            self.loop_role(f0, LoopStart::HalfEdge(h0)),
            self.loop_role(f1, LoopStart::HalfEdge(h1)),
        );
        let outer1 = self.outer_loop(f1);
        let mut h = n1;
        while h != h1 {
            self.set_face(h, Some(f0));
            h = self.next(h);
        }
        if rings {
            let others: Vec<HalfEdgeId> = self
                .face_all_halfedges(f1)
                .filter(|&x| self.face(x) == Some(f1) && x != h1)
                .collect();
            for x in others {
                self.set_face(x, Some(f0));
            }
        }
        self.link(p0, n1);
        self.link(p1, n0);
        let merged = LoopStart::HalfEdge(p0);
        let mut rings1 = self.face_rings.remove(&f1).unwrap_or_default();
        self.face_lone_vertex.remove(&f1);
        match (role0, role1) {
            (Role::Outer, Role::Outer) => self.face_halfedge[f0.index()] = p0.0,
            (Role::Ring(i), Role::Outer) => self.set_loop(f0, Role::Ring(i), merged),
            (Role::Outer, Role::Ring(j)) => {
                rings1.remove(j);
                self.set_loop(f0, Role::Outer, outer1);
                self.push_ring(f0, merged);
            }
            (Role::Ring(i), Role::Ring(j)) => {
                rings1.remove(j);
                self.set_loop(f0, Role::Ring(i), merged);
                self.push_ring(f0, outer1);
            }
        }
        for r in rings1 {
            self.push_ring(f0, r);
        }
        self.free_edge(e);
        self.free_face(f1);
        self.fix_vertex_halfedge(a, n1);
        self.fix_vertex_halfedge(b, n0);
        Ok(f1)
    }

    // ----- MVE / KVE ----------------------------------------------------------

    /// MVE, make vertex and edge (split edge): a new vertex at `p` on edge
    /// `e`. The old edge keeps its id from its start (origin of half-edge 0)
    /// to the new vertex; a new edge continues to the old end. ΔV = +1, ΔE = +1.
    ///
    /// Inverse: [`join_edges`](Self::join_edges).
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::NonFinite`].
    ///
    /// # Example
    /// ```
    /// use hedra_geom::{EdgeId, EulerError, Primitive};
    /// let cube = Primitive::Cube { size: 2.0 }.build()?;
    /// let mut m = cube.clone();
    /// let e = EdgeId(0);
    /// let v = m.split_edge(e, m.edge_midpoint(e))?;
    /// assert_eq!((m.vertex_count(), m.edge_count(), m.face_count()), (9, 13, 6));
    /// assert_eq!(m.vertex_valence(v), 2);
    /// m.validate()?;
    ///
    /// assert_eq!(m.join_edges(v)?, e);
    /// m.validate()?;
    /// assert!(m.same_as(&cube));
    ///
    /// // A refusal names the element and leaves the mesh as it was.
    /// let err = m.split_edge(EdgeId(99), m.edge_midpoint(e)).unwrap_err();
    /// assert_eq!(err, EulerError::Missing(EdgeId(99).into()));
    /// assert_eq!(err.to_string(), "e99 does not exist");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn split_edge(&mut self, e: EdgeId, p: DVec3) -> Result<VertexId, EulerError> {
        self.check_edge(e)?;
        if !p.is_finite() {
            return Err(EulerError::NonFinite);
        }
        let h = e.halfedge(0);
        let o = h.twin();
        let b = self.origin(o);
        let (nh, po) = (self.next(h), self.prev(o));
        let spike_end = nh == o; // b has valence 1
        let m = self.alloc_vertex(p);
        let g0 = self.alloc_edge(m, b);
        let g1 = g0.twin();
        self.set_origin(o, m);
        self.set_face(g0, self.face(h));
        self.set_face(g1, self.face(o));
        self.link(h, g0);
        if spike_end {
            self.link(g0, g1);
            self.link(g1, o);
        } else {
            self.link(g0, nh);
            self.link(po, g1);
            self.link(g1, o);
        }
        if self.vertex_out[b.index()] == o.0 {
            self.vertex_out[b.index()] = g1.0;
        }
        self.fix_vertex_halfedge(m, o);
        Ok(m)
    }

    /// KVE, kill vertex and edge (join edges): removes a vertex of valence 2;
    /// the edge with the smaller id survives and spans both. ΔV = −1, ΔE = −1.
    ///
    /// Inverse: [`split_edge`](Self::split_edge).
    ///
    /// # Errors
    /// [`EulerError::Valence`], [`EulerError::Degenerate`] when a face would
    /// drop below three sides, [`EulerError::SelfLoop`].
    pub fn join_edges(&mut self, v: VertexId) -> Result<EdgeId, EulerError> {
        if !self.is_vertex(v) {
            return Err(EulerError::Missing(v.into()));
        }
        let outs: Vec<HalfEdgeId> = self.vertex_outgoing(v).collect();
        if outs.len() != 2 {
            return Err(EulerError::Valence {
                vertex: v,
                valence: outs.len(),
                needed: "exactly 2",
            });
        }
        let (keep, kill) = if outs[0].edge() < outs[1].edge() {
            (outs[0].edge(), outs[1].edge())
        } else {
            (outs[1].edge(), outs[0].edge())
        };
        // hk: x -> v on the kept edge; hx: v -> y on the killed edge.
        let hk = if self.target(keep.halfedge(0)) == v {
            keep.halfedge(0)
        } else {
            keep.halfedge(1)
        };
        let hx = if self.origin(kill.halfedge(0)) == v {
            kill.halfedge(0)
        } else {
            kill.halfedge(1)
        };
        let (x, y) = (self.origin(hk), self.target(hx));
        if x == y {
            return Err(EulerError::SelfLoop { vertex: x });
        }
        for h in [hk, hx.twin()] {
            if self.face(h).is_some() && self.loop_from(h).count() < 4 {
                return Err(EulerError::Degenerate);
            }
        }
        let (tk, tx) = (hk.twin(), hx.twin());
        let (nx, ptx) = (self.next(hx), self.prev(tx));
        self.replace_loop_start(self.face(hx), &[hx], LoopStart::HalfEdge(hk));
        self.replace_loop_start(self.face(tx), &[tx], LoopStart::HalfEdge(tk));
        self.set_origin(tk, y);
        if nx == tx {
            // y had valence 1: the joined edge dangles.
            self.link(hk, tk);
        } else {
            self.link(hk, nx);
            self.link(ptx, tk);
        }
        if self.vertex_out[y.index()] == tx.0 {
            self.vertex_out[y.index()] = tk.0;
        }
        self.free_edge(kill);
        self.free_vertex(v);
        self.fix_vertex_halfedge(y, tk);
        self.fix_vertex_halfedge(x, hk);
        Ok(keep)
    }

    // ----- edge collapse / vertex split ----------------------------------------------

    /// Edge collapse (seed 004's progressive-mesh step): removes the edge of
    /// `h` and its end vertex; every edge of that vertex moves to the start
    /// vertex, which goes to `p`. The faces on both sides lose one side.
    /// ΔV = −1, ΔE = −1.
    ///
    /// Inverse: [`split_vertex`](Self::split_vertex) with the returned
    /// [`Collapse`] record (and the old positions it keeps).
    ///
    /// # Errors
    /// [`EulerError::Degenerate`] when a face beside the edge is a triangle,
    /// [`EulerError::SharedNeighbours`] when the two vertices have a common
    /// neighbour (the result would have a double edge), and
    /// [`EulerError::BoundaryEdge`] when both ends are on a boundary but the
    /// edge is not (the surface would be pinched).
    pub fn collapse_edge(&mut self, h: HalfEdgeId, p: DVec3) -> Result<Collapse, EulerError> {
        self.check_halfedge(h)?;
        for x in [h, h.twin()] {
            if self.face(x).is_some() && self.loop_from(x).count() < 4 {
                return Err(EulerError::Degenerate);
            }
        }
        // Without triangles beside the edge the general collapse removes no
        // face, and its fan split is exactly undone by `split_vertex`.
        let record = Collapse {
            kept: self.origin(h),
            first: self.prev(h.twin()).twin(),
            last: self.next(h),
            kept_position: self.position(self.origin(h)),
            removed_position: self.position(self.target(h)),
        };
        self.collapse_edge_removing_triangles(h, p)?;
        Ok(record)
    }

    /// Edge collapse that also removes the triangles beside the edge (the
    /// general form of seed 004's progressive-mesh collapse, pmp-library's
    /// `collapse` with its link condition): the end vertex of `h` merges
    /// into its start, which goes to `p`; each triangle beside the edge
    /// disappears with one of its other edges. ΔV = −1, ΔE = −1 − t,
    /// ΔF = −t for t triangles (0, 1 or 2).
    ///
    /// Inverse: [`split_vertex`](Self::split_vertex), then
    /// [`make_edge_face`](Self::make_edge_face) for each removed triangle.
    ///
    /// # Errors
    /// As [`collapse_edge`](Self::collapse_edge), except that triangles are
    /// allowed; [`EulerError::Degenerate`] when both sides are triangles on
    /// the same apex or a triangle's other edges are both on a boundary.
    pub fn collapse_edge_removing_triangles(
        &mut self,
        h: HalfEdgeId,
        p: DVec3,
    ) -> Result<VertexId, EulerError> {
        self.check_halfedge(h)?;
        if !p.is_finite() {
            return Err(EulerError::NonFinite);
        }
        let t = h.twin();
        let (a, b) = (self.origin(h), self.target(h));
        if self.face(h) == self.face(t) {
            return Err(EulerError::SameFace { edge: h.edge() });
        }
        let apex = |x: HalfEdgeId| -> Option<VertexId> {
            (self.face(x).is_some() && self.loop_from(x).count() == 3)
                .then(|| self.target(self.next(x)))
        };
        let (vl, vr) = (apex(h), apex(t));
        if vl.is_some() && vl == vr {
            return Err(EulerError::Degenerate);
        }
        for x in [h, t] {
            if let Some(f) = self.face(x).filter(|_| apex(x).is_some()) {
                // The triangle's face disappears: it must have no other loop.
                self.check_polygon_face(f)?;
                let (x1, x2) = (self.next(x), self.next(self.next(x)));
                if self.is_boundary_halfedge(x1.twin()) && self.is_boundary_halfedge(x2.twin()) {
                    return Err(EulerError::Degenerate);
                }
            }
        }
        if self.vertex_neighbors(a).filter(|&n| n == b).count() > 1 {
            return Err(EulerError::SelfLoop { vertex: a });
        }
        // b's neighbours on the stack (valences are small), so the link
        // condition costs no allocation.
        let mut near_b = [VertexId(NONE); 32];
        let mut n_b = 0;
        let mut many_b = false;
        for n in self.vertex_neighbors(b) {
            if n_b == near_b.len() {
                many_b = true;
                break;
            }
            near_b[n_b] = n;
            n_b += 1;
        }
        let is_near_b = |n: VertexId| {
            if many_b {
                self.vertex_neighbors(b).any(|m| m == n)
            } else {
                near_b[..n_b].contains(&n)
            }
        };
        if self
            .vertex_neighbors(a)
            .any(|n| n != b && Some(n) != vl && Some(n) != vr && is_near_b(n))
        {
            return Err(EulerError::SharedNeighbours { a, b });
        }
        if self.is_boundary_vertex(a)
            && self.is_boundary_vertex(b)
            && !self.is_boundary_edge(h.edge())
        {
            return Err(EulerError::BoundaryEdge { edge: h.edge() });
        }
        // No interior vertex may drop below valence 3 (a tetrahedron would
        // fold into two triangles glued along all their edges): the two
        // vertices' other neighbours must be at least three.
        let interior = |v: VertexId| !self.is_boundary_vertex(v);
        if interior(a) && interior(b) {
            let mut distinct = [VertexId(NONE); 3];
            let mut found = 0;
            for n in self.vertex_neighbors(a).chain(self.vertex_neighbors(b)) {
                if n != a && n != b && !distinct[..found].contains(&n) {
                    distinct[found] = n;
                    found += 1;
                    if found == 3 {
                        break;
                    }
                }
            }
            if found < 3 {
                return Err(EulerError::Degenerate);
            }
        }
        if [vl, vr]
            .into_iter()
            .flatten()
            .any(|v| interior(v) && self.vertex_valence(v) <= 3)
        {
            return Err(EulerError::Degenerate);
        }
        let (tri_h, tri_t) = (vl.is_some(), vr.is_some());
        // The kept vertex's stored half-edge afterwards: its first outgoing
        // one (in fan order) that survives, else the first of those it
        // takes over from `b`.
        let (nh0, nt0) = (self.next(h), self.next(t));
        let survivor = self
            .vertex_outgoing(a)
            .find(|&o| o != h && !(tri_t && o == nt0))
            .or_else(|| {
                self.vertex_outgoing(b)
                    .find(|&o| o != t && !(tri_h && o == nh0))
            });
        // Move b's fan to a: origins only, so the fan walk (prev, twin)
        // is unchanged while it runs.
        if let Some(start) = self.vertex_halfedge(b) {
            let mut o = start;
            loop {
                if o != t {
                    self.set_origin(o, a);
                }
                o = self.prev(o).twin();
                if o == start {
                    break;
                }
            }
        }
        let (ph, nh, pt, nt) = (self.prev(h), self.next(h), self.prev(t), self.next(t));
        self.link(ph, nh);
        self.link(pt, nt);
        for (x, replacement) in [(h, nh), (t, nt)] {
            self.replace_loop_start(self.face(x), &[x], LoopStart::HalfEdge(replacement));
        }
        self.free_edge(h.edge());
        self.free_vertex(b);
        self.set_position(a, p);
        // Each triangle is now a two-sided loop [h0, h1]: drop it and the edge
        // of h0; h1 takes the place of h0's twin in the face beyond.
        for (is_tri, h0) in [(tri_h, nh), (tri_t, nt)] {
            if !is_tri {
                continue;
            }
            let h1 = self.next(h0);
            let o0 = h0.twin();
            let gone = self.face(h0).expect("the loop is a face");
            let (on, op) = (self.next(o0), self.prev(o0));
            self.link(h1, on);
            self.link(op, h1);
            self.set_face(h1, self.face(o0));
            self.replace_loop_start(self.face(o0), &[o0], LoopStart::HalfEdge(h1));
            // h1 runs from the triangle's apex to `a`; `a` is fixed below.
            let apex_vertex = self.origin(h1);
            self.free_edge(h0.edge());
            self.free_face(gone);
            self.fix_vertex_halfedge(apex_vertex, h1);
        }
        if let Some(o) = survivor {
            self.fix_vertex_halfedge(a, o);
        }
        Ok(a)
    }

    /// Vertex split, the inverse of [`collapse_edge`](Self::collapse_edge): the
    /// outgoing half-edges of `v` from `first` to `last` (in fan order) move to
    /// a new vertex at `p`, joined to `v` by a new edge; the faces of `last`
    /// and of `first`'s twin gain one side each. ΔV = +1, ΔE = +1.
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::NotInFan`] when the half-edges
    /// do not start at `v` or would take all of its edges.
    pub fn split_vertex(
        &mut self,
        v: VertexId,
        first: HalfEdgeId,
        last: HalfEdgeId,
        p: DVec3,
    ) -> Result<EdgeId, EulerError> {
        if !self.is_vertex(v) {
            return Err(EulerError::Missing(v.into()));
        }
        self.check_halfedge(first)?;
        self.check_halfedge(last)?;
        if !p.is_finite() {
            return Err(EulerError::NonFinite);
        }
        if self.origin(first) != v || self.origin(last) != v {
            return Err(EulerError::NotInFan { vertex: v });
        }
        let fan: Vec<HalfEdgeId> = self.vertex_outgoing(v).collect();
        let start = fan
            .iter()
            .position(|&o| o == first)
            .expect("first starts at v");
        let moved: Vec<HalfEdgeId> = fan
            .iter()
            .cycle()
            .skip(start)
            .take(fan.len())
            .copied()
            .take_while(|&o| o != last)
            .chain(std::iter::once(last))
            .collect();
        if moved.len() >= fan.len() {
            return Err(EulerError::NotInFan { vertex: v });
        }
        let before_last = self.prev(last);
        let into_first = first.twin();
        let after_first = self.next(into_first);
        let w = self.alloc_vertex(p);
        let h = self.alloc_edge(v, w);
        let t = h.twin();
        for &o in &moved {
            self.set_origin(o, w);
        }
        self.set_face(h, self.face(last));
        self.link(before_last, h);
        self.link(h, last);
        self.set_face(t, self.face(into_first));
        self.link(into_first, t);
        self.link(t, after_first);
        self.fix_vertex_halfedge(w, last);
        self.fix_vertex_halfedge(v, h);
        Ok(h.edge())
    }

    // ----- KFMH / MFKH -----------------------------------------------------------

    /// Kill face, make hole: the face's loop becomes a boundary loop; its
    /// edges and vertices stay (Blender's "delete only faces"). In the
    /// Euler–Poincaré count a boundary loop is a ring of the surface, so
    /// ΔF = −1 and Δ(boundary loops) = +1. Only for faces that touch no
    /// boundary, so every vertex keeps a single boundary wedge.
    ///
    /// Inverse: [`fill_hole`](Self::fill_hole).
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::BoundaryEdge`] when the face
    /// touches a boundary (at an edge or a vertex), [`EulerError::HasRings`]
    /// for a face with rings or without edges, [`EulerError::Degenerate`] for
    /// a wire (a loop of fewer than three edges).
    pub fn make_hole(&mut self, f: FaceId) -> Result<HalfEdgeId, EulerError> {
        if !self.is_face(f) {
            return Err(EulerError::Missing(f.into()));
        }
        self.check_polygon_face(f)?;
        let loop_: Vec<HalfEdgeId> = self.face_halfedges(f).collect();
        if loop_.len() < 3 {
            return Err(EulerError::Degenerate);
        }
        if let Some(&h) = loop_.iter().find(|&&h| {
            self.is_boundary_vertex(self.origin(h)) || self.is_boundary_halfedge(h.twin())
        }) {
            return Err(EulerError::BoundaryEdge { edge: h.edge() });
        }
        // A loop that passes a vertex twice (a dangling edge inside the face)
        // would leave that vertex with two boundary wedges.
        let mut corners: Vec<u32> = loop_.iter().map(|&h| self.origin(h).0).collect();
        corners.sort_unstable();
        if let Some(w) = corners.windows(2).find(|w| w[0] == w[1]) {
            return Err(EulerError::Valence {
                vertex: VertexId(w[0]),
                valence: 2,
                needed: "to appear once in the face's loop",
            });
        }
        for &h in &loop_ {
            self.set_face(h, None);
            // The vertex now lies on a boundary: store the boundary half-edge.
            let v = self.origin(h);
            self.vertex_out[v.index()] = h.0;
        }
        self.free_face(f);
        Ok(loop_[0])
    }

    /// Make face, kill hole: a new face fills the boundary loop through `h`
    /// (Blender's F on a closed boundary). ΔF = +1.
    ///
    /// Inverse: [`make_hole`](Self::make_hole).
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::NoFace`]-like misuse when `h`
    /// is not on a boundary ([`EulerError::SameFace`]), and
    /// [`EulerError::Degenerate`] for a loop of fewer than three edges.
    pub fn fill_hole(&mut self, h: HalfEdgeId) -> Result<FaceId, EulerError> {
        self.check_halfedge(h)?;
        if !self.is_boundary_halfedge(h) {
            return Err(EulerError::SameFace { edge: h.edge() });
        }
        let loop_: Vec<HalfEdgeId> = self.loop_from(h).collect();
        if loop_.len() < 3 {
            return Err(EulerError::Degenerate);
        }
        let f = self.alloc_face(h);
        for &x in &loop_ {
            self.set_face(x, Some(f));
        }
        for &x in &loop_ {
            let v = self.origin(x);
            self.fix_vertex_halfedge(v, x);
        }
        Ok(f)
    }

    // ----- MVFS / KVFS -----------------------------------------------------------

    /// MVFS, make vertex, face and shell: a new shell of one vertex at `p`
    /// and one face whose only loop is that lone vertex (no edges; the face's
    /// [`face_halfedge`](Self::face_halfedge) is invalid and
    /// [`outer_loop`](Self::outer_loop) is [`LoopStart::Vertex`]). Grow it
    /// with [`make_edge_vertex_lone`](Self::make_edge_vertex_lone).
    /// ΔV = +1, ΔF = +1, ΔL = +1, ΔS = +1.
    ///
    /// Inverse: [`kill_vertex_face_shell`](Self::kill_vertex_face_shell).
    ///
    /// # Errors
    /// [`EulerError::NonFinite`].
    pub fn make_vertex_face_shell(&mut self, p: DVec3) -> Result<(VertexId, FaceId), EulerError> {
        if !p.is_finite() {
            return Err(EulerError::NonFinite);
        }
        let v = self.alloc_vertex(p);
        let f = self.alloc_face(HalfEdgeId(NONE));
        self.face_lone_vertex.insert(f, v);
        Ok((v, f))
    }

    /// KVFS, kill vertex, face and shell: removes a face whose only loop is a
    /// lone vertex, and that vertex. ΔV = −1, ΔF = −1, ΔL = −1, ΔS = −1.
    ///
    /// Inverse: [`make_vertex_face_shell`](Self::make_vertex_face_shell).
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::NotVertexFaceShell`] when the
    /// face has edges or rings.
    pub fn kill_vertex_face_shell(&mut self, f: FaceId) -> Result<VertexId, EulerError> {
        if !self.is_face(f) {
            return Err(EulerError::Missing(f.into()));
        }
        let Some(v) = self.lone_vertex_face(f) else {
            return Err(EulerError::NotVertexFaceShell { face: f });
        };
        if self.face_rings.contains_key(&f) {
            return Err(EulerError::NotVertexFaceShell { face: f });
        }
        self.face_lone_vertex.remove(&f);
        self.free_face(f);
        self.free_vertex(v);
        Ok(v)
    }

    /// MEV at a lone vertex: a new vertex at `p` joined to the lone vertex
    /// `v` of a loop (made by MVFS or left by KEMR); the loop becomes the
    /// wire `v → w → v`. Half-edge 0 of the new edge runs from `v`.
    /// ΔV = +1, ΔE = +1.
    ///
    /// Inverse: [`kill_edge_vertex`](Self::kill_edge_vertex).
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::NotLoneVertex`],
    /// [`EulerError::NonFinite`].
    pub fn make_edge_vertex_lone(
        &mut self,
        v: VertexId,
        p: DVec3,
    ) -> Result<(EdgeId, VertexId), EulerError> {
        let f = self.corner_face(LoopStart::Vertex(v))?;
        if !p.is_finite() {
            return Err(EulerError::NonFinite);
        }
        let role = self.loop_role(f, LoopStart::Vertex(v));
        let w = self.alloc_vertex(p);
        let h = self.alloc_edge(v, w);
        let t = h.twin();
        self.set_face(h, Some(f));
        self.set_face(t, Some(f));
        self.link(h, t);
        self.link(t, h);
        self.vertex_out[v.index()] = h.0;
        self.vertex_out[w.index()] = t.0;
        self.set_loop(f, role, LoopStart::HalfEdge(h));
        Ok((h.edge(), w))
    }

    // ----- KEMR / MEKR -----------------------------------------------------------

    /// KEMR, kill edge, make ring: removes the edge of `h` when both its
    /// half-edges lie on the same loop of one face. That loop falls apart in
    /// two: the part after `twin(h)` (through `origin(h)`) keeps the loop's
    /// place (outer loop or ring), the part after `h` (through `target(h)`)
    /// becomes a new ring of the face. A part without edges is a lone
    /// vertex. ΔE = −1, ΔL = +1 (rings +1).
    ///
    /// Returns the corners `(kept, ring)` that
    /// [`make_edge_kill_ring`](Self::make_edge_kill_ring) takes to undo it.
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::NoFace`] on a boundary loop,
    /// [`EulerError::NotSameLoop`] when the half-edges lie on different loops,
    /// [`EulerError::Degenerate`] when a part would be a loop of two
    /// different edges.
    pub fn kill_edge_make_ring(
        &mut self,
        h: HalfEdgeId,
    ) -> Result<(LoopStart, LoopStart), EulerError> {
        self.check_halfedge(h)?;
        let f = self.face(h).ok_or(EulerError::NoFace { halfedge: h })?;
        let t = h.twin();
        if !self.loop_from(h).any(|x| x == t) {
            return Err(EulerError::NotSameLoop { a: h, b: t });
        }
        let role = self.loop_role(f, LoopStart::HalfEdge(h));
        let (a, b) = (self.origin(h), self.target(h));
        let (ph, nh, pt, nt) = (self.prev(h), self.next(h), self.prev(t), self.next(t));
        // Each part must be a polygon, a wire of one edge, or empty.
        for (first, stop) in [(nh, t), (nt, h)] {
            let len = self.loop_from(first).take_while(|&x| x != stop).count();
            if len == 1 || (len == 2 && self.next(first) != first.twin()) {
                return Err(EulerError::Degenerate);
            }
        }
        let ring = if nh == t {
            LoopStart::Vertex(b)
        } else {
            self.link(pt, nh);
            LoopStart::HalfEdge(nh)
        };
        let kept = if nt == h {
            LoopStart::Vertex(a)
        } else {
            self.link(ph, nt);
            LoopStart::HalfEdge(nt)
        };
        self.free_edge(h.edge());
        for (v, l) in [(a, kept), (b, ring)] {
            match l {
                LoopStart::HalfEdge(x) => self.fix_vertex_halfedge(v, x),
                LoopStart::Vertex(_) => self.vertex_out[v.index()] = NONE,
            }
        }
        self.set_loop(f, role, kept);
        self.push_ring(f, ring);
        Ok((kept, ring))
    }

    /// MEKR, make edge, kill ring: joins corner `a` of one loop of a face to
    /// corner `b` of one of its rings with a new edge (half-edge 0 from `a`'s
    /// vertex to `b`'s), inserted before each corner's half-edge (a lone
    /// vertex is the whole loop). The ring merges into `a`'s loop, which
    /// keeps its place. ΔE = +1, ΔL = −1 (rings −1).
    ///
    /// Inverse: [`kill_edge_make_ring`](Self::kill_edge_make_ring) on
    /// half-edge 0 of the returned edge.
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::NoFace`],
    /// [`EulerError::NotLoneVertex`] for a vertex that is not a loop's lone
    /// vertex, [`EulerError::DifferentFaces`], [`EulerError::SameLoop`],
    /// [`EulerError::NotARing`] when `b` is on the outer loop,
    /// [`EulerError::SelfLoop`] when the loops share the corner's vertex.
    pub fn make_edge_kill_ring(
        &mut self,
        a: LoopStart,
        b: LoopStart,
    ) -> Result<EdgeId, EulerError> {
        let f = self.corner_face(a)?;
        let fb = self.corner_face(b)?;
        if f != fb {
            return Err(EulerError::DifferentFaces { a: f, b: fb });
        }
        let (role_a, role_b) = (self.loop_role(f, a), self.loop_role(f, b));
        if role_a == role_b {
            return Err(EulerError::SameLoop { face: f });
        }
        let Role::Ring(j) = role_b else {
            return Err(EulerError::NotARing { face: f });
        };
        let (va, vb) = (a.vertex(self), b.vertex(self));
        if va == vb {
            return Err(EulerError::SelfLoop { vertex: va });
        }
        let n = self.alloc_edge(va, vb);
        let t = n.twin();
        self.set_face(n, Some(f));
        self.set_face(t, Some(f));
        match b {
            LoopStart::HalfEdge(hb) => {
                let pb = self.prev(hb);
                self.link(n, hb);
                self.link(pb, t);
            }
            LoopStart::Vertex(_) => {
                self.link(n, t);
                self.vertex_out[vb.index()] = t.0;
            }
        }
        match a {
            LoopStart::HalfEdge(ha) => {
                let pa = self.prev(ha);
                self.link(pa, n);
                self.link(t, ha);
            }
            LoopStart::Vertex(_) => {
                self.link(t, n);
                self.vertex_out[va.index()] = n.0;
            }
        }
        self.set_loop(f, role_a, LoopStart::HalfEdge(n));
        self.remove_ring(f, j);
        Ok(n.edge())
    }

    // ----- KFMRH / MFKRH ---------------------------------------------------------

    /// KFMRH, kill face, make ring and hole: face `kill` disappears and its
    /// loop becomes an inner ring of face `keep` (Mäntylä's way to make a
    /// through hole: `kill` lies inside `keep`, facing the other way, as the
    /// bottom of a hole swept through a solid; the geometry is the caller's).
    /// ΔF = −1, ΔL = 0 (rings +1), and ΔH = +1 when both faces are in one
    /// shell, ΔS = −1 when the operator glues two shells.
    ///
    /// Returns the new ring.
    ///
    /// Inverse: [`make_face_kill_ring_hole`](Self::make_face_kill_ring_hole).
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::FaceWithItself`],
    /// [`EulerError::HasRings`] when `kill` has rings,
    /// [`EulerError::FacesTouch`] when the faces share a vertex.
    pub fn kill_face_make_ring_hole(
        &mut self,
        keep: FaceId,
        kill: FaceId,
    ) -> Result<LoopStart, EulerError> {
        for f in [keep, kill] {
            if !self.is_face(f) {
                return Err(EulerError::Missing(f.into()));
            }
        }
        if keep == kill {
            return Err(EulerError::FaceWithItself { face: keep });
        }
        if self.face_rings.contains_key(&kill) {
            return Err(EulerError::HasRings { face: kill });
        }
        let ring = self.outer_loop(kill);
        let mut mine: BTreeSet<VertexId> = self
            .face_all_halfedges(keep)
            .map(|h| self.origin(h))
            .collect();
        mine.extend(self.face_loops(keep).filter_map(|l| match l {
            LoopStart::Vertex(v) => Some(v),
            LoopStart::HalfEdge(_) => None,
        }));
        let theirs: Vec<VertexId> = match ring {
            LoopStart::Vertex(v) => vec![v],
            LoopStart::HalfEdge(h) => self.loop_from(h).map(|x| self.origin(x)).collect(),
        };
        if let Some(&vertex) = theirs.iter().find(|v| mine.contains(v)) {
            return Err(EulerError::FacesTouch {
                a: keep,
                b: kill,
                vertex,
            });
        }
        let hs: Vec<HalfEdgeId> = self.loop_halfedges(ring).collect();
        for h in hs {
            self.set_face(h, Some(keep));
        }
        self.face_lone_vertex.remove(&kill);
        self.free_face(kill);
        self.push_ring(keep, ring);
        Ok(ring)
    }

    /// MFKRH, make face, kill ring and hole: the ring through `ring` (any
    /// corner of it, or its lone vertex) leaves its face and becomes the
    /// outer loop of a new face. ΔF = +1, ΔL = 0 (rings −1), and ΔH = −1 or
    /// ΔS = +1 (when the ring was all that held another shell).
    ///
    /// Inverse: [`kill_face_make_ring_hole`](Self::kill_face_make_ring_hole).
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::NoFace`],
    /// [`EulerError::NotLoneVertex`], [`EulerError::NotARing`] when the loop
    /// is its face's outer loop.
    pub fn make_face_kill_ring_hole(&mut self, ring: LoopStart) -> Result<FaceId, EulerError> {
        let f = self.corner_face(ring)?;
        let Role::Ring(j) = self.loop_role(f, ring) else {
            return Err(EulerError::NotARing { face: f });
        };
        let start = self.remove_ring(f, j);
        let g = match start {
            LoopStart::HalfEdge(h) => {
                let g = self.alloc_face(h);
                let hs: Vec<HalfEdgeId> = self.loop_from(h).collect();
                for x in hs {
                    self.set_face(x, Some(g));
                }
                g
            }
            LoopStart::Vertex(v) => {
                let g = self.alloc_face(HalfEdgeId(NONE));
                self.face_lone_vertex.insert(g, v);
                g
            }
        };
        Ok(g)
    }

    // ----- composite ------------------------------------------------------------

    /// Extrudes one face along `offset` (seed 004's face extrude): each corner
    /// grows an edge (MEV), consecutive new corners are joined (MEF), so the
    /// face becomes the cap and every side gets a new quad. For an n-gon:
    /// ΔV = +n, ΔE = +2n, ΔF = +n. The cap keeps the face's id.
    ///
    /// Inverse: for each side quad, [`kill_edge_face`](Self::kill_edge_face)
    /// on the edges between new corners, then
    /// [`kill_edge_vertex`](Self::kill_edge_vertex) on each corner edge.
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::NonFinite`],
    /// [`EulerError::HasRings`] for a face with rings or without edges,
    /// [`EulerError::Degenerate`] for a wire of one edge, or a loop that
    /// passes a vertex twice where the side faces cannot be made.
    ///
    /// Complexity: O(n²) for an n-gon (loop walks in MEF); a loop that passes
    /// a vertex twice is extruded on a copy first.
    pub fn extrude_face(&mut self, f: FaceId, offset: DVec3) -> Result<Vec<FaceId>, EulerError> {
        if !self.is_face(f) {
            return Err(EulerError::Missing(f.into()));
        }
        if !offset.is_finite() {
            return Err(EulerError::NonFinite);
        }
        self.check_polygon_face(f)?;
        let mut corners: Vec<VertexId> = self.face_vertices(f).collect();
        if corners.len() < 3 {
            return Err(EulerError::Degenerate); // the single edge of a wire
        }
        corners.sort_unstable();
        if corners.windows(2).any(|w| w[0] == w[1]) {
            let mut trial = self.clone();
            let sides = trial.extrude_face_unchecked(f, offset)?;
            *self = trial;
            return Ok(sides);
        }
        self.extrude_face_unchecked(f, offset)
    }

    fn extrude_face_unchecked(
        &mut self,
        f: FaceId,
        offset: DVec3,
    ) -> Result<Vec<FaceId>, EulerError> {
        let loop_: Vec<HalfEdgeId> = self.face_halfedges(f).collect();
        // Spikes out of every corner: after each original half-edge h (ending at target(h)).
        let mut spikes = Vec::with_capacity(loop_.len());
        for &h in &loop_ {
            let p = self.position(self.target(h)) + offset;
            let (e, _) = self
                .make_edge_vertex(h, p)
                .expect("checked face and position");
            let out = if self.origin(e.halfedge(0)) == self.target(h) {
                e.halfedge(0)
            } else {
                e.halfedge(1)
            };
            spikes.push(out);
        }
        let mut sides = Vec::with_capacity(loop_.len());
        let mut h_a = spikes[0];
        for k in 1..=spikes.len() {
            let h_b = spikes[k % spikes.len()];
            // Corners of a simple loop are always far enough apart; a wire's
            // may not be (its copy is dropped then).
            let (e, g) = self.make_edge_face(h_a, h_b)?;
            sides.push(g);
            h_a = e.halfedge(0);
        }
        Ok(sides)
    }

    /// True when both meshes have the same elements and links (positions may
    /// differ): what a tool that only moves vertices leaves unchanged.
    pub fn same_connectivity(&self, other: &HalfEdgeMesh) -> bool {
        self.halfedges == other.halfedges
            && self.face_halfedge == other.face_halfedge
            && self.vertex_dead == other.vertex_dead
            && self.edge_dead == other.edge_dead
            && self.face_dead == other.face_dead
            && self.face_rings == other.face_rings
            && self.face_lone_vertex == other.face_lone_vertex
    }

    /// Structural equality: the same live vertices at the same positions, the
    /// same live edges with the same half-edge links and faces, the same live
    /// faces with the same outer loops and rings. Ignores free choices (which
    /// half-edge a vertex or loop starts at, the order of rings) and trailing
    /// dead slots: what "restores the mesh exactly" means.
    pub fn same_as(&self, other: &HalfEdgeMesh) -> bool {
        let live = |m: &HalfEdgeMesh| {
            (
                m.vertices().collect::<Vec<_>>(),
                m.edges().collect::<Vec<_>>(),
                m.faces().collect::<Vec<_>>(),
            )
        };
        if live(self) != live(other) {
            return false;
        }
        let loops_of: BTreeSet<FaceId> = [self, other]
            .iter()
            .flat_map(|m| m.face_rings.keys().chain(m.face_lone_vertex.keys()))
            .copied()
            .collect();
        self.vertices()
            .all(|v| self.position(v) == other.position(v))
            && self
                .halfedges()
                .all(|h| self.halfedges[h.index()] == other.halfedges[h.index()])
            && loops_of
                .into_iter()
                .all(|f| self.canonical_loops(f) == other.canonical_loops(f))
    }

    /// A face's loops named by their smallest half-edge (or lone vertex):
    /// the outer loop, then the sorted rings.
    fn canonical_loops(&self, f: FaceId) -> (LoopStart, Vec<LoopStart>) {
        let canon = |l: LoopStart| match l {
            LoopStart::HalfEdge(h) => {
                LoopStart::HalfEdge(self.loop_from(h).min().expect("a loop has a half-edge"))
            }
            v => v,
        };
        let mut rings: Vec<LoopStart> = self.face_rings(f).iter().map(|&r| canon(r)).collect();
        rings.sort();
        (canon(self.outer_loop(f)), rings)
    }
}
