//! One refinement level's connectivity in flat arrays: face-vertex lists plus
//! the edge and vertex tables the subdivision masks read. This is the layout
//! of OpenSubdiv's `Vtr::Level`: refining walks arrays, never pointers, so a
//! level of a hundred thousand faces refines in milliseconds.

use std::collections::HashMap;
use std::sync::{Arc, OnceLock};

use super::rules::is_infinite;
use super::{BoundaryInterpolation, Creases, INFINITE_SHARPNESS};
use crate::{EdgeId, FaceId, HalfEdgeMesh, VertexId};

/// "No element" in the `u32` tables (a boundary edge's missing second face).
pub(crate) const NONE: u32 = u32::MAX;

/// Connectivity and sharpness of one level. Corner `c` of face `f` (for
/// `c` in [`face_corners(f)`](Self::face_corners)) is the vertex
/// `face_vertices[c]`; `face_edges[c]` is the edge from that corner to the
/// next one.
#[derive(Clone, Debug, Default)]
pub(crate) struct Level {
    pub vertex_count: usize,
    /// When every face has this many sides (every refined Catmull-Clark or
    /// Loop level), `face_offsets` is empty: face `f` has the corners
    /// `sides * f..sides * (f + 1)`. Zero otherwise.
    pub sides: u32,
    /// Face `f` has the corners `face_offsets[f]..face_offsets[f + 1]`
    /// (when `sides` is zero).
    pub face_offsets: Vec<u32>,
    pub face_vertices: Vec<u32>,
    pub face_edges: Vec<u32>,
    pub edge_vertices: Vec<[u32; 2]>,
    /// Crease sharpness per edge (boundary edges are infinitely sharp);
    /// empty when every edge is smooth (read it through
    /// [`edge_sharp`](Self::edge_sharp)).
    pub edge_sharpness: Vec<f32>,
    /// Corner sharpness per vertex; empty when none is sharp (read it
    /// through [`vertex_sharp`](Self::vertex_sharp)).
    pub vertex_sharpness: Vec<f32>,
    /// The cage face (dense index) each face descends from is
    /// `face_origin[f >> origin_shift]`: a refinement of an all-quad or
    /// all-triangle level splits face `f` into `4f..4f + 4`, so its
    /// children share the parent's table with the shift raised by 2
    /// (read it through [`face_origin`](Self::face_origin)).
    pub face_origin: Arc<[u32]>,
    pub origin_shift: u32,
    /// The level has an edge in more than two faces or a vertex whose
    /// faces form more than one fan (`Level::from_polygon_cage`); its
    /// children too. The edge tables then keep only the first two faces of
    /// an edge, which the masks never read: such edges are infinitely
    /// sharp.
    pub non_manifold: bool,
    /// Tables derived from the face and edge lists on first use, each on
    /// its own: the last level of a refinement often needs none, and Loop
    /// never needs the vertices' corners.
    pub(crate) adjacency: Adjacency,
}

/// Tables derived from the face and edge lists.
#[derive(Clone, Debug, Default)]
pub(crate) struct Adjacency {
    /// The face of each corner, for levels whose faces differ in size
    /// (read it through [`Level::corner_face`]).
    corner_face: OnceLock<Vec<u32>>,
    /// The one or two face corners that start each edge, in increasing
    /// order; the second is [`NONE`] on a boundary.
    edge_corners: OnceLock<Vec<[u32; 2]>>,
    /// Each vertex's edges in increasing order.
    vertex_edges: OnceLock<Lists>,
    /// Face corners at each vertex in increasing order.
    vertex_corners: OnceLock<Lists>,
}

/// Where a polygon cage is not manifold (what a half-edge mesh cannot
/// hold), as `Level::from_polygon_cage` finds it: for reports that name
/// the places (issue 37).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct NonManifoldPlaces {
    /// Edges in three or more faces: their vertices and how many faces.
    pub crowded_edges: Vec<([u32; 2], u32)>,
    /// Edges two faces run along the same way (one of them is turned
    /// over), as the vertex pair of the second face's run.
    pub same_way_edges: Vec<[u32; 2]>,
    /// Vertices where separate fans of faces meet (a bow-tie), other than
    /// the ends of crowded edges and the corners of repeating faces.
    pub split_vertices: Vec<u32>,
    /// Faces that visit a vertex more than once.
    pub repeating_faces: Vec<usize>,
}

impl NonManifoldPlaces {
    /// True when the cage is manifold: a half-edge mesh holds it.
    pub fn is_empty(&self) -> bool {
        self.crowded_edges.is_empty()
            && self.same_way_edges.is_empty()
            && self.split_vertices.is_empty()
            && self.repeating_faces.is_empty()
    }
}

/// What `Level::from_polygon_cage` learns of each edge while it finds
/// them: how many faces use it, the last of them, and whether it is
/// non-manifold. Edges are found by their lower vertex: `first_at[v]`
/// starts the list of edges whose lower end is `v`, `next_at[e]` goes on
/// and `last_at[v]` ends it (a vertex has a handful, so a walk beats
/// hashing the vertex pair).
#[derive(Default)]
struct CageEdges {
    /// The first two corners that start each edge, as
    /// [`Level::edge_corner_table`] has them (found here, where each
    /// corner's edge is at hand, instead of in a pass of its own).
    corners: Vec<[u32; 2]>,
    face_count: Vec<u32>,
    last_face: Vec<u32>,
    non_manifold: Vec<bool>,
    /// Each edge's higher vertex ([`NONE`] for an edge from a vertex to
    /// itself, which `find` never returns), beside `next_at` for the walk.
    high_end: Vec<u32>,
    first_at: Vec<u32>,
    last_at: Vec<u32>,
    next_at: Vec<u32>,
}

impl CageEdges {
    /// A new edge of `level` from `a` to `b`.
    fn push(&mut self, level: &mut Level, [a, b]: [u32; 2], non_manifold: bool) -> u32 {
        let e = level.edge_vertices.len() as u32;
        level.edge_vertices.push([a, b]);
        self.corners.push([NONE, NONE]);
        self.face_count.push(0);
        self.last_face.push(NONE);
        self.non_manifold.push(non_manifold);
        // Appended behind the vertex's other edges: the first edge of a
        // vertex pair is the one `find` returns, as in OpenSubdiv.
        let low = a.min(b) as usize;
        self.high_end.push(if a == b { NONE } else { a.max(b) });
        self.next_at.push(NONE);
        match self.last_at[low] {
            NONE => self.first_at[low] = e,
            last => self.next_at[last as usize] = e,
        }
        self.last_at[low] = e;
        e
    }
    /// The first edge between `a` and `b` (two different vertices).
    fn find(&self, a: u32, b: u32) -> Option<u32> {
        let (low, high) = (a.min(b), a.max(b));
        let mut e = self.first_at[low as usize];
        while e != NONE {
            if self.high_end[e as usize] == high {
                return Some(e);
            }
            e = self.next_at[e as usize];
        }
        None
    }
}

/// One list per vertex, packed: list `v` is `items[offsets[v]..offsets[v + 1]]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Lists {
    pub offsets: Vec<u32>,
    pub items: Vec<u32>,
}

impl Lists {
    #[inline]
    pub fn get(&self, v: usize) -> &[u32] {
        &self.items[self.offsets[v] as usize..self.offsets[v + 1] as usize]
    }

    /// Lists of `count` vertices by counting sort: `count_into(offsets)`
    /// adds each list's length at `offsets[v + 2]`, `fill(offsets, items)`
    /// writes each item at `offsets[v + 1]` (then raises it) in increasing
    /// item order, so each list stays in increasing order.
    fn gather(
        count: usize,
        len: usize,
        count_into: impl FnOnce(&mut [u32]),
        fill: impl FnOnce(&mut [u32], &mut [u32]),
    ) -> Lists {
        let mut offsets = vec![0u32; count + 2];
        count_into(&mut offsets);
        prefix_sum(&mut offsets);
        let mut items = vec![0u32; len];
        fill(&mut offsets, &mut items);
        offsets.pop();
        Lists { offsets, items }
    }
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
        if self.sides > 0 {
            self.face_vertices.len() / self.sides as usize
        } else {
            self.face_offsets.len() - 1
        }
    }
    pub fn edge_count(&self) -> usize {
        self.edge_vertices.len()
    }
    #[inline]
    pub fn face_corners(&self, f: u32) -> std::ops::Range<usize> {
        if self.sides > 0 {
            let n = self.sides as usize;
            n * f as usize..n * (f as usize + 1)
        } else {
            self.face_offsets[f as usize] as usize..self.face_offsets[f as usize + 1] as usize
        }
    }
    /// The cage face (dense index) face `f` descends from.
    #[inline]
    pub fn face_origin(&self, f: usize) -> u32 {
        self.face_origin[f >> self.origin_shift]
    }
    /// The face of corner `c`.
    #[inline]
    pub fn corner_face(&self, c: usize) -> u32 {
        // Constant divisors, so no division instruction on the hot path.
        match self.sides {
            4 => (c / 4) as u32,
            3 => (c / 3) as u32,
            0 => self
                .adjacency
                .corner_face
                .get_or_init(|| self.corner_face_table())[c],
            n => (c / n as usize) as u32,
        }
    }
    /// The one or two face corners starting each edge, in increasing order
    /// (the second is [`NONE`] on a boundary).
    pub(crate) fn edge_corner_table(&self) -> &[[u32; 2]] {
        self.adjacency.edge_corners.get_or_init(|| {
            let mut edge_corners = vec![[NONE, NONE]; self.edge_vertices.len()];
            for (c, &e) in self.face_edges.iter().enumerate() {
                let slot = &mut edge_corners[e as usize];
                // A non-manifold edge keeps its first two corners.
                if slot[1] == NONE {
                    slot[usize::from(slot[0] != NONE)] = c as u32;
                }
            }
            edge_corners
        })
    }
    /// Every vertex's edges, in increasing order.
    pub(crate) fn vertex_edge_lists(&self) -> &Lists {
        self.adjacency.vertex_edges.get_or_init(|| {
            Lists::gather(
                self.vertex_count,
                2 * self.edge_count(),
                |offsets| {
                    for &[a, b] in &self.edge_vertices {
                        offsets[a as usize + 2] += 1;
                        offsets[b as usize + 2] += 1;
                    }
                },
                |offsets, items| {
                    for (e, &[a, b]) in self.edge_vertices.iter().enumerate() {
                        for v in [a, b] {
                            let slot = &mut offsets[v as usize + 1];
                            items[*slot as usize] = e as u32;
                            *slot += 1;
                        }
                    }
                },
            )
        })
    }
    /// Every vertex's face corners, in increasing order.
    pub(crate) fn vertex_corner_lists(&self) -> &Lists {
        self.adjacency.vertex_corners.get_or_init(|| {
            Lists::gather(
                self.vertex_count,
                self.face_vertices.len(),
                |offsets| {
                    for &v in &self.face_vertices {
                        offsets[v as usize + 2] += 1;
                    }
                },
                |offsets, items| {
                    for (c, &v) in self.face_vertices.iter().enumerate() {
                        let slot = &mut offsets[v as usize + 1];
                        items[*slot as usize] = c as u32;
                        *slot += 1;
                    }
                },
            )
        })
    }
    /// Sets the derived tables, when the refinement that made this level
    /// knows them without a search (see `refine::split_quads`).
    pub(crate) fn set_adjacency(
        &mut self,
        edge_corners: Vec<[u32; 2]>,
        vertex_edges: Lists,
        vertex_corners: Option<Lists>,
    ) {
        self.adjacency = Adjacency {
            corner_face: OnceLock::new(),
            edge_corners: edge_corners.into(),
            vertex_edges: vertex_edges.into(),
            vertex_corners: vertex_corners.map_or_else(OnceLock::new, OnceLock::from),
        };
    }
    fn corner_face_table(&self) -> Vec<u32> {
        let mut corner_face = Vec::with_capacity(self.face_vertices.len());
        for f in 0..self.face_count() {
            corner_face.extend(std::iter::repeat_n(
                f as u32,
                self.face_corners(f as u32).len(),
            ));
        }
        corner_face
    }
    /// The one or two faces of edge `e`; the second is [`NONE`] on a boundary.
    pub fn edge_faces(&self, e: u32) -> [u32; 2] {
        let [c0, c1] = self.edge_corner_table()[e as usize];
        [
            self.corner_face(c0 as usize),
            if c1 == NONE {
                NONE
            } else {
                self.corner_face(c1 as usize)
            },
        ]
    }
    pub fn vertex_edges(&self, v: u32) -> &[u32] {
        self.vertex_edge_lists().get(v as usize)
    }
    /// Face corners at vertex `v`.
    pub fn vertex_corners(&self, v: u32) -> &[u32] {
        self.vertex_corner_lists().get(v as usize)
    }
    /// The other end of edge `e` seen from `v`.
    pub fn other_end(&self, e: u32, v: u32) -> u32 {
        let [a, b] = self.edge_vertices[e as usize];
        if a == v { b } else { a }
    }
    pub fn is_boundary_edge(&self, e: u32) -> bool {
        self.edge_corner_table()[e as usize][1] == NONE
    }
    /// Corner before `c` in its face.
    #[inline]
    pub fn prev_corner(&self, c: usize) -> usize {
        let r = self.corner_range(c);
        if c == r.start { r.end - 1 } else { c - 1 }
    }
    /// Corner after `c` in its face.
    #[inline]
    pub fn next_corner(&self, c: usize) -> usize {
        let r = self.corner_range(c);
        if c + 1 == r.end { r.start } else { c + 1 }
    }
    /// The corners of corner `c`'s face.
    #[inline]
    fn corner_range(&self, c: usize) -> std::ops::Range<usize> {
        match self.sides {
            4 => (c & !3)..(c & !3) + 4,
            _ => self.face_corners(self.corner_face(c)),
        }
    }
    /// Crease sharpness of edge `e`.
    #[inline]
    pub fn edge_sharp(&self, e: u32) -> f32 {
        self.edge_sharpness.get(e as usize).copied().unwrap_or(0.0)
    }
    /// Corner sharpness of vertex `v`.
    #[inline]
    pub fn vertex_sharp(&self, v: u32) -> f32 {
        self.vertex_sharpness
            .get(v as usize)
            .copied()
            .unwrap_or(0.0)
    }
    /// True when no edge or vertex is sharp (and the level has no boundary).
    pub fn is_smooth(&self) -> bool {
        self.edge_sharpness.is_empty() && self.vertex_sharpness.is_empty()
    }
    /// Drops the sharpness tables when they hold only zeros, so that
    /// smooth levels (most of them) carry none and their children skip
    /// the crease rules.
    pub(crate) fn drop_zero_sharpness(&mut self) {
        if self.edge_sharpness.iter().all(|&s| s == 0.0) {
            self.edge_sharpness = Vec::new();
        }
        if self.vertex_sharpness.iter().all(|&s| s == 0.0) {
            self.vertex_sharpness = Vec::new();
        }
    }
    /// Sets [`sides`](Self::sides) (and drops the offsets) when every face
    /// has the same number of sides.
    fn settle_face_sizes(&mut self) {
        if self.sides == 0 && self.face_count() > 0 {
            let n = self.face_offsets[1];
            if n > 0 && self.all_faces_have(n) {
                self.sides = n;
                self.face_offsets = Vec::new();
            }
        }
    }
    /// True when every face has `n` sides.
    pub fn all_faces_have(&self, n: u32) -> bool {
        if self.sides > 0 {
            self.sides == n
        } else {
            self.face_offsets.windows(2).all(|w| w[1] - w[0] == n)
        }
    }

    /// The level of a half-edge mesh's live faces and vertices (isolated
    /// vertices too: they are corners, infinitely sharp, and stay put at
    /// every level, as OpenSubdiv keeps them) with the given creases.
    /// Boundary edges are infinitely sharp; with
    /// [`BoundaryInterpolation::EdgesAndCorners`] so are boundary vertices
    /// that touch a single face (OpenSubdiv's `VTX_BOUNDARY_EDGE_AND_CORNER`).
    ///
    /// Also returns, per cage face, whether it is left out of the result:
    /// a hole of `creases`, or (when `hide_boundary`, boundary `None`) a face
    /// at a vertex one of whose boundary edges the user did not make
    /// infinitely sharp (OpenSubdiv's `prepareComponentTagsAndSharpness`).
    pub fn from_mesh(
        mesh: &HalfEdgeMesh,
        creases: &Creases,
        boundary: BoundaryInterpolation,
        hide_boundary: bool,
    ) -> (Level, CageMap, Vec<bool>) {
        let mut map = CageMap {
            vertices: mesh.vertices().collect(),
            edges: mesh.edges().collect(),
            faces: Vec::new(),
        };
        // Dense indices of raw ids; the same when nothing is dead.
        let compact = map.vertices.len() == mesh.vertex_capacity()
            && map.edges.len() == mesh.edge_capacity()
            && mesh.face_count() == mesh.face_capacity();
        let dense = |ids: &mut dyn Iterator<Item = usize>, capacity: usize| {
            let mut to_dense = vec![NONE; capacity];
            for (i, id) in ids.enumerate() {
                to_dense[id] = i as u32;
            }
            to_dense
        };
        let (vmap, emap) = if compact {
            (Vec::new(), Vec::new())
        } else {
            (
                dense(
                    &mut map.vertices.iter().map(|v| v.index()),
                    mesh.vertex_capacity(),
                ),
                dense(
                    &mut map.edges.iter().map(|e| e.index()),
                    mesh.edge_capacity(),
                ),
            )
        };
        let vertex_index = |v: VertexId| {
            if compact {
                v.index() as u32
            } else {
                vmap[v.index()]
            }
        };
        let edge_vertices: Vec<[u32; 2]> = map
            .edges
            .iter()
            .map(|&e| mesh.edge_vertices(e).map(vertex_index))
            .collect();
        let mut level = Level {
            vertex_count: map.vertices.len(),
            face_offsets: Vec::with_capacity(mesh.face_count() + 1),
            face_vertices: Vec::with_capacity(2 * mesh.edge_count()),
            face_edges: Vec::with_capacity(2 * mesh.edge_count()),
            edge_vertices,
            ..Level::default()
        };
        level.face_offsets.push(0);
        mesh.append_face_corners(
            &mut level.face_offsets,
            &mut level.face_vertices,
            &mut level.face_edges,
        );
        // Raw ids to dense indices (the same when nothing is dead).
        if !compact {
            for v in &mut level.face_vertices {
                *v = vmap[*v as usize];
            }
            for e in &mut level.face_edges {
                *e = emap[*e as usize];
            }
        }
        map.faces = mesh.faces().collect();
        level.face_origin = (0..map.faces.len() as u32).collect();
        level.settle_face_sizes();
        let tapered;
        let edge_sharpness = if creases.tapers.is_empty() {
            &creases.edges
        } else {
            tapered = creases.edge_sharpness();
            &tapered
        };
        level.edge_sharpness = map
            .edges
            .iter()
            .map(|e| clamp_sharpness(edge_sharpness.get(e).copied().unwrap_or(0.0)))
            .collect();
        level.vertex_sharpness = map
            .vertices
            .iter()
            .map(|v| clamp_sharpness(creases.vertices.get(v).copied().unwrap_or(0.0)))
            .collect();
        let mut hidden: Vec<bool> = map.faces.iter().map(|&f| creases.is_hole(f)).collect();
        if hide_boundary {
            for v in 0..level.vertex_count as u32 {
                let soft_boundary = level.vertex_edges(v).iter().any(|&e| {
                    level.is_boundary_edge(e) && !is_infinite(level.edge_sharpness[e as usize])
                });
                if soft_boundary {
                    for &c in level.vertex_corners(v) {
                        hidden[level.corner_face(c as usize) as usize] = true;
                    }
                }
            }
        }
        for e in 0..level.edge_count() {
            if level.is_boundary_edge(e as u32) {
                level.edge_sharpness[e] = INFINITE_SHARPNESS;
            }
        }
        for v in 0..level.vertex_count {
            let edges = level.vertex_edges(v as u32);
            let isolated = edges.is_empty();
            let boundary_corner = boundary == BoundaryInterpolation::EdgesAndCorners
                && level.vertex_corners(v as u32).len() == 1
                && edges.iter().any(|&e| level.is_boundary_edge(e));
            if isolated || boundary_corner {
                level.vertex_sharpness[v] = INFINITE_SHARPNESS;
            }
        }
        level.drop_zero_sharpness();
        (level, map, hidden)
    }

    /// The cage level of polygons given as vertex lists, kept as they are:
    /// an edge may be in more than two faces and a vertex may join
    /// separate fans of faces. Topology and sharpness follow OpenSubdiv
    /// (`Vtr::Level::completeTopologyFromFaceVertices` and
    /// `Far::TopologyRefinerFactoryBase::prepareComponentTagsAndSharpness`):
    ///
    /// - an edge is non-manifold when it is in three or more faces, when two
    ///   faces run along it the same way, or when one face uses it twice
    ///   (each use is then an edge of its own) or joins a vertex to itself;
    ///   non-manifold and boundary edges are infinitely sharp;
    /// - a vertex is non-manifold at the end of a non-manifold edge or when
    ///   its faces do not form one fan (separate fans, a face that comes
    ///   back to it); it is then a corner, unless it is inside a fin crease
    ///   (exactly two non-manifold edges, no boundary edge, more faces than
    ///   edges), where it follows them as a crease;
    /// - isolated vertices and, with [`BoundaryInterpolation::EdgesAndCorners`],
    ///   vertices of one face and two edges are corners.
    ///
    /// Also returns, per face, whether boundary `None` (`hide_boundary`)
    /// leaves it out, as [`from_mesh`](Self::from_mesh) does.
    pub fn from_polygon_cage(
        vertex_count: usize,
        faces: &[Vec<u32>],
        boundary: BoundaryInterpolation,
        hide_boundary: bool,
    ) -> (Level, Vec<bool>, NonManifoldPlaces) {
        let mut places = NonManifoldPlaces::default();
        let mut level = Level {
            vertex_count,
            face_offsets: vec![0],
            face_origin: (0..faces.len() as u32).collect(),
            ..Level::default()
        };
        let mut edges = CageEdges {
            first_at: vec![NONE; vertex_count],
            last_at: vec![NONE; vertex_count],
            ..CageEdges::default()
        };
        for (f, poly) in faces.iter().enumerate() {
            let f = f as u32;
            for (i, &a) in poly.iter().enumerate() {
                // (No `%`: a division per corner is a measurable share here.)
                let b = if i + 1 == poly.len() {
                    poly[0]
                } else {
                    poly[i + 1]
                };
                let e = match edges.find(a, b) {
                    _ if a == b => edges.push(&mut level, [a, b], true),
                    None => edges.push(&mut level, [a, b], false),
                    Some(e) if edges.last_face[e as usize] == f => {
                        // The face uses this edge twice: two edges.
                        edges.non_manifold[e as usize] = true;
                        edges.push(&mut level, [a, b], true)
                    }
                    Some(e) => {
                        let same_way = level.edge_vertices[e as usize][0] == a;
                        if same_way && edges.face_count[e as usize] == 1 {
                            places.same_way_edges.push([b, a]);
                        }
                        if edges.face_count[e as usize] >= 2 || same_way {
                            edges.non_manifold[e as usize] = true;
                        }
                        e
                    }
                };
                edges.face_count[e as usize] += 1;
                edges.last_face[e as usize] = f;
                let corner = level.face_vertices.len() as u32;
                let slot = &mut edges.corners[e as usize];
                if slot[0] == NONE {
                    slot[0] = corner;
                } else if slot[1] == NONE {
                    slot[1] = corner;
                }
                level.face_vertices.push(a);
                level.face_edges.push(e);
            }
            level.face_offsets.push(level.face_vertices.len() as u32);
            if (1..poly.len()).any(|i| poly[..i].contains(&poly[i])) {
                places.repeating_faces.push(f as usize);
            }
        }
        let CageEdges {
            corners: edge_corners,
            face_count: edge_face_count,
            non_manifold: edge_non_manifold,
            ..
        } = edges;
        level.adjacency.edge_corners = OnceLock::from(edge_corners);
        level.settle_face_sizes();
        let boundary_edge = |e: u32| edge_face_count[e as usize] < 2;
        let mut hidden = vec![false; faces.len()];
        if hide_boundary {
            for v in 0..vertex_count as u32 {
                if level.vertex_edges(v).iter().any(|&e| boundary_edge(e)) {
                    for &c in level.vertex_corners(v) {
                        hidden[level.corner_face(c as usize) as usize] = true;
                    }
                }
            }
        }
        level.edge_sharpness = (0..level.edge_count())
            .map(|e| {
                if edge_non_manifold[e] || boundary_edge(e as u32) {
                    INFINITE_SHARPNESS
                } else {
                    0.0
                }
            })
            .collect();
        level.vertex_sharpness = vec![0.0; vertex_count];
        // Every edge in one or two faces that run along it in opposite
        // directions, no face coming back to a vertex: the fans at a vertex
        // can then be walked instead of joined (much the cheaper).
        let oriented_edges =
            places.repeating_faces.is_empty() && !edge_non_manifold.iter().any(|&n| n);
        for v in 0..vertex_count as u32 {
            let edges = level.vertex_edges(v);
            let corners = level.vertex_corners(v);
            let (e, f) = (edges.len(), corners.len());
            // (Counted only when some edge is not manifold: else both are
            // read only where `non_manifold_edges` is 2.)
            let non_manifold_edges = if oriented_edges {
                0
            } else {
                edges
                    .iter()
                    .filter(|&&e| edge_non_manifold[e as usize])
                    .count()
            };
            let boundary_edges = if oriented_edges {
                0
            } else {
                edges.iter().filter(|&&e| boundary_edge(e)).count()
            };
            let one_fan = (e == f || e == f + 1)
                && if oriented_edges {
                    level.walks_one_fan(corners, e == f + 1)
                } else {
                    level.single_fan(v, &edge_face_count)
                };
            let non_manifold = non_manifold_edges > 0 || (f > 0 && !one_fan);
            let corner =
                e == 0 || (boundary == BoundaryInterpolation::EdgesAndCorners && f == 1 && e == 2);
            let fin_crease = non_manifold_edges == 2 && boundary_edges == 0 && f > e;
            // A split fan is reported as such unless a crowded edge or a
            // face that comes back to `v` explains it (checked only then).
            if f > 0 && !one_fan {
                let crowded = edges.iter().any(|&e| edge_face_count[e as usize] > 2);
                let face = |c: u32| level.corner_face(c as usize);
                let repeated = (1..corners.len())
                    .any(|i| corners[..i].iter().any(|&c| face(c) == face(corners[i])));
                if !crowded && !repeated {
                    places.split_vertices.push(v);
                }
            }
            level.non_manifold |= non_manifold;
            if corner || (non_manifold && !fin_crease) {
                level.vertex_sharpness[v as usize] = INFINITE_SHARPNESS;
            }
        }
        places.crowded_edges = (0..level.edge_count())
            .filter(|&e| edge_face_count[e] > 2)
            .map(|e| (level.edge_vertices[e], edge_face_count[e]))
            .collect();
        level.drop_zero_sharpness();
        (level, hidden, places)
    }

    /// Whether the faces at a vertex (its `corners`; none: false) form
    /// one fan, when every edge is in one face or in two that run along it
    /// in opposite directions and no face comes back to a vertex. From
    /// corner `c`, the edge into the vertex (the edge of the corner before)
    /// leads to the other face's corner at the same vertex; a fan is the
    /// walk along these steps, from a corner whose edge out of the vertex
    /// is on the boundary (none: any corner, round to it again). One fan
    /// when the walk meets every corner.
    /// `open`: the vertex has one edge more than faces, so a boundary
    /// edge (else none is looked for).
    fn walks_one_fan(&self, corners: &[u32], open: bool) -> bool {
        if corners.is_empty() {
            return false;
        }
        let edge_corners = self.edge_corner_table();
        let boundary_out = |c: u32| edge_corners[self.face_edges[c as usize] as usize][1] == NONE;
        let start = match open {
            true => corners.iter().copied().find(|&c| boundary_out(c)),
            false => None,
        }
        .unwrap_or(corners[0]);
        let mut c = start;
        let mut met = 1;
        loop {
            let before = self.prev_corner(c as usize) as u32;
            let [c0, c1] = edge_corners[self.face_edges[before as usize] as usize];
            let across = if c0 == before { c1 } else { c0 };
            if across == NONE || across == start {
                return met == corners.len();
            }
            met += 1;
            if met > corners.len() {
                return false;
            }
            c = across;
        }
    }

    /// Whether the faces at `v` form one fan, each face there once, joined
    /// through the edges at `v` that are in exactly two faces
    /// (`edge_face_count`).
    fn single_fan(&self, v: u32, edge_face_count: &[u32]) -> bool {
        let corners = self.vertex_corners(v);
        // The faces at `v` and their union-find parents, on the stack for
        // the usual valences.
        let mut faces_buf = [0u32; 32];
        let mut parent_buf = [0usize; 32];
        let (mut faces_heap, mut parent_heap);
        let (faces, parent): (&mut [u32], &mut [usize]) = if corners.len() <= 32 {
            (
                &mut faces_buf[..corners.len()],
                &mut parent_buf[..corners.len()],
            )
        } else {
            faces_heap = vec![0u32; corners.len()];
            parent_heap = vec![0usize; corners.len()];
            (&mut faces_heap[..], &mut parent_heap[..])
        };
        for (i, &c) in corners.iter().enumerate() {
            faces[i] = self.corner_face(c as usize);
            parent[i] = i;
        }
        if (1..faces.len()).any(|i| faces[..i].contains(&faces[i])) {
            return false;
        }
        fn root(parent: &mut [usize], mut i: usize) -> usize {
            while parent[i] != i {
                parent[i] = parent[parent[i]];
                i = parent[i];
            }
            i
        }
        for &e in self.vertex_edges(v) {
            if edge_face_count[e as usize] != 2 {
                continue;
            }
            let [c0, c1] = self.edge_corner_table()[e as usize];
            let (f0, f1) = (self.corner_face(c0 as usize), self.corner_face(c1 as usize));
            if let (Some(i), Some(j)) = (
                faces.iter().position(|&f| f == f0),
                faces.iter().position(|&f| f == f1),
            ) {
                let (ri, rj) = (root(parent, i), root(parent, j));
                parent[ri] = rj;
            }
        }
        (0..faces.len()).filter(|&i| root(parent, i) == i).count() == 1
    }

    /// A level from polygons alone (no creases); edges are found by vertex
    /// pair. Used by the schemes whose child faces are not a fixed split
    /// pattern (Doo-Sabin).
    pub fn from_polygons(vertex_count: usize, faces: &[Vec<u32>], face_origin: Vec<u32>) -> Level {
        let mut level = Level {
            vertex_count,
            face_offsets: vec![0],
            face_origin: face_origin.into(),
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
        level.settle_face_sizes();
        level.edge_sharpness = vec![0.0; level.edge_vertices.len()];
        level.vertex_sharpness = vec![0.0; vertex_count];
        for e in 0..level.edge_count() {
            if level.is_boundary_edge(e as u32) {
                level.edge_sharpness[e] = INFINITE_SHARPNESS;
            }
        }
        level.drop_zero_sharpness();
        level
    }
}

fn prefix_sum(offsets: &mut [u32]) {
    for i in 1..offsets.len() {
        offsets[i] += offsets[i - 1];
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The edge table `from_polygon_cage` fills while it finds the edges
    /// equals the one counted afresh from the face list: on a closed cube,
    /// an open strip, a crowded edge (three faces), a face turned over and
    /// a face that uses an edge twice.
    #[test]
    fn cage_edge_corners_equal_counted() {
        let cases: [(&str, usize, Vec<Vec<u32>>); 5] = [
            (
                "cube",
                8,
                vec![
                    vec![0, 3, 2, 1],
                    vec![4, 5, 6, 7],
                    vec![0, 1, 5, 4],
                    vec![1, 2, 6, 5],
                    vec![2, 3, 7, 6],
                    vec![3, 0, 4, 7],
                ],
            ),
            ("strip", 6, vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4]]),
            (
                "crowded",
                5,
                vec![vec![0, 1, 2], vec![1, 0, 3], vec![0, 1, 4]],
            ),
            ("turned over", 4, vec![vec![0, 1, 2], vec![0, 1, 3]]),
            ("edge twice", 4, vec![vec![0, 1, 2, 1, 3], vec![1, 0, 3]]),
        ];
        for (name, vertex_count, faces) in cases {
            let boundary = BoundaryInterpolation::EdgesOnly;
            let (level, _, _) = Level::from_polygon_cage(vertex_count, &faces, boundary, false);
            let counted = Level {
                adjacency: Adjacency::default(),
                ..level.clone()
            };
            assert_eq!(
                level.edge_corner_table(),
                counted.edge_corner_table(),
                "{name}"
            );
        }
    }
}
