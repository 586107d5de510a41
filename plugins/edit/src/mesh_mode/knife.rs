//! The Knife (Blender's K in edit mode): click points on the mesh's
//! surface, Enter cuts along the path (`Command::Knife`, one undo step) and
//! selects the cut edges; Backspace takes the last point back, Esc or a
//! right click cancels. A click near a vertex (or, failing that, an edge's
//! midpoint) snaps to it, as Blender's knife does; elsewhere the point is
//! where the pointer's ray meets the surface.

use super::*;
use crate::bindings::{Action, KeyMode};

/// What the status line says while the knife runs.
const KNIFE_HELP: &str = "Knife: click points on the surface (near a vertex or an edge's \
     middle snaps to it) · C: angle constraint (45° steps on screen) · Enter cuts · \
     Backspace removes the last point · Esc cancels";

/// How near the pointer (logical pixels) a vertex or edge midpoint snaps.
const KNIFE_SNAP_PIXELS: f32 = 12.0;

/// The running knife: its path so far, in the edited mesh's local space.
#[derive(Resource, Debug, Default, Clone, PartialEq)]
pub struct KnifeTool {
    /// K started the tool; edit-mode selection and shortcuts ignore input.
    pub active: bool,
    /// The clicked points, local space.
    pub points: Vec<DVec3>,
    /// The path in world space with the point the pointer would add last,
    /// for drawing.
    pub drawn: Vec<DVec3>,
    /// C toggles it: the next segment runs at a multiple of 45° on screen
    /// from the last point (Blender's knife angle constraint).
    pub angle_constraint: bool,
}

/// `cursor` moved onto the nearest screen line through `from` at a multiple
/// of 45°.
pub fn constrain_to_45_degrees(from: Vec2, cursor: Vec2) -> Vec2 {
    let d = cursor - from;
    let step = std::f32::consts::FRAC_PI_4;
    let angle = (d.y.atan2(d.x) / step).round() * step;
    let dir = Vec2::new(angle.cos(), angle.sin());
    from + dir * d.dot(dir)
}

/// K in edit mode (no tool running) starts the knife.
pub fn start_knife(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mode: Res<EditMode>,
    mut knife: ResMut<KnifeTool>,
    mut status: ResMut<StatusMessage>,
) {
    if knife.active
        || !mode.active()
        || mode.tool.is_some()
        || !gate.keyboard_free
        || !crate::bindings::pressed(
            &keys,
            crate::bindings::KeyMode::Edit,
            crate::bindings::Action::Knife,
        )
    {
        return;
    }
    *knife = KnifeTool {
        active: true,
        ..Default::default()
    };
    status.info(KNIFE_HELP);
}

/// The surface point a click at `cursor` adds: a vertex or edge midpoint
/// within [`KNIFE_SNAP_PIXELS`] of the pointer, else the ray's hit on the
/// mesh (local space); `None` off the mesh.
fn knife_point(
    mesh: &HalfEdgeMesh,
    world: DMat4,
    ray: Option<(DVec3, DVec3)>,
    cursor: Vec2,
    to_screen: &dyn Fn(DVec3) -> Option<Vec2>,
) -> Option<DVec3> {
    let (origin, dir) = ray?;
    let to_local = world.inverse();
    let (o, d) = (
        to_local.transform_point3(origin),
        to_local.transform_vector3(dir),
    );
    // Snap only to what is in sight from the eye (tested for the few
    // points near the pointer only).
    let near = |points: &mut dyn Iterator<Item = DVec3>| {
        let mut close: Vec<(f32, DVec3)> = points
            .filter_map(|p| {
                let d = to_screen(world.transform_point3(p))?.distance(cursor);
                (d <= KNIFE_SNAP_PIXELS).then_some((d, p))
            })
            .collect();
        close.sort_by(|a, b| a.0.total_cmp(&b.0));
        close
            .into_iter()
            .map(|(_, p)| p)
            .find(|&p| hedra_geom::query::is_visible_from(mesh, o, p))
    };
    let hit = hedra_geom::query::ray_cast(mesh, o, d).map(|(_, t)| o + d * t);
    near(&mut mesh.vertices().map(|v| mesh.position(v)))
        .or_else(|| near(&mut mesh.edges().map(|e| mesh.edge_midpoint(e))))
        .or(hit)
}

/// Follows the knife: adds a point per click, draws the path, cuts on
/// Enter and selects the cut edges; cancels on Esc, a right click or when
/// edit mode ends.
pub fn drive_knife(
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut knife: ResMut<KnifeTool>,
    mut mode: ResMut<EditMode>,
    state: Res<DocState>,
    viewport: hedra_scene::ViewportPointer,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<StatusMessage>,
) {
    let (window, camera) = (viewport.window(), viewport.camera());
    if !knife.active {
        return;
    }
    let (Some(node), Some(mesh)) = (mode.node, edited_mesh(&state, &mode)) else {
        *knife = KnifeTool::default();
        return;
    };
    let pressed = |action| crate::bindings::pressed(&keys, KeyMode::Tool, action);
    if pressed(Action::Cancel) || buttons.just_pressed(MouseButton::Right) {
        *knife = KnifeTool::default();
        status.info("Knife cancelled");
        return;
    }
    let (cam, cam_t) = camera;
    let world = state.session.doc.world_matrix(node);
    let to_screen = |p: DVec3| cam.world_to_viewport(cam_t, p.as_vec3()).ok();
    if pressed(Action::KnifeAngle) {
        knife.angle_constraint = !knife.angle_constraint;
    }
    // With the angle constraint the pointer is moved onto the nearest 45°
    // line from the last point, and the surface point taken there.
    let last_on_screen = knife
        .points
        .last()
        .and_then(|&p| to_screen(world.transform_point3(p)));
    let pointer = window.cursor_position().map(|c| match last_on_screen {
        Some(from) if knife.angle_constraint => constrain_to_45_degrees(from, c),
        _ => c,
    });
    let under_pointer = pointer.and_then(|c| {
        let ray = viewport.ray_at(c);
        knife_point(&mesh, world, ray, c, &to_screen)
    });
    if pressed(Action::RemoveLastPoint) {
        knife.points.pop();
    }
    if gate.pointer_free && buttons.just_pressed(MouseButton::Left) {
        match under_pointer {
            Some(p) => knife.points.push(p),
            None => status.error("Knife: click on the mesh's surface"),
        }
    }
    knife.drawn = knife
        .points
        .iter()
        .chain(under_pointer.iter())
        .map(|&p| world.transform_point3(p))
        .collect();
    // Enter cuts (Space does not: the knife is clicked, not confirmed).
    if !keys.any_just_pressed([KeyCode::Enter, KeyCode::NumpadEnter]) {
        return;
    }
    let points = std::mem::take(&mut knife.points);
    *knife = KnifeTool::default();
    let view = world
        .inverse()
        .transform_vector3((cam_t.rotation() * Vec3::NEG_Z).as_dvec3());
    let cmd = Command::Knife {
        node: NodeRef::from(node),
        points,
        view,
    };
    match state.session.doc.decide_with_result(&cmd, 0) {
        Ok(decision) => {
            // Blender leaves the cut edges selected.
            mode.kind = ElementKind::Edge;
            mode.selection = ElementSelection {
                edges: decision.created_edges.iter().copied().collect(),
                ..Default::default()
            };
            requests.write(DocRequest::Execute(cmd));
        }
        Err(e) => status.error(format!("Knife: {e}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_angle_constraint_keeps_45_degree_lines() {
        let from = Vec2::new(100.0, 100.0);
        // Nearly horizontal: onto the horizontal line.
        assert_eq!(
            constrain_to_45_degrees(from, Vec2::new(150.0, 104.0)),
            Vec2::new(150.0, 100.0)
        );
        // Nearly diagonal: onto the diagonal, projected.
        let p = constrain_to_45_degrees(from, Vec2::new(140.0, 136.0));
        assert!((p - Vec2::new(138.0, 138.0)).length() < 1e-3, "{p}");
    }
}
