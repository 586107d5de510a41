//! Commands that make surfaces and meshes from curves (extrude, revolve,
//! sweep, two-rail sweep, loft), change and apply them, and the pass after
//! every command that keeps such nodes following their inputs (see
//! [`crate::construction`]).

use super::plan::Plan;
use super::{Command, CommandError, NodeRef};
use crate::construction::{
    CapEnd, Construction, ConstructionError, Made, Output, content_of, input_of, same_geometry,
};
use crate::scene::{Node, NodeId, NodeTransform};

impl Plan<'_> {
    /// Makes a construction from the nodes as this plan sees them.
    fn make(&self, c: &Construction) -> Result<Made, ConstructionError> {
        let lookup = |id: NodeId| self.current(id);
        c.make(&|id| input_of(&lookup, id))
    }

    fn resolve_construction(
        &self,
        c: &Construction<NodeRef>,
    ) -> Result<Construction, CommandError> {
        c.map_inputs(|r| self.resolve(r))
    }

    pub(super) fn make_from_curves(
        &mut self,
        name: &str,
        construction: &Construction<NodeRef>,
    ) -> Result<(), CommandError> {
        let c = self.resolve_construction(construction)?;
        let made = self.make(&c).map_err(|error| CommandError::Construction {
            node: format!("'{name}'"),
            error,
        })?;
        let id = self.add_node(name, &None, NodeTransform::IDENTITY, content_of(made, None))?;
        let mut n = self.current(id).cloned().expect("just added");
        n.construction = Some(c.clone());
        self.set(n);
        self.sync_caps(id, &c)
    }

    /// The cap nodes of `id`: its children made as caps of a construction.
    fn cap_children(&self, id: NodeId) -> Vec<Node> {
        let mut ids: Vec<NodeId> = self.doc.nodes.keys().copied().collect();
        ids.extend(self.changes.iter().map(|c| c.id));
        ids.sort();
        ids.dedup();
        ids.into_iter()
            .filter_map(|i| self.current(i))
            .filter(|n| {
                n.parent == Some(id)
                    && n.construction
                        .as_ref()
                        .is_some_and(|c| matches!(c.output, Output::Cap { .. }))
            })
            .cloned()
            .collect()
    }

    /// Keeps `id`'s cap nodes as its construction `c` asks: a NURBS result
    /// whose recipe asks for caps gets a child node for each end it has
    /// (named after it, made with the same recipe), kept in step when the
    /// recipe changes; other results have none.
    fn sync_caps(&mut self, id: NodeId, c: &Construction) -> Result<(), CommandError> {
        let existing = self.cap_children(id);
        let wanted = c.output == Output::Nurbs && c.recipe.caps();
        let name = self.current(id).map(|n| n.name.clone()).unwrap_or_default();
        for (end, label) in [(CapEnd::Start, "start"), (CapEnd::End, "end")] {
            let cap = Construction {
                recipe: c.recipe.clone(),
                output: Output::Cap { end },
            };
            let made = if wanted {
                match self.make(&cap) {
                    Ok(made) => Some(made),
                    // A surface without ends (a full turn) gets no caps.
                    Err(ConstructionError::NoEnds) => None,
                    Err(error) => {
                        return Err(CommandError::Construction {
                            node: format!("'{name}'"),
                            error,
                        });
                    }
                }
            } else {
                None
            };
            let old = existing
                .iter()
                .find(|n| n.construction.as_ref().map(|c| c.output) == Some(cap.output));
            match (made, old) {
                (Some(made), Some(old)) => {
                    let mut n = old.clone();
                    n.content = content_of(made, Some(&n.content));
                    n.construction = Some(cap);
                    self.set(n);
                }
                (Some(made), None) => {
                    let cap_id = self.add_node(
                        &format!("{name} cap {label}"),
                        &None,
                        NodeTransform::IDENTITY,
                        content_of(made, None),
                    )?;
                    let mut n = self.current(cap_id).cloned().expect("just added");
                    n.parent = Some(id);
                    n.construction = Some(cap);
                    self.set(n);
                }
                (None, Some(old)) => self.remove(old.id),
                (None, None) => {}
            }
        }
        Ok(())
    }

    pub(super) fn set_construction(
        &mut self,
        node: &NodeRef,
        construction: &Construction<NodeRef>,
    ) -> Result<(), CommandError> {
        let mut n = self.node(node)?;
        let label = self.doc.label_of(n.id);
        match &n.construction {
            None => return Err(CommandError::NoConstruction { node: label }),
            Some(old) if matches!(old.output, Output::Cap { .. }) => {
                let parent = n.parent.map(|p| self.doc.label_of(p)).unwrap_or_default();
                return Err(CommandError::CapOfConstruction {
                    node: label,
                    parent,
                });
            }
            Some(_) => {}
        }
        let c = self.resolve_construction(construction)?;
        let made = self
            .make(&c)
            .map_err(|error| CommandError::Construction { node: label, error })?;
        n.content = content_of(made, Some(&n.content));
        n.construction = Some(c.clone());
        let id = n.id;
        self.set(n);
        self.sync_caps(id, &c)
    }

    pub(super) fn apply_construction(&mut self, nodes: &[NodeRef]) -> Result<(), CommandError> {
        for r in nodes {
            let mut n = self.node(r)?;
            if n.construction.take().is_none() {
                return Err(CommandError::NoConstruction {
                    node: self.doc.label_of(n.id),
                });
            }
            // Its caps are frozen with it.
            for mut cap in self.cap_children(n.id) {
                cap.construction = None;
                self.set(cap);
            }
            self.set(n);
        }
        Ok(())
    }

    /// True when `ancestor` is `id` or one of its parents, as this plan
    /// sees the tree.
    pub(super) fn is_ancestor_here(&self, ancestor: NodeId, id: NodeId) -> bool {
        let mut cur = Some(id);
        let mut guard = self.doc.node_count() + self.changes.len() + 1;
        while let Some(c) = cur {
            if c == ancestor {
                return true;
            }
            guard -= 1;
            if guard == 0 {
                return false;
            }
            cur = self.current(c).and_then(|n| n.parent);
        }
        false
    }

    fn freeze(&mut self, node: &Node) {
        let mut n = node.clone();
        n.construction = None;
        self.set(n);
    }

    /// After `_cmd` is decided: results whose geometry it edited directly
    /// are frozen, results whose inputs it deleted are frozen, and results
    /// whose inputs (or their ancestors) it changed are made again, all in
    /// this plan. Returns notes for the step's label ("froze 'Vase': its
    /// input #3 was deleted").
    ///
    /// # Errors
    /// [`CommandError::Construction`] when a dependent cannot be made
    /// again with the change (the command is refused).
    pub(super) fn follow_constructions(
        &mut self,
        _cmd: &Command,
    ) -> Result<Vec<String>, CommandError> {
        let mut notes = Vec::new();
        let changed: Vec<NodeId> = self.changes.iter().map(|c| c.id).collect();
        if changed.is_empty() {
            return Ok(notes);
        }
        // Results edited directly: same construction, other geometry.
        for change in self.changes.clone() {
            let (Some(before), Some(after)) = (&change.before, &change.after) else {
                continue;
            };
            let Some(c) = &after.construction else {
                continue;
            };
            if before.construction.as_ref() == Some(c)
                && !same_geometry(&before.content, &after.content)
            {
                self.freeze(after);
                notes.push(format!("froze '{}': edited directly", after.name));
            }
        }
        // Dependents of what changed.
        let mut ids: Vec<NodeId> = self.doc.nodes.keys().copied().collect();
        ids.extend(
            self.changes
                .iter()
                .filter(|c| c.before.is_none())
                .map(|c| c.id),
        );
        for id in ids {
            let Some(n) = self.current(id).cloned() else {
                continue;
            };
            let Some(c) = &n.construction else { continue };
            let inputs: Vec<NodeId> = c.recipe.inputs().into_iter().copied().collect();
            if let Some(gone) = inputs.iter().find(|&&i| self.current(i).is_none()) {
                notes.push(format!("froze '{}': its input {gone} was deleted", n.name));
                self.freeze(&n);
                continue;
            }
            // Made by this very command (MakeFromCurves, SetConstruction).
            let just_made = self
                .changes
                .iter()
                .find(|ch| ch.id == id)
                .is_some_and(|ch| {
                    ch.before.as_ref().map(|b| &b.construction) != Some(&n.construction)
                });
            let affected = inputs
                .iter()
                .any(|&i| changed.iter().any(|&ch| self.is_ancestor_here(ch, i)));
            if just_made || !affected {
                continue;
            }
            let made = self.make(c).map_err(|error| CommandError::Construction {
                node: self.doc.label_of(id),
                error,
            })?;
            let content = content_of(made, Some(&n.content));
            if !same_geometry(&content, &n.content) {
                let mut m = n.clone();
                m.content = content;
                self.set(m);
            }
        }
        Ok(notes)
    }
}

impl Plan<'_> {
    /// Decides a command of the surfaces and meshes from curves family (the variants
    /// [`Family::Constructions`](super::plan::Family::Constructions) names; [`Plan::run`] sends only those here).
    pub(super) fn run_construction_command(&mut self, cmd: &Command) -> Result<(), CommandError> {
        match cmd {
            Command::MakeFromCurves { name, construction } => {
                self.make_from_curves(name, construction)
            }
            Command::SetConstruction { node, construction } => {
                self.set_construction(node, construction)
            }
            Command::ApplyConstruction { nodes } => self.apply_construction(nodes),
            Command::MakeG1Join { triangle, quad } => self.make_g1_join(triangle, quad),
            Command::BreakG1Join { node } => self.break_g1_join(node),
            _ => unreachable!("not a command of the surfaces and meshes from curves family"),
        }
    }
}
