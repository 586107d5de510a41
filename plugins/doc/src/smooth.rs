//! The smooth preview of a mesh with a subdivision modifier, Bevy-free: a
//! kept refinement of the cage ([`SmoothRefinement`]) whose stencils are
//! re-applied while only cage positions change (libigl's "build S once":
//! a drag recomputes only what the moved vertices influence), and the
//! render buffers of the refined faces (normals, triangles).

use crate::render::{RenderBuffers, Rewritten, SharpSplit, split_sharp_corners};
use crate::{Shading, SubdivisionModifier};
use hedra_geom::subdivision::{
    Creases, INFINITE_SHARPNESS, LevelPoints, Refiner, StencilEvaluation, StencilTable,
    limit_normals,
};
use hedra_geom::{DVec3, HalfEdgeMesh};
use std::collections::HashSet;
use std::sync::Arc;
use std::sync::OnceLock;

/// Above this many refined faces a drag keeps every level's points
/// instead of stencils (whose weights would take hundreds of megabytes)
/// and recomputes the points the moved vertices reach through the masks
/// ([`Refiner::update_kept`]).
pub const STENCIL_FACE_LIMIT: usize = 400_000;

/// The refinement of one cage, kept while its connectivity, creases and
/// modifier stay.
pub struct SmoothRefinement {
    cage: Arc<HalfEdgeMesh>,
    creases: Creases,
    modifier: SubdivisionModifier,
    refiner: Arc<Refiner>,
    /// Made on the first drag, or beforehand on a worker thread
    /// ([`stencil_job`](SmoothRefinement::stencil_job)): the weights and
    /// every level's points.
    stencils: Option<(StencilTable, StencilEvaluation)>,
    /// Above [`STENCIL_FACE_LIMIT`]: every level's points, made on first
    /// use and updated where the cage moved.
    kept: Option<LevelPoints>,
    /// The refined corners split along infinitely sharp creases, made on
    /// first use and kept while only positions change.
    sharp: OnceLock<SharpSplit>,
    /// Where each refined face's corners start in the flat-shaded
    /// attributes (`u32::MAX`: a hidden face), made on the first update
    /// of a few faces.
    flat_starts: OnceLock<Vec<u32>>,
}

/// A stencil table with the evaluation of the cage it was built for, made
/// by a [`SmoothRefinement::stencil_job`] (on any thread: it is `Send`) and
/// handed back with [`SmoothRefinement::set_stencils`].
pub struct PreparedStencils {
    table: StencilTable,
    eval: StencilEvaluation,
}

/// Why a cage could not be refined.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(transparent)]
pub struct SmoothError(#[from] pub hedra_geom::subdivision::SubdivisionError);

/// The message, for callers that report refinement failures as text (the
/// viewport's background jobs).
impl From<SmoothError> for String {
    fn from(e: SmoothError) -> String {
        e.to_string()
    }
}

impl SmoothRefinement {
    /// Refines `cage` to the modifier's viewport level.
    ///
    /// # Errors
    /// The subdivision's [`SmoothError`] (Loop on quads, too many faces).
    pub fn new(
        cage: &Arc<HalfEdgeMesh>,
        creases: &Creases,
        modifier: &SubdivisionModifier,
    ) -> Result<SmoothRefinement, SmoothError> {
        let refiner = Refiner::new(cage, creases, modifier.options, modifier.viewport_level)?;
        Ok(Self::from_refiner(cage, creases, modifier, refiner))
    }

    /// A refinement made elsewhere (a cancellable background job).
    pub fn from_refiner(
        cage: &Arc<HalfEdgeMesh>,
        creases: &Creases,
        modifier: &SubdivisionModifier,
        refiner: Refiner,
    ) -> SmoothRefinement {
        SmoothRefinement {
            cage: cage.clone(),
            creases: creases.clone(),
            modifier: *modifier,
            refiner: Arc::new(refiner),
            stencils: None,
            kept: None,
            sharp: OnceLock::new(),
            flat_starts: OnceLock::new(),
        }
    }

    /// The stencil build as a job that owns its inputs (the shared
    /// refinement and the cage), so the app can run it on a worker thread
    /// when the refinement is made (topology, creases or modifier changed)
    /// instead of on the first drag frame (about 200 ms for a 10,000-face
    /// cage at level 3). `None` when the stencils exist already or the
    /// refinement is above [`STENCIL_FACE_LIMIT`].
    pub fn stencil_job(&self) -> Option<impl FnOnce() -> PreparedStencils + Send + 'static> {
        if self.stencils.is_some() || self.refiner.face_count() > STENCIL_FACE_LIMIT {
            return None;
        }
        let (refiner, cage) = (Arc::clone(&self.refiner), Arc::clone(&self.cage));
        Some(move || {
            let table = refiner.stencils();
            let eval = table.evaluate(&refiner.cage_positions(&cage));
            PreparedStencils { table, eval }
        })
    }

    /// True when the stencils are there (a drag re-applies them).
    pub fn has_stencils(&self) -> bool {
        self.stencils.is_some()
    }

    /// Installs stencils a [`stencil_job`](Self::stencil_job) of this
    /// refinement made; later [`points`](Self::points) calls update them.
    /// Stencils that exist already are kept.
    pub fn set_stencils(&mut self, stencils: PreparedStencils) {
        if self.stencils.is_none() {
            self.stencils = Some((stencils.table, stencils.eval));
        }
    }

    /// True when `cage` differs from the refined cage at most in positions.
    pub fn fits(
        &self,
        cage: &HalfEdgeMesh,
        creases: &Creases,
        modifier: &SubdivisionModifier,
    ) -> bool {
        self.modifier.options == modifier.options
            && self.modifier.viewport_level == modifier.viewport_level
            && self.creases == *creases
            && (std::ptr::eq(&*self.cage, cage) || self.cage.same_connectivity(cage))
    }

    /// The refined positions of `cage` (which [`fits`](Self::fits)): the
    /// first call refines through the masks; later calls re-apply the
    /// stencils to the cage vertices that moved since the last call.
    pub fn points(&mut self, cage: &Arc<HalfEdgeMesh>) -> Vec<DVec3> {
        self.points_with(cage, true)
    }

    /// As [`points`](Self::points), but while `build_stencils` is false
    /// (their [`stencil_job`](Self::stencil_job) runs elsewhere) a moved
    /// cage is refined through the masks instead of building the stencils
    /// on this frame.
    pub fn points_with(&mut self, cage: &Arc<HalfEdgeMesh>, build_stencils: bool) -> Vec<DVec3> {
        if self.refiner.face_count() > STENCIL_FACE_LIMIT {
            self.update_kept(cage);
            return self.kept.as_ref().expect("made above").points().to_vec();
        }
        let first = self.stencils.is_none() && (!build_stencils || Arc::ptr_eq(&self.cage, cage));
        self.cage = cage.clone();
        let cage_points = self.refiner.cage_positions(cage);
        if first {
            return self.refiner.refine(&cage_points);
        }
        let refiner = &*self.refiner;
        let (table, eval) = self.stencils.get_or_insert_with(|| {
            let table = refiner.stencils();
            let eval = table.evaluate(&cage_points);
            (table, eval)
        });
        let moved = moved_between(eval.cage(), &cage_points);
        if !moved.is_empty() {
            table.update(eval, &moved);
        }
        eval.points().to_vec()
    }

    /// Makes or updates the kept levels for `cage`: the refined points
    /// that were recomputed (`None`: all of them).
    fn update_kept(&mut self, cage: &Arc<HalfEdgeMesh>) -> Option<Vec<u32>> {
        self.cage = cage.clone();
        let cage_points = self.refiner.cage_positions(cage);
        let Some(kept) = &mut self.kept else {
            self.kept = Some(self.refiner.refine_kept(&cage_points));
            return None;
        };
        let moved = moved_between(kept.cage(), &cage_points);
        self.refiner.update_kept(kept, &moved)
    }

    /// Rewrites `positions` and `normals` (the [`attributes`](Self::attributes)
    /// of this refinement) for `cage` (which [`fits`](Self::fits)). Flat
    /// shaded above [`STENCIL_FACE_LIMIT`], only the corners of the faces
    /// at the recomputed points are written (a drag of one vertex of a
    /// 100k-face cage at level 2 rewrites a few hundred of 6.4M corners);
    /// otherwise all, from [`points_with`](Self::points_with). Says which
    /// (the caller's bounds of the positions follow from it).
    pub fn update_attributes(
        &mut self,
        cage: &Arc<HalfEdgeMesh>,
        build_stencils: bool,
        shading: Shading,
        positions: &mut Vec<[f32; 3]>,
        normals: &mut Vec<[f32; 3]>,
    ) -> Rewritten {
        let patch = shading == Shading::Flat
            && self.kept.is_some()
            && self.refiner.face_count() > STENCIL_FACE_LIMIT
            && positions.len() == normals.len();
        if !patch {
            let points = self.points_with(cage, build_stencils);
            self.attributes_into(&points, shading, positions, normals);
            return Rewritten::All;
        }
        let Some(recomputed) = self.update_kept(cage) else {
            let points = self.kept.as_ref().expect("kept").points();
            let split = self.sharp_split(shading);
            attributes_into(&self.refiner, points, shading, split, positions, normals);
            return Rewritten::All;
        };
        let mut written = Rewritten::nothing();
        let refiner = &*self.refiner;
        let starts = self.flat_starts.get_or_init(|| flat_starts(refiner));
        let points = self.kept.as_ref().expect("kept").points();
        let mut faces: Vec<usize> = recomputed
            .iter()
            .flat_map(|&v| refiner.faces_at(v))
            .collect();
        faces.sort_unstable();
        faces.dedup();
        let f32s = |p: &DVec3| p.as_vec3().to_array();
        for f in faces {
            let start = starts[f];
            if start == u32::MAX {
                continue;
            }
            let face = refiner.face(f);
            let n = newell_normal(face, points).as_vec3().to_array();
            for (k, &v) in face.iter().enumerate() {
                let p = f32s(&points[v as usize]);
                positions[start as usize + k] = p;
                normals[start as usize + k] = n;
                written.include(p);
            }
        }
        written
    }

    /// Render buffers of the refined faces at `points`.
    pub fn buffers(&self, points: &[DVec3], shading: Shading) -> RenderBuffers {
        buffers_with(&self.refiner, points, shading, self.sharp_split(shading))
    }

    /// Positions and normals only (the triangles stay while positions move).
    pub fn attributes(&self, points: &[DVec3], shading: Shading) -> (Vec<[f32; 3]>, Vec<[f32; 3]>) {
        attributes_with(&self.refiner, points, shading, self.sharp_split(shading))
    }

    /// [`attributes`](Self::attributes) written into the given buffers,
    /// reusing their memory.
    pub fn attributes_into(
        &self,
        points: &[DVec3],
        shading: Shading,
        positions: &mut Vec<[f32; 3]>,
        normals: &mut Vec<[f32; 3]>,
    ) {
        let split = self.sharp_split(shading);
        attributes_into(&self.refiner, points, shading, split, positions, normals);
    }

    /// The kept split for smooth shading (none for flat).
    fn sharp_split(&self, shading: Shading) -> &SharpSplit {
        static NONE: OnceLock<SharpSplit> = OnceLock::new();
        match shading {
            Shading::Smooth => self
                .sharp
                .get_or_init(|| refined_sharp_split(&self.refiner)),
            Shading::Flat => NONE.get_or_init(SharpSplit::default),
        }
    }
}

/// Render buffers of refined faces: shared vertices with limit normals when
/// smooth (area-weighted normals for schemes without a limit evaluation),
/// face corners with the face's Newell normal when flat; each face a fan of
/// triangles (refined faces are small and convex).
pub fn refined_buffers(refiner: &Refiner, points: &[DVec3], shading: Shading) -> RenderBuffers {
    let split = match shading {
        Shading::Smooth => refined_sharp_split(refiner),
        Shading::Flat => SharpSplit::default(),
    };
    buffers_with(refiner, points, shading, &split)
}

/// [`refined_buffers`] with the split made already.
fn buffers_with(
    refiner: &Refiner,
    points: &[DVec3],
    shading: Shading,
    split: &SharpSplit,
) -> RenderBuffers {
    let (positions, normals) = attributes_with(refiner, points, shading, split);
    let mut indices = Vec::new();
    let mut corner = 0u32;
    for face in refiner.faces() {
        for i in 1..face.len().saturating_sub(1) {
            let tri = [0, i, i + 1];
            match shading {
                Shading::Smooth => {
                    indices.extend(tri.map(|k| split.vertex(corner as usize + k, face[k])))
                }
                Shading::Flat => indices.extend(tri.map(|k| corner + k as u32)),
            }
        }
        corner += face.len() as u32;
    }
    RenderBuffers {
        positions,
        normals,
        indices,
    }
}

/// The positions and normals of [`refined_buffers`].
pub fn refined_attributes(
    refiner: &Refiner,
    points: &[DVec3],
    shading: Shading,
) -> (Vec<[f32; 3]>, Vec<[f32; 3]>) {
    let split = match shading {
        Shading::Smooth => refined_sharp_split(refiner),
        Shading::Flat => SharpSplit::default(),
    };
    attributes_with(refiner, points, shading, &split)
}

/// [`refined_attributes`] with the split made already.
fn attributes_with(
    refiner: &Refiner,
    points: &[DVec3],
    shading: Shading,
    split: &SharpSplit,
) -> (Vec<[f32; 3]>, Vec<[f32; 3]>) {
    let (mut positions, mut normals) = (Vec::new(), Vec::new());
    attributes_into(
        refiner,
        points,
        shading,
        split,
        &mut positions,
        &mut normals,
    );
    (positions, normals)
}

/// [`attributes_with`] written into `positions` and `normals` (cleared
/// first; their memory is reused: a level-2 preview of 100k faces is 6.4M
/// corners, rewritten in every frame of a drag).
fn attributes_into(
    refiner: &Refiner,
    points: &[DVec3],
    shading: Shading,
    split: &SharpSplit,
    positions: &mut Vec<[f32; 3]>,
    normals: &mut Vec<[f32; 3]>,
) {
    let f32s = |p: &DVec3| p.as_vec3().to_array();
    positions.clear();
    normals.clear();
    match shading {
        Shading::Smooth => {
            let limit =
                limit_normals(refiner, points).unwrap_or_else(|_| area_normals(refiner, points));
            positions.extend(points.iter().map(f32s));
            normals.extend(limit.iter().map(f32s));
            split.apply(points, positions, normals);
        }
        Shading::Flat => {
            let corners: usize = refiner.faces().map(<[u32]>::len).sum();
            positions.reserve(corners);
            normals.reserve(corners);
            for face in refiner.faces() {
                let n = newell_normal(face, points).as_vec3().to_array();
                for &v in face {
                    positions.push(f32s(&points[v as usize]));
                    normals.push(n);
                }
            }
        }
    }
}

/// The refined faces' corners split along the edges that are still
/// infinitely sharp at the last level (a crease of sharpness 10 or more;
/// boundary edges end fans anyway): each side of such a crease gets its
/// own render vertices, appended after the refined points, with the
/// normal of that side's faces, so the shading does not round the crease.
fn refined_sharp_split(refiner: &Refiner) -> SharpSplit {
    let sharp: HashSet<(u32, u32)> = refiner
        .edges()
        .filter(|&(_, s)| s >= INFINITE_SHARPNESS)
        .map(|([a, b], _)| (a.min(b), a.max(b)))
        .collect();
    if sharp.is_empty() {
        return SharpSplit::default();
    }
    let faces: Vec<&[u32]> = refiner.faces().collect();
    split_sharp_corners(&faces, refiner.vertex_count(), &sharp)
}

/// The cage vertices whose position differs between `old` and `new` (in
/// `Refiner::cage_positions` order), with the new position.
fn moved_between(old: &[DVec3], new: &[DVec3]) -> Vec<(u32, DVec3)> {
    new.iter()
        .zip(old)
        .enumerate()
        .filter(|(_, (new, old))| new != old)
        .map(|(i, (new, _))| (i as u32, *new))
        .collect()
}

/// Where each refined face's corners start in the flat-shaded attributes
/// (`u32::MAX` for a hidden face), as [`attributes_into`] writes them.
fn flat_starts(refiner: &Refiner) -> Vec<u32> {
    let mut next = 0u32;
    (0..refiner.face_count())
        .map(|f| {
            if refiner.is_face_hidden(f) {
                return u32::MAX;
            }
            let start = next;
            next += refiner.face(f).len() as u32;
            start
        })
        .collect()
}

/// Newell's normal of a polygon (Newell 1972; unit, or zero when degenerate).
fn newell_normal(face: &[u32], points: &[DVec3]) -> DVec3 {
    newell_sum(face, points).normalize_or_zero()
}

fn newell_sum(face: &[u32], points: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for (i, &a) in face.iter().enumerate() {
        let b = face[(i + 1) % face.len()];
        n += points[a as usize].cross(points[b as usize]);
    }
    n
}

/// Vertex normals as the sum of the (area-weighted) Newell normals of the
/// faces around each vertex.
fn area_normals(refiner: &Refiner, points: &[DVec3]) -> Vec<DVec3> {
    let mut normals = vec![DVec3::ZERO; points.len()];
    for face in refiner.faces() {
        let n = newell_sum(face, points);
        for &v in face {
            normals[v as usize] += n;
        }
    }
    normals.iter().map(|n| n.normalize_or_zero()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use hedra_geom::Primitive;

    fn cube() -> Arc<HalfEdgeMesh> {
        Arc::new(Primitive::Cube { size: 2.0 }.build().unwrap())
    }

    #[test]
    fn a_cube_at_level_one_gives_its_triangles_and_unit_normals() {
        let cage = cube();
        let mut r = SmoothRefinement::new(
            &cage,
            &Creases::default(),
            &SubdivisionModifier::with_level(1),
        )
        .unwrap();
        let points = r.points(&cage);
        assert_eq!(points.len(), 26);
        let smooth = r.buffers(&points, Shading::Smooth);
        assert_eq!(smooth.positions.len(), 26);
        assert_eq!(smooth.indices.len(), 24 * 2 * 3);
        let flat = r.buffers(&points, Shading::Flat);
        assert_eq!(flat.positions.len(), 24 * 4, "each quad its own corners");
        assert_eq!(flat.indices.len(), 24 * 2 * 3);
        for n in smooth.normals.iter().chain(&flat.normals) {
            let n = glam::Vec3::from(*n);
            assert!((n.length() - 1.0).abs() < 1e-5);
        }
        // Outward: each smooth normal points away from the centre.
        for (p, n) in smooth.positions.iter().zip(&smooth.normals) {
            assert!(glam::Vec3::from(*p).dot(glam::Vec3::from(*n)) > 0.0);
        }
    }

    /// Above the stencil limit a drag keeps every level's points and
    /// rewrites only the flat corners of the faces the move reaches: after
    /// each of several moves (one vertex, then a few, then every vertex,
    /// which rewrites all) the attributes are the same bits as those of a
    /// fresh refinement of the moved cage. With boundary `None` (faces
    /// hidden, so the corners of a face do not start at 4 × its index) and
    /// without.
    #[test]
    fn a_large_drag_rewrites_the_reached_faces_to_a_fresh_refinement_s_attributes() {
        use hedra_geom::subdivision::BoundaryInterpolation;
        for boundary in [
            BoundaryInterpolation::EdgesOnly,
            BoundaryInterpolation::None,
        ] {
            let grid = Primitive::Grid {
                x_segments: 161,
                z_segments: 160,
                size: 2.0,
            };
            let cage = Arc::new(grid.build().unwrap());
            let mut modifier = SubdivisionModifier::with_level(2);
            modifier.options.boundary = boundary;
            let creases = Creases::default();
            let mut r = SmoothRefinement::new(&cage, &creases, &modifier).unwrap();
            assert!(r.refiner.face_count() > STENCIL_FACE_LIMIT);
            let points = r.points(&cage);
            let (mut positions, mut normals) = r.attributes(&points, Shading::Flat);
            let vertices: Vec<_> = cage.vertices().collect();
            let mut moved = (*cage).clone();
            let moves: [&[usize]; 3] = [&[13_000], &[0, 161, 5_000, 5_001], &[]];
            for (step, which) in moves.into_iter().enumerate() {
                let which: Vec<usize> = if which.is_empty() {
                    (0..vertices.len()).collect()
                } else {
                    which.to_vec()
                };
                for &i in &which {
                    let v = vertices[i];
                    let p = moved.position(v) + DVec3::new(0.01, 0.02 * step as f64 + 0.03, -0.01);
                    moved.set_position(v, p);
                }
                let cage = Arc::new(moved.clone());
                let before = positions.clone();
                let written =
                    r.update_attributes(&cage, true, Shading::Flat, &mut positions, &mut normals);
                // Every position that changed is within the bounds reported.
                if let Rewritten::Some { min, max } = written {
                    for (a, b) in before.iter().zip(&positions).filter(|(a, b)| a != b) {
                        assert!(
                            (0..3).all(|i| min[i] <= b[i] && b[i] <= max[i]),
                            "{a:?} -> {b:?}"
                        );
                    }
                } else {
                    assert_eq!(step, 2, "only moving every vertex rewrites all");
                }
                let mut fresh = SmoothRefinement::new(&cage, &creases, &modifier).unwrap();
                let points = fresh.points(&cage);
                let (p, n) = fresh.attributes(&points, Shading::Flat);
                assert!(p == positions, "{boundary:?}, move {step}: positions");
                assert!(n == normals, "{boundary:?}, move {step}: normals");
            }
        }
    }

    #[test]
    fn stencils_after_a_move_equal_a_full_refinement() {
        let cage = cube();
        let modifier = SubdivisionModifier::with_level(2);
        let mut r = SmoothRefinement::new(&cage, &Creases::default(), &modifier).unwrap();
        r.points(&cage);
        let mut moved = (*cage).clone();
        let v = moved.vertices().next().unwrap();
        moved.set_position(v, moved.position(v) + DVec3::new(0.3, -0.2, 0.5));
        let moved = Arc::new(moved);
        assert!(r.fits(&moved, &Creases::default(), &modifier));
        // Twice: the first move builds the stencils, the second updates them.
        for _ in 0..2 {
            let fast = r.points(&moved);
            let exact = SmoothRefinement::new(&moved, &Creases::default(), &modifier)
                .unwrap()
                .points(&moved);
            for (a, b) in fast.iter().zip(&exact) {
                assert!(a.distance(*b) < 1e-12);
            }
        }
        let other = Arc::new(Primitive::Plane { size: 1.0 }.build().unwrap());
        assert!(!r.fits(&other, &Creases::default(), &modifier));
    }

    #[test]
    fn stencils_built_on_a_worker_thread_serve_the_first_drag() {
        let cage = cube();
        let modifier = SubdivisionModifier::with_level(2);
        let mut r = SmoothRefinement::new(&cage, &Creases::default(), &modifier).unwrap();
        let job = r.stencil_job().expect("no stencils yet");
        let prepared = std::thread::spawn(job).join().unwrap();
        r.set_stencils(prepared);
        assert!(r.stencil_job().is_none(), "built already");
        let mut moved = (*cage).clone();
        let v = moved.vertices().next().unwrap();
        moved.set_position(v, moved.position(v) + DVec3::new(0.3, -0.2, 0.5));
        let moved = Arc::new(moved);
        let fast = r.points(&moved);
        let exact = SmoothRefinement::new(&moved, &Creases::default(), &modifier)
            .unwrap()
            .points(&moved);
        assert_eq!(fast.len(), exact.len());
        for (a, b) in fast.iter().zip(&exact) {
            assert!(a.distance(*b) < 1e-12);
        }
    }
}
