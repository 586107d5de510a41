//! Quintic Hermite segments (C2): points with first and second
//! derivatives, at parameters 0, 1, 2, … (seed 002); exact as one quintic
//! Bézier per span.

use super::cubic_hermite::{keep, move_with_handles};
use super::{KindRules, NurbsForm, TangentHandle, map_points, map_vectors};
use crate::curves::interpolating::HermiteSpline;
use crate::curves::nurbs::NurbsCurve;
use crate::curves::{CurveError, check_points};
use glam::{DMat4, DVec3};

/// Quintic Hermite segments (C2): points with first and second
/// derivatives, at parameters 0, 1, 2, … (seed 002).
#[derive(Clone, Debug, PartialEq)]
pub struct QuinticHermite {
    /// The points (at least 2).
    pub points: Vec<DVec3>,
    /// dp/dt at each point.
    pub tangents: Vec<DVec3>,
    /// d²p/dt² at each point.
    pub accelerations: Vec<DVec3>,
}

impl KindRules for QuinticHermite {
    fn name(&self) -> &'static str {
        "quintic Hermite"
    }
    fn points(&self) -> &[DVec3] {
        &self.points
    }
    fn points_mut(&mut self) -> Option<&mut Vec<DVec3>> {
        Some(&mut self.points)
    }
    fn interpolates(&self) -> bool {
        true
    }
    fn handles_editable(&self) -> bool {
        true
    }
    fn check_data(&self) -> Result<(), CurveError> {
        let (points, tangents, accelerations) = (&self.points, &self.tangents, &self.accelerations);
        super::too_few(self.name(), 2, points.len())?;
        super::count(points.len(), "tangents", tangents.len())?;
        super::count(points.len(), "accelerations", accelerations.len())?;
        check_points(tangents).map_err(|_| CurveError::NotFiniteVector { what: "a tangent" })?;
        check_points(accelerations).map_err(|_| CurveError::NotFiniteVector {
            what: "an acceleration",
        })
    }
    /// The keys at parameters 0, 1, 2, … with their tangents, for handles
    /// of degree 5 (not checked, as the handles of a broken curve are
    /// still drawn).
    fn handle_keys(&self) -> Option<(HermiteSpline, f64)> {
        Some((
            HermiteSpline {
                params: (0..self.points.len()).map(|i| i as f64).collect(),
                points: self.points.clone(),
                tangents: self.tangents.clone(),
                incoming: self.tangents.clone(),
            },
            5.0,
        ))
    }
    fn own_key_parameters(&self) -> Result<Vec<f64>, CurveError> {
        Ok((0..self.points.len()).map(|i| i as f64).collect())
    }
    fn nurbs_form(&self) -> Result<NurbsForm, CurveError> {
        let (points, v, a) = (&self.points, &self.tangents, &self.accelerations);
        let mut cp = vec![points[0]];
        let mut knots = vec![0.0; 6];
        let segs = points.len() - 1;
        for i in 0..segs {
            let (p0, p1) = (points[i], points[i + 1]);
            cp.extend([
                p0 + v[i] / 5.0,
                p0 + 2.0 * v[i] / 5.0 + a[i] / 20.0,
                p1 - 2.0 * v[i + 1] / 5.0 + a[i + 1] / 20.0,
                p1 - v[i + 1] / 5.0,
                p1,
            ]);
            let reps = if i + 1 == segs { 6 } else { 5 };
            knots.extend(std::iter::repeat_n((i + 1) as f64, reps));
        }
        let w = vec![1.0; cp.len()];
        Ok(NurbsForm {
            curve: NurbsCurve::new(5, knots, cp, w)?,
            tolerance: None,
        })
    }
    fn move_points(
        &mut self,
        moves: &[(usize, DVec3)],
        handles: &[TangentHandle],
    ) -> Result<(), CurveError> {
        move_with_handles(&mut self.points, &mut self.tangents, moves, handles, 5.0);
        Ok(())
    }
    fn transform(&mut self, m: &DMat4) -> Result<(), CurveError> {
        self.points = map_points(m, &self.points);
        self.tangents = map_vectors(m, &self.tangents);
        self.accelerations = map_vectors(m, &self.accelerations);
        Ok(())
    }
    fn insert_at(&mut self, _span: (usize, f64), at: usize, [p, d1, d2]: [DVec3; 3]) -> usize {
        self.points.insert(at, p);
        self.tangents.insert(at, d1 * 0.5);
        self.accelerations.insert(at, d2 * 0.25);
        at
    }
    fn delete(&mut self, gone: &[usize]) -> Result<(), CurveError> {
        self.points = super::remove_indices(&self.points, gone);
        self.tangents = super::remove_indices(&self.tangents, gone);
        self.accelerations = super::remove_indices(&self.accelerations, gone);
        Ok(())
    }
    fn push_end(&mut self, to: DVec3) -> Result<(), CurveError> {
        self.tangents.push(to - self.points[self.points.len() - 1]);
        self.accelerations.push(DVec3::ZERO);
        self.points.push(to);
        Ok(())
    }
    fn reversed(&self) -> Result<Self, CurveError> {
        Ok(QuinticHermite {
            points: super::rev(&self.points, false),
            tangents: super::neg(&self.tangents),
            accelerations: super::rev(&self.accelerations, false),
        })
    }
    fn keep(&mut self, k: usize, left: bool) {
        keep(&mut self.points, k, left);
        keep(&mut self.tangents, k, left);
        keep(&mut self.accelerations, k, left);
    }
    fn append(&mut self, other: &Self, skip: usize) -> Result<(), CurveError> {
        self.points.extend_from_slice(&other.points[skip..]);
        self.tangents.extend_from_slice(&other.tangents[skip..]);
        self.accelerations
            .extend_from_slice(&other.accelerations[skip..]);
        Ok(())
    }
}
