//! The menu bar: File, Edit, Add, Mesh (in edit mode), Object and View.

use super::*;
use hedra_edit::bindings::{
    Action,
    KeyMode::{Edit, Everywhere, Object},
};

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
    /// The direction the viewport looks (world), the axis Spin turns about.
    pub view_direction: Option<DVec3>,
}

pub(super) fn menu_bar(
    ui: &mut egui::Ui,
    state: &mut UiState,
    model: &Model,
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
        view_direction,
    } = view;
    egui::MenuBar::new().ui(ui, |ui| {
        ui.menu_button("File", |ui| {
            if ui
                .button(keyed_in(Everywhere, "New", Action::NewFile))
                .clicked()
            {
                events.push(UiEvent::File(FileAction::New));
            }
            if ui
                .button(keyed_in(Everywhere, "Open…", Action::OpenFile))
                .clicked()
            {
                events.push(UiEvent::File(FileAction::Open));
            }
            ui.menu_button("Open Recent", |ui| {
                if model.prefs.recent.is_empty() {
                    ui.label("(no recent files)");
                }
                for p in &model.prefs.recent {
                    if ui.button(p.display().to_string()).clicked() {
                        events.push(UiEvent::File(FileAction::OpenPath(p.clone())));
                    }
                }
            });
            ui.menu_button("Open Sample", |ui| {
                let samples = model
                    .samples
                    .as_ref()
                    .map(|d| files::list_samples(&d.0))
                    .unwrap_or_default();
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
                    }
                }
            });
            ui.separator();
            if ui
                .button(keyed_in(Everywhere, "Save", Action::Save))
                .clicked()
            {
                events.push(UiEvent::File(FileAction::Save));
            }
            if ui
                .button(keyed_in(Everywhere, "Save As…", Action::SaveAs))
                .clicked()
            {
                events.push(UiEvent::File(FileAction::SaveAs));
            }
            ui.separator();
            if ui
                .button("Import…")
                .on_hover_text(format!(
                    "Add a file's nodes to the scene: {}",
                    hedra_doc::import::supported_imports()
                ))
                .clicked()
            {
                events.push(UiEvent::File(FileAction::Import));
            }
            ui.menu_button("Export", |ui| {
                for format in hedra_doc::export::ExportFormat::ALL {
                    if ui.button(format.menu_label()).clicked() {
                        events.push(UiEvent::File(FileAction::Export(format)));
                    }
                }
                ui.separator();
                export_option_checkboxes(ui, &mut state.export_options);
            });
            ui.separator();
            if ui
                .button(keyed_in(Everywhere, "Quit", Action::Quit))
                .clicked()
            {
                events.push(UiEvent::File(FileAction::Quit));
            }
        });
        ui.menu_button("Edit", |ui| {
            let h = &model.state.session.history;
            if ui
                .add_enabled(
                    h.can_undo(),
                    egui::Button::new(keyed_in(Everywhere, "Undo", Action::Undo)),
                )
                .clicked()
            {
                events.push(UiEvent::Request(DocRequest::Undo));
            }
            if ui
                .add_enabled(
                    h.can_redo(),
                    egui::Button::new(keyed_in(Everywhere, "Redo", Action::Redo)),
                )
                .clicked()
            {
                events.push(UiEvent::Request(DocRequest::Redo));
            }
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
        let curve = active_curve(&model.state.session.doc, model.selection.active());
        let at = *cursor;
        ui.menu_button("Add", |ui| {
            add_primitive_buttons(ui, events, at);
            add_shape_buttons(ui, events, curve, at, None);
        });
        if let Some(node) = model.mode.node {
            // Spin turns about the view axis through the 3D cursor (Blender),
            // both given to the command in the node's local space.
            let to_local = model.state.session.doc.world_matrix(node).inverse();
            let spin_axis = view_direction.map(|d| {
                (
                    to_local.transform_point3(*cursor),
                    to_local.transform_vector3(d),
                )
            });
            ui.menu_button("Mesh", |ui| {
                let mesh = match model.state.session.doc.node(node).map(|n| &n.content) {
                    Some(NodeContent::Mesh(m)) => Some(m.mesh.clone()),
                    _ => None,
                };
                mesh_menu(ui, node, &model.mode, spin_axis, mesh.as_deref(), events)
            });
        }
        if model.mode.node.is_none() {
            // Object mode: the Mesh menu's one object-level tool.
            ui.menu_button("Mesh", |ui| {
                kept_mesh_items(ui, &model.state.session.doc, &model.selection, events)
            });
        }
        if let Some(node) = model.shape_edit.node
            && let Some(NodeContent::Curve(curve)) =
                model.state.session.doc.node(node).map(|n| &n.content)
        {
            ui.menu_button("Curve", |ui| {
                curve_menu(ui, node, curve, &model.shape_edit.selected, events)
            });
        }
        ui.menu_button("Object", |ui| {
            let sel = model.selection.refs();
            let any = !sel.is_empty();
            if ui
                .add_enabled(
                    any,
                    egui::Button::new(keyed_in(Object, "Duplicate", Action::Duplicate)),
                )
                .clicked()
            {
                exec(events, Command::Duplicate { nodes: sel.clone() });
            }
            if ui
                .add_enabled(
                    any,
                    egui::Button::new(keyed_in(Object, "Delete", Action::Delete)),
                )
                .clicked()
            {
                exec(events, Command::Delete { nodes: sel.clone() });
            }
            if ui
                .add_enabled(
                    any,
                    egui::Button::new(keyed_in(Object, "Hide", Action::Hide)),
                )
                .clicked()
            {
                exec(
                    events,
                    Command::SetVisible {
                        nodes: sel.clone(),
                        visible: false,
                    },
                );
            }
            ui.menu_button("Surface from Curves", |ui| {
                surface_from_curves_menu(ui, &model.state.session.doc, &model.selection, events)
            });
            g1_join_items(ui, &model.state.session.doc, &model.selection, events);
            ui.menu_button("Convert", |ui| {
                convert_items(ui, &model.state.session.doc, &model.selection, events)
            });
            ui.separator();
            ui.label(egui::RichText::new("Boolean").weak());
            boolean_menu(ui, &model.selection, events);
            ui.separator();
            let join = hedra_edit::join_curves_command(&model.state.session.doc, &model.selection);
            if ui
                .add_enabled(
                    join.is_ok(),
                    egui::Button::new(keyed_in(Object, "Join Curves", Action::JoinCurves)),
                )
                .on_disabled_hover_text("Select two curves: the active one comes first")
                .clicked()
                && let Ok(cmd) = join
            {
                exec(events, cmd);
            }
            if ui
                .add_enabled(any, egui::Button::new("Clear Parent"))
                .clicked()
            {
                for r in &sel {
                    exec(
                        events,
                        Command::Reparent {
                            node: r.clone(),
                            parent: None,
                            keep_world: true,
                        },
                    );
                }
            }
            ui.separator();
            if ui
                .add_enabled(any, egui::Button::new("Shade Flat"))
                .clicked()
            {
                exec(
                    events,
                    Command::SetShading {
                        nodes: sel.clone(),
                        shading: Shading::Flat,
                    },
                );
            }
            if ui
                .add_enabled(any, egui::Button::new("Shade Smooth"))
                .clicked()
            {
                exec(
                    events,
                    Command::SetShading {
                        nodes: sel,
                        shading: Shading::Smooth,
                    },
                );
            }
        });
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

/// Object ▸ Convert: To NURBS turns the active mesh's Catmull-Clark limit
/// surface into NURBS surfaces (the cage kept, hidden; Adjust Last sets
/// the tolerance and whether the cage is kept).
fn convert_items(
    ui: &mut egui::Ui,
    doc: &hedra_doc::Document,
    selection: &hedra_edit::Selection,
    events: &mut Vec<UiEvent>,
) {
    use hedra_geom::subdivision::Scheme;
    let active = selection.active().and_then(|id| doc.node(id));
    let why_not = match active.map(|n| &n.content) {
        None => Some("Select a mesh with a Catmull-Clark subdivision modifier"),
        Some(hedra_doc::NodeContent::Mesh(m)) => match &m.subdivision {
            None => Some("The active mesh has no subdivision modifier (Ctrl+1 adds one)"),
            Some(s) if s.options.scheme != Scheme::CatmullClark => {
                Some("Only a Catmull-Clark limit surface converts to NURBS")
            }
            Some(_) => None,
        },
        Some(_) => Some("The active object is not a mesh"),
    };
    if ui
        .add_enabled(why_not.is_none(), egui::Button::new("To NURBS"))
        .on_hover_text(
            "The smooth surface as NURBS patches: exact B-spline surfaces where the cage is regular, \
             fitted patches within 1e-4 of the size elsewhere; the cage is kept, hidden",
        )
        .on_disabled_hover_text(why_not.unwrap_or_default())
        .clicked()
        && let Some(node) = active
    {
        exec(
            events,
            Command::ConvertSubdivisionToNurbs {
                node: hedra_doc::NodeRef::Id(node.id.0),
                tolerance: None,
                keep_cage: true,
            },
        );
    }
}

/// Make Manifold: repairs the selected kept (non-manifold) meshes into
/// editable meshes; disabled, with the reason on hover, when none is
/// selected.
pub(super) fn kept_mesh_items(
    ui: &mut egui::Ui,
    doc: &hedra_doc::Document,
    selection: &Selection,
    events: &mut Vec<UiEvent>,
) {
    let kept: Vec<NodeRef> = selection
        .nodes
        .iter()
        .filter(|id| {
            matches!(
                doc.node(**id).map(|n| &n.content),
                Some(NodeContent::Kept(_))
            )
        })
        .map(|&id| NodeRef::from(id))
        .collect();
    let button = ui
        .add_enabled(!kept.is_empty(), egui::Button::new("Make Manifold"))
        .on_hover_text("Repair meshes kept as imported (not manifold) into editable meshes")
        .on_disabled_hover_text("Select a mesh kept as imported (⚠ in the outliner)");
    if button.clicked() {
        exec(events, Command::MakeManifold { nodes: kept });
        ui.close();
    }
}
