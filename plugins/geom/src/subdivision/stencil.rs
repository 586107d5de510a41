//! Subdivision as a sparse linear map per level (libigl's `S` in
//! `newV = S·V`): built once for a cage topology, re-applied whenever cage
//! vertices move, without rebuilding any connectivity.

use glam::DVec3;

use super::Refiner;
use super::refiner::{ChildPoint, child_count, child_point, point_mask};
use super::rules::Sink;

// What the doc above promises.
const _: () = {
    const fn send_and_sync<T: Send + Sync>() {}
    send_and_sync::<StencilTable>();
    send_and_sync::<StencilEvaluation>();
    send_and_sync::<Refiner>();
};

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
///
/// Built by [`Refiner::stencils`]. A table owns all it holds and is `Send`
/// and `Sync` (as are [`Refiner`] and [`StencilEvaluation`]), so it can be
/// built on a worker thread from an `Arc<Refiner>` when the topology
/// changes and handed to the thread that drags:
///
/// ```
/// use std::sync::Arc;
/// use hedra_geom::Primitive;
/// use hedra_geom::subdivision::{Creases, Options, Refiner};
/// let cube = Primitive::Cube { size: 2.0 }.build()?;
/// let refiner = Arc::new(Refiner::new(&cube, &Creases::default(), Options::default(), 2)?);
/// let cage = refiner.cage_positions(&cube);
/// let worker = Arc::clone(&refiner);
/// let table = std::thread::spawn(move || worker.stencils()).join().unwrap();
/// let (by_table, by_masks) = (table.apply(&cage), refiner.refine(&cage));
/// assert!(by_table.iter().zip(&by_masks).all(|(a, b)| a.distance(*b) < 1e-12));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct StencilTable {
    steps: Vec<Rows>,
    /// Per level, the transpose of `steps` without weights: which child
    /// points each parent point feeds (for incremental updates).
    feeds: Vec<(Vec<u32>, Vec<u32>)>,
    cage_vertices: usize,
}

/// The points of every level from the last evaluation of a
/// [`StencilTable`], kept so that moving a few cage vertices recomputes only
/// the points they influence.
#[derive(Clone, Debug, Default)]
pub struct StencilEvaluation {
    levels: Vec<Vec<DVec3>>,
    /// Per level, the update serial that last marked each point dirty.
    marks: Vec<Vec<u32>>,
    serial: u32,
}

impl StencilEvaluation {
    /// The cage positions this evaluation was made from.
    pub fn cage(&self) -> &[DVec3] {
        self.levels.first().map_or(&[], |v| v)
    }
    /// The refined points (the last level).
    pub fn points(&self) -> &[DVec3] {
        self.levels.last().map_or(&[], |v| v)
    }
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
        let mut parent_counts = vec![levels[0].vertex_count];
        parent_counts.extend(steps.iter().map(|r| r.offsets.len() - 1));
        let feeds = steps
            .iter()
            .zip(&parent_counts)
            .map(|(rows, &parents)| transpose(rows, parents))
            .collect();
        StencilTable {
            steps,
            feeds,
            cage_vertices: levels[0].vertex_count,
        }
    }

    /// Every level's points from cage positions, kept for
    /// [`update`](Self::update).
    pub fn evaluate(&self, cage: &[DVec3]) -> StencilEvaluation {
        assert_eq!(
            cage.len(),
            self.cage_vertices,
            "one position per cage vertex"
        );
        let mut levels = vec![cage.to_vec()];
        for rows in &self.steps {
            let parent = levels.last().expect("cage level");
            let next = (0..rows.offsets.len() - 1)
                .map(|i| row(rows, parent, i))
                .collect();
            levels.push(next);
        }
        let marks = levels.iter().map(|l| vec![0; l.len()]).collect();
        StencilEvaluation {
            levels,
            marks,
            serial: 0,
        }
    }

    /// Moves cage vertices (by [`Refiner::cage_positions`] index) and
    /// recomputes only the points they influence, level by level (what a
    /// drag needs). Where the moved vertices reach much of a level (a cage
    /// of few faces, or many vertices moved), that level and the ones after
    /// it are recomputed whole, in order, which is then cheaper than
    /// visiting the points one by one: an update never costs much more than
    /// [`apply`](Self::apply). Complexity: O(weights of the influenced rows),
    /// at most O(nonzeros).
    pub fn update(&self, eval: &mut StencilEvaluation, moved: &[(u32, DVec3)]) {
        eval.serial = eval.serial.wrapping_add(1);
        if eval.serial == 0 {
            eval.marks.iter_mut().for_each(|m| m.fill(0));
            eval.serial = 1;
        }
        let serial = eval.serial;
        let mut dirty: Vec<u32> = Vec::with_capacity(moved.len());
        for &(v, p) in moved {
            eval.levels[0][v as usize] = p;
            dirty.push(v);
        }
        let mut whole = false;
        for (k, rows) in self.steps.iter().enumerate() {
            let (parents, rest) = eval.levels.split_at_mut(k + 1);
            let (parent, child) = (&parents[k], &mut rest[0]);
            let n = child.len();
            let (offsets, children) = &self.feeds[k];
            if !whole {
                // How many (parent, child) pairs the dirty points feed: the
                // work of finding the dirty children, and an upper bound on
                // their weights. Past a quarter of the level's weights,
                // visiting them one by one (scattered) costs more than
                // recomputing the level in order.
                let reach: usize = dirty
                    .iter()
                    .map(|&d| (offsets[d as usize + 1] - offsets[d as usize]) as usize)
                    .sum();
                whole = 4 * reach > rows.columns.len();
            }
            if whole {
                for (i, p) in child.iter_mut().enumerate() {
                    *p = row(rows, parent, i);
                }
                continue;
            }
            let marks = &mut eval.marks[k + 1];
            let mut next = Vec::new();
            for &d in &dirty {
                for &c in &children[offsets[d as usize] as usize..offsets[d as usize + 1] as usize]
                {
                    let mark = &mut marks[c as usize];
                    if *mark != serial {
                        *mark = serial;
                        next.push(c);
                    }
                }
            }
            // Many points: in index order, so the rows and points are read
            // forwards (a few hundred fit in the cache in any order).
            if next.len() > n / 32 {
                next.clear();
                next.extend((0..n as u32).filter(|&c| marks[c as usize] == serial));
            } else if next.len() > 4096 {
                next.sort_unstable();
            }
            for &c in &next {
                child[c as usize] = row(rows, parent, c as usize);
            }
            dirty = next;
        }
    }

    /// Number of stored weights over all levels.
    pub fn nonzeros(&self) -> usize {
        self.steps.iter().map(|r| r.weights.len()).sum()
    }

    /// Refined positions from cage positions (in
    /// [`Refiner::cage_positions`] order); a level of
    /// [`super::PARALLEL_POINTS`] points or more on all cores, as
    /// [`Refiner::refine`] does. Complexity: O(nonzeros).
    pub fn apply(&self, cage: &[DVec3]) -> Vec<DVec3> {
        self.apply_with(cage, None)
    }

    /// [`apply`](Self::apply) on this thread only.
    pub fn apply_serial(&self, cage: &[DVec3]) -> Vec<DVec3> {
        self.apply_with(cage, Some(false))
    }

    /// [`apply`](Self::apply) with every level on all cores, however small.
    pub fn apply_parallel(&self, cage: &[DVec3]) -> Vec<DVec3> {
        self.apply_with(cage, Some(true))
    }

    /// `parallel`: forced one way, or `None` for by size (levels of
    /// [`super::PARALLEL_POINTS`] points or more on all cores).
    fn apply_with(&self, cage: &[DVec3], parallel: Option<bool>) -> Vec<DVec3> {
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
            let mut next = Vec::with_capacity(n);
            if parallel.unwrap_or(n >= super::PARALLEL_POINTS) {
                use rayon::prelude::*;
                next.par_extend((0..n).into_par_iter().map(row));
            } else {
                next.extend((0..n).map(row));
            }
            points = next;
        }
        points
    }
}

/// Child point `i` of one level: its weighted parent points.
#[inline]
fn row(rows: &Rows, points: &[DVec3], i: usize) -> DVec3 {
    let r = rows.offsets[i] as usize..rows.offsets[i + 1] as usize;
    rows.columns[r.clone()]
        .iter()
        .zip(&rows.weights[r])
        .fold(DVec3::ZERO, |sum, (&c, &w)| sum + w * points[c as usize])
}

/// For each parent point, the child rows that read it (a compressed table).
fn transpose(rows: &Rows, parents: usize) -> (Vec<u32>, Vec<u32>) {
    let mut offsets = vec![0u32; parents + 1];
    for &c in &rows.columns {
        offsets[c as usize + 1] += 1;
    }
    for i in 1..offsets.len() {
        offsets[i] += offsets[i - 1];
    }
    let mut fill = offsets.clone();
    let mut children = vec![0u32; rows.columns.len()];
    for i in 0..rows.offsets.len() - 1 {
        for &c in &rows.columns[rows.offsets[i] as usize..rows.offsets[i + 1] as usize] {
            let slot = &mut fill[c as usize];
            children[*slot as usize] = i as u32;
            *slot += 1;
        }
    }
    (offsets, children)
}
