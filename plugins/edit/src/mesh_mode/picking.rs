//! Which vertex, edge or face is under the cursor, and where points land on screen.

use super::*;

/// The parameter `t` of the point `origin + direction * t` of a line nearest
/// to a ray (closest points of two lines: Ericson, *Real-Time Collision
/// Detection*, 5.1.8). `None` when they are within about 6° of parallel,
/// where the nearest point runs off too fast to follow.
pub(super) fn line_parameter_nearest_ray(
    (origin, direction): (DVec3, DVec3),
    (ray_origin, ray_direction): (DVec3, DVec3),
) -> Option<f64> {
    let w = origin - ray_origin;
    let (a, b, c) = (
        direction.dot(direction),
        direction.dot(ray_direction),
        ray_direction.dot(ray_direction),
    );
    let denom = a * c - b * b;
    (denom > 1e-2 * a * c).then(|| (b * ray_direction.dot(w) - c * direction.dot(w)) / denom)
}

/// Screen distance (logical pixels) within which a vertex or edge is picked.
pub(super) const PICK_RADIUS: f32 = 12.0;

/// The element under the cursor: vertices and edges by screen distance,
/// faces by ray.
pub fn element_under_cursor(
    kind: ElementKind,
    mesh: &HalfEdgeMesh,
    world: DMat4,
    window: &Window,
    camera: &Camera,
    camera_transform: &GlobalTransform,
) -> Option<ElementHit> {
    let cursor = window.cursor_position()?;
    let screen = |p: DVec3| {
        camera
            .world_to_viewport(camera_transform, world.transform_point3(p).as_vec3())
            .ok()
    };
    // Vertices and edges hidden behind the surface are not candidates.
    let inv = world.inverse();
    let eye = inv.transform_point3(camera_transform.translation().as_dvec3());
    let visible = |p: DVec3| hedra_geom::query::is_visible_from(mesh, eye, p);
    // Nearest on screen first; the first unhidden candidate wins.
    let nearest_visible = |mut candidates: Vec<(ElementHit, f32, Vec<DVec3>)>| {
        candidates.sort_by(|a, b| a.1.total_cmp(&b.1));
        candidates
            .into_iter()
            .find(|(_, _, probes)| probes.iter().any(|&p| visible(p)))
            .map(|(hit, _, _)| hit)
    };
    match kind {
        ElementKind::Vertex => nearest_visible(
            mesh.vertices()
                .filter_map(|v| {
                    let d = screen(mesh.position(v))?.distance(cursor);
                    (d <= PICK_RADIUS).then(|| (ElementHit::Vertex(v), d, vec![mesh.position(v)]))
                })
                .collect(),
        ),
        ElementKind::Edge => nearest_visible(
            mesh.edges()
                .filter_map(|e| {
                    let [a, b] = mesh.edge_vertices(e);
                    let (sa, sb) = (screen(mesh.position(a))?, screen(mesh.position(b))?);
                    let d = point_segment_distance(cursor, sa, sb);
                    (d <= PICK_RADIUS).then(|| {
                        let (pa, pb) = (mesh.position(a), mesh.position(b));
                        let probes = [0.25, 0.5, 0.75].map(|s| pa.lerp(pb, s)).to_vec();
                        (ElementHit::Edge(e), d, probes)
                    })
                })
                .collect(),
        ),
        ElementKind::Face => {
            let (o, d) = hedra_scene::camera_ray(camera, camera_transform, cursor)?;
            hedra_geom::query::ray_cast(mesh, inv.transform_point3(o), inv.transform_vector3(d))
                .map(|(f, _)| ElementHit::Face(f))
        }
    }
}

/// A picked element.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum ElementHit {
    /// A vertex of the edited mesh.
    Vertex(VertexId),
    /// An edge of the edited mesh.
    Edge(EdgeId),
    /// A face of the edited mesh.
    Face(FaceId),
}

pub(super) fn point_segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

/// A mesh-space point on screen (logical pixels), if in front of the camera.
pub(super) fn camera_point(
    cam: &Camera,
    cam_t: &GlobalTransform,
    world: DMat4,
    p: DVec3,
) -> Option<Vec2> {
    cam.world_to_viewport(cam_t, world.transform_point3(p).as_vec3())
        .ok()
}

#[cfg(test)]
mod tests {
    use super::line_parameter_nearest_ray;
    use bevy::math::DVec3;

    #[test]
    fn nearest_point_on_a_line_to_a_ray() {
        // The Y axis scaled by 2 (t counts half units) and a ray along -X at height 3.
        let line = (DVec3::ZERO, DVec3::new(0.0, 2.0, 0.0));
        let ray = (DVec3::new(5.0, 3.0, 1.0), DVec3::new(-1.0, 0.0, 0.0));
        let t = line_parameter_nearest_ray(line, ray).unwrap();
        assert!((t - 1.5).abs() < 1e-12, "{t}");
        // Looking straight down the line gives nothing to follow.
        let along = (DVec3::new(0.0, 9.0, 0.0), DVec3::new(0.01, -1.0, 0.0));
        assert_eq!(line_parameter_nearest_ray(line, along), None);
    }
}
