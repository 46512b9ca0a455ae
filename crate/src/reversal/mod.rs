//! # Rotary-axis reversal (Nishiguchi, Hasegawa, Sato & Shirase 2017)
//!
//! C reciprocates from 0° to its reversal angle (90°) and back while X and Y keep the tool on a
//! circle in *table* coordinates, so that X and Y do not reverse when C does and C's own
//! behaviour at its direction change is copied onto the circle ([`motion`]). Every axis is a
//! single-inertia feed drive with P position and PI velocity loops; C has the friction of eq 2,
//! a nonlinear spring near the direction change ([`drive`]). The result is what a ball bar of
//! length `R` between the spindle and a socket `r` from C's axis records: the actual tip in
//! table coordinates (eq 1, through the machine's chain), its radial deviation against the
//! trace angle, with and without friction, and the dent the friction makes at the reversal
//! (180°). [`fit`] reads a measured trace and fits `f_c`, `a` and C's position-loop gain.
//!
//! Units: mm, degrees at the edge (the reader converts degrees to radians); drive parameters in
//! SI as their labels say (kg, kg·m², N, N·m, 1/s, Hz, ms); time in s.
//!
//! # Defaults (the paper gives no drive parameters)
//! Values typical of a mid-size five-axis machining centre, from the ranges servo makers and
//! the feed-drive literature give for such machines (position-loop gains 20–50 1/s, velocity-loop
//! bandwidths of some tens of Hz to 100 Hz, integral times of some ms): linear axes 400 kg
//! moved, `K_p` 30 1/s, velocity loop 60 Hz with a 10 ms integral time, 1 kN·s/m damping, 20 kN
//! limit, no friction; C a direct-drive table of 2 kg·m² (table and workpiece), `K_p` 30 1/s,
//! velocity loop 40 Hz, 15 ms, 5 N·m·s/rad, 500 N·m (peak), 250 N·m rated (a torque motor gives about
//! half its peak torque continuously), `f_c` = 10 N·m and `a` = 500 1/rad (the
//! friction has turned half way 0.063° after a reversal: a few milliseconds at the test's C
//! speeds, comparable to the velocity loop, as the paper's Fig 8 spring suggests). The ball bar is 50 mm long: with `r` = 50 mm X then stops at the reversal without
//! changing direction, as the paper reports (Section 5.2). All are inputs.

pub mod drive;
pub mod fit;
pub mod measure;
pub mod motion;

use crate::edge::{ApiInput, Checked};
use crate::error::{Error, Result};
use crate::machine::Machine;
use crate::schema::{self, DefaultValue, Kind, Quantity};
use drive::{AxisState, Drive, Reference};
use motion::{Motion, MotionSpec};
use serde::Serialize;
use serde_json::Value;
use std::f64::consts::{PI, TAU};

crate::choices! {
    /// Which feed-forwards the drives have.
    pub enum FeedForward {
        /// None: the position loop alone.
        None = "none" {
            label: "None",
            help: "The position loop alone: every axis lags its command (a circle comes out smaller).",
        },
        /// Velocity feed-forward.
        Velocity = "velocity" {
            label: "Velocity",
            help: "The command's velocity is added to the velocity loop's reference: no steady lag.",
        },
        /// Velocity and torque (acceleration) feed-forward.
        Full = "full" {
            label: "Velocity and torque",
            help: "Velocity and the torque the command's acceleration needs: an ideal drive follows exactly.",
        },
    }
}

crate::inputs! {
    /// The test motion (Table 1).
    pub struct ReversalTest {
        /// Circle radius, mm.
        pub radius: f64 = "radius" optional {
            label: "Ball-bar length / cut radius R",
            help: "Radius of the circle the tool runs round in table coordinates (a 50 mm ball bar; the cylinder's radius in the cutting test).",
            kind: schema::positive(Quantity::Length, 1000.0),
            default: DefaultValue::Num(50.0),
            group: "Test",
        },
        /// Centre from C's axis, mm.
        pub offset: f64 = "offset" optional {
            label: "Circle centre from the C axis r",
            help: "How far the ball-bar's table socket (or the workpiece's centre) sits from the C axis; the paper: 25 and 50 mm. At most R, or X or Y reverses with C.",
            kind: schema::number(Quantity::Length, 0.0, 1000.0),
            default: DefaultValue::Num(25.0),
            group: "Test",
        },
        /// Feed, mm/min.
        pub feed: f64 = "feed" optional {
            label: "Feed F (mm/min)",
            help: "Speed of the tool along the circle; the paper: 1000, 2000 and 3000 mm/min.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 1.0, max: 60000.0, exclusive_min: false },
            default: DefaultValue::Num(1000.0),
            group: "Test",
        },
        /// C at the reversal.
        pub reversal_angle: f64 = "reversalAngle" optional {
            label: "C at the reversal",
            help: "C turns from 0 to this angle and back while the tool goes once round (the paper: 90°).",
            kind: schema::Kind::Number { quantity: Quantity::Angle, min: 1.0, max: 180.0, exclusive_min: false },
            default: DefaultValue::Num(90.0),
            group: "Test",
        },
        /// Acceleration time, ms.
        pub accel_time: f64 = "accelTime" optional {
            label: "Acceleration time (ms)",
            help: "Time the tool takes from rest to the feed at the start (and back to rest at the end), with a smooth profile.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 1.0, max: 5000.0, exclusive_min: false },
            default: DefaultValue::Num(50.0),
            group: "Test",
        },
        /// Reversal time of C, ms.
        pub reversal_time: f64 = "reversalTime" optional {
            label: "C reversal time (ms)",
            help: "Time the control takes to turn C's velocity round at the reversal (its acceleration limit).",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.1, max: 5000.0, exclusive_min: false },
            default: DefaultValue::Num(20.0),
            group: "Test",
        },
    }
}

crate::inputs! {
    /// The linear axes' drives (all three alike), SI.
    pub struct LinearDrive {
        /// Mass, kg.
        pub mass: f64 = "mass" optional {
            label: "Moved mass (kg)",
            help: "Mass each linear axis moves (slide, and table or head).",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.1, max: 100000.0, exclusive_min: false },
            default: DefaultValue::Num(400.0),
            group: "Linear axes (X, Y, Z)",
        },
        /// Position-loop gain, 1/s.
        pub position_gain: f64 = "positionGain" optional {
            label: "Position-loop gain (1/s)",
            help: "Following error = velocity / gain without feed-forward (30 1/s is common).",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.1, max: 1000.0, exclusive_min: false },
            default: DefaultValue::Num(30.0),
            group: "Linear axes (X, Y, Z)",
        },
        /// Velocity-loop bandwidth, Hz.
        pub velocity_bandwidth: f64 = "velocityBandwidth" optional {
            label: "Velocity-loop bandwidth (Hz)",
            help: "Sets the velocity-loop gain: K_v = mass · 2π · bandwidth.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.1, max: 2000.0, exclusive_min: false },
            default: DefaultValue::Num(60.0),
            group: "Linear axes (X, Y, Z)",
        },
        /// Integral time, ms.
        pub integral_time: f64 = "integralTime" optional {
            label: "Velocity-loop integral time (ms)",
            help: "K_i = K_v / integral time.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.1, max: 100000.0, exclusive_min: false },
            default: DefaultValue::Num(10.0),
            group: "Linear axes (X, Y, Z)",
        },
        /// Viscous damping, N·s/m.
        pub damping: f64 = "damping" optional {
            label: "Viscous damping (N·s/m)",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.0, max: 1e8, exclusive_min: false },
            default: DefaultValue::Num(1000.0),
            group: "Linear axes (X, Y, Z)",
        },
        /// Force limit, N.
        pub force_limit: f64 = "forceLimit" optional {
            label: "Force limit (N)",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 1.0, max: 1e8, exclusive_min: false },
            default: DefaultValue::Num(20000.0),
            group: "Linear axes (X, Y, Z)",
        },
        /// Coulomb friction, N.
        pub friction: f64 = "friction" optional {
            label: "Coulomb friction (N)",
            help: "0: none. Built up as eq 2 with the slope below.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.0, max: 1e6, exclusive_min: false },
            default: DefaultValue::Num(0.0),
            group: "Linear axes (X, Y, Z)",
        },
        /// Friction slope, 1/mm.
        pub friction_slope: f64 = "frictionSlope" optional {
            label: "Friction slope a (1/mm)",
            help: "How fast the friction turns after a reversal: half way at 0.55/a.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.001, max: 1e6, exclusive_min: false },
            default: DefaultValue::Num(100.0),
            group: "Linear axes (X, Y, Z)",
        },
    }
}

crate::inputs! {
    /// The C table's drive and friction, SI.
    pub struct RotaryDrive {
        /// Inertia, kg·m².
        pub inertia: f64 = "inertia" optional {
            label: "Inertia (kg·m²)",
            help: "The table, fixture and workpiece about the C axis.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.0001, max: 100000.0, exclusive_min: false },
            default: DefaultValue::Num(2.0),
            group: "C axis",
        },
        /// Position-loop gain, 1/s.
        pub position_gain: f64 = "positionGain" optional {
            label: "Position-loop gain (1/s)",
            help: "Following error = angular velocity / gain without feed-forward.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.1, max: 1000.0, exclusive_min: false },
            default: DefaultValue::Num(30.0),
            group: "C axis",
        },
        /// Velocity-loop bandwidth, Hz.
        pub velocity_bandwidth: f64 = "velocityBandwidth" optional {
            label: "Velocity-loop bandwidth (Hz)",
            help: "Sets the velocity-loop gain: K_v = inertia · 2π · bandwidth.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.1, max: 2000.0, exclusive_min: false },
            default: DefaultValue::Num(40.0),
            group: "C axis",
        },
        /// Integral time, ms.
        pub integral_time: f64 = "integralTime" optional {
            label: "Velocity-loop integral time (ms)",
            help: "K_i = K_v / integral time.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.1, max: 100000.0, exclusive_min: false },
            default: DefaultValue::Num(15.0),
            group: "C axis",
        },
        /// Viscous damping, N·m·s/rad.
        pub damping: f64 = "damping" optional {
            label: "Viscous damping (N·m·s/rad)",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.0, max: 1e6, exclusive_min: false },
            default: DefaultValue::Num(5.0),
            group: "C axis",
        },
        /// Torque limit, N·m.
        pub torque_limit: f64 = "torqueLimit" optional {
            label: "Torque limit (N·m)",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.01, max: 1e7, exclusive_min: false },
            default: DefaultValue::Num(500.0),
            group: "C axis",
        },
        /// Rated torque, N·m.
        pub rated_torque: f64 = "ratedTorque" optional {
            label: "Rated torque (N·m)",
            help: "The C drive's rated (continuous) torque, from its name plate: the fitted friction is also given as a share of it, the unit a drive takes its friction compensation in. At most the torque limit.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.01, max: 1e7, exclusive_min: false },
            default: DefaultValue::Num(250.0),
            group: "C axis",
        },
        /// Coulomb friction f_c, N·m.
        pub friction: f64 = "friction" optional {
            label: "Coulomb friction torque (N·m)",
            help: "Eq 2's f_c: the friction torque far from a reversal. 0: no friction.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.0, max: 1e5, exclusive_min: false },
            default: DefaultValue::Num(10.0),
            group: "C axis",
        },
        /// Friction slope a, 1/rad.
        pub friction_slope: f64 = "frictionSlope" optional {
            label: "Friction slope a (1/rad)",
            help: "Eq 2's a: after a reversal the friction has turned half way at 0.55/a rad (500 1/rad: 0.063°).",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.01, max: 1e8, exclusive_min: false },
            default: DefaultValue::Num(500.0),
            group: "C axis",
        },
    }
}

crate::inputs! {
    /// Everything one simulation needs.
    pub struct ReversalCase {
        /// The machine (it needs a C table).
        pub machine: Machine = "machine" optional {
            label: "Machine", kind: Kind::Object(Machine::FIELDS), default: DefaultValue::Empty,
        },
        /// The motion.
        pub test: ReversalTest = "test" optional {
            label: "Test", kind: Kind::Object(ReversalTest::FIELDS), default: DefaultValue::Empty,
        },
        /// The linear drives.
        pub linear: LinearDrive = "linear" optional {
            label: "Linear axes", kind: Kind::Object(LinearDrive::FIELDS), default: DefaultValue::Empty,
        },
        /// C's drive.
        pub c: RotaryDrive = "c" optional {
            label: "C axis", kind: Kind::Object(RotaryDrive::FIELDS), default: DefaultValue::Empty,
        },
        /// Feed-forward of every drive.
        pub feed_forward: FeedForward = "feedForward" optional {
            label: "Feed-forward (every axis)",
            help: "What the control adds to the position loop; the paper's figures look like none.",
            kind: Kind::Choice(FeedForward::CHOICES),
            default: DefaultValue::Str("none"),
            group: "Drives",
        },
        /// Integration step, ms.
        pub step: f64 = "step" optional {
            label: "Integration step (ms)",
            help: "Fixed step of the simulation; the result says how much halving it changes the trace.",
            kind: schema::Kind::Number { quantity: Quantity::Number, min: 0.005, max: 2.0, exclusive_min: false },
            default: DefaultValue::Num(0.2),
            group: "Drives",
        },
        /// Output points.
        pub samples: usize = "samples" optional {
            label: "Points of the trace", kind: Kind::Count { min: 100, max: 200_000 },
            default: DefaultValue::Num(3600.0), shown: false,
        },
    }
}

crate::inputs! {
    /// What a simulation adds to the case.
    pub struct ReversalRunInput {
        /// Run again at half the step and report the difference.
        pub check_step: bool = "checkStep" optional {
            label: "Check the step", help: "Runs again with half the step and reports how much the trace changes.",
            kind: Kind::Flag, default: DefaultValue::Flag(false), shown: false,
        },
    }
}

crate::inputs! {
    /// What a fit adds to the case.
    pub struct ReversalFitInput {
        /// The measured trace.
        pub csv: String = "csv" {
            label: "Measured trace (CSV)",
            help: "Header angle_deg,deviation_mm (or deviation_um): trace angle with C's reversal at 180°, radial deviation + outwards.",
            kind: Kind::Text { max_len: 5_000_000 },
            group: "Fit",
        },
    }
}

impl ReversalCase {
    /// Reads a case and an export's own inputs from one object (the keys of `B` go to `B`).
    pub fn read_with<B: Checked>(value: &Value) -> Result<(Self, B)> {
        <(Self, B) as ApiInput>::read(value)
    }

    /// Reads a case (and checks the machine).
    pub fn read(value: &Value) -> Result<Self> {
        <Self as ApiInput>::read(value)
    }
}

impl Checked for ReversalCase {
    /// The checks across fields: the machine, and C's rated torque at most its torque limit.
    fn check(&self) -> Result<()> {
        self.machine.validate("machine")?;
        if self.c.rated_torque > self.c.torque_limit {
            return Err(Error::field(
                "c.ratedTorque",
                format!(
                    "{} N·m is above the torque limit ({} N·m): a drive's rated (continuous) torque is at most its peak",
                    self.c.rated_torque, self.c.torque_limit
                ),
            ));
        }
        Ok(())
    }
}

impl Checked for ReversalRunInput {}
impl Checked for ReversalFitInput {}

impl ReversalCase {
    /// The same case with C's friction `f_c` set to `fc`.
    pub fn with_c_friction(&self, fc: f64) -> Self {
        let mut c = self.clone();
        c.c.friction = fc;
        c
    }

    /// The programmed motion, engine units.
    pub fn motion(&self) -> Result<Motion> {
        let t = &self.test;
        Motion::new(
            self.machine.build()?,
            MotionSpec {
                radius: t.radius,
                offset: t.offset,
                feed: t.feed / 60.0,
                reversal_angle: t.reversal_angle,
                accel_time: t.accel_time * 1e-3,
                reversal_time: t.reversal_time * 1e-3,
            },
        )
    }

    /// The drives: the three linear axes (m) and C (rad).
    pub fn drives(&self) -> ([Drive; 3], Drive) {
        let (fv, ft) = match self.feed_forward {
            FeedForward::None => (false, false),
            FeedForward::Velocity => (true, false),
            FeedForward::Full => (true, true),
        };
        let l = &self.linear;
        let kv = l.mass * TAU * l.velocity_bandwidth;
        let lin = Drive {
            inertia: l.mass,
            kp: l.position_gain,
            kv,
            ki: kv / (l.integral_time * 1e-3),
            damping: l.damping,
            limit: l.force_limit,
            fc: l.friction,
            slope: l.friction_slope * 1e3,
            ff_velocity: fv,
            ff_torque: ft,
        };
        let c = &self.c;
        let kv = c.inertia * TAU * c.velocity_bandwidth;
        let rot = Drive {
            inertia: c.inertia,
            kp: c.position_gain,
            kv,
            ki: kv / (c.integral_time * 1e-3),
            damping: c.damping,
            limit: c.torque_limit,
            fc: c.friction,
            slope: c.friction_slope,
            ff_velocity: fv,
            ff_torque: ft,
        };
        ([lin; 3], rot)
    }
}

/// One linear axis along the run (at the trace's samples).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct LinearTrace {
    /// Its name ("X", …).
    pub name: String,
    /// Command, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub command: Vec<f64>,
    /// Actual velocity, mm/s.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub velocity: Vec<f64>,
    /// Following error (command − actual), mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub error: Vec<f64>,
}

/// Whether a linear axis changes direction near the reversal of C.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct DirectionCheck {
    /// The axis.
    pub name: String,
    /// Commanded velocity just before C's reversal turns it round, mm/s.
    pub before: f64,
    /// Just after, mm/s.
    pub after: f64,
    /// Smallest |commanded velocity| within ±5° of trace angle around the reversal, mm/s.
    pub min_speed: f64,
    /// The commanded velocity changes sign there (beyond 0.1 % of the feed).
    pub reverses: bool,
    /// It comes to rest there without changing direction (below 0.1 % of the feed).
    pub stops: bool,
    /// The simulated velocity changes sign there (beyond 0.1 % of the feed).
    pub actual_reverses: bool,
}

/// One simulated run: the ball-bar trace and the axes (series at the same instants).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct Trace {
    /// Time, s.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub time: Vec<f64>,
    /// Commanded trace angle θ, degrees (radians in Rust; C reverses at 180°).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub theta: Vec<f64>,
    /// Actual trace angle, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub angle: Vec<f64>,
    /// Radial deviation |tip − centre| − R, mm (+ outwards).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub deviation: Vec<f64>,
    /// Actual tip in table (workpiece) coordinates, mm (eq 1).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub x: Vec<f64>,
    /// y, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub y: Vec<f64>,
    /// C command, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub c_command: Vec<f64>,
    /// C actual, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub c_actual: Vec<f64>,
    /// C velocity, degrees/s (rad/s in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub c_velocity: Vec<f64>,
    /// C following error (command − actual), degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub c_error: Vec<f64>,
    /// C friction torque, N·m (eq 2; + resists positive motion).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub c_friction: Vec<f64>,
    /// C motor torque, N·m.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub c_torque: Vec<f64>,
    /// The linear axes: X, Y, Z.
    pub linear: Vec<LinearTrace>,
    /// Time of C's reversal, s.
    pub reversal_time: f64,
    /// Index of the sample nearest the reversal.
    pub reversal_index: usize,
    /// Integration steps taken.
    pub steps: usize,
    /// Step, s.
    #[serde(skip)]
    pub step: f64,
    /// Direction changes the friction model saw (all axes).
    #[serde(skip)]
    pub direction_changes: usize,
}

/// Settling time simulated after the command has stopped, s.
const SETTLE: f64 = 0.1;

/// Most integration steps of one simulation (about 0.7 s of wasm): a slower feed or a longer
/// circle would keep the page's worker busy for minutes.
pub const MAX_STEPS: usize = 2_000_000;

/// Simulates `case` with integration step `h` (s). More than [`MAX_STEPS`] steps is refused.
pub fn simulate_with_step(case: &ReversalCase, motion: &Motion, h: f64) -> Result<Trace> {
    let exact = (motion.duration + SETTLE) / h;
    // Also refuses a NaN count.
    if exact.is_nan() || exact > MAX_STEPS as f64 {
        return Err(Error::field(
            "test.feed",
            format!(
                "the test lasts {:.0} s: {:.0} integration steps of {} ms, more than {MAX_STEPS}; raise the feed, shorten the circle or lengthen the step",
                motion.duration + SETTLE,
                exact,
                h * 1e3
            ),
        ));
    }
    let steps = exact.ceil() as usize;
    run(case, motion, h, steps.div_ceil(case.samples.max(1)).max(1))
}

/// Simulates with step `h`, recording every `stride` steps.
fn run(case: &ReversalCase, motion: &Motion, h: f64, stride: usize) -> Result<Trace> {
    let (lin, cd) = case.drives();
    let end = motion.duration + SETTLE;
    let steps = (end / h).ceil() as usize;
    let refs = |t: f64| -> [Reference; 4] {
        let c = motion.commands(t);
        let m = |j: motion::Jet| Reference {
            x: j.x * 1e-3,
            v: j.v * 1e-3,
            a: j.a * 1e-3,
        };
        [m(c.linear[0]), m(c.linear[1]), m(c.linear[2]), c.c]
    };
    let drives = [lin[0], lin[1], lin[2], cd];
    let first = refs(0.0);
    let probe = refs(motion.spec.accel_time / 2.0);
    let mut state: [AxisState; 4] =
        std::array::from_fn(|i| AxisState::at_rest(&drives[i], &first[i], probe[i].v));
    // An axis whose command stands still (Z) stays exactly on it: nothing to integrate.
    let still: [bool; 4] = std::array::from_fn(|k| {
        k < 3 && {
            let c = motion.commands(motion.duration / 3.0).linear[k];
            let d = motion.commands(motion.duration * 0.7).linear[k];
            c.v == 0.0
                && d.v == 0.0
                && c.a == 0.0
                && d.a == 0.0
                && first[k].x == refs(motion.reversal)[k].x
        }
    });
    let n_out = steps / stride + 1;
    let mut tr = Trace {
        time: Vec::with_capacity(n_out),
        theta: Vec::with_capacity(n_out),
        angle: Vec::with_capacity(n_out),
        deviation: Vec::with_capacity(n_out),
        x: Vec::with_capacity(n_out),
        y: Vec::with_capacity(n_out),
        c_command: Vec::with_capacity(n_out),
        c_actual: Vec::with_capacity(n_out),
        c_velocity: Vec::with_capacity(n_out),
        c_error: Vec::with_capacity(n_out),
        c_friction: Vec::with_capacity(n_out),
        c_torque: Vec::with_capacity(n_out),
        linear: motion
            .linear_names
            .iter()
            .map(|n| LinearTrace {
                name: n.clone(),
                command: Vec::with_capacity(n_out),
                velocity: Vec::with_capacity(n_out),
                error: Vec::with_capacity(n_out),
            })
            .collect(),
        reversal_time: motion.reversal,
        reversal_index: 0,
        steps,
        step: h,
        direction_changes: 0,
    };
    let mut last_angle = 0.0;
    let mut record =
        |t: f64, r: &[Reference; 4], s: &[AxisState; 4], tr: &mut Trace| -> Result<()> {
            let lin_mm = [0, 1, 2].map(|k| (r[k].x - s[k].e) * 1e3);
            let c = r[3].x - s[3].e;
            let tip = motion.actual_tip(lin_mm, c)?;
            let (ang, dev) = motion.trace_point(&tip);
            // Continuous angle: the nearest turn to the last one.
            let ang = ang + TAU * ((last_angle - ang) / TAU).round();
            last_angle = ang;
            let theta = motion.path(t).x / motion.spec.radius;
            let (f, tau) = s[3].forces(&drives[3], &r[3]);
            tr.time.push(t);
            tr.theta.push(theta);
            tr.angle.push(ang);
            tr.deviation.push(dev);
            tr.x.push(tip.x);
            tr.y.push(tip.y);
            tr.c_command.push(r[3].x);
            tr.c_actual.push(c);
            tr.c_velocity.push(r[3].v - s[3].ev);
            tr.c_error.push(s[3].e);
            tr.c_friction.push(f);
            tr.c_torque.push(tau);
            for k in 0..3 {
                let l = &mut tr.linear[k];
                l.command.push(r[k].x * 1e3);
                l.velocity.push((r[k].v - s[k].ev) * 1e3);
                l.error.push(s[k].e * 1e3);
            }
            Ok(())
        };
    let mut r0 = first;
    record(0.0, &r0, &state, &mut tr)?;
    for i in 0..steps {
        let t0 = i as f64 * h;
        let rm = refs(t0 + h / 2.0);
        let r1 = refs(t0 + h);
        for k in 0..4 {
            if still[k] {
                continue;
            }
            let one = |t: f64| refs(t)[k];
            tr.direction_changes +=
                state[k].step(&drives[k], (t0, h), [&r0[k], &rm[k], &r1[k]], &one);
        }
        r0 = r1;
        if (i + 1) % stride == 0 || i + 1 == steps {
            record(t0 + h, &r0, &state, &mut tr)?;
        }
    }
    if tr.deviation.iter().any(|v| !v.is_finite()) {
        return Err(Error::field(
            "step",
            "the simulation diverged: the drives are unstable with these gains or this step",
        ));
    }
    tr.reversal_index = tr
        .time
        .iter()
        .enumerate()
        .min_by(|a, b| {
            (a.1 - motion.reversal)
                .abs()
                .total_cmp(&(b.1 - motion.reversal).abs())
        })
        .map_or(0, |(i, _)| i);
    Ok(tr)
}

/// Simulates `case` with its own step.
pub fn simulate(case: &ReversalCase) -> Result<(Motion, Trace)> {
    let motion = case.motion()?;
    let tr = simulate_with_step(case, &motion, case.step * 1e-3)?;
    Ok((motion, tr))
}

/// Whether the linear axes change direction within ±5° of trace angle around C's reversal:
/// commanded (the closed form at 4001 instants) and simulated (the trace's samples). A velocity
/// counts as a direction only beyond 0.1 % of the feed: an axis whose speed falls below that
/// without changing sign beyond it *stops* (with `r = R` one axis's own turning point of the
/// circle falls on C's reversal, and it comes to rest there: Section 5.2's "X stops").
pub fn direction_checks(motion: &Motion, trace: &Trace) -> Vec<DirectionCheck> {
    let half = 5f64.to_radians() * motion.spec.radius / motion.spec.feed;
    let (t0, t1) = (motion.reversal - half, motion.reversal + half);
    let tol = 1e-3 * motion.spec.feed;
    let n = 4000;
    let v: Vec<[f64; 3]> = (0..=n)
        .map(|i| {
            let c = motion.commands(t0 + (t1 - t0) * i as f64 / n as f64);
            [c.linear[0].v, c.linear[1].v, c.linear[2].v]
        })
        .collect();
    let changes = |vs: &mut dyn Iterator<Item = f64>| {
        let mut last = 0.0;
        let mut flips = false;
        for v in vs.filter(|v| v.abs() > tol) {
            flips |= last * v < 0.0;
            last = v;
        }
        flips
    };
    let edge = motion.spec.reversal_time;
    (0..3)
        .map(|k| {
            let actual = trace
                .time
                .iter()
                .zip(&trace.linear[k].velocity)
                .filter(|(t, _)| **t >= t0 && **t <= t1)
                .map(|(_, v)| *v);
            let min_speed = v.iter().map(|x| x[k].abs()).fold(f64::INFINITY, f64::min);
            let reverses = changes(&mut v.iter().map(|x| x[k]));
            DirectionCheck {
                name: motion.linear_names[k].clone(),
                before: motion.commands(motion.reversal - edge).linear[k].v,
                after: motion.commands(motion.reversal + edge).linear[k].v,
                min_speed,
                reverses,
                stops: !reverses && min_speed < tol && {
                    let moving = v.iter().any(|x| x[k].abs() > tol);
                    moving
                },
                actual_reverses: changes(&mut actual.clone()),
            }
        })
        .collect()
}

/// The dent the friction makes: the difference of two runs that differ only in friction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct Dent {
    /// Deepest inward difference (with − without friction), mm (positive: a dent).
    pub depth: f64,
    /// Its trace angle, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub angle: f64,
    /// Width at half depth, degrees of trace angle (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub width: f64,
    /// Largest outward difference, mm.
    pub bump: f64,
}

/// The dent of `with` against `without` (same case, C's friction 0), sample by sample.
pub fn dent(with: &Trace, without: &Trace) -> Dent {
    let d: Vec<f64> = with
        .deviation
        .iter()
        .zip(&without.deviation)
        .map(|(a, b)| b - a)
        .collect();
    let (i, depth) = d
        .iter()
        .copied()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0, 0.0));
    let half = depth / 2.0;
    let mut lo = i;
    while lo > 0 && d[lo - 1] >= half {
        lo -= 1;
    }
    let mut hi = i;
    while hi + 1 < d.len() && d[hi + 1] >= half {
        hi += 1;
    }
    let th = &with.theta;
    Dent {
        depth,
        angle: th.get(i).copied().unwrap_or(0.0),
        width: if depth > 0.0 { th[hi] - th[lo] } else { 0.0 },
        bump: d.iter().copied().fold(0.0, |a: f64, b| a.max(-b)),
    }
}

/// The step check: the largest difference between the trace at `h` and at `h/2` (sample by
/// sample, the same instants), mm, and as a fraction of the largest |deviation|.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct StepCheck {
    /// Step, ms (s in Rust; ms like the input `step`).
    #[serde(serialize_with = "seconds_as_ms")]
    pub step: f64,
    /// Largest difference, mm.
    pub difference: f64,
    /// Over the largest |deviation| of the finer run.
    pub relative: f64,
}

/// A time held in s, written in ms.
fn seconds_as_ms<S: serde::Serializer>(s: &f64, ser: S) -> std::result::Result<S::Ok, S::Error> {
    ser.serialize_f64(s * 1e3)
}

/// Runs `case` again with half its step and compares (see [`StepCheck`]).
pub fn step_check(case: &ReversalCase, motion: &Motion, trace: &Trace) -> Result<StepCheck> {
    // The same output instants: twice the steps between samples.
    let stride = if trace.time.len() > 1 {
        ((trace.time[1] - trace.time[0]) / trace.step).round() as usize
    } else {
        1
    };
    let fine = run(case, motion, trace.step / 2.0, 2 * stride)?;
    let mut diff = 0.0f64;
    for (i, (t, d)) in trace.time.iter().zip(&trace.deviation).enumerate() {
        if let (Some(tf), Some(df)) = (fine.time.get(i), fine.deviation.get(i)) {
            if (tf - t).abs() < trace.step / 4.0 {
                diff = diff.max((d - df).abs());
            }
        }
    }
    let scale = fine.deviation.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    Ok(StepCheck {
        step: trace.step,
        difference: diff,
        relative: if scale > 0.0 { diff / scale } else { 0.0 },
    })
}

/// The dent for one of Table 1's conditions.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct DentRow {
    /// Feed F, mm/min.
    pub feed: f64,
    /// Socket offset r, mm.
    pub offset: f64,
    /// The dent.
    pub dent: Dent,
}

/// The dent for each of Table 1's feeds (1000, 2000, 3000 mm/min) and radii r (25, 50 mm), the
/// other inputs as given (the export `reversalDents`).
pub fn table1_dents(case: &ReversalCase) -> Result<Vec<DentRow>> {
    let mut out = Vec::new();
    for r in [25.0, 50.0] {
        for f in [1000.0, 2000.0, 3000.0] {
            let mut c = case.clone();
            c.test.feed = f;
            c.test.offset = r;
            let (m, with) = simulate(&c)?;
            let without = simulate_with_step(&c.with_c_friction(0.0), &m, c.step * 1e-3)?;
            out.push(DentRow {
                feed: f,
                offset: r,
                dent: dent(&with, &without),
            });
        }
    }
    Ok(out)
}

/// One simulated test (the export `reversalSimulate`): the trace with C's friction, the same
/// run without it, the dent, and whether X and Y change direction with C.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct ReversalSimulation {
    /// The run with friction.
    #[serde(flatten)]
    pub trace: Trace,
    /// The radial deviation of the same run with C's friction 0, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub without_friction: Vec<f64>,
    /// The friction's dent.
    pub dent: Dent,
    /// X, Y and Z at C's reversal.
    pub directions: Vec<DirectionCheck>,
    /// Halving the step (with `checkStep`); null without.
    pub step_check: Option<StepCheck>,
    /// Circle centre in table coordinates `[x, y]`, mm.
    pub centre: [f64; 2],
    /// C's axis in table coordinates `[x, y]`, mm.
    pub axis: [f64; 2],
}

/// Simulates the reversal test on the machine with and without C's friction (module docs), and
/// with `checkStep` again at half the step.
pub fn simulation((case, run): &(ReversalCase, ReversalRunInput)) -> Result<ReversalSimulation> {
    let (m, trace) = simulate(case)?;
    let without = simulate_with_step(&case.with_c_friction(0.0), &m, trace.step)?;
    let step_check = if run.check_step {
        Some(step_check(case, &m, &trace)?)
    } else {
        None
    };
    Ok(ReversalSimulation {
        dent: dent(&trace, &without),
        directions: direction_checks(&m, &trace),
        step_check,
        centre: [m.centre.x, m.centre.y],
        axis: [m.axis.x, m.axis.y],
        without_friction: without.deviation,
        trace,
    })
}

/// π, for the tests: the trace angle of the reversal.
pub const REVERSAL_THETA: f64 = PI;
