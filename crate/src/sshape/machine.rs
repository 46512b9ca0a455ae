//! The head-B / table-C machine of Section 5.2 (Chanal et al. 2022) on the shared kinematic
//! chain, its 8 location errors (Table 3), the inverse kinematics of the tool path and the
//! machining defect at the measurement points (eq 14, Fig 19).
//!
//! # The chain (eq 12, Appendix A)
//! Workpiece branch: `Y` (carries the table) → `C`; tool branch: `X` → `Z` → `B`; the tool
//! centre point sits `L0` below the B axis (paper: 499.889 mm), the tool axis points up the tool.
//! Every axis passes through the machine origin at zero (ISO 230-1's choice of origin in the
//! paper: on the C axis, at the height where the B axis crosses the ZX plane). With all axes at
//! zero the tool tip is at `(0, 0, −L0)` in workpiece coordinates; the tool tip reaches the
//! workpiece origin at `X = Y = 0, Z = L0, B = C = 0`.
//!
//! Signs (found by matching every entry of the Appendix A Jacobian, see
//! `crate/tests/sshape_machine.rs`): X, Z, B move the tool positively (ISO 841, `Link::sign = +1`),
//! Y moves the table by `−Y` (ISO 841), and **C turns the table by `+C`**, the opposite of ISO 841:
//! this is what the paper's `tan C = −R·y_p/R·x_p` implies. The tool axis in workpiece
//! coordinates is then `(sin B cos C, −sin B sin C, cos B)`.
//!
//! The 8 errors `ξ = (E_C0Y, E_A0Z, E_B0Z, E_A0C, E_B0C, E_X0B, E_A0B, E_C0B)` (mm for `E_X0B`,
//! rad for the others) are the chain's location errors of the same names, with the same sign
//! (`D_i` of eq 11 is the chain's `D(l_i)` to first order), and no workpiece set-up transform
//! (eq 12 has none: the reference subtraction of eq 14 plays that role).
//!
//! # Inverse kinematics (Section 5.2)
//! `tan C = −R·y_p/R·x_p` and `tan B = √((R·x_p)² + (R·y_p)²)/R·z_p`. The square root makes
//! `B ≥ 0`, and then `C = atan2(−R_y, R_x)` ([`Branch::Paper`], the default). The other solution
//! `(C + 180°, −B)` is chosen instead wherever it continues the previous pose more closely with
//! [`Branch::Continuous`]. When the tool axis is vertical (`R_x = R_y = 0`, which happens on the
//! whole middle part of the S, `u ∈ [6/13, 8/13]`, where the surfaces are vertical planes) C is
//! undefined: C keeps its previous value along the path (0 at the start) and the pose is flagged
//! `singular`. C is unwrapped to the turn nearest its previous value. X, Y, Z then follow from the
//! chain ([`Chain::solve_linear`]).
//!
//! # Machining defect (eq 14)
//! `Mdef = (J(X_tool(u)) − J(X_ref))·ξ · N`, with `J` the chain's first-order sensitivity of the
//! tool tip and `N` the outward normal at the measurement point (eq 14 prints `N(u, 1)`, the
//! normal at the top curve; the measured deviation is along the local normal). Positive = the
//! surface lies outside its nominal position (material left). The reference pose `X_ref`:
//! * [`Reference::WorkOrigin`] (default): the tool tip at the workpiece origin, tool vertical
//!   (`X = Y = 0, Z = L0, B = C = 0`), what the text describes ("the tool position defect on the
//!   origin of WCS");
//! * [`Reference::AxesZero`]: all axes at zero, as eq 14 is printed.
//!
//! Eq 14 moves the tool tip only. With [`Point::Contact`] the displacement of the tool-axis point
//! at the measurement height `h` is used instead, `d(tip) + h·d(axis)`, which adds the effect of
//! the tool's tilt on the flank.

use super::overcut::ToolPath;
use super::part::{MeasurementPoint, Part, Surface, SurfaceId};
use crate::chain::{Chain, Link, RigidError, Setup};
use crate::error::{check_positive, Error, Result};
use crate::geometry::Axis;
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// The paper's pivot-to-tool-tip distance, mm.
pub const PAPER_L0: f64 = 499.889;
/// Largest accepted L0, mm.
pub const MAX_L0: f64 = 5000.0;
/// The 8 error parameters of Table 3, in the order of eq 12's `ξ`.
pub const ERROR_NAMES: [&str; 8] = [
    "E_C0Y", "E_A0Z", "E_B0Z", "E_A0C", "E_B0C", "E_X0B", "E_A0B", "E_C0B",
];
/// True for the parameters that are lengths (mm); the others are angles (rad).
pub const IS_LENGTH: [bool; 8] = [false, false, false, false, false, true, false, false];
/// Tilt (rad) below which the tool axis counts as vertical and C as undefined.
pub const SINGULAR_TILT: f64 = 1e-9;
/// Tool positions per unit of u used to carry C along the path (C turns by at most about 2° per
/// step on the standard's surfaces) and through the singular part.
const PATH_STEPS: usize = 520;

/// The 8 errors, mm (`E_X0B`) and rad (the others), in the order of [`ERROR_NAMES`].
pub type Errors = [f64; 8];

/// Which of the two inverse-kinematics solutions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Branch {
    /// `B ≥ 0`, `C = atan2(−R_y, R_x)`: the paper's tan relations with the positive root.
    #[default]
    Paper,
    /// The solution nearest the previous pose along the path (B may change sign).
    Continuous,
}

/// The pose whose defect eq 14 subtracts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum Reference {
    /// Tool tip at the workpiece origin, tool vertical.
    #[default]
    WorkOrigin,
    /// All axes at zero (eq 14 as printed).
    AxesZero,
}

/// Which point of the tool eq 14 moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Point {
    /// The tool tip (eq 14).
    #[default]
    Tip,
    /// The point of the tool axis at the measurement height.
    Contact,
}

/// The model options of the machining defect.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct DefectModel {
    /// IK branch.
    #[serde(default)]
    pub branch: Branch,
    /// Reference pose.
    #[serde(default)]
    pub reference: Reference,
    /// Tip or contact point.
    #[serde(default)]
    pub point: Point,
}

/// Axis positions in the paper's order: X, Y, Z (mm), B, C (rad).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AxisPose {
    /// X, mm.
    pub x: f64,
    /// Y, mm.
    pub y: f64,
    /// Z, mm.
    pub z: f64,
    /// B, rad.
    pub b: f64,
    /// C, rad.
    pub c: f64,
    /// The tool axis is vertical here: C is undefined and was kept from the previous pose.
    pub singular: bool,
}

/// The paper's machine.
#[derive(Debug, Clone)]
pub struct Machine {
    /// The chain (order Y, C, X, Z, B).
    pub chain: Chain,
    /// Pivot to tool tip, mm.
    pub l0: f64,
}

impl Machine {
    /// The machine with pivot-to-tip distance `l0` (mm) and no errors.
    pub fn new(l0: f64) -> Result<Self> {
        check_positive("l0", l0, MAX_L0, "mm")?;
        let mut c_axis = Link::rotary("C", Axis::Z).on_table();
        c_axis.sign = 1.0; // the paper's sense of C (see the module docs)
        let chain = Chain {
            work: vec![Link::linear("Y", Axis::Y).on_table(), c_axis],
            tool: vec![
                Link::linear("X", Axis::X),
                Link::linear("Z", Axis::Z),
                Link::rotary("B", Axis::Y),
            ],
            work_origin: Vector3::zeros(),
            tool_tip: Vector3::new(0.0, 0.0, -l0),
            tool_axis: Axis::Z,
        };
        Ok(Self { chain, l0 })
    }

    /// Where error `k` (0..8) sits in the chain: (link index in chain order, component 0..6).
    pub fn slot(&self, k: usize) -> (usize, usize) {
        let name = ERROR_NAMES[k];
        let link = name
            .chars()
            .nth(4)
            .map(|c| c.to_string())
            .unwrap_or_default();
        let comp = name
            .chars()
            .nth(2)
            .and_then(|c| RigidError::LETTERS.iter().position(|l| *l == c));
        (self.chain.index_of(&link).unwrap_or(0), comp.unwrap_or(0))
    }

    /// The chain with the errors `xi` set (everything else zero).
    pub fn with_errors(&self, xi: &Errors) -> Chain {
        let mut chain = self.chain.clone();
        chain.clear_errors();
        for (k, v) in xi.iter().enumerate() {
            let (link, comp) = self.slot(k);
            chain.link_mut(link).location.set(comp, *v);
        }
        chain
    }

    /// Chain-order positions `[Y, C, X, Z, B]` of a pose.
    pub fn positions(&self, p: &AxisPose) -> Vec<f64> {
        vec![p.y, p.c, p.x, p.z, p.b]
    }

    /// The pose of chain-order positions.
    fn pose_of(q: &[f64], singular: bool) -> AxisPose {
        AxisPose {
            x: q[2],
            y: q[0],
            z: q[3],
            b: q[4],
            c: q[1],
            singular,
        }
    }

    /// The reference pose of eq 14.
    pub fn reference_pose(&self, r: Reference) -> AxisPose {
        let z = match r {
            Reference::WorkOrigin => self.l0,
            Reference::AxesZero => 0.0,
        };
        AxisPose {
            x: 0.0,
            y: 0.0,
            z,
            b: 0.0,
            c: 0.0,
            singular: false,
        }
    }

    /// Inverse kinematics of one tool pose (tip, unit axis; workpiece coordinates), continuing
    /// from `previous` (see the module docs for the branch and the singular case).
    pub fn inverse(
        &self,
        tip: &Vector3<f64>,
        axis: &Vector3<f64>,
        branch: Branch,
        previous: Option<&AxisPose>,
    ) -> Result<AxisPose> {
        let n = axis.norm();
        if !n.is_finite() || n < 1e-12 {
            return Err(Error::field(
                "axis",
                "the tool axis must be finite and non-zero",
            ));
        }
        let r = axis / n;
        let horizontal = r.x.hypot(r.y);
        let tilt = horizontal.atan2(r.z);
        let singular = tilt.abs() < SINGULAR_TILT;
        let prev_c = previous.map_or(0.0, |p| p.c);
        let unwrap = |c: f64| c + TAU * ((prev_c - c) / TAU).round();
        let (b, c) = if singular {
            (tilt, prev_c)
        } else {
            let c_paper = unwrap((-r.y).atan2(r.x));
            match (branch, previous) {
                (Branch::Continuous, Some(p)) => {
                    let other = unwrap(c_paper + std::f64::consts::PI);
                    let d1 = (c_paper - p.c).powi(2) + (tilt - p.b).powi(2);
                    let d2 = (other - p.c).powi(2) + (-tilt - p.b).powi(2);
                    if d2 < d1 {
                        (-tilt, other)
                    } else {
                        (tilt, c_paper)
                    }
                }
                _ => (tilt, c_paper),
            }
        };
        let mut q = vec![0.0, c, 0.0, 0.0, b];
        q = self.chain.solve_linear(tip, &q)?;
        Ok(Self::pose_of(&q, singular))
    }

    /// The first-order displacement (mm per unit of each error) of the tool tip and of the tool
    /// axis at a pose, for the 8 errors: `[(d tip, d axis); 8]`, workpiece coordinates.
    pub fn sensitivities(&self, pose: &AxisPose) -> Result<[(Vector3<f64>, Vector3<f64>); 8]> {
        let q = self.positions(pose);
        let jac = self.chain.jacobian(&q, &Setup::None)?;
        let mut out = [(Vector3::zeros(), Vector3::zeros()); 8];
        for (k, o) in out.iter_mut().enumerate() {
            let (link, comp) = self.slot(k);
            let s = &jac[Chain::location_index(link, comp)];
            *o = (s.tip, s.axis);
        }
        Ok(out)
    }
}

/// The tool path of one surface and the machine poses at the measurement points.
#[derive(Debug, Clone)]
pub struct PointPose {
    /// The measurement point.
    pub point: MeasurementPoint,
    /// The machine axes when the tool cuts it.
    pub pose: AxisPose,
    /// Height of the point along the tool axis above the tool tip, mm.
    pub height: f64,
}

/// Machine poses along the tool path of `surface` at the parameters `us` (any order): the path
/// is followed from `u = 0` to `u = 1` in small steps so that C is carried through the singular
/// part as it would be on the machine. Returns the poses in the order of `us`.
pub fn poses_along(
    machine: &Machine,
    path: &ToolPath,
    surface: &Surface,
    us: &[f64],
    branch: Branch,
) -> Result<Vec<AxisPose>> {
    let mut order: Vec<(f64, Option<usize>)> = (0..=PATH_STEPS)
        .map(|i| (i as f64 / PATH_STEPS as f64, None))
        .collect();
    order.extend(
        us.iter()
            .enumerate()
            .map(|(k, u)| (u.clamp(0.0, 1.0), Some(k))),
    );
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out = vec![None; us.len()];
    let mut previous: Option<AxisPose> = None;
    for (u, k) in order {
        let t = path.at(surface, u);
        let pose = machine.inverse(&t.tip, &t.axis, branch, previous.as_ref())?;
        if let Some(k) = k {
            out[k] = Some(pose);
        }
        previous = Some(pose);
    }
    out.into_iter()
        .map(|p| p.ok_or_else(|| Error::field("u", "a parameter was not reached")))
        .collect()
}

/// The machine poses at the 100 measurement points (list order).
pub fn measurement_poses(
    machine: &Machine,
    path: &ToolPath,
    part: &Part,
    points: &[MeasurementPoint],
    branch: Branch,
) -> Result<Vec<PointPose>> {
    let mut out: Vec<Option<PointPose>> = vec![None; points.len()];
    for id in SurfaceId::BOTH {
        let surface = part.surface(id);
        let idx: Vec<usize> = (0..points.len())
            .filter(|&i| points[i].surface == id)
            .collect();
        let us: Vec<f64> = idx.iter().map(|&i| points[i].u).collect();
        let poses = poses_along(machine, path, surface, &us, branch)?;
        for (&i, pose) in idx.iter().zip(poses) {
            let t = path.at(surface, points[i].u);
            let height = (Vector3::from(points[i].point) - t.tip).dot(&t.axis);
            out[i] = Some(PointPose {
                point: points[i],
                pose,
                height,
            });
        }
    }
    out.into_iter()
        .map(|p| p.ok_or_else(|| Error::field("points", "a point was not assigned a surface")))
        .collect()
}

/// The sensitivity matrix of eq 14: row `k` (measurement point), column `j` (error): the
/// machining defect along the outward normal (mm) per unit of error `j` (mm or rad).
pub fn defect_matrix(
    machine: &Machine,
    poses: &[PointPose],
    model: &DefectModel,
) -> Result<Vec<[f64; 8]>> {
    let reference = machine.sensitivities(&machine.reference_pose(model.reference))?;
    poses
        .iter()
        .map(|pp| {
            let s = machine.sensitivities(&pp.pose)?;
            let n = Vector3::from(pp.point.normal);
            let mut row = [0.0; 8];
            for (j, r) in row.iter_mut().enumerate() {
                let mut d = s[j].0 - reference[j].0;
                if model.point == Point::Contact {
                    d += s[j].1 * pp.height;
                }
                *r = d.dot(&n);
            }
            Ok(row)
        })
        .collect()
}
