//! Typed numbers for modal tools, as in Blender: digits and a point build
//! the value, minus toggles the sign, Backspace deletes.

use bevy::prelude::*;
use hedra_scene::Strokes;

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
    /// Reads this frame's key presses in the order they arrived (several
    /// arrive in one frame on a slow machine: `2` then `1` is 21, and `100`
    /// keeps both zeros); with `minus_toggles`, Minus flips the sign.
    pub fn read(&mut self, strokes: &Strokes, minus_toggles: bool) {
        for key in strokes.key_presses() {
            self.type_key(key, minus_toggles);
        }
    }

    /// One key press: a digit or point is added, Minus flips the sign (with
    /// `minus_toggles`), Backspace deletes the last character.
    pub fn type_key(&mut self, key: KeyCode, minus_toggles: bool) {
        if let Some(&(_, c)) = KEYS.iter().find(|(k, _)| *k == key) {
            self.0.push(c);
        } else if minus_toggles && matches!(key, KeyCode::Minus | KeyCode::NumpadSubtract) {
            self.0 = self
                .0
                .strip_prefix('-')
                .map_or_else(|| format!("-{}", self.0), str::to_string);
        } else if key == KeyCode::Backspace {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn typed(keys: &[KeyCode], minus_toggles: bool) -> TypedNumber {
        let mut t = TypedNumber::default();
        for &k in keys {
            t.type_key(k, minus_toggles);
        }
        t
    }

    #[test]
    fn keys_build_the_number_in_the_order_typed() {
        use KeyCode::*;
        assert_eq!(typed(&[Digit2, Digit1], true).value(), Some(21.0));
        assert_eq!(typed(&[Digit1, Digit0, Digit0], true).value(), Some(100.0));
        assert_eq!(typed(&[Digit0, Period, Digit5], true).value(), Some(0.5));
        assert_eq!(
            typed(&[Minus, Digit3, Minus, Minus], true).value(),
            Some(-3.0)
        );
        assert_eq!(typed(&[Minus, Digit3], false).value(), Some(3.0));
        assert_eq!(typed(&[Digit4, Digit2, Backspace], true).value(), Some(4.0));
        assert_eq!(typed(&[Minus], true).value(), None);
    }
}
