//! Building a half-edge mesh from an indexed face set (seed 000's "indexed
//! storage": a position list and polygons as vertex index lists).
//!
//! The strict build ([`HalfEdgeMesh::from_polygons`]) writes the records
//! in bulk, so it lives inside the mesh module (`mesh/construct.rs`); here
//! are its errors, the repairing build on top of it (which only rewrites the
//! polygon lists before calling it), export to polygons and compaction.

use crate::ids::NONE;
use crate::mesh::HalfEdgeMesh;
use glam::DVec3;
use std::collections::HashMap;

/// Why an indexed face set cannot become a manifold half-edge mesh.
/// Face and vertex numbers are indices into the input lists.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum BuildError {
    /// A polygon names a vertex index past the end of the position list.
    #[error("face {face} refers to vertex {index}, but there are only {vertex_count} vertices")]
    IndexOutOfRange {
        /// Index of the polygon in the input.
        face: usize,
        /// The vertex index it names.
        index: u32,
        /// Length of the position list.
        vertex_count: usize,
    },
    /// A polygon has fewer than three corners.
    #[error("face {face} has {sides} vertices; a face needs at least 3")]
    TooFewSides {
        /// Index of the polygon in the input.
        face: usize,
        /// Its number of corners.
        sides: usize,
    },
    /// A polygon visits the same vertex twice.
    #[error("face {face} uses vertex {vertex} more than once")]
    RepeatedVertex {
        /// Index of the polygon in the input.
        face: usize,
        /// The input vertex it repeats.
        vertex: u32,
    },
    /// Three or more polygons share one edge.
    #[error("edge {a}-{b} is shared by more than two faces (faces {faces:?})")]
    NonManifoldEdge {
        /// One end of the edge (input vertex index).
        a: u32,
        /// The other end.
        b: u32,
        /// Every input polygon that uses the edge.
        faces: Vec<usize>,
    },
    /// Two polygons run along an edge in the same direction, so their
    /// windings disagree.
    #[error(
        "faces {faces:?} both run edge {a}->{b} in the same direction: their orientations disagree"
    )]
    InconsistentOrientation {
        /// Start of the directed edge (input vertex index).
        a: u32,
        /// End of the directed edge.
        b: u32,
        /// The input polygons that both run `a`→`b`.
        faces: Vec<usize>,
    },
    /// The polygons around a vertex form more than one fan.
    #[error("vertex {vertex} joins separate fans of faces (non-manifold vertex)")]
    NonManifoldVertex {
        /// The input vertex index.
        vertex: u32,
    },
    /// A position has a NaN or infinite coordinate.
    #[error("vertex {vertex} has a non-finite position")]
    NonFinitePosition {
        /// The input vertex index.
        vertex: u32,
    },
    /// More elements than a 32-bit id can number.
    #[error("the mesh is too large: {what} exceed the 32-bit id space")]
    TooLarge {
        /// Which elements overflow: `"vertices"`, `"corners"` or `"half-edges"`.
        what: &'static str,
    },
}

/// What [`HalfEdgeMesh::from_polygons_repaired`] had to change.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RepairReport {
    /// Input face index and the reason it was dropped.
    pub dropped_faces: Vec<(usize, BuildError)>,
    /// Input vertices that were duplicated because separate fans met there,
    /// with the number of copies added.
    pub split_vertices: Vec<(u32, usize)>,
    /// Kept input face index for each face id of the result.
    pub face_origin: Vec<usize>,
    /// Input faces that visit a vertex more than once (a polygon pinched at
    /// a point, a "keyhole"), split there into simple loops, with the number
    /// of loops kept.
    pub split_faces: Vec<(usize, usize)>,
}

impl RepairReport {
    /// True when the input was used as it was.
    pub fn is_clean(&self) -> bool {
        self.dropped_faces.is_empty()
            && self.split_vertices.is_empty()
            && self.split_faces.is_empty()
    }
}

impl std::fmt::Display for RepairReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.is_clean() {
            return write!(f, "no repairs needed");
        }
        // Only what happened: no "dropped 0 faces".
        let mut parts = Vec::new();
        if !self.dropped_faces.is_empty() {
            let mut text = format!("dropped {} face(s)", self.dropped_faces.len());
            for (i, (face, why)) in self.dropped_faces.iter().take(5).enumerate() {
                text += &format!("{}face {face}: {why}", if i == 0 { " (" } else { "; " });
            }
            if self.dropped_faces.len() > 5 {
                text += "; …";
            }
            parts.push(text + ")");
        }
        if !self.split_faces.is_empty() {
            parts.push(format!(
                "split {} face(s) that visit a vertex twice into simple loops",
                self.split_faces.len()
            ));
        }
        if !self.split_vertices.is_empty() {
            let copies: usize = self.split_vertices.iter().map(|(_, n)| n).sum();
            parts.push(format!(
                "split {} non-manifold vertex(es) into {copies} extra copies",
                self.split_vertices.len()
            ));
        }
        write!(f, "{}", parts.join(", "))
    }
}

/// The simple loops of a polygon that visits some vertices twice (pinched,
/// as a keyhole outline), cut at the repeats (each loop of three or more
/// corners; shorter ones, such as a doubled corner, vanish); `None` when no
/// vertex repeats, or one repeats more than twice.
fn simple_loops(poly: &[u32]) -> Option<Vec<Vec<u32>>> {
    let mut count: HashMap<u32, usize> = HashMap::with_capacity(poly.len());
    for &v in poly {
        *count.entry(v).or_default() += 1;
    }
    // Only pinches (each repeated vertex visited twice): a face that runs
    // around its outline again and again is garbage, not a shape.
    if count.values().all(|&n| n == 1) || count.values().any(|&n| n > 2) {
        return None;
    }
    let mut loops = Vec::new();
    let mut path: Vec<u32> = Vec::with_capacity(poly.len());
    for &v in poly {
        if let Some(at) = path.iter().position(|&w| w == v) {
            let cut: Vec<u32> = path.split_off(at + 1);
            let mut piece = vec![v];
            piece.extend(cut);
            if piece.len() >= 3 {
                loops.push(piece);
            }
        } else {
            path.push(v);
        }
    }
    if path.len() >= 3 {
        loops.push(path);
    }
    Some(loops)
}

/// The loops of a polygon split by [`simple_loops`], with every loop that
/// runs against the outline inside a loop that runs with it (a hole, as a
/// keyhole outline walks its inner ring backwards) cut out of that loop:
/// two bridges from the outer loop to the hole split the ring between them
/// into two simple loops that keep the outline's orientation, and together
/// cover the outline's area (outer minus hole) once. Without this the hole
/// became a face of its own over the outer one, facing the other way.
///
/// Orientation and areas are measured in the plane of the whole polygon's
/// Newell normal. Loops are returned unchanged when the polygon has no
/// area, or no pair of bridges inside the ring can be found.
///
/// Complexity: O(h · n²) for n corners and h holes in the worst case; a
/// bridge is usually found among the first candidates.
fn keep_outline(positions: &[DVec3], poly: &[u32], loops: Vec<Vec<u32>>) -> Vec<Vec<u32>> {
    let mut normal = DVec3::ZERO;
    for (i, &a) in poly.iter().enumerate() {
        let b = poly[(i + 1) % poly.len()];
        normal += positions[a as usize].cross(positions[b as usize]);
    }
    let Some(n) = normal.try_normalize() else {
        return loops;
    };
    let u = n.any_orthonormal_vector();
    let w = n.cross(u);
    let flat = |v: u32| {
        let p = positions[v as usize];
        glam::DVec2::new(p.dot(u), p.dot(w))
    };
    let area = |l: &[u32]| {
        let mut a = 0.0;
        for (i, &x) in l.iter().enumerate() {
            a += flat(x).perp_dot(flat(l[(i + 1) % l.len()]));
        }
        0.5 * a
    };
    let (mut outers, mut holes): (Vec<Vec<u32>>, Vec<Vec<u32>>) =
        loops.into_iter().partition(|l| area(l) >= 0.0);
    if holes.is_empty() || outers.is_empty() {
        outers.extend(holes);
        return outers;
    }
    let mut kept_holes = Vec::new();
    while let Some(hole) = holes.pop() {
        let inside = outers.iter().position(|o| {
            hole.iter()
                .find(|v| !o.contains(v))
                .is_some_and(|&v| point_in_loop(flat(v), o, &flat))
        });
        let Some(k) = inside else {
            kept_holes.push(hole);
            continue;
        };
        // Every other loop's edges are obstacles for the bridges.
        let others: Vec<&Vec<u32>> = holes.iter().chain(&kept_holes).collect();
        match bridge_split(&outers[k], &hole, &others, &flat) {
            Some((a, b)) if area(&a) > 0.0 && area(&b) > 0.0 => {
                outers[k] = a;
                outers.push(b);
            }
            _ => kept_holes.push(hole),
        }
    }
    outers.extend(kept_holes);
    outers
}

/// Even-odd test of a point against a loop in the plane.
fn point_in_loop(p: glam::DVec2, l: &[u32], flat: &impl Fn(u32) -> glam::DVec2) -> bool {
    let mut inside = false;
    for (i, &a) in l.iter().enumerate() {
        let (a, b) = (flat(a), flat(l[(i + 1) % l.len()]));
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
    }
    inside
}

/// True when segments pq and rs cross at a point inside both (touching
/// ends and collinear overlaps count as crossing, to stay on the safe side).
fn segments_meet(p: glam::DVec2, q: glam::DVec2, r: glam::DVec2, s: glam::DVec2) -> bool {
    let side = |a: glam::DVec2, b: glam::DVec2, c: glam::DVec2| (b - a).perp_dot(c - a);
    let (d1, d2) = (side(r, s, p), side(r, s, q));
    let (d3, d4) = (side(p, q, r), side(p, q, s));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |a: glam::DVec2, b: glam::DVec2, c: glam::DVec2, d: f64| {
        d == 0.0 && c.cmpge(a.min(b)).all() && c.cmple(a.max(b)).all()
    };
    on(r, s, p, d1) || on(r, s, q, d2) || on(p, q, r, d3) || on(p, q, s, d4)
}

/// Two loops `outer` (with the outline) and `hole` (against it, inside
/// `outer`) joined by two bridges into two simple loops that run with the
/// outline: `outer` from the first bridge's end to the second's, across,
/// `hole` back to the first bridge, and the rest the other way round. A
/// vertex the two loops share is a bridge of no length. `None` when no
/// two bridges lie inside the ring without crossing anything.
fn bridge_split(
    outer: &[u32],
    hole: &[u32],
    others: &[&Vec<u32>],
    flat: &impl Fn(u32) -> glam::DVec2,
) -> Option<(Vec<u32>, Vec<u32>)> {
    let loops: Vec<&[u32]> = [outer, hole]
        .into_iter()
        .chain(others.iter().map(|l| l.as_slice()))
        .collect();
    // A bridge from outer corner i to hole corner j: inside the ring, and
    // crossing no edge that does not end at one of its ends.
    let valid = |i: usize, j: usize| {
        let (a, b) = (outer[i], hole[j]);
        if a == b {
            return true;
        }
        let (p, q) = (flat(a), flat(b));
        if p == q {
            return false;
        }
        for l in &loops {
            for (k, &x) in l.iter().enumerate() {
                let y = l[(k + 1) % l.len()];
                if [x, y].iter().any(|&v| v == a || v == b) {
                    continue;
                }
                if segments_meet(p, q, flat(x), flat(y)) {
                    return false;
                }
            }
        }
        let middle = 0.5 * (p + q);
        loops
            .iter()
            .filter(|l| point_in_loop(middle, l, flat))
            .count()
            % 2
            == 1
    };
    let (no, nh) = (outer.len(), hole.len());
    let by_distance = |j: usize| {
        let mut order: Vec<usize> = (0..no).collect();
        let h = flat(hole[j]);
        order.sort_by(|&x, &y| {
            h.distance_squared(flat(outer[x]))
                .total_cmp(&h.distance_squared(flat(outer[y])))
        });
        order
    };
    // The first bridge: a shared vertex, else the shortest valid one from
    // the hole's corner nearest the outer loop.
    let first = (0..nh)
        .find_map(|j| outer.iter().position(|&v| v == hole[j]).map(|i| (i, j)))
        .or_else(|| {
            let mut js: Vec<usize> = (0..nh).collect();
            let gap = |j: usize| {
                outer
                    .iter()
                    .map(|&v| flat(v).distance_squared(flat(hole[j])))
                    .fold(f64::INFINITY, f64::min)
            };
            js.sort_by(|&x, &y| gap(x).total_cmp(&gap(y)));
            js.into_iter().find_map(|j| {
                by_distance(j)
                    .into_iter()
                    .find(|&i| valid(i, j))
                    .map(|i| (i, j))
            })
        })?;
    let (i1, j1) = first;
    // The second: from the hole's corner farthest round from the first,
    // not sharing an end with the first, not crossing it.
    let mut js: Vec<usize> = (1..nh).map(|d| (j1 + d) % nh).collect();
    js.sort_by_key(|&j| ((j + nh - j1) % nh).abs_diff(nh / 2));
    let (p1, q1) = (flat(outer[i1]), flat(hole[j1]));
    let (i2, j2) = js.into_iter().find_map(|j| {
        by_distance(j)
            .into_iter()
            .find(|&i| {
                i != i1
                    && hole[j] != outer[i1]
                    && outer[i] != hole[j1]
                    && valid(i, j)
                    && (outer[i1] == hole[j1]
                        || outer[i] == hole[j]
                        || !segments_meet(p1, q1, flat(outer[i]), flat(hole[j])))
            })
            .map(|i| (i, j))
    })?;
    let run = |l: &[u32], from: usize, to: usize| {
        let mut out = vec![l[from]];
        let mut k = from;
        while k != to {
            k = (k + 1) % l.len();
            out.push(l[k]);
        }
        out
    };
    let join = |mut a: Vec<u32>, b: Vec<u32>| {
        for v in b {
            if a.last() != Some(&v) {
                a.push(v);
            }
        }
        while a.len() > 1 && a.first() == a.last() {
            a.pop();
        }
        a
    };
    let one = join(run(outer, i1, i2), run(hole, j2, j1));
    let two = join(run(outer, i2, i1), run(hole, j1, j2));
    let simple = |l: &[u32]| l.len() >= 3 && l.iter().enumerate().all(|(k, v)| !l[..k].contains(v));
    (simple(&one) && simple(&two)).then_some((one, two))
}

#[inline]
pub(crate) fn check_face(face: usize, poly: &[u32], vertex_count: usize) -> Result<(), BuildError> {
    if poly.len() < 3 {
        return Err(BuildError::TooFewSides {
            face,
            sides: poly.len(),
        });
    }
    for (i, &v) in poly.iter().enumerate() {
        if v as usize >= vertex_count {
            return Err(BuildError::IndexOutOfRange {
                face,
                index: v,
                vertex_count,
            });
        }
        if poly[..i].contains(&v) {
            return Err(BuildError::RepeatedVertex { face, vertex: v });
        }
    }
    Ok(())
}

impl HalfEdgeMesh {
    /// Like [`from_polygons`](Self::from_polygons), but repairs instead of
    /// failing: faces that are malformed or would make an edge non-manifold or
    /// flip orientation are dropped (first come, first kept), and vertices
    /// where separate fans meet are duplicated, one copy per extra fan.
    /// Non-finite positions drop the faces that use them.
    ///
    /// Complexity: O(corners) expected (hash map of directed edges).
    pub fn from_polygons_repaired<P: AsRef<[u32]>>(
        positions: &[DVec3],
        polygons: &[P],
    ) -> Result<(Self, RepairReport), BuildError> {
        // Most files need no repair: the strict build has no hash maps and,
        // when it succeeds, gives the very mesh the repair would (nothing
        // dropped, nothing split, faces in input order).
        if let Ok(mesh) = Self::from_polygons(positions, polygons) {
            let report = RepairReport {
                face_origin: (0..polygons.len()).collect(),
                ..RepairReport::default()
            };
            return Ok((mesh, report));
        }
        let mut report = RepairReport::default();
        let mut kept: Vec<Vec<u32>> = Vec::new();
        let mut used: HashMap<(u32, u32), usize> = HashMap::new(); // directed edge -> kept face
        // A face that visits a vertex twice becomes its simple loops, each
        // checked and kept like a face of its own.
        let mut pieces: Vec<(usize, Vec<u32>)> = Vec::with_capacity(polygons.len());
        for (fi, poly) in polygons.iter().enumerate() {
            let poly = poly.as_ref();
            match simple_loops(poly) {
                Some(loops)
                    if !loops.is_empty()
                        && poly.iter().all(|&v| (v as usize) < positions.len()) =>
                {
                    let loops = keep_outline(positions, poly, loops);
                    report.split_faces.push((fi, loops.len()));
                    pieces.extend(loops.into_iter().map(|l| (fi, l)));
                }
                _ => pieces.push((fi, poly.to_vec())),
            }
        }
        for (fi, poly) in &pieces {
            let (fi, poly) = (*fi, poly.as_slice());
            if let Err(e) = check_face(fi, poly, positions.len()) {
                report.dropped_faces.push((fi, e));
                continue;
            }
            if let Some(&v) = poly.iter().find(|&&v| !positions[v as usize].is_finite()) {
                report
                    .dropped_faces
                    .push((fi, BuildError::NonFinitePosition { vertex: v }));
                continue;
            }
            let n = poly.len();
            let conflict = (0..n).find_map(|i| {
                let (a, b) = (poly[i], poly[(i + 1) % n]);
                if let Some(&other) = used.get(&(a, b)) {
                    let mut faces = vec![report.face_origin[other], fi];
                    return Some(match used.get(&(b, a)) {
                        // Both sides taken: every face on the edge.
                        Some(&twin) => {
                            faces.push(report.face_origin[twin]);
                            faces.sort_unstable();
                            BuildError::NonManifoldEdge {
                                a: a.min(b),
                                b: a.max(b),
                                faces,
                            }
                        }
                        None => BuildError::InconsistentOrientation { a, b, faces },
                    });
                }
                None
            });
            if let Some(e) = conflict {
                report.dropped_faces.push((fi, e));
                continue;
            }
            for i in 0..n {
                used.insert((poly[i], poly[(i + 1) % n]), kept.len());
            }
            report.face_origin.push(fi);
            kept.push(poly.to_vec());
        }

        // Split vertices where separate fans meet: corners around a vertex that
        // share an edge belong to one fan (union-find over corners).
        let corner_base: Vec<usize> = kept
            .iter()
            .scan(0, |acc, p| {
                let b = *acc;
                *acc += p.len();
                Some(b)
            })
            .collect();
        let total: usize = kept.iter().map(Vec::len).sum();
        let mut parent: Vec<usize> = (0..total).collect();
        fn find(parent: &mut [usize], mut x: usize) -> usize {
            while parent[x] != x {
                parent[x] = parent[parent[x]];
                x = parent[x];
            }
            x
        }
        for (f, poly) in kept.iter().enumerate() {
            let n = poly.len();
            for i in 0..n {
                let (a, b) = (poly[i], poly[(i + 1) % n]);
                if let Some(&g) = used.get(&(b, a)) {
                    let other = &kept[g];
                    let m = other.len();
                    let j = other
                        .iter()
                        .position(|&x| x == b)
                        .expect("edge b->a lies in face g");
                    // In face g the edge runs b (corner j) -> a (corner j+1).
                    let pairs = [
                        (corner_base[f] + i, corner_base[g] + (j + 1) % m),
                        (corner_base[f] + (i + 1) % n, corner_base[g] + j),
                    ];
                    for (x, y) in pairs {
                        let (rx, ry) = (find(&mut parent, x), find(&mut parent, y));
                        parent[rx] = ry;
                    }
                }
            }
        }
        let mut new_positions = positions.to_vec();
        let mut fan_vertex: HashMap<usize, u32> = HashMap::new(); // fan root -> vertex id
        let mut first_fan: HashMap<u32, usize> = HashMap::new(); // vertex -> its first fan root
        let mut copies: HashMap<u32, usize> = HashMap::new();
        for (f, poly) in kept.iter_mut().enumerate() {
            for (i, v) in poly.iter_mut().enumerate() {
                let root = find(&mut parent, corner_base[f] + i);
                if let Some(&nv) = fan_vertex.get(&root) {
                    *v = nv;
                    continue;
                }
                let orig = *v;
                let id = match first_fan.get(&orig) {
                    None => {
                        first_fan.insert(orig, root);
                        orig
                    }
                    Some(_) => {
                        new_positions.push(positions[orig as usize]);
                        *copies.entry(orig).or_default() += 1;
                        (new_positions.len() - 1) as u32
                    }
                };
                fan_vertex.insert(root, id);
                *v = id;
            }
        }
        report.split_vertices = copies.into_iter().collect();
        report.split_vertices.sort_unstable();
        let mesh = Self::from_polygons(&new_positions, &kept)?;
        Ok((mesh, report))
    }

    /// Positions and polygons (vertex ids as indices) of the live faces, for
    /// export. Dead vertex slots keep their index, so the output may contain
    /// unused positions; use [`compacted`](Self::compacted) first to avoid that.
    pub fn to_polygons(&self) -> (Vec<DVec3>, Vec<Vec<u32>>) {
        let polys = self
            .faces()
            .map(|f| self.face_vertices(f).map(|v| v.0).collect())
            .collect();
        (self.positions().to_vec(), polys)
    }

    /// Self when there are no dead slots, else [`compacted`](Self::compacted).
    pub fn compacted_if_needed(self) -> HalfEdgeMesh {
        let unused = self.vertices().any(|v| self.is_isolated_vertex(v));
        if self.vertex_count() == self.vertex_capacity() && !unused {
            self
        } else {
            self.compacted()
        }
    }

    /// A copy with dead slots (and vertices no face uses) removed and ids renumbered densely, in the old
    /// order. Returns the new mesh.
    ///
    /// Faces with inner rings or without edges cannot be rebuilt from
    /// polygons; a mesh with such faces is renumbered record by record (its
    /// lone vertices are kept).
    pub fn compacted(&self) -> HalfEdgeMesh {
        if self.first_non_polygon_face().is_some() {
            return self.compacted_records();
        }
        let mut vmap = vec![NONE; self.vertex_capacity()];
        let mut positions = Vec::with_capacity(self.vertex_count());
        for v in self.vertices().filter(|&v| !self.is_isolated_vertex(v)) {
            vmap[v.index()] = positions.len() as u32;
            positions.push(self.position(v));
        }
        let polys: Vec<Vec<u32>> = self
            .faces()
            .map(|f| self.face_vertices(f).map(|v| vmap[v.index()]).collect())
            .collect();
        HalfEdgeMesh::from_polygons(&positions, &polys)
            .expect("a valid mesh stays valid when renumbered")
    }
}
