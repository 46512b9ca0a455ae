//! Exports of the toolpath study (`fiveaxis::toolpath::export`): the path's typed arrays copied
//! in, the engine called, its result written out. Each takes a path (a second argument that
//! may be a `Float64Array` of 10⁶ points, copied as it is, never through JSON), so they are
//! written here rather than declared in `fiveaxis::for_each_export!`. The reader is a class,
//! fed piece by piece.

use crate::{js_error, json, output, to_json, Path};
use fiveaxis::toolpath::export::{self, Part, PathInput, PathValue, Reading};
use fiveaxis::toolpath::{ToolpathCase, ToolpathReadInput};
use fiveaxis::Error;
use js_sys::{Float64Array, JsString, Object, Reflect, Uint8Array};
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

/// A part of a path: a typed array copied, anything else as JSON (at `key`).
fn part(v: &JsValue, key: &str) -> Result<Part, Error> {
    if let Some(a) = v.dyn_ref::<Float64Array>() {
        Ok(Part::Float64(a.to_vec()))
    } else if let Some(a) = v.dyn_ref::<Uint8Array>() {
        Ok(Part::Uint8(a.to_vec()))
    } else {
        to_json(v, Path::Key(&Path::Root, key), 1).map(Part::Json)
    }
}

/// A path from JavaScript (`ToolpathPath | Float64Array`), read and checked by the engine.
fn read_path(value: &JsValue) -> Result<PathInput, JsError> {
    let read = if let Some(a) = value.dyn_ref::<Float64Array>() {
        PathInput::read(PathValue::Points(a.to_vec()))
    } else if value.is_object()
        && !value.is_function()
        && !js_sys::Array::is_array(value)
        && !js_sys::ArrayBuffer::is_view(value)
    {
        let obj: &Object = value.unchecked_ref();
        let keys = Object::keys(obj)
            .iter()
            .map(|k| k.as_string().unwrap_or_default())
            .collect();
        let get = |k: &str| {
            part(
                &Reflect::get(obj, &JsValue::from_str(k)).unwrap_or(JsValue::UNDEFINED),
                k,
            )
        };
        PathInput::read(PathValue::Object { keys, get: &get })
    } else {
        PathInput::read(PathValue::Other)
    };
    read.map_err(js_error)
}

fn case(value: &JsValue) -> Result<ToolpathCase, JsError> {
    ToolpathCase::read(&json(value)?).map_err(js_error)
}

/// The path on the machine: its commands, each segment's nonlinear error and where, flips and
/// pole passages, the rapids apart, and the totals of the cutting segments.
#[wasm_bindgen(js_name = toolpathAnalyse, unchecked_return_type = "ToolpathAnalysis")]
pub fn toolpath_analyse(
    #[wasm_bindgen(unchecked_param_type = "ToolpathCase")] value: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolpathPath | Float64Array")] path: JsValue,
) -> Result<JsValue, JsError> {
    let c = case(&value)?;
    output(&export::analyse(&c, &read_path(&path)?).map_err(js_error)?)
}

/// The path on each of the twelve rotary-axis types (the machine's kind, geometry, senses and
/// travel), or on `types` (names such as `"CAZ"`) when given, ranked: those that follow the whole
/// path first, by largest δ of the cutting segments (each row's `rank`).
#[wasm_bindgen(js_name = toolpathCompare, unchecked_return_type = "ToolpathSummary[]")]
pub fn toolpath_compare(
    #[wasm_bindgen(unchecked_param_type = "ToolpathCase")] value: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolpathPath | Float64Array")] path: JsValue,
    #[wasm_bindgen(unchecked_param_type = "RotaryType[] | undefined")] types: JsValue,
) -> Result<JsValue, JsError> {
    let c = case(&value)?;
    let p = read_path(&path)?;
    output(&export::compare(&c, &p, &json(&types)?).map_err(js_error)?)
}

/// The path with the fewest equally spaced points inserted into each cutting segment above the
/// tolerance, so that every piece stays within it on the machine; rapids are left as they are.
#[wasm_bindgen(js_name = toolpathRefine, unchecked_return_type = "ToolpathRefined")]
pub fn toolpath_refine(
    #[wasm_bindgen(unchecked_param_type = "ToolpathCase")] value: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolpathPath | Float64Array")] path: JsValue,
) -> Result<JsValue, JsError> {
    let c = case(&value)?;
    output(&export::refine(&c, &read_path(&path)?).map_err(js_error)?)
}

/// Writes a path in a format: CSV, APT, or ISO NC blocks for the machine, for which the path's
/// `angles` (`[K, M]` degrees per point, e.g. a refined path's) are needed; rapids are written
/// as rapids (`RAPID`, `G0`).
#[wasm_bindgen(js_name = toolpathWrite)]
pub fn toolpath_write(
    #[wasm_bindgen(unchecked_param_type = "ToolpathReadInput")] options: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolpathPath | Float64Array")] path: JsValue,
) -> Result<String, JsError> {
    let o = ToolpathReadInput::read(&json(&options)?).map_err(js_error)?;
    export::write_path(&o, &read_path(&path)?).map_err(js_error)
}

/// Reads a toolpath file piece by piece, so that a large file never needs to be one string:
/// `new ToolpathReader({format, machine, unit, aptFrame, chordTolerance})`, then `feed(text)`
/// for each piece (pieces may split lines anywhere; returns the lines read so far), then
/// `finish()`. A bad line throws an Error `"toolpath: line 12, column 7: …"`.
#[wasm_bindgen]
pub struct ToolpathReader(Reading);

#[wasm_bindgen]
impl ToolpathReader {
    /// A reader for the format and machine of `options` (`format` `"auto"` recognises it from
    /// the first piece).
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "ToolpathReadInput")] options: JsValue,
    ) -> Result<ToolpathReader, JsError> {
        let options = ToolpathReadInput::read(&json(&options)?).map_err(js_error)?;
        Ok(Self(Reading::new(options)))
    }

    /// Reads the next piece of the file, its text or its bytes (a `Uint8Array`: UTF-8, else
    /// Windows-1252; the cheaper way, as no string is copied); returns the lines read so far.
    /// (The piece is taken as a `JsValue` and checked: wasm-bindgen does not check that a `&str`
    /// argument is a string.)
    pub fn feed(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "string | Uint8Array")] text: JsValue,
    ) -> Result<u32, JsError> {
        self.piece(&text, "a piece of the file")
    }

    /// Ends the file: the points read and the report.
    #[wasm_bindgen(unchecked_return_type = "ParsedToolpath")]
    pub fn finish(&mut self) -> Result<JsValue, JsError> {
        output(&self.0.finish().map_err(js_error)?)
    }
}

impl ToolpathReader {
    /// Feeds `text`, a string or a `Uint8Array` (`what` it is, for the message).
    fn piece(&mut self, text: &JsValue, what: &str) -> Result<u32, JsError> {
        let r = if let Some(bytes) = text.dyn_ref::<Uint8Array>() {
            self.0.feed_bytes(&bytes.to_vec())
        } else if let Some(s) = text.dyn_ref::<JsString>() {
            self.0.feed(&crate::text(s))
        } else {
            Err(Error::field(
                "text",
                format!("expected {what}: its text or its bytes (Uint8Array)"),
            ))
        };
        r.map_err(js_error)
    }
}

/// Reads a whole toolpath file at once, its text or its bytes (see [`ToolpathReader`]).
#[wasm_bindgen(js_name = toolpathParse, unchecked_return_type = "ParsedToolpath")]
pub fn toolpath_parse(
    #[wasm_bindgen(unchecked_param_type = "string | Uint8Array")] text: JsValue,
    #[wasm_bindgen(unchecked_param_type = "ToolpathReadInput")] options: JsValue,
) -> Result<JsValue, JsError> {
    let mut r = ToolpathReader::new(options)?;
    r.piece(&text, "the file")?;
    r.finish()
}
