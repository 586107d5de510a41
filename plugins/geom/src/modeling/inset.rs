//! Inset: a region as one (Blender's I) or each face on its own. Corners
//! move along their bisector by thickness / cos or / sin of half the turn
//! so the border keeps its width.

use super::ModelingError;
use super::common::check_faces;
use super::extrude::rebuild_region;
use crate::ids::{FaceId, VertexId};
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;

/// Insets a region of faces as one (Blender's I): a border `thickness` wide
/// runs inside the region's outline, and the region is pushed by `depth`
/// along its average normal. Corners of the outline move along the bisector
/// of their two outline edges by thickness / cos(half the turn), so the
/// border keeps its width.
///
/// # Errors
/// As [`extrude_region`](super::extrude_region); thickness must be finite and not negative.
pub fn inset_region(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    thickness: f64,
    depth: f64,
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    if !(thickness.is_finite() && thickness >= 0.0 && depth.is_finite()) {
        return Err(ModelingError::Parameter {
            what: "thickness and depth",
            allowed: "finite, thickness >= 0",
            value: format!("{thickness}, {depth}"),
        });
    }
    let normal = mesh.region_normal(faces);
    let in_region = |f: Option<FaceId>| f.is_some_and(|f| faces.contains(&f));
    // Inward normals (in the region's plane) of the outline edges at each corner.
    let mut inward: std::collections::HashMap<VertexId, Vec<DVec3>> =
        std::collections::HashMap::new();
    for &f in faces {
        for h in mesh
            .face_halfedges(f)
            .filter(|&h| !in_region(mesh.face(h.twin())))
        {
            let d =
                (mesh.position(mesh.target(h)) - mesh.position(mesh.origin(h))).normalize_or_zero();
            let n_edge = normal.cross(d);
            for v in [mesh.origin(h), mesh.target(h)] {
                inward.entry(v).or_default().push(n_edge);
            }
        }
    }
    let corner = |v: VertexId, p: DVec3| -> DVec3 {
        let dirs = &inward[&v];
        let bisector = dirs.iter().copied().sum::<DVec3>().normalize_or_zero();
        let cos_half = if dirs.len() == 2 {
            dirs[0].dot(bisector).max(1e-3)
        } else {
            1.0
        };
        p + bisector * (thickness / cos_half) + normal * depth
    };
    rebuild_region(mesh, faces, corner, |_, p| p + normal * depth)
}

/// Insets each face on its own: a border of quads `thickness` wide inside
/// the face, the inner face pushed along the normal by `depth` (Blender's
/// inset, "individual"). Corners move along their bisector by
/// thickness / sin(half the corner angle), so the border keeps its width.
///
/// # Errors
/// As [`extrude_faces_individual`](super::extrude_faces_individual); a thickness below zero is refused.
pub fn inset_faces_individual(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    thickness: f64,
    depth: f64,
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    if !(thickness.is_finite() && thickness >= 0.0 && depth.is_finite()) {
        return Err(ModelingError::Parameter {
            what: "thickness and depth",
            allowed: "finite, thickness >= 0",
            value: format!("{thickness}, {depth}"),
        });
    }
    let mut sides = Vec::new();
    for &f in faces {
        let normal = mesh.face_normal(f);
        let corners: Vec<VertexId> = mesh.face_vertices(f).collect();
        let pts: Vec<DVec3> = corners.iter().map(|&v| mesh.position(v)).collect();
        let n = pts.len();
        let targets: Vec<DVec3> = (0..n)
            .map(|i| {
                let p = pts[i];
                let to_prev = (pts[(i + n - 1) % n] - p).normalize_or_zero();
                let to_next = (pts[(i + 1) % n] - p).normalize_or_zero();
                let bisector = (to_prev + to_next).normalize_or_zero();
                let half_angle_sin = (to_prev.angle_between(to_next) / 2.0).sin().max(1e-3);
                // A reflex corner's bisector points outwards: flip it inwards.
                let inward = if to_next.cross(to_prev).dot(normal) < 0.0 {
                    -bisector
                } else {
                    bisector
                };
                p + inward * (thickness / half_angle_sin) + normal * depth
            })
            .collect();
        sides.extend(mesh.extrude_face(f, DVec3::ZERO)?);
        for (v, t) in mesh
            .face_vertices(f)
            .collect::<Vec<_>>()
            .into_iter()
            .zip(rotate_to_match(&corners, mesh, f, &targets))
        {
            mesh.set_position(v, t);
        }
    }
    Ok(sides)
}

/// The cap of an extruded face starts at the corner after the first original
/// corner; line the targets up with the cap's vertex order by position.
fn rotate_to_match(
    original: &[VertexId],
    mesh: &HalfEdgeMesh,
    cap: FaceId,
    targets: &[DVec3],
) -> Vec<DVec3> {
    let cap_pts: Vec<DVec3> = mesh.face_vertices(cap).map(|v| mesh.position(v)).collect();
    let first = mesh.position(original[0]);
    let shift = cap_pts
        .iter()
        .position(|p| p.distance_squared(first) < 1e-24)
        .unwrap_or(0);
    (0..cap_pts.len())
        .map(|i| targets[(i + targets.len() - shift) % targets.len()])
        .collect()
}
