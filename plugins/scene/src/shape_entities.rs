//! Curves and surfaces as entities: each control point is a child entity
//! of its node with a [`ControlPoint`] (index, position, weight); each
//! surface is drawn by child entities with a [`SurfacePatch`] and their own
//! render mesh, one per knot-span tile of its render grid. A weight or point
//! drag changes a few `ControlPoint`s, and Bevy's change detection tells
//! [`project_surface_patches`] which patches to re-tessellate: the patches
//! whose inputs changed, and no others.

use crate::*;
use hedra_doc::SurfaceShape;
use hedra_doc::render::{RenderBuffers, SurfaceTile, surface_tiles, tile_buffers};
use hedra_geom::DVec3;

/// A control point of a curve or surface node, on a child entity of the
/// node's entity. Written only by [`project_control_points`], from the
/// document or the running tool's preview.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct ControlPoint {
    /// The point's index, as commands count them (row-major on surfaces).
    pub index: u32,
    /// Local position.
    pub position: DVec3,
    /// Rational weight (1 for shapes without weights).
    pub weight: f64,
}

/// A piece of a surface node's render mesh, on a child entity with its own
/// `Mesh3d`: a knot-span tile of a NURBS surface's grid, or the whole
/// surface (Bézier triangles). Written only by [`project_surface_patches`].
#[derive(Component, Clone, Debug, PartialEq)]
pub struct SurfacePatch {
    /// `None`: the whole surface, shaped by every control point.
    pub tile: Option<SurfaceTile>,
}

/// On a surface node: the layout its patches were made for (the surface's
/// kind, degrees, knots and size, and the render grid), kept while only
/// points and weights change so that a drag never re-lays the patches.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct PatchLayout {
    key: LayoutKey,
    grid: Option<SurfaceGrid>,
}

#[derive(Clone, Debug, PartialEq)]
enum LayoutKey {
    Nurbs {
        degrees: (usize, usize),
        knots: (Vec<f64>, Vec<f64>),
        size: (usize, usize),
    },
    Triangle {
        points: usize,
    },
}

impl LayoutKey {
    fn of(surface: &SurfaceShape) -> LayoutKey {
        match surface {
            SurfaceShape::Nurbs(n) => {
                let (ku, kv) = n.knots();
                LayoutKey::Nurbs {
                    degrees: n.degrees(),
                    knots: (ku.to_vec(), kv.to_vec()),
                    size: n.size(),
                }
            }
            SurfaceShape::Triangle(_) => LayoutKey::Triangle {
                points: surface.control_points().len(),
            },
        }
    }
}

/// The control-point entities' values of the node entity `node`, by index
/// (what the screen shows: the document or a running tool's preview).
pub fn control_points_of(
    node: Entity,
    points: &Query<(&ControlPoint, &ChildOf)>,
) -> Vec<ControlPoint> {
    let mut out: Vec<ControlPoint> = points
        .iter()
        .filter(|(_, parent)| parent.parent() == node)
        .map(|(p, _)| *p)
        .collect();
    out.sort_by_key(|p| p.index);
    out
}

/// Control points of a curve or surface (local space); none for meshes and empties.
pub fn control_points(content: &NodeContent) -> Vec<DVec3> {
    match content {
        // The kind's defining points (interpolation points, anchors and
        // handles, NURBS control points), then a Hermite curve's tangent
        // handle ends: what SetControlPoints indexes.
        NodeContent::Curve(c) => c.edit_points(),
        NodeContent::Surface(s) => s.control_points().to_vec(),
        _ => Vec::new(),
    }
}

/// Weights of the control points, `None` for shapes without weights.
pub fn control_weights(content: &NodeContent) -> Option<Vec<f64>> {
    match content {
        NodeContent::Curve(c) => c.weights().map(<[f64]>::to_vec),
        NodeContent::Surface(s) => match &**s {
            SurfaceShape::Nurbs(n) => Some(n.weights().to_vec()),
            SurfaceShape::Triangle(_) => None,
        },
        _ => None,
    }
}

/// The one writer of [`ControlPoint`]s: one child entity per control point
/// of every curve and surface node, with the values the screen shows
/// ([`ShownShape`]: a tool's preview or the document). Runs for a node when
/// what it shows changed; a value is written only when it differs, so
/// change detection marks exactly the points that moved.
#[allow(clippy::type_complexity)]
pub fn project_control_points(
    mut commands: Commands,
    nodes: Query<(Entity, Option<Ref<ShownShape>>, Option<&Children>)>,
    mut points: Query<&mut ControlPoint>,
) {
    for (entity, shown, children) in &nodes {
        let changed = shown.as_ref().is_some_and(|s| s.is_changed());
        // Nothing to do unless the shape changed, or a node that is no
        // longer a curve or surface still has point entities.
        let is_point = |c: &&Entity| points.contains(**c);
        let shape = shown.is_some();
        if !changed && (shape || !children.into_iter().flatten().any(|c| is_point(&c))) {
            continue;
        }
        let existing: Vec<Entity> = children
            .into_iter()
            .flatten()
            .filter(is_point)
            .copied()
            .collect();
        let content = shown.as_ref().map(|s| s.content());
        let wanted = content.as_ref().map(control_points).unwrap_or_default();
        let weights = content.as_ref().and_then(control_weights);
        let value = |i: usize| ControlPoint {
            index: i as u32,
            position: wanted[i],
            weight: weights.as_ref().map_or(1.0, |w| w[i]),
        };
        if existing.len() == wanted.len() {
            for e in existing {
                let mut p = points.get_mut(e).expect("filtered above");
                let new = value(p.index as usize);
                p.set_if_neq(new);
            }
            continue;
        }
        for e in existing {
            commands.entity(e).despawn();
        }
        for i in 0..wanted.len() {
            commands.spawn((value(i), ChildOf(entity)));
        }
    }
}

/// The one writer of surface patches and their render meshes. Lays out a
/// surface node's patches when it first shows or its kind, degrees, knots
/// or size change (or, outside a tool, its render grid); otherwise
/// re-tessellates exactly the patches one of whose input control points
/// changed since the last frame (Bevy's change detection on
/// [`ControlPoint`]).
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn project_surface_patches(
    mut commands: Commands,
    material: Option<Res<MeshMaterial>>,
    shading: Res<crate::ViewportShading>,
    orientation: Option<Res<crate::FaceOrientationMaterials>>,
    mut meshes: ResMut<Assets<Mesh>>,
    nodes: Query<(
        Entity,
        Option<Ref<ShownShape>>,
        Option<&PatchLayout>,
        Option<&Children>,
    )>,
    points: Query<Ref<ControlPoint>>,
    patches: Query<(&SurfacePatch, &Mesh3d)>,
    patch_materials: Query<(Entity, &MeshMaterial3d<StandardMaterial>), With<SurfacePatch>>,
) {
    let material = material
        .as_deref()
        .map(|m| crate::model_material(m, orientation.as_deref(), &shading));
    crate::refresh_materials(&mut commands, &shading, material.as_ref(), &patch_materials);
    for (entity, shown, layout, children) in &nodes {
        let changed = shown.as_ref().is_some_and(|s| s.is_changed());
        if !changed && (shown.is_some() || layout.is_none()) {
            continue;
        }
        let children: Vec<Entity> = children.into_iter().flatten().copied().collect();
        let old_patches = || children.iter().copied().filter(|c| patches.contains(*c));
        let surface = match shown.as_ref().map(|s| &s.shape) {
            Some(Shape::Surface(s)) => s.clone(),
            _ => {
                if layout.is_some() {
                    old_patches().for_each(|p| commands.entity(p).despawn());
                    commands.entity(entity).remove::<PatchLayout>();
                }
                continue;
            }
        };
        let key = LayoutKey::of(&surface);
        let previewed = shown.as_ref().is_some_and(|s| s.previewed);
        let grid = |s: &SurfaceShape| match s {
            SurfaceShape::Nurbs(n) => Some(surface_grid(n)),
            SurfaceShape::Triangle(_) => None,
        };
        let keep = layout.filter(|l| l.key == key && (previewed || l.grid == grid(&surface)));
        let Some(layout) = keep else {
            old_patches().for_each(|p| commands.entity(p).despawn());
            let layout = PatchLayout {
                key,
                grid: grid(&surface),
            };
            for patch in layout_patches(&surface, layout.grid.as_ref()) {
                let mesh = meshes.add(buffers_mesh(patch_buffers(
                    &surface,
                    layout.grid.as_ref(),
                    &patch,
                )));
                let mut e = commands.spawn((
                    patch,
                    Mesh3d(mesh),
                    Transform::default(),
                    Visibility::default(),
                    ChildOf(entity),
                ));
                if let Some(m) = &material {
                    e.insert(MeshMaterial3d(m.0.clone()));
                }
            }
            commands.entity(entity).insert(layout);
            continue;
        };
        // Which control points changed since the last frame.
        let mut moved = vec![false; surface.control_points().len()];
        for p in children.iter().filter_map(|c| points.get(*c).ok()) {
            if let Some(slot) = moved.get_mut(p.index as usize) {
                *slot = p.is_changed();
            }
        }
        if !moved.contains(&true) {
            continue;
        }
        for (patch, mesh3d) in children.iter().filter_map(|c| patches.get(*c).ok()) {
            let touched = match &patch.tile {
                Some(tile) => tile.inputs.iter().any(|&i| moved[i as usize]),
                None => true,
            };
            if touched && let Some(mut m) = meshes.get_mut(&mesh3d.0) {
                *m = buffers_mesh(patch_buffers(&surface, layout.grid.as_ref(), patch));
            }
        }
    }
}

/// The patches of a surface: its grid's knot-span tiles, or one patch for
/// the whole of a Bézier triangle.
fn layout_patches(surface: &SurfaceShape, grid: Option<&SurfaceGrid>) -> Vec<SurfacePatch> {
    match (surface, grid) {
        (SurfaceShape::Nurbs(n), Some(grid)) => surface_tiles(n, grid)
            .into_iter()
            .map(|tile| SurfacePatch { tile: Some(tile) })
            .collect(),
        _ => vec![SurfacePatch { tile: None }],
    }
}

/// Triangles of one patch.
fn patch_buffers(
    surface: &SurfaceShape,
    grid: Option<&SurfaceGrid>,
    patch: &SurfacePatch,
) -> RenderBuffers {
    match (surface, grid, &patch.tile) {
        (SurfaceShape::Nurbs(n), Some(grid), Some(tile)) => tile_buffers(n, grid, tile),
        _ => {
            let tol = VIEW_TOLERANCE * extent(surface.control_points());
            let (positions, normals, triangles) = surface.tessellate(tol);
            let f32s = |v: &DVec3| v.as_vec3().to_array();
            RenderBuffers {
                positions: positions.iter().map(f32s).collect(),
                normals: normals.iter().map(f32s).collect(),
                indices: triangles.into_iter().flatten().collect(),
            }
        }
    }
}
