//! Helpers shared by several modeling operations: input checks, joining
//! two vertices across a face, adding faces back in any order, and the
//! faces around a selection (public: the edit tools use them to turn an
//! edge or vertex selection into faces).

use super::{InvalidResult, ModelingError};
use crate::ids::{EdgeId, FaceId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;

pub(super) fn check_faces(mesh: &HalfEdgeMesh, faces: &[FaceId]) -> Result<(), ModelingError> {
    if faces.is_empty() {
        return Err(ModelingError::Empty("no faces"));
    }
    match faces.iter().find(|f| !mesh.is_face(**f)) {
        Some(f) => Err(ModelingError::Missing((*f).into())),
        None => Ok(()),
    }
}

/// Joins two vertices of a common face by a new edge (MEF), preferring `hint`.
pub(super) fn connect_in_shared_face(
    mesh: &mut HalfEdgeMesh,
    a: VertexId,
    b: VertexId,
    hint: Option<FaceId>,
) -> Result<EdgeId, ModelingError> {
    let incoming = |mesh: &HalfEdgeMesh, v: VertexId| -> Vec<HalfEdgeId> {
        mesh.vertex_outgoing(v)
            .map(|h| h.twin())
            .filter(|h| mesh.face(*h).is_some())
            .collect()
    };
    let ins_a = incoming(mesh, a);
    let ins_b = incoming(mesh, b);
    let view: &HalfEdgeMesh = mesh;
    let mut pairs: Vec<(HalfEdgeId, HalfEdgeId)> = Vec::new();
    for &ha in &ins_a {
        for &hb in &ins_b {
            if view.face(hb) == view.face(ha) {
                pairs.push((ha, hb));
            }
        }
    }
    pairs.sort_by_key(|(ha, _)| view.face(*ha) != hint);
    if mesh.find_edge(a, b).is_some() {
        return Err(ModelingError::NotConnectable { a, b });
    }
    let (ha, hb) = *pairs
        .first()
        .ok_or(ModelingError::NotConnectable { a, b })?;
    Ok(mesh.make_edge_face(ha, hb)?.0)
}

/// Adds polygons with pmp's `add_face`, which relinks boundary fans: a face
/// that cannot attach yet may attach once its neighbours are in, so the
/// failed ones are retried until a pass adds nothing. Returns the new faces
/// in the order the polygons were given.
pub(super) fn add_faces_in_any_order(
    work: &mut HalfEdgeMesh,
    polygons: Vec<Vec<VertexId>>,
    what: &'static str,
) -> Result<Vec<FaceId>, ModelingError> {
    let mut added = vec![None; polygons.len()];
    let mut pending: Vec<usize> = (0..polygons.len()).collect();
    while !pending.is_empty() {
        let before = pending.len();
        let mut failed = Vec::new();
        let mut last_error = None;
        for i in pending {
            match work.add_face(&polygons[i]) {
                Ok(f) => added[i] = Some(f),
                Err(e) => {
                    last_error = Some(e);
                    failed.push(i);
                }
            }
        }
        if failed.len() == before {
            return Err(ModelingError::Invalid(InvalidResult::NonManifold {
                operation: what,
                error: last_error,
            }));
        }
        pending = failed;
    }
    Ok(added.into_iter().flatten().collect())
}

/// The faces touching any of the edges.
pub fn faces_around_edges(mesh: &HalfEdgeMesh, edges: &[EdgeId]) -> Vec<FaceId> {
    let mut out: Vec<FaceId> = edges
        .iter()
        .filter(|e| mesh.is_edge(**e))
        .flat_map(|&e| mesh.edge_faces(e))
        .flatten()
        .collect();
    out.sort();
    out.dedup();
    out
}

/// The faces touching any of the vertices.
pub fn faces_around_vertices(mesh: &HalfEdgeMesh, vertices: &[VertexId]) -> Vec<FaceId> {
    let mut out: Vec<FaceId> = vertices
        .iter()
        .filter(|v| mesh.is_vertex(**v))
        .flat_map(|&v| mesh.vertex_faces(v))
        .collect();
    out.sort();
    out.dedup();
    out
}
