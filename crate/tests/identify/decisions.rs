//! The identification's decisions on least-squares problems solved by hand: the decision options'
//! ranges and defaults, which errors are found and which are not, the combinations the data can
//! measure with their intervals, verdicts and units, the groups of errors the data cannot tell
//! apart, and the summary's wording.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::close;
use fiveaxis::identify::{
    check_options, fit, identify, meaning, DecisionInput, Options, Param, Verdict,
};
use nalgebra::DMatrix;

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// A tolerance of 0 means "none" (every error found is reported present); a positive one is
/// kept as given (the input's documented meaning).
#[test]
fn a_zero_tolerance_is_none_and_a_positive_one_is_kept() {
    let none = DecisionInput {
        alpha: 0.05,
        noise: None,
        tolerance: 0.0,
    };
    assert_eq!(none.options().tolerance, None);
    let some = DecisionInput {
        tolerance: 0.002,
        ..none
    };
    assert_eq!(some.options().tolerance, Some(0.002));
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// Each option outside its documented range is refused at its own name: α in [1e-6, 0.5],
/// the level in [0.5, 0.999999], the noise in [1e-9, 10] mm, the tolerance in [0, 100] mm.
#[test]
fn options_outside_their_ranges_are_refused_by_name() {
    let ok = Options::default();
    assert!(check_options(&ok).is_ok());
    let cases = [
        ("alpha", Options { alpha: 0.7, ..ok }),
        ("level", Options { level: 0.3, ..ok }),
        (
            "noise",
            Options {
                noise: Some(0.0),
                ..ok
            },
        ),
        (
            "tolerance",
            Options {
                tolerance: Some(-1.0),
                ..ok
            },
        ),
    ];
    for (name, o) in cases {
        assert_eq!(check_options(&o).unwrap_err().field, name);
        // The whole identification refuses them too, before fitting anything.
        let a = DMatrix::identity(3, 1);
        let p = [Param::error("E_X0B").unwrap()];
        assert_eq!(
            identify(&a, &p, &[0.1, 0.1, 0.1], 1e-9, &o)
                .unwrap_err()
                .field,
            name
        );
    }
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// Two measurements of each of two errors with unit sensitivity: each estimate is the mean of
/// its two. 0.1 mm under 1 µm of noise is found present; 0 ± 0.4 µm is not (t ≈ 0).
#[test]
fn an_error_far_above_its_noise_is_found_and_a_zero_one_is_not() {
    let a = DMatrix::from_row_slice(4, 2, &[1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0]);
    let p = [
        Param::error("E_X0B").unwrap(),
        Param::error("E_Y0B").unwrap(),
    ];
    let d = [0.1005, 0.0995, 0.0004, -0.0004];
    let o = Options {
        noise: Some(0.001),
        ..Options::default()
    };
    let j = identify(&a, &p, &d, 1e-9, &o).unwrap();
    assert_eq!(j.found(), vec!["E_X0B"]);
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// Data the model fits exactly, with no noise given: the residual is 0, and so is every
/// standard error. Two zero readings of one error: it is estimated at exactly 0 and shows
/// nothing (p = 1: not distinguishable). Two equal non-zero readings: certain (p = 0: present).
#[test]
fn an_exact_fit_finds_a_nonzero_error_and_not_a_zero_one() {
    let a = DMatrix::from_row_slice(2, 1, &[1.0, 1.0]);
    let p = [Param::error("E_X0B").unwrap()];
    let zero = identify(&a, &p, &[0.0, 0.0], 1e-9, &Options::default()).unwrap();
    assert_eq!(zero.decisions[0].value, Some(0.0));
    assert_eq!(zero.decisions[0].std_error, Some(0.0), "an exact fit");
    assert!(zero.found().is_empty(), "{:?}", zero.decisions[0]);
    assert_eq!(
        zero.decisions[0].t, None,
        "no t statistic without a standard error"
    );
    let two = identify(&a, &p, &[0.25, 0.25], 1e-9, &Options::default()).unwrap();
    assert_eq!(two.decisions[0].std_error, Some(0.0), "an exact fit");
    assert_eq!(two.found(), vec!["E_X0B"]);
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// The verdict's two thresholds, met exactly: a p-value equal to α is significant (the test
/// rejects at p ≤ α), and an effect equal to the tolerance reaches it ("present" once the
/// effect reaches the tolerance). The thresholds are set to the first run's own p-value and
/// effect, so that they are met to the last bit.
#[test]
fn a_p_value_at_alpha_is_significant_and_an_effect_at_the_tolerance_reaches_it() {
    let a = DMatrix::from_row_slice(3, 1, &[1.0, 1.0, 1.0]);
    let p = [Param::error("E_X0B").unwrap()];
    let d = [0.010, 0.014, 0.009];
    let first = identify(&a, &p, &d, 1e-9, &Options::default()).unwrap();
    let p_adj = first.decisions[0].p_adjusted.unwrap();
    assert!(
        (1e-6..0.5).contains(&p_adj),
        "a p-value α can take: {p_adj}"
    );
    let dec = &first.decisions[0];
    // t = value / standard error; the mean 0.011 of the readings over s/√3, s their deviation.
    let s = ((0.001f64.powi(2) + 0.003f64.powi(2) + 0.002f64.powi(2)) / 2.0).sqrt();
    close(dec.t.unwrap(), 0.011 / (s / 3f64.sqrt()), 1e-9, "t");
    let at_alpha = Options {
        alpha: p_adj,
        ..Options::default()
    };
    let j = identify(&a, &p, &d, 1e-9, &at_alpha).unwrap();
    assert_eq!(j.found(), vec!["E_X0B"], "p = α is significant");
    let effect = first.decisions[0].effect;
    close(
        effect,
        0.011,
        1e-12,
        "effect: the mean reading, sensitivity 1",
    );
    let at_tolerance = Options {
        tolerance: Some(effect),
        ..Options::default()
    };
    let j = identify(&a, &p, &d, 1e-9, &at_tolerance).unwrap();
    assert_eq!(
        j.decisions[0].verdict,
        Verdict::Present,
        "effect = tolerance reaches it"
    );
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// Two pairs of errors the test cannot tell apart (each pair's columns are equal): only each
/// pair's sum is measurable. The first sum reads 10, 14 and 9 µm, the second 1, −2 and 0.5 µm.
/// Each sum is its readings' mean; the pooled deviation has 6 − 2 = 4 degrees of freedom; the
/// 95 % half-width is t(0.975, 4) = 2.776445 times the standard error s/√3. The first sum is
/// found, the second (−0.17 ± 3.5 µm) is not.
#[test]
fn each_measurable_combination_gets_its_own_interval_and_verdict() {
    let a = DMatrix::from_row_slice(
        6,
        4,
        &[
            1.0, 1.0, 0.0, 0.0, //
            1.0, 1.0, 0.0, 0.0, //
            1.0, 1.0, 0.0, 0.0, //
            0.0, 0.0, 1.0, 1.0, //
            0.0, 0.0, 1.0, 1.0, //
            0.0, 0.0, 1.0, 1.0,
        ],
    );
    let p = ["E_X0B", "E_Y0B", "E_X0C", "E_Y0C"].map(|n| Param::error(n).unwrap());
    let d = [0.010, 0.014, 0.009, 0.001, -0.002, 0.0005];
    let j = identify(&a, &p, &d, 1e-9, &Options::default()).unwrap();
    assert_eq!(j.combinations.len(), 2);
    let m2 = (0.001 - 0.002 + 0.0005) / 3.0;
    let ssr = [0.001, 0.003, 0.002]
        .iter()
        .map(|r: &f64| r * r)
        .sum::<f64>()
        + [0.001, -0.002, 0.0005]
            .iter()
            .map(|r: &f64| (r - m2).powi(2))
            .sum::<f64>();
    let se = (ssr / 4.0).sqrt() / 3f64.sqrt();
    let half = 2.776_445_105_197_793 * se;
    for (c, mean) in j.combinations.iter().zip([0.011, m2]) {
        close(
            c.combination.value,
            mean,
            1e-12,
            "the sum is the mean reading",
        );
        close(c.combination.std_error, se, 1e-12, "standard error");
        close(c.interval[0], mean - half, 1e-9, "interval low");
        close(c.interval[1], mean + half, 1e-9, "interval high");
    }
    assert_eq!(j.combinations[0].verdict, Verdict::Present);
    assert_eq!(j.combinations[1].verdict, Verdict::NotDistinguishable);
    // A combination's p-value equal to α is significant, as for a single error.
    let at_alpha = Options {
        alpha: j.combinations[0].p_adjusted,
        ..Options::default()
    };
    let again = identify(&a, &p, &d, 1e-9, &at_alpha).unwrap();
    assert_eq!(again.combinations[0].verdict, Verdict::Present);
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// A length and an angle the test cannot tell apart (equal columns): the combination is
/// written in its first term's unit, µm for the position error E_X0C, degrees for the
/// squareness E_A0C.
#[test]
fn a_combination_is_written_in_its_first_terms_unit() {
    let a = DMatrix::from_row_slice(3, 2, &[1.0, 1.0, 1.0, 1.0, 1.0, 1.0]);
    let p = ["E_X0C", "E_A0C"].map(|n| Param::error(n).unwrap());
    let j = identify(&a, &p, &[0.010, 0.014, 0.009], 1e-9, &Options::default()).unwrap();
    let c = &j.combinations[0];
    let unit = match c.combination.terms[0].0.as_str() {
        "E_X0C" => " µm",
        "E_A0C" => "°",
        other => panic!("first term {other}"),
    };
    // The sum, the mean reading 0.011, to three significant figures.
    let value = if unit == " µm" {
        "11.0 µm"
    } else {
        "0.630°"
    };
    assert!(c.words.contains(&format!(" = {value}")), "{}", c.words);
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// What an error's value means, in the words of ISO 230-1's names `E_<component>0<axis>`: a
/// position error of a rotary axis across its line moves the line, one along its own line
/// moves the axis along it; an angle about its own line is the zero offset, about another
/// direction a tilt; a linear axis's angle is a squareness. The sign follows the value.
#[test]
fn each_error_is_explained_by_its_iso_name() {
    let cases = [
        (
            "E_X0C",
            0.01,
            "the C axis line lies 10.0 µm towards +X of where the control believes it is",
        ),
        (
            "E_Y0C",
            -0.01,
            "the C axis line lies 10.0 µm towards −Y of where the control believes it is",
        ),
        (
            "E_Z0C",
            0.01,
            "the C axis sits 10.0 µm towards +Z along its own line",
        ),
        (
            "E_X0A",
            -0.01,
            "the A axis sits 10.0 µm towards −X along its own line",
        ),
        (
            "E_Y0B",
            0.01,
            "the B axis sits 10.0 µm towards +Y along its own line",
        ),
        (
            "E_Z0B",
            0.01,
            "the B axis line lies 10.0 µm towards +Z of where the control believes it is",
        ),
        (
            "E_C0C",
            1e-3,
            "the C axis's zero is 0.0573° (206″) off: it stands turned +0.0573° (206″) at C = 0",
        ),
        (
            "E_A0A",
            -1e-3,
            "the A axis's zero is 0.0573° (206″) off: it stands turned −0.0573° (206″) at A = 0",
        ),
        (
            "E_B0B",
            1e-3,
            "the B axis's zero is 0.0573° (206″) off: it stands turned +0.0573° (206″) at B = 0",
        ),
        (
            "E_A0C",
            1e-3,
            "the C axis line is tilted by 0.0573° (206″) about +X",
        ),
        (
            "E_B0C",
            -1e-3,
            "the C axis line is tilted by 0.0573° (206″) about −Y",
        ),
        (
            "E_C0Y",
            1e-3,
            "the Y axis is out of square by 0.0573° (206″) about +Z",
        ),
        (
            "E_A0Z",
            1e-3,
            "the Z axis is out of square by 0.0573° (206″) about +X",
        ),
    ];
    for (name, v, want) in cases {
        let def = fiveaxis::machine::errors::find(name).unwrap();
        assert_eq!(meaning(def, v), want, "{name}");
    }
    // A zero value is "+", not "−".
    assert!(meaning(fiveaxis::machine::errors::find("E_X0C").unwrap(), 0.0).contains("+X"));
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// The summary: the false-call rate α as a percentage when nothing is found, and the
/// goodness of fit said once, first when the errors do not explain the measurement, last
/// otherwise (and when no noise is given, so nothing can be judged).
#[test]
fn the_summary_states_alpha_and_the_goodness_of_fit_once() {
    let a = DMatrix::from_row_slice(3, 1, &[1.0, 1.0, 1.0]);
    let p = [Param::error("E_X0B").unwrap()];
    let zero = [0.0004, -0.0006, 0.0002];
    for (alpha, rate) in [
        (0.05, "rate 5 %)"),
        (0.025, "rate 2.5 %)"),
        (0.1, "rate 10 %)"),
    ] {
        let o = Options {
            alpha,
            ..Options::default()
        };
        let j = identify(&a, &p, &zero, 1e-9, &o).unwrap();
        assert!(j.summary[0].contains(rate), "{alpha}: {}", j.summary[0]);
        assert_eq!(j.summary.last(), Some(&j.goodness.words), "no noise: last");
        assert_eq!(
            j.summary.iter().filter(|s| **s == j.goodness.words).count(),
            1
        );
    }
    // Readings scattered ±0.5 mm against a stated noise of 1 µm: not explained, said first.
    let o = Options {
        noise: Some(0.001),
        ..Options::default()
    };
    let j = identify(&a, &p, &[0.5, -0.5, 0.1], 1e-9, &o).unwrap();
    assert_eq!(j.goodness.explains, Some(false));
    assert_eq!(j.summary[0], j.goodness.words);
    assert_eq!(
        j.summary.iter().filter(|s| **s == j.goodness.words).count(),
        1
    );
    // Readings within the noise: explained, said last.
    let j = identify(&a, &p, &[0.0105, 0.0095, 0.0101], 1e-9, &o).unwrap();
    assert_eq!(j.goodness.explains, Some(true));
    assert_eq!(j.summary.last(), Some(&j.goodness.words));
    assert_eq!(
        j.summary.iter().filter(|s| **s == j.goodness.words).count(),
        1
    );
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// The least-squares fit refuses a problem that does not hold together, each alone: names for
/// another number of columns, readings for another number of rows, a single reading, no
/// parameter; two readings of one parameter are the smallest problem it solves.
#[test]
fn the_fit_refuses_shapes_that_do_not_match_and_solves_the_smallest_one() {
    let names = |n: usize| (0..n).map(|i| format!("p{i}")).collect::<Vec<_>>();
    let a = DMatrix::from_row_slice(3, 1, &[1.0, 1.0, 1.0]);
    assert!(
        fit(&a, &names(2), &[0.1, 0.1, 0.1], 1e-9).is_err(),
        "two names, one column"
    );
    assert!(
        fit(&a, &names(1), &[0.1, 0.1], 1e-9).is_err(),
        "two readings, three rows"
    );
    let one = DMatrix::from_row_slice(1, 1, &[1.0]);
    assert!(fit(&one, &names(1), &[0.1], 1e-9).is_err(), "one reading");
    let none = DMatrix::<f64>::zeros(3, 0);
    assert!(
        fit(&none, &names(0), &[0.1, 0.1, 0.1], 1e-9).is_err(),
        "no parameter"
    );
    let two = DMatrix::from_row_slice(2, 1, &[1.0, 1.0]);
    let f = fit(&two, &names(1), &[0.1, 0.3], 1e-9).unwrap();
    close(
        f.estimates[0].value.unwrap(),
        0.2,
        1e-12,
        "the mean of two readings",
    );
    assert_eq!(f.dof, 1);
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// A column at most 1e-12 of the largest column's norm is no effect at all (rounding noise):
/// the parameter is reported as not seen, alone in its group, not paired with the other column
/// it would equal once scaled. Checked at exactly the bound, and relative to a largest column
/// of norm 1000 (bound 1e-9).
#[test]
fn a_column_at_most_1e_12_of_the_largest_is_no_effect() {
    let names = ["a".to_string(), "b".to_string()];
    for (big, small) in [(1.0, 1e-12), (1000.0, 1e-10)] {
        let a = DMatrix::from_row_slice(3, 2, &[big, small, 0.0, 0.0, 0.0, 0.0]);
        let f = fit(&a, &names, &[0.1, 0.0, 0.0], 1e-9).unwrap();
        assert_eq!(
            f.estimates[1].value, None,
            "{big}, {small}: b not identifiable"
        );
        let b = f
            .groups
            .iter()
            .find(|g| g.members.contains(&names[1]))
            .unwrap();
        assert_eq!(
            b.members,
            ["b"],
            "{big}, {small}: b alone, not combined with a"
        );
        assert!(b.combinations.is_empty());
        close(f.estimates[0].value.unwrap(), 0.1 / big, 1e-15, "a");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// Four errors whose weak directions (what the measurement cannot see) span the columns
/// `(√½, ½, 0, ½)` and `(0, ½, √½, −½)` of the parameters a, b, c, d: the measurement rows
/// `(−√2, 1, 0, 1)` and `(0, 1, −√2, −1)` are square to both (worked by hand), and every column
/// has the norm √2 · √2 = 2, so scaling the columns keeps that geometry. The projector onto
/// the weak directions couples a with b and d, and c with b and d, but not a with c: c joins
/// a's group only through b or d. All four are one group, two of its four directions weak,
/// two combinations measurable.
#[test]
fn errors_linked_only_through_a_third_are_one_group() {
    let s = 2f64.sqrt();
    let r1 = [-s, 1.0, 0.0, 1.0];
    let r2 = [0.0, 1.0, -s, -1.0];
    let rows: Vec<f64> = [r1, r2, r1, r2].concat();
    let a = DMatrix::from_row_slice(4, 4, &rows);
    let names = ["a", "b", "c", "d"].map(String::from);
    let f = fit(&a, &names, &[0.01, 0.02, 0.012, 0.018], 1e-9).unwrap();
    assert_eq!(f.rank, 2);
    assert_eq!(f.groups.len(), 1, "{:?}", f.groups);
    assert_eq!(f.groups[0].members, names);
    assert_eq!(f.groups[0].deficiency, 2);
    assert_eq!(f.groups[0].combinations.len(), 2);
    // Each combination is written with its first coefficient 1.
    for c in &f.groups[0].combinations {
        assert_eq!(c.terms[0].1, 1.0, "{}", c.text);
    }
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// Two errors with the same effect direction, a's effect per unit `ka`, b's `kb`: only
/// `ka·a + kb·b` is measurable, written with the first term's coefficient 1 as
/// `a + (kb/ka)·b`, its value the mean reading over `ka`. A first coefficient small against the
/// others is still the lead (only one below 10⁻⁶ of the largest counts as zero): a at 10⁻⁴ of
/// b, and a at 10⁻⁵ of b with both effects small (10⁻⁷ and 10⁻² per unit).
#[test]
fn a_combination_leads_with_its_first_term_even_when_its_effect_is_small() {
    for (ka, kb) in [(1e-4, 1.0), (1e-7, 1e-2)] {
        let a = DMatrix::from_row_slice(3, 2, &[ka, kb, ka, kb, ka, kb]);
        let names = ["a", "b"].map(String::from);
        let f = fit(&a, &names, &[0.010, 0.014, 0.009], 1e-9).unwrap();
        let c = &f.groups[0].combinations[0];
        assert_eq!(c.terms[0].0, "a");
        close(c.terms[0].1, 1.0, 1e-12, "first coefficient");
        assert_eq!(c.terms[1].0, "b");
        let want = kb / ka;
        close(c.terms[1].1 / want, 1.0, 1e-9, "second coefficient");
        close(c.value / (0.011 / ka), 1.0, 1e-9, "value");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// A combination as text: the first name alone (coefficient 1), then each term with its sign
/// and its size to 4 decimals, trailing zeros dropped, and no "1·" for a size within 5e-5 of 1.
/// A zero coefficient is written with "+".
#[test]
fn a_combination_is_written_with_signs_and_sizes_to_four_decimals() {
    use fiveaxis::identify::combination_text;
    let t = |terms: &[(&str, f64)]| {
        combination_text(
            &terms
                .iter()
                .map(|(n, c)| (n.to_string(), *c))
                .collect::<Vec<_>>(),
        )
    };
    assert_eq!(
        t(&[("E_A0Z", 1.0), ("E_A0C", -1.0187)]),
        "E_A0Z − 1.0187·E_A0C"
    );
    assert_eq!(t(&[("a", 1.0), ("b", 1.0), ("c", -1.0)]), "a + b − c");
    assert_eq!(
        t(&[("a", 1.0), ("b", 1.00004), ("c", -0.99996)]),
        "a + b − c"
    );
    assert_eq!(
        t(&[("a", 1.0), ("b", 1.0001), ("c", 0.9999)]),
        "a + 1.0001·b + 0.9999·c"
    );
    assert_eq!(t(&[("a", 1.0), ("b", 2.5), ("c", -3.0)]), "a + 2.5·b − 3·c");
    assert_eq!(t(&[("a", 1.0), ("b", 0.0)]), "a + 0·b");
    assert_eq!(t(&[("a", 2.0)]), "a", "the first term is taken as 1");
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// The singular values reported are relative to the largest. Two unit columns at cos θ = 0.6
/// have singular values √(1 ± 0.6) = √1.6 and √0.4, the ratio exactly 1/2.
#[test]
fn the_singular_values_are_relative_to_the_largest() {
    let a = DMatrix::from_row_slice(3, 2, &[1.0, 0.6, 0.0, 0.8, 0.0, 0.0]);
    let names = ["a", "b"].map(String::from);
    let f = fit(&a, &names, &[0.1, 0.2, 0.0], 1e-9).unwrap();
    close(f.singular_values[0], 1.0, 1e-15, "largest");
    close(f.singular_values[1], 0.5, 1e-12, "ratio");
    assert_eq!(f.dof, 1, "3 readings, rank 2");
}

// Found by cargo-mutants: a mutant in `crate/src/identify/` survived every other test.
/// An error found but below the tolerance is still said in the summary, with why it does not
/// matter; one not distinguishable from zero is not.
#[test]
fn the_summary_names_an_error_below_the_tolerance_and_not_a_zero_one() {
    let a = DMatrix::from_row_slice(
        6,
        2,
        &[1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0],
    );
    let p = [
        Param::error("E_X0B").unwrap(),
        Param::error("E_Y0B").unwrap(),
    ];
    // E_X0B: 11 µm, clearly present, below a 20 µm tolerance; E_Y0B: 0 ± noise.
    let d = [0.010, 0.014, 0.009, 0.0004, -0.0006, 0.0002];
    let o = Options {
        tolerance: Some(0.020),
        ..Options::default()
    };
    let j = identify(&a, &p, &d, 1e-9, &o).unwrap();
    assert_eq!(j.decisions[0].verdict, Verdict::BelowTolerance);
    assert_eq!(j.decisions[1].verdict, Verdict::NotDistinguishable);
    assert!(j.summary.contains(&j.decisions[0].words), "{:?}", j.summary);
    assert!(j.decisions[0].words.contains("below the tolerance"));
    assert!(
        !j.summary.contains(&j.decisions[1].words),
        "{:?}",
        j.summary
    );
}
