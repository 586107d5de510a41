//! Why a modeling operation refused: [`ModelingError`], shared by every
//! operation in this module.

use crate::euler::EulerError;
use crate::ids::{EdgeId, ElementId, FaceId, VertexId};
use crate::validate::ValidationError;
use std::fmt;

/// Why a modeling operation refused; the mesh is unchanged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ModelingError {
    #[error("nothing selected: {0}")]
    Empty(&'static str),
    #[error("{} does not exist", .0.short())]
    Missing(ElementId),
    #[error("{edge} has no quad on either side: a loop cut needs a ring of quads")]
    NoRing { edge: EdgeId },
    #[error("{edge} is not on a boundary (there is no hole to fill there)")]
    NotBoundary { edge: EdgeId },
    #[error("{a} and {b} do not share a face, or are already joined by an edge")]
    NotConnectable { a: VertexId, b: VertexId },
    #[error("{what} must be {allowed}, got {value}")]
    Parameter {
        what: &'static str,
        allowed: &'static str,
        value: String,
    },
    #[error(
        "the faces around {face} close a whole shell: dissolving them would leave no surface (select fewer faces)"
    )]
    ClosedShell { face: FaceId },
    #[error("the result would not be a valid mesh: {0}")]
    Invalid(InvalidResult),
    #[error("no two of the vertices are within {distance} of each other: nothing to merge")]
    NothingToMerge { distance: f64 },
    #[error(transparent)]
    Euler(#[from] EulerError),
}

/// Why the mesh an operation built was not valid (the payload of
/// [`ModelingError::Invalid`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum InvalidResult {
    #[error("{0}")]
    Validation(ValidationError),
    #[error("{face}: {error}")]
    Face { face: NewFace, error: EulerError },
    #[error("welding would make {face} meet itself at a vertex")]
    FaceMeetsItself { face: FaceId },
    #[error("{vertex} has edges without faces; delete them before welding")]
    WireEdges { vertex: VertexId },
    #[error("{operation} would make the surface non-manifold ({})", OptionalError(.error))]
    NonManifold {
        operation: &'static str,
        error: Option<EulerError>,
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
    Side { a: VertexId, b: VertexId },
    /// A moved copy of a face of an extruded region.
    Cap,
    /// The quad of a boundary-edge extrusion, on the edge `a`–`b`.
    BoundaryEdge { a: VertexId, b: VertexId },
    /// Quad `index` of a bridge, counted from the first loop's first edge.
    BridgeQuad { index: usize },
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
