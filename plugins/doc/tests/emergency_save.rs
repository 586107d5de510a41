//! The panic hook saves the last committed document as an emergency
//! recovery point (its own test binary: the hook is process-wide).

use hedra_doc::recovery::{self, RecoveryKind, RecoveryPoint};
use hedra_doc::{Command, NodeTransform, Session};
use hedra_geom::Primitive;
use std::sync::{Arc, Mutex};

#[test]
fn a_panic_saves_the_last_committed_document_for_the_next_start() {
    let dir = tempfile::tempdir().unwrap();
    let mut session = Session::new();
    session
        .execute(&Command::AddPrimitive {
            primitive: Primitive::Cube { size: 1.0 },
            name: Some("Saved by the hook".into()),
            parent: None,
            transform: NodeTransform::IDENTITY,
        })
        .unwrap();
    let point = RecoveryPoint::new(dir.path(), None);
    let snapshot: recovery::EmergencySnapshot = Arc::new(Mutex::new(None));
    recovery::install_emergency_save(snapshot.clone());

    // Nothing committed yet: a panic writes nothing.
    assert!(
        std::thread::spawn(|| panic!("first test panic"))
            .join()
            .is_err()
    );
    assert_eq!(std::fs::read_dir(dir.path()).map_or(0, |d| d.count()), 0);

    *snapshot.lock().unwrap() = Some((session.clone(), point.clone()));
    assert!(
        std::thread::spawn(|| panic!("second test panic"))
            .join()
            .is_err()
    );
    let (scene, meta) = point.paths(RecoveryKind::Emergency);
    assert!(scene.is_file() && meta.is_file());

    let offered = recovery::pending_with(dir.path(), &|_| false);
    assert_eq!(offered.len(), 1);
    assert_eq!(offered[0].meta.kind, RecoveryKind::Emergency);
    let mut recovered = recovery::recover(&offered[0]).unwrap().session;
    assert_eq!(recovered.doc, session.doc);
    assert!(recovered.doc.find_by_name("Saved by the hook").is_some());
    assert!(recovered.undo().is_some(), "the history came along");
    assert!(recovered.doc.find_by_name("Saved by the hook").is_none());
}
