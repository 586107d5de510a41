//! Bézier triangles (seed 001: de Casteljau on the triangular net,
//! directional derivatives, subdivision at an interior point, degree
//! elevation; seed 002). Barycentric coordinates `(u, v, w)`, `u + v + w = 1`.

use glam::DVec3;

use crate::curves::{CurveError, binomial, check_points};

/// A Bézier triangle of degree n: control points `b_ijk`, `i + j + k = n`,
/// stored in the order of [`BezierTriangle::index`].
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "BezierTriangleData", into = "BezierTriangleData")]
pub struct BezierTriangle {
    /// Degree n ≥ 1.
    pub degree: usize,
    /// The `(n + 1)(n + 2) / 2` control points.
    pub points: Vec<DVec3>,
}

/// The stored form of a [`BezierTriangle`], validated on load.
#[derive(serde::Serialize, serde::Deserialize)]
pub struct BezierTriangleData {
    /// Degree n ≥ 1.
    pub degree: usize,
    /// The `(n + 1)(n + 2) / 2` control points.
    pub points: Vec<DVec3>,
}

impl TryFrom<BezierTriangleData> for BezierTriangle {
    type Error = CurveError;
    fn try_from(d: BezierTriangleData) -> Result<Self, CurveError> {
        BezierTriangle::new(d.degree, d.points)
    }
}

impl From<BezierTriangle> for BezierTriangleData {
    fn from(t: BezierTriangle) -> Self {
        BezierTriangleData {
            degree: t.degree,
            points: t.points,
        }
    }
}

/// Number of control points of a degree-n triangle: (n+1)(n+2)/2.
pub fn point_count(n: usize) -> usize {
    (n + 1) * (n + 2) / 2
}

impl BezierTriangle {
    /// # Errors
    /// Degree 0, a point count that is not (n+1)(n+2)/2, non-finite points.
    pub fn new(degree: usize, points: Vec<DVec3>) -> Result<Self, CurveError> {
        if degree == 0 {
            return Err(CurveError::ZeroDegree);
        }
        if points.len() != point_count(degree) {
            return Err(CurveError::TrianglePointCount {
                degree,
                needed: point_count(degree),
                got: points.len(),
            });
        }
        check_points(&points)?;
        Ok(BezierTriangle { degree, points })
    }

    /// Storage index of `b_ijk` (k = n − i − j): rows of equal i, j rising.
    pub fn index(n: usize, i: usize, j: usize) -> usize {
        // Rows i' < i hold n − i' + 1 points each.
        i * (n + 1) - i * i.saturating_sub(1) / 2 + j
    }

    /// `b_ijk`.
    pub fn point(&self, i: usize, j: usize) -> DVec3 {
        self.points[Self::index(self.degree, i, j)]
    }

    /// All levels of de Casteljau's algorithm at `(u, v, w)`: level r holds
    /// the degree n − r net.
    fn levels(&self, bary: DVec3) -> Vec<Vec<DVec3>> {
        let n = self.degree;
        let mut out = vec![self.points.clone()];
        for r in 1..=n {
            let prev = &out[r - 1];
            let m = n - r;
            let mut next = Vec::with_capacity(point_count(m));
            for i in 0..=m {
                for j in 0..=m - i {
                    let a = prev[Self::index(m + 1, i + 1, j)];
                    let b = prev[Self::index(m + 1, i, j + 1)];
                    let c = prev[Self::index(m + 1, i, j)];
                    next.push(bary.x * a + bary.y * b + bary.z * c);
                }
            }
            out.push(next);
        }
        out
    }

    /// The point at barycentric `(u, v, w)` by de Casteljau on the net.
    pub fn evaluate(&self, bary: DVec3) -> DVec3 {
        self.levels(bary)[self.degree][0]
    }

    /// `Σ n!/(i! j! k!) u^i v^j w^k b_ijk` (the Bernstein form).
    pub fn bernstein_point(&self, bary: DVec3) -> DVec3 {
        let n = self.degree;
        let mut sum = DVec3::ZERO;
        for i in 0..=n {
            for j in 0..=n - i {
                let k = n - i - j;
                let c = binomial(n, i) * binomial(n - i, j);
                sum += c
                    * bary.x.powi(i as i32)
                    * bary.y.powi(j as i32)
                    * bary.z.powi(k as i32)
                    * self.point(i, j);
            }
        }
        sum
    }

    /// The derivative along a direction `d` of the domain (`d.x + d.y + d.z
    /// = 0`): one de Casteljau step with `d`, then n − 1 with the point,
    /// times n (seed 001, "directional derivative").
    pub fn directional_derivative(&self, bary: DVec3, d: DVec3) -> DVec3 {
        let n = self.degree;
        let once = BezierTriangle {
            degree: n,
            points: self.points.clone(),
        }
        .levels(d);
        if n == 1 {
            return once[1][0];
        }
        let reduced = BezierTriangle {
            degree: n - 1,
            points: once[1].clone(),
        };
        n as f64 * reduced.evaluate(bary)
    }

    /// The same surface with degree n + 1:
    /// `b'_ijk = (i b_{i−1,j,k} + j b_{i,j−1,k} + k b_{i,j,k−1}) / (n + 1)`.
    pub fn elevate(&self) -> BezierTriangle {
        let n = self.degree;
        let m = n + 1;
        let mut points = Vec::with_capacity(point_count(m));
        for i in 0..=m {
            for j in 0..=m - i {
                let k = m - i - j;
                let mut p = DVec3::ZERO;
                if i > 0 {
                    p += i as f64 * self.point(i - 1, j);
                }
                if j > 0 {
                    p += j as f64 * self.point(i, j - 1);
                }
                if k > 0 {
                    p += k as f64 * self.point(i, j);
                }
                points.push(p / m as f64);
            }
        }
        BezierTriangle { degree: m, points }
    }

    /// A triangle mesh of the patch: `steps` segments along each edge,
    /// vertices with their barycentric coordinates, counter-clockwise in
    /// (u, v, w) order.
    pub fn tessellate(&self, steps: usize) -> (Vec<DVec3>, Vec<DVec3>, Vec<[u32; 3]>) {
        let n = steps.max(1);
        let mut positions = Vec::new();
        let mut barys = Vec::new();
        for i in 0..=n {
            for j in 0..=n - i {
                let b = DVec3::new(
                    i as f64 / n as f64,
                    j as f64 / n as f64,
                    (n - i - j) as f64 / n as f64,
                );
                positions.push(self.evaluate(b));
                barys.push(b);
            }
        }
        let id = |i: usize, j: usize| Self::index(n, i, j) as u32;
        let mut triangles = Vec::new();
        for i in 0..n {
            for j in 0..n - i {
                triangles.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
                if j + 1 < n - i {
                    triangles.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
                }
            }
        }
        (positions, barys, triangles)
    }

    /// Splits at the interior point `bary` into three triangles, each with
    /// that point as its first corner and two of the original corners
    /// (the edges of de Casteljau's tetrahedron of levels, seed 001). The
    /// first has corners (P, e_v, e_w), the second (P, e_w, e_u), the third
    /// (P, e_u, e_v), where e_u is the corner with u = 1.
    pub fn split(&self, bary: DVec3) -> [BezierTriangle; 3] {
        let n = self.degree;
        let levels = self.levels(bary);
        // The point of level r with index (i, j) of the degree n − r net.
        let at = |r: usize, i: usize, j: usize| levels[r][Self::index(n - r, i, j)];
        let make = |f: &dyn Fn(usize, usize, usize) -> DVec3| {
            let mut points = Vec::with_capacity(point_count(n));
            for a in 0..=n {
                for b in 0..=n - a {
                    let c = n - a - b;
                    points.push(f(a, b, c));
                }
            }
            BezierTriangle { degree: n, points }
        };
        // Sub-triangle corner weights (a, b, c) for (P, first, second).
        [
            make(&|a, b, _| at(a, 0, b)),
            make(&|a, _, c| at(a, c, 0)),
            make(&|a, b, c| at(a, b, c)),
        ]
    }
}
