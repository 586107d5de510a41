//! Face extrude (seed 004): MEV at each corner, MEF between them.

use super::EulerError;
use crate::ids::{FaceId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;

impl HalfEdgeMesh {
    // ----- composite ------------------------------------------------------------

    /// Extrudes one face along `offset` (seed 004's face extrude): each corner
    /// grows an edge (MEV), consecutive new corners are joined (MEF), so the
    /// face becomes the cap and every side gets a new quad. For an n-gon:
    /// ΔV = +n, ΔE = +2n, ΔF = +n. The cap keeps the face's id.
    ///
    /// Inverse: for each side quad, [`kill_edge_face`](Self::kill_edge_face)
    /// on the edges between new corners, then
    /// [`kill_edge_vertex`](Self::kill_edge_vertex) on each corner edge.
    ///
    /// # Errors
    /// [`EulerError::Missing`], [`EulerError::NonFinite`],
    /// [`EulerError::HasRings`] for a face with rings or without edges,
    /// [`EulerError::Degenerate`] for a wire of one edge, or a loop that
    /// passes a vertex twice where the side faces cannot be made.
    ///
    /// Complexity: O(n²) for an n-gon (loop walks in MEF); a loop that passes
    /// a vertex twice is extruded on a copy first.
    pub fn extrude_face(&mut self, f: FaceId, offset: DVec3) -> Result<Vec<FaceId>, EulerError> {
        if !self.is_face(f) {
            return Err(EulerError::Missing(f.into()));
        }
        if !offset.is_finite() {
            return Err(EulerError::NonFinite);
        }
        self.check_polygon_face(f)?;
        let mut corners: Vec<VertexId> = self.face_vertices(f).collect();
        if corners.len() < 3 {
            return Err(EulerError::Degenerate); // the single edge of a wire
        }
        corners.sort_unstable();
        if corners.windows(2).any(|w| w[0] == w[1]) {
            let mut trial = self.clone();
            let sides = trial.extrude_face_unchecked(f, offset)?;
            *self = trial;
            return Ok(sides);
        }
        self.extrude_face_unchecked(f, offset)
    }
    fn extrude_face_unchecked(
        &mut self,
        f: FaceId,
        offset: DVec3,
    ) -> Result<Vec<FaceId>, EulerError> {
        let loop_: Vec<HalfEdgeId> = self.face_halfedges(f).collect();
        // Spikes out of every corner: after each original half-edge h (ending at target(h)).
        let mut spikes = Vec::with_capacity(loop_.len());
        for &h in &loop_ {
            let p = self.position(self.target(h)) + offset;
            let (e, _) = self
                .make_edge_vertex(h, p)
                .expect("checked face and position");
            let out = if self.origin(e.halfedge(0)) == self.target(h) {
                e.halfedge(0)
            } else {
                e.halfedge(1)
            };
            spikes.push(out);
        }
        let mut sides = Vec::with_capacity(loop_.len());
        let mut h_a = spikes[0];
        for k in 1..=spikes.len() {
            let h_b = spikes[k % spikes.len()];
            // Corners of a simple loop are always far enough apart; a wire's
            // may not be (its copy is dropped then).
            let (e, g) = self.make_edge_face(h_a, h_b)?;
            sides.push(g);
            h_a = e.halfedge(0);
        }
        Ok(sides)
    }
}
