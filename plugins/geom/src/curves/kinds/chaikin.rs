//! Chaikin's corner cutting of a control polygon (seed 000), `level`
//! times: its NURBS form is the level's polyline (degree 1), exact.

use super::{KindRules, MAX_LEVEL_POINTS, NurbsForm, polyline};
use crate::curves::CurveError;
use crate::curves::interpolating::chaikin;
use glam::DVec3;

/// Chaikin's corner cutting of a control polygon, `level` times.
#[derive(Clone, Debug, PartialEq)]
pub struct Chaikin {
    /// The control polygon (at least 2; 3 closed).
    pub points: Vec<DVec3>,
    /// How many times the corners are cut.
    pub level: u32,
    /// A closed polygon.
    pub closed: bool,
}

impl Chaikin {
    /// The polygon at the level: the control polygon cut `level` times
    /// (closed: back at its first point).
    pub fn polygon(&self) -> Vec<DVec3> {
        let mut p = chaikin(&self.points, self.level, self.closed);
        if self.closed {
            p.push(p[0]);
        }
        p
    }
}

impl KindRules for Chaikin {
    fn name(&self) -> &'static str {
        "Chaikin"
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
    fn check_data(&self) -> Result<(), CurveError> {
        let (points, level, closed) = (&self.points, self.level, self.closed);
        super::too_few(self.name(), super::least(closed), points.len())?;
        let edges = points.len() - usize::from(!closed);
        let max = (0..=20u32)
            .take_while(|&l| edges << l <= MAX_LEVEL_POINTS)
            .last()
            .unwrap_or(0);
        if level > max {
            return Err(CurveError::LevelTooHigh { level, max });
        }
        Ok(())
    }
    fn level_polygon(&self) -> Option<Vec<DVec3>> {
        Some(self.polygon())
    }
    fn nurbs_form(&self) -> Result<NurbsForm, CurveError> {
        polyline(self.polygon())
    }
    /// On the polygon, not on the curve.
    fn insert_at(&mut self, (i, s): (usize, f64), at: usize, _: [DVec3; 3]) -> usize {
        let n = self.points.len();
        let q = self.points[i].lerp(self.points[(i + 1) % n], s);
        self.points.insert(at, q);
        at
    }
    fn reversed(&self) -> Result<Self, CurveError> {
        Ok(Chaikin {
            points: super::rev(&self.points, self.closed),
            level: self.level,
            closed: self.closed,
        })
    }
    fn set_closed(&mut self, closed: bool) -> Result<(), CurveError> {
        self.closed = closed;
        Ok(())
    }
}
