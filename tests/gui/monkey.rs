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
//! A failure prints the seed, the events so far, and the shortest list of
//! them found that still fails the same way (delta debugging on replays
//! in fresh apps, [`shrink`]). The short version runs
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

/// One thing a user did, recorded so that a failing run can be replayed
/// and shrunk. What depends on the screen is kept by what the user aimed
/// at (a widget's text, the n-th mesh), so that a replay of fewer events
/// still aims at it.
#[derive(Clone, Debug, PartialEq)]
enum Event {
    /// A primitive or a kept (non-manifold) mesh added through its
    /// command, given as its text (the hand's first move on an empty
    /// scene).
    Add(&'static str),
    Tap(KeyCode),
    Shortcut(&'static [KeyCode], KeyCode),
    KeysInOneFrame(Vec<KeyCode>),
    Click(Vec2),
    Drag(Vec2, Vec2, usize),
    Wheel(f32),
    /// Click the n-th mesh (modulo their count) where its origin shows,
    /// then Tab.
    EditMesh(usize),
    MoveTo(Vec2),
    /// Click the first widget with this text (a frame when none shows).
    ClickWidget(String),
}

impl std::fmt::Display for Event {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Event::Add(command) => write!(f, "{command}"),
            Event::Tap(k) => write!(f, "tap {k:?}"),
            Event::Shortcut(mods, k) => write!(f, "shortcut {mods:?} {k:?}"),
            Event::KeysInOneFrame(keys) => write!(f, "keys in one frame {keys:?}"),
            Event::Click(at) => write!(f, "click {at}"),
            Event::Drag(from, to, steps) => write!(f, "drag {from} → {to} in {steps} steps"),
            Event::Wheel(lines) => write!(f, "wheel {lines}"),
            Event::EditMesh(n) => write!(f, "click mesh {n} where its origin shows and Tab"),
            Event::MoveTo(at) => write!(f, "move to {at}"),
            Event::ClickWidget(text) => write!(f, "click widget '{text}'"),
        }
    }
}

/// Three quads on one edge, beside the z axis at x = 3: a mesh kept as
/// imported (issue 37).
const KEPT_FIN: &str = "AddKeptMesh(name: \"Fin\", positions: [(0.0, 0.0, 0.0), (0.0, 0.0, 1.0), (1.0, 0.0, 0.0), (1.0, 0.0, 1.0), (0.0, 1.0, 0.0), (0.0, 1.0, 1.0), (-1.0, 0.0, 0.0), (-1.0, 0.0, 1.0)], faces: [[0, 2, 3, 1], [1, 5, 4, 0], [0, 6, 7, 1]], transform: (translation: (3.0, 0.0, 0.0)))";

/// The hand's next event. An empty scene gets a primitive first, as a
/// user would add one.
fn choose(user: &User, hand: &mut Hand) -> Event {
    if user.doc().nodes().next().is_none() {
        return Event::Add(
            [
                "AddPrimitive(primitive: Cube(size: 2.0))",
                "AddPrimitive(primitive: UvSphere(segments: 12, rings: 6, radius: 1.0))",
                "AddPrimitive(primitive: Cylinder(segments: 8, radius: 1.0, depth: 2.0))",
                KEPT_FIN,
            ][hand.below(4)],
        );
    }
    let view = user.viewport();
    let point = |hand: &mut Hand| {
        Vec2::new(
            view.min.x + 4.0 + hand.unit() * (view.width() - 8.0),
            view.min.y + 4.0 + hand.unit() * (view.height() - 8.0),
        )
    };
    match hand.below(100) {
        0..=44 => Event::Tap(KEYS[hand.below(KEYS.len())]),
        45..=54 => {
            let (mods, key) = CHORDS[hand.below(CHORDS.len())];
            Event::Shortcut(mods, key)
        }
        55..=59 => Event::KeysInOneFrame(
            (0..2 + hand.below(3))
                .map(|_| KEYS[hand.below(KEYS.len())])
                .collect(),
        ),
        60..=71 => Event::Click(point(hand)),
        72..=79 => {
            let (from, to) = (point(hand), point(hand));
            Event::Drag(from, to, 1 + hand.below(4))
        }
        80..=83 => Event::Wheel(hand.below(5) as f32 - 2.0),
        84..=85 => Event::EditMesh(hand.below(1 << 16)),
        86..=87 => Event::MoveTo(point(hand)),
        _ => {
            let widgets: Vec<String> = user
                .widgets()
                .iter()
                .filter(|w| !w.text.is_empty() && !forbidden(&w.text))
                .map(|w| w.text.clone())
                .collect();
            match widgets.len() {
                0 => Event::MoveTo(point(hand)),
                n => Event::ClickWidget(widgets[hand.below(n)].clone()),
            }
        }
    }
}

/// Sends `event` to the app as a user would.
fn apply(user: &mut User, event: &Event) {
    match event {
        Event::Add(command) => {
            user.app.world_mut().write_message(DocRequest::Execute(
                ron::from_str(command).expect("a command"),
            ));
            user.frames(2);
        }
        Event::Tap(key) => user.tap(*key),
        Event::Shortcut(mods, key) => user.shortcut(mods, *key),
        Event::KeysInOneFrame(keys) => user.taps_in_one_frame(keys),
        Event::Click(at) => user.click(*at),
        Event::Drag(from, to, steps) => user.drag(*from, *to, *steps),
        Event::Wheel(lines) => user.wheel(*lines),
        Event::EditMesh(n) => {
            let view = user.viewport();
            let meshes: Vec<DVec3> = user
                .doc()
                .nodes()
                .filter(|n| n.content.mesh().is_some())
                .map(|n| user.doc().world_matrix(n.id).transform_point3(DVec3::ZERO))
                .collect();
            let at = meshes
                .get(n % meshes.len().max(1))
                .and_then(|origin| user.try_screen_of(origin.as_vec3()))
                .filter(|p| view.contains(egui::pos2(p.x, p.y)));
            match at {
                Some(at) => {
                    user.tap(KeyCode::Escape);
                    user.click(at);
                    user.tap(KeyCode::Tab);
                }
                None => user.frame(),
            }
        }
        Event::MoveTo(at) => {
            user.move_to(*at);
            user.frame();
        }
        Event::ClickWidget(text) => {
            let at = user
                .widgets()
                .iter()
                .find(|w| &w.text == text)
                .map(|w| Vec2::new(w.rect.center().x, w.rect.center().y));
            match at {
                Some(at) => user.click(at),
                None => user.frame(),
            }
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

/// What kind of failure a run found: a shrunk run must fail the same way.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Panic,
    Invalid,
    Undo,
    Redo,
    SaveLoad,
}

/// A violation: its kind, what it says, and how many events had been sent.
#[derive(Debug)]
struct Failure {
    kind: Kind,
    what: String,
    after: usize,
}

/// A run of the hand (or a replay): a fresh windowless app with one cube,
/// the start recorded for the final checks.
struct Run {
    user: User,
    start: hedra_doc::Document,
    start_steps: usize,
}

/// A check beside validation (tests of the shrinker inject one).
type Check = fn(&User) -> Option<String>;

impl Run {
    fn new() -> Run {
        // The start is the empty scene before the first step: the hand may
        // undo the cube too.
        let mut user = User::new();
        // Saves and exports go beside a scene file in the test's own folder
        // (the hand may press Ctrl+S, or type into a path prompt and Enter).
        let scene_path = user.config_dir().join("monkey.hedra.ron");
        user.app.world_mut().resource_mut::<DocState>().path = Some(scene_path);
        let start = user.doc().clone();
        let start_steps = user.undo_steps();
        user.add("Cube");
        // And a mesh kept as imported (not manifold), beside the cube.
        apply(&mut user, &Event::Add(KEPT_FIN));
        Run {
            user,
            start,
            start_steps,
        }
    }

    /// Sends one event and checks every mesh (and `extra`) after it.
    fn step(&mut self, event: &Event, n: usize, extra: Option<Check>) -> Result<(), Failure> {
        let user = &mut self.user;
        let sent = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| apply(user, event)));
        let fail = |kind, what| {
            Err(Failure {
                kind,
                what,
                after: n + 1,
            })
        };
        if sent.is_err() {
            return fail(Kind::Panic, format!("event {n} panicked"));
        }
        if let Some(problem) =
            invalid_mesh(&self.user).or_else(|| extra.and_then(|c| c(&self.user)))
        {
            return fail(Kind::Invalid, format!("after event {n}: {problem}"));
        }
        Ok(())
    }

    /// Leaves any tool, then undo all, redo all, and save → load → save.
    fn finish(mut self, events: usize) -> Result<(), Failure> {
        let user = &mut self.user;
        let fail = |kind, what| {
            Err(Failure {
                kind,
                what,
                after: events,
            })
        };
        for _ in 0..3 {
            user.tap(KeyCode::Escape);
        }
        user.frames(3);
        let end = user.doc().clone();
        let end_steps = user.undo_steps();
        let history = |user: &User| {
            user.app
                .world()
                .resource::<DocState>()
                .session
                .history
                .dropped
        };
        eprintln!(
            "monkey: {events} events, {} undo steps ({} dropped by the limits), {} nodes, {} faces",
            end_steps - self.start_steps,
            history(user),
            end.nodes().count(),
            end.nodes()
                .filter_map(|n| n.content.mesh())
                .map(|m| m.face_count())
                .sum::<usize>()
        );
        let mut guard = 0;
        while user.undo_steps() > self.start_steps && guard < 10_000 {
            user.app.world_mut().write_message(DocRequest::Undo);
            user.frame();
            guard += 1;
        }
        // A hand that lowered "Undo steps kept" in the preferences dropped
        // the oldest steps: undo all then reaches the oldest step kept, not
        // the start, and only the way back to the end can be checked.
        if history(user) == 0
            && (user.undo_steps() != self.start_steps || user.doc() != &self.start)
        {
            return fail(
                Kind::Undo,
                format!(
                    "undo all does not return to the start ({} undo steps left, {})",
                    user.undo_steps() - self.start_steps,
                    first_difference(&self.start, user.doc())
                ),
            );
        }
        while user.undo_steps() < end_steps && guard < 20_000 {
            user.app.world_mut().write_message(DocRequest::Redo);
            user.frame();
            guard += 1;
        }
        if user.doc() != &end {
            return fail(
                Kind::Redo,
                format!(
                    "redo all does not return to the end ({})",
                    first_difference(&end, user.doc())
                ),
            );
        }
        let session = &user.app.world().resource::<DocState>().session;
        let text = hedra_doc::file::to_string(session);
        match hedra_doc::file::from_str(&text, std::path::Path::new("monkey.hedra.ron")) {
            Err(e) => fail(
                Kind::SaveLoad,
                format!("the saved scene does not load: {e}"),
            ),
            Ok(loaded) if hedra_doc::file::to_string(&loaded.session) != text => {
                fail(Kind::SaveLoad, "save → load → save differs".into())
            }
            Ok(_) => Ok(()),
        }
    }
}

/// Runs `events` random events from `seed` with the checks; on a failure
/// returns the events sent up to it and the failure.
fn run_seed(seed: u64, events: usize, extra: Option<Check>) -> Result<(), (Vec<Event>, Failure)> {
    let mut run = Run::new();
    let mut hand = Hand(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let mut sent = Vec::with_capacity(events);
    for n in 0..events {
        let event = choose(&run.user, &mut hand);
        sent.push(event);
        if let Err(failure) = run.step(&sent[n], n, extra) {
            return Err((sent, failure));
        }
    }
    run.finish(events).map_err(|failure| (sent, failure))
}

/// Replays `events` with the checks (a fresh app): the failure, if any.
fn replay(events: &[Event], extra: Option<Check>) -> Option<Failure> {
    let mut run = Run::new();
    for (n, event) in events.iter().enumerate() {
        if let Err(failure) = run.step(event, n, extra) {
            return Some(failure);
        }
    }
    run.finish(events.len()).err()
}

/// The shortest sublist of `events` found for which `fails` still holds,
/// by delta debugging (A. Zeller, "Simplifying and Isolating
/// Failure-Inducing Input", 2002): drop chunks of half the list, then of
/// smaller and smaller sizes down to single events, keeping every drop
/// after which it still fails. `fails` may also cut the list (it returns
/// how many of the events it needed), as a replay stops at its failure.
/// Stops at `deadline` with the shortest list so far.
fn shrink<T: Clone>(
    events: &[T],
    mut fails: impl FnMut(&[T]) -> Option<usize>,
    deadline: std::time::Instant,
) -> Vec<T> {
    let mut shortest = events.to_vec();
    let mut chunk = shortest.len().div_ceil(2);
    while chunk > 0 && std::time::Instant::now() < deadline {
        let mut i = 0;
        while i < shortest.len() && std::time::Instant::now() < deadline {
            let mut candidate = shortest[..i].to_vec();
            candidate.extend_from_slice(&shortest[(i + chunk).min(shortest.len())..]);
            match fails(&candidate) {
                Some(needed) => {
                    candidate.truncate(needed);
                    shortest = candidate;
                }
                None => i += chunk,
            }
        }
        chunk /= 2;
    }
    shortest
}

/// Runs a seed; on a failure shrinks its events (for at most
/// `HEDRA_MONKEY_SHRINK_SECS`, 300 by default) to a list that still fails
/// the same way, and panics with the seed, the failure and both lists.
fn monkey(seed: u64, events: usize) {
    let Err((sent, failure)) = run_seed(seed, events, None) else {
        return;
    };
    let budget = std::time::Duration::from_secs(from_env("HEDRA_MONKEY_SHRINK_SECS", 300));
    let kind = failure.kind;
    let sent = &sent[..failure.after.min(sent.len())];
    let shrunk = shrink(
        sent,
        |events| {
            replay(events, None)
                .filter(|f| f.kind == kind)
                .map(|f| f.after)
        },
        std::time::Instant::now() + budget,
    );
    let list = |events: &[Event]| {
        let mut log = String::new();
        for (i, e) in events.iter().enumerate() {
            let _ = writeln!(log, "{i}: {e}");
        }
        log
    };
    let again =
        replay(&shrunk, None).map_or("(the shrunk list no longer fails)".into(), |f| f.what);
    panic!(
        "monkey seed {seed}: {}\n\nshrunk to {} of {} events, which fail with: {again}\n{}\nall events:\n{}",
        failure.what,
        shrunk.len(),
        sent.len(),
        list(&shrunk),
        list(sent)
    );
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

/// The shrinker keeps what makes a list fail: here an 8 followed later by
/// a 3, hidden in 200 numbers; and a list cut at its failure stays cut.
#[test]
fn shrinking_finds_the_events_that_fail() {
    let events: Vec<u32> = (0..200).map(|i| (i * 7 + 1) % 10).collect();
    let fails = |e: &[u32]| {
        let eight = e.iter().position(|&x| x == 8)?;
        let three = e[eight..].iter().position(|&x| x == 3)?;
        Some(eight + three + 1)
    };
    assert!(fails(&events).is_some());
    let far = std::time::Instant::now() + std::time::Duration::from_secs(60);
    assert_eq!(shrink(&events, fails, far), vec![8, 3]);
    // A passed deadline returns the list as it was.
    let past = std::time::Instant::now();
    assert_eq!(shrink(&events, fails, past).len(), 200);
}

/// The monkey's own shrinking on the real app: a check that calls a moved
/// object a violation fails a seeded run after a few events (a tool, then
/// the mouse), and the shrunk list is a handful of events that, replayed,
/// fail the same way.
#[test]
fn a_failing_run_shrinks_to_the_events_that_matter() {
    fn moved(user: &User) -> Option<String> {
        let doc = user.doc();
        let node = doc.nodes().next()?;
        let origin = doc.world_matrix(node.id).transform_point3(DVec3::ZERO);
        (origin.length() > 1e-6).then(|| format!("'{}' moved to {origin}", node.name))
    }
    let (sent, failure) = (1..20)
        .filter_map(|seed| run_seed(seed, 60, Some(moved)).err())
        .find(|(_, failure)| failure.after >= 5)
        .expect("some seed moves the object after 5 to 60 events");
    assert_eq!(failure.kind, Kind::Invalid);
    let far = std::time::Instant::now() + std::time::Duration::from_secs(240);
    let shrunk = shrink(
        &sent[..failure.after],
        |events| replay(events, Some(moved)).map(|f| f.after),
        far,
    );
    eprintln!("{} events shrunk to {shrunk:?}", failure.after);
    let again = replay(&shrunk, Some(moved)).expect("the shrunk list fails");
    assert_eq!(again.kind, Kind::Invalid);
    assert!(
        shrunk.len() <= 4 && shrunk.len() < failure.after,
        "{} of {} events left: {shrunk:?}",
        shrunk.len(),
        failure.after
    );
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
