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

/// Seed 003's basis matrix `M` of degree `n`: `[uⁿ, …, u, 1] · M =
/// [Bₙⁿ(u), …, B₁ⁿ(u), B₀ⁿ(u)]`, so that a Bézier curve with control
/// points `G = [bₙ, …, b₀]ᵀ` has power-basis coefficients `A = M G =
/// [aₙ, …, a₀]ᵀ`, `r(u) = Σ aₖ uᵏ`. Both are in the seed's descending
/// order: row r stands for `u^(n−r)`, column c for `b_(n−c)`. The entry is
/// the coefficient of `uᵏ` in `Bᵢⁿ`, `C(n, i) C(n − i, k − i) (−1)^(k−i)`
/// for k ≥ i. For n = 2 it is the seed's `[[1, −2, 1], [0, 2, −2], [0, 0,
/// 1]]`. Inverse: [`power_to_bernstein_matrix`]. O(n²).
pub fn bernstein_to_power_matrix(n: usize) -> Vec<Vec<f64>> {
    (0..=n)
        .map(|r| {
            let k = n - r;
            (0..=n)
                .map(|c| {
                    let i = n - c;
                    if k < i {
                        0.0
                    } else {
                        let sign = if (k - i).is_multiple_of(2) { 1.0 } else { -1.0 };
                        sign * binomial(n, i) * binomial(n - i, k - i)
                    }
                })
                .collect()
        })
        .collect()
}

/// `M⁻¹` of [`bernstein_to_power_matrix`]: `G = M⁻¹ A`, from power-basis
/// coefficients `[aₙ, …, a₀]` to Bézier control points `[bₙ, …, b₀]`
/// (seed 003's "báziskonverzió", `X = M₂⁻¹ M₁ G₁` with `M₁ = I`). The
/// entry for `b_i` and `a_k` is `C(i, k) / C(n, k)` (k ≤ i), since `uᵏ =
/// Σ_(i≥k) C(i, k) / C(n, k) Bᵢⁿ(u)`. For n = 2 it is the seed's `[[1, 1,
/// 1], [0, ½, 1], [0, 0, 1]]`. O(n²).
pub fn power_to_bernstein_matrix(n: usize) -> Vec<Vec<f64>> {
    (0..=n)
        .map(|r| {
            let i = n - r;
            (0..=n)
                .map(|c| {
                    let k = n - c;
                    binomial(i, k) / binomial(n, k)
                })
                .collect()
        })
        .collect()
}

/// `M · G` for a matrix `M` and a column of values (points, weights).
fn apply<T>(m: &[Vec<f64>], g: &[T]) -> Vec<T>
where
    T: Copy + std::iter::Sum<T> + std::ops::Mul<f64, Output = T>,
{
    m.iter()
        .map(|row| row.iter().zip(g).map(|(&x, &v)| v * x).sum())
        .collect()
}

/// One Bézier segment of a curve in seed 003's matrix form, `r(u) = uᵀ M
/// G` with the segment's own parameter `u = (t − t₀)/(t₁ − t₀)` in [0, 1].
/// A rational segment is `r(u) = (uᵀ A) / (uᵀ W)` with `A = M (w G)` and
/// `W = M w`; a polynomial one has `W = [0, …, 0, 1]` and `A = M G`.
/// Every list is in the seed's descending order (index 0 is degree n).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PowerBasisSegment {
    /// The segment's interval `(t₀, t₁)` on the curve.
    pub interval: (f64, f64),
    /// `M` of the segment's degree ([`bernstein_to_power_matrix`]).
    pub matrix: Vec<Vec<f64>>,
    /// `G`: the control points `bₙ, …, b₀`.
    pub control_points: Vec<DVec3>,
    /// Their weights `wₙ, …, w₀` (all 1 when polynomial).
    pub weights: Vec<f64>,
    /// `A = M (w G)`: the coefficients `aₙ, …, a₀` of the numerator
    /// (of `r(u)` itself when polynomial).
    pub coefficients: Vec<DVec3>,
    /// `W = M w`: the coefficients of the denominator `Σ wᵢ Bᵢⁿ(u)`.
    pub weight_coefficients: Vec<f64>,
}

impl PowerBasisSegment {
    /// The segment of Bézier control points `points` (b₀ first, as a curve
    /// stores them) with `weights`, on `interval`. O(n²).
    pub fn new(interval: (f64, f64), points: &[DVec3], weights: &[f64]) -> Self {
        let n = points.len() - 1;
        let matrix = bernstein_to_power_matrix(n);
        let control_points: Vec<DVec3> = points.iter().rev().copied().collect();
        let weights: Vec<f64> = weights.iter().rev().copied().collect();
        let weighted: Vec<DVec3> = control_points
            .iter()
            .zip(&weights)
            .map(|(&p, &w)| p * w)
            .collect();
        let coefficients = apply(&matrix, &weighted);
        let weight_coefficients = apply(&matrix, &weights);
        PowerBasisSegment {
            interval,
            matrix,
            control_points,
            weights,
            coefficients,
            weight_coefficients,
        }
    }

    /// The point at the segment's own parameter `u` by Horner's rule on
    /// the coefficients. O(n).
    pub fn point(&self, u: f64) -> DVec3 {
        let a = self
            .coefficients
            .iter()
            .fold(DVec3::ZERO, |acc, &c| acc * u + c);
        let w = self
            .weight_coefficients
            .iter()
            .fold(0.0, |acc, &c| acc * u + c);
        a / w
    }

    /// The control points back from the coefficients, `G = M⁻¹ A / M⁻¹ W`
    /// ([`power_to_bernstein_matrix`]), in the seed's order `bₙ, …, b₀`;
    /// the inverse of [`new`](Self::new) to rounding. O(n²).
    pub fn control_points_from_coefficients(&self) -> Vec<DVec3> {
        let inverse = power_to_bernstein_matrix(self.coefficients.len() - 1);
        let weighted = apply(&inverse, &self.coefficients);
        let weights = apply(&inverse, &self.weight_coefficients);
        weighted
            .iter()
            .zip(&weights)
            .map(|(&p, &w)| p / w)
            .collect()
    }
}

/// Every Bézier segment of `curve` ([`NurbsCurve::bezier_segments`]) in
/// seed 003's matrix form. O(k p²) for k segments of degree p.
///
/// [`NurbsCurve::bezier_segments`]: super::NurbsCurve::bezier_segments
///
/// # Errors
/// A knot insertion that fails.
pub fn power_basis_segments(
    curve: &super::NurbsCurve,
) -> Result<Vec<PowerBasisSegment>, CurveError> {
    Ok(curve
        .bezier_segments()?
        .into_iter()
        .map(|(interval, pw)| {
            let points: Vec<DVec3> = pw.iter().map(|h| h.truncate() / h.w).collect();
            let weights: Vec<f64> = pw.iter().map(|h| h.w).collect();
            PowerBasisSegment::new(interval, &points, &weights)
        })
        .collect())
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
    fn piece_degree(&self) -> Option<usize> {
        Some(self.points.len().saturating_sub(1).max(1))
    }
}
