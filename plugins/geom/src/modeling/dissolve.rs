//! Dissolving edges (KEF), valence-2 vertices (KVE) and regions of faces
//! (Blender's dissolve faces).

use super::ModelingError;
use super::common::check_faces;
use crate::ids::{EdgeId, FaceId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;

/// Removes edges between two faces, merging the faces (KEF).
///
/// # Errors
/// The first edge that cannot be dissolved, with the reason; edges before it
/// are dissolved on a copy only, so the mesh stays unchanged on error.
pub fn dissolve_edges(mesh: &mut HalfEdgeMesh, edges: &[EdgeId]) -> Result<(), ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no edges"));
    }
    let mut work = mesh.clone();
    for &e in edges {
        if !work.is_edge(e) {
            return Err(ModelingError::Missing(e.into()));
        }
        work.kill_edge_face(e)?;
    }
    *mesh = work;
    Ok(())
}

/// Removes vertices of valence 2, joining their edges (KVE).
///
/// # Errors
/// As [`dissolve_edges`].
pub fn dissolve_vertices(
    mesh: &mut HalfEdgeMesh,
    vertices: &[VertexId],
) -> Result<(), ModelingError> {
    if vertices.is_empty() {
        return Err(ModelingError::Empty("no vertices"));
    }
    let mut work = mesh.clone();
    for &v in vertices {
        work.join_edges(v)?;
    }
    *mesh = work;
    Ok(())
}

/// A face of `region` whose edge-connected part of the region has no edge
/// on its outline (every neighbour across every edge is in the region):
/// that part is a whole closed shell.
fn closed_shell_in(
    mesh: &HalfEdgeMesh,
    region: &std::collections::BTreeSet<FaceId>,
) -> Option<FaceId> {
    let mut seen = std::collections::BTreeSet::new();
    for &start in region {
        if !seen.insert(start) {
            continue;
        }
        let (mut stack, mut closed) = (vec![start], true);
        while let Some(f) = stack.pop() {
            for h in mesh.face_halfedges(f) {
                match mesh.face(h.twin()) {
                    Some(g) if region.contains(&g) => {
                        if seen.insert(g) {
                            stack.push(g);
                        }
                    }
                    _ => closed = false,
                }
            }
        }
        if closed {
            return Some(start);
        }
    }
    None
}

/// Merges adjacent faces into one by removing the edges between them, and
/// then the edges left dangling inside (Blender's dissolve faces). Returns
/// the faces left of the region.
///
/// # Errors
/// [`ModelingError::Missing`], [`ModelingError::ClosedShell`] when the
/// selection covers a whole closed shell (there is no outline left to make a
/// face of), [`ModelingError::Invalid`] if the result would not be valid; the
/// mesh is unchanged on error.
pub fn dissolve_faces(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    let mut region: std::collections::BTreeSet<FaceId> = faces.iter().copied().collect();
    if let Some(face) = closed_shell_in(mesh, &region) {
        return Err(ModelingError::ClosedShell { face });
    }
    let mut work = mesh.clone();
    // Grow one face over its region neighbours, one neighbour at a time, so
    // the growing face never closes a ring: the edges it shares with the
    // neighbour form one chain; join the chain's inner vertices (KVE) until
    // one edge is left, then remove it (KEF).
    let mut pending: Vec<FaceId> = region.iter().copied().collect();
    while let Some(seed) = pending.pop() {
        if !work.is_face(seed) {
            continue;
        }
        let mut current = seed;
        loop {
            let shared: Vec<HalfEdgeId> = work
                .face_halfedges(current)
                .filter(|&h| {
                    work.face(h.twin())
                        .is_some_and(|g| g != current && region.contains(&g))
                })
                .collect();
            let Some(&first) = shared.first() else { break };
            let other = work.face(first.twin()).expect("filtered");
            let chain: Vec<HalfEdgeId> = shared
                .iter()
                .copied()
                .filter(|&h| work.face(h.twin()) == Some(other))
                .collect();
            // Inner vertices of the chain (both of their edges are in it).
            for &h in &chain {
                let v = work.target(h);
                if chain.iter().any(|&g| work.origin(g) == v) && work.vertex_valence(v) == 2 {
                    let _ = work.join_edges(v);
                }
            }
            let remaining: Vec<HalfEdgeId> = work
                .halfedges()
                .filter(|&h| work.face(h) == Some(current) && work.face(h.twin()) == Some(other))
                .collect();
            let Some(&h) = remaining.first() else { break };
            // Keep `current`: it must be the face of the half-edge 0 side.
            let e = h.edge();
            let survivor_side = if e.halfedge(0) == h { current } else { other };
            match work.kill_edge_face(e) {
                Ok(gone) => {
                    region.remove(&gone);
                    current = survivor_side;
                }
                Err(_) => break,
            }
        }
    }
    // Remove edges left dangling inside the merged faces.
    loop {
        let dangling = work.edges().find(|&e| {
            let [a, b] = work.edge_faces(e);
            a.is_some()
                && a == b
                && region.contains(&a.unwrap())
                && work
                    .edge_vertices(e)
                    .iter()
                    .any(|&v| work.vertex_valence(v) == 1)
        });
        let Some(e) = dangling else { break };
        if work.kill_edge_vertex(e).is_err() {
            break;
        }
    }
    work.validate()?;
    *mesh = work;
    Ok(region.into_iter().collect())
}
