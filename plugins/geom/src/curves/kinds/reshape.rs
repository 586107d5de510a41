//! Whole-curve edits of a curve kind: reversing, opening and closing,
//! splitting in two and joining two curves. What every kind shares is
//! here; the edit itself is the kind's ([`KindRules`]).

use super::{CurveKind, KindRules};
use crate::curves::CurveError;
use glam::DVec3;

/// A closed loop's list traced back from its first entry, which stays
/// first.
pub(super) fn reverse_closed<T: Clone>(v: &[T]) -> Vec<T> {
    let mut r = vec![v[0].clone()];
    r.extend(v[1..].iter().rev().cloned());
    r
}

/// Points traced back (a closed loop keeps point 0 first).
pub(super) fn rev(v: &[DVec3], closed: bool) -> Vec<DVec3> {
    if closed {
        reverse_closed(v)
    } else {
        v.iter().rev().copied().collect()
    }
}

/// Tangents traced back: reversed and negated.
pub(super) fn neg(v: &[DVec3]) -> Vec<DVec3> {
    v.iter().rev().map(|x| -*x).collect()
}

impl CurveKind {
    pub(super) fn reversed_if(self, yes: bool) -> Result<CurveKind, CurveError> {
        if yes { self.reverse() } else { Ok(self) }
    }
    /// The same curve traced the other way (its own inverse). Closed kinds
    /// keep point 0 first; Kochanek-Bartels keys negate their bias; a
    /// clamped C2 spline swaps and negates its end tangents; a fractal
    /// Koch curve negates its normal so the bumps stay where they are (the
    /// point-symmetric quadratic Koch keeps it).
    ///
    /// # Errors
    /// None in practice (a NURBS rebuilt from valid data).
    pub fn reverse(&self) -> Result<CurveKind, CurveError> {
        each_kind!(self, k => KindRules::reversed(k).map(CurveKind::from))
    }
    /// Opens or closes the curve (Blender's Alt+C). Catmull-Rom,
    /// Kochanek-Bartels, Chaikin and fractals toggle their flag; the C2
    /// spline switches between natural and closed ends; a poly-Bézier
    /// closes with a straight segment back to its start (or by merging
    /// its ends where they meet) and opens at point 0 keeping its shape.
    /// Inverse: the other call (a poly-Bézier closed with an added segment
    /// keeps it when opened).
    ///
    /// # Errors
    /// Lagrange, Hermite and NURBS curves ("closing is not possible on a
    /// Lagrange curve"); too few points for a loop.
    pub fn set_closed(&self, closed: bool) -> Result<CurveKind, CurveError> {
        if self.is_closed() == closed {
            return Ok(self.clone());
        }
        let mut out = self.clone();
        each_kind!(&mut out, k => KindRules::set_closed(k, closed))?;
        out.check()?;
        Ok(out)
    }
    /// Splits an open curve (or any NURBS) at parameter `t` into two of the same kind
    /// that meet there: a point is inserted as by
    /// [`insert_point`](Self::insert_point) and the curve cut at it (exact
    /// for NURBS and poly-Bézier). Inverse: [`join`](Self::join).
    ///
    /// # Errors
    /// A closed curve (open it first), `t` outside the open domain, a half
    /// with too few points.
    pub fn split(&self, t: f64) -> Result<(CurveKind, CurveKind), CurveError> {
        // A NURBS curve whose ends meet (a circle) splits like any other.
        if let Some(done) = each_kind!(self, k => KindRules::split_exact(k, t)) {
            return done;
        }
        if self.is_closed() {
            return Err(CurveError::NotForKind {
                operation: "splitting a closed curve (open it first)",
                kind: self.name(),
            });
        }
        // At a point already on the curve (an interpolated point, a
        // poly-Bézier anchor) the curve splits there; elsewhere a point is
        // inserted first.
        let last = self.points().len() - 1;
        let (with, k) = match self.point_at_parameter(t) {
            Some(k) if k > 0 && k < last => (self.clone(), k),
            _ => self.insert_point(t)?,
        };
        let (mut a, mut b) = (with.clone(), with);
        for (c, left) in [(&mut a, true), (&mut b, false)] {
            each_kind!(&mut *c, half => KindRules::keep(half, k, left));
            c.check()?;
        }
        Ok((a, b))
    }
    /// This curve followed by `other`, which must be open and of the same
    /// kind (a NURBS of the same degree, clamped). Where the end of this
    /// meets the start of `other` the shared point is kept once; elsewhere
    /// a straight piece bridges the gap (poly-Bézier, NURBS) or the curve
    /// simply continues through the other's points (interpolating kinds).
    /// Exact for NURBS and poly-Bézier. The settings (parameterisation,
    /// level, rule) are this curve's.
    ///
    /// # Errors
    /// [`CurveError::KindMismatch`], a closed curve, NURBS of different
    /// degrees or unclamped.
    pub fn join(&self, other: &CurveKind) -> Result<CurveKind, CurveError> {
        let mismatch = || CurveError::KindMismatch {
            first: self.name(),
            second: other.name(),
        };
        if std::mem::discriminant(self) != std::mem::discriminant(other) {
            return Err(mismatch());
        }
        for c in [self, other] {
            if c.is_closed() {
                return Err(CurveError::NotForKind {
                    operation: "joining a closed curve",
                    kind: c.name(),
                });
            }
        }
        let meet = |a: &[DVec3], b: &[DVec3]| (a[a.len() - 1] - b[0]).length() <= 1e-9;
        let skip = usize::from(meet(self.points(), other.points()));
        let mut out = self.clone();
        each_kind!(&mut out, other, (a, b) => KindRules::append(a, b, skip), _ => Err(mismatch()))?;
        out.check()?;
        Ok(out)
    }
}
