//! The stored form of every curve kind, pinned as text: scene files and
//! their history keep `CurveKind` values in RON, so a change in how the
//! kinds are laid out in code must not change a byte of what is written
//! or stop an older file from loading. The expected texts were written by
//! the kinds as they stood before each kind became its own type.

use glam::DVec3;
use hedra_geom::curves::interpolating::Tbc;
use hedra_geom::curves::{
    CatmullRom, Chaikin, CubicHermite, CubicSpline, CurveKind, Fractal, FractalRule, Join,
    KochanekBartels, Lagrange, NurbsCurve, Parameterization, PolyBezier, QuinticHermite,
    SplineEnds,
};

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// One curve of every kind (two fractal rules, clamped spline ends), in
/// the order of `EXPECTED`.
fn every_kind() -> Vec<CurveKind> {
    let p = vec![v(0.0, 0.0, 0.0), v(1.0, 2.0, 0.0), v(3.0, 1.5, -1.0)];
    vec![
        CurveKind::Nurbs(NurbsCurve::clamped(2, p.clone()).unwrap()),
        CurveKind::Lagrange(Lagrange {
            points: p.clone(),
            parameterization: Parameterization::Chord,
        }),
        CurveKind::CubicHermite(CubicHermite {
            points: p[..2].to_vec(),
            tangents: vec![v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0)],
        }),
        CurveKind::QuinticHermite(QuinticHermite {
            points: p[..2].to_vec(),
            tangents: vec![v(1.0, 0.0, 0.0), v(0.0, 1.0, 0.0)],
            accelerations: vec![v(0.0, 0.0, 0.5), v(0.25, 0.0, 0.0)],
        }),
        CurveKind::CatmullRom(CatmullRom {
            points: p.clone(),
            parameterization: Parameterization::Centripetal,
            closed: true,
        }),
        CurveKind::KochanekBartels(KochanekBartels {
            points: p.clone(),
            keys: vec![
                Tbc::default(),
                Tbc {
                    tension: 0.5,
                    bias: -0.25,
                    continuity: 0.125,
                },
                Tbc::default(),
            ],
            closed: false,
        }),
        CurveKind::CubicSpline(CubicSpline {
            points: p.clone(),
            parameterization: Parameterization::Uniform,
            ends: SplineEnds::Clamped {
                start: v(1.0, 0.0, 0.0),
                end: v(0.0, -1.0, 0.0),
            },
        }),
        CurveKind::CubicSpline(CubicSpline {
            points: p.clone(),
            parameterization: Parameterization::Chord,
            ends: SplineEnds::Closed,
        }),
        CurveKind::Chaikin(Chaikin {
            points: p.clone(),
            level: 3,
            closed: true,
        }),
        CurveKind::PolyBezier(PolyBezier {
            points: vec![
                v(0.0, 0.0, 0.0),
                v(1.0, 0.0, 0.0),
                v(2.0, 1.0, 0.0),
                v(3.0, 1.0, 0.0),
                v(4.0, 1.0, 0.0),
                v(5.0, 0.0, 0.0),
                v(6.0, 0.0, 0.0),
            ],
            joins: vec![Join::Auto],
            closed: false,
        }),
        CurveKind::Fractal(Fractal {
            rule: FractalRule::Koch,
            points: p.clone(),
            level: 2,
            closed: true,
            normal: v(0.0, 0.0, 1.0),
        }),
        CurveKind::Fractal(Fractal {
            rule: FractalRule::QuadraticKoch,
            points: p[..2].to_vec(),
            level: 1,
            closed: false,
            normal: v(0.0, 1.0, 0.0),
        }),
    ]
}

/// `ron::to_string` of each of [`every_kind`], as the kinds wrote it when
/// they were struct variants of `CurveKind` (a newtype variant holding a
/// struct would write `Lagrange((points: …))`).
const EXPECTED: &[&str] = &[
    "Nurbs((degree:2,knots:[0.0,0.0,0.0,1.0,1.0,1.0],points:[(0.0,0.0,0.0),(1.0,2.0,0.0),(3.0,1.5,-1.0)],weights:[1.0,1.0,1.0]))",
    "Lagrange(points:[(0.0,0.0,0.0),(1.0,2.0,0.0),(3.0,1.5,-1.0)],parameterization:Chord)",
    "CubicHermite(points:[(0.0,0.0,0.0),(1.0,2.0,0.0)],tangents:[(1.0,0.0,0.0),(0.0,1.0,0.0)])",
    "QuinticHermite(points:[(0.0,0.0,0.0),(1.0,2.0,0.0)],tangents:[(1.0,0.0,0.0),(0.0,1.0,0.0)],accelerations:[(0.0,0.0,0.5),(0.25,0.0,0.0)])",
    "CatmullRom(points:[(0.0,0.0,0.0),(1.0,2.0,0.0),(3.0,1.5,-1.0)],parameterization:Centripetal,closed:true)",
    "KochanekBartels(points:[(0.0,0.0,0.0),(1.0,2.0,0.0),(3.0,1.5,-1.0)],keys:[(tension:0.0,bias:0.0,continuity:0.0),(tension:0.5,bias:-0.25,continuity:0.125),(tension:0.0,bias:0.0,continuity:0.0)],closed:false)",
    "CubicSpline(points:[(0.0,0.0,0.0),(1.0,2.0,0.0),(3.0,1.5,-1.0)],parameterization:Uniform,ends:Clamped(start:(1.0,0.0,0.0),end:(0.0,-1.0,0.0)))",
    "CubicSpline(points:[(0.0,0.0,0.0),(1.0,2.0,0.0),(3.0,1.5,-1.0)],parameterization:Chord,ends:Closed)",
    "Chaikin(points:[(0.0,0.0,0.0),(1.0,2.0,0.0),(3.0,1.5,-1.0)],level:3,closed:true)",
    "PolyBezier(points:[(0.0,0.0,0.0),(1.0,0.0,0.0),(2.0,1.0,0.0),(3.0,1.0,0.0),(4.0,1.0,0.0),(5.0,0.0,0.0),(6.0,0.0,0.0)],joins:[Auto],closed:false)",
    "Fractal(rule:Koch,points:[(0.0,0.0,0.0),(1.0,2.0,0.0),(3.0,1.5,-1.0)],level:2,closed:true,normal:(0.0,0.0,1.0))",
    "Fractal(rule:QuadraticKoch,points:[(0.0,0.0,0.0),(1.0,2.0,0.0)],level:1,closed:false,normal:(0.0,1.0,0.0))",
];

#[test]
fn every_kind_is_written_as_it_always_was() {
    let kinds = every_kind();
    assert_eq!(kinds.len(), EXPECTED.len());
    for (kind, expected) in kinds.iter().zip(EXPECTED) {
        let text = ron::to_string(kind).unwrap();
        assert_eq!(&text, expected, "the stored form of {}", kind.name());
    }
}

#[test]
fn every_kind_is_read_back_equal() {
    for (kind, text) in every_kind().iter().zip(EXPECTED) {
        let read: CurveKind = ron::from_str(text).unwrap();
        assert_eq!(&read, kind, "{text}");
    }
}

/// Older files leave out the fields that have defaults (parameterization,
/// closed, ends); they still load, with the defaults.
#[test]
fn fields_older_files_leave_out_take_their_defaults() {
    let two = "[(0.0,0.0,0.0),(1.0,2.0,0.0)]";
    for (text, name) in [
        (format!("Lagrange(points:{two})"), "Lagrange"),
        (format!("CatmullRom(points:{two})"), "Catmull-Rom"),
        (
            format!(
                "KochanekBartels(points:{two},keys:[(tension:0.0,bias:0.0,continuity:0.0),(tension:0.0,bias:0.0,continuity:0.0)])"
            ),
            "Kochanek-Bartels",
        ),
        (format!("CubicSpline(points:{two})"), "C2 cubic spline"),
        (format!("Chaikin(points:{two},level:1)"), "Chaikin"),
        (
            "PolyBezier(points:[(0.0,0.0,0.0),(1.0,0.0,0.0),(2.0,1.0,0.0),(3.0,1.0,0.0)],joins:[])"
                .to_string(),
            "poly-Bézier",
        ),
        (
            format!("Fractal(rule:Koch,points:{two},level:1,normal:(0.0,0.0,1.0))"),
            "Koch",
        ),
    ] {
        let kind: CurveKind = ron::from_str(&text).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(kind.name(), name);
        assert!(!kind.is_closed(), "{text}");
        kind.check().unwrap();
        // Re-saved with every field written out.
        let again: CurveKind = ron::from_str(&ron::to_string(&kind).unwrap()).unwrap();
        assert_eq!(again, kind);
    }
}
