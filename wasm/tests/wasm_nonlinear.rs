//! The exported JavaScript API, run as WebAssembly in headless Node (`wasm-pack test --node`).
//! Inputs are JSON-like objects as a script would pass them; results are read back into typed
//! structs before asserting, and bad input must come back as a JavaScript `Error` with a message.
#![cfg(target_arch = "wasm32")]

mod common;

use common::wasm::{error_message, js};
use fiveaxis::wasm;
use serde::Deserialize;
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::wasm_bindgen_test;

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct MoveOut {
    max: f64,
    u_at_max: f64,
    approx: Option<f64>,
    closed_form: Option<f64>,
    reference: String,
    #[serde(with = "serde_wasm_bindgen::preserve")]
    delta: js_sys::Float64Array,
}

#[wasm_bindgen_test]
fn nonlinear_move_at_the_pole_matches_eq26_and_its_exact_curve() {
    // Group I (CAZ) from θm = 0 with Δθk = Δθm = 40°: the maximum is at u = 0.5 and equals
    // eq 26, L·sin²(20°) (closed form, computed here, not by the engine).
    let out = wasm::nonlinear_move(js(
        r#"{"type":"CAZ","length":200,"start":{"k":10,"m":0},"end":{"k":50,"m":40},"samples":5}"#,
    ))
    .expect("valid input");
    let r: MoveOut = serde_wasm_bindgen::from_value(out).expect("result shape");
    let expected = 200.0 * 20f64.to_radians().sin().powi(2);
    assert!((r.max - expected).abs() < 1e-9, "{} vs {expected}", r.max);
    assert!((r.u_at_max - 0.5).abs() < 1e-7);
    assert!((r.closed_form.expect("starts at the pole") - expected).abs() < 1e-9);
    assert!((r.approx.expect("plane") - expected).abs() < 1e-9);
    assert_eq!(r.reference, "plane");
    let delta = r.delta.to_vec();
    assert_eq!(delta.len(), 5);
    // δ(u) = L |sin(u Δm) sin((1-u) Δk)| at u = 0.25.
    let d = 40f64.to_radians();
    let at_quarter = 200.0 * ((0.25 * d).sin() * (0.75 * d).sin()).abs();
    assert!((delta[1] - at_quarter).abs() < 1e-9);
}

#[wasm_bindgen_test]
fn bad_input_comes_back_as_an_error_naming_the_field() {
    let cases = [
        (
            r#"{"type":"CAZ","length":-5,"start":{"k":0,"m":0},"end":{"k":1,"m":1}}"#,
            "length:",
        ),
        (
            r#"{"type":"CAZ","length":5,"start":{"k":"ten","m":0},"end":{"k":1,"m":1}}"#,
            "start.k:",
        ),
        (
            r#"{"type":"CAZ","length":5,"start":{"k":0,"m":0}}"#,
            "missing field `end`",
        ),
        (
            r#"{"type":"CAX","length":5,"start":{"k":0,"m":0},"end":{"k":1,"m":1}}"#,
            "type",
        ),
        (
            r#"{"type":"CAZ","length":5,"start":{"k":1e9,"m":0},"end":{"k":1,"m":1}}"#,
            "start.k:",
        ),
        (
            r#"{"type":"CAZ","lenght":5,"start":{"k":0,"m":0},"end":{"k":1,"m":1}}"#,
            "missing field `length`",
        ),
    ];
    for (input, expected) in cases {
        let msg = error_message(wasm::nonlinear_move(js(input)));
        assert!(msg.contains(expected), "{input} -> {msg}");
    }
    // NaN and Infinity cannot be written in JSON; build them directly.
    let obj = js(r#"{"type":"CAZ","length":5,"start":{"k":0,"m":0},"end":{"k":1,"m":1}}"#);
    js_sys::Reflect::set(&obj, &"length".into(), &JsValue::from_f64(f64::NAN)).expect("set");
    assert!(error_message(wasm::nonlinear_move(obj)).starts_with("length:"));
    assert!(error_message(wasm::nonlinear_move(JsValue::UNDEFINED)).starts_with("input:"));
}

#[wasm_bindgen_test]
fn inverse_kinematics_reproduces_table_2_of_the_cubic_test() {
    // B/C tilting-rotary table = type CBZ: zone II-2 tool vector (0, 1/2, √3/2) is B = 30°, C = 90°.
    #[derive(Deserialize)]
    struct Pose {
        k: f64,
        m: f64,
    }
    #[derive(Deserialize)]
    struct Out {
        chosen: Pose,
        singular: bool,
    }
    let out = wasm::inverse_kinematics(js(r#"{"type":"CBZ","vector":[0,0.5,0.8660254037844386]}"#))
        .expect("valid");
    let r: Out = serde_wasm_bindgen::from_value(out).expect("shape");
    assert!(!r.singular);
    assert!((r.chosen.k - 90.0).abs() < 1e-9 && (r.chosen.m - 30.0).abs() < 1e-9);
    let out = wasm::inverse_kinematics(js(
        r#"{"type":"CBZ","vector":[0,0,1],"previous":{"k":33,"m":1}}"#,
    ))
    .expect("valid");
    let r: Out = serde_wasm_bindgen::from_value(out).expect("shape");
    assert!(r.singular && r.chosen.k == 33.0);
    assert!(error_message(wasm::inverse_kinematics(js(
        r#"{"type":"CBZ","vector":[0,0]}"#
    )))
    .starts_with("vector:"));
}

#[wasm_bindgen_test]
fn sweeps_and_grid_have_the_documented_shapes() {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct Grid {
        nx: usize,
        ny: usize,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        max: js_sys::Float64Array,
        u_at_max: Vec<Option<f64>>,
    }
    let out = wasm::nonlinear_grid(js(
        r#"{"type":"CAZ","length":1,"thetaM":0,"dK":{"from":0,"to":90},"dM":{"from":0,"to":60},"nx":4,"ny":3}"#,
    ))
    .expect("valid");
    let g: Grid = serde_wasm_bindgen::from_value(out).expect("shape");
    assert_eq!(
        (g.nx, g.ny, g.max.length(), g.u_at_max.len()),
        (4, 3, 12, 12)
    );
    // Row iy = 2 (Δθm = 60°), column ix = 2 (Δθk = 60°): equal increments at the pole, so the
    // maximum is sin²(30°) = 0.25 at u = 0.5. Row 0 (Δθm = 0) has no error and no argmax.
    let max = g.max.to_vec();
    assert!((max[2 * 4 + 2] - 0.25).abs() < 1e-12);
    assert!((g.u_at_max[2 * 4 + 2].expect("defined") - 0.5).abs() < 1e-7);
    assert!(g.u_at_max[1].is_none() && max[1] == 0.0);

    let k = wasm::nonlinear_sweep_k(js(
        r#"{"type":"BCX","length":10,"thetaM":10,"dK":30,"dM":15,"from":-180,"to":180,"n":7}"#,
    ))
    .expect("valid");
    let max: js_sys::Float64Array = js_sys::Reflect::get(&k, &"max".into()).expect("max").into();
    let v = max.to_vec();
    assert!(
        v.iter().all(|x| (x - v[0]).abs() < 1e-10),
        "Fig 4: constant in θk"
    );

    let types = wasm::nonlinear_compare_types(js(
        r#"{"length":1,"start":{"k":0,"m":10},"end":{"k":30,"m":25}}"#,
    ))
    .expect("valid");
    assert_eq!(js_sys::Array::from(&types).length(), 12);
    assert!(error_message(wasm::nonlinear_sweep_m(js(
        r#"{"type":"CAZ","length":1,"dM":30,"ratios":[],"from":-180,"to":180,"n":10}"#
    )))
    .starts_with("ratios.length:"));
}

#[wasm_bindgen_test]
fn bulk_max_errors_rejects_ragged_input() {
    let moves = |v: &[f64]| JsValue::from(js_sys::Float64Array::from(v));
    let ok = wasm::nonlinear_max_errors("CAZ".into(), 2.0.into(), moves(&[0.0, 0.0, 40.0, 40.0]))
        .expect("valid");
    assert!((ok.to_vec()[0] - 2.0 * 20f64.to_radians().sin().powi(2)).abs() < 1e-9);
    let err: JsValue =
        wasm::nonlinear_max_errors("CAZ".into(), 2.0.into(), moves(&[0.0, 1.0, 2.0]))
            .expect_err("ragged")
            .into();
    let err: js_sys::Error = err.dyn_into().expect("Error");
    assert!(String::from(err.message()).starts_with("moves:"));
    // Wrong JavaScript types are errors too, not undefined behaviour.
    for (t, l, m, field) in [
        (JsValue::from_f64(1.0), 2.0.into(), moves(&[]), "type"),
        ("CAZ".into(), "2".into(), moves(&[]), "length"),
        (
            "CAZ".into(),
            2.0.into(),
            js_sys::Array::new().into(),
            "moves",
        ),
    ] {
        let err: JsValue = wasm::nonlinear_max_errors(t, l, m)
            .expect_err("wrong type")
            .into();
        let err: js_sys::Error = err.dyn_into().expect("Error");
        assert!(String::from(err.message()).starts_with(field), "{field}");
    }
}
