//! A glTF file's external buffers are read only from inside its own folder
//! (issue 11): every hostile form of a reference kept in the fuzz corpus is
//! refused with a message naming the file, the buffer and the reference;
//! references inside the folder, percent-encoded ones and subfolders work.

use hedra_doc::fuzz::reference_sandbox;
use hedra_doc::gltf::gltf_from_bytes;
use hedra_doc::import::import_file;
use std::path::PathBuf;

fn corpus() -> PathBuf {
    std::path::PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo test"))
        .join("fuzz/corpus/gltf")
}

/// The `uri` of buffer 0 of a glTF JSON file.
fn buffer_uri(bytes: &[u8]) -> String {
    let json: serde_json::Value = serde_json::from_slice(bytes).unwrap();
    json["buffers"][0]["uri"].as_str().unwrap().to_string()
}

/// One triangle whose buffer 0 is `uri`, `declared` bytes long.
fn triangle_gltf(uri: &str, declared: usize) -> String {
    serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "Triangle"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [2, 3, 0]}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "buffers": [{"byteLength": declared, "uri": uri}],
    })
    .to_string()
}

fn triangle_bytes() -> Vec<u8> {
    [[0.0f32, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 3.0, 0.0]]
        .iter()
        .flatten()
        .flat_map(|c| c.to_le_bytes())
        .collect()
}

#[test]
fn every_hostile_reference_of_the_corpus_is_refused_by_name() {
    let mut forms: Vec<String> = Vec::new();
    for entry in std::fs::read_dir(corpus()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let Some(form) = name
            .strip_prefix("reference_refused_")
            .and_then(|n| n.strip_suffix(".gltf"))
        else {
            continue;
        };
        let bytes = std::fs::read(&path).unwrap();
        let uri = buffer_uri(&bytes);
        let error = gltf_from_bytes(&bytes, Some(&reference_sandbox()), "scene.gltf")
            .map(|m| m.len())
            .unwrap_err();
        assert_eq!(
            error.to_string(),
            format!("scene.gltf: buffers[0] refers to '{uri}', outside the file's folder; refused"),
            "{name}"
        );
        forms.push(form.to_string());
    }
    forms.sort();
    // The forms the issue names, each kept as a corpus seed.
    for required in [
        "absolute",
        "dotdot",
        "percent_dotdot",
        "percent_absolute",
        "backslash_dotdot",
        "percent_backslash_dotdot",
        "drive_letter",
        "file_scheme",
        "http_scheme",
        "symlink_out",
    ] {
        assert!(
            forms.iter().any(|f| f == required),
            "no corpus seed reference_refused_{required}.gltf (have {forms:?})"
        );
    }
}

#[test]
fn references_inside_the_folder_of_the_corpus_are_read() {
    for seed in [
        "reference_inside.gltf",
        "reference_subfolder_percent_encoded.gltf",
    ] {
        let bytes = std::fs::read(corpus().join(seed)).unwrap();
        let meshes = gltf_from_bytes(&bytes, Some(&reference_sandbox()), seed)
            .unwrap_or_else(|e| panic!("{seed}: {e}"));
        assert_eq!(meshes.len(), 1, "{seed}");
        let mesh = meshes[0].mesh.as_ref().unwrap();
        assert_eq!(mesh.face_count(), 1, "{seed}");
        assert_eq!(
            mesh.positions()[1],
            glam::DVec3::new(1.0, 0.0, 0.0),
            "{seed}: the sandbox's buffer.bin, not outside.bin"
        );
    }
}

#[test]
fn a_gltf_with_its_buffer_in_a_subfolder_imports_from_disk() {
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("model");
    std::fs::create_dir_all(model.join("buffers")).unwrap();
    std::fs::write(model.join("buffers/tri angle.bin"), triangle_bytes()).unwrap();
    let file = model.join("scene.gltf");
    std::fs::write(&file, triangle_gltf("buffers/tri%20angle.bin", 36)).unwrap();
    let meshes = import_file(&file).unwrap();
    let mesh = meshes[0].mesh.as_ref().unwrap();
    assert_eq!(mesh.positions()[2], glam::DVec3::new(0.0, 3.0, 0.0));
    // The same reference with a backslash, as Windows exporters write it.
    std::fs::write(&file, triangle_gltf("buffers\\tri angle.bin", 36)).unwrap();
    assert_eq!(import_file(&file).unwrap().len(), 1);
}

#[test]
fn the_refusal_names_the_file_the_buffer_and_the_reference() {
    let dir = tempfile::tempdir().unwrap();
    // A readable triangle outside the folder: importing it would succeed.
    std::fs::write(dir.path().join("secret.bin"), triangle_bytes()).unwrap();
    let model = dir.path().join("model");
    std::fs::create_dir_all(&model).unwrap();
    let file = model.join("scene.gltf");
    for uri in [
        "/etc/passwd".to_string(),
        "../secret.bin".to_string(),
        format!("{}", dir.path().join("secret.bin").display()),
        format!("file://{}", dir.path().join("secret.bin").display()),
    ] {
        std::fs::write(&file, triangle_gltf(&uri, 36)).unwrap();
        let error = import_file(&file).map(|m| m.len()).unwrap_err();
        assert_eq!(
            error.to_string(),
            format!(
                "{}: buffers[0] refers to '{uri}', outside the file's folder; refused",
                file.display()
            )
        );
    }
}

#[cfg(unix)]
#[test]
fn a_link_out_of_the_folder_is_refused_and_one_inside_is_followed() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("secret.bin"), triangle_bytes()).unwrap();
    let model = dir.path().join("model");
    std::fs::create_dir_all(&model).unwrap();
    std::fs::write(model.join("real.bin"), triangle_bytes()).unwrap();
    std::os::unix::fs::symlink("../secret.bin", model.join("out.bin")).unwrap();
    std::os::unix::fs::symlink("real.bin", model.join("in.bin")).unwrap();
    // A linked folder that leads out.
    std::os::unix::fs::symlink(dir.path(), model.join("up")).unwrap();
    let file = model.join("scene.gltf");
    for (uri, refused) in [
        ("out.bin", true),
        ("up/secret.bin", true),
        ("in.bin", false),
    ] {
        std::fs::write(&file, triangle_gltf(uri, 36)).unwrap();
        let result = import_file(&file);
        assert_eq!(result.is_err(), refused, "{uri}");
        if refused {
            assert!(
                result
                    .unwrap_err()
                    .to_string()
                    .contains("outside the file's folder; refused"),
                "{uri}"
            );
        }
    }
}

#[test]
fn a_buffer_file_larger_than_declared_is_not_read() {
    let dir = tempfile::tempdir().unwrap();
    let mut big = triangle_bytes();
    big.resize(1 << 20, 0);
    std::fs::write(dir.path().join("big.bin"), big).unwrap();
    let file = dir.path().join("scene.gltf");
    std::fs::write(&file, triangle_gltf("big.bin", 36)).unwrap();
    assert_eq!(
        import_file(&file).map(|m| m.len()).unwrap_err().to_string(),
        format!(
            "{}: buffers[0] refers to 'big.bin', a file of 1048576 bytes where 36 are declared; not read",
            file.display()
        )
    );
    // The same file at its declared size is read.
    std::fs::write(dir.path().join("big.bin"), triangle_bytes()).unwrap();
    assert_eq!(import_file(&file).unwrap().len(), 1);
}

#[test]
fn a_missing_buffer_file_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("scene.gltf");
    std::fs::write(&file, triangle_gltf("gone.bin", 36)).unwrap();
    assert_eq!(
        import_file(&file).map(|m| m.len()).unwrap_err().to_string(),
        format!(
            "{}: buffers[0] refers to 'gone.bin', which cannot be found next to the file",
            file.display()
        )
    );
}
