//! Reading meshes from other formats into the scene. OBJ: every object or
//! group becomes a mesh node, polygons are kept, `vt` UVs and `vn` normals
//! become corner attributes, polylines (`l`) are left out with a note; STL
//! (binary, or ASCII with any number of `solid` blocks, one node each):
//! triangles with equal corners welded. Faces that cannot join a
//! manifold half-edge mesh are dropped or split off (with a report); the
//! corners of the faces that are kept keep their attributes.
//!
//! OBJ objects and groups: `o` and `g` both start a new node (tobj reads
//! them alike; a pre-pass over the text tells them apart). A file with only
//! `o` or only `g` gives one top-level mesh node per object or group. When
//! an object holds groups, the object becomes a parent node (an empty, or a
//! mesh of its faces outside any group) and each group a child mesh node.
//! A group name that appears again later gives another node.
//!
//! OBJ free-form curves (`cstype [rat] bspline` or `bezier`, `deg`, `curv`,
//! `parm u`, `end`, with weights from `v x y z w`) become NURBS curve
//! nodes, named after the object or group they are in, trimmed to their
//! `curv` range; other free-form types (Cardinal, Taylor, basis-matrix
//! curves, surfaces, trimming curves) are left out with a note.

use crate::history::{NodeChange, Transaction};
use crate::scene::{
    CornerAttributes, Document, MeshContent, Node, NodeContent, NodeId, NodeTransform,
};
use glam::{DVec2, DVec3};
use hedra_geom::{HalfEdgeMesh, RepairReport};
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// A node read from a file: its mesh (none for a grouping node) with what
/// had to be repaired, its parent among the imported nodes, its transform.
#[derive(Debug)]
pub struct ImportedMesh {
    /// The node's name: the file's object, group or node name, else one made
    /// up from the file (its stem, "Node 3").
    pub name: String,
    /// The mesh in the node's local space; `None` for a grouping node (or when
    /// repair dropped every face).
    pub mesh: Option<HalfEdgeMesh>,
    /// What repair dropped or split to make the mesh manifold.
    pub report: RepairReport,
    /// Index of the parent in the same import list.
    pub parent: Option<usize>,
    /// The local transform relative to the parent (identity for OBJ and STL).
    pub transform: NodeTransform,
    /// Primitives that are not triangles (points, lines) and were left out.
    pub skipped_primitives: usize,
    /// OBJ polylines (`l`) left out (Hedra imports faces).
    pub skipped_polylines: usize,
    /// How the report's face numbers are shown (as the file counts them).
    pub face_numbers: FaceNumbers,
    /// What the file has that Hedra does not import ("2 material(s)"), on
    /// the first node of an import.
    pub not_imported: Vec<String>,
    /// The file's number of each input vertex (OBJ `v` lines, from 1), for
    /// the report; empty when the file numbers vertices no other way.
    pub vertex_numbers: Vec<u32>,
    /// UVs and normals of the mesh's face corners that the file gave.
    pub corners: CornerAttributes,
    /// A curve read from the file (an OBJ free-form B-spline or Bézier
    /// curve): the node is a curve node, `mesh` is `None`.
    pub curve: Option<hedra_geom::NurbsCurve>,
    /// The node's whole content as a richer format reads it (USD: a mesh
    /// with its subdivision modifier and creases, a NURBS surface or
    /// curve; STEP: a B-spline surface or curve). When set it is used as
    /// it is and `mesh`, `corners` and `curve` are not read.
    pub content: Option<NodeContent>,
    /// The file hides the node (USD `visibility = "invisible"`).
    pub hidden: bool,
}

impl ImportedMesh {
    /// A top-level mesh node.
    fn mesh(name: String, mesh: HalfEdgeMesh, report: RepairReport) -> Self {
        ImportedMesh {
            name,
            mesh: Some(mesh),
            report,
            parent: None,
            transform: NodeTransform::IDENTITY,
            skipped_primitives: 0,
            skipped_polylines: 0,
            face_numbers: FaceNumbers::InNode,
            not_imported: Vec::new(),
            vertex_numbers: Vec::new(),
            corners: CornerAttributes::default(),
            curve: None,
            content: None,
            hidden: false,
        }
    }

    /// A top-level grouping node without a mesh (the base that other
    /// importers fill in with `..ImportedMesh::empty(name)`).
    pub(crate) fn empty(name: String) -> Self {
        ImportedMesh {
            name,
            mesh: None,
            report: RepairReport::default(),
            parent: None,
            transform: NodeTransform::IDENTITY,
            skipped_primitives: 0,
            skipped_polylines: 0,
            face_numbers: FaceNumbers::InNode,
            not_imported: Vec::new(),
            vertex_numbers: Vec::new(),
            corners: CornerAttributes::default(),
            curve: None,
            content: None,
            hidden: false,
        }
    }
}

/// The corner attributes of a mesh built by
/// [`HalfEdgeMesh::from_polygons_repaired`] (and maybe compacted): `uvs`
/// and `normals` hold one entry per input corner, polygon after polygon
/// (`arities` gives the polygon sizes), `None` where the file gave none;
/// either may be empty. Kept face `k` came from input polygon
/// `report.face_origin[k]`, and its loop starts at that polygon's first
/// corner. Non-finite values and zero normals are left out; normals are
/// stored normalised and rounded ([`stored_normal`]).
pub(crate) fn corner_attributes(
    mesh: &HalfEdgeMesh,
    report: &RepairReport,
    arities: &[usize],
    uvs: &[Option<DVec2>],
    normals: &[Option<DVec3>],
) -> CornerAttributes {
    let mut out = CornerAttributes::default();
    if uvs.is_empty() && normals.is_empty() {
        return out;
    }
    let starts: Vec<usize> = arities
        .iter()
        .scan(0usize, |acc, &a| {
            let s = *acc;
            *acc += a;
            Some(s)
        })
        .collect();
    for (k, f) in mesh.faces().enumerate() {
        let Some(&origin) = report.face_origin.get(k) else {
            break;
        };
        let (Some(&start), Some(&arity)) = (starts.get(origin), arities.get(origin)) else {
            continue;
        };
        if mesh.face_degree(f) != arity {
            continue;
        }
        for (i, h) in mesh.face_halfedges(f).enumerate() {
            if let Some(Some(uv)) = uvs.get(start + i)
                && uv.is_finite()
            {
                Arc::make_mut(&mut out.uvs).insert(h, *uv);
            }
            if let Some(Some(n)) = normals.get(start + i)
                && let Some(n) = n.try_normalize()
            {
                Arc::make_mut(&mut out.normals).insert(h, stored_normal(n));
            }
        }
    }
    out
}

/// Decimal places a stored normal keeps ([`stored_normal`]).
pub const NORMAL_DECIMALS: i32 = 7;

/// A unit normal as a scene keeps it: each component rounded to
/// [`NORMAL_DECIMALS`] places (within 5e-8, finer than the f32 the
/// viewport and glTF use), so that files store at most 10 characters per
/// component instead of the 17 digits of a normalised f64 (issue 31:
/// assimp's ClearCoatTest.gltf, 111,348 normal corners, saves in 8.8 MB
/// instead of 11.9 MB).
pub fn stored_normal(n: DVec3) -> DVec3 {
    let scale = 10f64.powi(NORMAL_DECIMALS);
    // `+ 0.0` turns -0 into 0.
    (n * scale).round() / scale + DVec3::ZERO
}

/// The faces of one model as tobj returns it, seen in the OBJ text: the
/// object (`o`, counted from 1 so that repeated names stay apart) and group
/// (`g`) it lies in, and for each corner whether it names a `vt` and a `vn`
/// (tobj makes up missing ones from a neighbour).
struct ObjSegment {
    object: Option<(usize, String)>,
    group: Option<String>,
    corners: Vec<(bool, bool)>,
    /// The line of each face (`f`), 1-based.
    face_lines: Vec<u32>,
    /// The file's (1-based, absolute) vertex number of each corner.
    corner_vertices: Vec<u32>,
}

/// Splits OBJ text the way tobj splits it into models: a new model at each
/// `o` or `g` line after some faces, and always one at the end.
fn scan_obj(text: &str) -> Vec<ObjSegment> {
    let mut out = Vec::new();
    let mut objects = 0usize;
    let mut current = ObjSegment {
        object: None,
        group: None,
        corners: Vec::new(),
        face_lines: Vec::new(),
        corner_vertices: Vec::new(),
    };
    let mut has_faces = false;
    let mut vertices_seen = 0i64;
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some(key @ ("o" | "g")) => {
                if has_faces {
                    let next = ObjSegment {
                        object: current.object.clone(),
                        group: current.group.clone(),
                        corners: Vec::new(),
                        face_lines: Vec::new(),
                        corner_vertices: Vec::new(),
                    };
                    out.push(std::mem::replace(&mut current, next));
                    has_faces = false;
                }
                // The keyword is one ASCII letter.
                let name = line.trim_start()[1..].trim();
                let name = (!name.is_empty()).then(|| name.to_string());
                if key == "o" {
                    objects += 1;
                    current.object = name.map(|n| (objects, n));
                    current.group = None;
                } else {
                    current.group = name;
                }
            }
            Some("v") => vertices_seen += 1,
            Some("f") => {
                has_faces = true;
                current.face_lines.push(number as u32 + 1);
                for w in words {
                    let mut parts = w.split('/');
                    // Negative numbers count back from the line.
                    let v = parts
                        .next()
                        .and_then(|x| x.parse::<i64>().ok())
                        .unwrap_or(0);
                    let v = if v < 0 { vertices_seen + v + 1 } else { v };
                    current.corner_vertices.push(v.max(0) as u32);
                    let vt = parts.next().is_some_and(|x| !x.is_empty());
                    let vn = parts.next().is_some_and(|x| !x.is_empty());
                    current.corners.push((vt, vn));
                }
            }
            _ => {}
        }
    }
    out.push(current);
    out
}

/// Why a file could not be imported.
#[derive(Debug, thiserror::Error)]
pub enum ImportError {
    /// The file cannot be read or parsed; the message says where and why.
    #[error("{path}: {message}")]
    Read {
        /// The file, as the caller named it.
        path: String,
        /// What went wrong, naming the line, object or buffer where known.
        message: String,
    },
    /// An extension Hedra does not import.
    #[error(
        "{path}: unsupported format '.{ext}' (supported: {})",
        supported_imports()
    )]
    Unsupported {
        /// The file, as the caller named it.
        path: String,
        /// The extension, without the dot.
        ext: String,
    },
    #[error(
        "{path}: the file name has no extension to tell its format (supported: {})",
        supported_imports()
    )]
    /// A file name without an extension.
    NoExtension {
        /// The file, as the caller named it.
        path: String,
    },
    /// A readable file with no faces (or, for glTF, no nodes).
    #[error("{path}: contains no faces")]
    Empty {
        /// The file, as the caller named it.
        path: String,
    },
    /// Every face was dropped: the first object's repair report says why.
    #[error("{path}: no face could be kept: {reason}")]
    NothingLeft {
        /// The file, as the caller named it.
        path: String,
        /// The first dropped object's repair report, as a sentence.
        reason: String,
    },
    /// A malformed OBJ line, found before the OBJ reader runs.
    #[error("{path}: {error}")]
    Obj {
        /// The file, as the caller named it.
        path: String,
        /// What is wrong, and on which line.
        error: ObjError,
    },
    /// A malformed STL triangle.
    #[error("{path}: {error}")]
    Stl {
        /// The file, as the caller named it.
        path: String,
        /// What is wrong, and in which triangle (and line, for ASCII).
        error: StlError,
    },
    /// A glTF file whose data would be read out of bounds or in a layout
    /// Hedra does not read.
    #[error("{path}: {error}")]
    Gltf {
        /// The file, as the caller named it.
        path: String,
        /// What is wrong, naming the mesh, accessor or buffer view (boxed:
        /// it is large and rare).
        error: Box<crate::gltf::GltfError>,
    },
}

/// The kinds of element an OBJ file lists, which faces refer to by number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ObjElement {
    /// A `v` line.
    Vertex,
    /// A `vt` line.
    TextureCoordinate,
    /// A `vn` line.
    Normal,
}

impl ObjElement {
    /// The order faces name them in (`v/vt/vn`).
    const ALL: [ObjElement; 3] = [
        ObjElement::Vertex,
        ObjElement::TextureCoordinate,
        ObjElement::Normal,
    ];

    /// The singular name used in messages ("texture coordinate").
    pub fn one(self) -> &'static str {
        match self {
            ObjElement::Vertex => "vertex",
            ObjElement::TextureCoordinate => "texture coordinate",
            ObjElement::Normal => "normal",
        }
    }

    /// The plural name used in messages ("texture coordinates").
    pub fn many(self) -> &'static str {
        match self {
            ObjElement::Vertex => "vertices",
            ObjElement::TextureCoordinate => "texture coordinates",
            ObjElement::Normal => "normals",
        }
    }
}

/// A malformed line of an OBJ file. Lines count from 1.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ObjError {
    /// A `v` line without three numbers for x, y and z.
    #[error("line {line}: a vertex needs three numbers, found '{found}'")]
    VertexNumbers {
        /// The line of the vertex.
        line: usize,
        /// The words after `v`, joined by spaces.
        found: String,
    },
    /// A vertex coordinate that is infinite or NaN (`nan`, `inf`, `1e999`).
    #[error("line {line}: vertex coordinate '{value}' is not a finite number")]
    NonFiniteCoordinate {
        /// The line of the vertex.
        line: usize,
        /// The coordinate as written.
        value: String,
    },
    /// A vertex whose coordinates become infinite when divided by its `w`.
    #[error("line {line}: vertex ({x}, {y}, {z}) divided by w = {w} is not a finite number")]
    NonFiniteDivided {
        /// The line of the vertex.
        line: usize,
        /// The x coordinate as read.
        x: f64,
        /// The y coordinate as read.
        y: f64,
        /// The z coordinate as read.
        z: f64,
        /// The (non-zero) weight.
        w: f64,
    },
    /// A `vt` line without its u and v, or a `vn` line without x, y and z.
    #[error("line {line}: a {} needs {needs} number(s), found '{found}'", .element.one())]
    AttributeNumbers {
        /// The line of the `vt` or `vn`.
        line: usize,
        /// [`ObjElement::TextureCoordinate`] or [`ObjElement::Normal`].
        element: ObjElement,
        /// How many numbers that element needs (1 or 3).
        needs: usize,
        /// The words after the keyword, joined by spaces.
        found: String,
    },
    /// A vertex's w that does not parse.
    #[error("line {line}: {} value '{value}' is not a number", .element.one())]
    NotANumber {
        /// The line of the element.
        line: usize,
        /// Which element it is.
        element: ObjElement,
        /// The word as written.
        value: String,
    },
    /// A `v` line with other than x y z, x y z w or x y z r g b (a comment
    /// after the numbers, say).
    #[error("line {line}: a vertex is x y z, x y z w or x y z r g b, found '{found}'")]
    VertexExtras {
        /// The line of the vertex.
        line: usize,
        /// The words after `v`, joined by spaces.
        found: String,
    },
    /// A face or polyline corner that is not `v`, `v/vt`, `v//vn` or
    /// `v/vt/vn` with whole numbers (`x`, `/1/1`, `1/a`).
    #[error("line {line}: {kind} corner '{corner}' {problem}")]
    BadCorner {
        /// The line of the face or polyline.
        line: usize,
        /// `"face"` or `"polyline"`.
        kind: &'static str,
        /// The corner as written.
        corner: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A negative (relative) index reaching back before the first element.
    #[error(
        "line {line}: face refers to {} {index}, but only {before} {} come before it",
        .element.one(),
        .element.many()
    )]
    BeforeFirst {
        /// The line of the face (or polyline).
        line: usize,
        /// The kind of element the index counts.
        element: ObjElement,
        /// The index as written (negative).
        index: i64,
        /// How many such elements come before the line.
        before: usize,
    },
    /// Index 0, which OBJ does not use.
    #[error("line {line}: face refers to {} 0 (OBJ counts from 1)", .element.one())]
    ZeroIndex {
        /// The line of the face (or polyline).
        line: usize,
        /// The kind of element the index counts.
        element: ObjElement,
    },
    /// A free-form curve record that cannot make a curve (a missing `deg`
    /// or `parm`, knots that do not fit the points, a weight that is not
    /// positive, a `curv` range outside the knots).
    #[error("line {line}: free-form curve: {reason}")]
    FreeFormCurve {
        /// The line of its `curv` statement.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// A positive index past the elements the whole file has.
    #[error(
        "line {line}: face refers to {} {index}, but the file has {total} {}",
        .element.one(),
        .element.many()
    )]
    PastLast {
        /// The line of the face (or polyline).
        line: usize,
        /// The kind of element the index counts.
        element: ObjElement,
        /// The index as written.
        index: i64,
        /// How many such elements the file has.
        total: usize,
    },
}

/// A malformed STL triangle. Triangles count from 1 over the whole file,
/// lines (ASCII STL only) from 1.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StlError {
    /// An ASCII `vertex` line without three numbers.
    #[error("line {line}, triangle {triangle}: a vertex needs three numbers, found '{found}'")]
    VertexNumbers {
        /// The line of the vertex.
        line: usize,
        /// The facet the vertex belongs to.
        triangle: usize,
        /// The words after `vertex`, joined by spaces.
        found: String,
    },
    /// An ASCII vertex coordinate that is not finite as a 32-bit float
    /// (STL's precision).
    #[error("line {line}, triangle {triangle}: vertex coordinate '{value}' is not finite")]
    NonFiniteCoordinate {
        /// The line of the vertex.
        line: usize,
        /// The facet the vertex belongs to.
        triangle: usize,
        /// The coordinate as written.
        value: String,
    },
    /// An ASCII `vertex` line before any `facet`.
    #[error("line {line}: a vertex outside any facet")]
    VertexOutsideFacet {
        /// The line of the vertex.
        line: usize,
    },
    /// An ASCII `endfacet` after other than three vertices.
    #[error("line {line}, triangle {triangle}: a facet needs three vertices, found {found}")]
    FacetCorners {
        /// The line of the `endfacet`.
        line: usize,
        /// The facet.
        triangle: usize,
        /// How many vertices it has.
        found: usize,
    },
    /// A binary STL triangle with an infinite or NaN corner.
    #[error(
        "triangle {triangle} has a corner that is not finite: ({}, {}, {})",
        .corner.x,
        .corner.y,
        .corner.z
    )]
    NonFiniteCorner {
        /// The triangle.
        triangle: usize,
        /// The first corner that is not finite, as read.
        corner: DVec3,
    },
}

/// Checks what tobj does not report by line: a vertex coordinate that is
/// not a finite number (`nan`, `inf`, `1e999`, or made infinite by its `w`),
/// and a face or line index (`v`, `vt` or `vn`) outside the elements the
/// file has. Positive indices count over the whole file, negative ones back
/// from the line. Messages name the line.
fn check_obj_text(text: &str) -> Result<(), ObjError> {
    let mut totals = [0usize; 3];
    for line in text.lines() {
        match line.split_whitespace().next() {
            Some("v") => totals[0] += 1,
            Some("vt") => totals[1] += 1,
            Some("vn") => totals[2] += 1,
            _ => {}
        }
    }
    let mut seen = [0usize; 3];
    for (number, line) in text.lines().enumerate() {
        let number = number + 1;
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                seen[0] += 1;
                let values: Vec<&str> = words.collect();
                let parsed: Vec<Option<f64>> = values.iter().map(|w| w.parse().ok()).collect();
                if parsed.len() < 3 || parsed[..3].contains(&None) {
                    return Err(ObjError::VertexNumbers {
                        line: number,
                        found: values.join(" "),
                    });
                }
                if let Some(bad) =
                    (0..values.len().min(3)).find(|&k| parsed[k].is_some_and(|x| !x.is_finite()))
                {
                    return Err(ObjError::NonFiniteCoordinate {
                        line: number,
                        value: values[bad].to_string(),
                    });
                }
                // After x y z: nothing, a w, or an r g b colour (what tobj reads).
                match values.len() {
                    4 if parsed[3].is_none() => {
                        return Err(ObjError::NotANumber {
                            line: number,
                            element: ObjElement::Vertex,
                            value: values[3].to_string(),
                        });
                    }
                    3 | 4 | 6 => {}
                    _ => {
                        return Err(ObjError::VertexExtras {
                            line: number,
                            found: values.join(" "),
                        });
                    }
                }
                if let [Some(x), Some(y), Some(z), Some(w)] = parsed[..]
                    && w != 0.0
                    && [x, y, z].iter().any(|c| !(c / w).is_finite())
                {
                    return Err(ObjError::NonFiniteDivided {
                        line: number,
                        x,
                        y,
                        z,
                        w,
                    });
                }
            }
            Some(key @ ("vt" | "vn")) => {
                // tobj reads a vt's u and v (so both are needed), a vn's x y z,
                // and ignores what follows.
                let (k, needs) = if key == "vt" { (1, 2) } else { (2, 3) };
                seen[k] += 1;
                let values: Vec<&str> = words.collect();
                if values.len() < needs || values[..needs].iter().any(|w| w.parse::<f64>().is_err())
                {
                    return Err(ObjError::AttributeNumbers {
                        line: number,
                        element: ObjElement::ALL[k],
                        needs,
                        found: values.join(" "),
                    });
                }
            }
            Some(key @ ("f" | "l")) => {
                let kind = if key == "f" { "face" } else { "polyline" };
                for word in words {
                    let parts: Vec<&str> = word.split('/').collect();
                    let problem = if parts.len() == 1 && word.parse::<i64>().is_err() {
                        Some("is not a vertex number".to_string())
                    } else if parts.len() > 3 {
                        Some("has more than three numbers (v/vt/vn)".to_string())
                    } else if parts[0].is_empty() {
                        Some(
                            "has no vertex number (a corner is v, v/vt, v//vn or v/vt/vn)"
                                .to_string(),
                        )
                    } else {
                        parts.iter().enumerate().find_map(|(k, part)| {
                            (!(k > 0 && part.is_empty()) && part.parse::<i64>().is_err()).then(
                                || {
                                    format!(
                                        "has {} '{part}', which is not a whole number",
                                        ObjElement::ALL[k].one()
                                    )
                                },
                            )
                        })
                    };
                    if let Some(problem) = problem {
                        return Err(ObjError::BadCorner {
                            line: number,
                            kind,
                            corner: word.to_string(),
                            problem,
                        });
                    }
                    for (k, part) in parts.iter().enumerate() {
                        let Ok(i) = part.parse::<i64>() else {
                            continue;
                        };
                        let fits = if i < 0 {
                            i.unsigned_abs() <= seen[k] as u64
                        } else {
                            i >= 1 && i as u64 <= totals[k] as u64
                        };
                        if !fits {
                            let (line, element) = (number, ObjElement::ALL[k]);
                            return Err(if i < 0 {
                                ObjError::BeforeFirst {
                                    line,
                                    element,
                                    index: i,
                                    before: seen[k],
                                }
                            } else if i == 0 {
                                ObjError::ZeroIndex { line, element }
                            } else {
                                ObjError::PastLast {
                                    line,
                                    element,
                                    index: i,
                                    total: totals[k],
                                }
                            });
                        }
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Parses OBJ text. `path` only names the file in messages.
///
/// # Errors
/// [`ImportError::Read`] when the OBJ is malformed, [`ImportError::Empty`]
/// when nothing usable remains.
pub fn obj_from_str(text: &str, path: &str) -> Result<Vec<ImportedMesh>, ImportError> {
    // Lines may end in CR alone (classic Mac OS): made LF, so that lines are
    // counted and read as the file shows them (tobj would read the whole
    // file as one line).
    let unified;
    let text = if text.contains('\r') {
        unified = text.replace("\r\n", "\n").replace('\r', "\n");
        unified.as_str()
    } else {
        text
    };
    check_obj_text(text).map_err(|error| ImportError::Obj {
        path: path.to_string(),
        error,
    })?;
    let (curves, skipped_free_form) = obj_curves(text).map_err(|error| ImportError::Obj {
        path: path.to_string(),
        error,
    })?;
    let (cleaned, polylines) = without_polylines(text);
    let text = cleaned.as_str();
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ..Default::default()
    };
    let mut reader = std::io::BufReader::new(text.as_bytes());
    let (models, _) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| ImportError::Read {
        path: path.to_string(),
        message: format!("not a readable OBJ file ({e})"),
    })?;
    // The o/g structure and which corners really name a vt or vn, when the
    // pre-pass saw the same models and corners as tobj (else tobj's names).
    let segments = scan_obj(text);
    let aligned = segments.len() == models.len()
        && segments
            .iter()
            .zip(&models)
            .all(|(s, m)| s.corners.len() == m.mesh.indices.len());
    let mut out: Vec<ImportedMesh> = Vec::new();
    let mut nothing_kept: Option<String> = None;
    // Object number -> index of its node in `out`.
    let mut object_nodes: HashMap<usize, usize> = HashMap::new();
    for (i, model) in models.into_iter().enumerate() {
        let m = model.mesh;
        let segment = segments.get(i).filter(|_| aligned);
        let positions: Vec<DVec3> = m
            .positions
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0], c[1], c[2]))
            .collect();
        let arities: Vec<u32> = if m.face_arities.is_empty() {
            vec![3; m.indices.len() / 3]
        } else {
            m.face_arities.clone()
        };
        let mut polygons = Vec::with_capacity(arities.len());
        let mut at = 0usize;
        for a in arities {
            let end = (at + a as usize).min(m.indices.len());
            polygons.push(m.indices[at..end].to_vec());
            at = end;
        }
        if polygons.is_empty() {
            continue;
        }
        let (mesh, report) =
            HalfEdgeMesh::from_polygons_repaired(&positions, &polygons).map_err(|e| {
                ImportError::Read {
                    path: path.to_string(),
                    message: format!("object {}: {e}", model.name),
                }
            })?;
        if mesh.face_count() == 0 {
            let name = if model.name.is_empty() || model.name == "unnamed_object" {
                ""
            } else {
                &model.name
            };
            let numbers = match segment {
                Some(s) if s.face_lines.len() == polygons.len() => {
                    FaceNumbers::Lines(s.face_lines.clone())
                }
                _ => FaceNumbers::InNode,
            };
            nothing_kept.get_or_insert_with(|| why_nothing_kept(name, &report, &numbers));
            continue;
        }
        let mesh = mesh.compacted_if_needed();
        // Per input corner: tobj's vt/vn, unless the text shows the corner has none.
        let present = |c: usize, which: fn(&(bool, bool)) -> bool| {
            segment.is_none_or(|s| s.corners.get(c).is_some_and(which))
        };
        let uvs: Vec<Option<DVec2>> = (0..m.texcoord_indices.len())
            .map(|c| {
                let t = m.texcoord_indices[c] as usize;
                let uv = DVec2::new(*m.texcoords.get(2 * t)?, *m.texcoords.get(2 * t + 1)?);
                present(c, |p| p.0).then_some(uv)
            })
            .collect();
        let normals: Vec<Option<DVec3>> = (0..m.normal_indices.len())
            .map(|c| {
                let n = m.normal_indices[c] as usize;
                let v = m.normals.get(3 * n..3 * n + 3)?;
                present(c, |p| p.1).then(|| DVec3::new(v[0], v[1], v[2]))
            })
            .collect();
        let arities: Vec<usize> = polygons.iter().map(Vec::len).collect();
        let corners = corner_attributes(&mesh, &report, &arities, &uvs, &normals);
        let fallback = || {
            if model.name.trim().is_empty() || model.name == "unnamed_object" {
                format!("Object {}", i + 1)
            } else {
                model.name.clone()
            }
        };
        let face_numbers = match segment {
            Some(s) if s.face_lines.len() == polygons.len() => {
                FaceNumbers::Lines(s.face_lines.clone())
            }
            _ => FaceNumbers::InNode,
        };
        // tobj numbers each model's vertices anew: map them back to the file's.
        let mut vertex_numbers = Vec::new();
        if let Some(seg) = segment.filter(|s| s.corner_vertices.len() == m.indices.len()) {
            vertex_numbers = vec![0u32; positions.len()];
            for (local, file) in m.indices.iter().zip(&seg.corner_vertices) {
                if let Some(slot) = vertex_numbers.get_mut(*local as usize) {
                    *slot = *file;
                }
            }
        }
        let mut imported = ImportedMesh {
            corners,
            face_numbers,
            vertex_numbers,
            ..ImportedMesh::mesh(String::new(), mesh, report)
        };
        match segment {
            // A group inside an object: a child of the object's node.
            Some(ObjSegment {
                object: Some((number, object)),
                group: Some(group),
                ..
            }) if group != object => {
                let parent = *object_nodes.entry(*number).or_insert_with(|| {
                    out.push(ImportedMesh::empty(object.clone()));
                    out.len() - 1
                });
                imported.name = group.clone();
                imported.parent = Some(parent);
                out.push(imported);
            }
            // An object's own faces (outside any group).
            Some(ObjSegment {
                object: Some((number, object)),
                ..
            }) => match object_nodes.get(number) {
                // Its node is still an empty made for its groups: fill it.
                Some(&node) if out[node].mesh.is_none() => {
                    imported.name = object.clone();
                    imported.parent = None;
                    out[node] = imported;
                }
                Some(&node) => {
                    imported.name = object.clone();
                    imported.parent = Some(node);
                    out.push(imported);
                }
                None => {
                    imported.name = object.clone();
                    object_nodes.insert(*number, out.len());
                    out.push(imported);
                }
            },
            Some(ObjSegment {
                group: Some(group), ..
            }) => {
                imported.name = group.clone();
                out.push(imported);
            }
            _ => {
                imported.name = fallback();
                out.push(imported);
            }
        }
    }
    for (k, c) in curves.into_iter().enumerate() {
        out.push(ImportedMesh {
            mesh: None,
            curve: Some(c.curve),
            ..ImportedMesh::empty(c.name.unwrap_or_else(|| format!("Curve {}", k + 1)))
        });
    }
    if out.is_empty() {
        let path = path.to_string();
        return Err(match (nothing_kept, polylines) {
            (Some(reason), _) => ImportError::NothingLeft { path, reason },
            (None, n) if n > 0 => ImportError::NothingLeft {
                path,
                reason: format!("it has {n} polyline(s) (`l`) and no faces; Hedra imports faces"),
            },
            (None, _) => ImportError::Empty { path },
        });
    }
    // The notes go on the first mesh, else on the first curve.
    let first = out
        .iter()
        .position(|m| m.mesh.is_some())
        .or_else(|| out.iter().position(|m| m.curve.is_some()));
    if let Some(first) = first.map(|i| &mut out[i]) {
        first.skipped_polylines = polylines;
        let materials = text
            .lines()
            .any(|l| matches!(l.split_whitespace().next(), Some("mtllib" | "usemtl")));
        if materials {
            first.not_imported = vec!["materials (mtllib, usemtl)".to_string()];
        }
        if skipped_free_form > 0 {
            first.not_imported.push(format!(
                "{skipped_free_form} free-form record(s) other than B-spline and Bézier curves"
            ));
        }
    }
    Ok(out)
}

/// A free-form curve read from OBJ text, with the object or group it is in.
struct ObjCurve {
    name: Option<String>,
    curve: hedra_geom::NurbsCurve,
}

/// The free-form state between `cstype` and `end`.
#[derive(Default)]
struct FreeForm {
    rational: bool,
    /// `bspline`, `bezier`, or another type (read, then left out).
    kind: String,
    degree: Option<usize>,
    /// The `curv` line: its number, range and vertex references.
    curv: Option<(usize, f64, f64, Vec<i64>)>,
    knots: Option<Vec<f64>>,
    /// A `surf`, `curv2` or another record Hedra does not read.
    other: bool,
}

/// Reads the free-form curves of OBJ text: B-spline and Bézier curves
/// (rational or not) become NURBS curves; a record of another type is
/// counted. Lines ending in `\` continue on the next. Vertices number
/// over the whole file, negative numbers back from the line.
///
/// # Errors
/// [`ObjError::FreeFormCurve`] naming the `curv` line and what is wrong.
fn obj_curves(text: &str) -> Result<(Vec<ObjCurve>, usize), ObjError> {
    let mut vertices: Vec<(DVec3, f64)> = Vec::new();
    let (mut object, mut group): (Option<String>, Option<String>) = (None, None);
    let mut state = FreeForm::default();
    let mut out = Vec::new();
    let mut skipped = 0usize;
    let mut joined = String::new();
    let mut first_line = 0usize;
    for (number, raw) in text.lines().enumerate() {
        if joined.is_empty() {
            first_line = number + 1;
        }
        if let Some(head) = raw.trim_end().strip_suffix('\\') {
            joined.push_str(head);
            joined.push(' ');
            continue;
        }
        joined.push_str(raw);
        let line = std::mem::take(&mut joined);
        let number = first_line;
        let mut words = line.split_whitespace();
        let bad = |reason: String| ObjError::FreeFormCurve {
            line: number,
            reason,
        };
        let numbers = |words: std::str::SplitWhitespace| -> Result<Vec<f64>, ObjError> {
            words
                .map(|w| {
                    w.parse::<f64>()
                        .ok()
                        .filter(|x| x.is_finite())
                        .ok_or_else(|| bad(format!("'{w}' is not a finite number")))
                })
                .collect()
        };
        match words.next() {
            Some("v") => {
                let v: Vec<f64> = words.filter_map(|w| w.parse().ok()).collect();
                if v.len() >= 3 {
                    let w = if v.len() == 4 { v[3] } else { 1.0 };
                    vertices.push((DVec3::new(v[0], v[1], v[2]), w));
                }
            }
            Some("o") => {
                object = Some(line.trim_start()[1..].trim().to_string()).filter(|n| !n.is_empty());
                group = None;
            }
            Some("g") => {
                group = Some(line.trim_start()[1..].trim().to_string()).filter(|n| !n.is_empty());
            }
            Some("cstype") => {
                let rest: Vec<&str> = words.collect();
                state = FreeForm {
                    rational: rest.first() == Some(&"rat"),
                    kind: rest.last().copied().unwrap_or("").to_string(),
                    ..FreeForm::default()
                };
            }
            Some("deg") => {
                let d = words.next().and_then(|w| w.parse::<usize>().ok());
                state.degree = Some(d.ok_or_else(|| bad("'deg' needs a whole number".into()))?);
            }
            Some("curv") => {
                let all: Vec<&str> = words.collect();
                if all.len() < 4 {
                    return Err(bad("'curv' needs a range and two or more vertices".into()));
                }
                let range = numbers(all[..2].join(" ").split_whitespace())?;
                let refs = all[2..]
                    .iter()
                    .map(|w| {
                        w.parse::<i64>()
                            .map_err(|_| bad(format!("'{w}' is not a vertex number")))
                    })
                    .collect::<Result<Vec<i64>, _>>()?;
                state.curv = Some((number, range[0], range[1], refs));
            }
            Some("parm") if words.next() == Some("u") => {
                state.knots = Some(numbers(words)?);
            }
            Some("surf" | "curv2") => state.other = true,
            Some("end") => {
                let done = std::mem::take(&mut state);
                let Some((line, u0, u1, refs)) = done.curv.clone() else {
                    if done.other {
                        skipped += 1;
                    }
                    continue;
                };
                if done.other || !matches!(done.kind.as_str(), "bspline" | "bezier") {
                    skipped += 1;
                    continue;
                }
                let curve = free_form_curve(&done, &vertices, u0, u1, &refs)
                    .map_err(|reason| ObjError::FreeFormCurve { line, reason })?;
                out.push(ObjCurve {
                    name: group.clone().or_else(|| object.clone()),
                    curve,
                });
            }
            _ => {}
        }
    }
    Ok((out, skipped))
}

/// The NURBS curve of one free-form record, trimmed to `[u0, u1]`.
fn free_form_curve(
    f: &FreeForm,
    vertices: &[(DVec3, f64)],
    u0: f64,
    u1: f64,
    refs: &[i64],
) -> Result<hedra_geom::NurbsCurve, String> {
    use hedra_geom::curves::Curve;
    let degree = f.degree.ok_or("no 'deg' before 'end'")?;
    // Checked here, before anything computes `degree + 1`.
    if degree == 0 || degree >= refs.len() {
        return Err(format!(
            "degree {degree} does not fit {} control points (degree 1 to {})",
            refs.len(),
            refs.len() - 1
        ));
    }
    let mut points = Vec::with_capacity(refs.len());
    let mut weights = Vec::with_capacity(refs.len());
    for &r in refs {
        let i = if r < 0 {
            vertices.len() as i64 + r
        } else {
            r - 1
        };
        let &(p, w) = usize::try_from(i)
            .ok()
            .and_then(|i| vertices.get(i))
            .ok_or_else(|| format!("vertex {r} does not exist ({} come before)", vertices.len()))?;
        points.push(p);
        weights.push(if f.rational { w } else { 1.0 });
    }
    let knots = match (f.kind.as_str(), &f.knots) {
        ("bspline", Some(k)) => k.clone(),
        ("bspline", None) => return Err("no 'parm u' knots".into()),
        // Bézier: segments of `degree` points sharing ends, breakpoints
        // from `parm u` (uniform when absent).
        _ => {
            if !(refs.len() - 1).is_multiple_of(degree) {
                return Err(format!(
                    "a degree {degree} Bézier curve needs {degree}k + 1 points, got {}",
                    refs.len()
                ));
            }
            let segments = (refs.len() - 1) / degree;
            let breaks = f
                .knots
                .clone()
                .unwrap_or_else(|| (0..=segments).map(|i| i as f64).collect());
            if breaks.len() != segments + 1 {
                return Err(format!(
                    "{segments} Bézier segment(s) need {} 'parm u' values, got {}",
                    segments + 1,
                    breaks.len()
                ));
            }
            let mut k = vec![breaks[0]; degree + 1];
            for &b in &breaks[1..segments] {
                k.extend(std::iter::repeat_n(b, degree));
            }
            k.extend(std::iter::repeat_n(breaks[segments], degree + 1));
            k
        }
    };
    let curve =
        hedra_geom::NurbsCurve::new(degree, knots, points, weights).map_err(|e| e.to_string())?;
    let (a, b) = curve.domain();
    if !(u0 >= a && u1 <= b && u0 < u1) {
        return Err(format!(
            "the range [{u0}, {u1}] is not inside the knots' domain [{a}, {b}]"
        ));
    }
    let mut curve = curve;
    if u1 < b {
        curve = curve.split(u1).map_err(|e| e.to_string())?.0;
    }
    if u0 > a {
        curve = curve.split(u0).map_err(|e| e.to_string())?.1;
    }
    Ok(curve)
}

/// OBJ text without what tobj would misread, line numbers kept: polylines
/// (`l`, which tobj returns as faces) and `usemtl` lines with no name (which
/// tobj refuses; Blender 2.61 writes them) become empty lines. Returns the
/// text and the number of polylines left out.
fn without_polylines(text: &str) -> (String, usize) {
    let mut polylines = 0;
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let mut words = line.split_whitespace();
        let drop = match words.next() {
            Some("l") => {
                polylines += 1;
                true
            }
            Some("usemtl") => words.next().is_none(),
            _ => false,
        };
        if drop {
            if line.ends_with('\n') {
                out.push('\n');
            }
        } else {
            out.push_str(line);
        }
    }
    (out, polylines)
}

/// One `solid … endsolid` block of an ASCII STL: its name and triangles.
struct AsciiSolid {
    name: String,
    triangles: Vec<[DVec3; 3]>,
}

/// True when `bytes` start (after white space) with `solid` in any case:
/// `solid name`, `solid<TAB>name`, `solid` alone, `SOLID`.
fn starts_like_ascii_stl(bytes: &[u8]) -> bool {
    bytes
        .trim_ascii_start()
        .get(..5)
        .is_some_and(|w| w.eq_ignore_ascii_case(b"solid"))
}

/// Reads an ASCII STL: every `solid` block, keywords in any case (`facet`,
/// `vertex`, `endfacet`, `endsolid`; `normal`, `outer loop` and `endloop`
/// are not needed). Messages name the line and the triangle.
fn parse_ascii_stl(text: &str) -> Result<Vec<AsciiSolid>, StlError> {
    let mut solids: Vec<AsciiSolid> = Vec::new();
    let mut corners: Option<Vec<DVec3>> = None;
    let mut triangle = 0usize;
    for (number, line) in text.lines().enumerate() {
        let number = number + 1;
        let line = line.trim();
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        match keyword.to_ascii_lowercase().as_str() {
            "solid" => solids.push(AsciiSolid {
                name: line[keyword.len()..].trim().to_string(),
                triangles: Vec::new(),
            }),
            "facet" => {
                triangle += 1;
                corners = Some(Vec::with_capacity(3));
            }
            "vertex" => {
                let values: Vec<&str> = words.collect();
                let parsed: Vec<f64> = values.iter().filter_map(|w| w.parse().ok()).collect();
                if values.len() != 3 || parsed.len() != 3 {
                    return Err(StlError::VertexNumbers {
                        line: number,
                        triangle,
                        found: values.join(" "),
                    });
                }
                if let Some(k) = (0..3).find(|&k| !(parsed[k] as f32).is_finite()) {
                    return Err(StlError::NonFiniteCoordinate {
                        line: number,
                        triangle,
                        value: values[k].to_string(),
                    });
                }
                let Some(c) = corners.as_mut() else {
                    return Err(StlError::VertexOutsideFacet { line: number });
                };
                c.push(DVec3::new(parsed[0], parsed[1], parsed[2]));
            }
            "endfacet" => {
                let c = corners.take().unwrap_or_default();
                let [a, b, c] = c[..] else {
                    return Err(StlError::FacetCorners {
                        line: number,
                        triangle,
                        found: c.len(),
                    });
                };
                if solids.is_empty() {
                    solids.push(AsciiSolid {
                        name: String::new(),
                        triangles: Vec::new(),
                    });
                }
                solids
                    .last_mut()
                    .expect("pushed above")
                    .triangles
                    .push([a, b, c]);
            }
            _ => {}
        }
    }
    Ok(solids)
}

/// Triangles with equal corners welded: positions and polygons.
fn weld(triangles: &[[DVec3; 3]]) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let mut index: HashMap<[u64; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let polygons = triangles
        .iter()
        .map(|t| {
            t.iter()
                .map(|p| {
                    let key = [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
                    *index.entry(key).or_insert_with(|| {
                        positions.push(*p);
                        (positions.len() - 1) as u32
                    })
                })
                .collect()
        })
        .collect();
    (positions, polygons)
}

/// Parses a binary or ASCII STL file. A binary file must be exactly as long
/// as its triangle count says (so a damaged header cannot ask for
/// gigabytes); an ASCII file gives one node per `solid` block, named after
/// it (`name`, the file's stem, when it has none); `path` names the file in
/// messages.
///
/// # Errors
/// [`ImportError::Read`] naming the problem, [`ImportError::Empty`] when no
/// triangle remains.
pub fn stl_from_bytes(
    bytes: &[u8],
    name: &str,
    path: &str,
) -> Result<Vec<ImportedMesh>, ImportError> {
    let read_error = |message: String| ImportError::Read {
        path: path.to_string(),
        message,
    };
    let stl_error = |error: StlError| ImportError::Stl {
        path: path.to_string(),
        error,
    };
    let binary_size = bytes
        .get(80..84)
        .map(|c| 84 + 50 * u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as u64);
    let is_binary = binary_size == Some(bytes.len() as u64);
    let is_ascii = !is_binary && starts_like_ascii_stl(bytes);
    if !is_binary && !is_ascii {
        return Err(read_error(format!(
            "not an STL file: not ASCII (no 'solid'), and {} bytes where a binary STL of its triangle count has {}",
            bytes.len(),
            binary_size.map_or("at least 84".to_string(), |n| n.to_string())
        )));
    }
    let solids = if is_ascii {
        let text = std::str::from_utf8(bytes)
            .map_err(|e| read_error(format!("an ASCII STL that is not UTF-8 text ({e})")))?;
        parse_ascii_stl(text).map_err(stl_error)?
    } else {
        vec![AsciiSolid {
            name: String::new(),
            triangles: binary_stl_triangles(bytes).map_err(stl_error)?,
        }]
    };
    let mut out = Vec::new();
    let mut dropped = Vec::new();
    let mut offset = 0;
    for solid in &solids {
        let first = offset;
        offset += solid.triangles.len();
        let (positions, polygons) = weld(&solid.triangles);
        let (mesh, report) = HalfEdgeMesh::from_polygons_repaired(&positions, &polygons)
            .map_err(|e| read_error(e.to_string()))?;
        let node_name = if solid.name.is_empty() {
            name.to_string()
        } else {
            solid.name.clone()
        };
        if mesh.face_count() == 0 {
            if !solid.triangles.is_empty() {
                dropped.push(why_nothing_kept(
                    &node_name,
                    &report,
                    &FaceNumbers::Triangles { offset: first },
                ));
            }
            continue;
        }
        out.push(ImportedMesh {
            face_numbers: FaceNumbers::Triangles { offset: first },
            ..ImportedMesh::mesh(node_name, mesh.compacted_if_needed(), report)
        });
    }
    if out.is_empty() {
        return Err(match dropped.first() {
            Some(reason) => ImportError::NothingLeft {
                path: path.to_string(),
                reason: reason.clone(),
            },
            None => ImportError::Empty {
                path: path.to_string(),
            },
        });
    }
    Ok(out)
}

/// The triangles of a binary STL (its length already checked), refusing
/// corners that are not finite.
fn binary_stl_triangles(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, StlError> {
    let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    let mut out = Vec::with_capacity(count);
    for t in 0..count {
        let record = &bytes[84 + 50 * t..84 + 50 * (t + 1)];
        let float = |k: usize| {
            let at = 12 + 4 * k;
            f32::from_le_bytes([record[at], record[at + 1], record[at + 2], record[at + 3]]) as f64
        };
        let corner = |c: usize| DVec3::new(float(3 * c), float(3 * c + 1), float(3 * c + 2));
        let tri = [corner(0), corner(1), corner(2)];
        if let Some(p) = tri.iter().find(|p| !p.is_finite()) {
            return Err(StlError::NonFiniteCorner {
                triangle: t + 1,
                corner: *p,
            });
        }
        out.push(tri);
    }
    Ok(out)
}

/// OBJ text from a file's bytes: UTF-8 (invalid bytes replaced), or UTF-16
/// when the file starts with a UTF-16 byte-order mark (some Windows tools
/// write OBJ so).
fn obj_text(bytes: &[u8]) -> String {
    let utf16 = |le: bool| {
        let units: Vec<u16> = bytes[2..]
            .chunks_exact(2)
            .map(|c| {
                if le {
                    u16::from_le_bytes([c[0], c[1]])
                } else {
                    u16::from_be_bytes([c[0], c[1]])
                }
            })
            .collect();
        String::from_utf16_lossy(&units)
    };
    match bytes {
        [0xFF, 0xFE, ..] => utf16(true),
        [0xFE, 0xFF, ..] => utf16(false),
        _ => String::from_utf8_lossy(bytes).into_owned(),
    }
}

/// The extensions [`import_file`] reads, in the order menus list them.
pub const IMPORT_FORMATS: &[&str] = &[
    "obj", "stl", "gltf", "glb", "usda", "usdc", "usdz", "usd", "step", "stp",
];

/// The import extensions as messages list them: `.obj, .stl, ...`.
pub fn supported_imports() -> String {
    IMPORT_FORMATS
        .iter()
        .map(|e| format!(".{e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Reads a file by its extension.
///
/// # Errors
/// As [`obj_from_str`], plus unreadable files and unknown extensions.
pub fn import_file(path: &Path) -> Result<Vec<ImportedMesh>, ImportError> {
    let shown = path.display().to_string();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "obj" => {
            let bytes = crate::input::read(path).map_err(|e| ImportError::Read {
                path: shown.clone(),
                message: e.to_string(),
            })?;
            obj_from_str(&obj_text(&bytes), &shown)
        }
        "stl" => {
            let bytes = crate::input::read(path).map_err(|e| ImportError::Read {
                path: shown.clone(),
                message: e.to_string(),
            })?;
            let name = path
                .file_stem()
                .map_or_else(|| "STL".to_string(), |s| s.to_string_lossy().into_owned());
            stl_from_bytes(&bytes, &name, &shown)
        }
        "step" | "stp" => {
            let bytes = crate::input::read(path).map_err(|e| ImportError::Read {
                path: shown.clone(),
                message: e.to_string(),
            })?;
            crate::step::step_from_bytes(&bytes, &shown)
        }
        "gltf" | "glb" => {
            let bytes = crate::input::read(path).map_err(|e| ImportError::Read {
                path: shown.clone(),
                message: e.to_string(),
            })?;
            crate::gltf::gltf_from_bytes(&bytes, path.parent(), &shown)
        }
        "usda" | "usdc" | "usdz" | "usd" => crate::usd::usd_from_path(path),
        "" => Err(ImportError::NoExtension { path: shown }),
        other => Err(ImportError::Unsupported {
            path: shown,
            ext: other.to_string(),
        }),
    }
}

/// How an importer's input face numbers are shown to the user: as the
/// file counts them.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum FaceNumbers {
    /// "face k" counting from 1 within the node (glTF triangles).
    #[default]
    InNode,
    /// "line n": the OBJ line of each input polygon.
    Lines(Vec<u32>),
    /// "triangle n": STL triangles counted over the whole file, this node's
    /// first being `offset + 1`; a glTF node's triangles (offset 0).
    Triangles {
        /// How many triangles of the file come before this node's.
        offset: usize,
    },
}

impl FaceNumbers {
    fn name(&self, face: usize) -> String {
        match self {
            FaceNumbers::InNode => format!("face {}", face + 1),
            FaceNumbers::Lines(lines) => match lines.get(face) {
                Some(line) => format!("line {line}"),
                None => format!("face {}", face + 1),
            },
            FaceNumbers::Triangles { offset } => format!("triangle {}", offset + face + 1),
        }
    }
}

/// Why a face was dropped, in words a user can act on, naming other faces
/// as the file numbers them.
fn dropped_reason(
    why: &hedra_geom::BuildError,
    numbers: &FaceNumbers,
    face: usize,
) -> (&'static str, String) {
    use hedra_geom::BuildError as E;
    let others = |faces: &[usize]| {
        faces
            .iter()
            .filter(|&&f| f != face)
            .map(|&f| numbers.name(f))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match why {
        E::TooFewSides { sides, .. } => (
            "fewer than 3 corners",
            format!("has {sides} corner(s); a face needs 3"),
        ),
        E::RepeatedVertex { .. } => (
            "a corner used twice",
            "uses the same corner point twice".into(),
        ),
        E::NonManifoldEdge { faces, .. } => (
            "a third face on an edge",
            format!(
                "would be a third face on an edge already shared by {}",
                others(faces)
            ),
        ),
        E::InconsistentOrientation { faces, .. } => (
            "winding against a neighbour",
            format!(
                "runs an edge the same way as {}: its winding disagrees",
                others(faces)
            ),
        ),
        E::NonFinitePosition { .. } => (
            "a corner that is not finite",
            "has a corner that is not a finite number".into(),
        ),
        E::IndexOutOfRange { .. } => (
            "a corner the file lacks",
            "refers to a vertex the file does not have".into(),
        ),
        E::NonManifoldVertex { .. } | E::TooLarge { .. } => ("other", why.to_string()),
    }
}

/// Why an object kept no face, in the words of the import summary: how
/// many were dropped and the first one's reason, numbered as the file does.
fn why_nothing_kept(name: &str, report: &RepairReport, numbers: &FaceNumbers) -> String {
    match report.dropped_faces.first() {
        Some((face, why)) => {
            let (_, text) = dropped_reason(why, numbers, *face);
            let whose = if name.is_empty() {
                String::new()
            } else {
                format!("{name}: ")
            };
            format!(
                "{whose}all {} face(s) dropped; {} {text}",
                report.dropped_faces.len(),
                numbers.name(*face)
            )
        }
        None => format!("{name}: {report}"),
    }
}

/// What an import repaired or left out, for the user: an empty list when
/// nothing was; else a one-line summary (counts by kind) followed by the
/// details, one per dropped face or split vertex with the file's own
/// numbers (OBJ lines, STL triangles), at most [`MAX_DETAILS`] of them.
pub fn describe_repairs(meshes: &[ImportedMesh]) -> Vec<String> {
    let mut kinds: std::collections::BTreeMap<&'static str, usize> = Default::default();
    let mut details = Vec::new();
    let (mut split, mut repaired) = (0usize, 0usize);
    for m in meshes {
        if !m.report.is_clean() {
            repaired += 1;
        }
        for (face, why) in &m.report.dropped_faces {
            let (kind, text) = dropped_reason(why, &m.face_numbers, *face);
            *kinds.entry(kind).or_default() += 1;
            details.push(format!(
                "{}: {} dropped: {text}",
                m.name,
                m.face_numbers.name(*face)
            ));
        }
        for (face, loops) in &m.report.split_faces {
            details.push(format!(
                "{}: {} visits a corner twice; split there into {loops} face(s)",
                m.name,
                m.face_numbers.name(*face)
            ));
        }
        for (vertex, copies) in &m.report.split_vertices {
            split += 1;
            let number = match m.vertex_numbers.get(*vertex as usize) {
                Some(&n) if n > 0 => n,
                _ => vertex + 1,
            };
            details.push(format!(
                "{}: vertex {number} joined separate fans of faces; split into {} copies",
                m.name,
                copies + 1
            ));
        }
    }
    let primitives: usize = meshes.iter().map(|m| m.skipped_primitives).sum();
    let polylines: usize = meshes.iter().map(|m| m.skipped_polylines).sum();
    let mut parts = Vec::new();
    let dropped: usize = kinds.values().sum();
    if dropped > 0 {
        let by_kind: Vec<String> = kinds.iter().map(|(k, n)| format!("{n} {k}")).collect();
        parts.push(format!(
            "{dropped} face(s) dropped ({})",
            by_kind.join(", ")
        ));
    }
    let pinched: usize = meshes.iter().map(|m| m.report.split_faces.len()).sum();
    if pinched > 0 {
        parts.push(format!(
            "{pinched} face(s) that visit a corner twice split into simple faces"
        ));
    }
    if split > 0 {
        parts.push(format!(
            "{split} vertex(es) split where separate fans of faces met"
        ));
    }
    if primitives > 0 {
        parts.push(format!("{primitives} point or line primitive(s) left out"));
    }
    if polylines > 0 {
        parts.push(format!(
            "{polylines} polyline(s) (`l`) left out: Hedra imports faces"
        ));
    }
    let not_imported: Vec<&str> = meshes
        .iter()
        .flat_map(|m| &m.not_imported)
        .map(String::as_str)
        .collect();
    if !not_imported.is_empty() {
        parts.push(format!("not imported: {}", not_imported.join(", ")));
    }
    if parts.is_empty() {
        return Vec::new();
    }
    let whom = if repaired > 0 {
        format!(
            "{repaired} of {} object(s) repaired: ",
            meshes.iter().filter(|m| m.mesh.is_some()).count()
        )
    } else {
        String::new()
    };
    let mut out = vec![format!("{whom}{}", parts.join("; "))];
    let more = details.len().saturating_sub(MAX_DETAILS);
    out.extend(
        details
            .into_iter()
            .take(MAX_DETAILS)
            .map(|d| format!("  {d}")),
    );
    if more > 0 {
        out.push(format!("  … and {more} more"));
    }
    out
}

/// Detail lines of [`describe_repairs`] at most.
pub const MAX_DETAILS: usize = 20;

impl Document {
    /// The transaction that adds imported nodes (with their hierarchy and
    /// transforms) to the scene.
    pub fn decide_import(&self, meshes: &[ImportedMesh], label: &str, serial: u64) -> Transaction {
        let mut next = self.next_node_id;
        let mut changes = Vec::new();
        let mut names: Vec<String> = Vec::new();
        for m in meshes {
            let mut name = self.unique_name(&m.name);
            let base = name.clone();
            let mut k = 1;
            while names.contains(&name) {
                name = format!("{base}.{k:03}");
                k += 1;
            }
            names.push(name.clone());
            let id = NodeId(next);
            next += 1;
            let parent = m
                .parent
                .and_then(|p| changes.get(p))
                .map(|c: &NodeChange| c.id);
            let node = Node {
                id,
                name,
                parent,
                transform: m.transform,
                visible: !m.hidden,
                content: match (&m.mesh, &m.curve) {
                    _ if m.content.is_some() => m.content.clone().unwrap_or(NodeContent::Empty),
                    (Some(mesh), _) => NodeContent::Mesh(MeshContent {
                        corners: m.corners.clone(),
                        ..MeshContent::new(Arc::new(mesh.clone()))
                    }),
                    (None, Some(curve)) => NodeContent::Curve(Arc::new(
                        crate::scene::CurveContent::from_nurbs(curve.clone()),
                    )),
                    (None, None) => NodeContent::Empty,
                },
                construction: None,
                g1_join: None,
            };
            changes.push(NodeChange {
                id,
                before: None,
                after: Some(node),
            });
        }
        Transaction {
            serial,
            label: label.to_string(),
            command: None,
            changes,
            next_id_before: self.next_node_id,
            next_id_after: next,
        }
    }
}
