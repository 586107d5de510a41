//! glTF and GLB: what Hedra writes is read back with its hierarchy,
//! transforms and meshes (by the `gltf` crate, which validates it), and bad
//! files are refused by name.

use glam::{DQuat, DVec3};
use hedra_doc::command::{CurveSpec, SurfaceSpec};
use hedra_doc::export::{ExportOptions, export_bytes};
use hedra_doc::import::import_file;
use hedra_doc::{Command, NodeRef, NodeTransform, Session};
use hedra_geom::Primitive;

fn scene() -> Session {
    let mut s = Session::new();
    let run = |s: &mut Session, c: Command| {
        s.execute(&c).unwrap();
    };
    run(
        &mut s,
        Command::AddEmpty {
            name: "Rig".into(),
            parent: None,
            transform: NodeTransform {
                translation: DVec3::new(1.0, 2.0, 3.0),
                rotation: DQuat::from_rotation_y(0.5),
                scale: DVec3::splat(2.0),
            },
        },
    );
    run(
        &mut s,
        Command::AddPrimitive {
            primitive: Primitive::Cube { size: 2.0 },
            name: Some("Box".into()),
            parent: Some(NodeRef::Name("Rig".into())),
            transform: NodeTransform {
                translation: DVec3::new(0.0, 1.0, 0.0),
                ..NodeTransform::IDENTITY
            },
        },
    );
    run(
        &mut s,
        Command::AddPrimitive {
            primitive: Primitive::UvSphere {
                segments: 8,
                rings: 4,
                radius: 1.0,
            },
            name: Some("Ball".into()),
            parent: None,
            transform: NodeTransform::IDENTITY,
        },
    );
    // (A UV sphere is shaded smooth from the start: shared vertex normals.)
    run(
        &mut s,
        Command::AddCurve {
            name: "Ring".into(),
            curve: CurveSpec::Circle { radius: 1.0 },
            parent: None,
            transform: NodeTransform::IDENTITY,
        },
    );
    run(
        &mut s,
        Command::AddSurface {
            name: "Dome".into(),
            surface: SurfaceSpec::Sphere { radius: 0.5 },
            parent: None,
            transform: NodeTransform::IDENTITY,
        },
    );
    s
}

#[test]
fn gltf_and_glb_round_trip_hierarchy_transforms_and_meshes() {
    let s = scene();
    let dir = tempfile::tempdir().unwrap();
    for ext in ["glb", "gltf"] {
        let path = dir.path().join(format!("scene.{ext}"));
        let bytes = export_bytes(&s.doc, &path, ExportOptions::default()).unwrap();
        if ext == "glb" {
            assert_eq!(&bytes[..4], b"glTF");
        } else {
            assert!(String::from_utf8_lossy(&bytes).contains("\"version\":\"2.0\""));
        }
        std::fs::write(&path, &bytes).unwrap();
        let nodes = import_file(&path).unwrap();
        let names: Vec<&str> = nodes.iter().map(|n| n.name.as_str()).collect();
        assert_eq!(names, ["Rig", "Box", "Ball", "Ring", "Dome"], "{ext}");
        let rig = &nodes[0];
        assert!(rig.mesh.is_none());
        assert!((rig.transform.translation - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-6);
        assert!(
            rig.transform
                .rotation
                .angle_between(DQuat::from_rotation_y(0.5))
                < 1e-6
        );
        assert!((rig.transform.scale - DVec3::splat(2.0)).length() < 1e-6);
        let cube = &nodes[1];
        assert_eq!(cube.parent, Some(0), "the box stays under the rig");
        let m = cube.mesh.as_ref().unwrap();
        // glTF carries triangles: the cube's quads come back as 12 triangles
        // on 8 welded corners, closed.
        assert_eq!((m.vertex_count(), m.face_count()), (8, 12));
        assert!(m.stats().closed);
        let ball = nodes[2].mesh.as_ref().unwrap();
        assert!(ball.stats().closed && ball.face_count() > 40);
        // The curve is a line strip: kept as a node, its lines reported.
        assert!(nodes[3].mesh.is_none() && nodes[3].skipped_primitives == 1);
        let dome = nodes[4].mesh.as_ref().unwrap();
        assert!(
            dome.vertices()
                .all(|v| (dome.position(v).length() - 0.5).abs() < 1e-3)
        );
        // Imported into a session: the hierarchy and world positions hold.
        let mut back = Session::new();
        back.import(&nodes, "Import");
        let box_world = back
            .doc
            .world_matrix(back.doc.find_by_name("Box").unwrap().id);
        let original = s.doc.world_matrix(s.doc.find_by_name("Box").unwrap().id);
        assert!(
            box_world.abs_diff_eq(original, 1e-5),
            "{ext}: world transforms differ"
        );
    }
}

#[test]
fn bad_gltf_files_are_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &[u8], &str); 3] = [
        ("junk.glb", b"glTF\x02\x00\x00\x00garbage", "not a readable glTF file"),
        ("junk.gltf", b"{ \"asset\": 5 }", "not a readable glTF file"),
        (
            "missing.gltf",
            br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":12,"uri":"nowhere.bin"}],"scenes":[{"nodes":[]}],"scene":0}"#,
            "buffers[0] refers to 'nowhere.bin', which cannot be found next to the file",
        ),
    ];
    for (name, bytes, expected) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        let e = import_file(&path).unwrap_err().to_string();
        assert!(e.contains(name) && e.contains(expected), "{e}");
    }
}

/// Every normal a glTF export writes is a unit vector (the Khronos
/// validator's rule): at the poles of the NURBS sphere, and on a zero-area
/// face of an imported mesh, also subdivided.
#[test]
fn exported_normals_are_unit_length_at_poles_and_zero_area_faces() {
    let mut s = scene();
    // A flat quad with a zero-area triangle hanging on one edge.
    let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4\nf 2 1 5\n";
    let meshes = hedra_doc::import::obj_from_str(obj, "sliver.obj").unwrap();
    s.import(&meshes, "Import sliver.obj");
    for shape in [
        hedra_doc::export::ExportShape::Cage,
        hedra_doc::export::ExportShape::Subdivided(1),
    ] {
        let options = ExportOptions {
            shape,
            ..Default::default()
        };
        let bytes = export_bytes(&s.doc, std::path::Path::new("n.glb"), options).unwrap();
        let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
        let blob = gltf.blob.clone().unwrap();
        let mut checked = 0;
        for mesh in gltf.meshes() {
            for primitive in mesh.primitives() {
                let reader = primitive.reader(|_| Some(&blob));
                if let Some(normals) = reader.read_normals() {
                    for n in normals {
                        let len = glam::Vec3::from(n).length();
                        assert!(
                            (len - 1.0).abs() < 1e-4,
                            "{shape:?}: {} has length {len}",
                            mesh.name().unwrap_or("?")
                        );
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 100, "{checked}");
    }
}

/// A glTF with one square drawn as a triangle strip and one as a fan
/// (implicit indices, base64 buffer): both are read as two triangles with
/// the same winding as a triangle list.
#[test]
fn triangle_strips_and_fans_are_read() {
    use base64::Engine;
    // Square corners for a strip (0 1 2 3 zigzag) and for a fan (around 0).
    let strip: [[f32; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    let fan: [[f32; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let bytes: Vec<u8> = strip
        .iter()
        .chain(&fan)
        .flatten()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    let data = base64::engine::general_purpose::STANDARD.encode(&bytes);
    let accessor = |offset: usize| {
        format!(
            r#"{{"bufferView":0,"byteOffset":{offset},"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}"#
        )
    };
    let text = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0,1]}}],
        "nodes":[{{"name":"Strip","mesh":0}},{{"name":"Fan","mesh":1}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"mode":5}}]}},
                  {{"primitives":[{{"attributes":{{"POSITION":1}},"mode":6}}]}}],
        "accessors":[{},{}],
        "bufferViews":[{{"buffer":0,"byteLength":{len}}}],
        "buffers":[{{"byteLength":{len},"uri":"data:application/octet-stream;base64,{data}"}}]}}"#,
        accessor(0),
        accessor(48),
        len = bytes.len()
    );
    let meshes = hedra_doc::gltf::gltf_from_bytes(text.as_bytes(), None, "sq.gltf").unwrap();
    for name in ["Strip", "Fan"] {
        let m = meshes.iter().find(|m| m.name == name).unwrap();
        assert_eq!(m.skipped_primitives, 0, "{name}");
        let mesh = m.mesh.as_ref().unwrap();
        assert_eq!((mesh.vertex_count(), mesh.face_count()), (4, 2), "{name}");
        mesh.validate().unwrap();
        for f in mesh.faces() {
            assert!(
                mesh.face_normal(f).z > 0.99,
                "{name}: counter-clockwise from +Z"
            );
        }
    }
}
