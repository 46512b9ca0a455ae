//! The kinematic chain with geometric errors: the one machine model every study uses.
//!
//! # The model
//! A machine has two branches from the bed (frame 0): the **workpiece branch** (bed → … → table
//! → workpiece) and the **tool branch** (bed → … → spindle → tool). Each branch is a list of
//! [`Link`]s, one per axis, listed from the bed outwards. Every link is a homogeneous transform
//! (a rigid `nalgebra::Isometry3`):
//!
//! ```text
//! F_i = F_(i-1) · T(o_i) · D(l_i) · J_i(s_i·q_i) · D(m_i(q_i))
//! ```
//!
//! * `T(o_i)`: the nominal position of the axis frame in the previous frame (mm; a translation,
//!   so that nominally every frame stays parallel to the machine axes: orthogonal machines).
//! * `D(l_i)`: the axis's **position-independent location errors** (ISO 230-1): for axis `B`
//!   these are `E_X0B E_Y0B E_Z0B` (offsets of its average line, mm) and `E_A0B E_B0B E_C0B`
//!   (orientation errors about X, Y, Z, rad; for a rotary axis the one about its own direction is
//!   its zero-angle error, for a linear axis the two across its direction are squareness errors).
//!   Orientation errors turn about the origin of the axis frame, i.e. about the nominal point
//!   `o_i` on the axis.
//! * `J_i`: the nominal motion: a translation by `s_i·q_i` mm along, or a rotation by `s_i·q_i`
//!   rad about, the axis direction. `s_i = ±1` ([`Link::sign`]).
//! * `D(m_i(q_i))`: the axis's **position-dependent error motions** (ISO 230-1 `E_XX E_YX E_ZX
//!   E_AX E_BX E_CX` for axis X, …), given as a function of the position; none by default.
//!   They are of the tool relative to the workpiece (ISO 841 sense, as a laser reads them), so a
//!   link on the workpiece branch applies `D(m_i)⁻¹`. A linear axis's error motion acts in
//!   its moving frame, after `J_i` as written; a rotary axis's in the frame of its axis line
//!   before it turns, `F_i = F_(i-1)·T(o_i)·D(l_i)·D(m_i(q_i))^(±1)·J_i(s_i·q_i)` (a radial
//!   error motion `E_XC` stays along X whatever the angle, as a fixed sensor sees it).
//!
//! `D(x, y, z, a, b, c) = T(x, y, z) · R_X(a) · R_Y(b) · R_Z(c)` (exact rotations; to first order
//! the order of the three rotations does not matter). The workpiece frame sits at
//! [`Chain::work_origin`] in the last workpiece-branch frame, the tool tip at
//! [`Chain::tool_tip`] in the last tool-branch frame; the tool axis is [`Chain::tool_axis`] there,
//! pointing from the tip towards the spindle (the tool vector `(i, j, k)` of CL data).
//!
//! The tool in workpiece coordinates is `G = F_work⁻¹ · F_tool`: tip `G·0`, axis `G_rot·e_H`.
//!
//! # Signs of the axes (ISO 841)
//! A positive command moves the **tool relative to the workpiece** in the positive direction.
//! An axis on the tool branch therefore moves its own frame positively (`s = +1`), an axis on the
//! workpiece branch moves the table negatively (`s = −1`); [`Link::linear`] and
//! [`Link::rotary`] make tool-side links, [`Link::on_table`] turns a link into a table-side one.
//! A paper with another convention sets [`Link::sign`] itself. With these signs a machine whose
//! rotary axes are K (nearer the workpiece) and M has the tool orientation
//! `V = R_K(θk)·R_M(θm)·e_H` of the nonlinear-error study with θ the commanded angles, whatever
//! side each axis is on ([`Chain::rotary_type`]).
//!
//! # The workpiece set-up (Li et al. 2021, eqs 10–12)
//! The workpiece is clamped and its coordinate system set by the machine with the rotary axes at
//! the set-up pose `q0` (usually all zero), so it sits where the nominal table would have put it:
//! `F_work,actual(q) = F_work(q) · F_work(q0)⁻¹ · F_work,nominal(q0)`. This is the paper's `M_WC`
//! (eq 12: the inverse of the product of the workpiece branch's error matrices at zero angles,
//! when `F_work,nominal(q0) = I`). An error that is present at `q0` then has no effect at `q0`:
//! three-axis machining at the set-up pose is unaffected ([`Setup::AtPose`]). [`Setup::None`]
//! is the conventional model, in which the workpiece frame is the (erroneous) table frame.
//!
//! # Sensitivities
//! [`Chain::jacobian`] gives the first-order derivative of the tip and the tool axis, in workpiece
//! coordinates, with respect to every error component, analytically at zero errors:
//! inserting `D(ε)` at a point of a branch, `F = A·D(ε)·B`, changes a point `x` by
//! `A_rot·(ε_t + ε_r × (B·x))`. For a workpiece-branch error this enters through `F_work⁻¹` with
//! the opposite sign, and the set-up adds the same term at `q0` with the original sign.
//!
//! Units: mm and rad throughout. Nothing here knows about JavaScript.

use crate::error::{Error, Result};
use crate::geometry::{quaternion, Axis};
use crate::rotary::{Pose, RotaryAxis, RotaryType};
use nalgebra::{Isometry3, Matrix3, Point3, Translation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::sync::Arc;

/// A small rigid-body displacement: translations `x, y, z` (mm) and rotations `a, b, c` (rad)
/// about X, Y, Z. Used for location errors and for error motions.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct RigidError {
    /// Translation along X, mm.
    pub x: f64,
    /// Translation along Y, mm.
    pub y: f64,
    /// Translation along Z, mm.
    pub z: f64,
    /// Rotation about X, rad.
    pub a: f64,
    /// Rotation about Y, rad.
    pub b: f64,
    /// Rotation about Z, rad.
    pub c: f64,
}

impl RigidError {
    /// The letters of the six components, in order: translations X Y Z, rotations A B C.
    pub const LETTERS: [char; 6] = ['X', 'Y', 'Z', 'A', 'B', 'C'];

    /// All six components as an array `[x, y, z, a, b, c]`.
    pub fn to_array(self) -> [f64; 6] {
        [self.x, self.y, self.z, self.a, self.b, self.c]
    }

    /// From `[x, y, z, a, b, c]`.
    pub fn from_array(v: [f64; 6]) -> Self {
        Self {
            x: v[0],
            y: v[1],
            z: v[2],
            a: v[3],
            b: v[4],
            c: v[5],
        }
    }

    /// Component `k` (0..6, order of [`Self::LETTERS`]).
    pub fn get(&self, k: usize) -> f64 {
        self.to_array()[k]
    }

    /// Sets component `k` (0..6).
    pub fn set(&mut self, k: usize, value: f64) {
        let mut v = self.to_array();
        v[k] = value;
        *self = Self::from_array(v);
    }

    /// `D = T(x, y, z) · R_X(a) · R_Y(b) · R_Z(c)` (a zero angle adds no rotation).
    pub fn transform(&self) -> Isometry3<f64> {
        let mut r = UnitQuaternion::identity();
        for (axis, angle) in [(Axis::X, self.a), (Axis::Y, self.b), (Axis::Z, self.c)] {
            if angle != 0.0 {
                r *= quaternion(axis, angle);
            }
        }
        Isometry3::from_parts(Translation3::new(self.x, self.y, self.z), r)
    }
}

/// What an axis does: slide along or turn about a machine direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Joint {
    /// A linear axis along X, Y or Z (position in mm).
    Linear(Axis),
    /// A rotary axis about X (A), Y (B) or Z (C) (position in rad).
    Rotary(Axis),
}

impl Joint {
    /// The direction of the axis.
    pub fn axis(self) -> Axis {
        match self {
            Joint::Linear(a) | Joint::Rotary(a) => a,
        }
    }

    /// The nominal motion by `amount` (mm or rad).
    pub fn motion(self, amount: f64) -> Isometry3<f64> {
        match self {
            Joint::Linear(a) => Isometry3::from_parts(
                Translation3::from(a.unit() * amount),
                UnitQuaternion::identity(),
            ),
            Joint::Rotary(a) => {
                Isometry3::from_parts(Translation3::identity(), quaternion(a, amount))
            }
        }
    }
}

/// Position-dependent error motions of an axis: its six error components (mm, rad) as a
/// function of the axis position (mm or rad), or why they cannot be given there (a measured
/// table that does not reach the position).
pub type ErrorMotionFn = Arc<dyn Fn(f64) -> Result<RigidError> + Send + Sync>;

/// One axis of a branch. See the module documentation for the transform it stands for.
#[derive(Clone)]
pub struct Link {
    /// The axis letter used in ISO 230-1 error names: "X", "Y", "Z", "A", "B", "C".
    pub name: String,
    /// Linear or rotary, and its direction.
    pub joint: Joint,
    /// `+1` or `−1`: the frame moves by `sign·q` for the command `q` (ISO 841: `+1` on the tool
    /// branch, `−1` on the workpiece branch).
    pub sign: f64,
    /// Nominal position of the axis frame in the previous frame, mm.
    pub offset: Vector3<f64>,
    /// Position-independent location errors `E_X0i … E_C0i`.
    pub location: RigidError,
    /// Position-dependent error motions `E_Xi(q) … E_Ci(q)`, if any.
    pub motion: Option<ErrorMotionFn>,
}

impl fmt::Debug for Link {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Link")
            .field("name", &self.name)
            .field("joint", &self.joint)
            .field("sign", &self.sign)
            .field("offset", &self.offset)
            .field("location", &self.location)
            .field("motion", &self.motion.as_ref().map(|_| "fn"))
            .finish()
    }
}

impl Link {
    /// A tool-side linear axis named `name` along `axis` at the previous frame's origin.
    pub fn linear(name: &str, axis: Axis) -> Self {
        Self::new(name, Joint::Linear(axis))
    }

    /// A tool-side rotary axis named `name` about `axis` through the previous frame's origin.
    pub fn rotary(name: &str, axis: Axis) -> Self {
        Self::new(name, Joint::Rotary(axis))
    }

    fn new(name: &str, joint: Joint) -> Self {
        Self {
            name: name.to_string(),
            joint,
            sign: 1.0,
            offset: Vector3::zeros(),
            location: RigidError::default(),
            motion: None,
        }
    }

    /// The same link on the workpiece branch (ISO 841: the table moves the other way).
    pub fn on_table(mut self) -> Self {
        self.sign = -1.0;
        self
    }

    /// The same link with its frame at `offset` (mm) in the previous frame.
    pub fn at(mut self, offset: Vector3<f64>) -> Self {
        self.offset = offset;
        self
    }

    /// The nominal frame of this link relative to the previous one, at command `q`.
    fn nominal(&self, q: f64) -> Isometry3<f64> {
        let offset =
            Isometry3::from_parts(Translation3::from(self.offset), UnitQuaternion::identity());
        offset * self.joint.motion(self.sign * q)
    }

    /// The frame of this link relative to the previous one, at command `q`, with (`errors`) or
    /// without its errors (module docs); `on_work`: the link is on the workpiece branch.
    fn transform(&self, q: f64, errors: bool, on_work: bool) -> Result<Isometry3<f64>> {
        if !errors {
            return Ok(self.nominal(q));
        }
        let offset =
            Isometry3::from_parts(Translation3::from(self.offset), UnitQuaternion::identity());
        let motion = self.joint.motion(self.sign * q);
        let located = offset * self.location.transform();
        let Some(m) = &self.motion else {
            return Ok(located * motion);
        };
        let d = m(q)?.transform();
        let d = if on_work { d.inverse() } else { d };
        Ok(match self.joint {
            Joint::Linear(_) => located * motion * d,
            Joint::Rotary(_) => located * d * motion,
        })
    }

    /// ISO 230-1 name of location error component `k` (0..6): `E_X0B`.
    pub fn location_name(&self, k: usize) -> String {
        format!("E_{}0{}", RigidError::LETTERS[k], self.name)
    }

    /// ISO 230-1 name of error-motion component `k` (0..6): `E_XX`, `E_CB`.
    pub fn motion_name(&self, k: usize) -> String {
        format!("E_{}{}", RigidError::LETTERS[k], self.name)
    }
}

/// Which branch a link is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Branch {
    /// Bed → workpiece.
    Work,
    /// Bed → tool.
    Tool,
}

/// How the workpiece coordinate system is set (module docs, Li et al. eqs 10–12).
#[derive(Debug, Clone, PartialEq)]
pub enum Setup {
    /// The workpiece frame is the table frame, errors included (the conventional model, eq 2).
    None,
    /// The workpiece is set at the pose `q` (chain order) where it coincides with the nominal
    /// table frame (eq 12's `M_WC`).
    AtPose(Vec<f64>),
}

/// The tool in workpiece coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToolPose {
    /// Tool tip (the controlled point), mm.
    pub tip: Vector3<f64>,
    /// Unit tool axis, from the tip towards the spindle.
    pub axis: Vector3<f64>,
}

/// One error component of one link: a location error (position-independent, `E_X0B`) or an
/// error motion (a function of the axis position, `E_XB(B)`, taken at the current position).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub enum ErrorKind {
    /// Position-independent location error `E_X0i`.
    Location,
    /// Error motion `E_Xi`, its value at the current position.
    Motion,
}

/// The first-order effect of one error component on the tool in workpiece coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Sensitivity {
    /// The ISO 230-1 name, e.g. `E_A0B` or `E_XX`.
    pub name: String,
    /// Index of the link in chain order (workpiece branch first, then tool branch).
    pub link: usize,
    /// Location error or error motion.
    pub kind: ErrorKind,
    /// Component 0..6: x, y, z (mm), a, b, c (rad).
    pub component: usize,
    /// ∂tip/∂ε: mm per mm, or mm per rad.
    pub tip: Vector3<f64>,
    /// ∂axis/∂ε: per mm (always zero) or per rad.
    pub axis: Vector3<f64>,
}

/// A machine: the two branches, where the workpiece and the tool sit on them.
#[derive(Debug, Clone)]
pub struct Chain {
    /// Bed → workpiece, from the bed outwards.
    pub work: Vec<Link>,
    /// Bed → tool, from the bed outwards.
    pub tool: Vec<Link>,
    /// Origin of the workpiece frame in the last workpiece-branch frame, mm.
    pub work_origin: Vector3<f64>,
    /// Tool tip in the last tool-branch frame, mm.
    pub tool_tip: Vector3<f64>,
    /// Tool direction in the last tool-branch frame (tip → spindle).
    pub tool_axis: Axis,
}

impl Chain {
    /// Every link in chain order: the workpiece branch, then the tool branch. Positions `q`
    /// passed to the chain follow this order.
    pub fn links(&self) -> impl Iterator<Item = (Branch, &Link)> {
        self.work
            .iter()
            .map(|l| (Branch::Work, l))
            .chain(self.tool.iter().map(|l| (Branch::Tool, l)))
    }

    /// Number of axes.
    pub fn len(&self) -> usize {
        self.work.len() + self.tool.len()
    }

    /// True for a chain without axes.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The axis names in chain order, e.g. `["B", "C", "X", "Y", "Z"]`.
    pub fn axis_names(&self) -> Vec<String> {
        self.links().map(|(_, l)| l.name.clone()).collect()
    }

    /// The index in chain order of the axis named `name`.
    pub fn index_of(&self, name: &str) -> Option<usize> {
        self.links().position(|(_, l)| l.name == name)
    }

    /// The link with index `i` in chain order.
    pub fn link(&self, i: usize) -> &Link {
        if i < self.work.len() {
            &self.work[i]
        } else {
            &self.tool[i - self.work.len()]
        }
    }

    /// Mutable access to the link with index `i` in chain order.
    pub fn link_mut(&mut self, i: usize) -> &mut Link {
        let n = self.work.len();
        if i < n {
            &mut self.work[i]
        } else {
            &mut self.tool[i - n]
        }
    }

    fn check_positions(&self, q: &[f64]) -> Result<()> {
        if q.len() != self.len() {
            return Err(Error::field(
                "positions",
                format!(
                    "expected {} axis positions ({}), got {}",
                    self.len(),
                    self.axis_names().join(", "),
                    q.len()
                ),
            ));
        }
        if let Some(i) = q.iter().position(|v| !v.is_finite()) {
            return Err(Error::field(
                "positions",
                format!(
                    "the position of {} is not a finite number",
                    self.link(i).name
                ),
            ));
        }
        Ok(())
    }

    /// Products of one branch's link transforms: `F` (bed → end, end offset included);
    /// `on_work` for the workpiece branch.
    fn branch(
        &self,
        links: &[Link],
        q: &[f64],
        errors: bool,
        end: &Vector3<f64>,
        on_work: bool,
    ) -> Result<Isometry3<f64>> {
        let mut f = Isometry3::identity();
        for (l, &qi) in links.iter().zip(q) {
            f *= l.transform(qi, errors, on_work)?;
        }
        Ok(f * Isometry3::from_parts(Translation3::from(*end), UnitQuaternion::identity()))
    }

    /// The nominal frame of every axis in bed coordinates at `q` (chain order): where the axis
    /// sits and which way it points, before its own motion (`F_(i-1)·T(o_i)`). For drawings of
    /// the machine.
    pub fn axis_frames(&self, q: &[f64]) -> Result<Vec<Isometry3<f64>>> {
        self.check_positions(q)?;
        let nw = self.work.len();
        let mut out = Vec::with_capacity(self.len());
        for (links, qs) in [(&self.work, &q[..nw]), (&self.tool, &q[nw..])] {
            let mut f = Isometry3::identity();
            for (l, &qi) in links.iter().zip(qs) {
                out.push(
                    f * Isometry3::from_parts(
                        Translation3::from(l.offset),
                        UnitQuaternion::identity(),
                    ),
                );
                f *= l.nominal(qi);
            }
        }
        Ok(out)
    }

    /// The workpiece frame and the tool frame in bed coordinates (`F_work`, `F_tool`), without
    /// the set-up transform.
    pub fn frames(&self, q: &[f64], errors: bool) -> Result<(Isometry3<f64>, Isometry3<f64>)> {
        self.check_positions(q)?;
        let nw = self.work.len();
        Ok((
            self.branch(&self.work, &q[..nw], errors, &self.work_origin, true)?,
            self.branch(&self.tool, &q[nw..], errors, &self.tool_tip, false)?,
        ))
    }

    /// The set-up transform that multiplies `F_work(q)` on the right (module docs), or `None`
    /// where there is none: without a set-up, or without errors (it is then the identity).
    fn setup_transform(&self, errors: bool, setup: &Setup) -> Result<Option<Isometry3<f64>>> {
        match setup {
            Setup::None => Ok(None),
            Setup::AtPose(q0) if errors => {
                let (fw0, _) = self.frames(q0, true)?;
                let (fn0, _) = self.frames(q0, false)?;
                Ok(Some(fw0.inverse() * fn0))
            }
            Setup::AtPose(q0) => {
                self.check_positions(q0)?;
                Ok(None)
            }
        }
    }

    /// The workpiece frame actually used, `F_work(q)` times the set-up transform, and `F_tool`.
    fn used_frames(
        &self,
        q: &[f64],
        errors: bool,
        setup: &Setup,
    ) -> Result<(Isometry3<f64>, Isometry3<f64>)> {
        let (fw, ft) = self.frames(q, errors)?;
        Ok(match self.setup_transform(errors, setup)? {
            Some(m) => (fw * m, ft),
            None => (fw, ft),
        })
    }

    /// The tool in workpiece coordinates at positions `q`, with (`errors`) or without the
    /// chain's errors. The set-up only matters with errors.
    pub fn tool_pose(&self, q: &[f64], errors: bool, setup: &Setup) -> Result<ToolPose> {
        let (fw, ft) = self.used_frames(q, errors, setup)?;
        let g = fw.inverse() * ft;
        Ok(ToolPose {
            tip: (g * Point3::origin()).coords,
            axis: g.rotation * self.tool_axis.unit(),
        })
    }

    /// An evaluator of [`Chain::tool_pose`] (no set-up) for many poses that differ in a few
    /// axes, as over a grid: it keeps each link's transform and each branch's partial products
    /// and recomputes only from the first link whose position changed. Same results as
    /// `tool_pose(q, errors, &Setup::None)`.
    pub fn poses(&self, errors: bool) -> PoseEvaluator<'_> {
        PoseEvaluator {
            chain: self,
            errors,
            work: BranchCache::default(),
            tool: BranchCache::default(),
        }
    }

    /// Where [`Chain::jacobian`] puts location error component `component` (0..6) of the link
    /// with chain index `link`: location errors come first, 6 per link, links in chain order.
    pub const fn location_index(link: usize, component: usize) -> usize {
        6 * link + component
    }

    /// The first-order sensitivities of the tool tip and axis (workpiece coordinates) to every
    /// error component of every link: 6 location components per link, then 6 error-motion
    /// components per link, links in chain order. Evaluated at zero errors (the nominal chain).
    /// The set-up enters the location errors of the workpiece branch (an error-motion value is
    /// taken at the current position, which is not the set-up position).
    pub fn jacobian(&self, q: &[f64], setup: &Setup) -> Result<Vec<Sensitivity>> {
        self.check_positions(q)?;
        let q0 = match setup {
            Setup::None => None,
            Setup::AtPose(q0) => {
                self.check_positions(q0)?;
                Some(q0.as_slice())
            }
        };
        let (fw, ft) = self.frames(q, false)?;
        let g = fw.inverse() * ft;
        let (tip_w, axis_w) = (
            (g * Point3::origin()).coords,
            g.rotation * self.tool_axis.unit(),
        );
        let nw = self.work.len();
        let mut out = Vec::with_capacity(12 * self.len());
        for kind in [ErrorKind::Location, ErrorKind::Motion] {
            for i in 0..self.len() {
                let on_work = i < nw;
                // B: the rest of the branch after the insertion point, as a transform.
                let rest = |qs: &[f64]| -> Isometry3<f64> {
                    let (links, qb, end, j) = if on_work {
                        (&self.work, &qs[..nw], &self.work_origin, i)
                    } else {
                        (&self.tool, &qs[nw..], &self.tool_tip, i - nw)
                    };
                    // Location errors and rotary error motions sit before the axis's own
                    // motion, linear error motions after it.
                    let mut t = match (kind, links[j].joint) {
                        (ErrorKind::Motion, Joint::Linear(_)) => Isometry3::identity(),
                        _ => links[j].joint.motion(links[j].sign * qb[j]),
                    };
                    for (l, &qk) in links[j + 1..].iter().zip(&qb[j + 1..]) {
                        t *= l.nominal(qk);
                    }
                    t * Isometry3::from_parts(Translation3::from(*end), UnitQuaternion::identity())
                };
                let b = rest(q);
                // The same at the set-up pose, for the workpiece branch's location errors.
                let b0 = match (q0, kind, on_work) {
                    (Some(q0), ErrorKind::Location, true) => Some(rest(q0)),
                    _ => None,
                };
                let link = self.link(i);
                // A workpiece-side error motion enters as D(m)⁻¹ ≈ D(−m) (module docs).
                let side = match kind {
                    ErrorKind::Motion if on_work => -1.0,
                    _ => 1.0,
                };
                for k in 0..6 {
                    // ξ_k applied to a point y: e_k (translation) or e_(k-3) × y (rotation).
                    let xi = |y: &Vector3<f64>| -> Vector3<f64> {
                        if k < 3 {
                            Axis::ALL[k].unit()
                        } else {
                            Axis::ALL[k - 3].unit().cross(y)
                        }
                    };
                    let xi_dir = |d: &Vector3<f64>| -> Vector3<f64> {
                        if k < 3 {
                            Vector3::zeros()
                        } else {
                            Axis::ALL[k - 3].unit().cross(d)
                        }
                    };
                    let (dtip, daxis) = if on_work {
                        // F_work = A·D·B: the tool seen from the workpiece moves by -B_rotᵀ·ξ(B·x).
                        let binv = b.rotation.inverse();
                        let mut dt = -(binv * xi(&(b * Point3::from(tip_w)).coords));
                        let mut da = -(binv * xi_dir(&(b.rotation * axis_w)));
                        if let Some(b0) = b0 {
                            let b0inv = b0.rotation.inverse();
                            dt += b0inv * xi(&(b0 * Point3::from(tip_w)).coords);
                            da += b0inv * xi_dir(&(b0.rotation * axis_w));
                        }
                        (dt, da)
                    } else {
                        // F_tool = A·D·B: the tip moves by A_rot·ξ(B·0), seen through F_work⁻¹.
                        let a_rot = ft.rotation * b.rotation.inverse();
                        let to_work = fw.rotation.inverse() * a_rot;
                        let tip_local = (b * Point3::origin()).coords;
                        let axis_local = b.rotation * self.tool_axis.unit();
                        (to_work * xi(&tip_local), to_work * xi_dir(&axis_local))
                    };
                    out.push(Sensitivity {
                        name: match kind {
                            ErrorKind::Location => link.location_name(k),
                            ErrorKind::Motion => link.motion_name(k),
                        },
                        link: i,
                        kind,
                        component: k,
                        tip: dtip * side,
                        axis: daxis * side,
                    });
                }
            }
        }
        Ok(out)
    }

    /// The rotary axes of a five-axis chain in the nonlinear-error study's terms: the type `KMH`
    /// (K the rotary axis nearer the workpiece) and the indices of K and M in chain order, plus
    /// the factors `θ = f·q` that turn commands into the study's angles (module docs: with ISO 841
    /// signs both are `+1`).
    pub fn rotary_type(&self) -> Result<RotaryLayout> {
        let mut rotary: Vec<(usize, f64)> = Vec::new();
        let nw = self.work.len();
        // From the workpiece outwards: the workpiece branch reversed, then the tool branch.
        for i in (0..nw).rev() {
            let l = &self.work[i];
            if let Joint::Rotary(_) = l.joint {
                rotary.push((i, -l.sign));
            }
        }
        for (j, l) in self.tool.iter().enumerate() {
            if let Joint::Rotary(_) = l.joint {
                rotary.push((nw + j, l.sign));
            }
        }
        if rotary.len() != 2 {
            return Err(Error::field(
                "machine",
                format!(
                    "a five-axis chain needs exactly 2 rotary axes, this one has {}",
                    rotary.len()
                ),
            ));
        }
        let letter = |i: usize| match self.link(i).joint.axis() {
            Axis::X => RotaryAxis::A,
            Axis::Y => RotaryAxis::B,
            Axis::Z => RotaryAxis::C,
        };
        let name = format!(
            "{}{}{}",
            letter(rotary[0].0).letter(),
            letter(rotary[1].0).letter(),
            self.tool_axis.letter()
        );
        let rtype = RotaryType::parse(&name)?;
        Ok(RotaryLayout {
            rtype,
            k: rotary[0].0,
            m: rotary[1].0,
            k_factor: rotary[0].1,
            m_factor: rotary[1].1,
        })
    }

    /// Nominal inverse kinematics: the axis positions (chain order) that put the tool tip at
    /// `tip` with axis `direction` in workpiece coordinates. The rotary angles come from
    /// [`RotaryType::inverse`] (continuing from `previous`, chain order, when given); the three
    /// linear positions from the tip, which is affine in them once the rotary axes are fixed.
    /// Returns the positions and whether the orientation is singular (K arbitrary).
    pub fn inverse(
        &self,
        tip: &Vector3<f64>,
        direction: &Vector3<f64>,
        previous: Option<&[f64]>,
    ) -> Result<(Vec<f64>, bool)> {
        let layout = self.inverse_layout(previous)?;
        let prev_pose = previous
            .map(|p| Pose::new(layout.k_factor * p[layout.k], layout.m_factor * p[layout.m]));
        let sol = layout.rtype.inverse(direction, prev_pose)?;
        let mut q = previous.map_or_else(|| vec![0.0; self.len()], <[f64]>::to_vec);
        q[layout.k] = sol.chosen.k / layout.k_factor;
        q[layout.m] = sol.chosen.m / layout.m_factor;
        let q = self.solve_linear(tip, &q)?;
        Ok((q, sol.singular))
    }

    /// Every nominal inverse-kinematics solution for a tool tip and direction in workpiece
    /// coordinates: one position vector (chain order) per rotary solution of
    /// [`RotaryType::inverse`], i.e. two, or one at a singular orientation (then K is 0). Rotary
    /// commands are in `(-π, π]` (add whole turns as the machine needs); the linear positions
    /// are solved as in [`Chain::inverse`]. A study picks the branch its machine uses (a travel
    /// range, a sign of the tilt) from these. Returns the solutions and the singular flag.
    pub fn inverse_all(
        &self,
        tip: &Vector3<f64>,
        direction: &Vector3<f64>,
    ) -> Result<(Vec<Vec<f64>>, bool)> {
        let layout = self.inverse_layout(None)?;
        let sol = layout.rtype.inverse(direction, None)?;
        let mut out = Vec::with_capacity(sol.solutions.len());
        for pose in &sol.solutions {
            let mut q = vec![0.0; self.len()];
            q[layout.k] = pose.k / layout.k_factor;
            q[layout.m] = pose.m / layout.m_factor;
            out.push(self.solve_linear(tip, &q)?);
        }
        Ok((out, sol.singular))
    }

    /// The rotary layout, after checking `previous` and the axis offsets (inverse kinematics).
    fn inverse_layout(&self, previous: Option<&[f64]>) -> Result<RotaryLayout> {
        let layout = self.rotary_type()?;
        if let Some(p) = previous {
            self.check_positions(p)?;
        }
        if self
            .links()
            .any(|(_, l)| l.offset.iter().any(|v| !v.is_finite()))
        {
            return Err(Error::field("machine", "axis offsets must be finite"));
        }
        Ok(layout)
    }

    /// Nominal inverse kinematics for given rotary positions: `q` (chain order) with its rotary
    /// entries kept and its three linear entries replaced by those that put the tool tip at `tip`
    /// (workpiece coordinates, mm). The tip is affine in the linear positions once the rotary
    /// axes are fixed, so one 3×3 solve is exact. Used by [`Chain::inverse`],
    /// [`Chain::inverse_all`] and by studies that choose the rotary angles themselves (e.g. a
    /// paper's own branch of the two solutions).
    pub fn solve_linear(&self, tip: &Vector3<f64>, q: &[f64]) -> Result<Vec<f64>> {
        self.check_positions(q)?;
        if !tip.iter().all(|v| v.is_finite()) {
            return Err(Error::field("tip", "must be finite"));
        }
        let mut q = q.to_vec();
        let linear: Vec<usize> = (0..self.len())
            .filter(|&i| matches!(self.link(i).joint, Joint::Linear(_)))
            .collect();
        if linear.len() != 3 {
            return Err(Error::field(
                "machine",
                format!(
                    "a five-axis chain needs exactly 3 linear axes, this one has {}",
                    linear.len()
                ),
            ));
        }
        for &i in &linear {
            q[i] = 0.0;
        }
        let tip_at =
            |q: &[f64]| -> Result<Vector3<f64>> { Ok(self.tool_pose(q, false, &Setup::None)?.tip) };
        let c = tip_at(&q)?;
        let mut m = Matrix3::zeros();
        for (col, &i) in linear.iter().enumerate() {
            let mut qi = q.to_vec();
            qi[i] = 1.0;
            m.set_column(col, &(tip_at(&qi)? - c));
        }
        let x = m.lu().solve(&(tip - c)).ok_or_else(|| {
            Error::field("machine", "the linear axes do not span three directions")
        })?;
        for (col, &i) in linear.iter().enumerate() {
            q[i] = x[col];
        }
        Ok(q)
    }
}

/// Where the rotary axes K and M of the nonlinear-error study sit in a chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotaryLayout {
    /// The rotary-axis type `KMH`.
    pub rtype: RotaryType,
    /// Index of K in chain order.
    pub k: usize,
    /// Index of M in chain order.
    pub m: usize,
    /// θk = `k_factor`·q_K.
    pub k_factor: f64,
    /// θm = `m_factor`·q_M.
    pub m_factor: f64,
}

/// One branch's kept transforms: positions, each link's frame and the products from the bed.
#[derive(Debug, Default)]
struct BranchCache {
    q: Vec<f64>,
    link: Vec<Isometry3<f64>>,
    prefix: Vec<Isometry3<f64>>,
}

impl BranchCache {
    /// The branch's end frame at `q`, recomputing from the first link whose position changed.
    fn end(
        &mut self,
        links: &[Link],
        q: &[f64],
        errors: bool,
        on_work: bool,
    ) -> Result<Isometry3<f64>> {
        let n = links.len();
        let mut from = if self.q.len() == n {
            (0..n).find(|&i| self.q[i] != q[i]).unwrap_or(n)
        } else {
            self.q = q.to_vec();
            self.link = vec![Isometry3::identity(); n];
            self.prefix = vec![Isometry3::identity(); n];
            for (i, l) in links.iter().enumerate() {
                self.link[i] = l.transform(q[i], errors, on_work)?;
            }
            0
        };
        for i in from..n {
            if self.q[i] != q[i] {
                self.link[i] = links[i].transform(q[i], errors, on_work)?;
                self.q[i] = q[i];
            }
        }
        if n == 0 {
            return Ok(Isometry3::identity());
        }
        if from == 0 {
            self.prefix[0] = self.link[0];
            from = 1;
        }
        for i in from..n {
            self.prefix[i] = self.prefix[i - 1] * self.link[i];
        }
        Ok(self.prefix[n - 1])
    }
}

/// See [`Chain::poses`].
#[derive(Debug)]
pub struct PoseEvaluator<'a> {
    chain: &'a Chain,
    errors: bool,
    work: BranchCache,
    tool: BranchCache,
}

impl PoseEvaluator<'_> {
    /// The tool in workpiece coordinates at `q` (as [`Chain::tool_pose`] without a set-up).
    pub fn tool_pose(&mut self, q: &[f64]) -> Result<ToolPose> {
        let c = self.chain;
        c.check_positions(q)?;
        let nw = c.work.len();
        let end = |v: &Vector3<f64>| {
            Isometry3::from_parts(Translation3::from(*v), UnitQuaternion::identity())
        };
        let fw = self.work.end(&c.work, &q[..nw], self.errors, true)? * end(&c.work_origin);
        let ft = self.tool.end(&c.tool, &q[nw..], self.errors, false)? * end(&c.tool_tip);
        let g = fw.inverse() * ft;
        Ok(ToolPose {
            tip: (g * Point3::origin()).coords,
            axis: g.rotation * c.tool_axis.unit(),
        })
    }
}
