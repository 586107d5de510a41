//! Reversible edits and the undo history.
//!
//! Every change to the document is a [`Transaction`] of [`NodeChange`]s: the
//! whole node before and after. Mesh content sits behind an `Arc`, so
//! unchanged meshes are shared between steps (Wings 3D's snapshot undo), and a
//! step is exactly reversible without any inverse operator. A transaction also
//! keeps the command that made it, for "adjust last operation" and for the
//! history panel.

use crate::command::Command;
use crate::scene::{Document, Node, NodeContent, NodeId};

use std::collections::HashSet;
use std::sync::Arc;

/// One node replaced: `None` before means created, `None` after means deleted.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeChange {
    /// The node replaced.
    pub id: NodeId,
    /// The node before the step; `None`: the step created it.
    pub before: Option<Node>,
    /// The node after the step; `None`: the step deleted it.
    pub after: Option<Node>,
}

/// One undo step.
#[derive(Clone, Debug, PartialEq)]
pub struct Transaction {
    /// Unique, increasing; used to tell whether the document changed since a save.
    pub serial: u64,
    /// What the history panel shows ("Add Cube", "Move", …).
    pub label: String,
    /// The command that produced it, if any.
    pub command: Option<Command>,
    /// Every node the step changes, in the order they were decided; undo
    /// applies them in reverse.
    pub changes: Vec<NodeChange>,
    /// The document's next free node id before the step (restored by undo).
    pub next_id_before: u64,
    /// The next free node id after the step (restored by redo).
    pub next_id_after: u64,
}

impl Transaction {
    /// Applies the step forward (`redo`) or backward (`undo`).
    pub fn apply(&self, doc: &mut Document, forward: bool) {
        let changes: Box<dyn Iterator<Item = &NodeChange>> = if forward {
            Box::new(self.changes.iter())
        } else {
            Box::new(self.changes.iter().rev())
        };
        for c in changes {
            let target = if forward { &c.after } else { &c.before };
            match target {
                Some(n) => {
                    doc.nodes.insert(c.id, n.clone());
                }
                None => {
                    doc.nodes.remove(&c.id);
                }
            }
        }
        doc.next_node_id = if forward {
            self.next_id_after
        } else {
            self.next_id_before
        };
    }

    /// True when the document is in the state this step starts from
    /// (`forward`) or ends in (backward): every changed node matches.
    pub fn fits(&self, doc: &Document, forward: bool) -> bool {
        self.changes.iter().all(|c| {
            let expected = if forward { &c.before } else { &c.after };
            doc.nodes.get(&c.id) == expected.as_ref()
        })
    }

    /// Rough heap size of what this step alone keeps alive: meshes that
    /// differ between before and after, plus the node records.
    pub fn approx_bytes(&self) -> usize {
        let mut total = 0;
        for c in &self.changes {
            total += 256;
            let mb = c.before.as_ref().and_then(mesh_arc);
            let ma = c.after.as_ref().and_then(mesh_arc);
            match (mb, ma) {
                (Some(a), Some(b)) if Arc::ptr_eq(a, b) => {}
                (a, b) => {
                    total += a.map_or(0, |m| mesh_bytes(m)) + b.map_or(0, |m| mesh_bytes(m));
                }
            }
        }
        total
    }
}

fn mesh_arc(n: &Node) -> Option<&Arc<hedra_geom::HalfEdgeMesh>> {
    match &n.content {
        NodeContent::Mesh(m) => Some(&m.mesh),
        _ => None,
    }
}

/// Approximate heap bytes of a mesh.
pub fn mesh_bytes(m: &hedra_geom::HalfEdgeMesh) -> usize {
    m.vertex_capacity() * 33 + m.edge_capacity() * 33 + m.face_capacity() * 5
}

/// Undo and redo stacks with a step limit and a memory cap.
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    pub(crate) done: Vec<Transaction>,
    pub(crate) undone: Vec<Transaction>,
    /// Oldest steps are dropped beyond this many.
    pub max_steps: usize,
    /// Oldest steps are dropped while the history holds more than this
    /// (approximate bytes); the newest step is always kept.
    pub max_bytes: usize,
    /// How many old steps were dropped by the limits so far.
    pub dropped: usize,
    pub(crate) next_serial: u64,
}

impl Default for History {
    fn default() -> Self {
        History {
            done: Vec::new(),
            undone: Vec::new(),
            max_steps: 500,
            max_bytes: 512 * 1024 * 1024,
            dropped: 0,
            next_serial: 1,
        }
    }
}

impl History {
    /// True when there is a step to undo.
    pub fn can_undo(&self) -> bool {
        !self.done.is_empty()
    }
    /// True when there is an undone step to redo (a new step clears them).
    pub fn can_redo(&self) -> bool {
        !self.undone.is_empty()
    }
    /// Steps that can be undone, oldest first.
    pub fn done(&self) -> &[Transaction] {
        &self.done
    }
    /// Steps that can be redone, the next one to redo last.
    pub fn undone(&self) -> &[Transaction] {
        &self.undone
    }
    /// Serial of the step the document is at (0 before any step).
    pub fn current_serial(&self) -> u64 {
        self.done.last().map_or(0, |t| t.serial)
    }
    /// The next serial number to hand out.
    pub fn take_serial(&mut self) -> u64 {
        let s = self.next_serial;
        self.next_serial += 1;
        s
    }

    /// Pushes an applied step, drops the redo branch and enforces the limits.
    pub fn push(&mut self, t: Transaction) {
        self.undone.clear();
        self.done.push(t);
        self.enforce_limits();
    }

    /// Drops the oldest steps beyond `max_steps` or `max_bytes`. Dropping
    /// from the bottom never breaks the remaining steps: each holds whole nodes.
    pub fn enforce_limits(&mut self) {
        let mut excess = self.done.len().saturating_sub(self.max_steps);
        let mut bytes = self.approx_bytes();
        let mut drop = 0;
        while drop < self.done.len().saturating_sub(1) && (excess > 0 || bytes > self.max_bytes) {
            bytes -= self.done[drop].approx_bytes().min(bytes);
            excess = excess.saturating_sub(1);
            drop += 1;
        }
        if drop > 0 {
            self.done.drain(..drop);
            self.dropped += drop;
        }
    }

    /// Approximate bytes held by all steps, counting each shared mesh once.
    pub fn approx_bytes(&self) -> usize {
        let mut seen = HashSet::new();
        let mut total = 0;
        for t in self.done.iter().chain(&self.undone) {
            for c in &t.changes {
                total += 256;
                for m in [c.before.as_ref(), c.after.as_ref()]
                    .into_iter()
                    .flatten()
                    .filter_map(mesh_arc)
                {
                    if seen.insert(Arc::as_ptr(m)) {
                        total += mesh_bytes(m);
                    }
                }
            }
        }
        total
    }

    /// Moves the last done step to the redo stack, undoing it on `doc`.
    pub fn undo(&mut self, doc: &mut Document) -> Option<&Transaction> {
        let t = self.done.pop()?;
        t.apply(doc, false);
        self.undone.push(t);
        self.undone.last()
    }

    /// Re-applies the next undone step.
    pub fn redo(&mut self, doc: &mut Document) -> Option<&Transaction> {
        let t = self.undone.pop()?;
        t.apply(doc, true);
        self.done.push(t);
        self.done.last()
    }

    /// Undoes or redoes until exactly `position` steps are done
    /// (0 = before the first kept step).
    pub fn jump_to(&mut self, doc: &mut Document, position: usize) {
        while self.done.len() > position && self.undo(doc).is_some() {}
        while self.done.len() < position && self.redo(doc).is_some() {}
    }

    /// Discards everything (New, Open).
    pub fn clear(&mut self) {
        self.done.clear();
        self.undone.clear();
        self.dropped = 0;
    }
}
