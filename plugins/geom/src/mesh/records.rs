//! Whole-record conversions: the stored form [`MeshData`] in and out of
//! a mesh (scene files), and renumbering the records densely (compaction of
//! meshes with rings). Both copy raw records, so they live inside the
//! [`mesh`](super) module.

use super::{HalfEdgeMesh, HalfEdgeRecord, LoopStart, Topology};
use crate::ids::{ElementKind, FaceId, HalfEdgeId, NONE, VertexId};
use crate::validate::ValidationError;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// The stored form of a mesh in scene files: raw records, so that every id
/// survives a save and load. Loading validates the result.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct MeshData {
    /// Vertex positions by vertex id.
    pub positions: Vec<DVec3>,
    /// Outgoing half-edge per vertex id, `-1` for none.
    pub vertex_halfedge: Vec<i64>,
    /// Per half-edge id: `(origin, next, prev, face)`, face `-1` on a boundary.
    pub halfedges: Vec<(u32, u32, u32, i64)>,
    /// One half-edge per face id (of its outer loop); `u32::MAX` for a face
    /// without edges (listed in `lone_vertex_faces`).
    pub face_halfedge: Vec<u32>,
    /// Ids of removed vertices (their slots stay, so ids do not shift).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub dead_vertices: Vec<u32>,
    /// Ids of removed edges.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub dead_edges: Vec<u32>,
    /// Ids of removed faces.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub dead_faces: Vec<u32>,
    /// Inner rings as `(face id, loop starts)`; absent (and the file
    /// unchanged) when no face has a ring.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub face_rings: Vec<(u32, Vec<LoopStart>)>,
    /// Faces without edges as `(face id, lone vertex id)`; absent when none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub lone_vertex_faces: Vec<(u32, u32)>,
}

/// Why stored records do not make a mesh ([`HalfEdgeMesh`]'s
/// `TryFrom<MeshData>`, used when a scene file is loaded).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MeshDataError {
    /// `vertex_halfedge` and `positions` differ in length.
    #[error("mesh has {positions} positions but {records} vertex records")]
    VertexRecords {
        /// Length of `positions`.
        positions: usize,
        /// Length of `vertex_halfedge`.
        records: usize,
    },
    /// Half-edges come in pairs; the list has an odd length.
    #[error("odd number of half-edges ({count})")]
    OddHalfEdges {
        /// Length of `halfedges`.
        count: usize,
    },
    /// A stored reference is neither `-1` nor a 32-bit id.
    #[error("{kind} id {id} is out of range")]
    IdOutOfRange {
        /// What the reference names (a half-edge or a face).
        kind: ElementKind,
        /// The stored value.
        id: i64,
    },
    /// A dead-element list names an id past its array.
    #[error("dead {kind} id {id} is out of range")]
    DeadOutOfRange {
        /// Which list: vertices, edges or faces.
        kind: ElementKind,
        /// The stored id.
        id: u32,
    },
    /// `face_rings` lists a face twice.
    #[error("face {} has two ring lists", .face.0)]
    TwoRingLists {
        /// The face.
        face: FaceId,
    },
    /// `lone_vertex_faces` lists a face twice.
    #[error("face {} has two lone vertices", .face.0)]
    TwoLoneVertices {
        /// The face.
        face: FaceId,
    },
    /// The compact form's lists do not fit together (face starts out of
    /// order, a corner named twice, an edge id left unused, …).
    #[error("the polygon lists do not make a half-edge mesh")]
    Layout,
    /// The records read back but break an invariant (the validator's report).
    #[error(transparent)]
    Invalid(#[from] ValidationError),
}

fn opt_to_i64(x: u32) -> i64 {
    if x == NONE { -1 } else { x as i64 }
}

impl From<HalfEdgeMesh> for MeshData {
    fn from(m: HalfEdgeMesh) -> Self {
        let dead = |d: &[bool]| -> Vec<u32> {
            d.iter()
                .enumerate()
                .filter(|(_, x)| **x)
                .map(|(i, _)| i as u32)
                .collect()
        };
        MeshData {
            vertex_halfedge: m
                .topology
                .vertex_out
                .iter()
                .map(|&x| opt_to_i64(x))
                .collect(),
            halfedges: m
                .topology
                .halfedges
                .iter()
                .map(|r| (r.origin, r.next, r.prev, opt_to_i64(r.face)))
                .collect(),
            face_halfedge: m.topology.face_halfedge.clone(),
            dead_vertices: dead(&m.topology.vertex_dead),
            dead_edges: dead(&m.topology.edge_dead),
            dead_faces: dead(&m.topology.face_dead),
            face_rings: m
                .topology
                .face_rings
                .iter()
                .map(|(f, r)| (f.0, r.clone()))
                .collect(),
            lone_vertex_faces: m
                .topology
                .face_lone_vertex
                .iter()
                .map(|(f, v)| (f.0, v.0))
                .collect(),
            positions: m.positions,
        }
    }
}

impl TryFrom<MeshData> for HalfEdgeMesh {
    type Error = MeshDataError;
    fn try_from(d: MeshData) -> Result<Self, MeshDataError> {
        let nv = d.positions.len();
        if d.vertex_halfedge.len() != nv {
            return Err(MeshDataError::VertexRecords {
                positions: nv,
                records: d.vertex_halfedge.len(),
            });
        }
        if !d.halfedges.len().is_multiple_of(2) {
            return Err(MeshDataError::OddHalfEdges {
                count: d.halfedges.len(),
            });
        }
        let to_raw = |x: i64, kind: ElementKind| -> Result<u32, MeshDataError> {
            if x == -1 {
                Ok(NONE)
            } else if (0..NONE as i64).contains(&x) {
                Ok(x as u32)
            } else {
                Err(MeshDataError::IdOutOfRange { kind, id: x })
            }
        };
        let mut t = Topology {
            vertex_out: d
                .vertex_halfedge
                .iter()
                .map(|&x| to_raw(x, ElementKind::HalfEdge))
                .collect::<Result<_, _>>()?,
            halfedges: d
                .halfedges
                .iter()
                .map(|&(origin, next, prev, face)| {
                    Ok(HalfEdgeRecord {
                        origin,
                        next,
                        prev,
                        face: to_raw(face, ElementKind::Face)?,
                    })
                })
                .collect::<Result<_, MeshDataError>>()?,
            face_halfedge: d.face_halfedge,
            ..Default::default()
        };
        t.vertex_dead = vec![false; nv];
        t.edge_dead = vec![false; t.halfedges.len() / 2];
        t.face_dead = vec![false; t.face_halfedge.len()];
        for (list, flags, kind) in [
            (&d.dead_vertices, &mut t.vertex_dead, ElementKind::Vertex),
            (&d.dead_edges, &mut t.edge_dead, ElementKind::Edge),
            (&d.dead_faces, &mut t.face_dead, ElementKind::Face),
        ] {
            for &i in list {
                *flags
                    .get_mut(i as usize)
                    .ok_or(MeshDataError::DeadOutOfRange { kind, id: i })? = true;
            }
        }
        t.live_vertices = t.vertex_dead.iter().filter(|d| !**d).count();
        t.live_edges = t.edge_dead.iter().filter(|d| !**d).count();
        t.live_faces = t.face_dead.iter().filter(|d| !**d).count();
        for (f, rings) in d.face_rings {
            if t.face_rings.insert(FaceId(f), rings).is_some() {
                return Err(MeshDataError::TwoRingLists { face: FaceId(f) });
            }
        }
        for (f, v) in d.lone_vertex_faces {
            if t.face_lone_vertex.insert(FaceId(f), VertexId(v)).is_some() {
                return Err(MeshDataError::TwoLoneVertices { face: FaceId(f) });
            }
        }
        let m = HalfEdgeMesh::from_parts(d.positions, t);
        m.validate()?;
        Ok(m)
    }
}

impl HalfEdgeMesh {
    /// [`compacted`](Self::compacted) for meshes with rings: the same
    /// records with dense ids, in the old order.
    pub(crate) fn compacted_records(&self) -> HalfEdgeMesh {
        let lone: Vec<VertexId> = self
            .topology
            .face_lone_vertex
            .values()
            .copied()
            .chain(
                self.topology
                    .face_rings
                    .values()
                    .flatten()
                    .filter_map(|l| match l {
                        LoopStart::Vertex(v) => Some(*v),
                        LoopStart::HalfEdge(_) => None,
                    }),
            )
            .collect();
        let mut vmap = vec![NONE; self.positions.len()];
        let mut positions = Vec::new();
        for v in self
            .vertices()
            .filter(|&v| !self.is_isolated_vertex(v) || lone.contains(&v))
        {
            vmap[v.index()] = positions.len() as u32;
            positions.push(self.position(v));
        }
        let mut emap = vec![NONE; self.topology.edge_dead.len()];
        for (i, e) in self.edges().enumerate() {
            emap[e.index()] = i as u32;
        }
        let hmap = |h: u32| -> u32 {
            if h == NONE {
                NONE
            } else {
                (emap[h as usize / 2] << 1) | (h & 1)
            }
        };
        let mut fmap = vec![NONE; self.topology.face_halfedge.len()];
        for (i, f) in self.faces().enumerate() {
            fmap[f.index()] = i as u32;
        }
        let halfedges = self
            .halfedges()
            .map(|h| {
                let r = &self.topology.halfedges[h.index()];
                HalfEdgeRecord {
                    origin: vmap[r.origin as usize],
                    next: hmap(r.next),
                    prev: hmap(r.prev),
                    face: if r.face == NONE {
                        NONE
                    } else {
                        fmap[r.face as usize]
                    },
                }
            })
            .collect();
        let map_loop = |l: &LoopStart| match *l {
            LoopStart::HalfEdge(h) => LoopStart::HalfEdge(HalfEdgeId(hmap(h.0))),
            LoopStart::Vertex(v) => LoopStart::Vertex(VertexId(vmap[v.index()])),
        };
        let vertex_out = self
            .vertices()
            .filter(|v| vmap[v.index()] != NONE)
            .map(|v| hmap(self.topology.vertex_out[v.index()]))
            .collect();
        let face_halfedge = self
            .faces()
            .map(|f| hmap(self.topology.face_halfedge[f.index()]))
            .collect();
        let mut m = HalfEdgeMesh::all_live(positions, vertex_out, halfedges, face_halfedge);
        let topology = m.topology_mut();
        topology.face_rings = self
            .topology
            .face_rings
            .iter()
            .map(|(f, r)| (FaceId(fmap[f.index()]), r.iter().map(map_loop).collect()))
            .collect();
        topology.face_lone_vertex = self
            .topology
            .face_lone_vertex
            .iter()
            .map(|(f, v)| (FaceId(fmap[f.index()]), VertexId(vmap[v.index()])))
            .collect();
        m
    }
}
