//! The edge operators: make/kill edge-vertex (MEV/KEV), make/kill
//! edge-face (MEF/KEF), and the edge split and join built on them.

use super::{EulerError, Role};
use crate::ids::{EdgeId, FaceId, HalfEdgeId, NONE, VertexId};
use crate::mesh::{HalfEdgeMesh, LoopStart};
use glam::DVec3;

impl HalfEdgeMesh {
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
        self.topology_mut().vertex_out[w.index()] = back.0;
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
            self.topology_mut().vertex_out[v.index()] = NONE;
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
        let rings = self.topology.face_rings.contains_key(&f0)
            || self.topology.face_rings.contains_key(&f1);
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
        let mut rings1 = self
            .topology_mut()
            .face_rings
            .remove(&f1)
            .unwrap_or_default();
        self.topology_mut().face_lone_vertex.remove(&f1);
        match (role0, role1) {
            (Role::Outer, Role::Outer) => self.topology_mut().face_halfedge[f0.index()] = p0.0,
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
        if self.topology.vertex_out[b.index()] == o.0 {
            self.topology_mut().vertex_out[b.index()] = g1.0;
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
        if self.topology.vertex_out[y.index()] == tx.0 {
            self.topology_mut().vertex_out[y.index()] = tk.0;
        }
        self.free_edge(kill);
        self.free_vertex(v);
        self.fix_vertex_halfedge(y, tk);
        self.fix_vertex_halfedge(x, hk);
        Ok(keep)
    }
}
