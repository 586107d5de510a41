//! Surfaces made from curves (issue 20): Object ▸ Surface from Curves makes
//! an extrusion, revolution, sweep, two-rail sweep or loft of the selected
//! curves, a node that remembers them (Rhino's record history); the
//! Properties panel's "Made from curves" section edits its recipe (shown
//! live while a field is dragged, one undo step when let go) and Apply
//! freezes it.

use super::*;
use hedra_doc::construction::{Construction, Output, Recipe, Space};
use hedra_geom::surfaces::sweeps::{FrameKind, Tightness};

/// The curves of the selection, in the order they were selected (the
/// active one last).
fn selected_curves(doc: &Document, selection: &Selection) -> Vec<NodeId> {
    selection
        .nodes
        .iter()
        .copied()
        .filter(|&id| {
            doc.node(id)
                .is_some_and(|n| matches!(n.content, NodeContent::Curve(_)))
        })
        .collect()
}

/// The normal of the plane a curve's control points lie in (Newell's
/// method over the control polygon, closed), in the curve's space; +Z when
/// they make no area.
fn profile_normal(doc: &Document, id: NodeId) -> DVec3 {
    let Some(NodeContent::Curve(c)) = doc.node(id).map(|n| &n.content) else {
        return DVec3::Z;
    };
    let p = c.nurbs().points();
    let mut n = DVec3::ZERO;
    for (i, a) in p.iter().enumerate() {
        let b = p[(i + 1) % p.len()];
        n += DVec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    n.try_normalize().unwrap_or(DVec3::Z)
}

/// Object ▸ Surface from Curves: each recipe on the selected curves, or
/// greyed out with what it needs.
pub(super) fn surface_from_curves_menu(
    ui: &mut egui::Ui,
    doc: &Document,
    selection: &Selection,
    events: &mut Vec<UiEvent>,
) {
    let curves = selected_curves(doc, selection);
    let r = |id: &NodeId| NodeRef::from(*id);
    let one = (curves.len() == 1).then(|| curves[0]);
    let items: [(&str, &str, Option<Recipe<NodeRef>>); 5] = [
        (
            "Extrude",
            "select one curve: it is moved along its plane's normal",
            one.map(|p| Recipe::Extrude {
                profile: r(&p),
                direction: profile_normal(doc, p) * 2.0,
                space: Space::Profile,
                caps: false,
            }),
        ),
        (
            "Revolve",
            "select one curve: it turns about its own Y axis",
            one.map(|p| Recipe::Revolve {
                profile: r(&p),
                origin: DVec3::ZERO,
                axis: DVec3::Y,
                degrees: 360.0,
                pitch: 0.0,
                space: Space::Profile,
                caps: false,
            }),
        ),
        (
            "Sweep",
            "select the profile, then the rail",
            (curves.len() == 2).then(|| Recipe::Sweep {
                profile: r(&curves[0]),
                rail: r(&curves[1]),
                frame: FrameKind::default(),
                stations: 24,
                caps: false,
            }),
        ),
        (
            "Sweep Two Rails",
            "select the profile, then the two rails",
            (curves.len() == 3).then(|| Recipe::Sweep2 {
                profile: r(&curves[0]),
                rails: (r(&curves[1]), r(&curves[2])),
                stations: 24,
                caps: false,
            }),
        ),
        (
            "Loft",
            "select two section curves or more, in order",
            (curves.len() >= 2).then(|| Recipe::Loft {
                sections: curves.iter().map(r).collect(),
                closed: false,
                tightness: Tightness::default(),
                caps: false,
            }),
        ),
    ];
    for (label, needs, recipe) in items {
        let button = ui
            .add_enabled(recipe.is_some(), egui::Button::new(label))
            .on_disabled_hover_text(needs);
        if button.clicked()
            && let Some(recipe) = recipe
        {
            let name = match &recipe {
                Recipe::Extrude { .. } => "Extrusion",
                Recipe::Revolve { .. } => "Revolution",
                Recipe::Sweep { .. } | Recipe::Sweep2 { .. } => "Sweep",
                Recipe::Loft { .. } => "Loft",
            };
            exec(
                events,
                Command::MakeFromCurves {
                    name: name.into(),
                    construction: Construction {
                        recipe,
                        output: Output::Nurbs,
                    },
                },
            );
            ui.close();
        }
    }
}

/// A field's response: whether it is still being dragged or typed in.
fn busy(r: &egui::Response) -> bool {
    r.dragged() || r.has_focus()
}

/// The recipe's fields; true while one is being dragged or typed in.
fn recipe_fields(
    ui: &mut egui::Ui,
    recipe: &mut Recipe<NodeRef>,
    view_axis: Option<(DVec3, DVec3)>,
) -> bool {
    let mut held = false;
    let mut vec3 = |ui: &mut egui::Ui, label: &str, v: &mut DVec3| {
        let r = super::properties::vec3_row(ui, label, v, 0.01);
        held |= busy(&r);
    };
    let space_choice = |ui: &mut egui::Ui, space: &mut Space| {
        ui.horizontal(|ui| {
            ui.label("given in");
            ui.selectable_value(space, Space::Profile, "the profile's space")
                .on_hover_text("moves and turns with the profile");
            ui.selectable_value(space, Space::World, "world space");
        });
    };
    match recipe {
        Recipe::Extrude {
            direction,
            space,
            caps,
            ..
        } => {
            vec3(ui, "Direction", direction);
            space_choice(ui, space);
            ui.checkbox(caps, "Caps (mesh output, closed planar profile)");
        }
        Recipe::Revolve {
            origin,
            axis,
            degrees,
            pitch,
            space,
            caps,
            ..
        } => {
            ui.horizontal(|ui| {
                ui.label("Axis");
                for (v, name) in [(DVec3::X, "X"), (DVec3::Y, "Y"), (DVec3::Z, "Z")] {
                    if ui.selectable_label(*axis == v, name).clicked() {
                        *axis = v;
                    }
                }
                if let Some((through, towards)) = view_axis
                    && ui
                        .button("View axis")
                        .on_hover_text(
                            "About the view direction through the 3D cursor (world space)",
                        )
                        .clicked()
                {
                    *origin = through;
                    *axis = towards;
                    *space = Space::World;
                }
            });
            vec3(ui, "Axis direction", axis);
            vec3(ui, "Axis through", origin);
            space_choice(ui, space);
            let r = ui.add(egui::Slider::new(degrees, -360.0..=360.0).text("angle°"));
            held |= busy(&r);
            let r = ui.add(
                egui::DragValue::new(pitch)
                    .speed(0.01)
                    .prefix("pitch per turn "),
            );
            held |= busy(&r);
            ui.checkbox(caps, "Caps at a partial angle (mesh output)");
        }
        Recipe::Sweep {
            frame,
            stations,
            caps,
            ..
        } => {
            ui.horizontal(|ui| {
                ui.label("Frame");
                ui.selectable_value(frame, FrameKind::RotationMinimizing, "rotation-minimising");
                ui.selectable_value(frame, FrameKind::Frenet, "Frenet (may flip)");
            });
            let r = ui.add(egui::Slider::new(stations, 2..=200).text("stations"));
            held |= busy(&r);
            ui.checkbox(caps, "Caps (mesh output)");
        }
        Recipe::Sweep2 { stations, caps, .. } => {
            let r = ui.add(egui::Slider::new(stations, 2..=200).text("stations"));
            held |= busy(&r);
            ui.checkbox(caps, "Caps (mesh output)");
        }
        Recipe::Loft {
            closed,
            tightness,
            caps,
            ..
        } => {
            ui.checkbox(closed, "Closed (the last section back to the first)");
            ui.horizontal(|ui| {
                ui.label("Through the sections");
                ui.selectable_value(tightness, Tightness::Straight, "straight");
                ui.selectable_value(tightness, Tightness::Loose, "loose");
                ui.selectable_value(tightness, Tightness::Normal, "smooth");
            });
            ui.checkbox(caps, "Caps (mesh output)");
        }
    }
    held
}

/// The "Made from curves" section of a node that remembers its input
/// curves: what made it, its fields, the output kind, Apply.
pub(super) fn construction_panel(
    ui: &mut egui::Ui,
    node: &hedra_doc::Node,
    doc: &Document,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
) {
    let Some(made) = &node.construction else {
        return;
    };
    let id = node.id;
    let names: Vec<String> = made
        .recipe
        .inputs()
        .iter()
        .map(|&&i| {
            doc.node(i)
                .map_or(format!("{i}"), |n| format!("'{}'", n.name))
        })
        .collect();
    ui.label(format!("{} of {}", made.recipe.name(), names.join(", ")));
    ui.label(egui::RichText::new("Follows its curves: edit them and this is made again").weak());
    let stored: Construction<NodeRef> = made
        .map_inputs(|i| Ok::<_, ()>(NodeRef::from(*i)))
        .expect("renaming cannot fail");
    let mut edited = match &state.construction_edit {
        Some((eid, c)) if *eid == id => c.clone(),
        _ => stored.clone(),
    };
    let mut held = recipe_fields(ui, &mut edited.recipe, state.view_axis);
    ui.horizontal(|ui| {
        ui.label("Output");
        let mesh = matches!(edited.output, Output::Mesh { .. });
        if ui.selectable_label(!mesh, "NURBS surface").clicked() {
            edited.output = Output::Nurbs;
        }
        if ui.selectable_label(mesh, "Polygon mesh").clicked() && !mesh {
            edited.output = Output::Mesh {
                segments: 32,
                profile_segments: 16,
            };
        }
    });
    if let Output::Mesh {
        segments,
        profile_segments,
    } = &mut edited.output
    {
        let r = ui.add(egui::Slider::new(segments, 1..=512).text("segments"));
        held |= busy(&r);
        let r = ui.add(egui::Slider::new(profile_segments, 1..=512).text("along the profile"));
        held |= busy(&r);
    }
    if edited != stored {
        let cmd = Command::SetConstruction {
            node: id.into(),
            construction: edited.clone(),
        };
        if held {
            // Live while dragged: the result as the command would make it.
            match doc.decide(&cmd, 0) {
                Ok(t) => {
                    if let Some(after) = t
                        .changes
                        .iter()
                        .find(|c| c.id == id)
                        .and_then(|c| c.after.as_ref())
                    {
                        events.push(UiEvent::PreviewContent(id, after.content.clone()));
                    }
                }
                Err(e) => {
                    ui.colored_label(egui::Color32::LIGHT_RED, e.to_string());
                }
            }
            state.construction_edit = Some((id, edited));
        } else {
            state.construction_edit = None;
            exec(events, cmd);
        }
    } else if !held {
        state.construction_edit = None;
    }
    if ui
        .button("Apply")
        .on_hover_text("Freeze: keep the shape, forget the curves it was made from")
        .clicked()
    {
        exec(
            events,
            Command::ApplyConstruction {
                nodes: vec![id.into()],
            },
        );
    }
}
