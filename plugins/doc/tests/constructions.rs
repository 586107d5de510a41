//! Nodes made from curves that follow them (issue 20): the profile's
//! transform moves a revolution with it, editing the profile re-makes the
//! surface in the same undo step, save and load keep the link, deleting an
//! input or editing the result freezes it, refusals name what is wrong,
//! the preview for dragging matches the command, every result exports.

mod golden;

use glam::{DQuat, DVec3};
use hedra_doc::command::CurveSpec;
use hedra_doc::construction::{Construction, ConstructionError, Output, Recipe, Space};
use hedra_doc::{Command, CommandError, NodeContent, NodeRef, NodeTransform, Session};
use hedra_geom::surfaces::sweeps::{FrameKind, Tightness};
use std::path::Path;

fn name(n: &str) -> NodeRef {
    NodeRef::Name(n.into())
}

fn add_curve(s: &mut Session, n: &str, curve: CurveSpec, transform: NodeTransform) {
    s.execute(&Command::AddCurve {
        name: n.into(),
        curve,
        parent: None,
        transform,
    })
    .unwrap();
}

fn circle(radius: f64) -> CurveSpec {
    CurveSpec::Circle { radius }
}

fn revolve(profile: &str) -> Construction<NodeRef> {
    Construction {
        recipe: Recipe::Revolve {
            profile: name(profile),
            origin: DVec3::new(-2.0, 0.0, 0.0),
            axis: DVec3::Z,
            degrees: 360.0,
            pitch: 0.0,
            space: Space::Profile,
            caps: false,
        },
        output: Output::Nurbs,
    }
}

fn make(s: &mut Session, n: &str, c: Construction<NodeRef>) -> Result<(), CommandError> {
    s.execute(&Command::MakeFromCurves {
        name: n.into(),
        construction: c,
    })
    .map(|_| ())
}

fn surface_points(s: &Session, n: &str) -> Vec<DVec3> {
    match &s.doc.find_by_name(n).unwrap().content {
        NodeContent::Surface(sf) => sf.control_points().to_vec(),
        c => panic!("{n} is a {}", c.kind()),
    }
}

/// A torus: a circle of radius 0.5 at (5, 0, 0) revolved about the axis 2
/// from its centre.
fn torus_session() -> Session {
    let mut s = Session::new();
    add_curve(
        &mut s,
        "Profile",
        circle(0.5),
        NodeTransform::from_translation(DVec3::new(5.0, 0.0, 0.0)),
    );
    make(&mut s, "Torus", revolve("Profile")).unwrap();
    s
}

#[test]
fn the_revolved_circle_lands_where_the_profile_is_as_an_exact_torus() {
    use hedra_geom::Surface;
    let s = torus_session();
    let node = s.doc.find_by_name("Torus").unwrap();
    assert_eq!(node.transform, NodeTransform::IDENTITY);
    let NodeContent::Surface(sf) = &node.content else {
        panic!()
    };
    let hedra_doc::SurfaceShape::Nurbs(torus) = &**sf else {
        panic!()
    };
    // Axis: through (3, 0, 0) along Z; the tube's centre circle has radius 2.
    let ((u0, u1), (v0, v1)) = torus.domain();
    let mut worst: f64 = 0.0;
    for i in 0..100 {
        for j in 0..100 {
            let p = torus.point(
                u0 + (u1 - u0) * i as f64 / 99.0,
                v0 + (v1 - v0) * j as f64 / 99.0,
            );
            let rho = (p.x - 3.0).hypot(p.y);
            worst = worst.max((((rho - 2.0).powi(2) + p.z * p.z).sqrt() - 0.5).abs());
        }
    }
    assert!(worst < 1e-12, "{worst}");
}

#[test]
fn the_profiles_transform_moves_the_revolved_surface_with_it() {
    let mut s = torus_session();
    let before = surface_points(&s, "Torus");
    let motion = NodeTransform {
        translation: DVec3::new(1.0, 2.0, -3.0),
        rotation: DQuat::from_axis_angle(DVec3::new(1.0, 1.0, 0.0).normalize(), 0.7),
        scale: DVec3::ONE,
    };
    // Move the profile: its world matrix becomes motion · old.
    let old = s.doc.find_by_name("Profile").unwrap().transform;
    let new = NodeTransform::from_matrix(motion.to_matrix() * old.to_matrix());
    let id = s.doc.find_by_name("Profile").unwrap().id;
    let applied = s
        .execute(&Command::SetTransforms {
            nodes: vec![(NodeRef::from(id), new)],
        })
        .unwrap();
    assert_eq!(applied.label, "Transform 1 node");
    let after = surface_points(&s, "Torus");
    let m = motion.to_matrix();
    for (a, b) in before.iter().zip(&after) {
        assert!(m.transform_point3(*a).distance(*b) < 1e-12, "{a} → {b}");
    }
    // One step: undo puts the profile and the torus back together.
    s.undo();
    assert_eq!(surface_points(&s, "Torus"), before);
    assert_eq!(s.doc.find_by_name("Profile").unwrap().transform, old);
}

#[test]
fn editing_the_profile_remakes_the_surface_in_the_same_undo_step() {
    let mut s = torus_session();
    let steps = s.history.done().len();
    let before = surface_points(&s, "Torus");
    s.execute(&Command::SetControlPoints {
        node: name("Profile"),
        points: vec![(2, DVec3::new(0.0, 0.0, 1.0))],
    })
    .unwrap();
    assert_eq!(s.history.done().len(), steps + 1, "one step");
    let t = s.history.done().last().unwrap();
    let torus = s.doc.find_by_name("Torus").unwrap().id;
    assert!(
        t.changes.iter().any(|c| c.id == torus),
        "the torus is in it"
    );
    let after = surface_points(&s, "Torus");
    assert_ne!(before, after);
    assert!(s.doc.find_by_name("Torus").unwrap().construction.is_some());
    s.undo();
    assert_eq!(surface_points(&s, "Torus"), before);
    s.redo();
    assert_eq!(surface_points(&s, "Torus"), after);
}

#[test]
fn the_drag_preview_is_what_the_command_makes() {
    let s = torus_session();
    let mut dragged = s.doc.find_by_name("Profile").unwrap().clone();
    let NodeContent::Curve(c) = &dragged.content else {
        panic!()
    };
    let mut kind = c.kind().clone();
    kind = kind.set_points(&[(2, DVec3::new(0.0, 0.0, 1.0))]).unwrap();
    dragged.content = NodeContent::Curve(std::sync::Arc::new(
        hedra_doc::CurveContent::new(kind).unwrap(),
    ));
    let preview = s.doc.remade_dependents(&dragged);
    let torus = s.doc.find_by_name("Torus").unwrap().id;
    assert_eq!(preview.len(), 1);
    assert_eq!(preview[0].0, torus);
    let mut s2 = s.clone();
    s2.execute(&Command::SetControlPoints {
        node: name("Profile"),
        points: vec![(2, DVec3::new(0.0, 0.0, 1.0))],
    })
    .unwrap();
    assert_eq!(preview[0].1, s2.doc.node(torus).unwrap().content);
    // Moving the profile node (no content change) previews too.
    let mut moved = s.doc.find_by_name("Profile").unwrap().clone();
    moved.transform.translation.y += 1.0;
    assert_eq!(s.doc.remade_dependents(&moved).len(), 1);
    assert_eq!(s.doc.dependents(moved.id), vec![torus]);
}

#[test]
fn save_and_load_keep_the_link() {
    let mut s = torus_session();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("torus.hedra.ron");
    hedra_doc::file::save(&mut s, &path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.contains("construction: Some((recipe: Revolve("),
        "{text}"
    );
    let mut loaded = hedra_doc::file::load(&path).unwrap();
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    assert_eq!(loaded.session.doc, s.doc);
    let before = surface_points(&loaded.session, "Torus");
    loaded
        .session
        .execute(&Command::Translate {
            nodes: vec![name("Profile")],
            offset: DVec3::new(0.0, 0.0, 1.0),
        })
        .unwrap();
    let after = surface_points(&loaded.session, "Torus");
    for (a, b) in before.iter().zip(&after) {
        assert!((*a + DVec3::Z).distance(*b) < 1e-12);
    }
    // The history also undoes after loading.
    loaded.session.undo();
    loaded.session.undo();
    assert!(loaded.session.doc.find_by_name("Torus").is_none());
}

#[test]
fn deleting_an_input_freezes_its_dependents_and_undo_restores_the_link() {
    let mut s = torus_session();
    let applied = s
        .execute(&Command::Delete {
            nodes: vec![name("Profile")],
        })
        .unwrap();
    let torus = s.doc.find_by_name("Torus").unwrap();
    assert!(torus.construction.is_none());
    assert!(
        applied
            .label
            .ends_with("(froze 'Torus': its input #1 was deleted)"),
        "{}",
        applied.label
    );
    s.undo();
    assert!(s.doc.find_by_name("Torus").unwrap().construction.is_some());
    s.doc.check().unwrap();
}

#[test]
fn editing_the_result_directly_freezes_it_but_moving_it_does_not() {
    let mut s = torus_session();
    s.execute(&Command::Translate {
        nodes: vec![name("Torus")],
        offset: DVec3::X,
    })
    .unwrap();
    assert!(s.doc.find_by_name("Torus").unwrap().construction.is_some());
    let applied = s
        .execute(&Command::SetControlPoints {
            node: name("Torus"),
            points: vec![(0, DVec3::new(9.0, 9.0, 9.0))],
        })
        .unwrap();
    assert!(applied.label.contains("froze 'Torus': edited directly"));
    assert!(s.doc.find_by_name("Torus").unwrap().construction.is_none());
    // The profile now changes alone.
    let frozen = surface_points(&s, "Torus");
    s.execute(&Command::Translate {
        nodes: vec![name("Profile")],
        offset: DVec3::Y,
    })
    .unwrap();
    assert_eq!(surface_points(&s, "Torus"), frozen);
}

#[test]
fn apply_freezes_in_one_step_and_set_construction_remakes() {
    let mut s = torus_session();
    s.execute(&Command::SetConstruction {
        node: name("Torus"),
        construction: Construction {
            output: Output::Mesh {
                segments: 12,
                profile_segments: 8,
            },
            ..revolve("Profile")
        },
    })
    .unwrap();
    let mesh = s
        .doc
        .find_by_name("Torus")
        .unwrap()
        .content
        .mesh()
        .unwrap()
        .clone();
    mesh.validate().unwrap();
    assert_eq!((mesh.face_count(), mesh.stats().genus), (96, Some(1)));
    let applied = s
        .execute(&Command::ApplyConstruction {
            nodes: vec![name("Torus")],
        })
        .unwrap();
    assert_eq!(applied.label, "Apply Construction");
    assert!(s.doc.find_by_name("Torus").unwrap().construction.is_none());
    let err = s
        .execute(&Command::ApplyConstruction {
            nodes: vec![name("Torus")],
        })
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "'Torus' (#2) was not made from curves (or has been applied)"
    );
    s.undo();
    assert!(s.doc.find_by_name("Torus").unwrap().construction.is_some());
}

#[test]
fn refusals_name_the_node_and_the_reason() {
    let mut s = torus_session();
    let capped = Construction {
        recipe: Recipe::Extrude {
            profile: name("Profile"),
            direction: DVec3::Y,
            space: Space::Profile,
            caps: true,
        },
        output: Output::Nurbs,
    };
    // A capped mesh extrusion follows the circle; bending the circle out of
    // its plane is refused, naming the dependent.
    make(
        &mut s,
        "Can",
        Construction {
            output: Output::Mesh {
                segments: 2,
                profile_segments: 16,
            },
            ..capped
        },
    )
    .unwrap();
    let can = s.doc.find_by_name("Can").unwrap().content.mesh().unwrap();
    assert_eq!(can.stats().genus, Some(0));
    let doc = s.doc.clone();
    let err = s
        .execute(&Command::SetControlPoints {
            node: name("Profile"),
            points: vec![(2, DVec3::new(0.0, 0.3, 0.5))],
        })
        .unwrap_err();
    assert!(
        err.to_string()
            .starts_with("'Can' (#3): caps need a planar profile"),
        "{err}"
    );
    assert_eq!(s.doc, doc, "nothing changed");
    // A missing input and a non-curve input.
    let err = make(&mut s, "X", revolve("Nothing")).unwrap_err();
    assert_eq!(err, CommandError::UnknownNode(name("Nothing")));
    let err = make(&mut s, "X", revolve("Torus")).unwrap_err();
    assert_eq!(err.to_string(), "'X': input #2 is not a curve");
    let err = s
        .execute(&Command::SetConstruction {
            node: name("Profile"),
            construction: revolve("Profile"),
        })
        .unwrap_err();
    assert!(matches!(err, CommandError::NoConstruction { .. }));
}

/// One node of every recipe, as a NURBS surface and as a mesh, from
/// curves of their own; the loft's middle section moved afterwards.
fn every_recipe_session() -> Session {
    let mut s = Session::new();
    add_curve(
        &mut s,
        "Ring",
        circle(0.3),
        NodeTransform::from_translation(DVec3::new(0.0, 0.0, 0.0)),
    );
    add_curve(
        &mut s,
        "Rail",
        CurveSpec::CatmullRom {
            points: vec![
                DVec3::ZERO,
                DVec3::new(0.0, 2.0, 0.0),
                DVec3::new(1.0, 4.0, 1.0),
                DVec3::new(3.0, 5.0, 1.0),
            ],
            parameterization: Default::default(),
            closed: false,
        },
        NodeTransform::IDENTITY,
    );
    for (i, (y, r)) in [(0.0, 1.0), (1.0, 0.5), (2.0, 1.2)].iter().enumerate() {
        add_curve(
            &mut s,
            &format!("S{i}"),
            circle(*r),
            NodeTransform::from_translation(DVec3::new(6.0, *y, 0.0)),
        );
    }
    add_curve(
        &mut s,
        "A",
        CurveSpec::Bezier {
            points: vec![DVec3::new(10.0, 0.0, 0.0), DVec3::new(10.0, 0.0, 3.0)],
        },
        NodeTransform::IDENTITY,
    );
    add_curve(
        &mut s,
        "B",
        CurveSpec::Bezier {
            points: vec![DVec3::new(12.0, 0.0, 0.0), DVec3::new(12.5, 0.0, 3.0)],
        },
        NodeTransform::IDENTITY,
    );
    add_curve(
        &mut s,
        "Arc",
        CurveSpec::Bezier {
            points: vec![
                DVec3::new(10.0, 0.0, 0.0),
                DVec3::new(11.0, 1.0, 0.0),
                DVec3::new(12.0, 0.0, 0.0),
            ],
        },
        NodeTransform::IDENTITY,
    );
    let mesh = Output::Mesh {
        segments: 8,
        profile_segments: 8,
    };
    let recipes: Vec<(&str, Recipe<NodeRef>)> = vec![
        (
            "Extruded",
            Recipe::Extrude {
                profile: name("Ring"),
                direction: DVec3::new(0.0, 1.0, 0.0),
                space: Space::World,
                caps: false,
            },
        ),
        (
            "Screwed",
            Recipe::Revolve {
                profile: name("Ring"),
                origin: DVec3::new(-1.0, 0.0, 0.0),
                axis: DVec3::Z,
                degrees: 720.0,
                pitch: 1.0,
                space: Space::Profile,
                caps: false,
            },
        ),
        (
            "Swept",
            Recipe::Sweep {
                profile: name("Ring"),
                rail: name("Rail"),
                frame: FrameKind::RotationMinimizing,
                stations: 12,
                caps: false,
            },
        ),
        (
            "Swept2",
            Recipe::Sweep2 {
                profile: name("Arc"),
                rails: (name("A"), name("B")),
                stations: 8,
                caps: false,
            },
        ),
        (
            "Lofted",
            Recipe::Loft {
                sections: vec![name("S0"), name("S1"), name("S2")],
                closed: false,
                tightness: Tightness::Normal,
                caps: false,
            },
        ),
    ];
    for (n, recipe) in recipes {
        for output in [Output::Nurbs, mesh] {
            let kind = if output == Output::Nurbs {
                "NURBS"
            } else {
                "Mesh"
            };
            let node = format!("{n} {kind}");
            make(
                &mut s,
                &node,
                Construction {
                    recipe: recipe.clone(),
                    output,
                },
            )
            .unwrap_or_else(|e| panic!("{node}: {e}"));
            let made = s.doc.find_by_name(&node).unwrap();
            match (&made.content, output) {
                (NodeContent::Mesh(m), Output::Mesh { .. }) => m.mesh.validate().unwrap(),
                (NodeContent::Surface(_), Output::Nurbs) => {}
                (c, o) => panic!("{node}: {} for {o:?}", c.kind()),
            }
        }
    }
    s.execute(&Command::Translate {
        nodes: vec![name("S1")],
        offset: DVec3::new(0.2, 0.0, 0.0),
    })
    .unwrap();
    s
}

#[test]
fn every_recipe_makes_a_node_and_every_result_exports() {
    let s = every_recipe_session();
    let lofts = ["Lofted NURBS", "Lofted Mesh"];
    let step = s.history.done().last().unwrap();
    for l in lofts {
        let id = s.doc.find_by_name(l).unwrap().id;
        assert!(step.changes.iter().any(|c| c.id == id), "{l} followed S1");
    }
    for ext in ["obj", "stl", "gltf"] {
        let bytes = hedra_doc::export::export_bytes(
            &s.doc,
            Path::new(&format!("out.{ext}")),
            Default::default(),
        )
        .unwrap();
        assert!(bytes.len() > 1000, "{ext}");
    }
    // hedra info names the construction and its inputs.
    let report = hedra_doc::report::SceneReport::new(&s);
    let text = report.to_text();
    assert!(
        text.contains("made by: Sweep2 of 'Arc' (#8), 'A' (#6), 'B' (#7) (8 stations, NURBS)"),
        "{text}"
    );
    let json = report.to_json();
    assert!(json.contains("\"recipe\": \"Screw\""), "{json}");
}

#[test]
fn old_revolve_and_extrude_surfaces_still_compute_once() {
    let mut s = Session::new();
    add_curve(
        &mut s,
        "P",
        CurveSpec::Bezier {
            points: vec![DVec3::new(1.0, 0.0, 0.0), DVec3::new(1.0, 1.0, 0.0)],
        },
        NodeTransform::IDENTITY,
    );
    for (n, surface) in [
        (
            "Old Revolve",
            hedra_doc::command::SurfaceSpec::Revolve { profile: name("P") },
        ),
        (
            "Old Extrude",
            hedra_doc::command::SurfaceSpec::Extrude {
                profile: name("P"),
                direction: DVec3::Z,
            },
        ),
    ] {
        s.execute(&Command::AddSurface {
            name: n.into(),
            surface,
            parent: None,
            transform: NodeTransform::IDENTITY,
        })
        .unwrap();
        assert!(s.doc.find_by_name(n).unwrap().construction.is_none());
    }
    let before = surface_points(&s, "Old Revolve");
    s.execute(&Command::Translate {
        nodes: vec![name("P")],
        offset: DVec3::Y,
    })
    .unwrap();
    assert_eq!(surface_points(&s, "Old Revolve"), before);
}

#[test]
fn every_recipe_saves_and_loads_with_its_links() {
    let s = every_recipe_session();
    let text = hedra_doc::file::to_string(&s);
    // The scene corpus keeps this file forever (tests/scene_corpus.rs), and
    // it is what today's commands make (never rewritten: a change to what
    // the commands make fails here).
    golden::assert_matches_corpus("v2-constructions.hedra.ron", &text);
    let loaded = hedra_doc::file::from_str(&text, Path::new("c.hedra.ron")).unwrap();
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let mut back = loaded.session;
    assert_eq!(back.doc, s.doc);
    let made = back
        .doc
        .nodes()
        .filter(|n| n.construction.is_some())
        .count();
    assert_eq!(made, 10);
    while back.undo().is_some() {
        back.doc.check().unwrap();
    }
    assert_eq!(back.doc.node_count(), 0);
    while back.redo().is_some() {}
    assert_eq!(back.doc, s.doc);
}

#[test]
fn a_file_whose_construction_names_a_missing_input_is_refused_by_name() {
    let s = torus_session();
    let text = hedra_doc::file::to_string(&s);
    let bad = text.replacen(
        "recipe: Revolve(profile: 1,",
        "recipe: Revolve(profile: 7,",
        1,
    );
    assert_ne!(bad, text);
    let err = hedra_doc::file::from_str(&bad, Path::new("bad.hedra.ron")).unwrap_err();
    assert!(
        err.to_string()
            .ends_with("node #2 'Torus' is made from node #7, which is missing or not a curve"),
        "{err}"
    );
}

fn surface_of(s: &Session, n: &str) -> hedra_geom::surfaces::NurbsSurface {
    match &s.doc.find_by_name(n).unwrap().content {
        NodeContent::Surface(sf) => match &**sf {
            hedra_doc::SurfaceShape::Nurbs(x) => x.clone(),
            _ => panic!("{n} is a triangle"),
        },
        c => panic!("{n} is a {}", c.kind()),
    }
}

#[test]
fn nurbs_caps_are_child_nodes_that_follow_the_profile_and_the_recipe() {
    use hedra_geom::Surface;
    let mut s = torus_session();
    let can = Construction {
        recipe: Recipe::Extrude {
            profile: name("Profile"),
            direction: DVec3::new(0.0, 2.0, 0.0),
            space: Space::Profile,
            caps: true,
        },
        output: Output::Nurbs,
    };
    make(&mut s, "Can", can.clone()).unwrap();
    let can_id = s.doc.find_by_name("Can").unwrap().id;
    for (cap, y) in [("Can cap start", 0.0), ("Can cap end", 2.0)] {
        let node = s.doc.find_by_name(cap).unwrap();
        assert_eq!(node.parent, Some(can_id));
        let disc = surface_of(&s, cap);
        let ((a, b), (c, d)) = disc.domain();
        for i in 0..=10 {
            for j in 0..=10 {
                let p = disc.point(a + (b - a) * i as f64 / 10.0, c + (d - c) * j as f64 / 10.0);
                assert!((p.y - y).abs() < 1e-12);
                assert!(p.distance(DVec3::new(5.0, y, 0.0)) <= 0.5 + 1e-9);
            }
        }
    }
    // One undo step made all three.
    assert_eq!(s.doc.node_count(), 5);
    s.undo();
    assert_eq!(s.doc.node_count(), 2);
    s.redo();
    // Moving the profile moves the caps with the surface, in one step.
    s.execute(&Command::SetTransforms {
        nodes: vec![(
            name("Profile"),
            NodeTransform::from_translation(DVec3::new(5.0, 1.0, 0.0)),
        )],
    })
    .unwrap();
    let top = surface_of(&s, "Can cap end");
    assert!((top.points()[0].y - 3.0).abs() < 1e-12);
    // Caps off: the cap nodes go; on again: they come back.
    let mut open = can.clone();
    if let Recipe::Extrude { caps, .. } = &mut open.recipe {
        *caps = false;
    }
    s.execute(&Command::SetConstruction {
        node: name("Can"),
        construction: open,
    })
    .unwrap();
    assert!(s.doc.find_by_name("Can cap start").is_none());
    s.undo();
    assert!(s.doc.find_by_name("Can cap start").is_some());
    // A cap's recipe is its surface's: changing it there is refused.
    let err = s
        .execute(&Command::SetConstruction {
            node: name("Can cap end"),
            construction: can.clone(),
        })
        .unwrap_err();
    assert!(err.to_string().contains("is a cap of 'Can'"), "{err}");
    // A full revolution has no ends: caps asked of it make none.
    let mut full = revolve("Profile");
    if let Recipe::Revolve { caps, .. } = &mut full.recipe {
        *caps = true;
    }
    make(&mut s, "Ring", full).unwrap();
    assert!(s.doc.find_by_name("Ring cap start").is_none());
    // A partial one gets two, and Apply freezes them with it.
    let mut part = revolve("Profile");
    if let Recipe::Revolve { caps, degrees, .. } = &mut part.recipe {
        *caps = true;
        *degrees = 120.0;
    }
    make(&mut s, "Arc", part).unwrap();
    assert!(s.doc.find_by_name("Arc cap end").is_some());
    s.execute(&Command::ApplyConstruction {
        nodes: vec![name("Arc")],
    })
    .unwrap();
    assert!(
        s.doc
            .find_by_name("Arc cap end")
            .unwrap()
            .construction
            .is_none()
    );
    // The file keeps the caps' link.
    let text = hedra_doc::file::to_string(&s);
    let back = hedra_doc::file::from_str(&text, Path::new("c.hedra.ron")).unwrap();
    assert_eq!(
        back.session
            .doc
            .find_by_name("Can cap end")
            .unwrap()
            .construction,
        s.doc.find_by_name("Can cap end").unwrap().construction
    );
    // An open profile cannot be capped: refused, naming the node.
    add_curve(
        &mut s,
        "Arc profile",
        CurveSpec::Nurbs {
            degree: 1,
            points: vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0)],
            weights: None,
            knots: None,
        },
        NodeTransform::IDENTITY,
    );
    let err = make(
        &mut s,
        "Sheet",
        Construction {
            recipe: Recipe::Extrude {
                profile: name("Arc profile"),
                direction: DVec3::Z,
                space: Space::Profile,
                caps: true,
            },
            output: Output::Nurbs,
        },
    )
    .unwrap_err();
    assert!(err.to_string().starts_with("'Sheet'"), "{err}");
    assert!(err.to_string().contains("closed profile"), "{err}");
    let _ = ConstructionError::NoEnds;
}
