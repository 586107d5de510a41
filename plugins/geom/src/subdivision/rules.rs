//! The subdivision masks: which parent points, with which weights, make each
//! child point. Written once against a [`Sink`], so the same rules compute
//! positions directly and record stencil weights.
//!
//! Sources: Catmull-Clark face/edge/vertex masks and the crease and boundary
//! rules from seed 003 (Bán, "Catmull-Clark", slides on boundary and sharp
//! creases) and DeRose, Kass, Truong, "Subdivision Surfaces in Character
//! Animation" (SIGGRAPH 1998) for semi-sharp creases; the fractional blend
//! between rules and Chaikin's crease sharpness are OpenSubdiv's Sdc
//! (`crease.cpp`); Loop's masks from C. Loop, "Smooth Subdivision Surfaces
//! Based on Triangles" (1987).

use std::f64::consts::TAU;

use super::level::{Level, NONE};
use super::{CreaseMethod, INFINITE_SHARPNESS};

/// The face weight of a triangle in a smooth Catmull-Clark edge mask with
/// smooth triangles (OpenSubdiv's `CATMARK_SMOOTH_TRI_EDGE_WEIGHT`).
const TRIANGLE_EDGE_WEIGHT: f64 = 0.47;

/// Receives the weighted sources of one child point.
pub(crate) trait Sink {
    /// Parent vertex `v` with weight `w`.
    fn vertex(&mut self, v: u32, w: f64);
    /// The face point (centroid) of parent face `f` with weight `w`.
    fn face(&mut self, f: u32, w: f64);
}

/// The smoothing masks of a scheme; `Linear` only splits.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Masks {
    CatmullClark,
    Loop,
    Linear,
}

pub(crate) fn is_infinite(s: f32) -> bool {
    s >= INFINITE_SHARPNESS
}

/// Sharpness one level down: infinite stays, otherwise minus one, floored at 0.
pub(crate) fn decrement(s: f32) -> f32 {
    if is_infinite(s) {
        s
    } else {
        (s - 1.0).max(0.0)
    }
}

/// Sharpness of the child edge of `e` that touches `v`. Uniform: `s − 1`.
/// Chaikin: `¾ s + ¼ (mean of the other semi-sharp edges at v)`, then − 1.
pub(crate) fn child_edge_sharpness(level: &Level, e: u32, v: u32, method: CreaseMethod) -> f32 {
    let mut s = level.edge_sharp(e);
    if s <= 0.0 || is_infinite(s) {
        return s;
    }
    if method == CreaseMethod::Chaikin {
        let (mut sum, mut count) = (0.0f32, 0u32);
        for &other in level.vertex_edges(v) {
            let so = level.edge_sharp(other);
            if other != e && so > 0.0 && !is_infinite(so) {
                sum += so;
                count += 1;
            }
        }
        if count > 0 {
            s = 0.75 * s + 0.25 * sum / count as f32;
        }
    }
    decrement(s)
}

/// Vertex rules in order of sharpness (Sdc's `Crease::Rule`).
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Rule {
    Smooth,
    Dart,
    Crease,
    Corner,
}

fn rule(vertex_sharpness: f32, sharp_edges: usize) -> Rule {
    if vertex_sharpness > 0.0 {
        return Rule::Corner;
    }
    match sharp_edges {
        0 => Rule::Smooth,
        1 => Rule::Dart,
        2 => Rule::Crease,
        _ => Rule::Corner,
    }
}

/// The face point: the centroid of the face's vertices.
pub(crate) fn face_mask(level: &Level, f: u32, sink: &mut impl Sink) {
    let corners = level.face_corners(f);
    let w = 1.0 / corners.len() as f64;
    for c in corners {
        sink.vertex(level.face_vertices[c], w);
    }
}

/// The edge point of edge `e`. Smooth Catmull-Clark: ¼ of each end and of
/// each adjacent face point; smooth Loop: ⅜ of each end and ⅛ of the two
/// opposite vertices; sharp (s ≥ 1, boundary): the midpoint; 0 < s < 1 blends
/// the two with weight s. With `smooth_triangles` (OpenSubdiv's
/// `TRI_SUB_SMOOTH`, `catmarkScheme.h`), a Catmull-Clark edge beside a
/// triangle weighs each face point by `f = (w0 + w1) / 2`, where `w` is 0.47
/// for a triangle and 0.25 otherwise, and each end by `(1 − 2f) / 2`.
pub(crate) fn edge_mask(
    level: &Level,
    e: u32,
    masks: Masks,
    smooth_triangles: bool,
    sink: &mut impl Sink,
) {
    let [a, b] = level.edge_vertices[e as usize];
    let s = level.edge_sharp(e) as f64;
    let sharp = if masks == Masks::Linear || level.is_boundary_edge(e) {
        1.0
    } else {
        s.min(1.0)
    };
    let smooth = 1.0 - sharp;
    if sharp > 0.0 {
        sink.vertex(a, 0.5 * sharp);
        sink.vertex(b, 0.5 * sharp);
    }
    if smooth <= 0.0 {
        return;
    }
    let [f0, f1] = level.edge_faces(e);
    match masks {
        Masks::CatmullClark => {
            let (mut vw, mut fw) = (0.25, 0.25);
            if smooth_triangles {
                let tri = |f: u32| level.face_corners(f).len() == 3;
                if tri(f0) || tri(f1) {
                    let w = |f: u32| if tri(f) { TRIANGLE_EDGE_WEIGHT } else { 0.25 };
                    fw = 0.5 * (w(f0) + w(f1));
                    vw = 0.5 * (1.0 - 2.0 * fw);
                }
            }
            sink.vertex(a, vw * smooth);
            sink.vertex(b, vw * smooth);
            sink.face(f0, fw * smooth);
            sink.face(f1, fw * smooth);
        }
        Masks::Loop => {
            sink.vertex(a, 0.375 * smooth);
            sink.vertex(b, 0.375 * smooth);
            for f in [f0, f1] {
                sink.vertex(opposite_vertex(level, f, e), 0.125 * smooth);
            }
        }
        Masks::Linear => unreachable!("linear edges are always sharp"),
    }
}

/// The vertex of triangle `f` that is not on edge `e`.
fn opposite_vertex(level: &Level, f: u32, e: u32) -> u32 {
    let corners = level.face_corners(f);
    let c = corners
        .clone()
        .find(|&c| level.face_edges[c] == e)
        .expect("edge belongs to its face");
    level.face_vertices[level.next_corner(level.next_corner(c))]
}

/// The vertex point of vertex `v`: the smooth mask for smooth vertices and
/// darts, the crease mask `(a + 6v + b) / 8` along two sharp edges, the
/// corner mask (v stays) at three or more or at a sharp vertex. When
/// sharpness runs out during this step, the parent rule and the child rule
/// are blended by the mean sharpness that ran out (OpenSubdiv's fractional
/// weight), which is what makes sharpness 0.5 land between smooth and sharp.
pub(crate) fn vertex_mask(
    level: &Level,
    v: u32,
    masks: Masks,
    method: CreaseMethod,
    sink: &mut impl Sink,
) {
    if masks == Masks::Linear {
        sink.vertex(v, 1.0);
        return;
    }
    let edges = level.vertex_edges(v);
    let sharpness = |e: &u32| level.edge_sharp(*e);
    let vs = level.vertex_sharp(v);
    let parent_rule = rule(vs, edges.iter().filter(|e| sharpness(e) > 0.0).count());
    if parent_rule <= Rule::Dart {
        smooth_vertex_mask(level, v, masks, 1.0, sink);
        return;
    }
    let child_vs = decrement(vs);
    let (mut ran_out_sum, mut ran_out_count) = (0.0f32, 0u32);
    if vs > 0.0 && child_vs <= 0.0 {
        ran_out_sum += vs;
        ran_out_count += 1;
    }
    let mut child_sharp = [NONE; 2];
    let mut child_sharp_count = 0;
    for &e in edges {
        let cs = child_edge_sharpness(level, e, v, method);
        if cs > 0.0 {
            if child_sharp_count < 2 {
                child_sharp[child_sharp_count] = e;
            }
            child_sharp_count += 1;
        } else if level.edge_sharp(e) > 0.0 {
            ran_out_sum += level.edge_sharp(e);
            ran_out_count += 1;
        }
    }
    let child_rule = rule(child_vs, child_sharp_count);
    let parent_sharp: Vec<u32> = edges
        .iter()
        .copied()
        .filter(|e| sharpness(e) > 0.0)
        .collect();
    if child_rule == parent_rule || ran_out_count == 0 {
        sharp_vertex_mask(level, v, parent_rule, &parent_sharp, 1.0, sink);
        return;
    }
    let parent_weight = (ran_out_sum / ran_out_count as f32).min(1.0) as f64;
    sharp_vertex_mask(level, v, parent_rule, &parent_sharp, parent_weight, sink);
    let child_weight = 1.0 - parent_weight;
    match child_rule {
        Rule::Smooth | Rule::Dart => smooth_vertex_mask(level, v, masks, child_weight, sink),
        rule => sharp_vertex_mask(level, v, rule, &child_sharp, child_weight, sink),
    }
}

/// Crease `(a + 6v + b) / 8` or corner (v) mask, scaled by `weight`.
fn sharp_vertex_mask(
    level: &Level,
    v: u32,
    rule: Rule,
    crease_edges: &[u32],
    weight: f64,
    sink: &mut impl Sink,
) {
    if rule == Rule::Crease {
        sink.vertex(v, 0.75 * weight);
        for &e in &crease_edges[..2] {
            sink.vertex(level.other_end(e, v), 0.125 * weight);
        }
    } else {
        sink.vertex(v, weight);
    }
}

/// Smooth vertex masks, scaled by `weight`. Catmull-Clark (seed 003, valence
/// n): `((n − 2) v + Σ e_i / n + Σ f_i / n) / n`; Loop: `(1 − nβ) v + β Σ e_i`
/// with `β = (5/8 − (3/8 + cos(2π/n)/4)²) / n`.
fn smooth_vertex_mask(level: &Level, v: u32, masks: Masks, weight: f64, sink: &mut impl Sink) {
    let edges = level.vertex_edges(v);
    let n = edges.len() as f64;
    match masks {
        Masks::CatmullClark => {
            let corners = level.vertex_corners(v);
            sink.vertex(v, weight * (n - 2.0) / n);
            let w_edge = weight / (n * n);
            for &e in edges {
                sink.vertex(level.other_end(e, v), w_edge);
            }
            let w_face = weight / (n * corners.len() as f64);
            for &c in corners {
                sink.face(level.corner_face(c as usize), w_face);
            }
        }
        Masks::Loop => {
            let beta = loop_beta(edges.len());
            sink.vertex(v, weight * (1.0 - n * beta));
            for &e in edges {
                sink.vertex(level.other_end(e, v), weight * beta);
            }
        }
        Masks::Linear => sink.vertex(v, weight),
    }
}

/// Loop's β for valence n.
pub(crate) fn loop_beta(valence: usize) -> f64 {
    let n = valence as f64;
    let c = 0.375 + 0.25 * (TAU / n).cos();
    (0.625 - c * c) / n
}
