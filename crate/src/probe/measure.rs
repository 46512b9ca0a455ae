//! The measured centres, read from a file: one line per pose.
//!
//! ```text
//! # comment lines start with '#'
//! pose;C_deg;A_deg;X_mm;Y_mm;Z_mm
//! ref;0;0;+0,0012;-0,0008;+150,0003
//! 1;30;0;0,0031;0,0007;150,0011
//! ```
//!
//! * **Columns** (any order, names case-insensitive, each with its unit): K and M, named `k`,
//!   `m` or by their axis letters (`c`, `a` …, when the machine is known), in `deg` (the
//!   default) or `rad`; the measured centre `x`, `y`, `z` (linear-axis positions, machine
//!   coordinates, module docs of [`super`]) in `mm` (the default), `um` or `µm`. A unit is
//!   written `x_mm`, `x (mm)`, `x [mm]` or `x/mm`. Optional: `pose` (a label); columns whose
//!   names start with `expected` or `tilt` (the designer's export) are read as information only.
//! * **Separators**: a tab, `;`, `,` (as the header has), or runs of spaces; with anything but
//!   `,` a decimal comma is read (`0,0012`). Explicit `+` signs, CRLF line ends, a byte-order
//!   mark, blank lines and `#` comments are accepted ([`crate::csv`]).
//! * **The reference pose**: the first line may be the reference pose (K = M = 0, or labelled
//!   `ref`/`reference`), as probing cycles measure it first to find the sphere; it is one pose
//!   like the others in the fit (the sphere's position is fitted from all of them) and is
//!   reported as [`Measurements::reference`].
//!
//! Every problem names its line: `csv: line 7: Z "1,2,3" is not a number`.

use crate::csv;
use crate::error::{quote, Error, Result};
use crate::identify::csv::line_error;
use serde::Serialize;

/// Largest accepted rotary command, degrees.
const MAX_ANGLE_DEG: f64 = 3600.0;
/// Largest accepted linear position, mm.
const MAX_POSITION: f64 = 100_000.0;

/// One measured pose.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct MeasuredPose {
    /// Line of the file.
    pub line: usize,
    /// Its label (`pose` column), or the pose's number.
    pub label: String,
    /// K's command, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub k: f64,
    /// M's command, degrees (radians in Rust).
    #[serde(serialize_with = "crate::edge::degrees")]
    pub m: f64,
    /// The measured centre X, Y, Z, mm.
    pub centre: [f64; 3],
}

/// A measurement file read.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct Measurements {
    /// The poses in file order.
    pub poses: Vec<MeasuredPose>,
    /// Index of the reference pose when the first line is one (module docs).
    pub reference: Option<usize>,
    /// The separator found: "tab", ";", "," or "spaces".
    pub separator: String,
}

#[derive(Clone, Copy, PartialEq)]
enum Col {
    Label,
    K(f64),
    M(f64),
    Axis(usize, f64),
    Ignored,
}

fn column(cell: &str, letters: Option<[char; 2]>, line: usize) -> Result<Col> {
    let (name, unit) = csv::split_unit(cell);
    if name.starts_with("expected") || name.starts_with("tilt") {
        return Ok(Col::Ignored);
    }
    if name == "pose" {
        return Ok(Col::Label);
    }
    let angle_unit = |u: &Option<String>| -> Result<f64> {
        match u.as_deref() {
            None | Some("deg") | Some("°") | Some("degrees") => Ok(1.0),
            Some("rad") => Ok(1f64.to_degrees()),
            Some(other) => Err(line_error(
                line,
                format!(
                    "column {}: unknown angle unit {}; use deg or rad",
                    quote(cell),
                    quote(other)
                ),
            )),
        }
    };
    let lower = |c: char| c.to_ascii_lowercase().to_string();
    let is_k = name == "k" || letters.is_some_and(|[k, _]| name == lower(k));
    let is_m = name == "m" || letters.is_some_and(|[_, m]| name == lower(m));
    if is_k {
        return Ok(Col::K(angle_unit(&unit)?));
    }
    if is_m {
        return Ok(Col::M(angle_unit(&unit)?));
    }
    if let Some(axis) = ["x", "y", "z"].iter().position(|a| *a == name) {
        let f = match unit.as_deref() {
            None | Some("mm") => 1.0,
            Some("um") | Some("µm") => 1e-3,
            Some(other) => {
                return Err(line_error(
                    line,
                    format!(
                        "column {}: unknown length unit {}; use mm or um",
                        quote(cell),
                        quote(other)
                    ),
                ))
            }
        };
        return Ok(Col::Axis(axis, f));
    }
    let rotary = letters.map_or("k, m".to_string(), |[k, m]| {
        format!("{k} (or k), {m} (or m)")
    });
    Err(line_error(
        line,
        format!(
            "unknown column {}; expected {rotary} in deg, x, y, z in mm (optional pose)",
            quote(cell)
        ),
    ))
}

/// The cells of a line: split at `sep`, or at runs of spaces when `sep` is `' '`.
fn cells(line: &str, sep: char) -> Vec<&str> {
    if sep == ' ' {
        line.split_whitespace().collect()
    } else {
        csv::cells(line, sep)
    }
}

/// Reads the measured centres (module docs); `letters`: the machine's K and M letters, so that
/// the columns may be named after them.
pub fn read(text: &str, letters: Option<[char; 2]>) -> Result<Measurements> {
    let mut lines = csv::lines(text);
    let (header_line, header) = lines.next().ok_or_else(|| {
        Error::field(
            "csv",
            "the file is empty: expected a header such as k_deg;m_deg;x_mm;y_mm;z_mm and one line per pose",
        )
    })?;
    let sep = csv::separator(header).unwrap_or(' ');
    let cols: Vec<Col> = cells(header, sep)
        .iter()
        .map(|c| column(c, letters, header_line))
        .collect::<Result<_>>()?;
    let find = |f: &dyn Fn(&Col) -> bool, what: &str| -> Result<usize> {
        let hits: Vec<usize> = (0..cols.len()).filter(|&i| f(&cols[i])).collect();
        match hits.len() {
            1 => Ok(hits[0]),
            0 => Err(line_error(
                header_line,
                format!("missing column {what} in the header"),
            )),
            _ => Err(line_error(
                header_line,
                format!("two columns for {what}; keep one"),
            )),
        }
    };
    let kc = find(&|c| matches!(c, Col::K(_)), "K")?;
    let mc = find(&|c| matches!(c, Col::M(_)), "M")?;
    let xyz = [0, 1, 2].map(|a| {
        find(
            &|c| matches!(c, Col::Axis(b, _) if *b == a),
            ["X", "Y", "Z"][a],
        )
    });
    let [xc, yc, zc] = xyz;
    let axis_cols = [xc?, yc?, zc?];
    let label_col = cols.iter().position(|c| *c == Col::Label);
    let factor = |i: usize| match cols[i] {
        Col::K(f) | Col::M(f) | Col::Axis(_, f) => f,
        _ => 1.0,
    };
    let mut poses = Vec::new();
    for (line, row) in lines {
        let cs = cells(row, sep);
        if cs.len() != cols.len() {
            return Err(line_error(
                line,
                format!(
                    "expected {} values like the header, got {}",
                    cols.len(),
                    cs.len()
                ),
            ));
        }
        let value = |i: usize, what: &str, limit: f64| -> Result<f64> {
            let cell = cs[i];
            if cell.is_empty() {
                return Err(line_error(
                    line,
                    format!("{what} is empty: fill in the measured value"),
                ));
            }
            let v = csv::number(cell, sep).ok_or_else(|| {
                line_error(line, format!("{what} {} is not a number", quote(cell)))
            })? * factor(i);
            if v.abs() > limit {
                return Err(line_error(
                    line,
                    format!(
                        "{what} {} is out of range (at most {limit} in size)",
                        quote(cell)
                    ),
                ));
            }
            Ok(v)
        };
        let k = value(kc, "K", MAX_ANGLE_DEG)?;
        let m = value(mc, "M", MAX_ANGLE_DEG)?;
        let mut centre = [0.0; 3];
        for (a, &c) in axis_cols.iter().enumerate() {
            centre[a] = value(c, ["X", "Y", "Z"][a], MAX_POSITION)?;
        }
        let label = label_col.map_or_else(|| (poses.len() + 1).to_string(), |c| cs[c].to_string());
        poses.push(MeasuredPose {
            line,
            label,
            k: k.to_radians(),
            m: m.to_radians(),
            centre,
        });
    }
    if poses.len() < 2 {
        return Err(Error::field(
            "csv",
            format!(
                "{} pose{} measured: the sphere must be probed at several poses of the rotary axes",
                poses.len(),
                if poses.len() == 1 { "" } else { "s" }
            ),
        ));
    }
    let first = &poses[0];
    let labelled = ["ref", "reference"].contains(&first.label.to_lowercase().as_str());
    let reference = (labelled || (first.k == 0.0 && first.m == 0.0)).then_some(0);
    let separator = match sep {
        '\t' => "tab",
        ' ' => "spaces",
        ';' => ";",
        _ => ",",
    }
    .to_string();
    Ok(Measurements {
        poses,
        reference,
        separator,
    })
}
