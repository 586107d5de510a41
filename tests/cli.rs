//! The `hedra` command line, run as a user would: scripts, info, undo/redo,
//! export and every error path (message, exit code, no output file).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn hedra(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hedra"))
        .args(args)
        .output()
        .expect("the hedra binary runs")
}

fn script(name: &str) -> String {
    std::path::PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo test"))
        .join("tests/scripts")
        .join(name)
        .display()
        .to_string()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn build_hierarchy(dir: &Path) -> PathBuf {
    let out = dir.join("rig.hedra.ron");
    let o = hedra(&["run", &script("hierarchy.ron"), "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    out
}

fn info_json(file: &Path) -> serde_json::Value {
    let o = hedra(&["info", file.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    serde_json::from_slice(&o.stdout).expect("info --json prints one JSON object")
}

fn close(a: &serde_json::Value, b: [f64; 3]) -> bool {
    (0..3).all(|i| (a[i].as_f64().unwrap() - b[i]).abs() < 1e-9)
}

#[test]
fn run_builds_a_hierarchy_and_info_reports_it_field_by_field() {
    let dir = tempfile::tempdir().unwrap();
    let file = build_hierarchy(dir.path());
    let j = info_json(&file);
    assert_eq!(j["format_version"], hedra_doc::file::FORMAT_VERSION);
    let nodes = j["nodes"].as_array().unwrap();
    assert_eq!(nodes.len(), 5);
    let by_name = |n: &str| {
        nodes
            .iter()
            .find(|x| x["name"] == n)
            .unwrap_or_else(|| panic!("no node {n}"))
    };

    let rig = by_name("Rig");
    assert_eq!(rig["kind"], "empty");
    assert!(rig["mesh"].is_null());
    assert!(rig["parent"].is_null());

    let body = by_name("Body");
    assert_eq!(body["kind"], "mesh");
    assert_eq!(body["parent"], rig["id"]);
    // Rig at (1,2,3) scaled 2: the body's local (0.5,0,0) lands at (2,2,3).
    assert!(
        close(&body["world"]["translation"], [2.0, 2.0, 3.0]),
        "{}",
        body["world"]
    );
    assert!(close(&body["world"]["scale"], [2.0, 2.0, 2.0]));
    let m = &body["mesh"];
    assert_eq!(
        (
            m["vertices"].as_u64(),
            m["edges"].as_u64(),
            m["faces"].as_u64()
        ),
        (Some(8), Some(12), Some(6))
    );
    assert_eq!(m["euler_characteristic"], 2);
    assert_eq!(m["boundary_loops"], 0);
    assert_eq!(m["closed"], true);
    assert_eq!(m["manifold"], true);
    assert_eq!(m["valid"], true);
    assert_eq!(m["primitive"], "cube");

    let wheel = by_name("Wheel");
    assert_eq!(wheel["parent"], body["id"]);
    assert_eq!(wheel["mesh"]["euler_characteristic"], 0);
    assert_eq!(wheel["mesh"]["genus"], 1);
    // Local (0,-1,0) under Body (world (2,2,3), scale 2): (2, 0, 3).
    assert!(
        close(&wheel["world"]["translation"], [2.0, 0.0, 3.0]),
        "{}",
        wheel["world"]
    );

    let ground = by_name("Ground");
    assert_eq!(ground["mesh"]["boundary_loops"], 1);
    assert_eq!(ground["mesh"]["closed"], false);
    assert_eq!(ground["mesh"]["euler_characteristic"], 1);

    let tetra = by_name("Tetra");
    assert_eq!(tetra["mesh"]["faces"], 4);
    assert!(tetra["mesh"]["primitive"].is_null());

    assert_eq!(j["history"]["undo_steps"], 6);
    assert_eq!(j["history"]["labels"][0], "Add Empty 'Rig'");

    // The text form names the same things.
    let o = hedra(&["info", file.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("#2 Body [mesh] parent #1"), "{text}");
    assert!(text.contains("mesh: V 8 E 12 F 6"), "{text}");
    assert!(text.contains("validate: ok"));
}

#[test]
fn undo_and_redo_step_the_saved_history() {
    let dir = tempfile::tempdir().unwrap();
    let file = build_hierarchy(dir.path());
    let undone = dir.path().join("undone.hedra.ron");
    let o = hedra(&[
        "undo",
        file.to_str().unwrap(),
        "--steps",
        "2",
        "-o",
        undone.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let j = info_json(&undone);
    let names: Vec<&str> = j["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        ["Rig", "Body", "Wheel"],
        "adding Ground and Tetra is undone"
    );
    assert_eq!(j["history"]["undo_steps"], 4);
    assert_eq!(j["history"]["redo_steps"], 2);

    let redone = dir.path().join("redone.hedra.ron");
    let o = hedra(&[
        "redo",
        undone.to_str().unwrap(),
        "--steps",
        "2",
        "-o",
        redone.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(&redone).unwrap(),
        std::fs::read_to_string(&file).unwrap(),
        "redo returns the exact file"
    );

    // Undo everything: an empty scene.
    let empty = dir.path().join("empty.hedra.ron");
    assert!(
        hedra(&[
            "undo",
            file.to_str().unwrap(),
            "--steps",
            "6",
            "-o",
            empty.to_str().unwrap()
        ])
        .status
        .success()
    );
    assert_eq!(info_json(&empty)["nodes"].as_array().unwrap().len(), 0);
}

#[test]
fn run_on_an_input_scene_appends_to_its_history() {
    let dir = tempfile::tempdir().unwrap();
    let file = build_hierarchy(dir.path());
    let extra = dir.path().join("extra.ron");
    std::fs::write(
        &extra,
        "[Delete(nodes: [Name(\"Ground\")]), Rename(node: Name(\"Tetra\"), name: \"Pyramid\")]",
    )
    .unwrap();
    let out = dir.path().join("out.hedra.ron");
    let o = hedra(&[
        "run",
        extra.to_str().unwrap(),
        "--input",
        file.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let j = info_json(&out);
    assert_eq!(j["history"]["undo_steps"], 8);
    let names: Vec<&str> = j["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n["name"].as_str().unwrap())
        .collect();
    assert!(
        names.contains(&"Pyramid") && !names.contains(&"Ground"),
        "{names:?}"
    );
}

/// A hexagonal cylinder (radius 1, depth 2) at x = 10 exported to `c.<ext>`.
fn exported_cylinder(dir: &std::path::Path, ext: &str) -> std::path::PathBuf {
    let file = dir.join("c.hedra.ron");
    let s = dir.join("s.ron");
    std::fs::write(&s, "[AddPrimitive(primitive: Cylinder(segments: 6, radius: 1.0, depth: 2.0), transform: (translation: (10.0, 0.0, 0.0)))]").unwrap();
    assert!(
        hedra(&["run", s.to_str().unwrap(), "-o", file.to_str().unwrap()])
            .status
            .success()
    );
    let out = dir.join(format!("c.{ext}"));
    let o = hedra(&[
        "export",
        file.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    out
}

#[test]
fn export_writes_world_space_obj_with_ngons() {
    let dir = tempfile::tempdir().unwrap();
    let obj = exported_cylinder(dir.path(), "obj");
    let text = std::fs::read_to_string(&obj).unwrap();
    let v: Vec<Vec<f64>> = text
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| l[2..].split(' ').map(|x| x.parse().unwrap()).collect())
        .collect();
    let f: Vec<usize> = text
        .lines()
        .filter(|l| l.starts_with("f "))
        .map(|l| l.split(' ').count() - 1)
        .collect();
    assert_eq!(v.len(), 12);
    assert!(
        v.iter().all(|p| (p[0] - 10.0).abs() <= 1.0 + 1e-9),
        "positions are in world space"
    );
    assert_eq!(
        f.iter().filter(|&&n| n == 6).count(),
        2,
        "hexagon caps stay n-gons"
    );
    assert_eq!(f.iter().filter(|&&n| n == 4).count(), 6);
}

/// A binary STL read straight from its bytes as the format defines them
/// (an 80-byte header, a little-endian u32 triangle count, then per
/// triangle a normal, three corners (f32 × 3 each) and a u16), not with
/// `stl_io`, the crate Hedra writes STL with: a reader sharing the writer's
/// mistakes would pass them. Returns (normal, corners) per triangle.
fn read_binary_stl(bytes: &[u8]) -> Vec<([f32; 3], [[f32; 3]; 3])> {
    assert!(
        bytes.len() >= 84,
        "{} bytes: shorter than the header",
        bytes.len()
    );
    // Readers take a file whose header starts with "solid" for ASCII STL.
    assert!(
        !bytes.starts_with(b"solid"),
        "a binary STL header must not start with 'solid'"
    );
    let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    assert_eq!(
        bytes.len(),
        84 + 50 * count,
        "{count} triangles of 50 bytes after the header"
    );
    let f =
        |at: usize| f32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let xyz = |at: usize| [f(at), f(at + 4), f(at + 8)];
    (0..count)
        .map(|t| {
            let at = 84 + 50 * t;
            (xyz(at), [xyz(at + 12), xyz(at + 24), xyz(at + 36)])
        })
        .collect()
}

#[test]
fn export_writes_binary_stl_that_an_stl_reader_loads() {
    let dir = tempfile::tempdir().unwrap();
    let stl = exported_cylinder(dir.path(), "stl");
    let triangles = read_binary_stl(&std::fs::read(&stl).unwrap());
    // Two hexagon caps of 4 triangles each and 6 side quads of 2.
    assert_eq!(triangles.len(), 2 * 4 + 6 * 2);
    // Corners welded by their exact bits: the 12 points of the cylinder.
    let mut points: Vec<[u32; 3]> = Vec::new();
    let mut index = |p: [f32; 3]| {
        let key = p.map(f32::to_bits);
        match points.iter().position(|q| *q == key) {
            Some(i) => i,
            None => {
                points.push(key);
                points.len() - 1
            }
        }
    };
    let faces: Vec<[usize; 3]> = triangles.iter().map(|(_, c)| c.map(&mut index)).collect();
    assert_eq!(
        points.len(),
        12,
        "shared corners are written with the same bits"
    );
    // Closed and consistently oriented: every directed edge once, and its
    // reverse once.
    let mut directed: Vec<(usize, usize)> = faces
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .collect();
    directed.sort();
    let before = directed.len();
    directed.dedup();
    assert_eq!(
        directed.len(),
        before,
        "a directed edge used twice: orientation flips"
    );
    for &(a, b) in &directed {
        assert!(
            directed.binary_search(&(b, a)).is_ok(),
            "edge {a}-{b} is open"
        );
    }
    for p in &points {
        assert!(
            (f32::from_bits(p[0]) - 10.0).abs() <= 1.0 + 1e-5,
            "world space: {p:?}"
        );
    }
    for (n, c) in &triangles {
        let sub = |a: [f32; 3], b: [f32; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let (u, v) = (sub(c[1], c[0]), sub(c[2], c[0]));
        let cross = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let area2 = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt();
        assert!(area2 > 1e-6, "a zero-area triangle: {c:?}");
        // The stored normal is the corners' (counter-clockwise) normal and
        // points away from the cylinder's axis or caps' middle.
        let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let agree = (n[0] * cross[0] + n[1] * cross[1] + n[2] * cross[2]) / area2;
        let centre = [0, 1, 2].map(|k| (c[0][k] + c[1][k] + c[2][k]) / 3.0);
        let outward = n[0] * (centre[0] - 10.0) + n[1] * centre[1] + n[2] * centre[2];
        assert!(
            (length - 1.0).abs() < 1e-5 && agree > 1.0 - 1e-5 && outward > 0.0,
            "{n:?} {c:?}"
        );
    }
}

/// Runs a failing command and checks the one-line message, the exit code and
/// that no output file appeared.
fn fails(args: &[&str], output: &Path, expected: &str) {
    let o = hedra(args);
    let err = stderr(&o);
    assert!(!o.status.success(), "{args:?} succeeded");
    assert_eq!(o.status.code(), Some(1), "{args:?}");
    assert!(
        err.contains(expected),
        "{args:?}: stderr was {err:?}, expected {expected:?}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err:?}");
    assert!(!output.exists(), "{args:?} wrote {}", output.display());
}

#[test]
fn every_error_path_says_why_exits_non_zero_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = |n: &str| dir.path().join(n);
    let out = d("out.hedra.ron");
    let o = out.to_str().unwrap();

    fails(
        &["info", d("missing.hedra.ron").to_str().unwrap()],
        &out,
        "missing.hedra.ron: No such file",
    );

    std::fs::write(
        d("bad.ron"),
        "[\n  AddPrimitive(primitive: Cube(size: 2.0),\n  Bogus\n]",
    )
    .unwrap();
    fails(
        &["run", d("bad.ron").to_str().unwrap(), "-o", o],
        &out,
        "bad.ron:3:",
    );

    std::fs::write(d("unknown.ron"), "[Explode(power: 9)]").unwrap();
    fails(
        &["run", d("unknown.ron").to_str().unwrap(), "-o", o],
        &out,
        "Explode",
    );

    std::fs::write(
        d("noid.ron"),
        "[AddPrimitive(primitive: Cube(size: 1.0)), Delete(nodes: [Id(42)])]",
    )
    .unwrap();
    fails(
        &["run", d("noid.ron").to_str().unwrap(), "-o", o],
        &out,
        "command 2 (Delete 1 node): node #42 does not exist",
    );

    std::fs::write(
        d("badmesh.ron"),
        "[AddMesh(name: \"M\", positions: [(0.0,0.0,0.0)], polygons: [[0, 1, 2]])]",
    )
    .unwrap();
    fails(
        &["run", d("badmesh.ron").to_str().unwrap(), "-o", o],
        &out,
        "face 0 refers to vertex 1",
    );

    std::fs::write(
        d("newer.hedra.ron"),
        "(\n    format: \"hedra-scene\",\n    version: 99,\n)",
    )
    .unwrap();
    fails(
        &["info", d("newer.hedra.ron").to_str().unwrap()],
        &out,
        "newer Hedra (format version 99)",
    );

    std::fs::write(d("empty.ron"), "[]").unwrap();
    assert!(
        hedra(&[
            "run",
            d("empty.ron").to_str().unwrap(),
            "-o",
            d("e.hedra.ron").to_str().unwrap()
        ])
        .status
        .success()
    );
    fails(
        &["undo", d("e.hedra.ron").to_str().unwrap(), "-o", o],
        &out,
        "only 0 step(s) can be undone",
    );
    fails(
        &[
            "redo",
            d("e.hedra.ron").to_str().unwrap(),
            "--steps",
            "3",
            "-o",
            o,
        ],
        &out,
        "only 0 step(s) can be redone",
    );
    fails(
        &[
            "export",
            d("e.hedra.ron").to_str().unwrap(),
            "-o",
            d("x.fbx").to_str().unwrap(),
        ],
        &d("x.fbx"),
        "unsupported export format '.fbx'",
    );

    // A usage error is reported by the argument parser with its own exit code.
    let o = hedra(&["info"]);
    assert!(!o.status.success());
}

#[test]
fn import_keeps_a_non_manifold_object_as_in_the_file_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("in.obj");
    // Three triangles on the edge 1–2, and a plain quad.
    std::fs::write(&obj, "o Fan\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 2 1 5\no Quad\nv 0 0 3\nv 1 0 3\nv 1 1 3\nv 0 1 3\nf 6 7 8 9\n").unwrap();
    let out = dir.path().join("kept.hedra.ron");
    let o = hedra(&["import", obj.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The warning names the object and its edge by the file's vertex numbers.
    let err = stderr(&o);
    assert!(
        err.contains(": 1 object(s) kept as in the file, not manifold: 'Fan' (Mesh ▸ Make Manifold repairs them for editing)"),
        "{err}"
    );
    assert!(
        err.contains("  Fan: 1 edge(s) in 3 or more faces: 1–2 (3 faces)"),
        "{err}"
    );
    let j = info_json(&out);
    let fan = &j["nodes"][0];
    assert_eq!(fan["kind"], "kept mesh");
    assert_eq!(fan["kept"]["faces"], 3);
    assert_eq!(fan["kept"]["crowded_edges"].as_array().unwrap().len(), 1);
    assert_eq!(fan["kept"]["crowded_edges"][0][1], 3);
    assert_eq!(fan["export"]["faces"], 3);
    assert_eq!(j["nodes"][1]["mesh"]["faces"], 1);
    let text = hedra(&["info", out.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&text.stdout).into_owned();
    assert!(
        text.contains("not manifold (numbers from 1): 1 edge(s) in 3 or more faces:"),
        "{text}"
    );
    // Exported as it is (3 faces), and kept again when read back.
    let back = dir.path().join("back.obj");
    let o = hedra(&[
        "export",
        out.to_str().unwrap(),
        "-o",
        back.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let written = std::fs::read_to_string(&back).unwrap();
    assert_eq!(written.lines().filter(|l| l.starts_with("f ")).count(), 4);
    let again = dir.path().join("again.hedra.ron");
    let o = hedra(&[
        "import",
        back.to_str().unwrap(),
        "-o",
        again.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(info_json(&again)["nodes"][0]["kept"]["faces"], 3);
    // A script repairs it: MakeManifold drops the third face, says so in
    // the step's label, and undo gives the kept mesh back.
    let script = dir.path().join("repair.ron");
    std::fs::write(&script, "[MakeManifold(nodes: [Name(\"Fan\")])]").unwrap();
    let repaired = dir.path().join("repaired.hedra.ron");
    let o = hedra(&[
        "run",
        script.to_str().unwrap(),
        "--input",
        out.to_str().unwrap(),
        "-o",
        repaired.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let j = info_json(&repaired);
    assert_eq!(j["nodes"][0]["mesh"]["faces"], 2);
    assert_eq!(j["nodes"][0]["mesh"]["valid"], true);
    let label = j["history"]["labels"][1].as_str().unwrap();
    assert!(
        label.starts_with("Make Manifold ('Fan': dropped 1 face(s)"),
        "{label}"
    );
    let undone = dir.path().join("undone.hedra.ron");
    let o = hedra(&[
        "undo",
        repaired.to_str().unwrap(),
        "-o",
        undone.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(info_json(&undone)["nodes"][0]["kind"], "kept mesh");
    // MakeManifold on a mesh that is manifold says so, naming the node.
    let script = dir.path().join("again.ron");
    std::fs::write(&script, "[MakeManifold(nodes: [Name(\"Quad\")])]").unwrap();
    let o = hedra(&[
        "run",
        script.to_str().unwrap(),
        "--input",
        out.to_str().unwrap(),
        "-o",
        dir.path().join("no.hedra.ron").to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("'Quad' (#2) is not a kept (non-manifold) mesh"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn import_turns_obj_objects_into_nodes_and_reports_repairs() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("in.obj");
    std::fs::write(&obj, "o Fan\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 2 1 5\no Quad\nv 0 0 3\nv 1 0 3\nv 1 1 3\nv 0 1 3\nf 6 7 8 9\n").unwrap();
    let out = dir.path().join("imported.hedra.ron");
    let o = hedra(&[
        "import",
        obj.to_str().unwrap(),
        "--repair",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // One warning with the summary, the face named by its line in the file.
    let err = stderr(&o);
    assert!(
        err.contains(": 1 of 2 object(s) repaired: 1 face(s) dropped (1 a third face on an edge)"),
        "{err}"
    );
    assert!(
        err.contains("  Fan: line 9 dropped: would be a third face on an edge already shared by line 7, line 8"),
        "{err}"
    );
    assert_eq!(err.matches("hedra: warning").count(), 1, "{err}");
    let j = info_json(&out);
    let nodes = j["nodes"].as_array().unwrap();
    assert_eq!(nodes.len(), 2);
    assert_eq!(nodes[0]["name"], "Fan");
    assert_eq!(nodes[0]["mesh"]["faces"], 2);
    assert_eq!(nodes[1]["mesh"]["faces"], 1);
    assert_eq!(j["history"]["labels"][0], "Import in.obj");
    // Export and re-import give the same counts.
    let back = dir.path().join("back.obj");
    assert!(
        hedra(&[
            "export",
            out.to_str().unwrap(),
            "-o",
            back.to_str().unwrap()
        ])
        .status
        .success()
    );
    let again = dir.path().join("again.hedra.ron");
    assert!(
        hedra(&[
            "import",
            back.to_str().unwrap(),
            "--repair",
            "-o",
            again.to_str().unwrap()
        ])
        .status
        .success()
    );
    let k = info_json(&again);
    assert_eq!(k["nodes"][0]["mesh"]["faces"], 2);
    assert_eq!(k["nodes"][1]["mesh"]["vertices"], 4);
    fails(
        &[
            "import",
            dir.path().join("x.fbx").to_str().unwrap(),
            "-o",
            dir.path().join("n.hedra.ron").to_str().unwrap(),
        ],
        &dir.path().join("n.hedra.ron"),
        "unsupported format '.fbx' (supported: .obj, .stl, .gltf, .glb, .usda, .usdc, .usdz, .usd, .step, .stp)",
    );
}

#[test]
fn info_topology_prints_the_half_edge_and_winged_edge_tables() {
    let dir = tempfile::tempdir().unwrap();
    let s = dir.path().join("t.ron");
    std::fs::write(&s, "[AddMesh(name: \"Tetra\", positions: [(0.0,0.0,0.0),(1.0,0.0,0.0),(0.0,1.0,0.0),(0.0,0.0,1.0)], polygons: [[0,2,1],[0,1,3],[0,3,2],[1,2,3]])]").unwrap();
    let f = dir.path().join("t.hedra.ron");
    assert!(
        hedra(&["run", s.to_str().unwrap(), "-o", f.to_str().unwrap()])
            .status
            .success()
    );
    let o = hedra(&["info", f.to_str().unwrap(), "--topology"]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("topology of #1 Tetra:"), "{text}");
    assert!(text.contains("half-edges: half-edge | vertex | twin | next | prev | face"));
    assert!(text.contains("  e0 | v0 | v2 | f0 | "), "{text}");
    assert_eq!(text.lines().filter(|l| l.starts_with("  h")).count(), 12);
}

/// Counts of `v` and `f` lines in an OBJ file.
fn obj_counts(path: &Path) -> (usize, usize) {
    let text = std::fs::read_to_string(path).unwrap();
    let count = |p: &str| text.lines().filter(|l| l.starts_with(p)).count();
    (count("v "), count("f "))
}

#[test]
fn export_writes_the_subdivided_shape_the_cage_or_a_given_level() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("smooth.hedra.ron");
    let s = dir.path().join("s.ron");
    std::fs::write(
        &s,
        "[AddPrimitive(primitive: Cube(size: 2.0), name: \"Box\"),
          SetSubdivision(nodes: [Name(\"Box\")], modifier: Some((viewport_level: 1, export_level: 2))),
          SetEdgeCrease(node: Name(\"Box\"), edges: All, sharpness: 10.0)]",
    )
    .unwrap();
    let o = hedra(&["run", s.to_str().unwrap(), "-o", file.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let export = |extra: &[&str]| {
        let out = dir.path().join("out.obj");
        let mut args = vec![
            "export",
            file.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let o = hedra(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        out
    };
    let j = info_json(&file);
    let mesh = &j["nodes"][0]["mesh"];
    assert_eq!(mesh["subdivision"]["scheme"], "Catmull-Clark");
    assert_eq!(mesh["subdivision"]["export_level"], 2);
    assert_eq!(mesh["creased_edges"], 12);
    // The modifier's export level 2: 96 quads, 98 vertices, still a cube
    // because every edge is infinitely sharp.
    let out = export(&[]);
    assert_eq!(obj_counts(&out), (98, 96));
    let text = std::fs::read_to_string(&out).unwrap();
    for line in text.lines().filter(|l| l.starts_with("v ")) {
        let max = line[2..]
            .split(' ')
            .map(|x| x.parse::<f64>().unwrap().abs())
            .fold(0.0, f64::max);
        assert!((max - 1.0).abs() < 1e-9, "{line} is off the cube");
    }
    assert_eq!(obj_counts(&export(&["--cage"])), (8, 6));
    assert_eq!(obj_counts(&export(&["--subdivide", "3"])), (386, 384));
    fails(
        &[
            "export",
            file.to_str().unwrap(),
            "-o",
            dir.path().join("big.obj").to_str().unwrap(),
            "--subdivide",
            "11",
        ],
        &dir.path().join("big.obj"),
        "node 'Box': level 11 is above the maximum of 10",
    );
}

#[test]
fn eval_prints_exact_geometry_and_export_tessellates_curves_and_surfaces() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("shapes.hedra.ron");
    let s = dir.path().join("s.ron");
    std::fs::write(
        &s,
        "[AddCurve(name: \"Ring\", curve: Circle(radius: 2.0)),
          AddSurface(name: \"Ball\", surface: Sphere(radius: 1.0), transform: (translation: (5.0, 0.0, 0.0)))]",
    )
    .unwrap();
    let o = hedra(&["run", s.to_str().unwrap(), "-o", file.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let f = file.to_str().unwrap();
    // The circle at a quarter turn: radius 2, curvature 1/2.
    let o = hedra(&["eval", f, "Ring", "--at", "0.25", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(close(&j["point"], [0.0, 0.0, 2.0]), "{j}");
    assert!((j["curvature"][0].as_f64().unwrap() - 0.5).abs() < 1e-9);
    // The unit sphere: Gaussian curvature 1 everywhere (local space).
    let o = hedra(&["eval", f, "Ball", "--at", "0.3,0.6", "--json"]);
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let p: Vec<f64> = (0..3).map(|i| j["point"][i].as_f64().unwrap()).collect();
    assert!(((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs() < 1e-12);
    assert!((j["curvature"][0].as_f64().unwrap() - 1.0).abs() < 1e-9);
    // Text output names the node.
    let o = hedra(&["eval", f, "Ring", "--at", "0"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("Ring [curve] at [0.0]"));
    // Errors: a parameter outside the domain, the wrong count, not a number, not a shape.
    let out = dir.path().join("none");
    fails(
        &["eval", f, "Ring", "--at", "1.5"],
        &out,
        "'Ring': t = 1.5 is outside the domain [0, 1]",
    );
    fails(
        &["eval", f, "Ball", "--at", "0.5"],
        &out,
        "'Ball' is a surface: give 2 parameter value(s), got 1",
    );
    fails(
        &["eval", f, "Ring", "--at", "x"],
        &out,
        "--at x: 'x' is not a number",
    );
    fails(
        &["eval", f, "Nope", "--at", "0"],
        &out,
        "node 'Nope' does not exist",
    );
    // Export: the circle as an OBJ polyline, the sphere as triangles within the tolerance.
    let obj = dir.path().join("shapes.obj");
    let o = hedra(&["export", f, "-o", obj.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&obj).unwrap();
    let mut v: Vec<[f64; 3]> = Vec::new();
    let mut lines = 0;
    let mut faces = 0;
    for l in text.lines() {
        if let Some(rest) = l.strip_prefix("v ") {
            let c: Vec<f64> = rest.split(' ').map(|x| x.parse().unwrap()).collect();
            v.push([c[0], c[1], c[2]]);
        } else if let Some(rest) = l.strip_prefix("l ") {
            lines += 1;
            let idx: Vec<usize> = rest.split(' ').map(|x| x.parse().unwrap()).collect();
            assert!(
                idx.len() > 50,
                "the circle is finely tessellated: {}",
                idx.len()
            );
            for i in idx {
                let [x, y, z] = v[i - 1];
                assert!(
                    ((x * x + y * y + z * z).sqrt() - 2.0).abs() < 1e-12,
                    "polyline points lie on the circle"
                );
            }
        } else if l.starts_with("f ") {
            faces += 1;
        }
    }
    assert_eq!(lines, 1);
    assert!(faces > 1000, "{faces} sphere triangles");
    assert!(
        v.iter().skip(1).any(|p| (p[0] - 5.0).abs() < 1.0),
        "the sphere is exported in world space"
    );
}

#[test]
fn stl_round_trips_binary_and_ascii_and_bad_stl_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let binary = exported_cylinder(dir.path(), "stl");
    let scene = dir.path().join("c.hedra.ron");
    // ASCII export of the same scene.
    let ascii = dir.path().join("c_ascii.stl");
    let o = hedra(&[
        "export",
        scene.to_str().unwrap(),
        "-o",
        ascii.to_str().unwrap(),
        "--ascii",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&ascii).unwrap();
    // One solid per node, named after it.
    assert!(
        text.starts_with("solid Cylinder\n") && text.trim_end().ends_with("endsolid Cylinder"),
        "{text}"
    );
    assert_eq!(text.matches("facet normal").count(), 20);
    let read = stl_io::read_stl(&mut std::fs::File::open(&ascii).unwrap()).unwrap();
    assert_eq!((read.faces.len(), read.vertices.len()), (20, 12));
    // Both import back as one closed mesh with the corners welded.
    // The binary file's node takes the file's name, the ASCII file's its
    // solid's (the exported node's) name.
    for (file, name) in [(&binary, "c"), (&ascii, "Cylinder")] {
        let out = dir.path().join(format!("{name}.hedra.ron"));
        let o = hedra(&[
            "import",
            file.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let j = info_json(&out);
        let mesh = &j["nodes"][0]["mesh"];
        assert_eq!(j["nodes"][0]["name"], name);
        assert_eq!(
            (mesh["vertices"].as_u64(), mesh["faces"].as_u64()),
            (Some(12), Some(20))
        );
        assert_eq!(mesh["closed"], true);
    }
    // A truncated binary file and a hostile triangle count are refused by name.
    let bytes = std::fs::read(&binary).unwrap();
    let cut = dir.path().join("cut.stl");
    std::fs::write(&cut, &bytes[..bytes.len() - 7]).unwrap();
    let out = dir.path().join("never.hedra.ron");
    fails(
        &["import", cut.to_str().unwrap(), "-o", out.to_str().unwrap()],
        &out,
        "not an STL file",
    );
    let mut huge = bytes[..84].to_vec();
    huge[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
    let hostile = dir.path().join("hostile.stl");
    std::fs::write(&hostile, &huge).unwrap();
    fails(
        &[
            "import",
            hostile.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ],
        &out,
        "where a binary STL of its triangle count has",
    );
}

/// A `.gltf` whose buffer points at a file outside its folder (issue 11):
/// `hedra import` refuses it, naming file, buffer and reference, exits
/// non-zero and writes nothing.
#[test]
fn import_refuses_a_gltf_buffer_outside_the_files_folder() {
    let dir = tempfile::tempdir().unwrap();
    let gltf = dir.path().join("scene.gltf");
    std::fs::write(
        &gltf,
        r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
            "nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
            "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,1]}],
            "bufferViews":[{"buffer":0,"byteLength":36}],
            "buffers":[{"byteLength":36,"uri":"/etc/passwd"}]}"#,
    )
    .unwrap();
    let out = dir.path().join("out.hedra.ron");
    let o = hedra(&[
        "import",
        gltf.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert_eq!(
        stderr(&o).trim(),
        format!(
            "hedra: error: {}: buffers[0] refers to '/etc/passwd', outside the file's folder; refused",
            gltf.display()
        )
    );
    assert!(!out.exists());
}

/// `hedra info --json | head -1`: a reader that goes away ends the output
/// quietly (no panic, no backtrace, success), for info, its topology tables
/// and eval.
#[test]
fn a_reader_that_goes_away_ends_the_output_quietly() {
    let sample = std::path::PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").unwrap())
        .join("assets/samples/table.hedra.ron")
        .display()
        .to_string();
    let shapes = sample.replace("table", "shapes");
    for args in [
        vec!["info", "--json", &sample],
        vec!["info", "--topology", &sample],
        vec!["eval", "--json", &shapes, "Wave", "--at", "0.5"],
    ] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_hedra"))
            .args(&args)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        // Closed before the report is written: every write meets a broken pipe.
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let err = stderr(&out);
        assert!(out.status.success(), "{args:?}: {:?} {err}", out.status);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

/// A Decimate modifier's levels in `hedra info`, and `hedra export --lod`
/// writing the level nearest a ratio: a quarter of the 1280 triangles;
/// a ratio out of range, or a scene without Decimate, is refused by name.
#[test]
fn info_reports_levels_and_export_lod_writes_one() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("rock.hedra.ron");
    let o = hedra(&["run", &script("rock.ron"), "-o", scene.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = hedra(&["info", scene.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&o.stdout);
    let line = text
        .lines()
        .find(|l| l.contains("levels of detail"))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(line.ends_with("to 1280 faces)"), "{line}");
    let obj = dir.path().join("rock.obj");
    let o = hedra(&[
        "export",
        scene.to_str().unwrap(),
        "-o",
        obj.to_str().unwrap(),
        "--lod",
        "0.25",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let faces = std::fs::read_to_string(&obj)
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("f "))
        .count();
    assert!(
        (300..=320).contains(&faces),
        "{faces} faces, about a quarter of 1280"
    );
    let o = hedra(&[
        "export",
        scene.to_str().unwrap(),
        "-o",
        obj.to_str().unwrap(),
        "--lod",
        "1.5",
    ]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("--lod 1.5: the ratio must be above 0 and at most 1"),
        "{}",
        stderr(&o)
    );
    let plain = build_hierarchy(dir.path());
    let o = hedra(&[
        "export",
        plain.to_str().unwrap(),
        "-o",
        obj.to_str().unwrap(),
        "--lod",
        "0.5",
    ]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("no Decimate modifier"),
        "{}",
        stderr(&o)
    );
}

/// `hedra export --curves nurbs` writes a curve as an exact OBJ free-form
/// record (degree, control points with weights, knots), which imports back
/// as the same NURBS; the default stays a polyline.
#[test]
fn export_curves_as_nurbs_records() {
    let dir = tempfile::tempdir().unwrap();
    let script_path = dir.path().join("circle.ron");
    std::fs::write(
        &script_path,
        r#"[AddCurve(name: "Circle", curve: Circle(radius: 2.0), parent: None, transform: (translation: (1.0, 0.0, 0.0), rotation: (0.0, 0.0, 0.0, 1.0), scale: (1.0, 1.0, 1.0)))]"#,
    )
    .unwrap();
    let scene = dir.path().join("circle.hedra.ron");
    let o = hedra(&[
        "run",
        script_path.to_str().unwrap(),
        "-o",
        scene.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let obj = dir.path().join("circle.obj");
    let export = |extra: &[&str]| {
        let mut args = vec![
            "export",
            scene.to_str().unwrap(),
            "-o",
            obj.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let o = hedra(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read_to_string(&obj).unwrap()
    };
    let plain = export(&[]);
    assert!(plain.lines().any(|l| l.starts_with("l ")), "{plain}");
    assert!(!plain.contains("cstype"));
    let nurbs = export(&["--curves", "nurbs"]);
    assert!(nurbs.contains("cstype rat bspline"), "{nurbs}");
    assert!(nurbs.lines().any(|l| l == "deg 2"), "{nurbs}");
    assert!(nurbs.lines().any(|l| l.starts_with("parm u ")), "{nurbs}");
    // Every control point is a weighted `v x y z w` line, moved to x = 1.
    let v: Vec<Vec<f64>> = nurbs
        .lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| {
            l[2..]
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect()
        })
        .collect();
    assert_eq!(v.len(), 9, "the rational circle's nine control points");
    assert!(v.iter().all(|p| p.len() == 4));
    assert!(v.iter().any(|p| (p[0] - 3.0).abs() < 1e-12), "{v:?}");
    let o = hedra(&[
        "export",
        scene.to_str().unwrap(),
        "-o",
        obj.to_str().unwrap(),
        "--curves",
        "bezier",
    ]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("polylines") && stderr(&o).contains("nurbs"),
        "{}",
        stderr(&o)
    );
}

/// Issue 31, item 17: no command writes over a file it reads (`import
/// x.obj -o x.obj` replaced the mesh with a scene, keeping it only as
/// `.bak`), by the same path, another spelling of it or a link; the input
/// is left byte for byte, with no `.bak` beside it.
#[test]
fn no_command_writes_over_its_input() {
    let dir = tempfile::tempdir().unwrap();
    let d = |n: &str| dir.path().join(n);
    let obj = d("x.obj");
    let obj_text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::fs::write(&obj, obj_text).unwrap();
    let scene = build_hierarchy(dir.path());
    let scene_text = std::fs::read_to_string(&scene).unwrap();
    let script_path = d("s.ron");
    std::fs::write(&script_path, "[]").unwrap();
    let (o, s, r) = (
        obj.to_str().unwrap(),
        scene.to_str().unwrap(),
        script_path.to_str().unwrap(),
    );
    let dotted = dir.path().join(".").join("rig.hedra.ron");
    let dotted = dotted.to_str().unwrap();
    let refused: Vec<(Vec<&str>, &str)> = vec![
        (vec!["import", o, "-o", o], o),
        (vec!["import", o, "--input", s, "-o", s], s),
        (vec!["export", s, "-o", s], s),
        (vec!["export", s, "-o", dotted], dotted),
        (vec!["run", r, "-o", r], r),
        (vec!["run", r, "--input", s, "-o", s], s),
        (vec!["undo", s, "-o", s], s),
        (vec!["redo", s, "-o", s], s),
    ];
    for (args, output) in refused {
        let out = hedra(&args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?} was not refused");
        assert!(
            err.contains(&format!("{output}: this is the input file"))
                && err.contains("choose another output file"),
            "{args:?}: {err}"
        );
        assert_eq!(err.trim_end().lines().count(), 1, "one line: {err:?}");
    }
    assert_eq!(std::fs::read_to_string(&obj).unwrap(), obj_text);
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), scene_text);
    assert_eq!(std::fs::read_to_string(&script_path).unwrap(), "[]");
    for f in [&obj, &scene, &script_path] {
        let mut bak = f.as_os_str().to_owned();
        bak.push(".bak");
        assert!(!Path::new(&bak).exists(), "{} has a .bak", f.display());
    }
    // A hard link to the input is the input.
    #[cfg(unix)]
    {
        let link = d("link.obj");
        std::fs::hard_link(&obj, &link).unwrap();
        let out = hedra(&["import", o, "-o", link.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
        assert_eq!(std::fs::read_to_string(&obj).unwrap(), obj_text);
    }
    // Another output is fine.
    let out = hedra(&["import", o, "-o", d("x.hedra.ron").to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
}

/// Issue 31, item 17: a FIFO (or a folder) as the input is refused by
/// name before it is read, where `info` used to block forever. Each
/// command runs with a 20 s limit so that a regression fails instead of
/// hanging the suite.
#[cfg(unix)]
#[test]
fn a_fifo_or_a_folder_as_input_is_refused_without_blocking() {
    use std::time::{Duration, Instant};
    let dir = tempfile::tempdir().unwrap();
    let d = |n: &str| dir.path().join(n);
    let run_limited = |args: &[&str]| -> Output {
        let mut child = Command::new(env!("CARGO_BIN_EXE_hedra"))
            .args(args)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let start = Instant::now();
        while child.try_wait().unwrap().is_none() {
            if start.elapsed() > Duration::from_secs(20) {
                child.kill().unwrap();
                panic!("{args:?} blocked on its input");
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        child.wait_with_output().unwrap()
    };
    for name in ["pipe.hedra.ron", "pipe.obj", "pipe.ron"] {
        let status = Command::new("mkfifo").arg(d(name)).status().unwrap();
        assert!(status.success());
    }
    std::fs::create_dir(d("folder.obj")).unwrap();
    let out = d("out.hedra.ron");
    let o = out.to_str().unwrap();
    let pipe_scene = d("pipe.hedra.ron");
    let pipe_obj = d("pipe.obj");
    let pipe_script = d("pipe.ron");
    let folder = d("folder.obj");
    let x_obj = d("x.obj");
    let cases: Vec<(Vec<&str>, &Path, &str)> = vec![
        (
            vec!["info", pipe_scene.to_str().unwrap()],
            pipe_scene.as_path(),
            "FIFO",
        ),
        (
            vec![
                "export",
                pipe_scene.to_str().unwrap(),
                "-o",
                x_obj.to_str().unwrap(),
            ],
            pipe_scene.as_path(),
            "FIFO",
        ),
        (
            vec!["import", pipe_obj.to_str().unwrap(), "-o", o],
            pipe_obj.as_path(),
            "FIFO",
        ),
        (
            vec!["run", pipe_script.to_str().unwrap(), "-o", o],
            pipe_script.as_path(),
            "FIFO",
        ),
        (
            vec!["import", folder.to_str().unwrap(), "-o", o],
            folder.as_path(),
            "is a folder",
        ),
    ];
    for (args, path, what) in cases {
        let result = run_limited(&args);
        let err = stderr(&result);
        assert_eq!(result.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains(&path.display().to_string()) && err.contains(what),
            "{args:?}: {err}"
        );
        assert!(err.contains("not a regular file"), "{args:?}: {err}");
        assert!(!out.exists());
    }
}

/// Issue 31, item 18: `info` counts what `export` writes (a cube smoothed
/// three levels before a Decimate at 10 %: 76 faces, where info said 4),
/// and `export --lod` at the ratio the Decimate already has works.
#[test]
fn info_counts_what_export_writes_and_lod_at_the_same_ratio_works() {
    let dir = tempfile::tempdir().unwrap();
    let script_path = dir.path().join("cube.ron");
    std::fs::write(
        &script_path,
        r#"[
            AddPrimitive(primitive: Cube(size: 2.0), name: Some("Cube")),
            SetSubdivision(nodes: [Name("Cube")], modifier: Some((viewport_level: 3, export_level: 3, stack_position: Some(0)))),
            AddModifier(node: Name("Cube"), modifier: Decimate((target: Ratio(0.1)))),
        ]"#,
    )
    .unwrap();
    let scene = dir.path().join("cube.hedra.ron");
    let o = hedra(&[
        "run",
        script_path.to_str().unwrap(),
        "-o",
        scene.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let j = info_json(&scene);
    let export = &j["nodes"][0]["export"];
    assert_eq!(export["faces"], 76, "{j}");
    let obj = dir.path().join("cube.obj");
    for lod in [None, Some("0.1")] {
        let mut args = vec![
            "export",
            scene.to_str().unwrap(),
            "-o",
            obj.to_str().unwrap(),
        ];
        if let Some(r) = lod {
            args.extend(["--lod", r]);
        }
        let o = hedra(&args);
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
        let text = std::fs::read_to_string(&obj).unwrap();
        let count = |p: &str| text.lines().filter(|l| l.starts_with(p)).count() as u64;
        assert_eq!(count("f "), export["faces"].as_u64().unwrap(), "{args:?}");
        assert_eq!(
            count("v "),
            export["vertices"].as_u64().unwrap(),
            "{args:?}"
        );
    }
    let text = String::from_utf8(hedra(&["info", scene.to_str().unwrap()]).stdout).unwrap();
    assert!(text.contains(" F 76 (76 triangles)"), "{text}");
}

/// Issue 31, item 13: `export` of the CSG sample writes the emblem solid
/// (1,568 triangles within ±1) to glTF and GLB as to OBJ and STL, with
/// `--cage` and `--subdivide 2` too.
#[test]
fn export_writes_the_csg_solid_to_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let sample = std::path::PathBuf::from(
        std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"),
    )
    .join("assets/samples/csg.hedra.ron");
    for extra in [&[][..], &["--cage"][..], &["--subdivide", "2"][..]] {
        for ext in ["obj", "stl", "gltf", "glb"] {
            let out = dir.path().join(format!("emblem.{ext}"));
            let mut args = vec![
                "export",
                sample.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
            ];
            args.extend_from_slice(extra);
            let o = hedra(&args);
            assert!(o.status.success(), "{args:?}: {}", stderr(&o));
            let bytes = std::fs::read(&out).unwrap();
            let triangles = match ext {
                // OBJ: each face a fan of (corners − 2) triangles.
                "obj" => String::from_utf8(bytes)
                    .unwrap()
                    .lines()
                    .filter(|l| l.starts_with("f "))
                    .map(|l| l.split_whitespace().count() - 3)
                    .sum::<usize>(),
                // Binary STL: the count after the 80-byte header.
                "stl" => u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize,
                // glTF: read back by the importer the window uses.
                _ => hedra_doc::import::import_file(&out)
                    .unwrap()
                    .iter()
                    .filter_map(|m| m.mesh.as_ref())
                    .map(|m| m.faces().map(|f| m.face_degree(f) - 2).sum::<usize>())
                    .sum(),
            };
            assert_eq!(triangles, 1568, "{args:?}");
        }
    }
}

fn sample(name: &str) -> PathBuf {
    PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"))
        .join("assets/samples")
        .join(name)
}

/// Issue 32 from the command line: the jar (a creased Catmull-Clark cage)
/// goes out to USD and back in with its subdivision modifier and creases,
/// as `info` reports them; the shapes sample goes to STEP in millimetres
/// and back with its surfaces and curves, the export notes saying what
/// STEP left out.
#[test]
fn usd_and_step_round_trips_through_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let jar = sample("jar.hedra.ron");
    let usda = dir.path().join("jar.usda");
    let o = hedra(&[
        "export",
        jar.to_str().unwrap(),
        "-o",
        usda.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&usda).unwrap();
    assert!(
        text.starts_with("#usda 1.0"),
        "{}",
        &text[..40.min(text.len())]
    );
    assert!(text.contains("subdivisionScheme = \"catmullClark\""));
    let back = dir.path().join("jar-back.hedra.ron");
    let o = hedra(&[
        "import",
        usda.to_str().unwrap(),
        "-o",
        back.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let before = String::from_utf8(hedra(&["info", jar.to_str().unwrap()]).stdout).unwrap();
    let after = String::from_utf8(hedra(&["info", back.to_str().unwrap()]).stdout).unwrap();
    // Every mesh line (counts, validity) and subdivision/crease line of the
    // jar is in the imported scene's report.
    for line in before.lines().filter(|l| {
        let l = l.trim_start();
        l.starts_with("mesh:") || l.starts_with("subdivision:") || l.starts_with("creases:")
    }) {
        assert!(
            after.contains(line.trim()),
            "missing after the round trip: {line}\n{after}"
        );
    }

    let shapes = sample("shapes.hedra.ron");
    let step = dir.path().join("shapes.step");
    let o = hedra(&[
        "export",
        shapes.to_str().unwrap(),
        "-o",
        step.to_str().unwrap(),
        "--step-units",
        "mm",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&step).unwrap();
    assert!(text.starts_with("ISO-10303-21;"));
    assert!(
        text.contains("SI_UNIT(.MILLI.,.METRE.)"),
        "millimetres stated"
    );
    let back = dir.path().join("shapes-back.hedra.ron");
    let o = hedra(&[
        "import",
        step.to_str().unwrap(),
        "-o",
        back.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let count = |file: &Path, kind: &str| {
        info_json(file)["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|n| n["kind"] == kind && n["visible"] != false)
            .count()
    };
    for kind in ["surface", "curve"] {
        assert!(count(&shapes, kind) > 0);
        assert_eq!(count(&back, kind), count(&shapes, kind), "{kind} nodes");
    }
}

/// A scene of meshes only has nothing STEP holds without --step-meshes:
/// a clear error, exit 1, no file; with it, faceted shells and no error.
#[test]
fn step_export_of_meshes_needs_step_meshes() {
    let dir = tempfile::tempdir().unwrap();
    let chair = sample("chair.hedra.ron");
    let step = dir.path().join("chair.step");
    let o = hedra(&[
        "export",
        chair.to_str().unwrap(),
        "-o",
        step.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("--step-meshes"), "{}", stderr(&o));
    assert!(!step.exists());
    let o = hedra(&[
        "export",
        chair.to_str().unwrap(),
        "-o",
        step.to_str().unwrap(),
        "--step-meshes",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        std::fs::read_to_string(&step)
            .unwrap()
            .contains("FACETED_BREP")
    );
}

/// A USD file that references a file outside its folder is refused by
/// name, exit 1, and no scene is written.
#[test]
fn usd_import_refuses_a_reference_outside_the_folder() {
    let dir = tempfile::tempdir().unwrap();
    let inner = dir.path().join("inner");
    std::fs::create_dir(&inner).unwrap();
    std::fs::write(
        dir.path().join("secret.usda"),
        "#usda 1.0\ndef Xform \"S\" {}\n",
    )
    .unwrap();
    let file = inner.join("scene.usda");
    std::fs::write(
        &file,
        "#usda 1.0\ndef Xform \"A\" (\n    references = @../secret.usda@\n)\n{\n}\n",
    )
    .unwrap();
    let out = dir.path().join("out.hedra.ron");
    let o = hedra(&[
        "import",
        file.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("scene.usda") && e.contains("../secret.usda"),
        "{e}"
    );
    assert!(!out.exists());
}

/// Damaged USD files the fuzz target found (`plugins/doc/fuzz/regressions/usd`)
/// through the command line: each is an error naming the file, with exit
/// code 1 and nothing written, never a crash, a hang or a stack trace (the
/// reader's panic is reported as the file's error).
#[test]
fn damaged_usd_files_are_errors_that_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let regressions =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("plugins/doc/fuzz/regressions/usd");
    for (name, expected) in [
        (
            "usdc_path_index_out_of_range_is_a_reader_error.usdc",
            "the USD reader failed on this file (index out of bounds",
        ),
        (
            "usda_path_its_own_parent_hung_the_reader.usda",
            "is not an xform op",
        ),
    ] {
        let out = dir.path().join("out.hedra.ron");
        let o = hedra(&[
            "import",
            regressions.join(name).to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{name}: {e}");
        assert!(e.contains(name) && e.contains(expected), "{name}: {e}");
        assert!(!e.contains("panicked") && !e.contains("backtrace"), "{e}");
        assert!(!out.exists());
    }
}

/// `--step-subdivision-nurbs`: the cup (a closed, creased Catmull-Clark
/// cage) goes to STEP as its limit surface in NURBS patches, one closed
/// solid, and the note says how many patches and how close they are.
#[test]
fn step_export_writes_a_subdivision_cage_as_a_nurbs_solid() {
    let dir = tempfile::tempdir().unwrap();
    let cup = sample("cup.hedra.ron");
    let step = dir.path().join("cup.step");
    let o = hedra(&[
        "export",
        cup.to_str().unwrap(),
        "-o",
        step.to_str().unwrap(),
        "--step-subdivision-nurbs",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&step).unwrap();
    assert_eq!(text.matches("MANIFOLD_SOLID_BREP").count(), 1, "one solid");
    assert!(!text.contains("OPEN_SHELL"));
    let e = stderr(&o);
    assert!(
        e.contains("hedra: note:") && e.contains("NURBS patches"),
        "{e}"
    );
}

/// `info --to-nurbs` reports what Object ▸ Convert ▸ To NURBS would make of
/// each Catmull-Clark mesh: the cup's patches, how many exact, and the
/// measured distance and angle; the history's step of a conversion made by
/// `run` says the same.
#[test]
fn info_reports_the_nurbs_conversion_figures() {
    let dir = tempfile::tempdir().unwrap();
    let cup = sample("cup.hedra.ron");
    let o = hedra(&["info", cup.to_str().unwrap(), "--to-nurbs"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with("to NURBS #1 Cup: "))
        .unwrap_or_else(|| panic!("no conversion line:\n{text}"));
    assert!(
        line.contains(" exact, ") && line.contains("largest angle"),
        "{line}"
    );

    let script = dir.path().join("convert.ron");
    std::fs::write(&script, "[ConvertSubdivisionToNurbs(node: Name(\"Cup\"))]").unwrap();
    let out = dir.path().join("converted.hedra.ron");
    let o = hedra(&[
        "run",
        script.to_str().unwrap(),
        "--input",
        cup.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let figures = line.trim_start_matches("to NURBS #1 Cup: ");
    let saved = std::fs::read_to_string(&out).unwrap();
    assert!(
        saved.contains(&format!("Convert to NURBS ({figures})")),
        "the undo step's label carries the figures: {figures}"
    );
}
