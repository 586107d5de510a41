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

use crate::scene::{CornerAttributes, NodeId, NodeTransform, Shading, SubdivisionModifier};
use crate::session::Session;
use hedra_geom::Primitive;
use hedra_geom::subdivision::Creases;
use ron::value::RawValue;
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use stored_command::WriteCommand;

mod atomic;
mod errors;
mod load;
mod mesh_text;
mod save;
pub mod stored_command;

pub use atomic::{
    write_atomic, write_atomic_bytes, write_atomic_streamed, write_atomic_without_backup,
};
pub use errors::{CornerCounts, FileError, HistoryError, InvalidScene, NodeProblem, NotAScene};
pub use load::{from_str, load};
pub use save::{save, to_string};

/// The format name written at the top of every scene file.
pub const FORMAT_NAME: &str = "hedra-scene";
/// The newest format version this build reads and the one it writes.
pub const FORMAT_VERSION: u32 = 3;
/// The scene file extension.
pub const EXTENSION: &str = "hedra.ron";

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
    /// A kept (non-manifold) mesh: its faces, by index into the file's
    /// `kept` pool (the history's pool for history steps), its shading and
    /// subdivision.
    Kept {
        mesh: usize,
        #[serde(default)]
        shading: Shading,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        subdivision: Option<SubdivisionModifier>,
    },
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
struct StoredHistory<C, M, K> {
    /// Meshes only the history uses; index `i` here is pool index `scene_meshes + i`.
    meshes: Vec<M>,
    /// Corner attributes only the history uses, numbered after the scene's.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    corners: Vec<StoredCorners>,
    /// Kept meshes only history steps hold.
    #[serde(default = "Vec::new", skip_serializing_if = "Vec::is_empty")]
    kept: Vec<K>,
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
    /// Kept (non-manifold) meshes the scene's nodes hold.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    kept: Vec<&'a crate::kept::KeptMesh>,
    scene: StoredScene,
    history: StoredHistory<WriteCommand<'a>, (), &'a crate::kept::KeptMesh>,
}

#[derive(Deserialize)]
struct FileIn {
    format: String,
    version: u32,
    meshes: Vec<mesh_text::StoredMesh>,
    #[serde(default)]
    corners: Vec<StoredCorners>,
    #[serde(default)]
    kept: Vec<crate::kept::KeptMesh>,
    scene: StoredScene,
    #[serde(default)]
    history: Option<Box<RawValue>>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command::Command;
    use crate::scene::{MeshContent, NodeContent};
    use hedra_geom::HalfEdgeMesh;
    use std::path::Path;

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
