//! Building the record: checks and triangulation, the simplifier run,
//! the compact base mesh and the vertex splits that lead back to the input.

use super::{
    Base, Cancelled, Control, DecimateError, DecimateOptions, ProgressiveMesh, Quadric, Simplifier,
    VertexSplit,
};
use crate::ids::{FaceId, HalfEdgeId, VertexId};
use crate::mesh::{HalfEdgeMesh, MeshData, MeshDataError};
use crate::modeling::{TriangulateMethod, triangulate_faces};
use crate::subdivision::Creases;
use glam::DVec3;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

impl ProgressiveMesh {
    /// Simplifies (a triangulated copy of) `mesh` as far as the options
    /// allow and keeps the whole sequence; the result stands at level 0,
    /// the base mesh. `creases` are the input's (by its ids).
    ///
    /// Inverse: seeking the last level
    /// ([`seek`](Self::seek)`(level_count() − 1)`) gives the input back.
    ///
    /// # Errors
    /// [`DecimateError::NotManifold`], [`DecimateError::NotPolygon`],
    /// [`DecimateError::NoFaces`], [`DecimateError::Triangulate`]; the
    /// input is never changed.
    ///
    /// Complexity: O(n log n) for n edges (each collapse costs the edges
    /// of two rings of one vertex again and queues them in a binary
    /// heap); a few rounds over every edge at the end retry refusals.
    pub fn build(
        mesh: &HalfEdgeMesh,
        creases: &Creases,
        options: &DecimateOptions,
    ) -> Result<ProgressiveMesh, DecimateError> {
        Self::build_with_progress(mesh, creases, options, &mut |_| {}, &AtomicBool::new(false))
    }
    /// [`build`](Self::build) for a background job: calls `progress` with
    /// the fraction done, in [0, 1], never decreasing, each value at least
    /// 0.001 above the last and 1 as the last call when the build
    /// succeeds; reads `cancel` every few thousand queue keys of the
    /// simplification (every few milliseconds) and stops when it is set.
    /// The input is borrowed and never changed; see [`BuildJob`](super::BuildJob) for a
    /// build that owns its inputs and moves to a worker thread.
    ///
    /// # Errors
    /// As [`build`](Self::build), and [`DecimateError::Cancelled`] when
    /// `cancel` was set: nothing is returned but the error (the partial
    /// simplification is dropped) and `progress` is not called again.
    ///
    /// Complexity: as [`build`](Self::build).
    pub fn build_with_progress(
        mesh: &HalfEdgeMesh,
        creases: &Creases,
        options: &DecimateOptions,
        progress: &mut dyn FnMut(f64),
        cancel: &AtomicBool,
    ) -> Result<ProgressiveMesh, DecimateError> {
        let mut control = Control {
            progress,
            cancel,
            told: 0.0,
            faces: 0,
        };
        let cancelled = |_: Cancelled| DecimateError::Cancelled;
        control.report(0.0).map_err(cancelled)?;
        let input = Self::triangulated(mesh)?;
        control.faces = input.face_count();
        let mut s = Simplifier {
            quadrics: vec![Quadric::default(); input.vertex_capacity()],
            curvature: Vec::new(),
            curved_at: vec![super::NOT_CURVED; input.vertex_capacity()],
            feature: vec![false; input.edge_capacity()],
            near_feature: vec![false; input.vertex_capacity()],
            corner_sharp: (0..input.vertex_capacity() as u32)
                .map(|v| options.keep_creases && creases.vertex(VertexId(v)) > 0.0)
                .collect(),
            removed_faces: 0,
            cos_limit: options.max_normal_change.to_radians().cos(),
            options,
            creases,
            mesh: input,
        };
        s.init_quadrics();
        let n_faces = s.mesh.face_count();
        let mut splits = Vec::with_capacity(s.mesh.vertex_count());
        control.report(Control::BEFORE).map_err(cancelled)?;
        s.run(&mut splits, &mut control).map_err(cancelled)?;
        control.report(1.0 - Control::AFTER).map_err(cancelled)?;
        let capacity = [
            s.mesh.vertex_capacity(),
            s.mesh.edge_capacity(),
            s.mesh.face_capacity(),
        ];
        let base = Arc::new(Self::compact(&s.mesh)?);
        let mut pm = ProgressiveMesh::from_parts(capacity, base, Arc::new(splits));
        debug_assert_eq!(pm.face_counts.last(), Some(&n_faces));
        // The simplified mesh is the base in the input's ids: keep it as the
        // working mesh instead of the dense copy.
        pm.mesh = s.mesh;
        pm.identity_maps();
        control.report(1.0).map_err(cancelled)?;
        Ok(pm)
    }
    /// A triangulated copy of `mesh`, after checking it.
    fn triangulated(mesh: &HalfEdgeMesh) -> Result<HalfEdgeMesh, DecimateError> {
        mesh.validate().map_err(DecimateError::NotManifold)?;
        if let Some(face) = mesh.first_non_polygon_face() {
            return Err(DecimateError::NotPolygon { face });
        }
        if mesh.face_count() == 0 {
            return Err(DecimateError::NoFaces);
        }
        let mut out = mesh.clone();
        let big: Vec<FaceId> = mesh.faces().filter(|&f| mesh.face_degree(f) > 3).collect();
        if !big.is_empty() {
            triangulate_faces(&mut out, &big, TriangulateMethod::Beauty)
                .map_err(DecimateError::Triangulate)?;
        }
        Ok(out)
    }
    pub(super) fn from_parts(
        capacity: [usize; 3],
        base: Arc<Base>,
        splits: Arc<Vec<VertexSplit>>,
    ) -> ProgressiveMesh {
        let mut counts = Vec::with_capacity(splits.len() + 1);
        let mut faces = base.mesh.face_count();
        counts.push(faces);
        for s in splits.iter().rev() {
            faces += s.triangles();
            counts.push(faces);
        }
        let [nv, ne, nf] = capacity;
        let mut fwd_v = vec![u32::MAX; nv];
        let mut fwd_e = vec![u32::MAX; ne];
        let mut fwd_f = vec![u32::MAX; nf];
        for (i, &x) in base.vertices.iter().enumerate() {
            fwd_v[x as usize] = i as u32;
        }
        for (i, &x) in base.edges.iter().enumerate() {
            fwd_e[x as usize] = (i as u32) << 1;
        }
        for (i, &x) in base.faces.iter().enumerate() {
            fwd_f[x as usize] = i as u32;
        }
        ProgressiveMesh {
            capacity,
            mesh: base.mesh.clone(),
            inv_v: base.vertices.clone(),
            inv_e: base.edges.iter().map(|&e| e << 1).collect(),
            inv_f: base.faces.clone(),
            fwd_v,
            fwd_e,
            fwd_f,
            level: 0,
            face_counts: Arc::new(counts),
            base,
            splits,
        }
    }
    /// The maps when the working mesh is in the input's ids.
    pub(super) fn identity_maps(&mut self) {
        let [nv, ne, nf] = self.capacity;
        self.fwd_v = (0..nv as u32).collect();
        self.fwd_e = (0..ne as u32).map(|e| e << 1).collect();
        self.fwd_f = (0..nf as u32).collect();
        self.inv_v = self.fwd_v.clone();
        self.inv_e = self.fwd_e.clone();
        self.inv_f = self.fwd_f.clone();
    }
    /// The mesh with dense ids and the input id of each.
    fn compact(mesh: &HalfEdgeMesh) -> Result<Base, DecimateError> {
        let rank = |n: usize, live: &mut dyn Iterator<Item = u32>| {
            let mut map = vec![u32::MAX; n];
            let mut back = Vec::new();
            for x in live {
                map[x as usize] = back.len() as u32;
                back.push(x);
            }
            (map, back)
        };
        let (vm, vertices) = rank(mesh.vertex_capacity(), &mut mesh.vertices().map(|v| v.0));
        let (em, edges) = rank(mesh.edge_capacity(), &mut mesh.edges().map(|e| e.0));
        let (fm, faces) = rank(mesh.face_capacity(), &mut mesh.faces().map(|f| f.0));
        let dense = renumber(
            mesh,
            [vertices.len(), edges.len(), faces.len()],
            |v| vm[v.index()],
            |h| (em[h.edge().index()] << 1) | (h.0 & 1),
            |f| fm[f.index()],
        )?;
        Ok(Base {
            mesh: dense,
            vertices,
            edges,
            faces,
        })
    }
}

/// `mesh` with every live element renamed by the maps, in an id space of
/// the given capacities (vertices, edges, faces); other slots are dead.
/// Built through [`MeshData`], so the result is validated.
pub(super) fn renumber(
    mesh: &HalfEdgeMesh,
    [nv, ne, nf]: [usize; 3],
    vmap: impl Fn(VertexId) -> u32,
    hmap: impl Fn(HalfEdgeId) -> u32,
    fmap: impl Fn(FaceId) -> u32,
) -> Result<HalfEdgeMesh, MeshDataError> {
    let mut positions = vec![DVec3::ZERO; nv];
    let mut vertex_halfedge = vec![-1i64; nv];
    let mut halfedges = vec![(0u32, 0u32, 0u32, -1i64); 2 * ne];
    let mut face_halfedge = vec![u32::MAX; nf];
    let (mut live_v, mut live_e, mut live_f) = (vec![false; nv], vec![false; ne], vec![false; nf]);
    for v in mesh.vertices() {
        let i = vmap(v) as usize;
        live_v[i] = true;
        positions[i] = mesh.position(v);
        vertex_halfedge[i] = mesh.vertex_halfedge(v).map_or(-1, |h| hmap(h) as i64);
    }
    for h in mesh.halfedges() {
        let i = hmap(h) as usize;
        live_e[i / 2] = true;
        halfedges[i] = (
            vmap(mesh.origin(h)),
            hmap(mesh.next(h)),
            hmap(mesh.prev(h)),
            mesh.face(h).map_or(-1, |f| fmap(f) as i64),
        );
    }
    for f in mesh.faces() {
        let i = fmap(f) as usize;
        live_f[i] = true;
        face_halfedge[i] = hmap(mesh.face_halfedge(f));
    }
    let dead = |live: &[bool]| -> Vec<u32> {
        live.iter()
            .enumerate()
            .filter(|(_, l)| !**l)
            .map(|(i, _)| i as u32)
            .collect()
    };
    HalfEdgeMesh::try_from(MeshData {
        positions,
        vertex_halfedge,
        halfedges,
        face_halfedge,
        dead_vertices: dead(&live_v),
        dead_edges: dead(&live_e),
        dead_faces: dead(&live_f),
        face_rings: Vec::new(),
        lone_vertex_faces: Vec::new(),
    })
}
