//! A mesh tool's preview handed to the projection as data.

use super::*;
use hedra_scene::{PreviewContent, PreviewSource, Previews, ToolPreview};

/// Puts the running mesh tool's result (`EditMode::preview`, shared, not
/// copied) into its [`Previews`] slot, and clears the slot when the tool
/// ends; called by [`drive_mesh_tool`] after each step. The projection
/// draws it: smoothed when the node has a subdivision modifier, patched in
/// place when only positions moved.
pub(super) fn show_mesh_tool_preview(mode: &ResMut<EditMode>, previews: &mut ResMut<Previews>) {
    if !mode.is_changed() {
        return;
    }
    match (mode.node, &mode.preview) {
        (Some(node), Some(mesh)) => Previews::show(
            previews,
            PreviewSource::MeshTool,
            ToolPreview {
                contents: [(
                    node,
                    PreviewContent::Mesh {
                        mesh: mesh.clone(),
                        creases: mode.preview_creases.clone(),
                    },
                )]
                .into(),
                ..default()
            },
        ),
        _ => Previews::clear(previews, PreviewSource::MeshTool),
    }
}
