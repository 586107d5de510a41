//! The stored form of history commands is pinned (docs/file-format.md,
//! "Stored commands"): `tests/corpus/commands-v<N>.ron` holds, one per line,
//! the text format version `N` stores for examples of every [`Command`]
//! variant. The text of a stored command must never change within a format
//! version, and every older version's golden file must still read.
//!
//! `HEDRA_BLESS=1` writes the golden file of a new format version (from the
//! previous one, read through its migration) and appends the examples of
//! docs/commands.md it lacks (so a new command gets its line); it never
//! changes a line that is already there.

mod common;

use hedra_doc::Command;
use hedra_doc::file::{self, FORMAT_VERSION, stored_command};
use serde::Deserialize;
use std::path::{Path, PathBuf};

fn manifest_dir() -> PathBuf {
    PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo test"))
}

fn golden_path(version: u32) -> PathBuf {
    manifest_dir().join(format!("tests/corpus/commands-v{version}.ron"))
}

const HEADER: &str = "\
// The stored text of history commands, one per line, as format version VERSION
// writes them inside `command: Some(…)`. Pinned by plugins/doc/tests/stored_commands.rs:
// never edit a line; a changed stored shape needs a new format version.
";

/// The entries of a golden file: the lines of its RON list.
fn entries(text: &str) -> Vec<String> {
    text.lines()
        .filter_map(|l| l.strip_prefix("    "))
        .map(|l| l.strip_suffix(',').unwrap_or(l).to_string())
        .collect()
}

fn golden_text(version: u32, entries: &[String]) -> String {
    let mut text = HEADER.replace("VERSION", &version.to_string());
    text.push_str("[\n");
    for e in entries {
        text.push_str(&format!("    {e},\n"));
    }
    text.push_str("]\n");
    text
}

/// The variant name a stored command starts with.
fn variant(entry: &str) -> &str {
    entry.split(['(', ' ']).next().unwrap()
}

/// The serde names of every `Command` variant, from its derived
/// `Deserialize` (which hands them to `deserialize_enum`).
fn command_variants() -> Vec<&'static str> {
    use serde::de::{Error as _, Visitor, value::Error};
    struct Names<'a>(&'a mut &'static [&'static str]);
    impl<'de> serde::Deserializer<'de> for Names<'_> {
        type Error = Error;
        fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Error> {
            Err(Error::custom("not an enum"))
        }
        fn deserialize_enum<V: Visitor<'de>>(
            self,
            _: &'static str,
            variants: &'static [&'static str],
            _: V,
        ) -> Result<V::Value, Error> {
            *self.0 = variants;
            Err(Error::custom("names taken"))
        }
        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
            bytes byte_buf option unit unit_struct newtype_struct seq tuple
            tuple_struct map struct identifier ignored_any
        }
    }
    let mut names: &'static [&'static str] = &[];
    let _ = Command::deserialize(Names(&mut names));
    names.to_vec()
}

/// The examples of docs/commands.md, as commands.
fn docs_examples() -> Vec<Command> {
    let blocks = common::commands_md_blocks();
    let script = format!("[\n{}\n]", blocks.join(",\n"));
    hedra_doc::script::parse(&script, Path::new("docs/commands.md")).unwrap()
}

fn blessing() -> bool {
    std::env::var_os("HEDRA_BLESS").is_some_and(|v| v == "1")
}

/// Writes the current version's golden file when it is missing (from the
/// previous version's, migrated) and appends the docs' examples it lacks.
/// Existing lines are kept as they are.
fn bless() {
    let path = golden_path(FORMAT_VERSION);
    let mut lines = match std::fs::read_to_string(&path) {
        Ok(text) => entries(&text),
        Err(_) => match std::fs::read_to_string(golden_path(FORMAT_VERSION - 1)) {
            Ok(previous) => entries(&previous)
                .iter()
                .map(|e| {
                    let c = stored_command::from_text(FORMAT_VERSION - 1, e)
                        .unwrap_or_else(|err| panic!("{e}: {err}"));
                    stored_command::to_text(&c)
                })
                .collect(),
            Err(_) => Vec::new(),
        },
    };
    for c in docs_examples() {
        let text = stored_command::to_text(&c);
        if !lines.contains(&text) {
            lines.push(text);
        }
    }
    std::fs::write(&path, golden_text(FORMAT_VERSION, &lines)).unwrap();
}

#[test]
fn every_stored_command_reads_and_writes_back_to_the_same_text() {
    if blessing() {
        bless();
    }
    let path = golden_path(FORMAT_VERSION);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|_| {
        panic!(
            "{} is missing: a new format version needs its golden file (HEDRA_BLESS=1)",
            path.display()
        )
    });
    let lines = entries(&text);
    assert_eq!(
        text,
        golden_text(FORMAT_VERSION, &lines),
        "{}: the file is only written by HEDRA_BLESS=1",
        path.display()
    );
    for line in &lines {
        let command = stored_command::from_text(FORMAT_VERSION, line)
            .unwrap_or_else(|e| panic!("a stored command no longer reads: {line}\n{e}"));
        assert_eq!(
            &stored_command::to_text(&command),
            line,
            "the stored text of a {} command changed: keep it with #[serde(rename)] \
             and defaults, or bump the format version with a migration \
             (docs/file-format.md, \"Stored commands\")",
            variant(line)
        );
    }
}

#[test]
fn the_golden_file_has_every_command_variant() {
    let text = std::fs::read_to_string(golden_path(FORMAT_VERSION)).unwrap();
    let mut stored: Vec<&str> = Vec::new();
    let lines = entries(&text);
    for l in &lines {
        if !stored.contains(&variant(l)) {
            stored.push(variant(l));
        }
    }
    let mut stored: Vec<String> = stored.into_iter().map(String::from).collect();
    let mut variants: Vec<String> = command_variants().into_iter().map(String::from).collect();
    stored.sort();
    variants.sort();
    assert_eq!(variants.len(), 94, "{variants:?}");
    assert_eq!(
        stored, variants,
        "every command variant needs a line in the golden file (HEDRA_BLESS=1 appends it)"
    );
}

/// The first format version with a golden file: pinning stored commands
/// began with version 2. Version 1's stored commands are checked by the
/// v1 scene files of the corpus instead (`scene_corpus.rs` loads them and
/// undoes and redoes their whole histories).
const FIRST_PINNED_VERSION: u32 = 2;

#[test]
fn the_golden_files_of_older_versions_still_read() {
    assert!(!golden_path(1).exists(), "version 1 has no golden file");
    for version in FIRST_PINNED_VERSION..FORMAT_VERSION {
        // Every pinned version's file must be there: a deleted one would
        // otherwise pass unread.
        let path = golden_path(version);
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
            panic!(
                "{}: {e}: the golden file of format version {version} is gone",
                path.display()
            )
        });
        let lines = entries(&text);
        assert!(!lines.is_empty(), "{}: no stored commands", path.display());
        for line in lines {
            stored_command::from_text(version, &line).unwrap_or_else(|e| {
                panic!("a command stored by format version {version} no longer reads: {line}\n{e}")
            });
        }
    }
}

/// The golden text is what a saved file holds: every docs example, run and
/// saved, appears in the history as `command: Some(<stored text>)`.
#[test]
fn the_stored_text_is_what_a_saved_file_holds() {
    let commands = docs_examples();
    let mut session = hedra_doc::Session::new();
    hedra_doc::script::run(&mut session, &commands, Path::new("docs/commands.md")).unwrap();
    let text = file::to_string(&session);
    for c in &commands {
        let stored = match c {
            // Version 3: an `AddMesh` names the mesh it made in the pool
            // instead of repeating its positions and polygons.
            Command::AddMesh { name, .. } => {
                format!("command: Some(AddMesh(name: {name:?}, mesh: ")
            }
            c => format!("command: Some({})", stored_command::to_text(c)),
        };
        assert!(text.contains(&stored), "{stored}");
    }
    let again = file::from_str(&text, Path::new("every-command.hedra.ron")).unwrap();
    assert!(again.warnings.is_empty(), "{:?}", again.warnings);
    let read: Vec<&Command> = again
        .session
        .history
        .done()
        .iter()
        .filter_map(|t| t.command.as_ref())
        .collect();
    assert_eq!(read, commands.iter().collect::<Vec<_>>());
}
