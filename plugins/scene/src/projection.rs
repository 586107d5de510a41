//! The document mirrored as entities: one per node, with its transform, hierarchy, visibility and content components (render meshes: `render_projection.rs`).

use crate::*;
use by_address::ByAddress;
use std::sync::Arc;

/// The document node an entity mirrors.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct NodeEntity(pub NodeId);

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
    pub(crate) fn content_with(
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
/// `ChildOf` and the content components ([`NodeMesh`], [`NodeCurve`],
/// [`NodeSurface`], [`NodeKeptMesh`]), each written only when it
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
            Ok((mut name, mut v, child_of, mesh, curve, surface, kept)) => {
                if name.as_str() != node.name {
                    name.set(node.name.clone());
                }
                let wanted = visibility(node);
                if *v != wanted {
                    *v = wanted;
                }
                let content_components = (mesh, curve, surface, kept);
                mirror_content(&mut commands.entity(e), node_content, content_components);
                child_of.map(|c| c.parent())
            }
            Err(_) => {
                // Spawned above: its components go in with the spawn.
                mirror_content(
                    &mut commands.entity(e),
                    node_content,
                    (None, None, None, None),
                );
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

#[cfg(test)]
mod tests {
    use super::*;
    use hedra_doc::MeshContent;
    use hedra_geom::Primitive;

    /// The overlays' key for a mesh's content.
    fn source(content: &NodeContent) -> ContentSource {
        match content {
            NodeContent::Mesh(c) => ContentSource::Mesh(ByAddress(c.mesh.clone())),
            _ => unreachable!("a mesh"),
        }
    }

    /// A mesh replaced by another of the same size often gets the freed
    /// mesh's address; the overlays must still see a change (they held
    /// the address alone once, and could miss it).
    #[test]
    fn a_replaced_mesh_is_a_new_source_even_at_the_same_address() {
        let cube = || Arc::new(Primitive::Cube { size: 1.0 }.build().unwrap());
        let first = NodeContent::Mesh(MeshContent::new(cube()));
        let before = source(&first);
        drop(first);
        let second = NodeContent::Mesh(MeshContent::new(cube()));
        let after = source(&second);
        assert_ne!(before, after);
        // The same content gives an equal key, so nothing is rebuilt for it.
        assert_eq!(after, source(&second));
    }
}
