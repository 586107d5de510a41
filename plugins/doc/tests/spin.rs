//! Spin and Screw through the command pipeline: the torus of a plane's face,
//! undo and redo, the history labels, and refusals that name the node and
//! the element.

use glam::DVec3;
use hedra_doc::{
    Command, CommandError, EdgeSet, FaceSet, NodeRef, NodeTransform, ProfileSet, Session,
};
use hedra_geom::{ModelingError, Primitive};

fn name(n: &str) -> NodeRef {
    NodeRef::Name(n.into())
}

fn add_plane(s: &mut Session, n: &str) {
    s.execute(&Command::AddPrimitive {
        primitive: Primitive::Plane { size: 1.0 },
        name: Some(n.into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
}

fn torus_spin(node: &str) -> Command {
    Command::Spin {
        node: name(node),
        profile: ProfileSet::Faces(FaceSet::All),
        center: DVec3::new(2.0, 0.0, 0.0),
        axis: DVec3::Z,
        degrees: 360.0,
        steps: 8,
    }
}

#[test]
fn spinning_a_plane_a_full_turn_makes_a_torus_and_undoes() {
    let mut s = Session::new();
    add_plane(&mut s, "Donut");
    let plane = s.doc.clone();
    s.execute(&torus_spin("Donut")).unwrap();
    let mesh = s.doc.find_by_name("Donut").unwrap().content.mesh().unwrap();
    let stats = mesh.stats();
    assert_eq!((stats.vertices, stats.edges, stats.faces), (32, 64, 32));
    assert_eq!(stats.euler_characteristic, 0);
    assert_eq!(stats.genus, Some(1));
    assert!(stats.closed && stats.manifold);
    assert!(mesh.volume() > 0.0, "normals point out");
    let torus = s.doc.clone();
    assert_eq!(s.undo().as_deref(), Some("Spin"));
    assert_eq!(s.doc, plane);
    s.redo();
    assert_eq!(s.doc, torus);
}

#[test]
fn a_screw_of_a_boundary_edge_winds_up_the_axis() {
    let mut s = Session::new();
    add_plane(&mut s, "Coil");
    s.execute(&Command::Screw {
        node: name("Coil"),
        profile: ProfileSet::Edges(EdgeSet::Nearest(DVec3::new(0.5, 0.0, 0.0))),
        center: DVec3::new(1.5, 0.0, 0.0),
        axis: DVec3::Z,
        turns: 2,
        steps: 8,
        pitch: 1.0,
    })
    .unwrap();
    assert_eq!(s.history.done().last().unwrap().label, "Screw");
    let mesh = s.doc.find_by_name("Coil").unwrap().content.mesh().unwrap();
    let stats = mesh.stats();
    assert_eq!(
        (stats.vertices, stats.faces, stats.boundary_loops),
        (36, 17, 1)
    );
    let (lo, hi) = mesh.bounds().unwrap();
    assert!(
        (hi.z - lo.z - 3.0).abs() < 1e-9,
        "two turns of 1 plus the edge: {lo} {hi}"
    );
}

#[test]
fn refusals_name_the_node_and_the_edge_and_change_nothing() {
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: Primitive::Cube { size: 2.0 },
        name: Some("Box".into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    let before = s.clone();
    let e = s
        .execute(&Command::Spin {
            node: name("Box"),
            profile: ProfileSet::Edges(EdgeSet::Ids(vec![0])),
            center: DVec3::ZERO,
            axis: DVec3::Y,
            degrees: 90.0,
            steps: 4,
        })
        .unwrap_err();
    assert!(
        matches!(
            &e,
            CommandError::Modeling {
                error: ModelingError::SpinEdgeNotBoundary { .. },
                ..
            }
        ),
        "{e}"
    );
    let text = e.to_string();
    assert!(
        text.contains("'Box'") && text.contains("e0 has faces on both sides"),
        "{text}"
    );
    let e = s
        .execute(&Command::Spin {
            node: name("Box"),
            profile: ProfileSet::Faces(FaceSet::Ids(vec![0])),
            center: DVec3::ZERO,
            axis: DVec3::ZERO,
            degrees: 90.0,
            steps: 4,
        })
        .unwrap_err();
    assert!(e.to_string().contains("non-zero axis"), "{e}");
    let e = s.execute(&torus_spin("Nowhere")).unwrap_err();
    assert!(e.to_string().contains("Nowhere"), "{e}");
    assert_eq!(s, before);
}
