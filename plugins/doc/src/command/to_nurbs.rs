//! [`Command::ConvertSubdivisionToNurbs`](super::Command::ConvertSubdivisionToNurbs):
//! a subdivision cage becomes a group of NURBS surface nodes.

use std::sync::Arc;

use hedra_geom::subdivision::to_nurbs::{NurbsConversion, ToNurbsOptions, to_nurbs};

use super::CommandError;
use super::NodeRef;
use super::plan::Plan;
use crate::scene::{MeshContent, NodeContent, SurfaceShape};

/// The default tolerance: this fraction of the cage's bounding-box diagonal.
pub const DEFAULT_TOLERANCE: f64 = 1e-4;

/// A conversion's result in one line, as the undo step's label, `hedra
/// info --to-nurbs` and the STEP export's note give it: the patches, how
/// many are exact, and the largest distance from the limit surface and
/// normal angle across patch edges as measured (model units).
pub fn conversion_summary(c: &NurbsConversion) -> String {
    let (exact, approximated) = c.counts();
    let levels = if c.deepest_level > c.level {
        format!("levels {}–{}", c.level, c.deepest_level)
    } else {
        format!("level {}", c.level)
    };
    format!(
        "{} NURBS patches ({exact} exact, {approximated} approximated; {levels}), largest distance {:.1e}, largest angle {:.2}°",
        c.patches.len(),
        c.report.max_distance,
        c.report.max_angle_degrees
    )
}

impl MeshContent {
    /// The NURBS patches of this mesh's Catmull-Clark limit surface (what
    /// [`Command::ConvertSubdivisionToNurbs`](crate::Command::ConvertSubdivisionToNurbs)
    /// adds), within `fraction` of the cage's bounding-box diagonal, with the
    /// shared edge curves and patch loops (`NurbsConversion::sides`) a
    /// B-rep writer needs and the measured figures (`report`, `within`), for
    /// a STEP export of the node or a status line. `node` names the node in
    /// errors.
    ///
    /// # Errors
    /// [`CommandError::Tolerance`], [`CommandError::NoSubdivision`],
    /// [`CommandError::Modifier`] or [`CommandError::ModifierAfterSubdivision`]
    /// for the stack, [`CommandError::ToNurbs`] from the kernel.
    pub fn limit_nurbs(&self, fraction: f64, node: &str) -> Result<NurbsConversion, CommandError> {
        if !(fraction.is_finite() && fraction > 0.0) {
            return Err(CommandError::Tolerance(fraction));
        }
        let label = node.to_string();
        let Some(modifier) = self.subdivision else {
            return Err(CommandError::NoSubdivision { node: label });
        };
        let input = self
            .smooth_cage()
            .map_err(|error| CommandError::Modifier {
                node: label.clone(),
                error,
            })?
            .ok_or_else(|| CommandError::ModifierAfterSubdivision {
                node: label.clone(),
            })?;
        let options = ToNurbsOptions::relative(&input.mesh, fraction);
        to_nurbs(&input.mesh, &input.creases, modifier.options, &options)
            .map_err(|error| CommandError::ToNurbs { node: label, error })
    }
}

impl Plan<'_> {
    pub(super) fn convert_subdivision_to_nurbs(
        &mut self,
        node: &NodeRef,
        tolerance: Option<f64>,
        keep_cage: bool,
    ) -> Result<(), CommandError> {
        let fraction = tolerance.unwrap_or(DEFAULT_TOLERANCE);
        let mut cage = self.node(node)?;
        let label = self.doc.label_of(cage.id);
        let NodeContent::Mesh(content) = &cage.content else {
            return Err(CommandError::NotAMesh { node: label });
        };
        let conversion = content.limit_nurbs(fraction, &label)?;
        self.notes.push(conversion_summary(&conversion));
        let parent = cage.parent.map(|p| NodeRef::Id(p.0));
        let group = self.add_node(
            &format!("{} NURBS", cage.name),
            &parent,
            cage.transform,
            NodeContent::Empty,
        )?;
        let digits = conversion.patches.len().to_string().len();
        for (i, patch) in conversion.patches.into_iter().enumerate() {
            // The group is new in this plan, so the patch is parented here
            // rather than through a reference the document would resolve.
            let id = self.add_node(
                &format!("{} patch {:0digits$}", cage.name, i + 1),
                &None,
                Default::default(),
                NodeContent::Surface(Arc::new(SurfaceShape::Nurbs(patch.surface))),
            )?;
            let mut n = self.current(id).cloned().expect("just added");
            n.parent = Some(group);
            self.set(n);
        }
        if keep_cage {
            cage.visible = false;
            self.set(cage);
        } else {
            let children: Vec<_> = self.doc.children(cage.id).map(|n| n.id).collect();
            for child in children {
                if let Some(mut c) = self.current(child).cloned() {
                    c.parent = Some(group);
                    self.set(c);
                }
            }
            self.remove(cage.id);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::{Command, NodeContent, Session};

    fn run(session: &mut Session, text: &str) -> Result<(), crate::CommandError> {
        let cmds: Vec<Command> =
            crate::script::parse(&format!("[{text}]"), std::path::Path::new("test"))
                .expect("a command");
        session.execute(&cmds[0]).map(|_| ())
    }

    fn smooth_cube(session: &mut Session, name: &str) {
        run(
            session,
            &format!("AddPrimitive(primitive: Cube(size: 2.0), name: \"{name}\")"),
        )
        .unwrap();
        run(
            session,
            &format!("SetSubdivision(nodes: [Name(\"{name}\")], modifier: Some(()))"),
        )
        .unwrap();
    }

    #[test]
    fn a_cage_becomes_a_group_of_surfaces_in_one_undo_step() {
        let mut s = Session::new();
        smooth_cube(&mut s, "Box");
        let before = s.doc.nodes.len();
        run(
            &mut s,
            "ConvertSubdivisionToNurbs(node: Name(\"Box\"), tolerance: 1e-3)",
        )
        .unwrap();
        let group = s.doc.find_by_name("Box NURBS").unwrap();
        let patches: Vec<_> = s.doc.children(group.id).collect();
        // Level 2 (7 packed rectangles: bands of regular faces run around
        // the cube) with the corners at level 3 (level 2 is within 1e-3 of
        // the size but its normals are 0.6° apart): 24 approximated corner
        // faces and 3 exact rectangles of the ring around each corner.
        assert_eq!(patches.len(), 7 + 8 * 3 + 24);
        assert!(
            patches
                .iter()
                .all(|n| matches!(n.content, NodeContent::Surface(_)))
        );
        assert!(!s.doc.find_by_name("Box").unwrap().visible);
        // The undo step's label carries the conversion's figures.
        let label = s.undo().unwrap();
        assert!(
            label.starts_with(
                "Convert to NURBS (55 NURBS patches (31 exact, 24 approximated; levels 2–3)"
            ),
            "{label}"
        );
        assert_eq!(s.doc.nodes.len(), before);
        assert!(s.doc.find_by_name("Box").unwrap().visible);
    }

    #[test]
    fn deleting_the_cage_moves_its_children_to_the_group() {
        let mut s = Session::new();
        smooth_cube(&mut s, "Box");
        run(&mut s, "AddEmpty(name: \"Handle\", parent: Name(\"Box\"))").unwrap();
        run(
            &mut s,
            "ConvertSubdivisionToNurbs(node: Name(\"Box\"), tolerance: 1e-3, keep_cage: false)",
        )
        .unwrap();
        assert!(s.doc.find_by_name("Box").is_none());
        let group = s.doc.find_by_name("Box NURBS").unwrap().id;
        assert_eq!(s.doc.find_by_name("Handle").unwrap().parent, Some(group));
    }

    #[test]
    fn the_conversion_is_available_without_a_command() {
        let mut s = Session::new();
        smooth_cube(&mut s, "Box");
        let NodeContent::Mesh(content) = &s.doc.find_by_name("Box").unwrap().content else {
            panic!("a mesh");
        };
        let c = content
            .limit_nurbs(crate::command::DEFAULT_NURBS_TOLERANCE, "Box")
            .unwrap();
        assert!(c.report.max_distance > 0.0);
        // Level 2, the eight corners' stars refined once more on their own.
        assert_eq!((c.level, c.deepest_level, c.counts()), (2, 3, (31, 24)));
        assert_eq!(c.sides(0).len(), 4);
    }

    #[test]
    fn refusals_name_their_reason() {
        let mut s = Session::new();
        run(
            &mut s,
            "AddPrimitive(primitive: Cube(size: 2.0), name: \"Plain\")",
        )
        .unwrap();
        run(&mut s, "AddEmpty(name: \"Nothing\")").unwrap();
        let err = |s: &mut Session, node: &str| {
            run(
                s,
                &format!("ConvertSubdivisionToNurbs(node: Name(\"{node}\"))"),
            )
            .unwrap_err()
            .to_string()
        };
        assert!(err(&mut s, "Plain").ends_with("has no subdivision modifier to convert"));
        assert!(err(&mut s, "Nothing").ends_with("is not a mesh"));
        run(
            &mut s,
            "SetSubdivision(nodes: [Name(\"Plain\")], modifier: Some((options: (scheme: DooSabin))))",
        )
        .unwrap();
        assert!(
            err(&mut s, "Plain")
                .ends_with("only Catmull-Clark surfaces convert to NURBS, not Doo-Sabin")
        );
        let bad = run(
            &mut s,
            "ConvertSubdivisionToNurbs(node: Name(\"Plain\"), tolerance: -1.0)",
        )
        .unwrap_err();
        assert_eq!(
            bad.to_string(),
            "the tolerance must be a positive fraction of the size, not -1"
        );
    }
}
