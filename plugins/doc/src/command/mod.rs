//! User-level commands: what the GUI issues and what `hedra run` scripts list.
//!
//! A command is decided against the current document and turns into a
//! [`Transaction`] (Fornjot's "commands decide, events apply"). Deciding
//! never mutates, so a failing command leaves the document untouched.
//!
//! - `spec`: the [`Command`] enum and the specs it carries;
//! - `plan`: the [`Plan`](plan::Plan) a command is decided into, its helpers,
//!   and the dispatch by family to
//! - `nodes` (scene tree and node properties), `mesh` (mesh modeling),
//!   `creases` (creases and the subdivision modifier), `shapes` (curves and surfaces).

mod creases;
mod mesh;
mod nodes;
mod plan;
mod shapes;
mod spec;

pub use spec::{Command, CurveSpec, NodeRef, ParameterDirection, SurfaceSpec};

use crate::elements::{EdgeSet, ElementError, VertexSet};
use crate::history::Transaction;
use crate::scene::{Document, NodeId};
use hedra_geom::curves::CurveError;
use hedra_geom::subdivision::{self, INFINITE_SHARPNESS};
use hedra_geom::{BuildError, FaceId, PrimitiveError, VertexId};
use plan::Plan;

/// Why an edit refused the elements or values it was given (the node is
/// named by [`CommandError::Element`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EditError {
    /// An element set names nothing or an element the mesh does not have.
    #[error(transparent)]
    Elements(#[from] ElementError),
    #[error("the offset is not finite")]
    OffsetNotFinite,
    #[error("vertex {vertex} does not exist")]
    NoSuchVertex { vertex: VertexId },
    #[error("vertex {vertex}: position is not finite")]
    PositionNotFinite { vertex: VertexId },
    #[error("a loop cut needs exactly one edge, {edges:?} names {count}")]
    LoopCutEdges { edges: EdgeSet, count: usize },
    #[error("connecting needs exactly two vertices, {vertices:?} names {count}")]
    ConnectVertices { vertices: VertexSet, count: usize },
    #[error("the mesh already faces outwards (or is open)")]
    AlreadyOutwards,
    #[error("has no subdivision modifier (give `levels` to subdivide anyway)")]
    NoSubdivisionModifier,
}

/// Why a command was refused. The document is unchanged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CommandError {
    #[error("{0} does not exist")]
    UnknownNode(NodeRef),
    #[error("{node} is not a mesh")]
    NotAMesh { node: String },
    #[error("{node} was not made from a primitive (or has been edited since)")]
    NotAPrimitive { node: String },
    #[error("cannot parent {node} to {parent}: it would become its own ancestor")]
    Cycle { node: String, parent: String },
    #[error("invalid transform for {node}: values must be finite and scale non-zero")]
    BadTransform { node: String },
    #[error("a node name cannot be empty")]
    EmptyName,
    #[error("nothing to do: {0}")]
    Nothing(&'static str),
    #[error(transparent)]
    Primitive(#[from] PrimitiveError),
    #[error("bad mesh: {0}")]
    Mesh(#[from] BuildError),
    #[error("{node}: {error}")]
    Element { node: String, error: EditError },
    #[error("{node}: {error}")]
    Modeling {
        node: String,
        error: hedra_geom::ModelingError,
    },
    #[error("{node}: {error}")]
    Curve { node: String, error: CurveError },
    /// The profile node a surface is revolved or extruded from does not exist.
    #[error("{node}: {profile} does not exist")]
    NoProfile {
        /// The surface being made, as `surface 'name'`.
        node: String,
        /// The profile as the command named it.
        profile: NodeRef,
    },
    /// The profile node a surface is revolved or extruded from is not a curve.
    #[error("{node}: {profile} is not a curve")]
    ProfileNotACurve {
        /// The surface being made, as `surface 'name'`.
        node: String,
        /// The profile as the command named it.
        profile: NodeRef,
    },
    #[error("{node} is not a curve or surface")]
    NotAShape { node: String },
    #[error("{node}: {error}")]
    Subdivision {
        node: String,
        error: subdivision::SubdivisionError,
    },
    #[error("sharpness must be between 0 and {INFINITE_SHARPNESS} (infinitely sharp), not {0}")]
    Sharpness(f64),
    #[error("subdivision level {0} is above the maximum of {max}", max = subdivision::MAX_LEVEL)]
    Level(u32),
}

impl Document {
    /// Resolves a node reference.
    ///
    /// # Errors
    /// [`CommandError::UnknownNode`] when no node matches.
    pub fn resolve(&self, r: &NodeRef) -> Result<NodeId, CommandError> {
        match r {
            NodeRef::Id(i) if self.nodes.contains_key(&NodeId(*i)) => Ok(NodeId(*i)),
            NodeRef::Name(n) => self
                .find_by_name(n)
                .map(|n| n.id)
                .ok_or_else(|| CommandError::UnknownNode(r.clone())),
            _ => Err(CommandError::UnknownNode(r.clone())),
        }
    }

    fn label_of(&self, id: NodeId) -> String {
        self.nodes
            .get(&id)
            .map_or_else(|| id.to_string(), |n| format!("'{}' ({id})", n.name))
    }

    /// Decides a command: the transaction it would apply, or why not.
    /// The document is not changed; apply the result with
    /// [`Transaction::apply`].
    ///
    /// # Errors
    /// A [`CommandError`] naming the node or value at fault.
    pub fn decide(&self, cmd: &Command, serial: u64) -> Result<Transaction, CommandError> {
        self.decide_with_result(cmd, serial).map(|d| d.transaction)
    }

    /// As [`Document::decide`], with the mesh elements the command makes,
    /// so that a tool selects exactly those.
    ///
    /// # Errors
    /// As [`Document::decide`].
    pub fn decide_with_result(&self, cmd: &Command, serial: u64) -> Result<Decision, CommandError> {
        let mut plan = Plan {
            doc: self,
            next_id: self.next_node_id,
            changes: Vec::new(),
            created_faces: Vec::new(),
        };
        plan.run(cmd)?;
        if plan.changes.is_empty() {
            return Err(CommandError::Nothing("the command changes nothing"));
        }
        Ok(Decision {
            transaction: Transaction {
                serial,
                label: cmd.label(),
                command: Some(cmd.clone()),
                changes: plan.changes,
                next_id_before: self.next_node_id,
                next_id_after: plan.next_id,
            },
            created_faces: plan.created_faces,
        })
    }
}

/// A decided command and the mesh elements it makes.
#[derive(Clone, Debug, PartialEq)]
pub struct Decision {
    pub transaction: Transaction,
    /// The faces a region extrude makes (its caps) or a region inset makes
    /// (the inner faces), in the order of the command's faces; empty for
    /// other commands. Not part of the history: only tools use it.
    pub created_faces: Vec<FaceId>,
}
