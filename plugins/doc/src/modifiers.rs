//! A mesh node's modifier stack (Blender's modifier stack): the Mirror
//! and Array modifiers, evaluated in order on the cage, and where the
//! subdivision modifier runs among them
//! ([`SubdivisionModifier::stack_position`](crate::SubdivisionModifier::stack_position)). The cage stays what the user
//! edits; [`MeshContent::evaluated`] is what export, `hedra info` and the
//! viewport show.
//!
//! What follows the cage through the stack: creases are carried to every
//! copy (each copied edge and vertex gets its source's sharpness, through
//! [`CopiedMesh`]), so a subdivision after a mirror is as sharp on both
//! halves. Corner attributes (UVs, custom normals) are not part of the
//! evaluated mesh; [`Command::ApplyModifiers`](crate::Command::ApplyModifiers)
//! carries the UVs of every corner to its copies (normals are dropped, as
//! after any edit).

use crate::scene::{CornerAttributes, MeshContent};
use glam::DVec3;
use hedra_geom::modeling::{
    ArrayOffset, CopiedMesh, MAX_ARRAY_COUNT, MirrorAxis, ModelingError, arrayed_copies,
    mirrored_copies,
};
use hedra_geom::subdivision::{Creases, Refiner, SubdivisionError};
use hedra_geom::{HalfEdgeId, HalfEdgeMesh};
use serde::{Deserialize, Serialize};
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::fmt;
use std::sync::Arc;

/// One modifier of a mesh node's stack.
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum MeshModifier {
    /// Mirror copies across the node's local planes (Blender's Mirror).
    Mirror(MirrorModifier),
    /// Copies in a row (Blender's Array).
    Array(ArrayModifier),
}

impl MeshModifier {
    /// The modifier's kind as the user sees it: `"Mirror"` or `"Array"`.
    pub fn name(&self) -> &'static str {
        match self {
            MeshModifier::Mirror(_) => "Mirror",
            MeshModifier::Array(_) => "Array",
        }
    }

    /// A one-line description for listings (`hedra info`).
    pub fn summary(&self) -> String {
        match self {
            MeshModifier::Mirror(m) => {
                let axes: String = MirrorAxis::ALL
                    .iter()
                    .filter(|a| m.axes[a.index()])
                    .map(|a| format!("{a:?}"))
                    .collect();
                let axes = if axes.is_empty() { "none".into() } else { axes };
                format!(
                    "Mirror {axes}{}{}",
                    if m.merge {
                        format!(", merge {}", m.merge_distance)
                    } else {
                        String::new()
                    },
                    if m.clipping { ", clipping" } else { "" }
                )
            }
            MeshModifier::Array(a) => {
                let v = |v: DVec3| format!("({}, {}, {})", v.x, v.y, v.z);
                let mut s = format!("Array ×{}", a.count);
                if let Some(r) = a.relative_offset {
                    s += &format!(", relative {}", v(r));
                }
                if let Some(c) = a.constant_offset {
                    s += &format!(", constant {}", v(c));
                }
                if a.merge {
                    s += &format!(", merge {}", a.merge_distance);
                }
                s
            }
        }
    }

    /// Checks the values a stored or commanded modifier carries.
    ///
    /// # Errors
    /// The first [`ModifierProblem`] found.
    pub fn check(&self) -> Result<(), ModifierProblem> {
        let distance = |merge: bool, d: f64| {
            if merge && !(d.is_finite() && d >= 0.0) {
                Err(ModifierProblem::MergeDistance(d))
            } else {
                Ok(())
            }
        };
        match self {
            MeshModifier::Mirror(m) => distance(m.merge, m.merge_distance),
            MeshModifier::Array(a) => {
                if a.count == 0 || a.count > MAX_ARRAY_COUNT {
                    return Err(ModifierProblem::Count(a.count));
                }
                let finite = |v: Option<DVec3>| v.is_none_or(|v| v.is_finite());
                if !finite(a.relative_offset) || !finite(a.constant_offset) {
                    return Err(ModifierProblem::Offset);
                }
                distance(a.merge, a.merge_distance)
            }
        }
    }

    /// The modifier applied to `mesh`, with where each result element came
    /// from.
    ///
    /// # Errors
    /// The kernel's [`ModelingError`] (a count of 0, a merge that is not
    /// manifold, a mesh without faces).
    pub fn apply(&self, mesh: &HalfEdgeMesh) -> Result<CopiedMesh, ModelingError> {
        match self {
            MeshModifier::Mirror(m) => {
                mirrored_copies(mesh, m.axes, m.merge.then_some(m.merge_distance))
            }
            MeshModifier::Array(a) => arrayed_copies(
                mesh,
                a.count,
                ArrayOffset {
                    relative: a.relative_offset,
                    constant: a.constant_offset,
                },
                a.merge.then_some(a.merge_distance),
            ),
        }
    }
}

/// Blender's Mirror modifier: the mesh and its mirror images across the
/// planes x = 0, y = 0, z = 0 of the node's local space (its origin), for
/// each axis set, applied X, then Y, then Z (up to 8 copies); see
/// [`hedra_geom::modeling::mirrored`].
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MirrorModifier {
    /// Mirror across x = 0, y = 0, z = 0 (default: X only, as Blender).
    #[serde(default = "x_only")]
    pub axes: [bool; 3],
    /// Weld vertices within `merge_distance` of a mirror plane to their
    /// images (default on, as Blender).
    #[serde(default = "crate::scene::yes")]
    pub merge: bool,
    /// How close to the plane a vertex is welded and clipped (default
    /// 0.001, Blender's).
    #[serde(default = "mirror_distance")]
    pub merge_distance: f64,
    /// Keep vertices on the mirror plane while dragging them (Blender's
    /// Clipping). Only stored here: the GUI calls [`MirrorModifier::clip`]
    /// on each dragged vertex.
    #[serde(default)]
    pub clipping: bool,
}

fn x_only() -> [bool; 3] {
    [true, false, false]
}
fn mirror_distance() -> f64 {
    0.001
}

impl Default for MirrorModifier {
    fn default() -> Self {
        MirrorModifier {
            axes: x_only(),
            merge: true,
            merge_distance: mirror_distance(),
            clipping: false,
        }
    }
}

impl MirrorModifier {
    /// Where a vertex dragged from `before` to `after` (local space) goes
    /// with clipping on (Blender's Clipping): for each mirror axis, a vertex
    /// that was within `merge_distance` of the plane stays on it, and one
    /// that would cross the plane stops on it. With clipping off, `after`.
    pub fn clip(&self, before: DVec3, after: DVec3) -> DVec3 {
        if !self.clipping {
            return after;
        }
        let mut p = after;
        for i in (0..3).filter(|&i| self.axes[i]) {
            let on_plane = before[i].abs() <= self.merge_distance;
            let crossed = before[i] * after[i] < 0.0;
            if on_plane || crossed {
                p[i] = 0.0;
            }
        }
        p
    }
}

/// Blender's Array modifier with a fixed count: `count` copies, each moved
/// by `relative_offset × bounding box size + constant_offset` from the
/// previous one; see [`hedra_geom::modeling::arrayed`].
#[derive(Copy, Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ArrayModifier {
    /// Number of copies including the original, at least 1 (default 2).
    #[serde(default = "two_copies")]
    pub count: u32,
    /// Offset per copy as a factor of the bounding box size (default
    /// `(1, 0, 0)`, Blender's); `None`: off.
    #[serde(default = "along_x")]
    pub relative_offset: Option<DVec3>,
    /// Offset per copy in local units, added (default off).
    #[serde(default)]
    pub constant_offset: Option<DVec3>,
    /// Weld vertices of neighbouring copies within `merge_distance`
    /// (default off, as Blender).
    #[serde(default)]
    pub merge: bool,
    /// The merge distance (default 0.01, Blender's).
    #[serde(default = "array_distance")]
    pub merge_distance: f64,
}

fn two_copies() -> u32 {
    2
}
fn along_x() -> Option<DVec3> {
    Some(DVec3::X)
}
fn array_distance() -> f64 {
    0.01
}

impl Default for ArrayModifier {
    fn default() -> Self {
        ArrayModifier {
            count: two_copies(),
            relative_offset: along_x(),
            constant_offset: None,
            merge: false,
            merge_distance: array_distance(),
        }
    }
}

/// A modifier value out of range (refused by the modifier commands and
/// when loading a file).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ModifierProblem {
    /// An array count of 0 or above [`MAX_ARRAY_COUNT`].
    #[error("array count must be between 1 and {MAX_ARRAY_COUNT}, got {0}")]
    Count(u32),
    /// A merge distance that is negative or not finite.
    #[error("merge distance must be a finite distance ≥ 0, got {0}")]
    MergeDistance(f64),
    /// An array offset with an infinite or NaN component.
    #[error("array offset is not finite")]
    Offset,
}

/// Why a node's stack could not be evaluated.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EvaluationError {
    /// A stack modifier refused (numbered from 1, as the properties panel
    /// lists them).
    #[error("modifier {} ({name}): {error}", index + 1)]
    Modifier {
        /// The modifier's index in the stack, from 0.
        index: usize,
        /// Its kind, `"Mirror"` or `"Array"`.
        name: &'static str,
        /// The kernel's reason.
        error: ModelingError,
    },
    /// The subdivision modifier refused (its message as it is).
    #[error(transparent)]
    Subdivision(#[from] SubdivisionError),
}

/// A node's mesh with some or all of its stack applied, and the creases
/// that go with it.
#[derive(Clone, Debug)]
pub struct Evaluated<'a> {
    /// The mesh (the cage itself, borrowed, when nothing changed it).
    pub mesh: Cow<'a, HalfEdgeMesh>,
    /// Its creases.
    pub creases: Cow<'a, Creases>,
}

impl MeshContent {
    /// True when the node has Mirror or Array modifiers, so that what it
    /// shows is not the cage (or its subdivision) alone. The app's smooth
    /// preview refines [`smooth_cage`](Self::smooth_cage) then, not the
    /// cage.
    pub fn has_stack_modifiers(&self) -> bool {
        !self.modifiers.is_empty()
    }

    /// How many stack modifiers run before subdivision (the subdivision
    /// modifier's [`stack_position`](crate::SubdivisionModifier::stack_position),
    /// clamped to the stack; all of them by default).
    pub fn subdivision_position(&self) -> usize {
        self.subdivision
            .and_then(|s| s.stack_position)
            .unwrap_or(usize::MAX)
            .min(self.modifiers.len())
    }

    /// The first `count` stack modifiers applied to the cage, with the
    /// creases carried along.
    ///
    /// # Errors
    /// [`EvaluationError::Modifier`] naming the modifier that refused.
    pub fn apply_stack(&self, count: usize) -> Result<Evaluated<'_>, EvaluationError> {
        self.run_stack(
            &self.modifiers[..count.min(self.modifiers.len())],
            0,
            self.start(),
        )
    }

    fn start(&self) -> Evaluated<'_> {
        Evaluated {
            mesh: Cow::Borrowed(&self.mesh),
            creases: Cow::Borrowed(&self.creases),
        }
    }

    fn run_stack<'a>(
        &self,
        modifiers: &[MeshModifier],
        first_index: usize,
        mut current: Evaluated<'a>,
    ) -> Result<Evaluated<'a>, EvaluationError> {
        for (k, m) in modifiers.iter().enumerate() {
            let copies = m
                .apply(&current.mesh)
                .map_err(|error| EvaluationError::Modifier {
                    index: first_index + k,
                    name: m.name(),
                    error,
                })?;
            let creases = copies.creases(&current.mesh, &current.creases);
            current = Evaluated {
                mesh: Cow::Owned(copies.mesh),
                creases: Cow::Owned(creases),
            };
        }
        Ok(current)
    }

    /// The node's final mesh with subdivision at `level` (0: no
    /// subdivision): the stack modifiers in order, with subdivision (the
    /// modifier's options, else Catmull-Clark) at its place in the stack.
    /// Without stack modifiers and at level 0 this is the cage itself,
    /// borrowed. Export, `hedra info` and the viewport show this.
    ///
    /// # Errors
    /// [`EvaluationError`] naming the modifier or the subdivision that
    /// refused.
    pub fn evaluated(&self, level: u32) -> Result<Cow<'_, HalfEdgeMesh>, EvaluationError> {
        self.evaluate(level).map(|e| e.mesh)
    }

    /// [`evaluated`](Self::evaluated) with the creases of the result.
    ///
    /// # Errors
    /// As [`evaluated`](Self::evaluated).
    pub fn evaluate(&self, level: u32) -> Result<Evaluated<'_>, EvaluationError> {
        let split = self.subdivision_position();
        let before = self.run_stack(&self.modifiers[..split], 0, self.start())?;
        let smooth = if level == 0 {
            before
        } else {
            let options = self.subdivision.unwrap_or_default().options;
            let (mesh, creases) =
                Refiner::subdivide(&before.mesh, &before.creases, options, level)?;
            Evaluated {
                mesh: Cow::Owned(mesh),
                creases: Cow::Owned(creases),
            }
        };
        self.run_stack(&self.modifiers[split..], split, smooth)
    }

    /// What the viewport's smooth preview (the kept stencil refinement,
    /// [`SmoothRefinement`](crate::smooth::SmoothRefinement)) should refine:
    /// with subdivision last in the stack (the default), the cage with the
    /// stack applied and its creases (the cage itself without stack
    /// modifiers). `None` when a stack modifier comes after subdivision:
    /// then the app draws [`evaluated`](Self::evaluated) at the viewport
    /// level and keeps no stencils.
    ///
    /// # Errors
    /// [`EvaluationError::Modifier`] naming the modifier that refused.
    pub fn smooth_cage(&self) -> Result<Option<Evaluated<'_>>, EvaluationError> {
        if self.subdivision_position() < self.modifiers.len() {
            return Ok(None);
        }
        self.apply_stack(self.modifiers.len()).map(Some)
    }

    /// The content with its first `count` stack modifiers applied, as
    /// [`Command::ApplyModifiers`](crate::Command::ApplyModifiers) makes it:
    /// their result becomes the cage (creases carried to every copy, UVs to
    /// every copied corner; custom normals and the primitive dropped) and
    /// they leave the stack. Subdivision stays a modifier after the same
    /// remaining modifiers. The caller checks that subdivision does not
    /// come before any of the applied ones.
    ///
    /// # Errors
    /// [`EvaluationError::Modifier`] naming the modifier that refused.
    pub fn with_modifiers_applied(&self, count: usize) -> Result<MeshContent, EvaluationError> {
        let count = count.min(self.modifiers.len());
        let mut out = self.clone();
        for (index, m) in self.modifiers[..count].iter().enumerate() {
            let copies = m
                .apply(&out.mesh)
                .map_err(|error| EvaluationError::Modifier {
                    index,
                    name: m.name(),
                    error,
                })?;
            out.creases = copies.creases(&out.mesh, &out.creases);
            out.corners = carried_uvs(&copies, &out.mesh, &out.corners);
            out.mesh = Arc::new(copies.mesh);
        }
        if count > 0 {
            out.primitive = None;
        }
        out.modifiers.drain(..count);
        if let Some(s) = &mut out.subdivision
            && let Some(p) = &mut s.stack_position
        {
            *p = p.saturating_sub(count);
        }
        Ok(out)
    }
}

/// The UVs of `source`'s corners on their copies in `copies` (custom
/// normals are dropped).
fn carried_uvs(
    copies: &CopiedMesh,
    source: &HalfEdgeMesh,
    corners: &CornerAttributes,
) -> CornerAttributes {
    if corners.uvs.is_empty() {
        return CornerAttributes::default();
    }
    let mut uvs: BTreeMap<HalfEdgeId, glam::DVec2> = BTreeMap::new();
    for h in copies.mesh.halfedges() {
        if let Some(uv) = copies
            .corner_source(source, h)
            .and_then(|s| corners.uvs.get(&s))
        {
            uvs.insert(h, *uv);
        }
    }
    CornerAttributes {
        uvs: Arc::new(uvs),
        normals: Arc::default(),
    }
}

impl fmt::Display for MeshModifier {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.summary())
    }
}
