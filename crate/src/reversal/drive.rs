//! The feed drives (Nishiguchi et al. Section 4.1, Fig 7; the single-inertia model of their
//! refs 18, 19) and the friction of eq 2, integrated with a fixed step.
//!
//! # One axis (SI units: m or rad, s, kg or kg·m², N or N·m)
//! A position loop (P, gain `K_p`, 1/s) gives the velocity loop its reference; the velocity loop
//! (PI: `K_v`, `K_i`) gives the torque; one inertia `J` with viscous damping `D` and friction `f`
//! moves:
//!
//! ```text
//! v_ref = K_p·(x_r − x) + k_fv·v_r
//! τ     = sat_τmax( K_v·(v_ref − v) + K_i·∫(v_ref − v)dt + k_ft·(J·a_r + D·v_r) )
//! J·ẍ   = τ − D·ẋ − f
//! ```
//!
//! `x_r, v_r, a_r` are the command and its derivatives; `k_fv = 1` with velocity feed-forward,
//! `k_ft = 1` with torque (acceleration) feed-forward as well. The integral does not wind up
//! while the torque is at its limit and the error would push it further. Without feed-forward
//! and friction the loop is
//! `x/x_r = K_p(K_v s + K_i) / (J s³ + (D + K_v) s² + (K_i + K_p K_v) s + K_p K_i)`
//! ([`Drive::response`]); a circle at angular speed ω comes out with its radius times `|G(jω)|`.
//!
//! The state integrated is the *following error* `e = x_r − x`, its rate and the integral; with
//! both feed-forwards and no friction its equations have no input at all, so from rest the
//! error stays exactly zero (the ideal drive).
//!
//! # Friction (eq 2)
//! `f = f_c·(2·tanh(a·|x′|) − 1)·sgn(ẋ′)`, `x′` the travel since the last change of direction,
//! `f_c` the Coulomb friction, `a` how steeply it builds up (1/rad or 1/m): a nonlinear spring
//! that takes `f` from `+f_c` to `−f_c` over a travel of a few `1/a` after each reversal
//! (`f = 0` at `a·|x′| = atanh ½ ≈ 0.549`). Before the first motion the spring is taken as
//! unloaded (`f = 0` at rest, the axis having come to rest in the direction of its first
//! motion). The direction memory changes where the velocity changes sign: the step in which that
//! happens is split at the crossing (found by linear interpolation of the velocity), so the
//! friction's switch never falls inside an integration step.
//!
//! # Integration
//! Classical fourth-order Runge–Kutta with a fixed step `h` (default 0.2 ms). The stiffest terms
//! are the velocity loop (`(D + K_v)/J`: 254 1/s for C's defaults, 380 1/s for the linear axes')
//! and the friction spring's stiffness `2·f_c·a/J` (natural frequency `√(2 f_c a/J)` = 71 rad/s
//! for C's defaults): `h·λ` stays below 0.1, far inside RK4's stability region (2.78), and the
//! switch is handled by splitting. [`crate::reversal::simulate`] checks the step by halving it.

/// A drive's parameters, SI (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drive {
    /// Inertia `J`, kg or kg·m².
    pub inertia: f64,
    /// Position-loop gain `K_p`, 1/s.
    pub kp: f64,
    /// Velocity-loop gain `K_v`, N·s/m or N·m·s/rad.
    pub kv: f64,
    /// Velocity-loop integral gain `K_i`, N/m or N·m/rad.
    pub ki: f64,
    /// Viscous damping `D`, N·s/m or N·m·s/rad.
    pub damping: f64,
    /// Torque or force limit, N·m or N.
    pub limit: f64,
    /// Coulomb friction `f_c`, N·m or N (0: none).
    pub fc: f64,
    /// Friction slope `a`, 1/rad or 1/m.
    pub slope: f64,
    /// Velocity feed-forward.
    pub ff_velocity: bool,
    /// Torque (acceleration) feed-forward.
    pub ff_torque: bool,
}

impl Drive {
    /// The closed-loop gain `|x/x_r|` at angular frequency `omega` (rad/s) without
    /// feed-forward and friction (module docs).
    pub fn response(&self, omega: f64) -> f64 {
        use nalgebra::Complex;
        let s = Complex::new(0.0, omega);
        let num = self.kp * (self.kv * s + self.ki);
        let den = self.inertia * s * s * s
            + (self.damping + self.kv) * s * s
            + (self.ki + self.kp * self.kv) * s
            + self.kp * self.ki;
        (num / den).norm()
    }

    /// Friction at travel `travel` (≥ 0) since the reversal, moving in direction `dir` (±1).
    pub fn friction(&self, travel: f64, dir: f64) -> f64 {
        if self.fc == 0.0 {
            0.0
        } else {
            self.fc * (2.0 * (self.slope * travel).tanh() - 1.0) * dir
        }
    }
}

/// The state of one axis: following error, its rate, the velocity-loop integral and the
/// friction's direction memory.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisState {
    /// `e = x_r − x`.
    pub e: f64,
    /// `ė = v_r − v`.
    pub ev: f64,
    /// `∫(v_ref − v)dt`.
    pub z: f64,
    /// Position where the direction last changed.
    pub x_rev: f64,
    /// Direction since then, ±1.
    pub dir: f64,
}

/// Command of an axis at one instant: position, velocity, acceleration (SI).
pub type Reference = super::motion::Jet;

/// Derivative of `(e, ev, z)` and the friction and torque, at reference `r`.
fn rates(d: &Drive, s: &AxisState, e: [f64; 3], r: &Reference) -> ([f64; 3], f64, f64) {
    let x = r.x - e[0];
    let v = r.v - e[1];
    let fv = if d.ff_velocity { 1.0 } else { 0.0 };
    let eps = d.kp * e[0] + e[1] - (1.0 - fv) * r.v;
    let ff = if d.ff_torque {
        d.inertia * r.a + d.damping * r.v
    } else {
        0.0
    };
    let raw = d.kv * eps + d.ki * e[2] + ff;
    let tau = raw.clamp(-d.limit, d.limit);
    let wind = if tau != raw && eps * raw > 0.0 {
        0.0
    } else {
        eps
    };
    let f = d.friction((x - s.x_rev).abs(), s.dir);
    let acc = (tau - d.damping * v - f) / d.inertia;
    ([e[1], r.a - acc, wind], f, tau)
}

/// One RK4 step of length `h` from `s` with references at the start, middle and end.
fn rk4(d: &Drive, s: &AxisState, h: f64, r: [&Reference; 3]) -> AxisState {
    let y = [s.e, s.ev, s.z];
    let add =
        |y: [f64; 3], k: [f64; 3], c: f64| [y[0] + c * k[0], y[1] + c * k[1], y[2] + c * k[2]];
    let (k1, _, _) = rates(d, s, y, r[0]);
    let (k2, _, _) = rates(d, s, add(y, k1, h / 2.0), r[1]);
    let (k3, _, _) = rates(d, s, add(y, k2, h / 2.0), r[1]);
    let (k4, _, _) = rates(d, s, add(y, k3, h), r[2]);
    let n: Vec<f64> = (0..3)
        .map(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
        .collect();
    AxisState {
        e: n[0],
        ev: n[1],
        z: n[2],
        ..*s
    }
}

impl AxisState {
    /// At rest on the command `r0`, the friction spring unloaded for a first motion in
    /// direction `dir`.
    pub fn at_rest(d: &Drive, r0: &Reference, dir: f64) -> Self {
        let dir = if dir < 0.0 { -1.0 } else { 1.0 };
        AxisState {
            e: 0.0,
            ev: 0.0,
            z: 0.0,
            x_rev: r0.x - dir * 0.5f64.atanh() / d.slope.max(f64::MIN_POSITIVE),
            dir,
        }
    }

    /// Friction and torque now, at reference `r`.
    pub fn forces(&self, d: &Drive, r: &Reference) -> (f64, f64) {
        let (_, f, tau) = rates(d, self, [self.e, self.ev, self.z], r);
        (f, tau)
    }

    /// Advances by `h` from `t0`: `reference(t)` gives the command at any time in
    /// `[t0, t0 + h]`; `at` holds it at `t0`, `t0 + h/2` and `t0 + h`. A change of direction
    /// inside the step splits it there (module docs). Returns the number of direction changes.
    pub fn step(
        &mut self,
        d: &Drive,
        (t0, h): (f64, f64),
        at: [&Reference; 3],
        reference: &dyn Fn(f64) -> Reference,
    ) -> usize {
        let [start, mid, end] = at;
        let next = rk4(d, self, h, [start, mid, end]);
        let v0 = start.v - self.ev;
        let v1 = end.v - next.ev;
        if d.fc == 0.0 || v1 * self.dir >= 0.0 {
            *self = next;
            return 0;
        }
        // The velocity changed sign: split at the crossing.
        let frac = if v0 * self.dir > 0.0 {
            (v0 / (v0 - v1)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let h1 = frac * h;
        let mut s = *self;
        if h1 > 0.0 {
            let m = reference(t0 + h1 / 2.0);
            let e = reference(t0 + h1);
            s = rk4(d, &s, h1, [start, &m, &e]);
        }
        let at = reference(t0 + h1);
        s.x_rev = at.x - s.e;
        s.dir = -s.dir;
        let h2 = h - h1;
        if h2 > 0.0 {
            let m = reference(t0 + h1 + h2 / 2.0);
            s = rk4(d, &s, h2, [&at, &m, end]);
        }
        *self = s;
        1
    }
}
