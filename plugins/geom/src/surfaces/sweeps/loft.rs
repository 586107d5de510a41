//! Lofts: sections made compatible and skinned, as ruled strips, as
//! control rows or interpolated (The NURBS Book §10.3).

use super::SweepError;
use crate::curves::interpolating::solve_dense;
use crate::curves::nurbs::basis_derivatives;
use crate::curves::{Curve, CurveError, NurbsCurve};
use crate::surfaces::NurbsSurface;
use glam::{DVec3, DVec4};

/// How closely a loft follows its sections between them.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Tightness {
    /// Ruled strips between neighbouring sections (degree 1 across);
    /// passes through every section.
    Straight,
    /// The sections' control points are the surface's control rows
    /// (degree up to 3 across): smooth, passes through the first and last
    /// section only (Rhino's Loose).
    Loose,
    /// Interpolates every section with a cubic across (degree up to 3;
    /// Rhino's Normal).
    #[default]
    Normal,
}

/// How a loft is made.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct LoftOptions {
    /// The last section joins back to the first (periodic across).
    pub closed: bool,
    /// How the surface runs between the sections.
    pub tightness: Tightness,
}

/// The curves made compatible (The NURBS Book §10.3): each clamped at its
/// ends ([`NurbsCurve::clamped_ends`]), its domain mapped onto [0, 1],
/// raised to the highest degree among them ([`NurbsCurve::elevate_degree`])
/// and given every knot of the others with the highest multiplicity any of
/// them has ([`NurbsCurve::insert_knot`]); none of the curves moves. After
/// it they share degree, knots and control point count. Inverse: none
/// (each result traces its input's shape).
///
/// # Errors
/// A knot insertion or elevation that fails.
///
/// Complexity: O(curves × (elevations + knots) × points).
pub fn make_compatible(curves: &[NurbsCurve]) -> Result<Vec<NurbsCurve>, SweepError> {
    let mut out = Vec::with_capacity(curves.len());
    for c in curves {
        let c = c.clamped_ends();
        let (a, b) = c.domain();
        let knots = c.knots().iter().map(|k| (k - a) / (b - a)).collect();
        out.push(NurbsCurve::new(
            c.degree(),
            knots,
            c.points().to_vec(),
            c.weights().to_vec(),
        )?);
    }
    let degree = out.iter().map(NurbsCurve::degree).max().unwrap_or(1);
    for c in &mut out {
        while c.degree() < degree {
            *c = c.elevate_degree()?;
        }
    }
    // The merged interior knots with their highest multiplicity.
    let mut merged: Vec<(f64, usize)> = Vec::new();
    for c in &out {
        for (value, count) in interior_multiplicities(c) {
            match merged.iter_mut().find(|(v, _)| *v == value) {
                Some((_, m)) => *m = (*m).max(count),
                None => merged.push((value, count)),
            }
        }
    }
    for c in &mut out {
        let own = interior_multiplicities(c);
        for &(value, m) in &merged {
            let has = own.iter().find(|(v, _)| *v == value).map_or(0, |(_, n)| *n);
            for _ in has..m {
                *c = c.insert_knot(value)?;
            }
        }
    }
    Ok(out)
}

fn interior_multiplicities(c: &NurbsCurve) -> Vec<(f64, usize)> {
    let (a, b) = c.domain();
    let mut out: Vec<(f64, usize)> = Vec::new();
    for &k in c.knots().iter().filter(|&&k| k > a && k < b) {
        match out.last_mut() {
            Some((v, n)) if *v == k => *n += 1,
            _ => out.push((k, 1)),
        }
    }
    out
}

/// A surface through the ordered `sections` (u along them, v across):
/// they are made compatible ([`make_compatible`]), then joined as
/// [`Tightness`] says, open (the first and last section are the v = 0 and
/// v = 1 boundaries) or closed (periodic across, uniform knots). Straight
/// and Normal lofts pass through every section; the parameters of the
/// sections across are their averaged chord lengths (uniform when closed),
/// the knots by averaging (The NURBS Book eq. 9.8). Interpolation runs in
/// homogeneous coordinates, so rational sections (circles) are reproduced
/// exactly. Inverse: none (section k is the surface's iso-curve at its
/// parameter).
///
/// # Errors
/// [`SweepError::TooFewSections`] (2 open, 3 closed); as
/// [`make_compatible`]; [`CurveError::Singular`] or a weight that comes out
/// non-positive (through [`SweepError::Curve`]) for sections too wild to
/// interpolate.
///
/// Complexity: O(points × sections³) for the dense solves.
pub fn loft(sections: &[NurbsCurve], options: LoftOptions) -> Result<NurbsSurface, SweepError> {
    let needed = if options.closed { 3 } else { 2 };
    if sections.len() < needed {
        return Err(SweepError::TooFewSections {
            what: if options.closed {
                "a closed loft"
            } else {
                "a loft"
            },
            needed,
            got: sections.len(),
        });
    }
    let curves = make_compatible(sections)?;
    let n = curves.len();
    let q = match options.tightness {
        Tightness::Straight => 1,
        _ => 3.min(if options.closed { n } else { n - 1 }),
    };
    if options.closed {
        let knots: Vec<f64> = (0..=n + 2 * q).map(|k| k as f64).collect();
        let rows = match options.tightness {
            Tightness::Loose => curves.clone(),
            _ => interpolate_periodic(&curves, q)?,
        };
        let mut wrapped = rows.clone();
        wrapped.extend_from_slice(&rows[..q]);
        return skin_rows(&wrapped, q, knots);
    }
    match options.tightness {
        Tightness::Loose => {
            let params: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
            skin_rows(&curves, q, uniform_clamped(q, &params))
        }
        _ => {
            let params = section_parameters(&curves);
            let knots = clamped_knots(q, &params);
            let rows = if q == 1 {
                curves
            } else {
                interpolate_open(&curves, q, &params, &knots)?
            };
            skin_rows(&rows, q, knots)
        }
    }
}

/// Averaged chord-length parameters of compatible sections (The NURBS
/// Book eq. 10.8): each control point index's chord lengths across the
/// sections, normalised, averaged over the indices that move.
fn section_parameters(curves: &[NurbsCurve]) -> Vec<f64> {
    let n = curves.len();
    let m = curves[0].points().len();
    let mut sum = vec![0.0; n];
    let mut used = 0;
    for i in 0..m {
        let chords: Vec<f64> = (1..n)
            .map(|k| curves[k].points()[i].distance(curves[k - 1].points()[i]))
            .collect();
        let total: f64 = chords.iter().sum();
        if total <= 0.0 {
            continue;
        }
        used += 1;
        let mut acc = 0.0;
        for k in 1..n {
            acc += chords[k - 1];
            sum[k] += acc / total;
        }
    }
    if used == 0 {
        return (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
    }
    let mut params: Vec<f64> = sum.iter().map(|s| s / used as f64).collect();
    params[n - 1] = 1.0;
    // Sections that coincide everywhere would repeat a parameter.
    for k in 1..n {
        if params[k] <= params[k - 1] {
            params[k] = params[k - 1] + 1e-9;
        }
    }
    let last = params[n - 1];
    params.iter().map(|p| p / last).collect()
}

/// Clamped knots of degree `q` by averaging the parameters (eq. 9.8).
pub(super) fn clamped_knots(q: usize, params: &[f64]) -> Vec<f64> {
    let n = params.len();
    let mut knots = vec![params[0]; q + 1];
    for j in 1..n - q {
        knots.push(params[j..j + q].iter().sum::<f64>() / q as f64);
    }
    knots.extend(std::iter::repeat_n(params[n - 1], q + 1));
    knots
}

/// Clamped uniform knots of degree `q` for `params.len()` control points.
fn uniform_clamped(q: usize, params: &[f64]) -> Vec<f64> {
    crate::curves::nurbs::clamped_uniform_knots(q, params.len())
}

fn find_span(knots: &[f64], q: usize, count: usize, t: f64) -> usize {
    if t >= knots[count] {
        let mut i = count - 1;
        while i > q && knots[i] >= knots[count] {
            i -= 1;
        }
        return i;
    }
    let mut i = q;
    while i < count - 1 && knots[i + 1] <= t {
        i += 1;
    }
    i
}

/// Solves `A x = rhs` for the homogeneous control points of each column:
/// `rows[k]` are the compatible curves, the result the control curves.
fn solve_columns(
    matrix: &[Vec<f64>],
    curves: &[NurbsCurve],
) -> Result<Vec<NurbsCurve>, SweepError> {
    let n = curves.len();
    let m = curves[0].points().len();
    let mut out_points = vec![vec![DVec3::ZERO; m]; n];
    let mut out_weights = vec![vec![0.0; m]; n];
    for i in 0..m {
        let hom: Vec<DVec4> = curves
            .iter()
            .map(|c| (c.points()[i] * c.weights()[i]).extend(c.weights()[i]))
            .collect();
        let xyz = solve_dense(matrix.to_vec(), hom.iter().map(|h| h.truncate()).collect())?;
        let w = solve_dense(
            matrix.to_vec(),
            hom.iter().map(|h| DVec3::new(h.w, 0.0, 0.0)).collect(),
        )?;
        for k in 0..n {
            let wk = w[k].x;
            if !(wk.is_finite() && wk > 0.0) {
                return Err(CurveError::BadWeight {
                    index: k * m + i,
                    value: wk,
                }
                .into());
            }
            out_points[k][i] = xyz[k] / wk;
            out_weights[k][i] = wk;
        }
    }
    let c0 = &curves[0];
    out_points
        .into_iter()
        .zip(out_weights)
        .map(|(p, w)| Ok(NurbsCurve::new(c0.degree(), c0.knots().to_vec(), p, w)?))
        .collect()
}

/// The control rows of an open cubic (degree `q`) interpolation across.
fn interpolate_open(
    curves: &[NurbsCurve],
    q: usize,
    params: &[f64],
    knots: &[f64],
) -> Result<Vec<NurbsCurve>, SweepError> {
    let n = curves.len();
    let mut matrix = vec![vec![0.0; n]; n];
    for (k, &t) in params.iter().enumerate() {
        let span = find_span(knots, q, n, t);
        let basis = basis_derivatives(knots, span, t, q, 0);
        for (r, &b) in basis[0].iter().enumerate() {
            matrix[k][span - q + r] = b;
        }
    }
    solve_columns(&matrix, curves)
}

/// The `n` periodic control rows of degree `q` on uniform knots whose
/// surface passes through section `k` at `v = q + k` (odd `q`) or
/// `q + k + ½` (even `q`).
fn interpolate_periodic(curves: &[NurbsCurve], q: usize) -> Result<Vec<NurbsCurve>, SweepError> {
    let n = curves.len();
    let knots: Vec<f64> = (0..=n + 2 * q).map(|k| k as f64).collect();
    let shift = if q.is_multiple_of(2) { 0.5 } else { 0.0 };
    let mut matrix = vec![vec![0.0; n]; n];
    for (k, row) in matrix.iter_mut().enumerate() {
        let t = (q + k) as f64 + shift;
        let span = find_span(&knots, q, n + q, t);
        let basis = basis_derivatives(&knots, span, t, q, 0);
        for (r, &b) in basis[0].iter().enumerate() {
            row[(span - q + r) % n] += b;
        }
    }
    solve_columns(&matrix, curves)
}

/// The surface whose v-rows of control points are the compatible curves
/// `rows` (u along each), degree `q` across on `knots`.
pub(super) fn skin_rows(
    rows: &[NurbsCurve],
    q: usize,
    knots: Vec<f64>,
) -> Result<NurbsSurface, SweepError> {
    let nv = rows.len();
    let c0 = &rows[0];
    let nu = c0.points().len();
    let mut points = vec![DVec3::ZERO; nu * nv];
    let mut weights = vec![0.0; nu * nv];
    for (j, row) in rows.iter().enumerate() {
        for i in 0..nu {
            points[i * nv + j] = row.points()[i];
            weights[i * nv + j] = row.weights()[i];
        }
    }
    Ok(NurbsSurface::new(
        c0.degree(),
        q,
        c0.knots().to_vec(),
        knots,
        nu,
        nv,
        points,
        weights,
    )?)
}

/// The v parameters at which a loft made with `options` passes through its
/// sections (empty for an open Loose loft, which passes through only its
/// first and last).
///
/// Complexity: that of [`make_compatible`].
pub fn loft_section_parameters(sections: &[NurbsCurve], options: LoftOptions) -> Vec<f64> {
    let Ok(curves) = make_compatible(sections) else {
        return Vec::new();
    };
    let n = curves.len();
    if options.closed {
        let q = match options.tightness {
            Tightness::Straight => 1,
            _ => 3.min(n),
        };
        let shift = if q.is_multiple_of(2) { 0.5 } else { 0.0 };
        return (0..n).map(|k| (q + k) as f64 + shift).collect();
    }
    match options.tightness {
        Tightness::Loose => Vec::new(),
        _ => section_parameters(&curves),
    }
}
