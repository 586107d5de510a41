//! What running tools show in place of the document, as data.
//!
//! A tool does not write node transforms or render meshes: it puts what it
//! would change into its own [`PreviewSource`] slot of [`Previews`], and the
//! projection ([`crate::project_transforms`], [`crate::project_render_meshes`])
//! draws the document with the previews over it. When the tool ends it
//! clears its slot; a confirmed tool's command reaches the document in the
//! same frame, so the projection goes from the preview straight to the
//! result.

use crate::*;
use by_address::ByAddress;
use hedra_doc::CurveContent;
use hedra_doc::NodeTransform;
use hedra_doc::SurfaceShape;
use hedra_geom::subdivision::Creases;
use std::collections::BTreeMap;
use std::sync::Arc;

/// The tools that show previews, one slot each.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum PreviewSource {
    /// G / R / S on objects.
    TransformTool,
    /// A mesh tool in edit mode (move, extrude, bevel, …).
    MeshTool,
    /// A control-point tool on a curve or surface (move, weight).
    ShapeTool,
    /// A transform field being dragged in the Properties panel.
    Properties,
    /// The transform gizmo being dragged.
    Gizmo,
    /// CSG solids re-evaluated from the other slots' operands
    /// ([`crate::follow_csg_previews`]).
    Csg,
}

/// A node's shape as a tool would leave it. Shared with the tool (`Arc`),
/// never copied, and compared by identity.
#[derive(Clone, Debug)]
pub enum PreviewContent {
    /// A mesh tool's result; `creases` replace the document's when given.
    Mesh {
        /// The mesh as the tool would leave it, in the node's local space.
        mesh: Arc<HalfEdgeMesh>,
        /// Creases that replace the document's; `None` keeps the document's.
        creases: Option<Creases>,
    },
    /// A control-point tool's curve.
    Curve(Arc<CurveContent>),
    /// A control-point tool's surface.
    Surface(Arc<SurfaceShape>),
}

impl PreviewContent {
    /// The curve or surface of a control-point tool's preview content.
    pub fn of_shape(content: &NodeContent) -> Option<PreviewContent> {
        match content {
            NodeContent::Curve(c) => Some(PreviewContent::Curve(c.clone())),
            NodeContent::Surface(s) => Some(PreviewContent::Surface(s.clone())),
            NodeContent::Mesh(m) => Some(PreviewContent::Mesh {
                mesh: m.mesh.clone(),
                creases: Some(m.creases.clone()),
            }),
            NodeContent::Empty | NodeContent::Csg(_) | NodeContent::Kept(_) => None,
        }
    }

    fn same(&self, other: &PreviewContent) -> bool {
        match (self, other) {
            (
                PreviewContent::Mesh { mesh, creases },
                PreviewContent::Mesh {
                    mesh: m2,
                    creases: c2,
                },
            ) => Arc::ptr_eq(mesh, m2) && creases == c2,
            (PreviewContent::Curve(a), PreviewContent::Curve(b)) => Arc::ptr_eq(a, b),
            (PreviewContent::Surface(a), PreviewContent::Surface(b)) => Arc::ptr_eq(a, b),
            _ => false,
        }
    }
}

/// What one tool shows: node transforms and node contents that replace the
/// document's on screen.
#[derive(Clone, Debug, Default)]
pub struct ToolPreview {
    /// Local transforms (relative to the parent) shown instead of the
    /// document's, by node.
    pub transforms: HashMap<NodeId, NodeTransform>,
    /// Contents shown instead of the document's, by node.
    pub contents: HashMap<NodeId, PreviewContent>,
}

impl ToolPreview {
    /// True when the preview changes nothing on screen (an empty preview
    /// clears its slot instead of filling it).
    pub fn is_empty(&self) -> bool {
        self.transforms.is_empty() && self.contents.is_empty()
    }

    /// The same transforms and the same contents (by identity).
    fn same(&self, other: &ToolPreview) -> bool {
        self.transforms == other.transforms
            && self.contents.len() == other.contents.len()
            && self
                .contents
                .iter()
                .all(|(id, c)| other.contents.get(id).is_some_and(|o| o.same(c)))
    }
}

/// The previews of the running tools, by tool. Written by the tools (each
/// its own slot), read by the projection.
#[derive(Resource, Debug, Default)]
pub struct Previews {
    slots: BTreeMap<PreviewSource, ToolPreview>,
}

impl Previews {
    /// What `source` shows now.
    pub fn slot(&self, source: PreviewSource) -> Option<&ToolPreview> {
        self.slots.get(&source)
    }

    /// The transform shown for `node` instead of the document's, if a tool
    /// previews one (the later slot wins; only one tool runs at a time).
    pub fn transform(&self, node: NodeId) -> Option<&NodeTransform> {
        self.slots
            .values()
            .rev()
            .find_map(|s| s.transforms.get(&node))
    }

    /// The content shown for `node` instead of the document's.
    pub fn content(&self, node: NodeId) -> Option<&PreviewContent> {
        self.slots
            .values()
            .rev()
            .find_map(|s| s.contents.get(&node))
    }

    /// Shows `preview` for `source`. Marks the resource changed only when
    /// the preview differs, so the projection does nothing while a tool
    /// holds still.
    pub fn show(
        this: &mut impl std::ops::DerefMut<Target = Self>,
        source: PreviewSource,
        preview: ToolPreview,
    ) {
        if preview.is_empty() {
            return Self::clear(this, source);
        }
        if !this.slots.get(&source).is_some_and(|s| s.same(&preview)) {
            this.slots.insert(source, preview);
        }
    }

    /// Whether `source` shows a preview.
    pub fn has(&self, source: PreviewSource) -> bool {
        self.slots.contains_key(&source)
    }

    /// Ends the preview of `source` (changing nothing when it shows none).
    pub fn clear(this: &mut impl std::ops::DerefMut<Target = Self>, source: PreviewSource) {
        if this.slots.contains_key(&source) {
            this.slots.remove(&source);
        }
    }

    /// Nodes that the tools other than `source` preview.
    pub fn nodes_except(&self, source: PreviewSource) -> impl Iterator<Item = NodeId> + '_ {
        self.slots
            .iter()
            .filter(move |(s, _)| **s != source)
            .flat_map(|(_, p)| p.transforms.keys().chain(p.contents.keys()))
            .copied()
    }

    /// Nodes that any tool previews, transform or content.
    pub fn nodes(&self) -> impl Iterator<Item = NodeId> + '_ {
        self.slots
            .values()
            .flat_map(|s| s.transforms.keys().chain(s.contents.keys()))
            .copied()
    }
}

/// What a CSG preview was made from, per operand: its node, previewed
/// transform and previewed mesh (held, compared by identity).
type CsgOperandKey = (
    NodeId,
    Option<NodeTransform>,
    Option<ByAddress<Arc<HalfEdgeMesh>>>,
);

/// A CSG solid follows its operands while a tool moves or edits them (G/R/S,
/// the gizmo, the transform fields, edit-mode tools on an operand): the
/// outermost CSG node above each previewed node is evaluated as the
/// previews would leave the document, from simplified copies of big
/// operands ([`hedra_doc::csg::Quality::DRAG`]; the exact solid when the
/// tool's command lands), and shown in the [`PreviewSource::Csg`] slot.
/// Evaluated only when the previews change.
pub fn follow_csg_previews(
    state: Res<DocState>,
    mut previews: ResMut<Previews>,
    mut last: Local<Vec<CsgOperandKey>>,
) {
    let doc = &state.session.doc;
    let mut ids: Vec<NodeId> = previews
        .nodes_except(PreviewSource::Csg)
        .filter(|&id| hedra_doc::csg::inside_csg(doc, id))
        .collect();
    ids.sort();
    ids.dedup();
    let key: Vec<CsgOperandKey> = ids
        .iter()
        .map(|&id| {
            let mesh = match previews.content(id) {
                Some(PreviewContent::Mesh { mesh, .. }) => Some(ByAddress(mesh.clone())),
                _ => None,
            };
            (id, previews.transform(id).copied(), mesh)
        })
        .collect();
    if key == *last && (!key.is_empty() || previews.slot(PreviewSource::Csg).is_none()) {
        return;
    }
    *last = key;
    if ids.is_empty() {
        Previews::clear(&mut previews, PreviewSource::Csg);
        return;
    }
    let changed: Vec<hedra_doc::Node> = ids
        .iter()
        .filter_map(|&id| {
            let mut n = doc.node(id)?.clone();
            if let Some(t) = previews.transform(id) {
                n.transform = *t;
            }
            if let (Some(PreviewContent::Mesh { mesh, .. }), NodeContent::Mesh(c)) =
                (previews.content(id), &mut n.content)
            {
                c.mesh = mesh.clone();
            }
            Some(n)
        })
        .collect();
    let preview = doc.with_changed(changed);
    let mut tops: Vec<NodeId> = ids
        .iter()
        .filter_map(|&id| hedra_doc::csg::outermost_csg(doc, id))
        .collect();
    tops.sort();
    tops.dedup();
    let contents = tops
        .into_iter()
        .filter_map(|top| {
            let solid =
                hedra_doc::csg::evaluate_with(&preview, top, hedra_doc::csg::Quality::DRAG).ok()?;
            Some((
                top,
                PreviewContent::Mesh {
                    mesh: solid,
                    creases: None,
                },
            ))
        })
        .collect();
    Previews::show(
        &mut previews,
        PreviewSource::Csg,
        ToolPreview {
            contents,
            ..default()
        },
    );
}
