//! Deleting faces with the edges and vertices only they use (Blender's
//! X ▸ Faces).

use super::ModelingError;
use super::common::check_faces;
use crate::ids::FaceId;
use crate::mesh::HalfEdgeMesh;

/// Deletes faces together with the edges and vertices no other face uses
/// (Blender's X ▸ Faces). For X ▸ Edges and X ▸ Vertices pass the faces
/// around them ([`faces_around_edges`](super::faces_around_edges), [`faces_around_vertices`](super::faces_around_vertices)).
///
/// # Errors
/// [`ModelingError::Invalid`] when the rest would not be a manifold mesh
/// (for example two holes meeting at one vertex); the mesh is unchanged.
pub fn delete_faces(mesh: &mut HalfEdgeMesh, faces: &[FaceId]) -> Result<(), ModelingError> {
    check_faces(mesh, faces)?;
    let mut work = mesh.clone();
    work.delete_faces(faces, false);
    work.validate()?;
    *mesh = work;
    Ok(())
}
