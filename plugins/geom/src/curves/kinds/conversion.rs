//! A curve kind's NURBS form ([`CurveKind::to_nurbs`]) and what is computed
//! on the way (the Hermite form, the key parameters, the level polygon),
//! each handed to the kind; with the constructions the kinds share: a
//! piecewise cubic Hermite curve's exact NURBS form, a polyline's, and the
//! parameters of a closed loop.

use super::{CurveKind, KindRules, NurbsForm, Parameterization};
use crate::curves::CurveError;
use crate::curves::interpolating::HermiteSpline;
use crate::curves::nurbs::NurbsCurve;
use glam::DVec3;

/// Parameters of a closed loop: the points and the first again.
pub(super) fn closed_parameters(
    p: Parameterization,
    points: &[DVec3],
) -> Result<Vec<f64>, CurveError> {
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
pub(super) fn hermite_to_nurbs(h: &HermiteSpline) -> Result<NurbsCurve, CurveError> {
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

/// [`hermite_to_nurbs`] as an exact NURBS form: the Hermite family's.
pub(super) fn hermite_nurbs(h: &HermiteSpline) -> Result<NurbsForm, CurveError> {
    Ok(NurbsForm {
        curve: hermite_to_nurbs(h)?,
        tolerance: None,
    })
}

/// A polyline as an exact degree-1 NURBS form, uniform parameters on
/// [0, 1]: the level polygons'.
pub(super) fn polyline(points: Vec<DVec3>) -> Result<NurbsForm, CurveError> {
    Ok(NurbsForm {
        curve: NurbsCurve::clamped(1, points)?,
        tolerance: None,
    })
}

impl CurveKind {
    /// The Hermite form of the Hermite-family kinds (cubic Hermite,
    /// Catmull-Rom, Kochanek-Bartels, C2 spline); `None` for the others.
    ///
    /// # Errors
    /// As [`check`](Self::check).
    pub fn hermite(&self) -> Result<Option<HermiteSpline>, CurveError> {
        self.check_counts()?;
        each_kind!(self, k => KindRules::hermite_form(k))
    }
    /// The parameters (of the NURBS form) at which an interpolating kind
    /// passes through its points, in order; a closed kind also lists the
    /// closing parameter (back at point 0). Empty for the others.
    ///
    /// # Errors
    /// As [`check`](Self::check).
    pub fn key_parameters(&self) -> Result<Vec<f64>, CurveError> {
        each_kind!(self, k => KindRules::key_parameters(k))
    }
    /// The polygon a Chaikin or fractal kind draws at its level (degree-1
    /// NURBS form's points); `None` for other kinds.
    pub fn level_polygon(&self) -> Option<Vec<DVec3>> {
        each_kind!(self, k => KindRules::level_polygon(k))
    }
    /// The NURBS form (see the module documentation for where it is exact).
    /// O(n) for the piecewise kinds, O(n³) for exact Lagrange, O(4^level)
    /// for Koch.
    ///
    /// # Errors
    /// As [`check`](Self::check).
    pub fn to_nurbs(&self) -> Result<NurbsForm, CurveError> {
        self.check_counts()?;
        each_kind!(self, k => KindRules::nurbs_form(k))
    }
}
