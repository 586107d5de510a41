//! Render meshes of mesh and kept-mesh nodes: the one writer of their
//! `Mesh3d` assets and materials ([`project_render_meshes`]), patching
//! positions in place while a tool only moves vertices and starting large
//! smooth previews in the background.

use crate::*;
use bevy::camera::primitives::{Aabb, MeshAabb};
use bevy::camera::visibility::NoAutoAabb;
use hedra_doc::render::Rewritten;
use std::sync::Arc;

/// The most faces a kept mesh's subdivision preview is made with in a
/// frame (kept meshes have no background refinement).
pub const KEPT_PREVIEW_FACES: usize = 1_000_000;

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
    /// The bounds set on the entity (its `Aabb`, which this module keeps:
    /// see [`set_bounds`]).
    bounds: Option<Aabb>,
}

impl OnScreen {
    fn shows_mesh(&self, mesh: &Arc<HalfEdgeMesh>) -> bool {
        Arc::ptr_eq(&self.mesh, mesh)
    }
}

/// The one writer of mesh nodes' render meshes (the `Assets<Mesh>` entries
/// behind their `Mesh3d`) and of [`SmoothPreviews`]. Draws what each node
/// shows ([`ShownMesh`]: the document's mesh or a running tool's preview):
/// patches positions in place when only positions changed (cage or smooth
/// stencils), rebuilds otherwise; starts large smooth
/// previews in the background and puts them on screen when they finish
/// (Esc cancels them).
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn project_render_meshes(
    mut commands: Commands,
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
    shown: Query<Ref<ShownMesh>>,
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
                if let Some((entity, on_screen, mut m)) = node.and_then(|(e, _, _, _, m, o)| {
                    m.and_then(|h| meshes.get_mut(&h.0)).map(|m| (e, o, m))
                }) {
                    let bounds = mesh.compute_aabb();
                    *m = mesh;
                    let mut ec = commands.entity(entity);
                    set_bounds(&mut ec, bounds);
                    // What is on screen is the same; its bounds are new.
                    if let Some(o) = on_screen {
                        ec.insert(OnScreen { bounds, ..o.clone() });
                    }
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
        // Written in the same stage, just before: always there for a mesh.
        let Ok(shown) = shown.get(entity) else {
            continue;
        };
        if content.is_changed() || shown.is_changed() {
            let mut ec = commands.entity(entity);
            projector.mesh(&mut ec, node.0, name, &content, &shown, mesh3d, on_screen);
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
    /// subdivision modifier, of what it shows (the document's mesh or a
    /// tool's preview).
    #[allow(clippy::too_many_arguments)]
    fn mesh(
        &mut self,
        ec: &mut EntityCommands,
        node: NodeId,
        name: &str,
        content: &NodeMesh,
        shown: &ShownMesh,
        mesh3d: Option<&Mesh3d>,
        on_screen: Option<&OnScreen>,
    ) {
        let (cage, creases, is_preview) = (&shown.cage, shown.creases(content), shown.previewed);
        let modifier = content.active_modifier();
        let fingerprint = creases_fingerprint(creases);
        let mut wanted = OnScreen {
            mesh: cage.clone(),
            shading: content.shading,
            smooth: modifier.map(|m| (m, fingerprint)),
            modifiers: content.modifiers.clone(),
            creases: fingerprint,
            bounds: None,
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
            wanted.bounds = set_render_mesh(ec, mesh3d, self.meshes, built, self.material);
            ec.insert(wanted);
            return;
        }
        let mut render = mesh3d.and_then(|h| self.meshes.get_mut(&h.0));
        let patched = match (&modifier, render.as_deref_mut()) {
            (Some(m), Some(r)) if same_look => self
                .smooth
                .update_positions(
                    r,
                    &SmoothSource {
                        node,
                        cage,
                        creases,
                        modifier: m,
                        shading: content.shading,
                    },
                )
                .map(|written| grown_bounds(written, on_screen.and_then(|o| o.bounds), r)),
            (None, Some(r)) if same_look => on_screen.and_then(|o| {
                update_render_positions(r, &o.mesh, cage, content.shading)
                    .map(|written| grown_bounds(written, o.bounds, r))
            }),
            _ => None,
        };
        drop(render);
        if let Some(bounds) = patched {
            set_bounds(ec, bounds);
            wanted.bounds = bounds;
        } else {
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
            wanted.bounds = set_render_mesh(ec, mesh3d, self.meshes, built, self.material);
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

/// Puts `render` on the entity's mesh asset (or a new one) with the material.
/// Returns the bounds it set on the entity ([`set_bounds`]).
pub(crate) fn set_render_mesh(
    ec: &mut EntityCommands,
    mesh3d: Option<&Mesh3d>,
    meshes: &mut Assets<Mesh>,
    render: Mesh,
    material: Option<&MeshMaterial>,
) -> Option<Aabb> {
    if render.count_vertices() == 0 {
        // Nothing to draw (an empty CSG solid, a mesh whose faces were all
        // deleted): Bevy's mesh allocator keeps no slab for an empty mesh
        // and reports a use-after-free when one is drawn.
        ec.remove::<Mesh3d>();
        return None;
    }
    let bounds = render.compute_aabb();
    set_bounds(ec, bounds);
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
    bounds
}

/// Sets the bounds a node's render mesh is culled by. This module keeps
/// them (`NoAutoAabb`) instead of Bevy's `calculate_bounds`, which goes
/// over every position of a mesh whose asset changed, in every frame of a
/// drag: for a subdivision preview of 6.4M corners that was most of the
/// frame, while the drag had moved a few hundred (issue 36, item 1).
fn set_bounds(ec: &mut EntityCommands, bounds: Option<Aabb>) {
    match bounds {
        Some(aabb) => ec.insert((aabb, NoAutoAabb)),
        None => ec.remove::<Aabb>().insert(NoAutoAabb),
    };
}

/// Updates a render mesh built by [`render_mesh`] from `old` so that it shows
/// `new` when only vertex positions differ, rewriting only what changed
/// ([`hedra_doc::render::patch_positions`]); the attribute arrays are taken
/// out and put back, not copied. Returns which positions it rewrote, or
/// `None`, changing nothing, when the connectivity differs: rebuild with
/// [`render_mesh`] then.
pub fn update_render_positions(
    render: &mut Mesh,
    old: &HalfEdgeMesh,
    new: &HalfEdgeMesh,
    shading: Shading,
) -> Option<Rewritten> {
    use bevy::mesh::VertexAttributeValues::Float32x3;
    let is_f32x3 = |id| matches!(render.attribute(id), Some(Float32x3(_)));
    if !(is_f32x3(Mesh::ATTRIBUTE_POSITION) && is_f32x3(Mesh::ATTRIBUTE_NORMAL)) {
        return None;
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

/// The bounds of a patched render mesh: the old ones grown to hold the
/// rewritten positions (never too small; a drag's box only grows), or
/// computed afresh when all were rewritten or none were known.
fn grown_bounds(written: Rewritten, old: Option<Aabb>, render: &Mesh) -> Option<Aabb> {
    match (written, old) {
        (Rewritten::Some { min, max }, Some(old)) if min[0] <= max[0] => Some(Aabb::from_min_max(
            Vec3::from(old.min()).min(Vec3::from(min)),
            Vec3::from(old.max()).max(Vec3::from(max)),
        )),
        // None moved.
        (Rewritten::Some { .. }, Some(old)) => Some(old),
        _ => render.compute_aabb(),
    }
}
