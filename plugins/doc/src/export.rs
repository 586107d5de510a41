//! Writing meshes to other formats. OBJ keeps polygons as they are (n-gons
//! included); binary STL gets the faces triangulated. Both write world-space
//! positions of the visible meshes, as their subdivision modifiers shape
//! them unless the cage is asked for.
//!
//! A mesh written as its cage (no subdivision applied) carries its corner
//! attributes into OBJ: deduplicated `vt` and `vn` lines (normals turned to
//! world space) and `f v/vt/vn` corners. A face gets `vt` only when all its
//! corners have a UV, `vn` only when all have a normal; other faces are
//! plain `f v`. A subdivided shape is written without attributes.

use crate::scene::{CornerAttributes, Document, Node, NodeContent};
use glam::DVec3;
use hedra_geom::HalfEdgeMesh;
use hedra_geom::subdivision::Creases;
use std::borrow::Cow;
use std::collections::HashMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// Which shape of each mesh is written.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum ExportShape {
    /// The evaluated shape: meshes with their modifier stack (Mirror,
    /// Array) applied and a subdivision modifier at its export level.
    #[default]
    Evaluated,
    /// The editable cage, modifiers ignored.
    Cage,
    /// Every mesh subdivided this many levels (its modifier's scheme, else
    /// Catmull-Clark), its stack modifiers applied.
    Subdivided(u32),
}

/// A format File ▸ Export and `hedra export` write: the one place that
/// names each format, its extensions and its menu label.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum ExportFormat {
    /// Wavefront OBJ: polygons as they are, curves as polylines or NURBS records.
    Obj,
    /// STL, triangulated (binary, or text with [`ExportOptions::ascii_stl`]).
    Stl,
    /// glTF 2.0 with the hierarchy (`.glb` binary, `.gltf` text).
    Gltf,
    /// OpenUSD text: the hierarchy, subdivision cages with their creases
    /// kept live, NURBS surfaces and curves ([`crate::usd`]).
    Usd,
    /// STEP AP214: NURBS surfaces and curves for CAD, closed shells as
    /// solids ([`crate::step`]).
    Step,
}

impl ExportFormat {
    /// Every export format, in menu order.
    pub const ALL: [ExportFormat; 5] = [
        ExportFormat::Obj,
        ExportFormat::Stl,
        ExportFormat::Gltf,
        ExportFormat::Usd,
        ExportFormat::Step,
    ];

    /// The format's name ("Wavefront OBJ").
    pub fn name(self) -> &'static str {
        match self {
            ExportFormat::Obj => "Wavefront OBJ",
            ExportFormat::Stl => "STL",
            ExportFormat::Gltf => "glTF 2.0",
            ExportFormat::Usd => "OpenUSD",
            ExportFormat::Step => "STEP",
        }
    }

    /// The extensions that pick the format; the first is the one offered.
    pub fn extensions(self) -> &'static [&'static str] {
        match self {
            ExportFormat::Obj => &["obj"],
            ExportFormat::Stl => &["stl"],
            ExportFormat::Gltf => &["glb", "gltf"],
            ExportFormat::Usd => &["usda"],
            ExportFormat::Step => &["step", "stp"],
        }
    }

    /// What File ▸ Export shows for it.
    pub fn menu_label(self) -> &'static str {
        match self {
            ExportFormat::Obj => "Wavefront OBJ (.obj)…",
            ExportFormat::Stl => "STL, triangulated (.stl)…",
            ExportFormat::Gltf => "glTF 2.0 binary, with the hierarchy (.glb)…",
            ExportFormat::Usd => "OpenUSD, subdivision and NURBS kept (.usda)…",
            ExportFormat::Step => "STEP, NURBS for CAD (.step)…",
        }
    }

    /// The format a file name's extension picks (any case).
    pub fn of_path(path: &Path) -> Option<ExportFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        ExportFormat::ALL
            .into_iter()
            .find(|f| f.extensions().contains(&ext.as_str()))
    }
}

/// How OBJ holds curve nodes.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum CurveExport {
    /// Every curve as an `l` polyline through points of it, tessellated to
    /// a fraction of its size (what any OBJ reader understands).
    #[default]
    Polylines,
    /// Every curve whose NURBS form is exact (every kind but a Lagrange
    /// curve of more than 12 points) as an OBJ free-form B-spline record —
    /// `cstype bspline` (`cstype rat bspline` with `v x y z w` weights when
    /// rational), `deg`, `curv t₀ t₁ v…`, `parm u` with the whole knot
    /// vector, `end` — control points in world space (an affine map keeps
    /// a NURBS curve exact); an approximated one as a polyline.
    FreeForm,
}

/// How to export.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct ExportOptions {
    /// Which shape of each mesh to write (default: evaluated, modifiers applied).
    pub shape: ExportShape,
    /// Write STL as text instead of binary.
    pub ascii_stl: bool,
    /// How OBJ writes curve nodes (the other formats tessellate them or
    /// leave them out).
    pub curves: CurveExport,
    /// STEP's length unit and whether meshes go in as faceted shells.
    pub step: crate::step::StepOptions,
}

/// A written export: the file's bytes and what the user should know about
/// them (what a format could not hold and how it was written instead).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Exported {
    /// The file's contents.
    pub bytes: Vec<u8>,
    /// One line per thing the user should know, naming the node.
    pub notes: Vec<String>,
}

/// Why an export could not be made; nothing is written then.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// A visible CSG node has no solid (an open operand, an empty result).
    #[error(transparent)]
    Csg(Box<crate::csg::CsgError>),
    /// The scene has nothing the format can hold (no visible meshes or
    /// surfaces for STL; no visible meshes, curves or surfaces for OBJ).
    #[error("{}: nothing to export: the scene has no visible {}", path.display(), if *triangles_only {
        "meshes or surfaces (STL holds triangles only)"
    } else {
        "meshes, curves or surfaces"
    })]
    NothingToExport {
        /// The file asked for.
        path: PathBuf,
        /// The format holds triangles only (STL), so curves do not count.
        triangles_only: bool,
    },
    /// The path's extension names no export format.
    #[error("{}: unsupported export format '.{extension}' (supported: {})", path.display(), supported_formats())]
    UnsupportedFormat {
        /// The file asked for.
        path: PathBuf,
        /// Its extension, lower case (empty when it has none).
        extension: String,
    },
    /// A mesh's evaluated shape for the export could not be made (a stack
    /// modifier that refused, Loop on a mesh with quads, a level too large).
    #[error("node '{node}': {error}")]
    Evaluation {
        /// The node's name.
        node: String,
        /// The modifier's or the subdivision's reason.
        error: crate::modifiers::EvaluationError,
    },
    /// A mesh has a face with an inner ring or without edges (made by the
    /// Euler operators), which the exchange formats cannot hold.
    #[error(
        "node '{node}': {face} has an inner ring or no edges; OBJ, STL and glTF hold plain polygons only (join the ring to the face's outer loop with MEKR first)"
    )]
    NotPolygon {
        /// The node's name.
        node: String,
        /// The first such face.
        face: hedra_geom::FaceId,
    },
    /// A STEP export of a scene whose only visible content is meshes,
    /// which STEP gets only as faceted shells, when asked for
    /// ([`crate::step::StepOptions::meshes`]).
    #[error(
        "{}: nothing to export: STEP holds NURBS surfaces and curves, and the scene has none; its {meshes} visible mesh node(s) are written as faceted shells only when asked (--step-meshes)",
        path.display()
    )]
    StepMeshesOnly {
        /// The file asked for.
        path: PathBuf,
        /// The visible mesh and CSG nodes left out.
        meshes: usize,
    },
    /// The exported file could not be written (the old file is kept).
    #[error(transparent)]
    Write(Box<crate::file::FileError>),
    /// serde_json could not write the glTF document.
    #[error("cannot write glTF: {0}")]
    GltfJson(String),
}

/// The export extensions as the error lists them: `.obj, .stl, ...`.
fn supported_formats() -> String {
    ExportFormat::ALL
        .iter()
        .flat_map(|f| f.extensions())
        .map(|e| format!(".{e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The document in the format that `path`'s extension names (the bytes of
/// [`export_file`]).
///
/// # Errors
/// As [`export_file`].
pub fn export_bytes(
    doc: &Document,
    path: &Path,
    options: ExportOptions,
) -> Result<Vec<u8>, ExportError> {
    export_file(doc, path, options).map(|e| e.bytes)
}

/// The document in the format that `path`'s extension names, with the notes
/// the user should see, in memory. The readers
/// ([`crate::import::import_file`]) turn what Hedra writes back into nodes.
///
/// # Errors
/// As [`prepare_export`].
pub fn export_file(
    doc: &Document,
    path: &Path,
    options: ExportOptions,
) -> Result<Exported, ExportError> {
    let prepared = prepare_export(doc, path, options)?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    prepared
        .write_to(&mut bytes)
        .expect("writing to memory cannot fail");
    Ok(Exported {
        bytes: bytes.into_inner(),
        notes: prepared.notes,
    })
}

/// Exports the document to `path` (the format its extension names),
/// streamed into the file ([`crate::file::write_atomic_streamed`]: the old
/// file stays until the new one is whole), and returns the notes the user
/// should see. What File ▸ Export and `hedra export` do: a large export is
/// never held in memory as a whole file.
///
/// # Errors
/// As [`prepare_export`]; [`ExportError::Write`] when the file cannot be
/// written.
pub fn export_to_path(
    doc: &Document,
    path: &Path,
    options: ExportOptions,
) -> Result<Vec<String>, ExportError> {
    let prepared = prepare_export(doc, path, options)?;
    crate::file::write_atomic_streamed(path, |out| prepared.write_to(out))
        .map_err(|e| ExportError::Write(Box::new(e)))?;
    Ok(prepared.notes)
}

/// An output an export can be written to: a file, or memory through a
/// [`std::io::Cursor`]. Binary STL seeks back to fill in its triangle count.
pub trait ExportOutput: std::io::Write + std::io::Seek {}
impl<T: std::io::Write + std::io::Seek> ExportOutput for T {}

/// An export made from the document and ready to write: everything that
/// can fail for a reason of the scene (a node's shape, a format that holds
/// nothing of it) has been found, so writing it can fail only as its
/// output does.
pub struct PreparedExport<'a> {
    body: Body<'a>,
    /// One line per thing the user should know, naming the node.
    pub notes: Vec<String>,
}

/// What each format writes from.
enum Body<'a> {
    Obj(Vec<ExportItem<'a>>),
    Stl(Vec<ExportItem<'a>>),
    AsciiStl(Vec<ExportItem<'a>>),
    Glb(Box<crate::gltf::GltfParts<'a>>),
    /// Formats written whole in memory (glTF text, USD, STEP).
    Bytes(Vec<u8>),
}

impl PreparedExport<'_> {
    /// Writes the file's bytes to `out`, streamed: OBJ and STL as their
    /// faces are triangulated and formatted, GLB's buffer array by array.
    ///
    /// # Errors
    /// What `out` returns.
    pub fn write_to(&self, out: &mut dyn ExportOutput) -> std::io::Result<()> {
        match &self.body {
            Body::Obj(items) => write_obj(items, out),
            Body::Stl(items) => write_stl(items, out),
            Body::AsciiStl(items) => out.write_all(to_ascii_stl(items).as_bytes()),
            Body::Glb(parts) => parts.write_glb(out),
            Body::Bytes(bytes) => out.write_all(bytes),
        }
    }
}

/// Makes the export of the document in the format that `path`'s extension
/// names, with the notes the user should see.
///
/// # Errors
/// [`ExportError`] naming the file when the extension is not an export
/// format or the scene holds nothing the format can, or naming the node
/// whose subdivision failed.
pub fn prepare_export<'a>(
    doc: &'a Document,
    path: &Path,
    options: ExportOptions,
) -> Result<PreparedExport<'a>, ExportError> {
    let curves = options.curves;
    let shape = options.shape;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    // OBJ and STL of nothing would be empty files: say so instead.
    let items = |stl: bool| -> Result<Vec<ExportItem<'_>>, ExportError> {
        let items = export_meshes(
            doc,
            shape,
            if stl { CurveExport::Polylines } else { curves },
        )?;
        let holds = |i: &ExportItem| {
            !stl || !matches!(i.geometry, Geometry::Polyline(_) | Geometry::FreeForm(_))
        };
        if !items.iter().any(holds) {
            return Err(ExportError::NothingToExport {
                path: path.to_path_buf(),
                triangles_only: stl,
            });
        }
        Ok(items)
    };
    let body = match ext.as_str() {
        "obj" => Body::Obj(items(false)?),
        "stl" if options.ascii_stl => Body::AsciiStl(items(true)?),
        "stl" => Body::Stl(items(true)?),
        "gltf" => Body::Bytes(crate::gltf::gltf_parts(doc, shape)?.to_gltf_text()?),
        "glb" => Body::Glb(Box::new(crate::gltf::gltf_parts(doc, shape)?)),
        "usda" => {
            let (bytes, mut notes) = crate::usd::to_usd(doc, path, shape)?;
            notes.extend(empty_solid_notes(doc));
            return Ok(PreparedExport {
                body: Body::Bytes(bytes),
                notes,
            });
        }
        "step" | "stp" => {
            let name = path
                .file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
            let (bytes, mut notes) = crate::step::to_step(doc, options.step, &name)?;
            notes.extend(empty_solid_notes(doc));
            return Ok(PreparedExport {
                body: Body::Bytes(bytes),
                notes,
            });
        }
        other => {
            return Err(ExportError::UnsupportedFormat {
                path: path.to_path_buf(),
                extension: other.to_string(),
            });
        }
    };
    Ok(PreparedExport {
        body,
        notes: empty_solid_notes(doc),
    })
}

/// A note for each visible CSG node whose solid is empty, which an export
/// leaves out.
fn empty_solid_notes(doc: &Document) -> Vec<String> {
    let tree = doc.hierarchy();
    doc.nodes()
        .filter(|n| matches!(n.content, NodeContent::Csg(_)))
        .filter(|n| tree.is_visible(n.id) && !tree.inside_csg(n.id))
        .filter(|n| crate::csg::evaluate(doc, n.id).is_ok_and(|s| s.face_count() == 0))
        .map(|n| format!("'{}' is an empty solid (its operands do not overlap as its operation needs): nothing is written for it", n.name))
        .collect()
}

/// The visible meshes as binary STL: every face triangulated, positions
/// in world space, each triangle's normal from its corners
/// (counter-clockwise is the outside). Streamed into `out`, 50 bytes a
/// triangle after the 80-byte header and the count (the layout
/// `stl_io::write_stl` writes, which needs every triangle in memory
/// first); the count is filled in at the end, when it is known.
fn write_stl(items: &[ExportItem], out: &mut dyn ExportOutput) -> std::io::Result<()> {
    use std::io::SeekFrom;
    let start = out.stream_position()?;
    out.write_all(&[0u8; 84])?;
    let mut count = 0u32;
    for item in items {
        // A large mesh's records are made on every core.
        match &item.geometry {
            Geometry::Refined(r) if r.refiner.face_count() >= PARALLEL_FACES => {
                count += r.write_stl_records(item.world, item.mirrored, out)?;
                continue;
            }
            Geometry::Mesh(m) if m.face_count() >= PARALLEL_FACES => {
                count += write_mesh_stl_records(m, item.world, item.mirrored, out)?;
                continue;
            }
            _ => {}
        }
        let mut failed = Ok(());
        each_stl_triangle(std::slice::from_ref(item), |normal, corners| {
            if failed.is_ok() {
                failed = out.write_all(&stl_record(normal, corners));
            }
            count += 1;
        });
        failed?;
    }
    out.seek(SeekFrom::Start(start + 80))?;
    out.write_all(&count.to_le_bytes())?;
    out.seek(SeekFrom::End(0))?;
    Ok(())
}

/// Faces of a mesh from which its STL records and OBJ lines are made on
/// all cores: below it, the threads cost more than they save.
const PARALLEL_FACES: usize = 1 << 16;

/// The binary STL records of `m`'s triangles in world space, face by face
/// as [`each_stl_triangle`] visits them, made in pieces of
/// [`refined::FACES_PER_PIECE`] faces on all cores and written in order.
/// Returns how many.
fn write_mesh_stl_records(
    m: &HalfEdgeMesh,
    world: glam::DMat4,
    mirrored: bool,
    out: &mut dyn ExportOutput,
) -> std::io::Result<u32> {
    let faces: Vec<hedra_geom::FaceId> = m.faces().collect();
    let pieces: Vec<&[hedra_geom::FaceId]> = faces.chunks(refined::FACES_PER_PIECE).collect();
    let piece_records = |piece: usize, bytes: &mut Vec<u8>| {
        bytes.reserve(2 * 50 * pieces[piece].len());
        let mut face = Vec::new();
        for &f in pieces[piece] {
            face.clear();
            hedra_geom::query::triangulate_face_into(m, f, &mut face);
            for corners in &face {
                let corners = corners.map(|v| world.transform_point3(m.position(v)));
                let (normal, corners) = stl_triangle(corners, mirrored);
                bytes.extend_from_slice(&stl_record(normal, corners));
            }
        }
    };
    let written = write_pieces_in_order(pieces.len(), &piece_records, out)?;
    Ok((written / 50) as u32)
}

/// A binary STL record: the normal, three corners (twelve floats) and a
/// zero attribute count.
fn stl_record(normal: [f32; 3], [a, b, c]: [[f32; 3]; 3]) -> [u8; 50] {
    let mut record = [0u8; 50];
    for (k, x) in [normal, a, b, c].as_flattened().iter().enumerate() {
        record[4 * k..4 * k + 4].copy_from_slice(&x.to_le_bytes());
    }
    record
}

/// The unit normal and the corners of a world-space triangle as STL holds
/// them, counter-clockwise seen from outside (a mirroring transform turns
/// the winding over: it is turned back).
fn stl_triangle([a, b, c]: [DVec3; 3], mirrored: bool) -> ([f32; 3], [[f32; 3]; 3]) {
    let [a, b, c] = if mirrored { [a, c, b] } else { [a, b, c] };
    let n = (b - a).cross(c - a).normalize_or_zero();
    (
        n.as_vec3().to_array(),
        [a, b, c].map(|p| p.as_vec3().to_array()),
    )
}

/// ASCII STL: the same triangles as text, one `solid` block per node named
/// after it (Hedra's STL reader makes each block a node again).
fn to_ascii_stl(items: &[ExportItem]) -> String {
    let mut out = String::new();
    for item in items {
        let triangles = stl_triangles(std::slice::from_ref(item));
        if triangles.is_empty() {
            continue;
        }
        let name: String = item
            .node
            .name
            .chars()
            .map(|c| if c.is_control() { '_' } else { c })
            .collect();
        let _ = writeln!(out, "solid {name}");
        for t in triangles {
            let n = t.normal;
            let _ = writeln!(
                out,
                "  facet normal {} {} {}\n    outer loop",
                n[0], n[1], n[2]
            );
            for v in t.vertices {
                let _ = writeln!(out, "      vertex {} {} {}", v[0], v[1], v[2]);
            }
            out.push_str("    endloop\n  endfacet\n");
        }
        let _ = writeln!(out, "endsolid {name}");
    }
    if out.is_empty() {
        out.push_str("solid hedra\nendsolid hedra\n");
    }
    out
}

/// Every visible surface as world-space triangles with their normals.
fn stl_triangles(items: &[ExportItem]) -> Vec<stl_io::Triangle> {
    let mut triangles = Vec::with_capacity(triangle_estimate(items));
    each_stl_triangle(items, |normal, corners| {
        triangles.push(stl_io::Triangle {
            normal: stl_io::Normal::new(normal),
            vertices: corners.map(stl_io::Vertex::new),
        });
    });
    triangles
}

/// About how many triangles `items` make (two per quad, one per triangle),
/// to size the output once.
fn triangle_estimate(items: &[ExportItem]) -> usize {
    items
        .iter()
        .map(|i| match &i.geometry {
            Geometry::Mesh(m) => m.halfedge_count() / 2,
            Geometry::Refined(r) => 2 * r.refiner.face_count(),
            Geometry::Triangles(_, _, t) => t.len(),
            Geometry::Polygons(k) => k.corner_count(),
            _ => 0,
        })
        .sum()
}

/// Calls `visit` with the unit normal and the world-space corners of every
/// triangle of the visible surfaces, in order (curves have none).
fn each_stl_triangle(items: &[ExportItem], mut visit: impl FnMut([f32; 3], [[f32; 3]; 3])) {
    let mut push = |corners: [DVec3; 3], mirrored: bool| {
        let (normal, corners) = stl_triangle(corners, mirrored);
        visit(normal, corners);
    };
    let mut face = Vec::new();
    for item in items {
        let world = item.world;
        match &item.geometry {
            Geometry::Mesh(m) => {
                for f in m.faces() {
                    face.clear();
                    hedra_geom::query::triangulate_face_into(m, f, &mut face);
                    for corners in &face {
                        push(
                            corners.map(|v| world.transform_point3(m.position(v))),
                            item.mirrored,
                        );
                    }
                }
            }
            Geometry::Refined(r) => r.each_triangle(|corners| {
                push(corners.map(|p| world.transform_point3(p)), item.mirrored);
            }),
            Geometry::Triangles(positions, _, tris) => {
                for t in tris {
                    push(
                        t.map(|i| world.transform_point3(positions[i as usize])),
                        item.mirrored,
                    );
                }
            }
            Geometry::Polygons(k) => {
                for t in k.triangles() {
                    push(
                        t.map(|i| world.transform_point3(k.positions[i as usize])),
                        item.mirrored,
                    );
                }
            }
            // STL holds only triangles: curves are left out.
            Geometry::Polyline(_) | Geometry::FreeForm(_) => {}
        }
    }
}

/// What is written for one node.
pub(crate) enum Geometry<'a> {
    Mesh(Cow<'a, HalfEdgeMesh>),
    /// A mesh subdivided for OBJ or STL, written straight from the
    /// refiner's faces ([`RefinedFaces`]).
    Refined(RefinedFaces),
    /// A kept (non-manifold) mesh's faces as they are: OBJ writes them as
    /// polygons, STL and glTF as their triangles.
    Polygons(Cow<'a, crate::kept::KeptMesh>),
    /// A tessellated surface: positions, the surface's unit normals there
    /// (the limit at poles), triangles.
    Triangles(Vec<DVec3>, Vec<DVec3>, Vec<[u32; 3]>),
    /// A tessellated curve.
    Polyline(Vec<DVec3>),
    /// A curve written exactly as an OBJ free-form record (OBJ only; never
    /// made by [`node_geometry`]).
    FreeForm(std::sync::Arc<hedra_geom::NurbsCurve>),
}

/// A node, what to write for it and its world matrix.
struct ExportItem<'a> {
    node: &'a Node,
    geometry: Geometry<'a>,
    world: glam::DMat4,
    /// The world transform mirrors (negative determinant): faces are
    /// written with their corners reversed, so the outside stays outside.
    mirrored: bool,
    /// UVs and normals, for a mesh written as its cage that has some.
    corners: Option<&'a CornerAttributes>,
}

/// Curves and surfaces are tessellated to this fraction of their size.
const EXPORT_TOLERANCE: f64 = 1e-4;

/// The visible meshes, curves and surfaces in the requested shape.
///
/// # Errors
/// [`ExportError::Evaluation`] naming the node when its modifiers cannot
/// be evaluated (Loop on a mesh with quads, a level too large).
///
/// Complexity: O(N) for the hierarchy (world matrices and visibility are
/// computed once per node, top down: [`Document::hierarchy`]), plus each
/// node's geometry.
fn export_meshes(
    doc: &Document,
    shape: ExportShape,
    curves: CurveExport,
) -> Result<Vec<ExportItem<'_>>, ExportError> {
    let tree = doc.hierarchy();
    let mut out = Vec::new();
    for node in doc.nodes() {
        // A CSG node exports its solid; its operands are part of it.
        let Some(facts) = tree.facts(node.id) else {
            continue;
        };
        if !facts.visible || facts.inside_csg {
            continue;
        }
        let exact_curve = match &node.content {
            NodeContent::Curve(c) if curves == CurveExport::FreeForm && c.tolerance().is_none() => {
                Some(Geometry::FreeForm(c.nurbs().clone()))
            }
            _ => None,
        };
        let geometry = match exact_curve {
            Some(g) => Some(g),
            None => match refined_geometry(node, shape)? {
                Some(refined) => Some(refined),
                None => export_geometry(doc, node, shape)?,
            },
        };
        if let Some(geometry) = geometry {
            let corners = match (&node.content, &geometry) {
                (NodeContent::Mesh(c), Geometry::Mesh(Cow::Borrowed(_)))
                    if !c.corners.is_empty() =>
                {
                    Some(&c.corners)
                }
                _ => None,
            };
            let world = facts.world;
            out.push(ExportItem {
                node,
                geometry,
                world,
                mirrored: world.determinant() < 0.0,
                corners,
            });
        }
    }
    Ok(out)
}

/// What every export format writes for `node`, in its own (local) space:
/// a CSG node's solid, else [`node_geometry`]. OBJ, STL and glTF all call
/// this, so that they write the same shape (issue 31, item 13: glTF wrote
/// a CSG node's operands), and so does [`written_counts`].
///
/// # Errors
/// [`ExportError::Csg`] when a CSG node has no solid; as [`node_geometry`].
pub(crate) fn export_geometry<'a>(
    doc: &Document,
    node: &'a Node,
    shape: ExportShape,
) -> Result<Option<Geometry<'a>>, ExportError> {
    Ok(export_geometry_creased(doc, node, shape)?.map(|(geometry, _)| geometry))
}

/// [`export_geometry`] with the creases of what is written (none for a
/// CSG solid), for splitting smooth normals along infinitely sharp ones.
///
/// # Errors
/// As [`export_geometry`].
pub(crate) fn export_geometry_creased<'a>(
    doc: &Document,
    node: &'a Node,
    shape: ExportShape,
) -> Result<Option<(Geometry<'a>, Cow<'a, Creases>)>, ExportError> {
    match &node.content {
        NodeContent::Csg(_) => {
            let solid =
                crate::csg::evaluate(doc, node.id).map_err(|e| ExportError::Csg(Box::new(e)))?;
            if solid.face_count() == 0 {
                // An empty solid: nothing to write ([`empty_solid_notes`]).
                return Ok(None);
            }
            Ok(Some((
                Geometry::Mesh(Cow::Owned((*solid).clone())),
                Cow::Owned(Creases::default()),
            )))
        }
        _ => node_geometry(node, shape),
    }
}

/// What an export writes for one node, counted on the geometry the
/// writers write ([`export_geometry`]).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct WrittenCounts {
    /// Vertices: OBJ `v` lines of the node's mesh, surface or polyline.
    pub vertices: usize,
    /// Polygons as OBJ writes them (`f` lines; n-gons kept).
    pub faces: usize,
    /// Triangles as STL and glTF write them (every face triangulated).
    pub triangles: usize,
}

impl Geometry<'_> {
    /// The counts of what is written for this geometry.
    fn counts(&self) -> WrittenCounts {
        match self {
            Geometry::Refined(r) => r.counts(),
            Geometry::Mesh(m) => WrittenCounts {
                vertices: m.vertex_count(),
                faces: m.face_count(),
                triangles: m
                    .faces()
                    .map(|f| hedra_geom::query::triangulate_face(m, f).len())
                    .sum(),
            },
            Geometry::Triangles(p, _, t) => WrittenCounts {
                vertices: p.len(),
                faces: t.len(),
                triangles: t.len(),
            },
            Geometry::Polygons(k) => WrittenCounts {
                vertices: k.positions.len(),
                faces: k.faces.len(),
                triangles: k.triangles().len(),
            },
            Geometry::Polyline(p) => WrittenCounts {
                vertices: p.len(),
                ..WrittenCounts::default()
            },
            Geometry::FreeForm(c) => WrittenCounts {
                vertices: c.points().len(),
                ..WrittenCounts::default()
            },
        }
    }
}

/// What an export of `doc` in `shape` writes for node `id` when it is
/// visible: its vertices, OBJ faces and STL/glTF triangles, from the same
/// geometry the writers write. `hedra info` reports these (issue 31, item
/// 18: it counted the stack without the subdivision that comes before a
/// Decimate). `None` for a node that writes nothing (an empty, an
/// unknown id).
///
/// # Errors
/// As [`export_bytes`]: the node's shape cannot be evaluated.
pub fn written_counts(
    doc: &Document,
    id: crate::scene::NodeId,
    shape: ExportShape,
) -> Result<Option<WrittenCounts>, ExportError> {
    let Some(node) = doc.node(id) else {
        return Ok(None);
    };
    if let Some(refined) = refined_geometry(node, shape)? {
        return Ok(Some(refined.counts()));
    }
    Ok(export_geometry(doc, node, shape)?.map(|g| g.counts()))
}

/// What a node exports as, in its own (local) space: its mesh in the
/// requested shape, its surface tessellated, its curve as a polyline;
/// `None` for empties and CSG nodes ([`export_geometry`] evaluates those).
/// With the creases of what is written (a mesh's, after its modifiers and
/// subdivision; none for other content), so that smooth normals can be
/// split along infinitely sharp creases.
///
/// # Errors
/// [`ExportError::Evaluation`] naming the node when its modifier stack or
/// subdivision cannot be evaluated. [`ExportError::NotPolygon`] for a mesh
/// with a face with rings or without edges.
pub(crate) fn node_geometry(
    node: &Node,
    shape: ExportShape,
) -> Result<Option<(Geometry<'_>, Cow<'_, Creases>)>, ExportError> {
    let no_creases = || Cow::Owned(Creases::default());
    Ok(Some(match &node.content {
        // Evaluated with the document by `export_meshes`.
        NodeContent::Empty | NodeContent::Csg(_) => return Ok(None),
        NodeContent::Mesh(content) => {
            if let Some(face) = content.mesh.first_non_polygon_face() {
                return Err(ExportError::NotPolygon {
                    node: node.name.clone(),
                    face,
                });
            }
            let level = match shape {
                ExportShape::Cage => {
                    return Ok(Some((
                        Geometry::Mesh(Cow::Borrowed(&content.mesh)),
                        Cow::Borrowed(&content.creases),
                    )));
                }
                ExportShape::Evaluated => content.subdivision.map_or(0, |m| m.export_level),
                ExportShape::Subdivided(level) => level,
            };
            // The stack modifiers, then (or among them) subdivision at `level`.
            let evaluated = content
                .evaluate(level)
                .map_err(|error| ExportError::Evaluation {
                    node: node.name.clone(),
                    error,
                })?;
            (Geometry::Mesh(evaluated.mesh), evaluated.creases)
        }
        NodeContent::Kept(content) => {
            let level = match shape {
                ExportShape::Cage => 0,
                ExportShape::Evaluated => content.subdivision.map_or(0, |m| m.export_level),
                ExportShape::Subdivided(level) => level,
            };
            let shape = content
                .at_level(level)
                .map_err(|error| ExportError::Evaluation {
                    node: node.name.clone(),
                    error: crate::EvaluationError::Subdivision(error),
                })?;
            (Geometry::Polygons(shape), no_creases())
        }
        NodeContent::Curve(c) => (Geometry::Polyline(curve_polyline(c.nurbs())), no_creases()),
        NodeContent::Surface(sf) => {
            let size = crate::render::extent(sf.control_points());
            let (positions, normals, tris) = sf.tessellate(EXPORT_TOLERANCE * size);
            let (positions, normals, tris) = welded(&positions, &normals, &tris, 1e-9 * size);
            (Geometry::Triangles(positions, normals, tris), no_creases())
        }
    }))
}

/// Points along a curve for a polyline, within [`EXPORT_TOLERANCE`] of
/// its size.
pub(crate) fn curve_polyline(c: &hedra_geom::NurbsCurve) -> Vec<DVec3> {
    use hedra_geom::curves::Curve;
    let size = crate::render::extent(c.points());
    let params = hedra_geom::surfaces::tessellate::curve_parameters(c, EXPORT_TOLERANCE * size);
    params.iter().map(|&t| c.point(t)).collect()
}

/// A tessellation with coincident points merged (within `tolerance`: a
/// closed surface's seam, a sphere's pole) and the triangles that collapse
/// left out, so that other programs see it closed and without zero-area
/// triangles.
fn welded(
    positions: &[DVec3],
    normals: &[DVec3],
    triangles: &[[u32; 3]],
    tolerance: f64,
) -> (Vec<DVec3>, Vec<DVec3>, Vec<[u32; 3]>) {
    let cell = |p: DVec3| (p / tolerance).round().as_i64vec3().to_array();
    let mut index: HashMap<[i64; 3], u32> = HashMap::new();
    let (mut ps, mut ns) = (Vec::new(), Vec::new());
    let remap: Vec<u32> = positions
        .iter()
        .enumerate()
        .map(|(i, p)| {
            *index.entry(cell(*p)).or_insert_with(|| {
                ps.push(*p);
                ns.push(normals.get(i).copied().unwrap_or(DVec3::ZERO));
                (ps.len() - 1) as u32
            })
        })
        .collect();
    let tris = triangles
        .iter()
        .map(|t| t.map(|i| remap[i as usize]))
        .filter(|[a, b, c]| a != b && b != c && a != c)
        .collect();
    (ps, ns, tris)
}

/// True when the node and every ancestor are visible (false for an
/// unknown id).
///
/// Complexity: O(depth); for many nodes use [`Document::hierarchy`].
pub fn is_visible(doc: &Document, id: crate::scene::NodeId) -> bool {
    let mut cur = Some(id);
    let mut guard = doc.node_count() + 1;
    while let (Some(c), true) = (cur, guard > 0) {
        guard -= 1;
        match doc.node(c) {
            Some(n) if n.visible => cur = n.parent,
            _ => return false,
        }
    }
    true
}

mod obj;
mod pieces;
mod refined;
#[cfg(test)]
mod tests;

use obj::{Numbers, obj_face_line, obj_vertex_line, write_obj};
pub(crate) use pieces::write_pieces_in_order;
pub(crate) use refined::{FACES_PER_PIECE, RefinedFaces, VERTICES_PER_PIECE, refined_geometry};
