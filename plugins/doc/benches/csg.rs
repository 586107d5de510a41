//! Live CSG (issue 17): re-evaluating the emblem (a cube ∩ a sphere, minus
//! three rods) whose operands have about 10k faces each, after one rod
//! moved, as a drag frame does: the cached steps before the moved operand
//! are reused. Goal: under 16 ms a frame. Exact frames (`emblem_10k_move_*`)
//! and drag-preview frames with simplified operands
//! (`emblem_10k_preview_move_*`, `csg::Quality::DRAG`), and a frame where
//! nothing changed (`emblem_10k_unchanged`: the cache's own cost).

use criterion::{Criterion, criterion_main};
use glam::DVec3;
use hedra_doc::{Command, NodeRef, NodeTransform, Session, csg};
use hedra_geom::csg::BooleanOp;
use std::f64::consts::TAU;

/// The allocator the app uses (see `src/main.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// A cube of side 2 with n × n quads on each face (6n² faces).
fn cube(n: u32) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let mut positions = Vec::new();
    let mut index = std::collections::HashMap::new();
    let mut polygons = Vec::new();
    let mut at = |p: DVec3, positions: &mut Vec<DVec3>| {
        let key = (p * 1e6).round().as_i64vec3().to_array();
        *index.entry(key).or_insert_with(|| {
            positions.push(p);
            positions.len() as u32 - 1
        })
    };
    for axis in 0..3 {
        for side in [-1.0, 1.0] {
            let normal = DVec3::AXES[axis] * side;
            let u = DVec3::AXES[(axis + 1) % 3];
            let v = normal.cross(u);
            let corner = |i: u32, j: u32| {
                normal
                    + u * (2.0 * i as f64 / n as f64 - 1.0)
                    + v * (2.0 * j as f64 / n as f64 - 1.0)
            };
            for i in 0..n {
                for j in 0..n {
                    let q = [
                        corner(i, j),
                        corner(i + 1, j),
                        corner(i + 1, j + 1),
                        corner(i, j + 1),
                    ];
                    polygons.push(q.map(|p| at(p, &mut positions)).to_vec());
                }
            }
        }
    }
    (positions, polygons)
}

/// A rod along y: `segments` around, `stacks` along, capped (radius 0.5, length 3).
fn rod(segments: u32, stacks: u32) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let mut positions = Vec::new();
    for k in 0..=stacks {
        let y = -1.5 + 3.0 * k as f64 / stacks as f64;
        for s in 0..segments {
            let a = TAU * s as f64 / segments as f64;
            positions.push(DVec3::new(0.5 * a.cos(), y, -0.5 * a.sin()));
        }
    }
    let id = |k: u32, s: u32| k * segments + s % segments;
    let mut polygons = Vec::new();
    for k in 0..stacks {
        for s in 0..segments {
            polygons.push(vec![id(k, s), id(k, s + 1), id(k + 1, s + 1), id(k + 1, s)]);
        }
    }
    polygons.push((0..segments).rev().map(|s| id(0, s)).collect());
    polygons.push((0..segments).map(|s| id(stacks, s)).collect());
    (positions, polygons)
}

fn add(
    session: &mut Session,
    name: &str,
    mesh: (Vec<DVec3>, Vec<Vec<u32>>),
    rotation: glam::DQuat,
) {
    session
        .execute(&Command::AddMesh {
            name: name.into(),
            positions: mesh.0,
            polygons: mesh.1,
            parent: None,
            transform: NodeTransform {
                rotation,
                ..NodeTransform::IDENTITY
            },
        })
        .unwrap();
}

fn bench(c: &mut Criterion) {
    let mut s = Session::new();
    add(&mut s, "Cube", cube(41), glam::DQuat::IDENTITY); // 10,086 faces
    s.execute(&Command::AddPrimitive {
        primitive: hedra_geom::Primitive::UvSphere {
            segments: 128,
            rings: 80,
            radius: 1.35,
        }, // 10,240 faces
        name: Some("Sphere".into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let name = |n: &str| NodeRef::Name(n.into());
    s.execute(&Command::AddCsg {
        op: BooleanOp::Intersection,
        name: Some("Core".into()),
        operands: vec![name("Cube"), name("Sphere")],
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let q = |axis: DVec3| glam::DQuat::from_rotation_arc(DVec3::Y, axis);
    add(&mut s, "Rod Y", rod(100, 99), q(DVec3::Y)); // 9,902 faces
    add(&mut s, "Rod X", rod(100, 99), q(DVec3::X));
    add(&mut s, "Rod Z", rod(100, 99), q(DVec3::Z));
    s.execute(&Command::AddCsg {
        op: BooleanOp::Difference,
        name: Some("Emblem".into()),
        operands: vec![name("Core"), name("Rod Y"), name("Rod X"), name("Rod Z")],
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let emblem = s.doc.find_by_name("Emblem").unwrap().id;
    let mut g = c.benchmark_group("csg_drag");
    g.sample_size(10);
    g.bench_function("emblem_10k_unchanged", |b| {
        b.iter(|| std::hint::black_box(csg::evaluate(&s.doc, emblem).unwrap()))
    });
    let mut step = 0u64;
    // The command alone, without evaluating: what a frame costs besides
    // the CSG.
    {
        let id = s.doc.find_by_name("Rod Z").unwrap().id;
        let base = s.doc.node(id).unwrap().transform;
        g.bench_function("emblem_10k_set_transform_only", |b| {
            b.iter(|| {
                step += 1;
                let mut t = base;
                t.translation.x += 1e-6 * step as f64;
                s.execute(&Command::SetTransforms {
                    nodes: vec![(NodeRef::Id(id.0), t)],
                })
                .unwrap();
            })
        });
    }
    for (quality, prefix) in [
        (csg::Quality::Exact, "emblem_10k_move"),
        (csg::Quality::DRAG, "emblem_10k_preview_move"),
    ] {
        for rod_name in ["Rod Z", "Rod Y"] {
            let id = s.doc.find_by_name(rod_name).unwrap().id;
            let base = s.doc.node(id).unwrap().transform;
            // Each frame moves the rod a little further (a new position, so
            // the steps from it on are not cached), as a drag frame does.
            g.bench_function(format!("{prefix}_{}", rod_name.replace(' ', "_")), |b| {
                b.iter(|| {
                    step += 1;
                    let mut t = base;
                    t.translation.x += 1e-6 * step as f64;
                    s.execute(&Command::SetTransforms {
                        nodes: vec![(NodeRef::Id(id.0), t)],
                    })
                    .unwrap();
                    std::hint::black_box(csg::evaluate_with(&s.doc, emblem, quality).unwrap())
                })
            });
        }
    }
    g.finish();
}

// The macro's `benches` function is Criterion's, not an API to document.
#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::bench);
}
criterion_main!(group::benches);
