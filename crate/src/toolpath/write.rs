//! Writers: a path in CSV, APT or ISO NC blocks, so that the readers read it back equal within
//! the written precision ([`write()`]).

use super::read::{Format, Motion, Point, FIELD};
use crate::error::{Error, Result};
use std::fmt::Write as _;

/// Decimals written for lengths in CSV and APT (1 nm).
const LENGTH_DECIMALS: usize = 6;
/// Decimals written for tool-axis components in CSV and APT.
const VECTOR_DECIMALS: usize = 9;
/// Decimals written for NC words, lengths (0.1 µm) and angles (0.0001°): what controls take.
const NC_DECIMALS: usize = 4;
/// APT lines longer than this are continued with `$` by the writer.
const APT_WIDTH: usize = 72;

/// Appends `x` with `decimals` decimals, trailing zeros dropped (keeping one after the point
/// when `keep_point`), and no sign on a zero.
fn push_num(out: &mut String, x: f64, decimals: usize, keep_point: bool) {
    let start = out.len();
    let _ = write!(out, "{x:.decimals$}");
    if out[start..].contains('.') {
        let kept = out[start..].trim_end_matches('0').len();
        out.truncate(start + kept);
        if out.ends_with('.') {
            if keep_point {
                out.push('0');
            } else {
                out.pop();
            }
        }
    } else if keep_point {
        out.push_str(".0");
    }
    if out[start..].starts_with('-') && out[start + 1..].bytes().all(|c| c == b'0' || c == b'.') {
        out.remove(start);
    }
}

/// Writes `points` in `format`, so that [`parse`] reads them back equal within the written
/// precision: lengths with 6 decimals (1 nm) and axis components with 9 in CSV and APT; NC
/// words with 4 decimals (0.1 µm, 0.0001°; what controls accept), always with a decimal point
/// (`X10.0`: some controls read `X10` in their least increment). A point with a coordinate,
/// axis component or angle that is not finite is an error.
/// * CSV: a `#` comment, the header `x,y,z,i,j,k`, one line a point.
/// * APT: two `$$` comment lines, `PARTNO TOOLPATH`, `UNITS/MM`, `MULTAX/ON`, a
///   `GOTO/x,y,z,i,j,k` a point (continued with `$` after z when longer than 72 characters),
///   `RAPID` before a point reached at rapid, `FINI`.
/// * NC: `%`, comments, `G90 G21`, then `X Y Z` and the two rotary words `letters` (K then M)
///   from each point's `angles`, with `G0` or `G1` where the motion changes (arc chords are
///   `G1`), `M30`, `%`. It needs the letters and every point's angles (the axis is not
///   written: the machine gives it), else an error. Switching tool-centre-point control on is
///   left to the user (a comment says so).
pub fn write(format: Format, points: &[Point], letters: Option<[char; 2]>) -> Result<String> {
    for (n, p) in points.iter().enumerate() {
        let angles = p.angles.unwrap_or_default();
        if !p
            .tip
            .iter()
            .chain(p.axis.iter())
            .chain(&angles)
            .all(|v| v.is_finite())
        {
            return Err(Error::field(
                FIELD,
                format!(
                    "point {} (line {}) is not finite: tip {:?}, axis {:?}, angles {:?}",
                    n + 1,
                    p.line,
                    p.tip.as_slice(),
                    p.axis.as_slice(),
                    p.angles
                ),
            ));
        }
    }
    let mut s = String::with_capacity(64 * points.len() + 256);
    match format {
        Format::Csv => {
            s.push_str(
                "# five-axis toolpath, workpiece coordinates: tool tip x, y, z (mm), tool axis \
                 i, j, k (unit, from the tip towards the spindle)\nx,y,z,i,j,k\n",
            );
            for p in points {
                for (n, v) in p.tip.iter().chain(p.axis.iter()).enumerate() {
                    if n > 0 {
                        s.push(',');
                    }
                    let d = if n < 3 {
                        LENGTH_DECIMALS
                    } else {
                        VECTOR_DECIMALS
                    };
                    push_num(&mut s, *v, d, false);
                }
                s.push('\n');
            }
        }
        Format::Apt => {
            s.push_str(
                "$$ five-axis toolpath, workpiece coordinates: GOTO/x,y,z,i,j,k,\n$$ tool tip \
                 in mm, tool axis from the tip towards the spindle\nPARTNO TOOLPATH\nUNITS/MM\n\
                 MULTAX/ON\n",
            );
            let mut xyz = String::new();
            let mut ijk = String::new();
            for p in points {
                xyz.clear();
                ijk.clear();
                for (n, v) in p.tip.iter().enumerate() {
                    if n > 0 {
                        xyz.push(',');
                    }
                    push_num(&mut xyz, *v, LENGTH_DECIMALS, false);
                }
                for (n, v) in p.axis.iter().enumerate() {
                    if n > 0 {
                        ijk.push(',');
                    }
                    push_num(&mut ijk, *v, VECTOR_DECIMALS, false);
                }
                if p.motion == Motion::Rapid {
                    s.push_str("RAPID\n");
                }
                s.push_str("GOTO/");
                s.push_str(&xyz);
                if 5 + xyz.len() + 1 + ijk.len() > APT_WIDTH {
                    s.push_str(",$\n");
                } else {
                    s.push(',');
                }
                s.push_str(&ijk);
                s.push('\n');
            }
            s.push_str("FINI\n");
        }
        Format::Siemens | Format::Heidenhain => {
            return Err(Error::field(
                "format",
                "the refined path is written as ISO NC blocks (nc), APT or CSV",
            ))
        }
        Format::Nc => {
            let [kl, ml] = letters.ok_or_else(|| {
                Error::field(
                    FIELD,
                    "NC blocks need the machine's rotary letters (K and M)",
                )
            })?;
            let _ = write!(
                s,
                "%\n(five-axis toolpath: X Y Z tool tip in workpiece coordinates, mm; {kl} {ml} \
                 commanded angles, degrees)\n(geometry only: no feeds, tool, spindle or \
                 coolant; add them before running it)\n(tool centre point control must be on: \
                 G43.4, G234, M428 on LinuxCNC, TRAORI or M128)\nG90 G21\n"
            );
            let mut mode = None;
            for (n, p) in points.iter().enumerate() {
                let rapid = p.motion == Motion::Rapid;
                if mode != Some(rapid) {
                    s.push_str(if rapid { "G0 " } else { "G1 " });
                    mode = Some(rapid);
                }
                let [k, m] = p.angles.ok_or_else(|| {
                    Error::field(
                        FIELD,
                        format!(
                            "point {} (line {}) has no rotary angles; NC blocks need each \
                             point's {kl} and {ml} commands",
                            n + 1,
                            p.line
                        ),
                    )
                })?;
                for (letter, v) in [
                    ('X', p.tip.x),
                    ('Y', p.tip.y),
                    ('Z', p.tip.z),
                    (kl, k),
                    (ml, m),
                ] {
                    if letter != 'X' {
                        s.push(' ');
                    }
                    s.push(letter);
                    push_num(&mut s, v, NC_DECIMALS, true);
                }
                s.push('\n');
            }
            s.push_str("M30\n%\n");
        }
    }
    Ok(s)
}
