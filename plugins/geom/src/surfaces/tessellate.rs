//! Tessellation of curves and surfaces into polylines and triangles.
//! Curves are cut knot span by knot span ([`curve_parameters`]: every
//! breakpoint is a vertex, straight pieces get no others). Surfaces get one
//! grid (so neighbouring cells share their edges and no crack opens) whose
//! lines hold every knot and are spread by the surface's curvature within
//! each knot span, within a tolerance and a bound on the cell count
//! ([`surface_parameters`]); a uniform grid too ([`grid`]).

use glam::DVec3;

use super::Surface;
use crate::curves::Curve;

/// Triangles of a surface with the parameters of each vertex.
#[derive(Clone, Debug, Default)]
pub struct SurfaceMesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Unit normal per vertex (the limit normal at poles).
    pub normals: Vec<DVec3>,
    /// `(u, v)` of each vertex.
    pub params: Vec<(f64, f64)>,
    /// Vertex indices of each triangle.
    pub triangles: Vec<[u32; 3]>,
}

/// A `(cu + 1) × (cv + 1)` grid of points, two triangles per cell,
/// counter-clockwise around `S_u × S_v`.
pub fn grid(surface: &dyn Surface, cu: usize, cv: usize) -> SurfaceMesh {
    let ((u0, u1), (v0, v1)) = surface.domain();
    let (cu, cv) = (cu.max(1), cv.max(1));
    let us: Vec<f64> = (0..=cu)
        .map(|i| u0 + (u1 - u0) * i as f64 / cu as f64)
        .collect();
    let vs: Vec<f64> = (0..=cv)
        .map(|j| v0 + (v1 - v0) * j as f64 / cv as f64)
        .collect();
    grid_at(surface, &us, &vs)
}

/// The grid of points at the parameters `us × vs` (each increasing, at
/// least two), two triangles per cell, counter-clockwise around `S_u × S_v`.
pub fn grid_at(surface: &dyn Surface, us: &[f64], vs: &[f64]) -> SurfaceMesh {
    let (cu, cv) = (us.len().saturating_sub(1), vs.len().saturating_sub(1));
    let mut m = SurfaceMesh::default();
    for &u in us {
        for &v in vs {
            let s = surface.evaluate(u, v);
            m.positions.push(s.p);
            let n = s.normal();
            m.normals.push(if n == DVec3::ZERO {
                super::limit_normal(surface, u, v)
            } else {
                n
            });
            m.params.push((u, v));
        }
    }
    m.triangles = grid_triangles(cu, cv);
    m
}

/// Cells in u and v of [`surface_parameters`]' grid: its rows and columns
/// less one. The grid is not uniform; use [`surface_parameters`] for where
/// its lines are.
pub fn cells_for_tolerance(surface: &dyn Surface, tolerance: f64) -> (usize, usize) {
    let (us, vs) = surface_parameters(surface, tolerance);
    (us.len() - 1, vs.len() - 1)
}

/// The most cells of a surface grid in one direction.
pub const MAX_CELLS_PER_DIRECTION: usize = 2048;

/// The most cells of a surface grid (two triangles each): a surface that
/// would need more at the tolerance asked is tessellated more coarsely,
/// with its cells spread the same way (about a million triangles; the
/// unit sphere within 1e-4 takes about 30,000).
pub const MAX_CELLS: usize = 1 << 19;

/// The parameters of the grid lines of a surface tessellation within
/// `tolerance` of the surface (the grid of [`tessellate`]), `(us, vs)`, each
/// increasing from the domain's start to its end and holding every
/// breakpoint ([`Surface::breakpoints`]: a NURBS surface's distinct knots),
/// so that no cell straddles a knot line where the surface may fold.
///
/// Within each knot span the lines follow the surface's curvature, not its
/// parameterisation: the sag of a flat triangle over the surface is, to
/// second order, `(L hu² + 2M hu hv + N hv²) / 8` with the second
/// fundamental form `L = S_uu·n`, `M = S_uv·n`, `N = S_vv·n` (do Carmo,
/// *Differential Geometry of Curves and Surfaces*, §3-3; the `h² |f''| / 8`
/// error of linear interpolation, de Boor, *A Practical Guide to Splines*,
/// ch. II), which stays under `tolerance` when each direction keeps
/// `(|L| + |M|) hu² / 8` and `(|N| + |M|) hv² / 8` under half of it. The
/// densities `√((|L| + |M|) / 4 tol)` (u) and `√((|N| + |M|) / 4 tol)` (v),
/// their largest over the other direction, are sampled at the middles of a
/// few sub-intervals of each span, and the lines are spread so that each
/// cell holds an equal share of their integral (the equidistribution of
/// de Boor's `NEWNOT`, ibid. ch. XII). The tangential part of the second
/// derivatives, which moves points along the surface and not off it, is
/// left out: a rational patch with extreme weights has huge parametric
/// second derivatives where its parameterisation speeds up, though its
/// shape there may be nearly flat, and counting them asked for up to 2048
/// × 2048 cells. Then every cell is checked where a flat cell's error
/// peaks, the middles of its edges against their chords and its centre
/// against its two triangles, and the cells off by more than `tolerance`
/// are halved (the whole grid line: the grid stays crack-free), a few
/// rounds: the samples see most of the shape, the check what they miss.
///
/// Bounded: at most [`MAX_CELLS_PER_DIRECTION`] cells per direction and
/// [`MAX_CELLS`] in all (the densities are scaled down evenly to fit, so
/// such a grid is coarser than the tolerance). O(samples + cells).
pub fn surface_parameters(surface: &dyn Surface, tolerance: f64) -> (Vec<f64>, Vec<f64>) {
    let ((u0, u1), (v0, v1)) = surface.domain();
    let (bu, bv) = surface.breakpoints();
    let bu = clean_breakpoints(bu, (u0, u1));
    let bv = clean_breakpoints(bv, (v0, v1));
    let tol = tolerance.max(1e-12);
    let su = probe_intervals(&bu, SURFACE_PROBES);
    let sv = probe_intervals(&bv, SURFACE_PROBES);
    // The densities, largest over the other direction's samples.
    let mut du = vec![0.0f64; su.len()];
    let mut dv = vec![0.0f64; sv.len()];
    for (i, &(_, ua, ub)) in su.iter().enumerate() {
        let u = 0.5 * (ua + ub);
        for (j, &(_, va, vb)) in sv.iter().enumerate() {
            let v = 0.5 * (va + vb);
            let (l, m, n) = fundamental_form(surface, u, v);
            du[i] = du[i].max(finite_or_zero(((l + m) / (4.0 * tol)).sqrt()));
            dv[j] = dv[j].max(finite_or_zero(((n + m) / (4.0 * tol)).sqrt()));
        }
    }
    let lines = |breaks: &[f64], intervals: &[(usize, f64, f64)], density: &[f64], scale: f64| {
        let mut out = vec![breaks[0]];
        for span in 0..breaks.len() - 1 {
            let pieces: Vec<(f64, f64, f64)> = intervals
                .iter()
                .zip(density)
                .filter(|((s, _, _), _)| *s == span)
                .map(|(&(_, a, b), &d)| (a, b, d * scale))
                .collect();
            out.extend(equidistribute(&pieces, MAX_CELLS_PER_DIRECTION));
            out.push(breaks[span + 1]);
        }
        out
    };
    let (mut us, mut vs) = (lines(&bu, &su, &du, 1.0), lines(&bv, &sv, &dv, 1.0));
    let cells = |us: &[f64], vs: &[f64]| (us.len() - 1) * (vs.len() - 1);
    if cells(&us, &vs) > MAX_CELLS {
        let scale = (MAX_CELLS as f64 / cells(&us, &vs) as f64).sqrt();
        us = lines(&bu, &su, &du, scale);
        vs = lines(&bv, &sv, &dv, scale);
    }
    // The check of every cell where its error is largest: its edges'
    // middles against their chords, its centre against its two triangles.
    for _ in 0..CHECK_ROUNDS {
        let room = cells(&us, &vs) < MAX_CELLS;
        let (split_u, split_v) = sagging_cells(surface, &us, &vs, tol);
        let split_u = if room && us.len() <= MAX_CELLS_PER_DIRECTION {
            split_u
        } else {
            false_flags(&us)
        };
        let split_v = if room && vs.len() <= MAX_CELLS_PER_DIRECTION {
            split_v
        } else {
            false_flags(&vs)
        };
        if !split_u.contains(&true) && !split_v.contains(&true) {
            break;
        }
        us = with_midpoints(&us, &split_u);
        vs = with_midpoints(&vs, &split_v);
    }
    (us, vs)
}

/// Samples per knot span for the flatness estimate, before the cap: the
/// whole domain gets about [`SURFACE_PROBES`] (or [`CURVE_PROBES`]) spread
/// over its spans, at least 2 and at most 16 per span.
const SURFACE_PROBES: usize = 32;
const CURVE_PROBES: usize = 64;
const MAX_PROBES_PER_SPAN: usize = 16;

/// Rounds of the chord check after the spread: each splits the cells that
/// sag too much in two.
const CHECK_ROUNDS: usize = 6;

fn finite_or_zero(x: f64) -> f64 {
    if x.is_finite() { x } else { 0.0 }
}

fn false_flags(params: &[f64]) -> Vec<bool> {
    vec![false; params.len().saturating_sub(1)]
}

/// The breakpoints inside the domain, sorted and distinct, with the
/// domain's ends first and last.
fn clean_breakpoints(mut breaks: Vec<f64>, (a, b): (f64, f64)) -> Vec<f64> {
    breaks.retain(|&t| t.is_finite() && t > a && t < b);
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let mut out = Vec::with_capacity(breaks.len() + 2);
    out.push(a);
    out.extend(breaks);
    if b > a {
        out.push(b);
    }
    out
}

/// `(span, start, end)` of the sub-intervals each span is sampled on:
/// `total / spans` per span, between 2 and [`MAX_PROBES_PER_SPAN`].
fn probe_intervals(breaks: &[f64], total: usize) -> Vec<(usize, f64, f64)> {
    let spans = breaks.len().saturating_sub(1);
    let k = total.div_ceil(spans.max(1)).clamp(2, MAX_PROBES_PER_SPAN);
    let mut out = Vec::with_capacity(spans * k);
    for (span, w) in breaks.windows(2).enumerate() {
        let (a, b) = (w[0], w[1]);
        for j in 0..k {
            let s = a + (b - a) * j as f64 / k as f64;
            let e = if j + 1 == k {
                b
            } else {
                a + (b - a) * (j + 1) as f64 / k as f64
            };
            out.push((span, s, e));
        }
    }
    out
}

/// `|L|`, `|M|`, `|N|`: the normal components of the second partial
/// derivatives, with the limit normal where `S_u × S_v` vanishes, and the
/// whole second derivatives where no normal is defined at all.
fn fundamental_form(surface: &dyn Surface, u: f64, v: f64) -> (f64, f64, f64) {
    let s = surface.evaluate(u, v);
    let mut n = s.normal();
    if n == DVec3::ZERO {
        n = super::limit_normal(surface, u, v);
    }
    if n == DVec3::ZERO {
        return (s.duu.length(), s.duv.length(), s.dvv.length());
    }
    (s.duu.dot(n).abs(), s.duv.dot(n).abs(), s.dvv.dot(n).abs())
}

/// The interior cuts that split an interval covered by `pieces` (`(start,
/// end, density)`, density in cells per unit parameter, constant on each
/// piece) into `n = ⌈∫ density⌉` cells (at least 1, at most `max_cells`)
/// with an equal share of the integral each: de Boor's equidistribution
/// (*A Practical Guide to Splines*, ch. XII, `NEWNOT`). Increasing, strictly
/// inside the interval.
fn equidistribute(pieces: &[(f64, f64, f64)], max_cells: usize) -> Vec<f64> {
    let Some((&(a, _, _), &(_, b, _))) = pieces.first().zip(pieces.last()) else {
        return Vec::new();
    };
    let weights: Vec<f64> = pieces
        .iter()
        .map(|&(s, e, d)| (e - s) * finite_or_zero(d).max(0.0))
        .collect();
    let total: f64 = weights.iter().sum();
    // Weights are finite and not negative, so `total` is too.
    if total <= 1.0 {
        return Vec::new();
    }
    let n = (total.ceil() as usize).clamp(1, max_cells.max(1));
    let step = total / n as f64;
    let mut out = Vec::with_capacity(n - 1);
    let (mut acc, mut i) = (0.0, 1);
    for (&(s, e, _), &w) in pieces.iter().zip(&weights) {
        while i < n && acc + w >= i as f64 * step {
            let t = if w > 0.0 {
                s + (e - s) * ((i as f64 * step - acc) / w).clamp(0.0, 1.0)
            } else {
                e
            };
            if t > a && t < b && out.last().is_none_or(|&l| t > l) {
                out.push(t);
            }
            i += 1;
        }
        acc += w;
    }
    out
}

/// The u-cells and v-cells of the grid `us × vs` to halve: a u-cell where
/// the middle of one of its u-edges lies further than `tol` from the edge,
/// a v-cell likewise, and both of a cell whose centre lies further than
/// `tol` from both of its triangles (as [`grid_triangles`] cuts it). Four
/// grids of points: corners, u-edge and v-edge middles, centres.
fn sagging_cells(
    surface: &dyn Surface,
    us: &[f64],
    vs: &[f64],
    tol: f64,
) -> (Vec<bool>, Vec<bool>) {
    let mids = |p: &[f64]| -> Vec<f64> { p.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect() };
    let (um, vm) = (mids(us), mids(vs));
    let corner = surface.grid_points(us, vs);
    let u_mid = surface.grid_points(&um, vs);
    let v_mid = surface.grid_points(us, &vm);
    let centre = surface.grid_points(&um, &vm);
    let (nv, cv) = (vs.len(), vm.len());
    let (mut split_u, mut split_v) = (false_flags(us), false_flags(vs));
    for i in 0..um.len() {
        for j in 0..nv {
            let (a, b) = (corner[i * nv + j], corner[(i + 1) * nv + j]);
            if distance_to_segment(u_mid[i * nv + j], a, b) > tol {
                split_u[i] = true;
            }
        }
    }
    for i in 0..us.len() {
        for j in 0..cv {
            let (a, b) = (corner[i * nv + j], corner[i * nv + j + 1]);
            if distance_to_segment(v_mid[i * cv + j], a, b) > tol {
                split_v[j] = true;
            }
        }
    }
    for i in 0..um.len() {
        for j in 0..cv {
            let [p00, p10, p11, p01] = [
                corner[i * nv + j],
                corner[(i + 1) * nv + j],
                corner[(i + 1) * nv + j + 1],
                corner[i * nv + j + 1],
            ];
            let c = centre[i * cv + j];
            let d =
                distance_to_triangle(c, p00, p10, p11).min(distance_to_triangle(c, p00, p11, p01));
            if d > tol {
                split_u[i] = true;
                split_v[j] = true;
            }
        }
    }
    (split_u, split_v)
}

/// The distance from `p` to the triangle `abc`, through its closest point
/// (Ericson, *Real-Time Collision Detection*, §5.1.5, by Voronoi regions).
fn distance_to_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return (p - (a + ab * (d1 / (d1 - d3)))).length();
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return (p - (a + ac * (d2 / (d2 - d6)))).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).length();
    }
    let denom = va + vb + vc;
    if denom.abs() < f64::MIN_POSITIVE {
        // A degenerate triangle (a pole's cell): its corners' distance.
        return ap.length().min(bp.length()).min(cp.length());
    }
    (p - (a + ab * (vb / denom) + ac * (vc / denom))).length()
}

/// `params` with the middle of each flagged cell added.
fn with_midpoints(params: &[f64], split: &[bool]) -> Vec<f64> {
    let mut out = Vec::with_capacity(params.len() * 2);
    for (c, w) in params.windows(2).enumerate() {
        out.push(w[0]);
        let m = 0.5 * (w[0] + w[1]);
        if split[c] && m > w[0] && m < w[1] {
            out.push(m);
        }
    }
    out.extend(params.last());
    out
}

/// The distance from `p` to the segment `ab`.
fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + t * ab)).length()
}

/// A triangle mesh of the surface within about `tolerance` of it, on the
/// grid of [`surface_parameters`].
pub fn tessellate(surface: &dyn Surface, tolerance: f64) -> SurfaceMesh {
    let (us, vs) = surface_parameters(surface, tolerance);
    grid_at(surface, &us, &vs)
}

/// [`tessellate`] for a NURBS surface through its fast grid evaluator.
pub fn tessellate_nurbs(surface: &super::NurbsSurface, tolerance: f64) -> SurfaceMesh {
    let (us, vs) = surface_parameters(surface, tolerance);
    let (cu, cv) = (us.len() - 1, vs.len() - 1);
    let (positions, normals) = surface.grid(&us, &vs, true);
    let params = us
        .iter()
        .flat_map(|&u| vs.iter().map(move |&v| (u, v)))
        .collect();
    SurfaceMesh {
        positions,
        normals,
        params,
        triangles: grid_triangles(cu, cv),
    }
}

/// Two counter-clockwise triangles per cell of a `(cu + 1) × (cv + 1)` grid.
pub fn grid_triangles(cu: usize, cv: usize) -> Vec<[u32; 3]> {
    let id = |i: usize, j: usize| (i * (cv + 1) + j) as u32;
    let mut t = Vec::with_capacity(2 * cu * cv);
    for i in 0..cu {
        for j in 0..cv {
            t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    t
}

/// The most pieces one span of a curve is cut into.
pub const MAX_PIECES_PER_SPAN: usize = 4096;

/// Parameters along a curve for a polyline within `tolerance` of it, knot
/// span by knot span: every breakpoint ([`Curve::breakpoints`]: a NURBS
/// curve's distinct knots, so a corner is always a vertex) is one of them,
/// a curve of straight pieces ([`Curve::piece_degree`] 1: a polyline, a
/// Koch curve, a Chaikin polygon) gets nothing else, and a curved span is
/// cut where its bend asks for it.
///
/// A chord over a parameter step `h` stays within `h² |c''_⊥| / 8` of the
/// curve (the error of linear interpolation, de Boor, *A Practical Guide to
/// Splines*, ch. II), where `c''_⊥ = |c' × c''| / |c'|` is the part of the
/// second derivative across the curve, `κ |c'|²` (the part along it only
/// changes the speed). Each span is sampled at the middles of a few
/// sub-intervals, and its cuts spread so that each piece holds an equal
/// share of `∫ √(|c''_⊥| / 8 tol)` (de Boor's equidistribution, ibid. ch.
/// XII, `NEWNOT`), at most [`MAX_PIECES_PER_SPAN`]. Then each piece is
/// checked: where the curve at its quarters and middle lies further than
/// `tolerance` from the chord, it is halved (up to 12 times).
///
/// Increasing, from the domain's start to its end. O(spans + pieces).
pub fn curve_parameters(curve: &dyn Curve, tolerance: f64) -> Vec<f64> {
    let breaks = clean_breakpoints(curve.breakpoints(), curve.domain());
    if breaks.len() < 2 || curve.piece_degree() == Some(1) {
        return breaks;
    }
    let tol = tolerance.max(1e-12);
    let intervals = probe_intervals(&breaks, CURVE_PROBES);
    let mut out = vec![breaks[0]];
    for (span, w) in breaks.windows(2).enumerate() {
        let pieces: Vec<(f64, f64, f64)> = intervals
            .iter()
            .filter(|i| i.0 == span)
            .map(|&(_, a, b)| {
                let [_, d1, d2] = curve.derivatives(0.5 * (a + b));
                (a, b, (normal_acceleration(d1, d2) / (8.0 * tol)).sqrt())
            })
            .collect();
        let mut cuts = vec![w[0]];
        cuts.extend(equidistribute(&pieces, MAX_PIECES_PER_SPAN));
        cuts.push(w[1]);
        for c in cuts.windows(2) {
            let (a, b) = (curve.point(c[0]), curve.point(c[1]));
            halve_while_sagging(curve, (c[0], a), (c[1], b), tol, 12, &mut out);
        }
    }
    out
}

/// How far the curve leaves its chord between `s` and `e`: its distances
/// from the chord at the eighths of the step, the largest refined by the
/// parabola through it and its two neighbours (successive parabolic
/// interpolation, *Numerical Recipes*, 3rd ed., §10.3), since the largest
/// sag of a piece lies between samples, off the middle when the piece is
/// not symmetric.
fn chord_sag(curve: &dyn Curve, (s, ps): (f64, DVec3), (e, pe): (f64, DVec3)) -> f64 {
    let mut d = [0.0f64; 9];
    for (k, dk) in d.iter_mut().enumerate().take(8).skip(1) {
        *dk = distance_to_segment(curve.point(s + (e - s) * k as f64 / 8.0), ps, pe);
    }
    let k = (1..8).max_by(|&a, &b| d[a].total_cmp(&d[b])).unwrap_or(4);
    let (y0, y1, y2) = (d[k - 1], d[k], d[k + 1]);
    // The vertex of the parabola through (−1, y0), (0, y1), (1, y2).
    let curvature = y0 - 2.0 * y1 + y2;
    let peak = if curvature < 0.0 {
        y1 - (y2 - y0).powi(2) / (8.0 * curvature)
    } else {
        y1
    };
    peak.clamp(y1, 1.5 * y1)
}

/// `|d2 − (d2·T) T|` for the unit tangent `T` along `d1`: the second
/// derivative's part across the curve; all of it where `d1` vanishes.
fn normal_acceleration(d1: DVec3, d2: DVec3) -> f64 {
    let t = d1.normalize_or_zero();
    if t == DVec3::ZERO {
        return d2.length();
    }
    (d2 - d2.dot(t) * t).length()
}

/// Pushes the parameters after `s` up to `e`: `e`, and before it the
/// middles of the halves of `[s, e]` whose chord the curve leaves by more
/// than `tol` ([`chord_sag`]), `depth` levels at most.
fn halve_while_sagging(
    curve: &dyn Curve,
    (s, ps): (f64, DVec3),
    (e, pe): (f64, DVec3),
    tol: f64,
    depth: u32,
    out: &mut Vec<f64>,
) {
    let m = 0.5 * (s + e);
    let sags = depth > 0 && m > s && m < e && chord_sag(curve, (s, ps), (e, pe)) > tol;
    if sags {
        let pm = curve.point(m);
        halve_while_sagging(curve, (s, ps), (m, pm), tol, depth - 1, out);
        halve_while_sagging(curve, (m, pm), (e, pe), tol, depth - 1, out);
    } else {
        out.push(e);
    }
}

/// Where the plane through `origin` with normal `normal` cuts a
/// tessellated surface: one segment per triangle it crosses (the planar
/// section of seed 002's exercise, within the tessellation's tolerance).
pub fn plane_section(mesh: &SurfaceMesh, origin: DVec3, normal: DVec3) -> Vec<[DVec3; 2]> {
    let d: Vec<f64> = mesh
        .positions
        .iter()
        .map(|p| (*p - origin).dot(normal))
        .collect();
    let mut out = Vec::new();
    for t in &mesh.triangles {
        let mut crossing = Vec::with_capacity(2);
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            let (da, db) = (d[a], d[b]);
            if (da < 0.0) != (db < 0.0) {
                let s = da / (da - db);
                crossing.push(mesh.positions[a].lerp(mesh.positions[b], s));
            }
        }
        if let [p, q] = crossing[..] {
            out.push([p, q]);
        }
    }
    out
}
