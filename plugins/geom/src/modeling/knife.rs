//! Knife (Blender's K, without cut-through): cutting faces along a path of
//! points clicked on the surface, built from Euler MVE (split an edge where
//! the path crosses it), MEF (split a face between its entry and exit
//! vertices) and MEV/KEV (a path point strictly inside a face).
//!
//! The model is Blender's `editmesh_knife.cc`: two consecutive points and
//! the view direction span a "curtain", the part of the plane through the
//! segment and the view between the two points; the cut is where the
//! curtain meets the faces it reaches by walking across the surface from
//! the first point. Only the faces on that walk are cut (Blender without
//! cut-through), so a cut across a cube's front face leaves its back face
//! whole.

use super::ModelingError;
use crate::ids::{EdgeId, FaceId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;

/// What [`knife`] made: what Blender selects after a knife cut.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct KnifeResult {
    /// The vertices the cut made: where it crossed or ended on an edge, and
    /// the path's points kept inside faces, in the order they were made.
    pub new_vertices: Vec<VertexId>,
    /// The edges along the cut, in path order: the new edges splitting the
    /// crossed faces, and existing edges the cut ran along.
    pub cut_edges: Vec<EdgeId>,
}

/// How far from the surface a path point may be, relative to the size of
/// the mesh's bounding box (a viewport pick in `f32` is that close).
const SURFACE_TOLERANCE: f64 = 1e-5;
/// How far from the curtain a vertex may be and still count as on it,
/// relative to the mesh's size (as [`bisect`](super::bisect)).
const PLANE_TOLERANCE: f64 = 1e-9;

/// Cuts the mesh along the path `points` seen along `view` (Blender's
/// Knife, K, then Enter; without cut-through). Points and view are in the
/// mesh's own space; each point lies on a face, or on an edge or a vertex
/// (a point within `1e-5 ×` the mesh's size of a vertex is that vertex, of
/// an edge is on that edge).
///
/// For each pair of consecutive points the cut starts where the first point
/// lies and walks across the surface along the curtain (the plane through
/// the two points containing `view`, between them): in the current face it
/// finds where the curtain leaves it ahead of the walk, splits that edge
/// there (MVE; an existing vertex on the curtain is used as it is), splits
/// the face from its entry to that exit (MEF) and enters the face on the
/// other side, until it reaches the face, edge or vertex of the second
/// point. When the walk reaches a boundary edge, or can go no further,
/// before the second point, that segment stops there and the next one
/// starts afresh at the second point (Blender's cut also ends where the
/// surface does). Where a vertex offers several faces ahead, the one facing
/// the viewer is taken.
///
/// Points strictly inside a face: a point between two cuts of the same face
/// becomes a vertex of the split (the path bends there, as in Blender). A
/// point at an end of the path (or of a part of it cut off by a boundary)
/// would leave a dangling edge inside the face, which Blender keeps but
/// Hedra does not: `validate` accepts such a spike (MEV makes one), but
/// triangulation (ear clipping of the face's corner list), subdivision and
/// export read each face's loop as a simple polygon, and a spike visits its
/// base vertex twice. Such ends are dropped (KEV), so the cut starts and
/// ends at the first and last edge it crosses; an end on an edge still
/// splits that edge.
///
/// Segments of zero length, or seen end-on along `view`, cut nothing and
/// are skipped.
///
/// Inverse: none as one operator; each MEF is undone by
/// [`kill_edge_face`](HalfEdgeMesh::kill_edge_face), each MVE by
/// [`join_edges`](HalfEdgeMesh::join_edges).
///
/// # Errors
/// [`ModelingError::Parameter`] for fewer than two points, a non-finite
/// point or a zero or non-finite view; [`ModelingError::NotOnSurface`]
/// naming the first point farther than the tolerance from every face;
/// [`ModelingError::NothingToCut`] when the path splits no edge and no
/// face (two points inside one face). The mesh is unchanged on error.
///
/// Complexity: O(V + E + F) per point to locate it, plus O(face degree ×
/// faces around a vertex) per step of the walk.
pub fn knife(
    mesh: &mut HalfEdgeMesh,
    points: &[DVec3],
    view: DVec3,
) -> Result<KnifeResult, ModelingError> {
    if points.len() < 2 {
        return Err(ModelingError::Parameter {
            what: "knife points",
            allowed: "at least 2",
            value: points.len().to_string(),
        });
    }
    if let Some((i, p)) = points.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(ModelingError::Parameter {
            what: "knife point",
            allowed: "finite",
            value: format!("point {i} at {p}"),
        });
    }
    let view = view.normalize_or_zero();
    if view == DVec3::ZERO || !view.is_finite() {
        return Err(ModelingError::Parameter {
            what: "view direction",
            allowed: "finite and non-zero",
            value: format!("{view}"),
        });
    }
    let size = mesh
        .bounds()
        .map_or(1.0, |(lo, hi)| lo.distance(hi))
        .max(f64::MIN_POSITIVE);
    let tol = Tolerance {
        surface: SURFACE_TOLERANCE * size,
        plane: PLANE_TOLERANCE * size,
    };
    // Every point must be on the surface; snap it onto the vertex, edge or
    // face it lies on, so that the curtains pass exactly through them.
    let mut snapped = Vec::with_capacity(points.len());
    for (index, &point) in points.iter().enumerate() {
        let (_, p) =
            locate(mesh, point, tol.surface).ok_or(ModelingError::NotOnSurface { index, point })?;
        snapped.push(p);
    }

    let mut cut = Cut {
        work: mesh.clone(),
        out: KnifeResult::default(),
        tol,
        view,
    };
    // The vertex the previous segment's walk ended on, if it reached its
    // second point.
    let mut reached: Option<VertexId> = None;
    for pair in snapped.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if a.distance(b) <= tol.surface {
            continue;
        }
        let Some(curtain) = Curtain::new(a, b, view, tol) else {
            reached = None;
            continue;
        };
        reached = cut.segment(&curtain, reached)?;
    }
    cut.drop_dangling_ends()?;
    let Cut { work, out, .. } = cut;
    if out.new_vertices.is_empty() && out.cut_edges.is_empty() {
        return Err(ModelingError::NothingToCut);
    }
    work.validate()?;
    *mesh = work;
    Ok(out)
}

/// The tolerances, in the mesh's units.
#[derive(Copy, Clone, Debug)]
struct Tolerance {
    /// How far a point may be from the surface, a vertex or an edge.
    surface: f64,
    /// How far a vertex may be from a curtain and count as on it.
    plane: f64,
}

/// The cutting curtain of one segment `a`–`b`: the plane through them
/// containing the view direction, with the parameter `s` running from 0 at
/// `a` to 1 at `b` across the view.
struct Curtain {
    a: DVec3,
    b: DVec3,
    /// The plane's unit normal.
    normal: DVec3,
    /// `(b − a)` without its component along the view, divided by its
    /// squared length: `s(p) = (p − a) · across`.
    across: DVec3,
    /// The least step in `s` that counts as moving ahead.
    ahead: f64,
}

impl Curtain {
    /// `None` when the segment is seen end-on (no curtain).
    fn new(a: DVec3, b: DVec3, view: DVec3, tol: Tolerance) -> Option<Curtain> {
        let d = b - a;
        let flat = d - view * d.dot(view);
        let length = flat.length();
        if length <= tol.surface {
            return None;
        }
        Some(Curtain {
            a,
            b,
            normal: flat.cross(view).normalize(),
            across: flat / (length * length),
            ahead: tol.plane / length,
        })
    }

    /// Signed distance of `p` from the plane.
    fn side(&self, p: DVec3) -> f64 {
        (p - self.a).dot(self.normal)
    }

    /// Where `p` is between the two points: 0 at `a`, 1 at `b`.
    fn s(&self, p: DVec3) -> f64 {
        (p - self.a).dot(self.across)
    }
}

/// Where a point lies on the whole mesh.
#[derive(Copy, Clone, Debug, PartialEq)]
enum Spot {
    /// On (within tolerance of) a vertex.
    Vertex(VertexId),
    /// On an edge, away from its ends.
    Edge(EdgeId),
    /// Strictly inside a face.
    Face(FaceId),
}

/// Where a point lies relative to one face.
#[derive(Copy, Clone, Debug, PartialEq)]
enum InFace {
    /// On a corner of the face.
    Corner(VertexId),
    /// On a side of the face (the half-edge of the face), at the point.
    Side(HalfEdgeId, DVec3),
    /// Strictly inside the face.
    Inside,
}

/// Where the curtain leaves a face ahead of the walk.
#[derive(Copy, Clone, Debug, PartialEq)]
enum Exit {
    /// Through an existing vertex on the curtain.
    Corner(VertexId),
    /// Across a side of the face, at the point.
    Side(HalfEdgeId, DVec3),
}

/// The closest point to `p` on the segment `a`–`b`.
fn closest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let d = b - a;
    let t = if d.length_squared() > 0.0 {
        ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    a + d * t
}

/// `p` projected onto the plane of face `f`, if it is within `tol` of the
/// plane and inside the face's outline (crossing-number test in the plane,
/// as Blender's `isect_point_poly_v2`).
fn inside_face(mesh: &HalfEdgeMesh, f: FaceId, p: DVec3, tol: f64) -> Option<DVec3> {
    let normal = mesh.face_normal(f);
    if normal == DVec3::ZERO {
        return None;
    }
    let centre = mesh.face_centroid(f);
    let height = (p - centre).dot(normal);
    if height.abs() > tol {
        return None;
    }
    let q = p - normal * height;
    let (x_axis, y_axis) = normal.any_orthonormal_pair();
    let flat = |v: DVec3| ((v - q).dot(x_axis), (v - q).dot(y_axis));
    let mut inside = false;
    for h in mesh.face_halfedges(f) {
        let (x0, y0) = flat(mesh.position(mesh.origin(h)));
        let (x1, y1) = flat(mesh.position(mesh.target(h)));
        if (y0 > 0.0) != (y1 > 0.0) && x0 + (x1 - x0) * (-y0 / (y1 - y0)) > 0.0 {
            inside = !inside;
        }
    }
    inside.then_some(q)
}

/// Where `p` lies on the mesh, and `p` snapped there; `None` when it is
/// farther than `tol` from every face. Vertices come before edges, edges
/// before faces; among faces, the one whose plane is nearest.
fn locate(mesh: &HalfEdgeMesh, p: DVec3, tol: f64) -> Option<(Spot, DVec3)> {
    let nearest_vertex = mesh
        .vertices()
        .filter(|&v| !mesh.is_isolated_vertex(v))
        .map(|v| (v, mesh.position(v).distance(p)))
        .min_by(|x, y| x.1.total_cmp(&y.1));
    if let Some((v, d)) = nearest_vertex
        && d <= tol
    {
        return Some((Spot::Vertex(v), mesh.position(v)));
    }
    let nearest_edge = mesh
        .edges()
        .map(|e| {
            let [a, b] = mesh.edge_vertices(e);
            let q = closest_on_segment(p, mesh.position(a), mesh.position(b));
            (e, q, q.distance(p))
        })
        .min_by(|x, y| x.2.total_cmp(&y.2));
    if let Some((e, q, d)) = nearest_edge
        && d <= tol
    {
        return Some((Spot::Edge(e), q));
    }
    mesh.faces()
        .filter_map(|f| inside_face(mesh, f, p, tol).map(|q| (f, q, q.distance(p))))
        .min_by(|x, y| x.2.total_cmp(&y.2))
        .map(|(f, q, _)| (Spot::Face(f), q))
}

/// Where `p` lies relative to face `f`, or `None` when it is not on it.
fn locate_in_face(mesh: &HalfEdgeMesh, f: FaceId, p: DVec3, tol: f64) -> Option<InFace> {
    if let Some(v) = mesh
        .face_vertices(f)
        .find(|&v| mesh.position(v).distance(p) <= tol)
    {
        return Some(InFace::Corner(v));
    }
    for h in mesh.face_halfedges(f) {
        let (a, b) = (mesh.position(mesh.origin(h)), mesh.position(mesh.target(h)));
        let q = closest_on_segment(p, a, b);
        if q.distance(p) <= tol {
            return Some(InFace::Side(h, q));
        }
    }
    inside_face(mesh, f, p, tol).map(|_| InFace::Inside)
}

/// The cut under way: the mesh being cut and what was made so far.
struct Cut {
    work: HalfEdgeMesh,
    out: KnifeResult,
    tol: Tolerance,
    view: DVec3,
}

impl Cut {
    /// Cuts one segment, starting at `start` (the vertex the previous
    /// segment ended on) or else wherever the curtain's first point lies.
    /// Returns the vertex at the second point when the walk reached it.
    fn segment(
        &mut self,
        curtain: &Curtain,
        start: Option<VertexId>,
    ) -> Result<Option<VertexId>, ModelingError> {
        let from = match start {
            Some(v) => v,
            None => match locate(&self.work, curtain.a, self.tol.surface) {
                Some((Spot::Vertex(v), _)) => v,
                Some((Spot::Edge(e), p)) => self.split(e, p)?,
                Some((Spot::Face(f), _)) => match self.leave_from_inside(curtain, f)? {
                    Walk::Continue(v) => v,
                    Walk::Reached(v) => return Ok(v),
                },
                // Snapped points are on the surface; the walk cannot
                // have moved them off it.
                None => return Ok(None),
            },
        };
        self.walk(curtain, from)
    }

    /// The first step from a point strictly inside face `f`: to where the
    /// second point lies if it is on `f`, else to where the curtain leaves
    /// `f` ahead. The inside point itself gets no vertex (it would dangle).
    fn leave_from_inside(&mut self, curtain: &Curtain, f: FaceId) -> Result<Walk, ModelingError> {
        match locate_in_face(&self.work, f, curtain.b, self.tol.surface) {
            Some(InFace::Corner(v)) => return Ok(Walk::Reached(Some(v))),
            Some(InFace::Side(h, p)) => return Ok(Walk::Reached(Some(self.split(h.edge(), p)?))),
            Some(InFace::Inside) => return Ok(Walk::Reached(None)),
            None => {}
        }
        match self.exit_ahead(curtain, f, None, 0.0) {
            Some((Exit::Corner(v), s)) if s <= 1.0 + curtain.ahead => Ok(Walk::Continue(v)),
            Some((Exit::Side(h, p), s)) if s <= 1.0 + curtain.ahead => {
                Ok(Walk::Continue(self.split(h.edge(), p)?))
            }
            _ => Ok(Walk::Reached(None)),
        }
    }

    /// Walks from vertex `from` along the curtain to its second point,
    /// cutting every face on the way. Returns the vertex at the second point,
    /// or `None` when the walk stopped before it (a boundary, or no face
    /// ahead).
    fn walk(
        &mut self,
        curtain: &Curtain,
        mut from: VertexId,
    ) -> Result<Option<VertexId>, ModelingError> {
        let limit = 4 * (self.work.edge_count() + 4);
        for _ in 0..limit {
            let here = self.work.position(from);
            if here.distance(curtain.b) <= self.tol.surface {
                return Ok(Some(from));
            }
            let mut faces: Vec<FaceId> = self.work.vertex_faces(from).collect();
            faces.sort();
            faces.dedup();
            // Faces facing the viewer first.
            faces.sort_by_key(|&f| self.work.face_normal(f).dot(self.view) >= 0.0);
            // The second point on a face around: cut straight to it.
            let target = faces.iter().find_map(|&f| {
                locate_in_face(&self.work, f, curtain.b, self.tol.surface).map(|spot| (f, spot))
            });
            if let Some((f, spot)) = target {
                let end = match spot {
                    InFace::Corner(v) => v,
                    InFace::Side(h, p) => self.split(h.edge(), p)?,
                    InFace::Inside => self.point_inside(f, from, curtain.b)?,
                };
                if end != from && spot != InFace::Inside {
                    self.connect(f, from, end)?;
                }
                return Ok(Some(end));
            }
            // Else the face around whose exit is nearest ahead.
            let s_here = curtain.s(here);
            let mut best: Option<(FaceId, Exit, f64, bool)> = None;
            for &f in &faces {
                let Some((exit, s)) = self.exit_ahead(curtain, f, Some(from), s_here) else {
                    continue;
                };
                let front = self.work.face_normal(f).dot(self.view) < 0.0;
                let better = match best {
                    None => true,
                    Some((_, _, best_s, best_front)) => {
                        (front && !best_front) || (front == best_front && s < best_s)
                    }
                };
                if better {
                    best = Some((f, exit, s, front));
                }
            }
            let Some((f, exit, s, _)) = best else {
                return Ok(None);
            };
            if s > 1.0 + curtain.ahead {
                // Past the second point without meeting it: it is not on
                // this walk.
                return Ok(None);
            }
            let next = match exit {
                Exit::Corner(v) => v,
                Exit::Side(h, p) => self.split(h.edge(), p)?,
            };
            self.connect(f, from, next)?;
            from = next;
        }
        Ok(None)
    }

    /// Where the curtain leaves face `f` nearest ahead of `s_here` (and not
    /// at `from`), with its `s`.
    fn exit_ahead(
        &self,
        curtain: &Curtain,
        f: FaceId,
        from: Option<VertexId>,
        s_here: f64,
    ) -> Option<(Exit, f64)> {
        let m = &self.work;
        let eps = self.tol.plane;
        let mut best: Option<(Exit, f64)> = None;
        let mut offer = |exit: Exit, s: f64| {
            if s > s_here + curtain.ahead && best.is_none_or(|(_, b)| s < b) {
                best = Some((exit, s));
            }
        };
        for h in m.face_halfedges(f) {
            let (o, t) = (m.origin(h), m.target(h));
            let (po, pt) = (m.position(o), m.position(t));
            let (d_o, d_t) = (curtain.side(po), curtain.side(pt));
            if d_t.abs() <= eps && Some(t) != from {
                offer(Exit::Corner(t), curtain.s(pt));
            }
            if (d_o > eps && d_t < -eps) || (d_o < -eps && d_t > eps) {
                let p = po + (pt - po) * (d_o / (d_o - d_t));
                offer(Exit::Side(h, p), curtain.s(p));
            }
        }
        best
    }

    /// Splits edge `e` at `p` (MVE). A cut edge split again (a path crossing
    /// itself) stays cut in both halves.
    fn split(&mut self, e: EdgeId, p: DVec3) -> Result<VertexId, ModelingError> {
        let end = self.work.edge_vertices(e)[1];
        let v = self.work.split_edge(e, p)?;
        self.out.new_vertices.push(v);
        if self.out.cut_edges.contains(&e)
            && let Some(rest) = self.work.find_edge(v, end)
        {
            self.out.cut_edges.push(rest);
        }
        Ok(v)
    }

    /// A vertex at `p` inside face `f`, joined to its corner `from` by a
    /// dangling edge (MEV); the next segment's cut, or
    /// [`drop_dangling_ends`](Self::drop_dangling_ends), finishes it.
    fn point_inside(
        &mut self,
        f: FaceId,
        from: VertexId,
        p: DVec3,
    ) -> Result<VertexId, ModelingError> {
        let m = &self.work;
        let h_in = m
            .face_halfedges(f)
            .find(|&h| m.target(h) == from)
            .ok_or(ModelingError::NotConnectable { a: from, b: from })?;
        let (e, v) = self.work.make_edge_vertex(h_in, p)?;
        self.out.new_vertices.push(v);
        self.out.cut_edges.push(e);
        Ok(v)
    }

    /// Splits face `f` between its corners `a` and `b` (MEF), or records
    /// the edge already joining them.
    fn connect(&mut self, f: FaceId, a: VertexId, b: VertexId) -> Result<(), ModelingError> {
        let m = &self.work;
        if let Some(e) = m.find_edge(a, b) {
            if !self.out.cut_edges.contains(&e) {
                self.out.cut_edges.push(e);
            }
            return Ok(());
        }
        let into = |v: VertexId| m.face_halfedges(f).find(|&h| m.target(h) == v);
        let (Some(ha), Some(hb)) = (into(a), into(b)) else {
            return Err(ModelingError::NotConnectable { a, b });
        };
        let (e, _) = self.work.make_edge_face(ha, hb)?;
        self.out.cut_edges.push(e);
        Ok(())
    }

    /// Removes the edges left dangling inside faces by path ends strictly
    /// inside a face (KEV), back to the first edge the cut crossed.
    fn drop_dangling_ends(&mut self) -> Result<(), ModelingError> {
        while let Some(v) = self
            .out
            .new_vertices
            .iter()
            .copied()
            .find(|&v| self.work.vertex_valence(v) == 1)
        {
            let Some(h) = self.work.vertex_outgoing(v).next() else {
                break;
            };
            self.work.kill_edge_vertex(h.edge())?;
            self.out.new_vertices.retain(|&w| w != v);
            self.out.cut_edges.retain(|&e| e != h.edge());
        }
        Ok(())
    }
}

/// How the first step from a point inside a face ended.
enum Walk {
    /// The walk goes on from this vertex.
    Continue(VertexId),
    /// The segment is done: at the second point's vertex, or nowhere.
    Reached(Option<VertexId>),
}
