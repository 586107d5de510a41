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
//!   `euler` (rip, vertex split and the Euler operators as commands),
//!   `creases` (creases and the subdivision modifier), `modifiers` (the
//!   Mirror/Array modifier stack), `shapes` (curves and surfaces).

mod constructions;
mod creases;
mod csg;
mod euler;
mod joins;
mod mesh;
mod modifiers;
mod nodes;
mod plan;
mod shapes;
mod spec;
mod to_nurbs;

pub use plan::set_validate_edits;
pub use spec::{Command, Corner, CurveSpec, EulerOp, NodeRef, ParameterDirection, SurfaceSpec};
/// The default tolerance of [`Command::ConvertSubdivisionToNurbs`], a
/// fraction of the cage's bounding-box diagonal.
pub use to_nurbs::DEFAULT_TOLERANCE as DEFAULT_NURBS_TOLERANCE;
pub use to_nurbs::conversion_summary as nurbs_conversion_summary;

use crate::elements::{EdgeSet, ElementError, VertexSet};
use crate::history::Transaction;
use crate::scene::{Document, NodeId};
use hedra_geom::curves::CurveError;
use hedra_geom::subdivision::{self, INFINITE_SHARPNESS};
use hedra_geom::{BuildError, EdgeId, FaceId, PrimitiveError, VertexId};
use plan::Plan;

/// Why an edit refused the elements or values it was given (the node is
/// named by [`CommandError::Element`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EditError {
    /// An element set names nothing or an element the mesh does not have.
    #[error(transparent)]
    Elements(#[from] ElementError),
    /// A move offset or distance with an infinite or NaN component.
    #[error("the offset is not finite")]
    OffsetNotFinite,
    /// [`Command::SetVertexPositions`] names a vertex the mesh does not have.
    #[error("vertex {vertex} does not exist")]
    NoSuchVertex {
        /// The missing id.
        vertex: VertexId,
    },
    /// [`Command::SetVertexPositions`] gives a position that is not finite.
    #[error("vertex {vertex}: position is not finite")]
    PositionNotFinite {
        /// The vertex it was given for.
        vertex: VertexId,
    },
    /// [`Command::LoopCut`]'s edge set names other than one edge.
    #[error("a loop cut needs exactly one edge, {edges:?} names {count}")]
    LoopCutEdges {
        /// The set as given.
        edges: EdgeSet,
        /// How many edges it names.
        count: usize,
    },
    /// [`Command::ConnectVertices`]'s vertex set names other than two vertices.
    #[error("connecting needs exactly two vertices, {vertices:?} names {count}")]
    ConnectVertices {
        /// The set as given.
        vertices: VertexSet,
        /// How many vertices it names.
        count: usize,
    },
    /// A set that must name exactly one element names none or several.
    #[error("{role} must name exactly one element, it names {count}")]
    NotOne {
        /// The argument, as the message names it (`` "`vertex`" ``).
        role: &'static str,
        /// How many elements it names.
        count: usize,
    },
    /// Two vertices a command needs joined by an edge are not.
    #[error("no edge runs from {a} to {b}")]
    NotJoined {
        /// The first vertex.
        a: VertexId,
        /// The second vertex.
        b: VertexId,
    },
    /// An Euler operator that joins corners on edges was given a lone vertex.
    #[error("{vertex} is a lone vertex; this operator needs a corner between two edges")]
    LoneCorner {
        /// The lone vertex.
        vertex: VertexId,
    },
    /// [`Command::RecalculateNormals`] on a mesh with nothing to turn.
    #[error("the mesh already faces outwards (or is open)")]
    AlreadyOutwards,
    /// [`Command::ApplySubdivision`] without `levels` on a node without a
    /// subdivision modifier.
    #[error("has no subdivision modifier (give `levels` to subdivide anyway)")]
    NoSubdivisionModifier,
    /// [`Command::SetCreaseTaper`]'s edges are not one chain from `from`.
    #[error(transparent)]
    Taper(#[from] hedra_geom::subdivision::TaperError),
}

impl From<crate::csg::CsgError> for CommandError {
    fn from(e: crate::csg::CsgError) -> Self {
        CommandError::Csg(Box::new(e))
    }
}

/// Why a command was refused. The document is unchanged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CommandError {
    /// No node has this id or name.
    #[error("{0} does not exist")]
    UnknownNode(NodeRef),
    /// A mesh command (or shading, subdivision) names a node that is not a mesh.
    #[error("{node} is not a mesh")]
    NotAMesh {
        /// The node, as `'name' (#id)`.
        node: String,
    },
    /// [`Command::AddKeptMesh`]'s faces name no vertex, or a point is not finite.
    #[error(transparent)]
    KeptMesh(crate::kept::KeptMeshError),
    /// [`Command::MakeManifold`] on a node that is not a kept mesh.
    #[error("{node} is not a kept (non-manifold) mesh: there is nothing to make manifold")]
    NotKept {
        /// The node, as `'name' (#id)`.
        node: String,
    },
    /// [`Command::MakeManifold`] could keep no face of a kept mesh.
    #[error("{node} cannot be made manifold: {reason}")]
    Repair {
        /// The node, as `'name' (#id)`.
        node: String,
        /// Why no face could be kept.
        reason: String,
    },
    /// [`Command::SetPrimitive`] on a mesh that is not an unedited primitive
    /// of the same kind.
    #[error("{node} was not made from a primitive (or has been edited since)")]
    NotAPrimitive {
        /// The node, as `'name' (#id)`.
        node: String,
    },
    /// [`Command::Reparent`] would make a node its own ancestor.
    #[error("cannot parent {node} to {parent}: it would become its own ancestor")]
    Cycle {
        /// The node being moved, as `'name' (#id)`.
        node: String,
        /// The parent asked for, one of its descendants (or itself).
        parent: String,
    },
    /// A transform with a non-finite value, a zero rotation quaternion or a
    /// zero scale component.
    #[error("invalid transform for {node}: values must be finite and scale non-zero")]
    BadTransform {
        /// The node it was for, as `'name' (#id)`.
        node: String,
    },
    /// A name that is empty or only white space.
    #[error("a node name cannot be empty")]
    EmptyName,
    /// The command would change nothing (or has nothing to act on, such as a
    /// zero rotation axis); the message says why.
    #[error("nothing to do: {0}")]
    Nothing(&'static str),
    /// A primitive's parameters are out of range.
    #[error(transparent)]
    Primitive(#[from] PrimitiveError),
    /// [`Command::AddMesh`]'s polygons do not form a valid half-edge mesh.
    #[error("bad mesh: {0}")]
    Mesh(#[from] BuildError),
    /// A mesh edit refused its elements or values.
    #[error("{node}: {error}")]
    Element {
        /// The node, as `'name' (#id)`.
        node: String,
        /// What was wrong.
        error: EditError,
    },
    /// The kernel refused a mesh operation (it would break the mesh).
    #[error("{node}: {error}")]
    Modeling {
        /// The node, as `'name' (#id)`.
        node: String,
        /// The kernel's reason.
        error: hedra_geom::ModelingError,
    },
    /// A curve or surface command with bad data (knots, weights, degrees,
    /// indices).
    #[error("{node}: {error}")]
    Curve {
        /// The node being added or edited.
        node: String,
        /// The kernel's reason.
        error: CurveError,
    },
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
    /// A CSG command names a node that is not a CSG node.
    #[error("{node} is not a CSG node")]
    NotACsg {
        /// The node, as `'name' (#id)`.
        node: String,
    },
    /// A CSG node or boolean has no solid; the error names the nodes.
    #[error(transparent)]
    Csg(Box<crate::csg::CsgError>),
    /// A curve command names a node that is not a curve.
    #[error("{node} is not a curve")]
    NotACurve {
        /// The node, as `'name' (#id)`.
        node: String,
    },
    /// A curve or surface command names a node that is neither.
    #[error("{node} is not a curve or surface")]
    NotAShape {
        /// The node, as `'name' (#id)`.
        node: String,
    },
    /// Subdividing the mesh failed (a Loop scheme on non-triangles, say).
    #[error("{node}: {error}")]
    Subdivision {
        /// The node, as `'name' (#id)`.
        node: String,
        /// The kernel's reason.
        error: subdivision::SubdivisionError,
    },
    /// [`Command::ConvertSubdivisionToNurbs`] on a mesh without a
    /// subdivision modifier.
    #[error("{node} has no subdivision modifier to convert")]
    NoSubdivision {
        /// The node, as `'name' (#id)`.
        node: String,
    },
    /// [`Command::ConvertSubdivisionToNurbs`] on a node whose stack runs a
    /// modifier after subdivision: the shown surface is not a limit surface.
    #[error(
        "{node}: a modifier runs after subdivision; apply it or move subdivision last to convert"
    )]
    ModifierAfterSubdivision {
        /// The node, as `'name' (#id)`.
        node: String,
    },
    /// A conversion tolerance that is not a positive finite fraction.
    #[error("the tolerance must be a positive fraction of the size, not {0}")]
    Tolerance(f64),
    /// Converting the limit surface to NURBS failed (not Catmull-Clark, a
    /// face with an inner ring, …).
    #[error("{node}: {error}")]
    ToNurbs {
        /// The node, as `'name' (#id)`.
        node: String,
        /// The kernel's reason.
        error: subdivision::to_nurbs::ToNurbsError,
    },
    /// A crease sharpness outside 0 to 10 (or not finite).
    #[error("sharpness must be between 0 and {INFINITE_SHARPNESS} (infinitely sharp), not {0}")]
    Sharpness(f64),
    /// A modifier stack that cannot be evaluated or applied: the error
    /// names the modifier (by its number in the stack, from 1) and the
    /// kernel's reason.
    #[error("{node}: {error}")]
    Modifier {
        /// The node, as `'name' (#id)`.
        node: String,
        /// Which modifier refused and why.
        error: crate::modifiers::EvaluationError,
    },
    /// [`Command::Decimate`] refused: a mesh that is not manifold
    /// polygons, or a target below what it can be simplified to.
    #[error("{node}: {error}")]
    Decimate {
        /// The node, as `'name' (#id)`.
        node: String,
        /// The kernel's reason.
        error: hedra_geom::progressive::DecimateError,
    },
    /// A modifier with values out of range (an array count of 0, a
    /// negative merge distance).
    #[error("{node}: {problem}")]
    ModifierValue {
        /// The node, as `'name' (#id)`.
        node: String,
        /// What is out of range.
        problem: crate::modifiers::ModifierProblem,
    },
    /// A modifier index past the end of the node's stack.
    #[error("{node} has no modifier {} (its stack has {count})", index + 1)]
    NoModifier {
        /// The node, as `'name' (#id)`.
        node: String,
        /// The index given, from 0 (the message counts from 1).
        index: usize,
        /// How many modifiers the stack has.
        count: usize,
    },
    /// [`Command::ApplyModifiers`] would apply a modifier that runs after
    /// subdivision (the result would change).
    #[error(
        "{node}: subdivision runs after {position} of the stack's modifiers; apply only those, or move subdivision last"
    )]
    SubdivisionFirst {
        /// The node, as `'name' (#id)`.
        node: String,
        /// How many modifiers run before subdivision.
        position: usize,
    },
    /// A node made from curves could not be made (or made again after a
    /// change of its inputs: the change is refused; apply the node first
    /// to keep the change).
    #[error("{node}: {error}")]
    Construction {
        /// The node made, as `'name' (#id)` (or `'name'` while being added).
        node: String,
        /// Why.
        error: crate::construction::ConstructionError,
    },
    /// [`Command::SetConstruction`] or [`Command::ApplyConstruction`] on a
    /// node that does not follow curves.
    #[error("{node} was not made from curves (or has been applied)")]
    NoConstruction {
        /// The node, as `'name' (#id)`.
        node: String,
    },
    /// [`Command::SetConstruction`] on a cap node: its recipe is its
    /// surface's.
    #[error("{node} is a cap of {parent}: change {parent} instead")]
    CapOfConstruction {
        /// The cap node, as `'name' (#id)`.
        node: String,
        /// The surface node it caps.
        parent: String,
    },
    /// A G1 join that cannot be made, or kept after a change (the change is
    /// refused; break the join first to keep it).
    #[error("G1 join of {quad} and {triangle}: {error}")]
    Join {
        /// The patch node, as `'name' (#id)`.
        quad: String,
        /// The triangle node, as `'name' (#id)`.
        triangle: String,
        /// Why.
        error: crate::join::JoinError,
    },
    /// [`Command::BreakG1Join`] on a node in no join.
    #[error("{node} is not in a G1 join")]
    NotJoined {
        /// The node, as `'name' (#id)`.
        node: String,
    },
    /// A subdivision level above [`subdivision::MAX_LEVEL`].
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
            created_edges: Vec::new(),
            notes: Vec::new(),
        };
        plan.run(cmd)?;
        let mut notes = std::mem::take(&mut plan.notes);
        notes.extend(plan.follow_constructions(cmd)?);
        notes.extend(plan.follow_joins(cmd)?);
        if plan.changes.is_empty() {
            return Err(CommandError::Nothing("the command changes nothing"));
        }
        let label = if notes.is_empty() {
            cmd.label()
        } else {
            format!("{} ({})", cmd.label(), notes.join("; "))
        };
        Ok(Decision {
            transaction: Transaction {
                serial,
                label,
                command: Some(cmd.clone()),
                changes: plan.changes,
                next_id_before: self.next_node_id,
                next_id_after: plan.next_id,
            },
            created_faces: plan.created_faces,
            created_edges: plan.created_edges,
        })
    }
}

/// A decided command and the mesh elements it makes.
#[derive(Clone, Debug, PartialEq)]
pub struct Decision {
    /// The transaction to apply and push on the history.
    pub transaction: Transaction,
    /// The faces a region extrude makes (its caps), a region inset makes
    /// (the inner faces) or an edge bevel makes (its strips, then its corner
    /// patches), in the order of the command's elements; empty for other
    /// commands. Not part of the history: only tools use it.
    pub created_faces: Vec<FaceId>,
    /// The edges a knife cut makes or runs along, in path order (Blender
    /// selects them after the cut); empty for other commands. Not part of
    /// the history: only tools use it.
    pub created_edges: Vec<EdgeId>,
}
