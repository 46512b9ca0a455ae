//! The location errors of the rotary axes identified from measured ball-bar traces, with the
//! project's one identification ([`crate::identify`]: least squares by SVD with rank
//! detection, weak directions and groups, Holm's decisions, intervals, goodness of fit).
//!
//! # The files
//! Each test's trace ([`crate::ballbar::read`]: the moving axis's command in degrees, the bar's
//! length change with its unit in the header, a direction column) comes from the test's own
//! `csv`, or from the study's `csv` with a `test` column naming each line's test (by its name
//! or its number from 1); a file without a test column belongs to the only test. A line of a
//! test not defined, an angle outside the moving axis's travel, and a test with fewer than
//! [`super::MIN_POINTS`] points are refused, naming the line or the test.
//!
//! # The system
//! One row per point: the data `d` is the measured length change (mm), the columns the bar's
//! sensitivities to the errors at the commanded pose of that angle (module docs of [`super`])
//! and a one for the offset of its test and direction ([`super::see`]). Each point is one
//! measurement with the same noise (the `decision.noise`, mm, checks the fit's residual).
//!
//! The model is **first order** in the errors (the sensitivities at the nominal commanded
//! pose), the traces it is fitted to are what the machine does exactly: for errors of 10 µm and
//! 0.003° the remainder is below 0.1 µm (crate/tests/ballbar/rotary_trace.rs), far below a
//! ball-bar's resolution; the values found, put into the machine, reproduce the traces through
//! the exact chain (crate/tests/ballbar/rotary_identified_errors_are_the_machines.rs).
//!
//! # What is reported
//! The shared identification in API units ([`crate::identify::Identification`]); what the
//! tests see ([`super::see::RotaryVisibility`], from the fit's own groups) and what each sees alone
//! ([`super::see::RotaryTogether`]); per test the trace, the fit and the residual, with the rms
//! **before** (the measured trace less its mean per direction) and **after** correction (the
//! residual, what the model predicts once the errors found are entered); the errors found
//! present as `errors` for `machine.errors` and in words with the number to enter
//! ([`crate::identify::correct`]).

use super::see::{self, Point, RotaryTogether, RotaryVisibility};
use super::{BallbarRotaryInput, Study, MIN_POINTS};
use crate::ballbar::read::{read_points, Rules, TraceFile};
use crate::edge::Checked;
use crate::error::{Error, Result};
use crate::identify::correct::{found, Correction};
use crate::identify::{self, amount, DecisionInput, Identification, Options, Param};
use crate::machine::errors::ErrorValues;
use crate::schema::{DefaultValue, Kind, Quantity};
use serde::Serialize;

crate::inputs! {
    /// The identification's own inputs (with a [`BallbarRotaryInput`]).
    pub struct BallbarRotaryIdentifyInput {
        /// A file of traces with a `test` column, or the trace of the only test; empty: each
        /// test's own `csv`.
        pub csv: String = "csv" optional {
            label: "Measured traces (CSV)",
            help: "Angle of the moving axis (deg), the bar's length change (µm or mm) and the direction (ccw/cw) per line, units in the header; a test column names each line's test (by name or number). Empty: each test's own file.",
            kind: Kind::Text { max_len: 5_000_000 },
            default: DefaultValue::Str(""),
            group: "Identification",
        },
        /// Relative singular-value threshold of the rank decision.
        pub rtol: f64 = "rtol" optional {
            label: "Rank threshold (relative singular value)",
            help: "Directions below it count as not identifiable (0.01: condition number 100).",
            kind: Kind::Number { quantity: Quantity::Number, min: 1e-12, max: 0.5, exclusive_min: false },
            default: DefaultValue::Num(identify::DEFAULT_RTOL),
            group: "Identification",
        },
        /// How the values are judged.
        pub decision: DecisionInput = "decision" optional {
            label: "Decision",
            kind: Kind::Object(DecisionInput::FIELDS),
            default: DefaultValue::Empty,
        },
    }
}

impl Checked for BallbarRotaryIdentifyInput {}

/// One test's trace, fitted.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct RotaryTestFit {
    /// The test's name.
    pub name: String,
    /// The moving axis's letter.
    pub axis: char,
    /// Points measured.
    pub points: usize,
    /// The file's line of each point.
    pub lines: Vec<usize>,
    /// The moving axis's command per point, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees_series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub angle: Vec<f64>,
    /// +1 ccw, −1 cw, per point.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub run: Vec<f64>,
    /// The measured length change, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub measured: Vec<f64>,
    /// The fitted model (errors and offsets), mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub fitted: Vec<f64>,
    /// Measured − fitted, mm.
    #[serde(serialize_with = "crate::edge::series")]
    #[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]
    pub residual: Vec<f64>,
    /// rms of the measured trace less its mean per direction, mm (before correction).
    pub before: f64,
    /// rms of the residual, mm (after correction, predicted).
    pub after: f64,
    /// Largest minus smallest measured length change over the test, both directions, mm: the
    /// deviation range a tolerance of the test is set on (ISO 10791-6 style).
    pub range: f64,
    /// Largest minus smallest residual, mm: the range the model predicts once the errors found
    /// are entered (the offsets, the bar's length and set-up, stay).
    pub range_after: f64,
}

/// The identification's result.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct BallbarRotaryIdentification {
    /// Per test.
    pub tests: Vec<RotaryTestFit>,
    /// The fit and its decisions, in mm and degrees (errors, then the offsets).
    pub identification: Identification,
    /// What the tests can see of the errors fitted.
    pub visibility: RotaryVisibility,
    /// What each test sees alone and what they see together.
    pub together: RotaryTogether,
    /// The errors found present, in words and as numbers to enter.
    pub corrections: Vec<Correction>,
    /// The errors found present by ISO name, mm and degrees (radians in Rust): put it into
    /// `machine.errors` as it is.
    #[serde(serialize_with = "crate::machine::errors::api_values")]
    #[cfg_attr(feature = "ts", tsify(type = "Partial<Record<string, number>>"))]
    pub errors: ErrorValues,
    /// Columns of the files the reader did not use.
    pub ignored: Vec<String>,
    /// The conclusions in words, most important first.
    pub summary: Vec<String>,
}

/// One measured point of a file.
#[derive(Debug, Clone, Copy)]
struct Measured {
    test: usize,
    line: usize,
    angle: f64,
    direction: f64,
    value: f64,
}

/// The points of the files, per test (module docs), and the columns not used.
fn gather(study: &Study, own: &BallbarRotaryIdentifyInput) -> Result<(Vec<Measured>, Vec<String>)> {
    let rules = Rules {
        deviation_unit: None,
    };
    let mut out = Vec::new();
    let mut ignored: Vec<String> = Vec::new();
    let named = |label: &str| -> Option<usize> {
        study
            .tests
            .iter()
            .position(|t| t.name.eq_ignore_ascii_case(label))
            .or_else(|| {
                label
                    .parse::<usize>()
                    .ok()
                    .filter(|n| (1..=study.tests.len()).contains(n))
                    .map(|n| n - 1)
            })
    };
    let mut take = |file: TraceFile, field: &str, only: Option<usize>| -> Result<()> {
        for c in &file.ignored {
            if !ignored.contains(c) {
                ignored.push(c.clone());
            }
        }
        for p in file.points {
            let test = match (&p.test, only) {
                (Some(label), _) => {
                    let i = named(label).ok_or_else(|| {
                        Error::field(
                            field,
                            format!(
                                "line {}: test \"{label}\" is not one of the tests ({})",
                                p.line,
                                study
                                    .tests
                                    .iter()
                                    .map(|t| t.name.as_str())
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            ),
                        )
                    })?;
                    if let Some(o) = only.filter(|o| *o != i) {
                        return Err(Error::field(
                            field,
                            format!(
                                "line {}: test \"{label}\" in the file of test {}",
                                p.line, study.tests[o].name
                            ),
                        ));
                    }
                    i
                }
                (None, Some(o)) => o,
                (None, None) if study.tests.len() == 1 => 0,
                (None, None) => {
                    return Err(Error::field(
                        field,
                        format!(
                            "the file has no test column but {} tests are defined: add a test column naming each line's test, or give each test its own csv",
                            study.tests.len()
                        ),
                    ))
                }
            };
            let t = &study.tests[test];
            if !study.within(t, p.angle) {
                return Err(Error::field(
                    field,
                    format!(
                        "line {}: {} = {}° is outside its travel",
                        p.line,
                        t.letters[0],
                        (p.angle.to_degrees() * 1e6).round() / 1e6
                    ),
                ));
            }
            out.push(Measured {
                test,
                line: p.line,
                angle: p.angle,
                direction: p.direction,
                value: p.deviation,
            });
        }
        Ok(())
    };
    let relabel = |e: Error, field: &str| Error::field(field, e.message);
    if own.csv.trim().is_empty() && study.tests.iter().all(|t| t.csv.trim().is_empty()) {
        return Err(Error::field(
            "csv",
            "give the measured traces: a file whose test column names each line's test, or each test's own csv",
        ));
    }
    if !own.csv.trim().is_empty() {
        take(read_points(&own.csv, rules)?, "csv", None)?;
    }
    for (i, t) in study.tests.iter().enumerate() {
        if t.csv.trim().is_empty() {
            continue;
        }
        let field = format!("tests[{i}].csv");
        let file = read_points(&t.csv, rules).map_err(|e| relabel(e, &field))?;
        take(file, &field, Some(i))?;
    }
    for (i, t) in study.tests.iter().enumerate() {
        let n = out.iter().filter(|p| p.test == i).count();
        if n < MIN_POINTS {
            return Err(Error::field(
                if own.csv.trim().is_empty() {
                    format!("tests[{i}].csv")
                } else {
                    "csv".to_string()
                },
                format!(
                    "test {} has {n} measured point{}: give at least {MIN_POINTS} round its sweep",
                    t.name,
                    if n == 1 { "" } else { "s" }
                ),
            ));
        }
    }
    Ok((out, ignored))
}

/// Identifies the errors from the measured traces (module docs).
pub fn identify(
    (case, own): &(BallbarRotaryInput, BallbarRotaryIdentifyInput),
) -> Result<BallbarRotaryIdentification> {
    let study = Study::new(case)?;
    let (data, ignored) = gather(&study, own)?;
    let points: Vec<Point> = data
        .iter()
        .map(|p| Point {
            test: p.test,
            angle: p.angle,
            direction: p.direction,
        })
        .collect();
    let d: Vec<f64> = data.iter().map(|p| p.value).collect();
    identify_points(&study, &points, &d, own.rtol, &own.decision.options()).map(|mut r| {
        for (ti, tf) in r.tests.iter_mut().enumerate() {
            tf.lines = data
                .iter()
                .filter(|p| p.test == ti)
                .map(|p| p.line)
                .collect();
        }
        r.ignored = ignored;
        r
    })
}

/// Identifies the errors from measured length changes `d` (mm) at `points` (module docs); the
/// tests' `lines` are left empty.
pub fn identify_points(
    study: &Study,
    points: &[Point],
    d: &[f64],
    rtol: f64,
    options: &Options,
) -> Result<BallbarRotaryIdentification> {
    let sys = see::system(study, points)?;
    let ne = study.unknowns.len();
    let labels: Vec<String> = sys
        .offsets
        .iter()
        .map(|&(t, dir)| {
            format!(
                "the bar's length and the balls' set-up in test {} ({}) differ from the nominal by",
                study.tests[t].name,
                if dir > 0.0 { "ccw" } else { "cw" }
            )
        })
        .collect();
    let params: Vec<Param> = (0..sys.names.len())
        .map(|j| {
            if j < ne {
                Param::error(study.unknowns[j].name)
            } else {
                Ok(Param {
                    name: &sys.names[j],
                    quantity: Quantity::SmallLength,
                    def: None,
                    label: &labels[j - ne],
                })
            }
        })
        .collect::<Result<_>>()?;
    let judgement = identify::identify(&sys.a, &params, d, rtol, options).map_err(|e| {
        if e.field == "fit" {
            Error::field("csv", e.message)
        } else {
            e
        }
    })?;
    let visibility = see::visibility(study, &sys, &judgement.fit);
    let together = see::together(study, &sys, points, rtol)?;
    let (errors, corrections) = found(&judgement, &sys.defs)?;
    let f = &judgement.fit;
    let mut tests = Vec::with_capacity(study.tests.len());
    let mut summary = Vec::new();
    for (ti, t) in study.tests.iter().enumerate() {
        let idx: Vec<usize> = (0..points.len())
            .filter(|&i| points[i].test == ti)
            .collect();
        let measured: Vec<f64> = idx.iter().map(|&i| d[i]).collect();
        let run: Vec<f64> = idx.iter().map(|&i| points[i].direction).collect();
        // Before: less the mean of each direction.
        let mean = |dir: f64| {
            let v: Vec<f64> = idx
                .iter()
                .filter(|&&i| points[i].direction == dir)
                .map(|&i| d[i])
                .collect();
            v.iter().sum::<f64>() / v.len().max(1) as f64
        };
        let (mc, mw) = (mean(1.0), mean(-1.0));
        let rms = |v: &mut dyn Iterator<Item = f64>, n: usize| {
            (v.map(|x| x * x).sum::<f64>() / n.max(1) as f64).sqrt()
        };
        let n = idx.len();
        let before = rms(
            &mut idx
                .iter()
                .map(|&i| d[i] - if points[i].direction > 0.0 { mc } else { mw }),
            n,
        );
        let residual: Vec<f64> = idx.iter().map(|&i| f.residuals[i]).collect();
        let after = rms(&mut residual.iter().copied(), n);
        summary.push(format!(
            "Test {} ({} moving, {} bar, {n} points): the bar's length varies by {} rms about its mean; with the errors found entered the model predicts {} rms.",
            t.name,
            t.letters[0],
            t.direction.value(),
            amount(Quantity::SmallLength, before),
            amount(Quantity::SmallLength, after),
        ));
        tests.push(RotaryTestFit {
            name: t.name.clone(),
            axis: t.letters[0],
            points: n,
            lines: Vec::new(),
            angle: idx.iter().map(|&i| points[i].angle).collect(),
            run,
            measured: measured.clone(),
            fitted: idx.iter().map(|&i| f.fitted[i]).collect(),
            range: super::range(&measured),
            range_after: super::range(&residual),
            residual,
            before,
            after,
        });
    }
    // The shared summary, less the combinations that mix errors with the offsets (an arbitrary
    // basis of such a group; `visibility` says what they mean).
    let mixed: Vec<&str> = judgement
        .combinations
        .iter()
        .filter(|c| {
            f.groups[c.group]
                .members
                .iter()
                .any(|n| sys.names[ne..].contains(n))
        })
        .map(|c| c.words.as_str())
        .collect();
    // The shared summary's "cannot see at all" of an error the visibility explains (why the bar
    // misses it) is said once, by the visibility.
    let unseen_said = |w: &str| {
        w.starts_with("The test cannot see ")
            && visibility
                .invisible
                .iter()
                .any(|u| w.contains(u.name.as_str()))
    };
    summary.extend(
        judgement
            .summary
            .iter()
            .filter(|w| !mixed.contains(&w.as_str()) && !unseen_said(w))
            .cloned(),
    );
    summary.extend(
        visibility
            .invisible
            .iter()
            .map(|u| format!("{}: {}", u.name, u.why)),
    );
    summary.extend(visibility.inseparable.iter().map(|g| g.why.clone()));
    summary.push(together.words.clone());
    Ok(BallbarRotaryIdentification {
        tests,
        identification: judgement.identification(),
        visibility,
        together,
        corrections,
        errors,
        ignored: Vec::new(),
        summary,
    })
}
