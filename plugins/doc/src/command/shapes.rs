//! Commands on curves and surfaces: adding them from their specs, moving
//! control points, weights, knot insertion and degree elevation.

use super::plan::Plan;
use super::{Command, CommandError, CurveSpec, NodeRef, ParameterDirection, SurfaceSpec};
use crate::scene::{CurveContent, NodeContent, NodeTransform, SurfaceShape};
use glam::DVec3;
use hedra_geom::curves::interpolating::Tbc;
use hedra_geom::curves::nurbs::clamped_uniform_knots;
use hedra_geom::curves::{
    CatmullRom, Chaikin, CubicHermite, CubicSpline, CurveError, CurveKind, Fractal, Join,
    KochanekBartels, Lagrange, NurbsCurve, PolyBezier, QuinticHermite,
};
use hedra_geom::surfaces::{BezierTriangle, NurbsSurface};
use std::sync::Arc;

impl CurveSpec {
    /// The curve this spec describes, checked: what `AddCurve` would add
    /// (for a tool's preview before the command).
    ///
    /// # Errors
    /// What the kind's check finds ("Lagrange needs 2 points or more").
    pub fn curve(&self) -> Result<CurveKind, CurveError> {
        curve_from_spec(self)
    }

    /// The spec that adds `kind` exactly (`of_kind(k).curve() == Ok(k)`),
    /// with everything a spec may leave to its defaults written out. The
    /// match names every kernel kind, so a kind added to
    /// [`CurveKind`] without a spec here does not compile: the two enums
    /// stay in step (`tests/curve_kinds.rs` checks the round trip of each).
    pub fn of_kind(kind: &CurveKind) -> CurveSpec {
        match kind.clone() {
            CurveKind::Nurbs(c) => CurveSpec::Nurbs {
                degree: c.degree(),
                points: c.points().to_vec(),
                weights: Some(c.weights().to_vec()),
                knots: Some(c.knots().to_vec()),
            },
            CurveKind::Lagrange(Lagrange {
                points,
                parameterization,
            }) => CurveSpec::Lagrange {
                points,
                parameterization,
            },
            CurveKind::CubicHermite(CubicHermite { points, tangents }) => {
                CurveSpec::Hermite { points, tangents }
            }
            CurveKind::QuinticHermite(QuinticHermite {
                points,
                tangents,
                accelerations,
            }) => CurveSpec::QuinticHermite {
                points,
                tangents,
                accelerations,
            },
            CurveKind::CatmullRom(CatmullRom {
                points,
                parameterization,
                closed,
            }) => CurveSpec::CatmullRom {
                points,
                parameterization,
                closed,
            },
            CurveKind::KochanekBartels(KochanekBartels {
                points,
                keys,
                closed,
            }) => CurveSpec::KochanekBartels {
                points,
                keys: Some(keys),
                closed,
            },
            CurveKind::CubicSpline(CubicSpline {
                points,
                parameterization,
                ends,
            }) => CurveSpec::CubicSpline {
                points,
                parameterization,
                ends,
            },
            CurveKind::Chaikin(Chaikin {
                points,
                level,
                closed,
            }) => CurveSpec::Chaikin {
                points,
                level,
                closed,
            },
            CurveKind::PolyBezier(PolyBezier {
                points,
                joins,
                closed,
            }) => CurveSpec::PolyBezier {
                points,
                joins: Some(joins),
                closed,
            },
            CurveKind::Fractal(Fractal {
                rule,
                points,
                level,
                closed,
                normal,
            }) => CurveSpec::Fractal {
                rule,
                points,
                level,
                closed,
                normal,
            },
        }
    }
}

/// The curve kind a spec describes, checked.
pub(crate) fn curve_from_spec(spec: &CurveSpec) -> Result<CurveKind, CurveError> {
    let kind = match spec {
        CurveSpec::Nurbs {
            degree,
            points,
            weights,
            knots,
        } => CurveKind::Nurbs(NurbsCurve::new(
            *degree,
            knots
                .clone()
                .unwrap_or_else(|| clamped_uniform_knots(*degree, points.len())),
            points.clone(),
            weights.clone().unwrap_or_else(|| vec![1.0; points.len()]),
        )?),
        CurveSpec::Bezier { points } => {
            let degree = points.len().saturating_sub(1).max(1);
            CurveKind::Nurbs(NurbsCurve::clamped(degree, points.clone())?)
        }
        CurveSpec::Circle { radius } => {
            if !(radius.is_finite() && *radius > 0.0) {
                return Err(CurveError::NotPositive {
                    what: "a circle's radius",
                    value: *radius,
                });
            }
            CurveKind::Nurbs(NurbsCurve::circle(DVec3::ZERO, *radius))
        }
        CurveSpec::Closed {
            degree,
            points,
            weights,
        } => CurveKind::Nurbs(NurbsCurve::periodic(
            *degree,
            points.clone(),
            weights.clone().unwrap_or_else(|| vec![1.0; points.len()]),
        )?),
        CurveSpec::Lagrange {
            points,
            parameterization,
        } => CurveKind::Lagrange(Lagrange {
            points: points.clone(),
            parameterization: *parameterization,
        }),
        CurveSpec::Hermite { points, tangents } => CurveKind::CubicHermite(CubicHermite {
            points: points.clone(),
            tangents: tangents.clone(),
        }),
        CurveSpec::QuinticHermite {
            points,
            tangents,
            accelerations,
        } => CurveKind::QuinticHermite(QuinticHermite {
            points: points.clone(),
            tangents: tangents.clone(),
            accelerations: accelerations.clone(),
        }),
        CurveSpec::CatmullRom {
            points,
            parameterization,
            closed,
        } => CurveKind::CatmullRom(CatmullRom {
            points: points.clone(),
            parameterization: *parameterization,
            closed: *closed,
        }),
        CurveSpec::KochanekBartels {
            points,
            keys,
            closed,
        } => CurveKind::KochanekBartels(KochanekBartels {
            points: points.clone(),
            keys: keys
                .clone()
                .unwrap_or_else(|| vec![Tbc::default(); points.len()]),
            closed: *closed,
        }),
        CurveSpec::CubicSpline {
            points,
            parameterization,
            ends,
        } => CurveKind::CubicSpline(CubicSpline {
            points: points.clone(),
            parameterization: *parameterization,
            ends: *ends,
        }),
        CurveSpec::Chaikin {
            points,
            level,
            closed,
        } => CurveKind::Chaikin(Chaikin {
            points: points.clone(),
            level: *level,
            closed: *closed,
        }),
        CurveSpec::PolyBezier {
            points,
            joins,
            closed,
        } => {
            let segments = if *closed {
                points.len() / 3
            } else {
                points.len().saturating_sub(1) / 3
            };
            let joints = if *closed {
                segments
            } else {
                segments.saturating_sub(1)
            };
            let joins = joins.clone().unwrap_or_else(|| vec![Join::G1; joints]);
            let plain = CurveKind::PolyBezier(PolyBezier {
                points: points.clone(),
                joins: joins.clone(),
                closed: *closed,
            });
            plain.check()?;
            // Turn the handles to hold the joins.
            let mut k = plain;
            for (j, join) in joins.into_iter().enumerate() {
                k = k.set_join(j, join)?;
            }
            k
        }
        CurveSpec::Fractal {
            rule,
            points,
            level,
            closed,
            normal,
        } => CurveKind::Fractal(Fractal {
            rule: *rule,
            points: points.clone(),
            level: *level,
            closed: *closed,
            normal: *normal,
        }),
    };
    kind.check()?;
    Ok(kind)
}

/// Refuses an edit that only NURBS curves have (weights, knots, degree).
fn nurbs_only(
    kind: &CurveKind,
    operation: &'static str,
    edit: impl FnOnce(&mut NurbsCurve) -> Result<(), CurveError>,
) -> Result<CurveKind, CurveError> {
    match kind {
        CurveKind::Nurbs(c) => {
            let mut c = c.clone();
            edit(&mut c)?;
            Ok(CurveKind::Nurbs(c))
        }
        k => Err(CurveError::NotForKind {
            operation,
            kind: k.name(),
        }),
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
            Some(NodeContent::Curve(c)) => Ok((**c.nurbs()).clone()),
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
        let c = curve_from_spec(curve)
            .and_then(CurveContent::new)
            .map_err(|error| CommandError::Curve {
                node: format!("curve '{name}'"),
                error,
            })?;
        self.add_node(name, parent, transform, NodeContent::Curve(Arc::new(c)))?;
        Ok(())
    }

    /// Replaces a curve node's definition.
    pub(super) fn set_curve(
        &mut self,
        node: &NodeRef,
        curve: &CurveSpec,
    ) -> Result<(), CommandError> {
        self.edit_curve(node, |_| curve_from_spec(curve))
    }

    /// Splits a curve node at `at`: it keeps the first part; a new node
    /// with its parent and transform gets the second.
    pub(super) fn split_curve(
        &mut self,
        node: &NodeRef,
        at: f64,
        name: &Option<String>,
    ) -> Result<(), CommandError> {
        let n = self.node(node)?;
        let label = self.doc.label_of(n.id);
        let NodeContent::Curve(c) = &n.content else {
            return Err(CommandError::NotACurve { node: label });
        };
        let curve_error = |error| CommandError::Curve {
            node: label.clone(),
            error,
        };
        let (first, second) = c.kind().split(at).map_err(curve_error)?;
        let first = CurveContent::new(first).map_err(curve_error)?;
        let second = CurveContent::new(second).map_err(curve_error)?;
        let mut kept = n.clone();
        kept.content = NodeContent::Curve(Arc::new(first));
        self.set(kept);
        let new_name = name.clone().unwrap_or_else(|| n.name.clone());
        let id = self.add_node(
            &new_name,
            &None,
            n.transform,
            NodeContent::Curve(Arc::new(second)),
        )?;
        let mut new = self.current(id).cloned().expect("just added");
        new.parent = n.parent;
        new.visible = n.visible;
        self.set(new);
        Ok(())
    }

    /// Appends curve `second` to `first` (taken into `first`'s local
    /// space) and deletes `second`.
    pub(super) fn join_curves(
        &mut self,
        first: &NodeRef,
        second: &NodeRef,
    ) -> Result<(), CommandError> {
        let a = self.node(first)?;
        let b = self.node(second)?;
        let label = self.doc.label_of(a.id);
        if a.id == b.id {
            return Err(CommandError::Curve {
                node: label,
                error: CurveError::NotForKind {
                    operation: "joining a curve to itself (close it instead)",
                    kind: "this",
                },
            });
        }
        let (NodeContent::Curve(ca), NodeContent::Curve(cb)) = (&a.content, &b.content) else {
            let bad = if matches!(a.content, NodeContent::Curve(_)) {
                b.id
            } else {
                a.id
            };
            return Err(CommandError::NotACurve {
                node: self.doc.label_of(bad),
            });
        };
        // `second`'s points in `first`'s local space.
        let to_first = self.doc.world_matrix(a.id).inverse() * self.doc.world_matrix(b.id);
        let joined = cb
            .kind()
            .transformed(&to_first)
            .and_then(|b| ca.kind().join(&b))
            .and_then(CurveContent::new)
            .map_err(|error| CommandError::Curve { node: label, error })?;
        let mut kept = a.clone();
        kept.content = NodeContent::Curve(Arc::new(joined));
        self.set(kept);
        // Children of the deleted curve move to its parent, keeping their place.
        for child in self.doc.children(b.id).map(|c| c.id).collect::<Vec<_>>() {
            let mut c = self.current(child).cloned().expect("a child");
            c.parent = b.parent;
            c.transform = crate::scene::NodeTransform::from_matrix(
                b.transform.to_matrix() * c.transform.to_matrix(),
            );
            self.set(c);
        }
        self.remove(b.id);
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
        let moves: Vec<(usize, DVec3)> = points.iter().map(|&(i, p)| (i as usize, p)).collect();
        self.edit_shape(
            node,
            |c| c.set_points(&moves),
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
            |k| {
                nurbs_only(k, "setting weights (convert it to NURBS first)", |c| {
                    for &(i, w) in weights {
                        c.set_weight(i as usize, w)?;
                    }
                    Ok(())
                })
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
            |k| {
                nurbs_only(k, "inserting a knot (insert a point instead)", |c| {
                    *c = c.insert_knot(at)?;
                    Ok(())
                })
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
            |k| {
                nurbs_only(k, "elevating the degree (convert it to NURBS first)", |c| {
                    *c = c.elevate_degree()?;
                    Ok(())
                })
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

impl Plan<'_> {
    /// Decides a command of the curves and surfaces family (the variants
    /// [`Family::Shapes`](super::plan::Family::Shapes) names; [`Plan::run`] sends only those here).
    pub(super) fn run_shape_command(&mut self, cmd: &Command) -> Result<(), CommandError> {
        match cmd {
            Command::AddCurve {
                name,
                curve,
                parent,
                transform,
            } => self.add_curve(name, curve, parent, *transform),
            Command::AddSurface {
                name,
                surface,
                parent,
                transform,
            } => self.add_surface(name, surface, parent, *transform),
            Command::SetControlPoints { node, points } => self.set_control_points(node, points),
            Command::SetWeights { node, weights } => self.set_weights(node, weights),
            Command::InsertKnot {
                node,
                at,
                direction,
            } => self.insert_knot(node, *at, *direction),
            Command::ElevateDegree { node, direction } => self.elevate_degree(node, *direction),
            Command::SetCurve { node, curve } => self.set_curve(node, curve),
            Command::InsertCurvePoint { node, at } => {
                self.edit_curve(node, |k| Ok(k.insert_point(*at)?.0))
            }
            Command::DeleteCurvePoints { node, points } => {
                let points: Vec<usize> = points.iter().map(|&i| i as usize).collect();
                self.edit_curve(node, |k| k.delete_points(&points))
            }
            Command::ExtrudeCurve { node, end, to } => {
                self.edit_curve(node, |k| k.extrude(*end, *to))
            }
            Command::SetCurveClosed { node, closed } => {
                self.edit_curve(node, |k| k.set_closed(*closed))
            }
            Command::ReverseCurve { node } => self.edit_curve(node, |k| k.reverse()),
            Command::SplitCurve { node, at, name } => self.split_curve(node, *at, name),
            Command::JoinCurves { first, second } => self.join_curves(first, second),
            Command::SetCurveJoin { node, joint, join } => {
                self.edit_curve(node, |k| k.set_join(*joint as usize, *join))
            }
            Command::ConvertCurveToNurbs { node } => {
                self.edit_curve(node, |k| Ok(CurveKind::Nurbs(k.to_nurbs()?.curve)))
            }
            _ => unreachable!("not a command of the curves and surfaces family"),
        }
    }
}
