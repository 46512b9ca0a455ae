//! Chanal et al. (2022) in their own terms, for the S-shape tests: their head-B / table-C machine
//! (Section 5.2) as a machine of the engine, its 8 errors in the order of eq 12's `ξ`, and poses
//! as `(X, Y, Z, B, C)`.
#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use fiveaxis::machine::errors::ErrorValues;
use fiveaxis::machine::Machine;
use fiveaxis::schema::Inputs;
use fiveaxis::sshape::identify::Fit;
use fiveaxis::sshape::machine::{DefectPoint, DefectReference, OnMachine, PathBranch, Pose};
use fiveaxis::sshape::study::{Design, SShapeModel, SShapeTool};
use nalgebra::Vector3;
use serde_json::json;

/// The paper's pivot-to-tool-tip distance, mm.
pub const PAPER_L0: f64 = 499.889;

/// Eq 12's `ξ`.
pub const ERROR_NAMES: [&str; 8] = [
    "E_C0Y", "E_A0Z", "E_B0Z", "E_A0C", "E_B0C", "E_X0B", "E_A0B", "E_C0B",
];

/// The machine with pivot-to-tip distance `l0`: head-table CBZ, Y under the table, C reversed
/// (the paper's `tan C = −R·y/R·x`), every axis through the origin.
/// The page's preset of this machine, with the pivot set for `l0`.
pub fn machine(l0: f64) -> Machine {
    let mut v = super::machine_preset("B swivel head, C rotary table, Y under the table");
    let tool = v["geometry"]["toolLength"].as_f64().unwrap();
    v["geometry"]["pivotLength"] = json!(l0 - tool);
    Machine::from_value(&v, "machine").unwrap()
}

pub fn on(l0: f64) -> OnMachine {
    OnMachine::new(&machine(l0)).unwrap()
}

/// Axis positions in the paper's terms (mm, rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisPose {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub b: f64,
    pub c: f64,
    pub singular: bool,
}

/// Chain order of this machine: Y, C, X, Z, B.
pub fn positions(p: &AxisPose) -> Vec<f64> {
    vec![p.y, p.c, p.x, p.z, p.b]
}

pub fn pose_of(p: &Pose) -> AxisPose {
    let q = &p.q;
    AxisPose {
        x: q[2],
        y: q[0],
        z: q[3],
        b: q[4],
        c: q[1],
        singular: p.singular,
    }
}

/// Column of each of the 8 errors among the machine's errors.
pub fn columns(on: &OnMachine) -> [usize; 8] {
    std::array::from_fn(|k| on.error_index(ERROR_NAMES[k]).unwrap())
}

/// `(d tip, d axis)` per unit of each of the 8 errors at a pose.
pub fn sensitivities(on: &OnMachine, p: &AxisPose) -> [(Vector3<f64>, Vector3<f64>); 8] {
    let s = on.sensitivities(&positions(p)).unwrap();
    let c = columns(on);
    std::array::from_fn(|k| s[c[k]])
}

pub fn inverse(
    on: &OnMachine,
    tip: &Vector3<f64>,
    axis: &Vector3<f64>,
    branch: PathBranch,
    previous: Option<&AxisPose>,
) -> AxisPose {
    let prev = previous.map(positions);
    pose_of(&on.inverse(tip, axis, branch, prev.as_deref()).unwrap())
}

/// The 8 errors (mm for E_X0B, rad for the others) as the machine's error values.
pub fn errors(xi: &[f64; 8]) -> ErrorValues {
    let mut e = ErrorValues::none();
    for (n, v) in ERROR_NAMES.iter().zip(xi) {
        e.set(n, *v).unwrap();
    }
    e
}

pub fn model(branch: PathBranch, reference: DefectReference, point: DefectPoint) -> SShapeModel {
    SShapeModel {
        branch,
        reference,
        point,
    }
}

pub fn default_model() -> SShapeModel {
    model(
        PathBranch::Paper,
        DefectReference::WorkOrigin,
        DefectPoint::Tip,
    )
}

pub fn paper_tool() -> SShapeTool {
    SShapeTool {
        r_tool: 10.0,
        l_tool: 35.0,
    }
}

pub fn design(l0: f64, m: SShapeModel) -> Design {
    Design::new(&machine(l0), &paper_tool(), &m).unwrap()
}

/// The eq 14 matrix restricted to the 8 errors: row per point.
pub fn rows8(d: &Design) -> Vec<[f64; 8]> {
    let c = columns(&d.on);
    d.rows
        .iter()
        .map(|r| std::array::from_fn(|k| r[c[k]]))
        .collect()
}

/// Identification of the 8 errors (and dR) as the paper does.
pub fn identify8(d: &Design, measured: &[f64], radius: bool, rtol: f64) -> Fit {
    let names: Vec<String> = ERROR_NAMES.iter().map(|s| s.to_string()).collect();
    d.identify(measured, Some(&names), radius, rtol).unwrap()
}
