//! Making holes (deleting faces but keeping their edges) and filling
//! boundary loops with a face.

use super::ModelingError;
use super::common::check_faces;
use crate::ids::{EdgeId, FaceId};
use crate::mesh::HalfEdgeMesh;

/// Deletes faces but keeps their edges and vertices: each becomes a hole.
/// Faces that touch a boundary are refused (the mesh would stop being
/// manifold at that vertex); neighbouring faces are handled in order, so a
/// face next to an earlier one is refused too.
///
/// # Errors
/// The first face that cannot become a hole; the mesh is unchanged.
pub fn make_holes(mesh: &mut HalfEdgeMesh, faces: &[FaceId]) -> Result<(), ModelingError> {
    check_faces(mesh, faces)?;
    let mut work = mesh.clone();
    for &f in faces {
        work.make_hole(f)?;
    }
    *mesh = work;
    Ok(())
}

/// Fills the boundary loops through the given edges with one face each (F).
///
/// # Errors
/// [`ModelingError::Missing`], or the edge is not on a boundary.
pub fn fill_holes(mesh: &mut HalfEdgeMesh, edges: &[EdgeId]) -> Result<Vec<FaceId>, ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no boundary edges"));
    }
    let mut work = mesh.clone();
    let mut out = Vec::new();
    for &e in edges {
        if !work.is_edge(e) {
            return Err(ModelingError::Missing(e.into()));
        }
        let h = [e.halfedge(0), e.halfedge(1)]
            .into_iter()
            .find(|&h| work.is_boundary_halfedge(h));
        match h {
            Some(h) => out.push(work.fill_hole(h)?),
            None if out.iter().any(|&f| work.edge_faces(e).contains(&Some(f))) => {} // filled by an earlier edge of the same loop
            None => return Err(ModelingError::NotBoundary { edge: e }),
        }
    }
    *mesh = work;
    Ok(out)
}
