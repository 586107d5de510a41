//! Writing meshes to other formats. OBJ keeps polygons as they are (n-gons
//! included); binary STL gets the faces triangulated. Both write world-space
//! positions of the visible meshes, as their subdivision modifiers shape
//! them unless the cage is asked for.

use crate::scene::{Document, Node, NodeContent};
use hedra_geom::HalfEdgeMesh;
use std::borrow::Cow;
use std::fmt::Write;
use std::path::Path;

/// Which shape of each mesh is written.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum ExportShape {
    /// The evaluated shape: meshes with a subdivision modifier at its export level.
    #[default]
    Evaluated,
    /// The editable cage, modifiers ignored.
    Cage,
    /// Every mesh subdivided this many levels (its modifier's scheme, else
    /// Catmull-Clark).
    Subdivided(u32),
}

/// The formats [`export_bytes`] writes, by file extension.
pub const EXPORT_FORMATS: &[(&str, &str)] = &[("obj", "Wavefront OBJ"), ("stl", "binary STL")];

/// The document in the format that `path`'s extension names.
///
/// # Errors
/// A message naming the file when the extension is not an export format.
pub fn export_bytes(doc: &Document, path: &Path, shape: ExportShape) -> Result<Vec<u8>, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "obj" => Ok(to_obj(&export_meshes(doc, shape)?).into_bytes()),
        "stl" => Ok(to_stl(&export_meshes(doc, shape)?)),
        other => Err(format!(
            "{}: unsupported export format '.{other}' (supported: {})",
            path.display(),
            EXPORT_FORMATS
                .iter()
                .map(|(e, _)| format!(".{e}"))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// The visible meshes as binary STL (written by `stl_io`): every face
/// triangulated, positions in world space, each triangle's normal from its
/// corners (counter-clockwise is the outside).
fn to_stl(meshes: &[ExportMesh]) -> Vec<u8> {
    let mut triangles = Vec::new();
    for (_, m, world) in meshes {
        let (m, world) = (&**m, *world);
        for f in m.faces() {
            for corners in hedra_geom::query::triangulate_face(m, f) {
                let [a, b, c] = corners.map(|v| world.transform_point3(m.position(v)));
                let n = (b - a).cross(c - a).normalize_or_zero();
                let vertex = |p: glam::DVec3| stl_io::Vertex::new(p.as_vec3().to_array());
                triangles.push(stl_io::Triangle {
                    normal: stl_io::Normal::new(n.as_vec3().to_array()),
                    vertices: [vertex(a), vertex(b), vertex(c)],
                });
            }
        }
    }
    let mut out = Vec::new();
    stl_io::write_stl(&mut out, triangles.iter()).expect("writing to memory cannot fail");
    out
}

/// The scene's visible meshes as Wavefront OBJ text, one `o` object per mesh
/// node, positions in world space, faces 1-based and counter-clockwise.
fn to_obj(meshes: &[ExportMesh]) -> String {
    let mut out = String::from("# Hedra OBJ export\n");
    let mut base = 1usize;
    for (node, m, world) in meshes {
        let (m, world) = (&**m, *world);
        let mut index = vec![0usize; m.vertex_capacity()];
        let _ = writeln!(out, "o {}", node.name.replace(char::is_whitespace, "_"));
        for (i, v) in m.vertices().enumerate() {
            let p = world.transform_point3(m.position(v));
            index[v.index()] = base + i;
            let _ = writeln!(out, "v {} {} {}", p.x, p.y, p.z);
        }
        for f in m.faces() {
            out.push('f');
            for v in m.face_vertices(f) {
                let _ = write!(out, " {}", index[v.index()]);
            }
            out.push('\n');
        }
        base += m.vertex_count();
    }
    out
}

/// A node, the mesh to write for it and its world matrix.
type ExportMesh<'a> = (&'a Node, Cow<'a, HalfEdgeMesh>, glam::DMat4);

/// The visible meshes in the requested shape.
///
/// # Errors
/// A message naming the node when its subdivision cannot be made (Loop on
/// a mesh with quads, a level too large).
fn export_meshes(doc: &Document, shape: ExportShape) -> Result<Vec<ExportMesh<'_>>, String> {
    let mut out = Vec::new();
    for node in doc.nodes() {
        let NodeContent::Mesh(content) = &node.content else {
            continue;
        };
        if !is_visible(doc, node.id) {
            continue;
        }
        let level = match shape {
            ExportShape::Cage => 0,
            ExportShape::Evaluated => content.subdivision.map_or(0, |m| m.export_level),
            ExportShape::Subdivided(level) => level,
        };
        let mesh = content
            .subdivided(level)
            .map_err(|e| format!("node '{}': {e}", node.name))?;
        out.push((node, mesh, doc.world_matrix(node.id)));
    }
    Ok(out)
}

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
