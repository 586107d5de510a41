//! Fast batch evaluation of NURBS curves, and the basis that surface grids
//! ([`crate::surfaces::fast`]) share, for tessellation and benchmarks. The
//! B-spline basis at `u` (The NURBS Book, A2.2) divides by knot differences
//! that depend only on the span, so their reciprocals are computed once per
//! span; sorted parameters find their span without a search.

use glam::{DVec3, DVec4};

/// Degrees above this use the general evaluator.
pub const MAX_FAST_DEGREE: usize = 15;

/// One direction's basis: knots, degree and the reciprocal denominators of
/// A2.2 per span.
#[derive(Clone, Debug)]
pub struct Basis {
    degree: usize,
    knots: Vec<f64>,
    /// First span index with a non-empty interval and the last.
    first: usize,
    last: usize,
    /// Per span `i` (from `first`), `p(p+1)/2` reciprocals of
    /// `U[i+r+1] − U[i+1−j+r]` for j = 1..=p, r = 0..j (0 where the difference is 0).
    inv: Vec<f64>,
}

impl Basis {
    /// The basis of `count` control points of degree `degree` on `knots`
    /// (already validated by the curve or surface).
    pub fn new(degree: usize, knots: &[f64], count: usize) -> Basis {
        let p = degree;
        let (first, last) = (p, count - 1);
        let per = p * (p + 1) / 2;
        let mut inv = Vec::with_capacity((last + 1 - first) * per);
        for i in first..=last {
            for j in 1..=p {
                for r in 0..j {
                    let d = knots[i + r + 1] - knots[i + 1 - j + r];
                    inv.push(if d != 0.0 { 1.0 / d } else { 0.0 });
                }
            }
        }
        Basis {
            degree,
            knots: knots.to_vec(),
            first,
            last,
            inv,
        }
    }

    /// The polynomial degree p of the basis functions.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The first span with a non-empty interval (where span searches start).
    #[inline]
    pub fn first_span(&self) -> usize {
        self.first
    }

    /// The span of `u`, starting the search at `hint` (the previous span).
    #[inline]
    pub fn span(&self, u: f64, hint: usize) -> usize {
        let k = &self.knots;
        let hint = hint.clamp(self.first, self.last);
        if u >= k[hint] && (u < k[hint + 1] || hint == self.last) {
            // Skip empty spans at the end of the domain.
            return hint;
        }
        if u >= k[self.last + 1] {
            let mut i = self.last;
            while i > self.first && k[i] >= k[self.last + 1] {
                i -= 1;
            }
            return i;
        }
        if u <= k[self.first] {
            let mut i = self.first;
            while k[i + 1] <= u {
                i += 1;
            }
            return i;
        }
        let (mut lo, mut hi) = (self.first, self.last + 1);
        let mut mid = (lo + hi) / 2;
        while u < k[mid] || u >= k[mid + 1] {
            if u < k[mid] {
                hi = mid;
            } else {
                lo = mid;
            }
            mid = (lo + hi) / 2;
        }
        mid
    }

    /// The `p + 1` non-zero basis functions at `u` in span `i` (A2.2 with
    /// the stored reciprocals).
    #[inline]
    pub fn functions(&self, i: usize, u: f64, n: &mut [f64; MAX_FAST_DEGREE + 1]) {
        self.triangle(i, u, n, None);
    }

    /// A2.2's triangle of basis values; with `lower`, also the degree
    /// `p − 1` values (functions `i − p + 1 ..= i`) met on the way.
    #[inline]
    fn triangle(
        &self,
        i: usize,
        u: f64,
        n: &mut [f64; MAX_FAST_DEGREE + 1],
        mut lower: Option<&mut [f64; MAX_FAST_DEGREE + 1]>,
    ) {
        let p = self.degree;
        let k = &self.knots;
        let inv = &self.inv[(i - self.first) * (p * (p + 1) / 2)..];
        let mut left = [0.0; MAX_FAST_DEGREE + 1];
        let mut right = [0.0; MAX_FAST_DEGREE + 1];
        n[0] = 1.0;
        let mut at = 0;
        for j in 1..=p {
            left[j] = u - k[i + 1 - j];
            right[j] = k[i + j] - u;
            if j == p
                && let Some(lower) = lower.as_deref_mut()
            {
                lower[..p].copy_from_slice(&n[..p]);
            }
            let mut saved = 0.0;
            for r in 0..j {
                let temp = n[r] * inv[at];
                at += 1;
                n[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            n[j] = saved;
        }
    }

    /// The basis functions and their first derivatives at `u` in span `i`:
    /// `N'_{a,p} = p (N_{a,p−1} / (U_{a+p} − U_a) − N_{a+1,p−1} / (U_{a+p+1} − U_{a+1}))`.
    #[inline]
    pub fn functions_and_derivatives(
        &self,
        i: usize,
        u: f64,
        n: &mut [f64; MAX_FAST_DEGREE + 1],
        d: &mut [f64; MAX_FAST_DEGREE + 1],
    ) {
        let p = self.degree;
        let k = &self.knots;
        if p == 0 {
            n[0] = 1.0;
            d[0] = 0.0;
            return;
        }
        let mut m = [0.0; MAX_FAST_DEGREE + 1];
        self.triangle(i, u, n, Some(&mut m));
        // `m[..p]` holds degree p − 1 (functions i−p+1 ..= i).
        let pf = p as f64;
        for r in 0..=p {
            let a = i - p + r;
            let mut v = 0.0;
            if r >= 1 {
                let den = k[a + p] - k[a];
                if den != 0.0 {
                    v += m[r - 1] / den;
                }
            }
            if r < p {
                let den = k[a + p + 1] - k[a + 1];
                if den != 0.0 {
                    v -= m[r] / den;
                }
            }
            d[r] = pf * v;
        }
    }
}

/// Homogeneous control points `(w P, w)`.
pub fn homogeneous_points(points: &[DVec3], weights: &[f64]) -> Vec<DVec4> {
    points
        .iter()
        .zip(weights)
        .map(|(p, &w)| (*p * w).extend(w))
        .collect()
}

/// Points of a NURBS curve at many parameters (any order; increasing ones
/// are fastest). Each knot span's homogeneous polynomial is turned into
/// power-basis coefficients around the span's start once (its Taylor
/// coefficients, from the basis derivatives), so a point costs one span
/// check and `p` fused steps of Horner's rule.
pub fn curve_points(basis: &Basis, pw: &[DVec4], params: &[f64]) -> Vec<DVec3> {
    let p = basis.degree;
    let spans = basis.last + 1 - basis.first;
    // Taylor coefficients A^(k)(u_i) / k! of every span.
    let mut coefficients = vec![DVec4::ZERO; spans * (p + 1)];
    for (s, chunk) in coefficients.chunks_mut(p + 1).enumerate() {
        let i = basis.first + s;
        let start = basis.knots[i];
        if basis.knots[i + 1] <= start {
            continue; // an empty span is never evaluated
        }
        let ders = crate::curves::nurbs::basis_derivatives(&basis.knots, i, start, p, p);
        let mut factorial = 1.0;
        for (k, row) in ders.iter().enumerate() {
            if k > 0 {
                factorial *= k as f64;
            }
            let mut c = DVec4::ZERO;
            for (r, &b) in row.iter().enumerate() {
                c += b * pw[i - p + r];
            }
            chunk[k] = c / factorial;
        }
    }
    let mut out = Vec::with_capacity(params.len());
    let mut span = basis.first;
    for &u in params {
        span = basis.span(u, span);
        let c = &coefficients[(span - basis.first) * (p + 1)..][..p + 1];
        let h = u - basis.knots[span];
        let mut a = c[p];
        for k in (0..p).rev() {
            a = a * h + c[k];
        }
        out.push(a.truncate() / a.w);
    }
    out
}

/// Old name of [`crate::surfaces::fast::evaluate_grid`].
#[doc(hidden)]
pub use crate::surfaces::fast::evaluate_grid as surface_grid;
