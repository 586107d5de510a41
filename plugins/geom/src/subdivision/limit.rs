//! Limit positions and limit normals: where a refined vertex ends up after
//! infinitely many steps, and the surface normal there, from the vertex's
//! one-ring at the last level.
//!
//! Sources: Catmull-Clark limit and tangent masks from Halstead, Kass,
//! DeRose, "Efficient, Fair Interpolation using Catmull-Clark Surfaces"
//! (SIGGRAPH 1993), §A; Loop's from Hoppe et al., "Piecewise Smooth Surface
//! Reconstruction" (SIGGRAPH 1994), appendix; crease limit `(a + 4v + b) / 6`
//! is the cubic B-spline's.

use std::f64::consts::{PI, TAU};

use glam::DVec3;

use super::level::Level;
use super::rules::loop_beta;
use super::{Creases, Options, Refiner, Scheme, SubdivisionError};
use crate::{HalfEdgeMesh, VertexId};

/// How a vertex of the last level sits: smooth, on a crease between two
/// sharp neighbours, or a corner.
enum Kind {
    Smooth,
    Crease(u32, u32),
    Corner,
}

fn kind(level: &Level, v: u32) -> Kind {
    if level.vertex_sharp(v) > 0.0 {
        return Kind::Corner;
    }
    let mut sharp = level
        .vertex_edges(v)
        .iter()
        .filter(|&&e| level.edge_sharp(e) > 0.0);
    match (sharp.next(), sharp.next(), sharp.next()) {
        (None, ..) | (Some(_), None, _) => Kind::Smooth,
        (Some(&a), Some(&b), None) => Kind::Crease(level.other_end(a, v), level.other_end(b, v)),
        _ => Kind::Corner,
    }
}

/// Checks that the last level has the faces the scheme's limit masks need.
fn check(refiner: &Refiner) -> Result<(), SubdivisionError> {
    let last = refiner.levels.last().expect("cage level");
    let ok = match refiner.options().scheme {
        Scheme::CatmullClark => last.all_faces_have(4),
        Scheme::Loop => true,
        Scheme::DooSabin | Scheme::Linear => false,
    };
    if ok {
        Ok(())
    } else {
        Err(SubdivisionError::NoLimit {
            scheme: refiner.options().scheme,
        })
    }
}

/// The corners at `v` of the faces around it, in order: face `i`'s corner
/// at `v` starts the edge from `v` that face `i` shares with face `i - 1`
/// (the walk crosses each face's edge into `v`). `None` at a boundary.
pub(crate) fn ring_corners(level: &Level, v: u32) -> Option<Vec<usize>> {
    let corners = level.vertex_corners(v);
    let start = *corners.first()? as usize;
    let mut out = Vec::with_capacity(corners.len());
    let mut c = start;
    loop {
        out.push(c);
        let e = level.face_edges[level.prev_corner(c)];
        let [f0, f1] = level.edge_faces(e);
        let g = if f0 == level.corner_face(c) { f1 } else { f0 };
        if g == super::level::NONE {
            return None;
        }
        c = level
            .face_corners(g)
            .find(|&k| level.face_vertices[k] == v)?;
        if c == start {
            return Some(out);
        }
        if out.len() > corners.len() {
            return None;
        }
    }
}

/// The ring of one smooth vertex in order around it: for each face corner at
/// `v` ([`ring_corners`]), the next vertex along the face and (for quads) the
/// diagonal one.
fn ring(level: &Level, v: u32) -> Option<Vec<(u32, u32)>> {
    Some(ring_of(level, &ring_corners(level, v)?))
}

/// [`ring`] from the ring's corners.
fn ring_of(level: &Level, corners: &[usize]) -> Vec<(u32, u32)> {
    corners
        .iter()
        .map(|&c| {
            let next = level.next_corner(c);
            (
                level.face_vertices[next],
                level.face_vertices[level.next_corner(next)],
            )
        })
        .collect()
}

/// The Catmull-Clark tangent masks at a smooth vertex whose ring is `ring`
/// ([`ring`]: edge neighbour and diagonal per face, in order): `(t1, t2)`,
/// both scaled alike, so that the limit tangent along the ring's edge `i`
/// is `cos(2πi/n) t1 + sin(2πi/n) t2` (Halstead et al. 1993, §A).
pub(crate) fn catmull_clark_tangents(points: &[DVec3], ring: &[(u32, u32)]) -> (DVec3, DVec3) {
    let n = ring.len() as f64;
    let (mut t1, mut t2) = (DVec3::ZERO, DVec3::ZERO);
    let a_n = 1.0 + (TAU / n).cos() + (PI / n).cos() * (2.0 * (9.0 + (TAU / n).cos())).sqrt();
    for (i, &(e, d)) in ring.iter().enumerate() {
        let (angle, next_angle) = (TAU * i as f64 / n, TAU * (i + 1) as f64 / n);
        let (e, d) = (points[e as usize], points[d as usize]);
        t1 += a_n * angle.cos() * e + (angle.cos() + next_angle.cos()) * d;
        t2 += a_n * angle.sin() * e + (angle.sin() + next_angle.sin()) * d;
    }
    (t1, t2)
}

/// [`catmull_clark_tangents`] of smooth vertex `v` of `level`, with the
/// corners of its ring ([`ring_corners`]); `None` when `v` is not smooth
/// or not interior.
pub(crate) fn vertex_tangents(
    level: &Level,
    points: &[DVec3],
    v: u32,
) -> Option<(Vec<usize>, DVec3, DVec3)> {
    let Kind::Smooth = kind(level, v) else {
        return None;
    };
    let corners = ring_corners(level, v)?;
    let (t1, t2) = catmull_clark_tangents(points, &ring_of(level, &corners));
    Some((corners, t1, t2))
}

/// Limit positions of the refiner's last level, given that level's points.
///
/// # Errors
/// [`SubdivisionError::NoLimit`] for Doo-Sabin and Linear, and for
/// Catmull-Clark at level 0 on a cage with non-quad faces.
pub fn limit_positions(
    refiner: &Refiner,
    points: &[DVec3],
) -> Result<Vec<DVec3>, SubdivisionError> {
    check(refiner)?;
    let level = refiner.levels.last().expect("cage level");
    let catmull_clark = refiner.options().scheme == Scheme::CatmullClark;
    Ok((0..level.vertex_count as u32)
        .map(|v| {
            let p = points[v as usize];
            match kind(level, v) {
                Kind::Corner => p,
                Kind::Crease(a, b) => (points[a as usize] + 4.0 * p + points[b as usize]) / 6.0,
                Kind::Smooth => {
                    let edges = level.vertex_edges(v);
                    let n = edges.len() as f64;
                    let edge_sum: DVec3 = edges
                        .iter()
                        .map(|&e| points[level.other_end(e, v) as usize])
                        .sum();
                    if catmull_clark {
                        // (n² v + 4 Σ e_i + Σ d_i) / (n (n + 5))
                        let diagonal_sum: DVec3 = level
                            .vertex_corners(v)
                            .iter()
                            .map(|&c| {
                                let c = level.next_corner(level.next_corner(c as usize));
                                points[level.face_vertices[c] as usize]
                            })
                            .sum();
                        (n * n * p + 4.0 * edge_sum + diagonal_sum) / (n * (n + 5.0))
                    } else {
                        // (1 − nχ) v + χ Σ e_i, χ = 1 / (3 / (8β) + n)
                        let chi = 1.0 / (3.0 / (8.0 * loop_beta(edges.len())) + n);
                        (1.0 - n * chi) * p + chi * edge_sum
                    }
                }
            }
        })
        .collect())
}

/// Unit limit normals of the refiner's last level: tangent masks at smooth
/// interior vertices, the area-weighted normal of the surrounding faces (at
/// the limit positions) elsewhere.
///
/// # Errors
/// As [`limit_positions`].
pub fn limit_normals(refiner: &Refiner, points: &[DVec3]) -> Result<Vec<DVec3>, SubdivisionError> {
    let limit = limit_positions(refiner, points)?;
    let level = refiner.levels.last().expect("cage level");
    let catmull_clark = refiner.options().scheme == Scheme::CatmullClark;
    // Area-weighted face normals around each vertex, as the fallback and to
    // orient the tangent-mask normals.
    let mut area_normals = vec![DVec3::ZERO; level.vertex_count];
    for f in 0..level.face_count() as u32 {
        let corners = level.face_corners(f);
        let mut n = DVec3::ZERO;
        for c in corners.clone() {
            let a = limit[level.face_vertices[c] as usize];
            let b = limit[level.face_vertices[level.next_corner(c)] as usize];
            n += a.cross(b);
        }
        for c in corners {
            area_normals[level.face_vertices[c] as usize] += n;
        }
    }
    Ok((0..level.vertex_count as u32)
        .map(|v| {
            let fallback = area_normals[v as usize].normalize_or_zero();
            let Kind::Smooth = kind(level, v) else {
                return fallback;
            };
            let Some(ring) = ring(level, v) else {
                return fallback;
            };
            let (t1, t2) = if catmull_clark {
                catmull_clark_tangents(points, &ring)
            } else {
                let n = ring.len() as f64;
                ring.iter().enumerate().fold(
                    (DVec3::ZERO, DVec3::ZERO),
                    |(t1, t2), (i, &(e, _))| {
                        let angle = TAU * i as f64 / n;
                        let e = points[e as usize];
                        (t1 + angle.cos() * e, t2 + angle.sin() * e)
                    },
                )
            };
            let normal = t1.cross(t2).normalize_or_zero();
            if normal == DVec3::ZERO {
                fallback
            } else if normal.dot(fallback) < 0.0 {
                -normal
            } else {
                normal
            }
        })
        .collect())
}

/// Where each cage vertex lies on the limit surface ("snap cage to limit").
///
/// # Errors
/// [`SubdivisionError::NoLimit`] for Doo-Sabin and Linear;
/// [`SubdivisionError::NotTriangles`] for Loop on other faces.
pub fn snap_to_limit(
    mesh: &HalfEdgeMesh,
    creases: &Creases,
    options: Options,
) -> Result<Vec<(VertexId, DVec3)>, SubdivisionError> {
    let quads = mesh.faces().all(|f| mesh.face_degree(f) == 4);
    let levels = u32::from(options.scheme == Scheme::CatmullClark && !quads);
    let refiner = Refiner::new(mesh, creases, options, levels)?;
    let points = refiner.refine(&refiner.cage_positions(mesh));
    let limit = limit_positions(&refiner, &points)?;
    // A cage vertex's own point is the last block of the child points.
    let first = refiner.vertex_count() - refiner.cage_vertices().len();
    Ok(refiner
        .cage_vertices()
        .iter()
        .enumerate()
        .map(|(i, &v)| (v, limit[first + i]))
        .collect())
}
