//! The stored form of the commands in a scene file's history.
//!
//! Each history step keeps the [`Command`] that made it (the history panel's
//! "adjust last operation" re-issues it). A file stores it as RON, inside the
//! step's `command: Some(…)`. That text is a promise to every file ever
//! written, so it is pinned: `plugins/doc/tests/corpus/commands-v<N>.ron`
//! holds the stored text of at least one example of every command variant
//! for format version `N`, and `tests/stored_commands.rs` fails when the
//! text of any of them changes or a variant is missing there.
//!
//! Files of format versions 1 and 2 store commands in the shape of
//! [`StoredV2`], which is today's [`Command`]: its serde names are the stored
//! names. The in-memory command may still evolve:
//!
//! - a new variant, or a Rust rename kept by `#[serde(rename = "…")]`, leaves
//!   every stored text as it was (the golden file gains the new variant with
//!   `HEDRA_BLESS=1`);
//! - a change of a stored shape (a renamed or split variant, a field with a
//!   new meaning) needs a new format version: freeze the old shape here as
//!   `StoredV<N>` (copies of the command types as the golden file of version
//!   `N` reads them), convert it to the new [`Command`] in
//!   [`parse_history`] and [`from_text`], and bless the golden file of the
//!   new version; the old golden file stays and must still read.

use super::StoredHistory;
use crate::command::Command;
use ron::value::RawValue;

/// The stored shape of a command in files of format versions 1 and 2.
pub type StoredV2 = Command;

/// Why a stored command could not be read.
#[derive(Debug, thiserror::Error)]
pub enum StoredCommandError {
    /// The file's format version is newer (or older) than any this build reads.
    #[error("format version {0} has no stored commands this build knows")]
    Version(u32),
    /// The stored text is not a command of that version (the RON error has the
    /// line and column inside the command text).
    #[error("{0}")]
    Parse(#[from] ron::error::SpannedError),
}

/// The text a scene file stores for a command, exactly as it appears inside
/// a history step's `command: Some(…)`.
pub fn to_text(command: &Command) -> String {
    ron::ser::to_string_pretty(command, config()).expect("commands always serialise")
}

/// Reads the stored text of a command as format version `version` wrote it.
///
/// # Errors
/// [`StoredCommandError::Version`] for a version this build does not read,
/// [`StoredCommandError::Parse`] for text that is not such a command.
pub fn from_text(version: u32, text: &str) -> Result<Command, StoredCommandError> {
    match version {
        1 | 2 => Ok(ron::from_str::<StoredV2>(text)?),
        _ => Err(StoredCommandError::Version(version)),
    }
}

/// The serialisation of a command inside a scene file: past the file's
/// indentation depth, so on one line (see `file::to_string`).
fn config() -> ron::ser::PrettyConfig {
    ron::ser::PrettyConfig::new()
        .depth_limit(0)
        .struct_names(false)
}

/// Parses the history part of a file of format version `version`, its
/// commands converted to today's [`Command`].
/// (Every version this build reads, 1 and 2, stores today's shape; a later
/// version matches on `version` here and converts the older shapes.)
pub(super) fn parse_history(
    version: u32,
    raw: &RawValue,
) -> Result<StoredHistory<Command>, ron::error::SpannedError> {
    debug_assert!((1..=super::FORMAT_VERSION).contains(&version));
    raw.into_rust::<StoredHistory<StoredV2>>()
}
