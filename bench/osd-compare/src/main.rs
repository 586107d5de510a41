//! OpenSubdiv 3.x CPU uniform refinement timings on the meshes Hedra
//! benchmarks (`plugins/geom/benches/subdivision.rs`): Catmull-Clark of the
//! cube (side 2) to level 7, a 100x100 torus (R = 2, r = 0.5) to levels 1-3
//! and a 200x200 torus to level 1; Loop of the icosahedron to level 6. It
//! also prints a STREAM-like copy bandwidth, the machine's memory floor.
//!
//! "full"        = TopologyRefiner from a TopologyDescriptor + refine_uniform(level)
//!                 with full topology in the last level (as Hedra builds every
//!                 level's connectivity) + PrimvarRefiner::interpolate of the
//!                 positions through every level.
//! "create"      = only TopologyRefinerFactory::Create (base level), no refinement.
//! "full sparse" = "full" with OpenSubdiv's default fullTopologyInLastLevel = false
//!                 (the last level gets face-vertices only, no edges).
//! "positions"   = only the PrimvarRefiner interpolation on an already refined
//!                 refiner (PrimvarRefiner creation included; it is a thin wrapper).
//!
//! Single thread. Positions are f32 xyz (the only primvar type the
//! opensubdiv-petite wrapper exposes).

use opensubdiv_petite::far::{
    self, PrimvarRefiner, TopologyDescriptor, TopologyRefiner, TopologyRefinerOptions,
    topology_refiner::UniformRefinementOptions,
};
use std::hint::black_box;

/// The allocator Hedra's benches use; with the `override` feature it also
/// serves OpenSubdiv's C++ `new`/`malloc`.
#[cfg(feature = "mimalloc")]
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

const ALLOCATOR: &str = if cfg!(feature = "mimalloc") {
    "mimalloc (overrides malloc for C++ too)"
} else {
    "glibc malloc"
};
use std::time::Instant;

struct Mesh {
    name: &'static str,
    scheme: far::Scheme,
    positions: Vec<f32>,
    verts_per_face: Vec<u32>,
    indices: Vec<u32>,
}

/// Cube of side 2 centred at the origin, faces outward and counter-clockwise.
fn cube() -> Mesh {
    let positions = vec![
        -1.0, -1.0, -1.0, // 0
        1.0, -1.0, -1.0, // 1
        1.0, 1.0, -1.0, // 2
        -1.0, 1.0, -1.0, // 3
        -1.0, -1.0, 1.0, // 4
        1.0, -1.0, 1.0, // 5
        1.0, 1.0, 1.0, // 6
        -1.0, 1.0, 1.0, // 7
    ];
    let indices = vec![
        0, 3, 2, 1, // -z
        4, 5, 6, 7, // +z
        0, 1, 5, 4, // -y
        2, 3, 7, 6, // +y
        0, 4, 7, 3, // -x
        1, 2, 6, 5, // +x
    ];
    Mesh {
        name: "cube",
        scheme: far::Scheme::CatmullClark,
        positions,
        verts_per_face: vec![4; 6],
        indices,
    }
}

/// Torus grid: `major` segments around the main axis (z), `minor` around the
/// tube. `major * minor` vertices and quads, outward CCW faces.
fn torus(name: &'static str, major: u32, minor: u32, big_r: f32, small_r: f32) -> Mesh {
    let mut positions = Vec::with_capacity((major * minor * 3) as usize);
    for i in 0..major {
        let u = i as f32 / major as f32 * std::f32::consts::TAU;
        for j in 0..minor {
            let v = j as f32 / minor as f32 * std::f32::consts::TAU;
            let rr = big_r + small_r * v.cos();
            positions.extend_from_slice(&[rr * u.cos(), rr * u.sin(), small_r * v.sin()]);
        }
    }
    let idx = |i: u32, j: u32| (i % major) * minor + (j % minor);
    let mut indices = Vec::with_capacity((major * minor * 4) as usize);
    for i in 0..major {
        for j in 0..minor {
            indices.extend_from_slice(&[idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    Mesh {
        name,
        scheme: far::Scheme::CatmullClark,
        positions,
        verts_per_face: vec![4; (major * minor) as usize],
        indices,
    }
}

/// The icosahedron (radius 1; 12 vertices, 20 triangles, outward CCW), for Loop.
fn icosahedron() -> Mesh {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let s = 1.0 / (1.0 + t * t).sqrt();
    let (a, b) = (s, t * s);
    let positions = vec![
        -a, b, 0.0, a, b, 0.0, -a, -b, 0.0, a, -b, 0.0, //
        0.0, -a, b, 0.0, a, b, 0.0, -a, -b, 0.0, a, -b, //
        b, 0.0, -a, b, 0.0, a, -b, 0.0, -a, -b, 0.0, a,
    ];
    let indices = vec![
        0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, //
        1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, //
        3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, //
        4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1,
    ];
    Mesh {
        name: "icosahedron (Loop)",
        scheme: far::Scheme::Loop,
        positions,
        verts_per_face: vec![3; 20],
        indices,
    }
}

/// A STREAM-like copy of `mb` megabytes of f64 (read + write); returns the
/// best bandwidth in GB/s counting bytes read plus bytes written.
fn stream_copy(mb: usize, runs: usize) -> f64 {
    let n = mb * (1 << 20) / 8;
    let src: Vec<f64> = (0..n).map(|i| i as f64).collect();
    let mut dst = vec![0.0f64; n];
    let (_, min) = time(runs, || {
        dst.copy_from_slice(black_box(&src));
        black_box(&mut dst);
    });
    (2 * n * 8) as f64 / (min * 1e-3) / 1e9
}

fn refiner(mesh: &Mesh, level: usize, full_topology_in_last_level: bool) -> TopologyRefiner {
    let desc = TopologyDescriptor::new(mesh.positions.len() / 3, &mesh.verts_per_face, &mesh.indices)
        .expect("descriptor");
    let mut r = TopologyRefiner::new(
        desc,
        TopologyRefinerOptions {
            scheme: mesh.scheme,
            boundary_interpolation: Some(far::BoundaryInterpolation::EdgeOnly),
            ..Default::default()
        },
    )
    .expect("refiner");
    if level > 0 {
        r.refine_uniform(UniformRefinementOptions {
            refinement_level: level,
            order_vertices_from_faces_first: true,
            full_topology_in_last_level,
        });
    }
    r
}

/// Interpolate positions level by level; returns the last level's positions.
fn interpolate(r: &TopologyRefiner, cage: &[f32], level: usize) -> Vec<f32> {
    let pr = PrimvarRefiner::new(r).expect("primvar refiner");
    let mut cur = pr.interpolate(1, 3, cage).expect("level 1");
    for l in 2..=level {
        cur = pr.interpolate(l, 3, &cur).expect("level");
    }
    cur
}

fn stats(mut t: Vec<f64>) -> (f64, f64) {
    t.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let n = t.len();
    let median = if n % 2 == 1 { t[n / 2] } else { 0.5 * (t[n / 2 - 1] + t[n / 2]) };
    (median, t[0])
}

fn time<F: FnMut()>(runs: usize, mut f: F) -> (f64, f64) {
    for _ in 0..runs.div_ceil(10).max(2) {
        f(); // warm-up
    }
    let mut t = Vec::with_capacity(runs);
    for _ in 0..runs {
        let s = Instant::now();
        f();
        t.push(s.elapsed().as_secs_f64() * 1e3);
    }
    stats(t)
}

fn main() {
    let scale: f64 = std::env::var("OSD_RUNS_SCALE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1.0);
    let cube = cube();
    let torus_10k = torus("torus_10k", 100, 100, 2.0, 0.5);
    let torus_40k = torus("torus_40k (200×200)", 200, 200, 2.0, 0.5);
    let ico = icosahedron();
    // (mesh, level, runs)
    let cases: [(&Mesh, usize, usize); 6] = [
        (&cube, 7, 50),
        (&torus_10k, 1, 200),
        (&torus_10k, 2, 100),
        (&torus_10k, 3, 50),
        (&torus_40k, 1, 100),
        (&ico, 6, 100),
    ];
    let runs = ((20.0 * scale).round() as usize).max(3);
    println!(
        "STREAM-like copy of 64 MB f64 (read + write), best of {runs}: {:.1} GB/s",
        stream_copy(64, runs)
    );

    println!(
        "OpenSubdiv 3.7.0 (opensubdiv-petite 0.3.1), f32 positions, single thread, allocator: {ALLOCATOR}"
    );
    println!(
        "| case | faces (last level) | verts (last level) | runs | full | create refiner only | full, sparse last level | positions only |"
    );
    println!("| | | | | median / min ms | median / min ms | median / min ms | median / min ms |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    for (mesh, level, runs) in cases {
        let runs = ((runs as f64 * scale).round() as usize).max(3);

        // Sanity: face count at the last level.
        let r = refiner(mesh, level, true);
        let lvl = r.level(level).expect("last level");
        let faces = lvl.face_count();
        let verts = lvl.vertex_count();
        let expected = mesh.verts_per_face.len() * 4usize.pow(level as u32);
        assert_eq!(faces, expected, "{} level {level}: face count", mesh.name);
        let sides = mesh.verts_per_face[0] as usize;
        assert!(lvl.face_vertices_iter().all(|f| f.len() == sides));
        let out = interpolate(&r, &mesh.positions, level);
        assert_eq!(out.len(), verts * 3);
        assert!(out.iter().all(|x| x.is_finite()));

        let full = time(runs, || {
            let r = refiner(black_box(mesh), level, true);
            black_box(interpolate(&r, &mesh.positions, level));
        });
        let create = time(runs, || {
            black_box(refiner(black_box(mesh), 0, true));
        });
        let full_sparse = time(runs, || {
            let r = refiner(black_box(mesh), level, false);
            black_box(interpolate(&r, &mesh.positions, level));
        });
        let pos = time(runs, || {
            black_box(interpolate(&r, black_box(&mesh.positions), level));
        });
        let f = |(m, n): (f64, f64)| format!("{m:.3} / {n:.3}");
        println!(
            "| {} level {level} | {faces} | {verts} | {runs} | {} | {} | {} | {} |",
            mesh.name,
            f(full),
            f(create),
            f(full_sparse),
            f(pos)
        );
    }
}
