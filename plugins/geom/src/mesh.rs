//! The half-edge mesh: connectivity, positions, traversal and the validator.
//!
//! Half-edge structure as taught in seed 000 (Bán, "half-edge: vertex, sym, face,
//! next") and seed 001; storage follows pmp-library's `SurfaceMesh`: one record
//! per vertex, half-edge and face, twins implicit (`h ^ 1`). Every half-edge,
//! boundary ones included, has `next`/`prev`: boundary half-edges (no face) form
//! the loops around holes, so circulating `twin(prev(h))` around a vertex visits
//! all its outgoing half-edges. A boundary vertex stores a boundary half-edge
//! as its outgoing one, so boundary tests are O(1).
//!
//! Only [`crate::euler`] changes connectivity; everything else reads it.

use crate::ids::{EdgeId, FaceId, HalfEdgeId, NONE, VertexId};
use glam::DVec3;
use serde::{Deserialize, Serialize};

#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct HalfEdgeRecord {
    pub origin: u32,
    pub next: u32,
    pub prev: u32,
    pub face: u32,
}

/// A polygon mesh in half-edge form with `f64` positions.
///
/// Dead (removed) elements keep their slots so ids stay stable; iterate live
/// elements with [`vertices`](Self::vertices), [`edges`](Self::edges),
/// [`faces`](Self::faces).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "MeshData", into = "MeshData")]
pub struct HalfEdgeMesh {
    pub(crate) positions: Vec<DVec3>,
    pub(crate) vertex_out: Vec<u32>,
    pub(crate) halfedges: Vec<HalfEdgeRecord>,
    pub(crate) face_halfedge: Vec<u32>,
    pub(crate) vertex_dead: Vec<bool>,
    pub(crate) edge_dead: Vec<bool>,
    pub(crate) face_dead: Vec<bool>,
    pub(crate) live_vertices: usize,
    pub(crate) live_edges: usize,
    pub(crate) live_faces: usize,
}

/// Counts and topological invariants of a mesh, as `hedra info` prints them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeshStats {
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    pub boundary_loops: usize,
    /// Connected components (shells), isolated vertices included.
    pub shells: usize,
    /// V − E + F.
    pub euler_characteristic: i64,
    /// From χ = 2S − 2g − b, over components; `None` when the mesh is invalid.
    pub genus: Option<i64>,
    pub closed: bool,
    pub manifold: bool,
    /// `None` when [`HalfEdgeMesh::validate`] passed, else its first problems.
    pub validation: Result<(), String>,
}

impl HalfEdgeMesh {
    /// An empty mesh.
    pub fn new() -> Self {
        Self::default()
    }

    // ----- counts --------------------------------------------------------

    /// Number of live vertices.
    pub fn vertex_count(&self) -> usize {
        self.live_vertices
    }
    /// Number of live edges.
    pub fn edge_count(&self) -> usize {
        self.live_edges
    }
    /// Number of live faces.
    pub fn face_count(&self) -> usize {
        self.live_faces
    }
    /// Number of live half-edges (two per edge).
    pub fn halfedge_count(&self) -> usize {
        self.live_edges * 2
    }
    /// Size of the vertex id space (live and dead).
    pub fn vertex_capacity(&self) -> usize {
        self.positions.len()
    }
    /// Size of the edge id space (live and dead).
    pub fn edge_capacity(&self) -> usize {
        self.edge_dead.len()
    }
    /// Size of the face id space (live and dead).
    pub fn face_capacity(&self) -> usize {
        self.face_halfedge.len()
    }

    // ----- liveness ------------------------------------------------------

    pub fn is_vertex(&self, v: VertexId) -> bool {
        v.index() < self.vertex_dead.len() && !self.vertex_dead[v.index()]
    }
    pub fn is_edge(&self, e: EdgeId) -> bool {
        e.index() < self.edge_dead.len() && !self.edge_dead[e.index()]
    }
    pub fn is_halfedge(&self, h: HalfEdgeId) -> bool {
        self.is_edge(h.edge())
    }
    pub fn is_face(&self, f: FaceId) -> bool {
        f.index() < self.face_dead.len() && !self.face_dead[f.index()]
    }

    // ----- iteration over live elements ----------------------------------

    pub fn vertices(&self) -> impl Iterator<Item = VertexId> + '_ {
        (0..self.vertex_dead.len() as u32)
            .filter(|&i| !self.vertex_dead[i as usize])
            .map(VertexId)
    }
    pub fn edges(&self) -> impl Iterator<Item = EdgeId> + '_ {
        (0..self.edge_dead.len() as u32)
            .filter(|&i| !self.edge_dead[i as usize])
            .map(EdgeId)
    }
    pub fn halfedges(&self) -> impl Iterator<Item = HalfEdgeId> + '_ {
        self.edges().flat_map(|e| [e.halfedge(0), e.halfedge(1)])
    }
    pub fn faces(&self) -> impl Iterator<Item = FaceId> + '_ {
        (0..self.face_dead.len() as u32)
            .filter(|&i| !self.face_dead[i as usize])
            .map(FaceId)
    }

    // ----- connectivity queries (ids must be live) ------------------------

    #[inline]
    fn he(&self, h: HalfEdgeId) -> &HalfEdgeRecord {
        &self.halfedges[h.index()]
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
    #[inline]
    pub fn next(&self, h: HalfEdgeId) -> HalfEdgeId {
        HalfEdgeId(self.he(h).next)
    }
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
    #[inline]
    pub fn is_boundary_halfedge(&self, h: HalfEdgeId) -> bool {
        self.he(h).face == NONE
    }
    pub fn is_boundary_edge(&self, e: EdgeId) -> bool {
        self.is_boundary_halfedge(e.halfedge(0)) || self.is_boundary_halfedge(e.halfedge(1))
    }
    /// One outgoing half-edge of the vertex (a boundary one if the vertex is on
    /// a boundary); `None` for an isolated vertex.
    #[inline]
    pub fn vertex_halfedge(&self, v: VertexId) -> Option<HalfEdgeId> {
        let h = self.vertex_out[v.index()];
        (h != NONE).then_some(HalfEdgeId(h))
    }
    pub fn is_boundary_vertex(&self, v: VertexId) -> bool {
        self.vertex_halfedge(v)
            .is_some_and(|h| self.is_boundary_halfedge(h))
    }
    pub fn is_isolated_vertex(&self, v: VertexId) -> bool {
        self.vertex_out[v.index()] == NONE
    }
    /// One half-edge of the face's loop.
    #[inline]
    pub fn face_halfedge(&self, f: FaceId) -> HalfEdgeId {
        HalfEdgeId(self.face_halfedge[f.index()])
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

    /// Half-edges of a face loop, starting at [`face_halfedge`](Self::face_halfedge).
    pub fn face_halfedges(&self, f: FaceId) -> LoopIter<'_> {
        self.loop_from(self.face_halfedge(f))
    }
    /// Half-edges of the loop that contains `h` (a face or a boundary loop).
    pub fn loop_from(&self, h: HalfEdgeId) -> LoopIter<'_> {
        LoopIter {
            mesh: self,
            start: h,
            current: Some(h),
            guard: self.halfedges.len(),
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
            guard: self.halfedges.len(),
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
        let mut seen = vec![false; self.halfedges.len()];
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

    #[inline]
    pub fn position(&self, v: VertexId) -> DVec3 {
        self.positions[v.index()]
    }
    #[inline]
    pub fn set_position(&mut self, v: VertexId, p: DVec3) {
        self.positions[v.index()] = p;
    }
    /// Positions indexed by vertex id (dead slots included).
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
    }
    /// Mutable positions indexed by vertex id; connectivity cannot change this way.
    pub fn positions_mut(&mut self) -> &mut [DVec3] {
        &mut self.positions
    }

    /// Area-weighted face normal (not normalised) by Newell's method, which is
    /// exact for planar polygons and robust for non-planar ones.
    pub fn face_area_vector(&self, f: FaceId) -> DVec3 {
        let mut n = DVec3::ZERO;
        for h in self.face_halfedges(f) {
            let a = self.position(self.origin(h));
            let b = self.position(self.target(h));
            n += a.cross(b);
        }
        n * 0.5
    }
    /// Unit face normal; zero for a degenerate face.
    pub fn face_normal(&self, f: FaceId) -> DVec3 {
        self.face_area_vector(f).normalize_or_zero()
    }
    /// Average of the face's vertices.
    pub fn face_centroid(&self, f: FaceId) -> DVec3 {
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
    pub fn edge_midpoint(&self, e: EdgeId) -> DVec3 {
        let [a, b] = self.edge_vertices(e);
        (self.position(a) + self.position(b)) * 0.5
    }
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
        (comp, count)
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
        let euler =
            self.vertex_count() as i64 - self.edge_count() as i64 + self.face_count() as i64;
        let two_g = 2 * shells as i64 - boundary_loops as i64 - euler;
        let genus = (validation.is_ok() && two_g >= 0 && two_g % 2 == 0).then_some(two_g / 2);
        MeshStats {
            vertices: self.vertex_count(),
            edges: self.edge_count(),
            faces: self.face_count(),
            boundary_loops,
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

/// The stored form of a mesh in scene files: raw records, so that every id
/// survives a save and load. Loading validates the result.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct MeshData {
    /// Vertex positions by vertex id.
    pub positions: Vec<DVec3>,
    /// Outgoing half-edge per vertex id, `-1` for none.
    pub vertex_halfedge: Vec<i64>,
    /// Per half-edge id: `(origin, next, prev, face)`, face `-1` on a boundary.
    pub halfedges: Vec<(u32, u32, u32, i64)>,
    /// One half-edge per face id.
    pub face_halfedge: Vec<u32>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub dead_vertices: Vec<u32>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub dead_edges: Vec<u32>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub dead_faces: Vec<u32>,
}

fn opt_to_i64(x: u32) -> i64 {
    if x == NONE { -1 } else { x as i64 }
}

impl From<HalfEdgeMesh> for MeshData {
    fn from(m: HalfEdgeMesh) -> Self {
        let dead = |d: &[bool]| -> Vec<u32> {
            d.iter()
                .enumerate()
                .filter(|(_, x)| **x)
                .map(|(i, _)| i as u32)
                .collect()
        };
        MeshData {
            vertex_halfedge: m.vertex_out.iter().map(|&x| opt_to_i64(x)).collect(),
            halfedges: m
                .halfedges
                .iter()
                .map(|r| (r.origin, r.next, r.prev, opt_to_i64(r.face)))
                .collect(),
            face_halfedge: m.face_halfedge.clone(),
            dead_vertices: dead(&m.vertex_dead),
            dead_edges: dead(&m.edge_dead),
            dead_faces: dead(&m.face_dead),
            positions: m.positions,
        }
    }
}

impl TryFrom<MeshData> for HalfEdgeMesh {
    type Error = String;
    fn try_from(d: MeshData) -> Result<Self, String> {
        let nv = d.positions.len();
        if d.vertex_halfedge.len() != nv {
            return Err(format!(
                "mesh has {nv} positions but {} vertex records",
                d.vertex_halfedge.len()
            ));
        }
        if d.halfedges.len() % 2 != 0 {
            return Err(format!("odd number of half-edges ({})", d.halfedges.len()));
        }
        let to_raw = |x: i64, what: &str| -> Result<u32, String> {
            if x == -1 {
                Ok(NONE)
            } else if (0..NONE as i64).contains(&x) {
                Ok(x as u32)
            } else {
                Err(format!("{what} id {x} is out of range"))
            }
        };
        let mut m = HalfEdgeMesh {
            positions: d.positions,
            vertex_out: d
                .vertex_halfedge
                .iter()
                .map(|&x| to_raw(x, "half-edge"))
                .collect::<Result<_, _>>()?,
            halfedges: d
                .halfedges
                .iter()
                .map(|&(origin, next, prev, face)| {
                    Ok(HalfEdgeRecord {
                        origin,
                        next,
                        prev,
                        face: to_raw(face, "face")?,
                    })
                })
                .collect::<Result<_, String>>()?,
            face_halfedge: d.face_halfedge,
            ..Default::default()
        };
        m.vertex_dead = vec![false; nv];
        m.edge_dead = vec![false; m.halfedges.len() / 2];
        m.face_dead = vec![false; m.face_halfedge.len()];
        for (list, flags, what) in [
            (&d.dead_vertices, &mut m.vertex_dead, "vertex"),
            (&d.dead_edges, &mut m.edge_dead, "edge"),
            (&d.dead_faces, &mut m.face_dead, "face"),
        ] {
            for &i in list {
                *flags
                    .get_mut(i as usize)
                    .ok_or_else(|| format!("dead {what} id {i} is out of range"))? = true;
            }
        }
        m.live_vertices = m.vertex_dead.iter().filter(|d| !**d).count();
        m.live_edges = m.edge_dead.iter().filter(|d| !**d).count();
        m.live_faces = m.face_dead.iter().filter(|d| !**d).count();
        m.validate().map_err(|e| e.to_string())?;
        Ok(m)
    }
}
