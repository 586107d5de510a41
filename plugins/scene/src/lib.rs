//! The document inside the app, and its projection into the ECS.
//!
//! [`DocState`] holds the one [`Session`]; [`DocRequest`] messages are the
//! only way to change it, and [`apply_requests`] is the only system that
//! applies them. After every change [`sync_entities`] mirrors the document:
//! one entity per node with `Transform`, `ChildOf`, `Visibility` and, for
//! meshes, a render mesh built from the half-edge mesh.

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use hedra_doc::file;
use hedra_doc::{Command, NodeContent, NodeId, Session, Shading};
use hedra_geom::HalfEdgeMesh;
use std::collections::HashMap;
use std::path::PathBuf;

mod smooth;
pub use smooth::{SmoothPreviews, SmoothSource};

/// The open document, where it lives on disk, and a change counter.
#[derive(Resource, Default)]
pub struct DocState {
    pub session: Session,
    pub path: Option<PathBuf>,
    /// Increases on every change of the document (command, undo, load, …).
    pub revision: u64,
    /// History serial when this document was created or opened: steps up to
    /// it were made in an earlier session (no "adjust last operation" for them).
    pub opened_serial: u64,
}

impl DocState {
    /// The file name for titles ("untitled" before the first save).
    pub fn display_name(&self) -> String {
        self.path.as_ref().and_then(|p| p.file_name()).map_or_else(
            || "untitled".to_string(),
            |n| n.to_string_lossy().into_owned(),
        )
    }
}

/// A request to change the document or its file. Sent by tools, panels and
/// shortcuts; applied in order by [`apply_requests`].
#[derive(Message, Clone, Debug)]
pub enum DocRequest {
    Execute(Command),
    /// Re-run the last step with changed parameters.
    AdjustLast(Command),
    Undo,
    Redo,
    /// Undo or redo until this many steps are done.
    JumpTo(usize),
    /// Replace the document with an empty one (callers ask about unsaved changes first).
    New,
    Open(PathBuf),
    Save(PathBuf),
    /// Add the meshes of an OBJ file as new nodes (one step).
    Import(PathBuf),
    /// Replace the document with a recovery point (autosave or emergency
    /// save); it belongs to its original file and is unsaved.
    Recover(hedra_doc::recovery::RecoveryEntry),
    /// Undo history limits from the preferences (steps, approximate bytes).
    HistoryLimits {
        steps: usize,
        bytes: usize,
    },
}

/// Sent after a request changed the document.
#[derive(Message, Clone, Debug, Default)]
pub struct DocChanged {
    /// Nodes the change created (tools select them).
    pub created: Vec<NodeId>,
    /// True when a new document replaced the old one (New/Open).
    pub replaced: bool,
}

/// The user-facing outcome of the latest request (status bar, error popups).
#[derive(Resource, Default, Debug)]
pub struct StatusMessage {
    pub text: String,
    pub is_error: bool,
    /// Warnings that need acknowledging (damaged history, …).
    pub warnings: Vec<String>,
    pub serial: u64,
}

impl StatusMessage {
    pub fn info(&mut self, text: impl Into<String>) {
        self.text = text.into();
        self.is_error = false;
        self.serial += 1;
    }
    pub fn error(&mut self, text: impl Into<String>) {
        self.text = text.into();
        self.is_error = true;
        self.serial += 1;
    }
}

/// The document node an entity mirrors.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct NodeEntity(pub NodeId);

/// Which half-edge mesh (by identity), shading and subdivision the render
/// mesh was built from.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProjectedMesh {
    pub source: usize,
    pub shading: Shading,
    /// The modifier and a fingerprint of the creases, for smooth previews.
    pub smooth: Option<(hedra_doc::SubdivisionModifier, u64)>,
}

/// A fingerprint of crease values, to notice when they change.
pub fn creases_fingerprint(creases: &hedra_geom::subdivision::Creases) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for (e, s) in &creases.edges {
        (e, s.to_bits()).hash(&mut h);
    }
    for (v, s) in &creases.vertices {
        (v, s.to_bits()).hash(&mut h);
    }
    h.finish()
}

/// The subdivision a mesh's content shows in the viewport, if any.
pub fn active_modifier(content: &hedra_doc::MeshContent) -> Option<hedra_doc::SubdivisionModifier> {
    content.subdivision.filter(|m| m.viewport_level > 0)
}

/// Node id → entity, kept by [`sync_entities`].
#[derive(Resource, Default, Debug)]
pub struct NodeEntities(pub HashMap<NodeId, Entity>);

/// The material every mesh node uses.
#[derive(Resource, Clone)]
pub struct MeshMaterial(pub Handle<StandardMaterial>);

/// System sets, in order.
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub enum SceneSystems {
    /// Applies [`DocRequest`]s.
    Apply,
    /// Mirrors the document into entities.
    Sync,
}

/// Document state, the apply system and the ECS projection.
pub struct ScenePlugin;

impl Plugin for ScenePlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<DocState>()
            .init_resource::<StatusMessage>()
            .init_resource::<NodeEntities>()
            .init_resource::<SmoothPreviews>()
            .init_resource::<InputGate>()
            .add_message::<DocRequest>()
            .add_message::<DocChanged>()
            .configure_sets(Update, (SceneSystems::Apply, SceneSystems::Sync).chain())
            .add_systems(Startup, setup_material)
            .add_systems(Update, apply_requests.in_set(SceneSystems::Apply))
            .add_systems(
                Update,
                (sync_entities, show_finished_smooth_previews)
                    .chain()
                    .in_set(SceneSystems::Sync),
            );
    }
}

fn setup_material(mut commands: Commands, mut materials: ResMut<Assets<StandardMaterial>>) {
    let handle = materials.add(StandardMaterial {
        base_color: Color::srgb(0.72, 0.72, 0.75),
        perceptual_roughness: 0.55,
        // Open meshes (planes, grids, holes) show their back faces too.
        double_sided: true,
        cull_mode: None,
        ..default()
    });
    commands.insert_resource(MeshMaterial(handle));
}

/// The one system that changes the document.
pub fn apply_requests(
    mut requests: MessageReader<DocRequest>,
    mut state: ResMut<DocState>,
    mut status: ResMut<StatusMessage>,
    mut changed: MessageWriter<DocChanged>,
) {
    for request in requests.read() {
        let state = &mut *state;
        let result: Result<Option<DocChanged>, String> =
            match request {
                DocRequest::Execute(cmd) => state
                    .session
                    .execute(cmd)
                    .map_err(|e| e.to_string())
                    .map(|a| {
                        status.info(a.label.clone());
                        Some(DocChanged {
                            created: a.created,
                            replaced: false,
                        })
                    }),
                DocRequest::AdjustLast(cmd) => state
                    .session
                    .adjust_last(cmd)
                    .map_err(|e| e.to_string())
                    .map(|a| {
                        status.info(a.label.clone());
                        Some(DocChanged {
                            created: a.created,
                            replaced: false,
                        })
                    }),
                DocRequest::Undo => Ok(match state.session.undo() {
                    Some(label) => {
                        status.info(format!("Undo {label}"));
                        Some(DocChanged::default())
                    }
                    None => {
                        status.info("Nothing to undo");
                        None
                    }
                }),
                DocRequest::Redo => Ok(match state.session.redo() {
                    Some(label) => {
                        status.info(format!("Redo {label}"));
                        Some(DocChanged::default())
                    }
                    None => {
                        status.info("Nothing to redo");
                        None
                    }
                }),
                DocRequest::JumpTo(n) => {
                    state.session.jump_to(*n);
                    Ok(Some(DocChanged::default()))
                }
                DocRequest::New => {
                    state.session = Session::new();
                    state.path = None;
                    state.opened_serial = 0;
                    status.info("New scene");
                    Ok(Some(DocChanged {
                        created: vec![],
                        replaced: true,
                    }))
                }
                DocRequest::Open(path) => match file::load(path) {
                    Ok(loaded) => {
                        state.session = loaded.session;
                        state.path = Some(path.clone());
                        state.opened_serial = state.session.history.current_serial();
                        status.info(format!("Opened {}", path.display()));
                        status.warnings.extend(loaded.warnings);
                        Ok(Some(DocChanged {
                            created: vec![],
                            replaced: true,
                        }))
                    }
                    Err(e) => Err(e.to_string()),
                },
                DocRequest::Recover(entry) => match hedra_doc::recovery::recover(entry) {
                    Ok(loaded) => {
                        state.session = loaded.session;
                        state.path = entry.meta.original.clone();
                        state.opened_serial = state.session.history.current_serial();
                        status.info(format!(
                            "Recovered {} — save to keep it",
                            state.display_name()
                        ));
                        status.warnings.extend(loaded.warnings);
                        Ok(Some(DocChanged {
                            created: vec![],
                            replaced: true,
                        }))
                    }
                    Err(e) => Err(format!("Recovery failed, the file was kept: {e}")),
                },
                DocRequest::HistoryLimits { steps, bytes } => {
                    let history = &mut state.session.history;
                    history.max_steps = (*steps).max(1);
                    history.max_bytes = *bytes;
                    let before = history.done().len();
                    history.enforce_limits();
                    if history.done().len() < before {
                        Ok(Some(DocChanged::default()))
                    } else {
                        Ok(None)
                    }
                }
                DocRequest::Import(path) => match hedra_doc::import::import_file(path) {
                    Ok(meshes) => {
                        let name = path.file_name().map_or_else(
                            || path.display().to_string(),
                            |n| n.to_string_lossy().into_owned(),
                        );
                        let a = state.session.import(&meshes, &format!("Import {name}"));
                        status.info(format!(
                            "Imported {} object(s) from {name}",
                            a.created.len()
                        ));
                        status.warnings.extend(
                            hedra_doc::import::describe_repairs(&meshes)
                                .into_iter()
                                .map(|n| format!("{name}: {n}")),
                        );
                        Ok(Some(DocChanged {
                            created: a.created,
                            replaced: false,
                        }))
                    }
                    Err(e) => Err(e.to_string()),
                },
                DocRequest::Save(path) => match file::save(&mut state.session, path) {
                    Ok(()) => {
                        state.path = Some(path.clone());
                        status.info(format!("Saved {}", path.display()));
                        // The document is unchanged, but the title's `*` must go.
                        Ok(Some(DocChanged::default()))
                    }
                    Err(e) => Err(format!("Save failed, nothing was lost: {e}")),
                },
            };
        match result {
            Ok(Some(c)) => {
                state.revision += 1;
                changed.write(c);
            }
            Ok(None) => {}
            Err(e) => status.error(e),
        }
    }
}

/// Mirrors the document into entities whenever its revision changes.
pub fn sync_entities(
    mut commands: Commands,
    state: Res<DocState>,
    mut seen_revision: Local<Option<u64>>,
    mut map: ResMut<NodeEntities>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut previews: ResMut<SmoothPreviews>,
    mut status: ResMut<StatusMessage>,
    material: Option<Res<MeshMaterial>>,
    mut existing: Query<(
        &mut Transform,
        &mut Visibility,
        Option<&ChildOf>,
        Option<&ProjectedMesh>,
        Option<&Mesh3d>,
    )>,
) {
    if *seen_revision == Some(state.revision) {
        return;
    }
    *seen_revision = Some(state.revision);
    let doc = &state.session.doc;

    // Spawn missing entities first so parents exist for ChildOf.
    for node in doc.nodes() {
        if !map.0.get(&node.id).is_some_and(|e| existing.contains(*e)) {
            let e = commands
                .spawn((
                    NodeEntity(node.id),
                    Name::new(node.name.clone()),
                    Transform::default(),
                    Visibility::default(),
                ))
                .id();
            map.0.insert(node.id, e);
        }
    }
    for node in doc.nodes() {
        let e = map.0[&node.id];
        let transform = Transform {
            translation: node.transform.translation.as_vec3(),
            rotation: node.transform.rotation.as_quat(),
            scale: node.transform.scale.as_vec3(),
        };
        let visibility = if node.visible {
            Visibility::Inherited
        } else {
            Visibility::Hidden
        };
        let parent = node.parent.and_then(|p| map.0.get(&p).copied());
        let mut ec = commands.entity(e);
        ec.insert(Name::new(node.name.clone()));
        match existing.get_mut(e) {
            Ok((mut t, mut v, child_of, projected, mesh3d)) => {
                if *t != transform {
                    *t = transform;
                }
                if *v != visibility {
                    *v = visibility;
                }
                match (parent, child_of.map(|c| c.parent())) {
                    (Some(p), Some(old)) if p == old => {}
                    (Some(p), _) => {
                        ec.insert(ChildOf(p));
                    }
                    (None, Some(_)) => {
                        ec.remove::<ChildOf>();
                    }
                    (None, None) => {}
                }
                project_mesh(
                    &mut ec,
                    node,
                    projected.copied(),
                    mesh3d,
                    &mut meshes,
                    &mut previews,
                    &mut status,
                    material.as_deref(),
                );
            }
            Err(_) => {
                ec.insert((transform, visibility));
                if let Some(p) = parent {
                    ec.insert(ChildOf(p));
                }
                project_mesh(
                    &mut ec,
                    node,
                    None,
                    None,
                    &mut meshes,
                    &mut previews,
                    &mut status,
                    material.as_deref(),
                );
            }
        }
    }
    // Despawn entities of deleted nodes (after reparenting, so survivors are detached first).
    let gone: Vec<NodeId> = map
        .0
        .keys()
        .filter(|id| doc.node(**id).is_none())
        .copied()
        .collect();
    previews.retain(|id| {
        doc.node(id).is_some_and(|n| match &n.content {
            NodeContent::Mesh(c) => active_modifier(c).is_some(),
            _ => false,
        })
    });
    for id in gone {
        if let Some(e) = map.0.remove(&id) {
            commands.entity(e).remove::<ChildOf>();
            commands.entity(e).try_despawn();
        }
    }
}

/// Puts smooth previews finished in the background on their nodes; Esc
/// cancels the ones still running.
pub fn show_finished_smooth_previews(
    mut previews: ResMut<SmoothPreviews>,
    keys: Option<Res<ButtonInput<KeyCode>>>,
    map: Res<NodeEntities>,
    state: Res<DocState>,
    mesh3d: Query<&Mesh3d>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut status: ResMut<StatusMessage>,
) {
    if keys.is_some_and(|k| k.just_pressed(KeyCode::Escape)) && !previews.progress().is_empty() {
        previews.cancel_all();
    }
    for job in previews.finished() {
        let name = state
            .session
            .doc
            .node(job.node)
            .map_or_else(|| job.node.to_string(), |n| n.name.clone());
        match job.result {
            Ok(mesh) => {
                let handle = map.0.get(&job.node).and_then(|e| mesh3d.get(*e).ok());
                if let Some(mut m) = handle.and_then(|h| meshes.get_mut(&h.0)) {
                    *m = mesh;
                }
            }
            Err(e) if e == "cancelled" => status.info(format!(
                "Subdivision of '{name}' cancelled: showing its cage (Ctrl+1…Ctrl+5 pick a lower level)"
            )),
            Err(e) => status.error(format!("'{name}': subdivision not shown: {e}")),
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn project_mesh(
    ec: &mut EntityCommands,
    node: &hedra_doc::Node,
    projected: Option<ProjectedMesh>,
    mesh3d: Option<&Mesh3d>,
    meshes: &mut Assets<Mesh>,
    previews: &mut SmoothPreviews,
    status: &mut StatusMessage,
    material: Option<&MeshMaterial>,
) {
    let content = match &node.content {
        NodeContent::Mesh(content) => content,
        NodeContent::Surface(surface) => {
            let wanted = ProjectedMesh {
                source: std::sync::Arc::as_ptr(surface) as *const u8 as usize,
                shading: Shading::Smooth,
                smooth: None,
            };
            if projected != Some(wanted) {
                set_render_mesh(ec, mesh3d, meshes, surface_render_mesh(surface), material);
                ec.insert(wanted);
            }
            return;
        }
        NodeContent::Curve(curve) => {
            // Curves have no surface; the projection only tells the
            // overlays what to draw.
            let wanted = ProjectedMesh {
                source: std::sync::Arc::as_ptr(curve) as *const u8 as usize,
                shading: Shading::Flat,
                smooth: None,
            };
            if projected != Some(wanted) {
                ec.remove::<(Mesh3d, MeshMaterial3d<StandardMaterial>)>();
                ec.insert(wanted);
            }
            return;
        }
        NodeContent::Empty => {
            if projected.is_some() {
                ec.remove::<(Mesh3d, MeshMaterial3d<StandardMaterial>, ProjectedMesh)>();
            }
            return;
        }
    };
    let modifier = active_modifier(content);
    let wanted = ProjectedMesh {
        source: std::sync::Arc::as_ptr(&content.mesh) as usize,
        shading: content.shading,
        smooth: modifier.map(|m| (m, creases_fingerprint(&content.creases))),
    };
    if projected == Some(wanted) {
        return;
    }
    let smooth_source = modifier.map(|m| (m, content.shading));
    let background = smooth_source.is_some_and(|(m, shading)| {
        let src = SmoothSource {
            node: node.id,
            cage: &content.mesh,
            creases: &content.creases,
            modifier: &m,
            shading,
        };
        let big = previews.needs_background(&src);
        if big {
            previews.start_background(&src, &node.name);
        }
        big
    });
    // While a large preview is made in the background, the cage shows.
    let render = if background {
        render_mesh(&content.mesh, content.shading)
    } else {
        content_render_mesh(node.id, content, &content.mesh, &content.creases, previews)
            .unwrap_or_else(|(message, cage)| {
                status.error(format!("'{}': subdivision not shown: {message}", node.name));
                cage
            })
    };
    set_render_mesh(ec, mesh3d, meshes, render, material);
    ec.insert(wanted);
}

/// Puts `render` on the entity's mesh asset (or a new one) with the material.
fn set_render_mesh(
    ec: &mut EntityCommands,
    mesh3d: Option<&Mesh3d>,
    meshes: &mut Assets<Mesh>,
    render: Mesh,
    material: Option<&MeshMaterial>,
) {
    match mesh3d.filter(|m| meshes.contains(&m.0)) {
        Some(m) => {
            if let Some(mut existing) = meshes.get_mut(&m.0) {
                *existing = render;
            }
        }
        None => {
            ec.insert(Mesh3d(meshes.add(render)));
        }
    }
    if let Some(m) = material {
        ec.insert(MeshMaterial3d(m.0.clone()));
    }
}

/// Viewport tessellation of curves and surfaces, as a fraction of their size.
pub const VIEW_TOLERANCE: f64 = 5e-4;

/// The diagonal of the points' bounding box (at least 1e-9).
pub fn extent(points: &[hedra_geom::DVec3]) -> f64 {
    let (lo, hi) = points.iter().fold(
        (hedra_geom::DVec3::INFINITY, hedra_geom::DVec3::NEG_INFINITY),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    (hi - lo).length().max(1e-9)
}

/// A smooth-shaded triangle mesh of a surface node, tessellated to
/// [`VIEW_TOLERANCE`] of its size; both sides face the viewer (a patch is
/// open, its back is seen too).
pub fn surface_render_mesh(surface: &hedra_doc::SurfaceShape) -> Mesh {
    let tol = VIEW_TOLERANCE * extent(surface.control_points());
    let (positions, normals, triangles) = surface.tessellate(tol);
    let f32s = |v: &hedra_geom::DVec3| v.as_vec3().to_array();
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::MAIN_WORLD | RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(
        Mesh::ATTRIBUTE_POSITION,
        positions.iter().map(f32s).collect::<Vec<_>>(),
    )
    .with_inserted_attribute(
        Mesh::ATTRIBUTE_NORMAL,
        normals.iter().map(f32s).collect::<Vec<_>>(),
    )
    .with_inserted_indices(Indices::U32(triangles.into_iter().flatten().collect()))
}

/// The parameters of a NURBS surface's render grid (row-major by u), kept
/// so a drag re-evaluates only the part of the grid its change can reach.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceGrid {
    pub us: Vec<f64>,
    pub vs: Vec<f64>,
}

/// The grid [`surface_render_mesh`] uses for a NURBS surface.
pub fn surface_grid(surface: &hedra_geom::surfaces::NurbsSurface) -> SurfaceGrid {
    use hedra_geom::surfaces::Surface;
    let tol = VIEW_TOLERANCE * extent(surface.points());
    let (cu, cv) = hedra_geom::surfaces::tessellate::cells_for_tolerance(surface, tol);
    let ((u0, u1), (v0, v1)) = surface.domain();
    SurfaceGrid {
        us: (0..=cu)
            .map(|i| u0 + (u1 - u0) * i as f64 / cu as f64)
            .collect(),
        vs: (0..=cv)
            .map(|j| v0 + (v1 - v0) * j as f64 / cv as f64)
            .collect(),
    }
}

/// Rewrites the positions and normals of `render` (built on `grid` from
/// `old`) to show `new`, re-evaluating only the grid points inside the
/// knot spans of the control points that changed: a control point (i, j)
/// moves the surface only on `[U_i, U_{i+p+1}] × [V_j, V_{j+q+1}]`.
/// Returns false, changing nothing, when the two surfaces differ in more
/// than points and weights (rebuild then).
pub fn update_surface_render_mesh(
    render: &mut Mesh,
    grid: &SurfaceGrid,
    old: &hedra_geom::surfaces::NurbsSurface,
    new: &hedra_geom::surfaces::NurbsSurface,
) -> bool {
    use bevy::mesh::VertexAttributeValues;
    if old.size() != new.size() || old.degrees() != new.degrees() || old.knots() != new.knots() {
        return false;
    }
    let (nu, nv) = new.size();
    let changed: Vec<usize> = (0..nu * nv)
        .filter(|&k| old.points()[k] != new.points()[k] || old.weights()[k] != new.weights()[k])
        .collect();
    if changed.is_empty() {
        return true;
    }
    let ((p, q), (ku, kv)) = (new.degrees(), new.knots());
    let (mut u_lo, mut u_hi, mut v_lo, mut v_hi) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for k in changed {
        let (i, j) = (k / nv, k % nv);
        u_lo = u_lo.min(ku[i]);
        u_hi = u_hi.max(ku[i + p + 1]);
        v_lo = v_lo.min(kv[j]);
        v_hi = v_hi.max(kv[j + q + 1]);
    }
    let rows: Vec<usize> = (0..grid.us.len())
        .filter(|&a| (u_lo..=u_hi).contains(&grid.us[a]))
        .collect();
    let cols: Vec<usize> = (0..grid.vs.len())
        .filter(|&b| (v_lo..=v_hi).contains(&grid.vs[b]))
        .collect();
    let count = grid.us.len() * grid.vs.len();
    let (
        Some(VertexAttributeValues::Float32x3(positions)),
        Some(VertexAttributeValues::Float32x3(normals)),
    ) = (
        render.attribute(Mesh::ATTRIBUTE_POSITION).cloned(),
        render.attribute(Mesh::ATTRIBUTE_NORMAL).cloned(),
    )
    else {
        return false;
    };
    if positions.len() != count || normals.len() != count {
        return false;
    }
    let (mut positions, mut normals) = (positions, normals);
    let us: Vec<f64> = rows.iter().map(|&a| grid.us[a]).collect();
    let vs: Vec<f64> = cols.iter().map(|&b| grid.vs[b]).collect();
    let (points, norms) = new.grid(&us, &vs, true);
    for (r, &a) in rows.iter().enumerate() {
        for (c, &b) in cols.iter().enumerate() {
            let k = a * grid.vs.len() + b;
            positions[k] = points[r * vs.len() + c].as_vec3().to_array();
            normals[k] = norms[r * vs.len() + c].as_vec3().to_array();
        }
    }
    render.insert_attribute(Mesh::ATTRIBUTE_POSITION, positions);
    render.insert_attribute(Mesh::ATTRIBUTE_NORMAL, normals);
    true
}

/// The render mesh of a mesh node showing `cage` (the document's mesh or a
/// tool's preview of it) with `creases`: smooth when the node has a
/// subdivision modifier, else the cage itself.
///
/// # Errors
/// The subdivision's message together with the cage's render mesh, to show
/// instead.
pub fn content_render_mesh(
    node: NodeId,
    content: &hedra_doc::MeshContent,
    cage: &std::sync::Arc<HalfEdgeMesh>,
    creases: &hedra_geom::subdivision::Creases,
    previews: &mut SmoothPreviews,
) -> Result<Mesh, (String, Mesh)> {
    let Some(modifier) = active_modifier(content) else {
        return Ok(render_mesh(cage, content.shading));
    };
    previews
        .render_mesh(&SmoothSource {
            node,
            cage,
            creases,
            modifier: &modifier,
            shading: content.shading,
        })
        .map_err(|message| (message, render_mesh(cage, content.shading)))
}

/// A triangle render mesh of a half-edge mesh (the buffers of
/// [`hedra_doc::render::render_buffers`]: flat shading gives each face its
/// own corners, smooth shading shares them).
pub fn render_mesh(mesh: &HalfEdgeMesh, shading: Shading) -> Mesh {
    let b = hedra_doc::render::render_buffers(mesh, shading);
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::MAIN_WORLD | RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, b.positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, b.normals)
    .with_inserted_indices(Indices::U32(b.indices))
}

/// Whether viewport tools may use the pointer and keyboard this frame; the
/// UI clears these while the pointer is over a panel or a text field has focus.
#[derive(Resource, Debug, Clone, Copy)]
pub struct InputGate {
    pub pointer_free: bool,
    pub keyboard_free: bool,
}

impl Default for InputGate {
    fn default() -> Self {
        InputGate {
            pointer_free: true,
            keyboard_free: true,
        }
    }
}

/// Marks the 3D camera the viewport renders and tools cast rays from.
#[derive(Component, Debug, Default)]
pub struct ViewportCamera;

/// Modifier keys, counted as held when pressed or released this frame too
/// (a quick Ctrl+S can press and release Ctrl within one or two frames).
pub mod modifiers {
    use bevy::prelude::*;

    fn held(keys: &ButtonInput<KeyCode>, pair: [KeyCode; 2]) -> bool {
        keys.any_pressed(pair) || keys.any_just_pressed(pair) || keys.any_just_released(pair)
    }
    /// Ctrl (or the Super/Command key).
    pub fn ctrl(keys: &ButtonInput<KeyCode>) -> bool {
        held(keys, [KeyCode::ControlLeft, KeyCode::ControlRight])
            || held(keys, [KeyCode::SuperLeft, KeyCode::SuperRight])
    }
    pub fn shift(keys: &ButtonInput<KeyCode>) -> bool {
        held(keys, [KeyCode::ShiftLeft, KeyCode::ShiftRight])
    }
    pub fn alt(keys: &ButtonInput<KeyCode>) -> bool {
        held(keys, [KeyCode::AltLeft, KeyCode::AltRight])
    }
}

/// Updates a render mesh built by [`render_mesh`] from `old` so that it shows
/// `new` when only vertex positions differ, rewriting only what changed
/// ([`hedra_doc::render::patch_positions`]); the attribute arrays are taken
/// out and put back, not copied. Returns false, changing nothing, when the
/// connectivity differs: rebuild with [`render_mesh`] then.
pub fn update_render_positions(
    render: &mut Mesh,
    old: &HalfEdgeMesh,
    new: &HalfEdgeMesh,
    shading: Shading,
) -> bool {
    use bevy::mesh::VertexAttributeValues::Float32x3;
    let is_f32x3 = |id| matches!(render.attribute(id), Some(Float32x3(_)));
    if !(is_f32x3(Mesh::ATTRIBUTE_POSITION) && is_f32x3(Mesh::ATTRIBUTE_NORMAL)) {
        return false;
    }
    let (Some(Float32x3(mut positions)), Some(Float32x3(mut normals))) = (
        render.remove_attribute(Mesh::ATTRIBUTE_POSITION),
        render.remove_attribute(Mesh::ATTRIBUTE_NORMAL),
    ) else {
        unreachable!("both attributes were just checked");
    };
    let patched =
        hedra_doc::render::patch_positions(&mut positions, &mut normals, old, new, shading);
    render.insert_attribute(Mesh::ATTRIBUTE_POSITION, positions);
    render.insert_attribute(Mesh::ATTRIBUTE_NORMAL, normals);
    patched
}
