//! Catmull-Clark limit surface to NURBS patches ("SubD to NURBS", issue 33).
//!
//! # Method
//!
//! The cage is refined `k` levels (Catmull-Clark with its creases and
//! boundary rule, [`Refiner`]); at level `k` every face is a quad, and
//! (from level 2 on) each has at most one extraordinary vertex.
//!
//! - **Regular faces are exact.** A quad whose four corners are regular
//!   (smooth valence 4; on an infinitely sharp crease or boundary with two
//!   quads on each side; or a sharp corner of one quad) and that has no
//!   semi-sharp edge left at its corners has, as limit surface, the bicubic
//!   uniform B-spline patch of its 4×4 neighbourhood (phantom points mirrored
//!   across sharp edges) — Stam, "Exact Evaluation of Catmull-Clark
//!   Subdivision Surfaces at Arbitrary Parameter Values" (SIGGRAPH 1998),
//!   §2, and OpenSubdiv's regular (boundary, corner) patches. Maximal
//!   rectangles of such faces become one clamped bicubic B-spline surface
//!   each (`pack.rs`), equal to the limit surface up to rounding.
//! - **Irregular faces are approximated** by one bicubic Bézier patch each,
//!   after Peters, "Patching Catmull-Clark Meshes" (SIGGRAPH 2000): the
//!   B-spline-to-Bézier conversion of the face's grid wherever the grid
//!   exists (so the patch joins its regular neighbours with C1 continuity
//!   across their shared edges), the corner at an irregular vertex replaced
//!   by its exact limit position ([`limit_positions`]), and the Bézier
//!   edge point beside a smooth irregular vertex set so that the edge curve
//!   passes through the exact limit point at the edge's middle, then
//!   projected into the vertex's exact limit tangent plane
//!   ([`limit_normals`], Halstead et al.'s tangent masks), so that all
//!   patches around it share that tangent plane. (Fitting the middle
//!   lowered the largest distance between points of equal parameters by
//!   40 % on a cube; moving the inner point beside the vertex to fit the
//!   face's centre as well made the normal angles worse and the distance no
//!   better, so it is not done.) Around a smooth vertex of valence 6 or
//!   more, the tangent points and the patches' inner points at the vertex
//!   follow the vertex-enclosure construction instead (`star.rs`), which
//!   makes the normals agree to first order there. Neither is exactly G1
//!   along the edges out of the extraordinary vertex (no bicubic
//!   construction joined C1 to the regular patches is, in general); the
//!   mismatch and the distance from the limit surface fall with each
//!   further level, and both are measured ([`measure`]).
//! - **Refined only where needed.** The cage is refined to `k = 2` (more
//!   only for semi-sharp creases, or for irregular faces that belong to no
//!   single extraordinary vertex); from there each extraordinary vertex's
//!   star of faces is refined on its own, one level at a time, until its
//!   distance is within the tolerance and its normal angle within the limit,
//!   or [`ToNurbsOptions::max_level`] is reached (`local.rs`, after
//!   Nießner et al.'s feature-adaptive refinement, 2012). Each level adds
//!   `3n` exact patches around a vertex of valence `n`; a valence-12 vertex
//!   needs about level 8.
//! - **Watertight.** Each edge's boundary curve is computed once (its
//!   cubic Bézier control points in [`NurbsConversion::edges`]); Bézier
//!   patches copy them bit for bit, and packed B-spline surfaces equal them
//!   up to rounding (clamping by knot insertion). Infinitely sharp creases
//!   and boundaries are patch boundaries (C0, shared curve).
//! - **Semi-sharp creases** are refined away: `k` is at least the largest
//!   finite sharpness rounded up, after which the crease is smooth and the
//!   surface is the ordinary one of the refined mesh (exact, as the
//!   refinement is).

mod grid;
mod local;
pub mod measure;
mod pack;
mod star;

use std::collections::HashMap;

use glam::DVec3;

use super::level::Level;
use super::rules::is_infinite;
use super::{
    Creases, INFINITE_SHARPNESS, MAX_LEVEL, Options, Refiner, Scheme, SubdivisionError,
    limit_normals, limit_positions,
};
use crate::surfaces::NurbsSurface;
use crate::{FaceId, HalfEdgeMesh};
use grid::{VertexClass, bezier_point, classify, face_grid, full};

/// The highest level the whole cage is refined to; beyond it only the
/// stars of extraordinary vertices are (`local.rs`).
const UNIFORM_MAX_LEVEL: u32 = 5;

/// How closely to convert.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ToNurbsOptions {
    /// Largest distance allowed between an approximating patch and the limit
    /// surface, in model units (measured at dyadic samples of every
    /// approximated face).
    pub tolerance: f64,
    /// Largest normal angle allowed across a smooth patch edge, in degrees.
    pub max_angle_degrees: f64,
    /// Highest refinement level tried before giving up on the tolerance
    /// (the result is then the one of this level, with its measured
    /// figures). The whole cage is refined to at most level 5; beyond
    /// that only around extraordinary vertices.
    pub max_level: u32,
    /// Sample density of the measurement: `2^samples` intervals per level-`k`
    /// face edge.
    pub samples: u32,
    /// Sample the exact patches too (they equal the limit surface by
    /// construction; tests check it, conversions need not).
    pub measure_exact: bool,
}

impl ToNurbsOptions {
    /// The default tolerance: `fraction` (1e-4 by default) of the cage's
    /// bounding-box diagonal; 0.5° normal angle; up to level 12.
    pub fn relative(mesh: &HalfEdgeMesh, fraction: f64) -> Self {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for v in mesh.vertices() {
            lo = lo.min(mesh.position(v));
            hi = hi.max(mesh.position(v));
        }
        let diagonal = if lo.x <= hi.x {
            (hi - lo).length()
        } else {
            1.0
        };
        ToNurbsOptions {
            tolerance: fraction * diagonal,
            max_angle_degrees: 0.5,
            max_level: 12,
            samples: 2,
            measure_exact: false,
        }
    }
}

/// Why a conversion cannot be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ToNurbsError {
    /// The options' scheme is not Catmull-Clark.
    #[error("only Catmull-Clark surfaces convert to NURBS, not {}", scheme.label())]
    NotCatmullClark {
        /// The scheme.
        scheme: Scheme,
    },
    /// The refinement failed (a face with rings, a level too high, …).
    #[error(transparent)]
    Subdivision(#[from] SubdivisionError),
    /// The cage has no faces to convert.
    #[error("the cage has no faces to convert")]
    Empty,
}

/// How a patch came to be.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum PatchKind {
    /// A packed rectangle of regular faces: equal to the limit surface.
    Exact,
    /// One irregular face: within the tolerance of the limit surface.
    Approximate,
}

/// One NURBS patch of the result.
#[derive(Clone, Debug)]
pub struct ConvertedPatch {
    /// The clamped bicubic surface (weights 1). An exact patch of `w × h`
    /// faces has the domain `[0, w] × [0, h]`, an approximate one `[0, 1]²`.
    pub surface: NurbsSurface,
    /// Exact or approximate.
    pub kind: PatchKind,
    /// The cage faces it comes from (sorted, no repeats).
    pub cage_faces: Vec<FaceId>,
}

/// Where a face of the conversion level lies in its patch.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct FacePlacement {
    /// Index into [`NurbsConversion::patches`].
    pub patch: usize,
    /// The face's parameter square is `[a, a + 1] × [b, b + 1]`.
    pub offset: (usize, usize),
    /// The face's corner at the square's `(0, 0)`; its next corners follow
    /// at `(1, 0)`, `(1, 1)`, `(0, 1)`.
    pub rot: usize,
}

/// A boundary curve between patches: the limit curve along one edge of the
/// conversion level, as a cubic Bézier from `ends[0]` to `ends[1]`.
#[derive(Clone, Debug, PartialEq)]
pub struct SharedEdge {
    /// The edge's ends, as vertex indices of the conversion level.
    pub ends: [u32; 2],
    /// The Bézier control points from `ends[0]` to `ends[1]`.
    pub curve: [DVec3; 4],
    /// The one or two shown faces on the edge (level face indices).
    pub faces: Vec<u32>,
    /// An infinitely sharp crease or a boundary: C0 by design.
    pub sharp: bool,
}

/// The result of [`to_nurbs`].
#[derive(Clone, Debug)]
pub struct NurbsConversion {
    /// The refinement level the patches were made at; patches around
    /// extraordinary vertices may be finer (refined on their own, up to
    /// [`deepest_level`](Self::deepest_level)).
    pub level: u32,
    /// The finest level of any patch (`level` when no star was refined).
    pub deepest_level: u32,
    /// The patches: the exact ones of [`level`](Self::level) first, then
    /// one per irregular face left at that level, then those of the stars
    /// refined on their own (exact rings, then one per irregular face).
    /// [`placements`](Self::placements), [`edges`](Self::edges),
    /// [`face_edges`](Self::face_edges) and [`sides`](Self::sides) describe
    /// the patches of `level` only.
    pub patches: Vec<ConvertedPatch>,
    /// Per face of the conversion level: its patch, or `None` for a face
    /// left out (a hole, boundary rule None).
    pub placements: Vec<Option<FacePlacement>>,
    /// Every edge of the conversion level with a shown face, and its curve.
    pub edges: Vec<SharedEdge>,
    /// Per face of the conversion level (`None` when not shown): its four
    /// edges in face order (edge `k` from corner `k` to `k + 1`), as an index
    /// into [`edges`](Self::edges) and whether it runs the curve's way.
    pub face_edges: Vec<Option<[(usize, bool); 4]>>,
    /// The measured figures of the approximation.
    pub report: measure::Report,
}

impl NurbsConversion {
    /// The boundary of patch `patch` as four sides, counter-clockwise in
    /// its parameters: `v = 0` (u rising), `u = max` (v rising), `v = max`
    /// (u falling), `u = 0` (v falling). Each side is the chain of shared
    /// edges along it, as an index into [`edges`](Self::edges) and whether
    /// the curve runs the side's way. This is what a B-rep writer needs:
    /// every patch is one face whose loop is these edges, and each edge
    /// between two patches appears on exactly two sides (once each way on an
    /// oriented closed surface). A patch of a star refined on its own has
    /// no placement at `level`: its four sides are empty (the STEP writer
    /// takes every patch's boundary from its surface instead).
    pub fn sides(&self, patch: usize) -> [Vec<(usize, bool)>; 4] {
        let mut at: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
        for (f, p) in self.placements.iter().enumerate() {
            if let Some(p) = p
                && p.patch == patch
            {
                at.insert(p.offset, (f, p.rot));
            }
        }
        let w = at.keys().map(|&(a, _)| a + 1).max().unwrap_or(0);
        let h = at.keys().map(|&(_, b)| b + 1).max().unwrap_or(0);
        let edge = |a: usize, b: usize, local: usize| {
            let (f, rot) = at[&(a, b)];
            self.face_edges[f].expect("a placed face is shown")[(rot + local) % 4]
        };
        [
            (0..w).map(|a| edge(a, 0, 0)).collect(),
            (0..h).map(|b| edge(w - 1, b, 1)).collect(),
            (0..w).rev().map(|a| edge(a, h - 1, 2)).collect(),
            (0..h).rev().map(|b| edge(0, b, 3)).collect(),
        ]
    }

    /// Number of exact (packed) and approximate patches.
    pub fn counts(&self) -> (usize, usize) {
        let exact = self
            .patches
            .iter()
            .filter(|p| p.kind == PatchKind::Exact)
            .count();
        (exact, self.patches.len() - exact)
    }

    /// True when the measured figures meet `options`' tolerance and angle.
    /// [`to_nurbs`] can stop short of them at
    /// [`ToNurbsOptions::max_level`]: per level the distance falls by
    /// about ×0.17 at valence 3, ×0.32 at 5, ×0.37 at 6, ×0.44 at 8 and
    /// ×0.51 at 12, the angle by ×0.39, ×0.59, ×0.44, ×0.6 and ×0.83
    /// (measured on a cube and UV-sphere poles), so the default tolerance
    /// and 0.5° are met by level 3 at valence 3 and level 8 at valence 12.
    pub fn within(&self, options: &ToNurbsOptions) -> bool {
        self.report.max_distance <= options.tolerance
            && self.report.max_angle_degrees <= options.max_angle_degrees
    }
}

/// The level the conversion starts at: 0 for an all-quad cage without
/// semi-sharp creases, else enough to make every face a quad (1) and to
/// use up every finite sharpness.
fn first_level(mesh: &HalfEdgeMesh, creases: &Creases) -> u32 {
    let quads = mesh.faces().all(|f| mesh.face_degree(f) == 4);
    let sharpness = creases
        .edge_sharpness()
        .values()
        .chain(creases.vertices.values())
        .copied()
        .filter(|&s| s < f64::from(INFINITE_SHARPNESS))
        .fold(0.0, f64::max);
    u32::from(!quads).max(sharpness.ceil() as u32)
}

/// Converts the Catmull-Clark limit surface of `mesh` with `creases` and
/// `options` to NURBS patches (see the module documentation for the method
/// and its sources). An all-regular cage converts at level 0 in one
/// measurement pass; otherwise the cage is refined to the first level that
/// makes all faces quads and uses up semi-sharp creases, at least 2, and the
/// stars of extraordinary vertices further on their own until
/// [`ToNurbsOptions::tolerance`] and [`ToNurbsOptions::max_angle_degrees`]
/// hold or `max_level` is reached.
///
/// Complexity: O(faces · 4^(level + samples)) for the measurement of the
/// uniform level, plus about the same work per star and extra level.
///
/// # Example
/// A smoothed cube: its eight valence-3 corners give 24 approximated
/// patches at level 3; the rest of level 2 packs into 7 exact B-spline
/// surfaces, and the corners' refined rings into 24 more.
/// ```
/// use hedra_geom::Primitive;
/// use hedra_geom::subdivision::{Creases, Options};
/// use hedra_geom::subdivision::to_nurbs::{ToNurbsOptions, to_nurbs};
/// let cube = Primitive::Cube { size: 2.0 }.build()?;
/// let to = ToNurbsOptions::relative(&cube, 1e-4);
/// let c = to_nurbs(&cube, &Creases::default(), Options::default(), &to)?;
/// assert_eq!(c.counts(), (31, 24));
/// assert_eq!((c.level, c.deepest_level), (2, 3));
/// assert!(c.within(&to) && c.report.max_gap < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`ToNurbsError::NotCatmullClark`] for other schemes;
/// [`ToNurbsError::Subdivision`] when the cage cannot be refined (a face
/// with rings, too many faces); [`ToNurbsError::Empty`] for a cage without
/// faces.
pub fn to_nurbs(
    mesh: &HalfEdgeMesh,
    creases: &Creases,
    options: Options,
    to: &ToNurbsOptions,
) -> Result<NurbsConversion, ToNurbsError> {
    if options.scheme != Scheme::CatmullClark {
        return Err(ToNurbsError::NotCatmullClark {
            scheme: options.scheme,
        });
    }
    if mesh.face_count() == 0 {
        return Err(ToNurbsError::Empty);
    }
    // The measurement refines `samples` levels further, and a level one
    // further for the edge middles: neither may pass MAX_LEVEL. Beyond
    // level 2 only faces that are neither regular nor in a star make the
    // whole cage finer; stars are refined on their own (`local.rs`).
    let ceiling = MAX_LEVEL.saturating_sub(to.samples.max(1));
    let uniform_max = to.max_level.min(ceiling).min(UNIFORM_MAX_LEVEL);
    let mut level = first_level(mesh, creases).min(uniform_max);
    let mut previous: Option<NurbsConversion> = None;
    loop {
        let prepared = match Prepared::new(mesh, creases, options, level) {
            Ok(p) => p,
            // A level too large to refine: keep the last one that was not.
            Err(SubdivisionError::TooManyFaces { .. }) if previous.is_some() => {
                return Ok(previous.expect("checked"));
            }
            Err(e) => return Err(e.into()),
        };
        // The stars of extraordinary vertices are cut out with the rings
        // around them and refined on their own, as far as each needs (a star
        // whose cut-out is not manifold stays in the level). With many stars
        // (their cut-outs larger than the level) the whole level is first
        // converted and measured face by face, and only the stars that miss
        // the tolerance or the angle are cut out; with few, every star is
        // cut out and measured there, which spares measuring the level.
        let stars = if level >= 2 {
            local::stars(&prepared)
        } else {
            Vec::new()
        };
        let shown = prepared.all_shown();
        let cut_out_faces: usize = stars
            .iter()
            .map(|s| s.faces.len() * local::RINGS * local::RINGS)
            .sum();
        let measure_first = cut_out_faces > prepared.level().face_count();
        let convert = |keep: &[bool]| {
            convert_prepared(
                mesh,
                creases,
                options,
                &prepared,
                keep,
                to.samples,
                to.measure_exact,
            )
        };
        let everything = if measure_first || stars.is_empty() {
            Some(convert(&shown)?)
        } else {
            None
        };
        let misses = |star: &local::Star| {
            let Some((_, figures)) = &everything else {
                return true;
            };
            star.faces.iter().any(|&f| {
                figures.distance[f as usize] > to.tolerance
                    || figures.angle[f as usize] > to.max_angle_degrees
            })
        };
        let cuts: Vec<(local::Star, local::CutOut)> = stars
            .into_iter()
            .filter(misses)
            .filter_map(|star| {
                let cut = local::cut_out(&prepared, star.vertex, local::RINGS)?;
                Some((star, cut))
            })
            .collect();
        let mut conversion = match everything {
            Some((all, _)) if cuts.is_empty() => all,
            _ => {
                let mut keep = shown;
                for (star, _) in &cuts {
                    for &f in &star.faces {
                        keep[f as usize] = false;
                    }
                }
                convert(&keep)?.0
            }
        };
        let others_done = conversion.counts().1 == 0 || (level >= 2 && conversion.within(to));
        if !(others_done || level >= uniform_max) {
            previous = Some(conversion);
            level += 1;
            continue;
        }
        for (star, cut) in &cuts {
            let faces: Vec<u32> = (0..cut.level_faces.len() as u32)
                .filter(|&i| star.faces.contains(&cut.level_faces[i as usize]))
                .collect();
            let part = local::convert_star(
                cut,
                cut.vertices[&star.vertex],
                &faces,
                options,
                to,
                conversion.level,
            )?;
            conversion.report.merge(&part.report);
            conversion.deepest_level = conversion.deepest_level.max(part.deepest);
            conversion
                .patches
                .extend(cut.patches_of(&prepared, part.patches));
        }
        return Ok(conversion);
    }
}

/// The conversion at one refinement level, every patch measured at
/// `2^samples` intervals per face edge.
///
/// # Errors
/// As [`to_nurbs`].
pub fn convert_at(
    mesh: &HalfEdgeMesh,
    creases: &Creases,
    options: Options,
    level: u32,
    samples: u32,
) -> Result<NurbsConversion, ToNurbsError> {
    convert_with(mesh, creases, options, level, samples, true)
}

fn convert_with(
    mesh: &HalfEdgeMesh,
    creases: &Creases,
    options: Options,
    level: u32,
    samples: u32,
    exact: bool,
) -> Result<NurbsConversion, ToNurbsError> {
    let prepared = Prepared::new(mesh, creases, options, level)?;
    let keep = prepared.all_shown();
    Ok(convert_prepared(mesh, creases, options, &prepared, &keep, samples, exact)?.0)
}

/// A conversion level, refined, with its faces sorted out.
struct Prepared {
    /// The refinement to the level.
    pub refiner: Refiner,
    /// The level's points.
    pub points: Vec<DVec3>,
    /// Every vertex's class.
    pub classes: Vec<VertexClass>,
    /// Per face: not a hole (nor hidden by the boundary rule).
    pub shown: Vec<bool>,
    /// Per face: shown, every corner regular and its 4×4 grid full, so that
    /// its limit surface is the bicubic B-spline patch of that grid.
    pub regular: Vec<bool>,
    /// Limit positions one level down: at every edge's middle (child vertex
    /// `faces + e` is edge e's point).
    pub finer_limit: Vec<DVec3>,
}

impl Prepared {
    /// Refines `mesh` to `level` (at least 1 when a face is not a quad).
    pub fn new(
        mesh: &HalfEdgeMesh,
        creases: &Creases,
        options: Options,
        level: u32,
    ) -> Result<Prepared, SubdivisionError> {
        let quads = mesh.faces().all(|f| mesh.face_degree(f) == 4);
        let refiner = Refiner::new(mesh, creases, options, level.max(u32::from(!quads)))?;
        let points = refiner.refine(&refiner.cage_positions(mesh));
        let lv = refiner.levels.last().expect("cage level");
        let faces = lv.face_count();
        let classes = classify(lv);
        let shown: Vec<bool> = (0..faces).map(|f| !refiner.is_face_hidden(f)).collect();
        let face_vertex = |f: u32, i: usize| lv.face_vertices[lv.face_corners(f).start + i];
        let regular: Vec<bool> = (0..faces as u32)
            .map(|f| {
                shown[f as usize]
                    && (0..4).all(|i| classes[face_vertex(f, i) as usize].is_regular())
                    && full(&face_grid(lv, &classes, &points, f, 0)).is_some()
            })
            .collect();
        let finer = Refiner::new(mesh, creases, options, refiner.level_count() + 1)?;
        let finer_points = finer.refine(&finer.cage_positions(mesh));
        let finer_limit = limit_positions(&finer, &finer_points)?;
        Ok(Prepared {
            refiner,
            points,
            classes,
            shown,
            regular,
            finer_limit,
        })
    }

    /// The level the patches are made at.
    pub fn level(&self) -> &Level {
        self.refiner.levels.last().expect("cage level")
    }

    /// Every shown face.
    pub fn all_shown(&self) -> Vec<bool> {
        self.shown.clone()
    }
}

/// The patches of the faces `keep` (shown faces of the prepared level) and
/// the curves of every shown face's edges, measured; the other faces get
/// no placement.
fn convert_prepared(
    mesh: &HalfEdgeMesh,
    creases: &Creases,
    options: Options,
    prepared: &Prepared,
    keep: &[bool],
    samples: u32,
    exact: bool,
) -> Result<(NurbsConversion, measure::FaceFigures), ToNurbsError> {
    let mut conversion = build(prepared, keep, &prepared.finer_limit);
    let mut figures = measure::FaceFigures::default();
    if exact || conversion.counts().1 > 0 {
        (conversion.report, figures) =
            measure::measure_faces(mesh, creases, options, &conversion, samples, exact)?;
    } else {
        conversion.report.exact_measured = false;
    }
    Ok((conversion, figures))
}

/// The patches of the prepared level's faces `keep` (every face a quad).
fn build(prepared: &Prepared, keep: &[bool], finer_limit: &[DVec3]) -> NurbsConversion {
    let Prepared {
        refiner,
        points,
        classes,
        shown,
        regular,
        ..
    } = prepared;
    let (points, classes, shown) = (points.as_slice(), classes.as_slice(), shown.as_slice());
    let lv: &Level = prepared.level();
    let faces = lv.face_count();
    let limit = limit_positions(refiner, points).expect("an all-quad Catmull-Clark level");
    let normals = limit_normals(refiner, points).expect("an all-quad Catmull-Clark level");
    let kept = |f: usize| shown[f] && keep[f];
    let regular: Vec<bool> = (0..faces).map(|f| regular[f] && kept(f)).collect();
    let cage_face = |f: u32| refiner.cage.faces[lv.face_origin(f as usize) as usize];
    let mut patches = Vec::new();
    let mut placements = vec![None; faces];
    // Exact: packed rectangles of regular faces.
    for rect in pack::rectangles(lv, &regular) {
        let (w, h) = (rect[0].len(), rect.len());
        let mut big = vec![vec![None::<DVec3>; h + 3]; w + 3];
        let mut cage_faces = Vec::new();
        for (b, row) in rect.iter().enumerate() {
            for (a, &(f, rot)) in row.iter().enumerate() {
                let g = face_grid(lv, classes, points, f, rot);
                for (i, column) in g.iter().enumerate() {
                    for (j, p) in column.iter().enumerate() {
                        big[a + i][b + j].get_or_insert(p.expect("regular grids are full"));
                    }
                }
                placements[f as usize] = Some(FacePlacement {
                    patch: patches.len(),
                    offset: (a, b),
                    rot,
                });
                cage_faces.push(cage_face(f));
            }
        }
        let big: Vec<Vec<DVec3>> = big
            .into_iter()
            .map(|c| c.into_iter().map(|p| p.expect("filled")).collect())
            .collect();
        cage_faces.sort();
        cage_faces.dedup();
        patches.push(ConvertedPatch {
            surface: pack::clamped_surface(&big),
            kind: PatchKind::Exact,
            cage_faces,
        });
    }
    // Shared edge curves, each computed once from its first shown face.
    let mut edge_index: HashMap<u32, usize> = HashMap::new();
    let mut edges: Vec<SharedEdge> = Vec::new();
    let mut rows: Vec<Option<[[Option<DVec3>; 4]; 4]>> = vec![None; faces];
    let mut face_edges: Vec<Option<[(usize, bool); 4]>> = vec![None; faces];
    for f in 0..faces as u32 {
        if !shown[f as usize] {
            continue;
        }
        let g = face_grid(lv, classes, points, f, 0);
        let mut mine = [(0, true); 4];
        for (k, slot) in mine.iter_mut().enumerate() {
            let c = lv.face_corners(f).start + k;
            let e = lv.face_edges[c];
            let forward = lv.edge_vertices[e as usize][0] == lv.face_vertices[c];
            if let Some(&i) = edge_index.get(&e) {
                edges[i].faces.push(f);
                *slot = (i, forward);
                continue;
            }
            *slot = (edges.len(), forward);
            let (a, b) = (lv.face_vertices[c], lv.face_vertices[lv.next_corner(c)]);
            // The Bézier row along local edge k, from corner k to k + 1.
            let (pa, pb) = (limit[a as usize], limit[b as usize]);
            // A point the grid cannot give (no face across the edge: never
            // at level 1 and up, where every face is a quad) falls back to
            // the chord between the limit points.
            let curve: [DVec3; 4] = std::array::from_fn(|t| {
                let (i, j) = edge_point(k, t);
                bezier_point(&g, i, j).unwrap_or(pa + (pb - pa) * (t as f64 / 3.0))
            });
            let mut curve = curve;
            curve[0] = pa;
            curve[3] = pb;
            // Beside a smooth irregular end, the inner point is set so that
            // the curve passes through the exact limit point at the edge's
            // middle (the limit of its edge point one level down, child
            // vertex `faces + e`), then put into the end's tangent plane.
            let middle = finer_limit[faces + e as usize];
            for (end, inner, other) in [(a, 1, 2), (b, 2, 1)] {
                if let VertexClass::Irregular { smooth: true } = classes[end as usize] {
                    let n = normals[end as usize];
                    let p = limit[end as usize];
                    curve[inner] = (8.0 * middle - curve[0] - curve[3] - 3.0 * curve[other]) / 3.0;
                    curve[inner] -= n * (curve[inner] - p).dot(n);
                }
            }
            let [s, t] = lv.edge_vertices[e as usize];
            if [s, t] != [a, b] {
                curve.reverse();
            }
            edge_index.insert(e, edges.len());
            edges.push(SharedEdge {
                ends: [s, t],
                curve,
                faces: vec![f],
                sharp: is_infinite(lv.edge_sharp(e)),
            });
        }
        rows[f as usize] = Some(g);
        face_edges[f as usize] = Some(mine);
    }
    // Tangent continuity around smooth extraordinary vertices.
    let twists = star::smooth_stars(lv, classes, points, &rows, &limit, &mut edges, &edge_index);
    // Approximate: one Bézier patch per shown irregular face.
    for f in 0..faces as u32 {
        if !kept(f as usize) || regular[f as usize] {
            continue;
        }
        let g = rows[f as usize].expect("grid of a shown face");
        let mut net = [[DVec3::ZERO; 4]; 4];
        for (i, j) in [(1, 1), (1, 2), (2, 1), (2, 2)] {
            net[i][j] = bezier_point(&g, i, j).expect("inner points need only the face");
        }
        for k in 0..4 {
            let c = lv.face_corners(f).start + k;
            let e = lv.face_edges[c];
            let shared = &edges[edge_index[&e]];
            let forward = shared.ends[0] == lv.face_vertices[c];
            for t in 0..4 {
                let (i, j) = edge_point(k, t);
                net[i][j] = shared.curve[if forward { t } else { 3 - t }];
            }
        }
        for &((i, j), point) in twists.get(&f).into_iter().flatten() {
            net[i][j] = point;
        }
        let flat: Vec<DVec3> = net.iter().flatten().copied().collect();
        patches.push(ConvertedPatch {
            surface: NurbsSurface::from_bezier(4, 4, flat)
                .expect("a bicubic net of finite points is a valid surface"),
            kind: PatchKind::Approximate,
            cage_faces: vec![cage_face(f)],
        });
        placements[f as usize] = Some(FacePlacement {
            patch: patches.len() - 1,
            offset: (0, 0),
            rot: 0,
        });
    }
    NurbsConversion {
        level: refiner.level_count(),
        deepest_level: refiner.level_count(),
        patches,
        placements,
        edges,
        face_edges,
        report: measure::Report::default(),
    }
}

/// The Bézier net index of the `t`-th point along local edge `k` (from
/// corner `k` to corner `k + 1`).
fn edge_point(k: usize, t: usize) -> (usize, usize) {
    match k {
        0 => (t, 0),
        1 => (3, t),
        2 => (3 - t, 3),
        _ => (0, 3 - t),
    }
}

#[cfg(test)]
mod tests;
