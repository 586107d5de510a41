//! Shared data for the Hedra vs curvo benchmark: one cubic NURBS curve and one
//! bicubic NURBS surface, each built once as plain data and then handed to both
//! libraries, plus helpers to compare results and to measure a mesh's chord
//! error against the exact surface.

use curvo::prelude::{NurbsCurve3D, NurbsSurface3D};
use hedra_geom::DVec3;
use hedra_geom::curves::NurbsCurve;
use hedra_geom::curves::nurbs::clamped_uniform_knots;
use hedra_geom::surfaces::{NurbsSurface, Surface};
use nalgebra::Point4;

/// Number of control points of the benchmark curve.
pub const CURVE_POINTS: usize = 50;
/// Control points per direction of the benchmark surface.
pub const SURFACE_POINTS: usize = 20;
pub const DEGREE: usize = 3;

/// A small deterministic generator (SplitMix64), so the data is the same on
/// every run without a `rand` dependency.
pub struct SplitMix(u64);

impl SplitMix {
    pub fn new(seed: u64) -> Self {
        SplitMix(seed)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }
}

/// Plain NURBS curve data: degree, knots, points, weights.
#[derive(Clone, Debug)]
pub struct CurveData {
    pub degree: usize,
    pub knots: Vec<f64>,
    pub points: Vec<DVec3>,
    pub weights: Vec<f64>,
}

/// A cubic curve with 50 control points on a jittered helix (radius 2,
/// 5 turns, height 10), weights uniform in [0.5, 2], clamped uniform knots on
/// [0, 1].
pub fn curve_data() -> CurveData {
    let mut rng = SplitMix::new(0x00C0_FFEE);
    let n = CURVE_POINTS;
    let points = (0..n)
        .map(|i| {
            let t = i as f64 / (n - 1) as f64;
            let a = t * 5.0 * std::f64::consts::TAU;
            DVec3::new(
                2.0 * a.cos() + rng.range(-0.3, 0.3),
                2.0 * a.sin() + rng.range(-0.3, 0.3),
                10.0 * t + rng.range(-0.2, 0.2),
            )
        })
        .collect();
    let weights = (0..n).map(|_| rng.range(0.5, 2.0)).collect();
    CurveData {
        degree: DEGREE,
        knots: clamped_uniform_knots(DEGREE, n),
        points,
        weights,
    }
}

/// Plain NURBS surface data; `points[i * nv + j]`, i along u.
#[derive(Clone, Debug)]
pub struct SurfaceData {
    pub degree_u: usize,
    pub degree_v: usize,
    pub knots_u: Vec<f64>,
    pub knots_v: Vec<f64>,
    pub nu: usize,
    pub nv: usize,
    pub points: Vec<DVec3>,
    pub weights: Vec<f64>,
}

/// A bicubic 20 × 20 surface over the square [0, 19]² (x along u, y along v):
/// heights `1.5 sin(0.6 i) cos(0.45 j)` plus seeded noise in ±0.1, weights
/// `1.25 + 0.6 sin(0.5 i + 0.3) cos(0.4 j)` plus seeded noise in ±0.15 (so in
/// [0.5, 2]); clamped uniform knots on [0, 1] both ways. The weights vary
/// smoothly: independent random weights in [0.5, 2] on neighbouring points
/// make the parameterisation so uneven that Hedra's uniform grid hits its cap
/// of 2048 cells per direction at tolerance 0.001.
pub fn surface_data() -> SurfaceData {
    let mut rng = SplitMix::new(0x005E_ED0F_5A4F);
    let n = SURFACE_POINTS;
    let mut points = Vec::with_capacity(n * n);
    let mut weights = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let (x, y) = (i as f64, j as f64);
            let h = 1.5 * (0.6 * x).sin() * (0.45 * y).cos() + rng.range(-0.1, 0.1);
            points.push(DVec3::new(x, y, h));
            weights.push(
                1.25 + 0.6 * (0.5 * x + 0.3).sin() * (0.4 * y).cos() + rng.range(-0.15, 0.15),
            );
        }
    }
    SurfaceData {
        degree_u: DEGREE,
        degree_v: DEGREE,
        knots_u: clamped_uniform_knots(DEGREE, n),
        knots_v: clamped_uniform_knots(DEGREE, n),
        nu: n,
        nv: n,
        points,
        weights,
    }
}

fn homogeneous(p: DVec3, w: f64) -> Point4<f64> {
    // curvo stores (w x, w y, w z, w).
    Point4::new(p.x * w, p.y * w, p.z * w, w)
}

pub fn hedra_curve(d: &CurveData) -> NurbsCurve {
    NurbsCurve::new(
        d.degree,
        d.knots.clone(),
        d.points.clone(),
        d.weights.clone(),
    )
    .expect("valid curve")
}

pub fn curvo_curve(d: &CurveData) -> NurbsCurve3D<f64> {
    let cps = d
        .points
        .iter()
        .zip(&d.weights)
        .map(|(&p, &w)| homogeneous(p, w))
        .collect();
    NurbsCurve3D::try_new(d.degree, cps, d.knots.clone()).expect("valid curve")
}

pub fn hedra_surface(d: &SurfaceData) -> NurbsSurface {
    NurbsSurface::new(
        d.degree_u,
        d.degree_v,
        d.knots_u.clone(),
        d.knots_v.clone(),
        d.nu,
        d.nv,
        d.points.clone(),
        d.weights.clone(),
    )
    .expect("valid surface")
}

/// curvo's `control_points[i][j]` is i along u, j along v: the same layout as
/// Hedra's `points[i * nv + j]`, as rows.
pub fn curvo_surface(d: &SurfaceData) -> NurbsSurface3D<f64> {
    let cps = (0..d.nu)
        .map(|i| {
            (0..d.nv)
                .map(|j| homogeneous(d.points[i * d.nv + j], d.weights[i * d.nv + j]))
                .collect()
        })
        .collect();
    NurbsSurface3D::new(
        d.degree_u,
        d.degree_v,
        d.knots_u.clone(),
        d.knots_v.clone(),
        cps,
    )
}

/// `n` evenly spaced parameters on [0, 1], both ends included.
pub fn params(n: usize) -> Vec<f64> {
    (0..n).map(|i| i as f64 / (n - 1) as f64).collect()
}

pub fn to_dvec3(p: &nalgebra::Point3<f64>) -> DVec3 {
    DVec3::new(p.x, p.y, p.z)
}

/// Chord error of a triangle mesh against the exact surface: for every
/// triangle, the distance between the surface point at the parameters of the
/// triangle's centroid and of its three edge midpoints (parameters
/// interpolated linearly) and the corresponding point on the flat triangle.
/// Returns (max, mean over triangles of the per-triangle max).
pub fn chord_error(
    surface: &NurbsSurface,
    positions: &[DVec3],
    uvs: &[(f64, f64)],
    triangles: &[[usize; 3]],
) -> (f64, f64) {
    let mut max = 0.0f64;
    let mut sum = 0.0;
    for t in triangles {
        let (p, q) = (
            t.map(|k| positions[k]),
            t.map(|k| hedra_geom::DVec2::new(uvs[k].0, uvs[k].1)),
        );
        let mut tri_max = 0.0f64;
        for (a, b, c) in [
            (1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0),
            (0.5, 0.5, 0.0),
            (0.0, 0.5, 0.5),
            (0.5, 0.0, 0.5),
        ] {
            let uv = q[0] * a + q[1] * b + q[2] * c;
            let flat = p[0] * a + p[1] * b + p[2] * c;
            let exact = surface.point(uv.x, uv.y);
            tri_max = tri_max.max(exact.distance(flat));
        }
        max = max.max(tri_max);
        sum += tri_max;
    }
    (max, sum / triangles.len().max(1) as f64)
}

/// Positions, parameters (u, v) and triangles of a mesh.
pub type PlainMesh = (Vec<DVec3>, Vec<(f64, f64)>, Vec<[usize; 3]>);

/// A curvo tessellation in plain form: positions, uvs, triangles.
pub fn curvo_mesh(t: &curvo::prelude::SurfaceTessellation3D<f64>) -> PlainMesh {
    (
        t.points().iter().map(to_dvec3).collect(),
        t.uvs().iter().map(|uv| (uv.x, uv.y)).collect(),
        t.faces().clone(),
    )
}

/// A Hedra tessellation in the same plain form.
pub fn hedra_mesh(m: &hedra_geom::surfaces::tessellate::SurfaceMesh) -> PlainMesh {
    (
        m.positions.clone(),
        m.params.clone(),
        m.triangles.iter().map(|t| t.map(|k| k as usize)).collect(),
    )
}
