//! Curves through given points: a polyline with parameters, Lagrange
//! (power-basis) interpolation by solving the Vandermonde system, cubic
//! Hermite segments (and quintic with second derivatives), Catmull-Rom and
//! Kochanek-Bartels splines, the C2 cubic spline, and Chaikin's corner
//! cutting. Sources: seed 000 (polyline, Vandermonde, Hermite basis,
//! Catmull-Rom, Kochanek-Bartels with T, B, C, Chaikin), seed 002 (quintic
//! Hermite), seed 004 (the C2 cubic spline solving for its tangents).

use glam::DVec3;

use super::{Bezier, Curve, CurveError, check_points};

/// Cubic Hermite basis on [0, 1] (seed 000): `H0 = 2t³ − 3t² + 1`,
/// `H1 = t³ − 2t² + t`, `H2 = −2t³ + 3t²`, `H3 = t³ − t²`, with their first
/// and second derivatives.
fn hermite_basis(t: f64) -> [[f64; 4]; 3] {
    let (t2, t3) = (t * t, t * t * t);
    [
        [
            2.0 * t3 - 3.0 * t2 + 1.0,
            t3 - 2.0 * t2 + t,
            -2.0 * t3 + 3.0 * t2,
            t3 - t2,
        ],
        [
            6.0 * t2 - 6.0 * t,
            3.0 * t2 - 4.0 * t + 1.0,
            -6.0 * t2 + 6.0 * t,
            3.0 * t2 - 2.0 * t,
        ],
        [
            12.0 * t - 6.0,
            6.0 * t - 4.0,
            -12.0 * t + 6.0,
            6.0 * t - 2.0,
        ],
    ]
}

/// Parameter values must be finite and increase.
fn check_parameters(params: &[f64], count: usize) -> Result<(), CurveError> {
    if params.len() != count {
        return Err(CurveError::CountMismatch {
            points: count,
            what: "parameter values",
            got: params.len(),
        });
    }
    if let Some(i) = params.iter().position(|t| !t.is_finite()) {
        return Err(CurveError::NotFinite {
            what: "parameter",
            index: i,
        });
    }
    if let Some(i) = (1..params.len()).find(|&i| params[i] <= params[i - 1]) {
        return Err(CurveError::NotIncreasing {
            index: i,
            value: params[i],
        });
    }
    Ok(())
}

/// The segment of `params` containing `t` and the local parameter in it.
fn locate(params: &[f64], t: f64) -> (usize, f64) {
    let t = t.clamp(params[0], params[params.len() - 1]);
    let i = match params.partition_point(|&x| x <= t) {
        0 => 0,
        k => (k - 1).min(params.len() - 2),
    };
    (i, (t - params[i]) / (params[i + 1] - params[i]))
}

/// Piecewise cubic Hermite curve: points `p_i` at parameters `t_i` with
/// tangents `m_i` (derivatives with respect to t). A segment leaves `p_i`
/// along `tangents[i]` and arrives at `p_{i+1}` along `incoming[i + 1]`;
/// the two differ only at Kochanek-Bartels keys with continuity ≠ 0.
#[derive(Clone, Debug, PartialEq)]
pub struct HermiteSpline {
    /// Strictly increasing parameter of each key.
    pub params: Vec<f64>,
    /// The point at each key.
    pub points: Vec<DVec3>,
    /// Outgoing tangent (dp/dt) at each key.
    pub tangents: Vec<DVec3>,
    /// Incoming tangent at each key; equal to `tangents` except at
    /// Kochanek-Bartels keys with continuity ≠ 0.
    pub incoming: Vec<DVec3>,
}

impl HermiteSpline {
    /// # Errors
    /// Fewer than two points, mismatched lengths, parameters that do not
    /// increase, non-finite values.
    pub fn new(
        params: Vec<f64>,
        points: Vec<DVec3>,
        tangents: Vec<DVec3>,
    ) -> Result<Self, CurveError> {
        if points.len() < 2 {
            return Err(CurveError::TooFewPoints {
                degree: 3,
                needed: 2,
                got: points.len(),
            });
        }
        check_points(&points)?;
        check_points(&tangents).map_err(|_| CurveError::NotFiniteVector { what: "a tangent" })?;
        if tangents.len() != points.len() {
            return Err(CurveError::CountMismatch {
                points: points.len(),
                what: "tangents",
                got: tangents.len(),
            });
        }
        check_parameters(&params, points.len())?;
        Ok(HermiteSpline {
            params,
            points,
            incoming: tangents.clone(),
            tangents,
        })
    }

    /// Catmull-Rom: tangents `m_i = (p_{i+1} − p_{i−1}) / (t_{i+1} − t_{i−1})`
    /// (seed 000), one-sided at the ends.
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn catmull_rom(params: Vec<f64>, points: Vec<DVec3>) -> Result<Self, CurveError> {
        let keys = vec![Tbc::default(); points.len()];
        Self::kochanek_bartels(params, points, &keys)
    }

    /// Kochanek-Bartels: per key tension T, bias B and continuity C shape
    /// the incoming and outgoing tangents (seed 000, uniform parameters):
    /// `d_out = (1−T)(1+B)(1+C)/2 (p_i − p_{i−1}) + (1−T)(1−B)(1−C)/2 (p_{i+1} − p_i)`,
    /// `d_in  = (1−T)(1+B)(1−C)/2 (p_i − p_{i−1}) + (1−T)(1−B)(1+C)/2 (p_{i+1} − p_i)`.
    /// T = B = C = 0 is Catmull-Rom. With C ≠ 0 the tangent jumps at the key
    /// (a corner); this stores the outgoing one and uses the incoming one
    /// at the end of the previous segment.
    ///
    /// # Errors
    /// As [`new`](Self::new), and a key count that does not match.
    pub fn kochanek_bartels(
        params: Vec<f64>,
        points: Vec<DVec3>,
        keys: &[Tbc],
    ) -> Result<Self, CurveError> {
        let n = points.len();
        if keys.len() != n {
            return Err(CurveError::CountMismatch {
                points: n,
                what: "T/B/C keys",
                got: keys.len(),
            });
        }
        check_parameters(&params, n)?;
        let mut outgoing = Vec::with_capacity(n);
        let mut incoming = Vec::with_capacity(n);
        for i in 0..n {
            let prev = if i == 0 { points[0] } else { points[i - 1] };
            let next = if i + 1 == n {
                points[n - 1]
            } else {
                points[i + 1]
            };
            let Tbc {
                tension: t,
                bias: b,
                continuity: c,
            } = keys[i];
            let (before, after) = (points[i] - prev, next - points[i]);
            let out = (1.0 - t) * (1.0 + b) * (1.0 + c) / 2.0 * before
                + (1.0 - t) * (1.0 - b) * (1.0 - c) / 2.0 * after;
            let inc = (1.0 - t) * (1.0 + b) * (1.0 - c) / 2.0 * before
                + (1.0 - t) * (1.0 - b) * (1.0 + c) / 2.0 * after;
            // From "per key step" to "per unit of t": divide by the mean
            // neighbouring interval (one-sided at the ends, where one of the
            // two differences is zero, hence the factor 2).
            let per_t = if i == 0 {
                2.0 / (params[1] - params[0])
            } else if i + 1 == n {
                2.0 / (params[n - 1] - params[n - 2])
            } else {
                2.0 / (params[i + 1] - params[i - 1])
            };
            outgoing.push(per_t * out);
            incoming.push(per_t * inc);
        }
        let mut s = Self::new(params, points, outgoing)?;
        s.incoming = incoming;
        Ok(s)
    }

    /// Segment `i` as a cubic Bézier: `b0 = p_i`, `b1 = p_i + h m_i / 3`,
    /// `b2 = p_{i+1} − h m_{i+1} / 3`, `b3 = p_{i+1}` with `h` the interval.
    pub fn bezier_segment(&self, i: usize) -> Bezier {
        let h = self.params[i + 1] - self.params[i];
        Bezier {
            points: vec![
                self.points[i],
                self.points[i] + h * self.tangents[i] / 3.0,
                self.points[i + 1] - h * self.incoming[i + 1] / 3.0,
                self.points[i + 1],
            ],
        }
    }
}

/// A quintic Hermite segment on [0, 1] (seed 002): position, first and
/// second derivative given at both ends; C2 where segments share them.
#[derive(Clone, Debug, PartialEq)]
pub struct QuinticHermite {
    /// Positions `[p0, p1]` at t = 0 and t = 1.
    pub points: [DVec3; 2],
    /// First derivatives `[v0, v1]` at t = 0 and t = 1.
    pub velocities: [DVec3; 2],
    /// Second derivatives `[a0, a1]` at t = 0 and t = 1.
    pub accelerations: [DVec3; 2],
}

/// The six quintic Hermite basis functions and their first and second
/// derivatives, in the order p0, v0, a0, a1, v1, p1.
fn quintic_basis(t: f64) -> [[f64; 6]; 3] {
    let (t2, t3, t4, t5) = (t * t, t.powi(3), t.powi(4), t.powi(5));
    [
        [
            1.0 - 10.0 * t3 + 15.0 * t4 - 6.0 * t5,
            t - 6.0 * t3 + 8.0 * t4 - 3.0 * t5,
            0.5 * t2 - 1.5 * t3 + 1.5 * t4 - 0.5 * t5,
            0.5 * t3 - t4 + 0.5 * t5,
            -4.0 * t3 + 7.0 * t4 - 3.0 * t5,
            10.0 * t3 - 15.0 * t4 + 6.0 * t5,
        ],
        [
            -30.0 * t2 + 60.0 * t3 - 30.0 * t4,
            1.0 - 18.0 * t2 + 32.0 * t3 - 15.0 * t4,
            t - 4.5 * t2 + 6.0 * t3 - 2.5 * t4,
            1.5 * t2 - 4.0 * t3 + 2.5 * t4,
            -12.0 * t2 + 28.0 * t3 - 15.0 * t4,
            30.0 * t2 - 60.0 * t3 + 30.0 * t4,
        ],
        [
            -60.0 * t + 180.0 * t2 - 120.0 * t3,
            -36.0 * t + 96.0 * t2 - 60.0 * t3,
            1.0 - 9.0 * t + 18.0 * t2 - 10.0 * t3,
            3.0 * t - 12.0 * t2 + 10.0 * t3,
            -24.0 * t + 84.0 * t2 - 60.0 * t3,
            60.0 * t - 180.0 * t2 + 120.0 * t3,
        ],
    ]
}

impl Curve for QuinticHermite {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn derivatives(&self, t: f64) -> [DVec3; 3] {
        let t = t.clamp(0.0, 1.0);
        let data = [
            self.points[0],
            self.velocities[0],
            self.accelerations[0],
            self.accelerations[1],
            self.velocities[1],
            self.points[1],
        ];
        quintic_basis(t).map(|b| b.iter().zip(&data).map(|(w, p)| *w * *p).sum())
    }
    fn piece_degree(&self) -> Option<usize> {
        Some(5)
    }
}

/// Tension, bias and continuity of one Kochanek-Bartels key, each in [−1, 1].
#[derive(Copy, Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Tbc {
    /// Tension T: 1 shortens the tangents to zero, −1 doubles them.
    pub tension: f64,
    /// Bias B: > 0 leans the tangent towards the incoming chord, < 0 the
    /// outgoing one.
    pub bias: f64,
    /// Continuity C: ≠ 0 makes the incoming and outgoing tangents differ
    /// (a corner).
    pub continuity: f64,
}

impl Curve for HermiteSpline {
    fn domain(&self) -> (f64, f64) {
        (self.params[0], self.params[self.params.len() - 1])
    }
    /// The keys: one cubic per interval between two (a corner where the
    /// incoming and outgoing tangents differ).
    fn breakpoints(&self) -> Vec<f64> {
        self.params.clone()
    }
    fn piece_degree(&self) -> Option<usize> {
        Some(3)
    }
    fn derivatives(&self, t: f64) -> [DVec3; 3] {
        let (i, s) = locate(&self.params, t);
        let h = self.params[i + 1] - self.params[i];
        let basis = hermite_basis(s);
        let (p0, p1) = (self.points[i], self.points[i + 1]);
        let (m0, m1) = (h * self.tangents[i], h * self.incoming[i + 1]);
        let mut out = [DVec3::ZERO; 3];
        for (k, b) in basis.iter().enumerate() {
            let scale = h.powi(-(k as i32));
            out[k] = scale * (b[0] * p0 + b[1] * m0 + b[2] * p1 + b[3] * m1);
        }
        out
    }
}

/// The cubic C2 spline through points (seed 004): the tangents solve the
/// tridiagonal system that makes second derivatives continuous, with
/// natural ends (zero second derivative).
///
/// # Errors
/// As [`HermiteSpline::new`].
pub fn c2_cubic_spline(params: Vec<f64>, points: Vec<DVec3>) -> Result<HermiteSpline, CurveError> {
    let n = points.len();
    if n < 2 {
        return Err(CurveError::TooFewPoints {
            degree: 3,
            needed: 2,
            got: n,
        });
    }
    check_parameters(&params, n)?;
    let h: Vec<f64> = params.windows(2).map(|w| w[1] - w[0]).collect();
    // Equations for m_i (derivatives), from C2 at interior points:
    // h_i m_{i−1} + 2(h_{i−1}+h_i) m_i + h_{i−1} m_{i+1} = 3(h_i/h_{i−1}(p_i−p_{i−1}) + h_{i−1}/h_i(p_{i+1}−p_i));
    // natural ends: 2 m_0 + m_1 = 3 (p_1 − p_0)/h_0, m_{n−2} + 2 m_{n−1} = 3 (p_{n−1} − p_{n−2})/h_{n−2}.
    let mut a = vec![0.0; n];
    let mut b = vec![0.0; n];
    let mut c = vec![0.0; n];
    let mut d = vec![DVec3::ZERO; n];
    b[0] = 2.0;
    c[0] = 1.0;
    d[0] = 3.0 * (points[1] - points[0]) / h[0];
    for i in 1..n - 1 {
        a[i] = h[i];
        b[i] = 2.0 * (h[i - 1] + h[i]);
        c[i] = h[i - 1];
        d[i] = 3.0
            * (h[i] / h[i - 1] * (points[i] - points[i - 1])
                + h[i - 1] / h[i] * (points[i + 1] - points[i]));
    }
    a[n - 1] = 1.0;
    b[n - 1] = 2.0;
    d[n - 1] = 3.0 * (points[n - 1] - points[n - 2]) / h[n - 2];
    // Thomas algorithm.
    for i in 1..n {
        let w = a[i] / b[i - 1];
        b[i] -= w * c[i - 1];
        let prev = d[i - 1];
        d[i] -= w * prev;
    }
    let mut m = vec![DVec3::ZERO; n];
    m[n - 1] = d[n - 1] / b[n - 1];
    for i in (0..n - 1).rev() {
        m[i] = (d[i] - c[i] * m[i + 1]) / b[i];
    }
    HermiteSpline::new(params, points, m)
}

/// The polynomial of degree n − 1 through n points at the given parameters,
/// in the power basis: the Vandermonde system `Σ_k a_k t_i^k = p_i` solved
/// by Gaussian elimination with partial pivoting (seed 000).
#[derive(Clone, Debug, PartialEq)]
pub struct PowerBasisCurve {
    /// `p(t) = Σ coefficients[k] t^k`.
    pub coefficients: Vec<DVec3>,
    /// `(first, last)` interpolation parameter; evaluation clamps to it.
    pub domain: (f64, f64),
}

impl PowerBasisCurve {
    /// # Errors
    /// Mismatched lengths, parameters that do not increase, or a system
    /// too ill-conditioned to solve.
    pub fn interpolate(params: &[f64], points: &[DVec3]) -> Result<Self, CurveError> {
        let n = points.len();
        if n < 2 {
            return Err(CurveError::TooFewPoints {
                degree: 1,
                needed: 2,
                got: n,
            });
        }
        check_points(points)?;
        check_parameters(params, n)?;
        let m: Vec<Vec<f64>> = params
            .iter()
            .map(|&t| (0..n).map(|k| t.powi(k as i32)).collect())
            .collect();
        let coefficients = solve_dense(m, points.to_vec())?;
        Ok(PowerBasisCurve {
            coefficients,
            domain: (params[0], params[n - 1]),
        })
    }
}

impl Curve for PowerBasisCurve {
    fn domain(&self) -> (f64, f64) {
        self.domain
    }
    fn derivatives(&self, t: f64) -> [DVec3; 3] {
        let t = t.clamp(self.domain.0, self.domain.1);
        let mut out = [DVec3::ZERO; 3];
        // Horner's rule for the value and both derivatives.
        for (k, &a) in self.coefficients.iter().enumerate().rev() {
            out[2] = out[2] * t + 2.0 * out[1];
            out[1] = out[1] * t + out[0];
            out[0] = out[0] * t + a;
            let _ = k;
        }
        out
    }
    fn piece_degree(&self) -> Option<usize> {
        Some(self.coefficients.len().saturating_sub(1).max(1))
    }
}

/// A polyline through points at parameters (linear interpolation).
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline {
    /// Parameter of each point, increasing.
    pub params: Vec<f64>,
    /// The points, in order.
    pub points: Vec<DVec3>,
}

impl Polyline {
    /// # Errors
    /// Fewer than two points or parameters that do not increase.
    pub fn new(params: Vec<f64>, points: Vec<DVec3>) -> Result<Self, CurveError> {
        if points.len() < 2 {
            return Err(CurveError::TooFewPoints {
                degree: 1,
                needed: 2,
                got: points.len(),
            });
        }
        check_points(&points)?;
        check_parameters(&params, points.len())?;
        Ok(Polyline { params, points })
    }
}

impl Curve for Polyline {
    fn domain(&self) -> (f64, f64) {
        (self.params[0], self.params[self.params.len() - 1])
    }
    /// Every vertex.
    fn breakpoints(&self) -> Vec<f64> {
        self.params.clone()
    }
    fn piece_degree(&self) -> Option<usize> {
        Some(1)
    }
    fn derivatives(&self, t: f64) -> [DVec3; 3] {
        let (i, s) = locate(&self.params, t);
        let h = self.params[i + 1] - self.params[i];
        let (a, b) = (self.points[i], self.points[i + 1]);
        [a.lerp(b, s), (b - a) / h, DVec3::ZERO]
    }
}

/// Chaikin's corner cutting (seed 000): every edge `(a, b)` is replaced by
/// the points at ¼ and ¾; repeated, the polygon converges to the quadratic
/// uniform B-spline of the original points. Open polygons keep their ends.
pub fn chaikin(points: &[DVec3], iterations: u32, closed: bool) -> Vec<DVec3> {
    let mut p = points.to_vec();
    for _ in 0..iterations {
        if p.len() < 2 {
            break;
        }
        let mut next = Vec::with_capacity(2 * p.len());
        if !closed {
            next.push(p[0]);
        }
        let edges = if closed { p.len() } else { p.len() - 1 };
        for i in 0..edges {
            let (a, b) = (p[i], p[(i + 1) % p.len()]);
            next.push(a.lerp(b, 0.25));
            next.push(a.lerp(b, 0.75));
        }
        if !closed {
            next.push(p[p.len() - 1]);
        }
        p = next;
    }
    p
}

/// Solves the dense system `m x = rhs` by Gaussian elimination with
/// partial pivoting.
pub(crate) fn solve_dense(
    mut m: Vec<Vec<f64>>,
    mut rhs: Vec<DVec3>,
) -> Result<Vec<DVec3>, CurveError> {
    let n = rhs.len();
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))
            .expect("rows remain");
        if m[pivot][col].abs() < 1e-300 {
            return Err(CurveError::Singular);
        }
        m.swap(col, pivot);
        rhs.swap(col, pivot);
        for row in col + 1..n {
            let f = m[row][col] / m[col][col];
            let (above, below) = m.split_at_mut(row);
            for (x, y) in below[0][col..].iter_mut().zip(&above[col][col..]) {
                *x -= f * y;
            }
            let r = rhs[col];
            rhs[row] -= f * r;
        }
    }
    let mut x = vec![DVec3::ZERO; n];
    for row in (0..n).rev() {
        let mut s = rhs[row];
        for k in row + 1..n {
            s -= m[row][k] * x[k];
        }
        x[row] = s / m[row][row];
    }
    Ok(x)
}
