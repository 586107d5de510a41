//! The edit-mode keys that start a tool or run a command at once (E, I, Ctrl+R, Ctrl+B, J, M, X, F, …).

use super::*;
use crate::bindings::{Action, KeyMode};

/// Starts tools and runs instant ones (J, X).
#[allow(clippy::too_many_arguments)]
pub fn edit_shortcuts(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut mode: ResMut<EditMode>,
    state: Res<DocState>,
    viewport: hedra_scene::ViewportPointer,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<hedra_scene::StatusMessage>,
    knife: Res<KnifeTool>,
    pivot_point: Res<crate::PivotPoint>,
    cursor_3d: Res<hedra_scene::Cursor3d>,
    mut requested: ResMut<crate::bindings::RequestedAction>,
    shape_edit: Res<crate::ShapeEdit>,
) {
    let (window, camera) = (viewport.window(), viewport.camera());
    if !mode.active() && !shape_edit.active() {
        // A menu's request outlives no edit mode.
        requested.0 = None;
    }
    if !mode.active() || mode.tool.is_some() || !gate.keyboard_free || knife.active {
        return;
    }
    // A chord, or the same action asked for from a menu.
    let mut wants = |action: Action| {
        requested.take(action) || crate::bindings::pressed(&keys, KeyMode::Edit, action)
    };
    let Some(mesh) = edited_mesh(&state, &mode) else {
        return;
    };
    let node = NodeRef::from(mode.node.expect("active"));
    let world = state.session.doc.world_matrix(mode.node.expect("active"));
    let (c, a) = (ctrl(&keys), alt(&keys));
    let Some(cursor) = window.cursor_position() else {
        return;
    };
    let verts = mode.selection.all_vertices(&mesh);
    let pivot_local = if verts.is_empty() {
        DVec3::ZERO
    } else {
        verts.iter().map(|&v| mesh.position(v)).sum::<DVec3>() / verts.len() as f64
    };
    let pivot = match *pivot_point {
        crate::PivotPoint::MedianPoint => world.transform_point3(pivot_local),
        crate::PivotPoint::Cursor => cursor_3d.0,
    };
    let pivot_screen = camera
        .0
        .world_to_viewport(camera.1, pivot.as_vec3())
        .unwrap_or(cursor);
    let start = |kind: MeshToolKind| MeshTool {
        kind,
        axis: None,
        typed: Default::default(),
        start_cursor: cursor,
        pivot,
        pivot_screen,
        edge: None,
        cuts: 1,
        start_value: 0.0,
        created_faces: Vec::new(),
        linear: None,
        linear_tried: false,
        proportional: None,
        readout: String::new(),
    };
    if wants(Action::LoopCut) {
        let (cam, cam_t) = camera;
        let edge = match element_under_cursor(ElementKind::Edge, &mesh, world, window, cam, cam_t) {
            Some(ElementHit::Edge(e)) => Some(e),
            // Else the selected edge, or an edge of the selected face (face
            // mode; the ring then follows the pointer onto the one wanted).
            _ => mode.selection.edges.iter().next().copied().or_else(|| {
                let f = *mode.selection.faces.iter().next()?;
                mesh.face_halfedges(f).next().map(|h| h.edge())
            }),
        };
        match edge {
            Some(e) => {
                let mut t = start(MeshToolKind::LoopCut);
                t.edge = Some(e);
                mode.tool = Some(t);
            }
            None => status.error(
                "Loop cut: point at an edge of a quad strip (or select one), then press Ctrl+R",
            ),
        }
        return;
    }
    // Alt+V: the vertex split follows the pointer from the vertex itself.
    if wants(Action::SplitVertex) {
        match mode.selection.vertices.iter().collect::<Vec<_>>()[..] {
            [&v] if mesh.vertex_neighbors(v).count() < 2 => {
                status.error("Split vertex: the vertex needs two edges or more")
            }
            [&v] if mode.selection.edges.is_empty() && mode.selection.faces.is_empty() => {
                let mut t = start(MeshToolKind::SplitVertex);
                t.pivot = world.transform_point3(mesh.position(v));
                t.pivot_screen = camera
                    .0
                    .world_to_viewport(camera.1, t.pivot.as_vec3())
                    .unwrap_or(cursor);
                mode.tool = Some(t);
            }
            _ => status.error("Split vertex: select exactly one vertex (press 1 for vertex mode)"),
        }
        return;
    }
    // Tools that start only on a selection of one element kind.
    let faces_selected = !mode.selection.faces.is_empty();
    let edges_selected = !mode.selection.edges.is_empty();
    let vertices_selected = !mode.selection.vertices.is_empty();
    for (action, selected, tool, refusal) in [
        (
            Action::BevelVertices,
            vertices_selected,
            MeshToolKind::BevelVertices,
            "Vertex bevel: select vertices first (press 1 for vertex mode)",
        ),
        (
            Action::InsetIndividual,
            faces_selected,
            MeshToolKind::InsetIndividual,
            "Inset: select faces first (press 3 for face mode)",
        ),
        (
            Action::ExtrudeIndividual,
            faces_selected,
            MeshToolKind::ExtrudeIndividual,
            "Extrude: select faces first (press 3 for face mode)",
        ),
        (
            Action::Bevel,
            edges_selected,
            MeshToolKind::Bevel,
            "Bevel: select edges first (press 2 for edge mode)",
        ),
    ] {
        if wants(action) {
            if selected {
                mode.tool = Some(start(tool));
            } else {
                status.error(refusal);
            }
            return;
        }
    }
    if wants(Action::Crease) {
        let creases = match state
            .session
            .doc
            .node(mode.node.expect("active"))
            .map(|n| &n.content)
        {
            Some(NodeContent::Mesh(m)) => m.creases.clone(),
            _ => Creases::default(),
        };
        let values: Vec<f64> = if mode.kind == ElementKind::Vertex {
            mode.selection
                .vertices
                .iter()
                .map(|&v| creases.vertex(v))
                .collect()
        } else {
            mode.selection
                .edges
                .iter()
                .map(|&e| creases.edge(e))
                .collect()
        };
        if values.is_empty() {
            status.error("Crease: select edges (2), or vertices (1) for corner sharpness, first");
        } else {
            let mut t = start(MeshToolKind::Crease);
            t.start_value = values.iter().sum::<f64>() / values.len() as f64;
            mode.tool = Some(t);
        }
        return;
    }
    // Ctrl+T (Blender): triangulate the selected faces.
    if wants(Action::Triangulate) {
        if mode.selection.faces.is_empty() {
            status.error("Triangulate: select faces (press 3 for face mode)");
        } else {
            requests.write(DocRequest::Execute(Command::Triangulate {
                node: node.clone(),
                faces: FaceSet::Ids(mode.selection.faces.iter().map(|f| f.0).collect()),
                method: hedra_geom::modeling::TriangulateMethod::Beauty,
            }));
        }
        return;
    }
    // Alt+J (Blender): join the selected triangles into quads.
    if wants(Action::TrisToQuads) {
        if mode.selection.faces.is_empty() {
            status.error("Tris to Quads: select faces (press 3 for face mode)");
        } else {
            requests.write(DocRequest::Execute(Command::TrisToQuads {
                node: node.clone(),
                faces: FaceSet::Ids(mode.selection.faces.iter().map(|f| f.0).collect()),
                face_degrees: 40.0,
                shape_degrees: 40.0,
            }));
        }
        return;
    }
    // V (Blender's Rip): split the mesh along the selected edges (in
    // vertex mode, the edges between selected vertices) and grab the side
    // nearest the pointer.
    if wants(Action::Rip) {
        let edges: Vec<EdgeId> = if mode.kind == ElementKind::Vertex {
            mesh.edges()
                .filter(|&e| {
                    mesh.edge_vertices(e)
                        .iter()
                        .all(|v| mode.selection.vertices.contains(v))
                })
                .collect()
        } else {
            mode.selection.edges.iter().copied().collect()
        };
        if edges.is_empty() {
            status.error("Rip: select the edges to rip along (2 for edge mode)");
            return;
        }
        // Ripped on a copy first: the command makes the same mesh, so the
        // side found here is the one to grab.
        let mut ripped = (*mesh).clone();
        match hedra_geom::modeling::rip_edges(&mut ripped, &edges) {
            Ok(rip) => {
                let (cam, cam_t) = camera;
                let side_centre = |pick: &dyn Fn(&(EdgeId, EdgeId)) -> EdgeId| {
                    let faces: Vec<DVec3> = rip
                        .edges
                        .iter()
                        .filter_map(|pair| {
                            let [f, g] = ripped.edge_faces(pick(pair));
                            f.or(g).map(|f| ripped.face_centroid(f))
                        })
                        .collect();
                    let mean = faces.iter().sum::<DVec3>() / faces.len().max(1) as f64;
                    cam.world_to_viewport(cam_t, world.transform_point3(mean).as_vec3())
                        .map_or(f32::MAX, |p| p.distance(cursor))
                };
                let grab_a = side_centre(&|p| p.0) <= side_centre(&|p| p.1);
                let (side, other) = if grab_a {
                    (&rip.side_a, &rip.side_b)
                } else {
                    (&rip.side_b, &rip.side_a)
                };
                requests.write(DocRequest::Execute(Command::Rip {
                    node: node.clone(),
                    edges: EdgeSet::Ids(edges.iter().map(|e| e.0).collect()),
                }));
                mode.kind = ElementKind::Vertex;
                mode.selection = ElementSelection {
                    vertices: side
                        .iter()
                        .filter(|v| !other.contains(v))
                        .copied()
                        .collect(),
                    ..Default::default()
                };
                mode.tool = Some(start(MeshToolKind::Move));
            }
            Err(e) => status.error(format!("Rip: {e}")),
        }
        return;
    }
    if wants(Action::Dissolve) {
        match delete_or_dissolve(node.clone(), mode.kind, &mode.selection, true) {
            Some(cmd) => {
                requests.write(DocRequest::Execute(cmd));
            }
            None => status.error("Ctrl+X: select what to dissolve"),
        }
        return;
    }
    let flip = wants(Action::FlipNormals);
    if flip || wants(Action::RecalculateNormals) {
        let cmd = if flip {
            Command::FlipNormals { node: node.clone() }
        } else {
            Command::RecalculateNormals { node: node.clone() }
        };
        requests.write(DocRequest::Execute(cmd));
        return;
    }
    if c || a {
        return;
    }
    if wants(Action::Fill) {
        let edges: Vec<u32> = mode
            .selection
            .edges
            .iter()
            .map(|e| e.0)
            .chain(
                // In vertex mode: the boundary edges between selected vertices.
                mesh.edges()
                    .filter(|&e| {
                        mesh.is_boundary_edge(e)
                            && mesh
                                .edge_vertices(e)
                                .iter()
                                .all(|v| mode.selection.vertices.contains(v))
                    })
                    .map(|e| e.0),
            )
            .collect();
        if edges.is_empty() {
            status.error("Fill: select edges (or vertices) around a hole");
        } else {
            requests.write(DocRequest::Execute(Command::FillHoles {
                node: node.clone(),
                edges: EdgeSet::Ids(edges),
            }));
        }
        return;
    }
    for (action, kind) in [
        (Action::Move, MeshToolKind::Move),
        (Action::Rotate, MeshToolKind::Rotate),
        (Action::Scale, MeshToolKind::Scale),
    ] {
        if wants(action) {
            if verts.is_empty() {
                status.error("Nothing selected to transform");
            } else {
                mode.tool = Some(start(kind));
            }
        }
    }
    let extrude = wants(Action::Extrude);
    if extrude && mode.kind == ElementKind::Edge {
        if mode.selection.edges.is_empty() {
            status.error("Extrude: select boundary edges first");
        } else {
            mode.tool = Some(start(MeshToolKind::ExtrudeEdges));
        }
    } else if extrude {
        if mode.selection.faces.is_empty() {
            status.error("Extrude: select faces first (press 3 for face mode)");
        } else {
            mode.tool = Some(start(MeshToolKind::Extrude));
        }
    }
    if wants(Action::Inset) {
        if mode.selection.faces.is_empty() {
            status.error("Inset: select faces first (press 3 for face mode)");
        } else {
            mode.tool = Some(start(MeshToolKind::Inset));
        }
    }
    let merge = wants(Action::MergeOrCollapse);
    if merge && mode.kind == ElementKind::Vertex {
        if mode.selection.vertices.len() < 2 {
            status.error("Merge: select two or more vertices");
        } else {
            mode.merge_menu_at = window.cursor_position();
        }
    } else if merge {
        if mode.selection.edges.is_empty() {
            status.error("Collapse: select edges (press 2 for edge mode)");
        } else {
            requests.write(DocRequest::Execute(Command::CollapseEdges {
                node: node.clone(),
                edges: EdgeSet::Ids(mode.selection.edges.iter().map(|e| e.0).collect()),
            }));
        }
    }
    if wants(Action::Connect) {
        let vs: Vec<u32> = mode.selection.vertices.iter().map(|v| v.0).collect();
        if vs.len() == 2 {
            requests.write(DocRequest::Execute(Command::ConnectVertices {
                node,
                vertices: VertexSet::Ids(vs),
            }));
        } else {
            status.error("Connect: select exactly two vertices of one face");
        }
    } else if wants(Action::Delete) {
        match delete_or_dissolve(node, mode.kind, &mode.selection, false) {
            Some(c) => {
                requests.write(DocRequest::Execute(c));
            }
            None => status.error("X: select what to delete (Ctrl+X dissolves)"),
        }
    }
}

/// X deletes the selected elements of the current kind with what only they
/// use; Ctrl+X dissolves them (merging what is around).
pub(super) fn delete_or_dissolve(
    node: NodeRef,
    kind: ElementKind,
    sel: &ElementSelection,
    dissolve: bool,
) -> Option<Command> {
    let vertices = || VertexSet::Ids(sel.vertices.iter().map(|v| v.0).collect());
    let edges = || EdgeSet::Ids(sel.edges.iter().map(|e| e.0).collect());
    let faces = || FaceSet::Ids(sel.faces.iter().map(|f| f.0).collect());
    match (kind, dissolve) {
        (ElementKind::Vertex, _) if sel.vertices.is_empty() => None,
        (ElementKind::Edge, _) if sel.edges.is_empty() => None,
        (ElementKind::Face, _) if sel.faces.is_empty() => None,
        (ElementKind::Vertex, false) => Some(Command::DeleteVertices {
            node,
            vertices: vertices(),
        }),
        (ElementKind::Edge, false) => Some(Command::DeleteEdges {
            node,
            edges: edges(),
        }),
        (ElementKind::Face, false) => Some(Command::DeleteFaces {
            node,
            faces: faces(),
        }),
        (ElementKind::Vertex, true) => Some(Command::DissolveVertices {
            node,
            vertices: vertices(),
        }),
        (ElementKind::Edge, true) => Some(Command::DissolveEdges {
            node,
            edges: edges(),
        }),
        (ElementKind::Face, true) => Some(Command::DissolveFaces {
            node,
            faces: faces(),
        }),
    }
}
