//! Loop cut (Blender's Ctrl+R) and the edge ring it cuts across.

use super::ModelingError;
use super::common::connect_in_shared_face;
use crate::ids::{EdgeId, FaceId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;

/// The edge ring through `edge`: half-edges crossing a strip of quads, all
/// pointing the same way, and whether the ring closes.
pub fn edge_ring(mesh: &HalfEdgeMesh, edge: EdgeId) -> (Vec<HalfEdgeId>, bool) {
    let start = edge.halfedge(0);
    let is_quad = |h: HalfEdgeId| mesh.face(h).is_some_and(|f| mesh.face_degree(f) == 4);
    let step = |h: HalfEdgeId| -> Option<HalfEdgeId> {
        is_quad(h).then(|| mesh.next(mesh.next(h)).twin())
    };
    let mut forward = vec![start];
    let mut h = start;
    while let Some(n) = step(h) {
        if n == start {
            return (forward, true);
        }
        if forward.contains(&n) || forward.len() > mesh.edge_count() {
            break;
        }
        forward.push(n);
        h = n;
    }
    // Open ring: also walk backwards from the start through the other side.
    let mut backward = Vec::new();
    let mut h = start.twin();
    while let Some(n) = step(h) {
        let parallel = n.twin();
        if forward.contains(&parallel) || backward.contains(&parallel) {
            break;
        }
        backward.push(parallel);
        h = n;
    }
    backward.reverse();
    backward.extend(forward);
    (backward, false)
}

/// Loop cut (Blender's Ctrl+R): `cuts` new edge loops across the ring of
/// quads through `edge`, evenly spaced. Returns the new edges along the loops.
///
/// # Errors
/// [`ModelingError::NoRing`] when no quad touches the edge,
/// [`ModelingError::Parameter`] for 0 or more than 64 cuts.
pub fn loop_cut(
    mesh: &mut HalfEdgeMesh,
    edge: EdgeId,
    cuts: u32,
) -> Result<Vec<EdgeId>, ModelingError> {
    if !mesh.is_edge(edge) {
        return Err(ModelingError::Missing(edge.into()));
    }
    if !(1..=64).contains(&cuts) {
        return Err(ModelingError::Parameter {
            what: "cuts",
            allowed: "1 to 64",
            value: cuts.to_string(),
        });
    }
    let (ring, closed) = edge_ring(mesh, edge);
    let quad_between = |a: HalfEdgeId| mesh.face(a).is_some_and(|f| mesh.face_degree(f) == 4);
    if !ring
        .iter()
        .any(|&h| quad_between(h) || quad_between(h.twin()))
    {
        return Err(ModelingError::NoRing { edge });
    }
    // Faces to cut: between consecutive ring half-edges (each ring half-edge's own face).
    let faces: Vec<FaceId> = ring
        .iter()
        .take(if closed { ring.len() } else { ring.len() - 1 })
        .map(|&h| mesh.face(h).expect("ring half-edges lie on quads"))
        .collect();
    // New vertices on every ring edge, ordered from the half-edge's origin.
    let mut rails: Vec<Vec<VertexId>> = Vec::with_capacity(ring.len());
    for &h in &ring {
        let (pa, pb) = (mesh.position(mesh.origin(h)), mesh.position(mesh.target(h)));
        let e = h.edge();
        // `split_edge` keeps the edge from its first vertex `s` to the new one,
        // so split at the points farthest from `s` first.
        let from_start = mesh.edge_vertices(e)[0] == mesh.origin(h);
        let order: Vec<usize> = if from_start {
            (0..cuts as usize).rev().collect()
        } else {
            (0..cuts as usize).collect()
        };
        let mut made = vec![VertexId(0); cuts as usize];
        for k in order {
            made[k] = mesh.split_edge(e, pa.lerp(pb, (k + 1) as f64 / (cuts + 1) as f64))?;
        }
        rails.push(made);
    }
    let mut new_edges = Vec::new();
    for (i, &f) in faces.iter().enumerate() {
        let next_rail = &rails[(i + 1) % rails.len()];
        for k in 0..cuts as usize {
            let (a, b) = (rails[i][k], next_rail[k]);
            let e = connect_in_shared_face(mesh, a, b, Some(f))?;
            new_edges.push(e);
        }
    }
    Ok(new_edges)
}
