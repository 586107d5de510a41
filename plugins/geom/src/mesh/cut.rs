//! Cutting the surface open along edges: the connectivity half of
//! Blender's Rip (`edbm_rip_invoke__edge`, which calls BMesh's
//! `BM_mesh_edgesplit`). Lives inside [`crate::mesh`] because it relinks
//! the boundary fans of every vertex on the cut at once and moves whole
//! wedges of a fan to new vertices, which no single Euler operator does
//! (in Euler terms a cut of n edges is n edge doublings and one vertex
//! split per extra wedge: ΔE = +n, ΔV = Σ(wedges − 1)).

use crate::euler::EulerError;
use crate::ids::{EdgeId, HalfEdgeId, VertexId};
use crate::mesh::{HalfEdgeMesh, LoopStart};
use std::collections::{BTreeMap, BTreeSet};

/// What [`HalfEdgeMesh::cut_edges`] made.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Cut {
    /// For each cut edge (in the order given, repeats dropped) the edge
    /// itself and its new twin: the old edge keeps the face of its
    /// half-edge 0, the new edge (half-edge 0 in the same direction as the
    /// old edge's half-edge 1) takes the face of half-edge 1.
    pub edges: Vec<(EdgeId, EdgeId)>,
    /// For each vertex that fell apart, the vertex (it keeps one wedge of
    /// its fan) and the new vertices that took the other wedges, at the
    /// same position.
    pub vertices: Vec<(VertexId, Vec<VertexId>)>,
}

impl HalfEdgeMesh {
    /// Cuts the surface open along `edges`: every edge (it must have a
    /// different face on each side) becomes two boundary edges, one per
    /// face, and every vertex whose fan the cut divides into several wedges
    /// becomes one vertex per wedge. A vertex's fan is divided by the cut
    /// edges at it plus, on a boundary vertex, the boundary: an interior
    /// vertex with k ≥ 2 cut edges becomes k vertices, a boundary vertex
    /// with k cut edges k + 1; an interior vertex with one cut edge stays
    /// one vertex, the tip of a slit (the boundary turns around there).
    /// ΔE = +n for n edges, ΔV = Σ(wedges − 1), boundary loops change as
    /// the cut opens or joins them.
    ///
    /// An edge whose two ends are both slit tips (one cut edge, interior)
    /// gives two edges between the same two vertices around a boundary loop
    /// of two edges; valid for [`validate`](Self::validate), but most tools
    /// assume one edge per vertex pair, so `modeling::rip_edges` refuses it.
    ///
    /// No inverse operator: merging the copies back (weld) undoes it.
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::BoundaryEdge`] for an edge
    /// with no face on a side (also for an edge at a cut vertex that has no
    /// face on either side), [`EulerError::SameFace`] for an edge with one
    /// face on both sides. The mesh is unchanged on error.
    ///
    /// Complexity: O(n + Σ valence of the vertices on the cut).
    pub fn cut_edges(&mut self, edges: &[EdgeId]) -> Result<Cut, EulerError> {
        let mut seen = BTreeSet::new();
        let edges: Vec<EdgeId> = edges.iter().copied().filter(|e| seen.insert(*e)).collect();
        for &e in &edges {
            self.check_edge(e)?;
            match self.edge_faces(e) {
                [Some(a), Some(b)] if a == b => return Err(EulerError::SameFace { edge: e }),
                [Some(_), Some(_)] => {}
                _ => return Err(EulerError::BoundaryEdge { edge: e }),
            }
        }
        // Vertices on the cut, with their outgoing half-edges before it.
        let mut touched: BTreeMap<VertexId, Vec<HalfEdgeId>> = BTreeMap::new();
        for &e in &edges {
            for v in self.edge_vertices(e) {
                touched
                    .entry(v)
                    .or_insert_with(|| self.vertex_outgoing(v).collect());
            }
        }
        // Boundary walks below step over faces only: refuse faceless edges.
        for fan in touched.values() {
            if let Some(h) = fan
                .iter()
                .find(|h| self.is_boundary_halfedge(**h) && self.is_boundary_halfedge(h.twin()))
            {
                return Err(EulerError::BoundaryEdge { edge: h.edge() });
            }
        }
        // Boundary half-edges whose `next` may change: those ending at a
        // vertex on the cut, and the ones the cut makes.
        let mut relink: Vec<HalfEdgeId> = touched
            .values()
            .flatten()
            .map(|h| h.twin())
            .filter(|h| self.is_boundary_halfedge(*h))
            .collect();
        let mut pairs = Vec::with_capacity(edges.len());
        for &e in &edges {
            let h1 = e.halfedge(1);
            let f1 = self.face(h1);
            let (a, b) = (self.origin(h1), self.target(h1));
            let n = self.alloc_edge(a, b);
            let (p, x) = (self.prev(h1), self.next(h1));
            self.set_face(n, f1);
            self.link(p, n);
            self.link(n, x);
            self.set_face(h1, None);
            self.set_face(n.twin(), None);
            self.replace_loop_start(f1, &[h1], LoopStart::HalfEdge(n));
            touched.get_mut(&a).expect("an end of a cut edge").push(n);
            touched
                .get_mut(&b)
                .expect("an end of a cut edge")
                .push(n.twin());
            relink.extend([h1, n.twin()]);
            pairs.push((e, n.edge()));
        }
        // Each boundary half-edge continues with the boundary half-edge met
        // first when turning around its target across faces.
        for &b in &relink {
            let mut x = b.twin();
            let out = loop {
                let y = self.prev(x).twin();
                if self.is_boundary_halfedge(y) {
                    break y;
                }
                x = y;
            };
            self.link(b, out);
        }
        // Each cycle of the fan circulation is now one wedge: the first
        // keeps the vertex, the others get new ones.
        let mut split = Vec::new();
        for (&v, fan) in &touched {
            let mut done: BTreeSet<HalfEdgeId> = BTreeSet::new();
            let mut copies = Vec::new();
            for &start in fan {
                if done.contains(&start) {
                    continue;
                }
                let mut wedge = vec![start];
                let mut h = self.prev(start).twin();
                while h != start {
                    wedge.push(h);
                    h = self.prev(h).twin();
                }
                done.extend(wedge.iter().copied());
                if done.len() == wedge.len() {
                    self.fix_vertex_halfedge(v, start);
                    continue;
                }
                let w = self.alloc_vertex(self.position(v));
                for &o in &wedge {
                    self.set_origin(o, w);
                }
                self.fix_vertex_halfedge(w, start);
                copies.push(w);
            }
            if !copies.is_empty() {
                split.push((v, copies));
            }
        }
        Ok(Cut {
            edges: pairs,
            vertices: split,
        })
    }
}
