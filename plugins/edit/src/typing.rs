//! Typed numbers for modal tools, as in Blender: digits and a point build
//! the value, minus toggles the sign, Backspace deletes.

use bevy::prelude::*;

/// The digits typed during a modal tool.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TypedNumber(String);

const KEYS: [(KeyCode, char); 22] = [
    (KeyCode::Digit0, '0'),
    (KeyCode::Digit1, '1'),
    (KeyCode::Digit2, '2'),
    (KeyCode::Digit3, '3'),
    (KeyCode::Digit4, '4'),
    (KeyCode::Digit5, '5'),
    (KeyCode::Digit6, '6'),
    (KeyCode::Digit7, '7'),
    (KeyCode::Digit8, '8'),
    (KeyCode::Digit9, '9'),
    (KeyCode::Numpad0, '0'),
    (KeyCode::Numpad1, '1'),
    (KeyCode::Numpad2, '2'),
    (KeyCode::Numpad3, '3'),
    (KeyCode::Numpad4, '4'),
    (KeyCode::Numpad5, '5'),
    (KeyCode::Numpad6, '6'),
    (KeyCode::Numpad7, '7'),
    (KeyCode::Numpad8, '8'),
    (KeyCode::Numpad9, '9'),
    (KeyCode::Period, '.'),
    (KeyCode::NumpadDecimal, '.'),
];

impl TypedNumber {
    /// Reads this frame's keys; with `minus_toggles`, Minus flips the sign.
    pub fn read(&mut self, keys: &ButtonInput<KeyCode>, minus_toggles: bool) {
        for (key, c) in KEYS {
            if keys.just_pressed(key) {
                self.0.push(c);
            }
        }
        if minus_toggles && keys.any_just_pressed([KeyCode::Minus, KeyCode::NumpadSubtract]) {
            self.0 = self
                .0
                .strip_prefix('-')
                .map_or_else(|| format!("-{}", self.0), str::to_string);
        }
        if keys.just_pressed(KeyCode::Backspace) {
            self.0.pop();
        }
    }
    /// The typed value, if what was typed is a number.
    pub fn value(&self) -> Option<f64> {
        let t = self.0.trim();
        if t.is_empty() || t == "-" {
            None
        } else {
            t.parse().ok()
        }
    }
    /// True when nothing has been typed (or everything was deleted).
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
    /// The typed text as it stands, e.g. "-1.5" or "-" (for the readout).
    pub fn as_str(&self) -> &str {
        &self.0
    }
}
