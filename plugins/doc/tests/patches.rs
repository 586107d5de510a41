//! Coons patches and Gordon surfaces as nodes that follow their curves
//! (issue 20): they interpolate their input curves in world space, follow
//! a moved control point in one undo step, and refusals name the curves.

use glam::{DQuat, DVec3};
use hedra_doc::command::CurveSpec;
use hedra_doc::construction::{Construction, ConstructionError, Output, Recipe};
use hedra_doc::{
    Command, CommandError, NodeContent, NodeRef, NodeTransform, Session, SurfaceShape,
};
use hedra_geom::curves::{Curve, NurbsCurve};
use hedra_geom::surfaces::{NurbsSurface, Surface};

fn name(n: &str) -> NodeRef {
    NodeRef::Name(n.into())
}

/// Adds a Bézier curve node whose world points are `world` under
/// `transform` (the local points are `world` pulled back through it).
fn add_bezier(s: &mut Session, n: &str, world: &[DVec3], transform: NodeTransform) {
    let inverse = transform.to_matrix().inverse();
    s.execute(&Command::AddCurve {
        name: n.into(),
        curve: CurveSpec::Bezier {
            points: world.iter().map(|&p| inverse.transform_point3(p)).collect(),
        },
        parent: None,
        transform,
    })
    .unwrap();
}

fn turned(angle: f64, at: DVec3) -> NodeTransform {
    NodeTransform {
        translation: at,
        rotation: DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 0.5).normalize(), angle),
        scale: DVec3::new(1.0, 1.5, 0.75),
    }
}

fn world_curve(s: &Session, n: &str) -> NurbsCurve {
    let node = s.doc.find_by_name(n).unwrap();
    let NodeContent::Curve(c) = &node.content else {
        panic!("{n} is not a curve")
    };
    c.nurbs().transformed(&s.doc.world_matrix(node.id)).unwrap()
}

fn surface(s: &Session, n: &str) -> NurbsSurface {
    let node = s.doc.find_by_name(n).unwrap();
    let NodeContent::Surface(sf) = &node.content else {
        panic!("{n} is not a surface")
    };
    let SurfaceShape::Nurbs(sf) = &**sf else {
        panic!("{n} is not NURBS")
    };
    // Results are stored in world coordinates under the identity.
    assert_eq!(node.transform, NodeTransform::IDENTITY);
    sf.clone()
}

/// The largest distance, over `samples + 1` parameters, between the curve
/// and the best-matching side of the surface (either direction): a Coons
/// side is its curve with the same (affine) parameter for polynomial curves.
fn side_gap(surface: &NurbsSurface, curve: &NurbsCurve, samples: usize) -> f64 {
    let (a, b) = curve.domain();
    let sides: [&dyn Fn(f64) -> DVec3; 4] = [
        &|t| surface.point(t, 0.0),
        &|t| surface.point(t, 1.0),
        &|t| surface.point(0.0, t),
        &|t| surface.point(1.0, t),
    ];
    let mut best = f64::INFINITY;
    for side in sides {
        for reversed in [false, true] {
            let mut worst: f64 = 0.0;
            for k in 0..=samples {
                let t = k as f64 / samples as f64;
                let on_side = side(if reversed { 1.0 - t } else { t });
                worst = worst.max(on_side.distance(curve.point(a + (b - a) * t)));
            }
            best = best.min(worst);
        }
    }
    best
}

const EDGES: [&str; 4] = ["South", "North", "West", "East"];

/// Four Bézier edges of a saddle-like loop, each under its own transform,
/// the north edge running backwards, given out of order.
fn coons_session() -> Session {
    let mut s = Session::new();
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let south = [
        p(0.0, 0.0, 0.0),
        p(1.0, 0.5, 0.0),
        p(2.0, -0.3, 0.2),
        p(3.0, 0.0, 0.0),
    ];
    let east = [p(3.0, 0.0, 0.0), p(3.4, 0.4, 1.0), p(3.0, 0.0, 2.0)];
    let north = [
        p(3.0, 0.0, 2.0),
        p(2.0, -0.5, 2.3),
        p(1.0, 0.5, 2.0),
        p(0.0, 0.0, 2.0),
    ];
    let west = [p(0.0, 0.0, 0.0), p(-0.3, 0.3, 1.0), p(0.0, 0.0, 2.0)];
    add_bezier(&mut s, "South", &south, turned(0.4, p(1.0, 2.0, 3.0)));
    add_bezier(&mut s, "North", &north, turned(-0.9, p(-2.0, 0.0, 1.0)));
    add_bezier(&mut s, "West", &west, NodeTransform::IDENTITY);
    add_bezier(&mut s, "East", &east, turned(2.0, p(0.0, 5.0, 0.0)));
    s.execute(&Command::MakeFromCurves {
        name: "Patch".into(),
        construction: Construction {
            recipe: Recipe::Coons {
                boundaries: EDGES.map(name),
            },
            output: Output::Nurbs,
        },
    })
    .unwrap();
    s
}

fn coons_gap(s: &Session) -> f64 {
    let patch = surface(s, "Patch");
    EDGES
        .iter()
        .map(|e| side_gap(&patch, &world_curve(s, e), 1000))
        .fold(0.0, f64::max)
}

#[test]
fn a_coons_node_interpolates_its_four_boundary_nodes_in_world_space() {
    let s = coons_session();
    let gap = coons_gap(&s);
    assert!(gap < 1e-12, "{gap}");
    // And it is a patch, not a side: its middle is off every boundary.
    let middle = surface(&s, "Patch").point(0.5, 0.5);
    assert!(middle.distance(world_curve(&s, "West").point(0.5)) > 0.5);
}

#[test]
fn a_coons_node_follows_a_moved_boundary_point_in_one_undo_step() {
    let mut s = coons_session();
    let before = surface(&s, "Patch");
    let steps = s.history.done().len();
    let south = s.doc.find_by_name("South").unwrap();
    let NodeContent::Curve(c) = &south.content else {
        panic!()
    };
    let moved = c.control_points()[1] + DVec3::new(0.3, 0.8, -0.4);
    s.execute(&Command::SetControlPoints {
        node: name("South"),
        points: vec![(1, moved)],
    })
    .unwrap();
    assert_eq!(s.history.done().len(), steps + 1, "one undo step");
    let after = surface(&s, "Patch");
    assert_ne!(before, after, "the patch was made again");
    let gap = coons_gap(&s);
    assert!(gap < 1e-12, "follows the moved edge: {gap}");
    s.undo().unwrap();
    assert_eq!(surface(&s, "Patch"), before, "undo puts the patch back");
    let gap = coons_gap(&s);
    assert!(gap < 1e-12, "{gap}");
}

#[test]
fn a_coons_mesh_output_lies_on_the_patch() {
    let mut s = coons_session();
    s.execute(&Command::SetConstruction {
        node: name("Patch"),
        construction: Construction {
            recipe: Recipe::Coons {
                boundaries: EDGES.map(name),
            },
            output: Output::Mesh {
                segments: 6,
                profile_segments: 10,
            },
        },
    })
    .unwrap();
    let mesh = s.doc.find_by_name("Patch").unwrap().content.mesh().unwrap();
    mesh.validate().unwrap();
    assert_eq!((mesh.face_count(), mesh.vertex_count()), (60, 77));
    // Its four corners are the loop's corners.
    let corners = [
        DVec3::ZERO,
        DVec3::new(3.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 2.0),
        DVec3::new(3.0, 0.0, 2.0),
    ];
    for c in corners {
        assert!(
            mesh.vertices().any(|v| mesh.position(v).distance(c) < 1e-9),
            "{c}"
        );
    }
}

#[test]
fn coons_boundaries_that_miss_are_refused_by_name() {
    let mut s = Session::new();
    let p = |x: f64, z: f64| DVec3::new(x, 0.0, z);
    add_bezier(
        &mut s,
        "A",
        &[p(0.0, 0.0), p(2.0, 0.0)],
        NodeTransform::IDENTITY,
    );
    add_bezier(
        &mut s,
        "B",
        &[p(2.0, 0.0), p(2.0, 2.0)],
        NodeTransform::IDENTITY,
    );
    add_bezier(
        &mut s,
        "C",
        &[p(2.0, 2.0), p(0.0, 2.0)],
        NodeTransform::IDENTITY,
    );
    // Its start is 0.3 short of A's.
    add_bezier(
        &mut s,
        "D",
        &[p(0.0, 2.0), p(0.0, 0.3)],
        NodeTransform::IDENTITY,
    );
    let err = s
        .execute(&Command::MakeFromCurves {
            name: "Gap".into(),
            construction: Construction {
                recipe: Recipe::Coons {
                    boundaries: ["A", "B", "C", "D"].map(name),
                },
                output: Output::Nurbs,
            },
        })
        .unwrap_err();
    let CommandError::Construction {
        error: ConstructionError::CoonsGap { first, second, gap },
        ..
    } = &err
    else {
        panic!("{err}")
    };
    let pair = [first.as_str(), second.as_str()];
    assert!(pair.contains(&"'A'") && pair.contains(&"'D'"), "{err}");
    assert!((gap - 0.3).abs() < 1e-12, "{err}");
    assert_eq!(
        err.to_string(),
        format!(
            "'Gap': Coons: the boundaries {first} and {second} miss each other by {gap} at a corner"
        )
    );
    assert!(s.doc.find_by_name("Gap").is_none());
    // A move that opens the loop of a made patch is refused naming the patch.
    let mut s = coons_session();
    let err = s
        .execute(&Command::Translate {
            nodes: vec![name("East")],
            offset: DVec3::new(0.0, 0.1, 0.0),
        })
        .unwrap_err();
    assert!(
        err.to_string()
            .starts_with("'Patch' (#5): Coons: the boundaries"),
        "{err}"
    );
}

/// A bicubic polynomial surface the network is cut from.
fn shape(u: f64, v: f64) -> DVec3 {
    DVec3::new(
        10.0 + 4.0 * u,
        u * (1.0 - u) * (1.0 + v) + 0.5 * v * v * (1.0 - v),
        3.0 * v + 0.3 * u * u * v,
    )
}

/// The iso-curve of [`shape`] at constant v (or u) as a cubic Bézier:
/// the polynomial's values at 0, 1/3, 2/3, 1 interpolated.
fn iso(f: impl Fn(f64) -> DVec3) -> Vec<DVec3> {
    let q: Vec<DVec3> = (0..4).map(|k| f(k as f64 / 3.0)).collect();
    // Bézier points from the values at thirds (the inverse of the
    // Bernstein matrix at 0, 1/3, 2/3, 1).
    let b1 = (-5.0 * q[0] + 18.0 * q[1] - 9.0 * q[2] + 2.0 * q[3]) / 6.0;
    let b2 = (2.0 * q[0] - 9.0 * q[1] + 18.0 * q[2] - 5.0 * q[3]) / 6.0;
    vec![q[0], b1, b2, q[3]]
}

const US: [f64; 4] = [0.0, 0.3, 0.7, 1.0];
const VS: [f64; 3] = [0.0, 0.5, 1.0];

fn gordon_session() -> Session {
    let mut s = Session::new();
    // u-curves at v = VS[k], given out of order, one reversed, under
    // transforms; v-curves at u = US[l] likewise.
    for (k, &v) in VS.iter().enumerate() {
        let mut points = iso(|u| shape(u, v));
        if k == 1 {
            points.reverse();
        }
        add_bezier(
            &mut s,
            &format!("U{k}"),
            &points,
            turned(0.3 * k as f64, DVec3::X),
        );
    }
    for (l, &u) in US.iter().enumerate() {
        let mut points = iso(|v| shape(u, v));
        if l == 2 {
            points.reverse();
        }
        add_bezier(
            &mut s,
            &format!("V{l}"),
            &points,
            turned(-0.2 * l as f64, DVec3::Y),
        );
    }
    s.execute(&Command::MakeFromCurves {
        name: "Network".into(),
        construction: Construction {
            recipe: Recipe::Gordon {
                u_curves: ["U2", "U0", "U1"].map(name).to_vec(),
                v_curves: ["V1", "V3", "V0", "V2"].map(name).to_vec(),
            },
            output: Output::Nurbs,
        },
    })
    .unwrap();
    s
}

/// The largest distance from 1000 samples of `curve` to the surface's
/// iso-curve at the fixed parameter `at` (in u when `along_u`).
fn iso_gap(surface: &NurbsSurface, curve: &NurbsCurve, along_u: bool, at: f64) -> f64 {
    let (a, b) = curve.domain();
    let mut best = f64::INFINITY;
    for reversed in [false, true] {
        let mut worst: f64 = 0.0;
        for k in 0..=1000 {
            let t = k as f64 / 1000.0;
            let s = if reversed { 1.0 - t } else { t };
            let p = if along_u {
                surface.point(s, at)
            } else {
                surface.point(at, s)
            };
            worst = worst.max(p.distance(curve.point(a + (b - a) * t)));
        }
        best = best.min(worst);
    }
    best
}

#[test]
fn a_gordon_node_interpolates_every_network_curve() {
    let s = gordon_session();
    let g = surface(&s, "Network");
    // The network is cut from one polynomial surface at known parameters,
    // so the crossings fall at those: check each curve along its iso-line.
    let mut worst: f64 = 0.0;
    for (k, &v) in VS.iter().enumerate() {
        worst = worst.max(iso_gap(&g, &world_curve(&s, &format!("U{k}")), true, v));
    }
    for (l, &u) in US.iter().enumerate() {
        worst = worst.max(iso_gap(&g, &world_curve(&s, &format!("V{l}")), false, u));
    }
    assert!(worst < 1e-9, "{worst}");
    // Moving a crossing's neighbourhood together keeps interpolating: a
    // transform on every input moves the surface with them.
    let mut s = s;
    let ids: Vec<NodeRef> = s
        .doc
        .nodes()
        .filter(|n| n.name.starts_with('U') || n.name.starts_with('V'))
        .map(|n| NodeRef::from(n.id))
        .collect();
    s.execute(&Command::Translate {
        nodes: ids,
        offset: DVec3::new(0.0, 0.0, 5.0),
    })
    .unwrap();
    let moved = surface(&s, "Network");
    let shift = moved.point(0.4, 0.6) - g.point(0.4, 0.6);
    assert!(shift.distance(DVec3::new(0.0, 0.0, 5.0)) < 1e-9, "{shift}");
}

#[test]
fn gordon_curves_that_do_not_cross_are_refused_by_name() {
    let mut s = gordon_session();
    let err = s
        .execute(&Command::Translate {
            nodes: vec![name("V3")],
            offset: DVec3::new(0.0, 0.2, 0.0),
        })
        .unwrap_err();
    let CommandError::Construction {
        error: ConstructionError::GordonMiss {
            v_curve, distance, ..
        },
        ..
    } = &err
    else {
        panic!("{err}")
    };
    assert_eq!(v_curve, "'V3'", "{err}");
    // At most the offset (the curves are not perpendicular to it).
    assert!(*distance > 0.1 && *distance <= 0.2 + 1e-12, "{err}");
    assert!(err.to_string().contains("Gordon: the u-curve '"), "{err}");
    // Too few curves.
    let err = s
        .execute(&Command::MakeFromCurves {
            name: "Thin".into(),
            construction: Construction {
                recipe: Recipe::Gordon {
                    u_curves: vec![name("U0")],
                    v_curves: vec![name("V0"), name("V1")],
                },
                output: Output::Nurbs,
            },
        })
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "'Thin': Gordon: a curve network needs at least 2 u-curves, got 1"
    );
}
