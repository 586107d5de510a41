//! Hedra's document, free of Bevy: the scene graph, the commands users and
//! scripts issue, reversible transactions and the undo history, the
//! versioned `.hedra.ron` file and exports.

pub mod command;
pub mod construction;
pub mod csg;
pub mod elements;
pub mod eval;
pub mod export;
pub mod file;
pub mod fuzz;
pub mod gltf;
pub mod history;
pub mod import;
pub mod input;
pub mod join;
pub mod kept;
pub mod modifiers;
pub mod preview;
pub mod recovery;
pub mod reference;
pub mod render;
pub mod report;
pub mod scene;
pub mod script;
pub mod session;
pub mod smooth;
pub mod step;
pub mod usd;

pub use command::{Command, CommandError, NodeRef};
pub use elements::{EdgeSet, FaceSet, ProfileSet, VertexSet};
pub use history::{History, NodeChange, Transaction};
pub use kept::{KeptMesh, KeptMeshContent};
pub use modifiers::{
    ArrayModifier, DecimateModifier, DecimateRecord, EvaluationError, MeshModifier, MirrorModifier,
};
pub use scene::{
    CornerAttributes, CurveContent, Document, Hierarchy, MeshContent, Node, NodeContent, NodeFacts,
    NodeId, NodeTransform, Shading, SubdivisionModifier, SurfaceShape,
};
pub use session::{Applied, Session};
