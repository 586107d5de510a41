//! The transform gizmo on the active object and the command its drag becomes.

use crate::*;

/// The transform gizmo follows the active object.
pub(crate) fn focus_gizmo_on_active(
    mut commands: Commands,
    selection: Res<Selection>,
    entities: Res<NodeEntities>,
    focused: Query<Entity, With<TransformGizmoFocus>>,
    gizmo_state: Res<TransformGizmoState>,
    mode: Res<EditMode>,
    shape_edit: Res<hedra_edit::ShapeEdit>,
) {
    if gizmo_state.active {
        return;
    }
    // No object gizmo in edit mode.
    let wanted = if mode.active() || shape_edit.active() {
        None
    } else {
        selection
            .active()
            .and_then(|id| entities.0.get(&id).copied())
    };
    for e in &focused {
        if Some(e) != wanted {
            commands.entity(e).remove::<TransformGizmoFocus>();
        }
    }
    if let Some(e) = wanted {
        if !focused.contains(e) {
            commands.entity(e).try_insert(TransformGizmoFocus);
        }
    }
}

/// When a gizmo drag ends, the entity's new transform becomes one document step.
pub(crate) fn commit_gizmo_drag(
    gizmo_state: Res<TransformGizmoState>,
    mut was_active: Local<Option<Entity>>,
    nodes: Query<(&NodeEntity, &Transform)>,
    state: Res<DocState>,
    mut requests: MessageWriter<DocRequest>,
) {
    if gizmo_state.active {
        *was_active = gizmo_state.entity;
        return;
    }
    let Some(entity) = was_active.take() else {
        return;
    };
    let Ok((node, t)) = nodes.get(entity) else {
        return;
    };
    let Some(doc_node) = state.session.doc.node(node.0) else {
        return;
    };
    let new = dragged_transform(&doc_node.transform, t);
    if new != doc_node.transform {
        requests.write(DocRequest::Execute(hedra_doc::Command::SetTransforms {
            nodes: vec![(NodeRef::from(node.0), new)],
        }));
    }
}

/// The document transform after a gizmo drag left the entity at `dragged`
/// (f32): the drag's change, applied to the exact f64 transform. A part the
/// drag did not touch (its f32 value is the document's, rounded) keeps its
/// exact value, so moving an object does not round its rotation and scale;
/// a moved translation gains the f32 delta, a turned rotation the f32 turn,
/// a scaled axis the f32 ratio.
pub(crate) fn dragged_transform(doc: &DocTransform, dragged: &Transform) -> DocTransform {
    let before = Transform {
        translation: doc.translation.as_vec3(),
        rotation: doc.rotation.as_quat(),
        scale: doc.scale.as_vec3(),
    };
    let translation = doc.translation + (dragged.translation - before.translation).as_dvec3();
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
    DocTransform {
        translation,
        rotation,
        scale,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    fn doc() -> DocTransform {
        DocTransform {
            translation: DVec3::new(0.1, 0.2, 1.0 / 3.0),
            rotation: DQuat::from_rotation_y(0.3),
            scale: DVec3::new(1.0 / 3.0, 2.0, 0.7),
        }
    }

    fn as_dragged(t: &DocTransform) -> Transform {
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
        assert!((t.translation.x - 2.1).abs() < 1e-6);
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
