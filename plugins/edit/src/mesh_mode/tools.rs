//! The running mesh tool: the command the mouse and typed value ask for, decided on a copy each frame as a preview, confirmed or cancelled.

use super::*;
use crate::bindings::{Action, KeyMode};

/// The command a tool would run for the cursor position.
pub(super) fn tool_command(
    tool: &mut MeshTool,
    node: NodeRef,
    mesh: &HalfEdgeMesh,
    selection: &ElementSelection,
    world: DMat4,
    cursor: Vec2,
    ray_at: &dyn Fn(Vec2) -> Option<(DVec3, DVec3)>,
    view_dir: DVec3,
    pixel_size: f64,
    snap: crate::MoveSnap,
    steps: Option<&crate::Snapping>,
    proportional: Option<&BTreeMap<VertexId, f64>>,
) -> Command {
    let drag = (cursor - tool.start_cursor).x as f64 * pixel_size;
    let faces = || FaceSet::Ids(selection.faces.iter().map(|f| f.0).collect());
    match tool.kind {
        MeshToolKind::Move | MeshToolKind::ExtrudeEdges => {
            let world_delta = match tool.typed.value() {
                Some(v) => tool.axis.unwrap_or(Axis::X).vector() * v,
                None => snap.translation(
                    tool.start_cursor,
                    cursor,
                    tool.pivot,
                    view_dir,
                    tool.axis,
                    ray_at,
                ),
            };
            let verb = if tool.kind == MeshToolKind::Move {
                "Move"
            } else {
                "Extrude edges"
            };
            tool.readout = format!(
                "{verb} ({:.4}, {:.4}, {:.4})",
                world_delta.x, world_delta.y, world_delta.z
            );
            let offset = world.inverse().transform_vector3(world_delta);
            if let Some(weights) = proportional.filter(|_| tool.kind == MeshToolKind::Move) {
                let positions = weighted_positions(mesh, selection, world, weights, &|p, w| {
                    p + world_delta * w
                });
                return Command::SetVertexPositions { node, positions };
            }
            if tool.kind == MeshToolKind::ExtrudeEdges {
                let edges = EdgeSet::Ids(selection.edges.iter().map(|e| e.0).collect());
                return Command::ExtrudeEdges {
                    node,
                    edges,
                    offset,
                };
            }
            let vertices = selection
                .all_vertices(mesh)
                .into_iter()
                .map(|v| v.0)
                .collect();
            Command::MoveVertices {
                node,
                vertices: VertexSet::Ids(vertices),
                offset,
            }
        }
        MeshToolKind::Bevel => {
            let width = tool.typed.value().unwrap_or(drag.abs());
            let segments = tool.cuts;
            tool.readout = format!("Bevel width {width:.4}, {segments} segment(s) (wheel or +/-)");
            Command::BevelEdges {
                node,
                edges: EdgeSet::Ids(selection.edges.iter().map(|e| e.0).collect()),
                width,
                segments,
            }
        }
        MeshToolKind::BevelVertices => {
            let width = tool.typed.value().unwrap_or(drag.abs());
            tool.readout = format!("Vertex bevel width {width:.4}");
            Command::BevelVertices {
                node,
                vertices: VertexSet::Ids(selection.vertices.iter().map(|v| v.0).collect()),
                width,
            }
        }
        MeshToolKind::Crease => {
            // 100 pixels to the right add one level of sharpness.
            let sharpness = tool
                .typed
                .value()
                .unwrap_or(tool.start_value + ((cursor - tool.start_cursor).x / 100.0) as f64)
                .clamp(0.0, 10.0);
            let what = if selection.vertices.is_empty() || !selection.edges.is_empty() {
                "Edge crease"
            } else {
                "Vertex corner sharpness"
            };
            tool.readout = format!("{what} {sharpness:.2} (0 smooth … 10 sharp)");
            if what == "Edge crease" {
                Command::SetEdgeCrease {
                    node,
                    edges: EdgeSet::Ids(selection.edges.iter().map(|e| e.0).collect()),
                    sharpness,
                }
            } else {
                Command::SetVertexCrease {
                    node,
                    vertices: VertexSet::Ids(selection.vertices.iter().map(|v| v.0).collect()),
                    sharpness,
                }
            }
        }
        MeshToolKind::SlideEdges => {
            // 300 pixels to the right slide all the way to one side, to the left the other.
            let factor = tool
                .typed
                .value()
                .unwrap_or(((cursor - tool.start_cursor).x / 300.0) as f64)
                .clamp(-1.0, 1.0);
            tool.readout = format!("Edge slide {factor:.3}");
            Command::SlideEdges {
                node,
                edges: EdgeSet::Ids(selection.edges.iter().map(|e| e.0).collect()),
                factor,
            }
        }
        MeshToolKind::Rotate | MeshToolKind::Scale => {
            // The world-space transform taken with weight `w` (1: in full).
            let (xf, readout) = crate::modal::turn_or_scale(
                tool.kind == MeshToolKind::Rotate,
                (tool.start_cursor, cursor, tool.pivot_screen),
                tool.pivot,
                tool.axis,
                view_dir,
                tool.typed.value(),
                steps,
            );
            tool.readout = readout;
            if let Some(weights) = proportional {
                let positions = weighted_positions(mesh, selection, world, weights, &|p, w| {
                    xf(w).transform_point3(p)
                });
                return Command::SetVertexPositions { node, positions };
            }
            // The world-space transform, applied to mesh-space positions.
            let local = world.inverse() * xf(1.0) * world;
            let positions = selection
                .all_vertices(mesh)
                .into_iter()
                .map(|v| (v.0, local.transform_point3(mesh.position(v))))
                .collect();
            Command::SetVertexPositions { node, positions }
        }
        MeshToolKind::Extrude | MeshToolKind::ExtrudeIndividual => {
            // The faces follow the cursor along their normal, as in Blender;
            // sideways drag only when the normal points at the viewer.
            let distance = tool.typed.value().unwrap_or_else(|| {
                let faces: Vec<FaceId> = selection.faces.iter().copied().collect();
                // The local unit normal carried into the world: the line's
                // parameter then counts the local distance the command takes.
                let line = (
                    tool.pivot,
                    world.transform_vector3(mesh.region_normal(&faces)),
                );
                let along = |p: Vec2| line_parameter_nearest_ray(line, ray_at(p)?);
                match (along(tool.start_cursor), along(cursor)) {
                    (Some(a), Some(b)) => b - a,
                    _ => drag,
                }
            });
            tool.readout = format!("Extrude {distance:.4}");
            if tool.kind == MeshToolKind::Extrude {
                Command::ExtrudeRegion {
                    node,
                    faces: faces(),
                    distance,
                }
            } else {
                Command::ExtrudeFaces {
                    node,
                    faces: faces(),
                    distance,
                }
            }
        }
        MeshToolKind::Inset | MeshToolKind::InsetIndividual => {
            let thickness = tool.typed.value().unwrap_or(drag.abs());
            tool.readout = format!("Inset thickness {thickness:.4}");
            if tool.kind == MeshToolKind::Inset {
                Command::InsetRegion {
                    node,
                    faces: faces(),
                    thickness,
                    depth: 0.0,
                }
            } else {
                Command::InsetFaces {
                    node,
                    faces: faces(),
                    thickness,
                    depth: 0.0,
                }
            }
        }
        MeshToolKind::SplitVertex => {
            let v = *selection.vertices.first().expect("one vertex to split");
            // The new vertex goes where the pointer is, on the view plane
            // through the vertex (snapped like a move).
            let world_delta = match tool.typed.value() {
                Some(d) => tool.axis.unwrap_or(Axis::X).vector() * d,
                None => snap.translation(
                    tool.pivot_screen,
                    cursor,
                    tool.pivot,
                    view_dir,
                    tool.axis,
                    ray_at,
                ),
            };
            let (first, last) = split_side(mesh, v, world.inverse().transform_vector3(world_delta));
            tool.readout = format!(
                "Split vertex: new vertex at ({:.4}, {:.4}, {:.4}) from it; the edges on the pointer's side follow",
                world_delta.x, world_delta.y, world_delta.z
            );
            Command::SplitVertex {
                node,
                vertex: VertexSet::Ids(vec![v.0]),
                first: VertexSet::Ids(vec![first.0]),
                last: VertexSet::Ids(vec![last.0]),
                position: world
                    .inverse()
                    .transform_point3(world.transform_point3(mesh.position(v)) + world_delta),
            }
        }
        MeshToolKind::LoopCut => {
            let cuts = tool
                .typed
                .value()
                .map_or(tool.cuts, |v| v.round().clamp(1.0, 64.0) as u32);
            tool.readout = format!("Loop cut: {cuts} cut(s) (wheel or +/- to change)");
            Command::LoopCut {
                node,
                edge: EdgeSet::Ids(vec![tool.edge.expect("loop cut has an edge").0]),
                cuts,
            }
        }
    }
}

/// The first and last neighbour, in fan order, of the edges of `v` that a
/// vertex split towards `towards` (local) moves to the new vertex: the
/// longest run of consecutive edges that point the same way as `towards`,
/// never all of them; the one edge pointing most that way when none does.
fn split_side(mesh: &HalfEdgeMesh, v: VertexId, towards: DVec3) -> (VertexId, VertexId) {
    let fan: Vec<VertexId> = mesh.vertex_neighbors(v).collect();
    let here = mesh.position(v);
    let score: Vec<f64> = fan
        .iter()
        .map(|&w| (mesh.position(w) - here).normalize_or_zero().dot(towards))
        .collect();
    let n = fan.len();
    let best = (0..n)
        .max_by(|&a, &b| score[a].total_cmp(&score[b]))
        .unwrap_or(0);
    // Grow the run around the best edge while the neighbours point the same way.
    let (mut back, mut ahead) = (0, 0);
    while back + ahead + 1 < n - 1 && score[(best + n - back - 1) % n] > 0.0 {
        back += 1;
    }
    while back + ahead + 1 < n - 1 && score[(best + ahead + 1) % n] > 0.0 {
        ahead += 1;
    }
    (fan[(best + n - back) % n], fan[(best + ahead) % n])
}

/// A move of vertices with each Mirror modifier's clipping held (Blender's
/// Clipping): a vertex on a mirror plane stays on it, one that would cross
/// it stops on it. Other commands pass unchanged.
fn clip_to_mirrors(
    cmd: Command,
    mesh: &HalfEdgeMesh,
    modifiers: &[hedra_doc::MeshModifier],
) -> Command {
    let mirrors: Vec<&hedra_doc::MirrorModifier> = modifiers
        .iter()
        .filter_map(|m| match m {
            hedra_doc::MeshModifier::Mirror(m) if m.clipping => Some(m),
            _ => None,
        })
        .collect();
    if mirrors.is_empty() {
        return cmd;
    }
    let clip = |v: u32, after: DVec3| {
        let before = mesh.position(VertexId(v));
        mirrors.iter().fold(after, |p, m| m.clip(before, p))
    };
    match cmd {
        Command::MoveVertices {
            node,
            vertices: VertexSet::Ids(ids),
            offset,
        } => Command::SetVertexPositions {
            node,
            positions: ids
                .iter()
                .map(|&v| (v, clip(v, mesh.position(VertexId(v)) + offset)))
                .collect(),
        },
        Command::SetVertexPositions { node, positions } => Command::SetVertexPositions {
            node,
            positions: positions
                .into_iter()
                .map(|(v, p)| (v, clip(v, p)))
                .collect(),
        },
        other => other,
    }
}

/// New local positions of the selected vertices (transformed in full) and
/// of their proportional neighbours (by their weights): `transform` takes
/// a world position and a weight.
fn weighted_positions(
    mesh: &HalfEdgeMesh,
    selection: &ElementSelection,
    world: DMat4,
    weights: &BTreeMap<VertexId, f64>,
    transform: &dyn Fn(DVec3, f64) -> DVec3,
) -> Vec<(u32, DVec3)> {
    let to_local = world.inverse();
    let moved = |v: VertexId, w: f64| {
        let p = world.transform_point3(mesh.position(v));
        (v.0, to_local.transform_point3(transform(p, w)))
    };
    selection
        .all_vertices(mesh)
        .into_iter()
        .map(|v| moved(v, 1.0))
        .chain(weights.iter().map(|(&v, &w)| moved(v, w)))
        .collect()
}

/// The proportional weights of the unselected vertices for the running
/// G/R/S (world distances), kept while the settings stay the same.
#[derive(Clone, Debug)]
pub(super) struct CachedWeights {
    pub(super) settings: crate::Proportional,
    pub(super) weights: BTreeMap<VertexId, f64>,
}

/// Runs the active mesh tool: preview each frame, confirm or cancel.
#[allow(clippy::too_many_arguments)]
pub fn drive_mesh_tool(
    mut mode: ResMut<EditMode>,
    keys: Res<ButtonInput<KeyCode>>,
    strokes: Res<hedra_scene::Strokes>,
    buttons: Res<ButtonInput<MouseButton>>,
    scroll: Res<bevy::input::mouse::AccumulatedMouseScroll>,
    viewport: hedra_scene::ViewportPointer,
    state: Res<DocState>,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<hedra_scene::StatusMessage>,
    snapping: Res<crate::Snapping>,
    mut snap_target: ResMut<crate::SnapTarget>,
    mut proportional: ResMut<crate::Proportional>,
    mut ring: ResMut<crate::ProportionalRing>,
    mut previews: ResMut<hedra_scene::Previews>,
) {
    // The tool's step for this frame; then its slot in the previews
    // shows what it decided (cleared when no tool runs).
    (|| {
        let (window, camera) = (viewport.window(), viewport.camera());
        mode.just_finished = false;
        let Some(mut tool) = mode.tool.take() else {
            return;
        };
        let (Some(node_id), Some(mesh)) = (mode.node, edited_mesh(&state, &mode)) else {
            mode.preview = None;
            return;
        };
        let modal_keys = crate::modal::ModalKeys {
            keys: &keys,
            buttons: &buttons,
        };
        if modal_keys.cancel() {
            mode.preview = None;
            mode.just_finished = true;
            return;
        }
        if matches!(
            tool.kind,
            MeshToolKind::Move | MeshToolKind::Rotate | MeshToolKind::Scale
        ) {
            modal_keys.toggle_axis(&mut tool.axis);
        }
        // G again while moving edges: slide them instead (Blender's G G).
        if tool.kind == MeshToolKind::Move
            && mode.kind == ElementKind::Edge
            && crate::bindings::pressed(&keys, KeyMode::Tool, Action::Slide)
        {
            tool.kind = MeshToolKind::SlideEdges;
            tool.typed = Default::default();
        }
        // Loop cut and bevel: minus, plus and the wheel change the count of cuts or segments.
        let loop_cut = matches!(tool.kind, MeshToolKind::LoopCut | MeshToolKind::Bevel);
        tool.typed.read(&strokes, !loop_cut);
        if loop_cut {
            let less = crate::bindings::pressed(&keys, KeyMode::Tool, Action::FewerCuts)
                || scroll.delta.y < 0.0;
            let more = crate::bindings::pressed(&keys, KeyMode::Tool, Action::MoreCuts)
                || scroll.delta.y > 0.0;
            if less {
                tool.cuts = tool.cuts.saturating_sub(1).max(1);
            } else if more {
                tool.cuts = (tool.cuts + 1).min(64);
            }
        }
        let (cam, cam_t) = camera;
        let cursor = window.cursor_position().unwrap_or(tool.start_cursor);
        let world = state.session.doc.world_matrix(node_id);
        // Loop cut follows the edge under the pointer, as Blender's does.
        if tool.kind == MeshToolKind::LoopCut
            && let Some(ElementHit::Edge(e)) =
                element_under_cursor(ElementKind::Edge, &mesh, world, window, cam, cam_t)
        {
            tool.edge = Some(e);
        }
        let view_dir = (cam_t.rotation() * Vec3::NEG_Z).as_dvec3();
        // World size of one pixel at the pivot, so drags feel the same at any zoom.
        let dist = cam_t
            .translation()
            .as_dvec3()
            .distance(tool.pivot)
            .max(1e-6);
        let pixel_size = dist * 0.0008;
        let ray_at = |p: Vec2| viewport.ray_at(p);
        // Snapping: a move lands on the scene's vertices, edges or faces (this
        // mesh's moving part left out); the other tools go in increments.
        let snap = if matches!(tool.kind, MeshToolKind::Move | MeshToolKind::SplitVertex) {
            let to_screen = |p: DVec3| cam.world_to_viewport(cam_t, p.as_vec3()).ok();
            let moving = mode.selection.all_vertices(&mesh);
            let doc = &state.session.doc;
            let mut scene = crate::SnapScene::of_document(doc, |id| id != node_id);
            scene.meshes.push(crate::SnapMesh {
                mesh: &mesh,
                world,
                moving: Some(&moving),
            });
            crate::move_snap(
                &snapping,
                snapping.active(&keys),
                &scene,
                moving
                    .iter()
                    .map(|&v| world.transform_point3(mesh.position(v))),
                cursor,
                ray_at(cursor),
                &to_screen,
                &mut snap_target,
            )
        } else if snapping.active(&keys) {
            crate::MoveSnap::Increment(snapping.step)
        } else {
            crate::MoveSnap::Free
        };
        // Proportional editing: G/R/S move the neighbours too; the wheel sizes it.
        let soft = proportional.enabled
            && matches!(
                tool.kind,
                MeshToolKind::Move | MeshToolKind::Rotate | MeshToolKind::Scale
            );
        if soft {
            proportional.adjust_radius(&keys, scroll.delta.y);
            ring.0 = Some((tool.pivot, proportional.radius));
            if tool
                .proportional
                .as_ref()
                .is_none_or(|c| c.settings != *proportional)
            {
                let selected: Vec<VertexId> =
                    mode.selection.all_vertices(&mesh).into_iter().collect();
                let position = |v: VertexId| world.transform_point3(mesh.position(v));
                tool.proportional = Some(tools::CachedWeights {
                    settings: *proportional,
                    weights: hedra_geom::proportional::mesh_weights(
                        &mesh,
                        &position,
                        &selected,
                        proportional.radius,
                        proportional.falloff,
                        proportional.connected_only,
                    ),
                });
            }
        }
        // Out of the tool while the tool is borrowed for the command.
        let cached = tool.proportional.take();
        let weights = cached.as_ref().filter(|_| soft).map(|c| &c.weights);
        let cmd = tool_command(
            &mut tool,
            NodeRef::from(node_id),
            &mesh,
            &mode.selection,
            world,
            cursor,
            &ray_at,
            view_dir,
            pixel_size,
            snap,
            snapping.active(&keys).then_some(&*snapping),
            weights,
        );
        tool.proportional = cached;
        let cmd = match state.session.doc.node(node_id).map(|n| &n.content) {
            Some(NodeContent::Mesh(content)) => clip_to_mirrors(cmd, &mesh, &content.modifiers),
            _ => cmd,
        };
        if soft {
            tool.readout = format!(
                "{} · proportional {} radius {:.3} (wheel)",
                tool.readout,
                proportional.falloff.label(),
                proportional.radius
            );
        }
        if !tool.typed.is_empty() {
            tool.readout = format!("{} [{}]", tool.readout, tool.typed.as_str());
        }
        // Extrude and inset re-place vertices as the value changes: decided
        // twice when the drag starts, then one mesh copy a frame
        // (hedra_doc::preview). The command is decided in full on confirm.
        let value = cmd.linear_parameter();
        if value.is_some() && !tool.linear_tried {
            tool.linear_tried = true;
            tool.linear = state
                .session
                .doc
                .linear_preview(&cmd, node_id)
                .ok()
                .flatten();
        }
        let inset = matches!(
            cmd,
            Command::InsetRegion { .. } | Command::InsetFaces { .. }
        );
        if let (Some(linear), Some(t)) = (&tool.linear, value)
            && (t >= 0.0 || !inset)
        {
            tool.created_faces = linear.created_faces.clone();
            mode.preview = Some(Arc::new(linear.mesh_at(t)));
            mode.preview_creases = Some(linear.creases.clone());
        } else {
            decide_preview(&mut mode, &mut tool, &state, &cmd, node_id);
        }
        if modal_keys.confirm() {
            // A region extrude or inset selects the faces it made (the caps, the
            // inner faces), as Blender keeps them selected.
            // A bevel selects the faces it made, so the selection survives the
            // edges it replaces (and undo gives the edges back selected).
            if matches!(
                tool.kind,
                MeshToolKind::Extrude | MeshToolKind::Inset | MeshToolKind::Bevel
            ) && mode.preview.is_some()
                && !tool.created_faces.is_empty()
            {
                mode.selection_before_step = Some(mode.selection.clone());
                mode.selection.faces = tool.created_faces.iter().copied().collect();
                // In edge mode the new faces show as their edges.
                if mode.kind == ElementKind::Edge
                    && let Some(after) = &mode.preview
                {
                    mode.selection.edges = tool
                        .created_faces
                        .iter()
                        .filter(|f| after.is_face(**f))
                        .flat_map(|&f| after.face_halfedges(f).map(|h| h.edge()))
                        .collect();
                }
            }
            mode.preview = None;
            mode.just_finished = true;
            let nothing =
                matches!(&cmd, Command::MoveVertices { offset, .. } if *offset == DVec3::ZERO);
            if !nothing {
                requests.write(DocRequest::Execute(cmd));
            } else {
                status.info("Move cancelled (no movement)");
            }
            return;
        }
        mode.tool = Some(tool);
    })();
    show_mesh_tool_preview(&mode, &mut previews);
}

/// Decides the tool's command on a copy of the document: the preview mesh,
/// or the reason it cannot apply (shown in the readout).
fn decide_preview(
    mode: &mut EditMode,
    tool: &mut MeshTool,
    state: &DocState,
    cmd: &Command,
    node_id: NodeId,
) {
    match state.session.doc.decide_with_result(cmd, 0) {
        Ok(decision) => {
            tool.created_faces = decision.created_faces;
            let after = decision
                .transaction
                .changes
                .iter()
                .find(|c| c.id == node_id)
                .and_then(|c| c.after.as_ref())
                .and_then(|n| match &n.content {
                    NodeContent::Mesh(m) => Some(m),
                    _ => None,
                });
            mode.preview = after.map(|m| m.mesh.clone());
            mode.preview_creases = after.map(|m| m.creases.clone());
        }
        Err(e) => {
            mode.preview = None;
            tool.readout = format!("{} — {e}", tool.readout);
        }
    }
}
