//! Reversing the orientation of whole loops (flip normals): origin and
//! next/prev of every half-edge involved are rewritten in place, so this
//! lives inside the [`mesh`](super) module; the operations in
//! [`crate::modeling`] reach it through the two public methods.

use super::HalfEdgeMesh;
use crate::ids::{HalfEdgeId, VertexId};

impl HalfEdgeMesh {
    /// Reverses every loop (see [`flip_normals`](crate::modeling::flip_normals)).
    pub fn reverse_orientation(&mut self) {
        let all: Vec<HalfEdgeId> = self.halfedges().collect();
        self.reverse_halfedges(&all);
    }

    /// Reverses the loops of whole connected components given by a vertex
    /// of each (their half-edges only; other components keep their sides).
    pub fn reverse_components(&mut self, seeds: &[VertexId]) {
        let (comp, _) = self.components();
        let chosen: std::collections::HashSet<usize> = seeds
            .iter()
            .filter(|v| self.is_vertex(**v))
            .map(|v| comp[v.index()])
            .collect();
        let hs: Vec<HalfEdgeId> = self
            .halfedges()
            .filter(|&h| chosen.contains(&comp[self.origin(h).index()]))
            .collect();
        self.reverse_halfedges(&hs);
    }

    /// Origin becomes the old target, next and prev swap: a closed set of
    /// loops runs the other way.
    fn reverse_halfedges(&mut self, hs: &[HalfEdgeId]) {
        let targets: Vec<u32> = hs.iter().map(|&h| self.target(h).0).collect();
        let mut touched = Vec::new();
        let halfedges = &mut self.topology_mut().halfedges;
        for (&h, &t) in hs.iter().zip(&targets) {
            let r = &mut halfedges[h.index()];
            std::mem::swap(&mut r.next, &mut r.prev);
            r.origin = t;
            touched.push(VertexId(t));
        }
        touched.sort();
        touched.dedup();
        // Each vertex's stored half-edge now points into it: use one leaving it.
        for v in touched {
            if let Some(h) = self.vertex_halfedge(v) {
                let out = if self.origin(h) == v { h } else { h.twin() };
                self.fix_vertex_halfedge(v, out);
            }
        }
    }
}
