//! The JavaScript binding: the one module that knows about wasm-bindgen.
//!
//! Every export takes plain JavaScript objects (deserialised with serde; fields the
//! export does not know are ignored), converts units at this edge, calls the engine and returns plain objects, with long
//! numeric series as `Float64Array`. Conventions at this edge:
//! * **lengths in mm, angles in degrees**, in and out;
//! * bad input throws a JavaScript `Error` whose message starts with the field's path
//!   (`"start.k: must be a finite number of degrees, got NaN"`); nothing panics on bad input.
//!
//! The TypeScript declarations of the input and result objects are written out below and end
//! up in the generated `.d.ts`.

use crate::error::{check_range, Error};
use crate::nonlinear::{self, Move, Reference, MAX_ANGLE_DEG};
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
fn js_error(err: impl Display) -> JsError {
    JsError::new(&err.to_string())
}

/// Reads an input object into `T`, naming the offending path on failure.
fn input<T: DeserializeOwned>(value: JsValue) -> Result<T, JsError> {
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
fn output<T: Serialize>(value: &T) -> Result<JsValue, JsError> {
    let ser = serde_wasm_bindgen::Serializer::new()
        .serialize_missing_as_null(true)
        .serialize_maps_as_objects(true);
    value.serialize(&ser).map_err(js_error)
}

/// A `Float64Array` copy of `values`, to be kept through serialisation.
fn f64_array(values: &[f64]) -> Float64Array {
    Float64Array::from(values)
}

fn degrees(values: &[f64]) -> Vec<f64> {
    values.iter().map(|v| v.to_degrees()).collect()
}

fn parse_type(name: &str) -> Result<RotaryType, JsError> {
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
export interface NonlinearMoveInput {
  type: RotaryTypeName | string;
  /** Tool length or pivot distance L, mm (> 0). */
  length: number;
  start: PoseDeg;
  end: PoseDeg;
  /** Points of the returned δ(u) curve, default 201. */
  samples?: number;
}
export interface NonlinearMoveResult {
  /** Exact maximum error δ, mm. */ max: number;
  /** u ∈ [0, 1] of the maximum. */ uAtMax: number;
  /** δ(0.5) from the vectors, mm. */ atHalf: number;
  /** Eq 25 (Group I) or eq 30 (Group II), mm; null for coincident/opposite ends. */ approx: number | null;
  /** (max - approx) / max. */ approxShortfall: number | null;
  /** Eq 26, mm, when the move starts at the pole; else null. */ closedForm: number | null;
  reference: ReferenceKind;
  /** |V0 × V1|. */ planeSine: number;
  /** Angle between start and end tool orientation, degrees. */ sweepAngle: number;
  startVector: number[]; endVector: number[]; normal: number[];
  u: Float64Array;
  /** δ(u), mm. */ delta: Float64Array;
}
export interface SweepKInput {
  type: RotaryTypeName | string; length: number;
  /** Start angle of M, degrees. */ thetaM: number;
  dK: number; dM: number; from: number; to: number; n: number;
}
export interface SweepKResult { k: Float64Array; max: Float64Array }
export interface SweepMInput {
  type: RotaryTypeName | string; length: number;
  dM: number; ratios: number[]; from: number; to: number; n: number;
}
export interface SweepMResult {
  m: Float64Array;
  curves: { ratio: number; exact: Float64Array; approx: (number | null)[] }[];
}
export interface Range { from: number; to: number }
export interface GridInput {
  type: RotaryTypeName | string; length: number; thetaM: number;
  dK: Range; dM: Range; nx: number; ny: number;
}
export interface GridResult {
  nx: number; ny: number;
  /** Δθk per column, degrees. */ dK: Float64Array;
  /** Δθm per row, degrees. */ dM: Float64Array;
  /** Row-major ny × nx: entry [iy * nx + ix], mm. */ max: Float64Array;
  /** Row-major like max; null where the error is zero. */ uAtMax: (number | null)[];
}
export interface CompareInput { length: number; start: PoseDeg; end: PoseDeg }
export interface TypeComparison {
  type: RotaryTypeName; group: "I" | "II"; max: number; uAtMax: number;
  approx: number | null; reference: ReferenceKind;
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
struct PoseIn {
    k: f64,
    m: f64,
}

impl PoseIn {
    fn radians(&self, field: &str) -> Result<Pose, JsError> {
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
struct PoseOut {
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

/// One move: the δ(u) curve, its exact maximum and the paper's approximations.
#[wasm_bindgen(js_name = nonlinearMove, unchecked_return_type = "NonlinearMoveResult")]
pub fn nonlinear_move(
    #[wasm_bindgen(unchecked_param_type = "NonlinearMoveInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    #[derive(Deserialize)]
    struct In {
        #[serde(rename = "type")]
        rtype: String,
        length: f64,
        start: PoseIn,
        end: PoseIn,
        #[serde(default)]
        samples: Option<usize>,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        max: f64,
        u_at_max: f64,
        at_half: f64,
        approx: Option<f64>,
        approx_shortfall: Option<f64>,
        closed_form: Option<f64>,
        reference: Reference,
        plane_sine: f64,
        sweep_angle: f64,
        start_vector: [f64; 3],
        end_vector: [f64; 3],
        normal: [f64; 3],
        #[serde(with = "serde_wasm_bindgen::preserve")]
        u: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        delta: Float64Array,
    }
    let i: In = input(value)?;
    let mv = Move::new(
        parse_type(&i.rtype)?,
        i.start.radians("start")?,
        i.end.radians("end")?,
    );
    let a = nonlinear::analyze(mv, i.length, i.samples.unwrap_or(201)).map_err(js_error)?;
    output(&Out {
        max: a.max,
        u_at_max: a.u_at_max,
        at_half: a.at_half,
        approx: a.approx,
        approx_shortfall: a.approx_shortfall,
        closed_form: a.closed_form,
        reference: a.reference,
        plane_sine: a.plane_sine,
        sweep_angle: a.sweep_angle.to_degrees(),
        start_vector: a.start_vector,
        end_vector: a.end_vector,
        normal: a.normal,
        u: f64_array(&a.u),
        delta: f64_array(&a.delta),
    })
}

fn check_deg(field: &str, v: f64) -> Result<f64, JsError> {
    check_range(field, v, -MAX_ANGLE_DEG, MAX_ANGLE_DEG, "degrees")
        .map(f64::to_radians)
        .map_err(js_error)
}

fn check_span(field: &str, from: f64, to: f64) -> Result<(f64, f64), JsError> {
    nonlinear::check_range_deg(field, (from, to)).map_err(js_error)?;
    Ok((from.to_radians(), to.to_radians()))
}

/// Fig 4: maximum error against the start angle of K (the paper: constant).
#[wasm_bindgen(js_name = nonlinearSweepK, unchecked_return_type = "SweepKResult")]
pub fn nonlinear_sweep_k(
    #[wasm_bindgen(unchecked_param_type = "SweepKInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct In {
        #[serde(rename = "type")]
        rtype: String,
        length: f64,
        theta_m: f64,
        d_k: f64,
        d_m: f64,
        from: f64,
        to: f64,
        n: usize,
    }
    #[derive(Serialize)]
    struct Out {
        #[serde(with = "serde_wasm_bindgen::preserve")]
        k: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        max: Float64Array,
    }
    let i: In = input(value)?;
    let t = parse_type(&i.rtype)?;
    let range = check_span("range", i.from, i.to)?;
    let max = nonlinear::sweep_start_k(
        t,
        i.length,
        check_deg("thetaM", i.theta_m)?,
        check_deg("dK", i.d_k)?,
        check_deg("dM", i.d_m)?,
        range,
        i.n,
    )
    .map_err(js_error)?;
    let k = nonlinear::linspace(i.from, i.to, i.n);
    output(&Out {
        k: f64_array(&k),
        max: f64_array(&max),
    })
}

/// Fig 7: maximum error against the start angle of M, one curve per ratio Δθk/Δθm.
#[wasm_bindgen(js_name = nonlinearSweepM, unchecked_return_type = "SweepMResult")]
pub fn nonlinear_sweep_m(
    #[wasm_bindgen(unchecked_param_type = "SweepMInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct In {
        #[serde(rename = "type")]
        rtype: String,
        length: f64,
        d_m: f64,
        ratios: Vec<f64>,
        from: f64,
        to: f64,
        n: usize,
    }
    #[derive(Serialize)]
    struct Curve {
        ratio: f64,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        exact: Float64Array,
        approx: Vec<Option<f64>>,
    }
    #[derive(Serialize)]
    struct Out {
        #[serde(with = "serde_wasm_bindgen::preserve")]
        m: Float64Array,
        curves: Vec<Curve>,
    }
    let i: In = input(value)?;
    let t = parse_type(&i.rtype)?;
    let range = check_span("range", i.from, i.to)?;
    let curves =
        nonlinear::sweep_start_m(t, i.length, check_deg("dM", i.d_m)?, &i.ratios, range, i.n)
            .map_err(js_error)?;
    output(&Out {
        m: f64_array(&nonlinear::linspace(i.from, i.to, i.n)),
        curves: curves
            .into_iter()
            .map(|c| Curve {
                ratio: c.ratio,
                exact: f64_array(&c.exact),
                approx: c.approx,
            })
            .collect(),
    })
}

/// Figs 3, 5, 8: maximum error and its u over a grid of increments Δθk × Δθm.
#[wasm_bindgen(js_name = nonlinearGrid, unchecked_return_type = "GridResult")]
pub fn nonlinear_grid(
    #[wasm_bindgen(unchecked_param_type = "GridInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    #[derive(Deserialize)]
    struct RangeIn {
        from: f64,
        to: f64,
    }
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct In {
        #[serde(rename = "type")]
        rtype: String,
        length: f64,
        theta_m: f64,
        d_k: RangeIn,
        d_m: RangeIn,
        nx: usize,
        ny: usize,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        nx: usize,
        ny: usize,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        d_k: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        d_m: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        max: Float64Array,
        u_at_max: Vec<Option<f64>>,
    }
    let i: In = input(value)?;
    let t = parse_type(&i.rtype)?;
    let g = nonlinear::sweep_increments(
        t,
        i.length,
        check_deg("thetaM", i.theta_m)?,
        check_span("dK", i.d_k.from, i.d_k.to)?,
        check_span("dM", i.d_m.from, i.d_m.to)?,
        i.nx,
        i.ny,
    )
    .map_err(js_error)?;
    output(&Out {
        nx: g.nx,
        ny: g.ny,
        d_k: f64_array(&degrees(&g.d_k)),
        d_m: f64_array(&degrees(&g.d_m)),
        max: f64_array(&g.max),
        u_at_max: g.u_at_max,
    })
}

/// The same move of K and M on each of the twelve types.
#[wasm_bindgen(js_name = nonlinearCompareTypes, unchecked_return_type = "TypeComparison[]")]
pub fn nonlinear_compare_types(
    #[wasm_bindgen(unchecked_param_type = "CompareInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    #[derive(Deserialize)]
    struct In {
        length: f64,
        start: PoseIn,
        end: PoseIn,
    }
    let i: In = input(value)?;
    let rows = nonlinear::compare_types(i.length, i.start.radians("start")?, i.end.radians("end")?)
        .map_err(js_error)?;
    output(&rows)
}

/// Bulk: the exact maximum error (mm) of many moves of one type. `moves` holds
/// `[θk0, θm0, θk1, θm1]` in degrees per move (length a multiple of 4).
#[wasm_bindgen(js_name = nonlinearMaxErrors)]
pub fn nonlinear_max_errors(
    rtype: &str,
    length: f64,
    moves: &[f64],
) -> Result<Float64Array, JsError> {
    let t = parse_type(rtype)?;
    crate::error::check_positive("length", length, nonlinear::MAX_LENGTH_MM, "mm")
        .map_err(js_error)?;
    if moves.len() % 4 != 0 {
        return Err(js_error(Error::field(
            "moves",
            format!("length must be a multiple of 4, got {}", moves.len()),
        )));
    }
    let mut quads = Vec::with_capacity(moves.len() / 4);
    for (n, c) in moves.chunks_exact(4).enumerate() {
        let mut q = [0.0; 4];
        for j in 0..4 {
            q[j] = check_deg(&format!("moves[{}]", 4 * n + j), c[j])?;
        }
        quads.push(q);
    }
    let values: Vec<f64> = nonlinear::max_errors(t, &quads)
        .into_iter()
        .map(|v| v * length)
        .collect();
    Ok(f64_array(&values))
}
