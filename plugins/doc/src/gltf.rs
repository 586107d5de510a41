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
struct Buffer {
    arrays: Vec<BufferArray>,
    /// Bytes so far, with the padding between arrays.
    length: usize,
}

/// One array of the buffer: 4-byte numbers.
enum BufferArray {
    F32(Vec<f32>),
    U32(Vec<u32>),
    /// Numbers made as they are written (as their bits), so that a large
    /// subdivided mesh's arrays are never held: `len` of them, passed to
    /// the sink in pieces.
    Made {
        len: usize,
        make: MakeNumbers,
    },
}

/// Makes an array's numbers and passes them on in pieces; stops at the
/// first error the sink returns.
type MakeNumbers =
    Box<dyn Fn(&mut dyn FnMut(&[u32]) -> std::io::Result<()>) -> std::io::Result<()>>;

impl BufferArray {
    fn len(&self) -> usize {
        match self {
            BufferArray::F32(v) => v.len(),
            BufferArray::U32(v) => v.len(),
            BufferArray::Made { len, .. } => *len,
        }
    }

    /// An array made by `each`, which calls its visitor once per number.
    fn made(len: usize, each: impl Fn(&mut dyn FnMut(u32)) + 'static) -> BufferArray {
        BufferArray::Made {
            len,
            make: Box::new(move |sink| {
                let mut piece: Vec<u32> = Vec::with_capacity(1 << 14);
                let mut result = Ok(());
                each(&mut |x| {
                    piece.push(x);
                    if piece.len() == piece.capacity() {
                        if result.is_ok() {
                            result = sink(&piece);
                        }
                        piece.clear();
                    }
                });
                result?;
                sink(&piece)
            }),
        }
    }
}

/// Appends `numbers` to the buffer (4-byte aligned: every number is 4
/// bytes) and returns their view.
fn push_view(
    root: &mut json::Root,
    bin: &mut Buffer,
    numbers: BufferArray,
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

impl Buffer {
    /// Writes the arrays as little-endian bytes, through a small staging
    /// buffer.
    fn write(&self, out: &mut dyn std::io::Write) -> std::io::Result<()> {
        let mut staged: Vec<u8> = Vec::with_capacity(1 << 16);
        let mut put = |bytes: [u8; 4], out: &mut dyn std::io::Write| {
            staged.extend_from_slice(&bytes);
            if staged.len() >= 1 << 16 {
                out.write_all(&staged)?;
                staged.clear();
            }
            Ok::<(), std::io::Error>(())
        };
        for array in &self.arrays {
            match array {
                BufferArray::F32(v) => v.iter().try_for_each(|x| put(x.to_le_bytes(), out))?,
                BufferArray::U32(v) => v.iter().try_for_each(|x| put(x.to_le_bytes(), out))?,
                BufferArray::Made { len, make } => {
                    let mut written = 0;
                    make(&mut |piece| {
                        written += piece.len();
                        piece.iter().try_for_each(|x| put(x.to_le_bytes(), out))
                    })?;
                    if written != *len {
                        return Err(std::io::Error::other(format!(
                            "a glTF array made {written} numbers where its view holds {len}"
                        )));
                    }
                }
            }
        }
        out.write_all(&staged)
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
struct PrimitiveArrays {
    positions: BufferArray,
    vertex_count: usize,
    bounds: ([f32; 3], [f32; 3]),
    normals: Option<BufferArray>,
    uvs: Option<BufferArray>,
    indices: Option<BufferArray>,
    mode: json::mesh::Mode,
}

impl PrimitiveArrays {
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

/// A subdivided mesh's arrays made from the refiner's faces as the GLB is
/// written (the same numbers `mesh_triangles` gives the subdivided mesh:
/// the export holds no copy of the file); from the mesh, built for it,
/// where its adjacency is needed (a face or vertex without a normal,
/// normals split at infinitely sharp edges).
fn refined_arrays(refined: crate::export::RefinedFaces, shading: Shading) -> PrimitiveArrays {
    let smooth = shading == Shading::Smooth;
    let smooth_normals = if smooth {
        refined.smooth_normals()
    } else {
        None
    };
    if (smooth && smooth_normals.is_none()) || (!smooth && !refined.faces_have_normals()) {
        let (m, creases) = refined.to_mesh();
        let (p, n, i) = mesh_triangles(&m, shading, &creases);
        return PrimitiveArrays::new(p, n, Vec::new(), i, json::mesh::Mode::Triangles);
    }
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    refined.each_position(|p| {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    });
    let refined = std::rc::Rc::new(refined);
    let index_count = 3 * refined.triangle_count();
    let indices = {
        let refined = refined.clone();
        BufferArray::made(index_count, move |put| {
            refined.each_triangle_index(smooth, &mut *put)
        })
    };
    let (vertex_count, positions, normals) = match smooth_normals {
        Some(normals) => {
            let count = normals.len();
            let positions = {
                let refined = refined.clone();
                BufferArray::made(3 * count, move |put| {
                    refined.each_position(|p| p.iter().for_each(|x| put(x.to_bits())))
                })
            };
            (count, positions, BufferArray::F32(normals.into_flattened()))
        }
        None => {
            let count = refined.corner_count();
            let corners = |normal: bool| {
                let refined = refined.clone();
                BufferArray::made(3 * count, move |put| {
                    refined.each_flat_corner(|p, n| {
                        let x = if normal { n } else { p };
                        x.iter().for_each(|x| put(x.to_bits()));
                    })
                })
            };
            (count, corners(false), corners(true))
        }
    };
    PrimitiveArrays {
        positions,
        vertex_count,
        bounds: (lo, hi),
        normals: Some(normals),
        uvs: None,
        indices: (index_count > 0).then_some(indices),
        mode: json::mesh::Mode::Triangles,
    }
}

/// A glTF export made from the document: its JSON document and its
/// binary buffer as arrays, written as a `.glb` ([`write_glb`](Self::write_glb))
/// or a `.gltf` ([`to_gltf_text`](Self::to_gltf_text)).
pub struct GltfParts {
    root: json::Root,
    bin: Buffer,
}

/// The document's visible nodes as glTF.
///
/// # Errors
/// [`ExportError`] naming a node whose shape cannot be evaluated.
pub fn gltf_parts(doc: &Document, shape: ExportShape) -> Result<GltfParts, ExportError> {
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

impl GltfParts {
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

/// Reads a `.gltf` or `.glb` file's scene: every node becomes a node with
/// its parent, name and local transform; triangle primitives become one
/// half-edge mesh per node with equal positions welded (other primitive
/// modes (points, lines) are skipped and reported; strips and fans are
/// triangles). `base` is the file's folder: external
/// buffer files are read only from inside it ([`crate::reference`]).
///
/// # Errors
/// [`ImportError::Read`] naming the problem (not glTF, a missing buffer,
/// bad indices), [`ImportError::Empty`] when there are no nodes.
pub fn gltf_from_bytes(
    bytes: &[u8],
    base: Option<&Path>,
    path: &str,
) -> Result<Vec<ImportedMesh>, ImportError> {
    let err = |message: String| ImportError::Read {
        path: path.to_string(),
        message,
    };
    let gltf_error = |error: GltfError| ImportError::Gltf {
        path: path.to_string(),
        error: Box::new(error),
    };
    check_before_validation(bytes).map_err(gltf_error)?;
    let gltf = gltf::Gltf::from_slice(bytes).map_err(|e| {
        // Why a 2.0 reader fails on it, said plainly for glTF 1 files
        // (looked at only when reading failed).
        let why = match gltf1_version(bytes) {
            Some(v) => format!("glTF {v}, which Hedra does not read: re-export it as glTF 2.0"),
            None => e.to_string(),
        };
        err(format!("not a readable glTF file ({why})"))
    })?;
    let mut buffers: Vec<Vec<u8>> = Vec::new();
    for buffer in gltf.document.buffers() {
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => gltf
                .blob
                .clone()
                .ok_or_else(|| err("the GLB has no binary chunk".into()))?,
            gltf::buffer::Source::Uri(uri) if uri.starts_with("data:") => {
                let encoded = uri.split_once(";base64,").map(|(_, d)| d).ok_or_else(|| {
                    err(format!(
                        "buffers[{}]: a data URI that is not base64",
                        buffer.index()
                    ))
                })?;
                base64::engine::general_purpose::STANDARD
                    .decode(encoded)
                    .map_err(|e| err(format!("buffers[{}]: bad base64 ({e})", buffer.index())))?
            }
            // Another file: only inside this file's folder (crate::reference).
            gltf::buffer::Source::Uri(uri) => {
                let folder = base.ok_or_else(|| {
                    err(format!(
                        "buffers[{}] refers to '{uri}', which cannot be found",
                        buffer.index()
                    ))
                })?;
                crate::reference::read_inside(folder, uri, buffer.length() as u64)
                    .map_err(|e| err(format!("buffers[{}] {e}", buffer.index())))?
            }
        };
        if data.len() < buffer.length() {
            return Err(err(format!(
                "buffers[{}] has {} bytes, the file says {}",
                buffer.index(),
                data.len(),
                buffer.length()
            )));
        }
        buffers.push(data);
    }
    let scene = gltf
        .document
        .default_scene()
        .or_else(|| gltf.document.scenes().next())
        .ok_or_else(|| ImportError::Empty {
            path: path.to_string(),
        })?;
    let mut out: Vec<ImportedMesh> = Vec::new();
    let mut stack: Vec<(gltf::Node, Option<usize>)> = scene
        .nodes()
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .map(|n| (n, None))
        .collect();
    // glTF nodes form disjoint trees: a node reached twice (a cycle, or two
    // parents) would be imported again and again.
    let mut reached = vec![false; gltf.document.nodes().len()];
    while let Some((node, parent)) = stack.pop() {
        if std::mem::replace(&mut reached[node.index()], true) {
            return Err(err(format!(
                "nodes[{}] is reached twice (a cycle, or a node with two parents); glTF nodes must form trees",
                node.index()
            )));
        }
        let (t, r, s) = node.transform().decomposed();
        let transform = NodeTransform {
            translation: DVec3::from_array(t.map(f64::from)),
            rotation: DQuat::from_array(r.map(f64::from)).normalize(),
            scale: DVec3::from_array(s.map(f64::from)),
        };
        // A zero quaternion, a degenerate matrix, a huge value.
        if !(transform.translation.is_finite()
            && transform.rotation.is_finite()
            && transform.scale.is_finite())
        {
            return Err(err(format!(
                "nodes[{}]: its transform is not finite (translation {t:?}, rotation {r:?}, scale {s:?})",
                node.index()
            )));
        }
        let mut positions: Vec<DVec3> = Vec::new();
        let mut polygons: Vec<Vec<u32>> = Vec::new();
        // Per corner of `polygons`, in order (None where the file has none).
        let mut corner_uvs: Vec<Option<DVec2>> = Vec::new();
        let mut corner_normals: Vec<Option<DVec3>> = Vec::new();
        let mut skipped = 0usize;
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                let mode = primitive.mode();
                if !matches!(
                    mode,
                    gltf::mesh::Mode::Triangles
                        | gltf::mesh::Mode::TriangleStrip
                        | gltf::mesh::Mode::TriangleFan
                ) {
                    skipped += 1;
                    continue;
                }
                check_accessors(&primitive, &buffers).map_err(|error| {
                    gltf_error(GltfError::Accessor {
                        mesh: mesh.name().unwrap_or("?").to_string(),
                        error,
                    })
                })?;
                let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| d.as_slice()));
                let Some(points) = reader.read_positions() else {
                    skipped += 1;
                    continue;
                };
                let base_index = positions.len() as u32;
                positions.extend(points.map(|p| DVec3::from_array(p.map(f64::from))));
                let count = positions.len() as u32 - base_index;
                let indices: Vec<u32> = match reader.read_indices() {
                    Some(i) => i.into_u32().collect(),
                    None => (0..count).collect(),
                };
                if let Some(bad) = indices.iter().find(|&&i| i >= count) {
                    return Err(err(format!(
                        "mesh '{}': index {bad} is past its {count} positions",
                        mesh.name().unwrap_or("?")
                    )));
                }
                let vertex_normals: Vec<DVec3> = reader
                    .read_normals()
                    .map(|n| n.map(|x| DVec3::from_array(x.map(f64::from))).collect())
                    .unwrap_or_default();
                // glTF's v runs down; Hedra stores v up like OBJ.
                let vertex_uvs: Vec<DVec2> = reader
                    .read_tex_coords(0)
                    .map(|t| {
                        t.into_f32()
                            .map(|[u, v]| DVec2::new(short(u), short(1.0 - v)))
                            .collect()
                    })
                    .unwrap_or_default();
                let indices = triangle_list(mode, &indices);
                let triangles = indices.chunks_exact(3);
                for &i in indices.iter().take(triangles.len() * 3) {
                    corner_uvs.push(vertex_uvs.get(i as usize).copied());
                    corner_normals.push(vertex_normals.get(i as usize).copied());
                }
                polygons.extend(triangles.map(|t| t.iter().map(|i| i + base_index).collect()));
            }
        }
        let name = node
            .name()
            .map_or_else(|| format!("Node {}", node.index()), str::to_string);
        let mesh = if polygons.is_empty() {
            None
        } else {
            let (welded, polys) = weld(&positions, &polygons);
            let (mesh, report) = HalfEdgeMesh::from_polygons_repaired(&welded, &polys)
                .map_err(|e| err(format!("node '{name}': {e}")))?;
            let mesh = mesh.compacted_if_needed();
            let arities = vec![3; polys.len()];
            let corners = corner_attributes(&mesh, &report, &arities, &corner_uvs, &corner_normals);
            // The triangles as the file gave them, should import keep them.
            let input = (!report.is_clean()).then_some(crate::kept::KeptMesh {
                positions: welded,
                faces: polys,
            });
            Some((mesh, report, corners, input))
        };
        let me = out.len();
        out.push(ImportedMesh {
            name,
            // All triangles dropped (degenerate, say): an empty node, the
            // report says why.
            mesh: mesh
                .as_ref()
                .map(|(m, ..)| m.clone())
                .filter(|m| m.face_count() > 0),
            corners: mesh
                .as_ref()
                .map(|(_, _, c, _)| c.clone())
                .unwrap_or_default(),
            input: mesh.as_ref().and_then(|(.., i)| i.clone()),
            report: mesh.map(|(_, r, ..)| r).unwrap_or_default(),
            parent,
            transform,
            skipped_primitives: skipped,
            skipped_polylines: 0,
            // The node's triangles, counted from 1 over its primitives.
            face_numbers: crate::import::FaceNumbers::Triangles { offset: 0 },
            not_imported: Vec::new(),
            vertex_numbers: Vec::new(),
            curve: None,
            content: None,
            hidden: false,
            kept_places: Vec::new(),
        });
        for child in node.children().collect::<Vec<_>>().into_iter().rev() {
            stack.push((child, Some(me)));
        }
    }
    if out.is_empty() {
        return Err(ImportError::Empty {
            path: path.to_string(),
        });
    }
    // What Hedra does not keep, said once for the file.
    let d = &gltf.document;
    let morphs = d
        .meshes()
        .flat_map(|m| m.primitives())
        .filter(|p| p.morph_targets().next().is_some())
        .count();
    let counts = [
        (d.materials().len(), "material(s)"),
        (d.textures().len(), "texture(s)"),
        (d.skins().len(), "skin(s)"),
        (
            morphs,
            "primitive(s) with morph targets (their base shape is kept)",
        ),
        (d.animations().len(), "animation(s)"),
        (d.cameras().len(), "camera(s)"),
    ];
    out[0].not_imported = counts
        .iter()
        .filter(|(n, _)| *n > 0)
        .map(|(n, what)| format!("{n} {what}"))
        .collect();
    Ok(out)
}

/// An f32 of the file as the shortest decimal that reads back as it (what
/// the file's writer meant: 0.1, not 0.10000000149011612), so scenes store
/// imported UVs in a few digits.
fn short(x: f32) -> f64 {
    x.to_string().parse().unwrap_or(f64::from(x))
}

/// The version of a glTF 1.x file ("1.0"), once the 2.0 reader failed on
/// it: a GLB header of version 1, or JSON whose `asset.version`
/// starts with 1 or that keeps `accessors` as a map (glTF 1 keys its
/// objects by name; 2.0 lists them).
fn gltf1_version(bytes: &[u8]) -> Option<String> {
    if let Some(v) = bytes.strip_prefix(b"glTF").and_then(|h| h.get(..4)) {
        return (u32::from_le_bytes([v[0], v[1], v[2], v[3]]) == 1).then(|| "1.0 binary".into());
    }
    let value: serde_json::Value = serde_json::from_slice(bytes).ok()?;
    let version = value["asset"]["version"].as_str().unwrap_or("");
    if version.starts_with("1.") {
        return Some(version.to_string());
    }
    value["accessors"].is_object().then(|| "1.0".to_string())
}

/// Why a glTF file is refused before its meshes are read: what the `gltf`
/// crate would read out of bounds, panic on or silently read wrong.
/// glTF objects are named by their place in the file's JSON, counted from
/// 0 as there and written as the `gltf` crate's own messages write them
/// (`nodes[2]`, `meshes[0].primitives[1]`, `accessors[6]`, `bufferViews[3]`,
/// `buffers[0]`), so they cannot be taken for counts (a triangle, a line
/// and a face are counted from 1).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GltfError {
    /// A GLB header whose total length is less than the 12-byte header.
    #[error(
        "not a readable glTF file (the GLB header gives a length of {length} bytes, less than the header itself)"
    )]
    GlbLengthShort {
        /// The length the header gives, in bytes.
        length: u32,
    },
    /// A primitive attribute naming an accessor past the file's list.
    #[error(
        "not a readable glTF file (meshes[{mesh}].primitives[{primitive}]: an attribute uses accessors[{accessor}], but the file has {accessors} accessors)"
    )]
    AccessorPastList {
        /// The mesh's index.
        mesh: usize,
        /// The primitive's index in its mesh.
        primitive: usize,
        /// The accessor index the attribute gives.
        accessor: usize,
        /// How many accessors the file has.
        accessors: usize,
    },
    /// The file requires extensions Hedra does not read (`extensionsRequired`):
    /// Draco or meshopt compressed meshes, quantized attributes. Said once,
    /// before the `gltf` crate lists every accessor it cannot read.
    #[error(
        "needs the glTF extension(s) {}, which Hedra does not read{}",
        .extensions.join(", "),
        if .extensions.iter().any(|e| e.contains("compression")) {
            " (compressed meshes): export it again without mesh compression"
        } else {
            ""
        }
    )]
    ExtensionsRequired {
        /// The required extensions, as the file names them.
        extensions: Vec<String>,
    },
    /// An accessor of a triangle primitive that Hedra would read (its
    /// positions, normals, first UVs or indices) is unusable.
    #[error("mesh '{mesh}': {error}")]
    Accessor {
        /// The mesh's name, `?` when it has none.
        mesh: String,
        /// What is wrong with the accessor.
        error: AccessorError,
    },
}

/// Why an accessor of a glTF primitive cannot be read.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum AccessorError {
    /// Elements of a type or component type the attribute cannot have
    /// (positions and normals are `VEC3` floats; UVs `VEC2` floats or
    /// normalised bytes or shorts; indices unsigned scalars).
    #[error(
        "accessors[{accessor}] has {dimensions:?} {data_type:?} elements, which this attribute cannot have"
    )]
    Layout {
        /// The accessor's index.
        accessor: usize,
        /// Its element type.
        dimensions: gltf::accessor::Dimensions,
        /// Its component type.
        data_type: gltf::accessor::DataType,
    },
    /// A sparse accessor.
    #[error("accessors[{accessor}] is sparse, which is not supported")]
    Sparse {
        /// The accessor's index.
        accessor: usize,
    },
    /// An accessor with a count of zero.
    #[error("accessors[{accessor}] has no elements")]
    NoElements {
        /// The accessor's index.
        accessor: usize,
    },
    /// An accessor without a buffer view (all zeros, which Hedra does not
    /// read).
    #[error("accessors[{accessor}] has no buffer view")]
    NoBufferView {
        /// The accessor's index.
        accessor: usize,
    },
    /// A buffer view's byte stride shorter than the accessor's elements.
    #[error(
        "bufferViews[{view}] has a stride of {stride} bytes, less than accessors[{accessor}]'s {size}-byte elements"
    )]
    StrideShort {
        /// The buffer view's index.
        view: usize,
        /// Its byte stride.
        stride: u128,
        /// The accessor's index.
        accessor: usize,
        /// The size of one of its elements, in bytes.
        size: u128,
    },
    /// An accessor reaching past the end of its buffer view.
    #[error(
        "accessors[{accessor}] ({count} elements of {size} bytes) needs {needed} bytes, but bufferViews[{view}] has {length}"
    )]
    PastView {
        /// The accessor's index.
        accessor: usize,
        /// Its element count.
        count: u128,
        /// The size of one element, in bytes.
        size: u128,
        /// Bytes from the view's start to the end of the last element.
        needed: u128,
        /// The buffer view's index.
        view: usize,
        /// The view's length in bytes.
        length: usize,
    },
    /// A buffer view reaching past the end of its buffer's data.
    #[error(
        "bufferViews[{view}] (bytes {start}..{end}) lies outside buffers[{buffer}] of {have} bytes"
    )]
    ViewOutsideBuffer {
        /// The buffer view's index.
        view: usize,
        /// The view's first byte in the buffer.
        start: usize,
        /// One past the view's last byte in the buffer.
        end: u128,
        /// The buffer's index.
        buffer: usize,
        /// The bytes the buffer has.
        have: usize,
    },
}

/// What `gltf` reads or validates without checking: a GLB length shorter
/// than its header, required extensions (which `gltf` reports as one
/// "Missing data" per accessor they hold), and (gltf-json 1.4 panics) a
/// primitive's `POSITION` naming an accessor past the list.
/// Files that do not even parse are left to `gltf` to report.
fn check_before_validation(bytes: &[u8]) -> Result<(), GltfError> {
    // `gltf` subtracts the 12-byte header from the stated length unchecked.
    if let Some(&[a, b, c, d]) = bytes.strip_prefix(b"glTF").and_then(|h| h.get(4..8)) {
        let length = u32::from_le_bytes([a, b, c, d]);
        if length < 12 {
            return Err(GltfError::GlbLengthShort { length });
        }
    }
    let text: std::borrow::Cow<[u8]> = if bytes.starts_with(b"glTF") {
        match gltf::binary::Glb::from_slice(bytes) {
            Ok(glb) => glb.json,
            Err(_) => return Ok(()),
        }
    } else {
        bytes.into()
    };
    let Ok(root) = json::Root::from_slice(&text) else {
        return Ok(());
    };
    if !root.extensions_required.is_empty() {
        return Err(GltfError::ExtensionsRequired {
            extensions: root.extensions_required.clone(),
        });
    }
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            for accessor in primitive.attributes.values() {
                if accessor.value() >= root.accessors.len() {
                    return Err(GltfError::AccessorPastList {
                        mesh: m,
                        primitive: p,
                        accessor: accessor.value(),
                        accessors: root.accessors.len(),
                    });
                }
            }
        }
    }
    Ok(())
}

/// Every accessor of a primitive lies inside its buffer view and every view
/// inside its buffer (the `gltf` reader silently gives nothing otherwise,
/// and a count larger than the data must not be trusted).
fn check_accessors(primitive: &gltf::Primitive, buffers: &[Vec<u8>]) -> Result<(), AccessorError> {
    use gltf::accessor::{DataType, Dimensions};
    use gltf::mesh::Semantic;
    // The attributes Hedra reads, with the layouts the `gltf` reader
    // assumes (it only debug-asserts them).
    let read = primitive
        .attributes()
        .filter_map(|(semantic, a)| {
            let layouts: &[(Dimensions, DataType)] = match semantic {
                Semantic::Positions | Semantic::Normals => &[(Dimensions::Vec3, DataType::F32)],
                Semantic::TexCoords(0) => &[
                    (Dimensions::Vec2, DataType::F32),
                    (Dimensions::Vec2, DataType::U8),
                    (Dimensions::Vec2, DataType::U16),
                ],
                _ => return None,
            };
            Some((a, layouts))
        })
        .chain(primitive.indices().map(|a| {
            let layouts: &[(Dimensions, DataType)] = &[
                (Dimensions::Scalar, DataType::U8),
                (Dimensions::Scalar, DataType::U16),
                (Dimensions::Scalar, DataType::U32),
            ];
            (a, layouts)
        }));
    for (a, layouts) in read {
        if !layouts.contains(&(a.dimensions(), a.data_type())) {
            return Err(AccessorError::Layout {
                accessor: a.index(),
                dimensions: a.dimensions(),
                data_type: a.data_type(),
            });
        }
        if a.sparse().is_some() {
            return Err(AccessorError::Sparse {
                accessor: a.index(),
            });
        }
        if a.count() == 0 {
            return Err(AccessorError::NoElements {
                accessor: a.index(),
            });
        }
        let Some(view) = a.view() else {
            return Err(AccessorError::NoBufferView {
                accessor: a.index(),
            });
        };
        let (count, size) = (a.count() as u128, a.size() as u128);
        let stride = view.stride().map_or(size, |s| s as u128);
        if stride < size {
            return Err(AccessorError::StrideShort {
                view: view.index(),
                stride,
                accessor: a.index(),
                size,
            });
        }
        let needed = if count == 0 {
            0
        } else {
            a.offset() as u128 + stride * (count - 1) + size
        };
        if needed > view.length() as u128 {
            return Err(AccessorError::PastView {
                accessor: a.index(),
                count,
                size,
                needed,
                view: view.index(),
                length: view.length(),
            });
        }
        let buffer = view.buffer().index();
        let have = buffers.get(buffer).map_or(0, Vec::len);
        if view.offset() as u128 + view.length() as u128 > have as u128 {
            return Err(AccessorError::ViewOutsideBuffer {
                view: view.index(),
                start: view.offset(),
                end: view.offset() as u128 + view.length() as u128,
                buffer,
                have,
            });
        }
    }
    Ok(())
}

/// Merges exactly equal positions (glTF splits vertices at normal seams).
fn weld(positions: &[DVec3], polygons: &[Vec<u32>]) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let mut map: HashMap<[u64; 3], u32> = HashMap::new();
    let mut out = Vec::new();
    let remap: Vec<u32> = positions
        .iter()
        .map(|p| {
            let key = p.to_array().map(f64::to_bits);
            *map.entry(key).or_insert_with(|| {
                out.push(*p);
                out.len() as u32 - 1
            })
        })
        .collect();
    let polys = polygons
        .iter()
        .map(|f| f.iter().map(|&i| remap[i as usize]).collect())
        .collect();
    (out, polys)
}
