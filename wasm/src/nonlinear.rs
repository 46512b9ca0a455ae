//! Exports of the nonlinear-error study (see `fiveaxis::nonlinear`). Every input is the machine
//! (its type, senses and pivot), optionally `L`, and the export's own fields, in one object.

use crate::{degrees, f64_array, js_error, json, output, Series};
use fiveaxis::nonlinear::{
    self, NonlinearCase, NonlinearGridInput, NonlinearMoveInput, Reference, SweepKInput,
    SweepMInput, TypeCompareInput,
};
use fiveaxis::rotary::{Group, RotaryType};
use fiveaxis::schema::Inputs;
use fiveaxis::Error;
use js_sys::Float64Array;
use serde::Serialize;
use tsify::Tsify;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

fn read<B: Inputs>(value: &JsValue) -> Result<(NonlinearCase, B), JsError> {
    NonlinearCase::read_with(&json(value)?).map_err(js_error)
}

/// `L` of the case, or the machine's.
fn length(c: &NonlinearCase) -> Result<f64, JsError> {
    c.length().map_err(js_error)
}

/// One move: the δ(u) curve, its exact maximum and the paper's approximations.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct NonlinearMoveResult {
    /// The machine's rotary-axis type.
    #[serde(rename = "type")]
    pub rtype: String,
    /// Its group (eq 25 or eq 30 gives the approximation).
    pub group: Group,
    /// `L` used, mm (given, or the machine's).
    pub length: f64,
    /// Exact maximum error δ, mm.
    pub max: f64,
    /// u ∈ [0, 1] of the maximum.
    pub u_at_max: f64,
    /// δ(0.5) from the vectors, mm.
    pub at_half: f64,
    /// Eq 25 (Group I) or eq 30 (Group II), mm; null for coincident or opposite ends.
    pub approx: Option<f64>,
    /// (max − approx)/max.
    pub approx_shortfall: Option<f64>,
    /// Eq 26, mm, when the move starts at the pole; else null.
    pub closed_form: Option<f64>,
    /// How the reference plane was defined.
    pub reference: Reference,
    /// |V0 × V1|.
    pub plane_sine: f64,
    /// Angle between the start and end tool orientations, degrees.
    pub sweep_angle: f64,
    /// V0, workpiece coordinates.
    pub start_vector: [f64; 3],
    /// V1.
    pub end_vector: [f64; 3],
    /// Unit normal of the reference plane.
    pub normal: [f64; 3],
    /// Samples of u.
    pub u: Series,
    /// δ(u), mm.
    pub delta: Series,
    /// With a `tolerance`: the fewest equal steps of the move that keep δ within it
    /// (`fiveaxis::nonlinear::split_within`); steps in degrees. Null without a tolerance.
    pub split: Option<MoveSplit>,
}

/// The move split into equal steps that keep its nonlinear error within a tolerance.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct MoveSplit {
    /// The tolerance, mm.
    pub tolerance: f64,
    /// Equal steps needed (1: the move is within as it is); null when more than `maxSteps`.
    pub steps: Option<usize>,
    /// The most steps considered.
    pub max_steps: usize,
    /// Step of K per block, degrees (absolute).
    pub step_k: f64,
    /// Step of M per block, degrees (absolute).
    pub step_m: f64,
    /// The largest δ of the blocks, mm.
    pub max: f64,
}

/// One move of the machine's rotary axes from `start` to `end` (commands, degrees).
#[wasm_bindgen(js_name = nonlinearMove, unchecked_return_type = "NonlinearMoveResult")]
pub fn nonlinear_move(
    #[wasm_bindgen(unchecked_param_type = "NonlinearCase & NonlinearMoveInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (c, i): (_, NonlinearMoveInput) = read(&value)?;
    let l = length(&c)?;
    let mv = c.move_between(&i.start, &i.end);
    let a = nonlinear::analyze(mv, l, i.samples).map_err(js_error)?;
    let split = match i.tolerance {
        Some(t) => {
            let s = nonlinear::split_within(mv, l, t).map_err(js_error)?;
            Some(MoveSplit {
                tolerance: s.tolerance,
                steps: s.steps,
                max_steps: nonlinear::MAX_SPLIT,
                step_k: s.step_k.to_degrees(),
                step_m: s.step_m.to_degrees(),
                max: s.max,
            })
        }
        None => None,
    };
    output(&NonlinearMoveResult {
        rtype: c.rtype().name(),
        group: c.rtype().group(),
        length: l,
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
        split,
    })
}

/// Fig 4: the maximum error against the start angle of K.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct SweepKResult {
    /// Start commands of K, degrees.
    pub k: Series,
    /// Exact maximum error, mm.
    pub max: Series,
}

/// Fig 4: the maximum error against the start angle of K (the paper: constant).
#[wasm_bindgen(js_name = nonlinearSweepK, unchecked_return_type = "SweepKResult")]
pub fn nonlinear_sweep_k(
    #[wasm_bindgen(unchecked_param_type = "NonlinearCase & SweepKInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (c, i): (_, SweepKInput) = read(&value)?;
    let max = c.sweep_k(&i).map_err(js_error)?;
    let k = nonlinear::linspace(i.from.to_degrees(), i.to.to_degrees(), i.n);
    output(&SweepKResult {
        k: f64_array(&k),
        max: f64_array(&max),
    })
}

/// One curve of [`SweepMResult`].
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct RatioCurve {
    /// Δθk/Δθm.
    pub ratio: f64,
    /// Exact maximum error, mm.
    pub exact: Series,
    /// The u = 0.5 approximation, mm (null where undefined).
    pub approx: Vec<Option<f64>>,
}

/// Fig 7: the maximum error against the start angle of M.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct SweepMResult {
    /// Start commands of M, degrees.
    pub m: Series,
    /// One curve per ratio.
    pub curves: Vec<RatioCurve>,
}

/// Fig 7: the maximum error against the start angle of M, one curve per ratio Δθk/Δθm.
#[wasm_bindgen(js_name = nonlinearSweepM, unchecked_return_type = "SweepMResult")]
pub fn nonlinear_sweep_m(
    #[wasm_bindgen(unchecked_param_type = "NonlinearCase & SweepMInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (c, i): (_, SweepMInput) = read(&value)?;
    let curves = c.sweep_m(&i).map_err(js_error)?;
    output(&SweepMResult {
        m: f64_array(&nonlinear::linspace(
            i.from.to_degrees(),
            i.to.to_degrees(),
            i.n,
        )),
        curves: curves
            .into_iter()
            .map(|c| RatioCurve {
                ratio: c.ratio,
                exact: f64_array(&c.exact),
                approx: c.approx,
            })
            .collect(),
    })
}

/// Figs 3, 5, 8: the maximum error and its u over a grid of increments.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct GridResult {
    /// Columns.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// Increment of K per column (commands), degrees.
    pub d_k: Series,
    /// Increment of M per row (commands), degrees.
    pub d_m: Series,
    /// Row-major ny × nx (`[iy * nx + ix]`), mm.
    pub max: Series,
    /// Row-major like `max`; null where the error is zero.
    pub u_at_max: Vec<Option<f64>>,
}

/// Figs 3, 5, 8: maximum error and its u over a grid of increments Δθk × Δθm.
#[wasm_bindgen(js_name = nonlinearGrid, unchecked_return_type = "GridResult")]
pub fn nonlinear_grid(
    #[wasm_bindgen(unchecked_param_type = "NonlinearCase & NonlinearGridInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (c, i): (_, NonlinearGridInput) = read(&value)?;
    let g = c.grid(&i).map_err(js_error)?;
    output(&GridResult {
        nx: g.nx,
        ny: g.ny,
        d_k: degrees(&g.d_k),
        d_m: degrees(&g.d_m),
        max: f64_array(&g.max),
        u_at_max: g.u_at_max,
    })
}

/// One row of [`nonlinear_compare_types`]: the same tool path on one type.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct TypeComparison {
    /// The type.
    #[serde(rename = "type")]
    pub rtype: String,
    /// Its group.
    pub group: Group,
    /// Its commands `[K, M]` at the start and at the end, degrees; null when out of travel.
    pub start: Option<[f64; 2]>,
    /// At the end.
    pub end: Option<[f64; 2]>,
    /// Exact maximum error, mm; null when out of travel.
    pub max: Option<f64>,
    /// u of the maximum.
    pub u_at_max: Option<f64>,
    /// Why the type cannot make the move within the travel.
    pub unreachable: Option<String>,
}

/// The machine's move from `start` to `end` as a tool path (its start and end tool vectors),
/// made by each of the twelve types on the machine's kind and travel.
#[wasm_bindgen(js_name = nonlinearCompareTypes, unchecked_return_type = "TypeComparison[]")]
pub fn nonlinear_compare_types(
    #[wasm_bindgen(unchecked_param_type = "NonlinearCase & TypeCompareInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (c, i): (_, TypeCompareInput) = read(&value)?;
    let rows = c.compare_types(&i.start, &i.end).map_err(js_error)?;
    let deg = |p: &fiveaxis::rotary::Pose| [p.k.to_degrees(), p.m.to_degrees()];
    let out: Vec<TypeComparison> = rows
        .into_iter()
        .map(|r| TypeComparison {
            rtype: r.rtype.name(),
            group: r.group,
            start: r.commands.as_ref().map(|c| deg(&c[0])),
            end: r.commands.as_ref().map(|c| deg(&c[1])),
            max: r.max,
            u_at_max: r.u_at_max,
            unreachable: r.unreachable,
        })
        .collect();
    output(&out)
}

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
    let t = RotaryType::parse(&name).map_err(js_error)?;
    let length = length
        .as_f64()
        .ok_or_else(|| js_error(Error::field("length", "expected a number of mm")))?;
    fiveaxis::error::check_positive("length", length, nonlinear::MAX_LENGTH_MM, "mm")
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
    let lim = nonlinear::MAX_ANGLE_DEG;
    let mut quads = Vec::with_capacity(moves.len() / 4);
    for (n, c) in moves.chunks_exact(4).enumerate() {
        let mut q = [0.0; 4];
        for (j, v) in c.iter().enumerate() {
            q[j] = v.to_radians();
            if v.is_finite() && v.abs() <= lim {
                continue; // the message (and its formatted path) only for a bad value
            }
            fiveaxis::error::check_range(
                &format!("moves[{}]", 4 * n + j),
                *v,
                -lim,
                lim,
                "degrees",
            )
            .map_err(js_error)?;
        }
        quads.push(q);
    }
    let values: Vec<f64> = nonlinear::max_errors(t, &quads)
        .into_iter()
        .map(|v| v * length)
        .collect();
    Ok(Float64Array::from(values.as_slice()))
}
