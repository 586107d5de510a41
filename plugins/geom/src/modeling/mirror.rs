//! Mirroring across a world axis: symmetrize (Blender's Symmetrize),
//! mirroring vertices about their median (Blender's Ctrl+M), and the
//! mirrored copies of the Mirror modifier ([`mirrored`]).

use super::copies::{CopiedMesh, Soup, check_distance, join, root};
use super::{InvalidResult, ModelingError, NewFace};
use crate::ids::VertexId;
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;

/// A world axis for mirroring and symmetrizing.
#[derive(Copy, Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum MirrorAxis {
    /// Across a plane of constant x (the x coordinate flips).
    X,
    /// Across a plane of constant y.
    Y,
    /// Across a plane of constant z.
    Z,
}

impl MirrorAxis {
    /// The three axes in the order Blender's Mirror modifier applies them.
    pub const ALL: [MirrorAxis; 3] = [MirrorAxis::X, MirrorAxis::Y, MirrorAxis::Z];

    /// The coordinate the axis flips: 0 for x, 1 for y, 2 for z.
    pub fn index(self) -> usize {
        match self {
            MirrorAxis::X => 0,
            MirrorAxis::Y => 1,
            MirrorAxis::Z => 2,
        }
    }
    fn reflect(self, p: DVec3, center: f64) -> DVec3 {
        let mut a = p.to_array();
        let i = self.index();
        a[i] = 2.0 * center - a[i];
        DVec3::from_array(a)
    }
}

/// Makes the mesh symmetric across the plane `axis = 0`: faces on the
/// negative side are deleted and replaced by a mirror image of the positive
/// side, joined at the vertices on the plane (Blender's Symmetrize, +X to −X
/// for `X`). The plane must cut the mesh along edges (a loop cut there first).
///
/// # Errors
/// [`ModelingError::Parameter`] when a face straddles the plane;
/// [`ModelingError::Invalid`] when the mirrored half cannot be joined
/// manifold. The mesh is unchanged on error.
pub fn symmetrize(mesh: &mut HalfEdgeMesh, axis: MirrorAxis) -> Result<(), ModelingError> {
    const EPS: f64 = 1e-9;
    let i = axis.index();
    let side = |v: VertexId| {
        let c = mesh.position(v).to_array()[i];
        if c > EPS {
            1
        } else if c < -EPS {
            -1
        } else {
            0
        }
    };
    let mut negative = Vec::new();
    let mut positive = Vec::new();
    for f in mesh.faces() {
        let sides: Vec<i32> = mesh.face_vertices(f).map(side).collect();
        match (sides.iter().any(|&s| s > 0), sides.iter().any(|&s| s < 0)) {
            (true, true) => {
                return Err(ModelingError::Parameter {
                    what: "mesh",
                    allowed: "cut by the mirror plane along edges (add a loop cut there)",
                    value: format!("{f} crosses the plane"),
                });
            }
            (false, true) => negative.push(f),
            (true, false) => positive.push(f),
            (false, false) => negative.push(f), // flat on the plane: rebuilt from the mirror
        }
    }
    let polys: Vec<Vec<VertexId>> = positive
        .iter()
        .map(|&f| mesh.face_vertices(f).collect())
        .collect();
    let mut work = mesh.clone();
    work.delete_faces(&negative, false);
    // Snap plane vertices exactly onto the plane, then mirror the rest.
    let mut mirror = std::collections::HashMap::new();
    for p in &polys {
        for &v in p {
            if mirror.contains_key(&v) {
                continue;
            }
            let m = if side(v) == 0 {
                let mut a = work.position(v).to_array();
                a[i] = 0.0;
                work.set_position(v, DVec3::from_array(a));
                v
            } else {
                work.add_vertex(axis.reflect(work.position(v), 0.0))?
            };
            mirror.insert(v, m);
        }
    }
    for p in &polys {
        // A mirror image turns orientation around: reverse the corner order.
        let image: Vec<VertexId> = p.iter().rev().map(|v| mirror[v]).collect();
        work.add_face(&image).map_err(|error| {
            ModelingError::Invalid(InvalidResult::Face {
                face: NewFace::Mirrored,
                error,
            })
        })?;
    }
    work.validate()?;
    *mesh = work;
    Ok(())
}

/// Mirrors vertices across the plane through their median perpendicular to
/// `axis` (Blender's Ctrl+M). Whole connected parts that are mirrored get
/// their faces reversed so they keep facing outwards.
///
/// # Errors
/// [`ModelingError::Empty`], [`ModelingError::Missing`].
pub fn mirror_vertices(
    mesh: &mut HalfEdgeMesh,
    vertices: &[VertexId],
    axis: MirrorAxis,
) -> Result<(), ModelingError> {
    if vertices.is_empty() {
        return Err(ModelingError::Empty("no vertices"));
    }
    if let Some(v) = vertices.iter().find(|v| !mesh.is_vertex(**v)) {
        return Err(ModelingError::Missing((*v).into()));
    }
    let center = vertices
        .iter()
        .map(|&v| mesh.position(v).to_array()[axis.index()])
        .sum::<f64>()
        / vertices.len() as f64;
    let set: std::collections::HashSet<VertexId> = vertices.iter().copied().collect();
    for &v in &set {
        let p = axis.reflect(mesh.position(v), center);
        mesh.set_position(v, p);
    }
    // Components mirrored as a whole turn inside out: turn them back.
    let (comp, count) = mesh.components();
    let whole: Vec<VertexId> = (0..count)
        .filter_map(|c| {
            let members: Vec<VertexId> = mesh.vertices().filter(|v| comp[v.index()] == c).collect();
            (!members.is_empty() && members.iter().all(|v| set.contains(v))).then(|| members[0])
        })
        .collect();
    mesh.reverse_components(&whole);
    Ok(())
}

/// The Mirror modifier's result (Blender's Mirror modifier,
/// `MOD_mirror.cc`): the mesh and its mirror images across the planes
/// x = 0, y = 0, z = 0 of its own (local) space, for each axis set in
/// `axes` (`[x, y, z]`), applied in the order X, Y, Z, each to the result of
/// the previous one, so that all three give 8 copies. Mirror images have
/// their faces reversed, so normals keep facing outwards.
///
/// With `merge_distance: Some(d)` (Blender's Merge option), a vertex within
/// `d` of the mirror plane is moved onto the plane and welded with its
/// image, so a half model whose open seam lies on the plane becomes one
/// piece. (Blender compares a vertex with its image, 2·|x| < d; here the
/// distance is to the plane, |x| ≤ d, which is what the modifier's
/// clipping keeps.) With `None` the copies stay separate.
///
/// No axis set gives a copy of the mesh. Isolated vertices and wire edges
/// are not copied. The result's ids are new; see [`mirrored_copies`] for
/// where each element came from.
///
/// # Errors
/// [`ModelingError::Empty`] for a mesh without faces;
/// [`ModelingError::Parameter`] for a negative or non-finite merge
/// distance or a face with inner rings; [`ModelingError::Invalid`] with
/// [`InvalidResult::Copies`] when the welded copies are not manifold (faces
/// lying in the mirror plane, or a seam that is not a boundary).
///
/// Complexity: O(copies × corners).
///
/// ```
/// use hedra_geom::{HalfEdgeMesh, DVec3, modeling::mirrored};
/// // A unit quad touching the plane x = 0 along one edge.
/// let quad = HalfEdgeMesh::from_polygons(
///     &[DVec3::new(0.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0),
///       DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.0, 1.0, 0.0)],
///     &[[0u32, 1, 2, 3]],
/// ).unwrap();
/// let both = mirrored(&quad, [true, false, false], Some(0.001)).unwrap();
/// assert_eq!((both.vertex_count(), both.edge_count(), both.face_count()), (6, 7, 2));
/// ```
pub fn mirrored(
    mesh: &HalfEdgeMesh,
    axes: [bool; 3],
    merge_distance: Option<f64>,
) -> Result<HalfEdgeMesh, ModelingError> {
    mirrored_copies(mesh, axes, merge_distance).map(|c| c.mesh)
}

/// [`mirrored`], with the source vertex and face of every result element
/// (to carry creases and corner attributes over).
///
/// # Errors
/// As [`mirrored`].
pub fn mirrored_copies(
    mesh: &HalfEdgeMesh,
    axes: [bool; 3],
    merge_distance: Option<f64>,
) -> Result<CopiedMesh, ModelingError> {
    if let Some(d) = merge_distance {
        check_distance(d)?;
    }
    let mut soup = Soup::of(mesh)?;
    for axis in MirrorAxis::ALL.into_iter().filter(|a| axes[a.index()]) {
        let i = axis.index();
        let (n, faces) = (soup.positions.len(), soup.polygons.len());
        // Vertices on the seam go exactly onto the plane first, so that
        // they and their images coincide.
        let on_plane: Vec<bool> = soup
            .positions
            .iter()
            .map(|p| merge_distance.is_some_and(|d| p[i].abs() <= d))
            .collect();
        for (p, _) in soup
            .positions
            .iter_mut()
            .zip(&on_plane)
            .filter(|(_, o)| **o)
        {
            p[i] = 0.0;
        }
        let base = soup.append_copy(n, faces, |p| axis.reflect(p, 0.0), true);
        let mut parent: Vec<u32> = (0..soup.positions.len() as u32).collect();
        for (k, _) in on_plane.iter().enumerate().filter(|(_, o)| **o) {
            join(&mut parent, k as u32, base + k as u32);
        }
        let rep: Vec<u32> = (0..parent.len() as u32)
            .map(|k| root(&mut parent, k))
            .collect();
        soup.weld(&rep);
    }
    soup.build("the mirror")
}
