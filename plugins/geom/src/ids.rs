//! Typed element handles of a half-edge mesh.
//!
//! Ids are plain indices into the mesh's element arrays. They are monotonic and
//! never reused: removing an element marks its slot dead, and only an explicit
//! [`crate::HalfEdgeMesh::compacted`] renumbers. Edge `e` owns the two
//! half-edges `2e` and `2e + 1`, so a half-edge's twin is `h ^ 1` (the pmp-library
//! convention) and needs no stored link.

use serde::{Deserialize, Serialize};
use std::fmt;

/// Raw value used inside the mesh records for "no element".
pub(crate) const NONE: u32 = u32::MAX;

macro_rules! typed_id {
    ($(#[$doc:meta])* $name:ident, $prefix:literal) => {
        $(#[$doc])*
        #[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
        #[serde(transparent)]
        pub struct $name(pub u32);

        impl $name {
            /// The index of this element in the mesh's arrays.
            #[inline]
            pub fn index(self) -> usize {
                self.0 as usize
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, concat!($prefix, "{}"), self.0)
            }
        }
    };
}

typed_id!(
    /// A vertex of a half-edge mesh.
    VertexId,
    "v"
);
typed_id!(
    /// A directed half-edge; its twin is `HalfEdgeId(h ^ 1)`.
    HalfEdgeId,
    "h"
);
typed_id!(
    /// An undirected edge, made of half-edges `2e` and `2e + 1`.
    EdgeId,
    "e"
);
typed_id!(
    /// A face (a polygon bounded by one loop of half-edges).
    FaceId,
    "f"
);

impl HalfEdgeId {
    /// The opposite half-edge of the same edge.
    #[inline]
    pub fn twin(self) -> HalfEdgeId {
        HalfEdgeId(self.0 ^ 1)
    }

    /// The edge this half-edge belongs to.
    #[inline]
    pub fn edge(self) -> EdgeId {
        EdgeId(self.0 >> 1)
    }
}

impl EdgeId {
    /// One of the two half-edges of this edge (`side` 0 or 1).
    #[inline]
    pub fn halfedge(self, side: u32) -> HalfEdgeId {
        HalfEdgeId((self.0 << 1) | (side & 1))
    }
}

/// An element of any kind, for selections and error messages.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum ElementId {
    /// A vertex.
    Vertex(VertexId),
    /// An undirected edge.
    Edge(EdgeId),
    /// A face.
    Face(FaceId),
    /// A directed half-edge (named by errors about a half-edge argument).
    HalfEdge(HalfEdgeId),
}

impl ElementId {
    /// The bare id (`v3`, `e5`, `f0`, `h7`), without the kind's name that
    /// [`Display`](fmt::Display) puts in front.
    pub fn short(&self) -> &dyn fmt::Display {
        match self {
            ElementId::Vertex(v) => v,
            ElementId::Edge(e) => e,
            ElementId::Face(f) => f,
            ElementId::HalfEdge(h) => h,
        }
    }

    /// What kind of element this is.
    pub fn kind(&self) -> ElementKind {
        match self {
            ElementId::Vertex(_) => ElementKind::Vertex,
            ElementId::Edge(_) => ElementKind::Edge,
            ElementId::Face(_) => ElementKind::Face,
            ElementId::HalfEdge(_) => ElementKind::HalfEdge,
        }
    }
}

impl fmt::Display for ElementId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", self.kind(), self.short())
    }
}

impl From<VertexId> for ElementId {
    fn from(v: VertexId) -> Self {
        ElementId::Vertex(v)
    }
}

impl From<EdgeId> for ElementId {
    fn from(e: EdgeId) -> Self {
        ElementId::Edge(e)
    }
}

impl From<FaceId> for ElementId {
    fn from(f: FaceId) -> Self {
        ElementId::Face(f)
    }
}

impl From<HalfEdgeId> for ElementId {
    fn from(h: HalfEdgeId) -> Self {
        ElementId::HalfEdge(h)
    }
}

/// The kind of a mesh element, for messages that name a kind without an id
/// (displayed as `vertex`, `half-edge`, `edge`, `face`).
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum ElementKind {
    /// Vertices.
    Vertex,
    /// Directed half-edges.
    HalfEdge,
    /// Undirected edges.
    Edge,
    /// Faces.
    Face,
}

impl fmt::Display for ElementKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ElementKind::Vertex => "vertex",
            ElementKind::HalfEdge => "half-edge",
            ElementKind::Edge => "edge",
            ElementKind::Face => "face",
        })
    }
}
