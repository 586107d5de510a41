//! The Properties panel's modifier stack: Blender's Mirror and Array
//! modifiers on a mesh node, each with its settings, moved up and down,
//! applied or removed; and where subdivision runs among them.

use super::*;
use hedra_doc::{ArrayModifier, DecimateModifier, MeshModifier, MirrorModifier};
use hedra_geom::progressive::DecimateTarget;

/// The node's Mirror and Array modifiers, top to bottom in evaluation
/// order, with Add buttons; every change is one command (one undo step).
pub(super) fn modifier_stack_panel(
    ui: &mut egui::Ui,
    id: NodeId,
    content: &hedra_doc::MeshContent,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
) {
    let node = || NodeRef::from(id);
    ui.horizontal(|ui| {
        ui.label("Add");
        if ui
            .button("Mirror")
            .on_hover_text("Mirror copies across x = 0 of the object (seam welded)")
            .clicked()
        {
            exec(
                events,
                Command::AddModifier {
                    node: node(),
                    modifier: MeshModifier::Mirror(MirrorModifier::default()),
                },
            );
        }
        if ui
            .button("Array")
            .on_hover_text("Copies in a row, one bounding box apart along x")
            .clicked()
        {
            exec(
                events,
                Command::AddModifier {
                    node: node(),
                    modifier: MeshModifier::Array(ArrayModifier::default()),
                },
            );
        }
        if ui
            .button("Decimate")
            .on_hover_text(
                "Fewer faces by edge collapses (quadric error); a slider scrubs every level",
            )
            .clicked()
        {
            exec(
                events,
                Command::AddModifier {
                    node: node(),
                    modifier: MeshModifier::Decimate(DecimateModifier::default()),
                },
            );
        }
    });
    let count = content.modifiers.len();
    for (index, modifier) in content.modifiers.iter().enumerate() {
        ui.separator();
        ui.push_id(("modifier", index), |ui| {
            ui.horizontal(|ui| {
                ui.strong(format!("{}. {}", index + 1, modifier.name()));
                let moved = |to: usize| Command::MoveModifier {
                    node: node(),
                    from: index,
                    to,
                };
                if ui.add_enabled(index > 0, egui::Button::new("▲")).clicked() {
                    exec(events, moved(index - 1));
                }
                if ui
                    .add_enabled(index + 1 < count, egui::Button::new("▼"))
                    .clicked()
                {
                    exec(events, moved(index + 1));
                }
                if ui
                    .add_enabled(index == 0, egui::Button::new("Apply"))
                    .on_hover_text(
                        "Make the top modifier's result the mesh (Blender applies from the top)",
                    )
                    .clicked()
                {
                    exec(
                        events,
                        Command::ApplyModifiers {
                            node: node(),
                            count: Some(1),
                        },
                    );
                }
                if ui.button("Remove").clicked() {
                    exec(
                        events,
                        Command::RemoveModifier {
                            node: node(),
                            index,
                        },
                    );
                }
            });
            let mut edited = *modifier;
            let adjust = match &mut edited {
                MeshModifier::Mirror(m) => {
                    mirror_settings(ui, m);
                    false
                }
                MeshModifier::Array(a) => {
                    array_settings(ui, a);
                    false
                }
                MeshModifier::Decimate(d) => decimate_settings(ui, id, index, content, d, state),
            };
            if edited != *modifier {
                let cmd = Command::SetModifier {
                    node: node(),
                    index,
                    modifier: edited,
                };
                // A drag's later frames adjust its first step: the
                // viewport follows every frame, one undo step in all.
                events.push(UiEvent::Request(if adjust {
                    DocRequest::AdjustLast(cmd)
                } else {
                    DocRequest::Execute(cmd)
                }));
            }
        });
    }
    if let (Some(sub), true) = (content.subdivision, count > 0) {
        ui.separator();
        let mut after = content.subdivision_position();
        ui.horizontal(|ui| {
            ui.label("Subdivision after");
            ui.add(egui::DragValue::new(&mut after).range(0..=count))
                .on_hover_text(
                    "How many of these modifiers run before subdivision (all: mirror, then smooth)",
                );
            ui.label(format!("of {count}"));
        });
        if after != content.subdivision_position() {
            let mut moved = sub;
            moved.stack_position = (after < count).then_some(after);
            exec(
                events,
                Command::SetSubdivision {
                    nodes: vec![node()],
                    modifier: Some(moved),
                },
            );
        }
    }
}

/// Target, level slider and what holds, of a Decimate modifier. The level
/// slider moves through the progressive mesh's levels, the viewport
/// following every frame (the stored record is replayed, never simplified
/// again); the whole drag is one undo step. True when this frame's change
/// continues a drag and should adjust the drag's step rather than add one.
fn decimate_settings(
    ui: &mut egui::Ui,
    id: NodeId,
    index: usize,
    content: &hedra_doc::MeshContent,
    d: &mut DecimateModifier,
    state: &mut UiState,
) -> bool {
    use std::hash::{Hash, Hasher};
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    let settings = DecimateModifier { level: None, ..*d };
    (id, index, format!("{settings:?}")).hash(&mut hasher);
    // The cage is held in the key (compared by identity), so a freed cage's
    // address cannot be taken for the same one.
    let key = (by_address::ByAddress(content.mesh.clone()), hasher.finish());
    if state
        .decimate_counts
        .as_ref()
        .is_none_or(|(k, _)| *k != key)
    {
        let counts = content
            .decimate_face_counts(index)
            .ok()
            .flatten()
            .unwrap_or_default();
        state.decimate_counts = Some((key, counts));
    }
    let counts = state
        .decimate_counts
        .as_ref()
        .map(|(_, c)| c.clone())
        .unwrap_or_default();
    let mut adjust_step = false;
    ui.horizontal(|ui| {
        let mut by_ratio = matches!(d.target, DecimateTarget::Ratio(_));
        ui.radio_value(&mut by_ratio, true, "Ratio");
        ui.radio_value(&mut by_ratio, false, "Faces");
        match (&mut d.target, by_ratio) {
            (DecimateTarget::Ratio(r), true) => {
                ui.add(egui::Slider::new(r, 0.01..=1.0));
            }
            (DecimateTarget::Faces(n), false) => {
                ui.add(egui::DragValue::new(n).range(1..=10_000_000));
            }
            (target, true) => *target = DecimateTarget::Ratio(0.5),
            (target, false) => {
                *target = DecimateTarget::Faces(counts.last().map_or(100, |n| n / 2))
            }
        }
    });
    if let (Some(&least), Some(&most)) = (counts.first(), counts.last()) {
        let shown = d
            .level
            .unwrap_or_else(|| {
                let wanted = match d.target {
                    DecimateTarget::Ratio(r) => (most as f64 * r).round() as usize,
                    DecimateTarget::Faces(n) => n,
                };
                counts.iter().rposition(|&c| c <= wanted).unwrap_or(0)
            })
            .min(counts.len() - 1);
        let mut level = shown;
        let faces = counts[level.min(counts.len() - 1)];
        let r = ui.add(
            egui::Slider::new(&mut level, 0..=counts.len() - 1)
                .text(format!("level · {faces} faces")),
        );
        ui.label(
            egui::RichText::new(format!("{} levels, {least} to {most} faces", counts.len())).weak(),
        );
        let dragging = r.dragged() || r.has_focus();
        let adjust = r.changed() && state.decimate_dragging;
        if r.changed() {
            d.level = Some(level);
            state.decimate_dragging = dragging;
        }
        if !dragging {
            state.decimate_dragging = false;
        }
        adjust_step = adjust;
    }
    ui.horizontal(|ui| {
        ui.checkbox(&mut d.keep_borders, "Keep borders");
        ui.checkbox(&mut d.keep_creases, "Keep creases");
        ui.checkbox(&mut d.keep_uv_seams, "Keep UV seams");
    });
    ui.checkbox(&mut d.keep_quads, "Keep quads")
        .on_hover_text("Each level shown with its triangle pairs joined into quads where they fit");
    adjust_step
}

/// Axes, merge and clipping of a Mirror modifier.
fn mirror_settings(ui: &mut egui::Ui, m: &mut MirrorModifier) {
    ui.horizontal(|ui| {
        ui.label("Axes");
        for (i, axis) in ["X", "Y", "Z"].iter().enumerate() {
            ui.checkbox(&mut m.axes[i], *axis);
        }
    });
    ui.horizontal(|ui| {
        ui.checkbox(&mut m.merge, "Merge");
        ui.add_enabled(
            m.merge,
            egui::DragValue::new(&mut m.merge_distance)
                .speed(0.0005)
                .range(0.0..=10.0)
                .max_decimals(4),
        );
    });
    ui.checkbox(&mut m.clipping, "Clipping")
        .on_hover_text("Vertices on the mirror plane stay on it while you move them");
}

/// Count, offsets and merge of an Array modifier.
fn array_settings(ui: &mut egui::Ui, a: &mut ArrayModifier) {
    ui.horizontal(|ui| {
        ui.label("Count");
        ui.add(egui::DragValue::new(&mut a.count).range(1..=1000));
    });
    for (label, offset, default) in [
        ("Relative offset", &mut a.relative_offset, DVec3::X),
        ("Constant offset", &mut a.constant_offset, DVec3::ZERO),
    ] {
        let mut on = offset.is_some();
        ui.checkbox(&mut on, label);
        match (on, offset.as_mut()) {
            (true, Some(v)) => {
                vec3_row(ui, "", v, 0.01);
            }
            (true, None) => *offset = Some(default),
            (false, _) => *offset = None,
        }
    }
    ui.horizontal(|ui| {
        ui.checkbox(&mut a.merge, "Merge");
        ui.add_enabled(
            a.merge,
            egui::DragValue::new(&mut a.merge_distance)
                .speed(0.0005)
                .range(0.0..=10.0)
                .max_decimals(4),
        );
    });
}
