//! Non-uniform rational B-spline curves (seed 004: B-spline basis, NUBS,
//! NURBS weights; seed 001: de Boor). Evaluation, derivatives, knot
//! insertion and degree elevation follow Piegl & Tiller, *The NURBS Book*
//! (2nd ed.): A2.1 `FindSpan`, A2.3 `DersBasisFuns`, eq. 4.8 for rational
//! derivatives, A5.1 (Boehm's knot insertion), and degree elevation by
//! decomposition into Bézier segments (§5.6), elevating each (eq. 5.36).

use glam::{DVec3, DVec4};

use super::{Curve, CurveError, check_points};

/// Which one-sided limit [`NurbsCurve::derivatives_on_side`] takes.
#[derive(Copy, Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Side {
    /// The limit from below: the piece that ends at the parameter.
    Before,
    /// The limit from above: the piece that starts at the parameter.
    After,
}

/// One rational Bézier segment of a NURBS curve: its parameter interval
/// `(start, end)` and its homogeneous control points (`w·x, w·y, w·z, w`).
pub type BezierSegment = ((f64, f64), Vec<DVec4>);

/// A NURBS curve: control points with weights, a degree and a knot vector
/// of `points + degree + 1` non-decreasing values. Its domain is
/// `[knots[degree], knots[points]]`; clamped, unclamped and periodic knot
/// vectors are all allowed. All weights 1 is a (non-rational) B-spline.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "NurbsCurveData", into = "NurbsCurveData")]
pub struct NurbsCurve {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<DVec3>,
    weights: Vec<f64>,
}

/// The stored form of a [`NurbsCurve`], validated on load.
#[derive(serde::Serialize, serde::Deserialize)]
pub struct NurbsCurveData {
    /// Polynomial degree p ≥ 1.
    pub degree: usize,
    /// Non-decreasing knot vector of `points + degree + 1` values.
    pub knots: Vec<f64>,
    /// Control points.
    pub points: Vec<DVec3>,
    /// Positive weight of each control point.
    pub weights: Vec<f64>,
}

impl TryFrom<NurbsCurveData> for NurbsCurve {
    type Error = CurveError;
    fn try_from(d: NurbsCurveData) -> Result<Self, CurveError> {
        NurbsCurve::new(d.degree, d.knots, d.points, d.weights)
    }
}

impl From<NurbsCurve> for NurbsCurveData {
    fn from(c: NurbsCurve) -> Self {
        NurbsCurveData {
            degree: c.degree,
            knots: c.knots,
            points: c.points,
            weights: c.weights,
        }
    }
}

fn homogeneous(p: DVec3, w: f64) -> DVec4 {
    (p * w).extend(w)
}

fn from_homogeneous(h: DVec4) -> (DVec3, f64) {
    (h.truncate() / h.w, h.w)
}

impl NurbsCurve {
    /// A curve from explicit data.
    ///
    /// # Errors
    /// A [`CurveError`] naming what is wrong: degree 0, too few points, the
    /// wrong number of knots, decreasing knots, an empty domain, a weight
    /// that is not positive, a non-finite number.
    ///
    /// # Example
    /// A quarter of the unit circle: degree 2, the middle weight √2/2.
    /// ```
    /// use hedra_geom::curves::{Curve, CurveError, NurbsCurve};
    /// use hedra_geom::DVec3;
    /// let w = std::f64::consts::FRAC_1_SQRT_2;
    /// let points = vec![DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    /// let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    /// let arc = NurbsCurve::new(2, knots.clone(), points.clone(), vec![1.0, w, 1.0])?;
    /// for i in 0..=10 {
    ///     let p = arc.point(i as f64 / 10.0);
    ///     assert!((p.length() - 1.0).abs() < 1e-12, "{p} is on the unit circle");
    /// }
    /// let mid = arc.point(0.5);
    /// assert!((mid - DVec3::new(w, w, 0.0)).length() < 1e-12);
    ///
    /// // A weight that is not positive is refused, naming it.
    /// let err = NurbsCurve::new(2, knots, points, vec![1.0, 0.0, 1.0]).unwrap_err();
    /// assert_eq!(err, CurveError::BadWeight { index: 1, value: 0.0 });
    /// # Ok::<(), CurveError>(())
    /// ```
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<DVec3>,
        weights: Vec<f64>,
    ) -> Result<Self, CurveError> {
        if degree == 0 {
            return Err(CurveError::ZeroDegree);
        }
        if points.len() < degree + 1 {
            return Err(CurveError::TooFewPoints {
                degree,
                needed: degree + 1,
                got: points.len(),
            });
        }
        check_points(&points)?;
        if weights.len() != points.len() {
            return Err(CurveError::WeightCount {
                points: points.len(),
                weights: weights.len(),
            });
        }
        if let Some((index, &value)) = weights
            .iter()
            .enumerate()
            .find(|(_, w)| !w.is_finite() || **w <= 0.0)
        // NaN is not finite
        {
            return Err(CurveError::BadWeight { index, value });
        }
        let needed = points.len() + degree + 1;
        if knots.len() != needed {
            return Err(CurveError::KnotCount {
                points: points.len(),
                degree,
                needed,
                got: knots.len(),
            });
        }
        if let Some(index) = knots.iter().position(|k| !k.is_finite()) {
            return Err(CurveError::NotFinite {
                what: "knot",
                index,
            });
        }
        if let Some(index) = (1..knots.len()).find(|&i| knots[i] < knots[i - 1]) {
            return Err(CurveError::DecreasingKnots {
                index,
                value: knots[index],
            });
        }
        if knots[degree] >= knots[points.len()] {
            return Err(CurveError::EmptyDomain);
        }
        Ok(NurbsCurve {
            degree,
            knots,
            points,
            weights,
        })
    }

    /// A B-spline (all weights 1) with a clamped uniform knot vector on
    /// [0, 1]: it starts and ends at its end control points.
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn clamped(degree: usize, points: Vec<DVec3>) -> Result<Self, CurveError> {
        let weights = vec![1.0; points.len()];
        let knots = clamped_uniform_knots(degree, points.len());
        Self::new(degree, knots, points, weights)
    }

    /// A closed (periodic) B-spline through no point in particular: the
    /// first `degree` control points are repeated at the end and the knots
    /// are uniform, so the curve closes with full continuity.
    ///
    /// # Errors
    /// As [`new`](Self::new) (the points before wrapping must be at least `degree + 1`).
    pub fn periodic(
        degree: usize,
        points: Vec<DVec3>,
        weights: Vec<f64>,
    ) -> Result<Self, CurveError> {
        if points.len() < degree + 1 {
            return Err(CurveError::TooFewPoints {
                degree,
                needed: degree + 1,
                got: points.len(),
            });
        }
        if weights.len() != points.len() {
            return Err(CurveError::WeightCount {
                points: points.len(),
                weights: weights.len(),
            });
        }
        let mut p = points.clone();
        p.extend_from_slice(&points[..degree]);
        let mut w = weights.clone();
        w.extend_from_slice(&weights[..degree]);
        let knots = (0..p.len() + degree + 1).map(|i| i as f64).collect();
        Self::new(degree, knots, p, w)
    }

    /// The exact unit-speed-free circle: degree 2, nine control points on a
    /// square around `center` in the XZ plane, weights 1 and √2/2
    /// alternating, knots at quarter turns (The NURBS Book, §7.5).
    pub fn circle(center: DVec3, radius: f64) -> Self {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let corners = [
            (1.0, 0.0),
            (1.0, 1.0),
            (0.0, 1.0),
            (-1.0, 1.0),
            (-1.0, 0.0),
            (-1.0, -1.0),
            (0.0, -1.0),
            (1.0, -1.0),
            (1.0, 0.0),
        ];
        let points = corners
            .iter()
            .map(|&(x, z)| center + radius * DVec3::new(x, 0.0, z))
            .collect();
        let weights = (0..9).map(|i| if i % 2 == 0 { 1.0 } else { s }).collect();
        let knots = vec![
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
        ];
        Self::new(2, knots, points, weights).expect("the circle's data is valid")
    }

    /// The curve under the affine map `m`: control points mapped, weights
    /// and knots kept, which is exact for NURBS (affine invariance, The
    /// NURBS Book §4.2). Its inverse is the map by `m.inverse()`.
    ///
    /// # Errors
    /// A map that makes a control point non-finite.
    ///
    /// Complexity: O(points).
    pub fn transformed(&self, m: &glam::DMat4) -> Result<NurbsCurve, CurveError> {
        let points: Vec<DVec3> = self.points.iter().map(|p| m.transform_point3(*p)).collect();
        check_points(&points)?;
        Ok(NurbsCurve {
            points,
            ..self.clone()
        })
    }

    /// Polynomial degree p.
    pub fn degree(&self) -> usize {
        self.degree
    }
    /// The knot vector (`points + degree + 1` values).
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }
    /// Control points (Cartesian, not multiplied by their weights).
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }
    /// Weight of each control point (all positive).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }
    /// True when every weight is 1 (a polynomial B-spline).
    pub fn is_polynomial(&self) -> bool {
        self.weights.iter().all(|&w| w == 1.0)
    }

    /// Moves control point `i`.
    ///
    /// # Errors
    /// No such point, or a non-finite position.
    pub fn set_point(&mut self, i: usize, p: DVec3) -> Result<(), CurveError> {
        self.check_index(i)?;
        check_points(&[p]).map_err(|_| CurveError::NotFinite {
            what: "control point",
            index: i,
        })?;
        self.points[i] = p;
        Ok(())
    }

    /// Changes the weight of control point `i` (pulls the curve towards
    /// the point when larger).
    ///
    /// # Errors
    /// No such point, or a weight that is not positive and finite (the
    /// curve would leave the convex hull or divide by zero).
    pub fn set_weight(&mut self, i: usize, w: f64) -> Result<(), CurveError> {
        self.check_index(i)?;
        if !w.is_finite() || w <= 0.0 {
            // NaN is not finite: refused too
            return Err(CurveError::BadWeight { index: i, value: w });
        }
        self.weights[i] = w;
        Ok(())
    }

    fn check_index(&self, i: usize) -> Result<(), CurveError> {
        if i < self.points.len() {
            Ok(())
        } else {
            Err(CurveError::NoSuchPoint {
                index: i,
                count: self.points.len(),
            })
        }
    }

    /// The knot span `i` with `knots[i] ≤ u < knots[i + 1]` (the last span
    /// for `u` at the end of the domain). A2.1.
    fn span(&self, u: f64) -> usize {
        let n = self.points.len() - 1;
        let p = self.degree;
        if u >= self.knots[n + 1] {
            // The last non-empty span.
            let mut i = n;
            while i > p && self.knots[i] >= self.knots[n + 1] {
                i -= 1;
            }
            return i;
        }
        if u <= self.knots[p] {
            let mut i = p;
            while self.knots[i + 1] <= u {
                i += 1;
            }
            return i;
        }
        let (mut low, mut high) = (p, n + 1);
        let mut mid = (low + high) / 2;
        while u < self.knots[mid] || u >= self.knots[mid + 1] {
            if u < self.knots[mid] {
                high = mid;
            } else {
                low = mid;
            }
            mid = (low + high) / 2;
        }
        mid
    }

    /// Homogeneous position and derivatives up to `order` (≤ 2) at `u`.
    fn homogeneous_derivatives(&self, u: f64, order: usize) -> [DVec4; 3] {
        let p = self.degree;
        let span = self.span(u);
        let ders = basis_derivatives(&self.knots, span, u, p, order);
        let mut out = [DVec4::ZERO; 3];
        for (k, row) in ders.iter().enumerate().take(order + 1) {
            for (j, &b) in row.iter().enumerate() {
                let i = span - p + j;
                out[k] += b * homogeneous(self.points[i], self.weights[i]);
            }
        }
        out
    }

    /// Position, first and second derivative at `t` as the limit from one
    /// side: [`Side::Before`] evaluates the polynomial (rational) piece of
    /// the knot span that ends at `t`, [`Side::After`] the one that starts
    /// there. Away from knots both equal [`Curve::derivatives`]; at a knot
    /// of multiplicity m they are the two one-sided limits whose agreement
    /// is the curve's C^(p−m) continuity there. At the domain's start
    /// `Before` gives the first span, at its end `After` the last (no
    /// curve lies beyond). `t` is clamped to the domain. O(p²).
    ///
    /// Source: The NURBS Book, A2.3 on the chosen span and eq. 4.8.
    pub fn derivatives_on_side(&self, t: f64, side: Side) -> [DVec3; 3] {
        let (start, end) = self.domain();
        let u = t.clamp(start, end);
        let p = self.degree;
        let span = match side {
            Side::After => self.span(u),
            Side::Before if u <= start => self.span(u),
            Side::Before => {
                // The span [k_i, k_{i+1}) with k_i < u ≤ k_{i+1}: not empty,
                // and p ≤ i ≤ n because start < u ≤ end.
                let i = self.knots.partition_point(|&k| k < u) - 1;
                i.clamp(p, self.points.len() - 1)
            }
        };
        let ders = basis_derivatives(&self.knots, span, u, p, 2);
        let mut h = [DVec4::ZERO; 3];
        for (k, row) in ders.iter().enumerate().take(3) {
            for (j, &b) in row.iter().enumerate() {
                let i = span - p + j;
                h[k] += b * homogeneous(self.points[i], self.weights[i]);
            }
        }
        let c0 = h[0].truncate() / h[0].w;
        let c1 = (h[1].truncate() - h[1].w * c0) / h[0].w;
        let c2 = (h[2].truncate() - 2.0 * h[1].w * c1 - h[2].w * c0) / h[0].w;
        [c0, c1, c2]
    }

    /// The Greville abscissae: for each control point the average of the
    /// `degree` knots after its first, `(k_{i+1} + … + k_{i+p}) / p`, the
    /// parameter "under" the point (a poly-Bézier's anchor sits at its
    /// joint's knot). Clamped to the domain (a periodic curve's wrapped
    /// points lie past it). O(n p).
    pub fn greville(&self) -> Vec<f64> {
        let p = self.degree;
        let (start, end) = self.domain();
        (0..self.points.len())
            .map(|i| {
                let s: f64 = self.knots[i + 1..=i + p].iter().sum();
                (s / p as f64).clamp(start, end)
            })
            .collect()
    }

    /// The distinct knot values strictly inside the domain with their
    /// multiplicities, in order: where the pieces of the curve meet.
    pub fn interior_knots(&self) -> Vec<(f64, usize)> {
        let (start, end) = self.domain();
        let mut out: Vec<(f64, usize)> = Vec::new();
        for &k in self.knots.iter().filter(|&&k| k > start && k < end) {
            match out.last_mut() {
                Some((v, m)) if *v == k => *m += 1,
                _ => out.push((k, 1)),
            }
        }
        out
    }

    /// Inserts the knot `u` once without changing the curve (Boehm, A5.1).
    ///
    /// # Errors
    /// `u` outside the open domain, or already of multiplicity `degree`.
    pub fn insert_knot(&self, u: f64) -> Result<NurbsCurve, CurveError> {
        let (start, end) = self.domain();
        if !(u > start && u < end) {
            return Err(CurveError::OutsideDomain {
                value: u,
                start,
                end,
            });
        }
        let s = self.knots.iter().filter(|&&x| x == u).count();
        if s >= self.degree {
            return Err(CurveError::FullMultiplicity {
                value: u,
                multiplicity: s,
            });
        }
        Ok(self.insert_knot_at(u))
    }

    /// Boehm's insertion of `u` in the closed domain, of multiplicity below
    /// the degree (the callers check).
    fn insert_knot_at(&self, u: f64) -> NurbsCurve {
        let p = self.degree;
        // The span [U_k, U_k+1) holding u, the last one when knots repeat
        // (at the domain's start after an insertion there).
        let k = (self.knots.partition_point(|&x| x <= u) - 1).min(self.points.len() - 1);
        let s = self.knots.iter().filter(|&&x| x == u).count();
        let pw: Vec<DVec4> = self
            .points
            .iter()
            .zip(&self.weights)
            .map(|(&q, &w)| homogeneous(q, w))
            .collect();
        let mut qw = Vec::with_capacity(pw.len() + 1);
        for i in 0..=pw.len() {
            let q = if i + p <= k {
                pw[i]
            } else if i > k - s {
                pw[i - 1]
            } else {
                let alpha = (u - self.knots[i]) / (self.knots[i + p] - self.knots[i]);
                alpha * pw[i] + (1.0 - alpha) * pw[i - 1]
            };
            qw.push(q);
        }
        let mut knots = self.knots.clone();
        knots.insert(k + 1, u);
        let (points, weights) = qw.into_iter().map(from_homogeneous).unzip();
        NurbsCurve {
            degree: p,
            knots,
            points,
            weights,
        }
    }
    /// The same curve on the same domain with clamped ends (its ends become
    /// control points): the domain's end knots are inserted up to
    /// multiplicity `degree` (Boehm, which keeps the curve), then the knots
    /// outside the domain and the control points that shape only the part
    /// outside it are dropped (Piegl & Tiller, The NURBS Book, 12.2). A
    /// clamped curve is returned as it is.
    pub fn clamped_ends(&self) -> NurbsCurve {
        if self.is_clamped() {
            return self.clone();
        }
        // The start, then the end as the start of the reversed curve.
        self.clamped_start().reversed().clamped_start().reversed()
    }

    /// [`clamped_ends`](Self::clamped_ends) at the start only.
    fn clamped_start(&self) -> NurbsCurve {
        let p = self.degree;
        let (a, _) = self.domain();
        let mut c = self.clone();
        while c.knots.iter().filter(|&&x| x == a).count() < p {
            c = c.insert_knot_at(a);
        }
        let below = c.knots.iter().filter(|&&x| x < a).count();
        if below == 0 {
            return c;
        }
        // The basis functions of the first below − 1 points vanish on the
        // domain now: drop them with the knots below it, and clamp with
        // one more `a`.
        let mut knots = vec![a];
        knots.extend(c.knots.iter().copied().filter(|&x| x >= a));
        NurbsCurve {
            degree: p,
            knots,
            points: c.points[below - 1..].to_vec(),
            weights: c.weights[below - 1..].to_vec(),
        }
    }

    /// The same curve run backwards on the same domain `[a, b]`: `t ↦ a + b − t`.
    pub fn reversed(&self) -> NurbsCurve {
        let (a, b) = self.domain();
        NurbsCurve {
            degree: self.degree,
            knots: self.knots.iter().rev().map(|&x| a + b - x).collect(),
            points: self.points.iter().rev().copied().collect(),
            weights: self.weights.iter().rev().copied().collect(),
        }
    }

    /// Positions at many parameters at once (clamped to the domain), much
    /// faster than one [`Curve::point`] call each; increasing parameters are
    /// fastest. See [`super::fast`].
    pub fn points_at(&self, params: &[f64]) -> Vec<DVec3> {
        let (a, b) = self.domain();
        if self.degree > super::fast::MAX_FAST_DEGREE {
            return params.iter().map(|&t| self.point(t)).collect();
        }
        let basis = super::fast::Basis::new(self.degree, &self.knots, self.points.len());
        let pw = super::fast::homogeneous_points(&self.points, &self.weights);
        if params.iter().all(|t| (a..=b).contains(t)) {
            super::fast::curve_points(&basis, &pw, params)
        } else {
            let clamped: Vec<f64> = params.iter().map(|t| t.clamp(a, b)).collect();
            super::fast::curve_points(&basis, &pw, &clamped)
        }
    }

    /// The two pieces on either side of `u`, each a clamped curve tracing
    /// its part exactly: `u` is inserted until it has multiplicity
    /// `degree`, where the curve passes through a control point (an
    /// unclamped curve is clamped first).
    ///
    /// # Errors
    /// `u` outside the open domain.
    pub fn split(&self, u: f64) -> Result<(NurbsCurve, NurbsCurve), CurveError> {
        let (start, end) = self.domain();
        if !(u > start && u < end) {
            return Err(CurveError::OutsideDomain {
                value: u,
                start,
                end,
            });
        }
        if !self.is_clamped() {
            return self.clamped_ends().split(u);
        }
        let p = self.degree;
        let mut c = self.clone();
        while c.knots.iter().filter(|&&k| k == u).count() < p {
            c = c.insert_knot(u)?;
        }
        // The knots up to u (with one more copy to clamp) and the points before.
        let last_u = c.knots.iter().rposition(|&k| k == u).expect("inserted");
        let first_u = last_u + 1 - p;
        let mut left_knots = c.knots[..=last_u].to_vec();
        left_knots.push(u);
        let left_count = left_knots.len() - p - 1;
        let mut right_knots = vec![u];
        right_knots.extend_from_slice(&c.knots[first_u..]);
        let right_count = right_knots.len() - p - 1;
        let n = c.points.len();
        let left = NurbsCurve::new(
            p,
            left_knots,
            c.points[..left_count].to_vec(),
            c.weights[..left_count].to_vec(),
        )?;
        let right = NurbsCurve::new(
            p,
            right_knots,
            c.points[n - right_count..].to_vec(),
            c.weights[n - right_count..].to_vec(),
        )?;
        Ok((left, right))
    }

    /// Knot refinement: inserts every knot of `knots` (one at a time, by
    /// Boehm's rule); the curve does not move.
    ///
    /// # Errors
    /// As [`insert_knot`](Self::insert_knot), naming the first knot refused.
    pub fn refine(&self, knots: &[f64]) -> Result<NurbsCurve, CurveError> {
        knots
            .iter()
            .try_fold(self.clone(), |c, &u| c.insert_knot(u))
    }

    /// True when both ends have `degree + 1` equal knots (the curve starts
    /// and ends at its end control points).
    pub fn is_clamped(&self) -> bool {
        let p = self.degree;
        let m = self.knots.len();
        self.knots[..=p].iter().all(|&k| k == self.knots[0])
            && self.knots[m - p - 1..]
                .iter()
                .all(|&k| k == self.knots[m - 1])
    }

    /// The rational Bézier segments between distinct knots, each as
    /// (parameter interval, homogeneous control points): the curve with
    /// every interior knot inserted up to multiplicity `degree` (an
    /// unclamped curve is clamped first, [`clamped_ends`](Self::clamped_ends)).
    ///
    /// # Errors
    /// A knot insertion that fails.
    pub fn bezier_segments(&self) -> Result<Vec<BezierSegment>, CurveError> {
        if !self.is_clamped() {
            return self.clamped_ends().bezier_segments();
        }
        let p = self.degree;
        let mut c = self.clone();
        let (start, end) = self.domain();
        let mut breaks: Vec<f64> = self.knots.clone();
        breaks.dedup();
        breaks.retain(|&k| k > start && k < end);
        for &u in &breaks {
            while c.knots.iter().filter(|&&x| x == u).count() < p {
                c = c.insert_knot(u)?;
            }
        }
        let pw: Vec<DVec4> = c
            .points
            .iter()
            .zip(&c.weights)
            .map(|(&q, &w)| homogeneous(q, w))
            .collect();
        let mut bounds = vec![start];
        bounds.extend(&breaks);
        bounds.push(end);
        Ok(bounds
            .windows(2)
            .enumerate()
            .map(|(j, w)| ((w[0], w[1]), pw[j * p..=j * p + p].to_vec()))
            .collect())
    }

    /// The same curve with degree one higher, in the smallest knot vector
    /// that holds it: each interior knot of multiplicity `m` gets `m + 1`,
    /// so the curve keeps its continuity `C^(p−m)` there and stays that
    /// smooth when its points are moved afterwards (openNURBS's
    /// `IncreaseDegree` gives the same knots; a test compares). Each Bézier
    /// segment is elevated in homogeneous coordinates (The NURBS Book,
    /// eq. 5.36), and the joined segments are expressed in the smaller
    /// knot vector ([`respan`](Self::respan)). An unclamped curve comes
    /// back clamped, with the same shape on its domain.
    ///
    /// # Errors
    /// A knot insertion that fails.
    pub fn elevate_degree(&self) -> Result<NurbsCurve, CurveError> {
        let joined = self.elevate_segments()?;
        let (start, end) = self.domain();
        let q = self.degree + 1;
        let mut knots = vec![start; q + 1];
        for (k, m) in self.interior_knots() {
            knots.extend(std::iter::repeat_n(k, (m + 1).min(q)));
        }
        knots.extend(std::iter::repeat_n(end, q + 1));
        joined.respan(knots)
    }

    /// The same curve in the knot vector `knots` of its degree and domain,
    /// which must hold it (a vector with the curve's own knots among its
    /// knots, or one the curve's continuity allows): the homogeneous
    /// control points interpolate the curve at the Greville abscissae of
    /// `knots`, which meets the Schoenberg–Whitney condition; the
    /// collocation matrix is banded and totally positive, so elimination
    /// without pivoting is stable (de Boor, *A Practical Guide to Splines*,
    /// ch. XIII). Exact up to rounding when the curve is in the space.
    ///
    /// Complexity: O(n · p²) for n points.
    fn respan(&self, knots: Vec<f64>) -> Result<NurbsCurve, CurveError> {
        let q = self.degree;
        let n = knots.len() - q - 1;
        let probe = NurbsCurve::new(q, knots.clone(), vec![DVec3::ZERO; n], vec![1.0; n])?;
        // Band storage: row i keeps columns i − w ..= i + w.
        let w = 2 * q;
        let mut band = vec![vec![0.0; 2 * w + 1]; n];
        let mut rhs = vec![DVec4::ZERO; n];
        for i in 0..n {
            let tau = knots[i + 1..=i + q].iter().sum::<f64>() / q as f64;
            let span = probe.span(tau);
            let basis = &basis_derivatives(&knots, span, tau, q, 0)[0];
            for (j, b) in basis.iter().enumerate() {
                let column = span - q + j;
                band[i][column + w - i] = *b;
            }
            rhs[i] = self.homogeneous_derivatives(tau, 0)[0];
        }
        for k in 0..n {
            let row = band[k].clone();
            let (pivot, r) = (row[w], rhs[k]);
            for i in k + 1..n.min(k + w + 1) {
                let f = band[i][k + w - i] / pivot;
                if f == 0.0 {
                    continue;
                }
                for j in k..n.min(k + w + 1) {
                    band[i][j + w - i] -= f * row[j + w - k];
                }
                rhs[i] -= f * r;
            }
        }
        let mut pw = vec![DVec4::ZERO; n];
        for k in (0..n).rev() {
            let mut sum = rhs[k];
            for j in k + 1..n.min(k + w + 1) {
                sum -= band[k][j + w - k] * pw[j];
            }
            pw[k] = sum / band[k][w];
        }
        let (points, weights) = pw.into_iter().map(from_homogeneous).unzip();
        NurbsCurve::new(q, knots, points, weights)
    }

    /// The curve one degree higher as joined Bézier segments (interior
    /// knots of multiplicity `degree + 1`).
    fn elevate_segments(&self) -> Result<NurbsCurve, CurveError> {
        let segments = self.bezier_segments()?;
        let p = self.degree;
        let q = p + 1;
        let mut knots = vec![segments[0].0.0; q + 1];
        let mut pw: Vec<DVec4> = Vec::new();
        for (j, ((_, b), seg)) in segments.iter().enumerate() {
            let mut elevated = Vec::with_capacity(q + 1);
            elevated.push(seg[0]);
            for i in 1..=p {
                let a = i as f64 / q as f64;
                elevated.push(a * seg[i - 1] + (1.0 - a) * seg[i]);
            }
            elevated.push(seg[p]);
            let skip = usize::from(j > 0);
            pw.extend_from_slice(&elevated[skip..]);
            let copies = if j + 1 == segments.len() { q + 1 } else { q };
            knots.extend(std::iter::repeat_n(*b, copies));
        }
        let (points, weights) = pw.into_iter().map(from_homogeneous).unzip();
        NurbsCurve::new(q, knots, points, weights)
    }
}

impl Curve for NurbsCurve {
    fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.points.len()])
    }

    /// Position, first and second derivative by the rational quotient rule
    /// (eq. 4.8): `C = A/w`, `C' = (A' − w'C)/w`, `C'' = (A'' − 2w'C' − w''C)/w`.
    fn derivatives(&self, t: f64) -> [DVec3; 3] {
        let (start, end) = self.domain();
        let u = t.clamp(start, end);
        let [a0, a1, a2] = self.homogeneous_derivatives(u, 2);
        let c0 = a0.truncate() / a0.w;
        let c1 = (a1.truncate() - a1.w * c0) / a0.w;
        let c2 = (a2.truncate() - 2.0 * a1.w * c1 - a2.w * c0) / a0.w;
        [c0, c1, c2]
    }

    /// The domain's ends and every distinct knot between them
    /// ([`interior_knots`](Self::interior_knots)): the curve is one rational
    /// polynomial piece on each knot span and only `C^(p−k)` at a knot of
    /// multiplicity k, so a knot of multiplicity `p` may be a corner (The
    /// NURBS Book, property P2.5 of the basis functions).
    fn breakpoints(&self) -> Vec<f64> {
        let (start, end) = self.domain();
        let mut out = vec![start];
        out.extend(self.interior_knots().into_iter().map(|(k, _)| k));
        out.push(end);
        out
    }

    /// The degree `p`: a degree-1 NURBS (rational or not) is a polyline
    /// through its control points, one segment per knot span.
    fn piece_degree(&self) -> Option<usize> {
        Some(self.degree)
    }
}

/// Knots `[0; p+1], 1/(n−p), 2/(n−p), …, [1; p+1]` for `n` points.
pub fn clamped_uniform_knots(degree: usize, points: usize) -> Vec<f64> {
    let spans = points.saturating_sub(degree).max(1);
    let mut knots = vec![0.0; degree + 1];
    knots.extend((1..spans).map(|i| i as f64 / spans as f64));
    knots.extend(std::iter::repeat_n(1.0, degree + 1));
    knots
}

/// The non-zero basis functions `N_{span−p+j, p}` at `u` and their
/// derivatives up to `order`: `out[k][j]` (The NURBS Book, A2.3).
pub fn basis_derivatives(
    knots: &[f64],
    span: usize,
    u: f64,
    p: usize,
    order: usize,
) -> Vec<Vec<f64>> {
    let mut ndu = vec![vec![0.0; p + 1]; p + 1];
    let mut left = vec![0.0; p + 1];
    let mut right = vec![0.0; p + 1];
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = u - knots[span + 1 - j];
        right[j] = knots[span + j] - u;
        let mut saved = 0.0;
        for r in 0..j {
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    let n = order.min(p);
    let mut ders = vec![vec![0.0; p + 1]; order + 1];
    for j in 0..=p {
        ders[0][j] = ndu[j][p];
    }
    let mut a = [vec![0.0; p + 1], vec![0.0; p + 1]];
    for r in 0..=p {
        let (mut s1, mut s2) = (0, 1);
        a[0][0] = 1.0;
        for k in 1..=n {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = p - k;
            if r >= k {
                let rk = rk as usize;
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if r as isize - 1 <= pk as isize {
                k - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let idx = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                d += a[s2][j] * ndu[idx][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            ders[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut factor = p as f64;
    for (k, row) in ders.iter_mut().enumerate().take(n + 1).skip(1) {
        for d in row.iter_mut().take(p + 1) {
            *d *= factor;
        }
        factor *= (p - k) as f64;
    }
    ders
}
