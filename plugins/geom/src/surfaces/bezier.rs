//! The bilinear patch and tensor-product Bézier surfaces (seeds 001, 002,
//! 003): evaluation by de Casteljau in both directions, partial derivatives
//! from the hodographs of the rows and columns, the normal.

use glam::DVec3;

use super::{Surface, SurfacePoint};
use crate::curves::{Bezier, CurveError, check_points};

/// `S(u, v) = (1−u)(1−v) p00 + u(1−v) p10 + (1−u)v p01 + uv p11` (seed 003).
#[derive(Clone, Debug, PartialEq)]
pub struct BilinearPatch {
    /// `[p00, p10, p01, p11]`.
    pub corners: [DVec3; 4],
}

impl Surface for BilinearPatch {
    fn domain(&self) -> ((f64, f64), (f64, f64)) {
        ((0.0, 1.0), (0.0, 1.0))
    }
    fn evaluate(&self, u: f64, v: f64) -> SurfacePoint {
        let (u, v) = (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
        let [p00, p10, p01, p11] = self.corners;
        SurfacePoint {
            p: (1.0 - u) * (1.0 - v) * p00
                + u * (1.0 - v) * p10
                + (1.0 - u) * v * p01
                + u * v * p11,
            du: (1.0 - v) * (p10 - p00) + v * (p11 - p01),
            dv: (1.0 - u) * (p01 - p00) + u * (p11 - p10),
            duu: DVec3::ZERO,
            duv: p11 - p10 - p01 + p00,
            dvv: DVec3::ZERO,
        }
    }
}

/// A tensor-product Bézier surface of degree `(nu − 1, nv − 1)` on `[0, 1]²`
/// with control points `points[i * nv + j]` (i along u, j along v).
#[derive(Clone, Debug, PartialEq)]
pub struct BezierSurface {
    /// Control points in u (degree in u + 1), at least 2.
    pub nu: usize,
    /// Control points in v (degree in v + 1), at least 2.
    pub nv: usize,
    /// The `nu × nv` control points, row-major: `(i, j)` at `i * nv + j`.
    pub points: Vec<DVec3>,
}

impl BezierSurface {
    /// # Errors
    /// Fewer than 2 × 2 points, a count that is not `nu · nv`, non-finite points.
    pub fn new(nu: usize, nv: usize, points: Vec<DVec3>) -> Result<Self, CurveError> {
        if nu < 2 || nv < 2 {
            return Err(CurveError::GridTooSmall { nu, nv });
        }
        if points.len() != nu * nv {
            return Err(CurveError::GridPointCount {
                nu,
                nv,
                got: points.len(),
            });
        }
        check_points(&points)?;
        Ok(BezierSurface { nu, nv, points })
    }

    /// The control points of row `i` (fixed u index, along v).
    fn row(&self, i: usize) -> Bezier {
        Bezier {
            points: self.points[i * self.nv..(i + 1) * self.nv].to_vec(),
        }
    }

    /// The point at `(u, v)` as `Σ_i Σ_j B_i(u) B_j(v) b_ij` (the Bernstein
    /// form, seed 002).
    pub fn bernstein_point(&self, u: f64, v: f64) -> DVec3 {
        use crate::curves::bezier::bernstein;
        let (n, m) = (self.nu - 1, self.nv - 1);
        let mut sum = DVec3::ZERO;
        for i in 0..=n {
            let bu = bernstein(n, i, u);
            for j in 0..=m {
                sum += bu * bernstein(m, j, v) * self.points[i * self.nv + j];
            }
        }
        sum
    }

    /// The boundary curve at `u = 0` (its first row) — a Bézier surface's
    /// edges are the Bézier curves of its boundary control points (seed 002).
    pub fn boundary_u0(&self) -> Bezier {
        self.row(0)
    }
}

impl Surface for BezierSurface {
    fn domain(&self) -> ((f64, f64), (f64, f64)) {
        ((0.0, 1.0), (0.0, 1.0))
    }
    /// De Casteljau along v in every row, giving a curve in u whose value
    /// and derivatives are the surface's; the v-derivatives come from the
    /// rows' hodographs the same way.
    fn evaluate(&self, u: f64, v: f64) -> SurfacePoint {
        let (u, v) = (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
        let mut c0 = Vec::with_capacity(self.nu);
        let mut c1 = Vec::with_capacity(self.nu);
        let mut c2 = Vec::with_capacity(self.nu);
        for i in 0..self.nu {
            let row = self.row(i);
            let d1 = row.hodograph();
            c0.push(row.de_casteljau(v));
            c1.push(d1.de_casteljau(v));
            c2.push(d1.hodograph().de_casteljau(v));
        }
        let (c0, c1, c2) = (
            Bezier { points: c0 },
            Bezier { points: c1 },
            Bezier { points: c2 },
        );
        let (h0, h1) = (c0.hodograph(), c1.hodograph());
        SurfacePoint {
            p: c0.de_casteljau(u),
            du: h0.de_casteljau(u),
            dv: c1.de_casteljau(u),
            duu: h0.hodograph().de_casteljau(u),
            duv: h1.de_casteljau(u),
            dvv: c2.de_casteljau(u),
        }
    }
}
