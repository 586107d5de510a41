//! The Add menu (menu bar and Shift+A): primitives, curves and surfaces,
//! added at the 3D cursor, as tables.

use super::menu_table::{ALWAYS, MenuRow, item, with_hover};
use super::*;
use hedra_doc::command::{CurveSpec, SurfaceSpec};
use hedra_geom::curves::kinds::FractalRule;

/// The primitives, one item each (the kernel's list of kinds).
fn primitive_items(ui: &mut egui::Ui, s: &MenuState<'_>, events: &mut Vec<UiEvent>) {
    for kind in Primitive::KINDS {
        let p = Primitive::default_of(kind).expect("listed kinds have defaults");
        if ui.button(p.display_name()).clicked() {
            exec(
                events,
                Command::AddPrimitive {
                    primitive: p,
                    name: None,
                    parent: None,
                    transform: s.at_cursor(),
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

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// The control points most curves start from: a wave along X.
fn wave() -> Vec<DVec3> {
    vec![
        v(-2.0, 0.0, 0.0),
        v(-1.0, 1.5, 0.0),
        v(0.0, -1.0, 0.0),
        v(1.0, 1.5, 0.0),
        v(2.0, 0.0, 0.0),
    ]
}

/// A fractal's initiator: a segment along X.
fn segment() -> Vec<DVec3> {
    vec![v(-2.0, 0.0, 0.0), v(2.0, 0.0, 0.0)]
}

/// A 4 × 4 control net with a bump in the middle.
fn bump_net() -> Vec<DVec3> {
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
    net
}

/// Adds the curve `spec` named `name` at the 3D cursor.
fn add_curve(s: &MenuState<'_>, events: &mut Vec<UiEvent>, name: &str, curve: CurveSpec) {
    exec(
        events,
        Command::AddCurve {
            name: name.into(),
            curve,
            parent: None,
            transform: s.at_cursor(),
        },
    );
}

/// Adds the surface `spec` named `name` at the 3D cursor.
fn add_surface(s: &MenuState<'_>, events: &mut Vec<UiEvent>, name: &str, surface: SurfaceSpec) {
    exec(
        events,
        Command::AddSurface {
            name: name.into(),
            surface,
            parent: None,
            transform: s.at_cursor(),
        },
    );
}

fn fractal(rule: FractalRule, points: Vec<DVec3>, level: u32, closed: bool) -> CurveSpec {
    CurveSpec::Fractal {
        rule,
        points,
        level,
        closed,
        normal: DVec3::Z,
    }
}

/// Add ▸ Curve: drawing by clicks, then every curve kind of the lecture
/// notes with a small default control polygon.
pub(super) const CURVE_ITEMS: &[MenuRow] = &[
    with_hover(
        item("Draw Curve", ALWAYS, |_, e| {
            e.push(UiEvent::Edit(hedra_edit::EditRequest::DrawCurve))
        }),
        "Click control points on a surface or the grid plane; Enter ends",
    ),
    MenuRow::Separator,
    item("Bézier Curve", ALWAYS, |s, e| {
        add_curve(
            s,
            e,
            "Bezier Curve",
            CurveSpec::Bezier {
                points: wave()[..4].to_vec(),
            },
        )
    }),
    item("NURBS Curve", ALWAYS, |s, e| {
        add_curve(
            s,
            e,
            "NURBS Curve",
            CurveSpec::Nurbs {
                degree: 3,
                points: wave(),
                weights: None,
                knots: None,
            },
        )
    }),
    item("NURBS Circle", ALWAYS, |s, e| {
        add_curve(s, e, "Circle", CurveSpec::Circle { radius: 1.0 })
    }),
    item("Lagrange", ALWAYS, |s, e| {
        add_curve(
            s,
            e,
            "Lagrange",
            CurveSpec::Lagrange {
                points: wave(),
                parameterization: Default::default(),
            },
        )
    }),
    item("Cubic Hermite", ALWAYS, |s, e| {
        add_curve(
            s,
            e,
            "Hermite",
            CurveSpec::Hermite {
                points: vec![v(-2.0, 0.0, 0.0), v(0.0, 1.0, 0.0), v(2.0, 0.0, 0.0)],
                tangents: vec![v(2.0, 2.0, 0.0), v(2.0, 0.0, 0.0), v(2.0, -2.0, 0.0)],
            },
        )
    }),
    item("Quintic Hermite", ALWAYS, |s, e| {
        add_curve(
            s,
            e,
            "Quintic Hermite",
            CurveSpec::QuinticHermite {
                points: segment(),
                tangents: vec![v(3.0, 4.0, 0.0), v(3.0, -4.0, 0.0)],
                accelerations: vec![DVec3::ZERO; 2],
            },
        )
    }),
    item("Catmull-Rom", ALWAYS, |s, e| {
        add_curve(
            s,
            e,
            "Catmull-Rom",
            CurveSpec::CatmullRom {
                points: wave(),
                parameterization: Default::default(),
                closed: false,
            },
        )
    }),
    item("Kochanek-Bartels", ALWAYS, |s, e| {
        add_curve(
            s,
            e,
            "Kochanek-Bartels",
            CurveSpec::KochanekBartels {
                points: wave(),
                keys: None,
                closed: false,
            },
        )
    }),
    item("C2 Cubic Spline", ALWAYS, |s, e| {
        add_curve(
            s,
            e,
            "Cubic Spline",
            CurveSpec::CubicSpline {
                points: wave(),
                parameterization: Default::default(),
                ends: Default::default(),
            },
        )
    }),
    item("Chaikin", ALWAYS, |s, e| {
        add_curve(
            s,
            e,
            "Chaikin",
            CurveSpec::Chaikin {
                points: wave(),
                level: 3,
                closed: false,
            },
        )
    }),
    item("Poly-Bézier", ALWAYS, |s, e| {
        add_curve(
            s,
            e,
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
        )
    }),
    item("Koch Curve", ALWAYS, |s, e| {
        add_curve(
            s,
            e,
            "Koch Curve",
            fractal(FractalRule::Koch, segment(), 3, false),
        )
    }),
    item("Koch Snowflake", ALWAYS, |s, e| {
        let h = 3f64.sqrt();
        let triangle = vec![
            v(-1.5, -h / 2.0, 0.0),
            v(0.0, h, 0.0),
            v(1.5, -h / 2.0, 0.0),
        ];
        add_curve(
            s,
            e,
            "Koch Snowflake",
            fractal(FractalRule::Koch, triangle, 3, true),
        )
    }),
    item("Quadratic Koch", ALWAYS, |s, e| {
        add_curve(
            s,
            e,
            "Quadratic Koch",
            fractal(FractalRule::QuadraticKoch, segment(), 2, false),
        )
    }),
];

/// Add ▸ Surface: patches with small default nets, the NURBS primitives,
/// and a revolution of the selected curve (Object ▸ Surface from Curves
/// has the other constructions).
pub(super) const SURFACE_ITEMS: &[MenuRow] = &[
    item("Bézier Patch", ALWAYS, |s, e| {
        add_surface(
            s,
            e,
            "Bezier Patch",
            SurfaceSpec::Bezier {
                nu: 4,
                nv: 4,
                points: bump_net(),
            },
        )
    }),
    item("NURBS Surface", ALWAYS, |s, e| {
        add_surface(
            s,
            e,
            "NURBS Surface",
            SurfaceSpec::Nurbs {
                degree_u: 3,
                degree_v: 3,
                nu: 4,
                nv: 4,
                points: bump_net(),
                weights: None,
                knots_u: None,
                knots_v: None,
            },
        )
    }),
    item("NURBS Plane", ALWAYS, |s, e| {
        add_surface(s, e, "Plane", SurfaceSpec::Plane { size: 2.0 })
    }),
    item("NURBS Sphere", ALWAYS, |s, e| {
        add_surface(s, e, "Sphere", SurfaceSpec::Sphere { radius: 1.0 })
    }),
    item("NURBS Cylinder", ALWAYS, |s, e| {
        add_surface(
            s,
            e,
            "Cylinder",
            SurfaceSpec::Cylinder {
                radius: 1.0,
                height: 2.0,
            },
        )
    }),
    item("Bézier Triangle", ALWAYS, |s, e| {
        add_surface(
            s,
            e,
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
        )
    }),
    item(
        "Revolve Selected Curve",
        |s| match active_curve(s.doc, s.selection.active()) {
            Some(_) => Ok(()),
            None => Err("Select a curve to revolve"),
        },
        |s, e| {
            let Some(curve) = active_curve(s.doc, s.selection.active()) else {
                return;
            };
            exec(
                e,
                Command::MakeFromCurves {
                    name: "Revolution".into(),
                    construction: hedra_doc::construction::Construction {
                        recipe: hedra_doc::construction::Recipe::Revolve {
                            profile: curve.into(),
                            origin: DVec3::ZERO,
                            axis: DVec3::Y,
                            degrees: 360.0,
                            pitch: 0.0,
                            space: Default::default(),
                            caps: false,
                        },
                        output: Default::default(),
                    },
                },
            )
        },
    ),
];

/// The menu bar's Add menu: the primitives, then Curve ▸ and Surface ▸.
pub(super) const ADD_MENU_ROWS: &[MenuRow] = &[
    MenuRow::Listed(primitive_items),
    MenuRow::Separator,
    MenuRow::Submenu("Curve", None, CURVE_ITEMS),
    MenuRow::Submenu("Surface", None, SURFACE_ITEMS),
];

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

/// Shift+A at the pointer: one panel whose page changes (a popup submenu
/// would count as a press outside it).
pub(super) fn add_menu(
    ctx: &egui::Context,
    state: &mut UiState,
    menu: &MenuState<'_>,
    events: &mut Vec<UiEvent>,
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
        match *page {
            AddPage::Main => {
                primitive_items(ui, menu, events);
                ui.separator();
                if ui.button("Curve ⏵").clicked() {
                    *page = AddPage::Curves;
                }
                if ui.button("Surface ⏵").clicked() {
                    *page = AddPage::Surfaces;
                }
            }
            AddPage::Curves | AddPage::Surfaces => {
                if ui.button("⏴ Back").clicked() {
                    *page = AddPage::Main;
                }
                ui.separator();
                let rows = match *page {
                    AddPage::Curves => CURVE_ITEMS,
                    _ => SURFACE_ITEMS,
                };
                draw_menu(ui, rows, menu, events);
            }
        }
        events.len() > before
    });
    if close {
        state.add_menu_at = None;
        state.add_page = AddPage::Main;
    }
}

/// The egui id of the Shift+A menu.
pub const ADD_MENU: &str = "add-menu";
