//! Forward and inverse kinematics of the twelve rotary-axis types.

mod common;
use common::{close, Rng};
use fiveaxis::geometry::wrap_pi;
use fiveaxis::rotary::{Group, Pose, RotaryType};
use nalgebra::Vector3;
use std::f64::consts::PI;

fn same_angle(a: f64, b: f64) -> bool {
    wrap_pi(a - b).abs() < 1e-9
}

#[test]
fn fk_of_every_ik_solution_gives_the_vector_back_and_the_pose_is_among_them() {
    let mut rng = Rng::new(4);
    for t in RotaryType::ALL {
        for _ in 0..2000 {
            let pose = Pose::new(rng.range(-PI, PI), rng.range(-PI, PI));
            let v = t.tool_vector(pose);
            close(v.norm(), 1.0, 1e-15, "unit tool vector");
            let s = t.inverse(&(v * 3.7), None).expect("reachable");
            assert!(!s.singular);
            assert_eq!(s.solutions.len(), 2);
            for sol in &s.solutions {
                assert!(
                    (t.tool_vector(*sol) - v).norm() < 1e-12,
                    "{t}: FK(IK(v)) = v"
                );
            }
            assert!(
                s.solutions
                    .iter()
                    .any(|p| same_angle(p.k, pose.k) && same_angle(p.m, pose.m)),
                "{t}: {pose:?} not among {:?}",
                s.solutions
            );
            // With the true pose as the previous one, continuity picks exactly it.
            let near = t.inverse(&v, Some(pose)).expect("reachable").chosen;
            close(near.k, pose.k, 1e-9, "continuity k");
            close(near.m, pose.m, 1e-9, "continuity m");
        }
    }
}

#[test]
fn continuity_unwraps_whole_turns() {
    let t = RotaryType::parse("CAZ").expect("type");
    let prev = Pose::new(4.0 * PI + 0.3, 0.5);
    let v = t.tool_vector(Pose::new(0.32, 0.52));
    let c = t.inverse(&v, Some(prev)).expect("reachable").chosen;
    close(c.k, 4.0 * PI + 0.32, 1e-9, "k stays on the same turn");
    close(c.m, 0.52, 1e-9, "m");
}

#[test]
fn singular_orientations_along_k_are_detected() {
    for t in RotaryType::ALL {
        let e_k = t.k.axis().unit();
        for sign in [1.0, -1.0] {
            let prev = Pose::new(0.77, 0.1);
            let s = t.inverse(&(e_k * sign), Some(prev)).expect("reachable");
            assert!(s.singular, "{t}");
            assert_eq!(s.solutions.len(), 1);
            close(s.chosen.k, 0.77, 1e-15, "k kept from the previous pose");
            assert!((t.tool_vector(s.chosen) - e_k * sign).norm() < 1e-12);
            // Group I is singular at θm = 0 or π, Group II at θm = ±90°.
            let m = s.solutions[0].m.abs();
            match t.group() {
                Group::I => assert!(m < 1e-12 || (m - PI).abs() < 1e-12),
                Group::II => close(m, PI / 2.0, 1e-12, "Group II pole"),
            }
            close(s.pole_angle, 0.0, 1e-12, "pole angle");
        }
        // Near the pole the solution is still exact, and the pole angle says how near.
        let tilt = Vector3::new(1e-7, 2e-7, 0.0);
        let v = e_k + tilt - e_k * e_k.dot(&tilt);
        let s = t.inverse(&v, None).expect("reachable");
        assert!(!s.singular);
        assert!(s.pole_angle > 0.0 && s.pole_angle < 1e-6);
        for sol in &s.solutions {
            assert!((t.tool_vector(*sol) - v.normalize()).norm() < 1e-12);
        }
    }
}

#[test]
fn zero_and_non_finite_vectors_are_rejected() {
    let t = RotaryType::parse("ABX").expect("type");
    for v in [
        Vector3::zeros(),
        Vector3::new(f64::NAN, 0.0, 1.0),
        Vector3::new(f64::INFINITY, 0.0, 0.0),
    ] {
        let e = t.inverse(&v, None).expect_err("invalid");
        assert_eq!(e.field, "vector");
    }
}
