//! Helpers of the wasm-bindgen tests: JSON input and the message of a thrown `Error`.

use wasm_bindgen::{JsCast, JsValue};

/// A JavaScript value from JSON text.
pub fn js(json: &str) -> JsValue {
    js_sys::JSON::parse(json).expect("valid JSON in the test")
}

/// The message of the JavaScript `Error` an export threw.
pub fn error_message(result: Result<JsValue, wasm_bindgen::JsError>) -> String {
    let err: JsValue = result.expect_err("the call must fail").into();
    let err: js_sys::Error = err.dyn_into().expect("a JavaScript Error");
    String::from(err.message())
}
