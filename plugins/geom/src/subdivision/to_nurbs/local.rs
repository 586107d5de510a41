//! Refinement around extraordinary vertices only (feature-adaptive
//! refinement: Nießner, Loop, Meyer and DeRose, "Feature-Adaptive GPU
//! Rendering of Catmull-Clark Subdivision Surfaces", ACM TOG 31(1), 2012,
//! §3; OpenSubdiv's adaptive patch tables work the same way).
//!
//! At a level from 2 on, every irregular face has one extraordinary corner
//! `v`; its faces form the *star* of `v`. One more Catmull-Clark step turns
//! the star's `n` faces into `4n`: `3n` of them are regular (their limit
//! surface is an exact bicubic B-spline patch) and the `n` around the child
//! of `v` form the next, half as large, star. The approximation of a star
//! improves with each step (the normal angle by about ×0.4 per step at
//! valence 3, ×0.83 at 12), while the rest of the surface stays as coarse
//! as it was, so each step costs about the same whatever the depth.
//!
//! Each step works on a small cage of its own: the faces within
//! [`RINGS`] rings of `v`, cut out of the level with their points, creases
//! and holes. Catmull-Clark points depend only on the one-ring, so the
//! cut-out's refinement equals the whole mesh's except near the cut (its
//! border): one step changes only the points on the border (the boundary
//! rules), and each further step spreads the change by one ring of the
//! finer level, half a ring of the cut-out's, so never more than one ring of
//! it deep. The star, its neighbours' grids and the measurement samples lie
//! inside that (a test compares with the whole cage refined: two rings
//! already give the same patches).
//!
//! **Watertight.** A coarse exact patch beside a refined star meets two
//! finer exact patches along each of its edges (a T-junction); the limit
//! curve of the coarse edge is the two finer limit curves, so the patches
//! share their boundary exactly (the B-rep writer cuts the coarse side at
//! the finer corners).

use std::collections::HashMap;

use glam::DVec3;

use super::super::level::Level;
use super::super::{Creases, Options};
use super::measure::Report;
use super::{ConvertedPatch, PatchKind, Prepared, ToNurbsError, ToNurbsOptions, convert_prepared};
use crate::{FaceId, HalfEdgeMesh, VertexId};

/// How many rings of faces around the extraordinary vertex each step cuts
/// out: the star is ring 1, and the refinement of the cut-out equals the
/// whole cage's but within one ring of its border; one ring more than the
/// two that a test shows enough.
pub(super) const RINGS: usize = 3;

/// The faces of an extraordinary vertex that are converted apart.
#[derive(Clone, Debug)]
pub(super) struct Star {
    /// The vertex (of the prepared level).
    pub vertex: u32,
    /// Its faces (of the prepared level).
    pub faces: Vec<u32>,
}

/// The stars of `prepared`'s level that can be refined on their own: every
/// face around the irregular vertex is shown, not regular, and has no other
/// irregular corner.
pub(super) fn stars(prepared: &Prepared) -> Vec<Star> {
    let lv = prepared.level();
    let irregular = |v: u32| !prepared.classes[v as usize].is_regular();
    (0..lv.vertex_count as u32)
        .filter(|&v| irregular(v))
        .filter_map(|v| {
            let faces: Vec<u32> = lv
                .vertex_corners(v)
                .iter()
                .map(|&c| lv.corner_face(c as usize))
                .collect();
            let alone = |f: u32| {
                lv.face_corners(f)
                    .filter(|&c| irregular(lv.face_vertices[c]))
                    .count()
                    == 1
            };
            let ok = !faces.is_empty()
                && faces.iter().all(|&f| {
                    prepared.shown[f as usize] && !prepared.regular[f as usize] && alone(f)
                });
            ok.then_some(Star { vertex: v, faces })
        })
        .collect()
}

/// A part of a level cut out as a cage of its own.
pub(super) struct CutOut {
    /// The cage: the faces in order, as faces `0..` of the mesh.
    pub mesh: HalfEdgeMesh,
    /// Its creases and holes, as the level has them.
    pub creases: Creases,
    /// Per face of the cut-out, the level face it is.
    pub level_faces: Vec<u32>,
    /// Per level vertex in the cut-out, its vertex there.
    pub vertices: HashMap<u32, u32>,
}

impl CutOut {
    /// `patches` made from this cut-out, their `cage_faces` turned from
    /// faces of its mesh into the faces of the cage `prepared` refined.
    pub fn patches_of(
        &self,
        prepared: &Prepared,
        patches: Vec<ConvertedPatch>,
    ) -> impl Iterator<Item = ConvertedPatch> {
        let lv = prepared.level();
        patches.into_iter().map(move |mut p| {
            for f in &mut p.cage_faces {
                let at = self.level_faces[f.0 as usize];
                *f = prepared.refiner.cage.faces[lv.face_origin(at as usize) as usize];
            }
            p.cage_faces.sort();
            p.cage_faces.dedup();
            p
        })
    }
}

/// The faces of `prepared`'s level within `rings` rings of vertex `v` as a
/// cage (`None` when they do not form a manifold mesh, as where two fans
/// of a vertex on the cut touch only there).
pub(super) fn cut_out(prepared: &Prepared, v: u32, rings: usize) -> Option<CutOut> {
    let lv: &Level = prepared.level();
    let mut level_faces: Vec<u32> = Vec::new();
    let mut taken: Vec<bool> = vec![false; lv.face_count()];
    let mut vertices: HashMap<u32, u32> = HashMap::from([(v, 0)]);
    let mut order = vec![v];
    let mut frontier = vec![v];
    for _ in 0..rings {
        let mut next = Vec::new();
        for &u in &frontier {
            for &c in lv.vertex_corners(u) {
                let f = lv.corner_face(c as usize);
                if std::mem::replace(&mut taken[f as usize], true) {
                    continue;
                }
                level_faces.push(f);
                for corner in lv.face_corners(f) {
                    let w = lv.face_vertices[corner];
                    if let std::collections::hash_map::Entry::Vacant(slot) = vertices.entry(w) {
                        slot.insert(order.len() as u32);
                        order.push(w);
                        next.push(w);
                    }
                }
            }
        }
        frontier = next;
    }
    let positions: Vec<DVec3> = order.iter().map(|&w| prepared.points[w as usize]).collect();
    let polygons: Vec<Vec<u32>> = level_faces
        .iter()
        .map(|&f| {
            lv.face_corners(f)
                .map(|c| vertices[&lv.face_vertices[c]])
                .collect()
        })
        .collect();
    let mesh = HalfEdgeMesh::from_polygons(&positions, &polygons).ok()?;
    let mut creases = Creases::default();
    for (i, &f) in level_faces.iter().enumerate() {
        if !prepared.shown[f as usize] {
            creases.holes.insert(FaceId(i as u32));
        }
        for c in lv.face_corners(f) {
            let e = lv.face_edges[c];
            let sharpness = lv.edge_sharp(e);
            if sharpness > 0.0 {
                let [a, b] = lv.edge_vertices[e as usize].map(|w| VertexId(vertices[&w]));
                let edge = mesh
                    .find_edge(a, b)
                    .expect("an edge of a face of the cut-out");
                creases.set_edge(edge, f64::from(sharpness));
            }
        }
    }
    for (&w, &at) in &vertices {
        let sharpness = lv.vertex_sharp(w);
        if sharpness > 0.0 {
            creases.set_vertex(VertexId(at), f64::from(sharpness));
        }
    }
    Some(CutOut {
        mesh,
        creases,
        level_faces,
        vertices,
    })
}

/// The patches of a star and its measured figures.
pub(super) struct StarPatches {
    /// The patches; their `cage_faces` are faces of the cut-out's mesh.
    pub patches: Vec<ConvertedPatch>,
    /// Figures of the star's approximation and of its refined rings.
    pub report: Report,
    /// The level of the finest patches (the cut-out's level 0 is `level`).
    pub deepest: u32,
}

/// Converts the star of vertex `v` of `cut` (whose faces `star` are faces
/// of its mesh), at `level` of the whole refinement: as it is when its
/// approximation meets `to`, else one step finer (exact patches for the
/// `3n` regular children) with the child star converted the same way, up
/// to [`ToNurbsOptions::max_level`].
///
/// # Errors
/// As the refinement of the cut-out.
pub(super) fn convert_star(
    cut: &CutOut,
    v: u32,
    star: &[u32],
    options: Options,
    to: &ToNurbsOptions,
    level: u32,
) -> Result<StarPatches, ToNurbsError> {
    let (mesh, creases) = (&cut.mesh, &cut.creases);
    // The star as it is, measured with the faces around it (their patches
    // are exact; the normal angle across the star's outer edges is measured
    // against them).
    let here = Prepared::new(mesh, creases, options, 0)?;
    let lv = here.level();
    let in_star = {
        let mut mask = vec![false; lv.face_count()];
        for &f in star {
            mask[f as usize] = true;
        }
        mask
    };
    let mut keep = in_star.clone();
    for &f in star {
        for c in lv.face_corners(f) {
            for &d in lv.vertex_corners(lv.face_vertices[c]) {
                keep[lv.corner_face(d as usize) as usize] = true;
            }
        }
    }
    let (now, _) = convert_prepared(mesh, creases, options, &here, &keep, to.samples, false)?;
    let star_patch = |p: usize| {
        now.placements
            .iter()
            .enumerate()
            .any(|(f, at)| in_star[f] && at.is_some_and(|at| at.patch == p))
    };
    let as_is = StarPatches {
        patches: (0..now.patches.len())
            .filter(|&p| star_patch(p))
            .map(|p| now.patches[p].clone())
            .collect(),
        report: now.report.clone(),
        deepest: level,
    };
    if now.within(to) || level >= to.max_level {
        return Ok(as_is);
    }
    // One step finer: the star's children, less the child star, are exact.
    let finer = Prepared::new(mesh, creases, options, 1)?;
    let fl = finer.level();
    let child = (lv.face_count() + lv.edge_count()) as u32 + v;
    let child_star: Vec<u32> = fl
        .vertex_corners(child)
        .iter()
        .map(|&c| fl.corner_face(c as usize))
        .collect();
    let descendant: Vec<bool> = (0..fl.face_count())
        .map(|f| in_star[fl.face_origin(f) as usize])
        .collect();
    let mut ring = descendant.clone();
    for &f in &child_star {
        ring[f as usize] = false;
    }
    let Some(next_cut) = cut_out(&finer, child, RINGS) else {
        return Ok(as_is);
    };
    let (exact, _) = convert_prepared(
        mesh,
        creases,
        options,
        &finer,
        &ring,
        to.samples,
        to.measure_exact,
    )?;
    let next_star: Vec<u32> = next_cut
        .level_faces
        .iter()
        .enumerate()
        .filter(|(_, f)| child_star.contains(f))
        .map(|(i, _)| i as u32)
        .collect();
    let inner = convert_star(
        &next_cut,
        next_cut.vertices[&child],
        &next_star,
        options,
        to,
        level + 1,
    )?;
    let mut report = exact.report.clone();
    report.merge(&inner.report);
    let mut patches: Vec<ConvertedPatch> = exact.patches;
    patches.extend(next_cut.patches_of(&finer, inner.patches));
    debug_assert!(
        patches
            .iter()
            .all(|p| p.kind == PatchKind::Exact || p.cage_faces.len() == 1)
    );
    Ok(StarPatches {
        patches,
        report,
        deepest: inner.deepest,
    })
}
