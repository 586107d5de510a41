//! Boundary representation of NURBS patches: each patch becomes an
//! `ADVANCED_FACE` bounded by one `EDGE_LOOP` of its four iso-boundaries
//! (a boundary that collapses to a point, a pole, is left out of the
//! loop); edges whose curves coincide (within a tolerance) are one
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

/// The distance from `p` to the curve `c`: the nearest of 65 samples,
/// refined by Newton's method on `(C(t) − p) · C'(t) = 0`.
pub(crate) fn distance_to_curve(c: &NurbsCurve, p: DVec3) -> f64 {
    let (a, b) = c.domain();
    let mut t = (0..=64)
        .map(|k| a + (b - a) * k as f64 / 64.0)
        .min_by(|x, y| c.point(*x).distance(p).total_cmp(&c.point(*y).distance(p)))
        .unwrap_or(a);
    for _ in 0..12 {
        let [q, d1, d2] = c.derivatives(t);
        let f = (q - p).dot(d1);
        let df = d1.dot(d1) + (q - p).dot(d2);
        if df.abs() < 1e-300 {
            break;
        }
        t = (t - f / df).clamp(a, b);
    }
    c.point(t).distance(p)
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

/// Writes `patches` as faces with shared edges and vertices, grouped into
/// shells by the edges they share (see the module's description). Edges
/// coincide when their end points are within `tolerance` and so are their
/// points at five fractions of their domains (in the same or the
/// opposite direction); a side whose control points all lie within
/// `tolerance` of its first is a pole and has no edge.
///
/// Returns the shells in the order of their first patch.
///
/// Complexity: O(patches × control points) for the boundaries, vertices
/// merged through a grid in about O(1) each.
pub fn write_shells(w: &mut StepWriter, patches: &[Patch], tolerance: f64) -> Vec<WrittenShell> {
    let mut vertices = Vertices {
        tolerance,
        points: Vec::new(),
        cells: HashMap::new(),
    };
    let mut edges: Vec<Edge> = Vec::new();
    let mut by_ends: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    // Per patch, its loop: (edge, along the edge's direction).
    let mut loops: Vec<Vec<(usize, bool)>> = Vec::with_capacity(patches.len());
    for (pi, patch) in patches.iter().enumerate() {
        let mut lp = Vec::new();
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
            let key = (start.min(end), start.max(end));
            let same = |e: &Edge| -> Option<bool> {
                let forward = e.start == start
                    && e.end == end
                    && SAMPLES
                        .iter()
                        .all(|&f| at(&e.curve, f).distance(at(c, f)) <= tolerance);
                if forward {
                    return Some(true);
                }
                let backward = e.start == end
                    && e.end == start
                    && SAMPLES
                        .iter()
                        .all(|&f| at(&e.curve, 1.0 - f).distance(at(c, f)) <= tolerance);
                backward.then_some(false)
            };
            // An edge is shared only by a use in the direction it does not
            // have yet: two faces that run along it the same way (turned
            // against each other), or a third face, get an edge of their
            // own, so every edge bounds at most two faces, one each way.
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
