//! Holes, shells and rings: make/fill hole and Mäntylä's GWB operators
//! for faces of several loops (MVFS/KVFS, the lone-vertex MEV, KEMR/MEKR,
//! KFMRH/MFKRH).

use super::{EulerError, Role};
use crate::ids::{EdgeId, FaceId, HalfEdgeId, NONE, VertexId};
use crate::mesh::{HalfEdgeMesh, LoopStart};
use glam::DVec3;
use std::collections::BTreeSet;

impl HalfEdgeMesh {
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
            self.topology_mut().vertex_out[v.index()] = h.0;
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
        self.topology_mut().face_lone_vertex.insert(f, v);
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
        if self.topology.face_rings.contains_key(&f) {
            return Err(EulerError::NotVertexFaceShell { face: f });
        }
        self.topology_mut().face_lone_vertex.remove(&f);
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
        self.topology_mut().vertex_out[v.index()] = h.0;
        self.topology_mut().vertex_out[w.index()] = t.0;
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
                LoopStart::Vertex(_) => self.topology_mut().vertex_out[v.index()] = NONE,
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
                self.topology_mut().vertex_out[vb.index()] = t.0;
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
                self.topology_mut().vertex_out[va.index()] = n.0;
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
        if self.topology.face_rings.contains_key(&kill) {
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
        self.topology_mut().face_lone_vertex.remove(&kill);
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
                self.topology_mut().face_lone_vertex.insert(g, v);
                g
            }
        };
        Ok(g)
    }
}
