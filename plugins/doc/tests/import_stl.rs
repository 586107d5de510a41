//! STL files as other programs write them: ASCII headers in any case or
//! spacing, several `solid` blocks, binary files; errors that say why.

use hedra_doc::import::stl_from_bytes;

const FACETS: &str = "facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 0 1 0
 endloop
endfacet
facet normal 0 0 1
 outer loop
  vertex 1 0 0
  vertex 1 1 0
  vertex 0 1 0
 endloop
endfacet
";

fn faces(meshes: &[hedra_doc::import::ImportedMesh]) -> Vec<usize> {
    meshes
        .iter()
        .map(|m| m.mesh.as_ref().unwrap().face_count())
        .collect()
}

#[test]
fn ascii_headers_in_any_case_or_spacing_are_read() {
    for header in [
        "solid\tsquare",
        "solid",
        "   solid square",
        "SOLID square",
        "Solid",
    ] {
        let text = format!("{header}\n{FACETS}endsolid square\n");
        let meshes = stl_from_bytes(text.as_bytes(), "file", "square.stl")
            .unwrap_or_else(|e| panic!("{header:?}: {e}"));
        assert_eq!(faces(&meshes), [2], "{header:?}");
        let mesh = meshes[0].mesh.as_ref().unwrap();
        assert_eq!(mesh.vertex_count(), 4, "corners welded");
        mesh.validate().unwrap();
    }
    // Keywords in capitals too (some CAD exporters).
    let upper = format!("SOLID X\n{}ENDSOLID X\n", FACETS.to_uppercase());
    assert_eq!(
        faces(&stl_from_bytes(upper.as_bytes(), "f", "u.stl").unwrap()),
        [2]
    );
}

#[test]
fn every_solid_block_becomes_a_node_named_after_it() {
    let shifted = FACETS
        .replace("vertex 0 ", "vertex 5 ")
        .replace("vertex 1 ", "vertex 6 ");
    let text = format!("solid first\n{FACETS}endsolid first\nsolid\n{shifted}endsolid\n");
    let meshes = stl_from_bytes(text.as_bytes(), "parts", "parts.stl").unwrap();
    assert_eq!(faces(&meshes), [2, 2]);
    let names: Vec<&str> = meshes.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(
        names,
        ["first", "parts"],
        "an unnamed solid takes the file's name"
    );
}

#[test]
fn binary_files_are_still_read_and_bad_text_is_refused_by_line() {
    // A binary STL of the two triangles, its header starting with "solid"
    // as some exporters write it: the length decides.
    let mut bytes = b"solid but binary".to_vec();
    bytes.resize(80, b' ');
    bytes.extend_from_slice(&2u32.to_le_bytes());
    for tri in [
        [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ] {
        bytes.extend(std::iter::repeat_n(0u8, 12));
        for c in tri.iter().flatten() {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
        bytes.extend_from_slice(&[0, 0]);
    }
    assert_eq!(faces(&stl_from_bytes(&bytes, "b", "b.stl").unwrap()), [2]);

    let bad = format!(
        "solid s\n{}endsolid s\n",
        FACETS.replacen("vertex 1 0 0", "vertex 1 0", 1)
    );
    let e = stl_from_bytes(bad.as_bytes(), "s", "bad.stl").unwrap_err();
    assert_eq!(
        e.to_string(),
        "bad.stl: line 5, triangle 1: a vertex needs three numbers, found '1 0'"
    );
    // A triangle with two equal corners (welded into one vertex).
    let flat = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 0\nendloop\nendfacet\nendsolid\n";
    let e = stl_from_bytes(flat.as_bytes(), "s", "flat.stl")
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "flat.stl: no face could be kept: s: all 1 face(s) dropped; triangle 1 uses the same corner point twice"
    );
}

/// Report lines name STL triangles as the file counts them, over all solids.
#[test]
fn repairs_name_the_triangle_in_the_file() {
    let bad = "facet normal 0 0 1\nouter loop\nvertex 5 0 0\nvertex 6 0 0\nvertex 5 0 0\nendloop\nendfacet\n";
    let text = format!("solid a\n{FACETS}endsolid a\nsolid b\n{FACETS}{bad}endsolid b\n");
    let meshes = stl_from_bytes(text.as_bytes(), "f", "two.stl").unwrap();
    let notes = hedra_doc::import::describe_repairs(&meshes);
    assert_eq!(
        notes,
        [
            "1 of 2 object(s) repaired: 1 face(s) dropped (1 a corner used twice)",
            "  b: triangle 5 dropped: uses the same corner point twice",
        ]
    );
}
