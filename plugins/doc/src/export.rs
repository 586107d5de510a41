//! Writing meshes to other formats. OBJ keeps polygons as they are (n-gons
//! included); binary STL gets the faces triangulated. Both write world-space
//! positions of the visible meshes.

use crate::scene::{Document, NodeContent};
use std::fmt::Write;
use std::path::Path;

/// The formats [`export_bytes`] writes, by file extension.
pub const EXPORT_FORMATS: &[(&str, &str)] = &[("obj", "Wavefront OBJ"), ("stl", "binary STL")];

/// The document in the format that `path`'s extension names.
///
/// # Errors
/// A message naming the file when the extension is not an export format.
pub fn export_bytes(doc: &Document, path: &Path) -> Result<Vec<u8>, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "obj" => Ok(to_obj(doc).into_bytes()),
        "stl" => Ok(to_stl(doc)),
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
pub fn to_stl(doc: &Document) -> Vec<u8> {
    let mut triangles = Vec::new();
    for (_, m, world) in visible_meshes(doc) {
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
pub fn to_obj(doc: &Document) -> String {
    let mut out = String::from("# Hedra OBJ export\n");
    let mut base = 1usize;
    for (node, m, world) in visible_meshes(doc) {
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

/// The mesh nodes an export writes (visible ones), with their meshes and
/// world matrices.
fn visible_meshes(
    doc: &Document,
) -> impl Iterator<Item = (&crate::scene::Node, &hedra_geom::HalfEdgeMesh, glam::DMat4)> {
    doc.nodes().filter_map(|node| match &node.content {
        NodeContent::Mesh(content) if is_visible(doc, node.id) => {
            Some((node, &*content.mesh, doc.world_matrix(node.id)))
        }
        _ => None,
    })
}

/// True when the node and all its parents are visible.
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
