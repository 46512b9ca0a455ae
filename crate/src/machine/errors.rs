//! The machine's geometric errors, named once: the ISO 230-1 location errors of every axis a
//! five-axis machine can have, each with its unit kind, limit, a one-line description and the
//! symbols the papers use for it. Every study reads the machine's errors by these names.
//!
//! # Names and signs (ISO 230-1)
//! `E_<c>0<axis>`: the location error of `axis` in component `c`: `X`, `Y`, `Z` a position
//! (mm), `A`, `B`, `C` an orientation about X, Y, Z (rad inside the engine, degrees at the edge).
//! In the chain ([`crate::chain`]) it is the axis frame's displacement `D(l)` from its nominal
//! place: `E_X0B = +0.01 mm` means the B axis line lies 10 µm towards +X of where the control
//! believes it is; `E_A0C = +0.001°` means the C axis is turned by +0.001° about X (right-hand
//! rule). For a rotary axis the orientation about its own direction is its zero position
//! (`E_B0B`: B stands at `E_B0B` when the control shows 0°), the position along its own
//! direction moves what it carries along that axis. For the linear axes the table holds the
//! three squareness errors with X as the reference (`E_C0Y`, `E_A0Z`, `E_B0Z`), as ISO 230-1
//! recommends and Chanal et al. (2022) use.
//!
//! # The papers' symbols
//! Li et al. (2021) write the errors of a B/C tilting table as matrices from machine into table
//! coordinates (`δxBY … γBY`, `αCB`, `δxCB`): the inverse of the axis frame's displacement, so
//! each is the ISO error with a **minus sign** (`E_X0B = −δxBY`; exact, see
//! [`crate::cubic`]). Chanal et al. (2022) use the ISO names with the ISO signs.
//!
//! # Position-dependent error motions
//! The error motions `E_XX(X) … E_CC(C)` of every axis are the other half of the table:
//! [`super::motions`], given in `machine.motions` as constants, polynomials or measured tables.

use crate::error::{Error, Result};
use crate::schema::{check_number, closest, join, Custom, Kind, Quantity};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use std::collections::BTreeMap;

/// Largest accepted positional location error, mm (ten times the intentional 0.5 mm of Li et al.
/// Section 5.3).
pub const MAX_POSITION_ERROR: f64 = 5.0;
/// Largest accepted angular location error, degrees (ten times their intentional 0.5°).
pub const MAX_ANGLE_ERROR: f64 = 5.0;

pub use crate::chain::ErrorKind;

/// A paper's symbol for an error, and how its value relates to the ISO one.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct Alias {
    /// The symbol as printed, e.g. `"δxBY"`.
    pub symbol: &'static str,
    /// The same in ASCII as earlier versions of the API spelt it, e.g. `"dxBY"`.
    pub ascii: &'static str,
    /// `ISO = sign · symbol`.
    pub sign: f64,
    /// The paper.
    pub source: &'static str,
}

/// One entry of the error table.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct ErrorDef {
    /// The ISO 230-1 name, e.g. `"E_X0B"`.
    pub name: &'static str,
    /// The axis it belongs to: `'A'`, `'B'`, `'C'`, `'X'`, `'Y'` or `'Z'`.
    pub axis: char,
    /// Component of the axis frame's displacement: 0..3 positions X Y Z, 3..6 orientations A B C.
    pub component: usize,
    /// Location error or error motion.
    pub kind: ErrorKind,
    /// `SmallLength` (mm) or `SmallAngle` (degrees at the edge, rad inside).
    pub quantity: Quantity,
    /// Largest accepted magnitude, API units (mm or degrees).
    pub limit: f64,
    /// Short name for lists: "B axis position along X".
    pub label: &'static str,
    /// One plain sentence: what it means on the machine.
    pub description: &'static str,
    /// The papers' symbols.
    pub aliases: &'static [Alias],
}

const LI: &str = "Li et al. 2021 (cubic-machining test)";

const TAN_LIM: &str = "Tan & Lim (volumetric error)";

/// A Tan & Lim squareness symbol (their RRTTT loop, Section VI): the same angle between two
/// axes, with another axis as the reference, so equal to the ISO error up to a rigid turn of
/// the workpiece ([`crate::volumetric::paper`]).
const fn tan_lim(symbol: &'static str, ascii: &'static str, sign: f64) -> Alias {
    Alias {
        symbol,
        ascii,
        sign,
        source: TAN_LIM,
    }
}

const fn alias(symbol: &'static str, ascii: &'static str) -> Alias {
    Alias {
        symbol,
        ascii,
        sign: -1.0,
        source: LI,
    }
}

/// An entry of the table: a position (`component` 0..3, mm) or an orientation (3..6, degrees).
const fn def(
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
        kind: ErrorKind::Location,
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

/// Every location error, grouped per axis: A, B, C (two positions across the axis, the
/// position along it, two tilts, the zero position), then the squareness of the linear axes.
pub const TABLE: [ErrorDef; 21] = [
    // A (about X)
    def(
        "E_Y0A",
        'A',
        1,
        "A axis position along Y",
        "The A axis line lies this far towards +Y of where the control believes it is.",
        &[],
    ),
    def(
        "E_Z0A",
        'A',
        2,
        "A axis position along Z",
        "The A axis line lies this far towards +Z of where the control believes it is.",
        &[],
    ),
    def(
        "E_X0A",
        'A',
        0,
        "A axis position along its axis (X)",
        "Shifts everything A carries along X, like an offset of the X axis.",
        &[],
    ),
    def(
        "E_B0A",
        'A',
        4,
        "A axis tilt about Y",
        "The A axis is turned about Y: it is not parallel to X in the XZ plane.",
        &[],
    ),
    def(
        "E_C0A",
        'A',
        5,
        "A axis tilt about Z",
        "The A axis is turned about Z: it is not parallel to X in the XY plane.",
        &[],
    ),
    def(
        "E_A0A",
        'A',
        3,
        "A axis zero position",
        "A stands at this angle when the control shows 0°.",
        &[],
    ),
    // B (about Y)
    def(
        "E_X0B",
        'B',
        0,
        "B axis position along X",
        "The B axis line lies this far towards +X of where the control believes it is.",
        &[alias("δxBY", "dxBY")],
    ),
    def(
        "E_Z0B",
        'B',
        2,
        "B axis position along Z",
        "The B axis line lies this far towards +Z of where the control believes it is.",
        &[alias("δzBY", "dzBY")],
    ),
    def(
        "E_Y0B",
        'B',
        1,
        "B axis position along its axis (Y)",
        "Shifts everything B carries along Y, like an offset of the Y axis.",
        &[alias("δyBY", "dyBY")],
    ),
    def(
        "E_A0B",
        'B',
        3,
        "B axis tilt about X",
        "The B axis is turned about X: it is not parallel to Y in the YZ plane.",
        &[alias("αBY", "alphaBY")],
    ),
    def(
        "E_C0B",
        'B',
        5,
        "B axis tilt about Z",
        "The B axis is turned about Z: it is not parallel to Y in the XY plane.",
        &[alias("γBY", "gammaBY")],
    ),
    def(
        "E_B0B",
        'B',
        4,
        "B axis zero position",
        "B stands at this angle when the control shows 0°.",
        &[alias("βBY", "betaBY")],
    ),
    // C (about Z)
    def(
        "E_X0C",
        'C',
        0,
        "C axis position along X",
        "The C axis line lies this far towards +X of where the control believes it is.",
        &[alias("δxCB", "dxCB")],
    ),
    def(
        "E_Y0C",
        'C',
        1,
        "C axis position along Y",
        "The C axis line lies this far towards +Y of where the control believes it is.",
        &[],
    ),
    def(
        "E_Z0C",
        'C',
        2,
        "C axis position along its axis (Z)",
        "Shifts everything C carries along Z, like an offset of the Z axis.",
        &[],
    ),
    def(
        "E_A0C",
        'C',
        3,
        "C axis tilt about X",
        "The C axis is turned about X: it is not parallel to Z in the YZ plane.",
        &[alias("αCB", "alphaCB")],
    ),
    def(
        "E_B0C",
        'C',
        4,
        "C axis tilt about Y",
        "The C axis is turned about Y: it is not parallel to Z in the XZ plane.",
        &[],
    ),
    def(
        "E_C0C",
        'C',
        5,
        "C axis zero position",
        "C stands at this angle when the control shows 0°.",
        &[],
    ),
    // squareness of the linear axes, X the reference
    def(
        "E_C0Y",
        'Y',
        5,
        "Squareness of Y to X",
        "The Y axis is turned about Z: the angle between the X and Y motions is 90° plus this.",
        &[tan_lim("α", "alpha", -1.0)],
    ),
    def(
        "E_A0Z",
        'Z',
        3,
        "Squareness of Z to Y",
        "The Z axis is turned about X: it leans towards −Y (positive value) as it moves up.",
        &[tan_lim("β2", "beta2", 1.0)],
    ),
    def(
        "E_B0Z",
        'Z',
        4,
        "Squareness of Z to X",
        "The Z axis is turned about Y: it leans towards +X (positive value) as it moves up.",
        &[tan_lim("β1", "beta1", -1.0)],
    ),
];

/// The entry named `name` (exact ISO spelling).
pub fn find(name: &str) -> Option<&'static ErrorDef> {
    TABLE.iter().find(|d| d.name == name)
}

/// Values of the machine's errors by ISO name: mm, or degrees for an angle at the edge (radians
/// in Rust). Names not present are zero.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(transparent)]
pub struct ErrorValues(
    #[cfg_attr(feature = "ts", tsify(type = "Partial<Record<string, number>>"))]
    pub  BTreeMap<String, f64>,
);

impl ErrorValues {
    /// No errors.
    pub fn none() -> Self {
        Self::default()
    }

    /// The value of `name` (0 when not given), engine units.
    pub fn get(&self, name: &str) -> f64 {
        self.0.get(name).copied().unwrap_or(0.0)
    }

    /// Sets `name` to `value` (engine units). Unknown names are refused.
    pub fn set(&mut self, name: &str, value: f64) -> Result<()> {
        if find(name).is_none() {
            return Err(unknown_name(&join("errors", name), name));
        }
        self.0.insert(name.to_string(), value);
        Ok(())
    }

    /// Only `name` at `value` (engine units).
    pub fn single(name: &str, value: f64) -> Result<Self> {
        let mut e = Self::none();
        e.set(name, value)?;
        Ok(e)
    }

    /// From a paper's symbols (`"δxBY"` or `"dxBY"`), values in engine units in the paper's own
    /// sign: each becomes its ISO error by [`Alias::sign`].
    pub fn from_aliases(values: &[(&str, f64)]) -> Result<Self> {
        let mut e = Self::none();
        for (symbol, v) in values {
            let (def, a) = alias_of(symbol)
                .ok_or_else(|| Error::field(join("errors", symbol), "not a symbol of any paper"))?;
            e.set(def.name, a.sign * v)?;
        }
        Ok(e)
    }
}

/// Error values held in engine units (rad), written in API units (mm, degrees) by their entry
/// in the error table: a result's errors to put into `machine.errors` as they are
/// (`#[serde(serialize_with = "crate::machine::errors::api_values")]`).
pub fn api_values<S: serde::Serializer>(
    v: &ErrorValues,
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    use serde::ser::SerializeMap;
    let mut map = s.serialize_map(Some(v.0.len()))?;
    for (name, value) in &v.0 {
        let q = find(name).map_or(Quantity::SmallLength, |d| d.quantity);
        map.serialize_entry(name, &q.to_api(*value))?;
    }
    map.end()
}

/// The entry and alias a paper's symbol (or its ASCII spelling) stands for.
pub fn alias_of(symbol: &str) -> Option<(&'static ErrorDef, &'static Alias)> {
    TABLE.iter().find_map(|d| {
        d.aliases
            .iter()
            .find(|a| a.symbol == symbol || a.ascii == symbol)
            .map(|a| (d, a))
    })
}

/// The message for a paper's symbol entered where an ISO name belongs: the ISO name and sign.
pub(super) fn symbol_entered(path: &str, name: &str, d: &ErrorDef, a: &Alias) -> Error {
    let sign = if a.sign < 0.0 { "−" } else { "" };
    Error::field(
        path,
        format!(
            "{name} is the symbol {} of {}; enter it by its ISO 230-1 name: {} = {sign}{}",
            a.symbol, a.source, d.name, a.symbol
        ),
    )
}

/// The message for an unknown error name: a paper's symbol gets its ISO name, a slip the
/// closest name.
fn unknown_name(path: &str, name: &str) -> Error {
    if let Some(d) = super::motions::find(name) {
        return Error::field(
            path,
            format!(
                "{name} is an error motion of {} (a function of its position); give it in machine.motions",
                d.axis
            ),
        );
    }
    if let Some((d, a)) = alias_of(name) {
        return symbol_entered(path, name, d, a);
    }
    let names: Vec<&str> = TABLE.iter().map(|d| d.name).collect();
    let hint = closest(name, &names)
        .map(|k| format!(" Did you mean {k}?"))
        .unwrap_or_default();
    Error::field(
        path,
        format!("unknown error name; the errors are named as in ISO 230-1 (E_X0B, E_A0C, E_C0Y, …).{hint}"),
    )
}

/// The schema kind of the machine's error values: an object of ISO 230-1 names to numbers, each
/// in the unit and within the limit of its entry in [`TABLE`].
pub const VALUES: Kind = Kind::Custom(&Custom {
    name: "errors",
    read: read_values,
    list: false,
});

/// The schema kind of a list of ISO 230-1 error names (e.g. the errors to identify), no repeats.
pub const NAMES: Kind = Kind::Custom(&Custom {
    name: "errorNames",
    read: read_names,
    list: true,
});

/// Reads an object of error values (name → number in mm or degrees), checked against the table
/// and converted to engine units (the schema kind [`VALUES`]).
pub fn read_values(v: &Value, path: &str) -> Result<Value> {
    let obj = v.as_object().ok_or_else(|| {
        Error::field(
            path,
            "expected an object of error values by ISO 230-1 name, e.g. { \"E_X0B\": 0.01 }",
        )
    })?;
    let mut out = Map::new();
    for (name, value) in obj {
        let p = join(path, name);
        let def = find(name).ok_or_else(|| unknown_name(&p, name))?;
        let x = check_number(&p, value, def.quantity, -def.limit, def.limit)?;
        let engine = def.quantity.to_engine(x);
        out.insert(
            name.clone(),
            serde_json::Number::from_f64(engine).map_or(Value::Null, Value::Number),
        );
    }
    Ok(Value::Object(out))
}

/// Reads a list of error names (the schema kind [`NAMES`]).
pub fn read_names(v: &Value, path: &str) -> Result<Value> {
    let list = v.as_array().ok_or_else(|| {
        Error::field(
            path,
            "expected a list of ISO 230-1 error names, e.g. [\"E_X0B\"]",
        )
    })?;
    let mut seen: Vec<&str> = Vec::new();
    for (i, item) in list.iter().enumerate() {
        let p = format!("{path}[{i}]");
        let name = item
            .as_str()
            .ok_or_else(|| Error::field(&p, "expected an error name"))?;
        if find(name).is_none() {
            return Err(unknown_name(&p, name));
        }
        if seen.contains(&name) {
            return Err(Error::field(p, format!("{name} is listed twice")));
        }
        seen.push(name);
    }
    Ok(v.clone())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_names_every_component_once_and_its_name_says_where_it_is() {
        let letters = ['X', 'Y', 'Z', 'A', 'B', 'C'];
        for (i, d) in TABLE.iter().enumerate() {
            assert_eq!(
                d.name,
                format!("E_{}0{}", letters[d.component], d.axis),
                "entry {i}"
            );
            assert!(
                TABLE[..i].iter().all(|o| o.name != d.name),
                "{} twice",
                d.name
            );
        }
        // Six per rotary axis, three squareness errors.
        for axis in ['A', 'B', 'C'] {
            assert_eq!(TABLE.iter().filter(|d| d.axis == axis).count(), 6);
        }
    }

    #[test]
    fn aliases_and_slips_get_the_iso_name_in_the_message() {
        let e = read_values(&serde_json::json!({ "dxBY": 0.01 }), "machine.errors").unwrap_err();
        assert_eq!(e.field, "machine.errors.dxBY");
        assert!(e.message.contains("E_X0B = −δxBY"), "{}", e.message);
        let e = read_values(&serde_json::json!({ "E_A0b": 0.01 }), "errors").unwrap_err();
        assert!(e.message.contains("Did you mean E_A0B?"), "{}", e.message);
        let e = read_values(&serde_json::json!({ "E_X0B": 6 }), "errors").unwrap_err();
        assert_eq!(
            e.to_string(),
            "errors.E_X0B: must be between -5 mm and 5 mm, got 6"
        );
    }

    #[test]
    fn values_are_converted_from_degrees() {
        let v = read_values(&serde_json::json!({ "E_A0B": 0.5, "E_X0B": 0.5 }), "e").unwrap();
        assert!((v["E_A0B"].as_f64().unwrap() - 0.5f64.to_radians()).abs() < 1e-18);
        assert_eq!(v["E_X0B"].as_f64(), Some(0.5));
    }
}
