//! Frames of the windowless app on big scenes (issue 36, item 1): the CPU
//! time of each frame while a user drags, median and worst of 100 frames.
//! The app is the real one (`hedra::windowless_gui_app`: every plugin, the
//! document, the projection, egui's layout) without a GPU: what is timed is
//! the work a frame does before it is drawn. Input goes in as the GUI tests
//! send it (`tests/gui/user.rs`, included below): a key, then the pointer
//! moved a few pixels per frame.
//!
//! `cargo bench --bench frames` (release); `cargo bench --profile dev
//! --bench frames` for a quick look with the test build. `HEDRA_FRAMES_ROWS`
//! picks rows by name (comma-separated substrings).

#[path = "../tests/gui/user.rs"]
#[allow(dead_code, reason = "the tests' driver: the bench uses part of it")]
mod user;

use bevy::prelude::*;
use hedra_doc::command::{Command, NodeRef, SurfaceSpec};
use hedra_doc::{NodeTransform, SubdivisionModifier};
use hedra_geom::{DVec3, Primitive};
use hedra_scene::DocRequest;
use std::time::{Duration, Instant};
use user::User;

/// Frames timed per row.
const FRAMES: usize = 100;

/// Runs `command` as the UI would and waits a frame for it.
fn execute(user: &mut User, command: Command) {
    user.app
        .world_mut()
        .write_message(DocRequest::Execute(command));
    user.frames(2);
    let status = user.status();
    assert!(!status.contains("is_error: true"), "{status}");
}

fn add(user: &mut User, primitive: Primitive, name: &str) {
    execute(
        user,
        Command::AddPrimitive {
            primitive,
            name: Some(name.into()),
            parent: None,
            transform: NodeTransform::IDENTITY,
        },
    );
}

/// A 1000 × 1000 grid of quads (1M faces), 10 wide.
fn million_quads(user: &mut User) {
    add(
        user,
        Primitive::Grid {
            x_segments: 1000,
            z_segments: 1000,
            size: 10.0,
        },
        "Grid",
    );
}

/// The selected mesh in edit mode, in `kind` mode, with every `step`-th
/// vertex (or face) selected.
fn edit_with_every(user: &mut User, kind: hedra_edit::ElementKind, step: usize) {
    user.tap(KeyCode::Tab);
    let node = user.edit_mode().node.expect("edit mode");
    let mesh = match &user.doc().node(node).unwrap().content {
        hedra_doc::NodeContent::Mesh(m) => m.mesh.clone(),
        _ => panic!("a mesh"),
    };
    let mut mode = user.app.world_mut().resource_mut::<hedra_edit::EditMode>();
    mode.kind = kind;
    match kind {
        hedra_edit::ElementKind::Face => {
            mode.selection.faces = mesh.faces().step_by(step).collect();
        }
        _ => {
            mode.selection.vertices = mesh.vertices().step_by(step).collect();
        }
    }
    user.frames(2);
}

/// Times `FRAMES` frames of the pointer moving right by 2 pixels a frame
/// from the viewport's centre (a key already pressed starts the tool).
fn drag_frames(user: &mut User) -> Vec<Duration> {
    let start = user.viewport_center();
    (0..FRAMES)
        .map(|i| {
            let at = start + Vec2::new(2.0 * i as f32, -(i as f32));
            let t = Instant::now();
            user.move_to(at);
            t.elapsed()
        })
        .collect()
}

/// One row: the scene `setup` makes, the key that starts the drag (none:
/// an orbit with the middle button held), the frames timed.
struct Row {
    name: &'static str,
    setup: fn(&mut User),
    key: Option<KeyCode>,
}

fn rows() -> Vec<Row> {
    vec![
        Row {
            name: "orbit, 1M-face scene (nothing changes)",
            setup: |user| {
                million_quads(user);
                user.move_to(user.viewport_center());
                user.button_down(MouseButton::Middle);
            },
            key: None,
        },
        Row {
            name: "G on 10 % of the vertices of a 1M-face cage",
            setup: |user| {
                million_quads(user);
                edit_with_every(user, hedra_edit::ElementKind::Vertex, 10);
            },
            key: Some(KeyCode::KeyG),
        },
        Row {
            name: "extrude preview of 1,000 faces of a 1M-face cage",
            setup: |user| {
                million_quads(user);
                edit_with_every(user, hedra_edit::ElementKind::Face, 1000);
            },
            key: Some(KeyCode::KeyE),
        },
        Row {
            name: "G on one vertex of a 100k-face cage, subdivision level 2 shown",
            setup: |user| {
                add(
                    user,
                    Primitive::Grid {
                        x_segments: 316,
                        z_segments: 316,
                        size: 10.0,
                    },
                    "Grid",
                );
                execute(
                    user,
                    Command::SetSubdivision {
                        nodes: vec![NodeRef::Name("Grid".into())],
                        modifier: Some(SubdivisionModifier::with_level(2)),
                    },
                );
                // The level-2 preview of a 100k cage is made in the background
                // the first time: wait for it.
                for _ in 0..600 {
                    user.frame();
                    if user
                        .app
                        .world()
                        .resource::<hedra_scene::SmoothPreviews>()
                        .progress()
                        .is_empty()
                    {
                        break;
                    }
                }
                edit_with_every(user, hedra_edit::ElementKind::Vertex, 100_000);
            },
            key: Some(KeyCode::KeyG),
        },
        Row {
            name: "W (weight) drag on a 200 × 200 NURBS surface",
            setup: |user| {
                let (nu, nv) = (200, 200);
                let points = (0..nu * nv)
                    .map(|k| {
                        let (i, j) = ((k / nv) as f64, (k % nv) as f64);
                        DVec3::new(
                            i * 0.05 - 5.0,
                            (i * 0.3).sin() * (j * 0.2).cos() * 0.2,
                            j * 0.05 - 5.0,
                        )
                    })
                    .collect();
                execute(
                    user,
                    Command::AddSurface {
                        name: "Sheet".into(),
                        surface: SurfaceSpec::Nurbs {
                            degree_u: 3,
                            degree_v: 3,
                            nu,
                            nv,
                            points,
                            weights: None,
                            knots_u: None,
                            knots_v: None,
                        },
                        parent: None,
                        transform: NodeTransform::IDENTITY,
                    },
                );
                user.tap(KeyCode::Tab);
                let mut edit = user.app.world_mut().resource_mut::<hedra_edit::ShapeEdit>();
                assert!(edit.node.is_some(), "shape edit mode");
                edit.selected = [100 * 200 + 100].into();
                user.frames(2);
            },
            key: Some(KeyCode::KeyW),
        },
        Row {
            name: "G on a CSG operand, 2 × 200k triangles",
            setup: |user| {
                let sphere = Primitive::UvSphere {
                    segments: 400,
                    rings: 250,
                    radius: 1.0,
                };
                add(user, sphere.clone(), "A");
                add(user, sphere, "B");
                execute(
                    user,
                    Command::Translate {
                        nodes: vec![NodeRef::Name("B".into())],
                        offset: DVec3::new(0.7, 0.2, 0.1),
                    },
                );
                execute(
                    user,
                    Command::AddCsg {
                        op: hedra_geom::BooleanOp::Difference,
                        name: None,
                        operands: vec![NodeRef::Name("A".into()), NodeRef::Name("B".into())],
                        parent: None,
                        transform: NodeTransform::IDENTITY,
                    },
                );
                let b = user.doc().find_by_name("B").unwrap().id;
                user.app
                    .world_mut()
                    .resource_mut::<hedra_edit::Selection>()
                    .set([b]);
                user.frames(2);
            },
            key: Some(KeyCode::KeyG),
        },
    ]
}

fn median_and_worst(mut frames: Vec<Duration>) -> (f64, f64) {
    frames.sort();
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    (ms(frames[frames.len() / 2]), ms(*frames.last().unwrap()))
}

/// Opening a saved 1M-quad scene: from File ▸ Open to the first frame
/// that shows it (its render mesh made) and takes input.
fn first_frame_after_opening() -> f64 {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("grid.hedra.ron");
    let mut session = hedra_doc::Session::new();
    session
        .execute(&Command::AddPrimitive {
            primitive: Primitive::Grid {
                x_segments: 1000,
                z_segments: 1000,
                size: 10.0,
            },
            name: Some("Grid".into()),
            parent: None,
            transform: NodeTransform::IDENTITY,
        })
        .unwrap();
    hedra_doc::file::save(&mut session, &path).unwrap();
    let mut user = User::new();
    let t = Instant::now();
    user.app.world_mut().write_message(DocRequest::Open(path));
    loop {
        user.frame();
        let shown = user.doc().node_count() == 1
            && user
                .app
                .world_mut()
                .query_filtered::<&Mesh3d, With<hedra_scene::NodeEntity>>()
                .iter(user.app.world())
                .next()
                .is_some();
        if shown {
            break;
        }
        assert!(t.elapsed().as_secs() < 120, "the scene never showed");
    }
    t.elapsed().as_secs_f64() * 1e3
}

fn main() {
    // As the window runs (`hedra::gui_app`): edits are not validated
    // after every step unless HEDRA_VALIDATE_EDITS is set.
    hedra_doc::command::set_validate_edits(std::env::var_os("HEDRA_VALIDATE_EDITS").is_some());
    let only: Vec<String> = std::env::var("HEDRA_FRAMES_ROWS")
        .map(|s| s.split(',').map(str::to_string).collect())
        .unwrap_or_default();
    let wanted = |name: &str| only.is_empty() || only.iter().any(|o| name.contains(o.as_str()));
    println!("| row | median ms | worst ms |");
    println!("|---|---|---|");
    for row in rows() {
        if !wanted(row.name) {
            continue;
        }
        let mut user = User::new();
        (row.setup)(&mut user);
        if let Some(key) = row.key {
            user.tap(key);
        }
        let (median, worst) = median_and_worst(drag_frames(&mut user));
        println!("| {} | {median:.1} | {worst:.1} |", row.name);
        user.tap(KeyCode::Escape);
    }
    let name = "open a 1M-quad scene to its first interactive frame";
    if wanted(name) {
        println!("| {name} | {:.0} (once) | |", first_frame_after_opening());
    }
}
