//! The convex hull of a Bézier segment's control polygon (seed 002: a
//! Bézier curve lies in the convex hull of its control points; so does a
//! rational one with positive weights, and every piece of a NURBS curve).
//!
//! A segment has `degree + 1` control points, a dozen at most in practice,
//! so the hull is found exactly by brute force rather than by an
//! incremental quickhull: every triple of points whose plane has all the
//! points on one side gives a facet, and the points on a facet's plane are
//! ordered by a 2D hull (Andrew's monotone chain). That handles what is
//! usual here and what general hull crates refuse or mishandle: planar
//! control polygons (a curve drawn on a plane), collinear ones (a straight
//! segment) and repeated points. `chull` and `qhull` were weighed: both
//! treat planar input as degenerate, and `qhull` builds a C library for a
//! problem of a dozen points. O(n⁴) for n points.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::CurveError;
use super::joints::extent;
use super::nurbs::NurbsCurve;

/// The convex hull of a set of points, by its dimension.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum ControlHull {
    /// All points at one place.
    Point(DVec3),
    /// All points on a line: the two extreme ones.
    Segment([DVec3; 2]),
    /// All points on a plane: the hull polygon, counter-clockwise seen from
    /// the side `normal` points to.
    Polygon {
        /// The plane's unit normal.
        normal: DVec3,
        /// The hull's corners in order.
        vertices: Vec<DVec3>,
    },
    /// A solid hull: its corners and its faces, each a convex polygon of
    /// corner indices counter-clockwise seen from outside.
    Polyhedron {
        /// The hull's corners.
        vertices: Vec<DVec3>,
        /// The faces, as indices into `vertices`.
        faces: Vec<Vec<usize>>,
    },
}

/// The hull of one Bézier segment of a curve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SegmentHull {
    /// The segment's parameter interval on the curve.
    pub interval: (f64, f64),
    /// Its Bézier control points (Cartesian).
    pub control_points: Vec<DVec3>,
    /// Their weights (all 1 for a polynomial segment).
    pub weights: Vec<f64>,
    /// The convex hull of `control_points`.
    pub hull: ControlHull,
}

/// Indices of the 2D convex hull of `pts` (Andrew's monotone chain),
/// counter-clockwise; collinear points on the hull's edges are left out.
fn hull_2d(pts: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..pts.len()).collect();
    order.sort_by(|&a, &b| {
        pts[a]
            .0
            .total_cmp(&pts[b].0)
            .then(pts[a].1.total_cmp(&pts[b].1))
    });
    order.dedup_by(|a, b| pts[*a] == pts[*b]);
    if order.len() < 3 {
        return order;
    }
    let cross = |o: usize, a: usize, b: usize| {
        (pts[a].0 - pts[o].0) * (pts[b].1 - pts[o].1)
            - (pts[a].1 - pts[o].1) * (pts[b].0 - pts[o].0)
    };
    let mut hull: Vec<usize> = Vec::with_capacity(2 * order.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &usize>> = if pass == 0 {
            Box::new(order.iter())
        } else {
            Box::new(order.iter().rev())
        };
        for &i in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], i) <= 0.0
            {
                hull.pop();
            }
            hull.push(i);
        }
        hull.pop();
    }
    hull
}

/// The points' hull in the plane through `origin` with unit normal
/// `normal`: indices, counter-clockwise about `normal`.
fn planar_hull(points: &[DVec3], indices: &[usize], origin: DVec3, normal: DVec3) -> Vec<usize> {
    let u = normal.any_orthonormal_vector();
    let v = normal.cross(u);
    let flat: Vec<(f64, f64)> = indices
        .iter()
        .map(|&i| {
            let d = points[i] - origin;
            (d.dot(u), d.dot(v))
        })
        .collect();
    hull_2d(&flat).into_iter().map(|k| indices[k]).collect()
}

impl ControlHull {
    /// The convex hull of `points` (see the module documentation). Points
    /// within `1e-9` of the points' size of a line or plane count as on
    /// it. An empty slice gives the point at the origin. O(n⁴).
    pub fn of(points: &[DVec3]) -> ControlHull {
        let Some(&first) = points.first() else {
            return ControlHull::Point(DVec3::ZERO);
        };
        let size = extent(points);
        let eps = 1e-9 * size;
        if size <= f64::MIN_POSITIVE {
            return ControlHull::Point(first);
        }
        // Two points far apart, then the farthest from their line, then the
        // farthest from their plane: the affine dimension.
        let a = first;
        let b = *points
            .iter()
            .max_by(|p, q| p.distance_squared(a).total_cmp(&q.distance_squared(a)))
            .expect("not empty");
        let dir = (b - a).normalize();
        let off_line = |p: &DVec3| (*p - a).reject_from_normalized(dir).length();
        let c = *points
            .iter()
            .max_by(|p, q| off_line(p).total_cmp(&off_line(q)))
            .expect("not empty");
        if off_line(&c) <= eps {
            let along = |p: &DVec3| (*p - a).dot(dir);
            let lo = points.iter().min_by(|p, q| along(p).total_cmp(&along(q)));
            let hi = points.iter().max_by(|p, q| along(p).total_cmp(&along(q)));
            return ControlHull::Segment([*lo.expect("not empty"), *hi.expect("not empty")]);
        }
        let normal = dir.cross(c - a).normalize();
        let off_plane = |p: &DVec3| (*p - a).dot(normal).abs();
        if points.iter().all(|p| off_plane(p) <= eps) {
            let all: Vec<usize> = (0..points.len()).collect();
            let ring = planar_hull(points, &all, a, normal);
            return ControlHull::Polygon {
                normal,
                vertices: ring.into_iter().map(|i| points[i]).collect(),
            };
        }
        Self::solid(points, eps, size)
    }

    /// The 3D hull of points that span space.
    fn solid(points: &[DVec3], eps: f64, size: f64) -> ControlHull {
        let n = points.len();
        // Outward unit normals and offsets of the facet planes found so far.
        let mut planes: Vec<(DVec3, f64)> = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    let m = (points[j] - points[i]).cross(points[k] - points[i]);
                    if m.length() <= 1e-12 * size * size {
                        continue;
                    }
                    let m = m.normalize();
                    let d = m.dot(points[i]);
                    let (mut above, mut below) = (false, false);
                    for p in points {
                        let s = m.dot(*p) - d;
                        above |= s > eps;
                        below |= s < -eps;
                    }
                    let outward = match (above, below) {
                        (false, _) => m,
                        (true, false) => -m,
                        (true, true) => continue,
                    };
                    let offset = outward.dot(points[i]);
                    if !planes.iter().any(|&(q, e)| {
                        (q - outward).length() <= 1e-7 && (e - offset).abs() <= 10.0 * eps
                    }) {
                        planes.push((outward, offset));
                    }
                }
            }
        }
        let mut vertices: Vec<DVec3> = Vec::new();
        let mut index_of: Vec<Option<usize>> = vec![None; n];
        let mut faces = Vec::new();
        for (normal, offset) in planes {
            let on: Vec<usize> = (0..n)
                .filter(|&i| (normal.dot(points[i]) - offset).abs() <= 10.0 * eps)
                .collect();
            let ring = planar_hull(points, &on, points[on[0]], normal);
            if ring.len() < 3 {
                continue;
            }
            faces.push(
                ring.into_iter()
                    .map(|i| {
                        *index_of[i].get_or_insert_with(|| {
                            vertices.push(points[i]);
                            vertices.len() - 1
                        })
                    })
                    .collect(),
            );
        }
        ControlHull::Polyhedron { vertices, faces }
    }

    /// True when `p` lies in the hull or within `tolerance` of it. O(faces).
    pub fn contains(&self, p: DVec3, tolerance: f64) -> bool {
        match self {
            ControlHull::Point(q) => p.distance(*q) <= tolerance,
            ControlHull::Segment([a, b]) => {
                let ab = *b - *a;
                let s = ((p - *a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
                p.distance(*a + s * ab) <= tolerance
            }
            ControlHull::Polygon { normal, vertices } => {
                let m = vertices.len();
                (p - vertices[0]).dot(*normal).abs() <= tolerance
                    && (0..m).all(|i| {
                        let (a, b) = (vertices[i], vertices[(i + 1) % m]);
                        let inward = normal.cross(b - a).normalize_or_zero();
                        (p - a).dot(inward) >= -tolerance
                    })
            }
            ControlHull::Polyhedron { vertices, faces } => faces.iter().all(|f| {
                let normal = face_normal(vertices, f);
                (p - vertices[f[0]]).dot(normal) <= tolerance
            }),
        }
    }

    /// The hull as triangles for drawing (a polygon and each face fanned
    /// from its first corner; none for a point or a segment).
    pub fn triangles(&self) -> Vec<[DVec3; 3]> {
        let fan = |ring: &[DVec3]| -> Vec<[DVec3; 3]> {
            (1..ring.len().saturating_sub(1))
                .map(|i| [ring[0], ring[i], ring[i + 1]])
                .collect()
        };
        match self {
            ControlHull::Point(_) | ControlHull::Segment(_) => Vec::new(),
            ControlHull::Polygon { vertices, .. } => fan(vertices),
            ControlHull::Polyhedron { vertices, faces } => faces
                .iter()
                .flat_map(|f| fan(&f.iter().map(|&i| vertices[i]).collect::<Vec<_>>()))
                .collect(),
        }
    }
}

/// A face's outward unit normal (Newell's method over its ring).
fn face_normal(vertices: &[DVec3], face: &[usize]) -> DVec3 {
    let m = face.len();
    (0..m)
        .map(|i| vertices[face[i]].cross(vertices[face[(i + 1) % m]]))
        .sum::<DVec3>()
        .normalize_or_zero()
}

/// The control-polygon hull of every Bézier segment of `curve` (its
/// pieces between distinct knots, [`NurbsCurve::bezier_segments`]), in
/// order. Every point of a segment lies in its hull (weights are
/// positive). O(k (p² + p⁴)) for k segments of degree p.
///
/// # Errors
/// A knot insertion that fails.
pub fn segment_hulls(curve: &NurbsCurve) -> Result<Vec<SegmentHull>, CurveError> {
    Ok(curve
        .bezier_segments()?
        .into_iter()
        .map(|(interval, pw)| {
            let control_points: Vec<DVec3> = pw.iter().map(|h| h.truncate() / h.w).collect();
            let weights = pw.iter().map(|h| h.w).collect();
            let hull = ControlHull::of(&control_points);
            SegmentHull {
                interval,
                control_points,
                weights,
                hull,
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cube_has_six_square_faces_and_its_centre_inside() {
        let mut pts = Vec::new();
        for i in 0..8 {
            pts.push(DVec3::new(
                (i & 1) as f64,
                ((i >> 1) & 1) as f64,
                ((i >> 2) & 1) as f64,
            ));
        }
        pts.push(DVec3::splat(0.5));
        let ControlHull::Polyhedron { vertices, faces } = ControlHull::of(&pts) else {
            panic!("a solid hull");
        };
        assert_eq!(vertices.len(), 8, "the centre is no corner");
        assert_eq!(faces.len(), 6);
        assert!(faces.iter().all(|f| f.len() == 4));
        let hull = ControlHull::of(&pts);
        assert!(hull.contains(DVec3::splat(0.5), 0.0));
        assert!(!hull.contains(DVec3::new(0.5, 0.5, 1.01), 1e-9));
        // Faces face outwards: each normal points away from the centre.
        for f in &faces {
            let n = face_normal(&vertices, f);
            assert!((vertices[f[0]] - DVec3::splat(0.5)).dot(n) > 0.0);
        }
        assert_eq!(hull.triangles().len(), 12);
    }

    #[test]
    fn planar_collinear_and_repeated_points() {
        let square = [
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ];
        let ControlHull::Polygon { normal, vertices } = ControlHull::of(&square) else {
            panic!("planar");
        };
        assert_eq!(vertices.len(), 4, "the middle point is inside");
        assert!((normal.z.abs() - 1.0).abs() < 1e-12);
        let line = [DVec3::X, DVec3::ZERO, DVec3::new(3.0, 0.0, 0.0)];
        assert_eq!(
            ControlHull::of(&line),
            ControlHull::Segment([DVec3::ZERO, DVec3::new(3.0, 0.0, 0.0)])
        );
        assert_eq!(
            ControlHull::of(&[DVec3::ONE; 4]),
            ControlHull::Point(DVec3::ONE)
        );
    }
}
