//! Identification of a machine's errors from a measured test piece, one module for every test
//! piece (the S-shape of Chanal et al. 2022, Section 6; the cubic-machining test of Li et al.
//! 2021, whose Section 6 asks for "a machining test condition that can identify each geometric
//! error individually").
//!
//! # The model
//! A test piece gives `m` measured values `d` (deviations, zone heights, slopes), linear to first
//! order in the `p` errors `x`: `d = A·x + e`, `A` the chain's sensitivities at each measurement's
//! pose ([`crate::machine::Model::error_column`], [`crate::chain::Chain::jacobian`]), `e` the
//! measurement noise, independent, standard deviation σ.
//!
//! # The fit ([`fit`])
//! Least squares on the column-scaled matrix by SVD: the numerical rank `r` counts the relative
//! singular values above `rtol` (0.01 by default: a condition number of 100). Errors with weight
//! in the other, **weak directions** get no value of their own; their groups, and the
//! combinations of them the data do determine, come from the projector onto the weak directions
//! (unique, unlike the singular vectors). The covariance of the values is `σ̂²·(AᵀA)⁺` on the
//! strong directions, with `σ̂² = ‖d − A·x̂‖²/(m − r)` from the residual (`m − r` degrees of
//! freedom).
//!
//! # The decision ([`judge`])
//! * **Family-wise**: for every value and every identifiable combination, `t = x̂/se` and its
//!   two-sided p-value from Student's t with `m − r` degrees of freedom ([`stats`]). Holm's
//!   step-down over the whole family: sort the `n` p-values, `p(1) ≤ … ≤ p(n)`; reject while
//!   `p(i) ≤ α/(n − i + 1)`, stop at the first that is not. The probability that *any* error
//!   which is zero is reported as present is then at most α (5 % by default) whatever the
//!   dependence between the tests; testing each at 2σ, as the page used to, gives about
//!   1 − 0.954ⁿ (21.5 % observed for the S-shape's 8 + 1 parameters). Adjusted p-values:
//!   `p̃(i) = max_{j ≤ i} min(1, (n − j + 1)·p(j))`, reject where `p̃ ≤ α`.
//! * **Practical**: an error found present is compared with a tolerance by its effect, the
//!   largest `|A_kj·x̂_j|` over the measurements (mm): below the tolerance it is "present, but
//!   smaller than the tolerance".
//! * **Interval**: `x̂ ± t_{ν, (1+level)/2}·se` (95 % by default), each covering the truth at
//!   its stated rate (Monte-Carlo test `crate/tests/identify/monte_carlo.rs`).
//! * **Goodness of fit**: with the stated measurement noise `σ₀`, `‖d − A·x̂‖²/σ₀²` follows χ²
//!   with `m − r` degrees of freedom when the errors explain the measurement; a p-value below 1 %
//!   says they do not (a set-up error, a thermal drift, or an error the model lacks), and the
//!   values are then not to be trusted.
//!
//! # Degenerate cases
//! An error with no effect at all is a group of one with no identifiable combination ("the test
//! cannot see it"); `m ≤ r` (no measurement left over to estimate σ) is an error of the fit; a
//! zero residual gives `se = 0` and every non-zero value is found (with a `p` of 0).

pub mod correct;
pub mod csv;
mod fit;
mod result;
pub mod stats;

pub use fit::{combination_text, fit, Combination, Estimate, Fit, Group, DEFAULT_RTOL};
pub use result::{
    api_combination, api_terms, api_text, error_quantity, Identification, IdentifiedCombination,
    IdentifiedError, IdentifiedGroup,
};

use crate::error::{check_range, Error, Result};
use crate::machine::errors::{self, ErrorDef};
use crate::schema::Quantity;
use nalgebra::DMatrix;
use serde::Serialize;

/// Default family-wise false-call rate.
pub const DEFAULT_ALPHA: f64 = 0.05;
/// Default level of the intervals.
pub const DEFAULT_LEVEL: f64 = 0.95;
/// A goodness-of-fit p-value below this says the errors do not explain the measurement.
pub const MISFIT_P: f64 = 0.01;

/// How the values are judged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Family-wise false-call rate α (0 < α < 0.5).
    pub alpha: f64,
    /// Level of the intervals (0.5 ≤ level < 1).
    pub level: f64,
    /// The stated measurement noise, one standard deviation, mm (same unit as the data).
    pub noise: Option<f64>,
    /// The tolerance an error's effect is compared with, mm.
    pub tolerance: Option<f64>,
}

crate::inputs! {
    /// How identified errors are judged: the inputs every identification shares (module docs).
    pub struct DecisionInput {
        /// Family-wise false-call rate.
        pub alpha: f64 = "alpha" optional {
            label: "Chance of reporting an error that is not there",
            help: "For the whole set of errors together (Holm's step-down on the t statistics): 0.05 means that in at most 5 % of parts any error that is zero is reported as present.",
            kind: crate::schema::Kind::Number { quantity: Quantity::Number, min: 0.001, max: 0.2, exclusive_min: false },
            default: crate::schema::DefaultValue::Num(DEFAULT_ALPHA),
            group: "Decision",
        },
        /// Stated measurement noise, mm.
        pub noise: Option<f64> = "noise" optional {
            label: "Measurement noise (one standard deviation)",
            help: "Of the measuring instrument on this part. Used to check that the errors explain the measurement (the residual should be about this size); leave empty to skip the check.",
            kind: crate::schema::positive(Quantity::SmallLength, 1.0),
            group: "Decision",
        },
        /// Tolerance of an error's effect, mm (0: none).
        pub tolerance: f64 = "tolerance" optional {
            label: "Tolerance: smallest effect worth correcting",
            help: "An error that is present but moves the part by less than this (at its worst measured point) is reported as below the tolerance; 0: every error found is reported as present.",
            kind: crate::schema::number(Quantity::SmallLength, 0.0, 10.0),
            default: crate::schema::DefaultValue::Num(0.001),
            group: "Decision",
        },
    }
}

impl DecisionInput {
    /// The options of [`judge`] (intervals at 95 %).
    pub fn options(&self) -> Options {
        Options {
            alpha: self.alpha,
            level: DEFAULT_LEVEL,
            noise: self.noise,
            tolerance: (self.tolerance > 0.0).then_some(self.tolerance),
        }
    }
}

impl Default for Options {
    fn default() -> Self {
        Self {
            alpha: DEFAULT_ALPHA,
            level: DEFAULT_LEVEL,
            noise: None,
            tolerance: None,
        }
    }
}

/// What is concluded about one error (or one combination).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// The test cannot determine it on its own (a weak direction).
    NotIdentifiable,
    /// Not distinguishable from zero at the family-wise rate.
    NotDistinguishable,
    /// Present (family-wise test), but its effect is below the tolerance.
    BelowTolerance,
    /// Present, and its effect reaches the tolerance (or no tolerance was given).
    Present,
}

/// The decision on one parameter of the fit.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Decision {
    /// The parameter's name (`E_X0B`, `dR`).
    pub name: String,
    /// The value, engine units (mm, rad), `None` when not identifiable.
    pub value: Option<f64>,
    /// Its standard error.
    pub std_error: Option<f64>,
    /// The interval `[low, high]` at [`Options::level`].
    pub interval: Option<[f64; 2]>,
    /// `value/std_error`.
    pub t: Option<f64>,
    /// Holm-adjusted p-value.
    pub p_adjusted: Option<f64>,
    /// The verdict.
    pub verdict: Verdict,
    /// Its largest effect on the measurements, mm.
    pub effect: f64,
    /// What it means, in words.
    pub words: String,
}

/// The decision on an identifiable combination of inseparable errors.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct CombinationDecision {
    /// Index of its group in [`Fit::groups`].
    pub group: usize,
    /// The combination.
    pub combination: Combination,
    /// The interval at [`Options::level`], the lead term's unit.
    pub interval: [f64; 2],
    /// Holm-adjusted p-value.
    pub p_adjusted: f64,
    /// The verdict (never `NotIdentifiable`).
    pub verdict: Verdict,
    /// In words.
    pub words: String,
}

/// Does the fit explain the measurement?
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[cfg_attr(feature = "ts", tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct GoodnessOfFit {
    /// The stated noise, mm (null: not given).
    pub noise: Option<f64>,
    /// The residual's standard deviation, mm.
    pub sigma: f64,
    /// Degrees of freedom.
    pub dof: usize,
    /// `‖r‖²/σ₀²` (null without a stated noise).
    pub chi2: Option<f64>,
    /// Its upper-tail χ² p-value (null without a stated noise).
    pub p: Option<f64>,
    /// false: they do not explain the measurement (p < 1 %); null: not checked.
    pub explains: Option<bool>,
    /// In words.
    pub words: String,
}

/// Everything concluded from a fit.
#[derive(Debug, Clone, PartialEq)]
pub struct Judgement {
    /// The fit.
    pub fit: Fit,
    /// Per parameter, in the fit's order.
    pub decisions: Vec<Decision>,
    /// Per identifiable combination of a group.
    pub combinations: Vec<CombinationDecision>,
    /// The goodness of fit.
    pub goodness: GoodnessOfFit,
    /// The options used.
    pub options: Options,
    /// The conclusions in words, most important first.
    pub summary: Vec<String>,
}

impl Judgement {
    /// Names of the parameters found present (either verdict), the combinations' lead terms
    /// not included.
    pub fn found(&self) -> Vec<&str> {
        self.decisions
            .iter()
            .filter(|d| matches!(d.verdict, Verdict::Present | Verdict::BelowTolerance))
            .map(|d| d.name.as_str())
            .collect()
    }
}

/// A parameter of a fit: an error of the machine, or another unknown (the S-shape's tool
/// radius `dR`, mm) described by `label`.
#[derive(Debug, Clone, Copy)]
pub struct Param<'a> {
    /// Its name.
    pub name: &'a str,
    /// `SmallLength` (mm) or `SmallAngle` (rad in the engine).
    pub quantity: Quantity,
    /// The error table's entry, when it is a machine error.
    pub def: Option<&'static ErrorDef>,
    /// Words for a parameter that is not a machine error: "the tool radius is … larger".
    pub label: &'a str,
}

impl<'a> Param<'a> {
    /// The machine error `name` (an error when it is not in the table).
    pub fn error(name: &'a str) -> Result<Self> {
        let def = errors::find(name)
            .ok_or_else(|| Error::field("parameters", format!("{name} is not a machine error")))?;
        Ok(Self {
            name,
            quantity: def.quantity,
            def: Some(def),
            label: def.label,
        })
    }
}

/// Checks the options (messages name `alpha`, `level`, `noise`, `tolerance`).
pub fn check_options(o: &Options) -> Result<()> {
    check_range("alpha", o.alpha, 1e-6, 0.5, "")?;
    check_range("level", o.level, 0.5, 0.999_999, "")?;
    if let Some(n) = o.noise {
        check_range("noise", n, 1e-9, 10.0, "mm")?;
    }
    if let Some(t) = o.tolerance {
        check_range("tolerance", t, 0.0, 100.0, "mm")?;
    }
    Ok(())
}

/// Fits `d ≈ A·x` ([`fit`]) and judges every parameter (module docs). `a` in engine units (per
/// mm, per rad), `d` in mm.
pub fn identify(
    a: &DMatrix<f64>,
    params: &[Param],
    d: &[f64],
    rtol: f64,
    options: &Options,
) -> Result<Judgement> {
    check_options(options)?;
    let names: Vec<String> = params.iter().map(|p| p.name.to_string()).collect();
    let f = fit(a, &names, d, rtol)?;
    Ok(judge(f, a, params, options))
}

/// Judges a fit (module docs): Holm over the identifiable values and combinations, the
/// tolerance, the intervals and the goodness of fit.
pub fn judge(f: Fit, a: &DMatrix<f64>, params: &[Param], options: &Options) -> Judgement {
    let dof = f.dof as f64;
    let quantile = stats::t_quantile_two_sided(1.0 - options.level, dof);
    let p_of = |value: f64, se: f64| {
        if se > 0.0 {
            stats::t_two_sided(value / se, dof)
        } else if value == 0.0 {
            1.0
        } else {
            0.0
        }
    };
    // The family: identifiable values first, then the groups' combinations.
    let mut family: Vec<f64> = Vec::new();
    for e in &f.estimates {
        if let (Some(v), Some(se)) = (e.value, e.std_error) {
            family.push(p_of(v, se));
        }
    }
    for g in &f.groups {
        for c in &g.combinations {
            family.push(p_of(c.value, c.std_error));
        }
    }
    let adjusted = holm(&family);
    let effect = |j: usize, v: f64| -> f64 {
        a.column(j)
            .iter()
            .fold(0.0f64, |acc, k| acc.max((k * v).abs()))
    };
    let verdict_of = |p_adj: f64, effect: f64| {
        if p_adj > options.alpha {
            Verdict::NotDistinguishable
        } else if options.tolerance.is_some_and(|t| effect < t) {
            Verdict::BelowTolerance
        } else {
            Verdict::Present
        }
    };
    let mut next = 0;
    let mut decisions = Vec::with_capacity(params.len());
    for (j, (e, param)) in f.estimates.iter().zip(params).enumerate() {
        let d = match (e.value, e.std_error) {
            (Some(v), Some(se)) => {
                let p_adj = adjusted[next];
                next += 1;
                let eff = effect(j, v);
                let verdict = verdict_of(p_adj, eff);
                let half = quantile * se;
                Decision {
                    name: e.name.clone(),
                    value: Some(v),
                    std_error: Some(se),
                    interval: Some([v - half, v + half]),
                    t: (se > 0.0).then(|| v / se),
                    p_adjusted: Some(p_adj),
                    verdict,
                    effect: eff,
                    words: words_for(param, v, half, verdict, eff, options),
                }
            }
            _ => Decision {
                name: e.name.clone(),
                value: None,
                std_error: None,
                interval: None,
                t: None,
                p_adjusted: None,
                verdict: Verdict::NotIdentifiable,
                effect: 0.0,
                words: String::new(),
            },
        };
        decisions.push(d);
    }
    let mut combinations = Vec::new();
    let mut summary = Vec::new();
    for (gi, g) in f.groups.iter().enumerate() {
        if g.combinations.is_empty() {
            let list = g.members.join(", ");
            summary.push(if g.members.len() == 1 {
                format!(
                    "The test cannot see {list} at all: it changes none of the measured values."
                )
            } else {
                format!("The test cannot see {list}, nor any combination of them.")
            });
        }
        for c in &g.combinations {
            let p_adj = adjusted[next];
            next += 1;
            let half = quantile * c.std_error;
            let verdict = if p_adj > options.alpha {
                Verdict::NotDistinguishable
            } else {
                Verdict::Present
            };
            let lead = params
                .iter()
                .find(|p| p.name == c.terms[0].0)
                .map_or(Quantity::SmallLength, |p| p.quantity);
            let words = format!(
                "{} and {} cannot be told apart: only this combination is measurable: {} = {} ± {}{}",
                g.members[..g.members.len() - 1].join(", "),
                g.members[g.members.len() - 1],
                // In the units of the API (an angle per degree, as the values are given).
                result::api_text(c),
                amount(lead, c.value),
                amount(lead, half),
                if verdict == Verdict::NotDistinguishable {
                    " (not distinguishable from zero)."
                } else {
                    "."
                }
            );
            combinations.push(CombinationDecision {
                group: gi,
                combination: c.clone(),
                interval: [c.value - half, c.value + half],
                p_adjusted: p_adj,
                verdict,
                words,
            });
        }
    }
    let goodness = goodness(&f, options.noise);
    let mut head = Vec::new();
    if goodness.explains == Some(false) {
        head.push(goodness.words.clone());
    }
    let found: Vec<&Decision> = decisions
        .iter()
        .filter(|d| d.verdict == Verdict::Present)
        .collect();
    if found.is_empty() {
        head.push(format!(
            "No error is distinguishable from zero above the tolerance (family-wise false-call \
             rate {}).",
            percent(options.alpha)
        ));
    }
    head.extend(found.iter().map(|d| d.words.clone()));
    head.extend(
        decisions
            .iter()
            .filter(|d| d.verdict == Verdict::BelowTolerance)
            .map(|d| d.words.clone()),
    );
    head.extend(
        combinations
            .iter()
            .filter(|c| c.verdict == Verdict::Present)
            .map(|c| c.words.clone()),
    );
    head.extend(summary);
    if goodness.explains != Some(false) {
        head.push(goodness.words.clone());
    }
    Judgement {
        fit: f,
        decisions,
        combinations,
        goodness,
        options: *options,
        summary: head,
    }
}

/// Holm's adjusted p-values, in the order given (module docs).
pub fn holm(p: &[f64]) -> Vec<f64> {
    let n = p.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| p[i].total_cmp(&p[j]));
    let mut out = vec![0.0; n];
    let mut running: f64 = 0.0;
    for (rank, &i) in order.iter().enumerate() {
        running = running.max(((n - rank) as f64 * p[i]).min(1.0));
        out[i] = running;
    }
    out
}

fn goodness(f: &Fit, noise: Option<f64>) -> GoodnessOfFit {
    let rss = f.sigma * f.sigma * f.dof as f64;
    let Some(s0) = noise else {
        return GoodnessOfFit {
            noise,
            sigma: f.sigma,
            dof: f.dof,
            chi2: None,
            p: None,
            explains: None,
            words: format!(
                "Residual scatter {} ({} degrees of freedom); state the measurement's noise to \
                 check whether the errors explain the measurement.",
                amount(Quantity::SmallLength, f.sigma),
                f.dof
            ),
        };
    };
    let chi2 = rss / (s0 * s0);
    let p = stats::chi2_upper(chi2, f.dof as f64);
    let explains = p >= MISFIT_P;
    let words = if explains {
        format!(
            "The errors explain the measurement: residual scatter {} against the stated noise {} \
             (χ² test, p = {:.2}).",
            amount(Quantity::SmallLength, f.sigma),
            amount(Quantity::SmallLength, s0),
            p
        )
    } else {
        format!(
            "The errors do NOT explain the measurement: the residual scatter {} is larger than \
             the stated noise {} (χ² test, p = {:.1e}). Look for a set-up error, a thermal drift \
             or an error the model lacks; the values below are not to be trusted.",
            amount(Quantity::SmallLength, f.sigma),
            amount(Quantity::SmallLength, s0),
            p
        )
    };
    GoodnessOfFit {
        noise,
        sigma: f.sigma,
        dof: f.dof,
        chi2: Some(chi2),
        p: Some(p),
        explains: Some(explains),
        words,
    }
}

fn percent(x: f64) -> String {
    let t = format!("{:.1}", 100.0 * x);
    format!("{} %", t.trim_end_matches('0').trim_end_matches('.'))
}

/// A small length in µm or an angle in degrees and arc-seconds, signed, 3 significant figures.
pub fn amount(q: Quantity, v: f64) -> String {
    let sig = |x: f64| {
        if x == 0.0 {
            return "0".to_string();
        }
        let digits = (2 - x.abs().log10().floor() as i32).clamp(0, 8) as usize;
        format!("{x:.digits$}").replace('-', "−")
    };
    if q.is_angle() {
        let d = v.to_degrees();
        format!("{}° ({}″)", sig(d), sig(d * 3600.0))
    } else {
        format!("{} µm", sig(v * 1000.0))
    }
}

/// What an error's value means on the machine (the error table's sign: the axis frame's
/// displacement from where the control believes it is).
pub fn meaning(def: &ErrorDef, v: f64) -> String {
    let dir = ['X', 'Y', 'Z'][def.component % 3];
    let sign = if v < 0.0 { '−' } else { '+' };
    let rotary = matches!(def.axis, 'A' | 'B' | 'C');
    let own = match def.axis {
        'A' | 'X' => 'X',
        'B' | 'Y' => 'Y',
        _ => 'Z',
    };
    let a = def.axis;
    if def.component < 3 {
        let size = amount(Quantity::SmallLength, v.abs());
        if rotary && dir == own {
            format!("the {a} axis sits {size} towards {sign}{dir} along its own line")
        } else {
            format!("the {a} axis line lies {size} towards {sign}{dir} of where the control believes it is")
        }
    } else {
        let size = amount(Quantity::SmallAngle, v.abs());
        if rotary && dir == own {
            format!("the {a} axis's zero is {size} off: it stands turned {sign}{size} at {a} = 0")
        } else if rotary {
            format!("the {a} axis line is tilted by {size} about {sign}{dir}")
        } else {
            format!("the {a} axis is out of square by {size} about {sign}{dir}")
        }
    }
}

fn words_for(
    param: &Param,
    v: f64,
    half: f64,
    verdict: Verdict,
    effect: f64,
    options: &Options,
) -> String {
    let value = format!(
        "{} = {} ± {}",
        param.name,
        amount(param.quantity, v),
        amount(param.quantity, half)
    );
    let what = match param.def {
        Some(def) => meaning(def, v),
        None => format!("{} {}", param.label, amount(param.quantity, v)),
    };
    match verdict {
        Verdict::NotDistinguishable => format!("{value}: not distinguishable from zero."),
        Verdict::BelowTolerance => format!(
            "{value}: {what}; present, but its largest effect on the part, {}, is below the \
             tolerance {}.",
            amount(Quantity::SmallLength, effect),
            amount(Quantity::SmallLength, options.tolerance.unwrap_or(0.0))
        ),
        Verdict::Present | Verdict::NotIdentifiable => format!(
            "{value}: {what} (largest effect on the part {}).",
            amount(Quantity::SmallLength, effect)
        ),
    }
}
