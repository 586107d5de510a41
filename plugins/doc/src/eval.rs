//! Exact geometry of a curve or surface node at a parameter, for `hedra
//! eval`: point, derivatives, normal and curvature, in the node's local space.

use glam::DVec3;
use hedra_geom::curves::Curve;
use hedra_geom::curves::analysis::{curvature, frenet_frame};
use hedra_geom::surfaces::Surface;
use serde::Serialize;

use crate::command::{CommandError, NodeRef};
use crate::scene::{Document, NodeContent, SurfaceShape};

/// What `hedra eval` prints.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Evaluation {
    /// The node's name.
    pub node: String,
    /// "curve", "surface" or "triangle".
    pub kind: &'static str,
    /// The parameter values evaluated at: `[t]` for curves, `[u, v]` for
    /// surfaces and triangles.
    pub parameter: Vec<f64>,
    /// The point, in the node's local space.
    pub point: [f64; 3],
    /// Curves: [d/dt]; surfaces: [∂/∂u, ∂/∂v]; triangles: along u and v (w = 1 − u − v).
    pub first_derivatives: Vec<[f64; 3]>,
    /// Curves: [d²/dt²]; NURBS surfaces: [∂²/∂u², ∂²/∂u∂v, ∂²/∂v²]; triangles: none.
    pub second_derivatives: Vec<[f64; 3]>,
    /// Curves: the principal normal (none where straight); surfaces: the unit normal.
    pub normal: Option<[f64; 3]>,
    /// Curves: κ; NURBS surfaces: [Gaussian K, mean H]; triangles: none.
    pub curvature: Vec<f64>,
}

/// Why a node could not be evaluated.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EvalError {
    /// No node matches the reference.
    #[error(transparent)]
    Node(#[from] CommandError),
    /// A parameter value outside the curve's or surface's domain.
    #[error("'{node}': {parameter} = {value} is outside the domain [{}, {}]", domain.0, domain.1)]
    OutsideDomain {
        /// The node's name.
        node: String,
        /// Which parameter: "t", "u" or "v".
        parameter: &'static str,
        /// The value given.
        value: f64,
        /// The domain, as (start, end).
        domain: (f64, f64),
    },
    /// One value given for a surface, or two for a curve.
    #[error("'{node}' is a {kind}: give {wanted} parameter value(s), got {given}")]
    ParameterCount {
        /// The node's name.
        node: String,
        /// "curve", "surface" or "triangle".
        kind: &'static str,
        /// How many values that kind takes.
        wanted: usize,
        /// How many were given.
        given: usize,
    },
    /// Barycentric `(u, v)` outside a Bézier triangle.
    #[error("'{node}': (u, v) = ({u}, {v}) is outside the triangle (u, v ≥ 0, u + v ≤ 1)")]
    OutsideTriangle {
        /// The node's name.
        node: String,
        /// The u value given.
        u: f64,
        /// The v value given.
        v: f64,
    },
    /// The node is a mesh or an empty.
    #[error("'{node}' is a {kind}, not a curve or surface")]
    NotAShape {
        /// The node's name.
        node: String,
        /// What it is ("mesh", "empty").
        kind: &'static str,
    },
}

fn a(v: DVec3) -> [f64; 3] {
    v.to_array()
}

/// Evaluates node `node` at `params` (one value for curves, two for surfaces).
///
/// # Errors
/// A message naming the node or the parameter: no such node, not a curve or
/// surface, the wrong number of parameters, a parameter outside the domain.
pub fn evaluate(doc: &Document, node: &NodeRef, params: &[f64]) -> Result<Evaluation, EvalError> {
    let id = doc.resolve(node)?;
    let n = doc
        .node(id)
        .ok_or_else(|| CommandError::UnknownNode(node.clone()))?;
    let inside = |t: f64, (lo, hi): (f64, f64), parameter: &'static str| {
        if t.is_finite() && t >= lo - 1e-12 && t <= hi + 1e-12 {
            Ok(())
        } else {
            Err(EvalError::OutsideDomain {
                node: n.name.clone(),
                parameter,
                value: t,
                domain: (lo, hi),
            })
        }
    };
    let want = |count: usize| {
        if params.len() == count {
            Ok(())
        } else {
            Err(EvalError::ParameterCount {
                node: n.name.clone(),
                kind: n.content.kind(),
                wanted: count,
                given: params.len(),
            })
        }
    };
    match &n.content {
        NodeContent::Curve(c) => {
            let c = c.nurbs();
            want(1)?;
            let t = params[0];
            inside(t, c.domain(), "t")?;
            let [p, d1, d2] = c.derivatives(t);
            Ok(Evaluation {
                node: n.name.clone(),
                kind: "curve",
                parameter: vec![t],
                point: a(p),
                first_derivatives: vec![a(d1)],
                second_derivatives: vec![a(d2)],
                normal: frenet_frame(&**c, t).map(|[_, normal, _]| a(normal)),
                curvature: vec![curvature(&**c, t)],
            })
        }
        NodeContent::Surface(s) => {
            want(2)?;
            let (u, v) = (params[0], params[1]);
            match &**s {
                SurfaceShape::Nurbs(sf) => {
                    let (du_range, dv_range) = sf.domain();
                    inside(u, du_range, "u")?;
                    inside(v, dv_range, "v")?;
                    let e = sf.evaluate(u, v);
                    // At a pole: the limit of the normals around it.
                    let normal = sf.unit_normal(u, v);
                    // First and second fundamental forms: K = (LN − M²)/(EG − F²),
                    // H = (EN − 2FM + GL) / (2(EG − F²)).
                    let (ee, f, g) = (e.du.dot(e.du), e.du.dot(e.dv), e.dv.dot(e.dv));
                    let (l, m, nn) = (e.duu.dot(normal), e.duv.dot(normal), e.dvv.dot(normal));
                    let det = ee * g - f * f;
                    let curvature = if det.abs() > 1e-300 {
                        vec![
                            (l * nn - m * m) / det,
                            (ee * nn - 2.0 * f * m + g * l) / (2.0 * det),
                        ]
                    } else {
                        vec![]
                    };
                    Ok(Evaluation {
                        node: n.name.clone(),
                        kind: "surface",
                        parameter: vec![u, v],
                        point: a(e.p),
                        first_derivatives: vec![a(e.du), a(e.dv)],
                        second_derivatives: vec![a(e.duu), a(e.duv), a(e.dvv)],
                        normal: (normal != DVec3::ZERO).then(|| a(normal)),
                        curvature,
                    })
                }
                SurfaceShape::Triangle(t) => {
                    let w = 1.0 - u - v;
                    if !(u >= -1e-12 && v >= -1e-12 && w >= -1e-12) {
                        return Err(EvalError::OutsideTriangle {
                            node: n.name.clone(),
                            u,
                            v,
                        });
                    }
                    let b = DVec3::new(u, v, w);
                    let du = t.directional_derivative(b, DVec3::new(1.0, 0.0, -1.0));
                    let dv = t.directional_derivative(b, DVec3::new(0.0, 1.0, -1.0));
                    let normal = du.cross(dv).normalize_or_zero();
                    Ok(Evaluation {
                        node: n.name.clone(),
                        kind: "triangle",
                        parameter: vec![u, v],
                        point: a(t.evaluate(b)),
                        first_derivatives: vec![a(du), a(dv)],
                        second_derivatives: vec![],
                        normal: (normal != DVec3::ZERO).then(|| a(normal)),
                        curvature: vec![],
                    })
                }
            }
        }
        _ => Err(EvalError::NotAShape {
            node: n.name.clone(),
            kind: n.content.kind(),
        }),
    }
}

impl Evaluation {
    /// Human-readable lines.
    pub fn to_text(&self) -> String {
        let v = |x: &[f64; 3]| format!("({:.9}, {:.9}, {:.9})", x[0], x[1], x[2]);
        let mut out = format!(
            "{} [{}] at {:?}\n  point {}\n",
            self.node,
            self.kind,
            self.parameter,
            v(&self.point)
        );
        for d in &self.first_derivatives {
            out += &format!("  first derivative {}\n", v(d));
        }
        for d in &self.second_derivatives {
            out += &format!("  second derivative {}\n", v(d));
        }
        if let Some(n) = &self.normal {
            out += &format!("  normal {}\n", v(n));
        }
        match (self.kind, self.curvature.as_slice()) {
            ("curve", [k]) => out += &format!("  curvature {k:.9}\n"),
            (_, [k, h]) => out += &format!("  Gaussian curvature {k:.9}, mean curvature {h:.9}\n"),
            _ => {}
        }
        out
    }
}
