//! Operations on any [`Curve`] (seed 001, "Műveletek görbékkel"): arc
//! length, the closest point by Newton-Raphson with the geometric stopping
//! rule, the Frenet frame, curvature and the osculating circle, and points
//! at equal arc-length spacing.

use glam::DVec3;

use super::Curve;

/// Nodes and weights of 5-point Gauss-Legendre quadrature on [−1, 1].
const GAUSS: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_08),
    (0.906_179_845_938_664, 0.236_926_885_056_189_08),
];

fn gauss(curve: &dyn Curve, a: f64, b: f64) -> f64 {
    let (mid, half) = ((a + b) / 2.0, (b - a) / 2.0);
    GAUSS
        .iter()
        .map(|&(x, w)| w * curve.derivatives(mid + half * x)[1].length())
        .sum::<f64>()
        * half
}

/// Arc length `∫ |p'(t)| dt` from `a` to `b` by adaptive Gauss-Legendre
/// quadrature to a relative tolerance of about 1e-12.
pub fn arc_length(curve: &dyn Curve, a: f64, b: f64) -> f64 {
    fn adapt(curve: &dyn Curve, a: f64, b: f64, whole: f64, depth: u32) -> f64 {
        let m = (a + b) / 2.0;
        let (l, r) = (gauss(curve, a, m), gauss(curve, m, b));
        if depth == 0 || (l + r - whole).abs() <= 1e-13 * (l + r).abs().max(1e-300) {
            l + r
        } else {
            adapt(curve, a, m, l, depth - 1) + adapt(curve, m, b, r, depth - 1)
        }
    }
    if b <= a {
        return 0.0;
    }
    adapt(curve, a, b, gauss(curve, a, b), 30)
}

/// The parameter of the point of `curve` nearest to `x`: the best of a
/// coarse sampling is refined by Newton-Raphson on `f(t) = ⟨x − p(t), p'(t)⟩`
/// until the geometric criterion holds — the cosine of the angle between
/// `x − p(t)` and the tangent is below `1e-12` (the parameterisation-free
/// rule of the seed) — or the step stalls; the ends are checked too.
pub fn closest_parameter(curve: &dyn Curve, x: DVec3) -> f64 {
    let (a, b) = curve.domain();
    let samples = 64;
    let mut best = a;
    let mut best_d = f64::INFINITY;
    for i in 0..=samples {
        let t = a + (b - a) * i as f64 / samples as f64;
        let d = curve.point(t).distance_squared(x);
        if d < best_d {
            best_d = d;
            best = t;
        }
    }
    let mut t = best;
    for _ in 0..50 {
        let [p, d1, d2] = curve.derivatives(t);
        let r = x - p;
        let (rl, dl) = (r.length(), d1.length());
        if rl < 1e-15 || dl < 1e-300 || (r.dot(d1) / (rl * dl)).abs() < 1e-12 {
            break;
        }
        let f = r.dot(d1);
        let df = r.dot(d2) - d1.length_squared();
        if df.abs() < 1e-300 {
            break;
        }
        let next = (t - f / df).clamp(a, b);
        if (next - t).abs() < 1e-15 * (b - a) {
            t = next;
            break;
        }
        t = next;
    }
    // The true closest point may be an end of the curve.
    [t, a, b]
        .into_iter()
        .min_by(|&u, &v| {
            curve
                .point(u)
                .distance_squared(x)
                .total_cmp(&curve.point(v).distance_squared(x))
        })
        .expect("three candidates")
}

/// The Frenet frame at `t` (seed 001): unit tangent `t = p'/|p'|`, binormal
/// `b = (p' × p'')/|p' × p''|`, principal normal `n = b × t`. `None` where
/// the curve is straight (no normal) or stops (`p' = 0`).
pub fn frenet_frame(curve: &dyn Curve, t: f64) -> Option<[DVec3; 3]> {
    let [_, d1, d2] = curve.derivatives(t);
    let tangent = d1.try_normalize()?;
    let binormal = d1.cross(d2).try_normalize()?;
    Some([tangent, binormal.cross(tangent), binormal])
}

/// Curvature `κ = |p' × p''| / |p'|³` (seed 001).
pub fn curvature(curve: &dyn Curve, t: f64) -> f64 {
    let [_, d1, d2] = curve.derivatives(t);
    let speed = d1.length();
    if speed < 1e-300 {
        return 0.0;
    }
    d1.cross(d2).length() / (speed * speed * speed)
}

/// The osculating circle at `t`: centre `p + n/κ` and radius `1/κ`; `None`
/// where the curve is straight.
pub fn osculating_circle(curve: &dyn Curve, t: f64) -> Option<(DVec3, f64)> {
    let k = curvature(curve, t);
    let [_, normal, _] = frenet_frame(curve, t)?;
    (k > 1e-300).then(|| (curve.point(t) + normal / k, 1.0 / k))
}

/// `count` parameters (≥ 2) splitting the curve into pieces of equal arc
/// length, each found by Newton's method on `s(t) − target` (seed 001's
/// exercise), safeguarded by bisection.
pub fn equal_arc_length_parameters(curve: &dyn Curve, count: usize) -> Vec<f64> {
    let (a, b) = curve.domain();
    let total = arc_length(curve, a, b);
    let count = count.max(2);
    let mut out = vec![a];
    let mut prev = a;
    for i in 1..count - 1 {
        let target = total * i as f64 / (count - 1) as f64;
        let (mut lo, mut hi) = (prev, b);
        let mut t = prev
            + (b - prev) * (target - arc_length(curve, a, prev))
                / (total - arc_length(curve, a, prev)).max(1e-300);
        for _ in 0..60 {
            let f = arc_length(curve, a, t) - target;
            if f.abs() < 1e-12 * total.max(1.0) {
                break;
            }
            if f > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let speed = curve.derivatives(t)[1].length();
            let newton = t - f / speed.max(1e-300);
            t = if newton > lo && newton < hi {
                newton
            } else {
                (lo + hi) / 2.0
            };
        }
        out.push(t);
        prev = t;
    }
    out.push(b);
    out
}

/// How smoothly a curve that ends where another starts joins it.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Continuity {
    /// Positions meet.
    pub c0: bool,
    /// First derivatives are equal.
    pub c1: bool,
    /// Second derivatives are equal too.
    pub c2: bool,
    /// Tangent directions agree (seed 000: `m_i = α m_{i+1}`, α > 0).
    pub g1: bool,
    /// Tangent directions and curvature vectors agree.
    pub g2: bool,
}

/// The continuity of the joint between the end of `first` and the start of
/// `second`, each test within `tolerance` (relative for derivatives).
pub fn continuity(first: &dyn Curve, second: &dyn Curve, tolerance: f64) -> Continuity {
    let [p0, a1, a2] = first.derivatives(first.domain().1);
    let [q0, b1, b2] = second.derivatives(second.domain().0);
    let same =
        |x: DVec3, y: DVec3| (x - y).length() <= tolerance * (1.0 + x.length().max(y.length()));
    let c0 = (p0 - q0).length() <= tolerance;
    let g1 = c0
        && match (a1.try_normalize(), b1.try_normalize()) {
            (Some(ta), Some(tb)) => same(ta, tb),
            _ => false,
        };
    // Curvature vector κ n = (p' × p'') × p' / |p'|⁴.
    let curvature_vector =
        |d1: DVec3, d2: DVec3| d1.cross(d2).cross(d1) / d1.length_squared().powi(2);
    let g2 = g1 && same(curvature_vector(a1, a2), curvature_vector(b1, b2));
    let c1 = c0 && same(a1, b1);
    Continuity {
        c0,
        c1,
        c2: c1 && same(a2, b2),
        g1,
        g2,
    }
}
