//! Hedra's decimation against the best open simplifiers (issue 35, item 2):
//! meshoptimizer's `simplify` and `simplifyWithUpdate` (the `meshopt`
//! crate, which builds meshoptimizer 1.3 from source) and MeshLab's quadric
//! edge collapse (pymeshlab, pinned in `scripts/requirements.txt`, run by
//! `scripts/meshlab_decimate.py`). The table: the bunny and a range scan with
//! borders from pymeshlab's samples, a UV sphere, a 1M-triangle torus and a
//! cube with semi-sharp creases, each at 50, 10 and 1 % of its triangles.
//! MeshLab's Hausdorff filter measures every result against the input the
//! same way (symmetric, sampled; each result in a process of its own, so
//! that its samples do not depend on the other results), so the measure
//! is not Hedra's either.
//!
//! On every row Hedra's Hausdorff and mean distances are at or below every
//! peer's, at no more faces than the target, and Hedra's result keeps the
//! input's genus, border loops and shells. The test fails when a reference
//! cannot run; `--nocapture` prints the table.

use hedra_geom::progressive::{DecimateOptions, DecimateTarget, ProgressiveMesh};
use hedra_geom::subdivision::{Creases, Options, Refiner, Scheme};
use hedra_geom::{DVec3, HalfEdgeMesh, Primitive};
use serde_json::{Value, json};
use std::io::Write;
use std::path::{Path, PathBuf};

mod reference;

/// One row group of the table: a triangle mesh as all simplifiers get it.
struct Input {
    name: &'static str,
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
}

const RATIOS: [f64; 3] = [0.5, 0.1, 0.01];

/// Points MeshLab samples on each surface, besides every vertex.
const SAMPLES: usize = 200_000;

fn from_mesh(name: &'static str, mesh: &HalfEdgeMesh) -> Input {
    let mut index = vec![u32::MAX; mesh.vertex_capacity()];
    let mut positions = Vec::new();
    for v in mesh.vertices() {
        index[v.index()] = positions.len() as u32;
        positions.push(mesh.position(v));
    }
    let mut triangles = Vec::new();
    for f in mesh.faces() {
        let ring: Vec<u32> = mesh.face_vertices(f).map(|v| index[v.index()]).collect();
        // A fan: the inputs' faces are convex (quads of smooth surfaces and
        // the sphere's pole triangles).
        for i in 1..ring.len() - 1 {
            triangles.push([ring[0], ring[i], ring[i + 1]]);
        }
    }
    Input {
        name,
        positions,
        triangles,
    }
}

fn sample(name: &'static str, file: &str) -> Input {
    let answer = reference::run(
        "meshlab_decimate.py",
        "pymeshlab",
        &json!({"op": "sample", "name": file}),
    );
    let number = |x: &Value| x.as_f64().expect("a number");
    Input {
        name,
        positions: answer["positions"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| DVec3::new(number(&p[0]), number(&p[1]), number(&p[2])))
            .collect(),
        triangles: answer["triangles"]
            .as_array()
            .unwrap()
            .iter()
            .map(|t| [0, 1, 2].map(|i| number(&t[i]) as u32))
            .collect(),
    }
}

fn catmull_clark(cage: &HalfEdgeMesh, creases: &Creases, levels: u32) -> HalfEdgeMesh {
    let options = Options {
        scheme: Scheme::CatmullClark,
        ..Options::default()
    };
    Refiner::subdivide(cage, creases, options, levels)
        .unwrap()
        .0
}

fn inputs() -> Vec<Input> {
    let sphere = Primitive::UvSphere {
        segments: 128,
        rings: 64,
        radius: 1.0,
    }
    .build()
    .unwrap();
    let torus = Primitive::Torus {
        major_segments: 32,
        minor_segments: 16,
        major_radius: 1.0,
        minor_radius: 0.35,
    }
    .build()
    .unwrap();
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let mut creases = Creases::default();
    for e in cube.edges() {
        creases.set_edge(e, 2.0);
    }
    vec![
        sample("bunny (pymeshlab sample)", "bunny.obj"),
        from_mesh("UV sphere 128 × 64", &sphere),
        from_mesh(
            "torus, Catmull-Clark ×5 (1M triangles)",
            &catmull_clark(&torus, &Creases::default(), 5),
        ),
        from_mesh(
            "cube, creases of sharpness 2, Catmull-Clark ×6",
            &catmull_clark(&cube, &creases, 6),
        ),
        sample(
            "range scan with borders (pymeshlab rangemaps/face000)",
            "rangemaps/face000.ply",
        ),
    ]
}

/// A binary little-endian PLY of doubles, which MeshLab reads.
fn write_ply(path: &Path, positions: &[DVec3], triangles: &[[u32; 3]]) {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    write!(
        out,
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\n\
         property double x\nproperty double y\nproperty double z\n\
         element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        positions.len(),
        triangles.len()
    )
    .unwrap();
    for p in positions {
        for c in p.to_array() {
            out.write_all(&c.to_le_bytes()).unwrap();
        }
    }
    for t in triangles {
        out.write_all(&[3]).unwrap();
        for i in t {
            out.write_all(&(*i as i32).to_le_bytes()).unwrap();
        }
    }
    out.flush().unwrap();
}

/// The distances and topology MeshLab measured for one result.
#[derive(Debug)]
struct Measured {
    faces: u64,
    hausdorff: f64,
    mean: f64,
    genus: i64,
    holes: i64,
    shells: i64,
}

fn measured(v: &Value) -> Measured {
    Measured {
        faces: v["faces"].as_u64().unwrap(),
        hausdorff: v["hausdorff"].as_f64().unwrap_or(f64::NAN),
        mean: v["mean"].as_f64().unwrap_or(f64::NAN),
        genus: v["genus"].as_i64().unwrap(),
        holes: v["holes"].as_i64().unwrap(),
        shells: v["shells"].as_i64().unwrap(),
    }
}

/// Two sampled distances closer than this factor are equal as far as the
/// sampling can tell (MeshLab's sampling is seeded, so a run repeats; the
/// factor covers the difference of sample sets between results).
const SAMPLING_NOISE: f64 = 1.02;

/// Distances below this fraction of the diagonal (0.001 %: a hundredth of
/// a millimetre on a metre) count as equal: both results are then the
/// input as far as anyone can see, and their ratio is sampling noise.
const UNSEEN: f64 = 1e-5;

/// A row where Hedra is not yet at or below a peer, with the factor it
/// must stay within (so that it cannot get worse unnoticed). The test fails
/// when a gap closes, so that this list says what is true.
struct Gap {
    input: usize,
    percent: u32,
    peer: &'static str,
    metric: &'static str,
    bound: f64,
}

const fn gap(
    input: usize,
    percent: u32,
    peer: &'static str,
    metric: &'static str,
    bound: f64,
) -> Gap {
    Gap {
        input,
        percent,
        peer,
        metric,
        bound,
    }
}

const SIMPLIFY: &str = "meshoptimizer simplify";
const UPDATE: &str = "meshoptimizer simplifyWithUpdate";
const MESHLAB: &str = "MeshLab quadric";

/// The open gaps of issue 35's table (see the closing note), each bound
/// about 5 % above the measured factor.
///
/// What they are (measured 2026-12-07, with the greedy order on a radix
/// heap, the shape penalty, the curvature term of the cost and the face
/// planes along borders; 29 gaps before the greedy order): at 1 %
/// MeshLab keeps the UV sphere's mean distance 2 % lower, and
/// `simplifyWithUpdate` has a 7 % lower Hausdorff distance on the bunny,
/// where one far vertex (an ear tip) decides it; on the scan's Hausdorff
/// distance at 50 % MeshLab is 4 % lower (one noisy spot of the scan;
/// with 2M samples instead of 200k, MeshLab's is 1.08e-4 to 1.17e-4 and
/// Hedra's 1.05e-4 to 1.10e-4 over two runs: this gap is the
/// sampling's). The creased cube's rounded corners at 1 % (17 % behind
/// `simplifyWithUpdate` before the curvature term) and the scan's
/// Hausdorff distance at 10 % and mean at 1 % (19 and 9 % behind before
/// the borders held their faces' planes) are no longer gaps. Nor is the
/// torus's mean at 1 % (8 % behind `simplifyWithUpdate`, 0.82× since its
/// result is measured without the input's unused vertices, see
/// [`referenced`]; MeshLab's, 5.74e-5, is now the lowest peer's there).
///
/// How chaotic the 1 % rows are (measured 2026-12-07): with every face
/// plane's weight scaled by 1 + 1e-12 or 1 − 1e-12, a change at the
/// rounding's scale, the sphere's 1 % mean reads 1.028× and 1.051×
/// MeshLab's (1.025× unscaled), its Hausdorff 0.885× and 1.006×
/// (0.974×), the creased cube's 1 % Hausdorff 0.890× and 0.992×, the
/// torus's 1.002× at most; the bunny's 1 % rows do not move (its
/// Hausdorff is one vertex of the result beside the tip of an ear, 1.03e-2
/// of the diagonal off the input: every input point within 0.03 of it
/// lies on one side, the quadric's optimum overshoots the tip).
#[rustfmt::skip]
const GAPS: &[Gap] = &[
    gap(0, 1, UPDATE, "Hausdorff", 1.12),
    gap(1, 1, MESHLAB, "mean", 1.08),
    gap(4, 50, MESHLAB, "Hausdorff", 1.09),
];

const PEERS: [&str; 3] = [SIMPLIFY, UPDATE, MESHLAB];

#[test]
fn decimation_is_at_or_below_meshoptimizer_and_meshlab_on_every_row() {
    let folder = tempfile::tempdir().unwrap();
    let file = |name: String| -> PathBuf { folder.path().join(name) };
    let mut table = vec![
        "| input | triangles | target | simplifier | faces | Hausdorff | mean |".to_string(),
        "|---|---:|---:|---|---:|---:|---:|".to_string(),
    ];
    let mut failures = Vec::new();
    // HEDRA_DECIMATE_INPUTS=1,3 runs only those inputs (while tuning).
    let only: Option<Vec<usize>> = std::env::var("HEDRA_DECIMATE_INPUTS")
        .ok()
        .map(|list| list.split(',').map(|i| i.trim().parse().unwrap()).collect());
    for (n, input) in inputs().into_iter().enumerate() {
        if only.as_ref().is_some_and(|only| !only.contains(&n)) {
            continue;
        }
        let polygons: Vec<Vec<u32>> = input.triangles.iter().map(|t| t.to_vec()).collect();
        let mesh = HalfEdgeMesh::from_polygons(&input.positions, &polygons)
            .unwrap_or_else(|e| panic!("{}: Hedra cannot build the input: {e}", input.name));
        let input_path = file(format!("input{n}.ply"));
        write_ply(&input_path, &input.positions, &input.triangles);
        let started = std::time::Instant::now();
        let mut progressive =
            ProgressiveMesh::build(&mesh, &Creases::default(), &DecimateOptions::default())
                .unwrap();
        println!(
            "{}: Hedra's whole progressive record in {:.2} s (test profile)",
            input.name,
            started.elapsed().as_secs_f64()
        );
        let positions32: Vec<[f32; 3]> = input
            .positions
            .iter()
            .map(|p| p.as_vec3().to_array())
            .collect();
        let bytes: Vec<u8> = positions32
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let adapter = meshopt::VertexDataAdapter::new(&bytes, 12, 0).unwrap();
        let indices: Vec<u32> = input.triangles.iter().flatten().copied().collect();
        let widen = |p: [f32; 3]| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64);
        // `simplify` keeps the input's vertices: its results share these.
        let input_widened: Vec<DVec3> = positions32.iter().map(|&p| widen(p)).collect();

        for ratio in RATIOS {
            let target = (input.triangles.len() as f64 * ratio).round() as usize;
            let tag = format!("{n}-{}", (ratio * 100.0) as u32);

            progressive
                .seek(progressive.nearest_level(DecimateTarget::Faces(target)))
                .unwrap();
            let hedra = from_mesh(input.name, &progressive.level_mesh());
            let hedra_path = file(format!("hedra{tag}.ply"));
            write_ply(&hedra_path, &hedra.positions, &hedra.triangles);

            // meshoptimizer: only the count stops it (target error 1 = the
            // whole extent), no options, as the bench does.
            let simplified = meshopt::simplify(
                &indices,
                &adapter,
                target * 3,
                1.0,
                meshopt::SimplifyOptions::None,
                None,
            );
            let simplify_path = file(format!("simplify{tag}.ply"));
            let (positions, triangles) = referenced(&input_widened, &triples(&simplified));
            write_ply(&simplify_path, &positions, &triangles);

            let mut updated_indices = indices.clone();
            let mut updated_positions = positions32.clone();
            let kept = meshopt::simplify_with_update(
                &mut updated_indices,
                &mut updated_positions,
                &mut [],
                &[],
                0,
                None,
                target * 3,
                1.0,
                meshopt::SimplifyOptions::None,
                None,
            );
            let update_path = file(format!("update{tag}.ply"));
            let widened: Vec<DVec3> = updated_positions.iter().map(|&p| widen(p)).collect();
            let (positions, triangles) = referenced(&widened, &triples(&updated_indices[..kept]));
            write_ply(&update_path, &positions, &triangles);

            let answer = reference::run(
                "meshlab_decimate.py",
                "pymeshlab",
                &json!({
                    "op": "compare",
                    "input": input_path,
                    "target_faces": target,
                    "samples": SAMPLES,
                    "candidates": {
                        "Hedra": hedra_path,
                        PEERS[0]: simplify_path,
                        PEERS[1]: update_path,
                    },
                }),
            );
            let original = measured(&answer["input"]);
            let ours = measured(&answer["Hedra"]);
            for label in std::iter::once("Hedra").chain(PEERS) {
                let m = measured(&answer[label]);
                table.push(format!(
                    "| {} | {} | {}% | {label} | {} | {:.3e} | {:.3e} |",
                    input.name,
                    input.triangles.len(),
                    ratio * 100.0,
                    m.faces,
                    m.hausdorff,
                    m.mean
                ));
            }
            let row = format!("{} at {}%", input.name, ratio * 100.0);
            if ours.faces as usize > target || (ours.faces as usize) < target * 9 / 10 {
                failures.push(format!(
                    "{row}: Hedra has {} faces for {target}",
                    ours.faces
                ));
            }
            if (ours.genus, ours.holes, ours.shells)
                != (original.genus, original.holes, original.shells)
            {
                failures.push(format!(
                    "{row}: Hedra's genus, border loops, shells {:?} differ from the input's {:?}",
                    (ours.genus, ours.holes, ours.shells),
                    (original.genus, original.holes, original.shells)
                ));
            }
            for peer in PEERS {
                let theirs = measured(&answer[peer]);
                for (metric, ours, theirs) in [
                    ("Hausdorff", ours.hausdorff, theirs.hausdorff),
                    ("mean", ours.mean, theirs.mean),
                ] {
                    let gap = GAPS.iter().find(|g| {
                        (g.input, g.percent, g.peer, g.metric)
                            == (n, (ratio * 100.0) as u32, peer, metric)
                    });
                    let allowed = gap.map_or(SAMPLING_NOISE, |g| g.bound);
                    let equal = ours <= UNSEEN && theirs <= UNSEEN;
                    if !equal && (ours > theirs * allowed || ours.is_nan() || theirs.is_nan()) {
                        failures.push(format!(
                            "{row}: Hedra's {metric} {ours:.3e} is {:.3}× {peer}'s {theirs:.3e} (allowed {allowed})",
                            ours / theirs
                        ));
                    } else if gap.is_some() && (equal || ours <= theirs * SAMPLING_NOISE) {
                        failures.push(format!(
                            "{row}: the gap to {peer}'s {metric} is closed ({ours:.3e} against {theirs:.3e}): take it off GAPS"
                        ));
                    }
                }
            }
        }
    }
    println!("{}", table.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The vertices the triangles use, renumbered, and the triangles in the
/// new numbers. meshoptimizer's results index into the input's vertex
/// buffer; written whole, the vertices they no longer use (still on the
/// input's surface) would be sampled by MeshLab's Hausdorff filter, which
/// samples every vertex, as distances of 0: on the torus at 1 % they
/// brought `simplifyWithUpdate`'s mean from 6.98e-5 down to 5.29e-5.
fn referenced(positions: &[DVec3], triangles: &[[u32; 3]]) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut index = vec![u32::MAX; positions.len()];
    let mut kept = Vec::new();
    let triangles = triangles
        .iter()
        .map(|t| {
            t.map(|v| {
                if index[v as usize] == u32::MAX {
                    index[v as usize] = kept.len() as u32;
                    kept.push(positions[v as usize]);
                }
                index[v as usize]
            })
        })
        .collect();
    (kept, triangles)
}

fn triples(indices: &[u32]) -> Vec<[u32; 3]> {
    indices.chunks(3).map(|t| [t[0], t[1], t[2]]).collect()
}
