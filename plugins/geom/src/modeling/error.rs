//! Why a modeling operation refused: [`ModelingError`], shared by every
//! operation in this module.

use crate::euler::EulerError;
use crate::ids::{EdgeId, FaceId, VertexId};

/// Why a modeling operation refused; the mesh is unchanged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ModelingError {
    #[error("nothing selected: {0}")]
    Empty(&'static str),
    #[error("{0} does not exist")]
    Missing(String),
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
    Invalid(String),
    #[error("no two of the vertices are within {distance} of each other: nothing to merge")]
    NothingToMerge { distance: f64 },
    #[error(transparent)]
    Euler(#[from] EulerError),
}
