//! Never lose work, in the app: autosave of unsaved changes, the snapshot
//! the panic hook saves, the start-up offer to recover, the undo history
//! limits and the Preferences window. The files: `hedra_doc::recovery`.

use crate::files::Preferences;
use bevy::prelude::*;
use bevy_egui::{EguiContexts, egui};
use hedra_doc::recovery::{self, EmergencySnapshot, RecoveryEntry, RecoveryKind, RecoveryPoint};
use hedra_edit::{EditMode, ShapeEdit, TransformTool};
use hedra_scene::{DocRequest, DocState, StatusMessage};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

type AutosaveJob = JoinHandle<Result<(PathBuf, u64), String>>;

/// Recovery state of the running app.
#[derive(Resource)]
pub struct Recovery {
    /// The recovery folder; `None` when there is no configuration folder
    /// (nothing is autosaved; the Preferences window says so).
    pub dir: Option<PathBuf>,
    /// Where the open document's recovery points go, and the document path
    /// it was made for.
    point: Option<(RecoveryPoint, Option<PathBuf>)>,
    /// A recovered point waiting for its document to be loaded.
    adopted: Option<RecoveryPoint>,
    /// This session wrote (or adopted) files at `point`.
    wrote_files: bool,
    /// History serial of the last autosave.
    last_serial: Option<u64>,
    /// When the autosave interval started.
    since: Instant,
    writing: Option<AutosaveJob>,
    /// Recovery points offered on start (the window shows while non-empty).
    pub offer: Vec<RecoveryEntry>,
    /// What the panic hook saves (see [`recovery::install_emergency_save`]).
    pub snapshot: EmergencySnapshot,
    snapshot_revision: Option<u64>,
    /// Autosaves written this session.
    pub autosaves: usize,
}

impl Recovery {
    /// Recovery in `dir` (`None`: off).
    pub fn new(dir: Option<PathBuf>) -> Self {
        Recovery {
            dir,
            point: None,
            adopted: None,
            wrote_files: false,
            last_serial: None,
            since: Instant::now(),
            writing: None,
            offer: Vec::new(),
            snapshot: Arc::new(Mutex::new(None)),
            snapshot_revision: None,
            autosaves: 0,
        }
    }

    /// The recovery point of the open document, once known.
    pub fn point(&self) -> Option<&RecoveryPoint> {
        self.point.as_ref().map(|(p, _)| p)
    }

    /// True while an autosave is being written.
    pub fn is_writing(&self) -> bool {
        self.writing.is_some()
    }

    fn forget_own_files(&mut self) {
        if self.wrote_files {
            if let Some((p, _)) = &self.point {
                p.remove();
            }
            self.wrote_files = false;
        }
        self.last_serial = None;
    }
}

/// Autosave, the emergency snapshot for the panic hook, the start-up
/// recovery offer, the undo history limits and the Preferences window.
pub struct RecoveryPlugin;

impl Plugin for RecoveryPlugin {
    fn build(&self, app: &mut App) {
        app.insert_resource(Recovery::new(recovery::default_dir()))
            .add_systems(Startup, offer_recovery)
            .add_systems(
                Update,
                (
                    follow_document,
                    autosave,
                    update_snapshot,
                    apply_history_limits,
                )
                    .chain()
                    .in_set(hedra_scene::SceneSystems::View),
            )
            .add_systems(Last, on_exit)
            .add_systems(
                bevy_egui::EguiPrimaryContextPass,
                (recovery_window, preferences_window),
            );
    }
}

/// Finds the recovery points worth offering.
fn offer_recovery(mut rec: ResMut<Recovery>) {
    if let Some(dir) = &rec.dir {
        rec.offer = recovery::pending(dir);
        for e in &rec.offer {
            info!("recovery offered: {}", e.scene.display());
        }
    }
}

/// Keeps the recovery point on the open document's path; removes this
/// session's files once they are not needed (saved, discarded, replaced).
fn follow_document(mut rec: ResMut<Recovery>, state: Res<DocState>) {
    let Some(dir) = rec.dir.clone() else {
        return;
    };
    if let Some(adopted) = rec.adopted.take()
        && adopted.original() == state.path.as_deref().map(absolute).as_deref()
    {
        if rec.point().is_some_and(|p| *p != adopted) {
            rec.forget_own_files();
        }
        rec.point = Some((adopted, state.path.clone()));
        rec.wrote_files = true;
        rec.last_serial = Some(state.session.history.current_serial());
        rec.since = Instant::now();
        return;
    }
    if rec
        .point
        .as_ref()
        .is_none_or(|(_, path)| *path != state.path)
    {
        rec.forget_own_files();
        rec.point = Some((
            RecoveryPoint::new(&dir, state.path.as_deref()),
            state.path.clone(),
        ));
        rec.since = Instant::now();
    }
    if !state.session.is_dirty() {
        rec.forget_own_files();
        rec.since = Instant::now();
    }
}

fn absolute(p: &std::path::Path) -> PathBuf {
    std::fs::canonicalize(p)
        .or_else(|_| std::path::absolute(p))
        .unwrap_or_else(|_| p.to_path_buf())
}

/// Writes the document to its recovery point every `autosave_seconds` when
/// it changed since the last autosave and no tool is running; the file is
/// written on a worker thread from a copy (meshes are shared, not copied).
#[allow(clippy::too_many_arguments)]
fn autosave(
    mut rec: ResMut<Recovery>,
    state: Res<DocState>,
    prefs: Res<Preferences>,
    transform: Res<TransformTool>,
    mesh_edit: Res<EditMode>,
    shape_edit: Res<ShapeEdit>,
    ui: Res<crate::UiState>,
    mut status: ResMut<StatusMessage>,
) {
    if let Some(job) = rec.writing.take_if(|j| j.is_finished()) {
        match job.join() {
            Ok(Ok((path, serial))) => {
                rec.wrote_files = true;
                rec.last_serial = Some(serial);
                rec.autosaves += 1;
                info!("autosaved to {}", path.display());
            }
            Ok(Err(e)) => status.error(format!("Autosave failed: {e}")),
            Err(_) => status.error("Autosave failed (the writer stopped)"),
        }
    }
    let serial = state.session.history.current_serial();
    let tool_running = transform.active.is_some()
        || mesh_edit.tool.is_some()
        || shape_edit.tool.is_some()
        || ui.transform_edit.is_some()
        || ui.crease_edit.is_some()
        || ui.weight_edit.is_some();
    let due = prefs.autosave_seconds > 0
        && rec.since.elapsed() >= Duration::from_secs(u64::from(prefs.autosave_seconds));
    if !due
        || rec.writing.is_some()
        || !rec.offer.is_empty()
        || !state.session.is_dirty()
        || rec.last_serial == Some(serial)
        || tool_running
    {
        return;
    }
    let Some((point, _)) = rec.point.clone() else {
        return;
    };
    let session = state.session.clone();
    rec.since = Instant::now();
    rec.writing = Some(std::thread::spawn(move || {
        point
            .write(&session, RecoveryKind::Autosave)
            .map(|p| (p, serial))
            .map_err(|e| e.to_string())
    }));
}

/// Keeps the panic hook's snapshot at the last committed document (nothing
/// while it is saved).
fn update_snapshot(mut rec: ResMut<Recovery>, state: Res<DocState>) {
    if rec.snapshot_revision == Some(state.revision) {
        return;
    }
    rec.snapshot_revision = Some(state.revision);
    let value = match (&rec.point, state.session.is_dirty()) {
        (Some((p, _)), true) => Some((state.session.clone(), p.clone())),
        _ => None,
    };
    if let Ok(mut guard) = rec.snapshot.lock() {
        *guard = value;
    }
}

/// Sends the preferences' undo limits to the history when they differ.
fn apply_history_limits(
    prefs: Res<Preferences>,
    state: Res<DocState>,
    mut requests: MessageWriter<DocRequest>,
) {
    let h = &state.session.history;
    let bytes = prefs.undo_memory_mib.saturating_mul(1024 * 1024);
    if h.max_steps != prefs.undo_steps.max(1) || h.max_bytes != bytes {
        requests.write(DocRequest::HistoryLimits {
            steps: prefs.undo_steps,
            bytes,
        });
    }
}

/// The app is going down. A normal quit (the user saved or chose to
/// discard) removes this session's recovery files, and a panic while
/// shutting down saves nothing. An error exit (Bevy quits this way on a
/// render error) writes the last committed document as an emergency
/// recovery point instead, offered on the next start.
fn on_exit(mut exits: MessageReader<AppExit>, mut rec: ResMut<Recovery>) {
    let exits: Vec<AppExit> = exits.read().cloned().collect();
    if exits.is_empty() {
        return;
    }
    let error = exits.iter().any(AppExit::is_error);
    // A signal's exit says so: the recovery offer then says "stopped", not
    // "crashed".
    let stopped = exits.iter().any(|e| {
        matches!(e, AppExit::Error(code) if code.get() == hedra_doc::recovery::STOPPED_EXIT_CODE)
    });
    let kind = if stopped {
        RecoveryKind::Stopped
    } else {
        RecoveryKind::Emergency
    };
    if let Some(job) = rec.writing.take() {
        let _ = job.join();
        rec.wrote_files = true;
    }
    let snapshot = rec.snapshot.lock().ok().and_then(|mut g| g.take());
    if error {
        if let Some((session, point)) = snapshot {
            match point.write(&session, kind) {
                Ok(path) => error!(
                    "Hedra is quitting on an error; your work was saved to {} and is offered on the next start",
                    path.display()
                ),
                Err(e) => error!("emergency save failed: {e}"),
            }
        }
    } else {
        rec.forget_own_files();
    }
}

/// "Recover unsaved work": one row per recovery point.
pub fn recovery_window(
    mut contexts: EguiContexts,
    mut rec: ResMut<Recovery>,
    state: Res<DocState>,
    mut requests: MessageWriter<DocRequest>,
) -> Result {
    if rec.offer.is_empty() {
        return Ok(());
    }
    let ctx = contexts.ctx_mut()?;
    let now = recovery::now_unix_ms();
    let mut recover = None;
    let mut discard = None;
    let mut later = false;
    egui::Window::new("Recover unsaved work")
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, [0.0, 0.0])
        .show(ctx, |ui| {
            ui.label("Hedra found work that was not saved when it last closed:");
            ui.add_space(4.0);
            for (i, e) in rec.offer.iter().enumerate() {
                ui.horizontal(|ui| {
                    ui.label(e.describe(now));
                    let can = !state.session.is_dirty();
                    if ui
                        .add_enabled(can, egui::Button::new("Recover"))
                        .on_disabled_hover_text("Save or undo the current changes first")
                        .clicked()
                    {
                        recover = Some(i);
                    }
                    if ui.button("Discard").clicked() {
                        discard = Some(i);
                    }
                });
            }
            ui.add_space(4.0);
            if ui
                .button("Decide later")
                .on_hover_text("Keep the files; they are offered again on the next start")
                .clicked()
            {
                later = true;
            }
        });
    if let Some(i) = recover {
        let entry = rec.offer.remove(i);
        let dir = rec.dir.clone().unwrap_or_default();
        let point = RecoveryPoint::new(&dir, entry.meta.original.as_deref());
        let adopted = recovery::adopt(&entry, &point);
        rec.adopted = Some(point);
        requests.write(DocRequest::Recover(adopted));
    }
    if let Some(i) = discard {
        recovery::discard(&rec.offer.remove(i));
    }
    if later {
        rec.offer.clear();
    }
    Ok(())
}

/// Edit ▸ Preferences: autosave interval and undo limits, saved at once.
pub fn preferences_window(
    mut contexts: EguiContexts,
    rec: Res<Recovery>,
    mut ui_state: ResMut<crate::UiState>,
    mut prefs: ResMut<Preferences>,
    state: Res<DocState>,
    mut status: MessageWriter<hedra_scene::StatusRequest>,
) -> Result {
    if !ui_state.show_preferences {
        return Ok(());
    }
    let ctx = contexts.ctx_mut()?;
    let mut edited = prefs.clone();
    let mut open = true;
    egui::Window::new("Preferences")
        .open(&mut open)
        .resizable(false)
        .show(ctx, |ui| {
            egui::Grid::new("prefs").num_columns(2).show(ui, |ui| {
                ui.label("Autosave every");
                ui.add(
                    egui::DragValue::new(&mut edited.autosave_seconds)
                        .range(0..=3600)
                        .suffix(" s"),
                )
                .on_hover_text("0 turns autosave off");
                ui.end_row();
                ui.label("Undo steps kept");
                ui.add(egui::DragValue::new(&mut edited.undo_steps).range(1..=100_000));
                ui.end_row();
                ui.label("Undo memory");
                ui.add(
                    egui::DragValue::new(&mut edited.undo_memory_mib)
                        .range(16..=65_536)
                        .suffix(" MiB"),
                );
                ui.end_row();
            });
            ui.label(format!("Now: {}", history_summary(&state.session.history)));
            match &rec.dir {
                Some(d) => ui.label(format!("Recovery folder: {}", d.display())),
                None => ui.colored_label(
                    egui::Color32::LIGHT_RED,
                    "No configuration folder (HOME is not set): nothing is autosaved",
                ),
            };
        });
    ui_state.show_preferences = open;
    if edited != *prefs {
        *prefs = edited;
        if let Err(e) = prefs.save() {
            status.write(hedra_scene::StatusRequest::Error(format!(
                "Preferences not saved: {e}"
            )));
        }
    }
    Ok(())
}

/// "7 undo steps kept (limit 500), about 36 KiB of 512 MiB, 2 oldest
/// dropped" — what the history window and the preferences show.
pub(crate) fn history_summary(h: &hedra_doc::History) -> String {
    let bytes = |n: usize| match n {
        0..1024 => format!("{n} bytes"),
        1024..1_048_576 => format!("{} KiB", n / 1024),
        _ => format!("{:.1} MiB", n as f64 / 1_048_576.0),
    };
    format!(
        "{} undo steps kept (limit {}), about {} of {}{}",
        h.done().len() + h.undone().len(),
        h.max_steps,
        bytes(h.approx_bytes()),
        bytes(h.max_bytes),
        if h.dropped > 0 {
            format!(", {} oldest dropped", h.dropped)
        } else {
            String::new()
        }
    )
}
