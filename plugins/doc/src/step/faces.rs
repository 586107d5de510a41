//! The faces of a STEP file beyond their surfaces: faceted shells
//! (`POLY_LOOP` faces) read as meshes, and whether a B-spline face is
//! trimmed (its bounds run off its surface's natural boundary).

use super::p21::Param;
use super::read::{At, R, Reader, at, is_bspline_curve};
use crate::import::ImportedMesh;
use glam::DVec3;
use hedra_geom::NurbsSurface;
use hedra_geom::curves::Curve;
use std::collections::HashSet;

impl Reader<'_> {
    /// The polygon of a `POLY_LOOP` face (`FACE_SURFACE` or
    /// `ADVANCED_FACE` whose only bound is one), as point instance ids in
    /// the order that faces out; `None` for another kind of face.
    pub(super) fn poly_face(&self, id: u64) -> R<Option<Vec<u64>>> {
        let i = self.get(id, id)?;
        let Some(face) = i
            .records
            .iter()
            .find(|r| r.name == "FACE_SURFACE" || r.name == "ADVANCED_FACE")
        else {
            return at(id, "a shell's face that is not a face");
        };
        let bounds = self.list(id, self.param(id, face, 1)?, "the bounds")?;
        let [bound] = bounds else {
            return Ok(None);
        };
        let b = self.reference(id, bound, "a bound")?;
        let Some(br) = self.get(id, b)?.records.first() else {
            return Ok(None);
        };
        let lp = self.reference(b, self.param(b, br, 1)?, "the loop")?;
        let Ok(poly) = self.typed(b, lp, "POLY_LOOP") else {
            return Ok(None);
        };
        let mut points: Vec<u64> = self
            .list(lp, self.param(lp, poly, 1)?, "the polygon")?
            .iter()
            .map(|p| self.reference(lp, p, "a polygon corner"))
            .collect::<R<_>>()?;
        let flipped = |p: Option<&Param>| matches!(p, Some(Param::Enum(e)) if e == "F");
        if flipped(br.params.get(2)) != flipped(face.params.get(3)) {
            points.reverse();
        }
        Ok(Some(points))
    }

    /// A `FACETED_BREP`, or a `SHELL_BASED_SURFACE_MODEL` of `POLY_LOOP`
    /// faces, as a mesh node named after it (its faces are added to
    /// `done`); `None` for any other instance.
    pub(super) fn faceted(&self, id: u64, done: &mut HashSet<u64>) -> R<Option<ImportedMesh>> {
        let i = self.get(id, id)?;
        let Some(r) = i.records.first() else {
            return Ok(None);
        };
        let shells: Vec<u64> = match r.name.as_str() {
            "FACETED_BREP" => vec![self.reference(id, self.param(id, r, 1)?, "the shell")?],
            "SHELL_BASED_SURFACE_MODEL" => self
                .list(id, self.param(id, r, 1)?, "the shells")?
                .iter()
                .map(|x| self.reference(id, x, "a shell"))
                .collect::<R<_>>()?,
            _ => return Ok(None),
        };
        let mut index: std::collections::HashMap<u64, u32> = Default::default();
        let (mut positions, mut polygons, mut faces) = (Vec::new(), Vec::new(), Vec::new());
        for shell in shells {
            let sr = self.get(id, shell)?.records.first().ok_or(At {
                id: shell,
                message: "an empty shell".into(),
            })?;
            for f in self.list(shell, self.param(shell, sr, 1)?, "the faces")? {
                let f = self.reference(shell, f, "a face")?;
                let Some(corners) = self.poly_face(f)? else {
                    continue;
                };
                let mut polygon = Vec::with_capacity(corners.len());
                for c in corners {
                    let k = match index.get(&c) {
                        Some(&k) => k,
                        None => {
                            positions.push(self.point(f, &Param::Ref(c))?);
                            index.insert(c, positions.len() as u32 - 1);
                            positions.len() as u32 - 1
                        }
                    };
                    polygon.push(k);
                }
                polygons.push(polygon);
                faces.push(f);
            }
        }
        if polygons.is_empty() {
            return Ok(None);
        }
        let (mesh, report) =
            match hedra_geom::HalfEdgeMesh::from_polygons_repaired(&positions, &polygons) {
                Ok(m) => m,
                Err(e) => return at(id, format!("its facets make no mesh: {e}")),
            };
        done.extend(faces);
        let name = Some(self.name(r))
            .filter(|n| !n.is_empty())
            .unwrap_or_else(|| format!("Mesh #{id}"));
        Ok(Some(
            ImportedMesh {
                mesh: Some(mesh),
                report,
                ..ImportedMesh::empty(name)
            }
            .with_input(&positions, &polygons),
        ))
    }

    /// True when every vertex of the face's bounds, and three points
    /// inside each edge whose curve is a B-spline, lies on one of the
    /// surface's four boundary curves (within 1e-6 of the surface's
    /// size): an untrimmed face.
    pub(super) fn untrimmed(&self, face: u64, bounds: &[Param], s: &NurbsSurface) -> bool {
        let size = crate::render::extent(s.points()).max(1e-12);
        let sides = super::brep::boundary_curves(s);
        let mut vertices = Vec::new();
        self.collect_vertices(face, bounds, &mut vertices);
        // No vertex found (bounds of a kind not read here): no evidence
        // of a trim.
        vertices.iter().all(|p| {
            sides
                .iter()
                .any(|c| super::brep::distance_to_curve(c, *p) <= 1e-6 * size)
        })
    }

    pub(super) fn collect_vertices(&self, face: u64, bounds: &[Param], out: &mut Vec<DVec3>) {
        let deref = |p: &Param| match p {
            Param::Ref(x) => self.ex.instances.get(x).map(|i| (*x, i)),
            _ => None,
        };
        let _ = face;
        for b in bounds {
            let Some((_, bound)) = deref(b) else { continue };
            let Some(lp) = bound
                .records
                .first()
                .and_then(|r| r.params.get(1))
                .and_then(deref)
            else {
                continue;
            };
            let Some(edges) = lp.1.records.first().and_then(|r| r.params.get(1)) else {
                continue;
            };
            // A VERTEX_LOOP: one vertex (a closed surface's pole).
            if let Some((v, vertex)) = deref(edges)
                && let Some(Param::Ref(p)) = vertex.records.first().and_then(|r| r.params.get(1))
                && let Ok(p) = self.point(v, &Param::Ref(*p))
            {
                out.push(p);
                continue;
            }
            let Param::List(edges) = edges else { continue };
            for oe in edges {
                let Some((_, oe)) = deref(oe) else { continue };
                let Some(edge) = oe
                    .records
                    .first()
                    .and_then(|r| r.params.get(3))
                    .and_then(deref)
                else {
                    continue;
                };
                // Points inside the edge, where its curve is a B-spline
                // (itself, or the 3D curve of a SURFACE_CURVE or
                // SEAM_CURVE): a circle can touch a square's side at its
                // one vertex.
                let mut curve = edge
                    .1
                    .records
                    .first()
                    .and_then(|r| r.params.get(3))
                    .and_then(deref);
                if let Some((_, c)) = curve
                    && c.records.first().is_some_and(|r| {
                        r.name.ends_with("SURFACE_CURVE") || r.name == "SEAM_CURVE"
                    })
                {
                    curve = c
                        .records
                        .first()
                        .and_then(|r| r.params.get(1))
                        .and_then(deref);
                }
                if let Some((cid, c)) = curve
                    && is_bspline_curve(c)
                    && let Ok((_, c)) = self.curve(cid)
                {
                    let (a, b) = c.domain();
                    out.extend([0.25, 0.5, 0.75].map(|f| c.point(a + f * (b - a))));
                }
                for k in [1, 2] {
                    let Some(vertex) = edge
                        .1
                        .records
                        .first()
                        .and_then(|r| r.params.get(k))
                        .and_then(deref)
                    else {
                        continue;
                    };
                    if let Some(Param::Ref(p)) =
                        vertex.1.records.first().and_then(|r| r.params.get(1))
                        && let Ok(p) = self.point(vertex.0, &Param::Ref(*p))
                    {
                        out.push(p);
                    }
                }
            }
        }
    }
}
