//! Cubic Hermite segments through points with given derivatives, at
//! parameters 0, 1, 2, … (seed 000); the tangents are defining data a user
//! drags as handles.

use super::{KindRules, NurbsForm, TangentHandle, hermite_nurbs, map_points, map_vectors};
use crate::curves::interpolating::HermiteSpline;
use crate::curves::{CurveError, check_points};
use glam::{DMat4, DVec3};

/// Cubic Hermite segments through points with given derivatives, at
/// parameters 0, 1, 2, …
#[derive(Clone, Debug, PartialEq)]
pub struct CubicHermite {
    /// The points (at least 2).
    pub points: Vec<DVec3>,
    /// dp/dt at each point.
    pub tangents: Vec<DVec3>,
}

impl CubicHermite {
    /// The Hermite spline of the points and tangents.
    fn spline(&self) -> Result<HermiteSpline, CurveError> {
        HermiteSpline::new(
            (0..self.points.len()).map(|i| i as f64).collect(),
            self.points.clone(),
            self.tangents.clone(),
        )
    }
}

/// Sets the defining points moved by `moves` (indices below the point
/// count), then for each moved handle (indices after the points, in the
/// order of `handles`) its key's tangent, relative to the key's new
/// position: m = (end − p)·d/h (uniform keys, h = 1), the incoming side
/// negated. `degree` is 3 for cubic and 5 for quintic Hermite handles.
pub(super) fn move_with_handles(
    points: &mut [DVec3],
    tangents: &mut [DVec3],
    moves: &[(usize, DVec3)],
    handles: &[TangentHandle],
    degree: f64,
) {
    let count = points.len();
    for &(i, p) in moves.iter().filter(|m| m.0 < count) {
        points[i] = p;
    }
    for &(i, end) in moves.iter().filter(|m| m.0 >= count) {
        let h = handles[i - count];
        let m = (end - points[h.point]) * degree;
        tangents[h.point] = if h.incoming { -m } else { m };
    }
}

/// Cuts a per-point list at point `k` for a split: the left half keeps up
/// to and with `k`, the right half from `k` on.
pub(super) fn keep<T>(v: &mut Vec<T>, k: usize, left: bool) {
    if left {
        v.truncate(k + 1)
    } else {
        v.drain(..k);
    }
}

impl KindRules for CubicHermite {
    fn name(&self) -> &'static str {
        "cubic Hermite"
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
    fn handles_editable(&self) -> bool {
        true
    }
    fn check_data(&self) -> Result<(), CurveError> {
        let (points, tangents) = (&self.points, &self.tangents);
        super::too_few(self.name(), 2, points.len())?;
        super::count(points.len(), "tangents", tangents.len())?;
        check_points(tangents).map_err(|_| CurveError::NotFiniteVector { what: "a tangent" })
    }
    fn hermite_form(&self) -> Result<Option<HermiteSpline>, CurveError> {
        self.spline().map(Some)
    }
    fn nurbs_form(&self) -> Result<NurbsForm, CurveError> {
        hermite_nurbs(&self.spline()?)
    }
    fn move_points(
        &mut self,
        moves: &[(usize, DVec3)],
        handles: &[TangentHandle],
    ) -> Result<(), CurveError> {
        move_with_handles(&mut self.points, &mut self.tangents, moves, handles, 3.0);
        Ok(())
    }
    fn transform(&mut self, m: &DMat4) -> Result<(), CurveError> {
        self.points = map_points(m, &self.points);
        self.tangents = map_vectors(m, &self.tangents);
        Ok(())
    }
    fn insert_at(&mut self, _span: (usize, f64), at: usize, [p, d1, _]: [DVec3; 3]) -> usize {
        self.points.insert(at, p);
        self.tangents.insert(at, d1 * 0.5);
        at
    }
    fn delete(&mut self, gone: &[usize]) -> Result<(), CurveError> {
        self.points = super::remove_indices(&self.points, gone);
        self.tangents = super::remove_indices(&self.tangents, gone);
        Ok(())
    }
    fn push_end(&mut self, to: DVec3) -> Result<(), CurveError> {
        self.tangents.push(to - self.points[self.points.len() - 1]);
        self.points.push(to);
        Ok(())
    }
    fn reversed(&self) -> Result<Self, CurveError> {
        Ok(CubicHermite {
            points: super::rev(&self.points, false),
            tangents: super::neg(&self.tangents),
        })
    }
    fn keep(&mut self, k: usize, left: bool) {
        keep(&mut self.points, k, left);
        keep(&mut self.tangents, k, left);
    }
    fn append(&mut self, other: &Self, skip: usize) -> Result<(), CurveError> {
        self.points.extend_from_slice(&other.points[skip..]);
        self.tangents.extend_from_slice(&other.tangents[skip..]);
        Ok(())
    }
}
