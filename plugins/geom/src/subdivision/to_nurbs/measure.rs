//! Measuring a conversion against the exact limit surface: every face of
//! the conversion level is refined `samples` more levels, and the limit
//! positions of the refined vertices (exact points of the limit surface at
//! the dyadic parameters `(i / 2^s, j / 2^s)` of the face) are compared with
//! the patches at the same parameters. Normals are compared on both sides of
//! every smooth edge between patches.

use std::collections::HashMap;

use glam::DVec3;

use super::super::level::Level;
use super::super::{Creases, Options, Refiner, SubdivisionError, limit_positions};
use super::grid::CORNER;
use super::{FacePlacement, NurbsConversion, PatchKind};
use crate::HalfEdgeMesh;
use crate::surfaces::{NurbsSurface, Surface};

/// Measured figures of a conversion.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Report {
    /// Largest distance of the limit surface from the approximate patches:
    /// from each limit sample to the nearest point of its face's patch
    /// (model units).
    pub max_distance: f64,
    /// Largest distance between an exact patch and the limit surface
    /// (rounding only); when only the approximate patches were measured
    /// (`exact_measured` false), over the exact faces next to them only.
    pub max_distance_exact: f64,
    /// Whether the exact patches were sampled too.
    pub exact_measured: bool,
    /// Largest normal angle across a smooth edge between two different
    /// patches (degrees); sharp creases and boundaries are not counted.
    pub max_angle_degrees: f64,
    /// Largest distance between the two patches on each side of an edge,
    /// along the edge (0 when watertight).
    pub max_gap: f64,
    /// Number of limit samples compared.
    pub samples: usize,
}

impl Report {
    /// Takes in the figures of another part of the same conversion (a
    /// region refined on its own): the largest of each, the samples added.
    pub fn merge(&mut self, other: &Report) {
        self.max_distance = self.max_distance.max(other.max_distance);
        self.max_distance_exact = self.max_distance_exact.max(other.max_distance_exact);
        self.max_angle_degrees = self.max_angle_degrees.max(other.max_angle_degrees);
        self.max_gap = self.max_gap.max(other.max_gap);
        self.samples += other.samples;
    }
}

/// Native face coordinates `(s, t)` in the frame of `placement`.
fn to_patch(placement: FacePlacement, (mut s, mut t): (f64, f64)) -> (f64, f64) {
    for _ in 0..placement.rot {
        (s, t) = (t, 1.0 - s);
    }
    (placement.offset.0 as f64 + s, placement.offset.1 as f64 + t)
}

/// Directed edge `(a, b)` → the corner at `a` whose next corner is at `b`.
fn directed(level: &Level) -> HashMap<(u32, u32), usize> {
    let mut map = HashMap::with_capacity(level.face_vertices.len());
    for f in 0..level.face_count() as u32 {
        for c in level.face_corners(f) {
            let a = level.face_vertices[c];
            let b = level.face_vertices[level.next_corner(c)];
            map.insert((a, b), c);
        }
    }
    map
}

/// The vertices of face `f`'s grid after `levels` more steps:
/// `grid[i][j]` at native face coordinates `(i, j) / 2^levels`.
fn face_grids(levels: &[Level], faces: &[u32]) -> Vec<Vec<Vec<u32>>> {
    let first = &levels[0];
    let mut grids: Vec<Vec<Vec<u32>>> = faces
        .iter()
        .map(|&f| {
            let c = first.face_corners(f).start;
            let v = |k: usize| first.face_vertices[c + k];
            vec![vec![v(0), v(3)], vec![v(1), v(2)]]
        })
        .collect();
    for level in &levels[..levels.len() - 1] {
        let map = directed(level);
        let (nf, ne) = (level.face_count() as u32, level.edge_count() as u32);
        let edge = |a: u32, b: u32| {
            let c = map.get(&(a, b)).or_else(|| map.get(&(b, a))).copied();
            nf + level.face_edges[c.expect("an edge of the level")]
        };
        for grid in &mut grids {
            let m = grid.len() - 1;
            let mut new = vec![vec![0u32; 2 * m + 1]; 2 * m + 1];
            for i in 0..=m {
                for j in 0..=m {
                    new[2 * i][2 * j] = nf + ne + grid[i][j];
                    if i < m {
                        new[2 * i + 1][2 * j] = edge(grid[i][j], grid[i + 1][j]);
                    }
                    if j < m {
                        new[2 * i][2 * j + 1] = edge(grid[i][j], grid[i][j + 1]);
                    }
                    if i < m && j < m {
                        let c = map[&(grid[i][j], grid[i + 1][j])];
                        new[2 * i + 1][2 * j + 1] = level.corner_face(c);
                    }
                }
            }
            *grid = new;
        }
    }
    grids
}

/// Measures `conversion` (made from `mesh`, `creases`, `options`) with
/// `2^samples` intervals per face edge: every face with `exact`, else only
/// the approximated faces, their neighbours and the edges between them
/// (exact patches are exact by construction; sampling them is for tests).
///
/// # Errors
/// As [`Refiner::new`] for the sampling level.
pub fn measure(
    mesh: &HalfEdgeMesh,
    creases: &Creases,
    options: Options,
    conversion: &NurbsConversion,
    samples: u32,
    exact: bool,
) -> Result<Report, SubdivisionError> {
    Ok(measure_faces(mesh, creases, options, conversion, samples, exact)?.0)
}

/// The largest figures measured on each face of the conversion level (0
/// where nothing was measured).
#[derive(Clone, Debug, Default)]
pub(super) struct FaceFigures {
    /// Largest distance of the limit surface from the face's approximate
    /// patch.
    pub distance: Vec<f64>,
    /// Largest normal angle across the face's smooth edges (degrees).
    pub angle: Vec<f64>,
}

/// [`measure`], with the figures of each face.
pub(super) fn measure_faces(
    mesh: &HalfEdgeMesh,
    creases: &Creases,
    options: Options,
    conversion: &NurbsConversion,
    samples: u32,
    exact: bool,
) -> Result<(Report, FaceFigures), SubdivisionError> {
    let k = conversion.level as usize;
    let fine = Refiner::new(mesh, creases, options, conversion.level + samples)?;
    let points = fine.refine(&fine.cage_positions(mesh));
    let limit = limit_positions(&fine, &points)?;
    let approximate = |f: u32| {
        conversion.placements[f as usize]
            .is_some_and(|p| conversion.patches[p.patch].kind == PatchKind::Approximate)
    };
    let edges: Vec<&super::SharedEdge> = conversion
        .edges
        .iter()
        .filter(|e| exact || e.faces.iter().any(|&f| approximate(f)))
        .collect();
    let mut faces: Vec<u32> = if exact {
        (0..conversion.placements.len() as u32).collect()
    } else {
        edges.iter().flat_map(|e| e.faces.iter().copied()).collect()
    };
    faces.sort_unstable();
    faces.dedup();
    let grids = face_grids(&fine.levels[k..], &faces);
    let mut report = Report {
        exact_measured: exact,
        ..Report::default()
    };
    let count = conversion.placements.len();
    let mut figures = FaceFigures {
        distance: vec![0.0; count],
        angle: vec![0.0; count],
    };
    let n = 1usize << samples;
    for (slot, &f) in faces.iter().enumerate() {
        let Some(placement) = conversion.placements[f as usize] else {
            continue;
        };
        let patch = &conversion.patches[placement.patch];
        for i in 0..=n {
            for j in 0..=n {
                let st = (i as f64 / n as f64, j as f64 / n as f64);
                let (u, v) = to_patch(placement, st);
                let exact = limit[grids[slot][i][j] as usize];
                match patch.kind {
                    // Exact patches equal the limit surface parameter for
                    // parameter: compared at the same (u, v).
                    PatchKind::Exact => {
                        let d = patch.surface.point(u, v).distance(exact);
                        report.max_distance_exact = report.max_distance_exact.max(d);
                    }
                    PatchKind::Approximate => {
                        let d = distance_to_patch(&patch.surface, (u, v), exact);
                        report.max_distance = report.max_distance.max(d);
                        figures.distance[f as usize] = figures.distance[f as usize].max(d);
                    }
                }
                report.samples += 1;
            }
        }
    }
    let level = &fine.levels[k];
    let corner_of = |f: u32, v: u32| {
        level
            .face_corners(f)
            .position(|c| level.face_vertices[c] == v)
            .expect("a vertex of the face")
    };
    let steps = 2 * n;
    for edge in edges {
        let [f, g] = match edge.faces[..] {
            [f, g] => [f, g],
            _ => continue,
        };
        let (Some(pf), Some(pg)) = (
            conversion.placements[f as usize],
            conversion.placements[g as usize],
        ) else {
            continue;
        };
        let same = pf.patch == pg.patch && conversion.patches[pf.patch].kind == PatchKind::Exact;
        for step in 0..=steps {
            let t = step as f64 / steps as f64;
            let at = |face: u32, placement: FacePlacement| {
                let (a, b) = (
                    CORNER[corner_of(face, edge.ends[0])],
                    CORNER[corner_of(face, edge.ends[1])],
                );
                let st = (
                    a.0 as f64 + t * (b.0 - a.0) as f64,
                    a.1 as f64 + t * (b.1 - a.1) as f64,
                );
                let (u, v) = to_patch(placement, st);
                conversion.patches[placement.patch].surface.evaluate(u, v)
            };
            let (x, y) = (at(f, pf), at(g, pg));
            report.max_gap = report.max_gap.max(x.p.distance(y.p));
            if edge.sharp || same {
                continue;
            }
            let (nx, ny) = (x.du.cross(x.dv), y.du.cross(y.dv));
            if nx.length() < 1e-300 || ny.length() < 1e-300 {
                continue;
            }
            let angle = nx.angle_between(ny).to_degrees();
            report.max_angle_degrees = report.max_angle_degrees.max(angle);
            for face in [f, g] {
                figures.angle[face as usize] = figures.angle[face as usize].max(angle);
            }
        }
    }
    Ok((report, figures))
}

/// Distance from `q` to the nearest point of `surface` (a patch on
/// `[0, 1]²`), found by Gauss–Newton steps from `start` (the parameters
/// where `q` lies on the limit surface), clamped to the patch; never more
/// than the distance at `start`. This is the distance from the limit
/// surface, not between points of equal parameters: a patch that lies on
/// the limit surface but is parametrised a little differently (as the
/// flat middle of an n-gon, where the two differ only along the surface)
/// is at distance 0.
fn distance_to_patch(surface: &NurbsSurface, start: (f64, f64), q: DVec3) -> f64 {
    let (mut u, mut v) = start;
    let mut best = surface.point(u, v).distance(q);
    for _ in 0..8 {
        let e = surface.evaluate(u, v);
        let r = q - e.p;
        let (a, b, c) = (e.du.dot(e.du), e.du.dot(e.dv), e.dv.dot(e.dv));
        let det = a * c - b * b;
        if det.is_nan() || det.abs() <= 1e-300 {
            break;
        }
        let (gu, gv) = (e.du.dot(r), e.dv.dot(r));
        let (step_u, step_v) = ((c * gu - b * gv) / det, (a * gv - b * gu) / det);
        (u, v) = ((u + step_u).clamp(0.0, 1.0), (v + step_v).clamp(0.0, 1.0));
        best = best.min(surface.point(u, v).distance(q));
        if step_u.abs() + step_v.abs() < 1e-14 {
            break;
        }
    }
    best
}

/// A cubic Bézier curve's point at `t` (de Casteljau).
pub fn bezier3(curve: &[DVec3; 4], t: f64) -> DVec3 {
    let lerp = |a: DVec3, b: DVec3| a + t * (b - a);
    let (a, b, c) = (
        lerp(curve[0], curve[1]),
        lerp(curve[1], curve[2]),
        lerp(curve[2], curve[3]),
    );
    let (d, e) = (lerp(a, b), lerp(b, c));
    lerp(d, e)
}
