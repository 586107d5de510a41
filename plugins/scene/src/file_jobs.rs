//! Opening and saving scene files on a worker thread, so a big file does
//! not stall the window: [`apply_requests`](crate::apply_requests) starts a
//! job and keeps drawing frames; the job's result is applied in a later
//! frame. While a file is being opened, every later request waits for it
//! (they belong to the opened document); while one is being saved, edits go
//! on (the file gets the document as it was when the save began) and only
//! other file requests wait.

use crate::*;
use hedra_doc::file::{FileError, Loaded};
use std::collections::VecDeque;
use std::sync::Mutex;
use std::sync::mpsc::{Receiver, TryRecvError, channel};

/// A worker's result once it has one (a worker that stopped without one
/// is an error naming the file); `block` waits for it.
fn receive<T>(
    done: &Mutex<Receiver<Result<T, FileError>>>,
    path: &std::path::Path,
    block: bool,
) -> Option<Result<T, FileError>> {
    let done = done.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    let r = if block {
        done.recv().map_err(|_| TryRecvError::Disconnected)
    } else {
        done.try_recv()
    };
    match r {
        Ok(r) => Some(r),
        Err(TryRecvError::Empty) => None,
        Err(TryRecvError::Disconnected) => Some(Err(worker_died(path))),
    }
}

/// A file being read or written on a worker thread.
pub(crate) enum FileJob {
    Open {
        path: PathBuf,
        /// A sample: the document it gives has no path.
        untitled: bool,
        done: Mutex<Receiver<Result<Loaded, FileError>>>,
    },
    Save {
        path: PathBuf,
        /// The history serial of the saved state.
        serial: u64,
        done: Mutex<Receiver<Result<(), FileError>>>,
    },
}

/// The running file job and the requests waiting for it. Written only by
/// `apply_requests`.
#[derive(Resource, Default)]
pub struct FileJobs {
    pub(crate) running: Option<FileJob>,
    /// A big Decimate build a command waits for ([`crate::decimate_jobs`]):
    /// later requests wait too, in order.
    pub(crate) decimation: Option<crate::decimate_jobs::DecimateJob>,
    pub(crate) waiting: VecDeque<DocRequest>,
}

impl FileJobs {
    /// True while a file is being opened or saved (or requests wait).
    pub fn busy(&self) -> bool {
        self.running.is_some() || self.decimation.is_some() || !self.waiting.is_empty()
    }

    /// A running Decimate build's label and fraction done (the status bar's
    /// progress bar; Esc cancels).
    pub fn progress(&self) -> Option<(String, f32)> {
        self.decimation.as_ref().map(|j| j.progress())
    }

    /// What the status bar shows while a job runs.
    pub fn describe(&self) -> Option<String> {
        match &self.running {
            Some(FileJob::Open { path, .. }) => Some(format!("Opening {}…", path.display())),
            Some(FileJob::Save { path, .. }) => Some(format!("Saving {}…", path.display())),
            None => None,
        }
    }

    /// Whether `request` must wait for the running job.
    pub(crate) fn must_wait(&self, request: &DocRequest) -> bool {
        if self.decimation.is_some() {
            return true;
        }
        match &self.running {
            None => !self.waiting.is_empty(),
            Some(FileJob::Open { .. }) => true,
            Some(FileJob::Save { .. }) => {
                !self.waiting.is_empty()
                    || matches!(
                        request,
                        DocRequest::Open(_)
                            | DocRequest::OpenSample(_)
                            | DocRequest::Save(_)
                            | DocRequest::New
                            | DocRequest::Recover(_)
                    )
            }
        }
    }

    /// Reads `path` on a worker thread (`untitled`: as a sample, whose
    /// document gets no path).
    pub(crate) fn start_open(&mut self, path: &std::path::Path, untitled: bool) {
        let (send, done) = channel();
        let owned = path.to_path_buf();
        std::thread::spawn(move || {
            let _ = send.send(file::load(&owned));
        });
        self.running = Some(FileJob::Open {
            path: path.to_path_buf(),
            untitled,
            done: Mutex::new(done),
        });
    }

    /// Writes `session` (a copy: edits go on meanwhile) to `path` on a
    /// worker thread, atomically.
    pub(crate) fn start_save(&mut self, session: &Session, path: &std::path::Path) {
        let (send, done) = channel();
        let snapshot = session.clone();
        let owned = path.to_path_buf();
        std::thread::spawn(move || {
            let _ = send.send(file::write_atomic(&owned, &file::to_string(&snapshot)));
        });
        self.running = Some(FileJob::Save {
            path: path.to_path_buf(),
            serial: session.history.current_serial(),
            done: Mutex::new(done),
        });
    }

    /// The running job's result, if it has finished.
    pub(crate) fn finished(&mut self) -> Option<FinishedFile> {
        let result = match self.running.as_ref()? {
            FileJob::Open {
                path,
                untitled,
                done,
            } => FinishedFile::Opened(path.clone(), *untitled, receive(done, path, false)?),
            FileJob::Save { path, serial, done } => {
                FinishedFile::Saved(path.clone(), *serial, receive(done, path, false)?)
            }
        };
        self.running = None;
        Some(result)
    }
}

/// A file job's outcome.
pub(crate) enum FinishedFile {
    /// The file read, whether it opens untitled (a sample), what was read.
    Opened(PathBuf, bool, Result<Loaded, FileError>),
    Saved(PathBuf, u64, Result<(), FileError>),
}

fn worker_died(path: &std::path::Path) -> FileError {
    FileError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::other("the worker thread stopped unexpectedly"),
    }
}

/// When the app exits, a save still being written is finished first, so
/// quitting right after Ctrl+S loses nothing (the file is complete on disk;
/// the app is closing, so nothing else needs to know).
pub fn finish_saves_on_exit(exits: MessageReader<AppExit>, jobs: Res<FileJobs>) {
    if let (false, Some(FileJob::Save { done, path, .. })) = (exits.is_empty(), &jobs.running) {
        let _ = receive(done, path, true);
    }
}
