//! Reading a positioning test from CSV, in the three layouts measuring software writes:
//!
//! * **one line per measurement**: a target column, a direction column and a deviation (or
//!   actual position) column, a run column optional:
//!   `target (mm); direction; run; deviation (µm)` then `100; up; 1; 2,5`;
//! * **one line per target**, the runs in columns named for their direction and number:
//!   `target (mm), up 1 (µm), up 2 (µm), …, down 1 (µm), …`;
//! * **one line per run**, the targets in columns: `direction, run (µm), 0 mm, 100 mm, …` (the
//!   values' unit on the run or direction cell, each target with its unit).
//!
//! Directions: `up`, `↑`, `+`, `fwd`, `forward`, `pos`, `positive` and `down`, `↓`, `-`, `−`,
//! `bwd`, `backward`, `rev`, `neg`, `negative`. A column named `actual`, `measured`, `reading`,
//! `reached` or `reference` holds positions reached (the deviation is that less the target);
//! otherwise values are deviations. Units in the header, in `( )` or `[ ]`: mm, µm, nm, m, in for
//! a linear axis; deg, arcsec, rad, mrad, µrad for a rotary one. Separators and the decimal
//! comma as [`crate::csv`]; lines separated only by spaces are split at the spaces. Errors name
//! the line: `csv: line 7: …`.

use crate::csv::{cells, header_unit, lines, number, separator, unit_factor};
use crate::error::quote;
use crate::{Error, Result};

/// The runs read: deviations in mm (a linear axis) or degrees (a rotary axis).
#[derive(Debug, Clone, PartialEq)]
pub struct Runs {
    /// Targets, increasing.
    pub targets: Vec<f64>,
    /// `up[j][i]`: run `j`'s deviation at target `i`, approached in the positive direction.
    pub up: Vec<Vec<f64>>,
    /// `down[j][i]`, approached in the negative direction.
    pub down: Vec<Vec<f64>>,
    /// The targets are angles (a rotary axis).
    pub angular: bool,
    /// The units the header gave: targets, values.
    pub units: [String; 2],
}

fn bad(line: usize, message: impl std::fmt::Display) -> Error {
    Error::field("csv", format!("line {line}: {message}"))
}

/// `Some(true)` up, `Some(false)` down.
fn direction(cell: &str) -> Option<bool> {
    let c = cell.trim().to_lowercase();
    match c.as_str() {
        "up" | "↑" | "+" | "fwd" | "forward" | "pos" | "positive" => Some(true),
        "down" | "↓" | "-" | "−" | "bwd" | "backward" | "rev" | "neg" | "negative" => {
            Some(false)
        }
        _ => None,
    }
}

/// The name of a header cell without its unit, lower case.
fn name(cell: &str) -> String {
    let mut n = cell.to_lowercase();
    for open in ['(', '['] {
        if let Some(a) = n.find(open) {
            n.truncate(a);
        }
    }
    n.trim().to_string()
}

fn is_target(n: &str) -> bool {
    ["target", "position", "nominal", "soll", "pos"]
        .iter()
        .any(|w| n.starts_with(w))
}
fn is_direction(n: &str) -> bool {
    ["dir", "sense", "approach"]
        .iter()
        .any(|w| n.starts_with(w))
}
fn is_run(n: &str) -> bool {
    ["run", "cycle", "repeat"].iter().any(|w| n.starts_with(w))
}
fn is_actual(n: &str) -> bool {
    [
        "actual",
        "measured",
        "reading",
        "reached",
        "reference",
        "ist",
    ]
    .iter()
    .any(|w| n.contains(w))
}
fn is_value(n: &str) -> bool {
    is_actual(n)
        || ["deviation", "error", "dev", "abweichung"]
            .iter()
            .any(|w| n.contains(w))
}

/// `up 3`, `↑3`, `fwd_3`, `down 1` …: the direction and run of a column.
fn run_column(n: &str) -> Option<(bool, usize)> {
    let digits: String = n.chars().rev().take_while(|c| c.is_ascii_digit()).collect();
    let digits: String = digits.chars().rev().collect();
    let run: usize = digits.parse().ok()?;
    let stem = n[..n.len() - digits.len()].trim_end_matches([' ', '_', '-', '#']);
    let words = [
        ("up", true),
        ("↑", true),
        ("fwd", true),
        ("forward", true),
        ("pos", true),
        ("down", false),
        ("↓", false),
        ("bwd", false),
        ("backward", false),
        ("neg", false),
        ("rev", false),
    ];
    words
        .iter()
        .find(|(w, _)| stem.ends_with(w) || stem.starts_with(w))
        .map(|(_, up)| (*up, run))
}

/// The factor of a unit to mm (`angle` false) or degrees, and whether it is an angle.
fn factor(unit: &str, line: usize, what: &str) -> Result<(f64, bool)> {
    if let Some(f) = unit_factor(unit, false) {
        return Ok((f, false));
    }
    if let Some(f) = unit_factor(unit, true) {
        return Ok((f, true));
    }
    Err(bad(
        line,
        format!("give the unit of the {what} in the header, e.g. `(mm)`, `(µm)`, `(deg)` or `(arcsec)`; got {}", quote(unit)),
    ))
}

/// One measurement: target, up?, run order, deviation.
struct Point {
    target: f64,
    up: bool,
    run: f64,
    value: f64,
    line: usize,
}

/// Reads the runs (module docs).
pub fn read_runs(text: &str) -> Result<Runs> {
    let mut it = lines(text);
    let (hline, header) = it.next().ok_or_else(|| Error::field("csv", "is empty"))?;
    // A header with no tab, `;` or `,` is split at spaces, and so is every line after it (a
    // decimal comma then stays in its number).
    let spaced = separator(header).is_none();
    let split = |l: &str| -> (Vec<String>, char) {
        match separator(l).filter(|_| !spaced) {
            Some(s) => (cells(l, s).into_iter().map(str::to_string).collect(), s),
            None => (l.split_whitespace().map(str::to_string).collect(), ' '),
        }
    };
    let (head, _) = split(header);
    let names: Vec<String> = head.iter().map(|c| name(c)).collect();
    let col = |f: fn(&str) -> bool| names.iter().position(|n| f(n));
    let mut points = Vec::new();
    let (tunit, vunit);
    let (tf, angular, vf);

    if let (Some(tc), Some(dc), Some(vc)) = (col(is_target), col(is_direction), col(is_value)) {
        // One line per measurement.
        tunit = header_unit(&head[tc]).to_string();
        vunit = header_unit(&head[vc]).to_string();
        (tf, angular) = factor(&tunit, hline, "targets")?;
        let (f, va) = factor(&vunit, hline, "values")?;
        if va != angular {
            return Err(bad(
                hline,
                "the targets and the values must both be lengths or both angles",
            ));
        }
        vf = f;
        let actual = is_actual(&names[vc]);
        let rc = col(is_run);
        for (ln, l) in it {
            let (c, sep) = split(l);
            let need = tc.max(dc).max(vc).max(rc.unwrap_or(0));
            if c.len() <= need {
                return Err(bad(
                    ln,
                    format!("expected {} cells, got {}: {}", need + 1, c.len(), quote(l)),
                ));
            }
            let num = |i: usize, what: &str| {
                number(&c[i], sep)
                    .ok_or_else(|| bad(ln, format!("{what} is not a number: {}", quote(&c[i]))))
            };
            let target = num(tc, "the target")? * tf;
            let up = direction(&c[dc]).ok_or_else(|| {
                bad(
                    ln,
                    format!(
                        "the direction must be up (+, ↑, fwd) or down (−, ↓, bwd), got {}",
                        quote(&c[dc])
                    ),
                )
            })?;
            let v = num(vc, "the value")? * vf;
            let run = match rc {
                Some(r) => num(r, "the run")?,
                None => points.len() as f64,
            };
            points.push(Point {
                target,
                up,
                run,
                value: if actual { v - target } else { v },
                line: ln,
            });
        }
    } else if let Some(tc) = col(is_target) {
        // One line per target, runs in columns.
        let runs: Vec<(usize, bool, usize)> = names
            .iter()
            .enumerate()
            .filter_map(|(i, n)| run_column(n).map(|(up, r)| (i, up, r)))
            .collect();
        if !runs.iter().any(|r| r.1) || !runs.iter().any(|r| !r.1) {
            return Err(bad(hline, "name the run columns by direction and number: `up 1 (µm)` … `down 5 (µm)`, or give a direction column"));
        }
        tunit = header_unit(&head[tc]).to_string();
        (tf, angular) = factor(&tunit, hline, "targets")?;
        let first = runs[0].0;
        vunit = header_unit(&head[first]).to_string();
        let (f, va) = factor(&vunit, hline, "values")?;
        if va != angular {
            return Err(bad(
                hline,
                "the targets and the values must both be lengths or both angles",
            ));
        }
        vf = f;
        let actual = runs.iter().any(|r| is_actual(&names[r.0]));
        for (ln, l) in it {
            let (c, sep) = split(l);
            if c.len() != head.len() {
                return Err(bad(
                    ln,
                    format!(
                        "expected {} cells as in the header, got {}: {}",
                        head.len(),
                        c.len(),
                        quote(l)
                    ),
                ));
            }
            let target = number(&c[tc], sep)
                .ok_or_else(|| bad(ln, format!("the target is not a number: {}", quote(&c[tc]))))?
                * tf;
            for &(i, up, run) in &runs {
                let v = number(&c[i], sep).ok_or_else(|| {
                    bad(ln, format!("{} is not a number: {}", head[i], quote(&c[i])))
                })? * vf;
                points.push(Point {
                    target,
                    up,
                    run: run as f64,
                    value: if actual { v - target } else { v },
                    line: ln,
                });
            }
        }
    } else if let Some(dc) = col(is_direction) {
        // One line per run, targets in columns.
        let rc = col(is_run);
        let unit_cell = rc.filter(|&r| head[r].contains(['(', '['])).unwrap_or(dc);
        vunit = header_unit(&head[unit_cell]).to_string();
        let mut targets = Vec::new();
        let mut tu = String::new();
        for (i, cell) in head.iter().enumerate() {
            if i == dc || Some(i) == rc {
                continue;
            }
            let t = cell.trim();
            let numeric: String = t
                .chars()
                .take_while(|c| c.is_ascii_digit() || "+-−.,".contains(*c))
                .collect();
            let value = number(&numeric.replace('−', "-"), ';').ok_or_else(|| {
                bad(
                    hline,
                    format!(
                        "a target column must be a number with its unit (`100 mm`), got {}",
                        quote(t)
                    ),
                )
            })?;
            let rest = header_unit(t[numeric.len()..].trim());
            if rest.is_empty() {
                return Err(bad(
                    hline,
                    format!("give the target's unit: `{t} mm` or `{t} deg`"),
                ));
            }
            tu = rest.to_string();
            targets.push((i, value));
        }
        if targets.is_empty() {
            return Err(bad(
                hline,
                "no target column: name them by the target and its unit (`0 mm; 100 mm; …`)",
            ));
        }
        tunit = tu;
        (tf, angular) = factor(&tunit, hline, "targets")?;
        let (f, va) = factor(&vunit, hline, "values")?;
        if va != angular {
            return Err(bad(
                hline,
                "the targets and the values must both be lengths or both angles",
            ));
        }
        vf = f;
        let actual = is_actual(&names[unit_cell]);
        for (ln, l) in it {
            let (c, sep) = split(l);
            if c.len() != head.len() {
                return Err(bad(
                    ln,
                    format!(
                        "expected {} cells as in the header, got {}: {}",
                        head.len(),
                        c.len(),
                        quote(l)
                    ),
                ));
            }
            let up = direction(&c[dc]).ok_or_else(|| {
                bad(
                    ln,
                    format!(
                        "the direction must be up (+, ↑, fwd) or down (−, ↓, bwd), got {}",
                        quote(&c[dc])
                    ),
                )
            })?;
            let run = match rc {
                Some(r) => number(&c[r], sep)
                    .ok_or_else(|| bad(ln, format!("the run is not a number: {}", quote(&c[r]))))?,
                None => ln as f64,
            };
            for &(i, t) in &targets {
                let v = number(&c[i], sep).ok_or_else(|| {
                    bad(
                        ln,
                        format!("the value at {} is not a number: {}", head[i], quote(&c[i])),
                    )
                })? * vf;
                let target = t * tf;
                points.push(Point {
                    target,
                    up,
                    run,
                    value: if actual { v - target } else { v },
                    line: ln,
                });
            }
        }
    } else {
        return Err(bad(
            hline,
            format!(
                "the header names no target column (`target (mm)`) and no direction column: {}",
                quote(header)
            ),
        ));
    }
    gather(points, angular, [tunit, vunit])
}

/// The points as runs per target: each target's up and down values in run order, the same
/// number everywhere.
fn gather(mut points: Vec<Point>, angular: bool, units: [String; 2]) -> Result<Runs> {
    if points.is_empty() {
        return Err(Error::field("csv", "has a header but no measurements"));
    }
    points.sort_by(|a, b| a.target.total_cmp(&b.target).then(a.run.total_cmp(&b.run)));
    let mut targets: Vec<f64> = Vec::new();
    let mut cols: Vec<(Vec<f64>, Vec<f64>, usize)> = Vec::new();
    for p in &points {
        if targets.last() != Some(&p.target) {
            targets.push(p.target);
            cols.push((Vec::new(), Vec::new(), p.line));
        }
        let Some(c) = cols.last_mut() else {
            continue;
        };
        if p.up {
            c.0.push(p.value)
        } else {
            c.1.push(p.value)
        }
    }
    if targets.len() < 2 {
        return Err(Error::field("csv", "needs at least 2 targets"));
    }
    let n = cols[0].0.len();
    for (t, (up, down, line)) in targets.iter().zip(&cols) {
        if up.len() < 2 || down.len() < 2 {
            return Err(bad(*line, format!("target {t}: needs at least 2 runs each way (ISO 230-2 asks for 5), got {} up and {} down", up.len(), down.len())));
        }
        if up.len() != n || down.len() != n {
            return Err(bad(*line, format!("target {t}: {} runs up and {} down, but the first target has {n} each way; every target needs the same number", up.len(), down.len())));
        }
    }
    let run = |j: usize, up: bool| {
        cols.iter()
            .map(|c| if up { c.0[j] } else { c.1[j] })
            .collect()
    };
    Ok(Runs {
        up: (0..n).map(|j| run(j, true)).collect(),
        down: (0..n).map(|j| run(j, false)).collect(),
        targets,
        angular,
        units,
    })
}
