//! Render meshes from document content: half-edge meshes (flat or smooth), curves and tessellated surfaces.

use crate::*;

pub use hedra_doc::render::{SurfaceGrid, VIEW_TOLERANCE, extent, surface_grid};

/// A smooth-shaded triangle mesh of a surface node, tessellated to
/// `VIEW_TOLERANCE` of its size; both sides face the viewer (a patch is
/// open, its back is seen too).
pub fn surface_render_mesh(surface: &hedra_doc::SurfaceShape) -> Mesh {
    let tol = VIEW_TOLERANCE * extent(surface.control_points());
    let (positions, normals, triangles) = surface.tessellate(tol);
    let f32s = |v: &hedra_geom::DVec3| v.as_vec3().to_array();
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::MAIN_WORLD | RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(
        Mesh::ATTRIBUTE_POSITION,
        positions.iter().map(f32s).collect::<Vec<_>>(),
    )
    .with_inserted_attribute(
        Mesh::ATTRIBUTE_NORMAL,
        normals.iter().map(f32s).collect::<Vec<_>>(),
    )
    .with_inserted_indices(Indices::U32(triangles.into_iter().flatten().collect()))
}

/// Rewrites the positions and normals of `render` (built on `grid` from
/// `old`) to show `new`, re-evaluating only the grid points inside the
/// knot spans of the control points that changed: a control point (i, j)
/// moves the surface only on `[U_i, U_{i+p+1}] × [V_j, V_{j+q+1}]`.
/// Returns false, changing nothing, when the two surfaces differ in more
/// than points and weights (rebuild then).
pub fn update_surface_render_mesh(
    render: &mut Mesh,
    grid: &SurfaceGrid,
    old: &hedra_geom::surfaces::NurbsSurface,
    new: &hedra_geom::surfaces::NurbsSurface,
) -> bool {
    use bevy::mesh::VertexAttributeValues;
    if old.size() != new.size() || old.degrees() != new.degrees() || old.knots() != new.knots() {
        return false;
    }
    let (nu, nv) = new.size();
    let changed: Vec<usize> = (0..nu * nv)
        .filter(|&k| old.points()[k] != new.points()[k] || old.weights()[k] != new.weights()[k])
        .collect();
    if changed.is_empty() {
        return true;
    }
    let ((p, q), (ku, kv)) = (new.degrees(), new.knots());
    let (mut u_lo, mut u_hi, mut v_lo, mut v_hi) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for k in changed {
        let (i, j) = (k / nv, k % nv);
        u_lo = u_lo.min(ku[i]);
        u_hi = u_hi.max(ku[i + p + 1]);
        v_lo = v_lo.min(kv[j]);
        v_hi = v_hi.max(kv[j + q + 1]);
    }
    let rows: Vec<usize> = (0..grid.us.len())
        .filter(|&a| (u_lo..=u_hi).contains(&grid.us[a]))
        .collect();
    let cols: Vec<usize> = (0..grid.vs.len())
        .filter(|&b| (v_lo..=v_hi).contains(&grid.vs[b]))
        .collect();
    let count = grid.us.len() * grid.vs.len();
    let (
        Some(VertexAttributeValues::Float32x3(positions)),
        Some(VertexAttributeValues::Float32x3(normals)),
    ) = (
        render.attribute(Mesh::ATTRIBUTE_POSITION).cloned(),
        render.attribute(Mesh::ATTRIBUTE_NORMAL).cloned(),
    )
    else {
        return false;
    };
    if positions.len() != count || normals.len() != count {
        return false;
    }
    let (mut positions, mut normals) = (positions, normals);
    let us: Vec<f64> = rows.iter().map(|&a| grid.us[a]).collect();
    let vs: Vec<f64> = cols.iter().map(|&b| grid.vs[b]).collect();
    let (points, norms) = new.grid(&us, &vs, true);
    for (r, &a) in rows.iter().enumerate() {
        for (c, &b) in cols.iter().enumerate() {
            let k = a * grid.vs.len() + b;
            positions[k] = points[r * vs.len() + c].as_vec3().to_array();
            normals[k] = norms[r * vs.len() + c].as_vec3().to_array();
        }
    }
    render.insert_attribute(Mesh::ATTRIBUTE_POSITION, positions);
    render.insert_attribute(Mesh::ATTRIBUTE_NORMAL, normals);
    true
}

/// A triangle render mesh of a half-edge mesh (the buffers of
/// [`hedra_doc::render::render_buffers`]: flat shading gives each face its
/// own corners, smooth shading shares them).
pub fn render_mesh(mesh: &HalfEdgeMesh, shading: Shading) -> Mesh {
    let b = hedra_doc::render::render_buffers(mesh, shading);
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::MAIN_WORLD | RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, b.positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, b.normals)
    .with_inserted_indices(Indices::U32(b.indices))
}
