//! CSV points: one a line, `x,y,z,i,j,k`, the tool tip and the tool axis in workpiece
//! coordinates, every point a feed move.
//!
//! Fields are separated by semicolons, else by commas (then spaces around them are ignored),
//! else by spaces and tabs. In a line separated by semicolons or holding a tab, a comma is a
//! **decimal comma** (`1,5;2;3;0;0;1`, `1,5<tab>2<tab>…`), as European measuring software writes
//! it, the same rule as [`crate::csv`]. One trailing separator is allowed (`1,2,3,0,0,1,`).
//! Blank lines and lines starting with `#` are skipped; the first other line is a header, and
//! skipped, when none of its fields is a number. The file states no unit: the points are in the
//! unit of [`super::ReadOptions::unit`] (mm by default).

use super::lex::{number, shown, tip, unit_axis, Fields, Loc, Seg, NAMES};
use super::{Log, Motion, Point};
use crate::error::Result;

/// The CSV reader.
#[derive(Debug, Clone, Default)]
pub struct Csv {
    /// The first line that is not blank or a comment has been read (it may be a header).
    started: bool,
}

/// How a CSV line is separated (module docs).
#[derive(Clone, Copy, PartialEq)]
enum CsvSep {
    /// `;`; a comma is a decimal comma.
    Semicolon,
    /// `,` (and `;` is absent).
    Comma,
    /// Spaces and tabs; with a tab in the line a comma is a decimal comma.
    Blank { decimal_comma: bool },
}

impl CsvSep {
    fn of(line: &str) -> CsvSep {
        if line.contains(';') {
            CsvSep::Semicolon
        } else if line.contains('\t') {
            CsvSep::Blank {
                decimal_comma: true,
            }
        } else if line.contains(',') {
            CsvSep::Comma
        } else {
            CsvSep::Blank {
                decimal_comma: false,
            }
        }
    }

    fn splits(self, c: char) -> bool {
        match self {
            CsvSep::Semicolon => c == ';',
            CsvSep::Comma => c == ',',
            CsvSep::Blank { .. } => c.is_whitespace(),
        }
    }

    /// The number in a field: with a decimal comma `1,5` is 1.5.
    fn number(self, tok: &str) -> Option<f64> {
        let decimal_comma = matches!(
            self,
            CsvSep::Semicolon
                | CsvSep::Blank {
                    decimal_comma: true
                }
        );
        if decimal_comma && tok.contains(',') {
            // One comma at most: `1,5` is a number; `1,5,2` and `1.000,5`, with two points
            // once the commas are points, are not.
            number(&tok.replace(',', "."), true)
        } else {
            number(tok, true)
        }
    }
}

/// The fields of a CSV line: byte offset and trimmed text of each (module docs).
fn csv_fields(line: &str) -> impl Iterator<Item = (usize, &str)> + '_ {
    let sep = CsvSep::of(line);
    let delimited = !matches!(sep, CsvSep::Blank { .. });
    let mut body = line.trim_end();
    if delimited {
        body = body.strip_suffix(|c: char| sep.splits(c)).unwrap_or(body);
    }
    let base = body.as_ptr() as usize;
    body.split(move |c: char| sep.splits(c))
        .filter(move |p| delimited || !p.is_empty())
        .map(move |p| {
            let t = p.trim();
            let off = if t.is_empty() {
                p.as_ptr() as usize - base
            } else {
                t.as_ptr() as usize - base
            };
            (off, t)
        })
}

impl Csv {
    pub(super) fn line(
        &mut self,
        line: &str,
        no: u32,
        log: &mut Log,
        out: &mut Vec<Point>,
    ) -> Result<()> {
        csv_line(line, no, &mut self.started, log, out)
    }
}

fn csv_line(
    line: &str,
    no: u32,
    started: &mut bool,
    log: &mut Log,
    out: &mut Vec<Point>,
) -> Result<()> {
    let t = line.trim();
    if t.is_empty() || t.starts_with('#') {
        return Ok(());
    }
    let sep = CsvSep::of(line);
    if !*started {
        *started = true;
        if !csv_fields(line).any(|(_, tok)| sep.number(tok).is_some()) {
            return Ok(()); // the header
        }
    }
    log.blocks += 1;
    let segs = [Seg { start: 0, line: no }];
    let loc = Loc {
        text: line,
        segs: &segs,
    };
    let mut f = Fields::new();
    let mut n = 0;
    for (off, tok) in csv_fields(line) {
        if n == 6 {
            let count = csv_fields(line).count();
            return Err(loc.err(off, format!("expected 6 numbers x,y,z,i,j,k, got {count}")));
        }
        f.vals[n] = sep.number(tok).ok_or_else(|| {
            loc.err(
                off,
                format!("expected a number for {}, got {}", NAMES[n], shown(tok)),
            )
        })?;
        f.offs[n] = off;
        f.toks[n] = tok;
        n += 1;
    }
    if n < 6 {
        let mut end = line.trim_end();
        end = end.strip_suffix(|c: char| sep.splits(c)).unwrap_or(end);
        return Err(loc.err(
            end.len(),
            format!("expected 6 numbers x,y,z,i,j,k, got {n}"),
        ));
    }
    let (scale, _) = log.scale();
    out.push(Point {
        tip: tip(&loc, &f)? * scale,
        axis: unit_axis(&loc, &f)?,
        line: no,
        motion: Motion::Feed,
        angles: None,
    });
    Ok(())
}
