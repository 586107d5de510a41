//! The Properties panel: transform, primitive, subdivision, curve and surface settings.

use super::*;

pub(super) fn vec3_row(
    ui: &mut egui::Ui,
    label: &str,
    v: &mut DVec3,
    speed: f64,
) -> egui::Response {
    // Shown as 0, not "-0.0" (a quaternion's Euler angles give negative zeros).
    *v = v.map(|c| if c == 0.0 { 0.0 } else { c });
    ui.horizontal(|ui| {
        ui.label(label);
        let mut r = ui.add(
            egui::DragValue::new(&mut v.x)
                .speed(speed)
                .prefix("X ")
                .max_decimals(4),
        );
        r |= ui.add(
            egui::DragValue::new(&mut v.y)
                .speed(speed)
                .prefix("Y ")
                .max_decimals(4),
        );
        r |= ui.add(
            egui::DragValue::new(&mut v.z)
                .speed(speed)
                .prefix("Z ")
                .max_decimals(4),
        );
        r
    })
    .inner
}

pub(super) fn properties(
    ui: &mut egui::Ui,
    model: &Model,
    previewed_transform: Option<NodeTransform>,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
    analysis: &mut (
        hedra_viewport::CurveAnalysis,
        hedra_viewport::SurfaceAnalysis,
    ),
) {
    ui.heading("Properties");
    ui.separator();
    let doc = &model.state.session.doc;
    let Some(id) = model.selection.active() else {
        ui.label("Nothing selected.");
        ui.label("Click an object, or add one with Shift+A.");
        return;
    };
    let Some(node) = doc.node(id) else { return };
    ui.label(egui::RichText::new(&node.name).strong());
    ui.label(format!("{} {}", node.content.kind(), node.id));
    if let Some(p) = node.parent.and_then(|p| doc.node(p)) {
        ui.label(format!("Parent: {}", p.name));
    }
    ui.add_space(6.0);

    egui::CollapsingHeader::new("Transform")
        .default_open(true)
        .show(ui, |ui| {
            let mut t = match &state.transform_edit {
                Some((eid, t)) if *eid == id => *t,
                _ => previewed_transform.unwrap_or(node.transform),
            };
            let (ex, ey, ez) = t.rotation.to_euler(EulerRot::XYZ);
            let mut euler = DVec3::new(ex.to_degrees(), ey.to_degrees(), ez.to_degrees());
            let mut changed = false;
            let mut resp = vec3_row(ui, "Location", &mut t.translation, 0.01);
            changed |= resp.changed();
            let r = vec3_row(ui, "Rotation°", &mut euler, 0.5);
            if r.changed() {
                t.rotation = DQuat::from_euler(
                    EulerRot::XYZ,
                    euler.x.to_radians(),
                    euler.y.to_radians(),
                    euler.z.to_radians(),
                );
                changed = true;
            }
            resp |= r;
            let r = vec3_row(ui, "Scale", &mut t.scale, 0.01);
            changed |= r.changed();
            resp |= r;
            if changed {
                state.transform_edit = Some((id, t));
                events.push(UiEvent::Preview(id, t));
            }
            // A drag or a typed value becomes one step when the field is let go.
            let busy = resp.dragged() || resp.has_focus();
            if !busy
                && let Some((eid, edited)) = state.transform_edit.take()
                && eid == id
                && edited != node.transform
            {
                if edited.is_usable() {
                    exec(
                        events,
                        Command::SetTransforms {
                            nodes: vec![(id.into(), edited)],
                        },
                    );
                } else {
                    events.push(UiEvent::Preview(id, node.transform));
                    events.push(UiEvent::Error(
                        "A scale of zero (or a non-finite value) is not allowed".into(),
                    ));
                }
            }
        });

    if matches!(node.content, NodeContent::Csg(_)) {
        egui::CollapsingHeader::new("CSG")
            .default_open(true)
            .show(ui, |ui| csg_panel(ui, doc, node, events));
    }
    if node.construction.is_some() {
        egui::CollapsingHeader::new("Made from curves")
            .default_open(true)
            .show(ui, |ui| construction_panel(ui, node, doc, state, events));
    }
    if matches!(
        node.content,
        NodeContent::Curve(_) | NodeContent::Surface(_)
    ) {
        egui::CollapsingHeader::new(if matches!(node.content, NodeContent::Curve(_)) {
            "Curve"
        } else {
            "Surface"
        })
        .default_open(true)
        .show(ui, |ui| {
            g1_join_panel(ui, doc, id);
            // What the viewport shows: a control-point drag shows in the
            // measures and fields as it goes.
            let shown = model.shown.shape(id);
            let content = shown.as_ref().unwrap_or(&node.content);
            shape_panel(ui, id, content, model, state, events, analysis)
        });
    }
    if let NodeContent::Kept(kept) = &node.content {
        egui::CollapsingHeader::new("Kept mesh (not manifold)")
            .default_open(true)
            .show(ui, |ui| {
                kept_mesh_panel(ui, id, kept, &mut state.mesh_facts, events)
            });
    }
    if let NodeContent::Mesh(content) = &node.content {
        egui::CollapsingHeader::new("Modifiers")
            .default_open(true)
            .show(ui, |ui| {
                modifier_stack_panel(ui, id, content, state, events)
            });
        egui::CollapsingHeader::new("Subdivision")
            .default_open(true)
            .show(ui, |ui| {
                subdivision_panel(ui, id, content, model, state, events)
            });
    }
    if let (NodeContent::Mesh(content), Some(true)) =
        (&node.content, model.mode.node.map(|n| n == id))
    {
        egui::CollapsingHeader::new("Topology inspector")
            .default_open(true)
            .show(ui, |ui| {
                topology_counts(ui, id, &content.mesh, model, &mut state.mesh_facts);
                topology_inspector(ui, &content.mesh, &model.mode.selection)
            });
    }
    if let NodeContent::Mesh(content) = &node.content {
        egui::CollapsingHeader::new("Mesh")
            .default_open(true)
            .show(ui, |ui| {
                let s = state.mesh_facts.stats(&content.mesh);
                ui.label(format!(
                    "Vertices {}   Edges {}   Faces {}",
                    s.vertices, s.edges, s.faces
                ));
                ui.label(format!(
                    "Euler characteristic {}   {}   boundary loops {}",
                    s.euler_characteristic,
                    if s.closed { "closed" } else { "open" },
                    s.boundary_loops
                ));
                match &s.validation {
                    Ok(()) => ui.label("Half-edge structure valid"),
                    Err(e) => ui.colored_label(egui::Color32::LIGHT_RED, e),
                };
                ui.horizontal(|ui| {
                    ui.label("Shading");
                    for (sh, label) in [(Shading::Flat, "Flat"), (Shading::Smooth, "Smooth")] {
                        if ui.selectable_label(content.shading == sh, label).clicked()
                            && content.shading != sh
                        {
                            exec(
                                events,
                                Command::SetShading {
                                    nodes: vec![id.into()],
                                    shading: sh,
                                },
                            );
                        }
                    }
                });
            });
        if let Some(p) = &content.primitive {
            egui::CollapsingHeader::new(format!("{} parameters", p.display_name()))
                .default_open(true)
                .show(ui, |ui| {
                    let mut edited = p.clone();
                    if primitive_editor(ui, &mut edited) {
                        exec(
                            events,
                            Command::SetPrimitive {
                                node: id.into(),
                                primitive: edited,
                            },
                        );
                    }
                });
        }
    }
}

/// A drop-down choosing one of `options` by its label.
pub(super) fn choice<T: Copy + PartialEq>(
    ui: &mut egui::Ui,
    id: &str,
    value: &mut T,
    options: &[T],
    label: fn(T) -> &'static str,
) {
    egui::ComboBox::from_id_salt(id)
        .selected_text(label(*value))
        .show_ui(ui, |ui| {
            for &o in options {
                ui.selectable_value(value, o, label(o));
            }
        });
}

/// Fields for a primitive's parameters; true when one changed.
pub fn primitive_editor(ui: &mut egui::Ui, p: &mut Primitive) -> bool {
    let mut changed = false;
    let mut len = |ui: &mut egui::Ui, label: &str, v: &mut f64| {
        ui.horizontal(|ui| {
            ui.label(label);
            changed |= ui
                .add(
                    // Above zero and below the kernel's limit.
                    egui::DragValue::new(v)
                        .speed(0.01)
                        .range(f64::EPSILON..=hedra_geom::primitives::MAX_LENGTH)
                        .max_decimals(4),
                )
                .changed();
        });
    };
    let mut count_changed = false;
    // The kernel's ranges, by parameter name.
    let mut count = |ui: &mut egui::Ui, label: &str, v: &mut u32, parameter: &str| {
        let (range, _) = hedra_geom::primitives::count_range(parameter);
        ui.horizontal(|ui| {
            ui.label(label);
            count_changed |= ui
                .add(egui::DragValue::new(v).speed(0.1).range(range))
                .changed();
        });
    };
    match p {
        Primitive::Plane { size } | Primitive::Cube { size } => len(ui, "Size", size),
        Primitive::Grid {
            x_segments,
            z_segments,
            size,
        } => {
            count(ui, "X subdivisions", x_segments, "x_segments");
            count(ui, "Z subdivisions", z_segments, "z_segments");
            len(ui, "Size", size);
        }
        Primitive::UvSphere {
            segments,
            rings,
            radius,
        } => {
            count(ui, "Segments", segments, "segments");
            count(ui, "Rings", rings, "rings");
            len(ui, "Radius", radius);
        }
        Primitive::IcoSphere {
            subdivisions,
            radius,
        } => {
            count(ui, "Subdivisions", subdivisions, "subdivisions");
            len(ui, "Radius", radius);
        }
        Primitive::Cylinder {
            segments,
            radius,
            depth,
        }
        | Primitive::Cone {
            segments,
            radius,
            depth,
        } => {
            count(ui, "Vertices", segments, "segments");
            len(ui, "Radius", radius);
            len(ui, "Depth", depth);
        }
        Primitive::Torus {
            major_segments,
            minor_segments,
            major_radius,
            minor_radius,
        } => {
            count(ui, "Major segments", major_segments, "major_segments");
            count(ui, "Minor segments", minor_segments, "minor_segments");
            len(ui, "Major radius", major_radius);
            len(ui, "Minor radius", minor_radius);
        }
    }
    changed || count_changed
}

/// A kept (non-manifold) mesh: its counts, where it is not manifold, its
/// shading and subdivision (by OpenSubdiv's rules there), and the repair
/// that makes it editable.
fn kept_mesh_panel(
    ui: &mut egui::Ui,
    id: NodeId,
    kept: &hedra_doc::KeptMeshContent,
    facts: &mut crate::MeshFacts,
    events: &mut Vec<UiEvent>,
) {
    let m = &kept.mesh;
    ui.label(format!(
        "Vertices {}   Faces {}   Corners {}",
        m.positions.len(),
        m.faces.len(),
        m.corner_count()
    ));
    for line in facts.places(m).iter() {
        ui.colored_label(egui::Color32::from_rgb(255, 120, 210), line);
    }
    ui.label("Kept as imported: it is drawn, moved, smoothed and exported as it is; editing its elements needs a repair.");
    if ui
        .button("Make Manifold")
        .on_hover_text("Drop the faces a manifold mesh cannot hold and split shared vertices, so that edit mode works")
        .clicked()
    {
        exec(events, Command::MakeManifold { nodes: vec![id.into()] });
    }
    ui.horizontal(|ui| {
        ui.label("Shading");
        for (sh, label) in [(Shading::Flat, "Flat"), (Shading::Smooth, "Smooth")] {
            if ui.selectable_label(kept.shading == sh, label).clicked() && kept.shading != sh {
                exec(
                    events,
                    Command::SetShading {
                        nodes: vec![id.into()],
                        shading: sh,
                    },
                );
            }
        }
    });
    ui.horizontal(|ui| {
        let mut on = kept.subdivision.is_some();
        if ui.checkbox(&mut on, "Subdivision").changed() {
            exec(
                events,
                Command::SetSubdivision {
                    nodes: vec![id.into()],
                    modifier: on.then(|| hedra_doc::SubdivisionModifier::with_level(1)),
                },
            );
        }
        if let Some(modifier) = kept.subdivision {
            let mut level = modifier.viewport_level;
            let drag = ui.add(
                egui::DragValue::new(&mut level)
                    .range(0..=4)
                    .prefix("level "),
            );
            if drag.changed() && level != modifier.viewport_level {
                exec(
                    events,
                    Command::SetSubdivision {
                        nodes: vec![id.into()],
                        modifier: Some(hedra_doc::SubdivisionModifier {
                            viewport_level: level,
                            ..modifier
                        }),
                    },
                );
            }
        }
    });
}
