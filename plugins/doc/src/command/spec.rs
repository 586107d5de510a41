//! The [`Command`] enum, everything a user or script can ask of a document,
//! with the specs its variants carry (curves, surfaces, node references) and
//! the label each shows in the history panel. Its serde form is also the
//! stored form of the history (see `file::stored_command`).

use crate::elements::{EdgeSet, FaceSet, VertexSet};
use crate::scene::{NodeId, Shading, SubdivisionModifier, Transform};
use glam::DVec3;
use hedra_geom::Primitive;
use hedra_geom::modeling::MirrorAxis;
use serde::{Deserialize, Serialize};
use std::fmt;

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
