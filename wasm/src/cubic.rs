//! Exports of the cubic-machining test (see [`crate::cubic`]).
//!
//! Units at this edge: positions and lengths in mm, angles in degrees (the paper's units; the
//! page converts µm and its angle unit to these). Sensitivities are per mm or **per degree**,
//! slopes are dimensionless (mm/mm). Grids are `Float64Array`s with their shape `nx`, `ny`,
//! row-major: the point `(x[ix], y[iy])` is entry `[iy * nx + ix]`. Zone × error tables are
//! zone-major `9 × 8`: entry `[zone * 8 + error]`, zones and errors in the orders of
//! `cubicTest(...).zones` and `cubicErrors()`.

use super::{error_value, f64_array, input, js_error, output, per_edge_unit};
use crate::cubic::{
    self, CubicSetup, GeometricErrors, Options, Reference, ZonePlane, ERRORS, MAX_ANGLE_ERROR_DEG,
    MAX_POSITION_ERROR,
};
use js_sys::Float64Array;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use wasm_bindgen::prelude::*;

#[wasm_bindgen(typescript_custom_section)]
const TS_TYPES: &'static str = r#"
/** The paper's eight errors (Table 3): positions in mm, angles in degrees. Missing ones are 0. */
export interface CubicErrorsInput {
  dxBY?: number; dyBY?: number; dzBY?: number;
  alphaBY?: number; betaBY?: number; gammaBY?: number;
  alphaCB?: number; dxCB?: number;
}
/** Set-up geometry and cutting parameters, mm. Missing ones take the defaults shown. */
export interface CubicSetupInput {
  /** Table surface above the B axis at B = 0 (0). */ tableAboveB?: number;
  /** Top face above the table (50). */ workpieceHeight?: number;
  /** C axis from the B axis along X (0: they intersect). */ cOffset?: number;
  /** Face centre from the C axis (0, 0). */ workpieceX?: number; workpieceY?: number;
  /** Side of a zone (16). */ zoneSize?: number;
  /** Ball-end radius r (3). */ toolRadius?: number;
  /** Pick feed p (0.1). */ pick?: number;
  /** Stock above the nominal face, shown where no pass cuts (0.1). */ stock?: number;
}
/** What heights are measured from: the workpiece frame, or Section 5.1's measurement frame set
 * on ZONE I (its height removed, or its plane: height and tilt). */
export type CubicReference = "workpiece" | "zone1-height" | "zone1-plane";
export interface CubicInput {
  errors: CubicErrorsInput;
  setup?: CubicSetupInput;
  /** The workpiece coordinate transformation M_WC (eqs 10-12): set up at B = C = 0. Default true. */
  transform?: boolean;
  /** Default "workpiece". */
  reference?: CubicReference;
}
export interface CubicMapInput extends CubicInput {
  /** Grid points along X and Y over the whole face (4 to 4001 each, nx·ny ≤ 4e6). */
  nx: number; ny: number;
}
export interface CubicErrorInfo {
  key: keyof CubicErrorsInput; symbol: string;
  /** The ISO 230-1 location error of the chain it maps onto, with a minus sign. */
  iso: string; axis: "B" | "C"; unit: "mm" | "deg"; description: string;
}
export interface CubicZone {
  name: "I" | "II-1" | "II-2" | "II-3" | "II-4" | "III-1" | "III-2" | "III-3" | "III-4";
  /** Column -1 (left) .. 1 (right), row -1 (bottom) .. 1 (top) of Fig 2. */
  col: number; row: number;
  /** Nominal centre in the workpiece frame, mm. */ x: number; y: number;
  /** Table 1, tip → spindle. */ toolVector: number[];
  /** Table 2, degrees (C in [0, 360)). */ b: number; c: number;
  /** Exact height at the zone centre for all entered errors, mm (positive: material left). */
  height: number;
  /** Exact slopes ∂z/∂x, ∂z/∂y (mm/mm). */ slopeX: number; slopeY: number;
  /** First-order estimates Σ k·ε. */ linearHeight: number; linearSlopeX: number; linearSlopeY: number;
}
export interface CubicResult {
  zones: CubicZone[];
  errorKeys: (keyof CubicErrorsInput)[];
  /** Sensitivity k = E/ε (eq 15) of the height, 9 × 8 zone-major: mm/mm or mm/degree. */
  kHeight: Float64Array;
  /** Sensitivities of the slopes, 9 × 8: per mm or per degree. */
  kSlopeX: Float64Array; kSlopeY: Float64Array;
  /** Exact height with only that error at its entered value, 9 × 8, mm (0 where it is 0). */
  single: Float64Array;
  transform: boolean; reference: CubicReference;
}
export interface CubicMapResult {
  nx: number; ny: number;
  /** Grid coordinates, mm, over the face (-1.5·zoneSize to 1.5·zoneSize). */
  x: Float64Array; y: Float64Array;
  /** Heights, mm, row-major ny × nx: (x[ix], y[iy]) is [iy * nx + ix]. Scallops included. */
  height: Float64Array;
  /** Average height of each zone (order of cubicTest's zones), mm. */
  zoneAverage: number[];
  /** The zones in the same order: name and nominal centre (workpiece frame, mm). */
  zones: { name: string; x: number; y: number }[];
  /** Smallest and largest height, mm. */ min: number; max: number;
  /** Actual step between passes (≤ pick), mm, and its closed-form scallop height r − √(r² − (step/2)²), mm. */
  step: number; scallop: number;
  /** Passes simulated and pass-point evaluations made. */ passes: number; evaluations: number;
}
"#;

/// The errors as the binding reads them: mm and degrees, missing ones zero, unknown keys refused
/// (see [`strict`]).
#[derive(Deserialize, Default)]
#[serde(default, deny_unknown_fields)]
#[allow(non_snake_case)] // the JavaScript keys, spelt as in the paper
struct ErrorsIn {
    dxBY: f64,
    dyBY: f64,
    dzBY: f64,
    alphaBY: f64,
    betaBY: f64,
    gammaBY: f64,
    alphaCB: f64,
    dxCB: f64,
}

impl ErrorsIn {
    /// Checks (in the units given) and converts to the engine's mm and rad.
    fn engine(&self) -> Result<GeometricErrors, JsError> {
        let given = [
            self.dxBY,
            self.dyBY,
            self.dzBY,
            self.alphaBY,
            self.betaBY,
            self.gammaBY,
            self.alphaCB,
            self.dxCB,
        ];
        let mut out = [0.0; 8];
        for ((def, v), o) in ERRORS.iter().zip(given).zip(out.iter_mut()) {
            let limit = if def.angular {
                MAX_ANGLE_ERROR_DEG
            } else {
                MAX_POSITION_ERROR
            };
            *o = error_value(&format!("errors.{}", def.key), v, def.angular, limit)?;
        }
        Ok(GeometricErrors(out))
    }
}

/// A JavaScript object of numbers read into `T`, refusing keys `T` does not know.
///
/// serde-wasm-bindgen reads a struct by asking for its known properties only, so
/// `deny_unknown_fields` would never see a misspelt key (and a misspelt error would silently be
/// zero). The object is therefore read as a map first (values checked, with their paths), and
/// `T` is deserialised from that map, where serde does refuse unknown keys.
fn strict<T: DeserializeOwned>(path: &str, map: BTreeMap<String, f64>) -> Result<T, JsError> {
    let de = serde::de::value::MapDeserializer::<_, serde::de::value::Error>::new(map.into_iter());
    T::deserialize(de).map_err(|e| JsError::new(&format!("{path}: {e}")))
}

#[derive(Deserialize)]
struct CaseIn {
    errors: BTreeMap<String, f64>,
    #[serde(default)]
    setup: Option<BTreeMap<String, f64>>,
    #[serde(default)]
    transform: Option<bool>,
    #[serde(default)]
    reference: Reference,
}

impl CaseIn {
    fn engine(self) -> Result<(CubicSetup, GeometricErrors, Options), JsError> {
        let setup: CubicSetup = match self.setup {
            Some(map) => strict("setup", map)?,
            None => CubicSetup::default(),
        };
        setup.validate().map_err(js_error)?;
        let errors: ErrorsIn = strict("errors", self.errors)?;
        Ok((
            setup,
            errors.engine()?,
            Options {
                transform: self.transform.unwrap_or(true),
                reference: self.reference,
            },
        ))
    }
}

/// The eight errors of the paper (Table 3): key, symbol, unit and the chain's location error.
#[wasm_bindgen(js_name = cubicErrors, unchecked_return_type = "CubicErrorInfo[]")]
pub fn cubic_errors() -> Result<JsValue, JsError> {
    #[derive(Serialize)]
    struct Info {
        key: &'static str,
        symbol: &'static str,
        iso: &'static str,
        axis: &'static str,
        unit: &'static str,
        description: &'static str,
    }
    let list: Vec<Info> = ERRORS
        .iter()
        .map(|d| Info {
            key: d.key,
            symbol: d.symbol,
            iso: d.iso,
            axis: d.axis,
            unit: if d.angular { "deg" } else { "mm" },
            description: d.description,
        })
        .collect();
    output(&list)
}

/// Zone heights and tilts (exact and first-order), sensitivities of every error on every zone,
/// and the exact effect of each error alone (Figs 10, 12; Table 2).
#[wasm_bindgen(js_name = cubicTest, unchecked_return_type = "CubicResult")]
pub fn cubic_test(
    #[wasm_bindgen(unchecked_param_type = "CubicInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Zone {
        name: &'static str,
        col: i32,
        row: i32,
        x: f64,
        y: f64,
        tool_vector: [f64; 3],
        b: f64,
        c: f64,
        height: f64,
        slope_x: f64,
        slope_y: f64,
        linear_height: f64,
        linear_slope_x: f64,
        linear_slope_y: f64,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        zones: Vec<Zone>,
        error_keys: Vec<&'static str>,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        k_height: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        k_slope_x: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        k_slope_y: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        single: Float64Array,
        transform: bool,
        reference: Reference,
    }
    let case: CaseIn = input(value)?;
    let (setup, errors, options) = case.engine()?;
    let a = cubic::analyze(&setup, &errors, &options).map_err(js_error)?;
    let table = |f: fn(&ZonePlane) -> f64| -> Vec<f64> {
        a.sensitivity
            .iter()
            .flat_map(|row| {
                row.iter()
                    .zip(ERRORS)
                    .map(move |(k, def)| per_edge_unit(f(k), def.angular))
            })
            .collect()
    };
    let single: Vec<f64> = a.single.iter().flatten().copied().collect();
    output(&Out {
        zones: a
            .zones
            .iter()
            .map(|z| Zone {
                name: z.zone.name,
                col: z.zone.col,
                row: z.zone.row,
                x: z.centre[0],
                y: z.centre[1],
                tool_vector: z.zone.tool,
                b: z.b.to_degrees(),
                c: z.c.to_degrees(),
                height: z.exact.height,
                slope_x: z.exact.slope_x,
                slope_y: z.exact.slope_y,
                linear_height: z.linear.height,
                linear_slope_x: z.linear.slope_x,
                linear_slope_y: z.linear.slope_y,
            })
            .collect(),
        error_keys: ERRORS.iter().map(|d| d.key).collect(),
        k_height: f64_array(&table(|k| k.height)),
        k_slope_x: f64_array(&table(|k| k.slope_x)),
        k_slope_y: f64_array(&table(|k| k.slope_y)),
        single: f64_array(&single),
        transform: options.transform,
        reference: options.reference,
    })
}

/// The simulated machined face (Fig 16(b)): ball-end zig-zag passes, scallops included, on an
/// `nx × ny` grid, with each zone's average height.
#[wasm_bindgen(js_name = cubicHeightMap, unchecked_return_type = "CubicMapResult")]
pub fn cubic_height_map(
    #[wasm_bindgen(unchecked_param_type = "CubicMapInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    // The same object read twice: the case (CaseIn asks only for its own properties) and the
    // grid, so that messages keep their paths (serde's flatten would lose them).
    #[derive(Deserialize)]
    struct Grid {
        nx: usize,
        ny: usize,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        nx: usize,
        ny: usize,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        x: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        y: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        height: Float64Array,
        zone_average: Vec<f64>,
        zones: Vec<ZoneAt>,
        min: f64,
        max: f64,
        step: f64,
        scallop: f64,
        passes: usize,
        evaluations: usize,
    }
    #[derive(Serialize)]
    struct ZoneAt {
        name: &'static str,
        x: f64,
        y: f64,
    }
    let case: CaseIn = input(value.clone())?;
    let grid: Grid = input(value)?;
    let (setup, errors, options) = case.engine()?;
    let m = cubic::height_map(&setup, &errors, &options, grid.nx, grid.ny).map_err(js_error)?;
    let min = m.height.iter().copied().fold(f64::INFINITY, f64::min);
    let max = m.height.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    output(&Out {
        nx: m.nx,
        ny: m.ny,
        x: f64_array(&m.x),
        y: f64_array(&m.y),
        height: f64_array(&m.height),
        zone_average: m.zone_average,
        zones: cubic::ZONES
            .iter()
            .map(|z| ZoneAt {
                name: z.name,
                x: z.col as f64 * setup.zone_size,
                y: z.row as f64 * setup.zone_size,
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
