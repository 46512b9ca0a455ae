//! Checking the rotary axes with a touch probe and a sphere (issue 31): a sphere sits on the
//! table; the spindle's touch probe measures its centre at `N` poses of the two rotary axes; the
//! centres' wander identifies the location errors of the rotary axes (ISO 230-1,
//! [`crate::machine::errors`]), as Heidenhain's KinematicsOpt, Siemens' CYCLE996 and Renishaw's
//! AxiSet do.
//!
//! # What is measured (frame, units, signs)
//! The sphere's centre sits at `s` in the workpiece frame of the machine's chain
//! ([`crate::chain`]): the table surface's centre, axes parallel to the machine's at K = M = 0;
//! `s = x·u + y·v + height·n` with `(u, v, n)` the face frame ([`Machine::face_frame`]: X, Y, Z
//! for a vertical spindle), mm. The probe is the machine's tool: its ball centre is the tool tip
//! (`toolLength` from the spindle nose), calibrated (its length and ball are where the control
//! believes).
//!
//! At a pose `(K, M)` the control's probing cycle touches the sphere from several sides and
//! reports its centre as the **linear-axis positions `c = (X, Y, Z)`** (mm, in the machine's
//! coordinates, TCPM/RTCP off, in the chain's convention: at X = Y = Z = 0 and the rotary axes
//! at 0 the spindle nose, or a head's tilting axis, is at the machine origin, the rotary centre)
//! at which the probe's ball centre is at the sphere's centre. With the true machine `tip(q)` (the
//! chain with its errors) that is the solution of
//!
//! ```text
//! tip_actual(K, M, c) = s                       (1)
//! ```
//!
//! and the control expects `c₀`, the solution of `tip_nominal(K, M, c₀) = s` (the nominal
//! kinematics, [`crate::chain::Chain::solve_linear`]). A positive deviation `c − c₀` along X
//! means the control had to move X further positive than it believed to reach the sphere.
//! [`Study::measured`] solves (1) by Newton's method on the exact chain (the tip is affine in
//! the linear positions once the rotary axes stand still: one step is exact up to rounding).
//!
//! # Sensitivities
//! To first order `tip_actual(q₀ + δc, ε) = s + J_c·δc + J_ε·ε`, with `J_c` the 3 × 3 matrix
//! of the tip's derivatives by the three linear positions (nominal chain; exact, the tip is
//! affine in them) and `J_ε` the chain's analytic Jacobian ([`crate::chain::Chain::jacobian`],
//! workpiece frame, no set-up). From (1):
//!
//! ```text
//! ∂c/∂ε = −J_c⁻¹·J_ε           ∂c/∂s = J_c⁻¹                (2)
//! ```
//!
//! (per mm, per rad inside; per degree at the edge). The second is the effect of the sphere not
//! being exactly where it was stated: when `fitSphere` is on (the default) its three components
//! `sphere_X`, `sphere_Y`, `sphere_Z` (mm, workpiece frame) are fitted with the errors, so that
//! the sphere's position need only be known to a millimetre or so (the linear model holds for
//! a position error much smaller than the lever arms).
//!
//! # What a single sphere cannot see
//! An error is **invisible** when its column of (2) is zero at every pose within the travel:
//! e.g. the zero position of the table axis (`E_C0C`) with the sphere on C's axis line (a turn
//! about a line moves no point of it), or any error of the head of a head-head machine that only
//! turns the probe about its own ball centre. Such an error changes no measured centre at all
//! (a test checks it on the exact chain). An error whose column lies in the span of others at
//! every pose is **inseparable**: only combinations are measured ([`crate::identify::fit`]'s
//! groups). With the sphere's position fitted:
//! * a table axis's zero (`E_C0C`) turns the sphere about that axis, exactly as if it had been
//!   set at another angle on the table: it is inseparable from the sphere's position;
//! * a shift along a table axis's own line (`E_Z0C`) is a change of the sphere's height;
//! * the bed-side axis's line position (`E_X0B`, `E_Z0B` of a tilting table) shifts every
//!   centre by the same amount, as would a probe whose length or ball is mis-calibrated: the
//!   probe must be calibrated, and a constant offset of all readings (another origin) appears
//!   there.
//!
//! A **second sphere position** adds rows whose lever arms differ: with one sphere on C's axis
//! a tilt of C (`E_A0C`) and an offset of C's line (`E_Y0C`) move the sphere alike (a tilt at
//! height h is an offset of h·angle), and a second sphere at another height or radius separates
//! them; errors that act as a change of the sphere's own position stay inseparable however many
//! spheres are used, since each sphere's position is fitted. [`design::design`] reports both.
//!
//! # Degenerate cases
//! A pose where the tool axis tilts from the table's normal by more than `maxTilt` is not
//! probed (the sphere's stem or the table would be in the way); a machine whose linear axes do
//! not span three directions is refused by the chain; with fewer poses than the identifiable
//! combinations plus one the fit refuses (no residual left to judge).

pub mod api;
pub mod design;
pub mod fit;
pub mod measure;

use crate::chain::Setup;
use crate::cubic::design::{TYPICAL_ANGLE, TYPICAL_POSITION};
use crate::error::{Error, Result};
use crate::machine::errors::{ErrorDef, NAMES};
use crate::machine::{Machine, Model};
use crate::schema::{self, DefaultValue, Kind, Quantity};
use nalgebra::{Matrix3, Vector3};

/// Names of the sphere's position parameters (mm, workpiece frame at K = M = 0).
pub const SPHERE_NAMES: [&str; 3] = ["sphere_X", "sphere_Y", "sphere_Z"];

crate::inputs! {
    /// Where the sphere's centre sits on the table (mm, the face frame of the table surface).
    pub struct SpherePlace {
        /// Along the face's first axis (X for a vertical spindle), mm.
        pub x: f64 = "x" optional {
            label: "Sphere centre along the table's first axis",
            help: "From the table centre (on the table axis), along X for a vertical spindle (the face's first axis), with all axes at zero.",
            kind: schema::number(Quantity::Length, -2000.0, 2000.0),
            default: DefaultValue::Num(0.0),
            group: "Sphere",
        },
        /// Along the face's second axis (Y for a vertical spindle), mm.
        pub y: f64 = "y" optional {
            label: "Sphere centre along the table's second axis",
            help: "From the table centre, along Y for a vertical spindle (the face's second axis).",
            kind: schema::number(Quantity::Length, -2000.0, 2000.0),
            default: DefaultValue::Num(0.0),
            group: "Sphere",
        },
        /// Height of the centre above the table surface, mm.
        pub height: f64 = "height" optional {
            label: "Sphere centre above the table",
            help: "Height of the sphere's centre above the table surface (along the spindle at zero).",
            kind: schema::number(Quantity::Length, -2000.0, 2000.0),
            default: DefaultValue::Num(100.0),
            group: "Sphere",
        },
    }
}

crate::inputs! {
    /// The probing study's case: the machine, the sphere and what is fitted.
    pub struct ProbeInput {
        /// The machine (its errors are the truth the simulation uses).
        pub machine: Machine = "machine" optional {
            label: "Machine", kind: Kind::Object(Machine::FIELDS), default: DefaultValue::Empty,
        },
        /// Where the sphere sits.
        pub sphere: SpherePlace = "sphere" optional {
            label: "Sphere", kind: Kind::Object(SpherePlace::FIELDS), default: DefaultValue::Empty,
        },
        /// Fit the sphere's position with the errors.
        pub fit_sphere: bool = "fitSphere" optional {
            label: "Sphere position found from the measurement",
            help: "On: the sphere's exact position is unknown and is fitted with the errors (the usual case). Off: the sphere is exactly where stated (to the µm); then a table axis's zero can be seen too, if the sphere is off its axis.",
            kind: Kind::Flag,
            default: DefaultValue::Flag(true),
            group: "Sphere",
        },
        /// The errors to identify; the rotary axes' location errors when left out.
        pub parameters: Option<Vec<String>> = "parameters" optional {
            label: "Errors to identify",
            help: "ISO 230-1 names; left out: the twelve location errors of the two rotary axes.",
            kind: NAMES,
            group: "Sphere",
        },
        /// Largest tilt of the tool axis from the table's normal at which the sphere is probed.
        pub max_tilt: f64 = "maxTilt" optional {
            label: "Largest tilt of the probe from the table's normal",
            help: "Poses where the probe would lean further from the table's normal (the sphere's stem or the table in the way) are not used.",
            kind: schema::number(Quantity::Angle, 10.0, 180.0),
            default: DefaultValue::Num(90.0),
            group: "Sphere",
        },
        /// One standard deviation of a measured centre coordinate, mm.
        pub noise: f64 = "noise" optional {
            label: "Probing noise (one standard deviation)",
            help: "Of one coordinate of a measured centre; it scales the design (a singular value is in units of this noise).",
            kind: schema::positive(Quantity::SmallLength, 1.0),
            default: DefaultValue::Num(0.001),
            group: "Sphere",
        },
    }
}

impl crate::edge::Checked for ProbeInput {
    fn check(&self) -> Result<()> {
        self.machine.validate("machine")
    }
}

/// One unknown of the fit: a location error of the machine, or a component of the sphere's
/// position (0, 1, 2: X, Y, Z of the workpiece frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Unknown {
    /// A machine error (its column from the chain's Jacobian).
    Error(&'static ErrorDef),
    /// The sphere's position along X, Y or Z, mm.
    Sphere(usize),
}

impl Unknown {
    /// Its name: the ISO name or `sphere_X` ….
    pub fn name(&self) -> &'static str {
        match self {
            Unknown::Error(d) => d.name,
            Unknown::Sphere(i) => SPHERE_NAMES[*i],
        }
    }

    /// `SmallLength` (mm) or `SmallAngle` (rad inside).
    pub fn quantity(&self) -> Quantity {
        match self {
            Unknown::Error(d) => d.quantity,
            Unknown::Sphere(_) => Quantity::SmallLength,
        }
    }

    /// The typical size the designer scales it by (10 µm, 10⁻⁴ rad; [`crate::cubic::design`]).
    pub fn typical(&self) -> f64 {
        if self.quantity() == Quantity::SmallAngle {
            TYPICAL_ANGLE
        } else {
            TYPICAL_POSITION
        }
    }
}

/// The study on a built machine: the chain, the sphere and the unknowns.
#[derive(Debug, Clone)]
pub struct Study {
    /// The machine built (its chain with the errors, and the nominal one).
    pub model: Model,
    /// The sphere's centre in the workpiece frame, mm.
    pub sphere: Vector3<f64>,
    /// The unknowns: the errors, then the sphere's position when fitted.
    pub unknowns: Vec<Unknown>,
    /// Largest tilt of the tool axis from the table's normal, rad.
    pub max_tilt: f64,
    /// Noise of one centre coordinate, mm.
    pub noise: f64,
    linear: [usize; 3],
}

/// The default unknowns: the location errors of the two rotary axes, in table order.
pub fn rotary_errors(machine: &Machine) -> Vec<&'static ErrorDef> {
    let [k, m] = [machine.k().letter(), machine.m().letter()];
    machine
        .error_defs()
        .into_iter()
        .filter(|d| d.axis == k || d.axis == m)
        .collect()
}

impl Study {
    /// The study of the input: the machine built, the sphere placed, the unknowns chosen.
    pub fn new(input: &ProbeInput) -> Result<Self> {
        let machine = &input.machine;
        let model = machine.build()?;
        let errors: Vec<&'static ErrorDef> = match &input.parameters {
            None => rotary_errors(machine),
            Some(names) => {
                let all = machine.error_defs();
                names
                    .iter()
                    .enumerate()
                    .map(|(i, n)| {
                        all.iter().copied().find(|d| d.name == n).ok_or_else(|| {
                            Error::field(
                                format!("parameters[{i}]"),
                                format!("{n} is not an error of this machine"),
                            )
                        })
                    })
                    .collect::<Result<_>>()?
            }
        };
        if errors.is_empty() {
            return Err(Error::field(
                "parameters",
                "choose at least one error to identify",
            ));
        }
        let mut unknowns: Vec<Unknown> = errors.into_iter().map(Unknown::Error).collect();
        if input.fit_sphere {
            unknowns.extend((0..3).map(Unknown::Sphere));
        }
        let linear = crate::machine::linear_axes(&model.chain)?;
        let sphere = sphere_position(machine, &input.sphere);
        Ok(Self {
            model,
            sphere,
            unknowns,
            max_tilt: input.max_tilt,
            noise: input.noise,
            linear,
        })
    }

    /// The same study with the sphere at `place`.
    pub fn with_sphere(&self, place: &SpherePlace) -> Self {
        Self {
            sphere: sphere_position(&self.model.machine, place),
            ..self.clone()
        }
    }

    /// The unknowns' names.
    pub fn names(&self) -> Vec<String> {
        self.unknowns.iter().map(|u| u.name().to_string()).collect()
    }

    /// The chain positions at the rotary commands `k`, `m` (rad) with the linear axes at `c`.
    fn positions(&self, k: f64, m: f64, c: &Vector3<f64>) -> Vec<f64> {
        let mut q = self.model.positions(k, m);
        for (j, &i) in self.linear.iter().enumerate() {
            q[i] = c[j];
        }
        q
    }

    fn linear_of(&self, q: &[f64]) -> Vector3<f64> {
        Vector3::new(q[self.linear[0]], q[self.linear[1]], q[self.linear[2]])
    }

    /// The centre the control expects at `(k, m)` (rad): the linear positions `c₀` at which the
    /// nominal tip is at the sphere's centre (module docs), mm.
    pub fn expected(&self, k: f64, m: f64) -> Result<Vector3<f64>> {
        let q = self
            .model
            .nominal()
            .solve_linear(&self.sphere, &self.model.positions(k, m))?;
        Ok(self.linear_of(&q))
    }

    /// The centre measured on the machine with its errors (the exact chain, eq 1), mm.
    pub fn measured(&self, k: f64, m: f64) -> Result<Vector3<f64>> {
        let chain = &self.model.chain;
        let tip = |c: &Vector3<f64>| -> Result<Vector3<f64>> {
            Ok(chain
                .tool_pose(&self.positions(k, m, c), true, &Setup::None)?
                .tip)
        };
        let mut c = self.expected(k, m)?;
        for _ in 0..8 {
            let t = tip(&c)?;
            let r = self.sphere - t;
            if r.norm() < 1e-13 * (1.0 + self.sphere.norm()) {
                break;
            }
            let mut j = Matrix3::zeros();
            for i in 0..3 {
                let mut ci = c;
                ci[i] += 1.0;
                j.set_column(i, &(tip(&ci)? - t));
            }
            let step = j.lu().solve(&r).ok_or_else(|| {
                Error::field("machine", "the linear axes do not span three directions")
            })?;
            c += step;
        }
        Ok(c)
    }

    /// `J_c`: the nominal tip's derivatives by X, Y, Z at `(k, m)` (columns; exact, the tip
    /// is affine in them).
    fn linear_jacobian(&self, k: f64, m: f64) -> Result<Matrix3<f64>> {
        let nominal = self.model.nominal();
        let c0 = self.expected(k, m)?;
        let tip = |c: &Vector3<f64>| -> Result<Vector3<f64>> {
            Ok(nominal
                .tool_pose(&self.positions(k, m, c), false, &Setup::None)?
                .tip)
        };
        let t0 = tip(&c0)?;
        let mut j = Matrix3::zeros();
        for i in 0..3 {
            let mut ci = c0;
            ci[i] += 1.0;
            j.set_column(i, &(tip(&ci)? - t0));
        }
        Ok(j)
    }

    /// The sensitivities of the centre at `(k, m)` to every unknown (eq 2): one 3-vector per
    /// unknown, mm per mm or mm per rad.
    pub fn sensitivities(&self, k: f64, m: f64) -> Result<Vec<Vector3<f64>>> {
        let jc = self.linear_jacobian(k, m)?;
        let inv = jc.try_inverse().ok_or_else(|| {
            Error::field("machine", "the linear axes do not span three directions")
        })?;
        let c0 = self.expected(k, m)?;
        let q = self.positions(k, m, &c0);
        let jac = self.model.nominal().jacobian(&q, &Setup::None)?;
        self.unknowns
            .iter()
            .map(|u| match u {
                Unknown::Error(d) => {
                    let col = self.model.error_column(d)?;
                    Ok(effect(-(inv * jac[col].tip)))
                }
                Unknown::Sphere(i) => Ok(inv.column(*i).into_owned()),
            })
            .collect()
    }

    /// The angle between the tool axis and the table's normal at `(k, m)`, rad (nominal).
    pub fn tilt(&self, k: f64, m: f64) -> Result<f64> {
        let pose =
            self.model
                .nominal()
                .tool_pose(&self.model.positions(k, m), false, &Setup::None)?;
        let n = self.model.machine.home().unit();
        Ok(pose.axis.dot(&n).clamp(-1.0, 1.0).acos())
    }

    /// Whether `(k, m)` is within the travel and the tilt limit.
    pub fn reachable(&self, k: f64, m: f64) -> Result<bool> {
        let [(k_lo, k_hi), (m_lo, m_hi)] = self.model.travel();
        let tol = crate::machine::TRAVEL_TOLERANCE;
        let within = k >= k_lo - tol && k <= k_hi + tol && m >= m_lo - tol && m <= m_hi + tol;
        Ok(within && self.tilt(k, m)? <= self.max_tilt + 1e-9)
    }
}

/// The sphere's centre in the workpiece frame: `x·u + y·v + height·n` (module docs).
pub fn sphere_position(machine: &Machine, place: &SpherePlace) -> Vector3<f64> {
    let [u, v, n] = machine.face_frame();
    u * place.x + v * place.y + n * place.height
}

/// Below this a sensitivity of the centre to an error is the chain's rounding, not an effect:
/// mm per mm, or per rad (0.1 pm per rad; the rounding of a 1 m lever is about 1e-13 mm).
const EFFECT_FLOOR: f64 = 1e-10;

/// A sensitivity of the centre to an error, with the chain's rounding taken for what it is
/// ([`EFFECT_FLOOR`]): zero. An error no pose can see (C's zero with the sphere on C's line)
/// would otherwise keep a column of rounding, which the designer's and the fit's thresholds,
/// relative to the largest column, take for an effect when it is the only column.
fn effect(v: Vector3<f64>) -> Vector3<f64> {
    if v.norm() < EFFECT_FLOOR {
        Vector3::zeros()
    } else {
        v
    }
}
