//! Triangulating faces (Blender's Ctrl+T) along the diagonals of their
//! ear-clipping triangulation ([`crate::query::triangulate_face`]), and its
//! inverse, joining triangles into quads (Blender's Alt+J,
//! `bmo_join_triangles.c`).

use super::ModelingError;
use super::common::check_faces;
use crate::ids::{EdgeId, FaceId, VertexId};
use crate::mesh::HalfEdgeMesh;
use std::collections::HashSet;
use std::f64::consts::{FRAC_PI_2, PI};

/// Which triangles a face is cut into (Blender's Triangulate quad and
/// n-gon methods).
#[derive(
    Copy, Clone, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum TriangulateMethod {
    /// The ear-clipping triangulation as it comes
    /// ([`crate::query::triangulate_face`]; Blender's n-gon "Clip").
    #[default]
    Clip,
    /// Ear clipping, then diagonals flipped while that makes the
    /// triangles more regular: Lawson's flips to the Delaunay
    /// triangulation of the face's outline (the sum of the two angles
    /// facing a diagonal at most π), which maximises the smallest angle
    /// (Blender's "Beauty"); a quad is cut along its better diagonal.
    Beauty,
    /// A fan from the face's first corner (Blender's "Fixed" for quads),
    /// when every fan triangle lies inside the face; ear clipping for a
    /// face where it would not (a concave face).
    Fan,
}

impl TriangulateMethod {
    /// Every method, in menu order.
    pub const ALL: [TriangulateMethod; 3] = [
        TriangulateMethod::Beauty,
        TriangulateMethod::Fan,
        TriangulateMethod::Clip,
    ];

    /// The name a menu shows.
    pub fn label(self) -> &'static str {
        match self {
            TriangulateMethod::Clip => "Clip (ear clipping)",
            TriangulateMethod::Beauty => "Beauty",
            TriangulateMethod::Fan => "Fixed fan",
        }
    }
}

/// The triangles `method` cuts face `f` into, as corner triples in the
/// face's orientation.
fn face_triangles(mesh: &HalfEdgeMesh, f: FaceId, method: TriangulateMethod) -> Vec<[VertexId; 3]> {
    let clipped = crate::query::triangulate_face(mesh, f);
    match method {
        TriangulateMethod::Clip => clipped,
        TriangulateMethod::Beauty => beauty_flips(mesh, f, clipped),
        TriangulateMethod::Fan => {
            let corners: Vec<VertexId> = mesh.face_vertices(f).collect();
            let normal = mesh.face_area_vector(f);
            let fan: Vec<[VertexId; 3]> = (1..corners.len() - 1)
                .map(|i| [corners[0], corners[i], corners[i + 1]])
                .collect();
            let inside = fan
                .iter()
                .all(|t| triangle_area(mesh, *t).dot(normal) > 0.0);
            if inside { fan } else { clipped }
        }
    }
}

/// Twice the area vector of a triangle (its normal, by the right-hand rule).
fn triangle_area(mesh: &HalfEdgeMesh, [a, b, c]: [VertexId; 3]) -> glam::DVec3 {
    let p = |v| mesh.position(v);
    (p(b) - p(a)).cross(p(c) - p(a))
}

/// Lawson's flips (Lawson 1977; de Berg et al., Computational Geometry,
/// ch. 9): while two triangles sharing a diagonal see it under angles
/// summing to more than π, and their quad is convex, the other diagonal
/// replaces it. Ends at the Delaunay triangulation of the outline.
fn beauty_flips(
    mesh: &HalfEdgeMesh,
    f: FaceId,
    mut tris: Vec<[VertexId; 3]>,
) -> Vec<[VertexId; 3]> {
    let normal = mesh.face_area_vector(f);
    let angle_at = |apex: VertexId, a: VertexId, b: VertexId| {
        let p = |v| mesh.position(v);
        (p(a) - p(apex)).angle_between(p(b) - p(apex))
    };
    // Each flip raises the smallest angle; the bound only guards against
    // rounding cycles.
    for _ in 0..tris.len() * tris.len() + 1 {
        let mut flipped = false;
        'pairs: for i in 0..tris.len() {
            for j in i + 1..tris.len() {
                // A shared diagonal a→b in tris[i] is b→a in tris[j].
                for k in 0..3 {
                    let (a, b, c) = (tris[i][k], tris[i][(k + 1) % 3], tris[i][(k + 2) % 3]);
                    let Some(m) = (0..3).find(|&m| tris[j][m] == b && tris[j][(m + 1) % 3] == a)
                    else {
                        continue;
                    };
                    let d = tris[j][(m + 2) % 3];
                    if angle_at(c, a, b) + angle_at(d, b, a) <= std::f64::consts::PI + 1e-9 {
                        continue;
                    }
                    let (t1, t2) = ([c, a, d], [d, b, c]);
                    let convex = [t1, t2]
                        .iter()
                        .all(|t| triangle_area(mesh, *t).dot(normal) > 0.0);
                    if convex {
                        tris[i] = t1;
                        tris[j] = t2;
                        flipped = true;
                        break 'pairs;
                    }
                }
            }
        }
        if !flipped {
            break;
        }
    }
    tris
}

/// Splits faces into triangles (Blender's Ctrl+T): each face is cut along
/// the diagonals of the triangles `method` gives, one Euler MEF
/// ([`HalfEdgeMesh::make_edge_face`]) per diagonal; positions do not move
/// and triangles are left as they are. Returns the faces made.
///
/// # Errors
/// [`ModelingError::Missing`] for a face that does not exist.
pub fn triangulate_faces(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    method: TriangulateMethod,
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    let mut made = Vec::new();
    for &f in faces {
        let corners: Vec<VertexId> = mesh.face_vertices(f).collect();
        let n = corners.len();
        if n <= 3 {
            continue;
        }
        let outline = |a: VertexId, b: VertexId| {
            (0..n).any(|i| {
                let (p, q) = (corners[i], corners[(i + 1) % n]);
                (p, q) == (a, b) || (p, q) == (b, a)
            })
        };
        let mut diagonals: Vec<(VertexId, VertexId)> = Vec::new();
        for t in face_triangles(mesh, f, method) {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if !outline(a, b) && !diagonals.iter().any(|&d| d == (a, b) || d == (b, a)) {
                    diagonals.push((a, b));
                }
            }
        }
        // The diagonals do not cross: each lies in one piece of the face.
        let mut pieces = vec![f];
        for (a, b) in diagonals {
            // MEF takes the face's half-edges that end at the two corners.
            let corner = |m: &HalfEdgeMesh, g: FaceId, v: VertexId| {
                m.face_halfedges(g).find(|&h| m.target(h) == v)
            };
            let Some((ha, hb)) = pieces
                .iter()
                .find_map(|&g| Some((corner(mesh, g, a)?, corner(mesh, g, b)?)))
            else {
                continue;
            };
            let (_, new_face) = mesh.make_edge_face(ha, hb)?;
            pieces.push(new_face);
            made.push(new_face);
        }
    }
    Ok(made)
}

/// Blender's default limit for both the face angle and the shape angle (40°).
pub const DEFAULT_JOIN_LIMIT: f64 = 40.0 * PI / 180.0;

/// Joins pairs of the selected triangles that share an edge into quads,
/// best pairs first (Blender's Tris to Quads), and returns the quads.
///
/// A pair is a candidate when the angle between the two triangles' normals
/// is at most `face_angle_limit` (and so is the quad's fold across its
/// other diagonal, [`quad_fold`]), every corner of the quad they make is
/// within `shape_angle_limit` of a right angle, and the quad is convex.
/// Candidates are taken in order of the error Blender uses: the normal
/// angle over π/2 plus the corners' summed distance from π/2 over 2π; each
/// triangle joins at most once. Other faces of the selection stay as they
/// are. Each join is one [`kill_edge_face`](HalfEdgeMesh::kill_edge_face).
///
/// # Errors
/// [`ModelingError::Empty`] for no faces, [`ModelingError::Missing`] for a
/// dead face, [`ModelingError::Parameter`] for a limit outside [0, π].
pub fn tris_to_quads(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    face_angle_limit: f64,
    shape_angle_limit: f64,
) -> Result<Vec<FaceId>, ModelingError> {
    tris_to_quads_across(mesh, faces, face_angle_limit, shape_angle_limit, |_| true)
}

/// [`tris_to_quads`] joining only across the edges `joinable` accepts.
fn tris_to_quads_across(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    face_angle_limit: f64,
    shape_angle_limit: f64,
    joinable: impl Fn(EdgeId) -> bool,
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    for (what, limit) in [
        ("face angle limit", face_angle_limit),
        ("shape angle limit", shape_angle_limit),
    ] {
        if !(0.0..=PI).contains(&limit) {
            return Err(ModelingError::Parameter {
                what,
                allowed: "between 0° and 180°",
                value: format!("{}°", limit.to_degrees()),
            });
        }
    }
    let triangles: HashSet<FaceId> = faces
        .iter()
        .copied()
        .filter(|&f| mesh.face_degree(f) == 3 && mesh.face_rings(f).is_empty())
        .collect();
    let mut candidates: Vec<(f64, EdgeId)> = Vec::new();
    let mut seen = HashSet::new();
    for &f in &triangles {
        for h in mesh.face_halfedges(f) {
            let e = h.edge();
            let Some(g) = mesh.face(h.twin()) else {
                continue;
            };
            if g == f || !triangles.contains(&g) || !seen.insert(e) || !joinable(e) {
                continue;
            }
            if let Some(error) = join_error(mesh, e, face_angle_limit, shape_angle_limit) {
                candidates.push((error, e));
            }
        }
    }
    candidates.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut joined = HashSet::new();
    let mut quads = Vec::new();
    for (_, e) in candidates {
        let [Some(a), Some(b)] = mesh.edge_faces(e) else {
            continue;
        };
        if joined.contains(&a) || joined.contains(&b) {
            continue;
        }
        let killed = mesh.kill_edge_face(e)?;
        let kept = if killed == a { b } else { a };
        joined.insert(a);
        joined.insert(b);
        quads.push(kept);
    }
    Ok(quads)
}

/// Pairs of the triangles `faces` to join into quads, as the edges between
/// them, pairing as many triangles as it can: a maximal matching of the
/// triangles across their shared edges, grown by augmenting paths.
///
/// Candidates are the edges [`tris_to_quads`] would join with
/// `face_angle_limit` and `loose_shape_limit` (corners within that of a
/// right angle, convex); those within `shape_angle_limit` (good quads)
/// come before the others, each group in order of Blender's join error, and
/// are taken greedily (best first, each triangle at most once). Then each
/// unpaired triangle `a` looks for an alternating path `a–b, b=c, c–d`
/// (`b` paired with `c`, `d` unpaired; Edmonds' augmenting path of length
/// three): re-pairing `a` with `b` and `c` with `d` pairs two more
/// triangles. Rounds repeat until none is found (at most four).
///
/// Nothing is joined: the caller kills the returned edges (each has a
/// different pair of triangles on its sides).
pub(crate) fn quad_pairing(
    mesh: &HalfEdgeMesh,
    faces: &[FaceId],
    face_angle_limit: f64,
    shape_angle_limit: f64,
    loose_shape_limit: f64,
    joinable: impl Fn(EdgeId) -> bool,
) -> Vec<EdgeId> {
    let n = mesh.face_capacity();
    let mut is_tri = vec![false; n];
    for &f in faces {
        if mesh.is_face(f) && mesh.face_degree(f) == 3 && mesh.face_rings(f).is_empty() {
            is_tri[f.index()] = true;
        }
    }
    // Per triangle, its candidate edges: (error, edge, other triangle).
    let mut around: Vec<Vec<(f64, EdgeId, FaceId)>> = vec![Vec::new(); n];
    let mut candidates: Vec<(f64, EdgeId)> = Vec::new();
    for &f in faces {
        if !is_tri[f.index()] {
            continue;
        }
        for h in mesh.face_halfedges(f) {
            let e = h.edge();
            let Some(g) = mesh.face(h.twin()) else {
                continue;
            };
            // Each edge once: from its half-edge 0's face.
            if g == f || !is_tri[g.index()] || h != e.halfedge(0) || !joinable(e) {
                continue;
            }
            let Some(loose) = join_error(mesh, e, face_angle_limit, loose_shape_limit) else {
                continue;
            };
            // Blender's error is below 2 + 4·π/2/(2π) = 3: good quads first.
            let good = join_error(mesh, e, face_angle_limit, shape_angle_limit).is_some();
            let error = if good { loose } else { loose + 3.0 };
            candidates.push((error, e));
            around[f.index()].push((error, e, g));
            around[g.index()].push((error, e, f));
        }
    }
    candidates.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    // mate[f] = (edge, partner) of a paired triangle.
    let mut mate: Vec<Option<(EdgeId, FaceId)>> = vec![None; n];
    for &(_, e) in &candidates {
        let [Some(a), Some(b)] = mesh.edge_faces(e) else {
            continue;
        };
        if mate[a.index()].is_none() && mate[b.index()].is_none() {
            mate[a.index()] = Some((e, b));
            mate[b.index()] = Some((e, a));
        }
    }
    for _ in 0..4 {
        let mut grown = false;
        for &a in faces {
            if !is_tri[a.index()] || mate[a.index()].is_some() {
                continue;
            }
            // The cheapest augmenting path a–b, c–d.
            let mut best: Option<(f64, EdgeId, FaceId, EdgeId, FaceId, FaceId)> = None;
            for &(ab, e_ab, b) in &around[a.index()] {
                let Some((_, c)) = mate[b.index()] else {
                    continue;
                };
                for &(cd, e_cd, d) in &around[c.index()] {
                    if d == a || d == b || mate[d.index()].is_some() {
                        continue;
                    }
                    if best.is_none_or(|x| ab + cd < x.0) {
                        best = Some((ab + cd, e_ab, b, e_cd, c, d));
                    }
                }
            }
            if let Some((_, e_ab, b, e_cd, c, d)) = best {
                mate[a.index()] = Some((e_ab, b));
                mate[b.index()] = Some((e_ab, a));
                mate[c.index()] = Some((e_cd, d));
                mate[d.index()] = Some((e_cd, c));
                grown = true;
            }
        }
        if !grown {
            break;
        }
    }
    let mut edges: Vec<EdgeId> = faces
        .iter()
        .filter_map(|&f| match mate[f.index()] {
            Some((e, g)) if is_tri[f.index()] && f.index() < g.index() => Some(e),
            _ => None,
        })
        .collect();
    edges.sort();
    edges.dedup();
    edges
}

/// How far a quad `[p0, p1, p2, p3]` is from flat: the larger of the
/// angles between the normals of the two triangles it splits into along
/// either diagonal (0 for a planar convex quad; π for a degenerate one,
/// whose triangles have no normal). The measure keep-quads Decimate and
/// Tris to Quads hold to their face angle limit.
pub fn quad_fold(quad: [glam::DVec3; 4]) -> f64 {
    let normal = |a: glam::DVec3, b: glam::DVec3, c: glam::DVec3| (b - a).cross(c - a);
    let fold = |n: glam::DVec3, m: glam::DVec3| {
        let angle = n.angle_between(m);
        if angle.is_nan() || n.length_squared() == 0.0 || m.length_squared() == 0.0 {
            PI
        } else {
            angle
        }
    };
    let [p0, p1, p2, p3] = quad;
    // Along p0–p2: (p0, p1, p2) and (p0, p2, p3); along p1–p3: (p1, p2, p3) and (p1, p3, p0).
    fold(normal(p0, p1, p2), normal(p0, p2, p3)).max(fold(normal(p1, p2, p3), normal(p1, p3, p0)))
}

/// The quad two triangles across `e` would make, corners in order, and
/// Blender's join error, or `None` when the pair is outside the limits.
fn join_error(mesh: &HalfEdgeMesh, e: EdgeId, face_limit: f64, shape_limit: f64) -> Option<f64> {
    let h = e.halfedge(0);
    let (f, g) = (mesh.face(h)?, mesh.face(h.twin())?);
    // h runs a→b inside f; the quad is a, (g's apex), b, (f's apex).
    let a = mesh.origin(h);
    let b = mesh.target(h);
    let apex_f = mesh.target(mesh.next(h));
    let apex_g = mesh.target(mesh.next(h.twin()));
    let quad = [a, apex_g, b, apex_f].map(|v| mesh.position(v));
    let normal_angle = mesh.face_normal(f).angle_between(mesh.face_normal(g));
    // NaN (a degenerate triangle) never joins.
    if normal_angle.is_nan() || normal_angle > face_limit {
        return None;
    }
    // The quad folds along its other diagonal too (the one another
    // reader's triangulation may split it along): a long, thin pair can be
    // nearly flat across the shared edge and folded far more across the
    // other diagonal. Both folds stay within the limit (issue 31, item 18).
    if quad_fold(quad) > face_limit {
        return None;
    }
    let normal = (quad[2] - quad[0]).cross(quad[3] - quad[1]);
    let mut shape = 0.0;
    for i in 0..4 {
        let (prev, here, next) = (quad[(i + 3) % 4], quad[i], quad[(i + 1) % 4]);
        let (into, out) = (here - prev, next - here);
        // Convex: every turn goes the same way around the quad's normal.
        if into.cross(out).dot(normal) <= 0.0 {
            return None;
        }
        let corner = (prev - here).angle_between(next - here);
        let off = (corner - FRAC_PI_2).abs();
        if off.is_nan() || off > shape_limit {
            return None;
        }
        shape += off;
    }
    Some(normal_angle / FRAC_PI_2 + shape / (2.0 * PI))
}
