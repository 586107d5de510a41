//! Killing the process at any moment of a save leaves either the old or the
//! new file complete (`file::write_atomic`: temporary file, sync, `.bak`
//! link, rename).
//!
//! A child process (this test binary, running the ignored `saver_child`)
//! prepares a large scene, waits for "go", saves it over an older file and
//! says "saved". The parent first times one whole save, then kills children
//! with SIGKILL at moments spread from just after "go" to past the end of
//! the save, and each time checks the file on disk.

use hedra_doc::file;
use hedra_doc::{Command, NodeTransform, Session};
use hedra_geom::Primitive;
use std::io::{BufRead, BufReader, Write};
use std::path::Path;
use std::process::{Child, ChildStdout, Command as Process, Stdio};
use std::time::Instant;

const CHILD_ENV: &str = "HEDRA_KILL_TEST_TARGET";

fn scene(rows: u32) -> Session {
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: Primitive::Grid {
            x_segments: rows,
            z_segments: rows,
            size: 2.0,
        },
        name: Some("Grid".into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s
}

/// Run by the parent in a child process: save a big scene over `$CHILD_ENV`
/// when told to.
#[test]
#[ignore = "child process of killing_a_save_at_any_moment_leaves_the_old_or_the_new_file"]
fn saver_child() {
    let target = std::env::var(CHILD_ENV).expect("run by the kill test");
    let text = file::to_string(&scene(320));
    println!("ready");
    let mut line = String::new();
    std::io::stdin().read_line(&mut line).unwrap();
    file::write_atomic(Path::new(&target), &text).unwrap();
    println!("saved");
}

fn spawn(target: &Path) -> (Child, BufReader<ChildStdout>) {
    let mut child = Process::new(std::env::current_exe().unwrap())
        .args(["saver_child", "--exact", "--ignored", "--nocapture"])
        .args(["--test-threads", "1"])
        .env(CHILD_ENV, target)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut out = BufReader::new(child.stdout.take().unwrap());
    wait_for(&mut out, "ready");
    (child, out)
}

fn wait_for(out: &mut BufReader<ChildStdout>, word: &str) {
    let mut line = String::new();
    loop {
        line.clear();
        assert!(
            out.read_line(&mut line).unwrap() > 0,
            "child ended before '{word}'"
        );
        if line.trim_end().ends_with(word) {
            return;
        }
    }
}

#[test]
fn killing_a_save_at_any_moment_leaves_the_old_or_the_new_file() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("work.hedra.ron");
    let old_text = file::to_string(&scene(2));
    let new_text = file::to_string(&scene(320));
    assert!(
        new_text.len() > 4_000_000,
        "the new file is large enough to take a while"
    );

    // Time one whole save.
    file::write_atomic(&target, &old_text).unwrap();
    let (mut child, mut out) = spawn(&target);
    let start = Instant::now();
    child.stdin.as_mut().unwrap().write_all(b"go\n").unwrap();
    wait_for(&mut out, "saved");
    let whole = start.elapsed();
    child.wait().unwrap();
    assert_eq!(std::fs::read_to_string(&target).unwrap(), new_text);

    let trials = 40;
    // Spread over twice the measured save; should saves run slower than the
    // measured one (a busy CI machine), a few later kills follow until one
    // lands after the rename.
    let delays = (0..trials)
        .map(|i| whole.mul_f64(2.0 * f64::from(i) / f64::from(trials - 1)))
        .chain([4.0, 8.0, 16.0, 32.0].map(|k| whole.mul_f64(k)));
    let (mut old_seen, mut new_seen) = (0, 0);
    for (i, delay) in delays.enumerate() {
        if i >= trials as usize && new_seen > 0 {
            break;
        }
        file::write_atomic(&target, &old_text).unwrap();
        let (mut child, _out) = spawn(&target);
        child.stdin.as_mut().unwrap().write_all(b"go\n").unwrap();
        std::thread::sleep(delay);
        child.kill().unwrap();
        child.wait().unwrap();

        let text = std::fs::read_to_string(&target).expect("the file is always there");
        if text == old_text {
            old_seen += 1;
        } else if text == new_text {
            new_seen += 1;
        } else {
            panic!(
                "killed after {delay:?} of a {whole:?} save: the file is neither old nor new ({} bytes)",
                text.len()
            );
        }
        file::load(&target).expect("what is left loads");
    }
    eprintln!(
        "whole save {whole:?}; {trials} kills: {old_seen} left the old file, {new_seen} the new one"
    );
    // Killed saves leave their temporary file; the next save removes them.
    file::write_atomic(&target, &old_text).unwrap();
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(left.len(), 2, "only the file and its .bak remain: {left:?}");
    assert!(old_seen > 0, "some kills landed before the rename");
    assert!(new_seen > 0, "some kills landed after the rename");
}
