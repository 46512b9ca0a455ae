//! The split of a move into equal steps that keep its nonlinear error within a tolerance
//! (`split_within`), checked against a closed form: a move of K alone on a type whose K axis is
//! Z and whose tool is along Z at M = 0 (CAZ, CBZ) turns the tool on a cone of half-angle β = |θm|
//! about Z. A block of K step `s` then deviates from the plane of its ends most at its middle:
//! in the vertical plane through the bisector, the tool (sin β, cos β) lies off the line along
//! `V0 + V1 ∝ (sin β·cos(s/2), cos β)`, so
//!
//! ```text
//! δ(s) = L · sin β · cos β · (1 − cos(s/2)) / sqrt(sin²β · cos²(s/2) + cos²β)
//! ```
//!
//! increasing in `s` on (0, π): the smallest `n` has `δ(Δk/n) ≤ tol < δ(Δk/(n−1))`.

use crate::common;
use common::{close, deg};
use fiveaxis::nonlinear::*;
use fiveaxis::rotary::{Pose, RotaryType};

fn closed_form(beta: f64, s: f64, length: f64) -> f64 {
    let h = 0.5 * s;
    length * beta.sin() * beta.cos() * (1.0 - h.cos())
        / (beta.sin().powi(2) * h.cos().powi(2) + beta.cos().powi(2)).sqrt()
}

#[test]
fn a_move_of_k_alone_splits_into_the_fewest_steps_the_closed_form_allows() {
    for name in ["CAZ", "CBZ"] {
        let t = RotaryType::parse(name).unwrap();
        for &(m_deg, dk_deg, length, tol) in &[
            (30.0, 90.0, 100.0, 0.01),
            (45.0, 120.0, 250.0, 0.001),
            (10.0, 30.0, 100.0, 0.05),
            (60.0, 170.0, 300.0, 0.002),
            (20.0, 5.0, 100.0, 1.0),
        ] {
            let (m, dk) = (deg(m_deg), deg(dk_deg));
            // The convention the closed form assumes: the tool at angle |θm| from Z.
            let v = t.tool_vector(Pose::new(0.0, m));
            close(v.z, m.cos(), 1e-12, &format!("{name}: tool at θm from Z"));
            let mv = Move::new(t, Pose::new(0.3, m), Pose::new(0.3 + dk, m));
            // One block is the move itself: the engine's peak agrees with the closed form.
            let whole = Deviation::new(mv).peak().value * length;
            close(
                whole,
                closed_form(m, dk, length),
                1e-9,
                &format!("{name}: δ of the whole move"),
            );
            let expected = (1..=MAX_SPLIT)
                .find(|&n| closed_form(m, dk / n as f64, length) <= tol)
                .unwrap();
            let s = split_within(mv, length, tol).unwrap();
            assert_eq!(
                s.steps,
                Some(expected),
                "{name} θm {m_deg}°, Δk {dk_deg}°, L {length}, tol {tol}"
            );
            close(s.step_k, dk / expected as f64, 1e-12, "step of K");
            assert_eq!(s.step_m, 0.0);
            close(
                s.max,
                closed_form(m, dk / expected as f64, length),
                1e-9,
                "δ of the blocks",
            );
            assert!(s.max <= tol);
        }
    }
}

#[test]
fn a_move_within_the_tolerance_is_one_step_and_an_impossible_one_says_so() {
    let t = RotaryType::parse("CAZ").unwrap();
    let mv = Move::new(
        t,
        Pose::new(0.0, deg(10.0)),
        Pose::new(deg(30.0), deg(25.0)),
    );
    let whole = Deviation::new(mv).peak().value * 100.0;
    let s = split_within(mv, 100.0, 2.0 * whole).unwrap();
    assert_eq!(s.steps, Some(1));
    close(s.max, whole, 1e-15, "the move as it is");
    // A tolerance far below what MAX_SPLIT steps reach.
    let s = split_within(mv, 100.0, 1e-15).unwrap();
    assert_eq!(s.steps, None);
    assert!(s.max > 1e-15);
    // Both axes: every block of the split is within, and one step fewer is not (δ falls
    // monotonically here: the blocks are short and far from the pole).
    let s = split_within(mv, 100.0, 0.01).unwrap();
    let n = s.steps.unwrap();
    let worst = |n: usize| {
        (0..n)
            .map(|i| {
                let a = mv.pose_at(i as f64 / n as f64);
                let b = mv.pose_at((i + 1) as f64 / n as f64);
                Deviation::new(Move::new(t, a, b)).peak_dense().value * 100.0
            })
            .fold(0.0, f64::max)
    };
    assert!(worst(n) <= 0.01 * (1.0 + 1e-12));
    assert!(worst(n - 1) > 0.01);
    assert!(split_within(mv, 100.0, 0.0).is_err());
    assert!(split_within(mv, 100.0, f64::NAN).is_err());
}
