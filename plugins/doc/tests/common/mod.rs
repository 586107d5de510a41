//! What several test files read from docs/commands.md.

/// The ```ron blocks of docs/commands.md, trimmed, in order.
pub fn commands_md_blocks() -> Vec<String> {
    let dir = std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo test");
    let md =
        std::fs::read_to_string(std::path::Path::new(&dir).join("../../docs/commands.md")).unwrap();
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in md.lines() {
        match (&mut current, line.trim_start()) {
            (None, "```ron") => current = Some(String::new()),
            (Some(b), "```") => {
                blocks.push(b.trim().to_string());
                current = None;
            }
            (Some(b), _) => {
                b.push_str(line);
                b.push('\n');
            }
            _ => {}
        }
    }
    blocks
}
