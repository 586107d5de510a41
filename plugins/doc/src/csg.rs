//! CSG nodes (issue 17, seed 004's CSG tree): a node whose scene-graph
//! children are its operands (meshes, primitives, other CSG nodes, nested
//! to any depth), combined by one boolean. The node's solid is evaluated in
//! its own space, each operand placed by its local transform.
//!
//! Operands are the children in id order (the order they were added): a
//! difference is the first minus all the others; union and intersection do
//! not depend on the order. Children that are not solids (empties, curves,
//! surfaces) are not operands; a mesh operand counts with its modifier
//! stack and subdivision at the viewport level, as it is drawn; its own
//! children are not operands.
//!
//! Evaluation is cached process-wide by a fingerprint of its inputs (the
//! operation, each operand's geometry and transform): every partial result
//! of a node's fold and every nested node is a cache entry, so moving one
//! operand re-evaluates only the steps after it and the nodes above it.

use crate::scene::{Document, NodeContent, NodeId};
use glam::DMat4;
use hedra_geom::HalfEdgeMesh;
use hedra_geom::csg::{BooleanError, BooleanOp, Operand, boolean};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::sync::{Arc, Mutex};

/// A CSG node's content: the boolean that combines its children.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct CsgContent {
    /// Union, intersection, or difference (the first operand minus the rest).
    pub op: BooleanOp,
}

/// Why a CSG node has no solid; every variant names the nodes.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CsgError {
    /// The node has no operands (no mesh or CSG children).
    #[error("{node} has no operands (add meshes or CSG nodes under it)")]
    NoOperands {
        /// The CSG node, as `'name'`.
        node: String,
    },
    /// An operand cannot take part: open, non-manifold, empty, not polygonal.
    #[error("{node}: operand '{operand}' {problem}")]
    Operand {
        /// The CSG node, as `'name'`.
        node: String,
        /// The operand's name.
        operand: String,
        /// What is wrong with it (`is open: 4 border edges`).
        problem: String,
    },
    /// A mesh operand's modifier stack does not evaluate.
    #[error("{node}: operand '{operand}': {error}")]
    Evaluation {
        /// The CSG node, as `'name'`.
        node: String,
        /// The operand's name.
        operand: String,
        /// Why.
        error: Box<crate::modifiers::EvaluationError>,
    },
    /// The result is empty ("the intersection of Box and Ball is empty").
    #[error("the {op} of {operands} is empty")]
    Empty {
        /// The operation.
        op: BooleanOp,
        /// The operands' names, as "Box and Ball" or "A, B and C".
        operands: String,
    },
    /// The boolean engine failed.
    #[error("{node}: {error}")]
    Boolean {
        /// The CSG node, as `'name'`.
        node: String,
        /// The kernel's error.
        error: BooleanError,
    },
}

/// The evaluated solid of a CSG node, in the node's own space.
pub type Solid = Arc<HalfEdgeMesh>;

type Cache = HashMap<u64, Result<Solid, CsgError>>;

fn cache() -> &'static Mutex<Cache> {
    static CACHE: std::sync::OnceLock<Mutex<Cache>> = std::sync::OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// Entries kept before the cache is emptied (each is one mesh).
const CACHE_ENTRIES: usize = 256;

fn cached(key: u64, compute: impl FnOnce() -> Result<Solid, CsgError>) -> Result<Solid, CsgError> {
    if let Some(hit) = cache().lock().map(|c| c.get(&key).cloned()).ok().flatten() {
        return hit;
    }
    let value = compute();
    match cache().lock() {
        Ok(mut c) => {
            if c.len() >= CACHE_ENTRIES {
                c.clear();
            }
            // Another thread may have computed the same inputs meanwhile:
            // its solid wins, so equal inputs always give one shared solid.
            c.entry(key).or_insert(value).clone()
        }
        Err(_) => value,
    }
}

/// The tolerance every CSG evaluation uses (the engine's own precision
/// decides; slivers thinner than this are collapsed).
pub const CSG_TOLERANCE: f64 = 0.0;

/// True when `id` is a CSG node.
pub fn is_csg(doc: &Document, id: NodeId) -> bool {
    matches!(doc.node(id).map(|n| &n.content), Some(NodeContent::Csg(_)))
}

/// The CSG node `id` is an operand of (its parent, when that is a CSG
/// node): the viewport draws the CSG node's solid instead of its
/// operands (as ghosts while selected) and export skips them.
pub fn csg_owner(doc: &Document, id: NodeId) -> Option<NodeId> {
    let parent = doc.node(id)?.parent?;
    is_csg(doc, parent).then_some(parent)
}

/// True when `id` or one of its ancestors is a CSG operand (drawn through
/// the CSG node's solid, not by itself).
pub fn inside_csg(doc: &Document, id: NodeId) -> bool {
    let mut cur = Some(id);
    while let Some(c) = cur {
        if csg_owner(doc, c).is_some() {
            return true;
        }
        cur = doc.node(c).and_then(|n| n.parent);
    }
    false
}

/// The operands of CSG node `id`: its mesh and CSG children, in id order.
pub fn operands(doc: &Document, id: NodeId) -> Vec<NodeId> {
    doc.children(id)
        .filter(|n| matches!(n.content, NodeContent::Mesh(_) | NodeContent::Csg(_)))
        .map(|n| n.id)
        .collect()
}

/// "A", "A and B", "A, B and C".
fn names(list: &[String]) -> String {
    match list {
        [] => String::new(),
        [a] => a.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

/// The solid of CSG node `id` in its own space, from the cache when its
/// inputs have not changed.
///
/// # Errors
/// [`CsgError`] naming the node and the operand at fault, or the operands
/// of an empty result.
///
/// Complexity: O(n) to fingerprint the operands' n elements; each boolean
/// step that is not cached costs what [`boolean`] costs.
pub fn evaluate(doc: &Document, id: NodeId) -> Result<Solid, CsgError> {
    let node = doc.node(id).expect("evaluate: a node of the document");
    let NodeContent::Csg(content) = &node.content else {
        return Err(CsgError::NoOperands {
            node: format!("'{}'", node.name),
        });
    };
    let label = format!("'{}'", node.name);
    let ids = operands(doc, id);
    if ids.is_empty() {
        return Err(CsgError::NoOperands { node: label });
    }
    // Each operand's solid in this node's space, with its fingerprint.
    let mut inputs: Vec<(String, u64, Solid)> = Vec::with_capacity(ids.len());
    for &o in &ids {
        let n = doc.node(o).expect("a child");
        let local = match &n.content {
            NodeContent::Csg(_) => evaluate(doc, o)?,
            NodeContent::Mesh(m) => {
                let level = m.subdivision.map_or(0, |s| s.viewport_level);
                if m.has_stack_modifiers() || level > 0 {
                    Arc::new(
                        m.evaluated(level)
                            .map_err(|error| CsgError::Evaluation {
                                node: label.clone(),
                                operand: n.name.clone(),
                                error: Box::new(error),
                            })?
                            .into_owned(),
                    )
                } else {
                    m.mesh.clone()
                }
            }
            _ => unreachable!("operands are meshes and CSG nodes"),
        };
        let matrix = n.transform.to_matrix();
        let mut h = std::collections::hash_map::DefaultHasher::new();
        fingerprint(&local, &mut h);
        matrix.to_cols_array().map(f64::to_bits).hash(&mut h);
        let key = h.finish();
        let placed = cached(key ^ 0x9e37_79b9_7f4a_7c15, || {
            Ok(Arc::new(placed(&local, matrix)))
        })?;
        inputs.push((n.name.clone(), key, placed));
    }
    // Fold left, each partial result cached by the fingerprints so far.
    let op = content.op;
    let mut acc = inputs[0].2.clone();
    let mut key = inputs[0].1;
    for (i, (name, k, solid)) in inputs.iter().enumerate().skip(1) {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        (key, *k, op).hash(&mut h);
        key = h.finish();
        let a = acc.clone();
        let first = inputs[0].0.clone();
        let so_far: Vec<String> = inputs[..=i].iter().map(|x| x.0.clone()).collect();
        acc = cached(key, || {
            boolean(&a, solid, op, CSG_TOLERANCE)
                .map(Arc::new)
                .map_err(|error| match error {
                    BooleanError::EmptyResult { op } => CsgError::Empty {
                        op,
                        operands: names(&so_far),
                    },
                    BooleanError::Open { operand, .. }
                    | BooleanError::NonManifold { operand, .. }
                    | BooleanError::NotPolygonal { operand, .. }
                    | BooleanError::NonFinite { operand }
                    | BooleanError::EmptyOperand { operand } => CsgError::Operand {
                        node: label.clone(),
                        operand: match operand {
                            Operand::A if i == 1 => first,
                            Operand::A => format!("the {op} of {}", names(&so_far[..i])),
                            Operand::B => name.clone(),
                        },
                        problem: problem(&error),
                    },
                    error => CsgError::Boolean {
                        node: label.clone(),
                        error,
                    },
                })
        })?;
    }
    if inputs.len() == 1 {
        // One operand: check it is a solid all the same.
        let one = &inputs[0];
        if let Err(error) = boolean(&one.2, &one.2, BooleanOp::Union, CSG_TOLERANCE)
            && !matches!(error, BooleanError::EmptyResult { .. })
        {
            return Err(CsgError::Operand {
                node: label,
                operand: one.0.clone(),
                problem: problem(&error),
            });
        }
    }
    Ok(acc)
}

/// The kernel's message without its "the first operand" subject.
pub(crate) fn problem(e: &BooleanError) -> String {
    let text = e.to_string();
    for subject in ["the first operand ", "the second operand "] {
        if let Some(rest) = text.strip_prefix(subject) {
            return rest.to_string();
        }
    }
    text
}

fn placed(m: &HalfEdgeMesh, matrix: DMat4) -> HalfEdgeMesh {
    if matrix == DMat4::IDENTITY {
        return m.clone();
    }
    let mut m = m.clone();
    for p in m.positions_mut() {
        *p = matrix.transform_point3(*p);
    }
    if matrix.determinant() < 0.0 {
        m.reverse_orientation();
    }
    m
}

/// Hashes a mesh's positions and faces (O(n)).
fn fingerprint(m: &HalfEdgeMesh, h: &mut impl Hasher) {
    m.vertex_count().hash(h);
    m.face_count().hash(h);
    for v in m.vertices() {
        v.0.hash(h);
        m.position(v).to_array().map(f64::to_bits).hash(h);
    }
    for f in m.faces() {
        f.0.hash(h);
        for v in m.face_vertices(f) {
            v.0.hash(h);
        }
    }
}
