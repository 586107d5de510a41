//! CSG commands (issue 17): add a CSG node over operands, set its
//! operation, apply it (the solid becomes a plain mesh), and a one-shot
//! boolean between two nodes.

use super::plan::Plan;
use super::{Command, CommandError, NodeRef};
use crate::csg::{self, CsgContent, CsgError};
use crate::scene::{Document, MeshContent, NodeContent, NodeId, NodeTransform};
use glam::DMat4;
use hedra_geom::csg::{BooleanError, BooleanOp, Operand, boolean_with_sources};
use hedra_geom::subdivision::Creases;
use std::collections::BTreeMap;
use std::sync::Arc;

impl Plan<'_> {
    /// The document as it will be once the changes so far are applied.
    fn planned_doc(&self) -> Document {
        let mut d = self.doc.clone();
        for c in &self.changes {
            match &c.after {
                Some(n) => {
                    d.nodes.insert(c.id, n.clone());
                }
                None => {
                    d.nodes.remove(&c.id);
                }
            }
        }
        d
    }

    fn csg_node(&self, r: &NodeRef) -> Result<(crate::scene::Node, CsgContent), CommandError> {
        let n = self.node(r)?;
        match n.content {
            NodeContent::Csg(c) => Ok((n, c)),
            _ => Err(CommandError::NotACsg {
                node: self.doc.label_of(n.id),
            }),
        }
    }

    /// Refuses the plan when CSG node `id` would not evaluate.
    fn check_csg(&self, id: NodeId) -> Result<(), CommandError> {
        let d = self.planned_doc();
        if csg::operands(&d, id).is_empty() {
            return Ok(()); // an empty CSG node waits for operands
        }
        csg::evaluate(&d, id)?;
        Ok(())
    }

    pub(super) fn add_csg(
        &mut self,
        op: BooleanOp,
        name: &Option<String>,
        operands: &[NodeRef],
        parent: &Option<NodeRef>,
        transform: NodeTransform,
    ) -> Result<(), CommandError> {
        let label = name
            .clone()
            .unwrap_or_else(|| default_csg_name(op).to_string());
        let id = self.add_node(
            &label,
            parent,
            transform,
            NodeContent::Csg(CsgContent { op }),
        )?;
        let parent_world = parent
            .as_ref()
            .map(|p| self.resolve(p))
            .transpose()?
            .map_or(DMat4::IDENTITY, |p| self.doc.world_matrix(p));
        let world = parent_world * transform.to_matrix();
        for r in operands {
            let mut n = self.node(r)?;
            if self.doc.is_ancestor(n.id, id)
                || Some(n.id) == parent.as_ref().and_then(|p| self.resolve(p).ok())
            {
                return Err(CommandError::Cycle {
                    node: self.doc.label_of(n.id),
                    parent: label.clone(),
                });
            }
            n.transform = NodeTransform::from_matrix(world.inverse() * self.doc.world_matrix(n.id));
            n.parent = Some(id);
            self.set(n);
        }
        self.check_csg(id)
    }

    pub(super) fn set_csg_op(&mut self, node: &NodeRef, op: BooleanOp) -> Result<(), CommandError> {
        let (mut n, _) = self.csg_node(node)?;
        let id = n.id;
        // A node still called after its operation ("Union", "Union.001")
        // is renamed for the new one; a name the user gave stays.
        if let NodeContent::Csg(CsgContent { op: old }) = n.content {
            let stem = match n.name.rsplit_once('.') {
                Some((b, s)) if s.len() == 3 && s.chars().all(|c| c.is_ascii_digit()) => b,
                _ => n.name.as_str(),
            };
            if old != op && stem == default_csg_name(old) {
                n.name = self.unique_name(default_csg_name(op));
            }
        }
        n.content = NodeContent::Csg(CsgContent { op });
        self.set(n);
        self.check_csg(id)
    }

    pub(super) fn apply_csg(&mut self, node: &NodeRef) -> Result<(), CommandError> {
        let (mut n, content) = self.csg_node(node)?;
        let d = self.planned_doc();
        let solid = csg::evaluate(&d, n.id)?;
        if solid.face_count() == 0 {
            // An empty solid would become a mesh without faces.
            let operands: Vec<String> = csg::operands(&d, n.id)
                .iter()
                .filter_map(|&o| d.node(o).map(|x| x.name.clone()))
                .collect();
            return Err(CommandError::from(CsgError::Empty {
                op: content.op,
                operands: csg::names(&operands),
            }));
        }
        for o in csg::operands(&d, n.id) {
            for x in d.subtree(o).into_iter().rev() {
                self.remove(x);
            }
        }
        n.content = NodeContent::Mesh(MeshContent::new(solid));
        self.set(n);
        Ok(())
    }

    pub(super) fn boolean(
        &mut self,
        node: &NodeRef,
        other: &NodeRef,
        op: BooleanOp,
    ) -> Result<(), CommandError> {
        let mut a = self.node(node)?;
        let b = self.node(other)?;
        if a.id == b.id {
            return Err(CommandError::from(CsgError::Operand {
                node: format!("'{}'", a.name),
                operand: b.name.clone(),
                problem: "is the node itself".to_string(),
            }));
        }
        let d = self.planned_doc();
        let a_label = self.doc.label_of(a.id);
        let NodeContent::Mesh(content) = &mut a.content else {
            return Err(CommandError::NotAMesh { node: a_label });
        };
        // B's solid in A's space, through a CSG node of one operand.
        let b_solid = match &b.content {
            NodeContent::Csg(_) => csg::evaluate(&d, b.id)?,
            NodeContent::Mesh(m) => {
                let level = m.subdivision.map_or(0, |s| s.viewport_level);
                Arc::new(
                    m.evaluated(level)
                        .map_err(|error| CsgError::Evaluation {
                            node: format!("'{}'", a.name),
                            operand: b.name.clone(),
                            error: Box::new(error),
                        })?
                        .into_owned(),
                )
            }
            _ => {
                return Err(CommandError::NotAMesh {
                    node: self.doc.label_of(b.id),
                });
            }
        };
        let to_a = d.world_matrix(a.id).inverse() * d.world_matrix(b.id);
        let mut placed = (*b_solid).clone();
        for p in placed.positions_mut() {
            *p = to_a.transform_point3(*p);
        }
        if to_a.determinant() < 0.0 {
            placed.reverse_orientation();
        }
        let r = boolean_with_sources(&content.mesh, &placed, op, csg::CSG_TOLERANCE).map_err(
            |error| match error {
                BooleanError::EmptyResult { op } => CsgError::Empty {
                    op,
                    operands: format!("{} and {}", a.name, b.name),
                },
                BooleanError::Open { operand, .. }
                | BooleanError::NonManifold { operand, .. }
                | BooleanError::NotPolygonal { operand, .. }
                | BooleanError::NonFinite { operand }
                | BooleanError::SelfIntersecting { operand, .. }
                | BooleanError::EmptyOperand { operand } => CsgError::Operand {
                    node: format!("'{}'", a.name),
                    operand: if operand == Operand::A {
                        a.name.clone()
                    } else {
                        b.name.clone()
                    },
                    problem: csg::problem(&error),
                },
                error => CsgError::Boolean {
                    node: format!("'{}'", a.name),
                    error,
                },
            },
        )?;
        // UVs of A's corners and creases of A's edges that survive.
        let old = content.mesh.clone();
        let mut uvs = BTreeMap::new();
        if !content.corners.uvs.is_empty() {
            for f in r.mesh.faces() {
                for h in r.mesh.face_halfedges(f) {
                    if let Some((Operand::A, c)) = r.source_corner([&old, &placed], h)
                        && let Some(uv) = content.corners.uvs.get(&c)
                    {
                        uvs.insert(h, *uv);
                    }
                }
            }
        }
        let mut creases = Creases::default();
        for e in r.mesh.edges() {
            let [u, v] = r.mesh.edge_vertices(e);
            if let (Some((Operand::A, x)), Some((Operand::A, y))) =
                (r.vertices[u.index()], r.vertices[v.index()])
                && let Some(old_edge) = old.find_edge(x, y)
            {
                let s = content.creases.edge(old_edge);
                if s > 0.0 {
                    creases.set_edge(e, s);
                }
            }
        }
        content.mesh = Arc::new(r.mesh);
        content.primitive = None;
        content.creases = creases;
        content.corners = crate::scene::CornerAttributes {
            uvs: Arc::new(uvs),
            normals: Arc::default(),
        };
        self.set(a);
        for x in d.subtree(b.id).into_iter().rev() {
            self.remove(x);
        }
        Ok(())
    }
}

/// The name a CSG node gets when the user gives none: its operation.
fn default_csg_name(op: BooleanOp) -> &'static str {
    match op {
        BooleanOp::Union => "Union",
        BooleanOp::Intersection => "Intersection",
        BooleanOp::Difference => "Difference",
    }
}

impl Plan<'_> {
    /// Decides a command of the CSG family (the variants
    /// [`Family::Csg`](super::plan::Family::Csg) names; [`Plan::run`] sends only those here).
    pub(super) fn run_csg_command(&mut self, cmd: &Command) -> Result<(), CommandError> {
        match cmd {
            Command::AddCsg {
                op,
                name,
                operands,
                parent,
                transform,
            } => self.add_csg(*op, name, operands, parent, *transform),
            Command::SetCsgOp { node, op } => self.set_csg_op(node, *op),
            Command::ApplyCsg { node } => self.apply_csg(node),
            Command::Boolean { node, other, op } => self.boolean(node, other, *op),
            _ => unreachable!("not a command of the CSG family"),
        }
    }
}
