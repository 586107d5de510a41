//! Writing a document as `.usda` text. The mapping (see `docs/exchange.md`,
//! USD):
//!
//! * every node an `Xform` with its exact local transform, its geometry a
//!   `Geom` child prim;
//! * a mesh a `Mesh` with its cage, its subdivision scheme and options
//!   live (Catmull-Clark, Loop, Linear as `bilinear`), creases as per-edge
//!   sharpness (one two-vertex crease per plain crease edge, one chain per
//!   tapered crease), corners, holes, UVs as face-varying `primvars:st`;
//!   a mesh without subdivision as `subdivisionScheme = "none"` with
//!   normals (flat: `uniform`, smooth: `vertex`, imported corner normals:
//!   `faceVarying`);
//! * the modifier stack applied first; subdivision stays live when it
//!   comes last, else the mesh is written evaluated at its export level;
//!   Doo-Sabin (not a USD scheme) is written evaluated;
//! * NURBS surfaces (Bézier patches, Coons and Gordon results, sweeps) as
//!   `NurbsPatch`; Bézier triangles as their tessellation; curves of every
//!   kind as `NurbsCurves` through their NURBS form; CSG nodes as their
//!   solid (operands not written).
//!
//! `point3f` points are single precision: when a coordinate is not exactly
//! a float, the exact doubles go in `hedra:points` too; likewise crease
//! and corner sharpness (`hedra:creaseSharpnesses`,
//! `hedra:cornerSharpnesses`).

use super::HEDRA;
use crate::export::{ExportError, ExportShape, Geometry};
use crate::scene::{
    CornerAttributes, Document, MeshContent, Node, NodeContent, Shading, SubdivisionModifier,
    SurfaceShape,
};
use glam::{DVec2, DVec3};
use hedra_geom::HalfEdgeMesh;
use hedra_geom::subdivision::{BoundaryInterpolation, CreaseMethod, Creases, Options, Scheme};
use std::collections::HashSet;
use std::fmt::Write;
use std::path::Path;

/// The document as OpenUSD text (`.usda`), with the export report: one
/// note per thing written otherwise than Hedra holds it ("node 'Blob':
/// Doo-Sabin is not a USD scheme; written as its evaluated mesh (2
/// levels)").
///
/// `shape`: [`ExportShape::Evaluated`] keeps subdivision live where USD
/// can; [`ExportShape::Cage`] writes every cage without its stack
/// modifiers (subdivision still live); [`ExportShape::Subdivided`] writes
/// every mesh refined that many levels, as plain polygons.
///
/// # Errors
/// [`ExportError::UnsupportedFormat`] for an extension other than `.usda`;
/// [`ExportError::Evaluation`], [`ExportError::Csg`] and
/// [`ExportError::NotPolygon`] naming the node whose shape cannot be made.
pub fn to_usd(
    doc: &Document,
    path: &Path,
    shape: ExportShape,
) -> Result<(Vec<u8>, Vec<String>), ExportError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if ext != "usda" {
        return Err(ExportError::UnsupportedFormat {
            path: path.to_path_buf(),
            extension: ext,
        });
    }
    let mut w = Writer {
        out: String::new(),
        notes: Vec::new(),
    };
    w.out.push_str(
        "#usda 1.0\n(\n    defaultPrim = \"Hedra\"\n    doc = \"Written by Hedra\"\n    metersPerUnit = 1\n    upAxis = \"Y\"\n)\n\ndef Xform \"Hedra\"\n{\n    custom bool hedra:document = 1\n",
    );
    let tree = doc.hierarchy();
    // Depth first without recursion (a chain of 10,000 nodes): `Some(id)`
    // opens a node, `None` closes the last one opened.
    let mut stack: Vec<Option<crate::scene::NodeId>> = Vec::new();
    let mut names: Vec<HashSet<String>> = vec![HashSet::new()];
    let roots: Vec<_> = doc.roots().map(|n| n.id).collect();
    for &r in roots.iter().rev() {
        stack.push(Some(r));
    }
    let mut depth = 1;
    while let Some(item) = stack.pop() {
        let Some(id) = item else {
            depth -= 1;
            names.pop();
            let _ = writeln!(w.out, "{}}}", indent(depth));
            continue;
        };
        let (Some(node), Some(facts)) = (doc.node(id), tree.facts(id)) else {
            continue;
        };
        if facts.inside_csg {
            continue;
        }
        let taken = names.last_mut().expect("a level per open prim");
        let name = prim_name(&node.name, taken);
        taken.insert(name.clone());
        w.open_node(node, &name, depth);
        depth += 1;
        let mut own: HashSet<String> = HashSet::new();
        own.insert("Geom".to_string());
        names.push(own);
        w.geometry(doc, node, shape, depth)?;
        stack.push(None);
        let is_csg = matches!(node.content, NodeContent::Csg(_));
        for &c in tree.children(id).iter().rev() {
            if !is_csg {
                stack.push(Some(c));
            }
        }
    }
    w.out.push_str("}\n");
    Ok((w.out.into_bytes(), w.notes))
}

/// A USD prim name for `name`: letters, digits and `_` (others become
/// `_`), not starting with a digit, unique among `taken` (`_2`, `_3`, …).
fn prim_name(name: &str, taken: &HashSet<String>) -> String {
    let mut base: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if base.is_empty() || base.starts_with(|c: char| c.is_ascii_digit()) {
        base.insert(0, '_');
    }
    let mut out = base.clone();
    let mut k = 2;
    while taken.contains(&out) {
        out = format!("{base}_{k}");
        k += 1;
    }
    out
}

/// Indentation for a prim at `depth`, capped (USD does not read it; a
/// chain of 10,000 nodes would otherwise grow the file quadratically).
fn indent(depth: usize) -> String {
    "    ".repeat(depth.min(16))
}

/// A USD string literal. Written without escapes where it can be
/// (`"…"`, else `'…'` for text with double quotes, such as JSON): openusd
/// 0.6, which Hedra reads with, keeps escapes in the value.
pub(crate) fn quoted(s: &str) -> String {
    let plain = |q: char| !s.contains(q) && !s.contains('\\') && !s.chars().any(char::is_control);
    if plain('"') {
        return format!("\"{s}\"");
    }
    if plain('\'') {
        return format!("'{s}'");
    }
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if c.is_control() => {
                let _ = write!(out, "\\x{:02x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// True when every coordinate is exactly a single-precision float.
fn f32_exact(values: impl IntoIterator<Item = f64>) -> bool {
    values.into_iter().all(|x| (x as f32) as f64 == x)
}

fn list<T>(items: &[T], f: impl Fn(&T) -> String) -> String {
    let mut out = String::from("[");
    for (i, x) in items.iter().enumerate() {
        if i > 0 {
            out.push_str(", ");
        }
        out.push_str(&f(x));
    }
    out.push(']');
    out
}

fn p3f(p: &DVec3) -> String {
    format!("({}, {}, {})", p.x as f32, p.y as f32, p.z as f32)
}
fn p3d(p: &DVec3) -> String {
    format!("({}, {}, {})", p.x, p.y, p.z)
}
fn p2f(p: &DVec2) -> String {
    format!("({}, {})", p.x as f32, p.y as f32)
}
fn num<T: std::fmt::Display>(x: &T) -> String {
    x.to_string()
}

/// USD's name of a scheme that it has.
fn scheme_token(s: Scheme) -> Option<&'static str> {
    match s {
        Scheme::CatmullClark => Some("catmullClark"),
        Scheme::Loop => Some("loop"),
        Scheme::Linear => Some("bilinear"),
        Scheme::DooSabin => None,
    }
}

pub(crate) fn boundary_token(b: BoundaryInterpolation) -> &'static str {
    match b {
        BoundaryInterpolation::None => "none",
        BoundaryInterpolation::EdgesOnly => "edgeOnly",
        BoundaryInterpolation::EdgesAndCorners => "edgeAndCorner",
    }
}

struct Writer {
    out: String,
    notes: Vec<String>,
}

/// The geometry prim's lines, written by [`Writer::prim`].
struct Prim {
    kind: &'static str,
    lines: Vec<String>,
}

impl Prim {
    fn new(kind: &'static str) -> Self {
        Prim {
            kind,
            lines: vec![format!("custom bool {HEDRA}nodeGeometry = 1")],
        }
    }
    fn attr(&mut self, decl: &str, value: String) {
        self.lines.push(format!("{decl} = {value}"));
    }
    fn extent(&mut self, points: &[DVec3]) {
        let Some(first) = points.first() else {
            return;
        };
        let f = |p: &DVec3| p.as_vec3().as_dvec3();
        let (lo, hi) = points.iter().fold((f(first), f(first)), |(lo, hi), p| {
            (lo.min(f(p)), hi.max(f(p)))
        });
        self.attr("float3[] extent", format!("[{}, {}]", p3f(&lo), p3f(&hi)));
    }
    /// `points` as `point3f[]`, and as exact doubles in `hedra:points`
    /// when some coordinate is not a float.
    fn points(&mut self, points: &[DVec3]) {
        self.attr("point3f[] points", list(points, p3f));
        if !f32_exact(points.iter().flat_map(|p| p.to_array())) {
            self.attr(
                &format!("custom double3[] {HEDRA}points"),
                list(points, p3d),
            );
        }
        self.extent(points);
    }
}

impl Writer {
    fn note(&mut self, node: &Node, what: String) {
        self.notes.push(format!("node '{}': {what}", node.name));
    }

    fn open_node(&mut self, node: &Node, name: &str, depth: usize) {
        let i = indent(depth);
        let t = node.transform;
        let q = t.rotation;
        let _ = writeln!(self.out, "{i}def Xform \"{name}\"\n{i}{{");
        let i = indent(depth + 1);
        let _ = writeln!(
            self.out,
            "{i}custom string {HEDRA}name = {}",
            quoted(&node.name)
        );
        if !node.visible {
            let _ = writeln!(self.out, "{i}token visibility = \"invisible\"");
        }
        let _ = writeln!(
            self.out,
            "{i}double3 xformOp:translate = {}\n{i}quatd xformOp:orient = ({}, {}, {}, {})\n{i}double3 xformOp:scale = {}\n{i}uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:orient\", \"xformOp:scale\"]",
            p3d(&t.translation),
            q.w,
            q.x,
            q.y,
            q.z,
            p3d(&t.scale)
        );
    }

    fn prim(&mut self, prim: Prim, depth: usize) {
        let i = indent(depth);
        let _ = writeln!(self.out, "{i}def {} \"Geom\"\n{i}{{", prim.kind);
        for l in prim.lines {
            let _ = writeln!(self.out, "{i}    {l}");
        }
        let _ = writeln!(self.out, "{i}}}");
    }

    /// The node's geometry prim, if it has one.
    fn geometry(
        &mut self,
        doc: &Document,
        node: &Node,
        shape: ExportShape,
        depth: usize,
    ) -> Result<(), ExportError> {
        let evaluation = |error| ExportError::Evaluation {
            node: node.name.clone(),
            error,
        };
        match &node.content {
            NodeContent::Empty => {}
            NodeContent::Mesh(content) => {
                if let Some(face) = content.mesh.first_non_polygon_face() {
                    return Err(ExportError::NotPolygon {
                        node: node.name.clone(),
                        face,
                    });
                }
                let prim = self.mesh_prim(node, content, shape).map_err(evaluation)?;
                self.prim(prim, depth);
            }
            NodeContent::Kept(content) => {
                let prim = self.kept_prim(node, content, shape).map_err(evaluation)?;
                self.prim(prim, depth);
            }
            NodeContent::Csg(_) => {
                if let Some(Geometry::Mesh(m)) =
                    crate::export::export_geometry(doc, node, ExportShape::Evaluated)?
                {
                    let mut prim = Prim::new("Mesh");
                    write_cage(
                        &mut prim,
                        &m,
                        &Creases::default(),
                        None,
                        None,
                        Shading::Flat,
                    );
                    self.note(
                        node,
                        "CSG written as its solid (a plain mesh); its operands are not written"
                            .into(),
                    );
                    self.prim(prim, depth);
                }
            }
            NodeContent::Curve(c) => {
                let mut prim = Prim::new("NurbsCurves");
                let curve = c.nurbs();
                let (a, b) = hedra_geom::curves::Curve::domain(curve.as_ref());
                prim.attr(
                    "int[] curveVertexCounts",
                    format!("[{}]", curve.points().len()),
                );
                prim.attr("int[] order", format!("[{}]", curve.degree() + 1));
                prim.attr("double[] knots", list(curve.knots(), num));
                prim.attr("double2[] ranges", format!("[({a}, {b})]"));
                prim.points(curve.points());
                if !curve.is_polynomial() {
                    prim.attr("double[] pointWeights", list(curve.weights(), num));
                }
                if !matches!(c.kind(), hedra_geom::curves::CurveKind::Nurbs(_)) {
                    let text = ron::to_string(c.kind()).unwrap_or_default();
                    prim.attr(&format!("custom string {HEDRA}curveKind"), quoted(&text));
                }
                if let Some(t) = c.tolerance() {
                    self.note(
                        node,
                        format!("the curve's NURBS form is approximate (within {t:e}); written as that form"),
                    );
                }
                self.prim(prim, depth);
            }
            NodeContent::Surface(s) => match s.as_ref() {
                SurfaceShape::Nurbs(sf) => {
                    let mut prim = Prim::new("NurbsPatch");
                    let (du, dv) = sf.degrees();
                    let (nu, nv) = sf.size();
                    let (ku, kv) = sf.knots();
                    // USD: u varies fastest; Hedra: index i·nv + j.
                    let reorder = |v: &[f64]| -> Vec<f64> {
                        (0..nv)
                            .flat_map(|j| (0..nu).map(move |i| v[i * nv + j]))
                            .collect()
                    };
                    let points: Vec<DVec3> = (0..nv)
                        .flat_map(|j| (0..nu).map(move |i| (i, j)))
                        .map(|(i, j)| sf.points()[i * nv + j])
                        .collect();
                    prim.attr("int uVertexCount", nu.to_string());
                    prim.attr("int vVertexCount", nv.to_string());
                    prim.attr("int uOrder", (du + 1).to_string());
                    prim.attr("int vOrder", (dv + 1).to_string());
                    prim.attr("double[] uKnots", list(ku, num));
                    prim.attr("double[] vKnots", list(kv, num));
                    prim.attr("double2 uRange", format!("({}, {})", ku[du], ku[nu]));
                    prim.attr("double2 vRange", format!("({}, {})", kv[dv], kv[nv]));
                    prim.points(&points);
                    if sf.weights().iter().any(|&w| w != 1.0) {
                        prim.attr("double[] pointWeights", list(&reorder(sf.weights()), num));
                    }
                    self.prim(prim, depth);
                }
                SurfaceShape::Triangle(t) => {
                    if let Some(Geometry::Triangles(ps, ns, tris)) =
                        crate::export::export_geometry(doc, node, ExportShape::Evaluated)?
                    {
                        let mut prim = Prim::new("Mesh");
                        prim.attr("uniform token subdivisionScheme", quoted("none"));
                        prim.attr("int[] faceVertexCounts", list(&vec![3; tris.len()], num));
                        let flat: Vec<u32> = tris.iter().flatten().copied().collect();
                        prim.attr("int[] faceVertexIndices", list(&flat, num));
                        prim.points(&ps);
                        prim.lines.push(format!(
                            "normal3f[] normals = {} (\n        interpolation = \"vertex\"\n    )",
                            list(&ns, p3f)
                        ));
                        let text = ron::to_string(t).unwrap_or_default();
                        prim.attr(
                            &format!("custom string {HEDRA}bezierTriangle"),
                            quoted(&text),
                        );
                        self.note(
                            node,
                            format!(
                                "USD has no triangular patch: the Bézier triangle is written as its tessellation ({} triangles), its control points kept in hedra:bezierTriangle",
                                tris.len()
                            ),
                        );
                        self.prim(prim, depth);
                    }
                }
            },
        }
        Ok(())
    }

    /// A mesh node's `Mesh` prim, by the rules of the module doc.
    /// A kept (non-manifold) mesh as a `Mesh` prim of its faces as they
    /// are. Written as evaluated, its subdivision stays a scheme on the
    /// cage (USD subdivides non-manifold cages by OpenSubdiv's rules, as
    /// Hedra does); written subdivided, the faces of that level.
    fn kept_prim(
        &mut self,
        node: &Node,
        content: &crate::kept::KeptMeshContent,
        shape: ExportShape,
    ) -> Result<Prim, crate::modifiers::EvaluationError> {
        let mut prim = Prim::new("Mesh");
        let (mesh, subdivision) = match shape {
            ExportShape::Cage => (std::borrow::Cow::Borrowed(&*content.mesh), None),
            ExportShape::Evaluated => match content.subdivision {
                Some(s) if s.options.scheme == Scheme::DooSabin => {
                    self.note(
                        node,
                        "Doo-Sabin has no USD scheme: written subdivided, as plain polygons".into(),
                    );
                    (content.at_level(s.export_level)?, None)
                }
                s => (std::borrow::Cow::Borrowed(&*content.mesh), s),
            },
            ExportShape::Subdivided(level) => {
                self.note(
                    node,
                    format!("written subdivided {level} level(s), as plain polygons"),
                );
                (content.at_level(level)?, None)
            }
        };
        let scheme = subdivision.and_then(|s| scheme_token(s.options.scheme));
        prim.attr(
            "uniform token subdivisionScheme",
            quoted(scheme.unwrap_or("none")),
        );
        if let Some(s) = subdivision.filter(|_| scheme.is_some()) {
            subdivision_attrs(&mut prim, s);
        }
        shading_attr(&mut prim, content.shading);
        let counts: Vec<usize> = mesh.faces.iter().map(Vec::len).collect();
        let indices: Vec<u32> = mesh.faces.iter().flatten().copied().collect();
        prim.attr("int[] faceVertexCounts", list(&counts, num));
        prim.attr("int[] faceVertexIndices", list(&indices, num));
        prim.points(&mesh.positions);
        Ok(prim)
    }

    fn mesh_prim(
        &mut self,
        node: &Node,
        content: &MeshContent,
        shape: ExportShape,
    ) -> Result<Prim, crate::modifiers::EvaluationError> {
        let mut prim = Prim::new("Mesh");
        let sub = content.subdivision;
        let stacked = !content.modifiers.is_empty();
        let evaluated_at = |w: &mut Writer, level: u32, why: String| {
            w.note(node, why);
            content.evaluate(level)
        };
        match shape {
            ExportShape::Cage => {
                if stacked {
                    self.note(node, "cage written without its modifier stack".into());
                }
                let corners = Some(&content.corners);
                write_cage(
                    &mut prim,
                    &content.mesh,
                    &content.creases,
                    corners,
                    sub.filter(|s| s.options.scheme != Scheme::DooSabin),
                    content.shading,
                );
            }
            ExportShape::Subdivided(level) => {
                let e = evaluated_at(
                    self,
                    level,
                    format!("written subdivided {level} level(s), as plain polygons"),
                )?;
                write_cage(&mut prim, &e.mesh, &e.creases, None, None, content.shading);
            }
            ExportShape::Evaluated => match sub {
                Some(s) if s.options.scheme == Scheme::DooSabin => {
                    let e = evaluated_at(
                        self,
                        s.export_level,
                        format!(
                            "Doo-Sabin is not a USD scheme; written as its evaluated mesh ({} levels)",
                            s.export_level
                        ),
                    )?;
                    write_cage(&mut prim, &e.mesh, &e.creases, None, None, content.shading);
                }
                Some(s) => match content.smooth_cage()? {
                    Some(e) => {
                        if stacked {
                            self.note(
                                node,
                                "modifier stack applied; subdivision kept live on the result"
                                    .into(),
                            );
                        }
                        let corners = (!stacked).then_some(&content.corners);
                        write_cage(
                            &mut prim,
                            &e.mesh,
                            &e.creases,
                            corners,
                            Some(s),
                            content.shading,
                        );
                    }
                    None => {
                        let e = evaluated_at(
                            self,
                            s.export_level,
                            format!(
                                "a modifier comes after subdivision; written as the evaluated mesh ({} levels)",
                                s.export_level
                            ),
                        )?;
                        write_cage(&mut prim, &e.mesh, &e.creases, None, None, content.shading);
                    }
                },
                None => {
                    let e = if stacked {
                        evaluated_at(self, 0, "modifier stack applied".into())?
                    } else {
                        content.evaluate(0)?
                    };
                    let corners = (!stacked).then_some(&content.corners);
                    write_cage(
                        &mut prim,
                        &e.mesh,
                        &e.creases,
                        corners,
                        None,
                        content.shading,
                    );
                }
            },
        }
        Ok(prim)
    }
}

/// A crease chain as written: its vertices (indices) and per-edge values.
struct Chain {
    vertices: Vec<u32>,
    sharpness: Vec<f64>,
    /// The taper it comes from, with each edge's fraction along it.
    taper: Option<(usize, Vec<f64>)>,
}

/// The mesh, its creases, UVs and (without subdivision) normals.
fn write_cage(
    prim: &mut Prim,
    mesh: &HalfEdgeMesh,
    creases: &Creases,
    corners: Option<&CornerAttributes>,
    subdivision: Option<SubdivisionModifier>,
    shading: Shading,
) {
    let mut index = vec![u32::MAX; mesh.vertex_capacity()];
    let mut points = Vec::with_capacity(mesh.vertex_count());
    for (i, v) in mesh.vertices().enumerate() {
        index[v.index()] = i as u32;
        points.push(mesh.position(v));
    }
    let (mut counts, mut indices) = (Vec::new(), Vec::new());
    let mut face_index = std::collections::HashMap::new();
    for (k, f) in mesh.faces().enumerate() {
        face_index.insert(f, k);
        let mut n = 0;
        for h in mesh.face_halfedges(f) {
            indices.push(index[mesh.origin(h).index()]);
            n += 1;
        }
        counts.push(n);
    }
    let scheme = subdivision.and_then(|s| scheme_token(s.options.scheme));
    prim.attr(
        "uniform token subdivisionScheme",
        quoted(scheme.unwrap_or("none")),
    );
    if let Some(s) = subdivision.filter(|_| scheme.is_some()) {
        subdivision_attrs(prim, s);
    }
    shading_attr(prim, shading);
    prim.attr("int[] faceVertexCounts", list(&counts, num));
    prim.attr("int[] faceVertexIndices", list(&indices, num));
    prim.points(&points);
    // Normals, which USD reads only without subdivision.
    if scheme.is_none() {
        let custom = corners.filter(|c| !c.normals.is_empty());
        let (values, interpolation): (Vec<DVec3>, &str) = match (custom, shading) {
            (Some(c), _) => (
                mesh.faces()
                    .flat_map(|f| mesh.face_halfedges(f).map(move |h| (f, h)))
                    .map(|(f, h)| {
                        c.normals.get(&h).copied().unwrap_or_else(|| match shading {
                            Shading::Flat => mesh.face_normal(f),
                            Shading::Smooth => mesh.vertex_normal(mesh.origin(h)),
                        })
                    })
                    .collect(),
                "faceVarying",
            ),
            (None, Shading::Flat) => (
                mesh.faces().map(|f| mesh.face_normal(f)).collect(),
                "uniform",
            ),
            (None, Shading::Smooth) => (
                mesh.vertices().map(|v| mesh.vertex_normal(v)).collect(),
                "vertex",
            ),
        };
        prim.lines.push(format!(
            "normal3f[] normals = {} (\n        interpolation = \"{interpolation}\"\n    )",
            list(&values, p3f)
        ));
    }
    // UVs, face-varying, indexed.
    if let Some(c) = corners.filter(|c| !c.uvs.is_empty()) {
        let mut values: Vec<DVec2> = Vec::new();
        let mut of: std::collections::HashMap<[u64; 2], u32> = Default::default();
        let mut st_indices = Vec::new();
        for f in mesh.faces() {
            for h in mesh.face_halfedges(f) {
                let uv = c.uvs.get(&h).copied().unwrap_or(DVec2::ZERO);
                let key = uv.to_array().map(f64::to_bits);
                let i = *of.entry(key).or_insert_with(|| {
                    values.push(uv);
                    values.len() as u32 - 1
                });
                st_indices.push(i);
            }
        }
        prim.lines.push(format!(
            "texCoord2f[] primvars:st = {} (\n        interpolation = \"faceVarying\"\n    )",
            list(&values, p2f)
        ));
        prim.attr("int[] primvars:st:indices", list(&st_indices, num));
    }
    write_creases(prim, mesh, creases, &index, &face_index);
}

/// A subdivision modifier's options and levels as the prim's attributes
/// (the scheme itself is `subdivisionScheme`, written by the caller).
fn subdivision_attrs(prim: &mut Prim, s: SubdivisionModifier) {
    let o: Options = s.options;
    prim.attr(
        "token interpolateBoundary",
        quoted(boundary_token(o.boundary)),
    );
    prim.attr(
        "token triangleSubdivisionRule",
        quoted(if o.smooth_triangles {
            "smooth"
        } else {
            "catmullClark"
        }),
    );
    prim.attr(
        &format!("custom int {HEDRA}viewportLevel"),
        s.viewport_level.to_string(),
    );
    prim.attr(
        &format!("custom int {HEDRA}exportLevel"),
        s.export_level.to_string(),
    );
    prim.attr(
        &format!("custom bool {HEDRA}showCage"),
        u8::from(s.show_cage).to_string(),
    );
    prim.attr(
        &format!("custom token {HEDRA}creaseMethod"),
        quoted(match o.crease_method {
            CreaseMethod::Uniform => "uniform",
            CreaseMethod::Chaikin => "chaikin",
        }),
    );
}

/// Hedra's shading of a mesh, as a custom token USD readers ignore.
fn shading_attr(prim: &mut Prim, shading: Shading) {
    prim.attr(
        &format!("custom token {HEDRA}shading"),
        quoted(match shading {
            Shading::Flat => "flat",
            Shading::Smooth => "smooth",
        }),
    );
}

/// Creases (per-edge form), corners and holes.
fn write_creases(
    prim: &mut Prim,
    mesh: &HalfEdgeMesh,
    creases: &Creases,
    index: &[u32],
    face_index: &std::collections::HashMap<hedra_geom::FaceId, usize>,
) {
    let vi = |v: hedra_geom::VertexId| index[v.index()];
    let mut chains: Vec<Chain> = Vec::new();
    for (&e, &s) in &creases.edges {
        if !mesh.is_edge(e) || s <= 0.0 {
            continue;
        }
        let [a, b] = mesh.edge_vertices(e);
        chains.push(Chain {
            vertices: vec![vi(a), vi(b)],
            sharpness: vec![s],
            taper: None,
        });
    }
    for (k, t) in creases.tapers.iter().enumerate() {
        // The chain's vertices in order; a gap (an edge removed since)
        // starts a new chain of the same taper.
        let live: Vec<_> = t.edges.iter().filter(|(e, _)| mesh.is_edge(*e)).collect();
        let mut i = 0;
        while i < live.len() {
            let [a, b] = mesh.edge_vertices(live[i].0);
            // Start at the end not shared with the next edge.
            let start = match live.get(i + 1) {
                Some((next, _)) if mesh.edge_vertices(*next).contains(&a) => b,
                _ => a,
            };
            let mut chain = Chain {
                vertices: vec![vi(start)],
                sharpness: Vec::new(),
                taper: Some((k, Vec::new())),
            };
            let mut cur = start;
            while i < live.len() {
                let (e, at) = *live[i];
                let [a, b] = mesh.edge_vertices(e);
                let next = if a == cur {
                    b
                } else if b == cur {
                    a
                } else {
                    break;
                };
                chain.vertices.push(vi(next));
                chain.sharpness.push(t.sharpness_at(at));
                if let Some((_, fr)) = &mut chain.taper {
                    fr.push(at);
                }
                cur = next;
                i += 1;
            }
            chains.push(chain);
        }
    }
    if !chains.is_empty() {
        let idx: Vec<u32> = chains.iter().flat_map(|c| c.vertices.clone()).collect();
        let lengths: Vec<usize> = chains.iter().map(|c| c.vertices.len()).collect();
        let sharp: Vec<f64> = chains.iter().flat_map(|c| c.sharpness.clone()).collect();
        prim.attr("int[] creaseIndices", list(&idx, num));
        prim.attr("int[] creaseLengths", list(&lengths, num));
        prim.attr(
            "float[] creaseSharpnesses",
            list(&sharp, |s| (*s as f32).to_string()),
        );
        if !f32_exact(sharp.iter().copied()) {
            prim.attr(
                &format!("custom double[] {HEDRA}creaseSharpnesses"),
                list(&sharp, num),
            );
        }
        if !creases.tapers.is_empty() {
            let of: Vec<i64> = chains
                .iter()
                .map(|c| c.taper.as_ref().map_or(-1, |(k, _)| *k as i64))
                .collect();
            let fractions: Vec<f64> = chains
                .iter()
                .filter_map(|c| c.taper.as_ref())
                .flat_map(|(_, f)| f.clone())
                .collect();
            let starts: Vec<f64> = creases.tapers.iter().map(|t| t.start).collect();
            let ends: Vec<f64> = creases.tapers.iter().map(|t| t.end).collect();
            prim.attr(&format!("custom int[] {HEDRA}taperOf"), list(&of, num));
            prim.attr(
                &format!("custom double[] {HEDRA}taperFractions"),
                list(&fractions, num),
            );
            prim.attr(
                &format!("custom double[] {HEDRA}taperStarts"),
                list(&starts, num),
            );
            prim.attr(
                &format!("custom double[] {HEDRA}taperEnds"),
                list(&ends, num),
            );
        }
    }
    let corners: Vec<(u32, f64)> = creases
        .vertices
        .iter()
        .filter(|(v, s)| mesh.is_vertex(**v) && **s > 0.0)
        .map(|(v, s)| (vi(*v), *s))
        .collect();
    if !corners.is_empty() {
        prim.attr("int[] cornerIndices", list(&corners, |c| c.0.to_string()));
        prim.attr(
            "float[] cornerSharpnesses",
            list(&corners, |c| (c.1 as f32).to_string()),
        );
        if !f32_exact(corners.iter().map(|c| c.1)) {
            prim.attr(
                &format!("custom double[] {HEDRA}cornerSharpnesses"),
                list(&corners, |c| c.1.to_string()),
            );
        }
    }
    let holes: Vec<usize> = creases
        .holes
        .iter()
        .filter_map(|f| face_index.get(f).copied())
        .collect();
    if !holes.is_empty() {
        prim.attr("int[] holeIndices", list(&holes, num));
    }
}
