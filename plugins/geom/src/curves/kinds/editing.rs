//! Point edits of a curve kind: moving, transforming, joins between
//! poly-Bézier segments, inserting, deleting and extruding points. What
//! every kind shares (indices, finite positions, the check of the result)
//! is here; the edit itself is the kind's ([`KindRules`]).

use super::{CurveEnd, CurveKind, Join, KindRules};
use crate::curves::{Curve, CurveError};
use glam::{DMat4, DVec3};

impl CurveKind {
    /// Moves defining points, `(index, position)`. A poly-Bézier keeps its
    /// joins: an anchor moved without its handles carries them along; a
    /// handle moved without its partner turns the partner to stay C1 (a
    /// mirror) or G1 (collinear, its length kept).
    ///
    /// # Errors
    /// [`CurveError::NoSuchPoint`], a non-finite position, or what
    /// [`check`](Self::check) finds in the result.
    pub fn set_points(&self, moves: &[(usize, DVec3)]) -> Result<CurveKind, CurveError> {
        let points = self.points().len();
        let handles = if self.handles_editable() {
            self.tangent_handles()
        } else {
            Vec::new()
        };
        let count = points + handles.len();
        for &(index, p) in moves {
            if index >= count {
                return Err(CurveError::NoSuchPoint { index, count });
            }
            if !p.is_finite() {
                return Err(CurveError::NotFinite {
                    what: "control point",
                    index,
                });
            }
        }
        let mut out = self.clone();
        each_kind!(&mut out, k => KindRules::move_points(k, moves, &handles))?;
        out.check()?;
        Ok(out)
    }
    /// The curve with its points mapped by the affine map `m`; tangents,
    /// accelerations and clamped end derivatives by its linear part, a
    /// fractal's normal by the inverse transpose. Exact for every kind
    /// whose construction is affine-invariant (all but chord-length and
    /// centripetal parameters under a non-uniform scale).
    ///
    /// # Errors
    /// A map that makes a value non-finite.
    pub fn transformed(&self, m: &DMat4) -> Result<CurveKind, CurveError> {
        let mut out = self.clone();
        each_kind!(&mut out, k => KindRules::transform(k, m))?;
        out.check()?;
        Ok(out)
    }
    /// Sets the join of poly-Bézier joint `joint` and makes it hold, turning
    /// the outgoing handle (the incoming one stays).
    ///
    /// # Errors
    /// Not a poly-Bézier, or no such joint.
    pub fn set_join(&self, joint: usize, join: Join) -> Result<CurveKind, CurveError> {
        let mut out = self.clone();
        let CurveKind::PolyBezier(chain) = &mut out else {
            return Err(CurveError::NotForKind {
                operation: "setting a joint's continuity",
                kind: self.name(),
            });
        };
        chain.set_join(joint, join)?;
        Ok(out)
    }
    /// Which defining point a parameter of the NURBS form falls after, and
    /// the fraction of the way to the next one; for poly-Béziers the
    /// segment. Used by insertion and splitting.
    fn span_at(&self, t: f64) -> Result<(usize, f64), CurveError> {
        let form = self.to_nurbs()?;
        let (start, end) = form.curve.domain();
        if !(t > start && t < end) {
            return Err(CurveError::OutsideDomain {
                value: t,
                start,
                end,
            });
        }
        let keys = self.key_parameters()?;
        if !keys.is_empty() {
            let i = keys.partition_point(|&k| k <= t).clamp(1, keys.len() - 1) - 1;
            return Ok((i, (t - keys[i]) / (keys[i + 1] - keys[i])));
        }
        let edges = each_kind!(self, k => KindRules::edges(k));
        let x = (t - start) / (end - start) * edges as f64;
        let i = (x.floor() as usize).min(edges - 1);
        Ok((i, x - i as f64))
    }
    /// Inserts a defining point where the curve is at parameter `t` (of
    /// the NURBS form). Exact for NURBS (a knot) and poly-Bézier (de
    /// Casteljau split, the new joint C1); the interpolating kinds take the
    /// curve's point (Hermite kinds also its derivatives, halved for the
    /// halved span), so the curve still passes there and the others stay;
    /// Chaikin and fractals insert on their polygon. Inverse:
    /// [`delete_points`](Self::delete_points) of the new index.
    ///
    /// Returns the new curve and the new point's index.
    ///
    /// # Errors
    /// `t` outside the open domain; a NURBS knot at full multiplicity.
    pub fn insert_point(&self, t: f64) -> Result<(CurveKind, usize), CurveError> {
        if let Some(done) = each_kind!(self, k => KindRules::insert_exact(k, t)) {
            return done;
        }
        let (i, s) = self.span_at(t)?;
        let form = self.to_nurbs()?.curve;
        let at_curve = form.derivatives(t);
        let mut out = self.clone();
        let at = each_kind!(&mut out, k => KindRules::insert_at(k, (i, s), i + 1, at_curve));
        out.check()?;
        Ok((out, at))
    }
    /// The parameter (of the NURBS form) at which the curve passes through
    /// defining point `index`: an interpolating kind's key parameter, a
    /// poly-Bézier anchor's joint (anchor `3k` at `k`). `None` for points
    /// the curve does not pass through (NURBS control points, handles,
    /// Chaikin and fractal polygons).
    pub fn on_curve_parameter(&self, index: usize) -> Option<f64> {
        each_kind!(self, k => KindRules::on_curve_parameter(k, index))
    }
    /// The defining point the curve passes through at parameter `t`
    /// (within 1e-9 of its [`on_curve_parameter`](Self::on_curve_parameter)),
    /// if there is one.
    pub fn point_at_parameter(&self, t: f64) -> Option<usize> {
        (0..self.points().len()).find(|&i| {
            self.on_curve_parameter(i)
                .is_some_and(|k| (k - t).abs() <= 1e-9 * k.abs().max(1.0))
        })
    }
    /// Deletes defining points. Poly-Bézier: anchors only, each with its
    /// two handles (the neighbouring segments merge into one). NURBS:
    /// clamped curves only; the knots become clamped uniform again and the
    /// degree drops if too few points remain. Interpolating kinds keep
    /// passing through the points that stay.
    ///
    /// # Errors
    /// No such point, a poly-Bézier handle, a periodic NURBS, or too few
    /// points left ("Lagrange needs 2 points or more").
    pub fn delete_points(&self, indices: &[usize]) -> Result<CurveKind, CurveError> {
        let count = self.points().len();
        let mut gone: Vec<usize> = indices.to_vec();
        gone.sort_unstable();
        gone.dedup();
        if let Some(&index) = gone.iter().find(|&&i| i >= count) {
            return Err(CurveError::NoSuchPoint { index, count });
        }
        let mut out = self.clone();
        each_kind!(&mut out, k => KindRules::delete(k, &gone))?;
        out.check()?;
        Ok(out)
    }
    /// Adds a point after the last (or before the first) one, at `to`:
    /// Blender's extrude of a curve end. A poly-Bézier gets a segment whose
    /// first handle continues the end's tangent (a G1 joint); a Hermite end
    /// gets the chord as its tangent; a clamped NURBS gets a control point
    /// (weight 1) and clamped uniform knots. Inverse: delete that point.
    ///
    /// # Errors
    /// A closed curve (no ends), a non-finite position, a periodic NURBS.
    pub fn extrude(&self, end: CurveEnd, to: DVec3) -> Result<CurveKind, CurveError> {
        if !to.is_finite() {
            return Err(CurveError::NotFiniteVector {
                what: "the extruded point",
            });
        }
        if self.is_closed() {
            return Err(CurveError::NotForKind {
                operation: "extruding (a closed curve has no end)",
                kind: self.name(),
            });
        }
        let mut out = self.clone().reversed_if(end == CurveEnd::Start)?;
        each_kind!(&mut out, k => KindRules::push_end(k, to))?;
        let out = out.reversed_if(end == CurveEnd::Start)?;
        out.check()?;
        Ok(out)
    }
}
