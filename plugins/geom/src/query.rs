//! Geometric queries on meshes: polygon triangulation (for rendering and
//! exchange formats) and ray casting (for picking faces under the cursor).

use crate::ids::{FaceId, VertexId};
use crate::mesh::HalfEdgeMesh;
use glam::{DVec2, DVec3};

/// Splits a face into triangles by ear clipping in the plane of its Newell
/// normal, so concave n-gons triangulate correctly. Triangles keep the face's
/// orientation. A degenerate face falls back to a fan.
///
/// Complexity: O(n²) for an n-gon; O(1) for triangles and quads.
pub fn triangulate_face(mesh: &HalfEdgeMesh, f: FaceId) -> Vec<[VertexId; 3]> {
    let verts: Vec<VertexId> = mesh.face_vertices(f).collect();
    let n = verts.len();
    if n == 3 {
        return vec![[verts[0], verts[1], verts[2]]];
    }
    let normal = mesh.face_area_vector(f);
    if normal.length_squared() < 1e-300 {
        return fan(&verts);
    }
    // 2D coordinates in the face plane (u, v, normal right-handed).
    let nz = normal.normalize();
    let u = nz.any_orthonormal_vector();
    let v = nz.cross(u);
    let pts: Vec<DVec2> = verts
        .iter()
        .map(|&x| {
            let p = mesh.position(x);
            DVec2::new(p.dot(u), p.dot(v))
        })
        .collect();
    if n == 4 {
        // Split along the diagonal that keeps both triangles counter-clockwise,
        // preferring the shorter one.
        let ccw = |a: usize, b: usize, c: usize| cross2(pts[b] - pts[a], pts[c] - pts[a]) > 0.0;
        let d02 = ccw(0, 1, 2) && ccw(0, 2, 3);
        let d13 = ccw(1, 2, 3) && ccw(1, 3, 0);
        let use13 = match (d02, d13) {
            (true, true) => pts[1].distance_squared(pts[3]) < pts[0].distance_squared(pts[2]),
            (false, true) => true,
            _ => false,
        };
        return if use13 {
            vec![
                [verts[1], verts[2], verts[3]],
                [verts[1], verts[3], verts[0]],
            ]
        } else {
            vec![
                [verts[0], verts[1], verts[2]],
                [verts[0], verts[2], verts[3]],
            ]
        };
    }
    let mut idx: Vec<usize> = (0..n).collect();
    let mut out = Vec::with_capacity(n - 2);
    let mut guard = n * n;
    while idx.len() > 3 && guard > 0 {
        guard -= 1;
        let m = idx.len();
        let ear = (0..m).find(|&i| {
            let (a, b, c) = (idx[(i + m - 1) % m], idx[i], idx[(i + 1) % m]);
            if cross2(pts[b] - pts[a], pts[c] - pts[b]) <= 0.0 {
                return false; // reflex or flat corner
            }
            !idx.iter()
                .any(|&p| p != a && p != b && p != c && in_triangle(pts[p], pts[a], pts[b], pts[c]))
        });
        let Some(i) = ear else { break };
        let m = idx.len();
        out.push([
            verts[idx[(i + m - 1) % m]],
            verts[idx[i]],
            verts[idx[(i + 1) % m]],
        ]);
        idx.remove(i);
    }
    if idx.len() == 3 {
        out.push([verts[idx[0]], verts[idx[1]], verts[idx[2]]]);
        out
    } else {
        // Self-intersecting polygon: no ear left; finish with a fan of what remains.
        let rest: Vec<VertexId> = idx.iter().map(|&i| verts[i]).collect();
        out.extend(fan(&rest));
        out
    }
}

fn fan(verts: &[VertexId]) -> Vec<[VertexId; 3]> {
    (1..verts.len() - 1)
        .map(|i| [verts[0], verts[i], verts[i + 1]])
        .collect()
}

fn cross2(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

fn in_triangle(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    let d1 = cross2(b - a, p - a);
    let d2 = cross2(c - b, p - b);
    let d3 = cross2(a - c, p - c);
    d1 >= 0.0 && d2 >= 0.0 && d3 >= 0.0
}

/// Ray–triangle intersection (Möller–Trumbore, 1997). Returns the ray
/// parameter `t > 0` of the hit, from either side.
pub fn ray_triangle(origin: DVec3, dir: DVec3, a: DVec3, b: DVec3, c: DVec3) -> Option<f64> {
    let e1 = b - a;
    let e2 = c - a;
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-14 {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > 1e-12).then_some(t)
}

/// Whether `point` can be seen from `eye`: no face crosses the segment
/// between them before the point itself (faces through the point hit at its
/// end, within a small relative tolerance). Used to keep hidden vertices and
/// edges out of viewport picking.
pub fn is_visible_from(mesh: &HalfEdgeMesh, eye: DVec3, point: DVec3) -> bool {
    ray_cast(mesh, eye, point - eye).is_none_or(|(_, t)| t >= 1.0 - 1e-4)
}

/// The nearest face hit by a ray (in the mesh's own space) and its `t`.
///
/// Complexity: O(corners); fine for picking one ray per click.
pub fn ray_cast(mesh: &HalfEdgeMesh, origin: DVec3, dir: DVec3) -> Option<(FaceId, f64)> {
    let mut best: Option<(FaceId, f64)> = None;
    for f in mesh.faces() {
        for [a, b, c] in triangulate_face(mesh, f) {
            if let Some(t) = ray_triangle(
                origin,
                dir,
                mesh.position(a),
                mesh.position(b),
                mesh.position(c),
            ) {
                if best.is_none_or(|(_, bt)| t < bt) {
                    best = Some((f, t));
                }
            }
        }
    }
    best
}
