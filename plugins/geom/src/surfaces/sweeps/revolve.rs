//! Revolution about an axis: the exact rational circle construction
//! (Piegl & Tiller A8.1), with an optional pitch for a screw.

use super::SweepError;
use crate::curves::NurbsCurve;
use crate::surfaces::NurbsSurface;
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, TAU};

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
    pub(super) fn unit(self) -> Result<Axis, SweepError> {
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
    pub(super) fn turn(&self, p: DVec3, angle: f64, rise: f64) -> DVec3 {
        let d = self.direction;
        let o = self.origin + d * (p - self.origin).dot(d);
        let x = p - o;
        let y = d.cross(x);
        o + x * angle.cos() + y * angle.sin() + d * rise
    }
}

/// The checked angle of a revolution: not zero, finite, within one turn
/// either way unless there is a pitch.
pub(super) fn check_angle(angle: f64, pitch: f64) -> Result<(), SweepError> {
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
pub(super) fn full_turn(angle: f64, pitch: f64) -> bool {
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
