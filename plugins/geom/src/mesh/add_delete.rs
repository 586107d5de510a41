//! Adding and deleting whole faces (pmp-library's `add_face` and
//! `delete_face`): the building blocks for region extrude, bridges and
//! fills. Each call keeps the mesh manifold or refuses; compositions are
//! checked with `validate()` by the callers that run them on a copy.
//!
//! They live inside [`crate::mesh`] because relinking the boundary fans
//! around a new or removed face writes `next`/`prev` and the vertices'
//! outgoing half-edges directly, which no single Euler operator does.
//! (Formerly `patch.rs`; `hedra_geom::patch` still names this module.)

use crate::euler::EulerError;
use crate::ids::{FaceId, HalfEdgeId, NONE, VertexId};
use crate::mesh::{HalfEdgeMesh, LoopStart};

impl HalfEdgeMesh {
    /// Adds an isolated vertex (no edges yet). ΔV = +1.
    ///
    /// # Errors
    /// [`EulerError::NonFinite`].
    pub fn add_vertex(&mut self, p: glam::DVec3) -> Result<VertexId, EulerError> {
        if !p.is_finite() {
            return Err(EulerError::NonFinite);
        }
        Ok(self.alloc_vertex(p))
    }

    /// Adds a face over existing vertices (counter-clockwise), creating the
    /// edges that do not exist and relinking boundary loops (pmp-library's
    /// `SurfaceMesh::add_face`). ΔF = +1, ΔE = +(new edges).
    ///
    /// Inverse: [`delete_faces`](Self::delete_faces).
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::Degenerate`] for fewer than three
    /// or repeated vertices, [`EulerError::NotInFan`] when a vertex or an edge
    /// is not on a boundary (the face would make it non-manifold) or the
    /// boundary cannot be relinked. The mesh is unchanged on error.
    pub fn add_face(&mut self, vertices: &[VertexId]) -> Result<FaceId, EulerError> {
        let n = vertices.len();
        if n < 3 {
            return Err(EulerError::Degenerate);
        }
        for (i, &v) in vertices.iter().enumerate() {
            if !self.is_vertex(v) {
                return Err(EulerError::Missing(v.into()));
            }
            if vertices[..i].contains(&v) {
                return Err(EulerError::Degenerate);
            }
            if !(self.is_isolated_vertex(v) || self.is_boundary_vertex(v)) {
                return Err(EulerError::NotInFan { vertex: v });
            }
            if let Some(face) = self.lone_vertex_loop(v) {
                return Err(EulerError::HasRings { face });
            }
        }
        let mut hs: Vec<Option<HalfEdgeId>> = Vec::with_capacity(n);
        for i in 0..n {
            let h = self.find_halfedge(vertices[i], vertices[(i + 1) % n]);
            if let Some(h) = h
                && !self.is_boundary_halfedge(h)
            {
                return Err(EulerError::NotInFan {
                    vertex: vertices[i],
                });
            }
            hs.push(h);
        }
        // Re-link patches where two consecutive existing half-edges are not yet
        // consecutive along the boundary (all checks before any change).
        let mut next_cache: Vec<(HalfEdgeId, HalfEdgeId)> = Vec::new();
        for i in 0..n {
            let ii = (i + 1) % n;
            if let (Some(inner_prev), Some(inner_next)) = (hs[i], hs[ii])
                && self.next(inner_prev) != inner_next
            {
                let outer_prev = inner_next.twin();
                let mut boundary_prev = outer_prev;
                let mut guard = self.topology.halfedges.len();
                loop {
                    boundary_prev = self.next(boundary_prev).twin();
                    guard -= 1;
                    if guard == 0 {
                        return Err(EulerError::NotInFan {
                            vertex: vertices[ii],
                        });
                    }
                    if self.is_boundary_halfedge(boundary_prev) && boundary_prev != inner_prev {
                        break;
                    }
                }
                let boundary_next = self.next(boundary_prev);
                if boundary_next == inner_next {
                    return Err(EulerError::NotInFan {
                        vertex: vertices[ii],
                    });
                }
                let patch_start = self.next(inner_prev);
                let patch_end = self.prev(inner_next);
                next_cache.push((boundary_prev, patch_start));
                next_cache.push((patch_end, boundary_next));
                next_cache.push((inner_prev, inner_next));
            }
        }
        for (a, b) in next_cache.drain(..) {
            self.link(a, b);
        }
        let is_new: Vec<bool> = hs.iter().map(Option::is_none).collect();
        let hs: Vec<HalfEdgeId> = (0..n)
            .map(|i| match hs[i] {
                Some(h) => h,
                None => self.alloc_edge(vertices[i], vertices[(i + 1) % n]),
            })
            .collect();
        let f = self.alloc_face(hs[n - 1]);
        let mut needs_adjust = vec![false; n];
        for i in 0..n {
            let ii = (i + 1) % n;
            let v = vertices[ii];
            let (inner_prev, inner_next) = (hs[i], hs[ii]);
            let id = u8::from(is_new[i]) | (u8::from(is_new[ii]) << 1);
            if id != 0 {
                let outer_prev = inner_next.twin();
                let outer_next = inner_prev.twin();
                match id {
                    1 => {
                        let boundary_prev = self.prev(inner_next);
                        next_cache.push((boundary_prev, outer_next));
                        self.topology_mut().vertex_out[v.index()] = outer_next.0;
                    }
                    2 => {
                        let boundary_next = self.next(inner_prev);
                        next_cache.push((outer_prev, boundary_next));
                        self.topology_mut().vertex_out[v.index()] = boundary_next.0;
                    }
                    _ => {
                        if self.topology.vertex_out[v.index()] == NONE {
                            self.topology_mut().vertex_out[v.index()] = outer_next.0;
                            next_cache.push((outer_prev, outer_next));
                        } else {
                            let boundary_next = HalfEdgeId(self.topology.vertex_out[v.index()]);
                            let boundary_prev = self.prev(boundary_next);
                            next_cache.push((boundary_prev, outer_next));
                            next_cache.push((outer_prev, boundary_next));
                        }
                    }
                }
                next_cache.push((inner_prev, inner_next));
            } else {
                needs_adjust[ii] = self.topology.vertex_out[v.index()] == inner_next.0;
            }
            self.topology_mut().halfedges[hs[i].index()].face = f.0;
        }
        for (a, b) in next_cache {
            self.link(a, b);
        }
        for i in 0..n {
            if needs_adjust[i] {
                let v = vertices[i];
                let current = HalfEdgeId(self.topology.vertex_out[v.index()]);
                self.fix_vertex_halfedge(v, current);
            }
        }
        Ok(f)
    }

    /// Deletes faces; edges left without any face are deleted too, and so
    /// are vertices left without edges unless `keep_vertices` (pmp-library's
    /// `delete_face`, for a set). The caller checks the result with
    /// `validate()`: deleting a face that touches a hole only at a vertex
    /// leaves that vertex non-manifold. A face's rings go with it; its lone
    /// vertices are left like vertices without edges.
    pub fn delete_faces(&mut self, faces: &[FaceId], keep_vertices: bool) {
        for &f in faces {
            if !self.is_face(f) {
                continue;
            }
            let loop_: Vec<HalfEdgeId> = self.face_all_halfedges(f).collect();
            let mut corners: Vec<VertexId> = loop_.iter().map(|&h| self.origin(h)).collect();
            corners.extend(self.face_loops(f).filter_map(|l| match l {
                LoopStart::Vertex(v) => Some(v),
                LoopStart::HalfEdge(_) => None,
            }));
            // A loop passing a vertex twice (a wire) must not free it twice.
            corners.sort_unstable();
            corners.dedup();
            self.topology_mut().face_rings.remove(&f);
            self.topology_mut().face_lone_vertex.remove(&f);
            for &h in &loop_ {
                self.topology_mut().halfedges[h.index()].face = NONE;
            }
            self.free_face(f);
            for &h in &loop_ {
                if !self.is_boundary_halfedge(h.twin()) || !self.is_halfedge(h) {
                    continue;
                }
                // Both sides are holes now: remove the edge, joining the loops.
                let (h0, h1) = (h, h.twin());
                let (next0, prev0, next1, prev1) =
                    (self.next(h0), self.prev(h0), self.next(h1), self.prev(h1));
                let (v0, v1) = (self.target(h0), self.target(h1));
                self.link(prev0, next1);
                self.link(prev1, next0);
                if self.topology.vertex_out[v0.index()] == h1.0 {
                    self.topology_mut().vertex_out[v0.index()] =
                        if next0 == h1 { NONE } else { next0.0 };
                }
                if self.topology.vertex_out[v1.index()] == h0.0 {
                    self.topology_mut().vertex_out[v1.index()] =
                        if next1 == h0 { NONE } else { next1.0 };
                }
                self.free_edge(h.edge());
            }
            for v in corners {
                if self.topology.vertex_out[v.index()] == NONE {
                    if !keep_vertices {
                        self.free_vertex(v);
                    }
                } else {
                    let current = HalfEdgeId(self.topology.vertex_out[v.index()]);
                    self.fix_vertex_halfedge(v, current);
                }
            }
        }
    }
}
