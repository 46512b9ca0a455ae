//! The measurement files' common reading: comment lines (`#`) and blank lines skipped, a header
//! naming the columns (units in the names: `height_mm`, `height_um`), comma, semicolon or tab
//! (the header's decides; with `;` or tab a decimal comma is accepted: `0,0208`), every problem
//! reported as `csv: line 12: …` with the file's own line number. The lines, cells and numbers
//! come from the engine's one tokenizer, [`crate::csv`].

use crate::csv;
use crate::error::{quote, Error, Result};

/// The error of a line: `csv: line {line}: {msg}`.
pub fn line_error(line: usize, msg: impl std::fmt::Display) -> Error {
    Error::field("csv", format!("line {line}: {msg}"))
}

/// A file read into its header and rows (cells trimmed, quotes removed).
#[derive(Debug, Clone)]
pub struct Table<'a> {
    /// Line number of the header.
    pub header_line: usize,
    /// Column names, lower case.
    pub names: Vec<String>,
    /// `(line number, text)` per data row.
    lines: Vec<(usize, &'a str)>,
    sep: char,
}

impl<'a> Table<'a> {
    /// Reads `text`; `expected` is the header to suggest in messages (`curve,point,deviation_mm`).
    pub fn read(text: &'a str, expected: &str) -> Result<Self> {
        let mut lines = csv::lines(text);
        let (header_line, header) = lines.next().ok_or_else(|| {
            Error::field(
                "csv",
                format!("the file is empty: expected a header line {expected} and the rows"),
            )
        })?;
        let sep = csv::separator(header).ok_or_else(|| {
            line_error(
                header_line,
                format!(
                    "the header {} has no separator; expected {expected}",
                    quote(header)
                ),
            )
        })?;
        let names: Vec<String> = csv::cells(header, sep)
            .into_iter()
            .map(str::to_ascii_lowercase)
            .collect();
        Ok(Self {
            header_line,
            names,
            lines: lines.collect(),
            sep,
        })
    }

    /// `(line number, cells)` per data row, each with as many cells as the header (read after
    /// the header's columns are checked, so that a header problem is reported first).
    pub fn rows(&self) -> Result<Vec<(usize, Vec<&'a str>)>> {
        self.lines
            .iter()
            .map(|&(line, row)| {
                let cells = csv::cells(row, self.sep);
                if cells.len() == self.names.len() {
                    Ok((line, cells))
                } else {
                    Err(line_error(
                        line,
                        format!(
                            "expected {} columns like the header, got {}",
                            self.names.len(),
                            cells.len()
                        ),
                    ))
                }
            })
            .collect()
    }

    /// The index of the first column named one of `want`.
    pub fn column(&self, want: &[&str]) -> Option<usize> {
        self.names.iter().position(|n| want.contains(&n.as_str()))
    }

    /// The column `base` with its unit in the name: `base_mm` (or `base` alone, mm) or
    /// `base_um` / `base_µm` (µm). Returns the column and the factor to mm; an error when both
    /// units are given; `None` when neither.
    pub fn length_column(&self, base: &str) -> Result<Option<(usize, f64)>> {
        let mm = [format!("{base}_mm"), base.to_string()];
        let um = [format!("{base}_um"), format!("{base}_µm")];
        let find = |names: &[String]| self.names.iter().position(|n| names.contains(n));
        match (find(&mm), find(&um)) {
            (Some(c), None) => Ok(Some((c, 1.0))),
            (None, Some(c)) => Ok(Some((c, 1e-3))),
            (Some(_), Some(_)) => Err(line_error(
                self.header_line,
                format!("two {base} columns (mm and µm); keep one"),
            )),
            (None, None) => Ok(None),
        }
    }

    /// A finite number from a cell (a decimal comma when the separator is `;` or tab), or an
    /// error naming the line and `what`.
    pub fn number(&self, line: usize, cell: &str, what: &str) -> Result<f64> {
        csv::number(cell, self.sep)
            .ok_or_else(|| line_error(line, format!("{what} {} is not a number", quote(cell))))
    }
}
