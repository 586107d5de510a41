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

mod level;
mod limit;
mod refine;
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

/// The cage's subdivision tags, by the cage's ids: crease sharpness of
/// edges, corner sharpness of vertices (missing entries are 0, smooth;
/// values at or above [`INFINITE_SHARPNESS`] are infinitely sharp) and face
/// holes. Entries of elements that no longer exist are ignored.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Creases {
    /// Crease sharpness per edge (only values above 0 are stored).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub edges: BTreeMap<EdgeId, f64>,
    /// Corner sharpness per vertex (only values above 0 are stored).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub vertices: BTreeMap<VertexId, f64>,
    /// Faces that are holes (OpenSubdiv's face hole tag): a hole is refined
    /// like any face and its neighbours keep their shape, but it leaves no
    /// faces in the refined or limit surface.
    #[serde(default, skip_serializing_if = "BTreeSet::is_empty")]
    pub holes: BTreeSet<FaceId>,
    /// Chains of edges whose sharpness runs from a start to an end value
    /// along the chain ([`set_taper`](Self::set_taper)). An edge is in at
    /// most one chain, and then not in [`edges`](Self::edges).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tapers: Vec<CreaseTaper>,
}

/// A crease whose sharpness varies along a chain of edges (Rhino's tapered
/// SubD creases; OpenSubdiv has only per-edge sharpness): `start` at the
/// chain's first vertex, `end` at its last, linear in arc length between.
/// Each edge takes the value at its midpoint, measured along the chain when
/// the taper was set (so moving vertices later does not change it), and is
/// then subdivided with the ordinary semi-sharp rules.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CreaseTaper {
    /// The chain's edges in order, each with the arc-length fraction
    /// (0 at the start, 1 at the end) of its midpoint.
    pub edges: Vec<(EdgeId, f64)>,
    /// Sharpness at the chain's start.
    pub start: f64,
    /// Sharpness at the chain's end.
    pub end: f64,
}

impl CreaseTaper {
    /// The sharpness at arc-length fraction `t` (0 … 1) of the chain.
    pub fn sharpness_at(&self, t: f64) -> f64 {
        self.start + (self.end - self.start) * t
    }
}

/// Why [`Creases::set_taper`] refused a chain. The creases are unchanged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TaperError {
    /// No edges were given.
    #[error("a tapered crease needs at least one edge")]
    NoEdges,
    /// An edge id the mesh does not have.
    #[error("edge {edge} does not exist")]
    NoSuchEdge {
        /// The missing edge.
        edge: EdgeId,
    },
    /// The edges do not form one path or one loop (a vertex with three or
    /// more of them, or separate pieces).
    #[error("the edges do not form one chain (a path or a loop): {why}")]
    NotAChain {
        /// Which way they fail.
        why: &'static str,
    },
    /// The start vertex is not an end of the path (or not on the loop).
    #[error("vertex {vertex} is not an end of the chain")]
    NotAnEnd {
        /// The vertex given as the start.
        vertex: VertexId,
    },
    /// A sharpness that is negative or not finite.
    #[error("sharpness {0} is not a finite value of 0 or more")]
    BadSharpness(f64),
}

impl Creases {
    /// True when no edge or vertex has a sharpness entry.
    pub fn is_empty(&self) -> bool {
        self.edges.is_empty()
            && self.vertices.is_empty()
            && self.holes.is_empty()
            && self.tapers.is_empty()
    }
    /// True when face `f` is a hole.
    pub fn is_hole(&self, f: FaceId) -> bool {
        self.holes.contains(&f)
    }
    /// Makes face `f` a hole (`true`) or clears its hole (`false`).
    pub fn set_hole(&mut self, f: FaceId, hole: bool) {
        if hole {
            self.holes.insert(f);
        } else {
            self.holes.remove(&f);
        }
    }
    /// Sharpness of edge `e` (0 when unset): its own, or its value along a
    /// tapered chain.
    pub fn edge(&self, e: EdgeId) -> f64 {
        if let Some(&s) = self.edges.get(&e) {
            return s;
        }
        self.tapers
            .iter()
            .find_map(|t| {
                t.edges
                    .iter()
                    .find(|(te, _)| *te == e)
                    .map(|&(_, at)| t.sharpness_at(at))
            })
            .unwrap_or(0.0)
    }
    /// Every edge with a sharpness above 0, its own or from a taper.
    pub fn edge_sharpness(&self) -> BTreeMap<EdgeId, f64> {
        let mut out = self.edges.clone();
        for t in &self.tapers {
            for &(e, at) in &t.edges {
                let s = t.sharpness_at(at);
                if s > 0.0 {
                    out.insert(e, s);
                }
            }
        }
        out
    }
    /// Makes `edges` one tapered crease: sharpness `start` at vertex `from`
    /// (an end of the path the edges form, or any vertex of the loop they
    /// form), `end` at the other end, linear in arc length between (each
    /// edge takes the value at its midpoint, measured now). The edges leave
    /// any plain crease or other taper they were in; inverse: `set_edge`
    /// of each edge to its old value, or [`clear_taper`](Self::clear_taper).
    /// Complexity: O(edges · tapers).
    ///
    /// # Errors
    /// [`TaperError`] when the edges are none, missing, not one path or
    /// loop, `from` is not an end, or a sharpness is negative or not finite.
    pub fn set_taper(
        &mut self,
        mesh: &HalfEdgeMesh,
        edges: &[EdgeId],
        from: VertexId,
        start: f64,
        end: f64,
    ) -> Result<(), TaperError> {
        for s in [start, end] {
            if !s.is_finite() || s < 0.0 {
                return Err(TaperError::BadSharpness(s));
            }
        }
        let chain = order_chain(mesh, edges, from)?;
        let lengths: Vec<f64> = chain
            .iter()
            .map(|&e| {
                let [a, b] = mesh.edge_vertices(e);
                mesh.position(a).distance(mesh.position(b))
            })
            .collect();
        let total: f64 = lengths.iter().sum();
        let mut run = 0.0;
        let mut taper = CreaseTaper {
            edges: Vec::with_capacity(chain.len()),
            start,
            end,
        };
        for (&e, &l) in chain.iter().zip(&lengths) {
            let t = if total > 0.0 {
                (run + 0.5 * l) / total
            } else {
                0.5
            };
            run += l;
            taper.edges.push((e, t));
        }
        self.clear_taper(&chain);
        for e in &chain {
            self.edges.remove(e);
        }
        self.tapers.push(taper);
        Ok(())
    }
    /// Takes `edges` out of every taper (they become smooth unless they
    /// have a plain crease); tapers left without edges are removed.
    pub fn clear_taper(&mut self, edges: &[EdgeId]) {
        for t in &mut self.tapers {
            t.edges.retain(|(e, _)| !edges.contains(e));
        }
        self.tapers.retain(|t| !t.edges.is_empty());
    }
    /// Corner sharpness of vertex `v` (0 when unset).
    pub fn vertex(&self, v: VertexId) -> f64 {
        self.vertices.get(&v).copied().unwrap_or(0.0)
    }
    /// Sets (or with 0, clears) the sharpness of edge `e`.
    pub fn set_edge(&mut self, e: EdgeId, sharpness: f64) {
        self.clear_taper(&[e]);
        if sharpness > 0.0 {
            self.edges.insert(e, sharpness);
        } else {
            self.edges.remove(&e);
        }
    }
    /// Sets (or with 0, clears) the corner sharpness of vertex `v`.
    pub fn set_vertex(&mut self, v: VertexId, sharpness: f64) {
        if sharpness > 0.0 {
            self.vertices.insert(v, sharpness);
        } else {
            self.vertices.remove(&v);
        }
    }
    /// The creases whose elements are still alive in `mesh`.
    pub fn retain_live(&mut self, mesh: &HalfEdgeMesh) {
        self.edges.retain(|e, _| mesh.is_edge(*e));
        self.vertices.retain(|v, _| mesh.is_vertex(*v));
        self.holes.retain(|f| mesh.is_face(*f));
        for t in &mut self.tapers {
            t.edges.retain(|(e, _)| mesh.is_edge(*e));
        }
        self.tapers.retain(|t| !t.edges.is_empty());
    }
}

/// `edges` in order along the path or loop they form, starting at `from`.
fn order_chain(
    mesh: &HalfEdgeMesh,
    edges: &[EdgeId],
    from: VertexId,
) -> Result<Vec<EdgeId>, TaperError> {
    if edges.is_empty() {
        return Err(TaperError::NoEdges);
    }
    let mut at: BTreeMap<VertexId, Vec<EdgeId>> = BTreeMap::new();
    let mut unique = BTreeSet::new();
    for &e in edges {
        if !mesh.is_edge(e) {
            return Err(TaperError::NoSuchEdge { edge: e });
        }
        if unique.insert(e) {
            for v in mesh.edge_vertices(e) {
                at.entry(v).or_default().push(e);
            }
        }
    }
    if at.values().any(|es| es.len() > 2) {
        return Err(TaperError::NotAChain {
            why: "a vertex has three or more of them",
        });
    }
    let ends = at.values().filter(|es| es.len() == 1).count();
    let from_ok = match at.get(&from) {
        Some(es) => ends == 0 || es.len() == 1,
        None => false,
    };
    if !from_ok {
        return Err(TaperError::NotAnEnd { vertex: from });
    }
    let mut chain = Vec::with_capacity(unique.len());
    let mut v = from;
    let mut prev: Option<EdgeId> = None;
    while let Some(&e) = at[&v].iter().find(|&&e| Some(e) != prev) {
        if chain.first() == Some(&e) {
            break;
        }
        chain.push(e);
        prev = Some(e);
        let [a, b] = mesh.edge_vertices(e);
        v = if a == v { b } else { a };
    }
    if chain.len() != unique.len() {
        return Err(TaperError::NotAChain {
            why: "they fall into separate pieces",
        });
    }
    Ok(chain)
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

/// The refinement of one cage topology to a number of levels: every level's
/// connectivity, built once. Positions are mapped with [`refine`](Self::refine)
/// (or a [`StencilTable`]) as often as the cage moves.
#[derive(Clone, Debug)]
pub struct Refiner {
    options: Options,
    pub(crate) levels: Vec<Level>,
    cage: CageMap,
    /// Per cage face (dense): left out of the result (a hole, or boundary
    /// `None`).
    hidden_cage_faces: Vec<bool>,
}

impl Refiner {
    /// Builds the connectivity of `levels` refinement steps of `mesh` with
    /// `creases`. Complexity: O(result size).
    ///
    /// # Errors
    /// [`SubdivisionError::NotTriangles`] for Loop on a mesh with other
    /// faces; [`SubdivisionError::FaceWithRings`] for a face with inner
    /// rings or without edges; [`SubdivisionError::LevelTooHigh`] /
    /// `TooManyFaces` when the result would be too large (nothing is
    /// allocated first).
    pub fn new(
        mesh: &HalfEdgeMesh,
        creases: &Creases,
        options: Options,
        levels: u32,
    ) -> Result<Self, SubdivisionError> {
        Self::new_cancellable(mesh, creases, options, levels, &mut |_| true)
    }

    /// [`new`](Self::new) that calls `go_on(level)` after building each
    /// level and stops with [`SubdivisionError::Cancelled`] when it returns
    /// false (for background work the user can cancel).
    ///
    /// # Errors
    /// As [`new`](Self::new), and `Cancelled`.
    pub fn new_cancellable(
        mesh: &HalfEdgeMesh,
        creases: &Creases,
        options: Options,
        levels: u32,
        go_on: &mut dyn FnMut(u32) -> bool,
    ) -> Result<Self, SubdivisionError> {
        if levels > MAX_LEVEL {
            return Err(SubdivisionError::LevelTooHigh { level: levels });
        }
        if let Some(face) = mesh.first_non_polygon_face() {
            return Err(SubdivisionError::FaceWithRings { face });
        }
        if options.scheme == Scheme::Loop
            && let Some(f) = mesh.faces().find(|&f| mesh.face_degree(f) != 3)
        {
            return Err(SubdivisionError::NotTriangles {
                face: f,
                sides: mesh.face_degree(f),
            });
        }
        let hide_boundary =
            options.boundary == BoundaryInterpolation::None && options.scheme.applicable().boundary;
        let (cage_level, cage, hidden_cage_faces) =
            Level::from_mesh(mesh, creases, options.boundary, hide_boundary);
        Self::from_cage(cage_level, cage, hidden_cage_faces, options, levels, go_on)
    }

    /// Builds the refinement of polygons given as vertex lists (indices
    /// into `vertex_count` vertices), kept as they are: an edge may be in
    /// more than two faces and a vertex may join separate fans, as in
    /// scanned and game meshes (issue 37). Such edges are infinitely sharp
    /// and such vertices corners or creases, as OpenSubdiv treats them
    /// ([`Level::from_polygon_cage`]). Cage vertex, edge and face ids are
    /// the indices (`VertexId(i)` is vertex `i`, `FaceId(f)` face `f`);
    /// position the cage with `refine(&positions)`.
    ///
    /// # Errors
    /// [`SubdivisionError::NotTriangles`] for Loop with a face of another
    /// size; [`SubdivisionError::BadPolygon`] for a face of fewer than three
    /// corners or a vertex index out of range;
    /// `LevelTooHigh` / `TooManyFaces` as [`new`](Self::new).
    pub fn from_polygons(
        vertex_count: usize,
        faces: &[Vec<u32>],
        options: Options,
        levels: u32,
    ) -> Result<Self, SubdivisionError> {
        if levels > MAX_LEVEL {
            return Err(SubdivisionError::LevelTooHigh { level: levels });
        }
        check_polygons(vertex_count, faces, options.scheme)?;
        let hide_boundary =
            options.boundary == BoundaryInterpolation::None && options.scheme.applicable().boundary;
        let (cage_level, hidden_cage_faces, _) =
            Level::from_polygon_cage(vertex_count, faces, options.boundary, hide_boundary);
        let cage = CageMap {
            vertices: (0..vertex_count as u32).map(VertexId).collect(),
            edges: (0..cage_level.edge_count() as u32).map(EdgeId).collect(),
            faces: (0..faces.len() as u32).map(FaceId).collect(),
        };
        Self::from_cage(
            cage_level,
            cage,
            hidden_cage_faces,
            options,
            levels,
            &mut |_| true,
        )
    }

    /// The levels above `cage_level`, checked against the size limits.
    fn from_cage(
        cage_level: Level,
        cage: CageMap,
        hidden_cage_faces: Vec<bool>,
        options: Options,
        levels: u32,
        go_on: &mut dyn FnMut(u32) -> bool,
    ) -> Result<Self, SubdivisionError> {
        let split = split_for(options.scheme, &cage_level);
        for level in 1..=levels {
            let faces = faces_after(&cage_level, split, level);
            if faces > MAX_FACES {
                return Err(SubdivisionError::TooManyFaces { level, faces });
            }
        }
        let mut all = vec![cage_level];
        for level in 1..=levels {
            let child = refine_topology(
                all.last().expect("cage level"),
                split,
                options.crease_method,
                level < levels,
            );
            all.push(child);
            if !go_on(level) {
                return Err(SubdivisionError::Cancelled);
            }
        }
        Ok(Refiner {
            options,
            levels: all,
            cage,
            hidden_cage_faces,
        })
    }

    /// The scheme and rules this refinement was built with.
    pub fn options(&self) -> Options {
        self.options
    }
    /// Number of refinement steps.
    pub fn level_count(&self) -> u32 {
        self.levels.len() as u32 - 1
    }
    fn last(&self) -> &Level {
        self.levels.last().expect("at least the cage level")
    }
    /// Vertices of the refined mesh.
    pub fn vertex_count(&self) -> usize {
        self.last().vertex_count
    }
    /// Faces of the refined mesh (including those hidden by boundary `None`).
    pub fn face_count(&self) -> usize {
        self.last().face_count()
    }
    /// The refined faces as vertex index lists, without the faces that
    /// boundary interpolation `None` leaves out.
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        let last = self.last();
        (0..last.face_count())
            .filter(|&f| !self.hidden_cage_faces[last.face_origin(f) as usize])
            .map(move |f| &last.face_vertices[last.face_corners(f as u32)])
    }
    /// Refined face `f` (of all [`face_count`](Self::face_count) faces,
    /// hidden ones included) as vertex indices.
    pub fn face(&self, f: usize) -> &[u32] {
        let last = self.last();
        &last.face_vertices[last.face_corners(f as u32)]
    }
    /// True when refined face `f` (of all [`face_count`](Self::face_count)
    /// faces) is left out of the result: it descends from a hole, or from a
    /// face that boundary `None` leaves out.
    pub fn is_face_hidden(&self, f: usize) -> bool {
        self.hidden_cage_faces[self.last().face_origin(f) as usize]
    }
    /// True when cage face `f` is left out of the result (a hole, or a face
    /// that boundary `None` leaves out); false for faces not in the cage.
    pub fn is_cage_face_hidden(&self, f: FaceId) -> bool {
        self.cage
            .faces
            .iter()
            .position(|&g| g == f)
            .is_some_and(|i| self.hidden_cage_faces[i])
    }
    /// The cage face each shown refined face comes from, in [`faces`](Self::faces) order.
    pub fn face_origins(&self) -> impl Iterator<Item = FaceId> + '_ {
        let last = self.last();
        (0..last.face_count())
            .map(|f| last.face_origin(f))
            .filter(|&o| !self.hidden_cage_faces[o as usize])
            .map(|o| self.cage.faces[o as usize])
    }
    /// The refined edges (vertex index pairs) with their remaining sharpness.
    pub fn edges(&self) -> impl Iterator<Item = ([u32; 2], f32)> + '_ {
        let last = self.last();
        last.edge_vertices
            .iter()
            .enumerate()
            .map(|(e, &ends)| (ends, last.edge_sharp(e as u32)))
    }
    /// The cage's positions in the order [`refine`](Self::refine) expects.
    pub fn cage_positions(&self, mesh: &HalfEdgeMesh) -> Vec<DVec3> {
        self.cage
            .vertices
            .iter()
            .map(|&v| mesh.position(v))
            .collect()
    }
    /// Cage vertex ids in refine order.
    pub fn cage_vertices(&self) -> &[VertexId] {
        &self.cage.vertices
    }

    /// Refined positions from cage positions (in
    /// [`cage_positions`](Self::cage_positions) order), level by level
    /// through the masks. Complexity: O(result size).
    pub fn refine(&self, cage: &[DVec3]) -> Vec<DVec3> {
        self.refine_with(cage, false)
    }

    /// [`refine`](Self::refine) with each level's points computed on all
    /// cores (rayon).
    pub fn refine_parallel(&self, cage: &[DVec3]) -> Vec<DVec3> {
        self.refine_with(cage, true)
    }

    fn refine_with(&self, cage: &[DVec3], parallel: bool) -> Vec<DVec3> {
        self.refine_cancellable(cage, parallel, &mut |_| true)
            .expect("never cancelled")
    }

    /// [`refine`](Self::refine) (or its parallel form) that calls
    /// `go_on(level)` after each level and returns `None` when it says stop.
    pub fn refine_cancellable(
        &self,
        cage: &[DVec3],
        parallel: bool,
        go_on: &mut dyn FnMut(u32) -> bool,
    ) -> Option<Vec<DVec3>> {
        assert_eq!(
            cage.len(),
            self.levels[0].vertex_count,
            "one position per cage vertex"
        );
        let mut points = cage.to_vec();
        for (i, parent) in self.levels[..self.levels.len() - 1].iter().enumerate() {
            points = interpolate(parent, self.split(), self.options, &points, parallel);
            if !go_on(i as u32 + 1) {
                return None;
            }
        }
        Some(points)
    }

    pub(crate) fn split(&self) -> Split {
        split_for(self.options.scheme, &self.levels[0])
    }

    /// The weights of every level, for re-applying after cage moves.
    pub fn stencils(&self) -> StencilTable {
        StencilTable::new(self)
    }

    /// The refined mesh as a half-edge mesh with the creases that remain
    /// after the refinement (for "apply").
    ///
    /// # Errors
    /// A build error when the refined faces do not form a manifold mesh,
    /// which only a non-manifold cage can cause.
    pub fn to_mesh(
        &self,
        positions: &[DVec3],
    ) -> Result<(HalfEdgeMesh, Creases), crate::BuildError> {
        let last = self.last();
        // Vertices and edges are numbered in order of first use by the
        // shown faces (then isolated vertices): the numbering
        // `from_polygons` gives the same faces, which files and tests rely
        // on. The edges are the level's, so no twin has to be searched.
        let all_shown = !self.hidden_cage_faces.contains(&true);
        // Only hiding faces could make a vertex's fans touch; a whole
        // refinement of a valid mesh cannot.
        let (mesh, used, edge_map) = HalfEdgeMesh::from_level_faces(
            positions,
            crate::mesh::LevelFaces {
                sides: last.sides,
                face_offsets: &last.face_offsets,
                corner_vertex: &last.face_vertices,
                corner_edge: &last.face_edges,
                edge_count: last.edge_count(),
            },
            |f| all_shown || !self.is_face_hidden(f),
            |v| last.vertex_edges(v as u32).is_empty(),
            !all_shown,
        )?;
        let mut creases = Creases::default();
        for (e, &s) in last.edge_sharpness.iter().enumerate() {
            let m = edge_map[e];
            if s > 0.0 && m != u32::MAX && !mesh.is_boundary_edge(EdgeId(m)) {
                creases.set_edge(EdgeId(m), s as f64);
            }
        }
        for (v, &s) in last.vertex_sharpness.iter().enumerate() {
            let boundary_corner = self.options.boundary == BoundaryInterpolation::EdgesAndCorners
                && rules::is_infinite(s);
            if s > 0.0 && used[v] != u32::MAX && !boundary_corner {
                creases.set_vertex(VertexId(used[v]), s as f64);
            }
        }
        Ok((mesh, creases))
    }

    /// Refines `mesh` and builds the result in one call.
    ///
    /// # Errors
    /// As [`Refiner::new`]. (Refining a valid half-edge mesh always gives a
    /// valid one, so the build cannot fail.)
    ///
    /// # Example
    /// One level of Catmull-Clark turns each of a cube's 6 quads into 4:
    /// ```
    /// use hedra_geom::subdivision::{Creases, Options, Refiner, Scheme};
    /// use hedra_geom::Primitive;
    /// let cube = Primitive::Cube { size: 2.0 }.build()?;
    /// let options = Options { scheme: Scheme::CatmullClark, ..Options::default() };
    /// let (smooth, _creases) = Refiner::subdivide(&cube, &Creases::default(), options, 1)?;
    /// // 8 corners + 12 edge points + 6 face points.
    /// assert_eq!((smooth.vertex_count(), smooth.edge_count(), smooth.face_count()), (26, 48, 24));
    /// smooth.validate()?;
    /// // The surface shrinks inside the cage: every point stays within the cube.
    /// assert!(smooth.vertices().all(|v| smooth.position(v).abs().max_element() <= 1.0));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn subdivide(
        mesh: &HalfEdgeMesh,
        creases: &Creases,
        options: Options,
        levels: u32,
    ) -> Result<(HalfEdgeMesh, Creases), SubdivisionError> {
        let refiner = Refiner::new(mesh, creases, options, levels)?;
        let positions = refiner.refine(&refiner.cage_positions(mesh));
        Ok(refiner
            .to_mesh(&positions)
            .expect("refining a valid half-edge mesh gives a valid mesh"))
    }
}

pub use limit::{limit_normals, limit_positions, snap_to_limit};

/// Faces after `levels` steps (exact for Catmull-Clark, Loop and linear;
/// an estimate for Doo-Sabin past level 1). Saturates instead of overflowing.
fn faces_after(cage: &Level, split: Split, levels: u32) -> usize {
    let mut faces = cage.face_count();
    for level in 1..=levels {
        faces = match split {
            Split::Quads if level == 1 => cage.face_vertices.len(),
            Split::Dual if level == 1 => cage.face_count() + cage.edge_count() + cage.vertex_count,
            _ => faces.saturating_mul(4),
        };
    }
    faces
}

/// Where polygons given as vertex lists are not manifold: edges in three
/// or more faces, edges two faces run along the same way, vertices where
/// separate fans meet, faces that visit a vertex twice; empty when a
/// half-edge mesh can hold them. The same analysis
/// [`Refiner::from_polygons`] refines them by (OpenSubdiv's Vtr).
///
/// # Errors
/// [`SubdivisionError::BadPolygon`] as [`Refiner::from_polygons`].
pub fn non_manifold_places(
    vertex_count: usize,
    faces: &[Vec<u32>],
) -> Result<NonManifoldPlaces, SubdivisionError> {
    check_polygons(vertex_count, faces, Scheme::CatmullClark)?;
    let boundary = BoundaryInterpolation::EdgesOnly;
    Ok(Level::from_polygon_cage(vertex_count, faces, boundary, false).2)
}

/// Refuses polygons of fewer than three corners, vertex indices out of
/// range, and (for Loop) faces that are not triangles.
fn check_polygons(
    vertex_count: usize,
    faces: &[Vec<u32>],
    scheme: Scheme,
) -> Result<(), SubdivisionError> {
    for (f, face) in faces.iter().enumerate() {
        let face_id = FaceId(f as u32);
        if face.len() < 3 {
            return Err(SubdivisionError::BadPolygon {
                face: face_id,
                reason: format!("{} corners", face.len()),
            });
        }
        if let Some(&v) = face.iter().find(|&&v| v as usize >= vertex_count) {
            return Err(SubdivisionError::BadPolygon {
                face: face_id,
                reason: format!("vertex {v} is not one of the {vertex_count} vertices"),
            });
        }
        if scheme == Scheme::Loop && face.len() != 3 {
            return Err(SubdivisionError::NotTriangles {
                face: face_id,
                sides: face.len(),
            });
        }
    }
    Ok(())
}

/// How many faces `levels` steps of `scheme` make from `mesh`, without
/// refining (to decide whether to refine in the background).
pub fn face_count_after(mesh: &HalfEdgeMesh, scheme: Scheme, levels: u32) -> usize {
    let (cage, _, _) = Level::from_mesh(
        mesh,
        &Creases::default(),
        BoundaryInterpolation::EdgesOnly,
        false,
    );
    faces_after(&cage, split_for(scheme, &cage), levels)
}

fn split_for(scheme: Scheme, cage: &Level) -> Split {
    match scheme {
        Scheme::CatmullClark => Split::Quads,
        Scheme::Loop => Split::Triangles,
        Scheme::DooSabin => Split::Dual,
        Scheme::Linear if cage.face_count() > 0 && cage.all_faces_have(3) => Split::Triangles,
        Scheme::Linear => Split::Quads,
    }
}

fn masks_for(scheme: Scheme) -> Masks {
    match scheme {
        Scheme::CatmullClark => Masks::CatmullClark,
        Scheme::Loop => Masks::Loop,
        Scheme::DooSabin | Scheme::Linear => Masks::Linear,
    }
}

/// Accumulates a point from parent positions and face points.
struct PointSink<'a> {
    points: &'a [DVec3],
    face_points: &'a [DVec3],
    sum: DVec3,
}

impl Sink for PointSink<'_> {
    #[inline]
    fn vertex(&mut self, v: u32, w: f64) {
        self.sum += w * self.points[v as usize];
    }
    #[inline]
    fn face(&mut self, f: u32, w: f64) {
        self.sum += w * self.face_points[f as usize];
    }
}

/// What child point `i` of a step is.
#[derive(Copy, Clone)]
pub(crate) enum ChildPoint {
    Face(u32),
    Edge(u32),
    Vertex(u32),
    /// Doo-Sabin: the new point of a parent corner.
    Corner(u32),
}

/// Child point `i` of `parent` under `split`.
pub(crate) fn child_point(parent: &Level, split: Split, i: usize) -> ChildPoint {
    if split == Split::Dual {
        return ChildPoint::Corner(i as u32);
    }
    let nf = split.face_points(parent);
    let ne = parent.edge_count();
    if i < nf {
        ChildPoint::Face(i as u32)
    } else if i < nf + ne {
        ChildPoint::Edge((i - nf) as u32)
    } else {
        ChildPoint::Vertex((i - nf - ne) as u32)
    }
}

/// Emits the mask of child point `point` into `sink`.
pub(crate) fn point_mask(
    parent: &Level,
    options: Options,
    point: ChildPoint,
    sink: &mut impl Sink,
) {
    let masks = masks_for(options.scheme);
    match point {
        ChildPoint::Face(f) => rules::face_mask(parent, f, sink),
        ChildPoint::Edge(e) => rules::edge_mask(parent, e, masks, options.smooth_triangles, sink),
        ChildPoint::Vertex(v) => rules::vertex_mask(parent, v, masks, options.crease_method, sink),
        ChildPoint::Corner(c) => {
            let r = parent.face_corners(parent.corner_face(c as usize));
            let (n, i) = (r.len(), c as usize - r.start);
            for (j, k) in r.enumerate() {
                sink.vertex(parent.face_vertices[k], doo_sabin_weight(n, i, j));
            }
        }
    }
}

/// Number of child points of `parent` under `split`.
pub(crate) fn child_count(parent: &Level, split: Split) -> usize {
    match split {
        Split::Quads => parent.face_count() + parent.edge_count() + parent.vertex_count,
        Split::Triangles => parent.edge_count() + parent.vertex_count,
        Split::Dual => parent.face_vertices.len(),
    }
}

/// One level's child positions: face points first (edge and vertex masks
/// read them), then the rest.
///
/// Smooth edges and vertices of Catmull-Clark and Loop (no sharpness, not
/// on a boundary: almost every point of a typical mesh) are computed here
/// with their masks written out; every other point goes through
/// [`point_mask`]. Both add the same terms in the same order, so the result
/// is the same to the last bit either way (and the same as the stencils').
fn interpolate(
    parent: &Level,
    split: Split,
    options: Options,
    points: &[DVec3],
    parallel: bool,
) -> Vec<DVec3> {
    if split == Split::Dual {
        return interpolate_generic(parent, split, options, points, parallel);
    }
    let masks = masks_for(options.scheme);
    let nf = split.face_points(parent);
    let ne = parent.edge_count();
    let child_count = child_count(parent, split);
    let edge_corners = parent.edge_corner_table();
    let vertex_edges = parent.vertex_edge_lists();
    // Only Catmull-Clark's vertex mask reads the faces around a vertex.
    let vertex_corners = (masks == Masks::CatmullClark).then(|| parent.vertex_corner_lists());
    // A level without any sharpness needs no per-point test of its edges.
    let smooth_level = parent.is_smooth();
    let all_quads = parent.sides == 4;
    let betas: [f64; 16] = std::array::from_fn(rules::loop_beta);
    let generic = |face_points: &[DVec3], point: ChildPoint| {
        let mut sink = PointSink {
            points,
            face_points,
            sum: DVec3::ZERO,
        };
        point_mask(parent, options, point, &mut sink);
        sink.sum
    };
    // The face point (rules::face_mask).
    let face = |f: usize| {
        if all_quads {
            // The fold below written out (same terms, same order).
            let q = &parent.face_vertices[4 * f..4 * f + 4];
            return DVec3::ZERO
                + 0.25 * points[q[0] as usize]
                + 0.25 * points[q[1] as usize]
                + 0.25 * points[q[2] as usize]
                + 0.25 * points[q[3] as usize];
        }
        let r = parent.face_corners(f as u32);
        let w = 1.0 / r.len() as f64;
        parent.face_vertices[r]
            .iter()
            .fold(DVec3::ZERO, |sum, &v| sum + w * points[v as usize])
    };
    let triangle = |f: u32| parent.face_corners(f).len() == 3;
    // The smooth edge masks of rules::edge_mask.
    let edge = |face_points: &[DVec3], e: usize| {
        let [a, b] = parent.edge_vertices[e];
        let [c0, c1] = edge_corners[e];
        if parent.edge_sharp(e as u32) == 0.0 && c1 != level::NONE {
            let (f0, f1) = if all_quads {
                (c0 / 4, c1 / 4)
            } else {
                (
                    parent.corner_face(c0 as usize),
                    parent.corner_face(c1 as usize),
                )
            };
            let (pa, pb) = (points[a as usize], points[b as usize]);
            match masks {
                Masks::CatmullClark
                    if !(options.smooth_triangles && (triangle(f0) || triangle(f1))) =>
                {
                    return DVec3::ZERO
                        + 0.25 * pa
                        + 0.25 * pb
                        + 0.25 * face_points[f0 as usize]
                        + 0.25 * face_points[f1 as usize];
                }
                Masks::Loop => {
                    // The vertex of corner c's triangle that is not on
                    // the edge c starts: the corner before c (Loop levels
                    // are all triangles: corner c is in 3 (c / 3)..).
                    let opposite = |c: u32| {
                        let base = c - c % 3;
                        let before = base + (c - base + 2) % 3;
                        points[parent.face_vertices[before as usize] as usize]
                    };
                    return DVec3::ZERO
                        + 0.375 * pa
                        + 0.375 * pb
                        + 0.125 * opposite(c0)
                        + 0.125 * opposite(c1);
                }
                _ => {}
            }
        }
        generic(face_points, ChildPoint::Edge(e as u32))
    };
    // The smooth vertex masks of rules::smooth_vertex_mask (smooth vertices
    // and darts: no corner sharpness, at most one sharp edge).
    let vertex = |face_points: &[DVec3], v: usize| {
        let edges = vertex_edges.get(v);
        let smooth = smooth_level
            || (parent.vertex_sharp(v as u32) <= 0.0
                && edges
                    .iter()
                    .filter(|&&e| parent.edge_sharp(e) > 0.0)
                    .count()
                    <= 1);
        if smooth && !edges.is_empty() && masks != Masks::Linear {
            let n = edges.len() as f64;
            let other = |e: u32| {
                let [a, b] = parent.edge_vertices[e as usize];
                points[(if a as usize == v { b } else { a }) as usize]
            };
            if let Some(vertex_corners) = vertex_corners {
                let corners = vertex_corners.get(v);
                let w_edge = 1.0 / (n * n);
                let w_face = 1.0 / (n * corners.len() as f64);
                let sum = DVec3::ZERO + (n - 2.0) / n * points[v];
                let sum = edges.iter().fold(sum, |sum, &e| sum + w_edge * other(e));
                // Quads (every level past the first): corner c is in face c / 4.
                let face_of = |c: u32| {
                    if all_quads {
                        c / 4
                    } else {
                        parent.corner_face(c as usize)
                    }
                };
                return corners.iter().fold(sum, |sum, &c| {
                    sum + w_face * face_points[face_of(c) as usize]
                });
            }
            let beta = betas
                .get(edges.len())
                .copied()
                .unwrap_or_else(|| rules::loop_beta(edges.len()));
            let sum = DVec3::ZERO + (1.0 - n * beta) * points[v];
            return edges.iter().fold(sum, |sum, &e| sum + beta * other(e));
        }
        generic(face_points, ChildPoint::Vertex(v as u32))
    };
    if !parallel {
        // Each point written once, in order (no zero fill first).
        let face_points: Vec<DVec3> = (0..nf).map(face).collect();
        let mut out = Vec::with_capacity(child_count);
        out.extend_from_slice(&face_points);
        out.extend((0..ne).map(|e| edge(&face_points, e)));
        out.extend((0..parent.vertex_count).map(|v| vertex(&face_points, v)));
        return out;
    }
    let mut out = vec![DVec3::ZERO; child_count];
    let (faces, rest) = out.split_at_mut(nf);
    let (edges, vertices) = rest.split_at_mut(ne);
    {
        use rayon::prelude::*;
        faces
            .par_iter_mut()
            .enumerate()
            .for_each(|(f, p)| *p = face(f));
        let faces: &[DVec3] = faces;
        edges
            .par_iter_mut()
            .enumerate()
            .for_each(|(e, p)| *p = edge(faces, e));
        vertices
            .par_iter_mut()
            .enumerate()
            .for_each(|(v, p)| *p = vertex(faces, v));
    }
    out
}

/// [`interpolate`] through [`point_mask`] for every point.
fn interpolate_generic(
    parent: &Level,
    split: Split,
    options: Options,
    points: &[DVec3],
    parallel: bool,
) -> Vec<DVec3> {
    let child_count = child_count(parent, split);
    let nf = split.face_points(parent);
    let mut out = vec![DVec3::ZERO; child_count];
    let compute = |face_points: &[DVec3], i: usize| {
        let mut sink = PointSink {
            points,
            face_points,
            sum: DVec3::ZERO,
        };
        point_mask(parent, options, child_point(parent, split, i), &mut sink);
        sink.sum
    };
    let (faces, rest) = out.split_at_mut(nf);
    if parallel {
        use rayon::prelude::*;
        faces
            .par_iter_mut()
            .enumerate()
            .for_each(|(i, p)| *p = compute(&[], i));
        let faces: &[DVec3] = faces;
        rest.par_iter_mut()
            .enumerate()
            .for_each(|(i, p)| *p = compute(faces, nf + i));
    } else {
        for (i, p) in faces.iter_mut().enumerate() {
            *p = compute(&[], i);
        }
        let faces: &[DVec3] = faces;
        for (i, p) in rest.iter_mut().enumerate() {
            *p = compute(faces, nf + i);
        }
    }
    out
}
