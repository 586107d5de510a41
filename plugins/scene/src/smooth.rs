//! The smooth preview of meshes with a subdivision modifier. The refinement
//! of each node's cage is kept (libigl's "build S once"): while only cage
//! positions change, as during a drag, the preview re-applies the stored
//! stencils and rewrites positions and normals, without rebuilding
//! connectivity or triangles.

use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::thread::JoinHandle;

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use hedra_doc::{NodeId, Shading, SubdivisionModifier};
use hedra_geom::subdivision::{Creases, Refiner, StencilEvaluation, StencilTable, limit_normals};
use hedra_geom::{DVec3, HalfEdgeMesh};

/// Above this many refined faces a drag refines positions through the
/// masks each frame instead of keeping stencils (whose weights would take
/// hundreds of megabytes).
const STENCIL_FACE_LIMIT: usize = 400_000;

/// The refinement of one node's cage.
struct Refinement {
    cage: Arc<HalfEdgeMesh>,
    creases: Creases,
    modifier: SubdivisionModifier,
    refiner: Refiner,
    /// Made on the first drag: the weights and every level's points, so a
    /// drag recomputes only what the moved vertices influence.
    stencils: Option<(StencilTable, StencilEvaluation)>,
}

impl Refinement {
    /// True when `cage` differs from the refined cage at most in positions.
    fn fits(&self, cage: &HalfEdgeMesh, creases: &Creases, modifier: &SubdivisionModifier) -> bool {
        self.modifier.options == modifier.options
            && self.modifier.viewport_level == modifier.viewport_level
            && self.creases == *creases
            && (std::ptr::eq(&*self.cage, cage) || self.cage.same_connectivity(cage))
    }
}

/// Smooth previews of more faces than this are refined on a worker thread,
/// with a progress bar, so the window never freezes.
pub const BACKGROUND_FACES: usize = 150_000;

/// A smooth preview being refined on a worker thread.
struct Job {
    /// What it was started for; a finished job whose source changed since is dropped.
    key: JobKey,
    label: String,
    steps_done: Arc<AtomicU32>,
    steps: u32,
    cancel: Arc<AtomicBool>,
    handle: JoinHandle<Result<(Refinement, Mesh), String>>,
}

/// Identity of a smooth preview's source.
#[derive(Clone, Debug, PartialEq)]
struct JobKey {
    cage: usize,
    creases: Creases,
    modifier: SubdivisionModifier,
    shading: Shading,
}

impl JobKey {
    fn of(src: &SmoothSource) -> JobKey {
        JobKey {
            cage: Arc::as_ptr(src.cage) as usize,
            creases: src.creases.clone(),
            modifier: *src.modifier,
            shading: src.shading,
        }
    }
}

/// A finished background refinement, ready to show.
pub struct FinishedJob {
    pub node: NodeId,
    /// The render mesh, or why there is none (cancelled, too large).
    pub result: Result<Mesh, String>,
}

/// Refinements by node, reused while the cage's connectivity stays, and
/// the ones still being made on worker threads.
#[derive(Resource, Default)]
pub struct SmoothPreviews {
    done: HashMap<NodeId, Refinement>,
    jobs: HashMap<NodeId, Job>,
    /// Sources the user cancelled: not started again until they change.
    cancelled: HashMap<NodeId, JobKey>,
}

/// What a smooth preview is made from.
pub struct SmoothSource<'a> {
    pub node: NodeId,
    pub cage: &'a Arc<HalfEdgeMesh>,
    pub creases: &'a Creases,
    pub modifier: &'a SubdivisionModifier,
    pub shading: Shading,
}

impl SmoothPreviews {
    /// Forgets nodes that no longer have a smooth preview.
    pub fn retain(&mut self, keep: impl Fn(NodeId) -> bool) {
        self.done.retain(|n, _| keep(*n));
        self.cancelled.retain(|n, _| keep(*n));
        for (_, job) in self.jobs.extract_if(|n, _| !keep(*n)) {
            job.cancel.store(true, Ordering::Relaxed);
        }
    }

    /// The background refinements running: a label and the fraction done.
    pub fn progress(&self) -> Vec<(String, f32)> {
        self.jobs
            .values()
            .map(|j| {
                let done = j.steps_done.load(Ordering::Relaxed) as f32;
                (j.label.clone(), (done / j.steps.max(1) as f32).min(1.0))
            })
            .collect()
    }

    /// Asks every background refinement to stop.
    pub fn cancel_all(&mut self) {
        for job in self.jobs.values() {
            job.cancel.store(true, Ordering::Relaxed);
        }
    }

    /// True when `src` should be refined on a worker thread: it is large
    /// and no kept refinement fits it.
    pub fn needs_background(&self, src: &SmoothSource) -> bool {
        let fits = self
            .done
            .get(&src.node)
            .is_some_and(|r| r.fits(src.cage, src.creases, src.modifier));
        !fits
            && hedra_geom::subdivision::face_count_after(
                src.cage,
                src.modifier.options.scheme,
                src.modifier.viewport_level,
            ) > BACKGROUND_FACES
    }

    /// Starts refining `src` on a worker thread, unless the same job runs
    /// already or the user cancelled it. `name` labels the progress bar.
    pub fn start_background(&mut self, src: &SmoothSource, name: &str) {
        let key = JobKey::of(src);
        if self.jobs.get(&src.node).is_some_and(|j| j.key == key)
            || self.cancelled.get(&src.node) == Some(&key)
        {
            return;
        }
        if let Some(old) = self.jobs.remove(&src.node) {
            old.cancel.store(true, Ordering::Relaxed);
        }
        let levels = src.modifier.viewport_level;
        let steps_done = Arc::new(AtomicU32::new(0));
        let cancel = Arc::new(AtomicBool::new(false));
        let (cage, creases, modifier, shading) = (
            src.cage.clone(),
            src.creases.clone(),
            *src.modifier,
            src.shading,
        );
        let (done, stop) = (steps_done.clone(), cancel.clone());
        let handle = std::thread::spawn(move || {
            let mut go_on = |_| {
                done.fetch_add(1, Ordering::Relaxed);
                !stop.load(Ordering::Relaxed)
            };
            let refiner =
                Refiner::new_cancellable(&cage, &creases, modifier.options, levels, &mut go_on)
                    .map_err(|e| e.to_string())?;
            let points = refiner
                .refine_cancellable(&refiner.cage_positions(&cage), true, &mut go_on)
                .ok_or_else(|| "cancelled".to_string())?;
            let mesh = build(&refiner, &points, shading);
            Ok((
                Refinement {
                    cage,
                    creases,
                    modifier,
                    refiner,
                    stencils: None,
                },
                mesh,
            ))
        });
        self.jobs.insert(
            src.node,
            Job {
                key,
                label: format!("Subdividing '{name}' to level {levels}"),
                steps_done,
                steps: 2 * levels,
                cancel,
                handle,
            },
        );
    }

    /// Collects the background refinements that finished since the last call.
    pub fn finished(&mut self) -> Vec<FinishedJob> {
        let ready: Vec<NodeId> = self
            .jobs
            .iter()
            .filter(|(_, j)| j.handle.is_finished())
            .map(|(n, _)| *n)
            .collect();
        let mut out = Vec::new();
        for node in ready {
            let job = self.jobs.remove(&node).expect("listed above");
            let cancelled = job.cancel.load(Ordering::Relaxed);
            let result = match job.handle.join() {
                Ok(Ok((refinement, mesh))) => {
                    self.done.insert(node, refinement);
                    Ok(mesh)
                }
                Ok(Err(e)) => Err(e),
                Err(_) => Err("the subdivision worker failed".to_string()),
            };
            if cancelled {
                self.cancelled.insert(node, job.key);
            }
            out.push(FinishedJob { node, result });
        }
        out
    }

    /// The refined positions for `src`, refining anew only when the
    /// connectivity, creases or options changed. Returns whether the
    /// refinement was reused.
    ///
    /// # Errors
    /// The subdivision's message (Loop on quads, too many faces).
    fn points(&mut self, src: &SmoothSource) -> Result<(Vec<DVec3>, bool), String> {
        let reuse = self
            .done
            .get(&src.node)
            .is_some_and(|r| r.fits(src.cage, src.creases, src.modifier));
        if !reuse {
            let refiner = Refiner::new(
                src.cage,
                src.creases,
                src.modifier.options,
                src.modifier.viewport_level,
            )
            .map_err(|e| e.to_string())?;
            self.done.insert(
                src.node,
                Refinement {
                    cage: src.cage.clone(),
                    creases: src.creases.clone(),
                    modifier: *src.modifier,
                    refiner,
                    stencils: None,
                },
            );
        }
        let r = self.done.get_mut(&src.node).expect("inserted above");
        r.cage = src.cage.clone();
        let cage_points = r.refiner.cage_positions(src.cage);
        if !reuse || r.refiner.face_count() > STENCIL_FACE_LIMIT {
            return Ok((r.refiner.refine(&cage_points), reuse));
        }
        let (table, eval) = r.stencils.get_or_insert_with(|| {
            let table = r.refiner.stencils();
            let eval = table.evaluate(&cage_points);
            (table, eval)
        });
        let moved: Vec<(u32, DVec3)> = cage_points
            .iter()
            .zip(eval.cage())
            .enumerate()
            .filter(|(_, (new, old))| new != old)
            .map(|(i, (new, _))| (i as u32, *new))
            .collect();
        if !moved.is_empty() {
            table.update(eval, &moved);
        }
        Ok((eval.points().to_vec(), reuse))
    }

    /// A triangle render mesh of the smooth shape.
    ///
    /// # Errors
    /// The subdivision's message; show the cage then.
    pub fn render_mesh(&mut self, src: &SmoothSource) -> Result<Mesh, String> {
        let (points, _) = self.points(src)?;
        let r = &self.done[&src.node];
        Ok(build(&r.refiner, &points, src.shading))
    }

    /// Rewrites positions and normals of a render mesh made by
    /// [`render_mesh`](Self::render_mesh) when only cage positions changed
    /// (stencils re-applied, no triangles rebuilt). Returns false, changing
    /// nothing, when it has to be rebuilt.
    pub fn update_positions(&mut self, render: &mut Mesh, src: &SmoothSource) -> bool {
        let fits = self
            .done
            .get(&src.node)
            .is_some_and(|r| r.fits(src.cage, src.creases, src.modifier));
        if !fits {
            return false;
        }
        let Ok((points, _)) = self.points(src) else {
            return false;
        };
        let r = &self.done[&src.node];
        let (positions, normals) = attributes(&r.refiner, &points, src.shading);
        let count = render
            .attribute(Mesh::ATTRIBUTE_POSITION)
            .map_or(0, |a| a.len());
        if count != positions.len() {
            return false;
        }
        render.insert_attribute(Mesh::ATTRIBUTE_POSITION, positions);
        render.insert_attribute(Mesh::ATTRIBUTE_NORMAL, normals);
        true
    }
}

/// Render positions and normals: shared vertices with limit normals when
/// smooth (area-weighted normals for schemes without a limit evaluation),
/// face corners with the face normal when flat.
fn attributes(
    refiner: &Refiner,
    points: &[DVec3],
    shading: Shading,
) -> (Vec<[f32; 3]>, Vec<[f32; 3]>) {
    let f32s = |p: &DVec3| p.as_vec3().to_array();
    match shading {
        Shading::Smooth => {
            let normals =
                limit_normals(refiner, points).unwrap_or_else(|_| area_normals(refiner, points));
            (
                points.iter().map(f32s).collect(),
                normals.iter().map(f32s).collect(),
            )
        }
        Shading::Flat => {
            let mut positions = Vec::new();
            let mut normals = Vec::new();
            for face in refiner.faces() {
                let n = newell_normal(face, points).as_vec3().to_array();
                for &v in face {
                    positions.push(f32s(&points[v as usize]));
                    normals.push(n);
                }
            }
            (positions, normals)
        }
    }
}

/// Newell's normal of a polygon (unit, or zero when degenerate).
fn newell_normal(face: &[u32], points: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for (i, &a) in face.iter().enumerate() {
        let b = face[(i + 1) % face.len()];
        n += points[a as usize].cross(points[b as usize]);
    }
    n.normalize_or_zero()
}

fn area_normals(refiner: &Refiner, points: &[DVec3]) -> Vec<DVec3> {
    let mut normals = vec![DVec3::ZERO; points.len()];
    for face in refiner.faces() {
        let mut n = DVec3::ZERO;
        for (i, &a) in face.iter().enumerate() {
            let b = face[(i + 1) % face.len()];
            n += points[a as usize].cross(points[b as usize]);
        }
        for &v in face {
            normals[v as usize] += n;
        }
    }
    normals.iter().map(|n| n.normalize_or_zero()).collect()
}

fn build(refiner: &Refiner, points: &[DVec3], shading: Shading) -> Mesh {
    let (positions, normals) = attributes(refiner, points, shading);
    let mut indices = Vec::new();
    let mut corner = 0u32;
    for face in refiner.faces() {
        // Refined faces are small and convex: a fan.
        for i in 1..face.len().saturating_sub(1) {
            let tri = [0, i, i + 1];
            match shading {
                Shading::Smooth => indices.extend(tri.map(|k| face[k])),
                Shading::Flat => indices.extend(tri.map(|k| corner + k as u32)),
            }
        }
        corner += face.len() as u32;
    }
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::MAIN_WORLD | RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
    .with_inserted_indices(Indices::U32(indices))
}
