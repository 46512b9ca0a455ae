//! The cubic test's exports (`cubicTest`, `cubicHeightMap`, `cubicIdentify`, `cubicDesign`):
//! the engine's results as the API gives them.
//!
//! Units: lengths in mm, angles in degrees (radians in Rust, written in degrees by
//! `crate::edge::degrees`). Sensitivities are per mm or **per degree**; slopes are dimensionless
//! (mm/mm). Grids are `Float64Array`s with their shape `nx`, `ny`, row-major: the point
//! `(x[ix], y[iy])` is entry `[iy * nx + ix]`. Zone × error tables are zone-major `9 × n`:
//! entry `[zone * n + error]`, zones in the order of `zones`, errors in the order of
//! `errorNames` (the machine's errors in the order of the error table).

use super::design::{self, CubicDesignInput, LayoutReport};
use super::identify::{identify_zones, CubicIdentifyInput, LayoutZone};
use super::{analyze, height_map, CubicGrid, CubicInput, CubicReference, HeightMap};
use super::{ZonePlane, ZoneResult};
use crate::error::Result;
use crate::identify::{api_combination, api_text, Fit, Identification};
use serde::{Serialize, Serializer};

impl crate::edge::Checked for CubicInput {
    fn check(&self) -> Result<()> {
        self.machine.validate("machine")?;
        self.setup.validate()
    }
}
impl crate::edge::Checked for CubicGrid {}
impl crate::edge::Checked for CubicIdentifyInput {}
impl crate::edge::Checked for CubicDesignInput {}

/// One zone of `cubicTest`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct CubicZone {
    /// "I", "II-1", … "III-4".
    pub name: &'static str,
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
    /// K command that cuts the zone, degrees (radians in Rust; Table 2 on Li et al.'s machine:
    /// C).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub k: f64,
    /// M command, degrees (radians in Rust; B on Li et al.'s machine).
    #[serde(serialize_with = "crate::edge::degrees")]
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

impl From<&ZoneResult> for CubicZone {
    fn from(z: &ZoneResult) -> Self {
        Self {
            name: z.zone.name,
            col: z.zone.col,
            row: z.zone.row,
            x: z.centre[0],
            y: z.centre[1],
            tool_vector: z.tool,
            k: z.rotary[0],
            m: z.rotary[1],
            singular: z.singular,
            height: z.exact.height,
            slope_x: z.exact.slope_x,
            slope_y: z.exact.slope_y,
            linear_height: z.linear.height,
            linear_slope_x: z.linear.slope_x,
            linear_slope_y: z.linear.slope_y,
        }
    }
}

/// A member of a group of errors the zone heights cannot tell apart.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct AlikeMember {
    /// ISO name.
    pub name: &'static str,
    /// `k_member = factor · k_first`, sensitivities per mm or per degree.
    pub factor: f64,
}

/// What the test can see (see [`super::Visibility`]), sensitivities per mm or per degree.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct CubicVisibility {
    /// Errors with zero height sensitivity in every zone.
    pub invisible: Vec<&'static str>,
    /// Of those, the ones that tilt some zone.
    pub tilt_only: Vec<&'static str>,
    /// Groups of errors with proportional height sensitivities.
    pub alike: Vec<Vec<AlikeMember>>,
    /// Independent combinations the heights determine.
    pub rank: usize,
}

/// The cubic test's results (`cubicTest`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct CubicResult {
    /// The nine zones in Table 1's order.
    pub zones: Vec<CubicZone>,
    /// The machine's errors, the columns of the tables (ISO 230-1 names).
    pub error_names: Vec<&'static str>,
    /// Their units: "mm" or "deg".
    #[cfg_attr(feature = "ts", tsify(type = "(\"mm\" | \"deg\")[]"))]
    pub error_units: Vec<&'static str>,
    /// Sensitivity k = E/ε (eq 15) of the height, 9 × n zone-major: mm/mm or mm/degree.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub k_height: Vec<f64>,
    /// Sensitivities of the slopes along u, 9 × n: per mm or per degree.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub k_slope_x: Vec<f64>,
    /// Along v.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub k_slope_y: Vec<f64>,
    /// Exact height with only that error at its entered value, 9 × n, mm (0 where it is 0).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub single: Vec<f64>,
    /// What the test can and cannot see.
    pub visibility: CubicVisibility,
    /// The workpiece set at zero (M_WC).
    pub transform: bool,
    /// What heights are measured from.
    pub reference: CubicReference,
}

/// `cubicTest`: zone heights and tilts (exact and first-order), sensitivities of every error of
/// the machine on every zone (per mm or per degree), the exact effect of each error alone, and
/// what the test cannot see.
pub fn test(input: &CubicInput) -> Result<CubicResult> {
    let options = input.options();
    let a = analyze(&input.machine, &input.setup, &options)?;
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
    let v = &a.visibility;
    let visibility = CubicVisibility {
        invisible: v.invisible.clone(),
        tilt_only: v.tilt_only.clone(),
        alike: v
            .alike
            .iter()
            .map(|g| {
                // k_b = f·k_a: the combination k_a·(x_a + f·x_b + …) the test sees.
                let (factors, _) = api_combination(g.iter().copied());
                g.iter()
                    .zip(factors)
                    .map(|((name, _), factor)| AlikeMember { name, factor })
                    .collect()
            })
            .collect(),
        rank: v.rank,
    };
    Ok(CubicResult {
        zones: a.zones.iter().map(CubicZone::from).collect(),
        error_names: a.errors.iter().map(|d| d.name).collect(),
        error_units: a.errors.iter().map(|d| d.quantity.api_unit()).collect(),
        k_height: table(|k| k.height),
        k_slope_x: table(|k| k.slope_x),
        k_slope_y: table(|k| k.slope_y),
        single: a.single.iter().flatten().copied().collect(),
        visibility,
        transform: options.transform,
        reference: options.reference,
    })
}

/// `cubicHeightMap`: the simulated machined face (Fig 16(b)) on an `nx × ny` grid ([`height_map`]).
pub fn map(input: &(CubicInput, CubicGrid)) -> Result<HeightMap> {
    let (i, grid) = input;
    height_map(&i.machine, &i.setup, &i.options(), grid)
}

/// An azimuth held in radians, written in degrees from 0 to 360.
fn azimuth_degrees<S: Serializer>(radians: &f64, s: S) -> std::result::Result<S::Ok, S::Error> {
    s.serialize_f64(radians.to_degrees().rem_euclid(360.0))
}

/// A zone of a measured or designed layout on the machine.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
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
    /// Tilt of the tool from the face normal, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub tilt: f64,
    /// Azimuth of the tilt in the face frame (0 towards +u), degrees from 0 to 360 (radians in
    /// Rust).
    #[serde(serialize_with = "azimuth_degrees")]
    pub azimuth: f64,
    /// Tool vector in workpiece coordinates, tip → spindle.
    pub tool_vector: [f64; 3],
    /// K command, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub k: f64,
    /// M command, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub m: f64,
}

impl CubicLayoutZone {
    /// The zone `z` of set-up `setup`, its tilt and azimuth from its tool vector in the face
    /// frame.
    pub fn new(z: &LayoutZone, setup: usize) -> Self {
        let t = z.spec.tool;
        let tilt = t[2].clamp(-1.0, 1.0).acos();
        let azimuth = if tilt < 1e-12 { 0.0 } else { t[1].atan2(t[0]) };
        Self {
            name: z.spec.name.clone(),
            setup,
            piece_x: z.piece_x,
            x: z.spec.centre.0,
            y: z.spec.centre.1,
            tilt,
            azimuth,
            tool_vector: z.tool,
            k: z.rotary[0],
            m: z.rotary[1],
        }
    }
}

/// What a row of the identification's system measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub enum RowKind {
    /// The zone's height.
    Height,
    /// Its slope along u.
    SlopeX,
    /// Its slope along v.
    SlopeY,
}

/// The cubic identification (`cubicIdentify`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct CubicIdentifyResult {
    /// The fit, the decisions and the words (shared with the S-shape), mm and degrees.
    #[serde(flatten)]
    pub fit: Identification,
    /// The measured zones in file order.
    pub zones: Vec<CubicLayoutZone>,
    /// Per row of the fit: the zone's index in `zones`.
    pub row_zone: Vec<usize>,
    /// Per row: "height", "slopeX" or "slopeY".
    pub row_kind: Vec<RowKind>,
    /// Measured value per row: mm for a height; for a slope the height it makes over half a
    /// zone, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub measured: Vec<f64>,
    /// Fitted value per row, same units.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub fitted: Vec<f64>,
    /// Measured minus fitted, same units.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub residuals: Vec<f64>,
    /// RMS of the residuals, mm.
    pub rms: f64,
}

/// `cubicIdentify`: the machine's errors from measured zone heights (and slopes) of a cubic
/// test piece ([`identify_zones`]).
pub fn identify(input: &(CubicInput, CubicIdentifyInput)) -> Result<CubicIdentifyResult> {
    let r = identify_zones(&input.0, &input.1)?;
    let f = &r.judgement.fit;
    Ok(CubicIdentifyResult {
        fit: r.judgement.identification(),
        zones: r.zones.iter().map(|z| CubicLayoutZone::new(z, 1)).collect(),
        row_zone: r.rows.iter().map(|(z, _)| *z).collect(),
        row_kind: r
            .rows
            .iter()
            .map(|(_, k)| [RowKind::Height, RowKind::SlopeX, RowKind::SlopeY][*k])
            .collect(),
        measured: f
            .fitted
            .iter()
            .zip(&f.residuals)
            .map(|(a, b)| a + b)
            .collect(),
        fitted: f.fitted.clone(),
        residuals: f.residuals.clone(),
        rms: f.rms,
    })
}

/// Errors a layout cannot separate.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct CubicDesignGroup {
    /// The errors.
    pub members: Vec<String>,
    /// What it can see of them, x in mm and degrees (none: nothing).
    pub combinations: Vec<String>,
}

fn design_groups(f: &Fit) -> Vec<CubicDesignGroup> {
    f.groups
        .iter()
        .map(|g| CubicDesignGroup {
            members: g.members.clone(),
            combinations: g.combinations.iter().map(api_text).collect(),
        })
        .collect()
}

/// A layout's quality for the designer.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[cfg_attr(feature = "ts", tsify(missing_as_null))]
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

impl From<&LayoutReport> for CubicLayoutReport {
    fn from(r: &LayoutReport) -> Self {
        Self {
            zones: r
                .zones
                .iter()
                .map(|z| CubicLayoutZone::new(&z.zone, z.setup))
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
}

/// The designer's result (`cubicDesign`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[cfg_attr(feature = "ts", tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct CubicDesignResult {
    /// The errors considered.
    pub error_names: Vec<&'static str>,
    /// The rank every candidate zone together reaches: what any such test can determine.
    pub reachable_rank: usize,
    /// Candidate zones the machine reaches within its travel.
    pub candidates: usize,
    /// What no such test can see (all candidates together).
    pub unseen: Vec<CubicDesignGroup>,
    /// How the matrix is scaled, in words.
    pub scaling: &'static str,
    /// The paper's layout (null when it cannot be cut: see `paperMessage`).
    pub paper: Option<CubicLayoutReport>,
    /// Why the paper's layout cannot be cut.
    pub paper_message: Option<String>,
    /// The designed layout.
    pub designed: CubicLayoutReport,
}

/// `cubicDesign`: the zones' tool vectors (and optionally a second set-up) that make every
/// error a face of this kind can reveal identifiable, beside the paper's layout
/// ([`design::design`]).
pub fn design(input: &(CubicInput, CubicDesignInput)) -> Result<CubicDesignResult> {
    let d = design::design(&input.0, &input.1)?;
    Ok(CubicDesignResult {
        error_names: d.errors.iter().map(|e| e.name).collect(),
        reachable_rank: d.reachable_rank,
        candidates: d.candidates,
        unseen: design_groups(&d.all),
        scaling: design::SCALING,
        paper: d.paper.as_ref().ok().map(CubicLayoutReport::from),
        paper_message: d.paper.as_ref().err().cloned(),
        designed: CubicLayoutReport::from(&d.designed),
    })
}
