//! Self-intersection of a closed mesh: pairs of its faces that cross each
//! other (two overlapping shells in one mesh, a surface folded through
//! itself). A boolean's engine assumes operands that do not, so
//! [`boolean`](super::boolean) refuses them with the count of crossing
//! face pairs.
//!
//! Broad phase: a bounding-volume hierarchy over the triangles, sorted by
//! the Morton code of their centroids and split in halves (a linear BVH,
//! Lauterbach et al., "Fast BVH Construction on GPUs", 2009), traversed
//! against itself so every pair of triangles whose boxes overlap is seen
//! once. Narrow phase: two triangles that are not coplanar intersect in a
//! segment whose ends lie where an edge of one crosses the other (Möller,
//! "A Fast Triangle-Triangle Intersection Test", 1997), so a pair crosses
//! when an edge of one passes through the inside of the other. Triangles
//! sharing an edge are skipped (they meet along it); triangles sharing
//! one vertex are tested on the edges opposite that vertex.
//!
//! Each orientation sign is used only when it is certain: Shewchuk's error
//! bound for the floating-point `orient3d` ("Adaptive Precision
//! Floating-Point Arithmetic and Fast Robust Geometric Predicates", 1997,
//! `o3derrboundA`) says when the computed determinant's sign is the exact
//! one; a determinant inside the bound counts as zero (touching). So every
//! reported pair truly crosses (no false alarms on flat or nearly flat
//! regions); what is not reported is touching without crossing, coplanar
//! overlap and crossings too shallow for double precision to be sure of.

use glam::DVec3;

/// Triangles per BVH leaf.
const LEAF: usize = 4;

/// Shewchuk's `o3derrboundA` = (7 + 56ε)ε, ε = 2⁻⁵³.
const O3D_ERR: f64 = (7.0 + 56.0 * f64::EPSILON / 2.0) * (f64::EPSILON / 2.0);

/// The sign of the volume of tetrahedron (a, b, c, d), positive when d is
/// below the plane of a, b, c seen counter-clockwise: +1, −1, or 0 when
/// the floating-point value is not certain of its sign (Shewchuk's
/// `orient3d` with its static error bound, without the adaptive stages).
fn orient(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> i8 {
    let (ad, bd, cd) = (a - d, b - d, c - d);
    let bc = bd.x * cd.y - cd.x * bd.y;
    let ca = cd.x * ad.y - ad.x * cd.y;
    let ab = ad.x * bd.y - bd.x * ad.y;
    let det = ad.z * bc + bd.z * ca + cd.z * ab;
    let permanent = ((bd.x * cd.y).abs() + (cd.x * bd.y).abs()) * ad.z.abs()
        + ((cd.x * ad.y).abs() + (ad.x * cd.y).abs()) * bd.z.abs()
        + ((ad.x * bd.y).abs() + (bd.x * ad.y).abs()) * cd.z.abs();
    let bound = O3D_ERR * permanent;
    if det > bound {
        1
    } else if det < -bound {
        -1
    } else {
        0
    }
}

/// True when segment p–q passes through the inside of triangle t (its
/// ends strictly on opposite sides of the plane, the crossing point
/// strictly inside), every sign certain.
fn segment_crosses(p: DVec3, q: DVec3, t: [DVec3; 3]) -> bool {
    let sp = orient(t[0], t[1], t[2], p);
    let sq = orient(t[0], t[1], t[2], q);
    if sp == 0 || sp != -sq {
        return false;
    }
    let s0 = orient(p, q, t[0], t[1]);
    if s0 == 0 {
        return false;
    }
    orient(p, q, t[1], t[2]) == s0 && orient(p, q, t[2], t[0]) == s0
}

/// A triangle's plane for the quick rejection: its first vertex, its
/// (unnormalised) normal and its longest edge.
#[derive(Copy, Clone)]
struct Plane {
    origin: DVec3,
    normal: DVec3,
    size: f64,
}

impl Plane {
    fn of(p: [DVec3; 3]) -> Plane {
        let size = (p[1] - p[0])
            .length()
            .max((p[2] - p[1]).length())
            .max((p[0] - p[2]).length());
        Plane {
            origin: p[0],
            normal: (p[1] - p[0]).cross(p[2] - p[0]),
            size,
        }
    }

    /// True when the points of `q` not in `skip` lie clearly on one side:
    /// their distances pass a margin a million times the rounding error
    /// of computing them (‖normal‖ ≤ size², ‖p − origin‖ ≤ 3(size +
    /// other)), so the exact orientation signs agree and the triangles
    /// cannot meet.
    fn separates(&self, q: [DVec3; 3], other: f64, skip: [bool; 3]) -> bool {
        let margin = 1e-9 * self.size * self.size * (self.size + other);
        let (mut above, mut below) = (true, true);
        for (p, &skip) in q.iter().zip(&skip) {
            if !skip {
                let d = self.normal.dot(*p - self.origin);
                above &= d > margin;
                below &= d < -margin;
            }
        }
        above || below
    }
}

/// True when triangles `a` and `b` (vertex numbers into `positions`)
/// certainly cross. Triangles sharing two or more vertices never do here.
#[cfg(test)]
fn triangles_cross(positions: &[DVec3], a: [u32; 3], b: [u32; 3]) -> bool {
    let pa = a.map(|v| positions[v as usize]);
    let pb = b.map(|v| positions[v as usize]);
    cross_with_planes(a, b, pa, pb, Plane::of(pa), Plane::of(pb))
}

fn cross_with_planes(
    a: [u32; 3],
    b: [u32; 3],
    pa: [DVec3; 3],
    pb: [DVec3; 3],
    plane_a: Plane,
    plane_b: Plane,
) -> bool {
    let mut shared = None;
    let mut count = 0;
    for (i, &v) in a.iter().enumerate() {
        if let Some(j) = b.iter().position(|&w| w == v) {
            shared = Some((i, j));
            count += 1;
        }
    }
    if count > 1 {
        return false;
    }
    // Quick rejection (Möller's first test): one triangle clearly on one
    // side of the other's plane; a shared vertex lies on both planes.
    let skip_a = [0, 1, 2].map(|i| shared.is_some_and(|(s, _)| s == i));
    let skip_b = [0, 1, 2].map(|j| shared.is_some_and(|(_, s)| s == j));
    if plane_a.separates(pb, plane_b.size, skip_b) || plane_b.separates(pa, plane_a.size, skip_a) {
        return false;
    }
    match shared {
        None => (0..3).any(|i| {
            segment_crosses(pa[i], pa[(i + 1) % 3], pb)
                || segment_crosses(pb[i], pb[(i + 1) % 3], pa)
        }),
        // The segment where they meet starts at the shared vertex; it is
        // more than that point when an edge opposite it crosses the other.
        Some((i, j)) => {
            segment_crosses(pa[(i + 1) % 3], pa[(i + 2) % 3], pb)
                || segment_crosses(pb[(j + 1) % 3], pb[(j + 2) % 3], pa)
        }
    }
}

/// Spreads the low 10 bits of `x` three apart (for a 30-bit Morton code).
fn spread(mut x: u32) -> u32 {
    x &= 0x3ff;
    x = (x | (x << 16)) & 0x0300_00ff;
    x = (x | (x << 8)) & 0x0300_f00f;
    x = (x | (x << 4)) & 0x030c_30c3;
    x = (x | (x << 2)) & 0x0924_9249;
    x
}

struct Node {
    lo: DVec3,
    hi: DVec3,
    /// A leaf's range of the sorted triangles.
    start: u32,
    end: u32,
    /// An inner node's right child (its left child is the next node);
    /// `u32::MAX` for a leaf.
    right: u32,
}

/// Appends the subtree over the sorted triangles `start..end` depth
/// first; returns its index.
fn build(
    nodes: &mut Vec<Node>,
    boxes: &[(DVec3, DVec3)],
    codes: &[u32],
    start: usize,
    end: usize,
) -> u32 {
    let at = nodes.len();
    nodes.push(Node {
        lo: DVec3::ZERO,
        hi: DVec3::ZERO,
        start: start as u32,
        end: end as u32,
        right: u32::MAX,
    });
    let (lo, hi) = if end - start > LEAF {
        // Split where the highest differing bit of the Morton codes flips
        // (Karras, "Maximizing Parallelism in the Construction of BVHs,
        // Octrees, and k-d Trees", 2012), so each half is one block of
        // space; in the middle when the codes are all equal.
        let (first, last) = (codes[start], codes[end - 1]);
        let mid = if first == last {
            (start + end) / 2
        } else {
            let bit = 31 - (first ^ last).leading_zeros();
            let high = |c: u32| c >> bit;
            start + codes[start..end].partition_point(|&c| high(c) == high(first))
        };
        let left = build(nodes, boxes, codes, start, mid) as usize;
        let right = build(nodes, boxes, codes, mid, end);
        nodes[at].right = right;
        let (l, r) = (&nodes[left], &nodes[right as usize]);
        (l.lo.min(r.lo), l.hi.max(r.hi))
    } else {
        boxes[start..end].iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), b| (lo.min(b.0), hi.max(b.1)),
        )
    };
    nodes[at].lo = lo;
    nodes[at].hi = hi;
    at as u32
}

/// The pairs of distinct faces that cross, each once as (smaller,
/// larger), sorted: triangle `t` is `corners[3t..3t + 3]` (vertex numbers
/// into `positions`), `face[t]` is the face it belongs to (triangles of
/// one face are never tested against each other).
///
/// Complexity: O(n log n + k) for n triangles and k pairs of overlapping
/// boxes.
pub(crate) fn crossing_face_pairs(
    positions: &[DVec3],
    corners: &[usize],
    face: &[u32],
) -> Vec<(u32, u32)> {
    let n = corners.len() / 3;
    if n < 2 {
        return Vec::new();
    }
    let corner = |t: usize| [0, 1, 2].map(|k| corners[3 * t + k] as u32);
    let (lo, hi) = positions.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let scale = 1023.0 / (hi - lo).max(DVec3::splat(1e-300));
    let mut keyed: Vec<u64> = (0..n)
        .map(|t| {
            let [a, b, c] = corner(t).map(|v| positions[v as usize]);
            let centroid = ((a + b + c) / 3.0 - lo) * scale;
            let [x, y, z] = centroid.to_array().map(|x| x.clamp(0.0, 1023.0) as u32);
            let code = spread(x) | spread(y) << 1 | spread(z) << 2;
            (code as u64) << 32 | t as u64
        })
        .collect();
    keyed.sort_unstable();
    // Everything in the sorted order, so that neighbours in space are
    // neighbours in memory.
    let triangles: Vec<[u32; 3]> = keyed.iter().map(|&k| corner(k as u32 as usize)).collect();
    let face: Vec<u32> = keyed.iter().map(|&k| face[k as u32 as usize]).collect();
    let points: Vec<[DVec3; 3]> = triangles
        .iter()
        .map(|t| t.map(|v| positions[v as usize]))
        .collect();
    let boxes: Vec<(DVec3, DVec3)> = points
        .iter()
        .map(|&[a, b, c]| (a.min(b).min(c), a.max(b).max(c)))
        .collect();
    let planes: Vec<Plane> = points.iter().map(|&p| Plane::of(p)).collect();

    // Nodes in depth-first order, each over a range of the sorted triangles.
    let mut nodes: Vec<Node> = Vec::with_capacity(2 * n / LEAF + 2);
    let codes: Vec<u32> = keyed.iter().map(|&k| (k >> 32) as u32).collect();
    build(&mut nodes, &boxes, &codes, 0, n);

    let mut pairs: Vec<(u32, u32)> = Vec::new();
    let test = |s: usize, t: usize, pairs: &mut Vec<(u32, u32)>| {
        let (fs, ft) = (face[s], face[t]);
        if fs == ft {
            return;
        }
        let (bs, bt) = (&boxes[s], &boxes[t]);
        if bs.0.cmpgt(bt.1).any() || bt.0.cmpgt(bs.1).any() {
            return;
        }
        if cross_with_planes(
            triangles[s],
            triangles[t],
            points[s],
            points[t],
            planes[s],
            planes[t],
        ) {
            pairs.push((fs.min(ft), fs.max(ft)));
        }
    };
    let overlap = |lo: DVec3, hi: DVec3, b: &Node| !(lo.cmpgt(b.hi).any() || b.lo.cmpgt(hi).any());
    let mut stack: Vec<(u32, u32)> = vec![(0, 0)];
    while let Some((a, b)) = stack.pop() {
        let (na, nb) = (&nodes[a as usize], &nodes[b as usize]);
        let (leaf_a, leaf_b) = (na.right == u32::MAX, nb.right == u32::MAX);
        if a == b {
            if leaf_a {
                for s in na.start as usize..na.end as usize {
                    for t in s + 1..na.end as usize {
                        test(s, t, &mut pairs);
                    }
                }
            } else {
                let (l, r) = (a + 1, na.right);
                stack.extend([(l, l), (r, r), (l, r)]);
            }
            continue;
        }
        if !overlap(na.lo, na.hi, nb) {
            continue;
        }
        let larger_a = na.end - na.start >= nb.end - nb.start;
        match (leaf_a, leaf_b) {
            (true, true) => {
                let range = na.start as usize..na.end as usize;
                for (s, (lo, hi)) in boxes[range.clone()].iter().enumerate() {
                    let s = range.start + s;
                    if overlap(*lo, *hi, nb) {
                        for t in nb.start as usize..nb.end as usize {
                            test(s, t, &mut pairs);
                        }
                    }
                }
            }
            (false, true) => stack.extend([(a + 1, b), (na.right, b)]),
            (true, false) => stack.extend([(a, b + 1), (a, nb.right)]),
            (false, false) if larger_a => stack.extend([(a + 1, b), (na.right, b)]),
            (false, false) => stack.extend([(a, b + 1), (a, nb.right)]),
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    #[test]
    fn pairs_that_cross_and_pairs_that_only_touch() {
        let positions = [
            // 0..3: a triangle in z = 0.
            p(0.0, 0.0, 0.0),
            p(1.0, 0.0, 0.0),
            p(0.0, 1.0, 0.0),
            // 3..6: one piercing it (an edge through its inside).
            p(0.2, 0.2, -1.0),
            p(0.2, 0.2, 1.0),
            p(2.0, 2.0, 0.5),
            // 6..8: with vertex 0, a triangle folded through the first
            // (its opposite edge passes under and over it).
            p(0.3, 0.3, -0.5),
            p(0.3, 0.3, 0.5),
            // 8..10: with vertex 0, a triangle that only meets it there.
            p(-1.0, 0.0, 0.5),
            p(0.0, -1.0, 0.5),
            // 10..12: a triangle whose vertex rests on the first's inside.
            p(0.2, 0.2, 0.0),
            p(0.2, 3.0, 1.0),
        ];
        assert!(triangles_cross(&positions, [0, 1, 2], [3, 4, 5]));
        assert!(triangles_cross(&positions, [3, 4, 5], [0, 1, 2]));
        assert!(triangles_cross(&positions, [0, 1, 2], [0, 6, 7]));
        assert!(!triangles_cross(&positions, [0, 1, 2], [0, 8, 9]));
        assert!(!triangles_cross(&positions, [0, 1, 2], [10, 11, 5]));
        // Sharing an edge: never counted.
        assert!(!triangles_cross(&positions, [0, 1, 2], [1, 0, 4]));
        // Coplanar overlap is not reported (documented limit).
        let flat = [
            p(0.0, 0.0, 0.0),
            p(1.0, 0.0, 0.0),
            p(0.0, 1.0, 0.0),
            p(0.2, 0.2, 0.0),
            p(2.0, 0.2, 0.0),
            p(0.2, 2.0, 0.0),
        ];
        assert!(!triangles_cross(&flat, [0, 1, 2], [3, 4, 5]));
    }

    #[test]
    fn orientation_signs_are_exact_or_zero() {
        let (a, b, c) = (p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0));
        assert_eq!(orient(a, b, c, p(0.1, 0.1, -1.0)), 1);
        assert_eq!(orient(a, b, c, p(0.1, 0.1, 1.0)), -1);
        assert_eq!(orient(a, b, c, p(0.3, 0.3, 0.0)), 0);
        // Computed exactly: even 1e-300 off the plane has a certain sign.
        assert_eq!(orient(a, b, c, p(0.1, 0.1, -1e-300)), 1);
        // A rounded product near zero is not trusted: the four points of
        // a tilted square, coplanar but not exactly representable.
        let t = |x: f64, y: f64| p(x, y, 0.1 * x + 0.7 * y);
        let corners = [t(0.1, 0.2), t(0.9, 0.3), t(0.4, 0.8), t(0.7, 0.6)];
        let s = orient(corners[0], corners[1], corners[2], corners[3]);
        let exact_enough = (corners[3] - corners[0])
            .dot((corners[1] - corners[0]).cross(corners[2] - corners[0]))
            .abs();
        assert!(s == 0 || exact_enough > 1e-15, "{s} {exact_enough}");
    }
}
