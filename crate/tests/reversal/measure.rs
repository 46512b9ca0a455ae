//! The dent measured from a trace itself (`reversal::measure`): depth and width of synthetic
//! traces with a dent of known shape (a triangle, a Gaussian, a step), built here, against their
//! closed forms; the degenerate cases; the friction in a drive's terms against eq 2.

#![allow(clippy::unwrap_used)]

use fiveaxis::reversal::measure::{compensation, measure_dent};
use fiveaxis::reversal::{dent, simulate, simulate_with_step, ReversalCase};
use serde_json::json;

/// A trace from 160° to 200° every `step` degrees: `d(θ in degrees)` in mm.
fn trace(step: f64, d: impl Fn(f64) -> f64) -> (Vec<f64>, Vec<f64>) {
    let n = (40.0 / step).round() as usize;
    let deg: Vec<f64> = (0..=n).map(|i| 160.0 + i as f64 * step).collect();
    (
        deg.iter().map(|a| a.to_radians()).collect(),
        deg.iter().map(|a| d(*a)).collect(),
    )
}

fn close(a: f64, b: f64, tol: f64, what: &str) {
    assert!((a - b).abs() <= tol, "{what}: {a} vs {b}");
}

#[test]
fn a_triangular_dent_is_as_deep_and_half_as_wide_as_its_base() {
    // Level 4 µm; a triangle 6 µm deep at 182°, its base 3° wide (half-base w = 1.5°): the
    // fall is D·(1 − |θ − θ0|/w), at D/2 where |θ − θ0| = w/2, so the width at half depth is w.
    let (c, depth, th0, w) = (0.004, 0.006, 182.0, 1.5);
    let (a, d) = trace(0.01, |t| c - depth * (1.0 - (t - th0).abs() / w).max(0.0));
    let m = measure_dent(&a, &d).unwrap();
    close(m.baseline, c, 1e-15, "baseline");
    close(m.depth, depth, 1e-12, "depth");
    close(m.angle.to_degrees(), th0, 1e-9, "angle");
    close(m.width.to_degrees(), w, 1e-9, "width");
    close(m.low.to_degrees(), th0 - w / 2.0, 1e-9, "low");
    close(m.high.to_degrees(), th0 + w / 2.0, 1e-9, "high");
    assert!(!m.open);
    close(m.step, 0.0, 1e-15, "step");
    // In time: W·R/F (R = 50 mm at 1000 mm/min: 1.5° = 0.02618 rad → 78.5 ms).
    close(
        m.duration(50.0, 1000.0),
        w.to_radians() * 50.0 / (1000.0 / 60.0),
        1e-15,
        "duration",
    );
}

#[test]
fn a_gaussian_dent_is_its_full_width_at_half_maximum_wide() {
    // FWHM of a Gaussian: 2·√(2 ln 2)·σ.
    let (depth, th0, sigma) = (0.009, 181.5, 0.4);
    let (a, d) = trace(0.005, |t| {
        -0.001 - depth * (-(t - th0).powi(2) / (2.0 * sigma * sigma)).exp()
    });
    let m = measure_dent(&a, &d).unwrap();
    close(m.depth, depth, 1e-12, "depth");
    close(m.angle.to_degrees(), th0, 1e-9, "angle");
    let fwhm = 2.0 * (2.0 * 2f64.ln()).sqrt() * sigma;
    close(m.width.to_degrees(), fwhm, 1e-4, "width");
    assert!(!m.open);
}

#[test]
fn the_baseline_is_the_median_before_the_reversal() {
    // Spikes of +5 µm on every fourth point before the reversal, a 1 µm level otherwise: the
    // median ignores them (a mean would be 2.25 µm); a triangular dent 5 µm below the level.
    let (a, d) = trace(0.1, |t| {
        let k = (t * 10.0).round() as i64;
        let spike = if t < 180.0 && k % 4 == 0 { 0.005 } else { 0.0 };
        0.001 + spike - 0.005 * (1.0 - (t - 183.0).abs()).max(0.0)
    });
    let m = measure_dent(&a, &d).unwrap();
    close(m.baseline, 0.001, 1e-15, "baseline");
    close(m.depth, 0.005, 1e-12, "depth");
    close(m.width.to_degrees(), 1.0, 1e-9, "width");
}

#[test]
fn a_step_is_open_its_width_a_lower_bound() {
    // +9 µm before, −16 µm from 181° on, a straight ramp between: the fall is 25 µm, first
    // reached at 181°; half of it at 180.5°, and it never comes back up within the window.
    let (a, d) = trace(0.1, |t| {
        if t <= 180.0 {
            0.009
        } else if t >= 181.0 {
            -0.016
        } else {
            0.009 - 0.025 * (t - 180.0)
        }
    });
    let m = measure_dent(&a, &d).unwrap();
    close(m.depth, 0.025, 1e-12, "depth");
    close(m.angle.to_degrees(), 181.0, 1e-9, "angle");
    assert!(m.open);
    close(m.low.to_degrees(), 180.5, 1e-9, "low");
    close(
        m.high.to_degrees(),
        190.0,
        1e-9,
        "high: the last point of the window",
    );
    close(m.width.to_degrees(), 9.5, 1e-9, "width");
    close(m.level_after, -0.016, 1e-15, "level after");
    close(m.step, 0.025, 1e-12, "step");
}

#[test]
fn no_fall_no_dent_and_too_few_points_are_refused() {
    // A bump outwards only: no dent.
    let (a, d) = trace(0.1, |t| 0.002 * (1.0 - (t - 182.0).abs()).max(0.0));
    let m = measure_dent(&a, &d).unwrap();
    assert_eq!((m.depth, m.width, m.open), (0.0, 0.0, false));
    // A point every 5°: two in 170°–179° (170°, 175°).
    let (a, d) = trace(5.0, |_| 0.0);
    let e = measure_dent(&a, &d).unwrap_err();
    assert_eq!(e.field, "csv");
    assert!(e.to_string().contains("from 170° to 179°"), "{e}");
}

#[test]
fn with_ideal_drives_the_measured_depth_is_the_simulated_dent() {
    // Both feed-forwards: without friction the trace is the exact circle, so the fall below the
    // level before the reversal is the friction's dent (with − without).
    let c = ReversalCase::read(&json!({"feedForward": "full"})).unwrap();
    let (m, with) = simulate(&c).unwrap();
    let without = simulate_with_step(&c.with_c_friction(0.0), &m, c.step * 1e-3).unwrap();
    let sim = dent(&with, &without);
    let got = measure_dent(&with.angle, &with.deviation).unwrap();
    assert!(sim.depth > 1e-4, "{sim:?}");
    close(got.depth, sim.depth, 0.02 * sim.depth, "depth");
    close(got.width, sim.width, 0.1 * sim.width, "width");
}

#[test]
fn the_compensator_step_is_the_change_of_eq2_across_a_reversal() {
    let c = ReversalCase::read(&json!({"c": {"friction": 12, "ratedTorque": 250}})).unwrap();
    let (_, d) = c.drives();
    // Far before a reversal moving +, far after it moving −: eq 2's friction changes by 2·f_c.
    let far = 20.0 / d.slope;
    let change = d.friction(far, 1.0) - d.friction(far, -1.0);
    let k = compensation(d.fc, c.c.rated_torque);
    close(k.step, change, 1e-9 * change, "step");
    close(k.step, 24.0, 1e-12, "step");
    close(k.friction_share, 12.0 / 250.0, 1e-15, "share");
    close(k.step_share, 24.0 / 250.0, 1e-15, "step share");
}

#[test]
fn the_rated_torque_is_at_most_the_torque_limit() {
    let e = ReversalCase::read(&json!({"c": {"ratedTorque": 600}})).unwrap_err();
    assert_eq!(e.field, "c.ratedTorque", "{e}");
    assert!(e.to_string().contains("above the torque limit"), "{e}");
    assert!(ReversalCase::read(&json!({"c": {"ratedTorque": 500}})).is_ok());
    let e = ReversalCase::read(&json!({"c": {"ratedTorque": 0}})).unwrap_err();
    assert_eq!(e.field, "c.ratedTorque", "{e}");
}
