//! Real files from a public test suite: assimp's test models (Debian
//! package `assimp-testmodels`, installed by `scripts/setup`), OBJ, STL and
//! glTF 2 from many exporters, the glTF Asset Generator's primitive modes
//! among them, and files that are broken on purpose. Each is imported;
//! what Hedra makes of it (nodes, faces, vertices, bounding box, the import
//! summary, or the error) is pinned in `tests/corpus/assimp-testmodels.txt`,
//! so any change shows; every imported file is exported to OBJ and GLB and
//! read back with the same faces and bounds.
//!
//! After a deliberate change: `HEDRA_BLESS=1 cargo test -p hedra_doc --test
//! real_files` rewrites the pinned file; review its diff.

use glam::DVec3;
use hedra_doc::Session;
use hedra_doc::export::{ExportOptions, ExportShape, export_bytes};
use hedra_doc::import::{describe_repairs, import_file};
use std::path::{Path, PathBuf};

const MODELS: &str = "/usr/share/assimp/models";

fn files() -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![PathBuf::from(MODELS)];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().and_then(|e| e.to_str()).is_some_and(|e| {
                ["obj", "stl", "gltf", "glb"].contains(&e.to_ascii_lowercase().as_str())
            }) {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// Faces, vertices and the bounding box of a session's meshes in world space.
fn summary(s: &Session) -> (usize, usize, DVec3, DVec3) {
    let (mut faces, mut vertices) = (0, 0);
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for node in s.doc.nodes() {
        let world = s.doc.world_matrix(node.id);
        let mut grow = |p: DVec3| {
            let p = world.transform_point3(p);
            lo = lo.min(p);
            hi = hi.max(p);
        };
        if let Some(m) = node.content.mesh() {
            faces += m.face_count();
            vertices += m.vertex_count();
            m.vertices().for_each(|v| grow(m.position(v)));
        }
        // A kept (non-manifold) mesh: its faces and the points they use.
        if let hedra_doc::NodeContent::Kept(k) = &node.content {
            faces += k.mesh.faces.len();
            let mut used: Vec<u32> = k.mesh.faces.iter().flatten().copied().collect();
            used.sort_unstable();
            used.dedup();
            vertices += used.len();
            used.iter()
                .for_each(|&v| grow(k.mesh.positions[v as usize]));
        }
    }
    (faces, vertices, lo, hi)
}

fn rounded(p: DVec3) -> String {
    format!("({:.4}, {:.4}, {:.4})", p.x, p.y, p.z).replace("-0.0000", "0.0000")
}

#[test]
fn assimp_test_models_import_as_pinned_and_round_trip() {
    assert!(
        Path::new(MODELS).is_dir(),
        "{MODELS} is missing: run scripts/setup (it installs assimp-testmodels)"
    );
    let mut lines = Vec::new();
    let dir = tempfile::tempdir().unwrap();
    for path in files() {
        let name = path.strip_prefix(MODELS).unwrap().display().to_string();
        let meshes = match import_file(&path) {
            Ok(m) => m,
            Err(e) => {
                let message = e.to_string().replace(&path.display().to_string(), "FILE");
                lines.push(format!("{name}: error: {message}"));
                continue;
            }
        };
        let mut s = Session::new();
        s.import(&meshes, "Import");
        let (faces, vertices, lo, hi) = summary(&s);
        let notes = describe_repairs(&meshes);
        lines.push(format!(
            "{name}: {} node(s), {faces} face(s), {vertices} vertices, box {} {}{}",
            meshes.len(),
            rounded(lo),
            rounded(hi),
            notes.first().map_or(String::new(), |n| format!("; {n}"))
        ));
        if faces == 0 {
            continue;
        }
        // Out to OBJ and GLB and back: the same bounds, and for OBJ the
        // same faces.
        for ext in ["obj", "glb"] {
            let out = dir.path().join(format!("out.{ext}"));
            let options = ExportOptions {
                shape: ExportShape::Cage,
                ..Default::default()
            };
            let bytes = export_bytes(&s.doc, &out, options)
                .unwrap_or_else(|e| panic!("{name}: export to {ext}: {e}"));
            std::fs::write(&out, bytes).unwrap();
            let back = import_file(&out).unwrap_or_else(|e| panic!("{name}: {ext} back: {e}"));
            let mut again = Session::new();
            again.import(&back, "Import");
            let (f2, _, lo2, hi2) = summary(&again);
            let size = (hi - lo).length().max(1.0);
            assert!(
                (lo2 - lo).length() <= 1e-5 * size && (hi2 - hi).length() <= 1e-5 * size,
                "{name}: {ext} round trip moved the bounds: {lo} {hi} -> {lo2} {hi2}"
            );
            if ext == "obj" {
                assert_eq!(f2, faces, "{name}: OBJ round trip faces");
            }
        }
    }
    let text = lines.join("\n") + "\n";
    let pinned = std::path::PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").unwrap())
        .join("tests/corpus/assimp-testmodels.txt");
    if std::env::var_os("HEDRA_BLESS").is_some() {
        std::fs::write(&pinned, &text).unwrap();
    }
    let expected = std::fs::read_to_string(&pinned).unwrap_or_default();
    if expected != text {
        let diff: Vec<String> = expected
            .lines()
            .zip(text.lines())
            .filter(|(a, b)| a != b)
            .map(|(a, b)| format!("- {a}\n+ {b}"))
            .take(10)
            .collect();
        panic!(
            "what Hedra makes of the test models changed ({} lines now, {} pinned):\n{}\n(HEDRA_BLESS=1 to accept)",
            text.lines().count(),
            expected.lines().count(),
            diff.join("\n")
        );
    }
}
