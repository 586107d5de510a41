//! The 3D viewport: orbit camera, ground grid and axes, edge overlays with
//! the selection highlighted, and the transform gizmo on the active object.

use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll, MouseScrollUnit};
use bevy::prelude::*;
use glam::DVec3;
use hedra_doc::{NodeContent, NodeRef, Transform as DocTransform};
use hedra_edit::{EditMode, ElementKind, Selection, TransformTool};
use hedra_scene::modifiers;
use hedra_scene::{
    DocRequest, DocState, InputGate, NodeEntities, NodeEntity, ProjectedMesh, SceneSystems,
    ViewportCamera,
};
use std::f32::consts::FRAC_PI_2;

/// Orbit camera state (Blender-style: turntable around a focus point).
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct OrbitCamera {
    pub focus: Vec3,
    pub yaw: f32,
    pub pitch: f32,
    pub distance: f32,
}

impl Default for OrbitCamera {
    fn default() -> Self {
        OrbitCamera {
            focus: Vec3::ZERO,
            yaw: 0.75,
            pitch: -0.5,
            distance: 12.0,
        }
    }
}

impl OrbitCamera {
    pub fn transform(&self) -> Transform {
        let rotation = Quat::from_euler(EulerRot::YXZ, self.yaw, self.pitch, 0.0);
        Transform {
            translation: self.focus + rotation * Vec3::Z * self.distance,
            rotation,
            scale: Vec3::ONE,
        }
    }
}

/// Overlay child entity showing a mesh node's edges, and what it was built for.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq)]
pub struct EdgeOverlay {
    pub source: ProjectedMesh,
    pub selected: bool,
    pub active: bool,
    pub shown: bool,
}

pub struct ViewportPlugin;

impl Plugin for ViewportPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<CurveAnalysis>();
        app.init_resource::<SurfaceAnalysis>();
        app.insert_resource(ClearColor(Color::srgb(0.23, 0.23, 0.25)))
            .insert_resource(GlobalAmbientLight {
                brightness: 400.0,
                ..default()
            })
            .add_plugins(TransformGizmoPlugin)
            .insert_gizmo_config(
                AxisGizmos,
                GizmoConfig {
                    line: GizmoLineConfig {
                        width: 2.0,
                        ..default()
                    },
                    depth_bias: -0.001,
                    ..default()
                },
            )
            .add_systems(Startup, spawn_camera)
            .add_systems(PostStartup, overlay_cameras_keep_the_picture)
            .add_systems(
                Update,
                (camera_controls, frame_selection, draw_grid)
                    .chain()
                    .after(SceneSystems::Sync),
            )
            .add_systems(
                Update,
                (
                    update_edge_overlays,
                    focus_gizmo_on_active,
                    commit_gizmo_drag,
                    update_edit_edges,
                    draw_edit_overlay,
                    draw_shape_edit,
                    draw_curve_analysis,
                    draw_surface_analysis,
                )
                    .after(SceneSystems::Sync),
            );
    }
}

fn spawn_camera(mut commands: Commands) {
    let orbit = OrbitCamera::default();
    commands.spawn((
        Camera3d::default(),
        ViewportCamera,
        TransformGizmoCamera,
        orbit,
        orbit.transform(),
        Tonemapping::TonyMcMapface,
        Msaa::Sample4,
        children![(
            // A headlight slightly above and left of the eye, like a studio key light.
            DirectionalLight {
                illuminance: 6_000.0,
                ..default()
            },
            Transform::from_xyz(-2.0, 3.0, 4.0).looking_at(Vec3::ZERO, Vec3::Y),
        )],
    ));
}

/// Bevy's transform gizmo renders through a second 3D camera; it must draw
/// over the viewport, not clear it.
fn overlay_cameras_keep_the_picture(
    mut cameras: Query<&mut Camera, (With<Camera3d>, Without<ViewportCamera>)>,
) {
    for mut c in &mut cameras {
        c.clear_color = ClearColorConfig::None;
    }
}

/// Middle mouse orbits, Shift+middle pans, Ctrl+middle or the wheel zooms,
/// Alt+left orbits (trackpads); numpad 1/3/7 give front/right/top views.
#[allow(clippy::too_many_arguments)]
fn camera_controls(
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    gate: Res<InputGate>,
    tool: Res<TransformTool>,
    mut dragging: Local<bool>,
    mut camera: Single<(&mut OrbitCamera, &mut Transform), With<ViewportCamera>>,
) {
    let (orbit, transform) = &mut *camera;
    let alt = modifiers::alt(&keys);
    let shift = modifiers::shift(&keys);
    let ctrl = modifiers::ctrl(&keys);
    let drag_button =
        buttons.pressed(MouseButton::Middle) || (alt && buttons.pressed(MouseButton::Left));
    let drag_start = buttons.just_pressed(MouseButton::Middle)
        || (alt && buttons.just_pressed(MouseButton::Left));
    if drag_start && gate.pointer_free && tool.active.is_none() {
        *dragging = true;
    }
    if !drag_button {
        *dragging = false;
    }
    let delta = motion.delta;
    if *dragging && delta != Vec2::ZERO {
        if shift {
            let scale = orbit.distance * 0.0015;
            let right = transform.rotation * Vec3::X;
            let up = transform.rotation * Vec3::Y;
            orbit.focus += (-right * delta.x + up * delta.y) * scale;
        } else if ctrl {
            orbit.distance = (orbit.distance * (1.0 + delta.y * 0.01)).clamp(0.01, 1e5);
        } else {
            orbit.yaw -= delta.x * 0.008;
            orbit.pitch =
                (orbit.pitch - delta.y * 0.008).clamp(-FRAC_PI_2 + 0.001, FRAC_PI_2 - 0.001);
        }
    }
    if gate.pointer_free && scroll.delta.y != 0.0 {
        let lines = match scroll.unit {
            MouseScrollUnit::Line => scroll.delta.y,
            MouseScrollUnit::Pixel => scroll.delta.y / 40.0,
        };
        orbit.distance = (orbit.distance * 0.88f32.powf(lines)).clamp(0.01, 1e5);
    }
    if gate.keyboard_free && tool.active.is_none() {
        let flip = if ctrl { std::f32::consts::PI } else { 0.0 };
        if keys.just_pressed(KeyCode::Numpad1) {
            (orbit.yaw, orbit.pitch) = (flip, 0.0);
        }
        if keys.just_pressed(KeyCode::Numpad3) {
            (orbit.yaw, orbit.pitch) = (FRAC_PI_2 + flip, 0.0);
        }
        if keys.just_pressed(KeyCode::Numpad7) {
            (orbit.yaw, orbit.pitch) = (
                0.0,
                if ctrl {
                    FRAC_PI_2 - 0.001
                } else {
                    -FRAC_PI_2 + 0.001
                },
            );
        }
    }
    let wanted = orbit.transform();
    if **transform != wanted {
        **transform = wanted;
    }
}

/// World-space bounds of the given nodes' meshes (or positions for empties).
pub fn world_bounds(
    state: &DocState,
    ids: impl IntoIterator<Item = hedra_doc::NodeId>,
) -> Option<(DVec3, DVec3)> {
    let doc = &state.session.doc;
    let mut acc: Option<(DVec3, DVec3)> = None;
    let mut add = |p: DVec3| {
        acc = Some(acc.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))));
    };
    for id in ids {
        let world = doc.world_matrix(id);
        match doc.node(id).map(|n| &n.content) {
            Some(NodeContent::Mesh(m)) => {
                if let Some((lo, hi)) = m.mesh.bounds() {
                    for i in 0..8 {
                        let c = DVec3::new(
                            if i & 1 == 0 { lo.x } else { hi.x },
                            if i & 2 == 0 { lo.y } else { hi.y },
                            if i & 4 == 0 { lo.z } else { hi.z },
                        );
                        add(world.transform_point3(c));
                    }
                }
            }
            Some(_) => add(world.w_axis.truncate()),
            None => {}
        }
    }
    acc
}

/// F or Numpad . frames the selection, Home frames everything.
fn frame_selection(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    tool: Res<TransformTool>,
    selection: Res<Selection>,
    state: Res<DocState>,
    mut camera: Single<&mut OrbitCamera, With<ViewportCamera>>,
    mode: Res<EditMode>,
) {
    if !gate.keyboard_free || tool.active.is_some() {
        return;
    }
    // In edit mode F fills holes; Numpad . still frames.
    let f_frames = !mode.active();
    let ctrl = modifiers::ctrl(&keys);
    let bounds = if !ctrl
        && ((f_frames && keys.just_pressed(KeyCode::KeyF))
            || keys.just_pressed(KeyCode::NumpadDecimal))
    {
        if selection.nodes.is_empty() {
            world_bounds(&state, state.session.doc.nodes().map(|n| n.id))
        } else {
            world_bounds(&state, selection.nodes.iter().copied())
        }
    } else if keys.just_pressed(KeyCode::Home) {
        world_bounds(&state, state.session.doc.nodes().map(|n| n.id))
    } else {
        return;
    };
    if let Some((lo, hi)) = bounds {
        camera.focus = ((lo + hi) * 0.5).as_vec3();
        let radius = ((hi - lo).length() * 0.5).max(0.1) as f32;
        camera.distance = radius / (22.5f32.to_radians()).sin() * 1.1;
    }
}

/// Axis lines are drawn over the grid lines they coincide with.
#[derive(Default, Reflect, GizmoConfigGroup)]
pub struct AxisGizmos;

fn draw_grid(mut grid: Gizmos, mut axes: Gizmos<AxisGizmos>) {
    grid.grid(
        Quat::from_rotation_x(FRAC_PI_2),
        UVec2::splat(20),
        Vec2::splat(1.0),
        LinearRgba::gray(0.3),
    );
    axes.line(
        Vec3::new(-10.0, 0.0, 0.0),
        Vec3::new(10.0, 0.0, 0.0),
        Color::srgb(0.85, 0.25, 0.3),
    );
    axes.line(
        Vec3::new(0.0, 0.0, -10.0),
        Vec3::new(0.0, 0.0, 10.0),
        Color::srgb(0.25, 0.45, 0.9),
    );
    axes.line(
        Vec3::ZERO,
        Vec3::new(0.0, 1.0, 0.0),
        Color::srgb(0.35, 0.8, 0.3),
    );
}

/// Keeps one retained line gizmo per mesh node with its edges: dark for
/// unselected meshes, orange for selected ones (yellow for the active one),
/// empty for hidden nodes and for the mesh in edit mode (drawn live there).
/// Retained gizmos ignore `Visibility`, so hiding means an empty asset.
/// Rebuilt only when the mesh, its selection state or its visibility changes.
#[allow(clippy::too_many_arguments)]
fn update_edge_overlays(
    mut commands: Commands,
    state: Res<DocState>,
    selection: Res<Selection>,
    mode: Res<EditMode>,
    shape_edit: Res<hedra_edit::ShapeEdit>,
    nodes: Query<(Entity, &NodeEntity, &ProjectedMesh, Option<&Children>)>,
    mut overlays: Query<(&mut EdgeOverlay, &Gizmo)>,
    mut assets: ResMut<Assets<GizmoAsset>>,
) {
    let doc = &state.session.doc;
    for (entity, node, projected, children) in &nodes {
        let selected = selection.contains(node.0);
        let active = selection.active() == Some(node.0);
        let shown = hedra_edit::visible(doc, node.0)
            && mode.node != Some(node.0)
            && shape_edit.node != Some(node.0);
        let wanted = EdgeOverlay {
            source: *projected,
            selected,
            active,
            shown,
        };
        let existing = children.and_then(|c| c.iter().find(|c| overlays.contains(*c)));
        if let Some(child) = existing {
            if overlays.get(child).is_ok_and(|(o, _)| *o == wanted) {
                continue;
            }
        }
        let Some(content) = doc.node(node.0).map(|n| &n.content) else {
            continue;
        };
        let color = match (selected, active) {
            (true, true) => Color::srgb(1.0, 0.78, 0.25),
            (true, false) => Color::srgb(0.95, 0.45, 0.1),
            _ => Color::srgba(0.05, 0.05, 0.07, 0.8),
        };
        let mut asset = GizmoAsset::new();
        match content {
            NodeContent::Mesh(content) if shown => {
                // A smooth preview shows its cage as light lines, or none.
                let smooth = hedra_scene::active_modifier(content);
                let color = match smooth {
                    Some(_) if !selected => Color::srgba(0.75, 0.78, 0.85, 0.55),
                    _ => color,
                };
                if smooth.is_none_or(|m| m.show_cage) {
                    let m = &content.mesh;
                    for e in m.edges() {
                        let [a, b] = m.edge_vertices(e);
                        asset.line(m.position(a).as_vec3(), m.position(b).as_vec3(), color);
                    }
                }
            }
            NodeContent::Curve(curve) if shown => {
                draw_curve(&mut asset, curve, selected, color);
            }
            NodeContent::Surface(surface) if shown && selected => {
                draw_control_net(&mut asset, surface, Color::srgba(0.85, 0.85, 0.9, 0.7));
            }
            _ => {}
        }
        let line_config = GizmoLineConfig {
            width: if selected { 2.5 } else { 1.0 },
            ..default()
        };
        match existing {
            Some(child) => {
                if let Ok((mut overlay, gizmo)) = overlays.get_mut(child) {
                    if let Some(mut a) = assets.get_mut(&gizmo.handle) {
                        *a = asset;
                    }
                    *overlay = wanted;
                    commands.entity(child).insert(Gizmo {
                        handle: gizmo.handle.clone(),
                        line_config,
                        depth_bias: -0.0005,
                    });
                }
            }
            None => {
                let handle = assets.add(asset);
                commands.spawn((
                    wanted,
                    Gizmo {
                        handle,
                        line_config,
                        depth_bias: -0.0005,
                    },
                    Transform::IDENTITY,
                    ChildOf(entity),
                ));
            }
        }
    }
}

/// A curve as a polyline (light, or the selection colour) and its control
/// polygon (dim; brighter when selected).
fn draw_curve(
    asset: &mut GizmoAsset,
    curve: &hedra_geom::curves::NurbsCurve,
    selected: bool,
    selection_color: Color,
) {
    use hedra_geom::curves::Curve;
    let tol = hedra_scene::VIEW_TOLERANCE * hedra_scene::extent(curve.points());
    let params = hedra_geom::surfaces::tessellate::curve_parameters(curve, tol);
    let color = if selected {
        selection_color
    } else {
        Color::srgb(0.92, 0.92, 0.95)
    };
    let points: Vec<Vec3> = params.iter().map(|&t| curve.point(t).as_vec3()).collect();
    asset.linestrip(points, color);
    let polygon = if selected {
        Color::srgba(0.9, 0.9, 0.95, 0.8)
    } else {
        Color::srgba(0.6, 0.6, 0.65, 0.45)
    };
    asset.linestrip(curve.points().iter().map(|p| p.as_vec3()), polygon);
}

/// The control net of a surface: rows and columns of a NURBS net, the
/// rows of a Bézier triangle's net in all three directions.
fn draw_control_net(asset: &mut GizmoAsset, surface: &hedra_doc::SurfaceShape, color: Color) {
    for [a, b] in control_net_segments(surface) {
        asset.line(a.as_vec3(), b.as_vec3(), color);
    }
}

/// The segments of a surface's control net (local space): rows and
/// columns of a NURBS net; the three edge directions of a Bézier
/// triangle's net.
fn control_net_segments(surface: &hedra_doc::SurfaceShape) -> Vec<[DVec3; 2]> {
    let mut out = Vec::new();
    match surface {
        hedra_doc::SurfaceShape::Nurbs(s) => {
            let (nu, nv) = s.size();
            let p = s.points();
            for i in 0..nu {
                for j in 0..nv {
                    if j + 1 < nv {
                        out.push([p[i * nv + j], p[i * nv + j + 1]]);
                    }
                    if i + 1 < nu {
                        out.push([p[i * nv + j], p[(i + 1) * nv + j]]);
                    }
                }
            }
        }
        hedra_doc::SurfaceShape::Triangle(t) => {
            use hedra_geom::surfaces::BezierTriangle;
            let n = t.degree;
            let at = |i: usize, j: usize| t.points[BezierTriangle::index(n, i, j)];
            for i in 0..n {
                for j in 0..n - i {
                    out.push([at(i, j), at(i, j + 1)]);
                    out.push([at(i, j), at(i + 1, j)]);
                    out.push([at(i + 1, j), at(i, j + 1)]);
                }
            }
        }
    }
    out
}

/// The transform gizmo follows the active object.
fn focus_gizmo_on_active(
    mut commands: Commands,
    selection: Res<Selection>,
    entities: Res<NodeEntities>,
    focused: Query<Entity, With<TransformGizmoFocus>>,
    gizmo_state: Res<TransformGizmoState>,
    mode: Res<EditMode>,
    shape_edit: Res<hedra_edit::ShapeEdit>,
) {
    if gizmo_state.active {
        return;
    }
    // No object gizmo in edit mode.
    let wanted = if mode.active() || shape_edit.active() {
        None
    } else {
        selection
            .active()
            .and_then(|id| entities.0.get(&id).copied())
    };
    for e in &focused {
        if Some(e) != wanted {
            commands.entity(e).remove::<TransformGizmoFocus>();
        }
    }
    if let Some(e) = wanted {
        if !focused.contains(e) {
            commands.entity(e).try_insert(TransformGizmoFocus);
        }
    }
}

/// When a gizmo drag ends, the entity's new transform becomes one document step.
fn commit_gizmo_drag(
    gizmo_state: Res<TransformGizmoState>,
    mut was_active: Local<Option<Entity>>,
    nodes: Query<(&NodeEntity, &Transform)>,
    state: Res<DocState>,
    mut requests: MessageWriter<DocRequest>,
) {
    if gizmo_state.active {
        *was_active = gizmo_state.entity;
        return;
    }
    let Some(entity) = was_active.take() else {
        return;
    };
    let Ok((node, t)) = nodes.get(entity) else {
        return;
    };
    let Some(doc_node) = state.session.doc.node(node.0) else {
        return;
    };
    let new = DocTransform {
        translation: t.translation.as_dvec3(),
        rotation: t.rotation.as_dquat().normalize(),
        scale: t.scale.as_dvec3(),
    };
    let old = DocTransform {
        translation: doc_node.transform.translation.as_vec3().as_dvec3(),
        rotation: doc_node.transform.rotation.as_quat().as_dquat(),
        scale: doc_node.transform.scale.as_vec3().as_dvec3(),
    };
    if new != old {
        requests.write(DocRequest::Execute(hedra_doc::Command::SetTransforms {
            nodes: vec![(NodeRef::from(node.0), new)],
        }));
    }
}

/// The edited mesh's edges as one retained line gizmo, rebuilt only when the
/// mesh (or a tool's preview), the selection or the element kind changes:
/// a dense mesh costs nothing per frame while nothing changes.
#[derive(Component)]
pub struct EditEdges;

#[allow(clippy::type_complexity)]
fn update_edit_edges(
    mut commands: Commands,
    mode: Res<EditMode>,
    state: Res<DocState>,
    mut assets: ResMut<Assets<GizmoAsset>>,
    mut overlay: Local<Option<(Entity, Handle<GizmoAsset>)>>,
    mut built: Local<Option<u64>>,
    mut transforms: Query<&mut Transform, With<EditEdges>>,
) {
    use std::hash::{Hash, Hasher};
    let mesh = mode.node.and(
        mode.preview
            .clone()
            .or_else(|| hedra_edit::mesh_mode::edited_mesh(&state, &mode)),
    );
    let key = mesh.as_ref().map(|m| {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        (
            mode.node,
            std::sync::Arc::as_ptr(m) as usize,
            &mode.selection,
            mode.kind as u8,
            state.revision,
            mode.preview_creases
                .as_ref()
                .map(hedra_scene::creases_fingerprint),
        )
            .hash(&mut h);
        h.finish()
    });
    // The overlay follows the node's world transform every frame (the
    // entity spawned on the first frame has no Transform to set yet).
    if let (Some((entity, _)), Some(node)) = (overlay.as_ref(), mode.node) {
        if let Ok(mut t) = transforms.get_mut(*entity) {
            let want = Transform::from_matrix(state.session.doc.world_matrix(node).as_mat4());
            if *t != want {
                *t = want;
            }
        }
    }
    if *built == key {
        return;
    }
    *built = key;
    let (_, handle) = overlay.get_or_insert_with(|| {
        let handle = assets.add(GizmoAsset::new());
        let line_config = GizmoLineConfig {
            width: 1.5,
            ..default()
        };
        let e = commands
            .spawn((
                EditEdges,
                Gizmo {
                    handle: handle.clone(),
                    line_config,
                    depth_bias: -0.001,
                },
                Transform::IDENTITY,
            ))
            .id();
        (e, handle)
    });
    let mut asset = GizmoAsset::new();
    if let (Some(node), Some(mesh)) = (mode.node, mesh) {
        let creases = mode.preview_creases.clone().or_else(|| {
            match state.session.doc.node(node).map(|n| &n.content) {
                Some(NodeContent::Mesh(c)) => Some(c.creases.clone()),
                _ => None,
            }
        });
        draw_edit_edges(&mut asset, &mesh, &mode, &creases.unwrap_or_default());
    }
    if let Some(mut a) = assets.get_mut(handle.id()) {
        *a = asset;
    }
}

/// Edges in mesh space: selected ones orange, the inspector's related ones
/// cyan, creased ones magenta (brighter the sharper).
fn draw_edit_edges(
    asset: &mut GizmoAsset,
    mesh: &hedra_geom::HalfEdgeMesh,
    mode: &EditMode,
    creases: &hedra_geom::subdivision::Creases,
) {
    let sel = &mode.selection;
    let selected_vertices = sel.all_vertices(mesh);
    let orange = Color::srgb(1.0, 0.55, 0.1);
    let cyan = Color::srgb(0.2, 0.85, 0.95);
    let single = sel.vertices.len() + sel.edges.len() + sel.faces.len() == 1;
    let mut related_faces = std::collections::BTreeSet::new();
    let mut related_edges = std::collections::BTreeSet::new();
    if single {
        if let Some(&v) = sel.vertices.iter().next().filter(|v| mesh.is_vertex(**v)) {
            related_faces.extend(mesh.vertex_faces(v));
        } else if let Some(&e) = sel.edges.iter().next().filter(|e| mesh.is_edge(**e)) {
            let w = hedra_geom::topology::winged_edge_row(mesh, e);
            related_edges.extend([
                w.left_predecessor,
                w.left_successor,
                w.right_predecessor,
                w.right_successor,
            ]);
        } else if let Some(&f) = sel.faces.iter().next().filter(|f| mesh.is_face(**f)) {
            related_faces.extend(mesh.face_neighbors(f));
        }
    }
    let overlay = hedra_doc::render::OverlaySelection {
        vertices: (mode.kind == ElementKind::Vertex).then_some(&selected_vertices),
        edges: &sel.edges,
        faces: &sel.faces,
        related_edges: &related_edges,
        related_faces: &related_faces,
    };
    for (a, b, look) in hedra_doc::render::edge_overlay(mesh, &overlay, creases) {
        use hedra_doc::render::EdgeLook;
        let color = match look {
            EdgeLook::Selected => orange,
            EdgeLook::Related => cyan,
            EdgeLook::Crease(c) => {
                let k = 0.35 + 0.65 * (c.min(10.0) / 10.0) as f32;
                Color::srgb(0.95 * k, 0.1 * k, 0.8 * k)
            }
            EdgeLook::Plain => Color::srgb(0.08, 0.08, 0.1),
        };
        asset.line(Vec3::from(a), Vec3::from(b), color);
    }
}

/// Edit mode's vertex or face-centre dots; they face the camera, so they are
/// drawn every frame (only the selected ones on dense meshes).
/// The analysis overlays of the active curve (seed 001's exercises), set
/// from the properties panel.
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct CurveAnalysis {
    /// Curvature comb: normals scaled by curvature along the curve.
    pub comb: bool,
    /// Length of the comb's teeth per unit of curvature.
    pub comb_scale: f64,
    /// Colour the curve by curvature (blue flat … red bent).
    pub colour_by_curvature: bool,
    /// A moving point with its Frenet frame and osculating circle.
    pub frame: bool,
    /// Where that point is, as a fraction of the domain.
    pub at: f64,
}

impl Default for CurveAnalysis {
    fn default() -> Self {
        CurveAnalysis {
            comb: false,
            comb_scale: 0.3,
            colour_by_curvature: false,
            frame: false,
            at: 0.5,
        }
    }
}

/// Draws the active curve's analysis overlays: curvature comb, colour by
/// curvature, and the Frenet frame (tangent red, normal green, binormal
/// blue) with the osculating circle at a moving point.
fn draw_curve_analysis(
    analysis: Res<CurveAnalysis>,
    selection: Res<Selection>,
    state: Res<DocState>,
    edit: Res<hedra_edit::ShapeEdit>,
    mut gizmos: Gizmos<AxisGizmos>,
) {
    use hedra_geom::curves::Curve;
    use hedra_geom::curves::analysis::{curvature, frenet_frame, osculating_circle};
    if !(analysis.comb || analysis.frame || analysis.colour_by_curvature) {
        return;
    }
    let Some(id) = selection.active() else { return };
    let doc = &state.session.doc;
    let preview = edit.preview.as_ref().filter(|_| edit.node == Some(id));
    let Some(NodeContent::Curve(c)) = preview.or_else(|| doc.node(id).map(|n| &n.content)) else {
        return;
    };
    let world = doc.world_matrix(id);
    let to_world = |p: DVec3| world.transform_point3(p).as_vec3();
    let (a, b) = c.domain();
    let samples = 300;
    let ts: Vec<f64> = (0..=samples)
        .map(|i| a + (b - a) * i as f64 / samples as f64)
        .collect();
    let ks: Vec<f64> = ts.iter().map(|&t| curvature(&**c, t)).collect();
    let k_max = ks.iter().copied().fold(1e-12, f64::max);
    if analysis.colour_by_curvature {
        for (w, k) in ts.windows(2).zip(&ks) {
            let x = (k / k_max) as f32;
            let colour = Color::srgb(x, 0.2, 1.0 - x);
            gizmos.line(to_world(c.point(w[0])), to_world(c.point(w[1])), colour);
        }
    }
    if analysis.comb {
        let mut tips = Vec::with_capacity(ts.len());
        for (&t, &k) in ts.iter().zip(&ks) {
            let p = c.point(t);
            // The comb points away from the centre of curvature.
            let tip = match frenet_frame(&**c, t) {
                Some([_, normal, _]) => p - normal * k * analysis.comb_scale,
                None => p,
            };
            if tips.len() % 3 == 0 {
                gizmos.line(to_world(p), to_world(tip), Color::srgba(0.4, 0.9, 1.0, 0.6));
            }
            tips.push(to_world(tip));
        }
        gizmos.linestrip(tips, Color::srgb(0.4, 0.9, 1.0));
    }
    if analysis.frame {
        let t = a + (b - a) * analysis.at.clamp(0.0, 1.0);
        let p = c.point(t);
        let size = hedra_scene::extent(c.points()) * 0.15;
        gizmos.sphere(
            Isometry3d::from_translation(to_world(p)),
            (size * 0.08) as f32,
            Color::WHITE,
        );
        if let Some([tangent, normal, binormal]) = frenet_frame(&**c, t) {
            for (v, colour) in [
                (tangent, Color::srgb(1.0, 0.25, 0.25)),
                (normal, Color::srgb(0.3, 1.0, 0.3)),
                (binormal, Color::srgb(0.35, 0.5, 1.0)),
            ] {
                gizmos.arrow(to_world(p), to_world(p + v * size), colour);
            }
        }
        if let Some((centre, radius)) = osculating_circle(&**c, t)
            && radius < 1e4 * hedra_scene::extent(c.points())
            && let Some([tangent, normal, _]) = frenet_frame(&**c, t)
        {
            let circle: Vec<Vec3> = (0..=96)
                .map(|i| {
                    let angle = std::f64::consts::TAU * i as f64 / 96.0;
                    to_world(centre + radius * (angle.cos() * tangent + angle.sin() * normal))
                })
                .collect();
            gizmos.linestrip(circle, Color::srgba(1.0, 0.85, 0.3, 0.8));
        }
    }
}

/// The analysis overlays of the active surface (seed 002's exercise): a
/// planar section and a moving domain point.
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct SurfaceAnalysis {
    pub section: bool,
    /// The section plane's normal axis (0 = X, 1 = Y, 2 = Z, local space).
    pub section_axis: usize,
    /// Where the plane is, as a fraction of the control net's extent.
    pub section_at: f64,
    pub domain_point: bool,
    /// The moving point's parameters, as fractions of the domain.
    pub u: f64,
    pub v: f64,
}

impl Default for SurfaceAnalysis {
    fn default() -> Self {
        SurfaceAnalysis {
            section: false,
            section_axis: 1,
            section_at: 0.5,
            domain_point: false,
            u: 0.5,
            v: 0.5,
        }
    }
}

/// Draws the active NURBS surface's planar section (the plane's outline
/// and the cut) and the moving domain point with its iso-parameter curves.
fn draw_surface_analysis(
    analysis: Res<SurfaceAnalysis>,
    selection: Res<Selection>,
    state: Res<DocState>,
    mut gizmos: Gizmos<AxisGizmos>,
    mut tessellated: Local<
        Option<(
            std::sync::Arc<hedra_doc::SurfaceShape>,
            hedra_geom::surfaces::tessellate::SurfaceMesh,
        )>,
    >,
) {
    use hedra_geom::surfaces::Surface;
    if !(analysis.section || analysis.domain_point) {
        return;
    }
    let Some(id) = selection.active() else { return };
    let doc = &state.session.doc;
    let Some(NodeContent::Surface(shape)) = doc.node(id).map(|n| &n.content) else {
        return;
    };
    let hedra_doc::SurfaceShape::Nurbs(s) = &**shape else {
        return;
    };
    let world = doc.world_matrix(id);
    let to_world = |p: DVec3| world.transform_point3(p).as_vec3();
    if analysis.section {
        let (lo, hi) = s
            .points()
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        let axis = analysis.section_axis.min(2);
        let normal = [DVec3::X, DVec3::Y, DVec3::Z][axis];
        let origin = lo.lerp(hi, analysis.section_at.clamp(0.0, 1.0)) * normal
            + (lo + hi) / 2.0 * (DVec3::ONE - normal);
        // The plane: a square a little larger than the net.
        let half = (hi - lo).max_element() * 0.6;
        let (a, b) = match axis {
            0 => (DVec3::Y, DVec3::Z),
            1 => (DVec3::X, DVec3::Z),
            _ => (DVec3::X, DVec3::Y),
        };
        let corners = [
            (-1.0, -1.0),
            (1.0, -1.0),
            (1.0, 1.0),
            (-1.0, 1.0),
            (-1.0, -1.0),
        ]
        .map(|(x, y)| to_world(origin + half * (x * a + y * b)));
        gizmos.linestrip(corners, Color::srgba(0.6, 0.8, 1.0, 0.6));
        // Tessellated once per shape, not every frame the section is drawn
        // (the cache holds the shape, so its identity cannot be reused).
        if tessellated
            .as_ref()
            .is_none_or(|(k, _)| !std::sync::Arc::ptr_eq(k, shape))
        {
            let tol = hedra_scene::VIEW_TOLERANCE * hedra_scene::extent(s.points());
            let mesh = hedra_geom::surfaces::tessellate::tessellate_nurbs(s, tol);
            *tessellated = Some((shape.clone(), mesh));
        }
        let (_, mesh) = tessellated.as_ref().expect("filled above");
        for [p, q] in hedra_geom::surfaces::tessellate::plane_section(mesh, origin, normal) {
            gizmos.line(to_world(p), to_world(q), Color::srgb(1.0, 0.3, 0.9));
        }
    }
    if analysis.domain_point {
        let ((u0, u1), (v0, v1)) = s.domain();
        let u = u0 + (u1 - u0) * analysis.u.clamp(0.0, 1.0);
        let v = v0 + (v1 - v0) * analysis.v.clamp(0.0, 1.0);
        let iso_u: Vec<Vec3> = (0..=100)
            .map(|k| to_world(s.point(u, v0 + (v1 - v0) * k as f64 / 100.0)))
            .collect();
        let iso_v: Vec<Vec3> = (0..=100)
            .map(|k| to_world(s.point(u0 + (u1 - u0) * k as f64 / 100.0, v)))
            .collect();
        gizmos.linestrip(iso_u, Color::srgb(1.0, 0.85, 0.3));
        gizmos.linestrip(iso_v, Color::srgb(0.4, 1.0, 0.5));
        let e = s.evaluate(u, v);
        let size = hedra_scene::extent(s.points()) * 0.12;
        gizmos.sphere(
            Isometry3d::from_translation(to_world(e.p)),
            (size * 0.1) as f32,
            Color::WHITE,
        );
        gizmos.arrow(
            to_world(e.p),
            to_world(e.p + e.normal() * size),
            Color::srgb(0.35, 0.5, 1.0),
        );
    }
}

/// Shape edit mode: the curve (or surface's control net) as the running
/// tool would leave it, with its control points (selected ones orange,
/// larger the heavier their weight).
fn draw_shape_edit(
    edit: Res<hedra_edit::ShapeEdit>,
    state: Res<DocState>,
    camera: Single<&GlobalTransform, With<ViewportCamera>>,
    mut gizmos: Gizmos<AxisGizmos>,
) {
    use hedra_edit::shape_mode::{control_points, control_weights};
    let Some(node) = edit.node else { return };
    let Some(content) = edit
        .preview
        .clone()
        .or_else(|| state.session.doc.node(node).map(|n| n.content.clone()))
    else {
        return;
    };
    let world = state.session.doc.world_matrix(node);
    let to_world = |p: DVec3| world.transform_point3(p).as_vec3();
    let net = Color::srgba(0.9, 0.9, 0.95, 0.85);
    match &content {
        NodeContent::Curve(c) => {
            use hedra_geom::curves::Curve;
            let tol = hedra_scene::VIEW_TOLERANCE * hedra_scene::extent(c.points());
            let params = hedra_geom::surfaces::tessellate::curve_parameters(&**c, tol);
            gizmos.linestrip(
                params.iter().map(|&t| to_world(c.point(t))),
                Color::srgb(1.0, 0.78, 0.25),
            );
            gizmos.linestrip(c.points().iter().map(|p| to_world(*p)), net);
        }
        NodeContent::Surface(s) => {
            for [a, b] in control_net_segments(s) {
                gizmos.line(to_world(a), to_world(b), net);
            }
        }
        _ => return,
    }
    let cam = *camera;
    let weights = control_weights(&content);
    for (i, p) in control_points(&content).into_iter().enumerate() {
        let p = to_world(p);
        let w = weights.as_ref().map_or(1.0, |w| w[i]) as f32;
        let r = cam.translation().distance(p) * 0.005 * w.clamp(0.25, 4.0).sqrt();
        let c = if edit.selected.contains(&(i as u32)) {
            Color::srgb(1.0, 0.55, 0.1)
        } else {
            Color::srgb(0.05, 0.05, 0.05)
        };
        gizmos
            .circle(Isometry3d::new(p, cam.rotation()), r, c)
            .resolution(12);
    }
}

fn draw_edit_overlay(
    mode: Res<EditMode>,
    state: Res<DocState>,
    camera: Single<&GlobalTransform, With<ViewportCamera>>,
    mut gizmos: Gizmos<AxisGizmos>,
) {
    let Some(node) = mode.node else { return };
    let Some(mesh) = mode
        .preview
        .clone()
        .or_else(|| hedra_edit::mesh_mode::edited_mesh(&state, &mode))
    else {
        return;
    };
    let world = state.session.doc.world_matrix(node);
    let sel = &mode.selection;
    let orange = Color::srgb(1.0, 0.55, 0.1);
    let cam = *camera;
    let rotation = cam.rotation();
    let dense = mesh.vertex_count() > 20_000;
    let mut dot = |p: DVec3, selected: bool, size: f32| {
        let p = world.transform_point3(p).as_vec3();
        let r = cam.translation().distance(p) * size;
        let c = if selected {
            orange
        } else {
            Color::srgb(0.05, 0.05, 0.05)
        };
        gizmos
            .circle(Isometry3d::new(p, rotation), r, c)
            .resolution(8);
    };
    match mode.kind {
        ElementKind::Vertex => {
            for v in mesh
                .vertices()
                .filter(|v| !dense || sel.vertices.contains(v))
            {
                dot(mesh.position(v), sel.vertices.contains(&v), 0.004);
            }
        }
        ElementKind::Face => {
            for f in mesh.faces().filter(|f| !dense || sel.faces.contains(f)) {
                dot(mesh.face_centroid(f), sel.faces.contains(&f), 0.003);
            }
        }
        ElementKind::Edge => {}
    }
}
