//! Exports of the rotary-axis reversal study (see `fiveaxis::reversal`). Lengths in mm, angles
//! in degrees, time in s, torques in N·m, like the engine's inputs say.

use crate::{degrees, f64_array, js_error, json, output, Series};
use fiveaxis::reversal::fit::{self, Estimate};
use fiveaxis::reversal::measure::{compensation, measure_dent};
use fiveaxis::reversal::{
    self, direction_checks, ReversalCase, ReversalFitInput, ReversalRunInput,
};
use serde::Serialize;
use tsify::Tsify;
use wasm_bindgen::prelude::*;

/// One linear axis along the run.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct ReversalAxis {
    /// "X", "Y" or "Z".
    pub name: String,
    /// Command, mm.
    pub command: Series,
    /// Actual velocity, mm/s.
    pub velocity: Series,
    /// Following error (command − actual), mm.
    pub error: Series,
}

/// Whether a linear axis changes direction within ±5° of C's reversal.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct ReversalDirection {
    /// The axis.
    pub name: String,
    /// Commanded velocity before C turns round, mm/s.
    pub before: f64,
    /// After, mm/s.
    pub after: f64,
    /// Smallest |commanded velocity| there, mm/s.
    pub min_speed: f64,
    /// The command changes direction (beyond 0.1 % of the feed).
    pub reverses: bool,
    /// It comes to rest without changing direction.
    pub stops: bool,
    /// The simulated axis changes direction.
    pub actual_reverses: bool,
}

/// The dent of the friction (with − without), at the reversal.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct ReversalDent {
    /// Depth, mm (positive inwards).
    pub depth: f64,
    /// Trace angle of the deepest point, degrees.
    pub angle: f64,
    /// Width at half depth, degrees of trace angle.
    pub width: f64,
    /// Largest outward difference, mm.
    pub bump: f64,
}

/// The step check: the trace again at half the step.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct ReversalStepCheck {
    /// Step, ms.
    pub step: f64,
    /// Largest difference of the radial deviation, mm.
    pub difference: f64,
    /// Over the largest |deviation|.
    pub relative: f64,
}

/// One simulated test (series at the same instants).
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct ReversalResult {
    /// Time, s.
    pub time: Series,
    /// Commanded trace angle, degrees (C reverses at 180°).
    pub theta: Series,
    /// Actual trace angle, degrees.
    pub angle: Series,
    /// Radial deviation with friction, mm (+ outwards).
    pub deviation: Series,
    /// The same run with C's friction 0, mm.
    pub without_friction: Series,
    /// Actual tip in table coordinates (eq 1), mm.
    pub x: Series,
    /// y, mm.
    pub y: Series,
    /// C command, degrees.
    pub c_command: Series,
    /// C actual, degrees.
    pub c_actual: Series,
    /// C velocity, degrees/s.
    pub c_velocity: Series,
    /// C following error, degrees.
    pub c_error: Series,
    /// C friction torque (eq 2), N·m.
    pub c_friction: Series,
    /// C motor torque, N·m.
    pub c_torque: Series,
    /// X, Y, Z.
    pub linear: Vec<ReversalAxis>,
    /// Time of C's reversal, s.
    pub reversal_time: f64,
    /// Sample nearest it.
    pub reversal_index: usize,
    /// The friction's dent.
    pub dent: ReversalDent,
    /// X and Y at C's reversal.
    pub directions: Vec<ReversalDirection>,
    /// Halving the step (when `checkStep`).
    pub step_check: Option<ReversalStepCheck>,
    /// Circle centre in table coordinates, mm.
    pub centre: [f64; 2],
    /// C's axis in table coordinates, mm.
    pub axis: [f64; 2],
    /// Integration steps.
    pub steps: usize,
}

/// Simulates the reversal test on the machine: the ball-bar trace with and without C's
/// friction, the axes against time, the dent, and whether X and Y change direction with C.
#[wasm_bindgen(js_name = reversalSimulate, unchecked_return_type = "ReversalResult")]
pub fn reversal_simulate(
    #[wasm_bindgen(unchecked_param_type = "ReversalCase & ReversalRunInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (case, run) =
        ReversalCase::read_with::<ReversalRunInput>(&json(&value)?).map_err(js_error)?;
    let (m, tr) = reversal::simulate(&case).map_err(js_error)?;
    let without =
        reversal::simulate_with_step(&case.with_c_friction(0.0), &m, tr.step).map_err(js_error)?;
    let d = reversal::dent(&tr, &without);
    let step_check = if run.check_step {
        let s = reversal::step_check(&case, &m, &tr).map_err(js_error)?;
        Some(ReversalStepCheck {
            step: s.step * 1e3,
            difference: s.difference,
            relative: s.relative,
        })
    } else {
        None
    };
    output(&ReversalResult {
        time: f64_array(&tr.time),
        theta: degrees(&tr.theta),
        angle: degrees(&tr.angle),
        deviation: f64_array(&tr.deviation),
        without_friction: f64_array(&without.deviation),
        x: f64_array(&tr.x),
        y: f64_array(&tr.y),
        c_command: degrees(&tr.c_command),
        c_actual: degrees(&tr.c_actual),
        c_velocity: degrees(&tr.c_velocity),
        c_error: degrees(&tr.c_error),
        c_friction: f64_array(&tr.c_friction),
        c_torque: f64_array(&tr.c_torque),
        linear: tr
            .linear
            .iter()
            .map(|l| ReversalAxis {
                name: l.name.clone(),
                command: f64_array(&l.command),
                velocity: f64_array(&l.velocity),
                error: f64_array(&l.error),
            })
            .collect(),
        reversal_time: tr.reversal_time,
        reversal_index: tr.reversal_index,
        dent: ReversalDent {
            depth: d.depth,
            angle: d.angle.to_degrees(),
            width: d.width.to_degrees(),
            bump: d.bump,
        },
        directions: direction_checks(&m, &tr)
            .into_iter()
            .map(|c| ReversalDirection {
                name: c.name,
                before: c.before,
                after: c.after,
                min_speed: c.min_speed,
                reverses: c.reverses,
                stops: c.stops,
                actual_reverses: c.actual_reverses,
            })
            .collect(),
        step_check,
        centre: [m.centre.x, m.centre.y],
        axis: [m.axis.x, m.axis.y],
        steps: tr.steps,
    })
}

/// The dent for one of Table 1's conditions.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct ReversalDentRow {
    /// Feed, mm/min.
    pub feed: f64,
    /// r, mm.
    pub offset: f64,
    /// The dent.
    pub dent: ReversalDent,
}

/// The dent for Table 1's feeds (1000, 2000, 3000 mm/min) and radii r (25, 50 mm), the other
/// inputs as given.
#[wasm_bindgen(js_name = reversalDents, unchecked_return_type = "ReversalDentRow[]")]
pub fn reversal_dents(
    #[wasm_bindgen(unchecked_param_type = "ReversalCase")] value: JsValue,
) -> Result<JsValue, JsError> {
    let case = ReversalCase::read(&json(&value)?).map_err(js_error)?;
    let rows = reversal::table1_dents(&case).map_err(js_error)?;
    output(
        &rows
            .into_iter()
            .map(|(feed, offset, d)| ReversalDentRow {
                feed,
                offset,
                dent: ReversalDent {
                    depth: d.depth,
                    angle: d.angle.to_degrees(),
                    width: d.width.to_degrees(),
                    bump: d.bump,
                },
            })
            .collect::<Vec<_>>(),
    )
}

/// A fitted value and its 95 % confidence interval.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct ReversalEstimate {
    /// Value.
    pub value: f64,
    /// Lower end.
    pub low: f64,
    /// Upper end.
    pub high: f64,
}

fn estimate(e: Estimate) -> ReversalEstimate {
    ReversalEstimate {
        value: e.value,
        low: e.low,
        high: e.high,
    }
}

/// A fit of a measured trace.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct ReversalFitResult {
    /// Coulomb friction f_c, N·m.
    pub friction: ReversalEstimate,
    /// Eq 2's a, 1/rad.
    pub friction_slope: ReversalEstimate,
    /// C's position-loop gain, 1/s.
    pub position_gain: ReversalEstimate,
    /// Radius offset, mm.
    pub offset: ReversalEstimate,
    /// Where the friction has turned half way after a reversal, degrees.
    pub halfway: f64,
    /// Measured trace angle, degrees.
    pub angle: Series,
    /// Measured deviation, mm.
    pub measured: Series,
    /// The fitted model there, mm.
    pub fitted: Series,
    /// Measured − fitted, mm.
    pub residuals: Series,
    /// Residual standard deviation, mm.
    pub sigma: f64,
    /// Iterations.
    pub iterations: usize,
    /// C's rated torque the shares are of, N·m (the input `c.ratedTorque`).
    pub rated_torque: f64,
    /// Fitted f_c over the rated torque.
    pub friction_share: f64,
    /// The torque step a friction compensator needs at each reversal, 2·f_c, N·m (with the
    /// interval of f_c doubled).
    pub torque_step: ReversalEstimate,
    /// The torque step over the rated torque.
    pub torque_step_share: f64,
}

/// Fits C's friction (f_c, a) and position-loop gain to a measured trace (`csv`), the other
/// inputs as given (the fit starts from the entered values).
#[wasm_bindgen(js_name = reversalFit, unchecked_return_type = "ReversalFitResult")]
pub fn reversal_fit(
    #[wasm_bindgen(unchecked_param_type = "ReversalCase & ReversalFitInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (case, own) =
        ReversalCase::read_with::<ReversalFitInput>(&json(&value)?).map_err(js_error)?;
    let m = fit::parse_trace(&own.csv).map_err(js_error)?;
    let f = fit::fit(&case, &m).map_err(js_error)?;
    let k = compensation(f.fc.value, case.c.rated_torque);
    let low = compensation(f.fc.low, case.c.rated_torque).step;
    let high = compensation(f.fc.high, case.c.rated_torque).step;
    output(&ReversalFitResult {
        rated_torque: k.rated,
        friction_share: k.friction_share,
        torque_step: ReversalEstimate {
            value: k.step,
            low,
            high,
        },
        torque_step_share: k.step_share,
        friction: estimate(f.fc),
        friction_slope: estimate(f.slope),
        position_gain: estimate(f.kp),
        offset: estimate(f.offset),
        halfway: f.halfway.to_degrees(),
        angle: degrees(&m.angle),
        measured: f64_array(&m.deviation),
        fitted: f64_array(&f.fitted),
        residuals: f64_array(&f.residuals),
        sigma: f.sigma,
        iterations: f.iterations,
    })
}

/// The dent measured from a trace itself (see `fiveaxis::reversal::measure`).
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct ReversalMeasuredDent {
    /// The trace's level before the reversal (median over 170°–179°), mm.
    pub baseline: f64,
    /// Depth: the largest fall below the baseline over 180°–190°, mm (0: no dent).
    pub depth: f64,
    /// Trace angle of the deepest point, degrees.
    pub angle: f64,
    /// Width at half depth, degrees of trace angle (a lower bound when `open`).
    pub width: f64,
    /// Where the fall crosses half depth before the deepest point, degrees.
    pub low: f64,
    /// And after it, degrees.
    pub high: f64,
    /// Still at half depth or more at 190°: a step more than a dent.
    pub open: bool,
    /// The width as a time at the test's feed on its circle, W·R/F, s.
    pub duration: f64,
    /// The level after the reversal (median over 188°–190°), mm.
    pub level_after: f64,
    /// Baseline − level after, mm.
    pub step: f64,
}

/// A measured trace read and its dent measured, without a fit.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct ReversalTraceResult {
    /// The machine the file names (`# machine: <name>`), or null.
    pub machine: Option<String>,
    /// Points read.
    pub points: usize,
    /// The dent measured from the trace.
    pub dent: ReversalMeasuredDent,
}

/// Reads a measured trace (`csv`) and measures its dent: depth and width from the trace itself,
/// and the machine its file names. Fast (no simulation); the test's R and F give the width in
/// time.
#[wasm_bindgen(js_name = reversalTrace, unchecked_return_type = "ReversalTraceResult")]
pub fn reversal_trace(
    #[wasm_bindgen(unchecked_param_type = "ReversalCase & ReversalFitInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (case, own) =
        ReversalCase::read_with::<ReversalFitInput>(&json(&value)?).map_err(js_error)?;
    let m = fit::parse_trace(&own.csv).map_err(js_error)?;
    let d = measure_dent(&m.angle, &m.deviation).map_err(js_error)?;
    output(&ReversalTraceResult {
        machine: fit::declared_machine(&own.csv).map(str::to_string),
        points: m.angle.len(),
        dent: ReversalMeasuredDent {
            baseline: d.baseline,
            depth: d.depth,
            angle: d.angle.to_degrees(),
            width: d.width.to_degrees(),
            low: d.low.to_degrees(),
            high: d.high.to_degrees(),
            open: d.open,
            duration: d.duration(case.test.radius, case.test.feed),
            level_after: d.level_after,
            step: d.step,
        },
    })
}
