//! Rip, vertex split and the Euler operators as commands: the elements the
//! sets and corners name are resolved to exactly one each, then the
//! kernel's operator runs on a copy of the mesh (`modeling::rip_edges`,
//! `HalfEdgeMesh::split_vertex`, `make_edge_vertex`, …); a refusal names the
//! element, as the kernel's [`EulerError`](hedra_geom::EulerError) says it.

use super::plan::{Plan, Refusal};
use super::spec::{Corner, EulerOp};
use super::{CommandError, EditError, NodeRef};
use crate::elements::{EdgeSet, FaceSet, VertexSet};
use glam::DVec3;
use hedra_geom::modeling::{self, ModelingError};
use hedra_geom::{EdgeId, FaceId, HalfEdgeId, HalfEdgeMesh, LoopStart, VertexId};

/// The one vertex a set names.
pub(super) fn one_vertex(
    m: &HalfEdgeMesh,
    set: &VertexSet,
    role: &'static str,
) -> Result<VertexId, EditError> {
    let vs = set.resolve(m)?;
    match vs[..] {
        [v] => Ok(v),
        _ => Err(EditError::NotOne {
            role,
            count: vs.len(),
        }),
    }
}

/// The one edge a set names.
fn one_edge(m: &HalfEdgeMesh, set: &EdgeSet, role: &'static str) -> Result<EdgeId, EditError> {
    let es = set.resolve(m)?;
    match es[..] {
        [e] => Ok(e),
        _ => Err(EditError::NotOne {
            role,
            count: es.len(),
        }),
    }
}

/// The one face a set names.
fn one_face(m: &HalfEdgeMesh, set: &FaceSet, role: &'static str) -> Result<FaceId, EditError> {
    let fs = set.resolve(m)?;
    match fs[..] {
        [f] => Ok(f),
        _ => Err(EditError::NotOne {
            role,
            count: fs.len(),
        }),
    }
}

/// The half-edge from one vertex to another.
fn halfedge(m: &HalfEdgeMesh, from: VertexId, to: VertexId) -> Result<HalfEdgeId, EditError> {
    m.find_halfedge(from, to)
        .ok_or(EditError::NotJoined { a: from, b: to })
}

/// A corner as the half-edge arriving at it, or the lone vertex.
enum Resolved {
    Arriving(HalfEdgeId),
    Lone(VertexId),
}

fn corner(m: &HalfEdgeMesh, c: &Corner) -> Result<Resolved, EditError> {
    match c {
        Corner::At { at, from } => {
            let at = one_vertex(m, at, "a corner's `at`")?;
            let from = one_vertex(m, from, "a corner's `from`")?;
            Ok(Resolved::Arriving(halfedge(m, from, at)?))
        }
        Corner::Lone(v) => Ok(Resolved::Lone(one_vertex(m, v, "a lone corner")?)),
    }
}

/// A corner as the kernel's [`LoopStart`] (the half-edge leaving it).
fn loop_start(m: &HalfEdgeMesh, c: &Corner) -> Result<LoopStart, EditError> {
    Ok(match corner(m, c)? {
        Resolved::Arriving(h) => LoopStart::HalfEdge(m.next(h)),
        Resolved::Lone(v) => LoopStart::Vertex(v),
    })
}

/// A corner that must be on edges (MEF).
fn arriving(m: &HalfEdgeMesh, c: &Corner) -> Result<HalfEdgeId, EditError> {
    match corner(m, c)? {
        Resolved::Arriving(h) => Ok(h),
        Resolved::Lone(vertex) => Err(EditError::LoneCorner { vertex }),
    }
}

impl Plan<'_> {
    pub(super) fn rip(&mut self, node: &NodeRef, edges: &EdgeSet) -> Result<(), CommandError> {
        self.on_edges(node, edges, |m, es| modeling::rip_edges(m, es).map(drop))
    }

    pub(super) fn rip_vertex(
        &mut self,
        node: &NodeRef,
        vertex: &VertexSet,
        face: &FaceSet,
    ) -> Result<(), CommandError> {
        self.model(node, |m| {
            let v = one_vertex(m, vertex, "`vertex`")?;
            let f = one_face(m, face, "`face`")?;
            modeling::rip_vertex(m, v, f)?;
            Ok(())
        })
    }

    pub(super) fn split_vertex(
        &mut self,
        node: &NodeRef,
        vertex: &VertexSet,
        first: &VertexSet,
        last: &VertexSet,
        position: DVec3,
    ) -> Result<(), CommandError> {
        self.model(node, |m| {
            let v = one_vertex(m, vertex, "`vertex`")?;
            let a = halfedge(m, v, one_vertex(m, first, "`first`")?)?;
            let b = halfedge(m, v, one_vertex(m, last, "`last`")?)?;
            m.split_vertex(v, a, b, position).map_err(euler)?;
            Ok(())
        })
    }

    pub(super) fn euler(&mut self, node: &NodeRef, op: &EulerOp) -> Result<(), CommandError> {
        self.model(node, |m| {
            match op {
                EulerOp::Mev {
                    corner: c,
                    position,
                } => match corner(m, c)? {
                    Resolved::Arriving(h) => m.make_edge_vertex(h, *position).map(drop),
                    Resolved::Lone(v) => m.make_edge_vertex_lone(v, *position).map(drop),
                },
                EulerOp::Kev { edge } => m.kill_edge_vertex(one_edge(m, edge, "`edge`")?).map(drop),
                EulerOp::Mef { a, b } => {
                    let (a, b) = (arriving(m, a)?, arriving(m, b)?);
                    m.make_edge_face(a, b).map(drop)
                }
                EulerOp::Kef { edge } => m.kill_edge_face(one_edge(m, edge, "`edge`")?).map(drop),
                EulerOp::Kemr { from, to } => {
                    let from = one_vertex(m, from, "`from`")?;
                    let to = one_vertex(m, to, "`to`")?;
                    m.kill_edge_make_ring(halfedge(m, from, to)?).map(drop)
                }
                EulerOp::Mekr { a, ring } => {
                    let (a, ring) = (loop_start(m, a)?, loop_start(m, ring)?);
                    m.make_edge_kill_ring(a, ring).map(drop)
                }
                EulerOp::Kfmrh { keep, kill } => {
                    let keep = one_face(m, keep, "`keep`")?;
                    let kill = one_face(m, kill, "`kill`")?;
                    m.kill_face_make_ring_hole(keep, kill).map(drop)
                }
                EulerOp::Mfkrh { ring } => {
                    let ring = loop_start(m, ring)?;
                    m.make_face_kill_ring_hole(ring).map(drop)
                }
                EulerOp::Mvfs { position } => m.make_vertex_face_shell(*position).map(drop),
                EulerOp::Kvfs { vertex } => {
                    let v = one_vertex(m, vertex, "`vertex`")?;
                    let f = m
                        .lone_vertex_loop(v)
                        .ok_or(hedra_geom::EulerError::NotLoneVertex { vertex: v })
                        .map_err(euler)?;
                    m.kill_vertex_face_shell(f).map(drop)
                }
            }
            .map_err(euler)
        })
    }
}

/// An Euler operator's refusal, as the kernel words it.
fn euler(e: hedra_geom::EulerError) -> Refusal {
    Refusal::Modeling(ModelingError::Euler(e))
}
