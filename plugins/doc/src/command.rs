//! User-level commands: what the GUI issues and what `hedra run` scripts list.
//!
//! A command is decided against the current document and turns into a
//! [`Transaction`] (Fornjot's "commands decide, events apply"). Deciding
//! never mutates, so a failing command leaves the document untouched.

use crate::elements::{EdgeSet, FaceSet, VertexSet};
use crate::history::{NodeChange, Transaction};
use crate::scene::SurfaceShape;
use crate::scene::{
    CornerAttributes, Document, MeshContent, Node, NodeContent, NodeId, Shading,
    SubdivisionModifier, Transform,
};
use glam::{DQuat, DVec3};
use hedra_geom::curves::nurbs::clamped_uniform_knots;
use hedra_geom::curves::{CurveError, NurbsCurve};
use hedra_geom::modeling::{self, MirrorAxis};
use hedra_geom::subdivision::{self, Creases, INFINITE_SHARPNESS, Refiner};
use hedra_geom::surfaces::{BezierTriangle, NurbsSurface};
use hedra_geom::{
    BuildError, EdgeId, FaceId, HalfEdgeMesh, ModelingError, Primitive, PrimitiveError, VertexId,
};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::sync::Arc;

/// Which parameter of a surface.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum ParameterDirection {
    #[default]
    U,
    V,
}

/// A curve to add.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum CurveSpec {
    /// A NURBS curve; knots default to clamped uniform on [0, 1], weights to 1.
    Nurbs {
        degree: usize,
        points: Vec<DVec3>,
        #[serde(default)]
        weights: Option<Vec<f64>>,
        #[serde(default)]
        knots: Option<Vec<f64>>,
    },
    /// A Bézier curve of degree `points − 1`.
    Bezier { points: Vec<DVec3> },
    /// The exact NURBS circle in the XZ plane.
    Circle { radius: f64 },
    /// A closed periodic B-spline around the points.
    Closed {
        degree: usize,
        points: Vec<DVec3>,
        #[serde(default)]
        weights: Option<Vec<f64>>,
    },
}

/// A surface to add.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum SurfaceSpec {
    /// A NURBS surface of `nu × nv` points (`i * nv + j`); knots default to
    /// clamped uniform, weights to 1.
    Nurbs {
        degree_u: usize,
        degree_v: usize,
        nu: usize,
        nv: usize,
        points: Vec<DVec3>,
        #[serde(default)]
        weights: Option<Vec<f64>>,
        #[serde(default)]
        knots_u: Option<Vec<f64>>,
        #[serde(default)]
        knots_v: Option<Vec<f64>>,
    },
    /// A tensor-product Bézier patch of `nu × nv` points.
    Bezier {
        nu: usize,
        nv: usize,
        points: Vec<DVec3>,
    },
    /// A Bézier triangle: (n+1)(n+2)/2 points, rows of equal i.
    Triangle {
        degree: usize,
        points: Vec<DVec3>,
    },
    Plane {
        size: f64,
    },
    Sphere {
        radius: f64,
    },
    Cylinder {
        radius: f64,
        height: f64,
    },
    /// The curve of another node revolved around the Y axis.
    Revolve {
        profile: NodeRef,
    },
    /// The curve of another node swept along a direction.
    Extrude {
        profile: NodeRef,
        direction: DVec3,
    },
}

fn curve_from_spec(spec: &CurveSpec) -> Result<NurbsCurve, CurveError> {
    match spec {
        CurveSpec::Nurbs {
            degree,
            points,
            weights,
            knots,
        } => NurbsCurve::new(
            *degree,
            knots
                .clone()
                .unwrap_or_else(|| clamped_uniform_knots(*degree, points.len())),
            points.clone(),
            weights.clone().unwrap_or_else(|| vec![1.0; points.len()]),
        ),
        CurveSpec::Bezier { points } => {
            let degree = points.len().saturating_sub(1).max(1);
            NurbsCurve::clamped(degree, points.clone())
        }
        CurveSpec::Circle { radius } => {
            if !(radius.is_finite() && *radius > 0.0) {
                return Err(CurveError::Parameter(format!(
                    "a circle's radius must be positive, not {radius}"
                )));
            }
            Ok(NurbsCurve::circle(DVec3::ZERO, *radius))
        }
        CurveSpec::Closed {
            degree,
            points,
            weights,
        } => NurbsCurve::periodic(
            *degree,
            points.clone(),
            weights.clone().unwrap_or_else(|| vec![1.0; points.len()]),
        ),
    }
}

/// A node named by id or by (unique) name, so scripts need not know ids.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum NodeRef {
    Id(u64),
    Name(String),
}

impl fmt::Display for NodeRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NodeRef::Id(i) => write!(f, "node #{i}"),
            NodeRef::Name(n) => write!(f, "node '{n}'"),
        }
    }
}

impl From<NodeId> for NodeRef {
    fn from(id: NodeId) -> Self {
        NodeRef::Id(id.0)
    }
}

/// Everything a user can do to a document. Each variant is documented with
/// a RON example in `docs/commands.md`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Command {
    /// Adds a primitive mesh node.
    AddPrimitive {
        primitive: Primitive,
        #[serde(default)]
        name: Option<String>,
        #[serde(default)]
        parent: Option<NodeRef>,
        #[serde(default)]
        transform: Transform,
    },
    /// Adds a mesh from explicit positions and polygons (vertex index lists,
    /// counter-clockwise seen from outside).
    AddMesh {
        name: String,
        positions: Vec<DVec3>,
        polygons: Vec<Vec<u32>>,
        #[serde(default)]
        parent: Option<NodeRef>,
        #[serde(default)]
        transform: Transform,
    },
    /// Adds an empty (grouping) node.
    AddEmpty {
        name: String,
        #[serde(default)]
        parent: Option<NodeRef>,
        #[serde(default)]
        transform: Transform,
    },
    /// Rebuilds a primitive node with new parameters ("adjust last operation").
    SetPrimitive {
        node: NodeRef,
        primitive: Primitive,
    },
    /// Sets local transforms of one or more nodes in one step.
    SetTransforms {
        nodes: Vec<(NodeRef, Transform)>,
    },
    /// Moves nodes by an offset in their parent's space.
    Translate {
        nodes: Vec<NodeRef>,
        offset: DVec3,
    },
    /// Rotates nodes about their own origin around an axis (degrees).
    Rotate {
        nodes: Vec<NodeRef>,
        axis: DVec3,
        degrees: f64,
    },
    /// Multiplies nodes' scale.
    Scale {
        nodes: Vec<NodeRef>,
        factor: DVec3,
    },
    Rename {
        node: NodeRef,
        name: String,
    },
    /// Gives a node a new parent (`None` for the root). With `keep_world`
    /// the node stays where it is in the world.
    Reparent {
        node: NodeRef,
        parent: Option<NodeRef>,
        #[serde(default = "yes")]
        keep_world: bool,
    },
    SetVisible {
        nodes: Vec<NodeRef>,
        visible: bool,
    },
    /// Flat or smooth shading of mesh nodes.
    SetShading {
        nodes: Vec<NodeRef>,
        shading: Shading,
    },
    /// Adds, changes or (with `None`) removes the subdivision modifier of
    /// mesh nodes.
    SetSubdivision {
        nodes: Vec<NodeRef>,
        modifier: Option<SubdivisionModifier>,
    },
    /// Replaces the cage by its subdivision (at `levels`, or the modifier's
    /// viewport level) and removes the modifier; creases that are left after
    /// the refinement stay on the new edges.
    ApplySubdivision {
        node: NodeRef,
        #[serde(default)]
        levels: Option<u32>,
    },
    /// Deletes nodes with their descendants.
    Delete {
        nodes: Vec<NodeRef>,
    },
    /// Copies nodes with their descendants; copies get new ids and names.
    Duplicate {
        nodes: Vec<NodeRef>,
    },

    // ----- curves and surfaces (control points in the node's local space) -----
    /// Adds a curve node.
    AddCurve {
        name: String,
        curve: CurveSpec,
        #[serde(default)]
        parent: Option<NodeRef>,
        #[serde(default)]
        transform: Transform,
    },
    /// Adds a surface node.
    AddSurface {
        name: String,
        surface: SurfaceSpec,
        #[serde(default)]
        parent: Option<NodeRef>,
        #[serde(default)]
        transform: Transform,
    },
    /// Moves control points of a curve or surface (by index, as `hedra
    /// info --json` counts them; NURBS surfaces: `i * nv + j`).
    SetControlPoints {
        node: NodeRef,
        points: Vec<(u32, DVec3)>,
    },
    /// Sets the weights of control points (each must be positive).
    SetWeights {
        node: NodeRef,
        weights: Vec<(u32, f64)>,
    },
    /// Inserts a knot without changing the shape (surfaces: in `direction`).
    InsertKnot {
        node: NodeRef,
        at: f64,
        #[serde(default)]
        direction: ParameterDirection,
    },
    /// Raises the degree by one without changing the shape (surfaces: in
    /// `direction`).
    ElevateDegree {
        node: NodeRef,
        #[serde(default)]
        direction: ParameterDirection,
    },

    // ----- mesh editing (element positions in the node's local space) -----
    /// Moves vertices by an offset.
    MoveVertices {
        node: NodeRef,
        vertices: VertexSet,
        offset: DVec3,
    },
    /// Sets vertex positions (what the edit-mode move tool sends).
    SetVertexPositions {
        node: NodeRef,
        positions: Vec<(u32, DVec3)>,
    },
    /// Extrudes each face on its own along its normal.
    ExtrudeFaces {
        node: NodeRef,
        faces: FaceSet,
        distance: f64,
    },
    /// Extrudes faces as one region along their average normal; faces
    /// inside the region stay joined.
    ExtrudeRegion {
        node: NodeRef,
        faces: FaceSet,
        distance: f64,
    },
    /// Insets each face on its own: a border `thickness` wide, the inner face
    /// pushed by `depth` along the normal.
    InsetFaces {
        node: NodeRef,
        faces: FaceSet,
        thickness: f64,
        #[serde(default)]
        depth: f64,
    },
    /// Insets faces as one region: a border `thickness` wide inside the
    /// region's outline, the region pushed by `depth` along its normal.
    InsetRegion {
        node: NodeRef,
        faces: FaceSet,
        thickness: f64,
        #[serde(default)]
        depth: f64,
    },
    /// Cuts `cuts` evenly spaced edge loops across the ring of quads through one edge.
    LoopCut {
        node: NodeRef,
        edge: EdgeSet,
        #[serde(default = "one")]
        cuts: u32,
    },
    /// Splits edges into `cuts + 1` equal parts.
    SubdivideEdges {
        node: NodeRef,
        edges: EdgeSet,
        #[serde(default = "one")]
        cuts: u32,
    },
    /// Joins two vertices of one face by a new edge, splitting the face.
    ConnectVertices {
        node: NodeRef,
        vertices: VertexSet,
    },
    /// Splits faces into triangles along their ear-clipping diagonals.
    Triangulate {
        node: NodeRef,
        faces: FaceSet,
    },
    /// Sets the subdivision crease sharpness of edges: 0 is smooth, 10
    /// infinitely sharp, values between fade out after that many levels.
    SetEdgeCrease {
        node: NodeRef,
        edges: EdgeSet,
        sharpness: f64,
    },
    /// Sets the subdivision corner sharpness of vertices (0 … 10).
    SetVertexCrease {
        node: NodeRef,
        vertices: VertexSet,
        sharpness: f64,
    },
    /// Moves every cage vertex onto the limit surface of its subdivision
    /// (the node's modifier options, or Catmull-Clark).
    SnapToLimit {
        node: NodeRef,
    },
    /// Removes edges, merging the faces on their two sides.
    DissolveEdges {
        node: NodeRef,
        edges: EdgeSet,
    },
    /// Removes vertices of valence 2, joining their edges.
    DissolveVertices {
        node: NodeRef,
        vertices: VertexSet,
    },
    /// Reverses every face of the mesh.
    FlipNormals {
        node: NodeRef,
    },
    /// Turns a closed mesh that faces inwards outwards (no change otherwise).
    RecalculateNormals {
        node: NodeRef,
    },
    /// Deletes faces, keeping their edges: each becomes a hole.
    MakeHoles {
        node: NodeRef,
        faces: FaceSet,
    },
    /// Fills the boundary loops through the given edges with a face each.
    FillHoles {
        node: NodeRef,
        edges: EdgeSet,
    },
    /// Collapses each edge into a vertex at its midpoint.
    CollapseEdges {
        node: NodeRef,
        edges: EdgeSet,
    },
    /// Extrudes boundary edges: a quad on each edge's open side, reaching to
    /// copies of its ends moved by `offset`.
    ExtrudeEdges {
        node: NodeRef,
        edges: EdgeSet,
        offset: DVec3,
    },
    /// Mirrors vertices across the plane through their median perpendicular to an axis.
    MirrorVertices {
        node: NodeRef,
        vertices: VertexSet,
        axis: MirrorAxis,
    },
    /// Replaces the negative side of the mesh by a mirror image of the positive side.
    Symmetrize {
        node: NodeRef,
        axis: MirrorAxis,
    },
    /// Slides edge chains along the edges beside them; `factor` in [-1, 1]
    /// picks the side by its sign.
    SlideEdges {
        node: NodeRef,
        edges: EdgeSet,
        factor: f64,
    },
    /// Bevels edges `width` wide; more than one segment rounds the bevel.
    BevelEdges {
        node: NodeRef,
        edges: EdgeSet,
        width: f64,
        #[serde(default = "one")]
        segments: u32,
    },
    /// Cuts vertices off with a face through the points `width` along
    /// their edges (vertex bevel).
    BevelVertices {
        node: NodeRef,
        vertices: VertexSet,
        width: f64,
    },
    /// Merges faces into one by removing the edges between them.
    DissolveFaces {
        node: NodeRef,
        faces: FaceSet,
    },
    /// Deletes faces with the edges and vertices only they use.
    DeleteFaces {
        node: NodeRef,
        faces: FaceSet,
    },
    /// Deletes edges with the faces around them.
    DeleteEdges {
        node: NodeRef,
        edges: EdgeSet,
    },
    /// Deletes vertices with the faces around them.
    DeleteVertices {
        node: NodeRef,
        vertices: VertexSet,
    },
    /// Merges vertices into one at their centre, the first or the last
    /// given; vertices not joined by edges are welded.
    MergeVertices {
        node: NodeRef,
        vertices: VertexSet,
        #[serde(default, skip_serializing_if = "is_default")]
        at: hedra_geom::modeling::MergePoint,
    },
    /// Welds vertices closer than `distance` to each other (all of the
    /// mesh's unless `vertices` is given).
    MergeByDistance {
        node: NodeRef,
        #[serde(default = "all_vertices")]
        vertices: VertexSet,
        distance: f64,
    },
    /// Joins two boundary loops (named by some of their edges) with quads.
    BridgeLoops {
        node: NodeRef,
        edges: EdgeSet,
    },
}

use crate::scene::{one, yes};

fn all_vertices() -> VertexSet {
    VertexSet::All
}

fn is_default<T: Default + PartialEq>(value: &T) -> bool {
    *value == T::default()
}

/// Round primitives start smooth, boxy ones flat, as in most modelers.
fn primitive_shading(p: &Primitive) -> Shading {
    match p {
        Primitive::UvSphere { .. } | Primitive::IcoSphere { .. } | Primitive::Torus { .. } => {
            Shading::Smooth
        }
        _ => Shading::Flat,
    }
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
    #[error("{node}: {message}")]
    Element { node: String, message: String },
    #[error("{node}: {error}")]
    Modeling {
        node: String,
        error: hedra_geom::ModelingError,
    },
    #[error("{node}: {error}")]
    Curve { node: String, error: CurveError },
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

fn positive(what: &str, x: f64) -> Result<(), CurveError> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(CurveError::Parameter(format!(
            "{what} must be positive, not {x}"
        )))
    }
}

/// A crease value as stored: finite, in 0 ..= [`INFINITE_SHARPNESS`].
fn check_sharpness(s: f64) -> Result<f64, CommandError> {
    if s.is_finite() && (0.0..=INFINITE_SHARPNESS as f64).contains(&s) {
        Ok(s)
    } else {
        Err(CommandError::Sharpness(s))
    }
}

fn check_levels(level: u32) -> Result<(), CommandError> {
    if level > subdivision::MAX_LEVEL {
        Err(CommandError::Level(level))
    } else {
        Ok(())
    }
}

impl Command {
    /// The label shown in the history panel.
    pub fn label(&self) -> String {
        match self {
            Command::AddPrimitive { primitive, .. } => format!("Add {}", primitive.display_name()),
            Command::AddMesh { name, .. } => format!("Add Mesh '{name}'"),
            Command::AddEmpty { name, .. } => format!("Add Empty '{name}'"),
            Command::SetPrimitive { primitive, .. } => {
                format!("Adjust {}", primitive.display_name())
            }
            Command::SetTransforms { nodes } => {
                format!("Transform {}", plural(nodes.len(), "node"))
            }
            Command::Translate { nodes, .. } => format!("Move {}", plural(nodes.len(), "node")),
            Command::Rotate { nodes, .. } => format!("Rotate {}", plural(nodes.len(), "node")),
            Command::Scale { nodes, .. } => format!("Scale {}", plural(nodes.len(), "node")),
            Command::Rename { name, .. } => format!("Rename to '{name}'"),
            Command::Reparent { .. } => "Set Parent".to_string(),
            Command::SetVisible { visible, .. } => {
                if *visible { "Show" } else { "Hide" }.to_string()
            }
            Command::SetShading { shading, .. } => format!("Shade {shading:?}"),
            Command::Delete { nodes } => format!("Delete {}", plural(nodes.len(), "node")),
            Command::SetSubdivision { modifier: None, .. } => "Remove Subdivision".to_string(),
            Command::SetSubdivision {
                modifier: Some(m), ..
            } => format!("Subdivision Level {}", m.viewport_level),
            Command::ApplySubdivision { .. } => "Apply Subdivision".to_string(),
            Command::SetEdgeCrease { sharpness, .. } => format!("Edge Crease {sharpness:.2}"),
            Command::SetVertexCrease { sharpness, .. } => format!("Vertex Crease {sharpness:.2}"),
            Command::SnapToLimit { .. } => "Snap to Limit Surface".to_string(),
            Command::AddCurve { name, .. } => format!("Add Curve '{name}'"),
            Command::AddSurface { name, .. } => format!("Add Surface '{name}'"),
            Command::SetControlPoints { points, .. } => {
                format!("Move {}", plural(points.len(), "control point"))
            }
            Command::SetWeights { .. } => "Set Weights".to_string(),
            Command::InsertKnot { at, .. } => format!("Insert Knot {at}"),
            Command::ElevateDegree { .. } => "Elevate Degree".to_string(),
            Command::Duplicate { nodes } => format!("Duplicate {}", plural(nodes.len(), "node")),
            Command::MoveVertices { .. } | Command::SetVertexPositions { .. } => {
                "Move Vertices".to_string()
            }
            Command::ExtrudeFaces { .. } => "Extrude Faces".to_string(),
            Command::ExtrudeRegion { .. } => "Extrude Region".to_string(),
            Command::InsetFaces { .. } => "Inset Faces".to_string(),
            Command::InsetRegion { .. } => "Inset Region".to_string(),
            Command::LoopCut { cuts, .. } => format!("Loop Cut ({cuts})"),
            Command::SubdivideEdges { .. } => "Subdivide Edges".to_string(),
            Command::ConnectVertices { .. } => "Connect Vertices".to_string(),
            Command::Triangulate { .. } => "Triangulate Faces".to_string(),
            Command::DissolveEdges { .. } => "Dissolve Edges".to_string(),
            Command::DissolveVertices { .. } => "Dissolve Vertices".to_string(),
            Command::FlipNormals { .. } => "Flip Normals".to_string(),
            Command::RecalculateNormals { .. } => "Recalculate Normals".to_string(),
            Command::MakeHoles { .. } => "Delete Only Faces".to_string(),
            Command::FillHoles { .. } => "Fill".to_string(),
            Command::CollapseEdges { .. } => "Collapse Edges".to_string(),
            Command::BridgeLoops { .. } => "Bridge Edge Loops".to_string(),
            Command::MergeVertices { at, .. } => match at {
                hedra_geom::modeling::MergePoint::Center => "Merge at Center",
                hedra_geom::modeling::MergePoint::First => "Merge at First",
                hedra_geom::modeling::MergePoint::Last => "Merge at Last",
            }
            .to_string(),
            Command::MergeByDistance { .. } => "Merge by Distance".to_string(),
            Command::DissolveFaces { .. } => "Dissolve Faces".to_string(),
            Command::BevelEdges { .. } => "Bevel".to_string(),
            Command::BevelVertices { .. } => "Vertex Bevel".to_string(),
            Command::SlideEdges { .. } => "Edge Slide".to_string(),
            Command::MirrorVertices { axis, .. } => format!("Mirror {axis:?}"),
            Command::Symmetrize { axis, .. } => format!("Symmetrize {axis:?}"),
            Command::DeleteFaces { .. } => "Delete Faces".to_string(),
            Command::DeleteEdges { .. } => "Delete Edges".to_string(),
            Command::DeleteVertices { .. } => "Delete Vertices".to_string(),
            Command::ExtrudeEdges { .. } => "Extrude Edges".to_string(),
        }
    }
}

fn plural(n: usize, what: &str) -> String {
    if n == 1 {
        format!("1 {what}")
    } else {
        format!("{n} {what}s")
    }
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

/// Collects the node changes of one command.
struct Plan<'a> {
    doc: &'a Document,
    next_id: u64,
    changes: Vec<NodeChange>,
    /// See [`Decision::created_faces`].
    created_faces: Vec<FaceId>,
}

impl Plan<'_> {
    /// The node as this plan currently sees it (later changes win).
    fn current(&self, id: NodeId) -> Option<&Node> {
        match self.changes.iter().rev().find(|c| c.id == id) {
            Some(c) => c.after.as_ref(),
            None => self.doc.nodes.get(&id),
        }
    }

    fn resolve(&self, r: &NodeRef) -> Result<NodeId, CommandError> {
        self.doc.resolve(r)
    }

    fn set(&mut self, node: Node) {
        if let Some(c) = self.changes.iter_mut().find(|c| c.id == node.id) {
            c.after = Some(node);
        } else {
            let before = self.doc.nodes.get(&node.id).cloned();
            if before.as_ref() != Some(&node) {
                self.changes.push(NodeChange {
                    id: node.id,
                    before,
                    after: Some(node),
                });
            }
        }
    }

    fn remove(&mut self, id: NodeId) {
        if let Some(c) = self.changes.iter_mut().find(|c| c.id == id) {
            c.after = None;
        } else {
            let before = self.doc.nodes.get(&id).cloned();
            self.changes.push(NodeChange {
                id,
                before,
                after: None,
            });
        }
    }

    fn taken_name(&self, name: &str) -> bool {
        self.doc
            .nodes
            .values()
            .any(|n| n.name == name && self.current(n.id).is_some_and(|c| c.name == name))
            || self
                .changes
                .iter()
                .any(|c| c.after.as_ref().is_some_and(|n| n.name == name))
    }

    fn unique_name(&self, name: &str) -> String {
        if !self.taken_name(name) {
            return name.to_string();
        }
        let base = match name.rsplit_once('.') {
            Some((b, s)) if s.len() == 3 && s.chars().all(|c| c.is_ascii_digit()) => b,
            _ => name,
        };
        (1..)
            .map(|i| format!("{base}.{i:03}"))
            .find(|n| !self.taken_name(n))
            .expect("a free suffix exists")
    }

    fn add_node(
        &mut self,
        name: &str,
        parent: &Option<NodeRef>,
        transform: Transform,
        content: NodeContent,
    ) -> Result<NodeId, CommandError> {
        if name.trim().is_empty() {
            return Err(CommandError::EmptyName);
        }
        let parent = parent.as_ref().map(|p| self.resolve(p)).transpose()?;
        let id = NodeId(self.next_id);
        if !transform.is_usable() {
            return Err(CommandError::BadTransform {
                node: name.to_string(),
            });
        }
        self.next_id += 1;
        let name = self.unique_name(name);
        self.set(Node {
            id,
            name,
            parent,
            transform,
            visible: true,
            content,
        });
        Ok(id)
    }

    fn node(&self, r: &NodeRef) -> Result<Node, CommandError> {
        let id = self.resolve(r)?;
        Ok(self
            .current(id)
            .cloned()
            .ok_or(CommandError::UnknownNode(r.clone()))?)
    }

    fn set_transform(&mut self, mut node: Node, transform: Transform) -> Result<(), CommandError> {
        if !transform.is_usable() {
            return Err(CommandError::BadTransform {
                node: self.doc.label_of(node.id),
            });
        }
        node.transform = transform;
        self.set(node);
        Ok(())
    }

    /// Applies `edit` to a copy of the node's mesh and stores the result
    /// (no longer an adjustable primitive). `edit` reports element errors as text.
    fn edit_mesh(
        &mut self,
        r: &NodeRef,
        edit: impl FnOnce(&mut HalfEdgeMesh) -> Result<(), String>,
    ) -> Result<(), CommandError> {
        self.model(r, |m| edit(m).map(Ok))
    }

    /// Edits a curve or surface node; a refused edit changes nothing.
    fn edit_shape(
        &mut self,
        r: &NodeRef,
        curve: impl FnOnce(&mut NurbsCurve) -> Result<(), CurveError>,
        surface: impl FnOnce(&mut SurfaceShape) -> Result<(), CurveError>,
    ) -> Result<(), CommandError> {
        let mut n = self.node(r)?;
        let label = self.doc.label_of(n.id);
        let result = match &mut n.content {
            NodeContent::Curve(c) => curve(Arc::make_mut(c)),
            NodeContent::Surface(s) => surface(Arc::make_mut(s)),
            _ => return Err(CommandError::NotAShape { node: label }),
        };
        result.map_err(|error| CommandError::Curve { node: label, error })?;
        self.set(n);
        Ok(())
    }

    /// The surface a spec describes (Revolve and Extrude read another node's curve).
    fn surface_from_spec(&self, spec: &SurfaceSpec) -> Result<SurfaceShape, CurveError> {
        let profile = |r: &NodeRef| -> Result<NurbsCurve, CurveError> {
            let id = self
                .resolve(r)
                .map_err(|e| CurveError::Parameter(e.to_string()))?;
            match self.current(id).map(|n| &n.content) {
                Some(NodeContent::Curve(c)) => Ok((**c).clone()),
                _ => Err(CurveError::Parameter(format!("{r} is not a curve"))),
            }
        };
        Ok(match spec {
            SurfaceSpec::Nurbs {
                degree_u,
                degree_v,
                nu,
                nv,
                points,
                weights,
                knots_u,
                knots_v,
            } => SurfaceShape::Nurbs(NurbsSurface::new(
                *degree_u,
                *degree_v,
                knots_u
                    .clone()
                    .unwrap_or_else(|| clamped_uniform_knots(*degree_u, *nu)),
                knots_v
                    .clone()
                    .unwrap_or_else(|| clamped_uniform_knots(*degree_v, *nv)),
                *nu,
                *nv,
                points.clone(),
                weights.clone().unwrap_or_else(|| vec![1.0; points.len()]),
            )?),
            SurfaceSpec::Bezier { nu, nv, points } => {
                SurfaceShape::Nurbs(NurbsSurface::from_bezier(*nu, *nv, points.clone())?)
            }
            SurfaceSpec::Triangle { degree, points } => {
                SurfaceShape::Triangle(BezierTriangle::new(*degree, points.clone())?)
            }
            SurfaceSpec::Plane { size } => {
                positive("size", *size)?;
                SurfaceShape::Nurbs(NurbsSurface::plane(*size))
            }
            SurfaceSpec::Sphere { radius } => {
                positive("radius", *radius)?;
                SurfaceShape::Nurbs(NurbsSurface::sphere(DVec3::ZERO, *radius))
            }
            SurfaceSpec::Cylinder { radius, height } => {
                positive("radius", *radius)?;
                positive("height", *height)?;
                SurfaceShape::Nurbs(NurbsSurface::cylinder(*radius, *height))
            }
            SurfaceSpec::Revolve { profile: r } => {
                SurfaceShape::Nurbs(NurbsSurface::revolve(&profile(r)?)?)
            }
            SurfaceSpec::Extrude {
                profile: r,
                direction,
            } => SurfaceShape::Nurbs(NurbsSurface::extrude(&profile(r)?, *direction)?),
        })
    }

    /// Changes the creases of a mesh node (the mesh itself stays shared).
    fn edit_creases(
        &mut self,
        r: &NodeRef,
        edit: impl FnOnce(&HalfEdgeMesh, &mut Creases) -> Result<(), String>,
    ) -> Result<(), CommandError> {
        let mut n = self.node(r)?;
        let label = self.doc.label_of(n.id);
        let NodeContent::Mesh(content) = &mut n.content else {
            return Err(CommandError::NotAMesh { node: label });
        };
        edit(&content.mesh, &mut content.creases).map_err(|message| CommandError::Element {
            node: label,
            message,
        })?;
        self.set(n);
        Ok(())
    }

    /// Like [`edit_mesh`](Self::edit_mesh) for kernel operations that can refuse.
    fn model(
        &mut self,
        r: &NodeRef,
        edit: impl FnOnce(&mut HalfEdgeMesh) -> Result<Result<(), hedra_geom::ModelingError>, String>,
    ) -> Result<(), CommandError> {
        let mut n = self.node(r)?;
        let label = self.doc.label_of(n.id);
        let NodeContent::Mesh(content) = &mut n.content else {
            return Err(CommandError::NotAMesh { node: label });
        };
        let mut mesh = (*content.mesh).clone();
        match edit(&mut mesh) {
            Err(message) => {
                return Err(CommandError::Element {
                    node: label,
                    message,
                });
            }
            Ok(Err(error)) => return Err(CommandError::Modeling { node: label, error }),
            Ok(Ok(())) => {}
        }
        debug_assert!(
            mesh.validate().is_ok(),
            "a modeling operation broke the mesh"
        );
        content.creases.retain_live(&mesh);
        // Every mesh edit passes here: UVs follow their corners, imported
        // normals no longer describe the edited shape and are dropped.
        content.corners = content.corners.follow_edit(&content.mesh, &mesh);
        content.mesh = Arc::new(mesh);
        content.primitive = None;
        self.set(n);
        Ok(())
    }

    /// Runs a kernel operation on the faces a set names.
    fn on_faces(
        &mut self,
        r: &NodeRef,
        set: &FaceSet,
        op: impl FnOnce(&mut HalfEdgeMesh, &[FaceId]) -> Result<(), ModelingError>,
    ) -> Result<(), CommandError> {
        self.model(r, |m| {
            let fs = set.resolve(m).map_err(|e| e.0)?;
            Ok(op(m, &fs))
        })
    }

    /// Runs a kernel operation on the edges a set names.
    fn on_edges(
        &mut self,
        r: &NodeRef,
        set: &EdgeSet,
        op: impl FnOnce(&mut HalfEdgeMesh, &[EdgeId]) -> Result<(), ModelingError>,
    ) -> Result<(), CommandError> {
        self.model(r, |m| {
            let es = set.resolve(m).map_err(|e| e.0)?;
            Ok(op(m, &es))
        })
    }

    /// Runs a kernel operation on the vertices a set names.
    fn on_vertices(
        &mut self,
        r: &NodeRef,
        set: &VertexSet,
        op: impl FnOnce(&mut HalfEdgeMesh, &[VertexId]) -> Result<(), ModelingError>,
    ) -> Result<(), CommandError> {
        self.model(r, |m| {
            let vs = set.resolve(m).map_err(|e| e.0)?;
            Ok(op(m, &vs))
        })
    }

    fn run(&mut self, cmd: &Command) -> Result<(), CommandError> {
        match cmd {
            Command::AddPrimitive {
                primitive,
                name,
                parent,
                transform,
            } => {
                let mesh = primitive.build()?;
                let name = name
                    .clone()
                    .unwrap_or_else(|| primitive.display_name().to_string());
                let content = NodeContent::Mesh(MeshContent {
                    primitive: Some(primitive.clone()),
                    shading: primitive_shading(primitive),
                    ..MeshContent::new(Arc::new(mesh))
                });
                self.add_node(&name, parent, *transform, content)?;
            }
            Command::AddMesh {
                name,
                positions,
                polygons,
                parent,
                transform,
            } => {
                let mesh = HalfEdgeMesh::from_polygons(positions, polygons)?;
                let content = NodeContent::Mesh(MeshContent::new(Arc::new(mesh)));
                self.add_node(name, parent, *transform, content)?;
            }
            Command::AddEmpty {
                name,
                parent,
                transform,
            } => {
                self.add_node(name, parent, *transform, NodeContent::Empty)?;
            }
            Command::SetPrimitive { node, primitive } => {
                let mut n = self.node(node)?;
                let NodeContent::Mesh(content) = &n.content else {
                    return Err(CommandError::NotAMesh {
                        node: self.doc.label_of(n.id),
                    });
                };
                match &content.primitive {
                    Some(old) if old.kind() == primitive.kind() => {}
                    _ => {
                        return Err(CommandError::NotAPrimitive {
                            node: self.doc.label_of(n.id),
                        });
                    }
                }
                let mesh = primitive.build()?;
                n.content = NodeContent::Mesh(MeshContent {
                    mesh: Arc::new(mesh),
                    primitive: Some(primitive.clone()),
                    creases: Creases::default(),
                    corners: CornerAttributes::default(),
                    ..content.clone()
                });
                self.set(n);
            }
            Command::SetTransforms { nodes } => {
                for (r, t) in nodes {
                    let n = self.node(r)?;
                    self.set_transform(n, *t)?;
                }
            }
            Command::Translate { nodes, offset } => {
                for r in nodes {
                    let n = self.node(r)?;
                    let t = Transform {
                        translation: n.transform.translation + *offset,
                        ..n.transform
                    };
                    self.set_transform(n, t)?;
                }
            }
            Command::Rotate {
                nodes,
                axis,
                degrees,
            } => {
                let Some(axis) = axis.try_normalize() else {
                    return Err(CommandError::Nothing("the rotation axis is zero"));
                };
                let q = DQuat::from_axis_angle(axis, degrees.to_radians());
                for r in nodes {
                    let n = self.node(r)?;
                    let t = Transform {
                        rotation: (q * n.transform.rotation).normalize(),
                        ..n.transform
                    };
                    self.set_transform(n, t)?;
                }
            }
            Command::Scale { nodes, factor } => {
                for r in nodes {
                    let n = self.node(r)?;
                    let t = Transform {
                        scale: n.transform.scale * *factor,
                        ..n.transform
                    };
                    self.set_transform(n, t)?;
                }
            }
            Command::Rename { node, name } => {
                if name.trim().is_empty() {
                    return Err(CommandError::EmptyName);
                }
                let mut n = self.node(node)?;
                if n.name != *name {
                    n.name = self.unique_name(name);
                    self.set(n);
                }
            }
            Command::Reparent {
                node,
                parent,
                keep_world,
            } => {
                let mut n = self.node(node)?;
                let new_parent = parent.as_ref().map(|p| self.resolve(p)).transpose()?;
                if let Some(p) = new_parent {
                    if self.doc.is_ancestor(n.id, p) {
                        return Err(CommandError::Cycle {
                            node: self.doc.label_of(n.id),
                            parent: self.doc.label_of(p),
                        });
                    }
                }
                if *keep_world {
                    let world = self.doc.world_matrix(n.id);
                    let parent_world =
                        new_parent.map_or(glam::DMat4::IDENTITY, |p| self.doc.world_matrix(p));
                    n.transform = Transform::from_matrix(parent_world.inverse() * world);
                }
                n.parent = new_parent;
                self.set(n);
            }
            Command::SetVisible { nodes, visible } => {
                for r in nodes {
                    let mut n = self.node(r)?;
                    n.visible = *visible;
                    self.set(n);
                }
            }
            Command::SetShading { nodes, shading } => {
                for r in nodes {
                    let mut n = self.node(r)?;
                    let NodeContent::Mesh(content) = &mut n.content else {
                        return Err(CommandError::NotAMesh {
                            node: self.doc.label_of(n.id),
                        });
                    };
                    content.shading = *shading;
                    self.set(n);
                }
            }
            Command::AddCurve {
                name,
                curve,
                parent,
                transform,
            } => {
                let c = curve_from_spec(curve).map_err(|error| CommandError::Curve {
                    node: format!("curve '{name}'"),
                    error,
                })?;
                self.add_node(name, parent, *transform, NodeContent::Curve(Arc::new(c)))?;
            }
            Command::AddSurface {
                name,
                surface,
                parent,
                transform,
            } => {
                let shape =
                    self.surface_from_spec(surface)
                        .map_err(|error| CommandError::Curve {
                            node: format!("surface '{name}'"),
                            error,
                        })?;
                self.add_node(
                    name,
                    parent,
                    *transform,
                    NodeContent::Surface(Arc::new(shape)),
                )?;
            }
            Command::SetControlPoints { node, points } => self.edit_shape(
                node,
                |c| {
                    for &(i, p) in points {
                        c.set_point(i as usize, p)?;
                    }
                    Ok(())
                },
                |s| {
                    for &(i, p) in points {
                        match s {
                            SurfaceShape::Nurbs(n) => {
                                let nv = n.size().1;
                                n.set_point(i as usize / nv, i as usize % nv, p)?;
                            }
                            SurfaceShape::Triangle(t) => {
                                let count = t.points.len();
                                let slot = t.points.get_mut(i as usize).ok_or(
                                    CurveError::NoSuchPoint {
                                        index: i as usize,
                                        count,
                                    },
                                )?;
                                if !p.is_finite() {
                                    return Err(CurveError::NotFinite {
                                        what: "control point",
                                        index: i as usize,
                                    });
                                }
                                *slot = p;
                            }
                        }
                    }
                    Ok(())
                },
            )?,
            Command::SetWeights { node, weights } => self.edit_shape(
                node,
                |c| {
                    for &(i, w) in weights {
                        c.set_weight(i as usize, w)?;
                    }
                    Ok(())
                },
                |s| match s {
                    SurfaceShape::Nurbs(n) => {
                        let nv = n.size().1;
                        for &(i, w) in weights {
                            n.set_weight(i as usize / nv, i as usize % nv, w)?;
                        }
                        Ok(())
                    }
                    SurfaceShape::Triangle(_) => Err(CurveError::Parameter(
                        "Bézier triangles are polynomial: they have no weights".into(),
                    )),
                },
            )?,
            Command::InsertKnot {
                node,
                at,
                direction,
            } => self.edit_shape(
                node,
                |c| {
                    *c = c.insert_knot(*at)?;
                    Ok(())
                },
                |s| match s {
                    SurfaceShape::Nurbs(n) => {
                        *n = match direction {
                            ParameterDirection::U => n.insert_knot_u(*at)?,
                            ParameterDirection::V => n.insert_knot_v(*at)?,
                        };
                        Ok(())
                    }
                    SurfaceShape::Triangle(_) => Err(CurveError::Parameter(
                        "Bézier triangles have no knots (elevate or split them instead)".into(),
                    )),
                },
            )?,
            Command::ElevateDegree { node, direction } => self.edit_shape(
                node,
                |c| {
                    *c = c.elevate_degree()?;
                    Ok(())
                },
                |s| match s {
                    SurfaceShape::Triangle(t) => {
                        *t = t.elevate();
                        Ok(())
                    }
                    SurfaceShape::Nurbs(n) => {
                        *n = match direction {
                            ParameterDirection::U => n.elevate_u()?,
                            ParameterDirection::V => n.elevate_v()?,
                        };
                        Ok(())
                    }
                },
            )?,
            Command::SetSubdivision { nodes, modifier } => {
                if let Some(m) = modifier {
                    check_levels(m.viewport_level.max(m.export_level))?;
                }
                for r in nodes {
                    let mut n = self.node(r)?;
                    let label = self.doc.label_of(n.id);
                    let NodeContent::Mesh(content) = &mut n.content else {
                        return Err(CommandError::NotAMesh { node: label });
                    };
                    content.subdivision = *modifier;
                    self.set(n);
                }
            }
            Command::ApplySubdivision { node, levels } => {
                let mut n = self.node(node)?;
                let label = self.doc.label_of(n.id);
                let NodeContent::Mesh(content) = &mut n.content else {
                    return Err(CommandError::NotAMesh { node: label });
                };
                let (options, level) = match (content.subdivision, levels) {
                    (_, Some(l)) => (content.subdivision.unwrap_or_default().options, *l),
                    (Some(m), None) => (m.options, m.viewport_level),
                    (None, None) => {
                        return Err(CommandError::Element {
                            node: label,
                            message:
                                "has no subdivision modifier (give `levels` to subdivide anyway)"
                                    .into(),
                        });
                    }
                };
                check_levels(level)?;
                let (mesh, creases) =
                    Refiner::subdivide(&content.mesh, &content.creases, options, level)
                        .map_err(|error| CommandError::Subdivision { node: label, error })?;
                content.mesh = Arc::new(mesh);
                content.creases = creases;
                // The refined mesh has new ids: no corner attribute carries over.
                content.corners = CornerAttributes::default();
                content.subdivision = None;
                content.primitive = None;
                self.set(n);
            }
            Command::SetEdgeCrease {
                node,
                edges,
                sharpness,
            } => {
                let s = check_sharpness(*sharpness)?;
                self.edit_creases(node, |m, c| {
                    for e in edges.resolve(m).map_err(|e| e.0)? {
                        c.set_edge(e, s);
                    }
                    Ok(())
                })?;
            }
            Command::SetVertexCrease {
                node,
                vertices,
                sharpness,
            } => {
                let s = check_sharpness(*sharpness)?;
                self.edit_creases(node, |m, c| {
                    for v in vertices.resolve(m).map_err(|e| e.0)? {
                        c.set_vertex(v, s);
                    }
                    Ok(())
                })?;
            }
            Command::SnapToLimit { node } => {
                let n = self.node(node)?;
                let label = self.doc.label_of(n.id);
                let NodeContent::Mesh(content) = &n.content else {
                    return Err(CommandError::NotAMesh { node: label });
                };
                let options = content.subdivision.unwrap_or_default().options;
                let snapped = subdivision::snap_to_limit(&content.mesh, &content.creases, options)
                    .map_err(|error| CommandError::Subdivision { node: label, error })?;
                self.edit_mesh(node, |m| {
                    for (v, p) in snapped {
                        m.set_position(v, p);
                    }
                    Ok(())
                })?;
            }
            Command::Delete { nodes } => {
                for r in nodes {
                    let id = self.resolve(r)?;
                    for x in self.doc.subtree(id).into_iter().rev() {
                        if self.current(x).is_some() {
                            self.remove(x);
                        }
                    }
                }
            }
            Command::MoveVertices {
                node,
                vertices,
                offset,
            } => {
                self.edit_mesh(node, |m| {
                    let vs = vertices.resolve(m).map_err(|e| e.0)?;
                    if !offset.is_finite() {
                        return Err("the offset is not finite".into());
                    }
                    for v in vs {
                        m.set_position(v, m.position(v) + *offset);
                    }
                    Ok(())
                })?;
            }
            Command::SetVertexPositions { node, positions } => {
                self.edit_mesh(node, |m| {
                    for &(i, p) in positions {
                        if !m.is_vertex(VertexId(i)) {
                            return Err(format!("vertex v{i} does not exist"));
                        }
                        if !p.is_finite() {
                            return Err(format!("vertex v{i}: position is not finite"));
                        }
                        m.set_position(VertexId(i), p);
                    }
                    Ok(())
                })?;
            }
            Command::ExtrudeRegion {
                node,
                faces,
                distance,
            } => {
                let mut caps = Vec::new();
                self.on_faces(node, faces, |m, fs| {
                    let normal = m.region_normal(fs);
                    if normal == DVec3::ZERO {
                        return Err(ModelingError::Parameter {
                            what: "faces",
                            allowed: "facing some common direction",
                            value: "normals that cancel out".into(),
                        });
                    }
                    modeling::extrude_region(m, fs, normal * *distance).map(|c| caps = c)
                })?;
                self.created_faces = caps;
            }
            Command::ExtrudeFaces {
                node,
                faces,
                distance,
            } => self.on_faces(node, faces, |m, fs| {
                modeling::extrude_faces_individual(m, fs, *distance).map(drop)
            })?,
            Command::InsetFaces {
                node,
                faces,
                thickness,
                depth,
            } => self.on_faces(node, faces, |m, fs| {
                modeling::inset_faces_individual(m, fs, *thickness, *depth).map(drop)
            })?,
            Command::InsetRegion {
                node,
                faces,
                thickness,
                depth,
            } => {
                let mut inner = Vec::new();
                self.on_faces(node, faces, |m, fs| {
                    modeling::inset_region(m, fs, *thickness, *depth).map(|c| inner = c)
                })?;
                self.created_faces = inner;
            }
            Command::LoopCut { node, edge, cuts } => self.model(node, |m| {
                let es = edge.resolve(m).map_err(|e| e.0)?;
                let [e] = es[..] else {
                    return Err(format!(
                        "a loop cut needs exactly one edge, {edge:?} names {}",
                        es.len()
                    ));
                };
                Ok(modeling::loop_cut(m, e, *cuts).map(drop))
            })?,
            Command::SubdivideEdges { node, edges, cuts } => {
                self.on_edges(node, edges, |m, es| {
                    modeling::subdivide_edges(m, es, *cuts).map(drop)
                })?
            }
            Command::ConnectVertices { node, vertices } => self.model(node, |m| {
                let vs = vertices.resolve(m).map_err(|e| e.0)?;
                let [a, b] = vs[..] else {
                    return Err(format!(
                        "connecting needs exactly two vertices, {vertices:?} names {}",
                        vs.len()
                    ));
                };
                Ok(modeling::connect_vertices(m, a, b).map(drop))
            })?,
            Command::Triangulate { node, faces } => self.on_faces(node, faces, |m, fs| {
                modeling::triangulate_faces(m, fs).map(drop)
            })?,
            Command::DissolveEdges { node, edges } => {
                self.on_edges(node, edges, modeling::dissolve_edges)?
            }
            Command::DissolveVertices { node, vertices } => {
                self.on_vertices(node, vertices, modeling::dissolve_vertices)?
            }
            Command::DissolveFaces { node, faces } => self.on_faces(node, faces, |m, fs| {
                modeling::dissolve_faces(m, fs).map(drop)
            })?,
            Command::RecalculateNormals { node } => self.model(node, |m| {
                if !modeling::recalculate_normals_outward(m) {
                    return Err("the mesh already faces outwards (or is open)".into());
                }
                Ok(Ok(()))
            })?,
            Command::FlipNormals { node } => self.model(node, |m| {
                modeling::flip_normals(m);
                Ok(Ok(()))
            })?,
            Command::MakeHoles { node, faces } => {
                self.on_faces(node, faces, modeling::make_holes)?
            }
            Command::BevelEdges {
                node,
                edges,
                width,
                segments,
            } => self.on_edges(node, edges, |m, es| {
                modeling::bevel_edges(m, es, *width, *segments).map(drop)
            })?,
            Command::BevelVertices {
                node,
                vertices,
                width,
            } => self.on_vertices(node, vertices, |m, vs| {
                modeling::bevel_vertices(m, vs, *width).map(drop)
            })?,
            Command::SlideEdges {
                node,
                edges,
                factor,
            } => self.on_edges(node, edges, |m, es| modeling::slide_edges(m, es, *factor))?,
            Command::FillHoles { node, edges } => {
                self.on_edges(node, edges, |m, es| modeling::fill_holes(m, es).map(drop))?
            }
            Command::ExtrudeEdges {
                node,
                edges,
                offset,
            } => self.on_edges(node, edges, |m, es| {
                modeling::extrude_boundary_edges(m, es, *offset).map(drop)
            })?,
            Command::MirrorVertices {
                node,
                vertices,
                axis,
            } => self.on_vertices(node, vertices, |m, vs| {
                modeling::mirror_vertices(m, vs, *axis)
            })?,
            Command::Symmetrize { node, axis } => {
                self.model(node, |m| Ok(modeling::symmetrize(m, *axis)))?
            }
            Command::DeleteFaces { node, faces } => {
                self.on_faces(node, faces, modeling::delete_faces)?
            }
            Command::DeleteEdges { node, edges } => self.on_edges(node, edges, |m, es| {
                let fs = modeling::faces_around_edges(m, es);
                modeling::delete_faces(m, &fs)
            })?,
            Command::DeleteVertices { node, vertices } => {
                self.on_vertices(node, vertices, |m, vs| {
                    let fs = modeling::faces_around_vertices(m, vs);
                    modeling::delete_faces(m, &fs)
                })?
            }
            Command::MergeVertices { node, vertices, at } => {
                self.on_vertices(node, vertices, |m, vs| {
                    modeling::merge_vertices(m, vs, *at).map(drop)
                })?
            }
            Command::MergeByDistance {
                node,
                vertices,
                distance,
            } => self.on_vertices(node, vertices, |m, vs| {
                modeling::merge_by_distance(m, vs, *distance).map(drop)
            })?,
            Command::BridgeLoops { node, edges } => {
                self.on_edges(node, edges, |m, es| modeling::bridge_loops(m, es).map(drop))?
            }
            Command::CollapseEdges { node, edges } => self.on_edges(node, edges, |m, es| {
                modeling::collapse_edges(m, es).map(drop)
            })?,
            Command::Duplicate { nodes } => {
                for r in nodes {
                    let root = self.resolve(r)?;
                    let subtree = self.doc.subtree(root);
                    let mut map = std::collections::HashMap::new();
                    for &old in &subtree {
                        map.insert(old, NodeId(self.next_id));
                        self.next_id += 1;
                    }
                    for &old in &subtree {
                        let mut n = self
                            .current(old)
                            .cloned()
                            .ok_or(CommandError::UnknownNode(NodeRef::Id(old.0)))?;
                        n.id = map[&old];
                        n.parent = if old == root {
                            n.parent
                        } else {
                            n.parent.map(|p| map[&p])
                        };
                        n.name = self.unique_name(&n.name);
                        self.set(n);
                    }
                }
            }
        }
        Ok(())
    }
}
