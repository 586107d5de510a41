//! Damaged scene files never panic: every truncation and many byte flips of a
//! real file give either a scene (possibly without history) or an error.

use hedra_doc::file;
use std::path::Path;

fn sample_text() -> String {
    std::fs::read_to_string(
        std::path::PathBuf::from(
            std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo test"),
        )
        .join("../../assets/samples/table.hedra.ron"),
    )
    .unwrap()
}

#[test]
fn every_truncation_loads_or_fails_cleanly() {
    let text = sample_text();
    let bytes = text.as_bytes();
    let step = (bytes.len() / 400).max(1);
    for cut in (0..bytes.len()).step_by(step) {
        let part = String::from_utf8_lossy(&bytes[..cut]);
        let result = std::panic::catch_unwind(|| {
            file::from_str(&part, Path::new("t.hedra.ron")).map(|l| l.session.doc.node_count())
        });
        assert!(result.is_ok(), "loading the first {cut} bytes panicked");
    }
}

#[test]
fn flipped_digits_and_brackets_load_or_fail_cleanly() {
    let text = sample_text();
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let replacements = [
        "9",
        "-1",
        "4294967295",
        "0",
        "(",
        ")",
        "[",
        "]",
        ",",
        "NaN",
        "inf",
        "1e308",
        "\"",
        "",
    ];
    for _ in 0..600 {
        let mut bytes = text.clone().into_bytes();
        for _ in 0..3 {
            let at = (next() % bytes.len() as u64) as usize;
            let rep = replacements[(next() % replacements.len() as u64) as usize];
            let end = (at + 1).min(bytes.len());
            bytes.splice(at..end, rep.bytes());
        }
        let damaged = String::from_utf8_lossy(&bytes).into_owned();
        let result = std::panic::catch_unwind(|| {
            if let Ok(loaded) = file::from_str(&damaged, Path::new("t.hedra.ron")) {
                // Whatever loads is valid and can be undone and saved.
                let mut s = loaded.session;
                for n in s.doc.nodes() {
                    if let Some(m) = n.content.mesh() {
                        m.validate().expect("a loaded mesh is valid");
                    }
                }
                while s.undo().is_some() {}
                let _ = file::to_string(&s);
            }
        });
        assert!(
            result.is_ok(),
            "a damaged file panicked:\n{}",
            &damaged[..damaged.len().min(400)]
        );
    }
}
