//! Why a scene file cannot be read or written: the errors and the
//! problems they name.

use super::{FORMAT_NAME, FORMAT_VERSION};
use crate::scene::{DocumentError, NodeId};
use std::path::PathBuf;

/// Why a scene file could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// Reading or writing the file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The file's header does not say it is a Hedra scene.
    #[error("{path}: not a Hedra scene file ({reason})")]
    NotAScene {
        /// The file.
        path: PathBuf,
        /// What is missing or wrong in the header.
        reason: NotAScene,
    },
    #[error(
        "{path}: written by a newer Hedra (format version {version}); this build reads versions up to {FORMAT_VERSION}"
    )]
    /// A format version above [`FORMAT_VERSION`]: written by a newer build.
    NewerVersion {
        /// The file.
        path: PathBuf,
        /// The version the file gives.
        version: u32,
    },
    /// The scene part is not valid RON of the scene format.
    #[error("{path}:{line}:{column}: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// The line of the error in the file, from 1.
        line: usize,
        /// The column of the error, from 1.
        column: usize,
        /// The RON parser's message.
        message: String,
    },
    /// The scene parsed but cannot be opened (see [`InvalidScene`]).
    #[error("{path}: {error}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// Boxed: the scene problems are large and rare.
        error: Box<InvalidScene>,
    },
}

/// Why a file is not a Hedra scene file at all.
#[derive(Debug, thiserror::Error)]
pub enum NotAScene {
    /// The bytes are not UTF-8 text.
    #[error("not UTF-8 text ({0})")]
    NotUtf8(#[from] std::string::FromUtf8Error),
    /// No `format:` field in the first 1024 characters.
    #[error("no format header")]
    NoFormatHeader,
    /// A `format:` field that is not a quoted string.
    #[error("malformed format header")]
    MalformedFormatHeader,
    /// A `format:` other than `"hedra-scene"`.
    #[error("format is '{format}', expected '{FORMAT_NAME}'")]
    OtherFormat {
        /// The format the file names.
        format: String,
    },
    /// No `version:` field near the start.
    #[error("no version header")]
    NoVersionHeader,
    /// A `version:` field that is not a whole number.
    #[error("malformed version header")]
    MalformedVersionHeader,
    /// `version: 0`.
    #[error("format version 0 does not exist")]
    VersionZero,
    /// The fully parsed `format` or `version` differs from what the header
    /// sniffing read.
    #[error("header fields disagree")]
    HeaderFieldsDisagree,
}

/// What is wrong in a scene file that parsed: the scene cannot be opened.
#[derive(Debug, thiserror::Error)]
pub enum InvalidScene {
    /// Two stored nodes have the same id.
    #[error("two nodes share one id")]
    SharedId {
        /// The shared id.
        node: NodeId,
    },
    /// The scene tree is broken (see [`DocumentError`]).
    #[error(transparent)]
    Document(#[from] DocumentError),
    /// A pooled corner set whose half-edge and number lists do not pair up.
    #[error("corner set {index}: {counts}")]
    CornerSet {
        /// The set's index in the corner pool.
        index: usize,
        /// The list lengths found.
        counts: CornerCounts,
    },
    /// A node refers to a corner set past the end of the pool.
    #[error("node {node} '{name}' uses corner set {index}, which is not stored")]
    MissingCornerSet {
        /// The node's id.
        node: NodeId,
        /// The node's name.
        name: String,
        /// The index it refers to.
        index: usize,
    },
    /// A node refers to a kept mesh past the end of the pool.
    #[error("node {node} '{name}' uses kept mesh {index}, which is not stored")]
    MissingKeptMesh {
        /// The node's id.
        node: NodeId,
        /// The node's name.
        name: String,
        /// The index it refers to.
        index: usize,
    },
    /// A node refers to a mesh past the end of the pool.
    #[error("node {node} '{name}' uses mesh {index}, which is not stored")]
    MissingMesh {
        /// The node's id.
        node: NodeId,
        /// The node's name.
        name: String,
        /// The index it refers to.
        index: usize,
    },
    /// A node parameter that a command would have refused.
    #[error("node {node} '{name}': {problem}")]
    Node {
        /// The node's id.
        node: NodeId,
        /// The node's name.
        name: String,
        /// Which parameter, and why.
        problem: NodeProblem,
    },
    /// A stored curve kind whose data its own command would refuse.
    #[error("node {node}: {error}")]
    Curve {
        /// The node's id.
        node: NodeId,
        /// What is wrong with the curve.
        error: hedra_geom::curves::CurveError,
    },
}

/// A stored corner set whose lists do not pair up.
#[derive(Debug, thiserror::Error)]
#[error(
    "{uv_halfedges} UV half-edges with {uvs} numbers, {normal_halfedges} normal half-edges with {normals} numbers"
)]
pub struct CornerCounts {
    /// Half-edge ids in the UV list.
    pub uv_halfedges: usize,
    /// Numbers in the UV list (two per half-edge expected).
    pub uvs: usize,
    /// Half-edge ids in the normal list.
    pub normal_halfedges: usize,
    /// Numbers in the normal list (three per half-edge expected).
    pub normals: usize,
}

/// A stored mesh node's parameter that a command would have refused.
#[derive(Debug, thiserror::Error)]
pub enum NodeProblem {
    /// Primitive parameters out of range.
    #[error(transparent)]
    Primitive(#[from] hedra_geom::PrimitiveError),
    /// A subdivision modifier level above the maximum.
    #[error("subdivision level {level} is above the maximum {max}")]
    Level {
        /// The level stored.
        level: u32,
        /// The highest level Hedra subdivides to.
        max: u32,
    },
    /// A kept mesh with a face that names no vertex, or a point that is
    /// not finite.
    #[error("kept mesh: {0}")]
    Kept(#[from] crate::kept::KeptMeshError),
    /// A crease sharpness that is negative or not finite.
    #[error("crease sharpness {0} is not a finite value ≥ 0")]
    Sharpness(f64),
    /// A stack modifier with values out of range.
    #[error("modifier {}: {problem}", index + 1)]
    Modifier {
        /// Its index in the stack, from 0.
        index: usize,
        /// What is out of range.
        problem: crate::modifiers::ModifierProblem,
    },
}

/// Why the history part of a file was dropped (the scene opened without it).
#[derive(Debug, thiserror::Error)]
pub enum HistoryError {
    /// The history part is not valid RON of the history format.
    #[error("{message} at history line {line}, column {column}")]
    Parse {
        /// The line of the error, from 1, counted within the history part.
        line: usize,
        /// The column of the error, from 1.
        column: usize,
        /// The RON parser's message.
        message: String,
    },
    /// A stored step holds a node that could not be restored.
    #[error(transparent)]
    Scene(#[from] InvalidScene),
    /// Undoing back from the saved scene, a step's recorded "after" nodes are
    /// not what the scene (or the later steps) leave.
    #[error("step '{label}' does not lead to the state after it")]
    StepDoesNotFit {
        /// The step's label.
        label: String,
    },
    /// Undoing a step would leave a broken scene tree.
    #[error("undoing step '{label}' gives a broken scene: {error}")]
    UndoBreaks {
        /// The step's label.
        label: String,
        /// What would be broken.
        error: DocumentError,
    },
    /// Redoing a step would leave a broken scene tree.
    #[error("redoing step '{label}' gives a broken scene: {error}")]
    RedoBreaks {
        /// The step's label.
        label: String,
        /// What would be broken.
        error: DocumentError,
    },
    /// Replaying the done steps does not give the saved scene.
    #[error("the steps do not lead to the saved scene")]
    WrongEnd,
    /// An undone step's recorded "before" nodes are not what the saved scene
    /// (or the redo steps before it) leave.
    #[error("redo step '{label}' does not start from the scene")]
    RedoDoesNotStart {
        /// The step's label.
        label: String,
    },
    /// A stored `AddMesh` names a mesh the pool does not have.
    #[error("step '{label}': its command names a mesh that is not stored")]
    MissingCommandMesh {
        /// The step's label.
        label: String,
    },
    /// Step serial numbers do not increase, or reach the history's next serial.
    #[error("step serial numbers are out of order")]
    SerialsOutOfOrder,
}
