//! Exports of the cubic-machining test (see `fiveaxis::cubic`).
//!
//! Units at this edge: lengths in mm, angles in degrees. Sensitivities are per mm or **per
//! degree** (the engine's are per rad); slopes are dimensionless (mm/mm). Grids are
//! `Float64Array`s with their shape `nx`, `ny`, row-major: the point `(x[ix], y[iy])` is entry
//! `[iy * nx + ix]`. Zone × error tables are zone-major `9 × n`: entry `[zone * n + error]`,
//! zones in the order of `zones`, errors in the order of `errorNames` (the machine's errors in
//! the order of the error table).

use crate::identify::{identification, Identification};
use crate::{api_combination, f64_array, js_error, json, output, Series};
use fiveaxis::cubic::design::{design, CubicDesignInput};
use fiveaxis::cubic::identify::{identify_zones, CubicIdentifyInput};
use fiveaxis::cubic::{self, CubicInput, CubicReference, ZonePlane};
use serde::Serialize;
use tsify::Tsify;
use wasm_bindgen::prelude::*;

/// One zone.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct CubicZone {
    /// "I", "II-1", … "III-4".
    pub name: String,
    /// Column −1 (left) .. 1 (right), row −1 (bottom) .. 1 (top) of Fig 2, on the face.
    pub col: i32,
    /// Row.
    pub row: i32,
    /// Nominal centre on the face (along its axes u, v), mm.
    pub x: f64,
    /// Its second coordinate, mm.
    pub y: f64,
    /// Table 1's tool vector in workpiece (machine) coordinates, tip → spindle.
    pub tool_vector: [f64; 3],
    /// K and M commands that cut the zone, degrees (Table 2 on Li et al.'s machine: C, B).
    pub k: f64,
    /// M, degrees.
    pub m: f64,
    /// The tool lies along K here (K arbitrary, 0 used).
    pub singular: bool,
    /// Exact height at the zone centre for all the machine's errors, mm (positive: material
    /// left).
    pub height: f64,
    /// Exact slopes along u and v (mm/mm).
    pub slope_x: f64,
    /// Along v.
    pub slope_y: f64,
    /// First-order estimates Σ k·ε.
    pub linear_height: f64,
    /// First-order slope along u.
    pub linear_slope_x: f64,
    /// First-order slope along v.
    pub linear_slope_y: f64,
}

/// A group of errors the zone heights cannot tell apart.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct AlikeMember {
    /// ISO name.
    pub name: String,
    /// `k_member = factor · k_first`, sensitivities per mm or per degree.
    pub factor: f64,
}

/// What the test can see (see `fiveaxis::cubic::Visibility`).
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct CubicVisibility {
    /// Errors with zero height sensitivity in every zone.
    pub invisible: Vec<String>,
    /// Of those, the ones that tilt some zone.
    pub tilt_only: Vec<String>,
    /// Groups of errors with proportional height sensitivities.
    pub alike: Vec<Vec<AlikeMember>>,
    /// Independent combinations the heights determine.
    pub rank: usize,
}

/// The cubic test's results.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct CubicResult {
    /// The nine zones in Table 1's order.
    pub zones: Vec<CubicZone>,
    /// The machine's errors, the columns of the tables (ISO 230-1 names).
    pub error_names: Vec<String>,
    /// Their units: "mm" or "deg".
    pub error_units: Vec<String>,
    /// Sensitivity k = E/ε (eq 15) of the height, 9 × n zone-major: mm/mm or mm/degree.
    pub k_height: Series,
    /// Sensitivities of the slopes along u, 9 × n: per mm or per degree.
    pub k_slope_x: Series,
    /// Along v.
    pub k_slope_y: Series,
    /// Exact height with only that error at its entered value, 9 × n, mm (0 where it is 0).
    pub single: Series,
    /// What the test can and cannot see.
    pub visibility: CubicVisibility,
    /// The workpiece set at zero (M_WC).
    pub transform: bool,
    /// What heights are measured from.
    pub reference: CubicReference,
}

/// Zone heights and tilts (exact and first-order), sensitivities of every error of the machine
/// on every zone, the exact effect of each error alone, and what the test cannot see.
#[wasm_bindgen(js_name = cubicTest, unchecked_return_type = "CubicResult")]
pub fn cubic_test(
    #[wasm_bindgen(unchecked_param_type = "CubicInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let input = CubicInput::read(&json(&value)?).map_err(js_error)?;
    let options = input.options();
    let a = cubic::analyze(&input.machine, &input.setup, &options).map_err(js_error)?;
    let n = a.errors.len();
    let table = |f: fn(&ZonePlane) -> f64| -> Vec<f64> {
        a.sensitivity
            .iter()
            .flat_map(|row| {
                row.iter()
                    .zip(&a.errors)
                    .map(move |(k, d)| d.quantity.per_api_unit(f(k)))
            })
            .collect()
    };
    let single: Vec<f64> = a.single.iter().flatten().copied().collect();
    let v = &a.visibility;
    let visibility = CubicVisibility {
        invisible: v.invisible.iter().map(|s| s.to_string()).collect(),
        tilt_only: v.tilt_only.iter().map(|s| s.to_string()).collect(),
        alike: v
            .alike
            .iter()
            .map(|g| {
                // k_b = f·k_a: the combination k_a·(x_a + f·x_b + …) the test sees.
                let (factors, _) = api_combination(g.iter().map(|(name, f)| (*name, *f)));
                g.iter()
                    .zip(factors)
                    .map(|((name, _), factor)| AlikeMember {
                        name: name.to_string(),
                        factor,
                    })
                    .collect()
            })
            .collect(),
        rank: v.rank,
    };
    debug_assert_eq!(single.len(), 9 * n);
    output(&CubicResult {
        zones: a
            .zones
            .iter()
            .map(|z| CubicZone {
                name: z.zone.name.to_string(),
                col: z.zone.col,
                row: z.zone.row,
                x: z.centre[0],
                y: z.centre[1],
                tool_vector: z.tool,
                k: z.rotary[0].to_degrees(),
                m: z.rotary[1].to_degrees(),
                singular: z.singular,
                height: z.exact.height,
                slope_x: z.exact.slope_x,
                slope_y: z.exact.slope_y,
                linear_height: z.linear.height,
                linear_slope_x: z.linear.slope_x,
                linear_slope_y: z.linear.slope_y,
            })
            .collect(),
        error_names: a.errors.iter().map(|d| d.name.to_string()).collect(),
        error_units: a
            .errors
            .iter()
            .map(|d| d.quantity.api_unit().to_string())
            .collect(),
        k_height: f64_array(&table(|k| k.height)),
        k_slope_x: f64_array(&table(|k| k.slope_x)),
        k_slope_y: f64_array(&table(|k| k.slope_y)),
        single: f64_array(&single),
        visibility,
        transform: options.transform,
        reference: options.reference,
    })
}

/// A zone's name and nominal centre on the face.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct ZoneAt {
    /// Its name.
    pub name: String,
    /// Centre along u, mm.
    pub x: f64,
    /// Along v, mm.
    pub y: f64,
}

/// The simulated face.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct CubicMapResult {
    /// Columns (along u).
    pub nx: usize,
    /// Rows (along v).
    pub ny: usize,
    /// Grid coordinates along u, mm (−1.5·zoneSize to 1.5·zoneSize).
    pub x: Series,
    /// Along v, mm.
    pub y: Series,
    /// Heights, mm, row-major ny × nx: `(x[ix], y[iy])` is `[iy * nx + ix]`. Scallops included.
    pub height: Series,
    /// Average height of each zone (order of cubicTest's zones), mm.
    pub zone_average: Vec<f64>,
    /// The zones in the same order.
    pub zones: Vec<ZoneAt>,
    /// Smallest height, mm.
    pub min: f64,
    /// Largest height, mm.
    pub max: f64,
    /// Actual step between passes (≤ pick), mm.
    pub step: f64,
    /// Its closed-form scallop height r − √(r² − (step/2)²), mm.
    pub scallop: f64,
    /// Passes simulated.
    pub passes: usize,
    /// Pass-point evaluations made.
    pub evaluations: usize,
}

/// The simulated machined face (Fig 16(b)): ball-end zig-zag passes, scallops included, on an
/// `nx × ny` grid (`ny` automatic when left out), with each zone's average height.
#[wasm_bindgen(js_name = cubicHeightMap, unchecked_return_type = "CubicMapResult")]
pub fn cubic_height_map(
    #[wasm_bindgen(unchecked_param_type = "CubicInput & CubicGrid")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (input, grid) = CubicInput::read_with_grid(&json(&value)?).map_err(js_error)?;
    let m = cubic::height_map(&input.machine, &input.setup, &input.options(), &grid)
        .map_err(js_error)?;
    let min = m.height.iter().copied().fold(f64::INFINITY, f64::min);
    let max = m.height.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let zs = input.setup.zone_size;
    output(&CubicMapResult {
        nx: m.nx,
        ny: m.ny,
        x: f64_array(&m.x),
        y: f64_array(&m.y),
        height: f64_array(&m.height),
        zone_average: m.zone_average,
        zones: cubic::ZONES
            .iter()
            .map(|z| ZoneAt {
                name: z.name.to_string(),
                x: z.col as f64 * zs,
                y: z.row as f64 * zs,
            })
            .collect(),
        min,
        max,
        step: m.step,
        scallop: m.scallop,
        passes: m.passes,
        evaluations: m.evaluations,
    })
}

/// A zone of a measured or designed layout on the machine.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct CubicLayoutZone {
    /// Its name.
    pub name: String,
    /// Set-up 1 or 2 (the designer's; 1 for a measured file).
    pub setup: usize,
    /// The face centre's distance from the table centre along u in its set-up, mm.
    pub piece_x: f64,
    /// Centre on the face, mm.
    pub x: f64,
    /// Its second coordinate, mm.
    pub y: f64,
    /// Tilt of the tool from the face normal, degrees.
    pub tilt: f64,
    /// Azimuth of the tilt in the face frame (0 towards +u), degrees.
    pub azimuth: f64,
    /// Tool vector in workpiece coordinates, tip → spindle.
    pub tool_vector: [f64; 3],
    /// K command, degrees.
    pub k: f64,
    /// M command, degrees.
    pub m: f64,
}

fn layout_zone(z: &fiveaxis::cubic::identify::LayoutZone, setup: usize) -> CubicLayoutZone {
    let t = z.spec.tool;
    let tilt = t[2].clamp(-1.0, 1.0).acos();
    let azimuth = if tilt < 1e-12 { 0.0 } else { t[1].atan2(t[0]) };
    CubicLayoutZone {
        name: z.spec.name.clone(),
        setup,
        piece_x: z.piece_x,
        x: z.spec.centre.0,
        y: z.spec.centre.1,
        tilt: tilt.to_degrees(),
        azimuth: azimuth.to_degrees().rem_euclid(360.0),
        tool_vector: z.tool,
        k: z.rotary[0].to_degrees(),
        m: z.rotary[1].to_degrees(),
    }
}

/// The cubic identification.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct CubicIdentifyResult {
    /// The fit, the decisions and the words (shared with the S-shape).
    #[serde(flatten)]
    pub fit: Identification,
    /// The measured zones in file order.
    pub zones: Vec<CubicLayoutZone>,
    /// Per row of the fit: the zone's index in `zones`.
    pub row_zone: Vec<usize>,
    /// Per row: "height", "slopeX" or "slopeY".
    pub row_kind: Vec<String>,
    /// Measured value per row: mm for a height; for a slope the height it makes over half a
    /// zone, mm.
    pub measured: Series,
    /// Fitted value per row, same units.
    pub fitted: Series,
    /// Measured minus fitted, same units.
    pub residuals: Series,
    /// RMS of the residuals, mm.
    pub rms: f64,
}

/// Identification of the machine's errors from measured zone heights (and slopes) of a cubic
/// test piece, the paper's layout or a designed one (`csv`, see `fiveaxis::cubic::identify`).
#[wasm_bindgen(js_name = cubicIdentify, unchecked_return_type = "CubicIdentifyResult")]
pub fn cubic_identify(
    #[wasm_bindgen(unchecked_param_type = "CubicInput & CubicIdentifyInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (input, own): (CubicInput, CubicIdentifyInput) =
        CubicInput::read_with(&json(&value)?).map_err(js_error)?;
    let r = identify_zones(&input, &own).map_err(js_error)?;
    let f = &r.judgement.fit;
    let measured: Vec<f64> = f
        .fitted
        .iter()
        .zip(&f.residuals)
        .map(|(a, b)| a + b)
        .collect();
    output(&CubicIdentifyResult {
        zones: r.zones.iter().map(|z| layout_zone(z, 1)).collect(),
        row_zone: r.rows.iter().map(|(z, _)| *z).collect(),
        row_kind: r
            .rows
            .iter()
            .map(|(_, k)| ["height", "slopeX", "slopeY"][*k].to_string())
            .collect(),
        measured: f64_array(&measured),
        fitted: f64_array(&f.fitted),
        residuals: f64_array(&f.residuals),
        rms: f.rms,
        fit: identification(&r.judgement),
    })
}

/// A layout's quality for the designer.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct CubicLayoutReport {
    /// Its zones, the table to machine.
    pub zones: Vec<CubicLayoutZone>,
    /// Rank of its scaled sensitivity matrix.
    pub rank: usize,
    /// Condition number σ₁/σ_r (null: rank short of what the machine allows).
    pub condition: Option<f64>,
    /// The r-th singular value: the weakest combination of typical errors, in noise
    /// standard deviations.
    pub smallest: f64,
    /// Singular values of the scaled matrix, descending.
    pub singular_values: Vec<f64>,
    /// Errors it identifies on their own.
    pub identifiable: Vec<String>,
    /// Errors it cannot separate, with what it can see of them.
    pub groups: Vec<CubicDesignGroup>,
    /// The zone table as CSV (empty height_um, slope_x, slope_y to fill in); `cubicIdentify`
    /// reads it back.
    pub csv: String,
}

/// Errors a layout cannot separate.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct CubicDesignGroup {
    /// The errors.
    pub members: Vec<String>,
    /// What it can see of them (none: nothing).
    pub combinations: Vec<String>,
}

/// The designer's result.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct CubicDesignResult {
    /// The errors considered.
    pub error_names: Vec<String>,
    /// The rank every candidate zone together reaches: what any such test can determine.
    pub reachable_rank: usize,
    /// Candidate zones the machine reaches within its travel.
    pub candidates: usize,
    /// What no such test can see (all candidates together).
    pub unseen: Vec<CubicDesignGroup>,
    /// How the matrix is scaled, in words.
    pub scaling: String,
    /// The paper's layout (null when it cannot be cut: see `paperMessage`).
    pub paper: Option<CubicLayoutReport>,
    /// Why the paper's layout cannot be cut.
    pub paper_message: Option<String>,
    /// The designed layout.
    pub designed: CubicLayoutReport,
}

fn design_groups(f: &fiveaxis::identify::Fit) -> Vec<CubicDesignGroup> {
    f.groups
        .iter()
        .map(|g| CubicDesignGroup {
            members: g.members.clone(),
            combinations: g
                .combinations
                .iter()
                .map(|c| {
                    let (k, _) = api_combination(c.terms.iter().map(|(n, k)| (n.as_str(), *k)));
                    let terms: Vec<(String, f64)> = c
                        .terms
                        .iter()
                        .zip(k)
                        .map(|((n, _), k)| (n.clone(), k))
                        .collect();
                    fiveaxis::identify::combination_text(&terms)
                })
                .collect(),
        })
        .collect()
}

fn layout_report(r: &fiveaxis::cubic::design::LayoutReport) -> CubicLayoutReport {
    CubicLayoutReport {
        zones: r
            .zones
            .iter()
            .map(|z| layout_zone(&z.zone, z.setup))
            .collect(),
        rank: r.rank,
        condition: r.condition.is_finite().then_some(r.condition),
        smallest: r.smallest,
        singular_values: r.singular_values.clone(),
        identifiable: r
            .fit
            .estimates
            .iter()
            .filter(|e| e.value.is_some())
            .map(|e| e.name.clone())
            .collect(),
        groups: design_groups(&r.fit),
        csv: r.csv.clone(),
    }
}

/// The test designer: the zones' tool vectors (and optionally a second set-up) that make every
/// error a face of this kind can reveal identifiable, beside the paper's layout.
#[wasm_bindgen(js_name = cubicDesign, unchecked_return_type = "CubicDesignResult")]
pub fn cubic_design(
    #[wasm_bindgen(unchecked_param_type = "CubicInput & CubicDesignInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (input, own): (CubicInput, CubicDesignInput) =
        CubicInput::read_with(&json(&value)?).map_err(js_error)?;
    let d = design(&input, &own).map_err(js_error)?;
    output(&CubicDesignResult {
        error_names: d.errors.iter().map(|e| e.name.to_string()).collect(),
        reachable_rank: d.reachable_rank,
        candidates: d.candidates,
        unseen: design_groups(&d.all),
        scaling: fiveaxis::cubic::design::SCALING.to_string(),
        paper: d.paper.as_ref().ok().map(layout_report),
        paper_message: d.paper.as_ref().err().cloned(),
        designed: layout_report(&d.designed),
    })
}
