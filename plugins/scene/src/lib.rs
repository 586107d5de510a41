//! The document inside the app, and its projection into the ECS.
//!
//! [`DocState`] holds the one [`Session`]; [`DocRequest`] messages are the
//! only way to change it, and [`apply_requests`] is the only system that
//! applies them. The projection mirrors the document, with the previews of
//! running tools ([`Previews`]) over it: [`sync_entities`] keeps one entity
//! per node (`Name`, `Visibility`, `ChildOf`), [`project_transforms`] is the
//! one writer of their `Transform`, [`project_render_meshes`] of mesh nodes'
//! render meshes, [`project_control_points`] of the control-point child
//! entities of curves and surfaces, [`project_surface_patches`] of the patch
//! child entities that draw surfaces. One file each: `apply` (the one writer of the document),
//! `preview` (what tools show, as data), `projection` (entities and their
//! render meshes), `shape_entities` (control points and surface patches),
//! `render_mesh` (building meshes from content), `smooth`
//! (subdivision previews refined in the background).

// Bevy systems take their world access as parameters: long parameter lists
// and nested query types are how Bevy code is written (Bevy allows both too).
#![allow(clippy::too_many_arguments, clippy::type_complexity)]

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use hedra_doc::file;
use hedra_doc::{Command, NodeContent, NodeId, Session, Shading};
use hedra_geom::HalfEdgeMesh;
use std::collections::HashMap;
use std::path::PathBuf;

mod apply;
mod decimate_jobs;
mod file_jobs;
mod preview;
mod projection;
mod render_mesh;
mod render_projection;
mod requests;
mod shape_entities;
mod shown;
mod smooth;
mod strokes;

pub use apply::*;
pub use decimate_jobs::BACKGROUND_DECIMATE_FACES;
pub use file_jobs::FileJobs;
use file_jobs::FinishedFile;
pub use preview::*;
pub use projection::*;
pub use render_mesh::*;
pub use render_projection::*;
pub use requests::*;
pub use shape_entities::*;
pub use shown::*;
pub use smooth::{SmoothPreviews, SmoothSource};
pub use strokes::{Strokes, record_strokes};

/// The open document, where it lives on disk, and a change counter.
#[derive(Resource, Default)]
pub struct DocState {
    /// The document with its undo history; changed only by [`apply_requests`].
    pub session: Session,
    /// The file the document was opened from or last saved to (a recovered
    /// document keeps its original file); `None` for a new, never saved one.
    pub path: Option<PathBuf>,
    /// Increases on every change of the document (command, undo, load, …).
    pub revision: u64,
    /// History serial when this document was created or opened: steps up to
    /// it were made in an earlier session (no "adjust last operation" for them).
    pub opened_serial: u64,
}

impl DocState {
    /// The file name for titles ("untitled" before the first save).
    pub fn display_name(&self) -> String {
        self.path.as_ref().and_then(|p| p.file_name()).map_or_else(
            || "untitled".to_string(),
            |n| n.to_string_lossy().into_owned(),
        )
    }
}

/// A request to change the document or its file. Sent by tools, panels and
/// shortcuts; applied in order by [`apply_requests`].
#[derive(Message, Clone, Debug)]
pub enum DocRequest {
    /// Run a document command as one undo step.
    Execute(Command),
    /// Re-run the last step with changed parameters.
    AdjustLast(Command),
    /// Undo the last step (nothing when there is none).
    Undo,
    /// Redo the last undone step (nothing when there is none).
    Redo,
    /// Undo or redo until this many steps are done.
    JumpTo(usize),
    /// Replace the document with an empty one (callers ask about unsaved changes first).
    New,
    /// Load a scene file on a worker thread; it replaces the document when it
    /// has been read.
    Open(PathBuf),
    /// Load a sample scene as [`Open`](Self::Open) does, as a new untitled
    /// scene: Save then asks where to keep it, so that the sample (part of
    /// the installation) is never overwritten.
    OpenSample(PathBuf),
    /// Write the document to this file on a worker thread; the document's path
    /// becomes it when the write succeeds.
    Save(PathBuf),
    /// Add the meshes of an OBJ file as new nodes (one step).
    Import(PathBuf),
    /// Replace the document with a recovery point (autosave or emergency
    /// save); it belongs to its original file and is unsaved.
    Recover(hedra_doc::recovery::RecoveryEntry),
    /// Undo history limits from the preferences (steps, approximate bytes).
    HistoryLimits {
        /// At most this many undo steps (at least 1 is kept).
        steps: usize,
        /// At most about this many bytes of undo history (the newest step is
        /// always kept).
        bytes: usize,
    },
}

/// Sent after a request changed the document.
#[derive(Message, Clone, Debug, Default)]
pub struct DocChanged {
    /// Nodes the change created (tools select them).
    pub created: Vec<NodeId>,
    /// True when a new document replaced the old one (New/Open).
    pub replaced: bool,
}

/// The user-facing outcome of the latest request (status bar, error popups).
#[derive(Resource, Default, Debug)]
pub struct StatusMessage {
    /// The message shown in the status bar.
    pub text: String,
    /// True when `text` reports a failure (shown in red).
    pub is_error: bool,
    /// Warnings that need acknowledging (damaged history, …).
    pub warnings: Vec<String>,
    /// Increases with every [`info`](Self::info) and [`error`](Self::error),
    /// so a message repeated with the same text can still be told apart as new.
    pub serial: u64,
}

impl StatusMessage {
    /// Shows `text` as a normal message.
    pub fn info(&mut self, text: impl Into<String>) {
        self.text = text.into();
        self.is_error = false;
        self.serial += 1;
    }
    /// Shows `text` as an error.
    pub fn error(&mut self, text: impl Into<String>) {
        self.text = text.into();
        self.is_error = true;
        self.serial += 1;
    }
}

/// The material every mesh node uses.
#[derive(Resource, Clone)]
pub struct MeshMaterial(pub Handle<StandardMaterial>);

/// The 3D cursor's world position (Blender's): Shift+right click places
/// it, new objects are added there, and the View menu moves it.
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq)]
pub struct Cursor3d(pub glam::DVec3);

/// Quad view (Blender's Ctrl+Alt+Q): the viewport split in four, top,
/// front and right orthographic views beside the perspective one.
#[derive(Resource, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct QuadView(pub bool);

/// How the viewport draws meshes and surfaces, as Blender's shading
/// header: Shift+Z toggles wireframe, Alt+Z X-ray (View menu too).
#[derive(Resource, Debug, Clone, Copy, PartialEq, Eq)]
pub struct ViewportShading {
    /// Faces are not drawn: only the edge overlays show (Blender's
    /// Wireframe shading); like Blender's, it sees and selects through.
    pub wireframe: bool,
    /// Faces are see-through ([`X_RAY_ALPHA`]) and edit-mode box select
    /// takes the elements behind them too.
    pub x_ray: bool,
    /// Blender's Face Orientation overlay: front faces blue, back faces
    /// red, to find flipped normals (View menu).
    pub face_orientation: bool,
    /// How opaque faces are in X-ray, in percent (View ▸ X-ray opacity;
    /// [`X_RAY_ALPHA`] by default).
    pub x_ray_opacity: u8,
    /// Draw the cage's edges over meshes shown smoothed or through
    /// modifiers (View ▸ Cages; on by default); each subdivision modifier
    /// can also hide its own (Show cage).
    pub cages: bool,
}

impl Default for ViewportShading {
    fn default() -> Self {
        ViewportShading {
            wireframe: false,
            x_ray: false,
            face_orientation: false,
            x_ray_opacity: (X_RAY_ALPHA * 100.0).round() as u8,
            cages: true,
        }
    }
}

impl ViewportShading {
    /// Whether what is behind a face shows and can be selected.
    pub fn see_through(&self) -> bool {
        self.wireframe || self.x_ray
    }

    /// The alpha of the shared mesh material: 0 in wireframe, the X-ray
    /// opacity in X-ray, 1 when solid.
    pub fn face_alpha(&self) -> f32 {
        if self.wireframe {
            0.0
        } else if self.x_ray {
            f32::from(self.x_ray_opacity.min(100)) / 100.0
        } else {
            1.0
        }
    }
}

/// How opaque faces are in X-ray shading by default (Blender's default is
/// 0.5; lower here because the cage's edges are drawn over it).
pub const X_RAY_ALPHA: f32 = 0.35;

/// The two materials of the face orientation overlay: unlit blue drawn
/// on front faces only, unlit red on back faces only.
#[derive(Resource, Clone)]
pub struct FaceOrientationMaterials {
    /// Blue, back faces culled: put on the mesh entities themselves.
    pub front: Handle<StandardMaterial>,
    /// Red, front faces culled: on each mesh entity's [`BackFaces`] child.
    pub back: Handle<StandardMaterial>,
}

/// A child entity that draws its parent's render mesh again with the red
/// back-face material while the face orientation overlay is on.
#[derive(Component, Debug)]
pub struct BackFaces;

fn setup_face_orientation(mut commands: Commands, mut materials: ResMut<Assets<StandardMaterial>>) {
    let side = |color: Color, cull: bevy::render::render_resource::Face| StandardMaterial {
        base_color: color,
        unlit: true,
        cull_mode: Some(cull),
        ..default()
    };
    use bevy::render::render_resource::Face;
    commands.insert_resource(FaceOrientationMaterials {
        front: materials.add(side(Color::srgb(0.25, 0.4, 0.85), Face::Back)),
        back: materials.add(side(Color::srgb(0.8, 0.2, 0.2), Face::Front)),
    });
}

/// The material model meshes (mesh nodes and surface patches) are drawn
/// with: the shared one, or the blue front one while the face orientation
/// overlay is on. Their writers (`project_render_meshes`,
/// `project_surface_patches`) put it on; nothing else writes their
/// `MeshMaterial3d`.
pub fn model_material(
    shared: &MeshMaterial,
    orientation: Option<&FaceOrientationMaterials>,
    shading: &ViewportShading,
) -> MeshMaterial {
    match orientation {
        Some(o) if shading.face_orientation => MeshMaterial(o.front.clone()),
        _ => MeshMaterial(shared.0.clone()),
    }
}

/// Puts `chosen` on every entity of `entities` whose material differs,
/// when the shading changed (the face orientation overlay turned on or
/// off): the refresh pass of a model mesh writer.
pub(crate) fn refresh_materials<F: bevy::ecs::query::QueryFilter>(
    commands: &mut Commands,
    shading: &Res<ViewportShading>,
    chosen: Option<&MeshMaterial>,
    entities: &Query<(Entity, &MeshMaterial3d<StandardMaterial>), F>,
) {
    let Some(chosen) = chosen.filter(|_| shading.is_changed()) else {
        return;
    };
    for (e, m) in entities {
        if m.0 != chosen.0 {
            commands.entity(e).insert(MeshMaterial3d(chosen.0.clone()));
        }
    }
}

/// The red half of the face orientation overlay: while it is on, each
/// model mesh (drawn with the blue front material by its own writer) gets
/// a [`BackFaces`] child with the same mesh in red, front faces culled;
/// turned off, the children go. Writes only its children.
#[allow(clippy::type_complexity)]
fn project_face_orientation(
    mut commands: Commands,
    shading: Res<ViewportShading>,
    orientation: Option<Res<FaceOrientationMaterials>>,
    meshes: Query<(Entity, &Mesh3d, &MeshMaterial3d<StandardMaterial>), Without<BackFaces>>,
    backs: Query<(Entity, &Mesh3d, &ChildOf), With<BackFaces>>,
) {
    let Some(orientation) = orientation else {
        return;
    };
    if !shading.face_orientation {
        for (e, _, _) in &backs {
            commands.entity(e).despawn();
        }
        return;
    }
    let mut with_back = std::collections::HashSet::new();
    for (e, mesh, parent) in &backs {
        match meshes.get(parent.parent()) {
            Ok((_, parent_mesh, m)) if m.0 == orientation.front => {
                with_back.insert(parent.parent());
                if parent_mesh.0 != mesh.0 {
                    commands.entity(e).insert(Mesh3d(parent_mesh.0.clone()));
                }
            }
            _ => commands.entity(e).despawn(),
        }
    }
    for (e, mesh, m) in &meshes {
        if m.0 == orientation.front && !with_back.contains(&e) {
            commands.spawn((
                BackFaces,
                Mesh3d(mesh.0.clone()),
                MeshMaterial3d(orientation.back.clone()),
                Transform::IDENTITY,
                ChildOf(e),
            ));
        }
    }
}

/// Puts the shading on the shared mesh material: blended and faded for
/// X-ray, fully transparent for wireframe, opaque when solid.
fn apply_viewport_shading(
    shading: Res<ViewportShading>,
    material: Option<Res<MeshMaterial>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    let Some(material) = material else { return };
    let Some(mut m) = materials.get_mut(&material.0) else {
        return;
    };
    let alpha = shading.face_alpha();
    m.base_color.set_alpha(alpha);
    m.alpha_mode = if alpha < 1.0 {
        AlphaMode::Blend
    } else {
        AlphaMode::Opaque
    };
}

/// The stages of a frame's `Update`, in order (configured by
/// [`ScenePlugin`]); every plugin puts its systems into one of them, inside
/// its own set (`EditSystems`, `ViewportSystems`, `UiSystems`, …):
/// input (Bevy's `PreUpdate`) → `Requests` → `Tools` → `Apply` → `Sync` →
/// `View` → render (Bevy's `PostUpdate`, egui).
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub enum SceneSystems {
    /// Each plugin applies the messages the panels sent it in the last frame
    /// (settings, selection, tools to start: see [`requests`](crate::ChangeSetting))
    /// to the state it owns, before any tool reads this frame's input.
    Requests,
    /// Tools, shortcuts and panels' input handlers read this frame's input,
    /// show previews ([`Previews`]) and write [`DocRequest`]s.
    Tools,
    /// Applies [`DocRequest`]s: the one writer of the document.
    Apply,
    /// The projection: mirrors the document and the tools' previews into
    /// entities, components and render meshes; smooth previews finish here.
    Sync,
    /// Systems that follow the projected document: viewport overlays and
    /// camera, autosave.
    View,
}

/// Document state, the apply system and the ECS projection.
pub struct ScenePlugin;

impl Plugin for ScenePlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<DocState>()
            .init_resource::<StatusMessage>()
            .init_resource::<NodeEntities>()
            .init_resource::<SmoothPreviews>()
            .init_resource::<Previews>()
            .init_resource::<FileJobs>()
            .init_resource::<InputGate>()
            .init_resource::<ViewportShading>()
            .init_resource::<QuadView>()
            .init_resource::<ViewportShading>()
            .init_resource::<QuadView>()
            .init_resource::<Cursor3d>()
            .add_setting::<ViewportShading>()
            .add_setting::<QuadView>()
            .add_setting::<Cursor3d>()
            .init_resource::<Strokes>()
            .add_systems(PreUpdate, record_strokes.after(bevy::input::InputSystems))
            .add_message::<DocRequest>()
            .add_message::<DocChanged>()
            .add_message::<StatusRequest>()
            .add_message::<PreviewRequest>()
            .configure_sets(
                Update,
                (
                    SceneSystems::Requests,
                    SceneSystems::Tools,
                    SceneSystems::Apply,
                    SceneSystems::Sync,
                    SceneSystems::View,
                )
                    .chain(),
            )
            .add_systems(Startup, (setup_material, setup_face_orientation))
            .add_systems(
                Update,
                (apply_status_requests, apply_preview_requests).in_set(SceneSystems::Requests),
            )
            .add_systems(Update, apply_requests.in_set(SceneSystems::Apply))
            .add_systems(
                Update,
                follow_csg_previews
                    .in_set(SceneSystems::Apply)
                    .after(apply_requests),
            )
            .add_systems(
                Update,
                decimate_jobs::escape_cancels_background_jobs.in_set(SceneSystems::Tools),
            )
            .add_systems(
                Update,
                (
                    apply_viewport_shading.run_if(resource_changed::<ViewportShading>),
                    project_face_orientation,
                )
                    .in_set(SceneSystems::View),
            )
            .add_systems(Last, file_jobs::finish_saves_on_exit)
            .add_systems(
                Update,
                (
                    sync_entities,
                    project_shown_meshes,
                    project_shown_shapes,
                    project_transforms,
                    project_render_meshes,
                    project_control_points,
                    project_surface_patches,
                )
                    .chain()
                    .in_set(SceneSystems::Sync),
            );
    }
}

fn setup_material(mut commands: Commands, mut materials: ResMut<Assets<StandardMaterial>>) {
    let handle = materials.add(StandardMaterial {
        base_color: Color::srgb(0.72, 0.72, 0.75),
        perceptual_roughness: 0.55,
        // Open meshes (planes, grids, holes) show their back faces too.
        double_sided: true,
        cull_mode: None,
        ..default()
    });
    commands.insert_resource(MeshMaterial(handle));
}

/// Whether viewport tools may use the pointer and keyboard this frame; the
/// UI clears these while the pointer is over a panel or a text field has focus.
#[derive(Resource, Debug, Clone, Copy)]
pub struct InputGate {
    /// False while the pointer is not over the 3D view (over a panel, or
    /// outside the window) or egui is using it (a drag started in a panel).
    pub pointer_free: bool,
    /// False while an egui widget (such as a text field) takes keyboard input.
    pub keyboard_free: bool,
}

impl Default for InputGate {
    fn default() -> Self {
        InputGate {
            pointer_free: true,
            keyboard_free: true,
        }
    }
}

/// Marks the 3D camera the viewport renders and tools cast rays from.
#[derive(Component, Debug, Default)]
pub struct ViewportCamera;

/// The world ray (origin, unit direction, in `f64`) of `camera` through
/// window point `p` (logical pixels).
pub fn camera_ray(
    camera: &Camera,
    transform: &GlobalTransform,
    p: Vec2,
) -> Option<(glam::DVec3, glam::DVec3)> {
    let ray = camera.viewport_to_world(transform, p).ok()?;
    Some((ray.origin.as_dvec3(), Vec3::from(ray.direction).as_dvec3()))
}

/// The primary window and the viewport camera: what a system needs to
/// work under the pointer (where it is, the ray through it, where a world
/// point shows). One parameter instead of the window and camera queries
/// every tool used to take and turn into a ray itself.
#[derive(bevy::ecs::system::SystemParam)]
pub struct ViewportPointer<'w, 's> {
    window: Single<'w, 's, &'static Window, With<bevy::window::PrimaryWindow>>,
    camera: Single<'w, 's, (&'static Camera, &'static GlobalTransform), With<ViewportCamera>>,
}

impl ViewportPointer<'_, '_> {
    /// The primary window.
    pub fn window(&self) -> &Window {
        &self.window
    }
    /// The viewport camera and its world transform.
    pub fn camera(&self) -> (&Camera, &GlobalTransform) {
        *self.camera
    }
    /// The pointer in window coordinates (logical pixels), when it is over
    /// the window.
    pub fn cursor(&self) -> Option<Vec2> {
        self.window.cursor_position()
    }
    /// The world ray (origin, unit direction) through window point `p`.
    pub fn ray_at(&self, p: Vec2) -> Option<(glam::DVec3, glam::DVec3)> {
        let (camera, transform) = self.camera();
        camera_ray(camera, transform, p)
    }
    /// The world ray under the pointer.
    pub fn ray(&self) -> Option<(glam::DVec3, glam::DVec3)> {
        self.ray_at(self.cursor()?)
    }
}

/// Modifier keys, counted as held when pressed or released this frame too
/// (a quick Ctrl+S can press and release Ctrl within one or two frames).
pub mod modifiers {
    use bevy::prelude::*;

    fn held(keys: &ButtonInput<KeyCode>, pair: [KeyCode; 2]) -> bool {
        keys.any_pressed(pair) || keys.any_just_pressed(pair) || keys.any_just_released(pair)
    }
    /// Ctrl (or the Super/Command key).
    pub fn ctrl(keys: &ButtonInput<KeyCode>) -> bool {
        held(keys, [KeyCode::ControlLeft, KeyCode::ControlRight])
            || held(keys, [KeyCode::SuperLeft, KeyCode::SuperRight])
    }
    /// Shift (left or right).
    pub fn shift(keys: &ButtonInput<KeyCode>) -> bool {
        held(keys, [KeyCode::ShiftLeft, KeyCode::ShiftRight])
    }
    /// Alt (left or right; Option on macOS).
    pub fn alt(keys: &ButtonInput<KeyCode>) -> bool {
        held(keys, [KeyCode::AltLeft, KeyCode::AltRight])
    }
}
