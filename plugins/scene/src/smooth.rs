//! The smooth preview of meshes with a subdivision modifier, in the app:
//! each node's kept refinement ([`hedra_doc::smooth::SmoothRefinement`],
//! Bevy-free: stencils re-applied while only cage positions change,
//! normals, triangles), large refinements made on worker threads with a
//! progress bar, and the render meshes made from them.

use by_address::ByAddress;
use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::thread::JoinHandle;

use crate::buffers_mesh;
use bevy::prelude::*;
use hedra_doc::render::Rewritten;
use hedra_doc::smooth::{PreparedStencils, SmoothRefinement};
use hedra_doc::{NodeId, Shading, SubdivisionModifier};
use hedra_geom::HalfEdgeMesh;
use hedra_geom::subdivision::{Creases, Refiner};

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
    handle: JoinHandle<Result<(SmoothRefinement, Mesh), String>>,
}

/// Identity of a smooth preview's source.
#[derive(Clone, PartialEq)]
struct JobKey {
    /// The cage, held and compared by identity.
    cage: ByAddress<Arc<HalfEdgeMesh>>,
    creases: Creases,
    modifier: SubdivisionModifier,
    shading: Shading,
}

impl JobKey {
    fn of(src: &SmoothSource) -> JobKey {
        JobKey {
            cage: ByAddress(src.cage.clone()),
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
    done: HashMap<NodeId, SmoothRefinement>,
    /// Stencil tables being built on worker threads for the refinements in
    /// `done` (started when a refinement is made, so the first drag frame
    /// does not pay for them).
    stencils: HashMap<NodeId, JoinHandle<PreparedStencils>>,
    jobs: HashMap<NodeId, Job>,
    /// Sources the user cancelled: not started again until they change.
    cancelled: HashMap<NodeId, JobKey>,
    /// While set, background refinements wait between their steps (see
    /// [`hold_background`](Self::hold_background)).
    held: Arc<AtomicBool>,
}

/// What a smooth preview is made from.
pub struct SmoothSource<'a> {
    /// The mesh node the preview is for.
    pub node: NodeId,
    /// The cage that is subdivided (its `Arc` identity is part of the job's key).
    pub cage: &'a Arc<HalfEdgeMesh>,
    /// The creases the subdivision honours.
    pub creases: &'a Creases,
    /// The subdivision modifier (its viewport level is what is refined).
    pub modifier: &'a SubdivisionModifier,
    /// Flat or smooth normals for the resulting render mesh.
    pub shading: Shading,
}

impl SmoothPreviews {
    /// Makes this app's background refinements wait after each step while
    /// `hold` is set (they still stop at once when cancelled): a test can
    /// then press a key while one surely runs, however fast the machine.
    pub fn hold_background(&mut self, hold: bool) {
        self.held.store(hold, Ordering::Relaxed);
    }

    /// Forgets nodes that no longer have a smooth preview.
    pub fn retain(&mut self, keep: impl Fn(NodeId) -> bool) {
        self.done.retain(|n, _| keep(*n));
        self.stencils.retain(|n, _| keep(*n));
        self.cancelled.retain(|n, _| keep(*n));
        for (_, job) in self.jobs.extract_if(|n, _| !keep(*n)) {
            job.cancel.store(true, Ordering::Relaxed);
        }
    }

    /// True when `node`'s stencils are built (installed, or finished on
    /// their worker and installed on the next frame that draws it).
    pub fn stencils_ready(&self, node: NodeId) -> bool {
        self.done.get(&node).is_some_and(|r| r.has_stencils())
            || self.stencils.get(&node).is_some_and(|j| j.is_finished())
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
        let (done, stop, held) = (steps_done.clone(), cancel.clone(), self.held.clone());
        let handle = std::thread::spawn(move || {
            let mut go_on = |_| {
                done.fetch_add(1, Ordering::Relaxed);
                while held.load(Ordering::Relaxed) && !stop.load(Ordering::Relaxed) {
                    std::thread::sleep(std::time::Duration::from_millis(1));
                }
                !stop.load(Ordering::Relaxed)
            };
            let refiner =
                Refiner::new_cancellable(&cage, &creases, modifier.options, levels, &mut go_on)
                    .map_err(|e| e.to_string())?;
            let points = refiner
                .refine_cancellable(&refiner.cage_positions(&cage), true, &mut go_on)
                .ok_or_else(|| "cancelled".to_string())?;
            let mesh = buffers_mesh(hedra_doc::smooth::refined_buffers(
                &refiner, &points, shading,
            ));
            Ok((
                SmoothRefinement::from_refiner(&cage, &creases, &modifier, refiner),
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
                    self.keep(node, refinement);
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
    /// connectivity, creases or options changed.
    ///
    /// # Errors
    /// The subdivision's message (Loop on quads, too many faces).
    fn points(&mut self, src: &SmoothSource) -> Result<Vec<hedra_geom::DVec3>, String> {
        let reuse = self
            .done
            .get(&src.node)
            .is_some_and(|r| r.fits(src.cage, src.creases, src.modifier));
        if !reuse {
            let r = SmoothRefinement::new(src.cage, src.creases, src.modifier)?;
            self.keep(src.node, r);
        }
        let building = self.install_stencils(src.node);
        let r = self.done.get_mut(&src.node).expect("inserted above");
        Ok(r.points_with(src.cage, !building))
    }

    /// Installs `node`'s stencils when their worker has finished; true
    /// while they are still being built (a drag frame then refines through
    /// the masks).
    fn install_stencils(&mut self, node: NodeId) -> bool {
        match self.stencils.remove(&node) {
            Some(job) if job.is_finished() => {
                if let (Ok(prepared), Some(r)) = (job.join(), self.done.get_mut(&node)) {
                    r.set_stencils(prepared);
                }
                false
            }
            Some(job) => {
                self.stencils.insert(node, job);
                true
            }
            None => false,
        }
    }

    /// Keeps a new refinement of `node` and starts building its stencils on
    /// a worker thread (issue 16: no hitch when a drag starts).
    fn keep(&mut self, node: NodeId, refinement: SmoothRefinement) {
        match refinement.stencil_job() {
            Some(job) => {
                self.stencils.insert(node, std::thread::spawn(job));
            }
            None => {
                self.stencils.remove(&node);
            }
        }
        self.done.insert(node, refinement);
    }

    /// A triangle render mesh of the smooth shape.
    ///
    /// # Errors
    /// The subdivision's message; show the cage then.
    pub fn render_mesh(&mut self, src: &SmoothSource) -> Result<Mesh, String> {
        let points = self.points(src)?;
        Ok(buffers_mesh(
            self.done[&src.node].buffers(&points, src.shading),
        ))
    }

    /// Rewrites positions and normals of a render mesh made by
    /// [`render_mesh`](Self::render_mesh) when only cage positions changed
    /// (stencils re-applied, no triangles rebuilt): which positions it
    /// rewrote, or `None`, changing nothing, when it has to be rebuilt.
    pub fn update_positions(&mut self, render: &mut Mesh, src: &SmoothSource) -> Option<Rewritten> {
        let fits = self
            .done
            .get(&src.node)
            .is_some_and(|r| r.fits(src.cage, src.creases, src.modifier));
        if !fits {
            return None;
        }
        let building = self.install_stencils(src.node);
        // The render mesh's own buffers are refilled (no new 100 MB
        // allocation in every frame of a drag), only where the cage moved
        // when the refinement can tell.
        use bevy::mesh::VertexAttributeValues::Float32x3;
        let (Some(Float32x3(mut positions)), Some(Float32x3(mut normals))) = (
            render.remove_attribute(Mesh::ATTRIBUTE_POSITION),
            render.remove_attribute(Mesh::ATTRIBUTE_NORMAL),
        ) else {
            // Not the layout `render_mesh` makes: rebuilt by the caller.
            return None;
        };
        let count = positions.len();
        let r = self.done.get_mut(&src.node).expect("fits");
        let written = r.update_attributes(
            src.cage,
            !building,
            src.shading,
            &mut positions,
            &mut normals,
        );
        let fits = positions.len() == count;
        render.insert_attribute(Mesh::ATTRIBUTE_POSITION, positions);
        render.insert_attribute(Mesh::ATTRIBUTE_NORMAL, normals);
        fits.then_some(written)
    }
}
