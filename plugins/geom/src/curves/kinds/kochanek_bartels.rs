//! The Kochanek-Bartels spline (seed 000): tension, bias and continuity
//! per key shape each key's incoming and outgoing tangents, uniform
//! parameters; open or a closed loop.

use super::cubic_hermite::keep;
use super::{KindRules, NurbsForm, hermite_nurbs};
use crate::curves::CurveError;
use crate::curves::interpolating::{HermiteSpline, Tbc};
use glam::DVec3;

/// The Kochanek-Bartels spline: tension, bias, continuity per key,
/// uniform parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct KochanekBartels {
    /// The points (at least 2; 3 closed).
    pub points: Vec<DVec3>,
    /// One key per point.
    pub keys: Vec<Tbc>,
    /// A closed loop.
    pub closed: bool,
}

impl KochanekBartels {
    /// The Hermite spline of the keys' tangents.
    fn spline(&self) -> Result<HermiteSpline, CurveError> {
        let (points, keys, closed) = (&self.points, &self.keys, self.closed);
        let t: Vec<f64> = (0..points.len() + usize::from(closed))
            .map(|i| i as f64)
            .collect();
        if closed {
            closed_kb(points, keys, t)
        } else {
            HermiteSpline::kochanek_bartels(t, points.clone(), keys)
        }
    }
}

/// Kochanek-Bartels tangents of a closed loop (the open case is
/// [`HermiteSpline::kochanek_bartels`]): keys wrap around.
pub(super) fn closed_kb(
    points: &[DVec3],
    keys: &[Tbc],
    params: Vec<f64>,
) -> Result<HermiteSpline, CurveError> {
    let n = points.len();
    let mut out = Vec::with_capacity(n + 1);
    let mut inc = Vec::with_capacity(n + 1);
    for i in 0..n {
        let (prev, next) = (points[(i + n - 1) % n], points[(i + 1) % n]);
        let Tbc {
            tension: t,
            bias: b,
            continuity: c,
        } = keys[i];
        let (before, after) = (points[i] - prev, next - points[i]);
        let o = (1.0 - t) * (1.0 + b) * (1.0 + c) / 2.0 * before
            + (1.0 - t) * (1.0 - b) * (1.0 - c) / 2.0 * after;
        let d = (1.0 - t) * (1.0 + b) * (1.0 - c) / 2.0 * before
            + (1.0 - t) * (1.0 - b) * (1.0 + c) / 2.0 * after;
        let h_prev = if i == 0 {
            params[n] - params[n - 1]
        } else {
            params[i] - params[i - 1]
        };
        let per_t = 2.0 / (h_prev + params[i + 1] - params[i]);
        out.push(per_t * o);
        inc.push(per_t * d);
    }
    out.push(out[0]);
    inc.push(inc[0]);
    let mut ext = points.to_vec();
    ext.push(points[0]);
    let mut s = HermiteSpline::new(params, ext, out)?;
    s.incoming = inc;
    Ok(s)
}

impl KindRules for KochanekBartels {
    fn name(&self) -> &'static str {
        "Kochanek-Bartels"
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
        let (points, keys) = (&self.points, &self.keys);
        super::too_few(self.name(), super::least(self.closed), points.len())?;
        super::count(points.len(), "T/B/C keys", keys.len())?;
        if keys
            .iter()
            .any(|k| !(k.tension.is_finite() && k.bias.is_finite() && k.continuity.is_finite()))
        {
            return Err(CurveError::NotFiniteVector {
                what: "a T/B/C key",
            });
        }
        Ok(())
    }
    fn hermite_form(&self) -> Result<Option<HermiteSpline>, CurveError> {
        self.spline().map(Some)
    }
    fn nurbs_form(&self) -> Result<NurbsForm, CurveError> {
        hermite_nurbs(&self.spline()?)
    }
    fn insert_at(&mut self, _span: (usize, f64), at: usize, [p, _, _]: [DVec3; 3]) -> usize {
        self.points.insert(at, p);
        self.keys.insert(at, Tbc::default());
        at
    }
    fn delete(&mut self, gone: &[usize]) -> Result<(), CurveError> {
        self.points = super::remove_indices(&self.points, gone);
        self.keys = super::remove_indices(&self.keys, gone);
        Ok(())
    }
    fn push_end(&mut self, to: DVec3) -> Result<(), CurveError> {
        self.points.push(to);
        self.keys.push(Tbc::default());
        Ok(())
    }
    /// Traced back, every key's bias negates.
    fn reversed(&self) -> Result<Self, CurveError> {
        let c = self.closed;
        let flip = |k: &Tbc| Tbc {
            bias: -k.bias,
            ..*k
        };
        let keys: Vec<Tbc> = if c {
            super::reverse_closed(&self.keys).iter().map(flip).collect()
        } else {
            self.keys.iter().rev().map(flip).collect()
        };
        Ok(KochanekBartels {
            points: super::rev(&self.points, c),
            keys,
            closed: c,
        })
    }
    fn set_closed(&mut self, closed: bool) -> Result<(), CurveError> {
        self.closed = closed;
        Ok(())
    }
    fn keep(&mut self, k: usize, left: bool) {
        keep(&mut self.points, k, left);
        keep(&mut self.keys, k, left);
    }
    fn append(&mut self, other: &Self, skip: usize) -> Result<(), CurveError> {
        self.points.extend_from_slice(&other.points[skip..]);
        self.keys.extend_from_slice(&other.keys[skip..]);
        Ok(())
    }
}
