//! Refines every shape in `plugins/geom/tests/osd_shapes/*.obj` (OpenSubdiv's
//! regression shapes, as OBJ text with their `t` tags) with OpenSubdiv 3.7
//! itself, using the settings OpenSubdiv's own regression code reads from the
//! tags (`regression/common/far_utils.h`: `interpolateboundary`,
//! `creasemethod`, `smoothtriangles`, `crease`, `corner`, `hole`), and writes
//! the results to `plugins/geom/tests/osd_shapes/results.bin` for the test
//! `plugins/geom/tests/osd_shapes.rs`.
//!
//! Format (little-endian): magic `HEDRAOSD1`, u32 record count, then per
//! record: u8 name length, name, u8 level, u32 vertex count, u32 face count,
//! face-count bits (hidden faces, LSB first, padded to bytes), vertex-count ×
//! 3 f32 positions. Levels 1–3 are stored while the level has at most
//! `MAX_VERTICES` vertices (level 1 always).

use opensubdiv_petite::far::{
    BoundaryInterpolation, CreasingMethod, PrimvarRefiner, Scheme, TopologyDescriptor,
    TopologyRefiner, TopologyRefinerOptions, TriangleSubdivision,
    topology_refiner::UniformRefinementOptions,
};
use std::io::Write;
use std::path::Path;

/// Levels above 1 are stored only while they have at most this many vertices.
const MAX_VERTICES: usize = 6_000;

#[derive(Default)]
struct Shape {
    positions: Vec<f32>,
    face_sizes: Vec<u32>,
    indices: Vec<u32>,
    creases: Vec<u32>,
    crease_sharpness: Vec<f32>,
    corners: Vec<u32>,
    corner_sharpness: Vec<f32>,
    holes: Vec<u32>,
    boundary: Option<BoundaryInterpolation>,
    chaikin: bool,
    smooth_triangles: bool,
}

/// `t name ni/nf/ns ints… floats… strings…`
fn parse_tag(line: &str) -> (String, Vec<i64>, Vec<f32>, Vec<String>) {
    let mut it = line.split_whitespace().skip(1);
    let name = it.next().unwrap_or_default().to_string();
    let counts: Vec<usize> = it
        .next()
        .unwrap_or("0/0/0")
        .split('/')
        .map(|c| c.parse().unwrap())
        .collect();
    let ints = (0..counts[0])
        .map(|_| it.next().unwrap().parse().unwrap())
        .collect();
    let floats = (0..counts[1])
        .map(|_| it.next().unwrap().parse().unwrap())
        .collect();
    let strings = (0..counts[2])
        .map(|_| it.next().unwrap().to_string())
        .collect();
    (name, ints, floats, strings)
}

fn parse(text: &str) -> Shape {
    let mut s = Shape {
        boundary: Some(BoundaryInterpolation::EdgeOnly),
        ..Shape::default()
    };
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => s
                .positions
                .extend(words.take(3).map(|w| w.parse::<f32>().unwrap())),
            Some("f") => {
                let before = s.indices.len();
                s.indices
                    .extend(words.map(|w| w.parse::<u32>().unwrap() - 1));
                s.face_sizes.push((s.indices.len() - before) as u32);
            }
            Some("t") => {
                let (name, ints, floats, strings) = parse_tag(line);
                let sharp = |j: usize| floats[if floats.len() > 1 { j } else { 0 }].max(0.0);
                match name.as_str() {
                    "interpolateboundary" => {
                        s.boundary = match ints[0] {
                            0 => None,
                            1 => Some(BoundaryInterpolation::EdgeAndCorner),
                            _ => Some(BoundaryInterpolation::EdgeOnly),
                        }
                    }
                    "creasemethod" => s.chaikin = strings[0] == "chaikin",
                    "smoothtriangles" => s.smooth_triangles = strings[0] == "smooth",
                    // OpenSubdiv's regression reads vertex pairs (j, j + 1), j += 2.
                    "crease" => {
                        let mut j = 0;
                        while j + 1 < ints.len() {
                            s.creases.extend([ints[j] as u32, ints[j + 1] as u32]);
                            s.crease_sharpness.push(sharp(j));
                            j += 2;
                        }
                    }
                    "corner" => {
                        for (j, &v) in ints.iter().enumerate() {
                            s.corners.push(v as u32);
                            s.corner_sharpness.push(sharp(j));
                        }
                    }
                    "hole" => s.holes.extend(ints.iter().map(|&f| f as u32)),
                    _ => {}
                }
            }
            _ => {}
        }
    }
    s
}

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../plugins/geom/tests/osd_shapes");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| {
            let name = e.unwrap().file_name().into_string().unwrap();
            name.strip_suffix(".obj").map(str::to_string)
        })
        .collect();
    names.sort();
    let mut out = Vec::new();
    let mut records = 0u32;
    for name in &names {
        let shape = parse(&std::fs::read_to_string(dir.join(format!("{name}.obj"))).unwrap());
        let scheme = if name.starts_with("loop") {
            Scheme::Loop
        } else {
            Scheme::CatmullClark
        };
        let mut desc =
            TopologyDescriptor::new(shape.positions.len() / 3, &shape.face_sizes, &shape.indices)
                .unwrap();
        if !shape.creases.is_empty() {
            desc.creases(&shape.creases, &shape.crease_sharpness);
        }
        if !shape.corners.is_empty() {
            desc.corners(&shape.corners, &shape.corner_sharpness);
        }
        if !shape.holes.is_empty() {
            desc.holes(&shape.holes);
        }
        desc.left_handed(name == "catmark_lefthanded");
        let options = TopologyRefinerOptions {
            scheme,
            boundary_interpolation: shape.boundary,
            creasing_method: if shape.chaikin {
                CreasingMethod::Chaikin
            } else {
                CreasingMethod::Uniform
            },
            triangle_subdivision: if shape.smooth_triangles {
                TriangleSubdivision::Smooth
            } else {
                TriangleSubdivision::CatmullClark
            },
            ..TopologyRefinerOptions::default()
        };
        let Ok(mut refiner) = TopologyRefiner::new(desc, options) else {
            eprintln!("{name}: OpenSubdiv refused the cage");
            continue;
        };
        refiner.refine_uniform(UniformRefinementOptions {
            refinement_level: 3,
            order_vertices_from_faces_first: true,
            full_topology_in_last_level: true,
        });
        let primvars = PrimvarRefiner::new(&refiner).unwrap();
        let mut points = shape.positions.clone();
        for level in 1..=3usize {
            points = primvars.interpolate(level, 3, &points).unwrap();
            let topo = refiner.level(level).unwrap();
            let (nv, nf) = (topo.vertex_count(), topo.face_count());
            if level > 1 && nv > MAX_VERTICES {
                break;
            }
            // SAFETY: TopologyLevel is a pointer and a zero-sized marker.
            let ptr: opensubdiv_petite_sys::far::TopologyLevelPtr =
                unsafe { std::mem::transmute(topo) };
            let mut bits = vec![0u8; nf.div_ceil(8)];
            let mut hidden = 0;
            for f in 0..nf {
                if unsafe { opensubdiv_petite_sys::far::TopologyLevel_IsFaceHole(ptr, f as u32) } {
                    bits[f / 8] |= 1 << (f % 8);
                    hidden += 1;
                }
            }
            out.push(name.len() as u8);
            out.extend_from_slice(name.as_bytes());
            out.push(level as u8);
            out.extend_from_slice(&(nv as u32).to_le_bytes());
            out.extend_from_slice(&(nf as u32).to_le_bytes());
            out.extend_from_slice(&bits);
            for p in &points[..3 * nv] {
                out.extend_from_slice(&p.to_le_bytes());
            }
            records += 1;
            println!("{name} level {level}: {nv} vertices, {nf} faces, {hidden} hidden");
        }
    }
    let mut file = std::fs::File::create(dir.join("results.bin")).unwrap();
    file.write_all(b"HEDRAOSD1").unwrap();
    file.write_all(&records.to_le_bytes()).unwrap();
    file.write_all(&out).unwrap();
    println!("{records} records, {} bytes", out.len() + 13);
}
