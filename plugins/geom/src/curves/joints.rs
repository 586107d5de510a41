//! The continuity of a curve at each of its joints, measured from the
//! derivatives on both sides (seed 000: C^n / G^n continuity; seed 002:
//! C1/C2/G1/G2 joins of Bézier segments).
//!
//! A joint is where two polynomial (or rational) pieces of a curve's NURBS
//! form meet: every distinct interior knot — a NURBS knot of any
//! multiplicity, a poly-Bézier anchor, a Hermite, Catmull-Rom or
//! Kochanek-Bartels key, a C2 spline's knot, a vertex of a Chaikin or
//! fractal polygon — and, on a closed curve, the point where its end meets
//! its start. A Lagrange curve is one polynomial and has none.
//!
//! Each joint is classified from the one-sided limits
//! ([`NurbsCurve::derivatives_on_side`]) with the tolerances of
//! [`JointTolerance`]:
//!
//! - **C0**: the two positions within `position × size` (size: the
//!   diagonal of the control points' bounding box);
//! - **C1 / C2**: first (and second) derivatives equal within `derivative`
//!   relative to the larger of the two, but never less than
//!   `derivative × size / h^k` (h: the shorter neighbouring span's
//!   parameter length, k the order), so that rounding in nearly vanishing
//!   derivatives does not break a join;
//! - **G1**: C0, neither tangent vanishing, unit tangents within
//!   `direction` of each other (seed 000: `m_i = α m_{i+1}`, α > 0);
//! - **G2**: G1 and the same curvature vector `κ n = (p' × p'') × p' /
//!   |p'|⁴` within `derivative` relative to the larger, at least
//!   `derivative / size`.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::analysis::Continuity;
use super::nurbs::{NurbsCurve, Side};
use super::{Curve, CurveKind};

/// The tolerances a joint is classified with (see the module
/// documentation for how each is scaled).
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct JointTolerance {
    /// Largest gap between the two sides' positions, relative to the
    /// curve's size (its control points' bounding-box diagonal).
    pub position: f64,
    /// Largest relative difference of derivatives and curvature vectors.
    pub derivative: f64,
    /// Largest distance between the two unit tangents (about the angle in
    /// radians).
    pub direction: f64,
}

impl Default for JointTolerance {
    /// 1e-9 for each: rounding in the NURBS form stays far below, a real
    /// kink far above.
    fn default() -> Self {
        JointTolerance {
            position: 1e-9,
            derivative: 1e-9,
            direction: 1e-9,
        }
    }
}

/// One joint of a curve and how smoothly its two pieces meet there.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Joint {
    /// The parameter of the NURBS form at the joint (the domain's start for
    /// the closing joint of a closed curve).
    pub parameter: f64,
    /// The point there, in the curve's own space (the incoming side's).
    pub position: DVec3,
    /// The knot's multiplicity in the NURBS form; 0 for the closing joint.
    pub multiplicity: usize,
    /// True for the joint where a closed curve's end meets its start.
    pub closing: bool,
    /// Position, first and second derivative of the incoming piece.
    pub before: [DVec3; 3],
    /// Position, first and second derivative of the outgoing piece.
    pub after: [DVec3; 3],
    /// What the two sides agree on.
    pub continuity: Continuity,
}

impl Continuity {
    /// A short label for panels and `hedra eval`: the highest parametric
    /// order, with the geometric one where it goes further: "C2", "C1",
    /// "C1 G2", "G2", "G1", "C0", or "gap" where the positions differ.
    pub fn label(&self) -> &'static str {
        match (self.c0, self.c1, self.c2, self.g1, self.g2) {
            (false, ..) => "gap",
            (_, _, true, _, _) => "C2",
            (_, true, _, _, true) => "C1 G2",
            (_, true, ..) => "C1",
            (.., true) => "G2",
            (_, _, _, true, _) => "G1",
            _ => "C0",
        }
    }
}

/// The continuity of a joint from the derivatives on its two sides (see
/// the module documentation for the tests). `size` is the curve's size,
/// `h` the shorter neighbouring span's parameter length. O(1).
pub fn classify(
    before: [DVec3; 3],
    after: [DVec3; 3],
    size: f64,
    h: f64,
    tolerance: &JointTolerance,
) -> Continuity {
    let size = size.max(f64::MIN_POSITIVE);
    let h = if h > 0.0 { h } else { 1.0 };
    let eps = tolerance.derivative;
    let floor = |k: i32| size / h.powi(k);
    let same = |x: DVec3, y: DVec3, k: i32| {
        (x - y).length() <= eps * x.length().max(y.length()).max(floor(k))
    };
    let c0 = (before[0] - after[0]).length() <= tolerance.position * size;
    let c1 = c0 && same(before[1], after[1], 1);
    let c2 = c1 && same(before[2], after[2], 2);
    let moving = |d: DVec3| d.length() > eps * floor(1);
    let g1 = c0
        && moving(before[1])
        && moving(after[1])
        && (before[1].normalize() - after[1].normalize()).length() <= tolerance.direction;
    let kappa = |d1: DVec3, d2: DVec3| d1.cross(d2).cross(d1) / d1.length_squared().powi(2);
    let g2 = g1 && {
        let (ka, kb) = (kappa(before[1], before[2]), kappa(after[1], after[2]));
        (ka - kb).length() <= eps * ka.length().max(kb.length()).max(1.0 / size)
    };
    Continuity { c0, c1, c2, g1, g2 }
}

/// The diagonal of the points' bounding box.
pub(crate) fn extent(points: &[DVec3]) -> f64 {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    if points.is_empty() {
        0.0
    } else {
        (hi - lo).length()
    }
}

/// Every joint of a NURBS curve: each distinct interior knot in order,
/// then, when `closed`, the closing joint (the end's incoming piece against
/// the start's outgoing one). O(k p²) for k joints.
pub fn curve_joints(curve: &NurbsCurve, closed: bool, tolerance: &JointTolerance) -> Vec<Joint> {
    let (start, end) = curve.domain();
    let size = extent(curve.points());
    let knots = curve.interior_knots();
    let mut breaks = vec![start];
    breaks.extend(knots.iter().map(|k| k.0));
    breaks.push(end);
    let mut out: Vec<Joint> = knots
        .iter()
        .enumerate()
        .map(|(i, &(t, multiplicity))| {
            let before = curve.derivatives_on_side(t, Side::Before);
            let after = curve.derivatives_on_side(t, Side::After);
            let h = (t - breaks[i]).min(breaks[i + 2] - t);
            Joint {
                parameter: t,
                position: before[0],
                multiplicity,
                closing: false,
                before,
                after,
                continuity: classify(before, after, size, h, tolerance),
            }
        })
        .collect();
    if closed {
        let before = curve.derivatives_on_side(end, Side::Before);
        let after = curve.derivatives_on_side(start, Side::After);
        let n = breaks.len();
        let h = (breaks[1] - breaks[0]).min(breaks[n - 1] - breaks[n - 2]);
        out.push(Joint {
            parameter: start,
            position: before[0],
            multiplicity: 0,
            closing: true,
            before,
            after,
            continuity: classify(before, after, size, h, tolerance),
        });
    }
    out
}

/// The two one-sided evaluations of a curve at `t`: `(before, after)`,
/// `None` on the side where an open curve has no piece (before its start,
/// after its end). On a closed curve the start's "before" is the end's
/// incoming piece and the end's "after" the start's outgoing one. O(p²).
pub fn both_sides(
    curve: &NurbsCurve,
    closed: bool,
    t: f64,
) -> (Option<[DVec3; 3]>, Option<[DVec3; 3]>) {
    let (start, end) = curve.domain();
    let before = if t > start {
        Some(curve.derivatives_on_side(t, Side::Before))
    } else if closed {
        Some(curve.derivatives_on_side(end, Side::Before))
    } else {
        None
    };
    let after = if t < end {
        Some(curve.derivatives_on_side(t, Side::After))
    } else if closed {
        Some(curve.derivatives_on_side(start, Side::After))
    } else {
        None
    };
    (before, after)
}

impl CurveKind {
    /// The joints of this curve, each with its measured continuity (see
    /// the module documentation): `form` must be this kind's NURBS form
    /// ([`to_nurbs`](Self::to_nurbs), or a curve node's stored one). A
    /// Lagrange curve has none (one polynomial; the knots of an
    /// approximating form are not joints of the curve); a closed kind adds
    /// its closing joint. Read-only; the inverse is not applicable.
    /// O(k p²) for k joints.
    ///
    /// What each kind promises at its interior joints (tested): NURBS
    /// C^(p−m) at a knot of multiplicity m (generically no more);
    /// cubic Hermite, Catmull-Rom and Kochanek-Bartels keys with
    /// continuity 0 C1; Kochanek-Bartels keys with continuity ≠ 0 C0 only
    /// (G1 only where the neighbouring chords are parallel); quintic
    /// Hermite and the C2 spline C2; a poly-Bézier joint what its [`Join`]
    /// says; Chaikin and fractal polygon vertices C0 (more where two edges
    /// happen to continue each other).
    ///
    /// [`Join`]: super::Join
    pub fn joints(&self, form: &NurbsCurve, tolerance: &JointTolerance) -> Vec<Joint> {
        if matches!(self, CurveKind::Lagrange(_)) {
            return Vec::new();
        }
        curve_joints(form, self.is_closed(), tolerance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_name_the_highest_orders() {
        let c = |c0, c1, c2, g1, g2| Continuity { c0, c1, c2, g1, g2 };
        assert_eq!(c(true, true, true, true, true).label(), "C2");
        assert_eq!(c(true, true, false, true, true).label(), "C1 G2");
        assert_eq!(c(true, true, false, true, false).label(), "C1");
        assert_eq!(c(true, false, false, true, true).label(), "G2");
        assert_eq!(c(true, false, false, true, false).label(), "G1");
        assert_eq!(c(true, false, false, false, false).label(), "C0");
        assert_eq!(c(false, false, false, false, false).label(), "gap");
    }

    #[test]
    fn a_double_knot_of_a_cubic_is_c1_and_a_triple_knot_c0() {
        let points: Vec<DVec3> = (0..7)
            .map(|i| DVec3::new(i as f64, ((i * i) % 5) as f64, (i % 2) as f64))
            .collect();
        let w = vec![1.0; 7];
        let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 3.0, 3.0, 3.0, 3.0];
        let c = NurbsCurve::new(3, knots, points.clone(), w.clone()).unwrap();
        let j = curve_joints(&c, false, &JointTolerance::default());
        assert_eq!(j.len(), 2);
        assert_eq!((j[0].parameter, j[0].multiplicity), (1.0, 1));
        assert_eq!(j[0].continuity.label(), "C2");
        assert_eq!((j[1].parameter, j[1].multiplicity), (2.0, 2));
        assert_eq!(j[1].continuity.label(), "C1");
        let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0];
        let c = NurbsCurve::new(3, knots, points, w).unwrap();
        let j = curve_joints(&c, false, &JointTolerance::default());
        assert_eq!(j.len(), 1);
        assert_eq!(j[0].multiplicity, 3);
        assert_eq!(j[0].continuity.label(), "C0");
        assert!((j[0].position - c.points()[3]).length() < 1e-12);
    }
}
