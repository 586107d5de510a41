//! STEP import of hostile and unusual files, without OpenCASCADE: every
//! error names the file, the line and the instance; trimmed faces and
//! curves come in as the issue says.

use hedra_doc::NodeContent;
use hedra_doc::step::step_from_bytes;
use hedra_geom::curves::Curve;

/// A minimal file around `data` (instance lines).
fn file_with(data: &str) -> String {
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{data}ENDSEC;\nEND-ISO-10303-21;\n"
    )
}

/// A good curve set holding one cubic through 4 points (lines 6 to 11).
const GOOD: &str = "#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=CARTESIAN_POINT('',(1.,0.,0.));\n#3=CARTESIAN_POINT('',(2.,1.,0.));\n#4=CARTESIAN_POINT('',(3.,1.,0.));\n#5=B_SPLINE_CURVE_WITH_KNOTS('C',3,(#1,#2,#3,#4),.UNSPECIFIED.,.F.,.F.,(4,4),(0.,1.),.UNSPECIFIED.);\n#6=GEOMETRIC_CURVE_SET('',(#5));\n";

fn import_error(data: &str) -> String {
    match step_from_bytes(file_with(data).as_bytes(), "bad.step") {
        Ok(nodes) => panic!("imported {} node(s) from a bad file", nodes.len()),
        Err(e) => e.to_string(),
    }
}

#[test]
fn hostile_files_give_clear_errors_naming_the_file_the_line_and_the_instance() {
    // The good file reads.
    let nodes = step_from_bytes(file_with(GOOD).as_bytes(), "good.step").unwrap();
    assert_eq!(nodes.len(), 1);
    assert_eq!(nodes[0].name, "C");
    let cases: Vec<(String, &str)> = vec![
        // A dangling reference.
        (
            GOOD.replace("(#1,#2,#3,#4)", "(#1,#2,#3,#99)"),
            "line 10, #5: refers to #99, which the file does not define",
        ),
        // A reference of the wrong type.
        (
            format!(
                "{}#7=DIRECTION('',(1.,0.,0.));\n",
                GOOD.replace("(#1,#2,#3,#4)", "(#1,#2,#3,#7)")
            ),
            "line 10, #5: #7 is a DIRECTION, where a CARTESIAN_POINT was expected",
        ),
        // A huge multiplicity: refused before anything is allocated.
        (
            GOOD.replace("(4,4),(0.,1.)", "(4,4000000000000),(0.,1.)"),
            "line 10, #5: the knot multiplicities add up to 4000000000004",
        ),
        // A cycle.
        (
            GOOD.replace(
                "#6=GEOMETRIC_CURVE_SET('',(#5));",
                "#6=GEOMETRIC_CURVE_SET('',(#5,#7));\n#7=GEOMETRIC_CURVE_SET('',(#6));",
            ),
            "a cycle of references: #6 → #7 → #6",
        ),
        // Wrong counts.
        (
            GOOD.replace("(4,4),(0.,1.)", "(4,4),(0.,0.5,1.)"),
            "line 10, #5: 2 knot multiplicities for 3 knots",
        ),
        (GOOD.replace("'C',3,", "'C',99,"), "line 10, #5: degree 99"),
        (
            GOOD.replace("(0.,0.,0.)", "(0.,0.)"),
            "line 6, #1: a point of 2 coordinate(s)",
        ),
        (
            GOOD.replace("(0.,1.),.UN", "(1.,0.),.UN"),
            "line 10, #5: not a valid B-spline curve",
        ),
        // Truncated.
        (GOOD[..GOOD.len() - 20].to_string(), "bad.step: line"),
        // A huge number.
        (
            GOOD.replace("(1.,0.,0.)", "(1.E400,0.,0.)"),
            "line 7, #2: '1.E400' is not a finite number",
        ),
    ];
    for (data, want) in cases {
        let e = import_error(&data);
        assert!(e.starts_with("bad.step: "), "{e}");
        assert!(e.contains(want), "expected '{want}' in: {e}");
    }
    // Not a STEP file at all, and an empty one.
    let e = step_from_bytes(b"solid x\nendsolid x\n", "bad.step")
        .unwrap_err()
        .to_string();
    assert!(e.contains("not a STEP file"), "{e}");
    let e = step_from_bytes(b"", "bad.step").unwrap_err().to_string();
    assert!(e.starts_with("bad.step: "), "{e}");
    // A face on a point.
    let e = import_error(&format!("{GOOD}#7=ADVANCED_FACE('F',(),#1,.T.);\n"));
    assert!(
        e.contains("line 12, #7: #1 is a CARTESIAN_POINT, where a surface was expected"),
        "{e}"
    );
    let e = import_error("#1=CARTESIAN_POINT('',(0.,0.,0.));\n");
    assert!(e.contains("no B-spline surface or curve"), "{e}");
}

#[test]
fn a_trimmed_face_comes_in_as_its_underlying_surface_and_the_report_says_so() {
    // One bilinear face bounded by a loop of two edges inside it.
    let data = "#1=CARTESIAN_POINT('',(0.,0.,0.));\n#2=CARTESIAN_POINT('',(0.,1.,0.));\n#3=CARTESIAN_POINT('',(1.,0.,0.));\n#4=CARTESIAN_POINT('',(1.,1.,0.));\n\
#5=B_SPLINE_SURFACE_WITH_KNOTS('S',1,1,((#1,#2),(#3,#4)),.UNSPECIFIED.,.F.,.F.,.F.,(2,2),(2,2),(0.,1.),(0.,1.),.UNSPECIFIED.);\n\
#6=CARTESIAN_POINT('',(0.25,0.25,0.));\n#7=CARTESIAN_POINT('',(0.75,0.75,0.));\n#8=VERTEX_POINT('',#6);\n#9=VERTEX_POINT('',#7);\n\
#10=EDGE_CURVE('',#8,#9,#5,.T.);\n#11=ORIENTED_EDGE('',*,*,#10,.T.);\n#12=ORIENTED_EDGE('',*,*,#10,.F.);\n#13=EDGE_LOOP('',(#11,#12));\n\
#14=FACE_OUTER_BOUND('',#13,.T.);\n#15=ADVANCED_FACE('Trimmed',(#14),#5,.T.);\n";
    let nodes = step_from_bytes(file_with(data).as_bytes(), "t.step").unwrap();
    assert_eq!(nodes.len(), 1);
    assert_eq!(nodes[0].name, "Trimmed");
    let notes = hedra_doc::import::describe_repairs(&nodes).join("\n");
    assert!(
        notes.contains(
            "not imported: the trims of 1 face(s) (their whole underlying surfaces were imported)"
        ),
        "{notes}"
    );
}

#[test]
fn a_curve_trimmed_at_parameters_comes_in_cut_there_and_reversed_when_its_sense_disagrees() {
    let basis = step_from_bytes(file_with(GOOD).as_bytes(), "good.step").unwrap();
    let Some(NodeContent::Curve(basis)) = &basis[0].content else {
        panic!("a curve")
    };
    let basis = basis.nurbs().clone();
    // Against the basis (.F.), the first trim is the later parameter.
    for (sense, t1, t2) in [("T", 0.25, 0.75), ("F", 0.75, 0.25)] {
        let data = GOOD.replace(
            "#6=GEOMETRIC_CURVE_SET('',(#5));",
            &format!("#6=GEOMETRIC_CURVE_SET('',(#7));\n#7=TRIMMED_CURVE('Cut',#5,(PARAMETER_VALUE({t1})),(PARAMETER_VALUE({t2})),.{sense}.,.PARAMETER.);"),
        );
        let nodes = step_from_bytes(file_with(&data).as_bytes(), "t.step").unwrap();
        assert_eq!(nodes.len(), 1);
        assert_eq!(nodes[0].name, "Cut");
        let Some(NodeContent::Curve(c)) = &nodes[0].content else {
            panic!("a curve")
        };
        let c = c.nurbs();
        let (a, b) = c.domain();
        let ends = if sense == "T" {
            [0.25, 0.75]
        } else {
            [0.75, 0.25]
        };
        assert!(c.point(a).distance(basis.point(ends[0])) < 1e-12, "{sense}");
        assert!(c.point(b).distance(basis.point(ends[1])) < 1e-12, "{sense}");
        assert!(
            c.point((a + b) / 2.0).distance(basis.point(0.5)) < 1e-12,
            "{sense}"
        );
    }
}

/// A real export to damage: the shapes sample (surfaces, a solid,
/// curves), or the chair's meshes as faceted shells.
fn sample_export(chair: bool) -> Vec<u8> {
    let name = if chair { "chair" } else { "shapes" };
    let path = std::path::Path::new(
        &std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"),
    )
    .join(format!("../../assets/samples/{name}.hedra.ron"));
    let doc = hedra_doc::file::load(&path).unwrap().session.doc;
    let options = hedra_doc::step::StepOptions {
        meshes: chair,
        ..Default::default()
    };
    hedra_doc::step::to_step(&doc, options, "s.step").unwrap().0
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(300))]

    /// Truncated or with bytes replaced by Part 21's own punctuation, an
    /// export never makes the reader panic: it reads (every number
    /// finite) or gives an error naming the file.
    #[test]
    fn damaged_exports_read_or_fail_with_a_named_error_never_panic(
        chair in proptest::bool::ANY,
        cut in 0.0f64..1.0,
        edits in proptest::collection::vec((0.0f64..1.0, proptest::sample::select(b"#()',;.$*=0915E-/\\".to_vec())), 0..12),
    ) {
        let mut bytes = sample_export(chair);
        for (at, b) in edits {
            let k = ((bytes.len() - 1) as f64 * at) as usize;
            bytes[k] = b;
        }
        if cut < 0.5 {
            bytes.truncate((bytes.len() as f64 * cut * 2.0) as usize);
        }
        match step_from_bytes(&bytes, "damaged.step") {
            Ok(nodes) => {
                for n in nodes {
                    match n.content {
                        Some(NodeContent::Surface(s)) => {
                            proptest::prop_assert!(s.control_points().iter().all(|p| p.is_finite()));
                        }
                        Some(NodeContent::Curve(c)) => {
                            proptest::prop_assert!(c.nurbs().points().iter().all(|p| p.is_finite()));
                        }
                        None => {
                            let m = n.mesh.as_ref();
                            proptest::prop_assert!(m.is_some(), "a node without content");
                            if let Some(m) = m {
                                proptest::prop_assert!(m.vertices().all(|v| m.position(v).is_finite()));
                                proptest::prop_assert!(m.validate().is_ok());
                            }
                        }
                        other => proptest::prop_assert!(false, "unexpected content {other:?}"),
                    }
                }
            }
            Err(e) => proptest::prop_assert!(e.to_string().starts_with("damaged.step: "), "{e}"),
        }
    }
}
