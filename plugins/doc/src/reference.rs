//! Files that another file refers to (a glTF buffer's `uri`): the one place
//! that turns such a reference into a file to read.
//!
//! A file the user opened may name other files; Hedra follows only relative
//! references that stay inside that file's folder (subfolders included).
//! Refused: absolute paths, `..` that leaves the folder, URI schemes
//! (`file:`, `http:`, …) and drive letters, their percent-encoded and
//! backslash forms, and symbolic links whose target lies outside the folder.
//! A reference is a URI reference (RFC 3986, as the glTF 2.0 spec says), so
//! `my%20mesh.bin` names `my mesh.bin`.

use std::io::Read;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Why a reference was not followed. The message completes
/// "`<file>: buffers[0] `…".
#[derive(Debug, Error, Clone, PartialEq, Eq)]
pub enum ReferenceError {
    /// Absolute, a URI scheme or drive letter, `..` past the folder, or a
    /// link out of it.
    #[error("refers to '{reference}', outside the file's folder; refused")]
    Outside {
        /// The reference as the file gives it.
        reference: String,
    },
    /// Percent-decodes to something that is no file name (invalid UTF-8, NUL,
    /// an empty name).
    #[error("refers to '{reference}', which is not a file name; refused")]
    NotAFileName {
        /// The reference as the file gives it.
        reference: String,
    },
    /// Nothing of that name inside the folder.
    #[error("refers to '{reference}', which cannot be found next to the file")]
    Missing {
        /// The reference as the file gives it.
        reference: String,
    },
    /// The file is larger than the size the referring file declares.
    #[error(
        "refers to '{reference}', a file of {actual} bytes where {declared} are declared; not read"
    )]
    TooLarge {
        /// The reference as the file gives it.
        reference: String,
        /// The file's size in bytes.
        actual: u64,
        /// The size the referring file declares, in bytes.
        declared: u64,
    },
    /// The file exists inside the folder but cannot be read.
    #[error("refers to '{reference}', which cannot be read ({message})")]
    Unreadable {
        /// The reference as the file gives it.
        reference: String,
        /// The operating system's error.
        message: String,
    },
}

/// The file that `reference` names inside `folder`, canonical (links
/// resolved), after checking that it lies inside the folder.
///
/// An empty `folder` is the current directory (the parent of `scene.gltf`).
///
/// # Errors
/// [`ReferenceError::Outside`], [`ReferenceError::NotAFileName`] or
/// [`ReferenceError::Missing`]; nothing is read or opened outside `folder`.
pub fn resolve_inside(folder: &Path, reference: &str) -> Result<PathBuf, ReferenceError> {
    let outside = || ReferenceError::Outside {
        reference: reference.to_string(),
    };
    let not_a_name = || ReferenceError::NotAFileName {
        reference: reference.to_string(),
    };
    // RFC 3986: '?' starts the query and '#' the fragment; neither names a file.
    let path_part = reference.split(['?', '#']).next().unwrap_or_default();
    let decoded = percent_encoding::percent_decode_str(path_part)
        .decode_utf8()
        .map_err(|_| not_a_name())?;
    if decoded.contains('\0') {
        return Err(not_a_name());
    }
    // Backslashes are separators as on Windows, so `..\..\x` is `../../x`.
    let relative = decoded.replace('\\', "/");
    // A scheme (`file:`, `http:`) or drive letter (`C:`) sits before the
    // first '/'; a relative reference has no ':' there (RFC 3986 §4.2).
    let has_scheme = |s: &str| s.split('/').next().is_some_and(|first| first.contains(':'));
    if has_scheme(path_part) || has_scheme(&relative) || relative.starts_with('/') {
        return Err(outside());
    }
    let mut parts: Vec<&str> = Vec::new();
    for part in relative.split('/') {
        match part {
            "" | "." => {}
            ".." => {
                parts.pop().ok_or_else(outside)?;
            }
            name => parts.push(name),
        }
    }
    if parts.is_empty() {
        return Err(not_a_name());
    }
    let folder = if folder.as_os_str().is_empty() {
        Path::new(".")
    } else {
        folder
    };
    let missing = || ReferenceError::Missing {
        reference: reference.to_string(),
    };
    let folder = folder.canonicalize().map_err(|_| missing())?;
    let file = parts
        .iter()
        .fold(folder.clone(), |path, part| path.join(part))
        .canonicalize()
        .map_err(|_| missing())?;
    if !file.starts_with(&folder) {
        return Err(outside());
    }
    if file.is_dir() {
        return Err(missing());
    }
    // A FIFO or a device would block the read: refused without opening it.
    match crate::input::check(&file) {
        Ok(()) => Ok(file),
        Err(e) if e.kind() == std::io::ErrorKind::InvalidInput => Err(ReferenceError::Unreadable {
            reference: reference.to_string(),
            message: e.to_string(),
        }),
        Err(_) => Err(missing()),
    }
}

/// Reads the file that `reference` names inside `folder`, refusing one
/// larger than `declared` bytes padded to a multiple of 4 (glTF pads
/// buffers to 4 bytes) before reading it.
///
/// # Errors
/// As [`resolve_inside`], plus [`ReferenceError::TooLarge`] and
/// [`ReferenceError::Unreadable`].
pub fn read_inside(
    folder: &Path,
    reference: &str,
    declared: u64,
) -> Result<Vec<u8>, ReferenceError> {
    let file = resolve_inside(folder, reference)?;
    let unreadable = |e: std::io::Error| ReferenceError::Unreadable {
        reference: reference.to_string(),
        message: e.to_string(),
    };
    let limit = declared.next_multiple_of(4);
    let too_large = |actual| ReferenceError::TooLarge {
        reference: reference.to_string(),
        actual,
        declared,
    };
    let opened = std::fs::File::open(&file).map_err(unreadable)?;
    let actual = opened.metadata().map_err(unreadable)?.len();
    if actual > limit {
        return Err(too_large(actual));
    }
    // The file may grow between the size check and the read: read no more
    // than the limit allows.
    let mut data = Vec::with_capacity(actual as usize);
    opened
        .take(limit + 1)
        .read_to_end(&mut data)
        .map_err(unreadable)?;
    if data.len() as u64 > limit {
        return Err(too_large(data.len() as u64));
    }
    Ok(data)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `root/inside/{a.bin, sub/b c.bin, link_out.bin -> ../outside.bin,
    /// link_in.bin -> a.bin}` and `root/outside.bin`.
    fn folders() -> (tempfile::TempDir, PathBuf) {
        let root = tempfile::tempdir().unwrap();
        let inside = root.path().join("inside");
        std::fs::create_dir_all(inside.join("sub")).unwrap();
        std::fs::write(inside.join("a.bin"), [1u8; 12]).unwrap();
        std::fs::write(inside.join("sub/b c.bin"), [2u8; 12]).unwrap();
        std::fs::write(root.path().join("outside.bin"), [3u8; 12]).unwrap();
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink("../outside.bin", inside.join("link_out.bin")).unwrap();
            std::os::unix::fs::symlink("a.bin", inside.join("link_in.bin")).unwrap();
        }
        (root, inside)
    }

    #[test]
    fn references_inside_the_folder_are_followed() {
        let (_root, inside) = folders();
        let canonical = inside.canonicalize().unwrap();
        for (reference, expected) in [
            ("a.bin", "a.bin"),
            ("./a.bin", "a.bin"),
            ("sub/b%20c.bin", "sub/b c.bin"),
            ("sub/b c.bin", "sub/b c.bin"),
            ("sub\\b%20c.bin", "sub/b c.bin"),
            ("sub/../a.bin", "a.bin"),
            ("%61.bin", "a.bin"),
            ("a.bin?version=2#frag", "a.bin"),
        ] {
            assert_eq!(
                resolve_inside(&inside, reference),
                Ok(canonical.join(expected)),
                "{reference}"
            );
        }
        #[cfg(unix)]
        assert_eq!(
            resolve_inside(&inside, "link_in.bin"),
            Ok(canonical.join("a.bin"))
        );
    }

    #[test]
    fn references_that_leave_the_folder_are_refused() {
        let (_root, inside) = folders();
        let mut hostile = vec![
            "/etc/passwd",
            "../outside.bin",
            "../../../../../../etc/passwd",
            "sub/../../outside.bin",
            "%2e%2e/outside.bin",
            "%2E%2E%2Foutside.bin",
            "%2fetc%2fpasswd",
            "..\\outside.bin",
            "..%5coutside.bin",
            "\\etc\\passwd",
            "\\\\server\\share\\x.bin",
            "//server/share/x.bin",
            "C:\\Windows\\win.ini",
            "c:/windows/win.ini",
            "C%3A%5Cwin.ini",
            "file:///etc/passwd",
            "file:a.bin",
            "FILE:/etc/passwd",
            "http://example.com/a.bin",
            "%66ile:///etc/passwd",
        ];
        if cfg!(unix) {
            hostile.push("link_out.bin");
        }
        for reference in hostile {
            assert_eq!(
                resolve_inside(&inside, reference),
                Err(ReferenceError::Outside {
                    reference: reference.to_string()
                }),
                "{reference}"
            );
        }
    }

    #[test]
    fn names_that_are_no_file_are_refused_or_missing() {
        let (_root, inside) = folders();
        for reference in ["", ".", "sub/..", "a%00.bin", "%ff.bin"] {
            assert!(
                matches!(
                    resolve_inside(&inside, reference),
                    Err(ReferenceError::NotAFileName { .. })
                ),
                "{reference}"
            );
        }
        for reference in ["nothing.bin", "sub", "sub/"] {
            assert!(
                matches!(
                    resolve_inside(&inside, reference),
                    Err(ReferenceError::Missing { .. })
                ),
                "{reference}: {:?}",
                resolve_inside(&inside, reference)
            );
        }
    }

    #[test]
    fn a_file_larger_than_declared_is_not_read() {
        let (_root, inside) = folders();
        assert_eq!(read_inside(&inside, "a.bin", 12), Ok(vec![1u8; 12]));
        // 12 bytes against 9 declared: within the padding to 12.
        assert_eq!(read_inside(&inside, "a.bin", 9).map(|d| d.len()), Ok(12));
        assert_eq!(
            read_inside(&inside, "a.bin", 8),
            Err(ReferenceError::TooLarge {
                reference: "a.bin".into(),
                actual: 12,
                declared: 8
            })
        );
        assert_eq!(
            read_inside(&inside, "a.bin", 8).unwrap_err().to_string(),
            "refers to 'a.bin', a file of 12 bytes where 8 are declared; not read"
        );
    }
}
