//! Spin and screw: sweeping a profile around an axis in steps (Blender's
//! edit-mode Spin, `bmo_spin_exec`, and its Screw tool), built from
//! [`HalfEdgeMesh::delete_faces`] and [`HalfEdgeMesh::add_face`] on a copy
//! that is validated before it replaces the mesh.
//!
//! Blender's spin is a repeated extrude-region, each copy rotated by
//! `angle / steps` about the axis (and, for a screw, moved along it). Hedra
//! builds the same surface in one pass:
//!
//! - **A face profile** (a region) is swept like a region extrusion: its
//!   outline gets a ring of side quads per step, its faces end up at the end
//!   of the sweep as the end cap (the inner vertices of the region keep their
//!   ids and move there, as in [`extrude_region`](super::extrude_region)).
//!   When no face outside the region borders it (a lone plane), the region is
//!   also kept at the start as the start cap, so the sweep is a closed solid;
//!   when it is attached to the rest of the mesh the sweep grows out of it,
//!   as Blender's extrude deletes the original faces in that case.
//! - **An edge profile** must be boundary edges (an edge with faces on both
//!   sides has no open side to grow from): each step adds a ring of quads on
//!   the open side, as [`extrude_boundary_edges`](super::extrude_boundary_edges).
//!   A full turn of them is refused: its last step would come back onto the
//!   face beside the edges, giving each a third face (Blender makes them
//!   non-manifold; Hedra's meshes stay manifold).
//! - **A full turn** (`|angle| = 2π` within [`FULL_TURN_TOLERANCE`], no
//!   advance along the axis) joins the last step to the first, with no
//!   duplicate vertices and no caps: Blender's spin with its merge of the
//!   ends. A square face spun this way is a torus.
//! - **Vertices on the axis** (within [`AXIS_TOLERANCE`] × the profile's
//!   size) are not copied: every step shares them, so the faces that touch
//!   them are triangles (a half disc whose diameter lies on the axis spins
//!   into a closed sphere with triangle fans at the poles). Blender copies
//!   them and leaves the doubles to Merge by Distance; a screw, whose steps
//!   move along the axis, copies them too.
//!
//! Rotation follows the right-hand rule about `axis`: a positive angle turns
//! counter-clockwise seen from the tip of the axis.

use super::ModelingError;
use super::common::{add_faces_in_any_order, check_faces};
use crate::ids::{EdgeId, FaceId, VertexId};
use crate::mesh::HalfEdgeMesh;
use glam::{DQuat, DVec3};
use std::collections::{BTreeSet, HashMap, HashSet};
use std::f64::consts::TAU;

/// How close (in radians) a spin's angle must be to a full turn for the
/// ends to be joined.
pub const FULL_TURN_TOLERANCE: f64 = 1e-9;

/// How close to the axis a profile vertex must be to be shared by every
/// step, as a fraction of the profile's size (its largest distance from the
/// centre, at least 1).
pub const AXIS_TOLERANCE: f64 = 1e-6;

/// The most steps one sweep may take (a screw's turns × steps per turn):
/// more would build meshes of millions of faces from one typo, as the
/// primitives' `MAX_SEGMENTS` guards against.
pub const MAX_SPIN_STEPS: u32 = 65_536;

/// What [`spin`] and [`screw`] sweep.
#[derive(Clone, Debug, PartialEq)]
pub enum SpinProfile {
    /// A region of faces, swept as a solid (Blender's spin with faces
    /// selected).
    Faces(Vec<FaceId>),
    /// Boundary edges, swept as a surface of quads (Blender's spin with only
    /// edges selected).
    Edges(Vec<EdgeId>),
}

/// What [`spin`] and [`screw`] made, so that an editor can select the end
/// of the sweep as Blender does.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SpinResult {
    /// Every face made: sides, triangles at the axis, caps.
    pub faces: Vec<FaceId>,
    /// Every edge made.
    pub edges: Vec<EdgeId>,
    /// Every vertex made (the copies of the profile at each step).
    pub vertices: Vec<VertexId>,
    /// The start cap: the region's faces at the start of the sweep (only for
    /// a face profile with nothing beside it, when the turn is not full).
    pub start_faces: Vec<FaceId>,
    /// The end cap: the region's faces at the end of the sweep (a face
    /// profile, when the turn is not full).
    pub end_faces: Vec<FaceId>,
    /// The profile's edges at the end of the sweep (for a full turn, the
    /// start's, which are the same): what Blender leaves selected.
    pub end_edges: Vec<EdgeId>,
    /// The profile's vertices at the end of the sweep.
    pub end_vertices: Vec<VertexId>,
    /// The sweep made a full turn and its ends were joined.
    pub closed: bool,
}

/// Spins `profile` by `angle` radians about the axis through `center` along
/// `axis`, in `steps` equal steps (Blender's Spin). A region's outline gets
/// a ring of side faces per step and its faces end as the end cap (plus a
/// start cap when nothing borders it); boundary edges get a ring of quads
/// per step. A full turn (within [`FULL_TURN_TOLERANCE`]) joins the last
/// step to the first; vertices within [`AXIS_TOLERANCE`] of the axis are
/// shared by every step (faces there are triangles). Positive angles turn
/// counter-clockwise seen from the axis' tip. The new faces follow the
/// orientation of the faces beside the profile; a region with nothing
/// beside it makes a closed solid, oriented with its normals pointing out
/// (Blender leaves that to its Flip Normals option).
///
/// Counts: an edge profile of `e` edges over `v` vertices (none on the axis)
/// adds `e · steps` faces and `v · steps` vertices; a region of `f` faces
/// with `o` outline edges over `u` outline vertices adds `o · steps` sides,
/// `u · steps` vertices (`u · (steps − 1)` for a full turn) and its caps.
/// Complexity: O(profile size × steps), plus the validation of the mesh.
///
/// Inverse: none as one operator (deleting `faces` leaves the copies of the
/// profile); the document's undo restores the mesh.
///
/// # Errors
/// [`ModelingError::Empty`] / [`ModelingError::Missing`] for the profile,
/// [`ModelingError::SpinEdgeNotBoundary`] for an edge with faces on both
/// sides, [`ModelingError::Parameter`] for a zero or non-finite axis, a
/// non-finite centre, a zero or non-finite angle, zero steps (fewer than
/// 3 for a full turn, more than [`MAX_SPIN_STEPS`]), [`ModelingError::FullTurnMeetsFace`] when a full
/// turn would come back onto a face beside the profile,
/// [`ModelingError::Invalid`] when the sweep cannot be built manifold. The
/// mesh is unchanged on error.
pub fn spin(
    mesh: &mut HalfEdgeMesh,
    profile: &SpinProfile,
    center: DVec3,
    axis: DVec3,
    angle: f64,
    steps: u32,
) -> Result<SpinResult, ModelingError> {
    if !angle.is_finite() || angle == 0.0 {
        return Err(ModelingError::Parameter {
            what: "angle",
            allowed: "finite and not zero",
            value: angle.to_string(),
        });
    }
    let sweep = Sweep::new(center, axis, angle, steps, 0.0)?;
    sweep.run(mesh, profile)
}

/// Screws `profile` about the axis through `center` along `axis`: `turns`
/// full turns of `steps_per_turn` steps each, advancing `pitch` along the
/// axis per turn (Blender's Screw, whose advance per turn comes from the
/// profile's end vertices; here it is a number, negative to go against
/// `axis`). The ends of a screw are never joined, and vertices on the axis
/// are copied like the others; with `pitch` 0 it is [`spin`] by
/// `turns × 2π` (one turn closes).
///
/// Counts: `turns × steps_per_turn` steps of [`spin`]'s.
///
/// # Errors
/// As [`spin`]; [`ModelingError::Parameter`] also for zero turns or a
/// non-finite pitch.
pub fn screw(
    mesh: &mut HalfEdgeMesh,
    profile: &SpinProfile,
    center: DVec3,
    axis: DVec3,
    turns: u32,
    steps_per_turn: u32,
    pitch: f64,
) -> Result<SpinResult, ModelingError> {
    if turns == 0 {
        return Err(ModelingError::Parameter {
            what: "turns",
            allowed: "at least 1",
            value: "0".to_string(),
        });
    }
    if !pitch.is_finite() {
        return Err(ModelingError::Parameter {
            what: "pitch",
            allowed: "finite",
            value: pitch.to_string(),
        });
    }
    if steps_per_turn == 0 {
        return Err(zero_steps());
    }
    let angle = TAU * f64::from(turns);
    let steps = turns.saturating_mul(steps_per_turn);
    let sweep = Sweep::new(
        center,
        axis,
        angle,
        steps,
        pitch / f64::from(steps_per_turn),
    )?;
    sweep.run(mesh, profile)
}

fn zero_steps() -> ModelingError {
    ModelingError::Parameter {
        what: "steps",
        allowed: "at least 1",
        value: "0".to_string(),
    }
}

/// One sweep: the rigid motion of each step and whether the ends join.
struct Sweep {
    center: DVec3,
    /// Unit length.
    axis: DVec3,
    step_angle: f64,
    /// Distance along `axis` per step.
    step_advance: f64,
    steps: usize,
    closed: bool,
}

impl Sweep {
    fn new(
        center: DVec3,
        axis: DVec3,
        angle: f64,
        steps: u32,
        step_advance: f64,
    ) -> Result<Sweep, ModelingError> {
        let unit = axis.normalize_or_zero();
        if unit == DVec3::ZERO || !unit.is_finite() || !center.is_finite() {
            return Err(ModelingError::Parameter {
                what: "spin axis",
                allowed: "a finite centre and a non-zero axis",
                value: format!("centre {center}, axis {axis}"),
            });
        }
        if steps == 0 {
            return Err(zero_steps());
        }
        if steps > MAX_SPIN_STEPS {
            return Err(ModelingError::Parameter {
                what: "steps",
                allowed: "at most 65536 in all",
                value: steps.to_string(),
            });
        }
        let closed = step_advance == 0.0 && (angle.abs() - TAU).abs() <= FULL_TURN_TOLERANCE;
        if closed && steps < 3 {
            return Err(ModelingError::Parameter {
                what: "steps",
                allowed: "at least 3 for a full turn",
                value: steps.to_string(),
            });
        }
        Ok(Sweep {
            center,
            axis: unit,
            step_angle: angle / f64::from(steps),
            step_advance,
            steps: steps as usize,
            closed,
        })
    }

    /// Where step `k` puts a point: rotated by `k` step angles about the
    /// axis, moved `k` step advances along it.
    fn place(&self, p: DVec3, k: usize) -> DVec3 {
        let turn = DQuat::from_axis_angle(self.axis, self.step_angle * k as f64);
        self.center + turn * (p - self.center) + self.axis * (self.step_advance * k as f64)
    }

    fn distance_to_axis(&self, p: DVec3) -> f64 {
        let r = p - self.center;
        (r - self.axis * r.dot(self.axis)).length()
    }

    fn run(
        &self,
        mesh: &mut HalfEdgeMesh,
        profile: &SpinProfile,
    ) -> Result<SpinResult, ModelingError> {
        let read = read_profile(mesh, profile, self.closed)?;
        let old_vertices = mesh.vertex_capacity();
        let old_edges = mesh.edge_capacity();
        let old_faces = mesh.face_capacity();
        let n = self.steps;

        // Outline vertices stay at the start and get a copy per step (the
        // last is the start again for a full turn); vertices on the axis are
        // shared by every step. Inner vertices of a region move to the end.
        let outline_vertices: BTreeSet<VertexId> =
            read.outline.iter().flat_map(|&(a, b)| [a, b]).collect();
        let mut inner: Vec<VertexId> = Vec::new();
        for p in &read.caps {
            for &v in p {
                if !outline_vertices.contains(&v) && !inner.contains(&v) {
                    inner.push(v);
                }
            }
        }
        let size = outline_vertices
            .iter()
            .chain(&inner)
            .map(|&v| mesh.position(v).distance(self.center))
            .fold(1.0, f64::max);
        let on_axis = |p: DVec3| {
            self.step_advance == 0.0 && self.distance_to_axis(p) <= AXIS_TOLERANCE * size
        };

        let mut work = mesh.clone();
        if let SpinProfile::Faces(_) = profile {
            work.delete_faces(&read.region, true);
        }
        let mut ring: HashMap<VertexId, Vec<VertexId>> = HashMap::new();
        for &v in &outline_vertices {
            let p = work.position(v);
            let slots = if on_axis(p) {
                vec![v; n + 1]
            } else {
                let mut slots = Vec::with_capacity(n + 1);
                slots.push(v);
                for k in 1..n {
                    slots.push(work.add_vertex(self.place(p, k))?);
                }
                slots.push(if self.closed {
                    v
                } else {
                    work.add_vertex(self.place(p, n))?
                });
                slots
            };
            ring.insert(v, slots);
        }
        let with_start_cap = read.isolated && !self.closed;
        let mut start_copy: HashMap<VertexId, VertexId> = HashMap::new();
        if !self.closed {
            for &v in &inner {
                let p = work.position(v);
                if with_start_cap {
                    start_copy.insert(v, work.add_vertex(p)?);
                }
                work.set_position(v, self.place(p, n));
            }
        }

        // Side faces step by step, then the end cap, then the start cap.
        let mut polygons: Vec<Vec<VertexId>> = Vec::new();
        for k in 0..n {
            for &(a, b) in &read.outline {
                let mut quad = vec![ring[&a][k], ring[&b][k], ring[&b][k + 1], ring[&a][k + 1]];
                quad.dedup();
                if quad.len() > 1 && quad[0] == quad[quad.len() - 1] {
                    quad.pop();
                }
                if quad.len() >= 3 {
                    polygons.push(quad);
                }
            }
        }
        let sides = polygons.len();
        if !self.closed {
            for p in &read.caps {
                polygons.push(p.iter().map(|v| ring.get(v).map_or(*v, |r| r[n])).collect());
            }
        }
        let ends = polygons.len();
        if with_start_cap {
            for p in &read.caps {
                polygons.push(
                    p.iter()
                        .rev()
                        .map(|v| ring.get(v).map_or_else(|| start_copy[v], |r| r[0]))
                        .collect(),
                );
            }
        }
        let added = add_faces_in_any_order(&mut work, polygons, "the spin")?;
        if self.closed {
            for &v in &inner {
                work.free_vertex(v);
            }
        }

        // A region with nothing beside it is a solid of its own: turn it
        // outwards (its sign follows the sweep's direction otherwise).
        if read.isolated && self.signed_volume(&work, &added) < 0.0 {
            let seed = work.face_vertices(added[0]).next();
            let (comp, _) = work.components();
            let new: HashSet<FaceId> = added.iter().copied().collect();
            if let Some(seed) = seed {
                let only_new = work
                    .faces()
                    .filter(|&f| {
                        work.face_vertices(f)
                            .any(|v| comp[v.index()] == comp[seed.index()])
                    })
                    .all(|f| new.contains(&f));
                if only_new {
                    work.reverse_components(&[seed]);
                }
            }
        }
        work.validate()?;

        let mut end_vertices: Vec<VertexId> = outline_vertices.iter().map(|v| ring[v][n]).collect();
        end_vertices.extend(inner.iter().filter(|_| !self.closed));
        let end_faces = added[sides..ends].to_vec();
        let mut end_edges: Vec<EdgeId> = read
            .outline
            .iter()
            .filter_map(|(a, b)| work.find_edge(ring[a][n], ring[b][n]))
            .collect();
        end_edges.extend(
            end_faces
                .iter()
                .flat_map(|&f| work.face_halfedges(f).map(|h| h.edge())),
        );
        end_edges.sort();
        end_edges.dedup();
        let result = SpinResult {
            faces: added.clone(),
            edges: work.edges().filter(|e| e.index() >= old_edges).collect(),
            vertices: work
                .vertices()
                .filter(|v| v.index() >= old_vertices)
                .collect(),
            start_faces: added[ends..].to_vec(),
            end_faces,
            end_edges,
            end_vertices,
            closed: self.closed,
        };
        debug_assert!(result.faces.iter().all(|f| f.index() >= old_faces));
        *mesh = work;
        Ok(result)
    }

    /// The signed volume enclosed by `faces` (a closed shell), about the
    /// centre: Σ (centroid − centre) · area vector / 3.
    fn signed_volume(&self, mesh: &HalfEdgeMesh, faces: &[FaceId]) -> f64 {
        faces
            .iter()
            .map(|&f| (mesh.face_centroid(f) - self.center).dot(mesh.face_area_vector(f)) / 3.0)
            .sum()
    }
}

/// A profile read off the mesh: the outline as directed pairs `(a, b)` whose
/// side faces run `a → b`, the region's faces and their corners (caps), and
/// whether nothing but the region borders its outline.
struct Profile {
    region: Vec<FaceId>,
    outline: Vec<(VertexId, VertexId)>,
    caps: Vec<Vec<VertexId>>,
    isolated: bool,
}

fn read_profile(
    mesh: &HalfEdgeMesh,
    profile: &SpinProfile,
    closed: bool,
) -> Result<Profile, ModelingError> {
    match profile {
        SpinProfile::Faces(faces) => {
            check_faces(mesh, faces)?;
            let mut region = faces.clone();
            region.sort();
            region.dedup();
            let in_region = |f: Option<FaceId>| f.is_some_and(|f| region.binary_search(&f).is_ok());
            let mut outline = Vec::new();
            let mut beside = None;
            for &f in &region {
                for h in mesh.face_halfedges(f) {
                    let other = mesh.face(h.twin());
                    if in_region(other) {
                        continue;
                    }
                    if let (None, Some(face)) = (beside, other) {
                        beside = Some((h.edge(), face));
                    }
                    outline.push((mesh.origin(h), mesh.target(h)));
                }
            }
            if let (true, Some((edge, face))) = (closed, beside) {
                return Err(ModelingError::FullTurnMeetsFace { edge, face });
            }
            let caps = region
                .iter()
                .map(|&f| mesh.face_vertices(f).collect())
                .collect();
            Ok(Profile {
                outline,
                caps,
                isolated: beside.is_none(),
                region,
            })
        }
        SpinProfile::Edges(edges) => {
            if edges.is_empty() {
                return Err(ModelingError::Empty("no edges"));
            }
            let mut edges = edges.clone();
            edges.sort();
            edges.dedup();
            let mut outline = Vec::with_capacity(edges.len());
            for e in edges {
                if !mesh.is_edge(e) {
                    return Err(ModelingError::Missing(e.into()));
                }
                let h = [e.halfedge(0), e.halfedge(1)]
                    .into_iter()
                    .find(|&h| mesh.is_boundary_halfedge(h))
                    .ok_or(ModelingError::SpinEdgeNotBoundary { edge: e })?;
                if let (true, Some(face)) = (closed, mesh.face(h.twin())) {
                    return Err(ModelingError::FullTurnMeetsFace { edge: e, face });
                }
                outline.push((mesh.origin(h), mesh.target(h)));
            }
            Ok(Profile {
                region: Vec::new(),
                outline,
                caps: Vec::new(),
                isolated: false,
            })
        }
    }
}
