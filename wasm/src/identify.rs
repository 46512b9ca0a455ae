//! The identification's results at the edge, shared by `sshapeIdentify` and `cubicIdentify`
//! (see `fiveaxis::identify`): values, standard errors and intervals in mm and degrees, the
//! decision per error and per identifiable combination, the goodness of fit and the words.

use crate::{api_combination, error_quantity};
use fiveaxis::identify::{combination_text, Judgement, Verdict};
use serde::Serialize;
use tsify::Tsify;

/// One parameter of a fit, with its decision.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct IdentifiedError {
    /// ISO name, or "dR" (the S-shape's tool radius).
    pub name: String,
    /// "mm" or "deg".
    pub unit: String,
    /// Null when not identifiable on its own.
    pub value: Option<f64>,
    /// Its standard error, null likewise.
    pub std_error: Option<f64>,
    /// The 95 % interval `[low, high]`, null likewise.
    pub interval: Option<[f64; 2]>,
    /// value / standard error.
    pub t: Option<f64>,
    /// Holm-adjusted p-value (the family-wise test).
    pub p_adjusted: Option<f64>,
    /// "present" | "below-tolerance" | "not-distinguishable" | "not-identifiable".
    pub verdict: Verdict,
    /// Largest effect on the measured values, mm.
    pub effect: f64,
    /// What it means, in words (empty when not identifiable).
    pub words: String,
    /// The minimum-norm value (a convention where not identifiable).
    pub min_norm: f64,
    /// Index into groups when it cannot be separated from others.
    pub group: Option<usize>,
}

/// An identifiable combination Σ c·x (x in mm and degrees) of inseparable errors.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct IdentifiedCombination {
    /// (name, coefficient); the first coefficient is 1.
    pub terms: Vec<(String, f64)>,
    /// Its value, in the first member's unit.
    pub value: f64,
    /// Its standard error.
    pub std_error: f64,
    /// The 95 % interval.
    pub interval: [f64; 2],
    /// Holm-adjusted p-value.
    pub p_adjusted: f64,
    /// "present" or "not-distinguishable".
    pub verdict: Verdict,
    /// Readable form.
    pub text: String,
    /// In words.
    pub words: String,
}

/// Errors the test cannot separate.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct IdentifiedGroup {
    /// The errors.
    pub members: Vec<String>,
    /// Weak directions among them.
    pub deficiency: usize,
    /// What can be identified of them (none: the test cannot see them at all).
    pub combinations: Vec<IdentifiedCombination>,
}

/// Do the errors explain the measurement?
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct GoodnessOfFit {
    /// The stated noise, mm (null: not given).
    pub noise: Option<f64>,
    /// The residual's standard deviation, mm.
    pub sigma: f64,
    /// Degrees of freedom.
    pub dof: usize,
    /// χ² p-value (null without a stated noise).
    pub p: Option<f64>,
    /// false: they do not (p < 1 %); null: not checked.
    pub explains: Option<bool>,
    /// In words.
    pub words: String,
}

/// A fit and its decisions.
#[derive(Serialize, Tsify)]
#[tsify(missing_as_null, hashmap_as_object)]
#[serde(rename_all = "camelCase")]
pub struct Identification {
    /// Per parameter.
    pub estimates: Vec<IdentifiedError>,
    /// Inseparable groups.
    pub groups: Vec<IdentifiedGroup>,
    /// Numerical rank.
    pub rank: usize,
    /// Relative singular values of the column-scaled matrix, descending.
    pub singular_values: Vec<f64>,
    /// The rank threshold used.
    pub rtol: f64,
    /// The family-wise false-call rate.
    pub alpha: f64,
    /// The tolerance, mm (null: none).
    pub tolerance: Option<f64>,
    /// The goodness of fit.
    pub goodness: GoodnessOfFit,
    /// The conclusions in words, most important first.
    pub summary: Vec<String>,
}

/// A judgement in API units.
pub(crate) fn identification(j: &Judgement) -> Identification {
    let f = &j.fit;
    let estimates = f
        .estimates
        .iter()
        .zip(&j.decisions)
        .map(|(e, d)| {
            let q = error_quantity(&e.name);
            IdentifiedError {
                name: e.name.clone(),
                unit: q.api_unit().to_string(),
                value: e.value.map(|v| q.to_api(v)),
                std_error: e.std_error.map(|v| q.to_api(v)),
                interval: d.interval.map(|[a, b]| [q.to_api(a), q.to_api(b)]),
                t: d.t,
                p_adjusted: d.p_adjusted,
                verdict: d.verdict,
                effect: d.effect,
                words: d.words.clone(),
                min_norm: q.to_api(e.min_norm),
                group: e.group,
            }
        })
        .collect();
    let groups = f
        .groups
        .iter()
        .enumerate()
        .map(|(gi, g)| IdentifiedGroup {
            members: g.members.clone(),
            deficiency: g.deficiency,
            combinations: g
                .combinations
                .iter()
                .zip(j.combinations.iter().filter(|c| c.group == gi))
                .map(|(c, d)| {
                    let (coefficients, s) =
                        api_combination(c.terms.iter().map(|(n, k)| (n.as_str(), *k)));
                    let terms: Vec<(String, f64)> = c
                        .terms
                        .iter()
                        .zip(coefficients)
                        .map(|((n, _), k)| (n.clone(), k))
                        .collect();
                    IdentifiedCombination {
                        text: combination_text(&terms),
                        terms,
                        value: c.value * s,
                        std_error: c.std_error * s,
                        interval: [d.interval[0] * s, d.interval[1] * s],
                        p_adjusted: d.p_adjusted,
                        verdict: d.verdict,
                        words: d.words.clone(),
                    }
                })
                .collect(),
        })
        .collect();
    Identification {
        estimates,
        groups,
        rank: f.rank,
        singular_values: f.singular_values.clone(),
        rtol: f.rtol,
        alpha: j.options.alpha,
        tolerance: j.options.tolerance,
        goodness: GoodnessOfFit {
            noise: j.goodness.noise,
            sigma: j.goodness.sigma,
            dof: j.goodness.dof,
            p: j.goodness.p,
            explains: j.goodness.explains,
            words: j.goodness.words.clone(),
        },
        summary: j.summary.clone(),
    }
}
