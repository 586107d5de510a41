//! Building a mesh's records in bulk from an indexed face set: the strict
//! [`from_polygons`](HalfEdgeMesh::from_polygons). It writes the arrays
//! directly (one pass per corner), which is why it lives inside the
//! [`mesh`](super) module; the repairing build and compaction in
//! [`crate::build`] go through it.
//!
//! Twins are found with a compressed per-vertex list of outgoing corners
//! instead of a hash map, so building is linear in the number of corners.

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
        // Corners: corner c of face f goes from corner_from[c] to the next corner's vertex.
        let mut face_start = Vec::with_capacity(polygons.len() + 1);
        let mut corner_from: Vec<u32> = Vec::new();
        let mut corner_face: Vec<u32> = Vec::new();
        face_start.push(0usize);
        for (fi, poly) in polygons.iter().enumerate() {
            let poly = poly.as_ref();
            check_face(fi, poly, nv)?;
            corner_from.extend_from_slice(poly);
            corner_face.extend(std::iter::repeat_n(fi as u32, poly.len()));
            face_start.push(corner_from.len());
        }
        let nc = corner_from.len();
        if nc >= (NONE / 2) as usize {
            return Err(BuildError::TooLarge { what: "corners" });
        }
        let next_corner = |c: usize| -> usize {
            let f = corner_face[c] as usize;
            if c + 1 == face_start[f + 1] {
                face_start[f]
            } else {
                c + 1
            }
        };
        let prev_corner = |c: usize| -> usize {
            let f = corner_face[c] as usize;
            if c == face_start[f] {
                face_start[f + 1] - 1
            } else {
                c - 1
            }
        };
        let corner_to = |c: usize| corner_from[next_corner(c)];

        // Outgoing corners per vertex (compressed rows).
        let mut row = vec![0u32; nv + 1];
        for &v in &corner_from {
            row[v as usize + 1] += 1;
        }
        for i in 0..nv {
            row[i + 1] += row[i];
        }
        let mut fill = row.clone();
        let mut out_corner = vec![0u32; nc];
        for (c, &v) in corner_from.iter().enumerate() {
            out_corner[fill[v as usize] as usize] = c as u32;
            fill[v as usize] += 1;
        }
        let outgoing = |v: u32| &out_corner[row[v as usize] as usize..row[v as usize + 1] as usize];

        // Pair corners into edges.
        let mut corner_he = vec![NONE; nc];
        let mut halfedges: Vec<HalfEdgeRecord> = Vec::with_capacity(nc + nc / 8);
        let blank = HalfEdgeRecord {
            origin: NONE,
            next: NONE,
            prev: NONE,
            face: NONE,
        };
        for c in 0..nc {
            let (a, b) = (corner_from[c], corner_to(c));
            // Count without allocating: this loop runs once per corner.
            let same_dir = outgoing(a)
                .iter()
                .filter(|&&x| corner_to(x as usize) == b)
                .count();
            let mut twins = outgoing(b)
                .iter()
                .map(|&x| x as usize)
                .filter(|&x| corner_to(x) == a);
            let first_twin = twins.next();
            let twin_count = usize::from(first_twin.is_some()) + twins.count();
            if same_dir + twin_count > 2 || same_dir > 1 {
                let faces_of = |from: u32, to: u32| -> Vec<usize> {
                    outgoing(from)
                        .iter()
                        .map(|&x| x as usize)
                        .filter(|&x| corner_to(x) == to)
                        .map(|x| corner_face[x] as usize)
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
            if corner_he[c] != NONE {
                continue;
            }
            let h = halfedges.len() as u32;
            corner_he[c] = h;
            halfedges.push(blank);
            halfedges.push(blank);
            halfedges[h as usize] = HalfEdgeRecord {
                origin: a,
                next: NONE,
                prev: NONE,
                face: corner_face[c],
            };
            if let Some(t) = first_twin {
                corner_he[t] = h + 1;
                halfedges[h as usize + 1] = HalfEdgeRecord {
                    origin: b,
                    next: NONE,
                    prev: NONE,
                    face: corner_face[t],
                };
            } else {
                halfedges[h as usize + 1].origin = b;
            }
        }
        if halfedges.len() >= NONE as usize {
            return Err(BuildError::TooLarge { what: "half-edges" });
        }
        for c in 0..nc {
            let h = corner_he[c] as usize;
            halfedges[h].next = corner_he[next_corner(c)];
            halfedges[h].prev = corner_he[prev_corner(c)];
        }
        // Boundary half-edges: each vertex may start at most one.
        let mut boundary_out = vec![NONE; nv];
        for (h, record) in halfedges.iter().enumerate() {
            if record.face == NONE {
                let o = record.origin as usize;
                if boundary_out[o] != NONE {
                    return Err(BuildError::NonManifoldVertex { vertex: o as u32 });
                }
                boundary_out[o] = h as u32;
            }
        }
        for h in 0..halfedges.len() {
            if halfedges[h].face == NONE {
                let target = halfedges[h ^ 1].origin as usize;
                let n = boundary_out[target];
                halfedges[h].next = n;
                halfedges[n as usize].prev = h as u32;
            }
        }
        let mut vertex_out = boundary_out;
        for (v, out) in vertex_out.iter_mut().enumerate() {
            if *out == NONE
                && let Some(&c) = outgoing(v as u32).first()
            {
                *out = corner_he[c as usize];
            }
        }
        let ne = halfedges.len() / 2;
        let mesh = HalfEdgeMesh {
            positions: positions.to_vec(),
            vertex_out,
            halfedges,
            face_halfedge: (0..polygons.len())
                .map(|f| corner_he[face_start[f]])
                .collect(),
            vertex_dead: vec![false; nv],
            edge_dead: vec![false; ne],
            face_dead: vec![false; polygons.len()],
            live_vertices: nv,
            live_edges: ne,
            live_faces: polygons.len(),
            ..Default::default()
        };
        // Closed fans touching at a vertex (two cones tip to tip) pass the
        // boundary test above; the fan walk finds them.
        for v in 0..nv as u32 {
            let deg = (row[v as usize + 1] - row[v as usize]) as usize
                + usize::from(mesh.is_boundary_vertex(VertexId(v)));
            if deg > 0 && mesh.vertex_outgoing(VertexId(v)).take(deg + 1).count() != deg {
                return Err(BuildError::NonManifoldVertex { vertex: v });
            }
        }
        Ok(mesh)
    }
}
