//! The menu bar: File, Edit, Add, Mesh (in edit mode), Object and View.

use super::menu_table::{ALWAYS, MenuRow, When, item, keyed_item, with_hover};
use super::*;
use hedra_edit::bindings::{
    Action,
    KeyMode::{Edit, Everywhere, Object},
};

/// File ▸ up to Export (drawn by code: its option checkboxes).
pub(super) const FILE_MENU: &[MenuRow] = &[
    keyed_item("New", Everywhere, Action::NewFile, ALWAYS, |_, e| {
        e.push(UiEvent::File(FileAction::New))
    }),
    keyed_item("Open…", Everywhere, Action::OpenFile, ALWAYS, |_, e| {
        e.push(UiEvent::File(FileAction::Open))
    }),
    MenuRow::Submenu("Open Recent", None, &[MenuRow::Listed(recent_files)]),
    MenuRow::Submenu("Open Sample", None, &[MenuRow::Listed(sample_files)]),
    MenuRow::Separator,
    keyed_item("Save", Everywhere, Action::Save, ALWAYS, |_, e| {
        e.push(UiEvent::File(FileAction::Save))
    }),
    keyed_item("Save As…", Everywhere, Action::SaveAs, ALWAYS, |_, e| {
        e.push(UiEvent::File(FileAction::SaveAs))
    }),
    MenuRow::Separator,
    // Its hover text lists the formats the reader takes.
    MenuRow::Listed(|ui, _, e| {
        if ui
            .button("Import…")
            .on_hover_text(format!(
                "Add a file's nodes to the scene: {}",
                hedra_doc::import::supported_imports()
            ))
            .clicked()
        {
            e.push(UiEvent::File(FileAction::Import));
            ui.close();
        }
    }),
];

/// File ▸ after Export.
pub(super) const QUIT_MENU: &[MenuRow] = &[
    MenuRow::Separator,
    keyed_item("Quit", Everywhere, Action::Quit, ALWAYS, |_, e| {
        e.push(UiEvent::File(FileAction::Quit))
    }),
];

/// Edit ▸ Undo and Redo (the rest of the Edit menu are settings).
pub(super) const EDIT_MENU: &[MenuRow] = &[
    keyed_item(
        "Undo",
        Everywhere,
        Action::Undo,
        |s| match s.history.can_undo() {
            true => Ok(()),
            false => Err("Nothing to undo"),
        },
        |_, e| e.push(UiEvent::Request(DocRequest::Undo)),
    ),
    keyed_item(
        "Redo",
        Everywhere,
        Action::Redo,
        |s| match s.history.can_redo() {
            true => Ok(()),
            false => Err("Nothing to redo"),
        },
        |_, e| e.push(UiEvent::Request(DocRequest::Redo)),
    ),
];

/// File ▸ Open Recent: one item per recent file.
fn recent_files(ui: &mut egui::Ui, s: &MenuState<'_>, events: &mut Vec<UiEvent>) {
    if s.recent.is_empty() {
        ui.label("(no recent files)");
    }
    for p in s.recent {
        if ui.button(p.display().to_string()).clicked() {
            events.push(UiEvent::File(FileAction::OpenPath(p.clone())));
            ui.close();
        }
    }
}

/// File ▸ Open Sample: one item per sample scene.
fn sample_files(ui: &mut egui::Ui, s: &MenuState<'_>, events: &mut Vec<UiEvent>) {
    let samples = s.samples.map(files::list_samples).unwrap_or_default();
    if samples.is_empty() {
        ui.label("(no samples found)");
    }
    for p in samples {
        let name = p
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        if ui
            .button(name)
            .on_hover_text("Opens as a new scene: the sample stays as it is")
            .clicked()
        {
            events.push(UiEvent::File(FileAction::OpenSample(p)));
            ui.close();
        }
    }
}

const ANY_OBJECT: When = |s| match s.selection.nodes.is_empty() {
    true => Err("Select objects first (click, or A for all)"),
    false => Ok(()),
};

/// Object ▸ Convert ▸ To NURBS: why the active node cannot convert.
const CONVERTIBLE: When = |s| {
    use hedra_geom::subdivision::Scheme;
    match s
        .selection
        .active()
        .and_then(|id| s.doc.node(id))
        .map(|n| &n.content)
    {
        None => Err("Select a mesh with a Catmull-Clark subdivision modifier"),
        Some(NodeContent::Mesh(m)) => match &m.subdivision {
            None => Err("The active mesh has no subdivision modifier (Ctrl+1 adds one)"),
            Some(s) if s.options.scheme != Scheme::CatmullClark => {
                Err("Only a Catmull-Clark limit surface converts to NURBS")
            }
            Some(_) => Ok(()),
        },
        Some(_) => Err("The active object is not a mesh"),
    }
};

/// The selected kept (non-manifold) meshes.
fn selected_kept(s: &MenuState<'_>) -> Vec<NodeRef> {
    s.selection
        .nodes
        .iter()
        .filter(|id| {
            matches!(
                s.doc.node(**id).map(|n| &n.content),
                Some(NodeContent::Kept(_))
            )
        })
        .map(|&id| NodeRef::from(id))
        .collect()
}

/// The Mesh menu in object mode: Make Manifold repairs the selected kept
/// meshes into editable meshes.
pub(super) const OBJECT_MESH_MENU: &[MenuRow] = &[with_hover(
    item(
        "Make Manifold",
        |s| match selected_kept(s).is_empty() {
            true => Err("Select a mesh kept as imported (⚠ in the outliner)"),
            false => Ok(()),
        },
        |s, e| {
            exec(
                e,
                Command::MakeManifold {
                    nodes: selected_kept(s),
                },
            )
        },
    ),
    "Repair meshes kept as imported (not manifold) into editable meshes",
)];

/// The Object menu.
pub(super) const OBJECT_MENU: &[MenuRow] = &[
    keyed_item(
        "Duplicate",
        Object,
        Action::Duplicate,
        ANY_OBJECT,
        |s, e| exec(e, Command::Duplicate { nodes: s.nodes() }),
    ),
    keyed_item("Delete", Object, Action::Delete, ANY_OBJECT, |s, e| {
        exec(e, Command::Delete { nodes: s.nodes() })
    }),
    keyed_item("Hide", Object, Action::Hide, ANY_OBJECT, |s, e| {
        exec(
            e,
            Command::SetVisible {
                nodes: s.nodes(),
                visible: false,
            },
        )
    }),
    MenuRow::Submenu(
        "Surface from Curves",
        None,
        &[MenuRow::Listed(|ui, s, e| {
            surface_from_curves_menu(ui, s.doc, s.selection, e)
        })],
    ),
    MenuRow::Listed(|ui, s, e| g1_join_items(ui, s.doc, s.selection, e)),
    MenuRow::Submenu(
        "Convert",
        None,
        &[with_hover(
            item("To NURBS", CONVERTIBLE, |s, e| {
                if let Some(node) = s.selection.active() {
                    exec(
                        e,
                        Command::ConvertSubdivisionToNurbs {
                            node: NodeRef::from(node),
                            tolerance: None,
                            keep_cage: true,
                        },
                    )
                }
            }),
            "The smooth surface as NURBS patches: exact B-spline surfaces where the cage is \
             regular, fitted patches within 1e-4 of the size elsewhere; the cage is kept, hidden",
        )],
    ),
    MenuRow::Separator,
    MenuRow::Heading("Boolean"),
    MenuRow::Listed(|ui, s, e| draw_menu(ui, BOOLEAN_MENU, s, e)),
    MenuRow::Separator,
    keyed_item(
        "Join Curves",
        Object,
        Action::JoinCurves,
        |s| match hedra_edit::join_curves_command(s.doc, s.selection) {
            Ok(_) => Ok(()),
            Err(_) => Err("Select two curves: the active one comes first"),
        },
        |s, e| {
            if let Ok(cmd) = hedra_edit::join_curves_command(s.doc, s.selection) {
                exec(e, cmd)
            }
        },
    ),
    item("Clear Parent", ANY_OBJECT, |s, e| {
        for node in s.nodes() {
            exec(
                e,
                Command::Reparent {
                    node,
                    parent: None,
                    keep_world: true,
                },
            )
        }
    }),
    MenuRow::Separator,
    item("Shade Flat", ANY_OBJECT, |s, e| {
        exec(
            e,
            Command::SetShading {
                nodes: s.nodes(),
                shading: Shading::Flat,
            },
        )
    }),
    item("Shade Smooth", ANY_OBJECT, |s, e| {
        exec(
            e,
            Command::SetShading {
                nodes: s.nodes(),
                shading: Shading::Smooth,
            },
        )
    }),
];

/// What the View menu changes in the viewport (written back after the menus).
pub(super) struct ViewChoices<'a> {
    /// What the transform gizmo does.
    pub gizmo_mode: &'a mut bevy::gizmos::transform_gizmo::TransformGizmoMode,
    /// Wireframe and X-ray.
    pub shading: &'a mut hedra_scene::ViewportShading,
    /// Increment snapping and its steps.
    pub snapping: &'a mut hedra_edit::Snapping,
    /// Quad view on.
    pub quad_view: &'a mut bool,
    /// What R and S turn and scale about.
    pub pivot: &'a mut hedra_edit::PivotPoint,
    /// Proportional editing and its falloff and radius.
    pub proportional: &'a mut hedra_edit::Proportional,
    /// The 3D cursor's world position.
    pub cursor: &'a mut DVec3,
}

pub(super) fn menu_bar(
    ui: &mut egui::Ui,
    state: &mut UiState,
    model: &Model,
    menu: &MenuState<'_>,
    view: ViewChoices,
    events: &mut Vec<UiEvent>,
) {
    let ViewChoices {
        gizmo_mode,
        shading,
        snapping,
        proportional,
        pivot,
        quad_view,
        cursor,
    } = view;
    egui::MenuBar::new().ui(ui, |ui| {
        ui.menu_button("File", |ui| {
            draw_menu(ui, FILE_MENU, menu, events);
            ui.menu_button("Export", |ui| {
                for format in hedra_doc::export::ExportFormat::ALL {
                    if ui.button(format.menu_label()).clicked() {
                        events.push(UiEvent::File(FileAction::Export(format)));
                    }
                }
                ui.separator();
                export_option_checkboxes(ui, &mut state.export_options);
            });
            draw_menu(ui, QUIT_MENU, menu, events);
        });
        ui.menu_button("Edit", |ui| {
            draw_menu(ui, EDIT_MENU, menu, events);
            ui.separator();
            ui.checkbox(&mut state.show_history, "Undo History");
            ui.separator();
            // The transform gizmo on objects, mesh elements and control points.
            {
                use bevy::gizmos::transform_gizmo::TransformGizmoMode as Mode;
                ui.radio_value(gizmo_mode, Mode::Translate, "Gizmo: move");
                ui.radio_value(gizmo_mode, Mode::Rotate, "Gizmo: rotate");
                ui.radio_value(gizmo_mode, Mode::Scale, "Gizmo: scale");
            }
            ui.separator();
            if ui.button("Preferences…").clicked() {
                state.show_preferences = true;
            }
        });
        ui.menu_button("Add", |ui| draw_menu(ui, ADD_MENU_ROWS, menu, events));
        if model.mode.node.is_some() {
            ui.menu_button("Mesh", |ui| draw_menu(ui, MESH_MENU, menu, events));
        } else {
            // Object mode: the Mesh menu's one object-level tool.
            ui.menu_button("Mesh", |ui| draw_menu(ui, OBJECT_MESH_MENU, menu, events));
        }
        if let Some(node) = model.shape_edit.node
            && let Some(NodeContent::Curve(_)) =
                model.state.session.doc.node(node).map(|n| &n.content)
        {
            ui.menu_button("Curve", |ui| draw_menu(ui, CURVE_MENU, menu, events));
        }
        ui.menu_button("Object", |ui| draw_menu(ui, OBJECT_MENU, menu, events));
        ui.menu_button("View", |ui| {
            ui.checkbox(&mut state.show_outliner, "Outliner");
            ui.checkbox(&mut state.show_properties, "Properties");
            ui.checkbox(&mut state.show_history, "Undo History");
            ui.separator();
            ui.checkbox(&mut state.show_statistics, "Statistics");
            ui.checkbox(
                &mut shading.wireframe,
                keyed_in(Everywhere, "Wireframe", Action::Wireframe),
            );
            ui.horizontal(|ui| {
                ui.checkbox(
                    &mut shading.x_ray,
                    keyed_in(Everywhere, "X-ray", Action::XRay),
                );
                ui.add(
                    egui::DragValue::new(&mut shading.x_ray_opacity)
                        .range(0..=100)
                        .suffix("% opaque"),
                );
            });
            ui.checkbox(&mut shading.face_orientation, "Face Orientation");
            ui.checkbox(
                &mut shading.cages,
                "Cages (over smoothed and modified meshes)",
            );
            ui.checkbox(
                quad_view,
                keyed_in(Everywhere, "Quad View", Action::QuadView),
            );
            ui.separator();
            ui.checkbox(
                &mut snapping.enabled,
                keyed_in(Everywhere, "Snap", Action::Snapping),
            );
            ui.horizontal(|ui| {
                use hedra_edit::SnapElement;
                ui.label("Snap to");
                // Radio buttons: a combo box's popup would close the menu.
                for e in SnapElement::ALL {
                    ui.radio_value(&mut snapping.element, e, e.label());
                }
            });
            ui.horizontal(|ui| {
                ui.label("Snap step");
                ui.add(
                    egui::DragValue::new(&mut snapping.step)
                        .speed(0.01)
                        .range(0.001..=1000.0),
                );
                ui.label("angle°");
                ui.add(
                    egui::DragValue::new(&mut snapping.angle_step)
                        .speed(0.1)
                        .range(0.1..=180.0),
                );
            });
            ui.separator();
            ui.horizontal(|ui| {
                use hedra_edit::PivotPoint;
                ui.label(keyed_in(Everywhere, "Pivot", Action::PivotPoint));
                for p in [PivotPoint::MedianPoint, PivotPoint::Cursor] {
                    ui.radio_value(pivot, p, p.label());
                }
            });
            ui.checkbox(
                &mut proportional.enabled,
                keyed_in(Edit, "Proportional Editing", Action::Proportional),
            );
            ui.horizontal(|ui| {
                ui.label("Falloff");
                for f in hedra_geom::proportional::Falloff::ALL {
                    ui.radio_value(&mut proportional.falloff, f, f.label());
                }
                ui.label("radius");
                let (lo, hi) = hedra_edit::Proportional::RADIUS_RANGE;
                ui.add(
                    egui::DragValue::new(&mut proportional.radius)
                        .speed(0.01)
                        .range(lo..=hi),
                );
            });
            ui.checkbox(&mut proportional.connected_only, "Connected Only");
            ui.separator();
            // The transform gizmo on objects, mesh elements and control points.
            {
                use bevy::gizmos::transform_gizmo::TransformGizmoMode as Mode;
                ui.radio_value(gizmo_mode, Mode::Translate, "Gizmo: move");
                ui.radio_value(gizmo_mode, Mode::Rotate, "Gizmo: rotate");
                ui.radio_value(gizmo_mode, Mode::Scale, "Gizmo: scale");
            }
            ui.separator();
            if ui.button("Cursor to World Origin").clicked() {
                *cursor = DVec3::ZERO;
                ui.close();
            }
            let selected = selection_center(&model.state.session.doc, &model.selection);
            if ui
                .add_enabled(selected.is_some(), egui::Button::new("Cursor to Selected"))
                .clicked()
            {
                *cursor = selected.unwrap_or(*cursor);
                ui.close();
            }
            ui.label("Shift+right click: place the 3D cursor");
            ui.separator();
            {
                use hedra_edit::bindings::chord_label;
                let frame = [Object, Everywhere]
                    .map(|mode| chord_label(mode, Action::FrameSelected))
                    .join(", ");
                ui.label(format!("Frame selected: {frame}"));
                ui.label(format!(
                    "Frame all: {}",
                    chord_label(Everywhere, Action::FrameAll)
                ));
            }
        });
    });
}

/// File ▸ Export's options, kept for the session: how OBJ writes curves,
/// STEP's unit and whether STEP takes meshes.
fn export_option_checkboxes(ui: &mut egui::Ui, options: &mut hedra_doc::export::ExportOptions) {
    use hedra_doc::step::StepUnits;
    let mut millimetres = options.step.units == StepUnits::Millimetres;
    if ui
        .checkbox(&mut millimetres, "STEP: millimetres")
        .on_hover_text("Lengths × 1000, stated in the file; off: metres, Hedra's units as they are")
        .changed()
    {
        options.step.units = if millimetres {
            StepUnits::Millimetres
        } else {
            StepUnits::Metres
        };
    }
    ui.checkbox(
        &mut options.step.subdivision_as_nurbs,
        "STEP: subdivision meshes as NURBS solids",
    )
    .on_hover_text(
        "Catmull-Clark meshes as their limit surface in NURBS patches, a closed cage as one solid",
    );
    ui.checkbox(&mut options.step.meshes, "STEP: meshes as faceted shells")
        .on_hover_text("Off: STEP holds the NURBS surfaces and curves, and the report counts the meshes left out");
    use hedra_doc::export::CurveExport;
    let mut nurbs = options.curves == CurveExport::FreeForm;
    if ui
        .checkbox(&mut nurbs, "OBJ: curves as NURBS (curv/parm)")
        .on_hover_text("Exact free-form records other CAD programs read; off: polylines")
        .changed()
    {
        options.curves = if nurbs {
            CurveExport::FreeForm
        } else {
            CurveExport::Polylines
        };
    }
}
