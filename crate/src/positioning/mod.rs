//! Positioning of one axis, linear or rotary, evaluated as ISO 230-2:2014 defines it from a laser
//! (or any) measurement: `n` runs each way at each of `m` targets.
//!
//! # Definitions (ISO 230-2:2014, clause 3)
//! At target `P_i` (`i = 1 … m`), run `j` (`j = 1 … n`), approached in the positive (↑) or the
//! negative (↓) direction, the **positional deviation** is `x_ij = P_ij − P_i`: the position
//! reached less the target, in the axis's own coordinate (the tool relative to the workpiece, as
//! ISO 841 names axes). Then, at each target, for each direction:
//! * mean unidirectional positional deviation `x̄_i↑ = (1/n)·Σ_j x_ij↑` (and ↓);
//! * estimator of the unidirectional standard uncertainty
//!   `s_i↑ = √( Σ_j (x_ij↑ − x̄_i↑)² / (n − 1) )` (and ↓);
//! * unidirectional repeatability `R_i↑ = 4·s_i↑` (and ↓);
//! * mean bidirectional positional deviation `x̄_i = (x̄_i↑ + x̄_i↓)/2`;
//! * reversal value `B_i = x̄_i↑ − x̄_i↓`;
//! * bidirectional repeatability `R_i = max(2·s_i↑ + 2·s_i↓ + |B_i|, R_i↑, R_i↓)`.
//!
//! And for the axis:
//! * reversal value `B = max_i |B_i|`, mean reversal value `B̄ = (1/m)·Σ_i B_i` (signed);
//! * repeatabilities `R↑ = max_i R_i↑`, `R↓ = max_i R_i↓`, `R = max_i R_i` (the bidirectional one
//!   is the largest `R_i`, not the larger of `R↑` and `R↓`: with a reversal it can exceed both);
//! * systematic positional deviations `E↑ = max x̄_i↑ − min x̄_i↑` (and ↓), bidirectional
//!   `E = max(x̄_i↑, x̄_i↓) − min(x̄_i↑, x̄_i↓)` over both directions together;
//! * mean bidirectional positional deviation `M = max x̄_i − min x̄_i`;
//! * accuracy `A↑ = max(x̄_i↑ + 2·s_i↑) − min(x̄_i↑ − 2·s_i↑)` (and ↓), bidirectional
//!   `A = max(x̄_i↑ + 2·s_i↑, x̄_i↓ + 2·s_i↓) − min(x̄_i↑ − 2·s_i↑, x̄_i↓ − 2·s_i↓)`.
//!
//! # Units
//! A linear axis in mm, a rotary axis in degrees (at the edge and here: this study does not enter
//! the chain, so its values stay in the units they cross in). The file's header gives the units
//! (µm, arcsec, … are converted). Tolerances: `tolerance` (mm) for a linear axis,
//! `rotaryTolerance` (degrees at the edge, radians inside, compared in degrees) for a rotary one;
//! a tolerance of the other kind of axis is refused, naming it.
//!
//! # Into the machine
//! The mean bidirectional deviation `x̄_i` over the targets is the axis's positioning error
//! motion (`E_XX` for X, `E_CC` for C): the tool stands `x̄_i` further along the axis on the
//! workpiece than commanded, the sign of `machine::motions`.
//!
//! # Degenerate cases
//! At least 2 targets and 2 runs each way at each target (the standard asks for 5), the same
//! number of runs in both directions at a target; otherwise the file is refused, naming the target.

mod read;

pub use read::{read_runs, Runs};

use crate::edge::Checked;
use crate::schema::{self, DefaultValue, Kind, Quantity};
use crate::{Error, Result};
use serde::Serialize;

crate::inputs! {
    /// Tolerances of a linear axis's results, mm; 0 leaves a result unjudged.
    pub struct PositioningTolerances {
        /// Bidirectional accuracy A.
        pub a: f64 = "a" optional {
            label: "Tolerance of A (accuracy)", help: "Bidirectional accuracy of the axis (ISO 230-2); 0: not judged.",
            kind: schema::number(Quantity::SmallLength, 0.0, 10.0), default: DefaultValue::Num(0.0),
        },
        /// Bidirectional systematic positional deviation E.
        pub e: f64 = "e" optional {
            label: "Tolerance of E (systematic deviation)", help: "Bidirectional systematic positional deviation (ISO 230-2); 0: not judged.",
            kind: schema::number(Quantity::SmallLength, 0.0, 10.0), default: DefaultValue::Num(0.0),
        },
        /// Bidirectional repeatability R.
        pub r: f64 = "r" optional {
            label: "Tolerance of R (repeatability)", help: "Bidirectional repeatability of positioning (ISO 230-2); 0: not judged.",
            kind: schema::number(Quantity::SmallLength, 0.0, 10.0), default: DefaultValue::Num(0.0),
        },
        /// Reversal value B.
        pub b: f64 = "b" optional {
            label: "Tolerance of B (reversal)", help: "Reversal value of the axis, the largest |B_i| (ISO 230-2); 0: not judged.",
            kind: schema::number(Quantity::SmallLength, 0.0, 10.0), default: DefaultValue::Num(0.0),
        },
        /// Mean bidirectional positional deviation M.
        pub m: f64 = "m" optional {
            label: "Tolerance of M (mean deviation)", help: "Range of the mean bidirectional positional deviation (ISO 230-2); 0: not judged.",
            kind: schema::number(Quantity::SmallLength, 0.0, 10.0), default: DefaultValue::Num(0.0),
        },
    }
}

crate::inputs! {
    /// Tolerances of a rotary axis's results, degrees at the edge (radians inside); 0 leaves a
    /// result unjudged.
    pub struct RotaryTolerances {
        /// Bidirectional accuracy A.
        pub a: f64 = "a" optional {
            label: "Tolerance of A (accuracy)", help: "Bidirectional accuracy of the rotary axis (ISO 230-2); 0: not judged.",
            kind: schema::number(Quantity::SmallAngle, 0.0, 1.0), default: DefaultValue::Num(0.0),
        },
        /// Bidirectional systematic positional deviation E.
        pub e: f64 = "e" optional {
            label: "Tolerance of E (systematic deviation)", help: "Bidirectional systematic positional deviation of the rotary axis (ISO 230-2); 0: not judged.",
            kind: schema::number(Quantity::SmallAngle, 0.0, 1.0), default: DefaultValue::Num(0.0),
        },
        /// Bidirectional repeatability R.
        pub r: f64 = "r" optional {
            label: "Tolerance of R (repeatability)", help: "Bidirectional repeatability of positioning of the rotary axis (ISO 230-2); 0: not judged.",
            kind: schema::number(Quantity::SmallAngle, 0.0, 1.0), default: DefaultValue::Num(0.0),
        },
        /// Reversal value B.
        pub b: f64 = "b" optional {
            label: "Tolerance of B (reversal)", help: "Reversal value of the rotary axis, the largest |B_i| (ISO 230-2); 0: not judged.",
            kind: schema::number(Quantity::SmallAngle, 0.0, 1.0), default: DefaultValue::Num(0.0),
        },
        /// Mean bidirectional positional deviation M.
        pub m: f64 = "m" optional {
            label: "Tolerance of M (mean deviation)", help: "Range of the mean bidirectional positional deviation of the rotary axis (ISO 230-2); 0: not judged.",
            kind: schema::number(Quantity::SmallAngle, 0.0, 1.0), default: DefaultValue::Num(0.0),
        },
    }
}

/// The axes a positioning test may name.
const AXES: &[schema::Choice] = &[
    schema::Choice {
        value: "X",
        label: "X (linear)",
        help: "Its mean bidirectional deviation becomes E_XX.",
    },
    schema::Choice {
        value: "Y",
        label: "Y (linear)",
        help: "Its mean bidirectional deviation becomes E_YY.",
    },
    schema::Choice {
        value: "Z",
        label: "Z (linear)",
        help: "Its mean bidirectional deviation becomes E_ZZ.",
    },
    schema::Choice {
        value: "A",
        label: "A (rotary)",
        help: "Its mean bidirectional deviation becomes E_AA.",
    },
    schema::Choice {
        value: "B",
        label: "B (rotary)",
        help: "Its mean bidirectional deviation becomes E_BB.",
    },
    schema::Choice {
        value: "C",
        label: "C (rotary)",
        help: "Its mean bidirectional deviation becomes E_CC.",
    },
];

crate::inputs! {
    /// A positioning test of one axis (ISO 230-2).
    pub struct PositioningInput {
        /// The measured runs (module docs of `read`).
        pub csv: String = "csv" {
            label: "Measured runs (CSV)",
            help: "One line per measurement (target, direction, run, deviation or actual position), or one line per target with the runs in columns (up 1 … up 5, down 1 … down 5), or one line per run with the targets in columns. Units in the header: target (mm) or (deg), deviation (µm), (arcsec) …",
            kind: Kind::Text { max_len: 5_000_000 },
            group: "Positioning (ISO 230-2)",
        },
        /// The axis measured: X, Y, Z, A, B or C (names the error motion it gives).
        pub axis: String = "axis" optional {
            label: "Axis",
            help: "The axis the runs measured: its mean bidirectional deviation becomes its positioning error motion (E_XX for X).",
            kind: Kind::Choice(AXES),
            default: DefaultValue::Str("X"),
            group: "Positioning (ISO 230-2)",
        },
        /// Tolerances of a linear axis's results, mm.
        pub tolerance: PositioningTolerances = "tolerance" optional {
            label: "Tolerances (linear axis)",
            kind: Kind::Object(<PositioningTolerances as schema::Inputs>::FIELDS),
            default: DefaultValue::Empty,
            group: "Tolerances (linear axis)",
        },
        /// Tolerances of a rotary axis's results, degrees.
        pub rotary_tolerance: RotaryTolerances = "rotaryTolerance" optional {
            label: "Tolerances (rotary axis)",
            kind: Kind::Object(<RotaryTolerances as schema::Inputs>::FIELDS),
            default: DefaultValue::Empty,
            group: "Tolerances (rotary axis)",
        },
    }
}

impl Checked for PositioningTolerances {}
impl Checked for RotaryTolerances {}

impl Checked for PositioningInput {
    fn check(&self) -> Result<()> {
        let rotary = matches!(self.axis.as_str(), "A" | "B" | "C");
        let t = &self.tolerance;
        let r = &self.rotary_tolerance;
        let (given, set, other) = if rotary {
            (
                [t.a, t.e, t.r, t.b, t.m],
                "tolerance",
                "rotaryTolerance (angles)",
            )
        } else {
            (
                [r.a, r.e, r.r, r.b, r.m],
                "rotaryTolerance",
                "tolerance (lengths)",
            )
        };
        if let Some(k) = given.iter().position(|v| *v != 0.0) {
            return Err(Error::field(
                format!("{set}.{}", ["a", "e", "r", "b", "m"][k]),
                format!(
                    "{} is a {} axis: give its tolerances under {other}",
                    self.axis,
                    if rotary { "rotary" } else { "linear" }
                ),
            ));
        }
        if !matches!(self.axis.as_str(), "X" | "Y" | "Z" | "A" | "B" | "C") {
            return Err(Error::field(
                "axis",
                format!(
                    "must be one of X, Y, Z, A, B, C, got {}",
                    crate::error::quote(&self.axis)
                ),
            ));
        }
        Ok(())
    }
}

/// The results at one target.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct TargetResult {
    /// The target `P_i`, mm or degrees.
    pub target: f64,
    /// `x̄_i↑`, the mean deviation approached in the positive direction.
    pub mean_up: f64,
    /// `x̄_i↓`.
    pub mean_down: f64,
    /// `x̄_i`, the mean bidirectional deviation.
    pub mean: f64,
    /// `s_i↑`.
    pub s_up: f64,
    /// `s_i↓`.
    pub s_down: f64,
    /// `R_i↑ = 4·s_i↑`.
    pub r_up: f64,
    /// `R_i↓ = 4·s_i↓`.
    pub r_down: f64,
    /// `R_i`, the bidirectional repeatability there.
    pub r: f64,
    /// `B_i = x̄_i↑ − x̄_i↓`, the reversal value there.
    pub b: f64,
    /// `[x̄_i↑ − 2·s_i↑, x̄_i↑ + 2·s_i↑]`: the band the accuracy `A↑` spans (for the plot).
    pub band_up: [f64; 2],
    /// `[x̄_i↓ − 2·s_i↓, x̄_i↓ + 2·s_i↓]`.
    pub band_down: [f64; 2],
}

/// One result of the axis against its tolerance.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct PositioningCheck {
    /// "A", "E", "R", "B" or "M".
    pub name: &'static str,
    /// Its value, in the axis's unit.
    pub value: f64,
    /// The tolerance, in the axis's unit.
    pub tolerance: f64,
    /// `value ≤ tolerance`.
    pub pass: bool,
}

/// The axis's positioning error motion from the mean bidirectional deviation: what goes into
/// `machine.motions[name]`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct PositioningMotion {
    /// `E_XX` for X … `E_CC` for C.
    pub name: String,
    /// The targets, increasing, mm or degrees.
    pub position: Vec<f64>,
    /// `x̄_i` at each, mm or degrees.
    pub value: Vec<f64>,
}

/// ISO 230-2's results for one axis (module docs). Every value is in `unit`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Positioning {
    /// "mm" for a linear axis, "deg" for a rotary one: the unit of every value here.
    pub unit: &'static str,
    /// The units the file's header gave: target, values.
    pub units: [String; 2],
    /// Runs per direction at each target (`n`).
    pub runs: usize,
    /// Per target, in increasing order.
    pub targets: Vec<TargetResult>,
    /// The deviations `x_ij↑`, per run `j` then target `i` (for the plot).
    pub up: Vec<Vec<f64>>,
    /// The deviations `x_ij↓`.
    pub down: Vec<Vec<f64>>,
    /// Reversal value of the axis `B = max |B_i|`.
    pub b: f64,
    /// Mean reversal value `B̄` (signed).
    pub b_mean: f64,
    /// Unidirectional repeatability `R↑`.
    pub r_up: f64,
    /// `R↓`.
    pub r_down: f64,
    /// Bidirectional repeatability `R = max R_i`.
    pub r: f64,
    /// Unidirectional systematic positional deviation `E↑`.
    pub e_up: f64,
    /// `E↓`.
    pub e_down: f64,
    /// Bidirectional systematic positional deviation `E`.
    pub e: f64,
    /// Mean bidirectional positional deviation `M`.
    pub m: f64,
    /// Unidirectional accuracy `A↑`.
    pub a_up: f64,
    /// `A↓`.
    pub a_down: f64,
    /// Bidirectional accuracy `A`.
    pub a: f64,
    /// Each result with a tolerance above 0, against it.
    pub checks: Vec<PositioningCheck>,
    /// The error motion for the machine.
    pub motion: PositioningMotion,
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// The estimator `s` with `n − 1` in the denominator.
fn spread(v: &[f64], mean: f64) -> f64 {
    (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt()
}

fn range(v: impl Iterator<Item = f64> + Clone) -> f64 {
    let hi = v.clone().fold(f64::NEG_INFINITY, f64::max);
    let lo = v.fold(f64::INFINITY, f64::min);
    hi - lo
}

/// ISO 230-2's results from runs already read (module docs).
pub fn evaluate_runs(runs: &Runs) -> Vec<TargetResult> {
    runs.targets
        .iter()
        .enumerate()
        .map(|(i, &target)| {
            let up: Vec<f64> = runs.up.iter().map(|r| r[i]).collect();
            let down: Vec<f64> = runs.down.iter().map(|r| r[i]).collect();
            let (mean_up, mean_down) = (mean(&up), mean(&down));
            let (s_up, s_down) = (spread(&up, mean_up), spread(&down, mean_down));
            let b = mean_up - mean_down;
            TargetResult {
                target,
                mean_up,
                mean_down,
                mean: (mean_up + mean_down) / 2.0,
                s_up,
                s_down,
                r_up: 4.0 * s_up,
                r_down: 4.0 * s_down,
                r: (2.0 * s_up + 2.0 * s_down + b.abs())
                    .max(4.0 * s_up)
                    .max(4.0 * s_down),
                b,
                band_up: [mean_up - 2.0 * s_up, mean_up + 2.0 * s_up],
                band_down: [mean_down - 2.0 * s_down, mean_down + 2.0 * s_down],
            }
        })
        .collect()
}

/// Reads the runs and evaluates them (module docs); `input.axis` names the error motion and
/// must agree with the file's units (a rotary axis in angles).
pub fn evaluate(input: &PositioningInput) -> Result<Positioning> {
    let runs = read_runs(&input.csv)?;
    let rotary = matches!(input.axis.as_str(), "A" | "B" | "C");
    if rotary != runs.angular {
        return Err(Error::field(
            "axis",
            format!(
                "{} is a {} axis, but the file's targets are in {}",
                input.axis,
                if rotary { "rotary" } else { "linear" },
                runs.units[0]
            ),
        ));
    }
    let t = evaluate_runs(&runs);
    let max = |f: fn(&TargetResult) -> f64| t.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
    let min = |f: fn(&TargetResult) -> f64| t.iter().map(f).fold(f64::INFINITY, f64::min);
    let both = t.iter().flat_map(|r| [r.mean_up, r.mean_down]);
    let a = max(|r| r.band_up[1]).max(max(|r| r.band_down[1]))
        - min(|r| r.band_up[0]).min(min(|r| r.band_down[0]));
    let mut p = Positioning {
        unit: if runs.angular { "deg" } else { "mm" },
        units: runs.units.clone(),
        runs: runs.up.len(),
        b: max(|r| r.b.abs()),
        b_mean: mean(&t.iter().map(|r| r.b).collect::<Vec<_>>()),
        r_up: max(|r| r.r_up),
        r_down: max(|r| r.r_down),
        r: max(|r| r.r),
        e_up: range(t.iter().map(|r| r.mean_up)),
        e_down: range(t.iter().map(|r| r.mean_down)),
        e: range(both),
        m: range(t.iter().map(|r| r.mean)),
        a_up: max(|r| r.band_up[1]) - min(|r| r.band_up[0]),
        a_down: max(|r| r.band_down[1]) - min(|r| r.band_down[0]),
        a,
        checks: Vec::new(),
        motion: PositioningMotion {
            name: format!("E_{0}{0}", input.axis),
            position: t.iter().map(|r| r.target).collect(),
            value: t.iter().map(|r| r.mean).collect(),
        },
        up: runs.up,
        down: runs.down,
        targets: t,
    };
    // A rotary axis's tolerances come in radians (the edge's conversion); its values are in
    // degrees.
    let tol = if rotary {
        let r = &input.rotary_tolerance;
        [r.a, r.e, r.r, r.b, r.m].map(f64::to_degrees)
    } else {
        let t = &input.tolerance;
        [t.a, t.e, t.r, t.b, t.m]
    };
    for ((name, value), tolerance) in [("A", p.a), ("E", p.e), ("R", p.r), ("B", p.b), ("M", p.m)]
        .into_iter()
        .zip(tol)
    {
        if tolerance > 0.0 {
            p.checks.push(PositioningCheck {
                name,
                value,
                tolerance,
                pass: value <= tolerance,
            });
        }
    }
    Ok(p)
}
