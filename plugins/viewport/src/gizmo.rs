//! The transform gizmo: on the active object in object mode, on the
//! selected mesh elements in edit mode and on the selected control points
//! in control-point mode (Blender shows it in all three).
//!
//! Bevy's gizmo drives a proxy entity ([`GizmoProxy`]), never a node:
//! [`place_gizmo_proxy`] puts the proxy on what the gizmo acts on while no
//! drag runs, Bevy's `transform_gizmo_drag` moves it during a drag, and
//! [`drive_gizmo_drag`] turns the proxy's change into a preview
//! ([`PreviewSource::Gizmo`]) and, when the button is let go, into one
//! command applied to the exact f64 values. Esc or a right click during a
//! drag puts everything back.

use crate::*;
use glam::DMat4;
use hedra_doc::{Command, NodeId};
use hedra_edit::ShapeEdit;
use hedra_scene::{PreviewContent, PreviewSource, Previews, ToolPreview};

/// The entity the transform gizmo moves: a stand-in for the active object
/// or the selected elements.
#[derive(Component, Debug, Default)]
pub struct GizmoProxy;

/// What a gizmo drag acts on, as it was when the drag started.
#[derive(Clone, Debug, PartialEq)]
pub enum GizmoTarget {
    /// An object: its exact world transform and its parent's world matrix.
    Object {
        node: NodeId,
        world: NodeTransform,
        parent_world: DMat4,
    },
    /// Selected mesh vertices (`mesh: true`) or control points, by index,
    /// at their local positions, and the node's world matrix.
    Points {
        node: NodeId,
        mesh: bool,
        world: DMat4,
        points: Vec<(u32, DVec3)>,
    },
}

impl GizmoTarget {
    /// What the gizmo acts on now: the selected mesh elements in edit mode,
    /// the selected control points in control-point mode, else the active
    /// object; `None` when nothing is selected.
    pub fn of_selection(
        doc: &hedra_doc::Document,
        selection: &Selection,
        mode: &EditMode,
        shape_edit: &ShapeEdit,
    ) -> Option<GizmoTarget> {
        if let Some(node) = mode.node {
            let mesh = hedra_edit::mesh_mode::edited_mesh_of(doc, node)?;
            let points: Vec<(u32, DVec3)> = mode
                .selection
                .all_vertices(&mesh)
                .into_iter()
                .map(|v| (v.0, mesh.position(v)))
                .collect();
            return (!points.is_empty()).then(|| GizmoTarget::Points {
                node,
                mesh: true,
                world: doc.world_matrix(node),
                points,
            });
        }
        if let Some(node) = shape_edit.node {
            let all = hedra_edit::shape_mode::control_points(&doc.node(node)?.content);
            let points: Vec<(u32, DVec3)> = shape_edit
                .selected
                .iter()
                .filter_map(|&i| all.get(i as usize).map(|p| (i, *p)))
                .collect();
            return (!points.is_empty()).then(|| GizmoTarget::Points {
                node,
                mesh: false,
                world: doc.world_matrix(node),
                points,
            });
        }
        let node = doc.node(selection.active()?)?;
        let parent_world = node.parent.map_or(DMat4::IDENTITY, |p| doc.world_matrix(p));
        let world = if node.parent.is_some() {
            NodeTransform::from_matrix(parent_world * node.transform.to_matrix())
        } else {
            node.transform
        };
        Some(GizmoTarget::Object {
            node: node.id,
            world,
            parent_world,
        })
    }

    /// Where the proxy sits: the object's world transform, or the centre of
    /// the points with the world's axes.
    pub fn proxy_transform(&self) -> Transform {
        match self {
            GizmoTarget::Object { world, .. } => hedra_scene::bevy_transform(world),
            GizmoTarget::Points { world, points, .. } => {
                let centre = points
                    .iter()
                    .map(|(_, p)| world.transform_point3(*p))
                    .sum::<DVec3>()
                    / points.len() as f64;
                Transform::from_translation(centre.as_vec3())
            }
        }
    }

    /// The command that leaves the target where the proxy moved from
    /// `start` to `now`; `None` when the drag changed nothing.
    pub fn command(&self, start: &Transform, now: &Transform) -> Option<Command> {
        if start == now {
            return None;
        }
        match self {
            GizmoTarget::Object {
                node,
                world,
                parent_world,
            } => {
                let new_world = dragged_transform(world, now);
                let local = if *parent_world == DMat4::IDENTITY {
                    new_world
                } else {
                    NodeTransform::from_matrix(parent_world.inverse() * new_world.to_matrix())
                };
                Some(Command::SetTransforms {
                    nodes: vec![((*node).into(), local)],
                })
            }
            GizmoTarget::Points {
                node,
                mesh,
                world,
                points,
            } => {
                // The proxy's change as a world-space matrix, carried into
                // the node's local space.
                let affine = |t: &Transform| t.to_matrix().as_dmat4();
                let mut change = affine(now) * affine(start).inverse();
                // A plain move goes by a delta on the shown decimals.
                if now.rotation == start.rotation && now.scale == start.scale {
                    change = DMat4::from_translation(
                        (now.translation - start.translation)
                            .as_dvec3()
                            .map(shown_value),
                    );
                }
                let local = world.inverse() * change * *world;
                let moved: Vec<(u32, DVec3)> = points
                    .iter()
                    .map(|(i, p)| (*i, local.transform_point3(*p)))
                    .collect();
                let node = (*node).into();
                Some(if *mesh {
                    Command::SetVertexPositions {
                        node,
                        positions: moved,
                    }
                } else {
                    Command::SetControlPoints {
                        node,
                        points: moved,
                    }
                })
            }
        }
    }

    fn node(&self) -> NodeId {
        match self {
            GizmoTarget::Object { node, .. } | GizmoTarget::Points { node, .. } => *node,
        }
    }
}

pub(crate) fn spawn_gizmo_proxy(mut commands: Commands) {
    commands.spawn((GizmoProxy, Name::new("Gizmo proxy"), Transform::default()));
}

/// Puts the proxy (and the gizmo with it) on what the gizmo acts on, or
/// takes the gizmo away when nothing is selected or a modal tool runs.
#[allow(clippy::too_many_arguments)]
pub(crate) fn place_gizmo_proxy(
    mut commands: Commands,
    gizmo_state: Res<TransformGizmoState>,
    state: Res<DocState>,
    selection: Res<Selection>,
    mode: Res<EditMode>,
    shape_edit: Res<ShapeEdit>,
    tool: Res<TransformTool>,
    mut proxy: Single<(Entity, &mut Transform, Has<TransformGizmoFocus>), With<GizmoProxy>>,
) {
    if gizmo_state.active {
        return;
    }
    let modal_running = hedra_edit::modal_tool_running(&tool, &mode, &shape_edit);
    let target = (!modal_running)
        .then(|| GizmoTarget::of_selection(&state.session.doc, &selection, &mode, &shape_edit))
        .flatten();
    let (entity, transform, focused) = &mut *proxy;
    match target {
        Some(t) => {
            let wanted = t.proxy_transform();
            if **transform != wanted {
                **transform = wanted;
            }
            if !*focused {
                commands.entity(*entity).insert(TransformGizmoFocus);
            }
        }
        None if *focused => {
            commands.entity(*entity).remove::<TransformGizmoFocus>();
        }
        None => {}
    }
}

/// A running gizmo drag: what it acts on and where the proxy started.
#[derive(Debug, Default)]
pub(crate) struct GizmoDrag {
    target: Option<GizmoTarget>,
    start: Transform,
    cancelled: bool,
}

/// During a gizmo drag, shows the change as a preview; when the button is
/// let go, sends it as one command (one undo step). Esc or a right click
/// drops the drag's change. Runs before the document is applied, so the
/// release frame already shows the result.
#[allow(clippy::too_many_arguments)]
pub(crate) fn drive_gizmo_drag(
    gizmo_state: Res<TransformGizmoState>,
    keys: Res<ButtonInput<KeyCode>>,
    buttons: Res<ButtonInput<MouseButton>>,
    state: Res<DocState>,
    selection: Res<Selection>,
    mode: Res<EditMode>,
    shape_edit: Res<ShapeEdit>,
    proxy: Single<&Transform, With<GizmoProxy>>,
    mut drag: Local<GizmoDrag>,
    mut previews: ResMut<Previews>,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    let doc = &state.session.doc;
    if gizmo_state.active {
        if drag.target.is_none() && !drag.cancelled {
            drag.target = GizmoTarget::of_selection(doc, &selection, &mode, &shape_edit);
            drag.start = gizmo_state.start_transform;
        }
        let modal_keys = hedra_edit::modal::ModalKeys {
            keys: &keys,
            buttons: &buttons,
        };
        if modal_keys.cancel() && drag.target.is_some() {
            drag.target = None;
            drag.cancelled = true;
            status.info("Gizmo drag cancelled");
        }
        let preview = drag
            .target
            .as_ref()
            .and_then(|t| Some((t, t.command(&drag.start, &proxy)?)))
            .and_then(|(t, cmd)| preview_of(doc, t.node(), &cmd));
        match preview {
            Some(p) => Previews::show(&mut previews, PreviewSource::Gizmo, p),
            None => Previews::clear(&mut previews, PreviewSource::Gizmo),
        }
        return;
    }
    drag.cancelled = false;
    Previews::clear(&mut previews, PreviewSource::Gizmo);
    let Some(target) = drag.target.take() else {
        return;
    };
    if let Some(cmd) = target.command(&drag.start, &proxy) {
        requests.write(DocRequest::Execute(cmd));
    }
}

/// What a gizmo command would show: the node's new transform or content.
fn preview_of(doc: &hedra_doc::Document, node: NodeId, cmd: &Command) -> Option<ToolPreview> {
    let decided = doc.decide(cmd, 0).ok()?;
    let after = decided
        .changes
        .iter()
        .find(|c| c.id == node)?
        .after
        .clone()?;
    let mut preview = ToolPreview::default();
    // Nodes made from this one (a revolution of a dragged profile) follow.
    for change in decided.changes.iter().filter(|c| c.id != node) {
        if let Some(content) = change
            .after
            .as_ref()
            .and_then(|n| PreviewContent::of_shape(&n.content))
        {
            preview.contents.insert(change.id, content);
        }
    }
    match cmd {
        Command::SetTransforms { .. } => {
            preview.transforms.insert(node, after.transform);
        }
        _ => {
            preview
                .contents
                .insert(node, PreviewContent::of_shape(&after.content)?);
        }
    }
    Some(preview)
}

/// The document transform after a gizmo drag left the entity at `dragged`
/// (f32): the drag's change, applied to the exact f64 transform. A part the
/// drag did not touch (its f32 value is the document's, rounded) keeps its
/// exact value, so moving an object does not round its rotation and scale;
/// a moved translation gains the f32 delta, a turned rotation the f32 turn,
/// a scaled axis the f32 ratio.
/// `x` rounded to the 4 decimals the Properties fields show (the nearest
/// f64 to that decimal: 1.8033, not 1.80330002…).
pub(crate) fn shown_value(x: f64) -> f64 {
    (x * 1e4).round() / 1e4
}

pub(crate) fn dragged_transform(doc: &NodeTransform, dragged: &Transform) -> NodeTransform {
    let before = Transform {
        translation: doc.translation.as_vec3(),
        rotation: doc.rotation.as_quat(),
        scale: doc.scale.as_vec3(),
    };
    // A dragged coordinate lands on the value the Location field shows
    // (4 decimals), not on f32 noise (1.803330898284912); the others stay
    // exact.
    let moved = |now: f32, was: f32, exact: f64| {
        if now == was {
            exact
        } else {
            shown_value(exact + f64::from(now - was))
        }
    };
    let translation = DVec3::new(
        moved(
            dragged.translation.x,
            before.translation.x,
            doc.translation.x,
        ),
        moved(
            dragged.translation.y,
            before.translation.y,
            doc.translation.y,
        ),
        moved(
            dragged.translation.z,
            before.translation.z,
            doc.translation.z,
        ),
    );
    let rotation = if dragged.rotation == before.rotation {
        doc.rotation
    } else {
        let turn = dragged.rotation.as_dquat() * before.rotation.as_dquat().inverse();
        (turn * doc.rotation).normalize()
    };
    let ratio = |now: f32, was: f32, exact: f64| {
        if now == was {
            exact
        } else if was != 0.0 {
            exact * (now as f64 / was as f64)
        } else {
            now as f64
        }
    };
    let scale = DVec3::new(
        ratio(dragged.scale.x, before.scale.x, doc.scale.x),
        ratio(dragged.scale.y, before.scale.y, doc.scale.y),
        ratio(dragged.scale.z, before.scale.z, doc.scale.z),
    );
    NodeTransform {
        translation,
        rotation,
        scale,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    fn doc() -> NodeTransform {
        NodeTransform {
            translation: DVec3::new(0.1, 0.2, 1.0 / 3.0),
            rotation: DQuat::from_rotation_y(0.3),
            scale: DVec3::new(1.0 / 3.0, 2.0, 0.7),
        }
    }

    fn as_dragged(t: &NodeTransform) -> Transform {
        Transform {
            translation: t.translation.as_vec3(),
            rotation: t.rotation.as_quat(),
            scale: t.scale.as_vec3(),
        }
    }

    #[test]
    fn an_untouched_drag_changes_nothing() {
        assert_eq!(dragged_transform(&doc(), &as_dragged(&doc())), doc());
    }

    #[test]
    fn a_move_keeps_rotation_and_scale_exact() {
        let mut dragged = as_dragged(&doc());
        dragged.translation.x += 2.0;
        let t = dragged_transform(&doc(), &dragged);
        assert_eq!(t.rotation, doc().rotation);
        assert_eq!(t.scale, doc().scale);
        assert_eq!((t.translation.y, t.translation.z), (0.2, 1.0 / 3.0));
        assert_eq!(t.translation.x, 2.1, "lands on the shown decimal");
    }

    #[test]
    fn a_turn_and_a_scale_apply_their_change_to_the_exact_values() {
        let mut dragged = as_dragged(&doc());
        dragged.rotation = Quat::from_rotation_x(0.5) * dragged.rotation;
        dragged.scale.y *= 2.0;
        let t = dragged_transform(&doc(), &dragged);
        assert_eq!(t.translation, doc().translation);
        assert_eq!((t.scale.x, t.scale.z), (1.0 / 3.0, 0.7));
        assert!((t.scale.y - 4.0).abs() < 1e-6);
        let expected = DQuat::from_rotation_x(0.5) * doc().rotation;
        assert!(t.rotation.angle_between(expected) < 1e-6);
    }
}
