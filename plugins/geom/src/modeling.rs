//! Modeling operations built on the Euler operators: what the edit-mode
//! tools run. Each one checks its input first and returns a named error
//! without changing the mesh, or applies completely.

use crate::euler::EulerError;
use crate::ids::{EdgeId, FaceId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;

/// Why a modeling operation refused; the mesh is unchanged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ModelingError {
    #[error("nothing selected: {0}")]
    Empty(&'static str),
    #[error("{0} does not exist")]
    Missing(String),
    #[error("{edge} has no quad on either side: a loop cut needs a ring of quads")]
    NoRing { edge: EdgeId },
    #[error("{edge} is not on a boundary (there is no hole to fill there)")]
    NotBoundary { edge: EdgeId },
    #[error("{a} and {b} do not share a face, or are already joined by an edge")]
    NotConnectable { a: VertexId, b: VertexId },
    #[error("{what} must be {allowed}, got {value}")]
    Parameter {
        what: &'static str,
        allowed: &'static str,
        value: String,
    },
    #[error(
        "the faces around {face} close a whole shell: dissolving them would leave no surface (select fewer faces)"
    )]
    ClosedShell { face: FaceId },
    #[error("the result would not be a valid mesh: {0}")]
    Invalid(String),
    #[error("no two of the vertices are within {distance} of each other: nothing to merge")]
    NothingToMerge { distance: f64 },
    #[error(transparent)]
    Euler(#[from] EulerError),
}

fn check_faces(mesh: &HalfEdgeMesh, faces: &[FaceId]) -> Result<(), ModelingError> {
    if faces.is_empty() {
        return Err(ModelingError::Empty("no faces"));
    }
    match faces.iter().find(|f| !mesh.is_face(**f)) {
        Some(f) => Err(ModelingError::Missing(f.to_string())),
        None => Ok(()),
    }
}

/// Extrudes each face on its own along its normal by `distance`
/// (Blender's "extrude individual faces"). Returns the new side faces.
///
/// # Errors
/// [`ModelingError::Missing`] for a dead face, [`ModelingError::Parameter`]
/// for a non-finite distance.
pub fn extrude_faces_individual(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    distance: f64,
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    if !distance.is_finite() {
        return Err(ModelingError::Parameter {
            what: "distance",
            allowed: "finite",
            value: distance.to_string(),
        });
    }
    let mut sides = Vec::new();
    for &f in faces {
        let n = mesh.face_normal(f);
        sides.extend(mesh.extrude_face(f, n * distance)?);
    }
    Ok(sides)
}

/// Extrudes a region of faces as one (Blender's E): the region is lifted by
/// `offset`, side quads join its boundary to where it was, and faces inside
/// the region stay joined. Vertices inside the region keep their ids; the
/// boundary gets new vertices and the caps are new faces, returned in the
/// order of `faces`. Built from [`HalfEdgeMesh::delete_faces`] and
/// [`HalfEdgeMesh::add_face`]; the result is validated before it replaces
/// the mesh.
///
/// # Errors
/// [`ModelingError::Missing`], [`ModelingError::Parameter`] for a non-finite
/// offset, [`ModelingError::Invalid`] when the region's shape cannot be
/// extruded manifold (for example two regions touching at one vertex).
pub fn extrude_region(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    offset: DVec3,
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    if !offset.is_finite() {
        return Err(ModelingError::Parameter {
            what: "offset",
            allowed: "finite",
            value: format!("{offset:?}"),
        });
    }
    rebuild_region(mesh, faces, |_, p| p + offset, |_, p| p + offset)
}

/// Insets a region of faces as one (Blender's I): a border `thickness` wide
/// runs inside the region's outline, and the region is pushed by `depth`
/// along its average normal. Corners of the outline move along the bisector
/// of their two outline edges by thickness / cos(half the turn), so the
/// border keeps its width.
///
/// # Errors
/// As [`extrude_region`]; thickness must be finite and not negative.
pub fn inset_region(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    thickness: f64,
    depth: f64,
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    if !(thickness.is_finite() && thickness >= 0.0) || !depth.is_finite() {
        return Err(ModelingError::Parameter {
            what: "thickness and depth",
            allowed: "finite, thickness >= 0",
            value: format!("{thickness}, {depth}"),
        });
    }
    let normal = mesh.region_normal(faces);
    let in_region = |f: Option<FaceId>| f.is_some_and(|f| faces.contains(&f));
    // Inward normals (in the region's plane) of the outline edges at each corner.
    let mut inward: std::collections::HashMap<VertexId, Vec<DVec3>> =
        std::collections::HashMap::new();
    for &f in faces {
        for h in mesh
            .face_halfedges(f)
            .filter(|&h| !in_region(mesh.face(h.twin())))
        {
            let d =
                (mesh.position(mesh.target(h)) - mesh.position(mesh.origin(h))).normalize_or_zero();
            let n_edge = normal.cross(d);
            for v in [mesh.origin(h), mesh.target(h)] {
                inward.entry(v).or_default().push(n_edge);
            }
        }
    }
    let corner = |v: VertexId, p: DVec3| -> DVec3 {
        let dirs = &inward[&v];
        let bisector = dirs.iter().copied().sum::<DVec3>().normalize_or_zero();
        let cos_half = if dirs.len() == 2 {
            dirs[0].dot(bisector).max(1e-3)
        } else {
            1.0
        };
        p + bisector * (thickness / cos_half) + normal * depth
    };
    rebuild_region(mesh, faces, corner, |_, p| p + normal * depth)
}

/// Replaces a region of faces by caps over new outline vertices placed by
/// `outline` and old inner vertices moved by `inner`, joined to the old
/// outline by side quads: the shared core of region extrude and inset.
fn rebuild_region(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    outline: impl Fn(VertexId, DVec3) -> DVec3,
    inner: impl Fn(VertexId, DVec3) -> DVec3,
) -> Result<Vec<FaceId>, ModelingError> {
    let mut region: Vec<FaceId> = faces.to_vec();
    region.sort();
    region.dedup();
    let in_region = |f: Option<FaceId>| f.is_some_and(|f| region.binary_search(&f).is_ok());
    let boundary: Vec<(VertexId, VertexId)> = region
        .iter()
        .flat_map(|&f| mesh.face_halfedges(f))
        .filter(|&h| !in_region(mesh.face(h.twin())))
        .map(|h| (mesh.origin(h), mesh.target(h)))
        .collect();
    let polys: Vec<Vec<VertexId>> = faces
        .iter()
        .map(|&f| mesh.face_vertices(f).collect())
        .collect();
    let mut work = mesh.clone();
    work.delete_faces(&region, true);
    let mut copy = std::collections::HashMap::new();
    let mut moved = std::collections::HashSet::new();
    for p in &polys {
        for &v in p {
            if boundary.iter().any(|&(a, _)| a == v) {
                if !copy.contains_key(&v) {
                    let at = outline(v, work.position(v));
                    copy.insert(v, work.add_vertex(at)?);
                }
            } else if moved.insert(v) {
                let at = inner(v, work.position(v));
                work.set_position(v, at);
            }
        }
    }
    let lift = |v: VertexId| copy.get(&v).copied().unwrap_or(v);
    let invalid = |why: String| ModelingError::Invalid(why);
    for &(a, b) in &boundary {
        work.add_face(&[a, b, lift(b), lift(a)])
            .map_err(|e| invalid(format!("side of edge {a}-{b}: {e}")))?;
    }
    let mut caps = Vec::with_capacity(polys.len());
    for p in &polys {
        let lifted: Vec<VertexId> = p.iter().map(|&v| lift(v)).collect();
        caps.push(
            work.add_face(&lifted)
                .map_err(|e| invalid(format!("cap: {e}")))?,
        );
    }
    work.validate().map_err(|e| invalid(e.to_string()))?;
    *mesh = work;
    Ok(caps)
}

/// Insets each face on its own: a border of quads `thickness` wide inside
/// the face, the inner face pushed along the normal by `depth` (Blender's
/// inset, "individual"). Corners move along their bisector by
/// thickness / sin(half the corner angle), so the border keeps its width.
///
/// # Errors
/// As [`extrude_faces_individual`]; a thickness below zero is refused.
pub fn inset_faces_individual(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
    thickness: f64,
    depth: f64,
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    if !(thickness.is_finite() && thickness >= 0.0) || !depth.is_finite() {
        return Err(ModelingError::Parameter {
            what: "thickness and depth",
            allowed: "finite, thickness >= 0",
            value: format!("{thickness}, {depth}"),
        });
    }
    let mut sides = Vec::new();
    for &f in faces {
        let normal = mesh.face_normal(f);
        let corners: Vec<VertexId> = mesh.face_vertices(f).collect();
        let pts: Vec<DVec3> = corners.iter().map(|&v| mesh.position(v)).collect();
        let n = pts.len();
        let targets: Vec<DVec3> = (0..n)
            .map(|i| {
                let p = pts[i];
                let to_prev = (pts[(i + n - 1) % n] - p).normalize_or_zero();
                let to_next = (pts[(i + 1) % n] - p).normalize_or_zero();
                let bisector = (to_prev + to_next).normalize_or_zero();
                let half_angle_sin = (to_prev.angle_between(to_next) / 2.0).sin().max(1e-3);
                // A reflex corner's bisector points outwards: flip it inwards.
                let inward = if to_next.cross(to_prev).dot(normal) < 0.0 {
                    -bisector
                } else {
                    bisector
                };
                p + inward * (thickness / half_angle_sin) + normal * depth
            })
            .collect();
        sides.extend(mesh.extrude_face(f, DVec3::ZERO)?);
        for (v, t) in mesh
            .face_vertices(f)
            .collect::<Vec<_>>()
            .into_iter()
            .zip(rotate_to_match(&corners, mesh, f, &targets))
        {
            mesh.set_position(v, t);
        }
    }
    Ok(sides)
}

/// The cap of an extruded face starts at the corner after the first original
/// corner; line the targets up with the cap's vertex order by position.
fn rotate_to_match(
    original: &[VertexId],
    mesh: &HalfEdgeMesh,
    cap: FaceId,
    targets: &[DVec3],
) -> Vec<DVec3> {
    let cap_pts: Vec<DVec3> = mesh.face_vertices(cap).map(|v| mesh.position(v)).collect();
    let first = mesh.position(original[0]);
    let shift = cap_pts
        .iter()
        .position(|p| p.distance_squared(first) < 1e-24)
        .unwrap_or(0);
    (0..cap_pts.len())
        .map(|i| targets[(i + targets.len() - shift) % targets.len()])
        .collect()
}

/// The edge ring through `edge`: half-edges crossing a strip of quads, all
/// pointing the same way, and whether the ring closes.
pub fn edge_ring(mesh: &HalfEdgeMesh, edge: EdgeId) -> (Vec<HalfEdgeId>, bool) {
    let start = edge.halfedge(0);
    let is_quad = |h: HalfEdgeId| mesh.face(h).is_some_and(|f| mesh.face_degree(f) == 4);
    let step = |h: HalfEdgeId| -> Option<HalfEdgeId> {
        is_quad(h).then(|| mesh.next(mesh.next(h)).twin())
    };
    let mut forward = vec![start];
    let mut h = start;
    while let Some(n) = step(h) {
        if n == start {
            return (forward, true);
        }
        if forward.contains(&n) || forward.len() > mesh.edge_count() {
            break;
        }
        forward.push(n);
        h = n;
    }
    // Open ring: also walk backwards from the start through the other side.
    let mut backward = Vec::new();
    let mut h = start.twin();
    while let Some(n) = step(h) {
        let parallel = n.twin();
        if forward.contains(&parallel) || backward.contains(&parallel) {
            break;
        }
        backward.push(parallel);
        h = n;
    }
    backward.reverse();
    backward.extend(forward);
    (backward, false)
}

/// Loop cut (Blender's Ctrl+R): `cuts` new edge loops across the ring of
/// quads through `edge`, evenly spaced. Returns the new edges along the loops.
///
/// # Errors
/// [`ModelingError::NoRing`] when no quad touches the edge,
/// [`ModelingError::Parameter`] for 0 or more than 64 cuts.
pub fn loop_cut(
    mesh: &mut HalfEdgeMesh,
    edge: EdgeId,
    cuts: u32,
) -> Result<Vec<EdgeId>, ModelingError> {
    if !mesh.is_edge(edge) {
        return Err(ModelingError::Missing(edge.to_string()));
    }
    if !(1..=64).contains(&cuts) {
        return Err(ModelingError::Parameter {
            what: "cuts",
            allowed: "1 to 64",
            value: cuts.to_string(),
        });
    }
    let (ring, closed) = edge_ring(mesh, edge);
    let quad_between = |a: HalfEdgeId| mesh.face(a).is_some_and(|f| mesh.face_degree(f) == 4);
    if !ring
        .iter()
        .any(|&h| quad_between(h) || quad_between(h.twin()))
    {
        return Err(ModelingError::NoRing { edge });
    }
    // Faces to cut: between consecutive ring half-edges (each ring half-edge's own face).
    let faces: Vec<FaceId> = ring
        .iter()
        .take(if closed { ring.len() } else { ring.len() - 1 })
        .map(|&h| mesh.face(h).expect("ring half-edges lie on quads"))
        .collect();
    // New vertices on every ring edge, ordered from the half-edge's origin.
    let mut rails: Vec<Vec<VertexId>> = Vec::with_capacity(ring.len());
    for &h in &ring {
        let (pa, pb) = (mesh.position(mesh.origin(h)), mesh.position(mesh.target(h)));
        let e = h.edge();
        // `split_edge` keeps the edge from its first vertex `s` to the new one,
        // so split at the points farthest from `s` first.
        let from_start = mesh.edge_vertices(e)[0] == mesh.origin(h);
        let order: Vec<usize> = if from_start {
            (0..cuts as usize).rev().collect()
        } else {
            (0..cuts as usize).collect()
        };
        let mut made = vec![VertexId(0); cuts as usize];
        for k in order {
            made[k] = mesh.split_edge(e, pa.lerp(pb, (k + 1) as f64 / (cuts + 1) as f64))?;
        }
        rails.push(made);
    }
    let mut new_edges = Vec::new();
    for (i, &f) in faces.iter().enumerate() {
        let next_rail = &rails[(i + 1) % rails.len()];
        for k in 0..cuts as usize {
            let (a, b) = (rails[i][k], next_rail[k]);
            let e = connect_in_shared_face(mesh, a, b, Some(f))?;
            new_edges.push(e);
        }
    }
    Ok(new_edges)
}

/// Joins two vertices of a common face by a new edge (MEF), preferring `hint`.
fn connect_in_shared_face(
    mesh: &mut HalfEdgeMesh,
    a: VertexId,
    b: VertexId,
    hint: Option<FaceId>,
) -> Result<EdgeId, ModelingError> {
    let incoming = |mesh: &HalfEdgeMesh, v: VertexId| -> Vec<HalfEdgeId> {
        mesh.vertex_outgoing(v)
            .map(|h| h.twin())
            .filter(|h| mesh.face(*h).is_some())
            .collect()
    };
    let ins_a = incoming(mesh, a);
    let ins_b = incoming(mesh, b);
    let view: &HalfEdgeMesh = mesh;
    let mut pairs: Vec<(HalfEdgeId, HalfEdgeId)> = Vec::new();
    for &ha in &ins_a {
        for &hb in &ins_b {
            if view.face(hb) == view.face(ha) {
                pairs.push((ha, hb));
            }
        }
    }
    pairs.sort_by_key(|(ha, _)| view.face(*ha) != hint);
    if mesh.find_edge(a, b).is_some() {
        return Err(ModelingError::NotConnectable { a, b });
    }
    let (ha, hb) = *pairs
        .first()
        .ok_or(ModelingError::NotConnectable { a, b })?;
    Ok(mesh.make_edge_face(ha, hb)?.0)
}

/// Splits faces into triangles (Blender's Ctrl+T): each face is cut along
/// the diagonals of its ear-clipping triangulation
/// ([`crate::query::triangulate_face`]), one Euler MEF
/// ([`HalfEdgeMesh::make_edge_face`]) per diagonal; positions do not move
/// and triangles are left as they are. Returns the faces made.
///
/// # Errors
/// [`ModelingError::Missing`] for a face that does not exist.
pub fn triangulate_faces(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
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
        for t in crate::query::triangulate_face(mesh, f) {
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

/// Connects pairs of vertices that share a face (Blender's J).
///
/// # Errors
/// [`ModelingError::NotConnectable`] naming the pair.
pub fn connect_vertices(
    mesh: &mut HalfEdgeMesh,
    a: VertexId,
    b: VertexId,
) -> Result<EdgeId, ModelingError> {
    for v in [a, b] {
        if !mesh.is_vertex(v) {
            return Err(ModelingError::Missing(v.to_string()));
        }
    }
    connect_in_shared_face(mesh, a, b, None)
}

/// Splits each edge into `cuts + 1` equal parts. Returns the new vertices.
///
/// # Errors
/// [`ModelingError::Missing`], [`ModelingError::Parameter`] (1 to 64 cuts).
pub fn subdivide_edges(
    mesh: &mut HalfEdgeMesh,
    edges: &[EdgeId],
    cuts: u32,
) -> Result<Vec<VertexId>, ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no edges"));
    }
    if let Some(e) = edges.iter().find(|e| !mesh.is_edge(**e)) {
        return Err(ModelingError::Missing(e.to_string()));
    }
    if !(1..=64).contains(&cuts) {
        return Err(ModelingError::Parameter {
            what: "cuts",
            allowed: "1 to 64",
            value: cuts.to_string(),
        });
    }
    let mut out = Vec::new();
    for &e in edges {
        let [a, b] = mesh.edge_vertices(e);
        let (pa, pb) = (mesh.position(a), mesh.position(b));
        // Split from the far end so the original edge keeps shrinking towards `a`.
        for k in (1..=cuts).rev() {
            out.push(mesh.split_edge(e, pa.lerp(pb, k as f64 / (cuts + 1) as f64))?);
        }
    }
    Ok(out)
}

/// Removes edges between two faces, merging the faces (KEF).
///
/// # Errors
/// The first edge that cannot be dissolved, with the reason; edges before it
/// are dissolved on a copy only, so the mesh stays unchanged on error.
pub fn dissolve_edges(mesh: &mut HalfEdgeMesh, edges: &[EdgeId]) -> Result<(), ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no edges"));
    }
    let mut work = mesh.clone();
    for &e in edges {
        if !work.is_edge(e) {
            return Err(ModelingError::Missing(e.to_string()));
        }
        work.kill_edge_face(e)?;
    }
    *mesh = work;
    Ok(())
}

/// Removes vertices of valence 2, joining their edges (KVE).
///
/// # Errors
/// As [`dissolve_edges`].
pub fn dissolve_vertices(
    mesh: &mut HalfEdgeMesh,
    vertices: &[VertexId],
) -> Result<(), ModelingError> {
    if vertices.is_empty() {
        return Err(ModelingError::Empty("no vertices"));
    }
    let mut work = mesh.clone();
    for &v in vertices {
        work.join_edges(v)?;
    }
    *mesh = work;
    Ok(())
}

/// Deletes faces but keeps their edges and vertices: each becomes a hole.
/// Faces that touch a boundary are refused (the mesh would stop being
/// manifold at that vertex); neighbouring faces are handled in order, so a
/// face next to an earlier one is refused too.
///
/// # Errors
/// The first face that cannot become a hole; the mesh is unchanged.
pub fn make_holes(mesh: &mut HalfEdgeMesh, faces: &[FaceId]) -> Result<(), ModelingError> {
    check_faces(mesh, faces)?;
    let mut work = mesh.clone();
    for &f in faces {
        work.make_hole(f)?;
    }
    *mesh = work;
    Ok(())
}

/// Fills the boundary loops through the given edges with one face each (F).
///
/// # Errors
/// [`ModelingError::Missing`], or the edge is not on a boundary.
pub fn fill_holes(mesh: &mut HalfEdgeMesh, edges: &[EdgeId]) -> Result<Vec<FaceId>, ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no boundary edges"));
    }
    let mut work = mesh.clone();
    let mut out = Vec::new();
    for &e in edges {
        if !work.is_edge(e) {
            return Err(ModelingError::Missing(e.to_string()));
        }
        let h = [e.halfedge(0), e.halfedge(1)]
            .into_iter()
            .find(|&h| work.is_boundary_halfedge(h));
        match h {
            Some(h) => out.push(work.fill_hole(h)?),
            None if out.iter().any(|&f| work.edge_faces(e).contains(&Some(f))) => {} // filled by an earlier edge of the same loop
            None => return Err(ModelingError::NotBoundary { edge: e }),
        }
    }
    *mesh = work;
    Ok(out)
}

/// Makes closed shells face outwards: a shell with negative volume is
/// flipped. Open shells are left as they are.
pub fn recalculate_normals_outward(mesh: &mut HalfEdgeMesh) -> bool {
    if mesh.boundary_loops().is_empty() && mesh.volume() < 0.0 {
        mesh.reverse_orientation();
        true
    } else {
        false
    }
}

/// Collapses each edge to its midpoint (edge collapse).
///
/// # Errors
/// The first edge that cannot collapse, with the reason; the mesh is unchanged.
pub fn collapse_edges(
    mesh: &mut HalfEdgeMesh,
    edges: &[EdgeId],
) -> Result<Vec<VertexId>, ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no edges"));
    }
    let mut work = mesh.clone();
    let mut kept = Vec::new();
    for &e in edges {
        if !work.is_edge(e) {
            continue; // removed by an earlier collapse of this call
        }
        let mid = work.edge_midpoint(e);
        kept.push(work.collapse_edge_removing_triangles(e.halfedge(0), mid)?);
    }
    *mesh = work;
    Ok(kept)
}

/// Merges vertices joined by edges into one at their centre (Blender's
/// M ▸ At Center), collapsing the edges between them; faces that shrink to
/// nothing disappear.
///
/// # Errors
/// [`ModelingError::Empty`] for fewer than two vertices,
/// [`ModelingError::NotConnectable`] when the vertices are not all joined
/// by edges among themselves, or the reason a collapse was refused; the
/// mesh is unchanged on error.
pub fn merge_at_center(
    mesh: &mut HalfEdgeMesh,
    vertices: &[VertexId],
) -> Result<VertexId, ModelingError> {
    if vertices.len() < 2 {
        return Err(ModelingError::Empty("merging needs at least two vertices"));
    }
    if let Some(v) = vertices.iter().find(|v| !mesh.is_vertex(**v)) {
        return Err(ModelingError::Missing(v.to_string()));
    }
    let center = vertices.iter().map(|&v| mesh.position(v)).sum::<DVec3>() / vertices.len() as f64;
    merge_at(mesh, vertices, center)
}

/// Where [`merge_vertices`] puts the merged vertex (Blender's M menu).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum MergePoint {
    /// The centre of the vertices.
    #[default]
    Center,
    /// The first vertex given (the first one selected).
    First,
    /// The last vertex given (the last one selected).
    Last,
}

/// Merges vertices into one at `point` (Blender's M ▸ At Center / At First
/// / At Last). Vertices joined by edges among themselves collapse those
/// edges (faces that shrink to nothing disappear, the other elements keep
/// their ids); vertices that are not joined, such as the two sides of a
/// seam, are welded with [`weld_vertices`].
///
/// # Errors
/// As [`merge_at_center`] and [`weld_vertices`]; the mesh is unchanged on error.
pub fn merge_vertices(
    mesh: &mut HalfEdgeMesh,
    vertices: &[VertexId],
    point: MergePoint,
) -> Result<VertexId, ModelingError> {
    if vertices.len() < 2 {
        return Err(ModelingError::Empty("merging needs at least two vertices"));
    }
    if let Some(v) = vertices.iter().find(|v| !mesh.is_vertex(**v)) {
        return Err(ModelingError::Missing(v.to_string()));
    }
    let target = match point {
        MergePoint::Center => {
            vertices.iter().map(|&v| mesh.position(v)).sum::<DVec3>() / vertices.len() as f64
        }
        MergePoint::First => mesh.position(vertices[0]),
        MergePoint::Last => mesh.position(vertices[vertices.len() - 1]),
    };
    match merge_at(mesh, vertices, target) {
        Err(ModelingError::NotConnectable { .. }) => {
            let mut cluster = vertices.to_vec();
            if point == MergePoint::Last {
                cluster.rotate_right(1); // the kept vertex comes first
            }
            weld_vertices(mesh, &[(cluster.clone(), target)])?;
            Ok(cluster[0])
        }
        other => other,
    }
}

/// Merges vertices joined by edges among themselves into one at `target` by
/// collapsing those edges.
fn merge_at(
    mesh: &mut HalfEdgeMesh,
    vertices: &[VertexId],
    center: DVec3,
) -> Result<VertexId, ModelingError> {
    let mut work = mesh.clone();
    let mut alive: Vec<VertexId> = vertices.to_vec();
    alive.sort();
    alive.dedup();
    while alive.len() > 1 {
        let edge = work.edges().find(|&e| {
            work.edge_vertices(e)
                .iter()
                .all(|v| alive.binary_search(v).is_ok())
        });
        let Some(e) = edge else {
            return Err(ModelingError::NotConnectable {
                a: alive[0],
                b: alive[1],
            });
        };
        work.collapse_edge_removing_triangles(e.halfedge(0), center)?;
        alive.retain(|&v| work.is_vertex(v));
    }
    work.set_position(alive[0], center);
    *mesh = work;
    Ok(alive[0])
}

/// Welds each cluster of vertices into its first vertex, placed at the
/// cluster's point (Wings 3D's weld; what Merge by Distance does across a
/// seam). The faces around the other vertices are taken out and added back
/// over the kept vertices (pmp-library's `delete_face` / `add_face`, which
/// keep the mesh manifold or refuse); a face whose corners run together
/// loses them, and one left with fewer than three corners disappears. The
/// faces added back get new ids; every other element keeps its id.
/// Returns how many vertices were removed.
///
/// # Errors
/// [`ModelingError::Missing`] for a dead vertex, [`ModelingError::Invalid`]
/// when the weld would make an edge or vertex non-manifold (naming where),
/// or a face would meet itself at a vertex; the mesh is unchanged on error.
pub fn weld_vertices(
    mesh: &mut HalfEdgeMesh,
    clusters: &[(Vec<VertexId>, DVec3)],
) -> Result<usize, ModelingError> {
    let mut keep: std::collections::HashMap<VertexId, VertexId> = Default::default();
    for (cluster, _) in clusters {
        if let Some(v) = cluster.iter().find(|v| !mesh.is_vertex(**v)) {
            return Err(ModelingError::Missing(v.to_string()));
        }
        for &v in &cluster[1..] {
            if v != cluster[0] {
                keep.insert(v, cluster[0]);
            }
        }
    }
    let mut work = mesh.clone();
    let gone: Vec<VertexId> = keep.keys().copied().collect();
    let faces = faces_around_vertices(&work, &gone);
    let mut polygons = Vec::with_capacity(faces.len());
    for &f in &faces {
        let mut corners: Vec<VertexId> = work
            .face_vertices(f)
            .map(|v| keep.get(&v).copied().unwrap_or(v))
            .collect();
        corners.dedup();
        while corners.len() > 1 && corners.first() == corners.last() {
            corners.pop();
        }
        if corners.len() < 3 {
            continue; // the face collapsed
        }
        let mut sorted = corners.clone();
        sorted.sort();
        if sorted.windows(2).any(|w| w[0] == w[1]) {
            return Err(ModelingError::Invalid(format!(
                "welding would make {f} meet itself at a vertex"
            )));
        }
        polygons.push(corners);
    }
    work.delete_faces(&faces, true);
    for &v in &gone {
        if !work.is_isolated_vertex(v) {
            return Err(ModelingError::Invalid(format!(
                "{v} has edges without faces; delete them before welding"
            )));
        }
        work.free_vertex(v);
    }
    for (cluster, point) in clusters {
        work.set_position(cluster[0], *point);
    }
    add_faces_in_any_order(&mut work, polygons, "welding")?;
    work.validate()
        .map_err(|e| ModelingError::Invalid(e.to_string()))?;
    *mesh = work;
    Ok(gone.len())
}

/// Adds polygons with pmp's `add_face`, which relinks boundary fans: a face
/// that cannot attach yet may attach once its neighbours are in, so the
/// failed ones are retried until a pass adds nothing. Returns the new faces
/// in the order the polygons were given.
fn add_faces_in_any_order(
    work: &mut HalfEdgeMesh,
    polygons: Vec<Vec<VertexId>>,
    what: &str,
) -> Result<Vec<FaceId>, ModelingError> {
    let mut added = vec![None; polygons.len()];
    let mut pending: Vec<usize> = (0..polygons.len()).collect();
    while !pending.is_empty() {
        let before = pending.len();
        let mut failed = Vec::new();
        let mut last_error = None;
        for i in pending {
            match work.add_face(&polygons[i]) {
                Ok(f) => added[i] = Some(f),
                Err(e) => {
                    last_error = Some(e);
                    failed.push(i);
                }
            }
        }
        if failed.len() == before {
            return Err(ModelingError::Invalid(format!(
                "{what} would make the surface non-manifold ({})",
                last_error.map_or_else(String::new, |e| e.to_string())
            )));
        }
        pending = failed;
    }
    Ok(added.into_iter().flatten().collect())
}

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
            return Err(ModelingError::Missing(v.to_string()));
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
    work.validate()
        .map_err(|e| ModelingError::Invalid(e.to_string()))?;
    *mesh = work;
    Ok(added[face_count.min(added.len())..].to_vec())
}

/// Merges vertices closer than `distance` to each other (Blender's Merge by
/// Distance): clusters of `candidates` linked by distances up to `distance`
/// are welded into their lowest-id vertex at the cluster's centre (see
/// [`weld_vertices`]). Clusters come from a uniform grid of cell size
/// `distance`, so the search is O(n) expected. Returns the number of
/// vertices removed.
///
/// # Errors
/// [`ModelingError::Parameter`] for a negative or non-finite distance,
/// [`ModelingError::NothingToMerge`] when no two candidates are that close,
/// or [`weld_vertices`]'s errors; the mesh is unchanged on error.
pub fn merge_by_distance(
    mesh: &mut HalfEdgeMesh,
    candidates: &[VertexId],
    distance: f64,
) -> Result<usize, ModelingError> {
    if !(distance.is_finite() && distance >= 0.0) {
        return Err(ModelingError::Parameter {
            what: "merge distance",
            allowed: "a finite distance ≥ 0",
            value: distance.to_string(),
        });
    }
    if let Some(v) = candidates.iter().find(|v| !mesh.is_vertex(**v)) {
        return Err(ModelingError::Missing(v.to_string()));
    }
    let mut vs: Vec<VertexId> = candidates.to_vec();
    vs.sort();
    vs.dedup();
    let cell = distance.max(1e-12);
    let key = |p: DVec3| (p / cell).floor().as_i64vec3();
    let mut grid: std::collections::HashMap<glam::I64Vec3, Vec<usize>> = Default::default();
    for (i, &v) in vs.iter().enumerate() {
        grid.entry(key(mesh.position(v))).or_default().push(i);
    }
    // Union-find over the candidates.
    let mut parent: Vec<usize> = (0..vs.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for (i, &v) in vs.iter().enumerate() {
        let p = mesh.position(v);
        let k = key(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(cell) = grid.get(&(k + glam::I64Vec3::new(dx, dy, dz))) else {
                        continue;
                    };
                    for &j in cell {
                        if j > i && mesh.position(vs[j]).distance(p) <= distance {
                            let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                            parent[a.max(b)] = a.min(b);
                        }
                    }
                }
            }
        }
    }
    let mut groups: std::collections::BTreeMap<usize, Vec<VertexId>> = Default::default();
    for i in 0..vs.len() {
        let r = root(&mut parent, i);
        groups.entry(r).or_default().push(vs[i]);
    }
    let clusters: Vec<(Vec<VertexId>, DVec3)> = groups
        .into_values()
        .filter(|g| g.len() > 1)
        .map(|g| {
            let centre = g.iter().map(|&v| mesh.position(v)).sum::<DVec3>() / g.len() as f64;
            (g, centre)
        })
        .collect();
    if clusters.is_empty() {
        return Err(ModelingError::NothingToMerge { distance });
    }
    weld_vertices(mesh, &clusters)
}

/// Reverses the orientation of every face (flip normals). Connectivity is
/// relinked half-edge by half-edge: origin becomes the old target, next and
/// prev swap. ΔV = ΔE = ΔF = 0; applying it twice restores the mesh.
pub fn flip_normals(mesh: &mut HalfEdgeMesh) {
    mesh.reverse_orientation();
}

/// Bridges two boundary loops with a ring of quads (Blender's "Bridge Edge
/// Loops"). `edges` name at least one edge of each loop; the loops need the
/// same number of edges. Vertices are paired around the loops with the
/// rotation that keeps the quads shortest. Returns the new faces.
///
/// # Errors
/// [`ModelingError::Parameter`] when the edges do not lie on exactly two
/// boundary loops of equal length; [`ModelingError::Invalid`] when the
/// quads cannot be added manifold. The mesh is unchanged on error.
pub fn bridge_loops(
    mesh: &mut HalfEdgeMesh,
    edges: &[EdgeId],
) -> Result<Vec<FaceId>, ModelingError> {
    if let Some(e) = edges.iter().find(|e| !mesh.is_edge(**e)) {
        return Err(ModelingError::Missing(e.to_string()));
    }
    let loops = mesh.boundary_loops();
    let mut chosen: Vec<&Vec<HalfEdgeId>> = loops
        .iter()
        .filter(|l| l.iter().any(|h| edges.contains(&h.edge())))
        .collect();
    chosen.dedup();
    if chosen.len() != 2 || chosen[0].len() != chosen[1].len() {
        return Err(ModelingError::Parameter {
            what: "edges",
            allowed: "edges of exactly two boundary loops with the same number of edges",
            value: format!(
                "{} loop(s) of lengths {:?}",
                chosen.len(),
                chosen.iter().map(|l| l.len()).collect::<Vec<_>>()
            ),
        });
    }
    let a: Vec<VertexId> = chosen[0].iter().map(|&h| mesh.origin(h)).collect();
    let b: Vec<VertexId> = chosen[1].iter().map(|&h| mesh.origin(h)).collect();
    let n = a.len();
    let at = |k: i64| b[k.rem_euclid(n as i64) as usize];
    // a[i] pairs with b[s - i]: the loops run in opposite directions across the bridge.
    let cost = |s: i64| -> f64 {
        (0..n as i64)
            .map(|i| {
                mesh.position(a[i as usize])
                    .distance_squared(mesh.position(at(s - i)))
            })
            .sum()
    };
    let s = (0..n as i64)
        .min_by(|x, y| cost(*x).total_cmp(&cost(*y)))
        .expect("loops are not empty");
    let mut work = mesh.clone();
    let mut out = Vec::with_capacity(n);
    for i in 0..n as i64 {
        let quad = [
            a[i as usize],
            a[((i + 1) as usize) % n],
            at(s - i - 1),
            at(s - i),
        ];
        out.push(
            work.add_face(&quad)
                .map_err(|e| ModelingError::Invalid(format!("bridge quad {i}: {e}")))?,
        );
    }
    work.validate()
        .map_err(|e| ModelingError::Invalid(e.to_string()))?;
    *mesh = work;
    Ok(out)
}

/// Extrudes boundary edges (Blender's E on edges of an open border): each
/// gets a new quad on its open side, reaching to copies of its ends moved by
/// `offset`; neighbouring edges share the copies. Returns the new faces.
///
/// # Errors
/// [`ModelingError::NotBoundary`] for an edge with faces on both sides,
/// [`ModelingError::Invalid`] when the quads cannot be added manifold; the
/// mesh is unchanged on error.
pub fn extrude_boundary_edges(
    mesh: &mut HalfEdgeMesh,
    edges: &[EdgeId],
    offset: DVec3,
) -> Result<Vec<FaceId>, ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no edges"));
    }
    if !offset.is_finite() {
        return Err(ModelingError::Parameter {
            what: "offset",
            allowed: "finite",
            value: format!("{offset:?}"),
        });
    }
    let mut sides = Vec::with_capacity(edges.len());
    for &e in edges {
        if !mesh.is_edge(e) {
            return Err(ModelingError::Missing(e.to_string()));
        }
        let h = [e.halfedge(0), e.halfedge(1)]
            .into_iter()
            .find(|&h| mesh.is_boundary_halfedge(h))
            .ok_or(ModelingError::NotBoundary { edge: e })?;
        sides.push((mesh.origin(h), mesh.target(h)));
    }
    let mut work = mesh.clone();
    let mut copy = std::collections::HashMap::new();
    for &(x, y) in &sides {
        for v in [x, y] {
            if !copy.contains_key(&v) {
                let c = work.add_vertex(work.position(v) + offset)?;
                copy.insert(v, c);
            }
        }
    }
    let mut out = Vec::with_capacity(sides.len());
    for &(x, y) in &sides {
        let f = work
            .add_face(&[x, y, copy[&y], copy[&x]])
            .map_err(|e| ModelingError::Invalid(format!("edge {x}-{y}: {e}")))?;
        out.push(f);
    }
    work.validate()
        .map_err(|e| ModelingError::Invalid(e.to_string()))?;
    *mesh = work;
    Ok(out)
}

/// A face of `region` whose edge-connected part of the region has no edge
/// on its outline (every neighbour across every edge is in the region):
/// that part is a whole closed shell.
fn closed_shell_in(
    mesh: &HalfEdgeMesh,
    region: &std::collections::BTreeSet<FaceId>,
) -> Option<FaceId> {
    let mut seen = std::collections::BTreeSet::new();
    for &start in region {
        if !seen.insert(start) {
            continue;
        }
        let (mut stack, mut closed) = (vec![start], true);
        while let Some(f) = stack.pop() {
            for h in mesh.face_halfedges(f) {
                match mesh.face(h.twin()) {
                    Some(g) if region.contains(&g) => {
                        if seen.insert(g) {
                            stack.push(g);
                        }
                    }
                    _ => closed = false,
                }
            }
        }
        if closed {
            return Some(start);
        }
    }
    None
}

/// Merges adjacent faces into one by removing the edges between them, and
/// then the edges left dangling inside (Blender's dissolve faces). Returns
/// the faces left of the region.
///
/// # Errors
/// [`ModelingError::Missing`], [`ModelingError::ClosedShell`] when the
/// selection covers a whole closed shell (there is no outline left to make a
/// face of), [`ModelingError::Invalid`] if the result would not be valid; the
/// mesh is unchanged on error.
pub fn dissolve_faces(
    mesh: &mut HalfEdgeMesh,
    faces: &[FaceId],
) -> Result<Vec<FaceId>, ModelingError> {
    check_faces(mesh, faces)?;
    let mut region: std::collections::BTreeSet<FaceId> = faces.iter().copied().collect();
    if let Some(face) = closed_shell_in(mesh, &region) {
        return Err(ModelingError::ClosedShell { face });
    }
    let mut work = mesh.clone();
    // Grow one face over its region neighbours, one neighbour at a time, so
    // the growing face never closes a ring: the edges it shares with the
    // neighbour form one chain; join the chain's inner vertices (KVE) until
    // one edge is left, then remove it (KEF).
    let mut pending: Vec<FaceId> = region.iter().copied().collect();
    while let Some(seed) = pending.pop() {
        if !work.is_face(seed) {
            continue;
        }
        let mut current = seed;
        loop {
            let shared: Vec<HalfEdgeId> = work
                .face_halfedges(current)
                .filter(|&h| {
                    work.face(h.twin())
                        .is_some_and(|g| g != current && region.contains(&g))
                })
                .collect();
            let Some(&first) = shared.first() else { break };
            let other = work.face(first.twin()).expect("filtered");
            let chain: Vec<HalfEdgeId> = shared
                .iter()
                .copied()
                .filter(|&h| work.face(h.twin()) == Some(other))
                .collect();
            // Inner vertices of the chain (both of their edges are in it).
            for &h in &chain {
                let v = work.target(h);
                if chain.iter().any(|&g| work.origin(g) == v) && work.vertex_valence(v) == 2 {
                    let _ = work.join_edges(v);
                }
            }
            let remaining: Vec<HalfEdgeId> = work
                .halfedges()
                .filter(|&h| work.face(h) == Some(current) && work.face(h.twin()) == Some(other))
                .collect();
            let Some(&h) = remaining.first() else { break };
            // Keep `current`: it must be the face of the half-edge 0 side.
            let e = h.edge();
            let survivor_side = if e.halfedge(0) == h { current } else { other };
            match work.kill_edge_face(e) {
                Ok(gone) => {
                    region.remove(&gone);
                    current = survivor_side;
                }
                Err(_) => break,
            }
        }
    }
    // Remove edges left dangling inside the merged faces.
    loop {
        let dangling = work.edges().find(|&e| {
            let [a, b] = work.edge_faces(e);
            a.is_some()
                && a == b
                && region.contains(&a.unwrap())
                && work
                    .edge_vertices(e)
                    .iter()
                    .any(|&v| work.vertex_valence(v) == 1)
        });
        let Some(e) = dangling else { break };
        if work.kill_edge_vertex(e).is_err() {
            break;
        }
    }
    work.validate()
        .map_err(|e| ModelingError::Invalid(e.to_string()))?;
    *mesh = work;
    Ok(region.into_iter().collect())
}

/// Deletes faces together with the edges and vertices no other face uses
/// (Blender's X ▸ Faces). For X ▸ Edges and X ▸ Vertices pass the faces
/// around them ([`faces_around_edges`], [`faces_around_vertices`]).
///
/// # Errors
/// [`ModelingError::Invalid`] when the rest would not be a manifold mesh
/// (for example two holes meeting at one vertex); the mesh is unchanged.
pub fn delete_faces(mesh: &mut HalfEdgeMesh, faces: &[FaceId]) -> Result<(), ModelingError> {
    check_faces(mesh, faces)?;
    let mut work = mesh.clone();
    work.delete_faces(faces, false);
    work.validate()
        .map_err(|e| ModelingError::Invalid(e.to_string()))?;
    *mesh = work;
    Ok(())
}

/// The faces touching any of the edges.
pub fn faces_around_edges(mesh: &HalfEdgeMesh, edges: &[EdgeId]) -> Vec<FaceId> {
    let mut out: Vec<FaceId> = edges
        .iter()
        .filter(|e| mesh.is_edge(**e))
        .flat_map(|&e| mesh.edge_faces(e))
        .flatten()
        .collect();
    out.sort();
    out.dedup();
    out
}

/// The faces touching any of the vertices.
pub fn faces_around_vertices(mesh: &HalfEdgeMesh, vertices: &[VertexId]) -> Vec<FaceId> {
    let mut out: Vec<FaceId> = vertices
        .iter()
        .filter(|v| mesh.is_vertex(**v))
        .flat_map(|&v| mesh.vertex_faces(v))
        .collect();
    out.sort();
    out.dedup();
    out
}

/// A world axis for mirroring and symmetrizing.
#[derive(Copy, Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum MirrorAxis {
    X,
    Y,
    Z,
}

impl MirrorAxis {
    fn index(self) -> usize {
        match self {
            MirrorAxis::X => 0,
            MirrorAxis::Y => 1,
            MirrorAxis::Z => 2,
        }
    }
    fn reflect(self, p: DVec3, center: f64) -> DVec3 {
        let mut a = p.to_array();
        let i = self.index();
        a[i] = 2.0 * center - a[i];
        DVec3::from_array(a)
    }
}

/// Makes the mesh symmetric across the plane `axis = 0`: faces on the
/// negative side are deleted and replaced by a mirror image of the positive
/// side, joined at the vertices on the plane (Blender's Symmetrize, +X to −X
/// for `X`). The plane must cut the mesh along edges (a loop cut there first).
///
/// # Errors
/// [`ModelingError::Parameter`] when a face straddles the plane;
/// [`ModelingError::Invalid`] when the mirrored half cannot be joined
/// manifold. The mesh is unchanged on error.
pub fn symmetrize(mesh: &mut HalfEdgeMesh, axis: MirrorAxis) -> Result<(), ModelingError> {
    const EPS: f64 = 1e-9;
    let i = axis.index();
    let side = |v: VertexId| {
        let c = mesh.position(v).to_array()[i];
        if c > EPS {
            1
        } else if c < -EPS {
            -1
        } else {
            0
        }
    };
    let mut negative = Vec::new();
    let mut positive = Vec::new();
    for f in mesh.faces() {
        let sides: Vec<i32> = mesh.face_vertices(f).map(side).collect();
        match (sides.iter().any(|&s| s > 0), sides.iter().any(|&s| s < 0)) {
            (true, true) => {
                return Err(ModelingError::Parameter {
                    what: "mesh",
                    allowed: "cut by the mirror plane along edges (add a loop cut there)",
                    value: format!("{f} crosses the plane"),
                });
            }
            (false, true) => negative.push(f),
            (true, false) => positive.push(f),
            (false, false) => negative.push(f), // flat on the plane: rebuilt from the mirror
        }
    }
    let polys: Vec<Vec<VertexId>> = positive
        .iter()
        .map(|&f| mesh.face_vertices(f).collect())
        .collect();
    let mut work = mesh.clone();
    work.delete_faces(&negative, false);
    // Snap plane vertices exactly onto the plane, then mirror the rest.
    let mut mirror = std::collections::HashMap::new();
    for p in &polys {
        for &v in p {
            if mirror.contains_key(&v) {
                continue;
            }
            let m = if side(v) == 0 {
                let mut a = work.position(v).to_array();
                a[i] = 0.0;
                work.set_position(v, DVec3::from_array(a));
                v
            } else {
                work.add_vertex(axis.reflect(work.position(v), 0.0))?
            };
            mirror.insert(v, m);
        }
    }
    for p in &polys {
        // A mirror image turns orientation around: reverse the corner order.
        let image: Vec<VertexId> = p.iter().rev().map(|v| mirror[v]).collect();
        work.add_face(&image)
            .map_err(|e| ModelingError::Invalid(format!("mirrored face: {e}")))?;
    }
    work.validate()
        .map_err(|e| ModelingError::Invalid(e.to_string()))?;
    *mesh = work;
    Ok(())
}

/// Mirrors vertices across the plane through their median perpendicular to
/// `axis` (Blender's Ctrl+M). Whole connected parts that are mirrored get
/// their faces reversed so they keep facing outwards.
///
/// # Errors
/// [`ModelingError::Empty`], [`ModelingError::Missing`].
pub fn mirror_vertices(
    mesh: &mut HalfEdgeMesh,
    vertices: &[VertexId],
    axis: MirrorAxis,
) -> Result<(), ModelingError> {
    if vertices.is_empty() {
        return Err(ModelingError::Empty("no vertices"));
    }
    if let Some(v) = vertices.iter().find(|v| !mesh.is_vertex(**v)) {
        return Err(ModelingError::Missing(v.to_string()));
    }
    let center = vertices
        .iter()
        .map(|&v| mesh.position(v).to_array()[axis.index()])
        .sum::<f64>()
        / vertices.len() as f64;
    let set: std::collections::HashSet<VertexId> = vertices.iter().copied().collect();
    for &v in &set {
        let p = axis.reflect(mesh.position(v), center);
        mesh.set_position(v, p);
    }
    // Components mirrored as a whole turn inside out: turn them back.
    let (comp, count) = mesh.components();
    let whole: Vec<VertexId> = (0..count)
        .filter_map(|c| {
            let members: Vec<VertexId> = mesh.vertices().filter(|v| comp[v.index()] == c).collect();
            (!members.is_empty() && members.iter().all(|v| set.contains(v))).then(|| members[0])
        })
        .collect();
    mesh.reverse_components(&whole);
    Ok(())
}

/// Slides the vertices of selected edge chains (loops or open paths) along
/// the edges beside them (Blender's edge slide, G G): with `factor` in
/// [−1, 1], every vertex moves that fraction of the way to the far end of
/// its rail, the rails on one side of the chain for a positive factor and
/// on the other for a negative one. Vertices without a rail on that side
/// stay. Connectivity does not change.
///
/// # Errors
/// [`ModelingError::Parameter`] for a factor outside [−1, 1] or edges that
/// do not form simple chains (a vertex with three selected edges).
pub fn slide_edges(
    mesh: &mut HalfEdgeMesh,
    edges: &[EdgeId],
    factor: f64,
) -> Result<(), ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no edges"));
    }
    if let Some(e) = edges.iter().find(|e| !mesh.is_edge(**e)) {
        return Err(ModelingError::Missing(e.to_string()));
    }
    if !(factor.is_finite() && (-1.0..=1.0).contains(&factor)) {
        return Err(ModelingError::Parameter {
            what: "factor",
            allowed: "-1 to 1",
            value: factor.to_string(),
        });
    }
    let selected: std::collections::HashSet<EdgeId> = edges.iter().copied().collect();
    let chain_at = |v: VertexId| {
        mesh.vertex_outgoing(v)
            .filter(|h| selected.contains(&h.edge()))
            .collect::<Vec<_>>()
    };
    for &e in edges {
        for v in mesh.edge_vertices(e) {
            let n = chain_at(v).len();
            if n > 2 {
                return Err(ModelingError::Parameter {
                    what: "edges",
                    allowed: "simple chains or loops",
                    value: format!("{v} joins {n} selected edges"),
                });
            }
        }
    }
    // Walk each chain once, every half-edge pointing the same way along it.
    let mut done = std::collections::HashSet::new();
    let mut targets: Vec<(VertexId, DVec3)> = Vec::new();
    for &e in edges {
        if done.contains(&e) {
            continue;
        }
        // Back up to an end of an open chain (or all the way round a loop).
        let mut h = e.halfedge(0);
        let mut steps = 0;
        while let Some(prev) = chain_at(mesh.origin(h))
            .into_iter()
            .map(|o| o.twin())
            .find(|x| x.edge() != h.edge())
        {
            h = prev;
            steps += 1;
            if h.edge() == e || steps > edges.len() {
                break;
            }
        }
        let mut hs = vec![h];
        done.insert(h.edge());
        loop {
            let last = *hs.last().expect("not empty");
            let Some(next) = chain_at(mesh.target(last))
                .into_iter()
                .find(|o| o.edge() != last.edge())
            else {
                break;
            };
            if !done.insert(next.edge()) {
                break; // back at the start of a loop
            }
            hs.push(next);
        }
        let closed = chain_at(mesh.origin(hs[0])).len() == 2
            && mesh.target(*hs.last().expect("not empty")) == mesh.origin(hs[0]);
        let n = hs.len();
        let count = if closed { n } else { n + 1 };
        for i in 0..count {
            let v = if i < n {
                mesh.origin(hs[i])
            } else {
                mesh.target(hs[n - 1])
            };
            let incoming = if i > 0 {
                Some(hs[i - 1])
            } else if closed {
                Some(hs[n - 1])
            } else {
                None
            };
            let outgoing = if i < n { Some(hs[i]) } else { None };
            let on_face = |x: HalfEdgeId| mesh.face(x).is_some();
            let rail = if factor >= 0.0 {
                // Left of the chain: the next half-edge in the face of the incoming one.
                incoming
                    .filter(|&x| on_face(x))
                    .map(|x| mesh.next(x))
                    .or_else(|| {
                        outgoing
                            .map(|o| mesh.prev(o))
                            .filter(|&p| on_face(p))
                            .map(|p| p.twin())
                    })
            } else {
                // Right of the chain: the same, walking the chain backwards.
                outgoing
                    .map(|o| o.twin())
                    .filter(|&x| on_face(x))
                    .map(|x| mesh.next(x))
                    .or_else(|| {
                        incoming
                            .map(|h| mesh.prev(h.twin()))
                            .filter(|&p| on_face(p))
                            .map(|p| p.twin())
                    })
            };
            if let Some(r) = rail.filter(|r| mesh.origin(*r) == v && !selected.contains(&r.edge()))
            {
                let p = mesh.position(v);
                targets.push((v, p + (mesh.position(mesh.target(r)) - p) * factor.abs()));
            }
        }
    }
    for (v, p) in targets {
        mesh.set_position(v, p);
    }
    Ok(())
}

/// Bevels edges (Blender's Ctrl+B) `width` wide, flat or rounded with
/// `segments`, at any valence and where beveled edges meet (see
/// [`chamfer_edges`]). Returns the new faces: the strips, then the patches.
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
        return Err(ModelingError::Missing(e.to_string()));
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
fn chamfer_edges(
    mesh: &mut HalfEdgeMesh,
    edges: &[EdgeId],
    width: f64,
    segments: u32,
) -> Result<Vec<FaceId>, ModelingError> {
    use std::collections::{BTreeSet, HashMap};
    let beveled: BTreeSet<EdgeId> = edges.iter().copied().collect();
    let mut ends: BTreeSet<VertexId> = BTreeSet::new();
    for &e in &beveled {
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
    let dir = |m: &HalfEdgeMesh, from: VertexId, to: VertexId| {
        (m.position(to) - m.position(from)).normalize()
    };
    let sin_between = |a: DVec3, b: DVec3| a.cross(b).length();
    // Distance along each unbeveled edge at an end where faces slide their
    // corner (w / sin θ to the beveled edge of that face; the mean when both
    // faces of the edge ask).
    let mut slide: HashMap<(VertexId, EdgeId), (f64, u32)> = HashMap::new();
    for &v in &ends {
        for h in mesh.vertex_outgoing(v).collect::<Vec<_>>() {
            // In face(h) the corner at v is between prev(h) (in) and h (out).
            let (e_in, e_out) = (mesh.prev(h).edge(), h.edge());
            let (u_in, u_out) = (
                dir(mesh, v, mesh.origin(mesh.prev(h))),
                dir(mesh, v, mesh.target(h)),
            );
            let sin = sin_between(u_in, u_out);
            let (b_in, b_out) = (beveled.contains(&e_in), beveled.contains(&e_out));
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
                entry.0 += width / sin;
                entry.1 += 1;
            }
        }
    }
    let mut work = mesh.clone();
    let mut point_on: HashMap<(VertexId, EdgeId), VertexId> = HashMap::new();
    let mut used_length: HashMap<EdgeId, f64> = HashMap::new();
    for &v in &ends {
        for h in mesh.vertex_outgoing(v) {
            let e = h.edge();
            if beveled.contains(&e) {
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
    // New corners of every face around the ends; `corner_of[(f, v)]` is the
    // point a corner at v became (for the quads).
    let faces = faces_around_vertices(mesh, &ends.iter().copied().collect::<Vec<_>>());
    let mut corner_of: HashMap<(FaceId, VertexId), VertexId> = HashMap::new();
    let mut polygons = Vec::new();
    for &f in &faces {
        let mut corners = Vec::new();
        for h in mesh.face_halfedges(f).collect::<Vec<_>>() {
            let v = mesh.origin(h);
            if !ends.contains(&v) {
                corners.push(v);
                continue;
            }
            let hin = mesh.prev(h);
            let (e_in, e_out) = (hin.edge(), h.edge());
            match (beveled.contains(&e_in), beveled.contains(&e_out)) {
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
                    let q = mesh.position(v) + (u_in + u_out) * (width / sin);
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
    // Rounded bevels: at each end the cap edge between the two new corners
    // bends into a quadratic Bézier arc with the old vertex as control
    // point (B(½) = c₁/4 + v/2 + c₂/4). Edges in line share their corners
    // at a vertex, so the arc is keyed by the corner pair and shared too.
    let mut arcs: HashMap<(VertexId, VertexId, VertexId), Vec<VertexId>> = HashMap::new();
    let mut arc = |work: &mut HalfEdgeMesh, v: VertexId, from: VertexId, to: VertexId| {
        let key = (v, from.min(to), from.max(to));
        let mut inner = arcs
            .entry(key)
            .or_insert_with(|| {
                let (c1, c2) = (work.position(key.1), work.position(key.2));
                let control = mesh.position(v);
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
    };
    let mut strips = Vec::new();
    for &e in &beveled {
        let h = e.halfedge(0);
        let t = h.twin();
        let (a, b) = (mesh.origin(h), mesh.target(h));
        let (fh, ft) = (
            mesh.face(h).expect("checked"),
            mesh.face(t).expect("checked"),
        );
        let side = |work: &mut HalfEdgeMesh,
                    arc: &mut dyn FnMut(
            &mut HalfEdgeMesh,
            VertexId,
            VertexId,
            VertexId,
        ) -> Vec<VertexId>,
                    v: VertexId| {
            let (from, to) = (corner_of[&(fh, v)], corner_of[&(ft, v)]);
            let mut points = vec![from];
            points.extend(arc(work, v, from, to));
            points.push(to);
            points
        };
        let along_a = side(&mut work, &mut arc, a);
        let along_b = side(&mut work, &mut arc, b);
        for k in 0..segments as usize {
            strips.push(vec![along_a[k], along_a[k + 1], along_b[k + 1], along_b[k]]);
        }
    }
    // Patches: the new points around each end in fan order, when three or
    // more distinct ones leave a gap. The fan turns from a face to the one
    // across its incoming edge, so listing each face's out point before its
    // in point runs every edge of the gap against its face; crossing a
    // beveled edge, the gap follows that edge's arc. With only two points
    // the arcs meet each other, or the one face cut between them (a box
    // end) takes the arc as its new side.
    let mut patches = Vec::new();
    for &v in &ends {
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
            if beveled.contains(&e_in) {
                let g = mesh
                    .face(fan[(i + 1) % fan.len()])
                    .expect("inside the surface");
                let (from, to) = (corner_of[&(f, v)], corner_of[&(g, v)]);
                pts.extend(arc(&mut work, v, from, to));
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
        if distinct.len() >= 3 && segments == 1 {
            patches.push(ring);
        } else if distinct.len() >= 3 {
            // Rounded: a fan of triangles to a centre raised towards the old
            // vertex as the arcs are (half-way from the corners' centroid),
            // instead of one flat n-gon.
            let centroid =
                distinct.iter().map(|&p| work.position(p)).sum::<DVec3>() / distinct.len() as f64;
            let centre = work.add_vertex(centroid + (mesh.position(v) - centroid) * 0.5)?;
            for i in 0..ring.len() {
                patches.push(vec![ring[i], ring[(i + 1) % ring.len()], centre]);
            }
        } else if segments > 1 {
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
                let inner = arc(&mut work, v, p_in, p_out);
                let poly = &mut polygons[i];
                let at = poly
                    .iter()
                    .position(|&x| x == p_in)
                    .expect("the cut is in the face");
                poly.splice(at + 1..at + 1, inner);
            }
        }
    }
    let n_faces = polygons.len();
    polygons.extend(strips);
    polygons.extend(patches);
    work.delete_faces(&faces, true);
    for &v in &ends {
        work.free_vertex(v);
    }
    let added = add_faces_in_any_order(&mut work, polygons, "the bevel")?;
    work.validate()
        .map_err(|e| ModelingError::Invalid(e.to_string()))?;
    *mesh = work;
    Ok(added[n_faces.min(added.len())..].to_vec())
}
