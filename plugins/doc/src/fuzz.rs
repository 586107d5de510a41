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
use crate::scene::{Document, NodeContent, SurfaceShape, Transform};
use std::path::Path;

/// The file name the bodies pass to the loaders; errors must mention it.
pub const FUZZ_PATH: &str = "fuzz-input";

fn check_transform(t: &Transform, what: &str) {
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
            NodeContent::Empty => {}
            NodeContent::Mesh(m) => check_mesh(&m.mesh, &what),
            NodeContent::Curve(c) => assert!(
                c.points().iter().all(|p| p.is_finite())
                    && c.weights().iter().all(|w| w.is_finite())
                    && c.knots().iter().all(|k| k.is_finite()),
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
    let meshes = match result {
        Ok(m) => m,
        Err(e) => {
            assert!(e.to_string().starts_with(FUZZ_PATH), "unnamed error: {e}");
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

/// glTF JSON or GLB bytes, with no folder for external buffers (a URI that
/// is not a data URI must give an error, never a file read).
///
/// # Panics
/// When an imported mesh is not sane or an error does not name the file.
pub fn gltf(data: &[u8]) {
    check_imported(crate::gltf::gltf_from_bytes(data, None, FUZZ_PATH));
}
