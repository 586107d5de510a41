//! The OBJ writer: vertices, faces (n-gons kept), corner UVs and normals,
//! free-form curves; a large mesh's lines made in pieces on all cores.

use super::*;

/// The scene's visible meshes as Wavefront OBJ text, one `o` object per
/// node, positions in world space, faces 1-based and counter-clockwise;
/// surfaces as triangles, curves as `l` polylines. The text is formatted
/// into a buffer that is passed on to `w` whenever it holds
/// [`OBJ_SPILL`] bytes, so the file is never held whole.
pub(super) fn write_obj(items: &[ExportItem], w: &mut dyn ExportOutput) -> std::io::Result<()> {
    let mut out = String::with_capacity(OBJ_SPILL + (1 << 16));
    out.push_str("# Hedra OBJ export\n");
    let mut numbers = Numbers::default();
    let mut base = 1usize;
    // Next 1-based `vt` and `vn` numbers.
    let (mut next_vt, mut next_vn) = (1usize, 1usize);
    for item in items {
        let world = item.world;
        let _ = writeln!(
            out,
            "o {}",
            item.node.name.replace(char::is_whitespace, "_")
        );
        let mut vertex = |out: &mut String, p: DVec3| {
            obj_vertex_line(out, &mut numbers, world.transform_point3(p))
        };
        match &item.geometry {
            Geometry::Mesh(m) if item.corners.is_none() && m.face_count() >= PARALLEL_FACES => {
                w.write_all(out.as_bytes())?;
                out.clear();
                write_mesh_obj_lines(m, world, item.mirrored, base, w)?;
                base += m.vertex_count();
            }
            Geometry::Refined(r) if r.refiner.face_count() >= PARALLEL_FACES => {
                w.write_all(out.as_bytes())?;
                out.clear();
                r.write_obj_lines(world, item.mirrored, base, w)?;
                base += r.order.len();
            }
            Geometry::Mesh(m) => {
                let mut index = vec![0usize; m.vertex_capacity()];
                for (i, v) in m.vertices().enumerate() {
                    index[v.index()] = base + i;
                    vertex(&mut out, m.position(v));
                    spill(&mut out, w)?;
                }
                let Some(c) = item.corners else {
                    let mut vs = Vec::new();
                    for f in m.faces() {
                        vs.clear();
                        vs.extend(m.face_vertices(f).map(|v| index[v.index()]));
                        obj_face_line(&mut out, &mut numbers, &mut vs, item.mirrored);
                        spill(&mut out, w)?;
                    }
                    base += m.vertex_count();
                    continue;
                };
                // Normals go to world space with the inverse transpose.
                let normal_matrix = glam::DMat3::from_mat4(world).inverse().transpose();
                let (mut vts, mut vns, mut faces) = (String::new(), String::new(), String::new());
                let mut vt_of: HashMap<[u64; 2], usize> = HashMap::new();
                let mut vn_of: HashMap<[u64; 3], usize> = HashMap::new();
                for f in m.faces() {
                    let mut hs: Vec<hedra_geom::HalfEdgeId> = m.face_halfedges(f).collect();
                    // Mirrored: the corners in reverse order (each keeps its
                    // vertex, UV and normal).
                    if item.mirrored {
                        hs.reverse();
                    }
                    let with_uv = hs.iter().all(|h| c.uvs.contains_key(h));
                    let with_normal = hs.iter().all(|h| c.normals.contains_key(h));
                    faces.push('f');
                    for h in hs {
                        let _ = write!(faces, " {}", index[m.origin(h).index()]);
                        if with_uv {
                            let uv = c.uvs[&h];
                            let vt = *vt_of.entry(uv.to_array().map(f64::to_bits)).or_insert_with(
                                || {
                                    let _ = writeln!(vts, "vt {} {}", uv.x, uv.y);
                                    next_vt += 1;
                                    next_vt - 1
                                },
                            );
                            let _ = write!(faces, "/{vt}");
                        } else if with_normal {
                            faces.push('/');
                        }
                        if with_normal {
                            let n = (normal_matrix * c.normals[&h]).normalize_or_zero();
                            let vn =
                                *vn_of
                                    .entry(n.to_array().map(f64::to_bits))
                                    .or_insert_with(|| {
                                        let _ = writeln!(vns, "vn {} {} {}", n.x, n.y, n.z);
                                        next_vn += 1;
                                        next_vn - 1
                                    });
                            let _ = write!(faces, "/{vn}");
                        }
                    }
                    faces.push('\n');
                }
                out.push_str(&vts);
                out.push_str(&vns);
                out.push_str(&faces);
                spill(&mut out, w)?;
                base += m.vertex_count();
            }
            Geometry::Refined(r) => {
                for p in r.written_positions() {
                    vertex(&mut out, p);
                    spill(&mut out, w)?;
                }
                let mut vs = Vec::new();
                for face in r.faces() {
                    vs.clear();
                    vs.extend(face.map(|v| base + v as usize));
                    obj_face_line(&mut out, &mut numbers, &mut vs, item.mirrored);
                    spill(&mut out, w)?;
                }
                base += r.order.len();
            }
            Geometry::Triangles(positions, _, tris) => {
                for &p in positions {
                    vertex(&mut out, p);
                    spill(&mut out, w)?;
                }
                for t in tris {
                    let [a, b, c] = if item.mirrored {
                        [t[0], t[2], t[1]]
                    } else {
                        *t
                    };
                    out.push('f');
                    for i in [a, b, c] {
                        out.push(' ');
                        numbers.int(&mut out, base + i as usize);
                    }
                    out.push('\n');
                    spill(&mut out, w)?;
                }
                base += positions.len();
            }
            Geometry::Polygons(k) => {
                for &p in &k.positions {
                    vertex(&mut out, p);
                    spill(&mut out, w)?;
                }
                for f in &k.faces {
                    out.push('f');
                    let mut corner = |i: u32| {
                        out.push(' ');
                        numbers.int(&mut out, base + i as usize);
                    };
                    if item.mirrored {
                        f.iter().rev().for_each(|&i| corner(i));
                    } else {
                        f.iter().for_each(|&i| corner(i));
                    }
                    out.push('\n');
                    spill(&mut out, w)?;
                }
                base += k.positions.len();
            }
            Geometry::Polyline(points) => {
                for &p in points {
                    vertex(&mut out, p);
                }
                out.push('l');
                for i in 0..points.len() {
                    let _ = write!(out, " {}", base + i);
                }
                out.push('\n');
                base += points.len();
            }
            Geometry::FreeForm(curve) => {
                base += write_free_form(&mut out, curve, world, base);
            }
        }
        spill(&mut out, w)?;
    }
    w.write_all(out.as_bytes())
}

/// An OBJ `v` line.
pub(super) fn obj_vertex_line(out: &mut String, numbers: &mut Numbers, p: DVec3) {
    out.push('v');
    for x in [p.x, p.y, p.z] {
        out.push(' ');
        numbers.float(out, x);
    }
    out.push('\n');
}

/// An OBJ `f` line of 1-based vertex numbers, in reverse order when
/// `mirrored` (so the face keeps facing out).
pub(super) fn obj_face_line(
    out: &mut String,
    numbers: &mut Numbers,
    vertices: &mut [usize],
    mirrored: bool,
) {
    if mirrored {
        vertices.reverse();
    }
    out.push('f');
    for &v in vertices.iter() {
        out.push(' ');
        numbers.int(out, v);
    }
    out.push('\n');
}

/// The OBJ `v` and `f` lines of a mesh without corner attributes, its
/// vertices numbered from `base`, made in pieces on all cores and written
/// in order (the lines `write_obj` makes one by one for a small mesh).
pub(super) fn write_mesh_obj_lines(
    m: &HalfEdgeMesh,
    world: glam::DMat4,
    mirrored: bool,
    base: usize,
    w: &mut dyn ExportOutput,
) -> std::io::Result<()> {
    let vertices: Vec<hedra_geom::VertexId> = m.vertices().collect();
    let mut index = vec![0usize; m.vertex_capacity()];
    for (i, v) in vertices.iter().enumerate() {
        index[v.index()] = base + i;
    }
    let vertex_pieces: Vec<&[hedra_geom::VertexId]> =
        vertices.chunks(refined::VERTICES_PER_PIECE).collect();
    let vertex_lines = |piece: usize, bytes: &mut Vec<u8>| {
        let (mut out, mut numbers) = (String::new(), Numbers::default());
        for &v in vertex_pieces[piece] {
            obj_vertex_line(
                &mut out,
                &mut numbers,
                world.transform_point3(m.position(v)),
            );
        }
        bytes.extend_from_slice(out.as_bytes());
    };
    write_pieces_in_order(vertex_pieces.len(), &vertex_lines, w)?;
    let faces: Vec<hedra_geom::FaceId> = m.faces().collect();
    let face_pieces: Vec<&[hedra_geom::FaceId]> = faces.chunks(refined::FACES_PER_PIECE).collect();
    let face_lines = |piece: usize, bytes: &mut Vec<u8>| {
        let (mut out, mut numbers, mut vs) = (String::new(), Numbers::default(), Vec::new());
        for &f in face_pieces[piece] {
            vs.clear();
            vs.extend(m.face_vertices(f).map(|v| index[v.index()]));
            obj_face_line(&mut out, &mut numbers, &mut vs, mirrored);
        }
        bytes.extend_from_slice(out.as_bytes());
    };
    write_pieces_in_order(face_pieces.len(), &face_lines, w)?;
    Ok(())
}

/// How much OBJ text is formatted before it is passed on to the output.
pub(super) const OBJ_SPILL: usize = 1 << 20;

/// Passes `out` on to `w` once it holds [`OBJ_SPILL`] bytes.
pub(super) fn spill(out: &mut String, w: &mut dyn ExportOutput) -> std::io::Result<()> {
    if out.len() >= OBJ_SPILL {
        w.write_all(out.as_bytes())?;
        out.clear();
    }
    Ok(())
}

/// Formats numbers for the OBJ writer without `fmt`'s machinery (zmij's
/// shortest round-trip floats, itoa's integers): most of an OBJ is numbers.
#[derive(Default)]
pub(super) struct Numbers {
    floats: zmij::Buffer,
    ints: itoa::Buffer,
}

impl Numbers {
    pub(super) fn float(&mut self, out: &mut String, x: f64) {
        out.push_str(self.floats.format(x));
    }
    pub(super) fn int(&mut self, out: &mut String, n: usize) {
        out.push_str(self.ints.format(n));
    }
}

/// An OBJ free-form B-spline record of `curve` mapped by `world`, its
/// control points numbered from `base`: `v` lines (with the weight when
/// rational), `cstype`, `deg`, `curv` over the domain, `parm u` with every
/// knot, `end`. Numbers are written exactly (shortest round-trip form).
/// Returns the number of `v` lines written.
pub(super) fn write_free_form(
    out: &mut String,
    curve: &hedra_geom::NurbsCurve,
    world: glam::DMat4,
    base: usize,
) -> usize {
    let rational = !curve.is_polynomial();
    for (p, w) in curve.points().iter().zip(curve.weights()) {
        let p = world.transform_point3(*p);
        if rational {
            let _ = writeln!(out, "v {} {} {} {w}", p.x, p.y, p.z);
        } else {
            let _ = writeln!(out, "v {} {} {}", p.x, p.y, p.z);
        }
    }
    let (a, b) = hedra_geom::curves::Curve::domain(curve);
    let _ = writeln!(
        out,
        "cstype {}bspline\ndeg {}",
        if rational { "rat " } else { "" },
        curve.degree()
    );
    let _ = write!(out, "curv {a} {b}");
    for i in 0..curve.points().len() {
        let _ = write!(out, " {}", base + i);
    }
    out.push_str("\nparm u");
    for k in curve.knots() {
        let _ = write!(out, " {k}");
    }
    out.push_str("\nend\n");
    curve.points().len()
}
