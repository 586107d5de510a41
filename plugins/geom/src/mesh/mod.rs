//! The half-edge mesh: connectivity, positions, traversal, and the only
//! code that writes connectivity.
//!
//! Half-edge structure as taught in seed 000 (Bán, "half-edge: vertex, sym, face,
//! next") and seed 001; storage follows pmp-library's `SurfaceMesh`: one record
//! per vertex, half-edge and face, twins implicit (`h ^ 1`). Every half-edge,
//! boundary ones included, has `next`/`prev`: boundary half-edges (no face) form
//! the loops around holes, so circulating `twin(prev(h))` around a vertex visits
//! all its outgoing half-edges. A boundary vertex stores a boundary half-edge
//! as its outgoing one, so boundary tests are O(1).
//!
//! The arrays of [`HalfEdgeMesh`] are private to this module, so the compiler
//! holds the rest of the kernel to the accessors, iterators and operators
//! below. Inside the wall, connectivity is written by:
//!
//! - [`euler`]: the Euler operators, the normal way to change connectivity
//!   (checked, invertible, with stated V/E/F changes);
//! - [`add_delete`]: adding and deleting whole faces (pmp-library's
//!   `add_face` / `delete_face`), which relink boundary fans that no single
//!   Euler operator reaches;
//! - [`cut`]: cutting the surface open along edges (the connectivity of
//!   Blender's Rip), which relinks the boundary fans of every vertex on
//!   the cut and moves wedges of fans to new vertices at once;
//! - `orientation`: reversing whole loops (flip normals), which rewrites
//!   every half-edge in place instead of rebuilding the faces;
//! - `construct`: the strict bulk build from polygons, one pass over the
//!   corners instead of an operator per element;
//! - `records`: [`MeshData`] in and out and dense renumbering, which copy
//!   raw records;
//! - `polygon_form`: [`PolygonData`] in and out, the compact stored form
//!   (polygons plus the ids a numbering rule cannot derive).
//!
//! [`validate`] reads the raw records (it must survive corrupted ones).
//! One low-level writer is open to the rest of the crate: `free_vertex`
//! (in [`euler`]), with which weld and bevel drop the vertices they left
//! isolated after taking faces out; they validate before keeping the
//! result.
//! Positions are geometry, not connectivity: anyone may move them through
//! [`set_position`](HalfEdgeMesh::set_position) and
//! [`positions_mut`](HalfEdgeMesh::positions_mut).

pub mod add_delete;
mod construct;
pub(crate) use construct::LevelFaces;
pub mod cut;
pub mod euler;
mod orientation;
mod polygon_form;
mod records;
pub mod validate;

pub use polygon_form::PolygonData;
pub use records::{MeshData, MeshDataError};

use crate::ids::{EdgeId, FaceId, HalfEdgeId, NONE, VertexId};
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::sync::Arc;

#[derive(Copy, Clone, Debug, PartialEq, Eq)]
struct HalfEdgeRecord {
    origin: u32,
    next: u32,
    prev: u32,
    face: u32,
}

/// One loop of a face (Mäntylä's Loop), entered at a corner: the half-edge
/// leaving that corner, or, for a loop without edges (the one vertex of a
/// shell made by [`make_vertex_face_shell`](HalfEdgeMesh::make_vertex_face_shell)),
/// its lone vertex. As an operator argument it names the corner at the
/// half-edge's origin, between `prev(h)` and `h`.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum LoopStart {
    /// A loop with edges, entered at this half-edge.
    HalfEdge(HalfEdgeId),
    /// A loop without edges: its one (isolated) vertex.
    Vertex(VertexId),
}

impl LoopStart {
    /// The vertex at this corner.
    pub fn vertex(self, mesh: &HalfEdgeMesh) -> VertexId {
        match self {
            LoopStart::HalfEdge(h) => mesh.origin(h),
            LoopStart::Vertex(v) => v,
        }
    }
}

impl std::fmt::Display for LoopStart {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LoopStart::HalfEdge(h) => write!(f, "{h}"),
            LoopStart::Vertex(v) => write!(f, "lone {v}"),
        }
    }
}

/// A polygon mesh in half-edge form with `f64` positions.
///
/// Dead (removed) elements keep their slots so ids stay stable; iterate live
/// elements with [`vertices`](Self::vertices), [`edges`](Self::edges),
/// [`faces`](Self::faces).
///
/// A face has one outer loop and, rarely, inner rings (Mäntylä's GWB faces
/// with several loops, made by [`kill_edge_make_ring`](Self::kill_edge_make_ring)
/// and [`kill_face_make_ring_hole`](Self::kill_face_make_ring_hole)). The
/// outer loop starts at `face_halfedge`; the rings live in a side table that
/// is empty for ordinary meshes. A face whose outer loop has no edge (made by
/// MVFS) stores `NONE` as its half-edge and its lone vertex in a second side
/// table. Every half-edge of a face lies on exactly one of its loops.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "MeshData", into = "MeshData")]
pub struct HalfEdgeMesh {
    positions: Vec<DVec3>,
    /// The connectivity, shared by copies of the mesh until one of them
    /// changes it (copy on write, `Arc::make_mut`): a copy that only moves
    /// vertices, such as a tool preview in every frame of a drag, copies
    /// the positions alone, and [`same_connectivity`](Self::same_connectivity)
    /// of two such copies is a pointer comparison.
    topology: Arc<Topology>,
}

/// The records of a [`HalfEdgeMesh`] apart from its positions.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
struct Topology {
    vertex_out: Vec<u32>,
    halfedges: Vec<HalfEdgeRecord>,
    face_halfedge: Vec<u32>,
    vertex_dead: Vec<bool>,
    edge_dead: Vec<bool>,
    face_dead: Vec<bool>,
    live_vertices: usize,
    live_edges: usize,
    live_faces: usize,
    /// Inner rings by face; no entry (never an empty list) for a face without
    /// rings, so meshes without rings pay nothing.
    face_rings: BTreeMap<FaceId, Vec<LoopStart>>,
    /// Faces whose outer loop is a lone vertex (no edges); their
    /// `face_halfedge` is `NONE`.
    face_lone_vertex: BTreeMap<FaceId, VertexId>,
}

/// Counts and topological invariants of a mesh, as `hedra info` prints them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeshStats {
    /// Live vertices V.
    pub vertices: usize,
    /// Live edges E.
    pub edges: usize,
    /// Live faces F.
    pub faces: usize,
    /// Closed loops of boundary half-edges; 0 when the mesh is invalid
    /// (they are not counted then).
    pub boundary_loops: usize,
    /// Inner rings of faces (loops L − F); zero for ordinary meshes.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub rings: usize,
    /// Connected components (shells), isolated vertices included; the loops
    /// of one face belong to one shell.
    pub shells: usize,
    /// V − E + F.
    pub euler_characteristic: i64,
    /// Handles H from the Euler–Poincaré formula V − E + F − (L − F) =
    /// 2(S − H), each boundary loop counted as a face of one loop (so
    /// χ = 2S − 2g − b without rings); `None` when the mesh is invalid.
    pub genus: Option<i64>,
    /// Valid and without boundary loops.
    pub closed: bool,
    /// The validator passed (it rejects non-manifold fans).
    pub manifold: bool,
    /// `Ok` when [`HalfEdgeMesh::validate`] passed, else the message of its
    /// [`ValidationError`](crate::ValidationError). Kept a message on
    /// purpose: `MeshStats` derives `Deserialize`, which a violation's
    /// `&'static str` fields cannot; call `validate` for the typed error.
    pub validation: Result<(), String>,
}

fn is_zero(x: &usize) -> bool {
    *x == 0
}

impl HalfEdgeMesh {
    /// An empty mesh.
    pub fn new() -> Self {
        Self::default()
    }

    /// A mesh of these positions and records.
    fn from_parts(positions: Vec<DVec3>, topology: Topology) -> Self {
        HalfEdgeMesh {
            positions,
            topology: Arc::new(topology),
        }
    }

    /// The connectivity for writing: copied first when another mesh shares it.
    fn topology_mut(&mut self) -> &mut Topology {
        Arc::make_mut(&mut self.topology)
    }

    // ----- counts --------------------------------------------------------

    /// Number of live vertices.
    pub fn vertex_count(&self) -> usize {
        self.topology.live_vertices
    }
    /// Number of live edges.
    pub fn edge_count(&self) -> usize {
        self.topology.live_edges
    }
    /// Number of live faces.
    pub fn face_count(&self) -> usize {
        self.topology.live_faces
    }
    /// Number of live half-edges (two per edge).
    pub fn halfedge_count(&self) -> usize {
        self.topology.live_edges * 2
    }
    /// Size of the vertex id space (live and dead).
    pub fn vertex_capacity(&self) -> usize {
        self.positions.len()
    }
    /// Size of the edge id space (live and dead).
    pub fn edge_capacity(&self) -> usize {
        self.topology.edge_dead.len()
    }
    /// Size of the face id space (live and dead).
    pub fn face_capacity(&self) -> usize {
        self.topology.face_halfedge.len()
    }

    // ----- liveness ------------------------------------------------------

    /// True when `v` is a live vertex (in range and not removed).
    pub fn is_vertex(&self, v: VertexId) -> bool {
        v.index() < self.topology.vertex_dead.len() && !self.topology.vertex_dead[v.index()]
    }
    /// True when `e` is a live edge.
    pub fn is_edge(&self, e: EdgeId) -> bool {
        e.index() < self.topology.edge_dead.len() && !self.topology.edge_dead[e.index()]
    }
    /// True when `h` belongs to a live edge.
    pub fn is_halfedge(&self, h: HalfEdgeId) -> bool {
        self.is_edge(h.edge())
    }
    /// True when `f` is a live face.
    pub fn is_face(&self, f: FaceId) -> bool {
        f.index() < self.topology.face_dead.len() && !self.topology.face_dead[f.index()]
    }

    // ----- iteration over live elements ----------------------------------

    /// Live vertices in id order.
    pub fn vertices(&self) -> impl Iterator<Item = VertexId> + '_ {
        (0..self.topology.vertex_dead.len() as u32)
            .filter(|&i| !self.topology.vertex_dead[i as usize])
            .map(VertexId)
    }
    /// Live edges in id order.
    pub fn edges(&self) -> impl Iterator<Item = EdgeId> + '_ {
        (0..self.topology.edge_dead.len() as u32)
            .filter(|&i| !self.topology.edge_dead[i as usize])
            .map(EdgeId)
    }
    /// Both half-edges of every live edge, in id order.
    pub fn halfedges(&self) -> impl Iterator<Item = HalfEdgeId> + '_ {
        self.edges().flat_map(|e| [e.halfedge(0), e.halfedge(1)])
    }
    /// Live faces in id order.
    pub fn faces(&self) -> impl Iterator<Item = FaceId> + '_ {
        (0..self.topology.face_dead.len() as u32)
            .filter(|&i| !self.topology.face_dead[i as usize])
            .map(FaceId)
    }

    // ----- connectivity queries (ids must be live) ------------------------

    #[inline]
    fn he(&self, h: HalfEdgeId) -> &HalfEdgeRecord {
        &self.topology.halfedges[h.index()]
    }
    /// Vertex the half-edge starts at.
    #[inline]
    pub fn origin(&self, h: HalfEdgeId) -> VertexId {
        VertexId(self.he(h).origin)
    }
    /// Vertex the half-edge points to.
    #[inline]
    pub fn target(&self, h: HalfEdgeId) -> VertexId {
        VertexId(self.he(h.twin()).origin)
    }
    /// The following half-edge of `h`'s loop (face or boundary).
    #[inline]
    pub fn next(&self, h: HalfEdgeId) -> HalfEdgeId {
        HalfEdgeId(self.he(h).next)
    }
    /// The preceding half-edge of `h`'s loop.
    #[inline]
    pub fn prev(&self, h: HalfEdgeId) -> HalfEdgeId {
        HalfEdgeId(self.he(h).prev)
    }
    /// The face on the left of the half-edge, `None` on a boundary.
    #[inline]
    pub fn face(&self, h: HalfEdgeId) -> Option<FaceId> {
        let f = self.he(h).face;
        (f != NONE).then_some(FaceId(f))
    }
    /// True when `h` has no face (it runs along a boundary loop).
    #[inline]
    pub fn is_boundary_halfedge(&self, h: HalfEdgeId) -> bool {
        self.he(h).face == NONE
    }
    /// True when either side of `e` has no face.
    pub fn is_boundary_edge(&self, e: EdgeId) -> bool {
        self.is_boundary_halfedge(e.halfedge(0)) || self.is_boundary_halfedge(e.halfedge(1))
    }
    /// One outgoing half-edge of the vertex (a boundary one if the vertex is on
    /// a boundary); `None` for an isolated vertex.
    #[inline]
    pub fn vertex_halfedge(&self, v: VertexId) -> Option<HalfEdgeId> {
        let h = self.topology.vertex_out[v.index()];
        (h != NONE).then_some(HalfEdgeId(h))
    }
    /// True when `v` lies on a boundary (false for an isolated vertex).
    pub fn is_boundary_vertex(&self, v: VertexId) -> bool {
        self.vertex_halfedge(v)
            .is_some_and(|h| self.is_boundary_halfedge(h))
    }
    /// True when `v` has no edges.
    pub fn is_isolated_vertex(&self, v: VertexId) -> bool {
        self.topology.vertex_out[v.index()] == NONE
    }
    /// One half-edge of the face's outer loop. For a face without edges
    /// (see [`lone_vertex_face`](Self::lone_vertex_face)) this is an invalid
    /// id (`u32::MAX`); use [`outer_loop`](Self::outer_loop) where such faces
    /// may occur.
    #[inline]
    pub fn face_halfedge(&self, f: FaceId) -> HalfEdgeId {
        HalfEdgeId(self.topology.face_halfedge[f.index()])
    }
    /// The two vertices of an edge, in the direction of its half-edge 0.
    pub fn edge_vertices(&self, e: EdgeId) -> [VertexId; 2] {
        let h = e.halfedge(0);
        [self.origin(h), self.target(h)]
    }
    /// The faces on both sides of an edge (half-edge 0's face first).
    pub fn edge_faces(&self, e: EdgeId) -> [Option<FaceId>; 2] {
        [self.face(e.halfedge(0)), self.face(e.halfedge(1))]
    }

    /// Half-edges of a face's outer loop, starting at
    /// [`face_halfedge`](Self::face_halfedge); none for a face without edges.
    /// Inner rings are not included: see [`face_loops`](Self::face_loops).
    pub fn face_halfedges(&self, f: FaceId) -> LoopIter<'_> {
        if self.topology.face_halfedge[f.index()] == NONE {
            return LoopIter {
                mesh: self,
                start: HalfEdgeId(NONE),
                current: None,
                guard: 0,
            };
        }
        self.loop_from(self.face_halfedge(f))
    }

    // ----- loops and rings ---------------------------------------------------

    /// Appends every live face's corners, in face id order, each face from
    /// its first half-edge: the raw vertex and edge id of each corner, and
    /// after each face the number of corners so far. One walk of the
    /// records for bulk conversions (subdivision cages). Faces with inner
    /// rings give their outer loop only; faces without edges give none.
    pub(crate) fn append_face_corners(
        &self,
        face_offsets: &mut Vec<u32>,
        corner_vertex: &mut Vec<u32>,
        corner_edge: &mut Vec<u32>,
    ) {
        for (f, &start) in self.topology.face_halfedge.iter().enumerate() {
            if self.topology.face_dead[f] {
                continue;
            }
            if start != NONE {
                let mut h = start;
                // A valid loop closes within the half-edge count.
                for _ in 0..self.topology.halfedges.len() {
                    let r = &self.topology.halfedges[h as usize];
                    corner_vertex.push(r.origin);
                    corner_edge.push(h / 2);
                    h = r.next;
                    if h == start {
                        break;
                    }
                }
            }
            face_offsets.push(corner_vertex.len() as u32);
        }
    }

    /// True when some face has an inner ring.
    pub fn has_rings(&self) -> bool {
        !self.topology.face_rings.is_empty()
    }
    /// True when some face has no edges (its outer loop is a lone vertex).
    pub fn has_edgeless_faces(&self) -> bool {
        !self.topology.face_lone_vertex.is_empty()
    }
    /// The first face that is not a plain polygon (one loop of half-edges):
    /// a face with rings or without edges. Code that triangulates, refines
    /// or exports faces as polygons refuses a mesh where this is `Some`.
    pub fn first_non_polygon_face(&self) -> Option<FaceId> {
        let a = self.topology.face_rings.keys().next().copied();
        let b = self.topology.face_lone_vertex.keys().next().copied();
        match (a, b) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }
    /// True when the face is a plain polygon: its only loop has edges.
    pub fn is_polygon_face(&self, f: FaceId) -> bool {
        self.topology.face_halfedge[f.index()] != NONE && !self.topology.face_rings.contains_key(&f)
    }
    /// The inner rings of a face (empty for almost every face).
    pub fn face_rings(&self, f: FaceId) -> &[LoopStart] {
        self.topology.face_rings.get(&f).map_or(&[], Vec::as_slice)
    }
    /// Number of inner rings over all faces (L − F).
    pub fn ring_count(&self) -> usize {
        self.topology.face_rings.values().map(Vec::len).sum()
    }
    /// Number of loops L: one outer loop per face plus the rings.
    pub fn loop_count(&self) -> usize {
        self.topology.live_faces + self.ring_count()
    }
    /// The lone vertex of a face without edges (made by MVFS), else `None`.
    pub fn lone_vertex_face(&self, f: FaceId) -> Option<VertexId> {
        self.topology.face_lone_vertex.get(&f).copied()
    }
    /// The outer loop of a face.
    pub fn outer_loop(&self, f: FaceId) -> LoopStart {
        match self.topology.face_lone_vertex.get(&f) {
            Some(&v) => LoopStart::Vertex(v),
            None => LoopStart::HalfEdge(self.face_halfedge(f)),
        }
    }
    /// Every loop of a face: the outer loop first, then the rings.
    pub fn face_loops(&self, f: FaceId) -> impl Iterator<Item = LoopStart> + '_ {
        std::iter::once(self.outer_loop(f)).chain(self.face_rings(f).iter().copied())
    }
    /// Half-edges of one loop (none for a lone vertex).
    pub fn loop_halfedges(&self, l: LoopStart) -> LoopIter<'_> {
        match l {
            LoopStart::HalfEdge(h) => self.loop_from(h),
            LoopStart::Vertex(_) => LoopIter {
                mesh: self,
                start: HalfEdgeId(NONE),
                current: None,
                guard: 0,
            },
        }
    }
    /// Half-edges of every loop of a face (outer loop first).
    pub fn face_all_halfedges(&self, f: FaceId) -> impl Iterator<Item = HalfEdgeId> + '_ {
        self.face_loops(f).flat_map(|l| self.loop_halfedges(l))
    }
    /// The face and loop a lone vertex belongs to (`None` for a vertex with
    /// edges or a free isolated vertex). O(number of edge-less loops).
    pub fn lone_vertex_loop(&self, v: VertexId) -> Option<FaceId> {
        if let Some((&f, _)) = self
            .topology
            .face_lone_vertex
            .iter()
            .find(|(_, x)| **x == v)
        {
            return Some(f);
        }
        self.topology
            .face_rings
            .iter()
            .find(|(_, rings)| rings.contains(&LoopStart::Vertex(v)))
            .map(|(&f, _)| f)
    }
    /// Half-edges of the loop that contains `h` (a face or a boundary loop).
    pub fn loop_from(&self, h: HalfEdgeId) -> LoopIter<'_> {
        LoopIter {
            mesh: self,
            start: h,
            current: Some(h),
            guard: self.topology.halfedges.len(),
        }
    }
    /// Vertices of a face in order (counter-clockwise seen from the front).
    pub fn face_vertices(&self, f: FaceId) -> impl Iterator<Item = VertexId> + '_ {
        self.face_halfedges(f).map(|h| self.origin(h))
    }
    /// Number of sides of a face.
    pub fn face_degree(&self, f: FaceId) -> usize {
        self.face_halfedges(f).count()
    }
    /// Faces sharing an edge with `f` (each once per shared edge).
    pub fn face_neighbors(&self, f: FaceId) -> impl Iterator<Item = FaceId> + '_ {
        self.face_halfedges(f).filter_map(|h| self.face(h.twin()))
    }

    /// Outgoing half-edges of a vertex, circulating `twin(prev(h))`.
    pub fn vertex_outgoing(&self, v: VertexId) -> FanIter<'_> {
        let start = self.vertex_halfedge(v);
        FanIter {
            mesh: self,
            start,
            current: start,
            guard: self.topology.halfedges.len(),
        }
    }
    /// Vertices joined to `v` by an edge.
    pub fn vertex_neighbors(&self, v: VertexId) -> impl Iterator<Item = VertexId> + '_ {
        self.vertex_outgoing(v).map(|h| self.target(h))
    }
    /// Faces around a vertex.
    pub fn vertex_faces(&self, v: VertexId) -> impl Iterator<Item = FaceId> + '_ {
        self.vertex_outgoing(v).filter_map(|h| self.face(h))
    }
    /// Number of edges at a vertex.
    pub fn vertex_valence(&self, v: VertexId) -> usize {
        self.vertex_outgoing(v).count()
    }
    /// The half-edge from `a` to `b`, if they are joined by an edge.
    pub fn find_halfedge(&self, a: VertexId, b: VertexId) -> Option<HalfEdgeId> {
        self.vertex_outgoing(a).find(|&h| self.target(h) == b)
    }
    /// The edge joining `a` and `b`, if any.
    pub fn find_edge(&self, a: VertexId, b: VertexId) -> Option<EdgeId> {
        self.find_halfedge(a, b).map(HalfEdgeId::edge)
    }

    /// Every boundary loop, as the half-edges (without faces) around each hole.
    pub fn boundary_loops(&self) -> Vec<Vec<HalfEdgeId>> {
        let mut seen = vec![false; self.topology.halfedges.len()];
        let mut loops = Vec::new();
        for h in self.halfedges() {
            if seen[h.index()] || !self.is_boundary_halfedge(h) {
                continue;
            }
            let lp: Vec<HalfEdgeId> = self.loop_from(h).collect();
            for &x in &lp {
                seen[x.index()] = true;
            }
            loops.push(lp);
        }
        loops
    }

    // ----- geometry ------------------------------------------------------

    /// Position of vertex `v`.
    #[inline]
    pub fn position(&self, v: VertexId) -> DVec3 {
        self.positions[v.index()]
    }
    /// Moves vertex `v` to `p` (connectivity is unchanged; `p` is not
    /// checked for finiteness, [`validate`](Self::validate) reports it).
    #[inline]
    pub fn set_position(&mut self, v: VertexId, p: DVec3) {
        self.positions[v.index()] = p;
    }
    /// Positions indexed by vertex id (dead slots included).
    #[inline]
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }
    /// Mutable positions indexed by vertex id; connectivity cannot change this way.
    #[inline]
    pub fn positions_mut(&mut self) -> &mut [DVec3] {
        &mut self.positions
    }

    /// Area-weighted face normal (not normalised) by Newell's method, which is
    /// exact for planar polygons and robust for non-planar ones.
    /// Inner rings, oriented the other way round, subtract their area.
    pub fn face_area_vector(&self, f: FaceId) -> DVec3 {
        // Summed in the order of `query::polygon_area_vector`: the same bits
        // for a face without rings.
        let mut n = DVec3::ZERO;
        for h in self.face_halfedges(f) {
            let a = self.position(self.origin(h));
            let b = self.position(self.target(h));
            n += a.cross(b);
        }
        for &r in self.face_rings(f) {
            for h in self.loop_halfedges(r) {
                n += self
                    .position(self.origin(h))
                    .cross(self.position(self.target(h)));
            }
        }
        n * 0.5
    }
    /// Unit face normal; zero for a degenerate face.
    pub fn face_normal(&self, f: FaceId) -> DVec3 {
        self.face_area_vector(f).normalize_or_zero()
    }
    /// Unit normal of a region of faces: the sum of their area vectors
    /// (Newell), normalised, so a large face counts more than a small one.
    /// The one definition that region extrude and inset move along and the
    /// extrude tool's drag follows. Zero when the normals cancel out.
    pub fn region_normal(&self, faces: &[FaceId]) -> DVec3 {
        faces
            .iter()
            .map(|&f| self.face_area_vector(f))
            .sum::<DVec3>()
            .normalize_or_zero()
    }
    /// Average of the face's vertices (of its outer loop; a face without
    /// edges is at its lone vertex).
    pub fn face_centroid(&self, f: FaceId) -> DVec3 {
        if let Some(v) = self.lone_vertex_face(f) {
            return self.position(v);
        }
        let mut sum = DVec3::ZERO;
        let mut n = 0.0;
        for v in self.face_vertices(f) {
            sum += self.position(v);
            n += 1.0;
        }
        sum / n
    }
    /// Unit vertex normal: the area-weighted average of the normals around it.
    pub fn vertex_normal(&self, v: VertexId) -> DVec3 {
        self.vertex_faces(v)
            .map(|f| self.face_area_vector(f))
            .sum::<DVec3>()
            .normalize_or_zero()
    }
    /// Midpoint of edge `e`'s two ends.
    pub fn edge_midpoint(&self, e: EdgeId) -> DVec3 {
        let [a, b] = self.edge_vertices(e);
        (self.position(a) + self.position(b)) * 0.5
    }
    /// Distance between edge `e`'s two ends.
    pub fn edge_length(&self, e: EdgeId) -> f64 {
        let [a, b] = self.edge_vertices(e);
        self.position(a).distance(self.position(b))
    }
    /// Axis-aligned bounds of the live vertices, `None` for an empty mesh.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut it = self.vertices().map(|v| self.position(v));
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }
    /// Enclosed volume by the divergence theorem (meaningful for closed meshes).
    pub fn volume(&self) -> f64 {
        self.faces()
            .map(|f| {
                let c = self.face_centroid(f);
                c.dot(self.face_area_vector(f)) / 3.0
            })
            .sum()
    }

    // ----- topology summary ------------------------------------------------

    /// Connected components; isolated vertices count as one each.
    pub fn shell_count(&self) -> usize {
        self.components().1
    }

    /// Component index per vertex slot (dead slots get `usize::MAX`) and the
    /// number of components.
    pub fn components(&self) -> (Vec<usize>, usize) {
        let mut comp = vec![usize::MAX; self.positions.len()];
        let mut count = 0;
        let mut stack = Vec::new();
        for v in self.vertices() {
            if comp[v.index()] != usize::MAX {
                continue;
            }
            comp[v.index()] = count;
            stack.push(v);
            while let Some(x) = stack.pop() {
                for w in self.vertex_neighbors(x) {
                    if comp[w.index()] == usize::MAX {
                        comp[w.index()] = count;
                        stack.push(w);
                    }
                }
            }
            count += 1;
        }
        if self.topology.face_rings.is_empty() {
            return (comp, count);
        }
        // The loops of one face belong to one shell (a ring may be a loop of
        // another component glued in by KFMRH): merge their components.
        let mut parent: Vec<usize> = (0..count).collect();
        fn root(parent: &mut [usize], mut x: usize) -> usize {
            while parent[x] != x {
                parent[x] = parent[parent[x]];
                x = parent[x];
            }
            x
        }
        for (&f, rings) in &self.topology.face_rings {
            let a = comp[self.outer_loop(f).vertex(self).index()];
            for r in rings {
                let b = comp[r.vertex(self).index()];
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                parent[ra.max(rb)] = ra.min(rb);
            }
        }
        let mut label = vec![usize::MAX; count];
        let mut merged = 0;
        for c in comp.iter_mut().filter(|c| **c != usize::MAX) {
            let r = root(&mut parent, *c);
            if label[r] == usize::MAX {
                label[r] = merged;
                merged += 1;
            }
            *c = label[r];
        }
        (comp, merged)
    }

    /// Counts and invariants for reports (`hedra info`).
    pub fn stats(&self) -> MeshStats {
        let validation = self.validate().map_err(|e| e.to_string());
        let boundary_loops = if validation.is_ok() {
            self.boundary_loops().len()
        } else {
            0
        };
        let shells = self.shell_count();
        let rings = self.ring_count();
        let euler =
            self.vertex_count() as i64 - self.edge_count() as i64 + self.face_count() as i64;
        let two_g = 2 * shells as i64 - boundary_loops as i64 - euler + rings as i64;
        let genus = (validation.is_ok() && two_g >= 0 && two_g % 2 == 0).then_some(two_g / 2);
        MeshStats {
            vertices: self.vertex_count(),
            edges: self.edge_count(),
            faces: self.face_count(),
            boundary_loops,
            rings,
            shells,
            euler_characteristic: euler,
            genus,
            closed: validation.is_ok() && boundary_loops == 0,
            manifold: validation.is_ok(),
            validation,
        }
    }
}

/// Walks a loop of half-edges by `next`; stops after one turn (or, on a
/// corrupted mesh, after visiting as many half-edges as exist).
pub struct LoopIter<'a> {
    mesh: &'a HalfEdgeMesh,
    start: HalfEdgeId,
    current: Option<HalfEdgeId>,
    guard: usize,
}

impl Iterator for LoopIter<'_> {
    type Item = HalfEdgeId;
    fn next(&mut self) -> Option<HalfEdgeId> {
        let h = self.current?;
        if self.guard == 0 {
            self.current = None;
            return None;
        }
        self.guard -= 1;
        let n = self.mesh.next(h);
        self.current = (n != self.start).then_some(n);
        Some(h)
    }
}

/// Circulates the outgoing half-edges of a vertex by `twin(prev(h))`.
pub struct FanIter<'a> {
    mesh: &'a HalfEdgeMesh,
    start: Option<HalfEdgeId>,
    current: Option<HalfEdgeId>,
    guard: usize,
}

impl Iterator for FanIter<'_> {
    type Item = HalfEdgeId;
    fn next(&mut self) -> Option<HalfEdgeId> {
        let h = self.current?;
        if self.guard == 0 {
            self.current = None;
            return None;
        }
        self.guard -= 1;
        let n = self.mesh.prev(h).twin();
        self.current = (Some(n) != self.start).then_some(n);
        Some(h)
    }
}
