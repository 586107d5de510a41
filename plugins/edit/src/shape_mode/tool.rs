//! The control-point tools of shape edit mode (G, R, S, W, E): each frame
//! the running tool decides its command on a copy of the document and
//! shows the result (with the nodes made from the edited one); Enter or a
//! click confirms it as one undo step, Esc or a right click cancels.

use std::collections::BTreeSet;

use bevy::prelude::*;
use glam::DVec3;
use hedra_doc::{Command, NodeContent, NodeRef};
use hedra_geom::curves::CurveEnd;
use hedra_scene::{DocRequest, DocState, StatusMessage};

use super::ShapeEdit;
use super::{control_points, control_weights};
use crate::modal::Axis;
use crate::typing::TypedNumber;

/// What a shape tool changes.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum ShapeToolKind {
    /// Move the selected control points (G).
    Move,
    /// Change the selected control points' weights (W); a typed number sets
    /// them all to it.
    Weight,
    /// Turn the selected control points about the pivot (R).
    Rotate,
    /// Scale the selected control points about the pivot (S).
    Scale,
    /// Add a point beyond the selected end of a curve, following the
    /// pointer like a move (E, Blender's curve extrude).
    Extrude(CurveEnd),
}

/// A running shape tool.
#[derive(Clone, Debug)]
pub struct ShapeTool {
    /// Which tool runs.
    pub kind: ShapeToolKind,
    /// The world axis locked with X / Y / Z (move only); `None` when free.
    pub axis: Option<Axis>,
    /// Digits typed so far: when they form a number, it replaces the mouse (a
    /// world distance along the axis, or the new weight).
    pub typed: TypedNumber,
    pub(crate) start_cursor: Vec2,
    /// World-space centre of the selected points (the drag plane goes
    /// through it; R and S turn and scale about it, or about the 3D cursor).
    pub(crate) pivot: DVec3,
    /// Where the pivot is on screen (R measures the pointer's angle about it).
    pub(crate) pivot_screen: Vec2,
    /// What the status bar shows for the tool, with the typed digits or the
    /// reason the command cannot apply appended.
    pub readout: String,
}

/// Runs the shape tool: preview each frame, confirm or cancel.
#[allow(clippy::too_many_arguments)]
pub fn drive_shape_tool(
    keys: Res<ButtonInput<KeyCode>>,
    strokes: Res<hedra_scene::Strokes>,
    buttons: Res<ButtonInput<MouseButton>>,
    mut edit: ResMut<ShapeEdit>,
    state: Res<DocState>,
    viewport: hedra_scene::ViewportPointer,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<StatusMessage>,
    snapping: Res<crate::Snapping>,
    scroll: Res<bevy::input::mouse::AccumulatedMouseScroll>,
    mut proportional: ResMut<crate::Proportional>,
    mut ring: ResMut<crate::ProportionalRing>,
    mut snap_target: ResMut<crate::SnapTarget>,
    mut previews: ResMut<hedra_scene::Previews>,
) {
    // The tool's step for this frame; then its slot in the previews
    // shows what it decided (cleared when no tool runs).
    (|| {
        let (window, camera) = (viewport.window(), viewport.camera());
        // The ring and the snap target are cleared each frame by
        // `clear_tool_overlays`, which runs first.
        let (Some(id), Some(mut tool)) = (edit.node, edit.tool.take()) else {
            return;
        };
        let Some(node) = state.session.doc.node(id) else {
            return;
        };
        let modal_keys = crate::modal::ModalKeys {
            keys: &keys,
            buttons: &buttons,
        };
        if modal_keys.cancel() {
            edit.preview = None;
            edit.just_finished = true;
            return;
        }
        if tool.kind != ShapeToolKind::Weight {
            modal_keys.toggle_axis(&mut tool.axis);
        }
        tool.typed.read(&strokes, true);
        let cursor = window.cursor_position().unwrap_or(tool.start_cursor);
        let world = state.session.doc.world_matrix(id);
        let (cam, cam_t) = camera;
        let points = control_points(&node.content);
        let reference = NodeRef::from(id);
        let cmd = match tool.kind {
            ShapeToolKind::Move | ShapeToolKind::Extrude(_) => {
                let view_dir = (cam_t.rotation() * Vec3::NEG_Z).as_dvec3();
                let ray_at = |p: Vec2| viewport.ray_at(p);
                // Snapping: onto the shape's other control points and onto
                // every other node's vertices, edges, faces and control points.
                let doc = &state.session.doc;
                let mut scene = crate::SnapScene::of_document(doc, |other| other != id);
                let world_point = |i: usize| world.transform_point3(points[i]);
                scene.points.extend(
                    (0..points.len())
                        .filter(|&i| !edit.selected.contains(&(i as u32)))
                        .map(world_point),
                );
                let to_screen = |p: DVec3| cam.world_to_viewport(cam_t, p.as_vec3()).ok();
                let snap = crate::move_snap(
                    &snapping,
                    snapping.active(&keys),
                    &scene,
                    edit.selected.iter().map(|&i| world_point(i as usize)),
                    cursor,
                    ray_at(cursor),
                    &to_screen,
                    &mut snap_target,
                );
                let world_delta = match tool.typed.value() {
                    Some(v) => tool.axis.unwrap_or(Axis::X).vector() * v,
                    None => snap.translation(
                        tool.start_cursor,
                        cursor,
                        tool.pivot,
                        view_dir,
                        tool.axis,
                        &ray_at,
                    ),
                };
                let local = world.inverse().transform_vector3(world_delta);
                if let ShapeToolKind::Extrude(end) = tool.kind {
                    let from = match end {
                        CurveEnd::Start => points[0],
                        CurveEnd::End => points[points.len() - 1],
                    };
                    tool.readout = format!(
                        "Extrude curve ({:.4}, {:.4}, {:.4})",
                        world_delta.x, world_delta.y, world_delta.z
                    );
                    Command::ExtrudeCurve {
                        node: reference,
                        end,
                        to: from + local,
                    }
                } else {
                    tool.readout = format!(
                        "Move control points ({:.4}, {:.4}, {:.4})",
                        world_delta.x, world_delta.y, world_delta.z
                    );
                    let mut moved: Vec<(u32, DVec3)> = edit
                        .selected
                        .iter()
                        .map(|&i| (i, points[i as usize] + local))
                        .collect();
                    // Proportional editing: the other points by their falloff
                    // weights, from world distances.
                    if proportional.enabled {
                        proportional.adjust_radius(&keys, scroll.delta.y);
                        ring.0 = Some((tool.pivot, proportional.radius));
                        let world_points: Vec<DVec3> =
                            points.iter().map(|&p| world.transform_point3(p)).collect();
                        let selected: Vec<usize> =
                            edit.selected.iter().map(|&i| i as usize).collect();
                        let weights = hedra_geom::proportional::point_weights(
                            &world_points,
                            &selected,
                            proportional.radius,
                            proportional.falloff,
                        );
                        moved.extend(
                            weights
                                .into_iter()
                                .map(|(i, w)| (i as u32, points[i] + local * w)),
                        );
                        tool.readout = format!(
                            "{} · proportional {} radius {:.3} (wheel)",
                            tool.readout,
                            proportional.falloff.label(),
                            proportional.radius
                        );
                    }
                    Command::SetControlPoints {
                        node: reference,
                        points: moved,
                    }
                }
            }
            ShapeToolKind::Rotate | ShapeToolKind::Scale => {
                let view_dir = (cam_t.rotation() * Vec3::NEG_Z).as_dvec3();
                let (xf, readout) = crate::modal::turn_or_scale(
                    tool.kind == ShapeToolKind::Rotate,
                    (tool.start_cursor, cursor, tool.pivot_screen),
                    tool.pivot,
                    tool.axis,
                    view_dir,
                    tool.typed.value(),
                    snapping.active(&keys).then_some(&*snapping),
                );
                tool.readout = format!("{readout} (control points)");
                let to_local = world.inverse();
                let moved = |i: usize, w: f64| {
                    to_local
                        .transform_point3(xf(w).transform_point3(world.transform_point3(points[i])))
                };
                let mut new: Vec<(u32, DVec3)> = edit
                    .selected
                    .iter()
                    .map(|&i| (i, moved(i as usize, 1.0)))
                    .collect();
                if proportional.enabled {
                    proportional.adjust_radius(&keys, scroll.delta.y);
                    ring.0 = Some((tool.pivot, proportional.radius));
                    let world_points: Vec<DVec3> =
                        points.iter().map(|&p| world.transform_point3(p)).collect();
                    let selected: Vec<usize> = edit.selected.iter().map(|&i| i as usize).collect();
                    let weights = hedra_geom::proportional::point_weights(
                        &world_points,
                        &selected,
                        proportional.radius,
                        proportional.falloff,
                    );
                    new.extend(weights.into_iter().map(|(i, w)| (i as u32, moved(i, w))));
                }
                Command::SetControlPoints {
                    node: reference,
                    points: new,
                }
            }
            ShapeToolKind::Weight => {
                let weights = control_weights(&node.content).unwrap_or_default();
                // 150 pixels to the right multiply the weights by e; left divides.
                let factor = (((cursor - tool.start_cursor).x) as f64 / 150.0).exp();
                let new: Vec<(u32, f64)> = edit
                    .selected
                    .iter()
                    .map(|&i| {
                        (
                            i,
                            tool.typed.value().unwrap_or(weights[i as usize] * factor),
                        )
                    })
                    .collect();
                tool.readout = match new.as_slice() {
                    [(i, w)] => format!("Weight of point {i}: {w:.4}"),
                    _ => format!("Weights × {factor:.4}"),
                };
                Command::SetWeights {
                    node: reference,
                    weights: new,
                }
            }
        };
        if !tool.typed.is_empty() {
            tool.readout = format!("{} [{}]", tool.readout, tool.typed.as_str());
        }
        let decided = state.session.doc.decide(&cmd, 0);
        match &decided {
            Ok(t) => {
                edit.preview = t
                    .changes
                    .iter()
                    .find(|c| c.id == id)
                    .and_then(|c| c.after.as_ref())
                    .map(|n| n.content.clone());
                edit.dependents = t
                    .changes
                    .iter()
                    .filter(|c| c.id != id)
                    .filter_map(|c| Some((c.id, c.after.as_ref()?.content.clone())))
                    .collect();
            }
            Err(e) => {
                edit.preview = None;
                edit.dependents.clear();
                tool.readout = format!("{} — {e}", tool.readout);
            }
        }
        if modal_keys.confirm() {
            match decided {
                Ok(_) => {
                    // The extruded point is selected, ready for the next E.
                    if let (ShapeToolKind::Extrude(end), Some(NodeContent::Curve(c))) =
                        (tool.kind, &edit.preview)
                    {
                        let new_point = match end {
                            CurveEnd::Start => 0,
                            CurveEnd::End => c.control_points().len() as u32 - 1,
                        };
                        edit.selected = BTreeSet::from([new_point]);
                    }
                    requests.write(DocRequest::Execute(cmd));
                    edit.preview = None;
                    edit.just_finished = true;
                    return;
                }
                Err(e) => status.error(format!("{e}")),
            }
        }
        edit.tool = Some(tool);
    })();
    show_shape_tool_preview(&edit, &mut previews);
}

/// Puts the running control-point tool's result (`ShapeEdit::preview`)
/// into its [`Previews`](hedra_scene::Previews) slot, and clears the slot
/// when the tool ends; called by [`drive_shape_tool`] after each step. The
/// projection re-tessellates only the knot spans whose control points
/// changed.
fn show_shape_tool_preview(edit: &ResMut<ShapeEdit>, previews: &mut ResMut<hedra_scene::Previews>) {
    use hedra_scene::{PreviewContent, PreviewSource, Previews, ToolPreview};
    if !edit.is_changed() {
        return;
    }
    let content = edit
        .preview
        .as_ref()
        .and_then(PreviewContent::of_shape)
        .zip(edit.node);
    match content {
        Some((content, node)) => Previews::show(
            previews,
            PreviewSource::ShapeTool,
            ToolPreview {
                contents: std::iter::once((node, content))
                    .chain(
                        edit.dependents
                            .iter()
                            .filter_map(|(id, c)| Some((*id, PreviewContent::of_shape(c)?))),
                    )
                    .collect(),
                ..default()
            },
        ),
        None => Previews::clear(previews, PreviewSource::ShapeTool),
    }
}
