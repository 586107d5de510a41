//! Why a modeling operation refused: [`ModelingError`], shared by every
//! operation in this module.

use crate::build::BuildError;
use crate::euler::EulerError;
use crate::ids::{EdgeId, ElementId, FaceId, VertexId};
use crate::validate::ValidationError;
use glam::DVec3;
use std::fmt;

/// Why a modeling operation refused; the mesh is unchanged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ModelingError {
    /// The operation was given no elements; the text says which kind
    /// (`"no faces"`, `"no edges"`, ...).
    #[error("nothing selected: {0}")]
    Empty(&'static str),
    /// An element given is not live in the mesh.
    #[error("{} does not exist", .0.short())]
    Missing(ElementId),
    /// A loop cut on an edge with no quad beside it.
    #[error("{edge} has no quad on either side: a loop cut needs a ring of quads")]
    NoRing {
        /// The edge given.
        edge: EdgeId,
    },
    /// An operation on boundary edges (fill holes, boundary extrude) got
    /// an edge with faces on both sides.
    #[error("{edge} is not on a boundary (there is no hole to fill there)")]
    NotBoundary {
        /// The interior edge.
        edge: EdgeId,
    },
    /// Connecting two vertices that have no face in common, or already
    /// share an edge.
    #[error("{a} and {b} do not share a face, or are already joined by an edge")]
    NotConnectable {
        /// The first vertex.
        a: VertexId,
        /// The second vertex.
        b: VertexId,
    },
    /// A numeric argument (width, offset, cut count, ...) out of range.
    #[error("{what} must be {allowed}, got {value}")]
    Parameter {
        /// The argument's name.
        what: &'static str,
        /// Its allowed range, as words.
        allowed: &'static str,
        /// The refused value, formatted (a number or a vector).
        value: String,
    },
    /// Dissolving faces that make up a whole closed shell.
    #[error(
        "the faces around {face} close a whole shell: dissolving them would leave no surface (select fewer faces)"
    )]
    ClosedShell {
        /// One face of the shell.
        face: FaceId,
    },
    /// The mesh the operation built would be invalid.
    #[error("the result would not be a valid mesh: {0}")]
    Invalid(InvalidResult),
    /// Merge by distance found no pair of vertices close enough.
    #[error("no two of the vertices are within {distance} of each other: nothing to merge")]
    NothingToMerge {
        /// The merge distance given.
        distance: f64,
    },
    /// A spin profile edge with faces on both sides: it has no open side
    /// for the sweep to grow from.
    #[error(
        "{edge} has faces on both sides: a spin profile of edges must be boundary edges (spin the faces instead)"
    )]
    SpinEdgeNotBoundary {
        /// The interior edge.
        edge: EdgeId,
    },
    /// A full-turn spin whose profile has a face beside it: the last step
    /// would come back onto that face, giving the edge a third face.
    #[error(
        "a full turn would bring the sweep back onto {face} beside {edge}: spin less than 360 degrees, or spin a profile with nothing beside it"
    )]
    FullTurnMeetsFace {
        /// The profile edge the face is beside.
        edge: EdgeId,
        /// The face beside the profile.
        face: FaceId,
    },
    /// A knife point farther from every face than the tolerance (it
    /// must lie on the surface, as a viewport pick does).
    #[error("knife point {index} at {point} is not on the mesh surface")]
    NotOnSurface {
        /// The point's position in the path, from 0.
        index: usize,
        /// The point, in the mesh's space.
        point: DVec3,
    },
    /// A knife path that splits no edge and no face: its points lie inside
    /// one face without reaching an edge.
    #[error("the knife path crosses no edge: nothing to cut")]
    NothingToCut,
    /// Rip on an edge that already has no face on one side.
    #[error("{edge} is already on a boundary: only edges between two faces can be ripped")]
    RipOpenEdge {
        /// The boundary edge.
        edge: EdgeId,
    },
    /// Rip on an edge ripped alone with both ends inside the surface: its
    /// two copies would join the same two vertices.
    #[error(
        "{edge} is ripped alone and both its ends are inside the mesh: its two copies would join the same two vertices (rip a path of two or more edges, or one that reaches a boundary)"
    )]
    RipLoneEdge {
        /// The edge.
        edge: EdgeId,
    },
    /// Vertex rip at a corner with nothing to rip.
    #[error("{vertex} is not a corner of {face} with an edge between two faces: nothing to rip")]
    RipCorner {
        /// The vertex.
        vertex: VertexId,
        /// The face it was to be ripped off.
        face: FaceId,
    },
    /// An Euler operator the operation uses refused.
    #[error(transparent)]
    Euler(#[from] EulerError),
}

/// Why the mesh an operation built was not valid (the payload of
/// [`ModelingError::Invalid`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum InvalidResult {
    /// The validator's report on the finished mesh.
    #[error("{0}")]
    Validation(ValidationError),
    /// A new face could not be added.
    #[error("{face}: {error}")]
    Face {
        /// Which face the operation was adding.
        face: NewFace,
        /// Why [`HalfEdgeMesh::add_face`](crate::HalfEdgeMesh::add_face)
        /// refused it.
        error: EulerError,
    },
    /// Welding would leave a face that visits one vertex twice.
    #[error("welding would make {face} meet itself at a vertex")]
    FaceMeetsItself {
        /// The face.
        face: FaceId,
    },
    /// A vertex to be welded away has edges without faces.
    #[error("{vertex} has edges without faces; delete them before welding")]
    WireEdges {
        /// The vertex.
        vertex: VertexId,
    },
    /// No remaining face could be added in any order.
    #[error("{operation} would make the surface non-manifold ({})", OptionalError(.error))]
    NonManifold {
        /// The operation, as the message names it (`"the bevel"`,
        /// `"welding"`).
        operation: &'static str,
        /// The last refusal of `add_face`, if any.
        error: Option<EulerError>,
    },
    /// Copies of the mesh (a mirror or an array), welded where they meet,
    /// do not form a manifold, consistently oriented surface (a merge
    /// distance so large that a copy meets itself, or copies that overlap
    /// along more than a seam). The builder's error names input indices of
    /// the copies, not the source mesh's ids.
    #[error("{operation} would not make a manifold surface: {error}")]
    Copies {
        /// The operation, as the message names it (`"the mirror"`,
        /// `"the array"`).
        operation: &'static str,
        /// Why the strict build refused the welded copies.
        error: BuildError,
    },
}

impl From<ValidationError> for InvalidResult {
    fn from(e: ValidationError) -> Self {
        InvalidResult::Validation(e)
    }
}

impl From<ValidationError> for ModelingError {
    fn from(e: ValidationError) -> Self {
        ModelingError::Invalid(InvalidResult::Validation(e))
    }
}

impl From<InvalidResult> for ModelingError {
    fn from(e: InvalidResult) -> Self {
        ModelingError::Invalid(e)
    }
}

/// Displays an optional error as its message, or nothing.
struct OptionalError<'a>(&'a Option<EulerError>);

impl fmt::Display for OptionalError<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Some(e) => write!(f, "{e}"),
            None => Ok(()),
        }
    }
}

/// The face an operation failed to add, in [`InvalidResult::Face`].
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum NewFace {
    /// A side quad of a region extrusion, on the boundary edge `a`–`b`.
    Side {
        /// Start of the boundary edge.
        a: VertexId,
        /// End of the boundary edge.
        b: VertexId,
    },
    /// A moved copy of a face of an extruded region.
    Cap,
    /// The quad of a boundary-edge extrusion, on the edge `a`–`b`.
    BoundaryEdge {
        /// Start of the boundary edge.
        a: VertexId,
        /// End of the boundary edge.
        b: VertexId,
    },
    /// Quad `index` of a bridge, counted from the first loop's first edge.
    BridgeQuad {
        /// The quad's position along the loops, from 0.
        index: usize,
    },
    /// The mirror image of a face.
    Mirrored,
}

impl fmt::Display for NewFace {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NewFace::Side { a, b } => write!(f, "side of edge {a}-{b}"),
            NewFace::Cap => write!(f, "cap"),
            NewFace::BoundaryEdge { a, b } => write!(f, "edge {a}-{b}"),
            NewFace::BridgeQuad { index } => write!(f, "bridge quad {index}"),
            NewFace::Mirrored => write!(f, "mirrored face"),
        }
    }
}
