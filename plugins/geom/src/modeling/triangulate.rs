//! Triangulating faces (Blender's Ctrl+T) along the diagonals of their
//! ear-clipping triangulation ([`crate::query::triangulate_face`]).

use super::ModelingError;
use super::common::check_faces;
use crate::ids::{FaceId, VertexId};
use crate::mesh::HalfEdgeMesh;

/// Splits faces into triangles (Blender's Ctrl+T): each face is cut along
/// the diagonals of its ear-clipping triangulation
/// ([`crate::query::triangulate_face`]), one Euler MEF
/// ([`HalfEdgeMesh::make_edge_face`]) per diagonal; positions do not move
/// and triangles are left as they are. Returns the faces made.
///
/// # Errors
/// [`ModelingError::Missing`] for a face that does not exist.
pub fn triangulate_faces(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    let mut made = Vec::new();
    for &f in faces {
        let corners: Vec<VertexId> = mesh.face_vertices(f).collect();
        let n = corners.len();
        if n <= 3 {
            continue;
        }
        let outline = |a: VertexId, b: VertexId| {
            (0..n).any(|i| {
                let (p, q) = (corners[i], corners[(i + 1) % n]);
                (p, q) == (a, b) || (p, q) == (b, a)
            })
        };
        let mut diagonals: Vec<(VertexId, VertexId)> = Vec::new();
        for t in crate::query::triangulate_face(mesh, f) {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if !outline(a, b) && !diagonals.iter().any(|&d| d == (a, b) || d == (b, a)) {
                    diagonals.push((a, b));
                }
            }
        }
        // The diagonals do not cross: each lies in one piece of the face.
        let mut pieces = vec![f];
        for (a, b) in diagonals {
            // MEF takes the face's half-edges that end at the two corners.
            let corner = |m: &HalfEdgeMesh, g: FaceId, v: VertexId| {
                m.face_halfedges(g).find(|&h| m.target(h) == v)
            };
            let Some((ha, hb)) = pieces
                .iter()
                .find_map(|&g| Some((corner(mesh, g, a)?, corner(mesh, g, b)?)))
            else {
                continue;
            };
            let (_, new_face) = mesh.make_edge_face(ha, hb)?;
            pieces.push(new_face);
            made.push(new_face);
        }
    }
    Ok(made)
}
