//! NURBS surfaces: a tensor product of two B-spline bases with weights
//! (seed 004; The NURBS Book ch. 4.4, derivatives eq. 4.20), with knot
//! insertion in either direction and the standard constructions: plane,
//! sphere, cylinder, revolution and extrusion of a curve (seed 004's 2.5D
//! solids).

use glam::{DVec3, DVec4};

use super::{Surface, SurfacePoint};
use crate::curves::nurbs::basis_derivatives;
use crate::curves::{CurveError, NurbsCurve, check_points};

/// A NURBS surface: `nu × nv` control points `points[i * nv + j]` (i along
/// u) with weights, degrees and knot vectors in u and v.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "NurbsSurfaceData", into = "NurbsSurfaceData")]
pub struct NurbsSurface {
    degree_u: usize,
    degree_v: usize,
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
    nu: usize,
    nv: usize,
    points: Vec<DVec3>,
    weights: Vec<f64>,
}

/// The stored form of a [`NurbsSurface`], validated on load.
#[derive(serde::Serialize, serde::Deserialize)]
pub struct NurbsSurfaceData {
    /// Degree in u.
    pub degree_u: usize,
    /// Degree in v.
    pub degree_v: usize,
    /// Knot vector in u (`nu + degree_u + 1` values).
    pub knots_u: Vec<f64>,
    /// Knot vector in v (`nv + degree_v + 1` values).
    pub knots_v: Vec<f64>,
    /// Control points in the u direction.
    pub nu: usize,
    /// Control points in the v direction.
    pub nv: usize,
    /// The `nu × nv` control points, row-major: point `(i, j)` at `i * nv + j`.
    pub points: Vec<DVec3>,
    /// Positive weight of each control point, in the same order.
    pub weights: Vec<f64>,
}

impl TryFrom<NurbsSurfaceData> for NurbsSurface {
    type Error = CurveError;
    fn try_from(d: NurbsSurfaceData) -> Result<Self, CurveError> {
        NurbsSurface::new(
            d.degree_u, d.degree_v, d.knots_u, d.knots_v, d.nu, d.nv, d.points, d.weights,
        )
    }
}

impl From<NurbsSurface> for NurbsSurfaceData {
    fn from(s: NurbsSurface) -> Self {
        NurbsSurfaceData {
            degree_u: s.degree_u,
            degree_v: s.degree_v,
            knots_u: s.knots_u,
            knots_v: s.knots_v,
            nu: s.nu,
            nv: s.nv,
            points: s.points,
            weights: s.weights,
        }
    }
}

impl NurbsSurface {
    /// # Errors
    /// As [`NurbsCurve::new`] in each direction, and a point count that is
    /// not `nu · nv`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        degree_u: usize,
        degree_v: usize,
        knots_u: Vec<f64>,
        knots_v: Vec<f64>,
        nu: usize,
        nv: usize,
        points: Vec<DVec3>,
        weights: Vec<f64>,
    ) -> Result<Self, CurveError> {
        if points.len() != nu * nv || weights.len() != nu * nv {
            return Err(CurveError::GridCount {
                nu,
                nv,
                points: points.len(),
                weights: weights.len(),
            });
        }
        check_points(&points)?;
        // Validate each direction through a curve of the first row / column.
        let column: Vec<DVec3> = (0..nu).map(|i| points[i * nv]).collect();
        let column_w: Vec<f64> = (0..nu).map(|i| weights[i * nv]).collect();
        NurbsCurve::new(degree_u, knots_u.clone(), column, column_w)?;
        NurbsCurve::new(
            degree_v,
            knots_v.clone(),
            points[..nv].to_vec(),
            weights[..nv].to_vec(),
        )?;
        if let Some((index, &value)) = weights
            .iter()
            .enumerate()
            .find(|(_, w)| !w.is_finite() || **w <= 0.0)
        // NaN is not finite
        {
            return Err(CurveError::BadWeight { index, value });
        }
        Ok(NurbsSurface {
            degree_u,
            degree_v,
            knots_u,
            knots_v,
            nu,
            nv,
            points,
            weights,
        })
    }

    /// The surface with its control points mapped by the affine map `m`,
    /// weights and knots kept, which is exact for NURBS (affine invariance,
    /// The NURBS Book §4.2); as [`NurbsCurve::transformed`].
    ///
    /// # Errors
    /// A map that makes a control point non-finite.
    ///
    /// Complexity: O(points).
    pub fn transformed(&self, m: &glam::DMat4) -> Result<NurbsSurface, CurveError> {
        let points: Vec<DVec3> = self.points.iter().map(|p| m.transform_point3(*p)).collect();
        check_points(&points)?;
        Ok(NurbsSurface {
            points,
            ..self.clone()
        })
    }

    /// `(degree in u, degree in v)`.
    pub fn degrees(&self) -> (usize, usize) {
        (self.degree_u, self.degree_v)
    }
    /// `(nu, nv)`: control points in u and in v.
    pub fn size(&self) -> (usize, usize) {
        (self.nu, self.nv)
    }
    /// `(knots in u, knots in v)`.
    pub fn knots(&self) -> (&[f64], &[f64]) {
        (&self.knots_u, &self.knots_v)
    }
    /// Control points, row-major: `(i, j)` at `i * nv + j`.
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }
    /// Weights, in the order of [`points`](Self::points).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Moves control point `(i, j)`.
    ///
    /// # Errors
    /// No such point, or a non-finite position.
    pub fn set_point(&mut self, i: usize, j: usize, p: DVec3) -> Result<(), CurveError> {
        let k = self.index(i, j)?;
        if !p.is_finite() {
            return Err(CurveError::NotFinite {
                what: "control point",
                index: k,
            });
        }
        self.points[k] = p;
        Ok(())
    }

    /// Changes the weight of control point `(i, j)`.
    ///
    /// # Errors
    /// No such point, or a weight that is not positive and finite.
    pub fn set_weight(&mut self, i: usize, j: usize, w: f64) -> Result<(), CurveError> {
        let k = self.index(i, j)?;
        if !w.is_finite() || w <= 0.0 {
            // NaN is not finite: refused too
            return Err(CurveError::BadWeight { index: k, value: w });
        }
        self.weights[k] = w;
        Ok(())
    }

    fn index(&self, i: usize, j: usize) -> Result<usize, CurveError> {
        if i < self.nu && j < self.nv {
            Ok(i * self.nv + j)
        } else {
            Err(CurveError::NoSuchPoint {
                index: i * self.nv + j,
                count: self.points.len(),
            })
        }
    }

    /// A surface from a Bézier net (clamped knots, all weights 1).
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn from_bezier(nu: usize, nv: usize, points: Vec<DVec3>) -> Result<Self, CurveError> {
        let knots = |n: usize| {
            let mut k = vec![0.0; n];
            k.extend(std::iter::repeat_n(1.0, n));
            k
        };
        let weights = vec![1.0; points.len()];
        Self::new(
            nu - 1,
            nv - 1,
            knots(nu),
            knots(nv),
            nu,
            nv,
            points,
            weights,
        )
    }

    /// The curve `profile` (in the XY plane, x ≥ 0) revolved once around
    /// the Y axis: u goes around (the exact NURBS circle, clockwise seen
    /// from +Y), v along the profile, so a profile running upwards gets
    /// normals `S_u × S_v` pointing away from the axis.
    ///
    /// # Errors
    /// Never for a valid profile; kept for symmetry with the other makers.
    pub fn revolve(profile: &NurbsCurve) -> Result<Self, CurveError> {
        let circle = NurbsCurve::circle(DVec3::ZERO, 1.0);
        let (nu, nv) = (circle.points().len(), profile.points().len());
        let mut points = Vec::with_capacity(nu * nv);
        let mut weights = Vec::with_capacity(nu * nv);
        for (c, &cw) in circle.points().iter().zip(circle.weights()) {
            for (p, &pw) in profile.points().iter().zip(profile.weights()) {
                let r = p.x.hypot(p.z);
                points.push(DVec3::new(r * c.x, p.y, -r * c.z));
                weights.push(cw * pw);
            }
        }
        Self::new(
            2,
            profile.degree(),
            circle.knots().to_vec(),
            profile.knots().to_vec(),
            nu,
            nv,
            points,
            weights,
        )
    }

    /// `profile` swept along `direction`: degree 1 in v (seed 004's extrusion).
    ///
    /// # Errors
    /// A non-finite direction.
    pub fn extrude(profile: &NurbsCurve, direction: DVec3) -> Result<Self, CurveError> {
        if !direction.is_finite() {
            return Err(CurveError::NotFiniteVector {
                what: "the extrusion direction",
            });
        }
        let nu = profile.points().len();
        let mut points = Vec::with_capacity(2 * nu);
        let mut weights = Vec::with_capacity(2 * nu);
        for (p, &w) in profile.points().iter().zip(profile.weights()) {
            points.extend([*p, *p + direction]);
            weights.extend([w, w]);
        }
        Self::new(
            profile.degree(),
            1,
            profile.knots().to_vec(),
            vec![0.0, 0.0, 1.0, 1.0],
            nu,
            2,
            points,
            weights,
        )
    }

    /// An exact sphere: a half circle revolved around Y, then moved.
    pub fn sphere(center: DVec3, radius: f64) -> Self {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let half = NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
            vec![
                DVec3::new(0.0, -radius, 0.0),
                DVec3::new(radius, -radius, 0.0),
                DVec3::new(radius, 0.0, 0.0),
                DVec3::new(radius, radius, 0.0),
                DVec3::new(0.0, radius, 0.0),
            ],
            vec![1.0, s, 1.0, s, 1.0],
        )
        .expect("the half circle's data is valid");
        let mut sphere = Self::revolve(&half).expect("revolving a valid profile");
        sphere.points.iter_mut().for_each(|p| *p += center);
        sphere
    }

    /// An exact open cylinder around the Y axis from y = 0 to `height`.
    pub fn cylinder(radius: f64, height: f64) -> Self {
        let line = NurbsCurve::clamped(
            1,
            vec![
                DVec3::new(radius, 0.0, 0.0),
                DVec3::new(radius, height, 0.0),
            ],
        )
        .expect("a line is a valid curve");
        Self::revolve(&line).expect("revolving a valid profile")
    }

    /// A flat square of side `size` in the XZ plane, centred at the origin.
    pub fn plane(size: f64) -> Self {
        let h = size / 2.0;
        Self::from_bezier(
            2,
            2,
            vec![
                DVec3::new(-h, 0.0, -h),
                DVec3::new(-h, 0.0, h),
                DVec3::new(h, 0.0, -h),
                DVec3::new(h, 0.0, h),
            ],
        )
        .expect("a plane is valid")
    }

    /// The column of control points with fixed `j` as a curve in u.
    pub fn column(&self, j: usize) -> NurbsCurve {
        let pts = (0..self.nu).map(|i| self.points[i * self.nv + j]).collect();
        let w = (0..self.nu)
            .map(|i| self.weights[i * self.nv + j])
            .collect();
        NurbsCurve::new(self.degree_u, self.knots_u.clone(), pts, w)
            .expect("columns of a valid surface are valid")
    }

    /// The row of control points with fixed `i` as a curve in v.
    pub fn row(&self, i: usize) -> NurbsCurve {
        let r = i * self.nv..(i + 1) * self.nv;
        NurbsCurve::new(
            self.degree_v,
            self.knots_v.clone(),
            self.points[r.clone()].to_vec(),
            self.weights[r].to_vec(),
        )
        .expect("rows of a valid surface are valid")
    }

    /// Points (and, with `normals`, unit normals) on the grid of parameters
    /// `us × vs`, row-major by u; each u-row of control points is combined
    /// once, then every point costs `q + 1` terms. Parameters are clamped
    /// to the domain. See [`crate::curves::fast`]. Where the partial
    /// derivatives are parallel (a pole) the normal is the limit around it
    /// ([`super::limit_normal`]).
    pub fn grid(&self, us: &[f64], vs: &[f64], normals: bool) -> (Vec<DVec3>, Vec<DVec3>) {
        let (points, mut norms) = self.grid_raw(us, vs, normals);
        for (k, n) in norms.iter_mut().enumerate() {
            if *n == DVec3::ZERO {
                let (u, v) = (us[k / vs.len()], vs[k % vs.len()]);
                let ((u0, u1), (v0, v1)) = self.domain();
                *n = super::limit_normal(self, u.clamp(u0, u1), v.clamp(v0, v1));
            }
        }
        (points, norms)
    }

    fn grid_raw(&self, us: &[f64], vs: &[f64], normals: bool) -> (Vec<DVec3>, Vec<DVec3>) {
        use super::fast::evaluate_grid;
        use crate::curves::fast::{Basis, MAX_FAST_DEGREE, homogeneous_points};
        let ((u0, u1), (v0, v1)) = self.domain();
        let us: Vec<f64> = us.iter().map(|u| u.clamp(u0, u1)).collect();
        let vs: Vec<f64> = vs.iter().map(|v| v.clamp(v0, v1)).collect();
        if self.degree_u > MAX_FAST_DEGREE || self.degree_v > MAX_FAST_DEGREE {
            let mut points = Vec::with_capacity(us.len() * vs.len());
            let mut norms = Vec::new();
            for &u in &us {
                for &v in &vs {
                    let e = self.evaluate(u, v);
                    points.push(e.p);
                    if normals {
                        norms.push(e.normal());
                    }
                }
            }
            return (points, norms);
        }
        let bu = Basis::new(self.degree_u, &self.knots_u, self.nu);
        let bv = Basis::new(self.degree_v, &self.knots_v, self.nv);
        let pw = homogeneous_points(&self.points, &self.weights);
        evaluate_grid(&bu, &bv, self.nv, &pw, &us, &vs, normals)
    }

    /// Inserts a knot in u (every column gets it; the surface does not move).
    ///
    /// # Errors
    /// As [`NurbsCurve::insert_knot`].
    pub fn insert_knot_u(&self, u: f64) -> Result<NurbsSurface, CurveError> {
        self.map_columns(|c| c.insert_knot(u))
    }

    /// The surface whose columns (curves in u) are `f` of this one's; `f`
    /// must treat every column alike (same knots and degree out).
    fn map_columns(
        &self,
        f: impl Fn(&NurbsCurve) -> Result<NurbsCurve, CurveError>,
    ) -> Result<NurbsSurface, CurveError> {
        let columns: Vec<NurbsCurve> = (0..self.nv)
            .map(|j| f(&self.column(j)))
            .collect::<Result<_, _>>()?;
        let nu = columns[0].points().len();
        let mut points = vec![DVec3::ZERO; nu * self.nv];
        let mut weights = vec![0.0; nu * self.nv];
        for (j, c) in columns.iter().enumerate() {
            for i in 0..nu {
                points[i * self.nv + j] = c.points()[i];
                weights[i * self.nv + j] = c.weights()[i];
            }
        }
        Ok(NurbsSurface {
            degree_u: columns[0].degree(),
            knots_u: columns[0].knots().to_vec(),
            nu,
            points,
            weights,
            ..self.clone()
        })
    }

    /// The surface whose rows (curves in v) are `f` of this one's.
    fn map_rows(
        &self,
        f: impl Fn(&NurbsCurve) -> Result<NurbsCurve, CurveError>,
    ) -> Result<NurbsSurface, CurveError> {
        let rows: Vec<NurbsCurve> = (0..self.nu)
            .map(|i| f(&self.row(i)))
            .collect::<Result<_, _>>()?;
        Ok(NurbsSurface {
            degree_v: rows[0].degree(),
            knots_v: rows[0].knots().to_vec(),
            nv: rows[0].points().len(),
            points: rows.iter().flat_map(|r| r.points().to_vec()).collect(),
            weights: rows.iter().flat_map(|r| r.weights().to_vec()).collect(),
            ..self.clone()
        })
    }

    /// Raises the degree in u by one (every column is elevated the same
    /// way; the surface does not move).
    ///
    /// # Errors
    /// An unclamped knot vector in u.
    pub fn elevate_u(&self) -> Result<NurbsSurface, CurveError> {
        self.map_columns(NurbsCurve::elevate_degree)
    }

    /// Raises the degree in v by one (every row is elevated the same way).
    ///
    /// # Errors
    /// An unclamped knot vector in v.
    pub fn elevate_v(&self) -> Result<NurbsSurface, CurveError> {
        self.map_rows(NurbsCurve::elevate_degree)
    }

    /// Inserts a knot in v (every row gets it; the surface does not move).
    ///
    /// # Errors
    /// As [`NurbsCurve::insert_knot`].
    pub fn insert_knot_v(&self, v: f64) -> Result<NurbsSurface, CurveError> {
        self.map_rows(|r| r.insert_knot(v))
    }

    fn span(knots: &[f64], degree: usize, count: usize, u: f64) -> usize {
        // Reuse the curve's span search through a throwaway-free helper.
        let n = count - 1;
        if u >= knots[n + 1] {
            let mut i = n;
            while i > degree && knots[i] >= knots[n + 1] {
                i -= 1;
            }
            return i;
        }
        let mut i = degree;
        while i < n && knots[i + 1] <= u {
            i += 1;
        }
        i
    }
}

impl Surface for NurbsSurface {
    fn domain(&self) -> ((f64, f64), (f64, f64)) {
        (
            (self.knots_u[self.degree_u], self.knots_u[self.nu]),
            (self.knots_v[self.degree_v], self.knots_v[self.nv]),
        )
    }

    /// The domain's ends and the distinct knots between them, in each
    /// direction (one rational patch per pair of knot spans).
    fn breakpoints(&self) -> (Vec<f64>, Vec<f64>) {
        let ((u0, u1), (v0, v1)) = self.domain();
        let distinct = |knots: &[f64], a: f64, b: f64| {
            let mut out = vec![a];
            out.extend(knots.iter().copied().filter(|&k| k > a && k < b));
            out.dedup();
            out.push(b);
            out
        };
        (
            distinct(&self.knots_u, u0, u1),
            distinct(&self.knots_v, v0, v1),
        )
    }

    /// Through the fast grid evaluator ([`NurbsSurface::grid`]).
    fn grid_points(&self, us: &[f64], vs: &[f64]) -> Vec<DVec3> {
        self.grid(us, vs, false).0
    }

    /// Homogeneous derivatives `A^(k,l)` from the two bases, then the
    /// rational quotient rule (The NURBS Book eq. 4.20).
    fn evaluate(&self, u: f64, v: f64) -> SurfacePoint {
        let ((u0, u1), (v0, v1)) = self.domain();
        let (u, v) = (u.clamp(u0, u1), v.clamp(v0, v1));
        let (p, q) = (self.degree_u, self.degree_v);
        let su = Self::span(&self.knots_u, p, self.nu, u);
        let sv = Self::span(&self.knots_v, q, self.nv, v);
        let nu_d = basis_derivatives(&self.knots_u, su, u, p, 2);
        let nv_d = basis_derivatives(&self.knots_v, sv, v, q, 2);
        let mut a = [[DVec4::ZERO; 3]; 3];
        for (k, row_u) in nu_d.iter().enumerate() {
            for (l, row_v) in nv_d.iter().enumerate().take(3 - k) {
                let mut sum = DVec4::ZERO;
                for (r, &bu) in row_u.iter().enumerate() {
                    if bu == 0.0 {
                        continue;
                    }
                    let i = su - p + r;
                    for (s, &bv) in row_v.iter().enumerate() {
                        let j = sv - q + s;
                        let w = self.weights[i * self.nv + j];
                        sum += bu * bv * (self.points[i * self.nv + j] * w).extend(w);
                    }
                }
                a[k][l] = sum;
            }
        }
        let w = a[0][0].w;
        let s = a[0][0].truncate() / w;
        let su_ = (a[1][0].truncate() - a[1][0].w * s) / w;
        let sv_ = (a[0][1].truncate() - a[0][1].w * s) / w;
        let suu = (a[2][0].truncate() - 2.0 * a[1][0].w * su_ - a[2][0].w * s) / w;
        let svv = (a[0][2].truncate() - 2.0 * a[0][1].w * sv_ - a[0][2].w * s) / w;
        let suv = (a[1][1].truncate() - a[1][1].w * s - a[1][0].w * sv_ - a[0][1].w * su_) / w;
        SurfacePoint {
            p: s,
            du: su_,
            dv: sv_,
            duu: suu,
            duv: suv,
            dvv: svv,
        }
    }
}
