//! Hedra's modeling kernel, free of Bevy: half-edge meshes with typed ids, the
//! validator, building from indexed polygons, primitives; the Euler operators,
//! modeling operations, subdivision, curves and surfaces build on these.
//!
//! All math is in `f64` ([`glam::DVec3`]); render code converts to `f32`.
//!
//! Connectivity is private to [`mesh`]: the Euler operators, face
//! add/delete, orientation reversal, the bulk builders and the validator
//! live there as submodules; everything else (modeling operations,
//! subdivision, queries) uses the mesh's public API.

pub mod build;
pub mod curves;
pub mod ids;
pub mod mesh;
pub mod modeling;
pub mod primitives;
pub mod query;
pub mod subdivision;
pub mod surfaces;
pub mod topology;

// Modules that live inside the connectivity wall, at their old paths.
/// Old name of [`add_delete`].
#[doc(hidden)]
pub use mesh::add_delete as patch;
pub use mesh::{euler, validate};

pub use build::{BuildError, RepairReport};
pub use euler::EulerError;
pub use glam::{DMat4, DQuat, DVec2, DVec3};
pub use ids::{EdgeId, ElementId, FaceId, HalfEdgeId, VertexId};
pub use mesh::{HalfEdgeMesh, LoopStart, MeshData, MeshStats};
pub use modeling::ModelingError;
pub use primitives::{Primitive, PrimitiveError};
pub use validate::{ValidationError, Violation};
