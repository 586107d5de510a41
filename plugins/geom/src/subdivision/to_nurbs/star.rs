//! Tangent continuity around a smooth extraordinary vertex.
//!
//! The bicubic patches of the `n` faces around a smooth extraordinary
//! vertex `p` share its limit point; they join with tangent-plane (G1)
//! continuity along an edge curve `c(t)` from `p` when the cross-boundary
//! derivatives `d_L`, `d_R` of the two patches satisfy
//! `d_L(t) + d_R(t) = λ(t) c'(t)` with `λ(t) = λ₀ (1 − t)`,
//! `λ₀ = 2 cos(2π/n)` (the standard vertex-enclosure construction:
//! Peters, "Patching Catmull-Clark Meshes", SIGGRAPH 2000, §3; Loop and
//! Schaefer, "Approximating Catmull-Clark Subdivision Surfaces with Bicubic
//! Patches", ACM TOG 2008, §4 gives the same form). In Bernstein
//! coefficients of the cubic, with the curve's points `C₀ … C₃` and the two
//! patches' rows next to the edge `A₀ … A₃`, `B₀ … B₃`:
//!
//! - `k = 0`: `A₀ + B₀ − 2C₀ = λ₀ (C₁ − C₀)`. It holds when the edge
//!   points beside `p` lie on the limit tangents along their edges with one
//!   common length: `C₁ − p = s (cos θᵢ t₁ + sin θᵢ t₂)`, `θᵢ = 2πi/n`
//!   (Halstead et al.'s tangent masks `t₁`, `t₂`). `s` is fitted to the
//!   edge points the grid gives.
//! - `k = 1`: `A₁ + B₁ = 2C₁ + ⅔ λ₀ (C₂ − C₁)`, where `A₁`, `B₁` are the
//!   two patches' inner points at `p` ("twists"). Around the vertex these
//!   are `n` equations `P_{i−1} + P_i = R_i` for the `n` twists: solved
//!   exactly for odd `n`; for even `n` the system is singular (the
//!   alternating sum of the `R_i` must vanish) and its least-squares,
//!   least-change solution is taken.
//! - `k = 2, 3` involve points that also join the regular neighbours with
//!   C1 continuity, so they stay as the B-spline gives them.
//!
//! The normals then agree to first order at `p` (the angle across an edge
//! grows as `t²`, not `t`), but the `k = 2` remainder leaves a mismatch in
//! the middle of the edge. Measured on a cube's corners and UV-sphere poles
//! (largest normal angle in degrees, plain construction → this one, at
//! levels 3 / 5; the largest distance from the limit surface is within
//! 20 % either way):
//!
//! | valence | level 3 | level 5 |
//! |---|---|---|
//! | 3 (cube) | 0.24 → 0.83 | 0.037 → 0.17 |
//! | 5 | 0.37 → 0.63 | 0.13 → 0.12 |
//! | 6 | 1.04 → 0.65 | 0.44 → 0.13 |
//! | 8 | 3.09 → 0.73 | 1.65 → 0.25 |
//! | 12 | 9.23 → 1.32 | 6.17 → 0.92 |
//!
//! So it is used from valence [`MIN_VALENCE`] on, where the plain
//! construction's first-order mismatch dominates and falls slowly with the
//! level.

use std::collections::HashMap;
use std::f64::consts::TAU;

use glam::DVec3;

use super::super::level::Level;
use super::super::limit::vertex_tangents;
use super::SharedEdge;
use super::grid::{CORNER, VertexClass, bezier_point, face_grid};

/// The smallest valence the construction is used at (see the table above).
pub(super) const MIN_VALENCE: usize = 6;

/// A face's 4×4 control grid ([`super::grid::face_grid`], seen from corner 0).
type Grid = [[Option<DVec3>; 4]; 4];

/// Patch control points replaced, per face of the level: Bézier net index
/// `(i, j)` in the face's own frame, and the point.
pub(super) type Twists = HashMap<u32, Vec<((usize, usize), DVec3)>>;

/// Makes the edge points beside every smooth extraordinary vertex satisfy
/// the `k = 0` condition (in `edges`, in place) and returns the twists that
/// satisfy `k = 1`.
pub(super) fn smooth_stars(
    lv: &Level,
    classes: &[VertexClass],
    points: &[DVec3],
    grids: &[Option<Grid>],
    limit: &[DVec3],
    edges: &mut [SharedEdge],
    edge_index: &HashMap<u32, usize>,
) -> Twists {
    let mut twists = Twists::new();
    for v in 0..lv.vertex_count as u32 {
        if classes[v as usize] != (VertexClass::Irregular { smooth: true }) {
            continue;
        }
        let Some((corners, t1, t2)) = vertex_tangents(lv, points, v) else {
            continue;
        };
        let n = corners.len();
        if n < MIN_VALENCE {
            continue;
        }
        let Some(slots): Option<Vec<usize>> = corners
            .iter()
            .map(|&c| edge_index.get(&lv.face_edges[c]).copied())
            .collect()
        else {
            continue; // an edge with no shown face: a hole at the vertex
        };
        let p = limit[v as usize];
        let tangent: Vec<DVec3> = (0..n)
            .map(|i| {
                let angle = TAU * i as f64 / n as f64;
                angle.cos() * t1 + angle.sin() * t2
            })
            .collect();
        // The curve of edge i read from p outwards.
        let from_p = |e: &SharedEdge| {
            if e.ends[0] == v {
                e.curve
            } else {
                let mut c = e.curve;
                c.reverse();
                c
            }
        };
        let (num, den) = (0..n).fold((0.0, 0.0), |(num, den), i| {
            let c = from_p(&edges[slots[i]]);
            (
                num + (c[1] - p).dot(tangent[i]),
                den + tangent[i].length_squared(),
            )
        });
        let s = num / den;
        if !(s.is_finite() && s > 0.0) {
            continue;
        }
        let lambda = 2.0 * (TAU / n as f64).cos();
        let mut rhs = Vec::with_capacity(n);
        for i in 0..n {
            let e = &mut edges[slots[i]];
            let point = p + s * tangent[i];
            if e.ends[0] == v {
                e.curve[1] = point;
            } else {
                e.curve[2] = point;
            }
            let c = from_p(e);
            rhs.push(2.0 * c[1] + (2.0 / 3.0) * lambda * (c[2] - c[1]));
        }
        // Face i's twist at p, as the B-spline gives it.
        let at: Vec<(u32, (usize, usize))> = corners
            .iter()
            .map(|&c| {
                let f = lv.corner_face(c);
                let k = c - lv.face_corners(f).start;
                (f, (1 + CORNER[k].0 as usize, 1 + CORNER[k].1 as usize))
            })
            .collect();
        let old: Vec<DVec3> = at
            .iter()
            .map(|&(f, (i, j))| {
                // Shown faces' grids are made already; a hidden one's here.
                let grid =
                    grids[f as usize].unwrap_or_else(|| face_grid(lv, classes, points, f, 0));
                bezier_point(&grid, i, j).expect("inner points need only the face")
            })
            .collect();
        // Edge i lies between faces i - 1 and i.
        let change: Vec<DVec3> = (0..n)
            .map(|i| rhs[i] - old[(i + n - 1) % n] - old[i])
            .collect();
        for (i, delta) in solve_ring(&change).into_iter().enumerate() {
            twists
                .entry(at[i].0)
                .or_default()
                .push((at[i].1, old[i] + delta));
        }
    }
    twists
}

/// The least-squares solution of smallest norm of `x_{i−1} + x_i = b_i`
/// (indices mod `n`): exact for odd `n`; for even `n` the part of `b` along
/// the alternating vector `(−1)^i`, which no `x` reaches, is dropped first.
fn solve_ring(b: &[DVec3]) -> Vec<DVec3> {
    let n = b.len();
    let sign = |i: usize| if i.is_multiple_of(2) { 1.0 } else { -1.0 };
    let mut b = b.to_vec();
    if n.is_multiple_of(2) {
        let alternating = (0..n).map(|i| sign(i) * b[i]).sum::<DVec3>() / n as f64;
        for (i, bi) in b.iter_mut().enumerate() {
            *bi -= sign(i) * alternating;
        }
    }
    // x_i = a_i + (−1)^i x₀ with a₀ = 0 and a_i = b_i − a_{i−1}.
    let mut a = vec![DVec3::ZERO; n];
    for i in 1..n {
        a[i] = b[i] - a[i - 1];
    }
    let x0 = if !n.is_multiple_of(2) {
        // Closing equation x_{n−1} + x₀ = b₀ with x_{n−1} = a_{n−1} + x₀.
        (b[0] - a[n - 1]) / 2.0
    } else {
        // Every x₀ solves it; the smallest x has Σ (−1)^i x_i = 0.
        -(0..n).map(|i| sign(i) * a[i]).sum::<DVec3>() / n as f64
    };
    (0..n).map(|i| a[i] + sign(i) * x0).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn residual(x: &[DVec3], b: &[DVec3]) -> f64 {
        let n = x.len();
        (0..n)
            .map(|i| (x[(i + n - 1) % n] + x[i] - b[i]).length())
            .fold(0.0, f64::max)
    }

    #[test]
    fn an_odd_ring_is_solved_exactly() {
        let b: Vec<DVec3> = (0..5)
            .map(|i| DVec3::new(i as f64, (i * i) as f64, 1.0 - i as f64))
            .collect();
        assert!(residual(&solve_ring(&b), &b) < 1e-12);
    }

    #[test]
    fn an_even_ring_keeps_what_it_can_reach_and_is_smallest() {
        // A reachable right-hand side is met exactly ...
        let x: Vec<DVec3> = (0..6).map(|i| DVec3::splat(i as f64)).collect();
        let b: Vec<DVec3> = (0..6).map(|i| x[(i + 5) % 6] + x[i]).collect();
        let got = solve_ring(&b);
        assert!(residual(&got, &b) < 1e-12);
        // ... by the solution without an alternating part.
        let alternating: DVec3 = (0..6usize)
            .map(|i| if i.is_multiple_of(2) { got[i] } else { -got[i] })
            .sum();
        assert!(alternating.length() < 1e-12);
        // An alternating right-hand side is out of reach: nothing changes.
        let b: Vec<DVec3> = (0..6usize)
            .map(|i| DVec3::X * if i.is_multiple_of(2) { 1.0 } else { -1.0 })
            .collect();
        assert!(solve_ring(&b).iter().all(|x| x.length() < 1e-12));
    }
}
