//! A mesh node's modifier stack (Blender's modifier stack): the Mirror,
//! Array and Decimate modifiers, evaluated in order on the cage, and where the
//! subdivision modifier runs among them
//! ([`SubdivisionModifier::stack_position`](crate::SubdivisionModifier::stack_position)). The cage stays what the user
//! edits; [`MeshContent::evaluated`] is what export, `hedra info` and the
//! viewport show.
//!
//! What follows the cage through the stack: creases are carried to every
//! copy (each copied edge and vertex gets its source's sharpness, through
//! [`CopiedMesh`]), so a subdivision after a mirror is as sharp on both
//! halves. Corner attributes (UVs, custom normals) are not part of the
//! evaluated mesh; [`Command::ApplyModifiers`](crate::Command::ApplyModifiers)
//! carries the UVs of every corner to its copies (normals are dropped, as
//! after any edit).

use crate::scene::{CornerAttributes, MeshContent};
use glam::DVec3;
use hedra_geom::modeling::{
    ArrayOffset, CopiedMesh, MAX_ARRAY_COUNT, MirrorAxis, ModelingError, arrayed_copies,
    mirrored_copies,
};
use hedra_geom::progressive::{
    BuildJob, DecimateError, DecimateOptions, DecimateTarget, ProgressiveMesh,
};
use hedra_geom::subdivision::{Creases, Refiner, SubdivisionError};
use hedra_geom::{EdgeId, HalfEdgeId, HalfEdgeMesh};
use serde::{Deserialize, Serialize};
use std::borrow::Cow;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::sync::Arc;

/// One modifier of a mesh node's stack.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum MeshModifier {
    /// Mirror copies across the node's local planes (Blender's Mirror).
    Mirror(MirrorModifier),
    /// Copies in a row (Blender's Array).
    Array(ArrayModifier),
    /// Fewer faces by edge collapses, at a level of its progressive mesh
    /// (Blender's Decimate, Collapse).
    Decimate(DecimateModifier),
}

impl MeshModifier {
    /// The modifier's kind as the user sees it: `"Mirror"`, `"Array"` or
    /// `"Decimate"`.
    pub fn name(&self) -> &'static str {
        match self {
            MeshModifier::Mirror(_) => "Mirror",
            MeshModifier::Array(_) => "Array",
            MeshModifier::Decimate(_) => "Decimate",
        }
    }

    /// A one-line description for listings (`hedra info`).
    pub fn summary(&self) -> String {
        match self {
            MeshModifier::Mirror(m) => {
                let axes: String = MirrorAxis::ALL
                    .iter()
                    .filter(|a| m.axes[a.index()])
                    .map(|a| format!("{a:?}"))
                    .collect();
                let axes = if axes.is_empty() { "none".into() } else { axes };
                format!(
                    "Mirror {axes}{}{}",
                    if m.merge {
                        format!(", merge {}", m.merge_distance)
                    } else {
                        String::new()
                    },
                    if m.clipping { ", clipping" } else { "" }
                )
            }
            MeshModifier::Array(a) => {
                let v = |v: DVec3| format!("({}, {}, {})", v.x, v.y, v.z);
                let mut s = format!("Array ×{}", a.count);
                if let Some(r) = a.relative_offset {
                    s += &format!(", relative {}", v(r));
                }
                if let Some(c) = a.constant_offset {
                    s += &format!(", constant {}", v(c));
                }
                if a.merge {
                    s += &format!(", merge {}", a.merge_distance);
                }
                s
            }
            MeshModifier::Decimate(d) => {
                let mut s = match (d.level, d.target) {
                    (Some(level), _) => format!("Decimate to level {level}"),
                    (None, DecimateTarget::Ratio(r)) => format!("Decimate to {}%", r * 100.0),
                    (None, DecimateTarget::Faces(n)) => format!("Decimate to {n} faces"),
                };
                for (on, what) in [
                    (d.keep_borders, "borders"),
                    (d.keep_creases, "creases"),
                    (d.keep_uv_seams, "UV seams"),
                ] {
                    if on {
                        s += &format!(", keep {what}");
                    }
                }
                if let Some(a) = d.sharp_angle {
                    s += &format!(", sharp {a}°");
                }
                s
            }
        }
    }

    /// Checks the values a stored or commanded modifier carries.
    ///
    /// # Errors
    /// The first [`ModifierProblem`] found.
    pub fn check(&self) -> Result<(), ModifierProblem> {
        let distance = |merge: bool, d: f64| {
            if merge && !(d.is_finite() && d >= 0.0) {
                Err(ModifierProblem::MergeDistance(d))
            } else {
                Ok(())
            }
        };
        match self {
            MeshModifier::Mirror(m) => distance(m.merge, m.merge_distance),
            MeshModifier::Array(a) => {
                if a.count == 0 || a.count > MAX_ARRAY_COUNT {
                    return Err(ModifierProblem::Count(a.count));
                }
                let finite = |v: Option<DVec3>| v.is_none_or(|v| v.is_finite());
                if !finite(a.relative_offset) || !finite(a.constant_offset) {
                    return Err(ModifierProblem::Offset);
                }
                distance(a.merge, a.merge_distance)
            }
            MeshModifier::Decimate(d) => d.check(),
        }
    }

    /// A Mirror or Array modifier applied to `mesh`, with where each
    /// result element came from. A Decimate modifier needs its
    /// progressive record and is applied by [`MeshContent::evaluate`] and
    /// [`MeshContent::with_modifiers_applied`]; here it is refused.
    ///
    /// # Errors
    /// The kernel's [`ModelingError`] (a count of 0, a merge that is not
    /// manifold, a mesh without faces); [`ModelingError::Parameter`] for
    /// Decimate.
    pub fn apply(&self, mesh: &HalfEdgeMesh) -> Result<CopiedMesh, ModelingError> {
        match self {
            MeshModifier::Decimate(_) => Err(ModelingError::Parameter {
                what: "modifier",
                allowed: "Mirror or Array (Decimate is evaluated with its record)",
                value: "Decimate".into(),
            }),
            MeshModifier::Mirror(m) => {
                mirrored_copies(mesh, m.axes, m.merge.then_some(m.merge_distance))
            }
            MeshModifier::Array(a) => arrayed_copies(
                mesh,
                a.count,
                ArrayOffset {
                    relative: a.relative_offset,
                    constant: a.constant_offset,
                },
                a.merge.then_some(a.merge_distance),
            ),
        }
    }
}

/// Blender's Mirror modifier: the mesh and its mirror images across the
/// planes x = 0, y = 0, z = 0 of the node's local space (its origin), for
/// each axis set, applied X, then Y, then Z (up to 8 copies); see
/// [`hedra_geom::modeling::mirrored`].
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MirrorModifier {
    /// Mirror across x = 0, y = 0, z = 0 (default: X only, as Blender).
    #[serde(default = "x_only")]
    pub axes: [bool; 3],
    /// Weld vertices within `merge_distance` of a mirror plane to their
    /// images (default on, as Blender).
    #[serde(default = "crate::scene::yes")]
    pub merge: bool,
    /// How close to the plane a vertex is welded and clipped (default
    /// 0.001, Blender's).
    #[serde(default = "mirror_distance")]
    pub merge_distance: f64,
    /// Keep vertices on the mirror plane while dragging them (Blender's
    /// Clipping). Only stored here: the GUI calls [`MirrorModifier::clip`]
    /// on each dragged vertex.
    #[serde(default)]
    pub clipping: bool,
}

fn x_only() -> [bool; 3] {
    [true, false, false]
}
fn mirror_distance() -> f64 {
    0.001
}

impl Default for MirrorModifier {
    fn default() -> Self {
        MirrorModifier {
            axes: x_only(),
            merge: true,
            merge_distance: mirror_distance(),
            clipping: false,
        }
    }
}

impl MirrorModifier {
    /// Where a vertex dragged from `before` to `after` (local space) goes
    /// with clipping on (Blender's Clipping): for each mirror axis, a vertex
    /// that was within `merge_distance` of the plane stays on it, and one
    /// that would cross the plane stops on it. With clipping off, `after`.
    pub fn clip(&self, before: DVec3, after: DVec3) -> DVec3 {
        if !self.clipping {
            return after;
        }
        let mut p = after;
        for i in (0..3).filter(|&i| self.axes[i]) {
            let on_plane = before[i].abs() <= self.merge_distance;
            let crossed = before[i] * after[i] < 0.0;
            if on_plane || crossed {
                p[i] = 0.0;
            }
        }
        p
    }
}

/// Blender's Array modifier with a fixed count: `count` copies, each moved
/// by `relative_offset × bounding box size + constant_offset` from the
/// previous one; see [`hedra_geom::modeling::arrayed`].
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ArrayModifier {
    /// Number of copies including the original, at least 1 (default 2).
    #[serde(default = "two_copies")]
    pub count: u32,
    /// Offset per copy as a factor of the bounding box size (default
    /// `(1, 0, 0)`, Blender's); `None`: off.
    #[serde(default = "along_x")]
    pub relative_offset: Option<DVec3>,
    /// Offset per copy in local units, added (default off).
    #[serde(default)]
    pub constant_offset: Option<DVec3>,
    /// Weld vertices of neighbouring copies within `merge_distance`
    /// (default off, as Blender).
    #[serde(default)]
    pub merge: bool,
    /// The merge distance (default 0.01, Blender's).
    #[serde(default = "array_distance")]
    pub merge_distance: f64,
}

fn two_copies() -> u32 {
    2
}
fn along_x() -> Option<DVec3> {
    Some(DVec3::X)
}
fn array_distance() -> f64 {
    0.01
}

impl Default for ArrayModifier {
    fn default() -> Self {
        ArrayModifier {
            count: two_copies(),
            relative_offset: along_x(),
            constant_offset: None,
            merge: false,
            merge_distance: array_distance(),
        }
    }
}

/// Blender's Decimate modifier (Collapse) with Hedra's level slider: the
/// mesh simplified by quadric edge collapses
/// ([`hedra_geom::progressive`]) down to `target`, or to `level` of its
/// progressive mesh when the slider has set one. The progressive record
/// is built once per input and kept beside the stack
/// ([`MeshContent::decimations`]), so changing the target or the level
/// replays splits or collapses instead of simplifying again. The mesh is
/// triangulated first; with `keep_quads` each level shown is re-paired
/// into quads where they fit ([`hedra_geom::progressive::join_quads`]).
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DecimateModifier {
    /// How far: a ratio of the faces (default 0.5) or a face count.
    #[serde(default = "half")]
    pub target: DecimateTarget,
    /// A level of the progressive mesh (0: the coarsest), set by the
    /// level slider; it wins over `target` (default none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub level: Option<usize>,
    /// Border vertices never move (default off: they slide along the
    /// border, which keeps its shape).
    #[serde(default)]
    pub keep_borders: bool,
    /// Creased edges hold and corner-sharp vertices stay (default on).
    #[serde(default = "crate::scene::yes")]
    pub keep_creases: bool,
    /// Edges where the UVs of the corners on both sides differ hold
    /// (default on; only when the modifier runs on the cage, which has
    /// the UVs).
    #[serde(default = "crate::scene::yes")]
    pub keep_uv_seams: bool,
    /// Edges whose faces meet at more than this angle (degrees) hold
    /// (default none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sharp_angle: Option<f64>,
    /// Triangle pairs of the result joined into quads where they make a
    /// good one, never across a kept crease, seam or sharp edge, and never
    /// a quad folded more than 40° across either diagonal
    /// ([`hedra_geom::modeling::quad_fold`]) (default off: triangles;
    /// files from before it load with it off).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub keep_quads: bool,
}

fn half() -> DecimateTarget {
    DecimateTarget::Ratio(0.5)
}

impl Default for DecimateModifier {
    fn default() -> Self {
        DecimateModifier {
            target: half(),
            level: None,
            keep_borders: false,
            keep_creases: true,
            keep_uv_seams: true,
            sharp_angle: None,
            keep_quads: false,
        }
    }
}

impl DecimateModifier {
    /// Checks the target ratio and the sharp angle.
    ///
    /// # Errors
    /// [`ModifierProblem::Ratio`], [`ModifierProblem::SharpAngle`].
    pub fn check(&self) -> Result<(), ModifierProblem> {
        if let DecimateTarget::Ratio(r) = self.target
            && !(r > 0.0 && r <= 1.0)
        {
            return Err(ModifierProblem::Ratio(r));
        }
        if let Some(a) = self.sharp_angle
            && !(0.0..=180.0).contains(&a)
        {
            return Err(ModifierProblem::SharpAngle(a));
        }
        Ok(())
    }

    /// The kernel's options for these settings, with the seams to keep.
    pub fn options(&self, seams: BTreeSet<EdgeId>) -> DecimateOptions {
        DecimateOptions {
            keep_borders: self.keep_borders,
            keep_creases: self.keep_creases,
            sharp_angle: self.sharp_angle,
            keep_quads: self.keep_quads,
            seams: if self.keep_uv_seams {
                seams
            } else {
                BTreeSet::new()
            },
            ..DecimateOptions::default()
        }
    }

    /// The level these settings show on `progressive`: `level` (clamped),
    /// else the finest level within `target`, else the coarsest.
    pub fn level_on(&self, progressive: &ProgressiveMesh) -> usize {
        match self.level {
            Some(l) => l.min(progressive.max_level()),
            None => progressive.nearest_level(self.target),
        }
    }
}

/// A Decimate modifier's progressive record, kept beside the stack and in
/// the scene file: the record (base mesh and vertex splits, not every
/// level) and a fingerprint of what it was built from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DecimateRecord {
    /// [`decimate_key`] of the modifier's input mesh, creases and options.
    pub key: u64,
    /// The progressive mesh.
    pub progressive: ProgressiveMesh,
}

/// A progressive record a command would build: its key and the build,
/// with owned inputs, to run on a worker thread
/// ([`BuildJob::run`] reports progress and can be cancelled).
pub struct PendingDecimation {
    /// The record's [`decimate_key`].
    pub key: u64,
    /// The build.
    pub job: BuildJob,
}

thread_local! {
    /// While [`decimations_needed`] runs on this thread: the builds noted.
    static DEFERRED: std::cell::RefCell<Option<Vec<PendingDecimation>>> =
        const { std::cell::RefCell::new(None) };
}

/// Records built ahead of the command that needs them, taken by it.
static PREBUILT: std::sync::Mutex<Vec<Arc<DecimateRecord>>> = std::sync::Mutex::new(Vec::new());

/// How many records built ahead are kept at most (the oldest go).
const PREBUILT_KEPT: usize = 4;

fn deferring() -> bool {
    DEFERRED.with(|d| d.borrow().is_some())
}

fn defer(p: PendingDecimation) {
    DEFERRED.with(|d| {
        if let Some(list) = d.borrow_mut().as_mut() {
            list.push(p);
        }
    });
}

fn take_prebuilt(key: u64) -> Option<Arc<DecimateRecord>> {
    let mut kept = PREBUILT.lock().ok()?;
    let at = kept.iter().position(|r| r.key == key)?;
    Some(kept.remove(at))
}

/// Runs `dry_run` (deciding a command without applying it:
/// [`Document::decide`](crate::Document::decide)) with Decimate builds
/// deferred, and returns the progressive records it would have built —
/// the first of a stack only, as later ones depend on its result. The app
/// runs them on a worker thread with progress and cancel
/// ([`prebuild`]), then executes the command, which finds them built.
pub fn decimations_needed<T>(dry_run: impl FnOnce() -> T) -> Vec<PendingDecimation> {
    DEFERRED.with(|d| *d.borrow_mut() = Some(Vec::new()));
    let _ = dry_run();
    DEFERRED.with(|d| d.borrow_mut().take().unwrap_or_default())
}

/// Keeps a record built ahead (by a worker) for the command that needs
/// it: the next refresh whose input has `key` takes it instead of building.
pub fn prebuild(key: u64, progressive: ProgressiveMesh) {
    if let Ok(mut kept) = PREBUILT.lock() {
        kept.retain(|r| r.key != key);
        kept.push(Arc::new(DecimateRecord { key, progressive }));
        let extra = kept.len().saturating_sub(PREBUILT_KEPT);
        kept.drain(..extra);
    }
}

/// A fingerprint (64-bit FNV-1a, the same in every build) of a mesh's
/// records, its creases and decimation options: records whose key matches
/// were built from exactly this input.
pub fn decimate_key(mesh: &HalfEdgeMesh, creases: &Creases, options: &DecimateOptions) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |x: u64| {
        for b in x.to_le_bytes() {
            h ^= b as u64;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    eat(mesh.vertex_capacity() as u64);
    eat(mesh.edge_capacity() as u64);
    eat(mesh.face_capacity() as u64);
    for v in mesh.vertices() {
        let p = mesh.position(v);
        eat(v.0 as u64);
        for c in [p.x, p.y, p.z] {
            eat(c.to_bits());
        }
    }
    for x in mesh.halfedges() {
        eat(x.0 as u64);
        eat(mesh.origin(x).0 as u64);
        eat(mesh.next(x).0 as u64);
        eat(mesh.face(x).map_or(u64::MAX, |f| f.0 as u64));
    }
    for (e, s) in &creases.edges {
        eat(e.0 as u64);
        eat(s.to_bits());
    }
    eat(u64::MAX);
    for (v, s) in &creases.vertices {
        eat(v.0 as u64);
        eat(s.to_bits());
    }
    eat(options.keep_borders as u64);
    eat(options.keep_creases as u64);
    eat(options.sharp_angle.map_or(u64::MAX, f64::to_bits));
    eat(options.max_normal_change.to_bits());
    for e in &options.seams {
        eat(e.0 as u64);
    }
    h
}

/// The UV seams of `mesh`: edges where a corner on one side and the corner
/// at the same vertex on the other side both have UVs, and they differ.
///
/// # Example
/// Two quads of a grid with the UVs of the right one moved: the edge
/// between them is the one seam.
/// ```
/// use hedra_doc::{CornerAttributes, modifiers::uv_seams};
/// use hedra_geom::{DVec2, Primitive};
/// use std::sync::Arc;
/// let m = Primitive::Grid { x_segments: 2, z_segments: 1, size: 2.0 }.build()?;
/// let mut uvs = std::collections::BTreeMap::new();
/// for h in m.halfedges().filter(|&h| m.face(h).is_some()) {
///     let p = m.position(m.origin(h));
///     let right = m.face_centroid(m.face(h).unwrap()).x > 0.0;
///     uvs.insert(h, DVec2::new(p.x + if right { 5.0 } else { 0.0 }, p.z));
/// }
/// let corners = CornerAttributes { uvs: Arc::new(uvs), ..Default::default() };
/// let seams: Vec<_> = uv_seams(&m, &corners).into_iter().collect();
/// assert_eq!(seams.len(), 1);
/// assert!(m.edge_vertices(seams[0]).iter().all(|&v| m.position(v).x == 0.0));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn uv_seams(mesh: &HalfEdgeMesh, corners: &CornerAttributes) -> BTreeSet<EdgeId> {
    let uvs = &corners.uvs;
    if uvs.is_empty() {
        return BTreeSet::new();
    }
    let differ = |x: HalfEdgeId, y: HalfEdgeId| match (uvs.get(&x), uvs.get(&y)) {
        (Some(a), Some(b)) => a != b,
        _ => false,
    };
    mesh.edges()
        .filter(|&e| !mesh.is_boundary_edge(e))
        .filter(|&e| {
            let (h, t) = (e.halfedge(0), e.halfedge(1));
            differ(h, mesh.next(t)) || differ(mesh.next(h), t)
        })
        .collect()
}

/// A modifier value out of range (refused by the modifier commands and
/// when loading a file).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ModifierProblem {
    /// An array count of 0 or above [`MAX_ARRAY_COUNT`].
    #[error("array count must be between 1 and {MAX_ARRAY_COUNT}, got {0}")]
    Count(u32),
    /// A merge distance that is negative or not finite.
    #[error("merge distance must be a finite distance ≥ 0, got {0}")]
    MergeDistance(f64),
    /// An array offset with an infinite or NaN component.
    #[error("array offset is not finite")]
    Offset,
    /// A decimation ratio outside (0, 1].
    #[error("decimate ratio must be above 0 and at most 1, got {0}")]
    Ratio(f64),
    /// A sharp-feature angle outside 0° to 180°.
    #[error("sharp angle must be between 0 and 180 degrees, got {0}")]
    SharpAngle(f64),
}

/// Why a node's stack could not be evaluated.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EvaluationError {
    /// A stack modifier refused (numbered from 1, as the properties panel
    /// lists them).
    #[error("modifier {} ({name}): {error}", index + 1)]
    Modifier {
        /// The modifier's index in the stack, from 0.
        index: usize,
        /// Its kind, `"Mirror"` or `"Array"`.
        name: &'static str,
        /// The kernel's reason.
        error: ModelingError,
    },
    /// The subdivision modifier refused (its message as it is).
    #[error(transparent)]
    Subdivision(#[from] SubdivisionError),
    /// A Decimate modifier refused (its input is not manifold polygons,
    /// say), numbered from 1.
    #[error("modifier {} (Decimate): {error}", index + 1)]
    Decimate {
        /// The modifier's index in the stack, from 0.
        index: usize,
        /// The kernel's reason.
        error: DecimateError,
    },
}

/// A node's mesh with some or all of its stack applied, and the creases
/// that go with it.
#[derive(Clone, Debug)]
pub struct Evaluated<'a> {
    /// The mesh (the cage itself, borrowed, when nothing changed it).
    pub mesh: Cow<'a, HalfEdgeMesh>,
    /// Its creases.
    pub creases: Cow<'a, Creases>,
}

impl MeshContent {
    /// True when the node has Mirror or Array modifiers, so that what it
    /// shows is not the cage (or its subdivision) alone. The app's smooth
    /// preview refines [`smooth_cage`](Self::smooth_cage) then, not the
    /// cage.
    pub fn has_stack_modifiers(&self) -> bool {
        !self.modifiers.is_empty()
    }

    /// How many stack modifiers run before subdivision (the subdivision
    /// modifier's [`stack_position`](crate::SubdivisionModifier::stack_position),
    /// clamped to the stack; all of them by default).
    pub fn subdivision_position(&self) -> usize {
        self.subdivision
            .and_then(|s| s.stack_position)
            .unwrap_or(usize::MAX)
            .min(self.modifiers.len())
    }

    /// The first `count` stack modifiers applied to the cage, with the
    /// creases carried along.
    ///
    /// # Errors
    /// [`EvaluationError::Modifier`] naming the modifier that refused.
    pub fn apply_stack(&self, count: usize) -> Result<Evaluated<'_>, EvaluationError> {
        self.run_stack(
            &self.modifiers[..count.min(self.modifiers.len())],
            0,
            self.start(),
        )
    }

    fn start(&self) -> Evaluated<'_> {
        Evaluated {
            mesh: Cow::Borrowed(&self.mesh),
            creases: Cow::Borrowed(&self.creases),
        }
    }

    fn run_stack<'a>(
        &self,
        modifiers: &[MeshModifier],
        first_index: usize,
        mut current: Evaluated<'a>,
    ) -> Result<Evaluated<'a>, EvaluationError> {
        for (k, m) in modifiers.iter().enumerate() {
            if let MeshModifier::Decimate(d) = m {
                let (pm, level, options) = self.decimated(d, first_index + k, &current)?;
                let creases = pm.level_creases(&current.creases);
                current = Evaluated {
                    mesh: Cow::Owned(pm.output_mesh(&creases, &options)),
                    creases: Cow::Owned(creases),
                };
                debug_assert_eq!(pm.level(), level);
                continue;
            }
            let copies = m
                .apply(&current.mesh)
                .map_err(|error| EvaluationError::Modifier {
                    index: first_index + k,
                    name: m.name(),
                    error,
                })?;
            let creases = copies.creases(&current.mesh, &current.creases);
            current = Evaluated {
                mesh: Cow::Owned(copies.mesh),
                creases: Cow::Owned(creases),
            };
        }
        Ok(current)
    }

    /// The kernel options of Decimate modifier `d` on `input`: its UV
    /// seams are the cage's when `input` is the cage itself.
    fn decimate_options(&self, d: &DecimateModifier, input: &HalfEdgeMesh) -> DecimateOptions {
        let on_cage = std::ptr::eq(input, self.mesh.as_ref());
        let seams = if on_cage && d.keep_uv_seams {
            uv_seams(input, &self.corners)
        } else {
            BTreeSet::new()
        };
        d.options(seams)
    }

    /// The progressive mesh of Decimate modifier `d` (at stack `index`) on
    /// `input`, moved to the modifier's level: a copy of its stored record
    /// when one was built from this very input, else built now.
    fn decimated(
        &self,
        d: &DecimateModifier,
        index: usize,
        input: &Evaluated<'_>,
    ) -> Result<(ProgressiveMesh, usize, DecimateOptions), EvaluationError> {
        let here = |error| EvaluationError::Decimate { index, error };
        let options = self.decimate_options(d, &input.mesh);
        let key = decimate_key(&input.mesh, &input.creases, &options);
        let mut pm = match self.decimations.iter().find(|r| r.key == key) {
            Some(r) => r.progressive.clone(),
            None => ProgressiveMesh::build(&input.mesh, &input.creases, &options).map_err(here)?,
        };
        let level = d.level_on(&pm);
        pm.seek(level).map_err(here)?;
        Ok((pm, level, options))
    }

    /// The progressive mesh of the Decimate modifier at stack `index`, at
    /// the level it shows: its stored record when there is one for its
    /// input (subdivision before it at the viewport level), else built now.
    /// `None` when that modifier is not a Decimate. The app clones it to
    /// scrub the level (`seek`) without evaluating the stack again.
    ///
    /// # Errors
    /// [`EvaluationError`] naming the modifier that refused.
    pub fn progressive(&self, index: usize) -> Result<Option<ProgressiveMesh>, EvaluationError> {
        let Some(MeshModifier::Decimate(d)) = self.modifiers.get(index) else {
            return Ok(None);
        };
        let split = self.subdivision_position();
        let input = if split <= index {
            let before = self.run_stack(&self.modifiers[..split], 0, self.start())?;
            let level = self.subdivision.map_or(0, |s| s.viewport_level);
            let smooth = if level == 0 {
                before
            } else {
                let options = self.subdivision.unwrap_or_default().options;
                let (mesh, creases) =
                    Refiner::subdivide(&before.mesh, &before.creases, options, level)?;
                Evaluated {
                    mesh: Cow::Owned(mesh),
                    creases: Cow::Owned(creases),
                }
            };
            self.run_stack(&self.modifiers[split..index], split, smooth)?
        } else {
            self.run_stack(&self.modifiers[..index], 0, self.start())?
        };
        self.decimated(d, index, &input).map(|(pm, _, _)| Some(pm))
    }

    /// The face count of every level of the Decimate modifier at stack
    /// `index`, from the coarsest (level 0) to its input's (what `hedra
    /// info` reports as the levels available); `None` when that modifier is
    /// not a Decimate.
    ///
    /// # Errors
    /// As [`progressive`](Self::progressive).
    pub fn decimate_face_counts(
        &self,
        index: usize,
    ) -> Result<Option<Vec<usize>>, EvaluationError> {
        Ok(self.progressive(index)?.map(|pm| pm.face_counts().to_vec()))
    }

    /// True when the stack has a Decimate modifier.
    pub fn has_decimate(&self) -> bool {
        self.modifiers
            .iter()
            .any(|m| matches!(m, MeshModifier::Decimate(_)))
    }

    /// Builds the progressive record of every Decimate modifier whose
    /// input has none and drops records no modifier uses any more; each
    /// record is left at its modifier's level, so that evaluating starts
    /// there. The commands call this after every change of a node that has
    /// Decimate modifiers (an edit of the cage changes their input).
    ///
    /// # Errors
    /// [`EvaluationError`] naming the modifier that refused; the records
    /// are unchanged then.
    pub fn refresh_decimations(&mut self) -> Result<(), EvaluationError> {
        if !self.has_decimate() {
            self.decimations.clear();
            return Ok(());
        }
        let split = self.subdivision_position();
        let mut records: Vec<Arc<DecimateRecord>> = Vec::new();
        let mut current = self.start();
        for (index, m) in self.modifiers.iter().enumerate() {
            if index == split
                && let Some(s) = self.subdivision.filter(|s| s.viewport_level > 0)
            {
                // Subdivision before a Decimate: the record is the one of
                // the viewport level (another level builds its own when
                // evaluated).
                let (mesh, creases) = Refiner::subdivide(
                    &current.mesh,
                    &current.creases,
                    s.options,
                    s.viewport_level,
                )?;
                current = Evaluated {
                    mesh: Cow::Owned(mesh),
                    creases: Cow::Owned(creases),
                };
            }
            if let MeshModifier::Decimate(d) = m {
                let options = self.decimate_options(d, &current.mesh);
                let key = decimate_key(&current.mesh, &current.creases, &options);
                let record = match self.decimations.iter().find(|r| r.key == key) {
                    Some(r) => r.clone(),
                    None => match take_prebuilt(key) {
                        Some(r) => r,
                        None if deferring() => {
                            // A dry run: note the build (later modifiers
                            // depend on its result), build nothing.
                            defer(PendingDecimation {
                                key,
                                job: BuildJob::new(
                                    current.mesh.into_owned(),
                                    current.creases.into_owned(),
                                    options,
                                ),
                            });
                            self.decimations = records;
                            return Ok(());
                        }
                        None => {
                            let pm =
                                ProgressiveMesh::build(&current.mesh, &current.creases, &options)
                                    .map_err(|error| EvaluationError::Decimate { index, error })?;
                            Arc::new(DecimateRecord {
                                key,
                                progressive: pm,
                            })
                        }
                    },
                };
                let mut record = record;
                let level = d.level_on(&record.progressive);
                if record.progressive.level() != level {
                    Arc::make_mut(&mut record)
                        .progressive
                        .seek(level)
                        .map_err(|error| EvaluationError::Decimate { index, error })?;
                }
                let creases = record.progressive.level_creases(&current.creases);
                current = Evaluated {
                    mesh: Cow::Owned(record.progressive.output_mesh(&creases, &options)),
                    creases: Cow::Owned(creases),
                };
                records.push(record);
                continue;
            }
            current = self.run_stack(std::slice::from_ref(m), index, current)?;
        }
        self.decimations = records;
        Ok(())
    }

    /// The node's final mesh with subdivision at `level` (0: no
    /// subdivision): the stack modifiers in order, with subdivision (the
    /// modifier's options, else Catmull-Clark) at its place in the stack.
    /// Without stack modifiers and at level 0 this is the cage itself,
    /// borrowed. Export, `hedra info` and the viewport show this.
    ///
    /// # Errors
    /// [`EvaluationError`] naming the modifier or the subdivision that
    /// refused.
    pub fn evaluated(&self, level: u32) -> Result<Cow<'_, HalfEdgeMesh>, EvaluationError> {
        self.evaluate(level).map(|e| e.mesh)
    }

    /// [`evaluated`](Self::evaluated) with the creases of the result.
    ///
    /// # Errors
    /// As [`evaluated`](Self::evaluated).
    pub fn evaluate(&self, level: u32) -> Result<Evaluated<'_>, EvaluationError> {
        let split = self.subdivision_position();
        let before = self.run_stack(&self.modifiers[..split], 0, self.start())?;
        let smooth = if level == 0 {
            before
        } else {
            let options = self.subdivision.unwrap_or_default().options;
            let (mesh, creases) =
                Refiner::subdivide(&before.mesh, &before.creases, options, level)?;
            Evaluated {
                mesh: Cow::Owned(mesh),
                creases: Cow::Owned(creases),
            }
        };
        self.run_stack(&self.modifiers[split..], split, smooth)
    }

    /// What the viewport's smooth preview (the kept stencil refinement,
    /// [`SmoothRefinement`](crate::smooth::SmoothRefinement)) should refine:
    /// with subdivision last in the stack (the default), the cage with the
    /// stack applied and its creases (the cage itself without stack
    /// modifiers). `None` when a stack modifier comes after subdivision:
    /// then the app draws [`evaluated`](Self::evaluated) at the viewport
    /// level and keeps no stencils.
    ///
    /// # Errors
    /// [`EvaluationError::Modifier`] naming the modifier that refused.
    pub fn smooth_cage(&self) -> Result<Option<Evaluated<'_>>, EvaluationError> {
        if self.subdivision_position() < self.modifiers.len() {
            return Ok(None);
        }
        self.apply_stack(self.modifiers.len()).map(Some)
    }

    /// The content with its first `count` stack modifiers applied, as
    /// [`Command::ApplyModifiers`](crate::Command::ApplyModifiers) makes it:
    /// their result becomes the cage (creases carried to every copy, UVs to
    /// every copied corner; custom normals and the primitive dropped) and
    /// they leave the stack. Subdivision stays a modifier after the same
    /// remaining modifiers. The caller checks that subdivision does not
    /// come before any of the applied ones.
    ///
    /// # Errors
    /// [`EvaluationError::Modifier`] naming the modifier that refused.
    pub fn with_modifiers_applied(&self, count: usize) -> Result<MeshContent, EvaluationError> {
        let count = count.min(self.modifiers.len());
        let mut out = self.clone();
        for (index, m) in self.modifiers[..count].iter().enumerate() {
            if let MeshModifier::Decimate(d) = m {
                let input = Evaluated {
                    mesh: Cow::Borrowed(out.mesh.as_ref()),
                    creases: Cow::Borrowed(&out.creases),
                };
                // Seams are found on `out`'s cage, which is the input here.
                let (pm, _, options) = out.decimated(d, index, &input)?;
                let creases = pm.level_creases(&out.creases);
                let mesh = pm.output_mesh(&creases, &options);
                out.corners = decimated_uvs(&out.mesh, &mesh, &out.corners);
                out.creases = creases;
                out.mesh = Arc::new(mesh);
                continue;
            }
            let copies = m
                .apply(&out.mesh)
                .map_err(|error| EvaluationError::Modifier {
                    index,
                    name: m.name(),
                    error,
                })?;
            out.creases = copies.creases(&out.mesh, &out.creases);
            out.corners = carried_uvs(&copies, &out.mesh, &out.corners);
            out.mesh = Arc::new(copies.mesh);
        }
        if count > 0 {
            out.primitive = None;
        }
        out.modifiers.drain(..count);
        out.decimations.clear();
        if let Some(s) = &mut out.subdivision
            && let Some(p) = &mut s.stack_position
        {
            *p = p.saturating_sub(count);
        }
        Ok(out)
    }
}

/// The UVs of `source`'s corners on `decimated` (the same ids where they
/// survive): a corner keeps its UV when it still leaves the same vertex,
/// else (its vertex merged into another, or a corner that triangulation
/// made) it takes the UV of a corner of `source` at its vertex. Custom
/// normals are dropped.
pub fn decimated_uvs(
    source: &HalfEdgeMesh,
    decimated: &HalfEdgeMesh,
    corners: &CornerAttributes,
) -> CornerAttributes {
    if corners.uvs.is_empty() {
        return CornerAttributes::default();
    }
    let mut at_vertex: BTreeMap<hedra_geom::VertexId, glam::DVec2> = BTreeMap::new();
    for (h, uv) in corners.uvs.iter() {
        if source.is_halfedge(*h) {
            at_vertex.entry(source.origin(*h)).or_insert(*uv);
        }
    }
    let mut uvs: BTreeMap<HalfEdgeId, glam::DVec2> = BTreeMap::new();
    for h in decimated.halfedges() {
        if decimated.face(h).is_none() {
            continue;
        }
        let v = decimated.origin(h);
        let own = corners
            .uvs
            .get(&h)
            .filter(|_| source.is_halfedge(h) && source.origin(h) == v);
        if let Some(uv) = own.or_else(|| at_vertex.get(&v)) {
            uvs.insert(h, *uv);
        }
    }
    CornerAttributes {
        uvs: Arc::new(uvs),
        normals: Arc::default(),
    }
}

/// The UVs of `source`'s corners on their copies in `copies` (custom
/// normals are dropped).
fn carried_uvs(
    copies: &CopiedMesh,
    source: &HalfEdgeMesh,
    corners: &CornerAttributes,
) -> CornerAttributes {
    if corners.uvs.is_empty() {
        return CornerAttributes::default();
    }
    let mut uvs: BTreeMap<HalfEdgeId, glam::DVec2> = BTreeMap::new();
    for h in copies.mesh.halfedges() {
        if let Some(uv) = copies
            .corner_source(source, h)
            .and_then(|s| corners.uvs.get(&s))
        {
            uvs.insert(h, *uv);
        }
    }
    CornerAttributes {
        uvs: Arc::new(uvs),
        normals: Arc::default(),
    }
}

impl fmt::Display for MeshModifier {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.summary())
    }
}

/// Why [`set_decimate_ratio`] changed nothing.
#[derive(Debug, thiserror::Error)]
pub enum LodError {
    /// A ratio outside (0, 1].
    #[error("--lod {0}: the ratio must be above 0 and at most 1")]
    Ratio(f64),
    /// No mesh of the scene has a Decimate modifier.
    #[error("--lod: the scene has no Decimate modifier (add one in Properties ▸ Modifiers)")]
    NoDecimate,
    /// A modifier change was refused (its message as the command gives it).
    #[error(transparent)]
    Command(#[from] crate::CommandError),
}

/// Sets every Decimate modifier of the session's meshes to `ratio` of its
/// input's faces, its level slider cleared (`hedra export --lod`), each
/// change an undo step. A modifier that already shows exactly that is
/// left as it is: it is not an error that there is nothing to change
/// (issue 31, item 18: `--lod R` failed with "nothing to do" when a
/// Decimate already targeted R). Returns how many modifiers changed.
///
/// # Errors
/// [`LodError::Ratio`] for a ratio outside (0, 1]; [`LodError::NoDecimate`]
/// when no mesh has a Decimate modifier; [`LodError::Command`] when a
/// change is refused.
pub fn set_decimate_ratio(session: &mut crate::Session, ratio: f64) -> Result<usize, LodError> {
    if !(ratio > 0.0 && ratio <= 1.0) {
        return Err(LodError::Ratio(ratio));
    }
    let mut found = false;
    let mut changes = Vec::new();
    for node in session.doc.nodes() {
        let crate::NodeContent::Mesh(content) = &node.content else {
            continue;
        };
        for (index, m) in content.modifiers.iter().enumerate() {
            let MeshModifier::Decimate(d) = m else {
                continue;
            };
            found = true;
            let wanted = DecimateModifier {
                target: DecimateTarget::Ratio(ratio),
                level: None,
                ..*d
            };
            if wanted != *d {
                changes.push(crate::Command::SetModifier {
                    node: node.id.into(),
                    index,
                    modifier: MeshModifier::Decimate(wanted),
                });
            }
        }
    }
    if !found {
        return Err(LodError::NoDecimate);
    }
    for cmd in &changes {
        session.execute(cmd)?;
    }
    Ok(changes.len())
}
