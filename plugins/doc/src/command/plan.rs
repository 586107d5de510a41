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

    /// Decides one command into this plan: hands it to its family's
    /// function, in the family's file ([`Family`]).
    pub(super) fn run(&mut self, cmd: &Command) -> Result<(), CommandError> {
        match family(cmd) {
            Family::Nodes => self.run_node_command(cmd),
            Family::Csg => self.run_csg_command(cmd),
            Family::Shapes => self.run_shape_command(cmd),
            Family::Constructions => self.run_construction_command(cmd),
            Family::Creases => self.run_crease_command(cmd),
            Family::Modifiers => self.run_modifier_command(cmd),
            Family::Mesh => self.run_mesh_command(cmd),
        }
    }
}

/// The families of commands, each decided in its own file by its own
/// `run_…_command`, which matches only that family's variants.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Family {
    /// Nodes and the scene tree (nodes.rs).
    Nodes,
    /// CSG (csg.rs).
    Csg,
    /// Curves and surfaces (shapes.rs).
    Shapes,
    /// Surfaces and meshes from curves (constructions.rs).
    Constructions,
    /// Subdivision and creases (creases.rs).
    Creases,
    /// The modifier stack (modifiers.rs).
    Modifiers,
    /// Mesh modeling (mesh.rs).
    Mesh,
}

/// The family of a command: the one place every variant is named, so a
/// new command does not compile until it has a family.
fn family(cmd: &Command) -> Family {
    match cmd {
        Command::AddPrimitive { .. }
        | Command::AddMesh { .. }
        | Command::AddKeptMesh { .. }
        | Command::AddEmpty { .. }
        | Command::SetPrimitive { .. }
        | Command::SetTransforms { .. }
        | Command::Translate { .. }
        | Command::Rotate { .. }
        | Command::Scale { .. }
        | Command::Rename { .. }
        | Command::Reparent { .. }
        | Command::SetVisible { .. }
        | Command::SetShading { .. }
        | Command::MakeManifold { .. }
        | Command::Delete { .. }
        | Command::Duplicate { .. } => Family::Nodes,
        Command::AddCsg { .. }
        | Command::SetCsgOp { .. }
        | Command::ApplyCsg { .. }
        | Command::Boolean { .. } => Family::Csg,
        Command::AddCurve { .. }
        | Command::AddSurface { .. }
        | Command::SetControlPoints { .. }
        | Command::SetWeights { .. }
        | Command::InsertKnot { .. }
        | Command::ElevateDegree { .. }
        | Command::SetCurve { .. }
        | Command::InsertCurvePoint { .. }
        | Command::DeleteCurvePoints { .. }
        | Command::ExtrudeCurve { .. }
        | Command::SetCurveClosed { .. }
        | Command::ReverseCurve { .. }
        | Command::SplitCurve { .. }
        | Command::JoinCurves { .. }
        | Command::SetCurveJoin { .. }
        | Command::ConvertCurveToNurbs { .. } => Family::Shapes,
        Command::MakeFromCurves { .. }
        | Command::SetConstruction { .. }
        | Command::ApplyConstruction { .. }
        | Command::MakeG1Join { .. }
        | Command::BreakG1Join { .. } => Family::Constructions,
        Command::SetSubdivision { .. }
        | Command::ApplySubdivision { .. }
        | Command::SetEdgeCrease { .. }
        | Command::SetVertexCrease { .. }
        | Command::SetCreaseTaper { .. }
        | Command::SetFaceHole { .. }
        | Command::SnapToLimit { .. }
        | Command::ConvertSubdivisionToNurbs { .. } => Family::Creases,
        Command::AddModifier { .. }
        | Command::SetModifier { .. }
        | Command::RemoveModifier { .. }
        | Command::MoveModifier { .. }
        | Command::ApplyModifiers { .. }
        | Command::Decimate { .. } => Family::Modifiers,
        Command::MoveVertices { .. }
        | Command::SetVertexPositions { .. }
        | Command::ExtrudeFaces { .. }
        | Command::ExtrudeRegion { .. }
        | Command::InsetFaces { .. }
        | Command::InsetRegion { .. }
        | Command::LoopCut { .. }
        | Command::SubdivideEdges { .. }
        | Command::ConnectVertices { .. }
        | Command::Triangulate { .. }
        | Command::TrisToQuads { .. }
        | Command::Bisect { .. }
        | Command::Spin { .. }
        | Command::Screw { .. }
        | Command::Knife { .. }
        | Command::Rip { .. }
        | Command::RipVertex { .. }
        | Command::SplitVertex { .. }
        | Command::Euler { .. }
        | Command::DissolveEdges { .. }
        | Command::DissolveVertices { .. }
        | Command::DissolveFaces { .. }
        | Command::FlipNormals { .. }
        | Command::RecalculateNormals { .. }
        | Command::MakeHoles { .. }
        | Command::FillHoles { .. }
        | Command::CollapseEdges { .. }
        | Command::ExtrudeEdges { .. }
        | Command::MirrorVertices { .. }
        | Command::Symmetrize { .. }
        | Command::SlideEdges { .. }
        | Command::BevelEdges { .. }
        | Command::BevelVertices { .. }
        | Command::DeleteFaces { .. }
        | Command::DeleteEdges { .. }
        | Command::DeleteVertices { .. }
        | Command::MergeVertices { .. }
        | Command::MergeByDistance { .. }
        | Command::BridgeLoops { .. } => Family::Mesh,
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
