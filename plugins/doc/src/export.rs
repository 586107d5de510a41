//! Writing meshes to other formats. OBJ keeps polygons as they are (n-gons
//! included) and writes world-space positions.

use crate::scene::{Document, NodeContent};
use std::fmt::Write;

/// The scene's visible meshes as Wavefront OBJ text, one `o` object per mesh
/// node, positions in world space, faces 1-based and counter-clockwise.
pub fn to_obj(doc: &Document) -> String {
    let mut out = String::from("# Hedra OBJ export\n");
    let mut base = 1usize;
    for node in doc.nodes() {
        let NodeContent::Mesh(content) = &node.content else {
            continue;
        };
        if !is_visible(doc, node.id) {
            continue;
        }
        let m = &content.mesh;
        let world = doc.world_matrix(node.id);
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
