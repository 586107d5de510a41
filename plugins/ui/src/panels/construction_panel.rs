//! Surfaces made from curves (issue 20): Object ▸ Surface from Curves makes
//! an extrusion, revolution, sweep, two-rail sweep or loft of the selected
//! curves, a node that remembers them (Rhino's record history); the
//! Properties panel's "Made from curves" section edits its recipe (shown
//! live while a field is dragged, one undo step when let go) and Apply
//! freezes it.

use super::*;
use hedra_doc::construction::{CapEnd, Construction, Output, Recipe, Space};
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
    let items: [(&str, &str, Option<Recipe<NodeRef>>); 7] = [
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
        (
            "Coons Patch",
            "select four curves whose ends close one loop",
            (curves.len() == 4).then(|| Recipe::Coons {
                boundaries: [r(&curves[0]), r(&curves[1]), r(&curves[2]), r(&curves[3])],
            }),
        ),
        (
            "Gordon Surface",
            "select a network: two curves or more each way, every one crossing the others",
            gordon_network(doc, &curves).map(|(u, v)| Recipe::Gordon {
                u_curves: u.iter().map(r).collect(),
                v_curves: v.iter().map(r).collect(),
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
                Recipe::Coons { .. } => "Coons Patch",
                Recipe::Gordon { .. } => "Gordon Surface",
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

/// The selected curves split into a Gordon network's two families: those
/// that cross the first curve run the other way, the rest run with it
/// (crossing: their world polylines of 256 pieces come within 1 % of the
/// network's size). `None` unless each family has two curves or more.
fn gordon_network(doc: &Document, curves: &[NodeId]) -> Option<(Vec<NodeId>, Vec<NodeId>)> {
    use hedra_geom::curves::Curve;
    let polyline = |id: NodeId| -> Option<Vec<DVec3>> {
        let NodeContent::Curve(c) = &doc.node(id)?.content else {
            return None;
        };
        let world = doc.world_matrix(id);
        let c = c.nurbs();
        let (a, b) = c.domain();
        Some(
            (0..=256)
                .map(|i| world.transform_point3(c.point(a + (b - a) * i as f64 / 256.0)))
                .collect(),
        )
    };
    let lines: Vec<Vec<DVec3>> = curves
        .iter()
        .map(|&id| polyline(id))
        .collect::<Option<_>>()?;
    let first = lines.first()?;
    let size = first
        .iter()
        .chain(lines.iter().flatten())
        .fold((DVec3::MAX, DVec3::MIN), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let reach = (size.1 - size.0).length() * 1e-2 + 1e-9;
    // The nearest approach of two polylines, vertex to segment.
    let near = |a: &[DVec3], b: &[DVec3]| {
        a.iter().any(|p| {
            b.windows(2).any(|s| {
                let d = s[1] - s[0];
                let t = ((*p - s[0]).dot(d) / d.length_squared().max(1e-300)).clamp(0.0, 1.0);
                p.distance(s[0] + d * t) < reach
            })
        })
    };
    let (mut u, mut v) = (vec![curves[0]], Vec::new());
    for (id, line) in curves.iter().zip(&lines).skip(1) {
        if near(first, line) {
            v.push(*id);
        } else {
            u.push(*id);
        }
    }
    (u.len() >= 2 && v.len() >= 2).then_some((u, v))
}

/// Object ▸ Make G1 Join: a selected Bézier triangle and a selected patch
/// sharing an edge (seed 002's exercise); the join is kept while either is
/// edited.
pub(super) fn g1_join_items(
    ui: &mut egui::Ui,
    doc: &Document,
    selection: &Selection,
    events: &mut Vec<UiEvent>,
) {
    let is = |id: NodeId, triangle: bool| {
        doc.node(id).is_some_and(|n| match &n.content {
            NodeContent::Surface(s) => {
                matches!(**s, hedra_doc::SurfaceShape::Triangle(_)) == triangle
            }
            _ => false,
        })
    };
    let triangle = selection.nodes.iter().copied().find(|&id| is(id, true));
    let quad = selection.nodes.iter().copied().find(|&id| is(id, false));
    let pair = triangle.zip(quad).filter(|_| selection.nodes.len() == 2);
    if ui
        .add_enabled(pair.is_some(), egui::Button::new("Make G1 Join"))
        .on_disabled_hover_text("Select a Bézier triangle and a Bézier patch that share an edge")
        .clicked()
        && let Some((t, q)) = pair
    {
        exec(
            events,
            Command::MakeG1Join {
                triangle: t.into(),
                quad: q.into(),
            },
        );
        ui.close();
    }
    let joined = selection
        .active()
        .filter(|&id| doc.g1_joins().iter().any(|&(q, t)| q == id || t == id));
    if ui
        .add_enabled(joined.is_some(), egui::Button::new("Break G1 Join"))
        .clicked()
        && let Some(id) = joined
    {
        exec(events, Command::BreakG1Join { node: id.into() });
        ui.close();
    }
}

/// The G1 join a patch or triangle is in: the largest angle between the two
/// patches' normals along the joint, and the point colours' meaning.
pub(super) fn g1_join_panel(ui: &mut egui::Ui, doc: &Document, id: NodeId) {
    let Some((quad, triangle)) = doc
        .g1_joins()
        .into_iter()
        .find(|&(q, t)| q == id || t == id)
    else {
        return;
    };
    let name = |n: NodeId| doc.node(n).map_or(String::new(), |n| n.name.clone());
    ui.separator();
    ui.label(format!(
        "G1 join of '{}' and '{}'",
        name(triangle),
        name(quad)
    ));
    if let Some(report) = doc.g1_report(quad) {
        ui.label(format!(
            "normals along the joint within {:.2e} rad, gap {:.2e}",
            report.max_normal_angle, report.max_gap
        ));
    }
    ui.label(egui::RichText::new("Points: cyan on the joint, violet follow to keep it G1").weak());
}

/// A field's response: whether it is still being dragged or typed in.
const CAPS_HELP: &str = "Close the ends (closed planar profiles): n-gons on a mesh; on a NURBS surface, flat NURBS cap nodes under it (profiles whose centre sees all of them)";

fn busy(r: &egui::Response) -> bool {
    r.dragged() || r.has_focus()
}

/// The recipe's fields; true while one is being dragged or typed in.
fn recipe_fields(
    ui: &mut egui::Ui,
    recipe: &mut Recipe<NodeRef>,
    view_axis: Option<(DVec3, DVec3)>,
    pick_axis: &mut bool,
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
            ui.checkbox(caps, "Caps (closed planar profile)")
                .on_hover_text(CAPS_HELP);
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
                if ui
                    .button("Pick axis")
                    .on_hover_text("Click two points in the viewport: the axis runs through both (world space; snapping as in a move)")
                    .clicked()
                {
                    *pick_axis = true;
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
            ui.checkbox(caps, "Caps at a partial angle")
                .on_hover_text(CAPS_HELP);
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
            ui.checkbox(caps, "Caps").on_hover_text(CAPS_HELP);
        }
        Recipe::Sweep2 { stations, caps, .. } => {
            let r = ui.add(egui::Slider::new(stations, 2..=200).text("stations"));
            held |= busy(&r);
            ui.checkbox(caps, "Caps").on_hover_text(CAPS_HELP);
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
            ui.checkbox(caps, "Caps").on_hover_text(CAPS_HELP);
        }
        Recipe::Coons { .. } => {
            ui.label("Bilinearly blended from its four boundary curves (seed 003)");
        }
        Recipe::Gordon { .. } => {
            ui.label("Through every curve of its network (Gordon 1971)");
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
    if let Output::Cap { end } = made.output {
        let of = node
            .parent
            .and_then(|p| doc.node(p))
            .map_or("its surface".to_string(), |p| format!("'{}'", p.name));
        let end = if end == CapEnd::Start { "start" } else { "end" };
        ui.label(format!(
            "The flat cap at the {end} of {of}: change {of} to change it"
        ));
        if let Some(parent) = node.parent
            && ui.button(format!("Select {of}")).clicked()
        {
            events.push(UiEvent::Select(parent, false));
        }
        return;
    }
    if let Some(found) = doc.sweep_frames(id) {
        // The frames are drawn in the viewport (normal red, binormal green).
        match found.flips.len() {
            0 => ui.label(format!("Frames at {} stations: no flip", found.frames.len())),
            n => ui.colored_label(
                egui::Color32::from_rgb(255, 80, 220),
                format!(
                    "The frame flips at {n} station{} (ringed in the viewport): the profile turns half a turn there; the rotation-minimising frame does not flip",
                    if n == 1 { "" } else { "s" }
                ),
            ),
        };
    }
    let mut pick_axis = false;
    let mut held = recipe_fields(ui, &mut edited.recipe, state.view_axis, &mut pick_axis);
    if pick_axis {
        events.push(UiEvent::Edit(hedra_edit::EditRequest::PickAxis(id)));
    }
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
                    // The node and its caps, as the command would make them.
                    let contents = t
                        .changes
                        .iter()
                        .filter_map(|c| Some((c.id, c.after.as_ref()?.content.clone())))
                        .collect();
                    events.push(UiEvent::PreviewContents(contents));
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
