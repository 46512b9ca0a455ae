//! The reversal study's parts, each against a second method or a closed form:
//! - the drives: gains from their labels; the loop gain `Drive::response` against the loop's
//!   equations integrated with a sine; the integral held at the torque limit; a step over a
//!   reversal against 10 µs steps (where the friction switches, and the state after it);
//! - the run: the trace's sampling and end, each recorded quantity against finite differences
//!   and the chain at the recorded axes, every moving axis lagging, the friction's direction
//!   memory against the velocity's sign changes and eq 2 at the recorded travel;
//! - the motion: the path s(t) and the commands' accelerations against central differences;
//! - the measures: the dent of a known triangle, the direction checks' velocities, the step
//!   check against the test's own pair of runs;
//! - the fit: the reader's limits, the truth within 3σ, the intervals against σ²(JᵀJ)⁻¹ from the
//!   test's own Jacobian, the point count, a trace past 360°, an interval spanning over 10×.

#![allow(clippy::unwrap_used)]
use crate::common;

use fiveaxis::reversal::{
    dent, direction_checks, simulate, simulate_with_step, step_check, ReversalCase, Trace,
};
use serde_json::{json, Value};
use std::f64::consts::TAU;

fn case(v: Value) -> ReversalCase {
    ReversalCase::read(&v).unwrap()
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn the_drives_gains_are_what_their_labels_say() {
    // "K_v = mass · 2π · bandwidth", "K_i = K_v / integral time" (ms), slope 1/mm → 1/m.
    let c = case(json!({
        "linear": {"mass": 300, "velocityBandwidth": 50, "integralTime": 8, "positionGain": 25,
                   "damping": 700, "forceLimit": 9000, "friction": 40, "frictionSlope": 80},
        "c": {"inertia": 3, "velocityBandwidth": 20, "integralTime": 12, "positionGain": 35,
              "damping": 4, "torqueLimit": 300, "friction": 7, "frictionSlope": 600},
        "feedForward": "velocity"
    }));
    let (lin, rot) = c.drives();
    let kv = 300.0 * TAU * 50.0;
    for d in lin {
        assert!((d.kv - kv).abs() < 1e-9 * kv, "{d:?}");
        assert!((d.ki - kv / 0.008).abs() < 1e-9 * kv / 0.008, "{d:?}");
        assert_eq!(
            (d.inertia, d.kp, d.damping, d.limit, d.fc),
            (300.0, 25.0, 700.0, 9000.0, 40.0)
        );
        assert!((d.slope - 80_000.0).abs() < 1e-9, "{d:?}");
        assert!(d.ff_velocity && !d.ff_torque);
    }
    let kv = 3.0 * TAU * 20.0;
    assert!((rot.kv - kv).abs() < 1e-9 * kv, "{rot:?}");
    assert!((rot.ki - kv / 0.012).abs() < 1e-9 * kv / 0.012, "{rot:?}");
    assert_eq!(
        (rot.inertia, rot.kp, rot.damping, rot.limit),
        (3.0, 35.0, 4.0, 300.0)
    );
    assert_eq!((rot.fc, rot.slope), (7.0, 600.0));
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn the_trace_has_at_most_samples_plus_one_points_from_rest_to_the_end() {
    let c = case(json!({}));
    let (m, tr) = simulate(&c).unwrap();
    let h = c.step * 1e-3;
    // The run: the motion and 0.1 s of settling, in whole steps.
    assert_eq!(tr.steps, ((m.duration + 0.1) / h).ceil() as usize);
    // Half the steps, less one or two: the record must take every third step, not every second.
    let samples = (tr.steps - 1) / 2;
    for n in [c.samples, samples, 100] {
        let c = case(json!({ "samples": n }));
        let tr = simulate_with_step(&c, &m, h).unwrap();
        let len = tr.time.len();
        assert!(
            len <= n + 1 && len >= n / 2,
            "{n} samples asked, {len} recorded"
        );
        assert_eq!(tr.time[0], 0.0);
        // The last point is the end of the run, whatever the stride.
        let end = tr.steps as f64 * h;
        assert!(
            (tr.time[len - 1] - end).abs() < 1e-9,
            "ends at {} not {end}",
            tr.time[len - 1]
        );
        // The commanded trace angle: from 0 once round, never back, and 2π while the axes
        // settle after the motion.
        assert_eq!(tr.theta[0], 0.0);
        assert!(tr.theta.windows(2).all(|w| w[1] >= w[0]));
        assert!(
            (tr.theta[len - 1] - TAU).abs() < 1e-12,
            "{}",
            tr.theta[len - 1]
        );
        // Evenly spaced but for the last interval.
        let dt = tr.time[1] - tr.time[0];
        for w in tr.time[..len - 1].windows(2) {
            assert!((w[1] - w[0] - dt).abs() < 1e-9);
        }
        // The reversal's index: the recorded instant nearest to it (by scanning them all).
        let nearest = tr
            .time
            .iter()
            .map(|t| (t - m.reversal).abs())
            .fold(f64::INFINITY, f64::min);
        assert_eq!((tr.time[tr.reversal_index] - m.reversal).abs(), nearest);
        assert!(tr.reversal_index > 0 && tr.reversal_index < len - 1);
    }
}

/// A run recorded at every step (`samples` above the steps).
fn every_step(v: Value) -> (fiveaxis::reversal::motion::Motion, Trace) {
    let c = case(v);
    let (m, tr) = simulate(&c).unwrap();
    assert_eq!(tr.time.len(), tr.steps + 1, "every step recorded");
    (m, tr)
}

/// The largest |x|.
fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |a, b| a.max(b.abs()))
}

/// Largest gap between `v` and the central differences of `x` over `t`, and the largest |v|.
fn against_differences(t: &[f64], x: &[f64], v: &[f64]) -> (f64, f64) {
    let mut gap = 0.0f64;
    let mut top = 0.0f64;
    for i in 1..t.len() - 1 {
        let fd = (x[i + 1] - x[i - 1]) / (t[i + 1] - t[i - 1]);
        gap = gap.max((fd - v[i]).abs());
        top = top.max(v[i].abs());
    }
    (gap, top)
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn each_recorded_quantity_against_a_second_method() {
    let (m, tr) = every_step(json!({"samples": 200000, "test": {"offset": 40}}));
    let n = tr.time.len();
    for i in (0..n).step_by(97) {
        let cmd = m.commands(tr.time[i]);
        // Commands in mm as the motion gives them; C in rad.
        for k in 0..3 {
            let got = tr.linear[k].command[i];
            assert!(
                (got - cmd.linear[k].x).abs() < 1e-9,
                "{}: {got} vs {}",
                k,
                cmd.linear[k].x
            );
        }
        assert!((tr.c_command[i] - cmd.c.x).abs() < 1e-12);
        assert!((tr.c_command[i] - tr.c_error[i] - tr.c_actual[i]).abs() < 1e-15);
        // The tip through the chain at the actual axes (command − following error, mm): the
        // errors are in mm.
        let lin = [0, 1, 2].map(|k| tr.linear[k].command[i] - tr.linear[k].error[i]);
        let tip = m.actual_tip(lin, tr.c_actual[i]).unwrap();
        assert!(
            (tip.x - tr.x[i]).abs() < 1e-9 && (tip.y - tr.y[i]).abs() < 1e-9,
            "{i}"
        );
    }
    // Velocities: the central differences of the actual positions (steps of 0.2 ms: the
    // difference's own error is h²/6 · |x'''|, far below 1e-3 of the speed here).
    let (gap, top) = against_differences(&tr.time, &tr.c_actual, &tr.c_velocity);
    assert!(
        gap < 1e-3 * top && top > 0.01,
        "C: {gap:e} of {top:e} rad/s"
    );
    for l in &tr.linear[..2] {
        let actual: Vec<f64> = l.command.iter().zip(&l.error).map(|(c, e)| c - e).collect();
        let (gap, top) = against_differences(&tr.time, &actual, &l.velocity);
        assert!(
            gap < 1e-3 * top && top > 1.0,
            "{}: {gap:e} of {top:e} mm/s",
            l.name
        );
    }
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn every_moving_axis_lags_its_command_without_feed_forward() {
    // A P position loop: in the steady state the error is v/K_p; an axis whose command moves
    // is never followed exactly. Y is at the same place at the start and at C's reversal (to
    // the last bit with R = 40, r = 5): it moves all the same.
    for (r, radius) in [(0.0, 50.0), (25.0, 50.0), (50.0, 50.0), (5.0, 40.0)] {
        let c = case(json!({"test": {"offset": r, "radius": radius}}));
        let (_, tr) = simulate(&c).unwrap();
        let kp = c.linear.position_gain;
        for l in &tr.linear {
            let travel = l.command.iter().fold(f64::NEG_INFINITY, |a, b| a.max(*b))
                - l.command.iter().fold(f64::INFINITY, |a, b| a.min(*b));
            let (err, top) = (max_abs(&l.error), max_abs(&l.velocity));
            if travel > 1e-6 {
                assert!(
                    err > 0.5 * top / kp,
                    "r = {r}, {}: lag {err} mm at {top} mm/s",
                    l.name
                );
            } else {
                assert_eq!(err, 0.0, "r = {r}, {}", l.name);
            }
        }
    }
}

/// Sign changes of `v`, starting from the sign of its first non-zero value.
fn sign_changes(v: &[f64]) -> usize {
    let mut dir = 0.0;
    let mut n = 0;
    for x in v.iter().filter(|x| **x != 0.0) {
        if dir != 0.0 && x * dir < 0.0 {
            n += 1;
        }
        dir = x.signum();
    }
    n
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn the_friction_sees_the_direction_changes_of_the_velocity_and_no_others() {
    // The direction memory changes where the velocity changes sign (drive's docs), and starts
    // in the direction of the first motion. Recorded at every step, the count of the model is
    // the count of sign changes of each axis with friction. With an acceleration of 4 s at
    // 1000 mm/min, X is at rest at 0 s and Y turns round between 2 s and 8 s: a direction
    // taken at either instant instead of at the start of the motion is one change too many.
    for (v, linear) in [
        (json!({"samples": 200000}), false),
        (
            json!({"samples": 200000, "test": {"accelTime": 4000},
                   "linear": {"friction": 300}}),
            true,
        ),
    ] {
        let (_, tr) = every_step(v);
        let mut want = sign_changes(&tr.c_velocity);
        assert!(want >= 1, "C turns round");
        if linear {
            for l in &tr.linear {
                want += sign_changes(&l.velocity);
            }
        }
        assert_eq!(tr.direction_changes, want);
    }
}

/// A trace with only θ (rad) and the deviation (mm): what [`dent`] reads.
fn synthetic(theta: &[f64], deviation: Vec<f64>) -> Trace {
    let n = theta.len();
    Trace {
        time: theta.to_vec(),
        theta: theta.to_vec(),
        angle: theta.to_vec(),
        deviation,
        x: vec![0.0; n],
        y: vec![0.0; n],
        c_command: vec![0.0; n],
        c_actual: vec![0.0; n],
        c_velocity: vec![0.0; n],
        c_error: vec![0.0; n],
        c_friction: vec![0.0; n],
        c_torque: vec![0.0; n],
        linear: Vec::new(),
        reversal_time: 0.0,
        reversal_index: 0,
        steps: n,
        step: 1.0,
        direction_changes: 0,
    }
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn the_dent_of_a_triangle_is_its_depth_at_its_apex_and_half_its_base_wide() {
    // θ_i = i/100, i = 0..=100. The trace with friction dips by a triangle of depth D and half
    // base 20 samples at `apex` (clipped by the ends), and bulges out by B at one sample: the
    // dent is D deep at the apex, as wide at half depth as the triangle's half base (where the
    // ends do not clip it), and the bump is B.
    let theta: Vec<f64> = (0..=100).map(|i| i as f64 / 100.0).collect();
    let (d, b) = (0.004, 0.0015);
    for (apex, bump_at, width) in [(50usize, 85usize, 0.2), (0, 60, 0.1), (100, 30, 0.1)] {
        let without = synthetic(&theta, vec![0.25e-3; 101]);
        let mut dev: Vec<f64> = (0..=100)
            .map(|i| 0.25e-3 - d * (1.0 - (i as f64 - apex as f64).abs() / 20.0).max(0.0))
            .collect();
        dev[bump_at] += b;
        let got = dent(&synthetic(&theta, dev), &without);
        assert!((got.depth - d).abs() < 1e-15, "{apex}: {got:?}");
        assert_eq!(got.angle, theta[apex]);
        assert!((got.width - width).abs() < 1e-12, "{apex}: {got:?}");
        assert!((got.bump - b).abs() < 1e-15, "{apex}: {got:?}");
    }
    // The same trace twice: no dent, no width, no bump.
    let same = synthetic(&theta, theta.iter().map(|t| 0.01 * t.sin()).collect());
    let got = dent(&same, &same);
    assert_eq!((got.depth, got.width, got.bump), (0.0, 0.0, 0.0));
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn before_and_after_are_the_commanded_velocities_a_reversal_time_either_side() {
    // r > R: X and Y change direction with C; their velocities either side differ.
    for r in [25.0, 75.0] {
        let c = case(json!({"test": {"offset": r}}));
        let (m, tr) = simulate(&c).unwrap();
        let edge = c.test.reversal_time * 1e-3;
        let dt = 1e-6;
        for (k, d) in direction_checks(&m, &tr).iter().enumerate() {
            let at = |t: f64| {
                (m.commands(t + dt).linear[k].x - m.commands(t - dt).linear[k].x) / (2.0 * dt)
            };
            let (before, after) = (at(m.reversal - edge), at(m.reversal + edge));
            let tol = 1e-6 * (1.0 + before.abs() + after.abs());
            assert!(
                (d.before - before).abs() < tol,
                "r = {r}, {d:?}: before {before}"
            );
            assert!(
                (d.after - after).abs() < tol,
                "r = {r}, {d:?}: after {after}"
            );
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn the_step_check_compares_the_two_runs_at_the_same_instants_only() {
    // The check's difference, against the test's own pair of runs: every step at h and every
    // second step at h/2, paired where their times agree (to 1e-9 s). At 2500 mm/min the run
    // lasts T with T/h just above a whole number: the finer run then ends h/2 before the
    // coarse one, and its last sample must not be compared with the coarse run's last.
    for f in [2000.0, 2500.0] {
        let c = case(json!({"test": {"feed": f}, "samples": 200000}));
        let (m, tr) = simulate(&c).unwrap();
        assert_eq!(tr.time.len(), tr.steps + 1);
        let h = c.step * 1e-3;
        let fine_case = case(json!({"test": {"feed": f}, "samples": tr.steps}));
        let fine = simulate_with_step(&fine_case, &m, h / 2.0).unwrap();
        let mut want = 0.0f64;
        let mut pairs = 0;
        for (t, d) in tr.time.iter().zip(&tr.deviation) {
            let j = fine.time.partition_point(|tf| *tf < t - 1e-9);
            if j < fine.time.len() && (fine.time[j] - t).abs() < 1e-9 {
                want = want.max((d - fine.deviation[j]).abs());
                pairs += 1;
            }
        }
        assert!(pairs + 1 >= tr.time.len(), "{pairs} instants in common");
        let s = step_check(&c, &m, &tr).unwrap();
        assert!(
            (s.difference - want).abs() <= 1e-15,
            "F = {f}: {s:?}, pairs give {want:e}"
        );
    }
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn the_step_checks_relative_figure_is_the_difference_over_the_largest_deviation() {
    let c = case(json!({"test": {"feed": 2000}}));
    let (m, tr) = simulate(&c).unwrap();
    let s = step_check(&c, &m, &tr).unwrap();
    // The finer run's largest |deviation| is the coarse one's within the difference.
    let scale = max_abs(&tr.deviation);
    let (lo, hi) = (
        s.difference / (scale + s.difference),
        s.difference / (scale - s.difference),
    );
    assert!(
        s.difference > 0.0 && scale > 10.0 * s.difference,
        "{s:?}, {scale}"
    );
    assert!(
        lo <= s.relative && s.relative <= hi,
        "{s:?}: not within {lo}..{hi}"
    );
    assert_eq!(s.step, c.step * 1e-3);
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn the_closed_loop_gain_is_what_the_integrated_drive_does_with_a_sine() {
    // Drive::response, the transfer function of the loop's equations, against the same
    // equations integrated in time: a sine command x_r = A·sin ωt (A = 10 µm or µrad: far
    // from the torque limit, where the loop is linear), the drive's steady-state
    // amplitude from its projection on sin and cos over whole periods after the start-up has
    // died out (the slowest pole is about K_p: e^(−K_p·1 s) < 1e-12).
    use fiveaxis::reversal::drive::{AxisState, Reference};
    let c = case(json!({"c": {"friction": 0}}));
    let (lin, rot) = c.drives();
    let amp = 1e-5;
    for d in [lin[0], rot] {
        for omega in [20.0, 150.0, 600.0] {
            let r = |t: f64| Reference {
                x: amp * (omega * t).sin(),
                v: amp * omega * (omega * t).cos(),
                a: -amp * omega * omega * (omega * t).sin(),
            };
            let h = 2e-3 / omega;
            let mut s = AxisState::at_rest(&d, &r(0.0), 1.0);
            let period = TAU / omega;
            let settle = (1.0 / period).ceil() * period;
            let n = ((settle + 4.0 * period) / h).round() as usize;
            let (mut ps, mut pc, mut w) = (0.0, 0.0, 0.0);
            for i in 0..n {
                let t = (i + 1) as f64 * h;
                advance(&d, &mut s, &r, (t - h, h));
                if t > settle {
                    let x = r(t).x - s.e;
                    ps += x * (omega * t).sin();
                    pc += x * (omega * t).cos();
                    w += 0.5;
                }
            }
            let gain = (ps * ps + pc * pc).sqrt() / w / amp;
            let want = d.response(omega);
            assert!(
                (gain - want).abs() < 1e-4 * want,
                "ω = {omega}: integrated {gain}, response {want}"
            );
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn the_recorded_friction_is_eq2_at_the_travel_since_the_last_reversal() {
    // f = f_c·(2·tanh(a·|x′|) − 1)·sgn(ẋ′) (eq 2), x′ the travel of C's actual position since
    // its velocity last changed sign, found here from the recorded samples: the crossing by
    // linear interpolation of the velocity between two steps, the position there likewise.
    // Before the first motion the spring is unloaded: x′ starts at atanh(½)/a (f = 0).
    for v in [
        json!({"samples": 200000}),
        json!({"samples": 200000, "test": {"feed": 3000, "offset": 50}}),
    ] {
        let c = case(v.clone());
        let (_, tr) = every_step(v);
        let (fc, a) = (c.c.friction, c.c.friction_slope);
        let first = tr.c_velocity.iter().find(|v| **v != 0.0).unwrap().signum();
        let mut dir = first;
        let mut x_rev = tr.c_actual[0] - dir * 0.5f64.atanh() / a;
        let mut worst = 0.0f64;
        let mut reversals = 0;
        for i in 0..tr.time.len() {
            let (v0, v1) = (tr.c_velocity[i.saturating_sub(1)], tr.c_velocity[i]);
            if v1 * dir < 0.0 {
                let s = v0 / (v0 - v1);
                x_rev = tr.c_actual[i - 1] + s * (tr.c_actual[i] - tr.c_actual[i - 1]);
                dir = -dir;
                reversals += 1;
            }
            let want = fc * (2.0 * (a * (tr.c_actual[i] - x_rev).abs()).tanh() - 1.0) * dir;
            worst = worst.max((tr.c_friction[i] - want).abs());
        }
        assert!(reversals >= 1);
        assert!(worst < 1e-3 * fc, "friction off eq 2 by {worst} N·m");
    }
}

/// One step of `s` from `t0` to `t0 + h` following the command `r` (its values at the step's
/// start, middle and end, as the study's run gives them); the direction changes seen.
fn advance(
    d: &fiveaxis::reversal::drive::Drive,
    s: &mut fiveaxis::reversal::drive::AxisState,
    r: &dyn Fn(f64) -> fiveaxis::reversal::drive::Reference,
    (t0, h): (f64, f64),
) -> usize {
    s.step(d, (t0, h), [&r(t0), &r(t0 + h / 2.0), &r(t0 + h)], r)
}

/// A unit-inertia drive without damping or feed-forward: K_p = 30 1/s, a 40 Hz velocity loop
/// with a 15 ms integral time, the limit, f_c and a given.
fn unit_drive(limit: f64, fc: f64, slope: f64) -> fiveaxis::reversal::drive::Drive {
    let kv = TAU * 40.0;
    fiveaxis::reversal::drive::Drive {
        inertia: 1.0,
        kp: 30.0,
        kv,
        ki: kv / 0.015,
        damping: 0.0,
        limit,
        fc,
        slope,
        ff_velocity: false,
        ff_torque: false,
    }
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn the_integral_holds_while_the_torque_is_at_its_limit_and_the_error_pushes_on() {
    // A unit-inertia drive with a 5 N·m limit told to move at ±1 rad/s from rest: it saturates
    // for a while. Wherever the unclamped torque K_v·ε + K_i·z is beyond the limit with ε of its
    // sign at both ends of a step (ε = v_ref − v = K_p·e + ė − v_r, no feed-forward), the
    // integral z must not move; elsewhere it integrates ε.
    use fiveaxis::reversal::drive::{AxisState, Reference};
    let d = unit_drive(5.0, 0.0, 1.0);
    let kv = d.kv;
    for sign in [1.0, -1.0] {
        let r = |t: f64| Reference {
            x: sign * t,
            v: sign,
            a: 0.0,
        };
        let h = 1e-4;
        let mut s = AxisState::at_rest(&d, &r(0.0), sign);
        let pushing = |s: &AxisState, r: &Reference| {
            let eps = d.kp * s.e + s.ev - r.v;
            let raw = kv * eps + d.ki * s.z;
            raw.abs() > 1.5 * d.limit && eps * raw > 0.0
        };
        let (mut held, mut moved) = (0, 0);
        for i in 0..20000 {
            let t0 = i as f64 * h;
            let before = s;
            advance(&d, &mut s, &r, (t0, h));
            if pushing(&before, &r(t0)) && pushing(&s, &r(t0 + h)) {
                assert_eq!(s.z, before.z, "{sign}, step {i}: the integral wound up");
                held += 1;
            } else if s.z != before.z {
                moved += 1;
            }
        }
        assert!(
            held > 10 && moved > 10,
            "{sign}: held {held}, moved {moved}"
        );
    }
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn the_readers_limits_are_those_its_messages_state() {
    use fiveaxis::reversal::fit::parse_trace;
    // `far` points at 0°, 1°, … and `near` within ±10° of the reversal (175° on), the first
    // deviation `first` mm.
    let text = |far: usize, near: usize, first: f64| {
        let mut t = String::from("angle_deg,deviation_mm\n");
        for i in 0..far {
            let d = if i == 0 { first } else { 0.001 };
            t.push_str(&format!("{i},{d}\n"));
        }
        for i in 0..near {
            t.push_str(&format!("{},-0.002\n", 175.0 + i as f64 * 0.5));
        }
        t
    };
    // "at least 50" points, "at least 10" near the reversal, deviations up to 1 mm.
    let m = parse_trace(&text(40, 10, 1.0)).unwrap();
    assert_eq!(m.angle.len(), 50);
    assert_eq!(m.deviation[0], 1.0);
    assert!((m.angle[49] - 179.5f64.to_radians()).abs() < 1e-15);
    for (t, want) in [
        (text(39, 10, 0.0), "49 points: the fit needs at least 50"),
        (text(41, 9, 0.0), "9 points within ±10° of the reversal"),
        (text(40, 10, 1.0001), "deviation 1.0001 mm is over 1 mm"),
    ] {
        let e = parse_trace(&t).unwrap_err().to_string();
        assert!(e.contains(want), "{e}");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn a_step_over_a_reversal_puts_the_switch_where_the_velocity_crosses_zero() {
    // A drive with friction follows x_r = ±sin 2πt (SI) and turns round near t = 0.25 s. The
    // direction memory's position x′ = 0 (x_rev) after one step of H = 2 ms over the
    // crossing, against the same found with steps of 10 µs: the split at the linearly
    // interpolated crossing puts it within a small part of ½·|ẍ|·H² (the distance travelled
    // in a step from rest), where the crossing placed anywhere else in the step would not be.
    use fiveaxis::reversal::drive::{AxisState, Reference};
    let d = unit_drive(1e6, 5.0, 200.0);
    let w = TAU;
    for sign in [1.0, -1.0] {
        let r = |t: f64| Reference {
            x: sign * (w * t).sin(),
            v: sign * w * (w * t).cos(),
            a: -sign * w * w * (w * t).sin(),
        };
        let step = |s: &mut AxisState, t0: f64, h: f64| advance(&d, s, &r, (t0, h));
        // Fine: where the direction changes.
        let hf = 1e-5;
        let mut s = AxisState::at_rest(&d, &r(0.0), sign);
        let mut i = 0;
        while step(&mut s, i as f64 * hf, hf) == 0 {
            i += 1;
        }
        let (fine_rev, crossing) = (s.x_rev, i as f64 * hf);
        // Coarse: from the fine state 0.3·H or 0.7·H before the crossing, one step of H.
        let big = 2e-3;
        for lead in [0.3, 0.7] {
            let start = ((crossing - lead * big) / hf).round() as usize;
            let mut s = AxisState::at_rest(&d, &r(0.0), sign);
            for j in 0..start {
                assert_eq!(step(&mut s, j as f64 * hf, hf), 0);
            }
            // The fine run on to the end of the big step.
            let mut f = s;
            let sub = (big / hf).round() as usize;
            let turns: usize = (start..start + sub)
                .map(|j| step(&mut f, j as f64 * hf, hf))
                .sum();
            assert_eq!(turns, 1);
            assert_eq!(
                step(&mut s, start as f64 * hf, big),
                1,
                "the step holds the crossing"
            );
            // The state at its end: both sub-steps integrated with the command of their own times
            // (RK4 over 1 ms: far below the following error's change over the step, ė·H).
            let de = (s.e - f.e).abs();
            let dv = (s.ev - f.ev).abs();
            assert!(
                de < 1e-3 * f.ev.abs() * big,
                "{sign}, lead {lead}: e off by {de:e}"
            );
            assert!(
                dv < 1e-3 * w * w * big,
                "{sign}, lead {lead}: ė off by {dv:e}"
            );
            let scale = 0.5 * w * w * big * big;
            let off = (s.x_rev - fine_rev).abs();
            assert!(
                off < 1e-2 * scale,
                "{sign}, lead {lead}: x_rev off by {off:e} (scale {scale:e})"
            );
        }
    }
}

/// A measured trace of the points given, as the reader would return it (lines from 2).
fn measured(angle: Vec<f64>, deviation: Vec<f64>) -> fiveaxis::reversal::fit::Measured {
    let lines = (2..angle.len() + 2).collect();
    fiveaxis::reversal::fit::Measured {
        angle,
        deviation,
        lines,
        skipped: 0,
    }
}

/// The 95 % two-sided normal quantile.
const Z95: f64 = 1.959_963_984_540_054;

/// The case's trace at `angles` (rad), by the actual trace angle (linear between samples), plus
/// `offset` mm: what a ball bar of a slightly different length would record.
fn trace_at(c: &ReversalCase, angles: &[f64], offset: f64) -> Vec<f64> {
    let mut c = c.clone();
    c.samples = 10_000;
    let (_, tr) = simulate(&c).unwrap();
    angles
        .iter()
        .map(|x| {
            let i = tr
                .angle
                .partition_point(|v| v < x)
                .clamp(1, tr.angle.len() - 1);
            let (x0, x1) = (tr.angle[i - 1], tr.angle[i]);
            let (d0, d1) = (tr.deviation[i - 1], tr.deviation[i]);
            d0 + (d1 - d0) * (x - x0) / (x1 - x0) + offset
        })
        .collect()
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn a_fit_returns_the_truth_and_intervals_from_its_own_jacobian() {
    // A trace simulated with f_c = 12 N·m, a = 800 1/rad, K_p = 28 1/s and a ball bar 3 µm
    // long, with 0.2 µm of noise every 0.25°, fitted from the defaults (10, 500, 30): near the
    // truth. Then, at the fitted values: the 95 % intervals against σ²·(JᵀJ)⁻¹ with J by central differences
    // of the model in (ln f_c, ln a, ln K_p, offset) and σ² = Σr²/(n − 4); the fitted curve
    // is the trace less the residuals; the half-way travel is atanh(½)/a.
    use fiveaxis::reversal::fit::fit;
    use nalgebra::{Matrix4, Vector4};
    let params = |fc: f64, a: f64, kp: f64| {
        case(json!({"step": 0.5, "c": {"friction": fc, "frictionSlope": a, "positionGain": kp}}))
    };
    let angles: Vec<f64> = (1..1440).map(|i| (i as f64 * 0.25).to_radians()).collect();
    let mut rng = common::Rng::new(11);
    let deviation: Vec<f64> = trace_at(&params(12.0, 800.0, 28.0), &angles, 0.003)
        .iter()
        .map(|d| d + 2e-4 * rng.gauss())
        .collect();
    let n = angles.len();
    let f = fit(
        &params(10.0, 500.0, 30.0),
        &measured(angles.clone(), deviation.clone()),
    )
    .unwrap();
    // The truth within three standard deviations (the 95 % intervals' coverage is the
    // Monte-Carlo test's, in crate/tests/reversal/fit.rs).
    let z = Z95;
    for (e, truth) in [(f.fc, 12.0), (f.slope, 800.0), (f.kp, 28.0)] {
        let sd = (e.high / e.value).ln() / z;
        assert!(
            (e.value / truth).ln().abs() < 3.0 * sd,
            "{e:?} should be near {truth}"
        );
    }
    let sd = (f.offset.high - f.offset.value) / z;
    assert!((f.offset.value - 0.003).abs() < 3.0 * sd, "{:?}", f.offset);
    // The model at the fitted values and its Jacobian.
    let p = [
        f.fc.value.ln(),
        f.slope.value.ln(),
        f.kp.value.ln(),
        f.offset.value,
    ];
    let model = |p: [f64; 4]| trace_at(&params(p[0].exp(), p[1].exp(), p[2].exp()), &angles, p[3]);
    let at = model(p);
    let rss: f64 = deviation
        .iter()
        .zip(&at)
        .map(|(d, m)| (d - m).powi(2))
        .sum();
    let sigma2 = rss / (n - 4) as f64;
    assert!(
        (f.sigma * f.sigma / sigma2 - 1.0).abs() < 1e-3,
        "σ {} vs {}",
        f.sigma,
        sigma2.sqrt()
    );
    let mut cols = Vec::new();
    for k in 0..4 {
        let dk = if k < 3 { 1e-4 } else { 1e-6 };
        let (mut up, mut down) = (p, p);
        up[k] += dk;
        down[k] -= dk;
        let (mu, md) = (model(up), model(down));
        cols.push(
            mu.iter()
                .zip(&md)
                .map(|(u, d)| (u - d) / (2.0 * dk))
                .collect::<Vec<f64>>(),
        );
    }
    let jtj = Matrix4::from_fn(|i, j| cols[i].iter().zip(&cols[j]).map(|(a, b)| a * b).sum());
    let cov = jtj.try_inverse().unwrap() * sigma2;
    let sd = Vector4::from_fn(|k, _| cov[(k, k)].sqrt());
    for (k, e) in [f.fc, f.slope, f.kp].iter().enumerate() {
        assert!(
            (e.value * e.value / (e.low * e.high) - 1.0).abs() < 1e-9,
            "{e:?}"
        );
        let half = (e.high / e.value).ln() / z;
        assert!(
            (half / sd[k] - 1.0).abs() < 0.05,
            "{k}: σ_ln {half:e} vs {:e}",
            sd[k]
        );
    }
    let o = f.offset;
    assert!(((o.low + o.high) / 2.0 - o.value).abs() < 1e-12, "{o:?}");
    assert!(
        ((o.high - o.value) / z / sd[3] - 1.0).abs() < 0.05,
        "{o:?} vs σ {:e}",
        sd[3]
    );
    for i in 0..n {
        assert!((f.fitted[i] + f.residuals[i] - deviation[i]).abs() < 1e-15);
        assert!(
            (f.fitted[i] - at[i]).abs() < 1e-9,
            "{i}: {} vs {}",
            f.fitted[i],
            at[i]
        );
    }
    assert!((f.halfway - 0.5f64.atanh() / f.slope.value).abs() < 1e-15);
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn a_fit_needs_four_parameters_and_thirty_degrees_of_freedom() {
    // n − 4 ≥ 30 (fit's docs): 33 points are refused for their number, 34 and 60 are not.
    use fiveaxis::reversal::fit::fit;
    let c = case(json!({"step": 0.5}));
    for (n, refused) in [(33, true), (34, false), (60, false)] {
        let angle: Vec<f64> = (0..n)
            .map(|i| (170.0 + 20.0 * i as f64 / n as f64).to_radians())
            .collect();
        let deviation = trace_at(&c, &angle, 0.0);
        let said = fit(&c, &measured(angle, deviation))
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert_eq!(
            said.contains("too few points for the fit (at least 34)"),
            refused,
            "{n}: {said}"
        );
    }
    // Points past the model's last angle (the reader takes up to 390°) read the model's last
    // value (as a ball bar's trace that stops does): the fit of a trace running on to 370°,
    // with 0.2 µm of noise, finds f_c as any other, and does not fail.
    let angle: Vec<f64> = (0..740)
        .map(|i| (0.5 * i as f64 + 0.25).to_radians())
        .collect();
    let last = trace_at(&c, &[TAU], 0.0)[0];
    let mut rng = common::Rng::new(5);
    let deviation: Vec<f64> = trace_at(&c, &angle, 0.0)
        .iter()
        .zip(&angle)
        .map(|(d, a)| if *a < TAU { *d } else { last } + 2e-4 * rng.gauss())
        .collect();
    let f = fit(&c, &measured(angle, deviation)).unwrap();
    let sd = (f.fc.high / f.fc.value).ln() / Z95;
    assert!((f.fc.value / 10.0).ln().abs() < 3.0 * sd, "{:?}", f.fc);
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn the_path_is_its_velocitys_integral_from_rest_to_rest() {
    // Along the circle: s(t), ṡ and s̈ against central differences of each other, at rest
    // before 0 and after the end, the feed reached at the end of the acceleration time, the
    // circumference at the end.
    for (f, acc) in [(1000.0, 50.0), (3000.0, 400.0)] {
        let c = case(json!({"test": {"feed": f, "accelTime": acc}}));
        let m = c.motion().unwrap();
        let (v_f, ta) = (f / 60.0, acc * 1e-3);
        let dt = 1e-6;
        let n = 20_000;
        for i in 0..=n {
            let t = -0.01 + (m.duration + 0.02) * i as f64 / n as f64;
            let (p, lo, hi) = (m.path(t), m.path(t - dt), m.path(t + dt));
            let v = (hi.x - lo.x) / (2.0 * dt);
            let a = (hi.v - lo.v) / (2.0 * dt);
            assert!(
                (v - p.v).abs() < 1e-5 * v_f,
                "F = {f}, t = {t}: ṡ {} vs {v}",
                p.v
            );
            assert!(
                (a - p.a).abs() < 1e-4 * v_f / ta,
                "F = {f}, t = {t}: s̈ {} vs {a}",
                p.a
            );
        }
        // The ramps' closed form: half the feed half way, at rest at their far ends.
        assert!((m.path(ta / 2.0).v - v_f / 2.0).abs() < 1e-9 * v_f);
        assert!((m.path(m.duration - ta / 2.0).v - v_f / 2.0).abs() < 1e-9 * v_f);
        assert!(m.path(1e-9).v < 1e-6 * v_f && m.path(m.duration - 1e-9).v < 1e-6 * v_f);
        // C's and the axes' commands likewise, accelerations included (the ramps' too).
        let jets = |t: f64| {
            let c = m.commands(t);
            [c.c, c.linear[0], c.linear[1]]
        };
        let top = (0..=n)
            .map(|i| jets(m.duration * i as f64 / n as f64).map(|j| j.a.abs()))
            .fold([0.0f64; 3], |a, b| {
                [a[0].max(b[0]), a[1].max(b[1]), a[2].max(b[2])]
            });
        for i in 0..=n {
            let t = m.duration * i as f64 / n as f64;
            let (p, lo, hi) = (jets(t), jets(t - dt), jets(t + dt));
            for k in 0..3 {
                let a = (hi[k].v - lo[k].v) / (2.0 * dt);
                assert!(
                    (a - p[k].a).abs() < 1e-4 * top[k],
                    "F = {f}, t = {t}, {k}: {} vs {a}",
                    p[k].a
                );
            }
        }
        assert_eq!(m.path(-1.0), m.path(0.0));
        assert_eq!((m.path(0.0).x, m.path(0.0).v), (0.0, 0.0));
        assert!((m.path(ta).v - v_f).abs() < 1e-12 * v_f);
        // The ramp covers half the distance the feed would: s(ta) = v_f·ta/2.
        assert!((m.path(ta).x - v_f * ta / 2.0).abs() < 1e-9);
        let end = m.path(m.duration);
        assert!((end.x - TAU * 50.0).abs() < 1e-9 && end.v.abs() < 1e-12 && end.a.abs() < 1e-9);
        assert_eq!(m.path(m.duration + 1.0).x, end.x);
    }
}

// Found by cargo-mutants: a mutant in `crate/src/reversal/` survived every other test.
#[test]
fn a_fit_whose_interval_spans_more_than_a_factor_ten_is_refused() {
    // A small dent (f_c = 2 N·m) under 1 µm of noise: a's 95 % interval spans 14 to 476 1/rad
    // (a factor 34), so the fit refuses to give a and says why.
    use fiveaxis::reversal::fit::fit;
    let truth = case(json!({"step": 0.5, "c": {"friction": 2}}));
    let angle: Vec<f64> = (1..720).map(|i| (0.5 * i as f64).to_radians()).collect();
    let mut rng = common::Rng::new(7);
    let deviation: Vec<f64> = trace_at(&truth, &angle, 0.0)
        .iter()
        .map(|d| d + 1e-3 * rng.gauss())
        .collect();
    let e = fit(&case(json!({"step": 0.5})), &measured(angle, deviation)).unwrap_err();
    assert_eq!(e.field, "csv");
    assert!(
        e.message
            .contains("the trace hardly determines a: its 95 % interval spans"),
        "{e}"
    );
}
