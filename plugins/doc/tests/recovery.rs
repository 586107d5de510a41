//! Recovery points: autosaves and emergency saves, what is offered on start,
//! and that a recovered session keeps its undo history.

use glam::DVec3;
use hedra_doc::recovery::{self, RecoveryKind, RecoveryPoint};
use hedra_doc::{Command, NodeRef, NodeTransform, Session, file};
use hedra_geom::Primitive;
use std::path::Path;

fn edited_session() -> Session {
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: Primitive::Cube { size: 2.0 },
        name: Some("Box".into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s.execute(&Command::Translate {
        nodes: vec![NodeRef::Name("Box".into())],
        offset: DVec3::new(1.0, 2.0, 3.0),
    })
    .unwrap();
    s
}

fn nobody_runs(_: u32) -> bool {
    false
}

fn box_position(s: &Session) -> DVec3 {
    s.doc
        .find_by_name("Box")
        .expect("Box exists")
        .transform
        .translation
}

#[test]
fn an_autosave_of_an_untitled_scene_is_offered_and_recovers_with_its_history() {
    let dir = tempfile::tempdir().unwrap();
    let session = edited_session();
    let point = RecoveryPoint::new(dir.path(), None);
    let written = point.write(&session, RecoveryKind::Autosave).unwrap();
    assert!(written.to_string_lossy().ends_with(".autosave.hedra.ron"));

    // The writing process itself does not get its own point offered.
    assert!(recovery::pending(dir.path()).is_empty());
    let offered = recovery::pending_with(dir.path(), &nobody_runs);
    assert_eq!(offered.len(), 1);
    let entry = &offered[0];
    assert_eq!(entry.meta.original, None);
    assert_eq!(entry.meta.kind, RecoveryKind::Autosave);
    assert_eq!(entry.meta.steps, 2);
    assert_eq!(entry.meta.last_step.as_deref(), Some("Move 1 node"));
    let text = entry.describe(entry.meta.saved_unix_ms + 125_000);
    assert!(
        text.contains("untitled") && text.contains("2 min ago"),
        "{text}"
    );

    let mut recovered = recovery::recover(entry).unwrap().session;
    assert!(
        recovered.is_dirty(),
        "recovered work is not saved anywhere yet"
    );
    assert_eq!(recovered.doc, session.doc);
    assert_eq!(box_position(&recovered), DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(recovered.undo().as_deref(), Some("Move 1 node"));
    assert_eq!(box_position(&recovered), DVec3::ZERO);
}

#[test]
fn a_point_older_than_its_file_is_stale_and_removed() {
    let dir = tempfile::tempdir().unwrap();
    let original = dir.path().join("chair.hedra.ron");
    let mut session = edited_session();
    let point = RecoveryPoint::new(&dir.path().join("recovery"), Some(&original));
    let (scene, meta) = point.paths(RecoveryKind::Autosave);
    point.write(&session, RecoveryKind::Autosave).unwrap();
    assert!(scene.is_file() && meta.is_file());
    let name = scene.file_name().unwrap().to_string_lossy().into_owned();
    assert!(name.starts_with("chair-"), "{name}");

    // The file does not exist yet: offered.
    let offered = recovery::pending_with(&dir.path().join("recovery"), &nobody_runs);
    assert_eq!(offered.len(), 1);
    assert_eq!(
        offered[0].meta.original.as_deref(),
        Some(std::path::absolute(&original).unwrap().as_path())
    );

    // Saved afterwards: the autosave is older than the file.
    std::thread::sleep(std::time::Duration::from_millis(20));
    file::save(&mut session, &original).unwrap();
    assert!(recovery::pending_with(&dir.path().join("recovery"), &nobody_runs).is_empty());
    assert!(!scene.exists() && !meta.exists(), "stale point deleted");
}

#[test]
fn points_of_a_running_hedra_are_not_offered_and_remove_clears_every_kind() {
    let dir = tempfile::tempdir().unwrap();
    let session = edited_session();
    let point = RecoveryPoint::new(dir.path(), Some(Path::new("/nonexistent/a.hedra.ron")));
    point.write(&session, RecoveryKind::Autosave).unwrap();
    point.write(&session, RecoveryKind::Emergency).unwrap();
    point.write(&session, RecoveryKind::Stopped).unwrap();
    assert!(recovery::pending_with(dir.path(), &|_| true).is_empty());
    assert_eq!(recovery::pending_with(dir.path(), &nobody_runs).len(), 3);
    point.remove();
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn adopting_an_emergency_point_makes_it_this_sessions_autosave() {
    let dir = tempfile::tempdir().unwrap();
    let session = edited_session();
    let crashed = RecoveryPoint::new(dir.path(), Some(Path::new("/nonexistent/b.hedra.ron")));
    crashed.write(&session, RecoveryKind::Emergency).unwrap();
    let entry = recovery::pending_with(dir.path(), &nobody_runs).remove(0);
    assert_eq!(entry.meta.kind, RecoveryKind::Emergency);
    assert!(entry.describe(entry.meta.saved_unix_ms).contains("crashed"));

    let now = RecoveryPoint::new(dir.path(), entry.meta.original.as_deref());
    assert_eq!(now, crashed, "the same document gets the same point");
    let adopted = recovery::adopt(&entry, &now);
    let (scene, meta) = now.paths(RecoveryKind::Autosave);
    assert!(scene.is_file() && meta.is_file());
    assert_eq!((adopted.scene, adopted.meta_path), (scene, meta));
    assert!(!entry.scene.exists() && !entry.meta_path.exists());
    // Now owned by this (running) process: not offered to it again.
    assert!(recovery::pending(dir.path()).is_empty());
    let again = recovery::pending_with(dir.path(), &nobody_runs);
    assert_eq!(again.len(), 1);
    assert_eq!(again[0].meta.kind, RecoveryKind::Autosave);
    assert_eq!(again[0].meta.pid, std::process::id());
    assert_eq!(
        recovery::recover(&again[0]).unwrap().session.doc,
        session.doc
    );
}

#[test]
fn damaged_or_partial_points_are_skipped_without_error() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("x.autosave.meta.ron"), "(not a meta").unwrap();
    std::fs::write(dir.path().join("x.autosave.hedra.ron"), "(").unwrap();
    // A meta whose scene is missing.
    let point = RecoveryPoint::new(dir.path(), None);
    point
        .write(&edited_session(), RecoveryKind::Autosave)
        .unwrap();
    std::fs::remove_file(point.paths(RecoveryKind::Autosave).0).unwrap();
    assert!(recovery::pending_with(dir.path(), &nobody_runs).is_empty());
    // A point whose scene is damaged is offered, and recovering names the file.
    let p2 = RecoveryPoint::new(dir.path(), Some(Path::new("/nonexistent/c.hedra.ron")));
    p2.write(&edited_session(), RecoveryKind::Autosave).unwrap();
    std::fs::write(
        p2.paths(RecoveryKind::Autosave).0,
        "(format: \"hedra-scene\", version: 1, meshes: [",
    )
    .unwrap();
    let offered = recovery::pending_with(dir.path(), &nobody_runs);
    assert_eq!(offered.len(), 1);
    let err = recovery::recover(&offered[0]).unwrap_err().to_string();
    assert!(
        err.contains("c-") && err.contains(".autosave.hedra.ron"),
        "{err}"
    );
}

/// A point written on a signal (logout, kill) says so: the offer does not
/// claim Hedra crashed (issue 31).
#[test]
fn a_point_written_on_a_signal_says_stopped_not_crashed() {
    let dir = tempfile::tempdir().unwrap();
    let session = edited_session();
    let point = RecoveryPoint::new(dir.path(), Some(Path::new("/nonexistent/c.hedra.ron")));
    point.write(&session, RecoveryKind::Stopped).unwrap();
    let entry = recovery::pending_with(dir.path(), &nobody_runs).remove(0);
    assert_eq!(entry.meta.kind, RecoveryKind::Stopped);
    let offer = entry.describe(entry.meta.saved_unix_ms);
    assert!(
        offer.contains("stopped") && !offer.contains("crashed"),
        "{offer}"
    );
}
