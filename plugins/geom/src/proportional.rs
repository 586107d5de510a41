//! Proportional (soft) editing: how much a transform moves each unselected
//! vertex or control point near the selection, Blender's Proportional
//! Editing (O).
//!
//! A point at distance `d` from the nearest selected point, within the
//! radius `r`, takes the fraction `w = falloff(t)` of the transform, where
//! `t = 1 − d / r` (1 at the selection, 0 at the radius). The curves are
//! Blender's (`transform_generics`, `calculatePropRatio`): smooth
//! `3t² − 2t³`, sphere `√(2t − t²)`, root `√t`, linear `t`, sharp `t²`,
//! constant `1`. Distances are Euclidean, or measured along the edges
//! (Dijkstra over edge lengths) when only connected geometry may move.

use crate::ids::VertexId;
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;
use std::cmp::Ordering;
use std::collections::{BTreeMap, BinaryHeap};

/// The shape of the influence between the selection and the radius.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum Falloff {
    /// `3t² − 2t³`: eases out at both ends (Blender's default).
    #[default]
    Smooth,
    /// `√(2t − t²)`: a round dome.
    Sphere,
    /// `√t`: steep at the radius, flat near the selection.
    Root,
    /// `t`: a cone.
    Linear,
    /// `t²`: a sharp peak at the selection.
    Sharp,
    /// `1`: everything within the radius moves fully.
    Constant,
}

impl Falloff {
    /// Every falloff, in menu order.
    pub const ALL: [Falloff; 6] = [
        Falloff::Smooth,
        Falloff::Sphere,
        Falloff::Root,
        Falloff::Linear,
        Falloff::Sharp,
        Falloff::Constant,
    ];

    /// The curve's name as a menu shows it.
    pub fn label(self) -> &'static str {
        match self {
            Falloff::Smooth => "Smooth",
            Falloff::Sphere => "Sphere",
            Falloff::Root => "Root",
            Falloff::Linear => "Linear",
            Falloff::Sharp => "Sharp",
            Falloff::Constant => "Constant",
        }
    }

    /// The fraction of the transform taken at `distance` from the
    /// selection with influence `radius`: 1 at distance 0, 0 at and beyond
    /// the radius (the constant falloff stays 1 inside it).
    pub fn weight(self, distance: f64, radius: f64) -> f64 {
        if radius <= 0.0 || distance >= radius || !distance.is_finite() {
            return 0.0;
        }
        let t = (1.0 - distance / radius).clamp(0.0, 1.0);
        match self {
            Falloff::Smooth => 3.0 * t * t - 2.0 * t * t * t,
            Falloff::Sphere => (2.0 * t - t * t).sqrt(),
            Falloff::Root => t.sqrt(),
            Falloff::Linear => t,
            Falloff::Sharp => t * t,
            Falloff::Constant => 1.0,
        }
    }
}

/// The weight of every unselected vertex of `mesh` that a proportional
/// transform of `selected` moves (weight > 0), with positions given by
/// `position` (world space, so the radius is in world units). With
/// `connected`, distances run along edges and only vertices joined to the
/// selection move; otherwise the straight distance to the nearest selected
/// vertex counts.
pub fn mesh_weights(
    mesh: &HalfEdgeMesh,
    position: &dyn Fn(VertexId) -> DVec3,
    selected: &[VertexId],
    radius: f64,
    falloff: Falloff,
    connected: bool,
) -> BTreeMap<VertexId, f64> {
    let distances = if connected {
        edge_distances(mesh, position, selected, radius)
    } else {
        let sel: Vec<DVec3> = selected.iter().map(|&v| position(v)).collect();
        mesh.vertices()
            .filter_map(|v| {
                let p = position(v);
                let d = sel
                    .iter()
                    .map(|s| s.distance(p))
                    .fold(f64::INFINITY, f64::min);
                (d < radius).then_some((v, d))
            })
            .collect()
    };
    distances
        .into_iter()
        .filter(|(v, _)| !selected.contains(v))
        .map(|(v, d)| (v, falloff.weight(d, radius)))
        .filter(|&(_, w)| w > 0.0)
        .collect()
}

/// The weight of every unselected point (by index) that a proportional
/// transform of the `selected` points moves: straight distances, for
/// control points, which have no edges between them.
pub fn point_weights(
    points: &[DVec3],
    selected: &[usize],
    radius: f64,
    falloff: Falloff,
) -> BTreeMap<usize, f64> {
    points
        .iter()
        .enumerate()
        .filter(|(i, _)| !selected.contains(i))
        .filter_map(|(i, p)| {
            let d = selected
                .iter()
                .filter_map(|&s| points.get(s))
                .map(|s| s.distance(*p))
                .fold(f64::INFINITY, f64::min);
            let w = falloff.weight(d, radius);
            (w > 0.0).then_some((i, w))
        })
        .collect()
}

/// Shortest distances along edges from the selection, up to `radius`
/// (Dijkstra with a binary heap).
fn edge_distances(
    mesh: &HalfEdgeMesh,
    position: &dyn Fn(VertexId) -> DVec3,
    selected: &[VertexId],
    radius: f64,
) -> BTreeMap<VertexId, f64> {
    /// A heap entry ordered by smallest distance first.
    struct Entry(f64, VertexId);
    impl PartialEq for Entry {
        fn eq(&self, other: &Self) -> bool {
            self.0 == other.0
        }
    }
    impl Eq for Entry {}
    impl PartialOrd for Entry {
        fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
            Some(self.cmp(other))
        }
    }
    impl Ord for Entry {
        fn cmp(&self, other: &Self) -> Ordering {
            other.0.total_cmp(&self.0)
        }
    }
    let mut best: BTreeMap<VertexId, f64> = BTreeMap::new();
    let mut heap = BinaryHeap::new();
    for &v in selected.iter().filter(|&&v| mesh.is_vertex(v)) {
        best.insert(v, 0.0);
        heap.push(Entry(0.0, v));
    }
    while let Some(Entry(d, v)) = heap.pop() {
        if best.get(&v).is_some_and(|&b| d > b) {
            continue;
        }
        let p = position(v);
        for n in mesh.vertex_neighbors(v) {
            let nd = d + p.distance(position(n));
            if nd < radius && best.get(&n).is_none_or(|&b| nd < b) {
                best.insert(n, nd);
                heap.push(Entry(nd, n));
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives::Primitive;

    #[test]
    fn falloff_curves_match_blender_at_known_points() {
        // t = 1 − d/r = 0.5 at half the radius.
        let w = |f: Falloff| f.weight(1.0, 2.0);
        assert_eq!(w(Falloff::Linear), 0.5);
        assert_eq!(w(Falloff::Sharp), 0.25);
        assert_eq!(w(Falloff::Smooth), 0.5);
        assert!((w(Falloff::Root) - 0.5f64.sqrt()).abs() < 1e-15);
        assert!((w(Falloff::Sphere) - 0.75f64.sqrt()).abs() < 1e-15);
        assert_eq!(w(Falloff::Constant), 1.0);
        for f in Falloff::ALL {
            assert_eq!(f.weight(0.0, 2.0), 1.0, "{f:?} at the selection");
            assert_eq!(f.weight(2.0, 2.0), 0.0, "{f:?} at the radius");
            assert_eq!(f.weight(3.0, 2.0), 0.0, "{f:?} beyond the radius");
        }
        // Smooth at t = 0.25: 3/16 − 2/64.
        assert!((Falloff::Smooth.weight(1.5, 2.0) - (3.0 / 16.0 - 2.0 / 64.0)).abs() < 1e-15);
    }

    /// A 5 × 5 grid of unit quads.
    fn grid() -> HalfEdgeMesh {
        Primitive::Grid {
            x_segments: 5,
            z_segments: 5,
            size: 5.0,
        }
        .build()
        .unwrap()
    }

    #[test]
    fn euclidean_weights_follow_the_distance_to_the_nearest_selected_vertex() {
        let mesh = grid();
        let pos = |v: VertexId| mesh.position(v);
        let corner = mesh
            .vertices()
            .min_by(|&a, &b| {
                let (p, q) = (pos(a), pos(b));
                (p.x + p.z).total_cmp(&(q.x + q.z))
            })
            .unwrap();
        let weights = mesh_weights(&mesh, &pos, &[corner], 2.5, Falloff::Linear, false);
        assert!(
            !weights.contains_key(&corner),
            "the selection is not weighted"
        );
        for v in mesh.vertices().filter(|&v| v != corner) {
            let d = pos(v).distance(pos(corner));
            let expected = (1.0 - d / 2.5).max(0.0);
            assert!(
                (weights.get(&v).copied().unwrap_or(0.0) - expected).abs() < 1e-12,
                "vertex {v:?} at distance {d}"
            );
        }
        assert!(weights.values().all(|&w| w > 0.0 && w < 1.0));
    }

    #[test]
    fn connected_weights_measure_along_edges_and_skip_other_pieces() {
        // Two unit squares side by side but not joined: 1 apart in x.
        let mesh = HalfEdgeMesh::from_polygons(
            &[
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(0.0, 1.0, 0.0),
                DVec3::new(2.0, 0.0, 0.0),
                DVec3::new(3.0, 0.0, 0.0),
                DVec3::new(3.0, 1.0, 0.0),
                DVec3::new(2.0, 1.0, 0.0),
            ],
            &[vec![0, 1, 2, 3], vec![4, 5, 6, 7]],
        )
        .unwrap();
        let pos = |v: VertexId| mesh.position(v);
        let picked = VertexId(1);
        let near = mesh_weights(&mesh, &pos, &[picked], 3.0, Falloff::Linear, false);
        let joined = mesh_weights(&mesh, &pos, &[picked], 3.0, Falloff::Linear, true);
        // Vertex 4 is 1 away in space but in the other square.
        assert!((near[&VertexId(4)] - (1.0 - 1.0 / 3.0)).abs() < 1e-12);
        assert!(!joined.contains_key(&VertexId(4)));
        // Vertex 3 is √2 away in space, 2 along the edges (1 → 2 → 3 or 1 → 0 → 3).
        assert!((near[&VertexId(3)] - (1.0 - 2f64.sqrt() / 3.0)).abs() < 1e-12);
        assert!((joined[&VertexId(3)] - (1.0 - 2.0 / 3.0)).abs() < 1e-12);
    }

    #[test]
    fn point_weights_skip_the_selection_and_points_beyond_the_radius() {
        let points: Vec<DVec3> = (0..5).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
        let w = point_weights(&points, &[0], 2.0, Falloff::Sharp);
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[&1], 0.25);
    }
}
