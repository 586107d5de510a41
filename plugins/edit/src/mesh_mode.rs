//! Edit mode: Tab enters it on the active mesh; 1/2/3 pick vertices, edges
//! or faces; click / Shift-click / A / Alt+A / Ctrl+I select; G moves,
//! E extrudes, I insets, Ctrl+R loop-cuts, J connects two vertices,
//! X dissolves. Every tool is modal like Blender's: the mouse drives the
//! amount, typed numbers are exact, Enter or a click confirms as one undo
//! step, Esc or a right click restores. While a tool runs the command is
//! decided on a copy each frame and shown as a preview.

use crate::modal::Axis;
use crate::{Selection, TransformTool, cursor_ray};
use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use glam::{DMat4, DVec3};
use hedra_doc::{Command, EdgeSet, FaceSet, NodeContent, NodeId, NodeRef, VertexSet};
use hedra_geom::subdivision::Creases;
use hedra_geom::{EdgeId, FaceId, HalfEdgeMesh, VertexId};
use hedra_scene::modifiers::{alt, ctrl, shift};
use hedra_scene::{
    DocChanged, DocRequest, DocState, InputGate, NodeEntities, StatusMessage, ViewportCamera,
};
use std::collections::BTreeSet;
use std::sync::Arc;

/// Which elements clicks select.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum ElementKind {
    #[default]
    Vertex,
    Edge,
    Face,
}

/// Selected elements of the edited mesh (ids).
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct ElementSelection {
    pub vertices: BTreeSet<VertexId>,
    pub edges: BTreeSet<EdgeId>,
    pub faces: BTreeSet<FaceId>,
    /// Vertices in the order they were clicked (for Merge at First / Last).
    pub clicked: Vec<VertexId>,
}

impl ElementSelection {
    /// The selected vertices, those clicked first in click order, then the
    /// rest by id.
    pub fn ordered_vertices(&self) -> Vec<VertexId> {
        let mut out: Vec<VertexId> = self
            .clicked
            .iter()
            .copied()
            .filter(|v| self.vertices.contains(v))
            .collect();
        let rest: Vec<VertexId> = self
            .vertices
            .iter()
            .copied()
            .filter(|v| !out.contains(v))
            .collect();
        out.extend(rest);
        out
    }

    /// The elements of `kind` whose vertices all lie in `verts` (how Blender
    /// converts a selection between vertex, edge and face mode).
    pub fn from_vertices(
        kind: ElementKind,
        mesh: &HalfEdgeMesh,
        verts: &BTreeSet<VertexId>,
    ) -> Self {
        let mut sel = ElementSelection::default();
        match kind {
            ElementKind::Vertex => sel.vertices = verts.clone(),
            ElementKind::Edge => {
                sel.edges = mesh
                    .edges()
                    .filter(|&e| mesh.edge_vertices(e).iter().all(|v| verts.contains(v)))
                    .collect()
            }
            ElementKind::Face => {
                sel.faces = mesh
                    .faces()
                    .filter(|&f| mesh.face_vertices(f).all(|v| verts.contains(&v)))
                    .collect()
            }
        }
        sel
    }

    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty() && self.edges.is_empty() && self.faces.is_empty()
    }
    /// Every vertex touched by the selection (elements the mesh does not
    /// have are skipped).
    pub fn all_vertices(&self, m: &HalfEdgeMesh) -> BTreeSet<VertexId> {
        let mut out: BTreeSet<VertexId> = self
            .vertices
            .iter()
            .copied()
            .filter(|v| m.is_vertex(*v))
            .collect();
        for &e in self.edges.iter().filter(|e| m.is_edge(**e)) {
            out.extend(m.edge_vertices(e));
        }
        for &f in self.faces.iter().filter(|f| m.is_face(**f)) {
            out.extend(m.face_vertices(f));
        }
        out
    }
    /// Drops ids the mesh no longer has.
    pub fn retain_live(&mut self, m: &HalfEdgeMesh) {
        self.vertices.retain(|v| m.is_vertex(*v));
        self.edges.retain(|e| m.is_edge(*e));
        self.faces.retain(|f| m.is_face(*f));
    }
}

/// The modal mesh tools.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum MeshToolKind {
    Move,
    /// Extrude the selected faces each on its own (Alt+E).
    ExtrudeIndividual,
    /// Extrude the selected boundary edges (E in edge mode), moved like G.
    ExtrudeEdges,
    /// Slide the selected edges along their neighbours (G G in edge mode).
    SlideEdges,
    /// Bevel the selected edges (Ctrl+B).
    Bevel,
    /// Bevel the selected vertices (Ctrl+Shift+B).
    BevelVertices,
    /// Inset the selected faces each on its own (Alt+I).
    InsetIndividual,
    /// Drag the subdivision crease of the selected edges, or the corner
    /// sharpness of the selected vertices in vertex mode (Shift+E).
    Crease,
    Rotate,
    Scale,
    Extrude,
    Inset,
    LoopCut,
}

/// A running mesh tool.
#[derive(Clone, Debug)]
pub struct MeshTool {
    pub kind: MeshToolKind,
    pub axis: Option<Axis>,
    pub typed: crate::typing::TypedNumber,
    start_cursor: Vec2,
    pivot: DVec3,
    pivot_screen: Vec2,
    /// Loop cut: the edge under the cursor and the number of cuts.
    edge: Option<EdgeId>,
    cuts: u32,
    /// Crease: the mean sharpness of the selection when the tool started.
    start_value: f64,
    /// Faces the previewed command makes (extrude caps, inset inner faces),
    /// selected when the tool is confirmed.
    created_faces: Vec<FaceId>,
    pub readout: String,
}

/// Edit-mode state: the edited node, element mode, selection, running tool.
#[derive(Resource, Default, Debug)]
pub struct EditMode {
    pub node: Option<NodeId>,
    pub kind: ElementKind,
    pub selection: ElementSelection,
    pub tool: Option<MeshTool>,
    /// X-ray (Alt+Z): box selection also takes elements hidden behind the surface.
    pub x_ray: bool,
    /// M in vertex mode: the merge menu is open at this window position.
    pub merge_menu_at: Option<Vec2>,
    /// The mesh as the running tool would leave it (shown instead of the document's).
    pub preview: Option<Arc<HalfEdgeMesh>>,
    /// The creases as the running tool would leave them.
    pub preview_creases: Option<Creases>,
    /// Set on the frame a tool ended, so its confirming click selects nothing.
    pub just_finished: bool,
    /// The rectangle being dragged for box selection (window coordinates).
    pub box_select: Option<(Vec2, Vec2)>,
}

impl EditMode {
    pub fn active(&self) -> bool {
        self.node.is_some()
    }
}

/// The mesh being edited, as the document has it.
pub fn edited_mesh(state: &DocState, mode: &EditMode) -> Option<Arc<HalfEdgeMesh>> {
    let node = state.session.doc.node(mode.node?)?;
    match &node.content {
        NodeContent::Mesh(m) => Some(m.mesh.clone()),
        _ => None,
    }
}

/// Tab toggles edit mode on the active mesh; 1/2/3 choose the element kind.
pub fn mode_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut mode: ResMut<EditMode>,
    selection: Res<Selection>,
    state: Res<DocState>,
    tool: Res<TransformTool>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    if !gate.keyboard_free || tool.active.is_some() || mode.tool.is_some() {
        return;
    }
    if keys.just_pressed(KeyCode::Tab) {
        if mode.active() {
            mode.node = None;
            mode.selection = ElementSelection::default();
        } else {
            match selection.active().and_then(|id| state.session.doc.node(id)) {
                Some(n) if matches!(n.content, NodeContent::Mesh(_)) => {
                    mode.node = Some(n.id);
                    mode.selection = ElementSelection::default();
                }
                // Curves and surfaces have their own edit mode (shape_mode).
                Some(n) if matches!(n.content, NodeContent::Curve(_) | NodeContent::Surface(_)) => {
                }
                Some(n) => status.error(format!(
                    "'{}' is an empty: meshes, curves and surfaces have an edit mode",
                    n.name
                )),
                None => status.error("Select a mesh to edit (click it), then press Tab"),
            }
        }
    }
    if !mode.active() || ctrl(&keys) {
        return;
    }
    let new_kind = if keys.just_pressed(KeyCode::Digit1) {
        Some(ElementKind::Vertex)
    } else if keys.just_pressed(KeyCode::Digit2) {
        Some(ElementKind::Edge)
    } else if keys.just_pressed(KeyCode::Digit3) {
        Some(ElementKind::Face)
    } else {
        None
    };
    if let (Some(k), Some(mesh)) = (new_kind, edited_mesh(&state, &mode)) {
        if k != mode.kind {
            // Convert the selection like Blender: keep what the new kind can express.
            mode.selection =
                ElementSelection::from_vertices(k, &mesh, &mode.selection.all_vertices(&mesh));
            mode.kind = k;
        }
    }
}

/// Leaves edit mode when its node disappears; keeps the selection to live ids.
pub fn follow_changes(
    mut changes: MessageReader<DocChanged>,
    mut mode: ResMut<EditMode>,
    state: Res<DocState>,
) {
    if changes.read().count() == 0 {
        return;
    }
    match edited_mesh(&state, &mode) {
        Some(m) => mode.selection.retain_live(&m),
        None => {
            mode.node = None;
            mode.selection = ElementSelection::default();
            mode.tool = None;
            mode.preview = None;
        }
    }
}

/// The parameter `t` of the point `origin + direction * t` of a line nearest
/// to a ray (closest points of two lines: Ericson, *Real-Time Collision
/// Detection*, 5.1.8). `None` when they are within about 6° of parallel,
/// where the nearest point runs off too fast to follow.
fn line_parameter_nearest_ray(
    (origin, direction): (DVec3, DVec3),
    (ray_origin, ray_direction): (DVec3, DVec3),
) -> Option<f64> {
    let w = origin - ray_origin;
    let (a, b, c) = (
        direction.dot(direction),
        direction.dot(ray_direction),
        ray_direction.dot(ray_direction),
    );
    let denom = a * c - b * b;
    (denom > 1e-2 * a * c).then(|| (b * ray_direction.dot(w) - c * direction.dot(w)) / denom)
}

/// Screen distance (logical pixels) within which a vertex or edge is picked.
const PICK_RADIUS: f32 = 12.0;

/// The element under the cursor: vertices and edges by screen distance,
/// faces by ray.
pub fn element_under_cursor(
    kind: ElementKind,
    mesh: &HalfEdgeMesh,
    world: DMat4,
    window: &Window,
    camera: &Camera,
    camera_transform: &GlobalTransform,
) -> Option<ElementHit> {
    let cursor = window.cursor_position()?;
    let screen = |p: DVec3| {
        camera
            .world_to_viewport(camera_transform, world.transform_point3(p).as_vec3())
            .ok()
    };
    // Vertices and edges hidden behind the surface are not candidates.
    let inv = world.inverse();
    let eye = inv.transform_point3(camera_transform.translation().as_dvec3());
    let visible = |p: DVec3| hedra_geom::query::is_visible_from(mesh, eye, p);
    // Nearest on screen first; the first unhidden candidate wins.
    let nearest_visible = |mut candidates: Vec<(ElementHit, f32, Vec<DVec3>)>| {
        candidates.sort_by(|a, b| a.1.total_cmp(&b.1));
        candidates
            .into_iter()
            .find(|(_, _, probes)| probes.iter().any(|&p| visible(p)))
            .map(|(hit, _, _)| hit)
    };
    match kind {
        ElementKind::Vertex => nearest_visible(
            mesh.vertices()
                .filter_map(|v| {
                    let d = screen(mesh.position(v))?.distance(cursor);
                    (d <= PICK_RADIUS).then(|| (ElementHit::Vertex(v), d, vec![mesh.position(v)]))
                })
                .collect(),
        ),
        ElementKind::Edge => nearest_visible(
            mesh.edges()
                .filter_map(|e| {
                    let [a, b] = mesh.edge_vertices(e);
                    let (sa, sb) = (screen(mesh.position(a))?, screen(mesh.position(b))?);
                    let d = point_segment_distance(cursor, sa, sb);
                    (d <= PICK_RADIUS).then(|| {
                        let (pa, pb) = (mesh.position(a), mesh.position(b));
                        let probes = [0.25, 0.5, 0.75].map(|s| pa.lerp(pb, s)).to_vec();
                        (ElementHit::Edge(e), d, probes)
                    })
                })
                .collect(),
        ),
        ElementKind::Face => {
            let (o, d) = cursor_ray(window, camera, camera_transform)?;
            hedra_geom::query::ray_cast(mesh, inv.transform_point3(o), inv.transform_vector3(d))
                .map(|(f, _)| ElementHit::Face(f))
        }
    }
}

/// A picked element.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum ElementHit {
    Vertex(VertexId),
    Edge(EdgeId),
    Face(FaceId),
}

fn point_segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

/// A left press in edit mode, until release: a click, an Alt+click (loop),
/// or a box drag.
#[derive(Clone, Copy, Debug, Default)]
pub struct Press {
    pub start: Vec2,
    pub alt: bool,
    pub ctrl: bool,
    pub shift: bool,
}

fn toggle<T: Ord + Copy>(set: &mut BTreeSet<T>, x: T) {
    if !set.remove(&x) {
        set.insert(x);
    }
}

/// Selection in edit mode: click (Shift toggles), drag a box, Alt+click an
/// edge loop, Ctrl+Alt+click an edge ring, A / Alt+A / Ctrl+I, Ctrl+Numpad
/// +/- grow and shrink, L linked under the cursor, Ctrl+L linked to the
/// selection.
#[allow(clippy::too_many_arguments)]
pub fn select_elements(
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut mode: ResMut<EditMode>,
    state: Res<DocState>,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Single<(&Camera, &GlobalTransform), With<ViewportCamera>>,
    mut press: Local<Option<Press>>,
    mut b_box: Local<Option<Vec2>>,
    mut status: ResMut<StatusMessage>,
) {
    if !mode.active() || mode.tool.is_some() {
        *press = None;
        *b_box = None;
        mode.box_select = None;
        return;
    }
    let Some(mesh) = edited_mesh(&state, &mode) else {
        return;
    };
    let kind = mode.kind;
    let world = state.session.doc.world_matrix(mode.node.expect("active"));
    let (cam, cam_t) = *camera;
    let cursor = window.cursor_position();
    if gate.keyboard_free {
        keyboard_selection(&keys, &mut mode, &mesh, kind, world, &window, cam, cam_t);
    }
    // B (Blender): a box from the cursor follows the mouse; a click closes
    // it and adds what it holds; Esc or a right click cancels.
    if gate.keyboard_free
        && keys.just_pressed(KeyCode::KeyB)
        && !(ctrl(&keys) || shift(&keys) || alt(&keys))
    {
        *b_box = cursor;
        status.info("Box select: move to the opposite corner and click (Esc cancels)");
    }
    if let Some(start) = *b_box {
        if keys.just_pressed(KeyCode::Escape) || buttons.just_pressed(MouseButton::Right) {
            *b_box = None;
            mode.box_select = None;
            return;
        }
        if let Some(c) = cursor {
            mode.box_select = Some((start, c));
        }
        if !(buttons.just_pressed(MouseButton::Left) && gate.pointer_free) {
            return;
        }
        *b_box = None;
        status.info("Box select");
        *press = Some(Press {
            start,
            alt: false,
            ctrl: false,
            shift: true,
        });
        return;
    }
    if buttons.just_pressed(MouseButton::Left) && gate.pointer_free && !mode.just_finished {
        if let Some(c) = cursor {
            *press = Some(Press {
                start: c,
                alt: alt(&keys),
                ctrl: ctrl(&keys),
                shift: shift(&keys),
            });
        }
    }
    if gate.keyboard_free && alt(&keys) && keys.just_pressed(KeyCode::KeyZ) {
        mode.x_ray = !mode.x_ray;
        status.info(if mode.x_ray {
            "X-ray on: box select also takes hidden elements"
        } else {
            "X-ray off: box select takes only what is in sight"
        });
    }
    let x_ray = mode.x_ray;
    let Some(p) = *press else { return };
    let moved = cursor.is_some_and(|c| c.distance(p.start) > 4.0);
    if buttons.pressed(MouseButton::Left) {
        if moved && !p.alt {
            mode.box_select = cursor.map(|c| (p.start, c));
        }
        return;
    }
    // Released: act once.
    *press = None;
    let boxed = mode.box_select.take();
    let sel = &mut mode.selection;
    if let Some((a, b)) = boxed {
        let (lo, hi) = (a.min(b), a.max(b));
        // Without X-ray only what the surface leaves in sight is taken: a
        // software depth buffer of the mesh at the viewport's size.
        let depth = (!x_ray).then(|| {
            let size = cam
                .logical_viewport_size()
                .unwrap_or(Vec2::new(1280.0, 800.0));
            let model_to_clip =
                cam.clip_from_view().as_dmat4() * cam_t.to_matrix().as_dmat4().inverse() * world;
            hedra_geom::query::DepthBuffer::render(
                &mesh,
                model_to_clip,
                size.x.ceil() as usize,
                size.y.ceil() as usize,
            )
        });
        let seen = |q: DVec3| depth.as_ref().is_none_or(|d| d.is_visible(q));
        let inside = |q: DVec3| {
            camera_point(cam, cam_t, world, q)
                .is_some_and(|s| s.x >= lo.x && s.y >= lo.y && s.x <= hi.x && s.y <= hi.y)
        };
        if !p.shift {
            *sel = ElementSelection::default();
        }
        match kind {
            ElementKind::Vertex => sel.vertices.extend(mesh.vertices().filter(|&v| {
                let p = mesh.position(v);
                inside(p) && seen(p)
            })),
            ElementKind::Edge => sel.edges.extend(mesh.edges().filter(|&e| {
                let [a, b] = mesh.edge_vertices(e).map(|v| mesh.position(v));
                inside(a) && inside(b) && seen(a.lerp(b, 0.5))
            })),
            ElementKind::Face => sel.faces.extend(mesh.faces().filter(|&f| {
                let c = mesh.face_centroid(f);
                inside(c) && seen(c)
            })),
        }
        return;
    }
    if p.alt {
        if moved {
            return; // Alt+drag orbited the camera
        }
        // Loop (Alt) or ring (Ctrl+Alt) through the edge under the cursor.
        let Some(ElementHit::Edge(e)) =
            element_under_cursor(ElementKind::Edge, &mesh, world, &window, cam, cam_t)
        else {
            return;
        };
        let edges = if p.ctrl {
            hedra_geom::modeling::edge_ring(&mesh, e)
                .0
                .into_iter()
                .map(|h| h.edge())
                .collect()
        } else {
            hedra_geom::topology::edge_loop(&mesh, e)
        };
        if !p.shift {
            *sel = ElementSelection::default();
        }
        match kind {
            ElementKind::Vertex => sel
                .vertices
                .extend(edges.iter().flat_map(|&e| mesh.edge_vertices(e))),
            ElementKind::Edge => sel.edges.extend(edges),
            ElementKind::Face => sel
                .faces
                .extend(edges.iter().flat_map(|&e| mesh.edge_faces(e)).flatten()),
        }
        return;
    }
    let hit = element_under_cursor(kind, &mesh, world, &window, cam, cam_t);
    if !p.shift {
        *sel = ElementSelection::default();
    }
    match hit {
        Some(ElementHit::Vertex(v)) => {
            toggle(&mut sel.vertices, v);
            sel.clicked.retain(|&c| c != v);
            if sel.vertices.contains(&v) {
                sel.clicked.push(v);
            }
        }
        Some(ElementHit::Edge(e)) => toggle(&mut sel.edges, e),
        Some(ElementHit::Face(f)) => toggle(&mut sel.faces, f),
        None => {}
    }
}

/// A mesh-space point on screen (logical pixels), if in front of the camera.
fn camera_point(cam: &Camera, cam_t: &GlobalTransform, world: DMat4, p: DVec3) -> Option<Vec2> {
    cam.world_to_viewport(cam_t, world.transform_point3(p).as_vec3())
        .ok()
}

#[allow(clippy::too_many_arguments)]
fn keyboard_selection(
    keys: &ButtonInput<KeyCode>,
    mode: &mut EditMode,
    mesh: &HalfEdgeMesh,
    kind: ElementKind,
    world: DMat4,
    window: &Window,
    cam: &Camera,
    cam_t: &GlobalTransform,
) {
    let sel = &mut mode.selection;
    let (c, a, s) = (ctrl(keys), alt(keys), shift(keys));
    let set_from_vertices = |sel: &mut ElementSelection, verts: &BTreeSet<VertexId>| {
        *sel = ElementSelection::from_vertices(kind, mesh, verts);
    };
    if !c && !s && keys.just_pressed(KeyCode::KeyA) {
        *sel = ElementSelection::default();
        if !a {
            match kind {
                ElementKind::Vertex => sel.vertices = mesh.vertices().collect(),
                ElementKind::Edge => sel.edges = mesh.edges().collect(),
                ElementKind::Face => sel.faces = mesh.faces().collect(),
            }
        }
    }
    if c && keys.just_pressed(KeyCode::KeyI) {
        match kind {
            ElementKind::Vertex => {
                sel.vertices = mesh
                    .vertices()
                    .filter(|v| !sel.vertices.contains(v))
                    .collect()
            }
            ElementKind::Edge => {
                sel.edges = mesh.edges().filter(|e| !sel.edges.contains(e)).collect()
            }
            ElementKind::Face => {
                sel.faces = mesh.faces().filter(|f| !sel.faces.contains(f)).collect()
            }
        }
    }
    let grow = c && (keys.just_pressed(KeyCode::NumpadAdd) || keys.just_pressed(KeyCode::Equal));
    let shrink =
        c && (keys.just_pressed(KeyCode::NumpadSubtract) || keys.just_pressed(KeyCode::Minus));
    if grow || shrink {
        let verts = sel.all_vertices(mesh);
        let next: BTreeSet<VertexId> = if grow {
            verts
                .iter()
                .flat_map(|&v| std::iter::once(v).chain(mesh.vertex_neighbors(v)))
                .collect()
        } else {
            verts
                .iter()
                .copied()
                .filter(|&v| mesh.vertex_neighbors(v).all(|w| verts.contains(&w)))
                .collect()
        };
        set_from_vertices(sel, &next);
    }
    if keys.just_pressed(KeyCode::KeyL) {
        let seeds: Vec<VertexId> = if c {
            sel.all_vertices(mesh).into_iter().collect()
        } else {
            match element_under_cursor(kind, mesh, world, window, cam, cam_t) {
                Some(ElementHit::Vertex(v)) => vec![v],
                Some(ElementHit::Edge(e)) => mesh.edge_vertices(e).to_vec(),
                Some(ElementHit::Face(f)) => mesh.face_vertices(f).collect(),
                None => vec![],
            }
        };
        let mut linked: BTreeSet<VertexId> = hedra_geom::topology::linked_vertices(mesh, seeds)
            .into_iter()
            .collect();
        if !c {
            linked.extend(sel.all_vertices(mesh));
        }
        set_from_vertices(sel, &linked);
    }
}

/// Starts tools and runs instant ones (J, X).
#[allow(clippy::too_many_arguments)]
pub fn edit_shortcuts(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut mode: ResMut<EditMode>,
    state: Res<DocState>,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Single<(&Camera, &GlobalTransform), With<ViewportCamera>>,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    if !mode.active() || mode.tool.is_some() || !gate.keyboard_free {
        return;
    }
    let Some(mesh) = edited_mesh(&state, &mode) else {
        return;
    };
    let node = NodeRef::from(mode.node.expect("active"));
    let world = state.session.doc.world_matrix(mode.node.expect("active"));
    let (c, s, a) = (ctrl(&keys), shift(&keys), alt(&keys));
    let Some(cursor) = window.cursor_position() else {
        return;
    };
    let verts = mode.selection.all_vertices(&mesh);
    let pivot_local = if verts.is_empty() {
        DVec3::ZERO
    } else {
        verts.iter().map(|&v| mesh.position(v)).sum::<DVec3>() / verts.len() as f64
    };
    let pivot = world.transform_point3(pivot_local);
    let pivot_screen = camera
        .0
        .world_to_viewport(camera.1, pivot.as_vec3())
        .unwrap_or(cursor);
    let start = |kind: MeshToolKind| MeshTool {
        kind,
        axis: None,
        typed: Default::default(),
        start_cursor: cursor,
        pivot,
        pivot_screen,
        edge: None,
        cuts: 1,
        start_value: 0.0,
        created_faces: Vec::new(),
        readout: String::new(),
    };
    if c && keys.just_pressed(KeyCode::KeyR) {
        let (cam, cam_t) = *camera;
        let edge = match element_under_cursor(ElementKind::Edge, &mesh, world, &window, cam, cam_t)
        {
            Some(ElementHit::Edge(e)) => Some(e),
            _ => mode.selection.edges.iter().next().copied(),
        };
        match edge {
            Some(e) => {
                let mut t = start(MeshToolKind::LoopCut);
                t.edge = Some(e);
                mode.tool = Some(t);
            }
            None => status.error(
                "Loop cut: point at an edge of a quad strip (or select one), then press Ctrl+R",
            ),
        }
        return;
    }
    // Tools that start only on a selection of one element kind.
    let faces_selected = !mode.selection.faces.is_empty();
    let edges_selected = !mode.selection.edges.is_empty();
    let vertices_selected = !mode.selection.vertices.is_empty();
    for (held, key, selected, tool, refusal) in [
        (
            c && s,
            KeyCode::KeyB,
            vertices_selected,
            MeshToolKind::BevelVertices,
            "Vertex bevel: select vertices first (press 1 for vertex mode)",
        ),
        (
            a,
            KeyCode::KeyI,
            faces_selected,
            MeshToolKind::InsetIndividual,
            "Inset: select faces first (press 3 for face mode)",
        ),
        (
            a,
            KeyCode::KeyE,
            faces_selected,
            MeshToolKind::ExtrudeIndividual,
            "Extrude: select faces first (press 3 for face mode)",
        ),
        (
            c && !s,
            KeyCode::KeyB,
            edges_selected,
            MeshToolKind::Bevel,
            "Bevel: select edges first (press 2 for edge mode)",
        ),
    ] {
        if held && keys.just_pressed(key) {
            if selected {
                mode.tool = Some(start(tool));
            } else {
                status.error(refusal);
            }
            return;
        }
    }
    if s && keys.just_pressed(KeyCode::KeyE) {
        let creases = match state
            .session
            .doc
            .node(mode.node.expect("active"))
            .map(|n| &n.content)
        {
            Some(NodeContent::Mesh(m)) => m.creases.clone(),
            _ => Creases::default(),
        };
        let values: Vec<f64> = if mode.kind == ElementKind::Vertex {
            mode.selection
                .vertices
                .iter()
                .map(|&v| creases.vertex(v))
                .collect()
        } else {
            mode.selection
                .edges
                .iter()
                .map(|&e| creases.edge(e))
                .collect()
        };
        if values.is_empty() {
            status.error("Crease: select edges (2), or vertices (1) for corner sharpness, first");
        } else {
            let mut t = start(MeshToolKind::Crease);
            t.start_value = values.iter().sum::<f64>() / values.len() as f64;
            mode.tool = Some(t);
        }
        return;
    }
    if c && keys.just_pressed(KeyCode::KeyX) {
        match delete_or_dissolve(node.clone(), mode.kind, &mode.selection, true) {
            Some(cmd) => {
                requests.write(DocRequest::Execute(cmd));
            }
            None => status.error("Ctrl+X: select what to dissolve"),
        }
        return;
    }
    if keys.just_pressed(KeyCode::KeyN) && (a || s) {
        let cmd = if a {
            Command::FlipNormals { node: node.clone() }
        } else {
            Command::RecalculateNormals { node: node.clone() }
        };
        requests.write(DocRequest::Execute(cmd));
        return;
    }
    if c || a {
        return;
    }
    if keys.just_pressed(KeyCode::KeyF) {
        let edges: Vec<u32> = mode
            .selection
            .edges
            .iter()
            .map(|e| e.0)
            .chain(
                // In vertex mode: the boundary edges between selected vertices.
                mesh.edges()
                    .filter(|&e| {
                        mesh.is_boundary_edge(e)
                            && mesh
                                .edge_vertices(e)
                                .iter()
                                .all(|v| mode.selection.vertices.contains(v))
                    })
                    .map(|e| e.0),
            )
            .collect();
        if edges.is_empty() {
            status.error("Fill: select edges (or vertices) around a hole");
        } else {
            requests.write(DocRequest::Execute(Command::FillHoles {
                node: node.clone(),
                edges: EdgeSet::Ids(edges),
            }));
        }
        return;
    }
    for (key, kind) in [
        (KeyCode::KeyG, MeshToolKind::Move),
        (KeyCode::KeyR, MeshToolKind::Rotate),
        (KeyCode::KeyS, MeshToolKind::Scale),
    ] {
        if keys.just_pressed(key) {
            if verts.is_empty() {
                status.error("Nothing selected to transform");
            } else {
                mode.tool = Some(start(kind));
            }
        }
    }
    if keys.just_pressed(KeyCode::KeyE) && !s && mode.kind == ElementKind::Edge {
        if mode.selection.edges.is_empty() {
            status.error("Extrude: select boundary edges first");
        } else {
            mode.tool = Some(start(MeshToolKind::ExtrudeEdges));
        }
    } else if keys.just_pressed(KeyCode::KeyE) && !s {
        if mode.selection.faces.is_empty() {
            status.error("Extrude: select faces first (press 3 for face mode)");
        } else {
            mode.tool = Some(start(MeshToolKind::Extrude));
        }
    }
    if keys.just_pressed(KeyCode::KeyI) {
        if mode.selection.faces.is_empty() {
            status.error("Inset: select faces first (press 3 for face mode)");
        } else {
            mode.tool = Some(start(MeshToolKind::Inset));
        }
    }
    if keys.just_pressed(KeyCode::KeyM) && mode.kind == ElementKind::Vertex {
        if mode.selection.vertices.len() < 2 {
            status.error("Merge: select two or more vertices");
        } else {
            mode.merge_menu_at = window.cursor_position();
        }
    } else if keys.just_pressed(KeyCode::KeyM) {
        if mode.selection.edges.is_empty() {
            status.error("Collapse: select edges (press 2 for edge mode)");
        } else {
            requests.write(DocRequest::Execute(Command::CollapseEdges {
                node: node.clone(),
                edges: EdgeSet::Ids(mode.selection.edges.iter().map(|e| e.0).collect()),
            }));
        }
    }
    if keys.just_pressed(KeyCode::KeyJ) {
        let vs: Vec<u32> = mode.selection.vertices.iter().map(|v| v.0).collect();
        if vs.len() == 2 {
            requests.write(DocRequest::Execute(Command::ConnectVertices {
                node,
                vertices: VertexSet::Ids(vs),
            }));
        } else {
            status.error("Connect: select exactly two vertices of one face");
        }
    } else if keys.just_pressed(KeyCode::KeyX) || keys.just_pressed(KeyCode::Delete) {
        match delete_or_dissolve(node, mode.kind, &mode.selection, false) {
            Some(c) => {
                requests.write(DocRequest::Execute(c));
            }
            None => status.error("X: select what to delete (Ctrl+X dissolves)"),
        }
    }
}

/// X deletes the selected elements of the current kind with what only they
/// use; Ctrl+X dissolves them (merging what is around).
fn delete_or_dissolve(
    node: NodeRef,
    kind: ElementKind,
    sel: &ElementSelection,
    dissolve: bool,
) -> Option<Command> {
    let vertices = || VertexSet::Ids(sel.vertices.iter().map(|v| v.0).collect());
    let edges = || EdgeSet::Ids(sel.edges.iter().map(|e| e.0).collect());
    let faces = || FaceSet::Ids(sel.faces.iter().map(|f| f.0).collect());
    match (kind, dissolve) {
        (ElementKind::Vertex, _) if sel.vertices.is_empty() => None,
        (ElementKind::Edge, _) if sel.edges.is_empty() => None,
        (ElementKind::Face, _) if sel.faces.is_empty() => None,
        (ElementKind::Vertex, false) => Some(Command::DeleteVertices {
            node,
            vertices: vertices(),
        }),
        (ElementKind::Edge, false) => Some(Command::DeleteEdges {
            node,
            edges: edges(),
        }),
        (ElementKind::Face, false) => Some(Command::DeleteFaces {
            node,
            faces: faces(),
        }),
        (ElementKind::Vertex, true) => Some(Command::DissolveVertices {
            node,
            vertices: vertices(),
        }),
        (ElementKind::Edge, true) => Some(Command::DissolveEdges {
            node,
            edges: edges(),
        }),
        (ElementKind::Face, true) => Some(Command::DissolveFaces {
            node,
            faces: faces(),
        }),
    }
}

/// The command a tool would run for the cursor position.
fn tool_command(
    tool: &mut MeshTool,
    node: NodeRef,
    mesh: &HalfEdgeMesh,
    selection: &ElementSelection,
    world: DMat4,
    cursor: Vec2,
    ray_at: &dyn Fn(Vec2) -> Option<(DVec3, DVec3)>,
    view_dir: DVec3,
    pixel_size: f64,
) -> Command {
    let drag = (cursor - tool.start_cursor).x as f64 * pixel_size;
    let faces = || FaceSet::Ids(selection.faces.iter().map(|f| f.0).collect());
    match tool.kind {
        MeshToolKind::Move | MeshToolKind::ExtrudeEdges => {
            let world_delta = if let Some(v) = tool.typed.value() {
                tool.axis.unwrap_or(Axis::X).vector() * v
            } else {
                let plane_hit = |p: Vec2| -> Option<DVec3> {
                    let (o, d) = ray_at(p)?;
                    let denom = d.dot(view_dir);
                    (denom.abs() > 1e-12).then(|| o + d * ((tool.pivot - o).dot(view_dir) / denom))
                };
                match (plane_hit(tool.start_cursor), plane_hit(cursor)) {
                    (Some(a), Some(b)) => {
                        let d = b - a;
                        tool.axis.map_or(d, |ax| ax.vector() * d.dot(ax.vector()))
                    }
                    _ => DVec3::ZERO,
                }
            };
            let verb = if tool.kind == MeshToolKind::Move {
                "Move"
            } else {
                "Extrude edges"
            };
            tool.readout = format!(
                "{verb} ({:.4}, {:.4}, {:.4})",
                world_delta.x, world_delta.y, world_delta.z
            );
            let offset = world.inverse().transform_vector3(world_delta);
            if tool.kind == MeshToolKind::ExtrudeEdges {
                let edges = EdgeSet::Ids(selection.edges.iter().map(|e| e.0).collect());
                return Command::ExtrudeEdges {
                    node,
                    edges,
                    offset,
                };
            }
            let vertices = selection
                .all_vertices(mesh)
                .into_iter()
                .map(|v| v.0)
                .collect();
            Command::MoveVertices {
                node,
                vertices: VertexSet::Ids(vertices),
                offset,
            }
        }
        MeshToolKind::Bevel => {
            let width = tool.typed.value().unwrap_or(drag.abs());
            let segments = tool.cuts;
            tool.readout = format!("Bevel width {width:.4}, {segments} segment(s) (wheel or +/-)");
            Command::BevelEdges {
                node,
                edges: EdgeSet::Ids(selection.edges.iter().map(|e| e.0).collect()),
                width,
                segments,
            }
        }
        MeshToolKind::BevelVertices => {
            let width = tool.typed.value().unwrap_or(drag.abs());
            tool.readout = format!("Vertex bevel width {width:.4}");
            Command::BevelVertices {
                node,
                vertices: VertexSet::Ids(selection.vertices.iter().map(|v| v.0).collect()),
                width,
            }
        }
        MeshToolKind::Crease => {
            // 100 pixels to the right add one level of sharpness.
            let sharpness = tool
                .typed
                .value()
                .unwrap_or(tool.start_value + ((cursor - tool.start_cursor).x / 100.0) as f64)
                .clamp(0.0, 10.0);
            let what = if selection.vertices.is_empty() || !selection.edges.is_empty() {
                "Edge crease"
            } else {
                "Vertex corner sharpness"
            };
            tool.readout = format!("{what} {sharpness:.2} (0 smooth … 10 sharp)");
            if what == "Edge crease" {
                Command::SetEdgeCrease {
                    node,
                    edges: EdgeSet::Ids(selection.edges.iter().map(|e| e.0).collect()),
                    sharpness,
                }
            } else {
                Command::SetVertexCrease {
                    node,
                    vertices: VertexSet::Ids(selection.vertices.iter().map(|v| v.0).collect()),
                    sharpness,
                }
            }
        }
        MeshToolKind::SlideEdges => {
            // 300 pixels to the right slide all the way to one side, to the left the other.
            let factor = tool
                .typed
                .value()
                .unwrap_or(((cursor - tool.start_cursor).x / 300.0) as f64)
                .clamp(-1.0, 1.0);
            tool.readout = format!("Edge slide {factor:.3}");
            Command::SlideEdges {
                node,
                edges: EdgeSet::Ids(selection.edges.iter().map(|e| e.0).collect()),
                factor,
            }
        }
        MeshToolKind::Rotate | MeshToolKind::Scale => {
            let xf: DMat4 = if tool.kind == MeshToolKind::Rotate {
                let degrees = tool.typed.value().unwrap_or_else(|| {
                    let a = (tool.start_cursor - tool.pivot_screen).to_angle();
                    let b = (cursor - tool.pivot_screen).to_angle();
                    -((b - a) as f64).to_degrees()
                });
                tool.readout = format!("Rotate {degrees:.2}°");
                let axis = tool.axis.map_or(-view_dir, Axis::vector);
                crate::rotation_about(
                    tool.pivot,
                    glam::DQuat::from_axis_angle(axis.normalize(), degrees.to_radians()),
                )
            } else {
                let factor = tool.typed.value().unwrap_or_else(|| {
                    let d0 = (tool.start_cursor - tool.pivot_screen).length().max(1.0);
                    ((cursor - tool.pivot_screen).length() / d0) as f64
                });
                tool.readout = format!("Scale {factor:.4}");
                let f = tool.axis.map_or(DVec3::splat(factor), |a| {
                    DVec3::ONE + a.vector() * (factor - 1.0)
                });
                DMat4::from_translation(tool.pivot)
                    * DMat4::from_scale(f)
                    * DMat4::from_translation(-tool.pivot)
            };
            // The world-space transform, applied to mesh-space positions.
            let local = world.inverse() * xf * world;
            let positions = selection
                .all_vertices(mesh)
                .into_iter()
                .map(|v| (v.0, local.transform_point3(mesh.position(v))))
                .collect();
            Command::SetVertexPositions { node, positions }
        }
        MeshToolKind::Extrude | MeshToolKind::ExtrudeIndividual => {
            // The faces follow the cursor along their normal, as in Blender;
            // sideways drag only when the normal points at the viewer.
            let distance = tool.typed.value().unwrap_or_else(|| {
                let normal = selection
                    .faces
                    .iter()
                    .map(|&f| mesh.face_normal(f))
                    .sum::<DVec3>();
                let line = (
                    tool.pivot,
                    world.transform_vector3(normal.normalize_or_zero()),
                );
                let along = |p: Vec2| line_parameter_nearest_ray(line, ray_at(p)?);
                match (along(tool.start_cursor), along(cursor)) {
                    (Some(a), Some(b)) => b - a,
                    _ => drag,
                }
            });
            tool.readout = format!("Extrude {distance:.4}");
            if tool.kind == MeshToolKind::Extrude {
                Command::ExtrudeRegion {
                    node,
                    faces: faces(),
                    distance,
                }
            } else {
                Command::ExtrudeFaces {
                    node,
                    faces: faces(),
                    distance,
                }
            }
        }
        MeshToolKind::Inset | MeshToolKind::InsetIndividual => {
            let thickness = tool.typed.value().unwrap_or(drag.abs());
            tool.readout = format!("Inset thickness {thickness:.4}");
            if tool.kind == MeshToolKind::Inset {
                Command::InsetRegion {
                    node,
                    faces: faces(),
                    thickness,
                    depth: 0.0,
                }
            } else {
                Command::InsetFaces {
                    node,
                    faces: faces(),
                    thickness,
                    depth: 0.0,
                }
            }
        }
        MeshToolKind::LoopCut => {
            let cuts = tool
                .typed
                .value()
                .map_or(tool.cuts, |v| v.round().clamp(1.0, 64.0) as u32);
            tool.readout = format!("Loop cut: {cuts} cut(s) (wheel or +/- to change)");
            Command::LoopCut {
                node,
                edge: EdgeSet::Ids(vec![tool.edge.expect("loop cut has an edge").0]),
                cuts,
            }
        }
    }
}

/// Runs the active mesh tool: preview each frame, confirm or cancel.
#[allow(clippy::too_many_arguments)]
pub fn drive_mesh_tool(
    mut mode: ResMut<EditMode>,
    keys: Res<ButtonInput<KeyCode>>,
    buttons: Res<ButtonInput<MouseButton>>,
    scroll: Res<bevy::input::mouse::AccumulatedMouseScroll>,
    window: Single<&Window, With<PrimaryWindow>>,
    camera: Single<(&Camera, &GlobalTransform), With<ViewportCamera>>,
    state: Res<DocState>,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<hedra_scene::StatusMessage>,
) {
    mode.just_finished = false;
    let Some(mut tool) = mode.tool.take() else {
        return;
    };
    let (Some(node_id), Some(mesh)) = (mode.node, edited_mesh(&state, &mode)) else {
        mode.preview = None;
        return;
    };
    if keys.just_pressed(KeyCode::Escape) || buttons.just_pressed(MouseButton::Right) {
        mode.preview = None;
        mode.just_finished = true;
        return;
    }
    for (key, axis) in [
        (KeyCode::KeyX, Axis::X),
        (KeyCode::KeyY, Axis::Y),
        (KeyCode::KeyZ, Axis::Z),
    ] {
        if keys.just_pressed(key)
            && matches!(
                tool.kind,
                MeshToolKind::Move | MeshToolKind::Rotate | MeshToolKind::Scale
            )
        {
            tool.axis = if tool.axis == Some(axis) {
                None
            } else {
                Some(axis)
            };
        }
    }
    // G again while moving edges: slide them instead (Blender's G G).
    if tool.kind == MeshToolKind::Move
        && mode.kind == ElementKind::Edge
        && keys.just_pressed(KeyCode::KeyG)
    {
        tool.kind = MeshToolKind::SlideEdges;
        tool.typed = Default::default();
    }
    // Loop cut and bevel: minus, plus and the wheel change the count of cuts or segments.
    let loop_cut = matches!(tool.kind, MeshToolKind::LoopCut | MeshToolKind::Bevel);
    tool.typed.read(&keys, !loop_cut);
    if loop_cut {
        let less = keys.any_just_pressed([KeyCode::Minus, KeyCode::NumpadSubtract])
            || scroll.delta.y < 0.0;
        let more =
            keys.any_just_pressed([KeyCode::NumpadAdd, KeyCode::Equal]) || scroll.delta.y > 0.0;
        if less {
            tool.cuts = tool.cuts.saturating_sub(1).max(1);
        } else if more {
            tool.cuts = (tool.cuts + 1).min(64);
        }
    }
    let (cam, cam_t) = *camera;
    let cursor = window.cursor_position().unwrap_or(tool.start_cursor);
    let world = state.session.doc.world_matrix(node_id);
    let view_dir = (cam_t.rotation() * Vec3::NEG_Z).as_dvec3();
    // World size of one pixel at the pivot, so drags feel the same at any zoom.
    let dist = cam_t
        .translation()
        .as_dvec3()
        .distance(tool.pivot)
        .max(1e-6);
    let pixel_size = dist * 0.0008;
    let ray_at = |p: Vec2| {
        cam.viewport_to_world(cam_t, p)
            .ok()
            .map(|r| (r.origin.as_dvec3(), Vec3::from(r.direction).as_dvec3()))
    };
    let cmd = tool_command(
        &mut tool,
        NodeRef::from(node_id),
        &mesh,
        &mode.selection,
        world,
        cursor,
        &ray_at,
        view_dir,
        pixel_size,
    );
    if !tool.typed.is_empty() {
        tool.readout = format!("{} [{}]", tool.readout, tool.typed.as_str());
    }
    // Decide on a copy: the preview, or the reason it cannot apply.
    match state.session.doc.decide_with_result(&cmd, 0) {
        Ok(decision) => {
            tool.created_faces = decision.created_faces;
            let after = decision
                .transaction
                .changes
                .iter()
                .find(|c| c.id == node_id)
                .and_then(|c| c.after.as_ref())
                .and_then(|n| match &n.content {
                    NodeContent::Mesh(m) => Some(m),
                    _ => None,
                });
            mode.preview = after.map(|m| m.mesh.clone());
            mode.preview_creases = after.map(|m| m.creases.clone());
        }
        Err(e) => {
            mode.preview = None;
            tool.readout = format!("{} — {e}", tool.readout);
        }
    }
    let confirm = keys.any_just_pressed([KeyCode::Enter, KeyCode::NumpadEnter, KeyCode::Space])
        || buttons.just_pressed(MouseButton::Left);
    if confirm {
        // A region extrude or inset selects the faces it made (the caps, the
        // inner faces), as Blender keeps them selected.
        if matches!(tool.kind, MeshToolKind::Extrude | MeshToolKind::Inset)
            && mode.preview.is_some()
            && !tool.created_faces.is_empty()
        {
            mode.selection.faces = tool.created_faces.iter().copied().collect();
        }
        mode.preview = None;
        mode.just_finished = true;
        let nothing =
            matches!(&cmd, Command::MoveVertices { offset, .. } if *offset == DVec3::ZERO);
        if !nothing {
            requests.write(DocRequest::Execute(cmd));
        } else {
            status.info("Move cancelled (no movement)");
        }
        return;
    }
    mode.tool = Some(tool);
}

/// While a tool runs, the edited node shows the preview mesh (smoothed when
/// the node has a subdivision modifier); afterwards the document's mesh
/// again. When a preview only moves vertices, the render mesh is patched in
/// place instead of rebuilt (dense meshes and smooth previews stay fluid).
pub fn show_preview(
    mode: Res<EditMode>,
    state: Res<DocState>,
    entities: Res<NodeEntities>,
    mut shown: Local<Option<Shown>>,
    mesh3d: Query<&Mesh3d>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut previews: ResMut<hedra_scene::SmoothPreviews>,
) {
    let content = |n: NodeId| -> Option<hedra_doc::MeshContent> {
        match &state.session.doc.node(n)?.content {
            NodeContent::Mesh(c) => Some(c.clone()),
            _ => None,
        }
    };
    let want: Option<Shown> = match (mode.node, &mode.preview) {
        (Some(n), Some(p)) => Some(Shown {
            node: n,
            mesh: p.clone(),
            creases: mode.preview_creases.clone(),
        }),
        _ => None,
    };
    let same = |a: &Option<Shown>, b: &Option<Shown>| match (a, b) {
        (Some(x), Some(y)) => {
            x.node == y.node && Arc::ptr_eq(&x.mesh, &y.mesh) && x.creases == y.creases
        }
        (None, None) => true,
        _ => false,
    };
    if same(&want, &shown) {
        return;
    }
    let mut show =
        |n: NodeId, from: &HalfEdgeMesh, to: &Arc<HalfEdgeMesh>, creases: Option<&Creases>| {
            let Some(c) = content(n) else {
                return;
            };
            let Some(h) = entities.0.get(&n).and_then(|e| mesh3d.get(*e).ok()) else {
                return;
            };
            let Some(mut m) = meshes.get_mut(&h.0) else {
                return;
            };
            let creases = creases.unwrap_or(&c.creases);
            if let Some(modifier) = hedra_scene::active_modifier(&c) {
                let src = hedra_scene::SmoothSource {
                    node: n,
                    cage: to,
                    creases,
                    modifier: &modifier,
                    shading: c.shading,
                };
                if !previews.update_positions(&mut m, &src) {
                    // A large preview is not refined every frame of a tool:
                    // the cage shows until the result is committed.
                    *m = if previews.needs_background(&src) {
                        hedra_scene::render_mesh(to, c.shading)
                    } else {
                        previews
                            .render_mesh(&src)
                            .unwrap_or_else(|_| hedra_scene::render_mesh(to, c.shading))
                    };
                }
            } else if !hedra_scene::update_render_positions(&mut m, from, to, c.shading) {
                *m = hedra_scene::render_mesh(to, c.shading);
            }
        };
    // Back to the document's mesh for the node previewed before.
    if let Some(prev) = shown.take() {
        if want.as_ref().is_none_or(|w| w.node != prev.node) {
            if let Some(doc) = content(prev.node) {
                show(prev.node, &prev.mesh, &doc.mesh, None);
            }
        } else if let Some(w) = &want {
            show(w.node, &prev.mesh, &w.mesh, w.creases.as_ref());
            *shown = want.clone();
            return;
        }
    }
    if let Some(w) = &want {
        if let Some(doc) = content(w.node) {
            show(w.node, &doc.mesh, &w.mesh, w.creases.as_ref());
        }
        *shown = want.clone();
    }
}

/// What [`show_preview`] last put on screen.
#[derive(Clone, Debug)]
pub struct Shown {
    node: NodeId,
    mesh: Arc<HalfEdgeMesh>,
    creases: Option<Creases>,
}

#[cfg(test)]
mod tests {
    use super::line_parameter_nearest_ray;
    use bevy::math::DVec3;

    #[test]
    fn nearest_point_on_a_line_to_a_ray() {
        // The Y axis scaled by 2 (t counts half units) and a ray along -X at height 3.
        let line = (DVec3::ZERO, DVec3::new(0.0, 2.0, 0.0));
        let ray = (DVec3::new(5.0, 3.0, 1.0), DVec3::new(-1.0, 0.0, 0.0));
        let t = line_parameter_nearest_ray(line, ray).unwrap();
        assert!((t - 1.5).abs() < 1e-12, "{t}");
        // Looking straight down the line gives nothing to follow.
        let along = (DVec3::new(0.0, 9.0, 0.0), DVec3::new(0.01, -1.0, 0.0));
        assert_eq!(line_parameter_nearest_ray(line, along), None);
    }
}
