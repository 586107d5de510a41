//! Issue 31, item 17: a path that is not a regular file is refused before
//! it is read (a FIFO used to block the reader forever), by every reader
//! of the document crate (scene files, imports, glTF buffers); and an
//! output that is one of the inputs is refused, by path, hard link or
//! symbolic link.

use hedra_doc::{file, import, input};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

/// Runs `f` on a thread and gives its result, failing the test (instead
/// of hanging it) when it has not returned within 20 s: a reader that
/// opens a FIFO blocks until a writer comes, which none does here.
fn within_time<T: Send + 'static>(what: &str, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(Duration::from_secs(20))
        .unwrap_or_else(|_| panic!("{what} blocked instead of refusing the path"))
}

#[cfg(unix)]
fn fifo(dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(name);
    let status = std::process::Command::new("mkfifo")
        .arg(&path)
        .status()
        .expect("mkfifo runs");
    assert!(status.success(), "mkfifo {}", path.display());
    path
}

#[cfg(unix)]
#[test]
fn a_fifo_is_refused_by_every_reader_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let scene = fifo(dir.path(), "pipe.hedra.ron");
    let shown = scene.display().to_string();
    let message = within_time("file::load", move || {
        file::load(&scene).map(|_| ()).unwrap_err().to_string()
    });
    assert!(message.starts_with(&shown), "{message}");
    assert!(message.contains("FIFO"), "{message}");
    assert!(message.contains("not a regular file"), "{message}");

    for name in ["pipe.obj", "pipe.stl", "pipe.gltf", "pipe.glb"] {
        let path = fifo(dir.path(), name);
        let shown = path.display().to_string();
        let message = within_time("import_file", move || {
            import::import_file(&path)
                .map(|_| ())
                .unwrap_err()
                .to_string()
        });
        assert!(message.starts_with(&shown), "{name}: {message}");
        assert!(message.contains("FIFO"), "{name}: {message}");
    }

    // A glTF whose buffer is a FIFO next to it.
    fifo(dir.path(), "buffer.bin");
    let gltf = dir.path().join("uses-pipe.gltf");
    std::fs::write(
        &gltf,
        r#"{"asset":{"version":"2.0"},"buffers":[{"uri":"buffer.bin","byteLength":36}],
           "nodes":[{"name":"A"}],"scenes":[{"nodes":[0]}],"scene":0}"#,
    )
    .unwrap();
    let shown = gltf.display().to_string();
    let message = within_time("a glTF buffer", move || {
        import::import_file(&gltf)
            .map(|_| ())
            .unwrap_err()
            .to_string()
    });
    assert!(message.starts_with(&shown), "{message}");
    assert!(message.contains("buffer.bin"), "{message}");
    assert!(message.contains("FIFO"), "{message}");

    // The checks themselves.
    let path = dir.path().join("pipe.obj");
    assert_eq!(
        input::not_regular(&path).unwrap(),
        Some("a FIFO (named pipe)")
    );
    assert_eq!(
        input::check(&path).unwrap_err().kind(),
        std::io::ErrorKind::InvalidInput
    );
}

#[test]
fn a_folder_is_refused_by_name_and_a_regular_file_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("looks-like.obj");
    std::fs::create_dir(&folder).unwrap();
    let message = import::import_file(&folder)
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(
        message.starts_with(&folder.display().to_string()),
        "{message}"
    );
    assert!(message.contains("is a folder"), "{message}");
    let scene = dir.path().join("folder.hedra.ron");
    std::fs::create_dir(&scene).unwrap();
    let message = file::load(&scene).map(|_| ()).unwrap_err().to_string();
    assert!(message.contains("is a folder"), "{message}");

    let missing = dir.path().join("missing.obj");
    let message = import::import_file(&missing)
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(
        message.starts_with(&missing.display().to_string()),
        "{message}"
    );

    let plain = dir.path().join("t.obj");
    std::fs::write(&plain, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    assert_eq!(input::not_regular(&plain).unwrap(), None);
    assert_eq!(input::read(&plain).unwrap().len(), 32);
    assert_eq!(import::import_file(&plain).unwrap().len(), 1);
}

#[test]
fn an_output_that_is_an_input_is_refused_by_path_and_by_link() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.obj");
    let b = dir.path().join("b.obj");
    std::fs::write(&a, "v 0 0 0\n").unwrap();
    std::fs::write(&b, "v 0 0 0\n").unwrap();
    let new = dir.path().join("new.hedra.ron");

    let e = input::refuse_overwrite(&a, [b.as_path(), a.as_path()]).unwrap_err();
    assert_eq!(
        (e.output.as_path(), e.input.as_path()),
        (a.as_path(), a.as_path())
    );
    let message = e.to_string();
    assert!(message.starts_with(&a.display().to_string()), "{message}");
    assert!(message.contains("input file"), "{message}");
    assert!(message.contains("choose another output"), "{message}");

    // The same file by another spelling of its path.
    let dotted = dir.path().join(".").join("a.obj");
    assert!(input::refuse_overwrite(&dotted, [a.as_path()]).is_err());
    // A new file, or another existing one, is fine.
    assert!(input::refuse_overwrite(&new, [a.as_path(), b.as_path()]).is_ok());
    assert!(input::refuse_overwrite(&b, [a.as_path()]).is_ok());
    assert!(input::refuse_overwrite(&a, []).is_ok());

    #[cfg(unix)]
    {
        let hard = dir.path().join("hard.obj");
        std::fs::hard_link(&a, &hard).unwrap();
        assert!(input::refuse_overwrite(&hard, [a.as_path()]).is_err());
        let soft = dir.path().join("soft.obj");
        std::os::unix::fs::symlink(&a, &soft).unwrap();
        assert!(input::refuse_overwrite(&soft, [a.as_path()]).is_err());
        assert!(input::refuse_overwrite(&a, [soft.as_path()]).is_err());
    }
}
