//! `hedra run` scripts: a RON list of [`Command`]s applied in order, each one
//! undo step. Optional fields may be written without `Some(…)`.

use crate::command::{Command, CommandError};
use crate::session::{Applied, Session};
use ron::extensions::Extensions;
use std::path::{Path, PathBuf};

/// Why a script stopped.
#[derive(Debug, thiserror::Error)]
pub enum ScriptError {
    /// The text is not a RON list of commands (an unknown command or field
    /// included).
    #[error("{path}:{line}:{column}: {message}")]
    Parse {
        /// The script file.
        path: PathBuf,
        /// The line of the error, from 1.
        line: usize,
        /// The column of the error, from 1.
        column: usize,
        /// The RON parser's message.
        message: String,
    },
    /// A command was refused; the commands before it stay applied.
    #[error("{path}: command {index} ({label}): {error}")]
    Command {
        /// The script file.
        path: PathBuf,
        /// The command's place in the script, from 1.
        index: usize,
        /// The command's history label ("Extrude Faces").
        label: String,
        /// Boxed: a command's error is large and a script stops at the first.
        error: Box<CommandError>,
    },
}

/// Parses script text into commands.
///
/// # Errors
/// [`ScriptError::Parse`] with line and column (an unknown command name is
/// reported there too).
pub fn parse(text: &str, path: &Path) -> Result<Vec<Command>, ScriptError> {
    let options = ron::Options::default().with_default_extension(Extensions::IMPLICIT_SOME);
    options.from_str(text).map_err(|e| ScriptError::Parse {
        path: path.to_path_buf(),
        line: e.span.start.line,
        column: e.span.start.col,
        message: e.code.to_string(),
    })
}

/// Applies commands in order. On the first failure the session keeps the
/// steps applied so far; callers that must not write partial results
/// (the CLI) simply discard the session.
///
/// # Errors
/// [`ScriptError::Command`] naming the 1-based command index.
pub fn run(
    session: &mut Session,
    commands: &[Command],
    path: &Path,
) -> Result<Vec<Applied>, ScriptError> {
    commands
        .iter()
        .enumerate()
        .map(|(i, c)| {
            session.execute(c).map_err(|error| ScriptError::Command {
                path: path.to_path_buf(),
                index: i + 1,
                label: c.label(),
                error: Box::new(error),
            })
        })
        .collect()
}
