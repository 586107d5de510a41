//! Packing regular faces into rectangles (Rhino's "packed faces"): a
//! rectangle of `w × h` regular quads with consistent orientation is one
//! uniform bicubic B-spline surface on the `(w + 3) × (h + 3)` grid the
//! faces' 4×4 grids overlap into, then clamped by knot insertion.

use std::collections::HashSet;

use glam::DVec3;

use super::super::level::Level;
use super::grid::twin_corner;
use crate::surfaces::NurbsSurface;

/// A face of a level seen from one of its corners: local corner `i` is the
/// face's corner `(rot + i) % 4`.
pub(crate) type Placed = (u32, usize);

fn corner(level: &Level, (f, rot): Placed, i: usize) -> usize {
    level.face_corners(f).start + (rot + i) % 4
}

fn placed_at(level: &Level, c: usize, local: usize) -> Placed {
    let f = level.corner_face(c);
    let k = c - level.face_corners(f).start;
    (f, (k + 4 - local) % 4)
}

/// The quad across local edge 1 (the `u = 1` side), in the same orientation.
/// Only across smooth edges: a sharp edge is a patch boundary, and the
/// grids on its two sides hold different phantom points.
fn right(level: &Level, p: Placed) -> Option<Placed> {
    let c = corner(level, p, 1);
    if level.edge_sharp(level.face_edges[c]) > 0.0 {
        return None;
    }
    let t = twin_corner(level, c)?;
    // t is at p's local corner 2; the corner after it is p's local corner 1,
    // which is the neighbour's local corner 0.
    Some(placed_at(level, level.next_corner(t), 0))
}

/// The quad across local edge 2 (the `v = 1` side), in the same orientation.
fn up(level: &Level, p: Placed) -> Option<Placed> {
    let c = corner(level, p, 2);
    if level.edge_sharp(level.face_edges[c]) > 0.0 {
        return None;
    }
    let t = twin_corner(level, c)?;
    // t is at p's local corner 3: the neighbour's local corner 0.
    Some(placed_at(level, t, 0))
}

/// The quad across local edge 3 (the `u = 0` side), in the same orientation.
fn left(level: &Level, p: Placed) -> Option<Placed> {
    let c = corner(level, p, 3);
    if level.edge_sharp(level.face_edges[c]) > 0.0 {
        return None;
    }
    // The twin corner is at p's local corner 0: the neighbour's local 1.
    Some(placed_at(level, twin_corner(level, c)?, 1))
}

/// The quad across local edge 0 (the `v = 0` side), in the same orientation.
fn down(level: &Level, p: Placed) -> Option<Placed> {
    let c = corner(level, p, 0);
    if level.edge_sharp(level.face_edges[c]) > 0.0 {
        return None;
    }
    // The twin corner is at p's local corner 1: the neighbour's local 2.
    Some(placed_at(level, twin_corner(level, c)?, 2))
}

/// The rectangle grown from `start`: a row to the right as long as it goes,
/// then rows upwards while the whole row fits. `free(g)` says whether face
/// `g` may join.
fn grow(level: &Level, start: Placed, free: &dyn Fn(u32) -> bool) -> Vec<Vec<Placed>> {
    let mut taken: HashSet<u32> = HashSet::from([start.0]);
    let mut row = vec![start];
    while let Some(next) = right(level, *row.last().expect("non-empty"))
        && free(next.0)
        && !taken.contains(&next.0)
    {
        taken.insert(next.0);
        row.push(next);
    }
    let mut rows = vec![row];
    'grow: loop {
        let below = rows.last().expect("non-empty");
        let mut new: Vec<Placed> = Vec::with_capacity(below.len());
        for (a, &p) in below.iter().enumerate() {
            let Some(q) = up(level, p) else {
                break 'grow;
            };
            if !free(q.0) || taken.contains(&q.0) || new.iter().any(|&(g, _)| g == q.0) {
                break 'grow;
            }
            // The row must be a row: each face right of the previous one.
            if a > 0 && right(level, new[a - 1]) != Some(q) {
                break 'grow;
            }
            new.push(q);
        }
        taken.extend(new.iter().map(|&(g, _)| g));
        rows.push(new);
    }
    rows
}

/// Greedy maximal rectangles of the faces `usable` says may join: from the
/// first free face in index order, in each of its four orientations, walk
/// left and down to a corner of the free region, grow a rectangle there
/// ([`grow`]), and keep the largest of the four. Returns each rectangle as
/// rows (`rect[b][a]` is the face at `(a, b)`).
pub(crate) fn rectangles(level: &Level, usable: &[bool]) -> Vec<Vec<Vec<Placed>>> {
    let mut used = vec![false; usable.len()];
    let mut out = Vec::new();
    for f in 0..usable.len() as u32 {
        if !usable[f as usize] || used[f as usize] {
            continue;
        }
        let free = |g: u32| usable[g as usize] && !used[g as usize];
        let mut best: Option<Vec<Vec<Placed>>> = None;
        for rot in 0..4 {
            let mut p = (f, rot);
            let mut seen = HashSet::from([f]);
            loop {
                let before = p;
                while let Some(q) = left(level, p)
                    && free(q.0)
                    && seen.insert(q.0)
                {
                    p = q;
                }
                while let Some(q) = down(level, p)
                    && free(q.0)
                    && seen.insert(q.0)
                {
                    p = q;
                }
                if p == before {
                    break;
                }
            }
            let rect = grow(level, p, &free);
            let area = |r: &Vec<Vec<Placed>>| r.len() * r[0].len();
            if best.as_ref().is_none_or(|b| area(&rect) > area(b)) {
                best = Some(rect);
            }
        }
        let rect = best.expect("four tries");
        for row in &rect {
            for &(g, _) in row {
                used[g as usize] = true;
            }
        }
        out.push(rect);
    }
    out
}

/// The clamped form of the uniform cubic B-spline with de Boor points `d`
/// (knots `−3, −2, …`, domain `[0, d.len() − 3]`): the same curve with knots
/// `0, 0, 0, 0, 1, 2, …, m, m, m, m` (`m = d.len() − 3`), by inserting each
/// end knot twice (Boehm's algorithm, The NURBS Book §5.2).
pub(crate) fn clamp_uniform(d: &[DVec3]) -> Vec<DVec3> {
    let m = d.len() - 3;
    let mut knots: Vec<f64> = (0..d.len() + 4).map(|i| i as f64 - 3.0).collect();
    let mut points = d.to_vec();
    for u in [0.0, 0.0, m as f64, m as f64] {
        // The span k with knots[k] <= u < knots[k + 1], or at the end of the
        // domain the last span, which ends at u.
        let k = knots
            .iter()
            .rposition(|&t| t <= u)
            .expect("u inside")
            .min(points.len() - 1);
        let mut new = Vec::with_capacity(points.len() + 1);
        for i in 0..=points.len() {
            let p = if i + 3 <= k {
                points[i]
            } else if i > k {
                points[i - 1]
            } else {
                let alpha = (u - knots[i]) / (knots[i + 3] - knots[i]);
                alpha * points[i] + (1.0 - alpha) * points[i - 1]
            };
            new.push(p);
        }
        knots.insert(k + 1, u);
        points = new;
    }
    // Knot 0 now has multiplicity 3 at index 3..6: the curve from 0 on
    // needs points from index 2; likewise at the end.
    points[2..points.len() - 2].to_vec()
}

/// Clamped cubic knots on `[0, m]`.
pub(crate) fn clamped_knots(m: usize) -> Vec<f64> {
    let mut k = vec![0.0; 4];
    k.extend((1..m).map(|i| i as f64));
    k.extend([m as f64; 4]);
    k
}

/// The clamped bicubic surface of a uniform grid `grid[i][j]` (`i` along u).
pub(crate) fn clamped_surface(grid: &[Vec<DVec3>]) -> NurbsSurface {
    let (nu, nv) = (grid.len(), grid[0].len());
    let rows: Vec<Vec<DVec3>> = grid.iter().map(|row| clamp_uniform(row)).collect();
    let mut points = vec![DVec3::ZERO; nu * nv];
    for j in 0..nv {
        let column: Vec<DVec3> = rows.iter().map(|r| r[j]).collect();
        for (i, p) in clamp_uniform(&column).into_iter().enumerate() {
            points[i * nv + j] = p;
        }
    }
    NurbsSurface::new(
        3,
        3,
        clamped_knots(nu - 3),
        clamped_knots(nv - 3),
        nu,
        nv,
        points,
        vec![1.0; nu * nv],
    )
    .expect("a clamped cubic grid of finite points is a valid surface")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curves::{Curve, NurbsCurve};

    #[test]
    fn clamping_keeps_the_curve() {
        let d: Vec<DVec3> = (0..7)
            .map(|i| DVec3::new(i as f64, ((i * i) % 5) as f64, (i % 3) as f64))
            .collect();
        let uniform = NurbsCurve::new(
            3,
            (0..11).map(|i| i as f64 - 3.0).collect(),
            d.clone(),
            vec![1.0; 7],
        )
        .unwrap();
        let clamped =
            NurbsCurve::new(3, clamped_knots(4), clamp_uniform(&d), vec![1.0; 7]).unwrap();
        for k in 0..=40 {
            let t = k as f64 / 10.0;
            assert!(
                (uniform.point(t) - clamped.point(t)).length() < 1e-13,
                "{t}"
            );
        }
        // The clamped ends are the curve's ends.
        assert!((clamp_uniform(&d)[0] - (d[0] + 4.0 * d[1] + d[2]) / 6.0).length() < 1e-15);
    }
}
