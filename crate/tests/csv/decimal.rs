//! The one decimal reader of the engine (`fiveaxis::csv::decimal`, used by every CSV reader and
//! the toolpath readers): its grammar, `[+-]digits[.digits]` or `[+-].digits`, with an exponent
//! only where the caller accepts one, and its values the bits `str::parse` gives (the standard
//! library's correctly rounded reader: an independent reference).
// Found by cargo-mutants: the exponent's and the second decimal point's checks changed no
// outcome of the tests before this file (the lexer's test reads no exponent and no second
// point).

#![allow(clippy::unwrap_used)]

use fiveaxis::csv::decimal;

fn same(tok: &str) {
    let want: f64 = tok.parse().unwrap();
    let got = decimal(tok, true).unwrap_or_else(|| panic!("{tok}: not read"));
    assert_eq!(got.to_bits(), want.to_bits(), "{tok}");
}

#[test]
fn an_exponent_is_read_where_it_is_accepted_and_refused_elsewhere() {
    for tok in [
        "1e5",
        "-2.5E-3",
        "+4e+2",
        ".5e1",
        "7.E2",
        "1e308",
        "12345.678e-20",
    ] {
        same(tok);
        assert_eq!(decimal(tok, false), None, "{tok} without exponents");
    }
    // Too large for a double: infinite, as the docs say (the CSV reader then refuses it).
    assert_eq!(decimal("1e999", true), Some(f64::INFINITY));
}

#[test]
fn what_is_not_a_number_of_the_grammar_is_none() {
    for tok in [
        "", "-", "+", ".", "-.", "e5", "1e", "1e+", "1e5x", "1.5x", "1.2.3", "1..2", "x1", "1 2",
        "--1", "0x10", "inf", "NaN",
    ] {
        assert_eq!(decimal(tok, true), None, "{tok:?}");
    }
}

#[test]
fn more_than_2_to_the_53_in_digits_is_read_as_parse_reads_it() {
    // 17 significant digits: the integer of the digits is above 2⁵³, so `m as f64 / 10^k` would
    // round twice; these three (found by a search against Python's correctly rounded float())
    // come out one bit off that way. The reader must give parse's bits.
    for tok in [
        "850466103.52879496",
        "124299667724.658516",
        "92471.31068846352888",
    ] {
        same(tok);
        same(&format!("-{tok}"));
    }
}
