//! Edit mode: Tab enters it on the active mesh; 1/2/3 pick vertices, edges
//! or faces; click / Shift-click / A / Alt+A / Ctrl+I select; G moves,
//! E extrudes, I insets, Ctrl+R loop-cuts, J connects two vertices,
//! X dissolves. Every tool is modal like Blender's: the mouse drives the
//! amount, typed numbers are exact, Enter or a click confirms as one undo
//! step, Esc or a right click restores. While a tool runs the command is
//! decided on a copy each frame and shown as a preview.

use crate::modal::Axis;
use crate::{Selection, TransformTool};
use bevy::gizmos::transform_gizmo::TransformGizmoState;
use bevy::prelude::*;
use glam::{DMat4, DVec3};
use hedra_doc::{Command, EdgeSet, FaceSet, NodeContent, NodeId, NodeRef, VertexSet};
use hedra_geom::subdivision::Creases;
use hedra_geom::{EdgeId, FaceId, HalfEdgeMesh, VertexId};
use hedra_scene::modifiers::{alt, ctrl, shift};
use hedra_scene::{DocChanged, DocRequest, DocState, InputGate, StatusMessage};
use std::collections::BTreeMap;
use std::collections::BTreeSet;
use std::sync::Arc;

mod bisect;
mod keymap;
mod knife;
mod picking;
mod preview;
mod selection;
mod tools;

pub use bisect::*;
pub use keymap::*;
pub use knife::*;
pub use picking::*;
use preview::show_mesh_tool_preview;
pub use selection::*;
pub use tools::*;

/// Which elements clicks select.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum ElementKind {
    /// Vertices (key 1), the default.
    #[default]
    Vertex,
    /// Edges (key 2).
    Edge,
    /// Faces (key 3).
    Face,
}

/// Selected elements of the edited mesh (ids).
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct ElementSelection {
    /// Selected vertices (the set vertex mode fills).
    pub vertices: BTreeSet<VertexId>,
    /// Selected edges (the set edge mode fills).
    pub edges: BTreeSet<EdgeId>,
    /// Selected faces (the set face mode fills).
    pub faces: BTreeSet<FaceId>,
    /// Vertices in the order they were clicked (for Merge at First / Last).
    pub clicked: Vec<VertexId>,
}

impl ElementSelection {
    /// The selected vertices, those clicked first in click order, then the
    /// rest by id.
    pub fn ordered_vertices(&self) -> Vec<VertexId> {
        let mut out: Vec<VertexId> = self
            .clicked
            .iter()
            .copied()
            .filter(|v| self.vertices.contains(v))
            .collect();
        let rest: Vec<VertexId> = self
            .vertices
            .iter()
            .copied()
            .filter(|v| !out.contains(v))
            .collect();
        out.extend(rest);
        out
    }

    /// The elements of `kind` whose vertices all lie in `verts` (how Blender
    /// converts a selection between vertex, edge and face mode).
    pub fn from_vertices(
        kind: ElementKind,
        mesh: &HalfEdgeMesh,
        verts: &BTreeSet<VertexId>,
    ) -> Self {
        let mut sel = ElementSelection::default();
        match kind {
            ElementKind::Vertex => sel.vertices = verts.clone(),
            ElementKind::Edge => {
                sel.edges = mesh
                    .edges()
                    .filter(|&e| mesh.edge_vertices(e).iter().all(|v| verts.contains(v)))
                    .collect()
            }
            ElementKind::Face => {
                sel.faces = mesh
                    .faces()
                    .filter(|&f| mesh.face_vertices(f).all(|v| verts.contains(&v)))
                    .collect()
            }
        }
        sel
    }

    /// True when no vertex, edge or face is selected.
    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty() && self.edges.is_empty() && self.faces.is_empty()
    }
    /// Every vertex touched by the selection (elements the mesh does not
    /// have are skipped).
    pub fn all_vertices(&self, m: &HalfEdgeMesh) -> BTreeSet<VertexId> {
        let mut out: BTreeSet<VertexId> = self
            .vertices
            .iter()
            .copied()
            .filter(|v| m.is_vertex(*v))
            .collect();
        for &e in self.edges.iter().filter(|e| m.is_edge(**e)) {
            out.extend(m.edge_vertices(e));
        }
        for &f in self.faces.iter().filter(|f| m.is_face(**f)) {
            out.extend(m.face_vertices(f));
        }
        out
    }
    /// Drops ids the mesh no longer has.
    pub fn retain_live(&mut self, m: &HalfEdgeMesh) {
        self.vertices.retain(|v| m.is_vertex(*v));
        self.edges.retain(|e| m.is_edge(*e));
        self.faces.retain(|f| m.is_face(*f));
    }
}

/// The element selection as it was before each step of the history, so
/// that undoing a step gives its selection back (a bevel removes the
/// selected edges; Ctrl+Z brings them back selected), as Blender and
/// Wings do.
#[derive(Default)]
pub struct SelectionMemory {
    /// The history's last step when last seen.
    top: Option<u64>,
    /// (edited node, the last step before a step was added) → the
    /// selection then; the oldest are dropped past [`Self::KEPT`].
    before: Vec<((NodeId, Option<u64>), ElementSelection)>,
}

impl SelectionMemory {
    /// How many steps' selections are kept.
    const KEPT: usize = 256;

    /// Follows the history to `top`: a new step remembers the selection as
    /// it was before it (`before` when the tool changed it on confirming,
    /// else `selection`); going back to a step that has a remembered
    /// selection restores it.
    pub fn follow(
        &mut self,
        node: NodeId,
        top: Option<u64>,
        before: Option<&ElementSelection>,
        selection: &mut ElementSelection,
    ) {
        if top == self.top {
            return;
        }
        let added = match (top, self.top) {
            (Some(now), Some(before)) => now > before,
            (Some(_), None) => true,
            (None, _) => false,
        };
        let key = (node, self.top);
        if added {
            self.before.retain(|(k, _)| *k != key);
            self.before.push((key, before.unwrap_or(selection).clone()));
            if self.before.len() > Self::KEPT {
                self.before.remove(0);
            }
        } else if let Some((_, kept)) = self.before.iter().find(|(k, _)| *k == (node, top)) {
            *selection = kept.clone();
        }
        self.top = top;
    }
}

/// The modal mesh tools.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum MeshToolKind {
    /// Move the selected elements' vertices (G), in the view plane or along a locked axis.
    Move,
    /// Extrude the selected faces each on its own (Alt+E).
    ExtrudeIndividual,
    /// Extrude the selected boundary edges (E in edge mode), moved like G.
    ExtrudeEdges,
    /// Slide the selected edges along their neighbours (G G in edge mode).
    SlideEdges,
    /// Bevel the selected edges (Ctrl+B).
    Bevel,
    /// Bevel the selected vertices (Ctrl+Shift+B).
    BevelVertices,
    /// Inset the selected faces each on its own (Alt+I).
    InsetIndividual,
    /// Drag the subdivision crease of the selected edges, or the corner
    /// sharpness of the selected vertices in vertex mode (Shift+E).
    Crease,
    /// Rotate the selected elements' vertices about their mean (R), about the view axis or a locked axis.
    Rotate,
    /// Scale the selected elements' vertices about their mean (S), uniformly or along a locked axis.
    Scale,
    /// Extrude the selected faces as one region along its normal (E, outside
    /// edge mode).
    Extrude,
    /// Inset the selected faces as one region (I).
    Inset,
    /// Cut edge loops across the ring through the edge under the cursor, or
    /// the first selected edge (Ctrl+R).
    LoopCut,
    /// Split the one selected vertex (Alt+V, seed 004's vertex split, the
    /// inverse of an edge collapse): the new vertex follows the pointer and
    /// takes the vertex's edges on the pointer's side.
    SplitVertex,
}

/// A running mesh tool.
#[derive(Clone, Debug)]
pub struct MeshTool {
    /// Which tool runs.
    pub kind: MeshToolKind,
    /// The world axis locked with X / Y / Z (move, rotate and scale only); `None`
    /// when free.
    pub axis: Option<Axis>,
    /// Digits typed so far: when they form a number, it replaces the mouse
    /// (a distance, angle in degrees, factor, sharpness or cut count, by tool).
    pub typed: crate::typing::TypedNumber,
    start_cursor: Vec2,
    pivot: DVec3,
    pivot_screen: Vec2,
    /// Loop cut: the edge under the cursor and the number of cuts.
    edge: Option<EdgeId>,
    cuts: u32,
    /// Crease: the mean sharpness of the selection when the tool started.
    start_value: f64,
    /// Faces the previewed command makes (extrude caps, inset inner faces),
    /// selected when the tool is confirmed.
    created_faces: Vec<FaceId>,
    /// Extrude and inset: the result as a function of the dragged value,
    /// decided once when the drag starts (`None` until then, or when the
    /// command has no such form).
    linear: Option<hedra_doc::preview::LinearPreview>,
    linear_tried: bool,
    /// Proportional editing: the neighbours' weights for these settings.
    proportional: Option<tools::CachedWeights>,
    /// What the status bar shows for the tool ("Extrude 0.2500"), with the
    /// typed digits or the reason the command cannot apply appended.
    pub readout: String,
}

impl MeshTool {
    /// The world point the tool works about (G/R/S move, turn and scale
    /// about it).
    pub fn pivot(&self) -> DVec3 {
        self.pivot
    }
}

/// Edit-mode state: the edited node, element mode, selection, running tool.
#[derive(Resource, Default, Debug)]
pub struct EditMode {
    /// The mesh node being edited; `None` outside edit mode.
    pub node: Option<NodeId>,
    /// Which elements clicks and box selection take (vertex, edge or face mode).
    pub kind: ElementKind,
    /// The selected elements of the edited mesh.
    pub selection: ElementSelection,
    /// The running modal tool, if any.
    pub tool: Option<MeshTool>,
    /// M in vertex mode: the merge menu is open at this window position.
    pub merge_menu_at: Option<Vec2>,
    /// The mesh as the running tool would leave it (shown instead of the document's).
    pub preview: Option<Arc<HalfEdgeMesh>>,
    /// The creases as the running tool would leave them.
    pub preview_creases: Option<Creases>,
    /// Set on the frame a tool ended, so its confirming click selects nothing.
    pub just_finished: bool,
    /// The rectangle being dragged for box selection (window coordinates).
    pub box_select: Option<(Vec2, Vec2)>,
    /// The selection as it was when a tool confirmed a step and then
    /// changed the selection (an extrude selects its caps): what undoing
    /// the step gives back ([`SelectionMemory`]).
    pub selection_before_step: Option<ElementSelection>,
}

impl EditMode {
    /// True while a mesh node is in edit mode.
    pub fn active(&self) -> bool {
        self.node.is_some()
    }
}

/// The mesh being edited, as the document has it.
pub fn edited_mesh(state: &DocState, mode: &EditMode) -> Option<Arc<HalfEdgeMesh>> {
    edited_mesh_of(&state.session.doc, mode.node?)
}

/// The half-edge mesh of a mesh node (shared, not copied).
pub fn edited_mesh_of(doc: &hedra_doc::Document, node: NodeId) -> Option<Arc<HalfEdgeMesh>> {
    match &doc.node(node)?.content {
        NodeContent::Mesh(m) => Some(m.mesh.clone()),
        _ => None,
    }
}

/// Tab toggles edit mode on the active mesh; 1/2/3 choose the element kind.
pub fn mode_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut mode: ResMut<EditMode>,
    selection: Res<Selection>,
    state: Res<DocState>,
    tool: Res<TransformTool>,
    mut status: ResMut<hedra_scene::StatusMessage>,
    draw: Res<crate::CurveDraw>,
) {
    if !gate.keyboard_free || tool.active.is_some() || mode.tool.is_some() || draw.active {
        return;
    }
    use crate::bindings::{Action, KeyMode, pressed};
    if pressed(&keys, KeyMode::Everywhere, Action::EditModeToggle) {
        if mode.active() {
            mode.node = None;
            mode.selection = ElementSelection::default();
        } else {
            match selection.active().and_then(|id| state.session.doc.node(id)) {
                Some(n) if matches!(n.content, NodeContent::Mesh(_)) => {
                    mode.node = Some(n.id);
                    mode.selection = ElementSelection::default();
                    // An earlier "select a mesh to edit" is answered now.
                    if status.is_error {
                        status.info(format!("Editing '{}'", n.name));
                    }
                }
                // Curves and surfaces have their own edit mode (shape_mode).
                Some(n) if matches!(n.content, NodeContent::Curve(_) | NodeContent::Surface(_)) => {
                }
                // A kept mesh cannot hold edits until it is repaired.
                Some(n) if matches!(n.content, NodeContent::Kept(_)) => {
                    status.error(kept_mesh_not_editable(n));
                }
                // A CSG node's solid is made from its operands: they are edited.
                Some(n) if matches!(n.content, NodeContent::Csg(_)) => status.error(format!(
                    "'{}' is a CSG node: its solid follows its operands (its children in the outliner); select one and press Tab to edit it",
                    n.name
                )),
                Some(n) => status.error(format!(
                    "'{}' is an empty: meshes, curves and surfaces have an edit mode",
                    n.name
                )),
                None => status.error("Select a mesh to edit (click it), then press Tab"),
            }
        }
    }
    if !mode.active() || ctrl(&keys) {
        return;
    }
    let new_kind = if pressed(&keys, KeyMode::Edit, Action::VertexMode) {
        Some(ElementKind::Vertex)
    } else if pressed(&keys, KeyMode::Edit, Action::EdgeMode) {
        Some(ElementKind::Edge)
    } else if pressed(&keys, KeyMode::Edit, Action::FaceMode) {
        Some(ElementKind::Face)
    } else {
        None
    };
    if let (Some(k), Some(mesh)) = (new_kind, edited_mesh(&state, &mode))
        && k != mode.kind
    {
        // Convert the selection like Blender: keep what the new kind can express.
        mode.selection =
            ElementSelection::from_vertices(k, &mesh, &mode.selection.all_vertices(&mesh));
        mode.kind = k;
    }
}

/// Leaves edit mode when its node disappears; keeps the selection to live ids.
pub fn follow_changes(
    mut changes: MessageReader<DocChanged>,
    mut mode: ResMut<EditMode>,
    state: Res<DocState>,
    mut memory: Local<SelectionMemory>,
) {
    if changes.read().count() == 0 {
        return;
    }
    let top = state.session.history.done().last().map(|t| t.serial);
    let before = mode.selection_before_step.take();
    match mode.node {
        Some(node) => {
            let mode = &mut *mode;
            memory.follow(node, top, before.as_ref(), &mut mode.selection);
        }
        // Steps made outside edit mode are not remembered, but the memory
        // must know where the history stands.
        None => memory.top = top,
    }
    match edited_mesh(&state, &mode) {
        Some(m) => mode.selection.retain_live(&m),
        None => {
            mode.node = None;
            mode.selection = ElementSelection::default();
            mode.tool = None;
            mode.preview = None;
        }
    }
}

/// Why edit mode does not open on a kept (non-manifold) mesh, naming where
/// it is not manifold, and how to make it editable.
pub fn kept_mesh_not_editable(node: &hedra_doc::Node) -> String {
    let NodeContent::Kept(k) = &node.content else {
        return format!("'{}' is not a kept mesh", node.name);
    };
    let number = |v: u32| (v + 1).to_string();
    let face = |f: usize| format!("face {}", f + 1);
    let places = hedra_doc::kept::describe_places(&k.mesh.places(), 2, &number, &face);
    format!(
        "'{}' is kept as imported and is not manifold ({}): edit mode needs Mesh ▸ Make Manifold first",
        node.name,
        places.join("; ")
    )
}
