//! Boolean operations on closed meshes: union, intersection and difference
//! (constructive solid geometry, seed 004's CSG tree; the engine is the
//! `boolmesh` crate, a pure-Rust port of Manifold's algorithm: Lévy-style
//! symbolic perturbation of the exact intersection predicates, so coplanar
//! faces, shared edges and vertices, identical operands and touching solids
//! give closed manifold results).
//!
//! [`boolean`] checks both operands (closed, manifold, polygonal), hands
//! their triangles to the engine with each triangle's source face attached,
//! and merges the engine's triangles back into polygons: every connected
//! piece of one source face that is a topological disc becomes one face,
//! so a face the cut did not touch comes back as the polygon it was
//! ([`merge`]). Pieces that are not discs (a face pierced by a cylinder
//! becomes an annulus) stay triangles.
//!
//! Why `boolmesh` rather than Manifold's C++ through a `-sys` crate or an
//! own implementation: see `docs/csg.md`.

mod crossing;
mod merge;

use crate::build::BuildError;
use crate::ids::{FaceId, HalfEdgeId, VertexId};
use crate::mesh::HalfEdgeMesh;
use boolmesh::prelude::{Manifold, OpType, compute_boolean};
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::fmt;

/// Which boolean: the points in A or B, in both, in A but not in B.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum BooleanOp {
    /// A ∪ B: the points inside either operand.
    #[default]
    Union,
    /// A ∩ B: the points inside both operands.
    Intersection,
    /// A − B: the points inside A and outside B.
    Difference,
}

impl BooleanOp {
    /// Every operation, in menu order.
    pub const ALL: [BooleanOp; 3] = [
        BooleanOp::Union,
        BooleanOp::Intersection,
        BooleanOp::Difference,
    ];
    /// The lower-case name (`"union"`, `"intersection"`, `"difference"`).
    pub fn label(self) -> &'static str {
        match self {
            BooleanOp::Union => "union",
            BooleanOp::Intersection => "intersection",
            BooleanOp::Difference => "difference",
        }
    }
}

impl fmt::Display for BooleanOp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.label())
    }
}

/// One of the two operands of a boolean.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Operand {
    /// The first operand, A (the one kept in A − B).
    A,
    /// The second operand, B.
    B,
}

impl fmt::Display for Operand {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Operand::A => "the first operand",
            Operand::B => "the second operand",
        })
    }
}

/// Why a boolean refused; the operands are never changed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BooleanError {
    /// An operand has no faces.
    #[error("{operand} has no faces")]
    EmptyOperand {
        /// Which operand.
        operand: Operand,
    },
    /// An operand has border edges, so it encloses no volume.
    #[error("{operand} is open: {border_edges} border edges (a boolean needs closed meshes)")]
    Open {
        /// Which operand.
        operand: Operand,
        /// How many of its edges have a face on one side only.
        border_edges: usize,
    },
    /// An operand is not a 2-manifold: vertices where separate fans of
    /// faces meet, or edges the engine found shared by more than two faces
    /// once coincident vertices were welded.
    #[error("{operand} is not manifold: {detail}")]
    NonManifold {
        /// Which operand.
        operand: Operand,
        /// What was found, in words with a count.
        detail: String,
    },
    /// An operand has faces with inner rings or without edges (made by the
    /// Euler operators); the engine takes polygons only.
    #[error("{operand} has {faces} faces with holes or without edges; fill or remove them first")]
    NotPolygonal {
        /// Which operand.
        operand: Operand,
        /// How many such faces.
        faces: usize,
    },
    /// Faces of an operand cross each other (two overlapping shells in one
    /// mesh, a surface folded through itself): the engine's inside and
    /// outside would be wrong.
    #[error("{operand} intersects itself: {face_pairs} pairs of its faces cross")]
    SelfIntersecting {
        /// Which operand.
        operand: Operand,
        /// How many pairs of its faces cross.
        face_pairs: usize,
    },
    /// An operand has a vertex at a non-finite position.
    #[error("{operand} has a vertex at a non-finite position")]
    NonFinite {
        /// Which operand.
        operand: Operand,
    },
    /// The result has no volume: disjoint operands intersected, an operand
    /// subtracted from itself or from something inside it. The document
    /// names the nodes ("the intersection of Box and Ball is empty").
    #[error("the {op} is empty")]
    EmptyResult {
        /// The operation.
        op: BooleanOp,
    },
    /// The engine failed.
    #[error("the boolean engine failed: {message}")]
    Engine {
        /// The engine's message.
        message: String,
    },
    /// The merged result could not be built as a half-edge mesh (a bug).
    #[error("the result is not a valid mesh: {0}")]
    Build(#[from] BuildError),
}

/// Where a face of a boolean's result comes from.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct FaceSource {
    /// The operand it is part of.
    pub operand: Operand,
    /// The operand's face.
    pub face: FaceId,
    /// True when the result face is the whole source face, corner for
    /// corner (the cut did not touch it): attributes of its corners (UVs)
    /// carry over unchanged.
    pub whole: bool,
}

/// A boolean's result with the provenance of its elements, for carrying
/// per-face and per-corner attributes (UVs, creases) of the operands over.
#[derive(Clone, Debug, PartialEq)]
pub struct BooleanResult {
    /// The closed, valid result.
    pub mesh: HalfEdgeMesh,
    /// The source of every face, indexed by [`FaceId::index`].
    pub faces: Vec<FaceSource>,
    /// For every vertex (by [`VertexId::index`]), the operand vertex at
    /// exactly its position, if it is one (vertices made by the cut are
    /// `None`).
    pub vertices: Vec<Option<(Operand, VertexId)>>,
}

impl BooleanResult {
    /// The operand corner a result corner (the half-edge of a face that
    /// leaves its vertex) continues: the corner of the source face at the
    /// same vertex, when both the face and the vertex come from one operand
    /// face. Used to carry UVs over.
    pub fn source_corner(
        &self,
        operands: [&HalfEdgeMesh; 2],
        h: HalfEdgeId,
    ) -> Option<(Operand, HalfEdgeId)> {
        let f = self.mesh.face(h)?;
        let src = self.faces.get(f.index())?;
        let (op, v) = (*self.vertices.get(self.mesh.origin(h).index())?)?;
        if op != src.operand {
            return None;
        }
        let m = operands[op as usize];
        m.face_halfedges(src.face)
            .find(|&c| m.origin(c) == v)
            .map(|c| (op, c))
    }
}

/// The boolean `op` of two closed meshes in one space, as a closed, valid
/// half-edge mesh. See [`boolean_with_sources`].
///
/// # Errors
/// See [`boolean_with_sources`].
pub fn boolean(
    a: &HalfEdgeMesh,
    b: &HalfEdgeMesh,
    op: BooleanOp,
    tolerance: f64,
) -> Result<HalfEdgeMesh, BooleanError> {
    boolean_with_sources(a, b, op, tolerance).map(|r| r.mesh)
}

/// The boolean `op` of `a` and `b` (both closed, in the same space) with
/// the source of every face and vertex.
///
/// Faces the cut did not touch come back as they were (the same polygon,
/// its vertices at the same positions); cut faces come back as one polygon
/// per piece that is a disc, as triangles otherwise; the faces of B inside
/// A come back reversed in A − B. Edges shorter than `tolerance` that the
/// cut makes are collapsed (the engine's own precision, 1e-12 of the
/// operands' size, is the floor), so no sliver is thinner than it.
/// Separate shells that touch only along an edge or at a vertex keep
/// separate copies of those vertices (a manifold mesh cannot share them).
///
/// Inverse: none (a boolean forgets the parts it removes).
///
/// # Errors
/// [`BooleanError`]: an empty, open, non-manifold, non-polygonal or
/// self-intersecting operand (named; the last with the count of its
/// crossing face pairs), an empty result, an engine failure.
///
/// Complexity: O((n + k) log n) for n triangles and k intersecting pairs
/// (the engine's BVH and the self-intersection check's), plus O(n) for
/// the conversions and the merge.
///
/// Source: seed 004 (CSG trees: union, intersection, difference of
/// solids); the engine follows Manifold (Lévy's symbolic perturbation,
/// <https://github.com/elalish/manifold/wiki/Manifold-Library>).
pub fn boolean_with_sources(
    a: &HalfEdgeMesh,
    b: &HalfEdgeMesh,
    op: BooleanOp,
    tolerance: f64,
) -> Result<BooleanResult, BooleanError> {
    let options = BooleanOptions {
        tolerance,
        ..BooleanOptions::default()
    };
    boolean_with_options(a, b, op, &options)
}

/// How [`boolean_with_options`] works.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct BooleanOptions {
    /// Edges shorter than this that the cut makes are collapsed (0: the
    /// engine's own precision).
    pub tolerance: f64,
    /// Whether to refuse operand A, B whose faces cross each other
    /// ([`BooleanError::SelfIntersecting`]); both by default. A caller
    /// that already checked an operand, or passes a boolean's own result
    /// (which the engine keeps free of crossings), can skip it.
    pub check_crossings: [bool; 2],
}

impl Default for BooleanOptions {
    fn default() -> Self {
        BooleanOptions {
            tolerance: 0.0,
            check_crossings: [true; 2],
        }
    }
}

/// [`boolean_with_sources`] with its options.
///
/// # Errors
/// As [`boolean_with_sources`].
pub fn boolean_with_options(
    a: &HalfEdgeMesh,
    b: &HalfEdgeMesh,
    op: BooleanOp,
    options: &BooleanOptions,
) -> Result<BooleanResult, BooleanError> {
    let input = stages::to_arrays(a, b)?;
    // The check runs beside the engine (a second core is free: the
    // engine runs on one); a crossing operand explains an engine failure,
    // so its error comes first.
    let (out, crossings) = rayon::join(
        || stages::engine(&input, op, options.tolerance),
        || stages::check_crossings(&input, options.check_crossings),
    );
    crossings?;
    let out = out?;
    let merged = stages::merge_back(&out, &input, [a, b]);
    stages::build(merged, [a, b])
}

/// Checks that `mesh` can be an operand of a boolean: not empty,
/// polygonal, closed, finite, manifold, and not crossing itself. The
/// errors name it as the first operand.
///
/// # Errors
/// The [`BooleanError`] a boolean with `mesh` as A would give for it.
///
/// Complexity: O(n log n) for n triangles (the self-intersection check).
pub fn check_operand(mesh: &HalfEdgeMesh) -> Result<(), BooleanError> {
    let t = Triangles::of(mesh, Operand::A, 0)?;
    let pairs = crossing::crossing_face_pairs(&t.points, &t.corners, &t.triangle_face);
    if pairs.is_empty() {
        Ok(())
    } else {
        Err(BooleanError::SelfIntersecting {
            operand: Operand::A,
            face_pairs: pairs.len(),
        })
    }
}

/// The faces of `mesh` that cross each other, as pairs (smaller id,
/// larger id), sorted: empty for a mesh that does not intersect itself.
/// Faces are tested through their triangles (as [`boolean`] passes them
/// to its engine); only certain crossings count (see the module
/// `crossing`: touching, coplanar overlap and crossings too shallow for
/// double precision to be sure of are not reported).
///
/// Complexity: O(n log n + k) for n triangles and k pairs of triangles
/// whose bounding boxes overlap.
pub fn self_intersections(mesh: &HalfEdgeMesh) -> Vec<(FaceId, FaceId)> {
    let t = Triangles::triangulate(mesh, 0);
    crossing::crossing_face_pairs(&t.points, &t.corners, &t.triangle_face)
        .into_iter()
        .map(|(f, g)| (t.faces[f as usize], t.faces[g as usize]))
        .map(|(f, g)| (f.min(g), f.max(g)))
        .collect()
}

/// The stages of [`boolean_with_sources`] one by one, public only for the
/// criterion benches that time each of them (`benches/csg.rs`); not an API.
#[doc(hidden)]
pub mod stages {
    use super::*;

    /// Both operands as the engine's input.
    pub struct Input {
        a: Triangles,
        b: Triangles,
    }

    /// Checks both operands (not empty, polygonal, closed, finite,
    /// manifold) and triangulates them.
    pub fn to_arrays(a: &HalfEdgeMesh, b: &HalfEdgeMesh) -> Result<Input, BooleanError> {
        let ta = Triangles::of(a, Operand::A, 0)?;
        let tb = Triangles::of(b, Operand::B, ta.faces.len())?;
        Ok(Input { a: ta, b: tb })
    }

    /// Refuses an operand whose faces cross each other (of those `which`
    /// names).
    pub fn check_crossings(input: &Input, which: [bool; 2]) -> Result<(), BooleanError> {
        let base = input.a.faces.len() as u32;
        let count = |t: &Triangles, check: bool, base: u32| {
            if !check {
                return 0;
            }
            let faces: Vec<u32> = t.triangle_face.iter().map(|f| f - base).collect();
            crossing::crossing_face_pairs(&t.points, &t.corners, &faces).len()
        };
        let (pairs_a, pairs_b) = (
            count(&input.a, which[0], 0),
            count(&input.b, which[1], base),
        );
        for (face_pairs, operand) in [(pairs_a, Operand::A), (pairs_b, Operand::B)] {
            if face_pairs > 0 {
                return Err(BooleanError::SelfIntersecting {
                    operand,
                    face_pairs,
                });
            }
        }
        Ok(())
    }

    /// The engine's boolean (building its input meshes included).
    pub fn engine(
        input: &Input,
        op: BooleanOp,
        tolerance: f64,
    ) -> Result<Manifold<f64>, BooleanError> {
        let mut ma = input.a.manifold(Operand::A)?;
        let mut mb = input.b.manifold(Operand::B)?;
        if tolerance.is_finite() && tolerance > 0.0 {
            for m in [&mut ma, &mut mb] {
                m.eps = m.eps.max(tolerance);
                m.tol = m.tol.max(tolerance);
            }
        }
        let kind = match op {
            BooleanOp::Union => OpType::Add,
            BooleanOp::Intersection => OpType::Intersect,
            BooleanOp::Difference => OpType::Subtract,
        };
        let out = match compute_boolean(&ma, &mb, kind) {
            Ok(out) => out,
            // The engine refuses to build an empty mesh.
            Err(m) if m.starts_with("empty") => return Err(BooleanError::EmptyResult { op }),
            Err(message) => return Err(BooleanError::Engine { message }),
        };
        if out.hs.is_empty() {
            return Err(BooleanError::EmptyResult { op });
        }
        Ok(out)
    }

    /// The engine's triangles merged back into polygons by source face.
    pub fn merge_back(
        out: &Manifold<f64>,
        input: &Input,
        operands: [&HalfEdgeMesh; 2],
    ) -> merge::Merged {
        let positions: Vec<DVec3> = out.ps.iter().map(|p| DVec3::new(p.x, p.y, p.z)).collect();
        let tails: Vec<usize> = out.hs.iter().map(|h| h.tail).collect();
        let pairs: Vec<usize> = out.hs.iter().map(|h| h.pair).collect();
        let sources: Vec<u64> = out
            .vals
            .iter()
            .step_by(3)
            .map(|v| v.round().max(0.0) as u64)
            .collect();
        let (ta, tb) = (&input.a.faces, &input.b.faces);
        let na = ta.len() as u64;
        let source_of = |s: u64| {
            if s < na {
                (Operand::A, ta[s as usize])
            } else {
                let i = (s - na).min(tb.len() as u64 - 1);
                (Operand::B, tb[i as usize])
            }
        };
        merge::merge(&positions, &tails, &pairs, &sources, operands, &source_of)
    }

    /// The half-edge mesh of the merged polygons, with the operand vertex
    /// at each of its vertices' places.
    pub fn build(
        merged: merge::Merged,
        operands: [&HalfEdgeMesh; 2],
    ) -> Result<BooleanResult, BooleanError> {
        let polygons: Vec<&[u32]> = merged.polygons().collect();
        let mesh = HalfEdgeMesh::from_polygons(&merged.positions, &polygons)?;
        // Vertices at an operand vertex's exact position came from it (A's
        // first where both have one).
        let mut at: PositionMap = PositionMap::with_capacity_and_hasher(
            operands[0].vertex_count() + operands[1].vertex_count(),
            Default::default(),
        );
        for (m, op) in [(operands[1], Operand::B), (operands[0], Operand::A)] {
            for v in m.vertices() {
                at.insert(key(m.position(v)), (op, v));
            }
        }
        let vertices = merged
            .positions
            .iter()
            .map(|&p| at.get(&key(p)).copied())
            .collect();
        Ok(BooleanResult {
            mesh,
            faces: merged.sources,
            vertices,
        })
    }
}

/// Exact positions (their bits) to what is there.
type PositionMap = std::collections::HashMap<
    [u64; 3],
    (Operand, VertexId),
    std::hash::BuildHasherDefault<PositionHasher>,
>;

/// A fast hasher for position bits (SipHash's protection against chosen
/// keys is not needed here): each 64-bit word is mixed into the state by
/// the SplitMix64 finalizer (Steele, Lea and Flood, "Fast Splittable
/// Pseudorandom Number Generators", 2014), so positions on a coarse grid,
/// whose low bits are all zero, still spread over the table.
#[derive(Default)]
struct PositionHasher(u64);

impl std::hash::Hasher for PositionHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }
    fn write_u64(&mut self, x: u64) {
        let mut z = (self.0 ^ x).wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        self.0 = z ^ (z >> 31);
    }
    fn finish(&self) -> u64 {
        self.0
    }
}

fn key(p: DVec3) -> [u64; 3] {
    // +0.0 and -0.0 are one position.
    [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f64::to_bits)
}

/// An operand as the engine's input: flat positions, triangle corners and
/// each corner's source face number (the engine interpolates it over the
/// pieces it makes, so it stays constant on each source face).
struct Triangles {
    /// Positions, compactly numbered, as `points` and flat for the engine.
    points: Vec<DVec3>,
    positions: Vec<f64>,
    corners: Vec<usize>,
    values: Vec<f64>,
    /// The face number of each triangle (`base` + its index in `faces`).
    triangle_face: Vec<u32>,
    faces: Vec<FaceId>,
}

impl Triangles {
    /// `base`: the number of the first face (B's follow A's).
    fn of(m: &HalfEdgeMesh, operand: Operand, base: usize) -> Result<Triangles, BooleanError> {
        if m.face_count() == 0 {
            return Err(BooleanError::EmptyOperand { operand });
        }
        let not_polygon = m.faces().filter(|&f| !m.is_polygon_face(f)).count();
        if not_polygon > 0 {
            return Err(BooleanError::NotPolygonal {
                operand,
                faces: not_polygon,
            });
        }
        let border_edges = m.edges().filter(|&e| m.is_boundary_edge(e)).count();
        if border_edges > 0 {
            return Err(BooleanError::Open {
                operand,
                border_edges,
            });
        }
        if m.vertices().any(|v| !m.position(v).is_finite()) {
            return Err(BooleanError::NonFinite { operand });
        }
        // A vertex whose fan does not reach all its half-edges joins
        // separate fans (two cones tip to tip).
        let mut outgoing = vec![0usize; m.vertex_capacity()];
        for h in m.halfedges() {
            outgoing[m.origin(h).index()] += 1;
        }
        let pinched = m
            .vertices()
            .filter(|&v| m.vertex_outgoing(v).count() != outgoing[v.index()])
            .count();
        if pinched > 0 {
            return Err(BooleanError::NonManifold {
                operand,
                detail: format!("{pinched} vertices join separate fans of faces"),
            });
        }
        Ok(Self::triangulate(m, base))
    }

    /// The triangles of a polygon mesh, without checks.
    fn triangulate(m: &HalfEdgeMesh, base: usize) -> Triangles {
        // Compact vertex numbers; the engine welds equal positions itself.
        let mut index = vec![usize::MAX; m.vertex_capacity()];
        let mut points = Vec::with_capacity(m.vertex_count());
        let mut positions = Vec::with_capacity(3 * m.vertex_count());
        for (i, v) in m.vertices().enumerate() {
            index[v.index()] = i;
            let p = m.position(v);
            points.push(p);
            positions.extend([p.x, p.y, p.z]);
        }
        let mut corners = Vec::with_capacity(6 * m.face_count());
        let mut values = Vec::with_capacity(6 * m.face_count());
        let mut triangle_face = Vec::with_capacity(2 * m.face_count());
        let mut faces = Vec::with_capacity(m.face_count());
        for f in m.faces() {
            let n = base + faces.len();
            for t in crate::query::triangulate_face(m, f) {
                corners.extend(t.map(|v| index[v.index()]));
                values.extend([n as f64; 3]);
                triangle_face.push(n as u32);
            }
            faces.push(f);
        }
        Triangles {
            points,
            positions,
            corners,
            values,
            triangle_face,
            faces,
        }
    }

    fn manifold(&self, operand: Operand) -> Result<Manifold<f64>, BooleanError> {
        Manifold::new_with_values(&self.positions, &self.corners, &self.values).map_err(|message| {
            if message.contains("more than two faces") || message.contains("not manifold") {
                BooleanError::NonManifold {
                    operand,
                    detail: message,
                }
            } else {
                BooleanError::Engine { message }
            }
        })
    }
}
