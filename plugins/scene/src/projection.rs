//! The document mirrored as entities: one per node, with its transform, hierarchy, visibility and render mesh.

use crate::*;
use by_address::ByAddress;
use std::sync::Arc;

/// The document node an entity mirrors.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct NodeEntity(pub NodeId);

/// Which document content (by identity), shading and subdivision a node
/// shows when no tool previews it; the overlays key on it. Written only by
/// [`sync_entities`].
#[derive(Component, Clone, Debug, PartialEq, Eq)]
pub struct ProjectedMesh {
    /// The content's shared geometry, compared by identity: a changed
    /// mesh, curve or surface is a new `Arc`, so it gives a different value.
    pub source: ContentSource,
    /// The content's shading (curves count as flat, surfaces as smooth).
    pub shading: Shading,
    /// The modifier and a fingerprint of the creases, for smooth previews.
    pub smooth: Option<(hedra_doc::SubdivisionModifier, u64)>,
}

/// The shared geometry of a node's content, held (so its address cannot be
/// reused by another value while this is kept) and compared by address.
#[derive(Clone, PartialEq, Eq)]
pub enum ContentSource {
    /// A mesh's cage.
    Mesh(ByAddress<Arc<HalfEdgeMesh>>),
    /// A curve.
    Curve(ByAddress<Arc<hedra_doc::CurveContent>>),
    /// A surface.
    Surface(ByAddress<Arc<hedra_doc::SurfaceShape>>),
    /// A kept (non-manifold) mesh's faces.
    Kept(ByAddress<Arc<hedra_doc::KeptMesh>>),
}

impl std::fmt::Debug for ContentSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // The address only: the content itself can be a million faces.
        match self {
            ContentSource::Mesh(m) => write!(f, "Mesh({:p})", Arc::as_ptr(m)),
            ContentSource::Curve(c) => write!(f, "Curve({:p})", Arc::as_ptr(c)),
            ContentSource::Surface(s) => write!(f, "Surface({:p})", Arc::as_ptr(s)),
            ContentSource::Kept(k) => write!(f, "Kept({:p})", Arc::as_ptr(k)),
        }
    }
}

/// A fingerprint of crease values, to notice when they change.
pub fn creases_fingerprint(creases: &hedra_geom::subdivision::Creases) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    // Every edge's sharpness, tapered chains included, then corners and holes.
    for (e, s) in creases.edge_sharpness() {
        (e, s.to_bits()).hash(&mut h);
    }
    for (v, s) in &creases.vertices {
        (v, s.to_bits()).hash(&mut h);
    }
    creases.holes.hash(&mut h);
    h.finish()
}

/// The subdivision a mesh's content shows in the viewport, if any.
pub fn active_modifier(content: &hedra_doc::MeshContent) -> Option<hedra_doc::SubdivisionModifier> {
    content.subdivision.filter(|m| m.viewport_level > 0)
}

/// A mesh node's content, mirrored from the document: the half-edge mesh
/// (shared with the document, not copied), shading, creases and the
/// subdivision modifier. Written only by [`sync_entities`], and only when
/// it differs, so `Changed<NodeMesh>` means the document's mesh changed.
#[derive(Component, Clone, Debug)]
pub struct NodeMesh {
    /// The cage, shared with the document (not copied).
    pub mesh: Arc<HalfEdgeMesh>,
    /// Flat or smooth normals for the render mesh.
    pub shading: Shading,
    /// Subdivision creases on the cage's edges and vertices.
    pub creases: hedra_geom::subdivision::Creases,
    /// The subdivision modifier; `None` when the mesh has none.
    pub subdivision: Option<hedra_doc::SubdivisionModifier>,
    /// The Mirror and Array modifiers, in stack order.
    pub modifiers: Vec<hedra_doc::MeshModifier>,
}

impl NodeMesh {
    fn of(c: &hedra_doc::MeshContent) -> NodeMesh {
        NodeMesh {
            mesh: c.mesh.clone(),
            shading: c.shading,
            creases: c.creases.clone(),
            subdivision: c.subdivision,
            modifiers: c.modifiers.clone(),
        }
    }

    fn same(&self, c: &hedra_doc::MeshContent) -> bool {
        Arc::ptr_eq(&self.mesh, &c.mesh)
            && self.shading == c.shading
            && self.subdivision == c.subdivision
            && self.creases == c.creases
            && self.modifiers == c.modifiers
    }

    /// The content with `cage` and `creases` in place of the document's
    /// (a tool's preview), to evaluate the modifier stack on.
    fn content_with(
        &self,
        cage: &Arc<HalfEdgeMesh>,
        creases: &hedra_geom::subdivision::Creases,
    ) -> hedra_doc::MeshContent {
        let mut content = hedra_doc::MeshContent::new(cage.clone());
        content.shading = self.shading;
        content.creases = creases.clone();
        content.subdivision = self.subdivision;
        content.modifiers = self.modifiers.clone();
        content
    }

    /// The subdivision the viewport shows, if any.
    pub fn active_modifier(&self) -> Option<hedra_doc::SubdivisionModifier> {
        self.subdivision.filter(|m| m.viewport_level > 0)
    }
}

/// A curve node's curve, mirrored from the document (shared). Written only
/// by [`sync_entities`], when it differs.
#[derive(Component, Clone, Debug)]
pub struct NodeCurve(pub Arc<hedra_doc::CurveContent>);

/// A surface node's surface, mirrored from the document (shared). Written
/// only by [`sync_entities`], when it differs.
#[derive(Component, Clone, Debug)]
pub struct NodeSurface(pub Arc<hedra_doc::SurfaceShape>);

/// The most faces a kept mesh's subdivision preview is made with in a
/// frame (kept meshes have no background refinement).
pub const KEPT_PREVIEW_FACES: usize = 1_000_000;

/// A kept (non-manifold) mesh node's faces, shading and subdivision,
/// mirrored from the document (the faces shared, not copied). Written
/// only by [`sync_entities`], when it differs.
#[derive(Component, Clone, Debug)]
pub struct NodeKeptMesh(pub hedra_doc::KeptMeshContent);

/// Node id → entity, kept by [`sync_entities`].
#[derive(Resource, Default, Debug)]
pub struct NodeEntities(pub HashMap<NodeId, Entity>);

/// A document transform as a Bevy one (f32).
pub fn bevy_transform(t: &hedra_doc::NodeTransform) -> Transform {
    Transform {
        translation: t.translation.as_vec3(),
        rotation: t.rotation.as_quat(),
        scale: t.scale.as_vec3(),
    }
}

/// Mirrors the document's nodes into entities whenever its revision
/// changes: spawns and despawns them, keeps `Name`, `Visibility`,
/// `ChildOf`, the content components ([`NodeMesh`], [`NodeCurve`],
/// [`NodeSurface`]) and [`ProjectedMesh`], each written only when it
/// differs. A new entity starts at its document transform;
/// [`project_transforms`] writes it after that.
#[allow(clippy::type_complexity)]
pub fn sync_entities(
    mut commands: Commands,
    state: Res<DocState>,
    mut seen_revision: Local<Option<u64>>,
    mut map: ResMut<NodeEntities>,
    mut existing: Query<(
        &mut Name,
        &mut Visibility,
        Option<&ChildOf>,
        Option<&mut NodeMesh>,
        Option<&mut NodeCurve>,
        Option<&mut NodeSurface>,
        Option<&mut NodeKeptMesh>,
        Option<&mut ProjectedMesh>,
    )>,
) {
    if *seen_revision == Some(state.revision) {
        return;
    }
    *seen_revision = Some(state.revision);
    let doc = &state.session.doc;
    // A CSG node's operands are drawn through its solid, not by themselves
    // (found for every node in one walk down the tree).
    let tree = doc.hierarchy();
    let visibility = |node: &hedra_doc::Node| {
        if node.visible && !tree.inside_csg(node.id) {
            Visibility::Inherited
        } else {
            Visibility::Hidden
        }
    };

    // Spawn missing entities first so parents exist for ChildOf.
    let mut spawned = Vec::new();
    for node in doc.nodes() {
        if !map.0.get(&node.id).is_some_and(|e| existing.contains(*e)) {
            let e = commands
                .spawn((
                    NodeEntity(node.id),
                    Name::new(node.name.clone()),
                    bevy_transform(&node.transform),
                    visibility(node),
                ))
                .id();
            map.0.insert(node.id, e);
            spawned.push(e);
        }
    }
    for node in doc.nodes() {
        let e = map.0[&node.id];
        let parent = node.parent.and_then(|p| map.0.get(&p).copied());
        let content = drawn_content(doc, node);
        let node_content = &*content;
        let old_parent = match existing.get_mut(e) {
            Ok((mut name, mut v, child_of, mesh, curve, surface, kept, projected)) => {
                if name.as_str() != node.name {
                    name.set(node.name.clone());
                }
                let wanted = visibility(node);
                if *v != wanted {
                    *v = wanted;
                }
                let content_components = (mesh, curve, surface, kept);
                mirror_content(&mut commands.entity(e), node_content, content_components);
                let wanted = ProjectedMesh::of(node_content);
                match (projected, wanted) {
                    (Some(mut p), Some(w)) => {
                        p.set_if_neq(w);
                    }
                    (None, Some(w)) => {
                        commands.entity(e).insert(w);
                    }
                    (Some(_), None) => {
                        commands.entity(e).remove::<ProjectedMesh>();
                    }
                    (None, None) => {}
                }
                child_of.map(|c| c.parent())
            }
            Err(_) => {
                // Spawned above: its components go in with the spawn.
                mirror_content(
                    &mut commands.entity(e),
                    node_content,
                    (None, None, None, None),
                );
                if let Some(w) = ProjectedMesh::of(node_content) {
                    commands.entity(e).insert(w);
                }
                None
            }
        };
        match (parent, old_parent) {
            (Some(p), Some(old)) if p == old => {}
            (Some(p), _) => {
                commands.entity(e).insert(ChildOf(p));
            }
            (None, Some(_)) => {
                commands.entity(e).remove::<ChildOf>();
            }
            (None, None) => {}
        }
    }
    // Despawn entities of deleted nodes (after reparenting, so survivors are detached first).
    let gone: Vec<NodeId> = map
        .0
        .keys()
        .filter(|id| doc.node(**id).is_none())
        .copied()
        .collect();
    for id in gone {
        if let Some(e) = map.0.remove(&id) {
            commands.entity(e).remove::<ChildOf>();
            commands.entity(e).try_despawn();
        }
    }
}

/// What a node draws: its content, or for a CSG node its evaluated solid as
/// a mesh (nothing while it cannot be evaluated; `hedra info` and the
/// panel say why).
fn drawn_content<'a>(
    doc: &hedra_doc::Document,
    node: &'a hedra_doc::Node,
) -> std::borrow::Cow<'a, NodeContent> {
    match &node.content {
        NodeContent::Csg(_) => {
            std::borrow::Cow::Owned(match hedra_doc::csg::evaluate(doc, node.id) {
                Ok(solid) => NodeContent::Mesh(hedra_doc::MeshContent::new(solid)),
                Err(_) => NodeContent::Empty,
            })
        }
        other => std::borrow::Cow::Borrowed(other),
    }
}

/// Puts a node's content on its entity: updates the component of its kind
/// when it differs, removes the others.
#[allow(clippy::type_complexity)]
fn mirror_content(
    ec: &mut EntityCommands,
    content: &NodeContent,
    (mesh, curve, surface, kept): (
        Option<Mut<NodeMesh>>,
        Option<Mut<NodeCurve>>,
        Option<Mut<NodeSurface>>,
        Option<Mut<NodeKeptMesh>>,
    ),
) {
    let (had_mesh, had_curve, had_surface) = (mesh.is_some(), curve.is_some(), surface.is_some());
    let had_kept = kept.is_some();
    match content {
        NodeContent::Kept(k) => match kept {
            Some(mut old) => {
                let same = Arc::ptr_eq(&old.0.mesh, &k.mesh)
                    && old.0.shading == k.shading
                    && old.0.subdivision == k.subdivision;
                if !same {
                    old.0 = k.clone();
                }
            }
            None => {
                ec.insert(NodeKeptMesh(k.clone()));
            }
        },
        NodeContent::Mesh(c) => match mesh {
            Some(mut m) => {
                if !m.same(c) {
                    *m = NodeMesh::of(c);
                }
            }
            None => {
                ec.insert(NodeMesh::of(c));
            }
        },
        NodeContent::Curve(c) => match curve {
            Some(mut old) => {
                if !Arc::ptr_eq(&old.0, c) {
                    old.0 = c.clone();
                }
            }
            None => {
                ec.insert(NodeCurve(c.clone()));
            }
        },
        NodeContent::Surface(s) => match surface {
            Some(mut old) => {
                if !Arc::ptr_eq(&old.0, s) {
                    old.0 = s.clone();
                }
            }
            None => {
                ec.insert(NodeSurface(s.clone()));
            }
        },
        NodeContent::Empty | NodeContent::Csg(_) => {}
    }
    if had_mesh && !matches!(content, NodeContent::Mesh(_)) {
        ec.remove::<NodeMesh>();
    }
    if had_curve && !matches!(content, NodeContent::Curve(_)) {
        ec.remove::<NodeCurve>();
    }
    if had_surface && !matches!(content, NodeContent::Surface(_)) {
        ec.remove::<NodeSurface>();
    }
    if had_kept && !matches!(content, NodeContent::Kept(_)) {
        ec.remove::<NodeKeptMesh>();
    }
}

/// The one writer of node `Transform`s: the document's transform, or the
/// one a running tool previews ([`Previews::transform`]). Runs when the
/// document, the previews or the set of node entities changed.
pub fn project_transforms(
    state: Res<DocState>,
    previews: Res<Previews>,
    mut seen_revision: Local<Option<u64>>,
    added: Query<(), Added<NodeEntity>>,
    mut nodes: Query<(&NodeEntity, &mut Transform)>,
) {
    if *seen_revision == Some(state.revision) && !previews.is_changed() && added.is_empty() {
        return;
    }
    *seen_revision = Some(state.revision);
    for (node, mut transform) in &mut nodes {
        let Some(doc_node) = state.session.doc.node(node.0) else {
            continue;
        };
        let wanted = bevy_transform(previews.transform(node.0).unwrap_or(&doc_node.transform));
        if *transform != wanted {
            *transform = wanted;
        }
    }
}

/// What a mesh node's render mesh shows now: the cage (by identity, kept
/// alive here so its address cannot be reused), how it is shaded and
/// smoothed.
/// Written only by [`project_render_meshes`].
#[derive(Component, Clone, Debug)]
pub struct OnScreen {
    mesh: Arc<HalfEdgeMesh>,
    shading: Shading,
    smooth: Option<(hedra_doc::SubdivisionModifier, u64)>,
    modifiers: Vec<hedra_doc::MeshModifier>,
    /// The creases drawn with (infinitely sharp ones split the normals of
    /// the cage too).
    creases: u64,
}

impl OnScreen {
    fn shows_mesh(&self, mesh: &Arc<HalfEdgeMesh>) -> bool {
        Arc::ptr_eq(&self.mesh, mesh)
    }
}

/// The one writer of mesh nodes' render meshes (the `Assets<Mesh>` entries
/// behind their `Mesh3d`) and of [`SmoothPreviews`]. Draws each node's
/// document mesh or the one a running tool previews ([`Previews::content`]):
/// patches positions in place when only positions changed (cage or smooth
/// stencils), rebuilds otherwise; starts large smooth
/// previews in the background and puts them on screen when they finish
/// (Esc cancels them).
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn project_render_meshes(
    mut commands: Commands,
    previews: Res<Previews>,
    mut smooth: ResMut<SmoothPreviews>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut status: ResMut<StatusMessage>,
    material: Option<Res<MeshMaterial>>,
    shading: Res<crate::ViewportShading>,
    orientation: Option<Res<crate::FaceOrientationMaterials>>,
    map: Res<NodeEntities>,
    nodes: Query<(
        Entity,
        &NodeEntity,
        &Name,
        Option<Ref<NodeMesh>>,
        Option<&Mesh3d>,
        Option<&OnScreen>,
    )>,
    kept: Query<Ref<NodeKeptMesh>>,
    node_materials: Query<(Entity, &MeshMaterial3d<StandardMaterial>), With<NodeEntity>>,
) {
    let chosen = material
        .as_deref()
        .map(|m| crate::model_material(m, orientation.as_deref(), &shading));
    crate::refresh_materials(&mut commands, &shading, chosen.as_ref(), &node_materials);
    for job in smooth.finished() {
        let node = map.0.get(&job.node).and_then(|e| nodes.get(*e).ok());
        let name = node.map_or_else(|| job.node.to_string(), |(_, _, n, ..)| n.to_string());
        match job.result {
            Ok(mesh) => {
                if let Some(mut m) = node
                    .and_then(|(_, _, _, _, m, _)| m)
                    .and_then(|h| meshes.get_mut(&h.0))
                {
                    *m = mesh;
                }
            }
            Err(e) if e == "cancelled" => status.info(format!(
                "Subdivision of '{name}' cancelled: showing its cage (Ctrl+1…Ctrl+5 pick a lower level)"
            )),
            Err(e) => status.error(format!("'{name}': subdivision not shown: {e}")),
        }
    }
    // The store is borrowed mutably only when something is drawn, so its
    // change ticks tell when render meshes were written.
    let mut projector = Projector {
        meshes: &mut meshes,
        smooth: &mut smooth,
        status: &mut status,
        material: chosen.as_ref(),
    };
    let mut any_changed = false;
    for (entity, node, name, content, mesh3d, on_screen) in &nodes {
        let Some(content) = content else {
            // A kept (non-manifold) mesh: its faces, rebuilt when they change.
            if let Ok(k) = kept.get(entity) {
                if k.is_changed() || mesh3d.is_none() || on_screen.is_some() {
                    let built = projector.kept(name, &k.0);
                    let mut ec = commands.entity(entity);
                    set_render_mesh(&mut ec, mesh3d, projector.meshes, built, projector.material);
                    ec.remove::<OnScreen>();
                    any_changed = true;
                }
                continue;
            }
            // No longer a mesh: surfaces are drawn by their patch entities,
            // curves and empties by the overlays.
            if mesh3d.is_some() || on_screen.is_some() {
                commands
                    .entity(entity)
                    .remove::<(Mesh3d, MeshMaterial3d<StandardMaterial>, OnScreen)>();
                any_changed = true;
            }
            continue;
        };
        any_changed |= content.is_changed();
        if content.is_changed() || previews.is_changed() {
            let preview = previews.content(node.0);
            let mut ec = commands.entity(entity);
            projector.mesh(&mut ec, node.0, name, &content, preview, mesh3d, on_screen);
        }
    }
    // Refinements of nodes that no longer smooth go (looked up only when
    // a mesh changed).
    if any_changed {
        smooth.retain(|id| {
            map.0
                .get(&id)
                .and_then(|e| nodes.get(*e).ok())
                .and_then(|(_, _, _, content, _, _)| content)
                .is_some_and(|c| c.active_modifier().is_some())
        });
    }
}

/// What [`project_render_meshes`] writes with (dereferenced mutably only
/// when used, so unchanged frames leave the change ticks alone).
struct Projector<'a, 'm, 's, 't> {
    meshes: &'a mut ResMut<'m, Assets<Mesh>>,
    smooth: &'a mut ResMut<'s, SmoothPreviews>,
    status: &'a mut ResMut<'t, StatusMessage>,
    material: Option<&'a MeshMaterial>,
}

impl Projector<'_, '_, '_, '_> {
    /// A mesh node: its cage, or its smooth preview when it has a
    /// subdivision modifier, of the document's mesh or a tool's preview.
    #[allow(clippy::too_many_arguments)]
    fn mesh(
        &mut self,
        ec: &mut EntityCommands,
        node: NodeId,
        name: &str,
        content: &NodeMesh,
        preview: Option<&PreviewContent>,
        mesh3d: Option<&Mesh3d>,
        on_screen: Option<&OnScreen>,
    ) {
        let (cage, creases, is_preview) = match preview {
            Some(PreviewContent::Mesh { mesh, creases }) => {
                (mesh, creases.as_ref().unwrap_or(&content.creases), true)
            }
            _ => (&content.mesh, &content.creases, false),
        };
        let modifier = content.active_modifier();
        let fingerprint = creases_fingerprint(creases);
        let wanted = OnScreen {
            mesh: cage.clone(),
            shading: content.shading,
            smooth: modifier.map(|m| (m, fingerprint)),
            modifiers: content.modifiers.clone(),
            creases: fingerprint,
        };
        let same_look = on_screen.is_some_and(|o| {
            o.shading == wanted.shading
                && o.smooth.map(|s| s.0) == modifier
                && o.modifiers == wanted.modifiers
                && o.creases == wanted.creases
        });
        if same_look && on_screen.is_some_and(|o| o.shows_mesh(cage) && o.smooth == wanted.smooth) {
            return;
        }
        if !content.modifiers.is_empty() {
            let built = self.with_stack(node, name, content, cage, creases, modifier.as_ref());
            set_render_mesh(ec, mesh3d, self.meshes, built, self.material);
            ec.insert(wanted);
            return;
        }
        let mut render = mesh3d.and_then(|h| self.meshes.get_mut(&h.0));
        let patched = match (&modifier, render.as_deref_mut()) {
            (Some(m), Some(r)) if same_look => self.smooth.update_positions(
                r,
                &SmoothSource {
                    node,
                    cage,
                    creases,
                    modifier: m,
                    shading: content.shading,
                },
            ),
            (None, Some(r)) if same_look => on_screen
                .is_some_and(|o| update_render_positions(r, &o.mesh, cage, content.shading)),
            _ => false,
        };
        drop(render);
        if !patched {
            let built = match &modifier {
                None => render_mesh(cage, content.shading, creases),
                Some(m) => {
                    let src = SmoothSource {
                        node,
                        cage,
                        creases,
                        modifier: m,
                        shading: content.shading,
                    };
                    if self.smooth.needs_background(&src) {
                        // While a large preview is made in the background
                        // the cage shows; a tool's preview is not refined
                        // every frame (the result is, once committed).
                        if !is_preview {
                            self.smooth.start_background(&src, name);
                        }
                        render_mesh(cage, content.shading, creases)
                    } else {
                        self.smooth.render_mesh(&src).unwrap_or_else(|message| {
                            self.status
                                .error(format!("'{name}': subdivision not shown: {message}"));
                            render_mesh(cage, content.shading, creases)
                        })
                    }
                }
            };
            set_render_mesh(ec, mesh3d, self.meshes, built, self.material);
        }
        ec.insert(wanted);
    }
}

impl Projector<'_, '_, '_, '_> {
    /// A kept mesh's render mesh: its faces, or their subdivision at the
    /// modifier's viewport level (by OpenSubdiv's rules at the non-manifold
    /// places); the faces with a message when the subdivision would be too
    /// large to make in a frame or is refused.
    fn kept(&mut self, name: &str, content: &hedra_doc::KeptMeshContent) -> Mesh {
        let level = content.subdivision.map_or(0, |m| m.viewport_level);
        let faces = content
            .mesh
            .faces
            .len()
            .saturating_mul(4usize.saturating_pow(level));
        let shape = if faces > KEPT_PREVIEW_FACES {
            self.status.error(format!(
                "'{name}': subdivision level {level} not shown: {faces} faces, more than {KEPT_PREVIEW_FACES} (Ctrl+1…Ctrl+5 pick a lower level)"
            ));
            Ok(std::borrow::Cow::Borrowed(&*content.mesh))
        } else {
            content.at_level(level)
        };
        match shape {
            Ok(shape) => buffers_mesh(hedra_doc::render::kept_render_buffers(
                &shape,
                content.shading,
            )),
            Err(e) => {
                self.status
                    .error(format!("'{name}': subdivision not shown: {e}"));
                buffers_mesh(hedra_doc::render::kept_render_buffers(
                    &content.mesh,
                    content.shading,
                ))
            }
        }
    }

    /// The render mesh of a node with Mirror or Array modifiers: the stack
    /// evaluated on the cage (or a tool's preview of it) every time, then
    /// the smooth preview of that result when subdivision comes last, or
    /// the whole evaluation when subdivision comes earlier. Shows the cage
    /// with a message when the stack cannot be evaluated.
    fn with_stack(
        &mut self,
        node: NodeId,
        name: &str,
        content: &NodeMesh,
        cage: &Arc<HalfEdgeMesh>,
        creases: &hedra_geom::subdivision::Creases,
        modifier: Option<&hedra_doc::SubdivisionModifier>,
    ) -> Mesh {
        let full = content.content_with(cage, creases);
        let shading = content.shading;
        let stacked = match full.smooth_cage() {
            Ok(Some(stacked)) => stacked,
            // Subdivision runs before a stack modifier: evaluate it all.
            Ok(None) => match full.evaluate(modifier.map_or(0, |m| m.viewport_level)) {
                Ok(e) => return render_mesh(&e.mesh, shading, &e.creases),
                Err(e) => return self.cage_instead(name, &e, cage, creases, shading),
            },
            Err(e) => return self.cage_instead(name, &e, cage, creases, shading),
        };
        let stacked_creases = stacked.creases.into_owned();
        let stacked = Arc::new(stacked.mesh.into_owned());
        let Some(m) = modifier else {
            return render_mesh(&stacked, shading, &stacked_creases);
        };
        self.smooth
            .render_mesh(&SmoothSource {
                node,
                cage: &stacked,
                creases: &stacked_creases,
                modifier: m,
                shading,
            })
            .unwrap_or_else(|message| {
                self.status
                    .error(format!("'{name}': subdivision not shown: {message}"));
                render_mesh(&stacked, shading, &stacked_creases)
            })
    }

    /// The cage's render mesh, with a message saying why the modifiers
    /// are not shown.
    fn cage_instead(
        &mut self,
        name: &str,
        error: &hedra_doc::EvaluationError,
        cage: &HalfEdgeMesh,
        creases: &hedra_geom::subdivision::Creases,
        shading: Shading,
    ) -> Mesh {
        self.status
            .error(format!("'{name}': modifiers not shown: {error}"));
        render_mesh(cage, shading, creases)
    }
}

impl ProjectedMesh {
    /// What the document content's render mesh and overlays are built
    /// from; `None` for empties.
    pub fn of(content: &NodeContent) -> Option<ProjectedMesh> {
        match content {
            NodeContent::Mesh(c) => {
                let modifier = active_modifier(c);
                Some(ProjectedMesh {
                    source: ContentSource::Mesh(ByAddress(c.mesh.clone())),
                    shading: c.shading,
                    smooth: modifier.map(|m| (m, creases_fingerprint(&c.creases))),
                })
            }
            NodeContent::Surface(s) => Some(ProjectedMesh {
                source: ContentSource::Surface(ByAddress(s.clone())),
                shading: Shading::Smooth,
                smooth: None,
            }),
            NodeContent::Curve(c) => Some(ProjectedMesh {
                source: ContentSource::Curve(ByAddress(c.clone())),
                shading: Shading::Flat,
                smooth: None,
            }),
            NodeContent::Kept(k) => Some(ProjectedMesh {
                source: ContentSource::Kept(ByAddress(k.mesh.clone())),
                shading: k.shading,
                smooth: None,
            }),
            NodeContent::Empty | NodeContent::Csg(_) => None,
        }
    }
}

/// Puts `render` on the entity's mesh asset (or a new one) with the material.
pub(crate) fn set_render_mesh(
    ec: &mut EntityCommands,
    mesh3d: Option<&Mesh3d>,
    meshes: &mut Assets<Mesh>,
    render: Mesh,
    material: Option<&MeshMaterial>,
) {
    if render.count_vertices() == 0 {
        // Nothing to draw (an empty CSG solid, a mesh whose faces were all
        // deleted): Bevy's mesh allocator keeps no slab for an empty mesh
        // and reports a use-after-free when one is drawn.
        ec.remove::<Mesh3d>();
        return;
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use hedra_doc::MeshContent;
    use hedra_geom::Primitive;

    /// A mesh replaced by another of the same size often gets the freed
    /// mesh's address; the projection must still see a change (it held
    /// the address alone before, and could miss it).
    #[test]
    fn a_replaced_mesh_is_a_new_source_even_at_the_same_address() {
        let cube = || Arc::new(Primitive::Cube { size: 1.0 }.build().unwrap());
        let first = NodeContent::Mesh(MeshContent::new(cube()));
        let before = ProjectedMesh::of(&first).unwrap();
        drop(first);
        let second = NodeContent::Mesh(MeshContent::new(cube()));
        let after = ProjectedMesh::of(&second).unwrap();
        assert_ne!(before, after);
        // The same content projects equal, so nothing is rebuilt for it.
        assert_eq!(after, ProjectedMesh::of(&second).unwrap());
    }
}
