//! What an exported file holds, read back without Hedra's own readers
//! (OBJ and STL by hand, glTF with the `gltf` crate), so that tests can
//! compare what each format writes for the same scene.

#![allow(dead_code)]

use glam::{DMat4, DVec3};

/// A triangle in world space.
pub type Triangle = [DVec3; 3];

/// The `v` positions and the `f` polygons (0-based vertex numbers) of an
/// OBJ text.
pub fn obj_polygons(text: &str) -> (Vec<DVec3>, Vec<Vec<usize>>) {
    let (mut v, mut f) = (Vec::new(), Vec::new());
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let x: Vec<f64> = words.take(3).map(|w| w.parse().unwrap()).collect();
                v.push(DVec3::new(x[0], x[1], x[2]));
            }
            Some("f") => f.push(
                words
                    .map(|w| w.split('/').next().unwrap().parse::<usize>().unwrap() - 1)
                    .collect(),
            ),
            _ => {}
        }
    }
    (v, f)
}

/// The triangles of an OBJ text: each polygon as a fan from its first
/// corner (a fan keeps a planar polygon's signed area, concave or not).
pub fn obj_triangles(text: &str) -> Vec<Triangle> {
    let (v, f) = obj_polygons(text);
    f.iter()
        .flat_map(|p| (1..p.len() - 1).map(|i| [v[p[0]], v[p[i]], v[p[i + 1]]]))
        .collect()
}

/// The triangles of a binary STL: an 80-byte header, a count, 50 bytes
/// per triangle (normal, three corners, attribute).
pub fn stl_triangles(bytes: &[u8]) -> Vec<Triangle> {
    let count = u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize;
    assert_eq!(bytes.len(), 84 + 50 * count, "binary STL size");
    let f = |at: usize| f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as f64;
    (0..count)
        .map(|t| {
            let base = 84 + 50 * t + 12;
            [0, 1, 2].map(|c| {
                let at = base + 12 * c;
                DVec3::new(f(at), f(at + 4), f(at + 8))
            })
        })
        .collect()
}

/// The triangles of an ASCII STL (`vertex x y z` lines, three a facet).
pub fn ascii_stl_triangles(text: &str) -> Vec<Triangle> {
    let corners: Vec<DVec3> = text
        .lines()
        .filter_map(|l| l.trim().strip_prefix("vertex "))
        .map(|l| {
            let x: Vec<f64> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
            DVec3::new(x[0], x[1], x[2])
        })
        .collect();
    assert_eq!(corners.len() % 3, 0);
    corners.chunks(3).map(|c| [c[0], c[1], c[2]]).collect()
}

/// The triangles of every triangle primitive of a glTF or GLB file's
/// default scene, in world space (node transforms composed down the
/// hierarchy, without recursion), and the number of line-strip
/// primitives.
pub fn gltf_triangles(bytes: &[u8]) -> (Vec<Triangle>, usize) {
    use base64::Engine;
    let gltf = gltf::Gltf::from_slice(bytes).expect("a readable glTF");
    let buffers: Vec<Vec<u8>> = gltf
        .document
        .buffers()
        .map(|b| match b.source() {
            gltf::buffer::Source::Bin => gltf.blob.clone().expect("a GLB binary chunk"),
            gltf::buffer::Source::Uri(uri) => {
                let data = uri.split_once(";base64,").expect("a data URI").1;
                base64::engine::general_purpose::STANDARD
                    .decode(data)
                    .unwrap()
            }
        })
        .collect();
    let scene = gltf.document.default_scene().expect("a default scene");
    let mut stack: Vec<(gltf::Node, DMat4)> = scene.nodes().map(|n| (n, DMat4::IDENTITY)).collect();
    let (mut triangles, mut lines) = (Vec::new(), 0);
    while let Some((node, parent)) = stack.pop() {
        let local = node.transform().matrix();
        let local = DMat4::from_cols_array_2d(&local.map(|c| c.map(f64::from)));
        let world = parent * local;
        if let Some(mesh) = node.mesh() {
            for p in mesh.primitives() {
                if p.mode() != gltf::mesh::Mode::Triangles {
                    lines += 1;
                    continue;
                }
                let reader = p.reader(|b| Some(&buffers[b.index()]));
                let positions: Vec<DVec3> = reader
                    .read_positions()
                    .expect("positions")
                    .map(|q| {
                        world.transform_point3(DVec3::new(q[0] as f64, q[1] as f64, q[2] as f64))
                    })
                    .collect();
                let indices: Vec<u32> = match reader.read_indices() {
                    Some(i) => i.into_u32().collect(),
                    None => (0..positions.len() as u32).collect(),
                };
                let mirrored = world.determinant() < 0.0;
                for t in indices.chunks(3) {
                    let [a, b, c] = [0, 1, 2].map(|k| positions[t[k] as usize]);
                    triangles.push(if mirrored { [a, c, b] } else { [a, b, c] });
                }
            }
        }
        for child in node.children() {
            stack.push((child, world));
        }
    }
    (triangles, lines)
}

/// The smallest and largest coordinates of the triangles' corners.
pub fn bounds(triangles: &[Triangle]) -> (DVec3, DVec3) {
    triangles
        .iter()
        .flatten()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        })
}

/// The signed volume the triangles enclose (divergence theorem).
pub fn volume(triangles: &[Triangle]) -> f64 {
    triangles
        .iter()
        .map(|[a, b, c]| a.dot(b.cross(*c)) / 6.0)
        .sum()
}

/// Edges (by corner positions, rounded to 1e-5) used by other than
/// exactly two triangles, once in each direction: 0 for a watertight,
/// consistently oriented surface.
pub fn open_edges(triangles: &[Triangle]) -> usize {
    use std::collections::HashMap;
    let key = |p: DVec3| (p * 1e5).round().as_i64vec3().to_array();
    let mut directed: HashMap<([i64; 3], [i64; 3]), i32> = HashMap::new();
    for t in triangles {
        for i in 0..3 {
            let (a, b) = (key(t[i]), key(t[(i + 1) % 3]));
            if a == b {
                continue;
            }
            *directed.entry((a, b)).or_default() += 1;
        }
    }
    directed
        .iter()
        .filter(|((a, b), n)| **n != 1 || directed.get(&(*b, *a)) != Some(&1))
        .count()
}
