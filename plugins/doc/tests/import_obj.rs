//! OBJ import: objects become nodes, n-gons stay, bad faces are reported.

use hedra_doc::Session;
use hedra_doc::import::{describe_repairs, obj_from_str};

const TWO_OBJECTS: &str = "\
o Quad
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
f 1 2 3 4
o Pentagon
v 5 0 0
v 6 0 0
v 6.5 1 0
v 5.5 1.8 0
v 4.5 1 0
f 5 6 7 8 9
";

#[test]
fn objects_become_named_meshes_with_their_polygons() {
    let meshes = obj_from_str(TWO_OBJECTS, "two.obj").unwrap();
    assert_eq!(meshes.len(), 2);
    assert_eq!(meshes[0].name, "Quad");
    assert_eq!(meshes[1].name, "Pentagon");
    assert_eq!(meshes[0].mesh.as_ref().unwrap().face_count(), 1);
    assert_eq!(
        meshes[0]
            .mesh
            .as_ref()
            .unwrap()
            .face_degree(hedra_geom::FaceId(0)),
        4
    );
    assert_eq!(meshes[1].mesh.as_ref().unwrap().vertex_count(), 5);
    assert_eq!(
        meshes[1]
            .mesh
            .as_ref()
            .unwrap()
            .face_degree(hedra_geom::FaceId(0)),
        5
    );
    assert!(describe_repairs(&meshes).is_empty());

    let mut s = Session::new();
    let applied = s.import(&meshes, "Import two.obj");
    assert_eq!(applied.created.len(), 2);
    assert!(s.doc.find_by_name("Pentagon").is_some());
    s.undo();
    assert_eq!(s.doc.node_count(), 0);
}

#[test]
fn non_manifold_input_is_repaired_and_reported() {
    // Three triangles on one edge: the third is dropped and named.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 2 1 5\n";
    let meshes = obj_from_str(text, "fan.obj").unwrap();
    assert_eq!(meshes[0].mesh.as_ref().unwrap().face_count(), 2);
    meshes[0].mesh.as_ref().unwrap().validate().unwrap();
    // A summary, then the face by its line in the file, with the faces it
    // collides with.
    assert_eq!(
        describe_repairs(&meshes),
        [
            "1 of 1 object(s) repaired: 1 face(s) dropped (1 a third face on an edge)",
            "  Object 1: line 8 dropped: would be a third face on an edge already shared by line 6, line 7",
        ]
    );
}

/// Many repairs: one summary with counts by kind, then at most
/// MAX_DETAILS detail lines and how many more there are; STL triangles are
/// counted over the whole file.
#[test]
fn many_repairs_give_one_summary_and_capped_details() {
    let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for _ in 0..30 {
        text.push_str("f 1 1 2\n");
    }
    text.push_str("f 1 2 3\n");
    let meshes = obj_from_str(&text, "many.obj").unwrap();
    let notes = describe_repairs(&meshes);
    assert_eq!(
        notes[0],
        "1 of 1 object(s) repaired: 30 face(s) dropped (30 a corner used twice)"
    );
    assert_eq!(
        notes[1],
        "  Object 1: line 4 dropped: uses the same corner point twice"
    );
    assert_eq!(notes.len(), 1 + hedra_doc::import::MAX_DETAILS + 1);
    assert_eq!(notes.last().unwrap(), "  … and 10 more");
}

#[test]
fn garbage_and_empty_files_are_errors_naming_the_file() {
    let e = obj_from_str("v 0 0 0\nv 1 0 0\n", "points.obj").unwrap_err();
    assert_eq!(e.to_string(), "points.obj: contains no faces");
    let e = obj_from_str("v zero one two\nf 1 2 3\n", "bad.obj").unwrap_err();
    assert_eq!(
        e.to_string(),
        "bad.obj: line 1: a vertex needs three numbers, found 'zero one two'"
    );
    let e = obj_from_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 x 1\nf 1 2 3\n", "n.obj").unwrap_err();
    assert_eq!(
        e.to_string(),
        "n.obj: line 4: a normal needs 3 number(s), found '0 x 1'"
    );
    let e = obj_from_str("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n", "range.obj").unwrap_err();
    assert!(e.to_string().contains("range.obj"), "{e}");
}

/// Polylines (`l`) are not faces: alone they give a clear "no faces" error,
/// beside faces they are left out with a note and the faces stay.
#[test]
fn polylines_are_left_out_and_faces_kept() {
    let square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
    let e = obj_from_str(&format!("{square}l 1 2 3 4\n"), "line.obj").unwrap_err();
    assert_eq!(
        e.to_string(),
        "line.obj: no face could be kept: it has 1 polyline(s) (`l`) and no faces; Hedra imports faces"
    );
    let mixed = format!("{square}v 0 0 1\nl 1 2 3 4\nf 1 2 5\nl 4 5\nf 2 3 5\n");
    let meshes = obj_from_str(&mixed, "mixed.obj").unwrap();
    let mesh = meshes[0].mesh.as_ref().unwrap();
    assert_eq!(mesh.face_count(), 2, "the two real faces");
    mesh.validate().unwrap();
    assert_eq!(
        describe_repairs(&meshes),
        ["2 polyline(s) (`l`) left out: Hedra imports faces"]
    );
}

/// Blender 2.61 writes `usemtl` with no name; it is read as no material.
#[test]
fn an_empty_usemtl_line_is_read() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl\nf 1 2 3\n";
    let meshes = obj_from_str(text, "old.obj").unwrap();
    assert_eq!(meshes[0].mesh.as_ref().unwrap().face_count(), 1);
}

/// When every face is dropped, the error says why.
#[test]
fn dropping_every_face_says_why() {
    // A face that visits vertex 1 twice.
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 1 3\n";
    let e = obj_from_str(text, "loop.obj").unwrap_err().to_string();
    assert_eq!(
        e,
        "loop.obj: no face could be kept: all 1 face(s) dropped; line 5 uses the same corner point twice"
    );
}

/// A split vertex is named by its number in the file (tobj numbers each
/// object's vertices anew; the report maps them back).
#[test]
fn split_vertices_are_named_as_the_file_numbers_them() {
    let text = "o A\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n\
                o B\nv 0 0 5\nv 1 0 5\nv 0 1 5\nv -1 0 5\nv 0 -1 5\n\
                f 4 5 6\nf 4 7 8\n";
    let meshes = obj_from_str(text, "two.obj").unwrap();
    let notes = describe_repairs(&meshes);
    assert_eq!(
        notes,
        [
            "1 of 2 object(s) repaired: 1 vertex(es) split where separate fans of faces met",
            "  B: vertex 4 joined separate fans of faces; split into 2 copies",
        ]
    );
}

/// assimp's `concave_polygon.obj` (issue 31, item 16): one face that walks
/// round a ring's outer edge, across, round the inner edge backwards and
/// back. Imported and exported, its faces all face the file's normal (+X)
/// and cover the ring once: area 0.245, where the outer disc (1.72) and
/// the hole made into a face facing the other way (1.48) gave 3.196 and a
/// mean normal of 0.
#[test]
fn a_keyhole_face_exports_as_its_ring() {
    use hedra_doc::export::{ExportOptions, export_bytes};
    use hedra_doc::import::{NonManifold, import_file_with};
    let path = std::path::Path::new("/usr/share/assimp/models/OBJ/concave_polygon.obj");
    assert!(
        path.exists(),
        "run scripts/setup (it installs assimp-testmodels)"
    );
    // Repaired, the face is split into simple faces; kept (the default),
    // it is written as the file has it, one face.
    for (mode, note) in [
        (NonManifold::Repair, "visits a corner twice"),
        (
            NonManifold::Keep,
            "1 face(s) that visit a vertex twice: line",
        ),
    ] {
        let meshes = import_file_with(path, mode).unwrap();
        let mut s = hedra_doc::Session::new();
        s.import(&meshes, "Import");
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("ring.obj");
        let text = String::from_utf8(export_bytes(&s.doc, &out, ExportOptions::default()).unwrap())
            .unwrap();
        // Read the export's polygons back from the text.
        let v: Vec<glam::DVec3> = text
            .lines()
            .filter_map(|l| l.strip_prefix("v "))
            .map(|l| {
                let x: Vec<f64> = l.split(' ').map(|w| w.parse().unwrap()).collect();
                glam::DVec3::new(x[0], x[1], x[2])
            })
            .collect();
        let (mut total, mut unsigned, mut faces) = (glam::DVec3::ZERO, 0.0, 0);
        for l in text.lines().filter_map(|l| l.strip_prefix("f ")) {
            let corners: Vec<glam::DVec3> = l
                .split(' ')
                .map(|w| v[w.split('/').next().unwrap().parse::<usize>().unwrap() - 1])
                .collect();
            let mut area = glam::DVec3::ZERO;
            for (i, p) in corners.iter().enumerate() {
                area += 0.5 * p.cross(corners[(i + 1) % corners.len()]);
            }
            assert!(
                area.normalize().dot(glam::DVec3::X) > 0.999,
                "a face facing {area}, not the file's +X"
            );
            total += area;
            unsigned += area.length();
            faces += 1;
        }
        match mode {
            NonManifold::Repair => assert!(faces >= 2, "{faces} faces"),
            NonManifold::Keep => assert_eq!(faces, 1, "the face as in the file"),
        }
        assert!(
            (total.length() - 0.245).abs() < 0.001,
            "area {}",
            total.length()
        );
        assert!(
            (unsigned - total.length()).abs() < 1e-9,
            "faces overlap: {unsigned}"
        );
        // The import summary says what was done.
        let notes = describe_repairs(&meshes);
        assert!(
            notes.iter().any(|n| n.contains(note)),
            "{mode:?}: {notes:?}"
        );
    }
}
