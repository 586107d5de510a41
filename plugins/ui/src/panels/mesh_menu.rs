//! Edit mode's Mesh menu: every tool on the current selection.

use super::*;
use hedra_edit::bindings::{Action, KeyMode};

/// A menu item's text with its edit-mode keys from the keymap after a tab.
fn keyed(label: &str, action: Action) -> String {
    keyed_in(KeyMode::Edit, label, action)
}

/// Edit mode's Mesh menu: every tool on the current selection. Amounts start
/// at sensible defaults and are changed in the Adjust Last window, as in
/// Blender; the keys run the same tools interactively.
pub(super) fn mesh_menu(
    ui: &mut egui::Ui,
    node: NodeId,
    mode: &EditMode,
    spin_axis: Option<(DVec3, DVec3)>,
    mesh: Option<&hedra_geom::HalfEdgeMesh>,
    events: &mut Vec<UiEvent>,
) {
    use hedra_doc::{EdgeSet, FaceSet, VertexSet};
    let sel = &mode.selection;
    let faces = || FaceSet::Ids(sel.faces.iter().map(|f| f.0).collect());
    let edges = || EdgeSet::Ids(sel.edges.iter().map(|e| e.0).collect());
    let vertices = || VertexSet::Ids(sel.vertices.iter().map(|v| v.0).collect());
    let n = NodeRef::from(node);
    let (has_f, has_e, has_v) = (
        !sel.faces.is_empty(),
        !sel.edges.is_empty(),
        !sel.vertices.is_empty(),
    );
    let mut merge_events = Vec::new();
    let mut euler_events = Vec::new();
    let mut start_bisect = false;
    let mut tool_to_start = None;
    let mut item = |ui: &mut egui::Ui, label: &str, enabled: bool, cmd: &dyn Fn() -> Command| {
        if ui.add_enabled(enabled, egui::Button::new(label)).clicked() {
            exec(events, cmd());
            ui.close();
        }
    };
    ui.label(egui::RichText::new("Faces").weak());
    item(
        ui,
        &keyed("Extrude Region", Action::Extrude),
        has_f,
        &|| Command::ExtrudeRegion {
            node: n.clone(),
            faces: faces(),
            distance: 0.5,
        },
    );
    item(
        ui,
        &keyed("Extrude Individual", Action::ExtrudeIndividual),
        has_f,
        &|| Command::ExtrudeFaces {
            node: n.clone(),
            faces: faces(),
            distance: 0.5,
        },
    );
    item(ui, &keyed("Inset Region", Action::Inset), has_f, &|| {
        Command::InsetRegion {
            node: n.clone(),
            faces: faces(),
            thickness: 0.1,
            depth: 0.0,
        }
    });
    item(
        ui,
        &keyed("Inset Individual", Action::InsetIndividual),
        has_f,
        &|| Command::InsetFaces {
            node: n.clone(),
            faces: faces(),
            thickness: 0.1,
            depth: 0.0,
        },
    );
    item(ui, "Delete Only Faces (keep edges)", has_f, &|| {
        Command::MakeHoles {
            node: n.clone(),
            faces: faces(),
        }
    });
    item(
        ui,
        &keyed("Triangulate Faces", Action::Triangulate),
        has_f,
        &|| Command::Triangulate {
            node: n.clone(),
            faces: faces(),
            method: hedra_geom::modeling::TriangulateMethod::Beauty,
        },
    );
    item(
        ui,
        &keyed("Tris to Quads", Action::TrisToQuads),
        has_f,
        &|| Command::TrisToQuads {
            node: n.clone(),
            faces: faces(),
            face_degrees: 40.0,
            shape_degrees: 40.0,
        },
    );
    // Subdivision holes (OpenSubdiv's face hole tag): the faces leave no
    // surface; their neighbours keep their shape.
    for (label, hole) in [("Make Hole (subdivision)", true), ("Clear Hole", false)] {
        item(ui, label, has_f, &|| Command::SetFaceHole {
            node: n.clone(),
            faces: faces(),
            hole,
        });
    }
    // Spin and Screw sweep the selected faces, or else the selected
    // boundary edges, about the view axis through the 3D cursor.
    let profile = || {
        if has_f {
            hedra_doc::ProfileSet::Faces(faces())
        } else {
            hedra_doc::ProfileSet::Edges(edges())
        }
    };
    if let Some((center, axis)) = spin_axis {
        item(
            ui,
            "Spin (about the cursor, view axis)",
            has_f || has_e,
            &|| Command::Spin {
                node: n.clone(),
                profile: profile(),
                center,
                axis,
                degrees: 90.0,
                steps: 9,
            },
        );
        item(
            ui,
            "Screw (about the cursor, view axis)",
            has_f || has_e,
            &|| Command::Screw {
                node: n.clone(),
                profile: profile(),
                center,
                axis,
                turns: 2,
                steps: 12,
                pitch: 1.0,
            },
        );
    }
    if ui
        .add_enabled(has_f, egui::Button::new("Bisect (drag a line)"))
        .clicked()
    {
        // Pushed after the menu: `item` holds the event list until then.
        start_bisect = true;
        ui.close();
    }
    ui.separator();
    ui.label(egui::RichText::new("Edges").weak());
    // The interactive tool, as Ctrl+R: the ring follows the pointer, the
    // wheel sets the cuts, a click places them (any selection mode).
    if ui
        .button(keyed("Loop Cut", Action::LoopCut))
        .on_hover_text("Point at an edge ring; the wheel or +/- sets the cuts; click to cut")
        .clicked()
    {
        tool_to_start = Some(Action::LoopCut);
        ui.close();
    }
    item(ui, "Subdivide", has_e, &|| Command::SubdivideEdges {
        node: n.clone(),
        edges: edges(),
        cuts: 1,
    });
    item(ui, "Bridge Edge Loops", has_e, &|| Command::BridgeLoops {
        node: n.clone(),
        edges: edges(),
    });
    item(ui, &keyed("Fill", Action::Fill), has_e, &|| {
        Command::FillHoles {
            node: n.clone(),
            edges: edges(),
        }
    });
    item(
        ui,
        &keyed("Collapse", Action::MergeOrCollapse),
        has_e,
        &|| Command::CollapseEdges {
            node: n.clone(),
            edges: edges(),
        },
    );
    item(
        ui,
        &keyed("Dissolve Edges", Action::Dissolve),
        has_e,
        &|| Command::DissolveEdges {
            node: n.clone(),
            edges: edges(),
        },
    );
    ui.separator();
    ui.label(egui::RichText::new("Vertices").weak());
    item(
        ui,
        &keyed("Connect", Action::Connect),
        sel.vertices.len() == 2,
        &|| Command::ConnectVertices {
            node: n.clone(),
            vertices: vertices(),
        },
    );
    ui.menu_button(keyed("Merge", Action::MergeOrCollapse), |ui| {
        merge_buttons(ui, node, sel, &mut merge_events)
    });
    item(
        ui,
        &keyed("Bevel Vertices", Action::BevelVertices),
        has_v,
        &|| Command::BevelVertices {
            node: n.clone(),
            vertices: vertices(),
            width: 0.1,
        },
    );
    if ui
        .add_enabled(
            sel.vertices.len() == 1,
            egui::Button::new(keyed("Split Vertex", Action::SplitVertex)),
        )
        .on_hover_text("The vertex's edges on the pointer's side go to a new vertex joined to it by an edge (the inverse of a collapse); click to place it")
        .clicked()
    {
        tool_to_start = Some(Action::SplitVertex);
        ui.close();
    }
    item(
        ui,
        &keyed("Dissolve Vertices", Action::Dissolve),
        has_v,
        &|| Command::DissolveVertices {
            node: n.clone(),
            vertices: vertices(),
        },
    );
    ui.separator();
    ui.label(egui::RichText::new("Symmetry").weak());
    for axis in [
        hedra_geom::modeling::MirrorAxis::X,
        hedra_geom::modeling::MirrorAxis::Y,
        hedra_geom::modeling::MirrorAxis::Z,
    ] {
        let set = selection_vertices(sel);
        item(ui, &format!("Mirror {axis:?}"), set.is_some(), &|| {
            Command::MirrorVertices {
                node: n.clone(),
                vertices: set.clone().unwrap_or(VertexSet::All),
                axis,
            }
        });
    }
    for axis in [
        hedra_geom::modeling::MirrorAxis::X,
        hedra_geom::modeling::MirrorAxis::Y,
        hedra_geom::modeling::MirrorAxis::Z,
    ] {
        item(
            ui,
            &format!("Symmetrize +{axis:?} to -{axis:?}"),
            true,
            &|| Command::Symmetrize {
                node: n.clone(),
                axis,
            },
        );
    }
    if let Some(mesh) = mesh {
        ui.menu_button("Euler Operators", |ui| {
            euler_operator_buttons(ui, node, mesh, sel, &mut euler_events)
        });
    }
    ui.separator();
    ui.label(egui::RichText::new("Normals").weak());
    item(ui, &keyed("Flip", Action::FlipNormals), true, &|| {
        Command::FlipNormals { node: n.clone() }
    });
    item(
        ui,
        &keyed("Recalculate Outside", Action::RecalculateNormals),
        true,
        &|| Command::RecalculateNormals { node: n.clone() },
    );
    events.extend(merge_events);
    events.extend(euler_events);
    events
        .extend(tool_to_start.map(|action| UiEvent::Edit(hedra_edit::EditRequest::Start(action))));
    if start_bisect {
        events.push(UiEvent::Edit(hedra_edit::EditRequest::StartBisect));
    }
}

/// The vertices a selection touches, of any element kind, as a command's set.
pub(super) fn selection_vertices(
    sel: &hedra_edit::ElementSelection,
) -> Option<hedra_doc::VertexSet> {
    use hedra_doc::{EdgeSet, FaceSet, VertexSet};
    if !sel.faces.is_empty() {
        Some(VertexSet::OfFaces(Box::new(FaceSet::Ids(
            sel.faces.iter().map(|f| f.0).collect(),
        ))))
    } else if !sel.edges.is_empty() {
        Some(VertexSet::OfEdges(Box::new(EdgeSet::Ids(
            sel.edges.iter().map(|e| e.0).collect(),
        ))))
    } else if !sel.vertices.is_empty() {
        Some(VertexSet::Ids(sel.vertices.iter().map(|v| v.0).collect()))
    } else {
        None
    }
}

/// Mesh ▸ Euler Operators: the seeds' operators applied to the selection,
/// one command each (the topology inspector shows the V/E/F/L/S/H change
/// the step made). Each item says what it needs selected.
fn euler_operator_buttons(
    ui: &mut egui::Ui,
    node: NodeId,
    mesh: &hedra_geom::HalfEdgeMesh,
    sel: &hedra_edit::ElementSelection,
    events: &mut Vec<UiEvent>,
) {
    use hedra_doc::command::{Corner, EulerOp};
    use hedra_doc::{EdgeSet, FaceSet, VertexSet};
    let one = |v: hedra_geom::VertexId| VertexSet::Ids(vec![v.0]);
    let edge = match sel.edges.iter().collect::<Vec<_>>().as_slice() {
        [e] => Some(**e),
        _ => None,
    };
    // The corner of `v` on face `f`: reached along the loop's edge into it.
    let corner = |f: hedra_geom::FaceId, v: hedra_geom::VertexId| {
        mesh.face_all_halfedges(f)
            .find(|&h| mesh.target(h) == v)
            .map(|h| Corner::At {
                at: one(v),
                from: one(mesh.origin(h)),
            })
    };
    let mef = match sel.vertices.iter().copied().collect::<Vec<_>>().as_slice() {
        [a, b] => mesh
            .vertex_faces(*a)
            .find(|&f| mesh.face_vertices(f).any(|v| v == *b))
            .and_then(|f| Some((corner(f, *a)?, corner(f, *b)?))),
        _ => None,
    };
    let faces: Vec<hedra_geom::FaceId> = sel.faces.iter().copied().collect();
    // KFMRH: the larger selected face keeps, the smaller becomes its ring.
    let kfmrh = match faces.as_slice() {
        [a, b] => {
            let area = |f: hedra_geom::FaceId| mesh.face_area_vector(f).length();
            Some(if area(*a) >= area(*b) {
                (*a, *b)
            } else {
                (*b, *a)
            })
        }
        _ => None,
    };
    let ring = match faces.as_slice() {
        [f] => mesh.face_rings(*f).first().and_then(|&r| {
            let h = mesh.loop_halfedges(r).next()?;
            Some(Corner::At {
                at: one(mesh.target(h)),
                from: one(mesh.origin(h)),
            })
        }),
        _ => None,
    };
    let n = NodeRef::from(node);
    let mut run = |ui: &mut egui::Ui, label: &str, op: Option<EulerOp>| {
        if ui
            .add_enabled(op.is_some(), egui::Button::new(label))
            .clicked()
        {
            if let Some(op) = op {
                exec(
                    events,
                    Command::Euler {
                        node: n.clone(),
                        op,
                    },
                );
            }
            ui.close();
        }
    };
    let edge_set = |e: hedra_geom::EdgeId| EdgeSet::Ids(vec![e.0]);
    run(
        ui,
        "MEF: edge and face between 2 selected vertices",
        mef.map(|(a, b)| EulerOp::Mef { a, b }),
    );
    run(
        ui,
        "KEF: kill the selected edge, merging its faces",
        edge.map(|e| EulerOp::Kef { edge: edge_set(e) }),
    );
    run(
        ui,
        "KEV: kill the selected dangling edge and its end",
        edge.map(|e| EulerOp::Kev { edge: edge_set(e) }),
    );
    run(
        ui,
        "KEMR: kill the selected bridge edge, making a ring",
        edge.map(|e| {
            let [a, b] = mesh.edge_vertices(e);
            EulerOp::Kemr {
                from: one(a),
                to: one(b),
            }
        }),
    );
    run(
        ui,
        "KFMRH: the smaller of 2 selected faces becomes a ring (hole) of the other",
        kfmrh.map(|(keep, kill)| EulerOp::Kfmrh {
            keep: FaceSet::Ids(vec![keep.0]),
            kill: FaceSet::Ids(vec![kill.0]),
        }),
    );
    run(
        ui,
        "MFKRH: the selected face's first ring becomes a face",
        ring.map(|ring| EulerOp::Mfkrh { ring }),
    );
}
