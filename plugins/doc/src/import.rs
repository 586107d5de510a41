//! Reading meshes from other formats into the scene. OBJ: every object or
//! group becomes a mesh node, polygons are kept, `vt` UVs and `vn` normals
//! become corner attributes; STL (binary or ASCII, read by `stl_io`): one
//! node, triangles with equal corners welded. Faces that cannot join a
//! manifold half-edge mesh are dropped or split off (with a report); the
//! corners of the faces that are kept keep their attributes.
//!
//! OBJ objects and groups: `o` and `g` both start a new node (tobj reads
//! them alike; a pre-pass over the text tells them apart). A file with only
//! `o` or only `g` gives one top-level mesh node per object or group. When
//! an object holds groups, the object becomes a parent node (an empty, or a
//! mesh of its faces outside any group) and each group a child mesh node.
//! A group name that appears again later gives another node.

use crate::history::{NodeChange, Transaction};
use crate::scene::{CornerAttributes, Document, MeshContent, Node, NodeContent, NodeId, Transform};
use glam::{DVec2, DVec3};
use hedra_geom::{HalfEdgeMesh, RepairReport};
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// A node read from a file: its mesh (none for a grouping node) with what
/// had to be repaired, its parent among the imported nodes, its transform.
#[derive(Debug)]
pub struct ImportedMesh {
    pub name: String,
    pub mesh: Option<HalfEdgeMesh>,
    pub report: RepairReport,
    /// Index of the parent in the same import list.
    pub parent: Option<usize>,
    pub transform: Transform,
    /// Primitives that are not triangles (points, lines) and were left out.
    pub skipped_primitives: usize,
    /// UVs and normals of the mesh's face corners that the file gave.
    pub corners: CornerAttributes,
}

impl ImportedMesh {
    /// A top-level mesh node.
    fn mesh(name: String, mesh: HalfEdgeMesh, report: RepairReport) -> Self {
        ImportedMesh {
            name,
            mesh: Some(mesh),
            report,
            parent: None,
            transform: Transform::IDENTITY,
            skipped_primitives: 0,
            corners: CornerAttributes::default(),
        }
    }

    /// A top-level grouping node without a mesh.
    fn empty(name: String) -> Self {
        ImportedMesh {
            name,
            mesh: None,
            report: RepairReport::default(),
            parent: None,
            transform: Transform::IDENTITY,
            skipped_primitives: 0,
            corners: CornerAttributes::default(),
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
/// stored normalised.
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
                Arc::make_mut(&mut out.normals).insert(h, n);
            }
        }
    }
    out
}

/// The faces of one model as tobj returns it, seen in the OBJ text: the
/// object (`o`, counted from 1 so that repeated names stay apart) and group
/// (`g`) it lies in, and for each corner whether it names a `vt` and a `vn`
/// (tobj makes up missing ones from a neighbour).
struct ObjSegment {
    object: Option<(usize, String)>,
    group: Option<String>,
    corners: Vec<(bool, bool)>,
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
    };
    let mut has_faces = false;
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some(key @ ("o" | "g")) => {
                if has_faces {
                    let next = ObjSegment {
                        object: current.object.clone(),
                        group: current.group.clone(),
                        corners: Vec::new(),
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
            Some("f" | "l") => {
                has_faces = true;
                current.corners.extend(words.map(|w| {
                    let mut parts = w.split('/').skip(1);
                    let vt = parts.next().is_some_and(|x| !x.is_empty());
                    let vn = parts.next().is_some_and(|x| !x.is_empty());
                    (vt, vn)
                }));
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
    #[error("{path}: {message}")]
    Read { path: String, message: String },
    #[error("{path}: unsupported format '.{ext}' (supported: .obj, .stl, .gltf, .glb)")]
    Unsupported { path: String, ext: String },
    #[error("{path}: contains no faces")]
    Empty { path: String },
}

/// Checks what tobj does not report by line: a vertex coordinate that is
/// not a finite number (`nan`, `inf`, `1e999`, or made infinite by its `w`),
/// and a face or line index (`v`, `vt` or `vn`) outside the elements the
/// file has. Positive indices count over the whole file, negative ones back
/// from the line. Messages name the line.
fn check_obj_text(text: &str) -> Result<(), String> {
    const KINDS: [(&str, &str); 3] = [
        ("vertex", "vertices"),
        ("texture coordinate", "texture coordinates"),
        ("normal", "normals"),
    ];
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
                    // tobj refuses the line itself.
                    return Ok(());
                }
                if let Some(bad) =
                    (0..values.len().min(3)).find(|&k| parsed[k].is_some_and(|x| !x.is_finite()))
                {
                    return Err(format!(
                        "line {number}: vertex coordinate '{}' is not a finite number",
                        values[bad]
                    ));
                }
                if let [Some(x), Some(y), Some(z), Some(w)] = parsed[..]
                    && w != 0.0
                    && [x, y, z].iter().any(|c| !(c / w).is_finite())
                {
                    return Err(format!(
                        "line {number}: vertex ({x}, {y}, {z}) divided by w = {w} is not a finite number"
                    ));
                }
            }
            Some("vt") => seen[1] += 1,
            Some("vn") => seen[2] += 1,
            Some("f" | "l") => {
                for word in words {
                    for (k, part) in word.split('/').take(3).enumerate() {
                        let Ok(i) = part.parse::<i64>() else {
                            continue;
                        };
                        let fits = if i < 0 {
                            i.unsigned_abs() <= seen[k] as u64
                        } else {
                            i >= 1 && i as u64 <= totals[k] as u64
                        };
                        if !fits {
                            let (one, many) = KINDS[k];
                            return Err(if i < 0 {
                                format!(
                                    "line {number}: face refers to {one} {i}, but only {} {many} come before it",
                                    seen[k]
                                )
                            } else if i == 0 {
                                format!("line {number}: face refers to {one} 0 (OBJ counts from 1)")
                            } else {
                                format!(
                                    "line {number}: face refers to {one} {i}, but the file has {} {many}",
                                    totals[k]
                                )
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
    check_obj_text(text).map_err(|message| ImportError::Read {
        path: path.to_string(),
        message,
    })?;
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
        let mut imported = ImportedMesh {
            corners,
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
    if out.is_empty() {
        return Err(ImportError::Empty {
            path: path.to_string(),
        });
    }
    Ok(out)
}

/// Refuses, by line and triangle, an ASCII STL vertex coordinate that is not
/// a finite `f32` (`nan`, `inf`, `1e99`); stl_io's own message names neither.
fn check_ascii_stl(bytes: &[u8]) -> Result<(), String> {
    let mut triangle = 0usize;
    for (number, line) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = String::from_utf8_lossy(line);
        let mut words = line.split_whitespace();
        match words.next() {
            Some("facet") => triangle += 1,
            Some("vertex") => {
                if let Some(bad) = words
                    .take(3)
                    .find(|w| w.parse::<f32>().is_ok_and(|x| !x.is_finite()))
                {
                    return Err(format!(
                        "line {}, triangle {triangle}: vertex coordinate '{bad}' is not finite",
                        number + 1
                    ));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Parses a binary or ASCII STL file. A binary file must be exactly as long
/// as its triangle count says (so a damaged header cannot ask for
/// gigabytes); `name` names the node, `path` the file in messages.
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
    let binary_size = bytes
        .get(80..84)
        .map(|c| 84 + 50 * u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as u64);
    let is_binary = binary_size == Some(bytes.len() as u64);
    let is_ascii = bytes.trim_ascii_start().starts_with(b"solid") && !is_binary;
    if !is_binary && !is_ascii {
        return Err(read_error(format!(
            "not an STL file: not ASCII (no 'solid'), and {} bytes where a binary STL of its triangle count has {}",
            bytes.len(),
            binary_size.map_or("at least 84".to_string(), |n| n.to_string())
        )));
    }
    if is_ascii {
        check_ascii_stl(bytes).map_err(read_error)?;
    }
    let indexed = stl_io::read_stl(&mut std::io::Cursor::new(bytes))
        .map_err(|e| read_error(format!("not a readable STL file ({e})")))?;
    let positions: Vec<DVec3> = indexed
        .vertices
        .iter()
        .map(|v| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64))
        .collect();
    // stl_io reads any f32 (binary) or any number (ASCII, `nan`, `1e99`).
    let non_finite = indexed.faces.iter().enumerate().find_map(|(t, f)| {
        f.vertices
            .iter()
            .filter_map(|&i| positions.get(i))
            .find(|p| !p.is_finite())
            .map(|p| (t, p))
    });
    if let Some((t, p)) = non_finite {
        return Err(read_error(format!(
            "triangle {} has a corner that is not finite: ({}, {}, {})",
            t + 1,
            p.x,
            p.y,
            p.z
        )));
    }
    let polygons: Vec<Vec<u32>> = indexed
        .faces
        .iter()
        .map(|f| f.vertices.iter().map(|&i| i as u32).collect())
        .collect();
    let (mesh, report) = HalfEdgeMesh::from_polygons_repaired(&positions, &polygons)
        .map_err(|e| read_error(e.to_string()))?;
    if mesh.face_count() == 0 {
        return Err(ImportError::Empty {
            path: path.to_string(),
        });
    }
    Ok(vec![ImportedMesh::mesh(
        name.to_string(),
        mesh.compacted_if_needed(),
        report,
    )])
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
            let bytes = std::fs::read(path).map_err(|e| ImportError::Read {
                path: shown.clone(),
                message: e.to_string(),
            })?;
            obj_from_str(&String::from_utf8_lossy(&bytes), &shown)
        }
        "stl" => {
            let bytes = std::fs::read(path).map_err(|e| ImportError::Read {
                path: shown.clone(),
                message: e.to_string(),
            })?;
            let name = path
                .file_stem()
                .map_or_else(|| "STL".to_string(), |s| s.to_string_lossy().into_owned());
            stl_from_bytes(&bytes, &name, &shown)
        }
        "gltf" | "glb" => {
            let bytes = std::fs::read(path).map_err(|e| ImportError::Read {
                path: shown.clone(),
                message: e.to_string(),
            })?;
            crate::gltf::gltf_from_bytes(&bytes, path.parent(), &shown)
        }
        other => Err(ImportError::Unsupported {
            path: shown,
            ext: other.to_string(),
        }),
    }
}

/// One line per repaired object, for the user.
pub fn describe_repairs(meshes: &[ImportedMesh]) -> Vec<String> {
    let mut out: Vec<String> = meshes
        .iter()
        .filter(|m| !m.report.is_clean())
        .map(|m| format!("{}: {}", m.name, m.report))
        .collect();
    out.extend(meshes.iter().filter(|m| m.skipped_primitives > 0).map(|m| {
        format!(
            "{}: {} primitive(s) that are not triangles left out",
            m.name, m.skipped_primitives
        )
    }));
    out
}

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
                visible: true,
                content: match &m.mesh {
                    Some(mesh) => NodeContent::Mesh(MeshContent {
                        corners: m.corners.clone(),
                        ..MeshContent::new(Arc::new(mesh.clone()))
                    }),
                    None => NodeContent::Empty,
                },
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
