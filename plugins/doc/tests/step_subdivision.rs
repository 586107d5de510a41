//! A Catmull-Clark cage converted to NURBS (`ConvertSubdivisionToNurbs`)
//! and exported to STEP is one closed solid in OpenCASCADE
//! (`scripts/step_read.py`): valid, one closed shell, no free edges, and
//! the volume of the limit surface within 1e-4. The document holds only
//! separate surface nodes after the conversion, so the writer finds the
//! topology from the geometry: a packed rectangle's side that runs along
//! several smaller patches is cut at their corners (`step::brep`).
//!
//! The reference volume does not come from the patches: it is the volume
//! of the polyhedra through the limit points of the cage refined `n` and
//! `n + 1` times, extrapolated (their error falls as 4^-level), with the
//! change from the extrapolation one level coarser as its error bound.

use hedra_doc::step::{StepOptions, to_step};
use hedra_doc::{Command, NodeContent, Session};
use hedra_geom::subdivision::to_nurbs::ToNurbsOptions;
use hedra_geom::subdivision::{Refiner, limit_positions};
use serde_json::Value;
use std::path::Path;
use std::process::Command as Process;

fn run(session: &mut Session, text: &str) {
    let cmds: Vec<Command> =
        hedra_doc::script::parse(&format!("[{text}]"), Path::new("test")).expect("a command");
    session
        .execute(&cmds[0])
        .unwrap_or_else(|e| panic!("{text}: {e}"));
}

/// What OpenCASCADE reads from `file`.
fn ocp(file: &Path) -> Value {
    let ok = Process::new("python3")
        .args(["-c", "import OCP.STEPControl"])
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        ok,
        "python3 cannot import 'OCP' (cadquery-ocp-novtk): run scripts/setup (it installs scripts/requirements.txt)"
    );
    let script =
        Path::new(&std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"))
            .join("../../scripts/step_read.py");
    let o = Process::new("python3")
        .arg(script)
        .arg(file)
        .output()
        .expect("python3 runs");
    assert!(
        o.status.success(),
        "step_read.py failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("step_read.py prints JSON")
}

/// The limit surface's volume of mesh node `name` (in world space) and
/// a bound on its error: limit polyhedra at the three finest levels with
/// at most about a million faces, the last two extrapolated, and the
/// difference from the extrapolation one level coarser as the bound.
fn limit_volume(session: &Session, name: &str) -> (f64, f64) {
    let node = session.doc.find_by_name(name).unwrap();
    let NodeContent::Mesh(content) = &node.content else {
        panic!("{name} is a mesh");
    };
    let cage = content.smooth_cage().unwrap().unwrap();
    let options = content.subdivision.unwrap().options;
    let faces = cage.mesh.faces().count() as f64;
    let fine = (1..=7u32)
        .take_while(|&l| faces * 4f64.powi(l as i32) <= 1.0e6)
        .last()
        .unwrap();
    let at = |level| {
        let r = Refiner::new(&cage.mesh, &cage.creases, options, level).unwrap();
        let points = r.refine(&r.cage_positions(&cage.mesh));
        let limit = limit_positions(&r, &points).unwrap();
        r.to_mesh(&limit).unwrap().0.volume()
    };
    let (v0, v1, v2) = (at(fine - 2), at(fine - 1), at(fine));
    let world = session.doc.hierarchy().facts(node.id).unwrap().world;
    let scale = world.determinant().abs();
    let (e1, e2) = ((4.0 * v1 - v0) / 3.0, (4.0 * v2 - v1) / 3.0);
    (e2 * scale, (e2 - e1).abs() * scale)
}

/// How the cage reaches the STEP file.
#[derive(Clone, Copy, PartialEq)]
enum Route {
    /// `ConvertSubdivisionToNurbs`, then the surface nodes are exported.
    Command,
    /// The mesh node is exported with `StepOptions::subdivision_as_nurbs`.
    Option,
}

/// Builds the cage with `setup`, converts it (`route`), exports the
/// document and checks what OpenCASCADE reads, with the Euler
/// characteristic V − E + F = 2 − 2 `genus` of the written topology;
/// returns the figures for the message.
fn check(label: &str, setup: &[&str], route: Route, genus: i64) -> String {
    let mut s = Session::new();
    for text in setup {
        run(&mut s, text);
    }
    check_node(label, s, "Cage", route, genus)
}

/// [`check`] for the mesh node `name` of session `s`.
fn check_node(label: &str, mut s: Session, name: &str, route: Route, genus: i64) -> String {
    let (reference, correction) = limit_volume(&s, name);
    let options = StepOptions {
        subdivision_as_nurbs: route == Route::Option,
        ..StepOptions::default()
    };
    if route == Route::Command {
        run(
            &mut s,
            &format!("ConvertSubdivisionToNurbs(node: Name(\"{name}\"), keep_cage: false)"),
        );
    }
    let (bytes, notes) = to_step(&s.doc, options, "cage.step").unwrap();
    let patches = match route {
        Route::Command => s
            .doc
            .nodes()
            .filter(|n| matches!(n.content, NodeContent::Surface(_)))
            .count(),
        Route::Option => {
            // The note gives the patch count.
            let note = notes
                .iter()
                .find(|n| n.starts_with(&format!("'{name}' written as its limit surface: ")))
                .unwrap_or_else(|| panic!("{label}: {notes:?}"));
            eprintln!("{label}: {note}");
            note.split(' ').nth(6).unwrap().parse().unwrap()
        }
    };
    let dir = tempfile::tempdir().unwrap();
    let file = match std::env::var_os("HEDRA_STEP_DEBUG") {
        Some(d) => Path::new(&d).join(format!("{label}.step")),
        None => dir.path().join(format!("{label}.step")),
    };
    std::fs::write(&file, &bytes).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    assert_eq!(
        text.matches("MANIFOLD_SOLID_BREP(").count(),
        1,
        "{label}: one solid ({notes:?})"
    );
    assert!(!text.contains("OPEN_SHELL("), "{label}: no open shell");
    let read = ocp(&file);
    assert_eq!(
        read["valid"], true,
        "{label}: OpenCASCADE finds the shape invalid"
    );
    assert_eq!(read["closed_shells"], 1, "{label}");
    assert_eq!(read["free_edges"], 0, "{label}: free edges");
    let faces = read["faces"].as_array().unwrap().len();
    assert_eq!(faces, patches, "{label}: a face per patch");
    let edges = text.matches("EDGE_CURVE(").count();
    let vertices = text.matches("VERTEX_POINT(").count();
    assert_eq!(
        read["edges"], edges,
        "{label}: OpenCASCADE's edges are the file's"
    );
    assert_eq!(
        vertices as i64 - edges as i64 + faces as i64,
        2 - 2 * genus,
        "{label}: V − E + F with {vertices} vertices, {edges} edges, {faces} faces"
    );
    let solids = read["solids"].as_array().unwrap();
    assert_eq!(solids.len(), 1, "{label}");
    assert_eq!(solids[0]["valid"], true, "{label}");
    let volume = solids[0]["volume"].as_f64().unwrap();
    let error = (volume - reference).abs() / reference;
    assert!(
        correction < 1e-5 * reference,
        "{label}: the reference is not converged ({correction})"
    );
    assert!(
        error < 1e-4,
        "{label}: OpenCASCADE's volume {volume} against the limit's {reference}: {error:.2e}"
    );
    format!(
        "{label}: {patches} faces, {edges} edges, {vertices} vertices, volume {volume:.9} vs limit {reference:.9} (±{correction:.1e}): {error:.2e} relative"
    )
}

#[test]
fn a_converted_cube_cage_exports_as_one_valid_solid_of_the_limit_volume() {
    let figures = check(
        "cube",
        &[
            "AddPrimitive(primitive: Cube(size: 2.0), name: \"Cage\")",
            "SetSubdivision(nodes: [Name(\"Cage\")], modifier: Some(()))",
        ],
        Route::Command,
        0,
    );
    eprintln!("{figures}");
}

#[test]
fn a_mesh_with_its_modifier_exports_as_its_limit_solid_on_request() {
    let setup = [
        "AddPrimitive(primitive: Cube(size: 2.0), name: \"Cage\")",
        "SetSubdivision(nodes: [Name(\"Cage\")], modifier: Some(()))",
        "Translate(nodes: [Name(\"Cage\")], offset: (1.0, -2.0, 0.5))",
        "Scale(nodes: [Name(\"Cage\")], factor: (1.5, 1.0, 0.5))",
    ];
    let figures = check("cube-option", &setup, Route::Option, 0);
    eprintln!("{figures}");
    // Without the option the mesh is left out, and the note says how to
    // write it.
    let mut s = Session::new();
    for text in setup {
        run(&mut s, text);
    }
    let err = to_step(&s.doc, StepOptions::default(), "cage.step").unwrap_err();
    assert!(err.to_string().contains("mesh"), "{err}");
    run(
        &mut s,
        "AddPrimitive(primitive: Cube(size: 2.0), name: \"Plain\")",
    );
    run(
        &mut s,
        "AddSurface(name: \"Sheet\", surface: Sphere(radius: 1.0))",
    );
    let (_, notes) = to_step(&s.doc, StepOptions::default(), "cage.step").unwrap();
    assert!(
        notes
            .iter()
            .any(|n| n.starts_with("1 of them have a subdivision modifier")),
        "{notes:?}"
    );
}

#[test]
fn a_cube_subdivided_once_and_a_creased_cube_export_as_valid_solids() {
    let once = check(
        "cube-once",
        &[
            "AddPrimitive(primitive: Cube(size: 2.0), name: \"Cage\")",
            "ApplySubdivision(node: Name(\"Cage\"), levels: Some(1))",
            "SetSubdivision(nodes: [Name(\"Cage\")], modifier: Some(()))",
        ],
        Route::Command,
        0,
    );
    let creased = check(
        "cube-creased",
        &[
            "AddPrimitive(primitive: Cube(size: 2.0), name: \"Cage\")",
            "SetSubdivision(nodes: [Name(\"Cage\")], modifier: Some(()))",
            "SetEdgeCrease(node: Name(\"Cage\"), edges: OfFaces(Facing(direction: (0.0, 1.0, 0.0), degrees: 1.0)), sharpness: 10.0)",
        ],
        Route::Command,
        0,
    );
    eprintln!("{once}\n{creased}");
}

#[test]
fn a_converted_torus_cage_exports_as_one_valid_solid() {
    let figures = check(
        "torus",
        &[
            "AddPrimitive(primitive: Torus(major_segments: 12, minor_segments: 8, major_radius: 2.0, minor_radius: 0.7), name: \"Cage\")",
            "SetSubdivision(nodes: [Name(\"Cage\")], modifier: Some(()))",
        ],
        Route::Command,
        1,
    );
    eprintln!("{figures}");
}

#[test]
fn cages_with_triangles_and_polygons_export_as_valid_solids() {
    // Triangle fans at a UV sphere's poles, hexagon and 12-gon caps on a
    // cylinder, and all triangles (678 patches): irregular faces
    // everywhere.
    for (label, primitive) in [
        ("uv-sphere", "UvSphere(segments: 8, rings: 5, radius: 1.0)"),
        ("cylinder", "Cylinder(segments: 6, depth: 2.0, radius: 1.0)"),
        // 12-gon caps: valence-12 centres, whose stars are refined on their
        // own to about level 8 beside level-2 patches (T-junctions).
        (
            "cylinder-12",
            "Cylinder(segments: 12, depth: 2.0, radius: 1.0)",
        ),
        ("ico-sphere", "IcoSphere(subdivisions: 1, radius: 1.0)"),
    ] {
        let figures = check(
            label,
            &[
                &format!("AddPrimitive(primitive: {primitive}, name: \"Cage\")"),
                "SetSubdivision(nodes: [Name(\"Cage\")], modifier: Some(()))",
            ],
            Route::Command,
            0,
        );
        eprintln!("{figures}");
    }
}

/// The cup sample (a 12-gon bottom: a valence-12 vertex, refined on its
/// own to about level 8; a creased rim) and the jar (infinitely sharp
/// creases): within the default tolerance and 0.5°, and one valid solid of
/// their limit volume in OpenCASCADE.
#[test]
fn the_cup_and_jar_samples_convert_within_tolerance_and_export_as_valid_solids() {
    for (sample, name) in [("cup", "Cup"), ("jar", "Jar")] {
        let path = Path::new(&std::env::var("CARGO_MANIFEST_DIR").unwrap())
            .join(format!("../../assets/samples/{sample}.hedra.ron"));
        let s = hedra_doc::file::load(&path).unwrap().session;
        let NodeContent::Mesh(content) = &s.doc.find_by_name(name).unwrap().content else {
            panic!("{name} is a mesh");
        };
        let c = content
            .limit_nurbs(hedra_doc::command::DEFAULT_NURBS_TOLERANCE, name)
            .unwrap();
        let cage = content.smooth_cage().unwrap().unwrap();
        let to = ToNurbsOptions::relative(&cage.mesh, 1e-4);
        assert!(c.within(&to), "{sample}: {:?}", c.report);
        eprintln!(
            "{sample}: levels {}–{}, {:?}, {:?}",
            c.level,
            c.deepest_level,
            c.counts(),
            c.report
        );
        let figures = check_node(sample, s, name, Route::Command, 0);
        eprintln!("{figures}");
    }
}
