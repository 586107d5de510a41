//! The edit-mode keys that start a tool or run a command at once (E, I,
//! Ctrl+R, Ctrl+B, J, M, X, F, …), as a table of actions ([`EDIT_ACTIONS`],
//! [`PLAIN_ACTIONS`]) in the style of the keymap's: each action names the
//! handler that runs when its chord is pressed or a menu asks for it.

use super::*;
use crate::bindings::{Action, KeyMode};

/// What an edit-mode shortcut works with: the edited mesh, where the pointer
/// and the pivot are, and where its requests and messages go.
pub(super) struct Shortcut<'a, 'w> {
    mode: &'a mut EditMode,
    mesh: Arc<HalfEdgeMesh>,
    node: NodeRef,
    doc: &'a hedra_doc::Document,
    world: DMat4,
    window: &'a Window,
    camera: (&'a Camera, &'a GlobalTransform),
    cursor: Vec2,
    pivot: DVec3,
    pivot_screen: Vec2,
    requests: &'a mut MessageWriter<'w, DocRequest>,
    status: &'a mut StatusMessage,
}

impl Shortcut<'_, '_> {
    /// A modal tool of `kind` starting at the pointer, about the pivot.
    fn start(&self, kind: MeshToolKind) -> MeshTool {
        MeshTool {
            kind,
            axis: None,
            typed: Default::default(),
            start_cursor: self.cursor,
            pivot: self.pivot,
            pivot_screen: self.pivot_screen,
            edge: None,
            cuts: 1,
            start_value: 0.0,
            created_faces: Vec::new(),
            linear: None,
            linear_tried: false,
            proportional: None,
            readout: String::new(),
        }
    }

    /// Starts the tool `kind` when `allowed`, else says `refusal`.
    fn start_if(&mut self, allowed: bool, kind: MeshToolKind, refusal: &str) {
        if allowed {
            self.mode.tool = Some(self.start(kind));
        } else {
            self.status.error(refusal);
        }
    }

    /// Sends `command` to the document.
    fn send(&mut self, command: Command) {
        self.requests.write(DocRequest::Execute(command));
    }

    fn faces(&self) -> FaceSet {
        FaceSet::Ids(self.mode.selection.faces.iter().map(|f| f.0).collect())
    }

    fn has_faces(&self) -> bool {
        !self.mode.selection.faces.is_empty()
    }
}

/// A shortcut's handler.
type Handler = fn(&mut Shortcut<'_, '_>);

/// Edit mode's actions, tried in order: the first whose chord was pressed
/// this frame (or that a menu asked for) runs, and no other.
pub(super) const EDIT_ACTIONS: &[(Action, Handler)] = &[
    (Action::LoopCut, loop_cut),
    (Action::SplitVertex, split_vertex),
    (Action::BevelVertices, |s| {
        let selected = !s.mode.selection.vertices.is_empty();
        s.start_if(
            selected,
            MeshToolKind::BevelVertices,
            "Vertex bevel: select vertices first (press 1 for vertex mode)",
        )
    }),
    (Action::InsetIndividual, |s| {
        s.start_if(
            s.has_faces(),
            MeshToolKind::InsetIndividual,
            "Inset: select faces first (press 3 for face mode)",
        )
    }),
    (Action::ExtrudeIndividual, |s| {
        s.start_if(
            s.has_faces(),
            MeshToolKind::ExtrudeIndividual,
            "Extrude: select faces first (press 3 for face mode)",
        )
    }),
    (Action::Bevel, |s| {
        let selected = !s.mode.selection.edges.is_empty();
        s.start_if(
            selected,
            MeshToolKind::Bevel,
            "Bevel: select edges first (press 2 for edge mode)",
        )
    }),
    (Action::Crease, crease),
    // Ctrl+T (Blender): triangulate the selected faces.
    (Action::Triangulate, |s| {
        if s.has_faces() {
            s.send(Command::Triangulate {
                node: s.node.clone(),
                faces: s.faces(),
                method: hedra_geom::modeling::TriangulateMethod::Beauty,
            });
        } else {
            s.status
                .error("Triangulate: select faces (press 3 for face mode)");
        }
    }),
    // Alt+J (Blender): join the selected triangles into quads.
    (Action::TrisToQuads, |s| {
        if s.has_faces() {
            s.send(Command::TrisToQuads {
                node: s.node.clone(),
                faces: s.faces(),
                face_degrees: 40.0,
                shape_degrees: 40.0,
            });
        } else {
            s.status
                .error("Tris to Quads: select faces (press 3 for face mode)");
        }
    }),
    (Action::Rip, rip),
    (Action::Dissolve, |s| {
        match delete_or_dissolve(s.node.clone(), s.mode.kind, &s.mode.selection, true) {
            Some(command) => s.send(command),
            None => s.status.error("Ctrl+X: select what to dissolve"),
        }
    }),
    (Action::FlipNormals, |s| {
        s.send(Command::FlipNormals {
            node: s.node.clone(),
        })
    }),
    (Action::RecalculateNormals, |s| {
        s.send(Command::RecalculateNormals {
            node: s.node.clone(),
        })
    }),
];

/// Edit mode's plain keys: tried after [`EDIT_ACTIONS`], only while neither
/// Ctrl nor Alt is held.
pub(super) const PLAIN_ACTIONS: &[(Action, Handler)] = &[
    (Action::Fill, fill),
    (Action::Move, |s| transform(s, MeshToolKind::Move)),
    (Action::Rotate, |s| transform(s, MeshToolKind::Rotate)),
    (Action::Scale, |s| transform(s, MeshToolKind::Scale)),
    (Action::Extrude, |s| {
        if s.mode.kind == ElementKind::Edge {
            let selected = !s.mode.selection.edges.is_empty();
            s.start_if(
                selected,
                MeshToolKind::ExtrudeEdges,
                "Extrude: select boundary edges first",
            )
        } else {
            s.start_if(
                s.has_faces(),
                MeshToolKind::Extrude,
                "Extrude: select faces first (press 3 for face mode)",
            )
        }
    }),
    (Action::Inset, |s| {
        s.start_if(
            s.has_faces(),
            MeshToolKind::Inset,
            "Inset: select faces first (press 3 for face mode)",
        )
    }),
    (Action::MergeOrCollapse, merge_or_collapse),
    (Action::Connect, |s| {
        let vs: Vec<u32> = s.mode.selection.vertices.iter().map(|v| v.0).collect();
        if vs.len() == 2 {
            s.send(Command::ConnectVertices {
                node: s.node.clone(),
                vertices: VertexSet::Ids(vs),
            });
        } else {
            s.status
                .error("Connect: select exactly two vertices of one face");
        }
    }),
    (Action::Delete, |s| {
        match delete_or_dissolve(s.node.clone(), s.mode.kind, &s.mode.selection, false) {
            Some(command) => s.send(command),
            None => s
                .status
                .error("X: select what to delete (Ctrl+X dissolves)"),
        }
    }),
];

/// Runs the first edit-mode action whose chord was pressed this frame, or
/// that a menu asked for ([`EDIT_ACTIONS`], then [`PLAIN_ACTIONS`]).
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
    let Some(mesh) = edited_mesh(&state, &mode) else {
        return;
    };
    let Some(cursor) = window.cursor_position() else {
        return;
    };
    let doc = &state.session.doc;
    let node_id = mode.node.expect("active");
    let world = doc.world_matrix(node_id);
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
    // A chord, or the same action asked for from a menu.
    let mut wants = |action: Action| {
        requested.take(action) || crate::bindings::pressed(&keys, KeyMode::Edit, action)
    };
    let plain = !(ctrl(&keys) || alt(&keys));
    let run = EDIT_ACTIONS
        .iter()
        .chain(PLAIN_ACTIONS.iter().filter(|_| plain))
        .find(|(action, _)| wants(*action));
    if let Some((_, handler)) = run {
        handler(&mut Shortcut {
            mode: &mut mode,
            mesh,
            node: NodeRef::from(node_id),
            doc,
            world,
            window,
            camera,
            cursor,
            pivot,
            pivot_screen,
            requests: &mut requests,
            status: &mut status,
        });
    }
}

/// Ctrl+R: the loop cut on the edge under the pointer, else the selected
/// edge, or an edge of the selected face (face mode; the ring then follows
/// the pointer onto the one wanted).
fn loop_cut(s: &mut Shortcut<'_, '_>) {
    let (cam, cam_t) = s.camera;
    let under = element_under_cursor(ElementKind::Edge, &s.mesh, s.world, s.window, cam, cam_t);
    let edge = match under {
        Some(ElementHit::Edge(e)) => Some(e),
        _ => s.mode.selection.edges.iter().next().copied().or_else(|| {
            let f = *s.mode.selection.faces.iter().next()?;
            s.mesh.face_halfedges(f).next().map(|h| h.edge())
        }),
    };
    match edge {
        Some(e) => {
            let mut t = s.start(MeshToolKind::LoopCut);
            t.edge = Some(e);
            s.mode.tool = Some(t);
        }
        None => s
            .status
            .error("Loop cut: point at an edge of a quad strip (or select one), then press Ctrl+R"),
    }
}

/// Alt+V: the vertex split follows the pointer from the vertex itself.
fn split_vertex(s: &mut Shortcut<'_, '_>) {
    let sel = &s.mode.selection;
    match sel.vertices.iter().collect::<Vec<_>>()[..] {
        [&v] if s.mesh.vertex_neighbors(v).count() < 2 => s
            .status
            .error("Split vertex: the vertex needs two edges or more"),
        [&v] if sel.edges.is_empty() && sel.faces.is_empty() => {
            let mut t = s.start(MeshToolKind::SplitVertex);
            t.pivot = s.world.transform_point3(s.mesh.position(v));
            t.pivot_screen = s
                .camera
                .0
                .world_to_viewport(s.camera.1, t.pivot.as_vec3())
                .unwrap_or(s.cursor);
            s.mode.tool = Some(t);
        }
        _ => s
            .status
            .error("Split vertex: select exactly one vertex (press 1 for vertex mode)"),
    }
}

/// Shift+E: crease the selected edges (corners of the selected vertices in
/// vertex mode), starting from their mean sharpness.
fn crease(s: &mut Shortcut<'_, '_>) {
    let creases = match s.doc.node(s.mode.node.expect("active")).map(|n| &n.content) {
        Some(NodeContent::Mesh(m)) => m.creases.clone(),
        _ => Creases::default(),
    };
    let values: Vec<f64> = if s.mode.kind == ElementKind::Vertex {
        s.mode
            .selection
            .vertices
            .iter()
            .map(|&v| creases.vertex(v))
            .collect()
    } else {
        s.mode
            .selection
            .edges
            .iter()
            .map(|&e| creases.edge(e))
            .collect()
    };
    if values.is_empty() {
        s.status
            .error("Crease: select edges (2), or vertices (1) for corner sharpness, first");
    } else {
        let mut t = s.start(MeshToolKind::Crease);
        t.start_value = values.iter().sum::<f64>() / values.len() as f64;
        s.mode.tool = Some(t);
    }
}

/// V (Blender's Rip): split the mesh along the selected edges (in vertex
/// mode, the edges between selected vertices) and grab the side nearest
/// the pointer.
fn rip(s: &mut Shortcut<'_, '_>) {
    let mesh = &s.mesh;
    let edges: Vec<EdgeId> = if s.mode.kind == ElementKind::Vertex {
        mesh.edges()
            .filter(|&e| {
                mesh.edge_vertices(e)
                    .iter()
                    .all(|v| s.mode.selection.vertices.contains(v))
            })
            .collect()
    } else {
        s.mode.selection.edges.iter().copied().collect()
    };
    if edges.is_empty() {
        s.status
            .error("Rip: select the edges to rip along (2 for edge mode)");
        return;
    }
    // Ripped on a copy first: the command makes the same mesh, so the side
    // found here is the one to grab.
    let mut ripped = (**mesh).clone();
    match hedra_geom::modeling::rip_edges(&mut ripped, &edges) {
        Ok(rip) => {
            let (cam, cam_t) = s.camera;
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
                cam.world_to_viewport(cam_t, s.world.transform_point3(mean).as_vec3())
                    .map_or(f32::MAX, |p| p.distance(s.cursor))
            };
            let grab_a = side_centre(&|p| p.0) <= side_centre(&|p| p.1);
            let (side, other) = if grab_a {
                (&rip.side_a, &rip.side_b)
            } else {
                (&rip.side_b, &rip.side_a)
            };
            let vertices = side
                .iter()
                .filter(|v| !other.contains(v))
                .copied()
                .collect();
            s.send(Command::Rip {
                node: s.node.clone(),
                edges: EdgeSet::Ids(edges.iter().map(|e| e.0).collect()),
            });
            s.mode.kind = ElementKind::Vertex;
            s.mode.selection = ElementSelection {
                vertices,
                ..Default::default()
            };
            s.mode.tool = Some(s.start(MeshToolKind::Move));
        }
        Err(e) => s.status.error(format!("Rip: {e}")),
    }
}

/// F: fill the holes around the selected edges (in vertex mode, the
/// boundary edges between selected vertices).
fn fill(s: &mut Shortcut<'_, '_>) {
    let mesh = &s.mesh;
    let sel = &s.mode.selection;
    let edges: Vec<u32> = sel
        .edges
        .iter()
        .map(|e| e.0)
        .chain(
            mesh.edges()
                .filter(|&e| {
                    mesh.is_boundary_edge(e)
                        && mesh
                            .edge_vertices(e)
                            .iter()
                            .all(|v| sel.vertices.contains(v))
                })
                .map(|e| e.0),
        )
        .collect();
    if edges.is_empty() {
        s.status
            .error("Fill: select edges (or vertices) around a hole");
    } else {
        s.send(Command::FillHoles {
            node: s.node.clone(),
            edges: EdgeSet::Ids(edges),
        });
    }
}

/// G, R, S: move, rotate or scale what is selected.
fn transform(s: &mut Shortcut<'_, '_>, kind: MeshToolKind) {
    let selected = !s.mode.selection.all_vertices(&s.mesh).is_empty();
    s.start_if(selected, kind, "Nothing selected to transform");
}

/// M: the merge menu at the pointer in vertex mode, else collapse the
/// selected edges.
fn merge_or_collapse(s: &mut Shortcut<'_, '_>) {
    if s.mode.kind == ElementKind::Vertex {
        if s.mode.selection.vertices.len() < 2 {
            s.status.error("Merge: select two or more vertices");
        } else {
            s.mode.merge_menu_at = s.window.cursor_position();
        }
    } else if s.mode.selection.edges.is_empty() {
        s.status
            .error("Collapse: select edges (press 2 for edge mode)");
    } else {
        s.send(Command::CollapseEdges {
            node: s.node.clone(),
            edges: EdgeSet::Ids(s.mode.selection.edges.iter().map(|e| e.0).collect()),
        });
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
