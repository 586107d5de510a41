//! Quadric error metrics (Garland and Heckbert, "Surface Simplification
//! Using Quadric Error Metrics", SIGGRAPH 1997): the squared distance of a
//! point to a set of planes as one symmetric 4×4 form, with the sum of the
//! planes' weights so that the error can be read as a weighted mean
//! (meshoptimizer's `quadricError`, A. Kapoulkine, `simplifier.cpp`).

use glam::{DMat3, DVec3};

/// A quadric `Q(p) = pᵀ A p + 2 bᵀ p + c` with `A` symmetric, stored as
/// its ten distinct entries. The sum of the quadrics of planes `n·p + d = 0`
/// measures the (weighted) sum of squared distances to them; `w` is the
/// sum of their weights.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct Quadric {
    a: [f64; 6],
    b: DVec3,
    c: f64,
    w: f64,
}

impl Quadric {
    /// The quadric of the plane through `point` with unit normal `normal`,
    /// times `weight`.
    pub fn plane(normal: DVec3, point: DVec3, weight: f64) -> Quadric {
        let n = normal;
        let d = -n.dot(point);
        Quadric {
            a: [
                n.x * n.x,
                n.x * n.y,
                n.x * n.z,
                n.y * n.y,
                n.y * n.z,
                n.z * n.z,
            ]
            .map(|x| x * weight),
            b: n * (d * weight),
            c: d * d * weight,
            w: weight,
        }
    }

    /// The error at `p` (never below 0 up to rounding).
    pub fn error(&self, p: DVec3) -> f64 {
        let [xx, xy, xz, yy, yz, zz] = self.a;
        let ap = DVec3::new(
            xx * p.x + xy * p.y + xz * p.z,
            xy * p.x + yy * p.y + yz * p.z,
            xz * p.x + yz * p.y + zz * p.z,
        );
        (p.dot(ap) + 2.0 * self.b.dot(p) + self.c).max(0.0)
    }

    /// The weighted mean of the squared distances at `p`: the error over
    /// the sum of the weights (0 for the empty quadric). Unlike the sum, it
    /// does not grow with the area a vertex stands for, so costs compare
    /// as squared distances across the whole mesh (meshoptimizer divides
    /// by the weight the same way).
    pub fn mean_error(&self, p: DVec3) -> f64 {
        if self.w > 0.0 {
            self.error(p) / self.w
        } else {
            0.0
        }
    }

    /// The sum of the planes' weights.
    pub fn weight(&self) -> f64 {
        self.w
    }

    /// The point of least error when `A` is well conditioned (its
    /// determinant not small against the cube of its size), else `None`.
    pub fn minimizer(&self) -> Option<DVec3> {
        let [xx, xy, xz, yy, yz, zz] = self.a;
        let m = DMat3::from_cols(
            DVec3::new(xx, xy, xz),
            DVec3::new(xy, yy, yz),
            DVec3::new(xz, yz, zz),
        );
        let scale = xx + yy + zz;
        let det = m.determinant();
        if scale.is_nan() || scale <= 0.0 || det.abs() <= 1e-9 * scale * scale * scale {
            return None;
        }
        let p = m.inverse() * -self.b;
        p.is_finite().then_some(p)
    }
}

impl std::ops::Add for Quadric {
    type Output = Quadric;
    fn add(mut self, o: Quadric) -> Quadric {
        self += o;
        self
    }
}

impl std::ops::AddAssign for Quadric {
    fn add_assign(&mut self, o: Quadric) {
        for (x, y) in self.a.iter_mut().zip(o.a) {
            *x += y;
        }
        self.b += o.b;
        self.c += o.c;
        self.w += o.w;
    }
}
