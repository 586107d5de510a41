//! The Decimate modifier and command (issue 18): the progressive record
//! kept beside the modifier, saved and loaded with the scene so that a
//! reopened file needs no simplification, undo and redo of the record,
//! the level slider's command, applying, and refusals.

use hedra_doc::modifiers::decimate_key;
use hedra_doc::{
    Command, CommandError, DecimateModifier, MeshContent, MeshModifier, NodeContent, NodeRef,
    Session, file,
};
use hedra_geom::progressive::{DecimateError, DecimateTarget};
use std::path::Path;

fn session() -> Session {
    let script = r#"[
        AddPrimitive(primitive: IcoSphere(subdivisions: 3, radius: 1.0), name: "Rock"),
        AddPrimitive(primitive: Grid(x_segments: 6, z_segments: 6, size: 2.0), name: "Sheet"),
    ]"#;
    let commands = hedra_doc::script::parse(script, Path::new("test.ron")).unwrap();
    let mut s = Session::new();
    hedra_doc::script::run(&mut s, &commands, Path::new("test.ron")).unwrap();
    s
}

fn content(s: &Session, name: &str) -> MeshContent {
    match &s.doc.find_by_name(name).unwrap().content {
        NodeContent::Mesh(m) => m.clone(),
        _ => panic!("{name} is a mesh"),
    }
}

fn rock() -> NodeRef {
    NodeRef::Name("Rock".into())
}

fn decimate(target: DecimateTarget, level: Option<usize>) -> MeshModifier {
    MeshModifier::Decimate(DecimateModifier {
        target,
        level,
        ..DecimateModifier::default()
    })
}

#[test]
fn the_record_is_kept_saved_loaded_undone_and_redone_with_the_modifier() {
    let mut s = session();
    let cage = content(&s, "Rock");
    s.execute(&Command::AddModifier {
        node: rock(),
        modifier: decimate(DecimateTarget::Ratio(0.25), None),
    })
    .unwrap();
    let c = content(&s, "Rock");
    assert_eq!(
        c.decimations.len(),
        1,
        "the record is built with the modifier"
    );
    let record = c.decimations[0].clone();
    let counts = c.decimate_face_counts(0).unwrap().unwrap();
    assert_eq!(*counts.last().unwrap(), 1280);
    let shown = c.evaluated(0).unwrap();
    shown.validate().unwrap();
    assert_eq!(shown.face_count(), 320);
    assert_eq!(c.mesh, cage.mesh, "the cage is unchanged");
    // The level slider: a level of the same record, no new simplification.
    s.execute(&Command::SetModifier {
        node: rock(),
        index: 0,
        modifier: decimate(DecimateTarget::Ratio(0.25), Some(10)),
    })
    .unwrap();
    let c = content(&s, "Rock");
    assert_eq!(c.decimations[0].key, record.key);
    assert_eq!(c.decimations[0].progressive, record.progressive);
    assert_eq!(c.evaluated(0).unwrap().face_count(), counts[10]);
    // Save and load: the record comes back and still fits its input, so
    // the reopened file evaluates from it.
    let text = file::to_string(&s);
    assert!(text.contains("decimations"));
    let loaded = file::from_str(&text, Path::new("rock.hedra.ron")).unwrap();
    let back = content(&loaded.session, "Rock");
    assert_eq!(back.decimations.len(), 1);
    assert_eq!(back.decimations[0].progressive, record.progressive);
    let MeshModifier::Decimate(d) = back.modifiers[0] else {
        panic!("a Decimate modifier")
    };
    let options = d.options(Default::default());
    assert_eq!(
        decimate_key(&back.mesh, &back.creases, &options),
        back.decimations[0].key,
        "the stored record is the one of the loaded cage"
    );
    assert!(back.evaluated(0).unwrap().same_as(&c.evaluated(0).unwrap()));
    // The record is not every level: the file stays within a few times
    // the cage's own size (16 times: since format version 3 the cage is
    // stored as polygons, a third of its records, while the record's base
    // mesh keeps the record form).
    let plain = file::to_string(&session());
    assert!(
        text.len() < 16 * plain.len(),
        "{} vs {}",
        text.len(),
        plain.len()
    );
    // Undo takes the level back, then the modifier and its record; redo
    // brings both back.
    let mut s = loaded.session;
    s.undo().unwrap();
    assert_eq!(content(&s, "Rock").evaluated(0).unwrap().face_count(), 320);
    s.undo().unwrap();
    let c = content(&s, "Rock");
    assert!(c.modifiers.is_empty() && c.decimations.is_empty());
    assert_eq!(c.evaluated(0).unwrap().face_count(), 1280);
    s.redo().unwrap();
    s.redo().unwrap();
    let c = content(&s, "Rock");
    assert_eq!(c.decimations[0].progressive, record.progressive);
    assert_eq!(c.evaluated(0).unwrap().face_count(), counts[10]);
}

#[test]
fn editing_the_cage_rebuilds_the_record_and_apply_makes_the_level_the_mesh() {
    let mut s = session();
    s.execute(&Command::AddModifier {
        node: rock(),
        modifier: decimate(DecimateTarget::Faces(100), None),
    })
    .unwrap();
    let before = content(&s, "Rock").decimations[0].key;
    s.execute(&Command::FlipNormals { node: rock() }).unwrap();
    let c = content(&s, "Rock");
    assert_eq!(c.decimations.len(), 1);
    assert_ne!(
        c.decimations[0].key, before,
        "an edited cage has a new record"
    );
    assert_eq!(c.evaluated(0).unwrap().face_count(), 100);
    s.execute(&Command::ApplyModifiers {
        node: rock(),
        count: None,
    })
    .unwrap();
    let c = content(&s, "Rock");
    assert!(c.modifiers.is_empty() && c.decimations.is_empty());
    assert_eq!(c.mesh.face_count(), 100);
    c.mesh.validate().unwrap();
    assert_eq!(c.mesh.stats().genus, Some(0));
}

#[test]
fn the_decimate_command_refuses_a_target_below_the_minimum_by_name() {
    let mut s = session();
    let err = s
        .execute(&Command::Decimate {
            node: rock(),
            target: DecimateTarget::Faces(1),
            keep_borders: false,
            keep_creases: true,
            keep_uv_seams: true,
            sharp_angle: None,
            keep_quads: false,
        })
        .unwrap_err();
    let CommandError::Decimate {
        error: DecimateError::BelowMinimum { target: 1, minimum },
        ..
    } = &err
    else {
        panic!("{err:?}")
    };
    assert!(err.to_string().starts_with("'Rock' (#"));
    assert!(
        err.to_string()
            .contains(&format!("1 faces is below the {minimum}"))
    );
    // A bad ratio is a modifier value error, before any work.
    let err = s
        .execute(&Command::AddModifier {
            node: rock(),
            modifier: decimate(DecimateTarget::Ratio(0.0), None),
        })
        .unwrap_err();
    assert!(matches!(err, CommandError::ModifierValue { .. }), "{err:?}");
    // Keep borders: the sheet's 24 border vertices all stay where they are.
    let sheet = content(&s, "Sheet");
    s.execute(&Command::Decimate {
        node: NodeRef::Name("Sheet".into()),
        target: DecimateTarget::Ratio(0.4),
        keep_borders: true,
        keep_creases: true,
        keep_uv_seams: true,
        sharp_angle: None,
        keep_quads: false,
    })
    .unwrap();
    let after = content(&s, "Sheet");
    after.mesh.validate().unwrap();
    let border = |m: &hedra_geom::HalfEdgeMesh| {
        let mut b: Vec<[i64; 3]> = m
            .vertices()
            .filter(|&v| m.is_boundary_vertex(v))
            .map(|v| (m.position(v) * 1e9).round().to_array().map(|x| x as i64))
            .collect();
        b.sort();
        b
    };
    assert_eq!(border(&after.mesh), border(&sheet.mesh));
    assert_eq!(border(&after.mesh).len(), 24);
    assert!(after.mesh.face_count() < sheet.mesh.face_count() * 2);
    s.undo().unwrap();
    assert_eq!(content(&s, "Sheet").mesh, sheet.mesh);
}
