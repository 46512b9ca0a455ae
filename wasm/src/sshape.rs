//! Exports of the S-shape study (see [`crate::sshape`]). Lengths in mm, angles in degrees (the
//! machine's angular errors too), like every export; the engine works in radians inside.

use super::{error_value, f64_array, input, js_error, output, per_edge_unit};
use crate::error::{check_count, check_range, Error};
use crate::sshape::identify::{combination_text, parse_measurements, DEFAULT_RTOL};
use crate::sshape::machine::{
    Branch, DefectModel, Errors, Point, Reference, ERROR_NAMES, IS_LENGTH, MAX_L0,
};
use crate::sshape::overcut::{OvercutMap, ToolPath};
use crate::sshape::part::{Part, SurfaceId};
use crate::sshape::study::{self, Design, MAX_ERROR};
use js_sys::Float64Array;
use serde::{Deserialize, Serialize};
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::prelude::*;

#[wasm_bindgen(typescript_custom_section)]
const TS_TYPES: &'static str = r#"
/** The S-shape machine and tool (Chanal et al. 2022, Section 5.2 and eq 2). */
export interface SShapeMachine {
  /** Pivot (B axis) to tool tip, mm (paper 499.889). */ l0: number;
  /** Tool radius, mm (paper 10). */ rTool: number;
  /** Tool length: tip to the section touching the top curve, mm (paper 35). */ lTool: number;
  /** Inverse kinematics: "paper" (B ≥ 0) or "continuous" (nearest the previous pose). */ branch?: "paper" | "continuous";
  /** Eq 14's reference: "workOrigin" (tool tip at the workpiece origin) or "axesZero" (as printed). */ reference?: "workOrigin" | "axesZero";
  /** Which tool point eq 14 moves: "tip" (eq 14) or "contact" (the axis point at the measurement height). */ point?: "tip" | "contact";
}
/** The 8 location errors of Table 3: E_X0B in mm, the others in degrees; missing = 0. */
export interface SShapeErrors {
  E_C0Y?: number; E_A0Z?: number; E_B0Z?: number; E_A0C?: number;
  E_B0C?: number; E_X0B?: number; E_A0B?: number; E_C0B?: number;
}
export interface SShapePartInput { nu?: number; nv?: number }
export interface SShapeSurfaceMesh {
  id: "A" | "B"; nu: number; nv: number;
  /** Row-major nv × nu ([iv * nu + iu]), mm; u from 0 to 1 along the S, v from the base (z = 0) to the top (z = 30). */
  x: Float64Array; y: Float64Array; z: Float64Array;
}
export interface SShapePoint {
  curve: "top" | "bottom"; number: number; surface: "A" | "B";
  u: number; v: number; point: number[]; normal: number[];
}
export interface SShapePartResult {
  surfaces: SShapeSurfaceMesh[];
  /** The 100 measurement points: TOP 1..50, then BOTTOM 1..50 (1..25 on A, 26..50 on B). */
  points: SShapePoint[];
  /** Length of each measurement curve, mm: [top A, top B, bottom A, bottom B]. */
  curveLengths: number[];
}
export interface SShapeOvercutInput { rTool: number; lTool: number; nu: number; nv: number }
export interface SShapeOvercutSurface {
  id: "A" | "B";
  /** Eq 6 with the paper's T, with T⊥, and the exact signed deviation δ (negative = gouge), mm, row-major nv × nu. */
  eq6Paper: Float64Array; eq6: Float64Array; exact: Float64Array;
  /** Largest eq 6 (paper's T, T⊥) and largest gouge (−δ), mm, with where: [u, z mm]. */
  maxEq6Paper: number; maxEq6: number; maxGouge: number;
  atEq6: number[]; atGouge: number[];
}
export interface SShapeOvercutResult {
  nu: number; nv: number;
  /** Grid: u from 0 to 1, z = 30·v mm. */ u: Float64Array; z: Float64Array;
  surfaces: SShapeOvercutSurface[];
  /** Eq 6 maxima on surface B with the paper's N = R × T (tool on B's side facing A): [paper T, T⊥], mm. */
  bPaperSide: number[];
  /** The paper's printed maxima, mm. */ paper: { a: number; b: number };
}
export interface SShapeDefectsInput { machine: SShapeMachine; errors: SShapeErrors; /** Tool radius error R' − R, mm. */ dR?: number }
export interface SShapePose { x: number; y: number; z: number; b: number; c: number; singular: boolean }
export interface SShapeDefectsResult {
  names: string[];
  /** Per point (list order): the deviation along the outward normal from all errors and dR, mm. */
  total: Float64Array;
  /** Row-major 100 × 8: the contribution of each error at each point, mm. */
  contributions: Float64Array;
  /** Row-major 100 × 8: mm per mm (E_X0B) or mm per degree (the others): Fig 19. */
  sensitivity: Float64Array;
  /** Per point: deviation from dR alone, mm. */ radius: Float64Array;
  /** Machine axes when the tool cuts each point (mm, degrees); singular: tool vertical, C kept. */
  poses: SShapePose[];
  /** Height of each point on the tool above its tip, mm. */ height: Float64Array;
  /** Cosine between the sensitivity columns of E_A0Z and E_A0C, and of E_B0Z and E_B0C (−1: alike but for sign). */
  pairCosines: number[];
}
export interface SShapeIdentifyInput {
  machine: SShapeMachine;
  /** The measurement file: header curve,point,deviation_mm (or deviation_um), 100 rows. */ csv: string;
  /** Fit a tool-radius error dR too (default true). */ radiusTerm?: boolean;
  /** Relative singular-value threshold of the rank decision (default 0.01). */ rtol?: number;
}
export interface SShapeEstimate {
  name: string; unit: "mm" | "°";
  /** null when not identifiable on its own. */ value: number | null; stdError: number | null;
  /** The minimum-norm value (a convention where not identifiable). */ minNorm: number;
  /** Index into groups when it cannot be separated from others. */ group: number | null;
}
export interface SShapeCombination { terms: [string, number][]; value: number; stdError: number; text: string }
export interface SShapeGroup { members: string[]; deficiency: number; combinations: SShapeCombination[] }
export interface SShapeIdentifyResult {
  estimates: SShapeEstimate[]; groups: SShapeGroup[]; rank: number;
  /** Relative singular values of the column-scaled matrix, descending. */ singularValues: number[];
  rtol: number;
  /** Per point, list order, mm. */ measured: Float64Array; fitted: Float64Array; residuals: Float64Array;
  rms: number; maxAbs: number; sigma: number;
}
"#;

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct MachineIn {
    l0: f64,
    r_tool: f64,
    l_tool: f64,
    #[serde(default)]
    branch: Branch,
    #[serde(default)]
    reference: Reference,
    #[serde(default)]
    point: Point,
}

#[derive(Deserialize, Default)]
#[allow(non_snake_case)]
struct ErrorsIn {
    #[serde(default)]
    E_C0Y: f64,
    #[serde(default)]
    E_A0Z: f64,
    #[serde(default)]
    E_B0Z: f64,
    #[serde(default)]
    E_A0C: f64,
    #[serde(default)]
    E_B0C: f64,
    #[serde(default)]
    E_X0B: f64,
    #[serde(default)]
    E_A0B: f64,
    #[serde(default)]
    E_C0B: f64,
}

impl ErrorsIn {
    /// The errors in engine units (mm, rad), checked.
    fn engine(&self) -> Result<Errors, JsError> {
        let given = [
            self.E_C0Y, self.E_A0Z, self.E_B0Z, self.E_A0C, self.E_B0C, self.E_X0B, self.E_A0B,
            self.E_C0B,
        ];
        let mut out = [0.0; 8];
        for (k, v) in given.iter().enumerate() {
            let angular = !IS_LENGTH[k];
            let limit = if angular {
                MAX_ERROR[k].to_degrees()
            } else {
                MAX_ERROR[k]
            };
            out[k] = error_value(&format!("errors.{}", ERROR_NAMES[k]), *v, angular, limit)?;
        }
        Ok(out)
    }
}

/// Engine unit → API unit of parameter `k` (rad → degrees; mm and the radius stay).
fn to_api(k: usize, v: f64) -> f64 {
    if k < 8 && !IS_LENGTH[k] {
        v.to_degrees()
    } else {
        v
    }
}

fn tool(r: f64, l: f64) -> Result<ToolPath, JsError> {
    ToolPath::new(r, l).map_err(js_error)
}

type Key = (u64, u64, u64, DefectModel);

thread_local! {
    /// The last few designs: the page asks for defects and an identification with the same
    /// machine, and a design costs a few milliseconds.
    static DESIGNS: RefCell<Vec<(Key, Rc<Design>)>> = const { RefCell::new(Vec::new()) };
}

fn design(m: &MachineIn) -> Result<Rc<Design>, JsError> {
    check_range("machine.l0", m.l0, 1.0, MAX_L0, "mm").map_err(js_error)?;
    let path = ToolPath::new(m.r_tool, m.l_tool)
        .map_err(|e| js_error(Error::field(format!("machine.{}", e.field), e.message)))?;
    let model = DefectModel {
        branch: m.branch,
        reference: m.reference,
        point: m.point,
    };
    let key = (
        m.l0.to_bits(),
        m.r_tool.to_bits(),
        m.l_tool.to_bits(),
        model,
    );
    if let Some(d) = DESIGNS.with(|c| {
        c.borrow()
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, d)| d.clone())
    }) {
        return Ok(d);
    }
    let d = Rc::new(Design::new(m.l0, path, model).map_err(js_error)?);
    DESIGNS.with(|c| {
        let mut c = c.borrow_mut();
        if c.len() >= 16 {
            c.remove(0);
        }
        c.push((key, d.clone()));
    });
    Ok(d)
}

/// The part for a 3D view: both surfaces on an `nu × nv` grid (default 131 × 7) and the 100
/// measurement points.
#[wasm_bindgen(js_name = sshapePart, unchecked_return_type = "SShapePartResult")]
pub fn sshape_part(
    #[wasm_bindgen(unchecked_param_type = "SShapePartInput | undefined")] value: JsValue,
) -> Result<JsValue, JsError> {
    #[derive(Deserialize, Default)]
    struct In {
        #[serde(default)]
        nu: Option<usize>,
        #[serde(default)]
        nv: Option<usize>,
    }
    #[derive(Serialize)]
    struct Mesh {
        id: SurfaceId,
        nu: usize,
        nv: usize,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        x: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        y: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        z: Float64Array,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        surfaces: Vec<Mesh>,
        points: Vec<crate::sshape::part::MeasurementPoint>,
        curve_lengths: Vec<f64>,
    }
    let i: In = if value.is_undefined() || value.is_null() {
        In::default()
    } else {
        input(value)?
    };
    let nu = check_count("nu", i.nu.unwrap_or(131), 2, 2001).map_err(js_error)?;
    let nv = check_count("nv", i.nv.unwrap_or(7), 2, 101).map_err(js_error)?;
    let part = Part::standard().map_err(js_error)?;
    let mut surfaces = Vec::new();
    for id in SurfaceId::BOTH {
        let s = part.surface(id);
        let mut xyz = [
            Vec::with_capacity(nu * nv),
            Vec::with_capacity(nu * nv),
            Vec::with_capacity(nu * nv),
        ];
        for iv in 0..nv {
            for iu in 0..nu {
                let p = s.point(iu as f64 / (nu - 1) as f64, iv as f64 / (nv - 1) as f64);
                for k in 0..3 {
                    xyz[k].push(p[k]);
                }
            }
        }
        surfaces.push(Mesh {
            id,
            nu,
            nv,
            x: f64_array(&xyz[0]),
            y: f64_array(&xyz[1]),
            z: f64_array(&xyz[2]),
        });
    }
    let mut curve_lengths = Vec::new();
    for z in [crate::sshape::part::Z_TOP, crate::sshape::part::Z_BOTTOM] {
        for id in SurfaceId::BOTH {
            curve_lengths.push(
                part.surface(id)
                    .curve_length(z / crate::sshape::part::HEIGHT),
            );
        }
    }
    output(&Out {
        surfaces,
        points: Part::standard_points().map_err(js_error)?.to_vec(),
        curve_lengths,
    })
}

/// The overcut maps of both surfaces (eq 6 and the exact gouge) on an `nu × nv` grid.
#[wasm_bindgen(js_name = sshapeOvercut, unchecked_return_type = "SShapeOvercutResult")]
pub fn sshape_overcut(
    #[wasm_bindgen(unchecked_param_type = "SShapeOvercutInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct In {
        r_tool: f64,
        l_tool: f64,
        nu: usize,
        nv: usize,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct SurfaceOut {
        id: SurfaceId,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        eq6_paper: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        eq6: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        exact: Float64Array,
        max_eq6_paper: f64,
        max_eq6: f64,
        max_gouge: f64,
        at_eq6: [f64; 2],
        at_gouge: [f64; 2],
    }
    #[derive(Serialize)]
    struct Paper {
        a: f64,
        b: f64,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        nu: usize,
        nv: usize,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        u: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        z: Float64Array,
        surfaces: Vec<SurfaceOut>,
        b_paper_side: [f64; 2],
        paper: Paper,
    }
    let i: In = input(value)?;
    check_count("nu", i.nu, 2, 1001).map_err(js_error)?;
    check_count("nv", i.nv, 2, 61).map_err(js_error)?;
    let path = tool(i.r_tool, i.l_tool)?;
    let o = study::overcut(&path, i.nu, i.nv).map_err(js_error)?;
    let surface = |id: SurfaceId, m: &OvercutMap| {
        let (e6p, _, _) = m.max_of(&m.eq6_paper);
        let (e6, u6, v6) = m.max_of(&m.eq6);
        let gouge: Vec<f64> = m.exact.iter().map(|d| -d).collect();
        let (g, ug, vg) = m.max_of(&gouge);
        SurfaceOut {
            id,
            eq6_paper: f64_array(&m.eq6_paper),
            eq6: f64_array(&m.eq6),
            exact: f64_array(&m.exact),
            max_eq6_paper: e6p,
            max_eq6: e6,
            max_gouge: g.max(0.0),
            at_eq6: [u6, v6 * crate::sshape::part::HEIGHT],
            at_gouge: [ug, vg * crate::sshape::part::HEIGHT],
        }
    };
    let z: Vec<f64> =
        o.a.v
            .iter()
            .map(|v| v * crate::sshape::part::HEIGHT)
            .collect();
    output(&Out {
        nu: i.nu,
        nv: i.nv,
        u: f64_array(&o.a.u),
        z: f64_array(&z),
        surfaces: vec![surface(SurfaceId::A, &o.a), surface(SurfaceId::B, &o.b)],
        b_paper_side: [o.b_paper_side.0, o.b_paper_side.1],
        paper: Paper {
            a: 0.0387,
            b: 0.0125,
        },
    })
}

/// The machining defect at the 100 points for the entered errors (eq 14) and a tool-radius
/// error, with the sensitivities of Fig 19 and the machine poses.
#[wasm_bindgen(js_name = sshapeDefects, unchecked_return_type = "SShapeDefectsResult")]
pub fn sshape_defects(
    #[wasm_bindgen(unchecked_param_type = "SShapeDefectsInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct In {
        machine: MachineIn,
        #[serde(default)]
        errors: ErrorsIn,
        #[serde(default, rename = "dR")]
        d_r: f64,
    }
    #[derive(Serialize)]
    struct Pose {
        x: f64,
        y: f64,
        z: f64,
        b: f64,
        c: f64,
        singular: bool,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        names: Vec<&'static str>,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        total: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        contributions: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        sensitivity: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        radius: Float64Array,
        poses: Vec<Pose>,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        height: Float64Array,
        pair_cosines: [f64; 2],
    }
    let i: In = input(value)?;
    let xi = i.errors.engine()?;
    check_range("dR", i.d_r, -1.0, 1.0, "mm").map_err(js_error)?;
    let d = design(&i.machine)?;
    let total = d.simulate(&xi, i.d_r).map_err(js_error)?;
    let mut contributions = Vec::with_capacity(800);
    let mut sensitivity = Vec::with_capacity(800);
    for row in &d.rows {
        for k in 0..8 {
            contributions.push(row[k] * xi[k]);
            sensitivity.push(per_edge_unit(row[k], !IS_LENGTH[k]));
        }
    }
    let cos = |a: usize, b: usize| {
        let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
        for r in &d.rows {
            ab += r[a] * r[b];
            aa += r[a] * r[a];
            bb += r[b] * r[b];
        }
        ab / (aa * bb).sqrt()
    };
    output(&Out {
        names: ERROR_NAMES.to_vec(),
        total: f64_array(&total),
        contributions: f64_array(&contributions),
        sensitivity: f64_array(&sensitivity),
        radius: f64_array(&d.radius.iter().map(|r| r * i.d_r).collect::<Vec<_>>()),
        poses: d
            .poses
            .iter()
            .map(|p| Pose {
                x: p.pose.x,
                y: p.pose.y,
                z: p.pose.z,
                b: p.pose.b.to_degrees(),
                c: p.pose.c.to_degrees(),
                singular: p.pose.singular,
            })
            .collect(),
        height: f64_array(&d.poses.iter().map(|p| p.height).collect::<Vec<_>>()),
        pair_cosines: [cos(1, 3), cos(2, 4)],
    })
}

/// Identification of the location errors (and the tool-radius error) from a measurement CSV.
#[wasm_bindgen(js_name = sshapeIdentify, unchecked_return_type = "SShapeIdentifyResult")]
pub fn sshape_identify(
    #[wasm_bindgen(unchecked_param_type = "SShapeIdentifyInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    #[derive(Deserialize)]
    #[serde(rename_all = "camelCase")]
    struct In {
        machine: MachineIn,
        csv: String,
        #[serde(default)]
        radius_term: Option<bool>,
        #[serde(default)]
        rtol: Option<f64>,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Estimate {
        name: String,
        unit: &'static str,
        value: Option<f64>,
        std_error: Option<f64>,
        min_norm: f64,
        group: Option<usize>,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Combination {
        terms: Vec<(String, f64)>,
        value: f64,
        std_error: f64,
        text: String,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Group {
        members: Vec<String>,
        deficiency: usize,
        combinations: Vec<Combination>,
    }
    #[derive(Serialize)]
    #[serde(rename_all = "camelCase")]
    struct Out {
        estimates: Vec<Estimate>,
        groups: Vec<Group>,
        rank: usize,
        singular_values: Vec<f64>,
        rtol: f64,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        measured: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        fitted: Float64Array,
        #[serde(with = "serde_wasm_bindgen::preserve")]
        residuals: Float64Array,
        rms: f64,
        max_abs: f64,
        sigma: f64,
    }
    let i: In = input(value)?;
    let rtol = i.rtol.unwrap_or(DEFAULT_RTOL);
    check_range("rtol", rtol, 1e-12, 0.5, "").map_err(js_error)?;
    if i.csv.len() > 1_000_000 {
        return Err(js_error(Error::field(
            "csv",
            "the file is larger than 1 MB",
        )));
    }
    let measured = parse_measurements(&i.csv).map_err(js_error)?;
    let d = design(&i.machine)?;
    let f = d
        .identify(&measured, i.radius_term.unwrap_or(true), rtol)
        .map_err(js_error)?;
    let index = |name: &str| -> usize { ERROR_NAMES.iter().position(|n| *n == name).unwrap_or(8) };
    // Angles to degrees: values, and coefficients of combinations (x_deg = x_rad·180/π, so a
    // coefficient on an angle scales by π/180 to keep the combination's meaning).
    let unit = |k: usize| if k < 8 && !IS_LENGTH[k] { "°" } else { "mm" };
    let estimates = f
        .estimates
        .iter()
        .map(|e| {
            let k = index(&e.name);
            Estimate {
                name: e.name.clone(),
                unit: unit(k),
                value: e.value.map(|v| to_api(k, v)),
                std_error: e.std_error.map(|v| to_api(k, v)),
                min_norm: to_api(k, e.min_norm),
                group: e.group,
            }
        })
        .collect();
    // Combinations Σ c_j·x_j in API units (x in degrees for the angles): with f_j = π/180 for an
    // angle and 1 for a length, c'_j = c_j·f_j·s, where s = 180/π when the first (leading, c = 1)
    // member is an angle, so that the value converts like that member.
    let factor = |name: &str| {
        if unit(index(name)) == "°" {
            1f64.to_radians()
        } else {
            1.0
        }
    };
    let groups = f
        .groups
        .iter()
        .map(|g| Group {
            members: g.members.clone(),
            deficiency: g.deficiency,
            combinations: g
                .combinations
                .iter()
                .map(|c| {
                    let s = c.terms.first().map_or(1.0, |(n, _)| 1.0 / factor(n));
                    let terms: Vec<(String, f64)> = c
                        .terms
                        .iter()
                        .map(|(n, k)| (n.clone(), k * factor(n) * s))
                        .collect();
                    Combination {
                        text: combination_text(&terms),
                        terms,
                        value: c.value * s,
                        std_error: c.std_error * s,
                    }
                })
                .collect(),
        })
        .collect();
    output(&Out {
        estimates,
        groups,
        rank: f.rank,
        singular_values: f.singular_values,
        rtol: f.rtol,
        measured: f64_array(&measured),
        fitted: f64_array(&f.fitted),
        residuals: f64_array(&f.residuals),
        rms: f.rms,
        max_abs: f.max_abs,
        sigma: f.sigma,
    })
}
