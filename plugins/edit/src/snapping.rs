//! Increment snapping (Blender's Shift+Tab, and Ctrl held during a drag
//! to invert it): moves go in whole grid steps, rotations in angle steps,
//! scales in factor steps. Typed values are exact and never snapped.
//! The one place that turns a drag into a translation, for the object,
//! mesh and control-point tools alike.

use crate::modal::Axis;
use bevy::prelude::*;
use glam::DVec3;
use hedra_scene::modifiers::ctrl;

/// What a move snaps to (Blender's snap target element).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum SnapElement {
    /// Whole steps of [`Snapping::step`].
    #[default]
    Increment,
    /// In mesh edit mode: the moved vertex nearest the target lands exactly
    /// on the mesh vertex nearest the pointer (within
    /// [`VERTEX_SNAP_PIXELS`]); elsewhere, increments.
    Vertex,
    /// In mesh edit mode: onto the point of an edge nearest the pointer's
    /// ray (Blender's Edge), within [`VERTEX_SNAP_PIXELS`].
    Edge,
    /// In mesh edit mode: onto the middle of the edge nearest the pointer
    /// (Blender's Edge Center).
    EdgeCenter,
    /// In mesh edit mode: onto the surface under the pointer (Blender's
    /// Face Project), the moved faces left out.
    Face,
}

impl SnapElement {
    /// Every element, in menu order.
    pub const ALL: [SnapElement; 5] = [
        SnapElement::Increment,
        SnapElement::Vertex,
        SnapElement::Edge,
        SnapElement::EdgeCenter,
        SnapElement::Face,
    ];

    /// The name the View menu shows.
    pub fn label(self) -> &'static str {
        match self {
            SnapElement::Increment => "Increment",
            SnapElement::Vertex => "Vertex",
            SnapElement::Edge => "Edge",
            SnapElement::EdgeCenter => "Edge Center",
            SnapElement::Face => "Face",
        }
    }
}

/// How near the pointer (logical pixels) a vertex must be to snap to it.
pub const VERTEX_SNAP_PIXELS: f32 = 20.0;

/// Where the running move snapped to this frame (world), for drawing.
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq)]
pub struct SnapTarget(pub Option<DVec3>);

/// Whether and how the transform tools snap.
#[derive(Resource, Debug, Clone, Copy, PartialEq)]
pub struct Snapping {
    /// Snapping is on (Shift+Tab, View ▸ Snap); Ctrl held inverts it.
    pub enabled: bool,
    /// What moves snap to.
    pub element: SnapElement,
    /// The move step in world units (the grid's cell is 1).
    pub step: f64,
    /// The rotation step in degrees (Blender's 5°).
    pub angle_step: f64,
    /// The scale step (0.1).
    pub scale_step: f64,
}

impl Default for Snapping {
    fn default() -> Self {
        Snapping {
            enabled: false,
            element: SnapElement::Increment,
            step: 1.0,
            angle_step: 5.0,
            scale_step: 0.1,
        }
    }
}

impl Snapping {
    /// Snapping applies now: on and Ctrl not held, or off and Ctrl held.
    pub fn active(&self, keys: &ButtonInput<KeyCode>) -> bool {
        self.enabled != ctrl(keys)
    }

    /// `value` to the nearest multiple of `step` when snapping is active.
    pub fn round(active: bool, value: f64, step: f64) -> f64 {
        if active && step > 0.0 {
            (value / step).round() * step
        } else {
            value
        }
    }
}

/// The world translation of a drag from `start` to `cursor` (window
/// coordinates) on the plane through `pivot` facing the view, along `axis`
/// when one is set, each component snapped to `step` when given.
pub fn drag_translation(
    start: Vec2,
    cursor: Vec2,
    pivot: DVec3,
    view_dir: DVec3,
    axis: Option<Axis>,
    ray_at: &dyn Fn(Vec2) -> Option<(DVec3, DVec3)>,
    step: Option<f64>,
) -> DVec3 {
    let plane_hit = |p: Vec2| -> Option<DVec3> {
        let (o, d) = ray_at(p)?;
        let denom = d.dot(view_dir);
        (denom.abs() > 1e-12).then(|| o + d * ((pivot - o).dot(view_dir) / denom))
    };
    let delta = match (plane_hit(start), plane_hit(cursor)) {
        (Some(a), Some(b)) => {
            let d = b - a;
            axis.map_or(d, |ax| ax.vector() * d.dot(ax.vector()))
        }
        _ => DVec3::ZERO,
    };
    match step {
        Some(s) => DVec3::new(
            Snapping::round(true, delta.x, s),
            Snapping::round(true, delta.y, s),
            Snapping::round(true, delta.z, s),
        ),
        None => delta,
    }
}

/// Shift+Tab toggles snapping (outside a running tool, as Blender).
pub fn snapping_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<hedra_scene::InputGate>,
    mut snapping: ResMut<Snapping>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    if gate.keyboard_free && hedra_scene::modifiers::shift(&keys) && keys.just_pressed(KeyCode::Tab)
    {
        snapping.enabled = !snapping.enabled;
        status.info(if snapping.enabled {
            "Snapping on: moves in grid steps, rotations in 5°, scales in 0.1 (Ctrl inverts; Shift+Tab off)"
        } else {
            "Snapping off (Shift+Tab on; Ctrl snaps during a drag)"
        });
    }
}

/// How a running move is snapped this frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MoveSnap {
    /// No snapping: the drag as it is.
    Free,
    /// Each component of the drag to whole multiples of the step.
    Increment(f64),
    /// This exact world translation (a vertex onto a vertex).
    To(DVec3),
}

/// Snapping of a move of `moved` onto an element of `mesh` (placed by
/// `world`) other than the moved ones: the target point by `element`
/// (vertex, edge point, edge centre or surface point under the pointer,
/// see [`SnapElement`]), the base the moved vertex nearest it (Blender's
/// "closest"); returns the target and the translation from base to
/// target, in world space. Increments give `None` (they are not a target).
pub fn element_snap(
    element: SnapElement,
    mesh: &hedra_geom::HalfEdgeMesh,
    world: glam::DMat4,
    moved: &std::collections::BTreeSet<hedra_geom::VertexId>,
    cursor: Vec2,
    ray: Option<(DVec3, DVec3)>,
    to_screen: &dyn Fn(DVec3) -> Option<Vec2>,
) -> Option<(DVec3, DVec3)> {
    let untouched = |vs: &[hedra_geom::VertexId]| vs.iter().all(|v| !moved.contains(v));
    let nearest_on_screen = |points: &mut dyn Iterator<Item = DVec3>| {
        points
            .filter_map(|p| {
                let d = to_screen(p)?.distance(cursor);
                (d <= VERTEX_SNAP_PIXELS).then_some((d, p))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, p)| p)
    };
    let edges = || {
        mesh.edges()
            .filter(move |&e| untouched(&mesh.edge_vertices(e)))
            .map(move |e| {
                mesh.edge_vertices(e)
                    .map(|v| world.transform_point3(mesh.position(v)))
            })
    };
    let target = match element {
        SnapElement::Increment => return None,
        SnapElement::Vertex => return vertex_snap(mesh, world, moved, cursor, to_screen),
        SnapElement::EdgeCenter => nearest_on_screen(&mut edges().map(|[a, b]| a.lerp(b, 0.5)))?,
        SnapElement::Edge => {
            let (o, d) = ray?;
            // The point of each edge nearest the pointer's ray.
            nearest_on_screen(&mut edges().map(|[a, b]| closest_on_segment(a, b, o, d)))?
        }
        SnapElement::Face => {
            let (o, d) = ray?;
            let to_local = world.inverse();
            let (lo, ld) = (to_local.transform_point3(o), to_local.transform_vector3(d));
            let t = mesh
                .faces()
                .filter(|&f| untouched(&mesh.face_vertices(f).collect::<Vec<_>>()))
                .flat_map(|f| hedra_geom::query::triangulate_face(mesh, f))
                .filter_map(|[a, b, c]| {
                    let p = |v| mesh.position(v);
                    hedra_geom::query::ray_triangle(lo, ld, p(a), p(b), p(c))
                })
                .min_by(|a, b| a.total_cmp(b))?;
            world.transform_point3(lo + ld * t)
        }
    };
    let base = moved
        .iter()
        .map(|&v| world.transform_point3(mesh.position(v)))
        .min_by(|a, b| a.distance(target).total_cmp(&b.distance(target)))?;
    Some((target, target - base))
}

/// The point of segment `a`–`b` nearest the line through `o` along `d`.
fn closest_on_segment(a: DVec3, b: DVec3, o: DVec3, d: DVec3) -> DVec3 {
    // Closest points of two lines (Ericson, Real-Time Collision Detection
    // 5.1.8), the segment's parameter clamped to [0, 1].
    let u = b - a;
    let w = a - o;
    let (uu, ud, dd) = (u.dot(u), u.dot(d), d.dot(d));
    let (uw, dw) = (u.dot(w), d.dot(w));
    let denom = uu * dd - ud * ud;
    let s = if denom.abs() < 1e-15 {
        0.0
    } else {
        ((ud * dw - dd * uw) / denom).clamp(0.0, 1.0)
    };
    a + u * s
}

/// Vertex snapping for a move of `moved` (local ids of `mesh`, placed by
/// `world`): the mesh vertex outside `moved` nearest the pointer on screen
/// (within [`VERTEX_SNAP_PIXELS`]) is the target, the moved vertex nearest
/// it the base (Blender's "closest"); returns the target and the
/// translation from base to target, both in world space.
pub fn vertex_snap(
    mesh: &hedra_geom::HalfEdgeMesh,
    world: glam::DMat4,
    moved: &std::collections::BTreeSet<hedra_geom::VertexId>,
    cursor: Vec2,
    to_screen: &dyn Fn(DVec3) -> Option<Vec2>,
) -> Option<(DVec3, DVec3)> {
    let target = mesh
        .vertices()
        .filter(|v| !moved.contains(v))
        .filter_map(|v| {
            let p = world.transform_point3(mesh.position(v));
            let d = to_screen(p)?.distance(cursor);
            (d <= VERTEX_SNAP_PIXELS).then_some((d, p))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))?
        .1;
    let base = moved
        .iter()
        .map(|&v| world.transform_point3(mesh.position(v)))
        .min_by(|a, b| a.distance(target).total_cmp(&b.distance(target)))?;
    Some((target, target - base))
}
