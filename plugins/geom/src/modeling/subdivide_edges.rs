//! Splitting edges into equal parts (edge subdivide).

use super::ModelingError;
use crate::ids::{EdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;

/// Splits each edge into `cuts + 1` equal parts. Returns the new vertices.
///
/// # Errors
/// [`ModelingError::Missing`], [`ModelingError::Parameter`] (1 to 64 cuts).
pub fn subdivide_edges(
    mesh: &mut HalfEdgeMesh,
    edges: &[EdgeId],
    cuts: u32,
) -> Result<Vec<VertexId>, ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no edges"));
    }
    if let Some(e) = edges.iter().find(|e| !mesh.is_edge(**e)) {
        return Err(ModelingError::Missing((*e).into()));
    }
    if !(1..=64).contains(&cuts) {
        return Err(ModelingError::Parameter {
            what: "cuts",
            allowed: "1 to 64",
            value: cuts.to_string(),
        });
    }
    let mut out = Vec::new();
    for &e in edges {
        let [a, b] = mesh.edge_vertices(e);
        let (pa, pb) = (mesh.position(a), mesh.position(b));
        // Split from the far end so the original edge keeps shrinking towards `a`.
        for k in (1..=cuts).rev() {
            out.push(mesh.split_edge(e, pa.lerp(pb, k as f64 / (cuts + 1) as f64))?);
        }
    }
    Ok(out)
}
