//! The identification as the API gives it (`sshapeIdentify`, `cubicIdentify`): values,
//! standard errors and intervals in mm and **degrees** (an angular error's engine value is in
//! radians), the decision per error and per identifiable combination, the goodness of fit and
//! the words. [`Judgement::identification`] computes it once from the judgement.

use super::{combination_text, Combination, Fit, GoodnessOfFit, Judgement, Verdict};
use crate::machine::errors;
use crate::schema::Quantity;
use serde::Serialize;

/// The quantity of a parameter by name: an error's from the error table; names not in it
/// (`"dR"`, the S-shape's tool radius) are small lengths.
pub fn error_quantity(name: &str) -> Quantity {
    errors::find(name).map_or(Quantity::SmallLength, |d| d.quantity)
}

/// A combination `Σ c_j·x_j` of errors (by name, engine units: mm, rad) in API units (mm,
/// degrees), its first member's coefficient kept: `c'_j = c_j·p_j/p_1`, where `p` is
/// [`Quantity::per_api_unit`] of 1 (π/180 for an angle, 1 for a length). Returns the new
/// coefficients and the factor `1/p_1` that turns the combination's value (in the first
/// member's engine unit) into API units.
pub fn api_combination<'a>(terms: impl IntoIterator<Item = (&'a str, f64)>) -> (Vec<f64>, f64) {
    let per = |name: &str| error_quantity(name).per_api_unit(1.0);
    let terms: Vec<(&str, f64)> = terms.into_iter().collect();
    let first = terms.first().map_or(1.0, |(n, _)| per(n));
    let coefficients = terms.iter().map(|(n, c)| c * per(n) / first).collect();
    (coefficients, 1.0 / first)
}

/// A combination's terms in API units ([`api_combination`]): `(name, coefficient)`, the first
/// coefficient 1, and the factor that turns its value into the first member's API unit.
pub fn api_terms(c: &Combination) -> (Vec<(String, f64)>, f64) {
    let (coefficients, s) = api_combination(c.terms.iter().map(|(n, k)| (n.as_str(), *k)));
    let terms = c
        .terms
        .iter()
        .zip(coefficients)
        .map(|((n, _), k)| (n.clone(), k))
        .collect();
    (terms, s)
}

/// A combination's readable form in API units (x in mm and degrees), e.g.
/// `E_A0Z − 1.0006·E_A0C`.
pub fn api_text(c: &Combination) -> String {
    combination_text(&api_terms(c).0)
}

/// One parameter of a fit, with its decision (values in mm or degrees, by `unit`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[cfg_attr(feature = "ts", tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct IdentifiedError {
    /// ISO name, or "dR" (the S-shape's tool radius).
    pub name: String,
    /// "mm" or "deg".
    #[cfg_attr(feature = "ts", tsify(type = "\"mm\" | \"deg\""))]
    pub unit: &'static str,
    /// Its value, mm or degrees; null when not identifiable on its own.
    pub value: Option<f64>,
    /// Its standard error, mm or degrees; null likewise.
    pub std_error: Option<f64>,
    /// The 95 % interval `[low, high]`, mm or degrees; null likewise.
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
    /// The minimum-norm value, mm or degrees (a convention where not identifiable).
    pub min_norm: f64,
    /// Index into groups when it cannot be separated from others.
    pub group: Option<usize>,
}

/// An identifiable combination Σ c·x (x in mm and degrees) of inseparable errors.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct IdentifiedCombination {
    /// (name, coefficient); the first coefficient is 1.
    pub terms: Vec<(String, f64)>,
    /// Its value, in the first member's unit (mm or degrees).
    pub value: f64,
    /// Its standard error, likewise.
    pub std_error: f64,
    /// The 95 % interval, likewise.
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
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct IdentifiedGroup {
    /// The errors.
    pub members: Vec<String>,
    /// Weak directions among them.
    pub deficiency: usize,
    /// What can be identified of them (none: the test cannot see them at all).
    pub combinations: Vec<IdentifiedCombination>,
}

/// A fit and its decisions, in API units (module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[cfg_attr(feature = "ts", tsify(missing_as_null))]
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

impl Judgement {
    /// The judgement in API units (module docs).
    pub fn identification(&self) -> Identification {
        let f: &Fit = &self.fit;
        let estimates = f
            .estimates
            .iter()
            .zip(&self.decisions)
            .map(|(e, d)| {
                let q = error_quantity(&e.name);
                IdentifiedError {
                    name: e.name.clone(),
                    unit: q.api_unit(),
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
                    .zip(self.combinations.iter().filter(|c| c.group == gi))
                    .map(|(c, d)| {
                        let (terms, s) = api_terms(c);
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
            alpha: self.options.alpha,
            tolerance: self.options.tolerance,
            goodness: self.goodness.clone(),
            summary: self.summary.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    //! Unit conversions worked out by hand, with π/180 written here, not taken from the engine.
    use super::*;

    const DEG: f64 = std::f64::consts::PI / 180.0;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()))
    }

    /// Angular location errors and error motions are small angles, linear ones small lengths, and a
    /// name outside the table (the tool-radius error `dR`) is a small length (ISO 230-1: `E_A..`,
    /// `E_B..`, `E_C..` are rotations, `E_X..`, `E_Y..`, `E_Z..` displacements).
    #[test]
    fn error_names_have_the_quantity_of_their_iso_letter() {
        assert_eq!(error_quantity("E_A0B"), Quantity::SmallAngle);
        assert_eq!(error_quantity("E_C0C"), Quantity::SmallAngle);
        assert_eq!(error_quantity("E_X0B"), Quantity::SmallLength);
        assert_eq!(error_quantity("E_Y0C"), Quantity::SmallLength);
        assert_eq!(error_quantity("dR"), Quantity::SmallLength);
    }

    /// A combination `Σ c_j·x_j` (engine units, x in mm or rad) equals, in the first member's API
    /// unit, `Σ c'_j·y_j` with `y` the same errors in API units (mm or degrees): with a length first
    /// the angle's coefficient is multiplied by π/180; with an angle first the length's is multiplied
    /// by 180/π and the value is turned into degrees (× 180/π).
    #[test]
    fn api_combination_keeps_the_value_of_the_combination_in_api_units() {
        // Length first: x = (0.01 mm, 0.02° = 0.02·π/180 rad).
        let (c, f) = api_combination([("E_X0B", 1.0), ("E_A0B", 250.0)]);
        assert!(close(f, 1.0), "{f}");
        assert_eq!(c.len(), 2);
        assert!(close(c[0], 1.0) && close(c[1], 250.0 * DEG), "{c:?}");
        let (y, x) = ([0.01, 0.02], [0.01, 0.02 * DEG]);
        let engine = 1.0 * x[0] + 250.0 * x[1];
        assert!(close(c[0] * y[0] + c[1] * y[1], engine * f));

        // Angle first: the value comes out in degrees.
        let (c, f) = api_combination([("E_B0C", 2.0), ("E_Y0C", -0.5), ("E_C0B", 3.0)]);
        assert!(close(f, 1.0 / DEG), "{f}");
        assert!(
            close(c[0], 2.0) && close(c[1], -0.5 / DEG) && close(c[2], 3.0),
            "{c:?}"
        );
        let (y, x) = ([0.03, 0.2, -0.01], [0.03 * DEG, 0.2, -0.01 * DEG]);
        let engine = 2.0 * x[0] - 0.5 * x[1] + 3.0 * x[2];
        assert!(close(c[0] * y[0] + c[1] * y[1] + c[2] * y[2], engine * f));
    }

    /// No terms: no coefficients, and a factor of one (nothing to convert).
    #[test]
    fn api_combination_of_nothing_is_empty() {
        let (c, f) = api_combination(std::iter::empty::<(&str, f64)>());
        assert!(c.is_empty());
        assert_eq!(f, 1.0);
    }
}
