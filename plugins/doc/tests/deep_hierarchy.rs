//! Issue 31, item 14: deep hierarchies. A chain of 2,000 nested nodes
//! opens, reports and exports with every world transform where it
//! belongs (computed once per node, top down: `Document::hierarchy`),
//! and a 10,000-deep glTF chain imports, reports and exports to OBJ and
//! STL. How fast is measured by `benches/deep_scene.rs`; these check the
//! values, and that nothing recurses as deep as the chain.

mod deep;
mod written;

use glam::DVec3;
use hedra_doc::export::{ExportOptions, export_bytes};
use hedra_doc::report::SceneReport;
use hedra_doc::{NodeId, file};
use std::path::Path;

fn close(a: DVec3, b: DVec3, what: &str) {
    assert!(
        (a - b).abs().max_element() < 1e-9,
        "{what}: {a}, expected {b}"
    );
}

#[test]
fn a_2000_deep_chain_opens_with_every_world_transform_in_place() {
    const N: usize = 2000;
    let loaded = file::from_str(&deep::chain_text(N), Path::new("chain.hedra.ron")).unwrap();
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let doc = &loaded.session.doc;
    assert_eq!(doc.node_count(), N);

    let tree = doc.hierarchy();
    assert_eq!(tree.order().len(), N, "every node is under the root");
    for depth in 0..N {
        let id = NodeId(depth as u64 + 1);
        let facts = tree.facts(id).unwrap();
        assert_eq!(facts.depth, depth);
        assert!(facts.visible && !facts.inside_csg);
        let world = facts.world;
        close(
            world.w_axis.truncate(),
            deep::chain_position(depth),
            &format!("node {id} translation"),
        );
        close(
            world.x_axis.truncate(),
            deep::chain_x_axis(depth),
            &format!("node {id} x axis"),
        );
        close(
            world.y_axis.truncate(),
            DVec3::Y,
            &format!("node {id} y axis"),
        );
        assert_eq!(
            tree.children(id),
            if depth + 1 < N {
                vec![NodeId(id.0 + 1)]
            } else {
                vec![]
            }
            .as_slice()
        );
    }
    // The walk up from one node gives the same bits as the walk down.
    for depth in [0, 1, 2, 3, 4, 999, N - 1] {
        let id = NodeId(depth as u64 + 1);
        assert_eq!(doc.world_matrix(id), tree.world_matrix(id), "node {id}");
    }
    assert_eq!(doc.subtree(NodeId(1)).len(), N);
    assert_eq!(doc.subtree(NodeId(N as u64 - 1)).len(), 2);

    // `hedra info` reports the same world transforms.
    let report = SceneReport::new(&loaded.session);
    for (depth, node) in report.nodes.iter().enumerate() {
        close(
            DVec3::from_array(node.world.translation),
            deep::chain_position(depth),
            &format!("info of node {}", node.id),
        );
    }

    // Export: the tip cube (size 2) lands around its world position.
    let tip = deep::chain_position(N - 1);
    let obj = export_bytes(doc, Path::new("x.obj"), ExportOptions::default()).unwrap();
    let (positions, faces) = written::obj_polygons(&String::from_utf8(obj).unwrap());
    assert_eq!((positions.len(), faces.len()), (8, 6));
    let stl = written::stl_triangles(
        &export_bytes(doc, Path::new("x.stl"), ExportOptions::default()).unwrap(),
    );
    let (gltf, _) = written::gltf_triangles(
        &export_bytes(doc, Path::new("x.glb"), ExportOptions::default()).unwrap(),
    );
    let obj = written::obj_triangles(
        &String::from_utf8(
            export_bytes(doc, Path::new("x.obj"), ExportOptions::default()).unwrap(),
        )
        .unwrap(),
    );
    for (format, triangles) in [("OBJ", obj), ("STL", stl), ("GLB", gltf)] {
        assert_eq!(triangles.len(), 12, "{format}");
        let (lo, hi) = written::bounds(&triangles);
        // f32 formats (STL, glTF) near a height of 1,000.
        let tolerance = if format == "OBJ" { 1e-9 } else { 1e-3 };
        assert!(
            (lo - (tip - DVec3::ONE)).abs().max_element() < tolerance
                && (hi - (tip + DVec3::ONE)).abs().max_element() < tolerance,
            "{format}: {lo} {hi} around {tip}"
        );
        assert!(written::volume(&triangles) > 7.9, "{format}: outward");
    }
}

#[test]
fn a_10000_deep_gltf_chain_imports_reports_and_exports() {
    const N: usize = 10_000;
    let doc = file::from_str(&deep::chain_text(N), Path::new("chain.hedra.ron"))
        .unwrap()
        .session
        .doc;
    let glb = export_bytes(&doc, Path::new("chain.glb"), ExportOptions::default()).unwrap();
    let meshes = hedra_doc::gltf::gltf_from_bytes(&glb, None, "chain.glb").unwrap();
    assert_eq!(meshes.len(), N);
    let mut session = hedra_doc::Session::new();
    session.import(&meshes, "Import chain.glb");
    assert_eq!(session.doc.node_count(), N);
    session.doc.check().unwrap();

    // The imported chain: the tip is the one mesh, as deep as the chain.
    let tree = session.doc.hierarchy();
    let tip = session
        .doc
        .nodes()
        .find(|n| matches!(n.content, hedra_doc::NodeContent::Mesh(_)))
        .unwrap();
    assert_eq!(tree.facts(tip.id).unwrap().depth, N - 1);
    // glTF stores f32 transforms: 10,000 of them compose to within 1e-3.
    let expected = deep::chain_position(N - 1);
    let got = tree.world_matrix(tip.id).w_axis.truncate();
    assert!(
        (got - expected).abs().max_element() < 1e-2,
        "{got} vs {expected}"
    );

    let report = SceneReport::new(&session);
    let reported = report.nodes.iter().find(|n| n.id == tip.id.0).unwrap();
    assert_eq!(DVec3::from_array(reported.world.translation), got);
    let export = reported.export.as_ref().unwrap();
    // glTF holds triangles: the cube comes back as 12.
    assert_eq!(
        (export.vertices, export.faces, export.triangles),
        (8, 12, 12)
    );

    for name in ["x.obj", "x.stl"] {
        let bytes = export_bytes(&session.doc, Path::new(name), ExportOptions::default()).unwrap();
        let triangles = if name.ends_with("obj") {
            written::obj_triangles(&String::from_utf8(bytes).unwrap())
        } else {
            written::stl_triangles(&bytes)
        };
        assert_eq!(triangles.len(), 12, "{name}");
        let (lo, hi) = written::bounds(&triangles);
        let centre = (lo + hi) / 2.0;
        assert!(
            (centre - got).abs().max_element() < 1e-2,
            "{name}: {centre} vs {got}"
        );
    }
}

#[test]
fn check_finds_a_cycle_of_parents_in_one_walk() {
    // A chain whose root is made a child of its tip: every node is on the
    // cycle; the first (by id) is named.
    let text = deep::chain_text(50).replacen("parent: None", "parent: Some(50)", 1);
    let e = file::from_str(&text, Path::new("cycle.hedra.ron")).unwrap_err();
    assert!(
        e.to_string()
            .contains("node #1 'Link 1' is its own ancestor"),
        "{e}"
    );
    // Nodes 10 to 20 on a cycle (10's parent is 20), hanging from nothing;
    // nodes 1 to 9 a chain from the root, 21 on under the cycle: the first
    // node on the cycle is named.
    let text = deep::chain_text(50).replacen(
        "(id: 10, name: \"Link 10\", parent: Some(9)",
        "(id: 10, name: \"Link 10\", parent: Some(20)",
        1,
    );
    let e = file::from_str(&text, Path::new("cycle.hedra.ron")).unwrap_err();
    assert!(
        e.to_string()
            .contains("node #10 'Link 10' is its own ancestor"),
        "{e}"
    );
}
