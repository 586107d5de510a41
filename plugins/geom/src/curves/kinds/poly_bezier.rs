//! Cubic Bézier segments sharing end points (a poly-Bézier), with the
//! continuity kept at each joint ([`Join`]): anchors and handles edited as
//! in Blender and Inkscape, exact as a NURBS with knots of multiplicity 3.

use super::cubic_hermite::keep;
use super::{Join, KindRules, NurbsForm, TangentHandle};
use crate::curves::CurveError;
use crate::curves::nurbs::NurbsCurve;
use glam::DVec3;

/// Cubic Bézier segments sharing end points: anchors at 0, 3, 6, …,
/// handles between. Open: `3k + 1` points for k segments, `k − 1`
/// joins (joint j at anchor `3(j + 1)`). Closed: `3k` points, the last
/// segment ends at point 0, `k` joins (joint j at anchor `3j`).
#[derive(Clone, Debug, PartialEq)]
pub struct PolyBezier {
    /// Anchors and handles.
    pub points: Vec<DVec3>,
    /// The continuity kept at each joint.
    pub joins: Vec<Join>,
    /// A closed chain.
    pub closed: bool,
}

impl PolyBezier {
    /// Sets the join of joint `joint` and makes it hold, turning the
    /// outgoing handle (the incoming one stays).
    ///
    /// # Errors
    /// No such joint.
    pub fn set_join(&mut self, joint: usize, join: Join) -> Result<(), CurveError> {
        let (points, joins, closed) = (&mut self.points, &mut self.joins, self.closed);
        if joint >= joins.len() {
            return Err(CurveError::NoSuchJoint {
                index: joint,
                count: joins.len(),
            });
        }
        joins[joint] = join;
        let (hin, a, hout) = joint_indices(joint, points.len(), closed);
        if join == Join::Auto {
            auto_handles(points, hin, a, hout);
        } else {
            enforce_join(points, join, hin, a, hout);
        }
        Ok(())
    }
}

impl KindRules for PolyBezier {
    fn name(&self) -> &'static str {
        "poly-Bézier"
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
        let (points, joins, closed) = (&self.points, &self.joins, self.closed);
        let (needed, per) = if closed { (3, 0) } else { (4, 1) };
        super::too_few(self.name(), needed, points.len())?;
        if (points.len() - per) % 3 != 0 {
            return Err(CurveError::CountMismatch {
                points: points.len(),
                what: if closed {
                    "a multiple of 3 points (3 per segment)"
                } else {
                    "3k + 1 points (3 per segment and one)"
                },
                got: points.len(),
            });
        }
        let segments = (points.len() - per) / 3;
        super::count(segments - per, "joins", joins.len())
    }
    fn nurbs_form(&self) -> Result<NurbsForm, CurveError> {
        let mut cp = self.points.clone();
        if self.closed {
            cp.push(self.points[0]);
        }
        let segs = (cp.len() - 1) / 3;
        let mut knots = vec![0.0; 4];
        for i in 1..=segs {
            let reps = if i == segs { 4 } else { 3 };
            knots.extend(std::iter::repeat_n(i as f64, reps));
        }
        let w = vec![1.0; cp.len()];
        Ok(NurbsForm {
            curve: NurbsCurve::new(3, knots, cp, w)?,
            tolerance: None,
        })
    }
    /// Keeps the joins: an anchor moved without its handles carries them
    /// along; a handle moved without its partner turns the partner to
    /// stay C1 (a mirror) or G1 (collinear, its length kept).
    fn move_points(
        &mut self,
        moves: &[(usize, DVec3)],
        _handles: &[TangentHandle],
    ) -> Result<(), CurveError> {
        let (points, joins, closed) = (&mut self.points, &mut self.joins, &self.closed);
        let before = points.clone();
        let moved: Vec<usize> = moves.iter().map(|m| m.0).collect();
        for &(i, p) in moves {
            points[i] = p;
        }
        let n = points.len();
        for (j, &join) in joins.iter().enumerate() {
            let (hin, a, hout) = joint_indices(j, n, *closed);
            let (mi, ma, mo) = (
                moved.contains(&hin),
                moved.contains(&a),
                moved.contains(&hout),
            );
            if ma {
                let delta = points[a] - before[a];
                if !mi {
                    points[hin] += delta;
                }
                if !mo {
                    points[hout] += delta;
                }
            } else if mi && !mo {
                enforce_join(points, join, hin, a, hout);
            } else if mo && !mi {
                enforce_join(points, join, hout, a, hin);
            }
        }
        // Auto joints: a dragged handle makes the joint G1 (its
        // partner was aligned above); else the handles follow the
        // anchors.
        for (j, join) in joins.iter_mut().enumerate() {
            if *join != Join::Auto {
                continue;
            }
            let (hin, a, hout) = joint_indices(j, n, *closed);
            let handle_dragged =
                (moved.contains(&hin) || moved.contains(&hout)) && !moved.contains(&a);
            if handle_dragged {
                *join = Join::G1;
            } else {
                auto_handles(points, hin, a, hout);
            }
        }
        // The free ends of an open chain carry their one handle.
        if !*closed {
            for (a, h) in [(0, 1), (n - 1, n - 2)] {
                if moved.contains(&a) && !moved.contains(&h) {
                    let d = points[a] - before[a];
                    points[h] += d;
                }
            }
        }
        Ok(())
    }
    /// Segments, not points.
    fn edges(&self) -> usize {
        (self.points.len() - usize::from(!self.closed)) / 3
    }
    /// A de Casteljau split of the segment, the new joint C1.
    fn insert_at(&mut self, (i, s): (usize, f64), _at: usize, _: [DVec3; 3]) -> usize {
        let points = &mut self.points;
        let n = points.len();
        let seg: Vec<DVec3> = (0..4).map(|k| points[(3 * i + k) % n]).collect();
        let (l, r) = crate::curves::Bezier { points: seg }.split(s);
        points.splice(
            3 * i + 1..3 * i + 3,
            [
                l.points[1],
                l.points[2],
                l.points[3],
                r.points[1],
                r.points[2],
            ],
        );
        self.joins
            .insert(if self.closed { i + 1 } else { i }, Join::C1);
        3 * i + 3
    }
    /// Anchor `3k` at parameter `k`.
    fn on_curve_parameter(&self, index: usize) -> Option<f64> {
        (index.is_multiple_of(3) && index < self.points.len()).then_some((index / 3) as f64)
    }
    /// Anchors only, each with its two handles (the neighbouring segments
    /// merge into one).
    fn delete(&mut self, gone: &[usize]) -> Result<(), CurveError> {
        let (points, joins, closed) = (&mut self.points, &mut self.joins, self.closed);
        if let Some(&index) = gone.iter().find(|&&i| i % 3 != 0) {
            return Err(CurveError::HandleNotAnchor { index });
        }
        // Highest first, so lower indices stay valid.
        for &a in gone.iter().rev() {
            let n = points.len();
            let segs = if closed { n / 3 } else { (n - 1) / 3 };
            if segs <= 1 {
                return Err(CurveError::KindTooFewPoints {
                    kind: "poly-Bézier",
                    needed: if closed { 3 } else { 4 },
                    got: n.saturating_sub(3),
                });
            }
            if closed {
                if a == 0 {
                    // Rotate the anchor to the end, then remove it.
                    points.rotate_left(3);
                    joins.rotate_left(1);
                    points.drain(n - 4..=n - 2);
                    joins.pop();
                } else {
                    points.drain(a - 1..=a + 1);
                    joins.remove(a / 3);
                }
            } else if a == 0 {
                points.drain(0..3);
                joins.remove(0);
            } else if a == n - 1 {
                points.drain(n - 3..n);
                joins.pop();
            } else {
                points.drain(a - 1..=a + 1);
                joins.remove(a / 3 - 1);
            }
        }
        Ok(())
    }
    /// A segment whose first handle continues the end's tangent (a G1
    /// joint).
    fn push_end(&mut self, to: DVec3) -> Result<(), CurveError> {
        let points = &mut self.points;
        let n = points.len();
        let (a, h) = (points[n - 1], points[n - 2]);
        let reach = (to - a).length() / 3.0;
        let dir = (a - h)
            .try_normalize()
            .unwrap_or((to - a).normalize_or_zero());
        points.extend([a + dir * reach, to + (a - to) / 3.0, to]);
        self.joins.push(Join::G1);
        Ok(())
    }
    fn reversed(&self) -> Result<Self, CurveError> {
        let c = self.closed;
        Ok(PolyBezier {
            points: super::rev(&self.points, c),
            joins: if c {
                super::reverse_closed(&self.joins)
            } else {
                self.joins.iter().rev().copied().collect()
            },
            closed: c,
        })
    }
    /// Closes with a straight segment back to the start (or by merging
    /// the ends where they meet); opens at point 0 keeping the shape.
    fn set_closed(&mut self, closed: bool) -> Result<(), CurveError> {
        let (points, joins) = (&mut self.points, &mut self.joins);
        self.closed = closed;
        if closed {
            let (first, last) = (points[0], points[points.len() - 1]);
            joins.insert(0, Join::C0);
            if (first - last).length() <= 1e-12 {
                points.pop();
            } else {
                points.extend([last.lerp(first, 1.0 / 3.0), last.lerp(first, 2.0 / 3.0)]);
                joins.push(Join::C0);
            }
        } else {
            points.push(points[0]);
            joins.remove(0);
        }
        Ok(())
    }
    fn keep(&mut self, k: usize, left: bool) {
        keep(&mut self.points, k, left);
        let j = k / 3 - 1;
        if left {
            self.joins.truncate(j);
        } else {
            self.joins.drain(..=j);
        }
    }
    /// A straight segment bridges a gap; the joints where they meet are C0.
    fn append(&mut self, other: &Self, skip: usize) -> Result<(), CurveError> {
        let (points, joins) = (&mut self.points, &mut self.joins);
        let (bp, bj) = (&other.points, &other.joins);
        let (last, first) = (points[points.len() - 1], bp[0]);
        joins.push(Join::C0);
        if skip == 0 {
            points.extend([
                last.lerp(first, 1.0 / 3.0),
                last.lerp(first, 2.0 / 3.0),
                first,
            ]);
            joins.push(Join::C0);
        }
        points.extend_from_slice(&bp[1..]);
        joins.extend_from_slice(bj);
        Ok(())
    }
}

/// The joint's incoming handle, anchor and outgoing handle indices.
fn joint_indices(j: usize, n: usize, closed: bool) -> (usize, usize, usize) {
    let a = if closed { 3 * j } else { 3 * (j + 1) };
    ((a + n - 1) % n, a, (a + 1) % n)
}

/// Places the handles of the auto joint at anchor `a` from its neighbouring
/// anchors (three points away along the chain, modulo its length).
fn auto_handles(points: &mut [DVec3], hin: usize, a: usize, hout: usize) {
    let n = points.len();
    let (prev, next) = (points[(a + n - 3) % n], points[(a + 3) % n]);
    let Some(dir) = (next - prev).try_normalize() else {
        return;
    };
    let p = points[a];
    points[hin] = p - dir * (p - prev).length() / 3.0;
    points[hout] = p + dir * (next - p).length() / 3.0;
}

/// Turns handle `other` about anchor `a` so the joint holds `join`, given
/// the handle `fixed`.
fn enforce_join(points: &mut [DVec3], join: Join, fixed: usize, a: usize, other: usize) {
    let arm = points[a] - points[fixed];
    match join {
        Join::C0 => {}
        Join::C1 => points[other] = points[a] + arm,
        Join::G1 | Join::Auto => {
            if let Some(dir) = arm.try_normalize() {
                let len = (points[other] - points[a]).length();
                points[other] = points[a] + dir * len;
            }
        }
    }
}
