//! A mesh tool's preview handed to the projection as data.

use super::*;
use hedra_scene::{PreviewContent, PreviewSource, Previews, ToolPreview};

/// Puts the running mesh tool's result (`EditMode::preview`, shared, not
/// copied) into its [`Previews`] slot, and clears the slot when the tool
/// ends. The projection draws it: smoothed when the node has a subdivision
/// modifier, patched in place when only positions moved.
pub fn publish_mesh_preview(mode: Res<EditMode>, mut previews: ResMut<Previews>) {
    if !mode.is_changed() {
        return;
    }
    match (mode.node, &mode.preview) {
        (Some(node), Some(mesh)) => Previews::show(
            &mut previews,
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
        _ => Previews::clear(&mut previews, PreviewSource::MeshTool),
    }
}
