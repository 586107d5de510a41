//! The ground grid and the coloured axes.

use crate::*;

/// Axis lines are drawn over the grid lines they coincide with.
#[derive(Default, Reflect, GizmoConfigGroup)]
pub struct AxisGizmos;

pub(crate) fn draw_grid(mut grid: Gizmos, mut axes: Gizmos<AxisGizmos>) {
    grid.grid(
        Quat::from_rotation_x(FRAC_PI_2),
        UVec2::splat(20),
        Vec2::splat(1.0),
        LinearRgba::gray(0.3),
    );
    axes.line(
        Vec3::new(-10.0, 0.0, 0.0),
        Vec3::new(10.0, 0.0, 0.0),
        Color::srgb(0.85, 0.25, 0.3),
    );
    axes.line(
        Vec3::new(0.0, 0.0, -10.0),
        Vec3::new(0.0, 0.0, 10.0),
        Color::srgb(0.25, 0.45, 0.9),
    );
    axes.line(
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        Color::srgb(0.35, 0.8, 0.3),
    );
}

/// The 3D cursor's lines: drawn over everything, as Blender does.
#[derive(Default, Reflect, GizmoConfigGroup)]
pub struct CursorGizmos;

/// The 3D cursor as Blender draws it: a red-and-white ring facing the view
/// with short cross hairs, sized to stay the same on screen.
pub(crate) fn draw_cursor(
    cursor: Res<hedra_scene::Cursor3d>,
    camera: Single<&GlobalTransform, With<ViewportCamera>>,
    mut gizmos: Gizmos<CursorGizmos>,
) {
    let at = cursor.0.as_vec3();
    let size = camera.translation().distance(at).max(1e-3) * 0.025;
    let facing = Isometry3d::new(at, camera.rotation());
    let (red, white) = (Color::srgb(0.9, 0.2, 0.2), Color::srgb(0.95, 0.95, 0.95));
    // Alternating arcs make the dashed ring.
    for k in 0..8 {
        let start = k as f32 * std::f32::consts::FRAC_PI_4;
        let arc = Isometry3d::new(at, camera.rotation() * Quat::from_rotation_z(start));
        let color = if k % 2 == 0 { red } else { white };
        gizmos.arc_3d(std::f32::consts::FRAC_PI_4, size, arc, color);
    }
    let (right, up) = (facing.rotation * Vec3::X, facing.rotation * Vec3::Y);
    for d in [right, up] {
        gizmos.line(at + d * size * 0.5, at + d * size * 1.6, Color::BLACK);
        gizmos.line(at - d * size * 0.5, at - d * size * 1.6, Color::BLACK);
    }
}

/// The vertex a running move snapped to: a ring around it, over everything.
pub(crate) fn draw_snap_target(
    target: Res<hedra_edit::SnapTarget>,
    camera: Single<&GlobalTransform, With<ViewportCamera>>,
    mut gizmos: Gizmos<CursorGizmos>,
) {
    let Some(at) = target.0 else { return };
    let at = at.as_vec3();
    let size = camera.translation().distance(at).max(1e-3) * 0.012;
    let facing = Isometry3d::new(at, camera.rotation());
    gizmos.circle(facing, size, Color::srgb(1.0, 0.6, 0.1));
}

/// The influence circle of a running proportional transform, around its
/// pivot and facing the view.
pub(crate) fn draw_proportional_ring(
    ring: Res<hedra_edit::ProportionalRing>,
    camera: Single<&GlobalTransform, With<ViewportCamera>>,
    mut gizmos: Gizmos<CursorGizmos>,
) {
    let Some((center, radius)) = ring.0 else {
        return;
    };
    let facing = Isometry3d::new(center.as_vec3(), camera.rotation());
    gizmos
        .circle(facing, radius as f32, Color::srgb(0.9, 0.9, 0.9))
        .resolution(64);
}

/// The axis a running G/R/S is locked to: a line through the pivot along
/// it, in the axis's colour (X red, Y green, Z blue), across the view, as
/// Blender draws it.
pub(crate) fn draw_axis_lock(
    lock: Res<hedra_edit::AxisLock>,
    camera: Single<&GlobalTransform, With<ViewportCamera>>,
    mut gizmos: Gizmos<CursorGizmos>,
) {
    let Some((pivot, axis)) = lock.0 else {
        return;
    };
    let color = match axis {
        hedra_edit::Axis::X => Color::srgb(0.95, 0.3, 0.35),
        hedra_edit::Axis::Y => Color::srgb(0.45, 0.85, 0.2),
        hedra_edit::Axis::Z => Color::srgb(0.25, 0.55, 1.0),
    };
    let pivot = pivot.as_vec3();
    // Long enough to leave the view from any distance it is seen at.
    let reach = camera.translation().distance(pivot).max(1.0) * 1000.0;
    let direction = axis.vector().as_vec3() * reach;
    gizmos.line(pivot - direction, pivot + direction, color);
}

/// The knife's path while it runs: its points ringed and joined, the last
/// segment to where the pointer would add the next point.
/// The curve being drawn (Add ▸ Draw Curve): its control polygon dim, the
/// curve bright, a ring on each point.
pub(crate) fn draw_curve_drawing(
    draw: Res<hedra_edit::CurveDraw>,
    camera: Single<&GlobalTransform, With<ViewportCamera>>,
    mut gizmos: Gizmos<CursorGizmos>,
) {
    if !draw.active {
        return;
    }
    let curve = Color::srgb(1.0, 0.75, 0.2);
    let polygon = Color::srgba(1.0, 0.75, 0.2, 0.35);
    let control: Vec<Vec3> = draw
        .points
        .iter()
        .chain(draw.hover.iter())
        .map(|p| p.as_vec3())
        .collect();
    for pair in control.windows(2) {
        gizmos.line(pair[0], pair[1], polygon);
    }
    for pair in draw.drawn.windows(2) {
        gizmos.line(pair[0].as_vec3(), pair[1].as_vec3(), curve);
    }
    for &p in &control {
        let size = camera.translation().distance(p).max(1e-3) * 0.006;
        gizmos.circle(Isometry3d::new(p, camera.rotation()), size, curve);
    }
}

pub(crate) fn draw_knife_path(
    knife: Res<hedra_edit::KnifeTool>,
    camera: Single<&GlobalTransform, With<ViewportCamera>>,
    mut gizmos: Gizmos<CursorGizmos>,
) {
    if !knife.active {
        return;
    }
    let color = Color::srgb(0.2, 0.9, 0.3);
    let points: Vec<Vec3> = knife.drawn.iter().map(|p| p.as_vec3()).collect();
    for pair in points.windows(2) {
        gizmos.line(pair[0], pair[1], color);
    }
    for &p in &points {
        let size = camera.translation().distance(p).max(1e-3) * 0.006;
        gizmos.circle(Isometry3d::new(p, camera.rotation()), size, color);
    }
}
