//! The RON examples in docs/file-format.md are what Hedra writes today:
//! every line of every example (its pieces between `…`) appears in a corpus
//! scene as this build saves it again.

use hedra_doc::file;
use std::path::PathBuf;

#[test]
fn every_file_format_example_is_what_hedra_writes() {
    let root = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo test"));
    let md = std::fs::read_to_string(root.join("../../docs/file-format.md")).unwrap();
    let mut written = String::new();
    for entry in std::fs::read_dir(root.join("tests/corpus/scenes")).unwrap() {
        let path = entry.unwrap().path();
        let loaded = file::load(&path).unwrap_or_else(|e| panic!("{e}"));
        written.push_str(&file::to_string(&loaded.session));
    }
    let mut in_block = false;
    let mut lines = 0;
    for line in md.lines() {
        match (in_block, line.trim()) {
            (false, "```ron") => in_block = true,
            (true, "```") => in_block = false,
            (true, text) if !text.is_empty() => {
                lines += 1;
                for piece in text.split('…') {
                    assert!(
                        written.contains(piece),
                        "docs/file-format.md shows what Hedra does not write: {piece}"
                    );
                }
            }
            _ => {}
        }
    }
    assert!(lines > 40, "found only {lines} example lines");
}
