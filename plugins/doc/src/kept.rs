//! Meshes kept as they came (issue 37): polygon meshes that a half-edge
//! mesh cannot hold — an edge in three or more faces, a vertex where
//! separate fans meet, a face that visits a vertex twice — stored as face
//! vertex lists, exactly as the file gave them. They are drawn, moved,
//! saved, undone, subdivided (by OpenSubdiv's rules for such places,
//! [`hedra_geom::Refiner::from_polygons`]) and exported; editing their
//! elements needs [`KeptMesh::repaired`] (Mesh ▸ Make Manifold), which
//! turns them into a half-edge mesh with the import repair.

use crate::scene::{Shading, SubdivisionModifier};
use glam::DVec3;
use hedra_geom::subdivision::{NonManifoldPlaces, non_manifold_places};
use hedra_geom::{BuildError, HalfEdgeMesh, Refiner, RepairReport, SubdivisionError};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// Positions and faces as vertex lists, nothing else: the form every
/// polygon file has.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct KeptMesh {
    /// Vertex positions in the node's local space.
    pub positions: Vec<DVec3>,
    /// Faces as counter-clockwise vertex lists (indices into `positions`),
    /// each of three or more corners.
    pub faces: Vec<Vec<u32>>,
}

/// Why a face list cannot be kept.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum KeptMeshError {
    /// A face of fewer than three corners.
    #[error("face {face} has {corners} corner(s); a face needs at least 3")]
    TooFewCorners {
        /// The face's index in the list.
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// A face names a vertex past the end of the positions.
    #[error("face {face} refers to vertex {vertex}, but there are only {vertex_count} vertices")]
    NoSuchVertex {
        /// The face's index in the list.
        face: usize,
        /// The index it names.
        vertex: u32,
        /// The number of positions.
        vertex_count: usize,
    },
    /// A position that is not a finite number.
    #[error("vertex {vertex} is not a finite point")]
    NotFinite {
        /// The vertex index.
        vertex: usize,
    },
}

impl KeptMesh {
    /// A kept mesh of these faces.
    ///
    /// # Errors
    /// [`KeptMeshError`] naming the first face with fewer than three
    /// corners or an index out of range, or a non-finite position.
    pub fn new(positions: Vec<DVec3>, faces: Vec<Vec<u32>>) -> Result<Self, KeptMeshError> {
        let mesh = KeptMesh { positions, faces };
        mesh.check()?;
        Ok(mesh)
    }

    /// Checks what [`new`](Self::new) checks (for a mesh read from a file).
    ///
    /// # Errors
    /// As [`new`](Self::new).
    pub fn check(&self) -> Result<(), KeptMeshError> {
        if let Some(vertex) = self.positions.iter().position(|p| !p.is_finite()) {
            return Err(KeptMeshError::NotFinite { vertex });
        }
        for (face, f) in self.faces.iter().enumerate() {
            if f.len() < 3 {
                return Err(KeptMeshError::TooFewCorners {
                    face,
                    corners: f.len(),
                });
            }
            if let Some(&vertex) = f.iter().find(|&&v| v as usize >= self.positions.len()) {
                return Err(KeptMeshError::NoSuchVertex {
                    face,
                    vertex,
                    vertex_count: self.positions.len(),
                });
            }
        }
        Ok(())
    }

    /// Where the faces are not manifold (empty when a half-edge mesh can
    /// hold them): OpenSubdiv's analysis, [`non_manifold_places`].
    pub fn places(&self) -> NonManifoldPlaces {
        non_manifold_places(self.positions.len(), &self.faces)
            .expect("a kept mesh's faces have three or more corners in range")
    }

    /// The mesh made manifold by the import repair
    /// ([`HalfEdgeMesh::from_polygons_repaired`]): faces on a crowded edge
    /// after the first two are dropped, faces run the wrong way are
    /// dropped, split fans get their own vertex copies, a face that visits
    /// a vertex twice is split there. The report says what changed.
    ///
    /// # Errors
    /// [`BuildError`] when no face can be kept.
    pub fn repaired(&self) -> Result<(HalfEdgeMesh, RepairReport), BuildError> {
        HalfEdgeMesh::from_polygons_repaired(&self.positions, &self.faces)
    }

    /// Positions and faces after `levels` steps of subdivision by
    /// OpenSubdiv's rules (non-manifold edges and vertices infinitely
    /// sharp), the faces OpenSubdiv hides (holes, and the boundary faces
    /// of the `None` boundary rule) left out.
    ///
    /// # Errors
    /// As [`Refiner::from_polygons`] (Loop on faces that are not triangles,
    /// too many faces).
    pub fn subdivided(
        &self,
        options: hedra_geom::SubdivisionOptions,
        levels: u32,
    ) -> Result<KeptMesh, SubdivisionError> {
        if levels == 0 {
            return Ok(self.clone());
        }
        let refiner = Refiner::from_polygons(self.positions.len(), &self.faces, options, levels)?;
        let positions = refiner.refine(&self.positions);
        let faces = (0..refiner.face_count())
            .filter(|&f| !refiner.is_face_hidden(f))
            .map(|f| refiner.face(f).to_vec())
            .collect();
        Ok(KeptMesh { positions, faces })
    }

    /// The number of corners of all faces.
    pub fn corner_count(&self) -> usize {
        self.faces.iter().map(Vec::len).sum()
    }

    /// The triangles the faces are drawn and exported as (each face ear
    /// clipped, [`hedra_geom::query::triangulate_polygon_into`]), as vertex
    /// indices, face after face.
    pub fn triangles(&self) -> Vec<[u32; 3]> {
        let mut out = Vec::with_capacity(self.corner_count());
        let (mut points, mut tris) = (Vec::new(), Vec::new());
        for f in &self.faces {
            points.clear();
            points.extend(f.iter().map(|&v| self.positions[v as usize]));
            tris.clear();
            hedra_geom::query::triangulate_polygon_into(&points, &mut tris);
            out.extend(tris.iter().map(|t| t.map(|i| f[i])));
        }
        out
    }

    /// The ray parameter of the nearest hit on the faces' triangles (from
    /// either side), for picking.
    pub fn ray_cast(&self, origin: DVec3, dir: DVec3) -> Option<f64> {
        self.triangles()
            .iter()
            .filter_map(|t| {
                let [a, b, c] = t.map(|v| self.positions[v as usize]);
                hedra_geom::query::ray_triangle(origin, dir, a, b, c)
            })
            .min_by(f64::total_cmp)
    }

    /// The smallest box around the points the faces use; `None` without
    /// faces.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        self.faces
            .iter()
            .flatten()
            .map(|&v| self.positions[v as usize])
            .fold(None, |acc, p| {
                Some(acc.map_or((p, p), |(lo, hi): (DVec3, DVec3)| (lo.min(p), hi.max(p))))
            })
    }

    /// The Newell normal of face `f`, of unit length (zero for a face
    /// without area).
    pub fn face_normal(&self, f: usize) -> DVec3 {
        let face = &self.faces[f];
        let p = |i: usize| self.positions[face[i % face.len()] as usize];
        (0..face.len())
            .map(|i| p(i).cross(p(i + 1)))
            .sum::<DVec3>()
            .normalize_or_zero()
    }
}

/// Where a kept mesh is not manifold, in words, one line per kind of
/// place naming at most `limit` of them ("1 edge(s) in 3 or more faces:
/// 3–7 (3 faces)"); `vertex` and `face` name a vertex and a face index as
/// the user counts them (a file's numbers, or the node's from 0). Empty
/// when the mesh is manifold.
pub fn describe_places(
    places: &NonManifoldPlaces,
    limit: usize,
    vertex: &dyn Fn(u32) -> String,
    face: &dyn Fn(usize) -> String,
) -> Vec<String> {
    fn listed<T>(items: &[T], limit: usize, each: impl Fn(&T) -> String) -> String {
        let mut text: Vec<String> = items.iter().take(limit).map(each).collect();
        if items.len() > limit {
            text.push(format!("… {} more", items.len() - limit));
        }
        text.join(", ")
    }
    let mut out = Vec::new();
    if !places.crowded_edges.is_empty() {
        out.push(format!(
            "{} edge(s) in 3 or more faces: {}",
            places.crowded_edges.len(),
            listed(&places.crowded_edges, limit, |([a, b], n)| format!(
                "{}–{} ({n} faces)",
                vertex(*a),
                vertex(*b)
            ))
        ));
    }
    if !places.same_way_edges.is_empty() {
        out.push(format!(
            "{} edge(s) two faces run the same way (orientations disagree): {}",
            places.same_way_edges.len(),
            listed(&places.same_way_edges, limit, |[a, b]| format!(
                "{}→{}",
                vertex(*a),
                vertex(*b)
            ))
        ));
    }
    if !places.split_vertices.is_empty() {
        out.push(format!(
            "{} vertex(es) where separate fans of faces meet: {}",
            places.split_vertices.len(),
            listed(&places.split_vertices, limit, |v| vertex(*v))
        ));
    }
    if !places.repeating_faces.is_empty() {
        out.push(format!(
            "{} face(s) that visit a vertex twice: {}",
            places.repeating_faces.len(),
            listed(&places.repeating_faces, limit, |f| face(*f))
        ));
    }
    out
}

/// A node holding a kept mesh: the faces (shared between history steps),
/// how they are shaded and the subdivision they are shown and exported
/// with.
#[derive(Clone, Debug, PartialEq)]
pub struct KeptMeshContent {
    /// The faces, in the node's local space.
    pub mesh: Arc<KeptMesh>,
    /// Flat or smooth normals when drawn and exported.
    pub shading: Shading,
    /// Subdivision shown in the viewport and written by export (OpenSubdiv's
    /// rules at the non-manifold places).
    pub subdivision: Option<SubdivisionModifier>,
}

impl KeptMeshContent {
    /// Flat shaded, not subdivided.
    pub fn new(mesh: Arc<KeptMesh>) -> Self {
        KeptMeshContent {
            mesh,
            shading: Shading::Flat,
            subdivision: None,
        }
    }

    /// The faces subdivided at `level` (the cage at level 0), with the
    /// modifier's options (the default ones when it has none).
    ///
    /// # Errors
    /// As [`KeptMesh::subdivided`].
    pub fn at_level(&self, level: u32) -> Result<std::borrow::Cow<'_, KeptMesh>, SubdivisionError> {
        if level == 0 {
            return Ok(std::borrow::Cow::Borrowed(&self.mesh));
        }
        let options = self.subdivision.map(|m| m.options).unwrap_or_default();
        Ok(std::borrow::Cow::Owned(
            self.mesh.subdivided(options, level)?,
        ))
    }
}
