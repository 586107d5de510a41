//! The keymap: which key chord runs which action in which mode, as one
//! table ([`BINDINGS`]). The shortcut systems ask it ([`pressed`]) instead
//! of naming keys, and the key help (F1) and the menus' key hints read the
//! same table ([`chord_label`], [`bindings_of`]), so what is shown cannot
//! drift from what the keys do.

use bevy::prelude::*;
use hedra_scene::modifiers::{alt, ctrl, shift};

/// Where a binding applies.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum KeyMode {
    /// In every mode while no tool runs: files, undo, views, shading.
    Everywhere,
    /// Object mode: the scene's nodes.
    Object,
    /// Mesh edit mode: vertices, edges and faces.
    Edit,
    /// Control-point mode: a curve's or surface's points and weights.
    ControlPoints,
    /// While a modal tool runs (G/R/S, extrude, bevel, knife, …).
    Tool,
}

impl KeyMode {
    /// The mode's name as the key help titles it.
    pub fn label(self) -> &'static str {
        match self {
            KeyMode::Everywhere => "Everywhere",
            KeyMode::Object => "Object mode",
            KeyMode::Edit => "Edit mode",
            KeyMode::ControlPoints => "Control-point mode",
            KeyMode::Tool => "While a tool runs",
        }
    }
}

/// A key with the modifiers that must be held (and no others).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct Chord {
    /// The key pressed.
    pub key: KeyCode,
    /// Ctrl held.
    pub ctrl: bool,
    /// Shift held.
    pub shift: bool,
    /// Alt held.
    pub alt: bool,
    /// Whatever modifiers are held (a tool's Enter or X still works while
    /// Ctrl inverts snapping).
    pub any_modifiers: bool,
}

impl Chord {
    /// The key alone.
    pub const fn key(key: KeyCode) -> Chord {
        Chord {
            key,
            ctrl: false,
            shift: false,
            alt: false,
            any_modifiers: false,
        }
    }
    /// The key, whatever modifiers are held.
    pub const fn any(key: KeyCode) -> Chord {
        Chord {
            any_modifiers: true,
            ..Chord::key(key)
        }
    }
    /// The key with Ctrl.
    pub const fn ctrl(key: KeyCode) -> Chord {
        Chord {
            ctrl: true,
            ..Chord::key(key)
        }
    }
    /// The key with Shift.
    pub const fn shift(key: KeyCode) -> Chord {
        Chord {
            shift: true,
            ..Chord::key(key)
        }
    }
    /// The key with Alt.
    pub const fn alt(key: KeyCode) -> Chord {
        Chord {
            alt: true,
            ..Chord::key(key)
        }
    }
    /// The key with Ctrl and Shift.
    pub const fn ctrl_shift(key: KeyCode) -> Chord {
        Chord {
            ctrl: true,
            shift: true,
            ..Chord::key(key)
        }
    }
    /// The key with Ctrl and Alt.
    pub const fn ctrl_alt(key: KeyCode) -> Chord {
        Chord {
            ctrl: true,
            alt: true,
            ..Chord::key(key)
        }
    }

    /// Pressed this frame with exactly these modifiers.
    pub fn just_pressed(&self, keys: &ButtonInput<KeyCode>) -> bool {
        keys.just_pressed(self.key)
            && (self.any_modifiers
                || (ctrl(keys) == self.ctrl && shift(keys) == self.shift && alt(keys) == self.alt))
    }

    /// As a person writes it: "Ctrl+Shift+B", "Numpad +", "Delete".
    pub fn label(&self) -> String {
        let mut s = String::new();
        for (held, name) in [
            (self.ctrl, "Ctrl+"),
            (self.shift, "Shift+"),
            (self.alt, "Alt+"),
        ] {
            if held {
                s += name;
            }
        }
        s + &key_label(self.key)
    }
}

/// A key's name as printed on it.
pub fn key_label(key: KeyCode) -> String {
    let debug = format!("{key:?}");
    match key {
        KeyCode::NumpadAdd => "Numpad +".into(),
        KeyCode::NumpadSubtract => "Numpad -".into(),
        KeyCode::Equal => "=".into(),
        KeyCode::Minus => "-".into(),
        KeyCode::Escape => "Esc".into(),
        KeyCode::PageUp => "Page Up".into(),
        KeyCode::PageDown => "Page Down".into(),
        KeyCode::Slash => "/".into(),
        KeyCode::NumpadDecimal => "Numpad .".into(),
        KeyCode::NumpadEnter => "Numpad Enter".into(),
        KeyCode::Period => ".".into(),
        KeyCode::NumpadMultiply => "Numpad *".into(),
        KeyCode::NumpadDivide => "Numpad /".into(),
        // Numpad digits read "Numpad 1", as printed beside the other keys.
        _ => match debug.strip_prefix("Numpad") {
            Some(rest) if rest.len() == 1 => format!("Numpad {rest}"),
            _ => debug
                .strip_prefix("Key")
                .or_else(|| debug.strip_prefix("Digit"))
                .unwrap_or(&debug)
                .to_string(),
        },
    }
}

/// Everything a key can run.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[allow(missing_docs)] // each is described by its binding's text
pub enum Action {
    NewFile,
    OpenFile,
    Save,
    SaveAs,
    Quit,
    Undo,
    Redo,
    AddMenu,
    SnapMenu,
    Snapping,
    ShadingMenu,
    Wireframe,
    XRay,
    QuadView,
    ViewFront,
    ViewBack,
    ViewRight,
    ViewLeft,
    ViewTop,
    ViewBottom,
    Orthographic,
    FrameSelected,
    FrameAll,
    SubdivisionLevel,
    SubdivisionUp,
    SubdivisionDown,
    EditModeToggle,
    VertexMode,
    EdgeMode,
    FaceMode,
    BoxSelect,
    Weight,
    InsertKnot,
    InsertKnotV,
    ToggleClosed,
    SplitCurve,
    JoinCurves,
    BooleanUnion,
    BooleanDifference,
    BooleanIntersection,
    Confirm,
    Cancel,
    AxisX,
    AxisY,
    AxisZ,
    Slide,
    MoreCuts,
    FewerCuts,
    LargerRadius,
    SmallerRadius,
    KnifeAngle,
    RemoveLastPoint,
    NextCurveKind,
    SelectAll,
    SelectNone,
    InvertSelection,
    GrowSelection,
    ShrinkSelection,
    SelectLinkedUnderPointer,
    SelectLinked,
    Move,
    Rotate,
    Scale,
    Delete,
    Duplicate,
    Hide,
    Unhide,
    Extrude,
    ExtrudeIndividual,
    Inset,
    InsetIndividual,
    LoopCut,
    Bevel,
    BevelVertices,
    Crease,
    Triangulate,
    TrisToQuads,
    Knife,
    Rip,
    SplitVertex,
    Dissolve,
    FlipNormals,
    RecalculateNormals,
    Fill,
    Connect,
    MergeOrCollapse,
    Proportional,
    ProportionalFalloff,
    KeyHelp,
    PivotPoint,
}

/// One row of the keymap.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Binding {
    /// Where it applies.
    pub mode: KeyMode,
    /// The chord.
    pub chord: Chord,
    /// What it runs.
    pub action: Action,
    /// What it does, for the key help.
    pub what: &'static str,
}

const fn bind(mode: KeyMode, chord: Chord, action: Action, what: &'static str) -> Binding {
    Binding {
        mode,
        chord,
        action,
        what,
    }
}

use Action as A;
use KeyMode::Everywhere;

mod table;
pub use table::{BINDINGS, TOOL_NOTES};

/// True when a chord bound to `action` in `mode` was pressed this frame.
pub fn pressed(keys: &ButtonInput<KeyCode>, mode: KeyMode, action: Action) -> bool {
    BINDINGS
        .iter()
        .filter(|b| b.mode == mode && b.action == action)
        .any(|b| b.chord.just_pressed(keys))
}

/// The key of the chord bound to `action` in `mode` that was pressed this
/// frame, for actions with a family of keys (Ctrl+0…Ctrl+5).
pub fn pressed_key(keys: &ButtonInput<KeyCode>, mode: KeyMode, action: Action) -> Option<KeyCode> {
    BINDINGS
        .iter()
        .filter(|b| b.mode == mode && b.action == action)
        .find(|b| b.chord.just_pressed(keys))
        .map(|b| b.chord.key)
}

/// The chords of `action` in `mode`, as a menu shows them ("X, Delete").
pub fn chord_label(mode: KeyMode, action: Action) -> String {
    BINDINGS
        .iter()
        .filter(|b| b.mode == mode && b.action == action)
        .map(|b| b.chord.label())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The first chord of `action` in `mode` ("X" for X, Delete), for short
/// hints; empty when it has none.
pub fn first_chord_label(mode: KeyMode, action: Action) -> String {
    BINDINGS
        .iter()
        .find(|b| b.mode == mode && b.action == action)
        .map_or(String::new(), |b| b.chord.label())
}

/// A status-bar hint from the keymap: "G move · E extrude · …", the keys
/// joined by "/" where several actions share one word ("1/2/3 kind").
pub fn hints(items: &[(KeyMode, &[Action], &str)]) -> String {
    items
        .iter()
        .map(|(mode, actions, word)| {
            let keys: Vec<String> = actions
                .iter()
                .map(|&a| first_chord_label(*mode, a))
                .collect();
            format!("{} {word}", keys.join("/"))
        })
        .collect::<Vec<_>>()
        .join(" · ")
}

/// The key help's rows for `mode`: each action once, with all its chords.
pub fn bindings_of(mode: KeyMode) -> Vec<(String, &'static str)> {
    let mut seen = Vec::new();
    BINDINGS
        .iter()
        .filter(|b| b.mode == mode)
        .filter(|b| {
            let first = !seen.contains(&b.action);
            seen.push(b.action);
            first
        })
        .map(|b| (chord_label(mode, b.action), b.what))
        .collect()
}

/// An action asked for from a menu rather than by its keys: the shortcut
/// systems run it next frame exactly as if its chord had been pressed, so
/// a menu item and its key start the same interactive tool.
#[derive(Resource, Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct RequestedAction(pub Option<Action>);

impl RequestedAction {
    /// True, once, when `action` was asked for.
    pub fn take(&mut self, action: Action) -> bool {
        let asked = self.0 == Some(action);
        if asked {
            self.0 = None;
        }
        asked
    }
}

/// Whether the key help (F1) is shown.
#[derive(Resource, Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct KeyHelp(pub bool);

/// F1 toggles the key help in either mode; Esc closes it.
pub fn key_help_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<hedra_scene::InputGate>,
    mut help: ResMut<KeyHelp>,
) {
    if gate.keyboard_free && pressed(&keys, Everywhere, A::KeyHelp) {
        help.0 = !help.0;
    } else if help.0 && keys.just_pressed(KeyCode::Escape) {
        help.0 = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use KeyCode as K;
    use KeyMode::{ControlPoints, Edit, Object, Tool};

    #[test]
    fn within_a_mode_each_chord_runs_one_action() {
        // A chord bound everywhere would also run in the mode it shares.
        let clash = |a: &Binding, b: &Binding| {
            a.chord == b.chord
                && (a.mode == b.mode
                    || (a.mode == Everywhere && b.mode != Tool)
                    || (b.mode == Everywhere && a.mode != Tool))
        };
        for (i, a) in BINDINGS.iter().enumerate() {
            for b in &BINDINGS[i + 1..] {
                assert!(
                    !clash(a, b),
                    "{} is bound twice in {:?}: {:?} and {:?}",
                    a.chord.label(),
                    a.mode,
                    a.action,
                    b.action
                );
            }
        }
    }

    #[test]
    fn labels_read_as_printed_on_the_keys() {
        assert_eq!(Chord::ctrl_shift(K::KeyB).label(), "Ctrl+Shift+B");
        assert_eq!(chord_label(Edit, A::Delete), "X, Delete");
        assert_eq!(chord_label(Edit, A::GrowSelection), "Ctrl+Numpad +, Ctrl+=");
        assert_eq!(
            chord_label(Object, A::BooleanIntersection),
            "Ctrl+Numpad *",
            "read like Numpad +, not NumpadMultiply"
        );
        assert_eq!(key_label(K::Numpad9), "Numpad 9");
        assert_eq!(key_label(K::NumpadDivide), "Numpad /");
        let rows = bindings_of(Edit);
        assert_eq!(
            rows.iter()
                .filter(|(_, what)| what.starts_with("delete"))
                .count(),
            1,
            "an action is listed once"
        );
    }

    #[test]
    fn every_action_says_what_it_does() {
        for mode in [Everywhere, Object, Edit, ControlPoints, Tool] {
            for (chord, what) in bindings_of(mode) {
                assert!(!what.is_empty(), "{chord} in {mode:?} has no text");
            }
        }
    }

    #[test]
    fn hints_read_the_keymap() {
        assert_eq!(
            hints(&[
                (Edit, &[A::VertexMode, A::EdgeMode, A::FaceMode], "kind"),
                (Edit, &[A::Delete], "delete"),
                (Edit, &[A::Dissolve], "dissolve"),
            ]),
            "1/2/3 kind · X delete · Ctrl+X dissolve"
        );
    }

    #[test]
    fn tool_keys_work_whatever_modifiers_are_held() {
        let mut keys = ButtonInput::<KeyCode>::default();
        keys.press(K::ControlLeft);
        keys.press(K::Enter);
        assert!(pressed(&keys, Tool, A::Confirm), "Enter with Ctrl held");
        assert!(!pressed(&keys, Everywhere, A::Save));
    }

    #[test]
    fn a_chord_needs_exactly_its_modifiers() {
        let mut keys = ButtonInput::<KeyCode>::default();
        keys.press(K::KeyB);
        assert!(!pressed(&keys, Edit, A::Bevel), "B alone is not Ctrl+B");
        keys.press(K::ControlLeft);
        assert!(pressed(&keys, Edit, A::Bevel));
        keys.press(K::ShiftLeft);
        assert!(
            !pressed(&keys, Edit, A::Bevel),
            "Ctrl+Shift+B is the vertex bevel"
        );
        assert!(pressed(&keys, Edit, A::BevelVertices));
    }
}
