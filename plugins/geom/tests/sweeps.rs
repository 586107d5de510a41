//! Tests of the sweeps: revolve, extrude, caps, sweep frames, sweep2,
//! loft and the meshes made from them.

use glam::DMat4;
use glam::DVec3;
use hedra_geom::curves::{Curve, NurbsCurve};
use hedra_geom::surfaces::sweeps::*;
use hedra_geom::surfaces::{NurbsSurface, Surface};
use std::f64::consts::TAU;

fn line(a: DVec3, b: DVec3) -> NurbsCurve {
    NurbsCurve::clamped(1, vec![a, b]).unwrap()
}

/// The unit-speed-free circle of `radius` about `center` in the plane
/// with normal `n` (the kernel's XZ circle turned onto it).
fn circle_in(center: DVec3, radius: f64, n: DVec3) -> NurbsCurve {
    let rot = glam::DQuat::from_rotation_arc(DVec3::Y, n.normalize());
    let m = DMat4::from_rotation_translation(rot, center);
    NurbsCurve::circle(DVec3::ZERO, radius)
        .transformed(&m)
        .unwrap()
}

fn grid_samples(s: &NurbsSurface, n: usize) -> Vec<(f64, f64)> {
    let ((u0, u1), (v0, v1)) = s.domain();
    (0..n)
        .flat_map(|i| {
            (0..n).map(move |j| {
                (
                    u0 + (u1 - u0) * i as f64 / (n - 1) as f64,
                    v0 + (v1 - v0) * j as f64 / (n - 1) as f64,
                )
            })
        })
        .collect()
}

#[test]
fn a_revolved_circle_is_an_exact_torus() {
    // Minor circle of radius 0.5 centred 2 from the Z axis, in the XZ plane.
    let minor = circle_in(DVec3::new(2.0, 0.0, 0.0), 0.5, DVec3::Y);
    let axis = Axis {
        origin: DVec3::ZERO,
        direction: DVec3::Z,
    };
    let torus = revolve(&minor, axis, TAU, 0.0).unwrap();
    let mut worst: f64 = 0.0;
    for (u, v) in grid_samples(&torus, 100) {
        let p = torus.point(u, v);
        // Distance to the axis circle (radius 2 in the XY plane).
        let rho = p.x.hypot(p.y);
        let d = ((rho - 2.0).powi(2) + p.z * p.z).sqrt();
        worst = worst.max((d - 0.5).abs());
    }
    assert!(worst < 1e-12, "off the torus by {worst}");
    // Four arcs around: 9 control points across u.
    assert_eq!(torus.size(), (9, 9));
}

#[test]
fn revolving_a_segment_makes_an_exact_cone_about_any_axis() {
    let axis = Axis {
        origin: DVec3::new(1.0, 2.0, 3.0),
        direction: DVec3::new(1.0, 1.0, 0.0),
    };
    let d = axis.direction.normalize();
    let apex = axis.origin + d * 2.0;
    let base = axis.origin + d.any_orthonormal_vector() * 1.5;
    let cone = revolve(&line(base, apex), axis, 200f64.to_radians(), 0.0).unwrap();
    // A 200° turn takes three arcs.
    assert_eq!(cone.size().0, 7);
    for (u, v) in grid_samples(&cone, 100) {
        let p = cone.point(u, v);
        let h = (p - axis.origin).dot(d);
        let r = ((p - axis.origin) - d * h).length();
        // Radius falls linearly from 1.5 at h = 0 to 0 at h = 2.
        assert!(
            (r - 1.5 * (1.0 - h / 2.0)).abs() < 1e-12,
            "{p}: r {r} at h {h}"
        );
    }
    // The end of the turn is the segment turned by 200°.
    let ((_, u1), _) = cone.domain();
    let end = cone.point(u1, 0.0);
    // (Turned right-handed about the axis, by glam's rotation.)
    let turn = glam::DQuat::from_axis_angle(d, 200f64.to_radians());
    let expected = axis.origin + turn * (base - axis.origin);
    assert!(end.distance(expected) < 1e-12);
}

#[test]
fn revolve_refuses_a_zero_axis_and_angle_by_name() {
    let l = line(DVec3::X, DVec3::new(1.0, 1.0, 0.0));
    let zero = Axis {
        origin: DVec3::ZERO,
        direction: DVec3::ZERO,
    };
    assert_eq!(
        revolve(&l, zero, 1.0, 0.0).unwrap_err(),
        SweepError::ZeroVector { what: "the axis" }
    );
    let y = Axis {
        origin: DVec3::ZERO,
        direction: DVec3::Y,
    };
    assert!(matches!(
        revolve(&l, y, 0.0, 0.0),
        Err(SweepError::BadAngle { .. })
    ));
    assert!(matches!(
        revolve(&l, y, 7.0, 0.0),
        Err(SweepError::BadAngle { .. })
    ));
    // With a pitch, two turns are a screw.
    assert!(revolve(&l, y, 2.0 * TAU, 1.0).is_ok());
}

#[test]
fn a_screw_rises_by_its_pitch_per_turn_and_stays_near_the_helix() {
    let l = line(DVec3::new(1.0, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0));
    let y = Axis {
        origin: DVec3::ZERO,
        direction: DVec3::Y,
    };
    let s = revolve(&l, y, 2.0 * TAU, 0.5).unwrap();
    let ((u0, u1), _) = s.domain();
    let mut worst: f64 = 0.0;
    for k in 0..=1000 {
        let u = u0 + (u1 - u0) * k as f64 / 1000.0;
        let p = s.point(u, 0.0);
        // On the cylinder of radius 1 exactly; the rise follows the angle.
        assert!((p.x.hypot(p.z) - 1.0).abs() < 1e-12);
        let turned = (-p.z).atan2(p.x).rem_euclid(TAU);
        let e = (p.y - 0.5 * turned / TAU) / 0.5;
        worst = worst.max((e - e.round()).abs() * 0.5);
    }
    assert!(worst < 6.5e-4 * 0.5, "{worst}");
    assert!((s.point(u1, 0.0).y - 1.0).abs() < 1e-12);
}

#[test]
fn an_extruded_circle_is_an_exact_cylinder() {
    let c = circle_in(DVec3::ZERO, 1.25, DVec3::Z);
    let cyl = extrude(&c, DVec3::new(0.0, 0.0, 3.0)).unwrap();
    for (u, v) in grid_samples(&cyl, 100) {
        let p = cyl.point(u, v);
        assert!((p.x.hypot(p.y) - 1.25).abs() < 1e-12);
        assert!((p.z - 3.0 * v).abs() < 1e-12);
    }
    assert_eq!(
        extrude(&c, DVec3::ZERO).unwrap_err(),
        SweepError::ZeroVector {
            what: "the extrusion vector"
        }
    );
}

#[test]
fn a_capped_extrusion_is_a_closed_genus_0_mesh() {
    let c = circle_in(DVec3::ZERO, 1.0, DVec3::Y);
    let m = extrude_mesh(&c, DVec3::Y * 2.0, 3, 16, true).unwrap();
    m.validate().unwrap();
    let stats = m.stats();
    assert!(stats.closed);
    assert_eq!(stats.genus, Some(0));
    // 16 around × 4 rings; 16 × 3 quads + 2 caps.
    assert_eq!((m.vertex_count(), m.face_count()), (64, 50));
    // Outwards: positive volume near π r² h.
    let vol = m.volume();
    // The prism over the sampled 16-gon (XZ plane) of height 2.
    let (params, _) = profile_parameters(&c, 16);
    let ring = c.points_at(&params);
    let area: f64 = (0..16)
        .map(|k| {
            let (a, b) = (ring[k], ring[(k + 1) % 16]);
            (a.z * b.x - a.x * b.z) / 2.0
        })
        .sum();
    let prism = area.abs() * 2.0;
    assert!((vol - prism).abs() < 1e-12, "{vol}");
}

#[test]
fn caps_refuse_open_and_non_planar_profiles_by_name() {
    let open =
        NurbsCurve::clamped(2, vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 0.0, 1.0)]).unwrap();
    assert!(matches!(
        extrude_mesh(&open, DVec3::Y, 1, 8, true),
        Err(SweepError::OpenProfile { .. })
    ));
    let bent = NurbsCurve::periodic(
        1,
        vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 0.5, 1.0), DVec3::Z],
        vec![1.0; 4],
    )
    .unwrap();
    let err = extrude_mesh(&bent, DVec3::Y, 1, 8, true).unwrap_err();
    assert!(matches!(err, SweepError::NotPlanar { .. }), "{err}");
    assert!(err.to_string().starts_with("caps need a planar profile"));
    // Without caps both are fine.
    extrude_mesh(&open, DVec3::Y, 1, 8, false)
        .unwrap()
        .validate()
        .unwrap();
}

#[test]
fn a_capped_partial_revolution_is_genus_0_and_a_full_one_a_torus() {
    let minor = circle_in(DVec3::new(2.0, 0.0, 0.0), 0.5, DVec3::Z);
    let y = Axis {
        origin: DVec3::ZERO,
        direction: DVec3::Y,
    };
    let part = revolve_mesh(&minor, y, 270f64.to_radians(), 0.0, 12, 16, true).unwrap();
    part.validate().unwrap();
    let s = part.stats();
    assert!(s.closed);
    assert_eq!(s.genus, Some(0));
    assert_eq!(part.face_count(), 12 * 16 + 2);
    let full = revolve_mesh(&minor, y, TAU, 0.0, 24, 16, true).unwrap();
    full.validate().unwrap();
    assert_eq!(full.stats().genus, Some(1));
    assert_eq!(full.vertex_count(), 24 * 16);
    // Every vertex lies on the torus.
    for v in full.vertices() {
        let p = full.position(v);
        let d = ((p.x.hypot(p.z) - 2.0).powi(2) + p.y * p.y).sqrt();
        assert!((d - 0.5).abs() < 1e-12, "{p}");
    }
}

#[test]
fn a_half_circle_revolved_shares_its_poles() {
    let half = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
        vec![
            DVec3::new(0.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ],
        vec![
            1.0,
            std::f64::consts::FRAC_1_SQRT_2,
            1.0,
            std::f64::consts::FRAC_1_SQRT_2,
            1.0,
        ],
    )
    .unwrap();
    let y = Axis {
        origin: DVec3::ZERO,
        direction: DVec3::Y,
    };
    let ball = revolve_mesh(&half, y, TAU, 0.0, 16, 8, false).unwrap();
    ball.validate().unwrap();
    let s = ball.stats();
    assert!(s.closed);
    assert_eq!(s.genus, Some(0));
    // 7 rings of 16 plus two poles; triangle fans at the poles.
    assert_eq!(ball.vertex_count(), 7 * 16 + 2);
    assert_eq!(ball.face_count(), 8 * 16);
}

/// A helix of radius `r` about Z rising `h` per turn, `turns` turns, as
/// a cubic B-spline through many points (close to the helix).
fn helix(r: f64, h: f64, turns: f64) -> NurbsCurve {
    let n = 200;
    let pts: Vec<DVec3> = (0..=n)
        .map(|k| {
            let t = turns * TAU * k as f64 / n as f64;
            DVec3::new(r * t.cos(), r * t.sin(), h * t / TAU)
        })
        .collect();
    NurbsCurve::clamped(3, pts).unwrap()
}

#[test]
fn a_circle_swept_along_a_helix_stays_perpendicular_to_it() {
    let rail = helix(3.0, 2.0, 1.5);
    let (a, _) = rail.domain();
    let [p0, d0, _] = rail.derivatives(a);
    let profile = circle_in(p0, 0.4, d0);
    for kind in [FrameKind::RotationMinimizing, FrameKind::Frenet] {
        let options = SweepOptions {
            frame: kind,
            sections: 40,
        };
        let sections = sweep_sections(&profile, &rail, options).unwrap();
        let tube = sweep(&profile, &rail, options).unwrap();
        let params = loft_section_parameters(
            &sections,
            LoftOptions {
                closed: false,
                tightness: Tightness::Normal,
            },
        );
        let (r0, r1) = rail.domain();
        for (k, &v) in params.iter().enumerate() {
            let t = r0 + (r1 - r0) * k as f64 / 39.0;
            let [centre, tangent, _] = rail.derivatives(t);
            let tangent = tangent.normalize();
            for i in 0..50 {
                let p = tube.point(i as f64 / 49.0, v);
                // In the normal plane, at the profile's radius.
                assert!((p - centre).dot(tangent).abs() < 1e-9, "{kind:?} {k}");
                assert!(((p - centre).length() - 0.4).abs() < 1e-9);
            }
        }
        // Between stations the tube stays close to round.
        let mut worst: f64 = 0.0;
        for k in 0..39 {
            let v = (params[k] + params[k + 1]) / 2.0;
            let t = r0 + (r1 - r0) * (k as f64 + 0.5) / 39.0;
            let centre = rail.point(t);
            for i in 0..20 {
                let p = tube.point(i as f64 / 19.0, v);
                worst = worst.max(((p - centre).length() - 0.4).abs());
            }
        }
        assert!(worst < 0.01, "{kind:?}: {worst}");
    }
}

/// A smooth closed rail that is not planar (a saddle-shaped loop, a
/// periodic cubic B-spline), along which the plain double reflection
/// comes back twisted.
fn saddle_loop() -> NurbsCurve {
    let pts: Vec<DVec3> = (0..12)
        .map(|k| {
            let t = TAU * k as f64 / 12.0;
            DVec3::new(3.0 * t.cos(), 2.0 * t.sin(), 1.5 * (2.0 * t).sin())
        })
        .collect();
    NurbsCurve::periodic(3, pts, vec![1.0; 12]).unwrap()
}

#[test]
fn the_rotation_minimising_frame_closes_up_on_a_closed_rail() {
    let rail = saddle_loop();
    assert!(is_smoothly_closed(&rail));
    let (a, b) = rail.domain();
    let params: Vec<f64> = (0..=60).map(|k| a + (b - a) * k as f64 / 60.0).collect();
    let frames = rail_frames(&rail, &params, FrameKind::RotationMinimizing).unwrap();
    let (first, last) = (frames[0], frames[60]);
    assert!(
        first.normal.distance(last.normal) < 1e-9,
        "{first:?} {last:?}"
    );
    // Still a frame: orthonormal, normal across the tangent.
    for f in &frames {
        assert!(f.normal.dot(f.tangent).abs() < 1e-12);
        assert!((f.normal.length() - 1.0).abs() < 1e-12);
    }
    // And the correction is needed: an open piece of the same loop
    // (not the whole of it) is not corrected, and its frame at the
    // seam differs from the start by the holonomy angle.
    let part: Vec<f64> = params[..60].to_vec();
    let open = rail_frames(&rail, &part, FrameKind::RotationMinimizing).unwrap();
    let twist = open[59].normal.angle_between(frames[59].normal);
    assert!(twist > 1e-3, "the saddle loop has holonomy: {twist}");
}

#[test]
fn a_sweep_around_a_closed_rail_is_closed_and_seamless() {
    let rail = saddle_loop();
    let (a, _) = rail.domain();
    let [p0, d0, _] = rail.derivatives(a);
    let profile = circle_in(p0, 0.3, d0);
    let options = SweepOptions {
        frame: FrameKind::RotationMinimizing,
        sections: 30,
    };
    let tube = sweep(&profile, &rail, options).unwrap();
    assert!(is_closed_in_v(&tube));
    let (_, (v0, v1)) = tube.domain();
    for i in 0..=20 {
        let u = i as f64 / 20.0;
        assert!(tube.point(u, v0).distance(tube.point(u, v1)) < 1e-9);
    }
    // As a mesh it is a closed torus-like tube, genus 1, no caps.
    let (us, closed_u) = compatible_parameters(&profile, 16);
    let mesh = surface_mesh(&tube, &us, closed_u, 30, true, false).unwrap();
    mesh.validate().unwrap();
    let stats = mesh.stats();
    assert!(stats.closed);
    assert_eq!(stats.genus, Some(1));
}

#[test]
fn the_frenet_frame_flips_at_an_inflection_and_the_rmf_does_not() {
    // An S in the XY plane, rising a little in Z so the Frenet frame
    // exists everywhere: its curvature changes sign once, in the middle.
    let pts: Vec<DVec3> = (0..=40)
        .map(|k| {
            let t = k as f64 / 40.0;
            DVec3::new(4.0 * t, (TAU * t).sin(), 0.0)
        })
        .collect();
    let rail = NurbsCurve::clamped(3, pts).unwrap();
    let (a, b) = rail.domain();
    // Stations that avoid the inflection at the middle itself.
    let params: Vec<f64> = (0..=20)
        .map(|k| a + (b - a) * (k as f64 + 0.25) / 20.5)
        .collect();
    let frenet = rail_frames(&rail, &params, FrameKind::Frenet).unwrap();
    let rmf = rail_frames(&rail, &params, FrameKind::RotationMinimizing).unwrap();
    let flips = frame_flips(&frenet);
    assert_eq!(flips.len(), 1, "{flips:?}");
    let middle = rail.point(params[flips[0]]).x;
    assert!(
        (middle - 2.0).abs() < 0.3,
        "the flip is at the inflection: {middle}"
    );
    assert!(frame_flips(&rmf).is_empty());
}

#[test]
fn the_rotation_minimising_frame_does_not_twist_on_a_plane_curve() {
    // On a planar rail the RMF's normal keeps its angle to the plane.
    let rail = NurbsCurve::circle(DVec3::ZERO, 2.0);
    let params: Vec<f64> = (0..=20).map(|k| k as f64 / 40.0).collect();
    let frames = rail_frames(&rail, &params, FrameKind::RotationMinimizing).unwrap();
    let first = frames[0].normal.dot(DVec3::Y);
    for f in &frames {
        assert!((f.normal.dot(DVec3::Y) - first).abs() < 1e-6);
        assert!(f.normal.dot(f.tangent).abs() < 1e-12);
    }
    // A straight rail has no Frenet frame.
    let straight = line(DVec3::ZERO, DVec3::X);
    assert!(matches!(
        rail_frames(&straight, &[0.0, 1.0], FrameKind::Frenet),
        Err(SweepError::NoFrenetFrame { .. })
    ));
}

#[test]
fn a_two_rail_sweep_keeps_the_profile_ends_on_both_rails() {
    let r1 = NurbsCurve::clamped(
        2,
        vec![
            DVec3::ZERO,
            DVec3::new(0.0, 0.5, 2.0),
            DVec3::new(0.0, 0.0, 4.0),
        ],
    )
    .unwrap();
    let r2 = NurbsCurve::clamped(
        2,
        vec![
            DVec3::X,
            DVec3::new(2.0, 0.0, 2.0),
            DVec3::new(1.5, 0.0, 4.0),
        ],
    )
    .unwrap();
    let profile =
        NurbsCurve::clamped(2, vec![DVec3::ZERO, DVec3::new(0.5, 0.6, 0.0), DVec3::X]).unwrap();
    let s = sweep2(&profile, [&r1, &r2], 12).unwrap();
    // The surface's u = 0 and u = 1 edges pass through the rails at the stations.
    let sections = sweep2_sections(&profile, [&r1, &r2], 12).unwrap();
    for (k, c) in sections.iter().enumerate() {
        let t = k as f64 / 11.0;
        let (a, b) = c.domain();
        assert!(c.point(a).distance(r1.point(t)) < 1e-12);
        assert!(c.point(b).distance(r2.point(t)) < 1e-12);
    }
    let params = loft_section_parameters(&sections, LoftOptions::default());
    for (k, &v) in params.iter().enumerate() {
        let t = k as f64 / 11.0;
        assert!(s.point(0.0, v).distance(r1.point(t)) < 1e-9);
        assert!(s.point(1.0, v).distance(r2.point(t)) < 1e-9);
    }
}

fn sections() -> Vec<NurbsCurve> {
    vec![
        circle_in(DVec3::ZERO, 1.0, DVec3::Y),
        // A square polyline (degree 1) around the axis.
        NurbsCurve::periodic(
            1,
            vec![
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::new(0.0, 1.0, 1.0),
                DVec3::new(-1.0, 1.0, 0.0),
                DVec3::new(0.0, 1.0, -1.0),
            ],
            vec![1.0; 4],
        )
        .unwrap(),
        circle_in(DVec3::new(0.0, 2.5, 0.0), 0.5, DVec3::Y),
        circle_in(DVec3::new(0.3, 3.5, 0.0), 1.2, DVec3::Y),
    ]
}

#[test]
fn make_compatible_keeps_every_curve_and_shares_knots() {
    let input = sections();
    let out = make_compatible(&input).unwrap();
    for (c, d) in input.iter().zip(&out) {
        assert_eq!(d.knots(), out[0].knots());
        assert_eq!(d.degree(), 2);
        let (a, b) = c.domain();
        for k in 0..=50 {
            let s = k as f64 / 50.0;
            assert!(c.point(a + (b - a) * s).distance(d.point(s)) < 1e-12);
        }
    }
}

#[test]
fn a_loft_passes_through_each_section() {
    let input = sections();
    for tightness in [Tightness::Straight, Tightness::Normal] {
        for closed in [false, true] {
            let options = LoftOptions { closed, tightness };
            let s = loft(&input, options).unwrap();
            let params = loft_section_parameters(&input, options);
            assert_eq!(params.len(), 4);
            for (c, &v) in input.iter().zip(&params) {
                let (a, b) = c.domain();
                for k in 0..=100 {
                    let u = k as f64 / 100.0;
                    let want = c.point(a + (b - a) * u);
                    let got = s.point(u, v);
                    assert!(
                        got.distance(want) < 1e-9,
                        "{tightness:?} closed {closed}: {got} vs {want}"
                    );
                }
            }
        }
    }
    // Loose passes through the ends only, and refuses a single section.
    let loose = loft(
        &input,
        LoftOptions {
            closed: false,
            tightness: Tightness::Loose,
        },
    )
    .unwrap();
    assert!(loose.point(0.0, 0.0).distance(input[0].point(0.0)) < 1e-12);
    assert!(loose.point(0.0, 1.0).distance(input[3].point(0.0)) < 1e-12);
    assert_eq!(
        loft(&input[..1], LoftOptions::default()).unwrap_err(),
        SweepError::TooFewSections {
            what: "a loft",
            needed: 2,
            got: 1
        }
    );
}

#[test]
fn a_planar_cap_of_a_circle_is_its_disc() {
    let c = circle_in(DVec3::new(1.0, 2.0, 3.0), 2.0, DVec3::new(0.0, 1.0, 1.0));
    let cap = planar_cap(&c).unwrap();
    let n = DVec3::new(0.0, 1.0, 1.0).normalize();
    for (u, v) in grid_samples(&cap, 30) {
        let p = cap.point(u, v);
        let rel = p - DVec3::new(1.0, 2.0, 3.0);
        assert!(rel.dot(n).abs() < 1e-12);
        assert!((rel.length() - 2.0 * (1.0 - v)).abs() < 1e-9, "{u} {v}");
    }
}

#[test]
fn nurbs_end_caps_close_an_extrusion_and_a_partial_revolution_facing_out() {
    let circle = circle_in(DVec3::new(2.0, 0.0, 0.0), 0.5, DVec3::Z);
    let tube = extrude(&circle, DVec3::new(0.0, 0.0, 3.0)).unwrap();
    let caps = end_caps(&tube, Along::V).unwrap();
    assert_eq!(caps.len(), 2);
    for (cap, z, outward) in [(&caps[0], 0.0, -DVec3::Z), (&caps[1], 3.0, DVec3::Z)] {
        for (u, v) in grid_samples(cap, 10) {
            let p = cap.point(u, v);
            assert!((p.z - z).abs() < 1e-12);
            assert!(p.distance(DVec3::new(2.0, 0.0, z)) <= 0.5 + 1e-9);
            let n = cap.evaluate(u, v.min(0.9)).normal();
            assert!(n.dot(outward) > 0.999, "{n}");
        }
        // The rim is the tube's end circle.
        let ((a, b), (v0, _)) = cap.domain();
        for k in 0..=16 {
            let p = cap.point(a + (b - a) * k as f64 / 16.0, v0);
            assert!((p.distance(DVec3::new(2.0, 0.0, z)) - 0.5).abs() < 1e-9);
        }
    }
    // A partial revolution of the same circle about Y gets its two
    // end discs; a full one (a torus) none.
    let axis = Axis {
        origin: DVec3::ZERO,
        direction: DVec3::Y,
    };
    let part = revolve(&circle, axis, 1.5, 0.0).unwrap();
    assert_eq!(end_caps(&part, Along::U).unwrap().len(), 2);
    let torus = revolve(&circle, axis, TAU, 0.0).unwrap();
    assert!(end_caps(&torus, Along::U).unwrap().is_empty());
    // An open profile cannot be capped.
    let arc = NurbsCurve::clamped(2, vec![DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y]).unwrap();
    let sheet = extrude(&arc, DVec3::Z).unwrap();
    assert!(matches!(
        end_caps(&sheet, Along::V),
        Err(SweepError::OpenProfile { .. })
    ));
}

#[test]
fn a_nurbs_cap_refuses_a_profile_its_centre_does_not_see() {
    // A C-shaped closed polygon: its centroid lies outside the notch's
    // view of part of the outline.
    let pts = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(4.0, 0.0, 0.0),
        DVec3::new(4.0, 1.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(1.0, 3.0, 0.0),
        DVec3::new(4.0, 3.0, 0.0),
        DVec3::new(4.0, 4.0, 0.0),
        DVec3::new(0.0, 4.0, 0.0),
        DVec3::new(0.0, 0.0, 0.0),
    ];
    let c = NurbsCurve::clamped(1, pts).unwrap();
    assert_eq!(planar_cap(&c), Err(SweepError::NotStarShaped));
}

#[test]
fn a_swept_and_lofted_mesh_validates_with_caps() {
    let rail = helix(3.0, 2.0, 0.75);
    let (a, _) = rail.domain();
    let [p0, d0, _] = rail.derivatives(a);
    let profile = circle_in(p0, 0.4, d0);
    let s = sweep(&profile, &rail, SweepOptions::default()).unwrap();
    let (us, closed) = compatible_parameters(&profile, 12);
    assert!(closed);
    let m = surface_mesh(&s, &us, closed, 20, false, true).unwrap();
    m.validate().unwrap();
    assert!(m.stats().closed);
    assert_eq!(m.stats().genus, Some(0));
    assert_eq!(m.face_count(), 12 * 20 + 2);
    let l = loft(
        &sections(),
        LoftOptions {
            closed: true,
            tightness: Tightness::Normal,
        },
    )
    .unwrap();
    let (us, _) = compatible_parameters(&sections()[0], 16);
    let torus = surface_mesh(&l, &us, true, 24, true, false).unwrap();
    torus.validate().unwrap();
    assert_eq!(torus.stats().genus, Some(1));
}
