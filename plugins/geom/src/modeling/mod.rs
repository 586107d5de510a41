//! Modeling operations built on the Euler operators: what the edit-mode
//! tools run. Each one checks its input first and returns a named error
//! without changing the mesh, or applies completely.
//!
//! One file per algorithm family (as pmp-library's `algorithms/`), helpers
//! shared between families in `common`, the error in `error`. They reach
//! connectivity only through [`HalfEdgeMesh`](crate::mesh::HalfEdgeMesh)'s
//! API (queries, Euler operators, face add/delete); every operation is
//! re-exported here, so `hedra_geom::modeling::<operation>` is the one path.

mod array;
mod bevel;
mod bisect;
mod bridge;
mod common;
mod connect;
mod copies;
mod delete;
mod dissolve;
mod error;
mod extrude;
mod holes;
mod inset;
mod knife;
mod loop_cut;
mod merge;
mod mirror;
mod normals;
mod rip;
mod slide;
mod spin;
mod subdivide_edges;
mod triangulate;

pub use array::{ArrayOffset, MAX_ARRAY_COUNT, arrayed, arrayed_copies};
pub use bevel::{bevel_edges, bevel_vertices};
pub use bisect::{BisectClear, Bisected, bisect};
pub use bridge::bridge_loops;
pub use common::{faces_around_edges, faces_around_vertices};
pub use connect::connect_vertices;
pub use copies::CopiedMesh;
pub use delete::delete_faces;
pub use dissolve::{dissolve_edges, dissolve_faces, dissolve_vertices};
pub use error::{InvalidResult, ModelingError, NewFace};
pub use extrude::{extrude_boundary_edges, extrude_faces_individual, extrude_region};
pub use holes::{fill_holes, make_holes};
pub use inset::{inset_faces_individual, inset_region};
pub use knife::{KnifeResult, knife};
pub use loop_cut::{edge_ring, loop_cut};
pub use merge::{
    MergePoint, collapse_edges, merge_at_center, merge_by_distance, merge_vertices, weld_vertices,
};
pub use mirror::{MirrorAxis, mirror_vertices, mirrored, mirrored_copies, symmetrize};
pub use normals::{flip_normals, recalculate_normals_outward};
pub use rip::{RipResult, rip_edges, rip_vertex};
pub use slide::slide_edges;
pub use spin::{
    AXIS_TOLERANCE, FULL_TURN_TOLERANCE, MAX_SPIN_STEPS, SpinProfile, SpinResult, screw, spin,
};
pub use subdivide_edges::subdivide_edges;
pub(crate) use triangulate::quad_pairing;
pub use triangulate::{
    DEFAULT_JOIN_LIMIT, TriangulateMethod, quad_fold, triangulate_faces, tris_to_quads,
};
