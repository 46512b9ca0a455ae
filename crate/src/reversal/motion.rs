//! The programmed motion of the reversal test (Nishiguchi et al. 2017, Section 3, Figs 2, 3, 5,
//! 6): a circle in table coordinates while C goes from 0 to its reversal angle and back, the
//! linear axes from the machine's inverse kinematics.
//!
//! # The circle (workpiece = table coordinates, mm)
//! The tool stands along C's axis (+Z in workpiece coordinates); its tip runs once round a
//! circle of radius `R` (the ball-bar length or the cut radius) at the height of the table
//! surface, counter-clockwise seen from +Z. The circle's centre is at distance `r` from C's axis
//! (Table 1: 25 and 50 mm). Its *trace angle* θ (the angle of the plots) runs from 0° to 360°;
//! C is at its reversal when θ = 180°, as in the paper's Figs 9–14. In workpiece coordinates the
//! tip is at `c + R·(cos ψ, sin ψ)` with `ψ = θ + ψ₀`.
//!
//! * **C against θ.** C rises at the rate `ċ = dC/dθ` from 0 at θ = 0 to the reversal angle
//!   (default 90°) at θ = 180° and falls back to 0 at θ = 360°. A real control cannot reverse an
//!   axis in no time: within `±w` of θ = 180° the rate turns over as `ċ·(−sin(π·u/2w))`
//!   (u = θ − 180°), so C, its velocity and its acceleration are continuous; `w` is what the
//!   axis covers in half the *reversal time* at the feed, and `ċ = C_rev/(π − w + 2w/π)` makes C
//!   reach exactly `C_rev`. The circle itself is exact whatever C does: the linear axes follow C
//!   through the inverse kinematics.
//! * **Where the centre is** (what makes the test work, Section 3): at the reversal the radius
//!   from the centre to the tip is at 45° to the machine's X and Y (`ψ₀` is chosen so), and
//!   the centre sits `r` from C's axis along the circle's tangent there, `c = a − σ·r·J·e(ψ_rev)`
//!   (`a` C's axis, `J` the quarter turn, `σ = ±1` the sense in which C turns the table). Then an
//!   error `δC` of C moves the tip by `δC·r` along the radius at the reversal: the C error is
//!   copied onto the circle (a lagging C dents it inwards). And X and Y do not reverse when C
//!   does: across the reversal the velocity in table coordinates jumps by `2ċθ̇·J·(tip − a)`,
//!   whose component along the radius (`±ċθ̇·r`) is smaller than the tangential speed
//!   `(1 ∓ ċ)·R·θ̇` on both machine axes at 45° as long as `R ≥ r` (for ċ = 1/2). At `R = r`
//!   one of them comes to a stop at the reversal without changing direction, as the paper
//!   observes for r = 50 mm (its ball bar is then 50 mm long).
//! * **Feed.** The tip accelerates from rest to the feed `F` in the acceleration time `T_a`
//!   with a smooth (jerk-limited) profile `ṡ = F/2·(1 − cos(πt/T_a))`, runs at `F`, and stops
//!   the same way at θ = 360°.
//!
//! # Inverse kinematics
//! The machine needs a rotary table C: K = C on the table (table-table or head-table). With
//! the tool along C's axis the orientation is C's pole, where C is free (it keeps the value
//! given) and M is fixed; the machine's inverse kinematics ([`Model::inverse`]) then gives the
//! linear axes. With M and the tool fixed, these are affine in the tip turned with the table:
//! `q_lin = L·R_Z(σC)·(p − a) + l₀`. `L`, `l₀`, `a` and `σ` are read off the machine's own
//! inverse kinematics at a few poses and checked against it at others (to 1e-9 mm), so that the
//! commands and their first two time derivatives come in closed form at every integration step.

use crate::error::{Error, Result};
use crate::machine::{BranchRule, MachineKind, Model};
use crate::rotary::RotaryAxis;
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI, TAU};

/// A position with its first two time derivatives (mm or rad, per s, per s²).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Jet {
    /// Position.
    pub x: f64,
    /// Velocity.
    pub v: f64,
    /// Acceleration.
    pub a: f64,
}

/// The commands at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Commands {
    /// The trace angle θ, rad.
    pub theta: f64,
    /// The three linear axes (chain order of [`Motion::linear`]), mm.
    pub linear: [Jet; 3],
    /// C, rad (command).
    pub c: Jet,
}

/// What the motion is made from (engine units: mm, rad, s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionSpec {
    /// Circle radius `R`, mm.
    pub radius: f64,
    /// Distance of the circle's centre from C's axis `r`, mm.
    pub offset: f64,
    /// Feed `F`, mm/s.
    pub feed: f64,
    /// C at the reversal, rad.
    pub reversal_angle: f64,
    /// Acceleration time `T_a`, s.
    pub accel_time: f64,
    /// Reversal time of C, s.
    pub reversal_time: f64,
}

/// The programmed motion on one machine (module docs).
#[derive(Debug, Clone)]
pub struct Motion {
    /// What it was made from.
    pub spec: MotionSpec,
    /// The machine's model (errors included).
    pub model: Model,
    /// Chain indices of the linear axes.
    pub linear: [usize; 3],
    /// Their names.
    pub linear_names: [String; 3],
    /// Chain index of C.
    pub c_index: usize,
    /// Chain positions with everything but the linear axes and C at their place (M fixed).
    pub base: Vec<f64>,
    /// `L`, mm of command per mm of turned tip.
    l: Matrix3<f64>,
    /// `l₀`, mm.
    l0: Vector3<f64>,
    /// C's axis in workpiece coordinates (x, y), mm.
    pub axis: Vector2<f64>,
    /// `σ`: the table turns by `σ·C` in the map (−1 under ISO 841).
    pub sigma: f64,
    /// The circle's centre in workpiece coordinates (x, y), mm.
    pub centre: Vector2<f64>,
    /// `ψ₀`, rad.
    pub psi0: f64,
    /// `w`, rad of θ.
    pub blend: f64,
    /// `ċ = dC/dθ` outside the blend.
    pub rate: f64,
    /// Total time, s.
    pub duration: f64,
    /// Time of the reversal (θ = 180°), s.
    pub reversal: f64,
}

/// The quarter turn `J` about +Z.
fn quarter(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v.y, v.x)
}

fn rot(phi: f64, v: Vector2<f64>) -> Vector2<f64> {
    let (s, c) = phi.sin_cos();
    Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

impl Motion {
    /// The motion of `spec` on `model`. Refuses a machine without a rotary table C, a C travel
    /// that does not hold 0 to the reversal angle, a pose out of the travel, and a feed profile
    /// that does not fit in the circle.
    pub fn new(model: Model, spec: MotionSpec) -> Result<Self> {
        let machine = &model.machine;
        if machine.k() != RotaryAxis::C || machine.kind == MachineKind::HeadHead {
            return Err(Error::field(
                "machine.type",
                format!(
                    "the reversal test needs a rotary table C (the rotary axis nearer the \
                     workpiece, K, turning the table about Z): this machine's type is {} on a \
                     {} machine; choose a type starting with C (CAZ, CBZ, CAY, CBX) on a \
                     table-table or head-table machine",
                    machine.rotary_type.name(),
                    machine.kind.value()
                ),
            ));
        }
        let v_f = spec.feed;
        let length = TAU * spec.radius;
        if v_f * spec.accel_time >= length / 2.0 {
            return Err(Error::field(
                "test.accelTime",
                format!(
                    "the tip would not reach the feed before half the circle: {:.0} ms at {} mm/min \
                     needs a circle longer than {:.1} mm",
                    spec.accel_time * 1e3,
                    v_f * 60.0,
                    2.0 * v_f * spec.accel_time
                ),
            ));
        }
        let blend = v_f * spec.reversal_time / 2.0 / spec.radius;
        let ramp_angle = v_f * spec.accel_time / 2.0 / spec.radius;
        if blend >= PI - ramp_angle {
            return Err(Error::field(
                "test.reversalTime",
                "the reversal of C would take longer than the run at full feed; shorten it",
            ));
        }
        let lay = model.layout;
        let c_index = lay.k;
        let linear: Vec<usize> = (0..model.chain.len())
            .filter(|&i| i != lay.k && i != lay.m)
            .collect();
        let linear: [usize; 3] = linear.try_into().map_err(|_| {
            Error::field("machine", "a five-axis chain needs exactly 3 linear axes")
        })?;
        let names = model.chain.axis_names();
        let linear_names = linear.map(|i| names[i].clone());
        let dir = Vector3::z();
        let start = model.positions(0.0, 0.0);
        let solve = |c: f64, p: Vector3<f64>, prev: &[f64]| -> Result<Vec<f64>> {
            let mut prev = prev.to_vec();
            prev[c_index] = c;
            let s = model
                .inverse(&p, &dir, BranchRule::Nearest, Some(&prev))
                .map_err(|e| {
                    Error::field(
                        "machine",
                        format!(
                            "the tool along C's axis at C = {:.4}°: {}",
                            c.to_degrees(),
                            e.message
                        ),
                    )
                })?;
            if !s.singular {
                return Err(Error::field(
                    "machine",
                    "the tool along C's axis is not at C's pole on this machine",
                ));
            }
            Ok(s.q)
        };
        let q00 = solve(0.0, Vector3::zeros(), &start)?;
        let lin_of = |q: &[f64]| Vector3::new(q[linear[0]], q[linear[1]], q[linear[2]]);
        let at = |c: f64, p: Vector3<f64>| solve(c, p, &q00).map(|q| lin_of(&q));
        let m0 = lin_of(&q00);
        let mut l = Matrix3::zeros();
        for k in 0..3 {
            let mut e = Vector3::zeros();
            e[k] = 1.0;
            l.set_column(k, &(at(0.0, e)? - m0));
        }
        let l_inv = l.try_inverse().ok_or_else(|| {
            Error::field("machine", "the linear axes do not span three directions")
        })?;
        let q90 = at(FRAC_PI_2, Vector3::zeros())?;
        let turned = l_inv * (at(FRAC_PI_2, Vector3::x())? - q90);
        let sigma = turned.y.signum();
        if (turned.y.abs() - 1.0).abs() > 1e-9 || turned.x.abs() > 1e-9 {
            return Err(Error::field(
                "machine",
                "C does not turn the table about an axis parallel to Z on this machine",
            ));
        }
        // (I − R)·a = L⁻¹(q(90°, 0) − q(0, 0)), R the quarter turn by σ·90°.
        let b = l_inv * (q90 - m0);
        let i_minus_r = Matrix2::new(1.0, sigma, -sigma, 1.0);
        let axis = i_minus_r
            .try_inverse()
            .map(|m| m * Vector2::new(b.x, b.y))
            .ok_or_else(|| Error::field("machine", "C's axis cannot be located"))?;
        let l0 = m0 + l * Vector3::new(axis.x, axis.y, 0.0);
        // ψ₀: the radius at the reversal at 45° to the machine axes.
        let psi_rev_machine = FRAC_PI_4 + FRAC_PI_2; // (−1, 1)/√2 in the turned frame
        let psi_rev = psi_rev_machine - sigma * spec.reversal_angle;
        let psi0 = (psi_rev - PI).rem_euclid(TAU);
        let e_rev = Vector2::new(psi_rev.cos(), psi_rev.sin());
        let centre = axis - sigma * spec.offset * quarter(e_rev);
        let rate = spec.reversal_angle / (PI - blend + 2.0 * blend / PI);
        let motion = Motion {
            spec,
            linear,
            linear_names,
            c_index,
            base: q00.clone(),
            l,
            l0,
            axis,
            sigma,
            centre,
            psi0,
            blend,
            rate,
            duration: length / v_f + spec.accel_time,
            reversal: PI * spec.radius / v_f + spec.accel_time / 2.0,
            model: model.clone(),
        };
        // The closed form against the machine's inverse kinematics, and the travel of C.
        for (c, th) in [
            (0.3, 0.4),
            (1.1, 2.0),
            (spec.reversal_angle, PI),
            (0.7, 5.5),
        ] {
            let c = c.min(spec.reversal_angle);
            let p = motion.tip(th);
            let want = at(c, p)?;
            let got = motion.linear_at(c, th).map(|j| j.x);
            for k in 0..3 {
                if (want[k] - got[k]).abs() > 1e-9 * (1.0 + want[k].abs()) {
                    return Err(Error::field(
                        "machine",
                        "the linear axes do not follow C as a turned table on this machine",
                    ));
                }
            }
        }
        Ok(motion)
    }

    /// The programmed tip at trace angle `theta`, workpiece coordinates, mm (z = 0: the table
    /// surface).
    pub fn tip(&self, theta: f64) -> Vector3<f64> {
        let psi = theta + self.psi0;
        let p = self.centre + self.spec.radius * Vector2::new(psi.cos(), psi.sin());
        Vector3::new(p.x, p.y, 0.0)
    }

    /// Linear commands at C = `c` for the programmed tip at `theta` (positions only).
    fn linear_at(&self, c: f64, theta: f64) -> [Jet; 3] {
        let p = self.tip(theta);
        let d = rot(self.sigma * c, Vector2::new(p.x, p.y) - self.axis);
        let q = self.l * Vector3::new(d.x, d.y, p.z) + self.l0;
        [0, 1, 2].map(|k| Jet {
            x: q[k],
            ..Jet::default()
        })
    }

    /// Path length along the circle `s` and its derivatives at time `t` (mm, mm/s, mm/s²).
    pub fn path(&self, t: f64) -> Jet {
        let (f, ta) = (self.spec.feed, self.spec.accel_time);
        let total = TAU * self.spec.radius;
        let ramp = |t: f64| {
            let w = PI * t / ta;
            Jet {
                x: f * (t / 2.0 - ta / (2.0 * PI) * w.sin()),
                v: f / 2.0 * (1.0 - w.cos()),
                a: f * PI / (2.0 * ta) * w.sin(),
            }
        };
        if t <= 0.0 {
            Jet::default()
        } else if t < ta {
            ramp(t)
        } else if t <= self.duration - ta {
            Jet {
                x: f * (t - ta / 2.0),
                v: f,
                a: 0.0,
            }
        } else if t < self.duration {
            let j = ramp(self.duration - t);
            Jet {
                x: total - j.x,
                v: j.v,
                a: -j.a,
            }
        } else {
            Jet {
                x: total,
                ..Jet::default()
            }
        }
    }

    /// C against θ: `(C, dC/dθ, d²C/dθ²)` (module docs).
    pub fn c_of(&self, theta: f64) -> (f64, f64, f64) {
        let (w, k) = (self.blend, self.rate);
        let u = theta - PI;
        if u < -w {
            (k * theta, k, 0.0)
        } else if u > w {
            (k * (TAU - theta), -k, 0.0)
        } else {
            let z = PI * u / (2.0 * w);
            (
                k * (PI - w) + k * 2.0 * w / PI * z.cos(),
                -k * z.sin(),
                -k * PI / (2.0 * w) * z.cos(),
            )
        }
    }

    /// Every command at time `t`.
    pub fn commands(&self, t: f64) -> Commands {
        let s = self.path(t);
        let r = self.spec.radius;
        let (th, thd, thdd) = (s.x / r, s.v / r, s.a / r);
        let (c, c1, c2) = self.c_of(th);
        let c = Jet {
            x: c,
            v: c1 * thd,
            a: c2 * thd * thd + c1 * thdd,
        };
        let psi = th + self.psi0;
        let (sn, cs) = psi.sin_cos();
        let e = Vector2::new(cs, sn);
        let et = Vector2::new(-sn, cs);
        let p = self.centre + r * e;
        let pd = r * thd * et;
        let pdd = r * thdd * et - r * thd * thd * e;
        let sg = self.sigma;
        let (phi, phid, phidd) = (sg * c.x, sg * c.v, sg * c.a);
        let d = rot(phi, p - self.axis);
        let rpd = rot(phi, pd);
        let u = d;
        let ud = rpd + phid * quarter(d);
        let udd = rot(phi, pdd) + 2.0 * phid * quarter(rpd) + phidd * quarter(d) - phid * phid * d;
        let q = self.l * Vector3::new(u.x, u.y, 0.0) + self.l0;
        let qd = self.l * Vector3::new(ud.x, ud.y, 0.0);
        let qdd = self.l * Vector3::new(udd.x, udd.y, 0.0);
        Commands {
            theta: th,
            linear: [0, 1, 2].map(|k| Jet {
                x: q[k],
                v: qd[k],
                a: qdd[k],
            }),
            c,
        }
    }

    /// The tool tip in workpiece coordinates for the axis positions `linear` (mm) and `c`
    /// (rad), through the machine's chain with its errors (eq 1 on any machine).
    pub fn actual_tip(&self, linear: [f64; 3], c: f64) -> Result<Vector3<f64>> {
        let mut q = self.base.clone();
        for k in 0..3 {
            q[self.linear[k]] = linear[k];
        }
        q[self.c_index] = c;
        Ok(self
            .model
            .chain
            .tool_pose(&q, true, &crate::chain::Setup::None)?
            .tip)
    }

    /// Trace angle (rad, continuous from the last one) and radial deviation (mm) of a tip.
    pub fn trace_point(&self, tip: &Vector3<f64>) -> (f64, f64) {
        let d = Vector2::new(tip.x, tip.y) - self.centre;
        (
            (d.y.atan2(d.x) - self.psi0).rem_euclid(TAU),
            d.norm() - self.spec.radius,
        )
    }
}
