//! Subdivided meshes written straight from the refiner's faces (issue 36,
//! item 2): OBJ, STL, glTF and the written counts of a Catmull-Clark or
//! Loop subdivision, without a half-edge mesh built for them.

use super::pieces::write_pieces_in_order;
use super::{
    ExportError, ExportOutput, ExportShape, Geometry, WrittenCounts, stl_record, stl_triangle,
};
use crate::scene::{Node, NodeContent};
use glam::DVec3;
use hedra_geom::HalfEdgeMesh;
use hedra_geom::subdivision::{Creases, Refiner, Scheme};

/// Refined faces per piece of work made on all cores (STL records,
/// glTF arrays).
pub(crate) const FACES_PER_PIECE: usize = 1 << 14;

/// Written vertices per piece of work made on all cores.
pub(crate) const VERTICES_PER_PIECE: usize = 1 << 15;

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

    /// How many pieces of [`FACES_PER_PIECE`] faces (hidden ones
    /// included) the faces are cut into, for work on all cores.
    pub(crate) fn piece_count(&self) -> usize {
        self.refiner.face_count().div_ceil(FACES_PER_PIECE)
    }

    /// The shown faces of `piece`, in [`faces`](Self::faces) order.
    fn piece_faces(&self, piece: usize) -> impl Iterator<Item = &[u32]> + '_ {
        let end = ((piece + 1) * FACES_PER_PIECE).min(self.refiner.face_count());
        (piece * FACES_PER_PIECE..end)
            .filter(|&f| !self.refiner.is_face_hidden(f))
            .map(|f| self.refiner.face(f))
    }

    /// The number of the first flat corner of each piece (the corners of
    /// the shown faces before it), and the number of all corners last.
    pub(crate) fn piece_corner_starts(&self) -> Vec<u32> {
        use rayon::prelude::*;
        let counts: Vec<u32> = (0..self.piece_count())
            .into_par_iter()
            .map(|p| self.piece_faces(p).map(|f| f.len() as u32).sum())
            .collect();
        let mut starts = Vec::with_capacity(counts.len() + 1);
        let mut start = 0u32;
        starts.push(0);
        for count in counts {
            start += count;
            starts.push(start);
        }
        starts
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
        let piece_records = |piece: usize, bytes: &mut Vec<u8>| {
            bytes.reserve(2 * 50 * FACES_PER_PIECE);
            for face in self.piece_faces(piece) {
                let (triangles, count) = self.face_triangles(face);
                for t in &triangles[..count] {
                    let corners =
                        t.map(|k| world.transform_point3(self.positions[face[k] as usize]));
                    let (normal, corners) = stl_triangle(corners, mirrored);
                    bytes.extend_from_slice(&stl_record(normal, corners));
                }
            }
        };
        let written = write_pieces_in_order(self.piece_count(), &piece_records, out)?;
        Ok((written / 50) as u32)
    }

    /// The OBJ `v` and `f` lines of these faces (the written vertices
    /// numbered from `base`), made in pieces on all cores and written in
    /// order: the lines `write_obj` makes one by one for a small mesh.
    pub(super) fn write_obj_lines(
        &self,
        world: glam::DMat4,
        mirrored: bool,
        base: usize,
        out: &mut dyn ExportOutput,
    ) -> std::io::Result<()> {
        let vertex_lines = |piece: usize, bytes: &mut Vec<u8>| {
            let (mut text, mut numbers) = (String::new(), super::Numbers::default());
            let end = ((piece + 1) * VERTICES_PER_PIECE).min(self.order.len());
            for &v in &self.order[piece * VERTICES_PER_PIECE..end] {
                let p = world.transform_point3(self.positions[v as usize]);
                super::obj_vertex_line(&mut text, &mut numbers, p);
            }
            bytes.extend_from_slice(text.as_bytes());
        };
        write_pieces_in_order(
            self.order.len().div_ceil(VERTICES_PER_PIECE),
            &vertex_lines,
            out,
        )?;
        let face_lines = |piece: usize, bytes: &mut Vec<u8>| {
            let (mut text, mut numbers, mut vs) =
                (String::new(), super::Numbers::default(), Vec::new());
            for face in self.piece_faces(piece) {
                vs.clear();
                vs.extend(
                    face.iter()
                        .map(|&v| base + self.number[v as usize] as usize),
                );
                super::obj_face_line(&mut text, &mut numbers, &mut vs, mirrored);
            }
            bytes.extend_from_slice(text.as_bytes());
        };
        write_pieces_in_order(self.piece_count(), &face_lines, out)?;
        Ok(())
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

    /// Triangles of all faces.
    pub(crate) fn triangle_count(&self) -> usize {
        self.refiner.faces().map(|f| f.len() - 2).sum()
    }

    /// The positions of written vertices `range`, as glTF stores them.
    pub(crate) fn written_positions_f32(
        &self,
        range: std::ops::Range<usize>,
        mut visit: impl FnMut([f32; 3]),
    ) {
        for &v in &self.order[range] {
            visit(self.positions[v as usize].as_vec3().to_array());
        }
    }

    /// The bounds of the written positions as glTF stores them (its
    /// accessor's `min` and `max`), found on all cores.
    pub(crate) fn written_bounds(&self) -> ([f32; 3], [f32; 3]) {
        use rayon::prelude::*;
        let empty = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        self.order
            .par_chunks(VERTICES_PER_PIECE)
            .map(|chunk| {
                let (mut lo, mut hi) = empty;
                for &v in chunk {
                    let p = self.positions[v as usize].as_vec3().to_array();
                    for k in 0..3 {
                        lo[k] = lo[k].min(p[k]);
                        hi[k] = hi[k].max(p[k]);
                    }
                }
                (lo, hi)
            })
            .reduce(
                || empty,
                |(a, b), (c, d)| {
                    (
                        std::array::from_fn(|k| a[k].min(c[k])),
                        std::array::from_fn(|k| b[k].max(d[k])),
                    )
                },
            )
    }

    /// True when every face has a normal: flat glTF can be written from
    /// the faces (else the mesh's neighbours stand in).
    pub(crate) fn faces_have_normals(&self) -> bool {
        use rayon::prelude::*;
        (0..self.piece_count()).into_par_iter().all(|p| {
            self.piece_faces(p)
                .all(|f| self.area_vector(f).try_normalize().is_some())
        })
    }

    /// Flat glTF vertices of `piece`, as `gltf::mesh_triangles` makes them
    /// from the subdivided mesh: each face's corners with its unit normal,
    /// face by face. Call when [`faces_have_normals`](Self::faces_have_normals).
    pub(crate) fn piece_flat_corners(
        &self,
        piece: usize,
        mut visit: impl FnMut([f32; 3], [f32; 3]),
    ) {
        for face in self.piece_faces(piece) {
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

    /// The triangles' corners of `piece` as glTF indices: into the flat
    /// corners ([`piece_flat_corners`](Self::piece_flat_corners)), numbered
    /// from `first_corner` (the piece's entry of
    /// [`piece_corner_starts`](Self::piece_corner_starts)), or into the
    /// written vertices when `smooth`.
    pub(crate) fn piece_triangle_indices(
        &self,
        piece: usize,
        smooth: bool,
        first_corner: u32,
        mut visit: impl FnMut(u32),
    ) {
        let mut base = first_corner;
        for face in self.piece_faces(piece) {
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
