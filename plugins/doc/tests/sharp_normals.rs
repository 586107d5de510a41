//! Smooth shading across infinitely sharp creases (issue 31, item 9): the
//! jar sample's rim is an infinitely sharp crease, so the shown surface
//! (the kept refinement's render buffers) and the glTF export give every
//! vertex on it one normal per side, each its side's faces' normal, as
//! Blender splits normals at sharp edges. Before, one normal was shared and
//! averaged across the rim (a soft rim).

use glam::Vec3;
use hedra_doc::export::{ExportOptions, export_bytes};
use hedra_doc::render::{RenderBuffers, render_buffers, render_buffers_creased};
use hedra_doc::smooth::SmoothRefinement;
use hedra_doc::{NodeContent, Session, Shading, file};
use hedra_geom::subdivision::Creases;
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

fn jar() -> Session {
    let path =
        PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"))
            .join("../../assets/samples/jar.hedra.ron");
    file::load(&path).unwrap().session
}

/// Render vertices grouped by position (bit-exact), with each group's
/// indices.
fn by_position(positions: &[[f32; 3]]) -> HashMap<[u32; 3], Vec<usize>> {
    let mut out: HashMap<[u32; 3], Vec<usize>> = HashMap::new();
    for (i, p) in positions.iter().enumerate() {
        out.entry(p.map(f32::to_bits)).or_default().push(i);
    }
    out
}

/// The area-weighted normal of the triangles that use render vertex `i`.
fn triangles_normal(positions: &[[f32; 3]], indices: &[u32], i: usize) -> Vec3 {
    let mut n = Vec3::ZERO;
    for t in indices.chunks(3) {
        if t.contains(&(i as u32)) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|k| Vec3::from(positions[k as usize]));
            n += (b - a).cross(c - a);
        }
    }
    n.normalize_or_zero()
}

/// Checks that the rim of the jar (the crease loop at y = 2, where the flat
/// top meets the walls: points at y = 2 used both by a triangle of the top
/// and by one reaching below it) is split: each rim position has exactly
/// two render vertices, one with the top's normal +Y, the other with its own
/// triangles' normal, clearly apart; and that no other point is split.
/// Returns the number of rim positions.
fn assert_rim_split(b: &RenderBuffers, what: &str) -> usize {
    let y = |i: u32| b.positions[i as usize][1];
    let at_top = |i: u32| (y(i) - 2.0).abs() < 1e-5;
    let (mut top, mut wall) = (
        vec![false; b.positions.len()],
        vec![false; b.positions.len()],
    );
    for t in b.indices.chunks(3) {
        let flags = if t.iter().all(|&i| at_top(i)) {
            &mut top
        } else {
            &mut wall
        };
        for &i in t {
            flags[i as usize] = true;
        }
    }
    let mut rim = 0;
    for verts in by_position(&b.positions).values() {
        let p = Vec3::from(b.positions[verts[0]]);
        let on_rim = at_top(verts[0] as u32)
            && verts.iter().any(|&i| top[i])
            && verts.iter().any(|&i| wall[i]);
        if !on_rim {
            assert_eq!(verts.len(), 1, "{what}: {p} off the rim is not split");
            continue;
        }
        rim += 1;
        assert_eq!(
            verts.len(),
            2,
            "{what}: rim point {p} has one vertex per side"
        );
        let normals: Vec<Vec3> = verts.iter().map(|&i| Vec3::from(b.normals[i])).collect();
        let up = normals
            .iter()
            .position(|n| (*n - Vec3::Y).length() < 1e-5)
            .unwrap_or_else(|| panic!("{what}: rim point {p}: no +Y normal in {normals:?}"));
        assert!(
            normals[1 - up].dot(Vec3::Y) < 0.9,
            "{what}: rim point {p}: the wall side's normal {} leans towards the top",
            normals[1 - up]
        );
        for (k, &i) in verts.iter().enumerate() {
            // Each vertex is used by one side's triangles only.
            assert!(
                top[i] != wall[i],
                "{what}: rim point {p}: a vertex on both sides"
            );
            let side = triangles_normal(&b.positions, &b.indices, i);
            assert!(
                (side - normals[k]).length() < 0.05,
                "{what}: rim point {p}: normal {} is not its side's {side}",
                normals[k]
            );
        }
    }
    rim
}

#[test]
fn the_jar_rim_is_shaded_sharp_in_the_viewport_and_in_gltf() {
    let session = jar();
    let node = session.doc.find_by_name("Jar").unwrap();
    let NodeContent::Mesh(content) = &node.content else {
        panic!("the jar is a mesh");
    };
    assert_eq!(content.shading, Shading::Smooth);
    let modifier = content.subdivision.unwrap();
    let cage = Arc::new(content.mesh.clone());
    let mut r = SmoothRefinement::new(&cage, &content.creases, &modifier).unwrap();
    let points = r.points(&cage);
    let b = r.buffers(&points, Shading::Smooth);
    // Level 3: each of the 4 rim edges is cut into 8, so 32 rim points.
    assert_eq!(assert_rim_split(&b, "viewport"), 32);
    assert_eq!(b.positions.len(), points.len() + 32);
    // A drag frame's attributes keep the same layout as the buffers.
    let (positions, normals) = r.attributes(&points, Shading::Smooth);
    assert_eq!(
        (positions, normals),
        (b.positions.clone(), b.normals.clone())
    );
    // Flat shading is untouched: one corner per refined face corner.
    let flat = r.buffers(&points, Shading::Flat);
    assert_eq!(flat.positions.len(), 4 * flat.indices.len() / 6);

    // glTF: the export level (2) splits its 16 rim points the same way.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("jar.glb");
    let bytes = export_bytes(&session.doc, &out, ExportOptions::default()).unwrap();
    let glb = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = glb.blob.as_deref();
    let prim = glb.meshes().next().unwrap().primitives().next().unwrap();
    let reader = prim.reader(|_| blob);
    let exported = RenderBuffers {
        positions: reader.read_positions().unwrap().collect(),
        normals: reader.read_normals().unwrap().collect(),
        indices: reader.read_indices().unwrap().into_u32().collect(),
    };
    assert_eq!(assert_rim_split(&exported, "glTF"), 16);
}

#[test]
fn a_cage_splits_only_at_infinitely_sharp_creases() {
    let cube = hedra_geom::Primitive::Cube { size: 2.0 }.build().unwrap();
    let top_edges: Vec<_> = cube
        .edges()
        .filter(|&e| {
            cube.edge_vertices(e)
                .iter()
                .all(|&v| cube.position(v).y > 0.5)
        })
        .collect();
    assert_eq!(top_edges.len(), 4);
    let plain = render_buffers(&cube, Shading::Smooth);
    assert_eq!(plain.positions.len(), 8);
    let with = |s: f64, edges: &[hedra_geom::EdgeId]| {
        let mut c = Creases::default();
        for &e in edges {
            c.set_edge(e, s);
        }
        render_buffers_creased(&cube, Shading::Smooth, &c)
    };
    // A finite crease, and one sharp edge alone (its ends' faces still
    // form one fan each), split nothing.
    assert_eq!(with(2.0, &top_edges), plain);
    assert_eq!(with(10.0, &top_edges[..1]), plain);
    // The top's loop infinitely sharp: each top corner twice, one vertex
    // with the top's normal, one with the two side faces' normal.
    let b = with(10.0, &top_edges);
    assert_eq!(b.positions.len(), 12);
    assert_eq!(b.indices.len(), plain.indices.len());
    for v in cube.vertices().filter(|&v| cube.position(v).y > 0.5) {
        let p = cube.position(v).as_vec3();
        let verts: Vec<usize> = (0..b.positions.len())
            .filter(|&i| Vec3::from(b.positions[i]) == p)
            .collect();
        assert_eq!(verts.len(), 2, "{p}");
        let normals: Vec<Vec3> = verts.iter().map(|&i| Vec3::from(b.normals[i])).collect();
        let sides = Vec3::new(p.x, 0.0, p.z).normalize();
        assert!(
            normals.iter().any(|n| (*n - Vec3::Y).length() < 1e-6)
                && normals.iter().any(|n| (*n - sides).length() < 1e-6),
            "{p}: {normals:?}"
        );
        // Every triangle at a vertex lies on its side: within 45° of it
        // (a shared normal, (1, 1, 1)/√3 at a corner, is 55° from each).
        for &i in &verts {
            let n = Vec3::from(b.normals[i]);
            for t in b.indices.chunks(3).filter(|t| t.contains(&(i as u32))) {
                let [a, c, d] = [t[0], t[1], t[2]].map(|k| Vec3::from(b.positions[k as usize]));
                let face = (c - a).cross(d - a).normalize();
                assert!(face.dot(n) > 0.7, "{p}: triangle {face} at normal {n}");
            }
        }
    }
    // Flat shading is the same with or without creases.
    assert_eq!(
        render_buffers_creased(&cube, Shading::Flat, &Creases::default()),
        render_buffers(&cube, Shading::Flat)
    );
}
