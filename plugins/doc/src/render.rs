//! The triangle buffers the viewport draws a half-edge mesh with, and their
//! in-place update while a tool drags vertices. Free of Bevy so that they are
//! tested and benchmarked without a renderer; `hedra_scene` wraps them in a
//! Bevy `Mesh`.

use crate::scene::Shading;
use hedra_geom::query::triangulate_outer_loop_into;
use hedra_geom::{DVec3, FaceId, HalfEdgeMesh, VertexId};

/// Positions, normals and triangle indices for the GPU (f32, as rendered).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderBuffers {
    /// Vertex positions in the mesh's (node's local) space.
    pub positions: Vec<[f32; 3]>,
    /// Unit normals, one per position.
    pub normals: Vec<[f32; 3]>,
    /// Three indices into `positions` per triangle, counter-clockwise seen from
    /// outside.
    pub indices: Vec<u32>,
}

/// Triangle buffers of a half-edge mesh. Flat shading gives each face its
/// own corners with the face normal, laid out face after face in id order
/// (a cube gets 24 vertices: seed 000's "cube problem"); smooth shading
/// shares one corner per vertex, in id order, with area-weighted vertex
/// normals.
///
/// A face with inner rings (made by the Euler operators) is drawn as its
/// outer loop only, covering its rings; a face without edges (MVFS) or a
/// wire draws nothing. Both keep their corners in the flat layout.
///
/// Complexity: O(corners), O(n²) only inside concave n-gons (ear clipping).
pub fn render_buffers(mesh: &HalfEdgeMesh, shading: Shading) -> RenderBuffers {
    render_buffers_creased(mesh, shading, &hedra_geom::subdivision::Creases::default())
}

/// [`render_buffers`] with smooth normals split along the infinitely sharp
/// creases of `creases` ([`split_sharp_corners`]): a vertex on such a crease
/// gets one render vertex per side, appended after the shared ones, each
/// with the normal of its side's faces. Flat shading is unchanged.
pub fn render_buffers_creased(
    mesh: &HalfEdgeMesh,
    shading: Shading,
    creases: &hedra_geom::subdivision::Creases,
) -> RenderBuffers {
    let mut b = RenderBuffers::default();
    // One face's corners and triangles, reused for every face.
    let (mut corners, mut face): (Vec<VertexId>, Vec<[VertexId; 3]>) = (Vec::new(), Vec::new());
    match shading {
        Shading::Flat => {
            for f in mesh.faces() {
                let n = mesh.face_normal(f).as_vec3().to_array();
                let base = b.positions.len() as u32;
                corners.clear();
                corners.extend(mesh.face_vertices(f));
                for &v in &corners {
                    b.positions.push(mesh.position(v).as_vec3().to_array());
                    b.normals.push(n);
                }
                // Faces are small: find each triangle corner by a linear search.
                let corner = |v: &VertexId| {
                    base + corners
                        .iter()
                        .position(|c| c == v)
                        .expect("a triangle corner is a face corner")
                        as u32
                };
                face.clear();
                triangulate_outer_loop_into(mesh, f, &mut face);
                for tri in &face {
                    b.indices.extend(tri.iter().map(corner));
                }
            }
        }
        Shading::Smooth => {
            let mut index = vec![u32::MAX; mesh.vertex_capacity()];
            for v in mesh.vertices() {
                index[v.index()] = b.positions.len() as u32;
                b.positions.push(mesh.position(v).as_vec3().to_array());
                b.normals.push(mesh.vertex_normal(v).as_vec3().to_array());
            }
            let split = mesh_sharp_split(mesh, creases, &index);
            if !split.is_empty() {
                let points: Vec<DVec3> = mesh.vertices().map(|v| mesh.position(v)).collect();
                split.apply(&points, &mut b.positions, &mut b.normals);
            }
            let mut corner = 0usize;
            for f in mesh.faces() {
                corners.clear();
                corners.extend(mesh.face_vertices(f));
                let render = |v: &VertexId| {
                    let k = corners.iter().position(|c| c == v).unwrap_or(0);
                    split.vertex(corner + k, index[v.index()])
                };
                face.clear();
                triangulate_outer_loop_into(mesh, f, &mut face);
                for tri in &face {
                    b.indices.extend(tri.iter().map(render));
                }
                corner += corners.len();
            }
        }
    }
    b
}

/// Triangle buffers of a kept (non-manifold) mesh, laid out as
/// [`render_buffers`] lays out a half-edge mesh: flat shading gives each
/// face its own corners with its Newell normal, smooth shading one corner
/// per vertex with the area-weighted normal of its faces (each face counts
/// once at each of its corners, so a fin's faces all bend the normal).
pub fn kept_render_buffers(mesh: &crate::kept::KeptMesh, shading: Shading) -> RenderBuffers {
    let mut b = RenderBuffers::default();
    let (mut points, mut tris) = (Vec::new(), Vec::new());
    let position = |v: u32| mesh.positions[v as usize];
    match shading {
        Shading::Flat => {
            for (f, face) in mesh.faces.iter().enumerate() {
                // A face without area gets a unit normal all the same
                // (glTF requires unit normals).
                let n = mesh.face_normal(f);
                let n = if n == DVec3::ZERO { DVec3::Z } else { n };
                let n = n.as_vec3().to_array();
                let base = b.positions.len() as u32;
                points.clear();
                points.extend(face.iter().map(|&v| position(v)));
                b.positions
                    .extend(points.iter().map(|p| p.as_vec3().to_array()));
                b.normals.extend(std::iter::repeat_n(n, face.len()));
                tris.clear();
                hedra_geom::query::triangulate_polygon_into(&points, &mut tris);
                b.indices
                    .extend(tris.iter().flatten().map(|&i| base + i as u32));
            }
        }
        Shading::Smooth => {
            let mut normals = vec![DVec3::ZERO; mesh.positions.len()];
            for face in &mesh.faces {
                let p = |i: usize| position(face[i % face.len()]);
                let area: DVec3 = (0..face.len()).map(|i| p(i).cross(p(i + 1))).sum();
                for &v in face {
                    normals[v as usize] += area;
                }
            }
            b.positions = mesh
                .positions
                .iter()
                .map(|p| p.as_vec3().to_array())
                .collect();
            b.normals = normals
                .iter()
                .map(|n| n.normalize_or(DVec3::Z).as_vec3().to_array())
                .collect();
            b.indices = mesh.triangles().into_iter().flatten().collect();
        }
    }
    b
}

/// [`split_sharp_corners`] of a half-edge mesh's faces (outer loops, in id
/// order) along its infinitely sharp creases; `index` maps vertex ids to
/// their ranks. Nothing when no crease is infinitely sharp.
pub(crate) fn mesh_sharp_split(
    mesh: &HalfEdgeMesh,
    creases: &hedra_geom::subdivision::Creases,
    index: &[u32],
) -> SharpSplit {
    let sharp = sharp_edges(mesh, creases, index);
    if sharp.is_empty() {
        return SharpSplit::default();
    }
    let polygons: Vec<Vec<u32>> = mesh
        .faces()
        .map(|f| mesh.face_vertices(f).map(|v| index[v.index()]).collect())
        .collect();
    let faces: Vec<&[u32]> = polygons.iter().map(Vec::as_slice).collect();
    split_sharp_corners(&faces, mesh.vertex_count(), &sharp)
}

/// Smooth-shaded corners split along sharp edges, as Blender splits
/// normals at sharp edges: around a vertex on a sharp edge, the faces
/// between two sharp edges (a fan) share one render vertex and one normal,
/// the area-weighted normal of that fan's faces, so the shading does not
/// blend across the edge. Made by [`split_sharp_corners`] from the
/// connectivity alone, so it is kept while only positions change.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SharpSplit {
    /// The render vertex of each face corner, faces in order, corners in
    /// order. Empty when nothing is split: then corner `k` of a face is
    /// its own vertex.
    pub corner_vertex: Vec<u32>,
    /// The source vertex of each added render vertex (numbered from the
    /// vertex count on, in order).
    pub copies: Vec<u32>,
    /// Each render vertex of a split vertex (its original index and its
    /// copies) with the end of its fan's faces in `fan_polygons`.
    fans: Vec<(u32, usize)>,
    /// The vertex lists of the fans' faces, each after its length.
    fan_polygons: Vec<u32>,
}

impl SharpSplit {
    /// True when nothing is split.
    pub fn is_empty(&self) -> bool {
        self.fans.is_empty()
    }

    /// The render vertex of corner `corner` (counted over all faces) whose
    /// vertex is `vertex`.
    #[inline]
    pub fn vertex(&self, corner: usize, vertex: u32) -> u32 {
        self.corner_vertex.get(corner).copied().unwrap_or(vertex)
    }

    /// The unit normal of every render vertex of a split vertex at
    /// `points`: the sum of its fan's faces' Newell area vectors,
    /// normalised (zero for a fan without area).
    pub fn normals(&self, points: &[DVec3]) -> Vec<(u32, DVec3)> {
        let mut at = 0;
        self.fans
            .iter()
            .map(|&(v, end)| {
                let mut n = DVec3::ZERO;
                while at < end {
                    let len = self.fan_polygons[at] as usize;
                    let face = &self.fan_polygons[at + 1..at + 1 + len];
                    for (i, &a) in face.iter().enumerate() {
                        let b = face[(i + 1) % len];
                        n += points[a as usize].cross(points[b as usize]);
                    }
                    at += 1 + len;
                }
                (v, n.normalize_or_zero())
            })
            .collect()
    }

    /// Appends the copies' positions and normals to smooth attributes
    /// (one per vertex of `points`) and sets the split vertices' normals
    /// from their fans at `points`.
    pub fn apply(
        &self,
        points: &[DVec3],
        positions: &mut Vec<[f32; 3]>,
        normals: &mut Vec<[f32; 3]>,
    ) {
        if self.is_empty() {
            return;
        }
        for &v in &self.copies {
            positions.push(positions[v as usize]);
            normals.push(normals[v as usize]);
        }
        for (v, n) in self.normals(points) {
            normals[v as usize] = n.as_vec3().to_array();
        }
    }
}

/// Splits the corners of polygons `faces` (vertex indices below
/// `vertex_count`) at every vertex on an edge of `sharp` (vertex pairs,
/// smaller first) into fans: corners of a vertex that share a non-sharp
/// edge share a render vertex. A vertex whose corners form a single fan (a
/// crease's end, a dart, a boundary vertex) is left alone, keeping its
/// smooth normal.
///
/// Complexity: O(corners) plus O(valence²) per vertex on a sharp edge.
pub fn split_sharp_corners(
    faces: &[&[u32]],
    vertex_count: usize,
    sharp: &std::collections::HashSet<(u32, u32)>,
) -> SharpSplit {
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let mut on_sharp = vec![false; vertex_count];
    for &(a, b) in sharp {
        for v in [a, b] {
            if let Some(flag) = on_sharp.get_mut(v as usize) {
                *flag = true;
            }
        }
    }
    // (vertex, corner, face) of every corner at a vertex on a sharp edge.
    let mut corners: Vec<(u32, usize, usize)> = Vec::new();
    let mut at = 0usize;
    for (f, face) in faces.iter().enumerate() {
        for (k, &v) in face.iter().enumerate() {
            if on_sharp.get(v as usize) == Some(&true) {
                corners.push((v, at + k, f));
            }
        }
        at += face.len();
    }
    let total = at;
    if corners.is_empty() {
        return SharpSplit::default();
    }
    corners.sort_unstable();
    // The two neighbours of each corner along its face.
    let mut face_start = Vec::with_capacity(faces.len());
    let mut sum = 0usize;
    for face in faces {
        face_start.push(sum);
        sum += face.len();
    }
    let neighbours = |corner: usize, f: usize| {
        let face = faces[f];
        let k = corner - face_start[f];
        let n = face.len();
        [face[(k + 1) % n], face[(k + n - 1) % n]]
    };
    let mut out = SharpSplit::default();
    let mut next = vertex_count as u32;
    let mut start = 0;
    while start < corners.len() {
        let v = corners[start].0;
        let end = start + corners[start..].iter().take_while(|c| c.0 == v).count();
        let group = &corners[start..end];
        start = end;
        // Union-find over the vertex's corners: joined across soft edges.
        let mut parent: Vec<usize> = (0..group.len()).collect();
        fn find(parent: &mut [usize], mut x: usize) -> usize {
            while parent[x] != x {
                parent[x] = parent[parent[x]];
                x = parent[x];
            }
            x
        }
        let mut first_at: Vec<(u32, usize)> = Vec::new();
        for (i, &(_, corner, f)) in group.iter().enumerate() {
            for w in neighbours(corner, f) {
                if sharp.contains(&key(v, w)) {
                    continue;
                }
                match first_at.iter().find(|(x, _)| *x == w) {
                    Some(&(_, j)) => {
                        let (a, b) = (find(&mut parent, i), find(&mut parent, j));
                        parent[a] = b;
                    }
                    None => first_at.push((w, i)),
                }
            }
        }
        let roots: Vec<usize> = (0..group.len()).map(|i| find(&mut parent, i)).collect();
        let mut fans: Vec<usize> = roots.clone();
        fans.sort_unstable();
        fans.dedup();
        if fans.len() < 2 {
            continue;
        }
        if out.corner_vertex.is_empty() {
            out.corner_vertex = Vec::with_capacity(total);
            for face in faces {
                out.corner_vertex.extend_from_slice(face);
            }
        }
        // The fan of the vertex's first corner keeps the vertex itself.
        let keep = roots[0];
        for fan in fans {
            let index = if fan == keep {
                v
            } else {
                out.copies.push(v);
                next += 1;
                next - 1
            };
            for (i, &(_, corner, f)) in group.iter().enumerate() {
                if roots[i] == fan {
                    out.corner_vertex[corner] = index;
                    out.fan_polygons.push(faces[f].len() as u32);
                    out.fan_polygons.extend_from_slice(faces[f]);
                }
            }
            out.fans.push((index, out.fan_polygons.len()));
        }
    }
    out
}

/// The infinitely sharp, non-boundary edges of `mesh` under `creases`
/// (sharpness at or above [`INFINITE_SHARPNESS`]) as pairs of vertex ranks
/// (the order of `mesh.vertices()`), for [`split_sharp_corners`].
///
/// [`INFINITE_SHARPNESS`]: hedra_geom::subdivision::INFINITE_SHARPNESS
pub fn sharp_edges(
    mesh: &HalfEdgeMesh,
    creases: &hedra_geom::subdivision::Creases,
    rank: &[u32],
) -> std::collections::HashSet<(u32, u32)> {
    let infinite = f64::from(hedra_geom::subdivision::INFINITE_SHARPNESS);
    creases
        .edge_sharpness()
        .into_iter()
        .filter(|&(e, s)| s >= infinite && mesh.is_edge(e) && !mesh.is_boundary_edge(e))
        .map(|(e, _)| {
            let [a, b] = mesh.edge_vertices(e).map(|v| rank[v.index()]);
            (a.min(b), a.max(b))
        })
        .collect()
}

/// Which positions of a render mesh a patch rewrote
/// ([`patch_positions`], `SmoothRefinement::update_attributes`), so that
/// the viewport can grow the mesh's bounds instead of going over them all.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rewritten {
    /// All of them.
    All,
    /// Some, all within these bounds (empty, min above max, when none).
    Some {
        /// The least coordinates of the rewritten positions.
        min: [f32; 3],
        /// The greatest.
        max: [f32; 3],
    },
}

impl Rewritten {
    /// None rewritten yet.
    pub fn nothing() -> Rewritten {
        Rewritten::Some {
            min: [f32::INFINITY; 3],
            max: [f32::NEG_INFINITY; 3],
        }
    }
    /// Counts `p` as rewritten.
    pub fn include(&mut self, p: [f32; 3]) {
        if let Rewritten::Some { min, max } = self {
            for i in 0..3 {
                min[i] = min[i].min(p[i]);
                max[i] = max[i].max(p[i]);
            }
        }
    }
}

/// Rewrites, in buffers made by [`render_buffers`] from `old`, only the
/// positions and normals that differ in `new`, when the two meshes differ
/// only in vertex positions (a move, rotate or scale of elements while the
/// mouse drags): which positions it rewrote, or `None`, changing nothing,
/// when the connectivity or the buffer layout differs: rebuild with
/// [`render_buffers`] then.
///
/// Complexity: O(V + F) comparisons plus work proportional to the moved
/// vertices' neighbourhoods; no triangulation, no allocation per face.
pub fn patch_positions(
    positions: &mut [[f32; 3]],
    normals: &mut [[f32; 3]],
    old: &HalfEdgeMesh,
    new: &HalfEdgeMesh,
    shading: Shading,
) -> Option<Rewritten> {
    if !old.same_connectivity(new) || positions.len() != normals.len() {
        return None;
    }
    let moved: Vec<VertexId> = new
        .vertices()
        .filter(|&v| old.position(v) != new.position(v))
        .collect();
    // Every rewritten position is a moved vertex's.
    let mut written = Rewritten::nothing();
    for &v in &moved {
        written.include(new.position(v).as_vec3().to_array());
    }
    if moved.is_empty() {
        return Some(written);
    }
    match shading {
        Shading::Flat => {
            // Render corners are laid out face after face in id order. With
            // many moved vertices the faces are rewritten in two halves of
            // the ids on two threads, each half into its own corners.
            let halves = moved.len() >= PARALLEL_PATCH_VERTICES;
            let middle = if halves { new.face_capacity() / 2 } else { 0 };
            let mut start = vec![u32::MAX; new.face_capacity()];
            let (mut at, mut middle_corner) = (0u32, None);
            for f in new.faces() {
                if f.index() >= middle && middle_corner.is_none() {
                    middle_corner = Some(at as usize);
                }
                start[f.index()] = at;
                at += new.face_degree(f) as u32;
            }
            if at as usize != positions.len() {
                return None;
            }
            // The faces at moved vertices, visited in id order (the order of
            // their records in memory: on a 1M-face cage this is a third
            // faster than the order of the moved vertices).
            let mut reached = vec![false; new.face_capacity()];
            for &v in &moved {
                for f in new.vertex_faces(v) {
                    reached[f.index()] = true;
                }
            }
            let middle_corner = middle_corner.unwrap_or(positions.len());
            let (p0, p1) = positions.split_at_mut(middle_corner);
            let (n0, n1) = normals.split_at_mut(middle_corner);
            let corners = FlatCorners {
                mesh: new,
                reached: &reached,
                start: &start,
            };
            let end = new.face_capacity();
            if halves {
                rayon::join(
                    || corners.rewrite(0..middle, p0, n0, 0),
                    || corners.rewrite(middle..end, p1, n1, middle_corner),
                );
            } else {
                corners.rewrite(0..end, p1, n1, 0);
            }
        }
        Shading::Smooth => {
            if new.vertex_count() != positions.len() {
                return None;
            }
            let mut rank = vec![u32::MAX; new.vertex_capacity()];
            for (i, v) in new.vertices().enumerate() {
                rank[v.index()] = i as u32;
            }
            let mut touched: Vec<VertexId> = moved
                .iter()
                .flat_map(|&v| std::iter::once(v).chain(new.vertex_neighbors(v)))
                .collect();
            touched.sort();
            touched.dedup();
            for &v in &moved {
                positions[rank[v.index()] as usize] = new.position(v).as_vec3().to_array();
            }
            for v in touched {
                normals[rank[v.index()] as usize] = new.vertex_normal(v).as_vec3().to_array();
            }
        }
    }
    Some(written)
}

/// Moved vertices from which [`patch_positions`] rewrites flat faces on two
/// threads (G on 10 % of a 1M-face cage: 56 instead of 67 ms a frame).
const PARALLEL_PATCH_VERTICES: usize = 20_000;

/// The faces [`patch_positions`] rewrites in a flat render mesh.
struct FlatCorners<'a> {
    mesh: &'a HalfEdgeMesh,
    /// By face id: a moved vertex is on the face.
    reached: &'a [bool],
    /// By face id: its first corner in the render mesh.
    start: &'a [u32],
}

impl FlatCorners<'_> {
    /// Rewrites the corners (positions and Newell normal) of the reached
    /// faces among `faces` into `positions` and `normals`, which hold the
    /// render mesh's corners from `first_corner` on.
    fn rewrite(
        &self,
        faces: std::ops::Range<usize>,
        positions: &mut [[f32; 3]],
        normals: &mut [[f32; 3]],
        first_corner: usize,
    ) {
        let rings = self.mesh.has_rings();
        let mut corners: Vec<DVec3> = Vec::with_capacity(8);
        for f in faces.filter(|&f| self.reached[f]).map(|f| FaceId(f as u32)) {
            // One walk of the face for its corners and its normal.
            corners.clear();
            corners.extend(self.mesh.face_vertices(f).map(|v| self.mesh.position(v)));
            let n = if rings {
                self.mesh.face_normal(f)
            } else {
                hedra_geom::query::polygon_area_vector(&corners).normalize_or_zero()
            };
            let n = n.as_vec3().to_array();
            let at = self.start[f.index()] as usize - first_corner;
            for (i, p) in (at..).zip(&corners) {
                positions[i] = p.as_vec3().to_array();
                normals[i] = n;
            }
        }
    }
}

/// How the edit-mode overlay draws an edge (the viewport picks the colour).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EdgeLook {
    /// Not selected, related or creased.
    Plain,
    /// Selected, or between selected faces or (in vertex mode) vertices.
    Selected,
    /// Related to the one selected element (the topology inspector).
    Related,
    /// Creased with this sharpness (> 0).
    Crease(f64),
}

/// What the edit-mode edge overlay highlights.
#[derive(Clone, Copy, Debug)]
pub struct OverlaySelection<'a> {
    /// In vertex mode: an edge with both ends here is selected.
    pub vertices: Option<&'a std::collections::BTreeSet<VertexId>>,
    /// Selected edges.
    pub edges: &'a std::collections::BTreeSet<hedra_geom::EdgeId>,
    /// An edge of a selected face is selected.
    pub faces: &'a std::collections::BTreeSet<FaceId>,
    /// Edges related to the selected element (drawn as related).
    pub related_edges: &'a std::collections::BTreeSet<hedra_geom::EdgeId>,
    /// An edge of a related face is related.
    pub related_faces: &'a std::collections::BTreeSet<FaceId>,
}

/// Every live edge of `mesh` as its two end points and its look, for the
/// edit-mode overlay; selection beats relation beats crease.
///
/// Complexity: O(E + selection), with flag arrays indexed by id rather than
/// a set lookup per edge (a 100,000-face mesh is redrawn on every frame of
/// a drag).
pub fn edge_overlay(
    mesh: &HalfEdgeMesh,
    sel: &OverlaySelection,
    creases: &hedra_geom::subdivision::Creases,
) -> Vec<([f32; 3], [f32; 3], EdgeLook)> {
    let flags = |n: usize, ids: &mut dyn Iterator<Item = usize>| {
        let mut f = vec![false; n];
        for i in ids.filter(|&i| i < n) {
            f[i] = true;
        }
        f
    };
    let hot_vertex = flags(
        mesh.vertex_capacity(),
        &mut sel.vertices.into_iter().flatten().map(|v| v.index()),
    );
    let hot_face = flags(
        mesh.face_capacity(),
        &mut sel.faces.iter().map(|f| f.index()),
    );
    let related_face = flags(
        mesh.face_capacity(),
        &mut sel.related_faces.iter().map(|f| f.index()),
    );
    let face_flag = |flags: &[bool], e: hedra_geom::EdgeId| {
        mesh.edge_faces(e)
            .iter()
            .flatten()
            .any(|f| flags[f.index()])
    };
    mesh.edges()
        .map(|e| {
            let [a, b] = mesh.edge_vertices(e);
            let look = if sel.edges.contains(&e)
                || (hot_vertex[a.index()] && hot_vertex[b.index()])
                || (!sel.faces.is_empty() && face_flag(&hot_face, e))
            {
                EdgeLook::Selected
            } else if sel.related_edges.contains(&e)
                || (!sel.related_faces.is_empty() && face_flag(&related_face, e))
            {
                EdgeLook::Related
            } else {
                match creases.edge(e) {
                    c if c > 0.0 => EdgeLook::Crease(c),
                    _ => EdgeLook::Plain,
                }
            };
            (
                mesh.position(a).as_vec3().to_array(),
                mesh.position(b).as_vec3().to_array(),
                look,
            )
        })
        .collect()
}

/// Viewport tessellation of curves and surfaces, as a fraction of their size
/// ([`extent`]); export uses its own, finer tolerance.
pub const VIEW_TOLERANCE: f64 = 5e-4;

/// The diagonal of the points' bounding box (at least 1e-9, also for no
/// points): the size that tessellation tolerances and analysis drawings
/// scale with.
pub fn extent(points: &[hedra_geom::DVec3]) -> f64 {
    if points.is_empty() {
        return 1e-9;
    }
    let (lo, hi) = points.iter().fold(
        (hedra_geom::DVec3::INFINITY, hedra_geom::DVec3::NEG_INFINITY),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    (hi - lo).length().max(1e-9)
}

/// The parameters of a NURBS surface's render grid (row-major by u), kept
/// so a drag re-evaluates only the part of the grid its change can reach.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceGrid {
    /// The u values of the grid rows, increasing, from the domain's start to
    /// its end.
    pub us: Vec<f64>,
    /// The v values of the grid columns, increasing, over the domain.
    pub vs: Vec<f64>,
}

/// The grid the viewport tessellates a NURBS surface on:
/// [`hedra_geom::surfaces::tessellate::surface_parameters`] at
/// [`VIEW_TOLERANCE`] of the surface's size (every knot a grid line, the
/// lines between spread by curvature), the grid the export uses at its
/// own tolerance.
pub fn surface_grid(surface: &hedra_geom::surfaces::NurbsSurface) -> SurfaceGrid {
    let tol = VIEW_TOLERANCE * extent(surface.points());
    let (us, vs) = hedra_geom::surfaces::tessellate::surface_parameters(surface, tol);
    SurfaceGrid { us, vs }
}

/// A tile of a NURBS surface's render grid: the grid cells of one knot
/// span cell, and the control points that shape it. A control point
/// (i, j) moves the surface only on `[U_i, U_{i+p+1}] × [V_j, V_{j+q+1}]`
/// (the local support of the B-spline basis, Piegl & Tiller, *The NURBS
/// Book*, property P2.1), so a tile changes only when one of its `inputs`
/// does.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceTile {
    /// Grid cells along u; the tile's grid rows are `rows.start..=rows.end`.
    pub rows: std::ops::Range<usize>,
    /// Grid cells along v; the tile's grid columns are `cols.start..=cols.end`.
    pub cols: std::ops::Range<usize>,
    /// Control points (`i * nv + j`) whose support meets the tile.
    pub inputs: Vec<u32>,
}

/// The cells of a grid's parameters (`params[c]..params[c + 1]`) grouped by
/// the knot span holding each cell's middle, in order.
fn cells_by_span(params: &[f64], knots: &[f64]) -> Vec<std::ops::Range<usize>> {
    let mut groups: Vec<(usize, std::ops::Range<usize>)> = Vec::new();
    for c in 0..params.len().saturating_sub(1) {
        let middle = 0.5 * (params[c] + params[c + 1]);
        let span = knots.partition_point(|&k| k <= middle);
        match groups.last_mut() {
            Some((s, cells)) if *s == span => cells.end = c + 1,
            _ => groups.push((span, c..c + 1)),
        }
    }
    groups.into_iter().map(|(_, cells)| cells).collect()
}

/// The tiles of a NURBS surface's render grid, one per knot span cell that
/// holds grid cells, row by row (u) then column (v). Together they cover
/// every cell once; neighbours share their boundary grid points.
pub fn surface_tiles(
    surface: &hedra_geom::surfaces::NurbsSurface,
    grid: &SurfaceGrid,
) -> Vec<SurfaceTile> {
    let ((p, q), (ku, kv)) = (surface.degrees(), surface.knots());
    let (nu, nv) = surface.size();
    // The basis N_i is zero from U_{i+p+1} on (the domain's end aside,
    // which no tile starts at); at U_i it may not be (repeated knots).
    let meets = |knots: &[f64], degree: usize, i: usize, lo: f64, hi: f64| {
        knots[i] <= hi && knots[i + degree + 1] > lo
    };
    let row_groups = cells_by_span(&grid.us, ku);
    let col_groups = cells_by_span(&grid.vs, kv);
    let mut tiles = Vec::with_capacity(row_groups.len() * col_groups.len());
    for rows in &row_groups {
        let (u_lo, u_hi) = (grid.us[rows.start], grid.us[rows.end]);
        let is: Vec<usize> = (0..nu).filter(|&i| meets(ku, p, i, u_lo, u_hi)).collect();
        for cols in &col_groups {
            let (v_lo, v_hi) = (grid.vs[cols.start], grid.vs[cols.end]);
            let inputs = is
                .iter()
                .flat_map(|&i| {
                    (0..nv)
                        .filter(move |&j| meets(kv, q, j, v_lo, v_hi))
                        .map(move |j| (i * nv + j) as u32)
                })
                .collect();
            tiles.push(SurfaceTile {
                rows: rows.clone(),
                cols: cols.clone(),
                inputs,
            });
        }
    }
    tiles
}

/// Render buffers of one tile: its grid points evaluated on `surface` with
/// their normals, two triangles per cell (the winding of
/// [`hedra_geom::surfaces::tessellate::grid_triangles`]).
pub fn tile_buffers(
    surface: &hedra_geom::surfaces::NurbsSurface,
    grid: &SurfaceGrid,
    tile: &SurfaceTile,
) -> RenderBuffers {
    let us = &grid.us[tile.rows.start..=tile.rows.end];
    let vs = &grid.vs[tile.cols.start..=tile.cols.end];
    let (points, normals) = surface.grid(us, vs, true);
    let f32s = |v: &hedra_geom::DVec3| v.as_vec3().to_array();
    RenderBuffers {
        positions: points.iter().map(f32s).collect(),
        normals: normals.iter().map(f32s).collect(),
        indices: hedra_geom::surfaces::tessellate::grid_triangles(tile.rows.len(), tile.cols.len())
            .into_iter()
            .flatten()
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hedra_geom::Primitive;

    /// Enough moved vertices to rewrite the faces in two halves on two
    /// threads: the same corners as a rebuild, bit for bit, with dead
    /// faces (holes in the face ids) in both halves and at the middle.
    #[test]
    fn patching_many_moved_vertices_in_two_halves_equals_rebuilding() {
        let mut grid = Primitive::Grid {
            x_segments: 210,
            z_segments: 200,
            size: 2.0,
        }
        .build()
        .unwrap();
        let middle = grid.face_capacity() / 2;
        grid.delete_faces(
            &[FaceId(17), FaceId(middle as u32 - 1), FaceId(middle as u32)],
            true,
        );
        grid.validate().unwrap();
        let mut moved = grid.clone();
        let vertices: Vec<VertexId> = moved.vertices().step_by(2).collect();
        assert!(vertices.len() >= PARALLEL_PATCH_VERTICES);
        for (i, &v) in vertices.iter().enumerate() {
            let p = moved.position(v);
            moved.set_position(v, p + glam::DVec3::new(0.0, 0.01 * (i % 7) as f64, 0.001));
        }
        let mut b = render_buffers(&grid, Shading::Flat);
        patch_positions(
            &mut b.positions,
            &mut b.normals,
            &grid,
            &moved,
            Shading::Flat,
        )
        .unwrap();
        let rebuilt = render_buffers(&moved, Shading::Flat);
        assert_eq!(b.positions, rebuilt.positions);
        assert_eq!(b.normals, rebuilt.normals);
    }

    #[test]
    fn patching_moved_vertices_equals_rebuilding_and_refuses_other_topology() {
        let grid = Primitive::Grid {
            x_segments: 6,
            z_segments: 5,
            size: 2.0,
        }
        .build()
        .unwrap();
        let mut moved = grid.clone();
        for v in moved.vertices().take(7).collect::<Vec<_>>() {
            let p = moved.position(v);
            moved.set_position(v, p + glam::DVec3::new(0.1, 0.3, -0.2));
        }
        for shading in [Shading::Flat, Shading::Smooth] {
            let mut b = render_buffers(&grid, shading);
            let written = patch_positions(&mut b.positions, &mut b.normals, &grid, &moved, shading);
            let Some(Rewritten::Some { min, max }) = written else {
                panic!("{shading:?}: patched, within bounds: {written:?}");
            };
            let expected = moved
                .vertices()
                .filter(|&v| moved.position(v) != grid.position(v))
                .map(|v| moved.position(v).as_vec3());
            let (lo, hi) = expected.fold(
                (glam::Vec3::INFINITY, glam::Vec3::NEG_INFINITY),
                |(lo, hi), p| (lo.min(p), hi.max(p)),
            );
            assert_eq!(
                (min, max),
                (lo.to_array(), hi.to_array()),
                "{shading:?}: the moved vertices' bounds"
            );
            let rebuilt = render_buffers(&moved, shading);
            assert_eq!(b.positions, rebuilt.positions, "{shading:?}");
            if shading == Shading::Flat {
                // Face normals: the same Newell sum in the same order.
                assert_eq!(b.normals, rebuilt.normals);
            }
            for (n, m) in b.normals.iter().zip(&rebuilt.normals) {
                assert!((glam::Vec3::from(*n) - glam::Vec3::from(*m)).length() < 1e-6);
            }
            // Different connectivity: refused, buffers untouched.
            let cube = Primitive::Cube { size: 1.0 }.build().unwrap();
            let before = b.clone();
            assert!(
                patch_positions(&mut b.positions, &mut b.normals, &grid, &cube, shading).is_none()
            );
            assert_eq!(b, before);
        }
        assert_eq!(render_buffers(&grid, Shading::Flat).positions.len(), 30 * 4);
        // The overlay: a selected face's four edges, an edge between two
        // selected vertices, a creased edge; everything else plain.
        use std::collections::BTreeSet;
        let f = grid.faces().next().unwrap();
        let face_edges: BTreeSet<_> = grid.face_halfedges(f).map(|h| h.edge()).collect();
        let e = grid.edges().find(|e| !face_edges.contains(e)).unwrap();
        let ends: BTreeSet<_> = grid.edge_vertices(e).into_iter().collect();
        let creased = grid
            .edges()
            .find(|x| *x != e && !face_edges.contains(x))
            .unwrap();
        let mut creases = hedra_geom::subdivision::Creases::default();
        creases.set_edge(creased, 2.5);
        let (empty_e, empty_f) = (BTreeSet::new(), BTreeSet::new());
        let faces: BTreeSet<_> = [f].into_iter().collect();
        let sel = OverlaySelection {
            vertices: Some(&ends),
            edges: &empty_e,
            faces: &faces,
            related_edges: &empty_e,
            related_faces: &empty_f,
        };
        let looks: Vec<EdgeLook> = edge_overlay(&grid, &sel, &creases)
            .into_iter()
            .map(|x| x.2)
            .collect();
        assert_eq!(looks.len(), grid.edge_count());
        assert_eq!(
            looks.iter().filter(|l| **l == EdgeLook::Selected).count(),
            5
        );
        assert_eq!(
            looks
                .iter()
                .filter(|l| matches!(l, EdgeLook::Crease(c) if *c == 2.5))
                .count(),
            1
        );
        assert_eq!(
            render_buffers(&grid, Shading::Smooth).positions.len(),
            7 * 6
        );
    }

    #[test]
    fn extent_is_the_bounding_box_diagonal_and_never_zero() {
        use hedra_geom::DVec3;
        let points = [DVec3::new(1.0, 2.0, 3.0), DVec3::new(4.0, 6.0, 3.0)];
        assert_eq!(extent(&points), 5.0);
        assert_eq!(extent(&[DVec3::ONE]), 1e-9);
        assert_eq!(extent(&[]), 1e-9);
    }

    #[test]
    fn the_surface_grid_spans_the_domain_and_refines_with_curvature() {
        use hedra_geom::surfaces::{NurbsSurface, Surface};
        // A plane is flat: one cell each way is exact.
        let plane = NurbsSurface::plane(2.0);
        let grid = surface_grid(&plane);
        let ((u0, u1), (v0, v1)) = plane.domain();
        assert_eq!((grid.us.first(), grid.us.last()), (Some(&u0), Some(&u1)));
        assert_eq!((grid.vs.first(), grid.vs.last()), (Some(&v0), Some(&v1)));
        assert_eq!((grid.us.len(), grid.vs.len()), (2, 2), "{grid:?}");
        // A sphere bends: many more cells, increasing, every knot a line.
        let sphere = NurbsSurface::sphere(hedra_geom::DVec3::ZERO, 1.0);
        let round = surface_grid(&sphere);
        assert!(
            round.us.len() > 8 && round.vs.len() > 8,
            "{} × {}",
            round.us.len(),
            round.vs.len()
        );
        assert!(round.us.windows(2).all(|w| w[0] < w[1]));
        assert!(round.vs.windows(2).all(|w| w[0] < w[1]));
        let (ku, kv) = sphere.knots();
        assert!(ku.iter().all(|k| round.us.contains(k)), "{:?}", round.us);
        assert!(kv.iter().all(|k| round.vs.contains(k)), "{:?}", round.vs);
    }

    fn wavy_sheet() -> hedra_geom::surfaces::NurbsSurface {
        let points = (0..64)
            .map(|k| {
                let (i, j) = ((k / 8) as f64, (k % 8) as f64);
                glam::DVec3::new(i, ((i + j) * 0.7).sin(), j)
            })
            .collect();
        let knots = hedra_geom::curves::nurbs::clamped_uniform_knots(3, 8);
        hedra_geom::surfaces::NurbsSurface::new(
            3,
            3,
            knots.clone(),
            knots,
            8,
            8,
            points,
            vec![1.0; 64],
        )
        .unwrap()
    }

    #[test]
    fn tiles_cover_the_grid_once_per_knot_span_and_equal_the_whole_surface() {
        let sheet = wavy_sheet();
        let grid = surface_grid(&sheet);
        let tiles = surface_tiles(&sheet, &grid);
        assert_eq!(tiles.len(), 25, "5 × 5 knot spans");
        // Every cell in exactly one tile.
        let (cu, cv) = (grid.us.len() - 1, grid.vs.len() - 1);
        let mut covered = vec![0; cu * cv];
        for t in &tiles {
            for a in t.rows.clone() {
                for b in t.cols.clone() {
                    covered[a * cv + b] += 1;
                }
            }
        }
        assert!(covered.iter().all(|&n| n == 1));
        // Each tile's points are the whole surface's at the same parameters.
        let (whole, _) = sheet.grid(&grid.us, &grid.vs, false);
        for t in &tiles {
            let b = tile_buffers(&sheet, &grid, t);
            let cols = t.cols.len() + 1;
            for (k, p) in b.positions.iter().enumerate() {
                let (a, c) = (t.rows.start + k / cols, t.cols.start + k % cols);
                let want = whole[a * grid.vs.len() + c].as_vec3();
                assert!((glam::Vec3::from(*p) - want).length() < 1e-5);
            }
            assert_eq!(b.indices.len(), 6 * t.rows.len() * t.cols.len());
        }
    }

    #[test]
    fn a_changed_point_reaches_only_the_tiles_listing_it() {
        let sheet = wavy_sheet();
        let grid = surface_grid(&sheet);
        let tiles = surface_tiles(&sheet, &grid);
        // Corner point 0 shapes the corner span (and a neighbour holding a
        // grid cell across the span's end); an inner point a 4 × 4 block of
        // spans.
        let with = |k: u32| tiles.iter().filter(|t| t.inputs.contains(&k)).count();
        assert!((1..=4).contains(&with(0)), "{}", with(0));
        assert!((16..=25).contains(&with(3 * 8 + 3)), "{}", with(3 * 8 + 3));
        let mut moved = sheet.clone();
        moved.set_weight(3, 3, 5.0).unwrap();
        for t in &tiles {
            let same = tile_buffers(&sheet, &grid, t) == tile_buffers(&moved, &grid, t);
            if !t.inputs.contains(&(3 * 8 + 3)) {
                assert!(same, "a tile without the point does not change");
            }
        }
        assert!(
            tiles
                .iter()
                .any(|t| tile_buffers(&sheet, &grid, t) != tile_buffers(&moved, &grid, t))
        );
    }
}
