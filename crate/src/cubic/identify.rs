//! Identification of the machine's errors from a machined cubic test piece: measured zone
//! heights, and the zones' tilts where a profilometer gives them, fitted by the project's one
//! identification module ([`crate::identify`]) on the sensitivities of [`super::analyze`] (the
//! chain's first-order derivatives at each zone's pose). Li et al.'s Section 6 asks for exactly
//! this: "a machining test condition that can identify each geometric error individually".
//!
//! # The measurement file (CSV, units in the header)
//! ```text
//! # comment lines start with '#'
//! zone,height_um,slope_x_um_per_mm,slope_y_um_per_mm
//! I,0.4,,
//! II-1,-5.1,0.02,-0.01
//! ```
//! * `zone`: Table 1's names (`I`, `II-1` … `III-4`, also `ZONE II-1`) for the paper's layout; for
//!   any other layout (the test designer's export, [`super::design`]) each row also gives the
//!   zone: `x_mm`, `y_mm` (its centre on the face), `tilt_deg`, `azimuth_deg` (its tool vector in
//!   the face frame: `(sin τ·cos φ, sin τ·sin φ, cos τ)`, leaning towards `φ`), and optionally
//!   `piece_x_mm` (the face centre's distance from the table centre along the face's first axis
//!   in that zone's set-up; default the input's `workpieceX`). Columns `setup`, `i`, `j`, `k`,
//!   `k_deg`, `m_deg` of the export are read as information only.
//! * `height_mm` or `height_um`: the zone's height at its centre, positive = material left, in
//!   the frame of the input's `reference` and `transform` (module docs of [`super`]).
//! * `slope_x`, `slope_y` (mm/mm; or `…_um_per_mm`): the zone's tilt along the face's axes;
//!   optional, a cell may be empty.
//!
//! Every problem names its line: `csv: line 7: height "0,01x" is not a number`. Zones of one
//! set-up are measured relative to the first zone listed for it when `reference` is ZONE I's.

use super::zones::{Test, ZoneSpec};
use super::{relative, CubicPiece, Options, ZonePlane, ZONES};
use crate::cache::{self, Models};
use crate::error::{check_range, quote, Error, Result};
use crate::identify::csv::{line_error, Table};
use crate::identify::{DecisionInput, Judgement, Param, DEFAULT_RTOL};
use crate::machine::errors::ErrorDef;
use crate::machine::Machine;
use crate::schema::{DefaultValue, Kind, Quantity};
use nalgebra::DMatrix;
use std::cell::RefCell;
use std::rc::Rc;

/// One zone of a layout on the machine, with its sensitivities.
#[derive(Debug, Clone, PartialEq)]
pub struct LayoutZone {
    /// The zone.
    pub spec: ZoneSpec,
    /// The face centre's distance from the table centre along `u` in its set-up, mm.
    pub piece_x: f64,
    /// Tool vector in workpiece coordinates.
    pub tool: [f64; 3],
    /// K and M commands, rad.
    pub rotary: [f64; 2],
    /// The tool along K (K arbitrary).
    pub singular: bool,
    /// Sensitivities of its plane to each error (per mm, per rad).
    pub sensitivity: Vec<ZonePlane>,
}

/// The zones of `specs` on `machine` (per zone the piece's `workpieceX` in its set-up),
/// with the sensitivities of their planes to `errors`, measured from `options.reference`
/// within each set-up. A zone outside the travel is an error naming it.
pub fn layout(
    machine: &Machine,
    piece: &CubicPiece,
    options: &Options,
    specs: &[(ZoneSpec, f64)],
    errors: &[&'static ErrorDef],
) -> Result<Vec<LayoutZone>> {
    let mut setups: Vec<f64> = Vec::new();
    for (_, x) in specs {
        if !setups.iter().any(|s| s == x) {
            setups.push(*x);
        }
    }
    let mut out: Vec<Option<LayoutZone>> = vec![None; specs.len()];
    for x in setups {
        let idx: Vec<usize> = (0..specs.len()).filter(|&i| specs[i].1 == x).collect();
        let zs: Vec<ZoneSpec> = idx.iter().map(|&i| specs[i].0.clone()).collect();
        let placed = CubicPiece {
            workpiece_x: x,
            ..piece.clone()
        };
        let test = Test::with_zones(machine, &placed, options, &zs)?;
        let centres: Vec<(f64, f64)> = test.zones.iter().map(|z| z.centre).collect();
        let raw: Vec<Vec<ZonePlane>> = test
            .zones
            .iter()
            .map(|z| test.sensitivities(z, errors))
            .collect::<Result<_>>()?;
        let mut rel = vec![vec![ZonePlane::default(); errors.len()]; raw.len()];
        for e in 0..errors.len() {
            let column: Vec<ZonePlane> = raw.iter().map(|k| k[e]).collect();
            for (z, p) in relative(&column, &centres, options.reference)
                .into_iter()
                .enumerate()
            {
                rel[z][e] = p;
            }
        }
        for ((k, z), s) in idx.iter().zip(&test.zones).zip(rel) {
            out[*k] = Some(LayoutZone {
                spec: specs[*k].0.clone(),
                piece_x: x,
                tool: z.dir.into(),
                rotary: z.rotary,
                singular: z.singular,
                sensitivity: s,
            });
        }
    }
    Ok(out.into_iter().flatten().collect())
}

/// [`layout`], built once per machine, piece, options, zones and errors and kept in a small
/// per-thread cache ([`crate::cache`]): the page identifies again and again on one layout.
pub fn cached_layout(
    machine: &Machine,
    piece: &CubicPiece,
    options: &Options,
    specs: &[(ZoneSpec, f64)],
    errors: &[&'static ErrorDef],
) -> Result<Rc<Vec<LayoutZone>>> {
    /// What a layout depends on: the machine, the piece, the options, the zones, the errors.
    type Key = (
        Machine,
        CubicPiece,
        Options,
        Vec<(ZoneSpec, f64)>,
        Vec<&'static str>,
    );
    thread_local! {
        static LAYOUTS: Models<Key, Vec<LayoutZone>> = const { RefCell::new(Vec::new()) };
    }
    let names = errors.iter().map(|d| d.name).collect();
    let key = (
        machine.clone(),
        piece.clone(),
        *options,
        specs.to_vec(),
        names,
    );
    cache::get_or_build(&LAYOUTS, key, || {
        layout(machine, piece, options, specs, errors)
    })
}

/// The tool vector in the face frame for a tilt `τ` and azimuth `φ` (rad).
pub fn tool_of(tilt: f64, azimuth: f64) -> [f64; 3] {
    [
        tilt.sin() * azimuth.cos(),
        tilt.sin() * azimuth.sin(),
        tilt.cos(),
    ]
}

/// One measured zone.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredZone {
    /// The zone and its set-up's `workpieceX`, mm.
    pub zone: (ZoneSpec, f64),
    /// File line.
    pub line: usize,
    /// Height, mm.
    pub height: f64,
    /// Slopes along u and v (mm/mm), when measured.
    pub slope_x: Option<f64>,
    /// Along v.
    pub slope_y: Option<f64>,
}

/// Reads the measurement file (module docs) for a piece.
pub fn parse_measurements(text: &str, piece: &CubicPiece) -> Result<Vec<MeasuredZone>> {
    let table = Table::read(text, "zone,height_mm,slope_x,slope_y")?;
    let h = table.header_line;
    let known = [
        "zone",
        "setup",
        "i",
        "j",
        "k",
        "k_deg",
        "m_deg",
        "x_mm",
        "y_mm",
        "tilt_deg",
        "azimuth_deg",
        "piece_x_mm",
    ];
    for n in &table.names {
        let unit_col = ["height", "slope_x", "slope_y"].iter().any(|b| {
            n == b
                || [
                    "_mm",
                    "_um",
                    "_µm",
                    "_mm_per_mm",
                    "_um_per_mm",
                    "_µm_per_mm",
                ]
                .iter()
                .any(|u| *n == format!("{b}{u}"))
        });
        if !known.contains(&n.as_str()) && !unit_col {
            return Err(line_error(
                h,
                format!(
                    "unknown column {}; expected zone, height_mm (or height_um), optional \
                     slope_x, slope_y, and for a designed layout x_mm, y_mm, tilt_deg, azimuth_deg",
                    quote(n)
                ),
            ));
        }
    }
    let zone_col = table
        .column(&["zone"])
        .ok_or_else(|| line_error(h, "missing column 'zone' in the header"))?;
    let (height_col, height_scale) = table.length_column("height")?.ok_or_else(|| {
        line_error(
            h,
            "missing column 'height_mm' (or 'height_um') in the header",
        )
    })?;
    let slope = |base: &str| -> Result<Option<(usize, f64)>> {
        let one = [base.to_string(), format!("{base}_mm_per_mm")];
        let milli = [format!("{base}_um_per_mm"), format!("{base}_µm_per_mm")];
        let a = table.names.iter().position(|n| one.contains(n));
        let b = table.names.iter().position(|n| milli.contains(n));
        match (a, b) {
            (Some(_), Some(_)) => Err(line_error(h, format!("two {base} columns; keep one"))),
            (Some(c), None) => Ok(Some((c, 1.0))),
            (None, Some(c)) => Ok(Some((c, 1e-3))),
            (None, None) => Ok(None),
        }
    };
    let (sx, sy) = (slope("slope_x")?, slope("slope_y")?);
    let geometry = ["x_mm", "y_mm", "tilt_deg", "azimuth_deg"].map(|n| table.column(&[n]));
    let given = geometry.iter().filter(|c| c.is_some()).count();
    if given != 0 && given != 4 {
        return Err(line_error(
            h,
            "a designed layout needs all four columns x_mm, y_mm, tilt_deg, azimuth_deg",
        ));
    }
    let piece_col = table.column(&["piece_x_mm"]);
    let mut out: Vec<MeasuredZone> = Vec::new();
    for (line, cells) in &table.rows()? {
        let line = *line;
        let name = cells[zone_col].trim();
        let piece_x = match piece_col {
            Some(c) if !cells[c].is_empty() => {
                let v = table.number(line, cells[c], "piece_x_mm")?;
                check_range("piece_x_mm", v, -2000.0, 2000.0, "mm")
                    .map_err(|e| line_error(line, e.message))?
            }
            _ => piece.workpiece_x,
        };
        let spec = if given == 4 {
            let num = |k: usize, what: &str| {
                geometry[k].map_or(Ok(0.0), |c| table.number(line, cells[c], what))
            };
            let (x, y) = (num(0, "x_mm")?, num(1, "y_mm")?);
            let (tilt, az) = (num(2, "tilt_deg")?, num(3, "azimuth_deg")?);
            if !(0.0..=89.0).contains(&tilt) {
                return Err(line_error(
                    line,
                    format!("tilt_deg {tilt} is outside 0..89"),
                ));
            }
            ZoneSpec {
                name: name.to_string(),
                centre: (x, y),
                tool: tool_of(tilt.to_radians(), az.to_radians()),
            }
        } else {
            let bare = name
                .strip_prefix("ZONE ")
                .or_else(|| name.strip_prefix("zone "))
                .unwrap_or(name)
                .trim();
            let def = ZONES
                .iter()
                .find(|d| d.name.eq_ignore_ascii_case(bare))
                .ok_or_else(|| {
                    line_error(
                        line,
                        format!(
                            "zone {} is not one of Table 1's (I, II-1 … III-4); for \
                             another layout give x_mm, y_mm, tilt_deg, azimuth_deg",
                            quote(name)
                        ),
                    )
                })?;
            ZoneSpec::paper(def, piece.zone_size)
        };
        if let Some(first) = out
            .iter()
            .find(|m| m.zone.0.name == spec.name && m.zone.1 == piece_x)
        {
            return Err(line_error(
                line,
                format!(
                    "zone {} is given twice (first on line {})",
                    spec.name, first.line
                ),
            ));
        }
        if cells[height_col].is_empty() {
            return Err(line_error(
                line,
                format!("zone {}: no height: fill in the measured height", spec.name),
            ));
        }
        let height = table.number(line, cells[height_col], "height")? * height_scale;
        check_range("height", height, -10.0, 10.0, "mm")
            .map_err(|e| line_error(line, format!("height {}", e.message)))?;
        let read_slope = |c: Option<(usize, f64)>, what: &str| -> Result<Option<f64>> {
            match c {
                Some((c, s)) if !cells[c].is_empty() => {
                    let v = table.number(line, cells[c], what)? * s;
                    check_range(what, v, -1.0, 1.0, "mm/mm")
                        .map_err(|e| line_error(line, format!("{what} {}", e.message)))?;
                    Ok(Some(v))
                }
                _ => Ok(None),
            }
        };
        out.push(MeasuredZone {
            zone: (spec, piece_x),
            line,
            height,
            slope_x: read_slope(sx, "slope_x")?,
            slope_y: read_slope(sy, "slope_y")?,
        });
    }
    if out.is_empty() {
        return Err(Error::field("csv", "the file has a header but no zone"));
    }
    Ok(out)
}

/// The least-squares system of measured zones: rows (height, then each measured slope, per
/// zone in file order), the measured values and the zones on the machine. A slope row is
/// multiplied by half the zone size: the height (mm) the tilt makes at the zone's edge, so that
/// heights and slopes share one noise level (a profilometer's tilt over half a zone is about as
/// good as its height).
pub fn system(
    machine: &Machine,
    piece: &CubicPiece,
    options: &Options,
    measured: &[MeasuredZone],
    errors: &[&'static ErrorDef],
) -> Result<(DMatrix<f64>, Vec<f64>, Vec<LayoutZone>)> {
    let specs: Vec<(ZoneSpec, f64)> = measured.iter().map(|m| m.zone.clone()).collect();
    let zones = cached_layout(machine, piece, options, &specs, errors).map_err(|e| {
        Error::field(
            "csv",
            format!(
                "a zone of the file cannot be cut on this machine: {}",
                e.message
            ),
        )
    })?;
    // A slope enters as the height it makes over half a zone (mm), so that one noise level
    // stands for heights and slopes alike.
    let zones: &[LayoutZone] = &zones;
    let lever = piece.zone_size / 2.0;
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut d = Vec::new();
    for (m, z) in measured.iter().zip(zones) {
        rows.push(z.sensitivity.iter().map(|p| p.height).collect());
        d.push(m.height);
        if let Some(s) = m.slope_x {
            rows.push(z.sensitivity.iter().map(|p| p.slope_x * lever).collect());
            d.push(s * lever);
        }
        if let Some(s) = m.slope_y {
            rows.push(z.sensitivity.iter().map(|p| p.slope_y * lever).collect());
            d.push(s * lever);
        }
    }
    let a = DMatrix::from_fn(rows.len(), errors.len(), |r, c| rows[r][c]);
    Ok((a, d, zones.to_vec()))
}

crate::inputs! {
    /// The cubic identification's own inputs (with a [`super::CubicInput`]).
    pub struct CubicIdentifyInput {
        /// The measurement file.
        pub csv: String = "csv" {
            label: "Measured zones (CSV)",
            help: "Header zone,height_um (or height_mm), optional slope_x, slope_y (mm/mm, or slope_x_um_per_mm); one row per zone: I, II-1 … III-4, or a designed layout's rows as exported.",
            kind: Kind::Text { max_len: 1_000_000 },
            group: "Identification",
        },
        /// The errors to identify; all the machine's when left out.
        pub parameters: Option<Vec<String>> = "parameters" optional {
            label: "Errors to identify",
            help: "The machine's errors the fit may use; left out: all of them. Those the test cannot see or separate are named.",
            kind: crate::machine::errors::NAMES,
            group: "Identification",
        },
        /// Relative singular-value threshold of the rank decision.
        pub rtol: f64 = "rtol" optional {
            label: "Rank threshold (relative singular value)",
            help: "Directions below it count as not identifiable (0.01: condition number 100).",
            kind: Kind::Number { quantity: Quantity::Number, min: 1e-12, max: 0.5, exclusive_min: false },
            default: DefaultValue::Num(DEFAULT_RTOL),
            group: "Identification",
        },
        /// How the values are judged.
        pub decision: DecisionInput = "decision" optional {
            label: "Decision",
            kind: Kind::Object(DecisionInput::FIELDS),
            default: DefaultValue::Empty,
        },
    }
}

/// A cubic identification: the zones on the machine and the judgement.
#[derive(Debug, Clone)]
pub struct CubicIdentification {
    /// The measured zones in file order.
    pub measured: Vec<MeasuredZone>,
    /// The zones on the machine (poses, sensitivities).
    pub zones: Vec<LayoutZone>,
    /// The errors fitted, the columns.
    pub errors: Vec<&'static ErrorDef>,
    /// Per row of the system: `(zone index, what)`, `what` 0 height, 1 slope x, 2 slope y.
    pub rows: Vec<(usize, usize)>,
    /// The fit and the decisions.
    pub judgement: Judgement,
}

/// Identifies the errors from a measurement file (module docs).
pub fn identify_zones(
    input: &super::CubicInput,
    own: &CubicIdentifyInput,
) -> Result<CubicIdentification> {
    let measured = parse_measurements(&own.csv, &input.setup)?;
    let all = input.machine.error_defs();
    let errors: Vec<&'static ErrorDef> = match &own.parameters {
        None => all,
        Some(names) => names
            .iter()
            .enumerate()
            .map(|(i, n)| {
                all.iter().copied().find(|d| d.name == n).ok_or_else(|| {
                    Error::field(
                        format!("parameters[{i}]"),
                        format!("{n} is not an error of this machine"),
                    )
                })
            })
            .collect::<Result<_>>()?,
    };
    if errors.is_empty() {
        return Err(Error::field(
            "parameters",
            "choose at least one error to identify",
        ));
    }
    let (a, d, zones) = system(
        &input.machine,
        &input.setup,
        &input.options(),
        &measured,
        &errors,
    )?;
    let mut rows = Vec::new();
    for (z, m) in measured.iter().enumerate() {
        rows.push((z, 0));
        if m.slope_x.is_some() {
            rows.push((z, 1));
        }
        if m.slope_y.is_some() {
            rows.push((z, 2));
        }
    }
    let params: Vec<Param> = errors
        .iter()
        .map(|d| Param::error(d.name))
        .collect::<Result<_>>()?;
    let judgement = crate::identify::identify(&a, &params, &d, own.rtol, &own.decision.options())
        .map_err(|e| {
        if e.field == "fit" {
            Error::field("csv", e.message)
        } else {
            e
        }
    })?;
    Ok(CubicIdentification {
        measured,
        zones,
        errors,
        rows,
        judgement,
    })
}

/// The exact machined planes of any layout on `machine` with its errors (the chain at each
/// zone's pose, not the first-order model), measured from `options.reference` within each
/// set-up, in the order of `specs`. What the tests simulate measurements with.
pub fn exact_planes(
    machine: &Machine,
    piece: &CubicPiece,
    options: &Options,
    specs: &[(ZoneSpec, f64)],
) -> Result<Vec<ZonePlane>> {
    let mut out = vec![ZonePlane::default(); specs.len()];
    let mut done = vec![false; specs.len()];
    for k in 0..specs.len() {
        if done[k] {
            continue;
        }
        let x = specs[k].1;
        let idx: Vec<usize> = (0..specs.len()).filter(|&i| specs[i].1 == x).collect();
        let zs: Vec<ZoneSpec> = idx.iter().map(|&i| specs[i].0.clone()).collect();
        let placed = CubicPiece {
            workpiece_x: x,
            ..piece.clone()
        };
        let test = Test::with_zones(machine, &placed, options, &zs)?;
        let planes: Vec<ZonePlane> = test
            .zones
            .iter()
            .map(|z| test.plane(z))
            .collect::<Result<_>>()?;
        let centres: Vec<(f64, f64)> = test.zones.iter().map(|z| z.centre).collect();
        for (i, p) in idx
            .iter()
            .zip(relative(&planes, &centres, options.reference))
        {
            out[*i] = p;
            done[*i] = true;
        }
    }
    Ok(out)
}
