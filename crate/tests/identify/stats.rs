//! The distributions of `fiveaxis::identify::stats` against closed forms, and Holm's step-down
//! against its definition worked by hand.
#![allow(clippy::unwrap_used)]
use crate::common;

use common::close;
use fiveaxis::identify::holm;
use fiveaxis::identify::stats::{chi2_upper, ln_gamma, t_quantile_two_sided, t_two_sided};
use std::f64::consts::PI;

#[test]
fn student_t_matches_its_closed_forms() {
    for &t in &[0.0, 0.3, 1.0, 2.0, 4.5, 30.0] {
        // ν = 1 (Cauchy): 1 − 2·atan|t|/π; ν = 2: 1 − |t|/√(t² + 2).
        close(
            t_two_sided(t, 1.0),
            1.0 - 2.0 * t.atan() / PI,
            1e-12,
            "ν = 1",
        );
        close(
            t_two_sided(-t, 2.0),
            1.0 - t / (t * t + 2.0).sqrt(),
            1e-12,
            "ν = 2",
        );
    }
    // Large ν: the normal, 2·(1 − Φ(1.959964)) = 0.05.
    close(t_two_sided(1.959_963_985, 1e7), 0.05, 1e-6, "normal limit");
    // Tabulated quantiles (any table of Student's t): ν = 10, 95 %: 2.228139; ν = 91: 1.986.
    close(t_quantile_two_sided(0.05, 10.0), 2.228_139, 1e-5, "t(10)");
    close(
        t_quantile_two_sided(0.05, 1.0),
        (PI * 0.475).tan(),
        1e-8,
        "t(1)",
    );
}

#[test]
fn chi_square_and_gamma_match_their_closed_forms() {
    for &x in &[0.0, 0.5, 2.0, 10.0, 60.0] {
        close(chi2_upper(x, 2.0), (-x / 2.0).exp(), 1e-12, "χ²(2)");
        // k = 4: e^(−x/2)·(1 + x/2).
        close(
            chi2_upper(x, 4.0),
            (-x / 2.0).exp() * (1.0 + x / 2.0),
            1e-12,
            "χ²(4)",
        );
    }
    close(ln_gamma(0.5), PI.sqrt().ln(), 1e-12, "Γ(½) = √π");
    close(ln_gamma(10.0), 362_880f64.ln(), 1e-12, "Γ(10) = 9!");
}

#[test]
fn holm_adjusts_by_rank_and_keeps_the_order() {
    // p = (0.01, 0.04, 0.03, 0.2), n = 4: sorted 0.01·4 = 0.04, 0.03·3 = 0.09, 0.04·2 = 0.08 →
    // 0.09 (monotone), 0.2·1 = 0.2.
    let a = holm(&[0.01, 0.04, 0.03, 0.2]);
    for (x, y) in a.iter().zip([0.04, 0.09, 0.09, 0.2]) {
        close(*x, y, 1e-15, "Holm");
    }
    assert_eq!(holm(&[0.9, 0.8]), vec![1.0, 1.0]);
}

// Found by cargo-mutants: a mutant in `crate/src/identify/stats.rs` survived every other test.
/// Far in the tail: with one degree of freedom `P(|T| ≥ t) = 1 − 2·atan(t)/π`, so the
/// two-sided quantile of p is `cot(π·p/2)`; for p = 1e-11 that is 6.366e10, found by doubling the
/// bracket from 1 (36 doublings), then Newton.
#[test]
fn a_far_tail_quantile_is_cot_pi_p_over_2_with_one_degree_of_freedom() {
    use fiveaxis::identify::stats::t_quantile_two_sided;
    for p in [1e-11, 1e-9, 1e-6, 0.05] {
        let want = 1.0 / (std::f64::consts::PI * p / 2.0).tan();
        let got = t_quantile_two_sided(p, 1.0);
        close(got / want, 1.0, 1e-9, &format!("p = {p}"));
    }
}

// Found by cargo-mutants: a mutant in `crate/src/identify/stats.rs` survived every other test.
/// The χ² upper tail where its continued fraction is used (x/2 ≥ k/2 + 1), against the closed
/// forms for even degrees of freedom: `Q(k/2, y) = e^(−y)·Σ_{n<k/2} yⁿ/n!`, y = x/2.
#[test]
fn the_chi2_tail_far_out_is_its_closed_form_for_even_degrees_of_freedom() {
    use fiveaxis::identify::stats::chi2_upper;
    for x in [0.5, 3.0, 10.0, 30.0, 80.0] {
        let y: f64 = x / 2.0;
        for (k, poly) in [(2.0, 1.0), (4.0, 1.0 + y), (6.0, 1.0 + y + y * y / 2.0)] {
            let want = (-y).exp() * poly;
            close(
                chi2_upper(x, k) / want,
                1.0,
                1e-10,
                &format!("x {x}, k {k}"),
            );
        }
    }
}
