//! Whole-curve edits of a curve kind: reversing, opening and closing,
//! splitting in two and joining two curves.

use super::{CurveKind, FractalRule, Join, SplineEnds};
use crate::curves::CurveError;
use crate::curves::interpolating::Tbc;
use crate::curves::nurbs::NurbsCurve;
use glam::DVec3;

fn reverse_closed<T: Clone>(v: &[T]) -> Vec<T> {
    let mut r = vec![v[0].clone()];
    r.extend(v[1..].iter().rev().cloned());
    r
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
        let closed = self.is_closed() && !matches!(self, CurveKind::Nurbs(_));
        let rev = |v: &[DVec3]| -> Vec<DVec3> {
            if closed {
                reverse_closed(v)
            } else {
                v.iter().rev().copied().collect()
            }
        };
        let neg = |v: &[DVec3]| -> Vec<DVec3> { v.iter().rev().map(|x| -*x).collect() };
        Ok(match self {
            CurveKind::Nurbs(c) => {
                let (k, n) = (c.knots(), c.knots().len());
                let (a, b) = (k[0], k[n - 1]);
                let knots = (0..n).map(|i| a + b - k[n - 1 - i]).collect();
                let points = c.points().iter().rev().copied().collect();
                let weights = c.weights().iter().rev().copied().collect();
                CurveKind::Nurbs(NurbsCurve::new(c.degree(), knots, points, weights)?)
            }
            CurveKind::Lagrange {
                points,
                parameterization,
            } => CurveKind::Lagrange {
                points: rev(points),
                parameterization: *parameterization,
            },
            CurveKind::CubicHermite { points, tangents } => CurveKind::CubicHermite {
                points: rev(points),
                tangents: neg(tangents),
            },
            CurveKind::QuinticHermite {
                points,
                tangents,
                accelerations,
            } => CurveKind::QuinticHermite {
                points: rev(points),
                tangents: neg(tangents),
                accelerations: rev(accelerations),
            },
            CurveKind::CatmullRom {
                points,
                parameterization,
                closed: c,
            } => CurveKind::CatmullRom {
                points: rev(points),
                parameterization: *parameterization,
                closed: *c,
            },
            CurveKind::KochanekBartels {
                points,
                keys,
                closed: c,
            } => {
                let flip = |k: &Tbc| Tbc {
                    bias: -k.bias,
                    ..*k
                };
                let keys: Vec<Tbc> = if *c {
                    reverse_closed(keys).iter().map(flip).collect()
                } else {
                    keys.iter().rev().map(flip).collect()
                };
                CurveKind::KochanekBartels {
                    points: rev(points),
                    keys,
                    closed: *c,
                }
            }
            CurveKind::CubicSpline {
                points,
                parameterization,
                ends,
            } => CurveKind::CubicSpline {
                points: rev(points),
                parameterization: *parameterization,
                ends: match *ends {
                    SplineEnds::Clamped { start, end } => SplineEnds::Clamped {
                        start: -end,
                        end: -start,
                    },
                    e => e,
                },
            },
            CurveKind::Chaikin {
                points,
                level,
                closed: c,
            } => CurveKind::Chaikin {
                points: rev(points),
                level: *level,
                closed: *c,
            },
            CurveKind::PolyBezier {
                points,
                joins,
                closed: c,
            } => CurveKind::PolyBezier {
                points: rev(points),
                joins: if *c {
                    reverse_closed(joins)
                } else {
                    joins.iter().rev().copied().collect()
                },
                closed: *c,
            },
            CurveKind::Fractal {
                rule,
                points,
                level,
                closed: c,
                normal,
            } => CurveKind::Fractal {
                rule: *rule,
                points: rev(points),
                level: *level,
                closed: *c,
                // Koch's bump is mirror-symmetric: traced back it must stay
                // on the same side, so the normal flips. The quadratic
                // Koch generator is point-symmetric: traced back with the
                // same normal it is the same polygon.
                normal: match rule {
                    FractalRule::Koch => -*normal,
                    FractalRule::QuadraticKoch => *normal,
                },
            },
        })
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
        match &mut out {
            CurveKind::CatmullRom { closed: c, .. }
            | CurveKind::KochanekBartels { closed: c, .. }
            | CurveKind::Chaikin { closed: c, .. }
            | CurveKind::Fractal { closed: c, .. } => *c = closed,
            CurveKind::CubicSpline { ends, .. } => {
                *ends = if closed {
                    SplineEnds::Closed
                } else {
                    SplineEnds::Natural
                }
            }
            CurveKind::PolyBezier {
                points,
                joins,
                closed: c,
            } => {
                *c = closed;
                if closed {
                    let (first, last) = (points[0], points[points.len() - 1]);
                    joins.insert(0, Join::C0);
                    if (first - last).length() <= 1e-12 {
                        points.pop();
                    } else {
                        points.extend([last.lerp(first, 1.0 / 3.0), last.lerp(first, 2.0 / 3.0)]);
                        joins.push(Join::C0);
                    }
                } else {
                    points.push(points[0]);
                    joins.remove(0);
                }
            }
            _ => {
                return Err(CurveError::NotForKind {
                    operation: if closed { "closing" } else { "opening" },
                    kind: self.name(),
                });
            }
        }
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
        if self.is_closed() && !matches!(self, CurveKind::Nurbs(_)) {
            return Err(CurveError::NotForKind {
                operation: "splitting a closed curve (open it first)",
                kind: self.name(),
            });
        }
        if let CurveKind::Nurbs(c) = self {
            let (a, b) = c.split(t)?;
            return Ok((CurveKind::Nurbs(a), CurveKind::Nurbs(b)));
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
        let keep = |v: &mut Vec<DVec3>, left: bool| {
            if left {
                v.truncate(k + 1)
            } else {
                v.drain(..k);
            }
        };
        for (c, left) in [(&mut a, true), (&mut b, false)] {
            match &mut *c {
                CurveKind::PolyBezier { points, joins, .. } => {
                    keep(points, left);
                    let j = k / 3 - 1;
                    if left {
                        joins.truncate(j);
                    } else {
                        joins.drain(..=j);
                    }
                }
                CurveKind::CubicHermite { points, tangents } => {
                    keep(points, left);
                    keep(tangents, left);
                }
                CurveKind::QuinticHermite {
                    points,
                    tangents,
                    accelerations,
                } => {
                    keep(points, left);
                    keep(tangents, left);
                    keep(accelerations, left);
                }
                CurveKind::KochanekBartels { points, keys, .. } => {
                    keep(points, left);
                    if left {
                        keys.truncate(k + 1)
                    } else {
                        keys.drain(..k);
                    }
                }
                o => keep(o.points_mut().expect("not NURBS"), left),
            }
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
        if std::mem::discriminant(self) != std::mem::discriminant(other) {
            return Err(CurveError::KindMismatch {
                first: self.name(),
                second: other.name(),
            });
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
        match (&mut out, other) {
            (CurveKind::Nurbs(a), CurveKind::Nurbs(b)) => *a = join_nurbs(a, b)?,
            (
                CurveKind::PolyBezier { points, joins, .. },
                CurveKind::PolyBezier {
                    points: bp,
                    joins: bj,
                    ..
                },
            ) => {
                let (last, first) = (points[points.len() - 1], bp[0]);
                joins.push(Join::C0);
                if skip == 0 {
                    points.extend([
                        last.lerp(first, 1.0 / 3.0),
                        last.lerp(first, 2.0 / 3.0),
                        first,
                    ]);
                    joins.push(Join::C0);
                }
                points.extend_from_slice(&bp[1..]);
                joins.extend_from_slice(bj);
            }
            (
                CurveKind::CubicHermite { points, tangents },
                CurveKind::CubicHermite {
                    points: bp,
                    tangents: bt,
                },
            ) => {
                points.extend_from_slice(&bp[skip..]);
                tangents.extend_from_slice(&bt[skip..]);
            }
            (
                CurveKind::QuinticHermite {
                    points,
                    tangents,
                    accelerations,
                },
                CurveKind::QuinticHermite {
                    points: bp,
                    tangents: bt,
                    accelerations: ba,
                },
            ) => {
                points.extend_from_slice(&bp[skip..]);
                tangents.extend_from_slice(&bt[skip..]);
                accelerations.extend_from_slice(&ba[skip..]);
            }
            (
                CurveKind::KochanekBartels { points, keys, .. },
                CurveKind::KochanekBartels {
                    points: bp,
                    keys: bk,
                    ..
                },
            ) => {
                points.extend_from_slice(&bp[skip..]);
                keys.extend_from_slice(&bk[skip..]);
            }
            (o, b) => o
                .points_mut()
                .expect("not NURBS")
                .extend_from_slice(&b.points()[skip..]),
        }
        out.check()?;
        Ok(out)
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
