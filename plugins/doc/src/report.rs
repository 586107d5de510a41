//! What `hedra info` prints: nodes with their kind, parent and world
//! transform, and for each mesh its counts and invariants. The JSON form is
//! documented in `docs/info-json.md`.

use crate::scene::{Document, NodeContent};
use crate::session::Session;
use hedra_geom::MeshStats;
use serde::Serialize;
use std::fmt::Write;

/// The whole `hedra info` report of a session (`docs/info-json.md`).
#[derive(Serialize)]
pub struct SceneReport {
    /// The scene file format version this build writes.
    pub format_version: u32,
    /// Every node, in id (creation) order.
    pub nodes: Vec<NodeReport>,
    /// The undo history's size and labels.
    pub history: HistoryReport,
}

/// One node of the report.
#[derive(Serialize)]
pub struct NodeReport {
    /// The node's id.
    pub id: u64,
    /// The node's name.
    pub name: String,
    /// "empty", "mesh", "curve" or "surface".
    pub kind: &'static str,
    /// The parent's id; `None` at the top level.
    pub parent: Option<u64>,
    /// The node's own visibility flag (a hidden ancestor is not counted).
    pub visible: bool,
    /// The transform relative to the parent.
    pub local: TransformReport,
    /// The transform relative to the world (the parents' transforms composed,
    /// root first).
    pub world: TransformReport,
    /// Counts and invariants of a mesh node's cage; `None` for other kinds.
    pub mesh: Option<MeshReport>,
    /// Curves and surfaces: degrees, control points, domain.
    pub shape: Option<ShapeReport>,
    /// A node made from curves that follows them: what it is made of;
    /// left out for other nodes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub construction: Option<ConstructionReport>,
    /// CSG nodes: the operation, the operands and the evaluated solid.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub csg: Option<CsgReport>,
    /// Mesh and CSG nodes: what `hedra export` writes for the node (when
    /// visible) with the default shape, counted on the very geometry the
    /// export writes ([`crate::export::written_counts`]); left out for
    /// other nodes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub export: Option<ExportReport>,
    /// Kept (non-manifold) meshes: counts and where they are not
    /// manifold; left out for other nodes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kept: Option<KeptReport>,
}

/// A kept mesh node: its counts and its non-manifold places (vertex and
/// face numbers count from 0, in the node's lists).
#[derive(Serialize)]
pub struct KeptReport {
    /// Vertices in the list (some may be used by no face).
    pub vertices: usize,
    /// Faces.
    pub faces: usize,
    /// Face corners.
    pub corners: usize,
    /// Edges in three or more faces: their two vertices and face count.
    pub crowded_edges: Vec<([u32; 2], u32)>,
    /// Edges two faces run along the same way.
    pub same_way_edges: Vec<[u32; 2]>,
    /// Vertices where separate fans of faces meet.
    pub split_vertices: Vec<u32>,
    /// Faces that visit a vertex twice.
    pub repeating_faces: Vec<usize>,
    /// The subdivision it is shown and exported with.
    pub subdivision: Option<SubdivisionReport>,
}

impl KeptReport {
    fn of(content: &crate::kept::KeptMeshContent) -> Self {
        let m = &content.mesh;
        let places = m.places();
        KeptReport {
            vertices: m.positions.len(),
            faces: m.faces.len(),
            corners: m.corner_count(),
            crowded_edges: places.crowded_edges,
            same_way_edges: places.same_way_edges,
            split_vertices: places.split_vertices,
            repeating_faces: places.repeating_faces,
            subdivision: content.subdivision.map(|m| SubdivisionReport::of(&m, 0)),
        }
    }
}

/// What `hedra export` writes for a node.
#[derive(Serialize)]
pub struct ExportReport {
    /// Vertices (OBJ `v` lines).
    pub vertices: usize,
    /// Polygons as OBJ writes them (`f` lines, n-gons kept).
    pub faces: usize,
    /// Triangles as STL and glTF write them.
    pub triangles: usize,
    /// Why the node cannot be exported (then the counts are 0).
    pub error: Option<String>,
}

impl ExportReport {
    /// The report of a mesh or CSG node; `None` for other kinds.
    fn of(doc: &Document, node: &crate::scene::Node) -> Option<Self> {
        if !matches!(
            node.content,
            NodeContent::Mesh(_) | NodeContent::Csg(_) | NodeContent::Kept(_)
        ) {
            return None;
        }
        Some(
            match crate::export::written_counts(doc, node.id, crate::export::ExportShape::Evaluated)
            {
                Ok(c) => {
                    let c = c.unwrap_or_default();
                    ExportReport {
                        vertices: c.vertices,
                        faces: c.faces,
                        triangles: c.triangles,
                        error: None,
                    }
                }
                Err(e) => ExportReport {
                    vertices: 0,
                    faces: 0,
                    triangles: 0,
                    error: Some(e.to_string()),
                },
            },
        )
    }
}

/// How a node follows the curves it was made from.
#[derive(Serialize)]
pub struct ConstructionReport {
    /// `"Extrude"`, `"Revolve"`, `"Screw"`, `"Sweep"`, `"Sweep2"` or `"Loft"`.
    pub recipe: &'static str,
    /// The input nodes' ids, profile first (then rails or the sections in order).
    pub inputs: Vec<u64>,
    /// One line: the recipe, its inputs by name, its parameters, the output.
    pub summary: String,
}

/// A CSG node: its boolean, its operands and its evaluated solid.
#[derive(Serialize)]
pub struct CsgReport {
    /// "union", "intersection" or "difference".
    pub op: &'static str,
    /// The operands' ids, in order.
    pub operands: Vec<u64>,
    /// The solid's counts, or why there is none.
    pub evaluated: EvaluatedReport,
}

fn csg_report(doc: &Document, id: crate::scene::NodeId) -> Option<CsgReport> {
    let NodeContent::Csg(c) = &doc.node(id)?.content else {
        return None;
    };
    let evaluated = EvaluatedReport::of(
        crate::csg::evaluate(doc, id)
            .as_deref()
            .map_err(|e| e.to_string()),
    );
    Some(CsgReport {
        op: c.op.label(),
        operands: crate::csg::operands(doc, id).iter().map(|o| o.0).collect(),
        evaluated,
    })
}

/// A transform as plain arrays.
#[derive(Serialize)]
pub struct TransformReport {
    /// Translation `[x, y, z]`.
    pub translation: [f64; 3],
    /// Quaternion `[x, y, z, w]`.
    pub rotation: [f64; 4],
    /// Scale `[x, y, z]`.
    pub scale: [f64; 3],
}

/// A mesh node's cage: counts and invariants, creases, corner attributes.
#[derive(Serialize)]
pub struct MeshReport {
    /// Live vertices.
    pub vertices: usize,
    /// Live edges.
    pub edges: usize,
    /// Live faces.
    pub faces: usize,
    /// Holes in the surface: loops of edges with a face on one side only.
    pub boundary_loops: usize,
    /// Connected components.
    pub shells: usize,
    /// V − E + F.
    pub euler_characteristic: i64,
    /// Handles, from χ = 2S − 2g − b; `None` when the mesh is invalid.
    pub genus: Option<i64>,
    /// True when the mesh is valid and has no boundary.
    pub closed: bool,
    /// True when the half-edge validator passed.
    pub manifold: bool,
    /// True when the half-edge validator passed.
    pub valid: bool,
    /// The validator's message when not valid.
    pub validation_error: Option<String>,
    /// The primitive kind the mesh was made from; `None` once edited, or for
    /// meshes not made from a primitive.
    pub primitive: Option<String>,
    /// Edges with a subdivision crease.
    pub creased_edges: usize,
    /// Vertices with a subdivision corner sharpness.
    pub creased_vertices: usize,
    /// The subdivision modifier; `None` without one.
    pub subdivision: Option<SubdivisionReport>,
    /// The modifier stack (Mirror, Array), in order; left out when empty.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub modifiers: Vec<ModifierReport>,
    /// The cage with the stack modifiers that come before subdivision
    /// applied (all of them by default): what subdivision refines. `None`
    /// (left out) without stack modifiers. What export writes is
    /// [`NodeReport::export`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub evaluated: Option<EvaluatedReport>,
    /// Face corners (the sum of the faces' sides).
    pub corners: usize,
    /// Face corners with a UV.
    pub uv_corners: usize,
    /// Face corners with a custom normal.
    pub normal_corners: usize,
}

/// A modifier of a mesh node's stack.
#[derive(Serialize)]
pub struct ModifierReport {
    /// `"Mirror"` or `"Array"`.
    pub kind: &'static str,
    /// Its settings in words (`"Mirror X, merge 0.001"`).
    pub summary: String,
    /// A Decimate modifier's progressive mesh: the face counts of its
    /// coarsest and finest levels and how many levels lie between; left out
    /// for other kinds.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub levels: Option<LevelsReport>,
}

/// The levels of detail a Decimate modifier's progressive mesh holds.
#[derive(Serialize)]
pub struct LevelsReport {
    /// How many levels (vertex splits + 1).
    pub count: usize,
    /// Faces at the coarsest level.
    pub min_faces: usize,
    /// Faces at the finest level (the input).
    pub max_faces: usize,
}

/// The counts of a mesh node's stack result.
#[derive(Serialize)]
pub struct EvaluatedReport {
    /// Vertices of the result.
    pub vertices: usize,
    /// Edges of the result.
    pub edges: usize,
    /// Faces of the result.
    pub faces: usize,
    /// Loops of boundary edges.
    pub boundary_loops: usize,
    /// Connected components.
    pub shells: usize,
    /// Handles; `None` when not valid.
    pub genus: Option<i64>,
    /// Why the stack could not be evaluated (then the counts are 0).
    pub error: Option<String>,
}

impl EvaluatedReport {
    /// The counts of an evaluated mesh, or zeros and why there is none.
    fn of(result: Result<&hedra_geom::HalfEdgeMesh, String>) -> Self {
        match result {
            Ok(mesh) => {
                let s = mesh.stats();
                EvaluatedReport {
                    vertices: s.vertices,
                    edges: s.edges,
                    faces: s.faces,
                    boundary_loops: s.boundary_loops,
                    shells: s.shells,
                    genus: s.genus,
                    error: None,
                }
            }
            Err(error) => EvaluatedReport {
                vertices: 0,
                edges: 0,
                faces: 0,
                boundary_loops: 0,
                shells: 0,
                genus: None,
                error: Some(error),
            },
        }
    }
}

/// A mesh node's subdivision modifier.
#[derive(Serialize)]
pub struct SubdivisionReport {
    /// The scheme's label ("Catmull-Clark").
    pub scheme: &'static str,
    /// Levels shown in the viewport.
    pub viewport_level: u32,
    /// Levels written on export.
    pub export_level: u32,
    /// The boundary rule's label ("Edges only").
    pub boundary: &'static str,
    /// The crease method's label ("Uniform").
    pub crease_method: &'static str,
    /// How many stack modifiers run before subdivision.
    pub stack_position: usize,
}

impl SubdivisionReport {
    /// The report of a modifier that runs after `stack_position` stack
    /// modifiers.
    fn of(m: &crate::scene::SubdivisionModifier, stack_position: usize) -> Self {
        SubdivisionReport {
            scheme: m.options.scheme.label(),
            viewport_level: m.viewport_level,
            export_level: m.export_level,
            boundary: m.options.boundary.label(),
            crease_method: m.options.crease_method.label(),
            stack_position,
        }
    }
}

/// A curve or surface node's shape.
#[derive(Serialize)]
pub struct ShapeReport {
    /// "nurbs curve" (or the curve kind: "catmull-rom curve", "koch curve", …),
    /// "nurbs surface", "bezier triangle".
    pub kind: &'static str,
    /// One degree for curves and triangles, (u, v) for surfaces.
    pub degrees: Vec<usize>,
    /// Number of control points.
    pub control_points: usize,
    /// Curves: [start, end]; surfaces: [u0, u1, v0, v1]; triangles: none.
    pub domain: Vec<f64>,
    /// True when every weight is 1.
    pub polynomial: bool,
}

/// The report's name of a curve kind ("nurbs curve", "catmull-rom curve").
fn curve_kind_label(kind: &hedra_geom::curves::CurveKind) -> &'static str {
    use hedra_geom::curves::{CurveKind as K, Fractal, FractalRule};
    match kind {
        K::Nurbs(_) => "nurbs curve",
        K::Lagrange(_) => "lagrange curve",
        K::CubicHermite(_) => "cubic hermite curve",
        K::QuinticHermite(_) => "quintic hermite curve",
        K::CatmullRom(_) => "catmull-rom curve",
        K::KochanekBartels(_) => "kochanek-bartels curve",
        K::CubicSpline(_) => "c2 cubic spline",
        K::Chaikin(_) => "chaikin curve",
        K::PolyBezier(_) => "poly-bezier curve",
        K::Fractal(Fractal {
            rule: FractalRule::Koch,
            ..
        }) => "koch curve",
        K::Fractal(Fractal {
            rule: FractalRule::QuadraticKoch,
            ..
        }) => "quadratic koch curve",
    }
}

fn shape_report(content: &NodeContent) -> Option<ShapeReport> {
    use hedra_geom::curves::Curve;
    use hedra_geom::surfaces::Surface;
    match content {
        NodeContent::Curve(content) => {
            let c = content.nurbs();
            let (a, b) = c.domain();
            Some(ShapeReport {
                kind: curve_kind_label(content.kind()),
                degrees: vec![c.degree()],
                // The points `SetControlPoints` indexes: the kind's own.
                control_points: content.control_points().len(),
                domain: vec![a, b],
                polynomial: c.is_polynomial(),
            })
        }
        NodeContent::Surface(s) => Some(match &**s {
            crate::scene::SurfaceShape::Nurbs(n) => {
                let ((u0, u1), (v0, v1)) = n.domain();
                let (du, dv) = n.degrees();
                ShapeReport {
                    kind: "nurbs surface",
                    degrees: vec![du, dv],
                    control_points: n.points().len(),
                    domain: vec![u0, u1, v0, v1],
                    polynomial: n.weights().iter().all(|&w| w == 1.0),
                }
            }
            crate::scene::SurfaceShape::Triangle(t) => ShapeReport {
                kind: "bezier triangle",
                degrees: vec![t.degree],
                control_points: t.points.len(),
                domain: vec![],
                polynomial: true,
            },
        }),
        _ => None,
    }
}

/// The size of the undo history.
#[derive(Serialize)]
pub struct HistoryReport {
    /// Steps that can be undone.
    pub undo_steps: usize,
    /// Undone steps that can be redone.
    pub redo_steps: usize,
    /// Oldest steps dropped by the history limits.
    pub dropped_steps: usize,
    /// Labels of the undoable steps, oldest first.
    pub labels: Vec<String>,
}

fn transform(t: &crate::scene::NodeTransform) -> TransformReport {
    TransformReport {
        translation: t.translation.to_array(),
        rotation: t.rotation.to_array(),
        scale: t.scale.to_array(),
    }
}

fn mesh_report(content: &crate::scene::MeshContent) -> MeshReport {
    let s: MeshStats = content.mesh.stats();
    let live = |e: &hedra_geom::EdgeId| content.mesh.is_edge(*e);
    let m = &content.mesh;
    let corner = |h: &&hedra_geom::HalfEdgeId| m.is_halfedge(**h) && m.face(**h).is_some();
    MeshReport {
        corners: crate::scene::CornerAttributes::corner_count(m),
        uv_corners: content.corners.uvs.keys().filter(corner).count(),
        normal_corners: content.corners.normals.keys().filter(corner).count(),
        creased_edges: content
            .creases
            .edge_sharpness()
            .keys()
            .filter(|e| live(e))
            .count(),
        creased_vertices: content
            .creases
            .vertices
            .keys()
            .filter(|v| content.mesh.is_vertex(**v))
            .count(),
        subdivision: content
            .subdivision
            .map(|m| SubdivisionReport::of(&m, content.subdivision_position())),
        modifiers: content
            .modifiers
            .iter()
            .enumerate()
            .map(|(i, m)| ModifierReport {
                kind: m.name(),
                summary: m.summary(),
                levels: content
                    .decimate_face_counts(i)
                    .ok()
                    .flatten()
                    .and_then(|counts| {
                        Some(LevelsReport {
                            count: counts.len(),
                            min_faces: *counts.first()?,
                            max_faces: *counts.last()?,
                        })
                    }),
            })
            .collect(),
        // The stack up to subdivision's place: what subdivision refines
        // (all of it by default). With subdivision placed before some
        // modifiers, the whole stack without it is a shape nothing shows
        // (issue 31, item 18: a Decimate at 10 % of the bare cube, F 4,
        // where export writes 76 faces); `export` counts what is written.
        evaluated: content.has_stack_modifiers().then(|| {
            let result = content.apply_stack(content.subdivision_position());
            EvaluatedReport::of(result.as_ref().map(|e| &*e.mesh).map_err(|e| e.to_string()))
        }),
        primitive: content.primitive.as_ref().map(|p| p.kind().to_string()),
        vertices: s.vertices,
        edges: s.edges,
        faces: s.faces,
        boundary_loops: s.boundary_loops,
        shells: s.shells,
        euler_characteristic: s.euler_characteristic,
        genus: s.genus,
        closed: s.closed,
        manifold: s.manifold,
        valid: s.validation.is_ok(),
        validation_error: s.validation.err(),
    }
}

impl SceneReport {
    /// The report of a session's document and history.
    ///
    /// Complexity: O(N) for the hierarchy (world transforms computed once
    /// per node, top down), plus each node's counts.
    pub fn new(session: &Session) -> Self {
        let doc: &Document = &session.doc;
        let tree = doc.hierarchy();
        let nodes = doc
            .nodes()
            .map(|n| NodeReport {
                id: n.id.0,
                name: n.name.clone(),
                kind: n.content.kind(),
                parent: n.parent.map(|p| p.0),
                visible: n.visible,
                local: transform(&n.transform),
                world: transform(&crate::scene::NodeTransform::from_matrix(
                    tree.world_matrix(n.id),
                )),
                mesh: match &n.content {
                    NodeContent::Mesh(m) => Some(mesh_report(m)),
                    _ => None,
                },
                shape: shape_report(&n.content),
                construction: n.construction.as_ref().map(|c| ConstructionReport {
                    recipe: c.recipe.name(),
                    inputs: c.recipe.inputs().iter().map(|i| i.0).collect(),
                    summary: c.summary(&|id| {
                        doc.node(id)
                            .map_or_else(|| id.to_string(), |n| format!("'{}' ({id})", n.name))
                    }),
                }),
                csg: csg_report(doc, n.id),
                export: ExportReport::of(doc, n),
                kept: match &n.content {
                    NodeContent::Kept(k) => Some(KeptReport::of(k)),
                    _ => None,
                },
            })
            .collect();
        let h = &session.history;
        SceneReport {
            format_version: crate::file::FORMAT_VERSION,
            nodes,
            history: HistoryReport {
                undo_steps: h.done().len(),
                redo_steps: h.undone().len(),
                dropped_steps: h.dropped,
                labels: h.done().iter().map(|t| t.label.clone()).collect(),
            },
        }
    }

    /// Pretty-printed JSON, as `hedra info --json` prints it.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("reports always serialise")
    }

    /// Human-readable text, one block per node.
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        let v3 = |a: [f64; 3]| format!("({:.4}, {:.4}, {:.4})", a[0], a[1], a[2]);
        for n in &self.nodes {
            let parent = n.parent.map_or("-".to_string(), |p| format!("#{p}"));
            let _ = writeln!(
                out,
                "#{} {} [{}] parent {} {}",
                n.id,
                n.name,
                n.kind,
                parent,
                if n.visible { "" } else { "(hidden)" }
            );
            let _ = writeln!(
                out,
                "    world: translation {} scale {} rotation {:?}",
                v3(n.world.translation),
                v3(n.world.scale),
                n.world.rotation
            );
            if let Some(sh) = &n.shape {
                let degrees: Vec<String> = sh.degrees.iter().map(|d| d.to_string()).collect();
                let _ = writeln!(
                    out,
                    "    {}: degree {}, {} control points, domain {:?}{}",
                    sh.kind,
                    degrees.join(" × "),
                    sh.control_points,
                    sh.domain,
                    if sh.polynomial { "" } else { ", rational" }
                );
            }
            if let Some(c) = &n.construction {
                let _ = writeln!(out, "    made by: {}", c.summary);
            }
            if let Some(c) = &n.csg {
                let ops: Vec<String> = c.operands.iter().map(|o| format!("#{o}")).collect();
                let e = &c.evaluated;
                let _ = match &e.error {
                    Some(err) => {
                        writeln!(out, "    csg: {} of {}: error: {err}", c.op, ops.join(", "))
                    }
                    None if e.faces == 0 => writeln!(
                        out,
                        "    csg: {} of {}: empty solid (V 0 E 0 F 0)",
                        c.op,
                        ops.join(", ")
                    ),
                    None => writeln!(
                        out,
                        "    csg: {} of {}: solid V {} E {} F {}, shells {}, genus {}",
                        c.op,
                        ops.join(", "),
                        e.vertices,
                        e.edges,
                        e.faces,
                        e.shells,
                        e.genus.map_or("?".into(), |g| g.to_string()),
                    ),
                };
            }
            if let Some(e) = &n.export {
                let _ = match &e.error {
                    Some(err) => writeln!(out, "    export: error: {err}"),
                    None => writeln!(
                        out,
                        "    export: V {} F {} ({} triangles)",
                        e.vertices, e.faces, e.triangles
                    ),
                };
            }
            if let Some(k) = &n.kept {
                let _ = writeln!(
                    out,
                    "    kept mesh: V {} F {} ({} corners), NOT manifold (kept as imported; Mesh ▸ Make Manifold or the MakeManifold command makes it editable)",
                    k.vertices, k.faces, k.corners
                );
                let places = hedra_geom::subdivision::NonManifoldPlaces {
                    crowded_edges: k.crowded_edges.clone(),
                    same_way_edges: k.same_way_edges.clone(),
                    split_vertices: k.split_vertices.clone(),
                    repeating_faces: k.repeating_faces.clone(),
                };
                let number = |v: u32| (v + 1).to_string();
                let face = |f: usize| format!("face {}", f + 1);
                for line in crate::kept::describe_places(&places, 10, &number, &face) {
                    let _ = writeln!(out, "    not manifold (numbers from 1): {line}");
                }
                if let Some(sd) = &k.subdivision {
                    let _ = writeln!(
                        out,
                        "    subdivision: {}, level {} in the viewport, {} on export, boundary {} (non-manifold edges and vertices sharp, as OpenSubdiv)",
                        sd.scheme, sd.viewport_level, sd.export_level, sd.boundary
                    );
                }
            }
            if let Some(m) = &n.mesh {
                let _ = writeln!(
                    out,
                    "    mesh: V {} E {} F {}, boundary loops {}, shells {}, Euler characteristic {}, genus {}, {}, {}",
                    m.vertices,
                    m.edges,
                    m.faces,
                    m.boundary_loops,
                    m.shells,
                    m.euler_characteristic,
                    m.genus.map_or("?".into(), |g| g.to_string()),
                    if m.closed { "closed" } else { "open" },
                    if m.manifold {
                        "manifold"
                    } else {
                        "NOT manifold"
                    },
                );
                let _ = writeln!(
                    out,
                    "    validate: {}",
                    m.validation_error.as_deref().unwrap_or("ok")
                );
                if let Some(sd) = &m.subdivision {
                    let _ = writeln!(
                        out,
                        "    subdivision: {}, level {} in the viewport, {} on export, boundary {}, creases {}{}",
                        sd.scheme,
                        sd.viewport_level,
                        sd.export_level,
                        sd.boundary,
                        sd.crease_method,
                        if sd.stack_position < m.modifiers.len() {
                            format!(", after {} of the stack's modifiers", sd.stack_position)
                        } else {
                            String::new()
                        }
                    );
                }
                for (i, md) in m.modifiers.iter().enumerate() {
                    let _ = writeln!(out, "    modifier {}: {}", i + 1, md.summary);
                    if let Some(l) = &md.levels {
                        let _ = writeln!(
                            out,
                            "      levels of detail: {} ({} to {} faces)",
                            l.count, l.min_faces, l.max_faces
                        );
                    }
                }
                if let Some(e) = &m.evaluated {
                    match &e.error {
                        Some(err) => {
                            let _ = writeln!(out, "    evaluated: error: {err}");
                        }
                        None => {
                            let _ = writeln!(
                                out,
                                "    evaluated: V {} E {} F {}, boundary loops {}, shells {}, genus {}",
                                e.vertices,
                                e.edges,
                                e.faces,
                                e.boundary_loops,
                                e.shells,
                                e.genus.map_or("?".into(), |g| g.to_string()),
                            );
                        }
                    }
                }
                if m.uv_corners + m.normal_corners > 0 {
                    let _ = writeln!(
                        out,
                        "    attributes: UVs on {} of {} corners, custom normals on {} corners",
                        m.uv_corners, m.corners, m.normal_corners
                    );
                }
                if m.creased_edges + m.creased_vertices > 0 {
                    let _ = writeln!(
                        out,
                        "    creases: {} edge(s), {} vertex corner(s)",
                        m.creased_edges, m.creased_vertices
                    );
                }
            }
        }
        let _ = writeln!(
            out,
            "history: {} undo step(s), {} redo step(s)",
            self.history.undo_steps, self.history.redo_steps
        );
        out
    }
}
