//! Writing a scene file: the mesh and corner pools, the scene and
//! history in their stored form, and the RON text.

use super::atomic::write_atomic;
use super::errors::FileError;
use super::stored_command::WriteCommand;
use super::{
    FORMAT_NAME, FORMAT_VERSION, FileOut, StoredChange, StoredContent, StoredCorners,
    StoredHistory, StoredNode, StoredScene, StoredTransaction, mesh_text, stored_command,
};
use crate::command::Command;
use crate::history::Transaction;
use crate::kept::KeptMesh;
use crate::scene::{CornerAttributes, Node, NodeContent};
use crate::session::Session;
use hedra_geom::HalfEdgeMesh;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// Collects meshes and corner attributes into pools, each `Arc` once.
struct MeshPool<'a> {
    index: HashMap<*const HalfEdgeMesh, usize>,
    meshes: Vec<&'a HalfEdgeMesh>,
    /// Corner attributes by the identity of their two shared maps (their
    /// addresses are stable: the pool borrows them for the whole save).
    corner_index: HashMap<(*const (), *const ()), usize>,
    corner_sets: Vec<&'a CornerAttributes>,
    kept_index: HashMap<*const KeptMesh, usize>,
    kept: Vec<&'a KeptMesh>,
}

impl<'a> MeshPool<'a> {
    fn add(&mut self, m: &'a Arc<HalfEdgeMesh>) -> usize {
        *self.index.entry(Arc::as_ptr(m)).or_insert_with(|| {
            self.meshes.push(m);
            self.meshes.len() - 1
        })
    }
    fn add_kept(&mut self, m: &'a Arc<KeptMesh>) -> usize {
        *self.kept_index.entry(Arc::as_ptr(m)).or_insert_with(|| {
            self.kept.push(m);
            self.kept.len() - 1
        })
    }
    fn add_corners(&mut self, c: &'a CornerAttributes) -> usize {
        let key = (
            Arc::as_ptr(&c.uvs).cast::<()>(),
            Arc::as_ptr(&c.normals).cast::<()>(),
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
                NodeContent::Kept(k) => StoredContent::Kept {
                    mesh: self.add_kept(&k.mesh),
                    shading: k.shading,
                    subdivision: k.subdivision,
                },
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
        kept_index: HashMap::new(),
        kept: Vec::new(),
    };
    let scene = StoredScene {
        next_node_id: session.doc.next_node_id,
        nodes: session.doc.nodes().map(|n| pool.node(n)).collect(),
    };
    let scene_meshes = pool.meshes.len();
    let scene_corners = pool.corner_sets.len();
    let scene_kept = pool.kept.len();
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
        kept: pool.kept[..scene_kept].to_vec(),
        scene,
        history: StoredHistory {
            meshes: Vec::new(),
            corners: history_corners,
            kept: pool.kept[scene_kept..].to_vec(),
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

/// Saves a session to `path` atomically and marks it saved.
///
/// # Errors
/// [`FileError::Io`] when the folder is not writable, the disk is full, ….
pub fn save(session: &mut Session, path: &Path) -> Result<(), FileError> {
    write_atomic(path, &to_string(session))?;
    session.mark_saved();
    Ok(())
}
