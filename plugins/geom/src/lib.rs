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
pub mod csg;
pub mod curves;
pub mod ids;
pub mod mesh;
pub mod modeling;
pub mod primitives;
pub mod progressive;
pub mod proportional;
pub mod query;
pub mod subdivision;
pub mod surfaces;
pub mod topology;

// Modules that live inside the connectivity wall, at their old paths.
/// Old name of [`mesh::add_delete`].
#[doc(hidden)]
pub use mesh::add_delete as patch;
pub use mesh::{euler, validate};

// The kernel's public API at the crate root: the mesh and its ids, and the
// main type (and error) of each area. Operations stay in their modules
// (`modeling::extrude_region`, `query::ray_cast`, ...), where their names
// read with the module's.

// Mesh, ids and the errors of building, checking and editing it.
pub use build::{BuildError, RepairReport};
pub use csg::{BooleanError, BooleanOp};
pub use euler::EulerError;
pub use ids::{EdgeId, ElementId, ElementKind, FaceId, HalfEdgeId, VertexId};
pub use mesh::{HalfEdgeMesh, LoopStart, MeshData, MeshDataError, MeshStats, PolygonData};
pub use modeling::{InvalidResult, MergePoint, MirrorAxis, ModelingError, NewFace};
pub use primitives::{Primitive, PrimitiveError};
pub use progressive::{DecimateError, DecimateOptions, DecimateTarget, ProgressiveMesh};
pub use topology::{TopologyCounts, TopologyDelta};
pub use validate::{ValidationError, Violation};

// Subdivision, curves and surfaces.
pub use curves::{Bezier, Curve, CurveError, NurbsCurve};
pub use subdivision::{Creases, Options as SubdivisionOptions, Refiner, SubdivisionError};
pub use surfaces::{BezierSurface, BezierTriangle, BilinearPatch, NurbsSurface, Surface};

// The math types every signature uses.
pub use glam::{DMat4, DQuat, DVec2, DVec3};
