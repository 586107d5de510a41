//! Subdivision's cage tags and options beyond creases: face holes, isolated
//! vertices, OpenSubdiv's hidden-face rule for boundary `None`, smooth
//! triangles and which options each scheme honours. OpenSubdiv's own
//! regression shapes check the same against OpenSubdiv (`osd_shapes.rs`).

use hedra_geom::subdivision::{
    BoundaryInterpolation, Creases, INFINITE_SHARPNESS, Options, Refiner, Scheme,
};
use hedra_geom::{DVec3, FaceId, HalfEdgeMesh, Primitive};

fn grid(n: u32) -> HalfEdgeMesh {
    Primitive::Grid {
        x_segments: n,
        z_segments: n,
        size: 2.0,
    }
    .build()
    .unwrap()
}

fn none() -> Options {
    Options {
        boundary: BoundaryInterpolation::None,
        ..Options::default()
    }
}

#[test]
fn a_hole_leaves_no_faces_and_does_not_move_its_neighbours() {
    let mesh = grid(4);
    let hole = mesh.faces().nth(5).unwrap();
    let mut creases = Creases::default();
    creases.set_hole(hole, true);
    let plain = Refiner::new(&mesh, &Creases::default(), Options::default(), 2).unwrap();
    let holed = Refiner::new(&mesh, &creases, Options::default(), 2).unwrap();
    // Same points (the hole is refined like any face), 16 faces fewer shown.
    assert_eq!(
        plain.refine(&plain.cage_positions(&mesh)),
        holed.refine(&holed.cage_positions(&mesh))
    );
    assert_eq!(plain.faces().count(), 16 * 16);
    assert_eq!(holed.faces().count(), 16 * 16 - 16);
    assert_eq!(holed.face_origins().filter(|&f| f == hole).count(), 0);
    assert!(holed.is_cage_face_hidden(hole));
    assert_eq!(
        (0..holed.face_count())
            .filter(|&f| holed.is_face_hidden(f))
            .count(),
        16
    );
    let (result, tags) = Refiner::subdivide(&mesh, &creases, Options::default(), 2).unwrap();
    result.validate().unwrap();
    assert_eq!(result.face_count(), 240);
    assert!(tags.holes.is_empty());
    // Clearing the hole gives the plain result back.
    creases.set_hole(hole, false);
    assert!(creases.is_empty());
}

#[test]
fn holes_of_faces_that_are_gone_are_dropped() {
    let mut mesh = grid(2);
    let mut creases = Creases::default();
    creases.set_hole(FaceId(3), true);
    creases.set_hole(FaceId(99), true);
    creases.retain_live(&mesh);
    assert_eq!(creases.holes.len(), 1);
    mesh = grid(1);
    creases.retain_live(&mesh);
    assert!(creases.holes.is_empty());
}

#[test]
fn isolated_vertices_stay_put_at_every_level() {
    let mut positions: Vec<DVec3> = Primitive::Cube { size: 2.0 }
        .build()
        .unwrap()
        .vertices()
        .map(|v| Primitive::Cube { size: 2.0 }.build().unwrap().position(v))
        .collect();
    let cube = Primitive::Cube { size: 2.0 }.build().unwrap();
    let faces: Vec<Vec<u32>> = cube
        .faces()
        .map(|f| cube.face_vertices(f).map(|v| v.0).collect())
        .collect();
    let lone = DVec3::new(5.0, 6.0, 7.0);
    positions.push(lone);
    let mesh = HalfEdgeMesh::from_polygons(&positions, &faces).unwrap();
    assert_eq!(mesh.vertex_count(), 9);
    for levels in 1..=3 {
        let r = Refiner::new(&mesh, &Creases::default(), Options::default(), levels).unwrap();
        let p = r.refine(&r.cage_positions(&mesh));
        // 6·4^L faces: F + E + V of the previous level, plus the lone vertex.
        assert_eq!(p.len(), [0, 27, 99, 387][levels as usize]);
        assert_eq!(p.iter().filter(|&&q| q == lone).count(), 1);
        assert!(p.iter().all(|q| q.is_finite()));
        let (smooth, _) =
            Refiner::subdivide(&mesh, &Creases::default(), Options::default(), levels).unwrap();
        smooth.validate().unwrap();
        assert_eq!(smooth.vertex_count(), p.len());
        assert!(smooth.vertices().any(|v| smooth.position(v) == lone));
    }
}

#[test]
fn boundary_none_keeps_faces_whose_boundary_edges_are_infinitely_sharp() {
    // A 4×4 grid: with boundary None only the 2×2 inner faces show, unless
    // the user made boundary edges infinitely sharp. Sharpening every
    // boundary edge keeps all 16; sharpening them only along the first row
    // keeps the row above the inner faces too, except at the row's ends,
    // whose corner vertices still have a soft boundary edge on the side.
    let mesh = grid(4);
    let shown = |creases: &Creases| {
        let r = Refiner::new(&mesh, creases, none(), 1).unwrap();
        r.faces().count() / 4
    };
    assert_eq!(shown(&Creases::default()), 4);
    let mut all = Creases::default();
    for e in mesh.edges().filter(|&e| mesh.is_boundary_edge(e)) {
        all.set_edge(e, INFINITE_SHARPNESS as f64);
    }
    assert_eq!(shown(&all), 16);
    // Semi-sharp is not enough.
    let mut semi = Creases::default();
    for e in mesh.edges().filter(|&e| mesh.is_boundary_edge(e)) {
        semi.set_edge(e, 3.0);
    }
    assert_eq!(shown(&semi), 4);
    // One side: boundary edges whose both ends have the lowest z.
    let zmin = mesh
        .vertices()
        .map(|v| mesh.position(v).z)
        .fold(f64::INFINITY, f64::min);
    let mut side = Creases::default();
    for e in mesh.edges().filter(|&e| mesh.is_boundary_edge(e)) {
        if mesh
            .edge_vertices(e)
            .iter()
            .all(|&v| mesh.position(v).z == zmin)
        {
            side.set_edge(e, INFINITE_SHARPNESS as f64);
        }
    }
    // The row along that side: its 2 middle faces join the 4 inner ones.
    assert_eq!(shown(&side), 6);
}

#[test]
fn smooth_triangles_change_only_edge_points_beside_triangles() {
    // A quad with a triangle on one side and a quad on the other, closed up
    // into a mesh by the grid's other faces: compare with and without.
    let positions = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 1.0, 0.3),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(2.0, 0.5, 0.5),
        DVec3::new(-1.0, 0.0, 0.2),
        DVec3::new(-1.0, 1.0, 0.0),
    ];
    let faces = vec![vec![0, 1, 2, 3], vec![1, 4, 2], vec![5, 0, 3, 6]];
    let mesh = HalfEdgeMesh::from_polygons(&positions, &faces).unwrap();
    let smooth = Options {
        smooth_triangles: true,
        ..Options::default()
    };
    let a = Refiner::new(&mesh, &Creases::default(), Options::default(), 1).unwrap();
    let b = Refiner::new(&mesh, &Creases::default(), smooth, 1).unwrap();
    let pa = a.refine(&a.cage_positions(&mesh));
    let pb = b.refine(&b.cage_positions(&mesh));
    let changed: Vec<usize> = (0..pa.len()).filter(|&i| pa[i] != pb[i]).collect();
    // Only the edge point of the one interior edge beside the triangle (1–2).
    assert_eq!(changed.len(), 1);
    let p = |i: usize| positions[i];
    let quad = (p(0) + p(1) + p(2) + p(3)) / 4.0;
    let tri = (p(1) + p(4) + p(2)) / 3.0;
    // f = (0.47 + 0.25) / 2 = 0.36 per face point, (1 − 2f) / 2 = 0.14 per end.
    let want = 0.14 * (p(1) + p(2)) + 0.36 * (quad + tri);
    assert!((pb[changed[0]] - want).length() < 1e-12);
    let plain = 0.25 * (p(1) + p(2) + quad + tri);
    assert!((pa[changed[0]] - plain).length() < 1e-12);
}

#[test]
fn each_scheme_says_which_options_it_honours() {
    let cc = Scheme::CatmullClark.applicable();
    assert!(cc.creases && cc.boundary && cc.smooth_triangles && cc.holes);
    assert!(cc.reason.is_empty());
    let lp = Scheme::Loop.applicable();
    assert!(lp.creases && lp.boundary && !lp.smooth_triangles);
    for s in [Scheme::DooSabin, Scheme::Linear] {
        let a = s.applicable();
        assert!(!a.creases && !a.boundary && !a.smooth_triangles && a.holes);
        assert!(!a.reason.is_empty());
    }
}

#[test]
fn doo_sabin_ignores_creases_and_the_boundary_rule() {
    let mesh = grid(3);
    let mut creases = Creases::default();
    for e in mesh.edges() {
        creases.set_edge(e, 2.0);
    }
    let base = Options {
        scheme: Scheme::DooSabin,
        ..Options::default()
    };
    let r0 = Refiner::new(&mesh, &Creases::default(), base, 2).unwrap();
    let p0 = r0.refine(&r0.cage_positions(&mesh));
    for boundary in BoundaryInterpolation::ALL {
        let opts = Options { boundary, ..base };
        let r = Refiner::new(&mesh, &creases, opts, 2).unwrap();
        assert_eq!(r.refine(&r.cage_positions(&mesh)), p0);
        assert_eq!(r.faces().count(), r0.faces().count());
    }
}

/// A 6 × 6 grid in the xz plane with the middle row (z = 0) raised to
/// y = 1, and that row's edges in order from x = −1 to x = 1.
fn ridge() -> (HalfEdgeMesh, Vec<hedra_geom::EdgeId>, hedra_geom::VertexId) {
    let mut mesh = grid(6);
    for v in mesh.vertices().collect::<Vec<_>>() {
        let p = mesh.position(v);
        if p.z.abs() < 1e-9 {
            mesh.set_position(v, DVec3::new(p.x, 1.0, p.z));
        }
    }
    let on_row = |v| mesh.position(v).z.abs() < 1e-9;
    let mut chain: Vec<_> = mesh
        .edges()
        .filter(|&e| mesh.edge_vertices(e).iter().all(|&v| on_row(v)))
        .collect();
    let mid_x = |e| {
        let [a, b] = mesh.edge_vertices(e);
        mesh.position(a).x + mesh.position(b).x
    };
    chain.sort_by(|&a, &b| mid_x(a).total_cmp(&mid_x(b)));
    let start = mesh
        .vertices()
        .find(|&v| on_row(v) && mesh.position(v).x < -0.99)
        .unwrap();
    (mesh, chain, start)
}

fn refined(mesh: &HalfEdgeMesh, creases: &Creases) -> Vec<DVec3> {
    let r = Refiner::new(mesh, creases, Options::default(), 3).unwrap();
    r.refine(&r.cage_positions(mesh))
}

#[test]
fn a_constant_taper_is_the_constant_crease() {
    let (mesh, chain, start) = ridge();
    assert_eq!(chain.len(), 6);
    let mut taper = Creases::default();
    taper.set_taper(&mesh, &chain, start, 2.5, 2.5).unwrap();
    let mut plain = Creases::default();
    for &e in &chain {
        plain.set_edge(e, 2.5);
    }
    assert_eq!(taper.edge_sharpness(), plain.edges);
    assert_eq!(refined(&mesh, &taper), refined(&mesh, &plain));
    // Reversed order and the other end give the same chain.
    let mut reversed: Vec<_> = chain.clone();
    reversed.reverse();
    let end = mesh
        .vertices()
        .find(|&v| mesh.position(v).z.abs() < 1e-9 && mesh.position(v).x > 0.99)
        .unwrap();
    let mut other = Creases::default();
    other.set_taper(&mesh, &reversed, end, 2.5, 2.5).unwrap();
    assert_eq!(refined(&mesh, &other), refined(&mesh, &plain));
}

#[test]
fn a_taper_from_0_to_4_blends_monotonically_from_smooth_to_sharp() {
    let (mesh, chain, start) = ridge();
    let mut taper = Creases::default();
    taper.set_taper(&mesh, &chain, start, 0.0, 4.0).unwrap();
    // Midpoints at 1/12, 3/12, … 11/12 of the way: 1/3, 1, … 11/3.
    let s: Vec<f64> = chain.iter().map(|&e| taper.edge(e)).collect();
    for (i, v) in s.iter().enumerate() {
        assert!((v - 4.0 * (2 * i + 1) as f64 / 12.0).abs() < 1e-12, "{s:?}");
    }
    let mut sharp = Creases::default();
    for &e in &chain {
        sharp.set_edge(e, 4.0);
    }
    let (p_smooth, p_sharp, p_taper) = (
        refined(&mesh, &Creases::default()),
        refined(&mesh, &sharp),
        refined(&mesh, &taper),
    );
    // The refined points on the ridge line (z = 0), inside the boundary.
    let mut ridge: Vec<usize> = (0..p_smooth.len())
        .filter(|&i| p_smooth[i].z.abs() < 1e-9 && p_smooth[i].x.abs() < 0.99)
        .collect();
    ridge.sort_by(|&a, &b| p_smooth[a].x.total_cmp(&p_smooth[b].x));
    assert!(ridge.len() > 20);
    let blend: Vec<f64> = ridge
        .iter()
        .map(|&i| (p_taper[i].y - p_smooth[i].y) / (p_sharp[i].y - p_smooth[i].y))
        .collect();
    for w in blend.windows(2) {
        assert!(w[1] >= w[0] - 1e-9, "not monotone: {blend:?}");
    }
    assert!(
        blend.iter().all(|&b| (-1e-9..=1.0 + 1e-9).contains(&b)),
        "{blend:?}"
    );
    // Near the start it is nearly smooth, near the end sharp.
    assert!(blend[0] < 0.5 && *blend.last().unwrap() > 0.99, "{blend:?}");
}

#[test]
fn a_taper_needs_one_chain_from_an_end() {
    use hedra_geom::subdivision::TaperError;
    let (mesh, chain, start) = ridge();
    let mut c = Creases::default();
    let middle = mesh.edge_vertices(chain[2])[0];
    assert_eq!(
        c.set_taper(&mesh, &chain, middle, 0.0, 4.0),
        Err(TaperError::NotAnEnd { vertex: middle })
    );
    let gapped = [chain[0], chain[2]];
    assert!(matches!(
        c.set_taper(&mesh, &gapped, start, 0.0, 4.0),
        Err(TaperError::NotAChain { .. })
    ));
    assert_eq!(
        c.set_taper(&mesh, &[], start, 0.0, 4.0),
        Err(TaperError::NoEdges)
    );
    assert_eq!(
        c.set_taper(&mesh, &chain, start, -1.0, 4.0),
        Err(TaperError::BadSharpness(-1.0))
    );
    assert!(c.is_empty());
    // A plain crease on one edge takes it out of the taper.
    c.set_taper(&mesh, &chain, start, 0.0, 4.0).unwrap();
    c.set_edge(chain[5], 10.0);
    assert_eq!(c.tapers[0].edges.len(), 5);
    assert_eq!(c.edge(chain[5]), 10.0);
    c.clear_taper(&chain);
    assert!(c.tapers.is_empty());
}
