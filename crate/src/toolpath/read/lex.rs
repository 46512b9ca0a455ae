//! What every reader shares: where a token is (line and column, for messages), numbers of the
//! readers' grammar, and the checks of a coordinate and a tool axis.

use super::FIELD;
use crate::error::Error;
use nalgebra::Vector3;
use std::fmt;

/// Largest coordinate accepted, mm (absolute value).
pub const MAX_COORDINATE: f64 = 1e5;
/// Largest NC rotary angle accepted, degrees (absolute value): a thousand turns (a continuous
/// table programmed turn after turn with literal commands).
pub const MAX_ANGLE: f64 = 360_000.0;

/// A piece of a statement's text that starts at column 1 of line `line`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Seg {
    /// Byte offset of the piece in the statement.
    pub start: usize,
    pub line: u32,
}

/// A statement's text and where its pieces come from, to report errors at a line and column.
pub(super) struct Loc<'a> {
    pub text: &'a str,
    pub segs: &'a [Seg],
}

impl<'a> Loc<'a> {
    /// The one-line statement `text` of line `line`.
    pub fn line(text: &'a str, segs: &'a [Seg; 1]) -> Self {
        Loc { text, segs }
    }

    /// Line and 1-based column (in characters) of byte `off` of the text.
    pub fn at(&self, off: usize) -> (u32, usize) {
        let seg = self
            .segs
            .iter()
            .rev()
            .find(|s| s.start <= off)
            .copied()
            .unwrap_or(Seg { start: 0, line: 0 });
        let col = self
            .text
            .get(seg.start..off)
            .map_or(0, |s| s.chars().count());
        (seg.line, col + 1)
    }

    /// The line of byte `off`.
    pub fn line_of(&self, off: usize) -> u32 {
        self.at(off).0
    }

    /// An error at byte `off`: `line L, column C: msg`.
    pub fn err(&self, off: usize, msg: impl fmt::Display) -> Error {
        let (l, c) = self.at(off);
        Error::field(FIELD, format!("line {l}, column {c}: {msg}"))
    }
}

/// A token as shown in a message: quoted, at most 40 characters ([`crate::error::quote`]).
pub(super) fn shown(tok: &str) -> String {
    crate::error::quote(tok)
}

/// Reads a number of the readers' grammar, `[+-]digits[.digits]` or `[+-].digits` (with an
/// exponent `e±n` when `exponent`); `None` if `tok` is not one ([`crate::csv::decimal`]).
pub(super) fn number(tok: &str, exponent: bool) -> Option<f64> {
    crate::csv::decimal(tok, exponent)
}

/// The length of the number at the start of `b` (sign, digits and one decimal point, no
/// exponent): NC words run together (`X10Y-2.5`).
pub(super) fn number_len(b: &[u8]) -> usize {
    let mut i = usize::from(matches!(b.first(), Some(b'+' | b'-')));
    let mut point = false;
    while i < b.len() {
        match b[i] {
            b'0'..=b'9' => i += 1,
            b'.' if !point => {
                point = true;
                i += 1;
            }
            _ => break,
        }
    }
    i
}

/// Names of the six numbers of a point.
pub(super) const NAMES: [&str; 6] = ["x", "y", "z", "i", "j", "k"];

/// Six numbers of a point read from a statement: values, byte offsets, tokens.
pub(super) struct Fields<'a> {
    pub vals: [f64; 6],
    pub offs: [usize; 6],
    pub toks: [&'a str; 6],
}

impl Fields<'_> {
    pub fn new() -> Self {
        Fields {
            vals: [0.0; 6],
            offs: [0; 6],
            toks: [""; 6],
        }
    }
}

/// A coordinate `v` (token `tok` at `off`, named `name`) checked against [`MAX_COORDINATE`].
pub(super) fn coordinate(
    loc: &Loc,
    off: usize,
    name: &str,
    tok: &str,
    v: f64,
) -> Result<f64, Error> {
    if v.abs() <= MAX_COORDINATE {
        Ok(v)
    } else {
        Err(loc.err(
            off,
            format!(
                "expected {name} within ±{MAX_COORDINATE} mm, got {}",
                shown(tok)
            ),
        ))
    }
}

/// The tip from fields 0..3.
pub(super) fn tip(loc: &Loc, f: &Fields) -> Result<Vector3<f64>, Error> {
    let mut p = Vector3::zeros();
    for n in 0..3 {
        p[n] = coordinate(loc, f.offs[n], NAMES[n], f.toks[n], f.vals[n])?;
    }
    Ok(p)
}

/// The unit tool axis from fields 3..6 (i, j, k): any finite non-zero length.
pub(super) fn unit_axis(loc: &Loc, f: &Fields) -> Result<Vector3<f64>, Error> {
    let from = 3;
    let mut v = Vector3::zeros();
    for n in 0..3 {
        let x = f.vals[from + n];
        if !x.is_finite() {
            return Err(loc.err(
                f.offs[from + n],
                format!(
                    "expected a finite number for {}, got {}",
                    NAMES[3 + n],
                    shown(f.toks[from + n])
                ),
            ));
        }
        v[n] = x;
    }
    unit(&v).ok_or_else(|| {
        loc.err(
            f.offs[from],
            format!(
                "expected a non-zero tool axis (i, j, k), got ({}, {}, {})",
                f.toks[from],
                f.toks[from + 1],
                f.toks[from + 2]
            ),
        )
    })
}

/// `v` scaled to unit length, `None` for a zero or non-finite vector (scaled by its largest
/// component first, so that neither tiny nor huge components under- or overflow).
pub(super) fn unit(v: &Vector3<f64>) -> Option<Vector3<f64>> {
    let scale = v.amax();
    if scale == 0.0 || !scale.is_finite() {
        return None;
    }
    let v = v / scale;
    Some(v / v.norm())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fast_path_gives_the_bits_of_str_parse() {
        // Every decimal of up to 7 decimals from a simple generator, and edge cases.
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut cases: Vec<String> = [
            "0",
            "-0",
            "+0.0",
            "1.",
            ".5",
            "-.5",
            "9007199254740992",
            "9007199254740993",
            "0.1",
            "0.3",
            "123456789.123456",
            "1.0000000000000000000001",
            "-99999.123456",
            // Around the 19 digits gathered without an overflow check (then `str::parse`).
            "9999999999999999999",
            "999999999999999999.9",
            "18446744073709551615",
            "18446744073709551616",
            "0000000000000000000001.5",
            "1234567890.1234567890123",
        ]
        .iter()
        .map(|s| (*s).to_string())
        .collect();
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let int = x % 1_000_000;
            let dec = (x >> 20) % 10_000_000;
            let places = ((x >> 45) % 8) as usize;
            let sign = if x & 1 == 0 { "-" } else { "" };
            cases.push(format!(
                "{sign}{int}.{:0places$}",
                dec % 10u64.pow(places as u32)
            ));
        }
        for c in &cases {
            let want: f64 = c.parse().unwrap_or(f64::NAN);
            let got = number(c, false).unwrap_or(f64::NAN);
            assert_eq!(got.to_bits(), want.to_bits(), "{c}");
        }
    }
}
