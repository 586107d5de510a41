//! The frames a profile rides along a rail: rotation-minimising
//! (double reflection, Wang et al. 2008) or Frenet.

use super::{SweepError, is_closed};
use crate::curves::{Curve, NurbsCurve};
use glam::{DMat4, DQuat, DVec3};

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
