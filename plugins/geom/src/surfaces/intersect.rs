//! Ray-surface intersection for picking (seed 003): a coarse tessellation
//! gives a first guess, then Newton's method on `S(u, v) − (o + t d) = 0`
//! with the Jacobian `[S_u, S_v, −d]` refines it to the exact surface.

use glam::{DMat3, DVec3};

use super::Surface;
use super::tessellate::grid;

/// Where a ray meets a surface.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct RayHit {
    /// Surface parameter u of the hit.
    pub u: f64,
    /// Surface parameter v of the hit.
    pub v: f64,
    /// Ray parameter of the hit (`origin + t·dir`), in units of `dir`'s
    /// length.
    pub t: f64,
    /// The surface point `S(u, v)`.
    pub point: DVec3,
}

/// The nearest intersection of the ray `origin + t·dir` (t ≥ 0) with the
/// surface, or `None`. `dir` need not be unit length; `t` is in units of it.
pub fn ray_surface(surface: &dyn Surface, origin: DVec3, dir: DVec3) -> Option<RayHit> {
    let mesh = grid(surface, 32, 32);
    let mut best: Option<(f64, (f64, f64))> = None;
    for tri in &mesh.triangles {
        let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
        if let Some(t) = crate::query::ray_triangle(origin, dir, a, b, c)
            && best.is_none_or(|(bt, _)| t < bt)
        {
            // The first guess: the parameters of the triangle's centroid.
            let uv = tri.map(|i| mesh.params[i as usize]);
            let guess = (
                (uv[0].0 + uv[1].0 + uv[2].0) / 3.0,
                (uv[0].1 + uv[1].1 + uv[2].1) / 3.0,
            );
            best = Some((t, guess));
        }
    }
    let (t0, (u0, v0)) = best?;
    newton(surface, origin, dir, u0, v0, t0)
}

/// Newton's method for `F(u, v, t) = S(u, v) − o − t d`.
pub fn newton(
    surface: &dyn Surface,
    origin: DVec3,
    dir: DVec3,
    u: f64,
    v: f64,
    t: f64,
) -> Option<RayHit> {
    let ((u0, u1), (v0, v1)) = surface.domain();
    let (mut u, mut v, mut t) = (u, v, t);
    for _ in 0..30 {
        let s = surface.evaluate(u, v);
        let f = s.p - origin - t * dir;
        if f.length() < 1e-12 * (1.0 + s.p.length()) {
            return (t >= 0.0).then_some(RayHit {
                u,
                v,
                t,
                point: s.p,
            });
        }
        let j = DMat3::from_cols(s.du, s.dv, -dir);
        if j.determinant().abs() < 1e-300 {
            return None;
        }
        let step = j.inverse() * f;
        u = (u - step.x).clamp(u0, u1);
        v = (v - step.y).clamp(v0, v1);
        t -= step.z;
    }
    None
}
