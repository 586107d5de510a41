//! The scene corpus as golden files: a stored scene, loaded today and
//! written with today's writer, against the file today's commands write.

use std::path::Path;

/// A piece of a scene file's text: a number, or the text between numbers.
#[derive(Debug, PartialEq)]
enum Token<'a> {
    Number(f64),
    Text(&'a str),
}

/// The text cut into numbers (`-1.5e-3`, `42`) and what lies between them;
/// digits inside a word (`v2`, `f32`) stay text.
fn tokens(text: &str) -> Vec<Token<'_>> {
    let bytes = text.as_bytes();
    let (mut out, mut start, mut i) = (Vec::new(), 0, 0);
    let word = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    while i < bytes.len() {
        let at_number = (bytes[i].is_ascii_digit()
            || (bytes[i] == b'-' && bytes.get(i + 1).is_some_and(u8::is_ascii_digit)))
            && (i == 0 || !word(bytes[i - 1]));
        if !at_number {
            i += 1;
            continue;
        }
        let mut j = i + 1;
        while j < bytes.len()
            && (bytes[j].is_ascii_digit()
                || matches!(bytes[j], b'.' | b'e' | b'E')
                || (matches!(bytes[j], b'-' | b'+') && matches!(bytes[j - 1], b'e' | b'E')))
        {
            j += 1;
        }
        if let Ok(x) = text[i..j].parse::<f64>() {
            if start < i {
                out.push(Token::Text(&text[start..i]));
            }
            out.push(Token::Number(x));
            start = j;
        }
        i = j;
    }
    if start < bytes.len() {
        out.push(Token::Text(&text[start..]));
    }
    out
}

/// The corpus file `tests/corpus/scenes/<name>`, loaded by today's reader
/// (migrated from its format version) and written by today's writer, is
/// `today` (today's writer on the session today's commands make): the same
/// text, numbers equal to 1e-9 of their size. The corpus files are written
/// once and kept; their numbers may differ from today's in the last bits
/// (a sum taken in another order since), never more.
pub fn assert_matches_corpus(name: &str, today: &str) {
    let path =
        Path::new(&std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"))
            .join("tests/corpus/scenes")
            .join(name);
    let stored = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (the corpus keeps it)", path.display()));
    let loaded = hedra_doc::file::from_str(&stored, &path).unwrap();
    assert!(loaded.warnings.is_empty(), "{name}: {:?}", loaded.warnings);
    let rewritten = hedra_doc::file::to_string(&loaded.session);
    let (a, b) = (tokens(&rewritten), tokens(today));
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        let same = match (x, y) {
            (Token::Number(p), Token::Number(q)) => {
                (p - q).abs() <= 1e-9 * p.abs().max(q.abs()).max(1.0)
            }
            _ => x == y,
        };
        if !same {
            let context: Vec<&Token> = b[k.saturating_sub(12)..k].iter().collect();
            panic!(
                "{name} differs from today's scene at token {k}: stored {x:?}, today {y:?}, after {context:?}"
            );
        }
    }
    assert_eq!(
        a.len(),
        b.len(),
        "{name}: a different length from today's scene"
    );
    assert!(a.len() > 100, "{name}: {} tokens", a.len());
}

#[test]
fn tokens_split_numbers_from_words() {
    assert_eq!(
        tokens("v2: (-1.5e-3, 42) f32"),
        vec![
            Token::Text("v2: ("),
            Token::Number(-1.5e-3),
            Token::Text(", "),
            Token::Number(42.0),
            Token::Text(") f32"),
        ]
    );
}
