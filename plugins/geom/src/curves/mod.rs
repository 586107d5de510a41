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
pub mod interpolating;
pub mod nurbs;

use glam::DVec3;

pub use bezier::Bezier;
pub use nurbs::NurbsCurve;

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
}

/// Why a curve cannot be made or changed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CurveError {
    #[error("a degree {degree} curve needs at least {needed} control points, got {got}")]
    TooFewPoints {
        degree: usize,
        needed: usize,
        got: usize,
    },
    #[error("degree must be at least 1")]
    ZeroDegree,
    #[error("{points} control points of degree {degree} need {needed} knots, got {got}")]
    KnotCount {
        points: usize,
        degree: usize,
        needed: usize,
        got: usize,
    },
    #[error("knot {index} ({value}) is smaller than the one before it (knots must not decrease)")]
    DecreasingKnots { index: usize, value: f64 },
    #[error("the knot vector has an empty domain (all the inner knots are equal)")]
    EmptyDomain,
    #[error("weight {index} is {value}: weights must be positive")]
    BadWeight { index: usize, value: f64 },
    #[error("{what} {index} is not finite")]
    NotFinite { what: &'static str, index: usize },
    #[error("{points} points but {weights} weights")]
    WeightCount { points: usize, weights: usize },
    #[error("parameter {value} is outside the domain [{start}, {end}]")]
    OutsideDomain { value: f64, start: f64, end: f64 },
    #[error(
        "knot {value} already has multiplicity {multiplicity} (the degree): no more can be inserted"
    )]
    FullMultiplicity { value: f64, multiplicity: usize },
    #[error("control point {index} does not exist (there are {count})")]
    NoSuchPoint { index: usize, count: usize },
    #[error("{points} points need {points} {what}, got {got}")]
    CountMismatch {
        points: usize,
        what: &'static str,
        got: usize,
    },
    #[error("parameter {index} ({value}) does not increase")]
    NotIncreasing { index: usize, value: f64 },
    #[error("{what} is not finite")]
    NotFiniteVector { what: &'static str },
    #[error("the Vandermonde system is singular")]
    Singular,
    #[error("a degree {degree} Bézier triangle has {needed} control points, got {got}")]
    TrianglePointCount {
        degree: usize,
        needed: usize,
        got: usize,
    },
    #[error("a Bézier surface needs at least 2 × 2 control points, got {nu} × {nv}")]
    GridTooSmall { nu: usize, nv: usize },
    #[error("{nu} × {nv} control points expected, got {got}")]
    GridPointCount { nu: usize, nv: usize, got: usize },
    #[error(
        "{nu} × {nv} control points and weights expected, got {points} points and {weights} weights"
    )]
    GridCount {
        nu: usize,
        nv: usize,
        points: usize,
        weights: usize,
    },
    #[error("{what} must be positive, not {value}")]
    NotPositive { what: &'static str, value: f64 },
    #[error("Bézier triangles are polynomial: they have no weights")]
    TriangleWeights,
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
