//! Curves exported as polylines keep every corner: a curve is tessellated
//! knot span by knot span, so the Koch curve of level L writes exactly its
//! `4^L + 1` points in OBJ and glTF (the 64 uniform steps of before wrote
//! level 4 as level 3: 65 points, length (4/3)³), a degree-1 NURBS of more
//! than 64 spans writes its control polygon, and a poly-Bézier keeps its C0
//! joints and a Chaikin curve its corners.

use glam::DVec3;
use hedra_doc::command::CurveSpec;
use hedra_doc::export::{ExportOptions, export_bytes};
use hedra_doc::{Command, NodeContent, NodeTransform, Session};
use hedra_geom::curves::{FractalRule, Join};
use std::path::Path;

fn session_with(name: &str, curve: CurveSpec) -> Session {
    let mut s = Session::new();
    s.execute(&Command::AddCurve {
        name: name.into(),
        curve,
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s
}

fn koch(level: u32) -> CurveSpec {
    CurveSpec::Fractal {
        rule: FractalRule::Koch,
        points: vec![DVec3::ZERO, DVec3::X],
        level,
        closed: false,
        normal: DVec3::Z,
    }
}

/// The points of the first `l` polyline of an OBJ file, in order.
fn obj_polyline(bytes: &[u8]) -> Vec<DVec3> {
    let text = std::str::from_utf8(bytes).unwrap();
    let vertices: Vec<DVec3> = text
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let c: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            DVec3::new(c[0], c[1], c[2])
        })
        .collect();
    let line = text
        .lines()
        .find_map(|l| l.strip_prefix("l "))
        .expect("an `l` record");
    line.split_whitespace()
        .map(|i| vertices[i.parse::<usize>().unwrap() - 1])
        .collect()
}

/// The points of the first line-strip primitive of a GLB file, in order.
fn glb_polyline(bytes: &[u8]) -> Vec<DVec3> {
    let gltf = gltf::Gltf::from_slice(bytes).unwrap();
    let blob = gltf.blob.clone().expect("a GLB holds its buffer");
    let primitive = gltf
        .document
        .meshes()
        .flat_map(|m| m.primitives().collect::<Vec<_>>())
        .find(|p| p.mode() == gltf::mesh::Mode::LineStrip)
        .expect("a line strip");
    let reader = primitive.reader(|_| Some(&blob));
    reader
        .read_positions()
        .unwrap()
        .map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64))
        .collect()
}

fn length(points: &[DVec3]) -> f64 {
    points.windows(2).map(|w| (w[1] - w[0]).length()).sum()
}

/// The curve node's kind's level polygon (Koch, Chaikin).
fn level_polygon(s: &Session, name: &str) -> Vec<DVec3> {
    match &s.doc.find_by_name(name).unwrap().content {
        NodeContent::Curve(c) => c.kind().level_polygon().unwrap(),
        other => panic!("{}", other.kind()),
    }
}

fn exported(s: &Session, file: &str) -> Vec<DVec3> {
    let bytes = export_bytes(&s.doc, Path::new(file), ExportOptions::default()).unwrap();
    if file.ends_with(".obj") {
        obj_polyline(&bytes)
    } else {
        glb_polyline(&bytes)
    }
}

#[test]
fn the_koch_curve_exports_exactly_its_points_in_obj_and_gltf() {
    for (level, count) in [(4u32, 257usize), (5, 1025)] {
        let s = session_with("Koch", koch(level));
        let exact = level_polygon(&s, "Koch");
        assert_eq!(exact.len(), count);
        let want_length = (4.0f64 / 3.0).powi(level as i32);
        assert!((length(&exact) - want_length).abs() < 1e-12);
        for (file, tol) in [("k.obj", 1e-12), ("k.glb", 1e-6)] {
            let points = exported(&s, file);
            assert_eq!(points.len(), count, "level {level}, {file}");
            for (k, (p, q)) in points.iter().zip(&exact).enumerate() {
                assert!((*p - *q).length() < tol, "{file} point {k}: {p} vs {q}");
            }
            let l = length(&points);
            assert!(
                (l - want_length).abs() < 1e3 * tol,
                "level {level}, {file}: length {l}, want {want_length}"
            );
        }
    }
}

#[test]
fn a_degree_one_nurbs_of_many_spans_keeps_every_corner() {
    // 100 spans of a zigzag: more than the 64 uniform steps of before.
    let points: Vec<DVec3> = (0..=100)
        .map(|i| DVec3::new(i as f64 * 0.1, (i % 2) as f64 * 0.3, 0.0))
        .collect();
    let s = session_with(
        "Zigzag",
        CurveSpec::Nurbs {
            degree: 1,
            points: points.clone(),
            weights: None,
            knots: None,
        },
    );
    for file in ["z.obj", "z.glb"] {
        let out = exported(&s, file);
        assert_eq!(out.len(), 101, "{file}");
        for (p, q) in out.iter().zip(&points) {
            assert!((*p - *q).length() < 1e-6, "{file}: {p} vs {q}");
        }
    }
}

#[test]
fn a_poly_bezier_keeps_its_c0_joints_and_a_chaikin_curve_its_corners() {
    let v = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    // Three segments meeting at two sharp corners (joints at anchors 3, 6).
    let points = vec![
        v(0.0, 0.0),
        v(1.0, 1.0),
        v(2.0, 1.0),
        v(3.0, 0.0),
        v(3.0, 1.0),
        v(4.0, 1.0),
        v(4.2, 0.0),
        v(5.0, 1.0),
        v(6.0, 1.0),
        v(7.0, 0.0),
    ];
    let s = session_with(
        "Corners",
        CurveSpec::PolyBezier {
            points: points.clone(),
            joins: Some(vec![Join::C0, Join::C0]),
            closed: false,
        },
    );
    for file in ["p.obj", "p.glb"] {
        let out = exported(&s, file);
        for anchor in [0, 3, 6, 9] {
            let nearest = out
                .iter()
                .map(|p| (*p - points[anchor]).length())
                .fold(f64::INFINITY, f64::min);
            assert!(nearest < 1e-6, "{file}: anchor {anchor} is {nearest} away");
        }
    }
    // Chaikin at level 5 of a zigzag: 4 · 2^5 + 2 = 130 points, a polyline.
    let s = session_with(
        "Cut",
        CurveSpec::Chaikin {
            points: vec![
                v(0.0, 0.0),
                v(1.0, 1.0),
                v(2.0, 0.0),
                v(3.0, 1.0),
                v(4.0, 0.0),
            ],
            level: 5,
            closed: false,
        },
    );
    let exact = level_polygon(&s, "Cut");
    assert!(exact.len() > 65, "{}", exact.len());
    for file in ["c.obj", "c.glb"] {
        let out = exported(&s, file);
        assert_eq!(out.len(), exact.len(), "{file}");
        for (p, q) in out.iter().zip(&exact) {
            assert!((*p - *q).length() < 1e-6, "{file}: {p} vs {q}");
        }
    }
}
