//! Commands on a mesh node's modifier stack (Mirror, Array): adding,
//! changing, removing and reordering modifiers, and applying them to the
//! cage. Subdivision's place in the stack is a field of its modifier, set
//! with [`Command::SetSubdivision`](super::Command::SetSubdivision).

use super::plan::Plan;
use super::{Command, CommandError, NodeRef};
use crate::modifiers::{DecimateModifier, MeshModifier, decimated_uvs, uv_seams};
use crate::scene::{MeshContent, Node, NodeContent};
use hedra_geom::progressive::ProgressiveMesh;
use std::sync::Arc;

impl Plan<'_> {
    /// The mesh node `r` with its label, or why not.
    fn mesh_node(&self, r: &NodeRef) -> Result<(Node, String), CommandError> {
        let n = self.node(r)?;
        let label = self.doc.label_of(n.id);
        if !matches!(n.content, NodeContent::Mesh(_)) {
            return Err(CommandError::NotAMesh { node: label });
        }
        Ok((n, label))
    }

    /// Changes the stack of mesh node `r` with `edit`, then checks that the
    /// new stack evaluates (so a merge that cannot be welded is refused
    /// when it is set, naming the modifier).
    fn edit_stack(
        &mut self,
        r: &NodeRef,
        edit: impl FnOnce(&mut MeshContent, &str) -> Result<(), CommandError>,
    ) -> Result<(), CommandError> {
        let (mut n, label) = self.mesh_node(r)?;
        let NodeContent::Mesh(content) = &mut n.content else {
            unreachable!("mesh_node checked the content");
        };
        edit(content, &label)?;
        // Decimate records first, so that the check below evaluates from them.
        content
            .refresh_decimations()
            .map_err(|error| CommandError::Modifier {
                node: label.clone(),
                error,
            })?;
        content
            .apply_stack(content.modifiers.len())
            .map_err(|error| CommandError::Modifier {
                node: label.clone(),
                error,
            })?;
        self.set(n);
        Ok(())
    }

    pub(super) fn add_modifier(
        &mut self,
        node: &NodeRef,
        modifier: &MeshModifier,
    ) -> Result<(), CommandError> {
        self.edit_stack(node, |c, label| {
            check(modifier, label)?;
            c.modifiers.push(*modifier);
            Ok(())
        })
    }

    pub(super) fn set_modifier(
        &mut self,
        node: &NodeRef,
        index: usize,
        modifier: &MeshModifier,
    ) -> Result<(), CommandError> {
        self.edit_stack(node, |c, label| {
            check(modifier, label)?;
            let slot = slot(c, index, label)?;
            c.modifiers[slot] = *modifier;
            Ok(())
        })
    }

    pub(super) fn remove_modifier(
        &mut self,
        node: &NodeRef,
        index: usize,
    ) -> Result<(), CommandError> {
        self.edit_stack(node, |c, label| {
            let slot = slot(c, index, label)?;
            c.modifiers.remove(slot);
            // Subdivision stays after the same modifiers.
            if let Some(s) = &mut c.subdivision
                && let Some(p) = &mut s.stack_position
                && slot < *p
            {
                *p -= 1;
            }
            Ok(())
        })
    }

    pub(super) fn move_modifier(
        &mut self,
        node: &NodeRef,
        from: usize,
        to: usize,
    ) -> Result<(), CommandError> {
        self.edit_stack(node, |c, label| {
            let from = slot(c, from, label)?;
            let to = slot(c, to, label)?;
            let m = c.modifiers.remove(from);
            c.modifiers.insert(to, m);
            Ok(())
        })
    }

    /// Makes the first `count` stack modifiers (all by default) part of the
    /// cage; they must all run before subdivision.
    pub(super) fn apply_modifiers(
        &mut self,
        node: &NodeRef,
        count: Option<usize>,
    ) -> Result<(), CommandError> {
        let (mut n, label) = self.mesh_node(node)?;
        let NodeContent::Mesh(content) = &mut n.content else {
            unreachable!("mesh_node checked the content");
        };
        if content.modifiers.is_empty() {
            return Err(CommandError::Nothing("the node has no modifiers to apply"));
        }
        let count = count.unwrap_or(content.modifiers.len());
        if count == 0 || count > content.modifiers.len() {
            return Err(CommandError::NoModifier {
                node: label,
                index: count.saturating_sub(1),
                count: content.modifiers.len(),
            });
        }
        if content.subdivision_position() < count {
            return Err(CommandError::SubdivisionFirst {
                node: label,
                position: content.subdivision_position(),
            });
        }
        *content = content
            .with_modifiers_applied(count)
            .map_err(|error| CommandError::Modifier { node: label, error })?;
        self.set(n);
        Ok(())
    }
}

impl Plan<'_> {
    /// [`Command::Decimate`](super::Command::Decimate): the cage replaced
    /// by its simplification (the modifier stack stays).
    pub(super) fn decimate(
        &mut self,
        node: &NodeRef,
        settings: DecimateModifier,
    ) -> Result<(), CommandError> {
        let (mut n, label) = self.mesh_node(node)?;
        let NodeContent::Mesh(content) = &mut n.content else {
            unreachable!("mesh_node checked the content");
        };
        check(&MeshModifier::Decimate(settings), &label)?;
        let here = |error| CommandError::Decimate {
            node: label.clone(),
            error,
        };
        let options = settings.options(uv_seams(&content.mesh, &content.corners));
        let mut pm =
            ProgressiveMesh::build(&content.mesh, &content.creases, &options).map_err(here)?;
        let level = pm.level_for(settings.target).map_err(here)?;
        pm.seek(level).map_err(here)?;
        content.creases = pm.level_creases(&content.creases);
        let mesh = pm.output_mesh(&content.creases, &options);
        content.corners = decimated_uvs(&content.mesh, &mesh, &content.corners);
        content.mesh = Arc::new(mesh);
        content.primitive = None;
        self.set(n);
        Ok(())
    }
}

/// The modifier's values, or [`CommandError::ModifierValue`].
fn check(modifier: &MeshModifier, label: &str) -> Result<(), CommandError> {
    modifier
        .check()
        .map_err(|problem| CommandError::ModifierValue {
            node: label.to_string(),
            problem,
        })
}

/// `index` if the stack has it, else [`CommandError::NoModifier`].
fn slot(c: &MeshContent, index: usize, label: &str) -> Result<usize, CommandError> {
    if index < c.modifiers.len() {
        Ok(index)
    } else {
        Err(CommandError::NoModifier {
            node: label.to_string(),
            index,
            count: c.modifiers.len(),
        })
    }
}

impl Plan<'_> {
    /// Decides a command of the the modifier stack family (the variants
    /// [`Family::Modifiers`](super::plan::Family::Modifiers) names; [`Plan::run`] sends only those here).
    pub(super) fn run_modifier_command(&mut self, cmd: &Command) -> Result<(), CommandError> {
        match cmd {
            Command::AddModifier { node, modifier } => self.add_modifier(node, modifier),
            Command::SetModifier {
                node,
                index,
                modifier,
            } => self.set_modifier(node, *index, modifier),
            Command::RemoveModifier { node, index } => self.remove_modifier(node, *index),
            Command::MoveModifier { node, from, to } => self.move_modifier(node, *from, *to),
            Command::ApplyModifiers { node, count } => self.apply_modifiers(node, *count),
            Command::Decimate {
                node,
                target,
                keep_borders,
                keep_creases,
                keep_uv_seams,
                sharp_angle,
                keep_quads,
            } => self.decimate(
                node,
                crate::modifiers::DecimateModifier {
                    target: *target,
                    level: None,
                    keep_borders: *keep_borders,
                    keep_creases: *keep_creases,
                    keep_uv_seams: *keep_uv_seams,
                    sharp_angle: *sharp_angle,
                    keep_quads: *keep_quads,
                },
            ),
            _ => unreachable!("not a command of the the modifier stack family"),
        }
    }
}
