//! Merging the engine's triangles back into polygons: the triangles of one
//! source face that form a connected disc become one polygon (its boundary
//! loop), so a face the cut did not touch comes back whole and a cut face
//! comes back as one polygon per piece. Pieces that are not discs (an
//! annulus where a cylinder pierced the face) stay triangles.

use super::{FaceSource, Operand};
use crate::ids::FaceId;
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;

/// The merged result: compacted positions, polygons (flat) and their sources.
pub struct Merged {
    pub(super) positions: Vec<DVec3>,
    /// Polygon `i` is `corners[starts[i]..starts[i + 1]]`.
    corners: Vec<u32>,
    starts: Vec<usize>,
    pub(super) sources: Vec<FaceSource>,
}

impl Merged {
    /// The polygons, as vertex number lists.
    pub(super) fn polygons(&self) -> impl Iterator<Item = &[u32]> {
        self.starts.windows(2).map(|w| &self.corners[w[0]..w[1]])
    }

    /// Appends a polygon of engine vertices, numbering them compactly in
    /// order of first use (`index`: engine vertex to output vertex).
    fn emit(&mut self, verts: impl Iterator<Item = usize>, index: &mut [u32], positions: &[DVec3]) {
        for v in verts {
            if index[v] == u32::MAX {
                index[v] = self.positions.len() as u32;
                self.positions.push(positions[v]);
            }
            self.corners.push(index[v]);
        }
        self.starts.push(self.corners.len());
    }
}

fn find(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        let p = parent[parent[i as usize] as usize];
        parent[i as usize] = p;
        i = p;
    }
    i
}

/// Merges triangles (half-edge `3t + k` goes from `tails[3t + k]` to
/// `tails[3t + (k + 1) % 3]`, its twin is `pairs[3t + k]`) by their source
/// numbers `sources[t]`.
///
/// Complexity: O(n α(n)) for n triangles (no hashing: per-vertex marks
/// stamped with the piece number).
pub(super) fn merge(
    positions: &[DVec3],
    tails: &[usize],
    pairs: &[usize],
    sources: &[u64],
    operands: [&HalfEdgeMesh; 2],
    source_of: &dyn Fn(u64) -> (Operand, FaceId),
) -> Merged {
    let nt = sources.len();
    let next = |h: usize| if h % 3 == 2 { h - 2 } else { h + 1 };
    // Union-find: triangles of one source sharing an edge are one piece.
    let mut parent: Vec<u32> = (0..nt as u32).collect();
    for (h, &pair) in pairs.iter().enumerate().take(3 * nt) {
        let (t, u) = (h / 3, pair / 3);
        if u < nt && t < u && sources[t] == sources[u] {
            let (a, b) = (find(&mut parent, t as u32), find(&mut parent, u as u32));
            if a != b {
                parent[a.max(b) as usize] = a.min(b);
            }
        }
    }
    // Pieces numbered in order of their first triangle; their triangles
    // listed together (a counting sort by piece).
    let mut piece = vec![u32::MAX; nt];
    let mut count: Vec<u32> = Vec::new();
    for t in 0..nt {
        let r = find(&mut parent, t as u32) as usize;
        if piece[r] == u32::MAX {
            piece[r] = count.len() as u32;
            count.push(0);
        }
        piece[t] = piece[r];
        count[piece[t] as usize] += 1;
    }
    let mut first = Vec::with_capacity(count.len() + 1);
    first.push(0usize);
    for &c in &count {
        first.push(first.last().unwrap() + c as usize);
    }
    let mut fill = first.clone();
    let mut members = vec![0u32; nt];
    for (t, &p) in piece.iter().enumerate() {
        members[fill[p as usize]] = t as u32;
        fill[p as usize] += 1;
    }

    let mut index = vec![u32::MAX; positions.len()];
    let mut out = Merged {
        positions: Vec::with_capacity(positions.len()),
        corners: Vec::with_capacity(3 * nt),
        starts: vec![0],
        sources: Vec::with_capacity(count.len()),
    };
    // Per engine vertex: the last piece that used it, the last piece whose
    // boundary leaves it, and where that boundary goes.
    let mut seen = vec![u32::MAX; positions.len()];
    let mut leaves = vec![u32::MAX; positions.len()];
    let mut boundary_next = vec![0usize; positions.len()];
    let mut lp = Vec::new();
    for (p, w) in first.windows(2).enumerate() {
        let tris = &members[w[0]..w[1]];
        let p32 = p as u32;
        let (operand, face) = source_of(sources[tris[0] as usize]);
        // Boundary half-edges: twin in another piece.
        let mut simple = true;
        let mut vertices = 0usize;
        let mut boundary = 0usize;
        let mut start = usize::MAX;
        for &t in tris {
            for h in 3 * t as usize..3 * t as usize + 3 {
                let v = tails[h];
                if seen[v] != p32 {
                    seen[v] = p32;
                    vertices += 1;
                }
                let u = pairs[h] / 3;
                if u >= nt || piece[u] != p32 {
                    boundary += 1;
                    start = h;
                    if leaves[v] == p32 {
                        simple = false; // the boundary touches itself
                    }
                    leaves[v] = p32;
                    boundary_next[v] = tails[next(h)];
                }
            }
        }
        // A disc: V − E + F = 1, one boundary loop through every boundary edge.
        let edges = (3 * tris.len() + boundary) / 2;
        let disc =
            simple && boundary >= 3 && vertices as i64 - edges as i64 + tris.len() as i64 == 1;
        lp.clear();
        let mut closed = false;
        if disc {
            let first = tails[start];
            let mut v = first;
            while lp.len() < boundary && leaves[v] == p32 {
                lp.push(v);
                v = boundary_next[v];
                if v == first {
                    closed = true;
                    break;
                }
            }
        }
        if closed && lp.len() == boundary {
            let m = operands[operand as usize];
            let whole = lp.len() == m.face_degree(face)
                && lp
                    .iter()
                    .all(|&v| m.face_vertices(face).any(|w| m.position(w) == positions[v]));
            out.emit(lp.iter().copied(), &mut index, positions);
            out.sources.push(FaceSource {
                operand,
                face,
                whole,
            });
        } else {
            for &t in tris {
                let t = t as usize;
                out.emit((3 * t..3 * t + 3).map(|h| tails[h]), &mut index, positions);
                out.sources.push(FaceSource {
                    operand,
                    face,
                    whole: false,
                });
            }
        }
    }
    out
}
