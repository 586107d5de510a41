//! Monkey testing (issue 35, item 4): a seeded random hand on the
//! windowless app. It sends what a user can send: the keys of the keymap in
//! every mode (tools, axes, typed numbers, Enter, Esc in the middle of a
//! tool, undo and redo), clicks and drags in the viewport, the wheel, and
//! clicks on whatever widget egui shows (menus, panels, buttons), leaving
//! out only those that open a file dialog, quit, or start a new scene.
//! After every event every mesh of the document validates. At the end, undo
//! all returns the document to where it started, redo all to where it
//! ended, and save → load → save gives the same text.
//!
//! A failure prints the seed and the events so far. The short version runs
//! in CI (a few seeds of a few hundred events); `scripts/monkey` runs the
//! long one (`HEDRA_MONKEY_SEEDS`, `HEDRA_MONKEY_EVENTS`).

use crate::user::User;
use bevy::prelude::*;
use bevy_egui::egui;
use hedra_geom::DVec3;
use hedra_scene::{DocRequest, DocState};
use std::fmt::Write as _;

/// xorshift64*: the same events for the same seed.
struct Hand(u64);

impl Hand {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// Keys of the keymap: object and edit mode tools, axes, element modes,
/// digits and signs for typed values, views.
const KEYS: [KeyCode; 34] = [
    KeyCode::KeyG,
    KeyCode::KeyR,
    KeyCode::KeyS,
    KeyCode::KeyE,
    KeyCode::KeyI,
    KeyCode::KeyX,
    KeyCode::KeyY,
    KeyCode::KeyZ,
    KeyCode::KeyA,
    KeyCode::KeyF,
    KeyCode::KeyM,
    KeyCode::KeyK,
    KeyCode::KeyL,
    KeyCode::KeyH,
    KeyCode::KeyV,
    KeyCode::KeyW,
    KeyCode::Tab,
    KeyCode::Digit1,
    KeyCode::Digit2,
    KeyCode::Digit3,
    KeyCode::Digit5,
    KeyCode::Digit0,
    KeyCode::Minus,
    KeyCode::Period,
    KeyCode::Backspace,
    KeyCode::Enter,
    KeyCode::Escape,
    KeyCode::Delete,
    KeyCode::Numpad1,
    KeyCode::Numpad3,
    KeyCode::Numpad7,
    KeyCode::NumpadAdd,
    KeyCode::NumpadSubtract,
    KeyCode::Space,
];

/// Shortcuts with modifiers (no Ctrl+S, Ctrl+O, Ctrl+N, Ctrl+Q: dialogs,
/// a new scene, quitting).
const CHORDS: [(&[KeyCode], KeyCode); 14] = [
    (&[KeyCode::ControlLeft], KeyCode::KeyZ),
    (&[KeyCode::ControlLeft, KeyCode::ShiftLeft], KeyCode::KeyZ),
    (&[KeyCode::ControlLeft], KeyCode::KeyR),
    (&[KeyCode::ControlLeft], KeyCode::KeyB),
    (&[KeyCode::ControlLeft], KeyCode::Digit1),
    (&[KeyCode::ControlLeft], KeyCode::Digit2),
    (&[KeyCode::ControlLeft], KeyCode::KeyI),
    (&[KeyCode::ControlLeft], KeyCode::KeyA),
    (&[KeyCode::ControlLeft], KeyCode::NumpadAdd),
    (&[KeyCode::ShiftLeft], KeyCode::KeyD),
    (&[KeyCode::ShiftLeft], KeyCode::KeyA),
    (&[KeyCode::ShiftLeft], KeyCode::KeyH),
    (&[KeyCode::AltLeft], KeyCode::KeyH),
    (&[KeyCode::AltLeft], KeyCode::KeyA),
];

/// Widgets a hand leaves alone: they open a file dialog, quit, start a new
/// scene or recover another session.
fn forbidden(text: &str) -> bool {
    text.ends_with('…')
        || text.ends_with("...")
        || [
            "Quit", "New", "Open", "Save", "Export", "Import", "Recover", "Revert", "Discard",
        ]
        .iter()
        .any(|w| text.starts_with(w))
}

/// One random event, applied; returns what it was, for the log. An empty
/// scene gets a primitive first, as a user would add one.
fn event(user: &mut User, hand: &mut Hand) -> String {
    if user.doc().nodes().next().is_none() {
        let item = [
            "Cube(size: 2.0)",
            "UvSphere(segments: 12, rings: 6, radius: 1.0)",
            "Cylinder(segments: 8, radius: 1.0, depth: 2.0)",
        ][hand.below(3)];
        let command = format!("AddPrimitive(primitive: {item})");
        user.app.world_mut().write_message(DocRequest::Execute(
            ron::from_str(&command).expect("a command"),
        ));
        user.frames(2);
        return format!("{command} (the scene was empty)");
    }
    let view = user.viewport();
    let point = |hand: &mut Hand| {
        Vec2::new(
            view.min.x + 4.0 + hand.unit() * (view.width() - 8.0),
            view.min.y + 4.0 + hand.unit() * (view.height() - 8.0),
        )
    };
    match hand.below(100) {
        0..=44 => {
            let key = KEYS[hand.below(KEYS.len())];
            user.tap(key);
            format!("tap {key:?}")
        }
        45..=54 => {
            let (mods, key) = CHORDS[hand.below(CHORDS.len())];
            user.shortcut(mods, key);
            format!("shortcut {mods:?} {key:?}")
        }
        55..=59 => {
            let keys: Vec<KeyCode> = (0..2 + hand.below(3))
                .map(|_| KEYS[hand.below(KEYS.len())])
                .collect();
            user.taps_in_one_frame(&keys);
            format!("keys in one frame {keys:?}")
        }
        60..=71 => {
            let at = point(hand);
            user.click(at);
            format!("click {at}")
        }
        72..=79 => {
            let (from, to) = (point(hand), point(hand));
            user.drag(from, to, 1 + hand.below(4));
            format!("drag {from} → {to}")
        }
        80..=83 => {
            let lines = hand.below(5) as f32 - 2.0;
            user.wheel(lines);
            format!("wheel {lines}")
        }
        84..=85 => {
            // Into edit mode: click a mesh where its origin shows, then Tab.
            let meshes: Vec<DVec3> = user
                .doc()
                .nodes()
                .filter(|n| n.content.mesh().is_some())
                .map(|n| user.doc().world_matrix(n.id).transform_point3(DVec3::ZERO))
                .collect();
            let Some(&origin) = meshes.get(hand.below(meshes.len().max(1))) else {
                user.frame();
                return "no mesh to edit".into();
            };
            let at = user.try_screen_of(origin.as_vec3());
            let Some(at) = at.filter(|p| view.contains(egui::pos2(p.x, p.y))) else {
                user.frame();
                return "the mesh is out of view".into();
            };
            user.tap(KeyCode::Escape);
            user.click(at);
            user.tap(KeyCode::Tab);
            format!("click the mesh at {at} and Tab")
        }
        86..=87 => {
            let at = point(hand);
            user.move_to(at);
            user.frame();
            format!("move to {at}")
        }
        _ => {
            let widgets: Vec<(String, Vec2)> = user
                .widgets()
                .iter()
                .filter(|w| !w.text.is_empty() && !forbidden(&w.text))
                .map(|w| {
                    (
                        w.text.clone(),
                        Vec2::new(w.rect.center().x, w.rect.center().y),
                    )
                })
                .collect();
            if widgets.is_empty() {
                user.frame();
                return "no widget".into();
            }
            let (text, at) = widgets[hand.below(widgets.len())].clone();
            user.click(at);
            format!("click widget '{text}' at {at}")
        }
    }
}

fn invalid_mesh(user: &User) -> Option<String> {
    user.doc().nodes().find_map(|n| {
        let mesh = n.content.mesh()?;
        mesh.validate()
            .err()
            .map(|e| format!("'{}' is not valid: {e}", n.name))
    })
}

/// Runs `events` random events from `seed` and checks the invariants.
fn monkey(seed: u64, events: usize) {
    // The start is the empty scene before the first step: the hand may undo
    // the cube too.
    let mut user = User::new();
    // Saves and exports go beside a scene file in the test's own folder
    // (the hand may press Ctrl+S, or type into a path prompt and Enter).
    let scene_path = user.config_dir().join("monkey.hedra.ron");
    user.app.world_mut().resource_mut::<DocState>().path = Some(scene_path);
    let start = user.doc().clone();
    let start_steps = user.undo_steps();
    user.add("Cube");
    let mut hand = Hand(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let mut log = String::new();
    let fail = |log: &str, what: &str| -> ! {
        panic!("monkey seed {seed}: {what}\nevents:\n{log}");
    };
    for i in 0..events {
        let what =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| event(&mut user, &mut hand)));
        match what {
            Ok(what) => {
                let _ = writeln!(log, "{i}: {what}");
            }
            Err(_) => fail(
                &log,
                &format!("event {i} panicked (after the events below)"),
            ),
        }
        if let Some(problem) = invalid_mesh(&user) {
            fail(&log, &problem);
        }
    }
    // Leave any tool and dialog, then undo all and redo all.
    for _ in 0..3 {
        user.tap(KeyCode::Escape);
    }
    user.frames(3);
    let end = user.doc().clone();
    let end_steps = user.undo_steps();
    eprintln!(
        "monkey seed {seed}: {events} events, {} undo steps ({} dropped by the limits), {} nodes, {} faces",
        end_steps - start_steps,
        user.app
            .world()
            .resource::<DocState>()
            .session
            .history
            .dropped,
        end.nodes().count(),
        end.nodes()
            .filter_map(|n| n.content.mesh())
            .map(|m| m.face_count())
            .sum::<usize>()
    );
    let mut guard = 0;
    while user.undo_steps() > start_steps && guard < 10_000 {
        user.app.world_mut().write_message(DocRequest::Undo);
        user.frame();
        guard += 1;
    }
    // A hand that lowered "Undo steps kept" in the preferences dropped the
    // oldest steps: undo all then reaches the oldest step kept, not the
    // start, and only the way back to the end can be checked.
    let dropped = user
        .app
        .world()
        .resource::<DocState>()
        .session
        .history
        .dropped;
    if dropped == 0 && (user.undo_steps() != start_steps || user.doc() != &start) {
        let what = format!(
            "undo all does not return to the start ({} undo steps left, {})",
            user.undo_steps() - start_steps,
            first_difference(&start, user.doc())
        );
        fail(&log, &what);
    }
    while user.undo_steps() < end_steps && guard < 20_000 {
        user.app.world_mut().write_message(DocRequest::Redo);
        user.frame();
        guard += 1;
    }
    if user.doc() != &end {
        let what = format!(
            "redo all does not return to the end ({})",
            first_difference(&end, user.doc())
        );
        fail(&log, &what);
    }
    let session = &user.app.world().resource::<DocState>().session;
    let text = hedra_doc::file::to_string(session);
    let loaded = hedra_doc::file::from_str(&text, std::path::Path::new("monkey.hedra.ron"))
        .unwrap_or_else(|e| fail(&log, &format!("the saved scene does not load: {e}")));
    if hedra_doc::file::to_string(&loaded.session) != text {
        fail(&log, "save → load → save differs");
    }
}

/// The first lines where two documents' debug forms differ, to say what a
/// failed undo or redo left behind.
fn first_difference(expected: &impl std::fmt::Debug, got: &impl std::fmt::Debug) -> String {
    let (expected, got) = (format!("{expected:#?}"), format!("{got:#?}"));
    let (a, b): (Vec<&str>, Vec<&str>) = (expected.lines().collect(), got.lines().collect());
    let Some(i) = (0..a.len().max(b.len())).find(|&i| a.get(i) != b.get(i)) else {
        return "the debug forms are equal".into();
    };
    let around = |lines: &[&str]| lines[i.saturating_sub(8)..(i + 4).min(lines.len())].join("\n");
    format!(
        "first difference at line {i} of the debug form; expected:\n{}\ngot:\n{}",
        around(&a),
        around(&b)
    )
}

fn from_env(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// The short version, in CI: three seeds of 150 events.
#[test]
fn a_random_hand_breaks_nothing() {
    for seed in 1..=3 {
        monkey(seed, 150);
    }
}

/// The long version (`scripts/monkey`): `HEDRA_MONKEY_SEEDS` seeds (200) of
/// `HEDRA_MONKEY_EVENTS` events (2,000), from `HEDRA_MONKEY_FIRST` (1000).
#[test]
#[ignore = "long: run by scripts/monkey"]
fn a_random_hand_breaks_nothing_for_long() {
    let first = from_env("HEDRA_MONKEY_FIRST", 1000);
    let seeds = from_env("HEDRA_MONKEY_SEEDS", 200);
    let events = from_env("HEDRA_MONKEY_EVENTS", 2000) as usize;
    for seed in first..first + seeds {
        let t = std::time::Instant::now();
        monkey(seed, events);
        eprintln!(
            "seed {seed}: {events} events clean in {:.1} s",
            t.elapsed().as_secs_f64()
        );
    }
}
