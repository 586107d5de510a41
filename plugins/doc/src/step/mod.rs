//! STEP (ISO 10303-21, AP214 `AUTOMOTIVE_DESIGN`) export and import of
//! NURBS geometry; what is kept and dropped is in `docs/exchange.md`.
//!
//! Export ([`to_step`]): every visible surface node becomes an
//! `ADVANCED_FACE` on a `B_SPLINE_SURFACE_WITH_KNOTS` (the complex
//! rational form when weighted) with its world transform applied to the
//! control points (an affine map keeps a NURBS exact); faces that share
//! boundary curves share edges, and a group of faces that closes up is a
//! `MANIFOLD_SOLID_BREP`, else a `SHELL_BASED_SURFACE_MODEL`
//! ([`brep::write_shells`]). A Bézier triangle of degree n is written
//! exactly as a degree n × n tensor-product patch with one side collapsed
//! ([`triangle_as_patch`]). Curves go in a `GEOMETRIC_CURVE_SET` as
//! `B_SPLINE_CURVE_WITH_KNOTS`. Meshes, on request, as faceted shells.
//!
//! Import ([`step_from_bytes`]): B-spline surfaces of faces and B-spline
//! curves of curve sets become surface and curve nodes, in metres.

pub mod brep;
mod faces;
pub mod p21;
pub mod read;
pub mod write;

pub use read::step_from_bytes;

use crate::export::{ExportError, ExportShape, Geometry};
use crate::scene::{Document, NodeContent, SurfaceShape};
use glam::{DMat4, DVec3};
use hedra_geom::{BezierTriangle, NurbsCurve, NurbsSurface};
use write::{StepWriter, list, r, string};

/// The length unit a STEP file is written in.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum StepUnits {
    /// Metres (Hedra's own unit: coordinates are written as they are).
    #[default]
    Metres,
    /// Millimetres (coordinates × 1000).
    Millimetres,
}

impl StepUnits {
    /// File units per metre.
    pub fn per_metre(self) -> f64 {
        match self {
            StepUnits::Metres => 1.0,
            StepUnits::Millimetres => 1000.0,
        }
    }
}

/// How to write a STEP file.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct StepOptions {
    /// The length unit (stated in the file's context).
    pub units: StepUnits,
    /// Write visible meshes (and CSG solids) as faceted shells; otherwise
    /// they are left out and the report says so.
    pub meshes: bool,
    /// Write a visible mesh with a Catmull-Clark subdivision modifier as
    /// the NURBS patches of its limit surface
    /// ([`MeshContent::limit_nurbs`](crate::scene::MeshContent::limit_nurbs)
    /// at [`DEFAULT_NURBS_TOLERANCE`](crate::command::DEFAULT_NURBS_TOLERANCE)),
    /// one solid when the cage is closed, instead of as a mesh (or not at
    /// all); the notes give the patch counts and the measured distance and
    /// angle. A mesh whose conversion is refused is treated as any mesh.
    pub subdivision_as_nurbs: bool,
}

/// Distance within which points of the file are one (edges shared,
/// vertices merged), in metres; also the file's stated uncertainty.
pub const TOLERANCE_METRES: f64 = 1e-7;

/// A degree-n Bézier triangle as the degree n × n tensor-product Bézier
/// patch with the same points: with `u = s`, `v = (1 − s) t`,
/// `w = (1 − s)(1 − t)`, the term `b_ijk` of the triangle is
/// `B^n_i(s) · B^{n−i}_j(t)`, so row i of the patch is the degree
/// `n − i` Bézier curve of `b_{i,j,n−i−j}` (j = 0…n−i) elevated to
/// degree n. Row n is the point `b_n00`: the side s = 1 collapses there.
/// Exact (degree elevation is); the patch at (s, t) is the triangle at
/// `(u, v) = (s, (1 − s) t)`.
pub fn triangle_as_patch(t: &BezierTriangle) -> NurbsSurface {
    let n = t.degree;
    let mut points = Vec::with_capacity((n + 1) * (n + 1));
    for i in 0..=n {
        let m = n - i;
        let mut row: Vec<DVec3> = (0..=m).map(|j| t.point(i, j)).collect();
        // Degree elevation of a Bézier curve (The NURBS Book eq. 5.36).
        for d in m..n {
            let mut next = Vec::with_capacity(d + 2);
            next.push(row[0]);
            for k in 1..=d {
                let a = k as f64 / (d + 1) as f64;
                next.push(row[k - 1] * a + row[k] * (1.0 - a));
            }
            next.push(row[d]);
            row = next;
        }
        points.extend(row);
    }
    NurbsSurface::from_bezier(n + 1, n + 1, points).expect("a triangle's points are finite")
}

/// A NURBS surface with its control points mapped by `m` (exact).
fn surface_transformed(s: &NurbsSurface, m: &DMat4) -> Option<NurbsSurface> {
    s.transformed(m).ok()
}

/// The document as a STEP file named `file_name` (in the header), with
/// the notes for the export report (what was left out, how triangles
/// were written).
///
/// # Errors
/// [`ExportError::StepMeshesOnly`] when the visible nodes are meshes only
/// and `options.meshes` is off; [`ExportError::NothingToExport`] when no
/// visible node has a surface, a curve or a mesh; as
/// [`crate::export::export_bytes`] for a mesh whose shape cannot be made.
pub fn to_step(
    doc: &Document,
    options: StepOptions,
    file_name: &str,
) -> Result<(Vec<u8>, Vec<String>), ExportError> {
    let scale = options.units.per_metre();
    let unit = DMat4::from_scale(DVec3::splat(scale));
    let tree = doc.hierarchy();
    let w = StepWriter::new();
    let mut surfaces: Vec<(String, NurbsSurface)> = Vec::new();
    let mut curves: Vec<(String, NurbsCurve)> = Vec::new();
    let mut meshes: Vec<FacetedMesh> = Vec::new();
    let (mut triangles, mut left_meshes, mut approximate) = (0usize, 0usize, Vec::new());
    // Notes on meshes written as their limit surface, and the meshes left
    // out that could have been.
    let (mut converted, mut left_subdivision) = (Vec::new(), 0usize);
    for &id in tree.order() {
        let (Some(node), Some(facts)) = (doc.node(id), tree.facts(id)) else {
            continue;
        };
        if !facts.visible || facts.inside_csg {
            continue;
        }
        let m = unit * facts.world;
        if let NodeContent::Mesh(content) = &node.content
            && options.subdivision_as_nurbs
            && content.subdivision.is_some()
        {
            match content.limit_nurbs(crate::command::DEFAULT_NURBS_TOLERANCE, &node.name) {
                Ok(c) => {
                    for (k, p) in c.patches.iter().enumerate() {
                        if let Some(s) = surface_transformed(&p.surface, &m) {
                            surfaces.push((format!("{} {}", node.name, k + 1), s));
                        }
                    }
                    converted.push(format!(
                        "'{}' written as its limit surface: {} (in the node's own coordinates)",
                        node.name,
                        crate::command::nurbs_conversion_summary(&c)
                    ));
                    continue;
                }
                Err(e) => converted.push(format!(
                    "'{}' not converted to NURBS ({e}); written as a mesh would be",
                    node.name
                )),
            }
        }
        match &node.content {
            NodeContent::Surface(shape) => {
                let local = match &**shape {
                    SurfaceShape::Nurbs(s) => s.clone(),
                    SurfaceShape::Triangle(t) => {
                        triangles += 1;
                        triangle_as_patch(t)
                    }
                };
                if let Some(s) = surface_transformed(&local, &m) {
                    surfaces.push((node.name.clone(), s));
                }
            }
            NodeContent::Curve(c) => {
                if let Some(e) = c.tolerance() {
                    approximate.push(format!("'{}' (within {e:.1e})", node.name));
                }
                if let Ok(curve) = c.nurbs().transformed(&m) {
                    curves.push((node.name.clone(), curve));
                }
            }
            NodeContent::Mesh(content) if !options.meshes => {
                left_meshes += 1;
                left_subdivision += usize::from(content.subdivision.is_some());
            }
            NodeContent::Csg(_) if !options.meshes => left_meshes += 1,
            NodeContent::Mesh(_) | NodeContent::Csg(_) => {
                if let Some(Geometry::Mesh(mesh)) =
                    crate::export::export_geometry(doc, node, ExportShape::Evaluated)?
                {
                    let mut tris = Vec::new();
                    let mirrored = m.determinant() < 0.0;
                    for f in mesh.faces() {
                        for t in hedra_geom::query::triangulate_face(&mesh, f) {
                            let [a, b, c] = t.map(|v| v.index() as u32);
                            tris.push(if mirrored { [a, c, b] } else { [a, b, c] });
                        }
                    }
                    // Indexed by vertex id: vertices at one place stay apart.
                    let mut positions = vec![DVec3::ZERO; mesh.vertex_capacity()];
                    for v in mesh.vertices() {
                        positions[v.index()] = m.transform_point3(mesh.position(v));
                    }
                    meshes.push(FacetedMesh {
                        name: node.name.clone(),
                        positions,
                        triangles: tris,
                        closed: mesh.halfedges().all(|h| mesh.face(h).is_some()),
                    });
                }
            }
            NodeContent::Kept(content) if !options.meshes => {
                left_meshes += 1;
                left_subdivision += usize::from(content.subdivision.is_some());
            }
            NodeContent::Kept(_) => {
                if let Some(Geometry::Polygons(kept)) =
                    crate::export::export_geometry(doc, node, ExportShape::Evaluated)?
                {
                    let mirrored = m.determinant() < 0.0;
                    let triangles = kept
                        .triangles()
                        .into_iter()
                        .map(|[a, b, c]| if mirrored { [a, c, b] } else { [a, b, c] })
                        .collect();
                    meshes.push(FacetedMesh {
                        name: node.name.clone(),
                        positions: kept
                            .positions
                            .iter()
                            .map(|&p| m.transform_point3(p))
                            .collect(),
                        triangles,
                        // A kept mesh is not manifold: never a closed shell.
                        closed: false,
                    });
                }
            }
            NodeContent::Empty => {}
        }
    }
    if surfaces.is_empty() && curves.is_empty() && meshes.is_empty() {
        if left_meshes > 0 {
            return Err(ExportError::StepMeshesOnly {
                path: file_name.into(),
                meshes: left_meshes,
            });
        }
        return Err(ExportError::NothingToExport {
            path: file_name.into(),
            triangles_only: false,
        });
    }
    let written = Written {
        surfaces: &surfaces,
        curves: &curves,
        meshes: &meshes,
    };
    let (w, shells) = write_file(w, &written, options.units, file_name);
    let mut notes = converted;
    if left_meshes > 0 {
        notes.push(format!(
            "{left_meshes} mesh node(s) left out; pass --step-meshes to write them as faceted shells"
        ));
    }
    if left_subdivision > 0 && !options.subdivision_as_nurbs {
        notes.push(format!(
            "{left_subdivision} of them have a subdivision modifier; pass --step-subdivision-nurbs to write their limit surfaces as NURBS solids"
        ));
    }
    if triangles > 0 {
        notes.push(format!(
            "{triangles} Bézier triangle(s) written exactly as tensor-product patches with one side collapsed"
        ));
    }
    if !approximate.is_empty() {
        notes.push(format!(
            "curve(s) written as their approximating NURBS form: {}",
            approximate.join(", ")
        ));
    }
    let solids = shells.iter().filter(|s| s.closed).count();
    if solids > 0 {
        notes.push(format!(
            "{solids} closed group(s) of surfaces written as solids (MANIFOLD_SOLID_BREP)"
        ));
    }
    let unit = match options.units {
        StepUnits::Metres => "metres",
        StepUnits::Millimetres => "millimetres",
    };
    let description = format!("Hedra scene: NURBS surfaces and curves, lengths in {unit}");
    Ok((w.finish(file_name, &description), notes))
}

/// A mesh to write as a faceted shell: world positions by vertex index
/// (in the file's unit), triangles, and whether it is closed.
struct FacetedMesh {
    name: String,
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    closed: bool,
}

/// What goes into a file, in its units.
struct Written<'a> {
    surfaces: &'a [(String, NurbsSurface)],
    curves: &'a [(String, NurbsCurve)],
    meshes: &'a [FacetedMesh],
}

/// Writes the context, the shells and solids of the surfaces, the curve
/// set, the faceted meshes, the representation and the product.
fn write_file(
    mut w: StepWriter,
    written: &Written,
    units: StepUnits,
    file_name: &str,
) -> (StepWriter, Vec<brep::WrittenShell>) {
    let tolerance = TOLERANCE_METRES * units.per_metre();
    let context = w.context(units, tolerance);
    let mut items = Vec::new();
    let patches: Vec<brep::Patch> = written
        .surfaces
        .iter()
        .map(|(name, s)| brep::Patch { name, surface: s })
        .collect();
    let shells = brep::write_shells(&mut w, &patches, tolerance);
    items.extend(shells.iter().map(|s| r(s.item)));
    if !written.curves.is_empty() {
        let ids: Vec<String> = written
            .curves
            .iter()
            .map(|(name, c)| r(w.bspline_curve(name, c)))
            .collect();
        items.push(r(
            w.add(&format!("GEOMETRIC_CURVE_SET('Curves',{})", list(ids)))
        ));
    }
    for mesh in written.meshes {
        items.push(r(write_faceted(&mut w, mesh)));
    }
    let origin = w.placement(DVec3::ZERO, DVec3::Z, DVec3::X);
    items.push(r(origin));
    let rep = w.add(&format!(
        "SHAPE_REPRESENTATION('Hedra',{},#{context})",
        list(items)
    ));
    let product = std::path::Path::new(file_name)
        .file_stem()
        .and_then(|s| s.to_str())
        .map_or("Hedra", |s| {
            s.trim_end_matches(".step").trim_end_matches(".stp")
        });
    w.product(product, rep);
    (w, shells)
}

/// A STEP file of `patches` alone (coordinates in metres), each a face
/// named after its patch, grouped into open shells and closed solids by
/// the edges they share ([`brep::write_shells`]): the entry for code that
/// makes its own patches (a subdivision surface's, one solid when they
/// close up). Returns the file and what was written per shell (closed,
/// volume in the file's unit cubed, edge count).
pub fn patches_to_step(
    patches: &[brep::Patch],
    units: StepUnits,
    file_name: &str,
) -> (Vec<u8>, Vec<brep::WrittenShell>) {
    let unit = DMat4::from_scale(DVec3::splat(units.per_metre()));
    let surfaces: Vec<(String, NurbsSurface)> = patches
        .iter()
        .filter_map(|p| Some((p.name.to_string(), surface_transformed(p.surface, &unit)?)))
        .collect();
    let written = Written {
        surfaces: &surfaces,
        curves: &[],
        meshes: &[],
    };
    let (w, shells) = write_file(StepWriter::new(), &written, units, file_name);
    (w.finish(file_name, "Hedra NURBS patches"), shells)
}

/// A mesh's triangles as planar faces (`FACE_SURFACE` on a `PLANE`,
/// bounded by a `POLY_LOOP`), one `CARTESIAN_POINT` per vertex (vertices
/// at one place stay apart, so the mesh comes back with its connectivity):
/// a `FACETED_BREP` when the mesh is closed, else a
/// `SHELL_BASED_SURFACE_MODEL`. Triangles of zero area are left out.
fn write_faceted(w: &mut StepWriter, mesh: &FacetedMesh) -> u64 {
    let mut ids: std::collections::HashMap<u32, u64> = Default::default();
    let mut faces = Vec::with_capacity(mesh.triangles.len());
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|k| mesh.positions[k as usize]);
        let Some(n) = (b - a).cross(c - a).try_normalize() else {
            continue;
        };
        let corners: Vec<String> = t
            .iter()
            .map(|&k| {
                r(*ids
                    .entry(k)
                    .or_insert_with(|| w.point(mesh.positions[k as usize])))
            })
            .collect();
        let plane_at = w.placement(a, n, (b - a).normalize());
        let plane = w.add(&format!("PLANE('',#{plane_at})"));
        let lp = w.add(&format!("POLY_LOOP('',{})", list(corners)));
        let bound = w.add(&format!("FACE_OUTER_BOUND('',#{lp},.T.)"));
        faces.push(r(
            w.add(&format!("FACE_SURFACE('',(#{bound}),#{plane},.T.)"))
        ));
    }
    let (name, closed) = (&mesh.name, mesh.closed);
    if closed {
        let shell = w.add(&format!("CLOSED_SHELL({},{})", string(name), list(faces)));
        w.add(&format!("FACETED_BREP({},#{shell})", string(name)))
    } else {
        let shell = w.add(&format!("OPEN_SHELL({},{})", string(name), list(faces)));
        w.add(&format!(
            "SHELL_BASED_SURFACE_MODEL({},(#{shell}))",
            string(name)
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hedra_geom::surfaces::Surface;

    #[test]
    fn patches_alone_make_a_file_with_one_solid_when_they_close_up() {
        let ball = NurbsSurface::sphere(DVec3::ZERO, 0.5);
        let (bytes, shells) = patches_to_step(
            &[brep::Patch {
                name: "Ball",
                surface: &ball,
            }],
            StepUnits::Millimetres,
            "ball.step",
        );
        assert_eq!(shells.len(), 1);
        assert!(shells[0].closed);
        // Radius 500 mm; the grid of 24 × 24 points measures within 3 %.
        let v = 4.0 / 3.0 * std::f64::consts::PI * 500f64.powi(3);
        assert!(
            (shells[0].volume - v).abs() < 0.03 * v,
            "{}",
            shells[0].volume
        );
        let text = String::from_utf8(bytes).unwrap();
        assert!(text.contains("MANIFOLD_SOLID_BREP('Ball'"));
        assert!(text.contains("SI_UNIT(.MILLI.,.METRE.)"));
        assert!(text.contains("PRODUCT('ball','ball'"));
    }

    #[test]
    fn a_triangle_as_a_collapsed_patch_has_the_same_points() {
        let points: Vec<DVec3> = (0..10)
            .map(|k| DVec3::new(k as f64, (k * k) as f64 * 0.1, (k as f64).sin()))
            .collect();
        let t = BezierTriangle::new(3, points).unwrap();
        let p = triangle_as_patch(&t);
        assert_eq!(p.degrees(), (3, 3));
        for i in 0..=6 {
            for j in 0..=6 {
                let (s, tt) = (i as f64 / 6.0, j as f64 / 6.0);
                let (u, v) = (s, (1.0 - s) * tt);
                let want = t.evaluate(DVec3::new(u, v, 1.0 - u - v));
                let got = p.evaluate(s, tt).p;
                assert!(got.distance(want) < 1e-12, "{s} {tt}: {got} vs {want}");
            }
        }
    }
}
