//! Polygon meshes of the sweeps: quad grids with n-gon caps, built
//! through `HalfEdgeMesh::from_polygons`.

use super::caps::check_caps;
use super::extrude::check_vector;
use super::revolve::{Axis, check_angle, full_turn};
use super::{SweepError, check_segments, profile_parameters};
use crate::curves::{Curve, NurbsCurve};
use crate::mesh::HalfEdgeMesh;
use crate::surfaces::NurbsSurface;
use glam::DVec3;
use std::collections::HashMap;
use std::f64::consts::TAU;

/// A polygon mesh from a grid of points `nu × nv` (`points[i * nv + j]`):
/// a quad for each cell, wrapping around in u or v where closed, and an
/// n-gon cap over the first and last row (`caps_u`: the rows `i = 0` and
/// `i = nu − 1`, each running over j) or column (`caps_v`). Points at the
/// same position (a profile touching the axis, a collapsed section) are
/// welded into one vertex, so quads there become triangles. A closed
/// result is turned to face outwards (positive volume); an open one keeps
/// the grid's orientation (the normal of `(i, j) → (i+1, j) → (i+1, j+1)`).
///
/// # Errors
/// [`SweepError::Mesh`] when the polygons are not a manifold mesh.
///
/// Complexity: O(nu · nv).
#[allow(clippy::too_many_arguments)]
pub fn grid_mesh(
    points: &[DVec3],
    nu: usize,
    nv: usize,
    closed_u: bool,
    closed_v: bool,
    caps_u: bool,
    caps_v: bool,
) -> Result<HalfEdgeMesh, SweepError> {
    // Weld equal positions (exactly equal: the constructions produce the
    // same bits for a point on the axis or a collapsed section).
    let mut index_of: HashMap<[u64; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let key = |p: DVec3| (p + DVec3::ZERO).to_array().map(f64::to_bits);
    let ids: Vec<u32> = points
        .iter()
        .map(|&p| {
            *index_of.entry(key(p)).or_insert_with(|| {
                positions.push(p);
                (positions.len() - 1) as u32
            })
        })
        .collect();
    let at = |i: usize, j: usize| ids[(i % nu) * nv + (j % nv)];
    let cells_u = if closed_u { nu } else { nu - 1 };
    let cells_v = if closed_v { nv } else { nv - 1 };
    let mut polygons: Vec<Vec<u32>> = Vec::new();
    for i in 0..cells_u {
        for j in 0..cells_v {
            polygons.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    if caps_u && !closed_u {
        polygons.push((0..nv).map(|j| at(0, j)).collect());
        polygons.push((0..nv).rev().map(|j| at(nu - 1, j)).collect());
    }
    if caps_v && !closed_v {
        polygons.push((0..nu).rev().map(|i| at(i, 0)).collect());
        polygons.push((0..nu).map(|i| at(i, nv - 1)).collect());
    }
    // Welded corners: drop repeats, then faces that collapsed.
    let polygons: Vec<Vec<u32>> = polygons
        .into_iter()
        .map(|mut f| {
            f.dedup();
            while f.len() > 1 && f.first() == f.last() {
                f.pop();
            }
            f
        })
        .filter(|f| f.len() >= 3)
        .collect();
    let mesh = HalfEdgeMesh::from_polygons(&positions, &polygons)?;
    if mesh.boundary_loops().is_empty() && signed_volume(&positions, &polygons) < 0.0 {
        let flipped: Vec<Vec<u32>> = polygons
            .into_iter()
            .map(|mut f| {
                f.reverse();
                f
            })
            .collect();
        return Ok(HalfEdgeMesh::from_polygons(&positions, &flipped)?);
    }
    Ok(mesh)
}

pub(super) fn signed_volume(positions: &[DVec3], polygons: &[Vec<u32>]) -> f64 {
    polygons
        .iter()
        .map(|f| {
            let p0 = positions[f[0] as usize];
            (1..f.len() - 1)
                .map(|k| p0.dot(positions[f[k] as usize].cross(positions[f[k + 1] as usize])) / 6.0)
                .sum::<f64>()
        })
        .sum()
}

/// The mesh of [`revolve`](super::revolve): the profile sampled at
/// [`profile_parameters`] and turned in `segments` equal steps of the angle
/// (each point on its exact circle or helix). A full turn without pitch
/// closes around; otherwise `caps` puts an n-gon on the profile at both
/// ends (closed planar profiles only). Vertices on the axis are shared.
/// Quads throughout, triangles where a quad touches the axis. Inverse:
/// none.
///
/// # Errors
/// As [`revolve`](super::revolve); [`SweepError::Segments`]; the caps' errors
/// ([`profile_plane`](super::profile_plane)); [`SweepError::Mesh`] for a profile that crosses
/// itself or the axis so the quads are not manifold.
///
/// Complexity: O(segments × profile segments).
pub fn revolve_mesh(
    profile: &NurbsCurve,
    axis: Axis,
    angle: f64,
    pitch: f64,
    segments: u32,
    profile_segments: u32,
    caps: bool,
) -> Result<HalfEdgeMesh, SweepError> {
    let axis = axis.unit()?;
    check_angle(angle, pitch)?;
    check_segments("segments", segments, 1)?;
    check_segments("profile segments", profile_segments, 1)?;
    let closed_u = full_turn(angle, pitch);
    if closed_u && segments < 3 {
        return Err(SweepError::Segments {
            what: "segments",
            min: 3,
            got: segments,
        });
    }
    let caps = caps && !closed_u;
    if caps {
        check_caps(profile)?;
    }
    let (params, closed_v) = profile_parameters(profile, profile_segments);
    let row = profile.points_at(&params);
    let nu = if closed_u { segments } else { segments + 1 } as usize;
    let nv = row.len();
    let mut points = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        let theta = angle * i as f64 / f64::from(segments);
        for &p in &row {
            points.push(axis.turn(p, theta, pitch * theta / TAU));
        }
    }
    grid_mesh(&points, nu, nv, closed_u, closed_v, caps, false)
}

/// The mesh of [`extrude`](super::extrude): the profile sampled at
/// [`profile_parameters`] and moved in `segments` equal steps along the
/// vector, with n-gon caps at both ends when `caps` (closed planar
/// profiles only; the capped mesh is closed, genus 0). Inverse: none.
///
/// # Errors
/// As [`extrude`](super::extrude); [`SweepError::Segments`]; the caps' errors.
///
/// Complexity: O(segments × profile segments).
pub fn extrude_mesh(
    profile: &NurbsCurve,
    vector: DVec3,
    segments: u32,
    profile_segments: u32,
    caps: bool,
) -> Result<HalfEdgeMesh, SweepError> {
    check_vector(vector)?;
    check_segments("segments", segments, 1)?;
    check_segments("profile segments", profile_segments, 1)?;
    if caps {
        check_caps(profile)?;
    }
    let (params, closed_u) = profile_parameters(profile, profile_segments);
    let row = profile.points_at(&params);
    let nv = segments as usize + 1;
    let mut points = vec![DVec3::ZERO; row.len() * nv];
    for (i, &p) in row.iter().enumerate() {
        for j in 0..nv {
            points[i * nv + j] = p + vector * j as f64 / f64::from(segments);
        }
    }
    grid_mesh(&points, row.len(), nv, closed_u, false, false, caps)
}

/// A mesh of a surface made from sections (a sweep or a loft, u along the
/// profile, v across): the surface evaluated at `u_params` (closed around
/// when `closed_u`, the last parameter then left out by the caller) and at
/// `segments` equal steps of its v domain (all the way round when
/// `closed_v`), with n-gon caps over the first and last v when `caps`.
/// Inverse: none.
///
/// # Errors
/// [`SweepError::Segments`]; [`SweepError::Mesh`].
///
/// Complexity: O(segments × u parameters).
pub fn surface_mesh(
    surface: &NurbsSurface,
    u_params: &[f64],
    closed_u: bool,
    segments: u32,
    closed_v: bool,
    caps: bool,
) -> Result<HalfEdgeMesh, SweepError> {
    use crate::surfaces::Surface;
    check_segments("segments", segments, 1)?;
    let (_, (v0, v1)) = surface.domain();
    let count = if closed_v { segments } else { segments + 1 };
    let vs: Vec<f64> = (0..count)
        .map(|j| v0 + (v1 - v0) * f64::from(j) / f64::from(segments))
        .collect();
    let (points, _) = surface.grid(u_params, &vs, false);
    grid_mesh(
        &points,
        u_params.len(),
        vs.len(),
        closed_u,
        closed_v,
        false,
        caps && !closed_v,
    )
}

/// The u parameters at which [`surface_mesh`] samples a sweep or loft of
/// `profile` (its [`profile_parameters`] mapped onto [0, 1] as
/// [`make_compatible`](super::make_compatible) maps its domain), and whether it is closed.
///
/// Complexity: as [`profile_parameters`].
pub fn compatible_parameters(profile: &NurbsCurve, segments: u32) -> (Vec<f64>, bool) {
    let (params, closed) = profile_parameters(profile, segments);
    let (a, b) = profile.domain();
    (params.iter().map(|t| (t - a) / (b - a)).collect(), closed)
}
