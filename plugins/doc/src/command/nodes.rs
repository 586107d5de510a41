//! Commands on nodes and the scene tree: adding primitives, meshes and
//! empties, adjusting a primitive, transforms, names, parents, visibility,
//! shading, deleting and duplicating.

use super::plan::Plan;
use super::{Command, CommandError, NodeRef};
use crate::scene::{CornerAttributes, MeshContent, NodeContent, NodeId, NodeTransform, Shading};
use glam::{DQuat, DVec3};
use hedra_geom::subdivision::Creases;
use hedra_geom::{HalfEdgeMesh, Primitive};
use std::sync::Arc;

/// Round primitives start smooth, boxy ones flat, as in most modelers.
fn primitive_shading(p: &Primitive) -> Shading {
    match p {
        Primitive::UvSphere { .. } | Primitive::IcoSphere { .. } | Primitive::Torus { .. } => {
            Shading::Smooth
        }
        _ => Shading::Flat,
    }
}

impl Plan<'_> {
    pub(super) fn add_primitive(
        &mut self,
        primitive: &Primitive,
        name: &Option<String>,
        parent: &Option<NodeRef>,
        transform: NodeTransform,
    ) -> Result<(), CommandError> {
        let mesh = primitive.build()?;
        let name = name
            .clone()
            .unwrap_or_else(|| primitive.display_name().to_string());
        let content = NodeContent::Mesh(MeshContent {
            primitive: Some(primitive.clone()),
            shading: primitive_shading(primitive),
            ..MeshContent::new(Arc::new(mesh))
        });
        self.add_node(&name, parent, transform, content)?;
        Ok(())
    }

    pub(super) fn add_mesh(
        &mut self,
        name: &str,
        positions: &[DVec3],
        polygons: &[Vec<u32>],
        parent: &Option<NodeRef>,
        transform: NodeTransform,
    ) -> Result<(), CommandError> {
        let mesh = HalfEdgeMesh::from_polygons(positions, polygons)?;
        let content = NodeContent::Mesh(MeshContent::new(Arc::new(mesh)));
        self.add_node(name, parent, transform, content)?;
        Ok(())
    }

    pub(super) fn add_empty(
        &mut self,
        name: &str,
        parent: &Option<NodeRef>,
        transform: NodeTransform,
    ) -> Result<(), CommandError> {
        self.add_node(name, parent, transform, NodeContent::Empty)?;
        Ok(())
    }

    /// Rebuilds a primitive node with new parameters of the same kind.
    pub(super) fn set_primitive(
        &mut self,
        node: &NodeRef,
        primitive: &Primitive,
    ) -> Result<(), CommandError> {
        let mut n = self.node(node)?;
        let NodeContent::Mesh(content) = &n.content else {
            return Err(CommandError::NotAMesh {
                node: self.doc.label_of(n.id),
            });
        };
        match &content.primitive {
            Some(old) if old.kind() == primitive.kind() => {}
            _ => {
                return Err(CommandError::NotAPrimitive {
                    node: self.doc.label_of(n.id),
                });
            }
        }
        let mesh = primitive.build()?;
        n.content = NodeContent::Mesh(MeshContent {
            mesh: Arc::new(mesh),
            primitive: Some(primitive.clone()),
            creases: Creases::default(),
            corners: CornerAttributes::default(),
            ..content.clone()
        });
        self.set(n);
        Ok(())
    }

    pub(super) fn set_transforms(
        &mut self,
        nodes: &[(NodeRef, NodeTransform)],
    ) -> Result<(), CommandError> {
        for (r, t) in nodes {
            let n = self.node(r)?;
            self.set_transform(n, *t)?;
        }
        Ok(())
    }

    pub(super) fn translate(
        &mut self,
        nodes: &[NodeRef],
        offset: DVec3,
    ) -> Result<(), CommandError> {
        for r in nodes {
            let n = self.node(r)?;
            let t = NodeTransform {
                translation: n.transform.translation + offset,
                ..n.transform
            };
            self.set_transform(n, t)?;
        }
        Ok(())
    }

    pub(super) fn rotate(
        &mut self,
        nodes: &[NodeRef],
        axis: DVec3,
        degrees: f64,
    ) -> Result<(), CommandError> {
        let Some(axis) = axis.try_normalize() else {
            return Err(CommandError::Nothing("the rotation axis is zero"));
        };
        let q = DQuat::from_axis_angle(axis, degrees.to_radians());
        for r in nodes {
            let n = self.node(r)?;
            let t = NodeTransform {
                rotation: (q * n.transform.rotation).normalize(),
                ..n.transform
            };
            self.set_transform(n, t)?;
        }
        Ok(())
    }

    pub(super) fn scale(&mut self, nodes: &[NodeRef], factor: DVec3) -> Result<(), CommandError> {
        for r in nodes {
            let n = self.node(r)?;
            let t = NodeTransform {
                scale: n.transform.scale * factor,
                ..n.transform
            };
            self.set_transform(n, t)?;
        }
        Ok(())
    }

    pub(super) fn rename(&mut self, node: &NodeRef, name: &str) -> Result<(), CommandError> {
        if name.trim().is_empty() {
            return Err(CommandError::EmptyName);
        }
        let mut n = self.node(node)?;
        if n.name != name {
            n.name = self.unique_name(name);
            self.set(n);
        }
        Ok(())
    }

    /// Gives a node a new parent; with `keep_world` it stays where it is.
    pub(super) fn reparent(
        &mut self,
        node: &NodeRef,
        parent: &Option<NodeRef>,
        keep_world: bool,
    ) -> Result<(), CommandError> {
        let mut n = self.node(node)?;
        let new_parent = parent.as_ref().map(|p| self.resolve(p)).transpose()?;
        if let Some(p) = new_parent
            && self.doc.is_ancestor(n.id, p)
        {
            return Err(CommandError::Cycle {
                node: self.doc.label_of(n.id),
                parent: self.doc.label_of(p),
            });
        }
        if keep_world {
            let world = self.doc.world_matrix(n.id);
            let parent_world =
                new_parent.map_or(glam::DMat4::IDENTITY, |p| self.doc.world_matrix(p));
            n.transform = NodeTransform::from_matrix(parent_world.inverse() * world);
        }
        n.parent = new_parent;
        self.set(n);
        Ok(())
    }

    pub(super) fn set_visible(
        &mut self,
        nodes: &[NodeRef],
        visible: bool,
    ) -> Result<(), CommandError> {
        for r in nodes {
            let mut n = self.node(r)?;
            n.visible = visible;
            self.set(n);
        }
        Ok(())
    }

    pub(super) fn set_shading(
        &mut self,
        nodes: &[NodeRef],
        shading: Shading,
    ) -> Result<(), CommandError> {
        for r in nodes {
            let mut n = self.node(r)?;
            match &mut n.content {
                NodeContent::Mesh(content) => content.shading = shading,
                NodeContent::Kept(content) => content.shading = shading,
                _ => {
                    return Err(CommandError::NotAMesh {
                        node: self.doc.label_of(n.id),
                    });
                }
            }
            self.set(n);
        }
        Ok(())
    }

    /// Repairs kept meshes into half-edge meshes ([`Command::MakeManifold`]).
    pub(super) fn make_manifold(&mut self, nodes: &[NodeRef]) -> Result<(), CommandError> {
        for r in nodes {
            let mut n = self.node(r)?;
            let label = self.doc.label_of(n.id);
            let NodeContent::Kept(kept) = &n.content else {
                return Err(CommandError::NotKept { node: label });
            };
            let (mesh, report) = kept.mesh.repaired().map_err(|e| CommandError::Repair {
                node: label.clone(),
                reason: e.to_string(),
            })?;
            if mesh.face_count() == 0 {
                return Err(CommandError::Repair {
                    node: label,
                    reason: format!("no face could be kept ({report})"),
                });
            }
            if !report.is_clean() {
                self.notes.push(format!("'{}': {report}", n.name));
            }
            n.content = NodeContent::Mesh(crate::scene::MeshContent {
                shading: kept.shading,
                subdivision: kept.subdivision,
                ..crate::scene::MeshContent::new(std::sync::Arc::new(mesh.compacted_if_needed()))
            });
            self.set(n);
        }
        Ok(())
    }

    /// Deletes nodes with their descendants.
    pub(super) fn delete(&mut self, nodes: &[NodeRef]) -> Result<(), CommandError> {
        for r in nodes {
            let id = self.resolve(r)?;
            for x in self.doc.subtree(id).into_iter().rev() {
                if self.current(x).is_some() {
                    self.remove(x);
                }
            }
        }
        Ok(())
    }

    /// Copies nodes with their descendants under new ids and names.
    pub(super) fn duplicate(&mut self, nodes: &[NodeRef]) -> Result<(), CommandError> {
        for r in nodes {
            let root = self.resolve(r)?;
            let subtree = self.doc.subtree(root);
            let mut map = std::collections::HashMap::new();
            for &old in &subtree {
                map.insert(old, NodeId(self.next_id));
                self.next_id += 1;
            }
            for &old in &subtree {
                let mut n = self
                    .current(old)
                    .cloned()
                    .ok_or(CommandError::UnknownNode(NodeRef::Id(old.0)))?;
                n.id = map[&old];
                n.parent = if old == root {
                    n.parent
                } else {
                    n.parent.map(|p| map[&p])
                };
                n.name = self.unique_name(&n.name);
                // A copy of a joined patch is not joined (it would share
                // the triangle's edge with the original).
                n.g1_join = None;
                self.set(n);
            }
        }
        Ok(())
    }
}

impl Plan<'_> {
    /// Decides a command of the nodes and the scene tree family (the variants
    /// [`Family::Nodes`](super::plan::Family::Nodes) names; [`Plan::run`] sends only those here).
    pub(super) fn run_node_command(&mut self, cmd: &Command) -> Result<(), CommandError> {
        match cmd {
            Command::AddPrimitive {
                primitive,
                name,
                parent,
                transform,
            } => self.add_primitive(primitive, name, parent, *transform),
            Command::AddMesh {
                name,
                positions,
                polygons,
                parent,
                transform,
            } => self.add_mesh(name, positions, polygons, parent, *transform),
            Command::AddKeptMesh {
                name,
                positions,
                faces,
                parent,
                transform,
            } => {
                let kept = crate::kept::KeptMesh::new(positions.clone(), faces.clone())
                    .map_err(CommandError::KeptMesh)?;
                let content =
                    NodeContent::Kept(crate::kept::KeptMeshContent::new(std::sync::Arc::new(kept)));
                self.add_node(name, parent, *transform, content).map(|_| ())
            }
            Command::AddEmpty {
                name,
                parent,
                transform,
            } => self.add_empty(name, parent, *transform),
            Command::SetPrimitive { node, primitive } => self.set_primitive(node, primitive),
            Command::SetTransforms { nodes } => self.set_transforms(nodes),
            Command::Translate { nodes, offset } => self.translate(nodes, *offset),
            Command::Rotate {
                nodes,
                axis,
                degrees,
            } => self.rotate(nodes, *axis, *degrees),
            Command::Scale { nodes, factor } => self.scale(nodes, *factor),
            Command::Rename { node, name } => self.rename(node, name),
            Command::Reparent {
                node,
                parent,
                keep_world,
            } => self.reparent(node, parent, *keep_world),
            Command::SetVisible { nodes, visible } => self.set_visible(nodes, *visible),
            Command::SetShading { nodes, shading } => self.set_shading(nodes, *shading),
            Command::MakeManifold { nodes } => self.make_manifold(nodes),
            Command::Delete { nodes } => self.delete(nodes),
            Command::Duplicate { nodes } => self.duplicate(nodes),
            _ => unreachable!("not a command of the nodes and the scene tree family"),
        }
    }
}
