//! What an import repaired, in words: the faces dropped or split off
//! and why, named by their numbers in the file.

use super::ImportedMesh;
use hedra_geom::RepairReport;

/// How an importer's input face numbers are shown to the user: as the
/// file counts them.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum FaceNumbers {
    /// "face k" counting from 1 within the node (glTF triangles).
    #[default]
    InNode,
    /// "line n": the OBJ line of each input polygon.
    Lines(Vec<u32>),
    /// "triangle n": STL triangles counted over the whole file, this node's
    /// first being `offset + 1`; a glTF node's triangles (offset 0).
    Triangles {
        /// How many triangles of the file come before this node's.
        offset: usize,
    },
}

impl FaceNumbers {
    pub(crate) fn name(&self, face: usize) -> String {
        match self {
            FaceNumbers::InNode => format!("face {}", face + 1),
            FaceNumbers::Lines(lines) => match lines.get(face) {
                Some(line) => format!("line {line}"),
                None => format!("face {}", face + 1),
            },
            FaceNumbers::Triangles { offset } => format!("triangle {}", offset + face + 1),
        }
    }
}

/// Why a face was dropped, in words a user can act on, naming other faces
/// as the file numbers them.
fn dropped_reason(
    why: &hedra_geom::BuildError,
    numbers: &FaceNumbers,
    face: usize,
) -> (&'static str, String) {
    use hedra_geom::BuildError as E;
    let others = |faces: &[usize]| {
        faces
            .iter()
            .filter(|&&f| f != face)
            .map(|&f| numbers.name(f))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match why {
        E::TooFewSides { sides, .. } => (
            "fewer than 3 corners",
            format!("has {sides} corner(s); a face needs 3"),
        ),
        E::RepeatedVertex { .. } => (
            "a corner used twice",
            "uses the same corner point twice".into(),
        ),
        E::NonManifoldEdge { faces, .. } => (
            "a third face on an edge",
            format!(
                "would be a third face on an edge already shared by {}",
                others(faces)
            ),
        ),
        E::InconsistentOrientation { faces, .. } => (
            "winding against a neighbour",
            format!(
                "runs an edge the same way as {}: its winding disagrees",
                others(faces)
            ),
        ),
        E::NonFinitePosition { .. } => (
            "a corner that is not finite",
            "has a corner that is not a finite number".into(),
        ),
        E::IndexOutOfRange { .. } => (
            "a corner the file lacks",
            "refers to a vertex the file does not have".into(),
        ),
        E::NonManifoldVertex { .. } | E::TooLarge { .. } => ("other", why.to_string()),
    }
}

/// Why an object kept no face, in the words of the import summary: how
/// many were dropped and the first one's reason, numbered as the file does.
pub(super) fn why_nothing_kept(name: &str, report: &RepairReport, numbers: &FaceNumbers) -> String {
    match report.dropped_faces.first() {
        Some((face, why)) => {
            let (_, text) = dropped_reason(why, numbers, *face);
            let whose = if name.is_empty() {
                String::new()
            } else {
                format!("{name}: ")
            };
            format!(
                "{whose}all {} face(s) dropped; {} {text}",
                report.dropped_faces.len(),
                numbers.name(*face)
            )
        }
        None => format!("{name}: {report}"),
    }
}

/// What an import repaired or left out, for the user: an empty list when
/// nothing was; else a one-line summary (counts by kind) followed by the
/// details, one per dropped face or split vertex with the file's own
/// numbers (OBJ lines, STL triangles), at most [`MAX_DETAILS`] of them.
pub fn describe_repairs(meshes: &[ImportedMesh]) -> Vec<String> {
    let mut kinds: std::collections::BTreeMap<&'static str, usize> = Default::default();
    let mut details = Vec::new();
    let (mut split, mut repaired) = (0usize, 0usize);
    for m in meshes {
        if !m.report.is_clean() {
            repaired += 1;
        }
        for (face, why) in &m.report.dropped_faces {
            let (kind, text) = dropped_reason(why, &m.face_numbers, *face);
            *kinds.entry(kind).or_default() += 1;
            details.push(format!(
                "{}: {} dropped: {text}",
                m.name,
                m.face_numbers.name(*face)
            ));
        }
        for (face, loops) in &m.report.split_faces {
            details.push(format!(
                "{}: {} visits a corner twice; split there into {loops} face(s)",
                m.name,
                m.face_numbers.name(*face)
            ));
        }
        for (vertex, copies) in &m.report.split_vertices {
            split += 1;
            let number = match m.vertex_numbers.get(*vertex as usize) {
                Some(&n) if n > 0 => n,
                _ => vertex + 1,
            };
            details.push(format!(
                "{}: vertex {number} joined separate fans of faces; split into {} copies",
                m.name,
                copies + 1
            ));
        }
    }
    let kept: Vec<&ImportedMesh> = meshes
        .iter()
        .filter(|m| !m.kept_places.is_empty())
        .collect();
    for m in &kept {
        details.extend(m.kept_places.iter().map(|p| format!("{}: {p}", m.name)));
    }
    let primitives: usize = meshes.iter().map(|m| m.skipped_primitives).sum();
    let polylines: usize = meshes.iter().map(|m| m.skipped_polylines).sum();
    let mut parts = Vec::new();
    let dropped: usize = kinds.values().sum();
    if dropped > 0 {
        let by_kind: Vec<String> = kinds.iter().map(|(k, n)| format!("{n} {k}")).collect();
        parts.push(format!(
            "{dropped} face(s) dropped ({})",
            by_kind.join(", ")
        ));
    }
    let pinched: usize = meshes.iter().map(|m| m.report.split_faces.len()).sum();
    if pinched > 0 {
        parts.push(format!(
            "{pinched} face(s) that visit a corner twice split into simple faces"
        ));
    }
    if split > 0 {
        parts.push(format!(
            "{split} vertex(es) split where separate fans of faces met"
        ));
    }
    // What repair changed comes after the count of objects repaired; the
    // rest is said on its own.
    let repair_parts = parts.len();
    if primitives > 0 {
        parts.push(format!("{primitives} point or line primitive(s) left out"));
    }
    if polylines > 0 {
        parts.push(format!(
            "{polylines} polyline(s) (`l`) left out: Hedra imports faces"
        ));
    }
    let not_imported: Vec<&str> = meshes
        .iter()
        .flat_map(|m| &m.not_imported)
        .map(String::as_str)
        .collect();
    if !not_imported.is_empty() {
        parts.push(format!("not imported: {}", not_imported.join(", ")));
    }
    if !kept.is_empty() {
        let mut names: Vec<String> = kept
            .iter()
            .take(3)
            .map(|m| format!("'{}'", m.name))
            .collect();
        if kept.len() > 3 {
            names.push(format!("{} more", kept.len() - 3));
        }
        parts.insert(
            0,
            format!(
                "{} object(s) kept as in the file, not manifold: {} (Mesh ▸ Make Manifold repairs them for editing)",
                kept.len(),
                names.join(", ")
            ),
        );
    }
    if parts.is_empty() {
        return Vec::new();
    }
    let mut summary: Vec<String> = Vec::new();
    if !kept.is_empty() {
        summary.push(parts.remove(0));
    }
    let others = parts.split_off(repair_parts);
    if !parts.is_empty() {
        let whom = if repaired > 0 {
            format!(
                "{repaired} of {} object(s) repaired: ",
                meshes.iter().filter(|m| m.mesh.is_some()).count()
            )
        } else {
            String::new()
        };
        summary.push(format!("{whom}{}", parts.join("; ")));
    }
    summary.extend(others);
    let mut out = vec![summary.join("; ")];
    let more = details.len().saturating_sub(MAX_DETAILS);
    out.extend(
        details
            .into_iter()
            .take(MAX_DETAILS)
            .map(|d| format!("  {d}")),
    );
    if more > 0 {
        out.push(format!("  … and {more} more"));
    }
    out
}

/// Detail lines of [`describe_repairs`] at most.
pub const MAX_DETAILS: usize = 20;
