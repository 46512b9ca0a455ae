//! Friction read off a measured trace: `f_c`, `a` (eq 2) and C's position-loop gain `K_p`
//! fitted by least squares to a ball-bar trace (or a roundness profile of the cut cylinder).
//!
//! # The file
//! The ball-bar traces' one reader, [`crate::ballbar::read`] (comma, semicolon or tab, as the
//! header has it; with `;` or tab a decimal comma is accepted, `181,4;-0,0072`; lines starting
//! with `#` are comments): a header with the angle (`angle_deg`, `angle (deg)`) and the
//! deviation (`deviation_mm`, `deviation_um`, `deviation (µm)`; `deviation` alone is in mm),
//! then one row per point: the trace angle in degrees in this study's convention (0° at the
//! start, the reversal of C at 180°, counter-clockwise in table coordinates) and the radial
//! deviation (+ outwards). Angles must increase. The files of the tests with a rotary axis
//! moving ([`crate::ballbar::rotary`]) are read too: with a `direction` column the
//! counter-clockwise points are the trace and the clockwise ones are counted as not used
//! ([`Measured::skipped`]); a file holding several tests (a `test` column) is refused.
//!
//! A comment line `# machine: <name>` (before or among the data, the first one counts) names
//! the machine the trace was made on, as a preset of `public/presets/machines.json` is named
//! ([`declared_machine`]): a trace fits only on the machine it was made on, and the page offers
//! to switch to it.
//!
//! # The fit
//! The model is the simulated trace of the case (the machine, the motion, every other drive
//! parameter as entered) with `f_c`, `a` and `K_p` of C free, interpolated linearly at the
//! measured angles (10 000 samples at least), plus a constant radius offset (a ball bar's length is only known to a few
//! µm). Parameters `ln f_c`, `ln a`, `ln K_p` (all positive) and the offset are found by
//! Levenberg–Marquardt ([`crate::numeric::levenberg_marquardt`]); the 95 % confidence intervals
//! are `exp(ln x ± 1.96·σ_ln x)` from the linearised covariance (`n − p` ≥ 30 degrees of
//! freedom, where Student's t is within 3 % of 1.96). A trace the model cannot fit is refused
//! with the reason: too few points, no points around the reversal, parameters the trace does not
//! determine, or no convergence.

use super::measure::{compensation, measure_dent, MeasuredDent};
use super::{simulate_with_step, ReversalCase, ReversalFitInput};
use crate::ballbar::read::{read_points, Rules};
use crate::error::{Error, Result};
use crate::numeric::{levenberg_marquardt, LsqFailure};
use serde::Serialize;

/// A measured trace: angles (rad) and deviations (mm), with the file line of each point.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// Trace angle, rad, increasing.
    pub angle: Vec<f64>,
    /// Radial deviation, mm.
    pub deviation: Vec<f64>,
    /// The file line of each point (1-based).
    pub lines: Vec<usize>,
    /// Clockwise points of the file, not used (the reversal trace runs counter-clockwise).
    pub skipped: usize,
}

/// Reads a measured trace (module docs) with the ball-bar traces' one reader
/// ([`crate::ballbar::read::read_points`]; a deviation without a unit is in mm). Errors name
/// the field `csv` and the line.
pub fn parse_trace(text: &str) -> Result<Measured> {
    let at = |line: usize, msg: String| Error::field("csv", format!("line {line}: {msg}"));
    let file = read_points(
        text,
        Rules {
            deviation_unit: Some(1.0),
        },
    )?;
    if file.tests.len() > 1 {
        return Err(Error::field(
            "csv",
            format!(
                "the file holds {} tests ({}); the friction fit reads one: give its lines alone",
                file.tests.len(),
                file.tests.join(", ")
            ),
        ));
    }
    let skipped = file.points.iter().filter(|p| p.direction < 0.0).count();
    if skipped == file.points.len() {
        return Err(Error::field(
            "csv",
            "the file has clockwise (cw) points only: the reversal trace runs counter-clockwise \
             (ccw) round the circle in table coordinates",
        ));
    }
    let mut m = Measured {
        angle: Vec::new(),
        deviation: Vec::new(),
        lines: Vec::new(),
        skipped,
    };
    for p in file.points.iter().filter(|p| p.direction > 0.0) {
        // The angle in degrees as the file gave it (the reader's radians rounded back).
        let (line, a, d) = (p.line, deg_text(p.angle), p.deviation);
        if !(-30.0..=390.0).contains(&a) {
            return Err(at(line, format!("angle {a}° is outside 0° to 360°")));
        }
        if d.abs() > 1.0 {
            return Err(at(
                line,
                format!("deviation {d} mm is over 1 mm: is the unit right?"),
            ));
        }
        if let (Some(&last), Some(&ll)) = (m.angle.last(), m.lines.last()) {
            if p.angle <= last {
                return Err(at(
                    line,
                    format!(
                        "angle {a}° does not increase (line {ll} has {:.4}°)",
                        last.to_degrees()
                    ),
                ));
            }
        }
        m.angle.push(p.angle);
        m.deviation.push(d);
        m.lines.push(line);
    }
    if m.angle.len() < 50 {
        return Err(Error::field(
            "csv",
            format!("{} points: the fit needs at least 50", m.angle.len()),
        ));
    }
    let near = m
        .angle
        .iter()
        .filter(|a| (**a - std::f64::consts::PI).abs() <= 10f64.to_radians())
        .count();
    if near < 10 {
        return Err(Error::field(
            "csv",
            format!(
                "{near} points within ±10° of the reversal at 180°: the friction dent is there, \
                 the fit needs at least 10"
            ),
        ));
    }
    Ok(m)
}

/// An angle held in radians in degrees, rounded to 10⁻⁹° (what the file wrote).
fn deg_text(radians: f64) -> f64 {
    (radians.to_degrees() * 1e9).round() / 1e9
}

/// The machine a trace file names in a comment line `# machine: <name>` (module docs), trimmed;
/// `None` without one (or with an empty name).
pub fn declared_machine(text: &str) -> Option<&str> {
    text.lines()
        .filter_map(|l| l.trim().trim_start_matches('\u{feff}').strip_prefix('#'))
        .find_map(|c| {
            let c = c.trim();
            let (key, rest) = c.split_once(':')?;
            key.trim()
                .eq_ignore_ascii_case("machine")
                .then(|| rest.trim())
        })
        .filter(|n| !n.is_empty())
}

/// One fitted parameter with its 95 % confidence interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct FitEstimate {
    /// Value.
    pub value: f64,
    /// Lower end of the 95 % interval.
    pub low: f64,
    /// Upper end.
    pub high: f64,
}

/// A fit of a measured trace (the export `reversalFit`), with the friction in a drive's terms
/// ([`super::measure::compensation`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct FrictionFit {
    /// Coulomb friction `f_c`, N·m.
    #[serde(rename = "friction")]
    pub fc: FitEstimate,
    /// Eq 2's `a`, 1/rad.
    #[serde(rename = "frictionSlope")]
    pub slope: FitEstimate,
    /// C's position-loop gain, 1/s.
    #[serde(rename = "positionGain")]
    pub kp: FitEstimate,
    /// Radius offset, mm.
    pub offset: FitEstimate,
    /// Where the fitted friction has turned half way after a reversal, `atanh(1/2)/a`, degrees
    /// (radians in Rust): with `2·f_c`, the torque step, what a friction compensator of eq 2's
    /// form is set with.
    #[serde(serialize_with = "crate::edge::degrees")]
    pub halfway: f64,
    /// The measured trace angles, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub angle: Vec<f64>,
    /// The measured deviation, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub measured: Vec<f64>,
    /// The model at the measured angles (offset included), mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub fitted: Vec<f64>,
    /// Measured − fitted, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub residuals: Vec<f64>,
    /// Residual standard deviation, mm.
    pub sigma: f64,
    /// Iterations.
    pub iterations: usize,
    /// C's rated torque the shares are of, N·m (the input `c.ratedTorque`).
    pub rated_torque: f64,
    /// Fitted `f_c` over the rated torque.
    pub friction_share: f64,
    /// The torque step a friction compensator needs at each reversal, `2·f_c`, N·m (with the
    /// interval of `f_c` doubled).
    pub torque_step: FitEstimate,
    /// The torque step over the rated torque.
    pub torque_step_share: f64,
    /// Clockwise points of the file not used (the reversal trace runs counter-clockwise).
    pub skipped: usize,
}

/// Samples of the model's trace in a fit (at least).
pub const FIT_SAMPLES: usize = 10_000;

/// 95 % two-sided normal quantile.
const Z95: f64 = 1.959_963_984_540_054;

/// Linear interpolation of `y(x)` (x increasing) at `at`; clamped at the ends.
fn interpolate(x: &[f64], y: &[f64], at: f64) -> f64 {
    let i = x.partition_point(|v| *v < at);
    if i == 0 {
        return y[0];
    }
    if i >= x.len() {
        return y[x.len() - 1];
    }
    let (x0, x1) = (x[i - 1], x[i]);
    if x1 <= x0 {
        return y[i];
    }
    y[i - 1] + (y[i] - y[i - 1]) * (at - x0) / (x1 - x0)
}

/// Fits `f_c`, `a`, C's `K_p` and a radius offset to `measured`, starting from the case's
/// values (module docs).
pub fn fit(case: &ReversalCase, measured: &Measured) -> Result<FrictionFit> {
    // The model finely sampled, so that interpolating it at the measured angles costs nothing
    // in accuracy (a dent is about 1° wide at 1000 mm/min).
    let mut case = case.clone();
    case.samples = case.samples.max(FIT_SAMPLES);
    let case = &case;
    let motion = case.motion()?;
    let h = case.step * 1e-3;
    let model = |p: &[f64]| -> Result<Vec<f64>> {
        let mut c = case.clone();
        c.c.friction = p[0].exp();
        c.c.friction_slope = p[1].exp();
        c.c.position_gain = p[2].exp();
        let tr = simulate_with_step(&c, &motion, h)?;
        // The trace by its actual angle, kept where the angle increases.
        let (mut xs, mut ys) = (
            Vec::with_capacity(tr.angle.len()),
            Vec::with_capacity(tr.angle.len()),
        );
        for (a, d) in tr.angle.iter().zip(&tr.deviation) {
            if xs.last().map_or(true, |l| a > l) {
                xs.push(*a);
                ys.push(*d);
            }
        }
        Ok(measured
            .angle
            .iter()
            .map(|a| interpolate(&xs, &ys, *a) + p[3])
            .collect())
    };
    let residuals = |p: &[f64]| -> Result<Vec<f64>> {
        Ok(model(p)?
            .iter()
            .zip(&measured.deviation)
            .map(|(m, d)| d - m)
            .collect())
    };
    if case.c.friction <= 0.0 {
        return Err(Error::field(
            "c.friction",
            "the fit starts from the entered f_c: enter a guess above 0",
        ));
    }
    let x0 = [
        case.c.friction.ln(),
        case.c.friction_slope.ln(),
        case.c.position_gain.ln(),
        0.0,
    ];
    let n = measured.angle.len();
    if n < 4 + 30 {
        return Err(Error::field(
            "csv",
            "too few points for the fit (at least 34)",
        ));
    }
    let names = ["f_c", "a", "C's position-loop gain", "the radius offset"];
    let lsq = levenberg_marquardt(residuals, &x0, &[1e-4, 1e-4, 1e-4, 1e-6], 40).map_err(|e| {
        match e {
        LsqFailure::Model(e) => e,
        LsqFailure::Undetermined(k) => Error::field(
            "csv",
            format!(
                "the trace does not determine {} (with the others): is there a friction dent \
                 at 180°, and does the trace cover it?",
                names[k]
            ),
        ),
        LsqFailure::NoConvergence => Error::field(
            "csv",
            "the fit did not converge: the model cannot reproduce this trace (check the test's \
             inputs: R, r, F, the machine)",
        ),
        LsqFailure::TooFewData => Error::field("csv", "too few points for the fit"),
    }
    })?;
    let sd = |k: usize| lsq.covariance[k * 4 + k].sqrt();
    let logs = |k: usize| {
        let v = lsq.x[k];
        FitEstimate {
            value: v.exp(),
            low: (v - Z95 * sd(k)).exp(),
            high: (v + Z95 * sd(k)).exp(),
        }
    };
    let fc = logs(0);
    let slope = logs(1);
    for (k, e) in [(0, fc), (1, slope)] {
        if !(e.high / e.low).is_finite() || e.high / e.low > 10.0 {
            return Err(Error::field(
                "csv",
                format!(
                    "the trace hardly determines {}: its 95 % interval spans {:.3e} to {:.3e}; \
                     is there a friction dent at 180°?",
                    names[k], e.low, e.high
                ),
            ));
        }
    }
    let fitted: Vec<f64> = measured
        .deviation
        .iter()
        .zip(&lsq.residuals)
        .map(|(d, r)| d - r)
        .collect();
    let rated = case.c.rated_torque;
    let k = compensation(fc.value, rated);
    Ok(FrictionFit {
        rated_torque: k.rated,
        friction_share: k.friction_share,
        torque_step: FitEstimate {
            value: k.step,
            low: compensation(fc.low, rated).step,
            high: compensation(fc.high, rated).step,
        },
        torque_step_share: k.step_share,
        angle: measured.angle.clone(),
        measured: measured.deviation.clone(),
        fc,
        slope,
        kp: logs(2),
        offset: FitEstimate {
            value: lsq.x[3],
            low: lsq.x[3] - Z95 * sd(3),
            high: lsq.x[3] + Z95 * sd(3),
        },
        halfway: 0.5f64.atanh() / slope.value,
        fitted,
        residuals: lsq.residuals,
        sigma: lsq.sigma,
        iterations: lsq.iterations,
        skipped: measured.skipped,
    })
}

/// The export `reversalFit`: the trace read from `csv` and fitted ([`fit`]) from the case's
/// values.
pub fn fit_trace((case, own): &(ReversalCase, ReversalFitInput)) -> Result<FrictionFit> {
    fit(case, &parse_trace(&own.csv)?)
}

/// A measured trace read and its dent measured, without a fit (the export `reversalTrace`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct MeasuredTrace {
    /// The machine the file names (`# machine: <name>`), or null.
    pub machine: Option<String>,
    /// Points read.
    pub points: usize,
    /// Clockwise points of the file not used (the reversal trace runs counter-clockwise).
    pub skipped: usize,
    /// The dent measured from the trace ([`measure_dent`]).
    pub dent: MeasuredDent,
    /// The dent's width as a time at the test's feed on its circle, `W·R/F`, s
    /// ([`MeasuredDent::duration`]).
    pub duration: f64,
}

/// Reads a measured trace (`csv`) and measures its dent: depth and width from the trace itself,
/// and the machine its file names; the test's R and F give the width in time. Fast (no
/// simulation).
pub fn measure_trace((case, own): &(ReversalCase, ReversalFitInput)) -> Result<MeasuredTrace> {
    let m = parse_trace(&own.csv)?;
    let dent = measure_dent(&m.angle, &m.deviation)?;
    Ok(MeasuredTrace {
        machine: declared_machine(&own.csv).map(str::to_string),
        points: m.angle.len(),
        skipped: m.skipped,
        duration: dent.duration(case.test.radius, case.test.feed),
        dent,
    })
}
