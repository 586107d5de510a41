//! Running an independent reference implementation: a Python script of
//! `scripts/` that reads JSON on stdin and prints JSON, with a package
//! pinned in `scripts/requirements.txt` (installed by `scripts/setup`).

use serde_json::Value;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};

/// What `scripts/<script>` prints for `input`. Panics, naming the script
/// and its package, when the reference cannot run.
pub fn run(script: &str, package: &str, input: &Value) -> Value {
    let script = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scripts")
        .join(script);
    let mut child = Command::new("python3")
        .arg(&script)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("python3 runs");
    let mut stdin = child.stdin.take().unwrap();
    let text = serde_json::to_vec(input).unwrap();
    // Written from another thread: a large input must not block on a full
    // pipe while the script's output waits to be read.
    let writer = std::thread::spawn(move || stdin.write_all(&text));
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap().unwrap();
    assert!(
        out.status.success(),
        "{} failed (run scripts/setup: it installs {package} from scripts/requirements.txt): {}",
        script.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("the script prints JSON")
}
