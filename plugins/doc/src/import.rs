//! Reading meshes from other formats into the scene. OBJ: every object or
//! group becomes a mesh node, polygons are kept; STL (binary or ASCII, read
//! by `stl_io`): one node, triangles with equal corners welded. Faces that
//! cannot join a manifold half-edge mesh are dropped or split off (with a
//! report).

use crate::history::{NodeChange, Transaction};
use crate::scene::{Document, MeshContent, Node, NodeContent, NodeId, Transform};
use glam::DVec3;
use hedra_geom::{HalfEdgeMesh, RepairReport};
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
        }
    }
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

/// Parses OBJ text. `path` only names the file in messages.
///
/// # Errors
/// [`ImportError::Read`] when the OBJ is malformed, [`ImportError::Empty`]
/// when nothing usable remains.
pub fn obj_from_str(text: &str, path: &str) -> Result<Vec<ImportedMesh>, ImportError> {
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
    let mut out = Vec::new();
    for (i, model) in models.into_iter().enumerate() {
        let m = model.mesh;
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
        let name = if model.name.trim().is_empty() || model.name == "unnamed_object" {
            format!("Object {}", i + 1)
        } else {
            model.name
        };
        out.push(ImportedMesh::mesh(name, mesh.compacted_if_needed(), report));
    }
    if out.is_empty() {
        return Err(ImportError::Empty {
            path: path.to_string(),
        });
    }
    Ok(out)
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
    let indexed = stl_io::read_stl(&mut std::io::Cursor::new(bytes))
        .map_err(|e| read_error(format!("not a readable STL file ({e})")))?;
    let positions: Vec<DVec3> = indexed
        .vertices
        .iter()
        .map(|v| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64))
        .collect();
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
                    Some(mesh) => NodeContent::Mesh(MeshContent::new(Arc::new(mesh.clone()))),
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
