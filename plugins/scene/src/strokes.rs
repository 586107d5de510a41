//! This frame's keys and mouse buttons in the order they arrived, each with
//! the modifier keys held at that moment.
//!
//! `ButtonInput` keeps a set per frame: on a slow frame several keys arrive
//! together (typing `21` after G X under lag), and the set loses their order
//! and their repeats (`100` became `10`), and a Shift pressed and let go
//! within the frame is gone by the time a click is read. `bevy_winit` writes
//! every keyboard, button and pointer event wrapped in one `WindowEvent`
//! stream as well, in the order the window system gave them: that stream is
//! read here.

use bevy::input::ButtonState;
use bevy::input::keyboard::{Key, KeyboardFocusLost, KeyboardInput};
use bevy::prelude::*;
use bevy::window::WindowEvent;

/// Which modifier keys are held.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HeldModifiers {
    /// Ctrl (or the Super/Command key).
    pub ctrl: bool,
    /// Shift.
    pub shift: bool,
    /// Alt (Option on macOS).
    pub alt: bool,
}

impl HeldModifiers {
    /// Follows one keyboard event: a modifier's press or release changes
    /// what is held; other keys leave it as it is.
    pub fn follow(&mut self, event: &KeyboardInput) {
        let down = event.state == ButtonState::Pressed;
        match (&event.logical_key, event.key_code) {
            (Key::Shift, _) | (_, KeyCode::ShiftLeft | KeyCode::ShiftRight) => self.shift = down,
            (Key::Control | Key::Super | Key::Meta, _)
            | (
                _,
                KeyCode::ControlLeft
                | KeyCode::ControlRight
                | KeyCode::SuperLeft
                | KeyCode::SuperRight,
            ) => self.ctrl = down,
            (Key::Alt, _) | (_, KeyCode::AltLeft | KeyCode::AltRight) => self.alt = down,
            _ => {}
        }
    }
}

/// One key or mouse-button event of this frame.
#[derive(Clone, Debug, PartialEq)]
pub enum Stroke {
    /// A key went down (`pressed`) or up.
    Key {
        /// The physical key.
        code: KeyCode,
        /// Down or up.
        pressed: bool,
        /// The modifiers held when it happened (a modifier's own press is
        /// already counted).
        modifiers: HeldModifiers,
    },
    /// A mouse button went down or up.
    Button {
        /// Which button.
        button: MouseButton,
        /// Down or up.
        pressed: bool,
        /// The modifiers held when it happened.
        modifiers: HeldModifiers,
    },
}

/// This frame's [`Stroke`]s in arrival order; written once a frame in
/// `PreUpdate` by [`record_strokes`], read by tools that type numbers or need
/// the modifiers of a click.
#[derive(Resource, Debug, Default)]
pub struct Strokes {
    /// The events, oldest first.
    pub events: Vec<Stroke>,
    /// What is held after the last event (carried across frames).
    held: HeldModifiers,
    /// The modifiers held at each button's last press (carried across
    /// frames: a click is read on release, its modifiers are the press's).
    at_press: Vec<(MouseButton, HeldModifiers)>,
}

impl Strokes {
    /// The keys pressed this frame, in order, repeats kept.
    pub fn key_presses(&self) -> impl Iterator<Item = (KeyCode, HeldModifiers)> + '_ {
        self.events.iter().filter_map(|s| match *s {
            Stroke::Key {
                code,
                pressed: true,
                modifiers,
            } => Some((code, modifiers)),
            _ => None,
        })
    }

    /// The modifiers that were held when `button` was last pressed (this
    /// frame or earlier); none held if it never was.
    pub fn modifiers_at_press(&self, button: MouseButton) -> HeldModifiers {
        self.at_press
            .iter()
            .find(|(b, _)| *b == button)
            .map(|(_, m)| *m)
            .unwrap_or_default()
    }

    /// What is held now, after this frame's events.
    pub fn held(&self) -> HeldModifiers {
        self.held
    }

    /// Adds one window event (keyboard and button events; others are
    /// ignored).
    pub fn push(&mut self, event: &WindowEvent) {
        match event {
            WindowEvent::KeyboardInput(key) => {
                self.held.follow(key);
                self.events.push(Stroke::Key {
                    code: key.key_code,
                    pressed: key.state == ButtonState::Pressed,
                    modifiers: self.held,
                });
            }
            WindowEvent::MouseButtonInput(b) => {
                let pressed = b.state == ButtonState::Pressed;
                if pressed {
                    self.at_press.retain(|(button, _)| *button != b.button);
                    self.at_press.push((b.button, self.held));
                }
                self.events.push(Stroke::Button {
                    button: b.button,
                    pressed,
                    modifiers: self.held,
                });
            }
            _ => {}
        }
    }
}

/// Rebuilds [`Strokes`] from this frame's window events.
pub fn record_strokes(
    mut events: MessageReader<WindowEvent>,
    mut focus_lost: MessageReader<KeyboardFocusLost>,
    mut strokes: ResMut<Strokes>,
) {
    strokes.events.clear();
    if focus_lost.read().count() > 0 {
        // Keys let go in another window never come back as releases.
        strokes.held = HeldModifiers::default();
    }
    for event in events.read() {
        strokes.push(event);
    }
}
