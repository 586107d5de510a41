//! Selecting elements: click, Shift+click, box (B or a drag), Alt+click loops and rings, A, Alt+A, Ctrl+I, grow, shrink, linked.

use super::*;

/// A left press in edit mode, until release: a click, an Alt+click (loop),
/// or a box drag.
#[derive(Clone, Copy, Debug, Default)]
pub struct Press {
    /// Where the button went down (window coordinates, logical pixels).
    pub start: Vec2,
    /// Alt was held: a click selects the edge loop under the cursor.
    pub alt: bool,
    /// Ctrl was held: with Alt, the edge ring instead of the loop.
    pub ctrl: bool,
    /// Shift was held: add to (or toggle in) the selection instead of replacing it.
    pub shift: bool,
}

pub(super) fn toggle<T: Ord + Copy>(set: &mut BTreeSet<T>, x: T) {
    if !set.remove(&x) {
        set.insert(x);
    }
}

/// Selection in edit mode: click (Shift toggles), drag a box, Alt+click an
/// edge loop, Ctrl+Alt+click an edge ring, A / Alt+A / Ctrl+I, Ctrl+Numpad
/// +/- grow and shrink, L linked under the cursor, Ctrl+L linked to the
/// selection.
#[allow(clippy::too_many_arguments)]
pub fn select_elements(
    buttons: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    gate: Res<InputGate>,
    mut mode: ResMut<EditMode>,
    state: Res<DocState>,
    viewport: hedra_scene::ViewportPointer,
    mut press: Local<Option<Press>>,
    mut b_box: Local<Option<Vec2>>,
    mut status: ResMut<StatusMessage>,
    gizmo: Option<Res<TransformGizmoState>>,
    shading: Res<hedra_scene::ViewportShading>,
    bisect: Res<BisectDrag>,
    knife: Res<KnifeTool>,
) {
    let (window, camera) = (viewport.window(), viewport.camera());
    if !mode.active() || mode.tool.is_some() || bisect.armed || knife.active {
        *press = None;
        *b_box = None;
        mode.box_select = None;
        return;
    }
    let Some(mesh) = edited_mesh(&state, &mode) else {
        return;
    };
    let kind = mode.kind;
    let world = state.session.doc.world_matrix(mode.node.expect("active"));
    let (cam, cam_t) = camera;
    let cursor = window.cursor_position();
    if gate.keyboard_free {
        keyboard_selection(&keys, &mut mode, &mesh, kind, world, window, cam, cam_t);
    }
    // B (Blender): a box from the cursor follows the mouse; a click closes
    // it and adds what it holds; Esc or a right click cancels.
    if gate.keyboard_free
        && crate::bindings::pressed(
            &keys,
            crate::bindings::KeyMode::Edit,
            crate::bindings::Action::BoxSelect,
        )
    {
        *b_box = cursor;
        status.info("Box select: move to the opposite corner and click (Esc cancels)");
    }
    if let Some(start) = *b_box {
        if keys.just_pressed(KeyCode::Escape) || buttons.just_pressed(MouseButton::Right) {
            *b_box = None;
            mode.box_select = None;
            return;
        }
        if let Some(c) = cursor {
            mode.box_select = Some((start, c));
        }
        if !(buttons.just_pressed(MouseButton::Left) && gate.pointer_free) {
            return;
        }
        *b_box = None;
        status.info("Box select");
        *press = Some(Press {
            start,
            alt: false,
            ctrl: false,
            shift: true,
        });
        return;
    }
    if buttons.just_pressed(MouseButton::Left)
        && gate.pointer_free
        && !mode.just_finished
        && !crate::gizmo_has_pointer(gizmo.as_deref())
        && let Some(c) = cursor
    {
        *press = Some(Press {
            start: c,
            alt: alt(&keys),
            ctrl: ctrl(&keys),
            shift: shift(&keys),
        });
    }
    // X-ray and wireframe (Alt+Z, Shift+Z; `hedra_viewport::shading_keys`)
    // see through: box select takes hidden elements too.
    let x_ray = shading.see_through();
    let Some(p) = *press else { return };
    let moved = cursor.is_some_and(|c| c.distance(p.start) > 4.0);
    if buttons.pressed(MouseButton::Left) {
        if moved && !p.alt {
            mode.box_select = cursor.map(|c| (p.start, c));
        }
        return;
    }
    // Released: act once.
    *press = None;
    let boxed = mode.box_select.take();
    let sel = &mut mode.selection;
    if let Some((a, b)) = boxed {
        let (lo, hi) = (a.min(b), a.max(b));
        // Without X-ray only what the surface leaves in sight is taken: a
        // software depth buffer of the mesh at the viewport's size.
        let depth = (!x_ray).then(|| {
            let size = cam
                .logical_viewport_size()
                .unwrap_or(Vec2::new(1280.0, 800.0));
            let model_to_clip =
                cam.clip_from_view().as_dmat4() * cam_t.to_matrix().as_dmat4().inverse() * world;
            hedra_geom::query::DepthBuffer::render(
                &mesh,
                model_to_clip,
                size.x.ceil() as usize,
                size.y.ceil() as usize,
            )
        });
        let seen = |q: DVec3| depth.as_ref().is_none_or(|d| d.is_visible(q));
        let inside = |q: DVec3| {
            camera_point(cam, cam_t, world, q)
                .is_some_and(|s| s.x >= lo.x && s.y >= lo.y && s.x <= hi.x && s.y <= hi.y)
        };
        if !p.shift {
            *sel = ElementSelection::default();
        }
        match kind {
            ElementKind::Vertex => sel.vertices.extend(mesh.vertices().filter(|&v| {
                let p = mesh.position(v);
                inside(p) && seen(p)
            })),
            ElementKind::Edge => sel.edges.extend(mesh.edges().filter(|&e| {
                let [a, b] = mesh.edge_vertices(e).map(|v| mesh.position(v));
                inside(a) && inside(b) && seen(a.lerp(b, 0.5))
            })),
            ElementKind::Face => sel.faces.extend(mesh.faces().filter(|&f| {
                let c = mesh.face_centroid(f);
                inside(c) && seen(c)
            })),
        }
        return;
    }
    if p.alt {
        if moved {
            return; // Alt+drag orbited the camera
        }
        // Loop (Alt) or ring (Ctrl+Alt) through the edge under the cursor.
        let Some(ElementHit::Edge(e)) =
            element_under_cursor(ElementKind::Edge, &mesh, world, window, cam, cam_t)
        else {
            return;
        };
        let edges = if p.ctrl {
            hedra_geom::modeling::edge_ring(&mesh, e)
                .0
                .into_iter()
                .map(|h| h.edge())
                .collect()
        } else {
            hedra_geom::topology::edge_loop(&mesh, e)
        };
        if !p.shift {
            *sel = ElementSelection::default();
        }
        match kind {
            ElementKind::Vertex => sel
                .vertices
                .extend(edges.iter().flat_map(|&e| mesh.edge_vertices(e))),
            ElementKind::Edge => sel.edges.extend(edges),
            ElementKind::Face => sel
                .faces
                .extend(edges.iter().flat_map(|&e| mesh.edge_faces(e)).flatten()),
        }
        return;
    }
    let hit = element_under_cursor(kind, &mesh, world, window, cam, cam_t);
    if !p.shift {
        *sel = ElementSelection::default();
    }
    match hit {
        Some(ElementHit::Vertex(v)) => {
            toggle(&mut sel.vertices, v);
            sel.clicked.retain(|&c| c != v);
            if sel.vertices.contains(&v) {
                sel.clicked.push(v);
            }
        }
        Some(ElementHit::Edge(e)) => toggle(&mut sel.edges, e),
        Some(ElementHit::Face(f)) => toggle(&mut sel.faces, f),
        None => {}
    }
}

#[allow(clippy::too_many_arguments)]
pub(super) fn keyboard_selection(
    keys: &ButtonInput<KeyCode>,
    mode: &mut EditMode,
    mesh: &HalfEdgeMesh,
    kind: ElementKind,
    world: DMat4,
    window: &Window,
    cam: &Camera,
    cam_t: &GlobalTransform,
) {
    let sel = &mut mode.selection;
    use crate::bindings::{Action, KeyMode, pressed};
    let set_from_vertices = |sel: &mut ElementSelection, verts: &BTreeSet<VertexId>| {
        *sel = ElementSelection::from_vertices(kind, mesh, verts);
    };
    let all = pressed(keys, KeyMode::Edit, Action::SelectAll);
    if all || pressed(keys, KeyMode::Edit, Action::SelectNone) {
        *sel = ElementSelection::default();
        if all {
            match kind {
                ElementKind::Vertex => sel.vertices = mesh.vertices().collect(),
                ElementKind::Edge => sel.edges = mesh.edges().collect(),
                ElementKind::Face => sel.faces = mesh.faces().collect(),
            }
        }
    }
    if pressed(keys, KeyMode::Edit, Action::InvertSelection) {
        match kind {
            ElementKind::Vertex => {
                sel.vertices = mesh
                    .vertices()
                    .filter(|v| !sel.vertices.contains(v))
                    .collect()
            }
            ElementKind::Edge => {
                sel.edges = mesh.edges().filter(|e| !sel.edges.contains(e)).collect()
            }
            ElementKind::Face => {
                sel.faces = mesh.faces().filter(|f| !sel.faces.contains(f)).collect()
            }
        }
    }
    let grow = pressed(keys, KeyMode::Edit, Action::GrowSelection);
    let shrink = pressed(keys, KeyMode::Edit, Action::ShrinkSelection);
    if grow || shrink {
        let verts = sel.all_vertices(mesh);
        let next: BTreeSet<VertexId> = if grow {
            verts
                .iter()
                .flat_map(|&v| std::iter::once(v).chain(mesh.vertex_neighbors(v)))
                .collect()
        } else {
            verts
                .iter()
                .copied()
                .filter(|&v| mesh.vertex_neighbors(v).all(|w| verts.contains(&w)))
                .collect()
        };
        set_from_vertices(sel, &next);
    }
    let linked_to_selection = pressed(keys, KeyMode::Edit, Action::SelectLinked);
    if linked_to_selection || pressed(keys, KeyMode::Edit, Action::SelectLinkedUnderPointer) {
        let seeds: Vec<VertexId> = if linked_to_selection {
            sel.all_vertices(mesh).into_iter().collect()
        } else {
            match element_under_cursor(kind, mesh, world, window, cam, cam_t) {
                Some(ElementHit::Vertex(v)) => vec![v],
                Some(ElementHit::Edge(e)) => mesh.edge_vertices(e).to_vec(),
                Some(ElementHit::Face(f)) => mesh.face_vertices(f).collect(),
                None => vec![],
            }
        };
        let mut linked: BTreeSet<VertexId> = hedra_geom::topology::linked_vertices(mesh, seeds)
            .into_iter()
            .collect();
        if !linked_to_selection {
            linked.extend(sel.all_vertices(mesh));
        }
        set_from_vertices(sel, &linked);
    }
}
