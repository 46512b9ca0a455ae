//! The engine's input checks and quoted texts, at their documented edges (`crate/src/error.rs`).
//!
//! Found by cargo-mutants (scope `error`): the bounds of `check_range`, `check_positive` and
//! `check_count` and the length of `quote` were reached by no test at their edges.

use fiveaxis::error::{check_count, check_positive, check_range, quote};

#[test]
fn a_range_holds_both_its_ends_and_refuses_past_them_by_name() {
    assert_eq!(check_range("a.b", -2.0, -2.0, 3.0, "mm"), Ok(-2.0));
    assert_eq!(check_range("a.b", 3.0, -2.0, 3.0, "mm"), Ok(3.0));
    assert_eq!(check_range("a.b", 0.5, -2.0, 3.0, "mm"), Ok(0.5));
    for bad in [-2.0 - 1e-12, 3.0 + 1e-12, -1e9, 1e9] {
        let e = check_range("a.b", bad, -2.0, 3.0, "mm").unwrap_err();
        assert_eq!(e.field, "a.b");
        assert!(e.message.contains("between -2 and 3 mm"), "{e}");
    }
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let e = check_range("rtol", bad, 0.0, 1.0, "").unwrap_err();
        assert!(e.message.contains("finite"), "{e}");
    }
}

#[test]
fn positive_means_above_zero_up_to_the_maximum() {
    assert_eq!(check_positive("length", 1e-300, 10.0, "mm"), Ok(1e-300));
    assert_eq!(check_positive("length", 10.0, 10.0, "mm"), Ok(10.0));
    assert_eq!(check_positive("length", 4.0, 10.0, "mm"), Ok(4.0));
    for bad in [0.0, -0.0, -1.0, 10.0 + 1e-9, 1e6] {
        let e = check_positive("length", bad, 10.0, "mm").unwrap_err();
        assert_eq!(
            e.to_string(),
            format!("length: must be greater than 0 and at most 10 mm, got {bad}")
        );
    }
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let e = check_positive("length", bad, 10.0, "mm").unwrap_err();
        assert!(
            e.message.starts_with("must be a finite number of mm"),
            "{e}"
        );
    }
}

#[test]
fn a_count_holds_both_its_ends_and_refuses_past_them() {
    assert_eq!(check_count("n", 2, 2, 7), Ok(2));
    assert_eq!(check_count("n", 7, 2, 7), Ok(7));
    assert_eq!(check_count("n", 5, 2, 7), Ok(5));
    for bad in [0, 1, 8, usize::MAX] {
        let e = check_count("n", bad, 2, 7).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!("n: must be a whole number between 2 and 7, got {bad}")
        );
    }
}

#[test]
fn a_quote_keeps_forty_characters_and_cuts_a_longer_text_to_thirty_nine_and_an_ellipsis() {
    let forty = "é".repeat(40);
    assert_eq!(quote(&forty), format!("\"{forty}\""));
    let long = "x".repeat(41);
    assert_eq!(quote(&long), format!("\"{}\"…", "x".repeat(39)));
    // Characters, not bytes: 30 two-byte characters are under the limit.
    let short = "ü".repeat(30);
    assert_eq!(quote(&short), format!("\"{short}\""));
    assert_eq!(quote(""), "\"\"");
}
