//! The stored form of a [`CurveKind`]: the struct variants the kinds were
//! before each became its own type (`Lagrange(points: […],
//! parameterization: Chord)` in RON), so that scene files and their
//! history written then load, and re-save byte for byte the same. A
//! newtype variant holding the kind's struct would be written
//! `Lagrange((points: …))`. Serialised from borrowed fields
//! ([`WireRef`]), read into owned ones ([`Wire`]) with the same defaults
//! for fields older files leave out.

use super::{
    CatmullRom, Chaikin, CubicHermite, CubicSpline, CurveKind, Fractal, FractalRule, Join,
    KochanekBartels, Lagrange, Parameterization, PolyBezier, QuinticHermite, SplineEnds,
};
use crate::curves::interpolating::Tbc;
use crate::curves::nurbs::NurbsCurve;
use glam::DVec3;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A [`CurveKind`] as written: fields in the order of the old variants.
#[derive(Serialize)]
#[serde(rename = "CurveKind")]
enum WireRef<'a> {
    Nurbs(&'a NurbsCurve),
    Lagrange {
        points: &'a [DVec3],
        parameterization: Parameterization,
    },
    CubicHermite {
        points: &'a [DVec3],
        tangents: &'a [DVec3],
    },
    QuinticHermite {
        points: &'a [DVec3],
        tangents: &'a [DVec3],
        accelerations: &'a [DVec3],
    },
    CatmullRom {
        points: &'a [DVec3],
        parameterization: Parameterization,
        closed: bool,
    },
    KochanekBartels {
        points: &'a [DVec3],
        keys: &'a [Tbc],
        closed: bool,
    },
    CubicSpline {
        points: &'a [DVec3],
        parameterization: Parameterization,
        ends: SplineEnds,
    },
    Chaikin {
        points: &'a [DVec3],
        level: u32,
        closed: bool,
    },
    PolyBezier {
        points: &'a [DVec3],
        joins: &'a [Join],
        closed: bool,
    },
    Fractal {
        rule: FractalRule,
        points: &'a [DVec3],
        level: u32,
        closed: bool,
        normal: DVec3,
    },
}

/// A [`CurveKind`] as read, with the defaults of the old variants.
#[derive(Deserialize)]
#[serde(rename = "CurveKind")]
enum Wire {
    Nurbs(NurbsCurve),
    Lagrange {
        points: Vec<DVec3>,
        #[serde(default)]
        parameterization: Parameterization,
    },
    CubicHermite {
        points: Vec<DVec3>,
        tangents: Vec<DVec3>,
    },
    QuinticHermite {
        points: Vec<DVec3>,
        tangents: Vec<DVec3>,
        accelerations: Vec<DVec3>,
    },
    CatmullRom {
        points: Vec<DVec3>,
        #[serde(default)]
        parameterization: Parameterization,
        #[serde(default)]
        closed: bool,
    },
    KochanekBartels {
        points: Vec<DVec3>,
        keys: Vec<Tbc>,
        #[serde(default)]
        closed: bool,
    },
    CubicSpline {
        points: Vec<DVec3>,
        #[serde(default)]
        parameterization: Parameterization,
        #[serde(default)]
        ends: SplineEnds,
    },
    Chaikin {
        points: Vec<DVec3>,
        level: u32,
        #[serde(default)]
        closed: bool,
    },
    PolyBezier {
        points: Vec<DVec3>,
        joins: Vec<Join>,
        #[serde(default)]
        closed: bool,
    },
    Fractal {
        rule: FractalRule,
        points: Vec<DVec3>,
        level: u32,
        #[serde(default)]
        closed: bool,
        normal: DVec3,
    },
}

impl<'a> From<&'a CurveKind> for WireRef<'a> {
    fn from(kind: &'a CurveKind) -> Self {
        match kind {
            CurveKind::Nurbs(c) => WireRef::Nurbs(c),
            CurveKind::Lagrange(k) => WireRef::Lagrange {
                points: &k.points,
                parameterization: k.parameterization,
            },
            CurveKind::CubicHermite(k) => WireRef::CubicHermite {
                points: &k.points,
                tangents: &k.tangents,
            },
            CurveKind::QuinticHermite(k) => WireRef::QuinticHermite {
                points: &k.points,
                tangents: &k.tangents,
                accelerations: &k.accelerations,
            },
            CurveKind::CatmullRom(k) => WireRef::CatmullRom {
                points: &k.points,
                parameterization: k.parameterization,
                closed: k.closed,
            },
            CurveKind::KochanekBartels(k) => WireRef::KochanekBartels {
                points: &k.points,
                keys: &k.keys,
                closed: k.closed,
            },
            CurveKind::CubicSpline(k) => WireRef::CubicSpline {
                points: &k.points,
                parameterization: k.parameterization,
                ends: k.ends,
            },
            CurveKind::Chaikin(k) => WireRef::Chaikin {
                points: &k.points,
                level: k.level,
                closed: k.closed,
            },
            CurveKind::PolyBezier(k) => WireRef::PolyBezier {
                points: &k.points,
                joins: &k.joins,
                closed: k.closed,
            },
            CurveKind::Fractal(k) => WireRef::Fractal {
                rule: k.rule,
                points: &k.points,
                level: k.level,
                closed: k.closed,
                normal: k.normal,
            },
        }
    }
}

impl From<Wire> for CurveKind {
    fn from(wire: Wire) -> Self {
        match wire {
            Wire::Nurbs(c) => CurveKind::Nurbs(c),
            Wire::Lagrange {
                points,
                parameterization,
            } => CurveKind::Lagrange(Lagrange {
                points,
                parameterization,
            }),
            Wire::CubicHermite { points, tangents } => {
                CurveKind::CubicHermite(CubicHermite { points, tangents })
            }
            Wire::QuinticHermite {
                points,
                tangents,
                accelerations,
            } => CurveKind::QuinticHermite(QuinticHermite {
                points,
                tangents,
                accelerations,
            }),
            Wire::CatmullRom {
                points,
                parameterization,
                closed,
            } => CurveKind::CatmullRom(CatmullRom {
                points,
                parameterization,
                closed,
            }),
            Wire::KochanekBartels {
                points,
                keys,
                closed,
            } => CurveKind::KochanekBartels(KochanekBartels {
                points,
                keys,
                closed,
            }),
            Wire::CubicSpline {
                points,
                parameterization,
                ends,
            } => CurveKind::CubicSpline(CubicSpline {
                points,
                parameterization,
                ends,
            }),
            Wire::Chaikin {
                points,
                level,
                closed,
            } => CurveKind::Chaikin(Chaikin {
                points,
                level,
                closed,
            }),
            Wire::PolyBezier {
                points,
                joins,
                closed,
            } => CurveKind::PolyBezier(PolyBezier {
                points,
                joins,
                closed,
            }),
            Wire::Fractal {
                rule,
                points,
                level,
                closed,
                normal,
            } => CurveKind::Fractal(Fractal {
                rule,
                points,
                level,
                closed,
                normal,
            }),
        }
    }
}

impl Serialize for CurveKind {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        WireRef::from(self).serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for CurveKind {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        Wire::deserialize(deserializer).map(CurveKind::from)
    }
}
