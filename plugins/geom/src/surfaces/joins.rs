//! How two patches meet along a shared boundary (seed 002: C0 and G1 joins
//! of Bézier patches, and its exercise joining a Bézier triangle to a
//! quadrilateral patch with G1 continuity). Each side is sampled along its
//! boundary; C0 needs equal points, G1 also parallel normals (the tangent
//! planes agree), which is the condition the exercise asks to hold.

use glam::DVec3;

use super::{BezierTriangle, Surface};

/// A boundary of a patch, as a function of `s` in [0, 1].
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Boundary {
    /// Rectangular patches: the side `u = u_start`.
    U0,
    /// The side `u = u_end`.
    U1,
    /// The side `v = v_start`.
    V0,
    /// The side `v = v_end`.
    V1,
    /// Triangles: the edge `u = 0`, opposite the corner u = 1.
    TriangleU0,
    /// The triangle edge `v = 0`, opposite the corner v = 1.
    TriangleV0,
    /// The triangle edge `w = 0`, opposite the corner w = 1.
    TriangleW0,
}

/// Point and unit normal of a rectangular patch along a boundary
/// (`reversed` walks it from the other end).
pub fn surface_boundary(s: &dyn Surface, b: Boundary, reversed: bool, t: f64) -> (DVec3, DVec3) {
    let ((u0, u1), (v0, v1)) = s.domain();
    let t = if reversed { 1.0 - t } else { t };
    let (u, v) = match b {
        Boundary::U0 => (u0, v0 + (v1 - v0) * t),
        Boundary::U1 => (u1, v0 + (v1 - v0) * t),
        Boundary::V0 => (u0 + (u1 - u0) * t, v0),
        _ => (u0 + (u1 - u0) * t, v1),
    };
    let e = s.evaluate(u, v);
    (e.p, e.normal())
}

/// Point and unit normal of a Bézier triangle along an edge.
pub fn triangle_boundary(
    tri: &BezierTriangle,
    b: Boundary,
    reversed: bool,
    t: f64,
) -> (DVec3, DVec3) {
    let t = if reversed { 1.0 - t } else { t };
    let bary = match b {
        Boundary::TriangleU0 => DVec3::new(0.0, t, 1.0 - t),
        Boundary::TriangleV0 => DVec3::new(t, 0.0, 1.0 - t),
        _ => DVec3::new(t, 1.0 - t, 0.0),
    };
    let du = tri.directional_derivative(bary, DVec3::new(1.0, 0.0, -1.0));
    let dv = tri.directional_derivative(bary, DVec3::new(0.0, 1.0, -1.0));
    (tri.evaluate(bary), du.cross(dv).normalize_or_zero())
}

/// The continuity of a join, from samples of both sides.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct Join {
    /// The boundaries coincide.
    pub c0: bool,
    /// The tangent planes agree all along (normals parallel).
    pub g1: bool,
}

/// Compares two boundaries at `samples + 1` points each. Normals may point
/// either way (the patches may be oriented oppositely); G1 needs them
/// parallel within `angle_tolerance` radians.
pub fn join(
    a: impl Fn(f64) -> (DVec3, DVec3),
    b: impl Fn(f64) -> (DVec3, DVec3),
    samples: usize,
    distance_tolerance: f64,
    angle_tolerance: f64,
) -> Join {
    let mut c0 = true;
    let mut g1 = true;
    for k in 0..=samples.max(1) {
        let t = k as f64 / samples.max(1) as f64;
        let ((pa, na), (pb, nb)) = (a(t), b(t));
        c0 &= pa.distance(pb) <= distance_tolerance;
        let cos = na.dot(nb).abs();
        g1 &= na != DVec3::ZERO && nb != DVec3::ZERO && cos >= angle_tolerance.cos();
    }
    Join { c0, g1: c0 && g1 }
}
