//! Primitive shapes as half-edge polygon meshes: quads wherever the shape
//! allows, n-gon caps, triangle fans only at poles and apexes. Y is up; every
//! face is counter-clockwise seen from outside.

use crate::mesh::HalfEdgeMesh;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::f64::consts::{PI, TAU};

/// A primitive and its parameters, as stored in commands and files so the
/// user can adjust them after creation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Primitive {
    /// A square in the XZ plane facing +Y.
    Plane {
        /// Side length.
        size: f64,
    },
    /// An axis-aligned cube centred at the origin.
    Cube {
        /// Edge length.
        size: f64,
    },
    /// A plane of `x_segments × z_segments` quads.
    Grid {
        /// Quads along X.
        x_segments: u32,
        /// Quads along Z.
        z_segments: u32,
        /// Side length of the whole (square) grid.
        size: f64,
    },
    /// A sphere of latitude rings and longitude segments, poles on the Y
    /// axis (triangle fans there, quads elsewhere).
    UvSphere {
        /// Vertices around each ring (longitude).
        segments: u32,
        /// Bands from pole to pole (latitude); `rings − 1` vertex rings.
        rings: u32,
        /// Sphere radius.
        radius: f64,
    },
    /// An icosahedron split `subdivisions` times (0 is the icosahedron).
    IcoSphere {
        /// Times each triangle is split into four.
        subdivisions: u32,
        /// Radius every vertex is projected to.
        radius: f64,
    },
    /// Y-aligned, n-gon caps.
    Cylinder {
        /// Side quads around the axis.
        segments: u32,
        /// Cap radius.
        radius: f64,
        /// Height along Y, centred at the origin.
        depth: f64,
    },
    /// Apex up, n-gon base.
    Cone {
        /// Side triangles around the axis.
        segments: u32,
        /// Base radius.
        radius: f64,
        /// Height along Y from base to apex, centred at the origin.
        depth: f64,
    },
    /// A ring around the Y axis, all quads.
    Torus {
        /// Segments around the Y axis.
        major_segments: u32,
        /// Segments around the tube.
        minor_segments: u32,
        /// Distance from the Y axis to the tube's centre line.
        major_radius: f64,
        /// Radius of the tube.
        minor_radius: f64,
    },
}

/// A primitive parameter outside its allowed range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{primitive}: {parameter} = {value} is out of range ({allowed})")]
pub struct PrimitiveError {
    /// The primitive's kind, as in commands (`"cube"`, `"uv_sphere"`, ...).
    pub primitive: &'static str,
    /// The parameter's name.
    pub parameter: &'static str,
    /// The refused value, formatted (`"0"`, `"NaN"`): parameters are floats
    /// or integers.
    pub value: String,
    /// The allowed range, as words.
    pub allowed: &'static str,
}

/// Segment counts above this are refused: they would build meshes of
/// hundreds of millions of elements from one typo.
pub const MAX_SEGMENTS: u32 = 4096;
/// Icosphere subdivisions above this are refused (20·4^9 ≈ 5 million faces).
pub const MAX_ICO_SUBDIVISIONS: u32 = 9;
/// Lengths (sizes, radii, depths) must be above zero and below this.
pub const MAX_LENGTH: f64 = 1e9;

/// The counts a primitive parameter allows, by its name in commands and
/// files, with the range as the error message says it: the one definition
/// that [`Primitive::check`] and the editors in the panels share.
pub fn count_range(parameter: &str) -> (std::ops::RangeInclusive<u32>, &'static str) {
    match parameter {
        "x_segments" | "z_segments" => (1..=MAX_SEGMENTS, "1 to 4096"),
        "segments" | "major_segments" | "minor_segments" => (3..=MAX_SEGMENTS, "3 to 4096"),
        "rings" => (2..=MAX_SEGMENTS, "2 to 4096"),
        "subdivisions" => (0..=MAX_ICO_SUBDIVISIONS, "0 to 9"),
        _ => (0..=u32::MAX, "any count"),
    }
}

impl Primitive {
    /// Blender-like defaults for each kind, by name (`"cube"`, `"uv_sphere"`, …).
    pub fn default_of(kind: &str) -> Option<Primitive> {
        Some(match kind {
            "plane" => Primitive::Plane { size: 2.0 },
            "cube" => Primitive::Cube { size: 2.0 },
            "grid" => Primitive::Grid {
                x_segments: 10,
                z_segments: 10,
                size: 2.0,
            },
            "uv_sphere" => Primitive::UvSphere {
                segments: 32,
                rings: 16,
                radius: 1.0,
            },
            "ico_sphere" => Primitive::IcoSphere {
                subdivisions: 2,
                radius: 1.0,
            },
            "cylinder" => Primitive::Cylinder {
                segments: 32,
                radius: 1.0,
                depth: 2.0,
            },
            "cone" => Primitive::Cone {
                segments: 32,
                radius: 1.0,
                depth: 2.0,
            },
            "torus" => Primitive::Torus {
                major_segments: 48,
                minor_segments: 12,
                major_radius: 1.0,
                minor_radius: 0.25,
            },
            _ => return None,
        })
    }

    /// Every kind name accepted by [`default_of`](Self::default_of).
    pub const KINDS: [&'static str; 8] = [
        "plane",
        "cube",
        "grid",
        "uv_sphere",
        "ico_sphere",
        "cylinder",
        "cone",
        "torus",
    ];

    /// The kind name (`"cube"`, …).
    pub fn kind(&self) -> &'static str {
        match self {
            Primitive::Plane { .. } => "plane",
            Primitive::Cube { .. } => "cube",
            Primitive::Grid { .. } => "grid",
            Primitive::UvSphere { .. } => "uv_sphere",
            Primitive::IcoSphere { .. } => "ico_sphere",
            Primitive::Cylinder { .. } => "cylinder",
            Primitive::Cone { .. } => "cone",
            Primitive::Torus { .. } => "torus",
        }
    }

    /// A display name for new nodes ("Cube", "UV Sphere", …).
    pub fn display_name(&self) -> &'static str {
        match self {
            Primitive::Plane { .. } => "Plane",
            Primitive::Cube { .. } => "Cube",
            Primitive::Grid { .. } => "Grid",
            Primitive::UvSphere { .. } => "Sphere",
            Primitive::IcoSphere { .. } => "Icosphere",
            Primitive::Cylinder { .. } => "Cylinder",
            Primitive::Cone { .. } => "Cone",
            Primitive::Torus { .. } => "Torus",
        }
    }

    /// Checks the parameters.
    ///
    /// # Errors
    /// [`PrimitiveError`] naming the first parameter out of range.
    pub fn check(&self) -> Result<(), PrimitiveError> {
        let name = self.kind();
        let length = |parameter, value: f64| {
            if value.is_finite() && value > 0.0 && value < MAX_LENGTH {
                Ok(())
            } else {
                Err(PrimitiveError {
                    primitive: name,
                    parameter,
                    value: value.to_string(),
                    allowed: "a finite length > 0",
                })
            }
        };
        let count = |parameter: &'static str, value: u32| {
            let (range, allowed) = count_range(parameter);
            if range.contains(&value) {
                Ok(())
            } else {
                Err(PrimitiveError {
                    primitive: name,
                    parameter,
                    value: value.to_string(),
                    allowed,
                })
            }
        };
        match *self {
            Primitive::Plane { size } | Primitive::Cube { size } => length("size", size),
            Primitive::Grid {
                x_segments,
                z_segments,
                size,
            } => {
                count("x_segments", x_segments)?;
                count("z_segments", z_segments)?;
                length("size", size)
            }
            Primitive::UvSphere {
                segments,
                rings,
                radius,
            } => {
                count("segments", segments)?;
                count("rings", rings)?;
                length("radius", radius)
            }
            Primitive::IcoSphere {
                subdivisions,
                radius,
            } => {
                count("subdivisions", subdivisions)?;
                length("radius", radius)
            }
            Primitive::Cylinder {
                segments,
                radius,
                depth,
            }
            | Primitive::Cone {
                segments,
                radius,
                depth,
            } => {
                count("segments", segments)?;
                length("radius", radius)?;
                length("depth", depth)
            }
            Primitive::Torus {
                major_segments,
                minor_segments,
                major_radius,
                minor_radius,
            } => {
                count("major_segments", major_segments)?;
                count("minor_segments", minor_segments)?;
                length("major_radius", major_radius)?;
                length("minor_radius", minor_radius)?;
                if minor_radius >= major_radius {
                    return Err(PrimitiveError {
                        primitive: name,
                        parameter: "minor_radius",
                        value: minor_radius.to_string(),
                        allowed: "less than major_radius",
                    });
                }
                Ok(())
            }
        }
    }

    /// Builds the mesh.
    ///
    /// # Errors
    /// [`PrimitiveError`] when a parameter is out of range.
    pub fn build(&self) -> Result<HalfEdgeMesh, PrimitiveError> {
        self.check()?;
        let (positions, polygons) = match *self {
            Primitive::Plane { size } => grid(1, 1, size),
            Primitive::Cube { size } => cube(size),
            Primitive::Grid {
                x_segments,
                z_segments,
                size,
            } => grid(x_segments, z_segments, size),
            Primitive::UvSphere {
                segments,
                rings,
                radius,
            } => uv_sphere(segments, rings, radius),
            Primitive::IcoSphere {
                subdivisions,
                radius,
            } => ico_sphere(subdivisions, radius),
            Primitive::Cylinder {
                segments,
                radius,
                depth,
            } => lathe(segments, radius, depth, false),
            Primitive::Cone {
                segments,
                radius,
                depth,
            } => lathe(segments, radius, depth, true),
            Primitive::Torus {
                major_segments,
                minor_segments,
                major_radius,
                minor_radius,
            } => torus(major_segments, minor_segments, major_radius, minor_radius),
        };
        Ok(HalfEdgeMesh::from_polygons(&positions, &polygons)
            .expect("primitive polygons are manifold"))
    }
}

type Polygons = (Vec<DVec3>, Vec<Vec<u32>>);

fn cube(size: f64) -> Polygons {
    let h = size / 2.0;
    // Vertex i has x = bit 0, y = bit 1, z = bit 2.
    let positions = (0..8)
        .map(|i| {
            DVec3::new(
                if i & 1 == 0 { -h } else { h },
                if i & 2 == 0 { -h } else { h },
                if i & 4 == 0 { -h } else { h },
            )
        })
        .collect();
    let faces = vec![
        vec![0, 4, 6, 2], // -X
        vec![1, 3, 7, 5], // +X
        vec![0, 1, 5, 4], // -Y
        vec![2, 6, 7, 3], // +Y
        vec![0, 2, 3, 1], // -Z
        vec![4, 5, 7, 6], // +Z
    ];
    (positions, faces)
}

fn grid(nx: u32, nz: u32, size: f64) -> Polygons {
    let mut positions = Vec::with_capacity(((nx + 1) * (nz + 1)) as usize);
    for j in 0..=nz {
        for i in 0..=nx {
            positions.push(DVec3::new(
                size * (i as f64 / nx as f64 - 0.5),
                0.0,
                size * (j as f64 / nz as f64 - 0.5),
            ));
        }
    }
    let id = |i: u32, j: u32| j * (nx + 1) + i;
    let mut faces = Vec::with_capacity((nx * nz) as usize);
    for j in 0..nz {
        for i in 0..nx {
            faces.push(vec![id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)]);
        }
    }
    (positions, faces)
}

/// Point on a Y-axis circle: angle 0 on +X, growing towards +Z.
fn ring_point(radius: f64, angle: f64, y: f64) -> DVec3 {
    DVec3::new(radius * angle.cos(), y, radius * angle.sin())
}

fn uv_sphere(segments: u32, rings: u32, radius: f64) -> Polygons {
    let n = segments;
    let mut positions = vec![DVec3::new(0.0, radius, 0.0)];
    for k in 1..rings {
        let theta = PI * k as f64 / rings as f64;
        for s in 0..n {
            positions.push(ring_point(
                radius * theta.sin(),
                TAU * s as f64 / n as f64,
                radius * theta.cos(),
            ));
        }
    }
    positions.push(DVec3::new(0.0, -radius, 0.0));
    let bottom = positions.len() as u32 - 1;
    let ring = |k: u32, s: u32| 1 + (k - 1) * n + s % n;
    let mut faces = Vec::new();
    for s in 0..n {
        faces.push(vec![0, ring(1, s + 1), ring(1, s)]);
    }
    for k in 1..rings - 1 {
        for s in 0..n {
            faces.push(vec![
                ring(k, s),
                ring(k, s + 1),
                ring(k + 1, s + 1),
                ring(k + 1, s),
            ]);
        }
    }
    for s in 0..n {
        faces.push(vec![ring(rings - 1, s), ring(rings - 1, s + 1), bottom]);
    }
    (positions, faces)
}

/// Cylinder (or cone when `apex`): side quads (triangles to the apex), n-gon caps.
fn lathe(segments: u32, radius: f64, depth: f64, apex: bool) -> Polygons {
    let n = segments;
    let h = depth / 2.0;
    let mut positions: Vec<DVec3> = (0..n)
        .map(|s| ring_point(radius, TAU * s as f64 / n as f64, -h))
        .collect();
    let lower = |s: u32| s % n;
    let mut faces = vec![(0..n).collect::<Vec<u32>>()];
    if apex {
        positions.push(DVec3::new(0.0, h, 0.0));
        for s in 0..n {
            faces.push(vec![n, lower(s + 1), lower(s)]);
        }
    } else {
        positions.extend((0..n).map(|s| ring_point(radius, TAU * s as f64 / n as f64, h)));
        let upper = |s: u32| n + s % n;
        for s in 0..n {
            faces.push(vec![upper(s), upper(s + 1), lower(s + 1), lower(s)]);
        }
        faces.push((0..n).rev().map(upper).collect());
    }
    (positions, faces)
}

fn torus(major: u32, minor: u32, major_radius: f64, minor_radius: f64) -> Polygons {
    let mut positions = Vec::with_capacity((major * minor) as usize);
    for i in 0..major {
        let u = TAU * i as f64 / major as f64;
        for j in 0..minor {
            let v = TAU * j as f64 / minor as f64;
            let r = major_radius + minor_radius * v.cos();
            positions.push(ring_point(r, u, minor_radius * v.sin()));
        }
    }
    let id = |i: u32, j: u32| (i % major) * minor + j % minor;
    let mut faces = Vec::with_capacity((major * minor) as usize);
    for i in 0..major {
        for j in 0..minor {
            faces.push(vec![id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)]);
        }
    }
    (positions, faces)
}

fn ico_sphere(subdivisions: u32, radius: f64) -> Polygons {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut positions: Vec<DVec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z).normalize() * radius)
    .collect();
    let mut faces: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut midpoint: HashMap<(u32, u32), u32> = HashMap::new();
        let mut mid = |a: u32, b: u32, positions: &mut Vec<DVec3>| -> u32 {
            *midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let p = (positions[a as usize] + positions[b as usize]).normalize() * radius;
                positions.push(p);
                positions.len() as u32 - 1
            })
        };
        let mut next = Vec::with_capacity(faces.len() * 4);
        for [a, b, c] in faces {
            let ab = mid(a, b, &mut positions);
            let bc = mid(b, c, &mut positions);
            let ca = mid(c, a, &mut positions);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = next;
    }
    (positions, faces.into_iter().map(|f| f.to_vec()).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `check` and the panels' editors take their ranges from `count_range`:
    /// each end is allowed, one beyond is refused with the range's words.
    #[test]
    fn counts_are_checked_against_count_range() {
        let grid = |x| Primitive::Grid {
            x_segments: x,
            z_segments: 4,
            size: 1.0,
        };
        let ico = |s| Primitive::IcoSphere {
            subdivisions: s,
            radius: 1.0,
        };
        let (range, words) = count_range("x_segments");
        assert!(grid(*range.start()).check().is_ok());
        assert!(grid(*range.end()).check().is_ok());
        let e = grid(range.end() + 1).check().unwrap_err();
        assert_eq!((e.parameter, e.allowed), ("x_segments", words));
        assert!(grid(range.start() - 1).check().is_err());
        let (range, words) = count_range("subdivisions");
        assert!(ico(*range.end()).check().is_ok());
        assert_eq!(ico(range.end() + 1).check().unwrap_err().allowed, words);
        let huge = Primitive::Cube { size: MAX_LENGTH };
        assert_eq!(huge.check().unwrap_err().parameter, "size");
    }
}
