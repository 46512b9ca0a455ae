//! Exports of the nonlinear-error study (see [`crate::nonlinear`]).

use super::{
    check_deg, check_span, degrees, f64_array, input, js_error, output, parse_type, PoseIn,
};
use crate::error::Error;
use crate::nonlinear::{self, Move, Reference};
use js_sys::Float64Array;
use serde::{Deserialize, Serialize};
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

#[wasm_bindgen(typescript_custom_section)]
const TS_TYPES: &'static str = r#"
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

/// Bulk: the exact maximum error (mm) of many moves of one type. `moves` is a `Float64Array`
/// holding `[θk0, θm0, θk1, θm1]` in degrees per move (length a multiple of 4).
///
/// The parameters are taken as `JsValue` and checked here: wasm-bindgen does not check the
/// JavaScript types of `&str`, `f64` or slice parameters, and a wrong type must give an error.
#[wasm_bindgen(js_name = nonlinearMaxErrors)]
pub fn nonlinear_max_errors(
    #[wasm_bindgen(unchecked_param_type = "RotaryTypeName | string")] rtype: JsValue,
    #[wasm_bindgen(unchecked_param_type = "number")] length: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Float64Array")] moves: JsValue,
) -> Result<Float64Array, JsError> {
    let rtype: String = input(rtype)
        .map_err(|_| js_error(Error::field("type", "expected a type name such as \"CAZ\"")))?;
    let t = parse_type(&rtype)?;
    let length = length
        .as_f64()
        .ok_or_else(|| js_error(Error::field("length", "expected a number of mm")))?;
    crate::error::check_positive("length", length, nonlinear::MAX_LENGTH_MM, "mm")
        .map_err(js_error)?;
    let moves = moves
        .dyn_into::<Float64Array>()
        .map_err(|_| {
            js_error(Error::field(
                "moves",
                "expected a Float64Array of [θk0, θm0, θk1, θm1] per move",
            ))
        })?
        .to_vec();
    if moves.len() % 4 != 0 {
        return Err(js_error(Error::field(
            "moves",
            format!("length must be a multiple of 4, got {}", moves.len()),
        )));
    }
    let mut quads = Vec::with_capacity(moves.len() / 4);
    for (n, c) in moves.chunks_exact(4).enumerate() {
        let mut q = [0.0; 4];
        for (j, v) in c.iter().enumerate() {
            q[j] = check_deg(&format!("moves[{}]", 4 * n + j), *v)?;
        }
        quads.push(q);
    }
    let values: Vec<f64> = nonlinear::max_errors(t, &quads)
        .into_iter()
        .map(|v| v * length)
        .collect();
    Ok(f64_array(&values))
}
