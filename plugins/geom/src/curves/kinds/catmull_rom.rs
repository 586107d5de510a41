//! The Catmull-Rom spline through the points (seed 000): Kochanek-Bartels
//! with all keys zero, with a choice of parameters; open or a closed loop.

use super::kochanek_bartels::closed_kb;
use super::{KindRules, NurbsForm, Parameterization, closed_parameters, hermite_nurbs};
use crate::curves::CurveError;
use crate::curves::interpolating::{HermiteSpline, Tbc};
use glam::DVec3;

/// The Catmull-Rom spline through the points.
#[derive(Clone, Debug, PartialEq)]
pub struct CatmullRom {
    /// The points (at least 2; 3 closed).
    pub points: Vec<DVec3>,
    /// How their parameters are chosen.
    pub parameterization: Parameterization,
    /// A closed loop (tangents wrap around).
    pub closed: bool,
}

impl CatmullRom {
    /// The Hermite spline of the Catmull-Rom tangents.
    fn spline(&self) -> Result<HermiteSpline, CurveError> {
        let (points, parameterization) = (&self.points, self.parameterization);
        let keys = vec![Tbc::default(); points.len()];
        if self.closed {
            closed_kb(points, &keys, closed_parameters(parameterization, points)?)
        } else {
            HermiteSpline::kochanek_bartels(
                parameterization.parameters(points)?,
                points.clone(),
                &keys,
            )
        }
    }
}

impl KindRules for CatmullRom {
    fn name(&self) -> &'static str {
        "Catmull-Rom"
    }
    fn points(&self) -> &[DVec3] {
        &self.points
    }
    fn points_mut(&mut self) -> Option<&mut Vec<DVec3>> {
        Some(&mut self.points)
    }
    fn is_closed(&self) -> bool {
        self.closed
    }
    fn interpolates(&self) -> bool {
        true
    }
    fn check_data(&self) -> Result<(), CurveError> {
        super::too_few(self.name(), super::least(self.closed), self.points.len())
    }
    fn hermite_form(&self) -> Result<Option<HermiteSpline>, CurveError> {
        self.spline().map(Some)
    }
    fn nurbs_form(&self) -> Result<NurbsForm, CurveError> {
        hermite_nurbs(&self.spline()?)
    }
    fn reversed(&self) -> Result<Self, CurveError> {
        Ok(CatmullRom {
            points: super::rev(&self.points, self.closed),
            parameterization: self.parameterization,
            closed: self.closed,
        })
    }
    fn set_closed(&mut self, closed: bool) -> Result<(), CurveError> {
        self.closed = closed;
        Ok(())
    }
}
