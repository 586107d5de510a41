//! Fast batch evaluation of NURBS surfaces on a parameter grid, for
//! tessellation and benchmarks: the tensor-product trick (The NURBS Book's
//! surface point, A4.3, shared across a grid): each u-row of control points
//! is combined once per `u`, then a point needs only `q + 1` terms, with
//! the per-span basis of [`crate::curves::fast::Basis`] (A2.2).

use crate::curves::fast::{Basis, MAX_FAST_DEGREE};
use glam::{DVec3, DVec4};

/// Evaluates a NURBS surface on a parameter grid: points and unit normals
/// at every `(us[a], vs[b])`, row-major (`a * vs.len() + b`). `pw` is
/// `nu × nv` row-major (i along u). (Choosing the grid's parameters for the
/// viewport is `hedra_doc::render::surface_grid`.)
///
/// The v-basis of every column is computed once; the columns are grouped
/// by knot span, so within a group the `q + 1` combined control points are
/// constants held in registers. Degrees `q` up to 5 get a loop with the
/// `q + 1` terms unrolled and no bounds checks; each grid row is built in a
/// small buffer and copied out whole (no per-point push). The sums are
/// taken in the same order as A4.3; a point is `A / w` taken as
/// `A · (1 / w)` (within an ulp of the quotient), and the normal is that of
/// `(A_u − w_u S) × (A_v − w_v S)`, which is `w² S_u × S_v`.
pub fn evaluate_grid(
    bu: &Basis,
    bv: &Basis,
    nv: usize,
    pw: &[DVec4],
    us: &[f64],
    vs: &[f64],
    normals: bool,
) -> (Vec<DVec3>, Vec<DVec3>) {
    match bv.degree() {
        0 => grid_with::<1>(bu, bv, nv, pw, us, vs, normals),
        1 => grid_with::<2>(bu, bv, nv, pw, us, vs, normals),
        2 => grid_with::<3>(bu, bv, nv, pw, us, vs, normals),
        3 => grid_with::<4>(bu, bv, nv, pw, us, vs, normals),
        4 => grid_with::<5>(bu, bv, nv, pw, us, vs, normals),
        5 => grid_with::<6>(bu, bv, nv, pw, us, vs, normals),
        _ => grid_any_degree(bu, bv, nv, pw, us, vs, normals),
    }
}

/// The columns `first..end` of a grid row all lie in the v-span `span`.
struct Segment {
    span: usize,
    first: usize,
    end: usize,
}

/// [`evaluate_grid`] for `bv.degree() == Q - 1`.
fn grid_with<const Q: usize>(
    bu: &Basis,
    bv: &Basis,
    nv: usize,
    pw: &[DVec4],
    us: &[f64],
    vs: &[f64],
    normals: bool,
) -> (Vec<DVec3>, Vec<DVec3>) {
    let p = bu.degree();
    let q = Q - 1;
    let m = vs.len();
    // The v-basis (and its derivative) of every column, and the runs of
    // columns that share a span.
    let mut nb: Vec<[f64; Q]> = Vec::with_capacity(m);
    let mut db: Vec<[f64; Q]> = Vec::with_capacity(if normals { m } else { 0 });
    let mut segments: Vec<Segment> = Vec::new();
    let mut s = bv.first_span();
    for (k, &v) in vs.iter().enumerate() {
        s = bv.span(v, s);
        let (mut n, mut d) = ([0.0; MAX_FAST_DEGREE + 1], [0.0; MAX_FAST_DEGREE + 1]);
        if normals {
            bv.functions_and_derivatives(s, v, &mut n, &mut d);
        } else {
            bv.functions(s, v, &mut n);
        }
        nb.push(std::array::from_fn(|r| n[r]));
        if normals {
            db.push(std::array::from_fn(|r| d[r]));
        }
        match segments.last_mut() {
            Some(g) if g.span == s => g.end = k + 1,
            _ => segments.push(Segment {
                span: s,
                first: k,
                end: k + 1,
            }),
        }
    }
    let mut points = Vec::with_capacity(us.len() * m);
    let mut norms = Vec::with_capacity(if normals { us.len() * m } else { 0 });
    let mut row0 = vec![DVec4::ZERO; nv];
    let mut row1 = vec![DVec4::ZERO; nv];
    let (mut n, mut d) = ([0.0; MAX_FAST_DEGREE + 1], [0.0; MAX_FAST_DEGREE + 1]);
    // One grid row (small enough to stay in cache), copied out whole.
    let mut row_points = vec![DVec3::ZERO; m];
    let mut row_normals = vec![DVec3::ZERO; if normals { m } else { 0 }];
    let mut su = bu.first_span();
    for &u in us {
        su = bu.span(u, su);
        if normals {
            bu.functions_and_derivatives(su, u, &mut n, &mut d);
        } else {
            bu.functions(su, u, &mut n);
        }
        // Combine the p + 1 rows of control points under this u once.
        let rows = &pw[(su - p) * nv..][..(p + 1) * nv];
        for j in 0..nv {
            let (mut a, mut b) = (DVec4::ZERO, DVec4::ZERO);
            for r in 0..=p {
                let c = rows[r * nv + j];
                a += n[r] * c;
                if normals {
                    b += d[r] * c;
                }
            }
            row0[j] = a;
            row1[j] = b;
        }
        if !normals {
            for g in &segments {
                let c: [DVec4; Q] = std::array::from_fn(|r| row0[g.span - q + r]);
                let range = g.first..g.end;
                for (o, n) in row_points[range.clone()].iter_mut().zip(&nb[range]) {
                    let h = combine(n, &c);
                    *o = h.truncate() * h.w.recip();
                }
            }
            points.extend_from_slice(&row_points);
        } else {
            for g in &segments {
                let c0: [DVec4; Q] = std::array::from_fn(|r| row0[g.span - q + r]);
                let c1: [DVec4; Q] = std::array::from_fn(|r| row1[g.span - q + r]);
                let range = g.first..g.end;
                let out = row_points[range.clone()]
                    .iter_mut()
                    .zip(&mut row_normals[range.clone()]);
                for ((o, no), (n, d)) in out.zip(nb[range.clone()].iter().zip(&db[range])) {
                    let h = combine(n, &c0);
                    let hu = combine(n, &c1);
                    let hv = combine(d, &c0);
                    let s = h.truncate() * h.w.recip();
                    // S_u = (A_u − w_u S) / w, the same for v (The NURBS
                    // Book, eq. 4.8); the normal's direction does not need
                    // the positive factor 1 / w² of S_u × S_v.
                    let su_w = hu.truncate() - hu.w * s;
                    let sv_w = hv.truncate() - hv.w * s;
                    *o = s;
                    *no = su_w.cross(sv_w).normalize_or_zero();
                }
            }
            points.extend_from_slice(&row_points);
            norms.extend_from_slice(&row_normals);
        }
    }
    (points, norms)
}

/// `Σ_r n[r] · c[r]`, summed from `r = 0` up (as A4.3).
#[inline(always)]
fn combine<const Q: usize>(n: &[f64; Q], c: &[DVec4; Q]) -> DVec4 {
    let mut h = DVec4::ZERO;
    for r in 0..Q {
        h += n[r] * c[r];
    }
    h
}

/// [`evaluate_grid`] for any degree in v (the plain A4.3 loop over a row).
fn grid_any_degree(
    bu: &Basis,
    bv: &Basis,
    nv: usize,
    pw: &[DVec4],
    us: &[f64],
    vs: &[f64],
    normals: bool,
) -> (Vec<DVec3>, Vec<DVec3>) {
    let (p, q) = (bu.degree(), bv.degree());
    // The v-basis of every column, once.
    let mut v_span = Vec::with_capacity(vs.len());
    let mut v_n = Vec::with_capacity(vs.len());
    let mut v_d = Vec::with_capacity(vs.len());
    let mut s = bv.first_span();
    for &v in vs {
        s = bv.span(v, s);
        let (mut n, mut d) = ([0.0; MAX_FAST_DEGREE + 1], [0.0; MAX_FAST_DEGREE + 1]);
        if normals {
            bv.functions_and_derivatives(s, v, &mut n, &mut d);
        } else {
            bv.functions(s, v, &mut n);
        }
        v_span.push(s);
        v_n.push(n);
        v_d.push(d);
    }
    let mut points = Vec::with_capacity(us.len() * vs.len());
    let mut norms = Vec::with_capacity(if normals { us.len() * vs.len() } else { 0 });
    let mut row0 = vec![DVec4::ZERO; nv];
    let mut row1 = vec![DVec4::ZERO; nv];
    let (mut n, mut d) = ([0.0; MAX_FAST_DEGREE + 1], [0.0; MAX_FAST_DEGREE + 1]);
    let mut su = bu.first_span();
    for &u in us {
        su = bu.span(u, su);
        if normals {
            bu.functions_and_derivatives(su, u, &mut n, &mut d);
        } else {
            bu.functions(su, u, &mut n);
        }
        // Combine the p + 1 rows of control points under this u once.
        for j in 0..nv {
            let (mut a, mut b) = (DVec4::ZERO, DVec4::ZERO);
            for r in 0..=p {
                let c = pw[(su - p + r) * nv + j];
                a += n[r] * c;
                if normals {
                    b += d[r] * c;
                }
            }
            row0[j] = a;
            row1[j] = b;
        }
        for (k, &sv) in v_span.iter().enumerate() {
            let (nvk, dvk) = (&v_n[k], &v_d[k]);
            let base = sv - q;
            let mut h = DVec4::ZERO;
            for r in 0..=q {
                h += nvk[r] * row0[base + r];
            }
            let s = h.truncate() / h.w;
            points.push(s);
            if normals {
                let (mut hu, mut hv) = (DVec4::ZERO, DVec4::ZERO);
                for r in 0..=q {
                    hu += nvk[r] * row1[base + r];
                    hv += dvk[r] * row0[base + r];
                }
                let su_ = (hu.truncate() - hu.w * s) / h.w;
                let sv_ = (hv.truncate() - hv.w * s) / h.w;
                norms.push(su_.cross(sv_).normalize_or_zero());
            }
        }
    }
    (points, norms)
}
