//! STEP exports read by OpenCASCADE (cadquery-ocp, `scripts/step_read.py`,
//! installed by `scripts/setup` from `scripts/requirements.txt`): every
//! export reads, its shape checker finds it valid, and the surfaces and
//! curves it evaluates on a grid of parameters equal Hedra's world-space
//! evaluation to 1e-9 m, in metres and in millimetres. Then Hedra reads the
//! file back and gets the same control points, weights, knots, degrees and
//! names. Without OCP the tests fail, naming the module.

use glam::{DMat4, DVec3};
use hedra_doc::step::{StepOptions, StepUnits, step_from_bytes, to_step, triangle_as_patch};
use hedra_doc::{Command, Document, NodeContent, NodeTransform, Session, SurfaceShape};
use hedra_geom::curves::Curve;
use hedra_geom::surfaces::Surface;
use hedra_geom::{NurbsCurve, NurbsSurface};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command as Process;

/// Fractions of each parameter's range the comparisons evaluate at
/// (uneven, so that curves that agree at their knots, such as a Hermite
/// and a Lagrange curve through the same points, are told apart).
const FRACTIONS: [f64; 7] = [0.0, 0.137, 0.29, 0.5, 0.713, 0.88, 1.0];

fn manifest_dir() -> PathBuf {
    PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"))
}

fn repo() -> PathBuf {
    manifest_dir().join("../..")
}

/// Fails, naming the module, when python3 cannot import OpenCASCADE.
fn require_ocp() {
    let ok = Process::new("python3")
        .args(["-c", "import OCP.STEPControl"])
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        ok,
        "python3 cannot import 'OCP' (cadquery-ocp-novtk): run scripts/setup (it installs scripts/requirements.txt)"
    );
}

/// What OpenCASCADE reads from `file`.
fn ocp(file: &Path) -> Value {
    let o = Process::new("python3")
        .arg(repo().join("scripts/step_read.py"))
        .arg(file)
        .arg(FRACTIONS.map(|f| f.to_string()).join(","))
        .output()
        .expect("python3 runs");
    assert!(
        o.status.success(),
        "step_read.py failed on {}: {}",
        file.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("step_read.py prints JSON")
}

fn v3(v: &Value) -> DVec3 {
    DVec3::new(
        v[0].as_f64().unwrap(),
        v[1].as_f64().unwrap(),
        v[2].as_f64().unwrap(),
    )
}

fn load(path: &Path) -> Document {
    hedra_doc::file::load(path)
        .unwrap_or_else(|e| panic!("{e}"))
        .session
        .doc
}

/// A visible surface or curve node as it should come out: its name and
/// its NURBS form in world space (a triangle as its collapsed patch).
enum Expected {
    Surface(String, NurbsSurface, bool),
    Curve(String, NurbsCurve),
}

fn world_surface(s: &NurbsSurface, m: DMat4) -> NurbsSurface {
    s.transformed(&m).unwrap()
}

fn expected(doc: &Document) -> Vec<Expected> {
    let tree = doc.hierarchy();
    let mut out = Vec::new();
    for &id in tree.order() {
        let node = doc.node(id).unwrap();
        let facts = tree.facts(id).unwrap();
        if !facts.visible || facts.inside_csg {
            continue;
        }
        match &node.content {
            NodeContent::Surface(s) => {
                let (local, triangle) = match &**s {
                    SurfaceShape::Nurbs(s) => (s.clone(), false),
                    SurfaceShape::Triangle(t) => (triangle_as_patch(t), true),
                };
                out.push(Expected::Surface(
                    node.name.clone(),
                    world_surface(&local, facts.world),
                    triangle,
                ))
            }
            NodeContent::Curve(c) => out.push(Expected::Curve(
                node.name.clone(),
                c.nurbs().transformed(&facts.world).unwrap(),
            )),
            _ => {}
        }
    }
    out
}

/// Hedra's own world-space points of node `name` on the grid, evaluated
/// through the document (`hedra eval`'s evaluation, in local space, then
/// the world matrix): a triangle at (u, v) = (s, (1 − s) t).
fn hedra_surface_points(doc: &Document, name: &str) -> Vec<DVec3> {
    let node = doc.find_by_name(name).unwrap();
    let world = doc.world_matrix(node.id);
    let NodeContent::Surface(shape) = &node.content else {
        unreachable!()
    };
    let mut out = Vec::new();
    for fs in FRACTIONS {
        for ft in FRACTIONS {
            let params = match &**shape {
                SurfaceShape::Nurbs(s) => {
                    let ((u0, u1), (v0, v1)) = s.domain();
                    [u0 + fs * (u1 - u0), v0 + ft * (v1 - v0)]
                }
                SurfaceShape::Triangle(_) => [fs, (1.0 - fs) * ft],
            };
            let e = hedra_doc::eval::evaluate(
                doc,
                &hedra_doc::NodeRef::Name(name.to_string()),
                &params,
            )
            .unwrap();
            out.push(world.transform_point3(DVec3::from_array(e.point)));
        }
    }
    out
}

fn hedra_curve_points(doc: &Document, name: &str) -> Vec<DVec3> {
    let node = doc.find_by_name(name).unwrap();
    let world = doc.world_matrix(node.id);
    let NodeContent::Curve(c) = &node.content else {
        unreachable!()
    };
    let (a, b) = c.nurbs().domain();
    FRACTIONS
        .iter()
        .map(|f| {
            let t = a + (b - a) * f;
            let e =
                hedra_doc::eval::evaluate(doc, &hedra_doc::NodeRef::Name(name.to_string()), &[t])
                    .unwrap();
            world.transform_point3(DVec3::from_array(e.point))
        })
        .collect()
}

fn points_of(v: &Value) -> Vec<DVec3> {
    v["points"]
        .as_array()
        .map(|a| a.iter().map(v3).collect())
        .unwrap_or_default()
}

fn close(a: &[DVec3], b: &[DVec3], tolerance: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(p, q)| p.distance(*q) <= tolerance)
}

fn knots_equal(a: &[f64], b: &[Value]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| (x - y.as_f64().unwrap()).abs() <= 1e-12 * x.abs().max(1.0))
}

/// Exports `doc` in `units`, has OpenCASCADE read it and compares; reads
/// it back with Hedra and compares. Returns OpenCASCADE's answer.
fn check_round_trip(label: &str, doc: &Document, units: StepUnits, dir: &Path) -> Value {
    let (bytes, _notes) = to_step(
        doc,
        StepOptions {
            units,
            meshes: false,
            subdivision_as_nurbs: false,
        },
        &format!("{label}.step"),
    )
    .unwrap_or_else(|e| panic!("{label}: {e}"));
    let file = dir.join(format!("{label}-{units:?}.step"));
    std::fs::write(&file, &bytes).unwrap();
    let read = ocp(&file);
    assert_eq!(
        read["read"],
        true,
        "{label}: OpenCASCADE cannot read {}",
        file.display()
    );
    assert_eq!(
        read["valid"], true,
        "{label} {units:?}: the shape checker finds the shape invalid"
    );
    let unit = read["length_unit"][0].as_str().unwrap_or("").to_string();
    match units {
        StepUnits::Metres => assert_eq!(unit, "metre", "{label}"),
        StepUnits::Millimetres => assert_eq!(unit, "millimetre", "{label}"),
    }
    let expected = expected(doc);
    let faces = read["faces"].as_array().unwrap();
    let curves = read["curves"].as_array().unwrap();
    let surfaces = expected
        .iter()
        .filter(|e| matches!(e, Expected::Surface(..)))
        .count();
    assert_eq!(faces.len(), surfaces, "{label}: one face per surface node");
    let ncurves = expected.len() - surfaces;
    assert_eq!(curves.len(), ncurves, "{label}: one curve per curve node");
    for e in &expected {
        match e {
            Expected::Surface(name, s, triangle) => {
                let ours = hedra_surface_points(doc, name);
                let face = faces
                    .iter()
                    .find(|f| close(&points_of(f), &ours, 1e-9))
                    .unwrap_or_else(|| {
                        panic!(
                            "{label} {units:?}: no face of OpenCASCADE's has the points of '{name}' (first {:?}, theirs {:?})",
                            ours[0],
                            faces.iter().map(|f| points_of(f).first().copied()).collect::<Vec<_>>()
                        )
                    });
                assert_eq!(face["valid"], true, "{label}: face '{name}'");
                let (du, dv) = s.degrees();
                assert_eq!(
                    face["degrees"],
                    serde_json::json!([du, dv]),
                    "{label}: '{name}'"
                );
                // OpenCASCADE makes a closed direction periodic (the
                // same points, other poles and knots): compare the data
                // where it did not.
                let (ku, kv) = s.knots();
                let periodic = [0, 1].map(|k| face["periodic"][k] == true);
                if !periodic[0] {
                    assert!(
                        knots_equal(ku, face["knots_u"].as_array().unwrap()),
                        "{label}: '{name}' u knots"
                    );
                }
                if !periodic[1] {
                    assert!(
                        knots_equal(kv, face["knots_v"].as_array().unwrap()),
                        "{label}: '{name}' v knots"
                    );
                }
                if periodic == [false, false] {
                    let poles: Vec<DVec3> =
                        face["poles"].as_array().unwrap().iter().map(v3).collect();
                    assert!(close(&poles, s.points(), 1e-9), "{label}: '{name}' poles");
                }
                // OpenCASCADE calls weights within 1e-9 of each other
                // polynomial.
                if s.weights().iter().any(|&w| (w - 1.0).abs() > 1e-6) {
                    assert_eq!(face["rational"], true, "{label}: '{name}'");
                }
                let _ = triangle;
            }
            Expected::Curve(name, c) => {
                let ours = hedra_curve_points(doc, name);
                let curve = curves
                    .iter()
                    .find(|f| close(&points_of(f), &ours, 1e-9))
                    .unwrap_or_else(|| panic!("{label} {units:?}: no curve of OpenCASCADE's has the points of '{name}'"));
                assert_eq!(curve["degree"], c.degree(), "{label}: '{name}'");
                if curve["periodic"] != true {
                    assert!(
                        knots_equal(c.knots(), curve["knots"].as_array().unwrap()),
                        "{label}: '{name}' knots"
                    );
                }
            }
        }
    }
    // Back into Hedra: the same nodes, in world space, in metres.
    let imported = step_from_bytes(&bytes, &file.display().to_string())
        .unwrap_or_else(|e| panic!("{label}: {e}"));
    assert_eq!(
        imported.len(),
        expected.len(),
        "{label}: one node per surface and curve"
    );
    // Hedra's faces are bounded by their natural boundaries: none is
    // taken for trimmed.
    let notes = hedra_doc::import::describe_repairs(&imported).join("\n");
    assert!(!notes.contains("trims"), "{label}: {notes}");
    let scale = match units {
        StepUnits::Metres => 0.0,
        StepUnits::Millimetres => 1e-12,
    };
    for e in &expected {
        let name = match e {
            Expected::Surface(n, ..) | Expected::Curve(n, _) => n,
        };
        let node = imported
            .iter()
            .find(|m| &m.name == name)
            .unwrap_or_else(|| panic!("{label}: '{name}' did not come back"));
        let same = |a: &[DVec3], b: &[DVec3]| {
            a.len() == b.len()
                && a.iter()
                    .zip(b)
                    .all(|(p, q)| p.distance(*q) <= scale * p.length().max(1.0))
        };
        match (e, &node.content) {
            (Expected::Surface(_, s, _), Some(NodeContent::Surface(got))) => {
                let SurfaceShape::Nurbs(got) = &**got else {
                    panic!("{label}: '{name}' came back as a triangle")
                };
                assert_eq!(got.degrees(), s.degrees(), "{label}: '{name}'");
                assert_eq!(got.size(), s.size(), "{label}: '{name}'");
                assert_eq!(got.knots(), s.knots(), "{label}: '{name}'");
                assert_eq!(got.weights(), s.weights(), "{label}: '{name}'");
                assert!(
                    same(got.points(), s.points()),
                    "{label}: '{name}' control points"
                );
            }
            (Expected::Curve(_, c), Some(NodeContent::Curve(got))) => {
                let got = got.nurbs();
                assert_eq!(got.degree(), c.degree(), "{label}: '{name}'");
                assert_eq!(got.knots(), c.knots(), "{label}: '{name}'");
                assert_eq!(got.weights(), c.weights(), "{label}: '{name}'");
                assert!(
                    same(got.points(), c.points()),
                    "{label}: '{name}' control points"
                );
            }
            _ => panic!("{label}: '{name}' came back as another kind"),
        }
    }
    read
}

fn scenes() -> Vec<(String, PathBuf)> {
    let mut out = Vec::new();
    for s in ["shapes", "g1-join"] {
        out.push((
            s.to_string(),
            repo().join(format!("assets/samples/{s}.hedra.ron")),
        ));
    }
    for s in [
        "v2-curve-kinds",
        "v2-constructions",
        "v2-patches",
        "v3-every-command",
    ] {
        out.push((
            s.to_string(),
            manifest_dir().join(format!("tests/corpus/scenes/{s}.hedra.ron")),
        ));
    }
    out
}

#[test]
fn opencascade_reads_every_nurbs_scene_and_evaluates_it_as_hedra_does_and_hedra_reads_it_back() {
    require_ocp();
    let dir = tempfile::tempdir().unwrap();
    let dir = debug_dir(&dir);
    for (label, path) in scenes() {
        let doc = load(&path);
        for units in [StepUnits::Metres, StepUnits::Millimetres] {
            check_round_trip(&label, &doc, units, &dir);
        }
    }
}

/// The folder the exports go to: `HEDRA_STEP_DIR` when set (to look at
/// them), else the temporary one.
fn debug_dir(temp: &tempfile::TempDir) -> PathBuf {
    match std::env::var_os("HEDRA_STEP_DIR") {
        Some(d) => {
            std::fs::create_dir_all(&d).unwrap();
            PathBuf::from(d)
        }
        None => temp.path().to_path_buf(),
    }
}

/// The six faces of the cube [−½, ½]³ as bicubic Bézier patches (the
/// bilinear face with its points spread evenly), `S_u × S_v` outward, or
/// inward with each patch's u and v swapped.
fn cube_faces(outward: bool) -> Vec<Vec<DVec3>> {
    let c = |x: f64, y: f64, z: f64| DVec3::new(x, y, z) - DVec3::splat(0.5);
    // Corners (u0v0, u0v1, u1v0, u1v1), S_u × S_v outward.
    let faces = [
        [c(0., 0., 0.), c(1., 0., 0.), c(0., 1., 0.), c(1., 1., 0.)],
        [c(0., 0., 1.), c(0., 1., 1.), c(1., 0., 1.), c(1., 1., 1.)],
        [c(0., 0., 0.), c(0., 0., 1.), c(1., 0., 0.), c(1., 0., 1.)],
        [c(0., 1., 0.), c(1., 1., 0.), c(0., 1., 1.), c(1., 1., 1.)],
        [c(0., 0., 0.), c(0., 1., 0.), c(0., 0., 1.), c(0., 1., 1.)],
        [c(1., 0., 0.), c(1., 0., 1.), c(1., 1., 0.), c(1., 1., 1.)],
    ];
    faces
        .iter()
        .map(|[a, b, d, e]| {
            let mut points = Vec::new();
            for i in 0..4 {
                for j in 0..4 {
                    let (s, t) = (i as f64 / 3.0, j as f64 / 3.0);
                    let (s, t) = if outward { (s, t) } else { (t, s) };
                    points.push(a.lerp(*d, s).lerp(b.lerp(*e, s), t));
                }
            }
            points
        })
        .collect()
}

/// A scene: the cube's six patches as nodes under a parent scaled by 2
/// (by −2 along x when `mirrored`), turned and moved (world volume 8), and
/// a sphere of radius 1.5.
fn solids_scene(outward: bool, mirrored: bool) -> Document {
    let mut s = Session::new();
    s.execute(&Command::AddEmpty {
        name: "Rig".into(),
        parent: None,
        transform: NodeTransform {
            translation: DVec3::new(3.0, -1.0, 2.0),
            rotation: glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.7, 1.1),
            // Mirrored: the cube's patches turn inside out in the world.
            scale: DVec3::new(if mirrored { -2.0 } else { 2.0 }, 2.0, 2.0),
        },
    })
    .unwrap();
    for (k, points) in cube_faces(outward).into_iter().enumerate() {
        s.execute(&Command::AddSurface {
            name: format!("Side {k}"),
            surface: hedra_doc::command::SurfaceSpec::Bezier {
                nu: 4,
                nv: 4,
                points,
            },
            parent: Some(hedra_doc::NodeRef::Name("Rig".into())),
            transform: NodeTransform::IDENTITY,
        })
        .unwrap();
    }
    s.execute(&Command::AddSurface {
        name: "Ball".into(),
        surface: hedra_doc::command::SurfaceSpec::Sphere { radius: 1.5 },
        parent: None,
        transform: NodeTransform::from_translation(DVec3::new(-5.0, 0.0, 0.0)),
    })
    .unwrap();
    s.doc
}

#[test]
fn patches_that_close_up_are_written_as_valid_solids_of_the_right_volume() {
    require_ocp();
    let dir = tempfile::tempdir().unwrap();
    let dir = debug_dir(&dir);
    for (outward, mirrored) in [(true, false), (false, false), (true, true)] {
        let doc = solids_scene(outward, mirrored);
        for units in [StepUnits::Metres, StepUnits::Millimetres] {
            let label = format!(
                "solids-{}{}",
                if outward { "out" } else { "in" },
                if mirrored { "-mirrored" } else { "" }
            );
            let read = check_round_trip(&label, &doc, units, &dir);
            let bytes = std::fs::read(dir.join(format!("{label}-{units:?}.step"))).unwrap();
            let text = String::from_utf8(bytes).unwrap();
            // The cube's six faces share 12 edges and 8 vertices; the
            // ball adds its seam and the seam's two end points.
            assert_eq!(text.matches("EDGE_CURVE(").count(), 13, "{label}");
            assert_eq!(text.matches("VERTEX_POINT(").count(), 10, "{label}");
            assert_eq!(text.matches("MANIFOLD_SOLID_BREP(").count(), 2, "{label}");
            assert_eq!(read["closed_shells"], 2, "{label}");
            let mut volumes: Vec<f64> = read["solids"]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| {
                    assert_eq!(s["valid"], true, "{label}: a solid is invalid");
                    s["volume"].as_f64().unwrap()
                })
                .collect();
            volumes.sort_by(f64::total_cmp);
            let ball = 4.0 / 3.0 * std::f64::consts::PI * 1.5f64.powi(3);
            assert_eq!(volumes.len(), 2, "{label}");
            assert!(
                (volumes[0] - 8.0).abs() < 1e-6,
                "{label}: cube volume {}",
                volumes[0]
            );
            assert!(
                (volumes[1] - ball).abs() < 1e-6 * ball,
                "{label}: ball volume {}",
                volumes[1]
            );
        }
    }
}

#[test]
fn meshes_are_left_out_with_a_note_or_written_as_faceted_shells() {
    require_ocp();
    let dir = tempfile::tempdir().unwrap();
    let dir = debug_dir(&dir);
    let doc = load(&manifest_dir().join("tests/corpus/scenes/v3-every-command.hedra.ron"));
    let meshes = doc
        .nodes()
        .filter(|n| matches!(n.content, NodeContent::Mesh(_)) && doc.hierarchy().is_visible(n.id))
        .count();
    assert!(meshes > 0);
    let (_, notes) = to_step(&doc, StepOptions::default(), "every.step").unwrap();
    assert!(
        notes
            .iter()
            .any(|n| n.starts_with(&format!("{meshes} mesh node(s) left out"))),
        "{notes:?}"
    );
    // A scene of meshes alone is nothing to export without them.
    let chair = load(&repo().join("assets/samples/chair.hedra.ron"));
    let e = to_step(&chair, StepOptions::default(), "chair.step").unwrap_err();
    assert!(
        e.to_string().ends_with("chair.step: nothing to export: STEP holds NURBS surfaces and curves, and the scene has none; its 1 visible mesh node(s) are written as faceted shells only when asked (--step-meshes)"),
        "{e}"
    );
    let (bytes, _) = to_step(
        &chair,
        StepOptions {
            units: StepUnits::Millimetres,
            meshes: true,
            subdivision_as_nurbs: false,
        },
        "chair.step",
    )
    .unwrap();
    let file = dir.join("chair-faceted.step");
    std::fs::write(&file, bytes).unwrap();
    let read = ocp(&file);
    assert_eq!(read["valid"], true);
    let triangles: usize = chair
        .nodes()
        .map(|n| {
            hedra_doc::export::written_counts(
                &chair,
                n.id,
                hedra_doc::export::ExportShape::Evaluated,
            )
            .unwrap()
            .map_or(0, |c| c.triangles)
        })
        .sum();
    assert_eq!(read["faces"].as_array().unwrap().len(), triangles);
    // Back into Hedra: one mesh node per mesh, named after it, with its
    // triangles and its world-space points (millimetres back to metres).
    let imported = hedra_doc::import::import_file(&file).unwrap();
    let tree = chair.hierarchy();
    let meshes: Vec<&hedra_doc::Node> = chair
        .nodes()
        .filter(|n| matches!(n.content, NodeContent::Mesh(_)) && tree.is_visible(n.id))
        .collect();
    assert_eq!(imported.len(), meshes.len());
    for node in meshes {
        let got = imported
            .iter()
            .find(|m| m.name == node.name)
            .unwrap_or_else(|| panic!("'{}' did not come back", node.name));
        let mesh = got.mesh.as_ref().expect("a mesh");
        let counts = hedra_doc::export::written_counts(
            &chair,
            node.id,
            hedra_doc::export::ExportShape::Evaluated,
        )
        .unwrap()
        .unwrap();
        assert_eq!(mesh.face_count(), counts.triangles, "'{}'", node.name);
        assert!(got.report.is_clean(), "'{}': {:?}", node.name, got.report);
        let world = tree.world_matrix(node.id);
        let NodeContent::Mesh(m) = &node.content else {
            unreachable!()
        };
        let evaluated = m
            .evaluate(m.subdivision.map_or(0, |s| s.export_level))
            .unwrap();
        for v in evaluated.mesh.vertices() {
            let want = world.transform_point3(evaluated.mesh.position(v));
            assert!(
                mesh.vertices()
                    .any(|w| mesh.position(w).distance(want) <= 1e-12 * want.length().max(1.0)),
                "'{}': {want} did not come back",
                node.name
            );
        }
    }
}

/// OpenCASCADE writes, in millimetres: a box, a cylinder and a sphere
/// turned into B-spline faces (`BRepBuilderAPI_NurbsConvert`), and a
/// free rational cubic edge.
const OCP_WRITER: &str = r#"import sys
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder, BRepPrimAPI_MakeSphere
from OCP.BRepBuilderAPI import BRepBuilderAPI_NurbsConvert, BRepBuilderAPI_MakeEdge
from OCP.STEPControl import STEPControl_Writer, STEPControl_AsIs
from OCP.gp import gp_Pnt
from OCP.OCP.collections import Array1_gp_Pnt as TColgp_Array1OfPnt, Array1_double as TColStd_Array1OfReal, Array1_int as TColStd_Array1OfInteger
from OCP.Geom import Geom_BSplineCurve
from OCP.BRep import BRep_Builder
from OCP.TopoDS import TopoDS_Compound
b = BRep_Builder(); comp = TopoDS_Compound(); b.MakeCompound(comp)
box = BRepPrimAPI_MakeBox(gp_Pnt(10, 0, 0), 20.0, 30.0, 40.0).Shape()
cyl = BRepPrimAPI_MakeCylinder(5.0, 12.0).Shape()
sph = BRepPrimAPI_MakeSphere(gp_Pnt(-30, 0, 0), 7.0).Shape()
for s in (box, cyl, sph):
    b.Add(comp, BRepBuilderAPI_NurbsConvert(s, True).Shape())
poles = TColgp_Array1OfPnt(1, 4)
for i, p in enumerate([(0, 0, 50), (10, 5, 50), (20, -5, 55), (30, 0, 50)]):
    poles.SetValue(i + 1, gp_Pnt(*p))
w = TColStd_Array1OfReal(1, 4)
for i, x in enumerate([1, 2, 0.5, 1]): w.SetValue(i + 1, x)
k = TColStd_Array1OfReal(1, 2); k.SetValue(1, 0); k.SetValue(2, 1)
m = TColStd_Array1OfInteger(1, 2); m.SetValue(1, 4); m.SetValue(2, 4)
curve = Geom_BSplineCurve(poles, w, k, m, 3)
b.Add(comp, BRepBuilderAPI_MakeEdge(curve).Edge())
wr = STEPControl_Writer()
wr.Transfer(comp, STEPControl_AsIs)
wr.Write(sys.argv[1])
"#;

#[test]
fn hedra_reads_what_opencascade_writes_with_the_same_surfaces_and_curves() {
    require_ocp();
    let dir = tempfile::tempdir().unwrap();
    let dir = debug_dir(&dir);
    let file = dir.join("occ-written.step");
    let o = Process::new("python3")
        .args(["-c", OCP_WRITER])
        .arg(&file)
        .output()
        .expect("python3 runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let read = ocp(&file);
    let nodes = hedra_doc::import::import_file(&file).unwrap_or_else(|e| panic!("{e}"));
    let faces = read["faces"].as_array().unwrap();
    let curves = read["curves"].as_array().unwrap();
    let surfaces: Vec<&NurbsSurface> = nodes
        .iter()
        .filter_map(|n| match &n.content {
            Some(NodeContent::Surface(s)) => match &**s {
                SurfaceShape::Nurbs(s) => Some(s),
                SurfaceShape::Triangle(_) => None,
            },
            _ => None,
        })
        .collect();
    // Box 6, cylinder 3, sphere 1.
    assert_eq!(surfaces.len(), 10);
    assert_eq!(faces.len(), 10);
    for face in faces {
        let theirs = points_of(face);
        let found = surfaces.iter().any(|s| {
            let ((u0, u1), (v0, v1)) = s.domain();
            let ours: Vec<DVec3> = FRACTIONS
                .iter()
                .flat_map(|&fu| {
                    FRACTIONS.map(|fv| s.evaluate(u0 + fu * (u1 - u0), v0 + fv * (v1 - v0)).p)
                })
                .collect();
            close(&ours, &theirs, 1e-9)
        });
        assert!(
            found,
            "no imported surface has the points of {:?}",
            theirs.first()
        );
    }
    let hedra_curves: Vec<NurbsCurve> = nodes
        .iter()
        .filter_map(|n| match &n.content {
            Some(NodeContent::Curve(c)) => Some((**c.nurbs()).clone()),
            _ => None,
        })
        .collect();
    assert_eq!(hedra_curves.len(), 1);
    assert_eq!(curves.len(), 1);
    let c = &hedra_curves[0];
    assert!(!c.is_polynomial(), "the weights came through");
    let (a, b) = c.domain();
    let ours: Vec<DVec3> = FRACTIONS.iter().map(|f| c.point(a + f * (b - a))).collect();
    assert!(close(&ours, &points_of(&curves[0]), 1e-9));
    // Millimetres became metres: the box is 0.02 × 0.03 × 0.04 m.
    assert!(
        surfaces
            .iter()
            .any(|s| s.points().iter().any(|p| (p.x - 0.03).abs() < 1e-12))
    );
    let notes = hedra_doc::import::describe_repairs(&nodes).join("\n");
    assert!(
        notes.contains("not imported: the trims of 2 face(s)"),
        "the cylinder's discs are trimmed planes: {notes}"
    );
}

#[test]
fn step_and_stp_paths_export_and_import_through_the_common_entry_points() {
    let doc = load(&repo().join("assets/samples/g1-join.hedra.ron"));
    let dir = tempfile::tempdir().unwrap();
    for ext in ["step", "stp", "STEP"] {
        let path = dir.path().join(format!("join.{ext}"));
        let bytes = hedra_doc::export::export_bytes(
            &doc,
            &path,
            hedra_doc::export::ExportOptions::default(),
        )
        .unwrap();
        assert!(bytes.starts_with(b"ISO-10303-21;"));
        std::fs::write(&path, bytes).unwrap();
        let nodes = hedra_doc::import::import_file(&path).unwrap();
        assert_eq!(nodes.len(), expected(&doc).len(), "{ext}");
        // Imported into a session, they are surface and curve nodes.
        let mut s = Session::new();
        s.import(&nodes, "Import");
        assert_eq!(s.doc.node_count(), nodes.len());
        assert!(
            s.doc
                .nodes()
                .all(|n| matches!(n.content, NodeContent::Surface(_) | NodeContent::Curve(_)))
        );
    }
}

#[test]
fn every_sample_with_its_meshes_reads_in_opencascade_and_comes_back_node_for_node() {
    require_ocp();
    let dir = tempfile::tempdir().unwrap();
    let dir = debug_dir(&dir);
    let mut samples: Vec<PathBuf> = std::fs::read_dir(repo().join("assets/samples"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.to_string_lossy().ends_with(".hedra.ron"))
        .collect();
    samples.sort();
    assert!(samples.len() >= 7);
    for path in samples {
        let label = path
            .file_name()
            .unwrap()
            .to_string_lossy()
            .replace(".hedra.ron", "");
        let doc = load(&path);
        let (bytes, _) = to_step(
            &doc,
            StepOptions {
                units: StepUnits::Metres,
                meshes: true,
                subdivision_as_nurbs: false,
            },
            &format!("{label}.step"),
        )
        .unwrap_or_else(|e| panic!("{label}: {e}"));
        let file = dir.join(format!("{label}-all.step"));
        std::fs::write(&file, &bytes).unwrap();
        let read = ocp(&file);
        assert_eq!(
            read["valid"], true,
            "{label}: the shape checker finds it invalid"
        );
        // What was written: surfaces, curves, and each visible mesh or CSG
        // solid (not inside a CSG node).
        let tree = doc.hierarchy();
        let written: Vec<&str> = doc
            .nodes()
            .filter(|n| {
                let f = tree.facts(n.id).unwrap();
                f.visible && !f.inside_csg && !matches!(n.content, NodeContent::Empty)
            })
            .map(|n| n.name.as_str())
            .collect();
        let imported = step_from_bytes(&bytes, &label).unwrap_or_else(|e| panic!("{e}"));
        let mut names: Vec<&str> = imported.iter().map(|m| m.name.as_str()).collect();
        let mut want = written.clone();
        names.sort_unstable();
        want.sort_unstable();
        assert_eq!(
            names, want,
            "{label}: every written node comes back, by name"
        );
    }
}

/// A kept (non-manifold) mesh written as a faceted shell: OpenCASCADE
/// reads it valid, one face per triangle, the spine an edge of three
/// faces; read back into Hedra it is kept again, its crowded edge named.
#[test]
fn a_kept_mesh_is_written_as_facets_and_comes_back_kept() {
    let dir = tempfile::tempdir().unwrap();
    let mut session = Session::new();
    let fin: Command = ron::from_str(
        "AddKeptMesh(name: \"Fin\", positions: [(0.0, 0.0, 0.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0), (1.0, 0.0, 1.0), (0.0, 1.0, 0.0), (0.0, 1.0, 1.0), (-1.0, 0.0, 0.0), (-1.0, 0.0, 1.0)], faces: [[0, 2, 3, 1], [1, 5, 4, 0], [0, 6, 7, 1]])",
    )
    .unwrap();
    session.execute(&fin).unwrap();
    let (bytes, _) = to_step(
        &session.doc,
        StepOptions {
            units: StepUnits::Metres,
            meshes: true,
            subdivision_as_nurbs: false,
        },
        "fin.step",
    )
    .unwrap();
    let file = dir.path().join("fin.step");
    std::fs::write(&file, bytes).unwrap();
    let read = ocp(&file);
    assert_eq!(read["valid"], true, "{read}");
    assert_eq!(read["faces"].as_array().unwrap().len(), 6);
    let imported = hedra_doc::import::import_file(&file).unwrap();
    let mut back = Session::new();
    back.import(&imported, "Import");
    let NodeContent::Kept(k) = &back.doc.nodes().next().unwrap().content else {
        panic!("kept again")
    };
    assert_eq!(k.mesh.faces.len(), 6);
    assert_eq!(k.mesh.places().crowded_edges.len(), 1);
}
