//! Rip: tearing the surface open along edges (Blender's V in edit mode,
//! `editmesh_rip.cc`), on the mesh's cut operator
//! ([`HalfEdgeMesh::cut_edges`]).
//!
//! As in Blender, every selected edge becomes two boundary edges, one per
//! side, and the vertices along the selection fall apart into one copy per
//! side; where the selection ends inside the surface the end vertex stays
//! one vertex, so the rip opens as a slit. Blender then starts a grab on
//! the side nearest the mouse; here [`RipResult`] gives both sides' vertices
//! and the GUI chooses.

use super::ModelingError;
use crate::ids::{EdgeId, FaceId, VertexId};
use crate::mesh::HalfEdgeMesh;
use std::collections::{BTreeMap, BTreeSet};

/// What [`rip_edges`] made.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RipResult {
    /// For each ripped edge (in the order given, repeats dropped): the edge,
    /// which keeps the face of its half-edge 0, and its new copy, which
    /// took the face of half-edge 1.
    pub edges: Vec<(EdgeId, EdgeId)>,
    /// Each vertex that was duplicated (it keeps one wedge of its faces)
    /// and its new copies (at the same position), one per other wedge.
    pub copies: Vec<(VertexId, Vec<VertexId>)>,
    /// The vertices along the rip on one side: the ends of the edges of
    /// that side. Sides are followed along each connected path, starting
    /// with the first edge's half-edge 0 side; a slit's end vertex is on
    /// both sides. Grab one side to open the rip (Blender grabs the side
    /// nearest the mouse).
    pub side_a: Vec<VertexId>,
    /// The vertices along the rip on the other side.
    pub side_b: Vec<VertexId>,
}

/// Rips the mesh along `edges` (Blender's Rip on an edge selection): each
/// edge, which must have a face on both sides, becomes two boundary
/// edges, and vertices along the edges are duplicated so the two sides are
/// disconnected. Interior vertices with two or more ripped edges and
/// boundary vertices with one or more are duplicated (one copy per wedge of
/// faces between ripped edges and the boundary); an interior vertex with
/// one ripped edge (a path ending inside the surface) stays one vertex,
/// the closed end of the slit. ΔE = +n for n edges, ΔV = Σ(wedges − 1).
///
/// A ripped edge whose two ends are both slit ends (an edge ripped alone,
/// inside the surface) is refused: its two copies would join the same two
/// vertices. Blender's edge split refuses such an edge too ("single marked
/// edges unconnected to any other marked edges", `bm_edgesplit_validate_seams`).
///
/// # Errors
/// [`ModelingError::Empty`], [`ModelingError::Missing`],
/// [`ModelingError::RipOpenEdge`] for an edge already on a boundary,
/// [`ModelingError::RipLoneEdge`] for an edge ripped alone inside the
/// surface, [`ModelingError::Euler`] when the cut refuses (an edge with one
/// face on both sides). The mesh is unchanged on error.
///
/// Complexity: O(n + Σ valence) and one validation of the mesh.
pub fn rip_edges(mesh: &mut HalfEdgeMesh, edges: &[EdgeId]) -> Result<RipResult, ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no edges"));
    }
    if let Some(e) = edges.iter().find(|e| !mesh.is_edge(**e)) {
        return Err(ModelingError::Missing((*e).into()));
    }
    if let Some(&edge) = edges.iter().find(|e| mesh.is_boundary_edge(**e)) {
        return Err(ModelingError::RipOpenEdge { edge });
    }
    let mut cuts: BTreeMap<VertexId, usize> = BTreeMap::new();
    let unique: BTreeSet<EdgeId> = edges.iter().copied().collect();
    for &e in &unique {
        for v in mesh.edge_vertices(e) {
            *cuts.entry(v).or_default() += 1;
        }
    }
    let stays = |v: VertexId| cuts[&v] == 1 && !mesh.is_boundary_vertex(v);
    if let Some(&edge) = unique.iter().find(|e| {
        let [a, b] = mesh.edge_vertices(**e);
        stays(a) && stays(b)
    }) {
        return Err(ModelingError::RipLoneEdge { edge });
    }
    let mut trial = mesh.clone();
    let cut = trial.cut_edges(edges)?;
    trial.validate()?;
    let (side_a, side_b) = sides(&trial, &cut.edges);
    *mesh = trial;
    Ok(RipResult {
        edges: cut.edges,
        copies: cut.vertices,
        side_a,
        side_b,
    })
}

/// Follows the two sides along connected rips: an edge touching (at a
/// vertex after the cut) an edge of a known side is on that side.
fn sides(mesh: &HalfEdgeMesh, pairs: &[(EdgeId, EdgeId)]) -> (Vec<VertexId>, Vec<VertexId>) {
    // side[i] = Some(true) when pair i's old edge is on side A.
    let mut side: Vec<Option<bool>> = vec![None; pairs.len()];
    let mut at: BTreeMap<VertexId, Vec<(usize, bool)>> = BTreeMap::new();
    for (i, &(old, new)) in pairs.iter().enumerate() {
        for (e, is_old) in [(old, true), (new, false)] {
            for v in mesh.edge_vertices(e) {
                at.entry(v).or_default().push((i, is_old));
            }
        }
    }
    for first in 0..pairs.len() {
        if side[first].is_some() {
            continue;
        }
        side[first] = Some(true);
        let mut stack = vec![first];
        while let Some(i) = stack.pop() {
            let old_on_a = side[i].expect("assigned before pushed");
            let (old, new) = pairs[i];
            for (e, is_old) in [(old, true), (new, false)] {
                let on_a = is_old == old_on_a;
                for v in mesh.edge_vertices(e) {
                    for &(j, j_old) in &at[&v] {
                        if side[j].is_none() {
                            // Edge (j, j_old) shares v with e: same side.
                            side[j] = Some(if j_old { on_a } else { !on_a });
                            stack.push(j);
                        }
                    }
                }
            }
        }
    }
    let (mut a, mut b) = (BTreeSet::new(), BTreeSet::new());
    for (i, &(old, new)) in pairs.iter().enumerate() {
        let (ea, eb) = if side[i] == Some(true) {
            (old, new)
        } else {
            (new, old)
        };
        a.extend(mesh.edge_vertices(ea));
        b.extend(mesh.edge_vertices(eb));
    }
    (a.into_iter().collect(), b.into_iter().collect())
}

/// Rips vertex `vertex` off face `face` (Blender's Rip on a single vertex,
/// which separates the vertex from the face nearest the mouse): the two
/// edges of the face's corner at the vertex are ripped, so the corner gets
/// a vertex of its own, and a boundary end of those edges is duplicated
/// too. Edges of the corner already on a boundary are left alone.
///
/// Returns the vertex now at the face's corner (the one to grab).
///
/// # Errors
/// [`ModelingError::Missing`], [`ModelingError::RipCorner`] when the vertex
/// is not a corner of the face or both edges of its corner are on a
/// boundary (nothing to rip), and the errors of [`rip_edges`]. The mesh is
/// unchanged on error.
pub fn rip_vertex(
    mesh: &mut HalfEdgeMesh,
    vertex: VertexId,
    face: FaceId,
) -> Result<VertexId, ModelingError> {
    if !mesh.is_vertex(vertex) {
        return Err(ModelingError::Missing(vertex.into()));
    }
    if !mesh.is_face(face) {
        return Err(ModelingError::Missing(face.into()));
    }
    let refuse = ModelingError::RipCorner { vertex, face };
    let corner = mesh
        .face_all_halfedges(face)
        .find(|&h| mesh.origin(h) == vertex)
        .ok_or(refuse.clone())?;
    let edges: Vec<EdgeId> = [mesh.prev(corner).edge(), corner.edge()]
        .into_iter()
        .filter(|&e| !mesh.is_boundary_edge(e))
        .collect();
    if edges.is_empty() {
        return Err(refuse);
    }
    let ripped = rip_edges(mesh, &edges)?;
    let mut same: Vec<VertexId> = vec![vertex];
    if let Some((_, copies)) = ripped.copies.iter().find(|(v, _)| *v == vertex) {
        same.extend(copies);
    }
    Ok(mesh
        .face_all_halfedges(face)
        .map(|h| mesh.origin(h))
        .find(|v| same.contains(v))
        .unwrap_or(vertex))
}

impl RipResult {
    /// The vertices the rip made, in the order of [`copies`](Self::copies).
    pub fn new_vertices(&self) -> Vec<VertexId> {
        self.copies
            .iter()
            .flat_map(|(_, c)| c.iter().copied())
            .collect()
    }
}
