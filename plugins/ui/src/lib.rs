//! Panels, menus, dialogs and the status bar (egui), plus the window title
//! and the file workflow (open, save, ask before discarding changes).

// Bevy systems take their world access as parameters: long parameter lists
// and nested query types are how Bevy code is written (Bevy allows both too).
#![allow(clippy::too_many_arguments, clippy::type_complexity)]

use bevy::camera::visibility::RenderLayers;
use bevy::camera::{CameraOutputMode, Viewport};
use bevy::prelude::*;
use bevy::render::render_resource::BlendState;
use bevy::window::{PrimaryWindow, WindowCloseRequested};
use bevy_egui::{EguiGlobalSettings, EguiPlugin, EguiPrimaryContextPass, PrimaryEguiContext, egui};
use hedra_doc::{Command, NodeId, NodeTransform};
use hedra_edit::{Selection, TransformTool};
use hedra_scene::{DocRequest, DocState, InputGate, StatusMessage, ViewportCamera};
use std::sync::Arc;

pub mod egui_input;
pub mod files;
mod panels;
pub use panels::{ADD_MENU, MERGE_MENU, SNAP_MENU, draw_ui};
pub mod recovery;

pub use files::{FilePurpose, Pending, Preferences, SamplesDir};

/// What the Decimate modifier's level counts depend on: the cage (held,
/// compared by identity) and a hash of the node, the modifier's index and
/// its settings.
pub type DecimateCountsKey = (
    by_address::ByAddress<std::sync::Arc<hedra_geom::HalfEdgeMesh>>,
    u64,
);

/// Everything the panels remember between frames.
#[derive(Resource)]
pub struct UiState {
    /// The Outliner panel is shown (View menu).
    pub show_outliner: bool,
    /// The Properties panel is shown (View menu).
    pub show_properties: bool,
    /// The Undo History window is shown (Edit or View menu).
    pub show_history: bool,
    /// The statistics overlay (View ▸ Statistics): counts of the scene and
    /// of the selection in the viewport's top left corner.
    pub show_statistics: bool,
    /// The object-mode statistics of the shown meshes (vertices, edges,
    /// faces, triangles) and the document revision they were counted at.
    pub shown_counts: Option<(u64, [usize; 4])>,
    /// Counts and checks of the meshes the panels show, made once per mesh.
    pub mesh_facts: MeshFacts,
    /// The outliner's tree and the document revision it was walked at.
    pub outliner_tree: Option<(u64, hedra_doc::Hierarchy)>,
    /// How File ▸ Export writes (its checkboxes: OBJ curves as NURBS
    /// records, …); the shape is always the evaluated one.
    pub export_options: hedra_doc::export::ExportOptions,
    /// The Preferences window is shown (Edit > Preferences…).
    pub show_preferences: bool,
    /// Shift+A menu position, while open.
    pub add_menu_at: Option<egui::Pos2>,
    /// Shift+S snap menu position, while open.
    pub snap_menu_at: Option<egui::Pos2>,
    /// The page the Shift+A menu shows (its Curve ▸ and Surface ▸ parts).
    pub add_page: panels::AddPage,
    /// Z shading menu position, while open.
    pub shading_menu_at: Option<egui::Pos2>,
    /// Waiting for the user to decide about unsaved changes.
    pub confirm: Option<Pending>,
    /// Runs after the next successful save (Save before New/Open/Quit).
    pub after_save: Option<Pending>,
    /// The path prompt, while one is open (Open, Save As, Import, Export).
    pub path_prompt: Option<files::PathPrompt>,
    /// The native file dialog, while one runs (beside the path prompt).
    pub dialog: Option<files::DialogTask>,
    /// True when a native file dialog can be shown here (checked once at start);
    /// without one, paths are typed into the prompt.
    pub dialog_backend: bool,
    /// Node being renamed in the outliner.
    pub rename: Option<Rename>,
    /// Transform fields being dragged in the properties panel (committed on release).
    pub transform_edit: Option<(NodeId, NodeTransform)>,
    /// Crease field being dragged (committed on release).
    pub crease_edit: Option<f64>,
    /// The tapered crease the panel sets on the selected edge chain: the
    /// sharpness at its start and at its end, and which end starts.
    pub taper: (f64, f64, bool),
    /// The face counts of the levels of the Decimate modifier last shown,
    /// keyed by what they depend on (node, index, cage, settings).
    pub decimate_counts: Option<(DecimateCountsKey, Vec<usize>)>,
    /// The Decimate slider is being dragged and its first step was sent
    /// (later frames adjust that step).
    pub decimate_dragging: bool,
    /// Weight field being dragged (committed on release).
    pub weight_edit: Option<f64>,
    /// Kochanek-Bartels tension, bias, continuity being dragged for the
    /// selected keys (committed on release).
    pub tbc_edit: Option<[f64; 3]>,
    /// The selected control points' median being typed or dragged in the
    /// panel (local space; committed on release).
    pub point_edit: Option<glam::DVec3>,
    /// The segment whose power basis the curve panel shows.
    pub power_segment: usize,
    /// A construction's fields being dragged (the node and the recipe as
    /// edited; committed on release).
    pub construction_edit: Option<(
        hedra_doc::NodeId,
        hedra_doc::construction::Construction<hedra_doc::NodeRef>,
    )>,
    /// This frame's view axis (a point, the 3D cursor, and the direction
    /// towards the viewer), for a revolution about the view.
    pub view_axis: Option<(glam::DVec3, glam::DVec3)>,
    /// Where "Insert knot" inserts.
    pub knot_at: f64,
    /// How many equal arc lengths Curve ▸ Divide makes.
    pub divide_count: usize,
    /// The 3D area left by the panels, in logical pixels.
    pub viewport_rect: Option<egui::Rect>,
    /// The window title last set, so the title is written only when it changes.
    pub last_title: String,
}

impl Default for UiState {
    fn default() -> Self {
        UiState {
            show_outliner: true,
            show_properties: true,
            show_history: false,
            show_statistics: false,
            shown_counts: None,
            mesh_facts: MeshFacts::default(),
            outliner_tree: None,
            show_preferences: false,
            add_menu_at: None,
            snap_menu_at: None,
            shading_menu_at: None,
            add_page: Default::default(),
            confirm: None,
            after_save: None,
            path_prompt: None,
            dialog: None,
            dialog_backend: files::dialog_backend_available(),
            rename: None,
            transform_edit: None,
            crease_edit: None,
            taper: (0.0, 4.0, false),
            decimate_counts: None,
            decimate_dragging: false,
            weight_edit: None,
            tbc_edit: None,
            point_edit: None,
            view_axis: None,
            construction_edit: None,
            export_options: hedra_doc::export::ExportOptions::default(),
            power_segment: 0,
            knot_at: 0.5,
            divide_count: 10,
            viewport_rect: None,
            last_title: String::new(),
        }
    }
}

/// An outliner rename in progress.
#[derive(Debug, Clone)]
pub struct Rename {
    /// The node being renamed.
    pub node: NodeId,
    /// The name as edited so far (applied, trimmed, when the field loses
    /// focus, unless Esc was pressed or it is empty).
    pub text: String,
    /// False until the field has been focused with its text selected.
    pub started: bool,
}

impl Rename {
    /// Starts renaming `node`, with its current `name` in the field.
    pub fn new(node: NodeId, name: &str) -> Self {
        Rename {
            node,
            text: name.to_string(),
            started: false,
        }
    }
}

/// Requests from menus and keys that need the file workflow.
#[derive(Message, Clone, Debug, PartialEq)]
pub enum FileAction {
    /// New scene (Ctrl+N), after asking about unsaved changes.
    New,
    /// Open a scene chosen in the file dialog or path prompt (Ctrl+O), after
    /// asking about unsaved changes.
    Open,
    /// Open this scene (recent files, a dropped file), after asking about
    /// unsaved changes.
    OpenPath(std::path::PathBuf),
    /// Open this sample as a new untitled scene (File ▸ Open Sample), after
    /// asking about unsaved changes.
    OpenSample(std::path::PathBuf),
    /// Save to the document's file (Ctrl+S), or ask for a path when it has none.
    Save,
    /// Save under a path chosen in the file dialog or path prompt (Ctrl+Shift+S).
    SaveAs,
    /// Import a file chosen in the file dialog or path prompt.
    Import,
    /// Export to a path chosen in the file dialog or path prompt, offering
    /// this format.
    Export(hedra_doc::export::ExportFormat),
    /// Quit (Ctrl+Q or closing the window), after asking about unsaved changes.
    Quit,
    /// The path typed into the path prompt, for what the prompt was for.
    UsePath(FilePurpose, std::path::PathBuf),
}

/// The egui panels, menus and dialogs, the window title, the file workflow
/// and recovery ([`recovery::RecoveryPlugin`]).
pub struct UiPlugin;

impl Plugin for UiPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins((EguiPlugin::default(), recovery::RecoveryPlugin))
            .init_resource::<UiState>()
            .insert_resource(Preferences::load())
            .add_message::<FileAction>()
            // egui's new glyphs reach its font texture in
            // `PostProcessOutput`; the render world only uploads a changed
            // image it hears of from `AssetEventSystems`. Run in the other
            // order, the frame that first shows new text draws it with
            // holes (a whole frame without panels when the atlas grows).
            .configure_sets(
                PostUpdate,
                bevy_egui::EguiPostUpdateSet::PostProcessOutput
                    .before(bevy::asset::AssetEventSystems),
            )
            .add_systems(Startup, spawn_ui_camera)
            .add_systems(
                PreUpdate,
                (
                    egui_input::allow_long_clicks,
                    egui_input::refresh_pointer_gate.after(bevy::input::InputSystems),
                    egui_input::write_egui_input_in_order
                        .in_set(bevy_egui::EguiInputSet::ReadBevyMessages),
                ),
            )
            .configure_sets(Update, UiSystems.in_set(hedra_scene::SceneSystems::Tools))
            .add_systems(
                EguiPrimaryContextPass,
                (panels::draw_ui, egui_input::refresh_keyboard_gate).chain(),
            )
            .add_systems(
                Update,
                (
                    global_shortcuts,
                    handle_file_actions,
                    poll_file_dialog,
                    on_close_requested,
                    on_file_dropped,
                    remember_recent,
                    update_title,
                    apply_viewport_rect,
                )
                    .chain()
                    .in_set(UiSystems),
            );
    }
}

/// The UI's input handlers (shortcuts, file actions, dropped files), in
/// `SceneSystems::Tools`; the panels themselves are drawn in egui's pass
/// (`PostUpdate`) and their requests are applied the next frame.
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub struct UiSystems;

/// egui draws through its own camera, so the 3D camera can be given just
/// the area between the panels.
fn spawn_ui_camera(mut commands: Commands, mut settings: ResMut<EguiGlobalSettings>) {
    settings.auto_create_primary_context = false;
    egui_input::take_over_egui_input(&mut settings);
    commands.spawn((
        PrimaryEguiContext,
        Camera2d,
        RenderLayers::none(),
        Camera {
            // After the 3D view (0) and Bevy's transform-gizmo overlay (1).
            order: 2,
            output_mode: CameraOutputMode::Write {
                blend_state: Some(BlendState::ALPHA_BLENDING),
                clear_color: ClearColorConfig::None,
            },
            clear_color: ClearColorConfig::Custom(Color::NONE),
            ..default()
        },
    ));
}

/// Gives the 3D camera the area the panels leave free.
fn apply_viewport_rect(
    ui: Res<UiState>,
    quad: Res<hedra_scene::QuadView>,
    window: Single<&Window, With<PrimaryWindow>>,
    mut camera: Single<&mut Camera, With<ViewportCamera>>,
    mut quad_cameras: Query<
        (&hedra_viewport::QuadViewCamera, &mut Camera),
        Without<ViewportCamera>,
    >,
) {
    let Some(free) = ui.viewport_rect else { return };
    // In quad view the perspective camera takes the bottom-right quarter
    // and the fixed views the others.
    let quarter = |column: f32, row: f32| {
        let size = free.size() / 2.0;
        egui::Rect::from_min_size(free.min + egui::vec2(column * size.x, row * size.y), size)
    };
    let rect = if quad.0 { quarter(1.0, 1.0) } else { free };
    for (view, mut c) in &mut quad_cameras {
        let (column, row) = match view {
            hedra_viewport::QuadViewCamera::Top => (0.0, 0.0),
            hedra_viewport::QuadViewCamera::Front => (1.0, 0.0),
            hedra_viewport::QuadViewCamera::Right => (0.0, 1.0),
        };
        let v = physical_viewport(&window, quarter(column, row));
        if c.viewport.as_ref().is_none_or(|old| {
            old.physical_position != v.physical_position || old.physical_size != v.physical_size
        }) {
            c.viewport = Some(v);
        }
    }
    let viewport = physical_viewport(&window, rect);
    if camera.viewport.as_ref().is_none_or(|v| {
        v.physical_position != viewport.physical_position
            || v.physical_size != viewport.physical_size
    }) {
        camera.viewport = Some(viewport);
    }
}

/// A window rectangle (logical pixels) as a camera viewport (physical).
fn physical_viewport(window: &Window, rect: egui::Rect) -> Viewport {
    let scale = window.scale_factor();
    let (w, h) = (window.physical_width(), window.physical_height());
    let x = ((rect.min.x * scale).max(0.0) as u32).min(w.saturating_sub(1));
    let y = ((rect.min.y * scale).max(0.0) as u32).min(h.saturating_sub(1));
    let width = ((rect.width() * scale) as u32).clamp(1, w.saturating_sub(x).max(1));
    let height = ((rect.height() * scale) as u32).clamp(1, h.saturating_sub(y).max(1));
    Viewport {
        physical_position: UVec2::new(x, y),
        physical_size: UVec2::new(width, height),
        ..default()
    }
}

/// Ctrl+N/O/S, Ctrl+Shift+S, Ctrl+Q and the menus at the pointer (Shift+A,
/// Shift+S, Z), while no tool runs (Z is then the tool's axis).
fn global_shortcuts(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    tool: Res<TransformTool>,
    mode: Res<hedra_edit::EditMode>,
    shape_edit: Res<hedra_edit::ShapeEdit>,
    window: Single<&Window, With<PrimaryWindow>>,
    mut ui: ResMut<UiState>,
    mut actions: MessageWriter<FileAction>,
) {
    if !gate.keyboard_free || hedra_edit::modal_tool_running(&tool, &mode, &shape_edit) {
        return;
    }
    use hedra_edit::bindings::{Action, KeyMode, pressed};
    let pressed = |action| pressed(&keys, KeyMode::Everywhere, action);
    for (action, file) in [
        (Action::NewFile, FileAction::New),
        (Action::OpenFile, FileAction::Open),
        (Action::Save, FileAction::Save),
        (Action::SaveAs, FileAction::SaveAs),
        (Action::Quit, FileAction::Quit),
    ] {
        if pressed(action) {
            actions.write(file);
        }
    }
    let pointer = || window.cursor_position().map(|c| egui::pos2(c.x, c.y));
    if pressed(Action::AddMenu) {
        ui.add_menu_at = pointer();
    } else if pressed(Action::SnapMenu) {
        ui.snap_menu_at = pointer();
    } else if pressed(Action::ShadingMenu) {
        ui.shading_menu_at = pointer();
    }
}

/// Runs file actions, asking first when unsaved changes would be lost.
#[allow(clippy::too_many_arguments)]
fn handle_file_actions(
    mut actions: MessageReader<FileAction>,
    mut ui: ResMut<UiState>,
    state: Res<DocState>,
    mut requests: MessageWriter<DocRequest>,
    mut exit: MessageWriter<AppExit>,
    mut status: ResMut<StatusMessage>,
) {
    for action in actions.read() {
        let dirty = state.session.is_dirty();
        let guarded = |p: Pending, ui: &mut UiState| -> Option<Pending> {
            if dirty {
                ui.confirm = Some(p);
                None
            } else {
                Some(p)
            }
        };
        let now = match action {
            FileAction::New => guarded(Pending::New, &mut ui),
            FileAction::Open => guarded(Pending::BrowseOpen, &mut ui),
            FileAction::OpenPath(p) => guarded(Pending::Open(p.clone()), &mut ui),
            FileAction::OpenSample(p) => guarded(Pending::OpenSample(p.clone()), &mut ui),
            FileAction::Quit => guarded(Pending::Quit, &mut ui),
            FileAction::Save => {
                match &state.path {
                    Some(p) => {
                        requests.write(DocRequest::Save(p.clone()));
                    }
                    None => begin_path(&mut ui, FilePurpose::SaveAs, &state),
                }
                None
            }
            FileAction::SaveAs => {
                begin_path(&mut ui, FilePurpose::SaveAs, &state);
                None
            }
            FileAction::Export(format) => {
                begin_path(&mut ui, FilePurpose::Export(*format), &state);
                None
            }
            FileAction::Import => {
                begin_path(&mut ui, FilePurpose::Import, &state);
                None
            }
            FileAction::UsePath(purpose, path) => {
                let options = ui.export_options;
                use_path(
                    *purpose,
                    path.clone(),
                    options,
                    &state,
                    &mut requests,
                    &mut status,
                );
                None
            }
        };
        if let Some(p) = now {
            run_pending(p, &mut ui, &state, &mut requests, &mut exit);
        }
    }
}

/// Carries out an action whose unsaved-changes question is settled.
pub fn run_pending(
    p: Pending,
    ui: &mut UiState,
    state: &DocState,
    requests: &mut MessageWriter<DocRequest>,
    exit: &mut MessageWriter<AppExit>,
) {
    match p {
        Pending::New => {
            requests.write(DocRequest::New);
        }
        Pending::Open(path) => {
            requests.write(DocRequest::Open(path));
        }
        Pending::OpenSample(path) => {
            requests.write(DocRequest::OpenSample(path));
        }
        Pending::BrowseOpen => begin_path(ui, FilePurpose::Open, state),
        Pending::Quit => {
            exit.write(AppExit::Success);
        }
    }
}

/// Shows the path prompt and, when a dialog backend exists, the native dialog.
pub fn begin_path(ui: &mut UiState, purpose: FilePurpose, state: &DocState) {
    let start_dir = state
        .path
        .as_ref()
        .and_then(|p| p.parent().map(|d| d.to_path_buf()))
        .or_else(|| std::env::current_dir().ok());
    let text = match purpose {
        FilePurpose::Open | FilePurpose::Import => String::new(),
        FilePurpose::SaveAs => state
            .path
            .as_ref()
            .map(|p| p.display().to_string())
            .unwrap_or_else(|| {
                start_dir
                    .clone()
                    .unwrap_or_default()
                    .join("untitled.hedra.ron")
                    .display()
                    .to_string()
            }),
        FilePurpose::Export(_) => start_dir
            .clone()
            .unwrap_or_default()
            .join(purpose.export_file_name())
            .display()
            .to_string(),
    };
    ui.path_prompt = Some(files::PathPrompt {
        purpose,
        text,
        focused: false,
    });
    if ui.dialog_backend && ui.dialog.is_none() {
        ui.dialog = Some(files::spawn_dialog(purpose, start_dir));
    }
}

/// Applies a chosen path for its purpose.
pub fn use_path(
    purpose: FilePurpose,
    path: std::path::PathBuf,
    options: hedra_doc::export::ExportOptions,
    state: &DocState,
    requests: &mut MessageWriter<DocRequest>,
    status: &mut StatusMessage,
) {
    match purpose {
        FilePurpose::Open => {
            requests.write(DocRequest::Open(path));
        }
        FilePurpose::SaveAs => {
            requests.write(DocRequest::Save(files::with_scene_extension(path)));
        }
        FilePurpose::Import => {
            requests.write(DocRequest::Import(path));
        }
        FilePurpose::Export(format) => {
            // No extension given: the one of the format chosen.
            let path = if path.extension().is_none() {
                path.with_extension(format.extensions()[0])
            } else {
                path
            };
            let written = hedra_doc::export::export_to_path(&state.session.doc, &path, options)
                .map_err(|e| e.to_string());
            match written {
                Ok(notes) => {
                    status.info(format!("Exported {}", path.display()));
                    // What the format could not hold, to acknowledge.
                    let name = path.file_name().map_or_else(
                        || path.display().to_string(),
                        |n| n.to_string_lossy().into_owned(),
                    );
                    status
                        .warnings
                        .extend(notes.into_iter().map(|n| format!("{name}: {n}")));
                }
                Err(e) => status.error(format!("Export failed: {e}")),
            }
        }
    }
}

fn poll_file_dialog(
    mut ui: ResMut<UiState>,
    state: Res<DocState>,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<StatusMessage>,
) {
    let Some(task) = ui.dialog.as_mut() else {
        return;
    };
    let Some(result) = files::poll_dialog(task) else {
        return;
    };
    let purpose = task.purpose;
    ui.dialog = None;
    if let Some(path) = result {
        ui.path_prompt = None;
        use_path(
            purpose,
            path,
            ui.export_options,
            &state,
            &mut requests,
            &mut status,
        );
    }
    // `None`: cancelled, or the backend failed; the path prompt stays open.
}

fn on_close_requested(
    mut closes: MessageReader<WindowCloseRequested>,
    mut actions: MessageWriter<FileAction>,
) {
    if closes.read().count() > 0 {
        actions.write(FileAction::Quit);
    }
}

fn on_file_dropped(
    mut drops: MessageReader<FileDragAndDrop>,
    mut actions: MessageWriter<FileAction>,
    mut requests: MessageWriter<DocRequest>,
    mut status: ResMut<StatusMessage>,
) {
    for d in drops.read() {
        if let FileDragAndDrop::DroppedFile { path_buf, .. } = d {
            let name = path_buf.to_string_lossy().to_ascii_lowercase();
            if name.ends_with(".ron") {
                actions.write(FileAction::OpenPath(path_buf.clone()));
            } else if hedra_doc::import::IMPORT_FORMATS
                .iter()
                .any(|e| name.ends_with(&format!(".{e}")))
            {
                requests.write(DocRequest::Import(path_buf.clone()));
            } else {
                status.error(format!(
                    "{}: Hedra opens .hedra.ron scenes and imports {} files",
                    path_buf.display(),
                    hedra_doc::import::IMPORT_FORMATS
                        .iter()
                        .map(|e| format!(".{e}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
        }
    }
}

/// Adds opened and saved files to the recent list, and runs what waited for a save.
#[allow(clippy::too_many_arguments)]
fn remember_recent(
    state: Res<DocState>,
    mut last_path: Local<Option<std::path::PathBuf>>,
    mut prefs: ResMut<Preferences>,
    mut ui: ResMut<UiState>,
    mut requests: MessageWriter<DocRequest>,
    mut exit: MessageWriter<AppExit>,
) {
    if state.path != *last_path {
        *last_path = state.path.clone();
        if let Some(p) = &state.path {
            prefs.add_recent(p);
            if let Err(e) = prefs.save() {
                warn!("could not save preferences: {e}");
            }
        }
    }
    if !state.session.is_dirty()
        && let Some(p) = ui.after_save.take()
    {
        run_pending(p, &mut ui, &state, &mut requests, &mut exit);
    }
}

/// "Hedra — name.hedra.ron *" while there are unsaved changes.
fn update_title(
    state: Res<DocState>,
    mut ui: ResMut<UiState>,
    mut window: Single<&mut Window, With<PrimaryWindow>>,
) {
    let title = format!(
        "Hedra — {}{}",
        state.display_name(),
        if state.session.is_dirty() { " *" } else { "" }
    );
    if ui.last_title != title {
        window.title = title.clone();
        ui.last_title = title;
    }
}

/// Sends a command from a panel.
pub fn execute(requests: &mut MessageWriter<DocRequest>, cmd: Command) {
    requests.write(DocRequest::Execute(cmd));
}

/// The selected nodes as command references.
pub fn selected_refs(selection: &Selection) -> Vec<hedra_doc::NodeRef> {
    selection.refs()
}

/// Counts and checks of the meshes the panels show (the Mesh section's
/// statistics and validation, the topology inspector's V/E/F/L/S/H, a kept
/// mesh's non-manifold places), made
/// once per mesh instead of every frame: validating a 1M-face mesh takes
/// tens of milliseconds, and a panel drew it in every frame of a drag
/// (issue 36's frame benchmark found it). Keyed by the mesh's `Arc`, kept
/// in the key, so the address compared is always a live one.
#[derive(Default)]
pub struct MeshFacts {
    stats: Vec<(Arc<hedra_geom::HalfEdgeMesh>, Arc<hedra_geom::MeshStats>)>,
    counts: Vec<(Arc<hedra_geom::HalfEdgeMesh>, hedra_geom::TopologyCounts)>,
    places: Vec<(Arc<hedra_doc::KeptMesh>, Arc<Vec<String>>)>,
}

/// Meshes remembered per kind of fact (the edited mesh, its last step's
/// mesh, a few selected ones).
const MESH_FACTS_KEPT: usize = 4;

impl MeshFacts {
    /// The statistics (with validation) of `mesh`.
    pub fn stats(&mut self, mesh: &Arc<hedra_geom::HalfEdgeMesh>) -> Arc<hedra_geom::MeshStats> {
        remembered(&mut self.stats, mesh, |m| Arc::new(m.stats()))
    }

    /// The topology counts of `mesh`.
    pub fn counts(&mut self, mesh: &Arc<hedra_geom::HalfEdgeMesh>) -> hedra_geom::TopologyCounts {
        remembered(&mut self.counts, mesh, hedra_geom::TopologyCounts::of)
    }

    /// Where a kept mesh is not manifold, in words (numbers from 1, at
    /// most 3 places of each kind).
    pub fn places(&mut self, mesh: &Arc<hedra_doc::KeptMesh>) -> Arc<Vec<String>> {
        remembered(&mut self.places, mesh, |m| {
            let number = |v: u32| (v + 1).to_string();
            let face = |f: usize| format!("face {}", f + 1);
            Arc::new(hedra_doc::kept::describe_places(
                &m.places(),
                3,
                &number,
                &face,
            ))
        })
    }
}

/// The value for `mesh` in `memory`, made by `make` when it is not there;
/// the oldest entry goes past [`MESH_FACTS_KEPT`].
fn remembered<M, T: Clone>(
    memory: &mut Vec<(Arc<M>, T)>,
    mesh: &Arc<M>,
    make: impl FnOnce(&M) -> T,
) -> T {
    if let Some((_, value)) = memory.iter().find(|(m, _)| Arc::ptr_eq(m, mesh)) {
        return value.clone();
    }
    let value = make(mesh);
    if memory.len() >= MESH_FACTS_KEPT {
        memory.remove(0);
    }
    memory.push((mesh.clone(), value.clone()));
    value
}
