//! A Decimate modifier's progressive record built on a worker thread when
//! it is big (issue 18): before a command runs, a dry run of it tells which
//! records it would build ([`hedra_doc::modifiers::decimations_needed`]);
//! when they simplify more than [`BACKGROUND_DECIMATE_FACES`] faces they are
//! built on a worker with a progress bar (Esc cancels: nothing changes),
//! kept ([`hedra_doc::modifiers::prebuild`]), and the command then runs at
//! once, finding them. Requests made meanwhile wait, in order.

use crate::*;
use hedra_doc::modifiers::{PendingDecimation, decimations_needed, prebuild};
use hedra_geom::progressive::{DecimateError, ProgressiveMesh};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::thread::JoinHandle;

/// Above this many faces to simplify, a command's Decimate build runs on a
/// worker thread (about a tenth of a second of work).
pub const BACKGROUND_DECIMATE_FACES: usize = 50_000;

/// Parts of the progress counter per unit.
const PROGRESS_STEPS: f64 = 10_000.0;

/// Records built by a worker, by key.
type Built = Result<Vec<(u64, ProgressiveMesh)>, DecimateError>;

/// The running build and the request that waits for it.
pub(crate) struct DecimateJob {
    pub(crate) request: DocRequest,
    label: String,
    progress: Arc<AtomicU32>,
    cancel: Arc<AtomicBool>,
    handle: JoinHandle<Built>,
}

impl DecimateJob {
    /// Starts the builds `request` needs on a worker thread, when they are
    /// big enough to be worth it; `None` runs the request at once.
    pub(crate) fn start(doc: &hedra_doc::Document, request: &DocRequest) -> Option<DecimateJob> {
        let DocRequest::Execute(cmd) = request else {
            return None;
        };
        if !may_decimate(doc, cmd) {
            return None;
        }
        let needed: Vec<PendingDecimation> = decimations_needed(|| doc.decide(cmd, 0));
        let faces: usize = needed.iter().map(|p| p.job.mesh.face_count()).sum();
        if faces <= BACKGROUND_DECIMATE_FACES {
            return None;
        }
        let progress = Arc::new(AtomicU32::new(0));
        let cancel = Arc::new(AtomicBool::new(false));
        let (done, stop) = (progress.clone(), cancel.clone());
        let handle = std::thread::spawn(move || {
            let total = needed.len() as f64;
            let mut built = Vec::with_capacity(needed.len());
            for (k, p) in needed.into_iter().enumerate() {
                let report = |f: f64| {
                    let whole = (k as f64 + f) / total;
                    done.store((whole * PROGRESS_STEPS) as u32, Ordering::Relaxed);
                };
                built.push((p.key, p.job.run(report, &stop)?));
            }
            Ok(built)
        });
        Some(DecimateJob {
            request: request.clone(),
            label: format!("Decimating {faces} faces"),
            progress,
            cancel,
            handle,
        })
    }

    /// The label and fraction done, for the status bar.
    pub(crate) fn progress(&self) -> (String, f32) {
        let f = self.progress.load(Ordering::Relaxed) as f64 / PROGRESS_STEPS;
        (self.label.clone(), f as f32)
    }

    pub(crate) fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// The request to run now that its records are kept, or why not.
    pub(crate) fn finish(self) -> Result<DocRequest, String> {
        match self.handle.join() {
            Ok(Ok(built)) => {
                for (key, pm) in built {
                    prebuild(key, pm);
                }
                Ok(self.request)
            }
            Ok(Err(DecimateError::Cancelled)) => {
                Err("Decimate cancelled: nothing changed".to_string())
            }
            Ok(Err(e)) => Err(format!("Decimate: {e}")),
            Err(_) => Err("Decimate: the worker thread stopped unexpectedly".to_string()),
        }
    }

    pub(crate) fn is_finished(&self) -> bool {
        self.handle.is_finished()
    }
}

/// True when `cmd` may build a progressive record: it sets a Decimate
/// modifier or decimates, or a mesh has one (an edit of it rebuilds the
/// record). Other commands are not dry-run first.
fn may_decimate(doc: &hedra_doc::Document, cmd: &hedra_doc::Command) -> bool {
    use hedra_doc::{Command, MeshModifier};
    matches!(
        cmd,
        Command::AddModifier {
            modifier: MeshModifier::Decimate(_),
            ..
        } | Command::SetModifier {
            modifier: MeshModifier::Decimate(_),
            ..
        } | Command::Decimate { .. }
    ) || doc
        .nodes()
        .any(|n| matches!(&n.content, NodeContent::Mesh(c) if c.has_decimate()))
}

/// Esc cancels the work that runs in the background for the document: a
/// Decimate build and smooth previews being refined (the frame shows the
/// cage meanwhile). Read in `SceneSystems::Tools`, with the other keys.
pub fn escape_cancels_background_jobs(
    keys: Option<Res<ButtonInput<KeyCode>>>,
    jobs: Res<FileJobs>,
    mut smooth: ResMut<crate::SmoothPreviews>,
) {
    if !keys.is_some_and(|k| k.just_pressed(KeyCode::Escape)) {
        return;
    }
    if let Some(job) = &jobs.decimation {
        job.cancel();
    }
    if !smooth.progress().is_empty() {
        smooth.cancel_all();
    }
}
