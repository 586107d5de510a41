//! Refined points kept level by level, so that a few moved cage vertices
//! recompute only the points they reach: a drag on a cage whose refinement
//! is too large for a stencil table (issue 36, item 1: one vertex of a
//! 100k-face cage dragged with level 2 shown).
//!
//! Which points a move reaches: every child point is a weighted sum of the
//! parent points of the faces around it (a face point of its face, an edge
//! point of the faces at its edge and its ends, a vertex point of the faces
//! at its vertex and its neighbours; OpenSubdiv's masks, seed 003, §2). So
//! the child points that read a moved parent point are among the child
//! points of the faces at that point: their face points, the edge points
//! of their edges and the vertex points of their vertices (Doo-Sabin: the
//! faces' corner points).

use glam::DVec3;

use super::Refiner;
use super::refine::Split;
use super::refiner::{PointSink, child_count, child_point, interpolate, point_mask};

/// Every level's points of a refinement (the cage's first), as
/// [`Refiner::refine_kept`] makes them and [`Refiner::update_kept`]
/// updates them.
#[derive(Clone, Debug)]
pub struct LevelPoints {
    levels: Vec<Vec<DVec3>>,
}

impl LevelPoints {
    /// The cage positions the points were refined from.
    pub fn cage(&self) -> &[DVec3] {
        &self.levels[0]
    }
    /// The refined points, as [`Refiner::refine`] gives them.
    pub fn points(&self) -> &[DVec3] {
        self.levels.last().expect("the cage level")
    }
}

/// A level whose dirty points are more than this share of it is computed
/// whole (in order, on all cores when large): visiting scattered points one
/// by one costs more past about an eighth.
const WHOLE_LEVEL_SHARE: usize = 8;

impl Refiner {
    /// [`refine`](Self::refine), keeping every level's points for
    /// [`update_kept`](Self::update_kept). The last level's points are the
    /// same bits as `refine`'s.
    pub fn refine_kept(&self, cage: &[DVec3]) -> LevelPoints {
        assert_eq!(
            cage.len(),
            self.levels[0].vertex_count,
            "one position per cage vertex"
        );
        let mut levels = vec![cage.to_vec()];
        for parent in &self.levels[..self.levels.len() - 1] {
            let parallel = child_count(parent, self.split()) >= super::PARALLEL_POINTS;
            let points = levels.last().expect("the cage level");
            levels.push(interpolate(
                parent,
                self.split(),
                self.options(),
                points,
                parallel,
            ));
        }
        LevelPoints { levels }
    }

    /// Moves cage vertices (`(index in cage_positions order, position)`)
    /// and recomputes the points the moves reach, level by level. The
    /// points are then the same bits as a full [`refine`](Self::refine) of
    /// the moved cage. Returns the refined points that were recomputed, in
    /// increasing order (a superset of those that changed), or `None` when
    /// the moves reached so much of a level that every point from there on
    /// was recomputed.
    pub fn update_kept(&self, kept: &mut LevelPoints, moved: &[(u32, DVec3)]) -> Option<Vec<u32>> {
        let mut dirty: Vec<u32> = Vec::with_capacity(moved.len());
        for &(v, p) in moved {
            kept.levels[0][v as usize] = p;
            dirty.push(v);
        }
        dirty.sort_unstable();
        dirty.dedup();
        let split = self.split();
        let mut whole = false;
        for (k, parent) in self.levels[..self.levels.len() - 1].iter().enumerate() {
            let (parents, rest) = kept.levels.split_at_mut(k + 1);
            let (points, child) = (&parents[k], &mut rest[0]);
            if !whole {
                dirty = reached(parent, split, &dirty);
                whole = dirty.len() * WHOLE_LEVEL_SHARE > child.len();
            }
            if whole {
                let parallel = child.len() >= super::PARALLEL_POINTS;
                *child = interpolate(parent, split, self.options(), points, parallel);
                continue;
            }
            // Face points first: the edge and vertex masks read them.
            let nf = split.face_points(parent);
            let (face_points, others) = child.split_at_mut(nf);
            let compute = |face_points: &[DVec3], i: u32| {
                let mut sink = PointSink {
                    points,
                    face_points,
                    sum: DVec3::ZERO,
                };
                point_mask(
                    parent,
                    self.options(),
                    child_point(parent, split, i as usize),
                    &mut sink,
                );
                sink.sum
            };
            let first_other = dirty.partition_point(|&i| (i as usize) < nf);
            for &i in &dirty[..first_other] {
                face_points[i as usize] = compute(&[], i);
            }
            for &i in &dirty[first_other..] {
                others[i as usize - nf] = compute(face_points, i);
            }
        }
        (!whole).then_some(dirty)
    }
}

/// The child points (increasing, no repeats) that read any of the `dirty`
/// points of `parent` (increasing): the child points of the faces at them,
/// and the vertex points of dirty vertices without faces.
fn reached(parent: &super::level::Level, split: Split, dirty: &[u32]) -> Vec<u32> {
    let vertex_corners = parent.vertex_corner_lists();
    let nf = split.face_points(parent) as u32;
    let ne = parent.edge_count() as u32;
    let mut faces: Vec<u32> = dirty
        .iter()
        .flat_map(|&v| vertex_corners.get(v as usize))
        .map(|&c| parent.corner_face(c as usize))
        .collect();
    faces.sort_unstable();
    faces.dedup();
    let mut out = Vec::with_capacity(9 * faces.len() + dirty.len());
    for &f in &faces {
        let corners = parent.face_corners(f);
        match split {
            Split::Quads => {
                out.push(f);
                for c in corners {
                    out.push(nf + parent.face_edges[c]);
                    out.push(nf + ne + parent.face_vertices[c]);
                }
            }
            Split::Triangles => {
                for c in corners {
                    out.push(parent.face_edges[c]);
                    out.push(ne + parent.face_vertices[c]);
                }
            }
            Split::Dual => out.extend(corners.map(|c| c as u32)),
        }
    }
    if split != Split::Dual {
        // A vertex without faces keeps its own vertex point.
        for &v in dirty {
            if vertex_corners.get(v as usize).is_empty() {
                out.push(nf + ne + v);
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}
