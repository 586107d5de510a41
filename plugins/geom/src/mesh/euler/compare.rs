//! Comparing two meshes: same connectivity, or the same mesh up to
//! where each face loop starts.

use crate::ids::FaceId;
use crate::mesh::{HalfEdgeMesh, LoopStart};
use std::collections::BTreeSet;

impl HalfEdgeMesh {
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
