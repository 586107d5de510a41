//! A chain of nested nodes as scene file text, and where each of its nodes
//! lands in the world: the deep hierarchies of issue 31, item 14.

#![allow(dead_code)]

use hedra_geom::DVec3;
use std::fmt::Write;

/// Each node's local transform: a quarter turn about +Y and a step of
/// (1, 0.5, 0) in its parent's frame.
pub const STEP: DVec3 = DVec3::new(1.0, 0.5, 0.0);

/// Scene file text (format 3) of a chain of `n` nodes, ids 1 to `n`, each
/// the parent of the next; every node is an empty but the last, a cube
/// of size 2 named "Tip".
pub fn chain_text(n: usize) -> String {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let mut out = String::from(
        "(\n    format: \"hedra-scene\",\n    version: 3,\n    meshes: [\n        (\n            positions: [(-1.0, -1.0, -1.0), (1.0, -1.0, -1.0), (-1.0, 1.0, -1.0), (1.0, 1.0, -1.0), (-1.0, -1.0, 1.0), (1.0, -1.0, 1.0), (-1.0, 1.0, 1.0), (1.0, 1.0, 1.0)],\n            faces: [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]],\n        ),\n    ],\n    scene: (\n        next_node_id: ",
    );
    let _ = writeln!(out, "{},\n        nodes: [", n + 1);
    for id in 1..=n {
        let parent = if id == 1 {
            "None".to_string()
        } else {
            format!("Some({})", id - 1)
        };
        let (name, content) = if id == n {
            ("Tip".to_string(), "Mesh(mesh: 0, shading: Flat)")
        } else {
            (format!("Link {id}"), "Empty")
        };
        let _ = writeln!(
            out,
            "            (id: {id}, name: \"{name}\", parent: {parent}, transform: (translation: ({:?}, {:?}, {:?}), rotation: (0.0, {s:?}, 0.0, {s:?}), scale: (1.0, 1.0, 1.0)), visible: true, content: {content}),",
            STEP.x, STEP.y, STEP.z
        );
    }
    out.push_str("        ],\n    ),\n)\n");
    out
}

/// The world position of the chain's node at `depth` (0 for the root):
/// the sum of the steps turned by 0, 1, …, `depth` quarter turns about +Y
/// (x, z) → (z, −x); the turns cancel every four nodes, the heights add up.
pub fn chain_position(depth: usize) -> DVec3 {
    let xz = [(1.0, 0.0), (1.0, -1.0), (0.0, -1.0), (0.0, 0.0)][depth % 4];
    DVec3::new(xz.0, 0.5 * (depth + 1) as f64, xz.1)
}

/// The world rotation of the node at `depth`: `depth + 1` quarter turns
/// about +Y, as the image of +X.
pub fn chain_x_axis(depth: usize) -> DVec3 {
    [DVec3::NEG_Z, DVec3::NEG_X, DVec3::Z, DVec3::X][depth % 4]
}
