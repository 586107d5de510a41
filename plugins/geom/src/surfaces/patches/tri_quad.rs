//! The exercise of seed 002 ("Önálló feladat"): a three-sided and a
//! four-sided Bézier patch, neighbours joined with G1 continuity (a common
//! tangent plane), whose control points the user drags while the join
//! holds ("kontrollpontok interaktív módosítása (függőség)").
//!
//! The triangle (degree n) and the tensor-product patch share an edge. C0:
//! the patch's boundary row becomes the triangle's edge, after degree
//! elevation of whichever is lower along it. G1 (seed 002, "G1
//! folytonosság szomszédos felületekre", condition b: `α(u) s_u + β(u) s_v
//! = γ(u) p_w`): along the edge, with `t` its parameter,
//!
//! ```text
//! T(t) = n Σ (e_{j+1} − e_j) B^{n−1}_j(t)        the edge's tangent
//! D(t) = n Σ (f_j − e_j) B^{n−1}_j(t)            the triangle's derivative across it
//! Q(t) = m Σ (c_i1 − c_i0) B^n_i(t)              the patch's derivative across it
//! ```
//!
//! (`e` the edge's control points, `f` the triangle's row next to it, `c_i0`
//! the patch's boundary row, `c_i1` its next row, m the patch's degree
//! across). The patch's next row is set so that
//!
//! ```text
//! Q(t) = −λ D(t) + (μ0 (1 − t) + μ1 t) T(t),   λ > 0
//! ```
//!
//! which has degree n like Q: the patch's cross derivative lies in the
//! triangle's tangent plane at every t, on the other side, so the normals
//! agree all along. With μ = 0 it is the seed's condition (a), `(c_i1 −
//! c_i0) = α (d_i1 − d_i0)`; the linear μ lets the row lean along the edge.
//! λ, μ0, μ1 are fitted by least squares to the row as it was, so *Make G1*
//! moves it as little as this family allows.
//!
//! While the user edits, the patch's boundary row is *shared* with the
//! triangle's edge (moving either moves both) and its next row is
//! *dependent*: re-solved from the triangle with the same λ, μ after any
//! move, or re-fitted when the user drags one of its points.

use glam::DVec3;

use super::PatchError;
use crate::curves::Bezier;
use crate::surfaces::joins::{Boundary, surface_boundary, triangle_boundary};
use crate::surfaces::{BezierSurface, BezierTriangle};

/// Which edge of the triangle lies on which side of the patch.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct SharedEdge {
    /// The triangle's edge: [`Boundary::TriangleU0`], `TriangleV0` or
    /// `TriangleW0` (parameterised as in [`triangle_boundary`]).
    pub triangle: Boundary,
    /// The patch's side: [`Boundary::U0`], `U1`, `V0` or `V1`.
    pub quad: Boundary,
    /// The side runs the other way: the patch's parameter along it is
    /// `1 − t` at the triangle edge's `t`.
    pub reversed: bool,
}

/// A control point of the pair: an index into [`BezierTriangle::points`]
/// or into [`BezierSurface::points`] (`i * nv + j`).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PatchPoint {
    /// Control point of the triangle.
    Triangle(usize),
    /// Control point of the quadrilateral patch.
    Quad(usize),
}

/// What a control point is to the join (the app draws each in its colour).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum PointRole {
    /// Moves alone; the join does not depend on it (or only the dependent
    /// points follow it, for the triangle's row next to the edge).
    Free,
    /// On the shared edge: the triangle's edge point and the patch's
    /// boundary point at the same place; moving one moves the other.
    Shared,
    /// The patch's row next to the edge: re-solved to keep G1 after every
    /// move; dragged, it goes to the nearest place that keeps G1.
    Dependent,
}

/// A Bézier triangle and a tensor-product Bézier patch with the edge they
/// share.
#[derive(Clone, Debug, PartialEq)]
pub struct TriangleQuad {
    /// The three-sided patch.
    pub triangle: BezierTriangle,
    /// The four-sided patch.
    pub quad: BezierSurface,
    /// Where they meet.
    pub edge: SharedEdge,
}

/// What the app shows for the join: the largest angle between the two
/// normals and the largest gap along the joint.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct JointReport {
    /// Largest angle in radians between the patches' normals (either
    /// orientation), `atan2(|a × b|, |a · b|)`; π/2 where a normal is
    /// undefined.
    pub max_normal_angle: f64,
    /// Largest distance between the two boundaries.
    pub max_gap: f64,
    /// Points sampled along the joint.
    pub samples: usize,
}

/// The triangle's edge points `e_0..=e_n` (in t order) and the row next to
/// it `f_0..n−1`, as storage indices.
fn triangle_rows(b: Boundary, n: usize) -> Result<(Vec<usize>, Vec<usize>), PatchError> {
    let idx = BezierTriangle::index;
    let (e, f): (Vec<usize>, Vec<usize>) = match b {
        Boundary::TriangleU0 => (
            (0..=n).map(|j| idx(n, 0, j)).collect(),
            (0..n).map(|j| idx(n, 1, j)).collect(),
        ),
        Boundary::TriangleV0 => (
            (0..=n).map(|j| idx(n, j, 0)).collect(),
            (0..n).map(|j| idx(n, j, 1)).collect(),
        ),
        Boundary::TriangleW0 => (
            (0..=n).map(|j| idx(n, j, n - j)).collect(),
            (0..n).map(|j| idx(n, j, n - 1 - j)).collect(),
        ),
        other => {
            return Err(PatchError::NotAnEdge {
                boundary: other,
                patch: "triangle",
            });
        }
    };
    Ok((e, f))
}

/// The patch's boundary row and the row next to it along a side (in the
/// side's own parameter order), as storage indices, and the degree across.
fn quad_rows(
    b: Boundary,
    nu: usize,
    nv: usize,
) -> Result<(Vec<usize>, Vec<usize>, usize), PatchError> {
    let at = |i: usize, j: usize| i * nv + j;
    Ok(match b {
        Boundary::U0 => (
            (0..nv).map(|j| at(0, j)).collect(),
            (0..nv).map(|j| at(1, j)).collect(),
            nu - 1,
        ),
        Boundary::U1 => (
            (0..nv).map(|j| at(nu - 1, j)).collect(),
            (0..nv).map(|j| at(nu - 2, j)).collect(),
            nu - 1,
        ),
        Boundary::V0 => (
            (0..nu).map(|i| at(i, 0)).collect(),
            (0..nu).map(|i| at(i, 1)).collect(),
            nv - 1,
        ),
        Boundary::V1 => (
            (0..nu).map(|i| at(i, nv - 1)).collect(),
            (0..nu).map(|i| at(i, nv - 2)).collect(),
            nv - 1,
        ),
        other => {
            return Err(PatchError::NotAnEdge {
                boundary: other,
                patch: "patch",
            });
        }
    })
}

/// The quad's boundary and next rows in the triangle edge's t order.
fn quad_rows_t(
    edge: &SharedEdge,
    quad: &BezierSurface,
) -> Result<(Vec<usize>, Vec<usize>, usize), PatchError> {
    let (mut b, mut i, m) = quad_rows(edge.quad, quad.nu, quad.nv)?;
    if edge.reversed {
        b.reverse();
        i.reverse();
    }
    Ok((b, i, m))
}

/// The largest distance between the ends of the triangle's edge and the
/// patch's side paired as `edge` says.
fn end_gap(
    tri: &BezierTriangle,
    quad: &BezierSurface,
    edge: &SharedEdge,
) -> Result<f64, PatchError> {
    let (e, _) = triangle_rows(edge.triangle, tri.degree)?;
    let (b, _, _) = quad_rows_t(edge, quad)?;
    let (te0, te1) = (tri.points[e[0]], tri.points[e[e.len() - 1]]);
    let (q0, q1) = (quad.points[b[0]], quad.points[b[b.len() - 1]]);
    Ok(te0.distance(q0).max(te1.distance(q1)))
}

/// The Bézier patch with one more control point along the side `side`
/// (every row along it degree-elevated; the surface does not move).
fn elevate_along(quad: &BezierSurface, side: Boundary) -> BezierSurface {
    let (nu, nv) = (quad.nu, quad.nv);
    if matches!(side, Boundary::U0 | Boundary::U1) {
        // The side runs in v: elevate every row i.
        let mut points = Vec::with_capacity(nu * (nv + 1));
        for i in 0..nu {
            let row = Bezier {
                points: quad.points[i * nv..(i + 1) * nv].to_vec(),
            };
            points.extend(row.elevate().points);
        }
        BezierSurface {
            nu,
            nv: nv + 1,
            points,
        }
    } else {
        let columns: Vec<Vec<DVec3>> = (0..nv)
            .map(|j| {
                Bezier {
                    points: (0..nu).map(|i| quad.points[i * nv + j]).collect(),
                }
                .elevate()
                .points
            })
            .collect();
        let mut points = Vec::with_capacity((nu + 1) * nv);
        for i in 0..=nu {
            for column in &columns {
                points.push(column[i]);
            }
        }
        BezierSurface {
            nu: nu + 1,
            nv,
            points,
        }
    }
}

/// λ, μ0, μ1 of the G1 family (see the module's documentation).
#[derive(Copy, Clone, Debug, PartialEq)]
struct Lean {
    lambda: f64,
    mu0: f64,
    mu1: f64,
}

/// The vectors of the G1 family along an edge of degree n: per Bernstein
/// coefficient i of degree n, `−D^(n)_i` (the triangle's cross derivative
/// elevated), `a_i` and `b_i` (`(1 − t) T` and `t T` elevated), so that
/// `Q_i = λ·minus_d_i + μ0·a_i + μ1·b_i`.
struct Family {
    minus_d: Vec<DVec3>,
    a: Vec<DVec3>,
    b: Vec<DVec3>,
}

impl Family {
    fn new(e: &[DVec3], f: &[DVec3]) -> Result<Family, PatchError> {
        let n = e.len() - 1;
        let nf = n as f64;
        let d: Vec<DVec3> = (0..n).map(|j| nf * (f[j] - e[j])).collect();
        let t: Vec<DVec3> = (0..n).map(|j| nf * (e[j + 1] - e[j])).collect();
        let at = |v: &[DVec3], j: isize| {
            if j < 0 || j as usize >= n {
                DVec3::ZERO
            } else {
                v[j as usize]
            }
        };
        let mut family = Family {
            minus_d: Vec::with_capacity(n + 1),
            a: Vec::with_capacity(n + 1),
            b: Vec::with_capacity(n + 1),
        };
        for i in 0..=n {
            let (l, r) = (i as f64 / nf, (n - i) as f64 / nf);
            let ii = i as isize;
            family.minus_d.push(-(l * at(&d, ii - 1) + r * at(&d, ii)));
            family.a.push(r * at(&t, ii));
            family.b.push(l * at(&t, ii - 1));
        }
        // The tangent plane must exist along the edge: D(t) × T(t) ≠ 0.
        let scale: f64 = d.iter().chain(&t).map(|v| v.length()).fold(0.0, f64::max);
        let bez = |v: &[DVec3]| Bezier { points: v.to_vec() };
        let (bd, bt) = (bez(&d), bez(&t));
        for k in 0..=8 {
            let s = k as f64 / 8.0;
            let cross = bd.de_casteljau(s).cross(bt.de_casteljau(s)).length();
            if cross <= 1e-12 * scale * scale || cross.is_nan() {
                return Err(PatchError::DegenerateEdge);
            }
        }
        Ok(family)
    }

    fn q(&self, i: usize, k: &Lean) -> DVec3 {
        k.lambda * self.minus_d[i] + k.mu0 * self.a[i] + k.mu1 * self.b[i]
    }

    /// The least-squares λ, μ0, μ1 for `targets` (coefficient index, wanted
    /// `Q_i`, weight). λ is kept positive (the patch on the other side of
    /// the edge): a fit below 1% of the size ratio of the rows takes that
    /// ratio and fits μ alone.
    fn fit(&self, targets: &[(usize, DVec3, f64)]) -> Lean {
        let g = |i: usize| [self.minus_d[i], self.a[i], self.b[i]];
        let mut m = [[0.0; 3]; 3];
        let mut rhs = [0.0; 3];
        let (mut qq, mut dd) = (0.0, 0.0);
        for &(i, q, w) in targets {
            let gi = g(i);
            for r in 0..3 {
                for c in 0..3 {
                    m[r][c] += w * gi[r].dot(gi[c]);
                }
                rhs[r] += w * gi[r].dot(q);
            }
            qq += w * q.length_squared();
            dd += w * gi[0].length_squared();
        }
        let reference = if qq > 0.0 && dd > 0.0 {
            (qq / dd).sqrt()
        } else {
            1.0
        };
        if let Some([lambda, mu0, mu1]) = solve3(m, rhs)
            && lambda > 0.01 * reference
        {
            return Lean { lambda, mu0, mu1 };
        }
        // μ alone for Q − λ·minus_d with λ fixed.
        let lambda = reference;
        let unit = m[1][1] + m[2][2];
        let m2 = [
            [m[1][1], m[1][2], 0.0],
            [m[2][1], m[2][2], 0.0],
            [0.0, 0.0, unit],
        ];
        let r2 = [rhs[1] - lambda * m[1][0], rhs[2] - lambda * m[2][0], 0.0];
        let [mu0, mu1, _] = solve3(m2, r2).unwrap_or_default();
        Lean { lambda, mu0, mu1 }
    }
}

/// Solves a 3 × 3 system by Gaussian elimination with partial pivoting;
/// `None` when it is singular (a pivot below 1e-13 of the largest entry).
fn solve3(mut m: [[f64; 3]; 3], mut r: [f64; 3]) -> Option<[f64; 3]> {
    let scale = m.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
    for col in 0..3 {
        let p = (col..3)
            .max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))
            .expect("rows");
        if m[p][col].abs() <= 1e-13 * scale || m[p][col].is_nan() {
            return None;
        }
        m.swap(col, p);
        r.swap(col, p);
        for row in col + 1..3 {
            let f = m[row][col] / m[col][col];
            let pivot_row = m[col];
            for (x, y) in m[row][col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * y;
            }
            r[row] -= f * r[col];
        }
    }
    let mut x = [0.0; 3];
    for row in (0..3).rev() {
        let mut s = r[row];
        for k in row + 1..3 {
            s -= m[row][k] * x[k];
        }
        x[row] = s / m[row][row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The rows of a joined pair (equal degrees along the edge), in t order.
struct Rows {
    /// Triangle edge indices `e_0..=e_n`.
    e: Vec<usize>,
    /// Triangle next-row indices `f_0..n−1`.
    f: Vec<usize>,
    /// Patch boundary indices, t order.
    boundary: Vec<usize>,
    /// Patch next-row indices, t order.
    inner: Vec<usize>,
    /// The patch's degree across the edge.
    m: usize,
}

impl TriangleQuad {
    /// The pair with the edge they share found: the triangle edge and patch
    /// side (either direction) whose ends are closest, within `tolerance`.
    ///
    /// # Errors
    /// [`PatchError::NoSharedEdge`] with the nearest pairing's gap.
    ///
    /// Complexity: O(1) (24 pairings of corners).
    pub fn new(
        triangle: BezierTriangle,
        quad: BezierSurface,
        tolerance: f64,
    ) -> Result<TriangleQuad, PatchError> {
        let mut best: Option<(f64, SharedEdge)> = None;
        for t in [
            Boundary::TriangleU0,
            Boundary::TriangleV0,
            Boundary::TriangleW0,
        ] {
            for q in [Boundary::U0, Boundary::U1, Boundary::V0, Boundary::V1] {
                for reversed in [false, true] {
                    let edge = SharedEdge {
                        triangle: t,
                        quad: q,
                        reversed,
                    };
                    let gap = end_gap(&triangle, &quad, &edge)?;
                    if best.is_none_or(|(g, _)| gap < g) {
                        best = Some((gap, edge));
                    }
                }
            }
        }
        let (gap, edge) = best.expect("24 pairings");
        if gap > tolerance || gap.is_nan() {
            return Err(PatchError::NoSharedEdge {
                nearest_gap: gap,
                tolerance,
            });
        }
        Ok(TriangleQuad {
            triangle,
            quad,
            edge,
        })
    }

    /// The pair with a given shared edge, checked.
    ///
    /// # Errors
    /// [`PatchError::NotAnEdge`] for a triangle edge given as the patch's
    /// side or the other way round; [`PatchError::EdgeEndsApart`] when the
    /// edge's ends are more than `tolerance` apart on the two patches.
    pub fn with_edge(
        triangle: BezierTriangle,
        quad: BezierSurface,
        edge: SharedEdge,
        tolerance: f64,
    ) -> Result<TriangleQuad, PatchError> {
        let gap = end_gap(&triangle, &quad, &edge)?;
        if gap > tolerance || gap.is_nan() {
            return Err(PatchError::EdgeEndsApart { gap, tolerance });
        }
        Ok(TriangleQuad {
            triangle,
            quad,
            edge,
        })
    }

    /// The patch's degree along the shared edge.
    pub fn quad_edge_degree(&self) -> usize {
        match self.edge.quad {
            Boundary::U0 | Boundary::U1 => self.quad.nv - 1,
            _ => self.quad.nu - 1,
        }
    }

    fn rows(&self) -> Result<Rows, PatchError> {
        let n = self.triangle.degree;
        if self.quad_edge_degree() != n {
            return Err(PatchError::NotJoined {
                triangle: n,
                quad: self.quad_edge_degree(),
            });
        }
        let (e, f) = triangle_rows(self.edge.triangle, n)?;
        let (boundary, inner, m) = quad_rows_t(&self.edge, &self.quad)?;
        Ok(Rows {
            e,
            f,
            boundary,
            inner,
            m,
        })
    }

    fn family(&self, rows: &Rows) -> Result<Family, PatchError> {
        let pts = |idx: &[usize]| -> Vec<DVec3> {
            idx.iter().map(|&k| self.triangle.points[k]).collect()
        };
        Family::new(&pts(&rows.e), &pts(&rows.f))
    }

    /// The patch's current cross-derivative coefficients `Q_i`.
    fn current_q(&self, rows: &Rows) -> Vec<DVec3> {
        let m = rows.m as f64;
        rows.boundary
            .iter()
            .zip(&rows.inner)
            .map(|(&b, &i)| m * (self.quad.points[i] - self.quad.points[b]))
            .collect()
    }

    /// Sets the patch's next row from the family and `lean`.
    fn apply(&mut self, rows: &Rows, family: &Family, lean: &Lean) {
        let m = rows.m as f64;
        for i in 0..rows.inner.len() {
            let base = self.quad.points[rows.boundary[i]];
            self.quad.points[rows.inner[i]] = base + family.q(i, lean) / m;
        }
    }

    /// C0: the two patches get the same degree along the edge (the lower one
    /// is degree-elevated, [`BezierTriangle::elevate`] or every row of the
    /// patch along the edge, neither moves), then the patch's boundary row
    /// becomes the triangle's edge. The triangle is not changed otherwise.
    /// Applying it twice gives the same pair; its inverse is keeping the
    /// old patch (nothing is stored).
    ///
    /// # Errors
    /// None for a pair made by [`new`](Self::new) or
    /// [`with_edge`](Self::with_edge).
    ///
    /// Complexity: O(elevations · points).
    pub fn make_c0(&self) -> Result<TriangleQuad, PatchError> {
        let mut out = self.clone();
        while out.triangle.degree < out.quad_edge_degree() {
            out.triangle = out.triangle.elevate();
        }
        while out.quad_edge_degree() < out.triangle.degree {
            out.quad = elevate_along(&out.quad, out.edge.quad);
        }
        let rows = out.rows()?;
        for (&b, &e) in rows.boundary.iter().zip(&rows.e) {
            out.quad.points[b] = out.triangle.points[e];
        }
        Ok(out)
    }

    /// G1 (seed 002's exercise): [`make_c0`](Self::make_c0), then the
    /// patch's row next to the edge is set to `c_i1 = c_i0 + Q_i / m` with
    /// `Q = −λ D + (μ0 (1 − t) + μ1 t) T` (module documentation), λ > 0,
    /// μ0, μ1 fitted by least squares to the row as it was. Afterwards the
    /// normals of the two patches agree along the whole joint. Applying it
    /// twice gives the same pair.
    ///
    /// # Errors
    /// [`PatchError::DegenerateEdge`] when the triangle has no tangent plane
    /// somewhere along the edge.
    ///
    /// Complexity: O(n) after the C0 step.
    pub fn make_g1(&self) -> Result<TriangleQuad, PatchError> {
        let mut out = self.make_c0()?;
        let rows = out.rows()?;
        let family = out.family(&rows)?;
        let q = out.current_q(&rows);
        let targets: Vec<(usize, DVec3, f64)> =
            q.iter().enumerate().map(|(i, &q)| (i, q, 1.0)).collect();
        let lean = family.fit(&targets);
        out.apply(&rows, &family, &lean);
        Ok(out)
    }

    /// What `point` is to the join: [`PointRole::Shared`] on the edge,
    /// [`PointRole::Dependent`] in the patch's row next to it,
    /// [`PointRole::Free`] otherwise.
    pub fn role(&self, point: PatchPoint) -> PointRole {
        let (e, _) = triangle_rows(self.edge.triangle, self.triangle.degree).unwrap_or_default();
        let (b, i, _) = quad_rows(self.edge.quad, self.quad.nu, self.quad.nv).unwrap_or_default();
        match point {
            PatchPoint::Triangle(k) if e.contains(&k) => PointRole::Shared,
            PatchPoint::Quad(k) if b.contains(&k) => PointRole::Shared,
            PatchPoint::Quad(k) if i.contains(&k) => PointRole::Dependent,
            _ => PointRole::Free,
        }
    }

    /// Every control point of both patches with its [`role`](Self::role):
    /// the triangle's in storage order, then the patch's.
    pub fn roles(&self) -> Vec<(PatchPoint, PointRole)> {
        let tri = (0..self.triangle.points.len()).map(PatchPoint::Triangle);
        let quad = (0..self.quad.points.len()).map(PatchPoint::Quad);
        tri.chain(quad).map(|p| (p, self.role(p))).collect()
    }

    /// The position of a control point.
    ///
    /// # Errors
    /// [`PatchError::NoSuchPoint`].
    pub fn position(&self, point: PatchPoint) -> Result<DVec3, PatchError> {
        let (patch, points, k) = match point {
            PatchPoint::Triangle(k) => ("triangle", &self.triangle.points, k),
            PatchPoint::Quad(k) => ("patch", &self.quad.points, k),
        };
        points.get(k).copied().ok_or(PatchError::NoSuchPoint {
            patch,
            index: k,
            count: points.len(),
        })
    }

    /// The pair after the user moved `point` to `to`, with the dependent
    /// points re-solved so that the join stays G1, and the list of every
    /// control point whose position changed (the moved one first).
    ///
    /// - a free point of the triangle moves; if it is in the row next to
    ///   the edge, the patch's next row is re-solved with the same λ, μ;
    /// - a shared point moves on both patches, and the patch's next row is
    ///   re-solved with the same λ, μ;
    /// - a dependent point goes to the nearest position that keeps G1: λ, μ
    ///   are re-fitted to put it at `to` (weight 1) while the rest of the row
    ///   stays nearly where it was (weight 1e-3), and the whole row is set
    ///   from them;
    /// - a free point of the patch moves alone.
    ///
    /// λ, μ are read off the pair before the move (least squares, exact when
    /// it is G1), so a pair that is not G1 yet becomes G1 at the first move.
    /// The inverse is moving the point back (λ, μ are unchanged by the first
    /// two kinds of move).
    ///
    /// # Errors
    /// [`PatchError::NoSuchPoint`], [`PatchError::NotFinite`];
    /// [`PatchError::NotJoined`] before [`make_c0`](Self::make_c0);
    /// [`PatchError::DegenerateEdge`] when the move leaves the triangle
    /// without a tangent plane along the edge (the pair is not changed).
    ///
    /// Complexity: O(n).
    pub fn move_point(
        &self,
        point: PatchPoint,
        to: DVec3,
    ) -> Result<(TriangleQuad, Vec<PatchPoint>), PatchError> {
        self.position(point)?;
        if !to.is_finite() {
            return Err(PatchError::NotFinite);
        }
        let rows = self.rows()?;
        let family = self.family(&rows)?;
        let q = self.current_q(&rows);
        let uniform: Vec<(usize, DVec3, f64)> =
            q.iter().enumerate().map(|(i, &q)| (i, q, 1.0)).collect();
        let lean = family.fit(&uniform);
        let mut out = self.clone();
        let original = point;
        // A shared point of the patch is moved as the triangle's.
        let point = match point {
            PatchPoint::Quad(k) => match rows.boundary.iter().position(|&b| b == k) {
                Some(j) => PatchPoint::Triangle(rows.e[j]),
                None => point,
            },
            p => p,
        };
        match point {
            PatchPoint::Triangle(k) => {
                out.triangle.points[k] = to;
                let on_edge = rows.e.iter().position(|&e| e == k);
                if let Some(j) = on_edge {
                    out.quad.points[rows.boundary[j]] = to;
                }
                if on_edge.is_some() || rows.f.contains(&k) {
                    let family = out.family(&rows)?;
                    out.apply(&rows, &family, &lean);
                }
            }
            PatchPoint::Quad(k) => match rows.inner.iter().position(|&i| i == k) {
                Some(i) => {
                    let target = rows.m as f64 * (to - self.quad.points[rows.boundary[i]]);
                    let mut targets: Vec<(usize, DVec3, f64)> =
                        q.iter().enumerate().map(|(i, &q)| (i, q, 1e-3)).collect();
                    targets.push((i, target, 1.0));
                    let lean = family.fit(&targets);
                    out.apply(&rows, &family, &lean);
                }
                None => out.quad.points[k] = to,
            },
        }
        let mut changed = vec![original];
        let tri = self.triangle.points.iter().zip(&out.triangle.points);
        let tri = tri.enumerate().map(|(k, ab)| (PatchPoint::Triangle(k), ab));
        let quad = self.quad.points.iter().zip(&out.quad.points);
        let quad = quad.enumerate().map(|(k, ab)| (PatchPoint::Quad(k), ab));
        for (p, (a, b)) in tri.chain(quad) {
            if a != b && p != original {
                changed.push(p);
            }
        }
        Ok((out, changed))
    }

    /// Samples the joint at `samples + 1` points: the largest angle between
    /// the two patches' normals and the largest gap (what the app shows; 0
    /// and 0 up to rounding after [`make_g1`](Self::make_g1)).
    /// O(samples · n²).
    pub fn report(&self, samples: usize) -> JointReport {
        let n = samples.max(1);
        let mut angle: f64 = 0.0;
        let mut gap: f64 = 0.0;
        for k in 0..=n {
            let t = k as f64 / n as f64;
            let (pt, nt) = triangle_boundary(&self.triangle, self.edge.triangle, false, t);
            let (pq, nq) = surface_boundary(&self.quad, self.edge.quad, self.edge.reversed, t);
            gap = gap.max(pt.distance(pq));
            let a = if nt == DVec3::ZERO || nq == DVec3::ZERO {
                std::f64::consts::FRAC_PI_2
            } else {
                nt.cross(nq).length().atan2(nt.dot(nq).abs())
            };
            angle = angle.max(a);
        }
        JointReport {
            max_normal_angle: angle,
            max_gap: gap,
            samples: n + 1,
        }
    }
}
