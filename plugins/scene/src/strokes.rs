//! This frame's key presses in the order they arrived.
//!
//! `ButtonInput` keeps a set per frame: on a slow frame several keys arrive
//! together (typing `21` after G X under lag), and the set loses their
//! order and their repeats (`100` became `10`). The `KeyboardInput`
//! messages keep both; they are read once a frame here, for every tool that
//! types numbers.

use bevy::input::ButtonState;
use bevy::input::keyboard::KeyboardInput;
use bevy::prelude::*;

/// This frame's key presses, oldest first; rebuilt once a frame in
/// `PreUpdate` by [`record_strokes`].
#[derive(Resource, Debug, Default)]
pub struct Strokes(Vec<KeyCode>);

impl Strokes {
    /// The keys pressed this frame, in order, repeats kept.
    pub fn key_presses(&self) -> impl Iterator<Item = KeyCode> + '_ {
        self.0.iter().copied()
    }
}

/// Rebuilds [`Strokes`] from this frame's keyboard messages.
pub fn record_strokes(mut keys: MessageReader<KeyboardInput>, mut strokes: ResMut<Strokes>) {
    strokes.0.clear();
    strokes.0.extend(
        keys.read()
            .filter(|k| k.state == ButtonState::Pressed)
            .map(|k| k.key_code),
    );
}
