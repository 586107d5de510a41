//! Hostile input (issue 6). Replays every stored fuzz input — the seed
//! corpus in `fuzz/corpus/<target>/` and the inputs that once crashed a
//! loader in `fuzz/regressions/<target>/` — through the fuzz bodies of
//! `hedra_doc::fuzz`, so `cargo test` checks them without cargo-fuzz; and
//! checks by hand the messages for the classic hostile files.

use hedra_doc::command::{CurveSpec, SurfaceSpec};
use hedra_doc::export::{ExportOptions, export_bytes};
use hedra_doc::file;
use hedra_doc::fuzz;
use hedra_doc::gltf::gltf_from_bytes;
use hedra_doc::import::{obj_from_str, stl_from_bytes};
use hedra_doc::{Command, NodeRef, NodeTransform, Session};
use hedra_geom::Primitive;
use std::path::{Path, PathBuf};

fn fuzz_dir() -> PathBuf {
    std::path::PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo test"))
        .join("fuzz")
}

/// Runs `body` over every file of `corpus/<target>` and
/// `regressions/<target>`; both folders must exist and the corpus must not
/// be empty.
fn replay(target: &str, body: fn(&[u8])) {
    let mut count = 0;
    for kind in ["corpus", "regressions"] {
        let dir = fuzz_dir().join(kind).join(target);
        let entries = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e} (the fuzz inputs are missing)", dir.display()));
        let mut files: Vec<PathBuf> = entries.map(|e| e.unwrap().path()).collect();
        files.sort();
        if kind == "corpus" {
            assert!(!files.is_empty(), "{}: no seed inputs", dir.display());
        }
        for f in files.iter().filter(|f| f.is_file()) {
            let data = std::fs::read(f).unwrap();
            if std::panic::catch_unwind(|| body(&data)).is_err() {
                panic!("{} fails its fuzz body", f.display());
            }
            count += 1;
        }
    }
    assert!(count > 0, "{target}: no fuzz inputs found");
}

#[test]
fn replay_scene_inputs() {
    replay("scene", fuzz::scene);
}

#[test]
fn replay_obj_inputs() {
    replay("obj", fuzz::obj);
}

#[test]
fn replay_stl_inputs() {
    replay("stl", fuzz::stl);
}

#[test]
fn replay_gltf_inputs() {
    replay("gltf", fuzz::gltf);
}

#[test]
fn replay_step_inputs() {
    replay("step", fuzz::step);
}

#[test]
fn replay_usd_inputs() {
    replay("usd", fuzz::usd);
}

fn error_of<T: std::fmt::Debug, E: std::fmt::Display>(r: Result<T, E>) -> String {
    match r {
        Ok(v) => panic!("expected an error, got {v:?}"),
        Err(e) => e.to_string(),
    }
}

fn assert_mentions(message: &str, parts: &[&str]) {
    for p in parts {
        assert!(message.contains(p), "'{message}' does not mention '{p}'");
    }
}

// ----- STL ------------------------------------------------------------------

#[test]
fn stl_header_claiming_a_billion_triangles_on_a_short_file() {
    let mut bytes = vec![0u8; 80];
    bytes.extend_from_slice(&1_000_000_000u32.to_le_bytes());
    bytes.extend_from_slice(&[0u8; 50]);
    let e = error_of(stl_from_bytes(&bytes, "big", "big.stl"));
    assert_mentions(&e, &["big.stl", "134 bytes", "50000000084"]);
}

fn binary_stl(corners: [[f32; 3]; 3]) -> Vec<u8> {
    let mut bytes = vec![0u8; 80];
    bytes.extend_from_slice(&1u32.to_le_bytes());
    bytes.extend_from_slice(&[0u8; 12]);
    for c in corners {
        for x in c {
            bytes.extend_from_slice(&x.to_le_bytes());
        }
    }
    bytes.extend_from_slice(&[0, 0]);
    bytes
}

#[test]
fn stl_with_nan_or_inf_coordinates() {
    let ok = binary_stl([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    assert!(stl_from_bytes(&ok, "ok", "ok.stl").is_ok());
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let bytes = binary_stl([[0.0; 3], [1.0, bad, 0.0], [0.0, 1.0, 0.0]]);
        let e = error_of(stl_from_bytes(&bytes, "bad", "bad.stl"));
        assert_mentions(&e, &["bad.stl", "triangle 1", "not finite"]);
    }
    for bad in ["nan", "inf", "-inf", "1e999"] {
        let text = format!(
            "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 {bad} 0\nendloop\nendfacet\nendsolid t\n"
        );
        let e = error_of(stl_from_bytes(text.as_bytes(), "bad", "bad.stl"));
        assert_mentions(&e, &["bad.stl", "triangle 1", "not finite"]);
    }
}

// ----- OBJ ------------------------------------------------------------------

#[test]
fn obj_face_index_out_of_range() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 7\n";
    let e = error_of(obj_from_str(text, "range.obj"));
    assert_mentions(&e, &["range.obj", "line 5", "7", "3 vertices"]);
    let negative = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -9\n";
    let e = error_of(obj_from_str(negative, "neg.obj"));
    assert_mentions(&e, &["neg.obj", "line 4", "-9"]);
}

#[test]
fn obj_with_nan_or_inf_coordinates() {
    for bad in ["nan", "NaN", "inf", "-infinity", "1e400"] {
        let text = format!("v 0 0 0\nv 1 0 0\nv 0 {bad} 0\nf 1 2 3\n");
        let e = error_of(obj_from_str(&text, "bad.obj"));
        assert_mentions(&e, &["bad.obj", "line 3", bad, "not a finite number"]);
    }
}

// ----- scene files ----------------------------------------------------------

fn deep_scene(depth: usize, in_history: bool) -> String {
    let open = "[".repeat(depth);
    let close = "]".repeat(depth);
    if in_history {
        format!(
            "(\n    format: \"hedra-scene\",\n    version: 1,\n    meshes: [],\n    scene: (next_node_id: 1, nodes: []),\n    history: (meshes: {open}{close}),\n)\n"
        )
    } else {
        format!(
            "(\n    format: \"hedra-scene\",\n    version: 1,\n    junk: {open}{close},\n    meshes: [],\n    scene: (next_node_id: 1, nodes: []),\n)\n"
        )
    }
}

#[test]
fn ron_nested_100000_levels_deep_does_not_overflow_the_stack() {
    // Test threads have a 2 MiB stack; run on a smaller one still.
    std::thread::Builder::new()
        .stack_size(1 << 20)
        .spawn(|| {
            let e = error_of(file::from_str(
                &deep_scene(100_000, false),
                Path::new("deep.hedra.ron"),
            ));
            assert_mentions(&e, &["deep.hedra.ron:4:", "recursion limit"]);
            // Deep nesting inside the history: the scene opens without it.
            let loaded = file::from_str(&deep_scene(100_000, true), Path::new("deep.hedra.ron"))
                .expect("a damaged history only warns");
            assert_eq!(loaded.warnings.len(), 1);
            assert_mentions(&loaded.warnings[0], &["undo history", "recursion limit"]);
        })
        .unwrap()
        .join()
        .unwrap();
}

#[test]
fn scene_with_a_mesh_index_out_of_the_pool() {
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: Primitive::Cube { size: 1.0 },
        name: Some("Box".into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let text = file::to_string(&s);
    assert!(text.contains("mesh: 0,"), "{text}");
    let bad = text.replacen("mesh: 0,", "mesh: 7,", 1);
    let e = error_of(file::from_str(&bad, Path::new("pool.hedra.ron")));
    assert_mentions(&e, &["pool.hedra.ron", "'Box'", "mesh 7", "not stored"]);
}

// ----- glTF -----------------------------------------------------------------

fn small_scene() -> Session {
    let mut s = Session::new();
    let mut run = |c: Command| {
        s.execute(&c).unwrap();
    };
    run(Command::AddEmpty {
        name: "Rig".into(),
        parent: None,
        transform: NodeTransform {
            translation: glam::DVec3::new(1.0, 2.0, 3.0),
            rotation: glam::DQuat::from_rotation_y(0.5),
            scale: glam::DVec3::splat(2.0),
        },
    });
    run(Command::AddPrimitive {
        primitive: Primitive::Cube { size: 2.0 },
        name: Some("Box".into()),
        parent: Some(NodeRef::Name("Rig".into())),
        transform: NodeTransform::IDENTITY,
    });
    run(Command::AddPrimitive {
        primitive: Primitive::UvSphere {
            segments: 6,
            rings: 3,
            radius: 1.0,
        },
        name: Some("Ball".into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    });
    s
}

#[test]
fn truncated_glb() {
    let glb = export_bytes(
        &small_scene().doc,
        Path::new("s.glb"),
        ExportOptions::default(),
    )
    .unwrap();
    assert!(gltf_from_bytes(&glb, None, "s.glb").is_ok());
    for cut in [4, 11, 12, 19, 40, glb.len() / 2, glb.len() - 1] {
        let e = error_of(gltf_from_bytes(&glb[..cut], None, "cut.glb"));
        assert_mentions(&e, &["cut.glb", "not a readable glTF file"]);
    }
    // A header length shorter than the header itself.
    let mut short = glb.clone();
    short[8..12].copy_from_slice(&5u32.to_le_bytes());
    let e = error_of(gltf_from_bytes(&short, None, "short.glb"));
    assert_mentions(
        &e,
        &["short.glb", "length of 5 bytes", "less than the header"],
    );
}

#[test]
fn gltf_accessor_count_larger_than_its_buffer() {
    use base64::Engine;
    let floats: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0.]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    let uri = base64::engine::general_purpose::STANDARD.encode(&floats);
    let gltf = |count: usize| {
        format!(
            r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],
            "nodes":[{{"mesh":0,"name":"Tri"}}],
            "meshes":[{{"name":"Tri","primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
            "accessors":[{{"bufferView":0,"componentType":5126,"count":{count},"type":"VEC3",
                "min":[0,0,0],"max":[1,1,0]}}],
            "bufferViews":[{{"buffer":0,"byteLength":36}}],
            "buffers":[{{"byteLength":36,"uri":"data:application/octet-stream;base64,{uri}"}}]}}"#
        )
    };
    let ok = gltf_from_bytes(gltf(3).as_bytes(), None, "ok.gltf").unwrap();
    assert_eq!(ok[0].mesh.as_ref().unwrap().face_count(), 1);
    let e = error_of(gltf_from_bytes(
        gltf(1_000_000_000).as_bytes(),
        None,
        "big.gltf",
    ));
    assert_mentions(&e, &["big.gltf", "accessors[0]", "1000000000", "36"]);
}

// ----- seeds ----------------------------------------------------------------

/// Writes the hand-made seed inputs into `fuzz/corpus/` (run on demand:
/// `cargo test -p hedra_doc --test fuzz_replay -- --ignored write_seeds`).
#[test]
#[ignore = "writes the fuzz seed corpus"]
fn write_seeds() {
    let corpus = fuzz_dir().join("corpus");
    let write = |target: &str, name: &str, bytes: &[u8]| {
        let dir = corpus.join(target);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join(name), bytes).unwrap();
    };
    let mut s = small_scene();
    s.execute(&Command::AddCurve {
        name: "Ring".into(),
        curve: CurveSpec::Circle { radius: 1.0 },
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s.execute(&Command::AddSurface {
        name: "Dome".into(),
        surface: SurfaceSpec::Sphere { radius: 0.5 },
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s.undo();
    write(
        "scene",
        "small_with_history.hedra.ron",
        file::to_string(&s).as_bytes(),
    );
    let doc = small_scene().doc;
    for (target, name, ascii) in [
        ("obj", "rig_box_ball.obj", false),
        ("stl", "rig_box_ball_binary.stl", false),
        ("stl", "rig_box_ball_ascii.stl", true),
        ("gltf", "rig_box_ball.gltf", false),
        ("gltf", "rig_box_ball.glb", false),
    ] {
        let options = ExportOptions {
            ascii_stl: ascii,
            ..ExportOptions::default()
        };
        write(
            target,
            name,
            &export_bytes(&doc, Path::new(name), options).unwrap(),
        );
    }
    write(
        "obj",
        "groups_quads_negative_indices.obj",
        b"# two objects\no Quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1//1 2//1 3//1 4//1\ng Tri\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf -3 -2 -1\n",
    );
    write(
        "stl",
        "one_triangle_ascii.stl",
        b"solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\nendsolid t\n",
    );
}

#[test]
fn gltf_node_cycles_and_bad_position_accessors_are_refused() {
    let regressions = fuzz_dir().join("regressions/gltf");
    let read = |name: &str| std::fs::read(regressions.join(name)).unwrap();
    for name in [
        "node_cycle_self_child.gltf",
        "node_shared_children_exponential.gltf",
    ] {
        let e = error_of(gltf_from_bytes(&read(name), None, name));
        assert_mentions(&e, &[name, "reached twice", "trees"]);
    }
    let name = "position_accessor_index_past_accessors_panics_gltf_json_validation.gltf";
    let e = error_of(gltf_from_bytes(&read(name), None, "bad.gltf"));
    assert_mentions(&e, &["bad.gltf", "meshes[1]", "accessors[6]", "has 6"]);
}
