//! Drawing a curve by clicks (Add ▸ Draw Curve; Rhino's Curve, Blender's
//! curve Draw): each left click puts a control point where the pointer is —
//! on the surface of a mesh under it, else on the construction plane (the
//! grid plane facing the view, through the 3D cursor) — snapped like a move
//! when snapping is on; Backspace takes the last point back, Enter ends
//! (`Command::AddCurve`, a clamped cubic NURBS, or lower with fewer points,
//! one undo step), Esc or a right click cancels.

use crate::bindings::{Action, KeyMode, pressed};
use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use glam::DVec3;
use hedra_doc::command::CurveSpec;
use hedra_doc::{Command, NodeTransform};
use hedra_scene::{DocRequest, DocState, InputGate, StatusMessage, ViewportCamera};

/// What the status line says while drawing.
const DRAW_HELP: &str = "Draw curve: click control points (on a surface or the grid plane; \
     snapping applies) · Backspace removes the last · Enter ends · Esc cancels";

/// The running curve drawing.
#[derive(Resource, Debug, Default, Clone, PartialEq)]
pub struct CurveDraw {
    /// Drawing: object picking and shortcuts ignore the input.
    pub active: bool,
    /// The clicked control points, world space.
    pub points: Vec<DVec3>,
    /// The curve through the points and the one the pointer would add, as
    /// a polyline in world space, for drawing.
    pub drawn: Vec<DVec3>,
    /// The point the pointer would add now.
    pub hover: Option<DVec3>,
    /// The frame that ended the drawing (its click or key is spent).
    pub just_finished: bool,
}

impl CurveDraw {
    /// Starts drawing (Add ▸ Draw Curve).
    pub fn start(&mut self, status: &mut StatusMessage) {
        *self = CurveDraw {
            active: true,
            ..default()
        };
        status.info(DRAW_HELP);
    }

    /// The degree a curve through `n` control points gets: cubic, or less
    /// when there are too few points for it.
    pub fn degree(n: usize) -> usize {
        n.saturating_sub(1).clamp(1, 3)
    }
}

/// The plane the points go on when no surface is under the pointer: through
/// `through`, facing the world axis nearest the view direction (the top
/// view draws on the ground, the front view on the XY plane).
pub fn construction_plane(view_dir: DVec3, through: DVec3) -> (DVec3, DVec3) {
    let a = view_dir.abs();
    let normal = if a.y >= a.x && a.y >= a.z {
        DVec3::Y
    } else if a.z >= a.x {
        DVec3::Z
    } else {
        DVec3::X
    };
    (through, normal)
}

/// Runs the drawing: the point under the pointer, clicks, keys, the end.
#[allow(clippy::too_many_arguments)]
pub fn drive_curve_draw(
    mut draw: ResMut<CurveDraw>,
    keys: Res<ButtonInput<KeyCode>>,
    buttons: Res<ButtonInput<MouseButton>>,
    gate: Res<InputGate>,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Single<(&Camera, &GlobalTransform), With<ViewportCamera>>,
    state: Res<DocState>,
    cursor_3d: Res<hedra_scene::Cursor3d>,
    snapping: Res<crate::Snapping>,
    mut snap_target: ResMut<crate::SnapTarget>,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<StatusMessage>,
) {
    draw.just_finished = false;
    if !draw.active {
        return;
    }
    let tool_key = |action| pressed(&keys, KeyMode::Tool, action);
    if tool_key(Action::Cancel) || buttons.just_pressed(MouseButton::Right) {
        *draw = CurveDraw {
            just_finished: true,
            ..default()
        };
        status.info("Draw curve cancelled");
        return;
    }
    if tool_key(Action::RemoveLastPoint) {
        draw.points.pop();
    }
    let (cam, cam_t) = *camera;
    let doc = &state.session.doc;
    let pointer = window.cursor_position();
    let ray = pointer.and_then(|c| {
        let r = cam.viewport_to_world(cam_t, c).ok()?;
        Some((r.origin.as_dvec3(), Vec3::from(r.direction).as_dvec3()))
    });
    let view_dir = (cam_t.rotation() * Vec3::NEG_Z).as_dvec3();
    let to_screen = |p: DVec3| cam.world_to_viewport(cam_t, p.as_vec3()).ok();
    let mut scene = crate::SnapScene::of_document(doc, |_| true);
    scene.points.extend(draw.points.iter().copied());
    let element_target = match (pointer, snapping.active(&keys), snapping.element) {
        (Some(c), true, element) => scene.target(element, c, ray, &to_screen),
        _ => None,
    };
    snap_target.0 = element_target;
    draw.hover = element_target.or_else(|| {
        let (o, d) = ray?;
        if let Some((_, dist)) = crate::pick_node(doc, o, d) {
            return Some(o + d.normalize() * dist);
        }
        let (through, normal) = construction_plane(view_dir, cursor_3d.0);
        let denom = d.dot(normal);
        let t = (through - o).dot(normal) / denom;
        if denom.abs() < 1e-12 || t <= 0.0 {
            return None;
        }
        let p = o + d * t;
        // Increments: whole steps within the plane.
        let round = |x: f64| crate::Snapping::round(snapping.active(&keys), x, snapping.step);
        Some(if normal == DVec3::Y {
            DVec3::new(round(p.x), p.y, round(p.z))
        } else if normal == DVec3::Z {
            DVec3::new(round(p.x), round(p.y), p.z)
        } else {
            DVec3::new(p.x, round(p.y), round(p.z))
        })
    });
    if gate.pointer_free && buttons.just_pressed(MouseButton::Left) {
        match draw.hover {
            Some(p) => draw.points.push(p),
            None => status.error("Draw curve: point at a surface or the grid plane"),
        }
    }
    let with_hover: Vec<DVec3> = draw
        .points
        .iter()
        .chain(draw.hover.iter())
        .copied()
        .collect();
    draw.drawn = preview(&with_hover);
    if !keys.any_just_pressed([KeyCode::Enter, KeyCode::NumpadEnter]) {
        return;
    }
    let points = std::mem::take(&mut draw.points);
    *draw = CurveDraw {
        just_finished: true,
        ..default()
    };
    if points.len() < 2 {
        status.error("Draw curve: click two points or more before Enter");
        return;
    }
    // The node's origin is the 3D cursor, as for every added object.
    let origin = cursor_3d.0;
    requests.write(DocRequest::Execute(Command::AddCurve {
        name: "Curve".into(),
        curve: CurveSpec::Nurbs {
            degree: CurveDraw::degree(points.len()),
            points: points.iter().map(|p| *p - origin).collect(),
            weights: None,
            knots: None,
        },
        parent: None,
        transform: NodeTransform::from_translation(origin),
    }));
}

/// The clamped NURBS through `points` as a polyline of 32 samples a span
/// (the control polygon itself for fewer than 3 points).
fn preview(points: &[DVec3]) -> Vec<DVec3> {
    if points.len() < 3 {
        return points.to_vec();
    }
    let Ok(curve) =
        hedra_geom::curves::NurbsCurve::clamped(CurveDraw::degree(points.len()), points.to_vec())
    else {
        return points.to_vec();
    };
    let samples = 32 * points.len();
    let params: Vec<f64> = (0..=samples).map(|i| i as f64 / samples as f64).collect();
    curve.points_at(&params)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plane_faces_the_nearest_axis_through_the_cursor() {
        let through = DVec3::new(1.0, 2.0, 3.0);
        assert_eq!(
            construction_plane(DVec3::new(0.1, -0.9, 0.2), through),
            (through, DVec3::Y)
        );
        assert_eq!(construction_plane(DVec3::NEG_Z, through).1, DVec3::Z);
        assert_eq!(
            construction_plane(DVec3::new(-1.0, 0.2, 0.3), through).1,
            DVec3::X
        );
    }

    #[test]
    fn cubic_once_there_are_four_points() {
        assert_eq!([2, 3, 4, 9].map(CurveDraw::degree), [1, 2, 3, 3]);
    }
}
