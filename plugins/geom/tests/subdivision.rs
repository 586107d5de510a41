//! Subdivision against values worked out by hand from the masks (seed 003)
//! and exact fractions from an independent dictionary-based implementation;
//! creases, boundaries, schemes, limit evaluation and stencils.

use hedra_geom::subdivision::{
    BoundaryInterpolation, CreaseMethod, Creases, INFINITE_SHARPNESS, Options, Refiner, Scheme,
    SubdivisionError, limit_normals, limit_positions, snap_to_limit,
};
use hedra_geom::{DVec3, HalfEdgeMesh, Primitive, VertexId};
use proptest::prelude::*;

fn cube() -> HalfEdgeMesh {
    Primitive::Cube { size: 2.0 }.build().unwrap()
}

fn icosahedron() -> HalfEdgeMesh {
    Primitive::IcoSphere {
        subdivisions: 0,
        radius: 1.0,
    }
    .build()
    .unwrap()
}

fn options(scheme: Scheme) -> Options {
    Options {
        scheme,
        ..Options::default()
    }
}

fn refine(
    mesh: &HalfEdgeMesh,
    creases: &Creases,
    opts: Options,
    levels: u32,
) -> (Refiner, Vec<DVec3>) {
    let r = Refiner::new(mesh, creases, opts, levels).unwrap();
    let p = r.refine(&r.cage_positions(mesh));
    (r, p)
}

/// The point that maximises `score`.
fn extreme(points: &[DVec3], score: impl Fn(DVec3) -> f64) -> DVec3 {
    *points
        .iter()
        .max_by(|a, b| score(**a).total_cmp(&score(**b)))
        .unwrap()
}

fn corner(p: &[DVec3]) -> DVec3 {
    extreme(p, |q| q.x + q.y + q.z)
}
fn face_centre(p: &[DVec3]) -> DVec3 {
    extreme(p, |q| q.x - q.y.abs() - q.z.abs())
}
fn edge_middle(p: &[DVec3]) -> DVec3 {
    extreme(p, |q| q.x + q.y - q.z.abs())
}

fn close(a: DVec3, b: DVec3, tol: f64) -> bool {
    (a - b).length() < tol
}

#[test]
fn catmull_clark_cube_matches_the_masks_at_levels_1_2_3() {
    // (corner, face centre on +X, middle of the +X+Y edge): exact fractions.
    let expected = [
        (5.0 / 9.0, 1.0, 3.0 / 4.0),
        (55.0 / 108.0, 253.0 / 288.0, 247.0 / 384.0),
        (325.0 / 648.0, 3913.0 / 4608.0, 11389.0 / 18432.0),
    ];
    for (level, (c, f, e)) in (1..=3).zip(expected) {
        let (r, p) = refine(&cube(), &Creases::default(), Options::default(), level);
        assert_eq!(
            r.face_count(),
            6 * 4usize.pow(level),
            "F·4^k faces at level {level}"
        );
        assert_eq!(p.len(), r.vertex_count());
        assert!(
            close(corner(&p), DVec3::splat(c), 1e-12),
            "corner at level {level}: {}",
            corner(&p)
        );
        assert!(
            close(face_centre(&p), DVec3::new(f, 0.0, 0.0), 1e-12),
            "face point at level {level}"
        );
        assert!(
            close(edge_middle(&p), DVec3::new(e, e, 0.0), 1e-12),
            "edge point at level {level}"
        );
    }
}

#[test]
fn level_1_points_follow_the_face_edge_and_vertex_masks_by_hand() {
    let (_, p) = refine(&cube(), &Creases::default(), Options::default(), 1);
    // Face point: centroid of (1,±1,±1) = (1,0,0).
    assert!(
        p.iter()
            .any(|q| close(*q, DVec3::new(1.0, 0.0, 0.0), 1e-15))
    );
    // Edge point: (v0 + v1 + f0 + f1)/4 = ((1,1,1) + (1,1,-1) + (1,0,0) + (0,1,0))/4.
    assert!(
        p.iter()
            .any(|q| close(*q, DVec3::new(0.75, 0.75, 0.0), 1e-15))
    );
    // Vertex point, n = 3: v/3 + Σe/9 + Σf/9 = (5/9, 5/9, 5/9).
    assert!(p.iter().any(|q| close(*q, DVec3::splat(5.0 / 9.0), 1e-15)));
}

fn all_edges(mesh: &HalfEdgeMesh, sharpness: f64) -> Creases {
    let mut c = Creases::default();
    for e in mesh.edges() {
        c.set_edge(e, sharpness);
    }
    c
}

#[test]
fn a_cube_with_all_edges_infinitely_sharp_stays_a_cube() {
    let mesh = cube();
    let creases = all_edges(&mesh, INFINITE_SHARPNESS as f64);
    let (r, p) = refine(&mesh, &creases, Options::default(), 3);
    assert_eq!(r.face_count(), 384);
    for q in &p {
        let m = q.abs().max_element();
        assert!((m - 1.0).abs() < 1e-12, "{q} is off the cube");
    }
    assert!(close(corner(&p), DVec3::ONE, 1e-12));
    assert!(close(edge_middle(&p), DVec3::new(1.0, 1.0, 0.0), 1e-12));
}

#[test]
fn sharpness_one_on_one_edge_lies_between_smooth_and_sharp() {
    let mesh = cube();
    let e = mesh
        .find_edge(VertexId(0), VertexId(1))
        .or_else(|| mesh.edges().next())
        .unwrap();
    let [a, b] = mesh.edge_vertices(e);
    let mid = (mesh.position(a) + mesh.position(b)) / 2.0;
    let dir = mid.normalize();
    let at_edge = |creases: &Creases| {
        let (_, p) = refine(&mesh, creases, Options::default(), 3);
        extreme(&p, |q| q.dot(dir)).dot(dir)
    };
    let smooth = at_edge(&Creases::default());
    let mut one = Creases::default();
    one.set_edge(e, 1.0);
    let mut sharp = Creases::default();
    sharp.set_edge(e, INFINITE_SHARPNESS as f64);
    let (s1, sinf) = (at_edge(&one), at_edge(&sharp));
    assert!(smooth < s1 && s1 < sinf, "{smooth} < {s1} < {sinf}");
    // Even infinitely sharp, the crease is a curve between ends that are
    // smoothed (a dart vertex follows the smooth rule): inside the cage.
    assert!(sinf < mid.length());
}

#[test]
fn semi_sharp_half_blends_the_edge_point_halfway() {
    let mesh = cube();
    let e = mesh.edges().next().unwrap();
    let [a, b] = mesh.edge_vertices(e);
    let (pa, pb) = (mesh.position(a), mesh.position(b));
    let faces = mesh.edge_faces(e).map(|f| mesh.face_centroid(f.unwrap()));
    let smooth = (pa + pb + faces[0] + faces[1]) / 4.0;
    let sharp = (pa + pb) / 2.0;
    let mut creases = Creases::default();
    creases.set_edge(e, 0.5);
    let (_, p) = refine(&mesh, &creases, Options::default(), 1);
    let want = 0.5 * smooth + 0.5 * sharp;
    assert!(
        p.iter().any(|q| close(*q, want, 1e-14)),
        "no point at {want}"
    );
}

#[test]
fn a_corner_vertex_stays_put_and_fractional_corners_move_partly() {
    let mesh = cube();
    let v = mesh.vertices().next().unwrap();
    let pv = mesh.position(v);
    let mut creases = Creases::default();
    creases.set_vertex(v, INFINITE_SHARPNESS as f64);
    let (_, p) = refine(&mesh, &creases, Options::default(), 3);
    assert!(p.iter().any(|q| close(*q, pv, 1e-14)), "sharp corner moved");
    let mut half = Creases::default();
    half.set_vertex(v, 0.5);
    let (_, p) = refine(&mesh, &half, Options::default(), 1);
    // Level 1: ½ corner rule (v) + ½ smooth rule (5/9 of v).
    let want = pv * (0.5 + 0.5 * 5.0 / 9.0);
    assert!(
        p.iter().any(|q| close(*q, want, 1e-14)),
        "no point at {want}"
    );
}

#[test]
fn chaikin_creases_fade_differently_from_uniform_ones() {
    // Two crease edges of sharpness 3 and 1 meeting at a cube corner v.
    let mesh = cube();
    let mut edges = mesh.edges();
    let e0 = edges.next().unwrap();
    let [a, b] = mesh.edge_vertices(e0);
    let e1 = mesh
        .edges()
        .find(|&e| e != e0 && mesh.edge_vertices(e).contains(&a))
        .unwrap();
    assert!(!mesh.edge_vertices(e1).contains(&b));
    let mut creases = Creases::default();
    creases.set_edge(e0, 3.0);
    creases.set_edge(e1, 1.0);
    let chaikin_opts = Options {
        crease_method: CreaseMethod::Chaikin,
        ..Options::default()
    };
    // The sharpness of the child edges, worked out by hand from the rules
    // (OpenSubdiv's Sdc `Crease::SubdivideEdgeSharpnessesAroundVertex`):
    // uniform `s − 1`; Chaikin `¾ s + ¼ (mean of the other semi-sharp
    // edges at the end) − 1`, floored at 0.
    let sharp = |opts: Options, levels: u32| {
        let r = Refiner::new(&mesh, &creases, opts, levels).unwrap();
        let mut s: Vec<f32> = r.edges().map(|(_, s)| s).filter(|&s| s > 0.0).collect();
        s.sort_by(f32::total_cmp);
        s
    };
    // Level 1. Uniform: 3 → 2, 2; 1 → 0, 0. Chaikin: e0 at v ¾·3 + ¼·1 − 1
    // = 1.5, at its other end 3 − 1 = 2; e1 at v ¾·1 + ¼·3 − 1 = 0.5, at
    // its other end 0.
    assert_eq!(sharp(Options::default(), 1), vec![2.0, 2.0]);
    assert_eq!(sharp(chaikin_opts, 1), vec![0.5, 1.5, 2.0]);
    // Level 2. Uniform: 1 four times. Chaikin: the 1.5 edge at v (beside
    // 0.5) ¾·1.5 + ¼·0.5 − 1 = 0.25, at e0's middle (beside 2)
    // ¾·1.5 + ¼·2 − 1 = 0.625; the 2 edge there ¾·2 + ¼·1.5 − 1 = 0.875,
    // at its far end 1; the 0.5 edge fades to 0 at both ends.
    assert_eq!(sharp(Options::default(), 2), vec![1.0; 4]);
    assert_eq!(sharp(chaikin_opts, 2), vec![0.25, 0.625, 0.875, 1.0]);
    // And the surfaces differ (only the sharpness rule does).
    let uniform = refine(&mesh, &creases, Options::default(), 3).1;
    let chaikin = refine(&mesh, &creases, chaikin_opts, 3).1;
    assert_eq!(uniform.len(), chaikin.len());
    let moved = uniform
        .iter()
        .zip(&chaikin)
        .filter(|(a, b)| !close(**a, **b, 1e-12))
        .count();
    assert!(moved > 0, "Chaikin changed nothing");
}

#[test]
fn loop_icosahedron_matches_the_masks() {
    let mesh = icosahedron();
    let r0 = mesh.position(VertexId(0)).length();
    let (r, p) = refine(&mesh, &Creases::default(), options(Scheme::Loop), 1);
    assert_eq!(r.face_count(), 80);
    assert_eq!(p.len(), 12 + 30);
    // Vertex point, valence 5: (1 − 5β) v + β Σ neighbours, and the five
    // neighbours sum to √5·r·v̂ (adjacent vertices are at cos θ = 1/√5).
    let beta = (0.625 - (0.375 + 0.25 * (std::f64::consts::TAU / 5.0).cos()).powi(2)) / 5.0;
    let vertex_radius = r0 * ((1.0 - 5.0 * beta) + beta * 5f64.sqrt());
    let radii: Vec<f64> = p.iter().map(|q| q.length()).collect();
    assert_eq!(
        radii
            .iter()
            .filter(|&&x| (x - vertex_radius).abs() < 1e-12)
            .count(),
        12
    );
    // Edge point: 3/8 (a + b) + 1/8 (c + d).
    let e = mesh.edges().next().unwrap();
    let [a, b] = mesh.edge_vertices(e);
    let opposite: Vec<DVec3> = mesh
        .edge_faces(e)
        .iter()
        .map(|f| {
            let f = f.unwrap();
            let v = mesh.face_vertices(f).find(|v| *v != a && *v != b).unwrap();
            mesh.position(v)
        })
        .collect();
    let want = 0.375 * (mesh.position(a) + mesh.position(b)) + 0.125 * (opposite[0] + opposite[1]);
    assert!(p.iter().any(|q| close(*q, want, 1e-14)));
    for level in 2..=3 {
        let (r, _) = refine(&mesh, &Creases::default(), options(Scheme::Loop), level);
        assert_eq!(r.face_count(), 20 * 4usize.pow(level));
    }
}

#[test]
fn loop_refuses_a_quad_mesh_naming_the_face() {
    let err = Refiner::new(&cube(), &Creases::default(), options(Scheme::Loop), 1).unwrap_err();
    assert!(matches!(
        err,
        SubdivisionError::NotTriangles { sides: 4, .. }
    ));
    assert!(err.to_string().contains("has 4 sides"), "{err}");
}

#[test]
fn doo_sabin_cube_has_face_edge_and_vertex_faces() {
    let mesh = cube();
    let (mesh1, _) =
        Refiner::subdivide(&mesh, &Creases::default(), options(Scheme::DooSabin), 1).unwrap();
    mesh1.validate().unwrap();
    assert_eq!((mesh1.vertex_count(), mesh1.face_count()), (24, 6 + 12 + 8));
    assert!(mesh1.stats().closed);
    // Corner point of a quad: 9/16 v + 3/16 (two neighbours) + 1/16 opposite.
    let p: Vec<DVec3> = mesh1.vertices().map(|v| mesh1.position(v)).collect();
    assert!(
        p.iter()
            .any(|q| close(*q, DVec3::new(1.0, 0.5, 0.5), 1e-15))
    );
    let (mesh2, _) =
        Refiner::subdivide(&mesh, &Creases::default(), options(Scheme::DooSabin), 2).unwrap();
    mesh2.validate().unwrap();
    assert_eq!(mesh2.face_count(), 26 + 48 + 24);
}

#[test]
fn linear_splits_without_moving_the_surface() {
    let (mesh, _) =
        Refiner::subdivide(&cube(), &Creases::default(), options(Scheme::Linear), 2).unwrap();
    mesh.validate().unwrap();
    assert_eq!(mesh.face_count(), 96);
    assert!(
        mesh.vertices()
            .all(|v| (mesh.position(v).abs().max_element() - 1.0).abs() < 1e-15)
    );
    let (tris, _) = Refiner::subdivide(
        &icosahedron(),
        &Creases::default(),
        options(Scheme::Linear),
        1,
    )
    .unwrap();
    assert_eq!(tris.face_count(), 80);
    assert!(tris.faces().all(|f| tris.face_degree(f) == 3));
}

fn square() -> HalfEdgeMesh {
    Primitive::Plane { size: 2.0 }.build().unwrap()
}

#[test]
fn boundary_modes_round_keep_or_drop_the_corners() {
    let mesh = square();
    let corner_kept = |b: BoundaryInterpolation| {
        let opts = Options {
            boundary: b,
            ..Options::default()
        };
        let (r, p) = refine(&mesh, &Creases::default(), opts, 2);
        let shown = r.faces().count();
        let kept = mesh
            .vertices()
            .all(|v| p.iter().any(|q| close(*q, mesh.position(v), 1e-14)));
        (shown, kept)
    };
    assert_eq!(
        corner_kept(BoundaryInterpolation::EdgesAndCorners),
        (16, true)
    );
    assert_eq!(corner_kept(BoundaryInterpolation::EdgesOnly), (16, false));
    // Every face of a single quad touches the boundary: nothing is left.
    assert_eq!(corner_kept(BoundaryInterpolation::None).0, 0);
    // Edges only: the corner follows the crease rule (a + 6v + b)/8 at level 1.
    let (_, p) = refine(&mesh, &Creases::default(), Options::default(), 1);
    let v = mesh.vertices().next().unwrap();
    let n: Vec<DVec3> = mesh.vertex_neighbors(v).map(|u| mesh.position(u)).collect();
    let want = (n[0] + 6.0 * mesh.position(v) + n[1]) / 8.0;
    assert!(p.iter().any(|q| close(*q, want, 1e-14)));
}

#[test]
fn boundary_none_hides_only_faces_at_the_boundary() {
    let grid = Primitive::Grid {
        x_segments: 4,
        z_segments: 4,
        size: 2.0,
    }
    .build()
    .unwrap();
    let opts = Options {
        boundary: BoundaryInterpolation::None,
        ..Options::default()
    };
    let (r, _) = refine(&grid, &Creases::default(), opts, 1);
    // The 2×2 inner cage faces survive, four quads each.
    assert_eq!(r.faces().count(), 16);
    let (mesh, _) = Refiner::subdivide(&grid, &Creases::default(), opts, 1).unwrap();
    mesh.validate().unwrap();
    assert_eq!(mesh.face_count(), 16);
}

#[test]
fn limit_positions_do_not_depend_on_the_level() {
    for (mesh, scheme) in [
        (cube(), Scheme::CatmullClark),
        (icosahedron(), Scheme::Loop),
    ] {
        let (r1, p1) = refine(&mesh, &Creases::default(), options(scheme), 1);
        let (r3, p3) = refine(&mesh, &Creases::default(), options(scheme), 3);
        let l1 = limit_positions(&r1, &p1).unwrap();
        let l3 = limit_positions(&r3, &p3).unwrap();
        // Every limit point of level 1 is again a limit point at level 3.
        for q in &l1 {
            assert!(
                l3.iter().any(|x| close(*x, *q, 1e-12)),
                "{scheme:?}: {q} not at level 3"
            );
        }
    }
}

#[test]
fn cube_limit_normals_are_symmetric() {
    let (r, p) = refine(&cube(), &Creases::default(), Options::default(), 2);
    let l = limit_positions(&r, &p).unwrap();
    let n = limit_normals(&r, &p).unwrap();
    for (q, normal) in l.iter().zip(&n) {
        assert!((normal.length() - 1.0).abs() < 1e-12);
        assert!(normal.dot(*q) > 0.0, "normal at {q} points inward");
        // On a symmetry axis the normal is the axis itself.
        if q.y.abs() < 1e-12 && q.z.abs() < 1e-12 {
            assert!(close(*normal, DVec3::X * q.x.signum(), 1e-12), "{normal}");
        }
        if (q.x - q.y).abs() < 1e-12 && (q.y - q.z).abs() < 1e-12 {
            assert!(
                close(*normal, DVec3::ONE.normalize() * q.x.signum(), 1e-12),
                "{normal}"
            );
        }
    }
}

#[test]
fn limit_evaluation_is_refused_where_it_is_not_defined() {
    let (r, p) = refine(
        &Primitive::Cylinder {
            segments: 5,
            radius: 1.0,
            depth: 2.0,
        }
        .build()
        .unwrap(),
        &Creases::default(),
        Options::default(),
        0,
    );
    assert!(matches!(
        limit_positions(&r, &p),
        Err(SubdivisionError::NoLimit { .. })
    ));
    let (r, p) = refine(&cube(), &Creases::default(), options(Scheme::DooSabin), 1);
    assert!(matches!(
        limit_normals(&r, &p),
        Err(SubdivisionError::NoLimit { .. })
    ));
}

#[test]
fn snapping_the_cube_cage_puts_corners_on_the_limit() {
    let snapped = snap_to_limit(&cube(), &Creases::default(), Options::default()).unwrap();
    assert_eq!(snapped.len(), 8);
    // Cube corner limit, from the quad mask (n = 3): (9v + 4Σe + Σd)/24 with
    // Σe = (1,1,1) and Σd = (−1,−1,−1) at v = (1,1,1): 12/24 = 1/2 per axis
    // (the level 1–3 corners 5/9, 55/108, 325/648 approach it).
    for (_, q) in snapped {
        assert!(close(q.abs(), DVec3::splat(0.5), 1e-12), "{q}");
    }
}

#[test]
fn applied_results_are_valid_and_keep_the_remaining_creases() {
    let mesh = cube();
    let mut creases = all_edges(&mesh, 2.0);
    let v = mesh.vertices().next().unwrap();
    creases.set_vertex(v, INFINITE_SHARPNESS as f64);
    let (out, left) = Refiner::subdivide(&mesh, &creases, Options::default(), 1).unwrap();
    out.validate().unwrap();
    assert_eq!(out.face_count(), 24);
    // Every cage edge became two child edges of sharpness 1.
    assert_eq!(left.edges.len(), 24);
    assert!(left.edges.values().all(|&s| (s - 1.0).abs() < 1e-6));
    assert_eq!(left.vertices.len(), 1);
    // Applying once more with what is left equals refining twice.
    let (twice, _) = Refiner::subdivide(&out, &left, Options::default(), 1).unwrap();
    let (direct, p) = refine(&mesh, &creases, Options::default(), 2);
    assert_eq!(twice.vertex_count(), direct.vertex_count());
    for v in twice.vertices() {
        assert!(p.iter().any(|q| close(*q, twice.position(v), 1e-12)));
    }
}

#[test]
fn levels_that_are_too_large_are_refused_before_allocating() {
    let err = Refiner::new(&cube(), &Creases::default(), Options::default(), 11).unwrap_err();
    assert_eq!(err, SubdivisionError::LevelTooHigh { level: 11 });
    // 6 · 4^9 = 1.6 million faces at level 9 is allowed; a torus of 576
    // faces reaches the 20 million limit at level 8.
    let torus = Primitive::Torus {
        major_segments: 24,
        minor_segments: 24,
        major_radius: 1.0,
        minor_radius: 0.3,
    }
    .build()
    .unwrap();
    let err = Refiner::new(&torus, &Creases::default(), Options::default(), 8).unwrap_err();
    assert!(
        matches!(err, SubdivisionError::TooManyFaces { level: 8, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("more than the limit"), "{err}");
}

/// The refined mesh built the slow way: the shown faces through
/// `from_polygons`, vertices numbered in order of first use and isolated
/// ones after them (what `to_mesh` promises, ids included).
fn polygons_mesh(r: &Refiner, points: &[DVec3]) -> HalfEdgeMesh {
    let mut used = vec![u32::MAX; points.len()];
    let mut kept = Vec::new();
    let faces: Vec<Vec<u32>> = r
        .faces()
        .map(|f| {
            f.iter()
                .map(|&v| {
                    if used[v as usize] == u32::MAX {
                        used[v as usize] = kept.len() as u32;
                        kept.push(points[v as usize]);
                    }
                    used[v as usize]
                })
                .collect()
        })
        .collect();
    let mut in_edge = vec![false; points.len()];
    for ([a, b], _) in r.edges() {
        in_edge[a as usize] = true;
        in_edge[b as usize] = true;
    }
    for (v, p) in points.iter().enumerate() {
        if used[v] == u32::MAX && !in_edge[v] {
            kept.push(*p);
        }
    }
    HalfEdgeMesh::from_polygons(&kept, &faces).unwrap()
}

#[test]
fn applied_meshes_equal_the_polygon_build_with_holes_and_boundaries() {
    for (cage, scheme) in [
        (0, Scheme::CatmullClark),
        (1, Scheme::CatmullClark),
        (2, Scheme::CatmullClark),
        (3, Scheme::Loop),
        (3, Scheme::CatmullClark),
    ] {
        for boundary in BoundaryInterpolation::ALL {
            for hole in [None, Some(0), Some(2)] {
                let mesh = cages().swap_remove(cage);
                let mut creases = Creases::default();
                if let Some(i) = hole {
                    creases.set_hole(mesh.faces().nth(i).unwrap(), true);
                }
                let opts = Options {
                    scheme,
                    boundary,
                    ..Options::default()
                };
                let (r, p) = refine(&mesh, &creases, opts, 2);
                let (out, _) = r.to_mesh(&p).unwrap();
                out.validate().unwrap();
                assert_eq!(
                    out,
                    polygons_mesh(&r, &p),
                    "cage {cage} {scheme:?} {boundary:?} hole {hole:?}"
                );
                assert_eq!(out.face_count(), r.faces().count());
            }
        }
    }
}

fn cages() -> Vec<HalfEdgeMesh> {
    vec![
        cube(),
        Primitive::Cylinder {
            segments: 5,
            radius: 1.0,
            depth: 2.0,
        }
        .build()
        .unwrap(),
        Primitive::Grid {
            x_segments: 3,
            z_segments: 2,
            size: 2.0,
        }
        .build()
        .unwrap(),
        icosahedron(),
    ]
}

/// The creases and options the property tests draw: edge `i` gets
/// sharpness `sharp[i] - 2` where that is positive, and the boundary rule,
/// crease method and scheme drawn.
fn random_rules(
    mesh: &HalfEdgeMesh,
    sharp: &[f64],
    scheme: Scheme,
    boundary: usize,
    chaikin: bool,
) -> (Creases, Options) {
    let mut creases = Creases::default();
    for (e, s) in mesh.edges().zip(sharp) {
        if *s > 2.0 {
            creases.set_edge(e, s - 2.0);
        }
    }
    let opts = Options {
        scheme,
        boundary: BoundaryInterpolation::ALL[boundary],
        crease_method: if chaikin {
            CreaseMethod::Chaikin
        } else {
            CreaseMethod::Uniform
        },
        smooth_triangles: scheme == Scheme::CatmullClark && boundary == 1,
    };
    (creases, opts)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The stencil table (weights recorded once) gives what the direct
    /// masks give, for every scheme, boundary rule and random creases; and
    /// every applied result validates.
    #[test]
    fn stencils_equal_direct_refinement(
        cage in 0usize..4,
        scheme in 0usize..4,
        boundary in 0usize..3,
        chaikin in any::<bool>(),
        levels in 0u32..3,
        sharp in proptest::collection::vec(0.0f64..4.0, 40),
        wiggle in proptest::collection::vec(-0.2f64..0.2, 60),
    ) {
        let mut mesh = cages().swap_remove(cage);
        let scheme = Scheme::ALL[scheme];
        prop_assume!(scheme != Scheme::Loop || cage == 3);
        for (i, v) in mesh.vertices().collect::<Vec<_>>().into_iter().enumerate() {
            let p = mesh.position(v) + DVec3::splat(wiggle[i % wiggle.len()]);
            mesh.set_position(v, p);
        }
        let (creases, opts) = random_rules(&mesh, &sharp, scheme, boundary, chaikin);
        let r = Refiner::new(&mesh, &creases, opts, levels).unwrap();
        let cage_points = r.cage_positions(&mesh);
        let direct = r.refine(&cage_points);
        let stencil = r.stencils().apply(&cage_points);
        let parallel = r.refine_parallel(&cage_points);
        let serial = r.refine_serial(&cage_points);
        prop_assert_eq!(direct.len(), stencil.len());
        prop_assert_eq!(&r.stencils().apply_parallel(&cage_points), &stencil);
        for ((a, b), (c, d)) in direct.iter().zip(&stencil).zip(parallel.iter().zip(&serial)) {
            prop_assert!(close(*a, *b, 1e-12), "{} vs {}", a, b);
            prop_assert_eq!(a, c);
            prop_assert_eq!(a, d);
        }
        let (out, _) = r.to_mesh(&direct).unwrap();
        prop_assert!(out.validate().is_ok());
        prop_assert!(out == polygons_mesh(&r, &direct), "to_mesh differs from from_polygons");

        // A drag: move some cage vertices and update incrementally; the
        // result equals refining the moved cage from scratch.
        let table = r.stencils();
        let mut eval = table.evaluate(&cage_points);
        let mut moved_cage = cage_points.clone();
        let moved: Vec<(u32, DVec3)> = (0..cage_points.len())
            .step_by(3)
            .map(|i| (i as u32, cage_points[i] + DVec3::new(0.3, -0.1, wiggle[i % wiggle.len()])))
            .collect();
        for &(i, p) in &moved {
            moved_cage[i as usize] = p;
        }
        table.update(&mut eval, &moved);
        let fresh = r.refine(&moved_cage);
        for (a, b) in eval.points().iter().zip(&fresh) {
            prop_assert!(close(*a, *b, 1e-12), "incremental {} vs fresh {}", a, b);
        }
    }
}

#[test]
fn loop_boundary_and_crease_rules_follow_the_cubic_b_spline_masks() {
    // A fan of four triangles around a centre vertex, open at the rim.
    let positions = [
        DVec3::ZERO,
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, -1.0),
        DVec3::new(-1.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
    ];
    let polys = [[0u32, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]];
    let mesh = HalfEdgeMesh::from_polygons(&positions, &polys).unwrap();
    let opts = options(Scheme::Loop);
    let (_, p) = refine(&mesh, &Creases::default(), opts, 1);
    // Boundary edge (1,2): its midpoint.
    assert!(
        p.iter()
            .any(|q| close(*q, DVec3::new(0.5, 0.0, -0.5), 1e-15))
    );
    // Boundary vertex 1, neighbours 2 and 4 on the rim: (a + 6v + b) / 8.
    let want = (positions[2] + 6.0 * positions[1] + positions[4]) / 8.0;
    assert!(p.iter().any(|q| close(*q, want, 1e-15)));
    // Interior edge (0,1) creased: its midpoint instead of 3/8, 3/8, 1/8, 1/8.
    let mut creases = Creases::default();
    creases.set_edge(
        mesh.find_edge(VertexId(0), VertexId(1)).unwrap(),
        INFINITE_SHARPNESS as f64,
    );
    let (_, p) = refine(&mesh, &creases, opts, 1);
    assert!(
        p.iter()
            .any(|q| close(*q, DVec3::new(0.5, 0.0, 0.0), 1e-15))
    );
    // Edges and corners: the rim vertices stay put.
    let corners = Options {
        boundary: BoundaryInterpolation::EdgesAndCorners,
        ..opts
    };
    let (_, p) = refine(&mesh, &Creases::default(), corners, 2);
    // (Every rim vertex touches two faces, so none is a corner here.)
    assert!(!p.iter().any(|q| close(*q, positions[1], 1e-15)));
}

/// Issue 37: a fin, three quads on one edge (which a half-edge mesh cannot
/// hold), refined as polygons kept as they are. OpenSubdiv's rules: the
/// edge in three faces is infinitely sharp, so its edge point is its
/// midpoint; its ends are non-manifold with boundary edges, so they are
/// corners and stay put; the face points are the quads' centroids.
#[test]
fn a_fin_of_three_quads_on_one_edge_refines_with_a_sharp_spine() {
    use hedra_geom::subdivision::{Options, Refiner, Scheme, SubdivisionError};
    let positions = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 1.0),
        DVec3::new(-0.5, 1.0, 0.0),
        DVec3::new(-0.5, 1.0, 1.0),
        DVec3::new(-0.5, -1.0, 0.0),
        DVec3::new(-0.5, -1.0, 1.0),
    ];
    // The spine is 0–1; each blade goes out from it.
    let faces = vec![vec![0, 2, 3, 1], vec![1, 5, 4, 0], vec![0, 6, 7, 1]];
    let r = Refiner::from_polygons(8, &faces, Options::default(), 1).unwrap();
    let points = r.refine(&positions);
    // 3 face points, 10 edge points (the spine once), 8 vertex points.
    assert_eq!(points.len(), 21);
    assert_eq!(r.face_count(), 12);
    let near = |p: DVec3| points.iter().any(|q| q.distance(p) < 1e-12);
    assert!(
        near(DVec3::new(0.0, 0.0, 0.5)),
        "the spine's edge point is its midpoint"
    );
    assert!(
        near(DVec3::new(0.0, 0.0, 0.0)) && near(DVec3::new(0.0, 0.0, 1.0)),
        "its ends stay"
    );
    assert!(
        near(DVec3::new(0.5, 0.0, 0.5)),
        "a face point is its quad's centroid"
    );
    // A level 2 refines the level 1 as it is, spine and all.
    let r2 = Refiner::from_polygons(8, &faces, Options::default(), 2).unwrap();
    let points2 = r2.refine(&positions);
    assert!(
        points2
            .iter()
            .any(|q| q.distance(DVec3::new(0.0, 0.0, 0.25)) < 1e-12)
    );
    // Loop takes triangles only; indices must name vertices.
    let looped = Options {
        scheme: Scheme::Loop,
        ..Options::default()
    };
    assert!(matches!(
        Refiner::from_polygons(8, &faces, looped, 1),
        Err(SubdivisionError::NotTriangles { sides: 4, .. })
    ));
    let err = Refiner::from_polygons(3, &faces, Options::default(), 1).unwrap_err();
    assert_eq!(
        err.to_string(),
        "face f0 is not a polygon of the cage: vertex 3 is not one of the 3 vertices"
    );
}

/// A refinement large enough to take both cores (levels of
/// `PARALLEL_POINTS` points or more) gives the serial path's bits, and so
/// does the stencil table's apply (issue 36, item 4).
#[test]
fn refining_on_all_cores_by_size_gives_the_serial_bits() {
    use hedra_geom::subdivision::PARALLEL_POINTS;
    let torus = Primitive::Torus {
        major_segments: 100,
        minor_segments: 100,
        major_radius: 2.0,
        minor_radius: 0.5,
    }
    .build()
    .unwrap();
    let mut creases = Creases::default();
    let e = torus.edges().nth(7).unwrap();
    creases.set_edge(e, 1.5);
    let r = Refiner::new(&torus, &creases, Options::default(), 3).unwrap();
    let cage = r.cage_positions(&torus);
    let serial = r.refine_serial(&cage);
    assert!(
        serial.len() > PARALLEL_POINTS,
        "the last level is refined on all cores"
    );
    assert!(r.refine(&cage) == serial, "by size");
    assert!(
        r.refine_parallel(&cage) == serial,
        "every level on all cores"
    );
    let table = r.stencils();
    let applied = table.apply_serial(&cage);
    assert!(table.apply(&cage) == applied, "stencils by size");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Whole pieces (closed and open, each oriented) glued at single
    /// vertices meet there in separate fans (bow-ties), and nowhere else.
    /// The polygon analysis that the refinement from a face list runs
    /// walks the fans around each vertex when every edge is manifold; it
    /// must name exactly the glued vertices, and the half-edge builder
    /// (independent code: it pairs half-edges) must refuse exactly when it
    /// names one.
    #[test]
    fn glued_pieces_are_split_exactly_at_the_glued_vertices(
        picks in proptest::collection::vec((0usize..4, any::<prop::sample::Index>()), 2..5),
        glue in proptest::collection::vec(
            (any::<prop::sample::Index>(), any::<prop::sample::Index>()), 0..3),
    ) {
        use hedra_geom::subdivision::non_manifold_places;
        let cages = cages();
        // The pieces side by side, each one's vertices numbered after the last's.
        let mut faces: Vec<Vec<u32>> = Vec::new();
        let mut starts = Vec::new();
        let mut count = 0u32;
        for &(kind, _) in &picks {
            let mesh = &cages[kind];
            starts.push((count, mesh.vertex_count() as u32));
            for f in mesh.faces() {
                faces.push(mesh.face_vertices(f).map(|v| count + v.0).collect());
            }
            count += mesh.vertex_count() as u32;
        }
        // Glue `p` joins a vertex of piece `p` to a vertex of piece `p + 1`,
        // renaming the second into the first (one glue per pair: two would
        // share the edge between them when their vertices are neighbours).
        let mut rename: Vec<u32> = (0..count).collect();
        let mut glued = std::collections::BTreeSet::new();
        for (p, (a, b)) in glue.iter().enumerate().take(picks.len() - 1) {
            let (sa, na) = starts[p];
            let (sb, nb) = starts[p + 1];
            let (va, vb) = (sa + a.index(na as usize) as u32, sb + b.index(nb as usize) as u32);
            // A vertex glued twice would join three pieces or two of its
            // own: keep each glue to fresh vertices.
            if rename[va as usize] != va || rename[vb as usize] != vb || glued.contains(&va) {
                continue;
            }
            rename[vb as usize] = va;
            glued.insert(va);
        }
        for face in &mut faces {
            for v in face.iter_mut() {
                *v = rename[*v as usize];
            }
        }
        let places = non_manifold_places(count as usize, &faces).unwrap();
        let named: std::collections::BTreeSet<u32> = places.split_vertices.iter().copied().collect();
        prop_assert_eq!(&named, &glued);
        prop_assert!(places.crowded_edges.is_empty() && places.same_way_edges.is_empty());
        let positions = vec![DVec3::ZERO; count as usize];
        prop_assert_eq!(HalfEdgeMesh::from_polygons(&positions, &faces).is_ok(), glued.is_empty());
    }
}

/// `Refiner::vertex_edge_count` counts a refined vertex's edges from the
/// level before; it must equal the count of the refined edges themselves,
/// for every scheme, with boundaries and creases, and on a cage with an
/// edge in three faces (counted on the last level then).
#[test]
fn refined_vertex_edge_counts_equal_the_refined_edges() {
    let crowded = Refiner::from_polygons(
        5,
        &[vec![0, 1, 2], vec![1, 0, 3], vec![0, 1, 4]],
        options(Scheme::CatmullClark),
        2,
    )
    .unwrap();
    let fan_positions: Vec<DVec3> = (0..5)
        .map(|i| DVec3::new(f64::from(i).cos(), f64::from(i).sin(), 0.0))
        .chain([DVec3::ZERO])
        .collect();
    let fan = HalfEdgeMesh::from_polygons(
        &fan_positions,
        &[[5, 0, 1], [5, 1, 2], [5, 2, 3], [5, 3, 4]],
    )
    .unwrap();
    let mut refiners = vec![("crowded", crowded)];
    for (name, mesh) in cages().into_iter().enumerate() {
        for scheme in [Scheme::CatmullClark, Scheme::Linear, Scheme::DooSabin] {
            for levels in [1, 2] {
                let creases = all_edges(&mesh, 1.5);
                let r = Refiner::new(&mesh, &creases, options(scheme), levels).unwrap();
                refiners.push((["cube", "cylinder", "grid", "icosahedron"][name], r));
            }
        }
    }
    for mesh in [icosahedron(), fan] {
        for scheme in [Scheme::Loop, Scheme::Linear] {
            let r = Refiner::new(&mesh, &Creases::default(), options(scheme), 2).unwrap();
            refiners.push(("triangles", r));
        }
    }
    for (name, r) in refiners {
        let mut counted = vec![0usize; r.vertex_count()];
        for ([a, b], _) in r.edges() {
            counted[a as usize] += 1;
            counted[b as usize] += 1;
        }
        for (v, &n) in counted.iter().enumerate() {
            assert_eq!(
                r.vertex_edge_count(v as u32),
                n,
                "{name}, {:?}, vertex {v}",
                r.options().scheme
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Refined points kept level by level and updated after a few cage
    /// vertices move are the same bits as refining the moved cage anew,
    /// for every scheme, boundary rule, crease method and random creases
    /// (infinitely sharp ones too); the points reported as recomputed hold
    /// every point that changed. Three drags in a row, so updates of
    /// updated points are checked as well.
    #[test]
    fn kept_levels_updated_after_moves_equal_a_fresh_refinement(
        cage in 0usize..8,
        scheme in 0usize..4,
        boundary in 0usize..3,
        chaikin in any::<bool>(),
        levels in 0u32..4,
        sharp in proptest::collection::vec(0.0f64..13.0, 40),
        drags in proptest::collection::vec(
            proptest::collection::vec((any::<prop::sample::Index>(), -0.5f64..0.5), 1..4), 3),
    ) {
        // The small cages reach most of each level (computed whole); the
        // larger ones leave most of it, so the point-by-point path runs.
        let mut all = cages();
        all.extend([
            Primitive::Grid { x_segments: 12, z_segments: 10, size: 2.0 },
            Primitive::Torus { major_segments: 12, minor_segments: 10, major_radius: 2.0, minor_radius: 0.5 },
            Primitive::Cylinder { segments: 24, radius: 1.0, depth: 2.0 },
            Primitive::IcoSphere { subdivisions: 2, radius: 1.0 },
        ].map(|p| p.build().unwrap()));
        let mesh = all.swap_remove(cage);
        let scheme = Scheme::ALL[scheme];
        prop_assume!(scheme != Scheme::Loop || cage == 3 || cage == 7);
        let (creases, opts) = random_rules(&mesh, &sharp, scheme, boundary, chaikin);
        let r = Refiner::new(&mesh, &creases, opts, levels).unwrap();
        let mut cage_points = r.cage_positions(&mesh);
        let mut kept = r.refine_kept(&cage_points);
        prop_assert_eq!(kept.points(), &r.refine(&cage_points)[..]);
        for drag in drags {
            let before = kept.points().to_vec();
            let moved: Vec<(u32, DVec3)> = drag
                .iter()
                .map(|(i, d)| {
                    let v = i.index(cage_points.len());
                    (v as u32, cage_points[v] + DVec3::new(*d, -0.5 * d, 0.25))
                })
                .collect();
            for &(v, p) in &moved {
                cage_points[v as usize] = p;
            }
            let recomputed = r.update_kept(&mut kept, &moved);
            let fresh = r.refine(&cage_points);
            prop_assert_eq!(kept.cage(), &cage_points[..]);
            prop_assert_eq!(kept.points(), &fresh[..]);
            if let Some(recomputed) = recomputed {
                prop_assert!(recomputed.windows(2).all(|w| w[0] < w[1]));
                for (i, (a, b)) in before.iter().zip(&fresh).enumerate() {
                    if a != b {
                        prop_assert!(recomputed.binary_search(&(i as u32)).is_ok(),
                            "point {} changed but was not reported", i);
                    }
                }
            }
        }
    }
}

/// On a large cage one moved vertex recomputes a few dozen refined points,
/// not the level: the update reports them, and they are the points that
/// changed (a grid of 10,000 quads, level 2, 160,000 faces).
#[test]
fn one_moved_vertex_of_a_large_cage_recomputes_only_its_neighbourhood() {
    let mesh = Primitive::Grid {
        x_segments: 100,
        z_segments: 100,
        size: 10.0,
    }
    .build()
    .unwrap();
    let r = Refiner::new(&mesh, &Creases::default(), options(Scheme::CatmullClark), 2).unwrap();
    let mut cage = r.cage_positions(&mesh);
    let mut kept = r.refine_kept(&cage);
    let before = kept.points().to_vec();
    // Row 50, column 50 of the 101 × 101 vertices: inside.
    let v = 50 * 101 + 50;
    cage[v] += DVec3::Y;
    let recomputed = r.update_kept(&mut kept, &[(v as u32, cage[v])]).unwrap();
    assert_eq!(kept.points(), &r.refine(&cage)[..]);
    let changed = before
        .iter()
        .zip(kept.points())
        .filter(|(a, b)| a != b)
        .count();
    // Level 1: the 2 × 2 faces at the vertex give 5 × 5 points, each of
    // which moves; level 2: the 6 × 6 faces at those give 36 face points,
    // 84 edge points and 49 vertex points, each of which moves too.
    assert_eq!(recomputed.len(), 36 + 84 + 49);
    assert_eq!(changed, recomputed.len());
}
