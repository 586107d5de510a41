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
    let mut out = Vec::new();
    triangulate_face_into(mesh, f, &mut out);
    out
}

/// [`triangulate_face`] appending to `out`: the exporters and the render
/// buffers call it for every face with one vector, and triangles and quads
/// then allocate nothing.
pub fn triangulate_face_into(mesh: &HalfEdgeMesh, f: FaceId, out: &mut Vec<[VertexId; 3]>) {
    if !mesh.is_polygon_face(f) || mesh.face_degree(f) < 3 {
        return; // rings, no edges or a wire: nothing to fill (issue 3)
    }
    triangulate_outer_loop_into(mesh, f, out);
}

/// Triangles of a face's outer loop alone, its inner rings ignored: how the
/// viewport draws a face with rings (Mäntylä's faces of several loops,
/// made by the Euler operators), which covers the rings' area. Nothing for
/// a face without edges or a wire. Same method and complexity as
/// [`triangulate_face`], which this is for a plain polygon.
pub fn triangulate_outer_loop(mesh: &HalfEdgeMesh, f: FaceId) -> Vec<[VertexId; 3]> {
    let mut out = Vec::new();
    triangulate_outer_loop_into(mesh, f, &mut out);
    out
}

/// [`triangulate_outer_loop`] appending to `out`.
pub fn triangulate_outer_loop_into(mesh: &HalfEdgeMesh, f: FaceId, out: &mut Vec<[VertexId; 3]>) {
    // Triangles and quads on the stack; longer loops in vectors.
    let mut small = [crate::ids::HalfEdgeId(0); 4];
    let mut n = 0;
    for h in mesh.face_halfedges(f) {
        if n < 4 {
            small[n] = h;
        }
        n += 1;
        if n > 4 {
            break;
        }
    }
    let long: Vec<crate::ids::HalfEdgeId>;
    let sides: &[crate::ids::HalfEdgeId] = if n <= 4 {
        &small[..n]
    } else {
        long = mesh.face_halfedges(f).collect();
        &long
    };
    let vert = |i: usize| mesh.origin(sides[i]);
    let n = sides.len();
    if n < 3 {
        return;
    }
    if n == 3 {
        out.push([vert(0), vert(1), vert(2)]);
        return;
    }
    // Corner i has two edges when the edge after it, seen from the other
    // side, runs on into the edge before it (one step, no walk round the
    // vertex: this runs for every face the viewport and the exporters draw).
    let shared = |i: usize| {
        let (before, after) = (sides[(i + n - 1) % n], sides[i]);
        mesh.next(after.twin()) == before.twin()
    };
    if n == 4 {
        let corners = [0, 1, 2, 3].map(|i| mesh.position(vert(i)));
        out.extend(triangulate_quad(corners, [0, 1, 2, 3].map(shared)).map(|t| t.map(vert)));
        return;
    }
    // Newell's normal of the outer loop (a ring would subtract its area).
    let normal = (0..n)
        .map(|i| {
            mesh.position(vert(i))
                .cross(mesh.position(vert((i + 1) % n)))
        })
        .sum::<DVec3>()
        * 0.5;
    if normal.length_squared() < 1e-300 {
        out.extend(fan(&(0..n).map(vert).collect::<Vec<_>>()));
        return;
    }
    // 2D coordinates in the face plane (u, v, normal right-handed).
    let nz = normal.normalize();
    let u = nz.any_orthonormal_vector();
    let v = nz.cross(u);
    let plane = |i: usize| {
        let p = mesh.position(vert(i));
        DVec2::new(p.dot(u), p.dot(v))
    };
    let pts: Vec<DVec2> = (0..n).map(plane).collect();
    // An ear at a vertex of only two edges would be clipped by both faces
    // that share those edges: the same triangle twice, and four triangles
    // on the diagonal (issue 35). A nearly flat ear is a sliver without
    // area. Either is taken only when no other ear is left.
    let sharp_turn = |a: usize, b: usize, c: usize| sharp_turn(pts[a], pts[b], pts[c]);

    let mut idx: Vec<usize> = (0..n).collect();
    out.reserve(n - 2);
    let mut guard = n * n;
    while idx.len() > 3 && guard > 0 {
        guard -= 1;
        let m = idx.len();
        let at = |i: usize| idx[i % m];
        // A vertex of two edges whose neighbours in what is left are still
        // its neighbours in the face: its ear is the triangle the other face
        // on those edges may clip too.
        let pristine = |i: usize| {
            let (a, b, c) = (at(i + m - 1), at(i), at(i + 1));
            shared(b) && a == (b + n - 1) % n && c == (b + 1) % n
        };
        let is_ear = |i: usize| {
            let (a, b, c) = (at(i + m - 1), at(i), at(i + 1));
            cross2(pts[b] - pts[a], pts[c] - pts[b]) > 0.0
                && !idx.iter().any(|&p| {
                    p != a && p != b && p != c && in_triangle(pts[p], pts[a], pts[b], pts[c])
                })
        };
        let good = |i: usize| {
            let (a, b, c) = (at(i + m - 1), at(i), at(i + 1));
            sharp_turn(a, b, c) && !pristine(i) && is_ear(i)
        };
        // First an ear beside such a vertex (it then gets a diagonal of its
        // own), then any good ear, then any ear at all.
        let ear = (0..m)
            .find(|&i| (pristine(i + m - 1) || pristine(i + 1)) && good(i))
            .or_else(|| (0..m).find(|&i| good(i)))
            .or_else(|| (0..m).find(|&i| is_ear(i)));
        let Some(i) = ear else { break };
        out.push([vert(at(i + m - 1)), vert(at(i)), vert(at(i + 1))]);
        idx.remove(i);
    }
    if idx.len() == 3 {
        out.push([vert(idx[0]), vert(idx[1]), vert(idx[2])]);
    } else {
        // Self-intersecting polygon: no ear left; finish with a fan of what remains.
        let rest: Vec<VertexId> = idx.iter().map(|&i| vert(i)).collect();
        out.extend(fan(&rest));
    }
}

/// Area vector of a closed polygon by Newell's method (Newell 1972):
/// ½ Σ pᵢ × pᵢ₊₁ over its corners in order; its length is the area of a
/// planar polygon. Summed in the same order as
/// [`HalfEdgeMesh::face_area_vector`], so both give the same bits for a face
/// without rings.
pub fn polygon_area_vector(points: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for (i, a) in points.iter().enumerate() {
        let b = points[if i + 1 == points.len() { 0 } else { i + 1 }];
        n += a.cross(b);
    }
    n * 0.5
}

/// The two triangles of a quad, as corner indices (0 to 3), split along
/// the diagonal that keeps both counter-clockwise in the plane of its
/// Newell normal, preferring one whose ears are good (not nearly flat, and
/// not at a corner of only two edges: `two_edged[i]`, whose ear the face
/// on the other side of those edges would clip too, issue 35), then the
/// shorter one; a fan when the quad has no area. How
/// [`triangulate_face`] splits every quad, so that the exporters writing
/// refined quads without a half-edge mesh split them the same way.
pub fn triangulate_quad(corners: [DVec3; 4], two_edged: [bool; 4]) -> [[usize; 3]; 2] {
    const FAN: [[usize; 3]; 2] = [[0, 1, 2], [0, 2, 3]];
    let normal = (0..4)
        .map(|i| corners[i].cross(corners[(i + 1) % 4]))
        .sum::<DVec3>()
        * 0.5;
    if normal.length_squared() < 1e-300 {
        return FAN;
    }
    let nz = normal.normalize();
    let u = nz.any_orthonormal_vector();
    let v = nz.cross(u);
    let pts = corners.map(|p| DVec2::new(p.dot(u), p.dot(v)));
    let good_ear =
        |a: usize, b: usize, c: usize| sharp_turn(pts[a], pts[b], pts[c]) && !two_edged[b];
    let ccw = |a: usize, b: usize, c: usize| cross2(pts[b] - pts[a], pts[c] - pts[a]) > 0.0;
    let d02 = ccw(0, 1, 2) && ccw(0, 2, 3);
    let d13 = ccw(1, 2, 3) && ccw(1, 3, 0);
    let good02 = d02 && good_ear(0, 1, 2) && good_ear(2, 3, 0);
    let good13 = d13 && good_ear(1, 2, 3) && good_ear(3, 0, 1);
    let shorter13 = pts[1].distance_squared(pts[3]) < pts[0].distance_squared(pts[2]);
    let use13 = match (good02, good13) {
        (true, true) => shorter13,
        (false, true) => true,
        (true, false) => false,
        (false, false) => match (d02, d13) {
            (true, true) => shorter13,
            (false, true) => true,
            _ => false,
        },
    };
    if use13 { [[1, 2, 3], [1, 3, 0]] } else { FAN }
}

/// A left turn a → b → c that is not nearly straight: the turn's sine
/// over [`FLAT_SINE`] (squared, without roots).
fn sharp_turn(a: DVec2, b: DVec2, c: DVec2) -> bool {
    let (e, f) = (b - a, c - b);
    let cross = cross2(e, f);
    cross > 0.0 && cross * cross > FLAT_SINE * FLAT_SINE * e.length_squared() * f.length_squared()
}

/// Triangles of a polygon given by its corner points, as indices into
/// `points`, appended to `out`: ear clipping in the plane of its Newell
/// normal (as [`triangulate_face`]), a fan when the polygon has no area or
/// no ear is left (self-intersecting). For faces that are not in a
/// half-edge mesh: a kept non-manifold mesh's faces, which may visit a
/// point twice.
///
/// Complexity: O(n²) for an n-gon; O(1) for triangles.
pub fn triangulate_polygon_into(points: &[DVec3], out: &mut Vec<[usize; 3]>) {
    let n = points.len();
    if n < 3 {
        return;
    }
    if n == 3 {
        out.push([0, 1, 2]);
        return;
    }
    let normal: DVec3 = (0..n).map(|i| points[i].cross(points[(i + 1) % n])).sum();
    let fan = |out: &mut Vec<[usize; 3]>, rest: &[usize]| {
        out.extend((1..rest.len() - 1).map(|i| [rest[0], rest[i], rest[i + 1]]));
    };
    if normal.length_squared() < 1e-300 {
        fan(out, &(0..n).collect::<Vec<_>>());
        return;
    }
    let nz = normal.normalize();
    let (u, v) = (
        nz.any_orthonormal_vector(),
        nz.cross(nz.any_orthonormal_vector()),
    );
    let pts: Vec<DVec2> = points
        .iter()
        .map(|p| DVec2::new(p.dot(u), p.dot(v)))
        .collect();
    let mut idx: Vec<usize> = (0..n).collect();
    while idx.len() > 3 {
        let m = idx.len();
        let at = |i: usize| idx[i % m];
        let ear = (0..m).find(|&i| {
            let (a, b, c) = (at(i + m - 1), at(i), at(i + 1));
            cross2(pts[b] - pts[a], pts[c] - pts[b]) > 0.0
                && !idx.iter().any(|&p| {
                    pts[p] != pts[a]
                        && pts[p] != pts[b]
                        && pts[p] != pts[c]
                        && in_triangle(pts[p], pts[a], pts[b], pts[c])
                })
        });
        let Some(i) = ear else { break };
        out.push([at(i + m - 1), at(i), at(i + 1)]);
        idx.remove(i);
    }
    fan(out, &idx);
}

/// The sine of the turn below which a polygon corner counts as flat: its
/// ear would be a sliver without area.
const FLAT_SINE: f64 = 1e-9;

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
            ) && best.is_none_or(|(_, bt)| t < bt)
            {
                best = Some((f, t));
            }
        }
    }
    best
}

/// A software depth buffer of a mesh seen through a projection, to tell many
/// points at once whether the surface hides them (box selection of
/// vertices, edges and faces on dense meshes). This is the CPU form of the
/// depth test a GPU does (Foley & van Dam, §15.4 "The z-buffer algorithm"):
/// every face's triangles are scan-converted into a `width × height` grid
/// keeping the nearest normalised-device depth per cell.
///
/// Complexity: O(corners + covered cells) to build, O(1) per query.
#[derive(Clone, Debug)]
pub struct DepthBuffer {
    width: usize,
    height: usize,
    /// Nearest depth per cell (NDC z, made "larger = nearer").
    depth: Vec<f32>,
    /// Depth change per cell of the triangle that wrote the cell: the
    /// tolerance for points lying on that triangle.
    slope: Vec<f32>,
    model_to_clip: glam::DMat4,
    /// +1 when NDC z grows towards the eye (reverse-Z, Bevy), else −1.
    nearer: f64,
}

impl DepthBuffer {
    /// Renders `mesh` through `model_to_clip` (projection · view · model)
    /// into a `width × height` grid. Triangles crossing the eye plane are
    /// left out (they cannot hide what the camera looks at in front).
    pub fn render(
        mesh: &HalfEdgeMesh,
        model_to_clip: glam::DMat4,
        width: usize,
        height: usize,
    ) -> Self {
        let (width, height) = (width.max(1), height.max(1));
        // Which way NDC z runs: of two points on the view axis, the one with
        // the smaller clip w is nearer (perspective). An orthographic
        // projection has w = 1 everywhere; it is taken as reverse-Z (near
        // plane at z = 1), Bevy's convention.
        let inv = model_to_clip.inverse();
        let w_at =
            |z: f64| (model_to_clip * inv.project_point3(DVec3::new(0.0, 0.0, z)).extend(1.0)).w;
        let (w_low, w_high) = (w_at(0.25), w_at(0.75));
        let nearer = if (w_low - w_high).abs() > 1e-9 * (w_low.abs() + w_high.abs()) {
            if w_high < w_low { 1.0 } else { -1.0 }
        } else {
            1.0
        };
        let mut buffer = DepthBuffer {
            width,
            height,
            depth: vec![f32::NEG_INFINITY; width * height],
            slope: vec![0.0; width * height],
            model_to_clip,
            nearer,
        };
        for f in mesh.faces() {
            for tri in triangulate_face(mesh, f) {
                let p = tri.map(|v| buffer.to_cell(mesh.position(v)));
                if let [Some(a), Some(b), Some(c)] = p {
                    buffer.fill(a, b, c);
                }
            }
        }
        buffer
    }

    /// A point's cell coordinates (x right, y down) and its depth (larger =
    /// nearer); `None` behind the eye.
    fn to_cell(&self, p: DVec3) -> Option<DVec3> {
        let clip = self.model_to_clip * p.extend(1.0);
        if clip.w <= 1e-9 {
            return None;
        }
        let ndc = clip.truncate() / clip.w;
        Some(DVec3::new(
            (ndc.x + 1.0) * 0.5 * self.width as f64,
            (1.0 - ndc.y) * 0.5 * self.height as f64,
            ndc.z * self.nearer,
        ))
    }

    /// Scan-converts one triangle (cell centres inside it, either winding).
    fn fill(&mut self, a: DVec3, b: DVec3, c: DVec3) {
        let area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        if area.abs() < 1e-12 {
            return;
        }
        // Depth as an affine function of the cell position: z = z0 + gx·x + gy·y.
        let gx = ((b.z - a.z) * (c.y - a.y) - (c.z - a.z) * (b.y - a.y)) / area;
        let gy = ((c.z - a.z) * (b.x - a.x) - (b.z - a.z) * (c.x - a.x)) / area;
        let slope = (gx.abs() + gy.abs()) as f32;
        let x0 = a.x.min(b.x).min(c.x).floor().max(0.0) as usize;
        let y0 = a.y.min(b.y).min(c.y).floor().max(0.0) as usize;
        let x1 = (a.x.max(b.x).max(c.x).ceil() as usize).min(self.width);
        let y1 = (a.y.max(b.y).max(c.y).ceil() as usize).min(self.height);
        let edge =
            |p: DVec3, q: DVec3, x: f64, y: f64| (q.x - p.x) * (y - p.y) - (x - p.x) * (q.y - p.y);
        let s = area.signum();
        for y in y0..y1 {
            let cy = y as f64 + 0.5;
            for x in x0..x1 {
                let cx = x as f64 + 0.5;
                if edge(a, b, cx, cy) * s < 0.0
                    || edge(b, c, cx, cy) * s < 0.0
                    || edge(c, a, cx, cy) * s < 0.0
                {
                    continue;
                }
                let z = (a.z + gx * (cx - a.x) + gy * (cy - a.y)) as f32;
                let i = y * self.width + x;
                if z > self.depth[i] {
                    self.depth[i] = z;
                    self.slope[i] = slope;
                }
            }
        }
    }

    /// Whether the surface leaves `p` (mesh space) in sight: nothing in its
    /// cell is nearer than `p` beyond the depth change across one cell of
    /// the triangle drawn there (so points on that triangle pass).
    /// Points outside the grid or behind the eye are not visible.
    pub fn is_visible(&self, p: DVec3) -> bool {
        let Some(q) = self.to_cell(p) else {
            return false;
        };
        if q.x < 0.0 || q.y < 0.0 || q.x >= self.width as f64 || q.y >= self.height as f64 {
            return false;
        }
        let i = q.y as usize * self.width + q.x as usize;
        let z = q.z as f32;
        z + self.slope[i] + 1e-6 * z.abs() + 1e-7 >= self.depth[i]
    }
}

#[cfg(test)]
mod depth_buffer_tests {
    use super::*;
    use crate::primitives::Primitive;
    use glam::DMat4;

    /// A camera at (3, 2, 4) looking at the origin, with Bevy's reverse-Z
    /// infinite perspective or a classic OpenGL one.
    fn view_projection(reverse_z: bool) -> DMat4 {
        let view = DMat4::look_at_rh(DVec3::new(3.0, 2.0, 4.0), DVec3::ZERO, DVec3::Y);
        let projection = if reverse_z {
            DMat4::perspective_infinite_reverse_rh(0.8, 1.5, 0.1)
        } else {
            DMat4::perspective_rh_gl(0.8, 1.5, 0.1, 100.0)
        };
        projection * view
    }

    #[test]
    fn the_depth_buffer_hides_exactly_the_back_corner_of_a_cube() {
        let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
        let eye = DVec3::new(3.0, 2.0, 4.0);
        for reverse_z in [true, false] {
            let buffer = DepthBuffer::render(&cube, view_projection(reverse_z), 600, 400);
            for v in cube.vertices() {
                let p = cube.position(v);
                // From (3, 2, 4) every corner but (−1, −1, −1) is in sight;
                // the ray test used for click picking agrees.
                let expected = p != DVec3::splat(-1.0);
                assert_eq!(is_visible_from(&cube, eye, p), expected, "{p}");
                assert_eq!(buffer.is_visible(p), expected, "{p} reverse_z {reverse_z}");
            }
            // Face centres: the three facing +X, +Y, +Z are seen.
            for f in cube.faces() {
                let n = cube.face_normal(f);
                let seen = n.x > 0.5 || n.y > 0.5 || n.z > 0.5;
                assert_eq!(buffer.is_visible(cube.face_centroid(f)), seen, "face {n}");
            }
            // A point far behind the cube, and one behind the eye.
            assert!(!buffer.is_visible(DVec3::new(-3.0, -2.0, -4.0)));
            assert!(!buffer.is_visible(DVec3::new(6.0, 4.0, 8.0)));
        }
    }

    #[test]
    fn dense_meshes_keep_their_front_vertices_visible() {
        // A 64-segment UV sphere: every vertex on the near hemisphere (seen
        // at more than 5° from the silhouette) is visible, every one on the
        // far side more than 12° past it is not (closer to the silhouette
        // the front surface is too steep for a one-cell tolerance).
        let sphere = Primitive::UvSphere {
            segments: 64,
            rings: 32,
            radius: 1.0,
        }
        .build()
        .unwrap();
        let eye = DVec3::new(3.0, 2.0, 4.0);
        let buffer = DepthBuffer::render(&sphere, view_projection(true), 1280, 800);
        let (mut front, mut back) = (0, 0);
        for v in sphere.vertices() {
            let p = sphere.position(v);
            // Cosine of the angle between the normal and the direction to the eye.
            let facing = p.normalize().dot((eye - p).normalize());
            if facing > 0.09 {
                assert!(buffer.is_visible(p), "front vertex {p} hidden");
                front += 1;
            } else if facing < -0.2 {
                assert!(!buffer.is_visible(p), "back vertex {p} seen");
                back += 1;
            }
        }
        assert!(front > 500 && back > 500, "{front} {back}");
    }
}
