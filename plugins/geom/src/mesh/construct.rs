//! Building a mesh's records in bulk from an indexed face set: the strict
//! [`from_polygons`](HalfEdgeMesh::from_polygons), and the build from
//! polygons whose corners already name their edges (a subdivision level's
//! tables). Both write the arrays directly (one pass per corner), which is
//! why they live inside the [`mesh`](super) module; the repairing build and
//! compaction in [`crate::build`] go through them.
//!
//! Twins are found with a compressed per-vertex list of outgoing corners
//! (each with its far end beside it) instead of a hash map, so building is
//! linear in the number of corners and the search reads one short
//! contiguous list per corner.

use super::{HalfEdgeMesh, HalfEdgeRecord, Topology};
use crate::build::{BuildError, check_face};
use crate::ids::NONE;
use glam::DVec3;

/// Calls `visit(corner, from, to)` for each face's corners in order, with
/// the corner's vertex and the vertex its edge runs to; stops at the first
/// error.
#[inline]
fn each_corner<E>(
    face_offsets: &[u32],
    corner_vertex: &[u32],
    mut visit: impl FnMut(usize, u32, u32) -> Result<(), E>,
) -> Result<(), E> {
    for w in face_offsets.windows(2) {
        let r = w[0] as usize..w[1] as usize;
        let poly = &corner_vertex[r.clone()];
        let last = poly.len() - 1;
        for (k, c) in r.enumerate() {
            visit(c, poly[k], poly[if k == last { 0 } else { k + 1 }])?;
        }
    }
    Ok(())
}

/// Each vertex's outgoing corners as compressed rows: `out[row[v]..row[v +
/// 1]]` holds `[far end, corner]` for the corners at `v`, in corner order.
#[derive(Clone, Copy)]
struct Rows<'a> {
    row: &'a [u32],
    out: &'a [[u32; 2]],
}

impl Rows<'_> {
    /// The outgoing corners of `v`.
    #[inline]
    fn outgoing(&self, v: u32) -> &[[u32; 2]] {
        &self.out[self.row[v as usize] as usize..self.row[v as usize + 1] as usize]
    }
}

/// Pairs corners into half-edges (the first corner of edge k, in corner
/// order, gets 2k, its twin 2k + 1) when every edge is manifold and
/// consistently oriented, returning the half-edge count; `None` as soon as
/// some edge is not, without saying which (then
/// [`pair_corners_checked`] finds the first).
///
/// Only a corner no earlier corner has claimed searches, and only the list
/// of its far end `b` for corners running back to its own vertex `a`: it
/// is the first corner of its edge, so a single unclaimed corner back is
/// its twin. A second corner along `a → b` shows up later, either finding
/// that twin claimed or, on a boundary edge, here, where the list of `a` is
/// read for corners along `a → b` (boundary corners only). Each edge is thus
/// searched once, from one list, instead of from both lists at every corner.
fn pair_corners(
    face_offsets: &[u32],
    corner_vertex: &[u32],
    rows: Rows,
    corner_he: &mut [u32],
) -> Option<u32> {
    let mut halfedge_count = 0u32;
    let paired = each_corner(face_offsets, corner_vertex, |c, a, b| {
        if corner_he[c] != NONE {
            return Ok(());
        }
        let mut twins = rows.outgoing(b).iter().filter(|x| x[0] == a);
        match (twins.next(), twins.next()) {
            (Some(&[_, t]), None) if corner_he[t as usize] == NONE => {
                corner_he[t as usize] = halfedge_count + 1;
            }
            (None, _) if rows.outgoing(a).iter().filter(|x| x[0] == b).count() == 1 => {}
            _ => return Err(()),
        }
        corner_he[c] = halfedge_count;
        halfedge_count += 2;
        Ok(())
    });
    paired.ok().map(|()| halfedge_count)
}

/// [`pair_corners`] checking both directions at every corner, so that the
/// error names the first corner (in corner order) whose edge is in more
/// than two faces ([`BuildError::NonManifoldEdge`]) or twice in one
/// direction ([`BuildError::InconsistentOrientation`]).
fn pair_corners_checked(
    face_offsets: &[u32],
    corner_vertex: &[u32],
    rows: Rows,
    corner_he: &mut [u32],
) -> Result<u32, BuildError> {
    let mut halfedge_count = 0u32;
    each_corner(face_offsets, corner_vertex, |c, a, b| {
        let same_dir = rows.outgoing(a).iter().filter(|x| x[0] == b).count();
        let mut twins = rows.outgoing(b).iter().filter(|x| x[0] == a);
        let first_twin = twins.next().map(|x| x[1] as usize);
        let twin_count = usize::from(first_twin.is_some()) + twins.count();
        if same_dir + twin_count > 2 || same_dir > 1 {
            let face_of = |c: u32| face_offsets.partition_point(|&s| s <= c) - 1;
            let faces_of = |from: u32, to: u32| -> Vec<usize> {
                rows.outgoing(from)
                    .iter()
                    .filter(|x| x[0] == to)
                    .map(|x| face_of(x[1]))
                    .collect()
            };
            if same_dir + twin_count > 2 {
                let mut faces = faces_of(a, b);
                faces.extend(faces_of(b, a));
                faces.sort_unstable();
                return Err(BuildError::NonManifoldEdge {
                    a: a.min(b),
                    b: a.max(b),
                    faces,
                });
            }
            return Err(BuildError::InconsistentOrientation {
                a,
                b,
                faces: faces_of(a, b),
            });
        }
        if corner_he[c] == NONE {
            corner_he[c] = halfedge_count;
            if let Some(t) = first_twin {
                corner_he[t] = halfedge_count + 1;
            }
            halfedge_count += 2;
        }
        Ok(())
    })?;
    Ok(halfedge_count)
}

impl HalfEdgeMesh {
    /// Builds a mesh from positions and polygons (vertex indices,
    /// counter-clockwise seen from outside). Vertex `i` gets id `i`, face `j`
    /// gets id `j`, edges are numbered in order of first use.
    ///
    /// # Errors
    /// A [`BuildError`] naming the first face, edge or vertex that breaks
    /// manifoldness or consistent orientation; nothing is built.
    ///
    /// Complexity: O(corners × valence).
    ///
    /// Each edge is searched once, in one list (see `pair_corners`); only
    /// when some edge is bad are all corners checked again, to name the
    /// first.
    pub fn from_polygons<P: AsRef<[u32]>>(
        positions: &[DVec3],
        polygons: &[P],
    ) -> Result<Self, BuildError> {
        let nv = positions.len();
        if nv >= NONE as usize {
            return Err(BuildError::TooLarge { what: "vertices" });
        }
        if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
            return Err(BuildError::NonFinitePosition { vertex: i as u32 });
        }
        // Corners: corner c of face f is corner_vertex[c], for c in
        // face_offsets[f]..face_offsets[f + 1]; its edge runs to the next
        // corner of the face.
        // Exact capacity (one pass over the lengths) so the corner list is
        // never regrown and copied.
        let corner_total: usize = polygons.iter().map(|p| p.as_ref().len()).sum();
        let mut face_offsets: Vec<u32> = Vec::with_capacity(polygons.len() + 1);
        face_offsets.push(0);
        let mut corner_vertex: Vec<u32> = Vec::with_capacity(corner_total);
        for (fi, poly) in polygons.iter().enumerate() {
            let poly = poly.as_ref();
            check_face(fi, poly, nv)?;
            if corner_vertex.len() + poly.len() >= (NONE / 2) as usize {
                return Err(BuildError::TooLarge { what: "corners" });
            }
            corner_vertex.extend_from_slice(poly);
            face_offsets.push(corner_vertex.len() as u32);
        }
        let nc = corner_vertex.len();
        // Outgoing corners per vertex (compressed rows, each row in corner
        // order): the far end of each corner's edge, and the corner.
        let mut row = vec![0u32; nv + 2];
        for &v in &corner_vertex {
            row[v as usize + 2] += 1;
        }
        for i in 2..row.len() {
            row[i] += row[i - 1];
        }
        let mut out = vec![[0u32; 2]; nc];
        let _ = each_corner(&face_offsets, &corner_vertex, |c, v, to| {
            let slot = &mut row[v as usize + 1];
            out[*slot as usize] = [to, c as u32];
            *slot += 1;
            Ok::<(), ()>(())
        });
        row.pop();
        let rows = Rows {
            row: &row,
            out: &out,
        };

        // Pair corners into edges, numbered in order of first use: the
        // first corner of edge k gets half-edge 2k, its twin 2k + 1.
        let mut corner_he = vec![NONE; nc];
        let paired = pair_corners(&face_offsets, &corner_vertex, rows, &mut corner_he);
        let halfedge_count = match paired {
            Some(count) => count,
            None => {
                // Some edge is bad: the full check names the first one.
                corner_he.fill(NONE);
                pair_corners_checked(&face_offsets, &corner_vertex, rows, &mut corner_he)?
            }
        };
        drop(out);
        let mesh = Self::assemble(
            positions.to_vec(),
            &face_offsets,
            &corner_vertex,
            &corner_he,
            halfedge_count as usize,
        )?;
        // Corners at each vertex: the length of its row.
        mesh.check_fans(|v| row[v + 1] - row[v])?;
        Ok(mesh)
    }

    /// Builds the mesh of a subdivision level's faces straight from the
    /// level's tables ([`LevelFaces`]), in one pass over the corners: every
    /// twin is known, so nothing is searched or sorted. Only faces with `shown(f)`
    /// are kept, then the unused level vertices with `keep_unused(v)` (as
    /// isolated vertices).
    ///
    /// The result is the mesh [`from_polygons`](Self::from_polygons) makes
    /// of the kept faces, ids and all: vertices and edges numbered in order
    /// of first use, each edge's first corner giving its even half-edge.
    /// Also returns, per level vertex and per level edge, its index in the
    /// mesh ([`NONE`] when not kept).
    ///
    /// The caller guarantees what a refinement of a valid half-edge mesh
    /// gives: well-formed faces, every edge used by at most two corners in
    /// opposite directions, distinct edges joining distinct vertex pairs.
    /// Closed fans touching at a vertex, which hiding faces can make, are
    /// found when `check_fans` is set.
    ///
    /// # Errors
    /// A non-finite position ([`BuildError::NonFinitePosition`], naming the
    /// mesh vertex); with `check_fans`, a vertex with two fans
    /// ([`BuildError::NonManifoldVertex`]); `TooLarge` past `u32` ids.
    ///
    /// Complexity: O(corners), one pass plus one over the boundary.
    pub(crate) fn from_level_faces(
        positions: &[DVec3],
        level: LevelFaces<'_>,
        shown: impl Fn(usize) -> bool,
        keep_unused: impl Fn(usize) -> bool,
        check_fans: bool,
    ) -> Result<(HalfEdgeMesh, Vec<u32>, Vec<u32>), BuildError> {
        let LevelFaces {
            sides,
            face_offsets,
            corner_vertex,
            corner_edge,
            edge_count,
        } = level;
        if corner_vertex.len() >= (NONE / 2) as usize || positions.len() >= NONE as usize {
            return Err(BuildError::TooLarge { what: "corners" });
        }
        let nf_all = if sides > 0 {
            corner_vertex.len() / sides as usize
        } else {
            face_offsets.len().saturating_sub(1)
        };
        let mut b = LevelBuild {
            positions,
            vertex_map: vec![NONE; positions.len()],
            edge_map: vec![NONE; edge_count],
            kept_positions: Vec::with_capacity(positions.len()),
            vertex_out: Vec::with_capacity(positions.len()),
            halfedges: Vec::with_capacity(2 * edge_count),
            face_halfedge: Vec::with_capacity(nf_all),
            corners: 0,
            long_face: Vec::new(),
        };
        // All quads or all triangles (every Catmull-Clark and Loop level):
        // fixed-size faces, so the per-face loops unroll.
        match sides {
            4 => b.add_fixed_faces::<4>(corner_vertex, corner_edge, &shown),
            3 => b.add_fixed_faces::<3>(corner_vertex, corner_edge, &shown),
            _ => {
                let corners = |f: usize| match sides as usize {
                    0 => face_offsets[f] as usize..face_offsets[f + 1] as usize,
                    n => n * f..n * (f + 1),
                };
                for f in (0..nf_all).filter(|&f| shown(f)) {
                    b.add_face(&corner_vertex[corners(f)], &corner_edge[corners(f)]);
                }
            }
        }
        let LevelBuild {
            mut vertex_map,
            edge_map,
            mut kept_positions,
            mut vertex_out,
            mut halfedges,
            face_halfedge,
            corners,
            ..
        } = b;
        for (v, u) in vertex_map.iter_mut().enumerate() {
            if *u == NONE && keep_unused(v) {
                *u = kept_positions.len() as u32;
                kept_positions.push(positions[v]);
                vertex_out.push(NONE);
            }
        }
        if let Some(v) = kept_positions.iter().position(|p| !p.is_finite()) {
            return Err(BuildError::NonFinitePosition { vertex: v as u32 });
        }
        let nv = kept_positions.len();
        if corners != halfedges.len() {
            link_boundary(&mut halfedges, &mut vertex_out, true)?;
        }
        let mesh = HalfEdgeMesh::all_live(kept_positions, vertex_out, halfedges, face_halfedge);
        if check_fans {
            let mut degree = vec![0u32; nv];
            for r in mesh.topology.halfedges.iter().filter(|r| r.face != NONE) {
                degree[r.origin as usize] += 1;
            }
            mesh.check_fans(|v| degree[v])?;
        }
        Ok((mesh, vertex_map, edge_map))
    }

    /// The records from checked faces and finite positions, given each
    /// corner's half-edge (`corner_he`: the first corner of each edge has
    /// the even one, its twin corner, if any, the odd one; `halfedge_count`
    /// of them). Half-edges no corner has are the boundary.
    fn assemble(
        positions: Vec<DVec3>,
        face_offsets: &[u32],
        corner_vertex: &[u32],
        corner_he: &[u32],
        halfedge_count: usize,
    ) -> Result<HalfEdgeMesh, BuildError> {
        if halfedge_count >= NONE as usize {
            return Err(BuildError::TooLarge { what: "half-edges" });
        }
        let nv = positions.len();
        let nf = face_offsets.len().saturating_sub(1);
        let blank = HalfEdgeRecord {
            origin: NONE,
            next: NONE,
            prev: NONE,
            face: NONE,
        };
        // Edges are numbered in order of first use, so the even half-edges
        // come in increasing order along the corners: each is appended with
        // a blank twin after it (filled when the twin's corner comes, or
        // left as boundary), and the array is written once, without a fill.
        let mut halfedges = Vec::with_capacity(halfedge_count);
        for (f, w) in face_offsets.windows(2).enumerate() {
            let r = w[0] as usize..w[1] as usize;
            let hs = &corner_he[r.clone()];
            let n = hs.len();
            for (k, (&h, &v)) in hs.iter().zip(&corner_vertex[r]).enumerate() {
                let record = HalfEdgeRecord {
                    origin: v,
                    next: hs[if k + 1 == n { 0 } else { k + 1 }],
                    prev: hs[if k == 0 { n - 1 } else { k - 1 }],
                    face: f as u32,
                };
                if h as usize == halfedges.len() {
                    halfedges.push(record);
                    halfedges.push(blank);
                } else {
                    halfedges[h as usize] = record;
                }
            }
        }
        // Every even half-edge has a corner, so all were appended.
        debug_assert_eq!(halfedges.len(), halfedge_count);
        // Boundary half-edges (no corner has them; a closed mesh has none):
        // each starts where its twin ends, and a vertex may start at most one.
        let mut vertex_out = vec![NONE; nv];
        if corner_vertex.len() != halfedge_count {
            link_boundary(&mut halfedges, &mut vertex_out, false)?;
        }
        // Other vertices: the half-edge of their first corner.
        for (&v, &h) in corner_vertex.iter().zip(corner_he) {
            let o = &mut vertex_out[v as usize];
            if *o == NONE {
                *o = h;
            }
        }
        let face_halfedge = face_offsets[..nf]
            .iter()
            .map(|&c| corner_he[c as usize])
            .collect();
        Ok(HalfEdgeMesh::all_live(
            positions,
            vertex_out,
            halfedges,
            face_halfedge,
        ))
    }

    /// A mesh of these records with every element live and no inner rings.
    pub(super) fn all_live(
        positions: Vec<DVec3>,
        vertex_out: Vec<u32>,
        halfedges: Vec<HalfEdgeRecord>,
        face_halfedge: Vec<u32>,
    ) -> HalfEdgeMesh {
        let (nv, ne, nf) = (positions.len(), halfedges.len() / 2, face_halfedge.len());
        HalfEdgeMesh::from_parts(
            positions,
            Topology {
                vertex_out,
                halfedges,
                face_halfedge,
                vertex_dead: vec![false; nv],
                edge_dead: vec![false; ne],
                face_dead: vec![false; nf],
                live_vertices: nv,
                live_edges: ne,
                live_faces: nf,
                ..Default::default()
            },
        )
    }

    /// Closed fans touching at a vertex (two cones tip to tip) pass the
    /// boundary test of [`assemble`](Self::assemble); walking each vertex's
    /// fan finds them: it must meet every corner at the vertex (and its
    /// boundary half-edge). `corners_at(v)` is the number of corners at
    /// vertex `v`.
    fn check_fans(&self, corners_at: impl Fn(usize) -> u32) -> Result<(), BuildError> {
        for v in 0..self.positions.len() {
            let corners = corners_at(v);
            let start = self.topology.vertex_out[v];
            if start == NONE {
                if corners > 0 {
                    return Err(BuildError::NonManifoldVertex { vertex: v as u32 });
                }
                continue;
            }
            // The fan around v: twin(prev(h)) from its outgoing half-edge,
            // which must come back to the start after `degree` steps.
            let boundary = self.topology.halfedges[start as usize].face == NONE;
            let deg = corners as usize + usize::from(boundary);
            let (mut h, mut steps) = (start, 0);
            loop {
                h = self.topology.halfedges[h as usize].prev ^ 1;
                steps += 1;
                if h == start || steps > deg {
                    break;
                }
            }
            if h != start || steps != deg {
                return Err(BuildError::NonManifoldVertex { vertex: v as u32 });
            }
        }
        Ok(())
    }
}

/// Fills in the boundary half-edges: the odd half-edges no corner has (a
/// closed mesh has none). Each starts where its twin ends, becomes its
/// vertex's outgoing half-edge, and is linked to the boundary half-edge
/// leaving its end. A vertex may start at most one: unless `replace` (the
/// caller set every vertex's half-edge already and checks fans after), a
/// vertex that has one is [`BuildError::NonManifoldVertex`].
fn link_boundary(
    halfedges: &mut [HalfEdgeRecord],
    vertex_out: &mut [u32],
    replace: bool,
) -> Result<(), BuildError> {
    let mut boundary = Vec::new();
    for h in (1..halfedges.len()).step_by(2) {
        if halfedges[h].face == NONE {
            let origin = halfedges[halfedges[h ^ 1].next as usize].origin;
            halfedges[h].origin = origin;
            let o = &mut vertex_out[origin as usize];
            if *o != NONE && !replace {
                return Err(BuildError::NonManifoldVertex { vertex: origin });
            }
            *o = h as u32;
            boundary.push(h);
        }
    }
    for h in boundary {
        let target = halfedges[h ^ 1].origin as usize;
        let n = vertex_out[target];
        halfedges[h].next = n;
        halfedges[n as usize].prev = h as u32;
    }
    Ok(())
}

/// A subdivision level's faces: face `f` has the corners
/// `sides * f..sides * (f + 1)` when `sides` is not zero, else
/// `face_offsets[f]..face_offsets[f + 1]`; corner `c` is the vertex
/// `corner_vertex[c]` and starts the edge `corner_edge[c]` (below
/// `edge_count`) to the next corner of its face.
#[derive(Copy, Clone)]
pub(crate) struct LevelFaces<'a> {
    pub sides: u32,
    pub face_offsets: &'a [u32],
    pub corner_vertex: &'a [u32],
    pub corner_edge: &'a [u32],
    pub edge_count: usize,
}

/// The state of [`HalfEdgeMesh::from_level_faces`] as it adds faces.
struct LevelBuild<'a> {
    positions: &'a [DVec3],
    vertex_map: Vec<u32>,
    edge_map: Vec<u32>,
    kept_positions: Vec<DVec3>,
    vertex_out: Vec<u32>,
    halfedges: Vec<HalfEdgeRecord>,
    face_halfedge: Vec<u32>,
    corners: usize,
    /// Half-edges of a face of more than eight sides.
    long_face: Vec<u32>,
}

impl LevelBuild<'_> {
    /// Adds the shown faces of a level whose faces all have `N` corners
    /// (fixed size, so the per-face loops unroll).
    fn add_fixed_faces<const N: usize>(
        &mut self,
        corner_vertex: &[u32],
        corner_edge: &[u32],
        shown: &impl Fn(usize) -> bool,
    ) {
        let faces = corner_vertex.as_chunks::<N>().0.iter();
        for (f, (v, e)) in faces.zip(corner_edge.as_chunks::<N>().0).enumerate() {
            if shown(f) {
                self.add_face(v, e);
            }
        }
    }

    /// Adds the face with these corner vertices and edges (level numbers).
    #[inline(always)]
    fn add_face(&mut self, verts: &[u32], edges: &[u32]) {
        let n = edges.len();
        self.corners += n;
        let mut short = [0u32; 8];
        let hs: &mut [u32] = if n <= 8 {
            &mut short[..n]
        } else {
            self.long_face.resize(n, 0);
            &mut self.long_face
        };
        // Each corner's half-edge: the even one of a new edge (edges are
        // numbered on first use), else its twin.
        let mut next_new = self.halfedges.len() as u32;
        for (h, &e) in hs.iter_mut().zip(edges) {
            let m = &mut self.edge_map[e as usize];
            if *m == NONE {
                *m = next_new / 2;
                *h = next_new;
                next_new += 2;
            } else {
                *h = 2 * *m + 1;
            }
        }
        let face = self.face_halfedge.len() as u32;
        self.face_halfedge.push(hs[0]);
        let blank = HalfEdgeRecord {
            origin: NONE,
            next: NONE,
            prev: NONE,
            face: NONE,
        };
        for (k, &v) in verts.iter().enumerate() {
            let h = hs[k];
            let u = &mut self.vertex_map[v as usize];
            if *u == NONE {
                *u = self.kept_positions.len() as u32;
                self.kept_positions.push(self.positions[v as usize]);
                self.vertex_out.push(h);
            }
            let record = HalfEdgeRecord {
                origin: *u,
                next: hs[if k + 1 == n { 0 } else { k + 1 }],
                prev: hs[if k == 0 { n - 1 } else { k - 1 }],
                face,
            };
            // New half-edges come in corner order: each is appended where
            // its number says, with its blank twin after it.
            if h as usize == self.halfedges.len() {
                self.halfedges.push(record);
                self.halfedges.push(blank);
            } else {
                self.halfedges[h as usize] = record;
            }
        }
    }
}
