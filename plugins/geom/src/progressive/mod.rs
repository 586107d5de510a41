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
//! faces and along them: borders, creases, UV seams and edges sharper
//! than the sharp-feature angle), costs a collapse as the quadric's error at the
//! best of the two ends, the midpoint and the optimum (with the tangent
//! planes of doubly curved vertices added to the cost,
//! `CURVATURE_WEIGHT`), divided by the
//! worst shape of the triangles it leaves (MeshLab's quality penalty), and
//! collapses edges cheapest first from a priority queue, costing the
//! edges around each collapse again (Garland and Heckbert's greedy
//! order), until no collapse is
//! allowed. Every collapse goes through the kernel's Euler
//! operator [`HalfEdgeMesh::collapse_edge_removing_triangles`] (with its
//! link condition, so genus, shells and border count never change) and is
//! refused when it would turn a face's normal by more than
//! [`DecimateOptions::max_normal_change`] (fold-over).
//!
//! Feature edges hold: a vertex on two feature edges may only slide along
//! them into a neighbour on the same line (placed on that edge), a vertex
//! on one or three or more feature edges, or on two that turn by more than
//! 45° both at it and over two edges on each side (a corner; a zigzag
//! border of a scan turns at every vertex but not over two edges), never
//! moves, and with
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

use crate::EulerError;
use crate::ids::{EdgeId, FaceId, HalfEdgeId, VertexId};
use crate::mesh::{HalfEdgeMesh, MeshDataError};
use crate::modeling::ModelingError;
use crate::subdivision::Creases;
use crate::validate::ValidationError;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

mod build;
mod collapse;
mod decimate;
mod levels;
mod order;
mod quadric;

pub use decimate::{LOOSE_JOIN_LIMIT, decimate, join_quads};
pub use quadric::Quadric;

/// Weight of a feature plane per unit of edge length, against face planes
/// weighted by the square root of their area (Garland and Heckbert's
/// boundary penalty, scaled as meshoptimizer scales it: both weights are
/// lengths, so the balance does not depend on the mesh's size or
/// density). Each side of a feature edge gives two planes through it,
/// both this strong: the one perpendicular to the face and the face's own
/// (meshoptimizer's `fillEdgeQuadrics`, `kEdgeWeightBorder` = 10).
/// Measured with the face's plane added, on issue 35's table (the range
/// scan, the one input with borders: at 10 % its Hausdorff distance
/// 7.20e-4 → 5.52e-4, at 1 % its mean 4.04e-4 → 3.75e-4, 20 gives
/// 5.70e-4 and 3.93e-4) and on `bench/decimate-compare`'s open tube at 1 %
/// (0.00841 → 0.00337; 20 gives 0.00270; meshoptimizer 0.00436). With the
/// perpendicular plane alone, 15 and 20 gave the tube's lowest error.
const FEATURE_WEIGHT: f64 = 10.0;

/// Weight of a vertex's tangent plane per radian of its angle defect and
/// unit of the square root of its area (so a length, like the other
/// weights), at vertices curved the same way as all their neighbours.
/// The angle defect `2π − Σ corner angles` is the discrete Gaussian
/// curvature integrated over the vertex's area (M. Meyer, M. Desbrun,
/// P. Schröder and A. Barr, "Discrete Differential-Geometry Operators for
/// Triangulated 2-Manifolds", VisMath 2002). Garland and Heckbert's
/// face planes barely notice a round corner or a tip leaving: its
/// faces' planes pass close to wherever the collapse puts the vertex.
/// The tangent plane of each doubly curved vertex makes such collapses
/// cost what their depth is, so the greedy order keeps corners and tips
/// longer (a curvature-aware cost, as S.-J. Kim, C.-H. Kim and D. Levin,
/// "Surface simplification using a discrete curvature norm", Computers &
/// Graphics 2002, measure curvature with the angle defect; here it is in
/// the cost only: the placement stays the quadric's optimum).
/// Measured on issue 35's table: the creased cube's rounded corners at
/// 1 % go from a Hausdorff distance 1.17× meshoptimizer's
/// `simplifyWithUpdate` to 0.99× for weights 0.25, 0.5, 1, 4 and 8
/// (1.08× at 2); 4 keeps
/// every other row at or below the peers (the 1 % rows of the bunny, the
/// sphere and the torus move by a few per cent either way with the
/// weight: their greedy order is chaotic at that coarseness).
/// Vertices whose defect changes sign within their ring (scan noise)
/// add nothing.
const CURVATURE_WEIGHT: f64 = 4.0;

/// `curved_at` of a vertex without tangent planes.
const NOT_CURVED: u32 = u32::MAX;

/// A vertex where two feature edges (border, crease, seam, sharp) meet
/// turning by more than this (45°), at the vertex and over two edges on
/// each side, is a corner of the features and never moves.
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

/// The simplification's state while it builds the sequence.
struct Simplifier<'a> {
    mesh: HalfEdgeMesh,
    options: &'a DecimateOptions,
    creases: &'a Creases,
    quadrics: Vec<Quadric>,
    /// The tangent planes of the curved spots a vertex stands for
    /// ([`CURVATURE_WEIGHT`]): added to the cost of its collapses, never
    /// to the quadric that places the vertex. Only the vertices that have
    /// any hold one (`curved_at[v]`, an index into `curvature`, or
    /// [`NOT_CURVED`]), so that the costing of the others reads no more
    /// memory than before.
    curvature: Vec<Quadric>,
    curved_at: Vec<u32>,
    feature: Vec<bool>,
    cos_limit: f64,
    /// Vertices on a feature edge or a border (a collapse passes the flag
    /// on to the kept vertex); the others have no feature edges to count.
    near_feature: Vec<bool>,
    /// Vertices with corner sharpness (with `keep_creases`): they stay.
    corner_sharp: Vec<bool>,
    /// Triangles removed so far (for the progress).
    removed_faces: usize,
}

/// How often (in queue keys taken) the build reports its progress and
/// reads the cancel flag: a few hundred times on a 1M-triangle mesh, each
/// a relaxed atomic load.
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
    /// (the base keeps a few, so the simplification ends a little short).
    fn collapsing(&mut self, removed: usize) -> Result<(), Cancelled> {
        let done = removed as f64 / self.faces.max(1) as f64;
        self.report(Self::BEFORE + (1.0 - Self::BEFORE - Self::AFTER) * done)
    }
}
