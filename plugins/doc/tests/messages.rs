//! Messages that name what the user can find (issue 31, item 19): OBJ parse
//! errors with their line, CR-only files read by line, a save into a
//! missing folder naming the folder, glTF objects named as in their JSON,
//! a Draco file refused in one line, and imported normals stored short.

use hedra_doc::import::{NORMAL_DECIMALS, obj_from_str, stored_normal};
use hedra_doc::{Session, file};

/// The message of an OBJ that must be refused.
fn obj_error(text: &str) -> String {
    obj_from_str(text, "bad.obj").unwrap_err().to_string()
}

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

#[test]
fn obj_parse_errors_name_their_line() {
    assert_eq!(
        obj_error(&format!("{TRIANGLE}vt 0 x\nf 1 2 3\n")),
        "bad.obj: line 4: a texture coordinate needs 2 number(s), found '0 x'"
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 1 2 x\n")),
        "bad.obj: line 4: face corner 'x' is not a vertex number"
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}vt 0 0\nvn 0 0 1\nf /1/1 /2/1 /3/1\n")),
        "bad.obj: line 6: face corner '/1/1' has no vertex number (a corner is v, v/vt, v//vn or v/vt/vn)"
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}vt 0 0\nf 1/1 2/a 3/1\n")),
        "bad.obj: line 5: face corner '2/a' has texture coordinate 'a', which is not a whole number"
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 1 2 3/1/1/1\n")),
        "bad.obj: line 4: face corner '3/1/1/1' has more than three numbers (v/vt/vn)"
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}l 1 2 q\n")),
        "bad.obj: line 4: polyline corner 'q' is not a vertex number"
    );
    assert_eq!(
        obj_error("v 0 0 0 zz\n"),
        "bad.obj: line 1: vertex value 'zz' is not a number"
    );
    assert_eq!(
        obj_error("v 0 0 0 # origin\n"),
        "bad.obj: line 1: a vertex is x y z, x y z w or x y z r g b, found '0 0 0 # origin'"
    );
    // What still reads: a w, colours, corners without vt, a vn with more.
    let ok = "v 0 0 0 1\nv 1 0 0 2\nv 0 1 0\nvn 0 0 1 # up\nf 1//1 2//1 3//1\n";
    assert_eq!(obj_from_str(ok, "ok.obj").unwrap().len(), 1);
    let colours = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n";
    assert_eq!(obj_from_str(colours, "ok.obj").unwrap().len(), 1);
    // tobj does not read a comment after a face's corners: said by line.
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 1 2 3 # a comment\n")),
        "bad.obj: line 4: face corner '#' is not a vertex number"
    );
}

#[test]
fn a_file_with_cr_line_ends_reads_by_line() {
    // Classic Mac OS line ends: before, one long line ("color parse error").
    let text = format!("{TRIANGLE}f 1 2 3\n").replace('\n', "\r");
    let meshes = obj_from_str(&text, "mac.obj").unwrap();
    assert_eq!(meshes[0].mesh.as_ref().unwrap().face_count(), 1);
    let bad = format!("{TRIANGLE}vt 0 x\n").replace('\n', "\r");
    assert_eq!(
        obj_error(&bad),
        "bad.obj: line 4: a texture coordinate needs 2 number(s), found '0 x'"
    );
    // Mixed CR LF and CR: each counts once.
    let mixed = "v 0 0 0\r\nv 1 0 0\rv 0 1 0\r\nf 1 2 x\r";
    assert_eq!(
        obj_error(mixed),
        "bad.obj: line 4: face corner 'x' is not a vertex number"
    );
}

#[test]
fn saving_into_a_missing_folder_names_the_folder() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("missing").join("x.hedra.ron");
    let mut session = Session::new();
    let e = file::save(&mut session, &target).unwrap_err().to_string();
    assert_eq!(
        e,
        format!(
            "{}: folder '{}' does not exist",
            target.display(),
            dir.path().join("missing").display()
        )
    );
    assert!(!e.contains(".tmp-"), "{e}");
    // Nothing was left behind, and the folder is still missing.
    assert!(!dir.path().join("missing").exists());
}

/// A glTF of one triangle under two nodes whose second is reached twice.
#[test]
fn gltf_messages_name_objects_as_their_json_does() {
    let positions: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0.]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    use base64::Engine;
    let data = base64::engine::general_purpose::STANDARD.encode(&positions);
    let gltf = |nodes: &str, extra: &str| {
        format!(
            r#"{{"asset":{{"version":"2.0"}},{extra}"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":{nodes},
            "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
            "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}],
            "bufferViews":[{{"buffer":0,"byteLength":36}}],
            "buffers":[{{"byteLength":36,"uri":"data:application/octet-stream;base64,{data}"}}]}}"#
        )
    };
    let read = |text: String| {
        hedra_doc::gltf::gltf_from_bytes(text.as_bytes(), None, "t.gltf")
            .map(|m| m.len())
            .map_err(|e| e.to_string())
    };
    assert_eq!(read(gltf(r#"[{"mesh":0}]"#, "")), Ok(1));
    assert_eq!(
        read(gltf(r#"[{"mesh":0,"children":[1]},{"children":[1]}]"#, "")),
        Err("t.gltf: nodes[1] is reached twice (a cycle, or a node with two parents); glTF nodes must form trees".into())
    );
    // A Draco file: one line naming the extension, not a "Missing data"
    // line per accessor.
    let draco = read(gltf(
        r#"[{"mesh":0}]"#,
        r#""extensionsUsed":["KHR_draco_mesh_compression"],"extensionsRequired":["KHR_draco_mesh_compression"],"#,
    ))
    .unwrap_err();
    assert_eq!(
        draco,
        "t.gltf: needs the glTF extension(s) KHR_draco_mesh_compression, which Hedra does not read (compressed meshes): export it again without mesh compression"
    );
}

#[test]
fn the_draco_sample_is_refused_in_one_line() {
    let path = std::path::Path::new("/usr/share/assimp/models/glTF2/draco/2CylinderEngine.gltf");
    assert!(
        path.exists(),
        "run scripts/setup (it installs assimp-testmodels)"
    );
    let e = hedra_doc::import::import_file(path)
        .unwrap_err()
        .to_string();
    assert!(!e.contains("Missing data"), "{e}");
    assert!(
        e.contains("KHR_draco_mesh_compression") && !e.contains('\n'),
        "{e}"
    );
}

#[test]
fn imported_normals_are_stored_rounded_and_read_back_the_same() {
    // Normals of an OBJ that normalising makes long: 1/√3 each way.
    let text = format!("{TRIANGLE}vn 1 1 1\nvn 0.3 0.4 0\nf 1//1 2//2 3//1\n");
    let meshes = obj_from_str(&text, "n.obj").unwrap();
    let normals: Vec<_> = meshes[0].corners.normals.values().copied().collect();
    assert_eq!(normals.len(), 3);
    let scale = 10f64.powi(NORMAL_DECIMALS);
    for n in &normals {
        // Unit within the rounding, each component a whole number of 1e-7.
        assert!((n.length() - 1.0).abs() < 2e-7, "{n}");
        for c in n.to_array() {
            assert_eq!((c * scale).round() / scale, c);
        }
    }
    assert!(normals.iter().any(|n| n.x == 0.5773503), "{normals:?}");
    assert!(
        normals.iter().any(|n| n.x == 0.6 && n.y == 0.8),
        "{normals:?}"
    );
    assert_eq!(
        stored_normal(glam::DVec3::new(-0.0, 1.0, 0.0)).x.to_bits(),
        0f64.to_bits()
    );
    // Saved, the file holds the short numbers, and loads back equal.
    let mut session = Session::new();
    session.import(&meshes, "Import");
    let saved = file::to_string(&session);
    assert!(saved.contains("0.5773503"), "stored short");
    assert!(!saved.contains("0.57735026918962"), "no 17-digit normals");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("n.hedra.ron");
    let loaded = file::from_str(&saved, &path).unwrap();
    assert_eq!(loaded.session.doc, session.doc);
    assert_eq!(file::to_string(&loaded.session), saved);
}
