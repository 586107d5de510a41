//! Nodes that remember their inputs (Rhino's record history): a surface or
//! mesh node made from curve nodes by extrusion, revolution, sweep,
//! two-rail sweep, loft, a Coons patch or a Gordon surface keeps a
//! [`Construction`] naming its input nodes and parameters, and is made
//! again whenever an input changes.
//!
//! - The result is evaluated in world terms: each input curve is taken
//!   through its node's world matrix, so the result lands where its inputs
//!   are. The geometry is stored in the result node's local space as those
//!   world coordinates: a result made at the top level with the identity
//!   transform (what [`Command::MakeFromCurves`](crate::Command::MakeFromCurves)
//!   makes) sits exactly on its inputs; its own transform, if the user
//!   gives it one, moves it from there.
//! - Every command that changes an input node (its curve, its transform or
//!   an ancestor's) re-makes the dependents in the same transaction, so one
//!   undo puts both back. A re-make that fails refuses the command, naming
//!   the dependent ([`CommandError::Construction`](crate::CommandError::Construction)).
//! - Deleting an input freezes its dependents (they keep their geometry
//!   and lose the construction; the step's label says so). Editing a
//!   result's geometry directly (moving its control points or vertices, any
//!   mesh operation) freezes it too; its transform, shading, modifiers and
//!   name do not. [`Command::ApplyConstruction`](crate::Command::ApplyConstruction)
//!   freezes on request.
//! - While the app drags an input's points without a command,
//!   [`Document::remade_dependents`] gives the re-made contents to draw.

use crate::scene::{Document, MeshContent, Node, NodeContent, NodeId, SurfaceShape};
use glam::{DMat4, DVec3};
use hedra_geom::HalfEdgeMesh;
use hedra_geom::curves::NurbsCurve;
use hedra_geom::surfaces::NurbsSurface;
use hedra_geom::surfaces::patches::{self, CoonsBoundaries, PatchError};
use hedra_geom::surfaces::sweeps::{
    self, Axis, FrameKind, LoftOptions, SweepError, SweepOptions, Tightness,
};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// In which space a construction's axis or direction is given.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Space {
    /// In the profile node's local space: the axis or direction moves,
    /// turns and scales with the profile (the default).
    #[default]
    Profile,
    /// In world space: the axis or direction stays where it is when the
    /// profile moves.
    World,
}

/// What a construction makes from its input curves. `N` names the input
/// nodes: [`NodeId`] on a node, [`NodeRef`](crate::NodeRef) in a command.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Recipe<N> {
    /// The profile moved along a vector (seed 004's extrusion).
    Extrude {
        /// The profile curve node.
        profile: N,
        /// The extrusion vector, length included.
        direction: DVec3,
        /// Where `direction` is given (default: the profile's space).
        #[serde(default, skip_serializing_if = "is_default")]
        space: Space,
        /// Caps on both ends (closed planar profiles): n-gons on a mesh,
        /// flat NURBS cap nodes beside a surface.
        #[serde(default, skip_serializing_if = "is_default")]
        caps: bool,
    },
    /// The profile turned about an axis (Blender's Spin; Screw with a pitch).
    Revolve {
        /// The profile curve node.
        profile: N,
        /// A point of the axis (default: the origin of `space`).
        #[serde(default, skip_serializing_if = "is_default")]
        origin: DVec3,
        /// The axis direction (default +Y); the turn is right-handed about it.
        #[serde(default = "y_axis")]
        axis: DVec3,
        /// The angle in degrees, ±360 at most without a pitch (default 360).
        #[serde(default = "full_turn")]
        degrees: f64,
        /// Rise along the axis per full turn (default 0: a plain revolution).
        #[serde(default, skip_serializing_if = "is_default")]
        pitch: f64,
        /// Where `origin` and `axis` are given (default: the profile's space).
        #[serde(default, skip_serializing_if = "is_default")]
        space: Space,
        /// Caps at both ends of a partial turn (closed planar profiles):
        /// n-gons on a mesh, flat NURBS cap nodes beside a surface.
        #[serde(default, skip_serializing_if = "is_default")]
        caps: bool,
    },
    /// The profile carried along a rail (Rhino's Sweep1).
    Sweep {
        /// The profile curve node, placed as it should be at the rail's start.
        profile: N,
        /// The rail curve node.
        rail: N,
        /// `RotationMinimizing` (default) or `Frenet`.
        #[serde(default, skip_serializing_if = "is_default")]
        frame: FrameKind,
        /// Copies of the profile placed along the rail and skinned (default 24).
        #[serde(default = "stations")]
        stations: u32,
        /// Caps on both ends (closed planar profiles): n-gons on a mesh,
        /// flat NURBS cap nodes beside a surface.
        #[serde(default, skip_serializing_if = "is_default")]
        caps: bool,
    },
    /// The profile carried along two rails, its ends on them (Rhino's Sweep2).
    Sweep2 {
        /// The profile curve node, its ends on the rails' starts.
        profile: N,
        /// The two rail curve nodes.
        rails: (N, N),
        /// Copies of the profile placed along the rails (default 24).
        #[serde(default = "stations")]
        stations: u32,
        /// Caps on both ends (closed planar profiles): n-gons on a mesh,
        /// flat NURBS cap nodes beside a surface.
        #[serde(default, skip_serializing_if = "is_default")]
        caps: bool,
    },
    /// A surface through ordered section curves.
    Loft {
        /// The section curve nodes, in order (at least 2; 3 closed).
        sections: Vec<N>,
        /// The last section joins back to the first.
        #[serde(default, skip_serializing_if = "is_default")]
        closed: bool,
        /// `Straight`, `Loose` or `Normal` (default).
        #[serde(default, skip_serializing_if = "is_default")]
        tightness: Tightness,
        /// Caps on the first and last section (open lofts): n-gons on a
        /// mesh, flat NURBS cap nodes beside a surface.
        #[serde(default, skip_serializing_if = "is_default")]
        caps: bool,
    },
    /// The bilinearly blended Coons patch bounded by four curves (Rhino's
    /// EdgeSrf; seed 003's bilinear patch subtracted from two ruled
    /// surfaces), exact NURBS: its four sides are the curves.
    Coons {
        /// The four boundary curve nodes, in any order and any direction,
        /// as long as their ends close one loop within [`PATCH_TOLERANCE`]
        /// ([`CoonsBoundaries::from_loop`]): the first runs along u at
        /// v = 0 in its own direction.
        boundaries: [N; 4],
    },
    /// The Gordon surface through a network of curves (Rhino's
    /// NetworkSrf): every u-curve crosses every v-curve; the crossings are
    /// found, the curves ordered and turned as the surface needs.
    Gordon {
        /// The curves running in u (at least 2), in any order.
        u_curves: Vec<N>,
        /// The curves running in v (at least 2), in any order.
        v_curves: Vec<N>,
    },
}

/// How far apart (in world units) the ends of Coons boundaries and the
/// crossings of a Gordon network may be: curves meant to meet should meet
/// exactly (snapped), this only absorbs rounding.
pub const PATCH_TOLERANCE: f64 = 1e-6;

fn is_default<T: Default + PartialEq>(value: &T) -> bool {
    *value == T::default()
}
fn y_axis() -> DVec3 {
    DVec3::Y
}
fn full_turn() -> f64 {
    360.0
}
fn stations() -> u32 {
    24
}

/// What a construction's node holds.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Output {
    /// A NURBS surface node (exact where the kernel's construction is).
    #[default]
    Nurbs,
    /// One of the flat NURBS caps closing the ends of the recipe's NURBS
    /// surface ([`sweeps::end_caps`]): the node is a child of the surface's
    /// node, made with it when its recipe asks for caps.
    Cap {
        /// Which end it closes.
        end: CapEnd,
    },
    /// A polygon mesh node of quads (n-gon caps).
    Mesh {
        /// Segments along the sweep (around a revolution, along an
        /// extrusion, a rail, across a loft).
        segments: u32,
        /// Segments along the profile (a polyline profile keeps its own
        /// corners instead).
        profile_segments: u32,
    },
}

/// The end of a swept surface a cap closes.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum CapEnd {
    /// Where the sweep starts (the profile itself for an extrusion).
    Start,
    /// Where it ends.
    End,
}

/// A node's record of how it was made: the recipe with its input nodes,
/// and the output kind.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Construction<N = NodeId> {
    /// What is made, from which curves.
    pub recipe: Recipe<N>,
    /// A NURBS surface (default) or a mesh.
    #[serde(default, skip_serializing_if = "is_default")]
    pub output: Output,
}

/// Why a construction cannot be (re)made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ConstructionError {
    /// An input node does not exist (any more).
    #[error("input {input} does not exist")]
    MissingInput {
        /// The missing node.
        input: NodeId,
    },
    /// An input node is not a curve.
    #[error("input {input} is not a curve")]
    NotACurve {
        /// The node.
        input: NodeId,
    },
    /// Coons boundaries that do not close a loop: the end of `first` is
    /// `gap` from the nearest end of any other boundary, `second`'s.
    #[error("Coons: the boundaries {first} and {second} miss each other by {gap} at a corner")]
    CoonsGap {
        /// The boundary whose end is farthest from any other's, as `'name'`.
        first: String,
        /// The boundary with the nearest end to it, as `'name'`.
        second: String,
        /// The distance between the two ends.
        gap: f64,
    },
    /// A u-curve and a v-curve of a Gordon network that do not cross.
    #[error(
        "Gordon: the u-curve {u_curve} and the v-curve {v_curve} do not meet: they pass {distance} apart"
    )]
    GordonMiss {
        /// The u-curve, as `'name'`.
        u_curve: String,
        /// The v-curve, as `'name'`.
        v_curve: String,
        /// Their least distance.
        distance: f64,
    },
    /// The kernel refused a Coons patch or a Gordon surface.
    #[error("{recipe}: {error}")]
    Patch {
        /// `"Coons"` or `"Gordon"`.
        recipe: &'static str,
        /// The kernel's reason.
        error: PatchError,
    },
    /// A cap asked of a surface that closes on itself (a full turn, a
    /// sweep around a closed rail, a closed loft): it has no ends.
    #[error("the surface closes on itself: it has no ends to cap")]
    NoEnds,
    /// The same node given as two inputs where that makes no sense (a
    /// profile that is its own rail).
    #[error("input {input} is used twice")]
    SameInput {
        /// The node.
        input: NodeId,
    },
    /// The kernel refused.
    #[error(transparent)]
    Sweep(#[from] SweepError),
}

impl<N> Recipe<N> {
    /// The recipe's name as the history and `hedra info` show it.
    pub fn name(&self) -> &'static str {
        match self {
            Recipe::Extrude { .. } => "Extrude",
            Recipe::Revolve { pitch, .. } if *pitch != 0.0 => "Screw",
            Recipe::Revolve { .. } => "Revolve",
            Recipe::Sweep { .. } => "Sweep",
            Recipe::Sweep2 { .. } => "Sweep2",
            Recipe::Loft { .. } => "Loft",
            Recipe::Coons { .. } => "Coons",
            Recipe::Gordon { .. } => "Gordon",
        }
    }

    /// The input nodes, profile first (then rails, or the sections in
    /// order; a Coons patch's boundaries, a Gordon network's u-curves then
    /// v-curves).
    pub fn inputs(&self) -> Vec<&N> {
        match self {
            Recipe::Extrude { profile, .. } | Recipe::Revolve { profile, .. } => vec![profile],
            Recipe::Sweep { profile, rail, .. } => vec![profile, rail],
            Recipe::Sweep2 {
                profile,
                rails: (a, b),
                ..
            } => vec![profile, a, b],
            Recipe::Loft { sections, .. } => sections.iter().collect(),
            Recipe::Coons { boundaries } => boundaries.iter().collect(),
            Recipe::Gordon { u_curves, v_curves } => u_curves.iter().chain(v_curves).collect(),
        }
    }

    /// The parametric direction the recipe's NURBS surface is swept along
    /// (where its ends are): u for a revolution, v for the others.
    pub fn along(&self) -> sweeps::Along {
        match self {
            Recipe::Revolve { .. } => sweeps::Along::U,
            _ => sweeps::Along::V,
        }
    }

    /// True when the recipe asks for caps on its ends.
    pub fn caps(&self) -> bool {
        match self {
            Recipe::Extrude { caps, .. }
            | Recipe::Revolve { caps, .. }
            | Recipe::Sweep { caps, .. }
            | Recipe::Sweep2 { caps, .. }
            | Recipe::Loft { caps, .. } => *caps,
            Recipe::Coons { .. } | Recipe::Gordon { .. } => false,
        }
    }
}

impl<N: Clone> Construction<N> {
    /// The same construction with its inputs renamed by `f` (resolving a
    /// command's `NodeRef`s to `NodeId`s, say); the first error stops it.
    ///
    /// # Errors
    /// `f`'s.
    pub fn map_inputs<M, E>(
        &self,
        mut f: impl FnMut(&N) -> Result<M, E>,
    ) -> Result<Construction<M>, E> {
        let recipe = match &self.recipe {
            Recipe::Extrude {
                profile,
                direction,
                space,
                caps,
            } => Recipe::Extrude {
                profile: f(profile)?,
                direction: *direction,
                space: *space,
                caps: *caps,
            },
            Recipe::Revolve {
                profile,
                origin,
                axis,
                degrees,
                pitch,
                space,
                caps,
            } => Recipe::Revolve {
                profile: f(profile)?,
                origin: *origin,
                axis: *axis,
                degrees: *degrees,
                pitch: *pitch,
                space: *space,
                caps: *caps,
            },
            Recipe::Sweep {
                profile,
                rail,
                frame,
                stations,
                caps,
            } => Recipe::Sweep {
                profile: f(profile)?,
                rail: f(rail)?,
                frame: *frame,
                stations: *stations,
                caps: *caps,
            },
            Recipe::Sweep2 {
                profile,
                rails: (a, b),
                stations,
                caps,
            } => Recipe::Sweep2 {
                profile: f(profile)?,
                rails: (f(a)?, f(b)?),
                stations: *stations,
                caps: *caps,
            },
            Recipe::Loft {
                sections,
                closed,
                tightness,
                caps,
            } => Recipe::Loft {
                sections: sections.iter().map(&mut f).collect::<Result<_, E>>()?,
                closed: *closed,
                tightness: *tightness,
                caps: *caps,
            },
            Recipe::Coons {
                boundaries: [a, b, c, d],
            } => Recipe::Coons {
                boundaries: [f(a)?, f(b)?, f(c)?, f(d)?],
            },
            Recipe::Gordon { u_curves, v_curves } => Recipe::Gordon {
                u_curves: u_curves.iter().map(&mut f).collect::<Result<_, E>>()?,
                v_curves: v_curves.iter().map(&mut f).collect::<Result<_, E>>()?,
            },
        };
        Ok(Construction {
            recipe,
            output: self.output,
        })
    }
}

/// What a construction makes.
#[derive(Clone, Debug, PartialEq)]
pub enum Made {
    /// A NURBS surface, in world coordinates.
    Surface(NurbsSurface),
    /// A polygon mesh, in world coordinates.
    Mesh(HalfEdgeMesh),
}

/// An input curve in world coordinates with its node's world matrix.
pub struct Input {
    /// The node's world matrix.
    pub world: DMat4,
    /// The curve's NURBS form in the node's local space.
    pub curve: Arc<NurbsCurve>,
    /// The node's name (errors name their inputs with it).
    pub name: String,
}

impl Construction<NodeId> {
    /// Makes the result from its inputs, looked up by `input` (`None`: the
    /// node is missing; `Some(None)`: it is not a curve).
    ///
    /// # Errors
    /// A [`ConstructionError`] naming the input or the kernel's reason.
    pub fn make(
        &self,
        input: &dyn Fn(NodeId) -> Option<Option<Input>>,
    ) -> Result<Made, ConstructionError> {
        let named = |id: NodeId| -> Result<(NurbsCurve, DMat4, String), ConstructionError> {
            let found = input(id).ok_or(ConstructionError::MissingInput { input: id })?;
            let Input { world, curve, name } =
                found.ok_or(ConstructionError::NotACurve { input: id })?;
            Ok((
                curve.transformed(&world).map_err(SweepError::from)?,
                world,
                name,
            ))
        };
        let fetch = |id: NodeId| named(id).map(|(c, w, _)| (c, w));
        let inputs = self.recipe.inputs();
        for (k, a) in inputs.iter().enumerate() {
            let twice = inputs[..k].contains(a);
            // A loft may pass the same section twice; a sweep's rails may not
            // be its profile.
            if twice && !matches!(self.recipe, Recipe::Loft { .. }) {
                return Err(ConstructionError::SameInput { input: **a });
            }
        }
        let mesh = match self.output {
            Output::Cap { end } => {
                let surface = Construction {
                    recipe: self.recipe.clone(),
                    output: Output::Nurbs,
                };
                let Made::Surface(s) = surface.make(input)? else {
                    unreachable!("NURBS output makes a surface")
                };
                let caps = sweeps::end_caps(&s, self.recipe.along())?;
                let k = if end == CapEnd::Start { 0 } else { 1 };
                return caps
                    .into_iter()
                    .nth(k)
                    .map(Made::Surface)
                    .ok_or(ConstructionError::NoEnds);
            }
            Output::Nurbs => None,
            Output::Mesh {
                segments,
                profile_segments,
            } => Some((segments, profile_segments)),
        };
        let made = match &self.recipe {
            Recipe::Extrude {
                profile,
                direction,
                space,
                caps,
            } => {
                let (curve, world) = fetch(*profile)?;
                let d = match space {
                    Space::Profile => world.transform_vector3(*direction),
                    Space::World => *direction,
                };
                match mesh {
                    None => Made::Surface(sweeps::extrude(&curve, d)?),
                    Some((n, m)) => Made::Mesh(sweeps::extrude_mesh(&curve, d, n, m, *caps)?),
                }
            }
            Recipe::Revolve {
                profile,
                origin,
                axis,
                degrees,
                pitch,
                space,
                caps,
            } => {
                let (curve, world) = fetch(*profile)?;
                let (origin, direction, pitch) = match space {
                    Space::Profile => {
                        let d = world.transform_vector3(*axis);
                        // The pitch scales with the axis.
                        let scale = d.length() / axis.length().max(1e-300);
                        (world.transform_point3(*origin), d, pitch * scale)
                    }
                    Space::World => (*origin, *axis, *pitch),
                };
                let axis = Axis { origin, direction };
                let angle = degrees.to_radians();
                match mesh {
                    None => Made::Surface(sweeps::revolve(&curve, axis, angle, pitch)?),
                    Some((n, m)) => Made::Mesh(sweeps::revolve_mesh(
                        &curve, axis, angle, pitch, n, m, *caps,
                    )?),
                }
            }
            Recipe::Sweep {
                profile,
                rail,
                frame,
                stations,
                caps,
            } => {
                let (p, _) = fetch(*profile)?;
                let (r, _) = fetch(*rail)?;
                let options = SweepOptions {
                    frame: *frame,
                    sections: *stations,
                };
                swept_output(sweeps::sweep(&p, &r, options)?, &p, mesh, *caps)?
            }
            Recipe::Sweep2 {
                profile,
                rails: (a, b),
                stations,
                caps,
            } => {
                let (p, _) = fetch(*profile)?;
                let (a, _) = fetch(*a)?;
                let (b, _) = fetch(*b)?;
                swept_output(sweeps::sweep2(&p, [&a, &b], *stations)?, &p, mesh, *caps)?
            }
            Recipe::Loft {
                sections,
                closed,
                tightness,
                caps,
            } => {
                let curves: Vec<NurbsCurve> = sections
                    .iter()
                    .map(|&s| fetch(s).map(|(c, _)| c))
                    .collect::<Result<_, _>>()?;
                let options = LoftOptions {
                    closed: *closed,
                    tightness: *tightness,
                };
                let surface = sweeps::loft(&curves, options)?;
                match mesh {
                    None => Made::Surface(surface),
                    Some((n, m)) => {
                        let caps = *caps && !*closed;
                        if caps {
                            sweeps::check_end_caps(&curves[0], &curves[curves.len() - 1])?;
                        }
                        let (us, closed_u) = sweeps::compatible_parameters(&curves[0], m);
                        Made::Mesh(sweeps::surface_mesh(
                            &surface, &us, closed_u, n, *closed, caps,
                        )?)
                    }
                }
            }
            Recipe::Coons { boundaries } => {
                let mut curves = Vec::with_capacity(4);
                let mut names = Vec::with_capacity(4);
                for &b in boundaries {
                    let (c, _, name) = named(b)?;
                    curves.push(c);
                    names.push(name);
                }
                let four: [NurbsCurve; 4] = curves.clone().try_into().expect("four boundaries");
                let patch = |error| ConstructionError::Patch {
                    recipe: "Coons",
                    error,
                };
                let loop_ =
                    CoonsBoundaries::from_loop(four, PATCH_TOLERANCE).map_err(|e| match e {
                        PatchError::NotALoop { .. } => coons_gap(&curves, &names),
                        other => patch(other),
                    })?;
                let surface = patches::coons(&loop_, PATCH_TOLERANCE).map_err(patch)?;
                patch_output(surface, mesh)?
            }
            Recipe::Gordon { u_curves, v_curves } => {
                let fetch_all =
                    |ids: &[NodeId]| -> Result<(Vec<NurbsCurve>, Vec<String>), ConstructionError> {
                        let mut curves = Vec::with_capacity(ids.len());
                        let mut names = Vec::with_capacity(ids.len());
                        for &id in ids {
                            let (c, _, name) = named(id)?;
                            curves.push(c);
                            names.push(name);
                        }
                        Ok((curves, names))
                    };
                let (us, u_names) = fetch_all(u_curves)?;
                let (vs, v_names) = fetch_all(v_curves)?;
                let g = patches::gordon(&us, &vs, None, PATCH_TOLERANCE).map_err(|e| match e {
                    PatchError::CurvesDoNotMeet {
                        u_curve,
                        v_curve,
                        distance,
                    } => ConstructionError::GordonMiss {
                        u_curve: format!("'{}'", u_names[u_curve]),
                        v_curve: format!("'{}'", v_names[v_curve]),
                        distance,
                    },
                    error => ConstructionError::Patch {
                        recipe: "Gordon",
                        error,
                    },
                })?;
                patch_output(g.surface, mesh)?
            }
        };
        Ok(made)
    }

    /// One line for `hedra info` and the history: the recipe, its inputs
    /// by name (through `name`) and its main parameters.
    pub fn summary(&self, name: &dyn Fn(NodeId) -> String) -> String {
        let inputs: Vec<String> = self.recipe.inputs().iter().map(|&&i| name(i)).collect();
        let output = match self.output {
            Output::Nurbs => "NURBS".to_string(),
            Output::Mesh {
                segments,
                profile_segments,
            } => format!("mesh {segments}×{profile_segments}"),
            Output::Cap { end: CapEnd::Start } => "NURBS cap at the start".to_string(),
            Output::Cap { end: CapEnd::End } => "NURBS cap at the end".to_string(),
        };
        let params = match &self.recipe {
            Recipe::Extrude { direction, .. } => format!("by {direction}"),
            Recipe::Revolve { degrees, pitch, .. } if *pitch != 0.0 => {
                format!("{degrees}°, pitch {pitch}")
            }
            Recipe::Revolve { degrees, .. } => format!("{degrees}°"),
            Recipe::Sweep {
                frame, stations, ..
            } => format!("{frame:?} frame, {stations} stations"),
            Recipe::Sweep2 { stations, .. } => format!("{stations} stations"),
            Recipe::Loft {
                closed, tightness, ..
            } => format!("{tightness:?}{}", if *closed { ", closed" } else { "" }),
            Recipe::Coons { .. } => "bilinearly blended".to_string(),
            Recipe::Gordon { u_curves, v_curves } => {
                format!("{} × {} curves", u_curves.len(), v_curves.len())
            }
        };
        let caps = if self.recipe.caps() { ", caps" } else { "" };
        format!(
            "{} of {} ({params}{caps}, {output})",
            self.recipe.name(),
            inputs.join(", ")
        )
    }
}

/// A sweep's NURBS surface, or its mesh: quads along the profile `p` (as
/// many as `mesh`'s profile segments) by its segments along the rail, with
/// end caps when asked (closed planar profiles).
fn swept_output(
    surface: NurbsSurface,
    p: &NurbsCurve,
    mesh: Option<(u32, u32)>,
    caps: bool,
) -> Result<Made, ConstructionError> {
    Ok(match mesh {
        None => Made::Surface(surface),
        Some((n, m)) => {
            // A sweep around a closed rail has no ends to cap.
            let closed_v = sweeps::is_closed_in_v(&surface);
            let caps = caps && !closed_v;
            if caps {
                sweeps::check_end_caps(p, p)?;
            }
            let (us, closed) = sweeps::compatible_parameters(p, m);
            Made::Mesh(sweeps::surface_mesh(
                &surface, &us, closed, n, closed_v, caps,
            )?)
        }
    })
}

/// A patch's NURBS surface, or its mesh: `profile_segments` quads along u,
/// `segments` along v, on the domain [0, 1]² the patches have.
fn patch_output(
    surface: NurbsSurface,
    mesh: Option<(u32, u32)>,
) -> Result<Made, ConstructionError> {
    Ok(match mesh {
        None => Made::Surface(surface),
        Some((n, m)) => {
            if m == 0 || m > sweeps::MAX_SEGMENTS {
                return Err(SweepError::Segments {
                    what: "profile segments",
                    min: 1,
                    got: m,
                }
                .into());
            }
            let us: Vec<f64> = (0..=m).map(|i| f64::from(i) / f64::from(m)).collect();
            Made::Mesh(sweeps::surface_mesh(&surface, &us, false, n, false, false)?)
        }
    })
}

/// Why four Coons boundaries do not close a loop, by name: the curve end
/// farthest from every other curve's ends, the curve with the nearest end
/// to it, and that distance. O(1).
fn coons_gap(curves: &[NurbsCurve], names: &[String]) -> ConstructionError {
    use hedra_geom::curves::Curve;
    let ends = |c: &NurbsCurve| {
        let (a, b) = c.domain();
        [c.point(a), c.point(b)]
    };
    let mut worst: Option<(f64, usize, usize)> = None;
    for (i, ci) in curves.iter().enumerate() {
        for p in ends(ci) {
            let mut nearest: Option<(f64, usize)> = None;
            for (j, cj) in curves.iter().enumerate() {
                if j == i {
                    continue;
                }
                for q in ends(cj) {
                    let d = p.distance(q);
                    if nearest.is_none_or(|(nd, _)| d < nd) {
                        nearest = Some((d, j));
                    }
                }
            }
            if let Some((d, j)) = nearest
                && worst.is_none_or(|(wd, _, _)| d > wd)
            {
                worst = Some((d, i, j));
            }
        }
    }
    let (gap, i, j) = worst.unwrap_or((f64::NAN, 0, 1));
    ConstructionError::CoonsGap {
        first: format!("'{}'", names[i]),
        second: format!("'{}'", names[j]),
        gap,
    }
}

/// The frames a sweep carries its profile in, for drawing and reporting.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepFrames {
    /// The frame at each station, world space.
    pub frames: Vec<sweeps::Frame>,
    /// The stations where the frame flips ([`sweeps::frame_flips`]).
    pub flips: Vec<usize>,
}

impl Document {
    /// The frames of the sweep node `id` at its stations and where they
    /// flip; `None` when `id` is not a sweep made from curves or its rail
    /// gives no frames.
    pub fn sweep_frames(&self, id: NodeId) -> Option<SweepFrames> {
        let c = self.nodes.get(&id)?.construction.as_ref()?;
        let Recipe::Sweep {
            rail,
            frame,
            stations,
            ..
        } = &c.recipe
        else {
            return None;
        };
        let lookup = |i: NodeId| self.nodes.get(&i);
        let Input { world, curve, .. } = input_of(&lookup, *rail)??;
        let rail = curve.transformed(&world).ok()?;
        let params = sweeps::stations(&rail, (*stations).max(2));
        let frames = sweeps::rail_frames(&rail, &params, *frame).ok()?;
        let flips = sweeps::frame_flips(&frames);
        Some(SweepFrames { frames, flips })
    }

    /// The nodes whose construction uses `id` as an input, in id order.
    pub fn dependents(&self, id: NodeId) -> Vec<NodeId> {
        self.nodes
            .values()
            .filter(|n| {
                n.construction
                    .as_ref()
                    .is_some_and(|c| c.recipe.inputs().contains(&&id))
            })
            .map(|n| n.id)
            .collect()
    }

    /// The contents the dependents of `changed` would have if the node
    /// were `changed` (its content, transform or parent differing from the
    /// document's), for a live preview while the app drags an input's
    /// control points or the node itself without a command. Dependents of
    /// `changed`'s descendants are included (their world matrices move
    /// too). A dependent that cannot be re-made with the change is left
    /// out (the app keeps drawing its old content); the command that ends
    /// the drag refuses in the same case. The document is not changed.
    ///
    /// Complexity: one construction per dependent.
    pub fn remade_dependents(&self, changed: &Node) -> Vec<(NodeId, NodeContent)> {
        let lookup = |id: NodeId| -> Option<&Node> {
            if id == changed.id {
                Some(changed)
            } else {
                self.nodes.get(&id)
            }
        };
        let moved = |id: NodeId| self.is_ancestor(changed.id, id);
        let mut out = Vec::new();
        for n in self.nodes.values() {
            let Some(c) = &n.construction else { continue };
            if !c.recipe.inputs().iter().any(|&&i| moved(i)) {
                continue;
            }
            let input = |id: NodeId| input_of(&lookup, id);
            if let Ok(made) = c.make(&input) {
                out.push((n.id, content_of(made, Some(&n.content))));
            }
        }
        out
    }
}

/// The world matrix of `id` through `lookup` (which may override nodes).
pub(crate) fn world_through<'a>(lookup: &dyn Fn(NodeId) -> Option<&'a Node>, id: NodeId) -> DMat4 {
    let mut m = DMat4::IDENTITY;
    let mut cur = Some(id);
    let mut guard = 10_000;
    while let Some(c) = cur {
        let Some(n) = lookup(c) else { break };
        m = n.transform.to_matrix() * m;
        cur = n.parent;
        guard -= 1;
        if guard == 0 {
            break;
        }
    }
    m
}

/// An input as [`Construction::make`] asks for it, through `lookup`.
pub(crate) fn input_of<'a>(
    lookup: &dyn Fn(NodeId) -> Option<&'a Node>,
    id: NodeId,
) -> Option<Option<Input>> {
    let n = lookup(id)?;
    Some(match &n.content {
        NodeContent::Curve(c) => Some(Input {
            world: world_through(lookup, id),
            curve: c.nurbs().clone(),
            name: n.name.clone(),
        }),
        _ => None,
    })
}

/// The node content a made result becomes; a mesh re-made over an older
/// mesh content keeps its shading, modifiers and subdivision (and its
/// creases where the connectivity is the same).
pub(crate) fn content_of(made: Made, old: Option<&NodeContent>) -> NodeContent {
    match made {
        Made::Surface(s) => NodeContent::Surface(Arc::new(SurfaceShape::Nurbs(s))),
        Made::Mesh(m) => {
            let mut content = match old {
                Some(NodeContent::Mesh(c)) => {
                    let mut c = c.clone();
                    if !c.mesh.same_connectivity(&m) {
                        c.creases = Default::default();
                    }
                    c.corners = Default::default();
                    c.primitive = None;
                    c
                }
                _ => MeshContent::new(Arc::new(HalfEdgeMesh::new())),
            };
            content.mesh = Arc::new(m);
            if content.has_decimate() || !content.decimations.is_empty() {
                let _ = content.refresh_decimations();
            }
            NodeContent::Mesh(content)
        }
    }
}

/// The geometry of a node's content a construction makes: the NURBS
/// surface or the mesh (not shading, modifiers or the like).
pub(crate) fn same_geometry(a: &NodeContent, b: &NodeContent) -> bool {
    match (a, b) {
        (NodeContent::Mesh(x), NodeContent::Mesh(y)) => {
            Arc::ptr_eq(&x.mesh, &y.mesh) || x.mesh == y.mesh
        }
        (NodeContent::Surface(x), NodeContent::Surface(y)) => Arc::ptr_eq(x, y) || x == y,
        _ => false,
    }
}
