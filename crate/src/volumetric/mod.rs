//! Volumetric error: where the tool tip really is, over a plane of the working volume, for all
//! the machine's errors at once (Tan & Lim, "Modeling the Volumetric Errors in Calibration of
//! Five-axis CNC Machine"), and which error is to blame.
//!
//! # The machine's model ([`map`])
//! The machine's one chain ([`crate::chain`]) with its location errors and its error motions
//! ([`crate::machine::motions`]: 6 per axis, each a constant, a polynomial or a measured table
//! against the axis position; for a three-linear-axis machine the 18 linear error motions and 3
//! squareness errors are ISO 230-1's 21, and each rotary axis adds 6) and the axes' nominal
//! motion, for any machine. At each pose `q` (X, Y, Z over the plane, K and M as given):
//! * the **exact deviation** `Δ = tip(q, errors) − tip(q, nominal)` of the tool tip, mm, in
//!   workpiece coordinates (the table frame; no workpiece set-up correction: what a probe or a
//!   laser tracker on the table would see), and the tool axis's **tilt error**
//!   `atan2(|a × a₀|, a·a₀)`, rad;
//! * its **first-order** form `Δ₁ = Σ_e J_e(q)·ε_e(q)`, the chain's analytic sensitivity
//!   `J_e` ([`crate::chain::Chain::jacobian`]) times each error's value at the pose.
//!
//! # The error budget
//! Each error's share of the squared deviation over the region:
//! `share_e = Σ_q (J_e·ε_e)·Δ₁ / Σ_q |Δ₁|²` (the shares add up to 1 exactly; a negative share
//! is an error that cancels part of the others), evaluated on at most [`BUDGET_SIDE`]² points of
//! the grid (every k-th point along each side). Also each error's rms contribution
//! `√(mean |J_e·ε_e|²)`.
//!
//! # Tan & Lim's model ([`paper`])
//! Their loop of Section VI, exactly as printed, and their first-order ΔX, ΔY, ΔZ; [`compare`]
//! puts it beside the machine's model at one pose of their machine (the C/A double turntable on
//! an X table, a preset), with the differences the loop's simplifications make (see
//! [`paper`]'s module docs).
//!
//! Units: mm and rad inside; positions of the plane in mm, rotary commands in degrees at the
//! edge.

pub mod paper;

use crate::chain::{Chain, Setup, ToolPose};
use crate::error::{Error, Result};
use crate::geometry::Axis;
use crate::machine::errors::{ErrorDef, ErrorKind};
use crate::machine::motions;
use crate::machine::{Machine, MachineKind, Model};
use crate::rotary::RotaryAxis;
use crate::schema::{self, DefaultValue, Kind, Quantity};
use nalgebra::Vector3;
use paper::PaperErrors;
use serde::Serialize;
use serde_json::Value;

/// At most this many budget points along each side of the grid.
pub const BUDGET_SIDE: usize = 41;
/// Largest grid side.
pub const MAX_STEPS: usize = 1001;
/// Largest plane coordinate, mm.
pub const MAX_POSITION: f64 = 10_000.0;

crate::choices! {
    /// The plane of the map: the two linear axes that vary.
    pub enum Plane {
        /// X and Y vary, Z fixed.
        Xy = "XY" { label: "X–Y (Z fixed)", help: "A horizontal plane at the given Z." },
        /// X and Z vary, Y fixed.
        Xz = "XZ" { label: "X–Z (Y fixed)", help: "A vertical plane at the given Y." },
        /// Y and Z vary, X fixed.
        Yz = "YZ" { label: "Y–Z (X fixed)", help: "A vertical plane at the given X." },
    }
}

impl Plane {
    /// The two axes that vary and the fixed one.
    pub fn axes(self) -> [Axis; 3] {
        match self {
            Plane::Xy => [Axis::X, Axis::Y, Axis::Z],
            Plane::Xz => [Axis::X, Axis::Z, Axis::Y],
            Plane::Yz => [Axis::Y, Axis::Z, Axis::X],
        }
    }
}

crate::inputs! {
    /// Where the map is drawn: a plane of linear-axis positions and the rotary commands.
    pub struct VolumetricRegion {
        /// The plane.
        pub plane: Plane = "plane" optional {
            label: "Plane of the map",
            help: "The two linear axes that move over the map; the third stands still.",
            kind: Kind::Choice(Plane::CHOICES),
            default: DefaultValue::Str("XY"),
            group: "Region",
        },
        /// First axis from, mm.
        pub u_from: f64 = "uFrom" optional {
            label: "First axis from",
            help: "Axis position (machine coordinates, as the control shows it) where the map starts along the plane's first axis (X for X–Y and X–Z, Y for Y–Z).",
            kind: schema::number(Quantity::Length, -MAX_POSITION, MAX_POSITION),
            default: DefaultValue::Num(-200.0),
            group: "Region",
        },
        /// First axis to, mm.
        pub u_to: f64 = "uTo" optional {
            label: "First axis to",
            help: "Where the map ends along the first axis.",
            kind: schema::number(Quantity::Length, -MAX_POSITION, MAX_POSITION),
            default: DefaultValue::Num(200.0),
            group: "Region",
        },
        /// Second axis from, mm.
        pub v_from: f64 = "vFrom" optional {
            label: "Second axis from",
            help: "Where the map starts along the plane's second axis (Y for X–Y, Z for X–Z and Y–Z).",
            kind: schema::number(Quantity::Length, -MAX_POSITION, MAX_POSITION),
            default: DefaultValue::Num(-200.0),
            group: "Region",
        },
        /// Second axis to, mm.
        pub v_to: f64 = "vTo" optional {
            label: "Second axis to",
            help: "Where the map ends along the second axis.",
            kind: schema::number(Quantity::Length, -MAX_POSITION, MAX_POSITION),
            default: DefaultValue::Num(200.0),
            group: "Region",
        },
        /// The third axis's position, mm; left out: the table surface ([`default_at`]).
        pub at: Option<f64> = "at" optional {
            label: "Third axis at",
            help: "Where the axis across the plane stands (Z for X–Y, Y for X–Z, X for Y–Z), as the control shows it: at Z 0 the spindle nose (a head: its tilting axis) is at the rotary centre. Left empty: the tool tip on the table surface when that axis is the spindle's, else 0.",
            kind: schema::number(Quantity::Length, -MAX_POSITION, MAX_POSITION),
            group: "Region",
        },
        /// Grid points per side.
        pub steps: usize = "steps" optional {
            label: "Points per side",
            help: "The map is computed exactly at this many points along each axis of the plane.",
            kind: Kind::Count { min: 2, max: MAX_STEPS },
            default: DefaultValue::Num(41.0),
            group: "Region",
        },
        /// K command, degrees (radians in Rust).
        pub k: f64 = "k" optional {
            label: "{K} at",
            help: "The rotary axis nearer the workpiece stands at this command over the whole map.",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            default: DefaultValue::Num(0.0),
            group: "Region",
        },
        /// M command, degrees (radians in Rust).
        pub m: f64 = "m" optional {
            label: "{M} at",
            help: "The rotary axis nearer the tool stands at this command over the whole map.",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            default: DefaultValue::Num(0.0),
            group: "Region",
        },
    }
}

crate::inputs! {
    /// The inputs of the volumetric map.
    pub struct VolumetricInput {
        /// The machine with its errors and error motions.
        pub machine: Machine = "machine" optional {
            label: "Machine",
            kind: Kind::Object(Machine::FIELDS),
            default: DefaultValue::Empty,
        },
        /// The region.
        pub region: VolumetricRegion = "region" optional {
            label: "Region",
            kind: Kind::Object(VolumetricRegion::FIELDS),
            default: DefaultValue::Empty,
        },
    }
}

impl VolumetricInput {
    /// Reads and checks the inputs.
    pub fn read(value: &Value) -> Result<Self> {
        <Self as crate::edge::ApiInput>::read(value)
    }
}

impl crate::edge::Checked for VolumetricInput {
    fn check(&self) -> Result<()> {
        self.machine.validate("machine")?;
        let r = &self.region;
        for (from, to, key) in [(r.u_from, r.u_to, "uTo"), (r.v_from, r.v_to, "vTo")] {
            if to <= from {
                return Err(Error::field(
                    format!("region.{key}"),
                    format!("must be above where the map starts ({from} mm), got {to} mm"),
                ));
            }
        }
        Ok(())
    }
}

/// One error's part in the deviation over the region.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Contribution {
    /// ISO 230-1 name.
    pub name: String,
    /// Short label ("X positioning").
    pub label: String,
    /// Location error or error motion.
    pub kind: ErrorKind,
    /// Share of the squared first-order deviation over the region (the shares add up to 1).
    pub share: f64,
    /// rms of its own deviation `|J_e·ε_e|` over the region, mm.
    pub rms: f64,
    /// Largest `|J_e·ε_e|` over the region, mm.
    pub max: f64,
}

/// The worst point of the map (of equal ones, the first in the grid's row order).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct WorstPoint {
    /// Linear-axis positions X, Y, Z, mm.
    pub position: [f64; 3],
    /// Deviation of the tip, workpiece coordinates, mm.
    pub deviation: [f64; 3],
    /// Its length, mm.
    pub norm: f64,
    /// Tilt error of the tool axis there, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub tilt: f64,
}

/// The map over the plane (module docs). Maps are row-major, `nu × nv`: the point
/// `(u[i], v[j])` is entry `[j·nu + i]`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct VolumetricMap {
    /// Names of the plane's first and second axis and the fixed one: `["X", "Y", "Z"]`.
    pub axes: [char; 3],
    /// Positions along the first axis, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub u: Vec<f64>,
    /// Positions along the second axis, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub v: Vec<f64>,
    /// Deviation components X, Y, Z in workpiece coordinates, mm, row-major.
    #[serde(serialize_with = "crate::edge::series3")]
    #[cfg_attr(
        feature = "ts",
        tsify(type = "[Float64Array, Float64Array, Float64Array]")
    )]
    pub deviation: [Vec<f64>; 3],
    /// `|Δ|`, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub norm: Vec<f64>,
    /// Tilt error of the tool axis, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub tilt: Vec<f64>,
    /// The worst point.
    pub worst: WorstPoint,
    /// rms of `|Δ|` over the grid, mm.
    pub rms: f64,
    /// The budget, largest share first (errors that are zero everywhere left out).
    pub budget: Vec<Contribution>,
    /// Grid points (per side) the budget used.
    pub budget_side: [usize; 2],
    /// Largest `|Δ − Δ₁|` on the budget points, mm.
    pub first_order_gap: f64,
    /// Largest `|Δ₁|` on the budget points, mm.
    pub first_order_max: f64,
    /// The third axis's position used (the input's, or [`default_at`]), mm.
    pub at: f64,
    /// The spindle axis's position at which the tool tip is on the table surface ([`surface_at`]).
    pub surface_at: f64,
    /// The tool tip's distance from the machine origin at the linear axes' 0 ([`tip_offset`]).
    pub tip_offset: f64,
    /// The table surface from the machine origin along the spindle, mm (`geometry.tableHeight`).
    pub table_height: f64,
    /// The linear axis along the spindle at zero ("Z" for a vertical spindle).
    pub spindle_axis: char,
    /// One plain sentence ([`VolumetricMap::summary`]).
    pub summary: String,
}

/// One error of the machine that is not zero, how to get its value at a pose, and where its
/// sensitivity sits in the chain's Jacobian.
struct Active {
    def: &'static ErrorDef,
    column: usize,
    /// Chain index of the axis whose position an error motion follows.
    link: usize,
    /// A location error's value (engine units).
    value: f64,
}

fn active_errors(model: &Model) -> Result<Vec<Active>> {
    let machine = &model.machine;
    let chain = &model.chain;
    let mut out = Vec::new();
    for def in machine.error_defs() {
        let value = machine.errors.get(def.name);
        if value != 0.0 {
            out.push(Active {
                def,
                column: model.error_column(def)?,
                link: 0,
                value,
            });
        }
    }
    for def in machine.motion_defs() {
        if machine.motions.0.contains_key(def.name) {
            let link = chain.index_of(&def.axis.to_string()).ok_or_else(|| {
                Error::field(format!("machine.motions.{}", def.name), "no such axis")
            })?;
            out.push(Active {
                def,
                column: 6 * chain.len() + Chain::location_index(link, def.component),
                link,
                value: 0.0,
            });
        }
    }
    Ok(out)
}

impl Active {
    /// The error's value at positions `q` (engine units).
    fn at(&self, model: &Model, q: &[f64]) -> Result<f64> {
        match self.def.kind {
            ErrorKind::Location => Ok(self.value),
            ErrorKind::Motion => {
                let f = &model.machine.motions.0[self.def.name];
                f.at(
                    q[self.link],
                    self.def.name,
                    motions::is_rotary(self.def.axis),
                )
            }
        }
    }
}

/// The linear axes' chain indices X, Y, Z.
fn linear_indices(chain: &Chain) -> Result<[usize; 3]> {
    let mut out = [0; 3];
    for (i, a) in Axis::ALL.iter().enumerate() {
        out[i] = chain.index_of(&a.letter().to_string()).ok_or_else(|| {
            Error::field(
                "machine.linear",
                format!("the machine has no {} axis", a.letter()),
            )
        })?;
    }
    Ok(out)
}

/// Exact deviation of the tip and tilt of the axis at `q` (module docs).
pub fn deviation_at(model: &Model, q: &[f64]) -> Result<(Vector3<f64>, f64)> {
    let actual = model.chain.tool_pose(q, true, &Setup::None)?;
    let nominal = model.nominal().tool_pose(q, false, &Setup::None)?;
    Ok(difference(&actual, &nominal))
}

/// The tip's deviation and the axis's tilt error of `actual` from `nominal`.
fn difference(actual: &ToolPose, nominal: &ToolPose) -> (Vector3<f64>, f64) {
    let tilt = actual
        .axis
        .cross(&nominal.axis)
        .norm()
        .atan2(actual.axis.dot(&nominal.axis));
    (actual.tip - nominal.tip, tilt)
}

/// First-order deviation at `q` and each active error's part of it.
fn first_order_at(
    model: &Model,
    active: &[Active],
    q: &[f64],
) -> Result<(Vector3<f64>, Vec<Vector3<f64>>)> {
    let jac = model.nominal().jacobian(q, &Setup::None)?;
    let mut total = Vector3::zeros();
    let mut parts = Vec::with_capacity(active.len());
    for a in active {
        let c = jac[a.column].tip * a.at(model, q)?;
        total += c;
        parts.push(c);
    }
    Ok((total, parts))
}

/// Evenly spaced `n` values from `a` to `b`.
fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
        .collect()
}

/// The map of the deviation over the region (module docs).
pub fn map(input: &VolumetricInput) -> Result<VolumetricMap> {
    let model = input.machine.build()?;
    let r = &input.region;
    let axes = r.plane.axes();
    let lin = linear_indices(&model.chain)?;
    let (iu, iv, iw) = (
        lin[axes[0].index()],
        lin[axes[1].index()],
        lin[axes[2].index()],
    );
    let (nu, nv) = (r.steps, r.steps);
    let u = linspace(r.u_from, r.u_to, nu);
    let v = linspace(r.v_from, r.v_to, nv);
    let mut q = model.positions(r.k, r.m);
    let at = r.at.unwrap_or_else(|| default_at(&input.machine, axes[2]));
    q[iw] = at;
    let n = nu * nv;
    let mut dev = [
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    ];
    let mut norm = Vec::with_capacity(n);
    let mut tilt = Vec::with_capacity(n);
    let mut worst = (0usize, -1.0);
    let mut sum2 = 0.0;
    let mut actual = model.chain.poses(true);
    let mut nominal = model.nominal().poses(false);
    for &vj in &v {
        q[iv] = vj;
        for &ui in &u {
            q[iu] = ui;
            let (d, t) = actual
                .tool_pose(&q)
                .and_then(|a| Ok(difference(&a, &nominal.tool_pose(&q)?)))
                .map_err(|e| at_pose(e, &q, &lin))?;
            let len = d.norm();
            if len > worst.1 {
                worst = (norm.len(), len);
            }
            sum2 += len * len;
            for (c, dv) in dev.iter_mut().enumerate() {
                dv.push(d[c]);
            }
            norm.push(len);
            tilt.push(t);
        }
    }
    let w = worst.0;
    let mut wp = [0.0; 3];
    wp[axes[0].index()] = u[w % nu];
    wp[axes[1].index()] = v[w / nu];
    wp[axes[2].index()] = at;
    let worst = WorstPoint {
        position: wp,
        deviation: [dev[0][w], dev[1][w], dev[2][w]],
        norm: norm[w],
        tilt: tilt[w],
    };

    // The budget on every k-th point.
    let active = active_errors(&model)?;
    let pick = |len: usize| -> Vec<usize> {
        let stride = len.div_ceil(BUDGET_SIDE).max(1);
        let mut idx: Vec<usize> = (0..len).step_by(stride).collect();
        if *idx.last().unwrap_or(&0) != len - 1 {
            idx.push(len - 1);
        }
        idx
    };
    let (bu, bv) = (pick(nu), pick(nv));
    let mut dot = vec![0.0; active.len()];
    let mut own2 = vec![0.0; active.len()];
    let mut own_max = vec![0.0f64; active.len()];
    let (mut total2, mut gap, mut first_max) = (0.0, 0.0f64, 0.0f64);
    for &j in &bv {
        q[iv] = v[j];
        for &i in &bu {
            q[iu] = u[i];
            let (d1, parts) =
                first_order_at(&model, &active, &q).map_err(|e| at_pose(e, &q, &lin))?;
            let k = j * nu + i;
            let exact = Vector3::new(dev[0][k], dev[1][k], dev[2][k]);
            gap = gap.max((exact - d1).norm());
            first_max = first_max.max(d1.norm());
            total2 += d1.norm_squared();
            for (e, c) in parts.iter().enumerate() {
                dot[e] += c.dot(&d1);
                own2[e] += c.norm_squared();
                own_max[e] = own_max[e].max(c.norm());
            }
        }
    }
    let count = (bu.len() * bv.len()) as f64;
    let mut budget: Vec<Contribution> = active
        .iter()
        .enumerate()
        .filter(|(e, _)| own_max[*e] > 0.0)
        .map(|(e, a)| Contribution {
            name: a.def.name.to_string(),
            label: a.def.label.to_string(),
            kind: a.def.kind,
            share: if total2 > 0.0 { dot[e] / total2 } else { 0.0 },
            rms: (own2[e] / count).sqrt(),
            max: own_max[e],
        })
        .collect();
    budget.sort_by(|a, b| b.share.total_cmp(&a.share).then(b.rms.total_cmp(&a.rms)));
    let mut map = VolumetricMap {
        axes: [axes[0].letter(), axes[1].letter(), axes[2].letter()],
        u,
        v,
        deviation: dev,
        norm,
        tilt,
        worst,
        rms: (sum2 / n as f64).sqrt(),
        budget,
        budget_side: [bu.len(), bv.len()],
        first_order_gap: gap,
        first_order_max: first_max,
        at,
        surface_at: surface_at(&input.machine),
        tip_offset: tip_offset(&input.machine),
        table_height: input.machine.geometry.table_height,
        spindle_axis: input.machine.home().letter(),
        summary: String::new(),
    };
    let m = &input.machine;
    map.summary =
        map.summary(m.errors.0.values().filter(|v| **v != 0.0).count() + m.motions.0.len());
    Ok(map)
}

/// Where the plane stands when `region.at` is left out: with the tool tip on the table surface
/// when the axis across the plane is the spindle's ([`surface_at`]), else at 0.
pub fn default_at(machine: &Machine, across: Axis) -> f64 {
    if machine.home() == across {
        surface_at(machine)
    } else {
        0.0
    }
}

/// How far the tool tip is from the machine origin (the rotary centre) with the linear axes at
/// 0, against the spindle direction, mm: the tool length (a table-table machine: the spindle
/// nose is at the origin), or the head's pivot length plus the tool length (the head's M axis is
/// at the origin).
pub fn tip_offset(machine: &Machine) -> f64 {
    let g = &machine.geometry;
    match machine.kind {
        MachineKind::TableTable => g.tool_length,
        MachineKind::HeadTable | MachineKind::HeadHead => g.pivot_length + g.tool_length,
    }
}

/// The spindle axis's position at which the tool tip is on the table surface (its centre at the
/// other axes' 0), mm: the table surface is `tableHeight` from the machine origin along the
/// spindle, the tip [`tip_offset`] from it the other way.
pub fn surface_at(machine: &Machine) -> f64 {
    machine.geometry.table_height + tip_offset(machine)
}

/// Adds the pose to an error from the chain (a table that does not reach it).
fn at_pose(e: Error, q: &[f64], lin: &[usize; 3]) -> Error {
    Error::field(
        e.field,
        format!(
            "{} (at X {}, Y {}, Z {} mm)",
            e.message,
            round(q[lin[0]]),
            round(q[lin[1]]),
            round(q[lin[2]])
        ),
    )
}

/// A deviation in words: µm below 1 mm (one decimal), mm above.
fn length(mm: f64) -> String {
    if mm < 1.0 {
        format!("{:.1} µm", mm * 1e3)
    } else {
        format!("{mm:.3} mm")
    }
}

fn round(x: f64) -> f64 {
    (x * 1e6).round() / 1e6
}

impl VolumetricMap {
    /// One plain sentence: the worst deviation, where, and the errors most to blame; `entered`
    /// is the number of errors and error motions the machine has.
    pub fn summary(&self, entered: usize) -> String {
        if self.worst.norm == 0.0 {
            return if entered == 0 {
                "No error is entered: the tool tip is where the control puts it everywhere on the plane.".to_string()
            } else {
                format!(
                    "The {entered} error{} entered do{} not move the tool tip anywhere on this plane.",
                    if entered == 1 { "" } else { "s" },
                    if entered == 1 { "es" } else { "" }
                )
            };
        }
        let [x, y, z] = self.worst.position;
        let mut s = format!(
            "The tool tip is off by up to {} (at X {}, Y {}, Z {} mm); rms {} over the plane.",
            length(self.worst.norm),
            round(x),
            round(y),
            round(z),
            length(self.rms)
        );
        let top: Vec<String> = self
            .budget
            .iter()
            .filter(|c| c.share >= 0.005)
            .take(3)
            .map(|c| format!("{} ({}) {:.0} %", c.name, c.label, 100.0 * c.share))
            .collect();
        if !top.is_empty() {
            s.push_str(&format!(" Most of it comes from {}.", top.join(", ")));
        }
        s
    }
}

/// Tan & Lim's model beside the machine's at one pose (module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct PaperComparison {
    /// The paper's loop solved exactly, mm (machine axes).
    pub paper_loop: [f64; 3],
    /// The paper's printed first-order ΔX, ΔY, ΔZ, mm.
    pub paper_printed: [f64; 3],
    /// The machine's exact deviation in workpiece coordinates, mm.
    pub machine: [f64; 3],
    /// The machine's deviation turned into machine-axis directions (the table's rotation undone),
    /// mm: what the paper's ΔX, ΔY, ΔZ stand for.
    pub machine_axes: [f64; 3],
    /// The paper's 33 symbols and their values at the pose, in the paper's signs.
    pub symbols: Vec<PaperSymbol>,
    /// Errors of the machine the paper's loop does not have (location errors of the rotary
    /// axes: its rotary errors are all error motions).
    pub not_in_paper: Vec<String>,
}

/// One of Tan & Lim's symbols at the pose.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct PaperSymbol {
    /// As printed: "δx(X)", "φ_C", "α".
    pub symbol: String,
    /// Its value in the paper's sign: mm, or degrees for an angle (radians in Rust).
    pub value: f64,
    /// "mm" or "deg": the unit `value` crosses the edge in.
    #[cfg_attr(feature = "ts", tsify(type = "\"mm\" | \"deg\""))]
    pub unit: &'static str,
}

impl Serialize for PaperSymbol {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut st = s.serialize_struct("PaperSymbol", 3)?;
        st.serialize_field("symbol", &self.symbol)?;
        let angle = self.unit == "deg";
        st.serialize_field(
            "value",
            &if angle {
                self.value.to_degrees()
            } else {
                self.value
            },
        )?;
        st.serialize_field("unit", self.unit)?;
        st.end()
    }
}

/// Tan & Lim's model beside the machine's exact one for the export's input (the machine
/// checked, the pose's angles in radians).
pub fn compare_input(input: &VolumetricPaperInput) -> Result<PaperComparison> {
    compare(
        &input.machine,
        [input.x, input.y, input.z],
        input.k,
        input.m,
    )
}

impl crate::edge::Checked for VolumetricPaperInput {
    fn check(&self) -> Result<()> {
        self.machine.validate("machine")
    }
}

impl crate::edge::Checked for MotionTableInput {}

/// Whether `machine` is Tan & Lim's RRTTT: X under the table carrying A, A carrying C, Y and Z
/// on the spindle side, A and C intersecting.
fn check_paper_machine(machine: &Machine) -> Result<()> {
    let ok = machine.kind == MachineKind::TableTable
        && machine.m() == RotaryAxis::A
        && machine.k() == RotaryAxis::C
        && machine.home() == Axis::Z
        && machine.linear.split().0 == [Axis::X]
        && machine.geometry.rotary_offset == 0.0
        && !machine.rotary.k_reversed
        && !machine.rotary.m_reversed;
    if ok {
        Ok(())
    } else {
        Err(Error::field(
            "machine",
            "Tan & Lim's loop is for their RRTTT machine: a C/A double turntable (table-table CAZ, A and C intersecting) on an X table, Y and Z moving the spindle. Choose the preset \"C/A double turntable on an X table (Tan & Lim)\".",
        ))
    }
}

/// The machine's errors at pose `q` in Tan & Lim's symbols and signs (ISO = sign·symbol).
pub fn paper_errors(model: &Model, q: &[f64]) -> Result<PaperErrors> {
    let mut slots = [0.0; 33];
    for (s, symbol) in paper::SYMBOLS.iter().enumerate() {
        let def = motions::MOTIONS
            .iter()
            .chain(crate::machine::errors::TABLE.iter())
            .find(|d| d.aliases.iter().any(|a| a.symbol == *symbol))
            .ok_or_else(|| Error::field("errors", format!("no ISO error for {symbol}")))?;
        let alias = def
            .aliases
            .iter()
            .find(|a| a.symbol == *symbol)
            .map_or(1.0, |a| a.sign);
        let iso = match def.kind {
            ErrorKind::Location => model.machine.errors.get(def.name),
            ErrorKind::Motion => match model.machine.motions.0.get(def.name) {
                None => 0.0,
                Some(f) => {
                    let link = model
                        .chain
                        .index_of(&def.axis.to_string())
                        .ok_or_else(|| Error::field("machine", format!("no {} axis", def.axis)))?;
                    f.at(q[link], def.name, motions::is_rotary(def.axis))?
                }
            },
        };
        slots[s] = iso * alias;
    }
    Ok(PaperErrors::from_slots(&slots))
}

/// Tan & Lim's model and the machine's at the linear positions `p` (mm) and rotary commands `k`,
/// `m` (rad) of their machine.
pub fn compare(machine: &Machine, p: [f64; 3], k: f64, m: f64) -> Result<PaperComparison> {
    check_paper_machine(machine)?;
    let model = machine.build()?;
    let lin = linear_indices(&model.chain)?;
    let mut q = model.positions(k, m);
    for (a, &i) in lin.iter().enumerate() {
        q[i] = p[a];
    }
    let e = paper_errors(&model, &q)?;
    let pos = Vector3::from(p);
    // The tool offset: the tip in the last spindle-side frame (the Z carriage).
    let tool = model.chain.tool_tip;
    let paper_loop = paper::loop_deviation(&e, pos, tool)?;
    let printed = paper::printed(&e, pos, tool);
    let (d, _) = deviation_at(&model, &q)?;
    // The table's nominal rotation: workpiece → machine axes.
    let (fw, _) = model.nominal().frames(&q, false)?;
    let axes = fw.rotation * d;
    let not_in_paper = machine
        .error_defs()
        .iter()
        .filter(|d| {
            machine.errors.get(d.name) != 0.0
                && d.aliases.iter().all(|a| !a.source.starts_with("Tan"))
        })
        .map(|d| d.name.to_string())
        .collect();
    Ok(PaperComparison {
        paper_loop: paper_loop.into(),
        paper_printed: printed.into(),
        machine: d.into(),
        machine_axes: axes.into(),
        symbols: paper::SYMBOLS
            .iter()
            .zip(e.slots())
            .enumerate()
            .map(|(slot, (s, value))| PaperSymbol {
                symbol: s.to_string(),
                value,
                unit: if paper::is_angle(slot) { "deg" } else { "mm" },
            })
            .collect(),
        not_in_paper,
    })
}

crate::inputs! {
    /// One pose of Tan & Lim's machine, for [`compare`].
    pub struct VolumetricPaperInput {
        /// Their machine (the preset), with its errors and error motions.
        pub machine: Machine = "machine" optional {
            label: "Machine",
            kind: Kind::Object(Machine::FIELDS),
            default: DefaultValue::Empty,
        },
        /// X, mm.
        pub x: f64 = "x" optional {
            label: "X", help: "X axis position.",
            kind: schema::number(Quantity::Length, -MAX_POSITION, MAX_POSITION),
            default: DefaultValue::Num(0.0), group: "Pose",
        },
        /// Y, mm.
        pub y: f64 = "y" optional {
            label: "Y", help: "Y axis position.",
            kind: schema::number(Quantity::Length, -MAX_POSITION, MAX_POSITION),
            default: DefaultValue::Num(0.0), group: "Pose",
        },
        /// Z, mm.
        pub z: f64 = "z" optional {
            label: "Z", help: "Z axis position.",
            kind: schema::number(Quantity::Length, -MAX_POSITION, MAX_POSITION),
            default: DefaultValue::Num(0.0), group: "Pose",
        },
        /// K (C) command, degrees (radians in Rust).
        pub k: f64 = "k" optional {
            label: "{K}", help: "C command.",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            default: DefaultValue::Num(0.0), group: "Pose",
        },
        /// M (A) command, degrees (radians in Rust).
        pub m: f64 = "m" optional {
            label: "{M}", help: "A command.",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            default: DefaultValue::Num(0.0), group: "Pose",
        },
    }
}

crate::inputs! {
    /// A measured table of one error motion, as CSV text.
    pub struct MotionTableInput {
        /// The error motion's ISO name.
        pub name: String = "name" {
            label: "Error motion",
            help: "Its ISO 230-1 name, e.g. E_XX.",
            kind: Kind::Text { max_len: 16 },
        },
        /// The CSV text.
        pub text: String = "text" {
            label: "CSV",
            help: "A header naming the columns with units, e.g. \"X (mm), E_XX (µm)\", then one position and value per line.",
            kind: Kind::Text { max_len: 1_000_000 },
        },
    }
}

impl MotionTableInput {
    /// Reads the input and the table (messages: `name`, or `csv` with the line).
    pub fn read_table(value: &Value) -> Result<motions::CsvTable> {
        read_table(&<Self as crate::edge::ApiInput>::read(value)?)
    }
}

/// Reads the measured table of one error motion (`name`) from its CSV text: positions and
/// values in API units (mm or degrees) from the units in the header; errors name the line.
pub fn read_table(input: &MotionTableInput) -> Result<motions::CsvTable> {
    if motions::find(&input.name).is_none() {
        return Err(motions::unknown("name", &input.name));
    }
    motions::read_table_csv(&input.text, &input.name)
}
