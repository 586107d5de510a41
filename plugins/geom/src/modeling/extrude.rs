//! Extrude: faces one by one or as a region (Blender's E), and open
//! boundary edges; region extrude and inset share [`rebuild_region`].

use super::common::check_faces;
use super::{InvalidResult, ModelingError, NewFace};
use crate::euler::EulerError;
use crate::ids::{EdgeId, FaceId, VertexId};
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;

/// Extrudes each face on its own along its normal by `distance`
/// (Blender's "extrude individual faces"). Returns the new side faces.
///
/// # Errors
/// [`ModelingError::Missing`] for a dead face, [`ModelingError::Parameter`]
/// for a non-finite distance.
pub fn extrude_faces_individual(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    distance: f64,
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    if !distance.is_finite() {
        return Err(ModelingError::Parameter {
            what: "distance",
            allowed: "finite",
            value: distance.to_string(),
        });
    }
    let mut sides = Vec::new();
    for &f in faces {
        let n = mesh.face_normal(f);
        sides.extend(mesh.extrude_face(f, n * distance)?);
    }
    Ok(sides)
}

/// Extrudes a region of faces as one (Blender's E): the region is lifted by
/// `offset`, side quads join its boundary to where it was, and faces inside
/// the region stay joined. Vertices inside the region keep their ids; the
/// boundary gets new vertices and the caps are new faces, returned in the
/// order of `faces`. Built from [`HalfEdgeMesh::delete_faces`] and
/// [`HalfEdgeMesh::add_face`]; the result is validated before it replaces
/// the mesh.
///
/// # Errors
/// [`ModelingError::Missing`], [`ModelingError::Parameter`] for a non-finite
/// offset, [`ModelingError::Invalid`] when the region's shape cannot be
/// extruded manifold (for example two regions touching at one vertex).
pub fn extrude_region(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    offset: DVec3,
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    if !offset.is_finite() {
        return Err(ModelingError::Parameter {
            what: "offset",
            allowed: "finite",
            value: format!("{offset:?}"),
        });
    }
    rebuild_region(mesh, faces, |_, p| p + offset, |_, p| p + offset)
}

/// Replaces a region of faces by caps over new outline vertices placed by
/// `outline` and old inner vertices moved by `inner`, joined to the old
/// outline by side quads: the shared core of region extrude and inset.
pub(super) fn rebuild_region(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    outline: impl Fn(VertexId, DVec3) -> DVec3,
    inner: impl Fn(VertexId, DVec3) -> DVec3,
) -> Result<Vec<FaceId>, ModelingError> {
    let mut region: Vec<FaceId> = faces.to_vec();
    region.sort();
    region.dedup();
    let in_region = |f: Option<FaceId>| f.is_some_and(|f| region.binary_search(&f).is_ok());
    let boundary: Vec<(VertexId, VertexId)> = region
        .iter()
        .flat_map(|&f| mesh.face_halfedges(f))
        .filter(|&h| !in_region(mesh.face(h.twin())))
        .map(|h| (mesh.origin(h), mesh.target(h)))
        .collect();
    let polys: Vec<Vec<VertexId>> = faces
        .iter()
        .map(|&f| mesh.face_vertices(f).collect())
        .collect();
    let mut work = mesh.clone();
    work.delete_faces(&region, true);
    let mut copy = std::collections::HashMap::new();
    let mut moved = std::collections::HashSet::new();
    for p in &polys {
        for &v in p {
            if boundary.iter().any(|&(a, _)| a == v) {
                if let std::collections::hash_map::Entry::Vacant(slot) = copy.entry(v) {
                    let at = outline(v, work.position(v));
                    slot.insert(work.add_vertex(at)?);
                }
            } else if moved.insert(v) {
                let at = inner(v, work.position(v));
                work.set_position(v, at);
            }
        }
    }
    let lift = |v: VertexId| copy.get(&v).copied().unwrap_or(v);
    let invalid = |face: NewFace, error: EulerError| {
        ModelingError::Invalid(InvalidResult::Face { face, error })
    };
    for &(a, b) in &boundary {
        work.add_face(&[a, b, lift(b), lift(a)])
            .map_err(|e| invalid(NewFace::Side { a, b }, e))?;
    }
    let mut caps = Vec::with_capacity(polys.len());
    for p in &polys {
        let lifted: Vec<VertexId> = p.iter().map(|&v| lift(v)).collect();
        caps.push(
            work.add_face(&lifted)
                .map_err(|e| invalid(NewFace::Cap, e))?,
        );
    }
    work.validate()?;
    *mesh = work;
    Ok(caps)
}

/// Extrudes boundary edges (Blender's E on edges of an open border): each
/// gets a new quad on its open side, reaching to copies of its ends moved by
/// `offset`; neighbouring edges share the copies. Returns the new faces.
///
/// # Errors
/// [`ModelingError::NotBoundary`] for an edge with faces on both sides,
/// [`ModelingError::Invalid`] when the quads cannot be added manifold; the
/// mesh is unchanged on error.
pub fn extrude_boundary_edges(
    mesh: &mut HalfEdgeMesh,
    edges: &[EdgeId],
    offset: DVec3,
) -> Result<Vec<FaceId>, ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no edges"));
    }
    if !offset.is_finite() {
        return Err(ModelingError::Parameter {
            what: "offset",
            allowed: "finite",
            value: format!("{offset:?}"),
        });
    }
    let mut sides = Vec::with_capacity(edges.len());
    for &e in edges {
        if !mesh.is_edge(e) {
            return Err(ModelingError::Missing(e.into()));
        }
        let h = [e.halfedge(0), e.halfedge(1)]
            .into_iter()
            .find(|&h| mesh.is_boundary_halfedge(h))
            .ok_or(ModelingError::NotBoundary { edge: e })?;
        sides.push((mesh.origin(h), mesh.target(h)));
    }
    let mut work = mesh.clone();
    let mut copy = std::collections::HashMap::new();
    for &(x, y) in &sides {
        for v in [x, y] {
            if let std::collections::hash_map::Entry::Vacant(slot) = copy.entry(v) {
                slot.insert(work.add_vertex(work.position(v) + offset)?);
            }
        }
    }
    let mut out = Vec::with_capacity(sides.len());
    for &(x, y) in &sides {
        let f = work
            .add_face(&[x, y, copy[&y], copy[&x]])
            .map_err(|error| {
                ModelingError::Invalid(InvalidResult::Face {
                    face: NewFace::BoundaryEdge { a: x, b: y },
                    error,
                })
            })?;
        out.push(f);
    }
    work.validate()?;
    *mesh = work;
    Ok(out)
}
