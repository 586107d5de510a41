//! A scripted person at the keyboard and mouse of the whole app.
//!
//! [`User`] owns [`hedra::windowless_gui_app`] (every plugin, egui
//! included, no window system) and advances it one frame per `App::update`.
//! Input goes in as Bevy's own messages, exactly as `bevy_winit` writes them:
//! the specific message (`KeyboardInput`, `MouseButtonInput`, `CursorMoved`,
//! `MouseWheel`), which drives `ButtonInput`, and the same one wrapped in a
//! `WindowEvent`, which `bevy_egui` reads; the window's cursor position is set
//! as winit sets it. A click holds the button for [`HOLD`] frames, as a
//! person's click spans several frames of the software renderer.
//!
//! Widgets are found by what they say, as a person finds them: egui's
//! AccessKit tree (what a screen reader reads) is captured every frame, so
//! `click_on("Cube")` clicks the middle of the widget labelled "Cube".

use bevy::input::ButtonState;
use bevy::input::keyboard::{Key, KeyboardInput};
use bevy::input::mouse::{MouseButtonInput, MouseScrollUnit, MouseWheel};
use bevy::input::touch::TouchPhase;
use bevy::prelude::*;
use bevy::window::{CursorMoved, PrimaryWindow, WindowEvent};
use bevy_egui::{EguiContext, EguiFullOutput, EguiPostUpdateSet, PrimaryEguiContext, egui};
use egui::accesskit;
use hedra_doc::Document;
use hedra_scene::{DocState, StatusMessage};

/// Frames a key or button stays down in a tap or click.
pub const HOLD: usize = 5;

pub struct User {
    pub app: App,
    window: Entity,
    _config: tempfile::TempDir,
}

impl User {
    /// The app after its first frames, cursor in the middle of the viewport.
    pub fn new() -> User {
        let config = tempfile::tempdir().unwrap();
        let mut app = hedra::windowless_gui_app(config.path().to_path_buf());
        let window = app
            .world_mut()
            .query_filtered::<Entity, With<PrimaryWindow>>()
            .single(app.world())
            .expect("the app has its primary window");
        app.init_resource::<Widgets>().add_systems(
            PostUpdate,
            capture_widgets
                .after(EguiPostUpdateSet::EndPass)
                .before(EguiPostUpdateSet::ProcessOutput),
        );
        let mut user = User {
            app,
            window,
            _config: config,
        };
        user.frames(2);
        user.egui().enable_accesskit();
        user.frames(1);
        user.move_to(user.viewport_center());
        user
    }

    pub fn frame(&mut self) {
        self.app.update();
    }

    /// The folder that stands for the configuration folder of this app
    /// (preferences, recovery points): the test's own.
    pub fn config_dir(&self) -> &std::path::Path {
        self._config.path()
    }

    pub fn frames(&mut self, n: usize) {
        for _ in 0..n {
            self.frame();
        }
    }

    fn write<M: Message + Clone>(&mut self, message: M, wrapped: impl FnOnce(M) -> WindowEvent) {
        let world = self.app.world_mut();
        world.write_message(message.clone());
        world.write_message(wrapped(message));
    }

    /// The 3D area between the panels, in logical pixels.
    pub fn viewport(&self) -> egui::Rect {
        self.app
            .world()
            .resource::<hedra_ui::UiState>()
            .viewport_rect
            .expect("the panels have left a viewport")
    }

    pub fn viewport_center(&self) -> Vec2 {
        let c = self.viewport().center();
        Vec2::new(c.x, c.y)
    }

    pub fn cursor(&self) -> Vec2 {
        self.app
            .world()
            .get::<Window>(self.window)
            .unwrap()
            .cursor_position()
            .unwrap_or_default()
    }

    /// A file dropped on the window (it is imported), and three frames.
    pub fn drop_file(&mut self, path: std::path::PathBuf) {
        let window = self.window;
        self.app
            .world_mut()
            .write_message(bevy::window::FileDragAndDrop::DroppedFile {
                window,
                path_buf: path,
            });
        self.frames(3);
    }

    /// Moves the pointer to `to` (logical pixels) in one frame.
    pub fn move_to(&mut self, to: Vec2) {
        let from = self.cursor();
        let mut window = self.app.world_mut().get_mut::<Window>(self.window).unwrap();
        let scale = window.resolution.scale_factor();
        window.set_physical_cursor_position(Some((to * scale).as_dvec2()));
        let window = self.window;
        self.write(
            CursorMoved {
                window,
                position: to,
                delta: Some(to - from),
            },
            WindowEvent::CursorMoved,
        );
        self.frame();
    }

    /// Moves the pointer to `to` in `steps` frames, as a hand does.
    pub fn glide_to(&mut self, to: Vec2, steps: usize) {
        let from = self.cursor();
        for i in 1..=steps {
            self.move_to(from.lerp(to, i as f32 / steps as f32));
        }
    }

    fn key(&mut self, key_code: KeyCode, state: ButtonState) {
        self.key_event(key_code, state);
        self.frame();
    }

    pub fn key_down(&mut self, key: KeyCode) {
        self.key(key, ButtonState::Pressed);
    }

    pub fn key_up(&mut self, key: KeyCode) {
        self.key(key, ButtonState::Released);
    }

    /// Presses `key` while `modifiers` are held, and lets go of all.
    pub fn shortcut(&mut self, modifiers: &[KeyCode], key: KeyCode) {
        for &m in modifiers {
            self.key_down(m);
        }
        self.key_down(key);
        self.frames(HOLD);
        self.key_up(key);
        for &m in modifiers.iter().rev() {
            self.key_up(m);
        }
        self.frames(2);
    }

    pub fn tap(&mut self, key: KeyCode) {
        self.shortcut(&[], key);
    }

    /// Writes one key event without advancing a frame.
    fn key_event(&mut self, key_code: KeyCode, state: ButtonState) {
        let (logical_key, text) = logical(key_code);
        let window = self.window;
        self.write(
            KeyboardInput {
                key_code,
                logical_key,
                state,
                text: text.filter(|_| state.is_pressed()).map(Into::into),
                repeat: false,
                window,
            },
            WindowEvent::KeyboardInput,
        );
    }

    /// Writes one mouse-button event without advancing a frame.
    fn button_event(&mut self, button: MouseButton, state: ButtonState) {
        let window = self.window;
        self.write(
            MouseButtonInput {
                button,
                state,
                window,
            },
            WindowEvent::MouseButtonInput,
        );
    }

    /// A slow frame: every key of `keys` pressed and released, in order,
    /// all arriving before the next frame (as typing does on a machine that
    /// draws a frame a second).
    pub fn taps_in_one_frame(&mut self, keys: &[KeyCode]) {
        for &k in keys {
            self.key_event(k, ButtonState::Pressed);
            self.key_event(k, ButtonState::Released);
        }
        self.frames(2);
    }

    /// `text` typed within one slow frame (digits, '.', '-').
    pub fn type_in_one_frame(&mut self, text: &str) {
        let keys: Vec<KeyCode> = text.chars().map(key_of).collect();
        self.taps_in_one_frame(&keys);
    }

    /// A chord within one slow frame: `modifiers` down, `key` pressed and
    /// released, `modifiers` up, all before the next frame.
    pub fn chord_in_one_frame(&mut self, modifiers: &[KeyCode], key: KeyCode) {
        for &m in modifiers {
            self.key_event(m, ButtonState::Pressed);
        }
        self.key_event(key, ButtonState::Pressed);
        self.key_event(key, ButtonState::Released);
        for &m in modifiers.iter().rev() {
            self.key_event(m, ButtonState::Released);
        }
        self.frames(2);
    }

    /// A click at `at` with `modifier` held, where the modifier goes down
    /// and up within the same slow frame as the click.
    pub fn modified_click_in_one_frame(&mut self, modifier: KeyCode, at: Vec2) {
        self.move_to(at);
        self.key_event(modifier, ButtonState::Pressed);
        self.button_event(MouseButton::Left, ButtonState::Pressed);
        self.button_event(MouseButton::Left, ButtonState::Released);
        self.key_event(modifier, ButtonState::Released);
        self.frames(3);
    }

    /// The pointer moves to `at` and clicks there, all within one slow
    /// frame (no frame sees the pointer at `at` before the click).
    pub fn move_and_click_in_one_frame(&mut self, at: Vec2) {
        let from = self.cursor();
        let mut window = self.app.world_mut().get_mut::<Window>(self.window).unwrap();
        let scale = window.resolution.scale_factor();
        window.set_physical_cursor_position(Some((at * scale).as_dvec2()));
        let window = self.window;
        self.write(
            CursorMoved {
                window,
                position: at,
                delta: Some(at - from),
            },
            WindowEvent::CursorMoved,
        );
        self.button_event(MouseButton::Left, ButtonState::Pressed);
        self.button_event(MouseButton::Left, ButtonState::Released);
        self.frames(3);
    }

    /// A click whose button stays down `seconds` of wall time (over a few
    /// frames), as a person's click on a loaded machine.
    pub fn click_held_seconds(&mut self, at: Vec2, seconds: f64) {
        self.move_to(at);
        self.button_down(MouseButton::Left);
        std::thread::sleep(std::time::Duration::from_secs_f64(seconds));
        self.frame();
        self.button_up(MouseButton::Left);
        self.frames(2);
    }

    /// Drags with `button` from `from` to `to` in `steps` frames, the
    /// pointer moving by absolute positions only (no raw device motion, as
    /// tablets, remote desktops and xdotool give it).
    pub fn drag_with(&mut self, button: MouseButton, from: Vec2, to: Vec2, steps: usize) {
        self.move_to(from);
        self.button_down(button);
        self.glide_to(to, steps);
        self.button_up(button);
        self.frames(2);
    }

    /// Types digits, '.', '-' (typed values of the modal tools).
    pub fn type_text(&mut self, text: &str) {
        for c in text.chars() {
            self.tap(key_of(c));
        }
    }

    fn button(&mut self, button: MouseButton, state: ButtonState) {
        self.button_event(button, state);
        self.frame();
    }

    pub fn button_down(&mut self, button: MouseButton) {
        self.button(button, ButtonState::Pressed);
    }

    pub fn button_up(&mut self, button: MouseButton) {
        self.button(button, ButtonState::Released);
    }

    /// Moves to `at`, presses the left button, holds it `hold` frames and
    /// lets go.
    pub fn click_held(&mut self, at: Vec2, hold: usize) {
        self.move_to(at);
        self.button_down(MouseButton::Left);
        self.frames(hold);
        self.button_up(MouseButton::Left);
        self.frames(2);
    }

    /// A synthetic click: press and release within one frame.
    pub fn click_instant(&mut self, at: Vec2) {
        self.move_to(at);
        for state in [ButtonState::Pressed, ButtonState::Released] {
            self.button_event(MouseButton::Left, state);
        }
        self.frames(3);
    }

    /// A person's click: the button down for [`HOLD`] frames.
    pub fn click(&mut self, at: Vec2) {
        self.click_held(at, HOLD);
    }

    /// Left-drags from `from` to `to` over `steps` frames.
    pub fn drag(&mut self, from: Vec2, to: Vec2, steps: usize) {
        self.move_to(from);
        self.button_down(MouseButton::Left);
        self.glide_to(to, steps);
        self.button_up(MouseButton::Left);
        self.frames(2);
    }

    /// Turns the wheel by `lines` notches (positive: away from the user).
    pub fn wheel(&mut self, lines: f32) {
        let window = self.window;
        self.write(
            MouseWheel {
                unit: MouseScrollUnit::Line,
                x: 0.0,
                y: lines,
                window,
                phase: TouchPhase::Moved,
            },
            WindowEvent::MouseWheel,
        );
        self.frame();
    }

    /// egui's context of the main window.
    pub fn egui(&mut self) -> egui::Context {
        let world = self.app.world_mut();
        let mut q = world.query_filtered::<&mut EguiContext, With<PrimaryEguiContext>>();
        q.single_mut(world).unwrap().get_mut().clone()
    }

    /// The widgets shown in the last frame.
    pub fn widgets(&self) -> &[Widget] {
        &self.app.world().resource::<Widgets>().0
    }

    /// The rects of the shown widgets that say `text`.
    pub fn find_all(&self, text: &str) -> Vec<egui::Rect> {
        self.widgets()
            .iter()
            .filter(|w| w.text == text)
            .map(|w| w.rect)
            .collect()
    }

    /// The middle of the one shown widget that says `text`; when several
    /// say it (a button and a text field holding the same name), the one
    /// that can be clicked (a button, a menu item, a combo box entry).
    ///
    /// # Panics
    /// When none or several say it (the message lists what is shown).
    pub fn find(&self, text: &str) -> Vec2 {
        let saying: Vec<&Widget> = self.widgets().iter().filter(|w| w.text == text).collect();
        let clickable: Vec<&Widget> = saying
            .iter()
            .copied()
            .filter(|w| {
                !matches!(
                    w.role,
                    accesskit::Role::TextInput | accesskit::Role::Label | accesskit::Role::TextRun
                )
            })
            .collect();
        match (saying.as_slice(), clickable.as_slice()) {
            ([one], _) | (_, [one]) => Vec2::new(one.rect.center().x, one.rect.center().y),
            _ => {
                let mut shown: Vec<&str> = self.widgets().iter().map(|w| w.text.as_str()).collect();
                shown.sort();
                shown.dedup();
                panic!(
                    "{} widgets say '{text}' ({saying:?}); shown: {shown:?}",
                    saying.len()
                )
            }
        }
    }

    pub fn shows(&self, text: &str) -> bool {
        !self.find_all(text).is_empty()
    }

    /// A person's click on the widget that says `text`.
    pub fn click_on(&mut self, text: &str) {
        let at = self.find(text);
        self.click(at);
    }

    /// Where the world point `p` is seen in the window, in logical pixels.
    pub fn screen_of(&mut self, p: Vec3) -> Vec2 {
        self.try_screen_of(p)
            .unwrap_or_else(|| panic!("{p} is not in view"))
    }

    /// [`screen_of`](Self::screen_of), `None` when `p` is behind the camera
    /// or outside its view.
    pub fn try_screen_of(&mut self, p: Vec3) -> Option<Vec2> {
        let world = self.app.world_mut();
        let mut q = world
            .query_filtered::<(&Camera, &GlobalTransform), With<hedra_scene::ViewportCamera>>();
        let (camera, transform) = q.single(world).unwrap();
        camera.world_to_viewport(transform, p).ok()
    }

    /// Shift+A with the pointer at `at`: the Add menu opens there.
    pub fn open_add_menu_at(&mut self, at: Vec2) {
        self.move_to(at);
        self.shortcut(&[KeyCode::ShiftLeft], KeyCode::KeyA);
        assert!(self.shows("Cube"), "Shift+A shows the Add menu");
    }

    /// A click on `item` of the open Add menu, through its Curve ▸ or
    /// Surface ▸ submenu when it is in one.
    pub fn choose_add(&mut self, item: &str) {
        for submenu in ["Curve ⏵", "⏴ Back", "Surface ⏵"] {
            if self.shows(item) {
                break;
            }
            self.click_on(submenu);
        }
        self.click_on(item);
    }

    /// Shift+A over the viewport's centre and a click on `item`.
    pub fn add(&mut self, item: &str) {
        let before = self.doc().nodes().count();
        let at = self.viewport_center();
        self.open_add_menu_at(at);
        self.choose_add(item);
        assert_eq!(
            self.doc().nodes().count(),
            before + 1,
            "Add ▸ {item}: {}",
            self.status()
        );
    }

    /// The (vertices, edges, faces) of the first mesh node.
    pub fn mesh_counts(&self) -> (usize, usize, usize) {
        let m = self.first_mesh();
        (m.vertex_count(), m.edge_count(), m.face_count())
    }

    pub fn first_mesh(&self) -> &hedra_geom::HalfEdgeMesh {
        self.doc()
            .nodes()
            .find_map(|n| n.content.mesh())
            .expect("the scene has a mesh")
    }

    pub fn edit_mode(&self) -> &hedra_edit::EditMode {
        self.app.world().resource::<hedra_edit::EditMode>()
    }

    pub fn doc(&self) -> &Document {
        &self.app.world().resource::<DocState>().session.doc
    }

    /// The steps Ctrl+Z can undo, oldest first.
    fn done(&self) -> &[hedra_doc::Transaction] {
        self.app
            .world()
            .resource::<DocState>()
            .session
            .history
            .done()
    }

    /// The command of the last undo step, if it has one.
    pub fn doc_last_command(&self) -> Option<hedra_doc::Command> {
        self.done().last().and_then(|t| t.command.clone())
    }

    pub fn undo_steps(&self) -> usize {
        self.done().len()
    }

    pub fn status(&self) -> String {
        format!("{:?}", self.app.world().resource::<StatusMessage>())
    }

    /// The positions of the first node's render mesh: its own, or those of
    /// its surface patches one after the other.
    pub fn render_positions(&self) -> Vec<Vec3> {
        let world = self.app.world();
        let entity = *world
            .resource::<hedra_scene::NodeEntities>()
            .0
            .values()
            .next()
            .expect("a node");
        let own = world.get::<Mesh3d>(entity).map(|m| m.0.clone());
        let patches = world
            .get::<Children>(entity)
            .into_iter()
            .flatten()
            .filter(|c| world.get::<hedra_scene::SurfacePatch>(**c).is_some())
            .filter_map(|c| world.get::<Mesh3d>(*c).map(|m| m.0.clone()));
        let handles: Vec<_> = own.into_iter().chain(patches).collect();
        assert!(!handles.is_empty(), "the node has a render mesh");
        let meshes = world.resource::<Assets<Mesh>>();
        handles
            .iter()
            .flat_map(
                |h| match meshes.get(h).unwrap().attribute(Mesh::ATTRIBUTE_POSITION) {
                    Some(bevy::mesh::VertexAttributeValues::Float32x3(p)) => {
                        p.iter().map(|q| Vec3::from(*q)).collect::<Vec<_>>()
                    }
                    _ => panic!("positions"),
                },
            )
            .collect()
    }

    /// The control-point entities of the first node, by index.
    pub fn control_point_entities(&mut self) -> Vec<hedra_scene::ControlPoint> {
        let world = self.app.world_mut();
        let entity = *world
            .resource::<hedra_scene::NodeEntities>()
            .0
            .values()
            .next()
            .expect("a node");
        let mut q = world.query::<(&hedra_scene::ControlPoint, &ChildOf)>();
        let mut points: Vec<_> = q
            .iter(world)
            .filter(|(_, c)| c.parent() == entity)
            .map(|(p, _)| *p)
            .collect();
        points.sort_by_key(|p| p.index);
        points
    }

    /// The names of the document's nodes, in id order.
    pub fn node_names(&self) -> Vec<String> {
        self.doc().nodes().map(|n| n.name.clone()).collect()
    }
}

/// A widget as a screen reader sees it: its text (label or value), its
/// role and where it is, in logical pixels.
#[derive(Debug, Clone)]
pub struct Widget {
    pub text: String,
    pub role: accesskit::Role,
    pub rect: egui::Rect,
}

#[derive(Resource, Default)]
struct Widgets(Vec<Widget>);

/// Keeps the widgets of the AccessKit tree egui wrote this frame.
fn capture_widgets(
    outputs: Query<&EguiFullOutput, With<PrimaryEguiContext>>,
    mut widgets: ResMut<Widgets>,
) {
    let Some(update) = outputs
        .iter()
        .find_map(|o| o.0.as_ref()?.platform_output.accesskit_update.as_ref())
    else {
        return;
    };
    widgets.0 = update
        .nodes
        .iter()
        .filter_map(|(_, node)| {
            let text = node.label().or(node.value())?.to_string();
            let b = node.bounds()?;
            Some(Widget {
                text,
                role: node.role(),
                rect: egui::Rect::from_min_max(
                    egui::pos2(b.x0 as f32, b.y0 as f32),
                    egui::pos2(b.x1 as f32, b.y1 as f32),
                ),
            })
        })
        .collect();
}

const DIGITS: [KeyCode; 10] = [
    KeyCode::Digit0,
    KeyCode::Digit1,
    KeyCode::Digit2,
    KeyCode::Digit3,
    KeyCode::Digit4,
    KeyCode::Digit5,
    KeyCode::Digit6,
    KeyCode::Digit7,
    KeyCode::Digit8,
    KeyCode::Digit9,
];

/// The key that types `c` (digits, '.', '-', lower-case letters, '/').
pub fn key_of(c: char) -> KeyCode {
    match c {
        '0'..='9' => DIGITS[c as usize - '0' as usize],
        '.' => KeyCode::Period,
        '-' => KeyCode::Minus,
        '/' => KeyCode::Slash,
        'a'..='z' => LETTER_CODES[c as usize - 'a' as usize],
        other => panic!("no key for '{other}'"),
    }
}

const LETTER_CODES: [KeyCode; 26] = [
    KeyCode::KeyA,
    KeyCode::KeyB,
    KeyCode::KeyC,
    KeyCode::KeyD,
    KeyCode::KeyE,
    KeyCode::KeyF,
    KeyCode::KeyG,
    KeyCode::KeyH,
    KeyCode::KeyI,
    KeyCode::KeyJ,
    KeyCode::KeyK,
    KeyCode::KeyL,
    KeyCode::KeyM,
    KeyCode::KeyN,
    KeyCode::KeyO,
    KeyCode::KeyP,
    KeyCode::KeyQ,
    KeyCode::KeyR,
    KeyCode::KeyS,
    KeyCode::KeyT,
    KeyCode::KeyU,
    KeyCode::KeyV,
    KeyCode::KeyW,
    KeyCode::KeyX,
    KeyCode::KeyY,
    KeyCode::KeyZ,
];

/// The logical key and text a US keyboard gives for `code`.
fn logical(code: KeyCode) -> (Key, Option<&'static str>) {
    let character = |c: &'static str| (Key::Character(c.into()), Some(c));
    const LETTERS: &str = "abcdefghijklmnopqrstuvwxyz";
    const NUMBERS: &str = "0123456789";
    if let Some(i) = LETTER_CODES.iter().position(|&k| k == code) {
        return character(&LETTERS[i..=i]);
    }
    if let Some(i) = DIGITS.iter().position(|&k| k == code) {
        return character(&NUMBERS[i..=i]);
    }
    match code {
        KeyCode::Period | KeyCode::NumpadDecimal => character("."),
        KeyCode::Minus | KeyCode::NumpadSubtract => character("-"),
        KeyCode::Slash => character("/"),
        KeyCode::NumpadAdd => character("+"),
        KeyCode::Enter | KeyCode::NumpadEnter => (Key::Enter, None),
        KeyCode::Escape => (Key::Escape, None),
        KeyCode::Tab => (Key::Tab, None),
        KeyCode::Space => (Key::Space, Some(" ")),
        KeyCode::Delete => (Key::Delete, None),
        KeyCode::Backspace => (Key::Backspace, None),
        KeyCode::ShiftLeft | KeyCode::ShiftRight => (Key::Shift, None),
        KeyCode::ControlLeft | KeyCode::ControlRight => (Key::Control, None),
        KeyCode::AltLeft | KeyCode::AltRight => (Key::Alt, None),
        KeyCode::Numpad1 => character("1"),
        KeyCode::Numpad3 => character("3"),
        KeyCode::Numpad7 => character("7"),
        _ => (
            Key::Unidentified(bevy::input::keyboard::NativeKey::Unidentified),
            None,
        ),
    }
}
