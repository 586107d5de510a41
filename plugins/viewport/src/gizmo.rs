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
    let new = DocTransform {
        translation: t.translation.as_dvec3(),
        rotation: t.rotation.as_dquat().normalize(),
        scale: t.scale.as_dvec3(),
    };
    let old = DocTransform {
        translation: doc_node.transform.translation.as_vec3().as_dvec3(),
        rotation: doc_node.transform.rotation.as_quat().as_dquat(),
        scale: doc_node.transform.scale.as_vec3().as_dvec3(),
    };
    if new != old {
        requests.write(DocRequest::Execute(hedra_doc::Command::SetTransforms {
            nodes: vec![(NodeRef::from(node.0), new)],
        }));
    }
}
