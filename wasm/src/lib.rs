//! The JavaScript binding: the one module that knows about wasm-bindgen.
//!
//! Every export takes plain JavaScript objects (deserialised with serde; fields the export does
//! not know are ignored), converts units at this edge, calls the engine and returns plain
//! objects, with long numeric series as `Float64Array`. Conventions at this edge:
//! * **lengths in mm, angles in degrees**, in and out;
//! * bad input throws a JavaScript `Error` whose message starts with the field's path
//!   (`"start.k: must be a finite number of degrees, got NaN"`); nothing panics on bad input.
//!
//! The TypeScript declarations of the input and result objects are written out below and end
//! up in the generated `.d.ts`. One submodule per study holds that study's exports.

mod nonlinear;
pub use self::nonlinear::*;
mod cubic;
pub use self::cubic::*;
mod sshape;
pub use self::sshape::*;

use crate::error::{check_interval, check_range, Error};
use crate::nonlinear::MAX_ANGLE_DEG;
use crate::rotary::{self, Group, MachineType, Pose, RotaryType};
use js_sys::Float64Array;
use nalgebra::Vector3;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::fmt::Display;
use wasm_bindgen::prelude::*;

#[wasm_bindgen(start)]
fn start() {
    console_error_panic_hook::set_once();
}

/// Turns any engine or decoding error into a JavaScript `Error` with its message.
pub(crate) fn js_error(err: impl Display) -> JsError {
    JsError::new(&err.to_string())
}

/// Reads an input object into `T`, naming the offending path on failure.
pub(crate) fn input<T: DeserializeOwned>(value: JsValue) -> Result<T, JsError> {
    let de = serde_wasm_bindgen::Deserializer::from(value);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let path = if path == "." {
            "input".to_string()
        } else {
            path
        };
        // serde-wasm-bindgen's messages come wrapped as "Error: ..."; the struct names are ours.
        let inner = e.inner().to_string();
        let inner = inner.strip_prefix("Error: ").unwrap_or(&inner);
        let inner = inner
            .replace(
                "unit value, expected struct In",
                "undefined or null, expected an input object",
            )
            .replace("struct In", "an input object");
        JsError::new(&format!("{path}: {inner}"))
    })
}

/// Writes a result object (`None` becomes `null`, maps become objects).
pub(crate) fn output<T: Serialize>(value: &T) -> Result<JsValue, JsError> {
    let ser = serde_wasm_bindgen::Serializer::new()
        .serialize_missing_as_null(true)
        .serialize_maps_as_objects(true);
    value.serialize(&ser).map_err(js_error)
}

/// A `Float64Array` copy of `values`, to be kept through serialisation.
pub(crate) fn f64_array(values: &[f64]) -> Float64Array {
    Float64Array::from(values)
}

pub(crate) fn degrees(values: &[f64]) -> Vec<f64> {
    values.iter().map(|v| v.to_degrees()).collect()
}

pub(crate) fn parse_type(name: &str) -> Result<RotaryType, JsError> {
    RotaryType::parse(name).map_err(js_error)
}

#[wasm_bindgen(typescript_custom_section)]
const TS_TYPES: &'static str = r#"
/** Angles of the rotary axes K and M, degrees. */
export interface PoseDeg { k: number; m: number }
/** One of the 12 rotary-axis types. */
export type RotaryTypeName =
  | "ABX" | "ACX" | "BCY" | "BAY" | "CAZ" | "CBZ"
  | "ABZ" | "ACY" | "BCX" | "BAZ" | "CAY" | "CBX";
export type MachineTypeName = "table-table" | "head-head" | "head-table";
export type ReferenceKind = "plane" | "coincident" | "opposite";
export interface RotaryTypeInfo { name: RotaryTypeName; group: "I" | "II"; k: string; m: string; home: string }
export interface MachineLayout {
  typeName: RotaryTypeName; group: "I" | "II"; machine: MachineTypeName;
  kAxis: string; mAxis: string; kRole: string; mRole: string; home: string;
}
export interface ToolVectorInput { type: RotaryTypeName | string; k: number; m: number }
export interface InverseInput { type: RotaryTypeName | string; vector: number[]; previous?: PoseDeg | null }
export interface InverseResult {
  /** Every pose giving the vector, degrees in (-180, 180]: two, or one when singular. */
  solutions: PoseDeg[];
  /** The vector lies along the K axis: θk is arbitrary (kept at the previous value). */
  singular: boolean;
  /** The solution nearest `previous` (whole turns added), or the smallest tilt. */
  chosen: PoseDeg;
  /** Angle between the vector and the nearer of ±K, degrees. */
  poleAngle: number;
}
"#;

/// The twelve rotary-axis types with their group and axes.
#[wasm_bindgen(js_name = rotaryTypes, unchecked_return_type = "RotaryTypeInfo[]")]
pub fn rotary_types() -> Result<JsValue, JsError> {
    #[derive(Serialize)]
    struct Info {
        name: RotaryType,
        group: Group,
        k: String,
        m: String,
        home: String,
    }
    let list: Vec<Info> = RotaryType::ALL
        .iter()
        .map(|t| Info {
            name: *t,
            group: t.group(),
            k: t.k.letter().to_string(),
            m: t.m.letter().to_string(),
            home: t.home.letter().to_string(),
        })
        .collect();
    output(&list)
}

/// Where the K and M axes of a type sit on a machine type (`"table-table"`, `"head-head"`,
/// `"head-table"`).
#[wasm_bindgen(js_name = machineLayout, unchecked_return_type = "MachineLayout")]
pub fn machine_layout(
    #[wasm_bindgen(unchecked_param_type = "RotaryTypeName | string")] rtype: JsValue,
    #[wasm_bindgen(unchecked_param_type = "MachineTypeName | string")] machine: JsValue,
) -> Result<JsValue, JsError> {
    let rtype: String = input(rtype)?;
    let machine: String = input(machine)?;
    let machine = MachineType::parse(&machine).map_err(js_error)?;
    output(&rotary::layout(parse_type(&rtype)?, machine))
}

#[derive(Deserialize)]
pub(crate) struct PoseIn {
    pub(crate) k: f64,
    pub(crate) m: f64,
}

impl PoseIn {
    pub(crate) fn radians(&self, field: &str) -> Result<Pose, JsError> {
        for (name, v) in [("k", self.k), ("m", self.m)] {
            check_range(
                &format!("{field}.{name}"),
                v,
                -MAX_ANGLE_DEG,
                MAX_ANGLE_DEG,
                "degrees",
            )
            .map_err(js_error)?;
        }
        Ok(Pose::new(self.k.to_radians(), self.m.to_radians()))
    }
}

#[derive(Serialize)]
pub(crate) struct PoseOut {
    k: f64,
    m: f64,
}

impl From<Pose> for PoseOut {
    fn from(p: Pose) -> Self {
        Self {
            k: p.k.to_degrees(),
            m: p.m.to_degrees(),
        }
    }
}

/// The tool orientation `V(θk, θm)` (eq 4), a unit vector `[x, y, z]` in workpiece coordinates.
#[wasm_bindgen(js_name = toolVector, unchecked_return_type = "number[]")]
pub fn tool_vector(
    #[wasm_bindgen(unchecked_param_type = "ToolVectorInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    #[derive(Deserialize)]
    struct In {
        #[serde(rename = "type")]
        rtype: String,
        k: f64,
        m: f64,
    }
    let i: In = input(value)?;
    let t = parse_type(&i.rtype)?;
    let pose = PoseIn { k: i.k, m: i.m }.radians("input")?;
    let v: [f64; 3] = t.tool_vector(pose).into();
    output(&v)
}

/// Every pose giving a tool vector, the singularity flag and the continuous choice.
#[wasm_bindgen(js_name = inverseKinematics, unchecked_return_type = "InverseResult")]
pub fn inverse_kinematics(
    #[wasm_bindgen(unchecked_param_type = "InverseInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    #[derive(Deserialize)]
    struct In {
        #[serde(rename = "type")]
        rtype: String,
        vector: Vec<f64>,
        #[serde(default)]
        previous: Option<PoseIn>,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        solutions: Vec<PoseOut>,
        singular: bool,
        chosen: PoseOut,
        pole_angle: f64,
    }
    let i: In = input(value)?;
    let t = parse_type(&i.rtype)?;
    if i.vector.len() != 3 {
        return Err(js_error(Error::field(
            "vector",
            format!("must have 3 components [x, y, z], got {}", i.vector.len()),
        )));
    }
    for (n, c) in i.vector.iter().enumerate() {
        check_range(&format!("vector[{n}]"), *c, -1e6, 1e6, "").map_err(js_error)?;
    }
    let previous = match &i.previous {
        Some(p) => Some(p.radians("previous")?),
        None => None,
    };
    let v = Vector3::new(i.vector[0], i.vector[1], i.vector[2]);
    let s = t.inverse(&v, previous).map_err(js_error)?;
    output(&Out {
        solutions: s.solutions.into_iter().map(PoseOut::from).collect(),
        singular: s.singular,
        chosen: s.chosen.into(),
        pole_angle: s.pole_angle.to_degrees(),
    })
}

/// A machine error as given at this edge, a position in mm or (`angular`) an angle in degrees,
/// checked against `±limit` (mm or degrees) and returned in engine units (mm or rad).
pub(crate) fn error_value(field: &str, v: f64, angular: bool, limit: f64) -> Result<f64, JsError> {
    if angular {
        check_range(field, v, -limit, limit, "degrees").map(f64::to_radians)
    } else {
        check_range(field, v, -limit, limit, "mm")
    }
    .map_err(js_error)
}

/// A sensitivity per unit of an error at this edge: per mm, or per degree for an angle (the
/// engine's are per rad).
pub(crate) fn per_edge_unit(k: f64, angular: bool) -> f64 {
    if angular {
        k.to_radians()
    } else {
        k
    }
}

pub(crate) fn check_deg(field: &str, v: f64) -> Result<f64, JsError> {
    check_range(field, v, -MAX_ANGLE_DEG, MAX_ANGLE_DEG, "degrees")
        .map(f64::to_radians)
        .map_err(js_error)
}

pub(crate) fn check_span(field: &str, from: f64, to: f64) -> Result<(f64, f64), JsError> {
    check_interval(field, (from, to), -MAX_ANGLE_DEG, MAX_ANGLE_DEG, "degrees")
        .map_err(js_error)?;
    Ok((from.to_radians(), to.to_radians()))
}
