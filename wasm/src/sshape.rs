//! Exports of the S-shape study (see `fiveaxis::sshape`). Lengths in mm, angles in degrees (the
//! machine's angular errors too; a sensitivity to one is per degree), like every export.

use crate::identify::{identification, Identification};
use crate::{f64_array, js_error, json, output, Series};
use fiveaxis::schema::{Inputs, Quantity};
use fiveaxis::sshape::overcut::OvercutMap;
use fiveaxis::sshape::part::{MeasurementPoint, Part, SurfaceId};
use fiveaxis::sshape::study::{
    self, Design, SShapeCase, SShapeDefectsInput, SShapeIdentifyInput, SShapeOvercutInput,
    SShapePartInput,
};
use serde::Serialize;
use tsify::Tsify;
use wasm_bindgen::prelude::*;

/// One surface of the part on a grid.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct SShapeSurfaceMesh {
    /// "A" or "B".
    pub id: SurfaceId,
    /// Points along u.
    pub nu: usize,
    /// Points over the height.
    pub nv: usize,
    /// Row-major nv × nu (`[iv * nu + iu]`), mm, part coordinates; u from 0 to 1 along the S,
    /// v from the base (z = 0) to the top (z = 30).
    pub x: Series,
    /// y, mm.
    pub y: Series,
    /// z, mm.
    pub z: Series,
}

/// The part for a 3D view.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct SShapePartResult {
    /// Surfaces A and B.
    pub surfaces: Vec<SShapeSurfaceMesh>,
    /// The 100 measurement points: TOP 1..50, then BOTTOM 1..50 (1..25 on A, 26..50 on B),
    /// part coordinates.
    pub points: Vec<MeasurementPoint>,
    /// Length of each measurement curve, mm: [top A, top B, bottom A, bottom B].
    pub curve_lengths: Vec<f64>,
}

/// The part for a 3D view: both surfaces on an `nu × nv` grid (default 131 × 7) and the 100
/// measurement points, in the part's own frame (z up from its base).
#[wasm_bindgen(js_name = sshapePart, unchecked_return_type = "SShapePartResult")]
pub fn sshape_part(
    #[wasm_bindgen(unchecked_param_type = "SShapePartInput | undefined")] value: JsValue,
) -> Result<JsValue, JsError> {
    let i = SShapePartInput::from_value(&json(&value)?, "").map_err(js_error)?;
    let part = Part::standard().map_err(js_error)?;
    let surfaces = SurfaceId::BOTH
        .into_iter()
        .map(|id| {
            let [x, y, z] = part.surface(id).mesh(i.nu, i.nv);
            SShapeSurfaceMesh {
                id,
                nu: i.nu,
                nv: i.nv,
                x: f64_array(&x),
                y: f64_array(&y),
                z: f64_array(&z),
            }
        })
        .collect();
    output(&SShapePartResult {
        surfaces,
        points: Part::standard_points().map_err(js_error)?.to_vec(),
        curve_lengths: part.curve_lengths(),
    })
}

/// One surface's overcut maps.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct SShapeOvercutSurface {
    /// "A" or "B".
    pub id: SurfaceId,
    /// Eq 6 with the paper's T, mm, row-major nv × nu.
    pub eq6_paper: Series,
    /// Eq 6 with T⊥, mm.
    pub eq6: Series,
    /// The exact signed deviation δ (negative = gouge), mm.
    pub exact: Series,
    /// Largest eq 6 with the paper's T, mm.
    pub max_eq6_paper: f64,
    /// Largest eq 6 with T⊥, mm.
    pub max_eq6: f64,
    /// Largest gouge (−δ), mm.
    pub max_gouge: f64,
    /// Where the largest eq 6 is: [u, z mm].
    pub at_eq6: [f64; 2],
    /// Where the largest gouge is: [u, z mm].
    pub at_gouge: [f64; 2],
}

/// The paper's printed overcut maxima, mm.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct PaperOvercut {
    /// Surface A.
    pub a: f64,
    /// Surface B.
    pub b: f64,
}

/// Overcut maps of both surfaces.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct SShapeOvercutResult {
    /// Points along u.
    pub nu: usize,
    /// Points over the height.
    pub nv: usize,
    /// Grid: u from 0 to 1.
    pub u: Series,
    /// z = 30·v, mm.
    pub z: Series,
    /// A, then B.
    pub surfaces: Vec<SShapeOvercutSurface>,
    /// Eq 6 maxima on surface B with the paper's N = R × T (tool on B's side facing A):
    /// [paper T, T⊥], mm.
    pub b_paper_side: [f64; 2],
    /// The paper's printed maxima, mm.
    pub paper: PaperOvercut,
}

/// The overcut maps of both surfaces (eq 6 and the exact gouge) on an `nu × nv` grid.
#[wasm_bindgen(js_name = sshapeOvercut, unchecked_return_type = "SShapeOvercutResult")]
pub fn sshape_overcut(
    #[wasm_bindgen(unchecked_param_type = "SShapeOvercutInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let i = SShapeOvercutInput::from_value(&json(&value)?, "").map_err(js_error)?;
    let o = study::overcut(&i.tool.path(), i.nu, i.nv).map_err(js_error)?;
    let surface = |id: SurfaceId, m: &OvercutMap| {
        let p = m.peaks();
        SShapeOvercutSurface {
            id,
            eq6_paper: f64_array(&m.eq6_paper),
            eq6: f64_array(&m.eq6),
            exact: f64_array(&m.exact),
            max_eq6_paper: p.eq6_paper,
            max_eq6: p.eq6,
            max_gouge: p.gouge,
            at_eq6: p.at_eq6,
            at_gouge: p.at_gouge,
        }
    };
    output(&SShapeOvercutResult {
        nu: i.nu,
        nv: i.nv,
        u: f64_array(&o.a.u),
        z: f64_array(&o.a.z()),
        surfaces: vec![surface(SurfaceId::A, &o.a), surface(SurfaceId::B, &o.b)],
        b_paper_side: [o.b_paper_side.0, o.b_paper_side.1],
        paper: PaperOvercut {
            a: study::PAPER_OVERCUT[0],
            b: study::PAPER_OVERCUT[1],
        },
    })
}

/// The machine's axes when the tool cuts a point.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct SShapePose {
    /// Positions in the order of `axes`: mm for linear axes, degrees for rotary ones.
    pub values: Vec<f64>,
    /// The tool lies along K there: K is undefined and was kept.
    pub singular: bool,
}

/// Two errors whose columns are nearly parallel.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
pub struct AlikePair {
    /// First error.
    pub a: String,
    /// Second error.
    pub b: String,
    /// Cosine of their columns (−1: alike but for sign).
    pub cosine: f64,
}

/// The defects at the 100 points.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct SShapeDefectsResult {
    /// The machine's errors, the columns of `contributions` and `sensitivity`.
    pub names: Vec<String>,
    /// Their units: "mm" or "deg".
    pub units: Vec<String>,
    /// Per point (list order): the deviation along the outward normal from all errors and dR,
    /// mm.
    pub total: Series,
    /// Row-major 100 × n: the contribution of each error at each point, mm.
    pub contributions: Series,
    /// Row-major 100 × n: mm per mm or mm per degree (Fig 19).
    pub sensitivity: Series,
    /// Per point: deviation from dR alone, mm.
    pub radius: Series,
    /// The machine's axes in chain order (the order of each pose's values).
    pub axes: Vec<String>,
    /// Machine axes when the tool cuts each point.
    pub poses: Vec<SShapePose>,
    /// Height of each point on the tool above its tip, mm.
    pub height: Series,
    /// Pairs of errors the part can hardly tell apart (|cosine| ≥ 0.95), most alike first.
    pub alike: Vec<AlikePair>,
}

/// The machining defect at the 100 points for the machine's errors (eq 14) and a tool-radius
/// error, with the sensitivities of Fig 19 and the machine poses.
#[wasm_bindgen(js_name = sshapeDefects, unchecked_return_type = "SShapeDefectsResult")]
pub fn sshape_defects(
    #[wasm_bindgen(unchecked_param_type = "SShapeCase & SShapeDefectsInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (c, own): (SShapeCase, SShapeDefectsInput) =
        SShapeCase::read_with(&json(&value)?).map_err(js_error)?;
    let d = Design::cached(&c).map_err(js_error)?;
    let total = d.simulate(&c.machine.errors, own.d_r);
    let errors = d.errors();
    let contributions: Vec<f64> = d.contributions(&c.machine.errors).concat();
    let sensitivity: Vec<f64> = d
        .rows
        .iter()
        .flat_map(|row| {
            row.iter()
                .zip(errors)
                .map(|(k, def)| def.quantity.per_api_unit(*k))
        })
        .collect();
    let chain = &d.on.model.chain;
    let quantities: Vec<Quantity> = chain
        .links()
        .map(|(_, l)| match l.joint {
            fiveaxis::chain::Joint::Rotary(_) => Quantity::Angle,
            fiveaxis::chain::Joint::Linear(_) => Quantity::Length,
        })
        .collect();
    output(&SShapeDefectsResult {
        names: errors.iter().map(|e| e.name.to_string()).collect(),
        units: errors
            .iter()
            .map(|e| e.quantity.api_unit().to_string())
            .collect(),
        total: f64_array(&total),
        contributions: f64_array(&contributions),
        sensitivity: f64_array(&sensitivity),
        radius: f64_array(&d.radius_deviation(own.d_r)),
        axes: chain.axis_names(),
        poses: d
            .poses
            .iter()
            .map(|p| SShapePose {
                values: p
                    .pose
                    .q
                    .iter()
                    .zip(&quantities)
                    .map(|(v, q)| q.to_api(*v))
                    .collect(),
                singular: p.pose.singular,
            })
            .collect(),
        height: f64_array(&d.poses.iter().map(|p| p.height).collect::<Vec<_>>()),
        alike: d
            .alike_pairs(0.95)
            .into_iter()
            .map(|(a, b, cosine)| AlikePair {
                a: a.to_string(),
                b: b.to_string(),
                cosine,
            })
            .collect(),
    })
}

/// The identification.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct SShapeIdentifyResult {
    /// The fit, the decisions and the words (shared with the cubic test).
    #[serde(flatten)]
    pub fit: Identification,
    /// Per point, list order, mm.
    pub measured: Series,
    /// The fitted deviation per point, mm.
    pub fitted: Series,
    /// Measured minus fitted, mm.
    pub residuals: Series,
    /// RMS of the residuals, mm.
    pub rms: f64,
    /// Largest |residual|, mm.
    pub max_abs: f64,
    /// Residual standard deviation, mm.
    pub sigma: f64,
}

/// Identification of the machine's errors (all, or `parameters`) and the tool-radius error from
/// a measurement CSV.
#[wasm_bindgen(js_name = sshapeIdentify, unchecked_return_type = "SShapeIdentifyResult")]
pub fn sshape_identify(
    #[wasm_bindgen(unchecked_param_type = "SShapeCase & SShapeIdentifyInput")] value: JsValue,
) -> Result<JsValue, JsError> {
    let (c, i): (SShapeCase, SShapeIdentifyInput) =
        SShapeCase::read_with(&json(&value)?).map_err(js_error)?;
    let (measured, j) = study::identify_case(&c, &i).map_err(js_error)?;
    let f = &j.fit;
    output(&SShapeIdentifyResult {
        measured: f64_array(&measured),
        fitted: f64_array(&f.fitted),
        residuals: f64_array(&f.residuals),
        rms: f.rms,
        max_abs: f.max_abs,
        sigma: f.sigma,
        fit: identification(&j),
    })
}
