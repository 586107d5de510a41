//! Sweeps: a profile carried along one rail ([`sweep`]) or two
//! ([`sweep2`]), then skinned through the placed copies.

use super::frames::{FrameKind, is_smoothly_closed, rail_frames};
use super::loft::{LoftOptions, Tightness, loft};
use super::{SweepError, check_segments, size_of};
use crate::curves::{Curve, NurbsCurve};
use crate::surfaces::NurbsSurface;
use glam::DMat4;

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
pub(super) fn same_curve(a: &NurbsCurve, b: &NurbsCurve) -> bool {
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
