//! OpenUSD export and import (issue 32). Every export is opened by Pixar's
//! usd-core (`scripts/usd_read.py`: `Usd.Stage.Open`, usdchecker's
//! validators, then a JSON dump of every prim), which must report no
//! error, and what it reads is compared with Hedra's document: local
//! transforms, points, topology, subdivision scheme and options, creases
//! (tapers as per-edge sharpness), corners, holes, UVs, NURBS orders,
//! knots, weights. Then the file is imported back and the document
//! compared with the one written. usd-core is installed by scripts/setup
//! (scripts/requirements.txt); without it these tests fail, naming it.

use glam::{DQuat, DVec2, DVec3};
use hedra_doc::export::ExportShape;
use hedra_doc::import::ImportedMesh;
use hedra_doc::scene::{
    CornerAttributes, CurveContent, Document, MeshContent, Node, NodeContent, NodeTransform,
    Shading, SubdivisionModifier, SurfaceShape,
};
use hedra_doc::session::Session;
use hedra_geom::HalfEdgeMesh;
use hedra_geom::subdivision::{BoundaryInterpolation, CreaseMethod, Creases, Options, Scheme};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

fn root() -> PathBuf {
    Path::new(&std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"))
        .join("../..")
}

/// Fails, naming the module, when python3 cannot import pxr.
fn require_pxr() {
    let imported = Command::new("python3")
        .args(["-c", "import pxr.Usd, pxr.UsdValidation"])
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        imported,
        "python3 cannot import 'pxr' (Pixar's usd-core): run scripts/setup (it installs scripts/requirements.txt)"
    );
}

/// What usd-core reads from `file`, as `scripts/usd_read.py` prints it.
fn pxr_read(file: &Path) -> Value {
    let o = Command::new("python3")
        .arg(root().join("scripts/usd_read.py"))
        .arg(file)
        .output()
        .expect("python3 runs");
    assert!(
        o.status.success(),
        "usd-core cannot open {}: {}{}",
        file.display(),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("usd_read.py prints JSON")
}

fn load(path: &Path) -> Document {
    hedra_doc::file::load(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .session
        .doc
}

/// The scenes every USD test runs on: the samples, the corpus scenes
/// holding every curve kind, constructions, patches and commands, and a
/// scene built here with every content kind and subdivision tag.
fn scenes() -> Vec<(String, Document)> {
    let mut out = Vec::new();
    for s in ["chair", "csg", "cup", "g1-join", "jar", "shapes", "table"] {
        out.push((
            s.to_string(),
            load(&root().join(format!("assets/samples/{s}.hedra.ron"))),
        ));
    }
    for s in [
        "v2-curve-kinds",
        "v2-constructions",
        "v2-patches",
        "v3-every-command",
        "v3-uv-panel",
    ] {
        out.push((
            s.to_string(),
            load(
                &Path::new(
                    &std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"),
                )
                .join(format!("tests/corpus/scenes/{s}.hedra.ron")),
            ),
        ));
    }
    out.push(("every-kind".into(), every_kind()));
    out
}

fn imported(name: &str, parent: Option<usize>, t: NodeTransform, c: NodeContent) -> ImportedMesh {
    ImportedMesh {
        name: name.into(),
        mesh: None,
        report: Default::default(),
        parent,
        transform: t,
        skipped_primitives: 0,
        skipped_polylines: 0,
        face_numbers: Default::default(),
        not_imported: Vec::new(),
        vertex_numbers: Vec::new(),
        corners: CornerAttributes::default(),
        curve: None,
        content: Some(c),
        hidden: false,
        input: None,
        kept_places: Vec::new(),
    }
}

/// A kept (non-manifold) mesh: three quads on one edge (a fin), smooth,
/// with Catmull-Clark at levels 1 and 2.
fn fin() -> NodeContent {
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let mesh = hedra_doc::KeptMesh::new(
        vec![
            p(0.0, 0.0, 0.0),
            p(0.0, 0.0, 1.0),
            p(1.0, 0.0, 0.0),
            p(1.0, 0.0, 1.0),
            p(0.0, 1.0, 0.0),
            p(0.0, 1.0, 1.0),
            p(-1.0, 0.0, 0.0),
            p(-1.0, 0.0, 1.0),
        ],
        vec![vec![0, 2, 3, 1], vec![0, 4, 5, 1], vec![0, 6, 7, 1]],
    )
    .unwrap();
    NodeContent::Kept(hedra_doc::KeptMeshContent {
        mesh: Arc::new(mesh),
        shading: Shading::Smooth,
        subdivision: Some(SubdivisionModifier {
            export_level: 2,
            ..SubdivisionModifier::with_level(1)
        }),
    })
}

/// A scene with every content kind: a hierarchy with rotations and
/// non-uniform scales, a hidden node; a cube cage with Catmull-Clark,
/// plain and tapered creases, corners, a hole, UVs, edge-only boundary,
/// Chaikin, smooth triangles; a Loop mesh; a Linear one; a Doo-Sabin one;
/// a plain flat mesh with sharpness values that are not floats; NURBS
/// surfaces (rational sphere) and curves; a Bézier triangle.
fn every_kind() -> Document {
    let cube = hedra_geom::Primitive::Cube { size: 2.0 }.build().unwrap();
    let verts: Vec<_> = cube.vertices().collect();
    let edges: Vec<_> = cube.edges().collect();
    let faces: Vec<_> = cube.faces().collect();
    let mut creases = Creases::default();
    creases.set_edge(edges[0], 2.0);
    creases.set_edge(edges[1], 0.3);
    creases.set_vertex(verts[3], 1.5);
    creases.set_hole(faces[5], true);
    // A taper along two edges of a face loop: the face's first three vertices.
    let f0: Vec<_> = cube.face_vertices(faces[0]).collect();
    let e1 = cube.find_edge(f0[1], f0[2]).unwrap();
    let e2 = cube.find_edge(f0[2], f0[3]).unwrap();
    creases
        .set_taper(&cube, &[e1, e2], f0[1], 0.5, 3.25)
        .unwrap();
    let mut uvs = BTreeMap::new();
    for (k, f) in cube.faces().enumerate() {
        for (i, h) in cube.face_halfedges(f).enumerate() {
            uvs.insert(h, DVec2::new(k as f64 * 0.125, i as f64 * 0.25));
        }
    }
    let sub = |scheme, boundary, crease_method, smooth_triangles| SubdivisionModifier {
        options: Options {
            scheme,
            boundary,
            crease_method,
            smooth_triangles,
        },
        viewport_level: 2,
        export_level: 3,
        show_cage: false,
        stack_position: None,
    };
    let cage = MeshContent {
        shading: Shading::Smooth,
        creases,
        subdivision: Some(sub(
            Scheme::CatmullClark,
            BoundaryInterpolation::EdgesOnly,
            CreaseMethod::Chaikin,
            true,
        )),
        corners: CornerAttributes {
            uvs: Arc::new(uvs),
            normals: Arc::default(),
        },
        ..MeshContent::new(Arc::new(cube.clone()))
    };
    let tri = HalfEdgeMesh::from_polygons(
        &[DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.1)],
        &[[0u32, 1, 2], [1, 3, 2]],
    )
    .unwrap();
    let loop_mesh = MeshContent {
        subdivision: Some(sub(
            Scheme::Loop,
            BoundaryInterpolation::EdgesAndCorners,
            CreaseMethod::Uniform,
            false,
        )),
        ..MeshContent::new(Arc::new(tri.clone()))
    };
    let linear = MeshContent {
        subdivision: Some(sub(
            Scheme::Linear,
            BoundaryInterpolation::None,
            CreaseMethod::Uniform,
            false,
        )),
        ..MeshContent::new(Arc::new(cube.clone()))
    };
    let doo = MeshContent {
        subdivision: Some(SubdivisionModifier {
            export_level: 2,
            ..sub(
                Scheme::DooSabin,
                BoundaryInterpolation::EdgesOnly,
                CreaseMethod::Uniform,
                false,
            )
        }),
        ..MeshContent::new(Arc::new(cube.clone()))
    };
    let mut odd = Creases::default();
    odd.set_edge(tri.edges().next().unwrap(), 0.1);
    let plain = MeshContent {
        creases: odd,
        ..MeshContent::new(Arc::new(tri))
    };
    let sphere = hedra_geom::surfaces::NurbsSurface::sphere(DVec3::new(0.1, 0.2, 0.3), 1.7);
    let circle = hedra_geom::curves::NurbsCurve::circle(DVec3::ONE / 3.0, 0.7);
    let triangle = hedra_geom::surfaces::BezierTriangle::new(
        2,
        vec![
            DVec3::ZERO,
            DVec3::new(0.5, 0.0, 0.2),
            DVec3::X,
            DVec3::new(0.0, 0.5, 0.2),
            DVec3::new(0.5, 0.5, 0.3),
            DVec3::Y,
        ],
    )
    .unwrap();
    let turned = NodeTransform {
        translation: DVec3::new(1.0 / 3.0, -2.5, 7.0),
        rotation: DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 2.0),
        scale: DVec3::new(1.5, 0.25, 3.0),
    };
    let nodes = vec![
        imported("Group", None, turned, NodeContent::Empty),
        imported(
            "Cage",
            Some(0),
            NodeTransform::from_translation(DVec3::new(0.1, 0.2, 0.3)),
            NodeContent::Mesh(cage),
        ),
        imported("Loopy", Some(1), turned, NodeContent::Mesh(loop_mesh)),
        imported(
            "Linear",
            None,
            NodeTransform::IDENTITY,
            NodeContent::Mesh(linear),
        ),
        imported(
            "Blob",
            None,
            NodeTransform::IDENTITY,
            NodeContent::Mesh(doo),
        ),
        imported(
            "Plain",
            Some(0),
            NodeTransform::IDENTITY,
            NodeContent::Mesh(plain),
        ),
        imported(
            "Ball",
            Some(0),
            turned,
            NodeContent::Surface(Arc::new(SurfaceShape::Nurbs(sphere))),
        ),
        imported(
            "Ring",
            None,
            NodeTransform::IDENTITY,
            NodeContent::Curve(Arc::new(CurveContent::from_nurbs(circle))),
        ),
        imported(
            "Tri",
            None,
            NodeTransform::IDENTITY,
            NodeContent::Surface(Arc::new(SurfaceShape::Triangle(triangle))),
        ),
        imported("Fin", None, NodeTransform::IDENTITY, fin()),
        imported(
            "Hidden",
            Some(0),
            NodeTransform::IDENTITY,
            NodeContent::Empty,
        ),
    ];
    let mut session = Session::new();
    session.import(&nodes, "Build");
    let hidden = session.doc.find_by_name("Hidden").unwrap().id;
    session
        .execute(&hedra_doc::command::Command::SetVisible {
            nodes: vec![hedra_doc::command::NodeRef::Id(hidden.0)],
            visible: false,
        })
        .unwrap();
    session.doc
}

/// What the export writes for a mesh node: the mesh, its creases and the
/// subdivision kept live (none when it was evaluated), by the rules of
/// `docs/exchange.md`.
fn written_mesh(c: &MeshContent) -> (HalfEdgeMesh, Creases, Option<SubdivisionModifier>) {
    match c.subdivision {
        Some(s) if s.options.scheme != Scheme::DooSabin => {
            if let Some(e) = c.smooth_cage().unwrap() {
                return (e.mesh.into_owned(), e.creases.into_owned(), Some(s));
            }
            let e = c.evaluate(s.export_level).unwrap();
            (e.mesh.into_owned(), e.creases.into_owned(), None)
        }
        Some(s) => {
            let e = c.evaluate(s.export_level).unwrap();
            (e.mesh.into_owned(), e.creases.into_owned(), None)
        }
        None => {
            let e = c.evaluate(0).unwrap();
            (e.mesh.into_owned(), e.creases.into_owned(), None)
        }
    }
}

/// A taper by bits: start, end, each edge (as vertex indices) with its
/// fraction.
type Taper = (u64, u64, Vec<((usize, usize), u64)>);

/// A mesh and its tags by vertex and face index (as USD numbers them).
#[derive(Debug, PartialEq)]
struct Indexed {
    points: Vec<[u64; 3]>,
    faces: Vec<Vec<usize>>,
    /// Edge (lower index, higher index) → sharpness, plain creases.
    edges: BTreeMap<(usize, usize), u64>,
    /// Each taper: start, end, and its edges with their fractions.
    tapers: Vec<Taper>,
    corners: BTreeMap<usize, u64>,
    holes: Vec<usize>,
    uvs: Vec<Vec<Option<[u64; 2]>>>,
}

fn indexed(m: &HalfEdgeMesh, c: &Creases, corners: Option<&CornerAttributes>) -> Indexed {
    let mut index = BTreeMap::new();
    for (i, v) in m.vertices().enumerate() {
        index.insert(v, i);
    }
    let pair = |e| {
        let [a, b] = m.edge_vertices(e);
        let (a, b) = (index[&a], index[&b]);
        (a.min(b), a.max(b))
    };
    let faces: Vec<_> = m.faces().collect();
    Indexed {
        points: m
            .vertices()
            .map(|v| m.position(v).to_array().map(f64::to_bits))
            .collect(),
        faces: faces
            .iter()
            .map(|&f| m.face_vertices(f).map(|v| index[&v]).collect())
            .collect(),
        edges: c
            .edges
            .iter()
            .filter(|(e, s)| m.is_edge(**e) && **s > 0.0)
            .map(|(e, s)| (pair(*e), s.to_bits()))
            .collect(),
        tapers: c
            .tapers
            .iter()
            .map(|t| {
                (
                    t.start.to_bits(),
                    t.end.to_bits(),
                    t.edges
                        .iter()
                        .map(|(e, f)| (pair(*e), f.to_bits()))
                        .collect(),
                )
            })
            .collect(),
        corners: c
            .vertices
            .iter()
            .map(|(v, s)| (index[v], s.to_bits()))
            .collect(),
        holes: faces
            .iter()
            .enumerate()
            .filter(|(_, f)| c.holes.contains(f))
            .map(|(k, _)| k)
            .collect(),
        uvs: match corners {
            Some(a) if !a.uvs.is_empty() => faces
                .iter()
                .map(|&f| {
                    m.face_halfedges(f)
                        .map(|h| a.uvs.get(&h).map(|uv| uv.to_array().map(f64::to_bits)))
                        .collect()
                })
                .collect(),
            _ => Vec::new(),
        },
    }
}

/// The nodes a USD export writes: visible tree, not inside a CSG node.
fn written_nodes(doc: &Document) -> Vec<&Node> {
    let tree = doc.hierarchy();
    doc.nodes()
        .filter(|n| tree.facts(n.id).is_some_and(|f| !f.inside_csg))
        .collect()
}

fn close(a: f64, b: f64, what: &str) {
    assert!(
        (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
        "{what}: usd-core reads {a}, Hedra has {b}"
    );
}

/// Equal within 1e-12 (relative above 1): JSON numbers pass through
/// Python's and serde_json's decimal forms.
fn same(read: &[f64], want: &[f64], what: &str) {
    assert_eq!(read.len(), want.len(), "{what}: count");
    for (k, (a, b)) in read.iter().zip(want).enumerate() {
        close(*a, *b, &format!("{what}[{k}]"));
    }
}

fn floats(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(a) => a.iter().flat_map(floats).collect(),
        Value::Number(n) => vec![n.as_f64().unwrap()],
        _ => Vec::new(),
    }
}

fn ints(v: &Value) -> Vec<i64> {
    floats(v).into_iter().map(|x| x as i64).collect()
}

fn f32s(points: &[DVec3]) -> Vec<f64> {
    points
        .iter()
        .flat_map(|p| p.to_array().map(|x| x as f32 as f64))
        .collect()
}

/// Compares what usd-core read with the document, node by node.
fn compare_with_pxr(scene: &str, doc: &Document, json: &Value) {
    let prims = json["prims"].as_array().unwrap();
    let by_name: BTreeMap<&str, &Value> = prims
        .iter()
        .filter_map(|p| Some((p["hedra_name"].as_str()?, p)))
        .collect();
    let by_path: BTreeMap<&str, &Value> = prims
        .iter()
        .map(|p| (p["path"].as_str().unwrap(), p))
        .collect();
    let nodes = written_nodes(doc);
    assert_eq!(by_name.len(), nodes.len(), "{scene}: one Xform per node");
    for node in nodes {
        let what = format!("{scene}: node '{}'", node.name);
        let xform = by_name
            .get(node.name.as_str())
            .unwrap_or_else(|| panic!("{what}: no prim"));
        assert_eq!(xform["type"], "Xform", "{what}");
        // usd-core's local matrix (row vectors) is Hedra's, transposed.
        let m = node.transform.to_matrix().to_cols_array();
        for (k, (a, b)) in floats(&xform["local"]).iter().zip(m).enumerate() {
            close(*a, b, &format!("{what}: local[{k}]"));
        }
        let path = format!("{}/Geom", xform["path"].as_str().unwrap());
        let geom = by_path.get(path.as_str());
        match &node.content {
            NodeContent::Empty => assert!(geom.is_none(), "{what}: an empty has no geometry"),
            NodeContent::Mesh(c) => {
                let g = geom.unwrap_or_else(|| panic!("{what}: no Geom"));
                assert_eq!(g["type"], "Mesh", "{what}");
                let (m, creases, sub) = written_mesh(c);
                let ix = indexed(&m, &creases, None);
                let points: Vec<DVec3> = m.vertices().map(|v| m.position(v)).collect();
                same(
                    &floats(&g["points"]),
                    &f32s(&points),
                    &format!("{what}: points"),
                );
                let counts: Vec<i64> = ix.faces.iter().map(|f| f.len() as i64).collect();
                assert_eq!(ints(&g["faceVertexCounts"]), counts, "{what}: counts");
                let flat: Vec<i64> = ix.faces.iter().flatten().map(|&i| i as i64).collect();
                assert_eq!(ints(&g["faceVertexIndices"]), flat, "{what}: indices");
                let scheme = match sub.map(|s| s.options.scheme) {
                    None => "none",
                    Some(Scheme::CatmullClark) => "catmullClark",
                    Some(Scheme::Loop) => "loop",
                    Some(Scheme::Linear) => "bilinear",
                    Some(Scheme::DooSabin) => unreachable!(),
                };
                assert_eq!(g["subdivisionSchemeResolved"], scheme, "{what}: scheme");
                if let Some(s) = sub {
                    let boundary = match s.options.boundary {
                        BoundaryInterpolation::None => "none",
                        BoundaryInterpolation::EdgesOnly => "edgeOnly",
                        BoundaryInterpolation::EdgesAndCorners => "edgeAndCorner",
                    };
                    assert_eq!(g["interpolateBoundaryResolved"], boundary, "{what}");
                    let rule = if s.options.smooth_triangles {
                        "smooth"
                    } else {
                        "catmullClark"
                    };
                    assert_eq!(g["triangleSubdivisionRule"], rule, "{what}");
                } else {
                    let interpolation = match c.shading {
                        Shading::Flat => "uniform",
                        Shading::Smooth => "vertex",
                    };
                    if c.corners.normals.is_empty() {
                        assert_eq!(g["normalsInterpolation"], interpolation, "{what}");
                    }
                }
                // Creases, per edge, as usd-core reads them.
                // Sharpness is a float in USD: compared as floats (the JSON's
                // decimal form may be an ulp off as a double).
                let mut read: BTreeMap<(usize, usize), f32> = BTreeMap::new();
                let idx = ints(&g["creaseIndices"]);
                let sharp = floats(&g["creaseSharpnesses"]);
                let (mut at, mut e) = (0usize, 0usize);
                for len in ints(&g["creaseLengths"]) {
                    for w in idx[at..at + len as usize].windows(2) {
                        let (a, b) = (w[0] as usize, w[1] as usize);
                        read.insert((a.min(b), a.max(b)), sharp[e] as f32);
                        e += 1;
                    }
                    at += len as usize;
                }
                assert_eq!(e, sharp.len(), "{what}: one sharpness per crease edge");
                let mut index = BTreeMap::new();
                for (i, v) in m.vertices().enumerate() {
                    index.insert(v, i);
                }
                let expected: BTreeMap<(usize, usize), f32> = creases
                    .edge_sharpness()
                    .into_iter()
                    .filter(|(e, _)| m.is_edge(*e))
                    .map(|(e, s)| {
                        let [a, b] = m.edge_vertices(e);
                        let (a, b) = (index[&a], index[&b]);
                        ((a.min(b), a.max(b)), s as f32)
                    })
                    .collect();
                assert_eq!(read, expected, "{what}: creases");
                let corners: BTreeMap<i64, f32> = ints(&g["cornerIndices"])
                    .into_iter()
                    .zip(
                        floats(&g["cornerSharpnesses"])
                            .into_iter()
                            .map(|s| s as f32),
                    )
                    .collect();
                let expected: BTreeMap<i64, f32> = ix
                    .corners
                    .iter()
                    .map(|(i, s)| (*i as i64, f64::from_bits(*s) as f32))
                    .collect();
                assert_eq!(corners, expected, "{what}: corners");
                let holes: Vec<i64> = ix.holes.iter().map(|&h| h as i64).collect();
                assert_eq!(ints(&g["holeIndices"]), holes, "{what}: holes");
                if sub.is_some() && c.modifiers.is_empty() && !c.corners.uvs.is_empty() {
                    let st = &g["st"];
                    assert_eq!(st["interpolation"], "faceVarying", "{what}");
                    let values = floats(&st["values"]);
                    let st_ix = ints(&st["indices"]);
                    let want = indexed(&m, &creases, Some(&c.corners)).uvs;
                    let got: Vec<[f64; 2]> = st_ix
                        .iter()
                        .map(|&i| [values[2 * i as usize], values[2 * i as usize + 1]])
                        .collect();
                    let want: Vec<[f64; 2]> = want
                        .iter()
                        .flatten()
                        .map(|uv| uv.unwrap().map(|b| f64::from_bits(b) as f32 as f64))
                        .collect();
                    same(&got.concat(), &want.concat(), &format!("{what}: UVs"));
                }
            }
            NodeContent::Surface(s) => {
                let g = geom.unwrap_or_else(|| panic!("{what}: no Geom"));
                match s.as_ref() {
                    SurfaceShape::Nurbs(sf) => {
                        assert_eq!(g["type"], "NurbsPatch", "{what}");
                        let (du, dv) = sf.degrees();
                        let (nu, nv) = sf.size();
                        let (ku, kv) = sf.knots();
                        assert_eq!(g["uOrder"], du as i64 + 1, "{what}");
                        assert_eq!(g["vOrder"], dv as i64 + 1, "{what}");
                        assert_eq!(g["uVertexCount"], nu as i64, "{what}");
                        assert_eq!(g["vVertexCount"], nv as i64, "{what}");
                        same(&floats(&g["uKnots"]), ku, &format!("{what}: u knots"));
                        same(&floats(&g["vKnots"]), kv, &format!("{what}: v knots"));
                        assert_eq!(floats(&g["uRange"]), [ku[du], ku[nu]], "{what}");
                        // USD: u varies fastest.
                        let points: Vec<DVec3> = (0..nv)
                            .flat_map(|j| (0..nu).map(move |i| sf.points()[i * nv + j]))
                            .collect();
                        same(
                            &floats(&g["points"]),
                            &f32s(&points),
                            &format!("{what}: points"),
                        );
                        let w: Vec<f64> = (0..nv)
                            .flat_map(|j| (0..nu).map(move |i| sf.weights()[i * nv + j]))
                            .collect();
                        let read = floats(&g["pointWeights"]);
                        if read.is_empty() {
                            assert!(w.iter().all(|&x| x == 1.0), "{what}: weights");
                        } else {
                            same(&read, &w, &format!("{what}: weights"));
                        }
                    }
                    SurfaceShape::Triangle(_) => {
                        assert_eq!(g["type"], "Mesh", "{what}: a triangle's tessellation");
                        assert_eq!(g["subdivisionSchemeResolved"], "none", "{what}");
                        assert!(!floats(&g["points"]).is_empty(), "{what}");
                    }
                }
            }
            NodeContent::Curve(c) => {
                let g = geom.unwrap_or_else(|| panic!("{what}: no Geom"));
                assert_eq!(g["type"], "NurbsCurves", "{what}");
                let n = c.nurbs();
                assert_eq!(ints(&g["order"]), [n.degree() as i64 + 1], "{what}");
                assert_eq!(ints(&g["curveVertexCounts"]), [n.points().len() as i64]);
                same(&floats(&g["knots"]), n.knots(), &format!("{what}: knots"));
                same(
                    &floats(&g["points"]),
                    &f32s(n.points()),
                    &format!("{what}: points"),
                );
                let read = floats(&g["pointWeights"]);
                if read.is_empty() {
                    assert!(n.is_polynomial(), "{what}: weights");
                } else {
                    same(&read, n.weights(), &format!("{what}: weights"));
                }
            }
            NodeContent::Kept(k) => {
                // As usd-core reads it: the faces as they are, the scheme live.
                let g = geom.unwrap_or_else(|| panic!("{what}: no Geom"));
                assert_eq!(g["type"], "Mesh", "{what}");
                same(
                    &floats(&g["points"]),
                    &f32s(&k.mesh.positions),
                    &format!("{what}: points"),
                );
                let counts: Vec<i64> = k.mesh.faces.iter().map(|f| f.len() as i64).collect();
                assert_eq!(ints(&g["faceVertexCounts"]), counts, "{what}: counts");
                let flat: Vec<i64> = k.mesh.faces.iter().flatten().map(|&i| i as i64).collect();
                assert_eq!(ints(&g["faceVertexIndices"]), flat, "{what}: indices");
                assert_eq!(
                    g["subdivisionSchemeResolved"], "catmullClark",
                    "{what}: scheme"
                );
            }
            NodeContent::Csg(_) => {
                let g = geom.unwrap_or_else(|| panic!("{what}: no Geom"));
                assert_eq!(g["type"], "Mesh", "{what}: the solid");
                let counts =
                    hedra_doc::export::written_counts(doc, node.id, ExportShape::Evaluated)
                        .unwrap()
                        .unwrap();
                assert_eq!(floats(&g["points"]).len(), 3 * counts.vertices, "{what}");
                assert_eq!(ints(&g["faceVertexCounts"]).len(), counts.faces, "{what}");
            }
        }
    }
}

/// Compares the document imported back with the one written.
fn compare_round_trip(scene: &str, doc: &Document, back: &Document) {
    let nodes = written_nodes(doc);
    assert_eq!(back.node_count(), nodes.len(), "{scene}: node count");
    for node in nodes {
        let what = format!("{scene}: node '{}'", node.name);
        let b = back
            .find_by_name(&node.name)
            .unwrap_or_else(|| panic!("{what}: not imported back"));
        let parent = |d: &Document, n: &Node| n.parent.map(|p| d.node(p).unwrap().name.clone());
        assert_eq!(parent(back, b), parent(doc, node), "{what}: parent");
        assert_eq!(b.transform, node.transform, "{what}: transform to the bit");
        assert_eq!(b.visible, node.visible, "{what}: visibility");
        match (&node.content, &b.content) {
            (NodeContent::Empty, NodeContent::Empty) => {}
            (NodeContent::Mesh(c), NodeContent::Mesh(r)) => {
                let (m, creases, sub) = written_mesh(c);
                let corners = (c.modifiers.is_empty()
                    && c.subdivision
                        .is_none_or(|s| s.options.scheme != Scheme::DooSabin))
                .then_some(&c.corners);
                assert_eq!(
                    indexed(&r.mesh, &r.creases, Some(&r.corners)),
                    indexed(&m, &creases, corners),
                    "{what}: cage, creases, tapers, corners, holes, UVs"
                );
                let levels = |s: Option<SubdivisionModifier>| {
                    s.map(|s| (s.options, s.viewport_level, s.export_level, s.show_cage))
                };
                assert_eq!(levels(r.subdivision), levels(sub), "{what}: subdivision");
                assert_eq!(r.shading, c.shading, "{what}: shading");
            }
            (NodeContent::Surface(s), NodeContent::Surface(r)) => {
                assert_eq!(r, s, "{what}: surface");
            }
            (NodeContent::Kept(k), NodeContent::Kept(r)) => {
                assert_eq!(r.mesh, k.mesh, "{what}: faces as they are");
                let levels = |s: Option<SubdivisionModifier>| {
                    s.map(|s| {
                        (
                            s.options.scheme,
                            s.options.boundary,
                            s.viewport_level,
                            s.export_level,
                        )
                    })
                };
                assert_eq!(
                    levels(r.subdivision),
                    levels(k.subdivision),
                    "{what}: subdivision"
                );
                assert_eq!(r.shading, k.shading, "{what}: shading");
            }
            (NodeContent::Curve(c), NodeContent::Curve(r)) => {
                assert_eq!(r.kind(), c.kind(), "{what}: curve kind");
                assert_eq!(r.nurbs(), c.nurbs(), "{what}: NURBS form");
            }
            (NodeContent::Csg(_), NodeContent::Mesh(r)) => {
                let counts =
                    hedra_doc::export::written_counts(doc, node.id, ExportShape::Evaluated)
                        .unwrap()
                        .unwrap();
                assert_eq!(r.mesh.vertex_count(), counts.vertices, "{what}: solid");
                assert_eq!(r.mesh.face_count(), counts.faces, "{what}: solid");
            }
            (a, b) => panic!("{what}: {} came back as {}", a.kind(), b.kind()),
        }
    }
}

fn export(doc: &Document, file: &Path) -> Vec<String> {
    let (bytes, notes) = hedra_doc::usd::to_usd(doc, file, ExportShape::Evaluated).unwrap();
    std::fs::write(file, bytes).unwrap();
    notes
}

fn import(file: &Path) -> (Document, Vec<String>) {
    let nodes = hedra_doc::import::import_file(file).unwrap_or_else(|e| panic!("{e}"));
    // The fin is kept as it is, with a note naming its crowded edge
    // (`compare_round_trip` checks that it came back kept); other notes
    // are what the tests look for.
    let report = hedra_doc::import::describe_repairs(&nodes)
        .into_iter()
        .filter(|l| !(l.starts_with("1 object(s) kept as in the file") || l.starts_with("  Fin: ")))
        .collect();
    let mut s = Session::new();
    s.import(&nodes, "Import");
    (s.doc, report)
}

#[test]
fn usd_core_reads_every_export_without_error_and_as_hedra_wrote_it() {
    require_pxr();
    let dir = tempfile::tempdir().unwrap();
    for (name, doc) in scenes() {
        let file = dir.path().join(format!("{name}.usda"));
        export(&doc, &file);
        let json = pxr_read(&file);
        assert_eq!(json["errors"], Value::Array(vec![]), "{name}: usdchecker");
        assert_eq!(json["default_prim"], "/Hedra", "{name}");
        compare_with_pxr(&name, &doc, &json);
    }
}

#[test]
fn every_scene_comes_back_equal_from_usd() {
    let dir = tempfile::tempdir().unwrap();
    for (name, doc) in scenes() {
        let file = dir.path().join(format!("{name}.usda"));
        export(&doc, &file);
        let (back, report) = import(&file);
        assert!(report.is_empty(), "{name}: nothing left out: {report:?}");
        compare_round_trip(&name, &doc, &back);
    }
}

#[test]
fn the_export_report_names_what_usd_cannot_hold() {
    let dir = tempfile::tempdir().unwrap();
    let notes = export(&every_kind(), &dir.path().join("e.usda"));
    assert!(
        notes.iter().any(|n| n
            == "node 'Blob': Doo-Sabin is not a USD scheme; written as its evaluated mesh (2 levels)"),
        "{notes:?}"
    );
    assert!(
        notes
            .iter()
            .any(|n| n.starts_with("node 'Tri': USD has no triangular patch")),
        "{notes:?}"
    );
    let csg = load(&root().join("assets/samples/csg.hedra.ron"));
    let notes = export(&csg, &dir.path().join("c.usda"));
    assert!(
        notes.iter().any(|n| n.contains("CSG written as its solid")),
        "{notes:?}"
    );
    let err =
        hedra_doc::usd::to_usd(&csg, Path::new("x.usdc"), ExportShape::Evaluated).unwrap_err();
    assert!(err.to_string().contains("'.usdc'"), "{err}");
}

/// A file written by usd-core itself: an Xform hierarchy (rotateXYZ and
/// scale ops), a subdivided mesh with a per-crease sharpness, a corner and
/// a hole, a NurbsPatch, a material and a SkelRoot with a Skeleton.
const PXR_WRITER: &str = r#"
import sys
from pxr import Usd, UsdGeom, UsdShade, UsdSkel, Gf, Sdf, Vt
stage = Usd.Stage.CreateNew(sys.argv[1])
UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.y)
root = UsdGeom.Xform.Define(stage, "/World")
stage.SetDefaultPrim(root.GetPrim())
arm = UsdGeom.Xform.Define(stage, "/World/Arm")
arm.AddTranslateOp().Set(Gf.Vec3d(1, 2, 3))
arm.AddRotateXYZOp().Set(Gf.Vec3f(0, 90, 0))
arm.AddScaleOp().Set(Gf.Vec3f(2, 2, 2))
mesh = UsdGeom.Mesh.Define(stage, "/World/Arm/Box")
# A 2x1 strip of quads: points 0..5.
mesh.CreatePointsAttr([(0,0,0),(1,0,0),(2,0,0),(0,1,0),(1,1,0),(2,1,0)])
mesh.CreateFaceVertexCountsAttr([4, 4])
mesh.CreateFaceVertexIndicesAttr([0,1,4,3, 1,2,5,4])
mesh.CreateSubdivisionSchemeAttr("catmullClark")
mesh.CreateInterpolateBoundaryAttr("edgeOnly")
mesh.CreateCreaseIndicesAttr([1, 4, 0, 1, 2])
mesh.CreateCreaseLengthsAttr([2, 3])
mesh.CreateCreaseSharpnessesAttr([2.5, 1.0])
mesh.CreateCornerIndicesAttr([5])
mesh.CreateCornerSharpnessesAttr([4.0])
mesh.CreateHoleIndicesAttr([1])
patch = UsdGeom.NurbsPatch.Define(stage, "/World/Sheet")
patch.CreateUVertexCountAttr(2)
patch.CreateVVertexCountAttr(3)
patch.CreateUOrderAttr(2)
patch.CreateVOrderAttr(3)
patch.CreateUKnotsAttr([0, 0, 1, 1])
patch.CreateVKnotsAttr([0, 0, 0, 1, 1, 1])
# u varies fastest.
patch.CreatePointsAttr([(0,0,0),(1,0,0),(0,1,1),(1,1,1),(0,2,0),(1,2,0)])
patch.CreatePointWeightsAttr([1, 1, 2, 2, 1, 1])
material = UsdShade.Material.Define(stage, "/World/Looks/Red")
UsdShade.MaterialBindingAPI.Apply(mesh.GetPrim()).Bind(material)
skel_root = UsdSkel.Root.Define(stage, "/World/Rig")
UsdSkel.Skeleton.Define(stage, "/World/Rig/Skel")
stage.GetRootLayer().Save()
"#;

#[test]
fn a_file_written_by_usd_core_imports_with_its_subdivision_tags_and_names_what_is_not_read() {
    require_pxr();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("pxr.usda");
    let o = Command::new("python3")
        .args(["-c", PXR_WRITER])
        .arg(&file)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (doc, report) = import(&file);
    let names: Vec<&str> = doc.nodes().map(|n| n.name.as_str()).collect();
    // The material's Scope is an empty node; the material is not read.
    assert_eq!(names, ["World", "Arm", "Box", "Sheet", "Looks", "Rig"]);
    let arm = doc.find_by_name("Arm").unwrap();
    // translate · rotateY(90°) · scale 2.
    let m = arm.transform.to_matrix();
    let want = glam::DMat4::from_translation(DVec3::new(1.0, 2.0, 3.0))
        * glam::DMat4::from_rotation_y(90f64.to_radians())
        * glam::DMat4::from_scale(DVec3::splat(2.0));
    assert!(m.abs_diff_eq(want, 1e-6), "{m} vs {want}");
    let b = doc.find_by_name("Box").unwrap();
    assert_eq!(doc.node(b.parent.unwrap()).unwrap().name, "Arm");
    let NodeContent::Mesh(c) = &b.content else {
        panic!("Box is a mesh");
    };
    let s = c.subdivision.expect("a subdivision modifier");
    assert_eq!(s.options.scheme, Scheme::CatmullClark);
    assert_eq!(s.options.boundary, BoundaryInterpolation::EdgesOnly);
    let ix = indexed(&c.mesh, &c.creases, None);
    assert_eq!(ix.faces, [vec![0, 1, 4, 3], vec![1, 2, 5, 4]]);
    // Per-crease sharpness: 2.5 on edge 1–4, 1.0 on both edges of 0–1–2.
    let edges: BTreeMap<(usize, usize), f64> = ix
        .edges
        .iter()
        .map(|(e, s)| (*e, f64::from_bits(*s)))
        .collect();
    assert_eq!(
        edges,
        BTreeMap::from([((1, 4), 2.5), ((0, 1), 1.0), ((1, 2), 1.0)])
    );
    assert_eq!(
        ix.corners,
        BTreeMap::from([(5, 4.0f64.to_bits())]),
        "corner"
    );
    assert_eq!(ix.holes, [1], "hole");
    let sheet = doc.find_by_name("Sheet").unwrap();
    let NodeContent::Surface(sf) = &sheet.content else {
        panic!("Sheet is a surface");
    };
    let SurfaceShape::Nurbs(sf) = sf.as_ref() else {
        panic!("a NURBS surface");
    };
    assert_eq!(sf.degrees(), (1, 2));
    assert_eq!(sf.size(), (2, 3));
    // Hedra's i·nv + j: point (u 1, v 1) is USD's 1·1 + 2 = 3rd.
    assert_eq!(sf.points()[4], DVec3::new(1.0, 1.0, 1.0));
    assert_eq!(sf.weights()[4], 2.0);
    let report = report.join("\n");
    assert!(report.contains("1 × materials"), "{report}");
    assert!(report.contains("skinning"), "{report}");
}

/// Imports `text` written as `name` in a fresh folder (with `others`
/// beside it) and returns the error.
fn refused(name: &str, text: &str, others: &[(&str, &str)]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let inner = dir.path().join("in");
    std::fs::create_dir(&inner).unwrap();
    for (n, t) in others {
        std::fs::write(dir.path().join(n), t).unwrap();
        std::fs::write(inner.join(n), t).unwrap();
    }
    let file = inner.join(name);
    std::fs::write(&file, text).unwrap();
    match hedra_doc::import::import_file(&file) {
        Ok(nodes) => panic!("{name} imported {} node(s)", nodes.len()),
        Err(e) => {
            let e = e.to_string();
            assert!(
                e.contains(&file.display().to_string()),
                "names the file: {e}"
            );
            e
        }
    }
}

const OUTSIDE: &str = "#usda 1.0\ndef Xform \"Secret\"\n{\n}\n";

#[test]
fn references_payloads_and_sublayers_outside_the_folder_are_refused_by_name() {
    let e = refused(
        "a.usda",
        "#usda 1.0\ndef Xform \"A\" (\n    references = @../outside.usda@\n)\n{\n}\n",
        &[("outside.usda", OUTSIDE)],
    );
    assert!(
        e.contains("'../outside.usda', outside the file's folder"),
        "{e}"
    );
    let e = refused(
        "b.usda",
        "#usda 1.0\ndef Xform \"B\" (\n    payload = @/etc/hostname@\n)\n{\n}\n",
        &[],
    );
    assert!(
        e.contains("'/etc/hostname', outside the file's folder"),
        "{e}"
    );
    let e = refused(
        "c.usda",
        "#usda 1.0\n(\n    subLayers = [@../outside.usda@]\n)\n",
        &[("outside.usda", OUTSIDE)],
    );
    assert!(e.contains("outside the file's folder"), "{e}");
}

#[test]
fn a_reference_inside_the_folder_is_read() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("part.usda"),
        "#usda 1.0\n(\n    defaultPrim = \"Part\"\n)\ndef Xform \"Part\"\n{\n    def Xform \"Inner\"\n    {\n    }\n}\n",
    )
    .unwrap();
    let file = dir.path().join("main.usda");
    std::fs::write(
        &file,
        "#usda 1.0\ndef Xform \"Main\" (\n    references = @./part.usda@\n)\n{\n}\n",
    )
    .unwrap();
    let (doc, _) = import(&file);
    let names: Vec<&str> = doc.nodes().map(|n| n.name.as_str()).collect();
    assert_eq!(names, ["Main", "Inner"]);
}

#[test]
fn hostile_usd_files_give_clear_errors() {
    let mesh = |body: &str| format!("#usda 1.0\ndef Mesh \"M\"\n{{\n{body}\n}}\n");
    let points = "    point3f[] points = [(0,0,0), (1,0,0), (0,1,0)]";
    // Counts far past the indices.
    let e = refused(
        "huge.usda",
        &mesh(&format!(
            "{points}\n    int[] faceVertexCounts = [2000000000]\n    int[] faceVertexIndices = [0, 1, 2]"
        )),
        &[],
    );
    assert!(e.contains("prim /M: faceVertexCounts:"), "{e}");
    // An index past the points.
    let e = refused(
        "index.usda",
        &mesh(&format!(
            "{points}\n    int[] faceVertexCounts = [3]\n    int[] faceVertexIndices = [0, 1, 7]"
        )),
        &[],
    );
    assert!(e.contains("faceVertexIndices: index 7 in face 0"), "{e}");
    // Wrong types.
    let e = refused(
        "type.usda",
        &mesh("    string points = \"many\"\n    int[] faceVertexCounts = [3]"),
        &[],
    );
    assert!(e.contains("prim /M: points"), "{e}");
    let e = refused(
        "scheme.usda",
        &mesh(&format!(
            "{points}\n    int[] faceVertexCounts = [3]\n    int[] faceVertexIndices = [0, 1, 2]\n    uniform token subdivisionScheme = \"fractal\""
        )),
        &[],
    );
    assert!(
        e.contains("subdivisionScheme: 'fractal' is not a USD scheme"),
        "{e}"
    );
    let e = refused(
        "crease.usda",
        &mesh(&format!(
            "{points}\n    int[] faceVertexCounts = [3]\n    int[] faceVertexIndices = [0, 1, 2]\n    int[] creaseIndices = [0, 1]\n    int[] creaseLengths = [5]\n    float[] creaseSharpnesses = [1]"
        )),
        &[],
    );
    assert!(e.contains("creaseLengths"), "{e}");
    let e = refused(
        "patch.usda",
        "#usda 1.0\ndef NurbsPatch \"P\"\n{\n    int uVertexCount = 1000000\n    int vVertexCount = 1000000\n    int uOrder = 2\n    int vOrder = 2\n    point3f[] points = [(0,0,0)]\n}\n",
        &[],
    );
    assert!(
        e.contains("prim /P: points: 1 points for 1000000 × 1000000"),
        "{e}"
    );
    // Garbage bytes as a binary crate file, and an empty text file.
    let e = refused("junk.usdc", "PXR-USDC\u{1}\u{2}garbage", &[]);
    assert!(e.contains("USD"), "{e}");
    let e = refused("empty.usda", "#usda 1.0\n", &[]);
    assert!(e.contains("contains no"), "{e}");
}

#[test]
fn sublayer_cycles_end() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.usda");
    std::fs::write(
        &a,
        "#usda 1.0\n(\n    subLayers = [@./b.usda@]\n)\ndef Xform \"A\"\n{\n}\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("b.usda"),
        "#usda 1.0\n(\n    subLayers = [@./a.usda@]\n)\ndef Xform \"B\" (\n    references = @./a.usda@\n)\n{\n}\n",
    )
    .unwrap();
    // Either read (the cycle cut) or refused by name; never a hang or a crash.
    match hedra_doc::import::import_file(&a) {
        Ok(nodes) => assert!(nodes.iter().any(|n| n.name == "A")),
        Err(e) => assert!(e.to_string().contains("a.usda"), "{e}"),
    }
}

#[test]
fn deep_nesting_is_refused_without_a_crash() {
    let deep = |n: usize| {
        let mut t = String::from("#usda 1.0\n");
        for i in 0..n {
            t.push_str(&format!("def Xform \"N{i}\" {{\n"));
        }
        t.push_str(&"}".repeat(n));
        t
    };
    let e = refused("deep.usda", &deep(5000), &[]);
    assert!(e.contains("nested deeper than 1000"), "{e}");
    // 900 levels are read (on the reader's own large stack).
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("ok.usda");
    std::fs::write(&file, deep(900)).unwrap();
    assert_eq!(hedra_doc::import::import_file(&file).unwrap().len(), 900);
}

#[test]
fn inactive_classes_and_overs_are_skipped_with_everything_below_them_as_usd_core_does() {
    require_pxr();
    let mesh = |name: &str| {
        format!(
            "def Mesh \"{name}\" {{\n int[] faceVertexCounts = [3]\n int[] faceVertexIndices = [0, 1, 2]\n point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]\n}}\n"
        )
    };
    let text = format!(
        "#usda 1.0\n\
         def Xform \"Kept\" {{\n{kept}def Xform \"Inner\" {{\n{inner}}}\n}}\n\
         def Xform \"Off\" (active = false) {{\n{off}def Xform \"OnUnderOff\" (active = true) {{\n{on_under_off}}}\n}}\n\
         class Xform \"Class\" {{\n{in_class}}}\n\
         over \"Over\" {{\n{in_over}}}\n",
        kept = mesh("KeptMesh"),
        inner = mesh("InnerMesh"),
        off = mesh("OffMesh"),
        on_under_off = mesh("OnUnderOffMesh"),
        in_class = mesh("ClassMesh"),
        in_over = mesh("OverMesh"),
    );
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("flags.usda");
    std::fs::write(&file, text).unwrap();
    let mut ours: Vec<String> = hedra_doc::import::import_file(&file)
        .unwrap()
        .into_iter()
        .map(|n| n.name)
        .collect();
    ours.sort();
    let listed = Command::new("python3")
        .args([
            "-c",
            "import sys; from pxr import Usd\n\
             s = Usd.Stage.Open(sys.argv[1])\n\
             print(' '.join(sorted(p.GetName() for p in s.Traverse())))",
        ])
        .arg(&file)
        .output()
        .expect("python3 runs");
    assert!(
        listed.status.success(),
        "{}",
        String::from_utf8_lossy(&listed.stderr)
    );
    let theirs: Vec<String> = String::from_utf8(listed.stdout)
        .unwrap()
        .split_whitespace()
        .map(str::to_string)
        .collect();
    assert_eq!(
        theirs,
        ["Inner", "InnerMesh", "Kept", "KeptMesh"],
        "usd-core's traversal"
    );
    assert_eq!(ours, theirs);
}

#[test]
fn a_prim_name_that_is_not_an_identifier_is_refused_naming_it() {
    // A fuzzed file named a prim with a thousand `/` in it: one prim became a
    // path a thousand levels deep, and the import took seconds before failing
    // (`fuzz/regressions/usd/prim_name_with_slashes_was_slow.usda`).
    let e = refused("slashes.usda", "#usda 1.0\ndef Xform \"a/b/c\" {\n}\n", &[]);
    assert!(e.contains("slashes.usda"), "{e}");
    assert!(e.contains("Invalid prim name \"a/b/c\""), "{e}");
    let long = format!("#usda 1.0\ndef Xform \"{}\" {{\n}}\n", "x/".repeat(3000));
    let e = refused("long.usda", &long, &[]);
    assert!(e.contains("Invalid prim name \"x/x/x/"), "{e}");
    assert!(e.len() < 400, "the name is shortened in the message: {e}");
    // Names of letters, digits and underscores (also beyond ASCII) are read.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("ok.usda");
    std::fs::write(&file, "#usda 1.0\ndef Xform \"_Größe_2\" {\n}\n").unwrap();
    let nodes = hedra_doc::import::import_file(&file).unwrap();
    assert_eq!(nodes.len(), 1);
}

#[cfg(unix)]
#[test]
fn a_link_out_of_the_folder_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let inner = dir.path().join("in");
    std::fs::create_dir(&inner).unwrap();
    std::fs::write(dir.path().join("secret.usda"), OUTSIDE).unwrap();
    std::os::unix::fs::symlink(dir.path().join("secret.usda"), inner.join("link.usda")).unwrap();
    let file = inner.join("main.usda");
    std::fs::write(
        &file,
        "#usda 1.0\ndef Xform \"Main\" (\n    references = @./link.usda@\n)\n{\n}\n",
    )
    .unwrap();
    let e = hedra_doc::import::import_file(&file)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("link.usda") && e.contains("outside the file's folder"),
        "{e}"
    );
}

/// usd-core turns an export into a binary crate file (`.usdc`) and a
/// package (`.usdz`); both import back equal.
#[test]
fn usdc_and_usdz_written_by_usd_core_come_back_equal() {
    require_pxr();
    let dir = tempfile::tempdir().unwrap();
    let doc = every_kind();
    let text = dir.path().join("every.usda");
    export(&doc, &text);
    let script = "import sys\n\
        from pxr import Sdf, UsdUtils\n\
        assert Sdf.Layer.FindOrOpen(sys.argv[1]).Export(sys.argv[2])\n\
        assert UsdUtils.CreateNewUsdzPackage(sys.argv[2], sys.argv[3])";
    let crate_file = dir.path().join("every.usdc");
    let package = dir.path().join("every.usdz");
    let o = Command::new("python3")
        .args(["-c", script])
        .args([&text, &crate_file, &package])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::read(&crate_file).unwrap().starts_with(b"PXR-USDC"));
    for file in [crate_file, package] {
        let (back, report) = import(&file);
        assert!(report.is_empty(), "{}: {report:?}", file.display());
        compare_round_trip(&file.display().to_string(), &doc, &back);
    }
}
