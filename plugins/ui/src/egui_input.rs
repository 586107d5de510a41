//! egui's pointer and keyboard input, in the order the window system gave
//! it, each event with the modifier keys held at that moment.
//!
//! bevy_egui gives every event of a frame the modifiers held at the frame's
//! end. On a slow frame a whole chord arrives at once: Shift+click in the
//! outliner became a plain click (Shift was already let go), and Ctrl+A in a
//! text field typed "a". Its pointer, button and keyboard writers are turned
//! off ([`take_over_egui_input`]) and [`write_egui_input_in_order`] does their
//! work from the one ordered `WindowEvent` stream, following the modifiers
//! event by event ([`HeldModifiers`]).
//!
//! Menus and buttons activate on release over the item however long the
//! press was, as on every desktop: egui counts a press held longer than
//! `max_click_duration` (0.8 s) as no click, and a loaded machine holds a
//! person's click that long.

use bevy::input::ButtonState;
use bevy::input::keyboard::{Key, KeyboardFocusLost, KeyboardInput};
use bevy::prelude::*;
use bevy::window::WindowEvent;
use bevy_egui::input::{EguiContextPointerPosition, EguiInputEvent};
use bevy_egui::{
    EguiContext, EguiGlobalSettings, EguiZoomFactor, PrimaryEguiContext, egui, helpers,
};

/// Which modifier keys are held.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct HeldModifiers {
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
    fn follow(&mut self, event: &KeyboardInput) {
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

/// How long a press may be held and still click: an hour, that is any
/// press a person makes (egui's default is 0.8 s).
pub const MAX_CLICK_SECONDS: f64 = 3600.0;

/// Turns off bevy_egui's own pointer, button and keyboard writers (the
/// ordered writer below replaces them).
pub(crate) fn take_over_egui_input(settings: &mut EguiGlobalSettings) {
    let input = &mut settings.input_system_settings;
    input.run_write_window_pointer_moved_messages = false;
    input.run_write_pointer_button_messages = false;
    input.run_write_keyboard_input_messages_system = false;
}

/// Lets a press of any length click, once the primary context exists.
pub(crate) fn allow_long_clicks(mut contexts: Query<&mut EguiContext, Added<PrimaryEguiContext>>) {
    for mut context in &mut contexts {
        context
            .get_mut()
            .options_mut(|o| o.input_options.max_click_duration = MAX_CLICK_SECONDS);
    }
}

fn egui_modifiers(held: HeldModifiers) -> egui::Modifiers {
    egui::Modifiers {
        alt: held.alt,
        ctrl: held.ctrl,
        shift: held.shift,
        mac_cmd: false,
        command: held.ctrl,
    }
}

fn egui_button(button: MouseButton) -> Option<egui::PointerButton> {
    Some(match button {
        MouseButton::Left => egui::PointerButton::Primary,
        MouseButton::Right => egui::PointerButton::Secondary,
        MouseButton::Middle => egui::PointerButton::Middle,
        MouseButton::Back => egui::PointerButton::Extra1,
        MouseButton::Forward => egui::PointerButton::Extra2,
        MouseButton::Other(_) => return None,
    })
}

/// Writes the window's pointer moves, buttons and keys to the primary egui
/// context in arrival order, each with the modifiers held when it happened.
pub(crate) fn write_egui_input_in_order(
    mut window_events: MessageReader<WindowEvent>,
    mut focus_lost: MessageReader<KeyboardFocusLost>,
    mut held: Local<HeldModifiers>,
    mut context: Query<
        (
            Entity,
            &EguiZoomFactor,
            &mut EguiContextPointerPosition,
            &mut EguiContext,
        ),
        With<PrimaryEguiContext>,
    >,
    mut egui_events: MessageWriter<EguiInputEvent>,
) {
    if focus_lost.read().count() > 0 {
        *held = HeldModifiers::default();
    }
    let Ok((context, zoom, mut pointer, mut egui_context)) = context.single_mut() else {
        window_events.clear();
        return;
    };
    // Tab is the viewport's (edit mode) unless a text field has the
    // keyboard: given to egui, it would move the focus to a button.
    let typing = egui_context.get_mut().text_edit_focused();
    let mut write = |event| {
        egui_events.write(EguiInputEvent { context, event });
    };
    for event in window_events.read() {
        match event {
            WindowEvent::CursorMoved(moved) => {
                let at = helpers::vec2_into_egui_pos2(moved.position / zoom.zoom_factor);
                pointer.position = at;
                write(egui::Event::PointerMoved(at));
            }
            WindowEvent::MouseButtonInput(input) => {
                if let Some(button) = egui_button(input.button) {
                    write(egui::Event::PointerButton {
                        pos: pointer.position,
                        button,
                        pressed: input.state == ButtonState::Pressed,
                        modifiers: egui_modifiers(*held),
                    });
                }
            }
            WindowEvent::KeyboardInput(input) => {
                held.follow(input);
                let pressed = input.state == ButtonState::Pressed;
                // Ctrl+Alt is AltGr, which types characters.
                let text_allowed = !held.ctrl || held.alt;
                if pressed && text_allowed {
                    match &input.logical_key {
                        Key::Character(c) if !c.chars().any(char::is_control) => {
                            write(egui::Event::Text(c.to_string()));
                        }
                        Key::Space => write(egui::Event::Text(" ".into())),
                        _ => {}
                    }
                }
                let physical_key = helpers::bevy_to_egui_physical_key(&input.key_code);
                if input.key_code == KeyCode::Tab && !typing {
                    continue;
                }
                if let Some(key) = helpers::bevy_to_egui_key(&input.logical_key).or(physical_key) {
                    write(egui::Event::Key {
                        key,
                        physical_key,
                        pressed,
                        repeat: false,
                        modifiers: egui_modifiers(*held),
                    });
                }
            }
            _ => {}
        }
    }
}

/// The modifiers of the primary button's release in this frame's egui
/// events (the click's own), or those held now when there is none.
pub fn click_modifiers(ui: &egui::Ui) -> egui::Modifiers {
    ui.input(|i| {
        i.events
            .iter()
            .rev()
            .find_map(|e| match e {
                egui::Event::PointerButton {
                    button: egui::PointerButton::Primary,
                    pressed: false,
                    modifiers,
                    ..
                } => Some(*modifiers),
                _ => None,
            })
            .unwrap_or(i.modifiers)
    })
}

/// The one writer of [`hedra_scene::InputGate::pointer_free`]: at the start
/// of a frame, whether the pointer is free for the viewport where it is
/// *now*: over the 3D area between the panels, not over a window, menu or
/// dialog egui drew last frame, and egui not dragging. (Decided at the end
/// of the frame before, a slow frame's move onto a dialog's button and
/// click reached the viewport too: Cancel in "Unsaved changes" cleared the
/// selection.)
pub(crate) fn refresh_pointer_gate(
    window: Single<&Window, With<bevy::window::PrimaryWindow>>,
    mut contexts: Query<&mut EguiContext, With<PrimaryEguiContext>>,
    ui: Res<crate::UiState>,
    mut gate: ResMut<hedra_scene::InputGate>,
) {
    // Before the panels are first laid out there is nothing to decide by.
    let (Some(viewport), Ok(mut context)) = (ui.viewport_rect, contexts.single_mut()) else {
        return;
    };
    let ctx = context.get_mut();
    let free = window.cursor_position().is_some_and(|cursor| {
        let at = egui::pos2(cursor.x, cursor.y);
        let over_window = ctx
            .layer_id_at(at)
            .is_some_and(|layer| layer.order != egui::Order::Background);
        viewport.contains(at) && !over_window && !ctx.egui_is_using_pointer()
    });
    if gate.pointer_free != free {
        gate.pointer_free = free;
    }
}

/// The one writer of [`hedra_scene::InputGate::keyboard_free`], right after
/// the panels are drawn: no shortcut runs while a text field has the
/// keyboard or a dialog that is typed into is open (the path prompt,
/// unsaved changes). Only text fields keep egui's focus: a clicked button
/// would keep it, every shortcut blocked until a click elsewhere, and Enter
/// or Space (a tool's confirm) would press it again.
pub(crate) fn refresh_keyboard_gate(
    mut contexts: Query<&mut EguiContext, With<PrimaryEguiContext>>,
    ui: Res<crate::UiState>,
    mut gate: ResMut<hedra_scene::InputGate>,
) {
    let Ok(mut context) = contexts.single_mut() else {
        return;
    };
    let ctx = context.get_mut();
    if let Some(id) = ctx.memory(|m| m.focused())
        && !ctx.text_edit_focused()
    {
        ctx.memory_mut(|m| m.surrender_focus(id));
    }
    let free = !ctx.text_edit_focused() && ui.path_prompt.is_none() && ui.confirm.is_none();
    if gate.keyboard_free != free {
        gate.keyboard_free = free;
    }
}
