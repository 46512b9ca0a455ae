//! The identification's decisions hold their stated rates (issue 13), by Monte-Carlo with fixed
//! seeds: simulated parts whose deviations come from the exact kinematic chain at each point's
//! pose (not from the linear model the fit uses, so that a sign slip in eq 14 or in the cubic
//! sensitivities fails here), plus Gaussian noise at the stated level.
//!
//! * the rate of parts with any error reported that is not there stays at or below the stated
//!   family-wise rate α = 5 % (one-sided Monte-Carlo margin 2.33 standard errors), where the old
//!   page's 2σ test one by one gives about 20 %;
//! * true errors at 5σ are found in at least 95 % of parts;
//! * the 95 % intervals cover the truth in 95 % of parts (± 3.3 standard errors);
//! * the χ² check flags about 1 % of good parts and nearly every part with a drift the model
//!   lacks.
#![allow(clippy::unwrap_used)]
use crate::common;

use common::chanal::{self, PAPER_L0};
use common::Rng;
use fiveaxis::chain::Setup;
use fiveaxis::identify::{Options, Verdict};
use fiveaxis::machine::errors::ErrorValues;
use fiveaxis::sshape::machine::DefectReference;
use fiveaxis::sshape::study::Design;
use nalgebra::{DMatrix, Vector3};

const NOISE: f64 = 0.002;
const ALPHA: f64 = 0.05;

/// Deviation at the 100 points (mm) of a part machined on Chanal et al.'s machine with `errors`
/// and a tool-radius error `dr`, from the exact chain: the tip's displacement at each point's
/// pose minus that at the workpiece origin, along the outward normal (eq 14's definition), and
/// `−sin θ·dR`.
fn exact_part(d: &Design, errors: &ErrorValues, dr: f64) -> Vec<f64> {
    let mut m = chanal::machine(PAPER_L0);
    m.errors = errors.clone();
    let chain = m.build().unwrap().chain;
    let nominal = d.on.model.nominal();
    let q_ref =
        d.on.reference_positions(DefectReference::WorkOrigin)
            .unwrap();
    let shift = |q: &[f64]| -> Vector3<f64> {
        let a = chain.tool_pose(q, true, &Setup::None).unwrap();
        let b = nominal.tool_pose(q, false, &Setup::None).unwrap();
        a.tip - b.tip
    };
    let back = d.on.frame.transpose();
    d.poses
        .iter()
        .zip(&d.radius)
        .map(|(pp, r)| {
            let moved = back * (shift(&pp.pose.q) - shift(&q_ref));
            moved.dot(&Vector3::from(pp.point.normal)) + r * dr
        })
        .collect()
}

fn names() -> Vec<String> {
    chanal::ERROR_NAMES.iter().map(|s| s.to_string()).collect()
}

/// Standard errors of the 8 errors and dR at noise σ: `σ·√((AᵀA)⁻¹)_jj`, computed here.
fn standard_errors(d: &Design) -> Vec<f64> {
    let rows = chanal::rows8(d);
    let a = DMatrix::from_fn(100, 9, |r, c| if c < 8 { rows[r][c] } else { d.radius[r] });
    let inv = (a.transpose() * &a).try_inverse().unwrap();
    (0..9).map(|j| NOISE * inv[(j, j)].sqrt()).collect()
}

fn binomial_margin(p: f64, n: usize, z: f64) -> f64 {
    z * (p * (1.0 - p) / n as f64).sqrt()
}

#[test]
fn sshape_false_calls_stay_within_the_family_wise_rate_and_5_sigma_errors_are_found() {
    let d = chanal::design(PAPER_L0, chanal::default_model());
    let se = standard_errors(&d);
    // Truth: E_C0Y, E_X0B, E_A0B and dR at 5σ (signs mixed); E_A0Z, E_B0Z, E_A0C, E_B0C,
    // E_C0B zero.
    let mut truth = [0.0; 9];
    for (j, s) in [(0, 5.0), (5, -5.0), (6, 5.0), (8, -5.0)] {
        truth[j] = s * se[j];
    }
    let zero: Vec<usize> = (0..9).filter(|&j| truth[j] == 0.0).collect();
    let mut xi = [0.0; 8];
    xi.copy_from_slice(&truth[..8]);
    let clean = exact_part(&d, &chanal::errors(&xi), truth[8]);
    let options = Options {
        alpha: ALPHA,
        noise: Some(NOISE),
        ..Options::default()
    };
    let n = 2000;
    let mut rng = Rng::new(2024_1123);
    let (mut false_parts, mut old_false_parts, mut flagged) = (0, 0, 0);
    let mut found = [0usize; 9];
    let mut covered = [0usize; 9];
    for _ in 0..n {
        let m: Vec<f64> = clean.iter().map(|v| v + NOISE * rng.gauss()).collect();
        let j = d.judge(&m, Some(&names()), true, 1e-2, &options).unwrap();
        let present = |k: usize| j.decisions[k].verdict == Verdict::Present;
        if zero.iter().any(|&k| present(k)) {
            false_parts += 1;
        }
        // The old page: each parameter on its own, "significant" at 2 standard errors.
        if zero.iter().any(|&k| {
            let e = &j.fit.estimates[k];
            e.value.unwrap().abs() >= 2.0 * e.std_error.unwrap()
        }) {
            old_false_parts += 1;
        }
        for k in 0..9 {
            if truth[k] != 0.0 && present(k) {
                found[k] += 1;
            }
            let [lo, hi] = j.decisions[k].interval.unwrap();
            if lo <= truth[k] && truth[k] <= hi {
                covered[k] += 1;
            }
        }
        if j.goodness.explains == Some(false) {
            flagged += 1;
        }
    }
    let rate = false_parts as f64 / n as f64;
    let old = old_false_parts as f64 / n as f64;
    println!("false-call rate: Holm {rate:.4}, old 2σ one by one {old:.4}");
    assert!(
        rate <= ALPHA + binomial_margin(ALPHA, n, 2.33),
        "Holm false-call rate {rate}"
    );
    // Five zero errors tested one by one at 2σ: far above 5 % (the issue saw 21.5 % with six).
    assert!(old > 0.15, "old rate {old}");
    for k in 0..9 {
        if truth[k] != 0.0 {
            let f = found[k] as f64 / n as f64;
            println!("{}: found in {f:.4}", j_name(k));
            assert!(f >= 0.95, "{} at 5σ found in {f}", j_name(k));
        }
        let c = covered[k] as f64 / n as f64;
        println!("{}: 95 % interval covers the truth in {c:.4}", j_name(k));
        assert!(
            (c - 0.95).abs() <= binomial_margin(0.95, n, 3.3),
            "{} coverage {c}",
            j_name(k)
        );
    }
    let g = flagged as f64 / n as f64;
    println!("χ² check flags {g:.4} of good parts");
    assert!(
        g <= 0.01 + binomial_margin(0.01, n, 3.3),
        "good parts flagged {g}"
    );
}

fn j_name(k: usize) -> String {
    if k < 8 {
        chanal::ERROR_NAMES[k].to_string()
    } else {
        "dR".to_string()
    }
}

#[test]
fn a_drift_the_model_lacks_is_flagged_and_said_first() {
    // A thermal drift during the measurement: 10 µm growing linearly over the 100 points, on
    // top of 2 µm noise. The χ² check flags nearly every part and the summary says so first.
    let d = chanal::design(PAPER_L0, chanal::default_model());
    let clean = exact_part(&d, &ErrorValues::none(), 0.0);
    let options = Options {
        noise: Some(NOISE),
        ..Options::default()
    };
    let mut rng = Rng::new(99);
    let n = 200;
    let mut flagged = 0;
    for _ in 0..n {
        let m: Vec<f64> = clean
            .iter()
            .enumerate()
            .map(|(k, v)| v + 0.010 * k as f64 / 99.0 + NOISE * rng.gauss())
            .collect();
        let j = d.judge(&m, Some(&names()), true, 1e-2, &options).unwrap();
        if j.goodness.explains == Some(false) {
            flagged += 1;
            assert!(j.summary[0].contains("do NOT explain"), "{}", j.summary[0]);
        }
    }
    assert!(flagged as f64 / n as f64 >= 0.95, "{flagged} of {n}");
}

#[test]
fn the_sample_reports_only_the_errors_it_was_made_with() {
    // The project's sample: Table 4's E_X0B and E_A0B, a tool 0.02 mm small, 2 µm noise; the
    // other six errors zero (the old page reported E_A0C = −30″ without a "not significant").
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../public/samples/sshape-measured.csv"
    ))
    .unwrap();
    let m = fiveaxis::sshape::identify::parse_measurements(&text).unwrap();
    let d = chanal::design(PAPER_L0, chanal::default_model());
    let options = Options {
        noise: Some(NOISE),
        tolerance: Some(0.005),
        ..Options::default()
    };
    let j = d.judge(&m, Some(&names()), true, 1e-2, &options).unwrap();
    let present: Vec<&str> = j
        .decisions
        .iter()
        .filter(|x| x.verdict == Verdict::Present)
        .map(|x| x.name.as_str())
        .collect();
    assert_eq!(present, vec!["E_X0B", "E_A0B", "dR"]);
    // This draw's noise puts E_A0C at t = −2.9: Holm's test (5 % of parts over the whole set,
    // the test above) calls it, but its largest effect on the part, 3.1 µm, is below a 5 µm
    // tolerance, and that is what the page says; the other five zero errors are not
    // distinguishable from zero.
    let a0c = j.decisions.iter().find(|x| x.name == "E_A0C").unwrap();
    assert_eq!(a0c.verdict, Verdict::BelowTolerance);
    assert!(a0c.words.contains("below the tolerance"), "{}", a0c.words);
    for x in &j.decisions {
        if !["E_X0B", "E_A0B", "dR", "E_A0C"].contains(&x.name.as_str()) {
            assert_eq!(x.verdict, Verdict::NotDistinguishable, "{}", x.name);
            assert!(
                x.words.contains("not distinguishable from zero"),
                "{}",
                x.words
            );
        }
    }
    assert_eq!(j.goodness.explains, Some(true));
    // In words: E_X0B = +29.4 µm puts the B axis line towards +X.
    let x0b = j.decisions.iter().find(|x| x.name == "E_X0B").unwrap();
    assert!(
        x0b.words.contains("the B axis line lies") && x0b.words.contains("towards +X"),
        "{}",
        x0b.words
    );
    for s in &j.summary {
        println!("{s}");
    }
}
