//! OpenUSD in and out (issue 32). Export writes `.usda` text itself (the
//! mapping is Hedra's; the text is simple and exact); import reads
//! `.usda`, `.usdc`, `.usdz` and `.usd` through the `openusd` crate's
//! composed stage, with an asset resolver that refuses every reference,
//! payload or sublayer outside the file's folder ([`import`]). See
//! `docs/exchange.md` (USD) for what the format keeps and drops.
//!
//! Layout of a file Hedra writes: a root `Xform` `/Hedra` (the default
//! prim); under it one `Xform` per node, nested as the nodes are, carrying
//! the node's exact local transform as `xformOp:translate` (double3),
//! `xformOp:orient` (quatd) and `xformOp:scale` (double3), in that order
//! (USD's row-vector product scale·orient·translate is Hedra's T·R·S); the
//! node's geometry is a child prim `Geom` of that Xform (`Mesh`,
//! `NurbsPatch` or `NurbsCurves`) with no transform, marked with
//! `hedra:nodeGeometry`, so that gprims are never nested (usdchecker's
//! encapsulation rule).

mod export;
mod import;

pub use export::to_usd;
pub use import::{UsdError, usd_from_path};

/// The namespace of the attributes that keep what USD cannot say.
pub(crate) const HEDRA: &str = "hedra:";

/// Prim-count limit of an import: past it the file is refused (a hostile
/// file could list millions of prims).
pub const MAX_PRIMS: usize = 100_000;

/// Element-count limit of one array attribute (points, indices, knots) of
/// an import.
pub const MAX_ARRAY: usize = 50_000_000;

/// Prim-nesting limit of an import.
pub const MAX_DEPTH: usize = 1_000;
