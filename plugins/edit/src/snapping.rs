//! Snapping (Blender's Shift+Tab, and Ctrl held during a drag to invert
//! it): moves go in whole grid steps or onto a vertex, edge or face of the
//! scene ([`SnapElement`]), rotations in angle steps, scales in factor
//! steps. Typed values are exact and never snapped. The one place that
//! turns a drag into a translation, for the object, mesh and control-point
//! tools alike.

use crate::modal::Axis;
use bevy::prelude::*;
use glam::{DMat4, DVec3};
use hedra_doc::{Document, NodeId};
use hedra_geom::VertexId;
use hedra_scene::modifiers::ctrl;
use std::collections::BTreeSet;

/// What a move snaps to (Blender's snap target element).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum SnapElement {
    /// Whole steps of [`Snapping::step`].
    #[default]
    Increment,
    /// Onto the vertex (or control point) nearest the pointer, within
    /// [`VERTEX_SNAP_PIXELS`]: the moved point nearest it lands exactly on it.
    Vertex,
    /// Onto the point of an edge nearest the pointer's ray (Blender's
    /// Edge), within [`VERTEX_SNAP_PIXELS`].
    Edge,
    /// Onto the middle of the edge nearest the pointer (Blender's Edge
    /// Center).
    EdgeCenter,
    /// Onto the surface under the pointer (Blender's Face Project), the
    /// moved faces left out.
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
    use crate::bindings::{Action, KeyMode, pressed};
    if gate.keyboard_free && pressed(&keys, KeyMode::Everywhere, Action::Snapping) {
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

impl MoveSnap {
    /// The world translation of a drag from `start` to `cursor` (see
    /// [`drag_translation`]) under this snapping; an element target is
    /// taken along `axis` only, when one is set (Blender).
    pub fn translation(
        self,
        start: Vec2,
        cursor: Vec2,
        pivot: DVec3,
        view_dir: DVec3,
        axis: Option<Axis>,
        ray_at: &dyn Fn(Vec2) -> Option<(DVec3, DVec3)>,
    ) -> DVec3 {
        let step = match self {
            MoveSnap::To(delta) => {
                return axis.map_or(delta, |a| a.vector() * delta.dot(a.vector()));
            }
            MoveSnap::Increment(step) => Some(step),
            MoveSnap::Free => None,
        };
        drag_translation(start, cursor, pivot, view_dir, axis, ray_at, step)
    }
}

/// One mesh a move can snap onto, placed in the world by `world`, with the
/// vertices that move (and so cannot be targets) left out.
pub struct SnapMesh<'a> {
    /// The mesh (its cage).
    pub mesh: &'a hedra_geom::HalfEdgeMesh,
    /// Its world matrix.
    pub world: DMat4,
    /// Its vertices that take part in the move; edges and faces touching
    /// them are not targets either.
    pub moving: Option<&'a BTreeSet<VertexId>>,
}

/// What a move can snap onto this frame: meshes and loose points (control
/// points), all in world space. The object, mesh and control-point tools
/// build one and ask it for the target under the pointer.
#[derive(Default)]
pub struct SnapScene<'a> {
    /// Meshes whose vertices, edges and faces are targets.
    pub meshes: Vec<SnapMesh<'a>>,
    /// Loose points that are vertex targets (a shape's still control points).
    pub points: Vec<DVec3>,
}

impl<'a> SnapScene<'a> {
    /// Every visible node of `doc` for which `keep` holds, whole: meshes,
    /// and the control points of curves and surfaces as vertex targets.
    pub fn of_document(doc: &'a Document, keep: impl Fn(NodeId) -> bool) -> Self {
        let mut scene = SnapScene::default();
        for node in doc.nodes() {
            if !keep(node.id) || !crate::visible(doc, node.id) {
                continue;
            }
            let world = doc.world_matrix(node.id);
            match node.content.mesh() {
                Some(mesh) => scene.meshes.push(SnapMesh {
                    mesh,
                    world,
                    moving: None,
                }),
                None => scene.points.extend(
                    hedra_scene::control_points(&node.content)
                        .into_iter()
                        .map(|p| world.transform_point3(p)),
                ),
            }
        }
        scene
    }

    /// The point `element` snaps to for the pointer at `cursor` (window
    /// coordinates; `ray` is the pointer's world ray): the vertex or edge
    /// centre nearest on screen, the point of an edge nearest the ray (all
    /// within [`VERTEX_SNAP_PIXELS`]), or the nearest surface point under
    /// the pointer. Increments have no target.
    pub fn target(
        &self,
        element: SnapElement,
        cursor: Vec2,
        ray: Option<(DVec3, DVec3)>,
        to_screen: &dyn Fn(DVec3) -> Option<Vec2>,
    ) -> Option<DVec3> {
        let nearest_on_screen = |points: &mut dyn Iterator<Item = DVec3>| {
            points
                .filter_map(|p| {
                    let d = to_screen(p)?.distance(cursor);
                    (d <= VERTEX_SNAP_PIXELS).then_some((d, p))
                })
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .map(|(_, p)| p)
        };
        let still = |m: &SnapMesh, vs: &[VertexId]| {
            m.moving
                .is_none_or(|moving| vs.iter().all(|v| !moving.contains(v)))
        };
        let edges = || {
            self.meshes.iter().flat_map(move |m| {
                m.mesh
                    .edges()
                    .map(|e| m.mesh.edge_vertices(e))
                    .filter(move |vs| still(m, vs))
                    .map(move |vs| vs.map(|v| m.world.transform_point3(m.mesh.position(v))))
            })
        };
        match element {
            SnapElement::Increment => None,
            SnapElement::Vertex => nearest_on_screen(
                &mut self
                    .meshes
                    .iter()
                    .flat_map(|m| {
                        m.mesh
                            .vertices()
                            .filter(move |&v| still(m, &[v]))
                            .map(move |v| m.world.transform_point3(m.mesh.position(v)))
                    })
                    .chain(self.points.iter().copied()),
            ),
            SnapElement::EdgeCenter => nearest_on_screen(&mut edges().map(|[a, b]| a.lerp(b, 0.5))),
            SnapElement::Edge => {
                let (o, d) = ray?;
                // The point of each edge nearest the pointer's ray.
                nearest_on_screen(&mut edges().map(|[a, b]| closest_on_segment(a, b, o, d)))
            }
            SnapElement::Face => {
                let (o, d) = ray?;
                self.meshes
                    .iter()
                    .filter_map(|m| {
                        let to_local = m.world.inverse();
                        let (lo, ld) =
                            (to_local.transform_point3(o), to_local.transform_vector3(d));
                        // `t` is the same parameter along the world ray (affine map).
                        let t = m
                            .mesh
                            .faces()
                            .filter(|&f| still(m, &m.mesh.face_vertices(f).collect::<Vec<_>>()))
                            .flat_map(|f| hedra_geom::query::triangulate_face(m.mesh, f))
                            .filter_map(|[a, b, c]| {
                                let p = |v| m.mesh.position(v);
                                hedra_geom::query::ray_triangle(lo, ld, p(a), p(b), p(c))
                            })
                            .min_by(|a, b| a.total_cmp(b))?;
                        Some(t)
                    })
                    .min_by(|a, b| a.total_cmp(b))
                    .map(|t| o + d * t)
            }
        }
    }
}

/// The translation that puts the base point nearest `target` exactly on it
/// (Blender's "closest" snap base), or `None` without bases.
pub fn snap_translation(target: DVec3, bases: impl IntoIterator<Item = DVec3>) -> Option<DVec3> {
    let base = bases
        .into_iter()
        .min_by(|a, b| a.distance(target).total_cmp(&b.distance(target)))?;
    Some(target - base)
}

/// [`MoveSnap`] for a running move, with the target published for the
/// viewport: free when snapping is not active, increments for
/// [`SnapElement::Increment`], else the translation from the base nearest
/// the target onto it (free while nothing is near the pointer).
pub fn move_snap(
    snapping: &Snapping,
    active: bool,
    scene: &SnapScene,
    bases: impl IntoIterator<Item = DVec3>,
    cursor: Vec2,
    ray: Option<(DVec3, DVec3)>,
    to_screen: &dyn Fn(DVec3) -> Option<Vec2>,
    drawn: &mut SnapTarget,
) -> MoveSnap {
    match (active, snapping.element) {
        (false, _) => MoveSnap::Free,
        (true, SnapElement::Increment) => MoveSnap::Increment(snapping.step),
        (true, element) => {
            let Some(target) = scene.target(element, cursor, ray, to_screen) else {
                return MoveSnap::Free;
            };
            match snap_translation(target, bases) {
                Some(delta) => {
                    drawn.0 = Some(target);
                    MoveSnap::To(delta)
                }
                None => MoveSnap::Free,
            }
        }
    }
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
