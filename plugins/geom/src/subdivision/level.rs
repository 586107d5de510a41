//! One refinement level's connectivity in flat arrays: face-vertex lists plus
//! the edge and vertex tables the subdivision masks read. This is the layout
//! of OpenSubdiv's `Vtr::Level`: refining walks arrays, never pointers, so a
//! level of a hundred thousand faces refines in milliseconds.

use std::collections::HashMap;

use super::{BoundaryInterpolation, Creases, INFINITE_SHARPNESS};
use crate::{EdgeId, FaceId, HalfEdgeMesh, VertexId};

/// "No element" in the `u32` tables (a boundary edge's missing second face).
pub(crate) const NONE: u32 = u32::MAX;

/// Connectivity and sharpness of one level. Corner `c` of face `f` (for
/// `c` in `face_offsets[f]..face_offsets[f + 1]`) is the vertex
/// `face_vertices[c]`; `face_edges[c]` is the edge from that corner to the
/// next one.
#[derive(Clone, Debug, Default)]
pub(crate) struct Level {
    pub vertex_count: usize,
    pub face_offsets: Vec<u32>,
    pub face_vertices: Vec<u32>,
    pub face_edges: Vec<u32>,
    pub corner_face: Vec<u32>,
    pub edge_vertices: Vec<[u32; 2]>,
    /// The one or two faces of each edge; the second is [`NONE`] on a boundary.
    pub edge_faces: Vec<[u32; 2]>,
    /// Crease sharpness per edge (boundary edges are infinitely sharp).
    pub edge_sharpness: Vec<f32>,
    /// Corner sharpness per vertex.
    pub vertex_sharpness: Vec<f32>,
    pub vertex_edge_offsets: Vec<u32>,
    pub vertex_edges: Vec<u32>,
    pub vertex_corner_offsets: Vec<u32>,
    /// Face corners at each vertex (a corner names its face through `corner_face`).
    pub vertex_corners: Vec<u32>,
    /// For every face, the cage face (dense index) it descends from.
    pub face_origin: Vec<u32>,
}

/// Dense numbering of a half-edge mesh's live elements, so that results can
/// be mapped back to the cage's ids.
#[derive(Clone, Debug, Default)]
pub(crate) struct CageMap {
    pub vertices: Vec<VertexId>,
    pub edges: Vec<EdgeId>,
    pub faces: Vec<FaceId>,
}

impl Level {
    pub fn face_count(&self) -> usize {
        self.face_offsets.len() - 1
    }
    pub fn edge_count(&self) -> usize {
        self.edge_vertices.len()
    }
    pub fn face_corners(&self, f: u32) -> std::ops::Range<usize> {
        self.face_offsets[f as usize] as usize..self.face_offsets[f as usize + 1] as usize
    }
    pub fn vertex_edges(&self, v: u32) -> &[u32] {
        let r = self.vertex_edge_offsets[v as usize] as usize
            ..self.vertex_edge_offsets[v as usize + 1] as usize;
        &self.vertex_edges[r]
    }
    pub fn vertex_corners(&self, v: u32) -> &[u32] {
        let r = self.vertex_corner_offsets[v as usize] as usize
            ..self.vertex_corner_offsets[v as usize + 1] as usize;
        &self.vertex_corners[r]
    }
    /// The other end of edge `e` seen from `v`.
    pub fn other_end(&self, e: u32, v: u32) -> u32 {
        let [a, b] = self.edge_vertices[e as usize];
        if a == v { b } else { a }
    }
    pub fn is_boundary_edge(&self, e: u32) -> bool {
        self.edge_faces[e as usize][1] == NONE
    }
    /// Corner before `c` in its face.
    pub fn prev_corner(&self, c: usize) -> usize {
        let f = self.corner_face[c];
        let r = self.face_corners(f);
        if c == r.start { r.end - 1 } else { c - 1 }
    }
    /// Corner after `c` in its face.
    pub fn next_corner(&self, c: usize) -> usize {
        let f = self.corner_face[c];
        let r = self.face_corners(f);
        if c + 1 == r.end { r.start } else { c + 1 }
    }
    /// True when every face has `n` sides.
    pub fn all_faces_have(&self, n: u32) -> bool {
        self.face_offsets.windows(2).all(|w| w[1] - w[0] == n)
    }

    /// The level of a half-edge mesh's live faces with the given creases.
    /// Boundary edges are infinitely sharp; with
    /// [`BoundaryInterpolation::EdgesAndCorners`] so are boundary vertices
    /// that touch a single face (OpenSubdiv's `VTX_BOUNDARY_EDGE_AND_CORNER`).
    pub fn from_mesh(
        mesh: &HalfEdgeMesh,
        creases: &Creases,
        boundary: BoundaryInterpolation,
    ) -> (Level, CageMap) {
        let mut map = CageMap::default();
        let mut vmap = vec![NONE; mesh.vertex_capacity()];
        for v in mesh.vertices().filter(|&v| !mesh.is_isolated_vertex(v)) {
            vmap[v.index()] = map.vertices.len() as u32;
            map.vertices.push(v);
        }
        let mut emap = vec![NONE; mesh.edge_capacity()];
        let mut edge_vertices = Vec::with_capacity(mesh.edge_count());
        for e in mesh.edges() {
            emap[e.index()] = map.edges.len() as u32;
            map.edges.push(e);
            let [a, b] = mesh.edge_vertices(e);
            edge_vertices.push([vmap[a.index()], vmap[b.index()]]);
        }
        let mut level = Level {
            vertex_count: map.vertices.len(),
            face_offsets: vec![0],
            edge_vertices,
            ..Level::default()
        };
        for f in mesh.faces() {
            for h in mesh.face_halfedges(f) {
                level.face_vertices.push(vmap[mesh.origin(h).index()]);
                level.face_edges.push(emap[h.edge().index()]);
            }
            level.face_offsets.push(level.face_vertices.len() as u32);
            level.face_origin.push(map.faces.len() as u32);
            map.faces.push(f);
        }
        level.edge_sharpness = map
            .edges
            .iter()
            .map(|e| clamp_sharpness(creases.edges.get(e).copied().unwrap_or(0.0)))
            .collect();
        level.vertex_sharpness = map
            .vertices
            .iter()
            .map(|v| clamp_sharpness(creases.vertices.get(v).copied().unwrap_or(0.0)))
            .collect();
        level.finish();
        for e in 0..level.edge_count() {
            if level.is_boundary_edge(e as u32) {
                level.edge_sharpness[e] = INFINITE_SHARPNESS;
            }
        }
        if boundary == BoundaryInterpolation::EdgesAndCorners {
            for v in 0..level.vertex_count {
                let on_boundary = level
                    .vertex_edges(v as u32)
                    .iter()
                    .any(|&e| level.is_boundary_edge(e));
                if on_boundary && level.vertex_corners(v as u32).len() == 1 {
                    level.vertex_sharpness[v] = INFINITE_SHARPNESS;
                }
            }
        }
        (level, map)
    }

    /// A level from polygons alone (no creases); edges are found by vertex
    /// pair. Used by the schemes whose child faces are not a fixed split
    /// pattern (Doo-Sabin).
    pub fn from_polygons(vertex_count: usize, faces: &[Vec<u32>], face_origin: Vec<u32>) -> Level {
        let mut level = Level {
            vertex_count,
            face_offsets: vec![0],
            face_origin,
            ..Level::default()
        };
        let mut edge_of: HashMap<(u32, u32), u32> = HashMap::new();
        for poly in faces {
            for (i, &a) in poly.iter().enumerate() {
                let b = poly[(i + 1) % poly.len()];
                let key = (a.min(b), a.max(b));
                let next = level.edge_vertices.len() as u32;
                let e = *edge_of.entry(key).or_insert(next);
                if e == next {
                    level.edge_vertices.push([a, b]);
                }
                level.face_vertices.push(a);
                level.face_edges.push(e);
            }
            level.face_offsets.push(level.face_vertices.len() as u32);
        }
        level.edge_sharpness = vec![0.0; level.edge_vertices.len()];
        level.vertex_sharpness = vec![0.0; vertex_count];
        level.finish();
        for e in 0..level.edge_count() {
            if level.is_boundary_edge(e as u32) {
                level.edge_sharpness[e] = INFINITE_SHARPNESS;
            }
        }
        level
    }

    /// Fills the derived tables (corner faces, edge faces, vertex adjacency)
    /// from the face and edge lists.
    pub fn finish(&mut self) {
        let nf = self.face_count();
        self.corner_face = Vec::with_capacity(self.face_vertices.len());
        for f in 0..nf {
            let n = (self.face_offsets[f + 1] - self.face_offsets[f]) as usize;
            self.corner_face.extend(std::iter::repeat_n(f as u32, n));
        }
        self.edge_faces = vec![[NONE, NONE]; self.edge_vertices.len()];
        for (c, &e) in self.face_edges.iter().enumerate() {
            let slot = &mut self.edge_faces[e as usize];
            let f = self.corner_face[c];
            if slot[0] == NONE {
                slot[0] = f;
            } else {
                slot[1] = f;
            }
        }
        let nv = self.vertex_count;
        let (offsets, edges) = group_by_vertex(
            nv,
            self.edge_vertices
                .iter()
                .enumerate()
                .flat_map(|(e, [a, b])| [(*a, e as u32), (*b, e as u32)]),
            2 * self.edge_vertices.len(),
        );
        self.vertex_edge_offsets = offsets;
        self.vertex_edges = edges;
        let (offsets, corners) = group_by_vertex(
            nv,
            self.face_vertices
                .iter()
                .enumerate()
                .map(|(c, &v)| (v, c as u32)),
            self.face_vertices.len(),
        );
        self.vertex_corner_offsets = offsets;
        self.vertex_corners = corners;
    }
}

/// Sharpness as the masks use it: negative and NaN become 0, anything at or
/// above [`INFINITE_SHARPNESS`] is infinite.
fn clamp_sharpness(s: f64) -> f32 {
    if s.is_nan() || s <= 0.0 {
        0.0
    } else {
        (s as f32).min(INFINITE_SHARPNESS)
    }
}

/// Counting sort of `(vertex, item)` pairs into a compressed row table.
fn group_by_vertex(
    vertex_count: usize,
    pairs: impl Iterator<Item = (u32, u32)> + Clone,
    total: usize,
) -> (Vec<u32>, Vec<u32>) {
    let mut offsets = vec![0u32; vertex_count + 1];
    for (v, _) in pairs.clone() {
        offsets[v as usize + 1] += 1;
    }
    for i in 0..vertex_count {
        offsets[i + 1] += offsets[i];
    }
    let mut fill = offsets.clone();
    let mut items = vec![0u32; total];
    for (v, item) in pairs {
        let slot = &mut fill[v as usize];
        items[*slot as usize] = item;
        *slot += 1;
    }
    (offsets, items)
}
