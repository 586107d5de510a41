//! The [`Command`] enum, everything a user or script can ask of a document,
//! with the specs its variants carry (curves, surfaces, node references) and
//! the label each shows in the history panel. Its serde form is also the
//! stored form of the history (see `file::stored_command`).

use crate::construction::Construction;
use crate::elements::{EdgeSet, FaceSet, ProfileSet, VertexSet};
use crate::modifiers::MeshModifier;
use crate::scene::{NodeId, NodeTransform, Shading, SubdivisionModifier};
use glam::DVec3;
use hedra_geom::Primitive;
use hedra_geom::csg::BooleanOp;
use hedra_geom::curves::interpolating::Tbc;
use hedra_geom::curves::{CurveEnd, FractalRule, Join, Parameterization, SplineEnds};
use hedra_geom::modeling::{BisectClear, MirrorAxis, TriangulateMethod};

/// Serde: the default triangulation is not written.
fn is_clip(method: &TriangulateMethod) -> bool {
    *method == TriangulateMethod::Clip
}
use serde::{Deserialize, Serialize};
use std::fmt;

/// Which parameter of a surface.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum ParameterDirection {
    /// The first parameter (for NURBS surfaces, along the rows `i` of `i * nv + j`).
    #[default]
    U,
    /// The second parameter (along `j`).
    V,
}

/// A curve to add, as a script writes it. It is not the kernel's
/// [`CurveKind`](hedra_geom::curves::CurveKind), on purpose: a spec may
/// leave knots, weights, keys and joins to their defaults and has shorthands
/// that are NURBS curves in the kernel (`Bezier`, `Circle`, `Closed`), and
/// its variant names are the file and script format (`Hermite` is the
/// kernel's `CubicHermite`). [`CurveSpec::of_kind`] maps every kernel kind
/// back to a spec with an exhaustive match, so the two cannot drift apart.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum CurveSpec {
    /// A NURBS curve; knots default to clamped uniform on [0, 1], weights to 1.
    Nurbs {
        /// Polynomial degree (1 = a polyline); needs at least `degree + 1` points.
        degree: usize,
        /// Control points in the node's local space.
        points: Vec<DVec3>,
        /// One positive weight per point; `None`: all 1 (non-rational).
        #[serde(default)]
        weights: Option<Vec<f64>>,
        /// `points + degree + 1` non-decreasing knots; `None`: clamped uniform on [0, 1].
        #[serde(default)]
        knots: Option<Vec<f64>>,
    },
    /// A Bézier curve of degree `points − 1`.
    Bezier {
        /// Control points in the node's local space (at least 2).
        points: Vec<DVec3>,
    },
    /// The exact NURBS circle in the XZ plane.
    Circle {
        /// Radius in local units, positive.
        radius: f64,
    },
    /// A closed periodic B-spline around the points.
    Closed {
        /// Polynomial degree.
        degree: usize,
        /// Control points in the node's local space, in order around the loop
        /// (at least `degree + 1`; Hedra wraps them, so do not repeat any).
        points: Vec<DVec3>,
        /// One positive weight per point; `None`: all 1.
        #[serde(default)]
        weights: Option<Vec<f64>>,
    },
    /// The polynomial of degree n − 1 through n points (seed 000).
    Lagrange {
        /// The points it passes through (at least 2).
        points: Vec<DVec3>,
        /// Uniform (the default), chord-length or centripetal parameters.
        #[serde(default)]
        parameterization: Parameterization,
    },
    /// Cubic Hermite segments: points with their tangents (dp/dt), at
    /// parameters 0, 1, 2, …
    Hermite {
        /// The points it passes through (at least 2).
        points: Vec<DVec3>,
        /// One tangent per point.
        tangents: Vec<DVec3>,
    },
    /// Quintic Hermite segments (C2): points with first and second
    /// derivatives (seed 002).
    QuinticHermite {
        /// The points it passes through (at least 2).
        points: Vec<DVec3>,
        /// One first derivative per point.
        tangents: Vec<DVec3>,
        /// One second derivative per point.
        accelerations: Vec<DVec3>,
    },
    /// The Catmull-Rom spline through the points.
    CatmullRom {
        /// The points it passes through (at least 2; 3 closed).
        points: Vec<DVec3>,
        /// Uniform (the default), chord-length or centripetal parameters.
        #[serde(default)]
        parameterization: Parameterization,
        /// A closed loop (default open).
        #[serde(default)]
        closed: bool,
    },
    /// The Kochanek-Bartels spline: tension, bias, continuity per point.
    KochanekBartels {
        /// The points it passes through (at least 2; 3 closed).
        points: Vec<DVec3>,
        /// One T/B/C key per point; `None`: all zero (Catmull-Rom).
        #[serde(default)]
        keys: Option<Vec<Tbc>>,
        /// A closed loop (default open).
        #[serde(default)]
        closed: bool,
    },
    /// The interpolating C2 cubic spline (seed 004).
    CubicSpline {
        /// The points it passes through (at least 2; 3 closed).
        points: Vec<DVec3>,
        /// Uniform (the default), chord-length or centripetal parameters.
        #[serde(default)]
        parameterization: Parameterization,
        /// `Natural` (the default), `Clamped(start:, end:)` or `Closed`.
        #[serde(default)]
        ends: SplineEnds,
    },
    /// Chaikin's corner cutting of a control polygon.
    Chaikin {
        /// The control polygon (at least 2; 3 closed).
        points: Vec<DVec3>,
        /// How many times the corners are cut.
        level: u32,
        /// A closed polygon (default open).
        #[serde(default)]
        closed: bool,
    },
    /// Cubic Bézier segments: anchors at 0, 3, 6, … with two handles
    /// between; `3k + 1` points open, `3k` closed.
    PolyBezier {
        /// Anchors and handles in the node's local space.
        points: Vec<DVec3>,
        /// The continuity of each joint (`k − 1` open, `k` closed, joint
        /// `j` at anchor `3(j + 1)` open, `3j` closed); `None`: all `G1`.
        /// Handles are turned to hold them (the outgoing one moves).
        #[serde(default)]
        joins: Option<Vec<Join>>,
        /// A closed chain (default open).
        #[serde(default)]
        closed: bool,
    },
    /// A fractal of the Koch family: the initiator's segments replaced
    /// `level` times (seed 004). Two points make the Koch curve, a
    /// clockwise triangle (seen from the normal) the Koch snowflake.
    Fractal {
        /// `Koch` (the default, D = log 4 / log 3) or `QuadraticKoch` (D = 1.5).
        #[serde(default)]
        rule: FractalRule,
        /// The initiator polygon (at least 2; 3 closed).
        points: Vec<DVec3>,
        /// Replacement levels.
        level: u32,
        /// A closed initiator (default open).
        #[serde(default)]
        closed: bool,
        /// The plane's normal, bumps to `normal × segment`; default +Z.
        #[serde(default = "plus_z")]
        normal: DVec3,
    },
}

/// Serde default of a fractal's normal.
fn plus_z() -> DVec3 {
    DVec3::Z
}

/// A surface to add.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum SurfaceSpec {
    /// A NURBS surface of `nu × nv` points (`i * nv + j`); knots default to
    /// clamped uniform, weights to 1.
    Nurbs {
        /// Degree along u (the `i` rows).
        degree_u: usize,
        /// Degree along v (the `j` columns).
        degree_v: usize,
        /// Number of control points along u.
        nu: usize,
        /// Number of control points along v.
        nv: usize,
        /// `nu * nv` control points in the node's local space, point `(i, j)` at `i * nv + j`.
        points: Vec<DVec3>,
        /// One positive weight per point, in the same order; `None`: all 1.
        #[serde(default)]
        weights: Option<Vec<f64>>,
        /// `nu + degree_u + 1` knots along u; `None`: clamped uniform.
        #[serde(default)]
        knots_u: Option<Vec<f64>>,
        /// `nv + degree_v + 1` knots along v; `None`: clamped uniform.
        #[serde(default)]
        knots_v: Option<Vec<f64>>,
    },
    /// A tensor-product Bézier patch of `nu × nv` points.
    Bezier {
        /// Number of control points along u (degree `nu - 1`).
        nu: usize,
        /// Number of control points along v (degree `nv - 1`).
        nv: usize,
        /// `nu * nv` control points in local space, point `(i, j)` at `i * nv + j`.
        points: Vec<DVec3>,
    },
    /// A Bézier triangle: (n+1)(n+2)/2 points, rows of equal i.
    Triangle {
        /// The triangle's degree `n`.
        degree: usize,
        /// `(n+1)(n+2)/2` control points in local space: rows of equal `i`, `j`
        /// rising (`b_00n, b_01(n-1), …`).
        points: Vec<DVec3>,
    },
    /// A flat square in the local XZ plane, centred on the origin.
    Plane {
        /// Side length, positive.
        size: f64,
    },
    /// An exact rational sphere around the local origin.
    Sphere {
        /// Radius, positive.
        radius: f64,
    },
    /// An exact open cylinder around the local Y axis, from y = 0 up to `height`.
    Cylinder {
        /// Radius, positive.
        radius: f64,
        /// Height along Y, positive.
        height: f64,
    },
    /// The curve of another node revolved around the Y axis.
    Revolve {
        /// The curve node to turn; its control points are read in its own local space (XY plane).
        profile: NodeRef,
    },
    /// The curve of another node swept along a direction.
    Extrude {
        /// The curve node to sweep, read in its own local space.
        profile: NodeRef,
        /// The sweep vector (length included), in the new node's local space.
        direction: DVec3,
    },
}

/// A node named by id or by (unique) name, so scripts need not know ids.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum NodeRef {
    /// The node with this id (`NodeId`'s number, as `hedra info` shows it).
    Id(u64),
    /// The node with this exact name (names are unique in a document).
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
///
/// Run through [`Session::execute`](crate::Session::execute), each command is
/// one undo step: undo puts back every node it changed exactly as it was
/// (id, name, parent, mesh, creases), redo applies the same result again. A
/// command that fails changes nothing. Node transforms are relative to the
/// parent; positions, offsets and element predicates of mesh, curve and
/// surface commands are in the node's own (local) space. Editing the mesh of
/// a primitive node makes it a plain mesh, which [`Command::SetPrimitive`]
/// no longer accepts (undo makes it a primitive again).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Command {
    /// Adds a primitive mesh node.
    AddPrimitive {
        /// The kind and its parameters (`Cube(size: 2.0)`).
        primitive: Primitive,
        /// The node's name; `None`: the primitive's display name ("Cube"). Made
        /// unique with a `.001`-style suffix when taken.
        #[serde(default)]
        name: Option<String>,
        /// The new node's parent; `None` (the default): the top level.
        #[serde(default)]
        parent: Option<NodeRef>,
        /// The new node's local transform, relative to its parent (default:
        /// identity).
        #[serde(default)]
        transform: NodeTransform,
    },
    /// Adds a mesh from explicit positions and polygons (vertex index lists,
    /// counter-clockwise seen from outside).
    AddMesh {
        /// The new node's name, made unique with a `.001`-style suffix when taken.
        name: String,
        /// Vertex positions in the node's local space.
        positions: Vec<DVec3>,
        /// Vertex index lists into `positions`, counter-clockwise seen from outside;
        /// they must form a manifold, consistently oriented surface.
        polygons: Vec<Vec<u32>>,
        /// The new node's parent; `None` (the default): the top level.
        #[serde(default)]
        parent: Option<NodeRef>,
        /// The new node's local transform, relative to its parent (default:
        /// identity).
        #[serde(default)]
        transform: NodeTransform,
    },
    /// Adds a mesh kept as it is, from positions and faces that need not
    /// be manifold (an edge in three faces, a vertex where fans meet, a
    /// face that visits a vertex twice): drawn, moved, subdivided and
    /// exported, but not edited until [`Command::MakeManifold`].
    AddKeptMesh {
        /// The new node's name, made unique with a `.001`-style suffix when taken.
        name: String,
        /// Vertex positions in the node's local space.
        positions: Vec<DVec3>,
        /// Faces as vertex index lists into `positions`, each of three or
        /// more corners.
        faces: Vec<Vec<u32>>,
        /// The new node's parent; `None` (the default): the top level.
        #[serde(default)]
        parent: Option<NodeRef>,
        /// The new node's local transform, relative to its parent (default:
        /// identity).
        #[serde(default)]
        transform: NodeTransform,
    },
    /// Adds an empty (grouping) node.
    AddEmpty {
        /// The new node's name, made unique with a `.001`-style suffix when taken.
        name: String,
        /// The new node's parent; `None` (the default): the top level.
        #[serde(default)]
        parent: Option<NodeRef>,
        /// The new node's local transform, relative to its parent (default:
        /// identity).
        #[serde(default)]
        transform: NodeTransform,
    },
    /// Rebuilds a primitive node with new parameters ("adjust last operation").
    /// The rebuilt mesh has no creases, UVs or custom normals; undo restores
    /// the old mesh with them.
    SetPrimitive {
        /// A mesh node that is still an unedited primitive.
        node: NodeRef,
        /// New parameters; must be the same kind as the node's.
        primitive: Primitive,
    },
    /// Sets local transforms of one or more nodes in one step.
    SetTransforms {
        /// Each node with its new local transform (relative to its parent).
        nodes: Vec<(NodeRef, NodeTransform)>,
    },
    /// Moves nodes by an offset in their parent's space.
    Translate {
        /// The nodes, changed in this order.
        nodes: Vec<NodeRef>,
        /// The offset, in each node's parent space (world space at the top level).
        offset: DVec3,
    },
    /// Rotates nodes about their own origin around an axis (degrees).
    Rotate {
        /// The nodes, changed in this order.
        nodes: Vec<NodeRef>,
        /// The rotation axis in the parent's space; need not be unit length, must
        /// not be zero.
        axis: DVec3,
        /// The angle in degrees, counter-clockwise looking down the axis.
        degrees: f64,
    },
    /// Multiplies nodes' scale.
    Scale {
        /// The nodes, changed in this order.
        nodes: Vec<NodeRef>,
        /// Per-axis factor each node's scale is multiplied by; a zero component
        /// is refused.
        factor: DVec3,
    },
    /// Renames a node. A name that is taken gets a `.001`-style suffix; an empty
    /// name is refused.
    Rename {
        /// The node to rename.
        node: NodeRef,
        /// The new name (not empty).
        name: String,
    },
    /// Gives a node a new parent (`None` for the root). With `keep_world`
    /// the node stays where it is in the world.
    Reparent {
        /// The node to move in the tree (it keeps its descendants).
        node: NodeRef,
        /// The new parent, `None` for the top level; not the node itself or one of
        /// its descendants.
        parent: Option<NodeRef>,
        /// `true` (the default): the local transform is recomputed so the node
        /// stays put in the world; `false`: the local transform is kept.
        #[serde(default = "yes")]
        keep_world: bool,
    },
    /// Shows or hides nodes (hidden nodes are not drawn or exported; they stay
    /// in the file).
    SetVisible {
        /// The nodes, changed in this order.
        nodes: Vec<NodeRef>,
        /// `true` to show, `false` to hide.
        visible: bool,
    },
    /// Flat or smooth shading of mesh nodes (kept meshes too).
    SetShading {
        /// Mesh or kept mesh nodes (any other node is refused).
        nodes: Vec<NodeRef>,
        /// `Flat` (one normal per face) or `Smooth` (averaged vertex normals).
        shading: Shading,
    },
    /// Adds, changes or (with `None`) removes the subdivision modifier of
    /// mesh nodes (kept meshes too: they subdivide by OpenSubdiv's rules
    /// for non-manifold places).
    SetSubdivision {
        /// Mesh or kept mesh nodes (any other node is refused).
        nodes: Vec<NodeRef>,
        /// The levels and options; `None` removes the modifier.
        modifier: Option<SubdivisionModifier>,
    },
    /// Turns kept (non-manifold) meshes into editable half-edge meshes by
    /// the import repair (`hedra import --repair`): faces on an edge after
    /// its first two and faces turned against their neighbours are
    /// dropped, vertices where separate fans meet are split, faces that
    /// visit a vertex twice are split there. Shading and subdivision stay;
    /// the step's label says what changed.
    MakeManifold {
        /// Kept mesh nodes (any other node is refused).
        nodes: Vec<NodeRef>,
    },
    /// Replaces the cage by its subdivision (at `levels`, or the modifier's
    /// viewport level) and removes the modifier; creases that are left after
    /// the refinement stay on the new edges. Undo restores the cage and the
    /// modifier.
    ApplySubdivision {
        /// A mesh node.
        node: NodeRef,
        /// Levels to apply; `None`: the modifier's viewport level (then the node
        /// must have a modifier).
        #[serde(default)]
        levels: Option<u32>,
    },
    /// Converts the Catmull-Clark limit surface of a mesh node with a
    /// subdivision modifier into NURBS surfaces (Rhino's SubD ▸ ToNURBS;
    /// `hedra_geom::subdivision::to_nurbs`): a new empty node named after
    /// the cage with " NURBS", with the cage's parent and transform, holds
    /// one NURBS surface node per patch (a packed rectangle of regular faces,
    /// exact; or one approximated irregular face). The cage is hidden
    /// (`keep_cage: true`, the default) or deleted (its children move to the
    /// new group). Undo restores the cage as it was.
    ConvertSubdivisionToNurbs {
        /// A mesh node with a Catmull-Clark subdivision modifier.
        node: NodeRef,
        /// Largest distance from the limit surface, as a fraction of the
        /// cage's bounding-box diagonal; `None`: 1e-4.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        tolerance: Option<f64>,
        /// Keep the cage, hidden (true), or delete it (false).
        #[serde(default = "crate::scene::yes")]
        keep_cage: bool,
    },
    /// Adds a modifier (Mirror, Array) at the end of a mesh node's stack
    /// (Blender's Add Modifier). A subdivision modifier at its default
    /// place stays last. Refused when the stack would not evaluate (a
    /// mirror merge that is not manifold), naming the modifier.
    AddModifier {
        /// A mesh node.
        node: NodeRef,
        /// The modifier and its settings.
        modifier: MeshModifier,
    },
    /// Replaces the settings of modifier `index` of a mesh node's stack.
    SetModifier {
        /// A mesh node.
        node: NodeRef,
        /// The modifier's place in the stack, from 0.
        index: usize,
        /// Its new kind and settings.
        modifier: MeshModifier,
    },
    /// Removes modifier `index` from a mesh node's stack; subdivision keeps
    /// its place after the same modifiers.
    RemoveModifier {
        /// A mesh node.
        node: NodeRef,
        /// The modifier's place in the stack, from 0.
        index: usize,
    },
    /// Moves a modifier within a mesh node's stack (Blender's Move Up /
    /// Move Down). Subdivision's place is its own field
    /// ([`SubdivisionModifier::stack_position`]), set by
    /// [`Command::SetSubdivision`], and is not moved.
    MoveModifier {
        /// A mesh node.
        node: NodeRef,
        /// The modifier's place in the stack, from 0.
        from: usize,
        /// Its new place, from 0.
        to: usize,
    },
    /// Makes the first `count` stack modifiers (default: all) part of the
    /// cage, in one undo step: their result becomes the mesh (creases on
    /// every copy, UVs on every copied corner) and they leave the stack.
    /// Blender applies one modifier at a time from the top: `count: Some(1)`.
    /// Subdivision stays a modifier; applying a modifier that runs after
    /// subdivision is refused.
    ApplyModifiers {
        /// A mesh node with stack modifiers.
        node: NodeRef,
        /// How many modifiers, from the top of the stack (default: all).
        #[serde(default)]
        count: Option<usize>,
    },
    /// Simplifies a mesh node's cage once (Blender's Decimate modifier
    /// applied): quadric edge collapses on the triangulated cage down to
    /// `target` (a ratio of its triangles or a face count), keeping
    /// borders, creases, UV seams and sharp edges as the options say;
    /// creases follow the collapses and UVs their corners. Refused when
    /// the target is below what the mesh can be simplified to, naming
    /// that minimum. For a level that stays adjustable use a `Decimate`
    /// modifier ([`Command::AddModifier`]).
    Decimate {
        /// A mesh node.
        node: NodeRef,
        /// `Ratio(r)` with r in (0, 1] or `Faces(n)`.
        target: hedra_geom::progressive::DecimateTarget,
        /// Border vertices never move (default off).
        #[serde(default)]
        keep_borders: bool,
        /// Creased edges hold (default on).
        #[serde(default = "yes")]
        keep_creases: bool,
        /// UV seams hold (default on).
        #[serde(default = "yes")]
        keep_uv_seams: bool,
        /// Edges sharper than this many degrees hold (default none).
        #[serde(default)]
        sharp_angle: Option<f64>,
        /// Triangle pairs of the result joined into quads where they fit
        /// (default off: triangles; written only when on, so stored
        /// commands from before it read and write unchanged).
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        keep_quads: bool,
    },
    /// Deletes nodes with their descendants. Undo brings them back with
    /// their ids and names.
    Delete {
        /// The nodes to delete; their descendants go too.
        nodes: Vec<NodeRef>,
    },
    /// Copies nodes with their descendants; copies get new ids and names
    /// (`Box.001`); a copy has its original's parent and transform.
    Duplicate {
        /// The nodes to copy; each copy has the original's parent.
        nodes: Vec<NodeRef>,
    },

    // ----- CSG (issue 17) -----
    /// Adds a CSG node whose children are its operands (see
    /// [`crate::csg`]): `operands` move under it keeping their world
    /// placement. A difference is the first operand (in id order) minus the
    /// others. Refused, naming the nodes, when the result would not
    /// evaluate (an open operand, an empty result).
    AddCsg {
        /// `Union`, `Intersection` or `Difference`.
        op: BooleanOp,
        /// The node's name; `None`: the operation's ("Union"). Made unique
        /// with a `.001`-style suffix when taken.
        #[serde(default)]
        name: Option<String>,
        /// Nodes (meshes or CSG nodes) to move under it (default: none).
        #[serde(default)]
        operands: Vec<NodeRef>,
        /// The new node's parent; `None` (the default): the top level.
        #[serde(default)]
        parent: Option<NodeRef>,
        /// The new node's local transform (default: identity).
        #[serde(default)]
        transform: NodeTransform,
    },
    /// Sets a CSG node's operation; refused when the result would not
    /// evaluate ("the intersection of Box and Ball is empty"). A node
    /// still named after its old operation ("Union", "Union.001") takes
    /// the new one's name; a name the user gave stays.
    SetCsgOp {
        /// A CSG node.
        node: NodeRef,
        /// The new operation.
        op: BooleanOp,
    },
    /// Turns a CSG node into a plain mesh node holding its solid (same id,
    /// name and place); its operands are deleted. One undo step.
    ApplyCsg {
        /// A CSG node with operands.
        node: NodeRef,
    },
    /// A one-shot boolean (Blender's Boolean applied at once): `node`'s
    /// mesh becomes `node` op `other` (in `node`'s space), and `other` is
    /// deleted with its descendants. UVs and creases of `node`'s faces and
    /// edges the cut did not touch are kept. One undo step.
    Boolean {
        /// The mesh node that is kept (the active object).
        node: NodeRef,
        /// A mesh or CSG node, deleted.
        other: NodeRef,
        /// `Union`, `Intersection` or `Difference` (`node` minus `other`).
        op: BooleanOp,
    },

    // ----- curves and surfaces (control points in the node's local space) -----
    /// Adds a curve node.
    AddCurve {
        /// The new node's name, made unique with a `.001`-style suffix when taken.
        name: String,
        /// The curve's kind and control points (local space).
        curve: CurveSpec,
        /// The new node's parent; `None` (the default): the top level.
        #[serde(default)]
        parent: Option<NodeRef>,
        /// The new node's local transform, relative to its parent (default:
        /// identity).
        #[serde(default)]
        transform: NodeTransform,
    },
    /// Adds a surface node.
    AddSurface {
        /// The new node's name, made unique with a `.001`-style suffix when taken.
        name: String,
        /// The surface's kind and control points (local space).
        surface: SurfaceSpec,
        /// The new node's parent; `None` (the default): the top level.
        #[serde(default)]
        parent: Option<NodeRef>,
        /// The new node's local transform, relative to its parent (default:
        /// identity).
        #[serde(default)]
        transform: NodeTransform,
    },
    /// Moves control points of a curve or surface (by index, as `hedra
    /// info --json` counts them; NURBS surfaces: `i * nv + j`).
    SetControlPoints {
        /// A curve or surface node.
        node: NodeRef,
        /// `(index, new position)` pairs, positions in the node's local space.
        points: Vec<(u32, DVec3)>,
    },
    /// Sets the weights of control points (each must be positive).
    SetWeights {
        /// A curve or surface node.
        node: NodeRef,
        /// `(index, weight)` pairs; each weight must be positive.
        weights: Vec<(u32, f64)>,
    },
    /// Inserts a knot without changing the shape (surfaces: in `direction`).
    InsertKnot {
        /// A curve or NURBS surface node.
        node: NodeRef,
        /// The parameter value of the new knot, inside the knot range.
        at: f64,
        /// For surfaces, which parameter (default `U`); ignored for curves.
        #[serde(default)]
        direction: ParameterDirection,
    },
    /// Raises the degree by one without changing the shape (surfaces: in
    /// `direction`).
    ElevateDegree {
        /// A curve, NURBS surface or Bézier triangle node.
        node: NodeRef,
        /// For NURBS surfaces, which parameter (default `U`); ignored otherwise.
        #[serde(default)]
        direction: ParameterDirection,
    },

    /// Replaces a curve node's definition (kind, points, tangents, keys,
    /// joins, level): what a curve's panel and its tangent handles send.
    SetCurve {
        /// A curve node.
        node: NodeRef,
        /// The new curve, in the node's local space.
        curve: CurveSpec,
    },
    /// Inserts a defining point where the curve is at parameter `at` (of
    /// the drawn NURBS form, as `hedra eval` takes it): a knot for NURBS,
    /// a de Casteljau split for poly-Bézier (shape kept exactly), the
    /// curve's point for interpolating kinds, a polygon point for Chaikin
    /// and fractals.
    InsertCurvePoint {
        /// A curve node.
        node: NodeRef,
        /// The parameter, inside the open domain.
        at: f64,
    },
    /// Deletes defining points (poly-Bézier: anchors, each with its handles).
    DeleteCurvePoints {
        /// A curve node.
        node: NodeRef,
        /// Indices as `SetControlPoints` counts them.
        points: Vec<u32>,
    },
    /// Adds a point past one end of an open curve (Blender's E in curve
    /// edit mode).
    ExtrudeCurve {
        /// A curve node.
        node: NodeRef,
        /// `End` (the default) or `Start`.
        #[serde(default)]
        end: CurveEnd,
        /// The new point in the node's local space.
        to: DVec3,
    },
    /// Opens or closes a curve (Blender's Alt+C).
    SetCurveClosed {
        /// A curve node.
        node: NodeRef,
        /// True to close.
        closed: bool,
    },
    /// Reverses a curve's direction; the shape stays.
    ReverseCurve {
        /// A curve node.
        node: NodeRef,
    },
    /// Splits an open curve at a parameter: the node keeps the first part,
    /// a new node (same parent and transform) gets the second.
    SplitCurve {
        /// A curve node.
        node: NodeRef,
        /// The parameter (of the drawn NURBS form), inside the open domain.
        at: f64,
        /// The new node's name; `None`: the curve's name, made unique.
        #[serde(default)]
        name: Option<String>,
    },
    /// Appends `second` to the end of `first` (same kind, both open) and
    /// deletes `second`; where their ends meet the point is shared, else a
    /// straight piece bridges them.
    JoinCurves {
        /// The curve that stays.
        first: NodeRef,
        /// The curve appended (its points taken into `first`'s space) and deleted.
        second: NodeRef,
    },
    /// Sets the continuity of a poly-Bézier joint and turns its outgoing
    /// handle to hold it.
    SetCurveJoin {
        /// A poly-Bézier curve node.
        node: NodeRef,
        /// The joint (see [`CurveSpec::PolyBezier`]).
        joint: u32,
        /// `C0`, `C1` or `G1`.
        join: Join,
    },
    /// Replaces a curve by its NURBS form (exact where the kind is
    /// piecewise polynomial or a polyline).
    ConvertCurveToNurbs {
        /// A curve node.
        node: NodeRef,
    },

    // ----- surfaces and meshes from curves, following them -----
    /// Makes a node from curve nodes (extrude, revolve, sweep, two-rail
    /// sweep, loft) that remembers them: it is made again, in the same undo
    /// step, whenever a command changes one of them (see
    /// [`crate::construction`]). The result is a NURBS surface or a mesh,
    /// placed where its inputs are (world terms), at the top level.
    MakeFromCurves {
        /// The new node's name, made unique with a `.001`-style suffix when taken.
        name: String,
        /// What to make from which curves, and the output kind.
        construction: Construction<NodeRef>,
    },
    /// Changes the recipe, inputs or output of a node made from curves; it
    /// is made again.
    SetConstruction {
        /// A node made by [`Command::MakeFromCurves`] and not applied.
        node: NodeRef,
        /// The new construction.
        construction: Construction<NodeRef>,
    },
    /// Freezes nodes made from curves: they keep their geometry and stop
    /// following their inputs (Rhino's history off, Blender's Apply).
    ApplyConstruction {
        /// Nodes made by [`Command::MakeFromCurves`].
        nodes: Vec<NodeRef>,
    },

    // ----- the G1 join of a Bézier triangle and a Bézier patch -----
    /// Joins a Bézier triangle and a Bézier patch that share an edge (seed
    /// 002's exercise): C0 (the lower degree along the edge elevated, the
    /// patch's boundary row put on the triangle's edge), then G1 (the
    /// patch's row next to the edge set so that the tangent planes agree),
    /// in one undo step. The join is kept: later changes of either node are
    /// followed in the same step (see [`crate::join`]).
    MakeG1Join {
        /// The Bézier triangle node (it leads).
        triangle: NodeRef,
        /// The Bézier patch node (a NURBS surface of one span, unit
        /// weights); its points next to the edge are adjusted.
        quad: NodeRef,
    },
    /// Ends the G1 joins a node is in (as the patch or the triangle): both
    /// keep their shapes and move independently again.
    BreakG1Join {
        /// A joined patch or triangle node.
        node: NodeRef,
    },

    // ----- mesh editing (element positions in the node's local space) -----
    /// Moves vertices by an offset.
    MoveVertices {
        /// The mesh node to edit.
        node: NodeRef,
        /// The vertices, by id or by a predicate in local space.
        vertices: VertexSet,
        /// The offset in the node's local space.
        offset: DVec3,
    },
    /// Sets vertex positions (what the edit-mode move tool sends).
    SetVertexPositions {
        /// The mesh node to edit.
        node: NodeRef,
        /// `(vertex id, new position)` pairs, positions in local space.
        positions: Vec<(u32, DVec3)>,
    },
    /// Extrudes each face on its own along its normal.
    ExtrudeFaces {
        /// The mesh node to edit.
        node: NodeRef,
        /// The faces, by id or by a predicate in local space.
        faces: FaceSet,
        /// How far along each face's normal, in local units (negative: inwards).
        distance: f64,
    },
    /// Extrudes faces as one region along their average normal; faces
    /// inside the region stay joined.
    ExtrudeRegion {
        /// The mesh node to edit.
        node: NodeRef,
        /// The faces, by id or by a predicate in local space.
        faces: FaceSet,
        /// How far along the region's average normal, in local units.
        distance: f64,
    },
    /// Insets each face on its own: a border `thickness` wide, the inner face
    /// pushed by `depth` along the normal.
    InsetFaces {
        /// The mesh node to edit.
        node: NodeRef,
        /// The faces, by id or by a predicate in local space.
        faces: FaceSet,
        /// Border width in local units.
        thickness: f64,
        /// How far the inner face moves along its normal (default 0; negative: in).
        #[serde(default)]
        depth: f64,
    },
    /// Insets faces as one region: a border `thickness` wide inside the
    /// region's outline, the region pushed by `depth` along its normal.
    InsetRegion {
        /// The mesh node to edit.
        node: NodeRef,
        /// The faces, by id or by a predicate in local space.
        faces: FaceSet,
        /// Border width in local units.
        thickness: f64,
        /// How far the region moves along its average normal (default 0).
        #[serde(default)]
        depth: f64,
    },
    /// Cuts `cuts` evenly spaced edge loops across the ring of quads through one edge.
    LoopCut {
        /// The mesh node to edit.
        node: NodeRef,
        /// Exactly one edge of the quad ring to cut across.
        edge: EdgeSet,
        /// Number of loops (default 1).
        #[serde(default = "one")]
        cuts: u32,
    },
    /// Splits edges into `cuts + 1` equal parts.
    SubdivideEdges {
        /// The mesh node to edit.
        node: NodeRef,
        /// The edges, by id or by a predicate in local space.
        edges: EdgeSet,
        /// New vertices per edge (default 1: split in half).
        #[serde(default = "one")]
        cuts: u32,
    },
    /// Joins two vertices of one face by a new edge, splitting the face.
    ConnectVertices {
        /// The mesh node to edit.
        node: NodeRef,
        /// Exactly two vertices that share a face and no edge.
        vertices: VertexSet,
    },
    /// Splits faces into triangles along their ear-clipping diagonals.
    Triangulate {
        /// The mesh node to edit.
        node: NodeRef,
        /// The faces, by id or by a predicate in local space.
        faces: FaceSet,
        /// Which diagonals: `Beauty` (most regular triangles), `Fan` (from
        /// each face's first corner) or `Clip` (plain ear clipping, the
        /// default, which is what files written before the choice existed
        /// replay).
        #[serde(default, skip_serializing_if = "is_clip")]
        method: TriangulateMethod,
    },
    /// Joins neighbouring triangles of the faces into quads, best pairs
    /// first (Blender's Tris to Quads); other faces stay as they are.
    TrisToQuads {
        /// The mesh node to edit.
        node: NodeRef,
        /// The faces, by id or by a predicate in local space; only the
        /// triangles among them are joined.
        faces: FaceSet,
        /// The largest angle between two triangles' normals that still
        /// joins them, in degrees (default 40, as Blender).
        #[serde(default = "join_limit_degrees")]
        face_degrees: f64,
        /// The largest distance of a quad's corner from a right angle, in
        /// degrees (default 40, as Blender).
        #[serde(default = "join_limit_degrees")]
        shape_degrees: f64,
    },
    /// Cuts faces with a plane (Blender's Bisect): edges crossing it are
    /// split, faces split along it; optionally one side is deleted and the
    /// cut filled.
    Bisect {
        /// The mesh node to edit.
        node: NodeRef,
        /// The faces to cut, by id or by a predicate in local space.
        faces: FaceSet,
        /// A point on the plane, in the node's local space.
        point: DVec3,
        /// The plane's normal, in local space (any length but zero).
        normal: DVec3,
        /// Which side to delete after cutting (default: neither).
        #[serde(default)]
        clear: BisectClear,
        /// Close each cut loop left open by the clear with a face.
        #[serde(default)]
        fill: bool,
    },
    /// Spins a profile around an axis in steps (Blender's Spin): a region
    /// of faces sweeps a solid (its faces end as the end cap), boundary
    /// edges sweep a surface of quads. A full turn (±360°) joins the last
    /// step to the first; vertices on the axis are shared by every step.
    /// See `hedra_geom::modeling::spin`.
    Spin {
        /// The mesh node to edit.
        node: NodeRef,
        /// What to sweep: `Faces(…)` or `Edges(…)` (boundary edges only).
        profile: ProfileSet,
        /// A point on the axis, in the node's local space (the GUI sends
        /// the 3D cursor).
        center: DVec3,
        /// The axis direction in local space, any length but zero (the GUI
        /// sends the view direction); positive degrees turn
        /// counter-clockwise seen from its tip.
        axis: DVec3,
        /// The whole sweep's angle in degrees, not zero; ±360 closes.
        degrees: f64,
        /// Steps the angle is divided into (at least 1; 3 for a full turn).
        steps: u32,
    },
    /// Screws a profile around an axis (Blender's Screw): a spin of
    /// `turns` full turns that advances `pitch` along the axis per turn.
    /// Its ends never join, unless `pitch` is 0 (then it is a spin).
    /// See `hedra_geom::modeling::screw`.
    Screw {
        /// The mesh node to edit.
        node: NodeRef,
        /// What to sweep: `Faces(…)` or `Edges(…)` (boundary edges only).
        profile: ProfileSet,
        /// A point on the axis, in the node's local space.
        center: DVec3,
        /// The axis direction in local space, any length but zero; the
        /// screw turns counter-clockwise seen from its tip.
        axis: DVec3,
        /// Full turns (default 1).
        #[serde(default = "one")]
        turns: u32,
        /// Steps per turn.
        steps: u32,
        /// Distance along the axis per turn, in local units (negative:
        /// against the axis).
        pitch: f64,
    },
    /// Cuts faces along a path of points on the surface (Blender's Knife,
    /// K, without cut-through): each pair of consecutive points and the
    /// view direction span a curtain, and the faces the cut walks across
    /// from the first point to the second are split where the curtain
    /// meets them. Only the faces on that walk are cut, not the ones
    /// behind. Path ends strictly inside a face are dropped (the cut starts
    /// and ends at the first and last edge it crosses); see
    /// `hedra_geom::modeling::knife`. The cut edges are the decision's
    /// `created_edges`.
    Knife {
        /// The mesh node to edit.
        node: NodeRef,
        /// The path, in the node's local space: at least two points, each
        /// on a face, an edge or a vertex of the mesh (as a viewport pick
        /// gives them; a point on a vertex uses it, one on an edge splits
        /// it there).
        points: Vec<DVec3>,
        /// The direction the path is seen along, in local space (from the
        /// eye into the scene; any length but zero).
        view: DVec3,
    },
    /// Tears the mesh open along edges (Blender's Rip, V in edit mode):
    /// each edge becomes two boundary edges, one per side, and the vertices
    /// along them are duplicated so the sides come apart; a path that ends
    /// inside the surface keeps its end vertex (a slit).
    Rip {
        /// The mesh node to edit.
        node: NodeRef,
        /// The edges to rip, each with a face on both sides.
        edges: EdgeSet,
    },
    /// Rips one vertex off one of its faces (Blender's Rip on a single
    /// vertex): the face's corner gets a vertex of its own.
    RipVertex {
        /// The mesh node to edit.
        node: NodeRef,
        /// Exactly one vertex.
        vertex: VertexSet,
        /// Exactly one face at the vertex (Blender: the one nearest the mouse).
        face: FaceSet,
    },
    /// Vertex split, the inverse of an edge collapse (Hoppe's progressive
    /// meshes, seed 004): the edges of `vertex` from the one to `first` to
    /// the one to `last`, counter-clockwise seen from the front (the order
    /// of the vertex's fan), move to a new vertex at `position`, joined to
    /// `vertex` by a new edge; the faces on the far side of `first` and
    /// `last` gain a side each.
    SplitVertex {
        /// The mesh node to edit.
        node: NodeRef,
        /// Exactly one vertex to split.
        vertex: VertexSet,
        /// The neighbour whose edge is the first to move.
        first: VertexSet,
        /// The neighbour whose edge is the last to move (may be `first`).
        last: VertexSet,
        /// Where the new vertex goes, in local space.
        position: DVec3,
    },
    /// One Euler operator on a mesh (Mäntylä's MEV, KEV, MEF, KEF, KEMR,
    /// MEKR, KFMRH, MFKRH, MVFS, KVFS): the low-level steps every modeling
    /// operation is made of, for teaching and for building faces with
    /// rings. Each keeps V − E + F − (L − F) = 2(S − H).
    Euler {
        /// The mesh node to edit.
        node: NodeRef,
        /// The operator and its arguments.
        op: EulerOp,
    },
    /// Sets the subdivision crease sharpness of edges: 0 is smooth, 10
    /// infinitely sharp, values between fade out after that many levels.
    SetEdgeCrease {
        /// The mesh node to edit.
        node: NodeRef,
        /// The edges, by id or by a predicate in local space.
        edges: EdgeSet,
        /// 0 (smooth) to 10 (infinitely sharp); outside that range is refused.
        sharpness: f64,
    },
    /// Sets the subdivision corner sharpness of vertices (0 … 10).
    SetVertexCrease {
        /// The mesh node to edit.
        node: NodeRef,
        /// The vertices, by id or by a predicate in local space.
        vertices: VertexSet,
        /// 0 (smooth) to 10 (infinitely sharp); outside that range is refused.
        sharpness: f64,
    },
    /// Makes a chain of edges one tapered crease: sharpness `start` at
    /// vertex `from` (an end of the path the edges form, or any vertex of
    /// their loop), `end` at the other end, linear in arc length between
    /// (each edge takes the value at its midpoint, measured when the command
    /// runs). The edges leave any crease or taper they had; `SetEdgeCrease`
    /// on an edge takes it out of its taper again.
    SetCreaseTaper {
        /// The mesh node to edit.
        node: NodeRef,
        /// The chain's edges, in any order.
        edges: EdgeSet,
        /// The vertex where the chain starts (exactly one).
        from: VertexSet,
        /// Sharpness at `from`, 0 … 10.
        start: f64,
        /// Sharpness at the other end, 0 … 10.
        end: f64,
    },
    /// Makes faces subdivision holes (`hole: true`) or clears their holes
    /// (OpenSubdiv's face holes): a hole is refined like any face and its
    /// neighbours keep their shape, but it leaves no faces in the subdivided
    /// result (viewport, export, apply). The cage keeps every face.
    SetFaceHole {
        /// The mesh node to edit.
        node: NodeRef,
        /// The faces, by id or by a predicate in local space.
        faces: FaceSet,
        /// True makes holes, false clears them.
        hole: bool,
    },
    /// Moves every cage vertex onto the limit surface of its subdivision
    /// (the node's modifier options, or Catmull-Clark).
    SnapToLimit {
        /// The mesh node to edit.
        node: NodeRef,
    },
    /// Removes edges, merging the faces on their two sides.
    DissolveEdges {
        /// The mesh node to edit.
        node: NodeRef,
        /// The edges, by id or by a predicate in local space.
        edges: EdgeSet,
    },
    /// Removes vertices of valence 2, joining their edges.
    DissolveVertices {
        /// The mesh node to edit.
        node: NodeRef,
        /// The vertices, by id or by a predicate in local space.
        vertices: VertexSet,
    },
    /// Reverses every face of the mesh.
    FlipNormals {
        /// The mesh node to edit.
        node: NodeRef,
    },
    /// Turns a closed mesh that faces inwards outwards (no change otherwise).
    RecalculateNormals {
        /// The mesh node to edit.
        node: NodeRef,
    },
    /// Deletes faces, keeping their edges: each becomes a hole.
    MakeHoles {
        /// The mesh node to edit.
        node: NodeRef,
        /// The faces to remove; faces touching a boundary are refused.
        faces: FaceSet,
    },
    /// Fills the boundary loops through the given edges with a face each.
    FillHoles {
        /// The mesh node to edit.
        node: NodeRef,
        /// An edge of each boundary loop to fill.
        edges: EdgeSet,
    },
    /// Collapses each edge into a vertex at its midpoint.
    CollapseEdges {
        /// The mesh node to edit.
        node: NodeRef,
        /// The edges, by id or by a predicate in local space.
        edges: EdgeSet,
    },
    /// Extrudes boundary edges: a quad on each edge's open side, reaching to
    /// copies of its ends moved by `offset`.
    ExtrudeEdges {
        /// The mesh node to edit.
        node: NodeRef,
        /// Boundary edges (with a face on one side only).
        edges: EdgeSet,
        /// Where the copied ends go, relative to the originals, in local space.
        offset: DVec3,
    },
    /// Mirrors vertices across the plane through their median perpendicular to an axis.
    MirrorVertices {
        /// The mesh node to edit.
        node: NodeRef,
        /// The vertices, by id or by a predicate in local space.
        vertices: VertexSet,
        /// The axis the mirror plane is perpendicular to.
        axis: MirrorAxis,
    },
    /// Replaces the negative side of the mesh by a mirror image of the positive side.
    Symmetrize {
        /// The mesh node to edit.
        node: NodeRef,
        /// The axis whose positive side is kept and mirrored.
        axis: MirrorAxis,
    },
    /// Slides edge chains along the edges beside them; `factor` in [-1, 1]
    /// picks the side by its sign.
    SlideEdges {
        /// The mesh node to edit.
        node: NodeRef,
        /// The edges, by id or by a predicate in local space.
        edges: EdgeSet,
        /// Fraction of the way along the neighbouring edges, in [-1, 1]; the sign
        /// picks the side.
        factor: f64,
    },
    /// Bevels edges `width` wide; more than one segment rounds the bevel.
    BevelEdges {
        /// The mesh node to edit.
        node: NodeRef,
        /// The edges, by id or by a predicate in local space.
        edges: EdgeSet,
        /// Distance from the old edge to each side of the bevel, in local units.
        width: f64,
        /// Strips across the bevel (default 1: flat; more: rounded).
        #[serde(default = "one")]
        segments: u32,
    },
    /// Cuts vertices off with a face through the points `width` along
    /// their edges (vertex bevel).
    BevelVertices {
        /// The mesh node to edit.
        node: NodeRef,
        /// The vertices, by id or by a predicate in local space.
        vertices: VertexSet,
        /// Distance along each edge to the cut, in local units; less than the edge.
        width: f64,
    },
    /// Merges faces into one by removing the edges between them.
    DissolveFaces {
        /// The mesh node to edit.
        node: NodeRef,
        /// The faces, by id or by a predicate in local space.
        faces: FaceSet,
    },
    /// Deletes faces with the edges and vertices only they use.
    DeleteFaces {
        /// The mesh node to edit.
        node: NodeRef,
        /// The faces, by id or by a predicate in local space.
        faces: FaceSet,
    },
    /// Deletes edges with the faces around them.
    DeleteEdges {
        /// The mesh node to edit.
        node: NodeRef,
        /// The edges, by id or by a predicate in local space.
        edges: EdgeSet,
    },
    /// Deletes vertices with the faces around them.
    DeleteVertices {
        /// The mesh node to edit.
        node: NodeRef,
        /// The vertices, by id or by a predicate in local space.
        vertices: VertexSet,
    },
    /// Merges vertices into one at their centre, the first or the last
    /// given; vertices not joined by edges are welded.
    MergeVertices {
        /// The mesh node to edit.
        node: NodeRef,
        /// The vertices, by id or by a predicate in local space.
        vertices: VertexSet,
        /// Where the merged vertex goes: `Center` (default), `First` or `Last` given.
        #[serde(default, skip_serializing_if = "is_default")]
        at: hedra_geom::modeling::MergePoint,
    },
    /// Welds vertices closer than `distance` to each other (all of the
    /// mesh's unless `vertices` is given).
    MergeByDistance {
        /// The mesh node to edit.
        node: NodeRef,
        /// The vertices to consider (default: all).
        #[serde(default = "all_vertices")]
        vertices: VertexSet,
        /// Vertices closer than this (local units) are welded.
        distance: f64,
    },
    /// Joins two boundary loops (named by some of their edges) with quads.
    BridgeLoops {
        /// The mesh node to edit.
        node: NodeRef,
        /// At least one edge of each of the two boundary loops.
        edges: EdgeSet,
    },
}

use crate::scene::{one, yes};

fn all_vertices() -> VertexSet {
    VertexSet::All
}

fn op_title(op: BooleanOp) -> &'static str {
    match op {
        BooleanOp::Union => "Union",
        BooleanOp::Intersection => "Intersection",
        BooleanOp::Difference => "Difference",
    }
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
            Command::AddKeptMesh { name, .. } => format!("Add Kept Mesh '{name}'"),
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
            Command::AddModifier { modifier, .. } => format!("Add {} Modifier", modifier.name()),
            Command::SetModifier { modifier, .. } => format!("Change {} Modifier", modifier.name()),
            Command::RemoveModifier { .. } => "Remove Modifier".to_string(),
            Command::MoveModifier { .. } => "Move Modifier".to_string(),
            Command::ApplyModifiers { count: Some(1), .. } => "Apply Modifier".to_string(),
            Command::ApplyModifiers { .. } => "Apply Modifiers".to_string(),
            Command::Decimate { .. } => "Decimate".to_string(),
            Command::SetEdgeCrease { sharpness, .. } => format!("Edge Crease {sharpness:.2}"),
            Command::SetVertexCrease { sharpness, .. } => format!("Vertex Crease {sharpness:.2}"),
            Command::SetCreaseTaper { start, end, .. } => {
                format!("Crease Taper {start:.2} to {end:.2}")
            }
            Command::SetFaceHole { hole: true, .. } => "Make Hole".to_string(),
            Command::SetFaceHole { hole: false, .. } => "Clear Hole".to_string(),
            Command::SnapToLimit { .. } => "Snap to Limit Surface".to_string(),
            Command::ConvertSubdivisionToNurbs { .. } => "Convert to NURBS".to_string(),
            Command::AddCurve { name, .. } => format!("Add Curve '{name}'"),
            Command::AddSurface { name, .. } => format!("Add Surface '{name}'"),
            Command::SetControlPoints { points, .. } => {
                format!("Move {}", plural(points.len(), "control point"))
            }
            Command::SetWeights { .. } => "Set Weights".to_string(),
            Command::InsertKnot { at, .. } => format!("Insert Knot {at}"),
            Command::ElevateDegree { .. } => "Elevate Degree".to_string(),
            Command::SetCurve { .. } => "Edit Curve".to_string(),
            Command::InsertCurvePoint { .. } => "Insert Curve Point".to_string(),
            Command::DeleteCurvePoints { points, .. } => match points.len() {
                1 => "Delete Curve Point".to_string(),
                n => format!("Delete {n} Curve Points"),
            },
            Command::ExtrudeCurve { .. } => "Extrude Curve".to_string(),
            Command::SetCurveClosed { closed: true, .. } => "Close Curve".to_string(),
            Command::SetCurveClosed { closed: false, .. } => "Open Curve".to_string(),
            Command::ReverseCurve { .. } => "Reverse Curve".to_string(),
            Command::SplitCurve { .. } => "Split Curve".to_string(),
            Command::JoinCurves { .. } => "Join Curves".to_string(),
            Command::SetCurveJoin { join, .. } => format!("Set Joint {join:?}"),
            Command::ConvertCurveToNurbs { .. } => "Convert to NURBS".to_string(),
            Command::MakeFromCurves { name, construction } => {
                format!("{} '{name}'", construction.recipe.name())
            }
            Command::SetConstruction { construction, .. } => {
                format!("Change {}", construction.recipe.name())
            }
            Command::ApplyConstruction { .. } => "Apply Construction".to_string(),
            Command::MakeG1Join { .. } => "Make G1 Join".to_string(),
            Command::BreakG1Join { .. } => "Break G1 Join".to_string(),
            Command::Duplicate { nodes } => format!("Duplicate {}", plural(nodes.len(), "node")),
            Command::AddCsg { op, .. } => format!("Add CSG {}", op_title(*op)),
            Command::SetCsgOp { op, .. } => format!("CSG {}", op_title(*op)),
            Command::ApplyCsg { .. } => "Apply CSG".to_string(),
            Command::Boolean { op, .. } => format!("Boolean {}", op_title(*op)),
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
            Command::MakeManifold { .. } => "Make Manifold".to_string(),
            Command::TrisToQuads { .. } => "Tris to Quads".to_string(),
            Command::Bisect { .. } => "Bisect".to_string(),
            Command::Spin { .. } => "Spin".to_string(),
            Command::Screw { .. } => "Screw".to_string(),
            Command::Knife { .. } => "Knife".to_string(),
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
            Command::Rip { .. } => "Rip".to_string(),
            Command::RipVertex { .. } => "Rip Vertex".to_string(),
            Command::SplitVertex { .. } => "Split Vertex".to_string(),
            Command::Euler { op, .. } => format!("Euler {}", op.name()),
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

/// Blender's default limit for Tris to Quads' face and shape angles.
fn join_limit_degrees() -> f64 {
    40.0
}

/// A corner of a face loop, where an Euler operator inserts or joins an
/// edge. Named by the half-edge that arrives at it, so a vertex that a
/// loop passes twice (the end of a dangling edge, say) is still one
/// unambiguous corner.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Corner {
    /// The corner at vertex `at` reached along the edge from `from`: on the
    /// face to the left of the half-edge `from` → `at`, between that
    /// half-edge and the next one of its loop.
    At {
        /// The corner's vertex (exactly one).
        at: VertexSet,
        /// The vertex before it on the loop (exactly one, joined to `at`).
        from: VertexSet,
    },
    /// A loop without edges: its lone vertex (left by MVFS, or by KEMR
    /// when a ring is a single vertex).
    Lone(VertexSet),
}

/// An Euler operator and its arguments, for [`Command::Euler`]. Each names
/// its change of V, E, F, loops L, shells S and holes H; the kernel
/// functions are `HalfEdgeMesh::make_edge_vertex` and the others named.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum EulerOp {
    /// MEV (`make_edge_vertex`): a new vertex at `position` joined to the
    /// corner's vertex by a new edge dangling into the corner's face.
    /// V +1, E +1. On a lone vertex the loop becomes a wire of one edge.
    Mev {
        /// Where the edge starts.
        corner: Corner,
        /// The new vertex, in local space.
        position: DVec3,
    },
    /// KEV (`kill_edge_vertex`): removes an edge with an end of valence 1
    /// and that end. V −1, E −1.
    Kev {
        /// Exactly one dangling edge.
        edge: EdgeSet,
    },
    /// MEF (`make_edge_face`): joins two corners of one loop of a face by
    /// a new edge; the part of the loop after `a` keeps the face, the part
    /// after `b` becomes a new face. E +1, F +1, L +1.
    Mef {
        /// The first corner (its side keeps the face).
        a: Corner,
        /// The second corner, on the same loop (its side is the new face).
        b: Corner,
    },
    /// KEF (`kill_edge_face`): removes an edge between two different
    /// faces, which become one. E −1, F −1, L −1.
    Kef {
        /// Exactly one edge.
        edge: EdgeSet,
    },
    /// KEMR (`kill_edge_make_ring`): removes an edge whose two sides lie on
    /// the same loop of one face; the loop falls apart in two and the part
    /// on `to`'s side becomes an inner ring of the face (a lone vertex if
    /// it has no edges left). E −1, L +1.
    Kemr {
        /// The end of the edge whose side keeps the loop's place.
        from: VertexSet,
        /// The other end; its side becomes the new ring.
        to: VertexSet,
    },
    /// MEKR (`make_edge_kill_ring`): joins a corner of one loop of a face
    /// to a corner of one of its rings by a new edge; the ring merges into
    /// the first loop. E +1, L −1.
    Mekr {
        /// A corner on the loop that stays (outer loop or ring).
        a: Corner,
        /// A corner on a ring of the same face.
        ring: Corner,
    },
    /// KFMRH (`kill_face_make_ring_hole`): face `kill` disappears and its
    /// loop becomes an inner ring of face `keep` (Mäntylä's through hole).
    /// F −1; H +1 when both faces are in one shell, else S −1.
    Kfmrh {
        /// The face that gets the ring (exactly one).
        keep: FaceSet,
        /// The face that becomes the ring (exactly one; no rings, sharing
        /// no vertex with `keep`).
        kill: FaceSet,
    },
    /// MFKRH (`make_face_kill_ring_hole`): a ring leaves its face and
    /// becomes the outer loop of a new face. F +1; H −1, or S +1 when the
    /// ring was all that held another shell.
    Mfkrh {
        /// Any corner of the ring, or its lone vertex.
        ring: Corner,
    },
    /// MVFS (`make_vertex_face_shell`): a new shell of one vertex and one
    /// face whose only loop is that vertex. V +1, F +1, L +1, S +1.
    Mvfs {
        /// The vertex, in local space.
        position: DVec3,
    },
    /// KVFS (`kill_vertex_face_shell`): removes a shell of one vertex and
    /// one face. V −1, F −1, L −1, S −1.
    Kvfs {
        /// The lone vertex of the shell (exactly one).
        vertex: VertexSet,
    },
}

impl EulerOp {
    /// The operator's short name, as in the literature (`"MEV"`).
    pub fn name(&self) -> &'static str {
        match self {
            EulerOp::Mev { .. } => "MEV",
            EulerOp::Kev { .. } => "KEV",
            EulerOp::Mef { .. } => "MEF",
            EulerOp::Kef { .. } => "KEF",
            EulerOp::Kemr { .. } => "KEMR",
            EulerOp::Mekr { .. } => "MEKR",
            EulerOp::Kfmrh { .. } => "KFMRH",
            EulerOp::Mfkrh { .. } => "MFKRH",
            EulerOp::Mvfs { .. } => "MVFS",
            EulerOp::Kvfs { .. } => "KVFS",
        }
    }
}
