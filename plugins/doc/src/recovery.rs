//! Never lose work: autosaves and emergency saves in a recovery folder, and
//! what the next start offers to recover.
//!
//! Each recovery point is an ordinary scene file with its undo history,
//! `<key>.<kind>.hedra.ron`, and a small `<key>.<kind>.meta.ron` beside it
//! saying which document it belongs to, when and by which process it was
//! written. The key is the document's file stem and a hash of its absolute
//! path (`chair-3f2a…`), or `untitled-<pid>-<start time>` before the first
//! save. Both files are written atomically, the scene first, so a meta file
//! always describes a complete scene.
//!
//! A recovery point is offered on start when no running Hedra owns it and it
//! is newer than the file it belongs to (or that file is gone, or it never
//! had one); points older than their file are stale and removed.

use crate::file::{self, FileError, Loaded};
use crate::session::Session;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{SystemTime, UNIX_EPOCH};

/// Hedra's configuration folder: `$HEDRA_CONFIG_DIR`, else
/// `$XDG_CONFIG_HOME/hedra`, else `~/.config/hedra`.
pub fn config_dir() -> Option<PathBuf> {
    if let Some(d) = std::env::var_os("HEDRA_CONFIG_DIR") {
        return Some(PathBuf::from(d));
    }
    if let Some(d) = std::env::var_os("XDG_CONFIG_HOME") {
        return Some(PathBuf::from(d).join("hedra"));
    }
    std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".config/hedra"))
}

/// The recovery folder inside [`config_dir`].
pub fn default_dir() -> Option<PathBuf> {
    config_dir().map(|d| d.join("recovery"))
}

/// Why a recovery point was written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum RecoveryKind {
    /// The periodic save of unsaved changes.
    Autosave,
    /// Written when the app went down (panic or render error).
    Emergency,
    /// Written when the app was asked to stop by a signal (a logout,
    /// `kill`, Ctrl+C in its terminal) with unsaved work.
    Stopped,
}

/// The exit code of an app stopped by a signal with unsaved work (128 +
/// SIGTERM, as shells report it): the exit that writes a
/// [`RecoveryKind::Stopped`] point rather than an emergency one.
pub const STOPPED_EXIT_CODE: u8 = 143;

impl RecoveryKind {
    fn tag(self) -> &'static str {
        match self {
            RecoveryKind::Autosave => "autosave",
            RecoveryKind::Emergency => "emergency",
            RecoveryKind::Stopped => "stopped",
        }
    }
}

/// What the meta file beside a recovery scene says.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RecoveryMeta {
    /// The document's own file (`None`: never saved).
    pub original: Option<PathBuf>,
    /// Why the recovery point was written.
    pub kind: RecoveryKind,
    /// When it was written, milliseconds since the Unix epoch.
    pub saved_unix_ms: u64,
    /// The process that wrote it.
    pub pid: u32,
    /// Undo steps in the saved history.
    pub steps: usize,
    /// Label of the last step, to help the user recognise the work.
    pub last_step: Option<String>,
}

/// A recovery point found in the folder.
#[derive(Clone, Debug, PartialEq)]
pub struct RecoveryEntry {
    /// The recovery scene file.
    pub scene: PathBuf,
    /// The meta file beside it.
    pub meta_path: PathBuf,
    /// What the meta file says.
    pub meta: RecoveryMeta,
}

impl RecoveryEntry {
    /// One line for the recovery dialog: file, kind, age, last step.
    pub fn describe(&self, now_unix_ms: u64) -> String {
        let name = self.meta.original.as_ref().map_or_else(
            || "an untitled scene".to_string(),
            |p| p.display().to_string(),
        );
        let age = now_unix_ms.saturating_sub(self.meta.saved_unix_ms) / 1000;
        let age = match age {
            0..60 => format!("{age} s ago"),
            60..3600 => format!("{} min ago", age / 60),
            3600..86400 => format!("{} h ago", age / 3600),
            _ => format!("{} days ago", age / 86400),
        };
        let why = match self.meta.kind {
            RecoveryKind::Autosave => "autosaved",
            RecoveryKind::Emergency => "saved when Hedra crashed",
            RecoveryKind::Stopped => "saved when Hedra was stopped (a logout or kill)",
        };
        let last = self
            .meta
            .last_step
            .as_ref()
            .map_or(String::new(), |l| format!(", last step: {l}"));
        format!("{name} — {why} {age}, {} undo steps{last}", self.meta.steps)
    }
}

/// Milliseconds since the Unix epoch.
pub fn now_unix_ms() -> u64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_millis() as u64)
}

/// Where one running document's recovery points go.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RecoveryPoint {
    dir: PathBuf,
    key: String,
    original: Option<PathBuf>,
}

impl RecoveryPoint {
    /// The recovery point of a document saved at `original` (or untitled).
    pub fn new(dir: &Path, original: Option<&Path>) -> Self {
        let original = original.map(absolute);
        let key = match &original {
            Some(p) => {
                let stem: String = p
                    .file_name()
                    .map(|n| {
                        n.to_string_lossy()
                            .trim_end_matches(".hedra.ron")
                            .to_string()
                    })
                    .unwrap_or_default()
                    .chars()
                    .map(|c| {
                        if c.is_alphanumeric() || c == '-' || c == '_' {
                            c
                        } else {
                            '_'
                        }
                    })
                    .take(40)
                    .collect();
                format!("{stem}-{:016x}", fnv1a(p.to_string_lossy().as_bytes()))
            }
            None => format!("untitled-{}-{}", std::process::id(), now_unix_ms()),
        };
        RecoveryPoint {
            dir: dir.to_path_buf(),
            key,
            original,
        }
    }

    /// The document's own file (`None`: never saved).
    pub fn original(&self) -> Option<&Path> {
        self.original.as_deref()
    }

    /// The scene and meta paths of a kind.
    pub fn paths(&self, kind: RecoveryKind) -> (PathBuf, PathBuf) {
        let base = format!("{}.{}", self.key, kind.tag());
        (
            self.dir.join(format!("{base}.{}", file::EXTENSION)),
            self.dir.join(format!("{base}.meta.ron")),
        )
    }

    /// Writes `session` (with its history) as a recovery point; returns the
    /// scene path.
    ///
    /// # Errors
    /// [`FileError::Io`] naming the folder or file.
    pub fn write(&self, session: &Session, kind: RecoveryKind) -> Result<PathBuf, FileError> {
        std::fs::create_dir_all(&self.dir).map_err(|source| FileError::Io {
            path: self.dir.clone(),
            source,
        })?;
        let (scene, meta_path) = self.paths(kind);
        file::write_atomic_without_backup(&scene, file::to_string(session).as_bytes())?;
        let meta = RecoveryMeta {
            original: self.original.clone(),
            kind,
            saved_unix_ms: now_unix_ms(),
            pid: std::process::id(),
            steps: session.history.done().len(),
            last_step: session.history.done().last().map(|t| t.label.clone()),
        };
        let text = ron::ser::to_string_pretty(&meta, ron::ser::PrettyConfig::default())
            .expect("recovery meta serializes");
        file::write_atomic_without_backup(&meta_path, text.as_bytes())?;
        Ok(scene)
    }

    /// Removes this document's recovery points (after a save, or when the
    /// user discards the changes).
    pub fn remove(&self) {
        for kind in [
            RecoveryKind::Autosave,
            RecoveryKind::Emergency,
            RecoveryKind::Stopped,
        ] {
            let (scene, meta) = self.paths(kind);
            let _ = std::fs::remove_file(meta);
            let _ = std::fs::remove_file(scene);
        }
    }
}

/// The recovery points in `dir` worth offering, newest first: not owned by a
/// running Hedra, newer than the file they belong to. Stale points (their
/// file was saved later) are deleted.
pub fn pending(dir: &Path) -> Vec<RecoveryEntry> {
    pending_with(dir, &hedra_is_running)
}

/// [`pending`] with the test for "this process is a running Hedra" given.
pub fn pending_with(dir: &Path, is_running: &dyn Fn(u32) -> bool) -> Vec<RecoveryEntry> {
    let Ok(read) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for entry in read.flatten() {
        let meta_path = entry.path();
        let Some(name) = meta_path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
        else {
            continue;
        };
        let Some(base) = name.strip_suffix(".meta.ron") else {
            continue;
        };
        let scene = dir.join(format!("{base}.{}", file::EXTENSION));
        let Some(meta) = std::fs::read_to_string(&meta_path)
            .ok()
            .and_then(|t| ron::from_str::<RecoveryMeta>(&t).ok())
        else {
            continue;
        };
        if !scene.is_file() || is_running(meta.pid) {
            continue;
        }
        let original_newer = meta.original.as_ref().is_some_and(|o| {
            std::fs::metadata(o)
                .and_then(|m| m.modified())
                .ok()
                .and_then(|t| t.duration_since(UNIX_EPOCH).ok())
                .is_some_and(|t| t.as_millis() as u64 > meta.saved_unix_ms)
        });
        let entry = RecoveryEntry {
            scene,
            meta_path,
            meta,
        };
        if original_newer {
            discard(&entry);
        } else {
            out.push(entry);
        }
    }
    out.sort_by_key(|e| std::cmp::Reverse(e.meta.saved_unix_ms));
    out
}

/// True when `pid` is a running process named like Hedra (Linux: `/proc`);
/// this process counts as running (its own points are not offered to it).
pub fn hedra_is_running(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    // `/proc/PID/stat` is "PID (COMM) STATE …"; a killed process may linger
    // as a zombie (state Z) until it is reaped.
    std::fs::read_to_string(format!("/proc/{pid}/stat")).is_ok_and(|stat| {
        let (comm, rest) = stat.rsplit_once(')').unwrap_or((&stat, ""));
        comm.contains("hedra") && !rest.trim_start().starts_with(['Z', 'X'])
    })
}

/// Deletes a recovery point.
pub fn discard(entry: &RecoveryEntry) {
    let _ = std::fs::remove_file(&entry.meta_path);
    let _ = std::fs::remove_file(&entry.scene);
}

/// Loads a recovery point. The session is marked unsaved (it is newer than
/// its file); the caller adopts the point with [`adopt`] so that it is
/// overwritten by the next autosave and removed by the next save.
///
/// # Errors
/// The scene file's [`FileError`].
pub fn recover(entry: &RecoveryEntry) -> Result<Loaded, FileError> {
    let mut loaded = file::load(&entry.scene)?;
    loaded.session.saved_serial = None;
    Ok(loaded)
}

/// Makes a recovered point this session's own: it becomes the autosave of
/// `point`, so nothing is lost until the next autosave or save replaces it.
///
/// Returns the entry as it is now (the same one if it could not be moved).
pub fn adopt(entry: &RecoveryEntry, point: &RecoveryPoint) -> RecoveryEntry {
    let (scene, meta_path) = point.paths(RecoveryKind::Autosave);
    if entry.scene != scene && std::fs::rename(&entry.scene, &scene).is_err() {
        return entry.clone();
    }
    let meta = RecoveryMeta {
        original: point.original.clone(),
        kind: RecoveryKind::Autosave,
        pid: std::process::id(),
        ..entry.meta.clone()
    };
    let text = ron::ser::to_string_pretty(&meta, ron::ser::PrettyConfig::default())
        .expect("recovery meta serializes");
    if file::write_atomic_without_backup(&meta_path, text.as_bytes()).is_ok()
        && entry.meta_path != meta_path
    {
        let _ = std::fs::remove_file(&entry.meta_path);
    }
    RecoveryEntry {
        scene,
        meta_path,
        meta,
    }
}

/// What the panic hook saves: the last committed document and where its
/// recovery point goes. The app replaces it after every change.
pub type EmergencySnapshot = Arc<Mutex<Option<(Session, RecoveryPoint)>>>;

/// Installs a panic hook that, after the usual message, writes the snapshot
/// as an emergency recovery point and says where. The lock is only tried:
/// a panic while the snapshot is being replaced saves nothing rather than
/// deadlocking.
pub fn install_emergency_save(snapshot: EmergencySnapshot) {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        previous(info);
        let Ok(guard) = snapshot.try_lock() else {
            return;
        };
        if let Some((session, point)) = guard.as_ref() {
            match point.write(session, RecoveryKind::Emergency) {
                Ok(path) => eprintln!(
                    "hedra: your work was saved to {}; the next start offers to recover it",
                    path.display()
                ),
                Err(e) => eprintln!("hedra: emergency save failed: {e}"),
            }
        }
    }));
}

fn absolute(p: &Path) -> PathBuf {
    std::fs::canonicalize(p)
        .or_else(|_| std::path::absolute(p))
        .unwrap_or_else(|_| p.to_path_buf())
}

/// 64-bit FNV-1a: a stable hash for file names (std's hasher may change
/// between Rust versions).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}
