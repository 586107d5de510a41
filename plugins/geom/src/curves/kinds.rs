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

use super::interpolating::{HermiteSpline, Tbc};
use super::nurbs::NurbsCurve;
use super::{Curve, CurveError, check_points};
use glam::DVec3;
use serde::{Deserialize, Serialize};

mod conversion;
mod editing;
mod reshape;

pub use conversion::lagrange_point;

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
}
