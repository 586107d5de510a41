//! The [`Refiner`]: every level's connectivity of one cage topology, built
//! once from a half-edge mesh or from polygons kept as they are, and the
//! masks that map cage positions to refined positions through it.

use super::*;

/// The refinement of one cage topology to a number of levels: every level's
/// connectivity, built once. Positions are mapped with [`refine`](Self::refine)
/// (or a [`StencilTable`]) as often as the cage moves.
#[derive(Clone, Debug)]
pub struct Refiner {
    options: Options,
    /// How each level's faces are split (from the scheme and the cage;
    /// kept, as per-vertex queries ask it).
    split: Split,
    pub(crate) levels: Vec<Level>,
    pub(super) cage: CageMap,
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
    /// (`Level::from_polygon_cage`). Cage vertex, edge and face ids are
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
            split,
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
    /// The refined faces (of all [`face_count`](Self::face_count) faces,
    /// hidden ones included) at refined vertex `v`, in increasing order (a
    /// face once per corner at `v`).
    pub fn faces_at(&self, v: u32) -> impl Iterator<Item = usize> + '_ {
        let last = self.last();
        last.vertex_corners(v)
            .iter()
            .map(|&c| last.corner_face(c as usize) as usize)
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
    /// Edges at refined vertex `v`. Counted from the level before (the
    /// last level's own vertex-edge lists, as large as its edges, are never
    /// built for it: an export asks this of every vertex): a face point has
    /// one edge per side of its face, an edge point its two halves and one
    /// edge per face of its parent edge (Catmull-Clark; two per triangle
    /// for Loop), a vertex point as many as its parent vertex. Levels with
    /// an edge in more than two faces, the cage and Doo-Sabin's count on
    /// the last level itself.
    pub fn vertex_edge_count(&self, v: u32) -> usize {
        let [.., parent, last] = &self.levels[..] else {
            return self.last().vertex_edges(v).len();
        };
        if parent.non_manifold {
            return last.vertex_edges(v).len();
        }
        let (nf, ne) = (parent.face_count() as u32, parent.edge_count() as u32);
        let edge_faces = |e: u32| 1 + usize::from(!parent.is_boundary_edge(e));
        match self.split() {
            Split::Quads if v < nf => parent.face_corners(v).len(),
            Split::Quads if v < nf + ne => 2 + edge_faces(v - nf),
            Split::Quads => parent.vertex_edges(v - nf - ne).len(),
            Split::Triangles if v < ne => 2 + 2 * edge_faces(v),
            Split::Triangles => parent.vertex_edges(v - ne).len(),
            Split::Dual => last.vertex_edges(v).len(),
        }
    }
    /// True when an edge of the refined mesh between two faces is still
    /// infinitely sharp (where smooth normals are split).
    pub fn has_infinitely_sharp_inner_edge(&self) -> bool {
        let last = self.last();
        (0..last.edge_count() as u32)
            .any(|e| last.edge_sharp(e) >= INFINITE_SHARPNESS && !last.is_boundary_edge(e))
    }
    /// The refined vertices in the order [`to_mesh`](Self::to_mesh)
    /// numbers them (first use by the shown faces, corner by corner, then
    /// the vertices without edges), as refined vertex indices; and each
    /// refined vertex's number in that order (`u32::MAX`: left out, used
    /// only by hidden faces). For writers that take the faces straight
    /// from [`faces`](Self::faces) and must number vertices as the mesh
    /// would.
    pub fn mesh_vertex_order(&self) -> (Vec<u32>, Vec<u32>) {
        let last = self.last();
        let mut number = vec![u32::MAX; last.vertex_count];
        let mut order = Vec::with_capacity(last.vertex_count);
        for face in self.faces() {
            for &v in face {
                if number[v as usize] == u32::MAX {
                    number[v as usize] = order.len() as u32;
                    order.push(v);
                }
            }
        }
        for v in 0..last.vertex_count as u32 {
            if number[v as usize] == u32::MAX && self.vertex_edge_count(v) == 0 {
                number[v as usize] = order.len() as u32;
                order.push(v);
            }
        }
        (order, number)
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
    /// through the masks; a level of [`PARALLEL_POINTS`] points or more on
    /// all cores (rayon), smaller ones on this thread, where the threads
    /// would cost more than they save. Every path gives the same bits.
    /// Complexity: O(result size).
    pub fn refine(&self, cage: &[DVec3]) -> Vec<DVec3> {
        self.refine_with(cage, Threads::BySize)
    }

    /// [`refine`](Self::refine) on this thread only.
    pub fn refine_serial(&self, cage: &[DVec3]) -> Vec<DVec3> {
        self.refine_with(cage, Threads::One)
    }

    /// [`refine`](Self::refine) with every level on all cores, however
    /// small.
    pub fn refine_parallel(&self, cage: &[DVec3]) -> Vec<DVec3> {
        self.refine_with(cage, Threads::All)
    }

    fn refine_with(&self, cage: &[DVec3], threads: Threads) -> Vec<DVec3> {
        self.refine_levels(cage, threads, &mut |_| true)
            .expect("never cancelled")
    }

    /// [`refine`](Self::refine) (or, when `parallel` is false, its serial
    /// form) that calls `go_on(level)` after each level and returns `None`
    /// when it says stop.
    pub fn refine_cancellable(
        &self,
        cage: &[DVec3],
        parallel: bool,
        go_on: &mut dyn FnMut(u32) -> bool,
    ) -> Option<Vec<DVec3>> {
        let threads = if parallel {
            Threads::BySize
        } else {
            Threads::One
        };
        self.refine_levels(cage, threads, go_on)
    }

    fn refine_levels(
        &self,
        cage: &[DVec3],
        threads: Threads,
        go_on: &mut dyn FnMut(u32) -> bool,
    ) -> Option<Vec<DVec3>> {
        assert_eq!(
            cage.len(),
            self.levels[0].vertex_count,
            "one position per cage vertex"
        );
        let mut points = cage.to_vec();
        for (i, parent) in self.levels[..self.levels.len() - 1].iter().enumerate() {
            let parallel = match threads {
                Threads::One => false,
                Threads::All => true,
                Threads::BySize => child_count(parent, self.split()) >= PARALLEL_POINTS,
            };
            points = interpolate(parent, self.split(), self.options, &points, parallel);
            if !go_on(i as u32 + 1) {
                return None;
            }
        }
        Some(points)
    }

    pub(crate) fn split(&self) -> Split {
        self.split
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
pub(crate) struct PointSink<'a> {
    pub points: &'a [DVec3],
    pub face_points: &'a [DVec3],
    pub sum: DVec3,
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
/// Points of a level from which [`Refiner::refine`] computes it on all
/// cores. Measured on the 2-core machine (`cargo bench -p hedra_geom
/// --bench subdivision`): the cube's level 7 (98k points) is 10 % slower on
/// two threads, the 100 × 100 torus's level 4 (2.56M points) 1.9× faster.
pub const PARALLEL_POINTS: usize = 1 << 18;

/// Which cores a refinement uses.
#[derive(Copy, Clone)]
enum Threads {
    One,
    All,
    BySize,
}

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
pub(crate) fn interpolate(
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
    // The same on the rayon pool, each point still written once: rayon's
    // indexed `par_extend` writes into the vector's spare capacity (a zero
    // fill first was a whole extra pass over the level).
    use rayon::prelude::*;
    let mut face_points = Vec::with_capacity(nf);
    face_points.par_extend((0..nf).into_par_iter().map(face));
    let mut out = Vec::with_capacity(child_count);
    out.extend_from_slice(&face_points);
    out.par_extend((0..ne).into_par_iter().map(|e| edge(&face_points, e)));
    out.par_extend(
        (0..parent.vertex_count)
            .into_par_iter()
            .map(|v| vertex(&face_points, v)),
    );
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
