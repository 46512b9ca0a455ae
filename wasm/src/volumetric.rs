//! Exports of the volumetric study (see `fiveaxis::volumetric`).
//!
//! Units at this edge: positions and deviations in mm, angles (the tool's tilt error, the
//! paper's angular symbols) in degrees. Maps are `Float64Array`s of shape `nu × nv`, row-major:
//! the point `(u[i], v[j])` is entry `[j * nu + i]`.

use crate::{degrees, f64_array, js_error, json, output, Series};
use fiveaxis::machine::motions::CsvTable;
use fiveaxis::volumetric::{
    self, Contribution, MotionTableInput, VolumetricInput, VolumetricPaperInput,
};
use serde::Serialize;
use tsify::Tsify;
use wasm_bindgen::prelude::*;

/// The worst point of a map.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct VolumetricWorst {
    /// X, Y, Z, mm.
    pub position: [f64; 3],
    /// Deviation of the tip in workpiece coordinates, mm.
    pub deviation: [f64; 3],
    /// Its length, mm.
    pub norm: f64,
    /// Tilt error of the tool axis, degrees.
    pub tilt: f64,
}

/// The map (see `fiveaxis::volumetric::VolumetricMap`).
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct VolumetricMapResult {
    /// The plane's first and second axis and the fixed one: `["X", "Y", "Z"]`.
    pub axes: [String; 3],
    /// Positions along the first axis, mm.
    pub u: Series,
    /// Positions along the second axis, mm.
    pub v: Series,
    /// Deviation along X, Y, Z of the workpiece, mm (row-major).
    pub dx: Series,
    /// Along Y.
    pub dy: Series,
    /// Along Z.
    pub dz: Series,
    /// `|Δ|`, mm.
    pub norm: Series,
    /// Tilt error of the tool axis, degrees.
    pub tilt: Series,
    /// The worst point.
    pub worst: VolumetricWorst,
    /// rms of `|Δ|`, mm.
    pub rms: f64,
    /// Each error's share of the squared deviation (adds up to 1), rms and max (mm), largest
    /// share first.
    pub budget: Vec<Contribution>,
    /// Grid points per side the budget used.
    pub budget_side: [usize; 2],
    /// Largest `|exact − first order|` on those points, mm.
    pub first_order_gap: f64,
    /// Largest first-order `|Δ|` there, mm.
    pub first_order_max: f64,
    /// The third axis's position used, mm: the input's, or when left out the tool tip on the
    /// table surface (the plane across the spindle axis; else 0).
    pub at: f64,
    /// The spindle axis's position at which the tool tip is on the table surface, mm.
    pub surface_at: f64,
    /// The tool tip's distance from the machine origin (the rotary centre) at the linear axes'
    /// 0, against the spindle direction, mm: the tool length (table-table), or the head's pivot
    /// length plus the tool length.
    pub tip_offset: f64,
    /// The table surface from the machine origin along the spindle, mm.
    pub table_height: f64,
    /// The linear axis along the spindle at zero: "Z" for a vertical spindle.
    pub spindle_axis: String,
    /// One plain sentence.
    pub summary: String,
}

/// The tool tip's deviation over a plane of the working volume for all the machine's errors
/// and error motions, its worst point and the error budget.
#[wasm_bindgen(js_name = volumetricMap, unchecked_return_type = "VolumetricMapResult")]
pub fn volumetric_map(
    #[wasm_bindgen(unchecked_param_type = "VolumetricInput")] input: JsValue,
) -> Result<JsValue, JsError> {
    let i = VolumetricInput::read(&json(&input)?).map_err(js_error)?;
    let m = volumetric::map(&i).map_err(js_error)?;
    let entered =
        i.machine.errors.0.values().filter(|v| **v != 0.0).count() + i.machine.motions.0.len();
    let summary = m.summary(entered);
    output(&VolumetricMapResult {
        axes: m.axes.map(|c| c.to_string()),
        u: f64_array(&m.u),
        v: f64_array(&m.v),
        dx: f64_array(&m.deviation[0]),
        dy: f64_array(&m.deviation[1]),
        dz: f64_array(&m.deviation[2]),
        norm: f64_array(&m.norm),
        tilt: degrees(&m.tilt),
        worst: VolumetricWorst {
            position: m.worst.position,
            deviation: m.worst.deviation,
            norm: m.worst.norm,
            tilt: m.worst.tilt.to_degrees(),
        },
        rms: m.rms,
        budget: m.budget,
        budget_side: m.budget_side,
        first_order_gap: m.first_order_gap,
        first_order_max: m.first_order_max,
        at: m.at,
        surface_at: m.surface_at,
        tip_offset: m.tip_offset,
        table_height: m.table_height,
        spindle_axis: m.spindle_axis.to_string(),
        summary,
    })
}

/// One of Tan & Lim's symbols at the pose.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct PaperSymbol {
    /// As printed: "δx(X)", "φ_C", "α".
    pub symbol: String,
    /// Its value in the paper's sign: mm, or degrees for an angle.
    pub value: f64,
    /// "mm" or "deg".
    pub unit: String,
}

/// Tan & Lim's model beside the machine's (see `fiveaxis::volumetric::PaperComparison`), mm.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct VolumetricPaperResult {
    /// The loop solved exactly (machine axes).
    pub paper_loop: [f64; 3],
    /// The printed first-order ΔX, ΔY, ΔZ.
    pub paper_printed: [f64; 3],
    /// The machine's exact deviation, workpiece coordinates.
    pub machine: [f64; 3],
    /// The same along the machine axes.
    pub machine_axes: [f64; 3],
    /// The paper's 33 symbols at the pose.
    pub symbols: Vec<PaperSymbol>,
    /// Errors of the machine the paper's loop does not have.
    pub not_in_paper: Vec<String>,
}

/// Tan & Lim's RRTTT model (their loop and their printed first-order formulas) beside the
/// machine's exact model at one pose of their machine.
#[wasm_bindgen(js_name = volumetricPaper, unchecked_return_type = "VolumetricPaperResult")]
pub fn volumetric_paper(
    #[wasm_bindgen(unchecked_param_type = "VolumetricPaperInput")] input: JsValue,
) -> Result<JsValue, JsError> {
    use fiveaxis::schema::Inputs;
    let i = VolumetricPaperInput::from_value(&json(&input)?, "").map_err(js_error)?;
    i.machine.validate("machine").map_err(js_error)?;
    let c = volumetric::compare(&i.machine, [i.x, i.y, i.z], i.k, i.m).map_err(js_error)?;
    let symbols = c
        .symbols
        .iter()
        .enumerate()
        .map(|(s, (symbol, v))| {
            let angle = volumetric::paper::is_angle(s);
            PaperSymbol {
                symbol: symbol.clone(),
                value: if angle { v.to_degrees() } else { *v },
                unit: if angle { "deg" } else { "mm" }.to_string(),
            }
        })
        .collect();
    output(&VolumetricPaperResult {
        paper_loop: c.paper_loop,
        paper_printed: c.paper_printed,
        machine: c.machine,
        machine_axes: c.machine_axes,
        symbols,
        not_in_paper: c.not_in_paper,
    })
}

/// Reads a measured table of one error motion from CSV (`{ name: "E_XX", text }`): positions
/// in mm or degrees, values in mm or degrees, converted from the units in the header. Errors
/// name the line: `csv: line 7: …`. The result's `position` and `value` go into
/// `machine.motions[name]` as they are.
#[wasm_bindgen(js_name = volumetricReadTable, unchecked_return_type = "CsvTable")]
pub fn volumetric_read_table(
    #[wasm_bindgen(unchecked_param_type = "MotionTableInput")] input: JsValue,
) -> Result<JsValue, JsError> {
    let t: CsvTable = MotionTableInput::read_table(&json(&input)?).map_err(js_error)?;
    output(&t)
}
