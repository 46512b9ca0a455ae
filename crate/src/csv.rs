//! The one CSV tokenizer every reader of measured data shares: the S-shape's measured
//! deviations ([`crate::sshape::identify`]), the cubic test's zone table
//! ([`crate::cubic::identify`]), the reversal trace ([`crate::reversal::fit`]) and the tables of
//! error motions ([`crate::machine::motions::read_table_csv`]).
//!
//! * Lines: numbered from 1 as in the file; blank lines and lines starting with `#` are skipped;
//!   a byte-order mark at the start is dropped.
//! * Separator: a tab if the line has one, else `;` if it has one, else `,`.
//! * **Decimal comma**: when the separator is `;` or a tab, a `,` inside a number is its decimal
//!   comma, as European measuring software writes it: `1,5;2,5` is 1.5 and 2.5. With `,` as the
//!   separator a comma only separates: `1,5,2,5` is four cells.
//! * Cells are trimmed and their surrounding double quotes removed.
//!
//! Messages quote what the user gave through [`crate::error::quote`] (at most 40 characters).

/// The lines that hold data or a header: `(line number, text trimmed)`, without blank lines,
/// `#` comments and a leading byte-order mark.
pub fn lines(text: &str) -> impl Iterator<Item = (usize, &str)> + '_ {
    text.lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim().trim_start_matches('\u{feff}').trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'))
}

/// The separator of a line: a tab, else `;`, else `,`; `None` when the line has none.
pub fn separator(line: &str) -> Option<char> {
    ['\t', ';', ','].into_iter().find(|c| line.contains(*c))
}

/// The cells of `line` split at `sep`, trimmed, surrounding double quotes removed.
pub fn cells(line: &str, sep: char) -> Vec<&str> {
    line.split(sep)
        .map(|c| c.trim().trim_matches('"').trim())
        .collect()
}

/// A finite number from a cell of a line separated by `sep`: `0.0208`, `-2e-3`, and with `;` or
/// a tab as the separator also `0,0208` (a decimal comma). `None` when it is not one.
pub fn number(cell: &str, sep: char) -> Option<f64> {
    let cell = cell.trim();
    let decimal_comma = sep != ',' && cell.matches(',').count() == 1 && !cell.contains('.');
    let parsed = if decimal_comma {
        decimal(&cell.replace(',', "."), true)
    } else {
        decimal(cell, true)
    };
    parsed.filter(|v| v.is_finite())
}

/// Reads a decimal number, the grammar of every reader of the engine: `[+-]digits[.digits]` or `[+-].digits` (with an
/// exponent `e±n` when `exponent`); `None` if `tok` is not one. The value may be infinite when
/// the exponent overflows.
///
/// One pass over the bytes: the digits are gathered as an integer `m` with `k` decimals, and when
/// `m ≤ 2⁵³` and `k ≤ 22` (every coordinate a CAM system writes) the value is `m / 10^k`, exact
/// doubles divided once: correctly rounded by Clinger's fast path, the bits `str::parse` gives.
/// Otherwise (an exponent, more digits) `str::parse` reads the token. (A toolpath holds 10⁵ to
/// 10⁷ numbers: this is most of the reading time; in WebAssembly `str::parse` is slower still,
/// its 128-bit multiplies being calls.)
pub fn decimal(tok: &str, exponent: bool) -> Option<f64> {
    let b = tok.as_bytes();
    let neg = b.first() == Some(&b'-');
    let mut i = usize::from(matches!(b.first(), Some(b'+' | b'-')));
    // The integer part, then the decimals: no test per digit but the digit's own. More than 19
    // digits may wrap `m` (10¹⁹ − 1 < 2⁶⁴ always fits): such a token is left to `str::parse`.
    let mut m = 0u64;
    let whole = i;
    while let Some(c @ b'0'..=b'9') = b.get(i) {
        m = m.wrapping_mul(10).wrapping_add(u64::from(c - b'0'));
        i += 1;
    }
    let mut count = i - whole;
    let mut k = 0;
    if b.get(i) == Some(&b'.') {
        i += 1;
        let decimals = i;
        while let Some(c @ b'0'..=b'9') = b.get(i) {
            m = m.wrapping_mul(10).wrapping_add(u64::from(c - b'0'));
            i += 1;
        }
        k = i - decimals;
        count += k;
    }
    let exact = count <= 19;
    if count == 0 {
        return None;
    }
    if i < b.len() {
        // Only an exponent may follow.
        if !exponent || !matches!(b[i], b'e' | b'E') {
            return None;
        }
        i += 1;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        let digits = b[i..].iter().take_while(|c| c.is_ascii_digit()).count();
        if digits == 0 || i + digits != b.len() {
            return None;
        }
        return tok.parse().ok();
    }
    if exact && m <= 1 << 53 && k < POW10.len() {
        let v = m as f64 / POW10[k];
        return Some(if neg { -v } else { v });
    }
    tok.parse().ok()
}

/// Powers of ten exactly representable as `f64`.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// A unit a measuring program may write in a CSV header, and its factor to the API unit (mm or
/// degrees) of its kind.
pub fn unit_factor(unit: &str, angle: bool) -> Option<f64> {
    let u = unit.trim().to_lowercase().replace('μ', "µ");
    let (len, ang) = match u.as_str() {
        "mm" => (Some(1.0), None),
        "µm" | "um" | "micron" | "microns" => (Some(1e-3), None),
        "nm" => (Some(1e-6), None),
        "m" => (Some(1e3), None),
        "in" | "inch" => (Some(25.4), None),
        "deg" | "°" | "degree" | "degrees" => (None, Some(1.0)),
        "rad" => (None, Some(180.0 / std::f64::consts::PI)),
        "mrad" => (None, Some(0.180 / std::f64::consts::PI)),
        "µrad" | "urad" => (None, Some(1.8e-4 / std::f64::consts::PI)),
        "arcsec" | "″" | "\"" | "sec" | "as" => (None, Some(1.0 / 3600.0)),
        "µm/m" | "um/m" => (None, Some(1.8e-4 / std::f64::consts::PI)),
        _ => (None, None),
    };
    if angle {
        ang
    } else {
        len
    }
}

/// The unit in a header cell: the text in `( )` or `[ ]`, or the cell itself.
pub fn header_unit(cell: &str) -> &str {
    for (open, close) in [('(', ')'), ('[', ']')] {
        if let (Some(a), Some(b)) = (cell.rfind(open), cell.rfind(close)) {
            if a < b {
                return &cell[a + 1..b];
            }
        }
    }
    cell
}

/// The name and the unit of a header cell, both lower case and trimmed: `x_mm`, `x (mm)`,
/// `x [mm]`, `x/mm` give `("x", Some("mm"))`; a cell without a unit gives `(name, None)`. A
/// unit in brackets may be anything (the reader judges it); one after `_` or `/` only counts
/// when it is `mm`, `um`, `µm`, `nm`, `deg`, `rad` or `°` (so `test_id` and `x_in` stay names).
pub fn split_unit(cell: &str) -> (String, Option<String>) {
    let c = cell.trim().to_lowercase();
    for (open, close) in [('(', ')'), ('[', ']')] {
        if let (Some(i), true) = (c.find(open), c.ends_with(close)) {
            let unit = c[i + open.len_utf8()..c.len() - close.len_utf8()]
                .trim()
                .to_string();
            return (c[..i].trim().to_string(), Some(unit));
        }
    }
    for sep in ['/', '_'] {
        if let Some(i) = c.rfind(sep) {
            let unit = &c[i + 1..];
            if ["mm", "um", "µm", "nm", "deg", "rad", "°"].contains(&unit) {
                return (c[..i].trim().to_string(), Some(unit.to_string()));
            }
        }
    }
    (c, None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimal_comma_only_where_the_separator_is_not_a_comma() {
        assert_eq!(separator("1,5;2,5"), Some(';'));
        assert_eq!(cells("1,5;2,5", ';'), vec!["1,5", "2,5"]);
        assert_eq!(number("1,5", ';'), Some(1.5));
        assert_eq!(number("-0,0208", '\t'), Some(-0.0208));
        assert_eq!(separator("1,5,2,5"), Some(','));
        assert_eq!(cells("1,5,2,5", ','), vec!["1", "5", "2", "5"]);
        assert_eq!(number("1,5", ','), None);
        // A thousands separator with a decimal point is not a number here.
        assert_eq!(number("1,000.5", ';'), None);
        assert_eq!(number("1,2,3", ';'), None);
        assert_eq!(number("inf", ';'), None);
    }

    #[test]
    fn a_header_cell_splits_into_its_name_and_unit() {
        let own = |n: &str, u: Option<&str>| (n.to_string(), u.map(str::to_string));
        assert_eq!(split_unit("X_mm"), own("x", Some("mm")));
        assert_eq!(split_unit(" Angle (deg) "), own("angle", Some("deg")));
        assert_eq!(split_unit("deviation [µm]"), own("deviation", Some("µm")));
        assert_eq!(split_unit("C/rad"), own("c", Some("rad")));
        assert_eq!(split_unit("angle (grad)"), own("angle", Some("grad")));
        assert_eq!(split_unit("test_id"), own("test_id", None));
        assert_eq!(split_unit("direction"), own("direction", None));
    }

    #[test]
    fn lines_skip_comments_blanks_and_the_byte_order_mark() {
        let got: Vec<_> = lines("\u{feff}a;b\n\n# note\n 1;2 \n").collect();
        assert_eq!(got, vec![(1, "a;b"), (4, "1;2")]);
    }
}
