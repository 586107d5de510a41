//! Connecting vertices that share a face with a new edge (Blender's J).

use super::ModelingError;
use super::common::connect_in_shared_face;
use crate::ids::{EdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;

/// Connects pairs of vertices that share a face (Blender's J).
///
/// # Errors
/// [`ModelingError::NotConnectable`] naming the pair.
pub fn connect_vertices(
    mesh: &mut HalfEdgeMesh,
    a: VertexId,
    b: VertexId,
) -> Result<EdgeId, ModelingError> {
    for v in [a, b] {
        if !mesh.is_vertex(v) {
            return Err(ModelingError::Missing(v.into()));
        }
    }
    connect_in_shared_face(mesh, a, b, None)
}
