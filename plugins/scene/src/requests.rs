//! What the panels ask of the state other plugins own, as messages.
//!
//! A panel never holds a `ResMut` of another crate's state: it reads the
//! state, and when the user changes something it sends a message. The plugin
//! that owns the state applies it in [`SceneSystems::Requests`], the first
//! stage of the next frame, before any tool reads input. Settings (snapping,
//! shading, the 3D cursor, …) travel whole as [`ChangeSetting`]; the status
//! line and the Properties panel's preview have their own messages here;
//! edit's own (selection, starting tools) are `hedra_edit::EditRequest`.

use crate::*;
use bevy::ecs::component::Mutable;

/// A resource the panels change whole by [`ChangeSetting`]: a value they
/// can copy, edit and compare.
pub trait Setting: Resource<Mutability = Mutable> + Clone + PartialEq {}

impl<T: Resource<Mutability = Mutable> + Clone + PartialEq> Setting for T {}

/// A panel's new value for the setting resource `T`, applied by the plugin
/// that registered `T` with [`SettingsApp::add_setting`].
#[derive(Message, Clone, Debug)]
pub struct ChangeSetting<T: Resource + Clone>(pub T);

/// Replaces the setting `T` with the last value the panels sent; the resource
/// is marked changed only when the value differs.
pub fn apply_setting_changes<T: Setting>(
    mut changes: MessageReader<ChangeSetting<T>>,
    mut setting: ResMut<T>,
) {
    if let Some(ChangeSetting(value)) = changes.read().last() {
        setting.set_if_neq(value.clone());
    }
}

/// Registers a setting resource that panels change by [`ChangeSetting`].
pub trait SettingsApp {
    /// Adds the message and its apply system in [`SceneSystems::Requests`].
    fn add_setting<T: Setting>(&mut self) -> &mut Self;
}

impl SettingsApp for App {
    fn add_setting<T: Setting>(&mut self) -> &mut Self {
        self.add_message::<ChangeSetting<T>>().add_systems(
            Update,
            apply_setting_changes::<T>.in_set(SceneSystems::Requests),
        )
    }
}

/// A panel's change to the status line.
#[derive(Message, Clone, Debug, PartialEq)]
pub enum StatusRequest {
    /// Show a failure (in red).
    Error(String),
    /// The warnings dialog was acknowledged: forget its warnings.
    ClearWarnings,
}

/// Applies the panels' [`StatusRequest`]s, in the order they were sent.
pub fn apply_status_requests(
    mut requests: MessageReader<StatusRequest>,
    mut status: ResMut<StatusMessage>,
) {
    for request in requests.read() {
        match request {
            StatusRequest::Error(text) => status.error(text.clone()),
            StatusRequest::ClearWarnings => status.warnings.clear(),
        }
    }
}

/// A panel's preview: what a field being dragged would make of the nodes.
#[derive(Message, Clone, Debug)]
pub enum PreviewRequest {
    /// Show `preview` in `source`'s slot.
    Show(PreviewSource, ToolPreview),
    /// Clear `source`'s slot.
    Clear(PreviewSource),
}

/// Applies the panels' [`PreviewRequest`]s, in the order they were sent.
pub fn apply_preview_requests(
    mut requests: MessageReader<PreviewRequest>,
    mut previews: ResMut<Previews>,
) {
    for request in requests.read() {
        match request {
            PreviewRequest::Show(source, preview) => {
                Previews::show(&mut previews, *source, preview.clone())
            }
            PreviewRequest::Clear(source) => Previews::clear(&mut previews, *source),
        }
    }
}
