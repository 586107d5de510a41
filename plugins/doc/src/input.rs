//! The files Hedra reads, checked before they are opened, and the outputs
//! that would write over them, refused (issue 31, item 17).
//!
//! A path that is not a regular file is refused before it is opened: a
//! FIFO (named pipe) would block the read forever (opening it waits for a
//! writer), a directory or a device is never a scene or a mesh. Every
//! reader of the document crate goes through [`read`] (scene files,
//! imports, glTF buffers), so the window refuses them as the command line
//! does.
//!
//! A command that reads some files and writes another refuses to write
//! over any of its inputs ([`refuse_overwrite`]): `hedra import x.obj -o
//! x.obj` would have replaced the mesh with a scene.

use std::io::Read;
use std::path::{Path, PathBuf};

/// What a path names when it is not a regular file, in words for messages
/// ("a FIFO (named pipe)"), `None` for a regular file (symbolic links are
/// followed). Looking does not open the file, so a FIFO does not block.
///
/// # Errors
/// The operating system's error when the path cannot be looked up (it
/// does not exist, a folder on the way cannot be read).
pub fn not_regular(path: &Path) -> std::io::Result<Option<&'static str>> {
    Ok(kind_unless_regular(&std::fs::metadata(path)?.file_type()))
}

fn kind_unless_regular(t: &std::fs::FileType) -> Option<&'static str> {
    if t.is_file() {
        return None;
    }
    if t.is_dir() {
        return Some("a folder");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return Some("a FIFO (named pipe)");
        }
        if t.is_socket() {
            return Some("a socket");
        }
        if t.is_block_device() || t.is_char_device() {
            return Some("a device");
        }
    }
    Some("not a regular file")
}

/// The error [`check`] and [`read`] give for a path that is not a
/// regular file: kind `InvalidInput`, its message saying what the path
/// is (the callers put the path in front).
fn refusal(kind: &str) -> std::io::Error {
    std::io::Error::new(
        std::io::ErrorKind::InvalidInput,
        format!("is {kind}, not a regular file; Hedra reads regular files only"),
    )
}

/// Ok when `path` is a regular file (or a link to one), checked without
/// opening it.
///
/// # Errors
/// An `InvalidInput` error saying what the path is instead (a FIFO, a
/// folder, a device, a socket), or the operating system's error when it
/// cannot be looked up. The message does not repeat the path: callers
/// name it.
pub fn check(path: &Path) -> std::io::Result<()> {
    match not_regular(path)? {
        None => Ok(()),
        Some(kind) => Err(refusal(kind)),
    }
}

/// The whole file at `path`, refused without being opened when it is not
/// a regular file (see [`check`]), and checked again once open (the path
/// may have been replaced in between).
///
/// # Errors
/// As [`check`], and the operating system's read errors.
pub fn read(path: &Path) -> std::io::Result<Vec<u8>> {
    check(path)?;
    let mut file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
    if let Some(kind) = kind_unless_regular(&meta.file_type()) {
        return Err(refusal(kind));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// [`read`] as UTF-8 text.
///
/// # Errors
/// As [`read`], and `InvalidData` when the bytes are not UTF-8.
pub fn read_to_string(path: &Path) -> std::io::Result<String> {
    String::from_utf8(read(path)?)
        .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e))
}

/// True when `a` and `b` name the same existing file: the same device and
/// inode on Unix (so hard links, symbolic links and `./x` versus `x` all
/// count), the same canonical path elsewhere. False when either does not
/// exist.
pub fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        match (std::fs::metadata(a), std::fs::metadata(b)) {
            (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    {
        match (a.canonicalize(), b.canonicalize()) {
            (Ok(x), Ok(y)) => x == y,
            _ => false,
        }
    }
}

/// An output that is one of the command's inputs.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "{}: this is the input file {}; Hedra does not write over a file it reads (choose another output file)",
    output.display(),
    input.display()
)]
pub struct OverwritesInput {
    /// The output path, as given.
    pub output: PathBuf,
    /// The input it names, as given.
    pub input: PathBuf,
}

/// Refuses to write `output` when it is the same file as one of `inputs`
/// ([`same_file`]; an output that does not exist yet is never an input).
///
/// # Errors
/// [`OverwritesInput`] naming the output and the input.
pub fn refuse_overwrite<'a>(
    output: &Path,
    inputs: impl IntoIterator<Item = &'a Path>,
) -> Result<(), OverwritesInput> {
    match inputs.into_iter().find(|i| same_file(output, i)) {
        Some(input) => Err(OverwritesInput {
            output: output.to_path_buf(),
            input: input.to_path_buf(),
        }),
        None => Ok(()),
    }
}
