//! The reversal study through the JavaScript API: inputs refused with their paths, units at the
//! edge (degrees in and out), the ideal drive's exact circle, the dent's proportion to r, a
//! machine without a C table refused, and a simulated trace fitted back to its friction.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common;

use common::{error_message, jv, read};
use fiveaxis_wasm as fa;
use serde::Deserialize;
use serde_json::json;
use wasm_bindgen_test::wasm_bindgen_test;

#[derive(Deserialize)]
struct Dent {
    depth: f64,
    angle: f64,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Direction {
    name: String,
    reverses: bool,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Sim {
    #[serde(with = "serde_wasm_bindgen::preserve")]
    theta: js_sys::Float64Array,
    #[serde(with = "serde_wasm_bindgen::preserve")]
    angle: js_sys::Float64Array,
    #[serde(with = "serde_wasm_bindgen::preserve")]
    deviation: js_sys::Float64Array,
    #[serde(with = "serde_wasm_bindgen::preserve")]
    c_command: js_sys::Float64Array,
    dent: Dent,
    directions: Vec<Direction>,
    step_check: Option<serde_json::Value>,
}

#[wasm_bindgen_test]
fn reversal_inputs_are_refused_with_their_paths() {
    for (input, want) in [
        (json!({"colour": 1}), "colour: unknown input"),
        (json!({"c": {"frction": 1}}), "c.frction: unknown input"),
        (json!({"test": {"feed": -5}}), "test.feed:"),
        (
            json!({"test": {"radius": "50"}}),
            "test.radius: expected a number",
        ),
        (
            json!({"machine": {"type": "ABZ"}}),
            "machine.type: the reversal test needs a rotary table C",
        ),
        (
            json!({"machine": {"kind": "head-head", "type": "CAZ"}}),
            "machine.type: the reversal test needs a rotary table C",
        ),
    ] {
        let m = error_message(fa::reversalSimulate(jv(&input)));
        assert!(m.starts_with(want), "{input}: {m}");
    }
    let m = error_message(fa::reversalFit(jv(&json!({}))));
    assert!(m.starts_with("csv: is required"), "{m}");
    let m = error_message(fa::reversalFit(jv(
        &json!({"csv": "angle_deg,deviation_mm\n1,x\n"}),
    )));
    assert!(
        m.starts_with("csv: line 2: deviation \"x\" is not a number"),
        "{m}"
    );
    let m = error_message(fa::reversalDents(jv(&json!({"checkStep": true}))));
    assert!(m.starts_with("checkStep: unknown input"), "{m}");
}

#[wasm_bindgen_test]
fn angles_cross_in_degrees_and_the_ideal_drive_traces_the_circle() {
    let r: Sim = read(fa::reversalSimulate(jv(&json!({
        "feedForward": "full", "c": {"friction": 0},
        "test": {"feed": 3000, "reversalAngle": 45}, "checkStep": true,
    }))));
    let theta = r.theta.to_vec();
    assert!((theta.last().unwrap() - 360.0).abs() < 1e-6);
    let c = r.c_command.to_vec();
    let peak = c.iter().copied().fold(f64::MIN, f64::max);
    assert!((peak - 45.0).abs() < 1e-3, "C peaks at {peak}°");
    let worst = r
        .deviation
        .to_vec()
        .iter()
        .fold(0.0f64, |a, b| a.max(b.abs()));
    assert!(worst < 1e-9, "{worst}");
    assert!(r.step_check.is_some());
    assert!(
        r.directions.iter().all(|d| !d.reverses),
        "{:?}",
        r.directions.iter().map(|d| &d.name).collect::<Vec<_>>()
    );
}

#[wasm_bindgen_test]
fn the_dent_doubles_with_r() {
    let depth = |r: f64| -> Dent {
        let s: Sim = read(fa::reversalSimulate(jv(
            &json!({"test": {"offset": r, "feed": 3000}, "step": 0.5}),
        )));
        s.dent
    };
    let (a, b) = (depth(25.0), depth(50.0));
    assert!(
        (b.depth / a.depth - 2.0).abs() < 0.1,
        "{} {}",
        a.depth,
        b.depth
    );
    assert!((180.0..190.0).contains(&a.angle), "{}", a.angle);
}

#[derive(Deserialize)]
struct Est {
    value: f64,
    low: f64,
    high: f64,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Fit {
    friction: Est,
    friction_slope: Est,
    position_gain: Est,
    halfway: f64,
    rated_torque: f64,
    friction_share: f64,
    torque_step: Est,
    torque_step_share: f64,
}

#[wasm_bindgen_test]
fn a_simulated_trace_fits_back_to_its_friction() {
    // A trace simulated through the API with f_c = 12 N·m, a = 800 1/rad, K_p = 28 1/s (F =
    // 3000 mm/min and a 1 ms step keep this quick in an unoptimised build), written as the CSV
    // a user would load, fitted from f_c = 8, a = 500, K_p = 30: without noise the fit must
    // land on the values simulated. (crate/tests/reversal/fit.rs fits the noisy sample file.)
    let case = json!({"test": {"feed": 3000}, "step": 1.0,
                      "c": {"friction": 12, "frictionSlope": 800, "positionGain": 28}});
    let s: Sim = read(fa::reversalSimulate(jv(&case)));
    let (angle, dev) = (s.angle.to_vec(), s.deviation.to_vec());
    let mut csv = String::from("angle_deg,deviation_um\n");
    let mut last = f64::MIN;
    for (a, d) in angle.iter().zip(&dev) {
        if *a > last + 0.05 && *a > 0.0 && *a < 360.0 {
            csv.push_str(&format!("{a},{}\n", d * 1e3));
            last = *a;
        }
    }
    let start = json!({"test": {"feed": 3000}, "step": 1.0, "csv": csv,
                       "c": {"friction": 8, "frictionSlope": 500, "positionGain": 30}});
    let f: Fit = read(fa::reversalFit(jv(&start)));
    // The drive's terms: the default rated torque 250 N·m, the step 2·f_c with its interval.
    assert_eq!(f.rated_torque, 250.0);
    assert!((f.friction_share - f.friction.value / 250.0).abs() < 1e-15);
    assert!((f.torque_step.value - 2.0 * f.friction.value).abs() < 1e-12);
    assert!((f.torque_step.low - 2.0 * f.friction.low).abs() < 1e-12);
    assert!((f.torque_step.high - 2.0 * f.friction.high).abs() < 1e-12);
    assert!((f.torque_step_share - 2.0 * f.friction.value / 250.0).abs() < 1e-15);
    for (e, v) in [
        (&f.friction, 12.0),
        (&f.friction_slope, 800.0),
        (&f.position_gain, 28.0),
    ] {
        assert!((e.value / v - 1.0).abs() < 0.01, "{} for {v}", e.value);
        assert!(e.low <= e.value && e.value <= e.high);
    }
    // atanh(1/2)/a in degrees.
    let want = 0.5f64.atanh() / 800.0 * 180.0 / std::f64::consts::PI;
    assert!((f.halfway / want - 1.0).abs() < 0.01, "{}", f.halfway);
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct MeasuredDent {
    baseline: f64,
    depth: f64,
    angle: f64,
    width: f64,
    open: bool,
}

#[derive(Deserialize)]
struct Trace {
    machine: Option<String>,
    points: usize,
    dent: MeasuredDent,
    duration: f64,
}

#[wasm_bindgen_test]
fn a_trace_s_dent_crosses_in_degrees_and_its_machine_is_named() {
    // A 2 µm level and a triangular dent 6 µm deep at 182°, its base 3° wide (1.5° at half
    // depth), every 0.1°, in µm with a decimal comma.
    let mut csv =
        String::from("# machine: A/C trunnion table, vertical spindle\nangle_deg;deviation_um\n");
    for i in 1..3600 {
        let a = i as f64 * 0.1;
        let d = 2.0 - 6.0 * (1.0 - (a - 182.0).abs() / 1.5).max(0.0);
        csv.push_str(&format!("{a:.1};{d}\n").replace('.', ","));
    }
    let t: Trace = read(fa::reversalTrace(jv(
        &json!({"csv": csv, "test": {"radius": 40, "feed": 2000}}),
    )));
    assert_eq!(
        t.machine.as_deref(),
        Some("A/C trunnion table, vertical spindle")
    );
    assert_eq!(t.points, 3599);
    assert!((t.dent.baseline - 0.002).abs() < 1e-12);
    assert!((t.dent.depth - 0.006).abs() < 1e-12, "{}", t.dent.depth);
    assert!((t.dent.angle - 182.0).abs() < 1e-9);
    assert!((t.dent.width - 1.5).abs() < 1e-9, "{}", t.dent.width);
    assert!(!t.dent.open);
    // W·R/F in s: 1.5° on a 40 mm circle at 2000 mm/min.
    let want = 1.5f64.to_radians() * 40.0 / (2000.0 / 60.0);
    assert!((t.duration - want).abs() < 1e-12, "{}", t.duration);
    let m = error_message(fa::reversalTrace(jv(
        &json!({"csv": "angle_deg,deviation_mm\n"}),
    )));
    // A header and no point: refused, the message naming the line (the one trace reader,
    // ballbar::read, shared with the ball-bar tests).
    assert!(
        m.starts_with("csv: line 1: the header is not followed by any point"),
        "{m}"
    );
}
