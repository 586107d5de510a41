//! Surfaces made from curves and joins made between patches (issue 20):
//!
//! - [`coons`]: the bilinearly blended Coons patch from four boundary curves
//!   (Coons 1967; the bilinear patch it subtracts is seed 003's), as an
//!   exact NURBS surface;
//! - [`gordon`]: the Gordon surface through a network of curves (Gordon
//!   1971; Piegl & Tiller, *The NURBS Book*, §10.5), as a NURBS surface;
//! - [`tri_quad`]: the exercise of seed 002, a Bézier triangle and a
//!   tensor-product Bézier patch joined along a shared edge with C0 and G1
//!   continuity, kept G1 while control points are dragged.
//!
//! The NURBS constructions work on homogeneous control points (`w·x, w·y,
//! w·z, w`): every operator they use (knot insertion, degree elevation,
//! interpolation, the Boolean sum) is linear on them, so rational boundary
//! curves (circle arcs) come out exactly. Every constructor returns a new
//! value and leaves its inputs untouched; a failure is a [`PatchError`].

pub mod coons;
pub mod gordon;
pub mod tri_quad;

use glam::{DVec3, DVec4};

use super::NurbsSurface;
use crate::curves::nurbs::basis_derivatives;
use crate::curves::{CurveError, NurbsCurve};

pub use coons::{CoonsBoundaries, CoonsReport, coons, coons_report};
pub use gordon::{Gordon, GordonReport, NetworkParams, gordon, gordon_report};
pub use tri_quad::{JointReport, PatchPoint, PointRole, SharedEdge, TriangleQuad};

/// Why a patch cannot be made from its curves, or a join cannot be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PatchError {
    /// Two boundary curves of a Coons patch do not meet at a corner.
    #[error(
        "the boundaries do not meet at corner {corner}: gap {gap} is more than the tolerance {tolerance}"
    )]
    CornerGap {
        /// The corner, as `"(u=0, v=0)"`.
        corner: &'static str,
        /// Distance between the two curves' ends there.
        gap: f64,
        /// The tolerance given.
        tolerance: f64,
    },
    /// Four curves that do not close into one loop (for
    /// [`CoonsBoundaries::from_loop`]).
    #[error(
        "curve {curve} has no neighbour within {tolerance} of its end: the curves do not close a loop"
    )]
    NotALoop {
        /// Index of the curve whose end found no next curve.
        curve: usize,
        /// The tolerance given.
        tolerance: f64,
    },
    /// A Gordon network with fewer than two curves in a direction.
    #[error("a curve network needs at least 2 {direction}-curves, got {got}")]
    TooFewCurves {
        /// `"u"` or `"v"`.
        direction: &'static str,
        /// The number given.
        got: usize,
    },
    /// Given intersection parameters of the wrong count.
    #[error("{curves} {direction}-curves need {curves} parameters, got {got}")]
    ParameterCount {
        /// `"u"` or `"v"`: which curves the parameters belong to.
        direction: &'static str,
        /// Number of curves.
        curves: usize,
        /// Number of parameters given.
        got: usize,
    },
    /// Intersection parameters that do not strictly increase in [0, 1].
    #[error("{direction}-parameter {index} ({value}) does not increase within [0, 1]")]
    ParametersOutOfOrder {
        /// `"u"` or `"v"`.
        direction: &'static str,
        /// Index of the first parameter out of order.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A u-curve and a v-curve of a network that do not meet at all.
    #[error("u-curve {u_curve} and v-curve {v_curve} do not meet: they pass {distance} apart")]
    CurvesDoNotMeet {
        /// Index of the u-curve (as given).
        u_curve: usize,
        /// Index of the v-curve (as given).
        v_curve: usize,
        /// Their least distance.
        distance: f64,
    },
    /// The v-curves do not cross the u-curves in the same order on every
    /// u-curve (or the other way round), so no surface parameterisation
    /// holds them all.
    #[error(
        "the {direction}-curves cross {across}-curve {curve} in another order than the first one"
    )]
    CrossingOrder {
        /// `"u"` or `"v"`: the curves whose order differs.
        direction: &'static str,
        /// `"u"` or `"v"`: the curves they cross.
        across: &'static str,
        /// Index of the crossed curve where the order differs.
        curve: usize,
    },
    /// The network is inconsistent: at the common parameters, a u-curve and
    /// a v-curve are apart (the curves meet at different parameters on
    /// different curves, or not at all).
    #[error(
        "inconsistent network: u-curve {u_curve} at u = {u} and v-curve {v_curve} at v = {v} are {gap} apart (tolerance {tolerance})"
    )]
    NetworkGap {
        /// Index of the u-curve (in the surface's order).
        u_curve: usize,
        /// Index of the v-curve (in the surface's order).
        v_curve: usize,
        /// The u-curve's parameter there.
        u: f64,
        /// The v-curve's parameter there.
        v: f64,
        /// Distance between the two points.
        gap: f64,
        /// The tolerance given.
        tolerance: f64,
    },
    /// A rational network whose curves carry different weights where they
    /// cross: the Boolean sum in homogeneous space would not interpolate.
    #[error(
        "u-curve {u_curve} and v-curve {v_curve} have different weights where they cross ({first} and {second})"
    )]
    WeightsDisagree {
        /// Index of the u-curve.
        u_curve: usize,
        /// Index of the v-curve.
        v_curve: usize,
        /// The u-curve's weight there.
        first: f64,
        /// The v-curve's weight there.
        second: f64,
    },
    /// The construction needs a control point of weight zero or below: the
    /// rational boundaries are too far from one another's weights.
    #[error(
        "the patch would need weight {value} at control point {index}: weights must be positive"
    )]
    NonPositiveWeight {
        /// Index `i * nv + j` of the control point.
        index: usize,
        /// The weight it would need.
        value: f64,
    },
    /// A Bézier triangle and a patch that share no edge.
    #[error(
        "the triangle and the patch share no edge: the nearest pair of edge ends is {nearest_gap} apart (tolerance {tolerance})"
    )]
    NoSharedEdge {
        /// Largest corner distance of the best edge pairing.
        nearest_gap: f64,
        /// The tolerance given.
        tolerance: f64,
    },
    /// A [`SharedEdge`] naming something that is not an edge of the right
    /// patch (a quad side for the triangle, or the other way round).
    #[error("{boundary:?} is not an edge of the {patch}")]
    NotAnEdge {
        /// The boundary given.
        boundary: super::joins::Boundary,
        /// `"triangle"` or `"patch"`.
        patch: &'static str,
    },
    /// A [`SharedEdge`] whose ends are apart on the two patches.
    #[error("the edge's ends are {gap} apart on the two patches (tolerance {tolerance})")]
    EdgeEndsApart {
        /// Largest distance between corresponding ends.
        gap: f64,
        /// The tolerance given.
        tolerance: f64,
    },
    /// The patches' degrees along the shared edge differ: make them C0
    /// first ([`TriangleQuad::make_c0`]).
    #[error(
        "the edge has degree {triangle} on the triangle and {quad} on the patch: make the join C0 first"
    )]
    NotJoined {
        /// Degree of the triangle.
        triangle: usize,
        /// Degree of the patch along the edge.
        quad: usize,
    },
    /// The triangle's tangent plane along the edge is undefined (the edge
    /// or the row next to it collapsed), so there is no plane to share.
    #[error("the triangle is degenerate along the edge: its tangent plane there is undefined")]
    DegenerateEdge,
    /// A point of a patch that does not exist.
    #[error("the {patch} has no control point {index} (it has {count})")]
    NoSuchPoint {
        /// `"triangle"` or `"patch"`.
        patch: &'static str,
        /// The index given.
        index: usize,
        /// The number of control points.
        count: usize,
    },
    /// A position that is NaN or infinite.
    #[error("the new position is not finite")]
    NotFinite,
    /// A curve operation failed (a curve that is not valid, a singular
    /// interpolation).
    #[error(transparent)]
    Curve(#[from] CurveError),
}

/// The same curve on the domain [0, 1] with clamped ends (its ends are its
/// first and last control points): unclamped knot vectors are clamped
/// ([`NurbsCurve::clamped_ends`]), then the knots are mapped affinely. The
/// constructions here parameterise their curves this way.
///
/// # Errors
/// None for a valid curve (kept for the constructors' `?`).
pub fn unit_domain(curve: &NurbsCurve) -> Result<NurbsCurve, CurveError> {
    let c = curve.clamped_ends();
    let (a, b) = (c.knots()[c.degree()], c.knots()[c.points().len()]);
    let knots = c
        .knots()
        .iter()
        .map(|&k| ((k - a) / (b - a)).clamp(0.0, 1.0))
        .collect();
    NurbsCurve::new(c.degree(), knots, c.points().to_vec(), c.weights().to_vec())
}

/// The same curve run backwards on [0, 1] (`t ↦ 1 − t`); `curve` must have
/// the domain [0, 1].
pub(crate) fn reversed(curve: &NurbsCurve) -> NurbsCurve {
    let rev = |v: &[f64]| v.iter().rev().copied().collect::<Vec<_>>();
    NurbsCurve::new(
        curve.degree(),
        curve.knots().iter().rev().map(|&k| 1.0 - k).collect(),
        curve.points().iter().rev().copied().collect(),
        rev(curve.weights()),
    )
    .expect("reversing a valid curve")
}

/// The same point set as the clamped curve `curve` on [0, 1] with both end
/// weights 1: the parameter is changed by the rational linear map
/// `u = (1 + γ) s / (1 + γ s)` that keeps 0 and 1, with `(1 + γ)^p =
/// w_0 / w_n`, then the weights are divided by `w_0`. Under that map each
/// basis function `N_i(u(s))`, times `(1 + γ s)^p`, is the B-spline on the
/// mapped knots `s_i` times `Π_{j=1..p} (1 + γ s_{i+j})`, so the new weights
/// are `w_i` times that product (Piegl & Tiller §6.4, reparameterisation
/// by a linear rational function). Curves whose end weights are equal are
/// only scaled. A Coons patch in homogeneous coordinates needs the weights
/// of the curves meeting at a corner to agree; this makes them all 1.
pub fn unit_end_weights(curve: &NurbsCurve) -> NurbsCurve {
    let p = curve.degree();
    let w = curve.weights();
    let (w0, wn) = (w[0], w[w.len() - 1]);
    if w0 == wn {
        if w0 == 1.0 {
            return curve.clone();
        }
        let weights = w.iter().map(|x| x / w0).collect();
        return NurbsCurve::new(p, curve.knots().to_vec(), curve.points().to_vec(), weights)
            .expect("scaling the weights of a valid curve");
    }
    let gamma = (w0 / wn).powf(1.0 / p as f64) - 1.0;
    // s = u / (1 + γ − γ u), the inverse of u = (1 + γ) s / (1 + γ s).
    let knots: Vec<f64> = curve
        .knots()
        .iter()
        .map(|&u| (u / (1.0 + gamma - gamma * u)).clamp(0.0, 1.0))
        .collect();
    let weights = (0..w.len())
        .map(|i| {
            let factor: f64 = (1..=p).map(|j| 1.0 + gamma * knots[i + j]).product();
            w[i] * factor / w0
        })
        .collect();
    NurbsCurve::new(p, knots, curve.points().to_vec(), weights)
        .expect("a linear rational reparameterisation of a valid curve")
}

/// The curves on [0, 1] with one degree (the highest, by degree elevation)
/// and one knot vector (the union of theirs, each value with its highest
/// multiplicity, by knot insertion): the same shapes, now with control
/// points that correspond (The NURBS Book §10.3, "compatibility").
pub(crate) fn compatible(curves: &[NurbsCurve]) -> Result<Vec<NurbsCurve>, CurveError> {
    let degree = curves.iter().map(NurbsCurve::degree).max().unwrap_or(1);
    let mut out = Vec::with_capacity(curves.len());
    for c in curves {
        let mut c = c.clone();
        while c.degree() < degree {
            c = c.elevate_degree()?;
        }
        out.push(c);
    }
    let merged = merged_knots(out.iter().map(NurbsCurve::knots));
    out.iter()
        .map(|c| c.refine(&missing_knots(c.knots(), &merged)))
        .collect()
}

/// Every knot value of the vectors with its highest multiplicity among them.
fn merged_knots<'a>(vectors: impl Iterator<Item = &'a [f64]>) -> Vec<f64> {
    let mut merged: Vec<f64> = Vec::new();
    for v in vectors {
        let missing = missing_knots(&merged, v);
        merged.extend(missing);
        merged.sort_by(f64::total_cmp);
    }
    merged
}

/// The knots of `target` that `have` lacks (counting multiplicity).
fn missing_knots(have: &[f64], target: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    let mut k = 0;
    while k < target.len() {
        let value = target[k];
        let want = target[k..].iter().take_while(|&&x| x == value).count();
        let got = have.iter().filter(|&&x| x == value).count();
        out.extend(std::iter::repeat_n(value, want.saturating_sub(got)));
        k += want;
    }
    out
}

/// The homogeneous control points of a curve.
pub(crate) fn homogeneous(curve: &NurbsCurve) -> Vec<DVec4> {
    curve
        .points()
        .iter()
        .zip(curve.weights())
        .map(|(&p, &w)| (p * w).extend(w))
        .collect()
}

/// The knot span holding `t` (the last non-empty one at the domain's end).
fn find_span(knots: &[f64], degree: usize, count: usize, t: f64) -> usize {
    let n = count - 1;
    if t >= knots[n + 1] {
        let mut i = n;
        while i > degree && knots[i] >= knots[n + 1] {
            i -= 1;
        }
        return i;
    }
    let mut i = degree;
    while i < n && knots[i + 1] <= t {
        i += 1;
    }
    i
}

/// The values at `t` of all `count` basis functions of degree `degree` on
/// `knots` (zero outside their support).
pub(crate) fn basis_row(knots: &[f64], degree: usize, count: usize, t: f64) -> Vec<f64> {
    let span = find_span(knots, degree, count, t);
    let values = &basis_derivatives(knots, span, t, degree, 0)[0];
    let mut row = vec![0.0; count];
    for (r, &v) in values.iter().enumerate() {
        row[span - degree + r] = v;
    }
    row
}

/// A net of homogeneous control points `pw[i * nv + j]` with degrees and
/// knots in u and v: the working form of the constructions, on which
/// elevation, refinement and sums are linear.
#[derive(Clone, Debug)]
pub(crate) struct Net {
    pub pu: usize,
    pub pv: usize,
    pub ku: Vec<f64>,
    pub kv: Vec<f64>,
    pub nu: usize,
    pub nv: usize,
    pub pw: Vec<DVec4>,
}

/// A sequence of homogeneous points as two polynomial curves, `xyz` and
/// `(w, 0, 0)`: knot insertion and degree elevation of a polynomial curve
/// are linear in its points, so doing them on both is doing them on the
/// homogeneous points (whatever the sign of the weights).
fn split4(degree: usize, knots: &[f64], pw: &[DVec4]) -> Result<[NurbsCurve; 2], CurveError> {
    let ones = vec![1.0; pw.len()];
    Ok([
        NurbsCurve::new(
            degree,
            knots.to_vec(),
            pw.iter().map(|h| h.truncate()).collect(),
            ones.clone(),
        )?,
        NurbsCurve::new(
            degree,
            knots.to_vec(),
            pw.iter().map(|h| DVec3::new(h.w, 0.0, 0.0)).collect(),
            ones,
        )?,
    ])
}

type CurveOp<'a> = &'a dyn Fn(&NurbsCurve) -> Result<NurbsCurve, CurveError>;

impl Net {
    /// A net from a homogeneous grid.
    pub fn new(
        (pu, ku): (usize, Vec<f64>),
        (pv, kv): (usize, Vec<f64>),
        nu: usize,
        nv: usize,
        pw: Vec<DVec4>,
    ) -> Net {
        debug_assert_eq!(pw.len(), nu * nv);
        Net {
            pu,
            pv,
            ku,
            kv,
            nu,
            nv,
            pw,
        }
    }

    /// `op` applied to every column (a curve in u).
    fn map_u(&self, op: CurveOp) -> Result<Net, CurveError> {
        let mut columns = Vec::with_capacity(self.nv);
        for j in 0..self.nv {
            let seq: Vec<DVec4> = (0..self.nu).map(|i| self.pw[i * self.nv + j]).collect();
            let [a, b] = split4(self.pu, &self.ku, &seq)?;
            columns.push((op(&a)?, op(&b)?));
        }
        let (first, _) = &columns[0];
        let nu = first.points().len();
        let mut pw = vec![DVec4::ZERO; nu * self.nv];
        for (j, (a, b)) in columns.iter().enumerate() {
            for i in 0..nu {
                pw[i * self.nv + j] = a.points()[i].extend(b.points()[i].x);
            }
        }
        Ok(Net {
            pu: first.degree(),
            ku: first.knots().to_vec(),
            nu,
            pw,
            ..self.clone()
        })
    }

    /// The net with u and v exchanged.
    fn transposed(&self) -> Net {
        let mut pw = Vec::with_capacity(self.pw.len());
        for j in 0..self.nv {
            for i in 0..self.nu {
                pw.push(self.pw[i * self.nv + j]);
            }
        }
        Net {
            pu: self.pv,
            pv: self.pu,
            ku: self.kv.clone(),
            kv: self.ku.clone(),
            nu: self.nv,
            nv: self.nu,
            pw,
        }
    }

    fn map_v(&self, op: CurveOp) -> Result<Net, CurveError> {
        Ok(self.transposed().map_u(op)?.transposed())
    }

    /// The same surface with degrees raised to `(pu, pv)`.
    fn elevated(&self, pu: usize, pv: usize) -> Result<Net, CurveError> {
        let mut net = self.clone();
        while net.pu < pu {
            net = net.map_u(&NurbsCurve::elevate_degree)?;
        }
        while net.pv < pv {
            net = net.map_v(&NurbsCurve::elevate_degree)?;
        }
        Ok(net)
    }

    /// `Σ factor_k · net_k` over nets of the same surfaces' domain [0, 1]²:
    /// every net is elevated to the highest degrees and refined to the
    /// union of the knot vectors, then the homogeneous points are summed.
    pub fn sum(terms: &[(f64, &Net)]) -> Result<Net, CurveError> {
        let pu = terms.iter().map(|(_, n)| n.pu).max().expect("terms");
        let pv = terms.iter().map(|(_, n)| n.pv).max().expect("terms");
        let elevated: Vec<Net> = terms
            .iter()
            .map(|(_, n)| n.elevated(pu, pv))
            .collect::<Result<_, _>>()?;
        let ku = merged_knots(elevated.iter().map(|n| n.ku.as_slice()));
        let kv = merged_knots(elevated.iter().map(|n| n.kv.as_slice()));
        let mut total: Option<Net> = None;
        for ((factor, _), net) in terms.iter().zip(&elevated) {
            let add_u = missing_knots(&net.ku, &ku);
            let add_v = missing_knots(&net.kv, &kv);
            let net = net
                .map_u(&|c| c.refine(&add_u))?
                .map_v(&|c| c.refine(&add_v))?;
            match &mut total {
                None => {
                    let mut first = net;
                    first.pw.iter_mut().for_each(|h| *h *= *factor);
                    total = Some(first);
                }
                Some(t) => {
                    for (a, b) in t.pw.iter_mut().zip(&net.pw) {
                        *a += *factor * *b;
                    }
                }
            }
        }
        Ok(total.expect("terms"))
    }

    /// The NURBS surface of the net.
    ///
    /// # Errors
    /// [`PatchError::NonPositiveWeight`] for a weight that is not positive.
    pub fn into_surface(self) -> Result<NurbsSurface, PatchError> {
        if let Some((index, h)) = self
            .pw
            .iter()
            .enumerate()
            .find(|(_, h)| !(h.w.is_finite() && h.w > 0.0))
        {
            return Err(PatchError::NonPositiveWeight { index, value: h.w });
        }
        let points = self.pw.iter().map(|h| h.truncate() / h.w).collect();
        let weights = self.pw.iter().map(|h| h.w).collect();
        Ok(NurbsSurface::new(
            self.pu, self.pv, self.ku, self.kv, self.nu, self.nv, points, weights,
        )?)
    }
}

/// Solves `m x = rhs` for several right-hand sides of homogeneous points at
/// once (Gaussian elimination with partial pivoting).
pub(crate) fn solve_many(
    mut m: Vec<Vec<f64>>,
    mut rhs: Vec<Vec<DVec4>>,
) -> Result<Vec<Vec<DVec4>>, CurveError> {
    let n = m.len();
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))
            .expect("rows remain");
        if m[pivot][col].abs() < 1e-14 {
            return Err(CurveError::Singular);
        }
        m.swap(col, pivot);
        rhs.swap(col, pivot);
        for row in col + 1..n {
            let f = m[row][col] / m[col][col];
            if f == 0.0 {
                continue;
            }
            let (above, below) = m.split_at_mut(row);
            for (x, y) in below[0][col..].iter_mut().zip(&above[col][col..]) {
                *x -= f * y;
            }
            let r = rhs[col].clone();
            for (x, y) in rhs[row].iter_mut().zip(&r) {
                *x -= f * *y;
            }
        }
    }
    let width = rhs.first().map_or(0, Vec::len);
    let mut x = vec![vec![DVec4::ZERO; width]; n];
    for row in (0..n).rev() {
        let mut s = rhs[row].clone();
        for k in row + 1..n {
            for (a, b) in s.iter_mut().zip(&x[k]) {
                *a -= m[row][k] * *b;
            }
        }
        x[row] = s.into_iter().map(|v| v / m[row][row]).collect();
    }
    Ok(x)
}

/// The interpolation knots for `params` (strictly increasing in [0, 1]) at
/// degree `degree`: clamped at 0 and 1, the inner ones averages of `degree`
/// consecutive parameters (The NURBS Book eq. 9.8), so that the matrix
/// `N_j(t_k)` is invertible (Schoenberg–Whitney).
pub(crate) fn averaged_knots(params: &[f64], degree: usize) -> Vec<f64> {
    let n = params.len() - 1;
    let mut knots = vec![0.0; degree + 1];
    for j in 1..=n - degree {
        knots.push(params[j..j + degree].iter().sum::<f64>() / degree as f64);
    }
    knots.extend(std::iter::repeat_n(1.0, degree + 1));
    knots
}

/// The spline of `degree` and `knots` through `rows[k]` at `params[k]`, for
/// every column of the rows at once: `out[k]` are the control points of
/// index k of each column (global interpolation, The NURBS Book §9.2.1).
pub(crate) fn interpolate(
    params: &[f64],
    degree: usize,
    knots: &[f64],
    rows: Vec<Vec<DVec4>>,
) -> Result<Vec<Vec<DVec4>>, CurveError> {
    let n = params.len();
    let m = params
        .iter()
        .map(|&t| basis_row(knots, degree, n, t))
        .collect();
    solve_many(m, rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curves::Curve;

    #[test]
    fn unit_end_weights_keeps_the_point_set_under_the_rational_map() {
        let c = NurbsCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0],
            vec![
                DVec3::ZERO,
                DVec3::new(1.0, 2.0, 0.0),
                DVec3::new(2.0, -1.0, 1.0),
                DVec3::new(3.0, 1.0, 0.0),
                DVec3::new(4.0, 0.0, 2.0),
            ],
            vec![2.0, 0.7, 1.5, 3.0, 0.5],
        )
        .unwrap();
        let d = unit_end_weights(&c);
        assert_eq!(d.weights()[0], 1.0);
        assert!((d.weights()[4] - 1.0).abs() < 1e-12, "{:?}", d.weights());
        let gamma = (2.0f64 / 0.5).powf(1.0 / 3.0) - 1.0;
        for k in 0..=200 {
            let s = k as f64 / 200.0;
            let u = (1.0 + gamma) * s / (1.0 + gamma * s);
            assert!(d.point(s).distance(c.point(u)) < 1e-12, "at s = {s}");
        }
    }

    #[test]
    fn compatible_curves_keep_their_shapes() {
        let a = NurbsCurve::clamped(2, vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z]).unwrap();
        let b = NurbsCurve::clamped(
            3,
            vec![DVec3::ONE, DVec3::X, DVec3::Y, DVec3::Z, DVec3::NEG_X],
        )
        .unwrap();
        let out = compatible(&[a.clone(), b.clone()]).unwrap();
        assert_eq!(out[0].degree(), 3);
        assert_eq!(out[0].knots(), out[1].knots());
        for k in 0..=50 {
            let t = k as f64 / 50.0;
            assert!(out[0].point(t).distance(a.point(t)) < 1e-12);
            assert!(out[1].point(t).distance(b.point(t)) < 1e-12);
        }
    }
}
