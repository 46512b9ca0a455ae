//! The reversal test's motion and drives (Nishiguchi et al. 2017, Sections 3 and 4.1): the
//! commands against the machine's own inverse kinematics and against finite differences, X and
//! Y not reversing with C, the ideal drive tracing the exact circle on several machines, the
//! servo lag against the closed-form radius reduction, and machines without a C table refused.

#![allow(clippy::unwrap_used)]

use fiveaxis::machine::BranchRule;
use fiveaxis::reversal::drive::Drive;
use fiveaxis::reversal::{direction_checks, simulate, ReversalCase};
use nalgebra::Vector3;
use serde_json::{json, Value};

fn case(v: Value) -> ReversalCase {
    ReversalCase::read(&v).unwrap()
}

fn machines() -> Vec<Value> {
    vec![
        json!({}),
        json!({"type": "CAZ", "geometry": {"rotaryOffset": 12.0, "tableHeight": 80.0}}),
        json!({"kind": "head-table", "type": "CBZ", "linear": "table-xy"}),
        json!({"kind": "head-table", "type": "CAZ", "linear": "table-y", "rotary": {"kReversed": true}}),
        json!({"type": "CAY", "linear": "table-z", "rotary": {"mFrom": -120, "mTo": 120}}),
    ]
}

#[test]
fn commands_are_the_machine_inverse_kinematics_and_their_derivatives() {
    for m in machines() {
        let c = case(json!({"machine": m, "test": {"feed": 2000}}));
        let motion = c.motion().unwrap();
        let model = &motion.model;
        for i in 1..40 {
            let t = motion.duration * i as f64 / 40.0;
            let cmd = motion.commands(t);
            // The machine's inverse kinematics for the programmed tip with C as commanded.
            let mut prev = motion.base.clone();
            prev[motion.c_index] = cmd.c.x;
            let q = model
                .inverse(
                    &motion.tip(cmd.theta),
                    &Vector3::z(),
                    BranchRule::Nearest,
                    Some(&prev),
                )
                .unwrap()
                .q;
            for k in 0..3 {
                let want = q[motion.linear[k]];
                assert!(
                    (cmd.linear[k].x - want).abs() < 1e-9,
                    "{m}: axis {k} at t = {t}"
                );
            }
            // Velocity and acceleration against central differences of the positions.
            let h = 1e-4;
            let (a, b) = (motion.commands(t - h), motion.commands(t + h));
            let now: Vec<_> = cmd.linear.iter().chain([&cmd.c]).collect();
            let before: Vec<_> = a.linear.iter().chain([&a.c]).collect();
            let after: Vec<_> = b.linear.iter().chain([&b.c]).collect();
            for k in 0..4 {
                let v = (after[k].x - before[k].x) / (2.0 * h);
                let acc = (after[k].x - 2.0 * now[k].x + before[k].x) / (h * h);
                assert!(
                    (now[k].v - v).abs() < 1e-5 * (1.0 + v.abs()),
                    "{m}: velocity at {t}"
                );
                assert!(
                    (now[k].a - acc).abs() < 1e-2 * (1.0 + acc.abs()),
                    "{m}: acceleration at {t}: {} vs {acc}",
                    now[k].a
                );
            }
        }
        // C goes 0 → the reversal angle at θ = 180° → 0.
        let at = |t: f64| motion.commands(t);
        assert!(at(0.0).c.x.abs() < 1e-12);
        assert!((at(motion.reversal).c.x - 90f64.to_radians()).abs() < 1e-9);
        assert!((at(motion.reversal).theta - std::f64::consts::PI).abs() < 1e-9);
        assert!(at(motion.duration).c.x.abs() < 1e-9);
    }
}

#[test]
fn x_and_y_keep_their_direction_when_c_reverses() {
    // Table 1's feeds with r = 25 mm (R = 50 mm): neither X nor Y changes direction within ±5°
    // of the reversal, commanded or simulated.
    for f in [1000.0, 2000.0, 3000.0] {
        let c = case(json!({"test": {"feed": f, "offset": 25}}));
        let (m, tr) = simulate(&c).unwrap();
        for d in direction_checks(&m, &tr) {
            assert!(
                !d.reverses && !d.actual_reverses && !d.stops,
                "F = {f}: {d:?}"
            );
            // And the velocity before and after C turns has the same sign.
            if d.name != "Z" {
                assert!(d.before * d.after > 0.0, "F = {f}: {d:?}");
            }
        }
    }
    // r = R: one axis comes to rest at the reversal (the paper's "X stops" for r = 50 mm).
    let c = case(json!({"test": {"offset": 50}}));
    let (m, tr) = simulate(&c).unwrap();
    let checks = direction_checks(&m, &tr);
    assert_eq!(checks.iter().filter(|d| d.stops).count(), 1, "{checks:?}");
    assert!(checks.iter().all(|d| !d.reverses), "{checks:?}");
    // r > R: the geometry makes one axis reverse with C (the test then fails its purpose).
    let c = case(json!({"test": {"offset": 80}}));
    let (m, tr) = simulate(&c).unwrap();
    assert!(direction_checks(&m, &tr).iter().any(|d| d.reverses));
}

#[test]
fn ideal_drives_trace_the_exact_circle_on_any_machine_with_a_c_table() {
    for m in machines() {
        let c = case(
            json!({"machine": m, "feedForward": "full", "c": {"friction": 0},
                             "test": {"feed": 3000}}),
        );
        let (_, tr) = simulate(&c).unwrap();
        let worst = tr.deviation.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        assert!(worst < 1e-9, "{m}: {worst:e} mm");
        // The trace goes once round.
        assert!((tr.angle.last().unwrap() - std::f64::consts::TAU).abs() < 1e-6);
    }
}

#[test]
fn servo_lag_shrinks_the_radius_by_the_closed_form_and_nothing_else() {
    // Centre on C's axis (r = 0): a lag of C only turns the circle about its centre, so the
    // radius is that of the linear axes' circle. In machine coordinates the tip turns at
    // θ̇·(1 − ċ) before the reversal and θ̇·(1 + ċ) after (C turns the table the other way),
    // and in the steady state a circle at angular speed ω comes out with radius R·|G(jω)|.
    for f in [1000.0, 3000.0] {
        let c = case(json!({"c": {"friction": 0}, "test": {"offset": 0, "feed": f}}));
        let (m, tr) = simulate(&c).unwrap();
        let (lin, _) = c.drives();
        let thd = f / 60.0 / 50.0;
        let rate = m.rate;
        let g: &Drive = &lin[0];
        for (from, to, omega) in [
            (60.0, 160.0, thd * (1.0 - rate)),
            (220.0, 340.0, thd * (1.0 + rate)),
        ] {
            let want = 50.0 * (g.response(omega) - 1.0);
            let devs: Vec<f64> = tr
                .theta
                .iter()
                .zip(&tr.deviation)
                .filter(|(t, _)| (from..to).contains(&t.to_degrees()))
                .map(|(_, d)| *d)
                .collect();
            assert!(devs.len() > 100);
            for d in &devs {
                assert!(
                    (d - want).abs() < 1e-3 * want.abs(),
                    "F = {f}, {from}–{to}°: {d:e} vs closed form {want:e} mm"
                );
            }
            assert!(want < 0.0);
        }
    }
}

#[test]
fn machines_without_a_c_table_are_refused() {
    for m in [
        json!({"kind": "head-head", "type": "CAZ"}),
        json!({"type": "ABZ"}),
        json!({"kind": "head-table", "type": "BCY"}),
    ] {
        let c = case(json!({"machine": m}));
        let e = c.motion().unwrap_err();
        assert_eq!(e.field, "machine.type", "{m}");
        assert!(
            e.message.contains("needs a rotary table C"),
            "{}",
            e.message
        );
    }
    // A C travel that does not reach the reversal angle.
    let c = case(json!({"machine": {"rotary": {"kFrom": -30, "kTo": 45}}}));
    let e = c.motion().unwrap_err();
    assert!(e.message.contains("outside the travel"), "{e}");
    // Unknown keys are refused with the path.
    let e = ReversalCase::read(&json!({"c": {"frction": 3}})).unwrap_err();
    assert!(e.to_string().starts_with("c.frction"), "{e}");
}

#[test]
fn a_test_that_would_take_minutes_to_simulate_is_refused_with_the_feed_named() {
    // 2 mm/min round the default 50 mm circle: about 9400 s of motion, 94 million steps of
    // 0.1 ms (minutes of work for the page's worker).
    let case = fiveaxis::reversal::ReversalCase::read(
        &serde_json::json!({ "test": { "feed": 2 }, "step": 0.1 }),
    )
    .unwrap();
    let e = fiveaxis::reversal::simulate(&case).unwrap_err();
    assert_eq!(e.field, "test.feed");
    assert!(e.message.contains("more than 2000000"), "{e}");
    // The default test is well inside.
    let case = fiveaxis::reversal::ReversalCase::read(&serde_json::json!({})).unwrap();
    assert!(fiveaxis::reversal::simulate(&case).is_ok());
}
