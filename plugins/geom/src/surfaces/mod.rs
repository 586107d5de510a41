//! Free-form surfaces: the bilinear patch, tensor-product Bézier and NURBS
//! surfaces (with the usual constructors: plane, sphere, cylinder,
//! revolution and extrusion of a curve), surfaces from curves (revolve
//! about any axis, extrude, sweep, loft: [`sweeps`]), Bézier triangles, ray
//! intersection for picking, fast grid evaluation of NURBS surfaces and
//! tessellation; patches made from curves (Coons, Gordon) and the
//! triangle–quad G1 join ([`patches`]).
//!
//! Every surface evaluates its point and first and second partial
//! derivatives through [`Surface`]; intersection and tessellation use only
//! that.

pub mod bezier;
pub mod fast;
pub mod intersect;
pub mod joins;
pub mod nurbs;
pub mod patches;
pub mod sweeps;
pub mod tessellate;
pub mod triangle;

use glam::DVec3;

pub use bezier::{BezierSurface, BilinearPatch};
pub use nurbs::NurbsSurface;
pub use triangle::BezierTriangle;

/// A point of a surface with its partial derivatives.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct SurfacePoint {
    /// The point `S(u, v)`.
    pub p: DVec3,
    /// First partial derivative `S_u`.
    pub du: DVec3,
    /// First partial derivative `S_v`.
    pub dv: DVec3,
    /// Second partial derivative `S_uu`.
    pub duu: DVec3,
    /// Mixed partial derivative `S_uv`.
    pub duv: DVec3,
    /// Second partial derivative `S_vv`.
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
    /// The point at `(u, v)`.
    fn point(&self, u: f64, v: f64) -> DVec3 {
        self.evaluate(u, v).p
    }
    /// The parameters where the surface's patches meet, in u and in v, with
    /// the domain's ends: increasing, distinct. Between two neighbours in
    /// each direction the surface is one smooth (rational) polynomial
    /// patch; along them it may fold. Tessellation keeps every one as a
    /// grid line ([`tessellate::surface_parameters`]). The default is one
    /// patch: the domain's ends.
    fn breakpoints(&self) -> (Vec<f64>, Vec<f64>) {
        let ((u0, u1), (v0, v1)) = self.domain();
        (vec![u0, u1], vec![v0, v1])
    }
    /// The points at every `(u, v)` of `us × vs`, row-major by u (point
    /// `(i, j)` at `i * vs.len() + j`). The default evaluates each; a NURBS
    /// surface shares the basis work along rows and columns.
    fn grid_points(&self, us: &[f64], vs: &[f64]) -> Vec<DVec3> {
        us.iter()
            .flat_map(|&u| vs.iter().map(move |&v| self.point(u, v)))
            .collect()
    }
    /// `S_u × S_v` normalised at `(u, v)`; zero where the derivatives are
    /// parallel (see [`unit_normal`](Self::unit_normal) for poles).
    fn normal(&self, u: f64, v: f64) -> DVec3 {
        self.evaluate(u, v).normal()
    }
    /// The unit normal at `(u, v)`, also where the partial derivatives are
    /// parallel or zero (a pole, a collapsed edge): there the limit of the
    /// normals around it, see [`limit_normal`]. Zero only on a surface that
    /// is degenerate all around the point.
    fn unit_normal(&self, u: f64, v: f64) -> DVec3 {
        let n = self.normal(u, v);
        if n != DVec3::ZERO {
            return n;
        }
        limit_normal(self, u, v)
    }
}

/// The normal of a surface where its partial derivatives are parallel or
/// zero, as the limit of the normals next to the point: the normals at
/// steps of 1e-6 of the domain into it, diagonally (the sphere's poles give
/// the pole's direction, as openNURBS does).
pub fn limit_normal<S: Surface + ?Sized>(surface: &S, u: f64, v: f64) -> DVec3 {
    let ((u0, u1), (v0, v1)) = surface.domain();
    let (du, dv) = ((u1 - u0) * 1e-6, (v1 - v0) * 1e-6);
    let mut sum = DVec3::ZERO;
    for (su, sv) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
        let (a, b) = (u + su * du, v + sv * dv);
        if (u0..=u1).contains(&a) && (v0..=v1).contains(&b) {
            sum += surface.normal(a, b);
        }
    }
    sum.normalize_or_zero()
}
