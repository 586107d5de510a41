//! Bézier curves (seeds 000, 001, 002: de Casteljau, the Bernstein form,
//! derivatives as the hodograph, subdivision at t, degree elevation) and
//! the matrix conversion to and from the power basis (seed 003).

use glam::DVec3;

use super::{Curve, CurveError, binomial, check_points};

/// A polynomial Bézier curve on [0, 1] with `degree + 1` control points.
#[derive(Clone, Debug, PartialEq)]
pub struct Bezier {
    /// Control points, first and last on the curve.
    pub points: Vec<DVec3>,
}

/// The Bernstein polynomial `B_i^n(t) = C(n, i) t^i (1 − t)^(n − i)`.
pub fn bernstein(n: usize, i: usize, t: f64) -> f64 {
    binomial(n, i) * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32)
}

impl Bezier {
    /// A curve through its first and last control points.
    ///
    /// # Errors
    /// Fewer than two points, or a non-finite one.
    pub fn new(points: Vec<DVec3>) -> Result<Self, CurveError> {
        if points.len() < 2 {
            return Err(CurveError::TooFewPoints {
                degree: 1,
                needed: 2,
                got: points.len(),
            });
        }
        check_points(&points)?;
        Ok(Bezier { points })
    }

    /// The polynomial degree: one less than the number of control points.
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }

    /// The point at `t` by de Casteljau's repeated linear interpolation
    /// (seed 000): O(n²), numerically the most stable.
    pub fn de_casteljau(&self, t: f64) -> DVec3 {
        let mut b = self.points.clone();
        let n = b.len();
        for r in 1..n {
            for i in 0..n - r {
                b[i] = b[i].lerp(b[i + 1], t);
            }
        }
        b[0]
    }

    /// The point at `t` as `Σ B_i^n(t) b_i` (seed 001).
    pub fn bernstein_point(&self, t: f64) -> DVec3 {
        let n = self.degree();
        self.points
            .iter()
            .enumerate()
            .map(|(i, &b)| bernstein(n, i, t) * b)
            .sum()
    }

    /// The derivative curve (hodograph): degree n − 1 with points
    /// `n (b_{i+1} − b_i)` (seed 002). A degree 0 result is a constant.
    pub fn hodograph(&self) -> Bezier {
        let n = self.degree() as f64;
        let points: Vec<DVec3> = self.points.windows(2).map(|w| n * (w[1] - w[0])).collect();
        Bezier {
            points: if points.is_empty() {
                vec![DVec3::ZERO]
            } else {
                points
            },
        }
    }

    /// The two halves at `t`, from the edges of de Casteljau's triangle
    /// (seed 002): together they trace the same curve.
    pub fn split(&self, t: f64) -> (Bezier, Bezier) {
        let mut b = self.points.clone();
        let n = b.len();
        let mut left = vec![b[0]];
        let mut right = vec![b[n - 1]];
        for r in 1..n {
            for i in 0..n - r {
                b[i] = b[i].lerp(b[i + 1], t);
            }
            left.push(b[0]);
            right.push(b[n - r - 1]);
        }
        right.reverse();
        (Bezier { points: left }, Bezier { points: right })
    }

    /// The same curve with one degree more: `b'_i = i/(n+1) b_{i−1} +
    /// (1 − i/(n+1)) b_i` (seed 002).
    pub fn elevate(&self) -> Bezier {
        let n = self.degree();
        let m = (n + 1) as f64;
        let mut points = Vec::with_capacity(n + 2);
        points.push(self.points[0]);
        for i in 1..=n {
            let a = i as f64 / m;
            points.push(a * self.points[i - 1] + (1.0 - a) * self.points[i]);
        }
        points.push(self.points[n]);
        Bezier { points }
    }

    /// Power-basis coefficients `a_k` with `p(t) = Σ a_k t^k`:
    /// `a_k = C(n, k) Σ_{i ≤ k} (−1)^(k−i) C(k, i) b_i` (the Bernstein to
    /// power basis matrix of seed 003).
    pub fn to_power_basis(&self) -> Vec<DVec3> {
        let n = self.degree();
        (0..=n)
            .map(|k| {
                let sum: DVec3 = (0..=k)
                    .map(|i| {
                        let sign = if (k - i) % 2 == 0 { 1.0 } else { -1.0 };
                        sign * binomial(k, i) * self.points[i]
                    })
                    .sum();
                binomial(n, k) * sum
            })
            .collect()
    }

    /// The Bézier curve of a power-basis polynomial (the inverse matrix):
    /// `b_i = Σ_{k ≤ i} C(i, k) / C(n, k) a_k`.
    ///
    /// # Errors
    /// Fewer than two coefficients or a non-finite one.
    pub fn from_power_basis(coefficients: &[DVec3]) -> Result<Bezier, CurveError> {
        let n = coefficients.len().saturating_sub(1);
        let points = (0..=n)
            .map(|i| {
                (0..=i)
                    .map(|k| binomial(i, k) / binomial(n, k) * coefficients[k])
                    .sum()
            })
            .collect();
        Bezier::new(points)
    }
}

impl Curve for Bezier {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn derivatives(&self, t: f64) -> [DVec3; 3] {
        let t = t.clamp(0.0, 1.0);
        let d1 = self.hodograph();
        let d2 = d1.hodograph();
        [self.de_casteljau(t), d1.de_casteljau(t), d2.de_casteljau(t)]
    }
}
