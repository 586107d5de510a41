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

use super::{HalfEdgeMesh, HalfEdgeRecord};
use crate::build::{BuildError, check_face};
use crate::ids::{NONE, VertexId};
use glam::DVec3;

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
        // Corners: corner c of a face goes from corner_vertex[c] to
        // corner_to[c], the next corner's vertex.
        let mut face_offsets: Vec<u32> = Vec::with_capacity(polygons.len() + 1);
        face_offsets.push(0);
        let mut corner_vertex: Vec<u32> = Vec::new();
        let mut corner_to: Vec<u32> = Vec::new();
        for (fi, poly) in polygons.iter().enumerate() {
            let poly = poly.as_ref();
            check_face(fi, poly, nv)?;
            if corner_vertex.len() + poly.len() >= (NONE / 2) as usize {
                return Err(BuildError::TooLarge { what: "corners" });
            }
            corner_vertex.extend_from_slice(poly);
            corner_to.extend_from_slice(&poly[1..]);
            corner_to.push(poly[0]);
            face_offsets.push(corner_vertex.len() as u32);
        }
        let nc = corner_vertex.len();

        // Outgoing corners per vertex (compressed rows, each row in corner
        // order), with each corner's far end beside it.
        let mut row = vec![0u32; nv + 2];
        for &v in &corner_vertex {
            row[v as usize + 2] += 1;
        }
        for i in 2..row.len() {
            row[i] += row[i - 1];
        }
        let mut out_corner = vec![0u32; nc];
        let mut out_to = vec![0u32; nc];
        for (c, (&v, &to)) in corner_vertex.iter().zip(&corner_to).enumerate() {
            let slot = &mut row[v as usize + 1];
            out_corner[*slot as usize] = c as u32;
            out_to[*slot as usize] = to;
            *slot += 1;
        }
        row.pop();
        let range = |v: u32| row[v as usize] as usize..row[v as usize + 1] as usize;

        // Pair corners into edges, numbered in order of first use.
        let mut corner_edge = vec![NONE; nc];
        let mut edge_count = 0u32;
        for c in 0..nc {
            let (a, b) = (corner_vertex[c], corner_to[c]);
            let same_dir = out_to[range(a)].iter().filter(|&&x| x == b).count();
            let rb = range(b);
            let mut twins = out_to[rb.clone()]
                .iter()
                .enumerate()
                .filter(|(_, x)| **x == a);
            let first_twin = twins.next().map(|(i, _)| out_corner[rb.start + i] as usize);
            let twin_count = usize::from(first_twin.is_some()) + twins.count();
            if same_dir + twin_count > 2 || same_dir > 1 {
                let face_of = |c: u32| face_offsets.partition_point(|&s| s <= c) - 1;
                let faces_of = |from: u32, to: u32| -> Vec<usize> {
                    let r = range(from);
                    out_to[r.clone()]
                        .iter()
                        .zip(&out_corner[r])
                        .filter(|(x, _)| **x == to)
                        .map(|(_, &c)| face_of(c))
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
            if corner_edge[c] != NONE {
                continue;
            }
            corner_edge[c] = edge_count;
            if let Some(t) = first_twin {
                corner_edge[t] = edge_count;
            }
            edge_count += 1;
        }
        drop((corner_to, out_to, out_corner));
        let mesh = Self::assemble(
            positions.to_vec(),
            &face_offsets,
            &corner_vertex,
            &corner_edge,
            edge_count as usize,
        )?;
        mesh.check_fans(&corner_vertex)?;
        Ok(mesh)
    }

    /// Builds a mesh from polygons whose corners already name their edges
    /// (a subdivision level's tables, where every edge is known from the
    /// refinement), without searching for twins. Face `f` has the corners
    /// `face_offsets[f]..face_offsets[f + 1]`; corner `c` is the vertex
    /// `corner_vertex[c]` and starts the edge `corner_edge[c]` (an id below
    /// `edge_count`) to the next corner of its face.
    ///
    /// The result is the mesh [`from_polygons`](Self::from_polygons) makes
    /// of the same polygons, ids and all (vertex `i` is id `i`, edges in
    /// order of first use, each edge's first corner giving its even
    /// half-edge), provided that distinct edge ids never join the same two
    /// vertices, which the caller guarantees. Everything else is checked as
    /// `from_polygons` checks it, except that closed fans touching at a
    /// vertex are found only when `check_fans` is set (a refinement of a
    /// valid mesh cannot make them).
    ///
    /// # Errors
    /// A malformed face, a non-finite position, an edge id out of range,
    /// used by more than two corners ([`BuildError::NonManifoldEdge`]) or
    /// twice in one direction ([`BuildError::InconsistentOrientation`]), a
    /// vertex with two boundary fans ([`BuildError::NonManifoldVertex`]).
    ///
    /// Complexity: O(corners), a few linear passes and no hashing.
    pub(crate) fn from_corner_edges(
        positions: Vec<DVec3>,
        face_offsets: &[u32],
        corner_vertex: &[u32],
        corner_edge: &[u32],
        edge_count: usize,
        check_fans: bool,
    ) -> Result<HalfEdgeMesh, BuildError> {
        let nv = positions.len();
        if nv >= NONE as usize {
            return Err(BuildError::TooLarge { what: "vertices" });
        }
        if corner_vertex.len() >= (NONE / 2) as usize || corner_edge.len() != corner_vertex.len() {
            return Err(BuildError::TooLarge { what: "corners" });
        }
        if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
            return Err(BuildError::NonFinitePosition { vertex: i as u32 });
        }
        for (f, w) in face_offsets.windows(2).enumerate() {
            let poly = corner_vertex
                .get(w[0] as usize..w[1] as usize)
                .unwrap_or_default();
            check_face(f, poly, nv)?;
        }
        if face_offsets.first().is_some_and(|&s| s != 0)
            || face_offsets.last().map_or(0, |&s| s as usize) != corner_vertex.len()
        {
            return Err(BuildError::TooLarge { what: "corners" });
        }
        let mesh = Self::assemble(
            positions,
            face_offsets,
            corner_vertex,
            corner_edge,
            edge_count,
        )?;
        if check_fans {
            mesh.check_fans(corner_vertex)?;
        }
        Ok(mesh)
    }

    /// The records from checked faces and finite positions, with each
    /// corner's edge id given (see [`from_corner_edges`](Self::from_corner_edges)).
    fn assemble(
        positions: Vec<DVec3>,
        face_offsets: &[u32],
        corner_vertex: &[u32],
        corner_edge: &[u32],
        edge_count: usize,
    ) -> Result<HalfEdgeMesh, BuildError> {
        let nv = positions.len();
        let nc = corner_vertex.len();
        let nf = face_offsets.len().saturating_sub(1);
        let mut edge_he = vec![NONE; edge_count];
        let mut corner_he = vec![NONE; nc];
        let mut paired = 0usize;
        let mut halfedges: Vec<HalfEdgeRecord> = Vec::with_capacity(2 * edge_count);
        for f in 0..nf {
            let r = face_offsets[f] as usize..face_offsets[f + 1] as usize;
            let poly = &corner_vertex[r.clone()];
            let n = r.len();
            for (k, c) in r.clone().enumerate() {
                let a = poly[k];
                let b = poly[if k + 1 == n { 0 } else { k + 1 }];
                let e = corner_edge[c] as usize;
                let Some(slot) = edge_he.get_mut(e) else {
                    return Err(BuildError::TooLarge { what: "edges" });
                };
                if *slot == NONE {
                    let h = halfedges.len() as u32;
                    *slot = h;
                    corner_he[c] = h;
                    halfedges.push(HalfEdgeRecord {
                        origin: a,
                        next: NONE,
                        prev: NONE,
                        face: f as u32,
                    });
                    halfedges.push(HalfEdgeRecord {
                        origin: b,
                        next: NONE,
                        prev: NONE,
                        face: NONE,
                    });
                } else {
                    let h = *slot as usize;
                    let (first, twin) = (halfedges[h], halfedges[h + 1]);
                    if twin.face != NONE || twin.origin != a || first.origin != b {
                        let faces = vec![first.face as usize, f];
                        return Err(if twin.face != NONE {
                            BuildError::NonManifoldEdge {
                                a: a.min(b),
                                b: a.max(b),
                                faces: vec![first.face as usize, twin.face as usize, f],
                            }
                        } else {
                            BuildError::InconsistentOrientation { a, b, faces }
                        });
                    }
                    halfedges[h + 1].face = f as u32;
                    corner_he[c] = h as u32 + 1;
                    paired += 1;
                }
            }
            for k in 0..n {
                let h = corner_he[r.start + k] as usize;
                halfedges[h].next = corner_he[r.start + if k + 1 == n { 0 } else { k + 1 }];
                halfedges[h].prev = corner_he[r.start + if k == 0 { n - 1 } else { k - 1 }];
            }
        }
        if halfedges.len() >= NONE as usize {
            return Err(BuildError::TooLarge { what: "half-edges" });
        }
        // Boundary half-edges: each vertex may start at most one. A closed
        // mesh (every edge paired) has none to look for.
        let mut vertex_out = vec![NONE; nv];
        if 2 * paired != halfedges.len() {
            for (h, record) in halfedges.iter().enumerate() {
                if record.face == NONE {
                    let o = &mut vertex_out[record.origin as usize];
                    if *o != NONE {
                        return Err(BuildError::NonManifoldVertex {
                            vertex: record.origin,
                        });
                    }
                    *o = h as u32;
                }
            }
            for h in 0..halfedges.len() {
                if halfedges[h].face == NONE {
                    let target = halfedges[h ^ 1].origin as usize;
                    let n = vertex_out[target];
                    halfedges[h].next = n;
                    halfedges[n as usize].prev = h as u32;
                }
            }
        }
        // Other vertices: the half-edge of their first corner.
        for (&v, &h) in corner_vertex.iter().zip(&corner_he) {
            let o = &mut vertex_out[v as usize];
            if *o == NONE {
                *o = h;
            }
        }
        let ne = halfedges.len() / 2;
        Ok(HalfEdgeMesh {
            positions,
            vertex_out,
            face_halfedge: face_offsets[..nf]
                .iter()
                .map(|&c| corner_he[c as usize])
                .collect(),
            halfedges,
            vertex_dead: vec![false; nv],
            edge_dead: vec![false; ne],
            face_dead: vec![false; nf],
            live_vertices: nv,
            live_edges: ne,
            live_faces: nf,
            ..Default::default()
        })
    }

    /// Closed fans touching at a vertex (two cones tip to tip) pass the
    /// boundary test of [`assemble`](Self::assemble); walking each vertex's
    /// fan finds them: it must meet every corner at the vertex (and its
    /// boundary half-edge).
    fn check_fans(&self, corner_vertex: &[u32]) -> Result<(), BuildError> {
        let mut degree = vec![0u32; self.positions.len()];
        for &v in corner_vertex {
            degree[v as usize] += 1;
        }
        for (v, &corners) in degree.iter().enumerate() {
            let v = VertexId(v as u32);
            let deg = corners as usize + usize::from(self.is_boundary_vertex(v));
            if deg > 0 && self.vertex_outgoing(v).take(deg + 1).count() != deg {
                return Err(BuildError::NonManifoldVertex { vertex: v.0 });
            }
        }
        Ok(())
    }
}
