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
//! Each kind is its own type in its own module ([`Lagrange`] in
//! `lagrange.rs`, [`PolyBezier`] in `poly_bezier.rs`, …; a NURBS curve is
//! [`NurbsCurve`] itself, in `nurbs.rs`) and answers the questions and
//! edits of one trait, [`KindRules`]; `CurveKind` holds one of them and
//! hands each call to it in one place (the `each_kind!` macro). What is
//! the same for every kind stays here and in `conversion.rs` (the NURBS
//! form), `editing.rs` (point edits) and `reshape.rs` (whole-curve edits);
//! `wire.rs` keeps the stored (RON) form that of the struct variants the
//! kinds once were, so older scene files load and re-save unchanged.
//!
//! Every edit ([`set_points`](CurveKind::set_points),
//! [`insert_point`](CurveKind::insert_point), …) returns a new value and
//! leaves `self` untouched; a refused edit returns a named [`CurveError`].

use super::interpolating::HermiteSpline;
use super::nurbs::NurbsCurve;
use super::{CurveError, check_points};
use glam::{DMat4, DVec3};
use serde::{Deserialize, Serialize};

/// `match` on a [`CurveKind`] (a value or a reference) with one arm per
/// kind, binding the kind's own value to `$k`: the one place where a call
/// is handed to the kind. Call the kind's [`KindRules`] methods in `$body`
/// by path (`KindRules::reversed(k)`), as [`NurbsCurve`] has inherent
/// methods of the same names.
macro_rules! each_kind {
    ($value:expr, $k:ident => $body:expr) => {
        match $value {
            CurveKind::Nurbs($k) => $body,
            CurveKind::Lagrange($k) => $body,
            CurveKind::CubicHermite($k) => $body,
            CurveKind::QuinticHermite($k) => $body,
            CurveKind::CatmullRom($k) => $body,
            CurveKind::KochanekBartels($k) => $body,
            CurveKind::CubicSpline($k) => $body,
            CurveKind::Chaikin($k) => $body,
            CurveKind::PolyBezier($k) => $body,
            CurveKind::Fractal($k) => $body,
        }
    };
    // Two values of one kind; `$other` for two of different kinds.
    ($a:expr, $b:expr, ($x:ident, $y:ident) => $body:expr, _ => $other:expr) => {
        match ($a, $b) {
            (CurveKind::Nurbs($x), CurveKind::Nurbs($y)) => $body,
            (CurveKind::Lagrange($x), CurveKind::Lagrange($y)) => $body,
            (CurveKind::CubicHermite($x), CurveKind::CubicHermite($y)) => $body,
            (CurveKind::QuinticHermite($x), CurveKind::QuinticHermite($y)) => $body,
            (CurveKind::CatmullRom($x), CurveKind::CatmullRom($y)) => $body,
            (CurveKind::KochanekBartels($x), CurveKind::KochanekBartels($y)) => $body,
            (CurveKind::CubicSpline($x), CurveKind::CubicSpline($y)) => $body,
            (CurveKind::Chaikin($x), CurveKind::Chaikin($y)) => $body,
            (CurveKind::PolyBezier($x), CurveKind::PolyBezier($y)) => $body,
            (CurveKind::Fractal($x), CurveKind::Fractal($y)) => $body,
            _ => $other,
        }
    };
}

mod catmull_rom;
mod chaikin;
mod conversion;
mod cubic_hermite;
mod cubic_spline;
mod editing;
mod fractal;
mod kochanek_bartels;
mod lagrange;
mod nurbs;
mod poly_bezier;
mod quintic_hermite;
mod reshape;
mod wire;

pub use catmull_rom::CatmullRom;
pub use chaikin::Chaikin;
pub use cubic_hermite::CubicHermite;
pub use cubic_spline::CubicSpline;
pub use fractal::Fractal;
pub use kochanek_bartels::KochanekBartels;
pub use lagrange::{Lagrange, lagrange_point};
pub use poly_bezier::PolyBezier;
pub use quintic_hermite::QuinticHermite;

use conversion::{closed_parameters, hermite_nurbs, hermite_to_nurbs, polyline};
use reshape::{neg, rev, reverse_closed};

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

/// A curve as the user defined it: one of the kinds, each its own type
/// with its own rules ([`KindRules`]). See the module documentation.
///
/// Stored (RON) as the struct variants of before
/// (`Lagrange(points: […], parameterization: Chord)`), not as newtype
/// variants holding a struct: see `wire.rs`.
#[derive(Clone, Debug, PartialEq)]
pub enum CurveKind {
    /// A NURBS curve, its own NURBS form.
    Nurbs(NurbsCurve),
    /// The polynomial of degree n − 1 through n points.
    Lagrange(Lagrange),
    /// Cubic Hermite segments through points with given derivatives, at
    /// parameters 0, 1, 2, …
    CubicHermite(CubicHermite),
    /// Quintic Hermite segments (C2): points with first and second
    /// derivatives, at parameters 0, 1, 2, … (seed 002).
    QuinticHermite(QuinticHermite),
    /// The Catmull-Rom spline through the points.
    CatmullRom(CatmullRom),
    /// The Kochanek-Bartels spline: tension, bias, continuity per key,
    /// uniform parameters.
    KochanekBartels(KochanekBartels),
    /// The interpolating C2 cubic spline (seed 004).
    CubicSpline(CubicSpline),
    /// Chaikin's corner cutting of a control polygon, `level` times.
    Chaikin(Chaikin),
    /// Cubic Bézier segments sharing end points, with a join per joint.
    PolyBezier(PolyBezier),
    /// A fractal of the Koch family at a level.
    Fractal(Fractal),
}

macro_rules! kind_from {
    ($($variant:ident($ty:ty)),* $(,)?) => {
        $(impl From<$ty> for CurveKind {
            fn from(kind: $ty) -> CurveKind {
                CurveKind::$variant(kind)
            }
        })*
    };
}

kind_from!(
    Nurbs(NurbsCurve),
    Lagrange(Lagrange),
    CubicHermite(CubicHermite),
    QuinticHermite(QuinticHermite),
    CatmullRom(CatmullRom),
    KochanekBartels(KochanekBartels),
    CubicSpline(CubicSpline),
    Chaikin(Chaikin),
    PolyBezier(PolyBezier),
    Fractal(Fractal),
);

/// What each curve kind answers and does in its own way; [`CurveKind`]'s
/// methods check what is the same for every kind (indices, finite
/// positions, the result's [`check`](CurveKind::check)) and hand the rest
/// to its kind through these. The defaults are those of a kind whose only
/// data per point is the point itself ([`points_mut`](Self::points_mut)).
pub trait KindRules: Clone + Into<CurveKind> {
    /// The kind's name for messages and panels ("Catmull-Rom", …).
    fn name(&self) -> &'static str;
    /// The defining points the user edits.
    fn points(&self) -> &[DVec3];
    /// The defining points as the list the default edits change; `None`
    /// for a kind that keeps them otherwise (NURBS), which overrides every
    /// default that uses it.
    fn points_mut(&mut self) -> Option<&mut Vec<DVec3>>;
    /// True for a closed loop.
    fn is_closed(&self) -> bool {
        false
    }
    /// True when the curve passes through every defining point at
    /// [`key_parameters`](Self::key_parameters).
    fn interpolates(&self) -> bool {
        false
    }
    /// True when the tangent handles are defining data a user drags.
    fn handles_editable(&self) -> bool {
        false
    }
    /// The kind's own checks of its data (counts, lists of matching
    /// lengths, finite values, the level), after the points' own.
    ///
    /// # Errors
    /// The first problem, named.
    fn check_data(&self) -> Result<(), CurveError>;
    /// The points finite and distinct enough, then
    /// [`check_data`](Self::check_data).
    ///
    /// # Errors
    /// The first problem, named.
    fn checked(&self) -> Result<(), CurveError> {
        check_points(self.points())?;
        self.check_data()
    }
    /// The Hermite form of a Hermite-family kind, its data unchecked;
    /// `None` for the others.
    ///
    /// # Errors
    /// What the solver finds (coincident points for chord parameters).
    fn hermite_form(&self) -> Result<Option<HermiteSpline>, CurveError> {
        Ok(None)
    }
    /// The keys its tangent handles are drawn from and their degree; by
    /// default the checked Hermite form, cubic.
    fn handle_keys(&self) -> Option<(HermiteSpline, f64)> {
        match self.checked().and_then(|()| self.hermite_form()) {
            Ok(Some(h)) => Some((h, 3.0)),
            _ => None,
        }
    }
    /// The key parameters of an interpolating kind without a Hermite form;
    /// empty for the others.
    ///
    /// # Errors
    /// What the parameterization finds.
    fn own_key_parameters(&self) -> Result<Vec<f64>, CurveError> {
        Ok(Vec::new())
    }
    /// The parameters (of the NURBS form) at which the curve passes
    /// through its points, checked: the Hermite form's, else
    /// [`own_key_parameters`](Self::own_key_parameters).
    ///
    /// # Errors
    /// As [`checked`](Self::checked).
    fn key_parameters(&self) -> Result<Vec<f64>, CurveError> {
        self.checked()?;
        if let Some(h) = self.hermite_form()? {
            return Ok(h.params);
        }
        self.own_key_parameters()
    }
    /// The polygon a Chaikin or fractal kind draws at its level.
    fn level_polygon(&self) -> Option<Vec<DVec3>> {
        None
    }
    /// The NURBS form of data already checked.
    ///
    /// # Errors
    /// What the construction finds.
    fn nurbs_form(&self) -> Result<NurbsForm, CurveError>;
    /// Moves defining points (indices checked); indices past the points
    /// name the `handles` of a kind with editable handles.
    ///
    /// # Errors
    /// What the kind refuses.
    fn move_points(
        &mut self,
        moves: &[(usize, DVec3)],
        handles: &[TangentHandle],
    ) -> Result<(), CurveError> {
        let _ = handles;
        let count = self.points().len();
        let points = self.points_mut().expect("a kind with a list of points");
        for &(i, p) in moves.iter().filter(|m| m.0 < count) {
            points[i] = p;
        }
        Ok(())
    }
    /// Maps the data by the affine map `m` (points by it, vectors by its
    /// linear part).
    ///
    /// # Errors
    /// A map that makes a value non-finite.
    fn transform(&mut self, m: &DMat4) -> Result<(), CurveError> {
        let points = self.points_mut().expect("a kind with a list of points");
        *points = map_points(m, points);
        Ok(())
    }
    /// A kind's own exact insertion at parameter `t` (the new curve and
    /// the new point's index), instead of [`insert_at`](Self::insert_at).
    fn insert_exact(&self, t: f64) -> Option<Result<(CurveKind, usize), CurveError>> {
        let _ = t;
        None
    }
    /// How many spans a parameter falls among when the kind has no key
    /// parameters: the polygon's edges.
    fn edges(&self) -> usize {
        self.points().len() - usize::from(!self.is_closed())
    }
    /// Inserts a point in span `(i, s)` (index and fraction) at index `at`
    /// (`i + 1`), given the curve's point and first two derivatives there;
    /// returns the new point's index.
    fn insert_at(&mut self, span: (usize, f64), at: usize, curve: [DVec3; 3]) -> usize {
        let _ = span;
        let points = self.points_mut().expect("a kind with a list of points");
        points.insert(at, curve[0]);
        at
    }
    /// The parameter at which the curve passes through defining point
    /// `index`, if it does.
    fn on_curve_parameter(&self, index: usize) -> Option<f64> {
        if self.interpolates() {
            self.key_parameters().ok()?.get(index).copied()
        } else {
            None
        }
    }
    /// A kind's own exact split at `t`, instead of inserting a point and
    /// cutting there.
    fn split_exact(&self, t: f64) -> Option<Result<(CurveKind, CurveKind), CurveError>> {
        let _ = t;
        None
    }
    /// Deletes the defining points `gone` (sorted, distinct, existing).
    ///
    /// # Errors
    /// What the kind refuses.
    fn delete(&mut self, gone: &[usize]) -> Result<(), CurveError> {
        let points = self.points_mut().expect("a kind with a list of points");
        *points = remove_indices(points, gone);
        Ok(())
    }
    /// Adds a point after the last one.
    ///
    /// # Errors
    /// What the kind refuses.
    fn push_end(&mut self, to: DVec3) -> Result<(), CurveError> {
        self.points_mut()
            .expect("a kind with a list of points")
            .push(to);
        Ok(())
    }
    /// The same curve traced the other way.
    ///
    /// # Errors
    /// A rebuilt value that is not valid.
    fn reversed(&self) -> Result<Self, CurveError>;
    /// Opens or closes the curve; by default refused.
    ///
    /// # Errors
    /// A kind that cannot be closed.
    fn set_closed(&mut self, closed: bool) -> Result<(), CurveError> {
        Err(CurveError::NotForKind {
            operation: if closed { "closing" } else { "opening" },
            kind: self.name(),
        })
    }
    /// One half of a split at defining point `k`: up to and with `k`
    /// (`left`) or from `k` on.
    fn keep(&mut self, k: usize, left: bool) {
        let points = self.points_mut().expect("a kind with a list of points");
        cubic_hermite::keep(points, k, left);
    }
    /// Appends `other`'s data, its first `skip` points left out (its start
    /// already at this end).
    ///
    /// # Errors
    /// What the kind refuses.
    fn append(&mut self, other: &Self, skip: usize) -> Result<(), CurveError> {
        let more = other.points()[skip..].to_vec();
        self.points_mut()
            .expect("a kind with a list of points")
            .extend_from_slice(&more);
        Ok(())
    }
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

/// The fewest points of an open (2) or closed (3) curve.
fn least(closed: bool) -> usize {
    if closed { 3 } else { 2 }
}

/// Points mapped by the affine map `m`.
fn map_points(m: &DMat4, v: &[DVec3]) -> Vec<DVec3> {
    v.iter().map(|x| m.transform_point3(*x)).collect()
}

/// Vectors mapped by the linear part of `m`.
fn map_vectors(m: &DMat4, v: &[DVec3]) -> Vec<DVec3> {
    v.iter().map(|x| m.transform_vector3(*x)).collect()
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
        each_kind!(self, k => KindRules::name(k))
    }

    /// The defining points the user edits: NURBS control points,
    /// interpolation points, a poly-Bézier's anchors and handles, a
    /// Chaikin control polygon, a fractal's initiator.
    pub fn points(&self) -> &[DVec3] {
        each_kind!(self, k => KindRules::points(k))
    }

    /// The tangent handles of a Hermite-family kind (cubic and quintic
    /// Hermite, Catmull-Rom, Kochanek-Bartels, C2 spline): at each key an
    /// incoming one (but the first of an open curve) and an outgoing one
    /// (but the last), in that order. Empty for the other kinds.
    pub fn tangent_handles(&self) -> Vec<TangentHandle> {
        let Some((keys, degree)) = each_kind!(self, k => KindRules::handle_keys(k)) else {
            return Vec::new();
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
        each_kind!(self, k => KindRules::handles_editable(k))
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

    /// True for a closed loop (a NURBS curve: its ends meet).
    pub fn is_closed(&self) -> bool {
        each_kind!(self, k => KindRules::is_closed(k))
    }

    /// True for kinds whose curve passes through every defining point at
    /// [`key_parameters`](Self::key_parameters).
    pub fn interpolates(&self) -> bool {
        each_kind!(self, k => KindRules::interpolates(k))
    }

    fn check_counts(&self) -> Result<(), CurveError> {
        each_kind!(self, k => KindRules::checked(k))
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
