//! Reading glTF 2.0 (`.gltf`, `.glb`) into nodes, with the checks a
//! damaged or hostile file needs before `gltf` validates it.

use super::*;

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
