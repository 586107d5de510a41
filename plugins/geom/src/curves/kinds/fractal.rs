//! A fractal of the Koch family at a level (seed 004): its NURBS form is
//! the level's polyline (degree 1), exact.

use super::{FractalRule, KindRules, MAX_LEVEL_POINTS, NurbsForm, map_points, polyline};
use crate::curves::CurveError;
use glam::{DMat4, DVec3};

/// A fractal of the Koch family at a level: every segment of the
/// initiator polygon replaced `level` times by the rule's generator,
/// bumps on the left of each segment seen from `normal` (so a
/// clockwise triangle grows the Koch snowflake).
#[derive(Clone, Debug, PartialEq)]
pub struct Fractal {
    /// The replacement rule.
    pub rule: FractalRule,
    /// The initiator polygon (at least 2; 3 closed).
    pub points: Vec<DVec3>,
    /// How many times segments are replaced.
    pub level: u32,
    /// A closed initiator (the snowflake).
    pub closed: bool,
    /// The plane's normal; bumps go to `normal × segment`.
    pub normal: DVec3,
}

impl Fractal {
    /// The polygon at the level: every segment replaced `level` times by
    /// the rule's generator (closed: back at its first point).
    pub fn polygon(&self) -> Vec<DVec3> {
        let n = self.normal.normalize();
        let mut poly = self.points.clone();
        if self.closed {
            poly.push(self.points[0]);
        }
        let generator = self.rule.generator();
        for _ in 0..self.level {
            let mut next = vec![poly[0]];
            for w in poly.windows(2) {
                let d = w[1] - w[0];
                let side = n.cross(d);
                next.extend(generator[1..].iter().map(|&(u, v)| w[0] + u * d + v * side));
            }
            poly = next;
        }
        poly
    }
}

impl KindRules for Fractal {
    fn name(&self) -> &'static str {
        match self.rule {
            FractalRule::Koch => "Koch",
            FractalRule::QuadraticKoch => "quadratic Koch",
        }
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
        let (rule, points, level, closed, normal) = (
            self.rule,
            &self.points,
            self.level,
            self.closed,
            self.normal,
        );
        super::too_few(self.name(), super::least(closed), points.len())?;
        if !normal.is_finite() || normal.length_squared() < 1e-24 {
            return Err(CurveError::NotFiniteVector {
                what: "the fractal's plane normal",
            });
        }
        let edges = points.len() - usize::from(!closed);
        let mut max = 0;
        while edges * rule.pieces().pow(max + 1) <= MAX_LEVEL_POINTS {
            max += 1;
        }
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
    /// The normal maps by the inverse transpose.
    fn transform(&mut self, m: &DMat4) -> Result<(), CurveError> {
        self.points = map_points(m, &self.points);
        self.normal = m
            .inverse()
            .transpose()
            .transform_vector3(self.normal)
            .normalize_or_zero();
        Ok(())
    }
    /// On the initiator polygon, not on the curve.
    fn insert_at(&mut self, (i, s): (usize, f64), at: usize, _: [DVec3; 3]) -> usize {
        let n = self.points.len();
        let q = self.points[i].lerp(self.points[(i + 1) % n], s);
        self.points.insert(at, q);
        at
    }
    fn reversed(&self) -> Result<Self, CurveError> {
        Ok(Fractal {
            rule: self.rule,
            points: super::rev(&self.points, self.closed),
            level: self.level,
            closed: self.closed,
            // Koch's bump is mirror-symmetric: traced back it must stay
            // on the same side, so the normal flips. The quadratic
            // Koch generator is point-symmetric: traced back with the
            // same normal it is the same polygon.
            normal: match self.rule {
                FractalRule::Koch => -self.normal,
                FractalRule::QuadraticKoch => self.normal,
            },
        })
    }
    fn set_closed(&mut self, closed: bool) -> Result<(), CurveError> {
        self.closed = closed;
        Ok(())
    }
}
