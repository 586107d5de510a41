//! Tool previews that only re-place vertices while a drag goes on.
//!
//! Extrude and inset make the same faces at any distance or thickness, and
//! put every vertex at `p₀ + t·d`: each new vertex is an old one moved along
//! a direction fixed by the selection (the region or face normal, the
//! corner bisector over the sine or cosine of its half angle), scaled by the
//! parameter `t` (`hedra_geom::modeling::{extrude_region, extrude_faces_individual,
//! inset_region, inset_faces_individual}`). Deciding such a command on every
//! frame of a drag copies the mesh twice and validates it; a
//! [`LinearPreview`] decides it twice when the drag starts (at 0 and at 1)
//! and then makes each frame's mesh with one copy and the moved positions.
//! The command itself is decided and validated as usual when the tool is
//! confirmed.

use crate::command::{Command, CommandError};
use crate::scene::{Document, NodeContent, NodeId};
use glam::DVec3;
use hedra_geom::subdivision::Creases;
use hedra_geom::{FaceId, HalfEdgeMesh, VertexId};
use std::sync::Arc;

/// A command's result as a function of its parameter, for a preview.
#[derive(Clone, Debug)]
pub struct LinearPreview {
    /// The result at parameter 0.
    at_zero: Arc<HalfEdgeMesh>,
    /// The vertices the parameter moves: position at 0 and change per unit.
    moves: Vec<(VertexId, DVec3, DVec3)>,
    /// The faces the command makes (extrude caps, inset inner faces).
    pub created_faces: Vec<FaceId>,
    /// The node's creases after the command.
    pub creases: Creases,
}

impl Command {
    /// The parameter a command's result moves linearly with: an extrude's
    /// distance, an inset's thickness (without depth). `None` for others.
    pub fn linear_parameter(&self) -> Option<f64> {
        match self {
            Command::ExtrudeRegion { distance, .. } | Command::ExtrudeFaces { distance, .. } => {
                Some(*distance)
            }
            Command::InsetRegion {
                thickness, depth, ..
            }
            | Command::InsetFaces {
                thickness, depth, ..
            } if *depth == 0.0 => Some(*thickness),
            _ => None,
        }
    }

    /// The same command with its [linear parameter](Self::linear_parameter) set to `t`.
    pub fn with_linear_parameter(&self, t: f64) -> Option<Command> {
        let mut c = self.clone();
        match &mut c {
            Command::ExtrudeRegion { distance, .. } | Command::ExtrudeFaces { distance, .. } => {
                *distance = t
            }
            Command::InsetRegion { thickness, .. } | Command::InsetFaces { thickness, .. } => {
                *thickness = t
            }
            _ => return None,
        }
        c.linear_parameter().map(|_| c)
    }
}

impl Document {
    /// A preview of `cmd` on mesh node `node` that re-places vertices for
    /// any value of its linear parameter; `Ok(None)` when the command has
    /// no such parameter or its results at 0 and 1 differ in connectivity.
    ///
    /// # Errors
    /// As [`Document::decide`], at parameter 0 or 1.
    pub fn linear_preview(
        &self,
        cmd: &Command,
        node: NodeId,
    ) -> Result<Option<LinearPreview>, CommandError> {
        let (Some(c0), Some(c1)) = (
            cmd.with_linear_parameter(0.0),
            cmd.with_linear_parameter(1.0),
        ) else {
            return Ok(None);
        };
        let d0 = self.decide_with_result(&c0, 0)?;
        let d1 = self.decide_with_result(&c1, 0)?;
        let mesh_of = |d: &crate::command::Decision| {
            d.transaction
                .changes
                .iter()
                .find(|c| c.id == node)
                .and_then(|c| c.after.as_ref())
                .and_then(|n| match &n.content {
                    NodeContent::Mesh(m) => Some((m.mesh.clone(), m.creases.clone())),
                    _ => None,
                })
        };
        let (Some((m0, creases)), Some((m1, _))) = (mesh_of(&d0), mesh_of(&d1)) else {
            return Ok(None);
        };
        if !m0.same_connectivity(&m1) {
            return Ok(None);
        }
        let moves = m0
            .vertices()
            .filter_map(|v| {
                let (a, b) = (m0.position(v), m1.position(v));
                (a != b).then_some((v, a, b - a))
            })
            .collect();
        Ok(Some(LinearPreview {
            at_zero: m0,
            moves,
            created_faces: d0.created_faces,
            creases,
        }))
    }
}

impl LinearPreview {
    /// The command's mesh at parameter `t`: one copy of the result at 0
    /// with the moved vertices placed.
    pub fn mesh_at(&self, t: f64) -> HalfEdgeMesh {
        let mut mesh = (*self.at_zero).clone();
        for &(v, p, d) in &self.moves {
            mesh.set_position(v, p + d * t);
        }
        mesh
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{FaceSet, NodeRef, NodeTransform, Session};
    use hedra_geom::Primitive;

    #[test]
    fn a_linear_preview_equals_the_decided_command_at_any_parameter() {
        let mut session = Session::new();
        session
            .execute(&Command::AddPrimitive {
                primitive: Primitive::Grid {
                    x_segments: 6,
                    z_segments: 6,
                    size: 2.0,
                },
                name: Some("G".into()),
                parent: None,
                transform: NodeTransform::IDENTITY,
            })
            .unwrap();
        let node = session.doc.find_by_name("G").unwrap().id;
        let faces = FaceSet::Ids(vec![7, 8, 13, 14]);
        let r = || NodeRef::Name("G".into());
        for cmd in [
            Command::ExtrudeRegion {
                node: r(),
                faces: faces.clone(),
                distance: 0.3,
            },
            Command::ExtrudeFaces {
                node: r(),
                faces: faces.clone(),
                distance: -0.2,
            },
            Command::InsetRegion {
                node: r(),
                faces: faces.clone(),
                thickness: 0.05,
                depth: 0.0,
            },
            Command::InsetFaces {
                node: r(),
                faces: faces.clone(),
                thickness: 0.04,
                depth: 0.0,
            },
        ] {
            let preview = session.doc.linear_preview(&cmd, node).unwrap().unwrap();
            for t in [0.0, 0.07, 0.3, 1.5] {
                let exact = session
                    .doc
                    .decide(&cmd.with_linear_parameter(t).unwrap(), 0)
                    .unwrap();
                let NodeContent::Mesh(m) = &exact.changes[0].after.as_ref().unwrap().content else {
                    panic!("a mesh")
                };
                let shown = preview.mesh_at(t);
                assert!(shown.same_connectivity(&m.mesh), "{}", cmd.label());
                for v in shown.vertices() {
                    let d = shown.position(v).distance(m.mesh.position(v));
                    assert!(d < 1e-12, "{} at {t}: vertex {v} off by {d}", cmd.label());
                }
            }
        }
        // Commands without a linear parameter have no linear preview.
        let moved = Command::MoveVertices {
            node: r(),
            vertices: crate::VertexSet::Ids(vec![0]),
            offset: DVec3::Y,
        };
        assert!(session.doc.linear_preview(&moved, node).unwrap().is_none());
    }
}
