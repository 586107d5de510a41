//! The modal transform tool, as in Blender: G moves, R rotates, S scales the
//! selected objects about their median; X/Y/Z constrain to a world axis
//! (press again to free); typing a number gives an exact amount; Enter or a
//! left click confirms as one undo step; Esc or a right click restores.

use crate::bindings::{Action, KeyMode};
use crate::{local_from_world, rotation_about};
use bevy::prelude::*;
use glam::{DMat4, DQuat, DVec3};
use hedra_doc::{Command, Document, NodeId, NodeRef, NodeTransform};
use hedra_scene::{DocRequest, DocState, PreviewSource, Previews, ToolPreview};

/// What a modal object transform does.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum TransformKind {
    /// Move (G).
    Grab,
    /// Rotate (R).
    Rotate,
    /// Scale (S).
    Scale,
}

/// A world axis a modal tool is locked to (the X, Y or Z key).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Axis {
    /// The world X axis.
    X,
    /// The world Y axis (up).
    Y,
    /// The world Z axis.
    Z,
}

impl Axis {
    /// How the status bar names it: Hedra is Y-up (Blender is Z-up), so Y
    /// says so.
    pub fn label(self) -> &'static str {
        match self {
            Axis::X => "X",
            Axis::Y => "Y (up)",
            Axis::Z => "Z",
        }
    }

    /// The axis as a world-space unit vector.
    pub fn vector(self) -> DVec3 {
        match self {
            Axis::X => DVec3::X,
            Axis::Y => DVec3::Y,
            Axis::Z => DVec3::Z,
        }
    }
}

/// The tool's state; `active` is `Some` while a G/R/S is running.
#[derive(Resource, Default, Debug)]
pub struct TransformTool {
    /// The running transform; `None` when no G/R/S is in progress.
    pub active: Option<ModalTransform>,
    /// Set on the frame a tool ended, so the confirming click selects nothing.
    pub just_finished: bool,
    /// Shift+D: start moving the copies as soon as they exist.
    pub grab_after_duplicate: bool,
}

#[derive(Clone, Debug)]
struct Item {
    id: NodeId,
    local: NodeTransform,
    world: DMat4,
    parent_world: DMat4,
}

/// A running G/R/S.
#[derive(Clone, Debug)]
pub struct ModalTransform {
    /// Move, rotate or scale.
    pub kind: TransformKind,
    /// The world axis locked with X / Y / Z; `None` when free (move in the view
    /// plane, rotate about the view axis, scale uniformly).
    pub axis: Option<Axis>,
    /// Digits typed so far (an exact distance, angle in degrees, or factor).
    pub typed: crate::typing::TypedNumber,
    start_cursor: Vec2,
    pivot: DVec3,
    pivot_screen: Vec2,
    items: Vec<Item>,
    /// What the status bar shows ("Move X 1.250").
    pub readout: String,
}

impl ModalTransform {
    /// The world point the tool moves, turns or scales about.
    pub fn pivot(&self) -> DVec3 {
        self.pivot
    }

    /// Starts a tool on the selected nodes; `None` without a selection or cursor.
    pub fn start(
        kind: TransformKind,
        doc: &Document,
        selection: &[NodeId],
        window: &Window,
        camera: &Camera,
        camera_transform: &GlobalTransform,
    ) -> Option<ModalTransform> {
        // Children of selected nodes move with their parent: skip them.
        let roots: Vec<NodeId> = selection
            .iter()
            .copied()
            .filter(|&id| {
                doc.node(id).is_some()
                    && !selection
                        .iter()
                        .any(|&other| other != id && doc.is_ancestor(other, id))
            })
            .collect();
        if roots.is_empty() {
            return None;
        }
        let items: Vec<Item> = roots
            .iter()
            .map(|&id| {
                let node = doc.node(id).expect("filtered above");
                Item {
                    id,
                    local: node.transform,
                    world: doc.world_matrix(id),
                    parent_world: node.parent.map_or(DMat4::IDENTITY, |p| doc.world_matrix(p)),
                }
            })
            .collect();
        let pivot = items
            .iter()
            .map(|i| i.world.w_axis.truncate())
            .sum::<DVec3>()
            / items.len() as f64;
        let start_cursor = window.cursor_position()?;
        let pivot_screen = camera
            .world_to_viewport(camera_transform, pivot.as_vec3())
            .unwrap_or(start_cursor);
        Some(ModalTransform {
            kind,
            axis: None,
            typed: Default::default(),
            start_cursor,
            pivot,
            pivot_screen,
            items,
            readout: String::new(),
        })
    }

    /// The same tool turning and scaling about `pivot` (world) instead of
    /// the selection's median (Blender's 3D cursor pivot).
    pub fn about(
        mut self,
        pivot: DVec3,
        camera: &Camera,
        camera_transform: &GlobalTransform,
    ) -> Self {
        self.pivot = pivot;
        self.pivot_screen = camera
            .world_to_viewport(camera_transform, pivot.as_vec3())
            .unwrap_or(self.start_cursor);
        self
    }

    /// New local transforms for the cursor position (window coordinates).
    pub fn compute(
        &mut self,
        cursor: Vec2,
        ray_at: impl Fn(Vec2) -> Option<(DVec3, DVec3)>,
        view_dir: DVec3,
        snapping: Option<&crate::Snapping>,
        snap: crate::MoveSnap,
    ) -> Vec<(NodeId, NodeTransform)> {
        let axis_name = self
            .axis
            .map_or(String::new(), |a| format!(" {}", a.label()));
        match self.kind {
            TransformKind::Grab => {
                let delta = if let Some(v) = self.typed.value() {
                    self.axis.unwrap_or(Axis::X).vector() * v
                } else {
                    snap.translation(
                        self.start_cursor,
                        cursor,
                        self.pivot,
                        view_dir,
                        self.axis,
                        &ray_at,
                    )
                };
                self.readout = format!(
                    "Move{axis_name} ({:.4}, {:.4}, {:.4})",
                    delta.x, delta.y, delta.z
                );
                let m = DMat4::from_translation(delta);
                self.items
                    .iter()
                    .map(|i| (i.id, local_from_world(i.parent_world, m * i.world)))
                    .collect()
            }
            TransformKind::Rotate => {
                let (turn, readout) = turn_or_scale(
                    true,
                    (self.start_cursor, cursor, self.pivot_screen),
                    self.pivot,
                    self.axis,
                    view_dir,
                    self.typed.value(),
                    snapping,
                );
                self.readout = readout.replacen("Rotate", &format!("Rotate{axis_name}"), 1);
                let m = turn(1.0);
                self.items
                    .iter()
                    .map(|i| {
                        let mut t = local_from_world(i.parent_world, m * i.world);
                        t.scale = i.local.scale; // keep the exact scale through the decomposition
                        (i.id, t)
                    })
                    .collect()
            }
            TransformKind::Scale => {
                let factor = self.typed.value().unwrap_or_else(|| {
                    let d0 = (self.start_cursor - self.pivot_screen).length().max(1.0);
                    let factor = ((cursor - self.pivot_screen).length() / d0) as f64;
                    snapping.map_or(factor, |s| {
                        crate::Snapping::round(true, factor, s.scale_step)
                    })
                });
                let f = match self.axis {
                    None => DVec3::splat(factor),
                    Some(a) => DVec3::ONE + a.vector() * (factor - 1.0),
                };
                self.readout = format!("Scale{axis_name} {factor:.4}");
                self.items
                    .iter()
                    .map(|i| {
                        let p = i.world.w_axis.truncate();
                        let moved = self.pivot + f * (p - self.pivot);
                        let translation = i.parent_world.inverse().transform_point3(moved);
                        (
                            i.id,
                            NodeTransform {
                                translation,
                                rotation: i.local.rotation,
                                scale: i.local.scale * f,
                            },
                        )
                    })
                    .collect()
            }
        }
    }
}

/// Runs the active tool: keys, preview as data, confirm or cancel.
#[allow(clippy::too_many_arguments)]
pub fn drive_transform_tool(
    mut tool: ResMut<TransformTool>,
    keys: Res<ButtonInput<KeyCode>>,
    strokes: Res<hedra_scene::Strokes>,
    buttons: Res<ButtonInput<MouseButton>>,
    viewport: hedra_scene::ViewportPointer,
    state: Res<DocState>,
    selection: Res<crate::Selection>,
    mut previews: ResMut<Previews>,
    mut requests: MessageWriter<DocRequest>,
    snapping: Res<crate::Snapping>,
    mut snap_target: ResMut<crate::SnapTarget>,
) {
    let (window, camera) = (viewport.window(), viewport.camera());
    tool.just_finished = false;
    let (cam, cam_t) = camera;
    if tool.grab_after_duplicate && tool.active.is_none() {
        tool.grab_after_duplicate = false;
        tool.active = ModalTransform::start(
            TransformKind::Grab,
            &state.session.doc,
            &selection.nodes,
            window,
            cam,
            cam_t,
        );
    }
    let Some(mut modal) = tool.active.take() else {
        Previews::clear(&mut previews, PreviewSource::TransformTool);
        return;
    };

    let modal_keys = ModalKeys {
        keys: &keys,
        buttons: &buttons,
    };
    if modal_keys.cancel() {
        Previews::clear(&mut previews, PreviewSource::TransformTool);
        tool.just_finished = true;
        return;
    }
    modal_keys.toggle_axis(&mut modal.axis);
    modal.typed.read(&strokes, true);
    let cursor = window.cursor_position().unwrap_or(modal.start_cursor);
    let view_dir = (cam_t.rotation() * Vec3::NEG_Z).as_dvec3();
    let ray_at = |p: Vec2| viewport.ray_at(p);
    let active = snapping.active(&keys);
    let snap = if modal.kind == TransformKind::Grab {
        // The moved nodes and their children are neither targets nor left
        // behind: their vertices (or origins) are the snap bases.
        let doc = &state.session.doc;
        let moving: Vec<NodeId> = modal.items.iter().flat_map(|i| doc.subtree(i.id)).collect();
        let scene = crate::SnapScene::of_document(doc, |id| !moving.contains(&id));
        let to_screen = |p: DVec3| cam.world_to_viewport(cam_t, p.as_vec3()).ok();
        crate::move_snap(
            &snapping,
            active,
            &scene,
            moving.iter().flat_map(|&id| node_points_in_world(doc, id)),
            cursor,
            ray_at(cursor),
            &to_screen,
            &mut snap_target,
        )
    } else {
        crate::MoveSnap::Free
    };
    let result = modal.compute(cursor, ray_at, view_dir, active.then_some(&*snapping), snap);
    if !modal.typed.is_empty() {
        modal.readout = format!("{} [{}]", modal.readout, modal.typed.as_str());
    }
    if modal_keys.confirm() {
        let changed: Vec<(NodeRef, NodeTransform)> = result
            .into_iter()
            .filter(|(id, t)| {
                state
                    .session
                    .doc
                    .node(*id)
                    .is_some_and(|n| n.transform != *t)
            })
            .map(|(id, t)| (NodeRef::from(id), t))
            .collect();
        // The command is applied this frame: the projection goes from the
        // preview straight to the result.
        Previews::clear(&mut previews, PreviewSource::TransformTool);
        if !changed.is_empty() {
            requests.write(DocRequest::Execute(Command::SetTransforms {
                nodes: changed,
            }));
        }
        tool.just_finished = true;
        return;
    }
    // Nodes made from a moved one (a revolution of a profile) follow it.
    let doc = &state.session.doc;
    let mut contents = std::collections::HashMap::new();
    for (id, t) in &result {
        if doc.dependents(*id).is_empty() {
            continue;
        }
        if let Some(mut moved) = doc.node(*id).cloned() {
            moved.transform = *t;
            for (dependent, content) in doc.remade_dependents(&moved) {
                if let Some(c) = hedra_scene::PreviewContent::of_shape(&content) {
                    contents.insert(dependent, c);
                }
            }
        }
    }
    Previews::show(
        &mut previews,
        PreviewSource::TransformTool,
        ToolPreview {
            transforms: result.into_iter().collect(),
            contents,
        },
    );
    tool.active = Some(modal);
}

/// The world transform of an R or S drag on points (mesh vertices, control
/// points) about `pivot`, as a function of the weight it is taken with (1:
/// in full; less for proportional neighbours), and the readout. R turns by
/// the pointer's angle about the pivot on screen (about the view axis, or
/// `axis`), S scales by the ratio of its distances from the pivot; a typed
/// value replaces the pointer; with `snapping` the angle goes in its angle
/// step and the factor in its scale step (Blender).
pub fn turn_or_scale(
    rotate: bool,
    (start_cursor, cursor, pivot_screen): (Vec2, Vec2, Vec2),
    pivot: DVec3,
    axis: Option<Axis>,
    view_dir: DVec3,
    typed: Option<f64>,
    snapping: Option<&crate::Snapping>,
) -> (Box<dyn Fn(f64) -> DMat4>, String) {
    if rotate {
        let degrees = typed.unwrap_or_else(|| {
            let a = (start_cursor - pivot_screen).to_angle();
            let b = (cursor - pivot_screen).to_angle();
            // Screen y points down: a clockwise drag on screen is a negative angle.
            let degrees = -((b - a) as f64).to_degrees();
            snapping.map_or(degrees, |s| {
                crate::Snapping::round(true, degrees, s.angle_step)
            })
        });
        let axis = axis.map_or(-view_dir, Axis::vector).normalize();
        (
            Box::new(move |w| {
                rotation_about(
                    pivot,
                    DQuat::from_axis_angle(axis, w * degrees.to_radians()),
                )
            }),
            format!("Rotate {degrees:.2}°"),
        )
    } else {
        let factor = typed.unwrap_or_else(|| {
            let d0 = (start_cursor - pivot_screen).length().max(1.0);
            let factor = ((cursor - pivot_screen).length() / d0) as f64;
            snapping.map_or(factor, |s| {
                crate::Snapping::round(true, factor, s.scale_step)
            })
        });
        let f = axis.map_or(DVec3::splat(factor), |a| {
            DVec3::ONE + a.vector() * (factor - 1.0)
        });
        (
            Box::new(move |w| {
                DMat4::from_translation(pivot)
                    * DMat4::from_scale(DVec3::ONE + (f - DVec3::ONE) * w)
                    * DMat4::from_translation(-pivot)
            }),
            format!("Scale {factor:.4}"),
        )
    }
}

/// A node's points in world space, the bases of an object snap: a mesh's
/// vertices, a curve's or surface's control points, else its origin.
fn node_points_in_world(doc: &hedra_doc::Document, id: NodeId) -> Vec<DVec3> {
    let Some(node) = doc.node(id) else {
        return Vec::new();
    };
    let world = doc.world_matrix(id);
    let local: Vec<DVec3> = match &node.content {
        hedra_doc::NodeContent::Mesh(m) => m.mesh.vertices().map(|v| m.mesh.position(v)).collect(),
        content => hedra_scene::control_points(content),
    };
    if local.is_empty() {
        vec![world.w_axis.truncate()]
    } else {
        local
            .into_iter()
            .map(|p| world.transform_point3(p))
            .collect()
    }
}

/// The keys every modal tool shares, as in Blender: Esc or a right click
/// cancels, X / Y / Z lock the tool to an axis (the same key again frees
/// it), Enter, Space or a left click confirms. The object transform tool,
/// the mesh tools and the control-point tools all read them here.
pub struct ModalKeys<'a> {
    /// This frame's keyboard state.
    pub keys: &'a ButtonInput<KeyCode>,
    /// This frame's mouse-button state.
    pub buttons: &'a ButtonInput<MouseButton>,
}

impl ModalKeys<'_> {
    /// True on the frame Esc or the right mouse button is pressed.
    pub fn cancel(&self) -> bool {
        self.pressed(Action::Cancel) || self.buttons.just_pressed(MouseButton::Right)
    }

    fn pressed(&self, action: Action) -> bool {
        crate::bindings::pressed(self.keys, KeyMode::Tool, action)
    }

    /// True on the frame Enter, Numpad Enter, Space or the left mouse button is pressed.
    pub fn confirm(&self) -> bool {
        self.pressed(Action::Confirm) || self.buttons.just_pressed(MouseButton::Left)
    }

    /// Locks `axis` to the axis whose key was pressed, or frees it when it
    /// was already locked there.
    pub fn toggle_axis(&self, axis: &mut Option<Axis>) {
        for (action, a) in [
            (Action::AxisX, Axis::X),
            (Action::AxisY, Axis::Y),
            (Action::AxisZ, Axis::Z),
        ] {
            if self.pressed(action) {
                *axis = if *axis == Some(a) { None } else { Some(a) };
            }
        }
    }
}
