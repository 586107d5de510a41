//! The orbit camera (Blender-style turntable), framing the selection or everything.

use crate::*;
use bevy::window::PrimaryWindow;

/// Orbit camera state (Blender-style: turntable around a focus point).
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct OrbitCamera {
    /// The point orbited and zoomed towards, in world space (Shift+middle
    /// drag pans it; framing moves it to the centre of the framed bounds).
    pub focus: Vec3,
    /// Turn about the world Y axis, in radians.
    pub yaw: f32,
    /// Tilt about the camera's X axis, in radians, kept inside ±π/2;
    /// negative looks down from above.
    pub pitch: f32,
    /// Eye-to-focus distance in world units (the wheel zooms it); in
    /// orthographic view it also sets the visible height.
    pub distance: f32,
    /// Numpad 5: parallel projection instead of perspective.
    pub orthographic: bool,
}

impl Default for OrbitCamera {
    fn default() -> Self {
        OrbitCamera {
            focus: Vec3::ZERO,
            yaw: 0.75,
            pitch: -0.5,
            distance: 12.0,
            orthographic: false,
        }
    }
}

/// The perspective's vertical field of view (Bevy's default).
const FOV: f32 = std::f32::consts::FRAC_PI_4;

impl OrbitCamera {
    /// The projection: perspective, or parallel with the height the
    /// perspective shows at the focus (so Numpad 5 keeps the framing and
    /// the wheel still zooms).
    pub fn projection(&self) -> Projection {
        if !self.orthographic {
            return Projection::Perspective(PerspectiveProjection {
                fov: FOV,
                ..default()
            });
        }
        Projection::Orthographic(OrthographicProjection {
            scaling_mode: bevy::camera::ScalingMode::FixedVertical {
                viewport_height: 2.0 * self.distance * (FOV / 2.0).tan(),
            },
            // Everything along the view line is seen, in front of the eye
            // or behind it.
            near: -1e4,
            far: 1e4,
            ..OrthographicProjection::default_3d()
        })
    }

    /// The camera's transform: at `distance` from `focus`, looking at it.
    pub fn transform(&self) -> Transform {
        let rotation = Quat::from_euler(EulerRot::YXZ, self.yaw, self.pitch, 0.0);
        Transform {
            translation: self.focus + rotation * Vec3::Z * self.distance,
            rotation,
            scale: Vec3::ONE,
        }
    }
}

pub(crate) fn spawn_camera(mut commands: Commands) {
    let orbit = OrbitCamera::default();
    commands.spawn((
        Camera3d::default(),
        ViewportCamera,
        TransformGizmoCamera,
        orbit,
        orbit.transform(),
        Tonemapping::TonyMcMapface,
        Msaa::Sample4,
        children![(
            // A headlight slightly above and left of the eye, like a studio key light.
            DirectionalLight {
                illuminance: 6_000.0,
                ..default()
            },
            Transform::from_xyz(-2.0, 3.0, 4.0).looking_at(Vec3::ZERO, Vec3::Y),
        )],
    ));
}

/// Bevy's transform gizmo renders through a second 3D camera; it must draw
/// over the viewport, not clear it.
pub(crate) fn overlay_cameras_keep_the_picture(
    mut cameras: Query<&mut Camera, (With<Camera3d>, Without<ViewportCamera>)>,
) {
    for mut c in &mut cameras {
        c.clear_color = ClearColorConfig::None;
    }
}

/// Middle mouse orbits, Shift+middle pans, Ctrl+middle or the wheel zooms,
/// Alt+left orbits (trackpads); numpad 1/3/7 give front/right/top views,
/// numpad 5 switches between perspective and orthographic (Blender).
#[allow(clippy::too_many_arguments)]
pub(crate) fn camera_controls(
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    scroll: Res<AccumulatedMouseScroll>,
    gate: Res<InputGate>,
    tool: Res<TransformTool>,
    (mode, shape_edit): (Res<hedra_edit::EditMode>, Res<hedra_edit::ShapeEdit>),
    window: Single<&Window, With<PrimaryWindow>>,
    mut last_cursor: Local<Option<Vec2>>,
    mut dragging: Local<bool>,
    mut projected: Local<Option<(bool, Option<f32>)>>,
    mut camera: Single<(&mut OrbitCamera, &mut Transform, &mut Projection), With<ViewportCamera>>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    let (orbit, transform, projection) = &mut *camera;
    let alt = modifiers::alt(&keys);
    let shift = modifiers::shift(&keys);
    let ctrl = modifiers::ctrl(&keys);
    let drag_button =
        buttons.pressed(MouseButton::Middle) || (alt && buttons.pressed(MouseButton::Left));
    let drag_start = buttons.just_pressed(MouseButton::Middle)
        || (alt && buttons.just_pressed(MouseButton::Left));
    if drag_start && gate.pointer_free && tool.active.is_none() {
        *dragging = true;
    }
    if !drag_button {
        *dragging = false;
    }
    // Orbit and pan follow the pointer's position, not raw device motion:
    // tablets, remote desktops and synthetic input move the pointer to
    // absolute positions and send no motion at all.
    let cursor = window.cursor_position();
    let delta = match (cursor, *last_cursor) {
        (Some(now), Some(before)) => now - before,
        _ => Vec2::ZERO,
    };
    *last_cursor = cursor;
    if *dragging && delta != Vec2::ZERO {
        if shift {
            let scale = orbit.distance * 0.0015;
            let right = transform.rotation * Vec3::X;
            let up = transform.rotation * Vec3::Y;
            orbit.focus += (-right * delta.x + up * delta.y) * scale;
        } else if ctrl {
            orbit.distance = (orbit.distance * (1.0 + delta.y * 0.01)).clamp(0.01, 1e5);
        } else {
            orbit.yaw -= delta.x * 0.008;
            orbit.pitch =
                (orbit.pitch - delta.y * 0.008).clamp(-FRAC_PI_2 + 0.001, FRAC_PI_2 - 0.001);
        }
    }
    // A running tool owns the wheel (loop cut's count, the proportional
    // radius): the view does not zoom under it.
    let tool_running = hedra_edit::modal_tool_running(&tool, &mode, &shape_edit);
    if gate.pointer_free && !tool_running && scroll.delta.y != 0.0 {
        let lines = match scroll.unit {
            MouseScrollUnit::Line => scroll.delta.y,
            MouseScrollUnit::Pixel => scroll.delta.y / 40.0,
        };
        orbit.distance = (orbit.distance * 0.88f32.powf(lines)).clamp(0.01, 1e5);
    }
    if gate.keyboard_free && tool.active.is_none() {
        use hedra_edit::bindings::{Action, KeyMode, pressed};
        let pressed = |action| pressed(&keys, KeyMode::Everywhere, action);
        let flip = std::f32::consts::PI;
        let view = [
            (Action::ViewFront, 0.0, 0.0),
            (Action::ViewBack, flip, 0.0),
            (Action::ViewRight, FRAC_PI_2, 0.0),
            (Action::ViewLeft, FRAC_PI_2 + flip, 0.0),
            (Action::ViewTop, 0.0, -FRAC_PI_2 + 0.001),
            (Action::ViewBottom, 0.0, FRAC_PI_2 - 0.001),
        ]
        .into_iter()
        .find(|&(action, _, _)| pressed(action));
        if let Some((_, yaw, pitch)) = view {
            (orbit.yaw, orbit.pitch) = (yaw, pitch);
        }
        if pressed(Action::Orthographic) {
            orbit.orthographic = !orbit.orthographic;
            status.info(if orbit.orthographic {
                "View: orthographic (Numpad 5 for perspective)"
            } else {
                "View: perspective (Numpad 5 for orthographic)"
            });
        }
    }
    let wanted = orbit.transform();
    if **transform != wanted {
        **transform = wanted;
    }
    // The projection follows the mode and, when parallel, the zoom.
    let key = (
        orbit.orthographic,
        orbit.orthographic.then_some(orbit.distance),
    );
    if *projected != Some(key) {
        *projected = Some(key);
        **projection = orbit.projection();
    }
}

/// World-space bounds of the given nodes' meshes (or positions for empties).
pub fn world_bounds(
    state: &DocState,
    ids: impl IntoIterator<Item = hedra_doc::NodeId>,
) -> Option<(DVec3, DVec3)> {
    let doc = &state.session.doc;
    let mut acc: Option<(DVec3, DVec3)> = None;
    let mut add = |p: DVec3| {
        acc = Some(acc.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))));
    };
    for id in ids {
        let world = doc.world_matrix(id);
        let bounds = match doc.node(id).map(|n| &n.content) {
            Some(NodeContent::Mesh(m)) => m.mesh.bounds(),
            Some(NodeContent::Kept(k)) => k.mesh.bounds(),
            _ => None,
        };
        match doc.node(id).map(|n| &n.content) {
            Some(NodeContent::Mesh(_) | NodeContent::Kept(_)) => {
                if let Some((lo, hi)) = bounds {
                    for i in 0..8 {
                        let c = DVec3::new(
                            if i & 1 == 0 { lo.x } else { hi.x },
                            if i & 2 == 0 { lo.y } else { hi.y },
                            if i & 4 == 0 { lo.z } else { hi.z },
                        );
                        add(world.transform_point3(c));
                    }
                }
            }
            Some(_) => add(world.w_axis.truncate()),
            None => {}
        }
    }
    acc
}

/// F or Numpad . frames the selection, Home frames everything.
pub(crate) fn frame_selection(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    tool: Res<TransformTool>,
    selection: Res<Selection>,
    state: Res<DocState>,
    mut camera: Single<&mut OrbitCamera, With<ViewportCamera>>,
    mode: Res<EditMode>,
) {
    if !gate.keyboard_free || tool.active.is_some() {
        return;
    }
    use hedra_edit::bindings::{Action, KeyMode, pressed};
    // In edit mode F fills holes; Numpad . still frames.
    let bounds = if (!mode.active() && pressed(&keys, KeyMode::Object, Action::FrameSelected))
        || pressed(&keys, KeyMode::Everywhere, Action::FrameSelected)
    {
        if selection.nodes.is_empty() {
            world_bounds(&state, state.session.doc.nodes().map(|n| n.id))
        } else {
            world_bounds(&state, selection.nodes.iter().copied())
        }
    } else if pressed(&keys, KeyMode::Everywhere, Action::FrameAll) {
        world_bounds(&state, state.session.doc.nodes().map(|n| n.id))
    } else {
        return;
    };
    if let Some((lo, hi)) = bounds {
        camera.focus = ((lo + hi) * 0.5).as_vec3();
        let radius = ((hi - lo).length() * 0.5).max(0.1) as f32;
        camera.distance = radius / (22.5f32.to_radians()).sin() * 1.1;
    }
}

/// One of quad view's three fixed orthographic views.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub enum QuadViewCamera {
    /// Looking down −Y (Numpad 7's view).
    Top,
    /// Looking along −Z (Numpad 1's view).
    Front,
    /// Looking along −X (Numpad 3's view).
    Right,
}

impl QuadViewCamera {
    /// The three, in the quadrants top-left, top-right, bottom-left (the
    /// perspective viewport takes bottom-right, as in Blender).
    pub const ALL: [QuadViewCamera; 3] = [
        QuadViewCamera::Top,
        QuadViewCamera::Front,
        QuadViewCamera::Right,
    ];

    /// The name painted in its corner.
    pub fn label(self) -> &'static str {
        match self {
            QuadViewCamera::Top => "Top",
            QuadViewCamera::Front => "Front",
            QuadViewCamera::Right => "Right",
        }
    }

    /// The orbit camera's yaw and pitch for this view.
    fn angles(self) -> (f32, f32) {
        use std::f32::consts::FRAC_PI_2;
        match self {
            QuadViewCamera::Top => (0.0, -FRAC_PI_2 + 1e-4),
            QuadViewCamera::Front => (0.0, 0.0),
            QuadViewCamera::Right => (FRAC_PI_2, 0.0),
        }
    }
}

/// The three quad-view cameras, inactive until Ctrl+Alt+Q; they draw after
/// the main camera, into their own quarters of the viewport.
pub(crate) fn spawn_quad_cameras(mut commands: Commands) {
    for (i, view) in QuadViewCamera::ALL.into_iter().enumerate() {
        commands.spawn((
            Camera3d::default(),
            Camera {
                is_active: false,
                order: 1 + i as isize,
                ..default()
            },
            view,
            Tonemapping::TonyMcMapface,
            Msaa::Sample4,
        ));
    }
}

/// Ctrl+Alt+Q toggles quad view (Blender); the View menu too.
pub(crate) fn quad_view_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut quad: ResMut<hedra_scene::QuadView>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    use hedra_edit::bindings::{Action, KeyMode, pressed};
    if gate.keyboard_free && pressed(&keys, KeyMode::Everywhere, Action::QuadView) {
        quad.0 = !quad.0;
        status.info(if quad.0 {
            "Quad view: top, front and right (orthographic) beside the perspective view, which takes the input (Ctrl+Alt+Q: one view)"
        } else {
            "One view (Ctrl+Alt+Q: quad view)"
        });
    }
}

/// The quad-view cameras follow the main camera's focus and zoom, each
/// looking along its axis in orthographic projection; active only in quad
/// view.
pub(crate) fn follow_quad_cameras(
    quad: Res<hedra_scene::QuadView>,
    main: Single<&OrbitCamera, With<ViewportCamera>>,
    mut cameras: Query<(
        &QuadViewCamera,
        &mut Camera,
        &mut Transform,
        &mut Projection,
    )>,
) {
    for (view, mut camera, mut transform, mut projection) in &mut cameras {
        if camera.is_active != quad.0 {
            camera.is_active = quad.0;
        }
        if !quad.0 {
            continue;
        }
        let (yaw, pitch) = view.angles();
        let orbit = OrbitCamera {
            yaw,
            pitch,
            orthographic: true,
            ..**main
        };
        let t = orbit.transform();
        if *transform != t {
            *transform = t;
        }
        // Written only when the zoom changed (or on the first frame).
        let height = |p: &Projection| match p {
            Projection::Orthographic(o) => match o.scaling_mode {
                bevy::camera::ScalingMode::FixedVertical { viewport_height } => {
                    Some(viewport_height)
                }
                _ => None,
            },
            _ => None,
        };
        let p = orbit.projection();
        if height(&projection) != height(&p) {
            *projection = p;
        }
    }
}
