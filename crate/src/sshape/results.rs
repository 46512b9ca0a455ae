//! The S-shape study's exports (`sshapePart`, `sshapeOvercut`, `sshapeDefects`,
//! `sshapeIdentify`): the engine's results as the API gives them. Lengths in mm, angles in
//! degrees (the machine's angular errors too; a sensitivity to one is per degree), like every
//! export; long series are `Float64Array`s.

use super::overcut::OvercutMap;
use super::part::{MeasurementPoint, Part, SurfaceId};
use super::study::{
    self, Design, SShapeCase, SShapeDefectsInput, SShapeIdentifyInput, SShapeOvercutInput,
    SShapePartInput,
};
use crate::chain::Joint;
use crate::error::Result;
use crate::identify::Identification;
use crate::schema::Quantity;
use serde::Serialize;

impl crate::edge::Checked for SShapeCase {
    fn check(&self) -> Result<()> {
        self.check_case()
    }
}
impl crate::edge::Checked for SShapeDefectsInput {}
impl crate::edge::Checked for SShapeIdentifyInput {}
impl crate::edge::Checked for SShapePartInput {}
impl crate::edge::Checked for SShapeOvercutInput {}

/// One surface of the part on a grid.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct SShapeSurfaceMesh {
    /// "A" or "B".
    pub id: SurfaceId,
    /// Points along u.
    pub nu: usize,
    /// Points over the height.
    pub nv: usize,
    /// Row-major nv × nu (`[iv * nu + iu]`), mm, part coordinates; u from 0 to 1 along the S,
    /// v from the base (z = 0) to the top (z = 30).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub x: Vec<f64>,
    /// y, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub y: Vec<f64>,
    /// z, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub z: Vec<f64>,
}

/// The part for a 3D view (`sshapePart`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
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

/// `sshapePart`: both surfaces on an `nu × nv` grid (default 131 × 7) and the 100 measurement
/// points, in the part's own frame (z up from its base).
pub fn part(i: &SShapePartInput) -> Result<SShapePartResult> {
    let part = Part::standard()?;
    let surfaces = SurfaceId::BOTH
        .into_iter()
        .map(|id| {
            let [x, y, z] = part.surface(id).mesh(i.nu, i.nv);
            SShapeSurfaceMesh {
                id,
                nu: i.nu,
                nv: i.nv,
                x,
                y,
                z,
            }
        })
        .collect();
    Ok(SShapePartResult {
        surfaces,
        points: Part::standard_points()?.to_vec(),
        curve_lengths: part.curve_lengths(),
    })
}

/// One surface's overcut maps.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct SShapeOvercutSurface {
    /// "A" or "B".
    pub id: SurfaceId,
    /// Eq 6 with the paper's T, mm, row-major nv × nu.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub eq6_paper: Vec<f64>,
    /// Eq 6 with T⊥, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub eq6: Vec<f64>,
    /// The exact signed deviation δ (negative = gouge), mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub exact: Vec<f64>,
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

impl SShapeOvercutSurface {
    fn new(id: SurfaceId, m: &OvercutMap) -> Self {
        let p = m.peaks();
        Self {
            id,
            eq6_paper: m.eq6_paper.clone(),
            eq6: m.eq6.clone(),
            exact: m.exact.clone(),
            max_eq6_paper: p.eq6_paper,
            max_eq6: p.eq6,
            max_gouge: p.gouge,
            at_eq6: p.at_eq6,
            at_gouge: p.at_gouge,
        }
    }
}

/// The paper's printed overcut maxima, mm.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct PaperOvercut {
    /// Surface A.
    pub a: f64,
    /// Surface B.
    pub b: f64,
}

/// Overcut maps of both surfaces (`sshapeOvercut`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct SShapeOvercutResult {
    /// Points along u.
    pub nu: usize,
    /// Points over the height.
    pub nv: usize,
    /// Grid: u from 0 to 1.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub u: Vec<f64>,
    /// z = 30·v, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub z: Vec<f64>,
    /// A, then B.
    pub surfaces: Vec<SShapeOvercutSurface>,
    /// Eq 6 maxima on surface B with the paper's N = R × T (tool on B's side facing A):
    /// [paper T, T⊥], mm.
    pub b_paper_side: [f64; 2],
    /// The paper's printed maxima, mm.
    pub paper: PaperOvercut,
}

/// `sshapeOvercut`: the overcut maps of both surfaces (eq 6 and the exact gouge) on an
/// `nu × nv` grid ([`study::overcut`]).
pub fn overcut(i: &SShapeOvercutInput) -> Result<SShapeOvercutResult> {
    let o = study::overcut(&i.tool.path(), i.nu, i.nv)?;
    Ok(SShapeOvercutResult {
        nu: i.nu,
        nv: i.nv,
        u: o.a.u.clone(),
        z: o.a.z(),
        surfaces: vec![
            SShapeOvercutSurface::new(SurfaceId::A, &o.a),
            SShapeOvercutSurface::new(SurfaceId::B, &o.b),
        ],
        b_paper_side: [o.b_paper_side.0, o.b_paper_side.1],
        paper: PaperOvercut {
            a: study::PAPER_OVERCUT[0],
            b: study::PAPER_OVERCUT[1],
        },
    })
}

/// The machine's axes when the tool cuts a point.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct SShapePose {
    /// Positions in the order of `axes`: mm for linear axes, degrees for rotary ones.
    pub values: Vec<f64>,
    /// The tool lies along K there: K is undefined and was kept.
    pub singular: bool,
}

/// Two errors whose columns are nearly parallel.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct AlikePair {
    /// First error.
    pub a: &'static str,
    /// Second error.
    pub b: &'static str,
    /// Cosine of their columns (−1: alike but for sign).
    pub cosine: f64,
}

/// The defects at the 100 points (`sshapeDefects`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct SShapeDefectsResult {
    /// The machine's errors, the columns of `contributions` and `sensitivity`.
    pub names: Vec<&'static str>,
    /// Their units: "mm" or "deg".
    #[cfg_attr(feature = "ts", tsify(type = "(\"mm\" | \"deg\")[]"))]
    pub units: Vec<&'static str>,
    /// Per point (list order): the deviation along the outward normal from all errors and dR,
    /// mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub total: Vec<f64>,
    /// Row-major 100 × n: the contribution of each error at each point, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub contributions: Vec<f64>,
    /// Row-major 100 × n: mm per mm or mm per degree (Fig 19).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub sensitivity: Vec<f64>,
    /// Per point: deviation from dR alone, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub radius: Vec<f64>,
    /// The machine's axes in chain order (the order of each pose's values).
    pub axes: Vec<String>,
    /// Machine axes when the tool cuts each point.
    pub poses: Vec<SShapePose>,
    /// Height of each point on the tool above its tip, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub height: Vec<f64>,
    /// Pairs of errors the part can hardly tell apart (|cosine| ≥ 0.95), most alike first.
    pub alike: Vec<AlikePair>,
}

/// `sshapeDefects`: the machining defect at the 100 points for the machine's errors (eq 14) and
/// a tool-radius error, with the sensitivities of Fig 19 (per mm or per degree) and the machine
/// poses (mm and degrees).
pub fn defects(input: &(SShapeCase, SShapeDefectsInput)) -> Result<SShapeDefectsResult> {
    let (c, own) = input;
    let d = Design::cached(c)?;
    let errors = d.errors();
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
            Joint::Rotary(_) => Quantity::Angle,
            Joint::Linear(_) => Quantity::Length,
        })
        .collect();
    Ok(SShapeDefectsResult {
        names: errors.iter().map(|e| e.name).collect(),
        units: errors.iter().map(|e| e.quantity.api_unit()).collect(),
        total: d.simulate(&c.machine.errors, own.d_r),
        contributions: d.contributions(&c.machine.errors).concat(),
        sensitivity,
        radius: d.radius_deviation(own.d_r),
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
        height: d.poses.iter().map(|p| p.height).collect(),
        alike: d
            .alike_pairs(0.95)
            .into_iter()
            .map(|(a, b, cosine)| AlikePair { a, b, cosine })
            .collect(),
    })
}

/// The S-shape identification (`sshapeIdentify`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct SShapeIdentifyResult {
    /// The fit, the decisions and the words (shared with the cubic test), mm and degrees.
    #[serde(flatten)]
    pub fit: Identification,
    /// Per point, list order, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub measured: Vec<f64>,
    /// The fitted deviation per point, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub fitted: Vec<f64>,
    /// Measured minus fitted, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub residuals: Vec<f64>,
    /// RMS of the residuals, mm.
    pub rms: f64,
    /// Largest |residual|, mm.
    pub max_abs: f64,
    /// Residual standard deviation, mm.
    pub sigma: f64,
}

/// `sshapeIdentify`: the machine's errors (all, or `parameters`) and the tool-radius error from
/// a measurement CSV ([`study::identify_case`]).
pub fn identify(input: &(SShapeCase, SShapeIdentifyInput)) -> Result<SShapeIdentifyResult> {
    let (measured, j) = study::identify_case(&input.0, &input.1)?;
    let f = &j.fit;
    Ok(SShapeIdentifyResult {
        fit: j.identification(),
        measured,
        fitted: f.fitted.clone(),
        residuals: f.residuals.clone(),
        rms: f.rms,
        max_abs: f.max_abs,
        sigma: f.sigma,
    })
}
