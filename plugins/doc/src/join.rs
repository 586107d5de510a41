//! The G1 join of a Bézier triangle and a Bézier patch kept live (seed 002's
//! exercise as a feature, issue 20): [`Command::MakeG1Join`](crate::Command::MakeG1Join)
//! makes the pair C0 then G1 (the patch's boundary row becomes the
//! triangle's edge, its next row is set so that the tangent planes agree,
//! [`TriangleQuad::make_g1`]) and stores a [`G1Join`] on the patch node.
//! From then on:
//!
//! - every command that changes either node (its control points, its
//!   degree, its transform or an ancestor's) re-solves the pair in the same
//!   transaction, so one undo restores both: each control point the command
//!   moved is replayed through [`TriangleQuad::move_point`] (the triangle's
//!   first, then the patch's free and shared points, its dependent points
//!   last), so a shared point moves on both patches and the dependent row
//!   follows; a re-solve that fails (the triangle loses its tangent plane
//!   along the edge) refuses the command, naming both nodes;
//! - a change of degree (ElevateDegree) or of either node's world matrix
//!   makes the join again ([`TriangleQuad::make_g1`]): **the triangle
//!   leads** — moving the triangle node carries the shared edge and the
//!   dependent row with it; moving the patch node moves its free points
//!   only, the joint stays on the triangle;
//! - deleting either node, or a patch that stops being one Bézier span with
//!   unit weights (a knot inserted, a weight changed), ends the join (the
//!   step's label says so); [`Command::BreakG1Join`](crate::Command::BreakG1Join)
//!   ends it on request; a duplicate of the patch is not joined.
//!
//! **World space.** Both patches keep their control points in their own
//! node's local space under any transforms. The join works in world space:
//! each patch is taken through its node's world matrix, solved there, and
//! written back through the inverse (affine maps keep Bézier control nets,
//! C0 and tangent planes, so G1 in world space is G1 as drawn). Points the
//! solve does not move keep their local coordinates bit for bit.

use crate::construction::world_through;
use crate::scene::{Document, Node, NodeContent, NodeId, SurfaceShape};
use glam::{DMat4, DVec3};
use hedra_geom::surfaces::patches::{JointReport, PatchError, PatchPoint, TriangleQuad};
use hedra_geom::surfaces::{BezierSurface, BezierTriangle, NurbsSurface};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

pub use hedra_geom::surfaces::patches::PointRole;

/// The record on a patch node that it is kept G1 to a Bézier triangle.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct G1Join {
    /// The Bézier triangle node that leads the join.
    pub triangle: NodeId,
}

/// How far apart (relative to the pair's size: the diagonal of the box of
/// both control nets) the ends of the shared edge may be when the join is
/// made; C0 then closes the gap.
pub const MAKE_TOLERANCE: f64 = 1e-3;

/// How far apart (in world units) the ends of a kept join's edge may drift
/// by rounding when it is found again.
pub const KEEP_TOLERANCE: f64 = 1e-6;

/// Why a G1 join cannot be made or kept.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum JoinError {
    /// The node given as the triangle is not a Bézier triangle.
    #[error("{node} is not a Bézier triangle")]
    NotATriangle {
        /// The node, as `'name' (#id)`.
        node: String,
    },
    /// The node given as the patch is not one Bézier patch.
    #[error("{node} is not a Bézier patch (a NURBS surface of one span with unit weights)")]
    NotAPatch {
        /// The node, as `'name' (#id)`.
        node: String,
    },
    /// The patch is already joined to a triangle.
    #[error("{node} is already joined to {triangle} (break that join first)")]
    AlreadyJoined {
        /// The patch, as `'name' (#id)`.
        node: String,
        /// Its triangle, as `'name' (#id)`.
        triangle: String,
    },
    /// The same node given as both.
    #[error("a node cannot be joined to itself")]
    SameNode,
    /// The kernel refused (no shared edge, a degenerate edge).
    #[error(transparent)]
    Patch(#[from] PatchError),
}

/// The Bézier triangle a node holds, if it holds one.
pub fn triangle_of(content: &NodeContent) -> Option<&BezierTriangle> {
    match content {
        NodeContent::Surface(s) => match &**s {
            SurfaceShape::Triangle(t) => Some(t),
            SurfaceShape::Nurbs(_) => None,
        },
        _ => None,
    }
}

/// The NURBS surface a node holds, if it is one Bézier patch: one knot
/// span in each direction (clamped ends) and every weight 1.
pub fn patch_of(content: &NodeContent) -> Option<&NurbsSurface> {
    let NodeContent::Surface(s) = content else {
        return None;
    };
    let SurfaceShape::Nurbs(n) = &**s else {
        return None;
    };
    let (pu, pv) = n.degrees();
    let (ku, kv) = n.knots();
    let one_span = |k: &[f64], p: usize| {
        k.len() == 2 * (p + 1)
            && k[..=p].iter().all(|&x| x == k[0])
            && k[p + 1..].iter().all(|&x| x == k[k.len() - 1])
    };
    (one_span(ku, pu) && one_span(kv, pv) && n.weights().iter().all(|&w| w == 1.0)).then_some(n)
}

fn world_triangle(t: &BezierTriangle, m: &DMat4) -> BezierTriangle {
    BezierTriangle {
        degree: t.degree,
        points: t.points.iter().map(|&p| m.transform_point3(p)).collect(),
    }
}

fn world_patch(n: &NurbsSurface, m: &DMat4) -> BezierSurface {
    let (nu, nv) = n.size();
    BezierSurface {
        nu,
        nv,
        points: n.points().iter().map(|&p| m.transform_point3(p)).collect(),
    }
}

/// Local points for world points `world` under `m`, keeping `old[k]` where
/// it already maps exactly to `world[k]`.
fn local_points(world: &[DVec3], m: &DMat4, old: &[DVec3]) -> Vec<DVec3> {
    let inverse = m.inverse();
    world
        .iter()
        .enumerate()
        .map(|(k, &w)| match old.get(k) {
            Some(&o) if old.len() == world.len() && m.transform_point3(o) == w => o,
            _ => inverse.transform_point3(w),
        })
        .collect()
}

/// The two nodes' contents for a solved world pair: the triangle's points
/// and the patch's, pulled back through the world matrices (the patch keeps
/// its knot domain; one more row after an elevation gets clamped knots on
/// the same domain).
fn contents(
    pair: &TriangleQuad,
    tri_world: &DMat4,
    tri_old: &BezierTriangle,
    quad_world: &DMat4,
    quad_old: &NurbsSurface,
) -> Result<(NodeContent, NodeContent), PatchError> {
    let tri = BezierTriangle {
        degree: pair.triangle.degree,
        points: local_points(&pair.triangle.points, tri_world, &tri_old.points),
    };
    let points = local_points(&pair.quad.points, quad_world, quad_old.points());
    let (ku, kv) = quad_old.knots();
    let knots = |n: usize, old: &[f64]| {
        let (a, b) = (old[0], old[old.len() - 1]);
        let mut k = vec![a; n];
        k.extend(std::iter::repeat_n(b, n));
        k
    };
    let (nu, nv) = (pair.quad.nu, pair.quad.nv);
    let quad = NurbsSurface::new(
        nu - 1,
        nv - 1,
        knots(nu, ku),
        knots(nv, kv),
        nu,
        nv,
        points,
        vec![1.0; nu * nv],
    )
    .map_err(PatchError::from)?;
    Ok((
        NodeContent::Surface(Arc::new(SurfaceShape::Triangle(tri))),
        NodeContent::Surface(Arc::new(SurfaceShape::Nurbs(quad))),
    ))
}

/// A triangle node and a patch node as [`follow`] and [`make`] take them:
/// the node and its world matrix.
#[derive(Copy, Clone)]
pub struct Placed<'a> {
    /// The node.
    pub node: &'a Node,
    /// Its world matrix.
    pub world: DMat4,
}

fn label(n: &Node) -> String {
    format!("'{}' ({})", n.name, n.id)
}

fn parts<'a>(
    tri: Placed<'a>,
    quad: Placed<'a>,
) -> Result<(&'a BezierTriangle, &'a NurbsSurface), JoinError> {
    let t = triangle_of(&tri.node.content).ok_or_else(|| JoinError::NotATriangle {
        node: label(tri.node),
    })?;
    let q = patch_of(&quad.node.content).ok_or_else(|| JoinError::NotAPatch {
        node: label(quad.node),
    })?;
    Ok((t, q))
}

/// The world pair of a triangle node and a patch node, with the shared
/// edge found within `tolerance` (world units).
///
/// # Errors
/// [`JoinError::NotATriangle`], [`JoinError::NotAPatch`],
/// [`PatchError::NoSharedEdge`].
pub fn world_pair(tri: Placed, quad: Placed, tolerance: f64) -> Result<TriangleQuad, JoinError> {
    let (t, q) = parts(tri, quad)?;
    Ok(TriangleQuad::new(
        world_triangle(t, &tri.world),
        world_patch(q, &quad.world),
        tolerance,
    )?)
}

/// Makes the join (C0, then G1 adjusting the patch's row next to the edge)
/// and returns the two nodes' new contents, triangle first. The edge is
/// found where the patches' corners are within [`MAKE_TOLERANCE`] of the
/// pair's size. Its inverse is keeping the old contents (undo).
///
/// # Errors
/// As [`world_pair`]; [`PatchError::DegenerateEdge`].
///
/// Complexity: O(points of both).
pub fn make(tri: Placed, quad: Placed) -> Result<(NodeContent, NodeContent), JoinError> {
    let (t, q) = parts(tri, quad)?;
    let (wt, wq) = (world_triangle(t, &tri.world), world_patch(q, &quad.world));
    let (lo, hi) = wt
        .points
        .iter()
        .chain(&wq.points)
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
            (lo.min(p), hi.max(p))
        });
    let size = (hi - lo).length();
    let pair = TriangleQuad::new(wt, wq, MAKE_TOLERANCE * size)?.make_g1()?;
    Ok(contents(&pair, &tri.world, t, &quad.world, q)?)
}

/// The pair after a change: `before` is how both nodes were (a kept G1
/// join), `after` how the command left them. Returns the nodes' contents
/// with the join kept (triangle first), or `None` when nothing of either
/// changed. See the module documentation for how each change is followed.
///
/// # Errors
/// [`JoinError::NotATriangle`] / [`JoinError::NotAPatch`] when a node
/// stopped being one (the caller ends the join); [`PatchError`] when the
/// pair cannot be solved (the caller refuses the change).
///
/// Complexity: O(moved points · n) for moved points, O(points) otherwise.
pub fn follow(
    before: (Placed, Placed),
    after: (Placed, Placed),
) -> Result<Option<(NodeContent, NodeContent)>, JoinError> {
    let (t1, q1) = parts(after.0, after.1)?;
    let (t0, q0) = parts(before.0, before.1)?;
    let old = TriangleQuad::new(
        world_triangle(t0, &before.0.world),
        world_patch(q0, &before.1.world),
        KEEP_TOLERANCE * (1.0 + size_of(t0, q0, &before.0.world, &before.1.world)),
    )?;
    let new_t = world_triangle(t1, &after.0.world);
    let new_q = world_patch(q1, &after.1.world);
    let same_shape =
        new_t.degree == old.triangle.degree && (new_q.nu, new_q.nv) == (old.quad.nu, old.quad.nv);
    let same_place = before.0.world == after.0.world && before.1.world == after.1.world;
    let pair = if !same_shape || !same_place {
        let edge = if same_shape {
            old.edge
        } else {
            TriangleQuad::new(new_t.clone(), new_q.clone(), f64::INFINITY)?.edge
        };
        TriangleQuad {
            triangle: new_t,
            quad: new_q,
            edge,
        }
        .make_g1()?
    } else {
        let mut pair = old.clone();
        for (k, (&a, &b)) in old.triangle.points.iter().zip(&new_t.points).enumerate() {
            if a != b {
                pair = pair.move_point(PatchPoint::Triangle(k), b)?.0;
            }
        }
        let moved: Vec<usize> = (0..old.quad.points.len())
            .filter(|&k| old.quad.points[k] != new_q.points[k])
            .collect();
        let dependent = |k: &usize| old.role(PatchPoint::Quad(*k)) == PointRole::Dependent;
        let (last, first): (Vec<usize>, Vec<usize>) = moved.into_iter().partition(dependent);
        for k in first.into_iter().chain(last) {
            pair = pair.move_point(PatchPoint::Quad(k), new_q.points[k])?.0;
        }
        if pair == old {
            return Ok(None);
        }
        pair
    };
    Ok(Some(contents(
        &pair,
        &after.0.world,
        t1,
        &after.1.world,
        q1,
    )?))
}

fn size_of(t: &BezierTriangle, q: &NurbsSurface, mt: &DMat4, mq: &DMat4) -> f64 {
    let (lo, hi) = t
        .points
        .iter()
        .map(|&p| mt.transform_point3(p))
        .chain(q.points().iter().map(|&p| mq.transform_point3(p)))
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        });
    (hi - lo).length()
}

impl Document {
    /// Every kept G1 join as `(patch node, triangle node)`, in patch id order.
    pub fn g1_joins(&self) -> Vec<(NodeId, NodeId)> {
        self.nodes
            .values()
            .filter_map(|n| n.g1_join.map(|j| (n.id, j.triangle)))
            .collect()
    }

    fn placed(&self, id: NodeId) -> Option<Placed<'_>> {
        Some(Placed {
            node: self.nodes.get(&id)?,
            world: self.world_matrix(id),
        })
    }

    /// The world pair of the join on patch node `quad`, as the kernel sees
    /// it (for the panel: [`TriangleQuad::report`]); `None` when `quad`
    /// has no join or the pair cannot be read.
    pub fn g1_pair(&self, quad: NodeId) -> Option<TriangleQuad> {
        let join = self.nodes.get(&quad)?.g1_join?;
        let (t, q) = (self.placed(join.triangle)?, self.placed(quad)?);
        let (tt, qq) = parts(t, q).ok()?;
        let tolerance = KEEP_TOLERANCE * (1.0 + size_of(tt, qq, &t.world, &q.world));
        world_pair(t, q, tolerance).ok()
    }

    /// The join's largest normal angle (radians) and gap along the joint,
    /// at 101 points in world space, for the panel; `None` as
    /// [`g1_pair`](Self::g1_pair). O(100 · n²).
    pub fn g1_report(&self, quad: NodeId) -> Option<JointReport> {
        Some(self.g1_pair(quad)?.report(100))
    }

    /// What each control point of `node` is to the joins it is in, in the
    /// node's control point order, for colours: [`PointRole::Shared`] on a
    /// shared edge (moving it moves both patches), [`PointRole::Dependent`]
    /// in a patch's row next to the edge (re-solved after every move;
    /// dragged, it goes to the nearest place that keeps G1),
    /// [`PointRole::Free`] otherwise. `None` when the node is in no join.
    pub fn g1_roles(&self, node: NodeId) -> Option<Vec<PointRole>> {
        let n = self.nodes.get(&node)?;
        let mut roles = vec![PointRole::Free; n.content_control_point_count()];
        let mut any = false;
        for (quad, tri) in self.g1_joins() {
            if quad != node && tri != node {
                continue;
            }
            let Some(pair) = self.g1_pair(quad) else {
                continue;
            };
            any = true;
            for (p, role) in pair.roles() {
                let k = match p {
                    PatchPoint::Triangle(k) if tri == node => k,
                    PatchPoint::Quad(k) if quad == node => k,
                    _ => continue,
                };
                if let Some(slot) = roles.get_mut(k)
                    && *slot == PointRole::Free
                {
                    *slot = role;
                }
            }
        }
        any.then_some(roles)
    }

    /// The contents the joined nodes would have if the node were `changed`
    /// (its control points or transform differing from the document's), for
    /// a live preview while the app drags a point of a joined patch without
    /// a command: `changed`'s own corrected content (a dragged dependent
    /// point moves its whole row) and its partners'. A join that cannot
    /// follow is left out (the command that ends the drag refuses in the
    /// same case). The document is not changed. O(joins · n).
    pub fn g1_preview(&self, changed: &Node) -> Vec<(NodeId, NodeContent)> {
        let lookup = |id: NodeId| -> Option<&Node> {
            if id == changed.id {
                Some(changed)
            } else {
                self.nodes.get(&id)
            }
        };
        let mut out: Vec<(NodeId, NodeContent)> = Vec::new();
        for (quad, tri) in self.g1_joins() {
            let moved = |id: NodeId| self.is_ancestor(changed.id, id);
            if !moved(quad) && !moved(tri) {
                continue;
            }
            let (Some(t0), Some(q0)) = (self.placed(tri), self.placed(quad)) else {
                continue;
            };
            let at = |id: NodeId| {
                lookup(id).map(|node| Placed {
                    node,
                    world: world_through(&lookup, id),
                })
            };
            let (Some(t1), Some(q1)) = (at(tri), at(quad)) else {
                continue;
            };
            if let Ok(Some((tc, qc))) = follow((t0, q0), (t1, q1)) {
                out.retain(|(id, _)| *id != tri && *id != quad);
                out.push((tri, tc));
                out.push((quad, qc));
            }
        }
        out
    }
}

impl Node {
    fn content_control_point_count(&self) -> usize {
        match &self.content {
            NodeContent::Surface(s) => s.control_points().len(),
            NodeContent::Curve(c) => c.edit_points().len(),
            _ => 0,
        }
    }
}
