//! Reading a ball-bar trace from CSV:
//! * `angle (deg); deviation (µm); direction` with `ccw`/`cw` (also `+`/`-`) per line, or
//! * `angle (deg); ccw (µm); cw (µm)`: both directions at the same angles.
//!
//! Comment lines `# radius: 100 mm` (mm, in) and `# feed: 1000 mm/min` (mm/min, m/min, mm/s)
//! give the test's radius and feed. Units of the deviations in the header (mm, µm, nm, in).
//! Separators and the decimal comma as [`crate::csv`]. Errors name the line.

use crate::csv::{cells, header_unit, lines, number, separator, unit_factor};
use crate::error::quote;
use crate::{Error, Result};

/// A trace read: angles in radians, deviations in mm.
#[derive(Debug, Clone, PartialEq)]
pub struct Trace {
    /// θ per point, radians.
    pub angle: Vec<f64>,
    /// Δr per point, mm.
    pub deviation: Vec<f64>,
    /// +1 CCW, −1 CW.
    pub direction: Vec<f64>,
    /// From a `# radius:` line, mm.
    pub radius: Option<f64>,
    /// From a `# feed:` line, mm/min.
    pub feed: Option<f64>,
}

fn bad(line: usize, message: impl std::fmt::Display) -> Error {
    Error::field("csv", format!("line {line}: {message}"))
}

/// `# key: 100 unit` → the value in mm (radius) or mm/min (feed).
fn comment(text: &str, key: &str) -> Result<Option<f64>> {
    for (i, l) in text.lines().enumerate() {
        let l = l.trim().trim_start_matches('\u{feff}');
        let Some(rest) = l.strip_prefix('#') else {
            continue;
        };
        let Some((k, v)) = rest.split_once(':') else {
            continue;
        };
        if k.trim().to_lowercase() != key {
            continue;
        }
        let v = v.trim();
        let num: String = v
            .chars()
            .take_while(|c| c.is_ascii_digit() || ".,+-".contains(*c))
            .collect();
        let unit = v[num.len()..].trim().to_lowercase();
        let x = number(&num, ';')
            .ok_or_else(|| bad(i + 1, format!("the {key} is not a number: {}", quote(v))))?;
        let f = match (key, unit.as_str()) {
            ("radius", "mm" | "") => 1.0,
            ("radius", "in" | "inch") => 25.4,
            ("feed", "mm/min" | "") => 1.0,
            ("feed", "m/min") => 1000.0,
            ("feed", "mm/s") => 60.0,
            _ => {
                return Err(bad(
                    i + 1,
                    format!("unknown unit of the {key}: {}", quote(&unit)),
                ))
            }
        };
        return Ok(Some(x * f));
    }
    Ok(None)
}

fn direction(cell: &str) -> Option<f64> {
    match cell.trim().to_lowercase().as_str() {
        "ccw" | "+" | "counter-clockwise" | "counterclockwise" | "g3" => Some(1.0),
        "cw" | "-" | "−" | "clockwise" | "g2" => Some(-1.0),
        _ => None,
    }
}

fn unit(cell: &str, line: usize, what: &str) -> Result<f64> {
    let u = header_unit(cell);
    unit_factor(u, false).ok_or_else(|| {
        bad(
            line,
            format!(
                "give the unit of the {what} in the header, e.g. `(µm)` or `(mm)`; got {}",
                quote(cell)
            ),
        )
    })
}

/// Reads a trace (module docs).
pub fn read_trace(text: &str) -> Result<Trace> {
    let radius = comment(text, "radius")?;
    let feed = comment(text, "feed")?;
    let mut it = lines(text);
    let (hl, header) = it.next().ok_or_else(|| Error::field("csv", "is empty"))?;
    let sep = separator(header).unwrap_or(',');
    let head = cells(header, sep);
    let low: Vec<String> = head.iter().map(|c| c.to_lowercase()).collect();
    let find = |w: &[&str]| low.iter().position(|c| w.iter().any(|x| c.starts_with(x)));
    let ac = find(&["angle", "theta", "θ"]).ok_or_else(|| {
        bad(
            hl,
            format!("the header names no angle column: {}", quote(header)),
        )
    })?;
    let au = header_unit(head[ac]).to_lowercase();
    let af = match au.as_str() {
        "deg" | "°" | "degree" | "degrees" | "angle" | "theta" | "θ" => 1f64.to_radians(),
        "rad" => 1.0,
        _ => {
            return Err(bad(
                hl,
                format!(
                    "the angle's unit must be deg or rad, got {}",
                    quote(head[ac])
                ),
            ))
        }
    };
    let mut t = Trace {
        angle: vec![],
        deviation: vec![],
        direction: vec![],
        radius,
        feed,
    };
    let (ccw, cw) = (
        find(&["ccw", "counter"]),
        low.iter()
            .position(|c| c.starts_with("cw") || c.starts_with("clockwise")),
    );
    if let (Some(cc), Some(c)) = (ccw, cw) {
        let (fc, fw) = (
            unit(head[cc], hl, "CCW deviation")?,
            unit(head[c], hl, "CW deviation")?,
        );
        for (ln, l) in it {
            let v = cells(l, sep);
            let get = |i: usize, what: &str| {
                v.get(i)
                    .and_then(|x| number(x, sep))
                    .ok_or_else(|| bad(ln, format!("{what} is not a number: {}", quote(l))))
            };
            let a = get(ac, "the angle")? * af;
            for (col, f, d) in [(cc, fc, 1.0), (c, fw, -1.0)] {
                t.angle.push(a);
                t.deviation.push(
                    get(
                        col,
                        if d > 0.0 {
                            "the CCW deviation"
                        } else {
                            "the CW deviation"
                        },
                    )? * f,
                );
                t.direction.push(d);
            }
        }
    } else {
        let dc = find(&["dev", "radial", "dr", "error", "Δr"]).ok_or_else(|| {
            bad(
                hl,
                format!("the header names no deviation column: {}", quote(header)),
            )
        })?;
        let fd = unit(head[dc], hl, "deviation")?;
        let dir = find(&["dir", "sense"]);
        for (ln, l) in it {
            let v = cells(l, sep);
            let get = |i: usize, what: &str| {
                v.get(i)
                    .and_then(|x| number(x, sep))
                    .ok_or_else(|| bad(ln, format!("{what} is not a number: {}", quote(l))))
            };
            t.angle.push(get(ac, "the angle")? * af);
            t.deviation.push(get(dc, "the deviation")? * fd);
            t.direction.push(match dir {
                Some(i) => v.get(i).and_then(|x| direction(x)).ok_or_else(|| {
                    bad(ln, format!("the direction must be ccw or cw: {}", quote(l)))
                })?,
                None => 1.0,
            });
        }
    }
    if t.angle.len() < 20 {
        return Err(Error::field(
            "csv",
            format!(
                "needs at least 20 points round the circle, got {}",
                t.angle.len()
            ),
        ));
    }
    Ok(t)
}
