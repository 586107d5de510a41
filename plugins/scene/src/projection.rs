//! The document mirrored as entities: one per node, with its transform, hierarchy, visibility and render mesh.

use crate::*;

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
pub(crate) fn project_mesh(
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
pub(crate) fn set_render_mesh(
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
