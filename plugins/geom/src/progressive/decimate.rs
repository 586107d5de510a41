//! One-shot decimation to a target, and re-pairing triangles into quads.

use super::{DecimateError, DecimateOptions, DecimateTarget, ProgressiveMesh};
use crate::ids::{EdgeId, FaceId};
use crate::mesh::HalfEdgeMesh;
use crate::subdivision::Creases;

/// Simplifies `mesh` to `target` in one go (Blender's Decimate ▸
/// Collapse, applied): builds the progressive mesh and returns the level,
/// triangulated, in the input's ids where they survive (triangulation's
/// new edges and faces have fresh ones).
///
/// Inverse: none (keep the [`ProgressiveMesh`] to go back).
///
/// # Errors
/// As [`ProgressiveMesh::build`] and [`ProgressiveMesh::level_for`]
/// ([`DecimateError::BelowMinimum`] when the target is below what the
/// mesh can be simplified to).
///
/// Complexity: O(n log n).
pub fn decimate(
    mesh: &HalfEdgeMesh,
    creases: &Creases,
    options: &DecimateOptions,
    target: DecimateTarget,
) -> Result<HalfEdgeMesh, DecimateError> {
    let mut pm = ProgressiveMesh::build(mesh, creases, options)?;
    let level = pm.level_for(target)?;
    pm.seek(level)?;
    Ok(pm.output_mesh(&pm.level_creases(creases), options))
}

/// Joins pairs of triangles of a decimated level into quads, pairing as
/// many as it can (Decimate's keep-quads): the good pairs of Blender's
/// Tris to Quads first ([`tris_to_quads`](crate::modeling::tris_to_quads)
/// with its default 40° limits on the faces' angle and on the corners'
/// distance from a right angle, best first; the faces' angle is the quad's
/// fold across either diagonal, [`quad_fold`](crate::modeling::quad_fold),
/// so that a reader splitting the quad the other way sees the same limit),
/// then pairs with corners up to
/// [`LOOSE_JOIN_LIMIT`] from a right angle for the triangles left over,
/// and augmenting paths that re-pair two joined triangles so that two
/// more join (a maximum matching of the triangles, nearly). Each join is
/// a [`kill_edge_face`](HalfEdgeMesh::kill_edge_face). Never across a
/// feature edge that the simplification kept: a crease of `creases`
/// (when `options.keep_creases`), a seam of `options`, or an edge sharper
/// than `options.sharp_angle`. Returns the quads made.
///
/// Why re-pairing rather than collapsing only along edges that keep
/// quads: the quadric collapses stay those of the triangle mesh, so the
/// progressive record, its error bound and the speed do not change, and
/// every level is still a valid mesh (a KEF keeps it valid); a quad grid
/// comes back as quads at the finest level (its own pairs are exact
/// squares, the best joins). Coarse levels are mostly quads by face count
/// (measured on a curved 24 × 24 sheet, a 48 × 24 torus and a cube cut
/// 16 × 16 per side, at 50, 25, 10 and 5 % of the triangles: see the
/// test `keep_quads_gives_mostly_quads_at_every_level`).
///
/// Inverse: none (triangulate the quads to go back to the level).
///
/// # Errors
/// None in practice: only the join's own refusals
/// ([`DecimateError::Triangulate`]), which a valid level never raises.
///
/// Complexity: O(t log t) for t triangles.
pub fn join_quads(
    mesh: &mut HalfEdgeMesh,
    creases: &Creases,
    options: &DecimateOptions,
) -> Result<Vec<FaceId>, DecimateError> {
    let triangles: Vec<FaceId> = mesh.faces().filter(|&f| mesh.face_degree(f) == 3).collect();
    if triangles.is_empty() {
        return Ok(Vec::new());
    }
    let cos_sharp = options.sharp_angle.map(|a| a.to_radians().cos());
    let joinable = |e: EdgeId| {
        if options.keep_creases && creases.edge(e) > 0.0 {
            return false;
        }
        if options.seams.contains(&e) {
            return false;
        }
        match (cos_sharp, mesh.edge_faces(e)) {
            (Some(c), [Some(f), Some(g)]) => mesh.face_normal(f).dot(mesh.face_normal(g)) >= c,
            _ => true,
        }
    };
    let limit = crate::modeling::DEFAULT_JOIN_LIMIT;
    let pairs =
        crate::modeling::quad_pairing(mesh, &triangles, limit, limit, LOOSE_JOIN_LIMIT, joinable);
    let mut quads = Vec::with_capacity(pairs.len());
    for e in pairs {
        let [Some(a), Some(b)] = mesh.edge_faces(e) else {
            continue;
        };
        let killed = mesh
            .kill_edge_face(e)
            .map_err(|err| DecimateError::Triangulate(err.into()))?;
        quads.push(if killed == a { b } else { a });
    }
    Ok(quads)
}

/// How far from a right angle a corner of a quad that keep-quads makes
/// from two leftover triangles may be (70°: corners between 20° and
/// 160°); good pairs use Blender's 40° first.
pub const LOOSE_JOIN_LIMIT: f64 = 70.0 * std::f64::consts::PI / 180.0;
