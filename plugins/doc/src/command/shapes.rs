//! Commands on curves and surfaces: adding them from their specs, moving
//! control points, weights, knot insertion and degree elevation.

use super::plan::Plan;
use super::{CommandError, CurveSpec, NodeRef, ParameterDirection, SurfaceSpec};
use crate::scene::{NodeContent, NodeTransform, SurfaceShape};
use glam::DVec3;
use hedra_geom::curves::nurbs::clamped_uniform_knots;
use hedra_geom::curves::{CurveError, NurbsCurve};
use hedra_geom::surfaces::{BezierTriangle, NurbsSurface};
use std::sync::Arc;

fn curve_from_spec(spec: &CurveSpec) -> Result<NurbsCurve, CurveError> {
    match spec {
        CurveSpec::Nurbs {
            degree,
            points,
            weights,
            knots,
        } => NurbsCurve::new(
            *degree,
            knots
                .clone()
                .unwrap_or_else(|| clamped_uniform_knots(*degree, points.len())),
            points.clone(),
            weights.clone().unwrap_or_else(|| vec![1.0; points.len()]),
        ),
        CurveSpec::Bezier { points } => {
            let degree = points.len().saturating_sub(1).max(1);
            NurbsCurve::clamped(degree, points.clone())
        }
        CurveSpec::Circle { radius } => {
            if !(radius.is_finite() && *radius > 0.0) {
                return Err(CurveError::NotPositive {
                    what: "a circle's radius",
                    value: *radius,
                });
            }
            Ok(NurbsCurve::circle(DVec3::ZERO, *radius))
        }
        CurveSpec::Closed {
            degree,
            points,
            weights,
        } => NurbsCurve::periodic(
            *degree,
            points.clone(),
            weights.clone().unwrap_or_else(|| vec![1.0; points.len()]),
        ),
    }
}

fn positive(what: &'static str, x: f64) -> Result<(), CurveError> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(CurveError::NotPositive { what, value: x })
    }
}

impl Plan<'_> {
    /// The curve of a surface's profile node; `node` names the surface.
    fn profile_curve(&self, r: &NodeRef, node: &str) -> Result<NurbsCurve, CommandError> {
        let id = match self.resolve(r) {
            Ok(id) => id,
            Err(CommandError::UnknownNode(profile)) => {
                return Err(CommandError::NoProfile {
                    node: node.to_string(),
                    profile,
                });
            }
            Err(e) => return Err(e),
        };
        match self.current(id).map(|n| &n.content) {
            Some(NodeContent::Curve(c)) => Ok((**c).clone()),
            _ => Err(CommandError::ProfileNotACurve {
                node: node.to_string(),
                profile: r.clone(),
            }),
        }
    }

    /// The surface a spec describes (Revolve and Extrude read another
    /// node's curve, looked up first); `node` names the surface.
    fn surface_from_spec(
        &self,
        spec: &SurfaceSpec,
        node: &str,
    ) -> Result<SurfaceShape, CommandError> {
        let curve = |error: CurveError| CommandError::Curve {
            node: node.to_string(),
            error,
        };
        Ok(match spec {
            SurfaceSpec::Nurbs {
                degree_u,
                degree_v,
                nu,
                nv,
                points,
                weights,
                knots_u,
                knots_v,
            } => SurfaceShape::Nurbs(
                NurbsSurface::new(
                    *degree_u,
                    *degree_v,
                    knots_u
                        .clone()
                        .unwrap_or_else(|| clamped_uniform_knots(*degree_u, *nu)),
                    knots_v
                        .clone()
                        .unwrap_or_else(|| clamped_uniform_knots(*degree_v, *nv)),
                    *nu,
                    *nv,
                    points.clone(),
                    weights.clone().unwrap_or_else(|| vec![1.0; points.len()]),
                )
                .map_err(curve)?,
            ),
            SurfaceSpec::Bezier { nu, nv, points } => SurfaceShape::Nurbs(
                NurbsSurface::from_bezier(*nu, *nv, points.clone()).map_err(curve)?,
            ),
            SurfaceSpec::Triangle { degree, points } => {
                SurfaceShape::Triangle(BezierTriangle::new(*degree, points.clone()).map_err(curve)?)
            }
            SurfaceSpec::Plane { size } => {
                positive("size", *size).map_err(curve)?;
                SurfaceShape::Nurbs(NurbsSurface::plane(*size))
            }
            SurfaceSpec::Sphere { radius } => {
                positive("radius", *radius).map_err(curve)?;
                SurfaceShape::Nurbs(NurbsSurface::sphere(DVec3::ZERO, *radius))
            }
            SurfaceSpec::Cylinder { radius, height } => {
                positive("radius", *radius).map_err(curve)?;
                positive("height", *height).map_err(curve)?;
                SurfaceShape::Nurbs(NurbsSurface::cylinder(*radius, *height))
            }
            SurfaceSpec::Revolve { profile: r } => {
                let c = self.profile_curve(r, node)?;
                SurfaceShape::Nurbs(NurbsSurface::revolve(&c).map_err(curve)?)
            }
            SurfaceSpec::Extrude {
                profile: r,
                direction,
            } => {
                let c = self.profile_curve(r, node)?;
                SurfaceShape::Nurbs(NurbsSurface::extrude(&c, *direction).map_err(curve)?)
            }
        })
    }

    pub(super) fn add_curve(
        &mut self,
        name: &str,
        curve: &CurveSpec,
        parent: &Option<NodeRef>,
        transform: NodeTransform,
    ) -> Result<(), CommandError> {
        let c = curve_from_spec(curve).map_err(|error| CommandError::Curve {
            node: format!("curve '{name}'"),
            error,
        })?;
        self.add_node(name, parent, transform, NodeContent::Curve(Arc::new(c)))?;
        Ok(())
    }

    pub(super) fn add_surface(
        &mut self,
        name: &str,
        surface: &SurfaceSpec,
        parent: &Option<NodeRef>,
        transform: NodeTransform,
    ) -> Result<(), CommandError> {
        let shape = self.surface_from_spec(surface, &format!("surface '{name}'"))?;
        self.add_node(
            name,
            parent,
            transform,
            NodeContent::Surface(Arc::new(shape)),
        )?;
        Ok(())
    }

    /// Moves control points by index (NURBS surfaces: `i * nv + j`).
    pub(super) fn set_control_points(
        &mut self,
        node: &NodeRef,
        points: &[(u32, DVec3)],
    ) -> Result<(), CommandError> {
        self.edit_shape(
            node,
            |c| {
                for &(i, p) in points {
                    c.set_point(i as usize, p)?;
                }
                Ok(())
            },
            |s| {
                for &(i, p) in points {
                    match s {
                        SurfaceShape::Nurbs(n) => {
                            let nv = n.size().1;
                            n.set_point(i as usize / nv, i as usize % nv, p)?;
                        }
                        SurfaceShape::Triangle(t) => {
                            let count = t.points.len();
                            let slot =
                                t.points
                                    .get_mut(i as usize)
                                    .ok_or(CurveError::NoSuchPoint {
                                        index: i as usize,
                                        count,
                                    })?;
                            if !p.is_finite() {
                                return Err(CurveError::NotFinite {
                                    what: "control point",
                                    index: i as usize,
                                });
                            }
                            *slot = p;
                        }
                    }
                }
                Ok(())
            },
        )
    }

    pub(super) fn set_weights(
        &mut self,
        node: &NodeRef,
        weights: &[(u32, f64)],
    ) -> Result<(), CommandError> {
        self.edit_shape(
            node,
            |c| {
                for &(i, w) in weights {
                    c.set_weight(i as usize, w)?;
                }
                Ok(())
            },
            |s| match s {
                SurfaceShape::Nurbs(n) => {
                    let nv = n.size().1;
                    for &(i, w) in weights {
                        n.set_weight(i as usize / nv, i as usize % nv, w)?;
                    }
                    Ok(())
                }
                SurfaceShape::Triangle(_) => Err(CurveError::TriangleWeights),
            },
        )
    }

    pub(super) fn insert_knot(
        &mut self,
        node: &NodeRef,
        at: f64,
        direction: ParameterDirection,
    ) -> Result<(), CommandError> {
        self.edit_shape(
            node,
            |c| {
                *c = c.insert_knot(at)?;
                Ok(())
            },
            |s| match s {
                SurfaceShape::Nurbs(n) => {
                    *n = match direction {
                        ParameterDirection::U => n.insert_knot_u(at)?,
                        ParameterDirection::V => n.insert_knot_v(at)?,
                    };
                    Ok(())
                }
                SurfaceShape::Triangle(_) => Err(CurveError::TriangleKnots),
            },
        )
    }

    pub(super) fn elevate_degree(
        &mut self,
        node: &NodeRef,
        direction: ParameterDirection,
    ) -> Result<(), CommandError> {
        self.edit_shape(
            node,
            |c| {
                *c = c.elevate_degree()?;
                Ok(())
            },
            |s| match s {
                SurfaceShape::Triangle(t) => {
                    *t = t.elevate();
                    Ok(())
                }
                SurfaceShape::Nurbs(n) => {
                    *n = match direction {
                        ParameterDirection::U => n.elevate_u()?,
                        ParameterDirection::V => n.elevate_v()?,
                    };
                    Ok(())
                }
            },
        )
    }
}
