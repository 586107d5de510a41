//! The examples in docs/commands.md run, in order, as one script.

mod common;

use std::path::Path;

#[test]
fn every_command_example_in_the_docs_runs() {
    let blocks = common::commands_md_blocks();
    assert!(blocks.len() >= 15, "found only {} examples", blocks.len());
    let script = format!("[\n{}\n]", blocks.join(",\n"));
    let commands = hedra_doc::script::parse(&script, Path::new("docs/commands.md"))
        .unwrap_or_else(|e| panic!("{e}"));
    // Every command variant has an example.
    let mut kinds: Vec<String> = commands
        .iter()
        .map(|c| {
            format!("{c:?}")
                .split([' ', '{', '('])
                .next()
                .unwrap()
                .to_string()
        })
        .collect();
    kinds.sort();
    kinds.dedup();
    assert_eq!(kinds.len(), 94, "{kinds:?}");
    let mut session = hedra_doc::Session::new();
    hedra_doc::script::run(&mut session, &commands, Path::new("docs/commands.md"))
        .unwrap_or_else(|e| panic!("{e}"));
    let doc = &session.doc;
    assert!(
        doc.find_by_name("Pyramid")
            .is_some_and(|n| n.parent.is_none())
    );
    assert!(doc.find_by_name("Box.001").is_none());
    assert_eq!(session.history.done().len(), commands.len());
    // ConvertSubdivisionToNurbs: the soap's cage is hidden beside its
    // group of patches (24 approximated faces at its 8 corners, and the
    // packed regular rest); the lifebuoy's cage is gone, one exact surface left.
    let soap = doc.find_by_name("Soap").unwrap();
    assert!(!soap.visible);
    let group = doc.find_by_name("Soap NURBS").unwrap();
    assert_eq!(group.content.kind(), "empty");
    let patches = doc.children(group.id).count();
    assert!(patches > 24, "{patches}");
    assert!(
        doc.children(group.id)
            .all(|n| matches!(n.content, hedra_doc::NodeContent::Surface(_)))
    );
    assert!(doc.find_by_name("Lifebuoy").is_none());
    let ring = doc.find_by_name("Lifebuoy NURBS").unwrap();
    assert_eq!(doc.children(ring.id).count(), 1);
    // The mesh examples leave a valid block: 2 loop cuts, an extrusion and an inset on the top.
    let half = doc.find_by_name("Half").unwrap().content.mesh().unwrap();
    let (lo, hi) = half.bounds().unwrap();
    assert!(
        (lo.x + hi.x).abs() < 1e-12 && hi.x > 1.0,
        "symmetric across x = 0: {lo:?} {hi:?}"
    );
    assert!(half.stats().closed);
    let spike = doc.find_by_name("Spike").unwrap().content.mesh().unwrap();
    assert!(
        spike.volume() > 0.0,
        "the mirrored cone still faces outwards"
    );
    let floor = doc.find_by_name("Floor").unwrap().content.mesh().unwrap();
    assert_eq!(
        (floor.face_count(), floor.vertex_count()),
        (1, 12),
        "the grid dissolved into its outline"
    );
    let dice = doc.find_by_name("Dice").unwrap().content.mesh().unwrap();
    assert_eq!(
        (dice.vertex_count(), dice.face_count()),
        (24, 26),
        "every edge chamfered: 6 squares, 12 strips, 8 corner triangles"
    );
    let cut = doc.find_by_name("Cut").unwrap().content.mesh().unwrap();
    assert_eq!(
        (cut.vertex_count(), cut.face_count()),
        (10, 7),
        "a corner cut off by a triangle"
    );
    let halves = doc.find_by_name("Halves").unwrap().content.mesh().unwrap();
    let s = halves.stats();
    assert_eq!(
        (s.vertices, s.faces, s.shells, s.boundary_loops),
        (6, 2, 1, 1),
        "the seam at x = 0 is welded"
    );
    let crate_ = doc.find_by_name("Crate").unwrap().content.mesh().unwrap();
    crate_.validate().unwrap();
    assert_eq!(
        crate_.face_count(),
        0,
        "a corner, an opposite edge's faces and the last face: all six gone"
    );
    let chamfered = doc
        .find_by_name("Chamfered")
        .unwrap()
        .content
        .mesh()
        .unwrap();
    assert_eq!(
        (chamfered.vertex_count(), chamfered.face_count()),
        (12 + 8, 8 + 4),
        "two chamfers of three segments"
    );
    let tray = doc.find_by_name("Tray").unwrap().content.mesh().unwrap();
    assert_eq!(
        (tray.vertex_count(), tray.face_count()),
        (8, 5),
        "a plane with four walls"
    );
    let patch = doc.find_by_name("Patch").unwrap().content.mesh().unwrap();
    assert_eq!(
        (patch.vertex_count(), patch.face_count()),
        (12, 8),
        "four inner vertices merged into one, then a corner and its neighbour"
    );
    let at = |p: glam::DVec3| {
        patch
            .vertices()
            .any(|v| patch.position(v).distance(p) < 1e-12)
    };
    assert!(
        at(glam::DVec3::new(1.5, 0.0, 1.5)),
        "merged at the first vertex"
    );
    assert!(!at(glam::DVec3::new(1.5, 0.0, 0.5)));
    // Bisect with the upper half cleared and the cut filled, then
    // triangulated and joined back: the closed lower half of the cube.
    let cut = doc.find_by_name("Halved").unwrap().content.mesh().unwrap();
    cut.validate().unwrap();
    assert_eq!(
        (cut.vertex_count(), cut.edge_count(), cut.face_count()),
        (8, 12, 6)
    );
    assert!(cut.stats().closed);
    assert!(cut.faces().all(|f| cut.face_degree(f) == 4));
    assert!(cut.vertices().all(|v| cut.position(v).y <= 0.0));
    // Spin and screw: the torus, the fin and the spring.
    let donut = doc.find_by_name("Donut").unwrap().content.mesh().unwrap();
    let s = donut.stats();
    assert_eq!((s.vertices, s.edges, s.faces), (32, 64, 32));
    assert_eq!((s.genus, s.closed), (Some(1), true));
    // Decimate: the modifier shows level 100 of the record kept beside it;
    // the one-shot command leaves 48 triangles of the torus, still a torus.
    let hedra_doc::NodeContent::Mesh(rock) = &doc.find_by_name("Rock").unwrap().content else {
        panic!("Rock is a mesh")
    };
    assert_eq!(rock.decimations.len(), 1);
    let levels = rock.decimate_face_counts(0).unwrap().unwrap();
    let shown = rock.evaluated(0).unwrap();
    shown.validate().unwrap();
    assert_eq!(shown.face_count(), levels[100]);
    assert_eq!(*levels.last().unwrap(), 1280);
    let bagel = doc.find_by_name("Bagel").unwrap().content.mesh().unwrap();
    let s = bagel.stats();
    assert_eq!((s.faces, s.genus, s.closed), (48, Some(1), true));
    let slab = doc.find_by_name("Slab").unwrap().content.mesh().unwrap();
    slab.validate().unwrap();
    assert_eq!(slab.face_count(), 64);
    assert!(slab.faces().all(|f| slab.face_degree(f) == 4));
    let fin = doc.find_by_name("Fin").unwrap().content.mesh().unwrap();
    let s = fin.stats();
    assert_eq!((s.vertices, s.faces, s.boundary_loops), (12, 5, 1));
    let spring = doc.find_by_name("Spring").unwrap().content.mesh().unwrap();
    let s = spring.stats();
    // 37 rings of 4 vertices, 36 × 4 sides and two caps: a closed solid.
    assert_eq!((s.vertices, s.faces, s.genus), (148, 146, Some(0)));
    let (lo, hi) = spring.bounds().unwrap();
    assert!(
        (hi.z - lo.z - 5.5).abs() < 1e-9,
        "three turns of 1.5 plus the square: {lo} {hi}"
    );
    // Knife across the front face: two edges split, the front face in two,
    // the back face untouched.
    let carved = doc.find_by_name("Carved").unwrap().content.mesh().unwrap();
    carved.validate().unwrap();
    assert_eq!(
        (
            carved.vertex_count(),
            carved.edge_count(),
            carved.face_count()
        ),
        (10, 15, 7)
    );
    assert_eq!(
        carved
            .faces()
            .filter(|&f| carved.face_normal(f).z > 0.999)
            .count(),
        2
    );
    let bridge = doc.find_by_name("Bridge").unwrap().content.mesh().unwrap();
    assert!(bridge.stats().closed, "the two squares became a closed box");
    let block = doc.find_by_name("Block").unwrap().content.mesh().unwrap();
    block.validate().unwrap();
    let s = block.stats();
    // Counts of each operation are checked in the kernel's tests; here the
    // whole sequence must leave a valid, closed, outward block.
    assert_eq!((s.vertices, s.edges, s.faces), (54, 99, 47));
    assert_eq!(s.euler_characteristic, 2);
    assert!(
        block.volume() > 0.0,
        "flipped inside out, then recalculated outwards"
    );
    assert!(s.closed, "the hole was filled again");
    // Subdivision: the creased cube applied at level 2, the snapped cube at 1.
    let rounded = doc.find_by_name("Rounded").unwrap();
    let hedra_doc::NodeContent::Mesh(content) = &rounded.content else {
        panic!("Rounded is a mesh");
    };
    assert!(
        content.subdivision.is_none(),
        "applying removes the modifier"
    );
    assert_eq!(content.mesh.face_count(), 6 * 16);
    content.mesh.validate().unwrap();
    // The top's four infinitely sharp edges became 16 child edges, still sharp.
    assert_eq!(
        content
            .creases
            .edges
            .values()
            .filter(|&&s| s >= 10.0)
            .count(),
        16
    );
    // The top face stays flat at y = 1 (its edges are infinitely sharp).
    let (_, hi) = content.mesh.bounds().unwrap();
    assert!((hi.y - 1.0).abs() < 1e-12, "{hi}");
    // The open box: its top is a hole, so level 2 shows 5 × 16 faces; the
    // cage keeps all 6.
    let open = doc.find_by_name("Open Box").unwrap();
    let hedra_doc::NodeContent::Mesh(content) = &open.content else {
        panic!("Open Box is a mesh");
    };
    assert_eq!(content.mesh.face_count(), 6);
    assert_eq!(content.creases.holes.len(), 1);
    // Its tapered crease: two edges, at 1 and 3 (midpoints at 1/4 and 3/4).
    assert_eq!(content.creases.tapers.len(), 1);
    let mut along: Vec<f64> = content.creases.edge_sharpness().into_values().collect();
    along.sort_by(f64::total_cmp);
    assert_eq!(along, [1.0, 3.0]);
    let smooth = content.evaluated(2).unwrap();
    assert_eq!(smooth.face_count(), 5 * 16);
    smooth.validate().unwrap();
    assert!(!smooth.stats().closed, "the top is open");
    let snapped = doc.find_by_name("Snapped").unwrap().content.mesh().unwrap();
    assert_eq!(snapped.face_count(), 24);
    let (lo, hi) = snapped.bounds().unwrap();
    // Corners snapped to ±1/2 (the cube's limit); one more level keeps the
    // face points of those faces at ±1/2 and pulls everything else inside.
    assert!(
        (hi.x - 0.5).abs() < 1e-12 && (lo.x + 0.5).abs() < 1e-12,
        "{lo} {hi}"
    );
    // The modifier stack: the mirrored half box, applied, is a closed box
    // cage that keeps its subdivision; the tube keeps its array.
    let mesh_content = |name: &str| match &doc.find_by_name(name).unwrap().content {
        hedra_doc::NodeContent::Mesh(c) => c.clone(),
        _ => panic!("{name} is a mesh"),
    };
    let half_box = mesh_content("HalfBox");
    assert!(half_box.modifiers.is_empty(), "applied");
    assert!(
        half_box.subdivision.is_some(),
        "subdivision stays a modifier"
    );
    half_box.mesh.validate().unwrap();
    let s = half_box.mesh.stats();
    assert_eq!((s.vertices, s.edges, s.faces), (12, 20, 10));
    assert_eq!((s.closed, s.genus), (true, Some(0)));
    let tube = mesh_content("Tube");
    assert_eq!(tube.modifiers.len(), 1);
    assert_eq!(tube.mesh.face_count(), 4, "the cage is one piece of tube");
    let evaluated = tube.evaluated(0).unwrap();
    evaluated.validate().unwrap();
    let s = evaluated.stats();
    assert_eq!((s.vertices, s.edges, s.faces), (16, 28, 12));
    assert_eq!((s.shells, s.boundary_loops, s.genus), (1, 2, Some(0)));
    // Rip, vertex rip, vertex split and the Euler operators.
    use hedra_geom::TopologyCounts;
    let counts = |name: &str| {
        let m = doc.find_by_name(name).unwrap().content.mesh().unwrap();
        m.validate().unwrap();
        let c = TopologyCounts::of(m);
        assert!(c.euler_poincare_holds(), "{name}: {c}");
        c.to_string()
    };
    assert_eq!(counts("Torn"), "V 30, E 44, F 16, L 16, S 2, H 0, B 2");
    assert_eq!(counts("Pinched"), "V 26, E 42, F 16, L 16, S 1, H 0, B 2");
    assert_eq!(counts("Split"), "V 26, E 41, F 16, L 16, S 1, H 0, B 1");
    let split = doc.find_by_name("Split").unwrap().content.mesh().unwrap();
    let mut degrees: Vec<usize> = split.faces().map(|f| split.face_degree(f)).collect();
    degrees.sort();
    assert_eq!(degrees[14..], [5, 5], "two quads gained a side");
    assert_eq!(counts("Ringed"), "V 12, E 16, F 7, L 8, S 1, H 0, B 0");
    let ringed = doc.find_by_name("Ringed").unwrap().content.mesh().unwrap();
    let top = ringed
        .faces()
        .find(|&f| !ringed.face_rings(f).is_empty())
        .expect("a face with a ring");
    assert!(
        ringed.face_normal(top).y > 0.9,
        "the ring is in the top face"
    );
    assert_eq!(ringed.loop_halfedges(ringed.face_rings(top)[0]).count(), 4);
    assert_eq!(counts("Euler Cube"), "V 8, E 12, F 6, L 6, S 1, H 0, B 0");
    let labels: Vec<&str> = session
        .history
        .done()
        .iter()
        .map(|t| t.label.as_str())
        .filter(|l| l.starts_with("Euler") || l.starts_with("Rip") || l.starts_with("Split V"))
        .collect();
    assert_eq!(
        labels,
        [
            "Rip",
            "Rip Vertex",
            "Split Vertex",
            "Euler MEV",
            "Euler MEV",
            "Euler MEV",
            "Euler MEV",
            "Euler MEF",
            "Euler KEMR",
            "Euler KFMRH",
            "Euler MFKRH",
            "Euler MVFS",
            "Euler MEV",
            "Euler KEV",
            "Euler KVFS"
        ]
    );
    // Curves and surfaces: edits keep their shapes where they promise to.
    use hedra_geom::curves::Curve;
    let curve = |name: &str| match &doc.find_by_name(name).unwrap().content {
        hedra_doc::NodeContent::Curve(c) => c.nurbs().clone(),
        _ => panic!("{name} is a curve"),
    };
    let wave = curve("Wave");
    assert_eq!(
        (wave.degree(), wave.points().len()),
        (3, 6),
        "one knot inserted"
    );
    let profile = curve("Profile");
    assert_eq!(profile.degree(), 4, "elevated once");
    // The Bézier point at ½ is (P0 + 3 P1 + 3 P2 + P3) / 8, elevated or not.
    assert!((profile.point(0.5) - hedra_geom::DVec3::new(0.7375, 0.8125, 0.0)).length() < 1e-12);
    let ring = curve("Ring");
    assert_eq!(ring.weights()[1], 3.0);
    // Every curve kind: the examples below add one of each and edit them.
    let kind = |name: &str| match &doc.find_by_name(name).unwrap().content {
        hedra_doc::NodeContent::Curve(c) => c.clone(),
        _ => panic!("{name} is a curve"),
    };
    use hedra_geom::curves::{CurveKind, Join, PolyBezier};
    let through = kind("Through");
    assert!(matches!(through.kind(), CurveKind::Lagrange(_)));
    assert_eq!(through.control_points().len(), 3, "one point deleted");
    let swing = kind("Swing");
    let keys = swing.kind().key_parameters().unwrap();
    for (t, p) in keys.iter().zip(swing.control_points()) {
        assert!(
            (swing.nurbs().point(*t) - *p).length() < 1e-12,
            "through its points"
        );
    }
    let path = kind("Path");
    match path.kind() {
        CurveKind::PolyBezier(PolyBezier { points, joins, .. }) => {
            assert_eq!(
                (points.len(), joins.as_slice()),
                (10, &[Join::G1, Join::G1][..])
            );
            let (a, b, c) = (points[2], points[3], points[4]);
            assert!(
                (b - a).normalize().dot((c - b).normalize()) > 1.0 - 1e-12,
                "G1"
            );
        }
        k => panic!("{k:?}"),
    }
    assert_eq!(kind("Snowflake").nurbs().points().len(), 3 * 64 + 1);
    assert!(matches!(kind("Sausage").kind(), CurveKind::Nurbs(_)));
    assert_eq!(kind("Sausage").nurbs().points().len(), 65);
    assert!(kind("Corners").kind().is_closed());
    assert!(doc.find_by_name("Rope End").is_none(), "joined back");
    assert_eq!(kind("Rope").control_points().len(), 7);
    assert_eq!(
        kind("Keys").control_points()[0],
        hedra_geom::DVec3::new(-1.0, 1.0, 0.0)
    );
    assert_eq!(kind("Loop").tolerance(), None);
    match &doc.find_by_name("Ball").unwrap().content {
        // 9 × 5 points, a knot in v (× 6), the circle direction elevated
        // from degree 2 (four quarter arcs of 3 new points each: 13).
        hedra_doc::NodeContent::Surface(s) => assert_eq!(s.control_points().len(), 13 * 6),
        _ => panic!("Ball is a surface"),
    }
    // Surfaces and meshes from curves.
    let made = |name: &str| doc.find_by_name(name).unwrap();
    let donut = made("Doughnut").content.mesh().unwrap();
    donut.validate().unwrap();
    let stats = donut.stats();
    assert!(stats.closed, "the 270° piece is capped");
    assert_eq!(stats.genus, Some(0));
    assert_eq!(donut.face_count(), 18 * 12 + 2);
    let star = made("Star").content.mesh().unwrap();
    assert_eq!((star.face_count(), star.stats().genus), (8 + 2, Some(0)));
    assert!(made("Swept Tube").construction.is_none(), "applied");
    assert!(made("Canopy").construction.is_some());
    // The loft followed the waist ring's move: it passes through the
    // moved circle (centre x = 32.3, radius 0.5, y = 1.5).
    let hedra_doc::NodeContent::Surface(loft) = &made("Vase Loft").content else {
        panic!("a surface")
    };
    let hedra_doc::SurfaceShape::Nurbs(loft) = &**loft else {
        panic!("a NURBS surface")
    };
    let world_curve = |name: &str| {
        let n = made(name);
        curve(name).transformed(&doc.world_matrix(n.id)).unwrap()
    };
    let rings = ["Base Ring", "Waist Ring", "Top Ring"].map(world_curve);
    let params = hedra_geom::surfaces::sweeps::loft_section_parameters(
        &rings,
        hedra_geom::surfaces::sweeps::LoftOptions::default(),
    );
    use hedra_geom::Surface;
    let near_waist = (0..=40)
        .map(|k| loft.point(k as f64 / 40.0, params[1]))
        .map(|p| ((p.x - 32.3).hypot(p.z) - 0.5).abs().max((p.y - 1.5).abs()))
        .fold(0.0, f64::max);
    assert!(near_waist < 1e-9, "{near_waist}");
    // The Coons patch followed its moved south edge: its corner (0, 0) and
    // the edge's middle, at u = 1/2 of a quadratic, are the curve's.
    let hedra_doc::NodeContent::Surface(patch) = &made("Coons Patch").content else {
        panic!("a surface")
    };
    let hedra_doc::SurfaceShape::Nurbs(patch) = &**patch else {
        panic!("a NURBS surface")
    };
    let south = world_curve("South Edge");
    assert!(patch.point(0.5, 0.0).distance(south.point(0.5)) < 1e-12);
    assert!(patch.point(0.0, 0.0).distance(south.point(0.0)) < 1e-12);
    // The G1 join was made, followed a shared drag, then broken.
    assert!(doc.g1_joins().is_empty(), "broken");
    let hedra_doc::NodeContent::Surface(g1) = &made("G1 Patch").content else {
        panic!("a surface")
    };
    assert!(
        g1.control_points()[3].distance(glam::DVec3::new(46.0, 0.5, 0.2)) < 1e-12,
        "the patch's corner followed the triangle's edge point"
    );
    // The Gordon mesh: 8 × 8 quads through the ridge's top (41, 0.5, 1).
    let network = made("Network").content.mesh().unwrap();
    network.validate().unwrap();
    assert_eq!(network.face_count(), 64);
    assert!(network.vertices().any(|v| {
        network
            .position(v)
            .distance(glam::DVec3::new(41.0, 0.5, 1.0))
            < 1e-12
    }));
}

#[test]
fn the_csg_examples_make_the_emblem_and_apply_a_boolean() {
    let blocks = common::commands_md_blocks();
    let script = format!("[\n{}\n]", blocks.join(",\n"));
    let commands = hedra_doc::script::parse(&script, Path::new("docs/commands.md")).unwrap();
    let mut session = hedra_doc::Session::new();
    hedra_doc::script::run(&mut session, &commands, Path::new("docs/commands.md")).unwrap();
    let doc = &session.doc;
    let emblem = doc.find_by_name("Emblem").unwrap();
    let solid = hedra_doc::csg::evaluate(doc, emblem.id).unwrap();
    solid.validate().unwrap();
    let s = solid.stats();
    // Three rods through a rounded cube: genus 5 (V − E + F = 2 − 2g).
    assert_eq!((s.shells, s.genus, s.closed), (1, Some(5), true));
    // The operands are children of the CSG nodes, drawn through them.
    let rounded = doc.find_by_name("Core").unwrap();
    assert_eq!(rounded.parent, Some(emblem.id));
    assert_eq!(hedra_doc::csg::operands(doc, emblem.id).len(), 4);
    assert!(hedra_doc::csg::inside_csg(
        doc,
        doc.find_by_name("Emblem Ball").unwrap().id
    ));
    // Applied: a plain mesh, the operands gone; then the one-shot union.
    let stamped = doc.find_by_name("Stamped").unwrap().content.mesh().unwrap();
    stamped.validate().unwrap();
    assert!(doc.find_by_name("Notch").is_none() && doc.find_by_name("Tool").is_none());
    assert!(
        (stamped.volume() - (0.875 + 1.0 - 0.25)).abs() < 1e-12,
        "{}",
        stamped.volume()
    );
    // Undo of the one-shot boolean brings the tool back.
    session.undo().unwrap();
    assert!(session.doc.find_by_name("Tool").is_some());
}
