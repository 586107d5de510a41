//! The G1 join commands (make, break) and the pass after every command
//! that keeps joined patches G1 (see [`crate::join`]).

use super::plan::Plan;
use super::{Command, CommandError, NodeRef};
use crate::construction::world_through;
use crate::join::{self, G1Join, JoinError, Placed};
use crate::scene::{Node, NodeId};

impl Plan<'_> {
    fn placed_here(&self, id: NodeId) -> Option<Placed<'_>> {
        let lookup = |id: NodeId| self.current(id);
        Some(Placed {
            node: self.current(id)?,
            world: world_through(&lookup, id),
        })
    }

    fn join_error(&self, quad: NodeId, triangle: NodeId, error: JoinError) -> CommandError {
        CommandError::Join {
            quad: self.doc.label_of(quad),
            triangle: self.doc.label_of(triangle),
            error,
        }
    }

    pub(super) fn make_g1_join(
        &mut self,
        triangle: &NodeRef,
        quad: &NodeRef,
    ) -> Result<(), CommandError> {
        let (t, q) = (self.node(triangle)?, self.node(quad)?);
        if t.id == q.id {
            return Err(self.join_error(q.id, t.id, JoinError::SameNode));
        }
        if let Some(j) = q.g1_join {
            let error = JoinError::AlreadyJoined {
                node: self.doc.label_of(q.id),
                triangle: self.doc.label_of(j.triangle),
            };
            return Err(self.join_error(q.id, t.id, error));
        }
        let (pt, pq) = (
            self.placed_here(t.id).expect("resolved"),
            self.placed_here(q.id).expect("resolved"),
        );
        let (tc, qc) = join::make(pt, pq).map_err(|e| self.join_error(q.id, t.id, e))?;
        let (mut t, mut q) = (t, q);
        t.content = tc;
        q.content = qc;
        q.g1_join = Some(G1Join { triangle: t.id });
        self.set(t);
        self.set(q);
        Ok(())
    }

    pub(super) fn break_g1_join(&mut self, node: &NodeRef) -> Result<(), CommandError> {
        let id = self.resolve(node)?;
        let joined: Vec<Node> = self
            .doc
            .nodes
            .keys()
            .filter_map(|&k| self.current(k))
            .filter(|n| n.g1_join.is_some_and(|j| n.id == id || j.triangle == id))
            .cloned()
            .collect();
        if joined.is_empty() {
            return Err(CommandError::NotJoined {
                node: self.doc.label_of(id),
            });
        }
        for mut n in joined {
            n.g1_join = None;
            self.set(n);
        }
        Ok(())
    }

    /// After `_cmd` is decided: every kept join whose patch or triangle (or
    /// an ancestor of either) the command changed is solved again in this
    /// plan ([`join::follow`]); a join whose node was deleted, or stopped
    /// being a Bézier triangle or patch, ends. Returns notes for the step's
    /// label.
    ///
    /// # Errors
    /// [`CommandError::Join`] when a join cannot follow the change (the
    /// command is refused).
    pub(super) fn follow_joins(&mut self, _cmd: &Command) -> Result<Vec<String>, CommandError> {
        let mut notes = Vec::new();
        let changed: Vec<NodeId> = self.changes.iter().map(|c| c.id).collect();
        if changed.is_empty() {
            return Ok(notes);
        }
        let quads: Vec<NodeId> = self
            .doc
            .nodes
            .values()
            .filter(|n| n.g1_join.is_some())
            .map(|n| n.id)
            .collect();
        for id in quads {
            let before = self.doc.nodes[&id].g1_join.expect("filtered");
            let Some(quad) = self.current(id).cloned() else {
                continue;
            };
            // Broken or remade by this very command.
            if quad.g1_join != Some(before) {
                continue;
            }
            let tri = before.triangle;
            let end = |plan: &mut Self, why: String, notes: &mut Vec<String>| {
                let mut q = quad.clone();
                q.g1_join = None;
                plan.set(q);
                notes.push(format!("ended the G1 join of '{}': {why}", quad.name));
            };
            if self.current(tri).is_none() {
                end(self, "its triangle was deleted".into(), &mut notes);
                continue;
            }
            let affected = changed
                .iter()
                .any(|&c| self.is_ancestor_here(c, id) || self.is_ancestor_here(c, tri));
            if !affected {
                continue;
            }
            let (Some(t0), Some(q0)) = (self.doc.nodes.get(&tri), self.doc.nodes.get(&id)) else {
                continue;
            };
            let old = (
                Placed {
                    node: t0,
                    world: self.doc.world_matrix(tri),
                },
                Placed {
                    node: q0,
                    world: self.doc.world_matrix(id),
                },
            );
            let new = (
                self.placed_here(tri).expect("exists"),
                self.placed_here(id).expect("exists"),
            );
            match join::follow(old, new) {
                Ok(None) => {}
                Ok(Some((tc, qc))) => {
                    let mut t = self.current(tri).cloned().expect("exists");
                    let mut q = self.current(id).cloned().expect("exists");
                    t.content = tc;
                    q.content = qc;
                    self.set(t);
                    self.set(q);
                }
                Err(JoinError::NotATriangle { node } | JoinError::NotAPatch { node }) => {
                    let why = format!("{node} is no longer a Bézier triangle or patch");
                    end(self, why, &mut notes);
                }
                Err(error) => return Err(self.join_error(id, tri, error)),
            }
        }
        Ok(notes)
    }
}
