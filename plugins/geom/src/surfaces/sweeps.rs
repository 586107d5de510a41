//! Surfaces from curves (seed 004's 2.5D modeling, Rhino's ExtrudeCrv,
//! Revolve, Sweep1, Sweep2 and Loft, Blender's Spin and Screw): each as an
//! exact or stated-accuracy NURBS surface, and as a polygon mesh of quads
//! with n-gon caps built through [`HalfEdgeMesh::from_polygons`].
//!
//! - [`revolve`]: a curve turned about any axis by any angle, with the
//!   exact rational circle construction (Piegl & Tiller, *The NURBS Book*,
//!   A8.1: at most 90° per rational quadratic arc, the middle weight
//!   `cos(Δθ/2)`), and a pitch (screw) that rises along the axis.
//! - [`extrude`]: a curve moved along a vector (degree 1 across).
//! - [`sweep`]: a profile carried along a rail by a rotation-minimising
//!   frame (the double-reflection method of Wang, Jüttler, Zheng and Liu,
//!   *Computation of rotation minimizing frames*, ACM TOG 27(1), 2008) or
//!   the Frenet frame (seed 001), then skinned ([`loft`]) through the
//!   placed copies.
//! - [`sweep2`]: a profile carried along two rails, turned and scaled so
//!   its ends stay on them.
//! - [`loft`]: a surface through an ordered set of sections made
//!   compatible ([`make_compatible`]: clamped, one domain, degree
//!   elevation, knot merging), open or closed, as ruled strips, with the
//!   sections as control rows, or interpolating them (The NURBS Book §10.3,
//!   skinning; parameters by averaged chord length, knots by averaging).
//! - [`planar_cap`]: the flat disc a closed planar profile bounds.
//!
//! Every function leaves its inputs untouched and returns a named
//! [`SweepError`] when it refuses.

use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, TAU};

use glam::{DMat4, DQuat, DVec3, DVec4};

use super::{NurbsSurface, Surface};
use crate::build::BuildError;
use crate::curves::interpolating::solve_dense;
use crate::curves::nurbs::basis_derivatives;
use crate::curves::{Curve, CurveError, NurbsCurve};
use crate::mesh::HalfEdgeMesh;

/// The most segments a mesh made here may have in either direction.
pub const MAX_SEGMENTS: u32 = 4096;

/// Why a surface cannot be made from its curves. The inputs are unchanged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SweepError {
    /// A curve operation (knot insertion, elevation, building the result)
    /// refused.
    #[error(transparent)]
    Curve(#[from] CurveError),
    /// An axis, direction or angle that is NaN or infinite.
    #[error("{what} is not finite")]
    NotFinite {
        /// The input, as the message names it (`"the axis"`).
        what: &'static str,
    },
    /// A revolution axis or extrusion vector of zero length.
    #[error("{what} has zero length")]
    ZeroVector {
        /// `"the axis"` or `"the extrusion vector"`.
        what: &'static str,
    },
    /// A revolution angle of zero, or beyond one turn without a pitch.
    #[error("the angle must not be 0 and at most 360° either way without a pitch, not {degrees}°")]
    BadAngle {
        /// The angle asked for, in degrees.
        degrees: f64,
    },
    /// Caps asked for on a profile whose ends do not meet.
    #[error("caps need a closed profile (its ends are {gap} apart)")]
    OpenProfile {
        /// The distance between the profile's two ends.
        gap: f64,
    },
    /// Caps asked for on a profile that does not lie in a plane.
    #[error("caps need a planar profile (a control point lies {deviation} off its plane)")]
    NotPlanar {
        /// The largest distance of a control point from the best plane.
        deviation: f64,
    },
    /// Caps asked for on a closed profile that encloses no area (all its
    /// points on a line).
    #[error("caps need a profile that encloses an area")]
    NoArea,
    /// A NURBS cap asked for on a profile that is not star-shaped about its
    /// centroid (the fan from it would fold over itself).
    #[error(
        "a NURBS cap needs a profile whose centre sees all of it (star-shaped); choose Mesh output, whose caps are n-gons"
    )]
    NotStarShaped,
    /// A loft with too few sections.
    #[error("{what} needs at least {needed} sections, got {got}")]
    TooFewSections {
        /// `"a loft"` or `"a closed loft"`.
        what: &'static str,
        /// The least number of sections it takes.
        needed: usize,
        /// The number given.
        got: usize,
    },
    /// The rail's tangent vanishes (it stops) at a parameter.
    #[error("the rail has no tangent at parameter {t}")]
    RailStops {
        /// The rail parameter.
        t: f64,
    },
    /// The Frenet frame is undefined where the rail is straight.
    #[error(
        "the Frenet frame is undefined at rail parameter {t} (the rail is straight there); use the rotation-minimising frame"
    )]
    NoFrenetFrame {
        /// The rail parameter.
        t: f64,
    },
    /// The two rails of a two-rail sweep meet, or run along the line
    /// between them.
    #[error(
        "the rails meet or run side by side at station {station}: the profile has no frame there"
    )]
    RailsDegenerate {
        /// The station (0 at the rails' start).
        station: usize,
    },
    /// A segment or station count out of range.
    #[error("{what} must be between {min} and {MAX_SEGMENTS}, not {got}")]
    Segments {
        /// `"segments"`, `"profile segments"`, `"sections"`.
        what: &'static str,
        /// The least allowed.
        min: u32,
        /// The count given.
        got: u32,
    },
    /// The polygons of a mesh result are not a manifold mesh (a profile
    /// that crosses the axis, say).
    #[error("the mesh cannot be built: {0}")]
    Mesh(#[from] BuildError),
}

/// An axis of revolution: a point on it and its direction (any length).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Axis {
    /// A point of the axis.
    pub origin: DVec3,
    /// The axis direction; the turn is right-handed about it.
    pub direction: DVec3,
}

impl Axis {
    /// The axis checked, its direction made a unit vector.
    fn unit(self) -> Result<Axis, SweepError> {
        if !self.origin.is_finite() || !self.direction.is_finite() {
            return Err(SweepError::NotFinite { what: "the axis" });
        }
        let d = self
            .direction
            .try_normalize()
            .ok_or(SweepError::ZeroVector { what: "the axis" })?;
        Ok(Axis {
            origin: self.origin,
            direction: d,
        })
    }

    /// `p` turned by `angle` (right-handed) about the axis and moved
    /// `rise` along it.
    fn turn(&self, p: DVec3, angle: f64, rise: f64) -> DVec3 {
        let d = self.direction;
        let o = self.origin + d * (p - self.origin).dot(d);
        let x = p - o;
        let y = d.cross(x);
        o + x * angle.cos() + y * angle.sin() + d * rise
    }
}

/// The checked angle of a revolution: not zero, finite, within one turn
/// either way unless there is a pitch.
fn check_angle(angle: f64, pitch: f64) -> Result<(), SweepError> {
    if !pitch.is_finite() {
        return Err(SweepError::NotFinite { what: "the pitch" });
    }
    let degrees = angle.to_degrees();
    if !angle.is_finite() || angle == 0.0 || (pitch == 0.0 && angle.abs() > TAU * (1.0 + 1e-12)) {
        return Err(SweepError::BadAngle { degrees });
    }
    // More than a thousand turns is a typo, not a screw.
    if angle.abs() > 1000.0 * TAU {
        return Err(SweepError::BadAngle { degrees });
    }
    Ok(())
}

/// True when a revolution by `angle` with `pitch` closes on itself.
fn full_turn(angle: f64, pitch: f64) -> bool {
    pitch == 0.0 && (angle.abs() - TAU).abs() <= TAU * 1e-12
}

/// `profile` revolved by `angle` radians (right-handed about the axis
/// direction; negative turns the other way) about `axis`, rising `pitch`
/// along the axis per full turn (a screw; 0 for a plain revolution). u goes
/// around (degree 2, one rational quadratic arc per 90° or less), v along
/// the profile (its degree and knots): a profile running along the axis
/// direction gets normals `S_u × S_v` pointing away from the axis.
///
/// Without a pitch the surface is exact: every point of the profile moves
/// on an exact circle about the axis (Piegl & Tiller A8.1). With a pitch
/// the circle part is exact and the rise follows the rational arc's
/// parameter, exact at the ends and middle of every arc and within about
/// `6.3e-4 · pitch` of the true helix between them (arcs of at most 45°).
/// Inverse: none (take the profile back as the surface's row `u = 0`).
///
/// # Errors
/// [`SweepError::NotFinite`] or [`SweepError::ZeroVector`] for the axis,
/// [`SweepError::BadAngle`] for a zero angle or more than a turn without a
/// pitch.
///
/// Complexity: O(profile points × arcs).
pub fn revolve(
    profile: &NurbsCurve,
    axis: Axis,
    angle: f64,
    pitch: f64,
) -> Result<NurbsSurface, SweepError> {
    let axis = axis.unit()?;
    check_angle(angle, pitch)?;
    // A helix needs shorter arcs to follow its rise closely.
    let max_arc = if pitch == 0.0 {
        FRAC_PI_2
    } else {
        FRAC_PI_2 / 2.0
    };
    let arcs = ((angle.abs() / max_arc) - 1e-9).ceil().max(1.0) as usize;
    let step = angle / arcs as f64;
    let wm = (step / 2.0).cos();
    let d = axis.direction;
    let nu = 2 * arcs + 1;
    let nv = profile.points().len();
    let mut points = vec![DVec3::ZERO; nu * nv];
    let mut weights = vec![0.0; nu * nv];
    for (j, (&p, &w)) in profile.points().iter().zip(profile.weights()).enumerate() {
        let o = axis.origin + d * (p - axis.origin).dot(d);
        let radial = p - o;
        let r = radial.length();
        let x = if r > 0.0 {
            radial / r
        } else {
            d.any_orthonormal_vector()
        };
        let y = d.cross(x);
        for i in 0..nu {
            let theta = angle * i as f64 / (2 * arcs) as f64;
            let rise = d * pitch * theta / TAU;
            let dir = x * theta.cos() + y * theta.sin();
            let (q, wq) = if i % 2 == 0 {
                (o + dir * r, w)
            } else {
                (o + dir * (r / wm), w * wm)
            };
            points[i * nv + j] = q + rise;
            weights[i * nv + j] = wq;
        }
    }
    let mut knots_u = vec![0.0; 3];
    for k in 1..arcs {
        let t = k as f64 / arcs as f64;
        knots_u.extend([t, t]);
    }
    knots_u.extend([1.0; 3]);
    Ok(NurbsSurface::new(
        2,
        profile.degree(),
        knots_u,
        profile.knots().to_vec(),
        nu,
        nv,
        points,
        weights,
    )?)
}

/// `profile` moved along `vector`: u along the profile (its degree and
/// knots), v along the vector (degree 1), exact (seed 004's extrusion).
/// Inverse: none (the profile is the row `v = 0`).
///
/// # Errors
/// [`SweepError::NotFinite`] or [`SweepError::ZeroVector`] for the vector.
///
/// Complexity: O(profile points).
pub fn extrude(profile: &NurbsCurve, vector: DVec3) -> Result<NurbsSurface, SweepError> {
    check_vector(vector)?;
    Ok(NurbsSurface::extrude(profile, vector)?)
}

fn check_vector(vector: DVec3) -> Result<(), SweepError> {
    if !vector.is_finite() {
        return Err(SweepError::NotFinite {
            what: "the extrusion vector",
        });
    }
    if vector.length_squared() == 0.0 {
        return Err(SweepError::ZeroVector {
            what: "the extrusion vector",
        });
    }
    Ok(())
}

// ----- profiles: closedness, plane, sampling ------------------------------

/// The size of a curve's control polygon (its bounding box diagonal), for
/// relative tolerances.
fn size_of(points: &[DVec3]) -> f64 {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    (hi - lo).length().max(1e-300)
}

/// The distance between a curve's two ends.
fn end_gap(curve: &NurbsCurve) -> f64 {
    let (a, b) = curve.domain();
    curve.point(a).distance(curve.point(b))
}

/// True when the curve's ends meet (within `1e-9` of its size).
///
/// Complexity: O(control points).
pub fn is_closed(curve: &NurbsCurve) -> bool {
    end_gap(curve) <= 1e-9 * size_of(curve.points())
}

/// The plane of a closed planar profile: its area centroid and unit
/// normal (Newell's method on a fine sample; the normal follows the
/// profile's direction by the right-hand rule).
///
/// # Errors
/// [`SweepError::OpenProfile`], [`SweepError::NotPlanar`] (a control
/// point off the plane by more than `1e-9` of the profile's size) or
/// [`SweepError::NoArea`].
///
/// Complexity: O(control points + 256 samples).
pub fn profile_plane(curve: &NurbsCurve) -> Result<(DVec3, DVec3), SweepError> {
    let size = size_of(curve.points());
    let gap = end_gap(curve);
    if gap > 1e-9 * size {
        return Err(SweepError::OpenProfile { gap });
    }
    let (a, b) = curve.domain();
    let samples: Vec<f64> = (0..256).map(|k| a + (b - a) * k as f64 / 256.0).collect();
    let poly = curve.points_at(&samples);
    let mut normal = DVec3::ZERO;
    for (k, p) in poly.iter().enumerate() {
        normal += p.cross(poly[(k + 1) % poly.len()]);
    }
    let n = normal
        .try_normalize()
        .filter(|_| normal.length() > 1e-12 * size * size)
        .ok_or(SweepError::NoArea)?;
    // Area centroid of the polygon, fanned from its first point.
    let mut area = 0.0;
    let mut centroid = DVec3::ZERO;
    for k in 1..poly.len() - 1 {
        let t = (poly[k] - poly[0]).cross(poly[k + 1] - poly[0]).dot(n) / 2.0;
        area += t;
        centroid += (poly[0] + poly[k] + poly[k + 1]) / 3.0 * t;
    }
    let centroid = if area.abs() > 0.0 {
        centroid / area
    } else {
        poly.iter().copied().sum::<DVec3>() / poly.len() as f64
    };
    let deviation = curve
        .points()
        .iter()
        .map(|p| (*p - centroid).dot(n).abs())
        .fold(0.0, f64::max);
    if deviation > 1e-9 * size {
        return Err(SweepError::NotPlanar { deviation });
    }
    Ok((centroid, n))
}

/// The flat cap a closed planar profile bounds, as a NURBS surface: the
/// profile (u, its degree and knots) joined by straight lines to its area
/// centroid (v, degree 1, `v = 1` collapsed to the centroid). Exact for a
/// circle (a disc); right for every profile that is star-shaped about its
/// centroid (convex ones are). Its normal `S_u × S_v` is opposite to
/// [`profile_plane`]'s. Inverse: none (the profile is its row `v = 0`).
///
/// # Errors
/// As [`profile_plane`].
///
/// Complexity: O(profile points + 256 samples).
pub fn planar_cap(profile: &NurbsCurve) -> Result<NurbsSurface, SweepError> {
    let (centroid, normal) = profile_plane(profile)?;
    // Star-shaped about the centroid: the ray from it turns one way only.
    let (a, b) = profile.domain();
    let samples: Vec<f64> = (0..=512).map(|k| a + (b - a) * k as f64 / 512.0).collect();
    let ring = profile.points_at(&samples);
    if ring
        .windows(2)
        .any(|w| (w[0] - centroid).cross(w[1] - centroid).dot(normal) <= 0.0)
    {
        return Err(SweepError::NotStarShaped);
    }
    let rim = profile.points().iter().map(|_| centroid).collect();
    let inner = NurbsCurve::new(
        profile.degree(),
        profile.knots().to_vec(),
        rim,
        profile.weights().to_vec(),
    )?;
    skin_rows(&[profile.clone(), inner], 1, clamped_knots(1, &[0.0, 1.0]))
}

/// The parametric direction a surface was swept along (its other
/// direction runs along the profile).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Along {
    /// Along u: a [`revolve`]'s turn.
    U,
    /// Along v: an [`extrude`], [`sweep`], [`sweep2`] or [`loft`].
    V,
}

/// The flat NURBS caps ([`planar_cap`]) that close the two ends of
/// `surface`, swept `along` one parametric direction: the start end's
/// first, each facing away from the surface (its normal against the sweep
/// at the start, with it at the end). None where the surface closes on
/// itself in that direction (a full revolution, a sweep around a closed
/// rail, a closed loft).
///
/// # Errors
/// As [`planar_cap`] for an end that is open, not planar or not
/// star-shaped.
///
/// Complexity: O(profile points + 512 samples) per end.
pub fn end_caps(surface: &NurbsSurface, along: Along) -> Result<Vec<NurbsSurface>, SweepError> {
    let (nu, nv) = surface.size();
    let ((u0, u1), (v0, v1)) = surface.domain();
    let closed_v = along == Along::V && is_closed_in_v(surface);
    let (first, last) = match along {
        Along::U => (surface.row(0), surface.row(nu - 1)),
        Along::V => (surface.column(0), surface.column(nv - 1)),
    };
    if closed_v || same_curve(&first, &last) {
        return Ok(Vec::new());
    }
    let mut caps = Vec::with_capacity(2);
    for (end, curve) in [(0, first), (1, last)] {
        let (a, b) = curve.domain();
        let t = (a + b) / 2.0;
        // The sweep's direction at the end, from the surface's partials.
        let e = match (along, end) {
            (Along::U, 0) => surface.evaluate(u0, t).du,
            (Along::U, _) => surface.evaluate(u1, t).du,
            (Along::V, 0) => surface.evaluate(t, v0).dv,
            (Along::V, _) => surface.evaluate(t, v1).dv,
        };
        let outward = if end == 0 { -e } else { e };
        let cap = planar_cap(&curve)?;
        let ((cu0, cu1), (cv0, cv1)) = cap.domain();
        let facing = cap.evaluate((cu0 + cu1) / 2.0, (cv0 + cv1) / 4.0).normal();
        caps.push(if facing.dot(outward) < 0.0 {
            planar_cap(&curve.reversed())?
        } else {
            cap
        });
    }
    Ok(caps)
}

/// The parameters a mesh samples a profile at: the control points' own
/// parameters for a polyline (degree 1, so corners stay sharp), else
/// `segments` equal steps of the domain; without the last one when the
/// curve is closed. Returns them and whether the curve is closed.
///
/// Complexity: O(knots + segments).
pub fn profile_parameters(curve: &NurbsCurve, segments: u32) -> (Vec<f64>, bool) {
    let closed = is_closed(curve);
    let (a, b) = curve.domain();
    let mut params: Vec<f64> = if curve.degree() == 1 {
        let mut k: Vec<f64> = curve
            .knots()
            .iter()
            .copied()
            .filter(|&t| (a..=b).contains(&t))
            .collect();
        k.dedup();
        k
    } else {
        let n = segments.max(1);
        (0..=n)
            .map(|i| a + (b - a) * f64::from(i) / f64::from(n))
            .collect()
    };
    if closed && params.len() > 2 {
        params.pop();
    }
    (params, closed)
}

fn check_segments(what: &'static str, got: u32, min: u32) -> Result<(), SweepError> {
    if got < min || got > MAX_SEGMENTS {
        return Err(SweepError::Segments { what, min, got });
    }
    Ok(())
}

// ----- frames along a rail ------------------------------------------------

/// Which frame carries a profile along a rail.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum FrameKind {
    /// The rotation-minimising frame (no twist about the tangent; Wang et
    /// al. 2008, double reflection).
    #[default]
    RotationMinimizing,
    /// The Frenet frame (tangent, principal normal, binormal; seed 001):
    /// it flips where the curvature changes sign and is undefined on
    /// straight stretches.
    Frenet,
}

/// A moving frame at a point of a rail: an origin and three orthonormal
/// axes (right-handed: `normal × binormal = tangent`).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Frame {
    /// The rail's point.
    pub origin: DVec3,
    /// The unit tangent.
    pub tangent: DVec3,
    /// The first normal axis.
    pub normal: DVec3,
    /// The second normal axis, `tangent × normal`.
    pub binormal: DVec3,
}

impl Frame {
    /// The matrix taking frame coordinates (normal, binormal, tangent) to
    /// world space.
    pub fn matrix(&self) -> DMat4 {
        DMat4::from_cols(
            self.normal.extend(0.0),
            self.binormal.extend(0.0),
            self.tangent.extend(0.0),
            self.origin.extend(1.0),
        )
    }
}

/// Sub-steps of the double reflection between two stations.
const RMF_SUBSTEPS: usize = 32;

/// True when `rail` is closed and its tangent turns smoothly across the
/// seam (the ends' unit tangents within 1e-6 of each other): then a frame
/// carried once around it can be made to close up.
///
/// Complexity: O(control points).
pub fn is_smoothly_closed(rail: &NurbsCurve) -> bool {
    let (a, b) = rail.domain();
    let t0 = rail.derivatives(a)[1].normalize_or_zero();
    let t1 = rail.derivatives(b)[1].normalize_or_zero();
    is_closed(rail) && t0 != DVec3::ZERO && t0.distance(t1) < 1e-6
}

/// The frames of `rail` at the increasing parameters `params`.
///
/// The rotation-minimising frame is propagated by double reflection in
/// `32` sub-steps per station interval from a normal chosen perpendicular
/// to the first tangent; its error per step is O(h⁴) (Wang et al. 2008,
/// §4). On a smoothly closed rail ([`is_smoothly_closed`]) traversed from
/// end to end the frame comes back turned by the rail's holonomy angle;
/// that angle is spread over the rail in proportion to arc length (Wang
/// et al. 2008, §6.3), so the last frame equals the first. The Frenet
/// frame is evaluated at each parameter.
///
/// # Errors
/// [`SweepError::RailStops`] where the tangent vanishes,
/// [`SweepError::NoFrenetFrame`] where the Frenet frame is undefined.
///
/// Complexity: O(stations × 32) evaluations.
pub fn rail_frames(
    rail: &NurbsCurve,
    params: &[f64],
    kind: FrameKind,
) -> Result<Vec<Frame>, SweepError> {
    let tangent_at = |t: f64| -> Result<(DVec3, DVec3), SweepError> {
        let [p, d1, _] = rail.derivatives(t);
        let tangent = d1.try_normalize().ok_or(SweepError::RailStops { t })?;
        Ok((p, tangent))
    };
    match kind {
        FrameKind::Frenet => params
            .iter()
            .map(|&t| {
                let [p, ..] = rail.derivatives(t);
                let [tangent, normal, binormal] = crate::curves::analysis::frenet_frame(rail, t)
                    .ok_or(SweepError::NoFrenetFrame { t })?;
                Ok(Frame {
                    origin: p,
                    tangent,
                    normal,
                    binormal,
                })
            })
            .collect(),
        FrameKind::RotationMinimizing => {
            let Some(&t0) = params.first() else {
                return Ok(Vec::new());
            };
            let (mut x, mut t) = tangent_at(t0)?;
            let mut r = t.any_orthonormal_vector();
            let frame = |x: DVec3, t: DVec3, r: DVec3| {
                // Re-orthonormalise against drift.
                let r = (r - t * r.dot(t)).normalize();
                Frame {
                    origin: x,
                    tangent: t,
                    normal: r,
                    binormal: t.cross(r),
                }
            };
            let mut frames = vec![frame(x, t, r)];
            // Arc length (as the sub-steps' chords) at each station.
            let mut lengths = vec![0.0];
            let mut length = 0.0;
            for w in params.windows(2) {
                for s in 1..=RMF_SUBSTEPS {
                    let u = w[0] + (w[1] - w[0]) * s as f64 / RMF_SUBSTEPS as f64;
                    let (x1, t1) = tangent_at(u)?;
                    let v1 = x1 - x;
                    length += v1.length();
                    let c1 = v1.dot(v1);
                    if c1 > 0.0 {
                        let rl = r - v1 * (2.0 / c1) * v1.dot(r);
                        let tl = t - v1 * (2.0 / c1) * v1.dot(t);
                        let v2 = t1 - tl;
                        let c2 = v2.dot(v2);
                        r = if c2 > 0.0 {
                            rl - v2 * (2.0 / c2) * v2.dot(rl)
                        } else {
                            rl
                        };
                    }
                    x = x1;
                    t = t1;
                }
                let f = frame(x, t, r);
                r = f.normal;
                frames.push(f);
                lengths.push(length);
            }
            let (a, b) = rail.domain();
            let whole_rail = params.len() > 1 && params[0] <= a && params[params.len() - 1] >= b;
            if whole_rail && length > 0.0 && is_smoothly_closed(rail) {
                let (first, last) = (frames[0], frames[frames.len() - 1]);
                // The angle about the tangent from the last normal to the first.
                let twist = last
                    .normal
                    .cross(first.normal)
                    .dot(last.tangent)
                    .atan2(last.normal.dot(first.normal));
                for (f, &l) in frames.iter_mut().zip(&lengths) {
                    let turn = DQuat::from_axis_angle(f.tangent, twist * l / length);
                    let normal = turn * f.normal;
                    *f = frame(f.origin, f.tangent, normal);
                }
            }
            Ok(frames)
        }
    }
}

/// The stations where a frame flips: its normal turns by more than 90°
/// from the previous station's. The Frenet frame does this where the
/// rail's curvature passes through zero (an inflection, seed 001: the
/// principal normal always points to the centre of curvature), which twists
/// a swept profile half a turn; the rotation-minimising frame never does
/// between stations close enough together.
///
/// Complexity: O(frames).
pub fn frame_flips(frames: &[Frame]) -> Vec<usize> {
    frames
        .windows(2)
        .enumerate()
        .filter(|(_, w)| w[0].normal.dot(w[1].normal) < 0.0)
        .map(|(k, _)| k + 1)
        .collect()
}

/// How a sweep is made.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct SweepOptions {
    /// The frame that carries the profile.
    pub frame: FrameKind,
    /// Copies of the profile placed along the rail and skinned (at least
    /// 2); more follow the rail more closely.
    pub sections: u32,
}

impl Default for SweepOptions {
    fn default() -> Self {
        SweepOptions {
            frame: FrameKind::RotationMinimizing,
            sections: 24,
        }
    }
}

/// `profile` carried along `rail`: the profile is read relative to the
/// rail's frame at its start (so a profile drawn perpendicular to the rail
/// there stays perpendicular to it), copied rigidly into the frame at
/// `sections` equal parameter steps, and the copies are skinned (an
/// interpolating [`loft`]). u runs along the profile, v along the rail.
/// The surface passes exactly through every copy; between them it is the
/// cubic interpolation of the copies. On a smoothly closed rail whose
/// frame closes up (always for the rotation-minimising frame, see
/// [`rail_frames`]) the last copy is the first and the surface is closed
/// (periodic) along the rail ([`is_closed_in_v`]). Inverse: none.
///
/// # Errors
/// As [`rail_frames`] and [`loft`]; [`SweepError::Segments`] for fewer
/// than 2 sections.
///
/// Complexity: O(sections × (32 + profile points)) plus the skinning's
/// dense solves, O(profile points × sections³).
pub fn sweep(
    profile: &NurbsCurve,
    rail: &NurbsCurve,
    options: SweepOptions,
) -> Result<NurbsSurface, SweepError> {
    let mut sections = sweep_sections(profile, rail, options)?;
    let closed = sections.len() >= 4
        && is_smoothly_closed(rail)
        && same_curve(&sections[0], &sections[sections.len() - 1]);
    if closed {
        sections.pop();
    }
    loft(
        &sections,
        LoftOptions {
            closed,
            tightness: Tightness::Normal,
        },
    )
}

/// True when two curves have the same control points (within `1e-9` of
/// their size) and weights.
fn same_curve(a: &NurbsCurve, b: &NurbsCurve) -> bool {
    let tolerance = 1e-9 * size_of(a.points());
    a.points().len() == b.points().len()
        && a.points()
            .iter()
            .zip(b.points())
            .all(|(p, q)| p.distance(*q) <= tolerance)
        && a.weights()
            .iter()
            .zip(b.weights())
            .all(|(w, v)| (w - v).abs() <= 1e-9 * w.abs())
}

/// True when `surface` is closed (periodic, unclamped knots) in v, as a
/// closed [`loft`] and a [`sweep`] along a closed rail are.
pub fn is_closed_in_v(surface: &NurbsSurface) -> bool {
    let (_, kv) = surface.knots();
    kv.len() > 1 && kv[0] != kv[1]
}

/// The rail parameters of a sweep's `sections` copies: equal steps over
/// the rail's domain, both ends included.
pub fn stations(curve: &NurbsCurve, sections: u32) -> Vec<f64> {
    let (a, b) = curve.domain();
    (0..sections)
        .map(|i| a + (b - a) * f64::from(i) / f64::from(sections - 1))
        .collect()
}

/// The copies of `profile` that [`sweep`] skins, in rail order.
///
/// # Errors
/// As [`sweep`].
pub fn sweep_sections(
    profile: &NurbsCurve,
    rail: &NurbsCurve,
    options: SweepOptions,
) -> Result<Vec<NurbsCurve>, SweepError> {
    check_segments("sections", options.sections, 2)?;
    let frames = rail_frames(rail, &stations(rail, options.sections), options.frame)?;
    let to_start = frames[0].matrix().inverse();
    frames
        .iter()
        .map(|f| Ok(profile.transformed(&(f.matrix() * to_start))?))
        .collect()
}

/// `profile` carried along two rails (Rhino's Sweep2): at each of
/// `sections` stations (equal parameter steps on each rail) the profile is
/// turned, moved and scaled uniformly so that the segment between the rails'
/// starting points maps onto the segment between the rails' points there,
/// its plane kept across the rails' mean direction. A profile whose ends lie
/// on the rails' starts keeps them on the rails. The copies are skinned as
/// in [`sweep`]. Inverse: none.
///
/// # Errors
/// [`SweepError::RailsDegenerate`] where the rails meet or the line
/// between them runs along their direction; as [`sweep`] otherwise.
///
/// Complexity: as [`sweep`].
pub fn sweep2(
    profile: &NurbsCurve,
    rails: [&NurbsCurve; 2],
    sections: u32,
) -> Result<NurbsSurface, SweepError> {
    let copies = sweep2_sections(profile, rails, sections)?;
    loft(
        &copies,
        LoftOptions {
            closed: false,
            tightness: Tightness::Normal,
        },
    )
}

/// The copies of `profile` that [`sweep2`] skins, in rail order.
///
/// # Errors
/// As [`sweep2`].
pub fn sweep2_sections(
    profile: &NurbsCurve,
    rails: [&NurbsCurve; 2],
    sections: u32,
) -> Result<Vec<NurbsCurve>, SweepError> {
    check_segments("sections", sections, 2)?;
    let ta = stations(rails[0], sections);
    let tb = stations(rails[1], sections);
    let mut frames = Vec::with_capacity(ta.len());
    for (station, (&s, &t)) in ta.iter().zip(&tb).enumerate() {
        let [a, da, _] = rails[0].derivatives(s);
        let [b, db, _] = rails[1].derivatives(t);
        let span = b - a;
        let width = span.length();
        let degenerate = SweepError::RailsDegenerate { station };
        let e1 = span.try_normalize().ok_or(degenerate.clone())?;
        let mean = da.normalize_or_zero() + db.normalize_or_zero();
        let e2 = (mean - e1 * mean.dot(e1))
            .try_normalize()
            .filter(|_| (mean - e1 * mean.dot(e1)).length() > 1e-9)
            .ok_or(degenerate)?;
        let e3 = e2.cross(e1);
        frames.push(DMat4::from_cols(
            (e1 * width).extend(0.0),
            (e3 * width).extend(0.0),
            (e2 * width).extend(0.0),
            a.extend(1.0),
        ));
    }
    let to_start = frames[0].inverse();
    frames
        .iter()
        .map(|m| Ok(profile.transformed(&(*m * to_start))?))
        .collect()
}

// ----- loft ---------------------------------------------------------------

/// How closely a loft follows its sections between them.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Tightness {
    /// Ruled strips between neighbouring sections (degree 1 across);
    /// passes through every section.
    Straight,
    /// The sections' control points are the surface's control rows
    /// (degree up to 3 across): smooth, passes through the first and last
    /// section only (Rhino's Loose).
    Loose,
    /// Interpolates every section with a cubic across (degree up to 3;
    /// Rhino's Normal).
    #[default]
    Normal,
}

/// How a loft is made.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct LoftOptions {
    /// The last section joins back to the first (periodic across).
    pub closed: bool,
    /// How the surface runs between the sections.
    pub tightness: Tightness,
}

/// The curves made compatible (The NURBS Book §10.3): each clamped at its
/// ends ([`NurbsCurve::clamped_ends`]), its domain mapped onto [0, 1],
/// raised to the highest degree among them ([`NurbsCurve::elevate_degree`])
/// and given every knot of the others with the highest multiplicity any of
/// them has ([`NurbsCurve::insert_knot`]); none of the curves moves. After
/// it they share degree, knots and control point count. Inverse: none
/// (each result traces its input's shape).
///
/// # Errors
/// A knot insertion or elevation that fails.
///
/// Complexity: O(curves × (elevations + knots) × points).
pub fn make_compatible(curves: &[NurbsCurve]) -> Result<Vec<NurbsCurve>, SweepError> {
    let mut out = Vec::with_capacity(curves.len());
    for c in curves {
        let c = c.clamped_ends();
        let (a, b) = c.domain();
        let knots = c.knots().iter().map(|k| (k - a) / (b - a)).collect();
        out.push(NurbsCurve::new(
            c.degree(),
            knots,
            c.points().to_vec(),
            c.weights().to_vec(),
        )?);
    }
    let degree = out.iter().map(NurbsCurve::degree).max().unwrap_or(1);
    for c in &mut out {
        while c.degree() < degree {
            *c = c.elevate_degree()?;
        }
    }
    // The merged interior knots with their highest multiplicity.
    let mut merged: Vec<(f64, usize)> = Vec::new();
    for c in &out {
        for (value, count) in interior_multiplicities(c) {
            match merged.iter_mut().find(|(v, _)| *v == value) {
                Some((_, m)) => *m = (*m).max(count),
                None => merged.push((value, count)),
            }
        }
    }
    for c in &mut out {
        let own = interior_multiplicities(c);
        for &(value, m) in &merged {
            let has = own.iter().find(|(v, _)| *v == value).map_or(0, |(_, n)| *n);
            for _ in has..m {
                *c = c.insert_knot(value)?;
            }
        }
    }
    Ok(out)
}

fn interior_multiplicities(c: &NurbsCurve) -> Vec<(f64, usize)> {
    let (a, b) = c.domain();
    let mut out: Vec<(f64, usize)> = Vec::new();
    for &k in c.knots().iter().filter(|&&k| k > a && k < b) {
        match out.last_mut() {
            Some((v, n)) if *v == k => *n += 1,
            _ => out.push((k, 1)),
        }
    }
    out
}

/// A surface through the ordered `sections` (u along them, v across):
/// they are made compatible ([`make_compatible`]), then joined as
/// [`Tightness`] says, open (the first and last section are the v = 0 and
/// v = 1 boundaries) or closed (periodic across, uniform knots). Straight
/// and Normal lofts pass through every section; the parameters of the
/// sections across are their averaged chord lengths (uniform when closed),
/// the knots by averaging (The NURBS Book eq. 9.8). Interpolation runs in
/// homogeneous coordinates, so rational sections (circles) are reproduced
/// exactly. Inverse: none (section k is the surface's iso-curve at its
/// parameter).
///
/// # Errors
/// [`SweepError::TooFewSections`] (2 open, 3 closed); as
/// [`make_compatible`]; [`CurveError::Singular`] or a weight that comes out
/// non-positive (through [`SweepError::Curve`]) for sections too wild to
/// interpolate.
///
/// Complexity: O(points × sections³) for the dense solves.
pub fn loft(sections: &[NurbsCurve], options: LoftOptions) -> Result<NurbsSurface, SweepError> {
    let needed = if options.closed { 3 } else { 2 };
    if sections.len() < needed {
        return Err(SweepError::TooFewSections {
            what: if options.closed {
                "a closed loft"
            } else {
                "a loft"
            },
            needed,
            got: sections.len(),
        });
    }
    let curves = make_compatible(sections)?;
    let n = curves.len();
    let q = match options.tightness {
        Tightness::Straight => 1,
        _ => 3.min(if options.closed { n } else { n - 1 }),
    };
    if options.closed {
        let knots: Vec<f64> = (0..=n + 2 * q).map(|k| k as f64).collect();
        let rows = match options.tightness {
            Tightness::Loose => curves.clone(),
            _ => interpolate_periodic(&curves, q)?,
        };
        let mut wrapped = rows.clone();
        wrapped.extend_from_slice(&rows[..q]);
        return skin_rows(&wrapped, q, knots);
    }
    match options.tightness {
        Tightness::Loose => {
            let params: Vec<f64> = (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
            skin_rows(&curves, q, uniform_clamped(q, &params))
        }
        _ => {
            let params = section_parameters(&curves);
            let knots = clamped_knots(q, &params);
            let rows = if q == 1 {
                curves
            } else {
                interpolate_open(&curves, q, &params, &knots)?
            };
            skin_rows(&rows, q, knots)
        }
    }
}

/// Averaged chord-length parameters of compatible sections (The NURBS
/// Book eq. 10.8): each control point index's chord lengths across the
/// sections, normalised, averaged over the indices that move.
fn section_parameters(curves: &[NurbsCurve]) -> Vec<f64> {
    let n = curves.len();
    let m = curves[0].points().len();
    let mut sum = vec![0.0; n];
    let mut used = 0;
    for i in 0..m {
        let chords: Vec<f64> = (1..n)
            .map(|k| curves[k].points()[i].distance(curves[k - 1].points()[i]))
            .collect();
        let total: f64 = chords.iter().sum();
        if total <= 0.0 {
            continue;
        }
        used += 1;
        let mut acc = 0.0;
        for k in 1..n {
            acc += chords[k - 1];
            sum[k] += acc / total;
        }
    }
    if used == 0 {
        return (0..n).map(|k| k as f64 / (n - 1) as f64).collect();
    }
    let mut params: Vec<f64> = sum.iter().map(|s| s / used as f64).collect();
    params[n - 1] = 1.0;
    // Sections that coincide everywhere would repeat a parameter.
    for k in 1..n {
        if params[k] <= params[k - 1] {
            params[k] = params[k - 1] + 1e-9;
        }
    }
    let last = params[n - 1];
    params.iter().map(|p| p / last).collect()
}

/// Clamped knots of degree `q` by averaging the parameters (eq. 9.8).
fn clamped_knots(q: usize, params: &[f64]) -> Vec<f64> {
    let n = params.len();
    let mut knots = vec![params[0]; q + 1];
    for j in 1..n - q {
        knots.push(params[j..j + q].iter().sum::<f64>() / q as f64);
    }
    knots.extend(std::iter::repeat_n(params[n - 1], q + 1));
    knots
}

/// Clamped uniform knots of degree `q` for `params.len()` control points.
fn uniform_clamped(q: usize, params: &[f64]) -> Vec<f64> {
    crate::curves::nurbs::clamped_uniform_knots(q, params.len())
}

fn find_span(knots: &[f64], q: usize, count: usize, t: f64) -> usize {
    if t >= knots[count] {
        let mut i = count - 1;
        while i > q && knots[i] >= knots[count] {
            i -= 1;
        }
        return i;
    }
    let mut i = q;
    while i < count - 1 && knots[i + 1] <= t {
        i += 1;
    }
    i
}

/// Solves `A x = rhs` for the homogeneous control points of each column:
/// `rows[k]` are the compatible curves, the result the control curves.
fn solve_columns(
    matrix: &[Vec<f64>],
    curves: &[NurbsCurve],
) -> Result<Vec<NurbsCurve>, SweepError> {
    let n = curves.len();
    let m = curves[0].points().len();
    let mut out_points = vec![vec![DVec3::ZERO; m]; n];
    let mut out_weights = vec![vec![0.0; m]; n];
    for i in 0..m {
        let hom: Vec<DVec4> = curves
            .iter()
            .map(|c| (c.points()[i] * c.weights()[i]).extend(c.weights()[i]))
            .collect();
        let xyz = solve_dense(matrix.to_vec(), hom.iter().map(|h| h.truncate()).collect())?;
        let w = solve_dense(
            matrix.to_vec(),
            hom.iter().map(|h| DVec3::new(h.w, 0.0, 0.0)).collect(),
        )?;
        for k in 0..n {
            let wk = w[k].x;
            if !(wk.is_finite() && wk > 0.0) {
                return Err(CurveError::BadWeight {
                    index: k * m + i,
                    value: wk,
                }
                .into());
            }
            out_points[k][i] = xyz[k] / wk;
            out_weights[k][i] = wk;
        }
    }
    let c0 = &curves[0];
    out_points
        .into_iter()
        .zip(out_weights)
        .map(|(p, w)| Ok(NurbsCurve::new(c0.degree(), c0.knots().to_vec(), p, w)?))
        .collect()
}

/// The control rows of an open cubic (degree `q`) interpolation across.
fn interpolate_open(
    curves: &[NurbsCurve],
    q: usize,
    params: &[f64],
    knots: &[f64],
) -> Result<Vec<NurbsCurve>, SweepError> {
    let n = curves.len();
    let mut matrix = vec![vec![0.0; n]; n];
    for (k, &t) in params.iter().enumerate() {
        let span = find_span(knots, q, n, t);
        let basis = basis_derivatives(knots, span, t, q, 0);
        for (r, &b) in basis[0].iter().enumerate() {
            matrix[k][span - q + r] = b;
        }
    }
    solve_columns(&matrix, curves)
}

/// The `n` periodic control rows of degree `q` on uniform knots whose
/// surface passes through section `k` at `v = q + k` (odd `q`) or
/// `q + k + ½` (even `q`).
fn interpolate_periodic(curves: &[NurbsCurve], q: usize) -> Result<Vec<NurbsCurve>, SweepError> {
    let n = curves.len();
    let knots: Vec<f64> = (0..=n + 2 * q).map(|k| k as f64).collect();
    let shift = if q.is_multiple_of(2) { 0.5 } else { 0.0 };
    let mut matrix = vec![vec![0.0; n]; n];
    for (k, row) in matrix.iter_mut().enumerate() {
        let t = (q + k) as f64 + shift;
        let span = find_span(&knots, q, n + q, t);
        let basis = basis_derivatives(&knots, span, t, q, 0);
        for (r, &b) in basis[0].iter().enumerate() {
            row[(span - q + r) % n] += b;
        }
    }
    solve_columns(&matrix, curves)
}

/// The surface whose v-rows of control points are the compatible curves
/// `rows` (u along each), degree `q` across on `knots`.
fn skin_rows(rows: &[NurbsCurve], q: usize, knots: Vec<f64>) -> Result<NurbsSurface, SweepError> {
    let nv = rows.len();
    let c0 = &rows[0];
    let nu = c0.points().len();
    let mut points = vec![DVec3::ZERO; nu * nv];
    let mut weights = vec![0.0; nu * nv];
    for (j, row) in rows.iter().enumerate() {
        for i in 0..nu {
            points[i * nv + j] = row.points()[i];
            weights[i * nv + j] = row.weights()[i];
        }
    }
    Ok(NurbsSurface::new(
        c0.degree(),
        q,
        c0.knots().to_vec(),
        knots,
        nu,
        nv,
        points,
        weights,
    )?)
}

/// The v parameters at which a loft made with `options` passes through its
/// sections (empty for an open Loose loft, which passes through only its
/// first and last).
///
/// Complexity: that of [`make_compatible`].
pub fn loft_section_parameters(sections: &[NurbsCurve], options: LoftOptions) -> Vec<f64> {
    let Ok(curves) = make_compatible(sections) else {
        return Vec::new();
    };
    let n = curves.len();
    if options.closed {
        let q = match options.tightness {
            Tightness::Straight => 1,
            _ => 3.min(n),
        };
        let shift = if q.is_multiple_of(2) { 0.5 } else { 0.0 };
        return (0..n).map(|k| (q + k) as f64 + shift).collect();
    }
    match options.tightness {
        Tightness::Loose => Vec::new(),
        _ => section_parameters(&curves),
    }
}

// ----- meshes -------------------------------------------------------------

/// A polygon mesh from a grid of points `nu × nv` (`points[i * nv + j]`):
/// a quad for each cell, wrapping around in u or v where closed, and an
/// n-gon cap over the first and last row (`caps_u`: the rows `i = 0` and
/// `i = nu − 1`, each running over j) or column (`caps_v`). Points at the
/// same position (a profile touching the axis, a collapsed section) are
/// welded into one vertex, so quads there become triangles. A closed
/// result is turned to face outwards (positive volume); an open one keeps
/// the grid's orientation (the normal of `(i, j) → (i+1, j) → (i+1, j+1)`).
///
/// # Errors
/// [`SweepError::Mesh`] when the polygons are not a manifold mesh.
///
/// Complexity: O(nu · nv).
#[allow(clippy::too_many_arguments)]
pub fn grid_mesh(
    points: &[DVec3],
    nu: usize,
    nv: usize,
    closed_u: bool,
    closed_v: bool,
    caps_u: bool,
    caps_v: bool,
) -> Result<HalfEdgeMesh, SweepError> {
    // Weld equal positions (exactly equal: the constructions produce the
    // same bits for a point on the axis or a collapsed section).
    let mut index_of: HashMap<[u64; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let key = |p: DVec3| (p + DVec3::ZERO).to_array().map(f64::to_bits);
    let ids: Vec<u32> = points
        .iter()
        .map(|&p| {
            *index_of.entry(key(p)).or_insert_with(|| {
                positions.push(p);
                (positions.len() - 1) as u32
            })
        })
        .collect();
    let at = |i: usize, j: usize| ids[(i % nu) * nv + (j % nv)];
    let cells_u = if closed_u { nu } else { nu - 1 };
    let cells_v = if closed_v { nv } else { nv - 1 };
    let mut polygons: Vec<Vec<u32>> = Vec::new();
    for i in 0..cells_u {
        for j in 0..cells_v {
            polygons.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    if caps_u && !closed_u {
        polygons.push((0..nv).map(|j| at(0, j)).collect());
        polygons.push((0..nv).rev().map(|j| at(nu - 1, j)).collect());
    }
    if caps_v && !closed_v {
        polygons.push((0..nu).rev().map(|i| at(i, 0)).collect());
        polygons.push((0..nu).map(|i| at(i, nv - 1)).collect());
    }
    // Welded corners: drop repeats, then faces that collapsed.
    let polygons: Vec<Vec<u32>> = polygons
        .into_iter()
        .map(|mut f| {
            f.dedup();
            while f.len() > 1 && f.first() == f.last() {
                f.pop();
            }
            f
        })
        .filter(|f| f.len() >= 3)
        .collect();
    let mesh = HalfEdgeMesh::from_polygons(&positions, &polygons)?;
    if mesh.boundary_loops().is_empty() && signed_volume(&positions, &polygons) < 0.0 {
        let flipped: Vec<Vec<u32>> = polygons
            .into_iter()
            .map(|mut f| {
                f.reverse();
                f
            })
            .collect();
        return Ok(HalfEdgeMesh::from_polygons(&positions, &flipped)?);
    }
    Ok(mesh)
}

fn signed_volume(positions: &[DVec3], polygons: &[Vec<u32>]) -> f64 {
    polygons
        .iter()
        .map(|f| {
            let p0 = positions[f[0] as usize];
            (1..f.len() - 1)
                .map(|k| p0.dot(positions[f[k] as usize].cross(positions[f[k + 1] as usize])) / 6.0)
                .sum::<f64>()
        })
        .sum()
}

/// Checks that caps can close a profile: closed and planar.
fn check_caps(profile: &NurbsCurve) -> Result<(), SweepError> {
    profile_plane(profile).map(|_| ())
}

/// The mesh of [`revolve`]: the profile sampled at
/// [`profile_parameters`] and turned in `segments` equal steps of the angle
/// (each point on its exact circle or helix). A full turn without pitch
/// closes around; otherwise `caps` puts an n-gon on the profile at both
/// ends (closed planar profiles only). Vertices on the axis are shared.
/// Quads throughout, triangles where a quad touches the axis. Inverse:
/// none.
///
/// # Errors
/// As [`revolve`]; [`SweepError::Segments`]; the caps' errors
/// ([`profile_plane`]); [`SweepError::Mesh`] for a profile that crosses
/// itself or the axis so the quads are not manifold.
///
/// Complexity: O(segments × profile segments).
pub fn revolve_mesh(
    profile: &NurbsCurve,
    axis: Axis,
    angle: f64,
    pitch: f64,
    segments: u32,
    profile_segments: u32,
    caps: bool,
) -> Result<HalfEdgeMesh, SweepError> {
    let axis = axis.unit()?;
    check_angle(angle, pitch)?;
    check_segments("segments", segments, 1)?;
    check_segments("profile segments", profile_segments, 1)?;
    let closed_u = full_turn(angle, pitch);
    if closed_u && segments < 3 {
        return Err(SweepError::Segments {
            what: "segments",
            min: 3,
            got: segments,
        });
    }
    let caps = caps && !closed_u;
    if caps {
        check_caps(profile)?;
    }
    let (params, closed_v) = profile_parameters(profile, profile_segments);
    let row = profile.points_at(&params);
    let nu = if closed_u { segments } else { segments + 1 } as usize;
    let nv = row.len();
    let mut points = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        let theta = angle * i as f64 / f64::from(segments);
        for &p in &row {
            points.push(axis.turn(p, theta, pitch * theta / TAU));
        }
    }
    grid_mesh(&points, nu, nv, closed_u, closed_v, caps, false)
}

/// The mesh of [`extrude`]: the profile sampled at
/// [`profile_parameters`] and moved in `segments` equal steps along the
/// vector, with n-gon caps at both ends when `caps` (closed planar
/// profiles only; the capped mesh is closed, genus 0). Inverse: none.
///
/// # Errors
/// As [`extrude`]; [`SweepError::Segments`]; the caps' errors.
///
/// Complexity: O(segments × profile segments).
pub fn extrude_mesh(
    profile: &NurbsCurve,
    vector: DVec3,
    segments: u32,
    profile_segments: u32,
    caps: bool,
) -> Result<HalfEdgeMesh, SweepError> {
    check_vector(vector)?;
    check_segments("segments", segments, 1)?;
    check_segments("profile segments", profile_segments, 1)?;
    if caps {
        check_caps(profile)?;
    }
    let (params, closed_u) = profile_parameters(profile, profile_segments);
    let row = profile.points_at(&params);
    let nv = segments as usize + 1;
    let mut points = vec![DVec3::ZERO; row.len() * nv];
    for (i, &p) in row.iter().enumerate() {
        for j in 0..nv {
            points[i * nv + j] = p + vector * j as f64 / f64::from(segments);
        }
    }
    grid_mesh(&points, row.len(), nv, closed_u, false, false, caps)
}

/// A mesh of a surface made from sections (a sweep or a loft, u along the
/// profile, v across): the surface evaluated at `u_params` (closed around
/// when `closed_u`, the last parameter then left out by the caller) and at
/// `segments` equal steps of its v domain (all the way round when
/// `closed_v`), with n-gon caps over the first and last v when `caps`.
/// Inverse: none.
///
/// # Errors
/// [`SweepError::Segments`]; [`SweepError::Mesh`].
///
/// Complexity: O(segments × u parameters).
pub fn surface_mesh(
    surface: &NurbsSurface,
    u_params: &[f64],
    closed_u: bool,
    segments: u32,
    closed_v: bool,
    caps: bool,
) -> Result<HalfEdgeMesh, SweepError> {
    use super::Surface;
    check_segments("segments", segments, 1)?;
    let (_, (v0, v1)) = surface.domain();
    let count = if closed_v { segments } else { segments + 1 };
    let vs: Vec<f64> = (0..count)
        .map(|j| v0 + (v1 - v0) * f64::from(j) / f64::from(segments))
        .collect();
    let (points, _) = surface.grid(u_params, &vs, false);
    grid_mesh(
        &points,
        u_params.len(),
        vs.len(),
        closed_u,
        closed_v,
        false,
        caps && !closed_v,
    )
}

/// The u parameters at which [`surface_mesh`] samples a sweep or loft of
/// `profile` (its [`profile_parameters`] mapped onto [0, 1] as
/// [`make_compatible`] maps its domain), and whether it is closed.
///
/// Complexity: as [`profile_parameters`].
pub fn compatible_parameters(profile: &NurbsCurve, segments: u32) -> (Vec<f64>, bool) {
    let (params, closed) = profile_parameters(profile, segments);
    let (a, b) = profile.domain();
    (params.iter().map(|t| (t - a) / (b - a)).collect(), closed)
}

/// Checks caps for a sweep or loft mesh: each end section closed and
/// planar.
///
/// # Errors
/// As [`profile_plane`].
///
/// Complexity: as [`profile_plane`], twice.
pub fn check_end_caps(first: &NurbsCurve, last: &NurbsCurve) -> Result<(), SweepError> {
    check_caps(first)?;
    check_caps(last)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surfaces::Surface;

    fn line(a: DVec3, b: DVec3) -> NurbsCurve {
        NurbsCurve::clamped(1, vec![a, b]).unwrap()
    }

    /// The unit-speed-free circle of `radius` about `center` in the plane
    /// with normal `n` (the kernel's XZ circle turned onto it).
    fn circle_in(center: DVec3, radius: f64, n: DVec3) -> NurbsCurve {
        let rot = glam::DQuat::from_rotation_arc(DVec3::Y, n.normalize());
        let m = DMat4::from_rotation_translation(rot, center);
        NurbsCurve::circle(DVec3::ZERO, radius)
            .transformed(&m)
            .unwrap()
    }

    fn grid_samples(s: &NurbsSurface, n: usize) -> Vec<(f64, f64)> {
        let ((u0, u1), (v0, v1)) = s.domain();
        (0..n)
            .flat_map(|i| {
                (0..n).map(move |j| {
                    (
                        u0 + (u1 - u0) * i as f64 / (n - 1) as f64,
                        v0 + (v1 - v0) * j as f64 / (n - 1) as f64,
                    )
                })
            })
            .collect()
    }

    #[test]
    fn a_revolved_circle_is_an_exact_torus() {
        // Minor circle of radius 0.5 centred 2 from the Z axis, in the XZ plane.
        let minor = circle_in(DVec3::new(2.0, 0.0, 0.0), 0.5, DVec3::Y);
        let axis = Axis {
            origin: DVec3::ZERO,
            direction: DVec3::Z,
        };
        let torus = revolve(&minor, axis, TAU, 0.0).unwrap();
        let mut worst: f64 = 0.0;
        for (u, v) in grid_samples(&torus, 100) {
            let p = torus.point(u, v);
            // Distance to the axis circle (radius 2 in the XY plane).
            let rho = p.x.hypot(p.y);
            let d = ((rho - 2.0).powi(2) + p.z * p.z).sqrt();
            worst = worst.max((d - 0.5).abs());
        }
        assert!(worst < 1e-12, "off the torus by {worst}");
        // Four arcs around: 9 control points across u.
        assert_eq!(torus.size(), (9, 9));
    }

    #[test]
    fn revolving_a_segment_makes_an_exact_cone_about_any_axis() {
        let axis = Axis {
            origin: DVec3::new(1.0, 2.0, 3.0),
            direction: DVec3::new(1.0, 1.0, 0.0),
        };
        let d = axis.direction.normalize();
        let apex = axis.origin + d * 2.0;
        let base = axis.origin + d.any_orthonormal_vector() * 1.5;
        let cone = revolve(&line(base, apex), axis, 200f64.to_radians(), 0.0).unwrap();
        // A 200° turn takes three arcs.
        assert_eq!(cone.size().0, 7);
        for (u, v) in grid_samples(&cone, 100) {
            let p = cone.point(u, v);
            let h = (p - axis.origin).dot(d);
            let r = ((p - axis.origin) - d * h).length();
            // Radius falls linearly from 1.5 at h = 0 to 0 at h = 2.
            assert!(
                (r - 1.5 * (1.0 - h / 2.0)).abs() < 1e-12,
                "{p}: r {r} at h {h}"
            );
        }
        // The end of the turn is the segment turned by 200°.
        let ((_, u1), _) = cone.domain();
        let end = cone.point(u1, 0.0);
        let expected = axis.unit().unwrap().turn(base, 200f64.to_radians(), 0.0);
        assert!(end.distance(expected) < 1e-12);
    }

    #[test]
    fn revolve_refuses_a_zero_axis_and_angle_by_name() {
        let l = line(DVec3::X, DVec3::new(1.0, 1.0, 0.0));
        let zero = Axis {
            origin: DVec3::ZERO,
            direction: DVec3::ZERO,
        };
        assert_eq!(
            revolve(&l, zero, 1.0, 0.0).unwrap_err(),
            SweepError::ZeroVector { what: "the axis" }
        );
        let y = Axis {
            origin: DVec3::ZERO,
            direction: DVec3::Y,
        };
        assert!(matches!(
            revolve(&l, y, 0.0, 0.0),
            Err(SweepError::BadAngle { .. })
        ));
        assert!(matches!(
            revolve(&l, y, 7.0, 0.0),
            Err(SweepError::BadAngle { .. })
        ));
        // With a pitch, two turns are a screw.
        assert!(revolve(&l, y, 2.0 * TAU, 1.0).is_ok());
    }

    #[test]
    fn a_screw_rises_by_its_pitch_per_turn_and_stays_near_the_helix() {
        let l = line(DVec3::new(1.0, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0));
        let y = Axis {
            origin: DVec3::ZERO,
            direction: DVec3::Y,
        };
        let s = revolve(&l, y, 2.0 * TAU, 0.5).unwrap();
        let ((u0, u1), _) = s.domain();
        let mut worst: f64 = 0.0;
        for k in 0..=1000 {
            let u = u0 + (u1 - u0) * k as f64 / 1000.0;
            let p = s.point(u, 0.0);
            // On the cylinder of radius 1 exactly; the rise follows the angle.
            assert!((p.x.hypot(p.z) - 1.0).abs() < 1e-12);
            let turned = (-p.z).atan2(p.x).rem_euclid(TAU);
            let e = (p.y - 0.5 * turned / TAU) / 0.5;
            worst = worst.max((e - e.round()).abs() * 0.5);
        }
        assert!(worst < 6.5e-4 * 0.5, "{worst}");
        assert!((s.point(u1, 0.0).y - 1.0).abs() < 1e-12);
    }

    #[test]
    fn an_extruded_circle_is_an_exact_cylinder() {
        let c = circle_in(DVec3::ZERO, 1.25, DVec3::Z);
        let cyl = extrude(&c, DVec3::new(0.0, 0.0, 3.0)).unwrap();
        for (u, v) in grid_samples(&cyl, 100) {
            let p = cyl.point(u, v);
            assert!((p.x.hypot(p.y) - 1.25).abs() < 1e-12);
            assert!((p.z - 3.0 * v).abs() < 1e-12);
        }
        assert_eq!(
            extrude(&c, DVec3::ZERO).unwrap_err(),
            SweepError::ZeroVector {
                what: "the extrusion vector"
            }
        );
    }

    #[test]
    fn a_capped_extrusion_is_a_closed_genus_0_mesh() {
        let c = circle_in(DVec3::ZERO, 1.0, DVec3::Y);
        let m = extrude_mesh(&c, DVec3::Y * 2.0, 3, 16, true).unwrap();
        m.validate().unwrap();
        let stats = m.stats();
        assert!(stats.closed);
        assert_eq!(stats.genus, Some(0));
        // 16 around × 4 rings; 16 × 3 quads + 2 caps.
        assert_eq!((m.vertex_count(), m.face_count()), (64, 50));
        // Outwards: positive volume near π r² h.
        let (pos, polys) = m.to_polygons();
        let polys: Vec<Vec<u32>> = polys;
        let vol = signed_volume(&pos, &polys);
        // The prism over the sampled 16-gon (XZ plane) of height 2.
        let (params, _) = profile_parameters(&c, 16);
        let ring = c.points_at(&params);
        let area: f64 = (0..16)
            .map(|k| {
                let (a, b) = (ring[k], ring[(k + 1) % 16]);
                (a.z * b.x - a.x * b.z) / 2.0
            })
            .sum();
        let prism = area.abs() * 2.0;
        assert!((vol - prism).abs() < 1e-12, "{vol}");
    }

    #[test]
    fn caps_refuse_open_and_non_planar_profiles_by_name() {
        let open =
            NurbsCurve::clamped(2, vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 0.0, 1.0)]).unwrap();
        assert!(matches!(
            extrude_mesh(&open, DVec3::Y, 1, 8, true),
            Err(SweepError::OpenProfile { .. })
        ));
        let bent = NurbsCurve::periodic(
            1,
            vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 0.5, 1.0), DVec3::Z],
            vec![1.0; 4],
        )
        .unwrap();
        let err = extrude_mesh(&bent, DVec3::Y, 1, 8, true).unwrap_err();
        assert!(matches!(err, SweepError::NotPlanar { .. }), "{err}");
        assert!(err.to_string().starts_with("caps need a planar profile"));
        // Without caps both are fine.
        extrude_mesh(&open, DVec3::Y, 1, 8, false)
            .unwrap()
            .validate()
            .unwrap();
    }

    #[test]
    fn a_capped_partial_revolution_is_genus_0_and_a_full_one_a_torus() {
        let minor = circle_in(DVec3::new(2.0, 0.0, 0.0), 0.5, DVec3::Z);
        let y = Axis {
            origin: DVec3::ZERO,
            direction: DVec3::Y,
        };
        let part = revolve_mesh(&minor, y, 270f64.to_radians(), 0.0, 12, 16, true).unwrap();
        part.validate().unwrap();
        let s = part.stats();
        assert!(s.closed);
        assert_eq!(s.genus, Some(0));
        assert_eq!(part.face_count(), 12 * 16 + 2);
        let full = revolve_mesh(&minor, y, TAU, 0.0, 24, 16, true).unwrap();
        full.validate().unwrap();
        assert_eq!(full.stats().genus, Some(1));
        assert_eq!(full.vertex_count(), 24 * 16);
        // Every vertex lies on the torus.
        for v in full.vertices() {
            let p = full.position(v);
            let d = ((p.x.hypot(p.z) - 2.0).powi(2) + p.y * p.y).sqrt();
            assert!((d - 0.5).abs() < 1e-12, "{p}");
        }
    }

    #[test]
    fn a_half_circle_revolved_shares_its_poles() {
        let half = NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
            vec![
                DVec3::new(0.0, -1.0, 0.0),
                DVec3::new(1.0, -1.0, 0.0),
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(0.0, 1.0, 0.0),
            ],
            vec![
                1.0,
                std::f64::consts::FRAC_1_SQRT_2,
                1.0,
                std::f64::consts::FRAC_1_SQRT_2,
                1.0,
            ],
        )
        .unwrap();
        let y = Axis {
            origin: DVec3::ZERO,
            direction: DVec3::Y,
        };
        let ball = revolve_mesh(&half, y, TAU, 0.0, 16, 8, false).unwrap();
        ball.validate().unwrap();
        let s = ball.stats();
        assert!(s.closed);
        assert_eq!(s.genus, Some(0));
        // 7 rings of 16 plus two poles; triangle fans at the poles.
        assert_eq!(ball.vertex_count(), 7 * 16 + 2);
        assert_eq!(ball.face_count(), 8 * 16);
    }

    /// A helix of radius `r` about Z rising `h` per turn, `turns` turns, as
    /// a cubic B-spline through many points (close to the helix).
    fn helix(r: f64, h: f64, turns: f64) -> NurbsCurve {
        let n = 200;
        let pts: Vec<DVec3> = (0..=n)
            .map(|k| {
                let t = turns * TAU * k as f64 / n as f64;
                DVec3::new(r * t.cos(), r * t.sin(), h * t / TAU)
            })
            .collect();
        NurbsCurve::clamped(3, pts).unwrap()
    }

    #[test]
    fn a_circle_swept_along_a_helix_stays_perpendicular_to_it() {
        let rail = helix(3.0, 2.0, 1.5);
        let (a, _) = rail.domain();
        let [p0, d0, _] = rail.derivatives(a);
        let profile = circle_in(p0, 0.4, d0);
        for kind in [FrameKind::RotationMinimizing, FrameKind::Frenet] {
            let options = SweepOptions {
                frame: kind,
                sections: 40,
            };
            let sections = sweep_sections(&profile, &rail, options).unwrap();
            let tube = sweep(&profile, &rail, options).unwrap();
            let params = loft_section_parameters(
                &sections,
                LoftOptions {
                    closed: false,
                    tightness: Tightness::Normal,
                },
            );
            let (r0, r1) = rail.domain();
            for (k, &v) in params.iter().enumerate() {
                let t = r0 + (r1 - r0) * k as f64 / 39.0;
                let [centre, tangent, _] = rail.derivatives(t);
                let tangent = tangent.normalize();
                for i in 0..50 {
                    let p = tube.point(i as f64 / 49.0, v);
                    // In the normal plane, at the profile's radius.
                    assert!((p - centre).dot(tangent).abs() < 1e-9, "{kind:?} {k}");
                    assert!(((p - centre).length() - 0.4).abs() < 1e-9);
                }
            }
            // Between stations the tube stays close to round.
            let mut worst: f64 = 0.0;
            for k in 0..39 {
                let v = (params[k] + params[k + 1]) / 2.0;
                let t = r0 + (r1 - r0) * (k as f64 + 0.5) / 39.0;
                let centre = rail.point(t);
                for i in 0..20 {
                    let p = tube.point(i as f64 / 19.0, v);
                    worst = worst.max(((p - centre).length() - 0.4).abs());
                }
            }
            assert!(worst < 0.01, "{kind:?}: {worst}");
        }
    }

    /// A smooth closed rail that is not planar (a saddle-shaped loop, a
    /// periodic cubic B-spline), along which the plain double reflection
    /// comes back twisted.
    fn saddle_loop() -> NurbsCurve {
        let pts: Vec<DVec3> = (0..12)
            .map(|k| {
                let t = TAU * k as f64 / 12.0;
                DVec3::new(3.0 * t.cos(), 2.0 * t.sin(), 1.5 * (2.0 * t).sin())
            })
            .collect();
        NurbsCurve::periodic(3, pts, vec![1.0; 12]).unwrap()
    }

    #[test]
    fn the_rotation_minimising_frame_closes_up_on_a_closed_rail() {
        let rail = saddle_loop();
        assert!(is_smoothly_closed(&rail));
        let (a, b) = rail.domain();
        let params: Vec<f64> = (0..=60).map(|k| a + (b - a) * k as f64 / 60.0).collect();
        let frames = rail_frames(&rail, &params, FrameKind::RotationMinimizing).unwrap();
        let (first, last) = (frames[0], frames[60]);
        assert!(
            first.normal.distance(last.normal) < 1e-9,
            "{first:?} {last:?}"
        );
        // Still a frame: orthonormal, normal across the tangent.
        for f in &frames {
            assert!(f.normal.dot(f.tangent).abs() < 1e-12);
            assert!((f.normal.length() - 1.0).abs() < 1e-12);
        }
        // And the correction is needed: an open piece of the same loop
        // (not the whole of it) is not corrected, and its frame at the
        // seam differs from the start by the holonomy angle.
        let part: Vec<f64> = params[..60].to_vec();
        let open = rail_frames(&rail, &part, FrameKind::RotationMinimizing).unwrap();
        let twist = open[59].normal.angle_between(frames[59].normal);
        assert!(twist > 1e-3, "the saddle loop has holonomy: {twist}");
    }

    #[test]
    fn a_sweep_around_a_closed_rail_is_closed_and_seamless() {
        let rail = saddle_loop();
        let (a, _) = rail.domain();
        let [p0, d0, _] = rail.derivatives(a);
        let profile = circle_in(p0, 0.3, d0);
        let options = SweepOptions {
            frame: FrameKind::RotationMinimizing,
            sections: 30,
        };
        let tube = sweep(&profile, &rail, options).unwrap();
        assert!(is_closed_in_v(&tube));
        let (_, (v0, v1)) = tube.domain();
        for i in 0..=20 {
            let u = i as f64 / 20.0;
            assert!(tube.point(u, v0).distance(tube.point(u, v1)) < 1e-9);
        }
        // As a mesh it is a closed torus-like tube, genus 1, no caps.
        let (us, closed_u) = compatible_parameters(&profile, 16);
        let mesh = surface_mesh(&tube, &us, closed_u, 30, true, false).unwrap();
        mesh.validate().unwrap();
        let stats = mesh.stats();
        assert!(stats.closed);
        assert_eq!(stats.genus, Some(1));
    }

    #[test]
    fn the_frenet_frame_flips_at_an_inflection_and_the_rmf_does_not() {
        // An S in the XY plane, rising a little in Z so the Frenet frame
        // exists everywhere: its curvature changes sign once, in the middle.
        let pts: Vec<DVec3> = (0..=40)
            .map(|k| {
                let t = k as f64 / 40.0;
                DVec3::new(4.0 * t, (TAU * t).sin(), 0.0)
            })
            .collect();
        let rail = NurbsCurve::clamped(3, pts).unwrap();
        let (a, b) = rail.domain();
        // Stations that avoid the inflection at the middle itself.
        let params: Vec<f64> = (0..=20)
            .map(|k| a + (b - a) * (k as f64 + 0.25) / 20.5)
            .collect();
        let frenet = rail_frames(&rail, &params, FrameKind::Frenet).unwrap();
        let rmf = rail_frames(&rail, &params, FrameKind::RotationMinimizing).unwrap();
        let flips = frame_flips(&frenet);
        assert_eq!(flips.len(), 1, "{flips:?}");
        let middle = rail.point(params[flips[0]]).x;
        assert!(
            (middle - 2.0).abs() < 0.3,
            "the flip is at the inflection: {middle}"
        );
        assert!(frame_flips(&rmf).is_empty());
    }

    #[test]
    fn the_rotation_minimising_frame_does_not_twist_on_a_plane_curve() {
        // On a planar rail the RMF's normal keeps its angle to the plane.
        let rail = NurbsCurve::circle(DVec3::ZERO, 2.0);
        let params: Vec<f64> = (0..=20).map(|k| k as f64 / 40.0).collect();
        let frames = rail_frames(&rail, &params, FrameKind::RotationMinimizing).unwrap();
        let first = frames[0].normal.dot(DVec3::Y);
        for f in &frames {
            assert!((f.normal.dot(DVec3::Y) - first).abs() < 1e-6);
            assert!(f.normal.dot(f.tangent).abs() < 1e-12);
        }
        // A straight rail has no Frenet frame.
        let straight = line(DVec3::ZERO, DVec3::X);
        assert!(matches!(
            rail_frames(&straight, &[0.0, 1.0], FrameKind::Frenet),
            Err(SweepError::NoFrenetFrame { .. })
        ));
    }

    #[test]
    fn a_two_rail_sweep_keeps_the_profile_ends_on_both_rails() {
        let r1 = NurbsCurve::clamped(
            2,
            vec![
                DVec3::ZERO,
                DVec3::new(0.0, 0.5, 2.0),
                DVec3::new(0.0, 0.0, 4.0),
            ],
        )
        .unwrap();
        let r2 = NurbsCurve::clamped(
            2,
            vec![
                DVec3::X,
                DVec3::new(2.0, 0.0, 2.0),
                DVec3::new(1.5, 0.0, 4.0),
            ],
        )
        .unwrap();
        let profile =
            NurbsCurve::clamped(2, vec![DVec3::ZERO, DVec3::new(0.5, 0.6, 0.0), DVec3::X]).unwrap();
        let s = sweep2(&profile, [&r1, &r2], 12).unwrap();
        // The surface's u = 0 and u = 1 edges pass through the rails at the stations.
        let sections = sweep2_sections(&profile, [&r1, &r2], 12).unwrap();
        for (k, c) in sections.iter().enumerate() {
            let t = k as f64 / 11.0;
            let (a, b) = c.domain();
            assert!(c.point(a).distance(r1.point(t)) < 1e-12);
            assert!(c.point(b).distance(r2.point(t)) < 1e-12);
        }
        let params = loft_section_parameters(&sections, LoftOptions::default());
        for (k, &v) in params.iter().enumerate() {
            let t = k as f64 / 11.0;
            assert!(s.point(0.0, v).distance(r1.point(t)) < 1e-9);
            assert!(s.point(1.0, v).distance(r2.point(t)) < 1e-9);
        }
    }

    fn sections() -> Vec<NurbsCurve> {
        vec![
            circle_in(DVec3::ZERO, 1.0, DVec3::Y),
            // A square polyline (degree 1) around the axis.
            NurbsCurve::periodic(
                1,
                vec![
                    DVec3::new(1.0, 1.0, 0.0),
                    DVec3::new(0.0, 1.0, 1.0),
                    DVec3::new(-1.0, 1.0, 0.0),
                    DVec3::new(0.0, 1.0, -1.0),
                ],
                vec![1.0; 4],
            )
            .unwrap(),
            circle_in(DVec3::new(0.0, 2.5, 0.0), 0.5, DVec3::Y),
            circle_in(DVec3::new(0.3, 3.5, 0.0), 1.2, DVec3::Y),
        ]
    }

    #[test]
    fn make_compatible_keeps_every_curve_and_shares_knots() {
        let input = sections();
        let out = make_compatible(&input).unwrap();
        for (c, d) in input.iter().zip(&out) {
            assert_eq!(d.knots(), out[0].knots());
            assert_eq!(d.degree(), 2);
            let (a, b) = c.domain();
            for k in 0..=50 {
                let s = k as f64 / 50.0;
                assert!(c.point(a + (b - a) * s).distance(d.point(s)) < 1e-12);
            }
        }
    }

    #[test]
    fn a_loft_passes_through_each_section() {
        let input = sections();
        for tightness in [Tightness::Straight, Tightness::Normal] {
            for closed in [false, true] {
                let options = LoftOptions { closed, tightness };
                let s = loft(&input, options).unwrap();
                let params = loft_section_parameters(&input, options);
                assert_eq!(params.len(), 4);
                for (c, &v) in input.iter().zip(&params) {
                    let (a, b) = c.domain();
                    for k in 0..=100 {
                        let u = k as f64 / 100.0;
                        let want = c.point(a + (b - a) * u);
                        let got = s.point(u, v);
                        assert!(
                            got.distance(want) < 1e-9,
                            "{tightness:?} closed {closed}: {got} vs {want}"
                        );
                    }
                }
            }
        }
        // Loose passes through the ends only, and refuses a single section.
        let loose = loft(
            &input,
            LoftOptions {
                closed: false,
                tightness: Tightness::Loose,
            },
        )
        .unwrap();
        assert!(loose.point(0.0, 0.0).distance(input[0].point(0.0)) < 1e-12);
        assert!(loose.point(0.0, 1.0).distance(input[3].point(0.0)) < 1e-12);
        assert_eq!(
            loft(&input[..1], LoftOptions::default()).unwrap_err(),
            SweepError::TooFewSections {
                what: "a loft",
                needed: 2,
                got: 1
            }
        );
    }

    #[test]
    fn a_planar_cap_of_a_circle_is_its_disc() {
        let c = circle_in(DVec3::new(1.0, 2.0, 3.0), 2.0, DVec3::new(0.0, 1.0, 1.0));
        let cap = planar_cap(&c).unwrap();
        let n = DVec3::new(0.0, 1.0, 1.0).normalize();
        for (u, v) in grid_samples(&cap, 30) {
            let p = cap.point(u, v);
            let rel = p - DVec3::new(1.0, 2.0, 3.0);
            assert!(rel.dot(n).abs() < 1e-12);
            assert!((rel.length() - 2.0 * (1.0 - v)).abs() < 1e-9, "{u} {v}");
        }
    }

    #[test]
    fn nurbs_end_caps_close_an_extrusion_and_a_partial_revolution_facing_out() {
        let circle = circle_in(DVec3::new(2.0, 0.0, 0.0), 0.5, DVec3::Z);
        let tube = extrude(&circle, DVec3::new(0.0, 0.0, 3.0)).unwrap();
        let caps = end_caps(&tube, Along::V).unwrap();
        assert_eq!(caps.len(), 2);
        for (cap, z, outward) in [(&caps[0], 0.0, -DVec3::Z), (&caps[1], 3.0, DVec3::Z)] {
            for (u, v) in grid_samples(cap, 10) {
                let p = cap.point(u, v);
                assert!((p.z - z).abs() < 1e-12);
                assert!(p.distance(DVec3::new(2.0, 0.0, z)) <= 0.5 + 1e-9);
                let n = cap.evaluate(u, v.min(0.9)).normal();
                assert!(n.dot(outward) > 0.999, "{n}");
            }
            // The rim is the tube's end circle.
            let ((a, b), (v0, _)) = cap.domain();
            for k in 0..=16 {
                let p = cap.point(a + (b - a) * k as f64 / 16.0, v0);
                assert!((p.distance(DVec3::new(2.0, 0.0, z)) - 0.5).abs() < 1e-9);
            }
        }
        // A partial revolution of the same circle about Y gets its two
        // end discs; a full one (a torus) none.
        let axis = Axis {
            origin: DVec3::ZERO,
            direction: DVec3::Y,
        };
        let part = revolve(&circle, axis, 1.5, 0.0).unwrap();
        assert_eq!(end_caps(&part, Along::U).unwrap().len(), 2);
        let torus = revolve(&circle, axis, TAU, 0.0).unwrap();
        assert!(end_caps(&torus, Along::U).unwrap().is_empty());
        // An open profile cannot be capped.
        let arc =
            NurbsCurve::clamped(2, vec![DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y]).unwrap();
        let sheet = extrude(&arc, DVec3::Z).unwrap();
        assert!(matches!(
            end_caps(&sheet, Along::V),
            Err(SweepError::OpenProfile { .. })
        ));
    }

    #[test]
    fn a_nurbs_cap_refuses_a_profile_its_centre_does_not_see() {
        // A C-shaped closed polygon: its centroid lies outside the notch's
        // view of part of the outline.
        let pts = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(4.0, 0.0, 0.0),
            DVec3::new(4.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(1.0, 3.0, 0.0),
            DVec3::new(4.0, 3.0, 0.0),
            DVec3::new(4.0, 4.0, 0.0),
            DVec3::new(0.0, 4.0, 0.0),
            DVec3::new(0.0, 0.0, 0.0),
        ];
        let c = NurbsCurve::clamped(1, pts).unwrap();
        assert_eq!(planar_cap(&c), Err(SweepError::NotStarShaped));
    }

    #[test]
    fn a_swept_and_lofted_mesh_validates_with_caps() {
        let rail = helix(3.0, 2.0, 0.75);
        let (a, _) = rail.domain();
        let [p0, d0, _] = rail.derivatives(a);
        let profile = circle_in(p0, 0.4, d0);
        let s = sweep(&profile, &rail, SweepOptions::default()).unwrap();
        let (us, closed) = compatible_parameters(&profile, 12);
        assert!(closed);
        let m = surface_mesh(&s, &us, closed, 20, false, true).unwrap();
        m.validate().unwrap();
        assert!(m.stats().closed);
        assert_eq!(m.stats().genus, Some(0));
        assert_eq!(m.face_count(), 12 * 20 + 2);
        let l = loft(
            &sections(),
            LoftOptions {
                closed: true,
                tightness: Tightness::Normal,
            },
        )
        .unwrap();
        let (us, _) = compatible_parameters(&sections()[0], 16);
        let torus = surface_mesh(&l, &us, true, 24, true, false).unwrap();
        torus.validate().unwrap();
        assert_eq!(torus.stats().genus, Some(1));
    }
}
