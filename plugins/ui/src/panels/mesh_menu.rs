//! Edit mode's Mesh menu: every tool on the current selection.

use super::*;
use hedra_edit::bindings::{Action, KeyMode, chord_label};

/// A menu item's text with its edit-mode keys from the keymap after a tab.
fn keyed(label: &str, action: Action) -> String {
    format!("{label}\t{}", chord_label(KeyMode::Edit, action))
}

/// Edit mode's Mesh menu: every tool on the current selection. Amounts start
/// at sensible defaults and are changed in the Adjust Last window, as in
/// Blender; the keys run the same tools interactively.
pub(super) fn mesh_menu(
    ui: &mut egui::Ui,
    node: NodeId,
    mode: &EditMode,
    spin_axis: Option<(DVec3, DVec3)>,
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
    let mut start_bisect = false;
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
    item(
        ui,
        &keyed("Loop Cut", Action::LoopCut),
        sel.edges.len() == 1,
        &|| Command::LoopCut {
            node: n.clone(),
            edge: edges(),
            cuts: 1,
        },
    );
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
    if start_bisect {
        events.push(UiEvent::StartBisect);
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
