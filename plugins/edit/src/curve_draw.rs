//! Drawing a curve by clicks (Add ▸ Draw Curve; Rhino's Curve, Blender's
//! curve Draw, Inkscape's pen): each left click puts a point where the
//! pointer is — on the surface of a mesh under it, else on the construction
//! plane (the grid plane facing the view, through the 3D cursor) — snapped
//! like a move when snapping is on. T chooses the kind: control points of a
//! NURBS curve, or points a Catmull-Rom, C2 spline, Lagrange, Hermite or
//! poly-Bézier curve passes through; for the last two a drag from a click
//! pulls the point's tangent out (Inkscape), other points get smooth
//! automatic ones. Backspace takes the last point back, Enter ends
//! (`Command::AddCurve`, one undo step), Esc or a right click cancels.

use crate::bindings::{Action, KeyMode, pressed};
use bevy::prelude::*;
use glam::DVec3;
use hedra_doc::command::CurveSpec;
use hedra_doc::construction::{Recipe, Space};
use hedra_doc::{Command, Document, NodeId, NodeRef, NodeTransform};
use hedra_geom::curves::{Curve, Join};
use hedra_scene::{DocRequest, DocState, InputGate, StatusMessage};

/// The kinds of curve drawing makes, in the order T steps through them.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum DrawKind {
    /// Clicks are control points of a clamped NURBS (cubic, or lower with
    /// fewer points).
    #[default]
    Nurbs,
    /// A Catmull-Rom spline through the clicks.
    CatmullRom,
    /// A Kochanek-Bartels spline through the clicks (tension, bias and
    /// continuity 0 at first: the panel sets them per key).
    KochanekBartels,
    /// The C2 cubic spline through the clicks (natural ends).
    CubicSpline,
    /// The Lagrange polynomial through the clicks.
    Lagrange,
    /// A cubic Hermite spline through the clicks; a drag gives the tangent.
    Hermite,
    /// A quintic Hermite spline through the clicks; a drag gives the
    /// tangent (accelerations 0).
    QuinticHermite,
    /// A chain of cubic Bézier segments through the clicks; a drag pulls
    /// out both handles (a smooth C1 joint).
    PolyBezier,
}

impl DrawKind {
    /// Every kind, in T's order.
    pub const ALL: [DrawKind; 8] = [
        DrawKind::Nurbs,
        DrawKind::CatmullRom,
        DrawKind::KochanekBartels,
        DrawKind::CubicSpline,
        DrawKind::Lagrange,
        DrawKind::Hermite,
        DrawKind::QuinticHermite,
        DrawKind::PolyBezier,
    ];

    /// Its name in the status line.
    pub fn label(self) -> &'static str {
        match self {
            DrawKind::Nurbs => "NURBS (control points)",
            DrawKind::CatmullRom => "Catmull-Rom",
            DrawKind::KochanekBartels => "Kochanek-Bartels",
            DrawKind::QuinticHermite => "quintic Hermite (drag: tangent)",
            DrawKind::CubicSpline => "C2 cubic spline",
            DrawKind::Lagrange => "Lagrange",
            DrawKind::Hermite => "cubic Hermite (drag: tangent)",
            DrawKind::PolyBezier => "poly-Bézier (drag: handles)",
        }
    }

    /// The kind after this one (T).
    pub fn next(self) -> DrawKind {
        let i = DrawKind::ALL.iter().position(|&k| k == self).unwrap_or(0);
        DrawKind::ALL[(i + 1) % DrawKind::ALL.len()]
    }

    /// True when a drag from a click sets the point's tangent.
    pub fn takes_tangents(self) -> bool {
        matches!(
            self,
            DrawKind::Hermite | DrawKind::QuinticHermite | DrawKind::PolyBezier
        )
    }

    /// The curve through (or controlled by) `points`, with the dragged
    /// tangents where given (a Bézier handle's reach: the tangent over 3),
    /// relative to `origin`.
    pub fn spec(self, points: &[DVec3], handles: &[Option<DVec3>], origin: DVec3) -> CurveSpec {
        let local: Vec<DVec3> = points.iter().map(|p| *p - origin).collect();
        match self {
            DrawKind::Nurbs => CurveSpec::Nurbs {
                degree: CurveDraw::degree(points.len()),
                points: local,
                weights: None,
                knots: None,
            },
            DrawKind::CatmullRom => CurveSpec::CatmullRom {
                points: local,
                parameterization: Default::default(),
                closed: false,
            },
            DrawKind::KochanekBartels => CurveSpec::KochanekBartels {
                points: local,
                keys: None,
                closed: false,
            },
            DrawKind::QuinticHermite => CurveSpec::QuinticHermite {
                // The Bézier handle of a quintic reaches a fifth of the
                // tangent (unit parameter spans).
                tangents: (0..points.len())
                    .map(|i| handle_reach(points, handles, i) * 5.0)
                    .collect(),
                accelerations: vec![DVec3::ZERO; points.len()],
                points: local,
            },
            DrawKind::CubicSpline => CurveSpec::CubicSpline {
                points: local,
                parameterization: Default::default(),
                ends: Default::default(),
            },
            DrawKind::Lagrange => CurveSpec::Lagrange {
                points: local,
                parameterization: Default::default(),
            },
            DrawKind::Hermite => CurveSpec::Hermite {
                tangents: (0..points.len())
                    .map(|i| handle_reach(points, handles, i) * 3.0)
                    .collect(),
                points: local,
            },
            DrawKind::PolyBezier => {
                let n = local.len();
                let mut chain = Vec::with_capacity(3 * n);
                for (i, &p) in local.iter().enumerate() {
                    let reach = handle_reach(points, handles, i);
                    if i > 0 {
                        chain.push(p - reach);
                    }
                    chain.push(p);
                    if i + 1 < n {
                        chain.push(p + reach);
                    }
                }
                CurveSpec::PolyBezier {
                    points: chain,
                    joins: Some(vec![Join::C1; n.saturating_sub(2)]),
                    closed: false,
                }
            }
        }
    }
}

/// Point `i`'s outgoing Bézier handle as a vector: the dragged one, else
/// the Catmull-Rom tangent over 3 ((p₊ − p₋)/6; an end's chord over 3).
fn handle_reach(points: &[DVec3], handles: &[Option<DVec3>], i: usize) -> DVec3 {
    if let Some(Some(h)) = handles.get(i) {
        return *h;
    }
    let n = points.len();
    match (i.checked_sub(1), (i + 1 < n).then_some(i + 1)) {
        (Some(a), Some(b)) => (points[b] - points[a]) / 6.0,
        (None, Some(b)) => (points[b] - points[i]) / 3.0,
        (Some(a), None) => (points[i] - points[a]) / 3.0,
        (None, None) => DVec3::ZERO,
    }
}

/// What the status line says while drawing.
const AXIS_HELP: &str = "Pick axis: click a point of the axis, then a second one along it (Ctrl snaps, as in a move) · Esc cancels";

fn draw_help(kind: DrawKind) -> String {
    format!(
        "Draw {}: click points (on a surface or the grid plane; snapping applies) · \
         T next kind · Backspace removes the last · Enter ends · Esc cancels",
        kind.label()
    )
}

/// The running curve drawing.
#[derive(Resource, Debug, Default, Clone, PartialEq)]
pub struct CurveDraw {
    /// Drawing: object picking and shortcuts ignore the input.
    pub active: bool,
    /// What the clicks make.
    pub kind: DrawKind,
    /// The clicked points, world space.
    pub points: Vec<DVec3>,
    /// Each point's dragged Bézier handle (outgoing, world vector), if
    /// dragged (Hermite and poly-Bézier).
    pub handles: Vec<Option<DVec3>>,
    /// The last click's screen position while its button is held (a drag
    /// from it pulls the tangent).
    pub held: Option<Vec2>,
    /// The curve through the points and the one the pointer would add, as
    /// a polyline in world space, for drawing.
    pub drawn: Vec<DVec3>,
    /// The point the pointer would add now.
    pub hover: Option<DVec3>,
    /// The frame that ended the drawing (its click or key is spent).
    pub just_finished: bool,
    /// Clicking the two points of a revolution's axis instead of a curve
    /// (the *Pick axis* button of a revolution made from curves): the node.
    pub axis_of: Option<NodeId>,
}

impl CurveDraw {
    /// Starts drawing (Add ▸ Draw Curve), of the kind drawn last.
    pub fn start(&mut self, status: &mut StatusMessage) {
        *self = CurveDraw {
            active: true,
            kind: self.kind,
            ..default()
        };
        status.info(draw_help(self.kind));
    }

    /// Starts picking the axis of the revolution `node` by two clicked
    /// points (snapped as a move is).
    pub fn start_axis(&mut self, node: NodeId, status: &mut StatusMessage) {
        *self = CurveDraw {
            active: true,
            kind: self.kind,
            axis_of: Some(node),
            ..default()
        };
        status.info(AXIS_HELP);
    }

    /// Ends the drawing, keeping the kind for the next one.
    fn finish(&mut self) {
        *self = CurveDraw {
            just_finished: true,
            kind: self.kind,
            ..default()
        };
    }

    /// The degree a curve through `n` control points gets: cubic, or less
    /// when there are too few points for it.
    pub fn degree(n: usize) -> usize {
        n.saturating_sub(1).clamp(1, 3)
    }
}

/// The plane the points go on when no surface is under the pointer: through
/// `through`, facing the world axis nearest the view direction (the top
/// view draws on the ground, the front view on the XY plane).
pub fn construction_plane(view_dir: DVec3, through: DVec3) -> (DVec3, DVec3) {
    let a = view_dir.abs();
    let normal = if a.y >= a.x && a.y >= a.z {
        DVec3::Y
    } else if a.z >= a.x {
        DVec3::Z
    } else {
        DVec3::X
    };
    (through, normal)
}

/// Runs the drawing: the point under the pointer, clicks, keys, the end.
#[allow(clippy::too_many_arguments)]
pub fn drive_curve_draw(
    mut draw: ResMut<CurveDraw>,
    keys: Res<ButtonInput<KeyCode>>,
    buttons: Res<ButtonInput<MouseButton>>,
    gate: Res<InputGate>,
    viewport: hedra_scene::ViewportPointer,
    state: Res<DocState>,
    cursor_3d: Res<hedra_scene::Cursor3d>,
    snapping: Res<crate::Snapping>,
    mut snap_target: ResMut<crate::SnapTarget>,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<StatusMessage>,
) {
    let (window, camera) = (viewport.window(), viewport.camera());
    draw.just_finished = false;
    if !draw.active {
        return;
    }
    let tool_key = |action| pressed(&keys, KeyMode::Tool, action);
    if tool_key(Action::Cancel) || buttons.just_pressed(MouseButton::Right) {
        draw.finish();
        status.info("Draw curve cancelled");
        return;
    }
    if tool_key(Action::RemoveLastPoint) {
        draw.points.pop();
        draw.handles.pop();
    }
    if tool_key(Action::NextCurveKind) && draw.axis_of.is_none() {
        draw.kind = draw.kind.next();
        status.info(draw_help(draw.kind));
    }
    let (cam, cam_t) = camera;
    let doc = &state.session.doc;
    let pointer = window.cursor_position();
    let ray = pointer.and_then(|c| viewport.ray_at(c));
    let view_dir = (cam_t.rotation() * Vec3::NEG_Z).as_dvec3();
    let to_screen = |p: DVec3| cam.world_to_viewport(cam_t, p.as_vec3()).ok();
    let mut scene = crate::SnapScene::of_document(doc, |_| true);
    scene.points.extend(draw.points.iter().copied());
    let element_target = match (pointer, snapping.active(&keys), snapping.element) {
        (Some(c), true, element) => scene.target(element, c, ray, &to_screen),
        _ => None,
    };
    snap_target.0 = element_target;
    draw.hover = element_target.or_else(|| {
        let (o, d) = ray?;
        if let Some((_, dist)) = crate::pick_node(doc, o, d) {
            return Some(o + d.normalize() * dist);
        }
        let (through, normal) = construction_plane(view_dir, cursor_3d.0);
        let denom = d.dot(normal);
        let t = (through - o).dot(normal) / denom;
        if denom.abs() < 1e-12 || t <= 0.0 {
            return None;
        }
        let p = o + d * t;
        // Increments: whole steps within the plane.
        let round = |x: f64| crate::Snapping::round(snapping.active(&keys), x, snapping.step);
        Some(if normal == DVec3::Y {
            DVec3::new(round(p.x), p.y, round(p.z))
        } else if normal == DVec3::Z {
            DVec3::new(round(p.x), round(p.y), p.z)
        } else {
            DVec3::new(p.x, round(p.y), round(p.z))
        })
    });
    if gate.pointer_free && buttons.just_pressed(MouseButton::Left) {
        match draw.hover {
            Some(p) => {
                draw.points.push(p);
                draw.handles.push(None);
                draw.held = pointer;
            }
            None => status.error("Draw curve: point at a surface or the grid plane"),
        }
    }
    // A drag from the last click pulls its tangent out, on the plane
    // through the point facing the view.
    if let (Some(from), Some(now)) = (draw.held, pointer) {
        let last = *draw.points.last().expect("a held click has its point");
        let pulled = ray.and_then(|(o, d)| {
            let denom = d.dot(view_dir);
            let t = (last - o).dot(view_dir) / denom;
            (denom.abs() > 1e-12 && t > 0.0).then(|| o + d * t - last)
        });
        if draw.kind.takes_tangents() && from.distance(now) > 4.0 {
            *draw.handles.last_mut().expect("one per point") = pulled;
        }
        if !buttons.pressed(MouseButton::Left) {
            draw.held = None;
        }
    }
    if let Some(node) = draw.axis_of {
        draw.drawn.clear();
        if let [from, to] = draw.points[..] {
            draw.finish();
            if let Some(cmd) = axis_command(&state.session.doc, node, from, to) {
                requests.write(DocRequest::Execute(cmd));
            } else {
                status.error("Pick axis: the two points must differ");
            }
        }
        return;
    }
    let hovering = draw.held.is_none().then_some(draw.hover).flatten();
    let with_hover: Vec<DVec3> = draw.points.iter().chain(hovering.iter()).copied().collect();
    draw.drawn = preview(draw.kind, &with_hover, &draw.handles);
    if !keys.any_just_pressed([KeyCode::Enter, KeyCode::NumpadEnter]) {
        return;
    }
    let points = std::mem::take(&mut draw.points);
    let handles = std::mem::take(&mut draw.handles);
    let kind = draw.kind;
    draw.finish();
    if points.len() < 2 {
        status.error("Draw curve: click two points or more before Enter");
        return;
    }
    // The node's origin is the 3D cursor, as for every added object.
    let origin = cursor_3d.0;
    let spec = kind.spec(&points, &handles, origin);
    if let Err(e) = spec.curve() {
        status.error(format!("Draw curve: {e}"));
        return;
    }
    requests.write(DocRequest::Execute(Command::AddCurve {
        name: "Curve".into(),
        curve: spec,
        parent: None,
        transform: NodeTransform::from_translation(origin),
    }));
}

/// The command that puts the axis of the revolution `node` through `from`
/// and `to` (world space); `None` for two equal points or a node that is
/// not a revolution made from curves.
pub fn axis_command(doc: &Document, node: NodeId, from: DVec3, to: DVec3) -> Option<Command> {
    let direction = (to - from).try_normalize()?;
    let made = doc.node(node)?.construction.as_ref()?;
    let mut c = made.map_inputs(|i| Ok::<_, ()>(NodeRef::from(*i))).ok()?;
    let Recipe::Revolve {
        origin,
        axis,
        space,
        ..
    } = &mut c.recipe
    else {
        return None;
    };
    *origin = from;
    *axis = direction;
    *space = Space::World;
    Some(Command::SetConstruction {
        node: node.into(),
        construction: c,
    })
}

/// The curve `kind` makes of `points` as a polyline of 32 samples a span
/// (the points themselves while they make no curve yet).
fn preview(kind: DrawKind, points: &[DVec3], handles: &[Option<DVec3>]) -> Vec<DVec3> {
    let curve = (points.len() >= 2)
        .then(|| {
            kind.spec(points, handles, DVec3::ZERO)
                .curve()
                .ok()?
                .to_nurbs()
                .ok()
        })
        .flatten();
    let Some(form) = curve else {
        return points.to_vec();
    };
    let (a, b) = form.curve.domain();
    let samples = 32 * points.len();
    let params: Vec<f64> = (0..=samples)
        .map(|i| a + (b - a) * i as f64 / samples as f64)
        .collect();
    form.curve.points_at(&params)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plane_faces_the_nearest_axis_through_the_cursor() {
        let through = DVec3::new(1.0, 2.0, 3.0);
        assert_eq!(
            construction_plane(DVec3::new(0.1, -0.9, 0.2), through),
            (through, DVec3::Y)
        );
        assert_eq!(construction_plane(DVec3::NEG_Z, through).1, DVec3::Z);
        assert_eq!(
            construction_plane(DVec3::new(-1.0, 0.2, 0.3), through).1,
            DVec3::X
        );
    }

    #[test]
    fn drawn_kinds_pass_through_the_clicks_and_keep_dragged_tangents() {
        let clicks = [
            DVec3::ZERO,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(3.0, 1.0, 0.0),
        ];
        let dragged = [None, Some(DVec3::new(0.5, 0.0, 0.0)), None, None];
        for kind in DrawKind::ALL {
            let curve = kind.spec(&clicks, &dragged, DVec3::ZERO).curve().unwrap();
            let form = curve.to_nurbs().unwrap().curve;
            let (a, b) = form.domain();
            let near = |p: DVec3| {
                (0..=3000)
                    .map(|i| form.point(a + (b - a) * i as f64 / 3000.0).distance(p))
                    .fold(f64::MAX, f64::min)
            };
            for p in clicks {
                let expected = if kind == DrawKind::Nurbs { 1.0 } else { 1e-3 };
                assert!(near(p) < expected, "{kind:?} misses {p}");
            }
            if kind.takes_tangents() {
                // At the dragged point the curve runs along the drag.
                let t = curve.on_curve_parameter(if kind == DrawKind::PolyBezier { 3 } else { 1 });
                let d = form.derivatives(t.unwrap())[1];
                assert!(d.normalize().distance(DVec3::X) < 1e-9, "{kind:?}: {d}");
            }
        }
        assert_eq!(DrawKind::PolyBezier.next(), DrawKind::Nurbs);
    }

    #[test]
    fn cubic_once_there_are_four_points() {
        assert_eq!([2, 3, 4, 9].map(CurveDraw::degree), [1, 2, 3, 3]);
    }
}
