//! Bevel: of vertices (Blender's Ctrl+Shift+B, one segment) and of edges
//! (Blender's Ctrl+B, flat or rounded on quadratic Bézier arcs); both take
//! the faces around the old vertices out and add them back (pmp-library's
//! `delete_face` / `add_face`).

use super::common::add_faces_in_any_order;
use super::{ModelingError, faces_around_vertices};
use crate::ids::{EdgeId, FaceId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;
use std::collections::{BTreeSet, HashMap};

/// Bevels vertices (Blender's Ctrl+Shift+B, one segment): each vertex is
/// cut off by a new face through the points `width` along each of its
/// edges, so a cube corner becomes a triangle and a valence-5 vertex a
/// pentagon. Works at any valence and on borders (a border vertex with two
/// edges gets no cap: its corner is simply cut); neighbouring vertices may
/// both be beveled when `width` is under half their edge. The faces around
/// the vertices are taken out and added back with their new corners (pmp
/// `delete_face` / `add_face`); other elements keep their ids. Returns the
/// new cap faces.
///
/// # Errors
/// [`ModelingError::Empty`], [`ModelingError::Missing`],
/// [`ModelingError::Parameter`] for a width that is not positive or does
/// not fit an edge (naming it) or an isolated vertex; the mesh is unchanged
/// on error.
pub fn bevel_vertices(
    mesh: &mut HalfEdgeMesh,
    vertices: &[VertexId],
    width: f64,
) -> Result<Vec<FaceId>, ModelingError> {
    if vertices.is_empty() {
        return Err(ModelingError::Empty("no vertices"));
    }
    if !(width.is_finite() && width > 0.0) {
        return Err(ModelingError::Parameter {
            what: "width",
            allowed: "a finite width > 0",
            value: width.to_string(),
        });
    }
    let mut set: Vec<VertexId> = vertices.to_vec();
    set.sort();
    set.dedup();
    for &v in &set {
        if !mesh.is_vertex(v) {
            return Err(ModelingError::Missing(v.into()));
        }
        if mesh.is_isolated_vertex(v) {
            return Err(ModelingError::Parameter {
                what: "vertices",
                allowed: "vertices with edges",
                value: format!("{v} has none"),
            });
        }
        for h in mesh.vertex_outgoing(v) {
            let u = mesh.target(h);
            let share = if set.binary_search(&u).is_ok() {
                0.5
            } else {
                1.0
            };
            let length = mesh.position(u).distance(mesh.position(v));
            if width >= share * length {
                return Err(ModelingError::Parameter {
                    what: "width",
                    allowed: "less than the edges it cuts (half of those between beveled vertices)",
                    value: format!("{width} on {}, {length:.6} long", h.edge()),
                });
            }
        }
    }
    let mut work = mesh.clone();
    // The new point on each edge at each beveled vertex.
    let mut point: std::collections::HashMap<(VertexId, EdgeId), VertexId> = Default::default();
    for &v in &set {
        let p = work.position(v);
        let outgoing: Vec<HalfEdgeId> = work.vertex_outgoing(v).collect();
        for h in outgoing {
            let q = work.position(work.target(h));
            let id = work.add_vertex(p + (q - p).normalize() * width)?;
            point.insert((v, h.edge()), id);
        }
    }
    let faces = faces_around_vertices(&work, &set);
    let beveled = |v: VertexId| set.binary_search(&v).is_ok();
    let mut polygons = Vec::with_capacity(faces.len() + set.len());
    // Cap edges run against the faces' new edges: p_out(f) → p_in(f).
    let mut cap_next: std::collections::HashMap<VertexId, VertexId> = Default::default();
    for &f in &faces {
        let mut corners = Vec::new();
        for h in work.face_halfedges(f).collect::<Vec<_>>() {
            let v = work.origin(h);
            if beveled(v) {
                let p_in = point[&(v, work.prev(h).edge())];
                let p_out = point[&(v, h.edge())];
                corners.extend([p_in, p_out]);
                cap_next.insert(p_out, p_in);
            } else {
                corners.push(v);
            }
        }
        polygons.push(corners);
    }
    let face_count = polygons.len();
    for &v in &set {
        let mine: Vec<VertexId> = work
            .vertex_outgoing(v)
            .map(|h| point[&(v, h.edge())])
            .collect();
        // Start where the chain starts (a border vertex's chain is open).
        let start = mine
            .iter()
            .copied()
            .find(|p| !cap_next.values().any(|q| q == p))
            .unwrap_or(mine[0]);
        let mut cap = vec![start];
        while let Some(&next) = cap_next.get(cap.last().expect("not empty")) {
            if next == start || cap.len() > mine.len() {
                break;
            }
            cap.push(next);
        }
        if cap.len() >= 3 {
            polygons.push(cap);
        }
    }
    work.delete_faces(&faces, true);
    for &v in &set {
        work.free_vertex(v);
    }
    let added = add_faces_in_any_order(&mut work, polygons, "the bevel")?;
    work.validate()?;
    *mesh = work;
    Ok(added[face_count.min(added.len())..].to_vec())
}

/// Bevels edges (Blender's Ctrl+B) `width` wide, flat or rounded with
/// `segments`, at any valence and where beveled edges meet (see
/// `chamfer_edges`). Returns the new faces: the strips, then the patches.
///
/// # Errors
/// [`ModelingError::Parameter`] for a width that is not positive or too
/// large for the neighbouring edges, segments outside 1–32, a border edge
/// or end, or edges in line at a corner. The mesh is unchanged on error.
pub fn bevel_edges(
    mesh: &mut HalfEdgeMesh,
    edges: &[EdgeId],
    width: f64,
    segments: u32,
) -> Result<Vec<FaceId>, ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no edges"));
    }
    if !(1..=32).contains(&segments) {
        return Err(ModelingError::Parameter {
            what: "segments",
            allowed: "1 to 32",
            value: segments.to_string(),
        });
    }
    if !(width.is_finite() && width > 0.0) {
        return Err(ModelingError::Parameter {
            what: "width",
            allowed: "a finite width > 0",
            value: width.to_string(),
        });
    }
    if let Some(e) = edges.iter().find(|e| !mesh.is_edge(**e)) {
        return Err(ModelingError::Missing((*e).into()));
    }
    chamfer_edges(mesh, edges, width, segments)
}

/// Bevel of any set of edges (Blender's Ctrl+B, "offset" width): every
/// face corner at an end of a beveled edge moves into its face so that it
/// lies `width` from the beveled edges of that corner (the intersection of
/// the offset lines when both edges of the corner are beveled, a point slid
/// `width / sin θ` along the other edge when one is); each beveled edge
/// becomes `segments` strips between its two faces' new corners, bent at
/// each end on a quadratic Bézier arc whose control point is the old
/// vertex; where three or more new points surround an old vertex a patch
/// closes the gap (a fully beveled box corner gets a triangle; rounded, a
/// fan of triangles through the arcs to a raised centre). The old end vertices go; the faces
/// around them are taken out and added back (pmp `delete_face` /
/// `add_face`); other elements keep their ids.
///
/// The steps, in order (each adds its new vertices to `work` in turn, so
/// the ids come out as one pass would give them): check the edges and
/// find their [`ends`](chamfer_ends), [slide distances](Chamfer::slide_distances)
/// along unbeveled edges, [points](Chamfer::edge_points) on those edges,
/// the [new corners](Chamfer::face_corners) of the faces around the ends,
/// the [strips](Chamfer::strips) along the beveled edges, the
/// [patches](Chamfer::patches) at the ends; then the faces are swapped.
fn chamfer_edges(
    mesh: &mut HalfEdgeMesh,
    edges: &[EdgeId],
    width: f64,
    segments: u32,
) -> Result<Vec<FaceId>, ModelingError> {
    let beveled: BTreeSet<EdgeId> = edges.iter().copied().collect();
    let ends = chamfer_ends(mesh, &beveled)?;
    let chamfer = Chamfer {
        mesh: &*mesh,
        beveled,
        ends,
        width,
        segments,
    };
    let slide = chamfer.slide_distances()?;
    let mut work = mesh.clone();
    let point_on = chamfer.edge_points(&mut work, &slide)?;
    let faces = faces_around_vertices(mesh, &chamfer.ends.iter().copied().collect::<Vec<_>>());
    let (corner_of, mut polygons) = chamfer.face_corners(&mut work, &faces, &point_on)?;
    let mut arcs = ArcCache::new();
    let strips = chamfer.strips(&mut work, &mut arcs, &corner_of);
    let patches = chamfer.patches(
        &mut work,
        &mut arcs,
        &faces,
        &corner_of,
        &point_on,
        &mut polygons,
    )?;
    let n_faces = polygons.len();
    polygons.extend(strips);
    polygons.extend(patches);
    work.delete_faces(&faces, true);
    for &v in &chamfer.ends {
        work.free_vertex(v);
    }
    let added = add_faces_in_any_order(&mut work, polygons, "the bevel")?;
    work.validate()?;
    *mesh = work;
    Ok(added[n_faces.min(added.len())..].to_vec())
}

/// The end vertices of the beveled edges; refuses an edge on a boundary
/// or an end on one.
fn chamfer_ends(
    mesh: &HalfEdgeMesh,
    beveled: &BTreeSet<EdgeId>,
) -> Result<BTreeSet<VertexId>, ModelingError> {
    let mut ends: BTreeSet<VertexId> = BTreeSet::new();
    for &e in beveled {
        let h = e.halfedge(0);
        if mesh.face(h).is_none() || mesh.face(h.twin()).is_none() {
            return Err(ModelingError::Parameter {
                what: "edge",
                allowed: "an edge between two faces",
                value: format!("{e} is on a boundary"),
            });
        }
        ends.extend(mesh.edge_vertices(e));
    }
    if let Some(v) = ends.iter().find(|v| mesh.is_boundary_vertex(**v)) {
        return Err(ModelingError::Parameter {
            what: "edge ends",
            allowed: "vertices inside the surface",
            value: format!("{v} is on a boundary"),
        });
    }
    Ok(ends)
}

/// Unit direction from one vertex to another.
fn dir(m: &HalfEdgeMesh, from: VertexId, to: VertexId) -> DVec3 {
    (m.position(to) - m.position(from)).normalize()
}

/// Sine of the angle between two unit vectors.
fn sin_between(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length()
}

/// Per unbeveled edge at an end: the summed slide distances asked for and
/// how many faces asked.
type SlideMap = HashMap<(VertexId, EdgeId), (f64, u32)>;
/// The new point on each unbeveled edge at each end.
type PointMap = HashMap<(VertexId, EdgeId), VertexId>;
/// The point a face's corner at an end became (one point per corner).
type CornerMap = HashMap<(FaceId, VertexId), VertexId>;
/// The inner points of each rounded arc, keyed by the end and its two
/// corner points in id order, so edges in line share their arcs.
type ArcCache = HashMap<(VertexId, VertexId, VertexId), Vec<VertexId>>;

/// What one edge bevel works on: the mesh as it was, the beveled edges and
/// their ends, and the parameters.
struct Chamfer<'a> {
    mesh: &'a HalfEdgeMesh,
    beveled: BTreeSet<EdgeId>,
    ends: BTreeSet<VertexId>,
    width: f64,
    segments: u32,
}

impl Chamfer<'_> {
    /// Distance along each unbeveled edge at an end where faces slide their
    /// corner (w / sin θ to the beveled edge of that face; the mean when both
    /// faces of the edge ask).
    fn slide_distances(&self) -> Result<SlideMap, ModelingError> {
        let mesh = self.mesh;
        let mut slide: SlideMap = HashMap::new();
        for &v in &self.ends {
            for h in mesh.vertex_outgoing(v).collect::<Vec<_>>() {
                // In face(h) the corner at v is between prev(h) (in) and h (out).
                let (e_in, e_out) = (mesh.prev(h).edge(), h.edge());
                let (u_in, u_out) = (
                    dir(mesh, v, mesh.origin(mesh.prev(h))),
                    dir(mesh, v, mesh.target(h)),
                );
                let sin = sin_between(u_in, u_out);
                let (b_in, b_out) = (self.beveled.contains(&e_in), self.beveled.contains(&e_out));
                let slid = match (b_in, b_out) {
                    (false, true) => Some(e_in),
                    (true, false) => Some(e_out),
                    _ => None,
                };
                if let Some(e) = slid {
                    if sin < 1e-9 {
                        return Err(ModelingError::Parameter {
                            what: "edges",
                            allowed: "edges at an angle to their neighbours",
                            value: format!("{e_in} and {e_out} are in line at {v}"),
                        });
                    }
                    let entry = slide.entry((v, e)).or_insert((0.0, 0));
                    entry.0 += self.width / sin;
                    entry.1 += 1;
                }
            }
        }
        Ok(slide)
    }

    /// The new point on every unbeveled edge at an end (at the slide
    /// distance, else `width` along it); refuses when the points of both
    /// ends would meet on an edge.
    fn edge_points(
        &self,
        work: &mut HalfEdgeMesh,
        slide: &SlideMap,
    ) -> Result<PointMap, ModelingError> {
        let (mesh, width) = (self.mesh, self.width);
        let mut point_on: PointMap = HashMap::new();
        let mut used_length: HashMap<EdgeId, f64> = HashMap::new();
        for &v in &self.ends {
            for h in mesh.vertex_outgoing(v) {
                let e = h.edge();
                if self.beveled.contains(&e) {
                    continue;
                }
                let t = slide
                    .get(&(v, e))
                    .map_or(width, |(sum, n)| sum / f64::from(*n));
                *used_length.entry(e).or_default() += t;
                let p = mesh.position(v) + dir(mesh, v, mesh.target(h)) * t;
                point_on.insert((v, e), work.add_vertex(p)?);
            }
        }
        for (&e, &used) in &used_length {
            let [a, b] = mesh.edge_vertices(e);
            let length = mesh.position(a).distance(mesh.position(b));
            if used >= length * (1.0 - 1e-9) {
                return Err(ModelingError::Parameter {
                    what: "width",
                    allowed: "small enough for the neighbouring edges",
                    value: format!("{width} needs {used:.6} of {e}, {length:.6} long"),
                });
            }
        }
        Ok(point_on)
    }

    /// New corners of every face around the ends, as the faces' new
    /// polygons; `corner_of[(f, v)]` is the point a corner at v became (for
    /// the quads).
    fn face_corners(
        &self,
        work: &mut HalfEdgeMesh,
        faces: &[FaceId],
        point_on: &PointMap,
    ) -> Result<(CornerMap, Vec<Vec<VertexId>>), ModelingError> {
        let mesh = self.mesh;
        let mut corner_of: CornerMap = HashMap::new();
        let mut polygons = Vec::new();
        for &f in faces {
            let mut corners = Vec::new();
            for h in mesh.face_halfedges(f).collect::<Vec<_>>() {
                let v = mesh.origin(h);
                if !self.ends.contains(&v) {
                    corners.push(v);
                    continue;
                }
                let hin = mesh.prev(h);
                let (e_in, e_out) = (hin.edge(), h.edge());
                match (self.beveled.contains(&e_in), self.beveled.contains(&e_out)) {
                    (true, true) => {
                        let (u_in, u_out) =
                            (dir(mesh, v, mesh.origin(hin)), dir(mesh, v, mesh.target(h)));
                        let sin = sin_between(u_in, u_out);
                        if sin < 1e-9 {
                            return Err(ModelingError::Parameter {
                                what: "edges",
                                allowed: "beveled edges at an angle",
                                value: format!("{e_in} and {e_out} are in line at {v}"),
                            });
                        }
                        let q = mesh.position(v) + (u_in + u_out) * (self.width / sin);
                        let id = work.add_vertex(q)?;
                        corner_of.insert((f, v), id);
                        corners.push(id);
                    }
                    (false, true) => {
                        let id = point_on[&(v, e_in)];
                        corner_of.insert((f, v), id);
                        corners.push(id);
                    }
                    (true, false) => {
                        let id = point_on[&(v, e_out)];
                        corner_of.insert((f, v), id);
                        corners.push(id);
                    }
                    (false, false) => {
                        corners.push(point_on[&(v, e_in)]);
                        corners.push(point_on[&(v, e_out)]);
                    }
                }
            }
            polygons.push(corners);
        }
        Ok((corner_of, polygons))
    }

    /// Rounded bevels: at each end the cap edge between the two new corners
    /// bends into a quadratic Bézier arc with the old vertex as control
    /// point (B(½) = c₁/4 + v/2 + c₂/4). Edges in line share their corners
    /// at a vertex, so the arc is keyed by the corner pair and shared too.
    /// Returns the arc's inner points from `from` to `to` (none for one
    /// segment).
    fn arc(
        &self,
        arcs: &mut ArcCache,
        work: &mut HalfEdgeMesh,
        v: VertexId,
        from: VertexId,
        to: VertexId,
    ) -> Vec<VertexId> {
        let segments = self.segments;
        let key = (v, from.min(to), from.max(to));
        let mut inner = arcs
            .entry(key)
            .or_insert_with(|| {
                let (c1, c2) = (work.position(key.1), work.position(key.2));
                let control = self.mesh.position(v);
                (1..segments)
                    .map(|k| {
                        let t = f64::from(k) / f64::from(segments);
                        let p = c1 * (1.0 - t) * (1.0 - t)
                            + control * (2.0 * t * (1.0 - t))
                            + c2 * t * t;
                        work.add_vertex(p).expect("finite")
                    })
                    .collect()
            })
            .clone();
        if from > to {
            inner.reverse();
        }
        inner
    }

    /// The `segments` quads along each beveled edge, between its two faces'
    /// new corners (and the arcs at its ends).
    fn strips(
        &self,
        work: &mut HalfEdgeMesh,
        arcs: &mut ArcCache,
        corner_of: &CornerMap,
    ) -> Vec<Vec<VertexId>> {
        let mesh = self.mesh;
        let mut strips = Vec::new();
        for &e in &self.beveled {
            let h = e.halfedge(0);
            let t = h.twin();
            let (a, b) = (mesh.origin(h), mesh.target(h));
            let (fh, ft) = (
                mesh.face(h).expect("checked"),
                mesh.face(t).expect("checked"),
            );
            let side = |work: &mut HalfEdgeMesh, arcs: &mut ArcCache, v: VertexId| {
                let (from, to) = (corner_of[&(fh, v)], corner_of[&(ft, v)]);
                let mut points = vec![from];
                points.extend(self.arc(arcs, work, v, from, to));
                points.push(to);
                points
            };
            let along_a = side(work, arcs, a);
            let along_b = side(work, arcs, b);
            for k in 0..self.segments as usize {
                strips.push(vec![along_a[k], along_a[k + 1], along_b[k + 1], along_b[k]]);
            }
        }
        strips
    }

    /// Patches: the new points around each end in fan order, when three or
    /// more distinct ones leave a gap. The fan turns from a face to the one
    /// across its incoming edge, so listing each face's out point before its
    /// in point runs every edge of the gap against its face; crossing a
    /// beveled edge, the gap follows that edge's arc. With only two points
    /// the arcs meet each other, or the one face cut between them (a box
    /// end) takes the arc as its new side (in `polygons`).
    fn patches(
        &self,
        work: &mut HalfEdgeMesh,
        arcs: &mut ArcCache,
        faces: &[FaceId],
        corner_of: &CornerMap,
        point_on: &PointMap,
        polygons: &mut [Vec<VertexId>],
    ) -> Result<Vec<Vec<VertexId>>, ModelingError> {
        let mesh = self.mesh;
        let mut patches = Vec::new();
        for &v in &self.ends {
            let (ring, distinct) = self.ring_around(work, arcs, corner_of, point_on, v);
            if distinct.len() >= 3 && self.segments == 1 {
                patches.push(ring);
            } else if distinct.len() >= 3 {
                // Rounded: a fan of triangles to a centre raised towards the old
                // vertex as the arcs are (half-way from the corners' centroid),
                // instead of one flat n-gon.
                let centroid = distinct.iter().map(|&p| work.position(p)).sum::<DVec3>()
                    / distinct.len() as f64;
                let centre = work.add_vertex(centroid + (mesh.position(v) - centroid) * 0.5)?;
                for i in 0..ring.len() {
                    patches.push(vec![ring[i], ring[(i + 1) % ring.len()], centre]);
                }
            } else if self.segments > 1 {
                self.round_cut_corners(work, arcs, faces, corner_of, point_on, polygons, v);
            }
        }
        Ok(patches)
    }

    /// The new points around end `v` in fan order (each face's out point
    /// before its in point, and across a beveled edge its arc), without
    /// repeats, and the set of distinct corner points among them.
    fn ring_around(
        &self,
        work: &mut HalfEdgeMesh,
        arcs: &mut ArcCache,
        corner_of: &CornerMap,
        point_on: &PointMap,
        v: VertexId,
    ) -> (Vec<VertexId>, BTreeSet<VertexId>) {
        let mesh = self.mesh;
        let fan: Vec<HalfEdgeId> = mesh.vertex_outgoing(v).collect();
        let mut ring: Vec<VertexId> = Vec::new();
        let mut distinct = BTreeSet::new();
        for (i, &h) in fan.iter().enumerate() {
            let f = mesh.face(h).expect("inside the surface");
            let e_in = mesh.prev(h).edge();
            let mut pts: Vec<VertexId> = match corner_of.get(&(f, v)) {
                Some(&p) => vec![p],
                None => vec![point_on[&(v, h.edge())], point_on[&(v, e_in)]],
            };
            distinct.extend(pts.iter().copied());
            if self.beveled.contains(&e_in) {
                let g = mesh
                    .face(fan[(i + 1) % fan.len()])
                    .expect("inside the surface");
                let (from, to) = (corner_of[&(f, v)], corner_of[&(g, v)]);
                pts.extend(self.arc(arcs, work, v, from, to));
            }
            for p in pts {
                if ring.last() != Some(&p) {
                    ring.push(p);
                }
            }
        }
        while ring.len() > 1 && ring.first() == ring.last() {
            ring.pop();
        }
        (ring, distinct)
    }

    /// Rounded bevel with two points at `v`: each face around `v` that
    /// kept no corner there (it was cut between two edge points) takes the
    /// arc between them as its new side.
    #[allow(clippy::too_many_arguments)]
    fn round_cut_corners(
        &self,
        work: &mut HalfEdgeMesh,
        arcs: &mut ArcCache,
        faces: &[FaceId],
        corner_of: &CornerMap,
        point_on: &PointMap,
        polygons: &mut [Vec<VertexId>],
        v: VertexId,
    ) {
        let mesh = self.mesh;
        for (i, &f) in faces.iter().enumerate() {
            if corner_of.contains_key(&(f, v)) || !mesh.face_vertices(f).any(|x| x == v) {
                continue;
            }
            let h = mesh
                .face_halfedges(f)
                .find(|&h| mesh.origin(h) == v)
                .expect("a corner at v");
            let (p_in, p_out) = (
                point_on[&(v, mesh.prev(h).edge())],
                point_on[&(v, h.edge())],
            );
            let inner = self.arc(arcs, work, v, p_in, p_out);
            let poly = &mut polygons[i];
            let at = poly
                .iter()
                .position(|&x| x == p_in)
                .expect("the cut is in the face");
            poly.splice(at + 1..at + 1, inner);
        }
    }
}
