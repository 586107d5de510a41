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
pub fn evaluate_grid(
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
