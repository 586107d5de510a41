//! The 3D cursor, as Blender's: Shift+right click puts it on the surface
//! under the pointer (or, over empty space, at its current depth facing the
//! view); new objects are added there; View ▸ Cursor to World Origin and
//! Cursor to Selected move it.

use crate::*;
use hedra_scene::{Cursor3d, StatusMessage};

/// Shift+right click places the 3D cursor (outside running tools).
#[allow(clippy::too_many_arguments)]
pub fn place_cursor(
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    tool: Res<TransformTool>,
    mode: Res<EditMode>,
    shape_edit: Res<ShapeEdit>,
    viewport: hedra_scene::ViewportPointer,
    state: Res<DocState>,
    mut cursor: ResMut<Cursor3d>,
    mut status: ResMut<StatusMessage>,
) {
    let busy = modal_tool_running(&tool, &mode, &shape_edit);
    if busy || !gate.pointer_free || !shift(&keys) || !buttons.just_pressed(MouseButton::Right) {
        return;
    }
    let Some((origin, dir)) = viewport.ray() else {
        return;
    };
    let (_, cam_t) = viewport.camera();
    let view_dir = (cam_t.rotation() * Vec3::NEG_Z).as_dvec3();
    let at = match pick_node(&state.session.doc, origin, dir) {
        Some((_, t)) => origin + dir * t,
        None => {
            // Empty space: the plane through the cursor facing the view.
            let denom = dir.dot(view_dir);
            if denom.abs() < 1e-12 {
                return;
            }
            origin + dir * ((cursor.0 - origin).dot(view_dir) / denom)
        }
    };
    cursor.0 = at;
    status.info(format!(
        "3D cursor at ({:.3}, {:.3}, {:.3}); new objects go there",
        at.x, at.y, at.z
    ));
}
