//! The plan a command is decided into: the node changes it collects, the
//! helpers every family of commands shares (looking nodes up, naming,
//! editing a mesh, curve or creases on a copy), and [`Plan::run`], which
//! hands each command to its family's file.

use super::{Command, CommandError, EditError, NodeRef};
use crate::elements::ElementError;
use crate::elements::{EdgeSet, FaceSet, VertexSet};
use crate::history::NodeChange;
use crate::scene::{
    CurveContent, Document, Node, NodeContent, NodeId, NodeTransform, SurfaceShape,
};
use hedra_geom::curves::{CurveError, CurveKind};
use hedra_geom::subdivision::Creases;
use hedra_geom::{EdgeId, FaceId, HalfEdgeMesh, ModelingError, VertexId};
use std::sync::Arc;

/// Why a mesh edit refused: the elements or values it was given, or the
/// kernel's operation.
pub(super) enum Refusal {
    Edit(EditError),
    Modeling(ModelingError),
}

impl From<EditError> for Refusal {
    fn from(e: EditError) -> Self {
        Refusal::Edit(e)
    }
}

impl From<ElementError> for Refusal {
    fn from(e: ElementError) -> Self {
        Refusal::Edit(e.into())
    }
}

impl From<ModelingError> for Refusal {
    fn from(e: ModelingError) -> Self {
        Refusal::Modeling(e)
    }
}

/// Collects the node changes of one command.
pub(super) struct Plan<'a> {
    pub(super) doc: &'a Document,
    pub(super) next_id: u64,
    pub(super) changes: Vec<NodeChange>,
    /// See [`Decision::created_faces`](super::Decision::created_faces).
    pub(super) created_faces: Vec<FaceId>,
    /// See [`Decision::created_edges`](super::Decision::created_edges).
    pub(super) created_edges: Vec<EdgeId>,
    /// What the user should read in the step's label besides its name
    /// (a conversion's measured figures).
    pub(super) notes: Vec<String>,
}

impl Plan<'_> {
    /// The node as this plan currently sees it (later changes win).
    pub(super) fn current(&self, id: NodeId) -> Option<&Node> {
        match self.changes.iter().rev().find(|c| c.id == id) {
            Some(c) => c.after.as_ref(),
            None => self.doc.nodes.get(&id),
        }
    }

    pub(super) fn resolve(&self, r: &NodeRef) -> Result<NodeId, CommandError> {
        self.doc.resolve(r)
    }

    pub(super) fn set(&mut self, mut node: Node) {
        // A Decimate modifier's input may have changed: its record follows
        // (an input it cannot decimate shows when the stack is evaluated).
        if let NodeContent::Mesh(c) = &mut node.content
            && (c.has_decimate() || !c.decimations.is_empty())
        {
            let _ = c.refresh_decimations();
        }
        if let Some(c) = self.changes.iter_mut().find(|c| c.id == node.id) {
            c.after = Some(node);
        } else {
            let before = self.doc.nodes.get(&node.id).cloned();
            if before.as_ref() != Some(&node) {
                self.changes.push(NodeChange {
                    id: node.id,
                    before,
                    after: Some(node),
                });
            }
        }
    }

    pub(super) fn remove(&mut self, id: NodeId) {
        if let Some(c) = self.changes.iter_mut().find(|c| c.id == id) {
            c.after = None;
        } else {
            let before = self.doc.nodes.get(&id).cloned();
            self.changes.push(NodeChange {
                id,
                before,
                after: None,
            });
        }
    }

    pub(super) fn taken_name(&self, name: &str) -> bool {
        self.doc
            .nodes
            .values()
            .any(|n| n.name == name && self.current(n.id).is_some_and(|c| c.name == name))
            || self
                .changes
                .iter()
                .any(|c| c.after.as_ref().is_some_and(|n| n.name == name))
    }

    pub(super) fn unique_name(&self, name: &str) -> String {
        if !self.taken_name(name) {
            return name.to_string();
        }
        let base = match name.rsplit_once('.') {
            Some((b, s)) if s.len() == 3 && s.chars().all(|c| c.is_ascii_digit()) => b,
            _ => name,
        };
        (1..)
            .map(|i| format!("{base}.{i:03}"))
            .find(|n| !self.taken_name(n))
            .expect("a free suffix exists")
    }

    pub(super) fn add_node(
        &mut self,
        name: &str,
        parent: &Option<NodeRef>,
        transform: NodeTransform,
        content: NodeContent,
    ) -> Result<NodeId, CommandError> {
        if name.trim().is_empty() {
            return Err(CommandError::EmptyName);
        }
        let parent = parent.as_ref().map(|p| self.resolve(p)).transpose()?;
        let id = NodeId(self.next_id);
        if !transform.is_usable() {
            return Err(CommandError::BadTransform {
                node: name.to_string(),
            });
        }
        self.next_id += 1;
        let name = self.unique_name(name);
        self.set(Node {
            id,
            name,
            parent,
            transform,
            visible: true,
            content,
            construction: None,
            g1_join: None,
        });
        Ok(id)
    }

    pub(super) fn node(&self, r: &NodeRef) -> Result<Node, CommandError> {
        let id = self.resolve(r)?;
        self.current(id)
            .cloned()
            .ok_or(CommandError::UnknownNode(r.clone()))
    }

    pub(super) fn set_transform(
        &mut self,
        mut node: Node,
        transform: NodeTransform,
    ) -> Result<(), CommandError> {
        if !transform.is_usable() {
            return Err(CommandError::BadTransform {
                node: self.doc.label_of(node.id),
            });
        }
        node.transform = transform;
        self.set(node);
        Ok(())
    }

    /// Applies `edit` to a copy of the node's mesh and stores the result
    /// (no longer an adjustable primitive).
    pub(super) fn edit_mesh(
        &mut self,
        r: &NodeRef,
        edit: impl FnOnce(&mut HalfEdgeMesh) -> Result<(), EditError>,
    ) -> Result<(), CommandError> {
        self.model(r, |m| Ok(edit(m)?))
    }

    /// Edits a curve or surface node; a refused edit changes nothing.
    pub(super) fn edit_shape(
        &mut self,
        r: &NodeRef,
        curve: impl FnOnce(&CurveKind) -> Result<CurveKind, CurveError>,
        surface: impl FnOnce(&mut SurfaceShape) -> Result<(), CurveError>,
    ) -> Result<(), CommandError> {
        let mut n = self.node(r)?;
        let label = self.doc.label_of(n.id);
        let result = match &mut n.content {
            NodeContent::Curve(c) => curve(c.kind())
                .and_then(CurveContent::new)
                .map(|new| *c = Arc::new(new)),
            NodeContent::Surface(s) => surface(Arc::make_mut(s)),
            _ => return Err(CommandError::NotAShape { node: label }),
        };
        result.map_err(|error| CommandError::Curve { node: label, error })?;
        self.set(n);
        Ok(())
    }

    /// Edits a curve node's kind; a refused edit changes nothing.
    pub(super) fn edit_curve(
        &mut self,
        r: &NodeRef,
        curve: impl FnOnce(&CurveKind) -> Result<CurveKind, CurveError>,
    ) -> Result<(), CommandError> {
        let mut n = self.node(r)?;
        let label = self.doc.label_of(n.id);
        let NodeContent::Curve(c) = &mut n.content else {
            return Err(CommandError::NotACurve { node: label });
        };
        let new = curve(c.kind())
            .and_then(CurveContent::new)
            .map_err(|error| CommandError::Curve { node: label, error })?;
        *c = Arc::new(new);
        self.set(n);
        Ok(())
    }

    /// Changes the creases of a mesh node (the mesh itself stays shared).
    pub(super) fn edit_creases(
        &mut self,
        r: &NodeRef,
        edit: impl FnOnce(&HalfEdgeMesh, &mut Creases) -> Result<(), EditError>,
    ) -> Result<(), CommandError> {
        let mut n = self.node(r)?;
        let label = self.doc.label_of(n.id);
        let NodeContent::Mesh(content) = &mut n.content else {
            return Err(CommandError::NotAMesh { node: label });
        };
        edit(&content.mesh, &mut content.creases)
            .map_err(|error| CommandError::Element { node: label, error })?;
        self.set(n);
        Ok(())
    }

    /// Like [`edit_mesh`](Self::edit_mesh) for kernel operations that can refuse.
    pub(super) fn model(
        &mut self,
        r: &NodeRef,
        edit: impl FnOnce(&mut HalfEdgeMesh) -> Result<(), Refusal>,
    ) -> Result<(), CommandError> {
        let mut n = self.node(r)?;
        let label = self.doc.label_of(n.id);
        let NodeContent::Mesh(content) = &mut n.content else {
            return Err(CommandError::NotAMesh { node: label });
        };
        let mut mesh = (*content.mesh).clone();
        match edit(&mut mesh) {
            Err(Refusal::Edit(error)) => return Err(CommandError::Element { node: label, error }),
            Err(Refusal::Modeling(error)) => {
                return Err(CommandError::Modeling { node: label, error });
            }
            Ok(()) => {}
        }
        if cfg!(debug_assertions) && validate_edits() {
            assert!(
                mesh.validate().is_ok(),
                "a modeling operation broke the mesh"
            );
        }
        content.creases.retain_live(&mesh);
        // Every mesh edit passes here: UVs follow their corners, imported
        // normals no longer describe the edited shape and are dropped.
        content.corners = content.corners.follow_edit(&content.mesh, &mesh);
        content.mesh = Arc::new(mesh);
        content.primitive = None;
        self.set(n);
        Ok(())
    }

    /// Runs a kernel operation on the faces a set names.
    pub(super) fn on_faces(
        &mut self,
        r: &NodeRef,
        set: &FaceSet,
        op: impl FnOnce(&mut HalfEdgeMesh, &[FaceId]) -> Result<(), ModelingError>,
    ) -> Result<(), CommandError> {
        self.model(r, |m| {
            let fs = set.resolve(m)?;
            Ok(op(m, &fs)?)
        })
    }

    /// Runs a kernel operation on the edges a set names.
    pub(super) fn on_edges(
        &mut self,
        r: &NodeRef,
        set: &EdgeSet,
        op: impl FnOnce(&mut HalfEdgeMesh, &[EdgeId]) -> Result<(), ModelingError>,
    ) -> Result<(), CommandError> {
        self.model(r, |m| {
            let es = set.resolve(m)?;
            Ok(op(m, &es)?)
        })
    }

    /// Runs a kernel operation on the vertices a set names.
    pub(super) fn on_vertices(
        &mut self,
        r: &NodeRef,
        set: &VertexSet,
        op: impl FnOnce(&mut HalfEdgeMesh, &[VertexId]) -> Result<(), ModelingError>,
    ) -> Result<(), CommandError> {
        self.model(r, |m| {
            let vs = set.resolve(m)?;
            Ok(op(m, &vs)?)
        })
    }

    /// Decides one command into this plan, by family: `nodes`, `shapes`,
    /// `creases`, `mesh`.
    pub(super) fn run(&mut self, cmd: &Command) -> Result<(), CommandError> {
        match cmd {
            // ----- nodes and the scene tree (nodes.rs) -----
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
            // ----- CSG (csg.rs) -----
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

            // ----- curves and surfaces (shapes.rs) -----
            Command::AddCurve {
                name,
                curve,
                parent,
                transform,
            } => self.add_curve(name, curve, parent, *transform),
            Command::AddSurface {
                name,
                surface,
                parent,
                transform,
            } => self.add_surface(name, surface, parent, *transform),
            Command::SetControlPoints { node, points } => self.set_control_points(node, points),
            Command::SetWeights { node, weights } => self.set_weights(node, weights),
            Command::InsertKnot {
                node,
                at,
                direction,
            } => self.insert_knot(node, *at, *direction),
            Command::ElevateDegree { node, direction } => self.elevate_degree(node, *direction),
            Command::SetCurve { node, curve } => self.set_curve(node, curve),
            Command::InsertCurvePoint { node, at } => {
                self.edit_curve(node, |k| Ok(k.insert_point(*at)?.0))
            }
            Command::DeleteCurvePoints { node, points } => {
                let points: Vec<usize> = points.iter().map(|&i| i as usize).collect();
                self.edit_curve(node, |k| k.delete_points(&points))
            }
            Command::ExtrudeCurve { node, end, to } => {
                self.edit_curve(node, |k| k.extrude(*end, *to))
            }
            Command::SetCurveClosed { node, closed } => {
                self.edit_curve(node, |k| k.set_closed(*closed))
            }
            Command::ReverseCurve { node } => self.edit_curve(node, |k| k.reverse()),
            Command::SplitCurve { node, at, name } => self.split_curve(node, *at, name),
            Command::JoinCurves { first, second } => self.join_curves(first, second),
            Command::SetCurveJoin { node, joint, join } => {
                self.edit_curve(node, |k| k.set_join(*joint as usize, *join))
            }
            Command::ConvertCurveToNurbs { node } => {
                self.edit_curve(node, |k| Ok(CurveKind::Nurbs(k.to_nurbs()?.curve)))
            }

            // ----- surfaces and meshes from curves (constructions.rs) -----
            Command::MakeFromCurves { name, construction } => {
                self.make_from_curves(name, construction)
            }
            Command::SetConstruction { node, construction } => {
                self.set_construction(node, construction)
            }
            Command::ApplyConstruction { nodes } => self.apply_construction(nodes),
            Command::MakeG1Join { triangle, quad } => self.make_g1_join(triangle, quad),
            Command::BreakG1Join { node } => self.break_g1_join(node),

            // ----- subdivision and creases (creases.rs) -----
            Command::SetSubdivision { nodes, modifier } => self.set_subdivision(nodes, *modifier),
            Command::ApplySubdivision { node, levels } => self.apply_subdivision(node, *levels),
            Command::SetEdgeCrease {
                node,
                edges,
                sharpness,
            } => self.set_edge_crease(node, edges, *sharpness),
            Command::SetVertexCrease {
                node,
                vertices,
                sharpness,
            } => self.set_vertex_crease(node, vertices, *sharpness),
            Command::SetCreaseTaper {
                node,
                edges,
                from,
                start,
                end,
            } => self.set_crease_taper(node, edges, from, *start, *end),
            Command::SetFaceHole { node, faces, hole } => self.set_face_hole(node, faces, *hole),
            Command::SnapToLimit { node } => self.snap_to_limit(node),
            Command::ConvertSubdivisionToNurbs {
                node,
                tolerance,
                keep_cage,
            } => self.convert_subdivision_to_nurbs(node, *tolerance, *keep_cage),

            // ----- the modifier stack (modifiers.rs) -----
            Command::AddModifier { node, modifier } => self.add_modifier(node, modifier),
            Command::SetModifier {
                node,
                index,
                modifier,
            } => self.set_modifier(node, *index, modifier),
            Command::RemoveModifier { node, index } => self.remove_modifier(node, *index),
            Command::MoveModifier { node, from, to } => self.move_modifier(node, *from, *to),
            Command::ApplyModifiers { node, count } => self.apply_modifiers(node, *count),
            Command::Decimate {
                node,
                target,
                keep_borders,
                keep_creases,
                keep_uv_seams,
                sharp_angle,
                keep_quads,
            } => self.decimate(
                node,
                crate::modifiers::DecimateModifier {
                    target: *target,
                    level: None,
                    keep_borders: *keep_borders,
                    keep_creases: *keep_creases,
                    keep_uv_seams: *keep_uv_seams,
                    sharp_angle: *sharp_angle,
                    keep_quads: *keep_quads,
                },
            ),

            // ----- mesh modeling (mesh.rs) -----
            Command::MoveVertices {
                node,
                vertices,
                offset,
            } => self.move_vertices(node, vertices, *offset),
            Command::SetVertexPositions { node, positions } => {
                self.set_vertex_positions(node, positions)
            }
            Command::ExtrudeFaces {
                node,
                faces,
                distance,
            } => self.extrude_faces(node, faces, *distance),
            Command::ExtrudeRegion {
                node,
                faces,
                distance,
            } => self.extrude_region(node, faces, *distance),
            Command::InsetFaces {
                node,
                faces,
                thickness,
                depth,
            } => self.inset_faces(node, faces, *thickness, *depth),
            Command::InsetRegion {
                node,
                faces,
                thickness,
                depth,
            } => self.inset_region(node, faces, *thickness, *depth),
            Command::LoopCut { node, edge, cuts } => self.loop_cut(node, edge, *cuts),
            Command::SubdivideEdges { node, edges, cuts } => {
                self.subdivide_edges(node, edges, *cuts)
            }
            Command::ConnectVertices { node, vertices } => self.connect_vertices(node, vertices),
            Command::Triangulate {
                node,
                faces,
                method,
            } => self.triangulate(node, faces, *method),
            Command::TrisToQuads {
                node,
                faces,
                face_degrees,
                shape_degrees,
            } => self.tris_to_quads(node, faces, *face_degrees, *shape_degrees),
            Command::Bisect {
                node,
                faces,
                point,
                normal,
                clear,
                fill,
            } => self.bisect(node, faces, *point, *normal, *clear, *fill),
            Command::Spin {
                node,
                profile,
                center,
                axis,
                degrees,
                steps,
            } => self.spin(node, profile, *center, *axis, *degrees, *steps),
            Command::Screw {
                node,
                profile,
                center,
                axis,
                turns,
                steps,
                pitch,
            } => self.screw(node, profile, *center, *axis, *turns, *steps, *pitch),
            Command::Knife { node, points, view } => self.knife(node, points, *view),
            Command::Rip { node, edges } => self.rip(node, edges),
            Command::RipVertex { node, vertex, face } => self.rip_vertex(node, vertex, face),
            Command::SplitVertex {
                node,
                vertex,
                first,
                last,
                position,
            } => self.split_vertex(node, vertex, first, last, *position),
            Command::Euler { node, op } => self.euler(node, op),
            Command::DissolveEdges { node, edges } => self.dissolve_edges(node, edges),
            Command::DissolveVertices { node, vertices } => self.dissolve_vertices(node, vertices),
            Command::DissolveFaces { node, faces } => self.dissolve_faces(node, faces),
            Command::FlipNormals { node } => self.flip_normals(node),
            Command::RecalculateNormals { node } => self.recalculate_normals(node),
            Command::MakeHoles { node, faces } => self.make_holes(node, faces),
            Command::FillHoles { node, edges } => self.fill_holes(node, edges),
            Command::CollapseEdges { node, edges } => self.collapse_edges(node, edges),
            Command::ExtrudeEdges {
                node,
                edges,
                offset,
            } => self.extrude_edges(node, edges, *offset),
            Command::MirrorVertices {
                node,
                vertices,
                axis,
            } => self.mirror_vertices(node, vertices, *axis),
            Command::Symmetrize { node, axis } => self.symmetrize(node, *axis),
            Command::SlideEdges {
                node,
                edges,
                factor,
            } => self.slide_edges(node, edges, *factor),
            Command::BevelEdges {
                node,
                edges,
                width,
                segments,
            } => self.bevel_edges(node, edges, *width, *segments),
            Command::BevelVertices {
                node,
                vertices,
                width,
            } => self.bevel_vertices(node, vertices, *width),
            Command::DeleteFaces { node, faces } => self.delete_faces(node, faces),
            Command::DeleteEdges { node, edges } => self.delete_edges(node, edges),
            Command::DeleteVertices { node, vertices } => self.delete_vertices(node, vertices),
            Command::MergeVertices { node, vertices, at } => {
                self.merge_vertices(node, vertices, *at)
            }
            Command::MergeByDistance {
                node,
                vertices,
                distance,
            } => self.merge_by_distance(node, vertices, *distance),
            Command::BridgeLoops { node, edges } => self.bridge_loops(node, edges),
        }
    }
}

/// Whether a debug build checks every mesh edit with
/// [`HalfEdgeMesh::validate`] (on unless [`set_validate_edits`] turned it
/// off; release builds never check).
static VALIDATE_EDITS: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(true);

/// Turns the debug builds' check of every mesh edit on or off. The tests
/// keep it on; the window turns it off, because it walks the whole mesh on
/// every frame of a tool's drag (a 100k-face move took 9.5 ms a frame
/// instead of 0.45 ms), so that `cargo run` (the tests' build) is as
/// responsive as a release build.
pub fn set_validate_edits(on: bool) {
    VALIDATE_EDITS.store(on, std::sync::atomic::Ordering::Relaxed);
}

fn validate_edits() -> bool {
    VALIDATE_EDITS.load(std::sync::atomic::Ordering::Relaxed)
}
