//! The schema of every input (`fiveaxis::api::schema`), with the exports this crate writes by
//! hand added to the declared ones.

use crate::output;
use fiveaxis::schema::{describe, FieldInfo, Inputs};
use fiveaxis::toolpath::{ToolpathCase, ToolpathReadInput};
use wasm_bindgen::prelude::*;

fn fields<A: Inputs>() -> Vec<FieldInfo> {
    describe(A::FIELDS, "")
}

/// The schema of every input: the machine's fields, the error table and each export's fields,
/// with labels, plain-language help, units (mm, deg), limits and defaults. The page renders its
/// forms from it. Labels may hold `{K}`, `{M}` (the machine's rotary axes) and `{U}`, `{V}` (the
/// face's axes), which the page replaces.
#[wasm_bindgen(js_name = schema, unchecked_return_type = "Schema")]
pub fn schema() -> Result<JsValue, JsError> {
    output(&fiveaxis::api::schema(vec![
        // Positional arguments (type, length, a Float64Array of moves), no input object.
        ("nonlinearMaxErrors", Vec::new()),
        ("toolpathAnalyse", fields::<ToolpathCase>()),
        ("toolpathCompare", fields::<ToolpathCase>()),
        ("toolpathRefine", fields::<ToolpathCase>()),
        ("toolpathParse", fields::<ToolpathReadInput>()),
        ("toolpathWrite", fields::<ToolpathReadInput>()),
    ]))
}
