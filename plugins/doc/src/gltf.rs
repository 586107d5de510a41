//! glTF 2.0 in and out (written with `gltf-json`, read with `gltf`): the
//! node hierarchy with local translation, rotation and scale; meshes as
//! triangles with normals (split at faces for flat shading, shared for
//! smooth); surfaces as triangles, curves as line strips. `.glb` holds the
//! JSON and one binary chunk; `.gltf` embeds the buffer as a data URI.
//!
//! Corner attributes: a mesh written as its cage with UVs or custom normals
//! gets one glTF vertex per distinct (position, normal, UV) of its face
//! corners. Custom normals are used where a corner has one, the computed
//! (flat or smooth) normal elsewhere. `TEXCOORD_0` is written when any
//! corner has a UV; corners without one get (0, 0). glTF's v runs down, so
//! v is flipped both ways (v' = 1 − v). Import reads `NORMAL` and
//! `TEXCOORD_0` into corner attributes.

use std::borrow::Cow;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use base64::Engine;
use glam::{DQuat, DVec2, DVec3};
use gltf_json as json;
use hedra_geom::HalfEdgeMesh;
use json::validation::Checked::Valid;
use json::validation::USize64;

use crate::export::{ExportError, ExportShape, Geometry, export_geometry_creased};
use crate::import::{ImportError, ImportedMesh, corner_attributes};
use crate::scene::{CornerAttributes, Document, NodeContent, NodeId, NodeTransform, Shading};
use hedra_geom::subdivision::Creases;

/// The binary buffer of a glTF export as the arrays it is made of, kept
/// as they are until they are written (GLB streams them, array by array;
/// a `.gltf` encodes them as a data URI).
#[derive(Default)]
struct Buffer<'a> {
    arrays: Vec<BufferArray<'a>>,
    /// Bytes so far, with the padding between arrays.
    length: usize,
}

/// One array of the buffer: 4-byte numbers.
enum BufferArray<'a> {
    F32(Vec<f32>),
    U32(Vec<u32>),
    /// Numbers made as they are written, so that a large subdivided mesh's
    /// arrays are never held: `len` of them, in `pieces` made on all cores
    /// ([`crate::export::write_pieces_in_order`]).
    Made {
        len: usize,
        pieces: usize,
        make: MakePiece<'a>,
    },
}

/// Appends the little-endian bytes of one piece's numbers.
type MakePiece<'a> = Box<dyn Fn(usize, &mut Vec<u8>) + Send + Sync + 'a>;

impl<'a> BufferArray<'a> {
    fn len(&self) -> usize {
        match self {
            BufferArray::F32(v) => v.len(),
            BufferArray::U32(v) => v.len(),
            BufferArray::Made { len, .. } => *len,
        }
    }

    /// An array of `len` numbers in `pieces`: `each(piece, put)` calls
    /// `put` with the bits of each number of the piece, in order.
    fn made(
        len: usize,
        pieces: usize,
        each: impl Fn(usize, &mut dyn FnMut(u32)) + Send + Sync + 'a,
    ) -> BufferArray<'a> {
        BufferArray::Made {
            len,
            pieces,
            make: Box::new(move |piece, bytes| {
                each(piece, &mut |x| bytes.extend_from_slice(&x.to_le_bytes()))
            }),
        }
    }

    /// Writes the array as little-endian bytes.
    fn write(&self, out: &mut dyn std::io::Write) -> std::io::Result<()> {
        match self {
            BufferArray::F32(v) => write_numbers(v.iter().map(|x| x.to_bits()), out),
            BufferArray::U32(v) => write_numbers(v.iter().copied(), out),
            BufferArray::Made { len, pieces, make } => {
                let written = crate::export::write_pieces_in_order(*pieces, make, out)?;
                if written != 4 * *len as u64 {
                    return Err(std::io::Error::other(format!(
                        "a glTF array made {} numbers where its view holds {len}",
                        written / 4
                    )));
                }
                Ok(())
            }
        }
    }
}

/// Writes `numbers` as little-endian bytes through a small staging
/// buffer.
fn write_numbers(
    numbers: impl Iterator<Item = u32>,
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    let mut staged: Vec<u8> = Vec::with_capacity(1 << 16);
    for x in numbers {
        staged.extend_from_slice(&x.to_le_bytes());
        if staged.len() == staged.capacity() {
            out.write_all(&staged)?;
            staged.clear();
        }
    }
    out.write_all(&staged)
}

/// Appends `numbers` to the buffer (4-byte aligned: every number is 4
/// bytes) and returns their view.
fn push_view<'a>(
    root: &mut json::Root,
    bin: &mut Buffer<'a>,
    numbers: BufferArray<'a>,
    target: json::buffer::Target,
) -> json::Index<json::buffer::View> {
    let offset = bin.length;
    let byte_length = 4 * numbers.len();
    bin.length += byte_length;
    bin.arrays.push(numbers);
    root.push(json::buffer::View {
        buffer: json::Index::new(0),
        byte_length: USize64(byte_length as u64),
        byte_offset: Some(USize64(offset as u64)),
        byte_stride: None,
        name: None,
        target: Some(Valid(target)),
        extensions: None,
        extras: Default::default(),
    })
}

impl Buffer<'_> {
    /// Writes the arrays as little-endian bytes, one after the other.
    fn write(&self, out: &mut dyn std::io::Write) -> std::io::Result<()> {
        self.arrays.iter().try_for_each(|array| array.write(out))
    }
}

/// An accessor of `count` elements over a view.
fn push_accessor(
    root: &mut json::Root,
    view: json::Index<json::buffer::View>,
    count: usize,
    component: json::accessor::ComponentType,
    type_: json::accessor::Type,
    bounds: Option<([f32; 3], [f32; 3])>,
) -> json::Index<json::Accessor> {
    root.push(json::Accessor {
        buffer_view: Some(view),
        byte_offset: Some(USize64(0)),
        count: USize64(count as u64),
        component_type: Valid(json::accessor::GenericComponentType(component)),
        extensions: None,
        extras: Default::default(),
        type_: Valid(type_),
        min: bounds.map(|(lo, _)| json::Value::from(lo.to_vec())),
        max: bounds.map(|(_, hi)| json::Value::from(hi.to_vec())),
        name: None,
        normalized: false,
        sparse: None,
    })
}

fn bounds(v: &[[f32; 3]]) -> ([f32; 3], [f32; 3]) {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for p in v {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// The corners of a primitive's triangles as a list, three per triangle:
/// strips and fans unrolled with the winding the glTF specification gives
/// (3.7.2.1: strip triangle i is (i, i + 1 + i mod 2, i + 2 − i mod 2), fan
/// triangle i is (i + 1, i + 2, 0)).
fn triangle_list(mode: gltf::mesh::Mode, indices: &[u32]) -> Vec<u32> {
    let n = indices.len();
    match mode {
        gltf::mesh::Mode::TriangleStrip => (0..n.saturating_sub(2))
            .flat_map(|i| {
                let odd = i % 2;
                [indices[i], indices[i + 1 + odd], indices[i + 2 - odd]]
            })
            .collect(),
        gltf::mesh::Mode::TriangleFan => (0..n.saturating_sub(2))
            .flat_map(|i| [indices[i + 1], indices[i + 2], indices[0]])
            .collect(),
        _ => indices.to_vec(),
    }
}

/// `n` when it is a unit vector; else the direction of `fallback()`, else
/// +Y: glTF requires unit normals, and a zero-area face (imported, or
/// subdivided from one) has none of its own.
fn unit_or_up(n: DVec3, fallback: impl FnOnce() -> DVec3) -> DVec3 {
    if n.is_normalized() {
        return n;
    }
    fallback().try_normalize().unwrap_or(DVec3::Y)
}

/// The summed normals of the faces around face `f` (its edge neighbours).
fn neighbours_normal(m: &HalfEdgeMesh, f: hedra_geom::FaceId) -> DVec3 {
    m.face_halfedges(f)
        .filter_map(|h| m.face(h.twin()))
        .map(|g| m.face_normal(g))
        .sum()
}

/// Triangles of a half-edge mesh with normals: each face's own corners and
/// normal when flat, shared vertices with area-weighted normals when smooth,
/// split along the infinitely sharp creases of `creases` (one vertex per
/// side, with its side's normal, as the viewport draws them).
pub(crate) fn mesh_triangles(
    m: &HalfEdgeMesh,
    shading: Shading,
    creases: &Creases,
) -> (Vec<[f32; 3]>, Vec<[f32; 3]>, Vec<u32>) {
    let (mut positions, mut normals, mut indices) = (Vec::new(), Vec::new(), Vec::new());
    let a = |p: DVec3| p.as_vec3().to_array();
    match shading {
        Shading::Flat => {
            // Each face its own corners (a cube: 24 vertices, seed 000's
            // "cube problem"), triangulated by index.
            let (mut corners, mut face) = (Vec::new(), Vec::new());
            for f in m.faces() {
                let n = a(unit_or_up(m.face_normal(f), || neighbours_normal(m, f)));
                let base = positions.len() as u32;
                corners.clear();
                corners.extend(m.face_vertices(f));
                for &v in &corners {
                    positions.push(a(m.position(v)));
                    normals.push(n);
                }
                face.clear();
                hedra_geom::query::triangulate_face_into(m, f, &mut face);
                for &tri in &face {
                    indices.extend(tri.map(|v| {
                        base + corners
                            .iter()
                            .position(|c| *c == v)
                            .expect("a triangle corner is a face corner")
                            as u32
                    }));
                }
            }
        }
        Shading::Smooth => {
            let mut index = vec![u32::MAX; m.vertex_capacity()];
            for v in m.vertices() {
                index[v.index()] = positions.len() as u32;
                positions.push(a(m.position(v)));
                normals.push(a(unit_or_up(m.vertex_normal(v), || {
                    m.vertex_faces(v).map(|f| neighbours_normal(m, f)).sum()
                })));
            }
            let split = crate::render::mesh_sharp_split(m, creases, &index);
            if !split.is_empty() {
                let points: Vec<DVec3> = m.vertices().map(|v| m.position(v)).collect();
                split.apply(&points, &mut positions, &mut normals);
                // A fan of zero area has no normal; glTF needs a unit one.
                for (v, n) in split.normals(&points) {
                    if n == DVec3::ZERO {
                        normals[v as usize] = [0.0, 1.0, 0.0];
                    }
                }
            }
            let mut corner = 0usize;
            let (mut corners, mut face) = (Vec::new(), Vec::new());
            for f in m.faces() {
                corners.clear();
                corners.extend(m.face_vertices(f));
                face.clear();
                hedra_geom::query::triangulate_face_into(m, f, &mut face);
                for &tri in &face {
                    indices.extend(tri.map(|v| {
                        let k = corners.iter().position(|c| *c == v).unwrap_or(0);
                        split.vertex(corner + k, index[v.index()])
                    }));
                }
                corner += corners.len();
            }
        }
    }
    (positions, normals, indices)
}

/// A large mesh's flat arrays, made in pieces on all cores as the GLB is
/// written: the numbers [`mesh_triangles`] gives with [`Shading::Flat`]
/// (each face's corners with its unit normal, its triangles by index),
/// without holding them (issue 36, item 2).
pub(crate) fn flat_mesh_arrays(mesh: Cow<'_, HalfEdgeMesh>) -> PrimitiveArrays<'_> {
    use crate::export::FACES_PER_PIECE;
    use rayon::prelude::*;
    let mesh = std::sync::Arc::new(mesh);
    let faces: std::sync::Arc<Vec<hedra_geom::FaceId>> =
        std::sync::Arc::new(mesh.faces().collect());
    let pieces = faces.len().div_ceil(FACES_PER_PIECE);
    let piece = |faces: &[hedra_geom::FaceId], p: usize| -> std::ops::Range<usize> {
        p * FACES_PER_PIECE..((p + 1) * FACES_PER_PIECE).min(faces.len())
    };
    // Each piece's corners, triangles and bounds, found on all cores.
    let measured: Vec<(u32, usize, [f32; 3], [f32; 3])> = (0..pieces)
        .into_par_iter()
        .map(|p| {
            let (mut corners, mut triangles) = (0u32, 0usize);
            let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
            let mut face = Vec::new();
            for &f in &faces[piece(&faces, p)] {
                for v in mesh.face_vertices(f) {
                    let x = mesh.position(v).as_vec3().to_array();
                    for k in 0..3 {
                        lo[k] = lo[k].min(x[k]);
                        hi[k] = hi[k].max(x[k]);
                    }
                    corners += 1;
                }
                face.clear();
                hedra_geom::query::triangulate_face_into(&mesh, f, &mut face);
                triangles += face.len();
            }
            (corners, triangles, lo, hi)
        })
        .collect();
    let mut starts = Vec::with_capacity(pieces);
    let (mut corner_count, mut triangle_count) = (0u32, 0usize);
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for (corners, triangles, l, h) in measured {
        starts.push(corner_count);
        corner_count += corners;
        triangle_count += triangles;
        for k in 0..3 {
            lo[k] = lo[k].min(l[k]);
            hi[k] = hi[k].max(h[k]);
        }
    }
    let corners = |normal: bool| {
        let (mesh, faces) = (mesh.clone(), faces.clone());
        BufferArray::made(3 * corner_count as usize, pieces, move |p, put| {
            for &f in &faces[piece(&faces, p)] {
                let n = unit_or_up(mesh.face_normal(f), || neighbours_normal(&mesh, f));
                for v in mesh.face_vertices(f) {
                    let x = if normal { n } else { mesh.position(v) };
                    x.as_vec3().to_array().iter().for_each(|x| put(x.to_bits()));
                }
            }
        })
    };
    let indices = {
        let (mesh, faces) = (mesh.clone(), faces.clone());
        BufferArray::made(3 * triangle_count, pieces, move |p, put| {
            let (mut corners, mut face) = (Vec::new(), Vec::new());
            let mut base = starts[p];
            for &f in &faces[piece(&faces, p)] {
                corners.clear();
                corners.extend(mesh.face_vertices(f));
                face.clear();
                hedra_geom::query::triangulate_face_into(&mesh, f, &mut face);
                for tri in &face {
                    for v in tri {
                        let k = corners
                            .iter()
                            .position(|c| c == v)
                            .expect("a triangle corner is a face corner");
                        put(base + k as u32);
                    }
                }
                base += corners.len() as u32;
            }
        })
    };
    PrimitiveArrays {
        positions: corners(false),
        vertex_count: corner_count as usize,
        bounds: (lo, hi),
        normals: Some(corners(true)),
        uvs: None,
        indices: (triangle_count > 0).then_some(indices),
        mode: json::mesh::Mode::Triangles,
    }
}

/// Positions, normals, UVs (empty when no corner has one) and triangle
/// indices of a mesh with corner attributes: one vertex per distinct
/// corner, custom normals where given, computed ones elsewhere.
type CornerTriangles = (Vec<[f32; 3]>, Vec<[f32; 3]>, Vec<[f32; 2]>, Vec<u32>);

fn corner_triangles(m: &HalfEdgeMesh, shading: Shading, c: &CornerAttributes) -> CornerTriangles {
    let (mut positions, mut normals, mut uvs, mut indices) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let with_uvs = !c.uvs.is_empty();
    let mut seen: HashMap<[u32; 8], u32> = HashMap::new();
    for f in m.faces() {
        let face_normal = m.face_normal(f);
        let mut corners: Vec<(hedra_geom::VertexId, u32)> = Vec::new();
        for h in m.face_halfedges(f) {
            let v = m.origin(h);
            let p = m.position(v).as_vec3().to_array();
            let n = c.normals.get(&h).copied().unwrap_or_else(|| match shading {
                Shading::Flat => unit_or_up(face_normal, || neighbours_normal(m, f)),
                Shading::Smooth => unit_or_up(m.vertex_normal(v), || neighbours_normal(m, f)),
            });
            let n = n.as_vec3().to_array();
            let uv = c
                .uvs
                .get(&h)
                .map_or([0.0, 0.0], |uv| [uv.x as f32, (1.0 - uv.y) as f32]);
            let key = [p[0], p[1], p[2], n[0], n[1], n[2], uv[0], uv[1]].map(f32::to_bits);
            let index = *seen.entry(key).or_insert_with(|| {
                positions.push(p);
                normals.push(n);
                if with_uvs {
                    uvs.push(uv);
                }
                positions.len() as u32 - 1
            });
            corners.push((v, index));
        }
        for tri in hedra_geom::query::triangulate_face(m, f) {
            indices.extend(tri.map(|v| {
                corners
                    .iter()
                    .find(|(c, _)| *c == v)
                    .expect("a triangle corner is a face corner")
                    .1
            }));
        }
    }
    (positions, normals, uvs, indices)
}

/// One primitive's arrays, as the buffer will hold them: positions (with
/// their count and bounds), and normals, UVs and indices where there are
/// any.
pub(crate) struct PrimitiveArrays<'a> {
    positions: BufferArray<'a>,
    vertex_count: usize,
    bounds: ([f32; 3], [f32; 3]),
    normals: Option<BufferArray<'a>>,
    uvs: Option<BufferArray<'a>>,
    indices: Option<BufferArray<'a>>,
    mode: json::mesh::Mode,
}

impl PrimitiveArrays<'_> {
    /// Arrays held in memory; empty ones are left out.
    fn new(
        positions: Vec<[f32; 3]>,
        normals: Vec<[f32; 3]>,
        uvs: Vec<[f32; 2]>,
        indices: Vec<u32>,
        mode: json::mesh::Mode,
    ) -> Self {
        let f32s = |v: Vec<f32>| (!v.is_empty()).then_some(BufferArray::F32(v));
        PrimitiveArrays {
            vertex_count: positions.len(),
            bounds: bounds(&positions),
            positions: BufferArray::F32(positions.into_flattened()),
            normals: f32s(normals.into_flattened()),
            uvs: f32s(uvs.into_flattened()),
            indices: (!indices.is_empty()).then_some(BufferArray::U32(indices)),
            mode,
        }
    }
}

/// A subdivided mesh's arrays: from the refiner's faces as the GLB is
/// written ([`arrays_from_faces`]); from the mesh, built for it, where
/// its adjacency is needed.
fn refined_arrays(
    refined: crate::export::RefinedFaces,
    shading: Shading,
) -> PrimitiveArrays<'static> {
    let refined = std::sync::Arc::new(refined);
    arrays_from_faces(&refined, shading).unwrap_or_else(|| {
        let (m, creases) = refined.to_mesh();
        let (p, n, i) = mesh_triangles(&m, shading, &creases);
        PrimitiveArrays::new(p, n, Vec::new(), i, json::mesh::Mode::Triangles)
    })
}

/// A subdivided mesh's arrays made from the refiner's faces as the GLB is
/// written, in pieces on all cores (the same numbers `mesh_triangles`
/// gives the subdivided mesh: the export holds no copy of the file).
/// `None` where the mesh is needed: a face or vertex without a normal,
/// normals split at infinitely sharp edges.
pub(crate) fn arrays_from_faces(
    refined: &std::sync::Arc<crate::export::RefinedFaces>,
    shading: Shading,
) -> Option<PrimitiveArrays<'static>> {
    use crate::export::VERTICES_PER_PIECE;
    let smooth = shading == Shading::Smooth;
    let smooth_normals = if smooth {
        Some(refined.smooth_normals()?)
    } else if refined.faces_have_normals() {
        None
    } else {
        return None;
    };
    let pieces = refined.piece_count();
    let corner_starts = std::sync::Arc::new(refined.piece_corner_starts());
    let index_count = 3 * refined.triangle_count();
    let indices = {
        let (refined, corner_starts) = (refined.clone(), corner_starts.clone());
        BufferArray::made(index_count, pieces, move |piece, put| {
            refined.piece_triangle_indices(piece, smooth, corner_starts[piece], &mut *put)
        })
    };
    let (vertex_count, positions, normals) = match smooth_normals {
        Some(normals) => {
            let count = normals.len();
            let positions = {
                let refined = refined.clone();
                BufferArray::made(
                    3 * count,
                    count.div_ceil(VERTICES_PER_PIECE),
                    move |piece, put| {
                        let range = piece * VERTICES_PER_PIECE
                            ..((piece + 1) * VERTICES_PER_PIECE).min(count);
                        refined.written_positions_f32(range, |p| {
                            p.iter().for_each(|x| put(x.to_bits()))
                        })
                    },
                )
            };
            (count, positions, BufferArray::F32(normals.into_flattened()))
        }
        None => {
            let count = corner_starts[pieces] as usize;
            let corners = |normal: bool| {
                let refined = refined.clone();
                BufferArray::made(3 * count, pieces, move |piece, put| {
                    refined.piece_flat_corners(piece, |p, n| {
                        let x = if normal { n } else { p };
                        x.iter().for_each(|x| put(x.to_bits()));
                    })
                })
            };
            (count, corners(false), corners(true))
        }
    };
    Some(PrimitiveArrays {
        positions,
        vertex_count,
        bounds: refined.written_bounds(),
        normals: Some(normals),
        uvs: None,
        indices: (index_count > 0).then_some(indices),
        mode: json::mesh::Mode::Triangles,
    })
}

#[cfg(test)]
impl PrimitiveArrays<'_> {
    /// The positions, normals and indices as they are written, read back.
    pub(crate) fn written(&self) -> (Vec<[f32; 3]>, Vec<[f32; 3]>, Vec<u32>) {
        let numbers = |array: &BufferArray| {
            let mut bytes = Vec::new();
            array.write(&mut bytes).unwrap();
            bytes
                .chunks(4)
                .map(|b| u32::from_le_bytes(b.try_into().unwrap()))
                .collect::<Vec<u32>>()
        };
        let vectors = |array: &BufferArray| {
            numbers(array)
                .chunks(3)
                .map(|v| [v[0], v[1], v[2]].map(f32::from_bits))
                .collect::<Vec<[f32; 3]>>()
        };
        let normals = self.normals.as_ref().map(vectors).unwrap_or_default();
        let indices = self.indices.as_ref().map(numbers).unwrap_or_default();
        (vectors(&self.positions), normals, indices)
    }
}

/// A glTF export made from the document: its JSON document and its
/// binary buffer as arrays, written as a `.glb` ([`write_glb`](Self::write_glb))
/// or a `.gltf` ([`to_gltf_text`](Self::to_gltf_text)).
pub struct GltfParts<'a> {
    root: json::Root,
    bin: Buffer<'a>,
}

/// The document's visible nodes as glTF.
///
/// # Errors
/// [`ExportError`] naming a node whose shape cannot be evaluated.
pub fn gltf_parts(doc: &Document, shape: ExportShape) -> Result<GltfParts<'_>, ExportError> {
    let mut root = json::Root {
        asset: json::Asset {
            version: "2.0".into(),
            generator: Some("Hedra".into()),
            copyright: None,
            min_version: None,
            extensions: None,
            extras: Default::default(),
        },
        ..Default::default()
    };
    let mut bin = Buffer::default();
    let mut index_of: HashMap<NodeId, json::Index<json::Node>> = HashMap::new();
    // Visible nodes, without CSG operands (their CSG node writes its
    // solid), parents before children; world transforms are not needed
    // (glTF keeps the hierarchy), visibility is found top down once.
    let tree = doc.hierarchy();
    let visible: Vec<&crate::scene::Node> = doc
        .nodes()
        .filter(|n| tree.is_visible(n.id) && !tree.inside_csg(n.id))
        .collect();
    for node in &visible {
        // A subdivided mesh from the refiner's faces; anything else as
        // every format evaluates it.
        let geometry = match crate::export::refined_geometry(node, shape)? {
            Some(refined) => Some((refined, Cow::Owned(Creases::default()))),
            None => export_geometry_creased(doc, node, shape)?,
        };
        let mesh = match geometry {
            None => None,
            Some((geometry, creases)) => {
                let (shading, corners) = match &node.content {
                    NodeContent::Mesh(c) => (c.shading, Some(&c.corners)),
                    NodeContent::Kept(c) => (c.shading, None),
                    // A CSG solid is drawn flat, as the viewport draws it.
                    NodeContent::Csg(_) => (Shading::Flat, None),
                    _ => (Shading::Smooth, None),
                };
                let arrays = match geometry {
                    // The cage carries the corner attributes; a subdivided shape does not.
                    Geometry::Mesh(std::borrow::Cow::Borrowed(m))
                        if corners.is_some_and(|c| !c.is_empty()) =>
                    {
                        let (p, n, t, i) =
                            corner_triangles(m, shading, corners.expect("checked above"));
                        PrimitiveArrays::new(p, n, t, i, json::mesh::Mode::Triangles)
                    }
                    Geometry::Mesh(m)
                        if shading == Shading::Flat
                            && m.face_count() >= crate::export::FACES_PER_PIECE =>
                    {
                        flat_mesh_arrays(m)
                    }
                    Geometry::Mesh(m) => {
                        let (p, n, i) = mesh_triangles(&m, shading, &creases);
                        PrimitiveArrays::new(p, n, Vec::new(), i, json::mesh::Mode::Triangles)
                    }
                    Geometry::Refined(r) => refined_arrays(r, shading),
                    Geometry::Polygons(k) => {
                        let b = crate::render::kept_render_buffers(&k, shading);
                        PrimitiveArrays::new(
                            b.positions,
                            b.normals,
                            Vec::new(),
                            b.indices,
                            json::mesh::Mode::Triangles,
                        )
                    }
                    Geometry::Triangles(p, n, tris) => {
                        let positions: Vec<[f32; 3]> =
                            p.iter().map(|x| x.as_vec3().to_array()).collect();
                        // The surface's own normals; a point where even the
                        // limit is undefined takes its triangles' normals.
                        let mut area = vec![DVec3::ZERO; p.len()];
                        for t in &tris {
                            let [a, b, c] = t.map(|i| p[i as usize]);
                            for i in t {
                                area[*i as usize] += (b - a).cross(c - a);
                            }
                        }
                        let normals = n
                            .iter()
                            .zip(&area)
                            .map(|(n, area)| {
                                unit_or_up(n.normalize_or_zero(), || *area)
                                    .as_vec3()
                                    .to_array()
                            })
                            .collect();
                        PrimitiveArrays::new(
                            positions,
                            normals,
                            Vec::new(),
                            tris.into_flattened(),
                            json::mesh::Mode::Triangles,
                        )
                    }
                    Geometry::Polyline(p) => PrimitiveArrays::new(
                        p.iter().map(|x| x.as_vec3().to_array()).collect(),
                        Vec::new(),
                        Vec::new(),
                        Vec::new(),
                        json::mesh::Mode::LineStrip,
                    ),
                    // Not made for glTF (node_geometry tessellates curves).
                    Geometry::FreeForm(c) => PrimitiveArrays::new(
                        crate::export::curve_polyline(&c)
                            .iter()
                            .map(|x| x.as_vec3().to_array())
                            .collect(),
                        Vec::new(),
                        Vec::new(),
                        Vec::new(),
                        json::mesh::Mode::LineStrip,
                    ),
                };
                let PrimitiveArrays {
                    positions,
                    vertex_count,
                    bounds: position_bounds,
                    normals,
                    uvs,
                    indices,
                    mode,
                } = arrays;
                let view = push_view(
                    &mut root,
                    &mut bin,
                    positions,
                    json::buffer::Target::ArrayBuffer,
                );
                let pos = push_accessor(
                    &mut root,
                    view,
                    vertex_count,
                    json::accessor::ComponentType::F32,
                    json::accessor::Type::Vec3,
                    Some(position_bounds),
                );
                let mut attributes = BTreeMap::new();
                attributes.insert(Valid(json::mesh::Semantic::Positions), pos);
                if let Some(normals) = normals {
                    let count = normals.len() / 3;
                    let view = push_view(
                        &mut root,
                        &mut bin,
                        normals,
                        json::buffer::Target::ArrayBuffer,
                    );
                    let nrm = push_accessor(
                        &mut root,
                        view,
                        count,
                        json::accessor::ComponentType::F32,
                        json::accessor::Type::Vec3,
                        None,
                    );
                    attributes.insert(Valid(json::mesh::Semantic::Normals), nrm);
                }
                if let Some(uvs) = uvs {
                    let count = uvs.len() / 2;
                    let view =
                        push_view(&mut root, &mut bin, uvs, json::buffer::Target::ArrayBuffer);
                    let tex = push_accessor(
                        &mut root,
                        view,
                        count,
                        json::accessor::ComponentType::F32,
                        json::accessor::Type::Vec2,
                        None,
                    );
                    attributes.insert(Valid(json::mesh::Semantic::TexCoords(0)), tex);
                }
                let indices = indices.map(|indices| {
                    let count = indices.len();
                    let view = push_view(
                        &mut root,
                        &mut bin,
                        indices,
                        json::buffer::Target::ElementArrayBuffer,
                    );
                    push_accessor(
                        &mut root,
                        view,
                        count,
                        json::accessor::ComponentType::U32,
                        json::accessor::Type::Scalar,
                        None,
                    )
                });
                Some(root.push(json::Mesh {
                    extensions: None,
                    extras: Default::default(),
                    name: Some(node.name.clone()),
                    primitives: vec![json::mesh::Primitive {
                        attributes,
                        extensions: None,
                        extras: Default::default(),
                        indices,
                        material: None,
                        mode: Valid(mode),
                        targets: None,
                    }],
                    weights: None,
                }))
            }
        };
        let t = node.transform;
        let index = root.push(json::Node {
            mesh,
            name: Some(node.name.clone()),
            translation: Some(t.translation.as_vec3().to_array()),
            rotation: Some(json::scene::UnitQuaternion(t.rotation.as_quat().to_array())),
            scale: Some(t.scale.as_vec3().to_array()),
            ..Default::default()
        });
        index_of.insert(node.id, index);
    }
    // Children (in document order), and the roots of the scene.
    let mut roots = Vec::new();
    for node in &visible {
        let me = index_of[&node.id];
        match node.parent.and_then(|p| index_of.get(&p)) {
            Some(parent) => {
                let parent = &mut root.nodes[parent.value()];
                parent.children.get_or_insert_with(Vec::new).push(me);
            }
            None => roots.push(me),
        }
    }
    let scene = root.push(json::Scene {
        extensions: None,
        extras: Default::default(),
        name: None,
        nodes: roots,
    });
    root.scene = Some(scene);
    if bin.length > 0 {
        root.push(json::Buffer {
            byte_length: USize64(bin.length as u64),
            name: None,
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
    }
    Ok(GltfParts { root, bin })
}

impl GltfParts<'_> {
    /// The `.gltf` text: the buffer embedded as a base64 data URI.
    ///
    /// # Errors
    /// [`ExportError::GltfJson`] when the JSON cannot be written.
    pub fn to_gltf_text(mut self) -> Result<Vec<u8>, ExportError> {
        if let Some(buffer) = self.root.buffers.first_mut() {
            let mut bytes = Vec::with_capacity(self.bin.length);
            self.bin
                .write(&mut bytes)
                .expect("writing to memory cannot fail");
            buffer.uri = Some(format!(
                "data:application/octet-stream;base64,{}",
                base64::engine::general_purpose::STANDARD.encode(&bytes)
            ));
        }
        self.root
            .to_string()
            .map(String::into_bytes)
            .map_err(|e| ExportError::GltfJson(e.to_string()))
    }

    /// Writes the `.glb`: the 12-byte header, the JSON chunk (padded with
    /// spaces to 4 bytes) and the binary chunk, streamed from the arrays
    /// (glTF 2.0, section 4.4 "GLB File Format Specification").
    ///
    /// # Errors
    /// What `out` returns; JSON that cannot be written, as
    /// [`std::io::ErrorKind::InvalidData`].
    pub fn write_glb(&self, out: &mut dyn std::io::Write) -> std::io::Result<()> {
        let mut json_bytes = self
            .root
            .to_string()
            .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string()))?
            .into_bytes();
        while !json_bytes.len().is_multiple_of(4) {
            json_bytes.push(b' ');
        }
        let bin_chunk = if self.bin.length == 0 {
            0
        } else {
            8 + self.bin.length
        };
        let length = 12 + 8 + json_bytes.len() + bin_chunk;
        let too_large = || {
            std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("the GLB would be {length} bytes; GLB holds at most 4 GiB"),
            )
        };
        let word = |n: usize| {
            u32::try_from(n)
                .map(u32::to_le_bytes)
                .map_err(|_| too_large())
        };
        out.write_all(b"glTF")?;
        out.write_all(&2u32.to_le_bytes())?;
        out.write_all(&word(length)?)?;
        out.write_all(&word(json_bytes.len())?)?;
        out.write_all(b"JSON")?;
        out.write_all(&json_bytes)?;
        if self.bin.length > 0 {
            out.write_all(&word(self.bin.length)?)?;
            out.write_all(b"BIN\0")?;
            self.bin.write(out)?;
        }
        Ok(())
    }
}

mod read;
pub use read::*;
