//! A curve kind's NURBS form and what it is computed from: the
//! spline solvers (Thomas, cyclic Thomas, Kochanek-Bartels and C2
//! tangents), the Hermite form, the key parameters, the level polygon and
//! [`CurveKind::to_nurbs`].

use super::{CurveKind, LAGRANGE_EXACT_POINTS, NurbsForm, Parameterization, SplineEnds};
use crate::curves::bezier::bernstein;
use crate::curves::interpolating::{HermiteSpline, Tbc, c2_cubic_spline, chaikin, solve_dense};
use crate::curves::nurbs::NurbsCurve;
use crate::curves::{Curve, CurveError, check_points};
use glam::DVec3;

/// Solves the tridiagonal system `a_i x_{i−1} + b_i x_i + c_i x_{i+1} = d_i`
/// (Thomas algorithm, O(n); `a[0]` and `c[n−1]` are ignored).
fn thomas(a: &[f64], b: &[f64], c: &[f64], d: &[DVec3]) -> Vec<DVec3> {
    let n = b.len();
    let (mut b, mut d) = (b.to_vec(), d.to_vec());
    for i in 1..n {
        let w = a[i] / b[i - 1];
        b[i] -= w * c[i - 1];
        let prev = d[i - 1];
        d[i] -= w * prev;
    }
    let mut x = vec![DVec3::ZERO; n];
    x[n - 1] = d[n - 1] / b[n - 1];
    for i in (0..n - 1).rev() {
        x[i] = (d[i] - c[i] * x[i + 1]) / b[i];
    }
    x
}

/// The cyclic tridiagonal system (`a[0]` couples `x_{n−1}` into row 0,
/// `c[n−1]` couples `x_0` into the last row), by Sherman-Morrison
/// (Numerical Recipes §2.7), O(n); n ≥ 3.
fn cyclic_thomas(a: &[f64], b: &[f64], c: &[f64], d: &[DVec3]) -> Vec<DVec3> {
    let n = b.len();
    let (alpha, beta) = (c[n - 1], a[0]);
    let gamma = -b[0];
    let mut bb = b.to_vec();
    bb[0] -= gamma;
    bb[n - 1] -= alpha * beta / gamma;
    let x = thomas(a, &bb, c, d);
    let mut u = vec![DVec3::ZERO; n];
    u[0] = DVec3::splat(gamma);
    u[n - 1] = DVec3::splat(alpha);
    let z = thomas(a, &bb, c, &u);
    let fact = (x[0] + beta * x[n - 1] / gamma) / (1.0 + z[0].x + beta * z[n - 1].x / gamma);
    x.iter().zip(&z).map(|(xi, zi)| *xi - fact * zi.x).collect()
}

/// Kochanek-Bartels tangents of a closed loop (the open case is
/// [`HermiteSpline::kochanek_bartels`]): keys wrap around.
fn closed_kb(
    points: &[DVec3],
    keys: &[Tbc],
    params: Vec<f64>,
) -> Result<HermiteSpline, CurveError> {
    let n = points.len();
    let mut out = Vec::with_capacity(n + 1);
    let mut inc = Vec::with_capacity(n + 1);
    for i in 0..n {
        let (prev, next) = (points[(i + n - 1) % n], points[(i + 1) % n]);
        let Tbc {
            tension: t,
            bias: b,
            continuity: c,
        } = keys[i];
        let (before, after) = (points[i] - prev, next - points[i]);
        let o = (1.0 - t) * (1.0 + b) * (1.0 + c) / 2.0 * before
            + (1.0 - t) * (1.0 - b) * (1.0 - c) / 2.0 * after;
        let d = (1.0 - t) * (1.0 + b) * (1.0 - c) / 2.0 * before
            + (1.0 - t) * (1.0 - b) * (1.0 + c) / 2.0 * after;
        let h_prev = if i == 0 {
            params[n] - params[n - 1]
        } else {
            params[i] - params[i - 1]
        };
        let per_t = 2.0 / (h_prev + params[i + 1] - params[i]);
        out.push(per_t * o);
        inc.push(per_t * d);
    }
    out.push(out[0]);
    inc.push(inc[0]);
    let mut ext = points.to_vec();
    ext.push(points[0]);
    let mut s = HermiteSpline::new(params, ext, out)?;
    s.incoming = inc;
    Ok(s)
}

/// The C2 cubic spline with clamped or closed ends (natural ends are
/// [`c2_cubic_spline`]); seed 004's tridiagonal system for the tangents.
fn c2_spline(
    points: &[DVec3],
    parameterization: Parameterization,
    ends: SplineEnds,
) -> Result<HermiteSpline, CurveError> {
    let n = points.len();
    match ends {
        SplineEnds::Natural => {
            c2_cubic_spline(parameterization.parameters(points)?, points.to_vec())
        }
        SplineEnds::Clamped { start, end } => {
            check_points(&[start, end]).map_err(|_| CurveError::NotFiniteVector {
                what: "an end tangent",
            })?;
            let t = parameterization.parameters(points)?;
            let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
            let (mut a, mut b, mut c) = (vec![0.0; n], vec![1.0; n], vec![0.0; n]);
            let mut d = vec![DVec3::ZERO; n];
            d[0] = start;
            d[n - 1] = end;
            for i in 1..n - 1 {
                a[i] = h[i];
                b[i] = 2.0 * (h[i - 1] + h[i]);
                c[i] = h[i - 1];
                d[i] = 3.0
                    * (h[i] / h[i - 1] * (points[i] - points[i - 1])
                        + h[i - 1] / h[i] * (points[i + 1] - points[i]));
            }
            HermiteSpline::new(t, points.to_vec(), thomas(&a, &b, &c, &d))
        }
        SplineEnds::Closed => {
            let mut ext = points.to_vec();
            ext.push(points[0]);
            let t = closed_parameters(parameterization, points)?;
            let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
            let (mut a, mut b, mut c) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            let mut d = vec![DVec3::ZERO; n];
            for i in 0..n {
                let (hp, hn) = (h[(i + n - 1) % n], h[i]);
                let (prev, next) = (points[(i + n - 1) % n], points[(i + 1) % n]);
                a[i] = hn;
                b[i] = 2.0 * (hp + hn);
                c[i] = hp;
                d[i] = 3.0 * (hn / hp * (points[i] - prev) + hp / hn * (next - points[i]));
            }
            let mut m = cyclic_thomas(&a, &b, &c, &d);
            m.push(m[0]);
            HermiteSpline::new(t, ext, m)
        }
    }
}

/// Parameters of a closed loop: the points and the first again.
fn closed_parameters(p: Parameterization, points: &[DVec3]) -> Result<Vec<f64>, CurveError> {
    let mut ext = points.to_vec();
    ext.push(points[0]);
    p.parameters(&ext).map_err(|e| match e {
        CurveError::CoincidentPoints { index, next } if next == points.len() => {
            CurveError::CoincidentPoints { index, next: 0 }
        }
        e => e,
    })
}

/// The exact NURBS form of a piecewise cubic Hermite curve: each span a
/// Bézier segment, interior knots of multiplicity 3 at the key parameters.
fn hermite_to_nurbs(h: &HermiteSpline) -> Result<NurbsCurve, CurveError> {
    let segments = h.params.len() - 1;
    let mut points = vec![h.points[0]];
    let mut knots = vec![h.params[0]; 4];
    for i in 0..segments {
        points.extend_from_slice(&h.bezier_segment(i).points[1..]);
        let reps = if i + 1 == segments { 4 } else { 3 };
        knots.extend(std::iter::repeat_n(h.params[i + 1], reps));
    }
    let w = vec![1.0; points.len()];
    NurbsCurve::new(3, knots, points, w)
}

/// A polyline as a degree-1 NURBS, uniform parameters on [0, 1].
fn polyline(points: Vec<DVec3>) -> Result<NurbsCurve, CurveError> {
    NurbsCurve::clamped(1, points)
}

/// The largest value of `f` on `[a, b]`: the best of 8 equal steps, then a
/// golden-section search (Kiefer 1953; *Numerical Recipes*, 3rd ed., §10.2)
/// between that sample's neighbours, 48 steps. Exact for a function with
/// one bump between neighbouring samples, as the error of an interpolating
/// spline between two of its nodes has (zero at both, one hump between).
fn interval_max(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    const STEPS: usize = 8;
    let x = |k: usize| a + (b - a) * k as f64 / STEPS as f64;
    let (mut best_k, mut best) = (0, f(a));
    for k in 1..=STEPS {
        let y = f(x(k));
        if y > best {
            (best_k, best) = (k, y);
        }
    }
    let (mut lo, mut hi) = (x(best_k.saturating_sub(1)), x((best_k + 1).min(STEPS)));
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut c, mut d) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..48 {
        if fc > fd {
            (hi, d, fd) = (d, c, fc);
            c = hi - g * (hi - lo);
            fc = f(c);
        } else {
            (lo, c, fc) = (c, d, fd);
            d = lo + g * (hi - lo);
            fd = f(d);
        }
    }
    best.max(fc).max(fd)
}

/// The Lagrange polynomial through `points` at `params`, at `t`, by the
/// barycentric formula (stable for any degree; seed 000's Vandermonde
/// system gives the same polynomial). O(n²).
pub fn lagrange_point(params: &[f64], points: &[DVec3], t: f64) -> DVec3 {
    let n = params.len();
    let mut num = DVec3::ZERO;
    let mut den = 0.0;
    for j in 0..n {
        let d = t - params[j];
        if d == 0.0 {
            return points[j];
        }
        let w: f64 = (0..n)
            .filter(|&k| k != j)
            .map(|k| 1.0 / (params[j] - params[k]))
            .product();
        num += w / d * points[j];
        den += w / d;
    }
    num / den
}

impl CurveKind {
    /// The Hermite form of the Hermite-family kinds (cubic Hermite,
    /// Catmull-Rom, Kochanek-Bartels, C2 spline); `None` for the others.
    ///
    /// # Errors
    /// As [`check`](Self::check).
    pub fn hermite(&self) -> Result<Option<HermiteSpline>, CurveError> {
        self.check_counts()?;
        Ok(Some(match self {
            CurveKind::CubicHermite { points, tangents } => HermiteSpline::new(
                (0..points.len()).map(|i| i as f64).collect(),
                points.clone(),
                tangents.clone(),
            )?,
            CurveKind::CatmullRom {
                points,
                parameterization,
                closed,
            } => {
                let keys = vec![Tbc::default(); points.len()];
                if *closed {
                    closed_kb(points, &keys, closed_parameters(*parameterization, points)?)?
                } else {
                    HermiteSpline::kochanek_bartels(
                        parameterization.parameters(points)?,
                        points.clone(),
                        &keys,
                    )?
                }
            }
            CurveKind::KochanekBartels {
                points,
                keys,
                closed,
            } => {
                let t: Vec<f64> = (0..points.len() + usize::from(*closed))
                    .map(|i| i as f64)
                    .collect();
                if *closed {
                    closed_kb(points, keys, t)?
                } else {
                    HermiteSpline::kochanek_bartels(t, points.clone(), keys)?
                }
            }
            CurveKind::CubicSpline {
                points,
                parameterization,
                ends,
            } => c2_spline(points, *parameterization, *ends)?,
            _ => return Ok(None),
        }))
    }
    /// The parameters (of the NURBS form) at which an interpolating kind
    /// passes through its points, in order; a closed kind also lists the
    /// closing parameter (back at point 0). Empty for the others.
    ///
    /// # Errors
    /// As [`check`](Self::check).
    pub fn key_parameters(&self) -> Result<Vec<f64>, CurveError> {
        if let Some(h) = self.hermite()? {
            return Ok(h.params);
        }
        Ok(match self {
            CurveKind::Lagrange {
                points,
                parameterization,
            } => parameterization.parameters(points)?,
            CurveKind::QuinticHermite { points, .. } => {
                (0..points.len()).map(|i| i as f64).collect()
            }
            _ => Vec::new(),
        })
    }
    /// The polygon a Chaikin or fractal kind draws at its level (degree-1
    /// NURBS form's points); `None` for other kinds.
    pub fn level_polygon(&self) -> Option<Vec<DVec3>> {
        match self {
            CurveKind::Chaikin {
                points,
                level,
                closed,
            } => {
                let mut p = chaikin(points, *level, *closed);
                if *closed {
                    p.push(p[0]);
                }
                Some(p)
            }
            CurveKind::Fractal {
                rule,
                points,
                level,
                closed,
                normal,
            } => {
                let n = normal.normalize();
                let mut poly = points.clone();
                if *closed {
                    poly.push(points[0]);
                }
                let generator = rule.generator();
                for _ in 0..*level {
                    let mut next = vec![poly[0]];
                    for w in poly.windows(2) {
                        let d = w[1] - w[0];
                        let side = n.cross(d);
                        next.extend(generator[1..].iter().map(|&(u, v)| w[0] + u * d + v * side));
                    }
                    poly = next;
                }
                Some(poly)
            }
            _ => None,
        }
    }
    /// The NURBS form (see the module documentation for where it is exact).
    /// O(n) for the piecewise kinds, O(n³) for exact Lagrange, O(4^level)
    /// for Koch.
    ///
    /// # Errors
    /// As [`check`](Self::check).
    pub fn to_nurbs(&self) -> Result<NurbsForm, CurveError> {
        self.check_counts()?;
        if let Some(h) = self.hermite()? {
            return Ok(NurbsForm {
                curve: hermite_to_nurbs(&h)?,
                tolerance: None,
            });
        }
        if let Some(poly) = self.level_polygon() {
            return Ok(NurbsForm {
                curve: polyline(poly)?,
                tolerance: None,
            });
        }
        let exact = |curve| {
            Ok(NurbsForm {
                curve,
                tolerance: None,
            })
        };
        match self {
            CurveKind::Nurbs(c) => exact(c.clone()),
            CurveKind::QuinticHermite {
                points,
                tangents: v,
                accelerations: a,
            } => {
                let mut cp = vec![points[0]];
                let mut knots = vec![0.0; 6];
                let segs = points.len() - 1;
                for i in 0..segs {
                    let (p0, p1) = (points[i], points[i + 1]);
                    cp.extend([
                        p0 + v[i] / 5.0,
                        p0 + 2.0 * v[i] / 5.0 + a[i] / 20.0,
                        p1 - 2.0 * v[i + 1] / 5.0 + a[i + 1] / 20.0,
                        p1 - v[i + 1] / 5.0,
                        p1,
                    ]);
                    let reps = if i + 1 == segs { 6 } else { 5 };
                    knots.extend(std::iter::repeat_n((i + 1) as f64, reps));
                }
                let w = vec![1.0; cp.len()];
                exact(NurbsCurve::new(5, knots, cp, w)?)
            }
            CurveKind::PolyBezier { points, closed, .. } => {
                let mut cp = points.clone();
                if *closed {
                    cp.push(points[0]);
                }
                let segs = (cp.len() - 1) / 3;
                let mut knots = vec![0.0; 4];
                for i in 1..=segs {
                    let reps = if i == segs { 4 } else { 3 };
                    knots.extend(std::iter::repeat_n(i as f64, reps));
                }
                let w = vec![1.0; cp.len()];
                exact(NurbsCurve::new(3, knots, cp, w)?)
            }
            CurveKind::Lagrange {
                points,
                parameterization,
            } => {
                let t = parameterization.parameters(points)?;
                let n = points.len();
                let (t0, t1) = (t[0], t[n - 1]);
                if n <= LAGRANGE_EXACT_POINTS {
                    let deg = n - 1;
                    let m = t
                        .iter()
                        .map(|&ti| {
                            let s = (ti - t0) / (t1 - t0);
                            (0..n).map(|j| bernstein(deg, j, s)).collect()
                        })
                        .collect();
                    let cp = solve_dense(m, points.clone())?;
                    let mut knots = vec![t0; n];
                    knots.extend(vec![t1; n]);
                    return exact(NurbsCurve::new(deg, knots, cp, vec![1.0; n])?);
                }
                // Dense samples through the (stable, barycentric) polynomial,
                // interpolated by a C2 cubic spline; the error is the largest
                // over every interval between two samples, each searched
                // ([`interval_max`]).
                let per = 32;
                let m = per * (n - 1);
                let ts: Vec<f64> = (0..=m)
                    .map(|i| t0 + (t1 - t0) * i as f64 / m as f64)
                    .collect();
                let ps: Vec<DVec3> = ts.iter().map(|&x| lagrange_point(&t, points, x)).collect();
                let h = c2_cubic_spline(ts.clone(), ps)?;
                let curve = hermite_to_nurbs(&h)?;
                let error = |x: f64| (curve.point(x) - lagrange_point(&t, points, x)).length();
                let tolerance = ts
                    .windows(2)
                    .map(|w| interval_max(&error, w[0], w[1]))
                    .fold(0.0, f64::max);
                Ok(NurbsForm {
                    curve,
                    tolerance: Some(tolerance),
                })
            }
            _ => unreachable!("the Hermite family and the level polygons returned above"),
        }
    }
}
