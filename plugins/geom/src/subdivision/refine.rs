//! Topology of the child level: which child points exist and how they form
//! faces and edges. Positions come from [`super::rules`]; this file only
//! numbers things.
//!
//! Child points are numbered face points first, then edge points, then vertex
//! points (OpenSubdiv's default order), so child vertex `F + E + v` is the
//! vertex point of parent vertex `v`.

use std::f64::consts::TAU;

use super::CreaseMethod;
use super::level::{Level, Lists, NONE};
use super::rules::{child_edge_sharpness, decrement};

/// How faces are split.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Split {
    /// Every n-gon becomes n quads around a face point (Catmull-Clark).
    Quads,
    /// Every triangle becomes four (Loop); needs an all-triangle level.
    Triangles,
    /// One face per face, edge and vertex, around new corner points (Doo-Sabin).
    Dual,
}

impl Split {
    /// Number of face points at the start of the child's vertex list.
    pub fn face_points(self, parent: &Level) -> usize {
        match self {
            Split::Quads => parent.face_count(),
            Split::Triangles | Split::Dual => 0,
        }
    }
}

/// The child level of `parent`. With `with_adjacency` (the child will be
/// refined in turn), the child's derived tables are set too where the
/// split makes them known without a search.
pub(crate) fn refine_topology(
    parent: &Level,
    split: Split,
    method: CreaseMethod,
    with_adjacency: bool,
) -> Level {
    // The derived tables below assume at most two faces per edge.
    let with_adjacency = with_adjacency && !parent.non_manifold;
    let mut child = match split {
        Split::Quads => {
            let mut child = split_quads(parent, method);
            if with_adjacency {
                quad_child_adjacency(parent, &mut child);
            }
            child
        }
        Split::Triangles => {
            let mut child = split_triangles(parent, method);
            if with_adjacency {
                triangle_child_adjacency(parent, &mut child);
            }
            child
        }
        Split::Dual => doo_sabin_topology(parent),
    };
    child.non_manifold = parent.non_manifold;
    child
}

/// Child edges `2e` and `2e + 1` are the halves of parent edge `e` (at its
/// first and second end), with their sharpness; then `extra` edges of
/// sharpness 0 the caller pushes. Vertex sharpness decrements.
fn split_edges(
    parent: &Level,
    first_edge_point: u32,
    first_vertex_point: u32,
    extra: usize,
    method: CreaseMethod,
    child: &mut Level,
) {
    let ne = parent.edge_count();
    child.edge_vertices.reserve_exact(2 * ne + extra);
    for (e, &[a, b]) in parent.edge_vertices.iter().enumerate() {
        let ep = first_edge_point + e as u32;
        child.edge_vertices.push([first_vertex_point + a, ep]);
        child.edge_vertices.push([ep, first_vertex_point + b]);
    }
    let total = 2 * ne + extra;
    // A smooth parent has smooth children: no tables (Level::is_smooth).
    if !parent.edge_sharpness.is_empty() {
        child.edge_sharpness = Vec::with_capacity(total);
        for (e, &[a, b]) in parent.edge_vertices.iter().enumerate() {
            child
                .edge_sharpness
                .push(child_edge_sharpness(parent, e as u32, a, method));
            child
                .edge_sharpness
                .push(child_edge_sharpness(parent, e as u32, b, method));
        }
        child.edge_sharpness.resize(total, 0.0);
    }
    if !parent.vertex_sharpness.is_empty() {
        child.vertex_sharpness = vec![0.0; first_vertex_point as usize];
        child
            .vertex_sharpness
            .extend(parent.vertex_sharpness.iter().map(|&s| decrement(s)));
    }
    child.drop_zero_sharpness();
}

/// The child half of parent edge `e` that touches parent vertex `v`.
#[inline]
fn half(parent: &Level, e: u32, v: u32) -> u32 {
    2 * e + u32::from(parent.edge_vertices[e as usize][0] != v)
}

fn split_quads(parent: &Level, method: CreaseMethod) -> Level {
    let (nf, ne, nv) = (
        parent.face_count() as u32,
        parent.edge_count() as u32,
        parent.vertex_count as u32,
    );
    let corners = parent.face_vertices.len();
    let mut child = Level {
        vertex_count: (nf + ne + nv) as usize,
        ..Level::default()
    };
    split_edges(parent, nf, nf + ne, corners, method, &mut child);
    // Edge 2E + c joins the edge point of corner c's edge to the face point.
    for f in 0..nf {
        for &e in &parent.face_edges[parent.face_corners(f)] {
            child.edge_vertices.push([nf + e, f]);
        }
    }
    child.sides = 4;
    // Child face c (one per parent corner c): the corner's vertex point, the
    // edge points of its edge and of the edge before, the face point.
    let mut face_vertices = Vec::with_capacity(4 * corners);
    let mut face_edges = Vec::with_capacity(4 * corners);
    for f in 0..nf {
        let r = parent.face_corners(f);
        let (start, n) = (r.start, r.len());
        let fv = &parent.face_vertices[r.clone()];
        let fe = &parent.face_edges[r];
        for k in 0..n {
            let p = if k == 0 { n - 1 } else { k - 1 };
            let (v, e, ep) = (fv[k], fe[k], fe[p]);
            face_vertices.extend_from_slice(&[nf + ne + v, nf + e, f, nf + ep]);
            face_edges.extend_from_slice(&[
                half(parent, e, v),
                2 * ne + (start + k) as u32,
                2 * ne + (start + p) as u32,
                half(parent, ep, v),
            ]);
        }
    }
    child.face_vertices = face_vertices;
    child.face_edges = face_edges;
    (child.face_origin, child.origin_shift) = corner_origins(parent);
    child
}

/// The child level's face origins when each parent corner is a child face
/// (Catmull-Clark): an all-quad parent's children `4f..4f + 4` share its
/// table one shift further; otherwise each child face gets its parent's
/// origin.
fn corner_origins(parent: &Level) -> (std::sync::Arc<[u32]>, u32) {
    if parent.sides == 4 {
        (parent.face_origin.clone(), parent.origin_shift + 2)
    } else {
        let origins = (0..parent.face_vertices.len())
            .map(|c| parent.face_origin(parent.corner_face(c) as usize))
            .collect();
        (origins, 0)
    }
}

fn split_triangles(parent: &Level, method: CreaseMethod) -> Level {
    let (nf, ne, nv) = (
        parent.face_count() as u32,
        parent.edge_count() as u32,
        parent.vertex_count as u32,
    );
    let mut child = Level {
        vertex_count: (ne + nv) as usize,
        ..Level::default()
    };
    split_edges(parent, 0, ne, 3 * nf as usize, method, &mut child);
    // Edge 2E + 3f + i cuts off corner i: it joins the edge points of the
    // edges before and after that corner.
    for fe in parent.face_edges.chunks_exact(3) {
        child
            .edge_vertices
            .extend_from_slice(&[[fe[0], fe[2]], [fe[1], fe[0]], [fe[2], fe[1]]]);
    }
    child.sides = 3;
    let mut face_vertices = Vec::with_capacity(12 * nf as usize);
    let mut face_edges = Vec::with_capacity(12 * nf as usize);
    for (f, (fv, fe)) in parent
        .face_vertices
        .chunks_exact(3)
        .zip(parent.face_edges.chunks_exact(3))
        .enumerate()
    {
        let inner = |i: u32| 2 * ne + 3 * f as u32 + i;
        let halves = [
            half(parent, fe[0], fv[0]),
            half(parent, fe[2], fv[0]),
            half(parent, fe[1], fv[1]),
            half(parent, fe[0], fv[1]),
            half(parent, fe[2], fv[2]),
            half(parent, fe[1], fv[2]),
        ];
        face_vertices.extend_from_slice(&[
            ne + fv[0],
            fe[0],
            fe[2],
            ne + fv[1],
            fe[1],
            fe[0],
            ne + fv[2],
            fe[2],
            fe[1],
            fe[0],
            fe[1],
            fe[2],
        ]);
        face_edges.extend_from_slice(&[
            halves[0],
            inner(0),
            halves[1],
            halves[2],
            inner(1),
            halves[3],
            halves[4],
            inner(2),
            halves[5],
            inner(1),
            inner(2),
            inner(0),
        ]);
    }
    child.face_vertices = face_vertices;
    child.face_edges = face_edges;
    // Triangle f's quarters are 4f..4f + 4: the parent's table, one shift on.
    (child.face_origin, child.origin_shift) = (parent.face_origin.clone(), parent.origin_shift + 2);
    child
}

/// The derived tables of `child = split_quads(parent)`, read off the
/// parent's in the numbering above instead of searched for (as
/// OpenSubdiv's `Vtr::QuadRefinement` populates its child relations).
/// Child face `c` (parent corner `c`, at vertex `v`, after corner `p`, in
/// face `f`) has the corners `4c..4c + 4` at VP(v), EP(e_c), FP(f),
/// EP(e_p), starting the edges half(e_c, v), `2E + c`, `2E + p`,
/// half(e_p, v). Lists come out in increasing order, as the counting sort
/// of `Level` gives them.
fn quad_child_adjacency(parent: &Level, child: &mut Level) {
    let (nf, ne) = (parent.face_count(), parent.edge_count());
    let corners = parent.face_vertices.len();
    let edge_corners = parent.edge_corner_table();
    let vertex_edges = parent.vertex_edge_lists();
    let vertex_corners = parent.vertex_corner_lists();
    let next = |c: u32| parent.next_corner(c as usize) as u32;
    let sorted = |a: u32, b: u32| if a < b { [a, b] } else { [b, a] };

    // Edge corners: the halves of each parent edge, then the inner edges.
    // Child face c's corner 0 starts the half of e_c at c's vertex; the
    // half at its far end is started by corner 3 of child face next(c).
    let mut child_edge_corners = Vec::with_capacity(2 * ne + corners);
    push_half_corners(
        parent,
        |c| 4 * c,
        |c| 4 * next(c) + 3,
        &mut child_edge_corners,
    );
    for c in 0..corners as u32 {
        child_edge_corners.push(sorted(4 * c + 1, 4 * next(c) + 2));
    }

    // Vertex lists: face points, edge points, vertex points.
    let face_start = |f: usize| parent.face_corners(f as u32).start as u32;
    let mut edge_offsets = Vec::with_capacity(child.vertex_count + 1);
    let mut corner_offsets = Vec::with_capacity(child.vertex_count + 1);
    edge_offsets.extend((0..nf).map(face_start));
    corner_offsets.extend((0..nf).map(face_start));
    let (mut edge_end, mut corner_end) = (corners as u32, corners as u32);
    let mut edge_items = Vec::with_capacity(2 * child.edge_vertices.len());
    let mut corner_items = Vec::with_capacity(4 * corners);
    edge_items.extend((0..corners as u32).map(|c| 2 * ne as u32 + c));
    corner_items.extend((0..corners as u32).map(|c| 4 * c + 2));
    for (e, &[c0, c1]) in edge_corners.iter().enumerate() {
        edge_offsets.push(edge_end);
        corner_offsets.push(corner_end);
        let e = e as u32;
        let inner = 2 * ne as u32;
        if c1 == NONE {
            edge_items.extend_from_slice(&[2 * e, 2 * e + 1, inner + c0]);
            corner_items.extend_from_slice(&sorted(4 * c0 + 1, 4 * next(c0) + 3));
            edge_end += 3;
            corner_end += 2;
        } else {
            edge_items.extend_from_slice(&[2 * e, 2 * e + 1, inner + c0, inner + c1]);
            let mut around = [4 * c0 + 1, 4 * next(c0) + 3, 4 * c1 + 1, 4 * next(c1) + 3];
            around.sort_unstable();
            corner_items.extend_from_slice(&around);
            edge_end += 4;
            corner_end += 4;
        }
    }
    for v in 0..parent.vertex_count {
        edge_offsets.push(edge_end + vertex_edges.offsets[v]);
        corner_offsets.push(corner_end + vertex_corners.offsets[v]);
        push_vertex_point_edges(parent, v, &mut edge_items);
        corner_items.extend(vertex_corners.get(v).iter().map(|&c| 4 * c));
    }
    edge_offsets.push(edge_items.len() as u32);
    corner_offsets.push(corner_items.len() as u32);
    child.set_adjacency(
        child_edge_corners,
        Lists {
            offsets: edge_offsets,
            items: edge_items,
        },
        Some(Lists {
            offsets: corner_offsets,
            items: corner_items,
        }),
    );
}

/// The derived tables of `child = split_triangles(parent)` (edge corners
/// and vertex edges; Loop's masks need no vertex corners), read off the
/// parent's as [`quad_child_adjacency`] does. Triangle `f`'s children
/// `4f..4f + 4` have the corners `12f..12f + 12`: child `4f + k` is
/// VP(v_k), EP(e_k), EP(e_{k-1}) with the edges half(e_k, v_k), inner
/// `2E + 3f + k`, half(e_{k-1}, v_k); child `4f + 3` is EP(e0), EP(e1),
/// EP(e2) with the inner edges 1, 2, 0. So the half of parent corner `c`'s
/// edge at its start is started by corner 0 of child `4f + k`, the half at
/// its end by corner 2 of the child at `next(c)`, and EP(e_c) touches the
/// inner edges `2E + c` and `2E + next(c)`.
fn triangle_child_adjacency(parent: &Level, child: &mut Level) {
    let ne = parent.edge_count();
    let edge_corners = parent.edge_corner_table();
    let vertex_edges = parent.vertex_edge_lists();
    let next = |c: u32| parent.next_corner(c as usize) as u32;
    let inner = 2 * ne as u32;
    // Child corner `pos` of child face 4f + k, where c = 3f + k.
    let child_corner = |c: u32, pos: u32| 4 * c - c % 3 + pos;
    let start = |c: u32| child_corner(c, 0);
    let end = |c: u32| child_corner(next(c), 2);

    let mut child_edge_corners = Vec::with_capacity(child.edge_vertices.len());
    push_half_corners(parent, start, end, &mut child_edge_corners);
    for f in 0..parent.face_count() as u32 {
        let q = 12 * f;
        child_edge_corners.extend_from_slice(&[[q + 1, q + 11], [q + 4, q + 9], [q + 7, q + 10]]);
    }

    let mut offsets = Vec::with_capacity(child.vertex_count + 1);
    let mut items = Vec::with_capacity(2 * child.edge_vertices.len());
    for (e, &[c0, c1]) in edge_corners.iter().enumerate() {
        offsets.push(items.len() as u32);
        let e = e as u32;
        if c1 == NONE {
            let mut around = [2 * e, 2 * e + 1, inner + c0, inner + next(c0)];
            around[2..].sort_unstable();
            items.extend_from_slice(&around);
        } else {
            let mut around = [inner + c0, inner + next(c0), inner + c1, inner + next(c1)];
            around.sort_unstable();
            items.extend_from_slice(&[2 * e, 2 * e + 1]);
            items.extend_from_slice(&around);
        }
    }
    let vertex_start = items.len() as u32;
    for v in 0..parent.vertex_count {
        offsets.push(vertex_start + vertex_edges.offsets[v]);
        push_vertex_point_edges(parent, v, &mut items);
    }
    offsets.push(items.len() as u32);
    child.set_adjacency(child_edge_corners, Lists { offsets, items }, None);
}

/// Pushes the starting child corners of the two halves of every parent
/// edge (child edges `2e`, `2e + 1`), in increasing order; `start(c)` is
/// the child corner that starts the half of corner `c`'s edge at `c`'s
/// vertex, `end(c)` the one that starts the half at its far end.
fn push_half_corners(
    parent: &Level,
    start: impl Fn(u32) -> u32,
    end: impl Fn(u32) -> u32,
    out: &mut Vec<[u32; 2]>,
) {
    let sorted = |a: u32, b: u32| if a < b { [a, b] } else { [b, a] };
    for (e, &[c0, c1]) in parent.edge_corner_table().iter().enumerate() {
        // c1 runs the other way: its start is c0's far end.
        let (at_c0, at_c1) = if c1 == NONE {
            ([start(c0), NONE], [end(c0), NONE])
        } else {
            (sorted(start(c0), end(c1)), sorted(start(c1), end(c0)))
        };
        if parent.edge_vertices[e][0] == parent.face_vertices[c0 as usize] {
            out.extend_from_slice(&[at_c0, at_c1]);
        } else {
            out.extend_from_slice(&[at_c1, at_c0]);
        }
    }
}

/// Pushes the edges of parent vertex `v`'s vertex point: the half of each
/// of its edges at `v`, in increasing order.
fn push_vertex_point_edges(parent: &Level, v: usize, out: &mut Vec<u32>) {
    let edges = parent.vertex_edge_lists().get(v);
    out.extend(edges.iter().map(|&e| half(parent, e, v as u32)));
}

/// Doo-Sabin's child faces (seed 001, slides 116–118): one per face (its new
/// corner points), one per interior edge (the four corner points at its
/// ends) and one per interior vertex (the corner points around it). Child
/// point `c` is the new point of parent corner `c`.
fn doo_sabin_topology(parent: &Level) -> Level {
    let mut faces: Vec<Vec<u32>> = Vec::new();
    let mut origin = Vec::new();
    for f in 0..parent.face_count() as u32 {
        faces.push(parent.face_corners(f).map(|c| c as u32).collect());
        origin.push(parent.face_origin(f as usize));
    }
    for e in 0..parent.edge_count() as u32 {
        let [f0, f1] = parent.edge_faces(e);
        if f1 == NONE {
            continue;
        }
        let corner_of = |f: u32| {
            parent
                .face_corners(f)
                .find(|&c| parent.face_edges[c] == e)
                .expect("edge belongs to its face")
        };
        let (c0, c1) = (corner_of(f0), corner_of(f1));
        faces.push(vec![
            parent.next_corner(c0) as u32,
            c0 as u32,
            parent.next_corner(c1) as u32,
            c1 as u32,
        ]);
        origin.push(parent.face_origin(f0 as usize));
    }
    for v in 0..parent.vertex_count as u32 {
        let interior = parent
            .vertex_edges(v)
            .iter()
            .all(|&e| !parent.is_boundary_edge(e));
        let Some(&start) = parent.vertex_corners(v).first() else {
            continue;
        };
        if !interior || parent.vertex_corners(v).len() < 3 {
            continue;
        }
        // Walk the faces around v: across the edge that ends at v.
        let mut ring = vec![start];
        let mut c = start as usize;
        loop {
            let e = parent.face_edges[parent.prev_corner(c)];
            let [f0, f1] = parent.edge_faces(e);
            let g = if f0 == parent.corner_face(c) { f1 } else { f0 };
            c = parent
                .face_corners(g)
                .find(|&k| parent.face_vertices[k] == v)
                .expect("neighbour face contains the vertex");
            if c as u32 == start || ring.len() > parent.vertex_corners(v).len() {
                break;
            }
            ring.push(c as u32);
        }
        origin.push(parent.face_origin(parent.corner_face(start as usize) as usize));
        faces.push(ring);
    }
    Level::from_polygons(parent.face_vertices.len(), &faces, origin)
}

/// Doo-Sabin weight of vertex j for the new point of corner i in an n-gon:
/// `(n + 5) / 4n` for j = i, `(3 + 2 cos(2π(i − j)/n)) / 4n` otherwise
/// (Doo & Sabin, "Behaviour of recursive division surfaces near
/// extraordinary points", 1978).
pub(crate) fn doo_sabin_weight(n: usize, i: usize, j: usize) -> f64 {
    let n_f = n as f64;
    if i == j {
        (n_f + 5.0) / (4.0 * n_f)
    } else {
        let k = (i as f64 - j as f64) / n_f;
        (3.0 + 2.0 * (TAU * k).cos()) / (4.0 * n_f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Primitive;
    use crate::subdivision::{BoundaryInterpolation, Creases};

    /// The tables `quad_child_adjacency` reads off the parent are the ones
    /// counted from the child's own faces, on closed and open cages with
    /// triangles, quads and n-gons, two levels deep.
    #[test]
    fn derived_quad_adjacency_equals_counted() {
        let cages = [
            Primitive::Cube { size: 2.0 },
            Primitive::Grid {
                x_segments: 3,
                z_segments: 2,
                size: 2.0,
            },
            Primitive::Cone {
                segments: 5,
                radius: 1.0,
                depth: 2.0,
            },
            Primitive::Cylinder {
                segments: 7,
                radius: 1.0,
                depth: 2.0,
            },
        ];
        for cage in cages {
            let mesh = cage.build().unwrap();
            assert_derived_tables(&mesh, Split::Quads, &format!("{cage:?}"));
        }
    }

    /// Likewise for the triangle split (Loop), on a closed icosahedron and
    /// an open fan of triangles.
    #[test]
    fn derived_triangle_adjacency_equals_counted() {
        let ico = Primitive::IcoSphere {
            subdivisions: 0,
            radius: 1.0,
        }
        .build()
        .unwrap();
        let positions: Vec<crate::DVec3> = (0..5)
            .map(|i| crate::DVec3::new(f64::from(i).cos(), f64::from(i).sin(), 0.0))
            .chain([crate::DVec3::ZERO])
            .collect();
        let fan = crate::HalfEdgeMesh::from_polygons(
            &positions,
            &[[5, 0, 1], [5, 1, 2], [5, 2, 3], [5, 3, 4]],
        )
        .unwrap();
        for (name, mesh) in [("icosahedron", ico), ("fan", fan)] {
            assert_derived_tables(&mesh, Split::Triangles, name);
        }
    }

    /// Refines `mesh` two levels with `split`, deriving each child's tables
    /// from its parent, and checks them against tables counted afresh.
    fn assert_derived_tables(mesh: &crate::HalfEdgeMesh, split: Split, name: &str) {
        let (mut parent, _, _) = Level::from_mesh(
            mesh,
            &Creases::default(),
            BoundaryInterpolation::EdgesOnly,
            false,
        );
        for level in 1..=2 {
            let child = refine_topology(&parent, split, CreaseMethod::Uniform, true);
            let counted = Level {
                adjacency: Default::default(),
                ..child.clone()
            };
            let what = format!("{name} level {level}");
            assert_eq!(
                child.edge_corner_table(),
                counted.edge_corner_table(),
                "{what}"
            );
            assert_eq!(
                child.vertex_edge_lists(),
                counted.vertex_edge_lists(),
                "{what}"
            );
            assert_eq!(
                child.vertex_corner_lists(),
                counted.vertex_corner_lists(),
                "{what}"
            );
            parent = child;
        }
    }
}
