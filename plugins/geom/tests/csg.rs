//! Mesh booleans (issue 17): exact volumes, genus by Euler–Poincaré, the
//! degenerate cases that break naive booleans (each named), polygons merged
//! back, named errors, and a property test over random primitive pairs.

use hedra_geom::csg::{
    BooleanError, BooleanOp, Operand, boolean, boolean_with_sources, check_operand,
    self_intersections,
};
use hedra_geom::{DMat4, DQuat, DVec3, HalfEdgeMesh, Primitive};
use proptest::prelude::*;

fn cube(size: f64) -> HalfEdgeMesh {
    Primitive::Cube { size }.build().unwrap()
}

fn moved(mut m: HalfEdgeMesh, matrix: DMat4) -> HalfEdgeMesh {
    for p in m.positions_mut() {
        *p = matrix.transform_point3(*p);
    }
    m
}

fn at(m: HalfEdgeMesh, t: DVec3) -> HalfEdgeMesh {
    moved(m, DMat4::from_translation(t))
}

/// A cylinder through the unit cube along `axis` (radius 0.25, length 2).
fn rod(axis: DVec3) -> HalfEdgeMesh {
    let c = Primitive::Cylinder {
        segments: 24,
        radius: 0.25,
        depth: 2.0,
    }
    .build()
    .unwrap();
    moved(
        c,
        DMat4::from_quat(DQuat::from_rotation_arc(DVec3::Y, axis)),
    )
}

/// Runs a boolean and checks what every result must be: valid, closed.
fn run(a: &HalfEdgeMesh, b: &HalfEdgeMesh, op: BooleanOp) -> HalfEdgeMesh {
    let m = boolean(a, b, op, 0.0).unwrap_or_else(|e| panic!("{op}: {e}"));
    m.validate().unwrap();
    let stats = m.stats();
    assert!(stats.closed, "{op}: result is open");
    assert!(stats.manifold, "{op}: result is not manifold");
    assert_triangles_are_manifold(&m, &op.to_string());
    m
}

/// The triangles every exporter and the viewport draw for `m`
/// (`query::triangulate_face` per face) form a closed 2-manifold: no
/// triangle without area, every edge in exactly two triangles, once each
/// way.
fn assert_triangles_are_manifold(m: &HalfEdgeMesh, what: &str) {
    use std::collections::HashMap;
    let mut uses: HashMap<(u32, u32), i32> = HashMap::new();
    let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
    for f in m.faces() {
        for t in hedra_geom::query::triangulate_face(m, f) {
            let [a, b, c] = t.map(|v| m.position(v));
            let area = (b - a).cross(c - a).length() / 2.0;
            assert!(
                area > 0.0,
                "{what}: a triangle of face {f:?} has no area: {t:?}"
            );
            for k in 0..3 {
                let (p, q) = (t[k].0, t[(k + 1) % 3].0);
                *uses.entry((p.min(q), p.max(q))).or_default() += 1;
                *directed.entry((p, q)).or_default() += 1;
            }
        }
    }
    let bad: Vec<_> = uses.iter().filter(|(_, n)| **n != 2).collect();
    assert!(
        bad.is_empty(),
        "{what}: {} edges not in exactly two triangles, e.g. {:?}",
        bad.len(),
        &bad[..bad.len().min(4)]
    );
    assert!(
        directed.values().all(|&n| n == 1),
        "{what}: an edge runs the same way in two triangles"
    );
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + b.abs())
}

#[test]
fn offset_unit_cubes_have_exact_volumes() {
    let a = cube(1.0);
    let b = at(cube(1.0), DVec3::splat(0.5));
    let u = run(&a, &b, BooleanOp::Union);
    let i = run(&a, &b, BooleanOp::Intersection);
    let d = run(&a, &b, BooleanOp::Difference);
    assert!(close(u.volume(), 15.0 / 8.0), "{}", u.volume());
    assert!(close(i.volume(), 1.0 / 8.0), "{}", i.volume());
    assert!(close(d.volume(), 7.0 / 8.0), "{}", d.volume());
    // The intersection is a cube again: its triangles merged back into six quads.
    assert_eq!((i.vertex_count(), i.face_count()), (8, 6));
    assert!(i.faces().all(|f| i.face_degree(f) == 4));
    // The union: three L-shaped hexagons and three quads from each cube.
    assert_eq!(u.face_count(), 12);
    assert_eq!(u.stats().genus, Some(0));
}

#[test]
fn untouched_faces_come_back_as_they_were() {
    // A cube minus a rod along y: the four side faces are not cut.
    let a = cube(1.0);
    let r = boolean_with_sources(&a, &rod(DVec3::Y), BooleanOp::Difference, 0.0).unwrap();
    let m = &r.mesh;
    m.validate().unwrap();
    let whole: Vec<_> = r
        .faces
        .iter()
        .filter(|s| s.whole && s.operand == Operand::A)
        .collect();
    assert_eq!(whole.len(), 4, "the ±x and ±z faces");
    for f in m.faces() {
        let src = r.faces[f.index()];
        if src.whole {
            let source = if src.operand == Operand::A {
                &a
            } else {
                unreachable!()
            };
            let mut got: Vec<[u64; 3]> = m
                .face_vertices(f)
                .map(|v| m.position(v).to_array().map(f64::to_bits))
                .collect();
            let mut want: Vec<[u64; 3]> = source
                .face_vertices(src.face)
                .map(|v| source.position(v).to_array().map(f64::to_bits))
                .collect();
            got.sort();
            want.sort();
            assert_eq!(got, want, "{f} is {} as it was", src.face);
        }
    }
    // The rod's 24 side quads come back as (shorter) quads, reversed.
    let rod_quads = m
        .faces()
        .filter(|&f| r.faces[f.index()].operand == Operand::B && m.face_degree(f) == 4)
        .count();
    assert_eq!(rod_quads, 24);
    // No two vertices at one place.
    let mut keys: Vec<[u64; 3]> = m
        .vertices()
        .map(|v| m.position(v).to_array().map(f64::to_bits))
        .collect();
    keys.sort();
    keys.dedup();
    assert_eq!(keys.len(), m.vertex_count());
    // Each vertex at an operand vertex's place is tracked to it.
    let tracked = r.vertices.iter().filter(|v| v.is_some()).count();
    assert_eq!(tracked, 8, "the cube's corners; the rod's ends are outside");
}

#[test]
fn cube_minus_a_rod_has_genus_one_and_minus_three_has_genus_five() {
    let mut m = cube(1.0);
    let mut want_volume = 1.0;
    for (k, axis) in [DVec3::Y, DVec3::X, DVec3::Z].into_iter().enumerate() {
        let before = m.volume();
        m = run(&m, &rod(axis), BooleanOp::Difference);
        assert!(m.volume() < before);
        let s = m.stats();
        // V − E + F = 2 − 2g on one closed shell.
        assert_eq!(s.shells, 1);
        assert_eq!(s.euler_characteristic, 2 - 2 * [1, 3, 5][k]);
        assert_eq!(s.genus, Some([1, 3, 5][k]), "after {} rods", k + 1);
        want_volume = m.volume();
    }
    assert!(want_volume > 0.5 && want_volume < 1.0);
}

#[test]
fn coplanar_faces_two_cubes_sharing_a_face() {
    let a = cube(1.0);
    let b = at(cube(1.0), DVec3::X);
    let u = run(&a, &b, BooleanOp::Union);
    assert!(close(u.volume(), 2.0));
    assert_eq!(u.stats().shells, 1);
    // The shared face is gone; the coplanar sides stay one face per cube.
    assert_eq!(u.face_count(), 10);
    assert_eq!(
        boolean(&a, &b, BooleanOp::Intersection, 0.0).unwrap_err(),
        BooleanError::EmptyResult {
            op: BooleanOp::Intersection
        }
    );
    let d = run(&a, &b, BooleanOp::Difference);
    assert!(close(d.volume(), 1.0));
    assert_eq!((d.vertex_count(), d.face_count()), (8, 6));
}

#[test]
fn coplanar_faces_cube_minus_a_cube_flush_with_its_top() {
    let a = cube(1.0);
    let b = at(cube(0.5), DVec3::new(0.0, 0.25, 0.0)); // top at y = 0.5
    let d = run(&a, &b, BooleanOp::Difference);
    assert!(close(d.volume(), 1.0 - 0.125), "{}", d.volume());
    assert_eq!(d.stats().genus, Some(0), "a pocket, not a hole");
    let i = run(&a, &b, BooleanOp::Intersection);
    assert!(close(i.volume(), 0.125));
    let u = run(&a, &b, BooleanOp::Union);
    assert!(close(u.volume(), 1.0));
    assert_eq!((u.vertex_count(), u.face_count()), (8, 6), "B adds nothing");
}

#[test]
fn shared_edge_and_shared_vertex() {
    let a = cube(1.0);
    for (what, offset) in [("edge", DVec3::new(1.0, 1.0, 0.0)), ("vertex", DVec3::ONE)] {
        let b = at(cube(1.0), offset);
        let u = run(&a, &b, BooleanOp::Union);
        assert!(close(u.volume(), 2.0), "{what}");
        // Two shells that touch; each keeps its own copy of the shared vertices.
        assert_eq!(u.stats().shells, 2, "{what}");
        assert_eq!(u.vertex_count(), 16, "{what}");
        assert!(matches!(
            boolean(&a, &b, BooleanOp::Intersection, 0.0),
            Err(BooleanError::EmptyResult { .. })
        ));
        let d = run(&a, &b, BooleanOp::Difference);
        assert!(close(d.volume(), 1.0), "{what}");
        assert_eq!(d.face_count(), 6, "{what}: A untouched");
    }
}

#[test]
fn touching_at_one_point() {
    // An octahedron's tip on the cube's top face.
    let o = Primitive::UvSphere {
        segments: 4,
        rings: 2,
        radius: 0.5,
    }
    .build()
    .unwrap();
    let b = at(o, DVec3::new(0.0, 1.0, 0.0)); // lower tip at y = 0.5
    let a = cube(1.0);
    let u = run(&a, &b, BooleanOp::Union);
    assert!(close(u.volume(), 1.0 + b.volume()));
    assert_eq!(u.stats().shells, 2);
    assert!(matches!(
        boolean(&a, &b, BooleanOp::Intersection, 0.0),
        Err(BooleanError::EmptyResult { .. })
    ));
}

#[test]
fn one_operand_entirely_inside_the_other() {
    let a = cube(1.0);
    let b = cube(0.5);
    let d = run(&a, &b, BooleanOp::Difference);
    assert!(close(d.volume(), 0.875));
    let s = d.stats();
    assert_eq!(s.shells, 2, "the outside and the cavity");
    assert_eq!(s.euler_characteristic, 4);
    let i = run(&a, &b, BooleanOp::Intersection);
    assert!(close(i.volume(), 0.125));
    let u = run(&a, &b, BooleanOp::Union);
    assert_eq!((u.vertex_count(), u.face_count()), (8, 6));
    // B minus A: nothing left.
    assert!(matches!(
        boolean(&b, &a, BooleanOp::Difference, 0.0),
        Err(BooleanError::EmptyResult {
            op: BooleanOp::Difference
        })
    ));
}

#[test]
fn identical_operands() {
    let a = Primitive::Cylinder {
        segments: 12,
        radius: 0.5,
        depth: 1.0,
    }
    .build()
    .unwrap();
    for op in [BooleanOp::Union, BooleanOp::Intersection] {
        let m = run(&a, &a, op);
        assert!(close(m.volume(), a.volume()), "{op}");
        // The same 24 vertices; a face may come back in two pieces, one
        // from each operand (the engine keeps either copy of a coplanar
        // pair triangle by triangle), never more.
        assert_eq!(m.vertex_count(), 24, "{op}");
        assert!(m.face_count() <= 2 * 14, "{op}: {}", m.face_count());
        let quads = m.faces().filter(|&f| m.face_degree(f) == 4).count();
        assert!(quads >= 8, "{op}: {quads}");
    }
    let e = boolean(&a, &a, BooleanOp::Difference, 0.0).unwrap_err();
    assert_eq!(e.to_string(), "the difference is empty");
}

#[test]
fn thin_sliver() {
    // Cubes overlapping by 1e-7.
    let a = cube(1.0);
    let b = at(cube(1.0), DVec3::new(0.0, 1.0 - 1e-7, 0.0));
    let i = run(&a, &b, BooleanOp::Intersection);
    assert!((i.volume() - 1e-7).abs() < 1e-15, "{}", i.volume());
    let u = run(&a, &b, BooleanOp::Union);
    assert!((u.volume() - (2.0 - 1e-7)).abs() < 1e-12);
    let d = run(&a, &b, BooleanOp::Difference);
    assert!((d.volume() - (1.0 - 1e-7)).abs() < 1e-12);
    assert_eq!(d.face_count(), 6);
}

#[test]
fn an_open_operand_is_refused_with_its_border_edge_count() {
    let plane = Primitive::Plane { size: 1.0 }.build().unwrap();
    let e = boolean(&cube(1.0), &plane, BooleanOp::Union, 0.0).unwrap_err();
    assert_eq!(
        e,
        BooleanError::Open {
            operand: Operand::B,
            border_edges: 4
        }
    );
    assert_eq!(
        e.to_string(),
        "the second operand is open: 4 border edges (a boolean needs closed meshes)"
    );
    let empty = HalfEdgeMesh::new();
    assert_eq!(
        boolean(&empty, &cube(1.0), BooleanOp::Union, 0.0).unwrap_err(),
        BooleanError::EmptyOperand {
            operand: Operand::A
        }
    );
}

/// One mesh of two shells: a unit cube and a copy moved by `offset`.
fn two_shells(offset: DVec3) -> HalfEdgeMesh {
    let (mut positions, mut polygons) = cube(1.0).to_polygons();
    let (p2, f2) = at(cube(1.0), offset).to_polygons();
    let base = positions.len() as u32;
    positions.extend(p2);
    polygons.extend(
        f2.into_iter()
            .map(|f| f.into_iter().map(|v| v + base).collect()),
    );
    HalfEdgeMesh::from_polygons(&positions, &polygons).unwrap()
}

#[test]
fn a_self_intersecting_operand_is_refused_with_its_crossing_face_pairs() {
    // Cubes [-0.5, 0.5]³ and that moved by (0.5, 0.3, 0.4) in one mesh:
    // each of the first's +x, +y, +z faces crosses two of the second's
    // −x, −y, −z faces (the two of the other axes): 6 pairs.
    let twin = two_shells(DVec3::new(0.5, 0.3, 0.4));
    twin.validate().unwrap();
    let pairs = self_intersections(&twin);
    assert_eq!(pairs.len(), 6, "{pairs:?}");
    // Every pair is one face of each shell (ids 0..6 and 6..12).
    assert!(pairs.iter().all(|(f, g)| f.index() < 6 && g.index() >= 6));
    let e = boolean(&cube(3.0), &twin, BooleanOp::Union, 0.0).unwrap_err();
    assert_eq!(
        e,
        BooleanError::SelfIntersecting {
            operand: Operand::B,
            face_pairs: 6
        }
    );
    assert_eq!(
        e.to_string(),
        "the second operand intersects itself: 6 pairs of its faces cross"
    );
    assert_eq!(
        check_operand(&twin).unwrap_err().to_string(),
        "the first operand intersects itself: 6 pairs of its faces cross"
    );
    // Shells apart, or touching along a face without crossing: none.
    assert!(self_intersections(&two_shells(DVec3::X * 2.0)).is_empty());
    assert!(self_intersections(&two_shells(DVec3::X)).is_empty());
    // One shell inside the other crosses nothing either (it is a solid
    // with a cavity, not a crossing).
    let (mut positions, mut polygons) = cube(3.0).to_polygons();
    let (p2, f2) = cube(1.0).to_polygons();
    let base = positions.len() as u32;
    positions.extend(p2);
    polygons.extend(
        f2.into_iter()
            .map(|f| f.into_iter().rev().map(|v| v + base).collect()),
    );
    let hollow = HalfEdgeMesh::from_polygons(&positions, &polygons).unwrap();
    assert!(self_intersections(&hollow).is_empty());
}

#[test]
fn smooth_primitives_and_boolean_results_do_not_intersect_themselves() {
    let meshes = [
        Primitive::UvSphere {
            segments: 64,
            rings: 32,
            radius: 1.0,
        },
        Primitive::Torus {
            major_segments: 48,
            minor_segments: 24,
            major_radius: 1.0,
            minor_radius: 0.25,
        },
        Primitive::Cylinder {
            segments: 64,
            radius: 0.5,
            depth: 2.0,
        },
        Primitive::Cube { size: 1.0 },
    ];
    for p in meshes {
        let m = p.build().unwrap();
        assert_eq!(self_intersections(&m), vec![], "{p:?}");
        check_operand(&m).unwrap();
    }
    let cube_minus_rods = [DVec3::X, DVec3::Y, DVec3::Z]
        .iter()
        .fold(cube(1.0), |acc, &axis| {
            run(&acc, &rod(axis), BooleanOp::Difference)
        });
    assert!(self_intersections(&cube_minus_rods).is_empty());
}

#[test]
fn disjoint_intersection_is_empty() {
    let e = boolean(
        &cube(1.0),
        &at(cube(1.0), DVec3::X * 3.0),
        BooleanOp::Intersection,
        0.0,
    )
    .unwrap_err();
    assert_eq!(e.to_string(), "the intersection is empty");
    // A union of disjoint solids is both.
    let u = run(&cube(1.0), &at(cube(1.0), DVec3::X * 3.0), BooleanOp::Union);
    assert_eq!((u.stats().shells, u.face_count()), (2, 12));
}

fn primitive(kind: u8) -> HalfEdgeMesh {
    match kind % 4 {
        0 => cube(1.0),
        1 => Primitive::UvSphere {
            segments: 10,
            rings: 6,
            radius: 0.6,
        }
        .build()
        .unwrap(),
        2 => Primitive::Cylinder {
            segments: 9,
            radius: 0.4,
            depth: 1.2,
        }
        .build()
        .unwrap(),
        _ => Primitive::IcoSphere {
            subdivisions: 1,
            radius: 0.6,
        }
        .build()
        .unwrap(),
    }
}

fn placed(kind: u8, t: [f64; 3], euler: [f64; 3], scale: f64) -> HalfEdgeMesh {
    let r = DQuat::from_euler(glam::EulerRot::XYZ, euler[0], euler[1], euler[2]);
    moved(
        primitive(kind),
        DMat4::from_scale_rotation_translation(DVec3::splat(scale), r, DVec3::from(t)),
    )
}

fn volume_of(a: &HalfEdgeMesh, b: &HalfEdgeMesh, op: BooleanOp) -> f64 {
    match boolean(a, b, op, 0.0) {
        Ok(m) => {
            m.validate().unwrap();
            assert!(m.stats().closed, "{op} open");
            assert_triangles_are_manifold(&m, &op.to_string());
            m.volume()
        }
        Err(BooleanError::EmptyResult { .. }) => 0.0,
        Err(e) => panic!("{op}: {e}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    #[test]
    fn inclusion_exclusion_and_partition(
        ka in 0u8..4, kb in 0u8..4,
        ta in prop::array::uniform3(-0.3f64..0.3), tb in prop::array::uniform3(-0.8f64..0.8),
        ea in prop::array::uniform3(-3.2f64..3.2), eb in prop::array::uniform3(-3.2f64..3.2),
        sa in 0.7f64..1.3, sb in 0.5f64..1.3,
    ) {
        let a = placed(ka, ta, ea, sa);
        let b = placed(kb, tb, eb, sb);
        let (va, vb) = (a.volume(), b.volume());
        let u = volume_of(&a, &b, BooleanOp::Union);
        let i = volume_of(&a, &b, BooleanOp::Intersection);
        let d = volume_of(&a, &b, BooleanOp::Difference);
        let scale = va + vb;
        prop_assert!((u + i - va - vb).abs() <= 1e-9 * scale, "∪ + ∩: {} vs {}", u + i, va + vb);
        prop_assert!((d + i - va).abs() <= 1e-9 * scale, "(A − B) + (A ∩ B): {} vs {}", d + i, va);
    }
}

fn uv_sphere() -> HalfEdgeMesh {
    Primitive::UvSphere {
        segments: 32,
        rings: 16,
        radius: 1.0,
    }
    .build()
    .unwrap()
}

/// Issue 35's repro: a sphere minus the same sphere turned by about 1e-4
/// rad. The merged polygons of the result share chains with nearly
/// collinear degree-2 vertices; ear clipping took the flat ear at such a
/// vertex in both polygons, so two coincident triangles of area 1.4e-13 put
/// 1 to 64 edges into four triangles (the exported STL was not watertight).
#[test]
fn a_sphere_minus_a_nearly_coincident_sphere_triangulates_watertight() {
    let a = uv_sphere();
    let turn = DQuat::from_xyzw(
        2.4628014712012152e-05,
        8.209338237337385e-05,
        1.641867647467477e-05,
        0.9999999961922823,
    );
    let b = moved(uv_sphere(), DMat4::from_quat(turn));
    for op in [
        BooleanOp::Difference,
        BooleanOp::Union,
        BooleanOp::Intersection,
    ] {
        let m = run(&a, &b, op);
        assert!(m.face_count() > 0, "{op}");
    }
}

/// `Triangulate` (every method) on `m`: valid, and no triangle without
/// area.
fn assert_triangulate_keeps_area(m: &HalfEdgeMesh, what: &str) {
    use hedra_geom::modeling::{TriangulateMethod, triangulate_faces};
    for method in [
        TriangulateMethod::Clip,
        TriangulateMethod::Beauty,
        TriangulateMethod::Fan,
    ] {
        let mut t = m.clone();
        let faces: Vec<_> = t.faces().collect();
        triangulate_faces(&mut t, &faces, method).unwrap();
        t.validate().unwrap();
        for f in t.faces() {
            let [a, b, c]: [DVec3; 3] = t
                .face_vertices(f)
                .map(|v| t.position(v))
                .collect::<Vec<_>>()
                .try_into()
                .unwrap_or_else(|v: Vec<DVec3>| panic!("{what} {method:?}: a face of {}", v.len()));
            let area = (b - a).cross(c - a).length() / 2.0;
            assert!(area > 0.0, "{what} {method:?}: face {f:?} has no area");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Near-coincident operands (the same primitive turned by 1e-7 to 1e-3
    /// rad and moved as little): every result triangulates into a closed
    /// 2-manifold without slivers of no area, for the exporters and for
    /// `Triangulate`.
    #[test]
    fn near_coincident_results_triangulate_watertight(
        kind in 0u8..4,
        axis in prop::array::uniform3(-1.0f64..1.0),
        exponent in -7.0f64..-3.0,
        shift in prop::array::uniform3(-1.0f64..1.0),
    ) {
        let axis = DVec3::from(axis);
        prop_assume!(axis.length() > 0.1);
        let small = 10f64.powf(exponent);
        let a = primitive(kind);
        let matrix = DMat4::from_rotation_translation(
            DQuat::from_axis_angle(axis.normalize(), small),
            DVec3::from(shift) * small,
        );
        let b = moved(primitive(kind), matrix);
        for op in [BooleanOp::Difference, BooleanOp::Union, BooleanOp::Intersection] {
            match boolean(&a, &b, op, 0.0) {
                Ok(m) => {
                    m.validate().unwrap();
                    let what = format!("{op} kind {kind} at {small:e}");
                    assert_triangles_are_manifold(&m, &what);
                    assert_triangulate_keeps_area(&m, &what);
                }
                Err(BooleanError::EmptyResult { .. }) => {}
                Err(e) => panic!("{op}: {e}"),
            }
        }
    }
}
