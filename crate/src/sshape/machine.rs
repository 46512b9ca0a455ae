//! The S-shape part on a machine (any kind and type, [`crate::machine`]): the tool path through
//! the machine's inverse kinematics, and the machining defect of the machine's errors at the
//! measurement points (eq 14, Fig 19).
//!
//! # The part on the machine
//! The part is defined in its own frame (Fig 3: z up from the base). On the machine its base
//! lies on the table square to the spindle's home direction, in the machine's face frame
//! `(u, v, n)` ([`crate::machine::face_frame`]): a part point `p` is the workpiece point
//! `F·p`, `F = [u v n]` (the identity for a vertical spindle). Its origin is the table centre
//! (the workpiece origin of the machine's chain). Results (positions, normals, sensitivities)
//! are given in the part's frame.
//!
//! # Chanal et al.'s machine (Section 5.2, eq 12, Appendix A)
//! Head-table CBZ: workpiece branch `Y → C`, tool branch `X → Z → B`, the tool tip
//! `L0 = 499.889 mm` below the B axis, every axis through the origin at zero. X, Y, Z, B follow
//! ISO 841 and **C turns the table by +C** (reversed): that is what the paper's
//! `tan C = −R·y_p/R·x_p` implies, found by matching every entry of the Appendix A Jacobian
//! (`crate/tests/sshape/machine.rs`). Its 8 errors `E_C0Y, E_A0Z, E_B0Z, E_A0C, E_B0C, E_X0B,
//! E_A0B, E_C0B` are the machine's location errors of the same names and signs (`D_i` of eq 11 is
//! the chain's `D(l_i)` to first order); eq 12 has no workpiece set-up transform (eq 14's
//! reference subtraction plays that role).
//!
//! # Inverse kinematics along the path
//! [`PathBranch::Paper`] is the paper's `tan B = √(R·x² + R·y²)/R·z ≥ 0`, i.e. the machine's
//! [`BranchRule::SmallestTilt`] (of two equal tilts, M ≥ 0); [`PathBranch::Continuous`] takes the
//! solution nearest the previous pose ([`BranchRule::Nearest`]). The path is followed from
//! `u = 0` to `u = 1` in small steps starting from the reference pose, so that the rotary axes
//! are unwrapped along it; where the tool lies along K (on Chanal et al.'s machine the whole
//! middle of the S, `u ∈ [6/13, 8/13]`, where the surfaces are vertical planes) K keeps its
//! previous value and the pose is flagged `singular`. Within the machine's travel; a pose beyond
//! it is an error naming the surface and `u`.
//!
//! # Machining defect (eq 14)
//! `Mdef = (J(X_tool(u)) − J(X_ref))·ξ · N`, with `J` the chain's first-order sensitivity of the
//! tool tip and `N` the outward normal at the measurement point (eq 14 prints `N(u, 1)`; the
//! measured deviation is along the local normal). Positive: the surface lies outside its
//! nominal position (material left). The reference pose `X_ref`:
//! * [`DefectReference::WorkOrigin`] (default): the rotary axes at zero and the tool tip at the
//!   workpiece origin, what the text describes ("the tool position defect on the origin of WCS");
//! * [`DefectReference::AxesZero`]: every axis at zero, as eq 14 is printed.
//!
//! Eq 14 moves the tool tip only. With [`DefectPoint::Contact`] the displacement of the tool-axis point
//! at the measurement height `h` is used instead, `d(tip) + h·d(axis)`.

use super::overcut::ToolPath;
use super::part::{MeasurementPoint, Part, Surface, SurfaceId};
use crate::chain::Setup;
use crate::error::{Error, Result};
use crate::machine::errors::ErrorDef;
use crate::machine::{BranchRule, Machine, Model};
use nalgebra::{Matrix3, Vector3};

crate::choices! {
    /// Which of the inverse-kinematics solutions along the path (module docs).
    pub enum PathBranch {
        /// The smallest tilt, M ≥ 0 first: the paper's tan relations with the positive root.
        Paper = "paper" {
            label: "Smallest tilt, M ≥ 0 (the paper's tan B, tan C)",
            help: "At every point the solution that tilts least; of two equal tilts the one with the tilting axis at 0° or above. The rotary axis may turn fast where the tool passes near its singular direction.",
        },
        /// The solution nearest the previous pose along the path.
        Continuous = "continuous" {
            label: "Nearest the previous pose",
            help: "Along the path, the solution that moves the rotary axes least from the previous point (the tilt may change sign).",
        },
    }
}

impl PathBranch {
    /// The machine's rule for this choice.
    pub fn rule(self) -> BranchRule {
        match self {
            PathBranch::Paper => BranchRule::SmallestTilt,
            PathBranch::Continuous => BranchRule::Nearest,
        }
    }
}

crate::choices! {
    /// The pose whose defect eq 14 subtracts (module docs).
    pub enum DefectReference {
        /// Tool tip at the workpiece origin, rotary axes at zero.
        WorkOrigin = "workOrigin" {
            label: "Tool tip at the workpiece origin",
            help: "The defect at the pose where the work offset was set (tool tip at the origin, rotary axes at zero) is subtracted.",
        },
        /// All axes at zero (eq 14 as printed).
        AxesZero = "axesZero" {
            label: "All axes at zero (as the paper prints it)",
            help: "The defect with every axis at zero is subtracted, as eq 14 is printed.",
        },
    }
}

crate::choices! {
    /// Which point of the tool eq 14 moves.
    pub enum DefectPoint {
        /// The tool tip (eq 14).
        Tip = "tip" {
            label: "Tool tip",
            help: "The defect is the tool tip's displacement along the normal, as in eq 14.",
        },
        /// The point of the tool axis at the measurement height.
        Contact = "contact" {
            label: "Tool axis at the point's height",
            help: "The displacement of the tool axis at the measured point's height: adds the effect of the tool's tilt on the flank.",
        },
    }
}

/// A pose on the path: the axis positions (chain order, mm and rad) and the singular flag.
pub use crate::machine::Solved as Pose;

/// The part set up on a machine (module docs).
#[derive(Debug, Clone)]
pub struct OnMachine {
    /// The machine's model (chain with errors, nominal chain, rotary layout).
    pub model: Model,
    /// `F = [u v n]`: part coordinates to workpiece coordinates.
    pub frame: Matrix3<f64>,
    /// The machine's errors, the columns of every sensitivity (table order).
    pub errors: Vec<&'static ErrorDef>,
    /// Their places in [`crate::chain::Chain::jacobian`]'s output.
    columns: Vec<usize>,
}

impl OnMachine {
    /// The part on `machine`, at the table centre.
    pub fn new(machine: &Machine) -> Result<Self> {
        let model = machine.build()?;
        let [u, v, n] = machine.face_frame();
        let errors = machine.error_defs();
        let columns = errors
            .iter()
            .map(|d| model.error_column(d))
            .collect::<Result<_>>()?;
        Ok(Self {
            model,
            frame: Matrix3::from_columns(&[u, v, n]),
            errors,
            columns,
        })
    }

    /// The index of the error `name` among [`Self::errors`].
    pub fn error_index(&self, name: &str) -> Option<usize> {
        self.errors.iter().position(|d| d.name == name)
    }

    /// The reference pose of eq 14 (chain order).
    pub fn reference_positions(&self, r: DefectReference) -> Result<Vec<f64>> {
        let q = self.model.positions(0.0, 0.0);
        match r {
            DefectReference::AxesZero => Ok(q),
            DefectReference::WorkOrigin => self.model.nominal().solve_linear(&Vector3::zeros(), &q),
        }
    }

    /// Inverse kinematics of one tool pose given in part coordinates (tip, axis), continuing from
    /// `previous` (module docs).
    pub fn inverse(
        &self,
        tip: &Vector3<f64>,
        axis: &Vector3<f64>,
        branch: PathBranch,
        previous: Option<&[f64]>,
    ) -> Result<Pose> {
        self.model.inverse(
            &(self.frame * tip),
            &(self.frame * axis),
            branch.rule(),
            previous,
        )
    }

    /// The first-order displacement of the tool tip and of the tool axis at positions `q`, per
    /// unit of each of the machine's errors (mm per mm or per rad), in part coordinates.
    pub fn sensitivities(&self, q: &[f64]) -> Result<Vec<(Vector3<f64>, Vector3<f64>)>> {
        let jac = self.model.chain.jacobian(q, &Setup::None)?;
        let back = self.frame.transpose();
        Ok(self
            .columns
            .iter()
            .map(|&c| (back * jac[c].tip, back * jac[c].axis))
            .collect())
    }
}

/// Tool positions per unit of u used to carry the rotary axes along the path (C turns by at
/// most about 2° per step on the standard's surfaces on Chanal et al.'s machine) and through the
/// singular part.
const PATH_STEPS: usize = 520;

/// A pose at one measurement point.
#[derive(Debug, Clone)]
pub struct PointPose {
    /// The measurement point.
    pub point: MeasurementPoint,
    /// The machine axes when the tool cuts it.
    pub pose: Pose,
    /// Height of the point along the tool axis above the tool tip, mm.
    pub height: f64,
}

/// Machine poses along the tool path of `surface` at the parameters `us` (any order): the path
/// is followed from `u = 0` to `u = 1` in small steps, starting from the reference pose (all
/// axes zero), so that the rotary axes are carried as they would be on the machine. Returns the
/// poses in the order of `us`.
pub fn poses_along(
    on: &OnMachine,
    path: &ToolPath,
    surface: &Surface,
    us: &[f64],
    branch: PathBranch,
) -> Result<Vec<Pose>> {
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
    let mut previous = on.model.positions(0.0, 0.0);
    for (u, k) in order {
        let t = path.at(surface, u);
        let pose = on
            .inverse(&t.tip, &t.axis, branch, Some(&previous))
            .map_err(|e| {
                Error::field(
                    "machine",
                    format!("surface {} at u = {u:.4}: {}", surface.id.name(), e.message),
                )
            })?;
        previous.clone_from(&pose.q);
        if let Some(k) = k {
            out[k] = Some(pose);
        }
    }
    out.into_iter()
        .map(|p| p.ok_or_else(|| Error::field("u", "a parameter was not reached")))
        .collect()
}

/// The machine poses at the 100 measurement points (list order).
pub fn measurement_poses(
    on: &OnMachine,
    path: &ToolPath,
    part: &Part,
    points: &[MeasurementPoint],
    branch: PathBranch,
) -> Result<Vec<PointPose>> {
    let mut out: Vec<Option<PointPose>> = vec![None; points.len()];
    for id in SurfaceId::BOTH {
        let surface = part.surface(id);
        let idx: Vec<usize> = (0..points.len())
            .filter(|&i| points[i].surface == id)
            .collect();
        let us: Vec<f64> = idx.iter().map(|&i| points[i].u).collect();
        let poses = poses_along(on, path, surface, &us, branch)?;
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

/// The sensitivity matrix of eq 14: row `k` (measurement point), column `j` (the machine's
/// error `j`): the machining defect along the outward normal (mm) per unit of error `j` (mm or
/// rad).
pub fn defect_matrix(
    on: &OnMachine,
    poses: &[PointPose],
    reference: DefectReference,
    point: DefectPoint,
) -> Result<Vec<Vec<f64>>> {
    let r = on.sensitivities(&on.reference_positions(reference)?)?;
    poses
        .iter()
        .map(|pp| {
            let s = on.sensitivities(&pp.pose.q)?;
            let n = Vector3::from(pp.point.normal);
            Ok(s.iter()
                .zip(&r)
                .map(|(sj, rj)| {
                    let mut d = sj.0 - rj.0;
                    if point == DefectPoint::Contact {
                        d += sj.1 * pp.height;
                    }
                    d.dot(&n)
                })
                .collect())
        })
        .collect()
}
