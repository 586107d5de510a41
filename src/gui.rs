//! The window: Hedra's plugin group, the windowed app, a windowless app for
//! tests (built with the `gui` feature, on by default).

// Bevy systems take their world access as parameters: long parameter lists
// and nested query types are how Bevy code is written (Bevy allows both too).
#![allow(clippy::too_many_arguments, clippy::type_complexity)]

use bevy::app::PluginGroupBuilder;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured, save_to_disk};
use bevy::window::WindowResolution;
use std::path::PathBuf;

/// Hedra's own plugins, in dependency order.
pub struct HedraPlugins;

impl PluginGroup for HedraPlugins {
    fn build(self) -> PluginGroupBuilder {
        PluginGroupBuilder::start::<Self>()
            .add(hedra_scene::ScenePlugin)
            .add(hedra_edit::EditPlugin)
            .add(hedra_viewport::ViewportPlugin)
            .add(hedra_ui::UiPlugin)
    }
}

/// Where the bundled assets (sample scenes) are: the checkout's `assets`
/// folder. Under cargo (`cargo run`, the tests) the folder cargo names at
/// run time, since a binary built in another checkout that shares the
/// target directory would otherwise read that checkout's files.
pub fn assets_dir() -> PathBuf {
    std::env::var_os("CARGO_MANIFEST_DIR")
        .map(PathBuf::from)
        .filter(|dir| dir.join("assets").is_dir())
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")))
        .join("assets")
}

/// How the window starts.
#[derive(Debug, Default, Clone)]
pub struct GuiOptions {
    /// A scene to open.
    pub file: Option<PathBuf>,
    /// Save a screenshot after `frames` frames and quit.
    pub screenshot: Option<PathBuf>,
    /// Frames to render before the screenshot is taken (`--frames`).
    pub frames: u32,
    /// Start in edit mode on this node, with these faces selected.
    pub edit: Option<(String, Option<hedra_doc::FaceSet>)>,
    /// Commands applied after opening (`--run SCRIPT`), one undo step each.
    pub run: Vec<hedra_doc::Command>,
}

/// The main window: 1280×800; closing asks about unsaved changes first
/// (hedra_ui handles the request).
fn main_window() -> WindowPlugin {
    WindowPlugin {
        primary_window: Some(Window {
            title: "Hedra".into(),
            resolution: WindowResolution::new(1280, 800),
            ..default()
        }),
        close_when_requested: false,
        ..default()
    }
}

/// The whole modeling app (every plugin, egui included) with its window
/// entity but no window system and no GPU, for tests that use it as a
/// person does: they call `App::update` frame by frame and feed keys,
/// buttons, cursor and wheel as Bevy's own input messages (`tests/gui/user.rs`).
/// Nothing is drawn; cameras, egui layout, picking and the document run as
/// in the window. `config_dir` stands for the configuration folder: the
/// preferences are read from and saved to it (defaults when it has none)
/// and recovery points go to its `recovery` folder, so a test touches
/// nothing of the user's.
pub fn windowless_gui_app(config_dir: PathBuf) -> App {
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(main_window())
            .set(bevy::render::RenderPlugin {
                render_creation: bevy::render::settings::WgpuSettings {
                    backends: None,
                    ..default()
                }
                .into(),
                ..default()
            })
            .disable::<bevy::winit::WinitPlugin>()
            .disable::<bevy::log::LogPlugin>(),
    )
    .add_plugins(HedraPlugins)
    .insert_resource(hedra_ui::SamplesDir(assets_dir().join("samples")))
    .insert_resource(hedra_ui::Preferences::load_from(Some(config_dir.clone())))
    .insert_resource(hedra_ui::recovery::Recovery::new(Some(
        config_dir.join("recovery"),
    )));
    app.finish();
    app.cleanup();
    app
}

/// The windowed modeling app.
pub fn gui_app(options: GuiOptions) -> App {
    // The window does not walk the whole mesh after every edit in a debug
    // build (the tests do); HEDRA_VALIDATE_EDITS=1 turns the check on.
    hedra_doc::command::set_validate_edits(std::env::var_os("HEDRA_VALIDATE_EDITS").is_some());
    let mut app = App::new();
    // Pipelines compile before the frame that first needs them: a new
    // cube is drawn in the frame it appears, not left out (only its cage
    // lines shown) until a background compile finishes, seconds later on
    // the software renderer.
    let render = bevy::render::RenderPlugin {
        synchronous_pipeline_compilation: true,
        ..default()
    };
    app.add_plugins(DefaultPlugins.set(main_window()).set(render))
        .add_plugins(HedraPlugins)
        .insert_resource(hedra_ui::SamplesDir(assets_dir().join("samples")));
    // Open the file, then run `--run`'s commands on it, in this order.
    let (file, commands) = (options.file, options.run);
    app.add_systems(
        Startup,
        move |mut requests: MessageWriter<hedra_scene::DocRequest>| {
            if let Some(path) = &file {
                requests.write(hedra_scene::DocRequest::Open(path.clone()));
            }
            for c in &commands {
                requests.write(hedra_scene::DocRequest::Execute(c.clone()));
            }
        },
    );
    // SIGTERM / SIGHUP / SIGINT (a logout, `kill`, Ctrl+C in the terminal)
    // end the app through an error exit, which writes the unsaved document
    // as an emergency recovery point first; a second signal ends it at once.
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    for signal in [
        signal_hook::consts::SIGTERM,
        signal_hook::consts::SIGHUP,
        signal_hook::consts::SIGINT,
    ] {
        // The second signal terminates (the flag is already set).
        let _ = signal_hook::flag::register_conditional_shutdown(signal, 1, stop.clone());
        let _ = signal_hook::flag::register(signal, stop.clone());
    }
    app.add_systems(
        Update,
        move |mut exit: MessageWriter<AppExit>, mut sent: Local<bool>| {
            if !*sent && stop.load(std::sync::atomic::Ordering::Relaxed) {
                *sent = true;
                warn!("Hedra was asked to stop by a signal; saving unsaved work for recovery");
                exit.write(AppExit::from_code(hedra_doc::recovery::STOPPED_EXIT_CODE));
            }
        },
    );
    // A panic or render error saves the last committed document first.
    let snapshot = app
        .world()
        .resource::<hedra_ui::recovery::Recovery>()
        .snapshot
        .clone();
    hedra_doc::recovery::install_emergency_save(snapshot);
    if let Some((node, faces)) = options.edit {
        app.add_systems(
            Update,
            start_in_edit_mode(node, faces).after(hedra_edit::EditSystems),
        );
    }
    if let Some(path) = options.screenshot {
        app.insert_resource(ScreenshotPlan {
            path,
            after_frames: options.frames.max(1),
            frame: 0,
            requested: false,
            done: false,
        })
        .add_systems(Update, take_screenshot);
    }
    app
}

/// `--edit NODE [--select FACES]`: once the node exists, select it, enter
/// edit mode in face mode and select the faces. On a curve or surface:
/// its control-point edit mode with every point selected.
fn start_in_edit_mode(
    node: String,
    faces: Option<hedra_doc::FaceSet>,
) -> impl FnMut(
    Res<hedra_scene::DocState>,
    ResMut<hedra_edit::Selection>,
    ResMut<hedra_edit::EditMode>,
    ResMut<hedra_edit::ShapeEdit>,
    ResMut<hedra_scene::StatusMessage>,
    Res<hedra_scene::FileJobs>,
) {
    let mut done = false;
    let mut frames = 0;
    move |state, mut selection, mut mode, mut shape_edit, mut status, jobs| {
        // The file opens on a worker thread: wait for it.
        if done || jobs.busy() {
            return;
        }
        frames += 1;
        let Some(n) = state.session.doc.find_by_name(&node) else {
            if frames == 60 {
                status.error(format!("--edit: there is no node named '{node}'"));
                done = true;
            }
            return;
        };
        done = true;
        let points = hedra_edit::shape_mode::control_points(&n.content).len() as u32;
        if points > 0 {
            selection.set([n.id]);
            shape_edit.node = Some(n.id);
            shape_edit.selected = (0..points).collect();
            return;
        }
        let Some(mesh) = n.content.mesh() else {
            status.error(format!("--edit: '{node}' is an empty: it has no edit mode"));
            return;
        };
        selection.set([n.id]);
        mode.node = Some(n.id);
        mode.kind = hedra_edit::ElementKind::Face;
        if let Some(set) = &faces {
            match set.resolve(mesh) {
                Ok(fs) => mode.selection.faces = fs.into_iter().collect(),
                Err(e) => status.error(format!("--select: {e}")),
            }
        }
    }
}

/// `--screenshot`: capture the window once after some frames, then quit.
#[derive(Resource, Debug)]
pub struct ScreenshotPlan {
    /// The PNG file the screenshot is saved to.
    pub path: PathBuf,
    /// Frames to count before the screenshot is requested.
    pub after_frames: u32,
    /// Frames counted so far; counting starts once the opened file has loaded,
    /// and the app gives up with an error 600 frames after `after_frames`.
    pub frame: u32,
    /// The screenshot has been requested (it arrives some frames later).
    pub requested: bool,
    /// The screenshot has been saved; the app exits on the next frame.
    pub done: bool,
}

fn take_screenshot(
    mut commands: Commands,
    mut plan: ResMut<ScreenshotPlan>,
    mut exit: MessageWriter<AppExit>,
    jobs: Res<hedra_scene::FileJobs>,
) {
    // Frames count once the file has opened (on a worker thread).
    if jobs.busy() && !plan.requested {
        return;
    }
    plan.frame += 1;
    if plan.done {
        exit.write(AppExit::Success);
        return;
    }
    if !plan.requested && plan.frame >= plan.after_frames {
        plan.requested = true;
        let path = plan.path.clone();
        let mut saver = save_to_disk(path);
        commands.spawn(Screenshot::primary_window()).observe(
            move |ev: On<ScreenshotCaptured>, mut plan: ResMut<ScreenshotPlan>| {
                saver(ev);
                plan.done = true;
            },
        );
    }
    if plan.frame > plan.after_frames + 600 {
        error!(
            "the screenshot was not captured after {} frames",
            plan.frame
        );
        exit.write(AppExit::error());
    }
}

/// A windowless app with the document, its projection and the edit logic,
/// for tests: no renderer, no egui.
pub fn headless_app() -> App {
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        TransformPlugin,
        bevy::input::InputPlugin,
        AssetPlugin::default(),
        bevy::mesh::MeshPlugin,
    ))
    .init_asset::<StandardMaterial>()
    .add_plugins((hedra_scene::ScenePlugin, hedra_edit::EditPlugin));
    app
}
