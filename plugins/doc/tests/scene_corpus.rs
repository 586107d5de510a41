//! The corpus of scene files (`tests/corpus/scenes`): files as Hedra wrote
//! them, one or more per format version, kept forever. Every one must load
//! (older versions through their migrations), be sound, keep its undo
//! history, and save again in the current format.

use hedra_doc::file::{self, FORMAT_VERSION};
use std::path::PathBuf;

fn corpus() -> Vec<PathBuf> {
    let dir = std::path::PathBuf::from(
        std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo test"),
    )
    .join("tests/corpus/scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("the scene corpus exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.to_string_lossy().ends_with(".hedra.ron"))
        .collect();
    files.sort();
    files
}

/// The `version: N` of a file's header.
fn header_version(text: &str) -> u32 {
    let at = text.find("version:").expect("a version header");
    text[at + 8..]
        .trim_start()
        .chars()
        .take_while(char::is_ascii_digit)
        .collect::<String>()
        .parse()
        .unwrap()
}

#[test]
fn every_format_version_has_files_in_the_corpus() {
    let versions: Vec<u32> = corpus()
        .iter()
        .map(|p| header_version(&std::fs::read_to_string(p).unwrap()))
        .collect();
    assert!(versions.len() >= 6, "{versions:?}");
    for v in 1..=FORMAT_VERSION {
        assert!(
            versions.contains(&v),
            "no corpus file of format version {v}: save one from the build that writes it"
        );
    }
}

#[test]
fn every_corpus_file_loads_is_sound_and_keeps_its_history() {
    for path in corpus() {
        let name = path.display();
        let loaded = file::load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(loaded.warnings.is_empty(), "{name}: {:?}", loaded.warnings);
        let mut session = loaded.session;
        session
            .doc
            .check()
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(session.history.can_undo(), "{name}: the history came along");

        // Saved in the current format, it loads to the same scene and history.
        let text = file::to_string(&session);
        assert_eq!(header_version(&text), FORMAT_VERSION);
        let again = file::from_str(&text, &path).unwrap().session;
        assert_eq!(again.doc, session.doc, "{name}");
        assert_eq!(again.history, session.history, "{name}");

        // Every step undoes to a sound scene and redoes back.
        let end = session.doc.clone();
        let steps = session.history.done().len();
        while session.undo().is_some() {
            session
                .doc
                .check()
                .unwrap_or_else(|e| panic!("{name}: after undo: {e}"));
        }
        session.jump_to(steps);
        assert_eq!(session.doc, end, "{name}: redo returns to the saved scene");

        // The steps the file kept to redo redo to sound scenes, and undo back.
        let to_redo = session.history.undone().len();
        while session.redo().is_some() {
            session
                .doc
                .check()
                .unwrap_or_else(|e| panic!("{name}: after redo: {e}"));
        }
        assert_eq!(session.history.done().len(), steps + to_redo, "{name}");
        session.jump_to(steps);
        assert_eq!(session.doc, end, "{name}: undo returns to the saved scene");
    }
}
