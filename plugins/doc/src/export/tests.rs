//! The export writers against the paths they replace.

use super::*;
use crate::scene::{MeshContent, NodeId, NodeTransform, SubdivisionModifier};
use hedra_geom::subdivision::{BoundaryInterpolation, Options, Refiner, Scheme};
use std::sync::Arc;

fn node(mesh: HalfEdgeMesh, creases: Creases, options: Options) -> Node {
    let mut content = MeshContent::new(Arc::new(mesh));
    content.creases = creases;
    content.subdivision = Some(SubdivisionModifier {
        options,
        ..SubdivisionModifier::with_level(1)
    });
    Node {
        id: NodeId(1),
        name: "Cage".into(),
        parent: None,
        transform: NodeTransform::IDENTITY,
        visible: true,
        content: NodeContent::Mesh(content),
        construction: None,
        g1_join: None,
    }
}

/// OBJ and binary STL of `geometry`, mirrored or not.
fn written(node: &Node, geometry: Geometry<'_>, mirrored: bool) -> (Vec<u8>, Vec<u8>) {
    let world = if mirrored {
        glam::DMat4::from_scale(DVec3::new(-1.0, 2.0, 1.0))
    } else {
        glam::DMat4::from_translation(DVec3::new(0.5, 0.0, -1.0))
    };
    let items = [ExportItem {
        node,
        geometry,
        world,
        mirrored,
        corners: None,
    }];
    let (mut obj, mut stl) = (
        std::io::Cursor::new(Vec::new()),
        std::io::Cursor::new(Vec::new()),
    );
    write_obj(&items, &mut obj).unwrap();
    write_stl(&items, &mut stl).unwrap();
    (obj.into_inner(), stl.into_inner())
}

/// glTF positions, normals and triangle indices of one mesh.
type GltfTriangles = (Vec<[f32; 3]>, Vec<[f32; 3]>, Vec<u32>);

/// The glTF arrays the GLB writer streams from `refined`, read back;
/// `None` when they are not written from the faces.
fn gltf_arrays(refined: &Arc<RefinedFaces>, smooth: bool) -> Option<GltfTriangles> {
    let shading = if smooth {
        crate::scene::Shading::Smooth
    } else {
        crate::scene::Shading::Flat
    };
    Some(crate::gltf::arrays_from_faces(refined, shading)?.written())
}

/// A large subdivided mesh's STL records, OBJ lines and glTF arrays, made
/// in pieces on all cores, are the ones the mesh's faces give, in the same
/// order:
/// also with boundary None, whose hidden faces leave pieces of uneven
/// length (the flat corners' numbers start where the last piece ended).
#[test]
fn stl_obj_and_gltf_made_on_all_cores_are_the_mesh_s() {
    let grid = hedra_geom::Primitive::Grid {
        x_segments: 90,
        z_segments: 70,
        size: 2.0,
    }
    .build()
    .unwrap();
    for boundary in [
        BoundaryInterpolation::EdgesOnly,
        BoundaryInterpolation::None,
    ] {
        let options = Options {
            boundary,
            ..Options::default()
        };
        let node = node(grid.clone(), Creases::default(), options);
        let shape = ExportShape::Subdivided(2);
        let Some(Geometry::Refined(refined)) = refined_geometry(&node, shape).unwrap() else {
            panic!("written as refined faces")
        };
        assert!(refined.refiner.face_count() >= PARALLEL_FACES);
        assert!(refined.piece_count() > 4, "{boundary:?}: pieces");
        let (mesh, creases) = node_geometry(&node, shape).unwrap().unwrap();
        let stl = |geometry, mirrored| {
            let world = if mirrored {
                glam::DMat4::from_scale(DVec3::new(1.0, -1.0, 3.0))
            } else {
                glam::DMat4::IDENTITY
            };
            let items = [ExportItem {
                node: &node,
                geometry,
                world,
                mirrored,
                corners: None,
            }];
            let mut bytes = std::io::Cursor::new(Vec::new());
            write_stl(&items, &mut bytes).unwrap();
            bytes.into_inner()
        };
        let Geometry::Mesh(m) = &mesh else { panic!() };
        let shown_faces = m.face_count();
        if boundary == BoundaryInterpolation::None {
            assert!(shown_faces < 90 * 70 * 16, "faces are hidden");
        }
        let refined_again = || refined_geometry(&node, shape).unwrap().unwrap();
        for mirrored in [false, true] {
            let (fast, slow) = (
                stl(refined_again(), mirrored),
                stl(Geometry::Mesh(Cow::Borrowed(m)), mirrored),
            );
            assert_eq!(fast.len(), 84 + 50 * 2 * shown_faces);
            assert!(
                fast == slow,
                "{boundary:?}, mirrored {mirrored}: the records differ"
            );
            // The mesh's records (made on all cores too) are the ones
            // each_stl_triangle visits one by one.
            assert!(m.face_count() >= PARALLEL_FACES);
            let item = ExportItem {
                node: &node,
                geometry: Geometry::Mesh(Cow::Borrowed(m)),
                world: if mirrored {
                    glam::DMat4::from_scale(DVec3::new(1.0, -1.0, 3.0))
                } else {
                    glam::DMat4::IDENTITY
                },
                mirrored,
                corners: None,
            };
            let mut one_by_one = Vec::new();
            each_stl_triangle(std::slice::from_ref(&item), |normal, corners| {
                one_by_one.extend_from_slice(&stl_record(normal, corners))
            });
            // OBJ: the refined faces' and the mesh's lines, made in pieces on
            // all cores, against the mesh's written one by one (the path of
            // a mesh with corner attributes, here none).
            let no_corners = CornerAttributes::default();
            let obj = |geometry, corners| {
                let items = [ExportItem {
                    node: &node,
                    geometry,
                    world: item.world,
                    mirrored,
                    corners,
                }];
                let mut bytes = std::io::Cursor::new(Vec::new());
                write_obj(&items, &mut bytes).unwrap();
                bytes.into_inner()
            };
            let serial = obj(Geometry::Mesh(Cow::Borrowed(m)), Some(&no_corners));
            assert!(
                obj(Geometry::Mesh(Cow::Borrowed(m)), None) == serial,
                "{boundary:?}, mirrored {mirrored}: the mesh's OBJ"
            );
            assert!(
                obj(refined_again(), None) == serial,
                "{boundary:?}, mirrored {mirrored}: the refined faces' OBJ"
            );
            assert!(
                slow[84..] == one_by_one[..],
                "{boundary:?}, mirrored {mirrored}: the mesh's records"
            );
        }
        let refined = Arc::new(refined);
        for smooth in [false, true] {
            let shading = if smooth {
                crate::scene::Shading::Smooth
            } else {
                crate::scene::Shading::Flat
            };
            let fast = gltf_arrays(&refined, smooth).expect("written from the faces");
            let slow = crate::gltf::mesh_triangles(m, shading, &creases);
            assert!(
                fast.0 == slow.0,
                "{boundary:?}, {shading:?}: glTF positions"
            );
            assert!(
                fast.2 == slow.2,
                "{boundary:?}, {shading:?}: glTF triangles"
            );
            if smooth {
                let off = fast
                    .1
                    .iter()
                    .zip(&slow.1)
                    .map(|(a, b)| glam::Vec3::from(*a).distance(glam::Vec3::from(*b)));
                assert!(
                    off.fold(0.0, f32::max) < 1e-6,
                    "{boundary:?}: smooth normals"
                );
            } else {
                assert!(fast.1 == slow.1, "{boundary:?}: flat normals");
            }
        }
    }
}

/// The refined faces are written exactly as the subdivided half-edge
/// mesh was: same vertex numbers, faces and triangles, byte for byte,
/// on cages with what changes them: corners of two edges (whose ears
/// the triangulation must not clip), hidden boundary faces (boundary
/// `None`: vertices left out), creases, a vertex without edges,
/// triangles (Loop) and a mirroring transform.
#[test]
fn refined_faces_write_what_the_subdivided_mesh_writes() {
    let cc = |boundary| Options {
        boundary,
        ..Options::default()
    };
    let loop_ = Options {
        scheme: Scheme::Loop,
        ..Options::default()
    };
    // One thin parallelogram: its corners have two edges, and at its
    // sharp ones the shorter diagonal of a refined quad would cut the
    // ear at the corner.
    let thin = HalfEdgeMesh::from_polygons(
        &[
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.5, 0.4, 0.1),
            DVec3::new(0.5, 0.4, 0.0),
        ],
        &[vec![0, 1, 2, 3]],
    )
    .unwrap();
    // A pillow: two quads on the same four edges (every vertex has two).
    let pillow = HalfEdgeMesh::from_polygons(
        &[
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.5, 0.4, 0.1),
            DVec3::new(0.5, 0.4, 0.0),
        ],
        &[vec![0, 1, 2, 3], vec![3, 2, 1, 0]],
    )
    .unwrap();
    // An open 3 × 2 grid of quads and a triangle, with a lone vertex.
    let mut points: Vec<DVec3> = (0..12)
        .map(|i| DVec3::new((i % 4) as f64, (i / 4) as f64, ((i * 7) % 5) as f64 * 0.1))
        .collect();
    points.push(DVec3::new(5.0, 5.0, 5.0));
    points.push(DVec3::new(-1.0, 0.5, 0.0));
    let open = HalfEdgeMesh::from_polygons(
        &points,
        &[
            vec![0, 1, 5, 4],
            vec![1, 2, 6, 5],
            vec![2, 3, 7, 6],
            vec![4, 5, 9, 8],
            vec![5, 6, 10, 9],
            vec![6, 7, 11, 10],
            vec![13, 0, 4],
        ],
    )
    .unwrap();
    assert_eq!(open.vertex_count(), 14, "the lone vertex is kept");
    let mut creased = Creases::default();
    creased.set_edge(open.edges().nth(3).unwrap(), 2.5);
    creased.set_edge(open.edges().nth(8).unwrap(), f64::INFINITY);
    // An octahedron, slightly uneven: triangles for Loop.
    let octahedron = HalfEdgeMesh::from_polygons(
        &[
            DVec3::X,
            DVec3::new(0.0, 1.2, 0.1),
            -DVec3::X,
            -DVec3::Y,
            DVec3::new(0.1, 0.0, 0.9),
            -DVec3::Z,
        ],
        &[
            vec![0, 1, 4],
            vec![1, 2, 4],
            vec![2, 3, 4],
            vec![3, 0, 4],
            vec![1, 0, 5],
            vec![2, 1, 5],
            vec![3, 2, 5],
            vec![0, 3, 5],
        ],
    )
    .unwrap();
    let cases = [
        (
            "thin quad",
            thin,
            Creases::default(),
            cc(BoundaryInterpolation::EdgesAndCorners),
        ),
        (
            "pillow",
            pillow,
            Creases::default(),
            cc(BoundaryInterpolation::EdgesOnly),
        ),
        (
            "open grid",
            open.clone(),
            creased.clone(),
            cc(BoundaryInterpolation::EdgesOnly),
        ),
        (
            "open grid, boundary None",
            open,
            creased,
            cc(BoundaryInterpolation::None),
        ),
        ("octahedron, Loop", octahedron, Creases::default(), loop_),
    ];
    for (name, mesh, creases, options) in cases {
        let node = node(mesh, creases, options);
        for level in 1..=2 {
            let shape = ExportShape::Subdivided(level);
            let Some(Geometry::Refined(refined)) = refined_geometry(&node, shape).unwrap() else {
                panic!("{name}: written as refined faces")
            };
            let (mesh, _) = node_geometry(&node, shape).unwrap().unwrap();
            let Geometry::Mesh(m) = &mesh else { panic!() };
            assert_eq!(refined.counts(), mesh.counts(), "{name}, level {level}");
            let refined = Arc::new(refined);
            for mirrored in [false, true] {
                let fast = written(
                    &node,
                    Geometry::Refined(
                        RefinedFaces::of(
                            match &node.content {
                                NodeContent::Mesh(c) => c,
                                _ => unreachable!(),
                            },
                            level,
                        )
                        .unwrap()
                        .unwrap(),
                    ),
                    mirrored,
                );
                let slow = written(&node, Geometry::Mesh(Cow::Borrowed(m)), mirrored);
                assert!(fast.0 == slow.0, "{name}, level {level}: the OBJ differs");
                assert!(fast.1 == slow.1, "{name}, level {level}: the STL differs");
            }
            // glTF: flat as the mesh makes it, byte for byte; smooth
            // the same vertices and triangles, normals summed in
            // another order (to 1e-6), or the mesh's own where they
            // must be split.
            let mesh_creases = Refiner::subdivide(
                match &node.content {
                    NodeContent::Mesh(c) => &c.mesh,
                    _ => unreachable!(),
                },
                match &node.content {
                    NodeContent::Mesh(c) => &c.creases,
                    _ => unreachable!(),
                },
                options,
                level,
            )
            .unwrap()
            .1;
            for smooth in [false, true] {
                let shading = if smooth {
                    crate::scene::Shading::Smooth
                } else {
                    crate::scene::Shading::Flat
                };
                let slow = crate::gltf::mesh_triangles(m, shading, &mesh_creases);
                let Some(fast) = gltf_arrays(&refined, smooth) else {
                    // The pillow's faces have no area (its two
                    // faces meet); the grid's crease is infinitely
                    // sharp. Everything else is written from the faces.
                    assert!(
                        name == "pillow" || (smooth && name.contains("grid")),
                        "{name}: glTF from the faces"
                    );
                    continue;
                };
                assert_eq!(fast.0, slow.0, "{name}, level {level}: glTF positions");
                assert_eq!(fast.2, slow.2, "{name}, level {level}: glTF triangles");
                if smooth {
                    for (a, b) in fast.1.iter().zip(&slow.1) {
                        let d = glam::Vec3::from(*a).distance(glam::Vec3::from(*b));
                        assert!(
                            d < 1e-6,
                            "{name}, level {level}: normal {a:?} against {b:?}"
                        );
                    }
                } else {
                    assert_eq!(fast.1, slow.1, "{name}, level {level}: glTF flat normals");
                }
            }
        }
    }
}

/// A large mesh's flat glTF arrays, made in pieces on all cores, are the
/// ones `mesh_triangles` makes: with a hexagon (two quads merged), so the
/// corners per face vary, and a quad of zero area, whose normal comes from
/// its neighbours.
#[test]
fn flat_gltf_arrays_made_on_all_cores_are_mesh_triangles() {
    let n = 230u32;
    let mut positions: Vec<DVec3> = (0..=n)
        .flat_map(|j| {
            (0..=n).map(move |i| DVec3::new(i as f64, (i * j % 7) as f64 * 0.1, j as f64))
        })
        .collect();
    let at = |i: u32, j: u32| j * (n + 1) + i;
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for j in 0..n {
        for i in 0..n {
            if (i, j) == (5, 5) {
                // The hexagon: this quad and the next one.
                faces.push(vec![
                    at(5, 5),
                    at(5, 6),
                    at(6, 6),
                    at(7, 6),
                    at(7, 5),
                    at(6, 5),
                ]);
            } else if (i, j) != (6, 5) {
                faces.push(vec![at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)]);
            }
        }
    }
    // A quad of zero area.
    let p = positions[at(20, 20) as usize];
    for (i, j) in [(20, 21), (21, 21), (21, 20)] {
        positions[at(i, j) as usize] = p;
    }
    let m = HalfEdgeMesh::from_polygons(&positions, &faces).unwrap();
    assert!(m.face_count() > 3 * crate::export::FACES_PER_PIECE);
    let fast = crate::gltf::flat_mesh_arrays(Cow::Borrowed(&m)).written();
    let slow = crate::gltf::mesh_triangles(&m, crate::scene::Shading::Flat, &Creases::default());
    assert!(fast.0 == slow.0, "positions");
    assert!(fast.1 == slow.1, "normals");
    assert!(fast.2 == slow.2, "triangles");
}
