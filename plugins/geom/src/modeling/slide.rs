//! Edge slide (Blender's G G): moving edge chains along their rails.

use super::ModelingError;
use crate::ids::{EdgeId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;

/// Slides the vertices of selected edge chains (loops or open paths) along
/// the edges beside them (Blender's edge slide, G G): with `factor` in
/// [−1, 1], every vertex moves that fraction of the way to the far end of
/// its rail, the rails on one side of the chain for a positive factor and
/// on the other for a negative one. Vertices without a rail on that side
/// stay. Connectivity does not change.
///
/// # Errors
/// [`ModelingError::Parameter`] for a factor outside [−1, 1] or edges that
/// do not form simple chains (a vertex with three selected edges).
pub fn slide_edges(
    mesh: &mut HalfEdgeMesh,
    edges: &[EdgeId],
    factor: f64,
) -> Result<(), ModelingError> {
    if edges.is_empty() {
        return Err(ModelingError::Empty("no edges"));
    }
    if let Some(e) = edges.iter().find(|e| !mesh.is_edge(**e)) {
        return Err(ModelingError::Missing((*e).into()));
    }
    if !(factor.is_finite() && (-1.0..=1.0).contains(&factor)) {
        return Err(ModelingError::Parameter {
            what: "factor",
            allowed: "-1 to 1",
            value: factor.to_string(),
        });
    }
    let selected: std::collections::HashSet<EdgeId> = edges.iter().copied().collect();
    let chain_at = |v: VertexId| {
        mesh.vertex_outgoing(v)
            .filter(|h| selected.contains(&h.edge()))
            .collect::<Vec<_>>()
    };
    for &e in edges {
        for v in mesh.edge_vertices(e) {
            let n = chain_at(v).len();
            if n > 2 {
                return Err(ModelingError::Parameter {
                    what: "edges",
                    allowed: "simple chains or loops",
                    value: format!("{v} joins {n} selected edges"),
                });
            }
        }
    }
    // Walk each chain once, every half-edge pointing the same way along it.
    let mut done = std::collections::HashSet::new();
    let mut targets: Vec<(VertexId, DVec3)> = Vec::new();
    for &e in edges {
        if done.contains(&e) {
            continue;
        }
        // Back up to an end of an open chain (or all the way round a loop).
        let mut h = e.halfedge(0);
        let mut steps = 0;
        while let Some(prev) = chain_at(mesh.origin(h))
            .into_iter()
            .map(|o| o.twin())
            .find(|x| x.edge() != h.edge())
        {
            h = prev;
            steps += 1;
            if h.edge() == e || steps > edges.len() {
                break;
            }
        }
        let mut hs = vec![h];
        done.insert(h.edge());
        loop {
            let last = *hs.last().expect("not empty");
            let Some(next) = chain_at(mesh.target(last))
                .into_iter()
                .find(|o| o.edge() != last.edge())
            else {
                break;
            };
            if !done.insert(next.edge()) {
                break; // back at the start of a loop
            }
            hs.push(next);
        }
        let closed = chain_at(mesh.origin(hs[0])).len() == 2
            && mesh.target(*hs.last().expect("not empty")) == mesh.origin(hs[0]);
        let n = hs.len();
        let count = if closed { n } else { n + 1 };
        for i in 0..count {
            let v = if i < n {
                mesh.origin(hs[i])
            } else {
                mesh.target(hs[n - 1])
            };
            let incoming = if i > 0 {
                Some(hs[i - 1])
            } else if closed {
                Some(hs[n - 1])
            } else {
                None
            };
            let outgoing = if i < n { Some(hs[i]) } else { None };
            let on_face = |x: HalfEdgeId| mesh.face(x).is_some();
            let rail = if factor >= 0.0 {
                // Left of the chain: the next half-edge in the face of the incoming one.
                incoming
                    .filter(|&x| on_face(x))
                    .map(|x| mesh.next(x))
                    .or_else(|| {
                        outgoing
                            .map(|o| mesh.prev(o))
                            .filter(|&p| on_face(p))
                            .map(|p| p.twin())
                    })
            } else {
                // Right of the chain: the same, walking the chain backwards.
                outgoing
                    .map(|o| o.twin())
                    .filter(|&x| on_face(x))
                    .map(|x| mesh.next(x))
                    .or_else(|| {
                        incoming
                            .map(|h| mesh.prev(h.twin()))
                            .filter(|&p| on_face(p))
                            .map(|p| p.twin())
                    })
            };
            if let Some(r) = rail.filter(|r| mesh.origin(*r) == v && !selected.contains(&r.edge()))
            {
                let p = mesh.position(v);
                targets.push((v, p + (mesh.position(mesh.target(r)) - p) * factor.abs()));
            }
        }
    }
    for (v, p) in targets {
        mesh.set_position(v, p);
    }
    Ok(())
}
