//! The one reader of ball-bar traces: the ISO 230-4 circular test ([`super::evaluate`]), the
//! tests with a rotary axis moving ([`super::rotary`]) and the reversal study's friction fit
//! ([`crate::reversal::fit`]) all read their files here ([`read_points`]), each then checking
//! what its own evaluation needs.
//!
//! # The file
//! A header naming the columns, then one line per point:
//! * `angle (deg); deviation (µm); direction` with `ccw`/`cw` (also `+`/`-`, `g3`/`g2`) per
//!   line, or
//! * `angle (deg); ccw (µm); cw (µm)`: both directions at the same angles;
//! * optionally a `test` column naming the test each line belongs to (several tests in one
//!   file), and any other columns (ignored, listed in [`TraceFile::ignored`]).
//!
//! **Names** (case-insensitive): the angle `angle…`, `theta`, `θ`, or a rotary axis's letter `a`,
//! `b`, `c`; the deviation `deviation`, `radial deviation`, `radial`, `dr`, `Δr`, `error`,
//! `length change`; the direction `direction`, `dir`, `sense`; the test `test`.
//! **Units** with the name: `angle (deg)`, `angle [deg]`, `angle_deg`, `angle/deg`. Angles in
//! `deg` (the default) or `rad`; deviations in `mm`, `µm` (`um`), `nm` or `in` ([`crate::csv`]);
//! a deviation without a unit is refused unless the caller's [`Rules`] give its unit.
//! **Lines**: separators, the decimal comma (with `;` or a tab), `#` comments, blank lines, a
//! byte-order mark and CRLF as [`crate::csv`] reads them; comment lines `# radius: 100 mm` (mm,
//! in) and `# feed: 1000 mm/min` (mm/min, m/min, mm/s) give an ISO 230-4 test's radius and feed.
//!
//! Every problem names its line: `csv: line 7: deviation "0,0x2" is not a number`.

use crate::csv::{cells, lines, number, separator, split_unit, unit_factor};
use crate::error::quote;
use crate::{Error, Result};

/// A trace read for the ISO 230-4 evaluation: angles in radians, deviations in mm.
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

/// One point of a trace file.
#[derive(Debug, Clone, PartialEq)]
pub struct TracePoint {
    /// The file's line (1-based).
    pub line: usize,
    /// The angle, radians.
    pub angle: f64,
    /// The deviation, mm.
    pub deviation: f64,
    /// +1 CCW, −1 CW (+1 when the file has no direction).
    pub direction: f64,
    /// The `test` column's label (`None` without one).
    pub test: Option<String>,
}

/// A trace file read ([`read_points`]).
#[derive(Debug, Clone, PartialEq)]
pub struct TraceFile {
    /// The points in file order.
    pub points: Vec<TracePoint>,
    /// The tests named in the `test` column, in order of first appearance (empty without one).
    pub tests: Vec<String>,
    /// Columns the reader does not use, as the header spells them.
    pub ignored: Vec<String>,
    /// From a `# radius:` line, mm.
    pub radius: Option<f64>,
    /// From a `# feed:` line, mm/min.
    pub feed: Option<f64>,
}

/// What a caller of [`read_points`] allows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rules {
    /// The unit (factor to mm) of a deviation column whose header gives none; `None`: the unit
    /// must be given.
    pub deviation_unit: Option<f64>,
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

/// What a header cell is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Col {
    /// The angle, factor to radians.
    Angle(f64),
    /// The deviation, factor to mm (`None`: no unit given).
    Deviation(Option<f64>),
    /// The CCW or CW deviation (+1, −1), factor to mm.
    Both(f64, Option<f64>),
    Direction,
    Test,
    Ignored,
}

const DEVIATION: [&str; 8] = [
    "deviation",
    "radial deviation",
    "radial",
    "dr",
    "δr",
    "error",
    "radial error",
    "length change",
];

fn column(cell: &str, line: usize) -> Result<Col> {
    let (name, unit) = split_unit(cell);
    let length = |u: &Option<String>| u.as_deref().and_then(|u| unit_factor(u, false));
    if name.starts_with("angle") || ["theta", "θ", "a", "b", "c"].contains(&name.as_str()) {
        let f = match unit.as_deref() {
            None | Some("deg" | "°" | "degree" | "degrees") => 1f64.to_radians(),
            Some("rad") => 1.0,
            Some(_) => {
                return Err(bad(
                    line,
                    format!("the angle's unit must be deg or rad, got {}", quote(cell)),
                ))
            }
        };
        return Ok(Col::Angle(f));
    }
    if DEVIATION.contains(&name.as_str()) {
        if unit.is_some() && length(&unit).is_none() {
            return Err(give_unit(line, "deviation", cell));
        }
        return Ok(Col::Deviation(length(&unit)));
    }
    let both = match name.as_str() {
        "ccw" | "counter-clockwise" | "counterclockwise" => Some(1.0),
        "cw" | "clockwise" => Some(-1.0),
        _ => None,
    };
    if let Some(d) = both {
        if unit.is_some() && length(&unit).is_none() {
            return Err(give_unit(
                line,
                if d > 0.0 {
                    "CCW deviation"
                } else {
                    "CW deviation"
                },
                cell,
            ));
        }
        return Ok(Col::Both(d, length(&unit)));
    }
    Ok(match name.as_str() {
        "direction" | "dir" | "sense" => Col::Direction,
        "test" => Col::Test,
        _ => Col::Ignored,
    })
}

fn give_unit(line: usize, what: &str, cell: &str) -> Error {
    bad(
        line,
        format!(
            "give the unit of the {what} in the header, e.g. `(µm)` or `(mm)`; got {}",
            quote(cell)
        ),
    )
}

/// Reads a trace file (module docs) by `rules`. At least one point; what else a study needs
/// (how many points, which angles) it checks itself.
pub fn read_points(text: &str, rules: Rules) -> Result<TraceFile> {
    let radius = comment(text, "radius")?;
    let feed = comment(text, "feed")?;
    let mut it = lines(text);
    let (hl, header) = it.next().ok_or_else(|| {
        Error::field(
            "csv",
            "the file is empty: expected a header such as angle (deg); deviation (µm); direction and one line per point",
        )
    })?;
    let sep = separator(header).unwrap_or(',');
    let head = cells(header, sep);
    let cols: Vec<Col> = head.iter().map(|c| column(c, hl)).collect::<Result<_>>()?;
    let find = |f: &dyn Fn(&Col) -> bool, what: &str| -> Result<Option<usize>> {
        let hits: Vec<usize> = (0..cols.len()).filter(|&i| f(&cols[i])).collect();
        match hits.len() {
            0 => Ok(None),
            1 => Ok(Some(hits[0])),
            _ => Err(bad(
                hl,
                format!(
                    "two columns for {what} ({} and {}); keep one",
                    quote(head[hits[0]]),
                    quote(head[hits[1]])
                ),
            )),
        }
    };
    let ac = find(&|c| matches!(c, Col::Angle(_)), "the angle")?.ok_or_else(|| {
        bad(
            hl,
            format!(
                "missing column 'angle_deg' (or angle (deg)) in the header {}",
                quote(header)
            ),
        )
    })?;
    let Col::Angle(af) = cols[ac] else {
        unreachable!("the angle column is an angle")
    };
    let ccw = find(
        &|c| matches!(c, Col::Both(d, _) if *d > 0.0),
        "the CCW deviation",
    )?;
    let cw = find(
        &|c| matches!(c, Col::Both(d, _) if *d < 0.0),
        "the CW deviation",
    )?;
    let dc = find(&|c| matches!(c, Col::Deviation(_)), "the deviation")?;
    let dir = find(&|c| *c == Col::Direction, "the direction")?;
    let tc = find(&|c| *c == Col::Test, "the test")?;
    let unit_of = |i: usize, what: &str| -> Result<f64> {
        let u = match cols[i] {
            Col::Deviation(u) | Col::Both(_, u) => u,
            _ => None,
        };
        u.or(rules.deviation_unit)
            .ok_or_else(|| give_unit(hl, what, head[i]))
    };
    // The deviation columns: (column, factor, direction or None for the direction column's).
    let devs: Vec<(usize, f64, Option<f64>)> = match (ccw, cw, dc) {
        (Some(a), Some(b), None) => vec![
            (a, unit_of(a, "CCW deviation")?, Some(1.0)),
            (b, unit_of(b, "CW deviation")?, Some(-1.0)),
        ],
        (None, None, Some(d)) => vec![(d, unit_of(d, "deviation")?, None)],
        (Some(_), None, None) | (None, Some(_), None) => {
            return Err(bad(
                hl,
                "one column per direction needs both, ccw and cw; or give one deviation column and a direction column",
            ))
        }
        (None, None, None) => {
            return Err(bad(
                hl,
                format!(
                    "missing column 'deviation_mm' (or deviation_um, deviation (µm), or ccw and cw columns) in the header {}",
                    quote(header)
                ),
            ))
        }
        _ => {
            return Err(bad(
                hl,
                "both a deviation column and ccw/cw columns: keep one way of giving the directions",
            ))
        }
    };
    if dir.is_some() && devs.len() == 2 {
        return Err(bad(
            hl,
            "a direction column beside ccw and cw columns: keep one way of giving the directions",
        ));
    }
    let ignored: Vec<String> = (0..cols.len())
        .filter(|&i| cols[i] == Col::Ignored)
        .map(|i| head[i].to_string())
        .collect();
    let mut file = TraceFile {
        points: Vec::new(),
        tests: Vec::new(),
        ignored,
        radius,
        feed,
    };
    for (ln, l) in it {
        let v = cells(l, sep);
        if v.len() != cols.len() {
            return Err(bad(
                ln,
                format!(
                    "expected {} columns like the header, got {}",
                    cols.len(),
                    v.len()
                ),
            ));
        }
        let num = |i: usize, what: &str| -> Result<f64> {
            number(v[i], sep)
                .ok_or_else(|| bad(ln, format!("{what} {} is not a number", quote(v[i]))))
        };
        let angle = num(ac, "angle")? * af;
        let test = match tc {
            Some(i) if v[i].is_empty() => {
                return Err(bad(ln, "the test is empty: name the test of this line"))
            }
            Some(i) => {
                if !file.tests.iter().any(|t| t == v[i]) {
                    file.tests.push(v[i].to_string());
                }
                Some(v[i].to_string())
            }
            None => None,
        };
        for &(col, f, d) in &devs {
            let what = match d {
                Some(x) if x > 0.0 => "CCW deviation",
                Some(_) => "CW deviation",
                None => "deviation",
            };
            let deviation = num(col, what)? * f;
            let direction = match (d, dir) {
                (Some(x), _) => x,
                (None, Some(i)) => direction(v[i]).ok_or_else(|| {
                    bad(
                        ln,
                        format!(
                            "the direction must be ccw or cw (or + and −), got {}",
                            quote(v[i])
                        ),
                    )
                })?,
                (None, None) => 1.0,
            };
            file.points.push(TracePoint {
                line: ln,
                angle,
                deviation,
                direction,
                test: test.clone(),
            });
        }
    }
    if file.points.is_empty() {
        return Err(Error::field(
            "csv",
            format!("line {hl}: the header is not followed by any point"),
        ));
    }
    Ok(file)
}

/// Reads a trace for the ISO 230-4 evaluation (module docs): the deviation's unit must be
/// given, one test, at least 20 points.
pub fn read_trace(text: &str) -> Result<Trace> {
    let f = read_points(
        text,
        Rules {
            deviation_unit: None,
        },
    )?;
    if f.tests.len() > 1 {
        return Err(Error::field(
            "csv",
            format!(
                "the file holds {} tests ({}); a circular test reads one: give its lines alone",
                f.tests.len(),
                f.tests.join(", ")
            ),
        ));
    }
    if f.points.len() < 20 {
        return Err(Error::field(
            "csv",
            format!(
                "needs at least 20 points round the circle, got {}",
                f.points.len()
            ),
        ));
    }
    Ok(Trace {
        angle: f.points.iter().map(|p| p.angle).collect(),
        deviation: f.points.iter().map(|p| p.deviation).collect(),
        direction: f.points.iter().map(|p| p.direction).collect(),
        radius: f.radius,
        feed: f.feed,
    })
}
