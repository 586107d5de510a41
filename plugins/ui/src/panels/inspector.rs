//! The topology inspector: the half-edge and winged-edge tables of the selection.

use super::*;

/// Seed 000's records for the one selected element: the half-edge record,
/// the winged-edge row, faces around a vertex, neighbours of a face.
pub(super) fn topology_inspector(
    ui: &mut egui::Ui,
    m: &hedra_geom::HalfEdgeMesh,
    sel: &hedra_edit::ElementSelection,
) {
    use hedra_geom::topology::{halfedge_record, winged_edge_row};
    let opt = |f: Option<hedra_geom::FaceId>| f.map_or("-".to_string(), |f| f.to_string());
    let join = |v: Vec<String>| {
        if v.is_empty() {
            "-".to_string()
        } else {
            v.join(" ")
        }
    };
    let he_grid = |ui: &mut egui::Ui, hs: &[hedra_geom::HalfEdgeId], salt: &str| {
        // Its own horizontal scroll keeps the wide table from pushing the
        // panel (and with it the viewport) wider when something is picked.
        egui::ScrollArea::horizontal().id_salt(salt).show(ui, |ui| {
            // Short headings and tight spacing: all six columns fit the
            // panel's default width (the face column was off to the right).
            egui::Grid::new(salt)
                .striped(true)
                .spacing([6.0, 2.0])
                .min_col_width(24.0)
                .show(ui, |ui| {
                    for t in ["h", "from", "twin", "next", "prev", "face"] {
                        ui.label(egui::RichText::new(t).strong());
                    }
                    ui.end_row();
                    for &h in hs {
                        let r = halfedge_record(m, h);
                        for t in [
                            r.halfedge.to_string(),
                            r.origin.to_string(),
                            r.twin.to_string(),
                            r.next.to_string(),
                            r.prev.to_string(),
                            opt(r.face),
                        ] {
                            ui.label(t);
                        }
                        ui.end_row();
                    }
                });
        });
    };
    // The selection can briefly name elements of the next mesh (a tool that
    // just confirmed): show only what this mesh has.
    let mut live = sel.clone();
    live.retain_live(m);
    let sel = &live;
    let total = sel.vertices.len() + sel.edges.len() + sel.faces.len();
    if total != 1 {
        ui.label("Select exactly one vertex, edge or face to see its records; related elements are drawn in cyan.");
        return;
    }
    if let Some(&v) = sel.vertices.iter().next() {
        let p = m.position(v);
        ui.label(format!(
            "{v} at ({:.4}, {:.4}, {:.4}), valence {}",
            p.x,
            p.y,
            p.z,
            m.vertex_valence(v)
        ));
        ui.label(format!(
            "faces around: {}",
            join(m.vertex_faces(v).map(|f| f.to_string()).collect())
        ));
        ui.label(format!(
            "neighbours: {}",
            join(m.vertex_neighbors(v).map(|w| w.to_string()).collect())
        ));
        ui.label("outgoing half-edges:");
        he_grid(
            ui,
            &m.vertex_outgoing(v).collect::<Vec<_>>(),
            "inspector-vertex",
        );
    } else if let Some(&e) = sel.edges.iter().next() {
        let w = winged_edge_row(m, e);
        ui.label("winged-edge row:");
        egui::Grid::new("inspector-winged")
            .striped(true)
            .show(ui, |ui| {
                for (k, v) in [
                    ("edge", w.edge.to_string()),
                    ("start", w.start.to_string()),
                    ("end", w.end.to_string()),
                    ("left face", opt(w.left_face)),
                    ("right face", opt(w.right_face)),
                    ("left predecessor", w.left_predecessor.to_string()),
                    ("left successor", w.left_successor.to_string()),
                    ("right predecessor", w.right_predecessor.to_string()),
                    ("right successor", w.right_successor.to_string()),
                ] {
                    ui.label(k);
                    ui.label(v);
                    ui.end_row();
                }
            });
        ui.label("its half-edges:");
        he_grid(ui, &[e.halfedge(0), e.halfedge(1)], "inspector-edge");
    } else if let Some(&f) = sel.faces.iter().next() {
        ui.label(format!(
            "{f}: {} sides, half-edge {}",
            m.face_degree(f),
            m.face_halfedge(f)
        ));
        ui.label(format!(
            "vertices: {}",
            join(m.face_vertices(f).map(|v| v.to_string()).collect())
        ));
        ui.label(format!(
            "neighbours: {}",
            join(m.face_neighbors(f).map(|g| g.to_string()).collect())
        ));
        ui.label("loop:");
        he_grid(
            ui,
            &m.face_halfedges(f).collect::<Vec<_>>(),
            "inspector-face",
        );
    }
}

/// The mesh's V, E, F, loops, shells, holes (genus) and borders, and how
/// the last undo step changed them (Euler operators name exactly such a
/// change: MEV is "V +1, E +1").
pub(super) fn topology_counts(
    ui: &mut egui::Ui,
    id: NodeId,
    mesh: &std::sync::Arc<hedra_geom::HalfEdgeMesh>,
    model: &Model,
    facts: &mut crate::MeshFacts,
) {
    let now = facts.counts(mesh);
    ui.label(format!("{now}"));
    let Some(last) = model.state.session.history.done().last() else {
        return;
    };
    let before = last
        .changes
        .iter()
        .find(|c| c.id == id)
        .and_then(|c| c.before.as_ref())
        .and_then(|n| match &n.content {
            NodeContent::Mesh(m) => Some(facts.counts(&m.mesh)),
            _ => None,
        });
    if let Some(before) = before {
        ui.label(format!("{}: {}", last.label, now.since(&before)));
    }
}
