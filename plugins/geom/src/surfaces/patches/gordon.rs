//! Gordon surfaces: a surface through a network of curves (W. J. Gordon,
//! *Blending-function methods of bivariate and multivariate interpolation
//! and approximation*, 1971; Piegl & Tiller, *The NURBS Book*, §10.5). The
//! u-curves `C_k(u)` lie at `v = v_k`, the v-curves `D_l(v)` at `u = u_l`,
//! and they cross at `Q_kl = C_k(u_l) = D_l(v_k)`. The surface is the
//! Boolean sum
//!
//! ```text
//! S = S_v + S_u − T
//! ```
//!
//! of the skin through the u-curves (interpolating them in v), the skin
//! through the v-curves (interpolating in u) and the tensor-product spline
//! interpolating the crossings. The three use the same interpolation in
//! each direction, so at `v = v_k` the last two cancel and `S = C_k`, and
//! at `u = u_l` the first and last cancel and `S = D_l`.

use glam::DVec4;

use super::{Net, PatchError, averaged_knots, basis_row, compatible, homogeneous, interpolate};
use super::{reversed, unit_domain};
use crate::curves::analysis::closest_parameter;
use crate::curves::{Curve, NurbsCurve};
use crate::surfaces::{NurbsSurface, Surface};

/// Where the curves of a network cross, on the curves' domains taken as
/// [0, 1] ([`unit_domain`](super::unit_domain)).
#[derive(Clone, Debug, PartialEq)]
pub struct NetworkParams {
    /// `u[l]`: the parameter on every u-curve where v-curve `l` crosses it,
    /// strictly increasing.
    pub u: Vec<f64>,
    /// `v[k]`: the parameter on every v-curve where u-curve `k` crosses it,
    /// strictly increasing.
    pub v: Vec<f64>,
}

/// A Gordon surface with the network as it was used.
#[derive(Clone, Debug, PartialEq)]
pub struct Gordon {
    /// The surface: `S(u, v_k) = u_curves[k](u)`, `S(u_l, v) = v_curves[l](v)`.
    pub surface: NurbsSurface,
    /// The crossing parameters, in the surface's order.
    pub params: NetworkParams,
    /// The u-curves on [0, 1] in the surface's order (reversed where the
    /// network needed it).
    pub u_curves: Vec<NurbsCurve>,
    /// The v-curves likewise.
    pub v_curves: Vec<NurbsCurve>,
    /// `u_order[k]`: the index (as given) of the surface's u-curve `k`.
    pub u_order: Vec<usize>,
    /// `v_order[l]`: the index (as given) of the surface's v-curve `l`.
    pub v_order: Vec<usize>,
    /// Per given u-curve, whether it runs backwards on the surface.
    pub u_reversed: Vec<bool>,
    /// Per given v-curve, whether it runs backwards on the surface.
    pub v_reversed: Vec<bool>,
}

/// The Gordon surface through a network of `u_curves` (each at a constant
/// v) and `v_curves` (each at a constant u), as a NURBS surface.
///
/// With `params`, the curves are used in the order and direction given and
/// cross at those parameters. Without, the crossings are found (the
/// closest points of every pair, by sampling and Newton's method on the
/// squared distance), the v-curves are ordered along the first u-curve and
/// the u-curves along the first v-curve, curves running the other way are
/// reversed, and each curve's crossing parameter is the mean over the
/// curves it crosses.
///
/// Construction (The NURBS Book §10.5): the u-curves are made compatible
/// and interpolated in v at `v_k` (degree `min(3, count − 1)`, knots
/// averaged from the parameters, eq. 9.8), the v-curves likewise in u at
/// `u_l`, the crossings by the tensor product of the same two
/// interpolations; the three are brought to common degrees and knots and
/// summed `S_v + S_u − T` in homogeneous coordinates. The inverse is
/// reading the network back (`S(u, v_k)`, `S(u_l, v)`).
///
/// # Errors
/// [`PatchError::TooFewCurves`] (fewer than 2 in a direction);
/// [`PatchError::ParameterCount`], [`PatchError::ParametersOutOfOrder`]
/// for bad given parameters; [`PatchError::CurvesDoNotMeet`] when a pair
/// passes more than `tolerance` apart, [`PatchError::CrossingOrder`] when
/// the curves cross in different orders on different curves;
/// [`PatchError::NetworkGap`] naming the first crossing where the curves
/// are more than `tolerance` apart at the common parameters (an
/// inconsistent network); [`PatchError::WeightsDisagree`] for rational
/// curves whose weights differ at a crossing; [`PatchError::Curve`] for a
/// singular interpolation.
///
/// Complexity: O(K·L·s²) to find the crossings (s = 64 samples) plus
/// O((K + L)³ + n_u·n_v·(K + L)) for the interpolations and the sum.
pub fn gordon(
    u_curves: &[NurbsCurve],
    v_curves: &[NurbsCurve],
    params: Option<&NetworkParams>,
    tolerance: f64,
) -> Result<Gordon, PatchError> {
    if u_curves.len() < 2 {
        return Err(PatchError::TooFewCurves {
            direction: "u",
            got: u_curves.len(),
        });
    }
    if v_curves.len() < 2 {
        return Err(PatchError::TooFewCurves {
            direction: "v",
            got: v_curves.len(),
        });
    }
    let cs: Vec<NurbsCurve> = u_curves.iter().map(unit_domain).collect::<Result<_, _>>()?;
    let ds: Vec<NurbsCurve> = v_curves.iter().map(unit_domain).collect::<Result<_, _>>()?;
    let (k_count, l_count) = (cs.len(), ds.len());
    let arranged = match params {
        Some(p) => {
            if p.u.len() != l_count {
                return Err(PatchError::ParameterCount {
                    direction: "u",
                    curves: l_count,
                    got: p.u.len(),
                });
            }
            if p.v.len() != k_count {
                return Err(PatchError::ParameterCount {
                    direction: "v",
                    curves: k_count,
                    got: p.v.len(),
                });
            }
            Arranged {
                params: p.clone(),
                u_order: (0..k_count).collect(),
                v_order: (0..l_count).collect(),
                u_reversed: vec![false; k_count],
                v_reversed: vec![false; l_count],
            }
        }
        None => find_crossings(&cs, &ds, tolerance)?,
    };
    for (direction, list) in [("u", &arranged.params.u), ("v", &arranged.params.v)] {
        for (index, &value) in list.iter().enumerate() {
            let below = index > 0 && value <= list[index - 1];
            if below || !(0.0..=1.0).contains(&value) {
                return Err(PatchError::ParametersOutOfOrder {
                    direction,
                    index,
                    value,
                });
            }
        }
    }
    let orient = |c: &NurbsCurve, rev: bool| if rev { reversed(c) } else { c.clone() };
    let cs: Vec<NurbsCurve> = arranged
        .u_order
        .iter()
        .map(|&k| orient(&cs[k], arranged.u_reversed[k]))
        .collect();
    let ds: Vec<NurbsCurve> = arranged
        .v_order
        .iter()
        .map(|&l| orient(&ds[l], arranged.v_reversed[l]))
        .collect();
    let NetworkParams { u: us, v: vs } = &arranged.params;
    // The crossings, checked: Q_kl in homogeneous coordinates.
    let mut q = vec![vec![DVec4::ZERO; l_count]; k_count];
    for (k, c) in cs.iter().enumerate() {
        for (l, d) in ds.iter().enumerate() {
            let (a, b) = (c.point(us[l]), d.point(vs[k]));
            let gap = a.distance(b);
            if gap > tolerance || gap.is_nan() {
                return Err(PatchError::NetworkGap {
                    u_curve: k,
                    v_curve: l,
                    u: us[l],
                    v: vs[k],
                    gap,
                    tolerance,
                });
            }
            let (wa, wb) = (weight_at(c, us[l]), weight_at(d, vs[k]));
            if (wa - wb).abs() > 1e-9 * wa.max(wb) {
                return Err(PatchError::WeightsDisagree {
                    u_curve: k,
                    v_curve: l,
                    first: wa,
                    second: wb,
                });
            }
            let w = 0.5 * (wa + wb);
            q[k][l] = (0.5 * (a + b) * w).extend(w);
        }
    }
    let cc = compatible(&cs)?;
    let dc = compatible(&ds)?;
    let (pu, pv) = ((l_count - 1).min(3), (k_count - 1).min(3));
    let (ku, kv) = (averaged_knots(us, pu), averaged_knots(vs, pv));
    // S_v: the u-curves interpolated in v; control points (i, k').
    let rows = cc.iter().map(homogeneous).collect();
    let skin = interpolate(vs, pv, &kv, rows)?;
    let n_c = cc[0].points().len();
    let mut pw = vec![DVec4::ZERO; n_c * k_count];
    for (kk, row) in skin.iter().enumerate() {
        for (i, &h) in row.iter().enumerate() {
            pw[i * k_count + kk] = h;
        }
    }
    let s_v = Net::new(
        (cc[0].degree(), cc[0].knots().to_vec()),
        (pv, kv.clone()),
        n_c,
        k_count,
        pw,
    );
    // S_u: the v-curves interpolated in u; control points (l', j).
    let rows = dc.iter().map(homogeneous).collect();
    let skin = interpolate(us, pu, &ku, rows)?;
    let n_d = dc[0].points().len();
    let s_u = Net::new(
        (pu, ku.clone()),
        (dc[0].degree(), dc[0].knots().to_vec()),
        l_count,
        n_d,
        skin.into_iter().flatten().collect(),
    );
    // T: the crossings interpolated in u (rows over l), then in v.
    let by_l: Vec<Vec<DVec4>> = (0..l_count)
        .map(|l| (0..k_count).map(|k| q[k][l]).collect())
        .collect();
    let in_u = interpolate(us, pu, &ku, by_l)?; // in_u[l'][k]
    let by_k: Vec<Vec<DVec4>> = (0..k_count)
        .map(|k| (0..l_count).map(|l| in_u[l][k]).collect())
        .collect();
    let in_v = interpolate(vs, pv, &kv, by_k)?; // in_v[k'][l']
    let mut pw = vec![DVec4::ZERO; l_count * k_count];
    for (kk, row) in in_v.iter().enumerate() {
        for (ll, &h) in row.iter().enumerate() {
            pw[ll * k_count + kk] = h;
        }
    }
    let t = Net::new((pu, ku), (pv, kv), l_count, k_count, pw);
    let surface = Net::sum(&[(1.0, &s_v), (1.0, &s_u), (-1.0, &t)])?.into_surface()?;
    Ok(Gordon {
        surface,
        params: arranged.params,
        u_curves: cs,
        v_curves: ds,
        u_order: arranged.u_order,
        v_order: arranged.v_order,
        u_reversed: arranged.u_reversed,
        v_reversed: arranged.v_reversed,
    })
}

/// The weight function `Σ N_i(t) w_i` of a curve at `t`.
fn weight_at(c: &NurbsCurve, t: f64) -> f64 {
    basis_row(c.knots(), c.degree(), c.points().len(), t)
        .iter()
        .zip(c.weights())
        .map(|(n, w)| n * w)
        .sum()
}

/// The order, directions and parameters of a network whose crossings were
/// found.
struct Arranged {
    params: NetworkParams,
    u_order: Vec<usize>,
    v_order: Vec<usize>,
    u_reversed: Vec<bool>,
    v_reversed: Vec<bool>,
}

/// The parameters `(s, t)` where `a(s)` and `b(t)` come closest, and the
/// distance: the best of 64 × 64 samples, refined by Newton's method on
/// `|a(s) − b(t)|²`.
fn closest_pair(a: &NurbsCurve, b: &NurbsCurve) -> (f64, f64, f64) {
    const N: usize = 64;
    let params: Vec<f64> = (0..=N).map(|i| i as f64 / N as f64).collect();
    let (pa, pb) = (a.points_at(&params), b.points_at(&params));
    let mut best = (0, 0, f64::INFINITY);
    for (i, x) in pa.iter().enumerate() {
        for (j, y) in pb.iter().enumerate() {
            let d = x.distance_squared(*y);
            if d < best.2 {
                best = (i, j, d);
            }
        }
    }
    let (mut s, mut t) = (params[best.0], params[best.1]);
    for _ in 0..40 {
        let [p, p1, p2] = a.derivatives(s);
        let [q, q1, q2] = b.derivatives(t);
        let r = p - q;
        let g = [r.dot(p1), -r.dot(q1)];
        let h = [
            [p1.dot(p1) + r.dot(p2), -p1.dot(q1)],
            [-p1.dot(q1), q1.dot(q1) - r.dot(q2)],
        ];
        let det = h[0][0] * h[1][1] - h[0][1] * h[1][0];
        if det.abs() < 1e-300 {
            break;
        }
        let ds = (g[0] * h[1][1] - g[1] * h[0][1]) / det;
        let dt = (h[0][0] * g[1] - h[1][0] * g[0]) / det;
        let (ns, nt) = ((s - ds).clamp(0.0, 1.0), (t - dt).clamp(0.0, 1.0));
        let done = (ns - s).abs() < 1e-16 && (nt - t).abs() < 1e-16;
        (s, t) = (ns, nt);
        if done {
            break;
        }
    }
    // Newton may have left for a worse point; keep the better, and refine
    // an end against the other curve (a crossing at a curve's end).
    let d_newton = a.point(s).distance(b.point(t));
    let (bs, bt) = (params[best.0], params[best.1]);
    let mut out = if d_newton <= best.2.sqrt() {
        (s, t, d_newton)
    } else {
        (bs, bt, best.2.sqrt())
    };
    for s_end in [0.0, 1.0] {
        let t_end = closest_parameter(b, a.point(s_end));
        let d = a.point(s_end).distance(b.point(t_end));
        if d < out.2 {
            out = (s_end, t_end, d);
        }
    }
    for t_end in [0.0, 1.0] {
        let s_end = closest_parameter(a, b.point(t_end));
        let d = a.point(s_end).distance(b.point(t_end));
        if d < out.2 {
            out = (s_end, t_end, d);
        }
    }
    out
}

/// Whether the values strictly increase (`Some(false)`), strictly decrease
/// (`Some(true)`) or neither (`None`).
fn monotone(values: &[f64]) -> Option<bool> {
    if values.windows(2).all(|w| w[0] < w[1]) {
        Some(false)
    } else if values.windows(2).all(|w| w[0] > w[1]) {
        Some(true)
    } else {
        None
    }
}

fn find_crossings(
    cs: &[NurbsCurve],
    ds: &[NurbsCurve],
    tolerance: f64,
) -> Result<Arranged, PatchError> {
    let (k_count, l_count) = (cs.len(), ds.len());
    // s[k][l] on u-curve k, t[k][l] on v-curve l.
    let mut s = vec![vec![0.0; l_count]; k_count];
    let mut t = vec![vec![0.0; l_count]; k_count];
    for (k, c) in cs.iter().enumerate() {
        for (l, d) in ds.iter().enumerate() {
            let (a, b, distance) = closest_pair(c, d);
            if distance > tolerance {
                return Err(PatchError::CurvesDoNotMeet {
                    u_curve: k,
                    v_curve: l,
                    distance,
                });
            }
            (s[k][l], t[k][l]) = (a, b);
        }
    }
    // The v-curves in their order along the first u-curve.
    let mut v_order: Vec<usize> = (0..l_count).collect();
    v_order.sort_by(|&a, &b| s[0][a].total_cmp(&s[0][b]));
    let mut u_reversed = vec![false; k_count];
    for k in 0..k_count {
        let along: Vec<f64> = v_order.iter().map(|&l| s[k][l]).collect();
        match monotone(&along) {
            Some(rev) => u_reversed[k] = rev,
            None => {
                return Err(PatchError::CrossingOrder {
                    direction: "v",
                    across: "u",
                    curve: k,
                });
            }
        }
        if u_reversed[k] {
            s[k].iter_mut().for_each(|x| *x = 1.0 - *x);
        }
    }
    // The u-curves in their order along the first v-curve (in order).
    let first = v_order[0];
    let mut u_order: Vec<usize> = (0..k_count).collect();
    u_order.sort_by(|&a, &b| t[a][first].total_cmp(&t[b][first]));
    let mut v_reversed = vec![false; l_count];
    for l in 0..l_count {
        let along: Vec<f64> = u_order.iter().map(|&k| t[k][l]).collect();
        match monotone(&along) {
            Some(rev) => v_reversed[l] = rev,
            None => {
                return Err(PatchError::CrossingOrder {
                    direction: "u",
                    across: "v",
                    curve: l,
                });
            }
        }
        if v_reversed[l] {
            t.iter_mut().for_each(|row| row[l] = 1.0 - row[l]);
        }
    }
    let u = v_order
        .iter()
        .map(|&l| u_order.iter().map(|&k| s[k][l]).sum::<f64>() / k_count as f64)
        .collect();
    let v = u_order
        .iter()
        .map(|&k| v_order.iter().map(|&l| t[k][l]).sum::<f64>() / l_count as f64)
        .collect();
    Ok(Arranged {
        params: NetworkParams { u, v },
        u_order,
        v_order,
        u_reversed,
        v_reversed,
    })
}

/// What the app shows for a Gordon surface: how closely it follows the
/// network (zero up to rounding), where the curves cross, its size.
#[derive(Clone, Debug, PartialEq)]
pub struct GordonReport {
    /// Largest distance between the surface and a network curve at
    /// `samples + 1` parameters per curve.
    pub max_curve_gap: f64,
    /// Largest distance between a u-curve and a v-curve at a crossing.
    pub max_crossing_gap: f64,
    /// The crossing parameters (the curves' iso-lines on the surface).
    pub params: NetworkParams,
    /// Degrees `(u, v)` of the surface.
    pub degrees: (usize, usize),
    /// Control points `(nu, nv)` of the surface.
    pub size: (usize, usize),
}

/// Measures a [`Gordon`] surface against its network. O(samples · (K + L)).
pub fn gordon_report(g: &Gordon, samples: usize) -> GordonReport {
    let n = samples.max(1);
    let mut curve_gap: f64 = 0.0;
    for k in 0..=n {
        let x = k as f64 / n as f64;
        for (c, &v) in g.u_curves.iter().zip(&g.params.v) {
            curve_gap = curve_gap.max(g.surface.evaluate(x, v).p.distance(c.point(x)));
        }
        for (d, &u) in g.v_curves.iter().zip(&g.params.u) {
            curve_gap = curve_gap.max(g.surface.evaluate(u, x).p.distance(d.point(x)));
        }
    }
    let mut crossing_gap: f64 = 0.0;
    for (c, &v) in g.u_curves.iter().zip(&g.params.v) {
        for (d, &u) in g.v_curves.iter().zip(&g.params.u) {
            crossing_gap = crossing_gap.max(c.point(u).distance(d.point(v)));
        }
    }
    GordonReport {
        max_curve_gap: curve_gap,
        max_crossing_gap: crossing_gap,
        params: g.params.clone(),
        degrees: g.surface.degrees(),
        size: g.surface.size(),
    }
}
