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
    /// Object mode: the scene's nodes.
    Object,
    /// Mesh edit mode: vertices, edges and faces.
    Edit,
}

impl KeyMode {
    /// The mode's name as the key help titles it.
    pub fn label(self) -> &'static str {
        match self {
            KeyMode::Object => "Object mode",
            KeyMode::Edit => "Edit mode",
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
}

impl Chord {
    /// The key alone.
    pub const fn key(key: KeyCode) -> Chord {
        Chord {
            key,
            ctrl: false,
            shift: false,
            alt: false,
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

    /// Pressed this frame with exactly these modifiers.
    pub fn just_pressed(&self, keys: &ButtonInput<KeyCode>) -> bool {
        keys.just_pressed(self.key)
            && ctrl(keys) == self.ctrl
            && shift(keys) == self.shift
            && alt(keys) == self.alt
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
        _ => debug
            .strip_prefix("Key")
            .or_else(|| debug.strip_prefix("Digit"))
            .unwrap_or(&debug)
            .to_string(),
    }
}

/// Everything a key can run.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
#[allow(missing_docs)] // each is described by its binding's text
pub enum Action {
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
use KeyCode as K;
use KeyMode::{Edit, Object};

/// The keymap (Blender's keys). An action may have several chords (X and
/// Delete); within a mode a chord runs one action.
pub const BINDINGS: &[Binding] = &[
    bind(Object, Chord::key(K::KeyA), A::SelectAll, "select all"),
    bind(Object, Chord::alt(K::KeyA), A::SelectNone, "select none"),
    bind(
        Object,
        Chord::key(K::KeyG),
        A::Move,
        "move (X/Y/Z, typed value, Enter or click; Esc cancels)",
    ),
    bind(Object, Chord::key(K::KeyR), A::Rotate, "rotate"),
    bind(Object, Chord::key(K::KeyS), A::Scale, "scale"),
    bind(
        Object,
        Chord::shift(K::KeyD),
        A::Duplicate,
        "duplicate and move",
    ),
    bind(Object, Chord::key(K::KeyX), A::Delete, "delete"),
    bind(Object, Chord::key(K::Delete), A::Delete, "delete"),
    bind(Object, Chord::key(K::KeyH), A::Hide, "hide the selection"),
    bind(Object, Chord::alt(K::KeyH), A::Unhide, "unhide all"),
    bind(Object, Chord::key(K::F1), A::KeyHelp, "this key help"),
    bind(Object, Chord::shift(K::Slash), A::KeyHelp, "this key help"),
    bind(
        Object,
        Chord::key(K::Period),
        A::PivotPoint,
        "pivot: median point / 3D cursor",
    ),
    bind(Edit, Chord::key(K::KeyA), A::SelectAll, "select all"),
    bind(Edit, Chord::alt(K::KeyA), A::SelectNone, "select none"),
    bind(
        Edit,
        Chord::ctrl(K::KeyI),
        A::InvertSelection,
        "invert the selection",
    ),
    bind(
        Edit,
        Chord::ctrl(K::NumpadAdd),
        A::GrowSelection,
        "grow the selection",
    ),
    bind(
        Edit,
        Chord::ctrl(K::Equal),
        A::GrowSelection,
        "grow the selection",
    ),
    bind(
        Edit,
        Chord::ctrl(K::NumpadSubtract),
        A::ShrinkSelection,
        "shrink the selection",
    ),
    bind(
        Edit,
        Chord::ctrl(K::Minus),
        A::ShrinkSelection,
        "shrink the selection",
    ),
    bind(
        Edit,
        Chord::key(K::KeyL),
        A::SelectLinkedUnderPointer,
        "select what is linked to the element under the pointer",
    ),
    bind(
        Edit,
        Chord::ctrl(K::KeyL),
        A::SelectLinked,
        "select everything linked to the selection",
    ),
    bind(
        Edit,
        Chord::key(K::KeyG),
        A::Move,
        "move the selection (G again in edge mode: slide)",
    ),
    bind(Edit, Chord::key(K::KeyR), A::Rotate, "rotate the selection"),
    bind(Edit, Chord::key(K::KeyS), A::Scale, "scale the selection"),
    bind(
        Edit,
        Chord::key(K::KeyE),
        A::Extrude,
        "extrude the faces as a region (edge mode: the border edges)",
    ),
    bind(
        Edit,
        Chord::alt(K::KeyE),
        A::ExtrudeIndividual,
        "extrude each face on its own",
    ),
    bind(
        Edit,
        Chord::key(K::KeyI),
        A::Inset,
        "inset the faces as a region",
    ),
    bind(
        Edit,
        Chord::alt(K::KeyI),
        A::InsetIndividual,
        "inset each face on its own",
    ),
    bind(
        Edit,
        Chord::ctrl(K::KeyR),
        A::LoopCut,
        "loop cut through the edge under the pointer (wheel: cuts)",
    ),
    bind(
        Edit,
        Chord::ctrl(K::KeyB),
        A::Bevel,
        "bevel the edges (wheel: segments)",
    ),
    bind(
        Edit,
        Chord::ctrl_shift(K::KeyB),
        A::BevelVertices,
        "bevel the vertices",
    ),
    bind(
        Edit,
        Chord::shift(K::KeyE),
        A::Crease,
        "crease the edges (vertex mode: corner sharpness)",
    ),
    bind(
        Edit,
        Chord::ctrl(K::KeyT),
        A::Triangulate,
        "triangulate the faces",
    ),
    bind(
        Edit,
        Chord::alt(K::KeyJ),
        A::TrisToQuads,
        "join triangles into quads",
    ),
    bind(
        Edit,
        Chord::key(K::KeyK),
        A::Knife,
        "knife: click points, Enter cuts",
    ),
    bind(
        Edit,
        Chord::key(K::KeyV),
        A::Rip,
        "rip along the edges and move one side",
    ),
    bind(
        Edit,
        Chord::alt(K::KeyV),
        A::SplitVertex,
        "split the vertex: its edges on the pointer's side go to a new vertex",
    ),
    bind(
        Edit,
        Chord::key(K::KeyX),
        A::Delete,
        "delete the selected elements",
    ),
    bind(
        Edit,
        Chord::key(K::Delete),
        A::Delete,
        "delete the selected elements",
    ),
    bind(
        Edit,
        Chord::ctrl(K::KeyX),
        A::Dissolve,
        "dissolve the selected elements",
    ),
    bind(Edit, Chord::alt(K::KeyN), A::FlipNormals, "flip normals"),
    bind(
        Edit,
        Chord::shift(K::KeyN),
        A::RecalculateNormals,
        "recalculate normals outside",
    ),
    bind(
        Edit,
        Chord::key(K::KeyF),
        A::Fill,
        "fill the hole around the selection",
    ),
    bind(
        Edit,
        Chord::key(K::KeyJ),
        A::Connect,
        "connect two vertices of a face",
    ),
    bind(
        Edit,
        Chord::key(K::KeyM),
        A::MergeOrCollapse,
        "merge menu (edge mode: collapse)",
    ),
    bind(
        Edit,
        Chord::key(K::KeyO),
        A::Proportional,
        "proportional editing on/off (wheel: radius)",
    ),
    bind(
        Edit,
        Chord::shift(K::KeyO),
        A::ProportionalFalloff,
        "next proportional falloff",
    ),
    bind(Edit, Chord::key(K::F1), A::KeyHelp, "this key help"),
    bind(Edit, Chord::shift(K::Slash), A::KeyHelp, "this key help"),
    bind(
        Edit,
        Chord::key(K::Period),
        A::PivotPoint,
        "pivot: median point / 3D cursor",
    ),
];

/// True when a chord bound to `action` in `mode` was pressed this frame.
pub fn pressed(keys: &ButtonInput<KeyCode>, mode: KeyMode, action: Action) -> bool {
    BINDINGS
        .iter()
        .filter(|b| b.mode == mode && b.action == action)
        .any(|b| b.chord.just_pressed(keys))
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

/// Whether the key help (F1) is shown.
#[derive(Resource, Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct KeyHelp(pub bool);

/// F1 toggles the key help in either mode; Esc closes it.
pub fn key_help_keys(
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<hedra_scene::InputGate>,
    mode: Res<crate::EditMode>,
    mut help: ResMut<KeyHelp>,
) {
    let here = if mode.active() { Edit } else { Object };
    if gate.keyboard_free && pressed(&keys, here, A::KeyHelp) {
        help.0 = !help.0;
    } else if help.0 && keys.just_pressed(KeyCode::Escape) {
        help.0 = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn within_a_mode_each_chord_runs_one_action() {
        for (i, a) in BINDINGS.iter().enumerate() {
            for b in &BINDINGS[i + 1..] {
                assert!(
                    !(a.mode == b.mode && a.chord == b.chord),
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
