//! Comparing two meshes: same connectivity, or the same mesh up to
//! where each face loop starts.

use crate::ids::FaceId;
use crate::mesh::{HalfEdgeMesh, LoopStart};
use std::collections::BTreeSet;
use std::sync::Arc;

impl HalfEdgeMesh {
    /// True when both meshes have the same elements and links (positions may
    /// differ): what a tool that only moves vertices leaves unchanged.
    /// O(1) for copies that share their connectivity (see
    /// [`HalfEdgeMesh`]); otherwise compares the records.
    pub fn same_connectivity(&self, other: &HalfEdgeMesh) -> bool {
        Arc::ptr_eq(&self.topology, &other.topology)
            || self.topology.halfedges == other.topology.halfedges
                && self.topology.face_halfedge == other.topology.face_halfedge
                && self.topology.vertex_dead == other.topology.vertex_dead
                && self.topology.edge_dead == other.topology.edge_dead
                && self.topology.face_dead == other.topology.face_dead
                && self.topology.face_rings == other.topology.face_rings
                && self.topology.face_lone_vertex == other.topology.face_lone_vertex
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
            .flat_map(|m| {
                m.topology
                    .face_rings
                    .keys()
                    .chain(m.topology.face_lone_vertex.keys())
            })
            .copied()
            .collect();
        self.vertices()
            .all(|v| self.position(v) == other.position(v))
            && self
                .halfedges()
                .all(|h| self.topology.halfedges[h.index()] == other.topology.halfedges[h.index()])
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
