//! Bridging two boundary loops with a ring of quads (Blender's "Bridge
//! Edge Loops").

use super::{InvalidResult, ModelingError, NewFace};
use crate::ids::{EdgeId, FaceId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;

/// Bridges two boundary loops with a ring of quads (Blender's "Bridge Edge
/// Loops"). `edges` name at least one edge of each loop; the loops need the
/// same number of edges. Vertices are paired around the loops with the
/// rotation that keeps the quads shortest. Returns the new faces.
///
/// # Errors
/// [`ModelingError::Parameter`] when the edges do not lie on exactly two
/// boundary loops of equal length; [`ModelingError::Invalid`] when the
/// quads cannot be added manifold. The mesh is unchanged on error.
pub fn bridge_loops(
    mesh: &mut HalfEdgeMesh,
    edges: &[EdgeId],
) -> Result<Vec<FaceId>, ModelingError> {
    if let Some(e) = edges.iter().find(|e| !mesh.is_edge(**e)) {
        return Err(ModelingError::Missing((*e).into()));
    }
    let loops = mesh.boundary_loops();
    let mut chosen: Vec<&Vec<HalfEdgeId>> = loops
        .iter()
        .filter(|l| l.iter().any(|h| edges.contains(&h.edge())))
        .collect();
    chosen.dedup();
    if chosen.len() != 2 || chosen[0].len() != chosen[1].len() {
        return Err(ModelingError::Parameter {
            what: "edges",
            allowed: "edges of exactly two boundary loops with the same number of edges",
            value: format!(
                "{} loop(s) of lengths {:?}",
                chosen.len(),
                chosen.iter().map(|l| l.len()).collect::<Vec<_>>()
            ),
        });
    }
    let a: Vec<VertexId> = chosen[0].iter().map(|&h| mesh.origin(h)).collect();
    let b: Vec<VertexId> = chosen[1].iter().map(|&h| mesh.origin(h)).collect();
    let n = a.len();
    let at = |k: i64| b[k.rem_euclid(n as i64) as usize];
    // a[i] pairs with b[s - i]: the loops run in opposite directions across the bridge.
    let cost = |s: i64| -> f64 {
        (0..n as i64)
            .map(|i| {
                mesh.position(a[i as usize])
                    .distance_squared(mesh.position(at(s - i)))
            })
            .sum()
    };
    let s = (0..n as i64)
        .min_by(|x, y| cost(*x).total_cmp(&cost(*y)))
        .expect("loops are not empty");
    let mut work = mesh.clone();
    let mut out = Vec::with_capacity(n);
    for i in 0..n as i64 {
        let quad = [
            a[i as usize],
            a[((i + 1) as usize) % n],
            at(s - i - 1),
            at(s - i),
        ];
        out.push(work.add_face(&quad).map_err(|error| {
            ModelingError::Invalid(InvalidResult::Face {
                face: NewFace::BridgeQuad { index: i as usize },
                error,
            })
        })?);
    }
    work.validate()?;
    *mesh = work;
    Ok(out)
}
