//! Helpers of the wasm-bindgen tests: JSON input, the message of a thrown `Error`, the page's
//! machine presets and the sample file.
#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use wasm_bindgen::{JsCast, JsValue};

/// A JavaScript value from JSON text.
pub fn js(json: &str) -> JsValue {
    js_sys::JSON::parse(json).expect("valid JSON in the test")
}

/// A JavaScript value from a `serde_json` value.
pub fn jv(v: &serde_json::Value) -> JsValue {
    js(&v.to_string())
}

/// The message of the JavaScript `Error` an export threw.
pub fn error_message(result: Result<JsValue, wasm_bindgen::JsError>) -> String {
    let err: JsValue = result.expect_err("the call must fail").into();
    let err: js_sys::Error = err.dyn_into().expect("a JavaScript Error");
    String::from(err.message())
}

/// A result object read back into `T`.
pub fn read<T: serde::de::DeserializeOwned>(result: Result<JsValue, wasm_bindgen::JsError>) -> T {
    serde_wasm_bindgen::from_value(result.expect("valid input")).expect("the documented shape")
}

/// The page's machine presets (public/presets/machines.json).
pub const PRESETS: &str = include_str!("../../../public/presets/machines.json");
/// The sample measurement file.
pub const SAMPLE: &str = include_str!("../../../public/samples/sshape-measured.csv");

/// The machine object of the preset whose name starts with `prefix`.
pub fn preset(prefix: &str) -> serde_json::Value {
    let all: serde_json::Value = serde_json::from_str(PRESETS).expect("valid JSON");
    all["presets"]
        .as_array()
        .expect("presets")
        .iter()
        .find(|p| p["name"].as_str().is_some_and(|n| n.starts_with(prefix)))
        .expect("a preset of that name")["machine"]
        .clone()
}

pub const LI: &str = "B/C tilting table, vertical spindle (Li et al. 2021)";
pub const CHANAL: &str = "B swivel head, C rotary table, Y under the table";
pub const TRUNNION: &str = "A/C trunnion table";
pub const FORK: &str = "A/C fork head";
