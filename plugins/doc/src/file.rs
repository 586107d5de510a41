//! The `.hedra.ron` scene file: the scene and its undo history in one RON
//! document.
//!
//! ```text
//! (
//!     format: "hedra-scene",
//!     version: 3,
//!     meshes: [ ... ],            // mesh pool, shared by nodes and history
//!     corners: [ ... ],           // corner attribute pool (UVs, normals)
//!     scene: (next_node_id: 4, nodes: [ ... ]),
//!     history: (meshes: [ ... ], corners: [ ... ], done: [ ... ], ...),
//! )
//! ```
//!
//! Meshes are stored once in a pool and referenced by index, so the many
//! history steps that share a mesh cost one copy. Corner attributes (the
//! UVs and normals of imported meshes) are pooled the same way, as flat
//! lists of half-edge ids and numbers (version 2; version 1 kept them
//! inline in every node and history step, as maps). The history comes last and
//! is read separately: when it is damaged the scene still opens, without
//! undo, and the caller gets a warning. Saving is atomic: a temporary file in
//! the same folder is written and synced, the old file is kept as
//! `.hedra.ron.bak`, and a rename puts the new file in place.
//!
//! Format versions: version 1 files are read as they are (version 2 only
//! adds the corner pool and `corner_set` references); version 3 stores
//! meshes as polygons plus the ids they cannot give (`file/mesh_text.rs`,
//! `hedra_geom::PolygonData`) instead of every half-edge record, and an
//! `AddMesh` command names the pool mesh it made. One reader takes every
//! version (a mesh's form is told by its fields); a newer build's file is
//! refused by name. The commands in the history have a stored form of
//! their own, pinned per version ([`stored_command`]). `docs/file-format.md`
//! describes the format for other tools.

use crate::command::Command;
use crate::history::{History, NodeChange, Transaction};
use crate::scene::{
    CornerAttributes, CurveContent, Document, DocumentError, MeshContent, Node, NodeContent,
    NodeId, NodeTransform, Shading, SubdivisionModifier,
};
use crate::session::Session;
use hedra_geom::subdivision::Creases;
use hedra_geom::{HalfEdgeMesh, Primitive};
use ron::value::RawValue;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use stored_command::WriteCommand;

mod mesh_text;
pub mod stored_command;

/// The format name written at the top of every scene file.
pub const FORMAT_NAME: &str = "hedra-scene";
/// The newest format version this build reads and the one it writes.
pub const FORMAT_VERSION: u32 = 3;
/// The scene file extension.
pub const EXTENSION: &str = "hedra.ron";

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

/// A scene read from a file, with what the reader had to give up.
#[derive(Debug)]
pub struct Loaded {
    /// The scene with its history (empty when the history was dropped),
    /// marked as saved.
    pub session: Session,
    /// Problems that did not stop the scene from opening (damaged history).
    pub warnings: Vec<String>,
}

// ----- stored forms --------------------------------------------------------

#[derive(Serialize, Deserialize)]
enum StoredContent {
    Empty,
    Mesh {
        mesh: usize,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        primitive: Option<Primitive>,
        #[serde(default)]
        shading: Shading,
        #[serde(default, skip_serializing_if = "Creases::is_empty")]
        creases: Creases,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        subdivision: Option<SubdivisionModifier>,
        /// The modifier stack (Mirror, Array), in order.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        modifiers: Vec<crate::modifiers::MeshModifier>,
        /// UVs and normals of face corners, by half-edge id, inline
        /// (version 1; version 2 writes `corner_set` instead).
        #[serde(default, skip_serializing_if = "CornerAttributes::is_empty")]
        corners: CornerAttributes,
        /// Index of the node's corner attributes in the corner pool.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        corner_set: Option<usize>,
        /// The progressive records of the Decimate modifiers (base mesh
        /// and vertex splits each); absent without Decimate modifiers.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        decimations: Vec<crate::modifiers::DecimateRecord>,
    },
    /// A NURBS curve node (every curve before curve kinds).
    Curve(hedra_geom::curves::NurbsCurve),
    Surface(crate::scene::SurfaceShape),
    /// A curve node of any other kind; its NURBS form is recomputed on load.
    CurveKind(hedra_geom::curves::CurveKind),
    /// A CSG node (issue 17): its operands are its children.
    Csg(crate::csg::CsgContent),
}

#[derive(Serialize, Deserialize)]
struct StoredNode {
    id: NodeId,
    name: String,
    #[serde(default)]
    parent: Option<NodeId>,
    #[serde(default)]
    transform: NodeTransform,
    #[serde(default = "visible_default")]
    visible: bool,
    content: StoredContent,
    /// How the node was made from other nodes while it follows them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    construction: Option<crate::construction::Construction>,
    /// On a patch kept G1 to a Bézier triangle: the triangle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    g1_join: Option<crate::join::G1Join>,
}

fn visible_default() -> bool {
    true
}

fn none<C>() -> Option<C> {
    None
}

#[derive(Serialize, Deserialize)]
struct StoredScene {
    next_node_id: u64,
    nodes: Vec<StoredNode>,
}

#[derive(Serialize, Deserialize)]
struct StoredChange {
    id: NodeId,
    before: Option<StoredNode>,
    after: Option<StoredNode>,
}

/// One history step. `C` is the stored command of the file's version
/// ([`stored_command`]): reading parses the version's own shape and
/// converts it to today's [`Command`].
#[derive(Serialize, Deserialize)]
pub(super) struct StoredTransaction<C> {
    serial: u64,
    label: String,
    #[serde(default = "none")]
    command: Option<C>,
    changes: Vec<StoredChange>,
    next_id_before: u64,
    next_id_after: u64,
}

impl<C> StoredTransaction<C> {
    /// The same step with its command converted.
    fn map_command<D>(self, f: impl FnOnce(C) -> D) -> StoredTransaction<D> {
        StoredTransaction {
            serial: self.serial,
            label: self.label,
            command: self.command.map(f),
            changes: self.changes,
            next_id_before: self.next_id_before,
            next_id_after: self.next_id_after,
        }
    }
}

/// One mesh's corner attributes, compactly: the half-edge ids that have a
/// UV and the UVs as `u, v` pairs, the ids that have a normal and the
/// normals as `x, y, z` triples.
#[derive(Serialize, Deserialize, Default)]
struct StoredCorners {
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    uv_halfedges: Vec<u32>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    uvs: Vec<f64>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    normal_halfedges: Vec<u32>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    normals: Vec<f64>,
}

impl StoredCorners {
    fn of(c: &CornerAttributes) -> StoredCorners {
        StoredCorners {
            uv_halfedges: c.uvs.keys().map(|h| h.0).collect(),
            uvs: c.uvs.values().flat_map(|uv| uv.to_array()).collect(),
            normal_halfedges: c.normals.keys().map(|h| h.0).collect(),
            normals: c.normals.values().flat_map(|n| n.to_array()).collect(),
        }
    }

    fn restore(self) -> Result<CornerAttributes, CornerCounts> {
        if self.uvs.len() != 2 * self.uv_halfedges.len()
            || self.normals.len() != 3 * self.normal_halfedges.len()
        {
            return Err(CornerCounts {
                uv_halfedges: self.uv_halfedges.len(),
                uvs: self.uvs.len(),
                normal_halfedges: self.normal_halfedges.len(),
                normals: self.normals.len(),
            });
        }
        let id = hedra_geom::HalfEdgeId;
        Ok(CornerAttributes {
            uvs: Arc::new(
                self.uv_halfedges
                    .iter()
                    .zip(self.uvs.chunks_exact(2))
                    .map(|(h, c)| (id(*h), glam::DVec2::new(c[0], c[1])))
                    .collect(),
            ),
            normals: Arc::new(
                self.normal_halfedges
                    .iter()
                    .zip(self.normals.chunks_exact(3))
                    .map(|(h, c)| (id(*h), glam::DVec3::new(c[0], c[1], c[2])))
                    .collect(),
            ),
        })
    }
}

/// The history part. `M` is a stored mesh when reading; when writing the
/// list is left empty and the meshes' text put in its place
/// ([`mesh_text`]).
#[derive(Serialize, Deserialize)]
struct StoredHistory<C, M> {
    /// Meshes only the history uses; index `i` here is pool index `scene_meshes + i`.
    meshes: Vec<M>,
    /// Corner attributes only the history uses, numbered after the scene's.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    corners: Vec<StoredCorners>,
    done: Vec<StoredTransaction<C>>,
    undone: Vec<StoredTransaction<C>>,
    #[serde(default)]
    dropped: usize,
    next_serial: u64,
    max_steps: usize,
}

#[derive(Serialize)]
struct FileOut<'a> {
    format: &'static str,
    version: u32,
    /// Left empty: the pool's text is put in its place.
    meshes: Vec<()>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    corners: Vec<StoredCorners>,
    scene: StoredScene,
    history: StoredHistory<WriteCommand<'a>, ()>,
}

#[derive(Deserialize)]
struct FileIn {
    format: String,
    version: u32,
    meshes: Vec<mesh_text::StoredMesh>,
    #[serde(default)]
    corners: Vec<StoredCorners>,
    scene: StoredScene,
    #[serde(default)]
    history: Option<Box<RawValue>>,
}

// ----- writing ---------------------------------------------------------------

/// Collects meshes and corner attributes into pools, each `Arc` once.
struct MeshPool<'a> {
    index: HashMap<*const HalfEdgeMesh, usize>,
    meshes: Vec<&'a HalfEdgeMesh>,
    /// Corner attributes by the identity of their two shared maps.
    corner_index: HashMap<(usize, usize), usize>,
    corner_sets: Vec<&'a CornerAttributes>,
}

impl<'a> MeshPool<'a> {
    fn add(&mut self, m: &'a Arc<HalfEdgeMesh>) -> usize {
        *self.index.entry(Arc::as_ptr(m)).or_insert_with(|| {
            self.meshes.push(m);
            self.meshes.len() - 1
        })
    }
    fn add_corners(&mut self, c: &'a CornerAttributes) -> usize {
        let key = (
            Arc::as_ptr(&c.uvs) as usize,
            Arc::as_ptr(&c.normals) as usize,
        );
        *self.corner_index.entry(key).or_insert_with(|| {
            self.corner_sets.push(c);
            self.corner_sets.len() - 1
        })
    }
    fn node(&mut self, n: &'a Node) -> StoredNode {
        StoredNode {
            id: n.id,
            name: n.name.clone(),
            parent: n.parent,
            transform: n.transform,
            visible: n.visible,
            content: match &n.content {
                NodeContent::Empty => StoredContent::Empty,
                NodeContent::Csg(c) => StoredContent::Csg(*c),
                NodeContent::Curve(c) => match c.kind() {
                    hedra_geom::curves::CurveKind::Nurbs(n) => StoredContent::Curve(n.clone()),
                    k => StoredContent::CurveKind(k.clone()),
                },
                NodeContent::Surface(sf) => StoredContent::Surface((**sf).clone()),
                NodeContent::Mesh(m) => StoredContent::Mesh {
                    mesh: self.add(&m.mesh),
                    primitive: m.primitive.clone(),
                    shading: m.shading,
                    creases: m.creases.clone(),
                    subdivision: m.subdivision,
                    modifiers: m.modifiers.clone(),
                    corners: CornerAttributes::default(),
                    corner_set: (!m.corners.is_empty()).then(|| self.add_corners(&m.corners)),
                    decimations: m.decimations.iter().map(|r| (**r).clone()).collect(),
                },
            },
            construction: n.construction.clone(),
            g1_join: n.g1_join,
        }
    }
    fn transaction(&mut self, t: &'a Transaction) -> StoredTransaction<WriteCommand<'a>> {
        let changes = t
            .changes
            .iter()
            .map(|c| StoredChange {
                id: c.id,
                before: c.before.as_ref().map(|n| self.node(n)),
                after: c.after.as_ref().map(|n| self.node(n)),
            })
            .collect();
        StoredTransaction {
            serial: t.serial,
            label: t.label.clone(),
            command: t.command.as_ref().map(|c| self.command(c, t)),
            changes,
            next_id_before: t.next_id_before,
            next_id_after: t.next_id_after,
        }
    }
    /// A step's command; an `AddMesh` names the mesh it made when that mesh
    /// is in the pool exactly as the command builds it.
    fn command(&mut self, c: &'a Command, t: &'a Transaction) -> WriteCommand<'a> {
        let Command::AddMesh {
            positions,
            polygons,
            ..
        } = c
        else {
            return WriteCommand::Command(c);
        };
        let made = t
            .changes
            .iter()
            .find_map(|ch| match ch.after.as_ref().map(|n| &n.content) {
                Some(NodeContent::Mesh(m)) if ch.before.is_none() => Some(&m.mesh),
                _ => None,
            });
        match made {
            Some(m) if stored_command::made_from(m, positions, polygons) => {
                WriteCommand::PooledAddMesh {
                    command: c,
                    mesh: self.add(m),
                }
            }
            _ => WriteCommand::Command(c),
        }
    }
}

/// The text of a scene file for a session.
pub fn to_string(session: &Session) -> String {
    let mut pool = MeshPool {
        index: HashMap::new(),
        meshes: Vec::new(),
        corner_index: HashMap::new(),
        corner_sets: Vec::new(),
    };
    let scene = StoredScene {
        next_node_id: session.doc.next_node_id,
        nodes: session.doc.nodes().map(|n| pool.node(n)).collect(),
    };
    let scene_meshes = pool.meshes.len();
    let scene_corners = pool.corner_sets.len();
    let h = &session.history;
    let done = h.done.iter().map(|t| pool.transaction(t)).collect();
    let undone = h.undone.iter().map(|t| pool.transaction(t)).collect();
    let history_corners = pool.corner_sets[scene_corners..]
        .iter()
        .map(|c| StoredCorners::of(c))
        .collect();
    let corners = pool.corner_sets[..scene_corners]
        .iter()
        .map(|c| StoredCorners::of(c))
        .collect();
    let file = FileOut {
        format: FORMAT_NAME,
        version: FORMAT_VERSION,
        meshes: Vec::new(),
        corners,
        scene,
        history: StoredHistory {
            meshes: Vec::new(),
            corners: history_corners,
            done,
            undone,
            dropped: h.dropped,
            next_serial: h.next_serial,
            max_steps: h.max_steps,
        },
    };
    let config = ron::ser::PrettyConfig::new()
        .depth_limit(3)
        .struct_names(false);
    let rest = ron::ser::to_string_pretty(&file, config).expect("scene data always serialises");
    // The mesh pools go where the empty lists are: the first `meshes` is
    // the top level's (third field), the last `history` is the top level's.
    let (scene_pool, history_pool) = pool.meshes.split_at(scene_meshes);
    const TOP: &str = "\n    meshes: [],\n";
    const HISTORY: &str = "\n    history: (\n        meshes: [],\n";
    let top = rest.find(TOP).expect("the top level has its mesh list");
    let history = rest.rfind(HISTORY).expect("the history has its mesh list");
    let mut text = String::with_capacity(rest.len() + pool_size(&pool.meshes));
    text.push_str(&rest[..top]);
    text.push_str("\n    meshes: [");
    for m in scene_pool {
        text.push_str("\n        ");
        mesh_text::write_mesh(
            &mut text,
            m,
            mesh_text::Layout::Lines("            ", "        "),
        );
        text.push(',');
    }
    text.push_str(if scene_pool.is_empty() {
        "],\n"
    } else {
        "\n    ],\n"
    });
    text.push_str(&rest[top + TOP.len()..history]);
    text.push_str("\n    history: (\n        meshes: [");
    for m in history_pool {
        text.push_str("\n            ");
        mesh_text::write_mesh(&mut text, m, mesh_text::Layout::OneLine);
        text.push(',');
    }
    text.push_str(if history_pool.is_empty() {
        "],\n"
    } else {
        "\n        ],\n"
    });
    text.push_str(&rest[history + HISTORY.len()..]);
    text.push('\n');
    text
}

/// Roughly how many bytes the meshes' text takes (a position up to ~64, a
/// corner ~10), to reserve the text once.
fn pool_size(meshes: &[&HalfEdgeMesh]) -> usize {
    meshes
        .iter()
        .map(|m| m.vertex_capacity() * 64 + m.edge_capacity() * 20)
        .sum()
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> FileError + '_ {
    move |source| FileError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Writes `text` to `path` atomically: a temporary file in the same folder,
/// synced, the previous file kept as `<path>.bak`, then a rename. A failure
/// at any point leaves the old file in place.
///
/// # Errors
/// [`FileError::Io`] naming the path.
pub fn write_atomic(path: &Path, text: &str) -> Result<(), FileError> {
    write_atomic_bytes(path, text.as_bytes())
}

/// [`write_atomic`] for binary contents (binary STL).
///
/// # Errors
/// [`FileError::Io`] naming the path.
pub fn write_atomic_bytes(path: &Path, bytes: &[u8]) -> Result<(), FileError> {
    write_atomic_impl(path, bytes, true)
}

/// [`write_atomic_bytes`] without the `.bak` copy (recovery files, preferences).
///
/// # Errors
/// [`FileError::Io`] naming the path.
pub fn write_atomic_without_backup(path: &Path, bytes: &[u8]) -> Result<(), FileError> {
    write_atomic_impl(path, bytes, false)
}

fn write_atomic_impl(path: &Path, bytes: &[u8], keep_backup: bool) -> Result<(), FileError> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path.file_name().ok_or_else(|| FileError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name"),
    })?;
    // Messages name the file asked for and its folder, never the
    // temporary file, which the user did not ask for and never sees.
    let in_folder = |source: std::io::Error| FileError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            source.kind(),
            format!("cannot write in folder '{}': {source}", dir.display()),
        ),
    };
    if !dir.is_dir() {
        return Err(FileError::Io {
            path: path.to_path_buf(),
            source: std::io::Error::new(
                std::io::ErrorKind::NotFound,
                format!("folder '{}' does not exist", dir.display()),
            ),
        });
    }
    let tmp = dir.join(format!(
        ".{}.tmp-{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp).map_err(in_folder)?;
        f.write_all(bytes).map_err(in_folder)?;
        f.sync_all().map_err(in_folder)?;
        drop(f);
        if keep_backup && path.exists() {
            let mut bak = path.as_os_str().to_owned();
            bak.push(".bak");
            let bak = PathBuf::from(bak);
            let _ = std::fs::remove_file(&bak);
            if std::fs::hard_link(path, &bak).is_err() {
                std::fs::copy(path, &bak).map_err(io(&bak))?;
            }
        }
        std::fs::rename(&tmp, path).map_err(io(path))?;
        if let Ok(d) = std::fs::File::open(&dir) {
            let _ = d.sync_all();
        }
        remove_abandoned_temporaries(&dir, &name.to_string_lossy());
        Ok(())
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Removes temporary files of `name` left by saves whose process was killed
/// (Linux: their pid is gone from `/proc`).
fn remove_abandoned_temporaries(dir: &Path, name: &str) {
    let prefix = format!(".{name}.tmp-");
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let Some(pid) = file_name.to_str().and_then(|n| n.strip_prefix(&prefix)) else {
            continue;
        };
        let alive = Path::new("/proc").join(pid).exists() || !Path::new("/proc/self").exists();
        if !alive {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Saves a session to `path` atomically and marks it saved.
///
/// # Errors
/// [`FileError::Io`] when the folder is not writable, the disk is full, ….
pub fn save(session: &mut Session, path: &Path) -> Result<(), FileError> {
    write_atomic(path, &to_string(session))?;
    session.mark_saved();
    Ok(())
}

// ----- reading ---------------------------------------------------------------

/// Reads a scene file.
///
/// # Errors
/// A [`FileError`] naming the file, and the line and column of a syntax error.
pub fn load(path: &Path) -> Result<Loaded, FileError> {
    let bytes = crate::input::read(path).map_err(io(path))?;
    let text = String::from_utf8(bytes).map_err(|e| FileError::NotAScene {
        path: path.to_path_buf(),
        reason: e.into(),
    })?;
    from_str(&text, path)
}

/// Reads scene file text; `path` is only used in messages.
///
/// # Errors
/// As [`load`].
pub fn from_str(text: &str, path: &Path) -> Result<Loaded, FileError> {
    let version = sniff_header(text).map_err(|reason| FileError::NotAScene {
        path: path.to_path_buf(),
        reason,
    })?;
    if version > FORMAT_VERSION {
        return Err(FileError::NewerVersion {
            path: path.to_path_buf(),
            version,
        });
    }
    if version == 0 {
        return Err(FileError::NotAScene {
            path: path.to_path_buf(),
            reason: NotAScene::VersionZero,
        });
    }
    // Versions 1 and 2 share one reader (version 1 lacks the corner pool);
    // a version that changes a stored shape converts the older ones in its
    // readers (commands: `stored_command`).
    read_scene(text, path)
}

/// Finds `format: "hedra-scene"` and `version: N` near the top of the text,
/// without parsing the rest (so even a damaged file gets a clear answer).
fn sniff_header(text: &str) -> Result<u32, NotAScene> {
    let head: String = text.chars().take(1024).collect();
    let after = |key: &str| head.find(key).map(|i| head[i + key.len()..].trim_start());
    let format = after("format:").ok_or(NotAScene::NoFormatHeader)?;
    let format = format
        .strip_prefix('"')
        .and_then(|f| f.split('"').next())
        .ok_or(NotAScene::MalformedFormatHeader)?;
    if format != FORMAT_NAME {
        return Err(NotAScene::OtherFormat {
            format: format.to_string(),
        });
    }
    let version = after("version:").ok_or(NotAScene::NoVersionHeader)?;
    let digits: String = version.chars().take_while(char::is_ascii_digit).collect();
    digits
        .parse()
        .map_err(|_| NotAScene::MalformedVersionHeader)
}

fn parse_error(path: &Path, e: ron::error::SpannedError) -> FileError {
    FileError::Parse {
        path: path.to_path_buf(),
        line: e.span.start.line,
        column: e.span.start.col,
        message: e.code.to_string(),
    }
}

fn read_scene(text: &str, path: &Path) -> Result<Loaded, FileError> {
    let mut warnings = Vec::new();
    // The mesh lists are read by their own parser where it can.
    let prepared = mesh_text::prepare(text);
    let text: &str = &prepared.text;
    // `history: (…)` is read as `Some(raw)`; the history is parsed later on its own.
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    let file: FileIn = match options.from_str(text) {
        Ok(f) => f,
        Err(e) => {
            // A syntax error inside the history: retry with the history cut off.
            let history_start = text.find("\n    history:");
            let history_line = history_start.map(|i| text[..i].lines().count() + 1);
            match (history_start, history_line) {
                (Some(cut), Some(hl)) if e.span.start.line >= hl => {
                    let truncated = format!("{}\n)", &text[..cut]);
                    let f: FileIn = options
                        .from_str(&truncated)
                        .map_err(|_| parse_error(path, e.clone()))?;
                    warnings.push(format!(
                        "the undo history could not be read ({}); the scene opened without it",
                        parse_error(path, e)
                    ));
                    f
                }
                _ => return Err(parse_error(path, e)),
            }
        }
    };
    if file.format != FORMAT_NAME || !(1..=FORMAT_VERSION).contains(&file.version) {
        return Err(FileError::NotAScene {
            path: path.to_path_buf(),
            reason: NotAScene::HeaderFieldsDisagree,
        });
    }
    let invalid = |error: InvalidScene| FileError::Invalid {
        path: path.to_path_buf(),
        error: Box::new(error),
    };
    let scene_pool: Vec<Arc<HalfEdgeMesh>> = match prepared.scene_meshes {
        Some(meshes) => meshes.into_iter().map(Arc::new).collect(),
        None => file.meshes.into_iter().map(|m| Arc::new(m.0)).collect(),
    };
    let scene_corners = restore_corners(file.corners).map_err(&invalid)?;
    let mut doc = Document::new();
    doc.next_node_id = file.scene.next_node_id;
    for sn in file.scene.nodes {
        let node = restore_node(sn, &scene_pool, &scene_corners).map_err(&invalid)?;
        let id = node.id;
        if doc.nodes.insert(id, node).is_some() {
            return Err(invalid(InvalidScene::SharedId { node: id }));
        }
    }
    doc.check().map_err(|e| invalid(e.into()))?;
    let mut session = Session {
        doc,
        history: History::default(),
        saved_serial: None,
    };
    if let Some(raw) = file.history {
        let meshes = prepared.history_meshes;
        match restore_history(
            &raw,
            file.version,
            meshes,
            scene_pool,
            scene_corners,
            &session.doc,
        ) {
            Ok(h) => session.history = h,
            Err(why) => warnings.push(format!(
                "the undo history is damaged ({why}); the scene opened without it"
            )),
        }
    }
    session.mark_saved();
    Ok(Loaded { session, warnings })
}

/// The corner pool's attributes, each restored once and shared by the nodes
/// that name it.
fn restore_corners(stored: Vec<StoredCorners>) -> Result<Vec<CornerAttributes>, InvalidScene> {
    stored
        .into_iter()
        .enumerate()
        .map(|(index, c)| {
            c.restore()
                .map_err(|counts| InvalidScene::CornerSet { index, counts })
        })
        .collect()
}

fn restore_node(
    sn: StoredNode,
    pool: &[Arc<HalfEdgeMesh>],
    corner_pool: &[CornerAttributes],
) -> Result<Node, InvalidScene> {
    let content = match sn.content {
        StoredContent::Empty => NodeContent::Empty,
        StoredContent::Csg(c) => NodeContent::Csg(c),
        StoredContent::Curve(c) => NodeContent::Curve(Arc::new(CurveContent::from_nurbs(c))),
        StoredContent::CurveKind(k) => NodeContent::Curve(Arc::new(
            CurveContent::new(k).map_err(|error| InvalidScene::Curve { node: sn.id, error })?,
        )),
        StoredContent::Surface(sf) => NodeContent::Surface(Arc::new(sf)),
        StoredContent::Mesh {
            mesh,
            primitive,
            shading,
            creases,
            subdivision,
            modifiers,
            corners: inline_corners,
            corner_set,
            decimations,
        } => {
            let mut corners = match corner_set {
                Some(index) => corner_pool.get(index).cloned().ok_or_else(|| {
                    InvalidScene::MissingCornerSet {
                        node: sn.id,
                        name: sn.name.clone(),
                        index,
                    }
                })?,
                None => inline_corners,
            };
            let m = pool.get(mesh).ok_or_else(|| InvalidScene::MissingMesh {
                node: sn.id,
                name: sn.name.clone(),
                index: mesh,
            })?;
            // Parameters a command would have refused are refused here too
            // (found by fuzzing: a NaN cube size loaded and broke the round trip).
            let here = |problem: NodeProblem| InvalidScene::Node {
                node: sn.id,
                name: sn.name.clone(),
                problem,
            };
            if let Some(p) = &primitive {
                p.check().map_err(|e| here(e.into()))?;
            }
            if let Some(m) = &subdivision {
                let level = m.viewport_level.max(m.export_level);
                let max = hedra_geom::subdivision::MAX_LEVEL;
                if level > max {
                    return Err(here(NodeProblem::Level { level, max }));
                }
            }
            for (index, m) in modifiers.iter().enumerate() {
                m.check()
                    .map_err(|problem| here(NodeProblem::Modifier { index, problem }))?;
            }
            let bad_sharpness = creases
                .edges
                .values()
                .chain(creases.vertices.values())
                .find(|s| !(s.is_finite() && **s >= 0.0));
            if let Some(s) = bad_sharpness {
                return Err(here(NodeProblem::Sharpness(*s)));
            }
            let mut creases = creases;
            creases.retain_live(m);
            // Attributes of corners the mesh does not have are dropped.
            corners.retain_valid(m);
            NodeContent::Mesh(MeshContent {
                mesh: m.clone(),
                primitive,
                shading,
                creases,
                subdivision,
                modifiers,
                corners,
                decimations: decimations.into_iter().map(Arc::new).collect(),
            })
        }
    };
    Ok(Node {
        id: sn.id,
        name: sn.name,
        parent: sn.parent,
        transform: sn.transform,
        visible: sn.visible,
        content,
        construction: sn.construction,
        g1_join: sn.g1_join,
    })
}

fn restore_history(
    raw: &RawValue,
    version: u32,
    meshes: Option<Vec<HalfEdgeMesh>>,
    mut pool: Vec<Arc<HalfEdgeMesh>>,
    mut corner_pool: Vec<CornerAttributes>,
    doc: &Document,
) -> Result<History, HistoryError> {
    let stored = stored_command::parse_history(version, raw).map_err(|e| HistoryError::Parse {
        line: e.span.start.line,
        column: e.span.start.col,
        message: e.code.to_string(),
    })?;
    match meshes {
        Some(meshes) => pool.extend(meshes.into_iter().map(Arc::new)),
        None => pool.extend(stored.meshes.into_iter().map(|m| Arc::new(m.0))),
    }
    corner_pool.extend(restore_corners(stored.corners)?);
    let restore_tx =
        |t: StoredTransaction<stored_command::ReadCommand>| -> Result<Transaction, HistoryError> {
            let mut changes = Vec::with_capacity(t.changes.len());
            for c in t.changes {
                changes.push(NodeChange {
                    id: c.id,
                    before: c
                        .before
                        .map(|n| restore_node(n, &pool, &corner_pool))
                        .transpose()?,
                    after: c
                        .after
                        .map(|n| restore_node(n, &pool, &corner_pool))
                        .transpose()?,
                });
            }
            let command = match t.command {
                Some(c) => Some(c.resolve(&pool).ok_or(HistoryError::MissingCommandMesh {
                    label: t.label.clone(),
                })?),
                None => None,
            };
            Ok(Transaction {
                serial: t.serial,
                label: t.label,
                command,
                changes,
                next_id_before: t.next_id_before,
                next_id_after: t.next_id_after,
            })
        };
    let done = stored
        .done
        .into_iter()
        .map(&restore_tx)
        .collect::<Result<Vec<_>, _>>()?;
    let undone = stored
        .undone
        .into_iter()
        .map(&restore_tx)
        .collect::<Result<Vec<_>, _>>()?;
    let history = History {
        done,
        undone,
        max_steps: stored.max_steps.max(1),
        dropped: stored.dropped,
        next_serial: stored.next_serial,
        ..History::default()
    };
    // The steps must chain exactly from the stored scene: undo each on a
    // copy, checking it ends where the scene (or the next step) starts,
    // then redo them all back to the scene.
    let mut probe_doc = doc.clone();
    for t in history.done.iter().rev() {
        if !t.fits(&probe_doc, false) {
            return Err(HistoryError::StepDoesNotFit {
                label: t.label.clone(),
            });
        }
        t.apply(&mut probe_doc, false);
        // Every state undo reaches must be sound, not only the first one.
        probe_doc
            .check()
            .map_err(|error| HistoryError::UndoBreaks {
                label: t.label.clone(),
                error,
            })?;
    }
    for t in &history.done {
        t.apply(&mut probe_doc, true);
        // Redoing must reach sound states too (found by fuzzing: a step
        // whose recorded next node id is too low passed the undo checks).
        probe_doc
            .check()
            .map_err(|error| HistoryError::RedoBreaks {
                label: t.label.clone(),
                error,
            })?;
    }
    if probe_doc != *doc {
        return Err(HistoryError::WrongEnd);
    }
    let mut redo_doc = doc.clone();
    for t in history.undone.iter().rev() {
        if !t.fits(&redo_doc, true) {
            return Err(HistoryError::RedoDoesNotStart {
                label: t.label.clone(),
            });
        }
        t.apply(&mut redo_doc, true);
        redo_doc.check().map_err(|error| HistoryError::RedoBreaks {
            label: t.label.clone(),
            error,
        })?;
    }
    let serials: Vec<u64> = history
        .done
        .iter()
        .chain(history.undone.iter().rev())
        .map(|t| t.serial)
        .collect();
    if serials.windows(2).any(|w| w[0] >= w[1])
        || serials.last().is_some_and(|&s| s >= history.next_serial)
    {
        return Err(HistoryError::SerialsOutOfOrder);
    }
    Ok(history)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fast path reads both mesh lists of a file Hedra wrote (the
    /// scene's and the history's), for files of every version.
    #[test]
    fn the_mesh_lists_are_read_by_the_fast_parser() {
        let mut session = Session::new();
        session
            .execute(&Command::AddPrimitive {
                primitive: Primitive::Cube { size: 1.0 },
                name: Some("Box".into()),
                parent: None,
                transform: NodeTransform::IDENTITY,
            })
            .unwrap();
        session
            .execute(&Command::ExtrudeFaces {
                node: crate::NodeRef::Name("Box".into()),
                faces: crate::FaceSet::Ids(vec![1]),
                distance: 0.5,
            })
            .unwrap();
        let text = to_string(&session);
        let prepared = mesh_text::prepare(&text);
        assert_eq!(prepared.scene_meshes.map(|m| m.len()), Some(1));
        assert_eq!(prepared.history_meshes.map(|m| m.len()), Some(1));
        assert!(prepared.text.len() < 2000, "{}", prepared.text);
        let corpus =
            Path::new(&std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"))
                .join("tests/corpus/scenes");
        for name in [
            "v1-chair.hedra.ron",
            "v2-every-command.hedra.ron",
            "v3-every-command.hedra.ron",
        ] {
            let text = std::fs::read_to_string(corpus.join(name)).unwrap();
            let prepared = mesh_text::prepare(&text);
            assert!(prepared.scene_meshes.is_some(), "{name}");
            assert!(prepared.history_meshes.is_some(), "{name}");
            assert_eq!(
                prepared.text.lines().count(),
                text.lines().count(),
                "{name}"
            );
        }
    }

    /// A mesh with an edge-less face (the kernel's MVFS) is stored and read
    /// back as it was: faces with rings or without edges are part of the
    /// document since the Euler operators became commands.
    #[test]
    fn a_scene_with_a_non_polygon_face_reads_back() {
        let mut session = Session::new();
        session
            .execute(&Command::AddPrimitive {
                primitive: Primitive::Cube { size: 1.0 },
                name: Some("Shell".into()),
                parent: None,
                transform: NodeTransform::IDENTITY,
            })
            .unwrap();
        let id = session.doc.find_by_name("Shell").unwrap().id;
        let mut mesh = HalfEdgeMesh::default();
        mesh.make_vertex_face_shell(glam::DVec3::ZERO).unwrap();
        if let Some(node) = session.doc.nodes.get_mut(&id) {
            node.content = NodeContent::Mesh(MeshContent::new(Arc::new(mesh.clone())));
        }
        session.doc.check().unwrap();
        let text = to_string(&session);
        let back = from_str(&text, Path::new("ring.hedra.ron")).unwrap();
        let node = back.session.doc.find_by_name("Shell").unwrap();
        assert!(node.content.mesh().unwrap().same_as(&mesh));
    }
}
