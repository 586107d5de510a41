//! What each node shows: its document content with a running tool's
//! preview over it, worked out once per frame on the node entity.
//!
//! [`project_shown_meshes`] writes [`ShownMesh`] on mesh nodes and
//! [`project_shown_shapes`] writes [`ShownShape`] on curve and surface
//! nodes, each only when it differs, so `Changed<ShownMesh>` means that what
//! the screen shows of the node changed. The render meshes, the control
//! points, the surface patches, the edge overlays, the edit-mode overlay
//! and the curve analysis read these components ([`Shown`] looks them up
//! by node); nothing else works out "document or preview".

use crate::*;
use hedra_doc::{CurveContent, SurfaceShape};
use hedra_geom::subdivision::Creases;
use std::sync::Arc;

/// What a mesh node shows: its cage as a running tool (or a dragged CSG
/// operand's re-evaluation) would leave it, else the document's.
#[derive(Component, Clone, Debug)]
pub struct ShownMesh {
    /// The cage shown, shared with the document or the tool.
    pub cage: Arc<HalfEdgeMesh>,
    /// Creases that replace the document's ([`NodeMesh::creases`]) while a
    /// tool previews them; `None` keeps the document's.
    pub creases: Option<Creases>,
    /// A tool's preview is shown, not the document's content.
    pub previewed: bool,
}

impl PartialEq for ShownMesh {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.cage, &other.cage)
            && self.previewed == other.previewed
            && self.creases == other.creases
    }
}

impl ShownMesh {
    /// The creases shown: the tool's, else the document's.
    pub fn creases<'a>(&'a self, node: &'a NodeMesh) -> &'a Creases {
        self.creases.as_ref().unwrap_or(&node.creases)
    }
}

/// What a curve or surface node shows: a control-point tool's preview, else
/// the document's shape.
#[derive(Component, Clone, Debug)]
pub struct ShownShape {
    /// The curve or surface shown, shared with the document or the tool.
    pub shape: Shape,
    /// A tool's preview is shown, not the document's content.
    pub previewed: bool,
}

/// A curve or a surface, shared (compared by identity).
#[derive(Clone, Debug)]
pub enum Shape {
    /// A curve.
    Curve(Arc<CurveContent>),
    /// A surface.
    Surface(Arc<SurfaceShape>),
}

impl PartialEq for ShownShape {
    fn eq(&self, other: &Self) -> bool {
        self.previewed == other.previewed
            && match (&self.shape, &other.shape) {
                (Shape::Curve(a), Shape::Curve(b)) => Arc::ptr_eq(a, b),
                (Shape::Surface(a), Shape::Surface(b)) => Arc::ptr_eq(a, b),
                _ => false,
            }
    }
}

impl ShownShape {
    /// The shape as node content (the `Arc` cloned, not the shape).
    pub fn content(&self) -> NodeContent {
        match &self.shape {
            Shape::Curve(c) => NodeContent::Curve(c.clone()),
            Shape::Surface(s) => NodeContent::Surface(s.clone()),
        }
    }
}

/// The one writer of [`ShownMesh`]: a mesh node's cage and creases from the
/// previews, else from its [`NodeMesh`]. Looks at a node only when the
/// previews or its mesh changed.
pub fn project_shown_meshes(
    mut commands: Commands,
    previews: Res<Previews>,
    mut nodes: Query<(
        Entity,
        &NodeEntity,
        Option<Ref<NodeMesh>>,
        Option<&mut ShownMesh>,
    )>,
) {
    for (entity, node, mesh, shown) in &mut nodes {
        let Some(mesh) = mesh else {
            if shown.is_some() {
                commands.entity(entity).remove::<ShownMesh>();
            }
            continue;
        };
        if shown.is_some() && !previews.is_changed() && !mesh.is_changed() {
            continue;
        }
        let wanted = match previews.content(node.0) {
            Some(PreviewContent::Mesh { mesh, creases }) => ShownMesh {
                cage: mesh.clone(),
                creases: creases.clone(),
                previewed: true,
            },
            _ => ShownMesh {
                cage: mesh.mesh.clone(),
                creases: None,
                previewed: false,
            },
        };
        match shown {
            Some(mut shown) => {
                shown.set_if_neq(wanted);
            }
            None => {
                commands.entity(entity).insert(wanted);
            }
        }
    }
}

/// The one writer of [`ShownShape`]: a curve or surface node's shape from
/// the previews, else from its [`NodeCurve`] or [`NodeSurface`].
pub fn project_shown_shapes(
    mut commands: Commands,
    previews: Res<Previews>,
    mut nodes: Query<(
        Entity,
        &NodeEntity,
        Option<Ref<NodeCurve>>,
        Option<Ref<NodeSurface>>,
        Option<&mut ShownShape>,
    )>,
) {
    for (entity, node, curve, surface, shown) in &mut nodes {
        let document = match (&curve, &surface) {
            (Some(c), _) => Some((Shape::Curve(c.0.clone()), c.is_changed())),
            (None, Some(s)) => Some((Shape::Surface(s.0.clone()), s.is_changed())),
            (None, None) => None,
        };
        let Some((document, changed)) = document else {
            if shown.is_some() {
                commands.entity(entity).remove::<ShownShape>();
            }
            continue;
        };
        if shown.is_some() && !previews.is_changed() && !changed {
            continue;
        }
        let wanted = match previews.content(node.0) {
            Some(PreviewContent::Curve(c)) => ShownShape {
                shape: Shape::Curve(c.clone()),
                previewed: true,
            },
            Some(PreviewContent::Surface(s)) => ShownShape {
                shape: Shape::Surface(s.clone()),
                previewed: true,
            },
            _ => ShownShape {
                shape: document,
                previewed: false,
            },
        };
        match shown {
            Some(mut shown) => {
                shown.set_if_neq(wanted);
            }
            None => {
                commands.entity(entity).insert(wanted);
            }
        }
    }
}

/// What nodes show, looked up by node id (for systems that start from a
/// node, such as the edited one, rather than from the entities).
#[derive(bevy::ecs::system::SystemParam)]
pub struct Shown<'w, 's> {
    entities: Res<'w, NodeEntities>,
    meshes: Query<'w, 's, (&'static ShownMesh, &'static NodeMesh)>,
    shapes: Query<'w, 's, &'static ShownShape>,
}

impl Shown<'_, '_> {
    /// A mesh node's cage and creases as the screen shows them.
    pub fn mesh(&self, node: NodeId) -> Option<(&Arc<HalfEdgeMesh>, &Creases)> {
        let (shown, mesh) = self.meshes.get(*self.entities.0.get(&node)?).ok()?;
        Some((&shown.cage, shown.creases(mesh)))
    }

    /// A curve or surface node's shape as the screen shows it.
    pub fn shape(&self, node: NodeId) -> Option<NodeContent> {
        let shown = self.shapes.get(*self.entities.0.get(&node)?).ok()?;
        Some(shown.content())
    }
}
