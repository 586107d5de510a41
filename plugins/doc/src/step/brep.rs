//! Boundary representation of NURBS patches: each patch becomes an
//! `ADVANCED_FACE` bounded by one `EDGE_LOOP` of its four iso-boundaries
//! (a boundary that collapses to a point, a pole, is left out of the
//! loop), each cut at the corners of other patches that lie on it (a long
//! side beside several short ones, a T-junction: the loop then has more
//! than four edges); edges whose curves coincide (within a tolerance) are one
//! `EDGE_CURVE` shared by the faces that meet there, and their end points
//! one `VERTEX_POINT` (an edge bounds at most two faces, which run along
//! it in opposite directions). Patches joined through shared edges form one shell:
//! a `CLOSED_SHELL` in a `MANIFOLD_SOLID_BREP` when every edge is used
//! exactly twice, once in each direction (watertight and orientable), else
//! an `OPEN_SHELL` in a `SHELL_BASED_SURFACE_MODEL`.
//!
//! A solid's faces face outwards: when the signed volume the patches
//! enclose (measured on a grid of their points) is negative, every face
//! is written with `same_sense = .F.` (its normal is the reverse of the
//! surface's `S_u × S_v`).

use super::write::{StepWriter, list, logical, r, string};
use glam::DVec3;
use hedra_geom::curves::Curve;
use hedra_geom::surfaces::Surface;
use hedra_geom::{NurbsCurve, NurbsSurface};
use std::collections::HashMap;

/// One patch to write: its face's name and its surface (in the file's
/// coordinates).
#[derive(Clone, Copy, Debug)]
pub struct Patch<'a> {
    /// The face's name (the node's).
    pub name: &'a str,
    /// The surface.
    pub surface: &'a NurbsSurface,
}

/// What [`write_shells`] wrote for one connected group of patches.
#[derive(Clone, Debug, PartialEq)]
pub struct WrittenShell {
    /// The representation item: a `MANIFOLD_SOLID_BREP` or a
    /// `SHELL_BASED_SURFACE_MODEL`.
    pub item: u64,
    /// A closed shell (a solid).
    pub closed: bool,
    /// The patches in it, by index in the input.
    pub patches: Vec<usize>,
    /// The signed volume the shell encloses as measured on a grid of its
    /// points (positive once oriented; only meaningful when closed).
    pub volume: f64,
    /// The number of distinct edges.
    pub edges: usize,
}

/// A side of a patch: its boundary curve in its own direction, and
/// whether the face's loop runs along it (true) or against it.
struct Side {
    curve: NurbsCurve,
    forward: bool,
}

/// The iso-curve of `s` at `u = u` (a curve in v), exact: each column
/// (a curve in u) is clamped at `u`, so that its first control point and
/// weight are the homogeneous point of the column there.
fn iso_u(s: &NurbsSurface, at_end: bool) -> NurbsCurve {
    let (nu, nv) = s.size();
    let _ = nu;
    let mut points = Vec::with_capacity(nv);
    let mut weights = Vec::with_capacity(nv);
    for j in 0..nv {
        let c = s.column(j).clamped_ends();
        let k = if at_end { c.points().len() - 1 } else { 0 };
        points.push(c.points()[k]);
        weights.push(c.weights()[k]);
    }
    let (_, kv) = s.knots();
    NurbsCurve::new(s.degrees().1, kv.to_vec(), points, weights)
        .expect("the boundary of a valid surface is a valid curve")
}

/// The iso-curve at the start or end of v (a curve in u).
fn iso_v(s: &NurbsSurface, at_end: bool) -> NurbsCurve {
    let (nu, _) = s.size();
    let mut points = Vec::with_capacity(nu);
    let mut weights = Vec::with_capacity(nu);
    for i in 0..nu {
        let c = s.row(i).clamped_ends();
        let k = if at_end { c.points().len() - 1 } else { 0 };
        points.push(c.points()[k]);
        weights.push(c.weights()[k]);
    }
    let (ku, _) = s.knots();
    NurbsCurve::new(s.degrees().0, ku.to_vec(), points, weights)
        .expect("the boundary of a valid surface is a valid curve")
}

/// The four sides in loop order, counter-clockwise in (u, v): v = v0
/// (u rising), u = u1 (v rising), v = v1 (u falling), u = u0 (v falling).
fn sides(s: &NurbsSurface) -> [Side; 4] {
    [
        Side {
            curve: iso_v(s, false),
            forward: true,
        },
        Side {
            curve: iso_u(s, true),
            forward: true,
        },
        Side {
            curve: iso_v(s, true),
            forward: false,
        },
        Side {
            curve: iso_u(s, false),
            forward: false,
        },
    ]
}

/// The surface's four boundary curves (v = v0, u = u1, v = v1, u = u0),
/// exact.
pub(crate) fn boundary_curves(s: &NurbsSurface) -> [NurbsCurve; 4] {
    sides(s).map(|side| side.curve)
}

/// The parameter of the point of `c` nearest to `p` and its distance:
/// the nearest of 8 samples per control point (at least 65), refined by
/// Newton's method on `(C(t) − p) · C'(t) = 0`.
pub(crate) fn project_to_curve(c: &NurbsCurve, p: DVec3) -> (f64, f64) {
    let (a, b) = c.domain();
    let n = (8 * c.points().len()).max(64);
    let mut t = (0..=n)
        .map(|k| a + (b - a) * k as f64 / n as f64)
        .min_by(|x, y| c.point(*x).distance(p).total_cmp(&c.point(*y).distance(p)))
        .unwrap_or(a);
    for _ in 0..16 {
        let [q, d1, d2] = c.derivatives(t);
        let f = (q - p).dot(d1);
        let df = d1.dot(d1) + (q - p).dot(d2);
        if df.abs() < 1e-300 {
            break;
        }
        let next = (t - f / df).clamp(a, b);
        let done = (next - t).abs() <= 1e-15 * (b - a);
        t = next;
        if done {
            break;
        }
    }
    (t, c.point(t).distance(p))
}

/// The distance from `p` to the curve `c` ([`project_to_curve`]).
pub(crate) fn distance_to_curve(c: &NurbsCurve, p: DVec3) -> f64 {
    project_to_curve(c, p).1
}

/// Fractions of a curve's domain at which two curves are compared.
const SAMPLES: [f64; 5] = [0.13, 0.31, 0.5, 0.71, 0.89];

fn at(c: &NurbsCurve, f: f64) -> DVec3 {
    let (a, b) = c.domain();
    c.point(a + f * (b - a))
}

/// Vertices merged within a tolerance, found through a grid of cells.
struct Vertices {
    tolerance: f64,
    points: Vec<DVec3>,
    cells: HashMap<[i64; 3], Vec<usize>>,
}

impl Vertices {
    fn cell(&self, p: DVec3) -> [i64; 3] {
        (p / (4.0 * self.tolerance)).floor().as_i64vec3().to_array()
    }
    fn find_or_add(&mut self, p: DVec3) -> usize {
        let c = self.cell(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(list) = self.cells.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                        for &k in list {
                            if self.points[k].distance(p) <= self.tolerance {
                                return k;
                            }
                        }
                    }
                }
            }
        }
        self.points.push(p);
        self.cells.entry(c).or_default().push(self.points.len() - 1);
        self.points.len() - 1
    }
}

/// An edge: its curve runs from vertex `start` to `end`.
struct Edge {
    start: usize,
    end: usize,
    curve: NurbsCurve,
    /// Uses along its direction and against it.
    uses: [usize; 2],
    /// The first patch that uses it.
    patch: usize,
}

/// The signed volume enclosed by `s` with its normal `S_u × S_v` taken as
/// outward, by the divergence theorem on an n × n grid of triangles.
fn signed_volume(s: &NurbsSurface, n: usize) -> f64 {
    let ((u0, u1), (v0, v1)) = s.domain();
    let us: Vec<f64> = (0..=n)
        .map(|i| u0 + (u1 - u0) * i as f64 / n as f64)
        .collect();
    let vs: Vec<f64> = (0..=n)
        .map(|i| v0 + (v1 - v0) * i as f64 / n as f64)
        .collect();
    let g = s.grid_points(&us, &vs);
    let p = |i: usize, j: usize| g[i * (n + 1) + j];
    let mut v = 0.0;
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
            v += a.dot(b.cross(c)) + a.dot(c.cross(d));
        }
    }
    v / 6.0
}

/// Whether curves `e` and `c` are one curve (their end points are
/// already known to match, in the same direction or, `reversed`, in the
/// opposite one): their points at five fractions of their domains agree
/// within `tolerance` (the same parametrisation up to a linear map), or,
/// when they do not, five points of each lie within `tolerance` of the
/// other (one curve parametrised differently: a piece of a long boundary
/// against a short one). A closed curve (one vertex at both ends) is
/// compared by fractions only, which tells its direction.
fn coincide(e: &NurbsCurve, c: &NurbsCurve, reversed: bool, tolerance: f64) -> bool {
    let g = |f: f64| if reversed { 1.0 - f } else { f };
    if SAMPLES
        .iter()
        .all(|&f| at(e, g(f)).distance(at(c, f)) <= tolerance)
    {
        return true;
    }
    let (e0, e1) = e.domain();
    let (c0, c1) = c.domain();
    let closed = e.point(e0).distance(e.point(e1)) <= tolerance
        || c.point(c0).distance(c.point(c1)) <= tolerance;
    !closed
        && SAMPLES.iter().all(|&f| {
            distance_to_curve(e, at(c, f)) <= tolerance
                && distance_to_curve(c, at(e, f)) <= tolerance
        })
}

/// Whether `p` lies in the box of `c`'s control points grown by
/// `tolerance` (a curve with positive weights lies in the convex hull of
/// its control points).
fn near_hull(c: &NurbsCurve, p: DVec3, tolerance: f64) -> bool {
    let (lo, hi) = c.points().iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), q| (lo.min(*q), hi.max(*q)),
    );
    p.cmpge(lo - tolerance).all() && p.cmple(hi + tolerance).all()
}

/// The side curve `c` (from vertex `start` to `end`) cut at every vertex
/// that lies on it within the tolerance, other than its ends (the corners
/// of other patches on it: a long boundary along several short ones, a
/// T-junction), in order along the curve: each piece exact (knot
/// insertion, [`NurbsCurve::split`]) with its end vertices. A parameter
/// within 1e-9 of the domain's length of a knot is moved onto it (no
/// sliver spans); a vertex whose parameter does not fall strictly inside
/// the piece left to cut is passed over.
fn split_at_vertices(
    c: &NurbsCurve,
    start: usize,
    end: usize,
    vertices: &Vertices,
) -> Vec<(NurbsCurve, usize, usize)> {
    let tolerance = vertices.tolerance;
    let (a, b) = c.domain();
    let mut cuts: Vec<(f64, usize)> = vertices
        .points
        .iter()
        .enumerate()
        .filter(|&(k, p)| k != start && k != end && near_hull(c, *p, tolerance))
        .filter_map(|(k, p)| {
            let (t, d) = project_to_curve(c, *p);
            (d <= tolerance && t > a && t < b).then_some((t, k))
        })
        .collect();
    if !SPLIT_SIDES || cuts.is_empty() {
        return vec![(c.clone(), start, end)];
    }
    cuts.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut pieces = Vec::with_capacity(cuts.len() + 1);
    let (mut rest, mut from) = (c.clone(), start);
    for (t, k) in cuts {
        let t = c
            .knots()
            .iter()
            .copied()
            .find(|&u| (u - t).abs() <= 1e-9 * (b - a))
            .unwrap_or(t);
        let (r0, r1) = rest.domain();
        if !(t > r0 && t < r1) {
            continue;
        }
        let Ok((left, right)) = rest.split(t) else {
            continue;
        };
        pieces.push((left, from, k));
        (rest, from) = (right, k);
    }
    pieces.push((rest, from, end));
    pieces
}

/// Cut sides at the corners of other patches on them (off only to show,
/// in a test, that whole-curve matching leaves such shells open).
const SPLIT_SIDES: bool = true;

/// Writes `patches` as faces with shared edges and vertices, grouped into
/// shells by the edges they share (see the module's description). Edges
/// coincide when their end points are within `tolerance` and so are their
/// points at five fractions of their domains (in the same or the
/// opposite direction) or, failing that, five points of each are within
/// `tolerance` of the other (`coincide`); each side is first cut at the
/// patch corners lying on it (`split_at_vertices`); a side whose control points all lie within
/// `tolerance` of its first is a pole and has no edge.
///
/// Returns the shells in the order of their first patch.
///
/// Complexity: O(patches × control points) for the boundaries, vertices
/// merged through a grid in about O(1) each; cutting sides tests every
/// vertex against every side's control-point box, O(sides × vertices),
/// projecting only those inside it.
pub fn write_shells(w: &mut StepWriter, patches: &[Patch], tolerance: f64) -> Vec<WrittenShell> {
    let mut vertices = Vertices {
        tolerance,
        points: Vec::new(),
        cells: HashMap::new(),
    };
    // Every side that is not a pole, with its end vertices: all the
    // patches' corners are known before any side is split at them.
    let mut patch_sides: Vec<Vec<(Side, usize, usize)>> = Vec::with_capacity(patches.len());
    for patch in patches {
        let mut list = Vec::new();
        for side in sides(patch.surface) {
            let c = &side.curve;
            let first = c.points()[0];
            if c.points().iter().all(|p| p.distance(first) <= tolerance) {
                continue;
            }
            let (a, b) = c.domain();
            let (start, end) = (
                vertices.find_or_add(c.point(a)),
                vertices.find_or_add(c.point(b)),
            );
            list.push((side, start, end));
        }
        patch_sides.push(list);
    }
    let mut edges: Vec<Edge> = Vec::new();
    let mut by_ends: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    // Per patch, its loop: (edge, along the edge's direction).
    let mut loops: Vec<Vec<(usize, bool)>> = Vec::with_capacity(patches.len());
    for (pi, list) in patch_sides.iter().enumerate() {
        let mut lp = Vec::new();
        for (side, start, end) in list {
            let pieces = split_at_vertices(&side.curve, *start, *end, &vertices);
            let ordered: Vec<&(NurbsCurve, usize, usize)> = if side.forward {
                pieces.iter().collect()
            } else {
                pieces.iter().rev().collect()
            };
            for (c, start, end) in ordered {
                let (start, end) = (*start, *end);
                let key = (start.min(end), start.max(end));
                let same = |e: &Edge| -> Option<bool> {
                    if e.start == start && e.end == end && coincide(&e.curve, c, false, tolerance) {
                        return Some(true);
                    }
                    let backward =
                        e.start == end && e.end == start && coincide(&e.curve, c, true, tolerance);
                    backward.then_some(false)
                };
                // An edge is shared only by a use in the direction it does
                // not have yet: two faces that run along it the same way
                // (turned against each other), or a third face, get an edge
                // of their own, so every edge bounds at most two faces, one
                // each way.
                let found = by_ends.get(&key).and_then(|list| {
                    list.iter().find_map(|&k| {
                        let along = same(&edges[k])? == side.forward;
                        (edges[k].uses[usize::from(!along)] == 0).then_some((k, along))
                    })
                });
                // `along`: the loop runs along the edge's curve.
                let (k, along) = match found {
                    Some(found) => found,
                    None => {
                        edges.push(Edge {
                            start,
                            end,
                            curve: c.clone(),
                            uses: [0, 0],
                            patch: pi,
                        });
                        by_ends.entry(key).or_default().push(edges.len() - 1);
                        (edges.len() - 1, side.forward)
                    }
                };
                edges[k].uses[usize::from(!along)] += 1;
                lp.push((k, along));
            }
        }
        loops.push(lp);
    }
    // Group the patches that share edges (union-find).
    let mut parent: Vec<usize> = (0..patches.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for (pi, lp) in loops.iter().enumerate() {
        for &(k, _) in lp {
            let (a, b) = (root(&mut parent, pi), root(&mut parent, edges[k].patch));
            parent[a] = b;
        }
    }
    let mut groups: Vec<(usize, Vec<usize>)> = Vec::new();
    for pi in 0..patches.len() {
        let g = root(&mut parent, pi);
        match groups.iter_mut().find(|(r, _)| *r == g) {
            Some((_, list)) => list.push(pi),
            None => groups.push((g, vec![pi])),
        }
    }
    // Write vertices and edges on first use.
    let mut vertex_ids: HashMap<usize, u64> = HashMap::new();
    let mut edge_ids: HashMap<usize, u64> = HashMap::new();
    let mut out = Vec::new();
    for (_, members) in groups {
        let used: Vec<usize> = {
            let mut e: Vec<usize> = members
                .iter()
                .flat_map(|&p| loops[p].iter().map(|x| x.0))
                .collect();
            e.sort_unstable();
            e.dedup();
            e
        };
        let closed = used.iter().all(|&k| edges[k].uses == [1, 1]);
        let volume: f64 = members
            .iter()
            .map(|&p| signed_volume(patches[p].surface, 24))
            .sum();
        let outward = !closed || volume >= 0.0;
        let mut faces = Vec::new();
        for &pi in &members {
            let mut oriented = Vec::new();
            for &(k, along) in &loops[pi] {
                let edge_id = match edge_ids.get(&k) {
                    Some(&id) => id,
                    None => {
                        let e = &edges[k];
                        let mut vertex = |v: usize, w: &mut StepWriter| match vertex_ids.get(&v) {
                            Some(&id) => id,
                            None => {
                                let p = w.point(vertices.points[v]);
                                let id = w.add(&format!("VERTEX_POINT('',#{p})"));
                                vertex_ids.insert(v, id);
                                id
                            }
                        };
                        let (s, t) = (vertex(e.start, w), vertex(e.end, w));
                        let curve = w.bspline_curve("", &e.curve);
                        let id = w.add(&format!("EDGE_CURVE('',#{s},#{t},#{curve},.T.)"));
                        edge_ids.insert(k, id);
                        id
                    }
                };
                oriented.push(r(w.add(&format!(
                    "ORIENTED_EDGE('',*,*,#{edge_id},{})",
                    logical(along)
                ))));
            }
            let patch = patches[pi];
            let surface = w.bspline_surface(patch.name, patch.surface);
            let lp = w.add(&format!("EDGE_LOOP('',{})", list(oriented)));
            let bound = w.add(&format!("FACE_OUTER_BOUND('',#{lp},.T.)"));
            faces.push(r(w.add(&format!(
                "ADVANCED_FACE({},(#{bound}),#{surface},{})",
                string(patch.name),
                logical(outward)
            ))));
        }
        let name = patches[members[0]].name;
        let item = if closed {
            let shell = w.add(&format!("CLOSED_SHELL({},{})", string(name), list(faces)));
            w.add(&format!("MANIFOLD_SOLID_BREP({},#{shell})", string(name)))
        } else {
            let shell = w.add(&format!("OPEN_SHELL({},{})", string(name), list(faces)));
            w.add(&format!(
                "SHELL_BASED_SURFACE_MODEL({},(#{shell}))",
                string(name)
            ))
        };
        out.push(WrittenShell {
            item,
            closed,
            volume: if outward { volume } else { -volume },
            edges: used.len(),
            patches: members,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The six faces of the cube [0, 1]³ as bilinear patches, normals out.
    pub(crate) fn cube_patches() -> Vec<NurbsSurface> {
        let c = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        // Each face: corners (u0v0, u0v1, u1v0, u1v1) with S_u × S_v outward.
        let faces = [
            [c(0., 0., 0.), c(1., 0., 0.), c(0., 1., 0.), c(1., 1., 0.)], // z = 0, normal −z
            [c(0., 0., 1.), c(0., 1., 1.), c(1., 0., 1.), c(1., 1., 1.)], // z = 1
            [c(0., 0., 0.), c(0., 0., 1.), c(1., 0., 0.), c(1., 0., 1.)], // y = 0
            [c(0., 1., 0.), c(1., 1., 0.), c(0., 1., 1.), c(1., 1., 1.)], // y = 1
            [c(0., 0., 0.), c(0., 1., 0.), c(0., 0., 1.), c(0., 1., 1.)], // x = 0
            [c(1., 0., 0.), c(1., 0., 1.), c(1., 1., 0.), c(1., 1., 1.)], // x = 1
        ];
        faces
            .iter()
            .map(|f| NurbsSurface::from_bezier(2, 2, f.to_vec()).unwrap())
            .collect()
    }

    #[test]
    fn a_cube_of_six_patches_is_one_closed_shell_with_twelve_shared_edges() {
        let patches = cube_patches();
        let list: Vec<Patch> = patches
            .iter()
            .map(|s| Patch {
                name: "Cube",
                surface: s,
            })
            .collect();
        let mut w = StepWriter::new();
        let shells = write_shells(&mut w, &list, 1e-9);
        assert_eq!(shells.len(), 1);
        assert!(shells[0].closed);
        assert_eq!(shells[0].edges, 12);
        assert!(
            (shells[0].volume - 1.0).abs() < 1e-9,
            "{}",
            shells[0].volume
        );
        let text = String::from_utf8(w.finish("x", "y")).unwrap();
        assert_eq!(text.matches("VERTEX_POINT").count(), 8);
        assert_eq!(text.matches("EDGE_CURVE").count(), 12);
        assert_eq!(text.matches("ADVANCED_FACE").count(), 6);
        // Without one face the shell is open.
        let mut w = StepWriter::new();
        let shells = write_shells(&mut w, &list[..5], 1e-9);
        assert!(!shells[0].closed);
    }

    #[test]
    fn faces_turned_against_each_other_or_a_third_face_get_edges_of_their_own() {
        let patches = cube_patches();
        // The bottom face with u and v swapped runs its edges the other way.
        let s = &patches[0];
        let p = s.points();
        let turned = NurbsSurface::from_bezier(2, 2, vec![p[0], p[2], p[1], p[3]]).unwrap();
        let mut list: Vec<Patch> = patches[1..]
            .iter()
            .map(|s| Patch {
                name: "Cube",
                surface: s,
            })
            .collect();
        list.push(Patch {
            name: "Turned",
            surface: &turned,
        });
        let mut w = StepWriter::new();
        let shells = write_shells(&mut w, &list, 1e-9);
        assert_eq!(shells.len(), 2, "the turned face shares no edge");
        assert!(shells.iter().all(|s| !s.closed));
        assert_eq!(shells.iter().map(|s| s.edges).sum::<usize>(), 12 + 4);
        // A third face on an edge of the whole cube.
        let mut list: Vec<Patch> = patches
            .iter()
            .map(|s| Patch {
                name: "Cube",
                surface: s,
            })
            .collect();
        list.push(Patch {
            name: "Fin",
            surface: &patches[0],
        });
        let mut w = StepWriter::new();
        let shells = write_shells(&mut w, &list, 1e-9);
        assert!(shells[0].closed, "the cube still closes");
        assert_eq!(shells.len(), 2);
    }

    #[test]
    fn a_side_along_two_smaller_faces_is_cut_at_their_corner_and_closes_the_shell() {
        // The cube with its top face (z = 1) in two halves, x < 0.5 and
        // x > 0.5: the whole sides y = 0 and y = 1 run along both halves,
        // so their top boundaries are cut at (0.5, 0, 1) and (0.5, 1, 1).
        let mut patches = cube_patches();
        let c = |x: f64, y: f64| DVec3::new(x, y, 1.0);
        let top = |x0: f64, x1: f64| {
            // Cubic in x (a long side's cut is not at a knot), linear in y.
            let mut points = Vec::new();
            for i in 0..4 {
                let x = x0 + (x1 - x0) * i as f64 / 3.0;
                points.extend([c(x, 0.0), c(x, 1.0)]);
            }
            NurbsSurface::from_bezier(4, 2, points).unwrap()
        };
        patches[1] = top(0.0, 0.5);
        patches.push(top(0.5, 1.0));
        let list: Vec<Patch> = patches
            .iter()
            .map(|s| Patch {
                name: "Cube",
                surface: s,
            })
            .collect();
        let mut w = StepWriter::new();
        let shells = write_shells(&mut w, &list, 1e-9);
        assert_eq!(shells.len(), 1);
        assert!(shells[0].closed, "the cut sides close the shell");
        // 12 cube edges, two of them cut in two, and the seam between the halves.
        assert_eq!(shells[0].edges, 12 + 2 + 1);
        assert!((shells[0].volume - 1.0).abs() < 1e-9);
        let text = String::from_utf8(w.finish("x", "y")).unwrap();
        assert_eq!(text.matches("VERTEX_POINT").count(), 10);
        // The faces y = 0 and y = 1 have five edges in their loops.
        assert_eq!(text.matches("ADVANCED_FACE").count(), 7);
    }

    #[test]
    fn a_vertex_near_a_side_but_off_it_does_not_cut_it() {
        let c = NurbsCurve::clamped(1, vec![DVec3::ZERO, DVec3::X]).unwrap();
        let mut v = Vertices {
            tolerance: 1e-7,
            points: Vec::new(),
            cells: HashMap::new(),
        };
        let (a, b) = (v.find_or_add(DVec3::ZERO), v.find_or_add(DVec3::X));
        v.find_or_add(DVec3::new(0.3, 2e-7, 0.0));
        assert_eq!(split_at_vertices(&c, a, b, &v).len(), 1);
        let k = v.find_or_add(DVec3::new(0.6, 5e-8, 0.0));
        let pieces = split_at_vertices(&c, a, b, &v);
        assert_eq!(pieces.len(), 2);
        assert_eq!(
            (pieces[0].1, pieces[0].2, pieces[1].1, pieces[1].2),
            (a, k, k, b)
        );
        assert!((pieces[0].0.point(pieces[0].0.domain().1).x - 0.6).abs() < 1e-12);
    }

    #[test]
    fn a_sphere_is_closed_by_its_seam_and_has_poles_without_edges() {
        let s = NurbsSurface::sphere(DVec3::ZERO, 2.0);
        let mut w = StepWriter::new();
        let shells = write_shells(
            &mut w,
            &[Patch {
                name: "Ball",
                surface: &s,
            }],
            1e-9,
        );
        assert!(shells[0].closed);
        // The seam; the two poles have none.
        assert_eq!(shells[0].edges, 1);
        let exact = 4.0 / 3.0 * std::f64::consts::PI * 8.0;
        assert!((shells[0].volume - exact).abs() < 0.05 * exact);
    }
}
