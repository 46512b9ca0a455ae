//! The rotary ball-bar study's building blocks at their documented edges: the default sweep of
//! a moving axis, the travel test, the number of tests, the machine checked, the tool ball's
//! displacement, and the first-order length change with error motions.
//!
//! Found by cargo-mutants (scope `ballbar`): each of these was reached by no test at its edge.
#![allow(clippy::unwrap_used)]
mod probe_common;

use fiveaxis::api::{call, ApiInput};
use fiveaxis::ballbar::rotary::{default_sweep, BallbarRotaryInput, Study, MAX_TESTS};
use probe_common::{bc_table, with_errors};
use serde_json::{json, Value};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

fn study(input: Value) -> Study {
    Study::new(&BallbarRotaryInput::read(&input).unwrap()).unwrap()
}

#[test]
fn the_default_sweep_is_a_turn_from_zero_else_from_the_start_else_the_travel_within_90_degrees() {
    // A travel holding [0, 2π]: the turn from 0, also when it starts a hair below 0.
    assert_eq!(default_sweep(0.0, TAU), (0.0, TAU));
    assert_eq!(default_sweep(-2.0 * TAU, 2.0 * TAU), (0.0, TAU));
    assert_eq!(default_sweep(-1e-10, TAU), (0.0, TAU));
    assert_eq!(default_sweep(0.0, TAU - 1e-10), (0.0, TAU));
    // A full turn that does not hold 0 … 2π: one turn from its start.
    assert_eq!(default_sweep(-PI, PI), (-PI, PI));
    assert_eq!(default_sweep(0.5, 7.0), (0.5, 0.5 + TAU));
    // Less than a turn: the travel, cut to ±90°.
    assert_eq!(default_sweep(-2.0, 1.0), (-FRAC_PI_2, 1.0));
    assert_eq!(default_sweep(-0.3, 2.5), (-0.3, FRAC_PI_2));
    assert_eq!(default_sweep(-0.3, 0.4), (-0.3, 0.4));
}

#[test]
fn an_angle_is_within_the_travel_up_to_its_ends_and_a_nanoradian_beyond() {
    // The B/C table: B (the tilt, M) travels −120° … 120°.
    let s = study(json!({
        "machine": bc_table(),
        "tests": [{ "axis": "m", "ball": { "x": 0, "y": 0, "height": 50 }, "length": 100, "from": -90, "to": 90 }],
    }));
    let t = &s.tests[0];
    let (lo, hi) = ((-120f64).to_radians(), 120f64.to_radians());
    for a in [lo, hi, lo - 0.5e-9, hi + 0.5e-9, 0.0] {
        assert!(s.within(t, a), "{a} within");
    }
    for a in [lo - 2e-9, hi + 2e-9, -PI, PI] {
        assert!(!s.within(t, a), "{a} outside");
    }
}

#[test]
fn at_most_max_tests_tests_are_read() {
    let one = json!({ "ball": { "x": 100, "y": 0, "height": 50 }, "length": 100 });
    let tests = |n: usize| {
        (0..n)
            .map(|i| {
                let mut t = one.clone();
                t["name"] = json!(format!("test {i}"));
                t
            })
            .collect::<Vec<_>>()
    };
    let input = |n: usize| json!({ "machine": bc_table(), "tests": tests(n) });
    assert_eq!(
        BallbarRotaryInput::read(&input(MAX_TESTS))
            .unwrap()
            .tests
            .len(),
        MAX_TESTS
    );
    let e = BallbarRotaryInput::read(&input(MAX_TESTS + 1)).unwrap_err();
    assert_eq!(e.field, "tests");
    assert!(e.message.contains(&format!("at most {MAX_TESTS}")), "{e}");
}

#[test]
fn a_machine_whose_travel_ends_before_it_starts_is_refused_by_name() {
    let mut m = bc_table();
    m["rotary"]["mFrom"] = json!(30);
    m["rotary"]["mTo"] = json!(-30);
    let e = BallbarRotaryInput::read(&json!({ "machine": m })).unwrap_err();
    assert_eq!(e.field, "machine.rotary.mTo", "{e}");
    let e = call("ballbarRotarySimulate", &json!({ "machine": m })).unwrap_err();
    assert_eq!(e.field, "machine.rotary.mTo", "{e}");
}

#[test]
fn without_errors_the_tool_ball_is_where_it_was_commanded_and_the_bar_keeps_its_length() {
    let s = study(json!({
        "machine": bc_table(),
        "tests": [{ "ball": { "x": 120, "y": 30, "height": 40 }, "length": 100 }],
    }));
    let t = &s.tests[0];
    for deg in [0.0, 37.0, 145.0, 300.0] {
        let e = s.exact(t, f64::to_radians(deg)).unwrap();
        assert!(e.deviation.abs() < 1e-9, "{deg}°: {}", e.deviation);
        for d in e.displacement {
            assert!(d.abs() < 1e-9, "{deg}°: {:?}", e.displacement);
        }
    }
}

#[test]
fn the_first_order_change_follows_the_exact_one_with_error_motions_alone() {
    // Error motions only (no location error): C's radial run-out and its angular error, X's
    // positioning. Values of a few µm: the first order is within the second (|e|² / L).
    let mut m = with_errors(&bc_table(), json!({}));
    m["motions"] = json!({
        "E_XC": { "position": [0, 90, 180, 270, 360], "value": [0, 0.004, 0, -0.004, 0] },
        "E_CC": 0.002,
        "E_XX": { "poly": [0.003, 2e-5] },
    });
    let s = study(json!({
        "machine": m,
        "tests": [
            { "ball": { "x": 120, "y": 0, "height": 40 }, "length": 100 },
            { "ball": { "x": 80, "y": 40, "height": 40 }, "length": 100, "direction": "tangential", "name": "tangential" }
        ],
    }));
    let mut largest: f64 = 0.0;
    for t in &s.tests {
        for deg in (0..360).step_by(15) {
            let a = f64::from(deg).to_radians();
            let exact = s.exact(t, a).unwrap().deviation;
            let first = s.first_order(t, a).unwrap();
            largest = largest.max(exact.abs());
            assert!(
                (exact - first).abs() < 1e-6,
                "{} at {deg}°: exact {exact}, first order {first}",
                t.name
            );
        }
    }
    // The motions do move the bar (micrometres), so the comparison above is not of zeros.
    assert!(largest > 1e-3, "{largest}");
}
