//! Reading and moving between levels: face counts and errors per
//! level, seeking by replaying vertex splits or edge collapses, and the
//! level as a mesh in the input's ids.

use super::build::renumber;
use super::decimate::join_quads;
use super::{DecimateError, DecimateOptions, DecimateTarget, ProgressiveMesh, VertexSplit};
use crate::EulerError;
use crate::ids::{FaceId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;
use crate::subdivision::Creases;

impl ProgressiveMesh {
    // ----- queries --------------------------------------------------------

    /// Number of levels: one more than the number of vertex splits.
    pub fn level_count(&self) -> usize {
        self.splits.len() + 1
    }
    /// The current level (0: the base mesh; `level_count() − 1`: the input).
    pub fn level(&self) -> usize {
        self.level
    }
    /// The finest level, the input's.
    pub fn max_level(&self) -> usize {
        self.splits.len()
    }
    /// Faces at each level, from the base (index 0) to the input.
    pub fn face_counts(&self) -> &[usize] {
        &self.face_counts
    }
    /// Faces at `level` (`None` past the last level).
    pub fn face_count_at(&self, level: usize) -> Option<usize> {
        self.face_counts.get(level).copied()
    }
    /// The vertex splits in collapse order: split `i` undoes the `i`-th
    /// collapse from the input, so going from level `L` to `L − 1`
    /// collapses `splits()[max_level() − L]`.
    pub fn splits(&self) -> &[VertexSplit] {
        &self.splits
    }
    /// The error of `level`: the largest cost ([`VertexSplit::error`]) of the collapses
    /// that lead from the input to it (0 for the input). It never grows as
    /// faces are added back.
    pub fn error_at(&self, level: usize) -> f64 {
        let applied = self.max_level().saturating_sub(level);
        self.splits[..applied.min(self.splits.len())]
            .iter()
            .map(|s| s.error)
            .fold(0.0, f64::max)
    }
    /// The input's creases carried to the current level, by the input's
    /// ids: an edge that a collapse merged into another (the two edges of
    /// a removed triangle that meet at the removed vertex's neighbour
    /// become one) passes its sharpness on when larger; corner sharpness
    /// of removed vertices goes with them.
    ///
    /// Complexity: O(collapses applied + creases).
    pub fn level_creases(&self, creases: &Creases) -> Creases {
        let mut out = creases.clone();
        if out.is_empty() {
            return out;
        }
        let applied = self.max_level() - self.level;
        for s in &self.splits[..applied] {
            for (_, gone, keep) in [s.left, s.right].into_iter().flatten() {
                let sharp = out.edge(gone.edge());
                if sharp > out.edge(keep) {
                    out.set_edge(keep, sharp);
                }
                out.set_edge(gone.edge(), 0.0);
            }
            out.set_edge(s.edge.edge(), 0.0);
            out.set_vertex(s.removed, 0.0);
        }
        out
    }
    /// The base mesh (level 0) in dense ids.
    pub fn base_mesh(&self) -> &HalfEdgeMesh {
        &self.base.mesh
    }
    /// The current level's working mesh. Its ids are fresh ones after
    /// vertex splits; [`level_mesh`](Self::level_mesh) gives the input's.
    pub fn mesh(&self) -> &HalfEdgeMesh {
        &self.mesh
    }
    /// The input vertex a vertex of [`mesh`](Self::mesh) stands for.
    pub fn input_vertex(&self, v: VertexId) -> VertexId {
        VertexId(self.inv_v[v.index()])
    }
    /// The level with at most the target's faces and the most faces, or
    /// an error when the base has more.
    ///
    /// # Errors
    /// [`DecimateError::Ratio`] for a ratio outside (0, 1],
    /// [`DecimateError::BelowMinimum`].
    pub fn level_for(&self, target: DecimateTarget) -> Result<usize, DecimateError> {
        let goal = self.target_faces(target)?;
        let minimum = self.face_counts[0];
        if goal < minimum {
            return Err(DecimateError::BelowMinimum {
                target: goal,
                minimum,
            });
        }
        Ok(self.face_counts.partition_point(|&f| f <= goal) - 1)
    }
    /// [`level_for`](Self::level_for) clamped to the levels there are (the
    /// base for a target below it; the input for a bad ratio above 1).
    pub fn nearest_level(&self, target: DecimateTarget) -> usize {
        let goal = match target {
            DecimateTarget::Ratio(r) if r.is_nan() => 0,
            DecimateTarget::Ratio(r) => {
                (r.clamp(0.0, 1.0) * *self.face_counts.last().unwrap_or(&0) as f64).round() as usize
            }
            DecimateTarget::Faces(n) => n,
        };
        self.face_counts.partition_point(|&f| f <= goal).max(1) - 1
    }
    fn target_faces(&self, target: DecimateTarget) -> Result<usize, DecimateError> {
        match target {
            DecimateTarget::Ratio(r) => {
                if !(r > 0.0 && r <= 1.0) {
                    return Err(DecimateError::Ratio(r));
                }
                Ok((r * *self.face_counts.last().unwrap_or(&0) as f64).round() as usize)
            }
            DecimateTarget::Faces(n) => Ok(n),
        }
    }
    // ----- moving between levels ---------------------------------------------

    /// Moves to `level` from the current one: vertex splits to go finer,
    /// edge collapses to go coarser, one Euler operator sequence per level
    /// passed.
    ///
    /// Inverse: `seek` back to the level it was at.
    ///
    /// # Errors
    /// [`DecimateError::NoLevel`]; [`DecimateError::Replay`] only for a
    /// damaged stored record (the level reached is then kept).
    ///
    /// Complexity: O(Σ valence) over the levels passed.
    pub fn seek(&mut self, level: usize) -> Result<(), DecimateError> {
        if level > self.max_level() {
            return Err(DecimateError::NoLevel {
                level,
                max: self.max_level(),
            });
        }
        while self.level < level {
            let i = self.max_level() - self.level - 1;
            self.split(i).map_err(DecimateError::Replay)?;
            self.level += 1;
        }
        while self.level > level {
            let i = self.max_level() - self.level;
            let s = &self.splits[i];
            let h = self.cur_h(s.edge);
            let p = s.position;
            self.mesh
                .collapse_edge_removing_triangles(h, p)
                .map_err(DecimateError::Replay)?;
            self.level -= 1;
        }
        self.compact_if_grown()?;
        Ok(())
    }
    /// Moves to the level with at most `faces` faces (the base when it has
    /// more); returns the level.
    ///
    /// # Errors
    /// As [`seek`](Self::seek).
    pub fn set_face_count(&mut self, faces: usize) -> Result<usize, DecimateError> {
        let level = self.nearest_level(DecimateTarget::Faces(faces));
        self.seek(level)?;
        Ok(level)
    }
    /// The current level in the input's ids (every element of a level is
    /// one of the input's): at the last level a mesh
    /// [`same_as`](HalfEdgeMesh::same_as) the (triangulated) input.
    ///
    /// Complexity: O(input ids).
    pub fn level_mesh(&self) -> HalfEdgeMesh {
        let [nv, ne, nf] = self.capacity;
        let (iv, ie, iff) = (&self.inv_v, &self.inv_e, &self.inv_f);
        renumber(
            &self.mesh,
            [nv, ne, nf],
            |v| iv[v.index()],
            |h| {
                let x = ie[h.edge().index()];
                ((x >> 1) << 1) | ((h.0 & 1) ^ (x & 1))
            },
            |f| iff[f.index()],
        )
        .expect("a level renumbers into the input's ids")
    }
    /// The current level as a Decimate modifier shows it:
    /// [`level_mesh`](Self::level_mesh), with triangle pairs joined into
    /// quads by [`join_quads`] when `options.keep_quads`. `creases` are
    /// the level's ([`level_creases`](Self::level_creases)); joins keep
    /// the input's ids of everything they do not remove.
    ///
    /// Complexity: O(input ids + t log t).
    pub fn output_mesh(&self, creases: &Creases, options: &DecimateOptions) -> HalfEdgeMesh {
        let mut mesh = self.level_mesh();
        if options.keep_quads {
            let before = mesh.clone();
            if join_quads(&mut mesh, creases, options).is_err() {
                // A refused join leaves triangles; the level itself is valid.
                mesh = before;
            }
        }
        mesh
    }
    /// After many moves the working mesh collects dead slots (each split
    /// takes fresh ids); rebuild it in the input's ids then.
    fn compact_if_grown(&mut self) -> Result<(), DecimateError> {
        if self.mesh.vertex_capacity() > 3 * self.capacity[0] + 1024 {
            self.mesh = self.level_mesh();
            self.identity_maps();
        }
        Ok(())
    }
    fn cur_v(&self, v: VertexId) -> VertexId {
        VertexId(self.fwd_v[v.index()])
    }
    fn cur_h(&self, h: HalfEdgeId) -> HalfEdgeId {
        let x = self.fwd_e[h.edge().index()];
        HalfEdgeId(((x >> 1) << 1) | ((h.0 & 1) ^ (x & 1)))
    }
    fn grow(&mut self) {
        self.inv_v.resize(self.mesh.vertex_capacity(), u32::MAX);
        self.inv_e.resize(self.mesh.edge_capacity(), u32::MAX);
        self.inv_f.resize(self.mesh.face_capacity(), u32::MAX);
    }
    fn map_vertex(&mut self, input: VertexId, current: VertexId) {
        self.fwd_v[input.index()] = current.0;
        self.inv_v[current.index()] = input.0;
    }
    /// Records that input half-edge `input` is current half-edge `current`.
    fn map_halfedge(&mut self, input: HalfEdgeId, current: HalfEdgeId) {
        let flip = (input.0 ^ current.0) & 1;
        self.fwd_e[input.edge().index()] = (current.edge().0 << 1) | flip;
        self.inv_e[current.edge().index()] = (input.edge().0 << 1) | flip;
    }
    fn map_face(&mut self, input: FaceId, current: FaceId) {
        self.fwd_f[input.index()] = current.0;
        self.inv_f[current.index()] = input.0;
    }
    /// Undoes collapse `i`: a vertex split, then one MEF per triangle.
    fn split(&mut self, i: usize) -> Result<(), EulerError> {
        let s = self.splits[i].clone();
        let a = self.cur_v(s.kept);
        let (first, last) = (self.cur_h(s.first), self.cur_h(s.last));
        let e = self.mesh.split_vertex(a, first, last, s.removed_position)?;
        self.mesh.set_position(a, s.kept_position);
        self.grow();
        let (h_new, t_new) = (e.halfedge(0), e.halfedge(1));
        let w = self.mesh.target(h_new);
        self.map_vertex(s.removed, w);
        self.map_halfedge(s.edge, h_new);
        if let Some((face, removed, _)) = s.left {
            let hb = self.mesh.prev(self.mesh.prev(h_new));
            let (ne, g) = self.mesh.make_edge_face(h_new, hb)?;
            self.grow();
            let from_w = if self.mesh.origin(ne.halfedge(0)) == w {
                ne.halfedge(0)
            } else {
                ne.halfedge(1)
            };
            self.map_halfedge(removed, from_w);
            let tri = self.mesh.face(h_new).expect("the new triangle");
            self.map_split_face(face, tri, g);
        }
        if let Some((face, removed, _)) = s.right {
            let hb = self.mesh.prev(first.twin());
            let (ne, g) = self.mesh.make_edge_face(t_new, hb)?;
            self.grow();
            let from_a = if self.mesh.origin(ne.halfedge(0)) == a {
                ne.halfedge(0)
            } else {
                ne.halfedge(1)
            };
            self.map_halfedge(removed, from_a);
            let tri = self.mesh.face(t_new).expect("the new triangle");
            self.map_split_face(face, tri, g);
        }
        Ok(())
    }
    /// After a MEF made face `made` and left the triangle `tri` (either may
    /// be the old face's id): the triangle is input face `input`, the other
    /// part keeps the input face the old id stood for.
    fn map_split_face(&mut self, input: FaceId, tri: FaceId, made: FaceId) {
        if tri != made {
            let other = FaceId(self.inv_f[tri.index()]);
            self.map_face(other, made);
        }
        self.map_face(input, tri);
    }
}
