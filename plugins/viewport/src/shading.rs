//! The shading keys: Shift+Z toggles wireframe, Alt+Z X-ray, as in Blender,
//! in object, edit and control-point modes. The material follows in
//! `hedra_scene` (`ViewportShading`).

use crate::*;
use hedra_scene::{StatusMessage, ViewportShading};

/// Shift+Z and Alt+Z; while a modal tool runs, Z belongs to its axis keys.
pub fn shading_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    tool: Res<TransformTool>,
    mode: Res<EditMode>,
    shape_edit: Res<hedra_edit::ShapeEdit>,
    mut shading: ResMut<ViewportShading>,
    mut status: ResMut<StatusMessage>,
) {
    use hedra_edit::bindings::{Action, KeyMode, pressed};
    let busy = hedra_edit::modal_tool_running(&tool, &mode, &shape_edit);
    if !gate.keyboard_free || busy {
        return;
    }
    if pressed(&keys, KeyMode::Everywhere, Action::Wireframe) {
        shading.wireframe = !shading.wireframe;
        status.info(if shading.wireframe {
            "Wireframe: faces hidden, everything selectable through (Shift+Z: solid)"
        } else {
            "Solid shading (Shift+Z: wireframe)"
        });
    } else if pressed(&keys, KeyMode::Everywhere, Action::XRay) {
        shading.x_ray = !shading.x_ray;
        status.info(if shading.x_ray {
            "X-ray on: faces see-through, box select also takes hidden elements"
        } else {
            "X-ray off: box select takes only what is in sight"
        });
    }
}
