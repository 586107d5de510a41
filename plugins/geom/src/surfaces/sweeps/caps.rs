//! Caps: the flat disc a closed planar profile bounds, and the caps
//! that close a surface's open ends.

use super::loft::{clamped_knots, skin_rows};
use super::sweep::{is_closed_in_v, same_curve};
use super::{SweepError, end_gap, size_of};
use crate::curves::{Curve, NurbsCurve};
use crate::surfaces::{NurbsSurface, Surface};
use glam::DVec3;

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
    /// Along u: a [`revolve`](super::revolve)'s turn.
    U,
    /// Along v: an [`extrude`](super::extrude), [`sweep`](super::sweep),
    /// [`sweep2`](super::sweep2) or [`loft`](super::loft).
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

/// Checks that caps can close a profile: closed and planar.
pub(super) fn check_caps(profile: &NurbsCurve) -> Result<(), SweepError> {
    profile_plane(profile).map(|_| ())
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
