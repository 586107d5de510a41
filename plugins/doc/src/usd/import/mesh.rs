//! Reading a USD `Mesh` prim: the cage, its subdivision modifier, creases
//! (per-edge or per-crease, Hedra's tapers), corners, holes, UVs and
//! corner normals.

use super::values::*;
use super::{Geometry, R, Skipped, attr_error, prim_error};
use crate::scene::{
    CornerAttributes, MeshContent, NodeContent, Shading, SubdivisionModifier, SurfaceShape,
};
use glam::{DVec2, DVec3};
use hedra_geom::HalfEdgeMesh;
use hedra_geom::subdivision::{
    BoundaryInterpolation, CreaseMethod, CreaseTaper, Creases, Options, Scheme,
};
use openusd::usd;
use std::sync::Arc;

fn scheme_of(prim: &usd::Prim) -> R<Option<Scheme>> {
    let s = get_token(prim, "subdivisionScheme")?.unwrap_or_else(|| "catmullClark".into());
    Ok(match s.as_str() {
        "catmullClark" => Some(Scheme::CatmullClark),
        "loop" => Some(Scheme::Loop),
        "bilinear" => Some(Scheme::Linear),
        "none" => None,
        other => {
            return Err(attr_error(
                prim,
                "subdivisionScheme",
                format!("'{other}' is not a USD scheme"),
            ));
        }
    })
}

pub(super) fn mesh(prim: &usd::Prim, skipped: &mut Skipped) -> R<Geometry> {
    let points = exact_points(prim)?;
    let counts = get_ints(prim, "faceVertexCounts")?.unwrap_or_default();
    let indices = get_ints(prim, "faceVertexIndices")?.unwrap_or_default();
    let mut polygons: Vec<Vec<u32>> = Vec::with_capacity(counts.len());
    let mut at = 0usize;
    for (k, &n) in counts.iter().enumerate() {
        if n < 0 {
            return Err(attr_error(
                prim,
                "faceVertexCounts",
                format!("face {k} has {n} corners"),
            ));
        }
        let end = at.saturating_add(n as usize);
        let corners = indices.get(at..end).ok_or_else(|| {
            attr_error(
                prim,
                "faceVertexCounts",
                format!(
                    "the counts add up past the {} faceVertexIndices",
                    indices.len()
                ),
            )
        })?;
        let mut poly = Vec::with_capacity(corners.len());
        for &i in corners {
            if i < 0 || i as usize >= points.len() {
                return Err(attr_error(
                    prim,
                    "faceVertexIndices",
                    format!(
                        "index {i} in face {k} is not one of the {} points",
                        points.len()
                    ),
                ));
            }
            poly.push(i as u32);
        }
        polygons.push(poly);
        at = end;
    }
    if get_token(prim, "orientation")?.as_deref() == Some("leftHanded") {
        for p in &mut polygons {
            p.reverse();
        }
    }
    let (mesh, report) = HalfEdgeMesh::from_polygons_repaired(&points, &polygons)
        .map_err(|e| prim_error(prim, e.to_string()))?;
    let input = (!report.is_clean()).then(|| crate::kept::KeptMesh {
        positions: points.clone(),
        faces: polygons.clone(),
    });
    let verts: Vec<_> = mesh.vertices().collect();
    let vertex = |i: i64| usize::try_from(i).ok().and_then(|i| verts.get(i).copied());
    let mut face_of = vec![None; polygons.len()];
    for (k, f) in mesh.faces().enumerate() {
        if let Some(&origin) = report.face_origin.get(k)
            && let Some(slot) = face_of.get_mut(origin)
        {
            *slot = Some(f);
        }
    }
    // Subdivision.
    let scheme = scheme_of(prim)?;
    let subdivision = match scheme {
        Some(scheme) => {
            let boundary = match get_token(prim, "interpolateBoundary")?.as_deref() {
                None | Some("edgeAndCorner") => BoundaryInterpolation::EdgesAndCorners,
                Some("edgeOnly") => BoundaryInterpolation::EdgesOnly,
                Some("none") => BoundaryInterpolation::None,
                Some(other) => {
                    return Err(attr_error(
                        prim,
                        "interpolateBoundary",
                        format!("'{other}' is not a USD rule"),
                    ));
                }
            };
            let smooth_triangles =
                get_token(prim, "triangleSubdivisionRule")?.as_deref() == Some("smooth");
            let crease_method = match get_token(prim, "hedra:creaseMethod")?.as_deref() {
                Some("chaikin") => CreaseMethod::Chaikin,
                _ => CreaseMethod::Uniform,
            };
            let level = |name: &str, default: u32| -> R<u32> {
                Ok(match get_value(prim, name)?.as_ref().and_then(scalar) {
                    Some(l) if (0.0..=hedra_geom::subdivision::MAX_LEVEL as f64).contains(&l) => {
                        l as u32
                    }
                    Some(_) => return Err(attr_error(prim, name, "is not a level Hedra allows")),
                    None => default,
                })
            };
            Some(SubdivisionModifier {
                options: Options {
                    scheme,
                    boundary,
                    crease_method,
                    smooth_triangles,
                },
                viewport_level: level("hedra:viewportLevel", 1)?,
                export_level: level("hedra:exportLevel", 2)?,
                show_cage: get_bool(prim, "hedra:showCage")?.unwrap_or(true),
                stack_position: None,
            })
        }
        None => None,
    };
    // Creases: per-edge or per-crease sharpness.
    let mut creases = Creases::default();
    let c_idx = get_ints(prim, "creaseIndices")?.unwrap_or_default();
    let c_len = get_ints(prim, "creaseLengths")?.unwrap_or_default();
    let c_sharp = exact_floats(prim, "creaseSharpnesses")?;
    let total: i64 = c_len.iter().map(|&l| l.max(0)).sum();
    if total != c_idx.len() as i64 || c_len.iter().any(|&l| l < 2) {
        return Err(attr_error(
            prim,
            "creaseLengths",
            format!(
                "lengths (each at least 2) must add up to the {} creaseIndices",
                c_idx.len()
            ),
        ));
    }
    let per_edge = c_sharp.len() as i64 == total - c_len.len() as i64;
    if !c_len.is_empty() && !per_edge && c_sharp.len() != c_len.len() {
        return Err(attr_error(
            prim,
            "creaseSharpnesses",
            format!(
                "{} values: neither one per crease ({}) nor one per edge ({})",
                c_sharp.len(),
                c_len.len(),
                total - c_len.len() as i64
            ),
        ));
    }
    let taper_of = get_ints(prim, "hedra:taperOf")?;
    let fractions = get_floats(prim, "hedra:taperFractions")?.unwrap_or_default();
    let starts = get_floats(prim, "hedra:taperStarts")?.unwrap_or_default();
    let ends = get_floats(prim, "hedra:taperEnds")?.unwrap_or_default();
    let taper_of = taper_of.filter(|t| {
        t.len() == c_len.len()
            && per_edge
            && starts.len() == ends.len()
            && t.iter().all(|&k| k < starts.len() as i64)
    });
    let mut tapers: Vec<CreaseTaper> = starts
        .iter()
        .zip(&ends)
        .map(|(&start, &end)| CreaseTaper {
            edges: Vec::new(),
            start,
            end,
        })
        .collect();
    let (mut at, mut edge_no, mut fraction_no) = (0usize, 0usize, 0usize);
    let mut missing = 0usize;
    for (chain, &len) in c_len.iter().enumerate() {
        let vs = &c_idx[at..at + len as usize];
        at += len as usize;
        for (k, pair) in vs.windows(2).enumerate() {
            let s = if per_edge {
                c_sharp[edge_no + k]
            } else {
                c_sharp[chain]
            };
            let e = match (vertex(pair[0]), vertex(pair[1])) {
                (Some(a), Some(b)) => mesh.find_edge(a, b),
                _ => None,
            };
            let Some(e) = e else {
                missing += 1;
                continue;
            };
            if !s.is_finite() || s < 0.0 {
                return Err(attr_error(
                    prim,
                    "creaseSharpnesses",
                    format!("{s} is not a sharpness"),
                ));
            }
            match taper_of.as_ref().map(|t| t[chain]) {
                Some(t) if t >= 0 => {
                    let f = fractions.get(fraction_no + k).copied().unwrap_or(0.5);
                    tapers[t as usize].edges.push((e, f));
                }
                _ => creases.set_edge(e, s),
            }
        }
        if taper_of.as_ref().is_some_and(|t| t[chain] >= 0) {
            fraction_no += len as usize - 1;
        }
        edge_no += len as usize - 1;
    }
    creases
        .tapers
        .extend(tapers.into_iter().filter(|t| !t.edges.is_empty()));
    if missing > 0 {
        skipped.add(format!(
            "crease edges that are not edges of the mesh ({})",
            prim.path()
        ));
    }
    let corner_idx = get_ints(prim, "cornerIndices")?.unwrap_or_default();
    let corner_sharp = exact_floats(prim, "cornerSharpnesses")?;
    if corner_idx.len() != corner_sharp.len() {
        return Err(attr_error(
            prim,
            "cornerSharpnesses",
            format!(
                "{} values for {} cornerIndices",
                corner_sharp.len(),
                corner_idx.len()
            ),
        ));
    }
    for (&i, &s) in corner_idx.iter().zip(&corner_sharp) {
        let v = vertex(i).ok_or_else(|| {
            attr_error(
                prim,
                "cornerIndices",
                format!("{i} is not a point of the mesh"),
            )
        })?;
        if !s.is_finite() || s < 0.0 {
            return Err(attr_error(
                prim,
                "cornerSharpnesses",
                format!("{s} is not a sharpness"),
            ));
        }
        creases.set_vertex(v, s);
    }
    for i in get_ints(prim, "holeIndices")?.unwrap_or_default() {
        let f = usize::try_from(i)
            .ok()
            .and_then(|i| face_of.get(i).copied().flatten());
        match f {
            Some(f) => creases.set_hole(f, true),
            None if usize::try_from(i).is_ok_and(|i| i < polygons.len()) => {}
            None => {
                return Err(attr_error(
                    prim,
                    "holeIndices",
                    format!("{i} is not one of the {} faces", polygons.len()),
                ));
            }
        }
    }
    // UVs and normals of the corners.
    let arities: Vec<usize> = polygons.iter().map(Vec::len).collect();
    let corner_count = indices.len();
    let uvs = corner_uvs(prim, &polygons, points.len(), corner_count, skipped)?;
    let (normals, interpolation) = if scheme.is_none() {
        corner_normals(prim, &polygons, points.len(), corner_count)?
    } else {
        (Vec::new(), None)
    };
    let corners: CornerAttributes =
        crate::import::corner_attributes(&mesh, &report, &arities, &uvs, &normals);
    let shading = match get_token(prim, "hedra:shading")?.as_deref() {
        Some("flat") => Shading::Flat,
        Some("smooth") => Shading::Smooth,
        _ if matches!(interpolation.as_deref(), Some("vertex" | "varying")) => Shading::Smooth,
        _ if scheme.is_some() => Shading::Smooth,
        _ => Shading::Flat,
    };
    // A corner normal that is the flat or smooth one Hedra computes is not
    // kept (Hedra writes them for other applications).
    let corners = if matches!(interpolation.as_deref(), Some("faceVarying")) {
        corners
    } else {
        CornerAttributes {
            normals: Arc::default(),
            ..corners
        }
    };
    if let Some(json) = get_string(prim, "hedra:bezierTriangle")?
        && let Ok(t) = ron::from_str::<hedra_geom::surfaces::BezierTriangle>(&json)
    {
        return Ok(Geometry::One(Box::new((
            NodeContent::Surface(Arc::new(SurfaceShape::Triangle(t))),
            Default::default(),
            None,
        ))));
    }
    let content = MeshContent {
        shading,
        creases,
        subdivision,
        corners,
        ..MeshContent::new(Arc::new(mesh))
    };
    Ok(Geometry::One(Box::new((
        NodeContent::Mesh(content),
        report,
        input,
    ))))
}

/// Face-varying (or vertex) `primvars:st`, one entry per corner.
fn corner_uvs(
    prim: &usd::Prim,
    polygons: &[Vec<u32>],
    point_count: usize,
    corner_count: usize,
    skipped: &mut Skipped,
) -> R<Vec<Option<DVec2>>> {
    let name = "primvars:st";
    let Some(value) = get_value(prim, name)? else {
        return Ok(Vec::new());
    };
    let values =
        vec2s(&value).ok_or_else(|| attr_error(prim, name, "is not an array of 2-vectors"))?;
    let per_corner = expand(prim, name, &values, point_count, corner_count, polygons)?;
    if per_corner.is_none() {
        skipped.add("UVs of an interpolation other than faceVarying or vertex");
    }
    Ok(per_corner
        .unwrap_or_default()
        .into_iter()
        .map(Some)
        .collect())
}

fn corner_normals(
    prim: &usd::Prim,
    polygons: &[Vec<u32>],
    point_count: usize,
    corner_count: usize,
) -> R<(Vec<Option<DVec3>>, Option<String>)> {
    let name = "normals";
    let Some(value) = get_value(prim, name)? else {
        return Ok((Vec::new(), None));
    };
    let values =
        vec3s(&value).ok_or_else(|| attr_error(prim, name, "is not an array of 3-vectors"))?;
    let interpolation = interpolation(prim, name);
    let per_corner = if interpolation.as_deref() == Some("faceVarying") {
        expand(prim, name, &values, point_count, corner_count, polygons)?.unwrap_or_default()
    } else {
        Vec::new()
    };
    Ok((per_corner.into_iter().map(Some).collect(), interpolation))
}

/// A primvar's values for each face corner (through its `:indices` when
/// it has them); `None` for an interpolation other than faceVarying or
/// vertex.
fn expand<T: Copy>(
    prim: &usd::Prim,
    name: &str,
    values: &[T],
    point_count: usize,
    corner_count: usize,
    polygons: &[Vec<u32>],
) -> R<Option<Vec<T>>> {
    let indices_name = format!("{name}:indices");
    let indices = get_ints(prim, &indices_name)?;
    let element = |i: usize| -> R<T> {
        let j = match &indices {
            Some(ix) => *ix
                .get(i)
                .ok_or_else(|| attr_error(prim, &indices_name, format!("has no entry {i}")))?,
            None => i as i64,
        };
        usize::try_from(j)
            .ok()
            .and_then(|j| values.get(j).copied())
            .ok_or_else(|| attr_error(prim, name, format!("has no element {j}")))
    };
    match interpolation(prim, name).as_deref() {
        Some("faceVarying") => {
            let n = indices.as_ref().map_or(values.len(), Vec::len);
            if n != corner_count {
                return Err(attr_error(
                    prim,
                    name,
                    format!("{n} face-varying values for {corner_count} face corners"),
                ));
            }
            (0..corner_count)
                .map(element)
                .collect::<R<Vec<T>>>()
                .map(Some)
        }
        Some("vertex" | "varying") => {
            let n = indices.as_ref().map_or(values.len(), Vec::len);
            if n != point_count {
                return Err(attr_error(
                    prim,
                    name,
                    format!("{n} vertex values for {point_count} points"),
                ));
            }
            polygons
                .iter()
                .flatten()
                .map(|&v| element(v as usize))
                .collect::<R<Vec<T>>>()
                .map(Some)
        }
        _ => Ok(None),
    }
}
