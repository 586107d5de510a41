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

/// Curves and surfaces of the Add menu (Blender's Curve ▸ and Surface ▸
/// submenus), with small default control nets: every curve kind of the
/// lecture notes, then the surfaces.
pub(super) fn add_shape_buttons(
    ui: &mut egui::Ui,
    events: &mut Vec<UiEvent>,
    curve: Option<NodeId>,
    at: DVec3,
    page: Option<&mut AddPage>,
) {
    use hedra_doc::command::{CurveSpec, SurfaceSpec};
    let v = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
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
    let segment = vec![v(-2.0, 0.0, 0.0), v(2.0, 0.0, 0.0)];
    let h = 3f64.sqrt();
    let triangle = vec![
        v(-1.5, -h / 2.0, 0.0),
        v(0.0, h, 0.0),
        v(1.5, -h / 2.0, 0.0),
    ];
    let fractal = |rule, points: Vec<DVec3>, level, closed| CurveSpec::Fractal {
        rule,
        points,
        level,
        closed,
        normal: DVec3::Z,
    };
    use hedra_geom::curves::kinds::FractalRule;
    let curves: Vec<(&str, Command)> = vec![
        (
            "Bézier Curve",
            curve_cmd(
                "Bezier Curve",
                CurveSpec::Bezier {
                    points: wave[..4].to_vec(),
                },
            ),
        ),
        (
            "NURBS Curve",
            curve_cmd(
                "NURBS Curve",
                CurveSpec::Nurbs {
                    degree: 3,
                    points: wave.clone(),
                    weights: None,
                    knots: None,
                },
            ),
        ),
        (
            "NURBS Circle",
            curve_cmd("Circle", CurveSpec::Circle { radius: 1.0 }),
        ),
        (
            "Lagrange",
            curve_cmd(
                "Lagrange",
                CurveSpec::Lagrange {
                    points: wave.clone(),
                    parameterization: Default::default(),
                },
            ),
        ),
        (
            "Cubic Hermite",
            curve_cmd(
                "Hermite",
                CurveSpec::Hermite {
                    points: vec![v(-2.0, 0.0, 0.0), v(0.0, 1.0, 0.0), v(2.0, 0.0, 0.0)],
                    tangents: vec![v(2.0, 2.0, 0.0), v(2.0, 0.0, 0.0), v(2.0, -2.0, 0.0)],
                },
            ),
        ),
        (
            "Quintic Hermite",
            curve_cmd(
                "Quintic Hermite",
                CurveSpec::QuinticHermite {
                    points: segment.clone(),
                    tangents: vec![v(3.0, 4.0, 0.0), v(3.0, -4.0, 0.0)],
                    accelerations: vec![DVec3::ZERO; 2],
                },
            ),
        ),
        (
            "Catmull-Rom",
            curve_cmd(
                "Catmull-Rom",
                CurveSpec::CatmullRom {
                    points: wave.clone(),
                    parameterization: Default::default(),
                    closed: false,
                },
            ),
        ),
        (
            "Kochanek-Bartels",
            curve_cmd(
                "Kochanek-Bartels",
                CurveSpec::KochanekBartels {
                    points: wave.clone(),
                    keys: None,
                    closed: false,
                },
            ),
        ),
        (
            "C2 Cubic Spline",
            curve_cmd(
                "Cubic Spline",
                CurveSpec::CubicSpline {
                    points: wave.clone(),
                    parameterization: Default::default(),
                    ends: Default::default(),
                },
            ),
        ),
        (
            "Chaikin",
            curve_cmd(
                "Chaikin",
                CurveSpec::Chaikin {
                    points: wave.clone(),
                    level: 3,
                    closed: false,
                },
            ),
        ),
        (
            "Poly-Bézier",
            curve_cmd(
                "Poly-Bezier",
                CurveSpec::PolyBezier {
                    points: vec![
                        v(-3.0, 0.0, 0.0),
                        v(-2.0, 1.5, 0.0),
                        v(-1.0, 1.5, 0.0),
                        v(0.0, 0.0, 0.0),
                        v(1.0, -1.5, 0.0),
                        v(2.0, -1.5, 0.0),
                        v(3.0, 0.0, 0.0),
                    ],
                    joins: None,
                    closed: false,
                },
            ),
        ),
        (
            "Koch Curve",
            curve_cmd(
                "Koch Curve",
                fractal(FractalRule::Koch, segment.clone(), 3, false),
            ),
        ),
        (
            "Koch Snowflake",
            curve_cmd(
                "Koch Snowflake",
                fractal(FractalRule::Koch, triangle, 3, true),
            ),
        ),
        (
            "Quadratic Koch",
            curve_cmd(
                "Quadratic Koch",
                fractal(FractalRule::QuadraticKoch, segment, 2, false),
            ),
        ),
    ];
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
    let surfaces: Vec<(&str, Command)> = vec![
        (
            "Bézier Patch",
            surface_cmd(
                "Bezier Patch",
                SurfaceSpec::Bezier {
                    nu: 4,
                    nv: 4,
                    points: net.clone(),
                },
            ),
        ),
        (
            "NURBS Surface",
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
        ),
        (
            "NURBS Plane",
            surface_cmd("Plane", SurfaceSpec::Plane { size: 2.0 }),
        ),
        (
            "NURBS Sphere",
            surface_cmd("Sphere", SurfaceSpec::Sphere { radius: 1.0 }),
        ),
        (
            "NURBS Cylinder",
            surface_cmd(
                "Cylinder",
                SurfaceSpec::Cylinder {
                    radius: 1.0,
                    height: 2.0,
                },
            ),
        ),
        (
            "Bézier Triangle",
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
        ),
    ];
    // A revolution that follows its curve (Object ▸ Surface from Curves
    // has the other constructions).
    let revolve = curve.map(|c| Command::MakeFromCurves {
        name: "Revolution".into(),
        construction: hedra_doc::construction::Construction {
            recipe: hedra_doc::construction::Recipe::Revolve {
                profile: c.into(),
                origin: DVec3::ZERO,
                axis: DVec3::Y,
                degrees: 360.0,
                pitch: 0.0,
                space: Default::default(),
                caps: false,
            },
            output: Default::default(),
        },
    });
    let curve_items = |ui: &mut egui::Ui, events: &mut Vec<UiEvent>| {
        if ui
            .button("Draw Curve")
            .on_hover_text("Click control points on a surface or the grid plane; Enter ends")
            .clicked()
        {
            events.push(UiEvent::Edit(hedra_edit::EditRequest::DrawCurve));
            ui.close();
        }
        ui.separator();
        for (label, command) in curves {
            if ui.button(label).clicked() {
                exec(events, command);
                ui.close();
            }
        }
    };
    let surface_items = |ui: &mut egui::Ui, events: &mut Vec<UiEvent>| {
        for (label, command) in surfaces {
            if ui.button(label).clicked() {
                exec(events, command);
                ui.close();
            }
        }
        if ui
            .add_enabled(
                revolve.is_some(),
                egui::Button::new("Revolve Selected Curve"),
            )
            .clicked()
            && let Some(command) = revolve
        {
            exec(events, command);
            ui.close();
        }
    };
    ui.separator();
    match page {
        // The menu bar's Add menu: egui submenus.
        None => {
            ui.menu_button("Curve", |ui| curve_items(ui, events));
            ui.menu_button("Surface", |ui| surface_items(ui, events));
        }
        // Shift+A at the pointer: one panel whose page changes (a popup
        // submenu would count as a press outside it).
        Some(page) => match *page {
            AddPage::Main => {
                if ui.button("Curve ⏵").clicked() {
                    *page = AddPage::Curves;
                }
                if ui.button("Surface ⏵").clicked() {
                    *page = AddPage::Surfaces;
                }
            }
            AddPage::Curves => curve_items(ui, events),
            AddPage::Surfaces => surface_items(ui, events),
        },
    }
}

/// Which part of the Shift+A menu shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AddPage {
    /// The primitives and the Curve ▸ and Surface ▸ entries.
    #[default]
    Main,
    /// Every curve kind.
    Curves,
    /// Every surface.
    Surfaces,
}

pub(super) fn add_menu(
    ctx: &egui::Context,
    state: &mut UiState,
    events: &mut Vec<UiEvent>,
    curve: Option<NodeId>,
    at: DVec3,
) {
    let Some(pos) = state.add_menu_at else {
        state.add_page = AddPage::Main;
        return;
    };
    let page = &mut state.add_page;
    // Each page is its own area: egui keeps an area's width and wraps new
    // content to it, so the wider Curve and Surface pages would wrap to the
    // first page's width ("Koch Snowflak/e") and be fitted to the window
    // by its height.
    let id = match *page {
        AddPage::Main => ADD_MENU.to_string(),
        other => format!("{ADD_MENU}-{other:?}"),
    };
    let close = cursor_menu(ctx, &id, pos, |ui| {
        ui.label(egui::RichText::new("Add").strong());
        ui.separator();
        let before = events.len();
        if *page == AddPage::Main {
            add_primitive_buttons(ui, events, at);
        } else if ui.button("⏴ Back").clicked() {
            *page = AddPage::Main;
        }
        add_shape_buttons(ui, events, curve, at, Some(page));
        events.len() > before
    });
    if close {
        state.add_menu_at = None;
        state.add_page = AddPage::Main;
    }
}

/// The egui id of the Shift+A menu.
pub const ADD_MENU: &str = "add-menu";
