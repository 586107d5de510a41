//! Point edits of a curve kind: moving, transforming, joins between
//! poly-Bézier segments, inserting, deleting and extruding points.

use super::{CurveEnd, CurveKind, Join, SplineEnds};
use crate::curves::interpolating::Tbc;
use crate::curves::nurbs::{NurbsCurve, clamped_uniform_knots};
use crate::curves::{Curve, CurveError};
use glam::{DMat4, DVec3};

fn remove_indices<T: Clone>(v: &[T], gone: &[usize]) -> Vec<T> {
    v.iter()
        .enumerate()
        .filter(|(i, _)| !gone.contains(i))
        .map(|(_, x)| x.clone())
        .collect()
}

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
        match &mut out {
            CurveKind::Nurbs(c) => {
                for &(i, p) in moves {
                    c.set_point(i, p)?;
                }
            }
            CurveKind::PolyBezier {
                points,
                joins,
                closed,
            } => {
                let before = points.clone();
                let moved: Vec<usize> = moves.iter().map(|m| m.0).collect();
                for &(i, p) in moves {
                    points[i] = p;
                }
                let n = points.len();
                for (j, &join) in joins.iter().enumerate() {
                    let (hin, a, hout) = joint_indices(j, n, *closed);
                    let (mi, ma, mo) = (
                        moved.contains(&hin),
                        moved.contains(&a),
                        moved.contains(&hout),
                    );
                    if ma {
                        let delta = points[a] - before[a];
                        if !mi {
                            points[hin] += delta;
                        }
                        if !mo {
                            points[hout] += delta;
                        }
                    } else if mi && !mo {
                        enforce_join(points, join, hin, a, hout);
                    } else if mo && !mi {
                        enforce_join(points, join, hout, a, hin);
                    }
                }
                // Auto joints: a dragged handle makes the joint G1 (its
                // partner was aligned above); else the handles follow the
                // anchors.
                for (j, join) in joins.iter_mut().enumerate() {
                    if *join != Join::Auto {
                        continue;
                    }
                    let (hin, a, hout) = joint_indices(j, n, *closed);
                    let handle_dragged =
                        (moved.contains(&hin) || moved.contains(&hout)) && !moved.contains(&a);
                    if handle_dragged {
                        *join = Join::G1;
                    } else {
                        auto_handles(points, hin, a, hout);
                    }
                }
                // The free ends of an open chain carry their one handle.
                if !*closed {
                    for (a, h) in [(0, 1), (n - 1, n - 2)] {
                        if moved.contains(&a) && !moved.contains(&h) {
                            let d = points[a] - before[a];
                            points[h] += d;
                        }
                    }
                }
            }
            other => {
                let pts = other.points_mut().expect("not NURBS");
                for &(i, p) in moves.iter().filter(|m| m.0 < points) {
                    pts[i] = p;
                }
                let keys = pts.clone();
                // A dragged handle sets its key's tangent, relative to
                // the key's new position: m = (end − p)·d/h (uniform keys,
                // h = 1), the incoming side negated.
                let degree = if matches!(other, CurveKind::QuinticHermite { .. }) {
                    5.0
                } else {
                    3.0
                };
                for &(i, end) in moves.iter().filter(|m| m.0 >= points) {
                    let h = handles[i - points];
                    let m = (end - keys[h.point]) * degree;
                    let m = if h.incoming { -m } else { m };
                    match other {
                        CurveKind::CubicHermite { tangents, .. }
                        | CurveKind::QuinticHermite { tangents, .. } => tangents[h.point] = m,
                        _ => unreachable!("only Hermite handles are editable"),
                    }
                }
            }
        }
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
        let p = |v: &[DVec3]| -> Vec<DVec3> { v.iter().map(|x| m.transform_point3(*x)).collect() };
        let v = |v: &[DVec3]| -> Vec<DVec3> { v.iter().map(|x| m.transform_vector3(*x)).collect() };
        let mut out = self.clone();
        match &mut out {
            CurveKind::Nurbs(c) => {
                *c = NurbsCurve::new(
                    c.degree(),
                    c.knots().to_vec(),
                    p(c.points()),
                    c.weights().to_vec(),
                )?;
            }
            CurveKind::CubicHermite { points, tangents } => {
                *points = p(points);
                *tangents = v(tangents);
            }
            CurveKind::QuinticHermite {
                points,
                tangents,
                accelerations,
            } => {
                *points = p(points);
                *tangents = v(tangents);
                *accelerations = v(accelerations);
            }
            CurveKind::CubicSpline { points, ends, .. } => {
                *points = p(points);
                if let SplineEnds::Clamped { start, end } = ends {
                    *start = m.transform_vector3(*start);
                    *end = m.transform_vector3(*end);
                }
            }
            CurveKind::Fractal { points, normal, .. } => {
                *points = p(points);
                *normal = m
                    .inverse()
                    .transpose()
                    .transform_vector3(*normal)
                    .normalize_or_zero();
            }
            other => {
                let pts = other.points_mut().expect("not NURBS");
                *pts = p(pts);
            }
        }
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
        let CurveKind::PolyBezier {
            points,
            joins,
            closed,
        } = &mut out
        else {
            return Err(CurveError::NotForKind {
                operation: "setting a joint's continuity",
                kind: self.name(),
            });
        };
        if joint >= joins.len() {
            return Err(CurveError::NoSuchJoint {
                index: joint,
                count: joins.len(),
            });
        }
        joins[joint] = join;
        let (hin, a, hout) = joint_indices(joint, points.len(), *closed);
        if join == Join::Auto {
            auto_handles(points, hin, a, hout);
        } else {
            enforce_join(points, join, hin, a, hout);
        }
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
        let edges = match self {
            CurveKind::PolyBezier { points, closed, .. } => {
                (points.len() - usize::from(!closed)) / 3
            }
            _ => self.points().len() - usize::from(!self.is_closed()),
        };
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
        if let CurveKind::Nurbs(c) = self {
            let c2 = c.insert_knot(t)?;
            let idx = (0..c2.points().len())
                .find(|&i| c.points().get(i) != c2.points().get(i))
                .unwrap_or(0);
            return Ok((CurveKind::Nurbs(c2), idx));
        }
        let (i, s) = self.span_at(t)?;
        let form = self.to_nurbs()?.curve;
        let [p, d1, d2] = form.derivatives(t);
        let mut out = self.clone();
        let at = i + 1;
        match &mut out {
            CurveKind::PolyBezier {
                points,
                joins,
                closed,
            } => {
                let n = points.len();
                let seg: Vec<DVec3> = (0..4).map(|k| points[(3 * i + k) % n]).collect();
                let (l, r) = crate::curves::Bezier { points: seg }.split(s);
                points.splice(
                    3 * i + 1..3 * i + 3,
                    [
                        l.points[1],
                        l.points[2],
                        l.points[3],
                        r.points[1],
                        r.points[2],
                    ],
                );
                joins.insert(if *closed { i + 1 } else { i }, Join::C1);
                out.check()?;
                return Ok((out, 3 * i + 3));
            }
            CurveKind::CubicHermite { points, tangents } => {
                points.insert(at, p);
                tangents.insert(at, d1 * 0.5);
            }
            CurveKind::QuinticHermite {
                points,
                tangents,
                accelerations,
            } => {
                points.insert(at, p);
                tangents.insert(at, d1 * 0.5);
                accelerations.insert(at, d2 * 0.25);
            }
            CurveKind::KochanekBartels { points, keys, .. } => {
                points.insert(at, p);
                keys.insert(at, Tbc::default());
            }
            CurveKind::Chaikin { points, .. } | CurveKind::Fractal { points, .. } => {
                let n = points.len();
                let q = points[i].lerp(points[(i + 1) % n], s);
                points.insert(at, q);
            }
            other => {
                other.points_mut().expect("not NURBS").insert(at, p);
            }
        }
        out.check()?;
        Ok((out, at))
    }
    /// The parameter (of the NURBS form) at which the curve passes through
    /// defining point `index`: an interpolating kind's key parameter, a
    /// poly-Bézier anchor's joint (anchor `3k` at `k`). `None` for points
    /// the curve does not pass through (NURBS control points, handles,
    /// Chaikin and fractal polygons).
    pub fn on_curve_parameter(&self, index: usize) -> Option<f64> {
        match self {
            CurveKind::PolyBezier { points, .. } => {
                (index.is_multiple_of(3) && index < points.len()).then_some((index / 3) as f64)
            }
            _ if self.interpolates() => self.key_parameters().ok()?.get(index).copied(),
            _ => None,
        }
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
        match &mut out {
            CurveKind::Nurbs(c) => {
                if !c.is_clamped() {
                    return Err(CurveError::NotForKind {
                        operation: "deleting points (clamp it first)",
                        kind: "periodic NURBS",
                    });
                }
                let points = remove_indices(c.points(), &gone);
                let weights = remove_indices(c.weights(), &gone);
                if points.len() < 2 {
                    return Err(CurveError::KindTooFewPoints {
                        kind: "NURBS",
                        needed: 2,
                        got: points.len(),
                    });
                }
                let degree = c.degree().min(points.len() - 1);
                let (a, b) = c.domain();
                let knots = clamped_uniform_knots(degree, points.len())
                    .into_iter()
                    .map(|k| a + (b - a) * k)
                    .collect();
                *c = NurbsCurve::new(degree, knots, points, weights)?;
            }
            CurveKind::PolyBezier {
                points,
                joins,
                closed,
            } => {
                if let Some(&index) = gone.iter().find(|&&i| i % 3 != 0) {
                    return Err(CurveError::HandleNotAnchor { index });
                }
                // Highest first, so lower indices stay valid.
                for &a in gone.iter().rev() {
                    let n = points.len();
                    let segs = if *closed { n / 3 } else { (n - 1) / 3 };
                    if segs <= 1 {
                        return Err(CurveError::KindTooFewPoints {
                            kind: "poly-Bézier",
                            needed: if *closed { 3 } else { 4 },
                            got: n.saturating_sub(3),
                        });
                    }
                    if *closed {
                        if a == 0 {
                            // Rotate the anchor to the end, then remove it.
                            points.rotate_left(3);
                            joins.rotate_left(1);
                            points.drain(n - 4..=n - 2);
                            joins.pop();
                        } else {
                            points.drain(a - 1..=a + 1);
                            joins.remove(a / 3);
                        }
                    } else if a == 0 {
                        points.drain(0..3);
                        joins.remove(0);
                    } else if a == n - 1 {
                        points.drain(n - 3..n);
                        joins.pop();
                    } else {
                        points.drain(a - 1..=a + 1);
                        joins.remove(a / 3 - 1);
                    }
                }
            }
            other => {
                let drop = |v: &mut Vec<DVec3>| *v = remove_indices(v, &gone);
                match other {
                    CurveKind::CubicHermite { points, tangents } => {
                        drop(points);
                        drop(tangents);
                    }
                    CurveKind::QuinticHermite {
                        points,
                        tangents,
                        accelerations,
                    } => {
                        drop(points);
                        drop(tangents);
                        drop(accelerations);
                    }
                    CurveKind::KochanekBartels { points, keys, .. } => {
                        drop(points);
                        *keys = remove_indices(keys, &gone);
                    }
                    o => drop(o.points_mut().expect("not NURBS")),
                }
            }
        }
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
        match &mut out {
            CurveKind::Nurbs(c) => {
                if !c.is_clamped() {
                    return Err(CurveError::NotForKind {
                        operation: "extruding (clamp it first)",
                        kind: "periodic NURBS",
                    });
                }
                let mut points = c.points().to_vec();
                let mut weights = c.weights().to_vec();
                points.push(to);
                weights.push(1.0);
                let (a, b) = c.domain();
                let knots = clamped_uniform_knots(c.degree(), points.len())
                    .into_iter()
                    .map(|k| a + (b - a) * k)
                    .collect();
                *c = NurbsCurve::new(c.degree(), knots, points, weights)?;
            }
            CurveKind::PolyBezier { points, joins, .. } => {
                let n = points.len();
                let (a, h) = (points[n - 1], points[n - 2]);
                let reach = (to - a).length() / 3.0;
                let dir = (a - h)
                    .try_normalize()
                    .unwrap_or((to - a).normalize_or_zero());
                points.extend([a + dir * reach, to + (a - to) / 3.0, to]);
                joins.push(Join::G1);
            }
            CurveKind::CubicHermite { points, tangents } => {
                tangents.push(to - points[points.len() - 1]);
                points.push(to);
            }
            CurveKind::QuinticHermite {
                points,
                tangents,
                accelerations,
            } => {
                tangents.push(to - points[points.len() - 1]);
                accelerations.push(DVec3::ZERO);
                points.push(to);
            }
            CurveKind::KochanekBartels { points, keys, .. } => {
                points.push(to);
                keys.push(Tbc::default());
            }
            other => other.points_mut().expect("not NURBS").push(to),
        }
        let out = out.reversed_if(end == CurveEnd::Start)?;
        out.check()?;
        Ok(out)
    }
}

/// The joint's incoming handle, anchor and outgoing handle indices.
fn joint_indices(j: usize, n: usize, closed: bool) -> (usize, usize, usize) {
    let a = if closed { 3 * j } else { 3 * (j + 1) };
    ((a + n - 1) % n, a, (a + 1) % n)
}

/// Places the handles of the auto joint at anchor `a` from its neighbouring
/// anchors (three points away along the chain, modulo its length).
fn auto_handles(points: &mut [DVec3], hin: usize, a: usize, hout: usize) {
    let n = points.len();
    let (prev, next) = (points[(a + n - 3) % n], points[(a + 3) % n]);
    let Some(dir) = (next - prev).try_normalize() else {
        return;
    };
    let p = points[a];
    points[hin] = p - dir * (p - prev).length() / 3.0;
    points[hout] = p + dir * (next - p).length() / 3.0;
}

/// Turns handle `other` about anchor `a` so the joint holds `join`, given
/// the handle `fixed`.
fn enforce_join(points: &mut [DVec3], join: Join, fixed: usize, a: usize, other: usize) {
    let arm = points[a] - points[fixed];
    match join {
        Join::C0 => {}
        Join::C1 => points[other] = points[a] + arm,
        Join::G1 | Join::Auto => {
            if let Some(dir) = arm.try_normalize() {
                let len = (points[other] - points[a]).length();
                points[other] = points[a] + dir * len;
            }
        }
    }
}
