//! Identification of the machine's location errors from deviations measured at the 100 points
//! (Chanal et al. 2022, Section 6, Table 4, Fig 21): the measurement file, a linear least-squares
//! fit with general rank detection, and the residuals.
//!
//! # The measurement file (CSV)
//! One line per point, 100 lines, any order, with a header naming the columns:
//!
//! ```text
//! # comment lines start with '#'; blank lines are ignored
//! curve,point,deviation_mm
//! top,1,0.0123
//! bottom,50,-0.0310
//! ```
//!
//! * `curve`: `top` (z = 25 mm) or `bottom` (z = 11 mm) (also `T`/`B`, `Z25`/`Z11`, `25`/`11`);
//! * `point`: 1..50 (1..25 on surface A, 26..50 on surface B, see [`super::part`]);
//! * `deviation_mm` (or `deviation`, also mm) or `deviation_um` (µm): the measured deviation along
//!   the outward normal, positive where the surface lies outside its nominal position.
//!
//! Separators: comma, semicolon or tab. Every problem is reported with its line number
//! (`csv: line 7: "0,01x" is not a number`); a missing point is named.
//!
//! # The fit
//! The least squares, the rank, the weak directions and the decision per error are the
//! project's one identification module, [`crate::identify`] (shared with the cubic test).

pub use crate::identify::{combination_text, fit, Combination, Estimate, Fit, Group, DEFAULT_RTOL};

use crate::error::{check_range, quote, Error, Result};
use crate::identify::csv::{line_error, Table};

use super::part::{index_of, parse_curve, Curve, N_POINTS, POINTS_PER_CURVE};

/// Parses the measurement CSV into 100 deviations (mm) in list order (TOP 1..50, BOTTOM 1..50).
pub fn parse_measurements(text: &str) -> Result<Vec<f64>> {
    let table = Table::read(text, "curve,point,deviation_mm")?;
    let hline = table.header_line;
    let col_curve = table.column(&["curve"]).ok_or_else(|| {
        line_error(
            hline,
            "missing column 'curve' in the header (top or bottom)",
        )
    })?;
    let col_point = table
        .column(&["point"])
        .ok_or_else(|| line_error(hline, "missing column 'point' in the header (1..50)"))?;
    let (col_dev, scale) = table.length_column("deviation")?.ok_or_else(|| {
        line_error(
            hline,
            "missing column 'deviation_mm' (or 'deviation_um') in the header",
        )
    })?;
    let err = line_error;
    let mut values: Vec<Option<(f64, usize)>> = vec![None; N_POINTS];
    for (line, cells) in table.rows()? {
        let curve = parse_curve(cells[col_curve]).map_err(|e| err(line, e.message))?;
        let number: usize = cells[col_point].parse().map_err(|_| {
            err(
                line,
                format!(
                    "point {} is not a whole number 1..50",
                    quote(cells[col_point])
                ),
            )
        })?;
        if !(1..=2 * POINTS_PER_CURVE).contains(&number) {
            return Err(err(line, format!("point {number} is outside 1..50")));
        }
        let value = table.number(line, cells[col_dev], "deviation")? * scale;
        check_range("deviation", value, -10.0, 10.0, "mm")
            .map_err(|e| err(line, format!("deviation {}", e.message)))?;
        let k = index_of(curve, number);
        if let Some((_, first)) = values[k] {
            return Err(err(
                line,
                format!(
                    "point {} {number} is given twice (first on line {first})",
                    curve.name()
                ),
            ));
        }
        values[k] = Some((value, line));
    }
    let missing: Vec<String> = values
        .iter()
        .enumerate()
        .filter(|(_, v)| v.is_none())
        .map(|(k, _)| {
            let curve = if k < 2 * POINTS_PER_CURVE {
                Curve::Top
            } else {
                Curve::Bottom
            };
            format!("{} {}", curve.name(), k % (2 * POINTS_PER_CURVE) + 1)
        })
        .collect();
    if !missing.is_empty() {
        let shown: Vec<&str> = missing.iter().take(8).map(String::as_str).collect();
        return Err(Error::field(
            "csv",
            format!(
                "{} of the 100 points are missing: {}{}",
                missing.len(),
                shown.join(", "),
                if missing.len() > 8 { ", …" } else { "" }
            ),
        ));
    }
    Ok(values.into_iter().map(|v| v.map_or(0.0, |x| x.0)).collect())
}
