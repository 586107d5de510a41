//! The 4×4 control grid of one quad face of a refinement level, and which
//! faces are regular (their limit surface is the bicubic uniform B-spline
//! of that grid).
//!
//! A face is regular when each of its corners is (OpenSubdiv's regular
//! interior, boundary and corner patches, `Far::PatchBuilder`): a smooth
//! interior vertex of valence 4 whose faces are quads; a vertex on an
//! infinitely sharp crease (or a boundary) with two quads on each side of
//! it; or a corner (infinite corner sharpness, a boundary vertex of one
//! face). Across an infinitely sharp edge the grid takes phantom points
//! mirrored through the edge, `2 P₀ − P₁`, so that the patch's boundary is
//! the cubic B-spline of the crease polygon, which is the crease rule's limit
//! (seed 003 on the crease masks; OpenSubdiv's boundary patches do the same).

use glam::DVec3;

use super::super::level::{Level, NONE};
use super::super::rules::is_infinite;

/// How a vertex of a level sits, for the patch it gives its faces.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum VertexClass {
    /// Smooth interior vertex of valence 4 among quads.
    Smooth,
    /// On an infinitely sharp crease or boundary, two quads on each side.
    Crease,
    /// Infinitely sharp corner (corner sharpness, or three or more
    /// infinitely sharp edges); regular for a face that alone fills a
    /// sector between two sharp edges.
    Corner,
    /// Anything else; `smooth` when it is interior with no sharp edge or
    /// corner sharpness (its limit tangent plane comes from the tangent
    /// masks, and the patch edge points beside it are put into that plane).
    Irregular {
        /// Interior and smooth (no sharpness at all).
        smooth: bool,
    },
}

impl VertexClass {
    pub fn is_regular(self) -> bool {
        !matches!(self, VertexClass::Irregular { .. })
    }
}

/// Every vertex's class at `level`.
pub(crate) fn classify(level: &Level) -> Vec<VertexClass> {
    (0..level.vertex_count as u32)
        .map(|v| classify_vertex(level, v))
        .collect()
}

fn classify_vertex(level: &Level, v: u32) -> VertexClass {
    let edges = level.vertex_edges(v);
    let corners = level.vertex_corners(v);
    let quads = corners
        .iter()
        .all(|&c| level.face_corners(level.corner_face(c as usize)).len() == 4);
    let sharp: Vec<u32> = edges
        .iter()
        .copied()
        .filter(|&e| level.edge_sharp(e) > 0.0)
        .collect();
    let all_infinite = sharp.iter().all(|&e| is_infinite(level.edge_sharp(e)));
    let corner = level.vertex_sharp(v);
    let irregular = |smooth| VertexClass::Irregular { smooth };
    // A corner: infinite corner sharpness, or three or more infinitely
    // sharp edges (the corner rule keeps the vertex in place either way).
    // The face's patch is then regular when the face alone fills the sector
    // between two sharp edges (checked per face in `face_grid`).
    let is_corner = if corner > 0.0 {
        is_infinite(corner) && sharp.len() >= 2
    } else {
        sharp.len() >= 3
    };
    if corner > 0.0 || sharp.len() >= 3 {
        return if is_corner && all_infinite && quads {
            VertexClass::Corner
        } else {
            irregular(false)
        };
    }
    match sharp.len() {
        0 if edges.len() == 4 && corners.len() == 4 && quads => VertexClass::Smooth,
        0 => irregular(!edges.is_empty() && edges.len() == corners.len()),
        2 if all_infinite && quads => {
            let boundary = edges.len() == 3 && corners.len() == 2;
            // Interior: the two sharp edges must not be neighbours around v
            // (two faces on each side). In the increasing edge list order is
            // lost, so test through the faces: every face at v has exactly
            // one sharp edge at v.
            let interior = edges.len() == 4
                && corners.len() == 4
                && corners.iter().all(|&c| {
                    let c = c as usize;
                    let a = level.face_edges[c];
                    let b = level.face_edges[level.prev_corner(c)];
                    (level.edge_sharp(a) > 0.0) != (level.edge_sharp(b) > 0.0)
                });
            if boundary || interior {
                VertexClass::Crease
            } else {
                irregular(false)
            }
        }
        _ => irregular(false),
    }
}

/// Grid coordinates of a face's corners in its own frame: corner `i` of the
/// face (from its first corner, in face order) sits at `CORNER[i]`; `u`
/// runs from corner 0 to 1, `v` from corner 0 to 3.
pub(crate) const CORNER: [(i32, i32); 4] = [(0, 0), (1, 0), (1, 1), (0, 1)];
/// Outward direction of each face edge (edge `i` runs from corner `i` to
/// corner `i + 1`).
const OUT: [(i32, i32); 4] = [(0, -1), (1, 0), (0, 1), (-1, 0)];

/// The corner of the face across the edge that corner `c` starts, at the
/// edge's far end (so that its next corner is at `c`'s vertex), or `None`
/// on a boundary.
pub(crate) fn twin_corner(level: &Level, c: usize) -> Option<usize> {
    let e = level.face_edges[c];
    let f = level.corner_face(c);
    let [f0, f1] = level.edge_faces(e);
    let g = if f0 == f { f1 } else { f0 };
    if g == NONE || g == f {
        return None;
    }
    let a = level.face_vertices[c];
    let b = level.face_vertices[level.next_corner(c)];
    level
        .face_corners(g)
        .find(|&k| level.face_vertices[k] == b && level.face_vertices[level.next_corner(k)] == a)
}

/// The control grid of quad `face` of `level`, seen from its corner `rot`
/// (that corner at `(0, 0)`): `grid[i + 1][j + 1]` is the
/// point at grid coordinates `(i, j)` (`-1 ..= 2`), or `None` where it does
/// not exist (the diagonal point at an irregular corner). Infinitely sharp
/// edges give mirrored phantom points.
pub(crate) fn face_grid(
    level: &Level,
    classes: &[VertexClass],
    points: &[DVec3],
    face: u32,
    rot: usize,
) -> [[Option<DVec3>; 4]; 4] {
    let mut grid = [[None; 4]; 4];
    let native: Vec<usize> = level.face_corners(face).collect();
    debug_assert_eq!(native.len(), 4);
    let corners: [usize; 4] = std::array::from_fn(|i| native[(rot + i) % 4]);
    let at = |(i, j): (i32, i32)| ((i + 1) as usize, (j + 1) as usize);
    let q: [DVec3; 4] = std::array::from_fn(|k| points[level.face_vertices[corners[k]] as usize]);
    for k in 0..4 {
        let (i, j) = at(CORNER[k]);
        grid[i][j] = Some(q[k]);
    }
    let add = |a: (i32, i32), b: (i32, i32)| (a.0 + b.0, a.1 + b.1);
    let sharp: [bool; 4] =
        std::array::from_fn(|k| is_infinite(level.edge_sharp(level.face_edges[corners[k]])));
    // Edge neighbours: the two far points of the quad across each edge.
    let mut far = [[None::<DVec3>; 2]; 4];
    for k in 0..4 {
        let (a, b) = (CORNER[k], CORNER[(k + 1) % 4]);
        let pair = if sharp[k] {
            // Mirror through the edge: the inner points are across the face.
            let qa = q[k];
            let qb = q[(k + 1) % 4];
            let ia = q[(k + 3) % 4];
            let ib = q[(k + 2) % 4];
            Some([2.0 * qa - ia, 2.0 * qb - ib])
        } else {
            twin_corner(level, corners[k]).and_then(|t| {
                let g = level.corner_face(t);
                (level.face_corners(g).len() == 4).then(|| {
                    let x = level.next_corner(level.next_corner(t));
                    let y = level.next_corner(x);
                    [
                        points[level.face_vertices[x] as usize],
                        points[level.face_vertices[y] as usize],
                    ]
                })
            })
        };
        if let Some([x, y]) = pair {
            far[k] = [Some(x), Some(y)];
            let (i, j) = at(add(a, OUT[k]));
            grid[i][j] = Some(x);
            let (i, j) = at(add(b, OUT[k]));
            grid[i][j] = Some(y);
        }
    }
    // Diagonal points, one per corner.
    for k in 0..4 {
        let prev = (k + 3) % 4;
        let (i, j) = at(add(add(CORNER[k], OUT[k]), OUT[prev]));
        let v = level.face_vertices[corners[k]] as usize;
        grid[i][j] = match (classes[v], sharp[k], sharp[prev]) {
            (VertexClass::Corner, true, true) => {
                Some(4.0 * q[k] - 2.0 * q[(k + 1) % 4] - 2.0 * q[prev] + q[(k + 2) % 4])
            }
            // Edge k sharp: mirror the previous edge's neighbours through it.
            (VertexClass::Crease, true, false) => match far[prev] {
                [Some(x), Some(y)] => Some(2.0 * y - x),
                _ => None,
            },
            (VertexClass::Crease, false, true) => match far[k] {
                [Some(x), Some(y)] => Some(2.0 * x - y),
                _ => None,
            },
            (VertexClass::Smooth, false, false) => {
                // Around the vertex: the quad across edge k, then the one
                // across its edge from the vertex outwards.
                twin_corner(level, corners[k]).and_then(|t| {
                    let at_v = level.next_corner(t);
                    twin_corner(level, at_v).map(|h| {
                        let w = level.next_corner(level.next_corner(level.next_corner(h)));
                        points[level.face_vertices[w] as usize]
                    })
                })
            }
            _ => None,
        };
    }
    grid
}

/// The uniform cubic B-spline's span in Bézier form: `b_i = Σ_r M[i][r] d_r`
/// for the span's four de Boor points `d_{-1} … d_2` (seed 004 on the uniform
/// B-spline basis; The NURBS Book §5.6 on decomposition into Bézier pieces).
pub(crate) const TO_BEZIER: [[f64; 4]; 4] = [
    [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0],
    [0.0, 2.0 / 3.0, 1.0 / 3.0, 0.0],
    [0.0, 1.0 / 3.0, 2.0 / 3.0, 0.0],
    [0.0, 1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0],
];

/// Bézier point `(i, j)` of the face's B-spline patch from its grid, or
/// `None` when a point it needs is missing.
pub(crate) fn bezier_point(grid: &[[Option<DVec3>; 4]; 4], i: usize, j: usize) -> Option<DVec3> {
    let mut sum = DVec3::ZERO;
    for (r, &wr) in TO_BEZIER[i].iter().enumerate() {
        if wr == 0.0 {
            continue;
        }
        for (s, &ws) in TO_BEZIER[j].iter().enumerate() {
            if ws == 0.0 {
                continue;
            }
            sum += (wr * ws) * grid[r][s]?;
        }
    }
    Some(sum)
}

/// All sixteen points of `grid`, or `None` when one is missing.
pub(crate) fn full(grid: &[[Option<DVec3>; 4]; 4]) -> Option<[[DVec3; 4]; 4]> {
    let mut out = [[DVec3::ZERO; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            out[i][j] = grid[i][j]?;
        }
    }
    Some(out)
}
