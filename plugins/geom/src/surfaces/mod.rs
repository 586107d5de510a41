//! Free-form surfaces: the bilinear patch, tensor-product Bézier and NURBS
//! surfaces (with the usual constructors: plane, sphere, cylinder,
//! revolution and extrusion of a curve), Bézier triangles, ray intersection
//! for picking and tessellation.
//!
//! Every surface evaluates its point and first and second partial
//! derivatives through [`Surface`]; intersection and tessellation use only
//! that.

pub mod bezier;
pub mod intersect;
pub mod joins;
pub mod nurbs;
pub mod tessellate;
pub mod triangle;

use glam::DVec3;

pub use bezier::{BezierSurface, BilinearPatch};
pub use nurbs::NurbsSurface;
pub use triangle::BezierTriangle;

/// A point of a surface with its partial derivatives.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct SurfacePoint {
    pub p: DVec3,
    pub du: DVec3,
    pub dv: DVec3,
    pub duu: DVec3,
    pub duv: DVec3,
    pub dvv: DVec3,
}

impl SurfacePoint {
    /// The unit normal `S_u × S_v / |S_u × S_v|` (zero where degenerate).
    pub fn normal(&self) -> DVec3 {
        self.du.cross(self.dv).normalize_or_zero()
    }
}

/// A parametric surface on a rectangle of parameters.
pub trait Surface {
    /// `((u_start, u_end), (v_start, v_end))`.
    fn domain(&self) -> ((f64, f64), (f64, f64));
    /// Point and partial derivatives at `(u, v)` (clamped to the domain).
    fn evaluate(&self, u: f64, v: f64) -> SurfacePoint;
    fn point(&self, u: f64, v: f64) -> DVec3 {
        self.evaluate(u, v).p
    }
    fn normal(&self, u: f64, v: f64) -> DVec3 {
        self.evaluate(u, v).normal()
    }
}
