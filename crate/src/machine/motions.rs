//! Position-dependent **error motions** of the machine's axes (ISO 230-1 `E_XX(X) … E_CC(C)`):
//! six per axis, each a function of that axis's own position, in the machine's one error table
//! beside the location errors ([`super::errors`]).
//!
//! # Names and signs
//! `E_<c><axis>`: component `c` of the error motion of `axis`: `X`, `Y`, `Z` a displacement
//! (mm), `A`, `B`, `C` a rotation about X, Y, Z (rad inside, degrees at the edge). For a linear
//! axis `E_XX` is its positioning error, `E_YX`, `E_ZX` its straightness, `E_AX` roll, `E_BX`,
//! `E_CX` pitch and yaw; for a rotary axis `E_XC`, `E_YC` are its radial error motions, `E_ZC`
//! axial, `E_AC`, `E_BC` its tilt error motions and `E_CC` its angular positioning error.
//!
//! **Sign (ISO 230-1, ISO 841).** An error motion is what the axis adds to its commanded motion
//! *of the tool relative to the workpiece*, in the sense of the machine axes: `E_XX = +2 µm` at
//! `X = 300` means the tool stands 2 µm further along +X on the workpiece than commanded,
//! whether X moves the spindle or the table: the value a laser interferometer reads as "actual
//! minus target". In the chain ([`crate::chain::Link`]) a spindle-side axis displaces its frame
//! by `D(m(q))`, a table-side axis by `D(m(q))⁻¹`. (Location errors `E_X0C` are positions of the
//! axis line itself and keep their sign on either side: see [`super::errors`].)
//!
//! **Frame.** The error motion of a linear axis acts in its moving frame at its current position
//! (roll, pitch and yaw turn about the carriage's reference point, the origin of the axis frame,
//! which is where the machine origin is carried by the axis); that of a rotary axis in the
//! non-rotating frame of its axis line (a radial error motion `E_XC` is along X whatever the
//! angle of C, as a fixed sensor sees it).
//!
//! # Values ([`ErrorFunction`])
//! Each error motion is a constant, a polynomial in the axis position or a table of measured
//! values against position:
//! * **constant** `0.002`: mm or degrees;
//! * **polynomial** `{ "poly": [c0, c1, c2, …] }`: `value = c0 + c1·p + c2·p² + …` with the
//!   position `p` in mm (linear axes) or degrees (rotary axes, the command as given) and the
//!   value in mm or degrees;
//! * **table** `{ "position": [p0, p1, …], "value": [v0, v1, …] }`: positions strictly increasing
//!   (mm or degrees), **linear interpolation** between neighbours (as the compensation tables of
//!   CNC controls do). A position outside `[p0, pn]` is refused with the error's name and the
//!   range; for a rotary axis the position is first taken modulo 360° into the range when that
//!   is possible (a table over 0°…360° serves −90°).
//!
//! [`read_table_csv`] reads such a table from the CSV a measuring program exports.

use super::errors::{Alias, ErrorDef, ErrorKind, MAX_ANGLE_ERROR, MAX_POSITION_ERROR};
use crate::chain::RigidError;
use crate::error::{Error, Result};
use crate::schema::{check_number, closest, join, Custom, Kind, Quantity};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use std::collections::BTreeMap;
use std::f64::consts::TAU;

const TAN_LIM: &str = "Tan & Lim (volumetric error)";

/// A Tan & Lim symbol: `ISO = sign · symbol` on their RRTTT machine (X under the table, Y and Z
/// on the spindle, see [`crate::volumetric::paper`]).
const fn tl(symbol: &'static str, ascii: &'static str, sign: f64) -> Alias {
    Alias {
        symbol,
        ascii,
        sign,
        source: TAN_LIM,
    }
}

const fn motion(
    name: &'static str,
    axis: char,
    component: usize,
    label: &'static str,
    description: &'static str,
    aliases: &'static [Alias],
) -> ErrorDef {
    let angle = component >= 3;
    ErrorDef {
        name,
        axis,
        component,
        kind: ErrorKind::Motion,
        quantity: if angle {
            Quantity::SmallAngle
        } else {
            Quantity::SmallLength
        },
        limit: if angle {
            MAX_ANGLE_ERROR
        } else {
            MAX_POSITION_ERROR
        },
        label,
        description,
        aliases,
    }
}

/// Every error motion: X, Y, Z (positioning, two straightnesses, roll/pitch/yaw about X, Y, Z),
/// then A, B, C (radial, axial, tilt and angular positioning). Tan & Lim's symbols are aliases
/// with the signs of their loop (Section VI): their X moves the table, so its translations
/// along Y, Z and its rotations change sign; their rotary-table translations `∂X_C` are already
/// of the tool relative to the table and their rotations `φ, λ, γ` are not.
pub const MOTIONS: [ErrorDef; 36] = [
    motion(
        "E_XX",
        'X',
        0,
        "X positioning",
        "The tool stands this far further along +X than commanded, as a laser reads it along X.",
        &[tl("δx(X)", "dx(X)", 1.0)],
    ),
    motion(
        "E_YX",
        'X',
        1,
        "X straightness in Y",
        "Moving X, the tool wanders this far towards +Y.",
        &[tl("δy(X)", "dy(X)", -1.0)],
    ),
    motion(
        "E_ZX",
        'X',
        2,
        "X straightness in Z",
        "Moving X, the tool wanders this far towards +Z.",
        &[tl("δz(X)", "dz(X)", -1.0)],
    ),
    motion(
        "E_AX",
        'X',
        3,
        "X roll about X",
        "The X carriage turns about X by this angle.",
        &[tl("Ex(X)", "Ex(X)", -1.0)],
    ),
    motion(
        "E_BX",
        'X',
        4,
        "X pitch about Y",
        "The X carriage turns about Y by this angle.",
        &[tl("Ey(X)", "Ey(X)", -1.0)],
    ),
    motion(
        "E_CX",
        'X',
        5,
        "X yaw about Z",
        "The X carriage turns about Z by this angle.",
        &[tl("Ez(X)", "Ez(X)", -1.0)],
    ),
    motion(
        "E_XY",
        'Y',
        0,
        "Y straightness in X",
        "Moving Y, the tool wanders this far towards +X.",
        &[tl("δx(Y)", "dx(Y)", 1.0)],
    ),
    motion(
        "E_YY",
        'Y',
        1,
        "Y positioning",
        "The tool stands this far further along +Y than commanded.",
        &[tl("δy(Y)", "dy(Y)", 1.0)],
    ),
    motion(
        "E_ZY",
        'Y',
        2,
        "Y straightness in Z",
        "Moving Y, the tool wanders this far towards +Z.",
        &[tl("δz(Y)", "dz(Y)", 1.0)],
    ),
    motion(
        "E_AY",
        'Y',
        3,
        "Y pitch about X",
        "The Y carriage turns about X by this angle.",
        &[tl("Ex(Y)", "Ex(Y)", 1.0)],
    ),
    motion(
        "E_BY",
        'Y',
        4,
        "Y roll about Y",
        "The Y carriage turns about Y by this angle.",
        &[tl("Ey(Y)", "Ey(Y)", 1.0)],
    ),
    motion(
        "E_CY",
        'Y',
        5,
        "Y yaw about Z",
        "The Y carriage turns about Z by this angle.",
        &[tl("Ez(Y)", "Ez(Y)", 1.0)],
    ),
    motion(
        "E_XZ",
        'Z',
        0,
        "Z straightness in X",
        "Moving Z, the tool wanders this far towards +X.",
        &[tl("δx(Z)", "dx(Z)", 1.0)],
    ),
    motion(
        "E_YZ",
        'Z',
        1,
        "Z straightness in Y",
        "Moving Z, the tool wanders this far towards +Y.",
        &[tl("δy(Z)", "dy(Z)", 1.0)],
    ),
    motion(
        "E_ZZ",
        'Z',
        2,
        "Z positioning",
        "The tool stands this far further along +Z than commanded.",
        &[tl("δz(Z)", "dz(Z)", 1.0)],
    ),
    motion(
        "E_AZ",
        'Z',
        3,
        "Z tilt about X",
        "The Z carriage turns about X by this angle.",
        &[tl("Ex(Z)", "Ex(Z)", 1.0)],
    ),
    motion(
        "E_BZ",
        'Z',
        4,
        "Z tilt about Y",
        "The Z carriage turns about Y by this angle.",
        &[tl("Ey(Z)", "Ey(Z)", 1.0)],
    ),
    motion(
        "E_CZ",
        'Z',
        5,
        "Z roll about Z",
        "The Z carriage turns about Z by this angle.",
        &[tl("Ez(Z)", "Ez(Z)", 1.0)],
    ),
    motion(
        "E_XA",
        'A',
        0,
        "A axial error motion along X",
        "Turning A, what it carries moves this far along X.",
        &[tl("∂X_A", "dXA", 1.0)],
    ),
    motion(
        "E_YA",
        'A',
        1,
        "A radial error motion in Y",
        "Turning A, what it carries moves this far along Y.",
        &[tl("∂Y_A", "dYA", 1.0)],
    ),
    motion(
        "E_ZA",
        'A',
        2,
        "A radial error motion in Z",
        "Turning A, what it carries moves this far along Z.",
        &[tl("∂Z_A", "dZA", 1.0)],
    ),
    motion(
        "E_AA",
        'A',
        3,
        "A angular positioning",
        "A turns this much further than commanded.",
        &[tl("φ_A", "phiA", -1.0)],
    ),
    motion(
        "E_BA",
        'A',
        4,
        "A tilt error motion about Y",
        "Turning A, its axis tilts about Y by this angle.",
        &[tl("λ_A", "lambdaA", -1.0)],
    ),
    motion(
        "E_CA",
        'A',
        5,
        "A tilt error motion about Z",
        "Turning A, its axis tilts about Z by this angle.",
        &[tl("γ_A", "gammaA", -1.0)],
    ),
    motion(
        "E_XB",
        'B',
        0,
        "B radial error motion in X",
        "Turning B, what it carries moves this far along X.",
        &[],
    ),
    motion(
        "E_YB",
        'B',
        1,
        "B axial error motion along Y",
        "Turning B, what it carries moves this far along Y.",
        &[],
    ),
    motion(
        "E_ZB",
        'B',
        2,
        "B radial error motion in Z",
        "Turning B, what it carries moves this far along Z.",
        &[],
    ),
    motion(
        "E_AB",
        'B',
        3,
        "B tilt error motion about X",
        "Turning B, its axis tilts about X by this angle.",
        &[],
    ),
    motion(
        "E_BB",
        'B',
        4,
        "B angular positioning",
        "B turns this much further than commanded.",
        &[],
    ),
    motion(
        "E_CB",
        'B',
        5,
        "B tilt error motion about Z",
        "Turning B, its axis tilts about Z by this angle.",
        &[],
    ),
    motion(
        "E_XC",
        'C',
        0,
        "C radial error motion in X",
        "Turning C, what it carries moves this far along X.",
        &[tl("∂X_C", "dXC", 1.0)],
    ),
    motion(
        "E_YC",
        'C',
        1,
        "C radial error motion in Y",
        "Turning C, what it carries moves this far along Y.",
        &[tl("∂Y_C", "dYC", 1.0)],
    ),
    motion(
        "E_ZC",
        'C',
        2,
        "C axial error motion along Z",
        "Turning C, what it carries moves this far along Z.",
        &[tl("∂Z_C", "dZC", 1.0)],
    ),
    motion(
        "E_AC",
        'C',
        3,
        "C tilt error motion about X",
        "Turning C, its axis tilts about X by this angle.",
        &[tl("φ_C", "phiC", -1.0)],
    ),
    motion(
        "E_BC",
        'C',
        4,
        "C tilt error motion about Y",
        "Turning C, its axis tilts about Y by this angle.",
        &[tl("λ_C", "lambdaC", -1.0)],
    ),
    motion(
        "E_CC",
        'C',
        5,
        "C angular positioning",
        "C turns this much further than commanded.",
        &[tl("γ_C", "gammaC", -1.0)],
    ),
];

/// The error motion named `name` (exact ISO spelling).
pub fn find(name: &str) -> Option<&'static ErrorDef> {
    MOTIONS.iter().find(|d| d.name == name)
}

/// Whether `letter` names a rotary axis (its error motions are functions of an angle).
pub fn is_rotary(letter: char) -> bool {
    matches!(letter, 'A' | 'B' | 'C')
}

/// The position quantity of an axis: mm or degrees.
pub fn position_quantity(letter: char) -> Quantity {
    if is_rotary(letter) {
        Quantity::Angle
    } else {
        Quantity::Length
    }
}

/// One error motion's values against the axis position. At the API: mm or degrees (positions
/// and values, the forms in the module docs); inside the engine the same forms in mm and rad.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(untagged)]
pub enum ErrorFunction {
    /// The same value at every position.
    Constant(f64),
    /// `Σ c_k·p^k`, coefficients in engine units per engine position unit to the k.
    Polynomial {
        /// `c0, c1, …`.
        poly: Vec<f64>,
    },
    /// Measured values, linearly interpolated.
    Table {
        /// Positions, strictly increasing.
        position: Vec<f64>,
        /// Values at those positions.
        value: Vec<f64>,
    },
}

impl ErrorFunction {
    /// The value at position `p` (engine units); `name` and `rotary` for the message and the
    /// modulo-360° rule of tables.
    pub fn at(&self, p: f64, name: &str, rotary: bool) -> Result<f64> {
        match self {
            ErrorFunction::Constant(v) => Ok(*v),
            ErrorFunction::Polynomial { poly } => {
                let v = poly.iter().rev().fold(0.0, |acc, c| acc * p + c);
                // A polynomial can leave the accepted range where a table or a constant cannot.
                let def = find(name);
                let (q, limit) = def.map_or((Quantity::SmallLength, MAX_POSITION_ERROR), |d| {
                    (d.quantity, d.limit)
                });
                if v.is_finite() && q.to_api(v).abs() <= limit {
                    return Ok(v);
                }
                let pq = position_quantity(def.map_or('X', |d| d.axis));
                Err(Error::field(
                    join("machine.motions", name),
                    format!(
                        "the polynomial gives {} {} at {} {}, beyond the ±{limit} {} accepted",
                        q.to_api(v),
                        q.api_unit(),
                        (pq.to_api(p) * 1e6).round() / 1e6,
                        pq.api_unit(),
                        q.api_unit()
                    ),
                ))
            }
            ErrorFunction::Table { position, value } => {
                let (lo, hi) = (position[0], position[position.len() - 1]);
                let mut x = p;
                if rotary && !(lo..=hi).contains(&x) {
                    x = lo + (x - lo).rem_euclid(TAU);
                }
                if !(lo..=hi).contains(&x) {
                    let q = if rotary {
                        Quantity::Angle
                    } else {
                        Quantity::Length
                    };
                    let show = |v: f64| format!("{}", (q.to_api(v) * 1e6).round() / 1e6);
                    return Err(Error::field(
                        join("machine.motions", name),
                        format!(
                            "the table covers {} to {} {}; the axis is at {} {} (outside it; a table is not extrapolated)",
                            show(lo),
                            show(hi),
                            q.api_unit(),
                            show(p),
                            q.api_unit()
                        ),
                    ));
                }
                // The segment [i, i+1] holding x: the first position above x, less one.
                let i = position
                    .partition_point(|&q| q <= x)
                    .clamp(1, position.len() - 1)
                    - 1;
                let t = (x - position[i]) / (position[i + 1] - position[i]);
                Ok(value[i] + t * (value[i + 1] - value[i]))
            }
        }
    }
}

/// The machine's error motions by ISO name (engine units); those not given are zero.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(transparent)]
pub struct ErrorMotions(
    #[cfg_attr(feature = "ts", tsify(type = "Partial<Record<string, ErrorFunction>>"))]
    pub  BTreeMap<String, ErrorFunction>,
);

impl ErrorMotions {
    /// The error motions of `axis` as one function of its position: the six components (engine
    /// units), or `None` when the axis has none.
    pub fn of_axis(&self, axis: char) -> Option<Vec<(usize, String, ErrorFunction)>> {
        let list: Vec<_> = MOTIONS
            .iter()
            .filter(|d| d.axis == axis)
            .filter_map(|d| {
                self.0
                    .get(d.name)
                    .map(|f| (d.component, d.name.to_string(), f.clone()))
            })
            .collect();
        (!list.is_empty()).then_some(list)
    }

    /// The six components of `axis`'s error motion at position `p`.
    pub fn rigid(
        list: &[(usize, String, ErrorFunction)],
        p: f64,
        axis: char,
    ) -> Result<RigidError> {
        let mut e = RigidError::default();
        for (k, name, f) in list {
            e.set(*k, f.at(p, name, is_rotary(axis))?);
        }
        Ok(e)
    }

    /// Sets `name` to `f` (engine units). Unknown names are refused.
    pub fn set(&mut self, name: &str, f: ErrorFunction) -> Result<()> {
        if find(name).is_none() {
            return Err(unknown(&join("motions", name), name));
        }
        self.0.insert(name.to_string(), f);
        Ok(())
    }
}

/// The message for a name that is not an error motion.
pub fn unknown(path: &str, name: &str) -> Error {
    if super::errors::find(name).is_some() {
        return Error::field(
            path,
            format!("{name} is a location error (a constant of the axis line); give it in machine.errors"),
        );
    }
    let alias = MOTIONS.iter().find_map(|d| {
        d.aliases
            .iter()
            .find(|a| a.symbol == name || a.ascii == name)
            .map(|a| (d, a))
    });
    if let Some((d, a)) = alias {
        return super::errors::symbol_entered(path, name, d, a);
    }
    let names: Vec<&str> = MOTIONS.iter().map(|d| d.name).collect();
    let hint = closest(name, &names)
        .map(|k| format!(" Did you mean {k}?"))
        .unwrap_or_default();
    Error::field(
        path,
        format!("unknown error motion; they are named as in ISO 230-1 (E_XX, E_YX, … E_CC).{hint}"),
    )
}

/// The schema kind of the machine's error motions: an object of ISO 230-1 names to a number, a
/// polynomial or a table against position.
pub const KIND: Kind = Kind::Custom(&Custom {
    name: "motions",
    read: read_motions,
    list: false,
});

/// Reads the error motions (the schema kind [`KIND`]): name → a number, a
/// `{ poly }` or a `{ position, value }` table in API units, checked and converted to engine
/// units.
pub fn read_motions(v: &Value, path: &str) -> Result<Value> {
    let obj = v.as_object().ok_or_else(|| {
        Error::field(
            path,
            "expected an object of error motions by ISO 230-1 name, e.g. { \"E_XX\": 0.002 }",
        )
    })?;
    let mut out = Map::new();
    for (name, value) in obj {
        let p = join(path, name);
        let def = find(name).ok_or_else(|| unknown(&p, name))?;
        let f = read_function(value, &p, def)?;
        out.insert(
            name.clone(),
            serde_json::to_value(f).map_err(|e| Error::field(&p, e.to_string()))?,
        );
    }
    Ok(Value::Object(out))
}

fn numbers(v: &Value, path: &str, min_len: usize) -> Result<Vec<f64>> {
    let list = v
        .as_array()
        .ok_or_else(|| Error::field(path, "expected a list of numbers"))?;
    if list.len() < min_len {
        return Err(Error::field(
            path,
            format!("expected at least {min_len} numbers, got {}", list.len()),
        ));
    }
    list.iter()
        .enumerate()
        .map(|(i, x)| {
            check_number(
                &format!("{path}[{i}]"),
                x,
                Quantity::Number,
                f64::MIN,
                f64::MAX,
            )
        })
        .collect()
}

/// One error motion at the edge → engine units.
fn read_function(v: &Value, path: &str, def: &ErrorDef) -> Result<ErrorFunction> {
    let q = def.quantity;
    let pq = position_quantity(def.axis);
    if v.is_number() {
        let x = check_number(path, v, q, -def.limit, def.limit)?;
        return Ok(ErrorFunction::Constant(q.to_engine(x)));
    }
    let obj = v.as_object().ok_or_else(|| {
        Error::field(
            path,
            format!(
                "expected a number ({}), {{ \"poly\": [c0, c1, …] }} or {{ \"position\": […], \"value\": […] }}",
                q.api_unit()
            ),
        )
    })?;
    let keys: Vec<&str> = obj.keys().map(String::as_str).collect();
    if keys == ["poly"] {
        let c = numbers(&obj["poly"], &join(path, "poly"), 1)?;
        if c.len() > 8 {
            return Err(Error::field(
                join(path, "poly"),
                "at most 8 coefficients (degree 7)",
            ));
        }
        // value_api = Σ c_k p_api^k → value_engine = to_engine(Σ c_k (p_engine/to_engine(1))^k).
        let unit = pq.to_engine(1.0);
        let poly = c
            .iter()
            .enumerate()
            .map(|(k, ck)| q.to_engine(*ck) / unit.powi(k as i32))
            .collect();
        return Ok(ErrorFunction::Polynomial { poly });
    }
    let mut sorted = keys.clone();
    sorted.sort_unstable();
    if sorted != ["position", "value"] {
        let bad = keys
            .iter()
            .find(|k| !matches!(**k, "poly" | "position" | "value"))
            .copied();
        return Err(Error::field(
            bad.map_or(path.to_string(), |k| join(path, k)),
            "expected { \"poly\": [c0, c1, …] } or { \"position\": […], \"value\": […] }",
        ));
    }
    let pos = numbers(&obj["position"], &join(path, "position"), 2)?;
    let val = numbers(&obj["value"], &join(path, "value"), 2)?;
    if pos.len() != val.len() {
        return Err(Error::field(
            join(path, "value"),
            format!("{} values for {} positions", val.len(), pos.len()),
        ));
    }
    if let Some(i) = (1..pos.len()).find(|&i| pos[i] <= pos[i - 1]) {
        return Err(Error::field(
            format!("{path}.position[{i}]"),
            format!("positions must increase: {} follows {}", pos[i], pos[i - 1]),
        ));
    }
    for (i, x) in val.iter().enumerate() {
        check_number(
            &format!("{path}.value[{i}]"),
            &Value::from(*x),
            q,
            -def.limit,
            def.limit,
        )?;
    }
    Ok(ErrorFunction::Table {
        position: pos.iter().map(|x| pq.to_engine(*x)).collect(),
        value: val.iter().map(|x| q.to_engine(*x)).collect(),
    })
}

/// A table read from CSV, API units (mm or degrees).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct CsvTable {
    /// Positions, mm or degrees, increasing.
    pub position: Vec<f64>,
    /// Values, mm or degrees.
    pub value: Vec<f64>,
    /// The units the header gave: position, value.
    pub units: [String; 2],
}

/// Reads a table for error motion `name` from CSV as measuring software exports it: a header
/// line naming the two columns with their units in brackets (`X (mm), E_XX (µm)`; lengths mm,
/// µm, nm, m, in; angles deg, rad, mrad, µrad, arcsec, µm/m), then one `position, value` per
/// line. Separators: comma, semicolon or tab, per line; with `;` or tab a decimal comma is
/// accepted (`0;0,0208`), with `,` a comma only separates. Lines starting with `#` and empty
/// lines are skipped. The engine's one tokenizer, [`crate::csv`]. Errors name the line
/// (`line 7: …`) and quote at most 40 characters of the text.
pub fn read_table_csv(text: &str, name: &str) -> Result<CsvTable> {
    let def = find(name).ok_or_else(|| unknown("name", name))?;
    let angle_pos = is_rotary(def.axis);
    let angle_val = def.component >= 3;
    let mut header: Option<(f64, f64, [String; 2])> = None;
    let (mut pos, mut val) = (Vec::new(), Vec::new());
    for (line_no, line) in crate::csv::lines(text) {
        let at = |msg: String| Error::field("csv", format!("line {line_no}: {msg}"));
        let sep = crate::csv::separator(line).unwrap_or(',');
        let cells = crate::csv::cells(line, sep);
        if cells.len() != 2 {
            return Err(at(format!(
                "expected two columns (position, value), found {}",
                cells.len()
            )));
        }
        let Some((fp, fv, _)) = &header else {
            let (up, uv) = (
                crate::csv::header_unit(cells[0]),
                crate::csv::header_unit(cells[1]),
            );
            // A header that names another error motion or axis is a file for another error.
            for (cell, expected) in [
                (cells[1], name.to_string()),
                (cells[0], def.axis.to_string()),
            ] {
                let word = cell.split(['(', '[']).next().unwrap_or("").trim();
                let other_error = word.len() == 4 && find(word).is_some() && word != expected;
                let other_axis = word.len() == 1 && "XYZABC".contains(word) && word != expected;
                if other_error || other_axis {
                    return Err(at(format!(
                        "the header names {word}, but this table is for {name} (against the {} position)",
                        def.axis
                    )));
                }
            }
            let fp = crate::csv::unit_factor(up, angle_pos).ok_or_else(|| {
                at(format!(
                    "the first line names the columns with their units, e.g. \"{} ({})\"; {} is not a unit of {}",
                    def.axis,
                    if angle_pos { "deg" } else { "mm" },
                    crate::error::quote(cells[0]),
                    if angle_pos { "angle" } else { "length" }
                ))
            })?;
            let fv = crate::csv::unit_factor(uv, angle_val).ok_or_else(|| {
                at(format!(
                    "the second column's unit: {} is not a unit of {} (e.g. \"{} ({})\")",
                    crate::error::quote(cells[1]),
                    if angle_val { "angle" } else { "length" },
                    name,
                    if angle_val { "arcsec" } else { "µm" }
                ))
            })?;
            header = Some((fp, fv, [up.trim().to_string(), uv.trim().to_string()]));
            continue;
        };
        let num = |cell: &str, what: &str| -> Result<f64> {
            crate::csv::number(cell, sep).ok_or_else(|| {
                at(format!(
                    "the {what} {} is not a number",
                    crate::error::quote(cell)
                ))
            })
        };
        let p = num(cells[0], "position")? * fp;
        let v = num(cells[1], "value")? * fv;
        if let Some(&last) = pos.last() {
            if p <= last {
                return Err(at(format!("positions must increase: {p} follows {last}")));
            }
        }
        if v.abs() > def.limit {
            return Err(at(format!(
                "{v} {} is beyond the ±{} {} accepted for {name}",
                def.quantity.api_unit(),
                def.limit,
                def.quantity.api_unit()
            )));
        }
        pos.push(p);
        val.push(v);
    }
    let Some((_, _, units)) = header else {
        return Err(Error::field(
            "csv",
            "the file is empty: expected a header line and at least two rows",
        ));
    };
    if pos.len() < 2 {
        return Err(Error::field(
            "csv",
            format!("a table needs at least two rows, found {}", pos.len()),
        ));
    }
    Ok(CsvTable {
        position: pos,
        value: val,
        units,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn the_table_names_every_component_of_every_axis_once() {
        let letters = ['X', 'Y', 'Z', 'A', 'B', 'C'];
        for (i, d) in MOTIONS.iter().enumerate() {
            assert_eq!(d.name, format!("E_{}{}", letters[d.component], d.axis));
            assert_eq!(d.kind, ErrorKind::Motion);
            assert!(MOTIONS[..i].iter().all(|o| o.name != d.name));
        }
    }

    #[test]
    fn polynomials_are_converted_from_degrees_per_degree() {
        // E_CC = 0.001° + 2e-5°/° · C: at C = 90° (π/2 rad) it is 0.0028° in radians.
        let v = read_motions(&json!({ "E_CC": { "poly": [0.001, 2e-5] } }), "m").unwrap();
        let f: ErrorFunction = serde_json::from_value(v["E_CC"].clone()).unwrap();
        let got = f.at(std::f64::consts::FRAC_PI_2, "E_CC", true).unwrap();
        assert!((got - 0.0028f64.to_radians()).abs() < 1e-15, "{got}");
    }
}
