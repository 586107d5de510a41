//! The bilinearly blended Coons patch (S. A. Coons, *Surfaces for
//! computer-aided design of space forms*, 1967; Farin, *Curves and
//! Surfaces for CAGD*, ch. 22): from four boundary curves that meet at the
//! corners,
//!
//! ```text
//! S(u, v) = (1 − v) c_v0(u) + v c_v1(u)          ruled between the v = 0 and v = 1 sides
//!         + (1 − u) c_u0(v) + u c_u1(v)          ruled between the u = 0 and u = 1 sides
//!         − B(u, v)                              the bilinear patch of the corners (seed 003)
//! ```
//!
//! Each term is a NURBS surface once the opposite curves are made
//! compatible (degree elevation, knot merging); the sum of the three is
//! exact after bringing them to common degrees and knots. Rational curves
//! are blended in homogeneous coordinates after making every end weight 1
//! ([`unit_end_weights`](super::unit_end_weights)), so the corners agree in
//! four dimensions and each boundary of the result is its curve exactly.

use glam::{DVec3, DVec4};

use super::{Net, PatchError, compatible, homogeneous, reversed, unit_domain, unit_end_weights};
use crate::curves::{Curve, NurbsCurve};
use crate::surfaces::{NurbsSurface, Surface};

/// The four boundaries of a Coons patch, each a curve whose domain is taken
/// as [0, 1] (mapped affinely, see [`unit_domain`](super::unit_domain)):
/// `v0` is `S(u, 0)`, `v1` is `S(u, 1)`, `u0` is `S(0, v)`, `u1` is
/// `S(1, v)`. So `v0` starts where `u0` starts, `v0` ends where `u1`
/// starts, `v1` starts where `u0` ends and ends where `u1` ends.
#[derive(Clone, Debug, PartialEq)]
pub struct CoonsBoundaries {
    /// The side `v = 0`, running in u.
    pub v0: NurbsCurve,
    /// The side `v = 1`, running in u.
    pub v1: NurbsCurve,
    /// The side `u = 0`, running in v.
    pub u0: NurbsCurve,
    /// The side `u = 1`, running in v.
    pub u1: NurbsCurve,
}

/// The corners in the order `(u=0, v=0)`, `(u=1, v=0)`, `(u=0, v=1)`,
/// `(u=1, v=1)`.
const CORNERS: [&str; 4] = ["(u=0, v=0)", "(u=1, v=0)", "(u=0, v=1)", "(u=1, v=1)"];

impl CoonsBoundaries {
    /// Four curves that close a loop, in any order and any direction
    /// (as a user picks them), arranged as boundaries: the first curve
    /// becomes `v0` in its own direction, the curve meeting its end becomes
    /// `u1`, the next `v1` and the last `u0` (reversed where needed).
    ///
    /// # Errors
    /// [`PatchError::NotALoop`] when some curve's end meets no other
    /// unused curve's end within `tolerance`.
    pub fn from_loop(curves: [NurbsCurve; 4], tolerance: f64) -> Result<Self, PatchError> {
        let curves: Vec<NurbsCurve> = curves.iter().map(unit_domain).collect::<Result<_, _>>()?;
        let ends = |c: &NurbsCurve| (c.point(0.0), c.point(1.0));
        let mut chain = vec![curves[0].clone()];
        let mut used = [true, false, false, false];
        for step in 0..3 {
            let end = ends(&chain[step]).1;
            let mut best: Option<(f64, usize, bool)> = None;
            for (k, c) in curves.iter().enumerate() {
                if used[k] {
                    continue;
                }
                let (a, b) = ends(c);
                for (d, rev) in [(end.distance(a), false), (end.distance(b), true)] {
                    if best.is_none_or(|(bd, _, _)| d < bd) {
                        best = Some((d, k, rev));
                    }
                }
            }
            match best {
                Some((d, k, rev)) if d <= tolerance => {
                    used[k] = true;
                    chain.push(if rev {
                        reversed(&curves[k])
                    } else {
                        curves[k].clone()
                    });
                }
                _ => {
                    return Err(PatchError::NotALoop {
                        curve: step,
                        tolerance,
                    });
                }
            }
        }
        if ends(&chain[3]).1.distance(ends(&chain[0]).0) > tolerance {
            return Err(PatchError::NotALoop {
                curve: 3,
                tolerance,
            });
        }
        // chain: v0 (→), u1 (↑), v1 reversed (←), u0 reversed (↓).
        Ok(CoonsBoundaries {
            v0: chain[0].clone(),
            u1: chain[1].clone(),
            v1: reversed(&chain[2]),
            u0: reversed(&chain[3]),
        })
    }

    /// The curves as the patch parameterises them: on [0, 1], clamped, end
    /// weights 1, in the order `[v0, v1, u0, u1]`. The patch satisfies
    /// `S(t, 0) = v0(t)` etc. for these (the same point sets as the given
    /// curves; the parameter differs where a curve's domain is not [0, 1]
    /// or its end weights differ).
    ///
    /// # Errors
    /// None for valid curves.
    pub fn normalized(&self) -> Result<[NurbsCurve; 4], PatchError> {
        let n = |c: &NurbsCurve| -> Result<NurbsCurve, PatchError> {
            Ok(unit_end_weights(&unit_domain(c)?))
        };
        Ok([n(&self.v0)?, n(&self.v1)?, n(&self.u0)?, n(&self.u1)?])
    }

    /// The distances between the curves' ends at the four corners, in the
    /// order `(u=0, v=0)`, `(u=1, v=0)`, `(u=0, v=1)`, `(u=1, v=1)`.
    pub fn corner_gaps(&self) -> [f64; 4] {
        let start = |c: &NurbsCurve| c.point(c.domain().0);
        let end = |c: &NurbsCurve| c.point(c.domain().1);
        [
            start(&self.v0).distance(start(&self.u0)),
            end(&self.v0).distance(start(&self.u1)),
            start(&self.v1).distance(end(&self.u0)),
            end(&self.v1).distance(end(&self.u1)),
        ]
    }
}

/// The bilinearly blended Coons patch of four boundaries, as an exact NURBS
/// surface: `v0`/`v1` are made compatible and give the ruled surface in v,
/// `u0`/`u1` the ruled surface in u, the four corners the bilinear patch;
/// the three are brought to common degrees and knots and summed (ruled +
/// ruled − bilinear) in homogeneous coordinates. Its degrees are the
/// highest of the opposite pairs; its four boundaries are the curves
/// ([`CoonsBoundaries::normalized`]), its corners the curves' ends. A
/// planar boundary gives a planar patch (every term is an affine
/// combination of boundary points). The inverse is reading the boundaries
/// back (`S(t, 0)` etc.).
///
/// Source: Coons 1967 (the Boolean sum of two lofts); the bilinear patch is
/// seed 003's `b(s, t)`; compatibility by degree elevation and knot
/// refinement as The NURBS Book §10.3.
///
/// # Errors
/// [`PatchError::CornerGap`] naming the first corner where two curves are
/// more than `tolerance` apart (with the gap); [`PatchError::NonPositiveWeight`]
/// when rational boundaries with very different weights would need a
/// weight of zero or below.
///
/// Complexity: O((n_u + n_v)² · p) for the elevations and insertions plus
/// O(n_u · n_v) for the sum, where n are the control points of the result.
pub fn coons(boundaries: &CoonsBoundaries, tolerance: f64) -> Result<NurbsSurface, PatchError> {
    let gaps = boundaries.corner_gaps();
    if let Some(k) = (0..4).find(|&k| gaps[k] > tolerance || gaps[k].is_nan()) {
        return Err(PatchError::CornerGap {
            corner: CORNERS[k],
            gap: gaps[k],
            tolerance,
        });
    }
    let [v0, v1, u0, u1] = boundaries.normalized()?;
    let along_u = compatible(&[v0, v1])?;
    let along_v = compatible(&[u0, u1])?;
    let linear = || (1, vec![0.0, 0.0, 1.0, 1.0]);
    // Ruled in v: S(u, v) = (1 − v) v0(u) + v v1(u); points (i, j), j ∈ {0, 1}.
    let (a, b) = (homogeneous(&along_u[0]), homogeneous(&along_u[1]));
    let ruled_v = Net::new(
        (along_u[0].degree(), along_u[0].knots().to_vec()),
        linear(),
        a.len(),
        2,
        a.iter().zip(&b).flat_map(|(&p, &q)| [p, q]).collect(),
    );
    // Ruled in u: S(u, v) = (1 − u) u0(v) + u u1(v); points (i, j), i ∈ {0, 1}.
    let (c, d) = (homogeneous(&along_v[0]), homogeneous(&along_v[1]));
    let ruled_u = Net::new(
        linear(),
        (along_v[0].degree(), along_v[0].knots().to_vec()),
        2,
        c.len(),
        c.iter().chain(&d).copied().collect(),
    );
    // The corners, as the v-curves hold them (they agree with the u-curves
    // within the tolerance; all have weight 1 after normalisation).
    let corners: [DVec4; 4] = [a[0], b[0], a[a.len() - 1], b[b.len() - 1]];
    let bilinear = Net::new(
        linear(),
        linear(),
        2,
        2,
        vec![corners[0], corners[1], corners[2], corners[3]],
    );
    Net::sum(&[(1.0, &ruled_v), (1.0, &ruled_u), (-1.0, &bilinear)])?.into_surface()
}

/// What the app shows for a Coons patch: how far apart the curves are at
/// the corners (why a patch is refused) and how closely the patch follows
/// them (zero up to rounding), with its size.
#[derive(Clone, Debug, PartialEq)]
pub struct CoonsReport {
    /// [`CoonsBoundaries::corner_gaps`].
    pub corner_gaps: [f64; 4],
    /// Largest distance between a boundary of the surface and its curve at
    /// `samples + 1` parameters per side.
    pub max_boundary_gap: f64,
    /// Degrees `(u, v)` of the surface.
    pub degrees: (usize, usize),
    /// Control points `(nu, nv)` of the surface.
    pub size: (usize, usize),
}

/// Measures `surface` (made by [`coons`] from `boundaries`) against its
/// boundaries. O(samples · (p + 1)(q + 1)).
///
/// # Errors
/// None for valid curves.
pub fn coons_report(
    boundaries: &CoonsBoundaries,
    surface: &NurbsSurface,
    samples: usize,
) -> Result<CoonsReport, PatchError> {
    let [v0, v1, u0, u1] = boundaries.normalized()?;
    let n = samples.max(1);
    let mut gap: f64 = 0.0;
    for k in 0..=n {
        let t = k as f64 / n as f64;
        let at = |u: f64, v: f64| surface.evaluate(u, v).p;
        let pairs: [(DVec3, DVec3); 4] = [
            (at(t, 0.0), v0.point(t)),
            (at(t, 1.0), v1.point(t)),
            (at(0.0, t), u0.point(t)),
            (at(1.0, t), u1.point(t)),
        ];
        for (a, b) in pairs {
            gap = gap.max(a.distance(b));
        }
    }
    Ok(CoonsReport {
        corner_gaps: boundaries.corner_gaps(),
        max_boundary_gap: gap,
        degrees: surface.degrees(),
        size: surface.size(),
    })
}
