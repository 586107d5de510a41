//! Merging the engine's triangles back into polygons: the triangles of one
//! source face that form a connected disc become one polygon (its boundary
//! loop), so a face the cut did not touch comes back whole and a cut face
//! comes back as one polygon per piece. Pieces that are not discs (an
//! annulus where a cylinder pierced the face) stay triangles.

use super::{FaceSource, Operand};
use crate::ids::FaceId;
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;

/// The merged result: compacted positions, polygons and their sources.
pub(super) struct Merged {
    pub positions: Vec<DVec3>,
    pub polygons: Vec<Vec<u32>>,
    pub sources: Vec<FaceSource>,
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
/// Complexity: O(n α(n)) for n triangles.
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
        if u < nt && sources[t] == sources[u] {
            let (a, b) = (find(&mut parent, t as u32), find(&mut parent, u as u32));
            if a != b {
                parent[a.max(b) as usize] = a.min(b);
            }
        }
    }
    // Pieces in order of their first triangle.
    let mut piece_of = vec![u32::MAX; nt];
    let mut pieces: Vec<Vec<u32>> = Vec::new();
    for t in 0..nt {
        let r = find(&mut parent, t as u32) as usize;
        if piece_of[r] == u32::MAX {
            piece_of[r] = pieces.len() as u32;
            pieces.push(Vec::new());
        }
        pieces[piece_of[r] as usize].push(t as u32);
    }
    let root = |t: usize, parent: &[u32]| {
        let mut i = t as u32;
        while parent[i as usize] != i {
            i = parent[i as usize];
        }
        i
    };
    let mut index = vec![u32::MAX; positions.len()];
    let mut out = Merged {
        positions: Vec::new(),
        polygons: Vec::new(),
        sources: Vec::new(),
    };
    let mut emit = |verts: &mut dyn Iterator<Item = usize>, out: &mut Merged| {
        let poly = verts
            .map(|v| {
                if index[v] == u32::MAX {
                    index[v] = out.positions.len() as u32;
                    out.positions.push(positions[v]);
                }
                index[v]
            })
            .collect();
        out.polygons.push(poly);
    };
    let mut boundary_next: std::collections::HashMap<usize, usize> = Default::default();
    let mut seen: std::collections::HashSet<usize> = Default::default();
    for piece in &pieces {
        let r = root(piece[0] as usize, &parent);
        let (operand, face) = source_of(sources[piece[0] as usize]);
        // Boundary half-edges: twin in another piece.
        boundary_next.clear();
        seen.clear();
        let mut simple = true;
        let mut boundary = 0usize;
        let mut start = usize::MAX;
        for &t in piece {
            for h in 3 * t as usize..3 * t as usize + 3 {
                seen.insert(tails[h]);
                let u = pairs[h] / 3;
                if u >= nt || root(u, &parent) != r {
                    boundary += 1;
                    start = h;
                    if boundary_next.insert(tails[h], tails[next(h)]).is_some() {
                        simple = false; // the boundary touches itself
                    }
                }
            }
        }
        // A disc: V − E + F = 1, one boundary loop through every boundary edge.
        let edges = (3 * piece.len() + boundary) / 2;
        let disc =
            simple && boundary >= 3 && seen.len() as i64 - edges as i64 + piece.len() as i64 == 1;
        let mut lp = Vec::new();
        if disc {
            let first = tails[start];
            let mut v = first;
            loop {
                lp.push(v);
                v = boundary_next[&v];
                if v == first || lp.len() > boundary {
                    break;
                }
            }
        }
        if disc && lp.len() == boundary {
            let m = operands[operand as usize];
            let whole = lp.len() == m.face_degree(face)
                && lp
                    .iter()
                    .all(|&v| m.face_vertices(face).any(|w| m.position(w) == positions[v]));
            emit(&mut lp.into_iter(), &mut out);
            out.sources.push(FaceSource {
                operand,
                face,
                whole,
            });
        } else {
            for &t in piece {
                let t = t as usize;
                emit(&mut (3 * t..3 * t + 3).map(|h| tails[h]), &mut out);
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
