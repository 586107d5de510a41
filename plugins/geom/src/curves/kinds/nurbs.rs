//! A NURBS curve as a curve kind: its own NURBS form, its control points
//! the defining points; knot insertion, clamped re-knotting on delete and
//! extrude, knot-vector reversal and end-to-end joins are exact.

use super::{CurveKind, KindRules, NurbsForm, TangentHandle, remove_indices};
use crate::curves::nurbs::{NurbsCurve, clamped_uniform_knots};
use crate::curves::{Curve, CurveError};
use glam::{DMat4, DVec3};

impl KindRules for NurbsCurve {
    fn name(&self) -> &'static str {
        "NURBS"
    }
    fn points(&self) -> &[DVec3] {
        NurbsCurve::points(self)
    }
    fn points_mut(&mut self) -> Option<&mut Vec<DVec3>> {
        None
    }
    /// A NURBS curve is closed when its ends meet.
    fn is_closed(&self) -> bool {
        let (a, b) = self.domain();
        (self.point(a) - self.point(b)).length() < 1e-12
    }
    fn check_data(&self) -> Result<(), CurveError> {
        Ok(())
    }
    fn nurbs_form(&self) -> Result<NurbsForm, CurveError> {
        Ok(NurbsForm {
            curve: self.clone(),
            tolerance: None,
        })
    }
    fn move_points(
        &mut self,
        moves: &[(usize, DVec3)],
        _handles: &[TangentHandle],
    ) -> Result<(), CurveError> {
        for &(i, p) in moves {
            self.set_point(i, p)?;
        }
        Ok(())
    }
    fn transform(&mut self, m: &DMat4) -> Result<(), CurveError> {
        *self = NurbsCurve::new(
            self.degree(),
            self.knots().to_vec(),
            super::map_points(m, NurbsCurve::points(self)),
            self.weights().to_vec(),
        )?;
        Ok(())
    }
    fn insert_exact(&self, t: f64) -> Option<Result<(CurveKind, usize), CurveError>> {
        Some(self.insert_knot(t).map(|c2| {
            let idx = (0..c2.points().len())
                .find(|&i| NurbsCurve::points(self).get(i) != c2.points().get(i))
                .unwrap_or(0);
            (CurveKind::Nurbs(c2), idx)
        }))
    }
    fn split_exact(&self, t: f64) -> Option<Result<(CurveKind, CurveKind), CurveError>> {
        Some(NurbsCurve::split(self, t).map(|(a, b)| (CurveKind::Nurbs(a), CurveKind::Nurbs(b))))
    }
    fn delete(&mut self, gone: &[usize]) -> Result<(), CurveError> {
        if !self.is_clamped() {
            return Err(CurveError::NotForKind {
                operation: "deleting points (clamp it first)",
                kind: "periodic NURBS",
            });
        }
        let points = remove_indices(NurbsCurve::points(self), gone);
        let weights = remove_indices(self.weights(), gone);
        if points.len() < 2 {
            return Err(CurveError::KindTooFewPoints {
                kind: "NURBS",
                needed: 2,
                got: points.len(),
            });
        }
        let degree = self.degree().min(points.len() - 1);
        let (a, b) = self.domain();
        let knots = clamped_uniform_knots(degree, points.len())
            .into_iter()
            .map(|k| a + (b - a) * k)
            .collect();
        *self = NurbsCurve::new(degree, knots, points, weights)?;
        Ok(())
    }
    fn push_end(&mut self, to: DVec3) -> Result<(), CurveError> {
        if !self.is_clamped() {
            return Err(CurveError::NotForKind {
                operation: "extruding (clamp it first)",
                kind: "periodic NURBS",
            });
        }
        let mut points = NurbsCurve::points(self).to_vec();
        let mut weights = self.weights().to_vec();
        points.push(to);
        weights.push(1.0);
        let (a, b) = self.domain();
        let knots = clamped_uniform_knots(self.degree(), points.len())
            .into_iter()
            .map(|k| a + (b - a) * k)
            .collect();
        *self = NurbsCurve::new(self.degree(), knots, points, weights)?;
        Ok(())
    }
    fn reversed(&self) -> Result<Self, CurveError> {
        let (k, n) = (self.knots(), self.knots().len());
        let (a, b) = (k[0], k[n - 1]);
        let knots = (0..n).map(|i| a + b - k[n - 1 - i]).collect();
        let points = NurbsCurve::points(self).iter().rev().copied().collect();
        let weights = self.weights().iter().rev().copied().collect();
        NurbsCurve::new(self.degree(), knots, points, weights)
    }
    fn append(&mut self, other: &Self, _skip: usize) -> Result<(), CurveError> {
        *self = join_nurbs(self, other)?;
        Ok(())
    }
}

/// Two clamped NURBS of one degree end to end: where `a` ends at `b`'s
/// start the knot vectors are concatenated (multiplicity `degree` at the
/// junction, `b`'s weights scaled to match), else a straight Bézier piece
/// bridges them. Exact.
fn join_nurbs(a: &NurbsCurve, b: &NurbsCurve) -> Result<NurbsCurve, CurveError> {
    let p = a.degree();
    if b.degree() != p || !a.is_clamped() || !b.is_clamped() {
        return Err(CurveError::NotForKind {
            operation: "joining NURBS of different degrees or unclamped (elevate or clamp first)",
            kind: "NURBS",
        });
    }
    let (last, first) = (a.points()[a.points().len() - 1], b.points()[0]);
    let mut b = b.clone();
    if (last - first).length() > 1e-9 {
        let bridge: Vec<DVec3> = (0..=p)
            .map(|i| last.lerp(first, i as f64 / p as f64))
            .collect();
        let mut knots = vec![0.0; p + 1];
        knots.extend(vec![1.0; p + 1]);
        let line = NurbsCurve::new(p, knots, bridge, vec![1.0; p + 1])?;
        b = join_nurbs(&line, &b)?;
    }
    let wa = a.weights()[a.weights().len() - 1];
    let scale = wa / b.weights()[0];
    let mut knots = a.knots()[..a.knots().len() - 1].to_vec();
    let (a_end, b_start) = (knots[knots.len() - 1], b.knots()[0]);
    knots.extend(b.knots()[p + 1..].iter().map(|k| k - b_start + a_end));
    let mut points = a.points().to_vec();
    points.extend_from_slice(&b.points()[1..]);
    let mut weights = a.weights().to_vec();
    weights.extend(b.weights()[1..].iter().map(|w| w * scale));
    NurbsCurve::new(p, knots, points, weights)
}
