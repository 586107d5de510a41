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
//! of a node's fold and every nested node's solid is a cache entry, keyed
//! by the fingerprints of what it was made from, so moving one operand
//! re-evaluates only the steps after it and the nodes above it; a nested
//! node whose operands did not change is found in the cache without
//! looking at its solid. A mesh's fingerprint is computed once per shared
//! mesh (remembered by the `Arc`'s identity), so a drag frame costs the
//! booleans it must re-run and nothing proportional to the other operands.
//!
//! While dragging, [`Quality::Preview`] evaluates with simplified copies of
//! the large operands (made once per operand mesh and cached), fast enough
//! for every frame; the exact solid is evaluated on release. [`CsgTree`]
//! is an owned snapshot of a node's tree that can be evaluated on a worker
//! thread.

use crate::scene::{Document, NodeContent, NodeId};
use glam::DMat4;
use hedra_geom::HalfEdgeMesh;
use hedra_geom::csg::{BooleanError, BooleanOp, BooleanOptions, Operand, boolean_with_options};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::sync::{Arc, Mutex, OnceLock, Weak};

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
    /// The result is empty ("the intersection of Box and Ball is empty"):
    /// from the one-shot Boolean and Apply, which would leave a mesh without
    /// faces; a CSG node's own solid is then an empty solid instead.
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

/// Each entry with the tick it was last used at.
struct Cache {
    entries: HashMap<u64, (Result<Solid, CsgError>, u64)>,
    tick: u64,
}

fn cache() -> &'static Mutex<Cache> {
    static CACHE: OnceLock<Mutex<Cache>> = OnceLock::new();
    CACHE.get_or_init(|| {
        Mutex::new(Cache {
            entries: HashMap::new(),
            tick: 0,
        })
    })
}

/// Entries kept (each is one mesh); when full, the half used longest ago
/// goes, so a long drag, which adds a few entries a frame, keeps the
/// steps it reuses.
const CACHE_ENTRIES: usize = 256;

fn cached(key: u64, compute: impl FnOnce() -> Result<Solid, CsgError>) -> Result<Solid, CsgError> {
    if let Ok(mut c) = cache().lock() {
        c.tick += 1;
        let tick = c.tick;
        if let Some((hit, used)) = c.entries.get_mut(&key) {
            *used = tick;
            return hit.clone();
        }
    }
    let value = compute();
    match cache().lock() {
        Ok(mut c) => {
            if c.entries.len() >= CACHE_ENTRIES {
                let mut ticks: Vec<u64> = c.entries.values().map(|e| e.1).collect();
                let half = ticks.len() / 2;
                let cut = *ticks.select_nth_unstable(half).1;
                c.entries.retain(|_, e| e.1 > cut);
            }
            c.tick += 1;
            let tick = c.tick;
            // Another thread may have computed the same inputs meanwhile:
            // its solid wins, so equal inputs always give one shared solid.
            c.entries.entry(key).or_insert((value, tick)).0.clone()
        }
        Err(_) => value,
    }
}

thread_local! {
    static BOOLEANS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// How many booleans CSG evaluation has computed on this thread (cache
/// misses), for tests and benches that check what a change re-runs.
pub fn booleans_computed() -> u64 {
    BOOLEANS.with(|b| b.get())
}

/// How a CSG node is evaluated.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum Quality {
    /// The operands as they are: the solid drawn at rest, exported and
    /// applied.
    #[default]
    Exact,
    /// Every mesh operand of more than `faces` triangles replaced by a
    /// simplified copy of at most that many (quadric edge collapses,
    /// `hedra_geom::progressive::decimate`), made once per operand mesh
    /// and cached, so dragging an operand pays only the booleans on the
    /// small copies. For showing the result during a drag; evaluate
    /// [`Exact`](Quality::Exact) on release.
    Preview {
        /// The most triangles a simplified operand keeps.
        faces: usize,
    },
}

impl Quality {
    /// The preview a drag uses: [`PREVIEW_FACES`] per operand.
    pub const DRAG: Quality = Quality::Preview {
        faces: PREVIEW_FACES,
    };
}

/// Triangles per operand in [`Quality::DRAG`]: small enough that a drag
/// frame of the emblem (one boolean on simplified operands) costs about
/// the 16 ms budget on a 2-core machine (see `benches/csg.rs` and
/// `docs/csg.md`), large enough that round operands still look round.
pub const PREVIEW_FACES: usize = 300;

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
pub(crate) fn names(list: &[String]) -> String {
    match list {
        [] => String::new(),
        [a] => a.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

/// The solid of CSG node `id` in its own space, from the cache when its
/// inputs have not changed. An empty result (operands moved apart under an
/// intersection, a difference that removes everything) is an empty solid,
/// a mesh without faces, as Manifold returns one: drawn and exported as
/// nothing, never an error.
///
/// # Errors
/// [`CsgError`] naming the node and the operand at fault.
///
/// Complexity: O(n) to fingerprint operand meshes not seen before (O(1)
/// for those already seen); each boolean step that is not cached costs
/// what [`boolean_with_options`] costs.
pub fn evaluate(doc: &Document, id: NodeId) -> Result<Solid, CsgError> {
    evaluate_with(doc, id, Quality::Exact)
}

/// [`evaluate`] at a chosen [`Quality`]: `Quality::DRAG` while an operand
/// is dragged, `Quality::Exact` on release.
///
/// # Errors
/// As [`evaluate`].
pub fn evaluate_with(doc: &Document, id: NodeId, quality: Quality) -> Result<Solid, CsgError> {
    CsgTree::of(doc, id)?.evaluate(quality)
}

/// An owned snapshot of a CSG node's tree: its operation and operands
/// (meshes shared with the document, not copied; nested CSG nodes as
/// trees of their own), `Send + 'static`, so that a worker thread can
/// evaluate it while the document moves on:
///
/// ```
/// # use hedra_doc::{Command, NodeRef, NodeTransform, Session, csg};
/// # let mut s = Session::new();
/// # for name in ["A", "B"] {
/// #     s.execute(&Command::AddPrimitive {
/// #         primitive: hedra_geom::Primitive::Cube { size: 1.0 },
/// #         name: Some(name.into()), parent: None,
/// #         transform: NodeTransform::IDENTITY }).unwrap();
/// # }
/// # s.execute(&Command::AddCsg { op: hedra_geom::BooleanOp::Union, name: Some("U".into()),
/// #     operands: vec![NodeRef::Name("A".into()), NodeRef::Name("B".into())],
/// #     parent: None, transform: NodeTransform::IDENTITY }).unwrap();
/// let id = s.doc.find_by_name("U").unwrap().id;
/// let tree = csg::CsgTree::of(&s.doc, id).unwrap();
/// let worker = std::thread::spawn(move || tree.evaluate(csg::Quality::Exact));
/// let solid = worker.join().unwrap().unwrap();
/// assert_eq!(solid.face_count(), 6);
/// ```
#[derive(Clone, Debug)]
pub struct CsgTree {
    /// The node's name, for messages.
    name: String,
    op: BooleanOp,
    operands: Vec<TreeOperand>,
}

#[derive(Clone, Debug)]
struct TreeOperand {
    name: String,
    matrix: DMat4,
    shape: Shape,
}

#[derive(Clone, Debug)]
enum Shape {
    /// A mesh as it is.
    Mesh(Arc<HalfEdgeMesh>),
    /// A mesh with a modifier stack or subdivision, evaluated at the
    /// level (on the thread that evaluates the tree).
    Stack(Box<crate::scene::MeshContent>, u32),
    /// A nested CSG node.
    Tree(CsgTree),
}

impl CsgTree {
    /// The tree of CSG node `id`. Cheap: meshes are shared, not copied
    /// (a mesh with a modifier stack copies its node's settings).
    ///
    /// # Errors
    /// [`CsgError::NoOperands`] for a node that is not a CSG node, is not
    /// in the document, or has no operands (or a nested one has none).
    pub fn of(doc: &Document, id: NodeId) -> Result<CsgTree, CsgError> {
        let Some(node) = doc.node(id) else {
            return Err(CsgError::NoOperands {
                node: format!("node {}", id.0),
            });
        };
        let label = format!("'{}'", node.name);
        let NodeContent::Csg(content) = &node.content else {
            return Err(CsgError::NoOperands { node: label });
        };
        let ids = operands(doc, id);
        if ids.is_empty() {
            return Err(CsgError::NoOperands { node: label });
        }
        let mut list = Vec::with_capacity(ids.len());
        for o in ids {
            let Some(n) = doc.node(o) else { continue };
            let shape = match &n.content {
                NodeContent::Csg(_) => Shape::Tree(CsgTree::of(doc, o)?),
                NodeContent::Mesh(m) => {
                    let level = m.subdivision.map_or(0, |s| s.viewport_level);
                    if m.has_stack_modifiers() || level > 0 {
                        Shape::Stack(Box::new(m.clone()), level)
                    } else {
                        Shape::Mesh(m.mesh.clone())
                    }
                }
                _ => continue,
            };
            list.push(TreeOperand {
                name: n.name.clone(),
                matrix: n.transform.to_matrix(),
                shape,
            });
        }
        Ok(CsgTree {
            name: node.name.clone(),
            op: content.op,
            operands: list,
        })
    }

    /// The solid, in the node's own space, from the cache where inputs
    /// did not change.
    ///
    /// # Errors
    /// As [`evaluate`].
    pub fn evaluate(&self, quality: Quality) -> Result<Solid, CsgError> {
        self.solid(quality).map(|(solid, _)| solid)
    }

    /// The solid and its fingerprint (that of its inputs).
    fn solid(&self, quality: Quality) -> Result<(Solid, u64), CsgError> {
        let label = format!("'{}'", self.name);
        // Each operand's solid in this node's space, with its fingerprint.
        let mut inputs: Vec<(String, u64, Solid)> = Vec::with_capacity(self.operands.len());
        for o in &self.operands {
            let (local, local_key) = match &o.shape {
                Shape::Tree(tree) => tree.solid(quality)?,
                Shape::Mesh(mesh) => leaf(
                    &label,
                    &o.name,
                    mesh.clone(),
                    known_fingerprint(mesh),
                    quality,
                )?,
                Shape::Stack(content, level) => {
                    let mesh = Arc::new(
                        content
                            .evaluated(*level)
                            .map_err(|error| CsgError::Evaluation {
                                node: label.clone(),
                                operand: o.name.clone(),
                                error: Box::new(error),
                            })?
                            .into_owned(),
                    );
                    let key = fingerprint(&mesh);
                    leaf(&label, &o.name, mesh, key, quality)?
                }
            };
            let mut h = std::collections::hash_map::DefaultHasher::new();
            local_key.hash(&mut h);
            o.matrix.to_cols_array().map(f64::to_bits).hash(&mut h);
            let key = h.finish();
            let matrix = o.matrix;
            let placed = cached(key ^ 0x9e37_79b9_7f4a_7c15, || {
                Ok(Arc::new(placed(&local, matrix)))
            })?;
            inputs.push((o.name.clone(), key, placed));
        }
        if matches!(quality, Quality::Preview { .. }) && inputs.len() > 2 {
            // The operands after the first commute (A − B − C = A − C − B;
            // union and intersection in any order): a preview folds the
            // ones unchanged longest first, so the cached prefix covers all
            // but the one being dragged, whichever it is, and a frame
            // re-runs one boolean. Exact evaluation keeps the document's
            // order, so its mesh does not depend on the cache's history.
            let age = |key: u64| first_seen(key);
            inputs[1..].sort_by_key(|x| age(x.1));
        }
        let Some(first) = inputs.first() else {
            return Err(CsgError::NoOperands { node: label });
        };
        // Fold left, each partial result cached by the fingerprints so far.
        // Operand meshes were checked as leaves; the partial results are
        // the engine's own closed, crossing-free solids.
        let options = BooleanOptions {
            tolerance: CSG_TOLERANCE,
            check_crossings: [false, false],
        };
        let op = self.op;
        let mut acc = first.2.clone();
        let mut key = first.1;
        for (i, (name, k, solid)) in inputs.iter().enumerate().skip(1) {
            let mut h = std::collections::hash_map::DefaultHasher::new();
            (key, *k, op).hash(&mut h);
            key = h.finish();
            if let Some(result) = with_empty(op, &acc, solid) {
                acc = result;
                continue;
            }
            let a = acc.clone();
            acc = cached(key, || {
                BOOLEANS.with(|b| b.set(b.get() + 1));
                boolean_with_options(&a, solid, op, &options)
                    .map(|r| Arc::new(r.mesh))
                    .or_else(|error| match error {
                        BooleanError::EmptyResult { .. } => Ok(Arc::new(HalfEdgeMesh::new())),
                        error => Err(error),
                    })
                    .map_err(|error| {
                        let so_far: Vec<String> =
                            inputs[..=i].iter().map(|x| x.0.clone()).collect();
                        match error {
                            BooleanError::Open { operand, .. }
                            | BooleanError::NonManifold { operand, .. }
                            | BooleanError::NotPolygonal { operand, .. }
                            | BooleanError::NonFinite { operand }
                            | BooleanError::SelfIntersecting { operand, .. }
                            | BooleanError::EmptyOperand { operand } => CsgError::Operand {
                                node: label.clone(),
                                operand: match operand {
                                    Operand::A if i == 1 => so_far[0].clone(),
                                    Operand::A => format!("the {op} of {}", names(&so_far[..i])),
                                    Operand::B => name.clone(),
                                },
                                problem: problem(&error),
                            },
                            error => CsgError::Boolean {
                                node: label.clone(),
                                error,
                            },
                        }
                    })
            })?;
        }
        Ok((acc, key))
    }
}

/// The result of `a op b` when either is an empty solid (no faces): the
/// boolean engine takes no empty operand. `None` when both have faces.
fn with_empty(op: BooleanOp, a: &Solid, b: &Solid) -> Option<Solid> {
    let (a_empty, b_empty) = (a.face_count() == 0, b.face_count() == 0);
    if !(a_empty || b_empty) {
        return None;
    }
    Some(match op {
        BooleanOp::Union if a_empty => b.clone(),
        BooleanOp::Union | BooleanOp::Difference => a.clone(),
        BooleanOp::Intersection => Arc::new(HalfEdgeMesh::new()),
    })
}

/// When an operand fingerprint was first met (a counter), for ordering a
/// preview's fold.
fn first_seen(key: u64) -> u64 {
    static SEEN: OnceLock<Mutex<(HashMap<u64, u64>, u64)>> = OnceLock::new();
    let Ok(mut seen) = SEEN.get_or_init(|| Mutex::new((HashMap::new(), 0))).lock() else {
        return 0;
    };
    if seen.0.len() >= 4096 {
        seen.0.clear();
    }
    seen.1 += 1;
    let next = seen.1;
    *seen.0.entry(key).or_insert(next)
}

/// A mesh operand, checked (closed, manifold, not crossing itself: once
/// per mesh, cached), and in a preview replaced by its simplified copy;
/// with its fingerprint.
fn leaf(
    label: &str,
    name: &str,
    mesh: Solid,
    key: u64,
    quality: Quality,
) -> Result<(Solid, u64), CsgError> {
    cached(key ^ 0x5851_f42d_4c95_7f2d, || {
        hedra_geom::csg::check_operand(&mesh)
            .map(|()| mesh.clone())
            .map_err(|error| CsgError::Operand {
                node: label.to_string(),
                operand: name.to_string(),
                problem: problem(&error),
            })
    })
    .map_err(|e| match e {
        // The cached error names the node and operand it was first met
        // under; name this one.
        CsgError::Operand { problem, .. } => CsgError::Operand {
            node: label.to_string(),
            operand: name.to_string(),
            problem,
        },
        e => e,
    })?;
    match quality {
        Quality::Preview { faces } => {
            let mut h = std::collections::hash_map::DefaultHasher::new();
            (key, faces, "preview").hash(&mut h);
            let proxy_key = h.finish();
            let proxy = cached(proxy_key, || Ok(Arc::new(preview_proxy(&mesh, faces))))?;
            Ok((proxy, proxy_key))
        }
        _ => Ok((mesh, key)),
    }
}

/// A simplified copy of a closed mesh with at most `faces` triangles (the
/// quadric decimation of `hedra_geom::progressive`, which keeps the
/// genus, the sharp edges and the orientation), for
/// [`Quality::Preview`]; the mesh itself when it is that small already,
/// or when the copy cannot be made or would cross itself.
///
/// Complexity: O(n log n) for n triangles.
pub fn preview_proxy(mesh: &HalfEdgeMesh, faces: usize) -> HalfEdgeMesh {
    use hedra_geom::progressive::{DecimateOptions, DecimateTarget, ProgressiveMesh};
    let triangles: usize = mesh
        .faces()
        .map(|f| mesh.face_degree(f).saturating_sub(2))
        .sum();
    if triangles <= faces {
        return mesh.clone();
    }
    let options = DecimateOptions::default();
    let creases = hedra_geom::Creases::default();
    let Ok(mut pm) = ProgressiveMesh::build(mesh, &creases, &options) else {
        return mesh.clone();
    };
    // Below the coarsest level (sharp edges hold a cube's grid vertices
    // on its edges), the coarsest level.
    let level = pm.level_for(DecimateTarget::Faces(faces)).unwrap_or(0);
    if pm.seek(level).is_err() {
        return mesh.clone();
    }
    let proxy = pm.output_mesh(&pm.level_creases(&creases), &options);
    if hedra_geom::csg::check_operand(&proxy).is_ok() {
        proxy
    } else {
        mesh.clone()
    }
}

/// The fingerprint of a shared mesh, computed once per `Arc`: the memo
/// holds a `Weak` to it, which keeps its allocation (so no other mesh can
/// take its address) and which `Arc::get_mut`/`make_mut` respect (neither
/// changes a mesh in place while a `Weak` points at it), so the same
/// address means the same, unchanged mesh.
fn known_fingerprint(mesh: &Arc<HalfEdgeMesh>) -> u64 {
    type Memo = HashMap<usize, (Weak<HalfEdgeMesh>, u64)>;
    static MEMO: OnceLock<Mutex<Memo>> = OnceLock::new();
    let memo = MEMO.get_or_init(|| Mutex::new(HashMap::new()));
    let at = Arc::as_ptr(mesh).addr();
    if let Ok(m) = memo.lock()
        && let Some((weak, key)) = m.get(&at)
        && std::ptr::eq(weak.as_ptr(), Arc::as_ptr(mesh))
    {
        return *key;
    }
    let key = fingerprint(mesh);
    if let Ok(mut m) = memo.lock() {
        if m.len() >= 4096 {
            m.retain(|_, (w, _)| w.strong_count() > 0);
        }
        if m.len() >= 4096 {
            m.clear();
        }
        m.insert(at, (Arc::downgrade(mesh), key));
    }
    key
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

/// A hash of a mesh's positions and faces (O(n)).
fn fingerprint(m: &HalfEdgeMesh) -> u64 {
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    let h = &mut hasher;
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
    hasher.finish()
}

/// The outermost CSG node whose solid `id` is drawn through (`id` is one
/// of its operands, or inside one), if any.
pub fn outermost_csg(doc: &Document, id: NodeId) -> Option<NodeId> {
    let mut top = None;
    let mut cur = id;
    let mut guard = doc.node_count() + 1;
    while let Some(parent) = doc.node(cur).and_then(|n| n.parent) {
        if csg_owner(doc, cur).is_some() {
            top = Some(parent);
        }
        cur = parent;
        guard -= 1;
        if guard == 0 {
            break;
        }
    }
    top
}

/// True when `ancestor` is a proper ancestor of `id`.
pub fn is_within(doc: &Document, id: NodeId, ancestor: NodeId) -> bool {
    let mut cur = doc.node(id).and_then(|n| n.parent);
    let mut guard = doc.node_count() + 1;
    while let Some(c) = cur {
        if c == ancestor {
            return true;
        }
        cur = doc.node(c).and_then(|n| n.parent);
        guard -= 1;
        if guard == 0 {
            break;
        }
    }
    false
}
