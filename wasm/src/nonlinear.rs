//! The one nonlinear-error export that is not declared in `fiveaxis::for_each_export!`: the bulk
//! kernel takes its moves as a `Float64Array` and gives one, without the per-number JSON reading
//! of a declared input (10⁶ moves are 4·10⁶ numbers).

use crate::js_error;
use fiveaxis::Error;
use js_sys::Float64Array;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

/// Bulk: the exact maximum error (mm) of many moves of one type. `moves` is a `Float64Array`
/// holding `[θk0, θm0, θk1, θm1]` in degrees per move (length a multiple of 4).
///
/// The parameters are taken as `JsValue` and checked here: wasm-bindgen does not check the
/// JavaScript types of `&str`, `f64` or slice parameters, and a wrong type must give an error.
#[wasm_bindgen(js_name = nonlinearMaxErrors)]
pub fn nonlinear_max_errors(
    #[wasm_bindgen(unchecked_param_type = "RotaryType")] rtype: JsValue,
    #[wasm_bindgen(unchecked_param_type = "number")] length: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array")] moves: JsValue,
) -> Result<Float64Array, JsError> {
    let name = rtype
        .as_string()
        .ok_or_else(|| js_error(Error::field("type", "expected a type name such as \"CAZ\"")))?;
    let length = length
        .as_f64()
        .ok_or_else(|| js_error(Error::field("length", "expected a number of mm")))?;
    let moves = moves.dyn_into::<Float64Array>().map_err(|_| {
        js_error(Error::field(
            "moves",
            "expected a Float64Array of [θk0, θm0, θk1, θm1] per move",
        ))
    })?;
    let values =
        fiveaxis::nonlinear::max_errors_mm(&name, length, &moves.to_vec()).map_err(js_error)?;
    Ok(Float64Array::from(values.as_slice()))
}
