//! Mesh modeling commands: moving vertices and the kernel's operations
//! (extrude, inset, loop cut, bevel, dissolve, merge, mirror, …) on the
//! elements a set names, in the node's local space.

use super::plan::Plan;
use super::{Command, CommandError, EditError, NodeRef};
use crate::elements::{EdgeSet, FaceSet, ProfileSet, VertexSet};
use glam::DVec3;
use hedra_geom::modeling::{self, BisectClear, MergePoint, MirrorAxis};
use hedra_geom::{ModelingError, VertexId};

impl Plan<'_> {
    pub(super) fn move_vertices(
        &mut self,
        node: &NodeRef,
        vertices: &VertexSet,
        offset: DVec3,
    ) -> Result<(), CommandError> {
        self.edit_mesh(node, |m| {
            let vs = vertices.resolve(m)?;
            if !offset.is_finite() {
                return Err(EditError::OffsetNotFinite);
            }
            for v in vs {
                m.set_position(v, m.position(v) + offset);
            }
            Ok(())
        })
    }

    pub(super) fn set_vertex_positions(
        &mut self,
        node: &NodeRef,
        positions: &[(u32, DVec3)],
    ) -> Result<(), CommandError> {
        self.edit_mesh(node, |m| {
            for &(i, p) in positions {
                let vertex = VertexId(i);
                if !m.is_vertex(vertex) {
                    return Err(EditError::NoSuchVertex { vertex });
                }
                if !p.is_finite() {
                    return Err(EditError::PositionNotFinite { vertex });
                }
                m.set_position(VertexId(i), p);
            }
            Ok(())
        })
    }

    pub(super) fn extrude_faces(
        &mut self,
        node: &NodeRef,
        faces: &FaceSet,
        distance: f64,
    ) -> Result<(), CommandError> {
        self.on_faces(node, faces, |m, fs| {
            modeling::extrude_faces_individual(m, fs, distance).map(drop)
        })
    }

    /// Extrudes faces as one region; its caps become the created faces.
    pub(super) fn extrude_region(
        &mut self,
        node: &NodeRef,
        faces: &FaceSet,
        distance: f64,
    ) -> Result<(), CommandError> {
        let mut caps = Vec::new();
        self.on_faces(node, faces, |m, fs| {
            let normal = m.region_normal(fs);
            if normal == DVec3::ZERO {
                return Err(ModelingError::Parameter {
                    what: "faces",
                    allowed: "facing some common direction",
                    value: "normals that cancel out".into(),
                });
            }
            modeling::extrude_region(m, fs, normal * distance).map(|c| caps = c)
        })?;
        self.created_faces = caps;
        Ok(())
    }

    pub(super) fn inset_faces(
        &mut self,
        node: &NodeRef,
        faces: &FaceSet,
        thickness: f64,
        depth: f64,
    ) -> Result<(), CommandError> {
        self.on_faces(node, faces, |m, fs| {
            modeling::inset_faces_individual(m, fs, thickness, depth).map(drop)
        })
    }

    /// Insets faces as one region; the inner faces become the created faces.
    pub(super) fn inset_region(
        &mut self,
        node: &NodeRef,
        faces: &FaceSet,
        thickness: f64,
        depth: f64,
    ) -> Result<(), CommandError> {
        let mut inner = Vec::new();
        self.on_faces(node, faces, |m, fs| {
            modeling::inset_region(m, fs, thickness, depth).map(|c| inner = c)
        })?;
        self.created_faces = inner;
        Ok(())
    }

    pub(super) fn loop_cut(
        &mut self,
        node: &NodeRef,
        edge: &EdgeSet,
        cuts: u32,
    ) -> Result<(), CommandError> {
        self.model(node, |m| {
            let es = edge.resolve(m)?;
            let [e] = es[..] else {
                return Err(EditError::LoopCutEdges {
                    edges: edge.clone(),
                    count: es.len(),
                }
                .into());
            };
            modeling::loop_cut(m, e, cuts)?;
            Ok(())
        })
    }

    pub(super) fn subdivide_edges(
        &mut self,
        node: &NodeRef,
        edges: &EdgeSet,
        cuts: u32,
    ) -> Result<(), CommandError> {
        self.on_edges(node, edges, |m, es| {
            modeling::subdivide_edges(m, es, cuts).map(drop)
        })
    }

    pub(super) fn connect_vertices(
        &mut self,
        node: &NodeRef,
        vertices: &VertexSet,
    ) -> Result<(), CommandError> {
        self.model(node, |m| {
            let vs = vertices.resolve(m)?;
            let [a, b] = vs[..] else {
                return Err(EditError::ConnectVertices {
                    vertices: vertices.clone(),
                    count: vs.len(),
                }
                .into());
            };
            modeling::connect_vertices(m, a, b)?;
            Ok(())
        })
    }

    pub(super) fn triangulate(
        &mut self,
        node: &NodeRef,
        faces: &FaceSet,
        method: modeling::TriangulateMethod,
    ) -> Result<(), CommandError> {
        self.on_faces(node, faces, |m, fs| {
            modeling::triangulate_faces(m, fs, method).map(drop)
        })
    }

    pub(super) fn tris_to_quads(
        &mut self,
        node: &NodeRef,
        faces: &FaceSet,
        face_degrees: f64,
        shape_degrees: f64,
    ) -> Result<(), CommandError> {
        self.on_faces(node, faces, |m, fs| {
            let (face, shape) = (face_degrees.to_radians(), shape_degrees.to_radians());
            modeling::tris_to_quads(m, fs, face, shape).map(drop)
        })
    }

    pub(super) fn bisect(
        &mut self,
        node: &NodeRef,
        faces: &FaceSet,
        point: DVec3,
        normal: DVec3,
        clear: BisectClear,
        fill: bool,
    ) -> Result<(), CommandError> {
        self.on_faces(node, faces, |m, fs| {
            modeling::bisect(m, fs, point, normal, clear, fill).map(drop)
        })
    }

    pub(super) fn spin(
        &mut self,
        node: &NodeRef,
        profile: &ProfileSet,
        center: DVec3,
        axis: DVec3,
        degrees: f64,
        steps: u32,
    ) -> Result<(), CommandError> {
        self.model(node, |m| {
            let p = profile.resolve(m)?;
            modeling::spin(m, &p, center, axis, degrees.to_radians(), steps)?;
            Ok(())
        })
    }

    #[allow(clippy::too_many_arguments)] // one per field of Command::Screw
    pub(super) fn screw(
        &mut self,
        node: &NodeRef,
        profile: &ProfileSet,
        center: DVec3,
        axis: DVec3,
        turns: u32,
        steps: u32,
        pitch: f64,
    ) -> Result<(), CommandError> {
        self.model(node, |m| {
            let p = profile.resolve(m)?;
            modeling::screw(m, &p, center, axis, turns, steps, pitch)?;
            Ok(())
        })
    }

    /// Knife cut along `points` seen along `view`; its cut edges become
    /// the created edges.
    pub(super) fn knife(
        &mut self,
        node: &NodeRef,
        points: &[DVec3],
        view: DVec3,
    ) -> Result<(), CommandError> {
        let mut cut_edges = Vec::new();
        self.model(node, |m| {
            cut_edges = modeling::knife(m, points, view)?.cut_edges;
            Ok(())
        })?;
        self.created_edges = cut_edges;
        Ok(())
    }

    pub(super) fn dissolve_edges(
        &mut self,
        node: &NodeRef,
        edges: &EdgeSet,
    ) -> Result<(), CommandError> {
        self.on_edges(node, edges, modeling::dissolve_edges)
    }

    pub(super) fn dissolve_vertices(
        &mut self,
        node: &NodeRef,
        vertices: &VertexSet,
    ) -> Result<(), CommandError> {
        self.on_vertices(node, vertices, modeling::dissolve_vertices)
    }

    pub(super) fn dissolve_faces(
        &mut self,
        node: &NodeRef,
        faces: &FaceSet,
    ) -> Result<(), CommandError> {
        self.on_faces(node, faces, |m, fs| {
            modeling::dissolve_faces(m, fs).map(drop)
        })
    }

    pub(super) fn flip_normals(&mut self, node: &NodeRef) -> Result<(), CommandError> {
        self.model(node, |m| {
            modeling::flip_normals(m);
            Ok(())
        })
    }

    pub(super) fn recalculate_normals(&mut self, node: &NodeRef) -> Result<(), CommandError> {
        self.model(node, |m| {
            if !modeling::recalculate_normals_outward(m) {
                return Err(EditError::AlreadyOutwards.into());
            }
            Ok(())
        })
    }

    pub(super) fn make_holes(
        &mut self,
        node: &NodeRef,
        faces: &FaceSet,
    ) -> Result<(), CommandError> {
        self.on_faces(node, faces, modeling::make_holes)
    }

    pub(super) fn fill_holes(
        &mut self,
        node: &NodeRef,
        edges: &EdgeSet,
    ) -> Result<(), CommandError> {
        self.on_edges(node, edges, |m, es| modeling::fill_holes(m, es).map(drop))
    }

    pub(super) fn collapse_edges(
        &mut self,
        node: &NodeRef,
        edges: &EdgeSet,
    ) -> Result<(), CommandError> {
        self.on_edges(node, edges, |m, es| {
            modeling::collapse_edges(m, es).map(drop)
        })
    }

    pub(super) fn extrude_edges(
        &mut self,
        node: &NodeRef,
        edges: &EdgeSet,
        offset: DVec3,
    ) -> Result<(), CommandError> {
        self.on_edges(node, edges, |m, es| {
            modeling::extrude_boundary_edges(m, es, offset).map(drop)
        })
    }

    pub(super) fn mirror_vertices(
        &mut self,
        node: &NodeRef,
        vertices: &VertexSet,
        axis: MirrorAxis,
    ) -> Result<(), CommandError> {
        self.on_vertices(node, vertices, |m, vs| {
            modeling::mirror_vertices(m, vs, axis)
        })
    }

    pub(super) fn symmetrize(
        &mut self,
        node: &NodeRef,
        axis: MirrorAxis,
    ) -> Result<(), CommandError> {
        self.model(node, |m| Ok(modeling::symmetrize(m, axis)?))
    }

    pub(super) fn slide_edges(
        &mut self,
        node: &NodeRef,
        edges: &EdgeSet,
        factor: f64,
    ) -> Result<(), CommandError> {
        self.on_edges(node, edges, |m, es| modeling::slide_edges(m, es, factor))
    }

    pub(super) fn bevel_edges(
        &mut self,
        node: &NodeRef,
        edges: &EdgeSet,
        width: f64,
        segments: u32,
    ) -> Result<(), CommandError> {
        // The bevel's strips and corner patches become the created faces
        // (the tool selects them).
        let mut made = Vec::new();
        self.on_edges(node, edges, |m, es| {
            modeling::bevel_edges(m, es, width, segments).map(|f| made = f)
        })?;
        self.created_faces = made;
        Ok(())
    }

    pub(super) fn bevel_vertices(
        &mut self,
        node: &NodeRef,
        vertices: &VertexSet,
        width: f64,
    ) -> Result<(), CommandError> {
        self.on_vertices(node, vertices, |m, vs| {
            modeling::bevel_vertices(m, vs, width).map(drop)
        })
    }

    pub(super) fn delete_faces(
        &mut self,
        node: &NodeRef,
        faces: &FaceSet,
    ) -> Result<(), CommandError> {
        self.on_faces(node, faces, modeling::delete_faces)
    }

    /// Deletes edges with the faces around them.
    pub(super) fn delete_edges(
        &mut self,
        node: &NodeRef,
        edges: &EdgeSet,
    ) -> Result<(), CommandError> {
        self.on_edges(node, edges, |m, es| {
            let fs = modeling::faces_around_edges(m, es);
            modeling::delete_faces(m, &fs)
        })
    }

    /// Deletes vertices with the faces around them.
    pub(super) fn delete_vertices(
        &mut self,
        node: &NodeRef,
        vertices: &VertexSet,
    ) -> Result<(), CommandError> {
        self.on_vertices(node, vertices, |m, vs| {
            let fs = modeling::faces_around_vertices(m, vs);
            modeling::delete_faces(m, &fs)
        })
    }

    pub(super) fn merge_vertices(
        &mut self,
        node: &NodeRef,
        vertices: &VertexSet,
        at: MergePoint,
    ) -> Result<(), CommandError> {
        self.on_vertices(node, vertices, |m, vs| {
            modeling::merge_vertices(m, vs, at).map(drop)
        })
    }

    pub(super) fn merge_by_distance(
        &mut self,
        node: &NodeRef,
        vertices: &VertexSet,
        distance: f64,
    ) -> Result<(), CommandError> {
        self.on_vertices(node, vertices, |m, vs| {
            modeling::merge_by_distance(m, vs, distance).map(drop)
        })
    }

    pub(super) fn bridge_loops(
        &mut self,
        node: &NodeRef,
        edges: &EdgeSet,
    ) -> Result<(), CommandError> {
        self.on_edges(node, edges, |m, es| modeling::bridge_loops(m, es).map(drop))
    }
}

impl Plan<'_> {
    /// Decides a command of the mesh modeling family (the variants
    /// [`Family::Mesh`](super::plan::Family::Mesh) names; [`Plan::run`] sends only those here).
    pub(super) fn run_mesh_command(&mut self, cmd: &Command) -> Result<(), CommandError> {
        match cmd {
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
            _ => unreachable!("not a command of the mesh modeling family"),
        }
    }
}
