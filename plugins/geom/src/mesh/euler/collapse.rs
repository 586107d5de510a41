//! Edge collapse and its inverse, the vertex split.

use super::{Collapse, EulerError};
use crate::ids::{EdgeId, HalfEdgeId, NONE, VertexId};
use crate::mesh::{HalfEdgeMesh, LoopStart};
use glam::DVec3;

impl HalfEdgeMesh {
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
}
