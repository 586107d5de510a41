//! The Lagrange curve: the polynomial of degree n − 1 through n points
//! (seed 000, Lagrange/Vandermonde), exact as one Bézier up to
//! [`LAGRANGE_EXACT_POINTS`] points, an interpolating cubic with a
//! measured deviation above.

use super::{KindRules, LAGRANGE_EXACT_POINTS, NurbsForm, Parameterization, hermite_to_nurbs};
use crate::curves::bezier::bernstein;
use crate::curves::interpolating::{c2_cubic_spline, solve_dense};
use crate::curves::nurbs::NurbsCurve;
use crate::curves::{Curve, CurveError};
use glam::DVec3;

/// The polynomial of degree n − 1 through n points.
#[derive(Clone, Debug, PartialEq)]
pub struct Lagrange {
    /// The interpolated points (at least 2).
    pub points: Vec<DVec3>,
    /// How their parameters are chosen.
    pub parameterization: Parameterization,
}

impl KindRules for Lagrange {
    fn name(&self) -> &'static str {
        "Lagrange"
    }
    fn points(&self) -> &[DVec3] {
        &self.points
    }
    fn points_mut(&mut self) -> Option<&mut Vec<DVec3>> {
        Some(&mut self.points)
    }
    fn interpolates(&self) -> bool {
        true
    }
    fn check_data(&self) -> Result<(), CurveError> {
        super::too_few(self.name(), 2, self.points.len())
    }
    fn own_key_parameters(&self) -> Result<Vec<f64>, CurveError> {
        self.parameterization.parameters(&self.points)
    }
    fn nurbs_form(&self) -> Result<NurbsForm, CurveError> {
        let points = &self.points;
        let t = self.parameterization.parameters(points)?;
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
            return Ok(NurbsForm {
                curve: NurbsCurve::new(deg, knots, cp, vec![1.0; n])?,
                tolerance: None,
            });
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
    fn reversed(&self) -> Result<Self, CurveError> {
        Ok(Lagrange {
            points: super::rev(&self.points, false),
            parameterization: self.parameterization,
        })
    }
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
