//! Commands on subdivision: the modifier, applying it, edge and vertex
//! creases, face holes, and snapping the cage to its limit surface.

use super::plan::Plan;
use super::{Command, CommandError, EditError, NodeRef};
use crate::elements::{EdgeSet, FaceSet, VertexSet};
use crate::scene::{CornerAttributes, NodeContent, SubdivisionModifier};
use hedra_geom::subdivision::{self, INFINITE_SHARPNESS, Refiner};
use std::sync::Arc;

/// A crease value as stored: finite, in 0 ..= [`INFINITE_SHARPNESS`].
fn check_sharpness(s: f64) -> Result<f64, CommandError> {
    if s.is_finite() && (0.0..=INFINITE_SHARPNESS as f64).contains(&s) {
        Ok(s)
    } else {
        Err(CommandError::Sharpness(s))
    }
}

fn check_levels(level: u32) -> Result<(), CommandError> {
    if level > subdivision::MAX_LEVEL {
        Err(CommandError::Level(level))
    } else {
        Ok(())
    }
}

impl Plan<'_> {
    /// Adds, changes or (with `None`) removes the modifier of mesh nodes.
    pub(super) fn set_subdivision(
        &mut self,
        nodes: &[NodeRef],
        modifier: Option<SubdivisionModifier>,
    ) -> Result<(), CommandError> {
        if let Some(m) = modifier {
            check_levels(m.viewport_level.max(m.export_level))?;
        }
        for r in nodes {
            let mut n = self.node(r)?;
            let label = self.doc.label_of(n.id);
            match &mut n.content {
                NodeContent::Mesh(content) => content.subdivision = modifier,
                NodeContent::Kept(content) => content.subdivision = modifier,
                _ => return Err(CommandError::NotAMesh { node: label }),
            }
            self.set(n);
        }
        Ok(())
    }

    /// Replaces the cage by its subdivision and removes the modifier.
    pub(super) fn apply_subdivision(
        &mut self,
        node: &NodeRef,
        levels: Option<u32>,
    ) -> Result<(), CommandError> {
        let mut n = self.node(node)?;
        let label = self.doc.label_of(n.id);
        let NodeContent::Mesh(content) = &mut n.content else {
            return Err(CommandError::NotAMesh { node: label });
        };
        let (options, level) = match (content.subdivision, levels) {
            (_, Some(l)) => (content.subdivision.unwrap_or_default().options, l),
            (Some(m), None) => (m.options, m.viewport_level),
            (None, None) => {
                return Err(CommandError::Element {
                    node: label,
                    error: EditError::NoSubdivisionModifier,
                });
            }
        };
        check_levels(level)?;
        let (mesh, creases) = Refiner::subdivide(&content.mesh, &content.creases, options, level)
            .map_err(|error| CommandError::Subdivision { node: label, error })?;
        content.mesh = Arc::new(mesh);
        content.creases = creases;
        // The refined mesh has new ids: no corner attribute carries over.
        content.corners = CornerAttributes::default();
        content.subdivision = None;
        content.primitive = None;
        self.set(n);
        Ok(())
    }

    pub(super) fn set_edge_crease(
        &mut self,
        node: &NodeRef,
        edges: &EdgeSet,
        sharpness: f64,
    ) -> Result<(), CommandError> {
        let s = check_sharpness(sharpness)?;
        self.edit_creases(node, |m, c| {
            for e in edges.resolve(m)? {
                c.set_edge(e, s);
            }
            Ok(())
        })
    }

    pub(super) fn set_vertex_crease(
        &mut self,
        node: &NodeRef,
        vertices: &VertexSet,
        sharpness: f64,
    ) -> Result<(), CommandError> {
        let s = check_sharpness(sharpness)?;
        self.edit_creases(node, |m, c| {
            for v in vertices.resolve(m)? {
                c.set_vertex(v, s);
            }
            Ok(())
        })
    }

    pub(super) fn set_crease_taper(
        &mut self,
        node: &NodeRef,
        edges: &EdgeSet,
        from: &VertexSet,
        start: f64,
        end: f64,
    ) -> Result<(), CommandError> {
        let (start, end) = (check_sharpness(start)?, check_sharpness(end)?);
        self.edit_creases(node, |m, c| {
            let chain = edges.resolve(m)?;
            let from = super::euler::one_vertex(m, from, "`from`")?;
            c.set_taper(m, &chain, from, start, end)?;
            Ok(())
        })
    }

    pub(super) fn set_face_hole(
        &mut self,
        node: &NodeRef,
        faces: &FaceSet,
        hole: bool,
    ) -> Result<(), CommandError> {
        self.edit_creases(node, |m, c| {
            for f in faces.resolve(m)? {
                c.set_hole(f, hole);
            }
            Ok(())
        })
    }

    /// Moves every cage vertex onto the limit surface of its subdivision.
    pub(super) fn snap_to_limit(&mut self, node: &NodeRef) -> Result<(), CommandError> {
        let n = self.node(node)?;
        let label = self.doc.label_of(n.id);
        let NodeContent::Mesh(content) = &n.content else {
            return Err(CommandError::NotAMesh { node: label });
        };
        let options = content.subdivision.unwrap_or_default().options;
        let snapped = subdivision::snap_to_limit(&content.mesh, &content.creases, options)
            .map_err(|error| CommandError::Subdivision { node: label, error })?;
        self.edit_mesh(node, |m| {
            for (v, p) in snapped {
                m.set_position(v, p);
            }
            Ok(())
        })
    }
}

impl Plan<'_> {
    /// Decides a command of the subdivision and creases family (the variants
    /// [`Family::Creases`](super::plan::Family::Creases) names; [`Plan::run`] sends only those here).
    pub(super) fn run_crease_command(&mut self, cmd: &Command) -> Result<(), CommandError> {
        match cmd {
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
            _ => unreachable!("not a command of the subdivision and creases family"),
        }
    }
}
