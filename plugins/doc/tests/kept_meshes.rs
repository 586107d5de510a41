//! Meshes kept as they come (issue 37): a non-manifold file imports as a
//! kept mesh, saves and loads exactly with its history, exports its faces
//! as they are, subdivides by OpenSubdiv's rules, and is repaired only by
//! Make Manifold.

use glam::DVec3;
use hedra_doc::command::{Command, NodeRef};
use hedra_doc::export::{ExportOptions, ExportShape, export_bytes};
use hedra_doc::import::{NonManifold, describe_repairs, import_file_with};
use hedra_doc::{KeptMesh, NodeContent, Session, SubdivisionModifier};
use std::path::Path;

/// Three quads on the edge from (0,0,0) to (0,0,1), flaps along +x, +y
/// and −x (file vertices 1 and 2 are the spine).
const FIN: &str = "o Fin
v 0 0 0
v 0 0 1
v 1 0 0
v 1 0 1
v 0 1 0
v 0 1 1
v -1 0 0
v -1 0 1
f 1 3 4 2
f 2 6 5 1
f 1 7 8 2
";

/// The fin's faces as corner points (independent of vertex numbering).
fn fin_faces() -> Vec<Vec<DVec3>> {
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    vec![
        vec![p(0., 0., 0.), p(1., 0., 0.), p(1., 0., 1.), p(0., 0., 1.)],
        vec![p(0., 0., 1.), p(0., 1., 1.), p(0., 1., 0.), p(0., 0., 0.)],
        vec![p(0., 0., 0.), p(-1., 0., 0.), p(-1., 0., 1.), p(0., 0., 1.)],
    ]
}

fn corner_points(k: &KeptMesh) -> Vec<Vec<DVec3>> {
    k.faces
        .iter()
        .map(|f| f.iter().map(|&v| k.positions[v as usize]).collect())
        .collect()
}

fn kept(session: &Session, name: &str) -> hedra_doc::KeptMeshContent {
    match &session.doc.find_by_name(name).expect("the node").content {
        NodeContent::Kept(k) => k.clone(),
        other => panic!("'{name}' is a {}, not a kept mesh", other.kind()),
    }
}

fn imported_fin(dir: &Path) -> Session {
    let path = dir.join("fin.obj");
    std::fs::write(&path, FIN).unwrap();
    let meshes = import_file_with(&path, NonManifold::Keep).unwrap();
    let mut session = Session::new();
    session.import(&meshes, "Import fin.obj");
    session
}

#[test]
fn a_fin_imports_kept_with_its_faces_as_in_the_file_and_its_edge_named() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fin.obj");
    std::fs::write(&path, FIN).unwrap();
    let meshes = import_file_with(&path, NonManifold::Keep).unwrap();
    assert_eq!(
        describe_repairs(&meshes),
        [
            "1 object(s) kept as in the file, not manifold: 'Fin' (Mesh ▸ Make Manifold repairs them for editing)",
            "  Fin: 1 edge(s) in 3 or more faces: 2–1 (3 faces)",
        ]
    );
    let mut session = Session::new();
    session.import(&meshes, "Import");
    let k = kept(&session, "Fin");
    assert_eq!(corner_points(&k.mesh), fin_faces());
    let places = k.mesh.places();
    assert_eq!(places.crowded_edges.len(), 1);
    assert_eq!(places.crowded_edges[0].1, 3);
    // Repair, as asked: the third face goes, the mesh is valid.
    let repaired = import_file_with(&path, NonManifold::Repair).unwrap();
    let mesh = repaired[0].mesh.as_ref().expect("a half-edge mesh");
    mesh.validate().unwrap();
    assert_eq!(mesh.face_count(), 2);
    assert!(describe_repairs(&repaired)[0].contains("1 face(s) dropped"));
}

#[test]
fn a_kept_mesh_saves_and_loads_exactly_and_its_history_still_undoes() {
    let dir = tempfile::tempdir().unwrap();
    let mut session = imported_fin(dir.path());
    let fin = NodeRef::Name("Fin".into());
    session
        .execute(&Command::SetSubdivision {
            nodes: vec![fin.clone()],
            modifier: Some(SubdivisionModifier::with_level(2)),
        })
        .unwrap();
    session
        .execute(&Command::Translate {
            nodes: vec![fin.clone()],
            offset: DVec3::new(0.0, 0.0, 0.5),
        })
        .unwrap();
    let before = kept(&session, "Fin");
    let text = hedra_doc::file::to_string(&session);
    // One copy of the faces for the scene and its three history steps.
    assert_eq!(text.matches("positions:").count(), 1, "{text}");
    let path = dir.path().join("fin.hedra.ron");
    let loaded = hedra_doc::file::from_str(&text, &path).unwrap();
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let mut back = loaded.session;
    assert_eq!(kept(&back, "Fin"), before);
    assert_eq!(
        hedra_doc::file::to_string(&back),
        text,
        "save → load → save"
    );
    // Undo after the reload: the move, the subdivision, the import.
    back.undo();
    back.undo();
    assert_eq!(kept(&back, "Fin").subdivision, None);
    assert_eq!(kept(&back, "Fin").mesh, before.mesh);
    back.undo();
    assert_eq!(back.doc.node_count(), 0);
    back.redo();
    assert_eq!(kept(&back, "Fin").mesh, before.mesh);
}

#[test]
fn a_hand_edited_kept_mesh_with_a_bad_face_is_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let session = imported_fin(dir.path());
    let text = hedra_doc::file::to_string(&session);
    // Face 3 names a vertex that is not there.
    let damaged = text.replacen("[0, 6, 7, 1]", "[0, 6, 70, 1]", 1);
    let damaged = if damaged == text {
        // tobj numbers the vertices in its own order: damage the last face.
        let at = text.find("faces: [").expect("the kept faces");
        let end = text[at..].find("]]").unwrap() + at;
        let last = text[..end].rfind('[').unwrap();
        format!("{}[0, 1, 99{}", &text[..last], &text[end..])
    } else {
        damaged
    };
    let e = hedra_doc::file::from_str(&damaged, Path::new("fin.hedra.ron")).unwrap_err();
    let message = e.to_string();
    assert!(
        message.contains("'Fin'") && message.contains("face 2 refers to vertex 99"),
        "{message}"
    );
}

#[test]
fn export_writes_the_faces_as_they_are() {
    let dir = tempfile::tempdir().unwrap();
    let session = imported_fin(dir.path());
    let cage = ExportOptions {
        shape: ExportShape::Cage,
        ..ExportOptions::default()
    };
    // OBJ: three quads, the spine's two points shared by all three.
    let obj = export_bytes(&session.doc, &dir.path().join("fin.obj"), cage).unwrap();
    let text = String::from_utf8(obj).unwrap();
    let v: Vec<DVec3> = text
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let x: Vec<f64> = l.split(' ').map(|w| w.parse().unwrap()).collect();
            DVec3::new(x[0], x[1], x[2])
        })
        .collect();
    let faces: Vec<Vec<DVec3>> = text
        .lines()
        .filter_map(|l| l.strip_prefix("f "))
        .map(|l| {
            l.split(' ')
                .map(|w| v[w.parse::<usize>().unwrap() - 1])
                .collect()
        })
        .collect();
    assert_eq!(faces, fin_faces());
    // STL: two triangles per quad, each facing its quad's way.
    let stl = export_bytes(&session.doc, &dir.path().join("fin.stl"), cage).unwrap();
    let count = u32::from_le_bytes(stl[80..84].try_into().unwrap());
    assert_eq!(count, 6);
    // glTF: read back as triangles it is the same kept fin (the import
    // welds the corners and finds the same crowded edge).
    let glb = dir.path().join("fin.glb");
    std::fs::write(&glb, export_bytes(&session.doc, &glb, cage).unwrap()).unwrap();
    let meshes = import_file_with(&glb, NonManifold::Keep).unwrap();
    let mut again = Session::new();
    again.import(&meshes, "Import");
    let k = kept(&again, "Fin");
    assert_eq!(k.mesh.faces.len(), 6);
    assert_eq!(k.mesh.places().crowded_edges.len(), 1);
    assert_eq!(
        k.mesh.places().crowded_edges[0].1,
        3,
        "one triangle of each flap on the spine"
    );
}

/// Subdivided, the spine is an infinitely sharp crease (OpenSubdiv's
/// rule for non-manifold edges): its edge point is its midpoint and its
/// ends do not move, while the flaps' free corners round off.
#[test]
fn the_fin_subdivides_with_a_sharp_spine() {
    let dir = tempfile::tempdir().unwrap();
    let mut session = imported_fin(dir.path());
    session
        .execute(&Command::SetSubdivision {
            nodes: vec![NodeRef::Name("Fin".into())],
            modifier: Some(SubdivisionModifier::with_level(1)),
        })
        .unwrap();
    let k = kept(&session, "Fin");
    let level1 = k.at_level(1).unwrap();
    assert_eq!(level1.faces.len(), 12);
    for p in [DVec3::ZERO, DVec3::new(0.0, 0.0, 0.5), DVec3::Z] {
        assert!(
            level1.positions.iter().any(|q| q.distance(p) < 1e-12),
            "{p} is a point of level 1"
        );
    }
    // Export writes the modifier's export level (2): 48 quads.
    let counts = hedra_doc::export::written_counts(
        &session.doc,
        session.doc.find_by_name("Fin").unwrap().id,
        ExportShape::Evaluated,
    )
    .unwrap()
    .unwrap();
    assert_eq!(counts.faces, 48);
    // Loop refuses quads, by name.
    let loop_scheme = SubdivisionModifier {
        options: hedra_geom::SubdivisionOptions {
            scheme: hedra_geom::subdivision::Scheme::Loop,
            ..Default::default()
        },
        ..SubdivisionModifier::with_level(1)
    };
    session
        .execute(&Command::SetSubdivision {
            nodes: vec![NodeRef::Name("Fin".into())],
            modifier: Some(loop_scheme),
        })
        .unwrap();
    let e = export_bytes(
        &session.doc,
        &dir.path().join("fin.obj"),
        ExportOptions::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("'Fin'"), "{e}");
}

#[test]
fn make_manifold_repairs_reports_and_undoes() {
    let dir = tempfile::tempdir().unwrap();
    let mut session = imported_fin(dir.path());
    let applied = session
        .execute(&Command::MakeManifold {
            nodes: vec![NodeRef::Name("Fin".into())],
        })
        .unwrap();
    assert!(
        applied
            .label
            .starts_with("Make Manifold ('Fin': dropped 1 face(s)"),
        "{}",
        applied.label
    );
    let NodeContent::Mesh(m) = &session.doc.find_by_name("Fin").unwrap().content else {
        panic!("a mesh")
    };
    m.mesh.validate().unwrap();
    assert_eq!(m.mesh.face_count(), 2);
    // Now editable: an extrusion works on it.
    session
        .execute(&Command::ExtrudeFaces {
            node: NodeRef::Name("Fin".into()),
            faces: hedra_doc::FaceSet::All,
            distance: 0.1,
        })
        .unwrap();
    // Saved now, the kept mesh lives only in the history's pool; loaded,
    // undo still brings it back.
    let text = hedra_doc::file::to_string(&session);
    let mut session = hedra_doc::file::from_str(&text, Path::new("fin.hedra.ron"))
        .unwrap()
        .session;
    assert_eq!(hedra_doc::file::to_string(&session), text);
    session.undo();
    session.undo();
    assert_eq!(kept(&session, "Fin").mesh.faces.len(), 3);
    // Again on a manifold mesh: refused by name.
    let e = session
        .execute(&Command::MakeManifold {
            nodes: vec![NodeRef::Name("Nothing".into())],
        })
        .unwrap_err();
    assert!(e.to_string().contains("Nothing"), "{e}");
    // A kept mesh from a script, with a bad face, is refused by face.
    let e = session
        .execute(&Command::AddKeptMesh {
            name: "Bad".into(),
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            faces: vec![vec![0, 1, 2], vec![0, 1]],
            parent: None,
            transform: Default::default(),
        })
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "face 1 has 2 corner(s); a face needs at least 3"
    );
}

#[test]
fn info_names_where_a_kept_mesh_is_not_manifold() {
    let dir = tempfile::tempdir().unwrap();
    let session = imported_fin(dir.path());
    let report = hedra_doc::report::SceneReport::new(&session);
    let text = report.to_text();
    assert!(text.contains("#1 Fin [kept mesh]"), "{text}");
    assert!(
        text.contains("kept mesh: V 8 F 3 (12 corners), NOT manifold"),
        "{text}"
    );
    assert!(
        text.contains("not manifold (numbers from 1): 1 edge(s) in 3 or more faces:"),
        "{text}"
    );
    let json: serde_json::Value = serde_json::from_str(&report.to_json()).unwrap();
    assert_eq!(json["nodes"][0]["kept"]["crowded_edges"][0][1], 3);
}
