//! Object-mode editing: selection, picking in the viewport, Blender-style
//! shortcuts and the modal move/rotate/scale tool (G/R/S).
//!
//! Tools never touch the document directly: they preview on entities and
//! send one [`DocRequest`] when the user confirms, so a drag is one undo step.

// Bevy systems take their world access as parameters: long parameter lists
// and nested query types are how Bevy code is written (Bevy allows both too).
#![allow(clippy::too_many_arguments, clippy::type_complexity)]

use bevy::prelude::*;
use glam::{DMat4, DQuat, DVec3};
use hedra_doc::{Command, Document, NodeContent, NodeId, NodeRef, NodeTransform};
use hedra_scene::modifiers::{alt, shift};
use hedra_scene::{DocChanged, DocRequest, DocState, InputGate, SceneSystems};

pub mod bindings;
mod cursor;
mod curve_draw;
pub mod mesh_mode;
pub mod modal;
mod proportional;
pub mod shape_mode;
mod shape_tool;
mod snapping;
pub mod typing;

pub use cursor::place_cursor;
pub use curve_draw::{CurveDraw, DrawKind, axis_command, construction_plane};
pub use mesh_mode::{
    BisectDrag, EditMode, ElementKind, ElementSelection, KnifeTool, MeshTool, MeshToolKind,
    start_bisect,
};
pub use modal::{Axis, ModalTransform, TransformKind, TransformTool};
pub use proportional::{Proportional, ProportionalRing, proportional_keys};
pub use shape_mode::ShapeEdit;
pub use snapping::{
    MoveSnap, SnapElement, SnapMesh, SnapScene, SnapTarget, Snapping, drag_translation, move_snap,
    snap_translation, snapping_keys,
};

/// Selected nodes, in the order they were selected; the last one is active.
#[derive(Resource, Default, Debug, Clone, PartialEq)]
pub struct Selection {
    /// The selected node ids, in selection order: the last one is active.
    pub nodes: Vec<NodeId>,
}

impl Selection {
    /// The active (last selected) node, or `None` when nothing is selected.
    pub fn active(&self) -> Option<NodeId> {
        self.nodes.last().copied()
    }
    /// True when `id` is selected, active or not.
    pub fn contains(&self, id: NodeId) -> bool {
        self.nodes.contains(&id)
    }
    /// Replaces the selection with `ids`, in that order (the last one becomes active).
    pub fn set(&mut self, ids: impl IntoIterator<Item = NodeId>) {
        self.nodes = ids.into_iter().collect();
    }
    /// Adds `id` (making it active), or removes it when it already is active.
    pub fn toggle(&mut self, id: NodeId) {
        if self.active() == Some(id) {
            self.nodes.retain(|&n| n != id);
        } else {
            self.nodes.retain(|&n| n != id);
            self.nodes.push(id);
        }
    }
    /// The selected nodes as command references (by id), in selection order.
    pub fn refs(&self) -> Vec<NodeRef> {
        self.nodes.iter().map(|&n| NodeRef::from(n)).collect()
    }
}

/// Tools, selection and shortcuts, in [`SceneSystems::Tools`]: they read
/// this frame's input and write requests, which [`SceneSystems::Apply`]
/// applies in the same frame, so the frame that confirms a tool already
/// shows its result.
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub struct EditSystems;

/// Selection, picking, shortcuts and the transform tool.
pub struct EditPlugin;

impl Plugin for EditPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<Selection>()
            .init_resource::<TransformTool>()
            .init_resource::<EditMode>()
            .init_resource::<mesh_mode::BisectDrag>()
            .init_resource::<mesh_mode::KnifeTool>()
            .init_resource::<Snapping>()
            .init_resource::<SnapTarget>()
            .init_resource::<Proportional>()
            .init_resource::<bindings::KeyHelp>()
            .init_resource::<bindings::RequestedAction>()
            .init_resource::<PivotPoint>()
            .init_resource::<ProportionalRing>()
            .init_resource::<AxisLock>()
            .init_resource::<ShapeEdit>()
            .init_resource::<CurveDraw>()
            .configure_sets(Update, EditSystems.in_set(SceneSystems::Tools))
            // What a command created is selected in the frame that applied
            // it, so that frame already draws it selected.
            .add_systems(
                Update,
                follow_document_changes
                    .in_set(SceneSystems::Apply)
                    .after(hedra_scene::apply_requests),
            )
            .add_systems(
                Update,
                (
                    (mesh_mode::follow_changes, mesh_mode::mode_keys).chain(),
                    snapping_keys,
                    proportional_keys,
                    bindings::key_help_keys,
                    pivot_keys,
                    undo_keys,
                    clear_tool_overlays,
                    modal::drive_transform_tool,
                    mesh_mode::drive_mesh_tool,
                    object_shortcuts,
                    subdivision_keys,
                    mesh_mode::edit_shortcuts,
                    mesh_mode::bisect_by_drag,
                    mesh_mode::start_knife,
                    mesh_mode::drive_knife,
                    place_cursor,
                    pick_objects,
                    mesh_mode::select_elements,
                    mesh_mode::publish_mesh_preview,
                )
                    .chain()
                    .in_set(EditSystems),
            )
            .add_systems(
                Update,
                (
                    shape_mode::shape_follow_changes,
                    shape_mode::shape_mode_keys,
                    shape_mode::drive_shape_tool,
                    shape_mode::shape_select_and_shortcuts,
                    shape_mode::publish_shape_preview,
                    curve_draw::drive_curve_draw,
                    publish_axis_lock,
                )
                    .chain()
                    .after(mesh_mode::publish_mesh_preview)
                    .in_set(EditSystems),
            );
    }
}

/// Selects what a command created; drops deleted nodes from the selection.
pub fn follow_document_changes(
    mut changes: MessageReader<DocChanged>,
    mut selection: ResMut<Selection>,
    state: Res<DocState>,
) {
    for c in changes.read() {
        if c.replaced {
            selection.nodes.clear();
        } else if !c.created.is_empty() {
            // Select the top-most created nodes (a duplicated hierarchy selects its root).
            let doc = &state.session.doc;
            let roots = c.created.iter().copied().filter(|id| {
                doc.node(*id)
                    .is_some_and(|n| !n.parent.is_some_and(|p| c.created.contains(&p)))
            });
            selection.set(roots);
        }
    }
    let doc = &state.session.doc;
    if selection.nodes.iter().any(|id| doc.node(*id).is_none()) {
        selection.nodes.retain(|id| doc.node(*id).is_some());
    }
}

/// The axis a running move, rotate or scale is locked to (X, Y or Z) and
/// the pivot it passes through, for drawing the constraint line as Blender
/// does; `None` while no tool runs or its axis is free.
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq)]
pub struct AxisLock(pub Option<(DVec3, Axis)>);

/// Publishes [`AxisLock`] from whichever tool runs (object G/R/S, a mesh
/// tool, a control-point tool), after they have read this frame's keys.
fn publish_axis_lock(
    tool: Res<TransformTool>,
    mode: Res<EditMode>,
    shape_edit: Res<ShapeEdit>,
    mut lock: ResMut<AxisLock>,
) {
    let now = tool
        .active
        .as_ref()
        .and_then(|t| Some((t.pivot(), t.axis?)))
        .or_else(|| mode.tool.as_ref().and_then(|t| Some((t.pivot(), t.axis?))))
        .or_else(|| {
            shape_edit
                .tool
                .as_ref()
                .and_then(|t| Some((t.pivot, t.axis?)))
        });
    lock.set_if_neq(AxisLock(now));
}

/// Clears what the running tools drew last frame (the snap target and the
/// proportional ring); the tool still running publishes it again.
fn clear_tool_overlays(mut snap_target: ResMut<SnapTarget>, mut ring: ResMut<ProportionalRing>) {
    snap_target.0 = None;
    ring.0 = None;
}

/// True when a node and all its parents are visible.
pub fn visible(doc: &Document, id: NodeId) -> bool {
    hedra_doc::export::is_visible(doc, id)
}

/// The nearest visible mesh or surface node under a world-space ray, with
/// the hit distance. (Curves are picked on screen: [`curve_near_cursor`].)
pub fn pick_node(doc: &Document, origin: DVec3, dir: DVec3) -> Option<(NodeId, f64)> {
    let mut best: Option<(NodeId, f64)> = None;
    for node in doc.nodes() {
        if !visible(doc, node.id) {
            continue;
        }
        let world = doc.world_matrix(node.id);
        let inv = world.inverse();
        if !inv.is_finite() {
            continue;
        }
        let lo = inv.transform_point3(origin);
        let ld = inv.transform_vector3(dir);
        // `t` is the same parameter along the world ray (affine map).
        let t = match &node.content {
            // What is drawn is hit: the mirrored half and the array's
            // copies too (their cage, before subdivision).
            NodeContent::Mesh(content) if content.has_stack_modifiers() => content
                .evaluated(0)
                .ok()
                .and_then(|mesh| hedra_geom::query::ray_cast(&mesh, lo, ld))
                .map(|(_, t)| t),
            NodeContent::Mesh(content) => {
                hedra_geom::query::ray_cast(&content.mesh, lo, ld).map(|(_, t)| t)
            }
            NodeContent::Surface(surface) => ray_surface_shape(surface, lo, ld),
            _ => None,
        };
        if let Some(t) = t {
            let dist = t * dir.length();
            if best.is_none_or(|(_, d)| dist < d) {
                best = Some((node.id, dist));
            }
        }
    }
    best
}

/// Ray parameter of the nearest hit on a surface node's shape.
fn ray_surface_shape(surface: &hedra_doc::SurfaceShape, origin: DVec3, dir: DVec3) -> Option<f64> {
    match surface {
        hedra_doc::SurfaceShape::Nurbs(s) => {
            hedra_geom::surfaces::intersect::ray_surface(s, origin, dir).map(|h| h.t)
        }
        hedra_doc::SurfaceShape::Triangle(t) => {
            let (positions, _, triangles) = t.tessellate(24);
            triangles
                .iter()
                .filter_map(|tri| {
                    let [a, b, c] = tri.map(|i| positions[i as usize]);
                    hedra_geom::query::ray_triangle(origin, dir, a, b, c)
                })
                .min_by(f64::total_cmp)
        }
    }
}

/// The visible curve node drawn within 8 pixels of the cursor, if any.
pub fn curve_near_cursor(
    doc: &Document,
    cursor: Vec2,
    camera: &Camera,
    camera_transform: &GlobalTransform,
) -> Option<NodeId> {
    use hedra_geom::curves::Curve;
    let mut best: Option<(NodeId, f32)> = None;
    for node in doc.nodes() {
        let NodeContent::Curve(c) = &node.content else {
            continue;
        };
        if !visible(doc, node.id) {
            continue;
        }
        let world = doc.world_matrix(node.id);
        let c = c.nurbs();
        let (a, b) = c.domain();
        let screen: Vec<Option<Vec2>> = (0..=200)
            .map(|i| {
                let p = world.transform_point3(c.point(a + (b - a) * i as f64 / 200.0));
                camera.world_to_viewport(camera_transform, p.as_vec3()).ok()
            })
            .collect();
        for w in screen.windows(2) {
            let (Some(p), Some(q)) = (w[0], w[1]) else {
                continue;
            };
            let seg = q - p;
            let t = ((cursor - p).dot(seg) / seg.length_squared().max(1e-12)).clamp(0.0, 1.0);
            let d = cursor.distance(p + t * seg);
            if d <= 8.0 && best.is_none_or(|(_, bd)| d < bd) {
                best = Some((node.id, d));
            }
        }
    }
    best.map(|(id, _)| id)
}

/// The world-space ray under the cursor, in `f64`.
pub fn cursor_ray(
    window: &Window,
    camera: &Camera,
    camera_transform: &GlobalTransform,
) -> Option<(DVec3, DVec3)> {
    hedra_scene::camera_ray(camera, camera_transform, window.cursor_position()?)
}

/// Whether a modal tool runs (object G/R/S, a mesh tool, a control-point
/// tool): its keys and clicks are not shortcuts then.
pub fn modal_tool_running(tool: &TransformTool, mode: &EditMode, shape_edit: &ShapeEdit) -> bool {
    tool.active.is_some() || mode.tool.is_some() || shape_edit.tool.is_some()
}

/// Click selects the object under the cursor (Shift toggles), click on empty space deselects.
#[allow(clippy::too_many_arguments)]
fn pick_objects(
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    tool: Res<TransformTool>,
    viewport: hedra_scene::ViewportPointer,
    state: Res<DocState>,
    mut selection: ResMut<Selection>,
    gizmo: Option<Res<TransformGizmoState>>,
    mode: Res<EditMode>,
    shape_edit: Res<ShapeEdit>,
    draw: Res<CurveDraw>,
) {
    let (window, camera) = (viewport.window(), viewport.camera());
    if mode.active()
        || shape_edit.active()
        || draw.active
        || draw.just_finished
        || !buttons.just_pressed(MouseButton::Left)
        || !gate.pointer_free
        || tool.active.is_some()
        || tool.just_finished
    {
        return;
    }
    if gizmo_has_pointer(gizmo.as_deref()) {
        return; // the click grabs a gizmo handle
    }
    if alt(&keys) {
        return; // Alt+drag orbits
    }
    let (cam, cam_t) = camera;
    let Some((origin, dir)) = viewport.ray() else {
        return;
    };
    // A curve under the cursor wins: it is thin and drawn over surfaces.
    let hit = window
        .cursor_position()
        .and_then(|c| curve_near_cursor(&state.session.doc, c, cam, cam_t))
        .or_else(|| pick_node(&state.session.doc, origin, dir).map(|(id, _)| id));
    // A click on a CSG solid selects the CSG node; once it (or a part of
    // it) is selected its operands are drawn as ghosts and clicks reach them.
    let hit = hit.map(|id| {
        let doc = &state.session.doc;
        match outermost_csg(doc, id) {
            Some(top)
                if !selection
                    .nodes
                    .iter()
                    .any(|&s| s == top || is_within(doc, s, top)) =>
            {
                top
            }
            _ => id,
        }
    });
    let shift = shift(&keys);
    match (hit, shift) {
        (Some(id), true) => selection.toggle(id),
        (Some(id), false) => selection.set([id]),
        (None, false) => selection.nodes.clear(),
        (None, true) => {}
    }
}

pub use hedra_doc::csg::{is_within, outermost_csg};

/// Ctrl+Z / Ctrl+Shift+Z (and Ctrl+Y), in both modes, when no tool runs.
pub fn undo_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    tool: Res<TransformTool>,
    mode: Res<EditMode>,
    mut requests: MessageWriter<DocRequest>,
) {
    if !gate.keyboard_free || tool.active.is_some() || mode.tool.is_some() {
        return;
    }
    let pressed = |action| bindings::pressed(&keys, bindings::KeyMode::Everywhere, action);
    if pressed(bindings::Action::Undo) {
        requests.write(DocRequest::Undo);
    } else if pressed(bindings::Action::Redo) {
        requests.write(DocRequest::Redo);
    }
}

/// Object-mode keys: A / Alt+A, X / Delete, Shift+D,
/// H / Alt+H, G / R / S.
#[allow(clippy::too_many_arguments)]
pub fn object_shortcuts(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut tool: ResMut<TransformTool>,
    mut selection: ResMut<Selection>,
    state: Res<DocState>,
    mut requests: MessageWriter<DocRequest>,
    viewport: hedra_scene::ViewportPointer,
    mode: Res<EditMode>,
    shape_edit: Res<ShapeEdit>,
    pivot_point: Res<PivotPoint>,
    cursor: Res<hedra_scene::Cursor3d>,
    draw: Res<CurveDraw>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    let (window, camera) = (viewport.window(), viewport.camera());
    if !gate.keyboard_free
        || tool.active.is_some()
        || mode.active()
        || shape_edit.active()
        || draw.active
    {
        return;
    }
    let doc = &state.session.doc;
    let pressed = |action| bindings::pressed(&keys, bindings::KeyMode::Object, action);
    use bindings::Action;
    if pressed(Action::SelectNone) {
        selection.nodes.clear();
    } else if pressed(Action::SelectAll) {
        selection.set(doc.nodes().filter(|n| visible(doc, n.id)).map(|n| n.id));
    }
    let unhide = pressed(Action::Unhide);
    if unhide || pressed(Action::Hide) {
        if unhide {
            let hidden: Vec<NodeRef> = doc
                .nodes()
                .filter(|n| !n.visible)
                .map(|n| n.id.into())
                .collect();
            if !hidden.is_empty() {
                requests.write(DocRequest::Execute(Command::SetVisible {
                    nodes: hidden,
                    visible: true,
                }));
            }
        } else if !selection.nodes.is_empty() {
            requests.write(DocRequest::Execute(Command::SetVisible {
                nodes: selection.refs(),
                visible: false,
            }));
        }
    }
    if pressed(Action::Delete) && !selection.nodes.is_empty() {
        requests.write(DocRequest::Execute(Command::Delete {
            nodes: selection.refs(),
        }));
    }
    if pressed(Action::JoinCurves) {
        match join_curves_command(doc, &selection) {
            Ok(cmd) => {
                requests.write(DocRequest::Execute(cmd));
            }
            Err(e) => status.error(e),
        }
    }
    for (action, op) in [
        (Action::BooleanUnion, hedra_geom::csg::BooleanOp::Union),
        (
            Action::BooleanDifference,
            hedra_geom::csg::BooleanOp::Difference,
        ),
        (
            Action::BooleanIntersection,
            hedra_geom::csg::BooleanOp::Intersection,
        ),
    ] {
        if pressed(action) {
            match boolean_command(&selection, op) {
                Some(cmd) => {
                    requests.write(DocRequest::Execute(cmd));
                }
                None => status.error("Boolean: select two closed meshes (the active one is kept)"),
            }
        }
    }
    if pressed(Action::Duplicate) && !selection.nodes.is_empty() {
        requests.write(DocRequest::Execute(Command::Duplicate {
            nodes: selection.refs(),
        }));
        tool.grab_after_duplicate = true;
    }
    let kind = if pressed(Action::Move) {
        Some(TransformKind::Grab)
    } else if pressed(Action::Rotate) {
        Some(TransformKind::Rotate)
    } else if pressed(Action::Scale) {
        Some(TransformKind::Scale)
    } else {
        None
    };
    if let Some(kind) = kind {
        let (cam, cam_t) = camera;
        tool.active =
            ModalTransform::start(kind, doc, &selection.nodes, window, cam, cam_t).map(|m| {
                match *pivot_point {
                    PivotPoint::Cursor => m.about(cursor.0, cam, cam_t),
                    PivotPoint::MedianPoint => m,
                }
            });
    }
}

/// Ctrl+J on two selected curves: the active one followed by the other
/// (`Command::JoinCurves`); a message names what is missing otherwise.
pub fn join_curves_command(
    doc: &hedra_doc::Document,
    selection: &Selection,
) -> Result<Command, String> {
    let is_curve = |id: NodeId| {
        doc.node(id)
            .is_some_and(|n| matches!(n.content, NodeContent::Curve(_)))
    };
    let curves: Vec<NodeId> = selection
        .nodes
        .iter()
        .copied()
        .filter(|&id| is_curve(id))
        .collect();
    let [a, b] = curves[..] else {
        return Err(format!(
            "Join: select two curves (the active one comes first); {} selected",
            curves.len()
        ));
    };
    let first = selection
        .active()
        .filter(|&id| id == a || id == b)
        .unwrap_or(a);
    let second = if first == a { b } else { a };
    Ok(Command::JoinCurves {
        first: first.into(),
        second: second.into(),
    })
}

/// The one-shot boolean of the selection (Object ▸ Boolean, Ctrl+Numpad
/// +, −, *): the active node with the other selected one; `None` unless
/// exactly two are selected.
pub fn boolean_command(selection: &Selection, op: hedra_geom::csg::BooleanOp) -> Option<Command> {
    let [a, b] = selection.nodes[..] else {
        return None;
    };
    let (kept, other) = match selection.active() {
        Some(x) if x == a => (a, b),
        _ => (b, a),
    };
    Some(Command::Boolean {
        node: kept.into(),
        other: other.into(),
        op,
    })
}

/// What R and S turn and scale about (Blender's Pivot Point).
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum PivotPoint {
    /// The median of the selected objects' origins, or of the selected
    /// vertices in edit mode.
    #[default]
    MedianPoint,
    /// The 3D cursor.
    Cursor,
}

impl PivotPoint {
    /// The name the View menu and the status line show.
    pub fn label(self) -> &'static str {
        match self {
            PivotPoint::MedianPoint => "Median Point",
            PivotPoint::Cursor => "3D Cursor",
        }
    }
}

/// `.` switches the pivot point between the median and the 3D cursor (in
/// Blender it opens the pivot menu).
pub fn pivot_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut pivot: ResMut<PivotPoint>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    if gate.keyboard_free
        && bindings::pressed(
            &keys,
            bindings::KeyMode::Everywhere,
            bindings::Action::PivotPoint,
        )
    {
        *pivot = match *pivot {
            PivotPoint::MedianPoint => PivotPoint::Cursor,
            PivotPoint::Cursor => PivotPoint::MedianPoint,
        };
        status.info(format!(
            "Pivot: {} (R and S turn and scale about it; . switches)",
            pivot.label()
        ));
    }
}

/// Ctrl+0…Ctrl+5 set the subdivision level of the selected meshes (or of
/// the mesh in edit mode), adding a Catmull-Clark modifier when there is
/// none, like Blender; Ctrl+0 shows the cage alone. Page Up / Page Down step
/// the level of meshes that have a modifier.
pub fn subdivision_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    tool: Res<TransformTool>,
    mode: Res<EditMode>,
    selection: Res<Selection>,
    state: Res<DocState>,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    if !gate.keyboard_free || tool.active.is_some() || mode.tool.is_some() {
        return;
    }
    const LEVEL_KEYS: [(KeyCode, u32); 6] = [
        (KeyCode::Digit0, 0),
        (KeyCode::Digit1, 1),
        (KeyCode::Digit2, 2),
        (KeyCode::Digit3, 3),
        (KeyCode::Digit4, 4),
        (KeyCode::Digit5, 5),
    ];
    use bindings::{Action, KeyMode::Everywhere};
    let set_level = bindings::pressed_key(&keys, Everywhere, Action::SubdivisionLevel)
        .and_then(|key| LEVEL_KEYS.iter().find(|(k, _)| *k == key))
        .map(|&(_, level)| level);
    let step: i64 = if bindings::pressed(&keys, Everywhere, Action::SubdivisionUp) {
        1
    } else if bindings::pressed(&keys, Everywhere, Action::SubdivisionDown) {
        -1
    } else {
        0
    };
    if set_level.is_none() && step == 0 {
        return;
    }
    let doc = &state.session.doc;
    let targets: Vec<NodeId> = match mode.node {
        Some(n) => vec![n],
        None => selection.nodes.to_vec(),
    };
    let mut changed = Vec::new();
    for id in targets {
        let Some(node) = doc.node(id) else { continue };
        let hedra_doc::NodeContent::Mesh(content) = &node.content else {
            continue;
        };
        let modifier = match (set_level, content.subdivision) {
            (Some(level), Some(mut m)) => {
                m.viewport_level = level;
                m
            }
            (Some(level), None) => hedra_doc::SubdivisionModifier::with_level(level),
            (None, Some(mut m)) => {
                let level = (m.viewport_level as i64 + step)
                    .clamp(0, hedra_geom::subdivision::MAX_VIEWPORT_LEVEL as i64)
                    as u32;
                if level == m.viewport_level {
                    continue;
                }
                m.viewport_level = level;
                m
            }
            (None, None) => continue,
        };
        if content.subdivision != Some(modifier) {
            changed.push((id, modifier));
        }
    }
    if changed.is_empty() {
        status.error(if set_level.is_some() {
            "Subdivision: select a mesh first"
        } else {
            "Page Up/Down: no selected mesh has a subdivision modifier (Ctrl+1 adds one)"
        });
        return;
    }
    // One command (one undo step) per distinct modifier: Ctrl+2 on meshes
    // with no modifier, or with the same one, is a single step.
    let mut groups: Vec<(hedra_doc::SubdivisionModifier, Vec<hedra_doc::NodeRef>)> = Vec::new();
    for (id, modifier) in changed {
        match groups.iter_mut().find(|(m, _)| *m == modifier) {
            Some((_, nodes)) => nodes.push(id.into()),
            None => groups.push((modifier, vec![id.into()])),
        }
    }
    for (modifier, nodes) in groups {
        requests.write(DocRequest::Execute(Command::SetSubdivision {
            nodes,
            modifier: Some(modifier),
        }));
    }
}

/// Local transform that puts a node at `world` under a parent at `parent_world`.
pub fn local_from_world(parent_world: DMat4, world: DMat4) -> NodeTransform {
    NodeTransform::from_matrix(parent_world.inverse() * world)
}

/// True while the pointer is on a transform gizmo handle or drags one: a
/// click there belongs to the gizmo, not to selection.
pub fn gizmo_has_pointer(gizmo: Option<&TransformGizmoState>) -> bool {
    gizmo.is_some_and(|g| g.hovered_axis.is_some() || g.active)
}

/// Rotation about a pivot as a matrix.
pub fn rotation_about(pivot: DVec3, rotation: DQuat) -> DMat4 {
    DMat4::from_translation(pivot) * DMat4::from_quat(rotation) * DMat4::from_translation(-pivot)
}
