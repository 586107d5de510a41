//! A document with its history: the one place commands are applied, for the
//! GUI, the CLI and the tests alike.

use crate::command::{Command, CommandError};
use crate::history::{History, Transaction};
use crate::scene::{Document, NodeId};

/// An open document, its undo history and whether it changed since saving.
///
/// This is where a user of the crate starts: every [`Command`] is applied
/// through [`Session::execute`] as one undo step.
///
/// ```
/// use glam::DVec3;
/// use hedra_doc::{Command, FaceSet, NodeRef, Session};
/// use hedra_geom::Primitive;
///
/// let mut session = Session::new();
/// session.execute(&Command::AddPrimitive {
///     primitive: Primitive::Cube { size: 2.0 },
///     name: Some("Box".into()),
///     parent: None,
///     transform: Default::default(),
/// })?;
/// let counts = |s: &Session| {
///     let node = s.doc.find_by_name("Box").expect("the cube node");
///     let mesh = node.content.mesh().expect("a mesh node");
///     (mesh.vertex_count(), mesh.edge_count(), mesh.face_count())
/// };
/// assert_eq!(counts(&session), (8, 12, 6));
///
/// // Extrude the top face (the face whose centre is nearest to +Y) by 0.5.
/// let applied = session.execute(&Command::ExtrudeFaces {
///     node: NodeRef::Name("Box".into()),
///     faces: FaceSet::Nearest(DVec3::Y),
///     distance: 0.5,
/// })?;
/// assert_eq!(applied.label, "Extrude Faces");
/// assert_eq!(counts(&session), (12, 20, 10));
/// assert!(session.is_dirty());
///
/// // Undo gives the cube back; redo the extrusion again.
/// assert_eq!(session.undo().as_deref(), Some("Extrude Faces"));
/// assert_eq!(counts(&session), (8, 12, 6));
/// session.redo();
/// assert_eq!(counts(&session), (12, 20, 10));
/// # Ok::<(), hedra_doc::CommandError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Session {
    /// The document as it is now.
    pub doc: Document,
    /// Its undo and redo steps.
    pub history: History,
    /// History serial at the last save or load (`None`: never saved).
    pub saved_serial: Option<u64>,
}

impl Default for Session {
    fn default() -> Self {
        Session {
            doc: Document::new(),
            history: History::default(),
            saved_serial: Some(0),
        }
    }
}

/// What an applied command did.
#[derive(Clone, Debug, PartialEq)]
pub struct Applied {
    /// The step's history label ("Add Cube").
    pub label: String,
    /// Nodes that did not exist before (for selecting them).
    pub created: Vec<NodeId>,
}

impl Session {
    /// An empty document with an empty history, counted as saved (not dirty).
    pub fn new() -> Self {
        Self::default()
    }

    /// True when the document differs from the last save.
    pub fn is_dirty(&self) -> bool {
        self.saved_serial != Some(self.history.current_serial())
    }

    /// Marks the current state as saved.
    pub fn mark_saved(&mut self) {
        self.saved_serial = Some(self.history.current_serial());
    }

    /// Decides and applies a command as one undo step.
    ///
    /// # Errors
    /// The command's [`CommandError`]; the document and history are unchanged.
    pub fn execute(&mut self, cmd: &Command) -> Result<Applied, CommandError> {
        let serial = self.history.next_serial;
        let t = self.doc.decide(cmd, serial)?;
        self.history.take_serial();
        Ok(self.commit(t))
    }

    /// Applies an already decided transaction and pushes it.
    pub fn commit(&mut self, t: Transaction) -> Applied {
        t.apply(&mut self.doc, true);
        let applied = Applied {
            label: t.label.clone(),
            created: t
                .changes
                .iter()
                .filter(|c| c.before.is_none() && c.after.is_some())
                .map(|c| c.id)
                .collect(),
        };
        self.history.push(t);
        applied
    }

    /// Re-runs the last step with a changed command (Blender's "adjust last
    /// operation"): undo it, execute `cmd`; if that fails, the old step is
    /// restored and the error returned.
    ///
    /// # Errors
    /// [`CommandError::Nothing`] without a step to adjust, or `cmd`'s error.
    pub fn adjust_last(&mut self, cmd: &Command) -> Result<Applied, CommandError> {
        if !self.history.can_undo() {
            return Err(CommandError::Nothing("there is no operation to adjust"));
        }
        let redo_branch = std::mem::take(&mut self.history.undone);
        self.history.undo(&mut self.doc);
        match self.execute(cmd) {
            Ok(a) => Ok(a),
            Err(e) => {
                self.history.redo(&mut self.doc);
                self.history.undone = redo_branch;
                Err(e)
            }
        }
    }

    /// Adds imported meshes as one undo step.
    pub fn import(&mut self, meshes: &[crate::import::ImportedMesh], label: &str) -> Applied {
        let serial = self.history.take_serial();
        let t = self.doc.decide_import(meshes, label, serial);
        self.commit(t)
    }

    /// Undoes the last step; its label, or `None` when there is nothing to
    /// undo.
    pub fn undo(&mut self) -> Option<String> {
        self.history.undo(&mut self.doc).map(|t| t.label.clone())
    }
    /// Redoes the last undone step; its label, or `None` when there is
    /// nothing to redo.
    pub fn redo(&mut self) -> Option<String> {
        self.history.redo(&mut self.doc).map(|t| t.label.clone())
    }
    /// Undoes or redoes to `position` done steps.
    pub fn jump_to(&mut self, position: usize) {
        self.history.jump_to(&mut self.doc, position);
    }
}
