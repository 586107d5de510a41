//! Issue 31, item 13: every export format writes the same shape for the
//! same scene. glTF and GLB wrote a CSG node's operands (the cube, the
//! sphere and three cylinders of the emblem: 2,592 triangles, ±1.5) where
//! OBJ and STL wrote its solid (1,568 triangles, ±1.0). The files are read
//! back without Hedra's readers and compared: triangle count, bounds,
//! volume and watertightness, for every shape option of the export.

mod written;

use hedra_doc::export::{ExportOptions, ExportShape, export_bytes};
use hedra_doc::{Document, file};
use std::path::{Path, PathBuf};
use written::Triangle;

fn sample(name: &str) -> Document {
    let path = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo test"))
        .join("../../assets/samples")
        .join(name);
    file::load(&path).unwrap().session.doc
}

/// The triangles each format writes for `doc`, by format name.
fn every_format(doc: &Document, shape: ExportShape) -> Vec<(&'static str, Vec<Triangle>)> {
    let bytes = |name: &str, ascii_stl: bool| {
        export_bytes(
            doc,
            Path::new(name),
            ExportOptions {
                shape,
                ascii_stl,
                ..ExportOptions::default()
            },
        )
        .unwrap()
    };
    let text = |b: Vec<u8>| String::from_utf8(b).unwrap();
    let gltf = |b: Vec<u8>| {
        let (triangles, lines) = written::gltf_triangles(&b);
        assert_eq!(lines, 0, "no curves in this scene");
        triangles
    };
    vec![
        ("OBJ", written::obj_triangles(&text(bytes("x.obj", false)))),
        ("STL", written::stl_triangles(&bytes("x.stl", false))),
        (
            "ASCII STL",
            written::ascii_stl_triangles(&text(bytes("x.stl", true))),
        ),
        ("glTF", gltf(bytes("x.gltf", false))),
        ("GLB", gltf(bytes("x.glb", false))),
    ]
}

#[test]
fn every_format_writes_the_emblem_solid_with_every_shape_option() {
    let doc = sample("csg.hedra.ron");
    for shape in [
        ExportShape::Evaluated,
        ExportShape::Cage,
        ExportShape::Subdivided(2),
    ] {
        let formats = every_format(&doc, shape);
        let (_, reference) = &formats[0];
        let reference_volume = written::volume(reference);
        for (format, triangles) in &formats {
            let (lo, hi) = written::bounds(triangles);
            assert_eq!(
                triangles.len(),
                1568,
                "{format} {shape:?}: the emblem solid has 1,568 triangles (bounds {lo} {hi})"
            );
            for p in [lo, hi] {
                assert!(
                    p.abs().max_element() <= 1.0 + 1e-6,
                    "{format} {shape:?}: bounds {lo} {hi} are not the solid's ±1"
                );
            }
            assert!(
                lo.max_element() <= -1.0 + 1e-6 && hi.min_element() >= 1.0 - 1e-6,
                "{format} {shape:?}: the solid reaches ±1 on every axis: {lo} {hi}"
            );
            assert_eq!(
                written::open_edges(triangles),
                0,
                "{format} {shape:?}: the solid is watertight"
            );
            let v = written::volume(triangles);
            assert!(
                v > 0.5 && (v - reference_volume).abs() < 1e-4 * reference_volume,
                "{format} {shape:?}: volume {v}, OBJ {reference_volume}"
            );
        }
    }
}

#[test]
fn a_csg_node_inside_a_transformed_parent_is_written_in_the_same_place_by_every_format() {
    // The emblem moved, scaled and mirrored under a parent: glTF keeps the
    // hierarchy, OBJ and STL bake the world transform; both land alike.
    let script = r#"[
        AddPrimitive(primitive: Cube(size: 2.0), name: "A"),
        AddPrimitive(primitive: Cube(size: 2.0), name: "B",
            transform: (translation: (1.0, 1.0, 0.0))),
        AddCsg(op: Difference, name: "Cut", operands: [Name("A"), Name("B")]),
        AddEmpty(name: "Holder",
            transform: (translation: (3.0, 0.0, 0.0), scale: (1.0, 2.0, -1.0))),
        Reparent(node: Name("Cut"), parent: Name("Holder"), keep_world: false),
    ]"#;
    let commands = hedra_doc::script::parse(script, Path::new("t.ron")).unwrap();
    let mut s = hedra_doc::Session::new();
    hedra_doc::script::run(&mut s, &commands, Path::new("t.ron")).unwrap();
    let formats = every_format(&s.doc, ExportShape::Evaluated);
    let (_, reference) = &formats[0];
    let (lo, hi) = written::bounds(reference);
    let solid_volume = written::volume(reference);
    assert!(solid_volume > 0.0, "outward: {solid_volume}");
    for (format, triangles) in &formats {
        assert_eq!(triangles.len(), reference.len(), "{format}");
        let (l, h) = written::bounds(triangles);
        assert!(
            (l - lo).abs().max_element() < 1e-5 && (h - hi).abs().max_element() < 1e-5,
            "{format}: {l} {h}, OBJ {lo} {hi}"
        );
        let v = written::volume(triangles);
        assert!(
            (v - solid_volume).abs() < 1e-4 * solid_volume,
            "{format}: volume {v}, OBJ {solid_volume}"
        );
        assert_eq!(written::open_edges(triangles), 0, "{format}");
    }
}
