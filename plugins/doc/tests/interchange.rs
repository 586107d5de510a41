//! Smaller interchange cases (issue 14, item 12): files without an
//! extension, UTF-16 OBJ, exports of nothing, the NURBS sphere's seam and
//! poles in STL.

use hedra_doc::command::SurfaceSpec;
use hedra_doc::export::{ExportOptions, export_bytes};
use hedra_doc::import::{import_file, stl_from_bytes};
use hedra_doc::{Command, NodeTransform, Session};
use std::path::Path;

#[test]
fn a_file_without_an_extension_is_refused_with_a_reason() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("model");
    std::fs::write(&path, "v 0 0 0\n").unwrap();
    let e = import_file(&path).unwrap_err().to_string();
    assert!(
        e.ends_with("model: the file name has no extension to tell its format (supported: .obj, .stl, .gltf, .glb, .usda, .usdc, .usdz, .usd, .step, .stp)"),
        "{e}"
    );
}

#[test]
fn a_utf16_obj_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let text = "o Tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    for (name, bom, le) in [
        ("le.obj", [0xFF, 0xFE], true),
        ("be.obj", [0xFE, 0xFF], false),
    ] {
        let mut bytes = bom.to_vec();
        for unit in text.encode_utf16() {
            bytes.extend(if le {
                unit.to_le_bytes()
            } else {
                unit.to_be_bytes()
            });
        }
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        let meshes = import_file(&path).unwrap();
        assert_eq!(meshes[0].name, "Tri", "{name}");
        assert_eq!(meshes[0].mesh.as_ref().unwrap().face_count(), 1, "{name}");
    }
}

fn add(s: &mut Session, c: Command) {
    s.execute(&c).unwrap();
}

#[test]
fn exporting_nothing_is_an_error_not_an_empty_file() {
    let mut s = Session::new();
    add(
        &mut s,
        Command::AddEmpty {
            name: "Rig".into(),
            parent: None,
            transform: NodeTransform::IDENTITY,
        },
    );
    for file in ["x.stl", "x.obj"] {
        let e = export_bytes(&s.doc, Path::new(file), ExportOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.starts_with(&format!("{file}: nothing to export")), "{e}");
    }
    // A curve alone: OBJ writes it as a polyline, STL cannot hold it.
    add(
        &mut s,
        Command::AddCurve {
            name: "Ring".into(),
            curve: hedra_doc::command::CurveSpec::Circle { radius: 1.0 },
            parent: None,
            transform: NodeTransform::IDENTITY,
        },
    );
    assert!(export_bytes(&s.doc, Path::new("x.obj"), ExportOptions::default()).is_ok());
    let e = export_bytes(&s.doc, Path::new("x.stl"), ExportOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("STL holds triangles only"), "{e}");
}

#[test]
fn the_nurbs_sphere_exports_closed_without_zero_area_triangles() {
    let mut s = Session::new();
    add(
        &mut s,
        Command::AddSurface {
            name: "Ball".into(),
            surface: SurfaceSpec::Sphere { radius: 1.0 },
            parent: None,
            transform: NodeTransform::IDENTITY,
        },
    );
    let bytes = export_bytes(&s.doc, Path::new("b.stl"), ExportOptions::default()).unwrap();
    let meshes = stl_from_bytes(&bytes, "b", "b.stl").unwrap();
    let mesh = meshes[0].mesh.as_ref().unwrap();
    assert!(meshes[0].report.is_clean(), "{}", meshes[0].report);
    mesh.validate().unwrap();
    assert!(
        mesh.boundary_loops().is_empty(),
        "the seam is welded and the poles closed"
    );
    for f in mesh.faces() {
        let p: Vec<_> = mesh.face_vertices(f).map(|v| mesh.position(v)).collect();
        let area = (p[1] - p[0]).cross(p[2] - p[0]).length() / 2.0;
        assert!(area > 1e-12, "a zero-area triangle");
    }
}

/// What a file has that Hedra does not import is said once, in the summary.
#[test]
fn materials_and_other_dropped_parts_are_named() {
    let obj = "mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Red\nf 1 2 3\n";
    let meshes = hedra_doc::import::obj_from_str(obj, "m.obj").unwrap();
    assert_eq!(
        hedra_doc::import::describe_repairs(&meshes),
        ["not imported: materials (mtllib, usemtl)"]
    );
    // A glTF triangle with two materials and a camera.
    use base64::Engine;
    let bytes: Vec<u8> = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        .iter()
        .flatten()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    let data = base64::engine::general_purpose::STANDARD.encode(&bytes);
    let text = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],
        "nodes":[{{"name":"T","mesh":0}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"material":0}}]}}],
        "materials":[{{"name":"A"}},{{"name":"B"}}],
        "cameras":[{{"type":"perspective","perspective":{{"yfov":1.0,"znear":0.1}}}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}],
        "bufferViews":[{{"buffer":0,"byteLength":36}}],
        "buffers":[{{"byteLength":36,"uri":"data:application/octet-stream;base64,{data}"}}]}}"#
    );
    let meshes = hedra_doc::gltf::gltf_from_bytes(text.as_bytes(), None, "t.gltf").unwrap();
    assert_eq!(
        hedra_doc::import::describe_repairs(&meshes),
        ["not imported: 2 material(s), 1 camera(s)"]
    );
}
