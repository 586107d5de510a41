//! Edit mode for curves and surfaces: Tab on the active curve or surface
//! shows its control points; click / Shift-click / A / Alt+A select them;
//! G moves them (X/Y/Z constrain, typed numbers are exact); W drags their
//! weight (right = heavier, typed numbers set it; 0 and below are refused);
//! K inserts a knot where the cursor points (Shift+K: in v on a surface).
//! Like the mesh tools, a tool decides its command on a copy every frame
//! and shows the result; Enter or a click confirms it as one undo step
//! (the tools themselves: `tool.rs`).

use crate::bindings::{Action, KeyMode};
use std::collections::BTreeSet;

use bevy::gizmos::transform_gizmo::TransformGizmoState;
use bevy::prelude::*;
use glam::DVec3;
use hedra_doc::{Command, NodeContent, NodeId, NodeRef, SurfaceShape};
use hedra_geom::curves::CurveEnd;
use hedra_scene::modifiers::{alt, shift};
use hedra_scene::{DocRequest, DocState, InputGate, StatusMessage};

mod tool;
use crate::typing::TypedNumber;
pub use tool::{ShapeTool, ShapeToolKind, drive_shape_tool};

/// Edit-mode state of a curve or surface node.
#[derive(Resource, Default, Debug)]
pub struct ShapeEdit {
    /// The curve or surface node being edited; `None` outside shape edit mode.
    pub node: Option<NodeId>,
    /// Selected control points (indices as commands count them).
    pub selected: BTreeSet<u32>,
    /// The running tool, if any.
    pub tool: Option<ShapeTool>,
    /// The node's content as the running tool would leave it.
    pub preview: Option<NodeContent>,
    /// Nodes made from this one (a surface revolved from the curve) as
    /// they would be made again, shown with the preview.
    pub dependents: Vec<(NodeId, NodeContent)>,
    /// Set on the frame a tool ended, so its confirming click selects nothing.
    pub just_finished: bool,
    /// The rectangle being dragged for box selection (window coordinates).
    pub box_select: Option<(Vec2, Vec2)>,
}

impl ShapeEdit {
    /// True while a curve or surface node is in shape edit mode.
    pub fn active(&self) -> bool {
        self.node.is_some()
    }
}

pub use hedra_scene::{control_points, control_weights};

fn is_shape(content: &NodeContent) -> bool {
    matches!(content, NodeContent::Curve(_) | NodeContent::Surface(_))
}

/// Tab enters and leaves shape edit mode on the active curve or surface.
pub fn shape_mode_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut edit: ResMut<ShapeEdit>,
    selection: Res<crate::Selection>,
    state: Res<DocState>,
    mesh_mode: Res<crate::EditMode>,
    draw: Res<crate::CurveDraw>,
) {
    if !gate.keyboard_free
        || edit.tool.is_some()
        || draw.active
        || mesh_mode.active()
        || !crate::bindings::pressed(&keys, KeyMode::Everywhere, Action::EditModeToggle)
    {
        return;
    }
    if edit.active() {
        *edit = ShapeEdit::default();
        return;
    }
    if let Some(id) = selection.active().filter(|&id| {
        state
            .session
            .doc
            .node(id)
            .is_some_and(|n| is_shape(&n.content))
    }) {
        edit.node = Some(id);
        edit.selected.clear();
    }
}

/// Leaves shape edit mode when its node disappears; drops stale indices.
pub fn shape_follow_changes(mut edit: ResMut<ShapeEdit>, state: Res<DocState>) {
    let Some(id) = edit.node else { return };
    match state.session.doc.node(id) {
        Some(n) if is_shape(&n.content) => {
            let count = control_points(&n.content).len() as u32;
            edit.selected.retain(|&i| i < count);
        }
        _ => *edit = ShapeEdit::default(),
    }
}

/// Adds the control points whose screen position lies in the box `a`–`b`.
fn select_in_box(
    selected: &mut BTreeSet<u32>,
    points: &[DVec3],
    world: glam::DMat4,
    (a, b): (Vec2, Vec2),
    (cam, cam_t): (&Camera, &GlobalTransform),
) {
    let (lo, hi) = (a.min(b), a.max(b));
    for (i, p) in points.iter().enumerate() {
        if let Ok(s) = cam.world_to_viewport(cam_t, world.transform_point3(*p).as_vec3())
            && s.cmpge(lo).all()
            && s.cmple(hi).all()
        {
            selected.insert(i as u32);
        }
    }
}

/// The control point nearest to the cursor on screen, within 14 pixels.
fn point_under_cursor(
    points: &[DVec3],
    world: glam::DMat4,
    cursor: Vec2,
    cam: &Camera,
    cam_t: &GlobalTransform,
) -> Option<u32> {
    points
        .iter()
        .enumerate()
        .filter_map(|(i, p)| {
            let s = cam
                .world_to_viewport(cam_t, world.transform_point3(*p).as_vec3())
                .ok()?;
            let d = s.distance(cursor);
            (d <= 14.0).then_some((i as u32, d))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

/// Click selects the control point under the cursor (Shift toggles, a click
/// on nothing clears); A selects all, Alt+A none; G and W start tools.
#[allow(clippy::too_many_arguments)]
pub fn shape_select_and_shortcuts(
    keys: Res<ButtonInput<KeyCode>>,
    buttons: Res<ButtonInput<MouseButton>>,
    gate: Res<InputGate>,
    mut edit: ResMut<ShapeEdit>,
    state: Res<DocState>,
    viewport: hedra_scene::ViewportPointer,
    mut status: ResMut<StatusMessage>,
    mut requests: MessageWriter<DocRequest>,
    mut b_box: Local<bool>,
    gizmo: Option<Res<TransformGizmoState>>,
    pivot_point: Res<crate::PivotPoint>,
    cursor_3d: Res<hedra_scene::Cursor3d>,
    mut requested: ResMut<crate::bindings::RequestedAction>,
) {
    let (window, camera) = (viewport.window(), viewport.camera());
    let Some(id) = edit.node else {
        *b_box = false;
        return;
    };
    if edit.tool.is_some() {
        return;
    }
    if edit.just_finished {
        edit.just_finished = false;
        return;
    }
    let Some(node) = state.session.doc.node(id) else {
        return;
    };
    let points = control_points(&node.content);
    let world = state.session.doc.world_matrix(id);
    let (cam, cam_t) = camera;
    let cursor = window.cursor_position();
    // B (Blender): a box from the cursor follows the mouse; a click adds
    // the points it holds; Esc or a right click cancels.
    // A chord, or the same action asked for from the Curve menu.
    let asked = requested.0.take();
    let pressed = |action| {
        asked == Some(action) || crate::bindings::pressed(&keys, KeyMode::ControlPoints, action)
    };
    if gate.keyboard_free
        && pressed(Action::BoxSelect)
        && let Some(c) = cursor
    {
        edit.box_select = Some((c, c));
        *b_box = true;
        status.info("Box select: move to the opposite corner and click (Esc cancels)");
    }
    if *b_box {
        if keys.just_pressed(KeyCode::Escape) || buttons.just_pressed(MouseButton::Right) {
            *b_box = false;
            edit.box_select = None;
        } else if let (Some((start, _)), Some(c)) = (edit.box_select, cursor) {
            edit.box_select = Some((start, c));
            if gate.pointer_free && buttons.just_pressed(MouseButton::Left) {
                *b_box = false;
                edit.box_select = None;
                select_in_box(&mut edit.selected, &points, world, (start, c), (cam, cam_t));
                status.info("Box select");
            }
        }
        return;
    }
    // Ctrl+click on a curve inserts a point there (Blender's curve edit
    // mode; the same insertion as K).
    if gate.pointer_free
        && buttons.just_pressed(MouseButton::Left)
        && hedra_scene::modifiers::ctrl(&keys)
        && matches!(node.content, NodeContent::Curve(_))
        && let Some(c) = cursor
    {
        match knot_under_cursor(id, &node.content, world, c, (cam, cam_t), false) {
            Some(cmd) => {
                requests.write(DocRequest::Execute(cmd));
            }
            None => status.error("Insert a point: Ctrl+click on the curve itself"),
        }
        return;
    }
    // A press on a point selects it; a press elsewhere starts a box, and a
    // release without dragging clears the selection (Shift keeps it).
    if gate.pointer_free
        && buttons.just_pressed(MouseButton::Left)
        && !alt(&keys)
        && !crate::gizmo_has_pointer(gizmo.as_deref())
        && let Some(cursor) = cursor
    {
        match point_under_cursor(&points, world, cursor, cam, cam_t) {
            Some(i) if shift(&keys) => {
                if !edit.selected.remove(&i) {
                    edit.selected.insert(i);
                }
            }
            Some(i) => edit.selected = BTreeSet::from([i]),
            None => edit.box_select = Some((cursor, cursor)),
        }
    }
    if let (Some((start, _)), Some(cursor)) = (edit.box_select, cursor) {
        edit.box_select = Some((start, cursor));
    }
    if buttons.just_released(MouseButton::Left)
        && let Some((a, b)) = edit.box_select.take()
    {
        if !shift(&keys) {
            edit.selected.clear();
        }
        if a.distance(b) > 4.0 {
            select_in_box(&mut edit.selected, &points, world, (a, b), (cam, cam_t));
        }
    }
    if !gate.keyboard_free {
        return;
    }
    if pressed(Action::SelectAll) {
        edit.selected = (0..points.len() as u32).collect();
    } else if pressed(Action::SelectNone) {
        edit.selected = BTreeSet::new();
    }
    // Curves: X deletes the selected points, Alt+C opens or closes.
    if let NodeContent::Curve(curve) = &node.content {
        if pressed(Action::Delete) {
            if edit.selected.is_empty() {
                status.error("Delete: select control points first");
            } else {
                // Tangent handles go with their key, not on their own.
                let keys = curve.control_points().len() as u32;
                requests.write(DocRequest::Execute(Command::DeleteCurvePoints {
                    node: reference_of(id),
                    points: edit
                        .selected
                        .iter()
                        .copied()
                        .filter(|&i| i < keys)
                        .collect(),
                }));
                edit.selected.clear();
            }
            return;
        }
        if pressed(Action::ToggleClosed) {
            requests.write(DocRequest::Execute(Command::SetCurveClosed {
                node: reference_of(id),
                closed: !curve.kind().is_closed(),
            }));
            return;
        }
        if pressed(Action::SplitCurve) {
            // At the one selected point the curve passes through, else at
            // the curve under the pointer.
            let on_curve = match edit.selected.iter().collect::<Vec<_>>()[..] {
                [&i] => curve.kind().on_curve_parameter(i as usize),
                _ => None,
            };
            let at = on_curve
                .or_else(|| curve_parameter_under_cursor(curve, world, cursor?, (cam, cam_t)));
            match at {
                Some(at) => {
                    requests.write(DocRequest::Execute(Command::SplitCurve {
                        node: reference_of(id),
                        at,
                        name: None,
                    }));
                    edit.selected.clear();
                }
                None => status.error(
                    "Split: select one point the curve passes through, or point at the curve",
                ),
            }
            return;
        }
    }
    let in_v = pressed(Action::InsertKnotV);
    if in_v || pressed(Action::InsertKnot) {
        let Some(cursor) = window.cursor_position() else {
            return;
        };
        match knot_under_cursor(id, &node.content, world, cursor, (cam, cam_t), in_v) {
            Some(cmd) => {
                requests.write(DocRequest::Execute(cmd));
            }
            None => status.error("Insert knot: point at the curve (or surface) where the knot goes, then press K (Shift+K: in v)"),
        }
        return;
    }
    let kind = if pressed(Action::Move) {
        Some(ShapeToolKind::Move)
    } else if pressed(Action::Weight) {
        Some(ShapeToolKind::Weight)
    } else if pressed(Action::Rotate) {
        Some(ShapeToolKind::Rotate)
    } else if pressed(Action::Scale) {
        Some(ShapeToolKind::Scale)
    } else if pressed(Action::Extrude) {
        match extruded_end(&node.content, &edit.selected) {
            Ok(end) => Some(ShapeToolKind::Extrude(end)),
            Err(e) => {
                status.error(e);
                return;
            }
        }
    } else {
        None
    };
    let Some(kind) = kind else { return };
    if edit.selected.is_empty() {
        status.error("Select control points first (click them, or A for all)");
        return;
    }
    if kind == ShapeToolKind::Weight && control_weights(&node.content).is_none() {
        status.error("Bézier triangles are polynomial: their points have no weights");
        return;
    }
    let centre = edit
        .selected
        .iter()
        .map(|&i| points[i as usize])
        .sum::<DVec3>()
        / edit.selected.len() as f64;
    let pivot = match (kind, *pivot_point) {
        (ShapeToolKind::Rotate | ShapeToolKind::Scale, crate::PivotPoint::Cursor) => cursor_3d.0,
        _ => world.transform_point3(centre),
    };
    let start_cursor = window.cursor_position().unwrap_or_default();
    edit.tool = Some(ShapeTool {
        kind,
        axis: None,
        typed: TypedNumber::default(),
        start_cursor,
        pivot,
        pivot_screen: cam
            .world_to_viewport(cam_t, pivot.as_vec3())
            .unwrap_or(start_cursor),
        readout: String::new(),
    });
}

/// A node as commands name it.
fn reference_of(id: NodeId) -> hedra_doc::NodeRef {
    hedra_doc::NodeRef::from(id)
}

/// The end of an open curve E extrudes from: the one selected point must
/// be its first or last defining point.
fn extruded_end(content: &NodeContent, selected: &BTreeSet<u32>) -> Result<CurveEnd, &'static str> {
    let NodeContent::Curve(curve) = content else {
        return Err("Extrude: surfaces have no ends to extrude (curves only)");
    };
    if curve.kind().is_closed() {
        return Err("Extrude: a closed curve has no end (Alt+C opens it)");
    }
    let last = curve.control_points().len() as u32 - 1;
    match selected.iter().collect::<Vec<_>>()[..] {
        [&0] => Ok(CurveEnd::Start),
        [&i] if i == last => Ok(CurveEnd::End),
        _ => Err("Extrude: select one end point of the curve (its first or last point)"),
    }
}

/// The parameter of a curve's point nearest the cursor on screen (the
/// nearest of 400 samples), when it is within 12 pixels.
fn curve_parameter_under_cursor(
    content: &hedra_doc::CurveContent,
    world: glam::DMat4,
    cursor: Vec2,
    (cam, cam_t): (&Camera, &GlobalTransform),
) -> Option<f64> {
    use hedra_geom::curves::Curve;
    let c = content.nurbs();
    let (a, b) = c.domain();
    let (t, d) = (1..400)
        .filter_map(|k| {
            let t = a + (b - a) * k as f64 / 400.0;
            let s = cam
                .world_to_viewport(cam_t, world.transform_point3(c.point(t)).as_vec3())
                .ok()?;
            Some((t, s.distance(cursor)))
        })
        .min_by(|x, y| x.1.total_cmp(&y.1))?;
    (d <= 12.0).then_some(t)
}

/// The knot insertion for the point of the shape under the cursor: for a
/// curve, the parameter of the nearest of 400 samples on screen (within 12
/// pixels); for a NURBS surface, the parameter the cursor's ray hits (`in_v`
/// picks the direction).
fn knot_under_cursor(
    id: NodeId,
    content: &NodeContent,
    world: glam::DMat4,
    cursor: Vec2,
    (cam, cam_t): (&Camera, &GlobalTransform),
    in_v: bool,
) -> Option<Command> {
    use hedra_doc::command::ParameterDirection;
    match content {
        NodeContent::Curve(content) => {
            let t = curve_parameter_under_cursor(content, world, cursor, (cam, cam_t))?;
            // A NURBS curve gets a knot; the other kinds a defining point
            // where the curve is (a de Casteljau split for poly-Béziers).
            let nurbs = matches!(content.kind(), hedra_geom::curves::CurveKind::Nurbs(_));
            Some(if nurbs {
                Command::InsertKnot {
                    node: NodeRef::from(id),
                    at: t,
                    direction: ParameterDirection::U,
                }
            } else {
                Command::InsertCurvePoint {
                    node: NodeRef::from(id),
                    at: t,
                }
            })
        }
        NodeContent::Surface(s) => {
            let SurfaceShape::Nurbs(n) = &**s else {
                return None;
            };
            let (origin, dir) = hedra_scene::camera_ray(cam, cam_t, cursor)?;
            let inv = world.inverse();
            let (origin, dir) = (inv.transform_point3(origin), inv.transform_vector3(dir));
            let hit = hedra_geom::surfaces::intersect::ray_surface(n, origin, dir)?;
            Some(Command::InsertKnot {
                node: NodeRef::from(id),
                at: if in_v { hit.v } else { hit.u },
                direction: if in_v {
                    ParameterDirection::V
                } else {
                    ParameterDirection::U
                },
            })
        }
        _ => None,
    }
}
