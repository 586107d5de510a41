//! Exact geometry of a curve or surface node at a parameter, for `hedra
//! eval`: point, derivatives, normal and curvature, in the node's local space.
//! For a curve of any kind also the limits from both sides at the
//! parameter (where two pieces meet they may differ), the continuity of
//! the joint there, and every joint of the curve with its continuity
//! ([`hedra_geom::curves::joints`]).

use glam::DVec3;
use hedra_geom::curves::Curve;
use hedra_geom::curves::analysis::{curvature, frenet_frame};
use hedra_geom::curves::joints::{Joint, JointTolerance, both_sides};
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
    /// Curves: the kind the user made ("Catmull-Rom", "NURBS", …).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curve_kind: Option<&'static str>,
    /// Curves whose NURBS form approximates the kind (high-degree
    /// Lagrange): the form's measured largest distance from it. The
    /// values above are the form's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub approximation: Option<f64>,
    /// Curves: the limits from both sides at the parameter.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sides: Option<CurveSides>,
    /// Curves: the joint at the parameter, when there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint: Option<JointReport>,
    /// Curves: every joint of the curve, in order (the closing joint of a
    /// closed curve last).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<JointReport>,
}

/// A curve's position and derivatives as the limit from one side.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SideValues {
    /// The point.
    pub point: [f64; 3],
    /// d/dt.
    pub first_derivative: [f64; 3],
    /// d²/dt².
    pub second_derivative: [f64; 3],
}

/// The two one-sided limits of a curve at a parameter: `before` is the
/// piece that ends there, `after` the one that starts there. An open
/// curve has no `before` at its start and no `after` at its end; a closed
/// one wraps around.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CurveSides {
    /// The incoming piece's values.
    pub before: Option<SideValues>,
    /// The outgoing piece's values.
    pub after: Option<SideValues>,
}

/// One joint of a curve as `hedra eval` reports it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct JointReport {
    /// The parameter of the joint (a closed curve's closing joint: the
    /// domain's start).
    pub parameter: f64,
    /// The point there, in the node's local space.
    pub point: [f64; 3],
    /// The knot's multiplicity in the NURBS form (0: the closing joint).
    pub multiplicity: usize,
    /// The joint where a closed curve's end meets its start.
    pub closing: bool,
    /// "C2", "C1 G2", "C1", "G2", "G1", "C0" or "gap".
    pub continuity: &'static str,
    /// Each test on its own: C0, C1, C2, G1, G2.
    pub c0: bool,
    /// First derivatives agree.
    pub c1: bool,
    /// Second derivatives agree too.
    pub c2: bool,
    /// Unit tangents agree.
    pub g1: bool,
    /// Curvature vectors agree too.
    pub g2: bool,
}

impl From<&Joint> for JointReport {
    fn from(j: &Joint) -> Self {
        let c = j.continuity;
        JointReport {
            parameter: j.parameter,
            point: a(j.position),
            multiplicity: j.multiplicity,
            closing: j.closing,
            continuity: c.label(),
            c0: c.c0,
            c1: c.c1,
            c2: c.c2,
            g1: c.g1,
            g2: c.g2,
        }
    }
}

fn side_values([p, d1, d2]: [DVec3; 3]) -> SideValues {
    SideValues {
        point: a(p),
        first_derivative: a(d1),
        second_derivative: a(d2),
    }
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
        NodeContent::Curve(content) => {
            let c = content.nurbs();
            want(1)?;
            let t = params[0];
            let (start, end) = c.domain();
            inside(t, (start, end), "t")?;
            let t = t.clamp(start, end);
            let [p, d1, d2] = c.derivatives(t);
            let kind = content.kind();
            let closed = kind.is_closed();
            let joints = kind.joints(c, &JointTolerance::default());
            // The joint at t: an interior knot, or either end of a closed
            // curve for its closing joint.
            let near = |x: f64| (x - t).abs() <= 1e-12 * (end - start);
            let joint = joints
                .iter()
                .find(|j| near(j.parameter) || (j.closing && near(end)))
                .map(JointReport::from);
            let (before, after) = both_sides(c, closed, t);
            Ok(Evaluation {
                node: n.name.clone(),
                kind: "curve",
                parameter: vec![t],
                point: a(p),
                first_derivatives: vec![a(d1)],
                second_derivatives: vec![a(d2)],
                normal: frenet_frame(&**c, t).map(|[_, normal, _]| a(normal)),
                curvature: vec![curvature(&**c, t)],
                curve_kind: Some(kind.name()),
                approximation: content.tolerance(),
                sides: Some(CurveSides {
                    before: before.map(side_values),
                    after: after.map(side_values),
                }),
                joint,
                joints: joints.iter().map(JointReport::from).collect(),
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
                        ..Evaluation::shape_only()
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
                        ..Evaluation::shape_only()
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

/// Joints [`Evaluation::to_text`] lists at most (JSON lists them all).
pub const MAX_JOINT_LINES: usize = 20;

impl Evaluation {
    /// The curve-only fields empty, for surfaces and triangles.
    fn shape_only() -> Evaluation {
        Evaluation {
            node: String::new(),
            kind: "",
            parameter: Vec::new(),
            point: [0.0; 3],
            first_derivatives: Vec::new(),
            second_derivatives: Vec::new(),
            normal: None,
            curvature: Vec::new(),
            curve_kind: None,
            approximation: None,
            sides: None,
            joint: None,
            joints: Vec::new(),
        }
    }

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
        if let Some(kind) = self.curve_kind {
            out += &format!("  kind {kind}\n");
        }
        if let Some(e) = self.approximation {
            out += &format!("  NURBS form within {e:.3e} of the curve\n");
        }
        if let Some(sides) = &self.sides {
            for (name, side) in [("before", &sides.before), ("after", &sides.after)] {
                match side {
                    Some(s) => {
                        out += &format!(
                            "  {name}: point {}, first derivative {}, second derivative {}\n",
                            v(&s.point),
                            v(&s.first_derivative),
                            v(&s.second_derivative)
                        )
                    }
                    None => out += &format!("  {name}: none (an end of the curve)\n"),
                }
            }
        }
        if let Some(j) = &self.joint {
            out += &format!("  joint here: {}\n", j.continuity);
        }
        if !self.joints.is_empty() {
            out += &format!("  joints ({}):", self.joints.len());
            for j in self.joints.iter().take(MAX_JOINT_LINES) {
                let closing = if j.closing { " (closing)" } else { "" };
                out += &format!(" t = {}{closing} {};", j.parameter, j.continuity);
            }
            if self.joints.len() > MAX_JOINT_LINES {
                out += &format!(" … and {} more", self.joints.len() - MAX_JOINT_LINES);
            }
            out += "\n";
        }
        out
    }
}
