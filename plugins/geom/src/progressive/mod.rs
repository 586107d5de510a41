//! Progressive meshes: simplification by quadric-driven edge collapses,
//! kept as a record that reaches any level of detail between a coarse base
//! mesh and the input by replaying vertex splits or edge collapses.
//!
//! Sources: seed 004 (progressive meshes, edge collapse / vertex split);
//! H. Hoppe, "Progressive Meshes", SIGGRAPH 1996 (the record: base mesh
//! plus vertex splits); M. Garland and P. Heckbert, "Surface
//! Simplification Using Quadric Error Metrics", SIGGRAPH 1997 (the cost,
//! the optimal placement and the boundary planes).
//!
//! [`ProgressiveMesh::build`] triangulates a copy of the input when it has
//! larger faces (each collapse removes the triangles beside its edge;
//! with [`DecimateOptions::keep_quads`] the levels shown are re-paired
//! into quads afterwards, [`join_quads`]), computes a quadric per vertex
//! (face planes weighted by the square root of their area, plus strongly
//! weighted planes through the feature edges, perpendicular to their
//! faces: borders, creases, UV seams and edges sharper than the
//! sharp-feature angle), costs a collapse as the weighted mean squared
//! distance to the merged planes ([`Quadric::mean_error`]) and collapses edges
//! cheapest first in passes (each pass costs every edge in memory order,
//! radix-sorts the costs and collapses the cheap ones whose neighbourhood
//! no earlier collapse of the pass changed), until no collapse is
//! allowed. Every collapse goes through the kernel's Euler
//! operator [`HalfEdgeMesh::collapse_edge_removing_triangles`] (with its
//! link condition, so genus, shells and border count never change) and is
//! refused when it would turn a face's normal by more than
//! [`DecimateOptions::max_normal_change`] (fold-over).
//!
//! Feature edges hold: a vertex on two feature edges may only slide along
//! them into a neighbour on the same line (placed on that edge), a vertex
//! on one or three or more feature edges, or on two that turn by more than
//! 45° (a corner), never moves, and with
//! [`DecimateOptions::keep_borders`] no border vertex moves at all.
//!
//! Levels are numbered from 0 (the base mesh) to
//! [`level_count`](ProgressiveMesh::level_count)` − 1` (the input). Each
//! level's elements carry the ids they had in the (triangulated) input:
//! [`ProgressiveMesh::level_mesh`] returns the current level in those ids,
//! so that collapsing everything and splitting it all back gives a mesh
//! [`same_as`](HalfEdgeMesh::same_as) the input. The working mesh itself
//! ([`ProgressiveMesh::mesh`]) gets fresh ids from every vertex split, as
//! the kernel never reuses ids.

mod quadric;

pub use quadric::Quadric;

use crate::EulerError;
use crate::ids::{EdgeId, FaceId, HalfEdgeId, VertexId};
use crate::mesh::{HalfEdgeMesh, MeshData, MeshDataError};
use crate::modeling::{ModelingError, TriangulateMethod, triangulate_faces};
use crate::subdivision::Creases;
use crate::validate::ValidationError;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// Weight of a feature plane per unit of edge length, against face planes
/// weighted by the square root of their area (Garland and Heckbert's
/// boundary penalty, scaled as meshoptimizer scales it: both weights are
/// lengths, so the balance does not depend on the mesh's size or
/// density). Measured on `bench/decimate-compare` (sampled Hausdorff
/// error of the open tube at 1 %): 15 and 20 give 0.0035, 25 to 60 give
/// 0.0054 to 0.0057; the gear's sharp edges hold at all of them.
const FEATURE_WEIGHT: f64 = 20.0;

/// A vertex where two feature edges (border, crease, seam, sharp) meet
/// turning by more than this (45°) is a corner of the features and never
/// moves.
const CORNER_TURN: f64 = std::f64::consts::FRAC_PI_4;

/// What [`ProgressiveMesh::build`] keeps while it simplifies.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DecimateOptions {
    /// Border vertices never move and are never removed (default off:
    /// borders still hold their shape, their vertices slide along them).
    #[serde(default)]
    pub keep_borders: bool,
    /// Creased edges (sharpness above 0) are feature edges and vertices
    /// with corner sharpness never move (default on).
    #[serde(default = "yes")]
    pub keep_creases: bool,
    /// Edges whose faces meet at more than this angle in degrees are
    /// feature edges (`None`, the default: no angle test).
    #[serde(default)]
    pub sharp_angle: Option<f64>,
    /// The largest turn of a face normal a collapse may cause, in degrees
    /// (default 60); larger turns are fold-overs and refused.
    #[serde(default = "normal_limit")]
    pub max_normal_change: f64,
    /// Edges of the input that are UV seams (the document finds them from
    /// its corner UVs), kept as feature edges.
    #[serde(default, skip_serializing_if = "BTreeSet::is_empty")]
    pub seams: BTreeSet<EdgeId>,
    /// Quads where they fit (default off: triangles). The collapses work
    /// on triangles either way, so the progressive record does not
    /// depend on it; each level shown is re-paired by
    /// [`ProgressiveMesh::output_mesh`] (see [`join_quads`]).
    #[serde(default)]
    pub keep_quads: bool,
}

fn yes() -> bool {
    true
}
fn normal_limit() -> f64 {
    60.0
}

impl Default for DecimateOptions {
    fn default() -> Self {
        DecimateOptions {
            keep_borders: false,
            keep_creases: true,
            sharp_angle: None,
            max_normal_change: normal_limit(),
            seams: BTreeSet::new(),
            keep_quads: false,
        }
    }
}

/// How far to simplify.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum DecimateTarget {
    /// A fraction of the input's faces (of its triangles after
    /// triangulation), in (0, 1].
    Ratio(f64),
    /// At most this many faces.
    Faces(usize),
}

/// A progressive-mesh build that owns its inputs, so that it can move to a
/// worker thread (it is `Send + 'static`, and so are its result and its
/// error): the app clones the mesh, creases and options, spawns
/// `move || job.run(progress, &cancel)` with an `Arc<AtomicBool>` it keeps
/// to cancel, and takes the [`ProgressiveMesh`] back when it is done.
///
/// ```
/// use hedra_geom::progressive::{BuildJob, DecimateOptions, DecimateError};
/// use hedra_geom::{subdivision::Creases, Primitive};
/// use std::sync::{Arc, atomic::{AtomicBool, Ordering}, mpsc};
///
/// let mesh = Primitive::IcoSphere { subdivisions: 3, radius: 1.0 }.build().unwrap();
/// let job = BuildJob::new(mesh, Creases::default(), DecimateOptions::default());
/// let cancel = Arc::new(AtomicBool::new(false));
/// let (tx, rx) = mpsc::channel();
/// let flag = cancel.clone();
/// let worker = std::thread::spawn(move || job.run(|f| { let _ = tx.send(f); }, &flag));
/// let pm = worker.join().unwrap().unwrap();
/// assert_eq!(rx.iter().last(), Some(1.0));
/// assert_eq!(pm.level_count(), 1 + pm.splits().len());
///
/// // Cancelled before it starts: the named error, nothing made.
/// cancel.store(true, Ordering::Relaxed);
/// let job = BuildJob::new(pm.base_mesh().clone(), Creases::default(), DecimateOptions::default());
/// assert_eq!(job.run(|_| {}, &cancel).unwrap_err(), DecimateError::Cancelled);
/// ```
#[derive(Clone, Debug)]
pub struct BuildJob {
    /// The mesh to simplify.
    pub mesh: HalfEdgeMesh,
    /// Its creases (by its ids).
    pub creases: Creases,
    /// What to keep.
    pub options: DecimateOptions,
}

impl BuildJob {
    /// A job over owned copies of the inputs.
    pub fn new(mesh: HalfEdgeMesh, creases: Creases, options: DecimateOptions) -> BuildJob {
        BuildJob {
            mesh,
            creases,
            options,
        }
    }

    /// Runs the build on the calling thread:
    /// [`ProgressiveMesh::build_with_progress`] over the job's inputs.
    ///
    /// # Errors
    /// As [`ProgressiveMesh::build_with_progress`]
    /// ([`DecimateError::Cancelled`] when `cancel` is set).
    pub fn run(
        self,
        mut progress: impl FnMut(f64),
        cancel: &AtomicBool,
    ) -> Result<ProgressiveMesh, DecimateError> {
        ProgressiveMesh::build_with_progress(
            &self.mesh,
            &self.creases,
            &self.options,
            &mut progress,
            cancel,
        )
    }
}

/// Why a simplification or a level change refused; the mesh (or the
/// progressive mesh) is unchanged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DecimateError {
    /// The input is not a valid manifold mesh (the validator's report).
    #[error("cannot decimate a mesh that is not manifold: {0}")]
    NotManifold(ValidationError),
    /// A face with inner rings or without edges.
    #[error("cannot decimate {face}: it is not a plain polygon (it has rings or no edges)")]
    NotPolygon {
        /// The face.
        face: FaceId,
    },
    /// The input has no faces.
    #[error("cannot decimate a mesh without faces")]
    NoFaces,
    /// Triangulating the input failed.
    #[error("cannot triangulate the mesh before decimating: {0}")]
    Triangulate(ModelingError),
    /// A ratio outside (0, 1] or not a number.
    #[error("the target ratio must be above 0 and at most 1, got {0}")]
    Ratio(f64),
    /// The target asks for fewer faces than the simplification reaches.
    #[error(
        "{target} faces is below the {minimum} this mesh can be simplified to \
         (its topology, borders, creases and the fold-over limit allow no fewer)"
    )]
    BelowMinimum {
        /// The faces asked for.
        target: usize,
        /// The fewest faces of any level (the base mesh's).
        minimum: usize,
    },
    /// A level outside `0..level_count`.
    #[error("level {level} does not exist (levels 0 to {max})")]
    NoLevel {
        /// The level asked for.
        level: usize,
        /// The finest level (the input).
        max: usize,
    },
    /// A stored record that does not replay on its base mesh (a damaged
    /// file): the Euler operator's refusal.
    #[error("the progressive record does not replay: {0}")]
    Replay(EulerError),
    /// A stored record whose ids or mesh are out of range.
    #[error("the progressive record is damaged: {0}")]
    Record(String),
    /// The build was cancelled through its cancel flag
    /// ([`ProgressiveMesh::build_with_progress`]); nothing was made.
    #[error("the decimation was cancelled")]
    Cancelled,
}

impl From<MeshDataError> for DecimateError {
    fn from(e: MeshDataError) -> Self {
        DecimateError::Record(e.to_string())
    }
}

/// One edge collapse of the sequence and the vertex split that undoes it
/// (Hoppe's `vsplit` record), in the ids of the input mesh.
///
/// Collapsing `edge` (from `kept` to `removed`) moves `kept` to `position`
/// and removes `removed` with the triangles `left` (beside `edge`) and
/// `right` (beside its twin), each with its edge at `removed` (left) or at
/// `kept` (right). The split moves the outgoing half-edges of `kept` from
/// `first` to `last` (fan order) back to `removed`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct VertexSplit {
    /// The collapsed half-edge, from the kept to the removed vertex.
    #[serde(rename = "h")]
    pub edge: HalfEdgeId,
    /// The vertex that stays.
    #[serde(rename = "k")]
    pub kept: VertexId,
    /// The vertex that goes.
    #[serde(rename = "r")]
    pub removed: VertexId,
    /// First half-edge of the kept vertex's fan that belonged to `removed`.
    #[serde(rename = "f")]
    pub first: HalfEdgeId,
    /// Last such half-edge.
    #[serde(rename = "l")]
    pub last: HalfEdgeId,
    /// The triangle beside `edge`, its half-edge from `removed` to its
    /// third corner (whose edge goes) and the edge from that corner to
    /// `kept` (which stays, taking the place of the one that goes); `None`
    /// when that side is a border.
    #[serde(rename = "tl", default, skip_serializing_if = "Option::is_none")]
    pub left: Option<(FaceId, HalfEdgeId, EdgeId)>,
    /// The triangle beside `edge`'s twin, its half-edge from `kept` to its
    /// third corner (whose edge goes) and the edge from that corner to
    /// `removed` (which stays).
    #[serde(rename = "tr", default, skip_serializing_if = "Option::is_none")]
    pub right: Option<(FaceId, HalfEdgeId, EdgeId)>,
    /// Where `kept` goes by the collapse.
    #[serde(rename = "p")]
    pub position: DVec3,
    /// Where `kept` was before it.
    #[serde(rename = "pk")]
    pub kept_position: DVec3,
    /// Where `removed` was.
    #[serde(rename = "pr")]
    pub removed_position: DVec3,
    /// The cost of the collapse: the weighted mean squared distance of
    /// `position` to the planes merged into it ([`Quadric::mean_error`]).
    #[serde(rename = "e")]
    pub error: f64,
}

impl VertexSplit {
    fn triangles(&self) -> usize {
        self.left.is_some() as usize + self.right.is_some() as usize
    }
}

/// The base mesh in dense ids and, per dense id, the input id.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
struct Base {
    mesh: HalfEdgeMesh,
    vertices: Vec<u32>,
    edges: Vec<u32>,
    faces: Vec<u32>,
}

/// The stored form: Hoppe's base mesh plus the vertex splits (in collapse
/// order; levels replay them backwards), and the input's id space.
#[derive(Clone, Debug, Serialize, Deserialize)]
struct Stored {
    capacity: [usize; 3],
    base: Base,
    splits: Vec<VertexSplit>,
}

/// A progressive mesh (Hoppe 1996): the collapse sequence of a
/// simplification with the current level's mesh, movable to any level by
/// replaying vertex splits (finer) or edge collapses (coarser) from where
/// it is, never by simplifying again.
///
/// Serialises as the base mesh and the splits (`serde`); a loaded one is
/// at level 0 (the base).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(into = "Stored", try_from = "Stored")]
pub struct ProgressiveMesh {
    capacity: [usize; 3],
    base: Arc<Base>,
    splits: Arc<Vec<VertexSplit>>,
    face_counts: Arc<Vec<usize>>,
    mesh: HalfEdgeMesh,
    level: usize,
    /// Input id → current id (vertices, faces); edges as `current << 1 |
    /// flip`, flip set when the input's half-edge 0 is the current 1.
    fwd_v: Vec<u32>,
    fwd_e: Vec<u32>,
    fwd_f: Vec<u32>,
    /// Current id → input id, same encoding.
    inv_v: Vec<u32>,
    inv_e: Vec<u32>,
    inv_f: Vec<u32>,
}

impl PartialEq for ProgressiveMesh {
    /// Equal records (the base and the splits); the current level is
    /// not compared.
    fn eq(&self, other: &Self) -> bool {
        self.capacity == other.capacity && self.base == other.base && self.splits == other.splits
    }
}

impl From<ProgressiveMesh> for Stored {
    fn from(p: ProgressiveMesh) -> Stored {
        Stored {
            capacity: p.capacity,
            base: (*p.base).clone(),
            splits: (*p.splits).clone(),
        }
    }
}

impl TryFrom<Stored> for ProgressiveMesh {
    type Error = DecimateError;
    fn try_from(s: Stored) -> Result<Self, DecimateError> {
        let [nv, ne, nf] = s.capacity;
        let b = &s.base;
        let bad = |what: &str| DecimateError::Record(what.to_string());
        if b.vertices.len() != b.mesh.vertex_capacity()
            || b.edges.len() != b.mesh.edge_capacity()
            || b.faces.len() != b.mesh.face_capacity()
        {
            return Err(bad("the base's id tables do not match its mesh"));
        }
        let in_range = |ids: &[u32], n: usize| ids.iter().all(|&x| (x as usize) < n);
        if !in_range(&b.vertices, nv) || !in_range(&b.edges, ne) || !in_range(&b.faces, nf) {
            return Err(bad("a base id is outside the input's"));
        }
        for s in s.splits.iter() {
            let hs = [Some(s.edge), Some(s.first), Some(s.last)]
                .into_iter()
                .chain([s.left, s.right].into_iter().flatten().map(|t| Some(t.1)));
            let faces_ok = [s.left, s.right]
                .into_iter()
                .flatten()
                .all(|t| t.0.index() < nf && t.2.index() < ne);
            if !hs.flatten().all(|h| h.edge().index() < ne)
                || s.kept.index() >= nv
                || s.removed.index() >= nv
                || !faces_ok
            {
                return Err(bad("a split names an id outside the input's"));
            }
        }
        Ok(ProgressiveMesh::from_parts(
            s.capacity,
            Arc::new(s.base),
            Arc::new(s.splits),
        ))
    }
}

/// A pass's sort key packed in 8 bytes: the cost as `f32` bits (costs are
/// never negative, so their bits order as the costs do) above the edge
/// id. The exact cost is computed again when the edge's turn comes.
fn entry(cost: f32, e: EdgeId) -> u64 {
    ((cost.to_bits() as u64) << 32) | e.0 as u64
}

/// Cost bands of a pass, as upper bounds of the cost bits, cheapest
/// first: [`PASS_BANDS`] bands of about equal size up to [`PASS_SLACK`]
/// times the cost at [`PASS_QUANTILE`] of the keys (all keys when not
/// `limited`). From a histogram of the costs' top 16 bits (sign, exponent
/// and 7 mantissa bits: within 1 %), linear in the keys.
fn cost_bands(keys: &[u64], hist: &mut [u32], limited: bool) -> Vec<u32> {
    hist.fill(0);
    for &k in keys {
        hist[(k >> 48) as usize] += 1;
    }
    // The upper bound of the bucket where the running count passes `n`.
    let bucket_top = |n: usize| -> u32 {
        let mut sum = 0usize;
        for (b, &c) in hist.iter().enumerate() {
            sum += c as usize;
            if sum > n {
                return ((b as u32) << 16) | 0xffff;
            }
        }
        u32::MAX
    };
    let limit = if limited {
        let q = bucket_top((keys.len() as f64 * PASS_QUANTILE) as usize);
        (f32::from_bits(q) * PASS_SLACK).to_bits()
    } else {
        u32::MAX
    };
    let eligible: usize = hist[..=(limit >> 16) as usize]
        .iter()
        .map(|&c| c as usize)
        .sum();
    let mut bands: Vec<u32> = (1..PASS_BANDS)
        .map(|i| bucket_top(eligible * i / PASS_BANDS).min(limit))
        .collect();
    bands.push(limit);
    bands.dedup();
    bands
}

/// Each pass works through its cost bands one after the other, each in
/// edge order (memory order, so that neighbouring collapses share cache
/// lines): the sequence is cheapest first up to a band.
const PASS_BANDS: usize = 4;

/// A pass collapses edges up to this multiple of the cost at
/// [`PASS_QUANTILE`] of its sorted keys (meshoptimizer takes 1.5 at about
/// two thirds; a lower quantile keeps the sequence closer to cheapest
/// first at the price of more passes).
const PASS_SLACK: f32 = 1.5;
/// See [`PASS_SLACK`].
const PASS_QUANTILE: f64 = 0.5;

/// Up to two collapses of one edge (one per direction), cheapest first:
/// cost, the half-edge whose target goes, the position.
#[derive(Copy, Clone)]
struct Candidates {
    items: [(f64, HalfEdgeId, DVec3); 2],
    len: usize,
}

impl Default for Candidates {
    fn default() -> Self {
        Candidates {
            items: [(0.0, HalfEdgeId(0), DVec3::ZERO); 2],
            len: 0,
        }
    }
}

impl Candidates {
    fn add(&mut self, c: (f64, HalfEdgeId, DVec3)) {
        self.items[self.len] = c;
        self.len += 1;
    }
    fn first(&self) -> Option<&(f64, HalfEdgeId, DVec3)> {
        self.items[..self.len].first()
    }
    fn iter(&self) -> impl Iterator<Item = (f64, HalfEdgeId, DVec3)> + '_ {
        self.items[..self.len].iter().copied()
    }
}

/// The simplification's state while it builds the sequence.
struct Simplifier<'a> {
    mesh: HalfEdgeMesh,
    options: &'a DecimateOptions,
    creases: &'a Creases,
    quadrics: Vec<Quadric>,
    feature: Vec<bool>,
    cos_limit: f64,
    /// Vertices on a feature edge or a border (a collapse passes the flag
    /// on to the kept vertex); the others have no feature edges to count.
    near_feature: Vec<bool>,
    /// Vertices with corner sharpness (with `keep_creases`): they stay.
    corner_sharp: Vec<bool>,
    /// Vertices that a collapse of this pass moved: their edges wait for
    /// the next pass, whose costs see the change.
    locked: Vec<bool>,
    /// Triangles removed so far (for the progress).
    removed_faces: usize,
}

/// How often (in sort keys looked at) the build reports its progress and
/// reads the cancel flag: a few hundred times per pass on a 1M-triangle
/// mesh, each a relaxed atomic load.
const CHECK_EVERY: usize = 4096;

/// The build was cancelled (inside the simplifier).
struct Cancelled;

/// The progress callback and the cancel flag of a build, with what the
/// callback was last told (so that it only hears increases).
struct Control<'a> {
    progress: &'a mut dyn FnMut(f64),
    cancel: &'a AtomicBool,
    told: f64,
    /// Triangles of the (triangulated) input.
    faces: usize,
}

impl Control<'_> {
    /// Share of the build before the collapses (checks, triangulation,
    /// quadrics) and after them (the base mesh).
    const BEFORE: f64 = 0.02;
    const AFTER: f64 = 0.03;

    /// Tells the callback `fraction` when it grew by at least 0.001 (or
    /// reached 1); `Err` when the cancel flag is set.
    fn report(&mut self, fraction: f64) -> Result<(), Cancelled> {
        if self.cancel.load(Ordering::Relaxed) {
            return Err(Cancelled);
        }
        let f = fraction.clamp(0.0, 1.0);
        if f >= self.told + 0.001 || (f == 1.0 && self.told < 1.0) {
            self.told = f;
            (self.progress)(f);
        }
        Ok(())
    }
    /// During the collapses: the share of the input's triangles removed
    /// (the base keeps a few, so the last pass ends a little short).
    fn collapsing(&mut self, removed: usize) -> Result<(), Cancelled> {
        let done = removed as f64 / self.faces.max(1) as f64;
        self.report(Self::BEFORE + (1.0 - Self::BEFORE - Self::AFTER) * done)
    }
}

impl Simplifier<'_> {
    fn is_feature(&self, e: EdgeId) -> bool {
        self.feature[e.index()] || self.mesh.is_boundary_edge(e)
    }
    /// Number of feature edges at `v`, and whether `v` is a corner of
    /// the features: one or three or more feature edges, or two that turn
    /// by more than [`CORNER_TURN`].
    fn feature_degree(&self, v: VertexId) -> (usize, bool) {
        if !self.near_feature[v.index()] {
            return (0, false);
        }
        let m = &self.mesh;
        let mut ends = [DVec3::ZERO; 2];
        let mut n = 0;
        for h in m.vertex_outgoing(v) {
            if self.is_feature(h.edge()) {
                if n < 2 {
                    ends[n] = m.position(m.target(h));
                }
                n += 1;
            }
        }
        let corner = match n {
            0 => false,
            2 => {
                let p = m.position(v);
                let (x, y) = (
                    (p - ends[0]).normalize_or_zero(),
                    (ends[1] - p).normalize_or_zero(),
                );
                x.dot(y) < CORNER_TURN.cos()
            }
            _ => true,
        };
        (n, corner)
    }
    fn fixed(&self, v: VertexId, corner: bool) -> bool {
        corner
            || (self.options.keep_borders && self.mesh.is_boundary_vertex(v))
            || self.corner_sharp[v.index()]
    }

    /// The position and error of collapsing `h` (its target into its
    /// origin), or `None` when the features forbid it.
    fn candidate(&self, h: HalfEdgeId) -> Option<(f64, DVec3)> {
        let m = &self.mesh;
        let (a, b) = (m.origin(h), m.target(h));
        let ((da, corner_a), (db, corner_b)) = (self.feature_degree(a), self.feature_degree(b));
        if self.fixed(b, corner_b) {
            return None;
        }
        let on_feature = self.is_feature(h.edge());
        if db == 2 && !on_feature {
            return None;
        }
        let q = self.quadrics[a.index()] + self.quadrics[b.index()];
        let (pa, pb) = (m.position(a), m.position(b));
        if self.fixed(a, corner_a) || (da > 0 && db == 0) {
            return Some((q.mean_error(pa), pa));
        }
        let mid = (pa + pb) * 0.5;
        let mut best = (q.error(pa), pa);
        let optimum = q.minimizer().map(|p| {
            if db == 2 {
                // Sliding along a feature line: stay on the edge.
                let d = pb - pa;
                pa + d * ((p - pa).dot(d) / d.length_squared()).clamp(0.0, 1.0)
            } else {
                p
            }
        });
        let reach = 2.0 * pa.distance(pb);
        let optimum = optimum.filter(|p| p.distance(mid) <= reach);
        for p in [Some(pb), Some(mid), optimum].into_iter().flatten() {
            let e = q.error(p);
            // Endpoints win ties, so exact positions (corners) stay exact.
            if e < best.0 * (1.0 - 1e-9) {
                best = (e, p);
            }
        }
        // The choice above compares one quadric's sums; the cost compares
        // collapses everywhere, as a mean squared distance.
        let w = q.weight();
        Some((if w > 0.0 { best.0 / w } else { 0.0 }, best.1))
    }

    /// The allowed collapses of `e`, cheapest first. Away from features
    /// both directions have the same placement and cost, computed once.
    fn candidates(&self, e: EdgeId) -> Candidates {
        let [a, b] = self.mesh.edge_vertices(e);
        let plain = |v: VertexId| !self.near_feature[v.index()] && !self.corner_sharp[v.index()];
        let mut out = Candidates::default();
        if plain(a) && plain(b) {
            let h = e.halfedge(0);
            if let Some((c, p)) = self.candidate(h) {
                out.add((c, h, p));
                out.add((c, h.twin(), p));
            }
            return out;
        }
        for h in [e.halfedge(0), e.halfedge(1)] {
            if let Some((c, p)) = self.candidate(h) {
                out.add((c, h, p));
            }
        }
        if out.len == 2 && out.items[1].0 < out.items[0].0 {
            out.items.swap(0, 1);
        }
        out
    }

    /// The checks the Euler operator does not make: no triangle edge that
    /// the collapse removes may be a border (its vertex split could not
    /// rebuild the triangle), and no face may turn by more than the limit
    /// or degenerate.
    fn allowed(&self, h: HalfEdgeId, p: DVec3) -> bool {
        let m = &self.mesh;
        let t = h.twin();
        for x in [h, t] {
            if m.face(x).is_some() && m.is_boundary_edge(m.next(x).edge()) {
                return false;
            }
        }
        let (a, b) = (m.origin(h), m.target(h));
        let (fl, fr) = (m.face(h), m.face(t));
        for v in [a, b] {
            for o in m.vertex_outgoing(v) {
                let Some(f) = m.face(o) else { continue };
                if Some(f) == fl || Some(f) == fr {
                    continue;
                }
                let x = m.position(m.target(o));
                let y = m.position(m.target(m.next(o)));
                let q = m.position(v);
                let before = (x - q).cross(y - q);
                let after = (x - p).cross(y - p);
                let scale = before.length();
                let turned = after.length();
                if turned <= 1e-12 * scale.max(1e-300) || turned == 0.0 {
                    return false;
                }
                if before.dot(after) < self.cos_limit * scale * turned {
                    return false;
                }
            }
        }
        true
    }
}

impl ProgressiveMesh {
    /// Simplifies (a triangulated copy of) `mesh` as far as the options
    /// allow and keeps the whole sequence; the result stands at level 0,
    /// the base mesh. `creases` are the input's (by its ids).
    ///
    /// Inverse: seeking the last level
    /// ([`seek`](Self::seek)`(level_count() − 1)`) gives the input back.
    ///
    /// # Errors
    /// [`DecimateError::NotManifold`], [`DecimateError::NotPolygon`],
    /// [`DecimateError::NoFaces`], [`DecimateError::Triangulate`]; the
    /// input is never changed.
    ///
    /// Complexity: O(n) per pass for n edges (costing, a radix sort and
    /// the collapses, each touching one vertex's neighbourhood); the
    /// number of passes grows as log n.
    pub fn build(
        mesh: &HalfEdgeMesh,
        creases: &Creases,
        options: &DecimateOptions,
    ) -> Result<ProgressiveMesh, DecimateError> {
        Self::build_with_progress(mesh, creases, options, &mut |_| {}, &AtomicBool::new(false))
    }

    /// [`build`](Self::build) for a background job: calls `progress` with
    /// the fraction done, in [0, 1], never decreasing, each value at least
    /// 0.001 above the last and 1 as the last call when the build
    /// succeeds; reads `cancel` a few hundred times per pass of the
    /// simplification (every few milliseconds) and stops when it is set.
    /// The input is borrowed and never changed; see [`BuildJob`] for a
    /// build that owns its inputs and moves to a worker thread.
    ///
    /// # Errors
    /// As [`build`](Self::build), and [`DecimateError::Cancelled`] when
    /// `cancel` was set: nothing is returned but the error (the partial
    /// simplification is dropped) and `progress` is not called again.
    ///
    /// Complexity: as [`build`](Self::build).
    pub fn build_with_progress(
        mesh: &HalfEdgeMesh,
        creases: &Creases,
        options: &DecimateOptions,
        progress: &mut dyn FnMut(f64),
        cancel: &AtomicBool,
    ) -> Result<ProgressiveMesh, DecimateError> {
        let mut control = Control {
            progress,
            cancel,
            told: 0.0,
            faces: 0,
        };
        let cancelled = |_: Cancelled| DecimateError::Cancelled;
        control.report(0.0).map_err(cancelled)?;
        let input = Self::triangulated(mesh)?;
        control.faces = input.face_count();
        let mut s = Simplifier {
            quadrics: vec![Quadric::default(); input.vertex_capacity()],
            feature: vec![false; input.edge_capacity()],
            near_feature: vec![false; input.vertex_capacity()],
            corner_sharp: (0..input.vertex_capacity() as u32)
                .map(|v| options.keep_creases && creases.vertex(VertexId(v)) > 0.0)
                .collect(),
            locked: vec![false; input.vertex_capacity()],
            removed_faces: 0,
            cos_limit: options.max_normal_change.to_radians().cos(),
            options,
            creases,
            mesh: input,
        };
        s.init_quadrics();
        let n_faces = s.mesh.face_count();
        let mut splits = Vec::with_capacity(s.mesh.vertex_count());
        control.report(Control::BEFORE).map_err(cancelled)?;
        s.run(&mut splits, &mut control).map_err(cancelled)?;
        control.report(1.0 - Control::AFTER).map_err(cancelled)?;
        let capacity = [
            s.mesh.vertex_capacity(),
            s.mesh.edge_capacity(),
            s.mesh.face_capacity(),
        ];
        let base = Arc::new(Self::compact(&s.mesh)?);
        let mut pm = ProgressiveMesh::from_parts(capacity, base, Arc::new(splits));
        debug_assert_eq!(pm.face_counts.last(), Some(&n_faces));
        // The simplified mesh is the base in the input's ids: keep it as the
        // working mesh instead of the dense copy.
        pm.mesh = s.mesh;
        pm.identity_maps();
        control.report(1.0).map_err(cancelled)?;
        Ok(pm)
    }

    /// A triangulated copy of `mesh`, after checking it.
    fn triangulated(mesh: &HalfEdgeMesh) -> Result<HalfEdgeMesh, DecimateError> {
        mesh.validate().map_err(DecimateError::NotManifold)?;
        if let Some(face) = mesh.first_non_polygon_face() {
            return Err(DecimateError::NotPolygon { face });
        }
        if mesh.face_count() == 0 {
            return Err(DecimateError::NoFaces);
        }
        let mut out = mesh.clone();
        let big: Vec<FaceId> = mesh.faces().filter(|&f| mesh.face_degree(f) > 3).collect();
        if !big.is_empty() {
            triangulate_faces(&mut out, &big, TriangulateMethod::Beauty)
                .map_err(DecimateError::Triangulate)?;
        }
        Ok(out)
    }

    fn from_parts(
        capacity: [usize; 3],
        base: Arc<Base>,
        splits: Arc<Vec<VertexSplit>>,
    ) -> ProgressiveMesh {
        let mut counts = Vec::with_capacity(splits.len() + 1);
        let mut faces = base.mesh.face_count();
        counts.push(faces);
        for s in splits.iter().rev() {
            faces += s.triangles();
            counts.push(faces);
        }
        let [nv, ne, nf] = capacity;
        let mut fwd_v = vec![u32::MAX; nv];
        let mut fwd_e = vec![u32::MAX; ne];
        let mut fwd_f = vec![u32::MAX; nf];
        for (i, &x) in base.vertices.iter().enumerate() {
            fwd_v[x as usize] = i as u32;
        }
        for (i, &x) in base.edges.iter().enumerate() {
            fwd_e[x as usize] = (i as u32) << 1;
        }
        for (i, &x) in base.faces.iter().enumerate() {
            fwd_f[x as usize] = i as u32;
        }
        ProgressiveMesh {
            capacity,
            mesh: base.mesh.clone(),
            inv_v: base.vertices.clone(),
            inv_e: base.edges.iter().map(|&e| e << 1).collect(),
            inv_f: base.faces.clone(),
            fwd_v,
            fwd_e,
            fwd_f,
            level: 0,
            face_counts: Arc::new(counts),
            base,
            splits,
        }
    }

    /// The maps when the working mesh is in the input's ids.
    fn identity_maps(&mut self) {
        let [nv, ne, nf] = self.capacity;
        self.fwd_v = (0..nv as u32).collect();
        self.fwd_e = (0..ne as u32).map(|e| e << 1).collect();
        self.fwd_f = (0..nf as u32).collect();
        self.inv_v = self.fwd_v.clone();
        self.inv_e = self.fwd_e.clone();
        self.inv_f = self.fwd_f.clone();
    }

    /// The mesh with dense ids and the input id of each.
    fn compact(mesh: &HalfEdgeMesh) -> Result<Base, DecimateError> {
        let rank = |n: usize, live: &mut dyn Iterator<Item = u32>| {
            let mut map = vec![u32::MAX; n];
            let mut back = Vec::new();
            for x in live {
                map[x as usize] = back.len() as u32;
                back.push(x);
            }
            (map, back)
        };
        let (vm, vertices) = rank(mesh.vertex_capacity(), &mut mesh.vertices().map(|v| v.0));
        let (em, edges) = rank(mesh.edge_capacity(), &mut mesh.edges().map(|e| e.0));
        let (fm, faces) = rank(mesh.face_capacity(), &mut mesh.faces().map(|f| f.0));
        let dense = renumber(
            mesh,
            [vertices.len(), edges.len(), faces.len()],
            |v| vm[v.index()],
            |h| (em[h.edge().index()] << 1) | (h.0 & 1),
            |f| fm[f.index()],
        )?;
        Ok(Base {
            mesh: dense,
            vertices,
            edges,
            faces,
        })
    }

    // ----- queries --------------------------------------------------------

    /// Number of levels: one more than the number of vertex splits.
    pub fn level_count(&self) -> usize {
        self.splits.len() + 1
    }
    /// The current level (0: the base mesh; `level_count() − 1`: the input).
    pub fn level(&self) -> usize {
        self.level
    }
    /// The finest level, the input's.
    pub fn max_level(&self) -> usize {
        self.splits.len()
    }
    /// Faces at each level, from the base (index 0) to the input.
    pub fn face_counts(&self) -> &[usize] {
        &self.face_counts
    }
    /// Faces at `level` (`None` past the last level).
    pub fn face_count_at(&self, level: usize) -> Option<usize> {
        self.face_counts.get(level).copied()
    }
    /// The vertex splits in collapse order: split `i` undoes the `i`-th
    /// collapse from the input, so going from level `L` to `L − 1`
    /// collapses `splits()[max_level() − L]`.
    pub fn splits(&self) -> &[VertexSplit] {
        &self.splits
    }
    /// The error of `level`: the largest cost ([`VertexSplit::error`]) of the collapses
    /// that lead from the input to it (0 for the input). It never grows as
    /// faces are added back.
    pub fn error_at(&self, level: usize) -> f64 {
        let applied = self.max_level().saturating_sub(level);
        self.splits[..applied.min(self.splits.len())]
            .iter()
            .map(|s| s.error)
            .fold(0.0, f64::max)
    }
    /// The input's creases carried to the current level, by the input's
    /// ids: an edge that a collapse merged into another (the two edges of
    /// a removed triangle that meet at the removed vertex's neighbour
    /// become one) passes its sharpness on when larger; corner sharpness
    /// of removed vertices goes with them.
    ///
    /// Complexity: O(collapses applied + creases).
    pub fn level_creases(&self, creases: &Creases) -> Creases {
        let mut out = creases.clone();
        if out.is_empty() {
            return out;
        }
        let applied = self.max_level() - self.level;
        for s in &self.splits[..applied] {
            for (_, gone, keep) in [s.left, s.right].into_iter().flatten() {
                let sharp = out.edge(gone.edge());
                if sharp > out.edge(keep) {
                    out.set_edge(keep, sharp);
                }
                out.set_edge(gone.edge(), 0.0);
            }
            out.set_edge(s.edge.edge(), 0.0);
            out.set_vertex(s.removed, 0.0);
        }
        out
    }

    /// The base mesh (level 0) in dense ids.
    pub fn base_mesh(&self) -> &HalfEdgeMesh {
        &self.base.mesh
    }
    /// The current level's working mesh. Its ids are fresh ones after
    /// vertex splits; [`level_mesh`](Self::level_mesh) gives the input's.
    pub fn mesh(&self) -> &HalfEdgeMesh {
        &self.mesh
    }
    /// The input vertex a vertex of [`mesh`](Self::mesh) stands for.
    pub fn input_vertex(&self, v: VertexId) -> VertexId {
        VertexId(self.inv_v[v.index()])
    }

    /// The level with at most the target's faces and the most faces, or
    /// an error when the base has more.
    ///
    /// # Errors
    /// [`DecimateError::Ratio`] for a ratio outside (0, 1],
    /// [`DecimateError::BelowMinimum`].
    pub fn level_for(&self, target: DecimateTarget) -> Result<usize, DecimateError> {
        let goal = self.target_faces(target)?;
        let minimum = self.face_counts[0];
        if goal < minimum {
            return Err(DecimateError::BelowMinimum {
                target: goal,
                minimum,
            });
        }
        Ok(self.face_counts.partition_point(|&f| f <= goal) - 1)
    }

    /// [`level_for`](Self::level_for) clamped to the levels there are (the
    /// base for a target below it; the input for a bad ratio above 1).
    pub fn nearest_level(&self, target: DecimateTarget) -> usize {
        let goal = match target {
            DecimateTarget::Ratio(r) if r.is_nan() => 0,
            DecimateTarget::Ratio(r) => {
                (r.clamp(0.0, 1.0) * *self.face_counts.last().unwrap_or(&0) as f64).round() as usize
            }
            DecimateTarget::Faces(n) => n,
        };
        self.face_counts.partition_point(|&f| f <= goal).max(1) - 1
    }

    fn target_faces(&self, target: DecimateTarget) -> Result<usize, DecimateError> {
        match target {
            DecimateTarget::Ratio(r) => {
                if !(r > 0.0 && r <= 1.0) {
                    return Err(DecimateError::Ratio(r));
                }
                Ok((r * *self.face_counts.last().unwrap_or(&0) as f64).round() as usize)
            }
            DecimateTarget::Faces(n) => Ok(n),
        }
    }

    // ----- moving between levels ---------------------------------------------

    /// Moves to `level` from the current one: vertex splits to go finer,
    /// edge collapses to go coarser, one Euler operator sequence per level
    /// passed.
    ///
    /// Inverse: `seek` back to the level it was at.
    ///
    /// # Errors
    /// [`DecimateError::NoLevel`]; [`DecimateError::Replay`] only for a
    /// damaged stored record (the level reached is then kept).
    ///
    /// Complexity: O(Σ valence) over the levels passed.
    pub fn seek(&mut self, level: usize) -> Result<(), DecimateError> {
        if level > self.max_level() {
            return Err(DecimateError::NoLevel {
                level,
                max: self.max_level(),
            });
        }
        while self.level < level {
            let i = self.max_level() - self.level - 1;
            self.split(i).map_err(DecimateError::Replay)?;
            self.level += 1;
        }
        while self.level > level {
            let i = self.max_level() - self.level;
            let s = &self.splits[i];
            let h = self.cur_h(s.edge);
            let p = s.position;
            self.mesh
                .collapse_edge_removing_triangles(h, p)
                .map_err(DecimateError::Replay)?;
            self.level -= 1;
        }
        self.compact_if_grown()?;
        Ok(())
    }

    /// Moves to the level with at most `faces` faces (the base when it has
    /// more); returns the level.
    ///
    /// # Errors
    /// As [`seek`](Self::seek).
    pub fn set_face_count(&mut self, faces: usize) -> Result<usize, DecimateError> {
        let level = self.nearest_level(DecimateTarget::Faces(faces));
        self.seek(level)?;
        Ok(level)
    }

    /// The current level in the input's ids (every element of a level is
    /// one of the input's): at the last level a mesh
    /// [`same_as`](HalfEdgeMesh::same_as) the (triangulated) input.
    ///
    /// Complexity: O(input ids).
    pub fn level_mesh(&self) -> HalfEdgeMesh {
        let [nv, ne, nf] = self.capacity;
        let (iv, ie, iff) = (&self.inv_v, &self.inv_e, &self.inv_f);
        renumber(
            &self.mesh,
            [nv, ne, nf],
            |v| iv[v.index()],
            |h| {
                let x = ie[h.edge().index()];
                ((x >> 1) << 1) | ((h.0 & 1) ^ (x & 1))
            },
            |f| iff[f.index()],
        )
        .expect("a level renumbers into the input's ids")
    }

    /// The current level as a Decimate modifier shows it:
    /// [`level_mesh`](Self::level_mesh), with triangle pairs joined into
    /// quads by [`join_quads`] when `options.keep_quads`. `creases` are
    /// the level's ([`level_creases`](Self::level_creases)); joins keep
    /// the input's ids of everything they do not remove.
    ///
    /// Complexity: O(input ids + t log t).
    pub fn output_mesh(&self, creases: &Creases, options: &DecimateOptions) -> HalfEdgeMesh {
        let mut mesh = self.level_mesh();
        if options.keep_quads {
            let before = mesh.clone();
            if join_quads(&mut mesh, creases, options).is_err() {
                // A refused join leaves triangles; the level itself is valid.
                mesh = before;
            }
        }
        mesh
    }

    /// After many moves the working mesh collects dead slots (each split
    /// takes fresh ids); rebuild it in the input's ids then.
    fn compact_if_grown(&mut self) -> Result<(), DecimateError> {
        if self.mesh.vertex_capacity() > 3 * self.capacity[0] + 1024 {
            self.mesh = self.level_mesh();
            self.identity_maps();
        }
        Ok(())
    }

    fn cur_v(&self, v: VertexId) -> VertexId {
        VertexId(self.fwd_v[v.index()])
    }
    fn cur_h(&self, h: HalfEdgeId) -> HalfEdgeId {
        let x = self.fwd_e[h.edge().index()];
        HalfEdgeId(((x >> 1) << 1) | ((h.0 & 1) ^ (x & 1)))
    }
    fn grow(&mut self) {
        self.inv_v.resize(self.mesh.vertex_capacity(), u32::MAX);
        self.inv_e.resize(self.mesh.edge_capacity(), u32::MAX);
        self.inv_f.resize(self.mesh.face_capacity(), u32::MAX);
    }
    fn map_vertex(&mut self, input: VertexId, current: VertexId) {
        self.fwd_v[input.index()] = current.0;
        self.inv_v[current.index()] = input.0;
    }
    /// Records that input half-edge `input` is current half-edge `current`.
    fn map_halfedge(&mut self, input: HalfEdgeId, current: HalfEdgeId) {
        let flip = (input.0 ^ current.0) & 1;
        self.fwd_e[input.edge().index()] = (current.edge().0 << 1) | flip;
        self.inv_e[current.edge().index()] = (input.edge().0 << 1) | flip;
    }
    fn map_face(&mut self, input: FaceId, current: FaceId) {
        self.fwd_f[input.index()] = current.0;
        self.inv_f[current.index()] = input.0;
    }

    /// Undoes collapse `i`: a vertex split, then one MEF per triangle.
    fn split(&mut self, i: usize) -> Result<(), EulerError> {
        let s = self.splits[i].clone();
        let a = self.cur_v(s.kept);
        let (first, last) = (self.cur_h(s.first), self.cur_h(s.last));
        let e = self.mesh.split_vertex(a, first, last, s.removed_position)?;
        self.mesh.set_position(a, s.kept_position);
        self.grow();
        let (h_new, t_new) = (e.halfedge(0), e.halfedge(1));
        let w = self.mesh.target(h_new);
        self.map_vertex(s.removed, w);
        self.map_halfedge(s.edge, h_new);
        if let Some((face, removed, _)) = s.left {
            let hb = self.mesh.prev(self.mesh.prev(h_new));
            let (ne, g) = self.mesh.make_edge_face(h_new, hb)?;
            self.grow();
            let from_w = if self.mesh.origin(ne.halfedge(0)) == w {
                ne.halfedge(0)
            } else {
                ne.halfedge(1)
            };
            self.map_halfedge(removed, from_w);
            let tri = self.mesh.face(h_new).expect("the new triangle");
            self.map_split_face(face, tri, g);
        }
        if let Some((face, removed, _)) = s.right {
            let hb = self.mesh.prev(first.twin());
            let (ne, g) = self.mesh.make_edge_face(t_new, hb)?;
            self.grow();
            let from_a = if self.mesh.origin(ne.halfedge(0)) == a {
                ne.halfedge(0)
            } else {
                ne.halfedge(1)
            };
            self.map_halfedge(removed, from_a);
            let tri = self.mesh.face(t_new).expect("the new triangle");
            self.map_split_face(face, tri, g);
        }
        Ok(())
    }

    /// After a MEF made face `made` and left the triangle `tri` (either may
    /// be the old face's id): the triangle is input face `input`, the other
    /// part keeps the input face the old id stood for.
    fn map_split_face(&mut self, input: FaceId, tri: FaceId, made: FaceId) {
        if tri != made {
            let other = FaceId(self.inv_f[tri.index()]);
            self.map_face(other, made);
        }
        self.map_face(input, tri);
    }
}

impl Simplifier<'_> {
    fn init_quadrics(&mut self) {
        let m = &self.mesh;
        let cos_sharp = self.options.sharp_angle.map(|a| a.to_radians().cos());
        for f in m.faces() {
            let n = m.face_area_vector(f);
            let area = n.length();
            if area <= 0.0 {
                continue;
            }
            let q = Quadric::plane(
                n / area,
                m.position(m.face_vertices(f).next().unwrap()),
                // √area (meshoptimizer's `quadricFromTriangle`): the
                // weights are lengths, like the feature planes'.
                area.sqrt(),
            );
            for v in m.face_vertices(f) {
                self.quadrics[v.index()] += q;
            }
        }
        for e in m.edges() {
            let crease = self.options.keep_creases && self.creases.edge(e) > 0.0;
            let seam = self.options.seams.contains(&e);
            let sharp = match (cos_sharp, m.edge_faces(e)) {
                (Some(c), [Some(f), Some(g)]) => m.face_normal(f).dot(m.face_normal(g)) < c,
                _ => false,
            };
            self.feature[e.index()] = crease || seam || sharp;
            if !(self.feature[e.index()] || m.is_boundary_edge(e)) {
                continue;
            }
            let [a, b] = m.edge_vertices(e);
            self.near_feature[a.index()] = true;
            self.near_feature[b.index()] = true;
            let (pa, pb) = (m.position(a), m.position(b));
            let dir = pb - pa;
            let len = dir.length();
            for f in m.edge_faces(e).into_iter().flatten() {
                let n = dir.cross(m.face_normal(f)).normalize_or_zero();
                if n == DVec3::ZERO {
                    continue;
                }
                let q = Quadric::plane(n, pa, FEATURE_WEIGHT * len);
                self.quadrics[a.index()] += q;
                self.quadrics[b.index()] += q;
            }
        }
    }

    /// Collapses in passes until none is possible, appending the records
    /// (meshoptimizer's scheme, A. Kapoulkine, `simplifier.cpp`): each
    /// pass computes every edge's cost in edge order (memory order, so
    /// the costs stream through the cache), sorts the keys, and collapses
    /// cheapest first up to [`PASS_SLACK`] times the cost at
    /// [`PASS_QUANTILE`]; a collapse locks the kept vertex for the rest of
    /// the pass (its quadric and position changed, so its edges' keys are
    /// stale until the next pass costs them). Every other edge's key stays
    /// exact (a cost reads only its two vertices), and the fold-over test
    /// and the features are checked when the edge's turn comes, on the
    /// mesh as it is then. A pass that collapses nothing is followed by
    /// one without the cost limit; when that collapses nothing either,
    /// no collapse is left (refusals depend on the neighbourhood, so each
    /// pass tries every edge again).
    ///
    /// `control` is told the faces removed and asked whether to stop
    /// every [`CHECK_EVERY`] keys; `Err` when it says stop.
    fn run(&mut self, out: &mut Vec<VertexSplit>, control: &mut Control) -> Result<(), Cancelled> {
        let mut keys: Vec<u64> = Vec::new();
        let mut hist = vec![0u32; 1 << 16];
        let mut touched: Vec<VertexId> = Vec::new();
        let mut limited = true;
        loop {
            keys.clear();
            for e in self.mesh.edges() {
                if let Some(&(cost, _, _)) = self.candidates(e).first() {
                    keys.push(entry(cost as f32, e));
                }
            }
            if keys.is_empty() {
                return Ok(());
            }
            let bands = cost_bands(&keys, &mut hist, limited);
            let before = out.len();
            let mut lower = None;
            for &upper in &bands {
                for (i, &k) in keys.iter().enumerate() {
                    if i % CHECK_EVERY == 0 {
                        control.collapsing(self.removed_faces)?;
                    }
                    let bits = (k >> 32) as u32;
                    if bits > upper || lower.is_some_and(|l| bits <= l) {
                        continue;
                    }
                    let e = EdgeId(k as u32);
                    if !self.mesh.is_edge(e) {
                        continue;
                    }
                    let [a, b] = self.mesh.edge_vertices(e);
                    if self.locked[a.index()] || self.locked[b.index()] {
                        continue;
                    }
                    for (cost, h, p) in self.candidates(e).iter() {
                        if !self.allowed(h, p) {
                            continue;
                        }
                        if let Some(split) = self.collapse(h, p, cost) {
                            self.locked[split.kept.index()] = true;
                            touched.push(split.kept);
                            self.removed_faces += split.triangles();
                            out.push(split);
                            break;
                        }
                    }
                }
                lower = Some(upper);
            }
            for v in touched.drain(..) {
                self.locked[v.index()] = false;
            }
            let progressed = out.len() > before;
            if !progressed && !limited {
                return Ok(());
            }
            limited = progressed;
        }
    }

    /// One collapse through the Euler operator, with its record; `None`
    /// when the operator refuses (the mesh is then unchanged).
    fn collapse(&mut self, h: HalfEdgeId, p: DVec3, cost: f64) -> Option<VertexSplit> {
        let m = &self.mesh;
        let t = h.twin();
        let (a, b) = (m.origin(h), m.target(h));
        let tri = |x: HalfEdgeId| m.face(x).is_some() && m.next(m.next(m.next(x))) == x;
        let left = tri(h).then(|| (m.face(h).unwrap(), m.next(h), m.prev(h).edge()));
        let right = tri(t).then(|| (m.face(t).unwrap(), m.next(t), m.prev(t).edge()));
        let last = match left {
            Some((_, nh, _)) => m.next(nh.twin()),
            None => m.next(h),
        };
        let split = VertexSplit {
            edge: h,
            kept: a,
            removed: b,
            first: m.prev(t).twin(),
            last,
            left,
            right,
            position: p,
            kept_position: m.position(a),
            removed_position: m.position(b),
            error: cost,
        };
        // The triangles' surviving edges take over the features of the
        // removed ones.
        self.mesh.collapse_edge_removing_triangles(h, p).ok()?;
        for (_, gone, keep) in [left, right].into_iter().flatten() {
            if self.feature[gone.edge().index()] {
                self.feature[keep.index()] = true;
            }
        }
        let q = self.quadrics[a.index()] + self.quadrics[b.index()];
        self.quadrics[a.index()] = q;
        self.near_feature[a.index()] |= self.near_feature[b.index()];
        Some(split)
    }
}

/// `mesh` with every live element renamed by the maps, in an id space of
/// the given capacities (vertices, edges, faces); other slots are dead.
/// Built through [`MeshData`], so the result is validated.
fn renumber(
    mesh: &HalfEdgeMesh,
    [nv, ne, nf]: [usize; 3],
    vmap: impl Fn(VertexId) -> u32,
    hmap: impl Fn(HalfEdgeId) -> u32,
    fmap: impl Fn(FaceId) -> u32,
) -> Result<HalfEdgeMesh, MeshDataError> {
    let mut positions = vec![DVec3::ZERO; nv];
    let mut vertex_halfedge = vec![-1i64; nv];
    let mut halfedges = vec![(0u32, 0u32, 0u32, -1i64); 2 * ne];
    let mut face_halfedge = vec![u32::MAX; nf];
    let (mut live_v, mut live_e, mut live_f) = (vec![false; nv], vec![false; ne], vec![false; nf]);
    for v in mesh.vertices() {
        let i = vmap(v) as usize;
        live_v[i] = true;
        positions[i] = mesh.position(v);
        vertex_halfedge[i] = mesh.vertex_halfedge(v).map_or(-1, |h| hmap(h) as i64);
    }
    for h in mesh.halfedges() {
        let i = hmap(h) as usize;
        live_e[i / 2] = true;
        halfedges[i] = (
            vmap(mesh.origin(h)),
            hmap(mesh.next(h)),
            hmap(mesh.prev(h)),
            mesh.face(h).map_or(-1, |f| fmap(f) as i64),
        );
    }
    for f in mesh.faces() {
        let i = fmap(f) as usize;
        live_f[i] = true;
        face_halfedge[i] = hmap(mesh.face_halfedge(f));
    }
    let dead = |live: &[bool]| -> Vec<u32> {
        live.iter()
            .enumerate()
            .filter(|(_, l)| !**l)
            .map(|(i, _)| i as u32)
            .collect()
    };
    HalfEdgeMesh::try_from(MeshData {
        positions,
        vertex_halfedge,
        halfedges,
        face_halfedge,
        dead_vertices: dead(&live_v),
        dead_edges: dead(&live_e),
        dead_faces: dead(&live_f),
        face_rings: Vec::new(),
        lone_vertex_faces: Vec::new(),
    })
}

/// Simplifies `mesh` to `target` in one go (Blender's Decimate ▸
/// Collapse, applied): builds the progressive mesh and returns the level,
/// triangulated, in the input's ids where they survive (triangulation's
/// new edges and faces have fresh ones).
///
/// Inverse: none (keep the [`ProgressiveMesh`] to go back).
///
/// # Errors
/// As [`ProgressiveMesh::build`] and [`ProgressiveMesh::level_for`]
/// ([`DecimateError::BelowMinimum`] when the target is below what the
/// mesh can be simplified to).
///
/// Complexity: O(n log n).
pub fn decimate(
    mesh: &HalfEdgeMesh,
    creases: &Creases,
    options: &DecimateOptions,
    target: DecimateTarget,
) -> Result<HalfEdgeMesh, DecimateError> {
    let mut pm = ProgressiveMesh::build(mesh, creases, options)?;
    let level = pm.level_for(target)?;
    pm.seek(level)?;
    Ok(pm.output_mesh(&pm.level_creases(creases), options))
}

/// Joins pairs of triangles of a decimated level into quads, pairing as
/// many as it can (Decimate's keep-quads): the good pairs of Blender's
/// Tris to Quads first ([`tris_to_quads`](crate::modeling::tris_to_quads)
/// with its default 40° limits on the faces' angle and on the corners'
/// distance from a right angle, best first; the faces' angle is the quad's
/// fold across either diagonal, [`quad_fold`](crate::modeling::quad_fold),
/// so that a reader splitting the quad the other way sees the same limit),
/// then pairs with corners up to
/// [`LOOSE_JOIN_LIMIT`] from a right angle for the triangles left over,
/// and augmenting paths that re-pair two joined triangles so that two
/// more join (a maximum matching of the triangles, nearly). Each join is
/// a [`kill_edge_face`](HalfEdgeMesh::kill_edge_face). Never across a
/// feature edge that the simplification kept: a crease of `creases`
/// (when `options.keep_creases`), a seam of `options`, or an edge sharper
/// than `options.sharp_angle`. Returns the quads made.
///
/// Why re-pairing rather than collapsing only along edges that keep
/// quads: the quadric collapses stay those of the triangle mesh, so the
/// progressive record, its error bound and the speed do not change, and
/// every level is still a valid mesh (a KEF keeps it valid); a quad grid
/// comes back as quads at the finest level (its own pairs are exact
/// squares, the best joins). Coarse levels are mostly quads by face count
/// (measured on a curved 24 × 24 sheet, a 48 × 24 torus and a cube cut
/// 16 × 16 per side, at 50, 25, 10 and 5 % of the triangles: see the
/// test `keep_quads_gives_mostly_quads_at_every_level`).
///
/// Inverse: none (triangulate the quads to go back to the level).
///
/// # Errors
/// None in practice: only the join's own refusals
/// ([`DecimateError::Triangulate`]), which a valid level never raises.
///
/// Complexity: O(t log t) for t triangles.
pub fn join_quads(
    mesh: &mut HalfEdgeMesh,
    creases: &Creases,
    options: &DecimateOptions,
) -> Result<Vec<FaceId>, DecimateError> {
    let triangles: Vec<FaceId> = mesh.faces().filter(|&f| mesh.face_degree(f) == 3).collect();
    if triangles.is_empty() {
        return Ok(Vec::new());
    }
    let cos_sharp = options.sharp_angle.map(|a| a.to_radians().cos());
    let joinable = |e: EdgeId| {
        if options.keep_creases && creases.edge(e) > 0.0 {
            return false;
        }
        if options.seams.contains(&e) {
            return false;
        }
        match (cos_sharp, mesh.edge_faces(e)) {
            (Some(c), [Some(f), Some(g)]) => mesh.face_normal(f).dot(mesh.face_normal(g)) >= c,
            _ => true,
        }
    };
    let limit = crate::modeling::DEFAULT_JOIN_LIMIT;
    let pairs =
        crate::modeling::quad_pairing(mesh, &triangles, limit, limit, LOOSE_JOIN_LIMIT, joinable);
    let mut quads = Vec::with_capacity(pairs.len());
    for e in pairs {
        let [Some(a), Some(b)] = mesh.edge_faces(e) else {
            continue;
        };
        let killed = mesh
            .kill_edge_face(e)
            .map_err(|err| DecimateError::Triangulate(err.into()))?;
        quads.push(if killed == a { b } else { a });
    }
    Ok(quads)
}

/// How far from a right angle a corner of a quad that keep-quads makes
/// from two leftover triangles may be (70°: corners between 20° and
/// 160°); good pairs use Blender's 40° first.
pub const LOOSE_JOIN_LIMIT: f64 = 70.0 * std::f64::consts::PI / 180.0;
