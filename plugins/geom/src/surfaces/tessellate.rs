//! Tessellation of curves and surfaces into polylines and triangles: a
//! uniform grid, and a grid whose resolution is chosen so the chord error
//! stays under a tolerance (`h² |S''| / 8` per direction, from sampled
//! second derivatives), which keeps neighbouring cells crack-free.

use glam::DVec3;

use super::Surface;
use crate::curves::Curve;

/// Triangles of a surface with the parameters of each vertex.
#[derive(Clone, Debug, Default)]
pub struct SurfaceMesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Unit normal per vertex (the limit normal at poles).
    pub normals: Vec<DVec3>,
    /// `(u, v)` of each vertex.
    pub params: Vec<(f64, f64)>,
    /// Vertex indices of each triangle.
    pub triangles: Vec<[u32; 3]>,
}

/// A `(cu + 1) × (cv + 1)` grid of points, two triangles per cell,
/// counter-clockwise around `S_u × S_v`.
pub fn grid(surface: &dyn Surface, cu: usize, cv: usize) -> SurfaceMesh {
    let ((u0, u1), (v0, v1)) = surface.domain();
    let (cu, cv) = (cu.max(1), cv.max(1));
    let mut m = SurfaceMesh::default();
    for i in 0..=cu {
        let u = u0 + (u1 - u0) * i as f64 / cu as f64;
        for j in 0..=cv {
            let v = v0 + (v1 - v0) * j as f64 / cv as f64;
            let s = surface.evaluate(u, v);
            m.positions.push(s.p);
            let n = s.normal();
            m.normals.push(if n == DVec3::ZERO {
                super::limit_normal(surface, u, v)
            } else {
                n
            });
            m.params.push((u, v));
        }
    }
    m.triangles = grid_triangles(cu, cv);
    m
}

/// Cells in u and v so that the chord error of a flat cell is about
/// `tolerance` at most: `n ≥ (b − a) √(max |S''| / (8 tol))`, the second
/// derivatives sampled on a 17 × 17 grid (capped at 2048 per direction).
pub fn cells_for_tolerance(surface: &dyn Surface, tolerance: f64) -> (usize, usize) {
    let ((u0, u1), (v0, v1)) = surface.domain();
    let (mut suu, mut svv, mut suv) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..=16 {
        for j in 0..=16 {
            let s = surface.evaluate(
                u0 + (u1 - u0) * i as f64 / 16.0,
                v0 + (v1 - v0) * j as f64 / 16.0,
            );
            suu = suu.max(s.duu.length());
            svv = svv.max(s.dvv.length());
            suv = suv.max(s.duv.length());
        }
    }
    let tol = tolerance.max(1e-12);
    let n =
        |span: f64, d2: f64| ((span * (d2 / (8.0 * tol)).sqrt()).ceil() as usize).clamp(1, 2048);
    (n(u1 - u0, suu + suv), n(v1 - v0, svv + suv))
}

/// A triangle mesh of the surface within about `tolerance` of it.
pub fn tessellate(surface: &dyn Surface, tolerance: f64) -> SurfaceMesh {
    let (cu, cv) = cells_for_tolerance(surface, tolerance);
    grid(surface, cu, cv)
}

/// [`tessellate`] for a NURBS surface through its fast grid evaluator.
pub fn tessellate_nurbs(surface: &super::NurbsSurface, tolerance: f64) -> SurfaceMesh {
    let (cu, cv) = cells_for_tolerance(surface, tolerance);
    let ((u0, u1), (v0, v1)) = surface.domain();
    let us: Vec<f64> = (0..=cu)
        .map(|i| u0 + (u1 - u0) * i as f64 / cu as f64)
        .collect();
    let vs: Vec<f64> = (0..=cv)
        .map(|j| v0 + (v1 - v0) * j as f64 / cv as f64)
        .collect();
    let (positions, normals) = surface.grid(&us, &vs, true);
    let params = us
        .iter()
        .flat_map(|&u| vs.iter().map(move |&v| (u, v)))
        .collect();
    SurfaceMesh {
        positions,
        normals,
        params,
        triangles: grid_triangles(cu, cv),
    }
}

/// Two counter-clockwise triangles per cell of a `(cu + 1) × (cv + 1)` grid.
pub fn grid_triangles(cu: usize, cv: usize) -> Vec<[u32; 3]> {
    let id = |i: usize, j: usize| (i * (cv + 1) + j) as u32;
    let mut t = Vec::with_capacity(2 * cu * cv);
    for i in 0..cu {
        for j in 0..cv {
            t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    t
}

/// Parameters along a curve so that each chord stays within about
/// `tolerance` of the curve (`h² |p''| / 8` per piece, refined where the
/// curve bends more).
pub fn curve_parameters(curve: &dyn Curve, tolerance: f64) -> Vec<f64> {
    let (a, b) = curve.domain();
    let tol = tolerance.max(1e-12);
    let mut out = vec![a];
    let samples = 64;
    for k in 0..samples {
        let (s, e) = (
            a + (b - a) * k as f64 / samples as f64,
            a + (b - a) * (k + 1) as f64 / samples as f64,
        );
        let d2 = [s, (s + e) / 2.0, e]
            .iter()
            .map(|&t| curve.derivatives(t)[2].length())
            .fold(0.0, f64::max);
        let pieces = (((e - s) * (d2 / (8.0 * tol)).sqrt()).ceil() as usize).clamp(1, 4096);
        for i in 1..=pieces {
            out.push(s + (e - s) * i as f64 / pieces as f64);
        }
    }
    out
}

/// Where the plane through `origin` with normal `normal` cuts a
/// tessellated surface: one segment per triangle it crosses (the planar
/// section of seed 002's exercise, within the tessellation's tolerance).
pub fn plane_section(mesh: &SurfaceMesh, origin: DVec3, normal: DVec3) -> Vec<[DVec3; 2]> {
    let d: Vec<f64> = mesh
        .positions
        .iter()
        .map(|p| (*p - origin).dot(normal))
        .collect();
    let mut out = Vec::new();
    for t in &mesh.triangles {
        let mut crossing = Vec::with_capacity(2);
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            let (da, db) = (d[a], d[b]);
            if (da < 0.0) != (db < 0.0) {
                let s = da / (da - db);
                crossing.push(mesh.positions[a].lerp(mesh.positions[b], s));
            }
        }
        if let [p, q] = crossing[..] {
            out.push([p, q]);
        }
    }
    out
}
