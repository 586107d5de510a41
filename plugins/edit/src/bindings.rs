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
        KeyCode::Numpad1 => "Numpad 1".into(),
        KeyCode::Numpad3 => "Numpad 3".into(),
        KeyCode::Numpad5 => "Numpad 5".into(),
        KeyCode::Numpad7 => "Numpad 7".into(),
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
use KeyMode::{ControlPoints, Edit, Everywhere, Object, Tool};

/// The keymap (Blender's keys). An action may have several chords (X and
/// Delete); within a mode a chord runs one action, and a chord bound
/// everywhere is bound in no single mode.
pub const BINDINGS: &[Binding] = &[
    bind(Everywhere, Chord::ctrl(K::KeyN), A::NewFile, "new scene"),
    bind(
        Everywhere,
        Chord::ctrl(K::KeyO),
        A::OpenFile,
        "open a scene",
    ),
    bind(Everywhere, Chord::ctrl(K::KeyS), A::Save, "save"),
    bind(Everywhere, Chord::ctrl_shift(K::KeyS), A::SaveAs, "save as"),
    bind(
        Everywhere,
        Chord::ctrl(K::KeyQ),
        A::Quit,
        "quit (asks first when there are unsaved changes)",
    ),
    bind(Everywhere, Chord::ctrl(K::KeyZ), A::Undo, "undo"),
    bind(Everywhere, Chord::ctrl_shift(K::KeyZ), A::Redo, "redo"),
    bind(Everywhere, Chord::ctrl(K::KeyY), A::Redo, "redo"),
    bind(
        Everywhere,
        Chord::shift(K::KeyA),
        A::AddMenu,
        "add menu at the pointer",
    ),
    bind(
        Everywhere,
        Chord::shift(K::KeyS),
        A::SnapMenu,
        "snap menu at the pointer (3D cursor, selection)",
    ),
    bind(
        Everywhere,
        Chord::key(K::Tab),
        A::EditModeToggle,
        "edit the active mesh (control points of a curve or surface); again to leave",
    ),
    bind(
        Everywhere,
        Chord::shift(K::Tab),
        A::Snapping,
        "snapping on/off (Ctrl held during a drag inverts it)",
    ),
    bind(
        Everywhere,
        Chord::key(K::KeyZ),
        A::ShadingMenu,
        "shading menu at the pointer: solid, wireframe, X-ray, flat, smooth",
    ),
    bind(
        Everywhere,
        Chord::shift(K::KeyZ),
        A::Wireframe,
        "wireframe on/off",
    ),
    bind(
        Everywhere,
        Chord::alt(K::KeyZ),
        A::XRay,
        "X-ray on/off (see through, select through)",
    ),
    bind(
        Everywhere,
        Chord::ctrl_alt(K::KeyQ),
        A::QuadView,
        "quad view: top, front, right and perspective",
    ),
    bind(
        Everywhere,
        Chord::key(K::Numpad1),
        A::ViewFront,
        "front view",
    ),
    bind(
        Everywhere,
        Chord::ctrl(K::Numpad1),
        A::ViewBack,
        "back view",
    ),
    bind(
        Everywhere,
        Chord::key(K::Numpad3),
        A::ViewRight,
        "right view",
    ),
    bind(
        Everywhere,
        Chord::ctrl(K::Numpad3),
        A::ViewLeft,
        "left view",
    ),
    bind(Everywhere, Chord::key(K::Numpad7), A::ViewTop, "top view"),
    bind(
        Everywhere,
        Chord::ctrl(K::Numpad7),
        A::ViewBottom,
        "bottom view",
    ),
    bind(
        Everywhere,
        Chord::key(K::Numpad5),
        A::Orthographic,
        "perspective / orthographic",
    ),
    bind(
        Everywhere,
        Chord::key(K::NumpadDecimal),
        A::FrameSelected,
        "frame the selection",
    ),
    bind(
        Everywhere,
        Chord::key(K::Home),
        A::FrameAll,
        "frame everything",
    ),
    bind(
        Everywhere,
        Chord::ctrl(K::Digit0),
        A::SubdivisionLevel,
        "subdivision level 0–5 of the selected meshes (0: the cage alone)",
    ),
    bind(Everywhere, Chord::ctrl(K::Digit1), A::SubdivisionLevel, ""),
    bind(Everywhere, Chord::ctrl(K::Digit2), A::SubdivisionLevel, ""),
    bind(Everywhere, Chord::ctrl(K::Digit3), A::SubdivisionLevel, ""),
    bind(Everywhere, Chord::ctrl(K::Digit4), A::SubdivisionLevel, ""),
    bind(Everywhere, Chord::ctrl(K::Digit5), A::SubdivisionLevel, ""),
    bind(
        Everywhere,
        Chord::key(K::PageUp),
        A::SubdivisionUp,
        "one subdivision level more",
    ),
    bind(
        Everywhere,
        Chord::key(K::PageDown),
        A::SubdivisionDown,
        "one subdivision level less",
    ),
    bind(
        Everywhere,
        Chord::key(K::Period),
        A::PivotPoint,
        "pivot: median point / 3D cursor",
    ),
    bind(Everywhere, Chord::key(K::F1), A::KeyHelp, "this key help"),
    bind(
        Everywhere,
        Chord::shift(K::Slash),
        A::KeyHelp,
        "this key help",
    ),
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
    bind(
        Object,
        Chord::key(K::KeyF),
        A::FrameSelected,
        "frame the selection",
    ),
    bind(
        Edit,
        Chord::key(K::Digit1),
        A::VertexMode,
        "select vertices",
    ),
    bind(Edit, Chord::key(K::Digit2), A::EdgeMode, "select edges"),
    bind(Edit, Chord::key(K::Digit3), A::FaceMode, "select faces"),
    bind(
        Edit,
        Chord::key(K::KeyB),
        A::BoxSelect,
        "box select: click the opposite corner",
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
    bind(
        ControlPoints,
        Chord::key(K::KeyA),
        A::SelectAll,
        "select all points",
    ),
    bind(
        ControlPoints,
        Chord::alt(K::KeyA),
        A::SelectNone,
        "select none",
    ),
    bind(
        ControlPoints,
        Chord::key(K::KeyB),
        A::BoxSelect,
        "box select: click the opposite corner",
    ),
    bind(
        ControlPoints,
        Chord::key(K::KeyG),
        A::Move,
        "move the selected points",
    ),
    bind(
        ControlPoints,
        Chord::key(K::KeyR),
        A::Rotate,
        "rotate the selected points (about their median or the 3D cursor)",
    ),
    bind(
        ControlPoints,
        Chord::key(K::KeyS),
        A::Scale,
        "scale the selected points",
    ),
    bind(
        ControlPoints,
        Chord::key(K::KeyW),
        A::Weight,
        "change the selected points' weights (drag right: heavier)",
    ),
    bind(
        ControlPoints,
        Chord::key(K::KeyK),
        A::InsertKnot,
        "insert a knot where the pointer is (the shape stays)",
    ),
    bind(
        ControlPoints,
        Chord::key(K::KeyX),
        A::Delete,
        "delete the selected points of a curve (its shape kept where the kind allows)",
    ),
    bind(
        ControlPoints,
        Chord::alt(K::KeyC),
        A::ToggleClosed,
        "open or close the curve",
    ),
    bind(
        ControlPoints,
        Chord::shift(K::KeyK),
        A::InsertKnotV,
        "insert a knot in v (surfaces)",
    ),
    bind(
        ControlPoints,
        Chord::key(K::KeyO),
        A::Proportional,
        "proportional editing on/off (wheel: radius)",
    ),
    bind(
        ControlPoints,
        Chord::shift(K::KeyO),
        A::ProportionalFalloff,
        "next proportional falloff",
    ),
    bind(
        Tool,
        Chord::any(K::Enter),
        A::Confirm,
        "confirm (or a left click; the knife cuts)",
    ),
    bind(Tool, Chord::any(K::NumpadEnter), A::Confirm, ""),
    bind(Tool, Chord::any(K::Space), A::Confirm, ""),
    bind(
        Tool,
        Chord::any(K::Escape),
        A::Cancel,
        "cancel (or a right click): nothing changes",
    ),
    bind(
        Tool,
        Chord::any(K::KeyX),
        A::AxisX,
        "only along X (again: free)",
    ),
    bind(Tool, Chord::any(K::KeyY), A::AxisY, "only along Y"),
    bind(Tool, Chord::any(K::KeyZ), A::AxisZ, "only along Z"),
    bind(
        Tool,
        Chord::key(K::KeyG),
        A::Slide,
        "moving edges: slide them along their neighbours instead",
    ),
    bind(
        Tool,
        Chord::key(K::NumpadAdd),
        A::MoreCuts,
        "loop cut, bevel: one cut or segment more (or the wheel)",
    ),
    bind(Tool, Chord::key(K::Equal), A::MoreCuts, ""),
    bind(
        Tool,
        Chord::key(K::NumpadSubtract),
        A::FewerCuts,
        "loop cut, bevel: one cut or segment less",
    ),
    bind(Tool, Chord::key(K::Minus), A::FewerCuts, ""),
    bind(
        Tool,
        Chord::key(K::PageUp),
        A::LargerRadius,
        "proportional radius larger (or the wheel)",
    ),
    bind(
        Tool,
        Chord::key(K::PageDown),
        A::SmallerRadius,
        "proportional radius smaller",
    ),
    bind(
        Tool,
        Chord::key(K::KeyC),
        A::KnifeAngle,
        "knife: keep the next segment at a multiple of 45°",
    ),
    bind(
        Tool,
        Chord::key(K::Backspace),
        A::RemoveLastPoint,
        "knife, curve drawing: take the last point back",
    ),
];

/// What the key help adds under the running tool's keys: the input that
/// is not one key.
pub const TOOL_NOTES: &[(&str, &str)] = &[
    (
        "0–9 . -",
        "type an exact amount (distance, angle, factor, count)",
    ),
    ("Ctrl (held)", "snapping inverted while held"),
];

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
