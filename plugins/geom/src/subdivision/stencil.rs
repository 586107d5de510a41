//! Subdivision as a sparse linear map per level (libigl's `S` in
//! `newV = S·V`): built once for a cage topology, re-applied whenever cage
//! vertices move, without rebuilding any connectivity.

use glam::DVec3;

use super::rules::Sink;
use super::{ChildPoint, Refiner, child_count, child_point, point_mask};

/// One level's weights: child point `i` is `Σ weights[k] · parent[columns[k]]`
/// over `k` in `offsets[i]..offsets[i + 1]`.
#[derive(Clone, Debug, Default)]
struct Rows {
    offsets: Vec<u32>,
    columns: Vec<u32>,
    weights: Vec<f64>,
}

/// The weights of every level of a [`Refiner`], from the same masks as
/// [`Refiner::refine`], with face points expanded into their vertices.
#[derive(Clone, Debug, Default)]
pub struct StencilTable {
    steps: Vec<Rows>,
    cage_vertices: usize,
}

/// Collects a mask as (parent vertex, weight) pairs.
struct WeightSink<'a> {
    level: &'a super::level::Level,
    entries: Vec<(u32, f64)>,
}

impl Sink for WeightSink<'_> {
    fn vertex(&mut self, v: u32, w: f64) {
        self.entries.push((v, w));
    }
    fn face(&mut self, f: u32, w: f64) {
        let corners = self.level.face_corners(f);
        let share = w / corners.len() as f64;
        for c in corners {
            self.entries.push((self.level.face_vertices[c], share));
        }
    }
}

impl StencilTable {
    pub(crate) fn new(refiner: &Refiner) -> Self {
        let split = refiner.split();
        let levels = &refiner.levels;
        let mut steps = Vec::with_capacity(levels.len().saturating_sub(1));
        for parent in &levels[..levels.len() - 1] {
            let n = child_count(parent, split);
            let mut rows = Rows {
                offsets: Vec::with_capacity(n + 1),
                ..Rows::default()
            };
            rows.offsets.push(0);
            let mut sink = WeightSink {
                level: parent,
                entries: Vec::new(),
            };
            for i in 0..n {
                sink.entries.clear();
                let point: ChildPoint = child_point(parent, split, i);
                point_mask(parent, refiner.options(), point, &mut sink);
                sink.entries.sort_unstable_by_key(|&(v, _)| v);
                let mut last = u32::MAX;
                for &(v, w) in &sink.entries {
                    if v == last {
                        *rows.weights.last_mut().expect("merged entry") += w;
                    } else {
                        rows.columns.push(v);
                        rows.weights.push(w);
                        last = v;
                    }
                }
                rows.offsets.push(rows.columns.len() as u32);
            }
            steps.push(rows);
        }
        StencilTable {
            steps,
            cage_vertices: levels[0].vertex_count,
        }
    }

    /// Number of stored weights over all levels.
    pub fn nonzeros(&self) -> usize {
        self.steps.iter().map(|r| r.weights.len()).sum()
    }

    /// Refined positions from cage positions (in
    /// [`Refiner::cage_positions`] order). Complexity: O(nonzeros).
    pub fn apply(&self, cage: &[DVec3]) -> Vec<DVec3> {
        self.apply_with(cage, false)
    }

    /// [`apply`](Self::apply) on all cores.
    pub fn apply_parallel(&self, cage: &[DVec3]) -> Vec<DVec3> {
        self.apply_with(cage, true)
    }

    fn apply_with(&self, cage: &[DVec3], parallel: bool) -> Vec<DVec3> {
        assert_eq!(
            cage.len(),
            self.cage_vertices,
            "one position per cage vertex"
        );
        let mut points = cage.to_vec();
        for rows in &self.steps {
            let n = rows.offsets.len() - 1;
            let row = |i: usize| {
                let r = rows.offsets[i] as usize..rows.offsets[i + 1] as usize;
                rows.columns[r.clone()]
                    .iter()
                    .zip(&rows.weights[r])
                    .fold(DVec3::ZERO, |sum, (&c, &w)| sum + w * points[c as usize])
            };
            let mut next = vec![DVec3::ZERO; n];
            if parallel {
                use rayon::prelude::*;
                next.par_iter_mut()
                    .enumerate()
                    .for_each(|(i, p)| *p = row(i));
            } else {
                for (i, p) in next.iter_mut().enumerate() {
                    *p = row(i);
                }
            }
            points = next;
        }
        points
    }
}
