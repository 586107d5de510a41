//! The render mesh of the edited node while a tool previews its result.

use super::*;

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
