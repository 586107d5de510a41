//! Surfaces from curves (seed 004's 2.5D modeling, Rhino's ExtrudeCrv,
//! Revolve, Sweep1, Sweep2 and Loft, Blender's Spin and Screw): each as an
//! exact or stated-accuracy NURBS surface, and as a polygon mesh of quads
//! with n-gon caps built through
//! [`HalfEdgeMesh::from_polygons`](crate::mesh::HalfEdgeMesh::from_polygons).
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

use crate::build::BuildError;
use crate::curves::{Curve, CurveError, NurbsCurve};
use glam::DVec3;

mod caps;
mod extrude;
mod frames;
mod loft;
mod meshes;
mod revolve;
mod sweep;

pub use caps::{Along, check_end_caps, end_caps, planar_cap, profile_plane};
pub use extrude::extrude;
pub use frames::{Frame, FrameKind, frame_flips, is_smoothly_closed, rail_frames};
pub use loft::{LoftOptions, Tightness, loft, loft_section_parameters, make_compatible};
pub use meshes::{compatible_parameters, extrude_mesh, grid_mesh, revolve_mesh, surface_mesh};
pub use revolve::{Axis, revolve};
pub use sweep::{
    SweepOptions, is_closed_in_v, stations, sweep, sweep_sections, sweep2, sweep2_sections,
};

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
