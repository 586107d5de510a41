//! Edge overlays of meshes (selection highlighted), curves, control nets and the edit-mode overlay.

use crate::*;
use by_address::ByAddress;
use hedra_doc::NodeId;
use hedra_geom::HalfEdgeMesh;
use hedra_scene::{NodeKeptMesh, NodeMesh, Shape, ShownMesh, ShownShape};
use std::sync::Arc;

/// Overlay child entity showing a mesh node's edges, and what it was built for.
#[derive(Component, Debug, Clone, PartialEq, Eq)]
pub struct EdgeOverlay {
    /// What the lines were built from: the shown content, held and compared
    /// by identity (a change, a tool's preview included, rebuilds them).
    pub source: hedra_scene::ContentSource,
    /// A mesh's look as far as its cage lines go: smoothed, the modifier's
    /// Show cage, and smoothed or modified (a derived surface).
    pub look: Option<(bool, bool, bool)>,
    /// The node is selected (orange lines).
    pub selected: bool,
    /// The node is the active one (yellow lines).
    pub active: bool,
    /// The node is visible and not being edited; when false the overlay is empty.
    pub shown: bool,
    /// Wireframe shading is on: unselected wires are drawn light, since
    /// no face is behind them.
    pub wireframe: bool,
    /// Cages over smoothed and modified meshes are drawn (View ▸ Cages).
    pub cages: bool,
}

/// Keeps one retained line gizmo per mesh node with its edges: dark for
/// unselected meshes, orange for selected ones (yellow for the active one),
/// empty for hidden nodes and for the mesh in edit mode (drawn live there).
/// Retained gizmos ignore `Visibility`, so hiding means an empty asset.
/// Rebuilt only when the mesh, its selection state or its visibility changes.
#[allow(clippy::too_many_arguments)]
pub(crate) fn update_edge_overlays(
    mut commands: Commands,
    state: Res<DocState>,
    selection: Res<Selection>,
    mode: Res<EditMode>,
    shape_edit: Res<hedra_edit::ShapeEdit>,
    nodes: Query<(
        Entity,
        &NodeEntity,
        Option<(&ShownMesh, &NodeMesh)>,
        Option<&ShownShape>,
        Option<&NodeKeptMesh>,
        Option<&Children>,
    )>,
    mut overlays: Query<(&mut EdgeOverlay, &Gizmo)>,
    mut assets: ResMut<Assets<GizmoAsset>>,
    shading: Res<hedra_scene::ViewportShading>,
) {
    let doc = &state.session.doc;
    let wireframe = shading.wireframe;
    for (entity, node, mesh, shape, kept, children) in &nodes {
        use hedra_scene::ContentSource;
        let source = match (mesh, shape, kept) {
            (Some((shown, _)), _, _) => ContentSource::Mesh(ByAddress(shown.cage.clone())),
            (_, Some(shown), _) => match &shown.shape {
                Shape::Curve(c) => ContentSource::Curve(ByAddress(c.clone())),
                Shape::Surface(s) => ContentSource::Surface(ByAddress(s.clone())),
            },
            (_, _, Some(k)) => ContentSource::Kept(ByAddress(k.0.mesh.clone())),
            _ => continue,
        };
        // A smooth preview shows its cage as light lines, or none; a cage
        // over a smoothed or modified mesh unless hidden.
        let look = mesh.map(|(_, m)| {
            let smooth = m.active_modifier();
            let derived = smooth.is_some() || !m.modifiers.is_empty();
            (
                smooth.is_some(),
                smooth.is_none_or(|m| m.show_cage),
                derived,
            )
        });
        let selected = selection.contains(node.0);
        let active = selection.active() == Some(node.0);
        // A CSG operand is drawn through its CSG node's solid (and as a
        // ghost while that is selected: `draw_csg_ghosts`), not by itself.
        let shown = hedra_edit::visible(doc, node.0)
            && !hedra_doc::csg::inside_csg(doc, node.0)
            && mode.node != Some(node.0)
            && shape_edit.node != Some(node.0);
        let wanted = EdgeOverlay {
            source: source.clone(),
            look,
            selected,
            active,
            shown,
            wireframe,
            cages: shading.cages,
        };
        let existing = children.and_then(|c| c.iter().find(|c| overlays.contains(*c)));
        if let Some(child) = existing
            && overlays.get(child).is_ok_and(|(o, _)| *o == wanted)
        {
            continue;
        }
        let color = match (selected, active) {
            (true, true) => Color::srgb(1.0, 0.78, 0.25),
            (true, false) => Color::srgb(0.95, 0.45, 0.1),
            _ if wireframe => Color::srgba(0.85, 0.87, 0.9, 0.9),
            _ => Color::srgba(0.05, 0.05, 0.07, 0.8),
        };
        let mut asset = GizmoAsset::new();
        match (&source, look) {
            (ContentSource::Mesh(m), Some((smooth, show_cage, derived))) if shown => {
                let color = match smooth {
                    true if !selected => Color::srgba(0.75, 0.78, 0.85, 0.55),
                    _ => color,
                };
                // View ▸ Cages, or the modifier's Show cage.
                if show_cage && (wanted.cages || !derived) {
                    for e in m.edges() {
                        let [a, b] = m.edge_vertices(e);
                        asset.line(m.position(a).as_vec3(), m.position(b).as_vec3(), color);
                    }
                }
            }
            (ContentSource::Kept(k), _) if shown => draw_kept_edges(&mut asset, k, color),
            (ContentSource::Curve(curve), _) if shown => {
                draw_curve(&mut asset, curve, selected, color);
            }
            (ContentSource::Surface(surface), _) if shown && selected => {
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
pub(crate) fn draw_curve(
    asset: &mut GizmoAsset,
    content: &hedra_doc::CurveContent,
    selected: bool,
    selection_color: Color,
) {
    use hedra_geom::curves::Curve;
    let curve: &hedra_geom::curves::NurbsCurve = content.nurbs();
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
    // The kind's defining points: NURBS control polygon, poly-Bézier
    // anchors and handles, interpolation points, a fractal's initiator.
    asset.linestrip(
        content.control_points().iter().map(|p| p.as_vec3()),
        polygon,
    );
}

/// The control net of a surface: rows and columns of a NURBS net, the
/// rows of a Bézier triangle's net in all three directions.
pub(crate) fn draw_control_net(
    asset: &mut GizmoAsset,
    surface: &hedra_doc::SurfaceShape,
    color: Color,
) {
    for [a, b] in control_net_segments(surface) {
        asset.line(a.as_vec3(), b.as_vec3(), color);
    }
}

/// The segments of a surface's control net (local space): rows and
/// columns of a NURBS net; the three edge directions of a Bézier
/// triangle's net.
pub(crate) fn control_net_segments(surface: &hedra_doc::SurfaceShape) -> Vec<[DVec3; 2]> {
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

/// The edited mesh's edges as one retained line gizmo, rebuilt only when the
/// mesh (or a tool's preview), the selection or the element kind changes:
/// a dense mesh costs nothing per frame while nothing changes.
#[derive(Component)]
pub struct EditEdges;

#[allow(clippy::type_complexity)]
pub(crate) fn update_edit_edges(
    mut commands: Commands,
    mode: Res<EditMode>,
    state: Res<DocState>,
    shown: hedra_scene::Shown,
    mut assets: ResMut<Assets<GizmoAsset>>,
    mut overlay: Local<Option<(Entity, Handle<GizmoAsset>)>>,
    mut built: Local<Option<(ByAddress<Arc<HalfEdgeMesh>>, u64)>>,
    mut transforms: Query<&mut Transform, With<EditEdges>>,
) {
    use std::hash::{Hash, Hasher};
    let shown = mode.node.and_then(|n| shown.mesh(n));
    let key = shown.map(|(m, creases)| {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        (
            mode.node,
            &mode.selection,
            mode.kind as u8,
            state.revision,
            hedra_scene::creases_fingerprint(creases),
        )
            .hash(&mut h);
        // The mesh is held in the key, so its address cannot be reused.
        (ByAddress(m.clone()), h.finish())
    });
    // The overlay follows the node's world transform every frame (the
    // entity spawned on the first frame has no Transform to set yet).
    if let (Some((entity, _)), Some(node)) = (overlay.as_ref(), mode.node)
        && let Ok(mut t) = transforms.get_mut(*entity)
    {
        let want = Transform::from_matrix(state.session.doc.world_matrix(node).as_mat4());
        if *t != want {
            *t = want;
        }
    }
    if *built == key {
        return;
    }
    // A tool that only moves vertices (G, R, S, a drag after an extrude):
    // the same lines and colours at new places, written in place.
    let moved_only = match (built.as_ref(), &key, shown, overlay.as_ref()) {
        (Some((old, old_hash)), Some((_, hash)), Some((mesh, creases)), Some((_, handle))) => {
            old_hash == hash
                && creases.holes.is_empty()
                && old.0.same_connectivity(mesh)
                && assets
                    .get_mut(handle.id())
                    .is_some_and(|mut asset| move_edge_lines(&mut asset, mesh))
        }
        _ => false,
    };
    *built = key;
    if moved_only {
        return;
    }
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
    if let Some((mesh, creases)) = shown {
        draw_edit_edges(&mut asset, mesh, &mode, creases);
    }
    if let Some(mut a) = assets.get_mut(handle.id()) {
        *a = asset;
    }
}

/// Moves the lines of an edit-edge overlay built by [`draw_edit_edges`]
/// for a mesh of the same connectivity to `mesh`'s positions (one line per
/// live edge, in id order). False, changing nothing, when the asset does
/// not hold exactly those lines.
fn move_edge_lines(asset: &mut GizmoAsset, mesh: &HalfEdgeMesh) -> bool {
    let lines = &mut asset.list_positions;
    if lines.len() != 2 * mesh.edge_count() {
        return false;
    }
    for (i, e) in mesh.edges().enumerate() {
        let [a, b] = mesh.edge_vertices(e);
        lines[2 * i] = mesh.position(a).as_vec3();
        lines[2 * i + 1] = mesh.position(b).as_vec3();
    }
    true
}

/// Edges in mesh space: selected ones orange, the inspector's related ones
/// cyan, creased ones magenta (brighter the sharper).
pub(crate) fn draw_edit_edges(
    asset: &mut GizmoAsset,
    mesh: &hedra_geom::HalfEdgeMesh,
    mode: &EditMode,
    creases: &hedra_geom::subdivision::Creases,
) {
    let sel = &mode.selection;
    let selected_vertices = sel.all_vertices(mesh);
    // Colours in linear space once (see `draw_edit_overlay`).
    let linear = |c: Color| -> Color { c.to_linear().into() };
    let orange = linear(Color::srgb(1.0, 0.55, 0.1));
    let cyan = linear(Color::srgb(0.2, 0.85, 0.95));
    let plain = linear(Color::srgb(0.08, 0.08, 0.1));
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
                linear(Color::srgb(0.95 * k, 0.1 * k, 0.8 * k))
            }
            EdgeLook::Plain => plain,
        };
        asset.line(Vec3::from(a), Vec3::from(b), color);
    }
    // Subdivision holes: a star from each hole face's middle to its corners.
    let hole = Color::srgb(0.6, 0.15, 0.55);
    for &f in creases.holes.iter().filter(|f| mesh.is_face(**f)) {
        let middle = mesh.face_centroid(f).as_vec3();
        for v in mesh.face_vertices(f) {
            asset.line(middle, mesh.position(v).as_vec3(), hole);
        }
    }
}

/// Shape edit mode: the curve (or surface's control net) as the running
/// tool would leave it, with its control points (selected ones orange,
/// larger the heavier their weight), read from the control-point entities.
pub(crate) fn draw_shape_edit(
    edit: Res<hedra_edit::ShapeEdit>,
    state: Res<DocState>,
    shown: hedra_scene::Shown,
    entities: Res<hedra_scene::NodeEntities>,
    points: Query<(&hedra_scene::ControlPoint, &ChildOf)>,
    camera: Single<&GlobalTransform, With<ViewportCamera>>,
    mut gizmos: Gizmos<AxisGizmos>,
) {
    let Some(node) = edit.node else { return };
    let Some(content) = shown.shape(node) else {
        return;
    };
    let world = state.session.doc.world_matrix(node);
    let to_world = |p: DVec3| world.transform_point3(p).as_vec3();
    // Colours in linear space once (see `draw_edit_overlay`).
    let linear = |c: Color| -> Color { c.to_linear().into() };
    let net = linear(Color::srgba(0.9, 0.9, 0.95, 0.85));
    match &content {
        NodeContent::Curve(content) => {
            use hedra_geom::curves::Curve;
            let c = content.nurbs();
            let tol = hedra_scene::VIEW_TOLERANCE * hedra_scene::extent(c.points());
            let params = hedra_geom::surfaces::tessellate::curve_parameters(&**c, tol);
            gizmos.linestrip(
                params.iter().map(|&t| to_world(c.point(t))),
                Color::srgb(1.0, 0.78, 0.25),
            );
            gizmos.linestrip(content.control_points().iter().map(|p| to_world(*p)), net);
            // Tangents as handles: dragged ones (Hermite) bright, derived
            // ones (Catmull-Rom, Kochanek-Bartels, C2 spline) dim.
            let kind = content.kind();
            let handle = if kind.handles_editable() {
                Color::srgb(0.45, 0.8, 1.0)
            } else {
                Color::srgba(0.45, 0.8, 1.0, 0.5)
            };
            let keys = kind.points();
            for h in kind.tangent_handles() {
                gizmos.line(to_world(keys[h.point]), to_world(h.end), handle);
            }
        }
        NodeContent::Surface(s) => {
            for [a, b] in control_net_segments(s) {
                gizmos.line(to_world(a), to_world(b), net);
            }
        }
        _ => return,
    }
    let cam = *camera;
    let Some(&entity) = entities.0.get(&node) else {
        return;
    };
    // A G1 join's points: on the joint cyan, those that follow violet.
    let roles = state.session.doc.g1_roles(node).unwrap_or_default();
    let (selected, shared, dependent, plain) = (
        linear(Color::srgb(1.0, 0.55, 0.1)),
        linear(Color::srgb(0.2, 0.85, 1.0)),
        linear(Color::srgb(0.75, 0.4, 1.0)),
        linear(Color::srgb(0.05, 0.05, 0.05)),
    );
    let all = hedra_scene::control_points_of(entity, &points);
    // A dense net's points as hexagons: half the lines of a 12-gon.
    let resolution = if all.len() > 2_000 { 6 } else { 12 };
    // The control-point entities: position and weight as the screen shows them.
    for point in all {
        let p = to_world(point.position);
        let w = point.weight as f32;
        let r = cam.translation().distance(p) * 0.005 * w.clamp(0.25, 4.0).sqrt();
        use hedra_geom::surfaces::patches::PointRole;
        let c = match roles.get(point.index as usize) {
            _ if edit.selected.contains(&point.index) => selected,
            Some(PointRole::Shared) => shared,
            Some(PointRole::Dependent) => dependent,
            _ => plain,
        };
        gizmos
            .circle(Isometry3d::new(p, cam.rotation()), r, c)
            .resolution(resolution);
    }
}

pub(crate) fn draw_edit_overlay(
    mode: Res<EditMode>,
    state: Res<DocState>,
    shown: hedra_scene::Shown,
    camera: Single<&GlobalTransform, With<ViewportCamera>>,
    mut gizmos: Gizmos<AxisGizmos>,
) {
    let Some(node) = mode.node else { return };
    let Some((mesh, _)) = shown.mesh(node) else {
        return;
    };
    let world = state.session.doc.world_matrix(node);
    let sel = &mode.selection;
    // Colours in linear space once: a gizmo converts an sRGB colour with
    // three powf per point, millions of times in a frame of a dense mesh.
    let orange: Color = Color::srgb(1.0, 0.55, 0.1).to_linear().into();
    let dark: Color = Color::srgb(0.05, 0.05, 0.05).to_linear().into();
    let cam = *camera;
    let rotation = cam.rotation();
    // A dense mesh shows only its selected elements' dots, walked from the
    // selection (not a set lookup for each of a million elements).
    let dense = mesh.vertex_count() > 20_000;
    let dots = match (mode.kind, dense) {
        (ElementKind::Vertex, true) => sel.vertices.len(),
        (ElementKind::Face, true) => sel.faces.len(),
        (ElementKind::Vertex, false) => mesh.vertex_count(),
        (ElementKind::Face, false) => mesh.face_count(),
        (ElementKind::Edge, _) => 0,
    };
    // Many dots are drawn as diamonds: half the lines of an octagon.
    let resolution = if dots > 10_000 { 4 } else { 8 };
    let mut dot = |p: DVec3, selected: bool, size: f32| {
        let p = world.transform_point3(p).as_vec3();
        let r = cam.translation().distance(p) * size;
        let c = if selected { orange } else { dark };
        gizmos
            .circle(Isometry3d::new(p, rotation), r, c)
            .resolution(resolution);
    };
    match (mode.kind, dense) {
        (ElementKind::Vertex, true) => {
            for &v in sel.vertices.iter().filter(|v| mesh.is_vertex(**v)) {
                dot(mesh.position(v), true, 0.004);
            }
        }
        (ElementKind::Vertex, false) => {
            for v in mesh.vertices() {
                dot(mesh.position(v), sel.vertices.contains(&v), 0.004);
            }
        }
        (ElementKind::Face, true) => {
            for &f in sel.faces.iter().filter(|f| mesh.is_face(**f)) {
                dot(mesh.face_centroid(f), true, 0.003);
            }
        }
        (ElementKind::Face, false) => {
            for f in mesh.faces() {
                dot(mesh.face_centroid(f), sel.faces.contains(&f), 0.003);
            }
        }
        (ElementKind::Edge, _) => {}
    }
}

/// Most edges a CSG ghost draws per operand (denser operands are thinned:
/// every k-th edge).
const GHOST_EDGES: usize = 20_000;

/// The operands of the selected CSG tree as wireframe ghosts (Blender's
/// Boolean cutters shown as wire), while the CSG node or a part of it is
/// selected: where each operand is on screen, following a drag (the
/// entities' transforms carry the tools' previews).
pub(crate) fn draw_csg_ghosts(
    selection: Res<Selection>,
    state: Res<DocState>,
    map: Res<hedra_scene::NodeEntities>,
    transforms: Query<&GlobalTransform>,
    mut gizmos: Gizmos<CursorGizmos>,
) {
    let doc = &state.session.doc;
    let mut tops: Vec<NodeId> = selection
        .nodes
        .iter()
        .filter_map(|&id| {
            hedra_edit::outermost_csg(doc, id)
                .or_else(|| hedra_doc::csg::is_csg(doc, id).then_some(id))
        })
        .collect();
    tops.sort();
    tops.dedup();
    for top in tops {
        for id in doc.subtree(top) {
            if id == top || !hedra_doc::csg::inside_csg(doc, id) {
                continue;
            }
            let Some(NodeContent::Mesh(content)) = doc.node(id).map(|n| &n.content) else {
                continue;
            };
            let Some(world) = map.0.get(&id).and_then(|e| transforms.get(*e).ok()) else {
                continue;
            };
            let m = world.to_matrix();
            let selected = selection.contains(id);
            let color = if selected {
                Color::srgba(1.0, 0.6, 0.2, 0.9)
            } else {
                Color::srgba(0.6, 0.75, 1.0, 0.45)
            };
            let mesh = &content.mesh;
            let step = mesh.edge_count().div_ceil(GHOST_EDGES).max(1);
            for e in mesh.edges().step_by(step) {
                let [a, b] = mesh.edge_vertices(e);
                gizmos.line(
                    m.transform_point3(mesh.position(a).as_vec3()),
                    m.transform_point3(mesh.position(b).as_vec3()),
                    color,
                );
            }
        }
    }
}

/// The edges of a kept (non-manifold) mesh's faces, each once, in `color`;
/// the edges that make it not manifold (in three or more faces, or run the
/// same way by two) in magenta, so that the user sees where it needs a
/// repair.
fn draw_kept_edges(asset: &mut GizmoAsset, mesh: &hedra_doc::KeptMesh, color: Color) {
    let places = mesh.places();
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let marked: std::collections::HashSet<(u32, u32)> = places
        .crowded_edges
        .iter()
        .map(|([a, b], _)| key(*a, *b))
        .chain(places.same_way_edges.iter().map(|[a, b]| key(*a, *b)))
        .collect();
    let mut drawn = std::collections::HashSet::new();
    let magenta = Color::srgb(1.0, 0.1, 0.8);
    for face in &mesh.faces {
        for (i, &a) in face.iter().enumerate() {
            let b = face[(i + 1) % face.len()];
            if a == b || !drawn.insert(key(a, b)) {
                continue;
            }
            let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
            let c = if marked.contains(&key(a, b)) {
                magenta
            } else {
                color
            };
            asset.line(pa.as_vec3(), pb.as_vec3(), c);
        }
    }
}
