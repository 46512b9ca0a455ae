//! The cubic-machining exports as WebAssembly in headless Node: inputs as a script writes them
//! (mm and degrees), results read back into typed structs, bad input as a JavaScript `Error`.
#![cfg(target_arch = "wasm32")]

mod common;

use common::wasm::{error_message, js};
use fiveaxis::wasm;
use serde::Deserialize;
use wasm_bindgen::JsValue;
use wasm_bindgen_test::wasm_bindgen_test;

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Zone {
    name: String,
    b: f64,
    c: f64,
    height: f64,
    linear_height: f64,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct TestOut {
    zones: Vec<Zone>,
    error_keys: Vec<String>,
    #[serde(with = "serde_wasm_bindgen::preserve")]
    k_height: js_sys::Float64Array,
    #[serde(with = "serde_wasm_bindgen::preserve")]
    single: js_sys::Float64Array,
    transform: bool,
    reference: String,
}

const TABLE5: &str = r#"{"dxBY":0.0146,"dyBY":-0.0089,"dzBY":-0.0142,"alphaBY":-0.0023,"betaBY":0.0029,"gammaBY":-0.00002,"alphaCB":-0.00017,"dxCB":0.0094}"#;

#[wasm_bindgen_test]
fn cubic_errors_lists_the_eight_errors_and_their_mapping() {
    #[derive(Deserialize)]
    struct Info {
        key: String,
        iso: String,
        unit: String,
    }
    let list: Vec<Info> =
        serde_wasm_bindgen::from_value(wasm::cubic_errors().expect("no input")).expect("shape");
    let keys: Vec<&str> = list.iter().map(|i| i.key.as_str()).collect();
    assert_eq!(
        keys,
        ["dxBY", "dyBY", "dzBY", "alphaBY", "betaBY", "gammaBY", "alphaCB", "dxCB"]
    );
    assert_eq!(list[6].iso, "E_A0C");
    assert_eq!(
        (list[0].unit.as_str(), list[3].unit.as_str()),
        ("mm", "deg")
    );
}

#[wasm_bindgen_test]
fn cubic_test_on_the_table_5_machine() {
    let out = wasm::cubic_test(js(&format!(r#"{{"errors":{TABLE5}}}"#))).expect("valid input");
    let r: TestOut = serde_wasm_bindgen::from_value(out).expect("result shape");
    assert!(r.transform && r.reference == "workpiece");
    assert_eq!(r.error_keys.len(), 8);
    let names: Vec<&str> = r.zones.iter().map(|z| z.name.as_str()).collect();
    assert_eq!(
        names,
        ["I", "II-1", "II-2", "II-3", "II-4", "III-1", "III-2", "III-3", "III-4"]
    );
    // Table 2.
    let c: Vec<f64> = r.zones.iter().map(|z| z.c).collect();
    for (got, want) in c
        .iter()
        .zip([0.0, 0.0, 90.0, 180.0, 270.0, 45.0, 135.0, 225.0, 315.0])
    {
        assert!((got - want).abs() < 1e-9, "{got} vs {want}");
    }
    assert!(r.zones[0].b.abs() < 1e-12 && (r.zones[1].b - 30.0).abs() < 1e-9);
    // With M_WC, ZONE I is exact; II-1 (C = 0°) feels only δxBY (−sin 30° per mm) and δzBY
    // (cos 30° − 1 per mm) to first order (closed forms of eq 10).
    assert!(r.zones[0].height.abs() < 1e-15);
    let ii1 = -0.5 * 0.0146 + (30f64.to_radians().cos() - 1.0) * -0.0142;
    assert!((r.zones[1].linear_height - ii1).abs() < 1e-12);
    assert!(
        (r.zones[1].height - ii1).abs() < 1e-7,
        "{}",
        r.zones[1].height
    );
    // k per degree at this edge: αBY at II-2 (C = 90°) is ρ·sin C = 16 mm/rad.
    let k = r.k_height.to_vec();
    assert_eq!(k.len(), 72);
    assert!((k[2 * 8 + 3] - 16f64.to_radians()).abs() < 1e-9);
    assert!((k[8] + 0.5).abs() < 1e-12, "δxBY at II-1");
    // The single-error table: δzBY alone at II-1 is exactly linear (a translation).
    let single = r.single.to_vec();
    assert!((single[8 + 2] - (30f64.to_radians().cos() - 1.0) * -0.0142).abs() < 1e-12);

    // Without M_WC, ZONE I moves with δzBY (k = +1 per mm).
    let out = wasm::cubic_test(js(
        r#"{"errors":{"dzBY":0.01},"transform":false,"reference":"workpiece"}"#,
    ))
    .expect("valid");
    let r: TestOut = serde_wasm_bindgen::from_value(out).expect("shape");
    assert!((r.zones[0].height - 0.01).abs() < 1e-12);
}

#[wasm_bindgen_test]
fn cubic_height_map_has_the_documented_shape() {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct MapOut {
        nx: usize,
        ny: usize,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        x: js_sys::Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        height: js_sys::Float64Array,
        zone_average: Vec<f64>,
        min: f64,
        max: f64,
        scallop: f64,
    }
    let out = wasm::cubic_height_map(js(
        r#"{"errors":{},"setup":{"zoneSize":4,"pick":0.5},"nx":13,"ny":25}"#,
    ))
    .expect("valid");
    let m: MapOut = serde_wasm_bindgen::from_value(out).expect("shape");
    assert_eq!(
        (m.nx, m.ny, m.height.length(), m.x.length()),
        (13, 25, 325, 13)
    );
    assert_eq!(m.zone_average.len(), 9);
    let x = m.x.to_vec();
    assert!((x[0] + 6.0).abs() < 1e-12 && (x[12] - 6.0).abs() < 1e-12);
    // No errors: the face lies between the passes' bottoms (0) and the scallop tops.
    let r = 3.0f64;
    let scallop = r - (r * r - 0.25f64 * 0.25).sqrt();
    assert!((m.scallop - scallop).abs() < 1e-15);
    assert!(
        m.min >= -1e-12 && m.max <= scallop + 1e-12,
        "{} {}",
        m.min,
        m.max
    );
}

#[wasm_bindgen_test]
fn bad_input_comes_back_as_an_error_naming_the_field() {
    let cases = [
        (r#"{"errors":{"dzBY":"abc"}}"#, "errors.dzBY:"),
        (r#"{"errors":{"alphaBY":6}}"#, "errors.alphaBY:"),
        (r#"{"errors":{"dxBy":0.01}}"#, "unknown field `dxBy`"),
        (r#"{"errors":{},"setup":{"pick":-1}}"#, "setup.pick:"),
        (
            r#"{"errors":{},"setup":{"workpieceHeight":0}}"#,
            "setup.workpieceHeight:",
        ),
        (r#"{"errors":{},"reference":"zone2"}"#, "reference:"),
        (r#"{"errors":{},"transform":"yes"}"#, "transform:"),
        (
            r#"{"errors":{},"setup":{"zonesize":10}}"#,
            "setup: unknown field `zonesize`",
        ),
        (r#"{"errors":{"dxBY":null}}"#, "errors.dxBY:"),
        (r#"{"setup":{}}"#, "missing field `errors`"),
    ];
    for (input, expected) in cases {
        let msg = error_message(wasm::cubic_test(js(input)));
        assert!(msg.contains(expected), "{input} -> {msg}");
    }
    let msg = error_message(wasm::cubic_height_map(js(
        r#"{"errors":{},"nx":3,"ny":10}"#,
    )));
    assert!(msg.starts_with("nx:"), "{msg}");
    let msg = error_message(wasm::cubic_height_map(js(r#"{"errors":{},"nx":10}"#)));
    assert!(msg.contains("missing field `ny`"), "{msg}");
    // NaN cannot be written in JSON; build it directly.
    let obj = js(r#"{"errors":{"betaBY":0}}"#);
    let errors = js_sys::Reflect::get(&obj, &"errors".into()).expect("get");
    js_sys::Reflect::set(&errors, &"betaBY".into(), &JsValue::from_f64(f64::NAN)).expect("set");
    assert!(error_message(wasm::cubic_test(obj)).starts_with("errors.betaBY:"));
    assert!(error_message(wasm::cubic_test(JsValue::UNDEFINED)).starts_with("input:"));
}
