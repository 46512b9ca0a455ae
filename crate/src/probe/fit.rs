//! Identification of the rotary axes' errors from measured centres, with the project's one
//! identification ([`crate::identify`]: least squares by SVD, rank, weak directions, Holm's
//! decisions, intervals, goodness of fit).
//!
//! # The system
//! Per measured pose `i` three rows (X, Y, Z): the data `dᵢ = cᵢ − c₀(Kᵢ, Mᵢ)`, measured minus
//! expected with the sphere where it was stated (mm), and the sensitivities of eq 2 of
//! [`super`] (the errors', and the sphere position's when fitted). Each coordinate is one
//! measurement with the same noise.
//!
//! # The spread of the centres
//! * **Before correction**: the deviations `dᵢ` less the best sphere position alone (least
//!   squares on its three columns; nothing subtracted when the sphere is not fitted): how far
//!   the measured centres wander from a fixed sphere as the rotary axes turn.
//! * **After correction** (what the model predicts once the identified errors are entered): the
//!   fit's residuals.
//!
//! Each reported as `σ = √(Σᵢ|rᵢ|²/(3N))` (one coordinate's rms, mm) and the largest `|rᵢ|`
//! (the 3-D distance of a pose's centre, mm).
//!
//! # The correction
//! An error found present (Holm at the family-wise rate, [`crate::identify::judge`]) is
//! reported in words (`"the C axis line lies 12 µm towards +X of where the control believes it
//! is"`) and as the number to enter: ISO 230-1's sign is the axis's real place minus the
//! control's belief, in the machine frame with all axes at zero, so a position is **added** to
//! the control's value of the axis line's position, a tilt turns the control's axis direction by
//! the angle (right-hand rule, degrees), and a zero error `E_C0C = +ε` (the axis stands at +ε
//! when the control shows 0°) is corrected by shifting the axis's zero by −ε. The same values
//! are the machine's errors: [`ProbeIdentification::errors`] goes into `machine.errors` as it is.

use super::measure::{self, Measurements};
use super::{Study, Unknown, SPHERE_NAMES};
use crate::error::{Error, Result};
use crate::identify::correct::found;
pub use crate::identify::correct::{enter, Correction};
use crate::identify::{self, amount, DecisionInput, Judgement, Options, Param, Verdict};
use crate::machine::errors::ErrorValues;
use crate::schema::{DefaultValue, Kind, Quantity};
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

crate::inputs! {
    /// The identification's own inputs (with a [`super::ProbeInput`]).
    pub struct ProbeIdentifyInput {
        /// The measured centres (module docs of [`super::measure`]).
        pub csv: String = "csv" {
            label: "Measured sphere centres (CSV)",
            help: "One line per pose: K and M (deg), the measured centre X, Y, Z (mm or um), units in the header, e.g. pose;C_deg;A_deg;X_mm;Y_mm;Z_mm. Separators , ; tab or spaces; decimal comma with ; tab or spaces.",
            kind: Kind::Text { max_len: 1_000_000 },
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

impl crate::edge::Checked for ProbeIdentifyInput {}

/// How far the centres wander (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Spread {
    /// One coordinate's rms, mm.
    pub sigma: f64,
    /// Largest 3-D distance of a pose's centre, mm.
    pub max: f64,
}

impl Spread {
    /// Of residuals `r`, 3 per pose.
    pub fn of(r: &[f64]) -> Self {
        let n = (r.len() / 3).max(1);
        let sigma = (r.iter().map(|v| v * v).sum::<f64>() / (3 * n) as f64).sqrt();
        let max = r
            .chunks(3)
            .map(|c| c.iter().map(|v| v * v).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        Self { sigma, max }
    }
}

/// One pose of the measurement, fitted.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct PoseFit {
    /// Its label.
    pub label: String,
    /// K, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub k: f64,
    /// M, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub m: f64,
    /// The measured centre, mm.
    pub measured: [f64; 3],
    /// The centre the control expects with the sphere where it was stated, mm.
    pub expected: [f64; 3],
    /// Before correction: measured minus expected, less the best sphere position, mm.
    pub before: [f64; 3],
    /// After correction (predicted): the fit's residual, mm.
    pub after: [f64; 3],
}

/// One unknown of the fit with its decision, in API units (`unit`: mm or deg).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct Estimate {
    /// ISO name, or `sphere_X` ….
    pub name: String,
    /// "mm" or "deg": the unit of `value`, `stdError` and `interval` (degrees for an angle,
    /// converted once, here, because the list mixes lengths and angles).
    pub unit: String,
    /// The value (null: not identifiable on its own).
    pub value: Option<f64>,
    /// Its standard error.
    pub std_error: Option<f64>,
    /// The 95 % interval.
    pub interval: Option<[f64; 2]>,
    /// Holm-adjusted p-value.
    pub p_adjusted: Option<f64>,
    /// The decision.
    pub verdict: Verdict,
    /// Largest effect on a measured coordinate, mm.
    pub effect: f64,
    /// In words.
    pub words: String,
    /// Index of its group of inseparable unknowns.
    pub group: Option<usize>,
}

/// A group of inseparable unknowns and the combinations measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct GroupFit {
    /// The unknowns.
    pub members: Vec<String>,
    /// The combinations measured (coefficients per mm and per degree), in words.
    pub words: Vec<String>,
}

/// Does the model explain the measurement? ([`crate::identify`]'s goodness of fit.)
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct Goodness {
    /// The stated noise, mm.
    pub noise: Option<f64>,
    /// The residual's standard deviation, mm.
    pub sigma: f64,
    /// Degrees of freedom.
    pub dof: usize,
    /// χ² p-value.
    pub p: Option<f64>,
    /// false: the errors do not explain the measurement.
    pub explains: Option<bool>,
    /// In words.
    pub words: String,
}

/// The identification's result.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct ProbeIdentification {
    /// The file as read.
    pub measurements: Measurements,
    /// Per pose.
    pub poses: Vec<PoseFit>,
    /// Per unknown.
    pub estimates: Vec<Estimate>,
    /// Inseparable groups.
    pub groups: Vec<GroupFit>,
    /// Numerical rank.
    pub rank: usize,
    /// Relative singular values of the column-scaled matrix.
    pub singular_values: Vec<f64>,
    /// The spread of the centres before correction (module docs).
    pub before: Spread,
    /// The spread the model predicts after correction.
    pub after: Spread,
    /// The goodness of fit.
    pub goodness: Goodness,
    /// The errors found present, in words and as numbers to enter.
    pub corrections: Vec<Correction>,
    /// The errors found present by ISO name, mm and degrees (radians in Rust): put it into
    /// `machine.errors` as it is.
    #[serde(serialize_with = "crate::machine::errors::api_values")]
    #[cfg_attr(feature = "ts", tsify(type = "Partial<Record<string, number>>"))]
    pub errors: ErrorValues,
    /// The sphere's centre (stated, plus the fitted shift when fitted), workpiece frame, mm.
    pub sphere: [f64; 3],
    /// The conclusions in words, most important first.
    pub summary: Vec<String>,
    /// The shared identification's judgement (engine units).
    #[serde(skip)]
    #[cfg_attr(feature = "ts", tsify(skip))]
    pub judgement: Judgement,
}

/// The system of the module docs: `A` (3 rows per pose, engine units) and `d`, mm.
pub fn system(study: &Study, poses: &[(f64, f64, [f64; 3])]) -> Result<(DMatrix<f64>, Vec<f64>)> {
    let p = study.unknowns.len();
    let mut a = DMatrix::zeros(3 * poses.len(), p);
    let mut d = Vec::with_capacity(3 * poses.len());
    for (i, &(k, m, c)) in poses.iter().enumerate() {
        let s = study.sensitivities(k, m)?;
        for (j, v) in s.iter().enumerate() {
            for r in 0..3 {
                a[(3 * i + r, j)] = v[r];
            }
        }
        let e = study.expected(k, m)?;
        for r in 0..3 {
            d.push(c[r] - e[r]);
        }
    }
    Ok((a, d))
}

/// Identifies the errors from measured centres (module docs).
pub fn identify_centres(
    study: &Study,
    measurements: Measurements,
    rtol: f64,
    options: &Options,
) -> Result<ProbeIdentification> {
    let list: Vec<(f64, f64, [f64; 3])> = measurements
        .poses
        .iter()
        .map(|p| (p.k, p.m, p.centre))
        .collect();
    for p in &measurements.poses {
        if !study.reachable(p.k, p.m)? {
            let [kl, ml] = study.model.letters();
            return Err(Error::field(
                "csv",
                format!(
                    "line {}: the pose {kl} = {}°, {ml} = {}° is outside the travel or the tilt limit",
                    p.line,
                    p.k.to_degrees(),
                    p.m.to_degrees()
                ),
            ));
        }
    }
    let (a, d) = system(study, &list)?;
    let params: Vec<Param> = study
        .unknowns
        .iter()
        .map(|u| match u {
            Unknown::Error(def) => Param::error(def.name),
            Unknown::Sphere(i) => Ok(Param {
                name: SPHERE_NAMES[*i],
                quantity: Quantity::SmallLength,
                def: None,
                label: "the sphere's position differs from the stated one by",
            }),
        })
        .collect::<Result<_>>()?;
    let judgement = identify::identify(&a, &params, &d, rtol, options).map_err(|e| {
        if e.field == "fit" {
            Error::field("csv", e.message)
        } else {
            e
        }
    })?;
    // Before: less the best sphere position alone.
    let sphere_cols: Vec<usize> = (0..study.unknowns.len())
        .filter(|&j| matches!(study.unknowns[j], Unknown::Sphere(_)))
        .collect();
    let before: Vec<f64> = if sphere_cols.is_empty() {
        d.clone()
    } else {
        let s = DMatrix::from_fn(a.nrows(), 3, |r, c| a[(r, sphere_cols[c])]);
        let dv = DVector::from_column_slice(&d);
        let x = s
            .clone()
            .svd(true, true)
            .solve(&dv, 1e-12)
            .map_err(|e| Error::field("fit", e.to_string()))?;
        (dv - s * x).iter().copied().collect()
    };
    let f = &judgement.fit;
    let after = f.residuals.clone();
    let poses: Vec<PoseFit> = measurements
        .poses
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let e = study.expected(p.k, p.m)?;
            Ok(PoseFit {
                label: p.label.clone(),
                k: p.k,
                m: p.m,
                measured: p.centre,
                expected: [e[0], e[1], e[2]],
                before: [before[3 * i], before[3 * i + 1], before[3 * i + 2]],
                after: [after[3 * i], after[3 * i + 1], after[3 * i + 2]],
            })
        })
        .collect::<Result<_>>()?;
    let estimates: Vec<Estimate> = study
        .unknowns
        .iter()
        .zip(&judgement.decisions)
        .map(|(u, dcs)| {
            let q = u.quantity();
            Estimate {
                name: dcs.name.clone(),
                unit: q.api_unit().to_string(),
                value: dcs.value.map(|v| q.to_api(v)),
                std_error: dcs.std_error.map(|v| q.to_api(v)),
                interval: dcs.interval.map(|[lo, hi]| [q.to_api(lo), q.to_api(hi)]),
                p_adjusted: dcs.p_adjusted,
                verdict: dcs.verdict,
                effect: dcs.effect,
                words: dcs.words.clone(),
                group: f
                    .estimates
                    .iter()
                    .find(|e| e.name == dcs.name)
                    .and_then(|e| e.group),
            }
        })
        .collect();
    let groups: Vec<GroupFit> = f
        .groups
        .iter()
        .enumerate()
        .map(|(gi, g)| GroupFit {
            members: g.members.clone(),
            words: judgement
                .combinations
                .iter()
                .filter(|c| c.group == gi)
                .map(|c| c.words.clone())
                .chain(
                    g.combinations
                        .is_empty()
                        .then(|| format!("The poses cannot see {} at all.", g.members.join(", "))),
                )
                .collect(),
        })
        .collect();
    let defs: Vec<Option<&'static crate::machine::errors::ErrorDef>> = study
        .unknowns
        .iter()
        .map(|u| match u {
            Unknown::Error(d) => Some(*d),
            Unknown::Sphere(_) => None,
        })
        .collect();
    let (errors, corrections) = found(&judgement, &defs)?;
    let mut sphere = study.sphere;
    for (u, e) in study.unknowns.iter().zip(&f.estimates) {
        if let Unknown::Sphere(i) = u {
            sphere[*i] += e.value.unwrap_or(e.min_norm);
        }
    }
    let before_s = Spread::of(&before);
    let after_s = Spread::of(&after);
    let mut summary = vec![format!(
        "The sphere's centre wanders by {} (1σ per coordinate, {} at most) as the rotary axes turn; with the errors found entered the model predicts {} ({} at most).",
        amount(Quantity::SmallLength, before_s.sigma),
        amount(Quantity::SmallLength, before_s.max),
        amount(Quantity::SmallLength, after_s.sigma),
        amount(Quantity::SmallLength, after_s.max),
    )];
    summary.extend(judgement.summary.iter().cloned());
    let g = &judgement.goodness;
    Ok(ProbeIdentification {
        measurements,
        poses,
        estimates,
        groups,
        rank: f.rank,
        singular_values: f.singular_values.clone(),
        before: before_s,
        after: after_s,
        goodness: Goodness {
            noise: g.noise,
            sigma: g.sigma,
            dof: g.dof,
            p: g.p,
            explains: g.explains,
            words: g.words.clone(),
        },
        corrections,
        errors,
        sphere: [sphere[0], sphere[1], sphere[2]],
        summary,
        judgement,
    })
}

/// Reads the file and identifies (the export's engine function). The model-fit check uses the
/// decision's measurement noise, or, left empty, the probing noise of the study: the probe's
/// one noise, stated once, is what the residuals are checked against.
pub fn identify_file(study: &Study, own: &ProbeIdentifyInput) -> Result<ProbeIdentification> {
    let m = measure::read(&own.csv, Some(study.model.letters()))?;
    let mut options = own.decision.options();
    options.noise = options.noise.or(Some(study.noise));
    identify_centres(study, m, own.rtol, &options)
}
