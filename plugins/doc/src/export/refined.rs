//! Subdivided meshes written straight from the refiner's faces (issue 36,
//! item 2): OBJ, STL, glTF and the written counts of a Catmull-Clark or
//! Loop subdivision, without a half-edge mesh built for them.

use super::{
    ExportError, ExportOutput, ExportShape, Geometry, WrittenCounts, stl_record, stl_triangle,
};
use crate::scene::{Node, NodeContent};
use glam::DVec3;
use hedra_geom::HalfEdgeMesh;
use hedra_geom::subdivision::{Creases, Refiner, Scheme};

/// A mesh subdivided by Catmull-Clark or Loop for export, kept as the
/// refiner's faces (all quads or all triangles) and positions instead of
/// being built into a half-edge mesh, which an 8M-triangle export does not
/// need and which took most of its time and memory (issue 36, item 2).
/// Writes the same vertices (numbered as [`Refiner::to_mesh`] numbers
/// them), faces and triangles ([`hedra_geom::query::triangulate_quad`])
/// as the mesh would.
pub(crate) struct RefinedFaces {
    pub(super) refiner: Refiner,
    /// Refined positions, in the refiner's order.
    positions: Vec<DVec3>,
    /// The written vertices as refined indices, in the mesh's order.
    pub(super) order: Vec<u32>,
    /// Each refined vertex's written number (`u32::MAX`: not written).
    number: Vec<u32>,
}

impl RefinedFaces {
    /// `content` subdivided `level` times when its subdivision can be
    /// written this way: the last step of its stack (the default), by
    /// Catmull-Clark or Loop. `None` otherwise (the caller evaluates the
    /// mesh).
    pub(super) fn of(
        content: &crate::scene::MeshContent,
        level: u32,
    ) -> Result<Option<Self>, crate::EvaluationError> {
        let options = content.subdivision.unwrap_or_default().options;
        if level == 0 || !matches!(options.scheme, Scheme::CatmullClark | Scheme::Loop) {
            return Ok(None);
        }
        let Some(cage) = content.smooth_cage()? else {
            return Ok(None);
        };
        let refiner = Refiner::new(&cage.mesh, &cage.creases, options, level)?;
        let positions = refiner.refine(&refiner.cage_positions(&cage.mesh));
        let (order, number) = refiner.mesh_vertex_order();
        Ok(Some(RefinedFaces {
            refiner,
            positions,
            order,
            number,
        }))
    }

    /// The written vertices' positions, in order.
    pub(super) fn written_positions(&self) -> impl Iterator<Item = DVec3> + '_ {
        self.order.iter().map(|&v| self.positions[v as usize])
    }

    /// The faces as written vertex numbers.
    pub(super) fn faces(&self) -> impl Iterator<Item = impl Iterator<Item = u32> + '_> + '_ {
        self.refiner
            .faces()
            .map(|f| f.iter().map(|&v| self.number[v as usize]))
    }

    /// The triangles of a refined face (a triangle or a quad) as corner
    /// indices, as [`hedra_geom::query::triangulate_face`] splits the
    /// mesh's: the first `count` of the pair.
    pub(super) fn face_triangles(&self, face: &[u32]) -> ([[usize; 3]; 2], usize) {
        match *face {
            [a, b, c, d] => {
                let corners = [a, b, c, d];
                let two_edged = corners.map(|v| self.refiner.vertex_edge_count(v) == 2);
                let at = |v: u32| self.positions[v as usize];
                (
                    hedra_geom::query::triangulate_quad(corners.map(at), two_edged),
                    2,
                )
            }
            [_, _, _] => ([[0, 1, 2], [0, 1, 2]], 1),
            // Never made: Catmull-Clark gives quads, Loop triangles.
            _ => unreachable!("a refined face of {} sides", face.len()),
        }
    }

    /// Writes the binary STL records of the triangles in world space
    /// (`world`, `mirrored` as [`stl_triangle`] takes them), face by face
    /// as [`each_triangle`](Self::each_triangle) visits them, made in
    /// pieces on all cores and written in order. Returns how many.
    pub(super) fn write_stl_records(
        &self,
        world: glam::DMat4,
        mirrored: bool,
        out: &mut dyn ExportOutput,
    ) -> std::io::Result<u32> {
        use rayon::prelude::*;
        const FACES_PER_PIECE: usize = 1 << 14;
        let faces = self.refiner.face_count();
        let pieces: Vec<usize> = (0..faces.div_ceil(FACES_PER_PIECE)).collect();
        let piece_records = |piece: usize| {
            let faces = piece * FACES_PER_PIECE..((piece + 1) * FACES_PER_PIECE).min(faces);
            let mut bytes = Vec::with_capacity(2 * 50 * faces.len());
            for f in faces.filter(|&f| !self.refiner.is_face_hidden(f)) {
                let face = self.refiner.face(f);
                let (triangles, count) = self.face_triangles(face);
                for t in &triangles[..count] {
                    let corners =
                        t.map(|k| world.transform_point3(self.positions[face[k] as usize]));
                    let (normal, corners) = stl_triangle(corners, mirrored);
                    bytes.extend_from_slice(&stl_record(normal, corners));
                }
            }
            bytes
        };
        let mut count = 0u32;
        // A few pieces per thread at a time, so that little is held.
        for batch in pieces.chunks(2 * rayon::current_num_threads()) {
            let made: Vec<Vec<u8>> = batch.par_iter().map(|&p| piece_records(p)).collect();
            for bytes in made {
                out.write_all(&bytes)?;
                count += (bytes.len() / 50) as u32;
            }
        }
        Ok(count)
    }

    /// Calls `visit` with the corner positions of every triangle, face by
    /// face.
    pub(super) fn each_triangle(&self, mut visit: impl FnMut([DVec3; 3])) {
        for face in self.refiner.faces() {
            let (triangles, count) = self.face_triangles(face);
            for t in &triangles[..count] {
                visit(t.map(|k| self.positions[face[k] as usize]));
            }
        }
    }

    /// Newell's area vector of a refined face (as
    /// [`HalfEdgeMesh::face_area_vector`] sums it, corner by corner).
    pub(super) fn area_vector(&self, face: &[u32]) -> DVec3 {
        let at = |v: u32| self.positions[v as usize];
        let n = face.len();
        (0..n)
            .map(|i| at(face[i]).cross(at(face[(i + 1) % n])))
            .sum::<DVec3>()
            * 0.5
    }

    /// Written vertices of all faces, corner by corner.
    pub(crate) fn corner_count(&self) -> usize {
        self.refiner.faces().map(<[u32]>::len).sum()
    }

    /// Triangles of all faces.
    pub(crate) fn triangle_count(&self) -> usize {
        self.refiner.faces().map(|f| f.len() - 2).sum()
    }

    /// The written vertices' positions as glTF stores them.
    pub(crate) fn each_position(&self, mut visit: impl FnMut([f32; 3])) {
        self.written_positions()
            .for_each(|p| visit(p.as_vec3().to_array()));
    }

    /// True when every face has a normal: flat glTF can be written from
    /// the faces (else the mesh's neighbours stand in).
    pub(crate) fn faces_have_normals(&self) -> bool {
        self.refiner
            .faces()
            .all(|f| self.area_vector(f).try_normalize().is_some())
    }

    /// Flat glTF vertices, as `gltf::mesh_triangles` makes them from the
    /// subdivided mesh: each face's corners with its unit normal, face by
    /// face. Call when [`faces_have_normals`](Self::faces_have_normals).
    pub(crate) fn each_flat_corner(&self, mut visit: impl FnMut([f32; 3], [f32; 3])) {
        for face in self.refiner.faces() {
            let normal = self
                .area_vector(face)
                .normalize_or_zero()
                .as_vec3()
                .to_array();
            for &v in face {
                visit(self.positions[v as usize].as_vec3().to_array(), normal);
            }
        }
    }

    /// Smooth glTF normals of the written vertices: the area vectors of
    /// the faces around each vertex, summed in face order, as unit
    /// vectors (to 1e-6 of `HalfEdgeMesh::vertex_normal`). `None` where
    /// the mesh is needed: a vertex without a normal, or normals to split
    /// along infinitely sharp edges.
    pub(crate) fn smooth_normals(&self) -> Option<Vec<[f32; 3]>> {
        if self.refiner.has_infinitely_sharp_inner_edge() {
            return None;
        }
        let mut normals = vec![DVec3::ZERO; self.order.len()];
        for face in self.refiner.faces() {
            let area = self.area_vector(face);
            for &v in face {
                normals[self.number[v as usize] as usize] += area;
            }
        }
        normals
            .into_iter()
            .map(|n| n.try_normalize().map(|n| n.as_vec3().to_array()))
            .collect()
    }

    /// The triangles' corners as glTF indices: into the flat corners
    /// ([`each_flat_corner`](Self::each_flat_corner)), or into the written
    /// vertices when `smooth`.
    pub(crate) fn each_triangle_index(&self, smooth: bool, mut visit: impl FnMut(u32)) {
        let mut base = 0u32;
        for face in self.refiner.faces() {
            let (triangles, count) = self.face_triangles(face);
            for t in &triangles[..count] {
                for k in *t {
                    visit(if smooth {
                        self.number[face[k] as usize]
                    } else {
                        base + k as u32
                    });
                }
            }
            base += face.len() as u32;
        }
    }

    /// The half-edge mesh and creases these faces are of (what
    /// [`Refiner::subdivide`] returns), for writers that need adjacency.
    pub(crate) fn to_mesh(&self) -> (HalfEdgeMesh, Creases) {
        self.refiner
            .to_mesh(&self.positions)
            .expect("refining a valid half-edge mesh gives a valid mesh")
    }

    pub(super) fn counts(&self) -> WrittenCounts {
        let faces = self.refiner.faces().count();
        WrittenCounts {
            vertices: self.order.len(),
            faces,
            triangles: self.refiner.faces().map(|f| f.len() - 2).sum(),
        }
    }
}

/// A mesh node's subdivided shape as [`RefinedFaces`], for the writers
/// that take faces as they are (OBJ, STL, the written counts); `None` when
/// the node is not a mesh subdivided that way (the caller uses
/// [`export_geometry`]).
///
/// # Errors
/// As [`node_geometry`].
pub(crate) fn refined_geometry(
    node: &Node,
    shape: ExportShape,
) -> Result<Option<Geometry<'_>>, ExportError> {
    let NodeContent::Mesh(content) = &node.content else {
        return Ok(None);
    };
    let level = match shape {
        ExportShape::Cage => 0,
        ExportShape::Evaluated => content.subdivision.map_or(0, |m| m.export_level),
        ExportShape::Subdivided(level) => level,
    };
    if level == 0 {
        return Ok(None);
    }
    if let Some(face) = content.mesh.first_non_polygon_face() {
        return Err(ExportError::NotPolygon {
            node: node.name.clone(),
            face,
        });
    }
    RefinedFaces::of(content, level)
        .map(|r| r.map(Geometry::Refined))
        .map_err(|error| ExportError::Evaluation {
            node: node.name.clone(),
            error,
        })
}
