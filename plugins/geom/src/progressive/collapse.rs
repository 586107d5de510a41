//! One collapse and what decides it: the quadrics, feature edges and
//! corners that hold, the candidate positions and their costs, the
//! fold-over check, and the collapse itself with its vertex split.

use super::{
    CORNER_TURN, CURVATURE_WEIGHT, FEATURE_WEIGHT, NOT_CURVED, Quadric, Simplifier, VertexSplit,
};
use crate::ids::{EdgeId, HalfEdgeId, VertexId};
use glam::DVec3;

/// The least error of a collapse, per cubed length of its edge (errors are
/// weights, lengths, times squared distances): far below any visible
/// error, it only orders the collapses of flat parts.
const FLAT_ERROR: f64 = 1e-12;

/// Up to two collapses of one edge (one per direction), cheapest first:
/// cost, the half-edge whose target goes, the position.
#[derive(Copy, Clone)]
pub(super) struct Candidates {
    items: [(f64, HalfEdgeId, DVec3); 2],
    len: usize,
}

impl Default for Candidates {
    fn default() -> Self {
        Candidates {
            items: [(0.0, HalfEdgeId(0), DVec3::ZERO); 2],
            len: 0,
        }
    }
}

impl Candidates {
    fn add(&mut self, c: (f64, HalfEdgeId, DVec3)) {
        self.items[self.len] = c;
        self.len += 1;
    }
    pub(super) fn first(&self) -> Option<&(f64, HalfEdgeId, DVec3)> {
        self.items[..self.len].first()
    }
    pub(super) fn iter(&self) -> impl Iterator<Item = (f64, HalfEdgeId, DVec3)> + '_ {
        self.items[..self.len].iter().copied()
    }
}

impl Simplifier<'_> {
    fn is_feature(&self, e: EdgeId) -> bool {
        self.feature[e.index()] || self.mesh.is_boundary_edge(e)
    }
    /// The feature edges at `v`: how many, and the far ends of the first two.
    fn feature_ends(&self, v: VertexId) -> (usize, [VertexId; 2]) {
        let m = &self.mesh;
        let mut ends = [v; 2];
        let mut n = 0;
        for h in m.vertex_outgoing(v) {
            if self.is_feature(h.edge()) {
                if n < 2 {
                    ends[n] = m.target(h);
                }
                n += 1;
            }
        }
        (n, ends)
    }
    /// Whether the feature line turns by more than [`CORNER_TURN`] at `p`,
    /// coming from `from` and going on to `to`.
    fn turns_sharply(from: DVec3, p: DVec3, to: DVec3) -> bool {
        let (x, y) = ((p - from).normalize_or_zero(), (to - p).normalize_or_zero());
        x.dot(y) < CORNER_TURN.cos()
    }
    /// The vertex after `u` on the feature line that comes from `v`
    /// (`u` itself where the line ends or branches at `u`).
    fn beyond(&self, v: VertexId, u: VertexId) -> VertexId {
        match self.feature_ends(u) {
            (2, [a, b]) => {
                if a == v {
                    b
                } else {
                    a
                }
            }
            _ => u,
        }
    }
    /// Number of feature edges at `v`, and whether `v` is a corner of
    /// the features: one or three or more feature edges, or two that turn
    /// by more than [`CORNER_TURN`] both at `v` and over two edges on
    /// each side. A line that zigzags (the jagged border of a scan) turns
    /// sharply at its vertices but hardly over two edges: that is noise at
    /// the scale of its edges, its vertices slide and the feature planes
    /// of the quadrics hold its shape.
    fn feature_degree(&self, v: VertexId) -> (usize, bool) {
        if !self.near_feature[v.index()] {
            return (0, false);
        }
        let (n, ends) = self.feature_ends(v);
        let corner = match n {
            0 => false,
            2 => {
                let m = &self.mesh;
                let p = m.position(v);
                let [a, b] = ends;
                Self::turns_sharply(m.position(a), p, m.position(b))
                    && Self::turns_sharply(
                        m.position(self.beyond(v, a)),
                        p,
                        m.position(self.beyond(v, b)),
                    )
            }
            _ => true,
        };
        (n, corner)
    }
    fn fixed(&self, v: VertexId, corner: bool) -> bool {
        corner
            || (self.options.keep_borders && self.mesh.is_boundary_vertex(v))
            || self.corner_sharp[v.index()]
    }
    /// The position and quadric error of collapsing `h` (its target into
    /// its origin), or `None` when the features forbid it. The error is a
    /// lower bound of the cost ([`shaped`](Self::shaped)).
    fn candidate(&self, h: HalfEdgeId) -> Option<(f64, DVec3)> {
        let m = &self.mesh;
        let (a, b) = (m.origin(h), m.target(h));
        let ((da, corner_a), (db, corner_b)) = (self.feature_degree(a), self.feature_degree(b));
        if self.fixed(b, corner_b) {
            return None;
        }
        let on_feature = self.is_feature(h.edge());
        if db == 2 && !on_feature {
            return None;
        }
        let q = self.quadrics[a.index()] + self.quadrics[b.index()];
        // The cost's quadric: the placement's plus the curved spots'.
        let mut cost = q;
        for v in [a, b] {
            if let Some(c) = self.curvature.get(self.curved_at[v.index()] as usize) {
                cost += *c;
            }
        }
        let (pa, pb) = (m.position(a), m.position(b));
        if self.fixed(a, corner_a) || (da > 0 && db == 0) {
            return Some((cost.error(pa), pa));
        }
        let mid = (pa + pb) * 0.5;
        let mut best = (cost.error(pa), pa);
        let optimum = q.minimizer().map(|p| {
            if db == 2 {
                // Sliding along a feature line: stay on the edge.
                let d = pb - pa;
                pa + d * ((p - pa).dot(d) / d.length_squared()).clamp(0.0, 1.0)
            } else {
                p
            }
        });
        let reach = 2.0 * pa.distance(pb);
        let optimum = optimum.filter(|p| p.distance(mid) <= reach);
        for p in [Some(pb), Some(mid), optimum].into_iter().flatten() {
            let e = cost.error(p);
            // Endpoints win ties, so exact positions (corners) stay exact.
            if e < best.0 * (1.0 - 1e-9) {
                best = (e, p);
            }
        }
        Some(best)
    }
    /// The costs of `raw` candidates (from [`candidates`](Self::candidates)),
    /// cheapest first: the error, raised where the collapse leaves thin
    /// triangles, divided by their [`worst_shape`](Self::worst_shape)
    /// (MeshLab's quality penalty, vcglib's
    /// `TriEdgeCollapseQuadric::ComputePriority`, here without its
    /// threshold: measured on the decimation table of issue 35, the full
    /// penalty has the lowest mean distances on curved surfaces; with
    /// vcglib's threshold at 0.1 or 0.3 the UV sphere's mean at 50 and
    /// 10 % is 1.23× and 1.35× MeshLab's).
    ///
    /// Measured and not taken (2026-12-07): dividing by the square root
    /// of the shape lowers the mean distance of the bunny (at 50, 10 and
    /// 1 %, by 1 to 4 %) and of the range scan (at 50 % and at every
    /// level measured from 5 to 20 %, by 1 to 3 %), and on the table
    /// closes the bunny's 1 % Hausdorff, the sphere's 1 %
    /// mean and the scan's 50 % Hausdorff gaps, but the scan's Hausdorff
    /// at 10 % goes from 0.91× to 1.07× `simplify`'s. That row is a dip
    /// of the full penalty: its
    /// Hausdorff is 6.0e-4, 6.1e-4, 5.5e-4, 6.0e-4 and 6.3e-4 at 11,
    /// 10.5, 10, 9.5 and 9 % (the square root gives 6.4e-4 to 6.5e-4
    /// there, and less at 11 to 15 %). Exponents 0.4 to 0.85 each
    /// take a row of the sphere or the scan over its bound at 1 or 10 %;
    /// with the optimum's reach cut from 2 to ½ edge length as well, the
    /// scan's 10 % row is back at 0.91× but the sphere's and the creased
    /// cube's 1 % Hausdorff go to 1.06× and 1.03×.
    pub(super) fn shaped(&self, mut raw: Candidates) -> Candidates {
        // Both directions to one position leave the same triangles.
        let mut last: Option<(DVec3, f64)> = None;
        for c in &mut raw.items[..raw.len] {
            let shape = match last {
                Some((p, shape)) if p == c.2 => shape,
                _ => self.worst_shape(c.1, c.2),
            };
            last = Some((c.2, shape));
            // Where the error is nil (flat parts), it still orders the
            // collapses: short edges and good shapes first, as vcglib's
            // `QuadricEpsilon` times the edge length does; else a flat
            // region collapses in id order into fans of thin triangles.
            let length = self
                .mesh
                .position(self.mesh.origin(c.1))
                .distance(self.mesh.position(self.mesh.target(c.1)));
            c.0 = c.0.max(FLAT_ERROR * length * length * length) / shape;
        }
        if raw.len == 2 && raw.items[1].0 < raw.items[0].0 {
            raw.items.swap(0, 1);
        }
        raw
    }
    /// The worst shape of the triangles left around the collapse of `h`
    /// with its vertex at `p`: the least of 4√3·area / (sum of the squared
    /// edges) over them (1 for an equilateral triangle, 0 for a
    /// degenerate one), at least 1e-6; 1 when none is left.
    fn worst_shape(&self, h: HalfEdgeId, p: DVec3) -> f64 {
        let mut worst = 1.0f64;
        for (_, x, y) in self.surviving_triangles(h) {
            let twice_area = (x - p).cross(y - p).length();
            let squares =
                (x - p).length_squared() + (y - p).length_squared() + (y - x).length_squared();
            let shape = if squares > 0.0 {
                2.0 * 3f64.sqrt() * twice_area / squares
            } else {
                0.0
            };
            worst = worst.min(shape);
        }
        worst.max(1e-6)
    }
    /// The triangles around both ends of `h` that its collapse keeps (all
    /// but the one or two beside it), each as the end it has and the
    /// positions of its other two corners, in order.
    fn surviving_triangles(
        &self,
        h: HalfEdgeId,
    ) -> impl Iterator<Item = (VertexId, DVec3, DVec3)> + '_ {
        let m = &self.mesh;
        let beside = [m.face(h), m.face(h.twin())];
        [m.origin(h), m.target(h)].into_iter().flat_map(move |v| {
            m.vertex_outgoing(v).filter_map(move |o| {
                let f = m.face(o)?;
                (!beside.contains(&Some(f)))
                    .then(|| (v, m.position(m.target(o)), m.position(m.target(m.next(o)))))
            })
        })
    }
    /// The allowed collapses of `e` with their quadric errors, least
    /// first. Away from features both directions have the same placement
    /// and error, computed once.
    pub(super) fn candidates(&self, e: EdgeId) -> Candidates {
        let [a, b] = self.mesh.edge_vertices(e);
        let plain = |v: VertexId| !self.near_feature[v.index()] && !self.corner_sharp[v.index()];
        let mut out = Candidates::default();
        if plain(a) && plain(b) {
            let h = e.halfedge(0);
            if let Some((c, p)) = self.candidate(h) {
                out.add((c, h, p));
                out.add((c, h.twin(), p));
            }
            return out;
        }
        for h in [e.halfedge(0), e.halfedge(1)] {
            if let Some((c, p)) = self.candidate(h) {
                out.add((c, h, p));
            }
        }
        if out.len == 2 && out.items[1].0 < out.items[0].0 {
            out.items.swap(0, 1);
        }
        out
    }
    /// The checks the Euler operator does not make: no triangle edge that
    /// the collapse removes may be a border (its vertex split could not
    /// rebuild the triangle), and no face may turn by more than the limit
    /// or degenerate.
    pub(super) fn allowed(&self, h: HalfEdgeId, p: DVec3) -> bool {
        let m = &self.mesh;
        let t = h.twin();
        for x in [h, t] {
            if m.face(x).is_some() && m.is_boundary_edge(m.next(x).edge()) {
                return false;
            }
        }
        for (v, x, y) in self.surviving_triangles(h) {
            let q = m.position(v);
            let before = (x - q).cross(y - q);
            let after = (x - p).cross(y - p);
            let scale = before.length();
            let turned = after.length();
            if turned <= 1e-12 * scale.max(1e-300) || turned == 0.0 {
                return false;
            }
            if before.dot(after) < self.cos_limit * scale * turned {
                return false;
            }
        }
        true
    }
}

impl Simplifier<'_> {
    pub(super) fn init_quadrics(&mut self) {
        let m = &self.mesh;
        let cos_sharp = self.options.sharp_angle.map(|a| a.to_radians().cos());
        for f in m.faces() {
            let n = m.face_area_vector(f);
            let area = n.length();
            if area <= 0.0 {
                continue;
            }
            let q = Quadric::plane(
                n / area,
                m.position(m.face_vertices(f).next().unwrap()),
                // √area (meshoptimizer's `quadricFromTriangle`): the
                // weights are lengths, like the feature planes'.
                area.sqrt(),
            );
            for v in m.face_vertices(f) {
                self.quadrics[v.index()] += q;
            }
        }
        self.init_curvature();
        let m = &self.mesh;
        for e in m.edges() {
            let crease = self.options.keep_creases && self.creases.edge(e) > 0.0;
            let seam = self.options.seams.contains(&e);
            let sharp = match (cos_sharp, m.edge_faces(e)) {
                (Some(c), [Some(f), Some(g)]) => m.face_normal(f).dot(m.face_normal(g)) < c,
                _ => false,
            };
            self.feature[e.index()] = crease || seam || sharp;
            if !(self.feature[e.index()] || m.is_boundary_edge(e)) {
                continue;
            }
            let [a, b] = m.edge_vertices(e);
            self.near_feature[a.index()] = true;
            self.near_feature[b.index()] = true;
            let (pa, pb) = (m.position(a), m.position(b));
            let dir = pb - pa;
            let len = dir.length();
            for f in m.edge_faces(e).into_iter().flatten() {
                let n = dir.cross(m.face_normal(f)).normalize_or_zero();
                if n == DVec3::ZERO {
                    continue;
                }
                // The face's own plane as well, as strongly: the
                // perpendicular plane holds the line within the surface,
                // this one holds it across (a border that dips out of
                // its surface, a scan's rim); meshoptimizer's
                // `fillEdgeQuadrics` adds the triangle's quadric to each
                // border edge's the same way.
                for q in [
                    Quadric::plane(n, pa, FEATURE_WEIGHT * len),
                    Quadric::plane(m.face_normal(f), pa, FEATURE_WEIGHT * len),
                ] {
                    self.quadrics[a.index()] += q;
                    self.quadrics[b.index()] += q;
                }
            }
        }
    }
    /// The tangent planes of the doubly curved vertices
    /// ([`CURVATURE_WEIGHT`]): at an inner vertex whose angle defect has
    /// the sign of every neighbour's, the plane through it normal to its
    /// ring's vector area, weighted by the defect times the square root
    /// of a third of the ring's area.
    fn init_curvature(&mut self) {
        let m = &self.mesh;
        let mut defect = vec![f64::NAN; m.vertex_capacity()];
        for v in m.vertices() {
            if m.is_boundary_vertex(v) {
                continue;
            }
            let p = m.position(v);
            let mut angles = 0.0;
            for o in m.vertex_outgoing(v) {
                let (x, y) = (
                    m.position(m.target(o)) - p,
                    m.position(m.target(m.next(o))) - p,
                );
                angles += x.angle_between(y);
            }
            defect[v.index()] = std::f64::consts::TAU - angles;
        }
        for v in m.vertices() {
            let d = defect[v.index()];
            // NaN (a border, a degenerate corner) is never consistent.
            if !m
                .vertex_outgoing(v)
                .all(|o| defect[m.target(o).index()] * d > 0.0)
            {
                continue;
            }
            let p = m.position(v);
            let area = m
                .vertex_outgoing(v)
                .map(|o| (m.position(m.target(o)) - p).cross(m.position(m.target(m.next(o))) - p))
                .sum::<DVec3>()
                * 0.5;
            let a = area.length();
            let weight = CURVATURE_WEIGHT * d.abs() * (a / 3.0).sqrt();
            if a > 0.0 && weight > 0.0 && weight.is_finite() {
                self.curved_at[v.index()] = self.curvature.len() as u32;
                self.curvature.push(Quadric::plane(area / a, p, weight));
            }
        }
    }
    /// One collapse through the Euler operator, with its record; `None`
    /// when the operator refuses (the mesh is then unchanged).
    pub(super) fn collapse(&mut self, h: HalfEdgeId, p: DVec3, cost: f64) -> Option<VertexSplit> {
        let m = &self.mesh;
        let t = h.twin();
        let (a, b) = (m.origin(h), m.target(h));
        let tri = |x: HalfEdgeId| m.face(x).is_some() && m.next(m.next(m.next(x))) == x;
        let left = tri(h).then(|| (m.face(h).unwrap(), m.next(h), m.prev(h).edge()));
        let right = tri(t).then(|| (m.face(t).unwrap(), m.next(t), m.prev(t).edge()));
        let last = match left {
            Some((_, nh, _)) => m.next(nh.twin()),
            None => m.next(h),
        };
        let split = VertexSplit {
            edge: h,
            kept: a,
            removed: b,
            first: m.prev(t).twin(),
            last,
            left,
            right,
            position: p,
            kept_position: m.position(a),
            removed_position: m.position(b),
            error: cost,
        };
        // The triangles' surviving edges take over the features of the
        // removed ones.
        self.mesh.collapse_edge_removing_triangles(h, p).ok()?;
        for (_, gone, keep) in [left, right].into_iter().flatten() {
            if self.feature[gone.edge().index()] {
                self.feature[keep.index()] = true;
            }
        }
        let q = self.quadrics[a.index()] + self.quadrics[b.index()];
        self.quadrics[a.index()] = q;
        match (self.curved_at[a.index()], self.curved_at[b.index()]) {
            (_, NOT_CURVED) => {}
            (NOT_CURVED, j) => self.curved_at[a.index()] = j,
            (i, j) => {
                let c = self.curvature[j as usize];
                self.curvature[i as usize] += c;
            }
        }
        self.near_feature[a.index()] |= self.near_feature[b.index()];
        Some(split)
    }
}
