//! The Add menu (menu bar and Shift+A): primitives, curves and surfaces,
//! added at the 3D cursor.

use super::*;

/// The transform of a new object: at the 3D cursor.
fn at_cursor(at: DVec3) -> NodeTransform {
    NodeTransform {
        translation: at,
        ..NodeTransform::IDENTITY
    }
}

pub(super) fn add_primitive_buttons(ui: &mut egui::Ui, events: &mut Vec<UiEvent>, at: DVec3) {
    for kind in Primitive::KINDS {
        let p = Primitive::default_of(kind).expect("listed kinds have defaults");
        if ui.button(p.display_name()).clicked() {
            exec(
                events,
                Command::AddPrimitive {
                    primitive: p,
                    name: None,
                    parent: None,
                    transform: at_cursor(at),
                },
            );
            ui.close();
        }
    }
}

/// The active node when it is a curve (for "revolve" / "extrude").
pub(super) fn active_curve(doc: &Document, active: Option<NodeId>) -> Option<NodeId> {
    active.filter(|&id| {
        matches!(
            doc.node(id).map(|n| &n.content),
            Some(NodeContent::Curve(_))
        )
    })
}

/// Curves and surfaces of the Add menu, with small default control nets.
pub(super) fn add_shape_buttons(
    ui: &mut egui::Ui,
    events: &mut Vec<UiEvent>,
    curve: Option<NodeId>,
    at: DVec3,
) {
    use hedra_doc::command::{CurveSpec, SurfaceSpec};
    let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    ui.separator();
    ui.label(egui::RichText::new("Curves").weak());
    if ui
        .button("Draw Curve")
        .on_hover_text("Click control points on a surface or the grid plane; Enter ends")
        .clicked()
    {
        events.push(UiEvent::DrawCurve);
        ui.close();
    }
    let mut add = |ui: &mut egui::Ui, label: &str, enabled: bool, command: Command| {
        if ui.add_enabled(enabled, egui::Button::new(label)).clicked() {
            exec(events, command);
            ui.close();
        }
    };
    let curve_cmd = |name: &str, curve: CurveSpec| Command::AddCurve {
        name: name.into(),
        curve,
        parent: None,
        transform: at_cursor(at),
    };
    let surface_cmd = |name: &str, surface: SurfaceSpec| Command::AddSurface {
        name: name.into(),
        surface,
        parent: None,
        transform: at_cursor(at),
    };

    let wave = vec![
        v(-2.0, 0.0, 0.0),
        v(-1.0, 1.5, 0.0),
        v(0.0, -1.0, 0.0),
        v(1.0, 1.5, 0.0),
        v(2.0, 0.0, 0.0),
    ];
    add(
        ui,
        "Bézier Curve",
        true,
        curve_cmd(
            "Bezier Curve",
            CurveSpec::Bezier {
                points: wave[..4].to_vec(),
            },
        ),
    );
    add(
        ui,
        "NURBS Curve",
        true,
        curve_cmd(
            "NURBS Curve",
            CurveSpec::Nurbs {
                degree: 3,
                points: wave,
                weights: None,
                knots: None,
            },
        ),
    );
    add(
        ui,
        "NURBS Circle",
        true,
        curve_cmd("Circle", CurveSpec::Circle { radius: 1.0 }),
    );
    ui.separator();
    ui.label(egui::RichText::new("Surfaces").weak());
    let mut net = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let (x, z) = (i as f64 - 1.5, j as f64 - 1.5);
            let bump = if (1..3).contains(&i) && (1..3).contains(&j) {
                1.0
            } else {
                0.0
            };
            net.push(v(x, bump, z));
        }
    }
    add(
        ui,
        "Bézier Patch",
        true,
        surface_cmd(
            "Bezier Patch",
            SurfaceSpec::Bezier {
                nu: 4,
                nv: 4,
                points: net.clone(),
            },
        ),
    );
    add(
        ui,
        "NURBS Surface",
        true,
        surface_cmd(
            "NURBS Surface",
            SurfaceSpec::Nurbs {
                degree_u: 3,
                degree_v: 3,
                nu: 4,
                nv: 4,
                points: net,
                weights: None,
                knots_u: None,
                knots_v: None,
            },
        ),
    );
    add(
        ui,
        "NURBS Plane",
        true,
        surface_cmd("Plane", SurfaceSpec::Plane { size: 2.0 }),
    );
    add(
        ui,
        "NURBS Sphere",
        true,
        surface_cmd("Sphere", SurfaceSpec::Sphere { radius: 1.0 }),
    );
    add(
        ui,
        "NURBS Cylinder",
        true,
        surface_cmd(
            "Cylinder",
            SurfaceSpec::Cylinder {
                radius: 1.0,
                height: 2.0,
            },
        ),
    );
    add(
        ui,
        "Bézier Triangle",
        true,
        surface_cmd(
            "Triangle",
            SurfaceSpec::Triangle {
                degree: 2,
                points: vec![
                    v(0.0, 0.0, 2.0),
                    v(-0.5, 0.6, 1.0),
                    v(-1.0, 0.0, 0.0),
                    v(0.5, 0.6, 1.0),
                    v(0.0, 0.6, 0.0),
                    v(1.0, 0.0, 0.0),
                ],
            },
        ),
    );
    let revolve =
        curve.map(|c| surface_cmd("Revolution", SurfaceSpec::Revolve { profile: c.into() }));
    let enabled = revolve.is_some();
    add(
        ui,
        "Revolve Selected Curve",
        enabled,
        revolve.unwrap_or(Command::AddEmpty {
            name: String::new(),
            parent: None,
            transform: NodeTransform::IDENTITY,
        }),
    );
}

pub(super) fn add_menu(
    ctx: &egui::Context,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
    curve: Option<NodeId>,
    at: DVec3,
) {
    let Some(pos) = state.add_menu_at else { return };
    let close = cursor_menu(ctx, ADD_MENU, pos, |ui| {
        ui.label(egui::RichText::new("Add").strong());
        ui.separator();
        let before = events.len();
        add_primitive_buttons(ui, events, at);
        add_shape_buttons(ui, events, curve, at);
        events.len() > before
    });
    if close {
        state.add_menu_at = None;
    }
}

/// The egui id of the Shift+A menu.
pub const ADD_MENU: &str = "add-menu";
