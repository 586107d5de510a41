//! Repeated copies of a mesh in a row: the Array modifier's result
//! ([`arrayed`], Blender's Array modifier with a fixed count).

use super::ModelingError;
use super::copies::{CopiedMesh, Soup, check_distance, join, root};
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;
use std::collections::HashMap;

/// The most copies an array makes (Blender's soft limit for the count is
/// 1000; this is the hard one).
pub const MAX_ARRAY_COUNT: u32 = 10_000;

/// How far each copy of an array is from the previous one (Blender's
/// Relative Offset and Constant Offset, both optional and added).
#[derive(Copy, Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ArrayOffset {
    /// Offset as a factor of the mesh's bounding box size per axis
    /// (`(1, 0, 0)`: each copy one box width further along x, touching
    /// the previous one).
    #[serde(default)]
    pub relative: Option<DVec3>,
    /// Offset in local units, added to the relative one.
    #[serde(default)]
    pub constant: Option<DVec3>,
}

impl ArrayOffset {
    /// The step from one copy to the next for a mesh whose bounding box is
    /// `size`: `relative × size + constant` (per component).
    pub fn step(&self, size: DVec3) -> DVec3 {
        self.relative.unwrap_or(DVec3::ZERO) * size + self.constant.unwrap_or(DVec3::ZERO)
    }
}

/// The Array modifier's result (Blender's Array modifier, `MOD_array.cc`,
/// with "Fit Type: Fixed Count"): `count` copies of the mesh, copy `k`
/// moved by `k × offset.step(bounding box size)`, joined into one mesh.
///
/// With `merge: Some(d)` (Blender's Merge option), each vertex of a copy
/// within `d` of a vertex of the previous copy is welded to it (the earlier
/// copy's vertex and position are kept), so copies whose open ends touch
/// become one piece. As in Blender the pairs are found once, between the
/// mesh and itself moved by one step, and used for every neighbouring pair
/// of copies. Blender's "First Last" option (welding the last copy to the
/// first) is not offered: without an object offset the two never meet.
///
/// Isolated vertices and wire edges are not copied. The result's ids are
/// new; see [`arrayed_copies`] for where each element came from.
///
/// # Errors
/// [`ModelingError::Parameter`] for a count of 0 or above
/// [`MAX_ARRAY_COUNT`], a non-finite offset, a negative or non-finite merge
/// distance, or a face with inner rings; [`ModelingError::Empty`] for a
/// mesh without faces; [`ModelingError::Invalid`] with
/// [`InvalidResult::Copies`](super::InvalidResult::Copies) when welded
/// copies are not manifold (copies that overlap, a merge distance larger
/// than the mesh's edges).
///
/// Complexity: O(count × corners) plus a grid search for the merge pairs.
pub fn arrayed(
    mesh: &HalfEdgeMesh,
    count: u32,
    offset: ArrayOffset,
    merge: Option<f64>,
) -> Result<HalfEdgeMesh, ModelingError> {
    arrayed_copies(mesh, count, offset, merge).map(|c| c.mesh)
}

/// [`arrayed`], with the source vertex and face of every result element
/// (to carry creases and corner attributes over).
///
/// # Errors
/// As [`arrayed`].
pub fn arrayed_copies(
    mesh: &HalfEdgeMesh,
    count: u32,
    offset: ArrayOffset,
    merge: Option<f64>,
) -> Result<CopiedMesh, ModelingError> {
    if count == 0 || count > MAX_ARRAY_COUNT {
        return Err(ModelingError::Parameter {
            what: "array count",
            allowed: "between 1 and 10000",
            value: count.to_string(),
        });
    }
    let finite = |v: Option<DVec3>| v.is_none_or(|v| v.is_finite());
    if !finite(offset.relative) || !finite(offset.constant) {
        return Err(ModelingError::Parameter {
            what: "array offset",
            allowed: "finite",
            value: format!("{offset:?}"),
        });
    }
    if let Some(d) = merge {
        check_distance(d)?;
    }
    let mut soup = Soup::of(mesh)?;
    let (lo, hi) = mesh.bounds().unwrap_or_default();
    let step = offset.step(hi - lo);
    let (n, faces) = (soup.positions.len(), soup.polygons.len());
    // Vertex j of copy k+1 welds to vertex pairs[j] of copy k.
    let pairs: Vec<Option<u32>> = match merge {
        Some(d) => pairs_within(&soup.positions, step, d),
        None => vec![None; n],
    };
    let mut bases = vec![0u32];
    for k in 1..count {
        let shift = step * k as f64;
        bases.push(soup.append_copy(n, faces, |p| p + shift, false));
    }
    if merge.is_some() {
        let mut parent: Vec<u32> = (0..soup.positions.len() as u32).collect();
        for w in bases.windows(2) {
            for (j, i) in pairs.iter().enumerate() {
                if let Some(i) = i {
                    join(&mut parent, w[0] + i, w[1] + j as u32);
                }
            }
        }
        let rep: Vec<u32> = (0..parent.len() as u32)
            .map(|k| root(&mut parent, k))
            .collect();
        soup.weld(&rep);
    }
    soup.build("the array")
}

/// For each point `j`, the nearest point `i` with `|p_j + step − p_i| ≤ d`,
/// if any (a uniform grid of cell `d`, as merge by distance).
fn pairs_within(points: &[DVec3], step: DVec3, d: f64) -> Vec<Option<u32>> {
    let cell = d.max(1e-12);
    let key = |p: DVec3| (p / cell).floor().as_i64vec3();
    let mut grid: HashMap<glam::I64Vec3, Vec<u32>> = HashMap::new();
    for (i, &p) in points.iter().enumerate() {
        grid.entry(key(p)).or_default().push(i as u32);
    }
    points
        .iter()
        .map(|&p| {
            let q = p + step;
            let k = key(q);
            let mut best: Option<(f64, u32)> = None;
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        let Some(c) = grid.get(&(k + glam::I64Vec3::new(dx, dy, dz))) else {
                            continue;
                        };
                        for &i in c {
                            let dist = points[i as usize].distance(q);
                            if dist <= d && best.is_none_or(|(b, _)| dist < b) {
                                best = Some((dist, i));
                            }
                        }
                    }
                }
            }
            best.map(|(_, i)| i)
        })
        .collect()
}
