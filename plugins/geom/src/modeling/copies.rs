//! Meshes built from transformed copies of another mesh, with some vertices
//! of neighbouring copies welded: what the Mirror and Array modifiers
//! ([`mirrored`](super::mirrored), [`arrayed`](super::arrayed)) share.
//!
//! The copies are gathered as an indexed face set (a "polygon soup" of
//! positions and vertex index lists, seed 000's indexed storage), the
//! welds applied as an index remap, and the result built once with the
//! strict [`HalfEdgeMesh::from_polygons`], which refuses anything
//! non-manifold. Every result vertex and face remembers the source element
//! it is a copy of ([`CopiedMesh`]), so that creases and corner attributes of
//! the source can follow (the source's ids are never reused by the result's
//! copies, so only this map ties them together).

use super::{InvalidResult, ModelingError};
use crate::ids::{FaceId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;
use crate::subdivision::Creases;
use glam::DVec3;

/// A mesh built from copies of a source mesh, with the source element each
/// of its vertices, faces and face corners was copied from.
#[derive(Clone, Debug, PartialEq)]
pub struct CopiedMesh {
    /// The result (dense ids: vertex `i` is `VertexId(i)`, face `j` is
    /// `FaceId(j)`).
    pub mesh: HalfEdgeMesh,
    /// The source vertex of each result vertex, by result vertex index. A
    /// welded vertex names the source vertex of the earliest copy.
    pub vertex_origin: Vec<VertexId>,
    /// The source face of each result face, by result face index.
    pub face_origin: Vec<FaceId>,
    /// Each result face's corners as (result vertex, source vertex) pairs,
    /// in the face's order. Welding joins vertices, never corners, so this
    /// keeps what `vertex_origin` loses: which source vertex each copy's
    /// corner came from.
    pub corner_origin: Vec<Vec<(VertexId, VertexId)>>,
}

impl CopiedMesh {
    /// The source vertex result vertex `v` is a copy of (for a welded
    /// vertex, its earliest copy's).
    pub fn vertex_source(&self, v: VertexId) -> VertexId {
        self.vertex_origin[v.index()]
    }

    /// The source face result face `f` is a copy of.
    pub fn face_source(&self, f: FaceId) -> FaceId {
        self.face_origin[f.index()]
    }

    /// The source corner (the half-edge of the source face leaving the
    /// source vertex) that result corner `h` (a half-edge with a face) is a
    /// copy of; `None` for a boundary half-edge. A mirrored copy runs its
    /// face backwards, but each corner still sits at the copy of the same
    /// vertex in the copy of the same face, which is what this finds.
    pub fn corner_source(&self, source: &HalfEdgeMesh, h: HalfEdgeId) -> Option<HalfEdgeId> {
        let f = self.mesh.face(h)?;
        let v = self.mesh.origin(h);
        let (_, sv) = *self.corner_origin[f.index()]
            .iter()
            .find(|(r, _)| *r == v)?;
        let sf = self.face_source(f);
        source.face_halfedges(sf).find(|&s| source.origin(s) == sv)
    }

    /// The source's creases carried to every copy: each edge of a copied
    /// face gets the sharpness of the source edge it copies; a vertex the
    /// largest corner sharpness of the source vertices welded into it; a
    /// copy of a hole is a hole.
    pub fn creases(&self, source: &HalfEdgeMesh, creases: &Creases) -> Creases {
        let mut out = Creases::default();
        if creases.is_empty() {
            return out;
        }
        for (j, f) in self.face_origin.iter().enumerate() {
            if creases.is_hole(*f) {
                out.set_hole(FaceId(j as u32), true);
            }
        }
        for corners in &self.corner_origin {
            for (k, &(a, sa)) in corners.iter().enumerate() {
                let (b, sb) = corners[(k + 1) % corners.len()];
                let sharpness = source.find_edge(sa, sb).map_or(0.0, |se| creases.edge(se));
                if let Some(e) = self.mesh.find_edge(a, b)
                    && sharpness > out.edge(e)
                {
                    out.set_edge(e, sharpness);
                }
                if creases.vertex(sa) > out.vertex(a) {
                    out.set_vertex(a, creases.vertex(sa));
                }
            }
        }
        out
    }
}

/// An indexed face set with the source vertex and face of every entry.
#[derive(Clone, Debug, Default)]
pub(super) struct Soup {
    pub positions: Vec<DVec3>,
    pub vertex_origin: Vec<VertexId>,
    pub polygons: Vec<Vec<u32>>,
    pub face_origin: Vec<FaceId>,
    /// The source vertex of each polygon corner, in the polygon's order.
    pub corner_origin: Vec<Vec<VertexId>>,
}

impl Soup {
    /// The source mesh's faces as a soup, or why it cannot be copied.
    ///
    /// # Errors
    /// [`ModelingError::Empty`] for a mesh without faces;
    /// [`ModelingError::Parameter`] for a face with inner rings (its
    /// holes would be lost).
    pub fn of(mesh: &HalfEdgeMesh) -> Result<Soup, ModelingError> {
        if mesh.face_count() == 0 {
            return Err(ModelingError::Empty("no faces"));
        }
        if let Some(f) = mesh.first_non_polygon_face() {
            return Err(ModelingError::Parameter {
                what: "mesh",
                allowed: "made of faces without inner rings",
                value: format!("{f} has a ring or no edges"),
            });
        }
        let mut index = vec![u32::MAX; mesh.vertex_capacity()];
        let mut soup = Soup::default();
        for v in mesh.vertices().filter(|&v| !mesh.is_isolated_vertex(v)) {
            index[v.index()] = soup.positions.len() as u32;
            soup.positions.push(mesh.position(v));
            soup.vertex_origin.push(v);
        }
        for f in mesh.faces() {
            soup.polygons
                .push(mesh.face_vertices(f).map(|v| index[v.index()]).collect());
            soup.corner_origin.push(mesh.face_vertices(f).collect());
            soup.face_origin.push(f);
        }
        Ok(soup)
    }

    /// Appends a copy of the first `n_vertices`/`n_faces` entries with
    /// positions mapped by `map`, faces reversed when `reverse` (a
    /// reflection turns orientation around). Returns the index of the
    /// copy's first vertex.
    pub fn append_copy(
        &mut self,
        n_vertices: usize,
        n_faces: usize,
        map: impl Fn(DVec3) -> DVec3,
        reverse: bool,
    ) -> u32 {
        let base = self.positions.len() as u32;
        for i in 0..n_vertices {
            self.positions.push(map(self.positions[i]));
            self.vertex_origin.push(self.vertex_origin[i]);
        }
        for j in 0..n_faces {
            let mut p: Vec<u32> = self.polygons[j].iter().map(|&i| i + base).collect();
            let mut c = self.corner_origin[j].clone();
            if reverse {
                p.reverse();
                c.reverse();
            }
            self.polygons.push(p);
            self.corner_origin.push(c);
            self.face_origin.push(self.face_origin[j]);
        }
        base
    }

    /// Applies welds: `rep[i]` is the vertex `i` becomes (itself when not
    /// welded; a vertex a weld keeps must map to itself). Unused vertices
    /// are dropped and the rest renumbered in order.
    pub fn weld(&mut self, rep: &[u32]) {
        let mut new_index = vec![u32::MAX; self.positions.len()];
        let mut positions = Vec::new();
        let mut origin = Vec::new();
        for (i, &r) in rep.iter().enumerate() {
            if r as usize == i {
                new_index[i] = positions.len() as u32;
                positions.push(self.positions[i]);
                origin.push(self.vertex_origin[i]);
            }
        }
        for p in &mut self.polygons {
            for i in p.iter_mut() {
                *i = new_index[rep[*i as usize] as usize];
            }
        }
        self.positions = positions;
        self.vertex_origin = origin;
    }

    /// Builds the mesh.
    ///
    /// # Errors
    /// [`ModelingError::Invalid`] with [`InvalidResult::Copies`] when the
    /// welded copies do not form a manifold, consistently oriented surface.
    pub fn build(self, operation: &'static str) -> Result<CopiedMesh, ModelingError> {
        let mesh = HalfEdgeMesh::from_polygons(&self.positions, &self.polygons)
            .map_err(|error| InvalidResult::Copies { operation, error })?;
        mesh.validate()?;
        let corner_origin = self
            .polygons
            .iter()
            .zip(&self.corner_origin)
            .map(|(p, c)| {
                p.iter()
                    .map(|&i| VertexId(i))
                    .zip(c.iter().copied())
                    .collect()
            })
            .collect();
        Ok(CopiedMesh {
            mesh,
            vertex_origin: self.vertex_origin,
            face_origin: self.face_origin,
            corner_origin,
        })
    }
}

/// Union-find root with path halving.
pub(super) fn root(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        parent[i as usize] = parent[parent[i as usize] as usize];
        i = parent[i as usize];
    }
    i
}

/// Joins the sets of `a` and `b`, the smaller index staying the root (so the
/// earlier copy's vertex is the one kept).
pub(super) fn join(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (root(parent, a), root(parent, b));
    parent[ra.max(rb) as usize] = ra.min(rb);
}

/// Checks a merge distance: finite and ≥ 0.
pub(super) fn check_distance(distance: f64) -> Result<(), ModelingError> {
    if distance.is_finite() && distance >= 0.0 {
        Ok(())
    } else {
        Err(ModelingError::Parameter {
            what: "merge distance",
            allowed: "a finite distance ≥ 0",
            value: distance.to_string(),
        })
    }
}
