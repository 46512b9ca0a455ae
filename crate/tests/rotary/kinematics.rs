//! Forward and inverse kinematics of the twelve rotary-axis types.

use crate::common;

use common::{close, Rng};
use fiveaxis::geometry::wrap_pi;
use fiveaxis::rotary::{Group, Pose, RotaryType};
use nalgebra::Vector3;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

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

/// Unit directions exactly perpendicular to K's axis (its component exactly 0).
fn perpendicular_to_k(t: RotaryType, rng: &mut Rng) -> Vector3<f64> {
    let mut v = rng.direction();
    v[t.k.axis().index()] = 0.0;
    v.normalize()
}

// Found by cargo-mutants: a mutant in `crate/src/rotary.rs` survived every other test.
#[test]
fn every_solution_of_inverse_gives_the_direction_back() {
    let mut rng = Rng::new(77);
    for t in RotaryType::ALL {
        for i in 0..600 {
            let v = if i % 3 == 0 {
                perpendicular_to_k(t, &mut rng)
            } else {
                rng.direction()
            };
            // Any length: the direction is normalised.
            let inv = t.inverse(&(v * rng.range(0.01, 100.0)), None).unwrap();
            assert!(!inv.singular);
            assert_eq!(inv.solutions.len(), 2);
            for s in &inv.solutions {
                let back = t.tool_vector(*s);
                assert!((back - v).norm() < 1e-12, "{t} {v:?}: {s:?} gives {back:?}");
                assert!(
                    s.k > -PI && s.k <= PI && s.m > -PI && s.m <= PI,
                    "{t}: {s:?}"
                );
            }
            assert!(inv.solutions.contains(&inv.chosen), "{t}: {inv:?}");
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/rotary.rs` survived every other test.
#[test]
fn without_a_previous_pose_the_smallest_tilt_is_chosen_then_the_smallest_k_then_m_positive() {
    let mut rng = Rng::new(78);
    for t in RotaryType::ALL {
        for _ in 0..600 {
            let v = rng.direction();
            let inv = t.inverse(&v, None).unwrap();
            let (a, b) = (inv.solutions[0], inv.solutions[1]);
            let key = |p: Pose| (p.m.abs(), p.k.abs());
            let want = if (a.m.abs() - b.m.abs()).abs() > 1e-6 {
                if a.m.abs() < b.m.abs() {
                    a
                } else {
                    b
                }
            } else if (a.k.abs() - b.k.abs()).abs() > 1e-6 {
                if a.k.abs() < b.k.abs() {
                    a
                } else {
                    b
                }
            } else if a.m >= 0.0 {
                a
            } else {
                b
            };
            assert_eq!(key(inv.chosen), key(want), "{t} {v:?}: {inv:?}");
        }
        // Both solutions equally tilted and equally turned: θk = ∓90°, θm = ±0.5 rad on
        // Group I (the second solution is θk + π, −θm).
        if t.group() == fiveaxis::rotary::Group::I {
            let v = t.tool_vector(Pose::new(-FRAC_PI_2, 0.5));
            let inv = t.inverse(&v, None).unwrap();
            assert!((inv.chosen.m - 0.5).abs() < 1e-12, "{t}: {inv:?}");
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/rotary.rs` survived every other test.
#[test]
fn with_a_previous_pose_the_nearest_solution_over_whole_turns_is_chosen() {
    let mut rng = Rng::new(79);
    for t in RotaryType::ALL {
        for _ in 0..600 {
            let v = rng.direction();
            let prev = Pose::new(rng.range(-9.0, 9.0), rng.range(-9.0, 9.0));
            let inv = t.inverse(&v, Some(prev)).unwrap();
            // Brute force: each solution plus whole turns in each angle, nearest by the sum of
            // squared angle differences.
            let mut best = (f64::INFINITY, Pose::default());
            for s in &inv.solutions {
                for i in -3..=3 {
                    for j in -3..=3 {
                        let c = Pose::new(s.k + TAU * i as f64, s.m + TAU * j as f64);
                        let d = (c.k - prev.k).powi(2) + (c.m - prev.m).powi(2);
                        if d < best.0 {
                            best = (d, c);
                        }
                    }
                }
            }
            let c = inv.chosen;
            assert!(
                (c.k - best.1.k).abs() < 1e-9 && (c.m - best.1.m).abs() < 1e-9,
                "{t} {v:?} from {prev:?}: {c:?}, nearest {:?}",
                best.1
            );
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/rotary.rs` survived every other test.
#[test]
fn the_jet_is_the_derivatives_of_the_tool_vector_along_any_line() {
    // V(u) = V(θk + u·dk, θm + u·dm): V', V'', V''' against central differences (h = 1e-3, error
    // O(h²) of the fourth and fifth derivatives, |V⁽ⁿ⁾| ≤ (|dk| + |dm|)ⁿ).
    let mut rng = Rng::new(80);
    let h = 1e-3;
    for t in RotaryType::ALL {
        for _ in 0..300 {
            let p = Pose::new(rng.range(-PI, PI), rng.range(-PI, PI));
            let (dk, dm) = (rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
            let at = |u: f64| t.tool_vector(Pose::new(p.k + u * dk, p.m + u * dm));
            let (m2, m1, z, p1, p2) = (at(-2.0 * h), at(-h), at(0.0), at(h), at(2.0 * h));
            let fd = [
                (p1 - m1) / (2.0 * h),
                (p1 - 2.0 * z + m1) / (h * h),
                (p2 - 2.0 * p1 + 2.0 * m1 - m2) / (2.0 * h * h * h),
            ];
            let jet = t.tool_vector_jet(p, dk, dm);
            let (v, d1, d2) = t.tool_vector_derivatives(p, dk, dm);
            let s = dk.abs() + dm.abs();
            assert!((jet[0] - z).norm() < 1e-15 && (v - z).norm() < 1e-15);
            for (n, (got, want)) in [jet[1], jet[2], jet[3]].iter().zip(&fd).enumerate() {
                let tol = 1e-5 * (1.0 + s).powi(n as i32 + 3);
                assert!(
                    (got - want).norm() < tol,
                    "{t} V^({}) {got:?} vs {want:?}",
                    n + 1
                );
            }
            assert!((d1 - jet[1]).norm() < 1e-15 && (d2 - jet[2]).norm() < 1e-15);
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/rotary.rs` survived every other test.
#[test]
fn a_type_prints_as_its_name() {
    let names = [
        "ABX", "ACX", "BCY", "BAY", "CAZ", "CBZ", "ABZ", "ACY", "BCX", "BAZ", "CAY", "CBX",
    ];
    for name in names {
        let t = RotaryType::parse(name).unwrap();
        assert_eq!(format!("{t}"), name);
        assert_eq!(t.to_string(), t.name());
    }
}
