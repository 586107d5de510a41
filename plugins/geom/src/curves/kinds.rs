//! Every curve of the lecture notes as one storable value, [`CurveKind`]:
//! the data a user edits (interpolation points, tangents, T/B/C keys, a
//! poly-Bézier's anchors and handles with their joins, a fractal's
//! initiator polygon and level) and its NURBS form, which is what is drawn,
//! evaluated and exported ([`CurveKind::to_nurbs`]).
//!
//! The NURBS form is exact where the kind is piecewise polynomial
//! (poly-Bézier, cubic and quintic Hermite, Catmull-Rom, Kochanek-Bartels,
//! the C2 cubic spline: one Bézier segment per span, same parameter, same
//! points to rounding), exact for the polylines of a Chaikin level and a
//! fractal level (degree 1), exact for Lagrange up to
//! [`LAGRANGE_EXACT_POINTS`] points (one Bézier of degree n − 1, solved in
//! the Bernstein basis) and an interpolating cubic approximation above
//! that, with its measured deviation stated in [`NurbsForm::tolerance`].
//!
//! Sources: seed 000 (Lagrange/Vandermonde, Hermite, Catmull-Rom,
//! Kochanek-Bartels, Chaikin), seed 002 (quintic Hermite), seed 003 (Bézier
//! ↔ power basis), seed 004 (C2 cubic spline, Koch curve and the Hausdorff
//! dimension `D = log N / log(1/r)`).
//!
//! Every edit ([`set_points`](CurveKind::set_points),
//! [`insert_point`](CurveKind::insert_point), …) returns a new value and
//! leaves `self` untouched; a refused edit returns a named [`CurveError`].

use glam::{DMat4, DVec3};
use serde::{Deserialize, Serialize};

use super::bezier::bernstein;
use super::interpolating::{HermiteSpline, Tbc, c2_cubic_spline, chaikin, solve_dense};
use super::nurbs::{NurbsCurve, clamped_uniform_knots};
use super::{Curve, CurveError, check_points};

/// Lagrange curves with at most this many points get an exact Bézier form
/// (degree ≤ 11); above it the NURBS form is an interpolating cubic spline
/// through dense samples, its deviation measured and stated.
pub const LAGRANGE_EXACT_POINTS: usize = 12;

/// Most points a Chaikin or fractal level may produce.
pub const MAX_LEVEL_POINTS: usize = 1 << 18;

/// How the parameters of interpolation points are chosen (seed 000).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Parameterization {
    /// `t_i = i`.
    #[default]
    Uniform,
    /// Steps proportional to the chord lengths `|p_{i+1} − p_i|`.
    Chord,
    /// Steps proportional to the square roots of the chord lengths.
    Centripetal,
}

impl Parameterization {
    /// Parameters of `points` in order, starting at 0 and scaled so that the
    /// last is `points.len() − 1` (the uniform range).
    ///
    /// # Errors
    /// [`CurveError::CoincidentPoints`] for neighbours at one place (chord
    /// and centripetal only).
    pub fn parameters(self, points: &[DVec3]) -> Result<Vec<f64>, CurveError> {
        let n = points.len();
        if self == Parameterization::Uniform || n < 2 {
            return Ok((0..n).map(|i| i as f64).collect());
        }
        let mut t = vec![0.0];
        for i in 1..n {
            let d = (points[i] - points[i - 1]).length();
            if d <= 1e-300 {
                return Err(CurveError::CoincidentPoints {
                    index: i - 1,
                    next: i,
                });
            }
            let step = if self == Parameterization::Chord {
                d
            } else {
                d.sqrt()
            };
            t.push(t[i - 1] + step);
        }
        let scale = (n - 1) as f64 / t[n - 1];
        Ok(t.into_iter().map(|x| x * scale).collect())
    }
}

/// The end conditions of the interpolating C2 cubic spline.
#[derive(Copy, Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum SplineEnds {
    /// Zero second derivative at both ends.
    #[default]
    Natural,
    /// Given first derivatives (dp/dt) at the ends.
    Clamped {
        /// The derivative at the first point.
        start: DVec3,
        /// The derivative at the last point.
        end: DVec3,
    },
    /// A closed loop, C2 everywhere including the closing point.
    Closed,
}

/// How two cubic segments of a poly-Bézier meet at a joint.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Join {
    /// Position only: the handles move freely (a corner).
    C0,
    /// Equal derivatives: the handles mirror each other (Blender's
    /// "aligned" with equal lengths; Inkscape's symmetric node).
    C1,
    /// Equal tangent direction: the handles are collinear, their lengths
    /// free (Inkscape's smooth node).
    #[default]
    G1,
    /// Handles placed from the neighbouring anchors and re-placed whenever
    /// an anchor moves (Blender's "auto"): along the chord from the
    /// previous anchor to the next, each a third of the distance to its
    /// neighbour, so the joint is G1. Dragging one of its handles makes
    /// the joint G1 (Blender turns it "aligned").
    Auto,
}

/// A fractal replacement rule of the Koch family: every segment becomes
/// `N` segments `r` times as long (seed 004).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum FractalRule {
    /// Koch: 4 segments of 1/3 with a triangular bump; D = log 4 / log 3.
    #[default]
    Koch,
    /// Quadratic Koch (Minkowski sausage): 8 segments of 1/4 with a square
    /// bump up and one down; D = log 8 / log 4 = 1.5.
    QuadraticKoch,
}

impl FractalRule {
    /// The generator: points along a unit segment as (along, to the side).
    pub fn generator(self) -> &'static [(f64, f64)] {
        const H: f64 = 0.288_675_134_594_812_9; // √3 / 6
        match self {
            FractalRule::Koch => &[
                (0.0, 0.0),
                (1.0 / 3.0, 0.0),
                (0.5, H),
                (2.0 / 3.0, 0.0),
                (1.0, 0.0),
            ],
            FractalRule::QuadraticKoch => &[
                (0.0, 0.0),
                (0.25, 0.0),
                (0.25, 0.25),
                (0.5, 0.25),
                (0.5, 0.0),
                (0.5, -0.25),
                (0.75, -0.25),
                (0.75, 0.0),
                (1.0, 0.0),
            ],
        }
    }
    /// `N`, the segments one segment becomes.
    pub fn pieces(self) -> usize {
        self.generator().len() - 1
    }
    /// `r`, the length of each piece relative to the segment.
    pub fn ratio(self) -> f64 {
        match self {
            FractalRule::Koch => 1.0 / 3.0,
            FractalRule::QuadraticKoch => 0.25,
        }
    }
    /// The Hausdorff (similarity) dimension `log N / log(1/r)` (seed 004).
    pub fn dimension(self) -> f64 {
        (self.pieces() as f64).ln() / (1.0 / self.ratio()).ln()
    }
}

/// Which end of an open curve.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum CurveEnd {
    /// The first point.
    Start,
    /// The last point.
    #[default]
    End,
}

/// A curve as the user defined it. See the module documentation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum CurveKind {
    /// A NURBS curve, its own NURBS form.
    Nurbs(NurbsCurve),
    /// The polynomial of degree n − 1 through n points.
    Lagrange {
        /// The interpolated points (at least 2).
        points: Vec<DVec3>,
        /// How their parameters are chosen.
        #[serde(default)]
        parameterization: Parameterization,
    },
    /// Cubic Hermite segments through points with given derivatives, at
    /// parameters 0, 1, 2, …
    CubicHermite {
        /// The points (at least 2).
        points: Vec<DVec3>,
        /// dp/dt at each point.
        tangents: Vec<DVec3>,
    },
    /// Quintic Hermite segments (C2): points with first and second
    /// derivatives, at parameters 0, 1, 2, … (seed 002).
    QuinticHermite {
        /// The points (at least 2).
        points: Vec<DVec3>,
        /// dp/dt at each point.
        tangents: Vec<DVec3>,
        /// d²p/dt² at each point.
        accelerations: Vec<DVec3>,
    },
    /// The Catmull-Rom spline through the points.
    CatmullRom {
        /// The points (at least 2; 3 closed).
        points: Vec<DVec3>,
        /// How their parameters are chosen.
        #[serde(default)]
        parameterization: Parameterization,
        /// A closed loop (tangents wrap around).
        #[serde(default)]
        closed: bool,
    },
    /// The Kochanek-Bartels spline: tension, bias, continuity per key,
    /// uniform parameters.
    KochanekBartels {
        /// The points (at least 2; 3 closed).
        points: Vec<DVec3>,
        /// One key per point.
        keys: Vec<Tbc>,
        /// A closed loop.
        #[serde(default)]
        closed: bool,
    },
    /// The interpolating C2 cubic spline (seed 004).
    CubicSpline {
        /// The points (at least 2; 3 closed).
        points: Vec<DVec3>,
        /// How their parameters are chosen.
        #[serde(default)]
        parameterization: Parameterization,
        /// Natural, clamped or closed.
        #[serde(default)]
        ends: SplineEnds,
    },
    /// Chaikin's corner cutting of a control polygon, `level` times.
    Chaikin {
        /// The control polygon (at least 2; 3 closed).
        points: Vec<DVec3>,
        /// How many times the corners are cut.
        level: u32,
        /// A closed polygon.
        #[serde(default)]
        closed: bool,
    },
    /// Cubic Bézier segments sharing end points: anchors at 0, 3, 6, …,
    /// handles between. Open: `3k + 1` points for k segments, `k − 1`
    /// joins (joint j at anchor `3(j + 1)`). Closed: `3k` points, the last
    /// segment ends at point 0, `k` joins (joint j at anchor `3j`).
    PolyBezier {
        /// Anchors and handles.
        points: Vec<DVec3>,
        /// The continuity kept at each joint.
        joins: Vec<Join>,
        /// A closed chain.
        #[serde(default)]
        closed: bool,
    },
    /// A fractal of the Koch family at a level: every segment of the
    /// initiator polygon replaced `level` times by the rule's generator,
    /// bumps on the left of each segment seen from `normal` (so a
    /// clockwise triangle grows the Koch snowflake).
    Fractal {
        /// The replacement rule.
        rule: FractalRule,
        /// The initiator polygon (at least 2; 3 closed).
        points: Vec<DVec3>,
        /// How many times segments are replaced.
        level: u32,
        /// A closed initiator (the snowflake).
        #[serde(default)]
        closed: bool,
        /// The plane's normal; bumps go to `normal × segment`.
        normal: DVec3,
    },
}

/// A tangent drawn as a handle at a key of a Hermite-family curve: the
/// segment from the key's point to `end`, which is the Bézier control point
/// next to the key in the NURBS form (`p ± m·h/d` for tangent `m`, span
/// length `h` and degree `d`), so the handles are the Bézier polygon.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct TangentHandle {
    /// The key's index among the defining points.
    pub point: usize,
    /// True for the incoming tangent (drawn backwards from the point).
    pub incoming: bool,
    /// The handle's far end.
    pub end: DVec3,
}

/// The NURBS form of a curve kind.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsForm {
    /// The curve.
    pub curve: NurbsCurve,
    /// `None` when exact (to rounding); else the largest measured distance
    /// between the NURBS form and the kind's curve.
    pub tolerance: Option<f64>,
}

fn too_few(kind: &'static str, needed: usize, got: usize) -> Result<(), CurveError> {
    if got < needed {
        Err(CurveError::KindTooFewPoints { kind, needed, got })
    } else {
        Ok(())
    }
}

fn count(points: usize, what: &'static str, got: usize) -> Result<(), CurveError> {
    if got == points {
        Ok(())
    } else {
        Err(CurveError::CountMismatch { points, what, got })
    }
}

/// Solves the tridiagonal system `a_i x_{i−1} + b_i x_i + c_i x_{i+1} = d_i`
/// (Thomas algorithm, O(n); `a[0]` and `c[n−1]` are ignored).
fn thomas(a: &[f64], b: &[f64], c: &[f64], d: &[DVec3]) -> Vec<DVec3> {
    let n = b.len();
    let (mut b, mut d) = (b.to_vec(), d.to_vec());
    for i in 1..n {
        let w = a[i] / b[i - 1];
        b[i] -= w * c[i - 1];
        let prev = d[i - 1];
        d[i] -= w * prev;
    }
    let mut x = vec![DVec3::ZERO; n];
    x[n - 1] = d[n - 1] / b[n - 1];
    for i in (0..n - 1).rev() {
        x[i] = (d[i] - c[i] * x[i + 1]) / b[i];
    }
    x
}

/// The cyclic tridiagonal system (`a[0]` couples `x_{n−1}` into row 0,
/// `c[n−1]` couples `x_0` into the last row), by Sherman-Morrison
/// (Numerical Recipes §2.7), O(n); n ≥ 3.
fn cyclic_thomas(a: &[f64], b: &[f64], c: &[f64], d: &[DVec3]) -> Vec<DVec3> {
    let n = b.len();
    let (alpha, beta) = (c[n - 1], a[0]);
    let gamma = -b[0];
    let mut bb = b.to_vec();
    bb[0] -= gamma;
    bb[n - 1] -= alpha * beta / gamma;
    let x = thomas(a, &bb, c, d);
    let mut u = vec![DVec3::ZERO; n];
    u[0] = DVec3::splat(gamma);
    u[n - 1] = DVec3::splat(alpha);
    let z = thomas(a, &bb, c, &u);
    let fact = (x[0] + beta * x[n - 1] / gamma) / (1.0 + z[0].x + beta * z[n - 1].x / gamma);
    x.iter().zip(&z).map(|(xi, zi)| *xi - fact * zi.x).collect()
}

/// Kochanek-Bartels tangents of a closed loop (the open case is
/// [`HermiteSpline::kochanek_bartels`]): keys wrap around.
fn closed_kb(
    points: &[DVec3],
    keys: &[Tbc],
    params: Vec<f64>,
) -> Result<HermiteSpline, CurveError> {
    let n = points.len();
    let mut out = Vec::with_capacity(n + 1);
    let mut inc = Vec::with_capacity(n + 1);
    for i in 0..n {
        let (prev, next) = (points[(i + n - 1) % n], points[(i + 1) % n]);
        let Tbc {
            tension: t,
            bias: b,
            continuity: c,
        } = keys[i];
        let (before, after) = (points[i] - prev, next - points[i]);
        let o = (1.0 - t) * (1.0 + b) * (1.0 + c) / 2.0 * before
            + (1.0 - t) * (1.0 - b) * (1.0 - c) / 2.0 * after;
        let d = (1.0 - t) * (1.0 + b) * (1.0 - c) / 2.0 * before
            + (1.0 - t) * (1.0 - b) * (1.0 + c) / 2.0 * after;
        let h_prev = if i == 0 {
            params[n] - params[n - 1]
        } else {
            params[i] - params[i - 1]
        };
        let per_t = 2.0 / (h_prev + params[i + 1] - params[i]);
        out.push(per_t * o);
        inc.push(per_t * d);
    }
    out.push(out[0]);
    inc.push(inc[0]);
    let mut ext = points.to_vec();
    ext.push(points[0]);
    let mut s = HermiteSpline::new(params, ext, out)?;
    s.incoming = inc;
    Ok(s)
}

/// The C2 cubic spline with clamped or closed ends (natural ends are
/// [`c2_cubic_spline`]); seed 004's tridiagonal system for the tangents.
fn c2_spline(
    points: &[DVec3],
    parameterization: Parameterization,
    ends: SplineEnds,
) -> Result<HermiteSpline, CurveError> {
    let n = points.len();
    match ends {
        SplineEnds::Natural => {
            c2_cubic_spline(parameterization.parameters(points)?, points.to_vec())
        }
        SplineEnds::Clamped { start, end } => {
            check_points(&[start, end]).map_err(|_| CurveError::NotFiniteVector {
                what: "an end tangent",
            })?;
            let t = parameterization.parameters(points)?;
            let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
            let (mut a, mut b, mut c) = (vec![0.0; n], vec![1.0; n], vec![0.0; n]);
            let mut d = vec![DVec3::ZERO; n];
            d[0] = start;
            d[n - 1] = end;
            for i in 1..n - 1 {
                a[i] = h[i];
                b[i] = 2.0 * (h[i - 1] + h[i]);
                c[i] = h[i - 1];
                d[i] = 3.0
                    * (h[i] / h[i - 1] * (points[i] - points[i - 1])
                        + h[i - 1] / h[i] * (points[i + 1] - points[i]));
            }
            HermiteSpline::new(t, points.to_vec(), thomas(&a, &b, &c, &d))
        }
        SplineEnds::Closed => {
            let mut ext = points.to_vec();
            ext.push(points[0]);
            let t = closed_parameters(parameterization, points)?;
            let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
            let (mut a, mut b, mut c) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            let mut d = vec![DVec3::ZERO; n];
            for i in 0..n {
                let (hp, hn) = (h[(i + n - 1) % n], h[i]);
                let (prev, next) = (points[(i + n - 1) % n], points[(i + 1) % n]);
                a[i] = hn;
                b[i] = 2.0 * (hp + hn);
                c[i] = hp;
                d[i] = 3.0 * (hn / hp * (points[i] - prev) + hp / hn * (next - points[i]));
            }
            let mut m = cyclic_thomas(&a, &b, &c, &d);
            m.push(m[0]);
            HermiteSpline::new(t, ext, m)
        }
    }
}

/// Parameters of a closed loop: the points and the first again.
fn closed_parameters(p: Parameterization, points: &[DVec3]) -> Result<Vec<f64>, CurveError> {
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
fn hermite_to_nurbs(h: &HermiteSpline) -> Result<NurbsCurve, CurveError> {
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

/// A polyline as a degree-1 NURBS, uniform parameters on [0, 1].
fn polyline(points: Vec<DVec3>) -> Result<NurbsCurve, CurveError> {
    NurbsCurve::clamped(1, points)
}

/// The largest value of `f` on `[a, b]`: the best of 8 equal steps, then a
/// golden-section search (Kiefer 1953; *Numerical Recipes*, 3rd ed., §10.2)
/// between that sample's neighbours, 48 steps. Exact for a function with
/// one bump between neighbouring samples, as the error of an interpolating
/// spline between two of its nodes has (zero at both, one hump between).
fn interval_max(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    const STEPS: usize = 8;
    let x = |k: usize| a + (b - a) * k as f64 / STEPS as f64;
    let (mut best_k, mut best) = (0, f(a));
    for k in 1..=STEPS {
        let y = f(x(k));
        if y > best {
            (best_k, best) = (k, y);
        }
    }
    let (mut lo, mut hi) = (x(best_k.saturating_sub(1)), x((best_k + 1).min(STEPS)));
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut c, mut d) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..48 {
        if fc > fd {
            (hi, d, fd) = (d, c, fc);
            c = hi - g * (hi - lo);
            fc = f(c);
        } else {
            (lo, c, fc) = (c, d, fd);
            d = lo + g * (hi - lo);
            fd = f(d);
        }
    }
    best.max(fc).max(fd)
}

/// The Lagrange polynomial through `points` at `params`, at `t`, by the
/// barycentric formula (stable for any degree; seed 000's Vandermonde
/// system gives the same polynomial). O(n²).
pub fn lagrange_point(params: &[f64], points: &[DVec3], t: f64) -> DVec3 {
    let n = params.len();
    let mut num = DVec3::ZERO;
    let mut den = 0.0;
    for j in 0..n {
        let d = t - params[j];
        if d == 0.0 {
            return points[j];
        }
        let w: f64 = (0..n)
            .filter(|&k| k != j)
            .map(|k| 1.0 / (params[j] - params[k]))
            .product();
        num += w / d * points[j];
        den += w / d;
    }
    num / den
}

fn reverse_closed<T: Clone>(v: &[T]) -> Vec<T> {
    let mut r = vec![v[0].clone()];
    r.extend(v[1..].iter().rev().cloned());
    r
}

fn remove_indices<T: Clone>(v: &[T], gone: &[usize]) -> Vec<T> {
    v.iter()
        .enumerate()
        .filter(|(i, _)| !gone.contains(i))
        .map(|(_, x)| x.clone())
        .collect()
}

impl CurveKind {
    /// The kind's name for messages and panels ("Catmull-Rom", …).
    pub fn name(&self) -> &'static str {
        match self {
            CurveKind::Nurbs(_) => "NURBS",
            CurveKind::Lagrange { .. } => "Lagrange",
            CurveKind::CubicHermite { .. } => "cubic Hermite",
            CurveKind::QuinticHermite { .. } => "quintic Hermite",
            CurveKind::CatmullRom { .. } => "Catmull-Rom",
            CurveKind::KochanekBartels { .. } => "Kochanek-Bartels",
            CurveKind::CubicSpline { .. } => "C2 cubic spline",
            CurveKind::Chaikin { .. } => "Chaikin",
            CurveKind::PolyBezier { .. } => "poly-Bézier",
            CurveKind::Fractal {
                rule: FractalRule::Koch,
                ..
            } => "Koch",
            CurveKind::Fractal {
                rule: FractalRule::QuadraticKoch,
                ..
            } => "quadratic Koch",
        }
    }

    /// The defining points the user edits: NURBS control points,
    /// interpolation points, a poly-Bézier's anchors and handles, a
    /// Chaikin control polygon, a fractal's initiator.
    pub fn points(&self) -> &[DVec3] {
        match self {
            CurveKind::Nurbs(c) => c.points(),
            CurveKind::Lagrange { points, .. }
            | CurveKind::CubicHermite { points, .. }
            | CurveKind::QuinticHermite { points, .. }
            | CurveKind::CatmullRom { points, .. }
            | CurveKind::KochanekBartels { points, .. }
            | CurveKind::CubicSpline { points, .. }
            | CurveKind::Chaikin { points, .. }
            | CurveKind::PolyBezier { points, .. }
            | CurveKind::Fractal { points, .. } => points,
        }
    }

    /// The tangent handles of a Hermite-family kind (cubic and quintic
    /// Hermite, Catmull-Rom, Kochanek-Bartels, C2 spline): at each key an
    /// incoming one (but the first of an open curve) and an outgoing one
    /// (but the last), in that order. Empty for the other kinds.
    pub fn tangent_handles(&self) -> Vec<TangentHandle> {
        let (keys, degree) = match self {
            CurveKind::QuinticHermite {
                points,
                tangents,
                accelerations: _,
            } => (
                HermiteSpline {
                    params: (0..points.len()).map(|i| i as f64).collect(),
                    points: points.clone(),
                    tangents: tangents.clone(),
                    incoming: tangents.clone(),
                },
                5.0,
            ),
            _ => match self.hermite() {
                Ok(Some(h)) => (h, 3.0),
                _ => return Vec::new(),
            },
        };
        let n = self.points().len();
        let closed = self.is_closed();
        let t = &keys.params;
        let mut out = Vec::with_capacity(2 * n);
        for i in 0..n {
            let p = keys.points[i];
            if i > 0 || closed {
                // The span before key i (for a closed curve's first key:
                // the closing span, at the end of the parameters).
                let (h, m) = if i == 0 {
                    let last = t.len() - 1;
                    (t[last] - t[last - 1], keys.incoming[last])
                } else {
                    (t[i] - t[i - 1], keys.incoming[i])
                };
                out.push(TangentHandle {
                    point: i,
                    incoming: true,
                    end: p - m * h / degree,
                });
            }
            if i + 1 < n || closed {
                out.push(TangentHandle {
                    point: i,
                    incoming: false,
                    end: p + keys.tangents[i] * (t[i + 1] - t[i]) / degree,
                });
            }
        }
        out
    }

    /// True when the tangent handles are defining data a user drags (cubic
    /// and quintic Hermite); for the other Hermite kinds they are derived
    /// from the points and shown only.
    pub fn handles_editable(&self) -> bool {
        matches!(
            self,
            CurveKind::CubicHermite { .. } | CurveKind::QuinticHermite { .. }
        )
    }

    /// The points a user edits: the [defining points](Self::points), then
    /// for the kinds with [editable handles](Self::handles_editable) the
    /// ends of their [tangent handles](Self::tangent_handles), numbered on
    /// after the points (what [`set_points`](Self::set_points) takes).
    pub fn edit_points(&self) -> Vec<DVec3> {
        let mut all = self.points().to_vec();
        if self.handles_editable() {
            all.extend(self.tangent_handles().iter().map(|h| h.end));
        }
        all
    }

    fn points_mut(&mut self) -> Option<&mut Vec<DVec3>> {
        match self {
            CurveKind::Nurbs(_) => None,
            CurveKind::Lagrange { points, .. }
            | CurveKind::CubicHermite { points, .. }
            | CurveKind::QuinticHermite { points, .. }
            | CurveKind::CatmullRom { points, .. }
            | CurveKind::KochanekBartels { points, .. }
            | CurveKind::CubicSpline { points, .. }
            | CurveKind::Chaikin { points, .. }
            | CurveKind::PolyBezier { points, .. }
            | CurveKind::Fractal { points, .. } => Some(points),
        }
    }

    /// True for a closed loop (a NURBS curve: its ends meet).
    pub fn is_closed(&self) -> bool {
        match self {
            CurveKind::Nurbs(c) => {
                let (a, b) = c.domain();
                (c.point(a) - c.point(b)).length() < 1e-12
            }
            CurveKind::Lagrange { .. }
            | CurveKind::CubicHermite { .. }
            | CurveKind::QuinticHermite { .. } => false,
            CurveKind::CatmullRom { closed, .. }
            | CurveKind::KochanekBartels { closed, .. }
            | CurveKind::Chaikin { closed, .. }
            | CurveKind::PolyBezier { closed, .. }
            | CurveKind::Fractal { closed, .. } => *closed,
            CurveKind::CubicSpline { ends, .. } => *ends == SplineEnds::Closed,
        }
    }

    /// True for kinds whose curve passes through every defining point at
    /// [`key_parameters`](Self::key_parameters).
    pub fn interpolates(&self) -> bool {
        matches!(
            self,
            CurveKind::Lagrange { .. }
                | CurveKind::CubicHermite { .. }
                | CurveKind::QuinticHermite { .. }
                | CurveKind::CatmullRom { .. }
                | CurveKind::KochanekBartels { .. }
                | CurveKind::CubicSpline { .. }
        )
    }

    /// The Hermite form of the Hermite-family kinds (cubic Hermite,
    /// Catmull-Rom, Kochanek-Bartels, C2 spline); `None` for the others.
    ///
    /// # Errors
    /// As [`check`](Self::check).
    pub fn hermite(&self) -> Result<Option<HermiteSpline>, CurveError> {
        self.check_counts()?;
        Ok(Some(match self {
            CurveKind::CubicHermite { points, tangents } => HermiteSpline::new(
                (0..points.len()).map(|i| i as f64).collect(),
                points.clone(),
                tangents.clone(),
            )?,
            CurveKind::CatmullRom {
                points,
                parameterization,
                closed,
            } => {
                let keys = vec![Tbc::default(); points.len()];
                if *closed {
                    closed_kb(points, &keys, closed_parameters(*parameterization, points)?)?
                } else {
                    HermiteSpline::kochanek_bartels(
                        parameterization.parameters(points)?,
                        points.clone(),
                        &keys,
                    )?
                }
            }
            CurveKind::KochanekBartels {
                points,
                keys,
                closed,
            } => {
                let t: Vec<f64> = (0..points.len() + usize::from(*closed))
                    .map(|i| i as f64)
                    .collect();
                if *closed {
                    closed_kb(points, keys, t)?
                } else {
                    HermiteSpline::kochanek_bartels(t, points.clone(), keys)?
                }
            }
            CurveKind::CubicSpline {
                points,
                parameterization,
                ends,
            } => c2_spline(points, *parameterization, *ends)?,
            _ => return Ok(None),
        }))
    }

    /// The parameters (of the NURBS form) at which an interpolating kind
    /// passes through its points, in order; a closed kind also lists the
    /// closing parameter (back at point 0). Empty for the others.
    ///
    /// # Errors
    /// As [`check`](Self::check).
    pub fn key_parameters(&self) -> Result<Vec<f64>, CurveError> {
        if let Some(h) = self.hermite()? {
            return Ok(h.params);
        }
        Ok(match self {
            CurveKind::Lagrange {
                points,
                parameterization,
            } => parameterization.parameters(points)?,
            CurveKind::QuinticHermite { points, .. } => {
                (0..points.len()).map(|i| i as f64).collect()
            }
            _ => Vec::new(),
        })
    }

    fn check_counts(&self) -> Result<(), CurveError> {
        let name = self.name();
        let least = if self.is_closed() { 3 } else { 2 };
        check_points(self.points())?;
        match self {
            CurveKind::Nurbs(_) => Ok(()),
            CurveKind::Lagrange { points, .. } | CurveKind::CatmullRom { points, .. } => {
                too_few(name, least, points.len())
            }
            CurveKind::CubicHermite { points, tangents } => {
                too_few(name, 2, points.len())?;
                count(points.len(), "tangents", tangents.len())?;
                check_points(tangents)
                    .map_err(|_| CurveError::NotFiniteVector { what: "a tangent" })
            }
            CurveKind::QuinticHermite {
                points,
                tangents,
                accelerations,
            } => {
                too_few(name, 2, points.len())?;
                count(points.len(), "tangents", tangents.len())?;
                count(points.len(), "accelerations", accelerations.len())?;
                check_points(tangents)
                    .map_err(|_| CurveError::NotFiniteVector { what: "a tangent" })?;
                check_points(accelerations).map_err(|_| CurveError::NotFiniteVector {
                    what: "an acceleration",
                })
            }
            CurveKind::KochanekBartels { points, keys, .. } => {
                too_few(name, least, points.len())?;
                count(points.len(), "T/B/C keys", keys.len())?;
                if keys.iter().any(|k| {
                    !(k.tension.is_finite() && k.bias.is_finite() && k.continuity.is_finite())
                }) {
                    return Err(CurveError::NotFiniteVector {
                        what: "a T/B/C key",
                    });
                }
                Ok(())
            }
            CurveKind::CubicSpline { points, .. } => too_few(name, least, points.len()),
            CurveKind::Chaikin {
                points,
                level,
                closed,
            } => {
                too_few(name, least, points.len())?;
                let edges = points.len() - usize::from(!closed);
                let max = (0..=20u32)
                    .take_while(|&l| edges << l <= MAX_LEVEL_POINTS)
                    .last()
                    .unwrap_or(0);
                if *level > max {
                    return Err(CurveError::LevelTooHigh { level: *level, max });
                }
                Ok(())
            }
            CurveKind::PolyBezier {
                points,
                joins,
                closed,
            } => {
                let (needed, per) = if *closed { (3, 0) } else { (4, 1) };
                too_few(name, needed, points.len())?;
                if (points.len() - per) % 3 != 0 {
                    return Err(CurveError::CountMismatch {
                        points: points.len(),
                        what: if *closed {
                            "a multiple of 3 points (3 per segment)"
                        } else {
                            "3k + 1 points (3 per segment and one)"
                        },
                        got: points.len(),
                    });
                }
                let segments = (points.len() - per) / 3;
                count(segments - per, "joins", joins.len())
            }
            CurveKind::Fractal {
                rule,
                points,
                level,
                closed,
                normal,
            } => {
                too_few(name, least, points.len())?;
                if !normal.is_finite() || normal.length_squared() < 1e-24 {
                    return Err(CurveError::NotFiniteVector {
                        what: "the fractal's plane normal",
                    });
                }
                let edges = points.len() - usize::from(!closed);
                let mut max = 0;
                while edges * rule.pieces().pow(max + 1) <= MAX_LEVEL_POINTS {
                    max += 1;
                }
                if *level > max {
                    return Err(CurveError::LevelTooHigh { level: *level, max });
                }
                Ok(())
            }
        }
    }

    /// Checks the kind's data: enough points, matching list lengths,
    /// finite values, a level that stays below [`MAX_LEVEL_POINTS`].
    ///
    /// # Errors
    /// The first problem, named ([`CurveError::KindTooFewPoints`]: "Lagrange
    /// needs 2 points or more, got 1").
    pub fn check(&self) -> Result<(), CurveError> {
        self.to_nurbs().map(|_| ())
    }

    /// The polygon a Chaikin or fractal kind draws at its level (degree-1
    /// NURBS form's points); `None` for other kinds.
    pub fn level_polygon(&self) -> Option<Vec<DVec3>> {
        match self {
            CurveKind::Chaikin {
                points,
                level,
                closed,
            } => {
                let mut p = chaikin(points, *level, *closed);
                if *closed {
                    p.push(p[0]);
                }
                Some(p)
            }
            CurveKind::Fractal {
                rule,
                points,
                level,
                closed,
                normal,
            } => {
                let n = normal.normalize();
                let mut poly = points.clone();
                if *closed {
                    poly.push(points[0]);
                }
                let generator = rule.generator();
                for _ in 0..*level {
                    let mut next = vec![poly[0]];
                    for w in poly.windows(2) {
                        let d = w[1] - w[0];
                        let side = n.cross(d);
                        next.extend(generator[1..].iter().map(|&(u, v)| w[0] + u * d + v * side));
                    }
                    poly = next;
                }
                Some(poly)
            }
            _ => None,
        }
    }

    /// The NURBS form (see the module documentation for where it is exact).
    /// O(n) for the piecewise kinds, O(n³) for exact Lagrange, O(4^level)
    /// for Koch.
    ///
    /// # Errors
    /// As [`check`](Self::check).
    pub fn to_nurbs(&self) -> Result<NurbsForm, CurveError> {
        self.check_counts()?;
        if let Some(h) = self.hermite()? {
            return Ok(NurbsForm {
                curve: hermite_to_nurbs(&h)?,
                tolerance: None,
            });
        }
        if let Some(poly) = self.level_polygon() {
            return Ok(NurbsForm {
                curve: polyline(poly)?,
                tolerance: None,
            });
        }
        let exact = |curve| {
            Ok(NurbsForm {
                curve,
                tolerance: None,
            })
        };
        match self {
            CurveKind::Nurbs(c) => exact(c.clone()),
            CurveKind::QuinticHermite {
                points,
                tangents: v,
                accelerations: a,
            } => {
                let mut cp = vec![points[0]];
                let mut knots = vec![0.0; 6];
                let segs = points.len() - 1;
                for i in 0..segs {
                    let (p0, p1) = (points[i], points[i + 1]);
                    cp.extend([
                        p0 + v[i] / 5.0,
                        p0 + 2.0 * v[i] / 5.0 + a[i] / 20.0,
                        p1 - 2.0 * v[i + 1] / 5.0 + a[i + 1] / 20.0,
                        p1 - v[i + 1] / 5.0,
                        p1,
                    ]);
                    let reps = if i + 1 == segs { 6 } else { 5 };
                    knots.extend(std::iter::repeat_n((i + 1) as f64, reps));
                }
                let w = vec![1.0; cp.len()];
                exact(NurbsCurve::new(5, knots, cp, w)?)
            }
            CurveKind::PolyBezier { points, closed, .. } => {
                let mut cp = points.clone();
                if *closed {
                    cp.push(points[0]);
                }
                let segs = (cp.len() - 1) / 3;
                let mut knots = vec![0.0; 4];
                for i in 1..=segs {
                    let reps = if i == segs { 4 } else { 3 };
                    knots.extend(std::iter::repeat_n(i as f64, reps));
                }
                let w = vec![1.0; cp.len()];
                exact(NurbsCurve::new(3, knots, cp, w)?)
            }
            CurveKind::Lagrange {
                points,
                parameterization,
            } => {
                let t = parameterization.parameters(points)?;
                let n = points.len();
                let (t0, t1) = (t[0], t[n - 1]);
                if n <= LAGRANGE_EXACT_POINTS {
                    let deg = n - 1;
                    let m = t
                        .iter()
                        .map(|&ti| {
                            let s = (ti - t0) / (t1 - t0);
                            (0..n).map(|j| bernstein(deg, j, s)).collect()
                        })
                        .collect();
                    let cp = solve_dense(m, points.clone())?;
                    let mut knots = vec![t0; n];
                    knots.extend(vec![t1; n]);
                    return exact(NurbsCurve::new(deg, knots, cp, vec![1.0; n])?);
                }
                // Dense samples through the (stable, barycentric) polynomial,
                // interpolated by a C2 cubic spline; the error is the largest
                // over every interval between two samples, each searched
                // ([`interval_max`]).
                let per = 32;
                let m = per * (n - 1);
                let ts: Vec<f64> = (0..=m)
                    .map(|i| t0 + (t1 - t0) * i as f64 / m as f64)
                    .collect();
                let ps: Vec<DVec3> = ts.iter().map(|&x| lagrange_point(&t, points, x)).collect();
                let h = c2_cubic_spline(ts.clone(), ps)?;
                let curve = hermite_to_nurbs(&h)?;
                let error = |x: f64| (curve.point(x) - lagrange_point(&t, points, x)).length();
                let tolerance = ts
                    .windows(2)
                    .map(|w| interval_max(&error, w[0], w[1]))
                    .fold(0.0, f64::max);
                Ok(NurbsForm {
                    curve,
                    tolerance: Some(tolerance),
                })
            }
            _ => unreachable!("the Hermite family and the level polygons returned above"),
        }
    }

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
                let (l, r) = super::Bezier { points: seg }.split(s);
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

    fn reversed_if(self, yes: bool) -> Result<CurveKind, CurveError> {
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
