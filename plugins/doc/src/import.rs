//! Reading meshes from other formats into the scene. OBJ: every object or
//! group becomes a mesh node, polygons are kept, `vt` UVs and `vn` normals
//! become corner attributes, polylines (`l`) are left out with a note; STL
//! (binary, or ASCII with any number of `solid` blocks, one node each):
//! triangles with equal corners welded. Faces that cannot join a
//! manifold half-edge mesh are dropped or split off (with a report); the
//! corners of the faces that are kept keep their attributes.
//!
//! OBJ objects and groups: `o` and `g` both start a new node (tobj reads
//! them alike; a pre-pass over the text tells them apart). A file with only
//! `o` or only `g` gives one top-level mesh node per object or group. When
//! an object holds groups, the object becomes a parent node (an empty, or a
//! mesh of its faces outside any group) and each group a child mesh node.
//! A group name that appears again later gives another node.
//!
//! OBJ free-form curves (`cstype [rat] bspline` or `bezier`, `deg`, `curv`,
//! `parm u`, `end`, with weights from `v x y z w`) become NURBS curve
//! nodes, named after the object or group they are in, trimmed to their
//! `curv` range; other free-form types (Cardinal, Taylor, basis-matrix
//! curves, surfaces, trimming curves) are left out with a note.

use crate::history::{NodeChange, Transaction};
use crate::kept::{KeptMesh, KeptMeshContent};
use crate::scene::{
    CornerAttributes, Document, MeshContent, Node, NodeContent, NodeId, NodeTransform,
};
use glam::{DVec2, DVec3};
use hedra_geom::{HalfEdgeMesh, RepairReport};
use std::path::Path;
use std::sync::Arc;

mod obj;
mod obj_curves;
mod repairs;
mod stl;

use obj::obj_text;
pub use obj::{ObjElement, ObjError, obj_from_str};
pub use repairs::{FaceNumbers, MAX_DETAILS, describe_repairs};
pub use stl::{StlError, stl_from_bytes};

/// A node read from a file: its mesh (none for a grouping node) with what
/// had to be repaired, its parent among the imported nodes, its transform.
#[derive(Debug)]
pub struct ImportedMesh {
    /// The node's name: the file's object, group or node name, else one made
    /// up from the file (its stem, "Node 3").
    pub name: String,
    /// The mesh in the node's local space; `None` for a grouping node (or when
    /// repair dropped every face).
    pub mesh: Option<HalfEdgeMesh>,
    /// What repair dropped or split to make the mesh manifold.
    pub report: RepairReport,
    /// Index of the parent in the same import list.
    pub parent: Option<usize>,
    /// The local transform relative to the parent (identity for OBJ and STL).
    pub transform: NodeTransform,
    /// Primitives that are not triangles (points, lines) and were left out.
    pub skipped_primitives: usize,
    /// OBJ polylines (`l`) left out (Hedra imports faces).
    pub skipped_polylines: usize,
    /// How the report's face numbers are shown (as the file counts them).
    pub face_numbers: FaceNumbers,
    /// What the file has that Hedra does not import ("2 material(s)"), on
    /// the first node of an import.
    pub not_imported: Vec<String>,
    /// The file's number of each input vertex (OBJ `v` lines, from 1), for
    /// the report; empty when the file numbers vertices no other way.
    pub vertex_numbers: Vec<u32>,
    /// UVs and normals of the mesh's face corners that the file gave.
    pub corners: CornerAttributes,
    /// A curve read from the file (an OBJ free-form B-spline or Bézier
    /// curve): the node is a curve node, `mesh` is `None`.
    pub curve: Option<hedra_geom::NurbsCurve>,
    /// The node's whole content as a richer format reads it (USD: a mesh
    /// with its subdivision modifier and creases, a NURBS surface or
    /// curve; STEP: a B-spline surface or curve). When set it is used as
    /// it is and `mesh`, `corners` and `curve` are not read.
    pub content: Option<NodeContent>,
    /// The file hides the node (USD `visibility = "invisible"`).
    pub hidden: bool,
    /// The faces as the file gave them, when repair had to change them
    /// to build `mesh` (or the mesh of `content`): [`keep_as_they_are`]
    /// keeps them instead when they are not manifold.
    pub input: Option<KeptMesh>,
    /// Where the faces kept as they are ([`keep_as_they_are`]) are not
    /// manifold, in words; empty when the node is not a kept mesh.
    pub kept_places: Vec<String>,
}

impl ImportedMesh {
    /// A top-level mesh node.
    fn mesh(name: String, mesh: HalfEdgeMesh, report: RepairReport) -> Self {
        ImportedMesh {
            name,
            mesh: Some(mesh),
            report,
            parent: None,
            transform: NodeTransform::IDENTITY,
            skipped_primitives: 0,
            skipped_polylines: 0,
            face_numbers: FaceNumbers::InNode,
            not_imported: Vec::new(),
            vertex_numbers: Vec::new(),
            corners: CornerAttributes::default(),
            curve: None,
            content: None,
            hidden: false,
            input: None,
            kept_places: Vec::new(),
        }
    }

    /// A top-level grouping node without a mesh (the base that other
    /// importers fill in with `..ImportedMesh::empty(name)`).
    pub(crate) fn empty(name: String) -> Self {
        ImportedMesh {
            name,
            mesh: None,
            report: RepairReport::default(),
            parent: None,
            transform: NodeTransform::IDENTITY,
            skipped_primitives: 0,
            skipped_polylines: 0,
            face_numbers: FaceNumbers::InNode,
            not_imported: Vec::new(),
            vertex_numbers: Vec::new(),
            corners: CornerAttributes::default(),
            curve: None,
            content: None,
            hidden: false,
            input: None,
            kept_places: Vec::new(),
        }
    }

    /// The faces as the file gave them when the repair changed them
    /// (`None` when it did not), to be kept by [`keep_as_they_are`].
    pub(crate) fn with_input(mut self, positions: &[DVec3], polygons: &[Vec<u32>]) -> Self {
        if !self.report.is_clean() {
            self.input = Some(KeptMesh {
                positions: positions.to_vec(),
                faces: polygons.to_vec(),
            });
        }
        self
    }
}

/// How an import treats faces that a half-edge mesh cannot hold.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum NonManifold {
    /// Keep them as they are (a kept mesh, [`crate::kept`]): the default.
    #[default]
    Keep,
    /// Repair them into an editable half-edge mesh (faces dropped, fans
    /// split), as `hedra import --repair` and Mesh ▸ Make Manifold do.
    Repair,
}

/// Turns every imported node whose faces are not manifold into a kept
/// mesh of the faces as the file gave them (issue 37): faces of fewer
/// than three different corners are left out (they have no area), the rest
/// are kept, with the node's shading and subdivision. A node whose repair
/// only dropped such faces stays the repaired mesh. UVs and normals are
/// not kept on a kept mesh.
pub fn keep_as_they_are(meshes: &mut [ImportedMesh]) {
    for m in meshes {
        let Some(input) = m.input.take() else {
            continue;
        };
        let (mut faces, mut origin) = (Vec::new(), Vec::new());
        for (i, f) in input.faces.into_iter().enumerate() {
            let mut corners = f.clone();
            corners.sort_unstable();
            corners.dedup();
            let in_range = f.iter().all(|&v| (v as usize) < input.positions.len());
            if corners.len() >= 3 && in_range {
                faces.push(f);
                origin.push(i);
            }
        }
        let kept = KeptMesh {
            positions: input.positions,
            faces,
        };
        let places = kept.places();
        if places.is_empty() {
            continue;
        }
        let numbers = &m.face_numbers;
        let vertex_numbers = &m.vertex_numbers;
        let vertex = |v: u32| match vertex_numbers.get(v as usize) {
            Some(&n) if n > 0 => n.to_string(),
            _ => (v + 1).to_string(),
        };
        let face = |f: usize| numbers.name(origin[f]);
        m.kept_places = crate::kept::describe_places(&places, 5, &vertex, &face);
        let left_out = m.report.dropped_faces.len().saturating_sub(
            // Faces the repair dropped that the kept mesh keeps.
            m.report
                .dropped_faces
                .iter()
                .filter(|(f, _)| origin.binary_search(f).is_ok())
                .count(),
        );
        if left_out > 0 {
            m.kept_places.push(format!(
                "{left_out} face(s) of fewer than 3 different corners left out"
            ));
        }
        let (shading, subdivision) = match &m.content {
            Some(NodeContent::Mesh(c)) => (c.shading, c.subdivision),
            _ => (crate::scene::Shading::Flat, None),
        };
        m.content = Some(NodeContent::Kept(KeptMeshContent {
            mesh: Arc::new(kept),
            shading,
            subdivision,
        }));
        m.mesh = None;
        m.report = RepairReport::default();
        m.corners = CornerAttributes::default();
    }
}

/// The corner attributes of a mesh built by
/// [`HalfEdgeMesh::from_polygons_repaired`] (and maybe compacted): `uvs`
/// and `normals` hold one entry per input corner, polygon after polygon
/// (`arities` gives the polygon sizes), `None` where the file gave none;
/// either may be empty. Kept face `k` came from input polygon
/// `report.face_origin[k]`, and its loop starts at that polygon's first
/// corner. Non-finite values and zero normals are left out; normals are
/// stored normalised and rounded ([`stored_normal`]).
pub(crate) fn corner_attributes(
    mesh: &HalfEdgeMesh,
    report: &RepairReport,
    arities: &[usize],
    uvs: &[Option<DVec2>],
    normals: &[Option<DVec3>],
) -> CornerAttributes {
    let mut out = CornerAttributes::default();
    if uvs.is_empty() && normals.is_empty() {
        return out;
    }
    let starts: Vec<usize> = arities
        .iter()
        .scan(0usize, |acc, &a| {
            let s = *acc;
            *acc += a;
            Some(s)
        })
        .collect();
    for (k, f) in mesh.faces().enumerate() {
        let Some(&origin) = report.face_origin.get(k) else {
            break;
        };
        let (Some(&start), Some(&arity)) = (starts.get(origin), arities.get(origin)) else {
            continue;
        };
        if mesh.face_degree(f) != arity {
            continue;
        }
        for (i, h) in mesh.face_halfedges(f).enumerate() {
            if let Some(Some(uv)) = uvs.get(start + i)
                && uv.is_finite()
            {
                Arc::make_mut(&mut out.uvs).insert(h, *uv);
            }
            if let Some(Some(n)) = normals.get(start + i)
                && let Some(n) = n.try_normalize()
            {
                Arc::make_mut(&mut out.normals).insert(h, stored_normal(n));
            }
        }
    }
    out
}

/// Decimal places a stored normal keeps ([`stored_normal`]).
pub const NORMAL_DECIMALS: i32 = 7;

/// A unit normal as a scene keeps it: each component rounded to
/// [`NORMAL_DECIMALS`] places (within 5e-8, finer than the f32 the
/// viewport and glTF use), so that files store at most 10 characters per
/// component instead of the 17 digits of a normalised f64 (issue 31:
/// assimp's ClearCoatTest.gltf, 111,348 normal corners, saves in 8.8 MB
/// instead of 11.9 MB).
pub fn stored_normal(n: DVec3) -> DVec3 {
    let scale = 10f64.powi(NORMAL_DECIMALS);
    // `+ 0.0` turns -0 into 0.
    (n * scale).round() / scale + DVec3::ZERO
}

/// Why a file could not be imported.
#[derive(Debug, thiserror::Error)]
pub enum ImportError {
    /// The file cannot be read or parsed; the message says where and why.
    #[error("{path}: {message}")]
    Read {
        /// The file, as the caller named it.
        path: String,
        /// What went wrong, naming the line, object or buffer where known.
        message: String,
    },
    /// An extension Hedra does not import.
    #[error(
        "{path}: unsupported format '.{ext}' (supported: {})",
        supported_imports()
    )]
    Unsupported {
        /// The file, as the caller named it.
        path: String,
        /// The extension, without the dot.
        ext: String,
    },
    #[error(
        "{path}: the file name has no extension to tell its format (supported: {})",
        supported_imports()
    )]
    /// A file name without an extension.
    NoExtension {
        /// The file, as the caller named it.
        path: String,
    },
    /// A readable file with no faces (or, for glTF, no nodes).
    #[error("{path}: contains no faces")]
    Empty {
        /// The file, as the caller named it.
        path: String,
    },
    /// Every face was dropped: the first object's repair report says why.
    #[error("{path}: no face could be kept: {reason}")]
    NothingLeft {
        /// The file, as the caller named it.
        path: String,
        /// The first dropped object's repair report, as a sentence.
        reason: String,
    },
    /// A malformed OBJ line, found before the OBJ reader runs.
    #[error("{path}: {error}")]
    Obj {
        /// The file, as the caller named it.
        path: String,
        /// What is wrong, and on which line.
        error: ObjError,
    },
    /// A malformed STL triangle.
    #[error("{path}: {error}")]
    Stl {
        /// The file, as the caller named it.
        path: String,
        /// What is wrong, and in which triangle (and line, for ASCII).
        error: StlError,
    },
    /// A glTF file whose data would be read out of bounds or in a layout
    /// Hedra does not read.
    #[error("{path}: {error}")]
    Gltf {
        /// The file, as the caller named it.
        path: String,
        /// What is wrong, naming the mesh, accessor or buffer view (boxed:
        /// it is large and rare).
        error: Box<crate::gltf::GltfError>,
    },
}

/// The extensions [`import_file`] reads, in the order menus list them.
pub const IMPORT_FORMATS: &[&str] = &[
    "obj", "stl", "gltf", "glb", "usda", "usdc", "usdz", "usd", "step", "stp",
];

/// The import extensions as messages list them: `.obj, .stl, ...`.
pub fn supported_imports() -> String {
    IMPORT_FORMATS
        .iter()
        .map(|e| format!(".{e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Reads a file by its extension, keeping faces that are not manifold as
/// they are ([`NonManifold::Keep`]).
///
/// # Errors
/// As [`obj_from_str`], plus unreadable files and unknown extensions.
pub fn import_file(path: &Path) -> Result<Vec<ImportedMesh>, ImportError> {
    import_file_with(path, NonManifold::Keep)
}

/// Reads a file by its extension, keeping or repairing faces that are not
/// manifold.
///
/// # Errors
/// As [`import_file`].
pub fn import_file_with(
    path: &Path,
    non_manifold: NonManifold,
) -> Result<Vec<ImportedMesh>, ImportError> {
    let mut meshes = read_file(path)?;
    if non_manifold == NonManifold::Keep {
        keep_as_they_are(&mut meshes);
    }
    Ok(meshes)
}

/// The file's nodes, repaired where they are not manifold.
fn read_file(path: &Path) -> Result<Vec<ImportedMesh>, ImportError> {
    let shown = path.display().to_string();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "obj" => {
            let bytes = crate::input::read(path).map_err(|e| ImportError::Read {
                path: shown.clone(),
                message: e.to_string(),
            })?;
            obj_from_str(&obj_text(&bytes), &shown)
        }
        "stl" => {
            let bytes = crate::input::read(path).map_err(|e| ImportError::Read {
                path: shown.clone(),
                message: e.to_string(),
            })?;
            let name = path
                .file_stem()
                .map_or_else(|| "STL".to_string(), |s| s.to_string_lossy().into_owned());
            stl_from_bytes(&bytes, &name, &shown)
        }
        "step" | "stp" => {
            let bytes = crate::input::read(path).map_err(|e| ImportError::Read {
                path: shown.clone(),
                message: e.to_string(),
            })?;
            crate::step::step_from_bytes(&bytes, &shown)
        }
        "gltf" | "glb" => {
            let bytes = crate::input::read(path).map_err(|e| ImportError::Read {
                path: shown.clone(),
                message: e.to_string(),
            })?;
            crate::gltf::gltf_from_bytes(&bytes, path.parent(), &shown)
        }
        "usda" | "usdc" | "usdz" | "usd" => crate::usd::usd_from_path(path),
        "" => Err(ImportError::NoExtension { path: shown }),
        other => Err(ImportError::Unsupported {
            path: shown,
            ext: other.to_string(),
        }),
    }
}

impl Document {
    /// The transaction that adds imported nodes (with their hierarchy and
    /// transforms) to the scene.
    pub fn decide_import(&self, meshes: &[ImportedMesh], label: &str, serial: u64) -> Transaction {
        let mut next = self.next_node_id;
        let mut changes = Vec::new();
        let mut names: Vec<String> = Vec::new();
        for m in meshes {
            let mut name = self.unique_name(&m.name);
            let base = name.clone();
            let mut k = 1;
            while names.contains(&name) {
                name = format!("{base}.{k:03}");
                k += 1;
            }
            names.push(name.clone());
            let id = NodeId(next);
            next += 1;
            let parent = m
                .parent
                .and_then(|p| changes.get(p))
                .map(|c: &NodeChange| c.id);
            let node = Node {
                id,
                name,
                parent,
                transform: m.transform,
                visible: !m.hidden,
                content: match (&m.mesh, &m.curve) {
                    _ if m.content.is_some() => m.content.clone().unwrap_or(NodeContent::Empty),
                    (Some(mesh), _) => NodeContent::Mesh(MeshContent {
                        corners: m.corners.clone(),
                        ..MeshContent::new(Arc::new(mesh.clone()))
                    }),
                    (None, Some(curve)) => NodeContent::Curve(Arc::new(
                        crate::scene::CurveContent::from_nurbs(curve.clone()),
                    )),
                    (None, None) => NodeContent::Empty,
                },
                construction: None,
                g1_join: None,
            };
            changes.push(NodeChange {
                id,
                before: None,
                after: Some(node),
            });
        }
        Transaction {
            serial,
            label: label.to_string(),
            command: None,
            changes,
            next_id_before: self.next_node_id,
            next_id_after: next,
        }
    }
}
