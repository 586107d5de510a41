//! OpenSubdiv 3.x CPU uniform Catmull-Clark refinement timings on the meshes
//! Hedra benchmarks (`plugins/geom/benches/subdivision.rs`):
//! the cube (side 2) to level 7 and a 100x100 torus (R = 2, r = 0.5) to
//! levels 1-3.
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
        positions,
        verts_per_face: vec![4; 6],
        indices,
    }
}

/// Torus grid: `major` segments around the main axis (z), `minor` around the
/// tube. `major * minor` vertices and quads, outward CCW faces.
fn torus(major: u32, minor: u32, big_r: f32, small_r: f32) -> Mesh {
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
        name: "torus_10k",
        positions,
        verts_per_face: vec![4; (major * minor) as usize],
        indices,
    }
}

fn refiner(mesh: &Mesh, level: usize, full_topology_in_last_level: bool) -> TopologyRefiner {
    let desc = TopologyDescriptor::new(mesh.positions.len() / 3, &mesh.verts_per_face, &mesh.indices)
        .expect("descriptor");
    let mut r = TopologyRefiner::new(
        desc,
        TopologyRefinerOptions {
            scheme: far::Scheme::CatmullClark,
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
    let torus = torus(100, 100, 2.0, 0.5);
    // (mesh, level, runs, Hedra single-thread "full" ms for reference)
    let cases: [(&Mesh, usize, usize, f64); 4] = [
        (&cube, 7, 50, 3.98),
        (&torus, 1, 200, 1.36),
        (&torus, 2, 100, 6.2),
        (&torus, 3, 50, 32.9),
    ];

    println!(
        "OpenSubdiv 3.7.0 (opensubdiv-petite 0.3.1), f32 positions, single thread, allocator: {ALLOCATOR}"
    );
    println!(
        "| case | faces (last level) | verts (last level) | runs | full | create refiner only | full, sparse last level | positions only | Hedra full (criterion) |"
    );
    println!("| | | | | median / min ms | median / min ms | median / min ms | median / min ms | ms |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (mesh, level, runs, hedra) in cases {
        let runs = ((runs as f64 * scale).round() as usize).max(3);

        // Sanity: face count at the last level.
        let r = refiner(mesh, level, true);
        let lvl = r.level(level).expect("last level");
        let faces = lvl.face_count();
        let verts = lvl.vertex_count();
        let expected = mesh.verts_per_face.len() * 4usize.pow(level as u32);
        assert_eq!(faces, expected, "{} level {level}: face count", mesh.name);
        assert!(lvl.face_vertices_iter().all(|f| f.len() == 4));
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
            "| {} level {level} | {faces} | {verts} | {runs} | {} | {} | {} | {} | {hedra} |",
            mesh.name,
            f(full),
            f(create),
            f(full_sparse),
            f(pos)
        );
    }
}
