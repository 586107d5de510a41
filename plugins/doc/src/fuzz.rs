//! Fuzz bodies for every loader: the scene file ([`crate::file::from_str`]),
//! OBJ ([`crate::import::obj_from_str`]), STL
//! ([`crate::import::stl_from_bytes`]) and glTF/GLB
//! ([`crate::gltf::gltf_from_bytes`]).
//!
//! Each function takes arbitrary bytes, runs the loader and, when it
//! succeeds, checks that what came out is sane: every half-edge mesh passes
//! `validate()`, every coordinate and transform is finite, a loaded scene
//! writes back with [`crate::file::to_string`] and reads again to the same
//! document, and an error names the file. Anything else panics, which is
//! what a fuzzer reports. They are called by the cargo-fuzz targets in
//! `plugins/doc/fuzz/` and, over the stored corpus and the regression
//! inputs, by the `fuzz_replay` test, so CI replays every input found
//! without cargo-fuzz.

use crate::file;
use crate::import::{ImportError, ImportedMesh};
use crate::scene::{Document, NodeContent, NodeTransform, SurfaceShape};
use std::path::Path;

/// The file name the bodies pass to the loaders; errors must mention it.
pub const FUZZ_PATH: &str = "fuzz-input";

fn check_transform(t: &NodeTransform, what: &str) {
    assert!(
        t.translation.is_finite() && t.rotation.is_finite() && t.scale.is_finite(),
        "{what}: non-finite transform {t:?}"
    );
}

fn check_mesh(m: &hedra_geom::HalfEdgeMesh, what: &str) {
    if let Err(e) = m.validate() {
        panic!("{what}: loaded mesh is invalid: {e}");
    }
    assert!(
        m.positions().iter().all(|p| p.is_finite()),
        "{what}: non-finite position"
    );
}

/// Every node of a document: finite transform, valid mesh, finite curve and
/// surface data, and the document's own consistency check.
fn check_document(doc: &Document, when: &str) {
    if let Err(e) = doc.check() {
        panic!("{when}: inconsistent document: {e}");
    }
    for n in doc.nodes() {
        let what = format!("{when}: node {} '{}'", n.id, n.name);
        check_transform(&n.transform, &what);
        match &n.content {
            NodeContent::Empty | NodeContent::Csg(_) => {}
            NodeContent::Mesh(m) => check_mesh(&m.mesh, &what),
            NodeContent::Kept(k) => assert!(
                k.mesh.check().is_ok(),
                "{what}: kept mesh with a bad face or point"
            ),
            NodeContent::Curve(c) => assert!(
                c.control_points().iter().all(|p| p.is_finite())
                    && c.nurbs().points().iter().all(|p| p.is_finite())
                    && c.nurbs().weights().iter().all(|w| w.is_finite())
                    && c.nurbs().knots().iter().all(|k| k.is_finite()),
                "{what}: non-finite curve data"
            ),
            NodeContent::Surface(s) => {
                assert!(
                    s.control_points().iter().all(|p| p.is_finite()),
                    "{what}: non-finite surface control point"
                );
                if let SurfaceShape::Nurbs(s) = &**s {
                    let (u, v) = s.knots();
                    assert!(
                        s.weights().iter().all(|w| w.is_finite())
                            && u.iter().chain(v).all(|k| k.is_finite()),
                        "{what}: non-finite surface weights or knots"
                    );
                }
            }
        }
    }
}

/// Scene file text: loads, and a loaded scene is sane in every state its
/// history reaches, writes back and reads again to the same scene.
///
/// # Panics
/// When a loaded scene is not sane or an error does not name the file.
pub fn scene(data: &[u8]) {
    // `file::load` refuses non-UTF-8 files before parsing.
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let path = Path::new(FUZZ_PATH);
    let loaded = match file::from_str(text, path) {
        Ok(l) => l,
        Err(e) => {
            assert!(e.to_string().starts_with(FUZZ_PATH), "unnamed error: {e}");
            return;
        }
    };
    let session = loaded.session;
    check_document(&session.doc, "loaded scene");
    let written = file::to_string(&session);
    let back = match file::from_str(&written, path) {
        Ok(b) => b,
        Err(e) => panic!("a loaded scene does not load back after saving: {e}\n{written}"),
    };
    assert!(
        back.session.doc == session.doc,
        "the scene changed in a save and load"
    );
    assert_eq!(
        (session.history.done().len(), session.history.undone().len()),
        (
            back.session.history.done().len(),
            back.session.history.undone().len()
        ),
        "the history changed in a save and load (warnings: {:?})",
        back.warnings
    );
    // Every state the user can reach with undo and redo is sane.
    let mut s = session;
    let mut steps = 0;
    while s.undo().is_some() {
        steps += 1;
        check_document(&s.doc, &format!("after {steps} undo step(s)"));
    }
    while s.redo().is_some() {
        check_document(&s.doc, "after redo");
    }
}

fn check_imported(result: Result<Vec<ImportedMesh>, ImportError>) {
    check_imported_from(result, FUZZ_PATH)
}

/// As [`check_imported`] for a file read from `path` (errors name it).
fn check_imported_from(result: Result<Vec<ImportedMesh>, ImportError>, path: &str) {
    let meshes = match result {
        Ok(m) => m,
        Err(e) => {
            assert!(e.to_string().starts_with(path), "unnamed error: {e}");
            return;
        }
    };
    assert!(!meshes.is_empty(), "an import succeeded with no nodes");
    for (i, m) in meshes.iter().enumerate() {
        let what = format!("imported node {i} '{}'", m.name);
        check_transform(&m.transform, &what);
        if let Some(p) = m.parent {
            assert!(p < i, "{what}: parent {p} does not come before it");
        }
        if let Some(mesh) = &m.mesh {
            check_mesh(mesh, &what);
            assert!(mesh.face_count() > 0, "{what}: mesh without faces");
        }
        if let Some(curve) = &m.curve {
            use hedra_geom::curves::Curve;
            assert!(m.mesh.is_none(), "{what}: both a mesh and a curve");
            let (a, b) = curve.domain();
            assert!(a < b, "{what}: an empty curve domain");
            for t in [a, (a + b) / 2.0, b] {
                assert!(
                    curve.point(t).is_finite(),
                    "{what}: a curve point not finite"
                );
            }
        }
    }
}

/// OBJ text (bytes read as `import_file` does, invalid UTF-8 replaced).
///
/// # Panics
/// When an imported mesh is not sane or an error does not name the file.
pub fn obj(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    check_imported(crate::import::obj_from_str(&text, FUZZ_PATH));
}

/// STL bytes, binary or ASCII.
///
/// # Panics
/// When an imported mesh is not sane or an error does not name the file.
pub fn stl(data: &[u8]) {
    check_imported(crate::import::stl_from_bytes(data, "fuzz", FUZZ_PATH));
}

/// STEP bytes (the exchange reader: faceted B-reps and triangulated
/// solids).
///
/// # Panics
/// When an imported mesh is not sane or an error does not name the file.
pub fn step(data: &[u8]) {
    check_imported(crate::step::read::step_from_bytes(data, FUZZ_PATH));
}

/// glTF JSON or GLB bytes, imported as a file of [`reference_sandbox`]'s
/// `inside` folder: external buffers inside it are read; a buffer that
/// leaves it (`../outside.bin`, a link, an absolute path, …) must be
/// refused, which is checked by the marker coordinate of `outside.bin`.
///
/// # Panics
/// When an imported mesh is not sane, an error does not name the file, or
/// the import read `outside.bin`.
pub fn gltf(data: &[u8]) {
    let result = crate::gltf::gltf_from_bytes(data, Some(&reference_sandbox()), FUZZ_PATH);
    if let Ok(meshes) = &result {
        for m in meshes.iter().filter_map(|m| m.mesh.as_ref()) {
            assert!(
                m.positions().iter().all(|p| p.x != OUTSIDE_MARKER as f64),
                "the import read a file outside the glTF file's folder"
            );
        }
    }
    check_imported(result);
}

/// USD bytes: text (`.usda`), or binary crate (`.usdc`) when they start
/// with its magic, imported as a file of [`reference_sandbox`]'s `inside`
/// folder (one file per process), so that sublayers, references and
/// payloads are resolved as for a user's file and refused when they leave
/// the folder.
///
/// # Panics
/// When an imported mesh is not sane or an error does not name the file.
pub fn usd(data: &[u8]) {
    let extension = if data.starts_with(b"PXR-USDC") {
        "usdc"
    } else {
        "usda"
    };
    let path = reference_sandbox().join(format!("fuzz-input-{}.{extension}", std::process::id()));
    std::fs::write(&path, data).expect("the fuzz sandbox can be written");
    let shown = path.display().to_string();
    check_imported_from(crate::usd::usd_from_path(&path), &shown);
}

/// The x coordinate of every point of the sandbox's `outside.bin`.
pub const OUTSIDE_MARKER: f32 = 777.0;

/// A folder for the glTF body's external buffers, made once per process
/// under the temporary directory (the same path every time):
///
/// ```text
/// hedra-fuzz-references/
///   outside.bin                 triangle at x = 777 (must never be read)
///   inside/                     the glTF file's folder
///     buffer.bin                triangle (0,0,0) (1,0,0) (0,1,0), 36 bytes
///     sub/my mesh.bin           the same triangle
///     link_out.bin -> ../outside.bin   (Unix)
/// ```
///
/// # Panics
/// When the temporary directory cannot be written.
pub fn reference_sandbox() -> std::path::PathBuf {
    static SANDBOX: std::sync::OnceLock<std::path::PathBuf> = std::sync::OnceLock::new();
    SANDBOX
        .get_or_init(|| {
            let root = std::env::temp_dir().join("hedra-fuzz-references");
            let inside = root.join("inside");
            std::fs::create_dir_all(inside.join("sub")).expect("the fuzz sandbox can be made");
            let triangle = |x0: f32| -> Vec<u8> {
                [[x0, 0.0, 0.0], [x0 + 1.0, 0.0, 0.0], [x0, 1.0, 0.0]]
                    .iter()
                    .flatten()
                    .flat_map(|c| c.to_le_bytes())
                    .collect()
            };
            let write = |path: &Path, bytes: &[u8]| {
                if std::fs::read(path).ok().as_deref() != Some(bytes) {
                    std::fs::write(path, bytes).expect("the fuzz sandbox can be written");
                }
            };
            write(&root.join("outside.bin"), &triangle(OUTSIDE_MARKER));
            write(&inside.join("buffer.bin"), &triangle(0.0));
            write(&inside.join("sub/my mesh.bin"), &triangle(0.0));
            #[cfg(unix)]
            {
                let _ = std::os::unix::fs::symlink("../outside.bin", inside.join("link_out.bin"));
            }
            inside
        })
        .clone()
}
