//! Render meshes from document content: half-edge meshes (flat or smooth);
//! surfaces are drawn by patch entities (`shape_entities`).

use crate::*;

pub use hedra_doc::render::{SurfaceGrid, VIEW_TOLERANCE, extent, surface_grid};

/// A triangle render mesh of a half-edge mesh (the buffers of
/// [`hedra_doc::render::render_buffers_creased`]: flat shading gives each
/// face its own corners, smooth shading shares them except across
/// infinitely sharp creases, where each side keeps its own normal).
pub fn render_mesh(
    mesh: &HalfEdgeMesh,
    shading: Shading,
    creases: &hedra_geom::subdivision::Creases,
) -> Mesh {
    buffers_mesh(hedra_doc::render::render_buffers_creased(
        mesh, shading, creases,
    ))
}

/// A Bevy triangle mesh of render buffers, kept in the main world too (the
/// projection patches its positions in place).
pub fn buffers_mesh(b: hedra_doc::render::RenderBuffers) -> Mesh {
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::MAIN_WORLD | RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, b.positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, b.normals)
    .with_inserted_indices(Indices::U32(b.indices))
}
