//! STL import: binary, or ASCII with any number of `solid` blocks,
//! triangles welded where their corners are equal.

use super::repairs::{FaceNumbers, why_nothing_kept};
use super::{ImportError, ImportedMesh};
use glam::DVec3;
use hedra_geom::HalfEdgeMesh;
use std::collections::HashMap;

/// A malformed STL triangle. Triangles count from 1 over the whole file,
/// lines (ASCII STL only) from 1.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StlError {
    /// An ASCII `vertex` line without three numbers.
    #[error("line {line}, triangle {triangle}: a vertex needs three numbers, found '{found}'")]
    VertexNumbers {
        /// The line of the vertex.
        line: usize,
        /// The facet the vertex belongs to.
        triangle: usize,
        /// The words after `vertex`, joined by spaces.
        found: String,
    },
    /// An ASCII vertex coordinate that is not finite as a 32-bit float
    /// (STL's precision).
    #[error("line {line}, triangle {triangle}: vertex coordinate '{value}' is not finite")]
    NonFiniteCoordinate {
        /// The line of the vertex.
        line: usize,
        /// The facet the vertex belongs to.
        triangle: usize,
        /// The coordinate as written.
        value: String,
    },
    /// An ASCII `vertex` line before any `facet`.
    #[error("line {line}: a vertex outside any facet")]
    VertexOutsideFacet {
        /// The line of the vertex.
        line: usize,
    },
    /// An ASCII `endfacet` after other than three vertices.
    #[error("line {line}, triangle {triangle}: a facet needs three vertices, found {found}")]
    FacetCorners {
        /// The line of the `endfacet`.
        line: usize,
        /// The facet.
        triangle: usize,
        /// How many vertices it has.
        found: usize,
    },
    /// A binary STL triangle with an infinite or NaN corner.
    #[error(
        "triangle {triangle} has a corner that is not finite: ({}, {}, {})",
        .corner.x,
        .corner.y,
        .corner.z
    )]
    NonFiniteCorner {
        /// The triangle.
        triangle: usize,
        /// The first corner that is not finite, as read.
        corner: DVec3,
    },
}

/// One `solid … endsolid` block of an ASCII STL: its name and triangles.
struct AsciiSolid {
    name: String,
    triangles: Vec<[DVec3; 3]>,
}

/// True when `bytes` start (after white space) with `solid` in any case:
/// `solid name`, `solid<TAB>name`, `solid` alone, `SOLID`.
fn starts_like_ascii_stl(bytes: &[u8]) -> bool {
    bytes
        .trim_ascii_start()
        .get(..5)
        .is_some_and(|w| w.eq_ignore_ascii_case(b"solid"))
}

/// Reads an ASCII STL: every `solid` block, keywords in any case (`facet`,
/// `vertex`, `endfacet`, `endsolid`; `normal`, `outer loop` and `endloop`
/// are not needed). Messages name the line and the triangle.
fn parse_ascii_stl(text: &str) -> Result<Vec<AsciiSolid>, StlError> {
    let mut solids: Vec<AsciiSolid> = Vec::new();
    let mut corners: Option<Vec<DVec3>> = None;
    let mut triangle = 0usize;
    for (number, line) in text.lines().enumerate() {
        let number = number + 1;
        let line = line.trim();
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        match keyword.to_ascii_lowercase().as_str() {
            "solid" => solids.push(AsciiSolid {
                name: line[keyword.len()..].trim().to_string(),
                triangles: Vec::new(),
            }),
            "facet" => {
                triangle += 1;
                corners = Some(Vec::with_capacity(3));
            }
            "vertex" => {
                let values: Vec<&str> = words.collect();
                let parsed: Vec<f64> = values.iter().filter_map(|w| w.parse().ok()).collect();
                if values.len() != 3 || parsed.len() != 3 {
                    return Err(StlError::VertexNumbers {
                        line: number,
                        triangle,
                        found: values.join(" "),
                    });
                }
                if let Some(k) = (0..3).find(|&k| !(parsed[k] as f32).is_finite()) {
                    return Err(StlError::NonFiniteCoordinate {
                        line: number,
                        triangle,
                        value: values[k].to_string(),
                    });
                }
                let Some(c) = corners.as_mut() else {
                    return Err(StlError::VertexOutsideFacet { line: number });
                };
                c.push(DVec3::new(parsed[0], parsed[1], parsed[2]));
            }
            "endfacet" => {
                let c = corners.take().unwrap_or_default();
                let [a, b, c] = c[..] else {
                    return Err(StlError::FacetCorners {
                        line: number,
                        triangle,
                        found: c.len(),
                    });
                };
                if solids.is_empty() {
                    solids.push(AsciiSolid {
                        name: String::new(),
                        triangles: Vec::new(),
                    });
                }
                solids
                    .last_mut()
                    .expect("pushed above")
                    .triangles
                    .push([a, b, c]);
            }
            _ => {}
        }
    }
    Ok(solids)
}

/// Triangles with equal corners welded: positions and polygons.
fn weld(triangles: &[[DVec3; 3]]) -> (Vec<DVec3>, Vec<Vec<u32>>) {
    let mut index: HashMap<[u64; 3], u32> = HashMap::new();
    let mut positions = Vec::new();
    let polygons = triangles
        .iter()
        .map(|t| {
            t.iter()
                .map(|p| {
                    let key = [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
                    *index.entry(key).or_insert_with(|| {
                        positions.push(*p);
                        (positions.len() - 1) as u32
                    })
                })
                .collect()
        })
        .collect();
    (positions, polygons)
}

/// Parses a binary or ASCII STL file. A binary file must be exactly as long
/// as its triangle count says (so a damaged header cannot ask for
/// gigabytes); an ASCII file gives one node per `solid` block, named after
/// it (`name`, the file's stem, when it has none); `path` names the file in
/// messages.
///
/// # Errors
/// [`ImportError::Read`] naming the problem, [`ImportError::Empty`] when no
/// triangle remains.
pub fn stl_from_bytes(
    bytes: &[u8],
    name: &str,
    path: &str,
) -> Result<Vec<ImportedMesh>, ImportError> {
    let read_error = |message: String| ImportError::Read {
        path: path.to_string(),
        message,
    };
    let stl_error = |error: StlError| ImportError::Stl {
        path: path.to_string(),
        error,
    };
    let binary_size = bytes
        .get(80..84)
        .map(|c| 84 + 50 * u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as u64);
    let is_binary = binary_size == Some(bytes.len() as u64);
    let is_ascii = !is_binary && starts_like_ascii_stl(bytes);
    if !is_binary && !is_ascii {
        return Err(read_error(format!(
            "not an STL file: not ASCII (no 'solid'), and {} bytes where a binary STL of its triangle count has {}",
            bytes.len(),
            binary_size.map_or("at least 84".to_string(), |n| n.to_string())
        )));
    }
    let solids = if is_ascii {
        let text = std::str::from_utf8(bytes)
            .map_err(|e| read_error(format!("an ASCII STL that is not UTF-8 text ({e})")))?;
        parse_ascii_stl(text).map_err(stl_error)?
    } else {
        vec![AsciiSolid {
            name: String::new(),
            triangles: binary_stl_triangles(bytes).map_err(stl_error)?,
        }]
    };
    let mut out = Vec::new();
    let mut dropped = Vec::new();
    let mut offset = 0;
    for solid in &solids {
        let first = offset;
        offset += solid.triangles.len();
        let (positions, polygons) = weld(&solid.triangles);
        let (mesh, report) = HalfEdgeMesh::from_polygons_repaired(&positions, &polygons)
            .map_err(|e| read_error(e.to_string()))?;
        let node_name = if solid.name.is_empty() {
            name.to_string()
        } else {
            solid.name.clone()
        };
        if mesh.face_count() == 0 {
            if !solid.triangles.is_empty() {
                dropped.push(why_nothing_kept(
                    &node_name,
                    &report,
                    &FaceNumbers::Triangles { offset: first },
                ));
            }
            continue;
        }
        out.push(
            ImportedMesh {
                face_numbers: FaceNumbers::Triangles { offset: first },
                ..ImportedMesh::mesh(node_name, mesh.compacted_if_needed(), report)
            }
            .with_input(&positions, &polygons),
        );
    }
    if out.is_empty() {
        return Err(match dropped.first() {
            Some(reason) => ImportError::NothingLeft {
                path: path.to_string(),
                reason: reason.clone(),
            },
            None => ImportError::Empty {
                path: path.to_string(),
            },
        });
    }
    Ok(out)
}

/// The triangles of a binary STL (its length already checked), refusing
/// corners that are not finite.
fn binary_stl_triangles(bytes: &[u8]) -> Result<Vec<[DVec3; 3]>, StlError> {
    let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    let mut out = Vec::with_capacity(count);
    for t in 0..count {
        let record = &bytes[84 + 50 * t..84 + 50 * (t + 1)];
        let float = |k: usize| {
            let at = 12 + 4 * k;
            f32::from_le_bytes([record[at], record[at + 1], record[at + 2], record[at + 3]]) as f64
        };
        let corner = |c: usize| DVec3::new(float(3 * c), float(3 * c + 1), float(3 * c + 2));
        let tri = [corner(0), corner(1), corner(2)];
        if let Some(p) = tri.iter().find(|p| !p.is_finite()) {
            return Err(StlError::NonFiniteCorner {
                triangle: t + 1,
                corner: *p,
            });
        }
        out.push(tri);
    }
    Ok(out)
}
