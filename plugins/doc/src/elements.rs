//! Mesh elements named in commands: by id, or by a simple predicate so that
//! scripts do not depend on id order. Positions are in the node's own
//! (local) space.

use glam::DVec3;
use hedra_geom::modeling::SpinProfile;
use hedra_geom::{EdgeId, FaceId, HalfEdgeMesh, VertexId};
use serde::{Deserialize, Serialize};

/// Faces of a mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum FaceSet {
    /// Every face of the mesh.
    All,
    /// These face ids (as `hedra info` and the topology panel show them).
    Ids(Vec<u32>),
    /// Faces whose normal is within `degrees` of `direction`.
    Facing {
        /// The direction in local space; need not be unit length, must not be zero.
        direction: DVec3,
        /// The largest angle between a face normal and `direction`.
        degrees: f64,
    },
    /// The face whose centre is nearest to a point.
    Nearest(DVec3),
    /// For each point, the face whose centre is nearest to it.
    NearestEach(Vec<DVec3>),
}

/// Edges of a mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum EdgeSet {
    /// Every edge of the mesh.
    All,
    /// These edge ids.
    Ids(Vec<u32>),
    /// The edge whose midpoint is nearest to a point.
    Nearest(DVec3),
    /// For each point, the edge whose midpoint is nearest to it.
    NearestEach(Vec<DVec3>),
    /// The edges around the faces of a face set.
    OfFaces(Box<FaceSet>),
}

/// Vertices of a mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum VertexSet {
    /// Every vertex of the mesh.
    All,
    /// These vertex ids, in the given order.
    Ids(Vec<u32>),
    /// The vertex nearest to a point.
    Nearest(DVec3),
    /// For each point, the vertex nearest to it (in that order).
    NearestEach(Vec<DVec3>),
    /// Vertices within `radius` of `center`.
    Within {
        /// The centre in local space.
        center: DVec3,
        /// The distance, inclusive, in local units.
        radius: f64,
    },
    /// The corners of a face set.
    OfFaces(Box<FaceSet>),
    /// The ends of an edge set.
    OfEdges(Box<EdgeSet>),
}

/// What a spin or screw sweeps ([`Command::Spin`](crate::Command::Spin),
/// [`Command::Screw`](crate::Command::Screw)): as Blender's Spin sweeps the
/// selected faces when there are any, and the selected edges otherwise.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum ProfileSet {
    /// A region of faces, swept as a solid: side faces along its outline,
    /// its faces as the end cap (and the start cap when nothing borders it).
    Faces(FaceSet),
    /// Boundary edges, swept as a surface of quads on their open side.
    Edges(EdgeSet),
}

impl ProfileSet {
    /// The kernel's profile for these elements.
    ///
    /// # Errors
    /// [`ElementError`] for a missing id or an empty match.
    pub fn resolve(&self, m: &HalfEdgeMesh) -> Result<SpinProfile, ElementError> {
        Ok(match self {
            ProfileSet::Faces(faces) => SpinProfile::Faces(faces.resolve(m)?),
            ProfileSet::Edges(edges) => SpinProfile::Edges(edges.resolve(m)?),
        })
    }
}

/// An id in a command that the mesh does not have, or a predicate that
/// matched nothing.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ElementError {
    /// [`FaceSet::Ids`] names a face the mesh does not have.
    #[error("face {face} does not exist")]
    NoSuchFace {
        /// The first missing id.
        face: FaceId,
    },
    /// [`EdgeSet::Ids`] names an edge the mesh does not have.
    #[error("edge {edge} does not exist")]
    NoSuchEdge {
        /// The first missing id.
        edge: EdgeId,
    },
    /// [`VertexSet::Ids`] names a vertex the mesh does not have.
    #[error("vertex {vertex} does not exist")]
    NoSuchVertex {
        /// The first missing id.
        vertex: VertexId,
    },
    /// [`FaceSet::Facing`] was given a zero (or non-finite) direction.
    #[error("the direction of Facing is zero")]
    ZeroFacingDirection,
    /// A face set resolved to no face.
    #[error("no face matches {faces:?}")]
    NoFaceMatches {
        /// The set that matched nothing.
        faces: FaceSet,
    },
    /// An edge set resolved to no edge.
    #[error("no edge matches {edges:?}")]
    NoEdgeMatches {
        /// The set that matched nothing.
        edges: EdgeSet,
    },
    /// A vertex set resolved to no vertex.
    #[error("no vertex matches {vertices:?}")]
    NoVertexMatches {
        /// The set that matched nothing.
        vertices: VertexSet,
    },
    /// [`VertexSet::NearestEach`] on a mesh without vertices.
    #[error("the mesh has no vertices")]
    NoVertices,
}

fn nearest<T: Copy>(items: impl Iterator<Item = T>, key: impl Fn(T) -> f64) -> Option<T> {
    items
        .map(|x| (x, key(x)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(x, _)| x)
}

impl FaceSet {
    /// The faces this set names, in a stable order.
    ///
    /// # Errors
    /// [`ElementError`] for a missing id or an empty match.
    pub fn resolve(&self, m: &HalfEdgeMesh) -> Result<Vec<FaceId>, ElementError> {
        let out: Vec<FaceId> = match self {
            FaceSet::All => m.faces().collect(),
            FaceSet::Ids(ids) => {
                let v: Vec<FaceId> = ids.iter().map(|&i| FaceId(i)).collect();
                if let Some(f) = v.iter().find(|f| !m.is_face(**f)) {
                    return Err(ElementError::NoSuchFace { face: *f });
                }
                v
            }
            FaceSet::Facing { direction, degrees } => {
                let d = direction.normalize_or_zero();
                if d == DVec3::ZERO {
                    return Err(ElementError::ZeroFacingDirection);
                }
                let cos = degrees.to_radians().cos();
                m.faces()
                    .filter(|&f| m.face_normal(f).dot(d) >= cos - 1e-12)
                    .collect()
            }
            FaceSet::Nearest(p) => nearest(m.faces(), |f| m.face_centroid(f).distance_squared(*p))
                .into_iter()
                .collect(),
            FaceSet::NearestEach(points) => {
                let mut v: Vec<FaceId> = points
                    .iter()
                    .filter_map(|p| nearest(m.faces(), |f| m.face_centroid(f).distance_squared(*p)))
                    .collect();
                v.dedup();
                v
            }
        };
        if out.is_empty() {
            return Err(ElementError::NoFaceMatches {
                faces: self.clone(),
            });
        }
        Ok(out)
    }
}

impl EdgeSet {
    /// The edges this set names.
    ///
    /// # Errors
    /// [`ElementError`] for a missing id or an empty match.
    pub fn resolve(&self, m: &HalfEdgeMesh) -> Result<Vec<EdgeId>, ElementError> {
        let out: Vec<EdgeId> = match self {
            EdgeSet::All => m.edges().collect(),
            EdgeSet::Ids(ids) => {
                let v: Vec<EdgeId> = ids.iter().map(|&i| EdgeId(i)).collect();
                if let Some(e) = v.iter().find(|e| !m.is_edge(**e)) {
                    return Err(ElementError::NoSuchEdge { edge: *e });
                }
                v
            }
            EdgeSet::Nearest(p) => nearest(m.edges(), |e| m.edge_midpoint(e).distance_squared(*p))
                .into_iter()
                .collect(),
            EdgeSet::NearestEach(points) => {
                let mut v: Vec<EdgeId> = points
                    .iter()
                    .filter_map(|p| nearest(m.edges(), |e| m.edge_midpoint(e).distance_squared(*p)))
                    .collect();
                v.dedup();
                v
            }
            EdgeSet::OfFaces(faces) => {
                let mut v: Vec<EdgeId> = faces
                    .resolve(m)?
                    .into_iter()
                    .flat_map(|f| m.face_halfedges(f).map(|h| h.edge()))
                    .collect();
                v.sort();
                v.dedup();
                v
            }
        };
        if out.is_empty() {
            return Err(ElementError::NoEdgeMatches {
                edges: self.clone(),
            });
        }
        Ok(out)
    }
}

impl VertexSet {
    /// The vertices this set names.
    ///
    /// # Errors
    /// [`ElementError`] for a missing id or an empty match.
    pub fn resolve(&self, m: &HalfEdgeMesh) -> Result<Vec<VertexId>, ElementError> {
        let mut out: Vec<VertexId> = match self {
            VertexSet::All => m.vertices().collect(),
            VertexSet::Ids(ids) => {
                let v: Vec<VertexId> = ids.iter().map(|&i| VertexId(i)).collect();
                if let Some(x) = v.iter().find(|x| !m.is_vertex(**x)) {
                    return Err(ElementError::NoSuchVertex { vertex: *x });
                }
                return Ok(v); // keep the given order (ConnectVertices pairs them)
            }
            VertexSet::Nearest(p) => nearest(m.vertices(), |v| m.position(v).distance_squared(*p))
                .into_iter()
                .collect(),
            VertexSet::NearestEach(points) => {
                let v: Vec<VertexId> = points
                    .iter()
                    .filter_map(|p| nearest(m.vertices(), |v| m.position(v).distance_squared(*p)))
                    .collect();
                if v.is_empty() {
                    return Err(ElementError::NoVertices);
                }
                return Ok(v);
            }
            VertexSet::Within { center, radius } => m
                .vertices()
                .filter(|&v| m.position(v).distance(*center) <= *radius)
                .collect(),
            VertexSet::OfFaces(f) => f
                .resolve(m)?
                .into_iter()
                .flat_map(|f| m.face_vertices(f))
                .collect(),
            VertexSet::OfEdges(e) => e
                .resolve(m)?
                .into_iter()
                .flat_map(|e| m.edge_vertices(e))
                .collect(),
        };
        out.sort();
        out.dedup();
        if out.is_empty() {
            return Err(ElementError::NoVertexMatches {
                vertices: self.clone(),
            });
        }
        Ok(out)
    }
}
