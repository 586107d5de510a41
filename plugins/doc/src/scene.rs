//! The scene graph: named nodes with a parent, a local transform and content
//! (seed 004: "scene storage as geometry + topology + hierarchy + local/world
//! transforms"). World transforms are derived by composing the parents' local
//! transforms, root first.

use glam::{DMat4, DQuat, DVec2, DVec3};
use hedra_geom::curves::{CurveError, CurveKind, NurbsCurve};
use hedra_geom::subdivision::{Creases, Options as SubdivisionOptions};
use hedra_geom::surfaces::{BezierTriangle, NurbsSurface};
use hedra_geom::{HalfEdgeId, HalfEdgeMesh, Primitive};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, HashMap, HashSet};
use std::fmt;
use std::sync::Arc;

/// A node's stable id: monotonic, written to files, never an ECS entity.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(transparent)]
pub struct NodeId(pub u64);

impl fmt::Display for NodeId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{}", self.0)
    }
}

/// Translation, rotation and scale, applied as T·R·S.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NodeTransform {
    /// Position of the node's origin in its parent's space (world space for a
    /// top-level node).
    #[serde(default)]
    pub translation: DVec3,
    /// Rotation about the node's origin, a unit quaternion.
    #[serde(default = "identity_rotation")]
    pub rotation: DQuat,
    /// Scale along the node's own axes; no component may be zero.
    #[serde(default = "unit_scale")]
    pub scale: DVec3,
}

fn identity_rotation() -> DQuat {
    DQuat::IDENTITY
}
fn unit_scale() -> DVec3 {
    DVec3::ONE
}

impl Default for NodeTransform {
    fn default() -> Self {
        NodeTransform::IDENTITY
    }
}

impl NodeTransform {
    /// No translation or rotation, unit scale.
    pub const IDENTITY: NodeTransform = NodeTransform {
        translation: DVec3::ZERO,
        rotation: DQuat::IDENTITY,
        scale: DVec3::ONE,
    };

    /// A pure translation by `t` (in the parent's space).
    pub fn from_translation(t: DVec3) -> Self {
        NodeTransform {
            translation: t,
            ..Self::IDENTITY
        }
    }
    /// The local-to-parent matrix, T·R·S.
    pub fn to_matrix(&self) -> DMat4 {
        DMat4::from_scale_rotation_translation(self.scale, self.rotation, self.translation)
    }
    /// Decomposes an affine matrix (shear is lost).
    pub fn from_matrix(m: DMat4) -> Self {
        let (scale, rotation, translation) = m.to_scale_rotation_translation();
        NodeTransform {
            translation,
            rotation: rotation.normalize(),
            scale,
        }
    }
    /// True when every component is finite and no scale is zero.
    pub fn is_usable(&self) -> bool {
        self.translation.is_finite()
            && self.rotation.is_finite()
            && self.rotation.length() > 1e-9
            && self.scale.is_finite()
            && self.scale.abs().min_element() > 1e-12
    }
}

/// A mesh node's content: the half-edge mesh (shared between history steps)
/// and, while it is still a pristine primitive, the parameters it was made
/// from, so they can be adjusted.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshContent {
    /// The cage, in the node's local space; shared, so an edit replaces it
    /// rather than changing it in place.
    pub mesh: Arc<HalfEdgeMesh>,
    /// The primitive's parameters while the mesh is unedited; `None` once it
    /// has been edited (or was never a primitive).
    pub primitive: Option<Primitive>,
    /// Flat or smooth normals when drawn and exported.
    pub shading: Shading,
    /// Edge crease and vertex corner sharpness, used by subdivision.
    pub creases: Creases,
    /// The non-destructive subdivision modifier, if the node has one; its
    /// [`stack_position`](SubdivisionModifier::stack_position) places it
    /// among `modifiers`.
    pub subdivision: Option<SubdivisionModifier>,
    /// The modifier stack (Mirror, Array), applied to the cage in order;
    /// see [`MeshContent::evaluated`].
    pub modifiers: Vec<crate::modifiers::MeshModifier>,
    /// Imported UVs and normals of face corners (none for meshes made in Hedra).
    pub corners: CornerAttributes,
    /// The progressive records of the stack's Decimate modifiers, beside
    /// them (see [`MeshContent::refresh_decimations`]); shared, so undo
    /// steps hold them without copies.
    pub decimations: Vec<Arc<crate::modifiers::DecimateRecord>>,
}

impl MeshContent {
    /// A plain mesh: flat shaded, no primitive, creases, modifier or corner attributes.
    pub fn new(mesh: Arc<HalfEdgeMesh>) -> Self {
        MeshContent {
            mesh,
            primitive: None,
            shading: Shading::Flat,
            creases: Creases::default(),
            subdivision: None,
            modifiers: Vec::new(),
            corners: CornerAttributes::default(),
            decimations: Vec::new(),
        }
    }
}

/// Per-corner attributes of a mesh: UVs and custom normals of face corners.
///
/// A corner (face `f`, vertex `v`) is keyed by the half-edge of `f` that
/// leaves `v` (its origin is `v`, its face is `f`). Half-edge ids are never
/// reused, so the attributes of corners that survive an edit stay valid;
/// corners an edit creates have none. Any corner may lack either attribute.
///
/// * `uvs`: texture coordinates with v pointing up (OBJ's and Blender's
///   convention; glTF's v = 1 − v). They follow the mesh through edits.
/// * `normals`: unit normals in the node's local space, as the imported file
///   gave them. They describe the imported geometry, so an edit that moves
///   vertices or changes the topology drops them all (see
///   [`follow_edit`](Self::follow_edit)).
///
/// The maps are shared (`Arc`): every undo step and the autosave copy hold
/// a node's attributes without copying them; an edit makes its own map.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct CornerAttributes {
    #[serde(
        default,
        skip_serializing_if = "shared_map::is_empty",
        with = "shared_map"
    )]
    /// Texture coordinates by face corner: the corner at the half-edge's
    /// origin, in its face. v runs up (as in OBJ).
    pub uvs: Arc<BTreeMap<HalfEdgeId, DVec2>>,
    #[serde(
        default,
        skip_serializing_if = "shared_map::is_empty",
        with = "shared_map"
    )]
    /// Custom unit normals by face corner, in the node's local space; corners
    /// without one use the shading's normal.
    pub normals: Arc<BTreeMap<HalfEdgeId, DVec3>>,
}

/// Serde for a shared map, written as the map itself (serde's `rc` feature
/// would do the same, but turning it on would rebuild Bevy).
mod shared_map {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};
    use std::collections::BTreeMap;
    use std::sync::Arc;

    pub fn is_empty<K, V>(map: &Arc<BTreeMap<K, V>>) -> bool {
        map.is_empty()
    }
    pub fn serialize<K: Serialize, V: Serialize, S: Serializer>(
        map: &Arc<BTreeMap<K, V>>,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        map.as_ref().serialize(s)
    }
    pub fn deserialize<'de, K, V, D>(d: D) -> Result<Arc<BTreeMap<K, V>>, D::Error>
    where
        K: Deserialize<'de> + Ord,
        V: Deserialize<'de>,
        D: Deserializer<'de>,
    {
        BTreeMap::deserialize(d).map(Arc::new)
    }
}

impl CornerAttributes {
    /// True when no corner has a UV or a normal.
    pub fn is_empty(&self) -> bool {
        self.uvs.is_empty() && self.normals.is_empty()
    }

    /// Face corners of `mesh` (live half-edges with a face).
    pub fn corner_count(mesh: &HalfEdgeMesh) -> usize {
        mesh.faces().map(|f| mesh.face_degree(f)).sum()
    }

    /// Keeps only finite values on live corners of `mesh` (after loading a
    /// file that might not match its mesh).
    pub fn retain_valid(&mut self, mesh: &HalfEdgeMesh) {
        let corner = |h: &HalfEdgeId| mesh.is_halfedge(*h) && mesh.face(*h).is_some();
        let uv_ok = |h: &HalfEdgeId, uv: &DVec2| corner(h) && uv.is_finite();
        let normal_ok =
            |h: &HalfEdgeId, n: &DVec3| corner(h) && n.is_finite() && n.length_squared() > 0.0;
        // Copied only when something goes: shared maps stay shared.
        if !self.uvs.iter().all(|(h, uv)| uv_ok(h, uv)) {
            Arc::make_mut(&mut self.uvs).retain(|h, uv| uv_ok(h, uv));
        }
        if !self.normals.iter().all(|(h, n)| normal_ok(h, n)) {
            Arc::make_mut(&mut self.normals).retain(|h, n| normal_ok(h, n));
        }
    }

    /// The attributes after `before` was edited into `after`: normals are
    /// dropped when the mesh changed at all; each UV stays with its corner,
    /// found as the half-edge of the same face that leaves the same vertex
    /// (usually the same id; after a flip it is a neighbouring half-edge;
    /// after a rip, the half-edge of the same face leaving the vertex's new
    /// copy). UVs of corners that no longer exist are dropped.
    pub fn follow_edit(&self, before: &HalfEdgeMesh, after: &HalfEdgeMesh) -> CornerAttributes {
        if before == after {
            return self.clone();
        }
        let mut uvs = BTreeMap::new();
        let mut moved = Vec::new();
        for (&h, &uv) in self.uvs.iter() {
            if !before.is_halfedge(h) || !after.is_halfedge(h) {
                continue;
            }
            let v = before.origin(h);
            // A ripped edge's half-edge leaves its face for the boundary;
            // the face keeps the corner on a new half-edge.
            let Some(f) = after
                .face(h)
                .or(before.face(h).filter(|&f| after.is_face(f)))
            else {
                continue;
            };
            if after.face(h) == Some(f) && after.origin(h) == v {
                uvs.insert(h, uv);
            } else if let Some(c) = after.face_halfedges(f).find(|&x| after.origin(x) == v) {
                moved.push((c, uv));
            } else if let Some(c) = after.face_halfedges(f).find(|&x| {
                // The vertex was copied (rip): the new vertex at its place.
                let o = after.origin(x);
                !before.is_vertex(o) && after.position(o) == before.position(v)
            }) {
                moved.push((c, uv));
            }
        }
        // A corner that kept its half-edge wins over a UV moved onto it.
        for (c, uv) in moved {
            uvs.entry(c).or_insert(uv);
        }
        CornerAttributes {
            uvs: Arc::new(uvs),
            normals: Arc::default(),
        }
    }
}

/// A subdivision modifier on a mesh node (Blender's Subdivision Surface
/// modifier): the cage stays editable, the viewport shows the smooth result.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct SubdivisionModifier {
    /// Scheme, boundary rule and crease method.
    #[serde(default)]
    pub options: SubdivisionOptions,
    /// Levels shown in the viewport.
    #[serde(default = "one")]
    pub viewport_level: u32,
    /// Levels written by export.
    #[serde(default = "two")]
    pub export_level: u32,
    /// Draw the cage's edges over the smooth result.
    #[serde(default = "yes")]
    pub show_cage: bool,
    /// Where subdivision runs in the node's modifier stack: after this many
    /// stack modifiers (0: on the cage, before all of them). `None` (the
    /// default): after all of them, Blender's usual Mirror → Subdivision
    /// order, which welds the halves before smoothing them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stack_position: Option<usize>,
}

/// Serde defaults shared by the document's stored types.
pub(crate) fn one() -> u32 {
    1
}
fn two() -> u32 {
    2
}
pub(crate) fn yes() -> bool {
    true
}

impl Default for SubdivisionModifier {
    fn default() -> Self {
        SubdivisionModifier::with_level(1)
    }
}

impl SubdivisionModifier {
    /// Catmull-Clark with `level` in the viewport and at least 2 on export.
    pub fn with_level(level: u32) -> Self {
        SubdivisionModifier {
            options: SubdivisionOptions::default(),
            viewport_level: level,
            export_level: level.max(2),
            show_cage: true,
            stack_position: None,
        }
    }
}

/// How a mesh is shaded: one normal per face (split at every edge, so a cube
/// shows crisp faces) or per vertex (area-weighted average).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Shading {
    /// One normal per face.
    #[default]
    Flat,
    /// Area-weighted averaged normals per vertex.
    Smooth,
}

/// What a node holds.
#[derive(Clone, Debug, PartialEq)]
#[allow(
    clippy::large_enum_variant,
    reason = "a few hundred bytes per node; boxing the mesh content would change every match on it for nothing measurable"
)]
pub enum NodeContent {
    /// A transform-only node for grouping.
    Empty,
    /// A polygon mesh.
    Mesh(MeshContent),
    /// A free-form curve: its kind (NURBS, Catmull-Rom, poly-Bézier, Koch,
    /// …) and the NURBS form everything draws and evaluates
    /// ([`CurveContent::nurbs`]).
    Curve(Arc<CurveContent>),
    /// A free-form surface.
    Surface(Arc<SurfaceShape>),
    /// A CSG node: its children are its operands, combined by one boolean
    /// (see [`crate::csg`]); its solid is evaluated, not stored.
    Csg(crate::csg::CsgContent),
    /// A polygon mesh kept as it came from a file because a half-edge
    /// mesh cannot hold it (not manifold; see [`crate::kept`]).
    Kept(crate::kept::KeptMeshContent),
}

impl NodeContent {
    /// A short kind name for listings ("empty", "mesh", "curve", "surface").
    pub fn kind(&self) -> &'static str {
        match self {
            NodeContent::Empty => "empty",
            NodeContent::Mesh(_) => "mesh",
            NodeContent::Curve(_) => "curve",
            NodeContent::Surface(_) => "surface",
            NodeContent::Csg(_) => "csg",
            NodeContent::Kept(_) => "kept mesh",
        }
    }
    /// The mesh cage, for a mesh node.
    pub fn mesh(&self) -> Option<&HalfEdgeMesh> {
        match self {
            NodeContent::Mesh(m) => Some(&m.mesh),
            _ => None,
        }
    }
}

/// A curve node's content: the [`CurveKind`] the user defined and edits,
/// and its NURBS form, computed once when the content is made (so it is
/// always in step with the kind). Readers that draw, evaluate, export or
/// revolve a curve use [`nurbs`](Self::nurbs); the control-point editor
/// shows and moves [`control_points`](Self::control_points), the kind's
/// defining points (`SetControlPoints` indexes them).
#[derive(Clone, Debug, PartialEq)]
pub struct CurveContent {
    kind: CurveKind,
    nurbs: Arc<NurbsCurve>,
    tolerance: Option<f64>,
}

impl CurveContent {
    /// The content of a curve of this kind, its NURBS form computed.
    ///
    /// # Errors
    /// What [`CurveKind::check`] finds ("Lagrange needs 2 points or more").
    pub fn new(kind: CurveKind) -> Result<Self, CurveError> {
        let form = kind.to_nurbs()?;
        Ok(CurveContent {
            kind,
            nurbs: Arc::new(form.curve),
            tolerance: form.tolerance,
        })
    }
    /// A NURBS curve node's content.
    pub fn from_nurbs(curve: NurbsCurve) -> Self {
        let nurbs = Arc::new(curve.clone());
        CurveContent {
            kind: CurveKind::Nurbs(curve),
            nurbs,
            tolerance: None,
        }
    }
    /// The kind and its defining data.
    pub fn kind(&self) -> &CurveKind {
        &self.kind
    }
    /// The NURBS form: what is drawn, evaluated, exported.
    pub fn nurbs(&self) -> &Arc<NurbsCurve> {
        &self.nurbs
    }
    /// `None` when the NURBS form is exact; else its measured largest
    /// distance from the kind's curve (high-degree Lagrange).
    pub fn tolerance(&self) -> Option<f64> {
        self.tolerance
    }
    /// The defining points a user edits: NURBS control points,
    /// interpolation points, poly-Bézier anchors and handles, a Chaikin
    /// polygon, a fractal's initiator.
    pub fn control_points(&self) -> &[DVec3] {
        self.kind.points()
    }
    /// The points the control-point editor shows and moves: the defining
    /// points, then a Hermite curve's tangent-handle ends
    /// ([`CurveKind::edit_points`]); `SetControlPoints` indexes these.
    pub fn edit_points(&self) -> Vec<DVec3> {
        self.kind.edit_points()
    }
    /// The weights of the control points, for a NURBS curve; `None` for
    /// the other kinds (they have none).
    pub fn weights(&self) -> Option<&[f64]> {
        match &self.kind {
            CurveKind::Nurbs(c) => Some(c.weights()),
            _ => None,
        }
    }
}

/// A surface node's shape: a NURBS surface (Bézier patches are clamped
/// NURBS) or a Bézier triangle.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum SurfaceShape {
    /// A NURBS surface.
    Nurbs(NurbsSurface),
    /// A Bézier triangle.
    Triangle(BezierTriangle),
}

impl SurfaceShape {
    /// The control points (NURBS: `i * nv + j`; triangle: rows of equal i).
    pub fn control_points(&self) -> &[DVec3] {
        match self {
            SurfaceShape::Nurbs(s) => s.points(),
            SurfaceShape::Triangle(t) => &t.points,
        }
    }

    /// Positions, normals and triangles within about `tolerance` of the surface.
    pub fn tessellate(&self, tolerance: f64) -> (Vec<DVec3>, Vec<DVec3>, Vec<[u32; 3]>) {
        match self {
            SurfaceShape::Nurbs(s) => {
                let m = hedra_geom::surfaces::tessellate::tessellate_nurbs(s, tolerance);
                (m.positions, m.normals, m.triangles)
            }
            SurfaceShape::Triangle(t) => {
                // The chord error of a degree-n patch falls with the square of the step.
                let size = t
                    .points
                    .iter()
                    .map(|p| (*p - t.points[0]).length())
                    .fold(0.0, f64::max);
                let steps = ((t.degree as f64 * size / tolerance.max(1e-9)).sqrt().ceil() as usize)
                    .clamp(4, 256);
                let (positions, barys, triangles) = t.tessellate(steps);
                let normals = barys
                    .iter()
                    .map(|&b| {
                        let du = t.directional_derivative(b, DVec3::new(1.0, 0.0, -1.0));
                        let dv = t.directional_derivative(b, DVec3::new(0.0, 1.0, -1.0));
                        du.cross(dv).normalize_or_zero()
                    })
                    .collect();
                (positions, normals, triangles)
            }
        }
    }
}

/// A scene-graph node.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// The node's id, unique in its document and never reused.
    pub id: NodeId,
    /// The node's name; commands and imports keep names unique.
    pub name: String,
    /// The parent node; `None` at the top level.
    pub parent: Option<NodeId>,
    /// The local transform, relative to the parent (to the world at the top
    /// level).
    pub transform: NodeTransform,
    /// False when hidden; a hidden node hides its descendants too.
    pub visible: bool,
    /// What the node holds.
    pub content: NodeContent,
    /// How the content was made from other nodes, while it follows them
    /// (see [`crate::construction`]); `None` for ordinary nodes and once
    /// applied (frozen).
    pub construction: Option<crate::construction::Construction>,
    /// On a Bézier patch node kept G1 to a Bézier triangle: the triangle
    /// (see [`crate::join`]); `None` otherwise.
    pub g1_join: Option<crate::join::G1Join>,
}

/// The scene: the single source of truth for what the user made.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Document {
    pub(crate) nodes: BTreeMap<NodeId, Node>,
    pub(crate) next_node_id: u64,
}

impl Document {
    /// An empty document; the first node gets id 1.
    pub fn new() -> Self {
        Document {
            nodes: BTreeMap::new(),
            next_node_id: 1,
        }
    }
    /// The node with this id, if there is one.
    pub fn node(&self, id: NodeId) -> Option<&Node> {
        self.nodes.get(&id)
    }
    /// All nodes in id order (creation order).
    pub fn nodes(&self) -> impl Iterator<Item = &Node> {
        self.nodes.values()
    }
    /// How many nodes the document has.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }
    /// The id the next new node gets.
    pub fn next_node_id(&self) -> NodeId {
        NodeId(self.next_node_id)
    }
    /// The node with exactly this name, if there is one.
    pub fn find_by_name(&self, name: &str) -> Option<&Node> {
        self.nodes.values().find(|n| n.name == name)
    }
    /// Nodes without a parent, in id order.
    pub fn roots(&self) -> impl Iterator<Item = &Node> {
        self.nodes.values().filter(|n| n.parent.is_none())
    }
    /// Direct children in id order.
    pub fn children(&self, id: NodeId) -> impl Iterator<Item = &Node> {
        self.nodes.values().filter(move |n| n.parent == Some(id))
    }
    /// The node and all its descendants, parents before children
    /// (breadth first, children in id order).
    ///
    /// Complexity: O(N) for the whole document (one pass finds every
    /// node's children), however deep the tree.
    pub fn subtree(&self, id: NodeId) -> Vec<NodeId> {
        let children = self.children_by_parent();
        let mut out = vec![id];
        let mut i = 0;
        while i < out.len() {
            let p = out[i];
            if let Some(c) = children.get(&p) {
                out.extend(c);
            }
            i += 1;
        }
        out
    }

    /// Every parent's children, in id order, found in one pass.
    fn children_by_parent(&self) -> HashMap<NodeId, Vec<NodeId>> {
        let mut children: HashMap<NodeId, Vec<NodeId>> = HashMap::new();
        for n in self.nodes.values() {
            if let Some(p) = n.parent {
                children.entry(p).or_default().push(n.id);
            }
        }
        children
    }

    /// What every node gets from its ancestors (world matrix, visibility,
    /// being drawn through a CSG solid), computed once per node, parents
    /// before children. Use it instead of [`world_matrix`](Self::world_matrix),
    /// [`crate::export::is_visible`] or [`crate::csg::inside_csg`] per node
    /// when visiting many nodes: each of those walks up to the root, which
    /// costs O(depth) per node and O(N²) on a deep chain.
    ///
    /// Complexity: O(N) for N nodes, however deep; no recursion (a chain
    /// of 10,000 nodes needs no deep stack).
    pub fn hierarchy(&self) -> Hierarchy {
        let children = self.children_by_parent();
        let mut facts: HashMap<NodeId, NodeFacts> = HashMap::with_capacity(self.nodes.len());
        let mut order = Vec::with_capacity(self.nodes.len());
        let is_csg = |id: NodeId| {
            matches!(
                self.nodes.get(&id).map(|n| &n.content),
                Some(NodeContent::Csg(_))
            )
        };
        // Depth first, roots in id order and children in id order.
        let mut stack: Vec<NodeId> = self.roots().map(|n| n.id).collect();
        stack.reverse();
        while let Some(id) = stack.pop() {
            let Some(node) = self.nodes.get(&id) else {
                continue;
            };
            let local = node.transform.to_matrix();
            let parent = node.parent.and_then(|p| Some((p, *facts.get(&p)?)));
            let here = match parent {
                None => NodeFacts {
                    world: DMat4::IDENTITY * local,
                    visible: node.visible,
                    inside_csg: false,
                    depth: 0,
                },
                Some((p, up)) => NodeFacts {
                    world: up.world * local,
                    visible: up.visible && node.visible,
                    inside_csg: up.inside_csg || is_csg(p),
                    depth: up.depth + 1,
                },
            };
            facts.insert(id, here);
            order.push(id);
            if let Some(c) = children.get(&id) {
                stack.extend(c.iter().rev());
            }
        }
        Hierarchy {
            order,
            facts,
            children,
        }
    }
    /// True when `ancestor` is `id` or one of its parents.
    pub fn is_ancestor(&self, ancestor: NodeId, id: NodeId) -> bool {
        let mut cur = Some(id);
        let mut guard = self.nodes.len() + 1;
        while let Some(c) = cur {
            if c == ancestor {
                return true;
            }
            guard -= 1;
            if guard == 0 {
                return false;
            }
            cur = self.nodes.get(&c).and_then(|n| n.parent);
        }
        false
    }
    /// The node's world matrix: parents' local matrices composed root first
    /// (in the order [`hierarchy`](Self::hierarchy) composes them, so both
    /// give the same bits).
    ///
    /// Complexity: O(depth); for many nodes use [`hierarchy`](Self::hierarchy).
    pub fn world_matrix(&self, id: NodeId) -> DMat4 {
        let mut chain = Vec::new();
        let mut cur = Some(id);
        let mut guard = self.nodes.len() + 1;
        while let Some(c) = cur {
            let Some(n) = self.nodes.get(&c) else { break };
            chain.push(n);
            cur = n.parent;
            guard -= 1;
            if guard == 0 {
                break;
            }
        }
        chain
            .iter()
            .rev()
            .fold(DMat4::IDENTITY, |m, n| m * n.transform.to_matrix())
    }
    /// A copy of the document with some nodes replaced by these versions
    /// of them (matched by id; others are ignored): what a running tool
    /// would leave, for evaluating what depends on it (a CSG solid while
    /// an operand is dragged). Contents are shared, not copied.
    pub fn with_changed(&self, nodes: impl IntoIterator<Item = Node>) -> Document {
        let mut doc = self.clone();
        for n in nodes {
            if let Some(slot) = doc.nodes.get_mut(&n.id) {
                *slot = n;
            }
        }
        doc
    }
    /// The node's world transform, decomposed.
    pub fn world_transform(&self, id: NodeId) -> NodeTransform {
        NodeTransform::from_matrix(self.world_matrix(id))
    }
    /// `name` if unused, else `name.001`, `name.002`, … like Blender.
    pub fn unique_name(&self, name: &str) -> String {
        let taken = |n: &str| self.nodes.values().any(|x| x.name == n);
        if !taken(name) {
            return name.to_string();
        }
        let base = match name.rsplit_once('.') {
            Some((b, suffix))
                if suffix.len() == 3 && suffix.chars().all(|c| c.is_ascii_digit()) =>
            {
                b
            }
            _ => name,
        };
        (1..)
            .map(|i| format!("{base}.{i:03}"))
            .find(|n| !taken(n))
            .expect("some suffix is free")
    }

    /// Checks the tree: parents exist, no cycles, ids match keys, transforms usable.
    ///
    /// # Errors
    /// The first [`DocumentError`] found, naming the node.
    ///
    /// Complexity: O(N) (parent cycles are found in one walk, not by
    /// walking up from every node).
    pub fn check(&self) -> Result<(), DocumentError> {
        let in_cycle = self.nodes_in_parent_cycles();
        for (id, n) in &self.nodes {
            if *id != n.id {
                return Err(DocumentError::WrongKey {
                    node: n.id,
                    key: *id,
                });
            }
            if id.0 >= self.next_node_id {
                return Err(DocumentError::IdNotBelowNext {
                    node: *id,
                    next: self.next_node_id,
                });
            }
            let named = || (*id, n.name.clone());
            if let Some(p) = n.parent {
                if !self.nodes.contains_key(&p) {
                    let (node, name) = named();
                    return Err(DocumentError::MissingParent {
                        node,
                        name,
                        parent: p,
                    });
                }
                if in_cycle.contains(id) {
                    let (node, name) = named();
                    return Err(DocumentError::OwnAncestor { node, name });
                }
            }
            if !n.transform.translation.is_finite()
                || !n.transform.rotation.is_finite()
                || !n.transform.scale.is_finite()
            {
                let (node, name) = named();
                return Err(DocumentError::NonFiniteTransform { node, name });
            }
            if let Some(c) = &n.construction
                && let Some(&&input) = c.recipe.inputs().iter().find(|i| {
                    !matches!(
                        self.nodes.get(i).map(|n| &n.content),
                        Some(NodeContent::Curve(_))
                    )
                })
            {
                let (node, name) = named();
                return Err(DocumentError::BadInput { node, name, input });
            }
            if let Some(j) = n.g1_join
                && (self
                    .nodes
                    .get(&j.triangle)
                    .and_then(|t| crate::join::triangle_of(&t.content))
                    .is_none()
                    || crate::join::patch_of(&n.content).is_none())
            {
                let (node, name) = named();
                return Err(DocumentError::BadJoin {
                    node,
                    name,
                    triangle: j.triangle,
                });
            }
            // Faces with inner rings or without edges (Mäntylä's Euler
            // operators, `Command::Euler`) are allowed: the file stores
            // them, rendering draws their outer loop's triangles only where
            // the kernel can triangulate, and exports and subdivision
            // refuse them by name.
        }
        Ok(())
    }
}

impl Document {
    /// The nodes that are their own ancestor (on a cycle of parents), each
    /// node visited once: a walk up from every node not yet seen stops at
    /// a node already seen, a root or a missing parent.
    fn nodes_in_parent_cycles(&self) -> HashSet<NodeId> {
        // 1: on the walk under way; 2: walked before.
        let mut state: HashMap<NodeId, u8> = HashMap::with_capacity(self.nodes.len());
        let mut in_cycle = HashSet::new();
        for &start in self.nodes.keys() {
            let mut path = Vec::new();
            let mut cur = Some(start);
            while let Some(c) = cur {
                match state.get(&c) {
                    Some(2) => break,
                    Some(_) => {
                        // Back on this walk: the nodes from `c` on form a cycle.
                        let at = path.iter().position(|&p| p == c).unwrap_or(0);
                        in_cycle.extend(path[at..].iter().copied());
                        break;
                    }
                    None => {}
                }
                let Some(n) = self.nodes.get(&c) else { break };
                state.insert(c, 1);
                path.push(c);
                cur = n.parent;
            }
            for p in path {
                state.insert(p, 2);
            }
        }
        in_cycle
    }
}

/// What a node gets from its ancestors, from [`Document::hierarchy`].
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct NodeFacts {
    /// The world matrix: the local matrices of the root, …, the parent and
    /// the node composed (the same bits as [`Document::world_matrix`]).
    pub world: DMat4,
    /// The node and every ancestor are visible.
    pub visible: bool,
    /// The node or an ancestor is a CSG operand (drawn and exported through
    /// a CSG node's solid), as [`crate::csg::inside_csg`] says.
    pub inside_csg: bool,
    /// Ancestors above the node (0 for a root).
    pub depth: usize,
}

/// Every node's [`NodeFacts`] and children, from [`Document::hierarchy`].
/// A snapshot: it does not follow later changes of the document.
#[derive(Clone, Debug, Default)]
pub struct Hierarchy {
    order: Vec<NodeId>,
    facts: HashMap<NodeId, NodeFacts>,
    children: HashMap<NodeId, Vec<NodeId>>,
}

impl Hierarchy {
    /// The facts of node `id`; `None` for a node that is not in the
    /// document or not under a root (on a cycle of parents, which
    /// [`Document::check`] refuses).
    pub fn facts(&self, id: NodeId) -> Option<&NodeFacts> {
        self.facts.get(&id)
    }
    /// The world matrix of node `id` (the identity for an unknown node).
    pub fn world_matrix(&self, id: NodeId) -> DMat4 {
        self.facts.get(&id).map_or(DMat4::IDENTITY, |f| f.world)
    }
    /// True when the node and all its ancestors are visible (false for an
    /// unknown node), as [`crate::export::is_visible`] says.
    pub fn is_visible(&self, id: NodeId) -> bool {
        self.facts.get(&id).is_some_and(|f| f.visible)
    }
    /// True when the node or an ancestor is a CSG operand, as
    /// [`crate::csg::inside_csg`] says.
    pub fn inside_csg(&self, id: NodeId) -> bool {
        self.facts.get(&id).is_some_and(|f| f.inside_csg)
    }
    /// The node's children, in id order.
    pub fn children(&self, id: NodeId) -> &[NodeId] {
        self.children.get(&id).map_or(&[], Vec::as_slice)
    }
    /// Every node under a root, parents before children: depth first,
    /// roots and children in id order.
    pub fn order(&self) -> &[NodeId] {
        &self.order
    }
}

/// What [`Document::check`] found wrong with a scene tree.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum DocumentError {
    /// A node stored under another id than its own.
    #[error("node {node} is stored under id {key}")]
    WrongKey {
        /// The node's own id.
        node: NodeId,
        /// The id it is stored under.
        key: NodeId,
    },
    /// A node id at or above the next id to hand out (a new node would clash).
    #[error("node {node} is not below the next id {next}")]
    IdNotBelowNext {
        /// The node's id.
        node: NodeId,
        /// The document's next free id.
        next: u64,
    },
    /// A node whose parent does not exist.
    #[error("node {node} '{name}' has missing parent {parent}")]
    MissingParent {
        /// The node's id.
        node: NodeId,
        /// The node's name.
        name: String,
        /// The missing parent's id.
        parent: NodeId,
    },
    /// A node that is its own ancestor (a parent cycle).
    #[error("node {node} '{name}' is its own ancestor")]
    OwnAncestor {
        /// The node's id.
        node: NodeId,
        /// The node's name.
        name: String,
    },
    /// A node made from curves names an input node that does not exist
    /// or is not a curve (deleting an input freezes its dependents, so a
    /// document never has one).
    #[error("node {node} '{name}' is made from node {input}, which is missing or not a curve")]
    BadInput {
        /// The node's id.
        node: NodeId,
        /// The node's name.
        name: String,
        /// The missing input.
        input: NodeId,
    },
    /// A node kept G1 to a triangle that is missing or not a Bézier
    /// triangle, or that is not a Bézier patch itself.
    #[error(
        "node {node} '{name}' is joined to node {triangle}, but they are not a Bézier patch and a Bézier triangle"
    )]
    BadJoin {
        /// The patch node's id.
        node: NodeId,
        /// Its name.
        name: String,
        /// The triangle it names.
        triangle: NodeId,
    },
    /// A node transform with a value that is not finite.
    #[error("node {node} '{name}' has a non-finite transform")]
    NonFiniteTransform {
        /// The node's id.
        node: NodeId,
        /// The node's name.
        name: String,
    },
}
