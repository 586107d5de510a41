//! Subdivision surfaces: Catmull-Clark (n-gons, boundaries, semi-sharp and
//! sharp creases, corner sharpness), Loop, Doo-Sabin and linear splitting.
//!
//! Subdivision is a linear operator (libigl's `newV = S·V`): for a fixed
//! cage topology and fixed creases, a [`Refiner`] builds every level's
//! connectivity once; [`Refiner::refine`] then maps cage positions to the
//! refined positions through the masks, and [`StencilTable`] records the same
//! weights so a cage drag re-applies them without touching topology.
//!
//! ```
//! use hedra_geom::primitives::Primitive;
//! use hedra_geom::subdivision::{Options, Refiner, Creases};
//! let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
//! let refiner = Refiner::new(&cube, &Creases::default(), Options::default(), 2).unwrap();
//! assert_eq!(refiner.face_count(), 6 * 16);
//! let positions = refiner.refine(&refiner.cage_positions(&cube));
//! assert_eq!(positions.len(), refiner.vertex_count());
//! ```

mod creases;
mod level;
mod limit;
mod moves;
mod refine;
mod refiner;
mod rules;
mod stencil;
pub mod to_nurbs;

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::{EdgeId, FaceId, HalfEdgeMesh, VertexId};
pub use level::NonManifoldPlaces;
use level::{CageMap, Level};
use refine::{Split, doo_sabin_weight, refine_topology};
use rules::{Masks, Sink};

pub use creases::{CreaseTaper, Creases, TaperError};
pub use limit::{limit_normals, limit_positions, snap_to_limit};
pub use moves::LevelPoints;
pub use refiner::{PARALLEL_POINTS, Refiner, face_count_after, non_manifold_places};
pub use stencil::{StencilEvaluation, StencilTable};

/// Sharpness at or above this is infinitely sharp (OpenSubdiv's
/// `SHARPNESS_INFINITE`).
pub const INFINITE_SHARPNESS: f32 = 10.0;

/// Refinement levels above this are refused.
pub const MAX_LEVEL: u32 = 10;

/// The highest level the viewport preview offers (Ctrl+1…5 and Page Up, the
/// Properties panel): level 6 turns each cage quad into 4,096 faces (a cube
/// into 24,576); higher levels are for export and apply, up to [`MAX_LEVEL`].
pub const MAX_VIEWPORT_LEVEL: u32 = 6;

/// Refined meshes above this many faces are refused.
pub const MAX_FACES: usize = 20_000_000;

/// Which subdivision scheme.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Scheme {
    /// Quads from any polygons; smooth (bicubic B-spline away from
    /// extraordinary vertices).
    #[default]
    CatmullClark,
    /// Triangles only; smooth (quartic box spline).
    Loop,
    /// The dual (corner-cutting) scheme; smooth (biquadratic B-spline).
    DooSabin,
    /// Splits like Catmull-Clark (or 1-to-4 on an all-triangle mesh) without
    /// moving anything: more resolution, same shape.
    Linear,
}

impl Scheme {
    /// Every scheme, in menu order.
    pub const ALL: [Scheme; 4] = [
        Scheme::CatmullClark,
        Scheme::Loop,
        Scheme::DooSabin,
        Scheme::Linear,
    ];

    /// The scheme's name for display (`"Catmull-Clark"`).
    pub fn label(self) -> &'static str {
        match self {
            Scheme::CatmullClark => "Catmull-Clark",
            Scheme::Loop => "Loop",
            Scheme::DooSabin => "Doo-Sabin",
            Scheme::Linear => "Linear",
        }
    }
}

/// How boundary edges and corners are treated (OpenSubdiv's
/// `VtxBoundaryInterpolation`).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum BoundaryInterpolation {
    /// Boundary faces are left out of the result: the surface stops short of
    /// the cage's boundary.
    None,
    /// Boundary edges are sharp creases; corners are rounded.
    #[default]
    EdgesOnly,
    /// Boundary edges are sharp and corners (a single face) stay put.
    EdgesAndCorners,
}

impl BoundaryInterpolation {
    /// Every rule, in menu order.
    pub const ALL: [BoundaryInterpolation; 3] = [
        BoundaryInterpolation::None,
        BoundaryInterpolation::EdgesOnly,
        BoundaryInterpolation::EdgesAndCorners,
    ];
    /// The rule's name for display (`"Edges only"`).
    pub fn label(self) -> &'static str {
        match self {
            BoundaryInterpolation::None => "None",
            BoundaryInterpolation::EdgesOnly => "Edges only",
            BoundaryInterpolation::EdgesAndCorners => "Edges and corners",
        }
    }
}

/// How semi-sharp crease values fall from level to level.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum CreaseMethod {
    /// Sharpness − 1 per level.
    #[default]
    Uniform,
    /// Chaikin's rule: blends with the neighbouring crease edges first, so
    /// creases of varying sharpness fade smoothly.
    Chaikin,
}

impl CreaseMethod {
    /// Every method, in menu order.
    pub const ALL: [CreaseMethod; 2] = [CreaseMethod::Uniform, CreaseMethod::Chaikin];
    /// The method's name for display.
    pub fn label(self) -> &'static str {
        match self {
            CreaseMethod::Uniform => "Uniform",
            CreaseMethod::Chaikin => "Chaikin",
        }
    }
}

/// Scheme and rules of a refinement.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Options {
    /// The subdivision scheme.
    #[serde(default)]
    pub scheme: Scheme,
    /// How boundary edges and corners are treated.
    #[serde(default)]
    pub boundary: BoundaryInterpolation,
    /// How semi-sharp creases soften from level to level.
    #[serde(default)]
    pub crease_method: CreaseMethod,
    /// Catmull-Clark only: OpenSubdiv's `TRI_SUB_SMOOTH` rule for
    /// triangles. The edge point of an edge beside a triangle weighs the
    /// triangle's face point by 0.47 instead of 0.25 (both faces' weights are
    /// averaged into `f`, each end vertex gets `(1 − 2f) / 2`), which rounds
    /// triangles in a quad mesh more evenly. Off by default (plain
    /// Catmull-Clark, and how files written before it load).
    #[serde(default, skip_serializing_if = "is_false")]
    pub smooth_triangles: bool,
}

fn is_false(b: &bool) -> bool {
    !*b
}

/// Which of the [`Options`] and cage tags a scheme honours
/// ([`Scheme::applicable`]), so a panel can grey out the rest.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Applicable {
    /// Edge crease and vertex corner sharpness, and the crease method.
    pub creases: bool,
    /// The boundary rule ([`Options::boundary`]).
    pub boundary: bool,
    /// [`Options::smooth_triangles`].
    pub smooth_triangles: bool,
    /// Face holes ([`Creases::holes`]).
    pub holes: bool,
    /// Why the options that do not apply do not, for a tooltip (empty when
    /// everything applies).
    pub reason: &'static str,
}

impl Scheme {
    /// Which options and tags this scheme honours. Catmull-Clark honours all;
    /// Loop all but smooth triangles (its faces are all triangles already);
    /// Doo-Sabin and Linear neither creases nor the boundary rule: Doo-Sabin
    /// is a corner-cutting (dual) scheme whose new points are affine
    /// combinations of one face's corners, so it has no edge or vertex rule
    /// a sharpness could switch, and its surface always stops short of an
    /// open boundary (boundary edges and vertices make no faces); Linear
    /// moves no points (OpenSubdiv's bilinear scheme likewise ignores both).
    /// Every scheme honours holes.
    pub fn applicable(self) -> Applicable {
        match self {
            Scheme::CatmullClark => Applicable {
                creases: true,
                boundary: true,
                smooth_triangles: true,
                holes: true,
                reason: "",
            },
            Scheme::Loop => Applicable {
                creases: true,
                boundary: true,
                smooth_triangles: false,
                holes: true,
                reason: "Smooth triangles is a Catmull-Clark rule; Loop's faces are all triangles",
            },
            Scheme::DooSabin => Applicable {
                creases: false,
                boundary: false,
                smooth_triangles: false,
                holes: true,
                reason: "Doo-Sabin cuts corners: it has no edge or vertex rule for creases to sharpen, and its surface always stops short of an open boundary",
            },
            Scheme::Linear => Applicable {
                creases: false,
                boundary: false,
                smooth_triangles: false,
                holes: true,
                reason: "Linear splits faces without moving points: creases and boundary rules change nothing",
            },
        }
    }
}

/// Why a refinement cannot be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SubdivisionError {
    /// Loop subdivision of a cage with a face that is not a triangle.
    #[error(
        "Loop subdivision needs triangles, but face {face} has {sides} sides (triangulate first)"
    )]
    NotTriangles {
        /// A cage face that is not a triangle.
        face: FaceId,
        /// Its number of sides.
        sides: usize,
    },
    /// More levels than [`MAX_LEVEL`] were asked for.
    #[error("level {level} is above the maximum of {MAX_LEVEL}")]
    LevelTooHigh {
        /// The level asked for.
        level: u32,
    },
    /// Limit evaluation asked of a scheme or level it does not cover.
    #[error("{} has no limit surface evaluation here (Catmull-Clark needs an all-quad level, Loop triangles)", scheme.label())]
    NoLimit {
        /// The refinement's scheme.
        scheme: Scheme,
    },
    /// The caller's `go_on` callback returned false
    /// ([`Refiner::new_cancellable`]).
    #[error("cancelled")]
    Cancelled,
    /// The cage has a face with rings or without edges.
    #[error("face {face} has inner rings or no edges; subdivision needs plain polygons")]
    FaceWithRings {
        /// The face.
        face: FaceId,
    },
    /// A polygon given as a vertex list ([`Refiner::from_polygons`]) has
    /// fewer than three corners or names a vertex that is not there.
    #[error("face {face} is not a polygon of the cage: {reason}")]
    BadPolygon {
        /// The face (its index in the list).
        face: FaceId,
        /// What is wrong with it.
        reason: String,
    },
    /// The result would have more than [`MAX_FACES`] faces.
    #[error("level {level} would make {faces} faces, more than the limit of {MAX_FACES}")]
    TooManyFaces {
        /// The level that would exceed the limit.
        level: u32,
        /// Its face count.
        faces: usize,
    },
}
