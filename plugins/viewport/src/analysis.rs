//! Curve and surface analysis drawn in the viewport (curvature comb, Frenet frame, sections).

use crate::*;

/// Edit mode's vertex or face-centre dots; they face the camera, so they are
/// drawn every frame (only the selected ones on dense meshes).
/// The analysis overlays of the active curve (seed 001's exercises), set
/// from the properties panel.
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct CurveAnalysis {
    /// Curvature comb: normals scaled by curvature along the curve.
    pub comb: bool,
    /// Length of the comb's teeth per unit of curvature.
    pub comb_scale: f64,
    /// Colour the curve by curvature (blue flat … red bent).
    pub colour_by_curvature: bool,
    /// A moving point with its Frenet frame and osculating circle.
    pub frame: bool,
    /// Where that point is, as a fraction of the domain.
    pub at: f64,
    /// The point of the curve nearest the pointer, found by Newton's method
    /// with the seed's stopping tests, drawn and reported live.
    pub closest: bool,
    /// What the closest-point probe found this frame (world space).
    pub closest_found: Option<ClosestPoint>,
    /// The continuity of each joint (C0 … C2, G1, G2) labelled on the
    /// canvas.
    pub joints: bool,
    /// The convex hull of each Bézier segment's control polygon.
    pub hulls: bool,
}

/// The point of the active curve nearest the pointer (on the plane facing
/// the view through the curve's middle).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosestPoint {
    /// The pointer's point in the world.
    pub from: DVec3,
    /// The curve's parameter there.
    pub t: f64,
    /// The nearest point of the curve.
    pub at: DVec3,
    /// Its distance from `from`.
    pub distance: f64,
}

/// The curve `c` with its control points carried into the world by
/// `world` (NURBS are affine invariant: the same curve, in world units, so
/// lengths and distances are the world's).
pub fn world_curve(
    c: &hedra_geom::NurbsCurve,
    world: glam::DMat4,
) -> Option<hedra_geom::NurbsCurve> {
    hedra_geom::NurbsCurve::new(
        c.degree(),
        c.knots().to_vec(),
        c.points()
            .iter()
            .map(|&p| world.transform_point3(p))
            .collect(),
        c.weights().to_vec(),
    )
    .ok()
}

/// The convex hull of each Bézier segment's control polygon (the curve
/// stays inside it: seed 001), its outline in alternating colours.
fn draw_segment_hulls(
    c: &hedra_geom::NurbsCurve,
    to_world: &dyn Fn(DVec3) -> Vec3,
    gizmos: &mut Gizmos<AxisGizmos>,
) {
    use hedra_geom::curves::hull::{ControlHull, segment_hulls};
    let Ok(hulls) = segment_hulls(c) else { return };
    for (i, segment) in hulls.iter().enumerate() {
        let colour = if i % 2 == 0 {
            Color::srgba(0.55, 1.0, 0.55, 0.7)
        } else {
            Color::srgba(1.0, 0.6, 0.9, 0.7)
        };
        let mut closed_loop = |points: Vec<DVec3>| {
            gizmos.linestrip(
                points.iter().chain(points.first()).map(|&p| to_world(p)),
                colour,
            );
        };
        match &segment.hull {
            ControlHull::Point(_) => {}
            ControlHull::Segment([a, b]) => gizmos.line(to_world(*a), to_world(*b), colour),
            ControlHull::Polygon { vertices, .. } => closed_loop(vertices.clone()),
            ControlHull::Polyhedron { vertices, faces } => {
                for face in faces {
                    closed_loop(face.iter().map(|&v| vertices[v]).collect());
                }
            }
        }
    }
}

/// Finds the closest point of the active curve to the pointer each frame
/// while [`CurveAnalysis::closest`] is on, and draws it.
pub(crate) fn closest_point_to_pointer(
    mut analysis: ResMut<CurveAnalysis>,
    selection: Res<Selection>,
    state: Res<DocState>,
    viewport: hedra_scene::ViewportPointer,
    mut gizmos: Gizmos<AxisGizmos>,
) {
    let (window, camera) = (viewport.window(), viewport.camera());
    let found = if analysis.closest {
        find_closest(&selection, &state, window, camera)
    } else {
        None
    };
    if analysis.closest_found != found {
        analysis.closest_found = found;
    }
    if let Some(c) = found {
        gizmos.line(c.from.as_vec3(), c.at.as_vec3(), Color::WHITE);
        gizmos.sphere(
            Isometry3d::from_translation(c.at.as_vec3()),
            (c.distance.max(0.05) * 0.05) as f32,
            Color::WHITE,
        );
    }
}

fn find_closest(
    selection: &Selection,
    state: &DocState,
    window: &Window,
    (cam, cam_t): (&Camera, &GlobalTransform),
) -> Option<ClosestPoint> {
    use hedra_geom::curves::Curve;
    let id = selection.active()?;
    let doc = &state.session.doc;
    let NodeContent::Curve(c) = &doc.node(id)?.content else {
        return None;
    };
    let curve = world_curve(c.nurbs(), doc.world_matrix(id))?;
    let (o, d) = hedra_scene::camera_ray(cam, cam_t, window.cursor_position()?)?;
    let middle = curve.points().iter().sum::<DVec3>() / curve.points().len() as f64;
    let normal = (cam_t.rotation() * Vec3::NEG_Z).as_dvec3();
    let denom = d.dot(normal);
    if denom.abs() < 1e-12 {
        return None;
    }
    let from = o + d * ((middle - o).dot(normal) / denom);
    let t = hedra_geom::curves::analysis::closest_parameter(&curve, from);
    let at = curve.point(t);
    Some(ClosestPoint {
        from,
        t,
        at,
        distance: at.distance(from),
    })
}

impl Default for CurveAnalysis {
    fn default() -> Self {
        CurveAnalysis {
            comb: false,
            comb_scale: 0.3,
            colour_by_curvature: false,
            frame: false,
            at: 0.5,
            closest: false,
            closest_found: None,
            joints: false,
            hulls: false,
        }
    }
}

/// Draws the active curve's analysis overlays: curvature comb, colour by
/// curvature, and the Frenet frame (tangent red, normal green, binormal
/// blue) with the osculating circle at a moving point.
pub(crate) fn draw_curve_analysis(
    analysis: Res<CurveAnalysis>,
    selection: Res<Selection>,
    state: Res<DocState>,
    shown: hedra_scene::Shown,
    mut gizmos: Gizmos<AxisGizmos>,
) {
    use hedra_geom::curves::Curve;
    use hedra_geom::curves::analysis::{curvature, frenet_frame, osculating_circle};
    if !(analysis.comb || analysis.frame || analysis.colour_by_curvature || analysis.hulls) {
        return;
    }
    let Some(id) = selection.active() else { return };
    let doc = &state.session.doc;
    let Some(NodeContent::Curve(content)) = &shown.shape(id) else {
        return;
    };
    let c = content.nurbs();
    let world = doc.world_matrix(id);
    let to_world = |p: DVec3| world.transform_point3(p).as_vec3();
    let (a, b) = c.domain();
    let samples = 300;
    let ts: Vec<f64> = (0..=samples)
        .map(|i| a + (b - a) * i as f64 / samples as f64)
        .collect();
    let ks: Vec<f64> = ts.iter().map(|&t| curvature(&**c, t)).collect();
    let k_max = ks.iter().copied().fold(1e-12, f64::max);
    if analysis.colour_by_curvature {
        for (w, k) in ts.windows(2).zip(&ks) {
            let x = (k / k_max) as f32;
            let colour = Color::srgb(x, 0.2, 1.0 - x);
            gizmos.line(to_world(c.point(w[0])), to_world(c.point(w[1])), colour);
        }
    }
    if analysis.hulls {
        draw_segment_hulls(c, &to_world, &mut gizmos);
    }
    if analysis.comb {
        let mut tips = Vec::with_capacity(ts.len());
        for (&t, &k) in ts.iter().zip(&ks) {
            let p = c.point(t);
            // The comb points away from the centre of curvature.
            let tip = match frenet_frame(&**c, t) {
                Some([_, normal, _]) => p - normal * k * analysis.comb_scale,
                None => p,
            };
            if tips.len() % 3 == 0 {
                gizmos.line(to_world(p), to_world(tip), Color::srgba(0.4, 0.9, 1.0, 0.6));
            }
            tips.push(to_world(tip));
        }
        gizmos.linestrip(tips, Color::srgb(0.4, 0.9, 1.0));
    }
    if analysis.frame {
        let t = a + (b - a) * analysis.at.clamp(0.0, 1.0);
        let p = c.point(t);
        let size = hedra_scene::extent(c.points()) * 0.15;
        gizmos.sphere(
            Isometry3d::from_translation(to_world(p)),
            (size * 0.08) as f32,
            Color::WHITE,
        );
        if let Some([tangent, normal, binormal]) = frenet_frame(&**c, t) {
            for (v, colour) in [
                (tangent, Color::srgb(1.0, 0.25, 0.25)),
                (normal, Color::srgb(0.3, 1.0, 0.3)),
                (binormal, Color::srgb(0.35, 0.5, 1.0)),
            ] {
                gizmos.arrow(to_world(p), to_world(p + v * size), colour);
            }
        }
        if let Some((centre, radius)) = osculating_circle(&**c, t)
            && radius < 1e4 * hedra_scene::extent(c.points())
            && let Some([tangent, normal, _]) = frenet_frame(&**c, t)
        {
            let circle: Vec<Vec3> = (0..=96)
                .map(|i| {
                    let angle = std::f64::consts::TAU * i as f64 / 96.0;
                    to_world(centre + radius * (angle.cos() * tangent + angle.sin() * normal))
                })
                .collect();
            gizmos.linestrip(circle, Color::srgba(1.0, 0.85, 0.3, 0.8));
        }
    }
}

/// The analysis overlays of the active surface (seed 002's exercise): a
/// planar section and a moving domain point.
#[derive(Resource, Debug, Clone, PartialEq)]
pub struct SurfaceAnalysis {
    /// Draw the planar section: the plane's outline and where it cuts the surface.
    pub section: bool,
    /// The section plane's normal axis (0 = X, 1 = Y, 2 = Z, local space).
    pub section_axis: usize,
    /// Where the plane is, as a fraction of the control net's extent.
    pub section_at: f64,
    /// Draw the moving domain point: the point at (`u`, `v`) with its normal
    /// and the two iso-parameter curves through it.
    pub domain_point: bool,
    /// The moving point's u parameter, as a fraction of the u domain (0 to 1).
    pub u: f64,
    /// The moving point's v parameter, as a fraction of the v domain (0 to 1).
    pub v: f64,
}

impl Default for SurfaceAnalysis {
    fn default() -> Self {
        SurfaceAnalysis {
            section: false,
            section_axis: 1,
            section_at: 0.5,
            domain_point: false,
            u: 0.5,
            v: 0.5,
        }
    }
}

/// What the surface analysis drew this frame, world space (for tests and
/// readers of the overlay).
#[derive(Resource, Debug, Clone, Default, PartialEq)]
pub struct SurfaceAnalysisShown {
    /// Each selected surface's planar-section segments.
    pub sections: Vec<(NodeId, Vec<[DVec3; 2]>)>,
    /// Each selected surface's moving domain point and unit normal there.
    pub points: Vec<(NodeId, DVec3, DVec3)>,
}

/// The moving domain point's barycentric coordinates on a Bézier
/// triangle for the panel's (u, v) fractions: u runs from the edge
/// opposite the first corner to it, v shares the rest between the other
/// two corners, so u = const and v = const are the iso-lines drawn.
pub fn triangle_domain_point(u: f64, v: f64) -> DVec3 {
    let (u, v) = (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
    DVec3::new(u, (1.0 - u) * v, (1.0 - u) * (1.0 - v))
}

/// Draws, for every selected surface (NURBS patches and Bézier triangles
/// alike), the planar section — one plane through all of them in world
/// space, so a section runs on across a joint — and the moving domain
/// point with its two iso-parameter curves and its normal.
pub(crate) fn draw_surface_analysis(
    analysis: Res<SurfaceAnalysis>,
    selection: Res<Selection>,
    state: Res<DocState>,
    mut gizmos: Gizmos<AxisGizmos>,
    mut shown: ResMut<SurfaceAnalysisShown>,
    mut tessellated: Local<
        Vec<(
            std::sync::Arc<hedra_doc::SurfaceShape>,
            hedra_geom::surfaces::tessellate::SurfaceMesh,
        )>,
    >,
) {
    use hedra_geom::surfaces::Surface;
    shown.sections.clear();
    shown.points.clear();
    if !(analysis.section || analysis.domain_point) {
        return;
    }
    let doc = &state.session.doc;
    let mut surfaces: Vec<(NodeId, std::sync::Arc<hedra_doc::SurfaceShape>, glam::DMat4)> =
        selection
            .nodes
            .iter()
            .filter_map(|&id| match doc.node(id).map(|n| &n.content) {
                Some(NodeContent::Surface(shape)) => {
                    Some((id, shape.clone(), doc.world_matrix(id)))
                }
                _ => None,
            })
            .collect();
    surfaces.sort_by_key(|(id, ..)| *id);
    if surfaces.is_empty() {
        return;
    }
    let world_points: Vec<DVec3> = surfaces
        .iter()
        .flat_map(|(_, s, m)| s.control_points().iter().map(|p| m.transform_point3(*p)))
        .collect();
    let size = hedra_scene::extent(&world_points);
    if analysis.section {
        let (lo, hi) = world_points
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        let axis = analysis.section_axis.min(2);
        let normal = [DVec3::X, DVec3::Y, DVec3::Z][axis];
        let origin = lo.lerp(hi, analysis.section_at.clamp(0.0, 1.0)) * normal
            + (lo + hi) / 2.0 * (DVec3::ONE - normal);
        // The plane: a square a little larger than the nets.
        let half = (hi - lo).max_element() * 0.6;
        let (a, b) = match axis {
            0 => (DVec3::Y, DVec3::Z),
            1 => (DVec3::X, DVec3::Z),
            _ => (DVec3::X, DVec3::Y),
        };
        let corners = [
            (-1.0, -1.0),
            (1.0, -1.0),
            (1.0, 1.0),
            (-1.0, 1.0),
            (-1.0, -1.0),
        ]
        .map(|(x, y)| (origin + half * (x * a + y * b)).as_vec3());
        gizmos.linestrip(corners, Color::srgba(0.6, 0.8, 1.0, 0.6));
        // Tessellated once per shape, not every frame the section is drawn
        // (the cache holds the shapes, so their identity cannot be reused).
        let fresh = tessellated.len() != surfaces.len()
            || tessellated
                .iter()
                .zip(&surfaces)
                .any(|((k, _), (_, s, _))| !std::sync::Arc::ptr_eq(k, s));
        if fresh {
            *tessellated = surfaces
                .iter()
                .map(|(_, s, _)| {
                    let tol = hedra_scene::VIEW_TOLERANCE * hedra_scene::extent(s.control_points());
                    let (positions, normals, triangles) = s.tessellate(tol);
                    let params = vec![(0.0, 0.0); positions.len()];
                    let mesh = hedra_geom::surfaces::tessellate::SurfaceMesh {
                        positions,
                        normals,
                        params,
                        triangles,
                    };
                    (s.clone(), mesh)
                })
                .collect();
        }
        for ((_, mesh), (id, _, world)) in tessellated.iter().zip(&surfaces) {
            let mut placed = mesh.clone();
            for p in &mut placed.positions {
                *p = world.transform_point3(*p);
            }
            let cut = hedra_geom::surfaces::tessellate::plane_section(&placed, origin, normal);
            for [p, q] in &cut {
                gizmos.line(p.as_vec3(), q.as_vec3(), Color::srgb(1.0, 0.3, 0.9));
            }
            shown.sections.push((*id, cut));
        }
    }
    if analysis.domain_point {
        let arrow = size * 0.12;
        for (id, shape, world) in &surfaces {
            let to_world = |p: DVec3| world.transform_point3(p).as_vec3();
            let (iso_u, iso_v, p, n): (Vec<Vec3>, Vec<Vec3>, DVec3, DVec3) = match &**shape {
                hedra_doc::SurfaceShape::Nurbs(s) => {
                    let ((u0, u1), (v0, v1)) = s.domain();
                    let u = u0 + (u1 - u0) * analysis.u.clamp(0.0, 1.0);
                    let v = v0 + (v1 - v0) * analysis.v.clamp(0.0, 1.0);
                    let e = s.evaluate(u, v);
                    (
                        (0..=100)
                            .map(|k| to_world(s.point(u, v0 + (v1 - v0) * k as f64 / 100.0)))
                            .collect(),
                        (0..=100)
                            .map(|k| to_world(s.point(u0 + (u1 - u0) * k as f64 / 100.0, v)))
                            .collect(),
                        e.p,
                        e.normal(),
                    )
                }
                hedra_doc::SurfaceShape::Triangle(t) => {
                    let at = |u: f64, v: f64| t.evaluate(triangle_domain_point(u, v));
                    let bary = triangle_domain_point(analysis.u, analysis.v);
                    // The normal from two directional derivatives (seed 001).
                    let du = t.directional_derivative(bary, DVec3::new(1.0, -0.5, -0.5));
                    let dv = t.directional_derivative(bary, DVec3::new(0.0, 1.0, -1.0));
                    (
                        (0..=100)
                            .map(|k| to_world(at(analysis.u, k as f64 / 100.0)))
                            .collect(),
                        (0..=100)
                            .map(|k| to_world(at(k as f64 / 100.0, analysis.v)))
                            .collect(),
                        t.evaluate(bary),
                        du.cross(dv).normalize_or_zero(),
                    )
                }
            };
            gizmos.linestrip(iso_u, Color::srgb(1.0, 0.85, 0.3));
            gizmos.linestrip(iso_v, Color::srgb(0.4, 1.0, 0.5));
            let normal = world.transform_vector3(n).normalize_or_zero();
            shown.points.push((*id, world.transform_point3(p), normal));
            gizmos.sphere(
                Isometry3d::from_translation(to_world(p)),
                (arrow * 0.1) as f32,
                Color::WHITE,
            );
            gizmos.arrow(
                to_world(p),
                (world.transform_point3(p) + normal * arrow).as_vec3(),
                Color::srgb(0.35, 0.5, 1.0),
            );
        }
    }
}

/// The frames a selected sweep made from curves carries its profile in,
/// at its stations: the first normal axis red, the second green, and a
/// ring where the frame flips (the Frenet frame at an inflection of the
/// rail: the profile turns half a turn there).
pub(crate) fn draw_sweep_frames(
    selection: Res<Selection>,
    state: Res<DocState>,
    mut gizmos: Gizmos<AxisGizmos>,
) {
    let Some(id) = selection.active() else { return };
    let doc = &state.session.doc;
    let Some(found) = doc.sweep_frames(id) else {
        return;
    };
    let size = found
        .frames
        .windows(2)
        .map(|w| w[0].origin.distance(w[1].origin))
        .fold(0.0, f64::max)
        .max(1e-3)
        * 0.8;
    for (k, f) in found.frames.iter().enumerate() {
        let o = f.origin.as_vec3();
        gizmos.line(
            o,
            (f.origin + f.normal * size).as_vec3(),
            Color::srgb(0.95, 0.3, 0.3),
        );
        gizmos.line(
            o,
            (f.origin + f.binormal * size).as_vec3(),
            Color::srgb(0.3, 0.9, 0.4),
        );
        if found.flips.contains(&k) {
            gizmos.circle(
                Isometry3d::new(o, Quat::from_rotation_arc(Vec3::Z, f.tangent.as_vec3())),
                (size * 1.2) as f32,
                Color::srgb(1.0, 0.2, 0.9),
            );
        }
    }
}
