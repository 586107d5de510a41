//! Extrusion: a curve moved along a vector (degree 1 across).

use super::SweepError;
use crate::curves::NurbsCurve;
use crate::surfaces::NurbsSurface;
use glam::DVec3;

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

pub(super) fn check_vector(vector: DVec3) -> Result<(), SweepError> {
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
