//! The simulated tests (the export `ballbarRotarySimulate`): per test and angle the commanded
//! pose, the balls on the machine with its errors, the bar's exact length change, its
//! first-order value and the sensitivities; what the tests can see; and the trace as a file the
//! reader takes back ([`crate::ballbar::read`]).

use super::see::{self, Point, RotaryTogether, RotaryVisibility};
use super::{BallbarRotaryInput, BarDirection, Study, Test};
use crate::error::Result;
use crate::identify::{amount, DEFAULT_RTOL};
use crate::schema::Quantity;
use serde::Serialize;

/// One axis's commanded positions along a test.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct CommandedAxis {
    /// The axis letter.
    pub name: String,
    /// "mm" or "deg".
    pub unit: String,
    /// Per point, mm, or degrees for a rotary axis (in API units already).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub values: Vec<f64>,
}

/// The bar's sensitivity to one error along a test.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct BarSensitivity {
    /// ISO name.
    pub name: String,
    /// Per "mm" or per "deg".
    pub per: String,
    /// Per point, mm of length change per mm, or per degree.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub values: Vec<f64>,
}

/// One simulated test.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct RotarySimulatedTest {
    /// Its name.
    pub name: String,
    /// The moving axis's letter.
    pub axis: char,
    /// The held axis's letter.
    pub held: char,
    /// The held axis's command, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub hold: f64,
    /// How the bar lies.
    pub direction: BarDirection,
    /// The bar's nominal length, mm.
    pub length: f64,
    /// The table ball, workpiece frame, mm.
    pub ball: [f64; 3],
    /// The tool ball where the ideal machine keeps it, workpiece frame, mm.
    pub tool_ball: [f64; 3],
    /// The bar's direction (table ball to tool ball), workpiece frame.
    pub bar: [f64; 3],
    /// The test's radial, tangential and axial directions, workpiece frame.
    pub frame: [[f64; 3]; 3],
    /// A point of the moving axis's line at 0°, workpiece frame, mm.
    pub axis_point: [f64; 3],
    /// The ball's distance from the axis line (the table ball's for a table axis, the tool
    /// ball's for a head axis), mm.
    pub radius: f64,
    /// Its position along the line from `axisPoint`, mm.
    pub height: f64,
    /// The moving axis's command per point, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub angle: Vec<f64>,
    /// +1 ccw (command increasing), −1 cw, per point.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub run: Vec<f64>,
    /// The commanded positions of every axis (chain order).
    pub commanded: Vec<CommandedAxis>,
    /// The tool ball on the machine with its errors, machine frame: X, Y, Z series, mm.
    #[serde(serialize_with = "crate::edge::series3")]
    #[cfg_attr(
        feature = "ts",
        tsify(type = "[Float64Array, Float64Array, Float64Array]")
    )]
    pub tool: [Vec<f64>; 3],
    /// The table ball on the machine with its errors, machine frame: X, Y, Z series, mm.
    #[serde(serialize_with = "crate::edge::series3")]
    #[cfg_attr(
        feature = "ts",
        tsify(type = "[Float64Array, Float64Array, Float64Array]")
    )]
    pub table: [Vec<f64>; 3],
    /// The bar's exact length change per point, mm (+ longer).
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub deviation: Vec<f64>,
    /// Its first-order value (every error and error motion of the machine), mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub first_order: Vec<f64>,
    /// The tool ball's displacement relative to the table in the test's radial, tangential
    /// and axial directions (exact), mm: what a bar in each direction would see.
    #[serde(serialize_with = "crate::edge::series3")]
    #[cfg_attr(
        feature = "ts",
        tsify(type = "[Float64Array, Float64Array, Float64Array]")
    )]
    pub displacement: [Vec<f64>; 3],
    /// The sensitivities to the study's errors.
    pub sensitivities: Vec<BarSensitivity>,
    /// Largest minus smallest length change, mm.
    pub spread: f64,
}

/// The simulation's result.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct BallbarRotarySimulation {
    /// Per test.
    pub tests: Vec<RotarySimulatedTest>,
    /// What the tests can see of the study's errors.
    pub visibility: RotaryVisibility,
    /// What each test sees alone and what they see together.
    pub together: RotaryTogether,
    /// The simulated traces as a file (one test: no test column), µm.
    pub csv: String,
    /// The conclusions in words.
    pub summary: Vec<String>,
}

/// A length change below this (mm, a picometre) is the exact chain's rounding: the summary says
/// the bar's length does not change.
pub const NO_CHANGE: f64 = 1e-9;

/// Simulates every test (module docs of [`super`]).
pub fn simulate(input: &BallbarRotaryInput) -> Result<BallbarRotarySimulation> {
    let study = Study::new(input)?;
    let chain = &study.model.chain;
    let names = chain.axis_names();
    let mut tests = Vec::with_capacity(study.tests.len());
    let mut points: Vec<Point> = Vec::new();
    for (ti, t) in study.tests.iter().enumerate() {
        let sweep = study.sweep(t);
        let n = sweep.len();
        let mut commanded: Vec<CommandedAxis> = names
            .iter()
            .enumerate()
            .map(|(i, name)| CommandedAxis {
                name: name.clone(),
                unit: if is_rotary(&study, i) { "deg" } else { "mm" }.to_string(),
                values: Vec::with_capacity(n),
            })
            .collect();
        let mut sens: Vec<Vec<f64>> = vec![Vec::with_capacity(n); study.unknowns.len()];
        let (mut tool, mut table, mut disp) = (empty3(n), empty3(n), empty3(n));
        let (mut deviation, mut first) = (Vec::with_capacity(n), Vec::with_capacity(n));
        for &(angle, d) in &sweep {
            let e = study.exact(t, angle)?;
            for (i, c) in commanded.iter_mut().enumerate() {
                c.values.push(if is_rotary(&study, i) {
                    e.q[i].to_degrees()
                } else {
                    e.q[i]
                });
            }
            for k in 0..3 {
                tool[k].push(e.tool[k]);
                table[k].push(e.table[k]);
                disp[k].push(e.displacement[k]);
            }
            deviation.push(e.deviation);
            first.push(study.first_order(t, angle)?);
            for (j, s) in study.sensitivities(t, angle)?.into_iter().enumerate() {
                sens[j].push(study.unknowns[j].quantity.per_api_unit(s));
            }
            points.push(Point {
                test: ti,
                angle,
                direction: d,
            });
        }
        let spread = super::range(&deviation);
        tests.push(RotarySimulatedTest {
            name: t.name.clone(),
            axis: t.letters[0],
            held: t.letters[1],
            hold: t.hold,
            direction: t.direction,
            length: t.length,
            ball: arr(&t.ball),
            tool_ball: arr(&t.tool),
            bar: arr(&t.bar),
            frame: t.frame.map(|v| arr(&v)),
            axis_point: arr(&t.axis_point),
            radius: t.radius,
            height: t.height,
            angle: sweep.iter().map(|s| s.0).collect(),
            run: sweep.iter().map(|s| s.1).collect(),
            commanded,
            tool,
            table,
            deviation,
            first_order: first,
            displacement: disp,
            sensitivities: study
                .unknowns
                .iter()
                .zip(sens)
                .map(|(d, values)| BarSensitivity {
                    name: d.name.to_string(),
                    per: d.quantity.api_unit().to_string(),
                    values,
                })
                .collect(),
            spread,
        });
    }
    let sys = see::system(&study, &points)?;
    let f = see::view(&sys.a, &sys.names, DEFAULT_RTOL)?;
    let visibility = see::visibility(&study, &sys, &f);
    let together = see::together(&study, &sys, &points, DEFAULT_RTOL)?;
    let mut summary: Vec<String> = tests
        .iter()
        .map(|s| {
            // Below a picometre the change is the chain's rounding, not the machine's errors.
            let change = if s.spread < NO_CHANGE {
                "does not change (no error of the machine moves it in this test)".to_string()
            } else {
                format!(
                    "changes by {} (largest − smallest)",
                    amount(Quantity::SmallLength, s.spread)
                )
            };
            format!(
                "Test {}: {} from {:.1}° to {:.1}° ({} at {:.1}°), {} bar of {} mm: the bar's length {change}.",
                s.name,
                s.axis,
                s.angle.first().copied().unwrap_or(0.0).to_degrees(),
                s.angle.iter().fold(f64::NEG_INFINITY, |a, b| a.max(*b)).to_degrees(),
                s.held,
                s.hold.to_degrees(),
                s.direction.value(),
                s.length,
            )
        })
        .collect();
    summary.extend(
        visibility
            .invisible
            .iter()
            .map(|u| format!("{}: {}", u.name, u.why)),
    );
    summary.extend(visibility.inseparable.iter().map(|g| g.why.clone()));
    summary.push(together.words.clone());
    Ok(BallbarRotarySimulation {
        csv: trace_csv(&study, &tests),
        tests,
        visibility,
        together,
        summary,
    })
}

fn is_rotary(study: &Study, i: usize) -> bool {
    matches!(
        study.model.chain.link(i).joint,
        crate::chain::Joint::Rotary(_)
    )
}

fn empty3(n: usize) -> [Vec<f64>; 3] {
    [
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    ]
}

fn arr(v: &nalgebra::Vector3<f64>) -> [f64; 3] {
    [v[0], v[1], v[2]]
}

/// The simulated traces as the reader's file ([`crate::ballbar::read`]): comment lines
/// stating each test, then `test;angle (deg);deviation (µm);direction` (no test column for
/// one test), deviations to 0.1 nm.
pub fn trace_csv(study: &Study, tests: &[RotarySimulatedTest]) -> String {
    let many = tests.len() > 1;
    let mut s = String::from(
        "# Ball-bar tests with a rotary axis moving (ISO 10791-6 style), SIMULATED by the\n\
         # five-axis accuracy calculator from the machine's errors.\n",
    );
    for t in &study.tests {
        s.push_str(&describe(t));
    }
    s.push_str(if many {
        "test;angle (deg);deviation (µm);direction\n"
    } else {
        "angle (deg);deviation (µm);direction\n"
    });
    for sim in tests {
        for ((a, d), r) in sim.angle.iter().zip(&sim.deviation).zip(&sim.run) {
            let dir = if *r > 0.0 { "ccw" } else { "cw" };
            let line = format!("{};{:.4};{dir}\n", num(a.to_degrees()), d * 1e3);
            if many {
                s.push_str(&format!("{};{line}", sim.name));
            } else {
                s.push_str(&line);
            }
        }
    }
    s
}

/// A comment line stating a test.
fn describe(t: &Test) -> String {
    format!(
        "# test {}: {} from {}° to {}° with {} at {}°, {} bar of {} mm, table ball at {}, {}, {} mm (workpiece frame)\n",
        t.name,
        t.letters[0],
        num(t.from.to_degrees()),
        num(t.to.to_degrees()),
        t.letters[1],
        num(t.hold.to_degrees()),
        t.direction.value(),
        num(t.length),
        num(t.ball[0]),
        num(t.ball[1]),
        num(t.ball[2]),
    )
}

fn num(v: f64) -> String {
    let t = format!("{v:.6}");
    let t = t.trim_end_matches('0').trim_end_matches('.').to_string();
    if t == "-0" {
        "0".to_string()
    } else {
        t
    }
}
