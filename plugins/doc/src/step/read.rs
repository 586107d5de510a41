//! Reading STEP B-spline geometry into Hedra nodes.
//!
//! Surfaces: the face geometry of every `ADVANCED_FACE` and `FACE_SURFACE`
//! that is a `B_SPLINE_SURFACE_WITH_KNOTS` (simple, or the complex
//! rational form), then every other B-spline surface the file holds, one
//! surface node each, named after the face (else the surface). A face
//! whose bounds do not run along its surface's natural boundary is
//! trimmed: it comes in as its whole underlying surface, and the report
//! says so. Curves: the B-spline curves of `GEOMETRIC_CURVE_SET`s,
//! `GEOMETRIC_SET`s and representations' items, one curve node each,
//! and `TRIMMED_CURVE`s on B-spline curves, cut to their parameters.
//! Coordinates are converted from the file's length unit to metres.
//!
//! Every reference is checked for its type, every count against what is
//! there before anything is allocated, and the reference graph for
//! cycles; every error names the file, the line and the instance.

use super::p21::{Exchange, Instance, Param, Record, parse};
use crate::import::{ImportError, ImportedMesh};
use crate::scene::{CurveContent, NodeContent, SurfaceShape};
use glam::DVec3;
use hedra_geom::curves::Curve;
use hedra_geom::{NurbsCurve, NurbsSurface};
use std::collections::{BTreeMap, HashSet};
use std::sync::Arc;

/// Degree a B-spline may have at most on import.
pub const MAX_DEGREE: i64 = 32;

/// A mapping error at an instance.
pub(super) struct At {
    pub(super) id: u64,
    pub(super) message: String,
}

pub(super) type R<T> = Result<T, At>;

pub(super) fn at<T>(id: u64, message: impl Into<String>) -> R<T> {
    Err(At {
        id,
        message: message.into(),
    })
}

pub(super) struct Reader<'a> {
    pub(super) ex: &'a Exchange,
    /// Metres per file length unit.
    pub(super) scale: f64,
}

fn is_bspline_surface(i: &Instance) -> bool {
    i.records
        .iter()
        .any(|r| r.name == "B_SPLINE_SURFACE_WITH_KNOTS")
}
pub(super) fn is_bspline_curve(i: &Instance) -> bool {
    i.records
        .iter()
        .any(|r| r.name == "B_SPLINE_CURVE_WITH_KNOTS")
}

impl Reader<'_> {
    pub(super) fn get(&self, from: u64, id: u64) -> R<&Instance> {
        match self.ex.instances.get(&id) {
            Some(i) => Ok(i),
            None => at(
                from,
                format!("refers to #{id}, which the file does not define"),
            ),
        }
    }

    /// The record named `name` of instance `id`.
    pub(super) fn record(&self, id: u64, name: &str) -> R<&Record> {
        let i = self.get(id, id)?;
        match i.records.iter().find(|r| r.name == name) {
            Some(r) => Ok(r),
            None => at(
                id,
                format!(
                    "is {}, where {name} was expected",
                    i.records
                        .iter()
                        .map(|r| r.name.as_str())
                        .collect::<Vec<_>>()
                        .join(" + ")
                ),
            ),
        }
    }

    pub(super) fn param<'p>(&self, id: u64, r: &'p Record, k: usize) -> R<&'p Param> {
        match r.params.get(k) {
            Some(p) => Ok(p),
            None => at(
                id,
                format!(
                    "{} has {} parameter(s), fewer than expected",
                    r.name,
                    r.params.len()
                ),
            ),
        }
    }

    pub(super) fn reference(&self, id: u64, p: &Param, what: &str) -> R<u64> {
        match p {
            Param::Ref(x) => Ok(*x),
            _ => at(id, format!("{what} is not a reference")),
        }
    }

    pub(super) fn list<'p>(&self, id: u64, p: &'p Param, what: &str) -> R<&'p [Param]> {
        match p {
            Param::List(l) => Ok(l),
            _ => at(id, format!("{what} is not a list")),
        }
    }

    pub(super) fn int(&self, id: u64, p: &Param, what: &str) -> R<i64> {
        match p {
            Param::Int(i) => Ok(*i),
            _ => at(id, format!("{what} is not an integer")),
        }
    }

    pub(super) fn real(&self, id: u64, p: &Param, what: &str) -> R<f64> {
        match p {
            Param::Real(x) => Ok(*x),
            Param::Int(i) => Ok(*i as f64),
            Param::Typed(_, x) => self.real(id, x, what),
            _ => at(id, format!("{what} is not a number")),
        }
    }

    pub(super) fn name(&self, r: &Record) -> String {
        match r.params.first() {
            Some(Param::Str(s)) => s.clone(),
            _ => String::new(),
        }
    }

    /// The record `name` of instance `id`, which `from` refers to; an
    /// error at `from` when `id` is undefined or of another type.
    pub(super) fn typed(&self, from: u64, id: u64, name: &str) -> R<&Record> {
        let i = self.get(from, id)?;
        match i.records.iter().find(|r| r.name == name) {
            Some(r) => Ok(r),
            None => at(
                from,
                format!(
                    "#{id} is a {}, where a {name} was expected",
                    i.records
                        .iter()
                        .map(|r| r.name.as_str())
                        .collect::<Vec<_>>()
                        .join(" + ")
                ),
            ),
        }
    }

    /// A 3D `CARTESIAN_POINT`, in metres.
    pub(super) fn point(&self, from: u64, p: &Param) -> R<DVec3> {
        let id = self.reference(from, p, "a control point")?;
        let r = self.typed(from, id, "CARTESIAN_POINT")?;
        let c = self.list(id, self.param(id, r, 1)?, "the coordinates")?;
        if c.len() != 3 {
            return at(
                id,
                format!(
                    "a point of {} coordinate(s); Hedra reads 3D points",
                    c.len()
                ),
            );
        }
        let v = [
            self.real(id, &c[0], "x")?,
            self.real(id, &c[1], "y")?,
            self.real(id, &c[2], "z")?,
        ];
        Ok(DVec3::from_array(v) * self.scale)
    }

    /// Knots expanded from values and multiplicities, checked to give
    /// exactly `needed` knots before they are expanded.
    pub(super) fn knots(
        &self,
        id: u64,
        mults: &Param,
        values: &Param,
        needed: usize,
    ) -> R<Vec<f64>> {
        let mults = self.list(id, mults, "the knot multiplicities")?;
        let values = self.list(id, values, "the knots")?;
        if mults.len() != values.len() {
            return at(
                id,
                format!(
                    "{} knot multiplicities for {} knots",
                    mults.len(),
                    values.len()
                ),
            );
        }
        let mut total: i64 = 0;
        let mut counts = Vec::with_capacity(mults.len());
        for m in mults {
            let m = self.int(id, m, "a knot multiplicity")?;
            if m < 1 {
                return at(id, format!("a knot multiplicity of {m}"));
            }
            total = total.saturating_add(m);
            counts.push(m as usize);
        }
        if total != needed as i64 {
            return at(
                id,
                format!(
                    "the knot multiplicities add up to {total}, but {needed} knots are needed (control points + degree + 1)"
                ),
            );
        }
        let mut out = Vec::with_capacity(needed);
        for (m, v) in counts.iter().zip(values) {
            let v = self.real(id, v, "a knot")?;
            out.extend(std::iter::repeat_n(v, *m));
        }
        Ok(out)
    }

    pub(super) fn degree(&self, id: u64, p: &Param) -> R<usize> {
        let d = self.int(id, p, "the degree")?;
        if !(1..=MAX_DEGREE).contains(&d) {
            return at(
                id,
                format!("degree {d} (Hedra reads degrees 1 to {MAX_DEGREE})"),
            );
        }
        Ok(d as usize)
    }

    /// A B-spline curve, simple or complex (rational).
    pub(super) fn curve(&self, id: u64) -> R<(String, NurbsCurve)> {
        let i = self.get(id, id)?;
        let (name, degree, points, mults, knots) = if i.complex {
            let b = self.record(id, "B_SPLINE_CURVE")?;
            let k = self.record(id, "B_SPLINE_CURVE_WITH_KNOTS")?;
            let name = self
                .record(id, "REPRESENTATION_ITEM")
                .map(|r| self.name(r))
                .unwrap_or_default();
            (
                name,
                self.param(id, b, 0)?,
                self.param(id, b, 1)?,
                self.param(id, k, 0)?,
                self.param(id, k, 1)?,
            )
        } else {
            let k = self.record(id, "B_SPLINE_CURVE_WITH_KNOTS")?;
            (
                self.name(k),
                self.param(id, k, 1)?,
                self.param(id, k, 2)?,
                self.param(id, k, 6)?,
                self.param(id, k, 7)?,
            )
        };
        let degree = self.degree(id, degree)?;
        let refs = self.list(id, points, "the control points")?;
        let points: Vec<DVec3> = refs.iter().map(|p| self.point(id, p)).collect::<R<_>>()?;
        let knots = self.knots(id, mults, knots, points.len() + degree + 1)?;
        let weights = match self.record(id, "RATIONAL_B_SPLINE_CURVE") {
            Ok(r) => {
                let w = self.list(id, self.param(id, r, 0)?, "the weights")?;
                if w.len() != points.len() {
                    return at(
                        id,
                        format!("{} weights for {} control points", w.len(), points.len()),
                    );
                }
                w.iter()
                    .map(|x| self.real(id, x, "a weight"))
                    .collect::<R<Vec<f64>>>()?
            }
            Err(_) => vec![1.0; points.len()],
        };
        match NurbsCurve::new(degree, knots, points, weights) {
            Ok(c) => Ok((name, c)),
            Err(e) => at(id, format!("not a valid B-spline curve: {e}")),
        }
    }

    /// A `TRIMMED_CURVE` on a B-spline curve: the basis cut to the trim
    /// parameters (`PARAMETER_VALUE`s), reversed when its sense disagrees;
    /// the whole basis when the trims are points only (then `true`: the
    /// trim was not applied).
    pub(super) fn trimmed(&self, id: u64) -> R<(String, NurbsCurve, bool)> {
        let r = self.record(id, "TRIMMED_CURVE")?;
        let basis = self.reference(id, self.param(id, r, 1)?, "the basis curve")?;
        if !is_bspline_curve(self.get(id, basis)?) {
            return at(id, format!("#{basis} is not a B-spline curve"));
        }
        let (basis_name, curve) = self.curve(basis)?;
        let name = Some(self.name(r))
            .filter(|n| !n.is_empty())
            .unwrap_or(basis_name);
        let trim = |k: usize| -> R<Option<f64>> {
            let list = self.list(id, self.param(id, r, k)?, "a trim")?;
            for t in list {
                if let Param::Typed(kind, v) = t
                    && kind == "PARAMETER_VALUE"
                {
                    return self.real(id, v, "a trim parameter").map(Some);
                }
            }
            Ok(None)
        };
        let sense = !matches!(r.params.get(4), Some(Param::Enum(e)) if e == "F");
        let (Some(a), Some(b)) = (trim(2)?, trim(3)?) else {
            return Ok((name, curve, true));
        };
        let (lo, hi) = curve.domain();
        let (a, b) = if sense { (a, b) } else { (b, a) };
        if !(lo - 1e-12..=hi + 1e-12).contains(&a)
            || !(lo - 1e-12..=hi + 1e-12).contains(&b)
            || a >= b
        {
            return at(
                id,
                format!("trims {a} and {b} outside the basis curve's domain [{lo}, {hi}]"),
            );
        }
        let span = hi - lo;
        let mut c = curve;
        if a > lo + 1e-12 * span {
            c = match c.split(a) {
                Ok((_, after)) => after,
                Err(e) => return at(id, format!("cannot trim at {a}: {e}")),
            };
        }
        if b < hi - 1e-12 * span {
            c = match c.split(b) {
                Ok((before, _)) => before,
                Err(e) => return at(id, format!("cannot trim at {b}: {e}")),
            };
        }
        Ok((name, if sense { c } else { c.reversed() }, false))
    }

    /// A B-spline surface, simple or complex (rational).
    pub(super) fn surface(&self, id: u64) -> R<(String, NurbsSurface)> {
        let i = self.get(id, id)?;
        let (name, du, dv, rows, knots) = if i.complex {
            let b = self.record(id, "B_SPLINE_SURFACE")?;
            let k = self.record(id, "B_SPLINE_SURFACE_WITH_KNOTS")?;
            let name = self
                .record(id, "REPRESENTATION_ITEM")
                .map(|r| self.name(r))
                .unwrap_or_default();
            let knots = [0, 1, 2, 3]
                .map(|n| self.param(id, k, n))
                .into_iter()
                .collect::<R<Vec<_>>>()?;
            (
                name,
                self.param(id, b, 0)?,
                self.param(id, b, 1)?,
                self.param(id, b, 2)?,
                knots,
            )
        } else {
            let k = self.record(id, "B_SPLINE_SURFACE_WITH_KNOTS")?;
            let knots = [8, 9, 10, 11]
                .map(|n| self.param(id, k, n))
                .into_iter()
                .collect::<R<Vec<_>>>()?;
            (
                self.name(k),
                self.param(id, k, 1)?,
                self.param(id, k, 2)?,
                self.param(id, k, 3)?,
                knots,
            )
        };
        let (du, dv) = (self.degree(id, du)?, self.degree(id, dv)?);
        let rows = self.list(id, rows, "the control points")?;
        let nu = rows.len();
        let nv = match rows.first() {
            Some(r) => self.list(id, r, "a row of control points")?.len(),
            None => 0,
        };
        let mut points = Vec::with_capacity(nu.saturating_mul(nv).min(super::p21::MAX_LIST));
        for row in rows {
            let row = self.list(id, row, "a row of control points")?;
            if row.len() != nv {
                return at(
                    id,
                    format!("rows of {} and {} control points", nv, row.len()),
                );
            }
            for p in row {
                points.push(self.point(id, p)?);
            }
        }
        let ku = self.knots(id, knots[0], knots[2], nu + du + 1)?;
        let kv = self.knots(id, knots[1], knots[3], nv + dv + 1)?;
        let weights = match self.record(id, "RATIONAL_B_SPLINE_SURFACE") {
            Ok(r) => {
                let w = self.list(id, self.param(id, r, 0)?, "the weights")?;
                let mut out = Vec::with_capacity(points.len());
                if w.len() != nu {
                    return at(
                        id,
                        format!(
                            "{} rows of weights for {nu} rows of control points",
                            w.len()
                        ),
                    );
                }
                for row in w {
                    let row = self.list(id, row, "a row of weights")?;
                    if row.len() != nv {
                        return at(
                            id,
                            format!("a row of {} weights for {nv} control points", row.len()),
                        );
                    }
                    for x in row {
                        out.push(self.real(id, x, "a weight")?);
                    }
                }
                out
            }
            Err(_) => vec![1.0; points.len()],
        };
        match NurbsSurface::new(du, dv, ku, kv, nu, nv, points, weights) {
            Ok(s) => Ok((name, s)),
            Err(e) => at(id, format!("not a valid B-spline surface: {e}")),
        }
    }

    /// Metres per length unit of the file: the `LENGTH_UNIT` of the first
    /// context that assigns units (metres when none does).
    pub(super) fn length_unit(&self) -> R<f64> {
        for &id in &self.ex.order {
            let i = &self.ex.instances[&id];
            let Some(units) = i
                .records
                .iter()
                .find(|r| r.name == "GLOBAL_UNIT_ASSIGNED_CONTEXT")
            else {
                continue;
            };
            let list = self.list(id, self.param(id, units, 0)?, "the units")?;
            for u in list {
                let uid = self.reference(id, u, "a unit")?;
                let unit = self.get(id, uid)?;
                if !unit.records.iter().any(|r| r.name == "LENGTH_UNIT") {
                    continue;
                }
                return self.unit_scale(uid, 0);
            }
        }
        Ok(1.0)
    }

    pub(super) fn unit_scale(&self, id: u64, depth: usize) -> R<f64> {
        if depth > 4 {
            return at(id, "a chain of unit conversions more than 4 deep");
        }
        let unit = self.get(id, id)?;
        if let Some(si) = unit.records.iter().find(|r| r.name == "SI_UNIT") {
            let prefix = match si.params.first() {
                Some(Param::Enum(p)) => p.as_str(),
                _ => "",
            };
            let factor = match prefix {
                "" => 1.0,
                "MILLI" => 1e-3,
                "CENTI" => 1e-2,
                "DECI" => 1e-1,
                "KILO" => 1e3,
                "MICRO" => 1e-6,
                "NANO" => 1e-9,
                other => return at(id, format!("length unit prefix .{other}. is not read")),
            };
            return Ok(factor);
        }
        if let Some(c) = unit
            .records
            .iter()
            .find(|r| r.name == "CONVERSION_BASED_UNIT")
        {
            let m = self.reference(id, self.param(id, c, 1)?, "the conversion factor")?;
            let measure = self.get(id, m)?;
            let Some(r) = measure.records.first() else {
                return at(m, "an empty measure");
            };
            let value = self.real(m, self.param(m, r, 0)?, "the conversion factor")?;
            let base = self.reference(m, self.param(m, r, 1)?, "the base unit")?;
            let scale = value * self.unit_scale(base, depth + 1)?;
            if !(scale.is_finite() && scale > 0.0) {
                return at(id, format!("a length unit of {scale} m"));
            }
            return Ok(scale);
        }
        at(
            id,
            "a length unit that is neither an SI_UNIT nor a CONVERSION_BASED_UNIT",
        )
    }
}

/// Reads a STEP file's B-spline surfaces and curves as nodes (see the
/// module's description). `path` is used in messages.
///
/// # Errors
/// [`ImportError::Read`] naming the file, the line and the instance: a
/// syntax error, a reference to an undefined instance or of the wrong
/// type, counts that do not match, a cycle of references; and when the
/// file has no B-spline surface or curve.
pub fn step_from_bytes(bytes: &[u8], path: &str) -> Result<Vec<ImportedMesh>, ImportError> {
    let fail = |message: String| ImportError::Read {
        path: path.to_string(),
        message,
    };
    let ex = parse(bytes).map_err(|e| fail(e.to_string()))?;
    ex.check_acyclic().map_err(|e| fail(e.to_string()))?;
    let named = |e: At| {
        let line = ex.instances.get(&e.id).map_or(0, |i| i.line);
        fail(format!("line {line}, #{}: {}", e.id, e.message))
    };
    let mut reader = Reader {
        ex: &ex,
        scale: 1.0,
    };
    reader.scale = reader.length_unit().map_err(named)?;
    let mut out = Vec::new();
    let mut done: HashSet<u64> = HashSet::new();
    let mut other_faces: BTreeMap<String, usize> = BTreeMap::new();
    let (mut trimmed, mut faceted) = (0usize, 0usize);
    // Faceted shells (POLY_LOOP faces) as mesh nodes; their faces are done.
    for &id in &ex.order {
        if let Some(mesh) = reader.faceted(id, &mut done).map_err(named)? {
            out.push(mesh);
        }
    }
    for &id in &ex.order {
        if done.contains(&id) {
            continue;
        }
        let i = &ex.instances[&id];
        let Some(face) = i
            .records
            .iter()
            .find(|r| r.name == "ADVANCED_FACE" || r.name == "FACE_SURFACE")
        else {
            continue;
        };
        let bounds = reader
            .list(id, reader.param(id, face, 1).map_err(named)?, "the bounds")
            .map_err(named)?;
        let geometry = reader
            .reference(
                id,
                reader.param(id, face, 2).map_err(named)?,
                "the face geometry",
            )
            .map_err(named)?;
        let surface = reader.get(id, geometry).map_err(named)?;
        if !is_bspline_surface(surface) {
            let kind = surface.records.first().map_or("?", |r| r.name.as_str());
            let a_surface = surface
                .records
                .iter()
                .any(|r| r.name.ends_with("SURFACE") || r.name == "PLANE");
            if !a_surface {
                return Err(named(At {
                    id,
                    message: format!("#{geometry} is a {kind}, where a surface was expected"),
                }));
            }
            if kind == "PLANE" && face.name == "FACE_SURFACE" {
                faceted += 1;
            } else {
                *other_faces.entry(kind.to_string()).or_default() += 1;
            }
            continue;
        }
        if !done.insert(geometry) {
            continue;
        }
        let (surface_name, s) = reader.surface(geometry).map_err(named)?;
        if !reader.untrimmed(id, bounds, &s) {
            trimmed += 1;
        }
        let name = [reader.name(face), surface_name]
            .into_iter()
            .find(|n| !n.is_empty())
            .unwrap_or_else(|| format!("Surface {}", out.len() + 1));
        out.push(surface_node(name, s));
    }
    // B-spline surfaces outside faces (a geometric set's).
    for &id in &ex.order {
        if done.contains(&id) || !is_bspline_surface(&ex.instances[&id]) {
            continue;
        }
        done.insert(id);
        let (name, s) = reader.surface(id).map_err(named)?;
        let name = if name.is_empty() {
            format!("Surface {}", out.len() + 1)
        } else {
            name
        };
        out.push(surface_node(name, s));
    }
    // Curves: the items of curve sets, geometric sets and representations.
    let mut skipped_curves: BTreeMap<String, usize> = BTreeMap::new();
    let mut untrimmed_curves = 0usize;
    for &id in &ex.order {
        let i = &ex.instances[&id];
        let Some(set) = i.records.iter().find(|r| {
            matches!(r.name.as_str(), "GEOMETRIC_CURVE_SET" | "GEOMETRIC_SET")
                || (r.name.ends_with("REPRESENTATION") && r.name != "DEFINITIONAL_REPRESENTATION")
        }) else {
            continue;
        };
        let Some(Param::List(items)) = set.params.get(1) else {
            continue;
        };
        for item in items {
            let Param::Ref(c) = item else { continue };
            let target = reader.get(id, *c).map_err(named)?;
            let kind = target.records.first().map_or("", |r| r.name.as_str());
            let trimmed_bspline = kind == "TRIMMED_CURVE"
                && matches!(target.records[0].params.get(1), Some(Param::Ref(b)) if ex.instances.get(b).is_some_and(is_bspline_curve));
            if is_bspline_curve(target) || trimmed_bspline {
                if !done.insert(*c) {
                    continue;
                }
                let (name, curve) = if trimmed_bspline {
                    let (name, curve, whole) = reader.trimmed(*c).map_err(named)?;
                    untrimmed_curves += usize::from(whole);
                    (name, curve)
                } else {
                    reader.curve(*c).map_err(named)?
                };
                let name = if name.is_empty() {
                    format!("Curve {}", out.len() + 1)
                } else {
                    name
                };
                out.push(ImportedMesh {
                    content: Some(NodeContent::Curve(Arc::new(CurveContent::from_nurbs(
                        curve,
                    )))),
                    ..ImportedMesh::empty(name)
                });
            } else if kind.ends_with("CURVE")
                || kind == "LINE"
                || kind == "CIRCLE"
                || kind == "ELLIPSE"
            {
                *skipped_curves.entry(kind.to_string()).or_default() += 1;
            }
        }
    }
    if out.is_empty() {
        return Err(fail(
            "no B-spline surface or curve to import (Hedra reads B_SPLINE_SURFACE_WITH_KNOTS and B_SPLINE_CURVE_WITH_KNOTS)"
                .to_string(),
        ));
    }
    let mut notes = Vec::new();
    if trimmed > 0 {
        notes.push(format!(
            "the trims of {trimmed} face(s) (their whole underlying surfaces were imported)"
        ));
    }
    for (kind, n) in other_faces {
        notes.push(format!(
            "{n} face(s) on a {kind} (Hedra reads B-spline surfaces)"
        ));
    }
    if faceted > 0 {
        notes.push(format!("{faceted} planar facet(s) of faceted shells"));
    }
    if untrimmed_curves > 0 {
        notes.push(format!(
            "the trims of {untrimmed_curves} curve(s) trimmed at points (their whole B-splines were imported)"
        ));
    }
    for (kind, n) in skipped_curves {
        notes.push(format!("{n} {kind} curve(s)"));
    }
    if let Some(first) = out.first_mut() {
        first.not_imported = notes;
    }
    Ok(out)
}

fn surface_node(name: String, s: NurbsSurface) -> ImportedMesh {
    ImportedMesh {
        content: Some(NodeContent::Surface(Arc::new(SurfaceShape::Nurbs(s)))),
        ..ImportedMesh::empty(name)
    }
}
