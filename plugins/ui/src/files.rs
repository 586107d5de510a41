//! File handling in the window: dialogs (rfd, with a typed-path fallback),
//! asking before unsaved changes are discarded, recent files and samples.

use bevy::prelude::*;
use bevy::tasks::{IoTaskPool, Task, futures::check_ready};
use hedra_doc::export::ExportFormat;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// What a chosen path is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FilePurpose {
    /// Open a scene (.hedra.ron).
    Open,
    /// Save the scene under a new path (the scene extension is added when
    /// missing).
    SaveAs,
    /// Import a file's nodes into the scene (every format of
    /// [`hedra_doc::import::IMPORT_FORMATS`]).
    Import,
    /// Export the scene, offering this format. The extension of the path
    /// finally chosen picks the format.
    Export(ExportFormat),
}

impl FilePurpose {
    /// The title of the dialog and of the path prompt ("Open Scene", …).
    pub fn title(self) -> String {
        match self {
            FilePurpose::Open => "Open Scene".to_string(),
            FilePurpose::SaveAs => "Save Scene As".to_string(),
            FilePurpose::Import => "Import".to_string(),
            FilePurpose::Export(format) => format!("Export {}", format.name()),
        }
    }
    /// The file name offered for an export ("export.obj").
    pub fn export_file_name(self) -> String {
        match self {
            FilePurpose::Export(format) => format!("export.{}", format.extensions()[0]),
            _ => "export.obj".to_string(),
        }
    }
    fn filter(self) -> (&'static str, &'static [&'static str]) {
        match self {
            FilePurpose::Open | FilePurpose::SaveAs => ("Hedra scene", &["ron"]),
            FilePurpose::Import => ("Files Hedra imports", hedra_doc::import::IMPORT_FORMATS),
            FilePurpose::Export(format) => (format.name(), format.extensions()),
        }
    }
}

/// Something to do once the user has decided about unsaved changes.
#[derive(Clone, Debug, PartialEq)]
pub enum Pending {
    /// Replace the document with an empty one.
    New,
    /// Open this scene file.
    Open(PathBuf),
    /// Open this sample as a new untitled scene.
    OpenSample(PathBuf),
    /// Show the Open dialog.
    BrowseOpen,
    /// Quit the app.
    Quit,
}

/// The path prompt: a text field, with "Browse…" when a dialog backend exists.
#[derive(Clone, Debug)]
pub struct PathPrompt {
    /// What the typed path will be used for.
    pub purpose: FilePurpose,
    /// The path as typed so far (pre-filled with a suggestion when saving or
    /// exporting).
    pub text: String,
    /// Whether the text field has been given the keyboard (it takes it
    /// once, when the prompt opens).
    pub focused: bool,
}

/// A native file dialog running on the IO pool (it blocks its thread).
pub struct DialogTask {
    /// What the chosen path will be used for.
    pub purpose: FilePurpose,
    /// The dialog's result: the chosen path, or `None` when it was cancelled
    /// or the backend failed.
    pub task: Task<Option<PathBuf>>,
}

/// True when rfd can show a dialog here: a desktop portal over D-Bus or zenity.
pub fn dialog_backend_available() -> bool {
    std::env::var_os("DBUS_SESSION_BUS_ADDRESS").is_some()
        || std::env::var_os("PATH")
            .is_some_and(|paths| std::env::split_paths(&paths).any(|p| p.join("zenity").is_file()))
}

/// Opens the native dialog for `purpose` on the IO task pool, starting in
/// `start_dir` when given; poll it with [`poll_dialog`].
pub fn spawn_dialog(purpose: FilePurpose, start_dir: Option<PathBuf>) -> DialogTask {
    let (name, exts) = purpose.filter();
    let task = IoTaskPool::get().spawn(async move {
        let mut d = rfd::FileDialog::new()
            .set_title(purpose.title())
            .add_filter(name, exts);
        if let Some(dir) = start_dir {
            d = d.set_directory(dir);
        }
        match purpose {
            FilePurpose::Open | FilePurpose::Import => d.pick_file(),
            FilePurpose::SaveAs => d.set_file_name("untitled.hedra.ron").save_file(),
            FilePurpose::Export(_) => d.set_file_name(purpose.export_file_name()).save_file(),
        }
    });
    DialogTask { purpose, task }
}

/// Polls a running dialog; `Some(result)` once it closed.
pub fn poll_dialog(task: &mut DialogTask) -> Option<Option<PathBuf>> {
    check_ready(&mut task.task)
}

/// Adds the scene extension when a typed save path has none.
pub fn with_scene_extension(path: PathBuf) -> PathBuf {
    let s = path.to_string_lossy();
    if s.ends_with(".hedra.ron") || s.ends_with(".ron") {
        path
    } else {
        PathBuf::from(format!("{s}.hedra.ron"))
    }
}

/// Preferences kept between runs (`preferences.ron` in the configuration
/// folder); fields missing from an older file take their defaults.
#[derive(Resource, Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Preferences {
    /// Scenes recently opened or saved, newest first, as canonical paths (at
    /// most ten).
    pub recent: Vec<PathBuf>,
    /// Seconds between autosaves of unsaved changes (0: never).
    pub autosave_seconds: u32,
    /// Undo steps kept; older ones are dropped.
    pub undo_steps: usize,
    /// Memory the undo history may hold, in MiB; older steps are dropped.
    pub undo_memory_mib: usize,
    /// The folder they are saved in (not part of the file): the
    /// configuration folder for the app, a test's own folder for the
    /// windowless app, `None` when there is none (nothing is saved).
    #[serde(skip)]
    pub folder: Option<PathBuf>,
}

impl Default for Preferences {
    fn default() -> Self {
        Preferences {
            recent: Vec::new(),
            autosave_seconds: 120,
            undo_steps: 500,
            undo_memory_mib: 512,
            folder: None,
        }
    }
}

impl Preferences {
    const MAX_RECENT: usize = 10;

    /// The configuration folder (see [`hedra_doc::recovery::config_dir`]).
    pub fn dir() -> Option<PathBuf> {
        hedra_doc::recovery::config_dir()
    }

    /// Reads the preferences of the configuration folder; a missing or
    /// unreadable file gives defaults.
    pub fn load() -> Self {
        Self::load_from(Self::dir())
    }

    /// Reads the preferences saved in `folder` (defaults when there are
    /// none); they are saved back there.
    pub fn load_from(folder: Option<PathBuf>) -> Self {
        let loaded: Preferences = folder
            .as_ref()
            .and_then(|d| std::fs::read_to_string(d.join("preferences.ron")).ok())
            .and_then(|t| ron::from_str(&t).ok())
            .unwrap_or_default();
        Preferences { folder, ..loaded }
    }

    /// Writes the preferences into their folder (atomically); failures only
    /// cost the preferences.
    pub fn save(&self) -> Result<(), String> {
        let dir = self
            .folder
            .clone()
            .ok_or("no configuration folder (HOME is not set)")?;
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let text = ron::ser::to_string_pretty(self, ron::ser::PrettyConfig::default())
            .map_err(|e| e.to_string())?;
        hedra_doc::file::write_atomic_without_backup(&dir.join("preferences.ron"), text.as_bytes())
            .map_err(|e| e.to_string())
    }

    /// Puts `path` first in the recent list.
    pub fn add_recent(&mut self, path: &Path) {
        let path = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
        self.recent.retain(|p| *p != path);
        self.recent.insert(0, path);
        self.recent.truncate(Self::MAX_RECENT);
    }
}

/// Where the sample scenes live (`assets/samples`).
#[derive(Resource, Debug, Clone)]
pub struct SamplesDir(pub PathBuf);

/// Sample scene files, sorted by name.
pub fn list_samples(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.to_string_lossy().ends_with(".hedra.ron"))
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}
