//! Proportional editing (Blender's O): G, R and S in edit mode, and G on
//! control points, also move the unselected neighbours within a radius,
//! each by the falloff of its distance to the selection
//! ([`hedra_geom::proportional`] has the curves). The wheel (or Page Up /
//! Page Down) changes the radius while a transform runs; the radius is
//! drawn as a circle around the pivot.

use crate::bindings::{Action, KeyMode, pressed};
use bevy::prelude::*;
use glam::DVec3;
use hedra_geom::proportional::Falloff;

/// Whether and how transforms move the selection's neighbours.
#[derive(Resource, Debug, Clone, Copy, PartialEq)]
pub struct Proportional {
    /// On (O toggles it in edit and control-point modes).
    pub enabled: bool,
    /// The influence curve (Shift+O cycles it).
    pub falloff: Falloff,
    /// The influence radius in world units.
    pub radius: f64,
    /// Measure along edges, so only geometry joined to the selection
    /// moves (Blender's "Connected Only").
    pub connected_only: bool,
}

impl Default for Proportional {
    fn default() -> Self {
        Proportional {
            enabled: false,
            falloff: Falloff::Smooth,
            radius: 1.0,
            connected_only: false,
        }
    }
}

impl Proportional {
    /// The smallest and largest radius the wheel reaches.
    pub const RADIUS_RANGE: (f64, f64) = (1e-3, 1e4);

    /// The wheel (up: larger) or Page Up / Page Down scale the radius by
    /// 10 % a notch; true when it changed.
    pub fn adjust_radius(&mut self, keys: &ButtonInput<KeyCode>, wheel: f32) -> bool {
        // Not `signum`: it is 1 for a still wheel (0.0).
        let notches = (wheel > 0.0) as i32 - (wheel < 0.0) as i32
            + pressed(keys, KeyMode::Tool, Action::LargerRadius) as i32
            - pressed(keys, KeyMode::Tool, Action::SmallerRadius) as i32;
        if notches == 0 {
            return false;
        }
        let (lo, hi) = Self::RADIUS_RANGE;
        self.radius = (self.radius * 1.1f64.powi(notches)).clamp(lo, hi);
        true
    }

    /// What the status bar says about the current settings.
    pub fn describe(&self) -> String {
        format!(
            "Proportional editing {} ({}, radius {:.3}{}; wheel changes the radius during G/R/S)",
            if self.enabled { "on" } else { "off" },
            self.falloff.label(),
            self.radius,
            if self.connected_only {
                ", connected only"
            } else {
                ""
            },
        )
    }
}

/// The running transform's influence circle (world centre and radius),
/// for drawing; `None` when no proportional transform runs.
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq)]
pub struct ProportionalRing(pub Option<(DVec3, f64)>);

/// O toggles proportional editing and Shift+O cycles the falloff, in edit
/// mode and control-point mode while no tool runs.
pub fn proportional_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<hedra_scene::InputGate>,
    mode: Res<crate::EditMode>,
    shapes: Res<crate::ShapeEdit>,
    mut proportional: ResMut<Proportional>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    let editing =
        (mode.active() && mode.tool.is_none()) || (shapes.active() && shapes.tool.is_none());
    let here = if mode.active() {
        KeyMode::Edit
    } else {
        KeyMode::ControlPoints
    };
    let cycle = pressed(&keys, here, Action::ProportionalFalloff);
    if !editing || !gate.keyboard_free {
        return;
    }
    if !cycle && !pressed(&keys, here, Action::Proportional) {
        return;
    }
    if cycle {
        let at = Falloff::ALL
            .iter()
            .position(|&f| f == proportional.falloff)
            .unwrap_or(0);
        proportional.falloff = Falloff::ALL[(at + 1) % Falloff::ALL.len()];
    } else {
        proportional.enabled = !proportional.enabled;
    }
    status.info(proportional.describe());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wheel_scales_the_radius_by_ten_percent_a_notch_within_range() {
        let keys = ButtonInput::<KeyCode>::default();
        let mut p = Proportional::default();
        assert!(!p.adjust_radius(&keys, 0.0));
        assert!(p.adjust_radius(&keys, 1.0));
        assert!((p.radius - 1.1).abs() < 1e-12);
        assert!(p.adjust_radius(&keys, -3.0));
        assert!((p.radius - 1.0).abs() < 1e-12, "{}", p.radius);
        p.radius = 1e-3;
        p.adjust_radius(&keys, -1.0);
        assert_eq!(p.radius, 1e-3);
    }
}
