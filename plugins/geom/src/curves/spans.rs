//! Arc length of a span of a curve (seed 001, "ívhossz"): between two
//! parameters, and between the points of a selection of a curve kind's
//! defining points. The length is the existing adaptive Gauss-Legendre
//! quadrature ([`arc_length`]) run on each knot span separately, so that
//! the integrand is smooth on every interval it sees (a NURBS curve's
//! speed may kink at its knots).

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::analysis::{arc_length, closest_parameter};
use super::nurbs::NurbsCurve;
use super::{Curve, CurveError, CurveKind, Fractal};

/// The arc length of `curve` between parameters `a` and `b` (in either
/// order): adaptive 5-point Gauss-Legendre on each knot span inside, to a
/// relative tolerance of about 1e-12 (the exact circle's length is 2πr to
/// 1e-12, tested). Read-only. O(spans × quadrature steps).
///
/// # Errors
/// [`CurveError::OutsideDomain`] for a parameter that is not finite or
/// lies outside the domain.
pub fn span_length(curve: &NurbsCurve, a: f64, b: f64) -> Result<f64, CurveError> {
    let (start, end) = curve.domain();
    for t in [a, b] {
        if !(t >= start && t <= end) {
            return Err(CurveError::OutsideDomain {
                value: t,
                start,
                end,
            });
        }
    }
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    let mut cuts = vec![lo];
    cuts.extend(
        curve
            .interior_knots()
            .into_iter()
            .map(|k| k.0)
            .filter(|&k| k > lo && k < hi),
    );
    cuts.push(hi);
    Ok(cuts.windows(2).map(|w| arc_length(curve, w[0], w[1])).sum())
}

/// The length of the whole curve ([`span_length`] over its domain).
pub fn curve_length(curve: &NurbsCurve) -> f64 {
    let (a, b) = curve.domain();
    span_length(curve, a, b).unwrap_or(0.0)
}

/// The span of the curve a selection of defining points covers.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SelectionSpan {
    /// The parameter of the first selected point along the curve.
    pub start: f64,
    /// The parameter of the last.
    pub end: f64,
    /// The curve's arc length from `start` to `end`.
    pub length: f64,
    /// The curve's points there (on the curve, in its own space).
    pub ends: [DVec3; 2],
}

impl CurveKind {
    /// The parameter of the NURBS form `form` (this kind's,
    /// [`to_nurbs`](Self::to_nurbs)) that stands for each defining point
    /// ([`points`](Self::points)), in order: where an interpolating kind
    /// passes through it ([`key_parameters`](Self::key_parameters)), a
    /// fractal initiator's vertex, the Greville abscissa of a NURBS or
    /// poly-Bézier control point (a poly-Bézier anchor's joint), and for a
    /// Chaikin polygon's corner the parameter of the curve's point nearest
    /// to it. O(n) (Chaikin: n closest-point searches).
    ///
    /// # Errors
    /// As [`check`](Self::check).
    pub fn point_parameters(&self, form: &NurbsCurve) -> Result<Vec<f64>, CurveError> {
        let n = self.points().len();
        if self.interpolates() {
            let mut keys = self.key_parameters()?;
            keys.truncate(n);
            return Ok(keys);
        }
        Ok(match self {
            CurveKind::Nurbs(_) | CurveKind::PolyBezier(_) => {
                let mut g = form.greville();
                g.truncate(n);
                g
            }
            CurveKind::Fractal(Fractal { rule, level, .. }) => {
                let (a, b) = form.domain();
                let per = rule.pieces().pow(*level) as f64;
                let segments = (form.points().len() - 1) as f64;
                (0..n)
                    .map(|i| a + (b - a) * (i as f64 * per / segments))
                    .collect()
            }
            _ => self
                .points()
                .iter()
                .map(|&p| closest_parameter(form, p))
                .collect(),
        })
    }

    /// The arc length of the span between the first and the last of the
    /// selected defining points along the curve (by
    /// [`point_parameters`](Self::point_parameters); on a closed curve the
    /// span that does not pass the start). One point gives a span of
    /// length 0. Read-only. O(n + quadrature).
    ///
    /// # Errors
    /// [`CurveError::NoSuchPoint`] for an index past the end,
    /// [`CurveError::KindTooFewPoints`] for an empty selection, or what
    /// [`check`](Self::check) finds.
    pub fn selection_span(
        &self,
        form: &NurbsCurve,
        selected: &[usize],
    ) -> Result<SelectionSpan, CurveError> {
        let count = self.points().len();
        if let Some(&index) = selected.iter().find(|&&i| i >= count) {
            return Err(CurveError::NoSuchPoint { index, count });
        }
        if selected.is_empty() {
            return Err(CurveError::KindTooFewPoints {
                kind: "a measured span",
                needed: 1,
                got: 0,
            });
        }
        let params = self.point_parameters(form)?;
        let ts = selected.iter().map(|&i| params[i]);
        let start = ts.clone().fold(f64::INFINITY, f64::min);
        let end = ts.fold(f64::NEG_INFINITY, f64::max);
        Ok(SelectionSpan {
            start,
            end,
            length: span_length(form, start, end)?,
            ends: [form.point(start), form.point(end)],
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_exact_circle_is_two_pi_r_long() {
        for r in [0.5, 1.0, 3.0, 1000.0] {
            let c = NurbsCurve::circle(DVec3::new(1.0, 2.0, 3.0), r);
            let l = curve_length(&c);
            let exact = std::f64::consts::TAU * r;
            assert!(
                (l - exact).abs() <= 1e-12 * exact,
                "r = {r}: {l} vs {exact}"
            );
            // A quarter: one knot span.
            let q = span_length(&c, 0.25, 0.5).unwrap();
            assert!((q - exact / 4.0).abs() <= 1e-12 * exact);
            // Either order, and across knots.
            let a = span_length(&c, 0.9, 0.1).unwrap();
            let b = span_length(&c, 0.1, 0.9).unwrap();
            assert_eq!(a, b);
        }
        let c = NurbsCurve::circle(DVec3::ZERO, 1.0);
        assert_eq!(
            span_length(&c, -0.1, 0.5),
            Err(CurveError::OutsideDomain {
                value: -0.1,
                start: 0.0,
                end: 1.0
            })
        );
    }
}
