//! OBJ import: the pre-pass that tells objects from groups, the checks
//! that name a bad line, and the meshes read through tobj.

use super::obj_curves::{obj_curves, without_polylines};
use super::repairs::{FaceNumbers, why_nothing_kept};
use super::{ImportError, ImportedMesh, corner_attributes};
use glam::{DVec2, DVec3};
use hedra_geom::HalfEdgeMesh;
use std::collections::HashMap;

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
        }
        .with_input(&positions, &polygons);
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

/// OBJ text from a file's bytes: UTF-8 (invalid bytes replaced), or UTF-16
/// when the file starts with a UTF-16 byte-order mark (some Windows tools
/// write OBJ so).
pub(super) fn obj_text(bytes: &[u8]) -> String {
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
