//! The interpolating C2 cubic spline (seed 004): the tangents solve a
//! tridiagonal system (Thomas), a cyclic one for a closed loop
//! (Sherman-Morrison); natural, clamped or closed ends.

use super::{
    KindRules, NurbsForm, Parameterization, SplineEnds, closed_parameters, hermite_nurbs,
    map_points,
};
use crate::curves::interpolating::{HermiteSpline, c2_cubic_spline};
use crate::curves::{CurveError, check_points};
use glam::{DMat4, DVec3};

/// The interpolating C2 cubic spline (seed 004).
#[derive(Clone, Debug, PartialEq)]
pub struct CubicSpline {
    /// The points (at least 2; 3 closed).
    pub points: Vec<DVec3>,
    /// How their parameters are chosen.
    pub parameterization: Parameterization,
    /// Natural, clamped or closed.
    pub ends: SplineEnds,
}

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

impl KindRules for CubicSpline {
    fn name(&self) -> &'static str {
        "C2 cubic spline"
    }
    fn points(&self) -> &[DVec3] {
        &self.points
    }
    fn points_mut(&mut self) -> Option<&mut Vec<DVec3>> {
        Some(&mut self.points)
    }
    fn is_closed(&self) -> bool {
        self.ends == SplineEnds::Closed
    }
    fn interpolates(&self) -> bool {
        true
    }
    fn check_data(&self) -> Result<(), CurveError> {
        super::too_few(
            self.name(),
            super::least(self.is_closed()),
            self.points.len(),
        )
    }
    fn hermite_form(&self) -> Result<Option<HermiteSpline>, CurveError> {
        c2_spline(&self.points, self.parameterization, self.ends).map(Some)
    }
    fn nurbs_form(&self) -> Result<NurbsForm, CurveError> {
        hermite_nurbs(&c2_spline(&self.points, self.parameterization, self.ends)?)
    }
    /// Clamped end derivatives map by the linear part.
    fn transform(&mut self, m: &DMat4) -> Result<(), CurveError> {
        self.points = map_points(m, &self.points);
        if let SplineEnds::Clamped { start, end } = &mut self.ends {
            *start = m.transform_vector3(*start);
            *end = m.transform_vector3(*end);
        }
        Ok(())
    }
    /// Clamped end derivatives swap and negate.
    fn reversed(&self) -> Result<Self, CurveError> {
        Ok(CubicSpline {
            points: super::rev(&self.points, self.is_closed()),
            parameterization: self.parameterization,
            ends: match self.ends {
                SplineEnds::Clamped { start, end } => SplineEnds::Clamped {
                    start: -end,
                    end: -start,
                },
                e => e,
            },
        })
    }
    /// Switches between natural and closed ends.
    fn set_closed(&mut self, closed: bool) -> Result<(), CurveError> {
        self.ends = if closed {
            SplineEnds::Closed
        } else {
            SplineEnds::Natural
        };
        Ok(())
    }
}
