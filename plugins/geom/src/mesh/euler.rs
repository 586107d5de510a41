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

mod collapse;
mod compare;
mod edges;
mod extrude;
mod rings;

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
        let t = self.topology_mut();
        t.vertex_out.push(NONE);
        t.vertex_dead.push(false);
        t.live_vertices += 1;
        VertexId(self.positions.len() as u32 - 1)
    }

    pub(super) fn alloc_edge(&mut self, a: VertexId, b: VertexId) -> HalfEdgeId {
        let t = self.topology_mut();
        let h = t.halfedges.len() as u32;
        for origin in [a.0, b.0] {
            t.halfedges.push(HalfEdgeRecord {
                origin,
                next: NONE,
                prev: NONE,
                face: NONE,
            });
        }
        t.edge_dead.push(false);
        t.live_edges += 1;
        HalfEdgeId(h)
    }

    pub(super) fn alloc_face(&mut self, h: HalfEdgeId) -> FaceId {
        let t = self.topology_mut();
        t.face_halfedge.push(h.0);
        t.face_dead.push(false);
        t.live_faces += 1;
        FaceId(t.face_halfedge.len() as u32 - 1)
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
        let t = self.topology_mut();
        t.live_vertices -= 1;
        t.vertex_dead[v.index()] = true;
        t.vertex_out[v.index()] = NONE;
    }

    /// Marks an edge dead; its ids are never handed out again.
    pub(super) fn free_edge(&mut self, e: EdgeId) {
        let t = self.topology_mut();
        t.live_edges -= 1;
        t.edge_dead[e.index()] = true;
    }

    /// Marks a face dead; its id is never handed out again.
    pub(super) fn free_face(&mut self, f: FaceId) {
        let t = self.topology_mut();
        t.live_faces -= 1;
        t.face_dead[f.index()] = true;
    }

    #[inline]
    pub(super) fn link(&mut self, h: HalfEdgeId, n: HalfEdgeId) {
        let halfedges = &mut self.topology_mut().halfedges;
        halfedges[h.index()].next = n.0;
        halfedges[n.index()].prev = h.0;
    }

    #[inline]
    pub(super) fn set_face(&mut self, h: HalfEdgeId, f: Option<FaceId>) {
        self.topology_mut().halfedges[h.index()].face = f.map_or(NONE, |f| f.0);
    }

    #[inline]
    pub(super) fn set_origin(&mut self, h: HalfEdgeId, v: VertexId) {
        self.topology_mut().halfedges[h.index()].origin = v.0;
    }

    /// Re-establishes the vertex's stored half-edge: a boundary one if any,
    /// else `preferred` (an outgoing half-edge known to be live).
    pub(super) fn fix_vertex_halfedge(&mut self, v: VertexId, preferred: HalfEdgeId) {
        self.topology_mut().vertex_out[v.index()] = preferred.0;
        let boundary = self
            .vertex_outgoing(v)
            .find(|&h| self.is_boundary_halfedge(h));
        if let Some(b) = boundary {
            self.topology_mut().vertex_out[v.index()] = b.0;
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
        let Some(rings) = self.topology.face_rings.get(&f) else {
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
                self.topology_mut().face_halfedge[f.index()] = h.0;
                self.topology_mut().face_lone_vertex.remove(&f);
            }
            (Role::Outer, LoopStart::Vertex(v)) => {
                self.topology_mut().face_halfedge[f.index()] = NONE;
                self.topology_mut().face_lone_vertex.insert(f, v);
            }
            (Role::Ring(i), _) => {
                self.topology_mut()
                    .face_rings
                    .get_mut(&f)
                    .expect("a face with rings")[i] = l;
            }
        }
    }

    fn push_ring(&mut self, f: FaceId, l: LoopStart) {
        self.topology_mut().face_rings.entry(f).or_default().push(l);
    }

    fn remove_ring(&mut self, f: FaceId, i: usize) -> LoopStart {
        let rings = self
            .topology_mut()
            .face_rings
            .get_mut(&f)
            .expect("a face with rings");
        let r = rings.remove(i);
        if rings.is_empty() {
            self.topology_mut().face_rings.remove(&f);
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
        let fh = self.topology.face_halfedge[f.index()];
        if fh != NONE && old.contains(&HalfEdgeId(fh)) {
            self.set_loop(f, Role::Outer, new);
        }
        if let Some(rings) = self.topology_mut().face_rings.get_mut(&f) {
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
        if self.topology.face_rings.contains_key(&f)
            || self.topology.face_lone_vertex.contains_key(&f)
        {
            Err(EulerError::HasRings { face: f })
        } else {
            Ok(())
        }
    }
}
