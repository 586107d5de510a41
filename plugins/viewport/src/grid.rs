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
