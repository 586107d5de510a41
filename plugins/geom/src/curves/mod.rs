//! Free-form curves: Bézier, B-spline and NURBS, the interpolating splines
//! of the lecture notes (Lagrange, Hermite, Catmull-Rom, Kochanek-Bartels,
//! C2 cubic), Chaikin corner cutting, and the operations on any curve (arc
//! length, closest point, Frenet frame, curvature).
//!
//! Every curve evaluates its position and first and second derivatives
//! through [`Curve`]; the operations in [`analysis`] use only that.

pub mod analysis;
pub mod bezier;
pub mod fast;
pub mod hull;
pub mod interpolating;
pub mod joints;
pub mod kinds;
pub mod nurbs;
pub mod spans;

use glam::DVec3;

pub use bezier::Bezier;
pub use kinds::{
    CatmullRom, Chaikin, CubicHermite, CubicSpline, CurveEnd, CurveKind, Fractal, FractalRule,
    Join, KindRules, KochanekBartels, Lagrange, NurbsForm, Parameterization, PolyBezier,
    QuinticHermite, SplineEnds, TangentHandle,
};
pub use nurbs::{NurbsCurve, Side};

/// A parametric curve on a closed parameter interval.
pub trait Curve {
    /// The parameter interval `(start, end)`.
    fn domain(&self) -> (f64, f64);
    /// Position, first and second derivative at `t` (clamped to the domain).
    fn derivatives(&self, t: f64) -> [DVec3; 3];
    /// Position at `t`.
    fn point(&self, t: f64) -> DVec3 {
        self.derivatives(t)[0]
    }
    /// The parameters where the curve's pieces meet, with the domain's two
    /// ends: increasing, distinct, first and last the domain's. Between two
    /// neighbours the curve is one polynomial (or rational) piece, smooth;
    /// at them it may have a corner (a NURBS knot of full multiplicity, a
    /// poly-Bézier C0 joint, a polyline's vertex). Tessellation samples
    /// every one of them ([`crate::surfaces::tessellate::curve_parameters`]).
    /// The default is one piece: the domain's ends.
    fn breakpoints(&self) -> Vec<f64> {
        let (a, b) = self.domain();
        if b > a { vec![a, b] } else { vec![a] }
    }
    /// The polynomial degree of every piece between two
    /// [`breakpoints`](Self::breakpoints), when the curve knows it; a rational
    /// piece reports the degree of its numerator and denominator. `Some(1)`
    /// means every piece is a straight segment, so the breakpoints alone
    /// are the exact polyline. `None` (the default): unknown.
    fn piece_degree(&self) -> Option<usize> {
        None
    }
}

/// Why a curve cannot be made or changed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CurveError {
    /// Fewer control points than the degree needs (`degree + 1`).
    #[error("a degree {degree} curve needs at least {needed} control points, got {got}")]
    TooFewPoints {
        /// The requested degree.
        degree: usize,
        /// The minimum number of control points.
        needed: usize,
        /// The number given.
        got: usize,
    },
    /// Degree 0 was requested.
    #[error("degree must be at least 1")]
    ZeroDegree,
    /// The knot vector's length is not `points + degree + 1`.
    #[error("{points} control points of degree {degree} need {needed} knots, got {got}")]
    KnotCount {
        /// Number of control points.
        points: usize,
        /// The degree.
        degree: usize,
        /// The knot count they need.
        needed: usize,
        /// The knot count given.
        got: usize,
    },
    /// A knot is smaller than its predecessor.
    #[error("knot {index} ({value}) is smaller than the one before it (knots must not decrease)")]
    DecreasingKnots {
        /// Position of the knot in the vector.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// The domain `[knots[degree], knots[points]]` has zero length.
    #[error("the knot vector has an empty domain (all the inner knots are equal)")]
    EmptyDomain,
    /// A weight is zero, negative, NaN or infinite.
    #[error("weight {index} is {value}: weights must be positive")]
    BadWeight {
        /// Index of the weight (of its control point; `i * nv + j` on a
        /// surface).
        index: usize,
        /// The refused value.
        value: f64,
    },
    /// An input value is NaN or infinite.
    #[error("{what} {index} is not finite")]
    NotFinite {
        /// What kind of value: `"control point"`, `"knot"`, `"parameter"`.
        what: &'static str,
        /// Its index in its list.
        index: usize,
    },
    /// The weight list's length differs from the point list's.
    #[error("{points} points but {weights} weights")]
    WeightCount {
        /// Number of control points.
        points: usize,
        /// Number of weights.
        weights: usize,
    },
    /// A parameter (for example a knot to insert) lies outside the domain.
    #[error("parameter {value} is outside the domain [{start}, {end}]")]
    OutsideDomain {
        /// The refused parameter.
        value: f64,
        /// Start of the domain.
        start: f64,
        /// End of the domain.
        end: f64,
    },
    /// A curve kind given fewer points than it needs.
    #[error("{kind} needs {needed} points or more, got {got}")]
    KindTooFewPoints {
        /// The kind, as [`CurveKind::name`] spells it.
        kind: &'static str,
        /// The least number of points it takes.
        needed: usize,
        /// The number given.
        got: usize,
    },
    /// An edit the curve's kind does not have (closing a Lagrange curve,
    /// extruding a closed curve).
    #[error("{operation} is not possible on a {kind} curve")]
    NotForKind {
        /// What was asked, as a phrase: `"closing"`, `"extruding a closed curve"`.
        operation: &'static str,
        /// The curve's kind.
        kind: &'static str,
    },
    /// Two curves of different kinds to be joined.
    #[error("a {first} curve cannot be joined to a {second} curve (convert both to NURBS first)")]
    KindMismatch {
        /// The first curve's kind.
        first: &'static str,
        /// The second curve's kind.
        second: &'static str,
    },
    /// A poly-Bézier point that is a tangent handle where an anchor is needed.
    #[error(
        "point {index} is a handle of the poly-Bézier, not an anchor (anchors are every third point)"
    )]
    HandleNotAnchor {
        /// The index given.
        index: usize,
    },
    /// A poly-Bézier joint index past the end.
    #[error("joint {index} does not exist (there are {count})")]
    NoSuchJoint {
        /// The index asked for.
        index: usize,
        /// The number of joints.
        count: usize,
    },
    /// A subdivision or fractal level that would make too many points.
    #[error("level {level} is too high (at most {max} for this curve)")]
    LevelTooHigh {
        /// The level asked for.
        level: u32,
        /// The highest level allowed for this curve.
        max: u32,
    },
    /// Two neighbouring points at the same place where chord-length or
    /// centripetal parameters need them apart.
    #[error(
        "points {index} and {next} coincide: chord-length and centripetal parameters need distinct neighbours"
    )]
    CoincidentPoints {
        /// The first of the two.
        index: usize,
        /// The second (0 for the closing span of a closed curve).
        next: usize,
    },
    /// Knot insertion at a knot whose multiplicity already equals the degree.
    #[error(
        "knot {value} already has multiplicity {multiplicity} (the degree): no more can be inserted"
    )]
    FullMultiplicity {
        /// The knot value.
        value: f64,
        /// Its current multiplicity.
        multiplicity: usize,
    },
    /// A control point index past the end.
    #[error("control point {index} does not exist (there are {count})")]
    NoSuchPoint {
        /// The index asked for.
        index: usize,
        /// The number of control points.
        count: usize,
    },
    /// A per-point list (parameters, tangents, keys) has the wrong length.
    #[error("{points} points need {points} {what}, got {got}")]
    CountMismatch {
        /// Number of points.
        points: usize,
        /// What the list holds: `"parameter values"`, `"tangents"`,
        /// `"T/B/C keys"`.
        what: &'static str,
        /// Its length.
        got: usize,
    },
    /// Interpolation parameters that do not strictly increase.
    #[error("parameter {index} ({value}) does not increase")]
    NotIncreasing {
        /// Index of the first parameter not above its predecessor.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A vector input (a tangent, a direction) is NaN or infinite.
    #[error("{what} is not finite")]
    NotFiniteVector {
        /// The input, with its article: `"a tangent"`, `"the extrusion
        /// direction"`.
        what: &'static str,
    },
    /// Power-basis interpolation met a singular system (parameters too
    /// close together).
    #[error("the Vandermonde system is singular")]
    Singular,
    /// A Bézier triangle's point count is not `(n + 1)(n + 2) / 2`.
    #[error("a degree {degree} Bézier triangle has {needed} control points, got {got}")]
    TrianglePointCount {
        /// The degree n.
        degree: usize,
        /// `(n + 1)(n + 2) / 2`.
        needed: usize,
        /// The number given.
        got: usize,
    },
    /// A Bézier surface grid smaller than 2 × 2.
    #[error("a Bézier surface needs at least 2 × 2 control points, got {nu} × {nv}")]
    GridTooSmall {
        /// Points in the u direction.
        nu: usize,
        /// Points in the v direction.
        nv: usize,
    },
    /// A Bézier surface's point count is not `nu · nv`.
    #[error("{nu} × {nv} control points expected, got {got}")]
    GridPointCount {
        /// Points in the u direction.
        nu: usize,
        /// Points in the v direction.
        nv: usize,
        /// The number given.
        got: usize,
    },
    /// A NURBS surface's point or weight count is not `nu · nv`.
    #[error(
        "{nu} × {nv} control points and weights expected, got {points} points and {weights} weights"
    )]
    GridCount {
        /// Points in the u direction.
        nu: usize,
        /// Points in the v direction.
        nv: usize,
        /// Number of points given.
        points: usize,
        /// Number of weights given.
        weights: usize,
    },
    /// A size (radius, height, ...) that is zero, negative or not finite.
    #[error("{what} must be positive, not {value}")]
    NotPositive {
        /// The quantity, as the message names it (`"radius"`, `"a circle's
        /// radius"`).
        what: &'static str,
        /// The refused value.
        value: f64,
    },
    /// Weights were set on a Bézier triangle, which has none.
    #[error("Bézier triangles are polynomial: they have no weights")]
    TriangleWeights,
    /// A knot was inserted into a Bézier triangle, which has no knots.
    #[error("Bézier triangles have no knots (elevate or split them instead)")]
    TriangleKnots,
}

/// Checks that every point is finite.
pub(crate) fn check_points(points: &[DVec3]) -> Result<(), CurveError> {
    match points.iter().position(|p| !p.is_finite()) {
        Some(index) => Err(CurveError::NotFinite {
            what: "control point",
            index,
        }),
        None => Ok(()),
    }
}

/// The binomial coefficient C(n, k) as a float.
pub(crate) fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}
