//! Merging vertices: edge collapse, merge at centre / first / last
//! (Blender's M), weld (Wings 3D) and merge by distance.

use super::common::add_faces_in_any_order;
use super::{InvalidResult, ModelingError, faces_around_vertices};
use crate::ids::{EdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;

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
        return Err(ModelingError::Missing((*v).into()));
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
        return Err(ModelingError::Missing((*v).into()));
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
            return Err(ModelingError::Missing((*v).into()));
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
            return Err(InvalidResult::FaceMeetsItself { face: f }.into());
        }
        polygons.push(corners);
    }
    work.delete_faces(&faces, true);
    for &v in &gone {
        if !work.is_isolated_vertex(v) {
            return Err(InvalidResult::WireEdges { vertex: v }.into());
        }
        work.free_vertex(v);
    }
    for (cluster, point) in clusters {
        work.set_position(cluster[0], *point);
    }
    add_faces_in_any_order(&mut work, polygons, "welding")?;
    work.validate()?;
    *mesh = work;
    Ok(gone.len())
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
        return Err(ModelingError::Missing((*v).into()));
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
    for (i, &v) in vs.iter().enumerate() {
        let r = root(&mut parent, i);
        groups.entry(r).or_default().push(v);
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
