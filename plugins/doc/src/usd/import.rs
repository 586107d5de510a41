//! Reading OpenUSD (`.usda`, `.usdc`, `.usdz`, `.usd`) through the
//! `openusd` crate's composed stage. Hedra's own [`FolderResolver`] is the
//! stage's asset resolver: every reference, payload and sublayer must
//! resolve to a file inside the opened file's folder (no absolute paths,
//! URIs, `..` or links out of it), and at most [`MAX_LAYERS`] layers are
//! opened; a file that asks for more is refused, naming the asset path.
//!
//! Prims become nodes: `Xform`, `Scope`, `SkelRoot` and untyped prims
//! empties; `Mesh` mesh nodes with their subdivision modifier (the
//! scheme, boundary and triangle rules) and creases, corners and holes;
//! `NurbsPatch` surface nodes; `NurbsCurves` curve nodes (one per curve).
//! A geometry prim marked `hedra:nodeGeometry` gives its content to its
//! parent's node (how Hedra writes a node). What is not read (materials,
//! skinning, animation, instancing, other prim types) is named in the
//! report of the first node.

use super::{MAX_ARRAY, MAX_DEPTH, MAX_PRIMS};
use crate::import::{ImportError, ImportedMesh};
use crate::scene::{CurveContent, NodeContent, NodeTransform, SurfaceShape};
use glam::{DMat4, DQuat, DVec3};
use hedra_geom::curves::NurbsCurve;
use hedra_geom::surfaces::NurbsSurface;
use openusd::{ar, sdf, usd};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// Layers one import opens at most (the file, its sublayers, references
/// and payloads).
pub const MAX_LAYERS: usize = 256;

/// The USD reader thread's stack: openusd recurses per nesting level.
const READER_STACK: usize = 256 << 20;

/// The deepest `{` nesting of USD text, outside strings and comments.
fn text_depth(bytes: &[u8]) -> usize {
    let (mut depth, mut deepest, mut i) = (0usize, 0usize, 0usize);
    while i < bytes.len() {
        match bytes[i] {
            b'#' => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
            }
            q @ (b'"' | b'\'') => {
                let triple = bytes.get(i..i + 3) == Some(&[q, q, q][..]);
                i += if triple { 3 } else { 1 };
                while i < bytes.len() {
                    if bytes[i] == b'\\' {
                        i += 2;
                        continue;
                    }
                    if bytes[i] == q && (!triple || bytes.get(i..i + 3) == Some(&[q, q, q][..])) {
                        i += if triple { 2 } else { 0 };
                        break;
                    }
                    i += 1;
                }
            }
            b'{' | b'(' | b'[' => {
                depth += 1;
                deepest = deepest.max(depth);
            }
            b'}' | b')' | b']' => depth = depth.saturating_sub(1),
            _ => {}
        }
        i += 1;
    }
    deepest
}

/// Why a USD file could not be read, naming the prim and attribute.
#[derive(Debug, thiserror::Error)]
pub enum UsdError {
    /// A reference, payload or sublayer outside the file's folder.
    #[error("refers to '{asset}', outside the file's folder; refused")]
    Outside {
        /// The asset path as authored.
        asset: String,
    },
    /// More layers than [`MAX_LAYERS`].
    #[error("opens more than {MAX_LAYERS} layers (references, payloads, sublayers); refused")]
    TooManyLayers,
    /// The stage could not be opened or composed.
    #[error("cannot open as USD: {0}")]
    Open(String),
    /// An attribute with a value Hedra cannot use.
    #[error("prim {prim}: {attribute}: {why}")]
    Attribute {
        /// The prim's path.
        prim: String,
        /// The attribute's name.
        attribute: String,
        /// What is wrong.
        why: String,
    },
    /// A prim Hedra cannot build.
    #[error("prim {prim}: {why}")]
    Prim {
        /// The prim's path.
        prim: String,
        /// What is wrong.
        why: String,
    },
    /// More than [`MAX_PRIMS`] prims or deeper than [`MAX_DEPTH`].
    #[error("more than {MAX_PRIMS} prims or nested deeper than {MAX_DEPTH}; refused")]
    TooLarge,
}

/// The resolver that keeps every asset inside the folder.
struct FolderResolver {
    folder: PathBuf,
    inner: ar::DefaultResolver,
    refused: Arc<Mutex<Vec<UsdError>>>,
    opened: Arc<Mutex<usize>>,
}

impl FolderResolver {
    fn refuse(&self, e: UsdError) {
        if let Ok(mut r) = self.refused.lock() {
            r.push(e);
        }
    }
    /// True when the file of a path (a package's outer file) is inside
    /// the folder: its canonical path when it exists, else the path with
    /// `.` and `..` taken out.
    fn inside(&self, path: &Path) -> bool {
        let s = path.to_string_lossy();
        let outer = if ar::is_package_relative_path(&s) {
            match ar::split_package_relative_path_outer(&s) {
                Some((p, _)) => PathBuf::from(p),
                None => return false,
            }
        } else {
            path.to_path_buf()
        };
        let real = outer.canonicalize().unwrap_or_else(|_| {
            let mut out = PathBuf::new();
            for c in outer.components() {
                match c {
                    std::path::Component::ParentDir => {
                        out.pop();
                    }
                    std::path::Component::CurDir => {}
                    c => out.push(c),
                }
            }
            out
        });
        real.is_absolute() && real.starts_with(&self.folder)
    }
}

impl ar::Resolver for FolderResolver {
    fn create_identifier(&self, asset_path: &str, anchor: Option<&ar::ResolvedPath>) -> String {
        if asset_path.is_empty() {
            return String::new();
        }
        let id = self.inner.create_identifier(asset_path, anchor);
        if asset_path.contains("://") || !self.inside(Path::new(&id)) {
            self.refuse(UsdError::Outside {
                asset: asset_path.to_string(),
            });
            return String::new();
        }
        id
    }
    fn resolve(&self, asset_path: &str) -> Option<ar::ResolvedPath> {
        let resolved = self.inner.resolve(asset_path)?;
        if !self.inside(&resolved) {
            self.refuse(UsdError::Outside {
                asset: asset_path.to_string(),
            });
            return None;
        }
        Some(resolved)
    }
    fn resolve_for_new_asset(&self, _asset_path: &str) -> Option<ar::ResolvedPath> {
        None
    }
    fn open_asset(&self, resolved: &ar::ResolvedPath) -> std::io::Result<Box<dyn ar::Asset>> {
        let refused = || std::io::Error::new(std::io::ErrorKind::PermissionDenied, "refused");
        if !self.inside(resolved) {
            self.refuse(UsdError::Outside {
                asset: resolved.to_string(),
            });
            return Err(refused());
        }
        let mut n = self.opened.lock().map_err(|_| refused())?;
        *n += 1;
        if *n > MAX_LAYERS {
            self.refuse(UsdError::TooManyLayers);
            return Err(refused());
        }
        self.inner.open_asset(resolved)
    }
}

/// The nodes of the USD file at `path`.
///
/// # Errors
/// [`ImportError::Read`] naming the file and the prim and attribute (or
/// the asset path refused) when the file cannot be opened, refers outside
/// its folder, is too large, or holds a value Hedra cannot use.
pub fn usd_from_path(path: &Path) -> Result<Vec<ImportedMesh>, ImportError> {
    let shown = path.display().to_string();
    let error = |e: UsdError| ImportError::Read {
        path: shown.clone(),
        message: e.to_string(),
    };
    crate::input::check(path).map_err(|e| ImportError::Read {
        path: shown.clone(),
        message: e.to_string(),
    })?;
    let file = path
        .canonicalize()
        .map_err(|e| error(UsdError::Open(e.to_string())))?;
    let folder = file.parent().map(Path::to_path_buf).unwrap_or_default();
    let refused = Arc::new(Mutex::new(Vec::new()));
    let file_str = file.to_string_lossy().into_owned();
    let resolver = FolderResolver {
        folder,
        inner: ar::DefaultResolver::new(),
        refused: refused.clone(),
        opened: Arc::new(Mutex::new(0)),
    };
    // Text nested deeper than Hedra reads is refused before the crate
    // parses it (its parser and composition recurse per level).
    if let Ok(bytes) = crate::input::read(&file)
        && bytes.starts_with(b"#usda")
        && text_depth(&bytes) > MAX_DEPTH + 2
    {
        return Err(error(UsdError::TooLarge));
    }
    // The crate is young: it runs on its own thread with a large stack, and
    // a panic on a hostile file is an error, not a crash.
    quiet_reader_panics();
    let result = std::thread::Builder::new()
        .name(READER_THREAD.into())
        .stack_size(READER_STACK)
        .spawn(move || {
            let stage = usd::Stage::builder()
                .resolver(resolver)
                .open(&file_str)
                .map_err(|e| UsdError::Open(format!("{e:#}")))?;
            read_stage(&stage)
        })
        .map_err(|e| UsdError::Open(format!("cannot start the reader: {e}")))
        .and_then(|h| {
            h.join().unwrap_or_else(|panic| {
                let why = panic
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| panic.downcast_ref::<String>().cloned())
                    .unwrap_or_default();
                Err(UsdError::Open(format!(
                    "the USD reader failed on this file ({why})"
                )))
            })
        });
    if let Some(e) = refused.lock().ok().and_then(|mut r| r.drain(..).next()) {
        return Err(error(e));
    }
    let nodes = result.map_err(error)?;
    if nodes.is_empty() {
        return Err(ImportError::Empty { path: shown });
    }
    Ok(nodes)
}

/// The name of the thread the USD crate reads on.
const READER_THREAD: &str = "usd import";

/// A panic of the USD reader's thread is reported as the file's error (with
/// its message), so the panic hook does not also print it, with a stack
/// trace, as if Hedra had crashed. Installed once; other threads' panics go
/// to the hook that was there before.
fn quiet_reader_panics() {
    static QUIET: std::sync::Once = std::sync::Once::new();
    QUIET.call_once(|| {
        let before = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if std::thread::current().name() != Some(READER_THREAD) {
                before(info)
            }
        }));
    });
}

/// What the walk gathers besides nodes, for the report.
#[derive(Default)]
struct Skipped {
    kinds: BTreeMap<String, usize>,
}

impl Skipped {
    fn add(&mut self, what: impl Into<String>) {
        *self.kinds.entry(what.into()).or_default() += 1;
    }
}

type R<T> = Result<T, UsdError>;

fn read_stage(stage: &usd::Stage) -> R<Vec<ImportedMesh>> {
    let mut out: Vec<ImportedMesh> = Vec::new();
    let mut skipped = Skipped::default();
    let root = stage.prim(sdf::Path::abs_root());
    let mut stack: Vec<(usd::Prim, Option<usize>, usize)> = children(&root)?
        .into_iter()
        .rev()
        .map(|p| (p, None, 0))
        .collect();
    let mut seen = 0usize;
    while let Some((prim, parent, depth)) = stack.pop() {
        seen += 1;
        if seen > MAX_PRIMS || depth > MAX_DEPTH {
            return Err(UsdError::TooLarge);
        }
        // Read a defined, active prim, not a class or an `over` (USD's
        // `IsActive`, `IsDefined` and not `IsAbstract`). Its ancestors were
        // checked on the way down (a skipped prim's children are never
        // visited), so only the prim's own opinions are asked: asking for the
        // ancestors' again made a 999-deep file take seconds.
        if !prim.is_active_here().unwrap_or(false)
            || prim.specifier().ok().flatten() != Some(sdf::Specifier::Def)
        {
            continue;
        }
        if prim.is_instance().unwrap_or(false) {
            skipped.add("instancing (instanced prims)");
        }
        let ty = prim
            .type_name()
            .ok()
            .flatten()
            .map(|t| t.as_str().to_string())
            .unwrap_or_default();
        let here = match ty.as_str() {
            "Material" | "Shader" | "NodeGraph" => {
                if ty == "Material" {
                    skipped.add("materials");
                }
                continue;
            }
            "Skeleton" | "SkelAnimation" | "BlendShape" => {
                skipped.add("skinning (skeletons, animations, blend shapes)");
                continue;
            }
            "GeomSubset" => {
                skipped.add("geometry subsets");
                continue;
            }
            _ if get_bool(&prim, "hedra:document")? == Some(true) => parent,
            "" | "Xform" | "Scope" | "SkelRoot" => {
                if ty == "SkelRoot" {
                    skipped.add("skinning (skeletons, animations, blend shapes)");
                }
                Some(push_node(
                    &mut out,
                    &prim,
                    parent,
                    NodeContent::Empty,
                    &mut skipped,
                )?)
            }
            "Mesh" | "NurbsPatch" | "NurbsCurves" => {
                let geometry = content(&prim, &ty, &mut skipped)?;
                let merged = get_bool(&prim, "hedra:nodeGeometry")? == Some(true);
                match (merged, parent) {
                    (true, Some(p)) => {
                        let (content, report, input) = single(geometry, &prim)?;
                        out[p].content = Some(content);
                        out[p].report = report;
                        out[p].input = input;
                        Some(p)
                    }
                    _ => Some(push_geometry(
                        &mut out,
                        &prim,
                        parent,
                        geometry,
                        &mut skipped,
                    )?),
                }
            }
            "PointInstancer" => {
                skipped.add("instancing (point instancers)");
                continue;
            }
            other => {
                skipped.add(format!("prims of type {other}"));
                parent
            }
        };
        for c in children(&prim)?.into_iter().rev() {
            stack.push((c, here, depth + 1));
        }
    }
    if let Some(first) = out.first_mut() {
        first.not_imported = skipped
            .kinds
            .iter()
            .map(|(k, n)| format!("{n} × {k}"))
            .collect();
    }
    Ok(out)
}

fn children(prim: &usd::Prim) -> R<Vec<usd::Prim>> {
    prim.children()
        .map_err(|e| prim_error(prim, format!("cannot list children: {e:#}")))
}

fn prim_error(prim: &usd::Prim, why: String) -> UsdError {
    UsdError::Prim {
        prim: prim.path().to_string(),
        why,
    }
}

fn attr_error(prim: &usd::Prim, attribute: &str, why: impl Into<String>) -> UsdError {
    UsdError::Attribute {
        prim: prim.path().to_string(),
        attribute: attribute.to_string(),
        why: why.into(),
    }
}

/// The node a prim makes (name, transform, visibility).
fn push_node(
    out: &mut Vec<ImportedMesh>,
    prim: &usd::Prim,
    parent: Option<usize>,
    content: NodeContent,
    skipped: &mut Skipped,
) -> R<usize> {
    let name = get_string(prim, "hedra:name")?
        .or_else(|| prim.path().name().map(str::to_string))
        .unwrap_or_else(|| "USD".into());
    let transform = transform(prim, skipped)?;
    let hidden = get_token(prim, "visibility")?.as_deref() == Some("invisible");
    out.push(ImportedMesh {
        parent,
        transform,
        hidden,
        content: Some(content),
        ..ImportedMesh::empty(name)
    });
    Ok(out.len() - 1)
}

/// What a geometry prim holds: one content, or (NurbsCurves with several
/// curves) one per curve.
enum Geometry {
    /// A content, what repair changed, and the faces as the file gave
    /// them when it changed them (for [`crate::import::keep_as_they_are`]).
    One(
        Box<(
            NodeContent,
            hedra_geom::RepairReport,
            Option<crate::kept::KeptMesh>,
        )>,
    ),
    Curves(Vec<NurbsCurve>),
}

type Single = (
    NodeContent,
    hedra_geom::RepairReport,
    Option<crate::kept::KeptMesh>,
);

fn single(g: Geometry, prim: &usd::Prim) -> R<Single> {
    match g {
        Geometry::One(one) => Ok(*one),
        Geometry::Curves(mut cs) if cs.len() == 1 => Ok((
            NodeContent::Curve(Arc::new(CurveContent::from_nurbs(cs.remove(0)))),
            Default::default(),
            None,
        )),
        Geometry::Curves(_) => Err(prim_error(
            prim,
            "a node's geometry holds several curves".into(),
        )),
    }
}

fn push_geometry(
    out: &mut Vec<ImportedMesh>,
    prim: &usd::Prim,
    parent: Option<usize>,
    g: Geometry,
    skipped: &mut Skipped,
) -> R<usize> {
    match g {
        Geometry::One(one) => {
            let (content, report, input) = *one;
            let i = push_node(out, prim, parent, content, skipped)?;
            out[i].report = report;
            out[i].input = input;
            Ok(i)
        }
        Geometry::Curves(curves) if curves.len() == 1 => {
            let c = curves.into_iter().next().expect("one curve");
            push_node(
                out,
                prim,
                parent,
                NodeContent::Curve(Arc::new(CurveContent::from_nurbs(c))),
                skipped,
            )
        }
        Geometry::Curves(curves) => {
            let group = push_node(out, prim, parent, NodeContent::Empty, skipped)?;
            let base = out[group].name.clone();
            for (k, c) in curves.into_iter().enumerate() {
                out.push(ImportedMesh {
                    parent: Some(group),
                    content: Some(NodeContent::Curve(Arc::new(CurveContent::from_nurbs(c)))),
                    ..ImportedMesh::empty(format!("{base}.{}", k + 1))
                });
            }
            Ok(group)
        }
    }
}

mod mesh;
mod values;
use mesh::mesh;
use values::*;

fn content(prim: &usd::Prim, ty: &str, skipped: &mut Skipped) -> R<Geometry> {
    match ty {
        "Mesh" => mesh(prim, skipped),
        "NurbsPatch" => patch(prim, skipped),
        _ => curves(prim),
    }
}

/// The local transform from the xform ops: exact when they are Hedra's
/// translate (double3), orient (quatd), scale (double3); else their
/// product, decomposed (shear is lost).
fn transform(prim: &usd::Prim, skipped: &mut Skipped) -> R<NodeTransform> {
    let Some(order) = get_tokens(prim, "xformOpOrder")? else {
        return Ok(NodeTransform::IDENTITY);
    };
    if order.len() > 64 {
        return Err(attr_error(prim, "xformOpOrder", "more than 64 ops"));
    }
    let mut m = DMat4::IDENTITY;
    let mut parts: Vec<(String, Option<DVec3>, Option<DQuat>)> = Vec::new();
    let mut exact = true;
    for op in &order {
        if op == "!resetXformStack!" {
            skipped.add("!resetXformStack! (read as a local transform)");
            continue;
        }
        let (invert, name) = match op.strip_prefix("!invert!") {
            Some(n) => (true, n),
            None => (false, op.as_str()),
        };
        exact &= !invert;
        if time_sampled(prim, name) {
            skipped.add("animation (time samples; the default value is read)");
        }
        let kind = name
            .strip_prefix("xformOp:")
            .map(|k| k.split(':').next().unwrap_or(""))
            .ok_or_else(|| {
                attr_error(prim, "xformOpOrder", format!("'{op}' is not an xform op"))
            })?;
        let value = get_value(prim, name)?
            .ok_or_else(|| attr_error(prim, name, "is listed in xformOpOrder but has no value"))?;
        let bad = |why: &str| attr_error(prim, name, why.to_string());
        let op_m = match kind {
            "translate" | "scale" => {
                let v = vec3(&value).ok_or_else(|| bad("is not a 3-vector"))?;
                parts.push((kind.to_string(), Some(v), None));
                exact &= matches!(value, sdf::Value::Vec3d(_));
                if kind == "translate" {
                    DMat4::from_translation(v)
                } else {
                    DMat4::from_scale(v)
                }
            }
            "orient" => {
                let q = quat(&value).ok_or_else(|| bad("is not a quaternion"))?;
                exact &= matches!(value, sdf::Value::Quatd(_));
                parts.push((kind.to_string(), None, Some(q)));
                DMat4::from_quat(q.normalize())
            }
            "transform" => {
                exact = false;
                match value {
                    sdf::Value::Matrix4d(mm) => DMat4::from_cols_array(&mm.0),
                    _ => return Err(bad("is not a matrix4d")),
                }
            }
            k if k.starts_with("rotate") => {
                exact = false;
                let axes = &k["rotate".len()..];
                let deg: Vec<f64> = if axes.len() == 1 {
                    vec![scalar(&value).ok_or_else(|| bad("is not a number"))?]
                } else {
                    vec3(&value)
                        .ok_or_else(|| bad("is not a 3-vector"))?
                        .to_array()
                        .to_vec()
                };
                if axes.len() != deg.len() || !axes.chars().all(|c| "XYZ".contains(c)) {
                    return Err(bad("is not a rotation Hedra reads"));
                }
                // rotateXYZ turns about X first: column-vector Rz·Ry·Rx.
                axes.chars()
                    .zip(deg)
                    .fold(DMat4::IDENTITY, |acc, (axis, d)| {
                        let r = d.to_radians();
                        let one = match axis {
                            'X' => DMat4::from_rotation_x(r),
                            'Y' => DMat4::from_rotation_y(r),
                            _ => DMat4::from_rotation_z(r),
                        };
                        one * acc
                    })
            }
            other => return Err(bad(&format!("op type '{other}' is not one Hedra reads"))),
        };
        m *= if invert { op_m.inverse() } else { op_m };
    }
    let kinds: Vec<&str> = parts.iter().map(|p| p.0.as_str()).collect();
    let t = if exact && kinds == ["translate", "orient", "scale"] {
        NodeTransform {
            translation: parts[0].1.unwrap_or_default(),
            rotation: parts[1].2.unwrap_or_default(),
            scale: parts[2].1.unwrap_or(DVec3::ONE),
        }
    } else {
        NodeTransform::from_matrix(m)
    };
    if !t.is_usable() {
        return Err(attr_error(
            prim,
            "xformOpOrder",
            "the transform is not finite or scales to zero",
        ));
    }
    Ok(t)
}

fn patch(prim: &usd::Prim, skipped: &mut Skipped) -> R<Geometry> {
    let count = |name: &str| -> R<usize> {
        get_value(prim, name)?
            .as_ref()
            .and_then(scalar)
            .filter(|n| *n >= 1.0 && *n <= MAX_ARRAY as f64)
            .map(|n| n as usize)
            .ok_or_else(|| attr_error(prim, name, "is missing or not a count"))
    };
    let (nu, nv) = (count("uVertexCount")?, count("vVertexCount")?);
    let (ou, ov) = (count("uOrder")?, count("vOrder")?);
    let ku = get_floats(prim, "uKnots")?.unwrap_or_default();
    let kv = get_floats(prim, "vKnots")?.unwrap_or_default();
    let points = exact_points(prim)?;
    if nu.checked_mul(nv) != Some(points.len()) {
        return Err(attr_error(
            prim,
            "points",
            format!("{} points for {nu} × {nv} vertices", points.len()),
        ));
    }
    let weights = get_floats(prim, "pointWeights")?.unwrap_or_else(|| vec![1.0; points.len()]);
    if weights.len() != points.len() {
        return Err(attr_error(
            prim,
            "pointWeights",
            format!("{} weights for {} points", weights.len(), points.len()),
        ));
    }
    // USD: u varies fastest; Hedra: i·nv + j.
    let mut ps = vec![DVec3::ZERO; points.len()];
    let mut ws = vec![1.0; points.len()];
    for j in 0..nv {
        for i in 0..nu {
            ps[i * nv + j] = points[j * nu + i];
            ws[i * nv + j] = weights[j * nu + i];
        }
    }
    let du = ou - 1;
    let dv = ov - 1;
    let domain = |k: &[f64], d: usize, n: usize| (k.get(d).copied(), k.get(n).copied());
    for (name, k, d, n) in [("uRange", &ku, du, nu), ("vRange", &kv, dv, nv)] {
        if let Some(r) = get_value(prim, name)?.as_ref().and_then(vec2)
            && (Some(r.x), Some(r.y)) != domain(k, d, n)
        {
            skipped.add(format!("{name} narrower than the knots (read whole)"));
        }
    }
    if get_value(prim, "trimCurve:counts")?.is_some() {
        skipped.add("NurbsPatch trim curves");
    }
    let sf = NurbsSurface::new(du, dv, ku, kv, nu, nv, ps, ws)
        .map_err(|e| prim_error(prim, format!("not a NURBS surface Hedra can hold: {e}")))?;
    Ok(Geometry::One(Box::new((
        NodeContent::Surface(Arc::new(SurfaceShape::Nurbs(sf))),
        Default::default(),
        None,
    ))))
}

fn curves(prim: &usd::Prim) -> R<Geometry> {
    let counts = get_ints(prim, "curveVertexCounts")?.unwrap_or_default();
    let orders = get_ints(prim, "order")?.unwrap_or_default();
    let knots = get_floats(prim, "knots")?.unwrap_or_default();
    let points = exact_points(prim)?;
    let weights = get_floats(prim, "pointWeights")?.unwrap_or_else(|| vec![1.0; points.len()]);
    if weights.len() != points.len() {
        return Err(attr_error(
            prim,
            "pointWeights",
            format!("{} weights for {} points", weights.len(), points.len()),
        ));
    }
    let (mut p_at, mut k_at) = (0usize, 0usize);
    let mut out = Vec::new();
    for (c, &n) in counts.iter().enumerate() {
        let order = orders.get(c).copied().unwrap_or(4);
        if n < 1 || !(2..=64).contains(&order) {
            return Err(attr_error(
                prim,
                "curveVertexCounts",
                format!("curve {c}: {n} vertices of order {order}"),
            ));
        }
        let (n, order) = (n as usize, order as usize);
        let (Some(ps), Some(ks)) = (
            points.get(p_at..p_at + n),
            knots.get(k_at..k_at + n + order),
        ) else {
            return Err(attr_error(
                prim,
                "knots",
                format!("curve {c}: fewer points or knots than its counts ask for"),
            ));
        };
        let curve = NurbsCurve::new(
            order - 1,
            ks.to_vec(),
            ps.to_vec(),
            weights[p_at..p_at + n].to_vec(),
        )
        .map_err(|e| {
            prim_error(
                prim,
                format!("curve {c} is not a NURBS curve Hedra can hold: {e}"),
            )
        })?;
        out.push(curve);
        p_at += n;
        k_at += n + order;
    }
    if out.is_empty() {
        return Err(attr_error(prim, "curveVertexCounts", "no curves"));
    }
    if out.len() == 1
        && let Some(json) = get_string(prim, "hedra:curveKind")?
        && let Ok(kind) = ron::from_str::<hedra_geom::curves::CurveKind>(&json)
        && let Ok(content) = CurveContent::new(kind)
    {
        return Ok(Geometry::One(Box::new((
            NodeContent::Curve(Arc::new(content)),
            Default::default(),
            None,
        ))));
    }
    Ok(Geometry::Curves(out))
}
