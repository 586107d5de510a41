//! Corner attributes (UVs and custom normals) through OBJ and glTF import and
//! export, edits, the scene file and `hedra info`; OBJ objects and groups as
//! nodes.

use glam::{DVec2, DVec3};
use hedra_doc::export::{ExportOptions, ExportShape, export_bytes};
use hedra_doc::file;
use hedra_doc::gltf::gltf_from_bytes;
use hedra_doc::import::{ImportedMesh, describe_repairs, obj_from_str};
use hedra_doc::report::SceneReport;
use hedra_doc::{
    Command, CornerAttributes, FaceSet, MeshContent, NodeContent, NodeRef, Session, VertexSet,
};
use hedra_geom::HalfEdgeMesh;
use std::collections::BTreeSet;
use std::path::Path;

/// A unit cube with a UV square on every face and one normal per face, and
/// a pentagon with normals only beside a triangle without attributes.
const BOX_AND_ROOF: &str = "\
o Box
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 -1
vn 0 0 1
vn 0 -1 0
vn 1 0 0
vn 0 1 0
vn -1 0 0
f 1/1/1 4/2/1 3/3/1 2/4/1
f 5/1/2 6/2/2 7/3/2 8/4/2
f 1/1/3 2/2/3 6/3/3 5/4/3
f 2/1/4 3/2/4 7/3/4 6/4/4
f 3/1/5 4/2/5 8/3/5 7/4/5
f 4/1/6 1/2/6 5/3/6 8/4/6
o Roof
v 0 0 3
v 1 0 3
v 1.5 1 3
v 0.5 1.8 3
v -0.5 1 3
v 0 0 4
f 9//2 10//2 11//2 12//2 13//2
f 10 9 14
";

/// One face corner as text: position, UV (or "-") and normal (or "-"),
/// rounded so that f32 storage (glTF) compares equal.
fn corner_key(p: DVec3, uv: Option<DVec2>, n: Option<DVec3>) -> String {
    let r = |x: f64| {
        let v = (x * 1e5).round() / 1e5;
        if v == 0.0 { 0.0 } else { v }
    };
    format!(
        "p({} {} {}) uv{} n{}",
        r(p.x),
        r(p.y),
        r(p.z),
        uv.map_or("-".into(), |t| format!("({} {})", r(t.x), r(t.y))),
        n.map_or("-".into(), |t| format!(
            "({} {} {})",
            r(t.x),
            r(t.y),
            r(t.z)
        ))
    )
}

/// The set of (position, uv, normal) over all face corners of a mesh.
fn corner_set(mesh: &HalfEdgeMesh, c: &CornerAttributes) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for f in mesh.faces() {
        for h in mesh.face_halfedges(f) {
            out.insert(corner_key(
                mesh.position(mesh.origin(h)),
                c.uvs.get(&h).copied(),
                c.normals.get(&h).copied(),
            ));
        }
    }
    out
}

fn imported<'a>(meshes: &'a [ImportedMesh], name: &str) -> &'a ImportedMesh {
    meshes
        .iter()
        .find(|m| m.name == name)
        .unwrap_or_else(|| panic!("no node '{name}'"))
}

fn imported_set(meshes: &[ImportedMesh], name: &str) -> BTreeSet<String> {
    let m = imported(meshes, name);
    corner_set(m.mesh.as_ref().unwrap(), &m.corners)
}

/// The box's 24 corners as the OBJ text gives them, read independently.
fn expected_box_corners() -> BTreeSet<String> {
    let v = [
        [0., 0., 0.],
        [1., 0., 0.],
        [1., 1., 0.],
        [0., 1., 0.],
        [0., 0., 1.],
        [1., 0., 1.],
        [1., 1., 1.],
        [0., 1., 1.],
    ];
    let vt = [[0., 0.], [1., 0.], [1., 1.], [0., 1.]];
    let vn = [
        [0., 0., -1.],
        [0., 0., 1.],
        [0., -1., 0.],
        [1., 0., 0.],
        [0., 1., 0.],
        [-1., 0., 0.],
    ];
    let faces = [
        [1, 4, 3, 2],
        [5, 6, 7, 8],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 4, 8, 7],
        [4, 1, 5, 8],
    ];
    let mut out = BTreeSet::new();
    for (fi, face) in faces.iter().enumerate() {
        for (k, &vi) in face.iter().enumerate() {
            out.insert(corner_key(
                DVec3::from_array(v[vi - 1]),
                Some(DVec2::from_array(vt[k])),
                Some(DVec3::from_array(vn[fi])),
            ));
        }
    }
    out
}

fn session_with(meshes: &[ImportedMesh]) -> Session {
    let mut s = Session::new();
    s.import(meshes, "Import");
    s
}

fn content<'a>(s: &'a Session, name: &str) -> &'a MeshContent {
    match &s.doc.find_by_name(name).unwrap().content {
        NodeContent::Mesh(m) => m,
        other => panic!("'{name}' is a {}", other.kind()),
    }
}

/// A session with one unit cube (no attributes).
fn cube_session() -> Session {
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: hedra_geom::Primitive::Cube { size: 1.0 },
        name: None,
        parent: None,
        transform: Default::default(),
    })
    .unwrap();
    s
}

#[test]
fn obj_uvs_and_normals_land_on_the_right_corners() {
    let meshes = obj_from_str(BOX_AND_ROOF, "box.obj").unwrap();
    assert!(describe_repairs(&meshes).is_empty());
    let boxed = imported(&meshes, "Box");
    assert_eq!(boxed.corners.uvs.len(), 24);
    assert_eq!(boxed.corners.normals.len(), 24);
    assert_eq!(imported_set(&meshes, "Box"), expected_box_corners());

    // The pentagon has normals only; the triangle names no vt or vn, so it
    // gets nothing (tobj would make some up from a neighbour).
    let roof = imported(&meshes, "Roof");
    let m = roof.mesh.as_ref().unwrap();
    assert!(roof.corners.uvs.is_empty());
    assert_eq!(roof.corners.normals.len(), 5);
    for f in m.faces() {
        let hs: Vec<_> = m.face_halfedges(f).collect();
        let with_normal = hs.iter().filter(|h| roof.corners.normals.contains_key(h));
        if hs.len() == 5 {
            for h in with_normal {
                assert_eq!(roof.corners.normals[h], DVec3::Z);
            }
        } else {
            assert_eq!(with_normal.count(), 0);
        }
    }
}

#[test]
fn obj_export_and_reimport_keep_positions_uvs_and_normals_per_corner() {
    let meshes = obj_from_str(BOX_AND_ROOF, "box.obj").unwrap();
    let s = session_with(&meshes);
    let options = ExportOptions {
        shape: ExportShape::Cage,
        ..Default::default()
    };
    let bytes = export_bytes(&s.doc, Path::new("out.obj"), options).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    // Deduplicated: four UVs; six normals for the box, one for the roof.
    assert_eq!(text.lines().filter(|l| l.starts_with("vt ")).count(), 4);
    assert_eq!(text.lines().filter(|l| l.starts_with("vn ")).count(), 7);
    assert!(
        text.lines()
            .any(|l| l.starts_with("f ") && l.contains("//"))
    );
    assert!(
        text.lines()
            .any(|l| l.starts_with("f ") && !l.contains('/')),
        "the roof triangle stays plain:\n{text}"
    );
    let again = obj_from_str(&text, "out.obj").unwrap();
    for name in ["Box", "Roof"] {
        assert_eq!(
            imported_set(&again, name),
            imported_set(&meshes, name),
            "{name}"
        );
    }
    // The same through the evaluated shape (no modifier: the cage itself).
    let plain = export_bytes(&s.doc, Path::new("out.obj"), ExportOptions::default()).unwrap();
    assert_eq!(String::from_utf8(plain).unwrap(), text);
}

#[test]
fn a_subdivided_export_has_no_attributes_and_plain_meshes_stay_plain() {
    let meshes = obj_from_str(BOX_AND_ROOF, "box.obj").unwrap();
    let s = session_with(&meshes);
    let options = ExportOptions {
        shape: ExportShape::Subdivided(1),
        ..Default::default()
    };
    let text =
        String::from_utf8(export_bytes(&s.doc, Path::new("o.obj"), options).unwrap()).unwrap();
    assert!(!text.contains("vt ") && !text.contains("vn ") && !text.contains('/'));

    let s = cube_session();
    let text = String::from_utf8(
        export_bytes(&s.doc, Path::new("o.obj"), ExportOptions::default()).unwrap(),
    )
    .unwrap();
    assert!(!text.contains("vt ") && !text.contains('/'));
}

#[test]
fn obj_world_transform_turns_exported_normals() {
    let meshes = obj_from_str(BOX_AND_ROOF, "box.obj").unwrap();
    let mut s = session_with(&meshes);
    s.execute(&Command::Rotate {
        nodes: vec![NodeRef::Name("Roof".into())],
        axis: DVec3::X,
        degrees: 90.0,
    })
    .unwrap();
    let text = String::from_utf8(
        export_bytes(&s.doc, Path::new("o.obj"), ExportOptions::default()).unwrap(),
    )
    .unwrap();
    let again = obj_from_str(&text, "o.obj").unwrap();
    let roof = imported(&again, "Roof");
    // +Z turned 90° about X is -Y.
    assert_eq!(roof.corners.normals.len(), 5);
    for n in roof.corners.normals.values() {
        assert!((*n - DVec3::NEG_Y).length() < 1e-12, "{n}");
    }
}

const ONLY_GROUPS: &str = "\
v 0 0 0
v 1 0 0
v 0 1 0
v 5 0 0
v 6 0 0
v 5 1 0
g Left
f 1 2 3
g Right
f 4 5 6
";

#[test]
fn obj_groups_alone_become_top_level_nodes() {
    let meshes = obj_from_str(ONLY_GROUPS, "g.obj").unwrap();
    let names: Vec<&str> = meshes.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["Left", "Right"]);
    assert!(
        meshes
            .iter()
            .all(|m| m.parent.is_none() && m.mesh.is_some())
    );
    let s = session_with(&meshes);
    assert_eq!(s.doc.node_count(), 2);
    assert_eq!(
        content(&s, "Right")
            .mesh
            .position(hedra_geom::VertexId(0))
            .x,
        5.0
    );
}

#[test]
fn obj_objects_alone_become_top_level_nodes() {
    let text = ONLY_GROUPS.replace("g ", "o ");
    let meshes = obj_from_str(&text, "o.obj").unwrap();
    let names: Vec<&str> = meshes.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["Left", "Right"]);
    assert!(
        meshes
            .iter()
            .all(|m| m.parent.is_none() && m.mesh.is_some())
    );
}

const OBJECTS_AND_GROUPS: &str = "\
v 0 0 0
v 1 0 0
v 0 1 0
v 2 0 0
v 3 0 0
v 2 1 0
v 4 0 0
v 5 0 0
v 4 1 0
v 6 0 0
v 7 0 0
v 6 1 0
v 8 0 0
v 9 0 0
v 8 1 0
o Car
f 1 2 3
g Wheel
f 4 5 6
g Door
f 7 8 9
o Tree
g Trunk
f 10 11 12
o Cube
g Cube
f 13 14 15
";

#[test]
fn obj_objects_with_groups_become_parents_of_group_nodes() {
    let meshes = obj_from_str(OBJECTS_AND_GROUPS, "og.obj").unwrap();
    let s = session_with(&meshes);
    let node = |name: &str| s.doc.find_by_name(name).unwrap();
    let parent_name = |name: &str| {
        node(name)
            .parent
            .map(|p| s.doc.node(p).unwrap().name.clone())
    };
    // The object's own faces stay on the object's node.
    assert_eq!(node("Car").content.kind(), "mesh");
    assert_eq!(
        content(&s, "Car").mesh.position(hedra_geom::VertexId(1)).x,
        1.0
    );
    assert_eq!(parent_name("Car"), None);
    assert_eq!(parent_name("Wheel").as_deref(), Some("Car"));
    assert_eq!(parent_name("Door").as_deref(), Some("Car"));
    assert_eq!(
        content(&s, "Door").mesh.position(hedra_geom::VertexId(0)).x,
        4.0
    );
    // An object made only of groups is an empty parent.
    assert_eq!(node("Tree").content.kind(), "empty");
    assert_eq!(parent_name("Trunk").as_deref(), Some("Tree"));
    // A group named like its object is the object's own faces.
    assert_eq!(node("Cube").content.kind(), "mesh");
    assert_eq!(parent_name("Cube"), None);
    assert_eq!(s.doc.node_count(), 6);
}

#[test]
fn repaired_obj_faces_keep_their_corner_attributes() {
    // Three triangles on edge 1-2: the third is dropped; the kept ones keep
    // their own UVs.
    let text = "\
v 0 0 0
v 1 0 0
v 0.5 1 0
v 0.5 -1 0
v 0.5 0 1
vt 0.1 0.1
vt 0.2 0.2
vt 0.3 0.3
vt 0.4 0.4
vt 0.5 0.5
f 1/1 2/2 3/3
f 2/2 1/1 4/4
f 1/1 2/2 5/5
";
    let meshes = obj_from_str(text, "bad.obj").unwrap();
    assert!(!describe_repairs(&meshes).is_empty());
    let m = &meshes[0];
    let mesh = m.mesh.as_ref().unwrap();
    assert_eq!(mesh.face_count(), 2);
    assert_eq!(m.corners.uvs.len(), 6);
    for (h, uv) in m.corners.uvs.iter() {
        // vt k was put on the vertex at x = ..., so check by position.
        let p = mesh.position(mesh.origin(*h));
        let expected = match (p.x, p.y) {
            (0.0, 0.0) => 0.1,
            (1.0, 0.0) => 0.2,
            (0.5, 1.0) => 0.3,
            (0.5, -1.0) => 0.4,
            _ => panic!("unexpected corner at {p}"),
        };
        assert_eq!(*uv, DVec2::splat(expected));
    }
}

#[test]
fn gltf_and_glb_round_trip_uvs_and_normals() {
    let meshes = obj_from_str(BOX_AND_ROOF, "box.obj").unwrap();
    let s = session_with(&meshes);
    for ext in ["gltf", "glb"] {
        let path = format!("out.{ext}");
        let bytes = export_bytes(&s.doc, Path::new(&path), ExportOptions::default()).unwrap();
        if ext == "gltf" {
            let text = String::from_utf8(bytes.clone()).unwrap();
            assert!(text.contains("TEXCOORD_0") && text.contains("NORMAL"));
        }
        let back = gltf_from_bytes(&bytes, None, &path).unwrap();
        // glTF holds triangles: the quads' corners come back as triangle
        // corners, with the same (position, uv, normal) combinations.
        assert_eq!(imported_set(&back, "Box"), expected_box_corners(), "{ext}");
        let roof = imported(&back, "Roof");
        let m = roof.mesh.as_ref().unwrap();
        assert!(roof.corners.uvs.is_empty(), "no UVs: no TEXCOORD_0");
        // Stored normals where the roof had them, computed (flat) elsewhere.
        for f in m.faces() {
            for h in m.face_halfedges(f) {
                let p = m.position(m.origin(h));
                let n = roof.corners.normals[&h];
                // Only the triangle (1,0,3) (0,0,3) (0,0,4) reaches z = 4; it faces +Y.
                if p.z == 4.0 {
                    assert!((n - DVec3::Y).length() < 1e-6, "{n}");
                }
            }
        }
        assert_eq!(
            corner_set(m, &roof.corners)
                .iter()
                .filter(|k| k.contains("n(0 0 1)"))
                .count(),
            5
        );
    }
}

#[test]
fn gltf_without_uvs_writes_no_texcoords() {
    let s = cube_session();
    let bytes = export_bytes(&s.doc, Path::new("c.gltf"), ExportOptions::default()).unwrap();
    assert!(!String::from_utf8(bytes).unwrap().contains("TEXCOORD_0"));
}

#[test]
fn edits_keep_uvs_of_surviving_corners_and_drop_normals() {
    let meshes = obj_from_str(BOX_AND_ROOF, "box.obj").unwrap();
    let mut s = session_with(&meshes);
    let before = content(&s, "Box").clone();

    // Moving a vertex: every corner survives with its UV; normals go.
    s.execute(&Command::MoveVertices {
        node: NodeRef::Name("Box".into()),
        vertices: VertexSet::Ids(vec![6]),
        offset: DVec3::new(0.0, 0.0, 0.5),
    })
    .unwrap();
    let moved = content(&s, "Box");
    assert_eq!(moved.corners.uvs, before.corners.uvs);
    assert!(moved.corners.normals.is_empty());
    s.undo();
    assert_eq!(content(&s, "Box").corners, before.corners);

    // Extruding the top: corners that still exist keep their UVs, the new
    // side faces' corners have none.
    s.execute(&Command::ExtrudeRegion {
        node: NodeRef::Name("Box".into()),
        faces: FaceSet::Ids(vec![1]),
        distance: 1.0,
    })
    .unwrap();
    let after = content(&s, "Box");
    assert!(after.corners.normals.is_empty());
    assert!(after.mesh.face_count() > before.mesh.face_count());
    let mut kept = 0;
    for (h, uv) in after.corners.uvs.iter() {
        assert_eq!(before.corners.uvs.get(h), Some(uv), "{h} kept its UV");
        assert_eq!(after.mesh.origin(*h), before.mesh.origin(*h));
        kept += 1;
    }
    assert!(kept >= 20, "only {kept} UVs kept");
    let corners = CornerAttributes::corner_count(&after.mesh);
    assert!(after.corners.uvs.len() < corners);
    // The untouched bottom face keeps all four.
    let bottom: Vec<_> = after.mesh.face_halfedges(hedra_geom::FaceId(0)).collect();
    assert!(bottom.iter().all(|h| after.corners.uvs.contains_key(h)));
}

#[test]
fn flipping_normals_keeps_each_uv_on_its_corner() {
    let meshes = obj_from_str(BOX_AND_ROOF, "box.obj").unwrap();
    let mut s = session_with(&meshes);
    let uv_set = |c: &MeshContent| {
        let stripped = CornerAttributes {
            uvs: c.corners.uvs.clone(),
            normals: Default::default(),
        };
        corner_set(&c.mesh, &stripped)
    };
    let before = uv_set(content(&s, "Box"));
    s.execute(&Command::FlipNormals {
        node: NodeRef::Name("Box".into()),
    })
    .unwrap();
    let after = content(&s, "Box");
    assert!(after.corners.normals.is_empty());
    assert_eq!(after.corners.uvs.len(), 24);
    assert_eq!(uv_set(after), before);
}

#[test]
fn scene_file_round_trips_corner_attributes() {
    let meshes = obj_from_str(BOX_AND_ROOF, "box.obj").unwrap();
    let mut s = session_with(&meshes);
    s.execute(&Command::Translate {
        nodes: vec![NodeRef::Name("Box".into())],
        offset: DVec3::X,
    })
    .unwrap();
    let text = file::to_string(&s);
    assert!(text.contains("uvs:") && text.contains("normals:"));
    let back = file::from_str(&text, Path::new("a.hedra.ron")).unwrap();
    assert!(back.warnings.is_empty(), "{:?}", back.warnings);
    assert_eq!(back.session.doc, s.doc);
    assert_eq!(content(&back.session, "Box").corners.uvs.len(), 24);
    assert_eq!(file::to_string(&back.session), text);
}

#[test]
fn info_reports_corner_attributes() {
    let meshes = obj_from_str(BOX_AND_ROOF, "box.obj").unwrap();
    let s = session_with(&meshes);
    let report = SceneReport::new(&s);
    let text = report.to_text();
    assert!(
        text.contains("attributes: UVs on 24 of 24 corners, custom normals on 24 corners"),
        "{text}"
    );
    assert!(text.contains("attributes: UVs on 0 of 8 corners, custom normals on 5 corners"));
    let json = report.to_json();
    assert!(json.contains("\"uv_corners\": 24"));
}

/// Undo steps share a node's attribute maps instead of copying them: moving
/// a node keeps the very same UV map on both sides of the step.
#[test]
fn undo_steps_share_the_attribute_maps() {
    let meshes = obj_from_str(BOX_AND_ROOF, "box.obj").unwrap();
    let mut s = session_with(&meshes);
    let before = content(&s, "Box").corners.uvs.clone();
    assert!(!before.is_empty());
    s.execute(&Command::Translate {
        nodes: vec![hedra_doc::NodeRef::Name("Box".into())],
        offset: DVec3::X,
    })
    .unwrap();
    let step = s.history.done().last().unwrap();
    let sides: Vec<&MeshContent> = [&step.changes[0].before, &step.changes[0].after]
        .into_iter()
        .map(|n| match &n.as_ref().unwrap().content {
            NodeContent::Mesh(m) => m,
            _ => unreachable!(),
        })
        .collect();
    assert!(std::sync::Arc::ptr_eq(&sides[0].corners.uvs, &before));
    assert!(std::sync::Arc::ptr_eq(&sides[1].corners.uvs, &before));
    assert!(std::sync::Arc::ptr_eq(
        &content(&s, "Box").corners.uvs,
        &before
    ));
}

/// A node mirrored by a scale of −1 exports with the outside outside: the
/// OBJ and STL cube keep volume +8, and every OBJ `vn` agrees with its
/// face's winding.
#[test]
fn mirrored_nodes_export_outside_out() {
    let meshes = obj_from_str(BOX_AND_ROOF, "box.obj").unwrap();
    let mut s = session_with(&meshes);
    s.execute(&Command::SetTransforms {
        nodes: vec![(
            NodeRef::Name("Box".into()),
            hedra_doc::NodeTransform {
                scale: DVec3::new(-2.0, 2.0, 2.0),
                ..hedra_doc::NodeTransform::IDENTITY
            },
        )],
    })
    .unwrap();
    s.execute(&Command::SetVisible {
        nodes: vec![NodeRef::Name("Roof".into())],
        visible: false,
    })
    .unwrap();
    let cage = ExportOptions {
        shape: ExportShape::Cage,
        ..Default::default()
    };
    // OBJ: signed volume of the faces (fanned) and the normals' sides.
    let text = String::from_utf8(export_bytes(&s.doc, Path::new("m.obj"), cage).unwrap()).unwrap();
    let vs: Vec<DVec3> = text
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let c: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
            DVec3::new(c[0], c[1], c[2])
        })
        .collect();
    let vns: Vec<DVec3> = text
        .lines()
        .filter_map(|l| l.strip_prefix("vn "))
        .map(|l| {
            let c: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
            DVec3::new(c[0], c[1], c[2])
        })
        .collect();
    let mut volume = 0.0;
    for line in text.lines().filter_map(|l| l.strip_prefix("f ")) {
        let corners: Vec<(usize, Option<usize>)> = line
            .split(' ')
            .map(|w| {
                let mut p = w.split('/');
                let v = p.next().unwrap().parse::<usize>().unwrap() - 1;
                let vn = p
                    .nth(1)
                    .and_then(|x| x.parse::<usize>().ok())
                    .map(|i| i - 1);
                (v, vn)
            })
            .collect();
        let p: Vec<DVec3> = corners.iter().map(|(v, _)| vs[*v]).collect();
        let mut normal = DVec3::ZERO;
        for i in 1..p.len() - 1 {
            volume += p[0].dot(p[i].cross(p[i + 1])) / 6.0;
            normal += (p[i] - p[0]).cross(p[i + 1] - p[0]);
        }
        for (_, vn) in &corners {
            if let Some(n) = vn {
                assert!(vns[*n].dot(normal) > 0.0, "vn {n} against its face");
            }
        }
    }
    assert!((volume - 8.0).abs() < 1e-9, "OBJ volume {volume}");
    // STL (ASCII and binary): the same volume, normals along the winding.
    for ascii_stl in [true, false] {
        let options = ExportOptions { ascii_stl, ..cage };
        let bytes = export_bytes(&s.doc, Path::new("m.stl"), options).unwrap();
        let back = hedra_doc::import::stl_from_bytes(&bytes, "m", "m.stl").unwrap();
        let m = back[0].mesh.as_ref().unwrap();
        let mut volume = 0.0;
        for f in m.faces() {
            let p: Vec<DVec3> = m.face_vertices(f).map(|v| m.position(v)).collect();
            volume += p[0].dot(p[1].cross(p[2])) / 6.0;
        }
        assert!((volume - 8.0).abs() < 1e-4, "STL volume {volume}");
    }
}

/// Corner attributes are stored once in the scene file however many
/// history steps hold them, as flat lists, and load back exactly.
#[test]
fn corner_attributes_are_stored_once_and_load_back_exactly() {
    let meshes = obj_from_str(BOX_AND_ROOF, "box.obj").unwrap();
    let mut s = session_with(&meshes);
    // More steps that keep the attributes (a move of the nodes).
    for _ in 0..3 {
        s.execute(&Command::Translate {
            nodes: vec![NodeRef::Name("Box".into()), NodeRef::Name("Roof".into())],
            offset: DVec3::X,
        })
        .unwrap();
    }
    let text = file::to_string(&s);
    // Box (UVs and normals) and Roof (normals): two corner sets, once each.
    assert_eq!(text.matches("normal_halfedges:").count(), 2, "{text}");
    assert_eq!(text.matches("uv_halfedges:").count(), 1);
    assert!(text.matches("corner_set:").count() >= 2 + 2 + 3 * 4);
    let again = file::from_str(&text, Path::new("box.hedra.ron"))
        .unwrap()
        .session;
    assert_eq!(again.doc, s.doc);
    assert_eq!(again.history, s.history);
    // The loaded nodes share one map per set, as the saved ones did.
    let corners = |s: &Session, name: &str| match &s.doc.find_by_name(name).unwrap().content {
        NodeContent::Mesh(m) => m.corners.clone(),
        _ => unreachable!(),
    };
    let step = &again.history.done().last().unwrap().changes[0];
    let NodeContent::Mesh(before) = &step.before.as_ref().unwrap().content else {
        unreachable!()
    };
    let now = corners(&again, &step.before.as_ref().unwrap().name);
    assert!(std::sync::Arc::ptr_eq(
        &before.corners.normals,
        &now.normals
    ));
}
