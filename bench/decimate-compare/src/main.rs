//! Hedra's progressive-mesh decimation against meshoptimizer's simplifier
//! (issue 18): on the same triangle meshes, for 50 %, 10 % and 1 % of the
//! faces, the sampled symmetric Hausdorff distance to the input (relative
//! to the input's bounding-box diagonal) and the time. See README.md.

use hedra_geom::progressive::{DecimateOptions, DecimateTarget, ProgressiveMesh};
use hedra_geom::subdivision::{Creases, Options, Refiner, Scheme};
use hedra_geom::{DVec3, EdgeId, HalfEdgeMesh, Primitive};
use std::collections::BTreeSet;
use std::time::Instant;

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// One test input: triangles over positions; `uv_seam` marks vertex pairs
/// (by position index) whose edge is a UV seam: meshoptimizer gets those
/// vertices twice (a seam in its vertex buffer), Hedra as seam edges.
struct Input {
    name: &'static str,
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    /// For each triangle corner, the vertex index in meshoptimizer's
    /// buffer (differs from the position index only on seams).
    corner_vertex: Option<Vec<[u32; 3]>>,
    seam_pairs: Vec<(u32, u32)>,
    options: DecimateOptions,
}

fn quads_to_triangles(quads: &[[u32; 4]]) -> Vec<[u32; 3]> {
    quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect()
}

/// Deterministic noise in [−1, 1].
fn noise(i: u64) -> f64 {
    let mut x = i.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03;
    x ^= x >> 31;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x ^= x >> 29;
    (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

fn subdivided_surface() -> Input {
    let cage = Primitive::Torus {
        major_segments: 32,
        minor_segments: 16,
        major_radius: 1.0,
        minor_radius: 0.35,
    }
    .build()
    .unwrap();
    let options = Options {
        scheme: Scheme::CatmullClark,
        ..Options::default()
    };
    let (smooth, _) = Refiner::subdivide(&cage, &Creases::default(), options, 5).unwrap();
    let (positions, polys) = dense(&smooth);
    let quads: Vec<[u32; 4]> = polys
        .iter()
        .map(|p| [p[0], p[1], p[2], p[3]])
        .collect();
    Input {
        name: "subdivided torus (Catmull-Clark ×5)",
        positions,
        triangles: quads_to_triangles(&quads),
        corner_vertex: None,
        seam_pairs: Vec::new(),
        options: DecimateOptions::default(),
    }
}

fn dense(m: &HalfEdgeMesh) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let mut index = vec![u32::MAX; m.vertex_capacity()];
    let mut positions = Vec::new();
    for v in m.vertices() {
        index[v.index()] = positions.len() as u32;
        positions.push(m.position(v));
    }
    let polys = m
        .faces()
        .map(|f| m.face_vertices(f).map(|v| index[v.index()]).collect())
        .collect();
    (positions, polys)
}

fn noisy_sphere() -> Input {
    let m = Primitive::IcoSphere {
        subdivisions: 6,
        radius: 1.0,
    }
    .build()
    .unwrap();
    let (mut positions, polys) = dense(&m);
    for (i, p) in positions.iter_mut().enumerate() {
        *p *= 1.0 + 0.01 * noise(i as u64);
    }
    Input {
        name: "noisy sphere (icosphere 6, ±1 % radius)",
        positions,
        triangles: polys.iter().map(|p| [p[0], p[1], p[2]]).collect(),
        corner_vertex: None,
        seam_pairs: Vec::new(),
        options: DecimateOptions::default(),
    }
}

/// A gear: 24 teeth, a bore, flat faces; quads triangulated. Sharp edges
/// where the faces meet the walls and at the teeth.
fn gear() -> Input {
    let teeth = 24;
    let per_tooth = 16; // samples along one tooth's outline
    let n = teeth * per_tooth;
    let (heights, radial) = (24, 16);
    let outline = |k: usize| -> (f64, f64) {
        let t = (k % per_tooth) as f64 / per_tooth as f64;
        // Trapezoid teeth: root, flank up, tip, flank down.
        let r = match t {
            t if t < 0.25 => 1.0,
            t if t < 0.375 => 1.0 + 0.2 * (t - 0.25) / 0.125,
            t if t < 0.625 => 1.2,
            t if t < 0.75 => 1.2 - 0.2 * (t - 0.625) / 0.125,
            _ => 1.0,
        };
        let a = k as f64 / n as f64 * std::f64::consts::TAU;
        (r * a.cos(), r * a.sin())
    };
    let bore = 0.4;
    let thick = 0.4;
    let mut positions = Vec::new();
    // Grid of (ring, k): outer wall rings 0..=heights (bottom to top),
    // then the top face inwards, the bore downwards, the bottom outwards.
    let mut rings: Vec<Vec<u32>> = Vec::new();
    let mut ring = |pts: Vec<DVec3>, positions: &mut Vec<DVec3>| {
        let ids = (0..pts.len() as u32)
            .map(|i| positions.len() as u32 + i)
            .collect::<Vec<_>>();
        positions.extend(pts);
        rings.push(ids);
    };
    let at = |k: usize, s: f64, z: f64| -> DVec3 {
        // s = 1: outline, s = 0: bore circle.
        let (x, y) = outline(k);
        let a = k as f64 / n as f64 * std::f64::consts::TAU;
        let (bx, by) = (bore * a.cos(), bore * a.sin());
        DVec3::new(bx + (x - bx) * s, by + (y - by) * s, z)
    };
    for h in 0..=heights {
        let z = thick * h as f64 / heights as f64;
        ring((0..n).map(|k| at(k, 1.0, z)).collect(), &mut positions);
    }
    for r in 1..=radial {
        let s = 1.0 - r as f64 / radial as f64;
        ring((0..n).map(|k| at(k, s, thick)).collect(), &mut positions);
    }
    for h in 1..=heights {
        let z = thick * (1.0 - h as f64 / heights as f64);
        ring((0..n).map(|k| at(k, 0.0, z)).collect(), &mut positions);
    }
    for r in 1..radial {
        let s = r as f64 / radial as f64;
        ring((0..n).map(|k| at(k, s, 0.0)).collect(), &mut positions);
    }
    let mut quads = Vec::new();
    let count = rings.len();
    for i in 0..count {
        let (a, b) = (&rings[i], &rings[(i + 1) % count]);
        for k in 0..n {
            let k1 = (k + 1) % n;
            quads.push([a[k], a[k1], b[k1], b[k]]);
        }
    }
    Input {
        name: "gear (24 teeth, bore, sharp edges)",
        positions,
        triangles: quads_to_triangles(&quads),
        corner_vertex: None,
        seam_pairs: Vec::new(),
        options: DecimateOptions {
            sharp_angle: Some(30.0),
            ..DecimateOptions::default()
        },
    }
}

/// An open wavy tube (two borders) with UVs around it: the UV seam runs
/// along one line, where meshoptimizer gets each vertex twice.
fn tube_with_uvs() -> Input {
    let (around, along) = (256usize, 128usize);
    let mut positions = Vec::new();
    for j in 0..=along {
        for i in 0..around {
            let a = i as f64 / around as f64 * std::f64::consts::TAU;
            let z = j as f64 / along as f64 * 4.0;
            let r = 1.0 + 0.15 * (3.0 * a).sin() * (2.0 * z).cos();
            positions.push(DVec3::new(r * a.cos(), r * a.sin(), z));
        }
    }
    let id = |i: usize, j: usize| (j * around + i % around) as u32;
    let mut quads = Vec::new();
    let mut corners = Vec::new();
    // meshoptimizer's buffer: the positions, then a second copy of column
    // 0 (u = 1) for the quads that close the tube.
    let seam_copy = |j: usize| ((along + 1) * around + j) as u32;
    for j in 0..along {
        for i in 0..around {
            let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            quads.push(q);
            let mut c = q;
            if i + 1 == around {
                c[1] = seam_copy(j);
                c[2] = seam_copy(j + 1);
            }
            corners.push(c);
        }
    }
    let seam_pairs = (0..along).map(|j| (id(0, j), id(0, j + 1))).collect();
    Input {
        name: "open tube with a UV seam (two borders)",
        positions,
        triangles: quads_to_triangles(&quads),
        corner_vertex: Some(
            corners
                .iter()
                .flat_map(|c| [[c[0], c[1], c[2]], [c[0], c[2], c[3]]])
                .collect(),
        ),
        seam_pairs,
        options: DecimateOptions::default(),
    }
}

/// The Stanford bunny's low-resolution version from the `bunny` npm
/// package (`exports.positions=[…];exports.cells=[…]`).
fn bunny(path: &str) -> Option<Input> {
    let text = std::fs::read_to_string(path).ok()?;
    let array = |name: &str| -> serde_json::Value {
        let start = text.find(&format!("exports.{name}=")).unwrap() + name.len() + 9;
        let rest = &text[start..];
        let end = rest.find("exports.").unwrap_or(rest.len());
        serde_json::from_str(rest[..end].trim().trim_end_matches(';')).unwrap()
    };
    let positions: Vec<DVec3> = array("positions")
        .as_array()?
        .iter()
        .map(|p| {
            let c: Vec<f64> = p.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
            DVec3::new(c[0], c[1], c[2])
        })
        .collect();
    let triangles: Vec<[u32; 3]> = array("cells")
        .as_array()?
        .iter()
        .map(|c| {
            let c: Vec<u32> = c.as_array().unwrap().iter().map(|x| x.as_u64().unwrap() as u32).collect();
            [c[0], c[1], c[2]]
        })
        .collect();
    Some(Input {
        name: "Stanford bunny (npm `bunny`, low resolution)",
        positions,
        triangles,
        corner_vertex: None,
        seam_pairs: Vec::new(),
        options: DecimateOptions::default(),
    })
}

// ----- distances ---------------------------------------------------------------

/// A bounding-volume hierarchy over triangles for closest-point queries.
struct Bvh {
    tris: Vec<[DVec3; 3]>,
    nodes: Vec<Node>,
    order: Vec<u32>,
}

struct Node {
    min: DVec3,
    max: DVec3,
    /// Leaf: first index into `order` and count; inner: left child (right is +1... stored explicitly).
    start: u32,
    count: u32,
    right: u32,
}

impl Bvh {
    fn new(tris: Vec<[DVec3; 3]>) -> Bvh {
        let mut order: Vec<u32> = (0..tris.len() as u32).collect();
        let centres: Vec<DVec3> = tris.iter().map(|t| (t[0] + t[1] + t[2]) / 3.0).collect();
        let mut nodes = Vec::new();
        build(&tris, &centres, &mut order, 0, tris.len(), &mut nodes);
        Bvh { tris, nodes, order }
    }

    fn distance(&self, p: DVec3) -> f64 {
        let mut best = f64::INFINITY;
        let mut stack = vec![0u32];
        while let Some(i) = stack.pop() {
            let n = &self.nodes[i as usize];
            let d = box_distance2(p, n.min, n.max);
            if d >= best {
                continue;
            }
            if n.count > 0 {
                for &t in &self.order[n.start as usize..(n.start + n.count) as usize] {
                    let t = &self.tris[t as usize];
                    let q = closest_on_triangle(p, t[0], t[1], t[2]);
                    best = best.min(p.distance_squared(q));
                }
            } else {
                let (l, r) = (i + 1, n.right);
                let dl = box_distance2(p, self.nodes[l as usize].min, self.nodes[l as usize].max);
                let dr = box_distance2(p, self.nodes[r as usize].min, self.nodes[r as usize].max);
                if dl < dr {
                    stack.push(r);
                    stack.push(l);
                } else {
                    stack.push(l);
                    stack.push(r);
                }
            }
        }
        best.sqrt()
    }
}

fn build(
    tris: &[[DVec3; 3]],
    centres: &[DVec3],
    order: &mut [u32],
    start: usize,
    end: usize,
    nodes: &mut Vec<Node>,
) -> u32 {
    let mut min = DVec3::splat(f64::INFINITY);
    let mut max = DVec3::splat(f64::NEG_INFINITY);
    for &t in &order[start..end] {
        for p in tris[t as usize] {
            min = min.min(p);
            max = max.max(p);
        }
    }
    let me = nodes.len() as u32;
    nodes.push(Node {
        min,
        max,
        start: start as u32,
        count: (end - start) as u32,
        right: 0,
    });
    if end - start <= 4 {
        return me;
    }
    let ext = max - min;
    let axis = if ext.x >= ext.y && ext.x >= ext.z {
        0
    } else if ext.y >= ext.z {
        1
    } else {
        2
    };
    let mid = (start + end) / 2;
    order[start..end].select_nth_unstable_by(mid - start, |&a, &b| {
        centres[a as usize][axis].total_cmp(&centres[b as usize][axis])
    });
    nodes[me as usize].count = 0;
    build(tris, centres, order, start, mid, nodes);
    let right = build(tris, centres, order, mid, end, nodes);
    nodes[me as usize].right = right;
    me
}

fn box_distance2(p: DVec3, min: DVec3, max: DVec3) -> f64 {
    let d = (min - p).max(p - max).max(DVec3::ZERO);
    d.length_squared()
}

/// Ericson, Real-Time Collision Detection, 5.1.5.
fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// `count` points spread over the triangles by area (stratified by a
/// deterministic sequence), plus every corner.
fn samples(tris: &[[DVec3; 3]], count: usize) -> Vec<DVec3> {
    let areas: Vec<f64> = tris
        .iter()
        .map(|t| (t[1] - t[0]).cross(t[2] - t[0]).length() * 0.5)
        .collect();
    let total: f64 = areas.iter().sum();
    let mut out: Vec<DVec3> = tris.iter().flat_map(|t| *t).collect();
    let mut acc = 0.0;
    let mut next = 0usize;
    for (i, t) in tris.iter().enumerate() {
        acc += areas[i];
        while next < count && (next as f64 + 0.5) / count as f64 * total <= acc {
            let (mut u, mut v) = (
                (noise(2 * next as u64) + 1.0) / 2.0,
                (noise(2 * next as u64 + 1) + 1.0) / 2.0,
            );
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            out.push(t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * v);
            next += 1;
        }
    }
    out
}

/// Symmetric Hausdorff distance, sampled both ways.
fn hausdorff(a: &[[DVec3; 3]], a_bvh: &Bvh, b: &[[DVec3; 3]], n: usize) -> f64 {
    let b_bvh = Bvh::new(b.to_vec());
    let worst = |pts: Vec<DVec3>, bvh: &Bvh| {
        pts.into_iter()
            .map(|p| (bvh.distance(p), p))
            .fold((0.0, DVec3::ZERO), |x, y| if y.0 > x.0 { y } else { x })
    };
    let (ab, pa) = worst(samples(a, n), &b_bvh);
    let (ba, pb) = worst(samples(b, n), a_bvh);
    if std::env::var("DC_WHERE").is_ok() {
        eprintln!("  worst input->result {ab:.5} at {pa:.3}; result->input {ba:.5} at {pb:.3}");
    }
    ab.max(ba)
}

// ----- the runs ------------------------------------------------------------------

fn thread_cpu_seconds() -> f64 {
    // /proc/thread-self/schedstat: nanoseconds on the CPU first.
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns * 1e-9)
}

fn main() {
    let bunny_path = std::env::var("BUNNY_JS").unwrap_or_else(|_| "/tmp/bunny/package/index.js".into());
    let only = std::env::args().nth(1);
    let mut inputs: Vec<Box<dyn Fn() -> Option<Input>>> = vec![
        Box::new(|| Some(subdivided_surface())),
        Box::new(|| Some(noisy_sphere())),
        Box::new(|| Some(gear())),
        Box::new(|| Some(tube_with_uvs())),
    ];
    let bp = bunny_path.clone();
    inputs.push(Box::new(move || bunny(&bp)));
    let sample_count = 200_000;
    println!("| input | triangles | target | Hedra faces | meshopt faces | Hedra error | meshopt error | Hedra time | meshopt time |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (k, make) in inputs.iter().enumerate() {
        if only.as_ref().is_some_and(|o| o.parse::<usize>().ok() != Some(k)) {
            continue;
        }
        let Some(input) = make() else {
            eprintln!("skipped the bunny: {bunny_path} not found (see README)");
            continue;
        };
        let tris_in: Vec<[DVec3; 3]> = input
            .triangles
            .iter()
            .map(|t| t.map(|i| input.positions[i as usize]))
            .collect();
        let (lo, hi) = tris_in.iter().flatten().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let diagonal = (hi - lo).length();
        let input_bvh = Bvh::new(tris_in.clone());

        // Hedra: the whole progressive mesh once, then a seek per target.
        let polys: Vec<Vec<u32>> = input.triangles.iter().map(|t| t.to_vec()).collect();
        let mesh = match HalfEdgeMesh::from_polygons(&input.positions, &polys) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("{}: Hedra cannot build the mesh: {e}", input.name);
                continue;
            }
        };
        let mut options = input.options.clone();
        if !input.seam_pairs.is_empty() {
            let seams: BTreeSet<EdgeId> = input
                .seam_pairs
                .iter()
                .filter_map(|&(a, b)| {
                    mesh.find_edge(hedra_geom::VertexId(a), hedra_geom::VertexId(b))
                })
                .collect();
            options.seams = seams;
        }
        let (c0, t0) = (thread_cpu_seconds(), Instant::now());
        let built = ProgressiveMesh::build(&mesh, &Creases::default(), &options);
        let (build_wall, build_cpu) = (t0.elapsed().as_secs_f64(), thread_cpu_seconds() - c0);
        let mut pm = match built {
            Ok(pm) => pm,
            Err(e) => {
                eprintln!("{}: Hedra refuses: {e}", input.name);
                continue;
            }
        };
        eprintln!(
            "{}: Hedra build {build_wall:.3} s wall, {build_cpu:.3} s CPU, {} levels, base {} faces",
            input.name,
            pm.level_count(),
            pm.face_counts()[0]
        );

        // meshoptimizer's vertex buffer (f32; seams duplicated).
        let mut vb: Vec<[f32; 3]> = input.positions.iter().map(|p| p.as_vec3().to_array()).collect();
        let indices: Vec<u32> = match &input.corner_vertex {
            Some(cv) => {
                let extra = cv.iter().flatten().map(|&i| i as usize + 1).max().unwrap_or(0);
                // Seam copies repeat column 0 of each ring.
                let around = 256;
                while vb.len() < extra {
                    let j = vb.len() - input.positions.len();
                    vb.push(input.positions[j * around].as_vec3().to_array());
                }
                cv.iter().flatten().copied().collect()
            }
            None => input.triangles.iter().flatten().copied().collect(),
        };
        let bytes: Vec<u8> = vb.iter().flatten().flat_map(|x| x.to_le_bytes()).collect();
        let adapter = meshopt::VertexDataAdapter::new(&bytes, 12, 0).unwrap();

        for ratio in [0.5, 0.1, 0.01] {
            let target = (input.triangles.len() as f64 * ratio).round() as usize;
            let t1 = Instant::now();
            let level = pm.nearest_level(DecimateTarget::Faces(target));
            pm.seek(level).unwrap();
            let level_mesh = pm.level_mesh();
            let seek_wall = t1.elapsed().as_secs_f64();
            level_mesh.validate().unwrap();
            let hedra_tris: Vec<[DVec3; 3]> = level_mesh
                .faces()
                .map(|f| {
                    let v: Vec<DVec3> = level_mesh.face_vertices(f).map(|v| level_mesh.position(v)).collect();
                    [v[0], v[1], v[2]]
                })
                .collect();
            let hedra_err = hausdorff(&tris_in, &input_bvh, &hedra_tris, sample_count) / diagonal;

            let mut best = f64::INFINITY;
            let mut result = Vec::new();
            let runs = if input.triangles.len() > 500_000 { 1 } else { 3 };
            for _ in 0..runs {
                let t2 = Instant::now();
                result = meshopt::simplify(
                    &indices,
                    &adapter,
                    target * 3,
                    1.0,
                    meshopt::SimplifyOptions::None,
                    None,
                );
                best = best.min(t2.elapsed().as_secs_f64());
            }
            let mo_tris: Vec<[DVec3; 3]> = result
                .chunks(3)
                .map(|t| [0, 1, 2].map(|i| {
                    let p = vb[t[i] as usize];
                    DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)
                }))
                .collect();
            if std::env::var("DC_WHERE").is_ok() {
                let hb = level_mesh.edges().filter(|&e| level_mesh.is_boundary_edge(e)).count();
                let mut count = std::collections::HashMap::new();
                for t in result.chunks(3) {
                    for i in 0..3 {
                        let key = |v: u32| { let p = vb[v as usize]; (p[0].to_bits(), p[1].to_bits(), p[2].to_bits()) };
                        let (a, b) = (key(t[i]), key(t[(i + 1) % 3]));
                        let k = if a < b { (a, b) } else { (b, a) };
                        *count.entry(k).or_insert(0) += 1;
                    }
                }
                let mb = count.values().filter(|&&c| c == 1).count();
                eprintln!("  border edges: Hedra {hb}, meshopt {mb}");
            }
            let mo_err = hausdorff(&tris_in, &input_bvh, &mo_tris, sample_count) / diagonal;
            println!(
                "| {} | {} | {}% | {} | {} | {:.5} | {:.5} | {:.0} ms + {:.1} ms | {:.1} ms |",
                input.name,
                input.triangles.len(),
                ratio * 100.0,
                level_mesh.face_count(),
                mo_tris.len(),
                hedra_err,
                mo_err,
                build_cpu * 1e3,
                seek_wall * 1e3,
                best * 1e3
            );
        }
    }
}
