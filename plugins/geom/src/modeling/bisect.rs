//! Bisect: cutting faces with a plane (Blender's Mesh ▸ Bisect), built from
//! Euler MVE (split an edge where it crosses the plane) and MEF (join two
//! points of a face on the plane), with the options to clear one side and
//! to fill the cut.

use super::ModelingError;
use super::common::check_faces;
use crate::ids::{EdgeId, FaceId, VertexId};
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;
use std::collections::{HashMap, HashSet};

/// Which side of the plane [`bisect`] deletes after cutting.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum BisectClear {
    /// Keep both sides.
    #[default]
    Neither,
    /// Delete the faces on the side the normal points to.
    Outer,
    /// Delete the faces on the side opposite the normal.
    Inner,
}

/// What [`bisect`] made.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bisected {
    /// The new edges that lie on the plane, in the order they were made.
    pub cut_edges: Vec<EdgeId>,
    /// The vertices made where edges crossed the plane.
    pub new_vertices: Vec<VertexId>,
    /// The faces that fill the cut (with `fill`).
    pub fill_faces: Vec<FaceId>,
}

/// Cuts `faces` with the plane through `point` with normal `normal`: every
/// edge of the faces that crosses the plane is split where it crosses (MVE,
/// at the linear interpolation of the signed distances), and each face is
/// split along the plane (MEF between its points on the plane, paired in
/// order along the cut line, so a concave face cut twice gets two edges).
/// Vertices within `1e-9 ×` the selection's size of the plane count as on
/// it. `clear` then deletes the faces on one side; `fill` closes each
/// boundary loop that lies wholly on the plane with one face.
///
/// # Errors
/// [`ModelingError::Empty`] / [`ModelingError::Missing`] for the faces,
/// [`ModelingError::Parameter`] for a zero or non-finite normal or a
/// non-finite point; the mesh is unchanged on error.
pub fn bisect(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    point: DVec3,
    normal: DVec3,
    clear: BisectClear,
    fill: bool,
) -> Result<Bisected, ModelingError> {
    check_faces(mesh, faces)?;
    let n = normal.normalize_or_zero();
    if n == DVec3::ZERO || !n.is_finite() || !point.is_finite() {
        return Err(ModelingError::Parameter {
            what: "bisect plane",
            allowed: "a finite point and a non-zero normal",
            value: format!("point {point}, normal {normal}"),
        });
    }
    let mut work = mesh.clone();
    let selected: Vec<FaceId> = faces
        .iter()
        .copied()
        .collect::<HashSet<_>>()
        .into_iter()
        .collect();
    let vertices: HashSet<VertexId> = selected
        .iter()
        .flat_map(|&f| work.face_vertices(f))
        .collect();
    let size = vertices
        .iter()
        .map(|&v| work.position(v).distance(point))
        .fold(1.0, f64::max);
    let eps = 1e-9 * size;
    let distance = |p: DVec3| (p - point).dot(n);
    let side_of = |d: f64| {
        if d.abs() <= eps {
            0
        } else if d > 0.0 {
            1
        } else {
            -1
        }
    };
    let mut side: HashMap<VertexId, i8> = vertices
        .iter()
        .map(|&v| (v, side_of(distance(work.position(v)))))
        .collect();

    // 1. Split every crossing edge (MVE); the new vertex is on the plane.
    let mut out = Bisected::default();
    let mut edges: Vec<EdgeId> = selected
        .iter()
        .flat_map(|&f| work.face_halfedges(f).map(|h| h.edge()))
        .collect::<HashSet<_>>()
        .into_iter()
        .collect();
    edges.sort();
    for e in edges {
        let [a, b] = work.edge_vertices(e);
        if side[&a] * side[&b] >= 0 {
            continue;
        }
        let (pa, pb) = (work.position(a), work.position(b));
        let (da, db) = (distance(pa), distance(pb));
        let v = work.split_edge(e, pa + (pb - pa) * (da / (da - db)))?;
        side.insert(v, 0);
        out.new_vertices.push(v);
    }

    // 2. Split each face that has corners on both sides along the plane (MEF).
    let mut pieces: Vec<FaceId> = Vec::new();
    for &f in &selected {
        let corners: Vec<VertexId> = work.face_vertices(f).collect();
        let sides: Vec<i8> = corners.iter().map(|v| side[v]).collect();
        pieces.push(f);
        if !(sides.contains(&1) && sides.contains(&-1)) {
            continue;
        }
        // The cut line runs along n × face normal; pair the on-plane corners
        // in order along it.
        let along = n.cross(work.face_normal(f));
        let mut on_plane: Vec<VertexId> =
            corners.iter().copied().filter(|v| side[v] == 0).collect();
        on_plane.sort_by(|a, b| {
            let (ta, tb) = (work.position(*a).dot(along), work.position(*b).dot(along));
            ta.total_cmp(&tb)
        });
        let mut face_pieces = vec![f];
        for pair in on_plane.chunks_exact(2) {
            let (a, b) = (pair[0], pair[1]);
            if work.find_edge(a, b).is_some() {
                continue;
            }
            let corner = |m: &HalfEdgeMesh, g: FaceId, v: VertexId| {
                m.face_halfedges(g).find(|&h| m.target(h) == v)
            };
            let Some((ha, hb)) = face_pieces
                .iter()
                .find_map(|&g| Some((corner(&work, g, a)?, corner(&work, g, b)?)))
            else {
                continue;
            };
            let (edge, new_face) = work.make_edge_face(ha, hb)?;
            out.cut_edges.push(edge);
            face_pieces.push(new_face);
            pieces.push(new_face);
        }
    }

    // 3. Clear one side: each piece now lies on one side of the plane.
    let cleared = match clear {
        BisectClear::Neither => None,
        BisectClear::Outer => Some(1),
        BisectClear::Inner => Some(-1),
    };
    if let Some(s) = cleared {
        let doomed: Vec<FaceId> = pieces
            .iter()
            .copied()
            .filter(|&g| {
                let sides: Vec<i8> = work.face_vertices(g).map(|v| side[&v]).collect();
                sides.contains(&s) && !sides.contains(&-s)
            })
            .collect();
        work.delete_faces(&doomed, false);
        out.cut_edges.retain(|&e| work.is_edge(e));
    }

    // 4. Fill each boundary loop that lies on the plane.
    if fill {
        for boundary in work.boundary_loops() {
            let flat = boundary.iter().all(|&h| {
                let v = work.origin(h);
                side.get(&v)
                    .map_or(distance(work.position(v)).abs() <= eps, |&s| s == 0)
            });
            if flat && boundary.len() >= 3 {
                out.fill_faces.push(work.fill_hole(boundary[0])?);
            }
        }
    }
    work.validate()?;
    *mesh = work;
    Ok(out)
}
