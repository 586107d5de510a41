//! The one system that changes the document: it applies [`DocRequest`]s through the session.

use crate::*;
use std::collections::VecDeque;

/// The one system that changes the document. Opening and saving run on a
/// worker thread ([`FileJobs`]); their results are applied here when they
/// arrive, and requests that must follow them wait in order.
pub fn apply_requests(
    mut requests: MessageReader<DocRequest>,
    mut state: ResMut<DocState>,
    mut jobs: ResMut<FileJobs>,
    mut status: ResMut<StatusMessage>,
    mut changed: MessageWriter<DocChanged>,
) {
    let state = &mut *state;
    if let Some(done) = jobs.finished() {
        let result = finish_file_job(state, &mut status, done);
        report(state, &mut status, &mut changed, result);
    }
    // A finished Decimate build: its command runs first.
    let mut first = None;
    if jobs.decimation.as_ref().is_some_and(|j| j.is_finished()) {
        let job = jobs.decimation.take().expect("checked above");
        match job.finish() {
            Ok(request) => first = Some(request),
            Err(e) if e.contains("cancelled") => status.info(e),
            Err(e) => status.error(e),
        }
    }
    // Requests that waited for a job, then this frame's.
    let mut queue: VecDeque<DocRequest> = first.into_iter().collect();
    queue.extend(std::mem::take(&mut jobs.waiting));
    queue.extend(requests.read().cloned());
    while let Some(request) = queue.pop_front() {
        if jobs.must_wait(&request) {
            jobs.waiting.push_back(request);
            continue;
        }
        // A command that builds a big progressive record waits for a worker.
        if let Some(job) = crate::decimate_jobs::DecimateJob::start(&state.session.doc, &request) {
            jobs.decimation = Some(job);
            continue;
        }
        let result = apply(state, &mut jobs, &mut status, &request);
        report(state, &mut status, &mut changed, result);
    }
}

/// Counts a change and tells the followers, or shows the error.
fn report(
    state: &mut DocState,
    status: &mut StatusMessage,
    changed: &mut MessageWriter<DocChanged>,
    result: Result<Option<DocChanged>, String>,
) {
    match result {
        Ok(Some(c)) => {
            state.revision += 1;
            changed.write(c);
        }
        Ok(None) => {}
        Err(e) => status.error(e),
    }
}

/// Makes a loaded session (an opened file, a recovery point) the document,
/// belonging to `path`; its warnings go to the user.
fn adopt(
    state: &mut DocState,
    status: &mut StatusMessage,
    loaded: hedra_doc::file::Loaded,
    path: Option<PathBuf>,
) -> DocChanged {
    state.session = loaded.session;
    state.path = path;
    state.opened_serial = state.session.history.current_serial();
    status.warnings.extend(loaded.warnings);
    DocChanged {
        created: vec![],
        replaced: true,
    }
}

/// Applies the result of a finished open or save.
fn finish_file_job(
    state: &mut DocState,
    status: &mut StatusMessage,
    done: FinishedFile,
) -> Result<Option<DocChanged>, String> {
    match done {
        FinishedFile::Opened(path, false, Ok(loaded)) => {
            status.info(format!("Opened {}", path.display()));
            Ok(Some(adopt(state, status, loaded, Some(path))))
        }
        FinishedFile::Opened(path, true, Ok(loaded)) => {
            status.info(format!(
                "Opened the sample {} as a new scene: Save asks where to keep it",
                path.file_name().unwrap_or_default().to_string_lossy()
            ));
            Ok(Some(adopt(state, status, loaded, None)))
        }
        FinishedFile::Opened(_, _, Err(e)) => Err(e.to_string()),
        FinishedFile::Saved(path, serial, Ok(())) => {
            state.session.saved_serial = Some(serial);
            state.path = Some(path.clone());
            status.info(format!("Saved {}", path.display()));
            // The document is unchanged, but the title's `*` must go.
            Ok(Some(DocChanged::default()))
        }
        FinishedFile::Saved(_, _, Err(e)) => Err(format!("Save failed, nothing was lost: {e}")),
    }
}

/// Applies one request.
fn apply(
    state: &mut DocState,
    jobs: &mut FileJobs,
    status: &mut StatusMessage,
    request: &DocRequest,
) -> Result<Option<DocChanged>, String> {
    match request {
        DocRequest::Execute(cmd) => {
            state
                .session
                .execute(cmd)
                .map_err(|e| e.to_string())
                .map(|a| {
                    status.info(a.label.clone());
                    Some(DocChanged {
                        created: a.created,
                        replaced: false,
                    })
                })
        }
        DocRequest::AdjustLast(cmd) => state
            .session
            .adjust_last(cmd)
            .map_err(|e| e.to_string())
            .map(|a| {
                status.info(a.label.clone());
                Some(DocChanged {
                    created: a.created,
                    replaced: false,
                })
            }),
        DocRequest::Undo => Ok(match state.session.undo() {
            Some(label) => {
                status.info(format!("Undo {label}"));
                Some(DocChanged::default())
            }
            None => {
                status.info("Nothing to undo");
                None
            }
        }),
        DocRequest::Redo => Ok(match state.session.redo() {
            Some(label) => {
                status.info(format!("Redo {label}"));
                Some(DocChanged::default())
            }
            None => {
                status.info("Nothing to redo");
                None
            }
        }),
        DocRequest::JumpTo(n) => {
            state.session.jump_to(*n);
            Ok(Some(DocChanged::default()))
        }
        DocRequest::New => {
            state.session = Session::new();
            state.path = None;
            state.opened_serial = 0;
            status.info("New scene");
            Ok(Some(DocChanged {
                created: vec![],
                replaced: true,
            }))
        }
        DocRequest::Open(path) | DocRequest::OpenSample(path) => {
            jobs.start_open(path, matches!(request, DocRequest::OpenSample(_)));
            status.info(format!("Opening {}…", path.display()));
            Ok(None)
        }
        DocRequest::Recover(entry) => match hedra_doc::recovery::recover(entry) {
            Ok(loaded) => {
                let changed = adopt(state, status, loaded, entry.meta.original.clone());
                status.info(format!(
                    "Recovered {} — save to keep it",
                    state.display_name()
                ));
                Ok(Some(changed))
            }
            Err(e) => Err(format!("Recovery failed, the file was kept: {e}")),
        },
        DocRequest::HistoryLimits { steps, bytes } => {
            let history = &mut state.session.history;
            history.max_steps = (*steps).max(1);
            history.max_bytes = *bytes;
            let before = history.done().len();
            history.enforce_limits();
            if history.done().len() < before {
                Ok(Some(DocChanged::default()))
            } else {
                Ok(None)
            }
        }
        DocRequest::Import(path) => match hedra_doc::import::import_file(path) {
            Ok(meshes) => {
                let name = path.file_name().map_or_else(
                    || path.display().to_string(),
                    |n| n.to_string_lossy().into_owned(),
                );
                let a = state.session.import(&meshes, &format!("Import {name}"));
                status.info(format!(
                    "Imported {} object(s) from {name}",
                    a.created.len()
                ));
                // One summary naming the file, then its details.
                status.warnings.extend(
                    hedra_doc::import::describe_repairs(&meshes)
                        .into_iter()
                        .enumerate()
                        .map(|(i, n)| if i == 0 { format!("{name}: {n}") } else { n }),
                );
                Ok(Some(DocChanged {
                    created: a.created,
                    replaced: false,
                }))
            }
            Err(e) => Err(e.to_string()),
        },
        DocRequest::Save(path) => {
            jobs.start_save(&state.session, path);
            status.info(format!("Saving {}…", path.display()));
            Ok(None)
        }
    }
}
