//! Ball-bar tests with a rotary axis moving (ISO 10791-6 style): a rotary axis turns while the
//! linear axes keep the spindle's ball where the ideal machine keeps it on the table, so that
//! the bar between the two balls keeps its length; what the bar records is the machine's
//! errors. The classic tests: the table axis C with X and Y (the ball on the C table at a
//! radius and height, the bar radial, tangential or axial), and the tilt axis (A or B) with Y
//! and Z (or X and Z). The simulation runs through the machine's one chain ([`crate::chain`]);
//! the identification of the axes' location errors uses the shared [`crate::identify`].
//!
//! # The test (frames, signs, units)
//! One test moves one rotary axis, the **moving axis** (K, the one nearer the workpiece, or M),
//! from `from` to `to` (its commands, degrees at the edge) and back, while the other rotary
//! axis stands at `hold`. Everything is in the **workpiece frame** of the chain (the table
//! surface's centre, axes parallel to the machine's with all axes at zero; mm):
//! * the **table ball** at `p = x·u + y·v + height·n` (the face frame `(u, v, n)` of
//!   [`crate::machine::Machine::face_frame`]: X, Y, Z for a vertical spindle), fixed to the
//!   table;
//! * the moving axis's **line** (point `a`, positive direction `â`, its ISO letter's
//!   direction) in the workpiece frame with the moving axis at 0° and the other at `hold`; for
//!   a table axis it is the same at every angle of the test;
//! * the test's frame: **radial** `r̂`, square to `â`, from the axis line towards the table
//!   ball (for a head axis: towards the tool ball, the spindle's ball centre, at 0°);
//!   **tangential** `t̂ = â × r̂`; **axial** `â`;
//! * the bar's direction `b̂` (from the table ball to the tool ball): radial `r̂` for a table
//!   axis (the tool ball further out), `−r̂` for a head axis (the bar continues the line from
//!   the axis through the tool ball, so the table ball lies beyond the tool's tip); tangential
//!   `t̂`; axial `â`;
//! * the **tool ball** (the tool tip of the chain: the ball's centre `toolLength` from the
//!   spindle nose, calibrated) at `t = p + L·b̂`, `L` the bar's nominal length.
//!
//! At each angle `θ` of the moving axis the **commanded pose** is the nominal inverse
//! kinematics ([`crate::chain::Chain::solve_linear`]): the rotary axes at `θ` and `hold`, the
//! three linear axes where the nominal tip is at `t`. In the ideal machine the two balls stay
//! at `p` and `t` on the table, and the bar at `L`.
//!
//! The direction of a run: **ccw** (`+`): the moving axis's command increasing, `from → to`;
//! **cw** (`−`): decreasing. (ISO 841: for a table axis the table itself turns the other way.)
//!
//! # What the bar records (exact)
//! On the machine with its errors ([`crate::chain`]: location errors and error motions, the
//! ball set on the actual table, no set-up transform), at the commanded pose `q`:
//! `F_work(q)·p` is the table ball and `F_tool(q)·0` the tool ball (machine frame), and the
//! bar's **length change** is `ΔL = |F_tool·0 − F_work·p| − L` (mm, + longer) — exactly, at
//! every angle ([`Study::exact`]). The tool ball's displacement relative to the table,
//! `δ = tip_actual(q) − t` (workpiece frame), is also given in the test's frame, `(δ·r̂, δ·t̂,
//! δ·â)`: what a radial, tangential and axial bar would see to first order.
//!
//! The simulation is **geometric**: the axes stand where they are commanded (no servo lag, no
//! backlash or reversal spike, no thermal drift), so the ccw and cw runs coincide; a measured
//! trace whose runs differ carries what the model lacks, and the fit's goodness says so (the
//! per-direction offsets take a constant lag of a tangential bar). Every error of the machine
//! acts, those of the held axis and of the linear axes (which move during the test) included.
//! The tool ball is taken as calibrated (its length from the spindle nose is known), as the
//! probe's ball is in [`crate::probe`].
//!
//! # First order
//! `ΔL ≈ b̂·δ`, and `δ ≈ Σ_ε J_ε·ε` with `J_ε` the chain's analytic Jacobian of the tip in the
//! workpiece frame ([`crate::chain::Chain::jacobian`], no set-up): the **sensitivity** of the
//! bar to error `ε` is `b̂·J_ε` (mm per mm, per rad; per degree at the edge). Its remainder is
//! of the second order in the errors (`|δ|²/(2L)` from the bar's turn, and the chain's own).
//!
//! A closed form checks it: with the table axis C of a table-table machine at `B = 0` whose
//! line lies `e` off along X (`E_X0C = e`), and a radial bar at the ball's table angle `φ`
//! (its angle about C in the workpiece frame), the table ball sits at `R_Z(−C)·p + e·x̂` while
//! the tool ball is at `R_Z(−C)·t`: `ΔL = √(L² − 2·L·e·cos(φ − C) + e²) − L ≈ −e·cos(C − φ)`,
//! once per turn, shortest at `C = φ` (crate/tests/ballbar/rotary_trace.rs).
//!
//! # What a test cannot see ([`see`])
//! The bar measures one length: a turn about the moving axis's own line (its zero, `E_C0C`)
//! moves the table ball along its circle, square to a radial bar; a shift along the own line
//! (`E_Z0C`) is square to a radial or tangential bar — both change the length only to the
//! second order. An error that moves the bar's length by the same amount at every angle acts
//! as the bar's own length and the balls' set-up, which are not known to a micrometre and are
//! fitted per test and direction (the **offsets**): a tangential bar sees `E_C0C` that way, an
//! axial bar `E_Z0C`. A tilt of C at the ball's height `h` above the tilt's pivot moves the
//! ball like an offset of the line by `h·angle`: one radial test sees only the combination;
//! a second test with the ball at another height, or an axial bar, separates them ([`see`]
//! reports what the tests see alone and together).
//!
//! # Degenerate cases
//! A radial or tangential bar needs the table ball off a table axis's line (the tool ball off a
//! head axis's line): else the direction is undefined and the test is refused (the axial bar
//! is not). A sweep outside the moving axis's travel, a `hold` outside the other's, `from ≥ to`
//! and more than 20 000 points a run are refused; the linear axes' travel is not modelled. The
//! identification refuses a test with fewer than 8 measured points and an angle of a file
//! outside the moving axis's travel, naming the line. Errors the tests cannot separate get no
//! value of their own (the groups of [`crate::identify::fit`]): e.g. on a machine with a B head
//! over a C table the offsets of B's line and of C's move the bar alike in every test here.

pub mod fit;
pub mod see;
pub mod simulate;

use crate::chain::{Joint, Setup};
use crate::edge::Checked;
use crate::error::{Error, Result};
use crate::machine::errors::{ErrorDef, NAMES};
use crate::machine::{Machine, Model};
use crate::schema::{self, Custom, DefaultValue, Inputs, Kind, Quantity};
use nalgebra::{Point3, Vector3};
use serde_json::Value;
use std::f64::consts::TAU;

/// Most tests in one study.
pub const MAX_TESTS: usize = 8;
/// Fewest points of a test.
pub const MIN_POINTS: usize = 8;
/// Most points of a simulated sweep, each direction.
pub const MAX_POINTS: usize = 20_000;
/// A ball closer than this to the axis line (mm) is on it: no radial direction.
const ON_LINE: f64 = 1e-6;

crate::choices! {
    /// How the bar lies relative to the moving axis, from the table ball to the spindle's ball.
    pub enum BarDirection {
        /// Square to the axis, through the balls.
        Radial = "radial" {
            label: "Radial",
            help: "Square to the moving axis, on the line from the axis through the ball: sees the axis line's offsets (and tilts at the ball's height) once per turn.",
        },
        /// Square to the axis and to the radial direction.
        Tangential = "tangential" {
            label: "Tangential",
            help: "Along the ball's circle about the axis: sees the offsets a quarter turn later, and the axis's zero as a constant (not separable from the bar's length).",
        },
        /// Along the axis.
        Axial = "axial" {
            label: "Axial",
            help: "Along the moving axis: sees its tilts at the ball's radius, once per turn.",
        },
    }
}

crate::choices! {
    /// Which rotary axis a test moves.
    pub enum MovingAxis {
        /// K, the rotary axis nearer the workpiece (C of a B/C or A/C table).
        K = "k" {
            label: "{K}",
            help: "The rotary axis nearer the workpiece (the C table of a B/C or A/C machine): the linear axes follow the ball round it.",
        },
        /// M, the one nearer the tool (the tilt axis).
        M = "m" {
            label: "{M}",
            help: "The rotary axis nearer the tool (the tilt axis A or B): the linear axes follow the ball as it tilts.",
        },
    }
}

crate::inputs! {
    /// Where the table ball's centre sits (mm, the face frame of the table surface).
    pub struct BallPlace {
        /// Along the face's first axis (X for a vertical spindle), mm.
        pub x: f64 = "x" optional {
            label: "Table ball along the table's first axis",
            help: "From the table centre, along X for a vertical spindle (the face's first axis), with all axes at zero: the ball's radius on a C table.",
            kind: schema::number(Quantity::Length, -2000.0, 2000.0),
            default: DefaultValue::Num(100.0),
            group: "Ball-bar test",
        },
        /// Along the face's second axis (Y for a vertical spindle), mm.
        pub y: f64 = "y" optional {
            label: "Table ball along the table's second axis",
            help: "From the table centre, along Y for a vertical spindle (the face's second axis).",
            kind: schema::number(Quantity::Length, -2000.0, 2000.0),
            default: DefaultValue::Num(0.0),
            group: "Ball-bar test",
        },
        /// Height of the centre above the table surface, mm.
        pub height: f64 = "height" optional {
            label: "Table ball above the table",
            help: "Height of the table ball's centre above the table surface (along the spindle at zero).",
            kind: schema::number(Quantity::Length, -2000.0, 2000.0),
            default: DefaultValue::Num(50.0),
            group: "Ball-bar test",
        },
    }
}

crate::inputs! {
    /// One test: the axis moved, the other's angle, the table ball, the bar, the sweep.
    pub struct RotaryTest {
        /// Its name (the `test` column of a file); its number from 1 when left empty.
        pub name: String = "name" optional {
            label: "Test name",
            help: "How the test is named in a file's test column; empty: its number (1, 2, …).",
            kind: Kind::Text { max_len: 40 },
            default: DefaultValue::Str(""),
            group: "Ball-bar test",
        },
        /// The rotary axis moved.
        pub axis: MovingAxis = "axis" optional {
            label: "Axis moved",
            help: "The rotary axis that turns during the test; the linear axes follow the ball.",
            kind: Kind::Choice(MovingAxis::CHOICES),
            default: DefaultValue::Str("k"),
            group: "Ball-bar test",
        },
        /// The other rotary axis's command during the test, degrees (radians in Rust).
        pub hold: f64 = "hold" optional {
            label: "The other rotary axis stands at",
            help: "The command of the rotary axis that does not move during the test.",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            default: DefaultValue::Num(0.0),
            group: "Ball-bar test",
        },
        /// Where the table ball sits.
        pub ball: BallPlace = "ball" optional {
            label: "Table ball", kind: Kind::Object(BallPlace::FIELDS), default: DefaultValue::Empty,
        },
        /// The bar's nominal length, mm.
        pub length: f64 = "length" optional {
            label: "Bar length",
            help: "The ball-bar's nominal length (centre to centre), e.g. 100 or 150 mm.",
            kind: schema::number(Quantity::Length, 10.0, 2000.0),
            default: DefaultValue::Num(100.0),
            group: "Ball-bar test",
        },
        /// How the bar lies.
        pub direction: BarDirection = "direction" optional {
            label: "Bar direction",
            help: "Radial, tangential or axial to the moving axis (from the table ball to the spindle's ball).",
            kind: Kind::Choice(BarDirection::CHOICES),
            default: DefaultValue::Str("radial"),
            group: "Ball-bar test",
        },
        /// Start of the sweep, degrees (radians in Rust); left out: 0° for an axis that turns a
        /// full turn, else the start of its travel, at most 90° from 0°.
        pub from: Option<f64> = "from" optional {
            label: "Sweep from",
            help: "The moving axis's first command; left empty: 0° for a full turn, or the travel (at most ±90°) of a tilt axis.",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            group: "Ball-bar test",
        },
        /// End of the sweep, degrees (radians in Rust); left out: 360° for an axis that turns a
        /// full turn, else the end of its travel, at most 90° from 0°.
        pub to: Option<f64> = "to" optional {
            label: "Sweep to",
            help: "The moving axis's last command; left empty: 360° for a full turn, or the travel (at most ±90°) of a tilt axis.",
            kind: schema::number(Quantity::Angle, -3600.0, 3600.0),
            group: "Ball-bar test",
        },
        /// Angle between simulated points, degrees (radians in Rust).
        pub step: f64 = "step" optional {
            label: "Simulated point every",
            help: "The angle between points of the simulated trace.",
            kind: schema::number(Quantity::Angle, 0.05, 90.0),
            default: DefaultValue::Num(1.0),
            group: "Ball-bar test",
        },
        /// The measured trace of this test: the moving axis's command (deg), the bar's length
        /// change (unit in the header) and the direction per line; empty: none.
        pub csv: String = "csv" optional {
            label: "Measured trace (CSV)",
            help: "Angle of the moving axis (deg) and the bar's length change (µm or mm) per line, with a direction column (ccw/cw), units in the header.",
            kind: Kind::Text { max_len: 5_000_000 },
            default: DefaultValue::Str(""),
            group: "Ball-bar test",
        },
    }
}

impl RotaryTest {
    /// The default test: K swept once round, the ball at the defaults, a radial bar.
    pub fn standard() -> Result<Self> {
        Self::from_value(&Value::Null, "tests[0]")
    }
}

/// The name of [`TESTS`] in the exported schema (its items' fields: the schema's `lists`).
pub const TESTS_KIND: &str = "ballbarTests";

/// The schema kind of the list of tests: 1 to [`MAX_TESTS`] objects of [`RotaryTest`]'s
/// fields, each read (and converted to engine units) at `tests[i]`.
pub const TESTS: Kind = Kind::Custom(&Custom {
    name: TESTS_KIND,
    read: read_tests,
    list: true,
});

fn read_tests(v: &Value, path: &str) -> Result<Value> {
    let list = v.as_array().ok_or_else(|| {
        Error::field(
            path,
            "expected a list of tests, e.g. [{ \"axis\": \"k\", \"direction\": \"radial\" }]",
        )
    })?;
    if list.len() > MAX_TESTS {
        return Err(Error::field(
            path,
            format!("{} tests: at most {MAX_TESTS}", list.len()),
        ));
    }
    let mut out = Vec::with_capacity(list.len());
    for (i, item) in list.iter().enumerate() {
        let t = RotaryTest::from_value(item, &format!("{path}[{i}]"))?;
        out.push(
            serde_json::to_value(&t)
                .map_err(|e| Error::field(format!("{path}[{i}]"), e.to_string()))?,
        );
    }
    Ok(Value::Array(out))
}

crate::inputs! {
    /// The ball-bar tests of the rotary axes on a machine.
    pub struct BallbarRotaryInput {
        /// The machine (its errors are the truth the simulation uses).
        pub machine: Machine = "machine" optional {
            label: "Machine", kind: Kind::Object(Machine::FIELDS), default: DefaultValue::Empty,
        },
        /// The tests; one default test (K, radial) when left out or empty.
        pub tests: Vec<RotaryTest> = "tests" optional {
            label: "Ball-bar tests",
            help: "Each test: the axis moved, the ball's place, the bar's length and direction, the sweep, and its measured trace.",
            kind: TESTS,
            default: DefaultValue::Empty,
            group: "Ball-bar test",
            shown: false,
        },
        /// The errors to identify; the location errors of the axes the tests move when left out.
        pub parameters: Option<Vec<String>> = "parameters" optional {
            label: "Errors to identify",
            help: "ISO 230-1 names; left out: the location errors of the rotary axes the tests move.",
            kind: NAMES,
            group: "Ball-bar test",
        },
    }
}

impl Checked for BallbarRotaryInput {
    fn check(&self) -> Result<()> {
        self.machine.validate("machine")
    }
}

/// One test on the machine: its geometry in the workpiece frame (module docs), mm, rad.
#[derive(Debug, Clone, PartialEq)]
pub struct Test {
    /// Its name.
    pub name: String,
    /// Which rotary axis moves.
    pub axis: MovingAxis,
    /// The moving axis's letter and the held one's.
    pub letters: [char; 2],
    /// The held axis's command, rad.
    pub hold: f64,
    /// The moving axis is on the workpiece branch (a table axis).
    pub table_side: bool,
    /// The table ball `p`, workpiece frame, mm.
    pub ball: Vector3<f64>,
    /// The tool ball `t = p + L·b̂`, workpiece frame, mm.
    pub tool: Vector3<f64>,
    /// The bar's direction `b̂`.
    pub bar: Vector3<f64>,
    /// The bar's nominal length `L`, mm.
    pub length: f64,
    /// How the bar lies.
    pub direction: BarDirection,
    /// Radial, tangential, axial unit vectors, workpiece frame.
    pub frame: [Vector3<f64>; 3],
    /// A point of the moving axis's line at 0°, workpiece frame, mm.
    pub axis_point: Vector3<f64>,
    /// The table ball's (table axis) or the tool ball's (head axis) distance from the line, mm.
    pub radius: f64,
    /// Its position along the line from `axis_point`, mm.
    pub height: f64,
    /// The sweep, rad: `from < to`, and the step.
    pub from: f64,
    /// End of the sweep, rad.
    pub to: f64,
    /// Step of a simulated sweep, rad.
    pub step: f64,
    /// Its measured trace (empty: none).
    pub csv: String,
}

/// The study: the machine built, the tests placed, the errors to fit.
#[derive(Debug, Clone)]
pub struct Study {
    /// The machine built.
    pub model: Model,
    /// The tests.
    pub tests: Vec<Test>,
    /// The errors whose sensitivities are reported and fitted.
    pub unknowns: Vec<&'static ErrorDef>,
}

/// The tool ball's actual place and the bar's exact length change at one angle.
#[derive(Debug, Clone, PartialEq)]
pub struct Exact {
    /// The commanded positions, chain order (mm, rad).
    pub q: Vec<f64>,
    /// The tool ball in the machine frame, mm (machine with its errors).
    pub tool: Vector3<f64>,
    /// The table ball in the machine frame, mm (machine with its errors).
    pub table: Vector3<f64>,
    /// The bar's length change, mm.
    pub deviation: f64,
    /// The tool ball's displacement relative to the table (workpiece frame) in the test's
    /// radial, tangential and axial directions, mm.
    pub displacement: [f64; 3],
}

/// The default sweep of a moving axis with the travel `(lo, hi)` (rad): a full turn from 0
/// where the travel allows one, else the travel within ±90°.
pub fn default_sweep(lo: f64, hi: f64) -> (f64, f64) {
    if hi - lo >= TAU - 1e-9 {
        if lo <= 1e-9 && hi >= TAU - 1e-9 {
            (0.0, TAU)
        } else {
            (lo, lo + TAU)
        }
    } else {
        let q = TAU / 4.0;
        (lo.max(-q), hi.min(q))
    }
}

impl Study {
    /// The study of the input: the machine built, every test placed (module docs).
    pub fn new(input: &BallbarRotaryInput) -> Result<Self> {
        let machine = &input.machine;
        let model = machine.build()?;
        let given = if input.tests.is_empty() {
            vec![RotaryTest::standard()?]
        } else {
            input.tests.clone()
        };
        let mut tests: Vec<Test> = Vec::with_capacity(given.len());
        for (i, t) in given.iter().enumerate() {
            let test = place(&model, t, i)?;
            if let Some(j) = tests.iter().position(|o| o.name == test.name) {
                return Err(Error::field(
                    format!("tests[{i}].name"),
                    format!("{} is the name of test {} too", test.name, j + 1),
                ));
            }
            tests.push(test);
        }
        let unknowns: Vec<&'static ErrorDef> = match &input.parameters {
            None => {
                let moving: Vec<char> = tests.iter().map(|t| t.letters[0]).collect();
                machine
                    .error_defs()
                    .into_iter()
                    .filter(|d| moving.contains(&d.axis))
                    .collect()
            }
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
        if unknowns.is_empty() {
            return Err(Error::field(
                "parameters",
                "choose at least one error to identify",
            ));
        }
        Ok(Self {
            model,
            tests,
            unknowns,
        })
    }

    /// The rotary commands `(k, m)` of test `t` at the moving axis's angle `angle`, rad.
    fn rotary(&self, t: &Test, angle: f64) -> (f64, f64) {
        match t.axis {
            MovingAxis::K => (angle, t.hold),
            MovingAxis::M => (t.hold, angle),
        }
    }

    /// The commanded positions (chain order, mm and rad) of test `t` at `angle` (rad): the
    /// nominal inverse kinematics with the tool ball at `t.tool` (module docs).
    pub fn commanded(&self, t: &Test, angle: f64) -> Result<Vec<f64>> {
        let (k, m) = self.rotary(t, angle);
        self.model
            .nominal()
            .solve_linear(&t.tool, &self.model.positions(k, m))
    }

    /// Whether `angle` (rad) lies within the moving axis's travel.
    pub fn within(&self, t: &Test, angle: f64) -> bool {
        let [k, m] = self.model.travel();
        let (lo, hi) = match t.axis {
            MovingAxis::K => k,
            MovingAxis::M => m,
        };
        let tol = crate::machine::TRAVEL_TOLERANCE;
        angle >= lo - tol && angle <= hi + tol
    }

    /// The balls and the bar on the machine with its errors at `angle` (rad), exactly (module
    /// docs).
    pub fn exact(&self, t: &Test, angle: f64) -> Result<Exact> {
        let q = self.commanded(t, angle)?;
        let chain = &self.model.chain;
        let (fw, ft) = chain.frames(&q, true)?;
        let table = (fw * Point3::from(t.ball)).coords;
        let tool = (ft * Point3::origin()).coords;
        let tip = chain.tool_pose(&q, true, &Setup::None)?.tip;
        let d = tip - t.tool;
        Ok(Exact {
            deviation: (tool - table).norm() - t.length,
            displacement: [d.dot(&t.frame[0]), d.dot(&t.frame[1]), d.dot(&t.frame[2])],
            q,
            tool,
            table,
        })
    }

    /// The bar's sensitivity to each unknown at `angle` (rad): `b̂·J_ε`, mm per mm or per rad
    /// (module docs).
    pub fn sensitivities(&self, t: &Test, angle: f64) -> Result<Vec<f64>> {
        let q = self.commanded(t, angle)?;
        let jac = self.model.nominal().jacobian(&q, &Setup::None)?;
        self.unknowns
            .iter()
            .map(|d| Ok(t.bar.dot(&jac[self.model.error_column(d)?].tip)))
            .collect()
    }

    /// The first-order length change of every error of the machine at `angle` (rad): its
    /// location errors and its error motions (their values at the commanded pose), mm.
    pub fn first_order(&self, t: &Test, angle: f64) -> Result<f64> {
        let q = self.commanded(t, angle)?;
        let jac = self.model.nominal().jacobian(&q, &Setup::None)?;
        let chain = &self.model.chain;
        let n = chain.len();
        let mut tip = Vector3::zeros();
        for link in 0..n {
            let l = chain.link(link);
            for k in 0..6 {
                tip += jac[6 * link + k].tip * l.location.get(k);
            }
            if let Some(m) = &l.motion {
                let e = m(q[link])?;
                for k in 0..6 {
                    tip += jac[6 * n + 6 * link + k].tip * e.get(k);
                }
            }
        }
        Ok(t.bar.dot(&tip))
    }

    /// The simulated sweep of test `t`: `(angle, direction)` pairs, ccw `from → to` then cw
    /// `to → from`, equal steps of at most `t.step`.
    pub fn sweep(&self, t: &Test) -> Vec<(f64, f64)> {
        let n = ((t.to - t.from) / t.step - 1e-9).ceil().max(1.0) as usize;
        let at = |i: usize| t.from + (t.to - t.from) * i as f64 / n as f64;
        let mut out: Vec<(f64, f64)> = (0..=n).map(|i| (at(i), 1.0)).collect();
        out.extend((0..=n).rev().map(|i| (at(i), -1.0)));
        out
    }
}

/// Places test `t` (the `i`-th) on the machine (module docs).
fn place(model: &Model, t: &RotaryTest, i: usize) -> Result<Test> {
    let path = |f: &str| format!("tests[{i}].{f}");
    let machine = &model.machine;
    let [kl, ml] = model.letters();
    let (moving, letters) = match t.axis {
        MovingAxis::K => (model.layout.k, [kl, ml]),
        MovingAxis::M => (model.layout.m, [ml, kl]),
    };
    let [kt, mt] = model.travel();
    let (travel, held_travel) = match t.axis {
        MovingAxis::K => (kt, mt),
        MovingAxis::M => (mt, kt),
    };
    let tol = crate::machine::TRAVEL_TOLERANCE;
    let deg = |x: f64| format!("{}°", (x.to_degrees() * 1e6).round() / 1e6);
    if t.hold < held_travel.0 - tol || t.hold > held_travel.1 + tol {
        return Err(Error::field(
            path("hold"),
            format!(
                "{} = {} is outside its travel ({} to {})",
                letters[1],
                deg(t.hold),
                deg(held_travel.0),
                deg(held_travel.1)
            ),
        ));
    }
    let (d_from, d_to) = default_sweep(travel.0, travel.1);
    let (from, to) = (t.from.unwrap_or(d_from), t.to.unwrap_or(d_to));
    if from >= to {
        return Err(Error::field(
            path("to"),
            format!(
                "the sweep must end above where it starts ({} to {})",
                deg(from),
                deg(to)
            ),
        ));
    }
    for (f, v) in [("from", from), ("to", to)] {
        if v < travel.0 - tol || v > travel.1 + tol {
            let range = if travel.0.is_finite() {
                format!("{} to {}", deg(travel.0), deg(travel.1))
            } else {
                "unlimited".to_string()
            };
            return Err(Error::field(
                path(f),
                format!(
                    "{} = {} is outside its travel ({range})",
                    letters[0],
                    deg(v)
                ),
            ));
        }
    }
    if (to - from) / t.step > MAX_POINTS as f64 {
        return Err(Error::field(
            path("step"),
            format!(
                "{} over {}: more than {MAX_POINTS} points; take a larger step",
                deg(t.step),
                deg(to - from)
            ),
        ));
    }
    let nominal = model.nominal();
    // The moving axis at 0°, the linear axes at 0: the geometry below is relative to the table
    // (a table axis) or to the tool (a head axis), which the linear axes only translate.
    let q0 = match t.axis {
        MovingAxis::K => model.positions(0.0, t.hold),
        MovingAxis::M => model.positions(t.hold, 0.0),
    };
    let (fw, _) = nominal.frames(&q0, false)?;
    let frame = nominal.axis_frames(&q0)?[moving];
    let Joint::Rotary(axis) = nominal.link(moving).joint else {
        return Err(Error::field("machine", "the moving axis is not rotary"));
    };
    let inv = fw.inverse();
    let a_point = (inv * Point3::from(frame.translation.vector)).coords;
    let a_dir = (inv.rotation * (frame.rotation * axis.unit())).normalize();
    let [u, v, n] = machine.face_frame();
    let ball = u * t.ball.x + v * t.ball.y + n * t.ball.height;
    let table_side = moving < nominal.work.len();
    let tip0 = nominal.tool_pose(&q0, false, &Setup::None)?.tip;
    let from_line = if table_side {
        ball - a_point
    } else {
        tip0 - a_point
    };
    let height = from_line.dot(&a_dir);
    let across = from_line - a_dir * height;
    let radius = across.norm();
    let needs_radial = t.direction != BarDirection::Axial;
    let radial = if radius > ON_LINE {
        across / radius
    } else if needs_radial {
        return Err(Error::field(
            if table_side {
                path("ball")
            } else {
                path("direction")
            },
            if table_side {
                format!(
                    "the table ball lies on the {} axis line: a {} bar needs it off the line (move it along x or y), or use an axial bar",
                    letters[0],
                    t.direction.value()
                )
            } else {
                format!(
                    "the tool ball lies on the {} axis line: a {} bar is undefined; use an axial bar",
                    letters[0],
                    t.direction.value()
                )
            },
        ));
    } else {
        // Any direction square to the axis: the face axis least along it.
        let pick = [u, v, n]
            .into_iter()
            .min_by(|a, b| a.dot(&a_dir).abs().total_cmp(&b.dot(&a_dir).abs()))
            .unwrap_or(u);
        (pick - a_dir * pick.dot(&a_dir)).normalize()
    };
    let tangential = a_dir.cross(&radial);
    let bar = match t.direction {
        BarDirection::Radial if table_side => radial,
        BarDirection::Radial => -radial,
        BarDirection::Tangential => tangential,
        BarDirection::Axial => a_dir,
    };
    let name = if t.name.trim().is_empty() {
        (i + 1).to_string()
    } else {
        t.name.trim().to_string()
    };
    let tool = ball + bar * t.length;
    Ok(Test {
        name,
        axis: t.axis,
        letters,
        hold: t.hold,
        table_side,
        tool,
        ball,
        bar,
        length: t.length,
        direction: t.direction,
        frame: [radial, tangential, a_dir],
        // A head axis's line sits where the commanded pose at 0° puts it (the linear axes
        // translate the tool by t − tip0).
        axis_point: if table_side {
            a_point
        } else {
            a_point + tool - tip0
        },
        radius,
        height,
        from,
        to,
        step: t.step,
        csv: t.csv.clone(),
    })
}

/// Largest minus smallest of `v` (0 for none).
pub(crate) fn range(v: &[f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let (lo, hi) = v
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
    hi - lo
}
