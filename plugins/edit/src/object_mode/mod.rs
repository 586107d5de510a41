//! Object mode: the selection of nodes, picking them in the viewport
//! (meshes and surfaces by ray, curves on screen, CSG operands once their
//! node is selected) and the object-mode shortcuts (A, X, Shift+D, H, G /
//! R / S, joins and booleans). The modal move/rotate/scale tool itself is
//! in `modal.rs`, shared by every mode.

use bevy::prelude::*;
use glam::DVec3;
use hedra_doc::{Command, Document, NodeContent, NodeId, NodeRef};
use hedra_scene::modifiers::{alt, shift};
use hedra_scene::{DocChanged, DocRequest, DocState, InputGate};

use crate::*;

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
            NodeContent::Kept(kept) => kept.mesh.ray_cast(lo, ld),
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
/// Click selects the object under the cursor (Shift toggles), click on empty space deselects.
#[allow(clippy::too_many_arguments)]
pub(crate) fn pick_objects(
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
