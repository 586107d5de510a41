//! Bisect by a drag (Blender's Mesh ▸ Bisect): after the menu item, the
//! user drags a line across the view; the plane through that line and the
//! view direction cuts the selected faces (`Command::Bisect`, one undo
//! step). Released plainly it only cuts; with Shift held the part right of
//! the line (as dragged) is removed and the cut filled, with Ctrl the part
//! left of it.

use super::*;
use hedra_geom::modeling::BisectClear;

/// What the status line says while Bisect waits for its line.
const BISECT_HELP: &str = "Bisect: drag a line across the mesh · release cuts · \
     Shift+release also removes the part right of the line and fills the cut, \
     Ctrl+release the part left of it · Esc cancels";

/// Mesh ▸ Bisect's state: armed by the menu, then following the drag of
/// its line (window coordinates, logical pixels).
#[derive(Resource, Debug, Default, Clone, Copy, PartialEq)]
pub struct BisectDrag {
    /// The menu started the tool; edit-mode selection ignores the mouse.
    pub armed: bool,
    /// Where the drag started, once the left button went down.
    pub start: Option<Vec2>,
}

/// Follows the drag of Bisect's line, draws it, and on release sends the
/// cut; Esc, a right click or leaving edit mode cancels.
#[allow(clippy::too_many_arguments)]
pub fn bisect_by_drag(
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut drag: ResMut<BisectDrag>,
    mode: Res<EditMode>,
    state: Res<DocState>,
    viewport: hedra_scene::ViewportPointer,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<StatusMessage>,
    mut gizmos: Gizmos,
) {
    if !drag.armed {
        return;
    }
    let (Some(node), None) = (mode.node, &mode.tool) else {
        *drag = BisectDrag::default();
        return;
    };
    if keys.just_pressed(KeyCode::Escape) || buttons.just_pressed(MouseButton::Right) {
        *drag = BisectDrag::default();
        status.info("Bisect cancelled");
        return;
    }
    let Some(cursor) = viewport.cursor() else {
        return;
    };
    let Some(start) = drag.start else {
        if gate.pointer_free && buttons.just_pressed(MouseButton::Left) {
            drag.start = Some(cursor);
        }
        return;
    };
    let rays = [start, cursor].map(|p| viewport.ray_at(p));
    let [Some((o0, d0)), Some((o1, d1))] = rays else {
        return;
    };
    if buttons.pressed(MouseButton::Left) {
        // The line, just in front of the camera so nothing hides it.
        gizmos.line(
            (o0 + d0 * 0.5).as_vec3(),
            (o1 + d1 * 0.5).as_vec3(),
            Color::srgb(1.0, 0.85, 0.3),
        );
        return;
    }
    *drag = BisectDrag::default();
    if start.distance(cursor) < 4.0 {
        status.error("Bisect: drag a line across the mesh, not a click");
        return;
    }
    // Two points on the first ray and one on the second span the plane
    // through both rays (through the eye in perspective, along the view in
    // orthographic); its normal points to the right of the drag.
    let (a0, b0, a1) = (o0 + d0, o0 + d0 * 2.0, o1 + d1);
    let normal_world = (b0 - a0).cross(a1 - a0);
    let world = state.session.doc.world_matrix(node);
    let to_local = world.inverse();
    let (point, normal) = (
        to_local.transform_point3(a0),
        to_local.transpose().transform_vector3(normal_world),
    );
    let (clear, fill) = if shift(&keys) {
        (BisectClear::Outer, true)
    } else if ctrl(&keys) {
        (BisectClear::Inner, true)
    } else {
        (BisectClear::Neither, false)
    };
    requests.write(DocRequest::Execute(Command::Bisect {
        node: NodeRef::from(node),
        faces: FaceSet::Ids(mode.selection.faces.iter().map(|f| f.0).collect()),
        point,
        normal,
        clear,
        fill,
    }));
}

/// Arms Bisect (Mesh ▸ Bisect) when faces are selected; says why not otherwise.
pub fn start_bisect(drag: &mut BisectDrag, mode: &EditMode, status: &mut StatusMessage) {
    if mode.selection.faces.is_empty() {
        status.error("Bisect: select the faces to cut first (3 for face mode, A for all)");
        return;
    }
    *drag = BisectDrag {
        armed: true,
        start: None,
    };
    status.info(BISECT_HELP);
}
