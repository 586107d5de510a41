//! Edit mode's Mesh menu: every tool on the current selection, as a table
//! ([`MESH_MENU`]). Amounts start at sensible defaults and are changed in
//! the Adjust Last window, as in Blender; the keys run the same tools
//! interactively.

use super::menu_table::{
    ALWAYS, MenuRow, MenuState, When, item, keyed_item, start_tool, with_hover,
};
use super::*;
use hedra_doc::ProfileSet;
use hedra_edit::EditRequest;
use hedra_edit::bindings::{Action as A, KeyMode::Edit};
use hedra_geom::modeling::{MirrorAxis, TriangulateMethod};

const FACES: When = |s| {
    if s.mode.selection.faces.is_empty() {
        Err("Select faces first (3: face mode, A: all)")
    } else {
        Ok(())
    }
};
const EDGES: When = |s| {
    if s.mode.selection.edges.is_empty() {
        Err("Select edges first (2: edge mode)")
    } else {
        Ok(())
    }
};
const VERTICES: When = |s| {
    if s.mode.selection.vertices.is_empty() {
        Err("Select vertices first (1: vertex mode)")
    } else {
        Ok(())
    }
};
/// Spin and Screw: a profile of faces or boundary edges, and a known view.
const PROFILE: When = |s| {
    let sel = &s.mode.selection;
    if sel.faces.is_empty() && sel.edges.is_empty() {
        Err("Select the faces or boundary edges to sweep")
    } else if s.spin_axis.is_none() {
        Err("The view's direction is not known yet")
    } else {
        Ok(())
    }
};
const ANY_ELEMENT: When = |s| match selection_vertices(&s.mode.selection) {
    Some(_) => Ok(()),
    None => Err("Select what to mirror"),
};

/// Spin and Screw sweep the selected faces, or else the selected boundary
/// edges.
fn profile(s: &MenuState<'_>) -> ProfileSet {
    if s.mode.selection.faces.is_empty() {
        ProfileSet::Edges(s.edges())
    } else {
        ProfileSet::Faces(s.faces())
    }
}

/// Mirror the vertices the selection touches across `axis`.
fn mirror(s: &MenuState<'_>, axis: MirrorAxis, events: &mut Vec<UiEvent>) {
    if let Some(vertices) = selection_vertices(&s.mode.selection) {
        exec(
            events,
            Command::MirrorVertices {
                node: s.edited(),
                vertices,
                axis,
            },
        );
    }
}

fn symmetrize(s: &MenuState<'_>, axis: MirrorAxis, events: &mut Vec<UiEvent>) {
    exec(
        events,
        Command::Symmetrize {
            node: s.edited(),
            axis,
        },
    );
}

/// Edit mode's Mesh menu.
pub(super) const MESH_MENU: &[MenuRow] = &[
    MenuRow::Heading("Faces"),
    keyed_item("Extrude Region", Edit, A::Extrude, FACES, |s, e| {
        exec(
            e,
            Command::ExtrudeRegion {
                node: s.edited(),
                faces: s.faces(),
                distance: 0.5,
            },
        )
    }),
    keyed_item(
        "Extrude Individual",
        Edit,
        A::ExtrudeIndividual,
        FACES,
        |s, e| {
            exec(
                e,
                Command::ExtrudeFaces {
                    node: s.edited(),
                    faces: s.faces(),
                    distance: 0.5,
                },
            )
        },
    ),
    keyed_item("Inset Region", Edit, A::Inset, FACES, |s, e| {
        exec(
            e,
            Command::InsetRegion {
                node: s.edited(),
                faces: s.faces(),
                thickness: 0.1,
                depth: 0.0,
            },
        )
    }),
    keyed_item(
        "Inset Individual",
        Edit,
        A::InsetIndividual,
        FACES,
        |s, e| {
            exec(
                e,
                Command::InsetFaces {
                    node: s.edited(),
                    faces: s.faces(),
                    thickness: 0.1,
                    depth: 0.0,
                },
            )
        },
    ),
    item("Delete Only Faces (keep edges)", FACES, |s, e| {
        exec(
            e,
            Command::MakeHoles {
                node: s.edited(),
                faces: s.faces(),
            },
        )
    }),
    keyed_item("Triangulate Faces", Edit, A::Triangulate, FACES, |s, e| {
        exec(
            e,
            Command::Triangulate {
                node: s.edited(),
                faces: s.faces(),
                method: TriangulateMethod::Beauty,
            },
        )
    }),
    keyed_item("Tris to Quads", Edit, A::TrisToQuads, FACES, |s, e| {
        exec(
            e,
            Command::TrisToQuads {
                node: s.edited(),
                faces: s.faces(),
                face_degrees: 40.0,
                shape_degrees: 40.0,
            },
        )
    }),
    // Subdivision holes (OpenSubdiv's face hole tag): the faces leave no
    // surface; their neighbours keep their shape.
    item("Make Hole (subdivision)", FACES, |s, e| {
        exec(
            e,
            Command::SetFaceHole {
                node: s.edited(),
                faces: s.faces(),
                hole: true,
            },
        )
    }),
    item("Clear Hole", FACES, |s, e| {
        exec(
            e,
            Command::SetFaceHole {
                node: s.edited(),
                faces: s.faces(),
                hole: false,
            },
        )
    }),
    // About the view axis through the 3D cursor.
    item("Spin (about the cursor, view axis)", PROFILE, |s, e| {
        if let Some((center, axis)) = s.spin_axis {
            exec(
                e,
                Command::Spin {
                    node: s.edited(),
                    profile: profile(s),
                    center,
                    axis,
                    degrees: 90.0,
                    steps: 9,
                },
            )
        }
    }),
    item("Screw (about the cursor, view axis)", PROFILE, |s, e| {
        if let Some((center, axis)) = s.spin_axis {
            exec(
                e,
                Command::Screw {
                    node: s.edited(),
                    profile: profile(s),
                    center,
                    axis,
                    turns: 2,
                    steps: 12,
                    pitch: 1.0,
                },
            )
        }
    }),
    item("Bisect (drag a line)", FACES, |_, e| {
        e.push(UiEvent::Edit(EditRequest::StartBisect))
    }),
    MenuRow::Separator,
    MenuRow::Heading("Edges"),
    // The interactive tool, as Ctrl+R: the ring follows the pointer, the
    // wheel sets the cuts, a click places them (any selection mode).
    with_hover(
        keyed_item("Loop Cut", Edit, A::LoopCut, ALWAYS, |_, e| {
            start_tool(e, A::LoopCut)
        }),
        "Point at an edge ring; the wheel or +/- sets the cuts; click to cut",
    ),
    item("Subdivide", EDGES, |s, e| {
        exec(
            e,
            Command::SubdivideEdges {
                node: s.edited(),
                edges: s.edges(),
                cuts: 1,
            },
        )
    }),
    item("Bridge Edge Loops", EDGES, |s, e| {
        exec(
            e,
            Command::BridgeLoops {
                node: s.edited(),
                edges: s.edges(),
            },
        )
    }),
    keyed_item("Fill", Edit, A::Fill, EDGES, |s, e| {
        exec(
            e,
            Command::FillHoles {
                node: s.edited(),
                edges: s.edges(),
            },
        )
    }),
    keyed_item("Collapse", Edit, A::MergeOrCollapse, EDGES, |s, e| {
        exec(
            e,
            Command::CollapseEdges {
                node: s.edited(),
                edges: s.edges(),
            },
        )
    }),
    keyed_item("Dissolve Edges", Edit, A::Dissolve, EDGES, |s, e| {
        exec(
            e,
            Command::DissolveEdges {
                node: s.edited(),
                edges: s.edges(),
            },
        )
    }),
    MenuRow::Separator,
    MenuRow::Heading("Vertices"),
    keyed_item(
        "Connect",
        Edit,
        A::Connect,
        |s| match s.mode.selection.vertices.len() {
            2 => Ok(()),
            _ => Err("Select two vertices of one face"),
        },
        |s, e| {
            exec(
                e,
                Command::ConnectVertices {
                    node: s.edited(),
                    vertices: s.vertices(),
                },
            )
        },
    ),
    MenuRow::Submenu(
        "Merge",
        Some((Edit, A::MergeOrCollapse)),
        &[MenuRow::Listed(|ui, s, e| {
            merge_buttons(ui, s.mode.node.expect("edit mode"), &s.mode.selection, e)
        })],
    ),
    keyed_item(
        "Bevel Vertices",
        Edit,
        A::BevelVertices,
        VERTICES,
        |s, e| {
            exec(
                e,
                Command::BevelVertices {
                    node: s.edited(),
                    vertices: s.vertices(),
                    width: 0.1,
                },
            )
        },
    ),
    with_hover(
        keyed_item(
            "Split Vertex",
            Edit,
            A::SplitVertex,
            |s| match s.mode.selection.vertices.len() {
                1 => Ok(()),
                _ => Err("Select one vertex"),
            },
            |_, e| start_tool(e, A::SplitVertex),
        ),
        "The vertex's edges on the pointer's side go to a new vertex joined to it by an \
         edge (the inverse of a collapse); click to place it",
    ),
    keyed_item("Dissolve Vertices", Edit, A::Dissolve, VERTICES, |s, e| {
        exec(
            e,
            Command::DissolveVertices {
                node: s.edited(),
                vertices: s.vertices(),
            },
        )
    }),
    MenuRow::Separator,
    // Submenus, as Blender's: the whole menu fits a window 800 pixels high.
    MenuRow::Submenu("Symmetry", None, SYMMETRY),
    MenuRow::Listed(|ui, s, e| {
        let node = s.mode.node.expect("edit mode");
        if let Some(NodeContent::Mesh(m)) = s.doc.node(node).map(|n| &n.content) {
            ui.menu_button("Euler Operators", |ui| {
                euler_operator_buttons(ui, node, &m.mesh, &s.mode.selection, e)
            });
        }
    }),
    MenuRow::Submenu("Normals", None, NORMALS),
];

/// Mesh ▸ Symmetry.
const SYMMETRY: &[MenuRow] = &[
    item("Mirror X", ANY_ELEMENT, |s, e| mirror(s, MirrorAxis::X, e)),
    item("Mirror Y", ANY_ELEMENT, |s, e| mirror(s, MirrorAxis::Y, e)),
    item("Mirror Z", ANY_ELEMENT, |s, e| mirror(s, MirrorAxis::Z, e)),
    MenuRow::Separator,
    item("Symmetrize +X to -X", ALWAYS, |s, e| {
        symmetrize(s, MirrorAxis::X, e)
    }),
    item("Symmetrize +Y to -Y", ALWAYS, |s, e| {
        symmetrize(s, MirrorAxis::Y, e)
    }),
    item("Symmetrize +Z to -Z", ALWAYS, |s, e| {
        symmetrize(s, MirrorAxis::Z, e)
    }),
];

/// Mesh ▸ Normals.
const NORMALS: &[MenuRow] = &[
    keyed_item("Flip", Edit, A::FlipNormals, ALWAYS, |s, e| {
        exec(e, Command::FlipNormals { node: s.edited() })
    }),
    keyed_item(
        "Recalculate Outside",
        Edit,
        A::RecalculateNormals,
        ALWAYS,
        |s, e| exec(e, Command::RecalculateNormals { node: s.edited() }),
    ),
];

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
