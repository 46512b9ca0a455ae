//! Inputs declared once: every study (and the machine) declares its inputs as Rust structs with
//! [`inputs!`](crate::inputs), which writes the struct, its serde names and a [`Field`] table
//! beside it: path, label, plain-language help, [`Quantity`], default and limits. The binding
//! exports these tables ([`describe`]); the page renders its forms from them; [`read`] is the one
//! place that refuses unknown keys, checks ranges and converts units.
//!
//! # Units
//! At the JavaScript and JSON edge lengths are in **mm** and angles in **degrees**; inside the
//! engine angles are in radians. [`Quantity::to_engine`] and [`Quantity::to_api`] are the only
//! conversions, and [`read`] applies the first to every number it reads. The page shows small
//! lengths and angles in the user's units (µm, ″, µrad …) and converts to mm and degrees itself.
//!
//! # Reading
//! [`read`] walks a `serde_json::Value` against a struct's field table: a key the table does not
//! know is refused (with the closest known key, or the ISO name for a paper's symbol), a missing
//! required field is refused, a missing optional one takes its default, every number is checked
//! against its limits in API units and converted, and the result is deserialised into the struct.
//! Every message starts with the dotted path of the offending input (`"setup.pick: ..."`).

use crate::error::{Error, Result};
use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::{Map, Value};

/// What a number is. It decides the unit at the edge (mm or degrees), the conversion into the
/// engine (degrees to radians) and, on the page, the unit shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub enum Quantity {
    /// A length of the machine or the part, mm.
    Length,
    /// A small length: an error or a deviation, mm at the edge (µm or mm on the page).
    SmallLength,
    /// An axis position or a large angle, degrees at the edge, radians in the engine.
    Angle,
    /// A small angle: an angular error, degrees at the edge (″, µrad … on the page), radians in
    /// the engine.
    SmallAngle,
    /// A whole number (points of a grid, samples).
    Count,
    /// A dimensionless number (a ratio, a threshold).
    Number,
}

impl Quantity {
    /// True for the two angle quantities (degrees at the edge, radians inside).
    pub fn is_angle(self) -> bool {
        matches!(self, Quantity::Angle | Quantity::SmallAngle)
    }

    /// A value in API units (mm, degrees) in engine units (mm, radians).
    pub fn to_engine(self, v: f64) -> f64 {
        if self.is_angle() {
            v.to_radians()
        } else {
            v
        }
    }

    /// A value in engine units (mm, radians) in API units (mm, degrees).
    pub fn to_api(self, v: f64) -> f64 {
        if self.is_angle() {
            v.to_degrees()
        } else {
            v
        }
    }

    /// A derivative per unit of this quantity in the engine (per mm, per radian) as one per API
    /// unit (per mm, per degree): `∂y/∂x_deg = ∂y/∂x_rad · π/180`.
    pub fn per_api_unit(self, k: f64) -> f64 {
        self.to_engine(k)
    }

    /// The unit at the edge, as messages and the schema spell it: `"mm"`, `"deg"` or `""`.
    pub fn api_unit(self) -> &'static str {
        match self {
            Quantity::Length | Quantity::SmallLength => "mm",
            Quantity::Angle | Quantity::SmallAngle => "deg",
            Quantity::Count | Quantity::Number => "",
        }
    }

    /// The unit in words for messages: "mm", "degrees" or "".
    pub fn unit_words(self) -> &'static str {
        match self {
            Quantity::Angle | Quantity::SmallAngle => "degrees",
            q => q.api_unit(),
        }
    }
}

/// One option of a choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
pub struct Choice {
    /// The value at the edge, e.g. `"table-table"`.
    pub value: &'static str,
    /// What the page shows.
    pub label: &'static str,
    /// One plain sentence.
    pub help: &'static str,
}

/// What kind of value a field holds and how it is checked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// A number of `quantity` in `[min, max]` (API units); above `min` strictly when
    /// `exclusive_min`.
    Number {
        /// What it is (unit and conversion).
        quantity: Quantity,
        /// Smallest accepted value, API units.
        min: f64,
        /// Largest accepted value, API units.
        max: f64,
        /// `min` itself is refused (a length that must be positive).
        exclusive_min: bool,
    },
    /// A whole number in `[min, max]`.
    Count {
        /// Smallest accepted value.
        min: usize,
        /// Largest accepted value.
        max: usize,
    },
    /// `true` or `false`.
    Flag,
    /// One of a list of strings.
    Choice(&'static [Choice]),
    /// Free text of at most `max_len` bytes (a pasted file).
    Text {
        /// Longest accepted text, bytes.
        max_len: usize,
    },
    /// A nested object with its own fields.
    Object(&'static [Field]),
    /// The machine's error values: an object of ISO 230-1 names ([`crate::machine::errors`]) to
    /// numbers, each in the unit and within the limit of its entry in the error table.
    Errors,
    /// A list of ISO 230-1 error names (e.g. the errors to identify), no repeats.
    ErrorNames,
    /// The machine's error motions: an object of ISO 230-1 names
    /// ([`crate::machine::motions`]) to a number, a polynomial or a table against position.
    Motions,
    /// A list of `min_len` to `max_len` numbers of `quantity` in `[min, max]` (none of them
    /// zero when `nonzero`).
    NumberList {
        /// What each is.
        quantity: Quantity,
        /// Smallest accepted value.
        min: f64,
        /// Largest accepted value.
        max: f64,
        /// Fewest values.
        min_len: usize,
        /// Most values.
        max_len: usize,
        /// Zero is refused.
        nonzero: bool,
    },
}

/// The default of a field, in API units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DefaultValue {
    /// No default: a required field, or an optional one that is simply absent (`null`).
    None,
    /// A number.
    Num(f64),
    /// A flag.
    Flag(bool),
    /// A choice or a text.
    Str(&'static str),
    /// An empty object or list (no errors entered, no names chosen) or, for an object field, the
    /// defaults of all its fields.
    Empty,
}

/// One input of a study or of the machine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Field {
    /// Its key in the input object, e.g. `"zoneSize"`.
    pub key: &'static str,
    /// What the page writes next to it.
    pub label: &'static str,
    /// One or two plain sentences: what it is, where it is measured from, what a typical value is.
    pub help: &'static str,
    /// Its kind, limits and unit.
    pub kind: Kind,
    /// Its default (API units).
    pub default: DefaultValue,
    /// It may be left out (then the default applies).
    pub optional: bool,
    /// The page's group (fieldset) it is shown in.
    pub group: &'static str,
    /// The machine kinds it applies to (`"table-table"` …); empty: every kind. A value given for
    /// a machine it does not apply to is refused.
    pub kinds: &'static [&'static str],
    /// The page shows it as a field; `false` for inputs the page derives from others (a sweep's
    /// range, the increments of a move).
    pub shown: bool,
}

impl Field {
    /// The base of every field declaration (`Field { key: …, ..Field::BASE }`).
    pub const BASE: Field = Field {
        key: "",
        label: "",
        help: "",
        kind: Kind::Flag,
        default: DefaultValue::None,
        optional: false,
        group: "",
        kinds: &[],
        shown: true,
    };
}

/// `true` when the `optional` marker was written in an [`inputs!`](crate::inputs) field.
pub const fn optional(marker: &[&str]) -> bool {
    !marker.is_empty()
}

/// A number field of `quantity` within `[min, max]` (API units).
pub const fn number(quantity: Quantity, min: f64, max: f64) -> Kind {
    Kind::Number {
        quantity,
        min,
        max,
        exclusive_min: false,
    }
}

/// A number field of `quantity` in `(0, max]`: a length that must be positive.
pub const fn positive(quantity: Quantity, max: f64) -> Kind {
    Kind::Number {
        quantity,
        min: 0.0,
        max,
        exclusive_min: true,
    }
}

/// A struct of inputs declared with [`inputs!`](crate::inputs): its field table.
pub trait Inputs: DeserializeOwned {
    /// The fields, in the order the page shows them.
    const FIELDS: &'static [Field];

    /// Reads the struct from a JSON value (module docs); `path` prefixes every message.
    fn from_value(value: &Value, path: &str) -> Result<Self> {
        read(Self::FIELDS, value, path)
    }
}

/// Declares a struct of inputs and its [`Field`] table in one place (module docs).
///
/// ```ignore
/// inputs! {
///     /// The test piece.
///     pub struct Piece {
///         /// Side of a zone, mm.
///         pub zone_size: f64 = "zoneSize" optional {
///             label: "Zone size", help: "The face is 3 × 3 zones.",
///             kind: schema::number(Quantity::Length, 1.0, 200.0), default: DefaultValue::Num(16.0),
///         },
///     }
/// }
/// ```
///
/// Each field gives its Rust name and type, its key at the edge, the marker `optional` (it may
/// be left out; its TypeScript property is then optional too) and the [`Field`] entries after
/// `key` and `optional`, each followed by a comma. The struct derives serde (names from the keys, unknown keys refused)
/// and, with the `ts` feature, `tsify::Tsify` for its TypeScript declaration.
#[macro_export]
macro_rules! inputs {
    (
        $(#[$meta:meta])*
        $vis:vis struct $name:ident {
            $(
                $(#[doc = $doc:literal])*
                $fvis:vis $field:ident : $ty:ty = $key:literal $($opt:ident)? { $($spec:tt)* }
            ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, PartialEq, ::serde::Serialize, ::serde::Deserialize)]
        #[cfg_attr(feature = "ts", derive(::tsify::Tsify))]
        #[serde(deny_unknown_fields)]
        $vis struct $name {
            $(
                $(#[doc = $doc])*
                #[serde(rename = $key)]
                $(#[cfg_attr(feature = "ts", tsify($opt))])?
                $fvis $field: $ty,
            )*
        }

        impl $crate::schema::Inputs for $name {
            const FIELDS: &'static [$crate::schema::Field] = &[
                $(
                    $crate::schema::Field {
                        key: $key,
                        optional: $crate::schema::optional(&[$(stringify!($opt))?]),
                        $($spec)*
                        ..$crate::schema::Field::BASE
                    },
                )*
            ];
        }
    };
}

/// Declares an enum of choices with its serde values and its [`Choice`] list (`CHOICES`).
///
/// ```ignore
/// choices! {
///     /// What the heights are measured from.
///     pub enum Reference {
///         /// The nominal face.
///         Workpiece = "workpiece" { label: "Workpiece frame", help: "…" },
///     }
/// }
/// ```
#[macro_export]
macro_rules! choices {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident {
            $(
                $(#[doc = $doc:literal])*
                $var:ident = $value:literal { label: $label:literal, help: $help:literal $(,)? }
            ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, ::serde::Serialize, ::serde::Deserialize)]
        #[cfg_attr(feature = "ts", derive(::tsify::Tsify))]
        $vis enum $name {
            $(
                $(#[doc = $doc])*
                #[serde(rename = $value)]
                $var,
            )*
        }

        impl $name {
            /// Every option, in the order the page lists them.
            pub const CHOICES: &'static [$crate::schema::Choice] = &[
                $($crate::schema::Choice { value: $value, label: $label, help: $help },)*
            ];

            /// The value at the edge.
            pub fn value(self) -> &'static str {
                match self {
                    $($name::$var => $value,)*
                }
            }
        }
    };
}

/// Reads `value` against `fields` into `T` (module docs). `path` is the prefix of messages
/// (`""` at the top).
pub fn read<T: DeserializeOwned>(fields: &[Field], value: &Value, path: &str) -> Result<T> {
    let checked = read_object(fields, value, path)?;
    // The checked object has exactly the struct's keys with values of the right kinds, so this
    // cannot fail unless a field table disagrees with its struct (a test checks every table).
    serde_json::from_value(checked).map_err(|e| {
        Error::field(
            path,
            format!("the input does not match its declaration ({e})"),
        )
    })
}

/// Reads one object as two input structs: the keys `B` declares go to `B`, the others to `A`
/// (an export whose inputs are a shared case plus its own, e.g. the cubic test and its grid).
/// A key neither declares is refused with both lists of keys.
pub fn read_split<A: Inputs, B: Inputs>(value: &Value, path: &str) -> Result<(A, B)> {
    let obj = match value {
        Value::Object(m) => m.clone(),
        Value::Null => Map::new(),
        other => {
            return Err(Error::field(
                if path.is_empty() { "input" } else { path },
                format!("expected an object, got {}", what(other)),
            ))
        }
    };
    let mut a = Map::new();
    let mut b = Map::new();
    for (k, v) in obj {
        if B::FIELDS.iter().any(|f| f.key == k) {
            b.insert(k, v);
        } else if A::FIELDS.iter().any(|f| f.key == k) {
            a.insert(k, v);
        } else {
            let all: Vec<Field> = A::FIELDS.iter().chain(B::FIELDS).copied().collect();
            return Err(unknown_key(&all, path, &k));
        }
    }
    Ok((
        A::from_value(&Value::Object(a), path)?,
        B::from_value(&Value::Object(b), path)?,
    ))
}

/// `path.key`, or `key` at the top.
pub fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// What a JSON value is, in words, for messages.
fn what(v: &Value) -> String {
    match v {
        Value::Null => "null".into(),
        Value::Bool(b) => b.to_string(),
        Value::Number(n) => n.to_string(),
        Value::String(s) if s.chars().count() > 40 => "a text".into(),
        Value::String(s) => format!("{s:?}"),
        Value::Array(_) => "a list".into(),
        Value::Object(_) => "an object".into(),
    }
}

/// Checks an object against `fields` and returns it with defaults filled in and every number in
/// engine units.
pub fn read_object(fields: &[Field], value: &Value, path: &str) -> Result<Value> {
    read_object_in(fields, value, path, None)
}

/// [`read_object`] within a machine of kind `machine_kind` (the value of a sibling or parent
/// field `"kind"`): a field that does not apply to that kind is refused when given.
fn read_object_in(
    fields: &[Field],
    value: &Value,
    path: &str,
    mut machine_kind: Option<String>,
) -> Result<Value> {
    let empty = Map::new();
    let obj = match value {
        Value::Object(m) => m,
        Value::Null => &empty,
        other => {
            return Err(Error::field(
                if path.is_empty() { "input" } else { path },
                format!("expected an object, got {}", what(other)),
            ))
        }
    };
    if let Some(key) = obj
        .keys()
        .find(|k| !fields.iter().any(|f| f.key == k.as_str()))
    {
        return Err(unknown_key(fields, path, key));
    }
    let mut out = Map::new();
    for f in fields {
        let p = join(path, f.key);
        let v = match obj.get(f.key) {
            Some(v) if !v.is_null() => {
                if let Some(kind) = &machine_kind {
                    if !f.kinds.is_empty() && !f.kinds.contains(&kind.as_str()) {
                        return Err(Error::field(
                            p,
                            format!(
                                "does not apply to a {kind} machine (only to {}); leave it out",
                                f.kinds.join(", ")
                            ),
                        ));
                    }
                }
                read_field(f, v, &p, &machine_kind)?
            }
            _ if !f.optional => {
                return Err(Error::field(p, format!("is required ({})", f.label)));
            }
            _ => default_value(f, &p)?,
        };
        if f.key == "kind" && matches!(f.kind, Kind::Choice(_)) {
            machine_kind = v.as_str().map(str::to_string);
        }
        out.insert(f.key.to_string(), v);
    }
    Ok(Value::Object(out))
}

/// The message for a key no field has: the known keys, and the closest one when it looks like a
/// slip (same letters in another case, or one letter off).
fn unknown_key(fields: &[Field], path: &str, key: &str) -> Error {
    let keys: Vec<&str> = fields.iter().map(|f| f.key).collect();
    let hint = closest(key, &keys)
        .map(|k| format!(" Did you mean {k:?}?"))
        .unwrap_or_default();
    Error::field(
        join(path, key),
        format!(
            "unknown input; expected one of {}.{hint}",
            keys.iter()
                .map(|k| format!("{k:?}"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    )
}

/// The candidate within edit distance 2 of `key` (case-insensitive), if exactly one is closest.
pub fn closest<'a>(key: &str, candidates: &[&'a str]) -> Option<&'a str> {
    let k = key.to_lowercase();
    let mut best: Option<(usize, &str)> = None;
    let mut tie = false;
    for c in candidates {
        let d = edit_distance(&k, &c.to_lowercase());
        match best {
            Some((bd, _)) if d > bd => {}
            Some((bd, _)) if d == bd => tie = true,
            _ => {
                best = Some((d, c));
                tie = false;
            }
        }
    }
    match best {
        Some((d, c)) if d <= 2 && !tie => Some(c),
        _ => None,
    }
}

/// Levenshtein distance between two short strings.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

/// The default of a field that was left out, in engine units.
fn default_value(f: &Field, path: &str) -> Result<Value> {
    Ok(match (f.kind, f.default) {
        (Kind::Object(fields), DefaultValue::Empty) => read_object(fields, &Value::Null, path)?,
        (Kind::Number { quantity, .. }, DefaultValue::Num(v)) => json_number(quantity.to_engine(v)),
        (Kind::Count { .. }, DefaultValue::Num(v)) => Value::from(v as u64),
        (_, DefaultValue::Num(v)) => json_number(v),
        (_, DefaultValue::Flag(b)) => Value::Bool(b),
        (_, DefaultValue::Str(s)) => Value::String(s.to_string()),
        (_, DefaultValue::None) => Value::Null,
        (Kind::ErrorNames, DefaultValue::Empty) => Value::Array(Vec::new()),
        (_, DefaultValue::Empty) => Value::Object(Map::new()),
    })
}

fn json_number(v: f64) -> Value {
    serde_json::Number::from_f64(v).map_or(Value::Null, Value::Number)
}

/// A number in `[min, max]` (API units), checked: the message says the unit.
pub fn check_number(path: &str, v: &Value, quantity: Quantity, min: f64, max: f64) -> Result<f64> {
    check_number_in(path, v, quantity, min, max, false)
}

fn check_number_in(
    path: &str,
    v: &Value,
    quantity: Quantity,
    min: f64,
    max: f64,
    exclusive_min: bool,
) -> Result<f64> {
    let unit = quantity.unit_words();
    let with_unit = |x: f64| {
        if unit.is_empty() {
            format!("{x}")
        } else {
            format!("{x} {unit}")
        }
    };
    let x = v.as_f64().ok_or_else(|| {
        Error::field(
            path,
            format!(
                "expected a number{}, got {}",
                if unit.is_empty() {
                    String::new()
                } else {
                    format!(" of {unit}")
                },
                what(v)
            ),
        )
    })?;
    if exclusive_min && x <= min {
        return Err(Error::field(
            path,
            format!(
                "must be greater than {} and at most {}, got {x}",
                with_unit(min),
                with_unit(max)
            ),
        ));
    }
    if x < min || x > max {
        return Err(Error::field(
            path,
            format!(
                "must be between {} and {}, got {x}",
                with_unit(min),
                with_unit(max)
            ),
        ));
    }
    Ok(x)
}

/// One given value of field `f` at `path`, checked and in engine units; an object is read
/// within the machine of kind `machine_kind` ([`read_object_in`]).
fn read_field(f: &Field, v: &Value, path: &str, machine_kind: &Option<String>) -> Result<Value> {
    match f.kind {
        Kind::Number {
            quantity,
            min,
            max,
            exclusive_min,
        } => {
            let x = check_number_in(path, v, quantity, min, max, exclusive_min)?;
            Ok(json_number(quantity.to_engine(x)))
        }
        Kind::Count { min, max } => {
            let x = v.as_f64().ok_or_else(|| {
                Error::field(path, format!("expected a whole number, got {}", what(v)))
            })?;
            if x.fract() != 0.0 || x < min as f64 || x > max as f64 {
                return Err(Error::field(
                    path,
                    format!("must be a whole number between {min} and {max}, got {x}"),
                ));
            }
            Ok(Value::from(x as u64))
        }
        Kind::Flag => match v {
            Value::Bool(_) => Ok(v.clone()),
            _ => Err(Error::field(
                path,
                format!("expected true or false, got {}", what(v)),
            )),
        },
        Kind::Choice(choices) => {
            let s = v.as_str().unwrap_or_default();
            if choices.iter().any(|c| c.value == s) {
                return Ok(v.clone());
            }
            let values: Vec<&str> = choices.iter().map(|c| c.value).collect();
            let hint = closest(s, &values)
                .map(|k| format!(" Did you mean {k:?}?"))
                .unwrap_or_default();
            Err(Error::field(
                path,
                format!(
                    "expected one of {}, got {}.{hint}",
                    values
                        .iter()
                        .map(|k| format!("{k:?}"))
                        .collect::<Vec<_>>()
                        .join(", "),
                    what(v)
                ),
            ))
        }
        Kind::Text { max_len } => match v {
            Value::String(s) if s.len() <= max_len => Ok(v.clone()),
            Value::String(s) => Err(Error::field(
                path,
                format!("is {} bytes long; at most {max_len} are accepted", s.len()),
            )),
            _ => Err(Error::field(
                path,
                format!("expected a text, got {}", what(v)),
            )),
        },
        Kind::Object(fields) => read_object_in(fields, v, path, machine_kind.clone()),
        Kind::NumberList {
            quantity,
            min,
            max,
            min_len,
            max_len,
            nonzero,
        } => {
            let list = v.as_array().ok_or_else(|| {
                Error::field(path, format!("expected a list of numbers, got {}", what(v)))
            })?;
            if list.len() < min_len || list.len() > max_len {
                let count = if min_len == max_len {
                    format!("{min_len}")
                } else {
                    format!("{min_len} to {max_len}")
                };
                return Err(Error::field(
                    path,
                    format!("expected {count} values, got {}", list.len()),
                ));
            }
            let mut out = Vec::with_capacity(list.len());
            for (i, item) in list.iter().enumerate() {
                let p = format!("{path}[{i}]");
                let x = check_number(&p, item, quantity, min, max)?;
                if nonzero && x == 0.0 {
                    return Err(Error::field(p, "must not be zero"));
                }
                out.push(json_number(quantity.to_engine(x)));
            }
            Ok(Value::Array(out))
        }
        Kind::Errors => crate::machine::errors::read_values(v, path),
        Kind::ErrorNames => crate::machine::errors::read_names(v, path),
        Kind::Motions => crate::machine::motions::read_motions(v, path),
    }
}

/// A field as the page and scripts see it (the schema the binding exports): the nested objects
/// are flattened into dotted paths.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify), tsify(missing_as_null))]
#[serde(rename_all = "camelCase")]
pub struct FieldInfo {
    /// Dotted path in the input object, e.g. `"setup.zoneSize"`.
    pub path: String,
    /// What the page writes next to it.
    pub label: String,
    /// Plain-language help.
    pub help: String,
    /// `"number"`, `"count"`, `"flag"`, `"choice"`, `"text"`, `"numberList"`, `"errors"` or
    /// `"errorNames"`.
    pub kind: String,
    /// For numbers: what it is (decides the unit shown).
    pub quantity: Option<Quantity>,
    /// API unit: `"mm"`, `"deg"` or `""`.
    pub unit: String,
    /// Smallest accepted value (API units), for numbers and counts.
    pub min: Option<f64>,
    /// Largest accepted value (API units), for numbers, counts and texts (bytes).
    pub max: Option<f64>,
    /// `min` itself is refused.
    pub exclusive_min: bool,
    /// For lists of numbers: fewest and most values, and whether zero is refused.
    pub list: Option<ListInfo>,
    /// The default: a number (API units), a flag, a string, or null.
    #[cfg_attr(feature = "ts", tsify(type = "number | boolean | string | null"))]
    pub default: Value,
    /// It may be left out.
    pub optional: bool,
    /// The options of a choice.
    pub choices: Vec<Choice>,
    /// The page's group.
    pub group: String,
    /// The label of the object it sits in (`"Start"` for `start.k`), or `""`.
    pub section: String,
    /// The machine kinds it applies to; empty: every kind.
    pub kinds: Vec<String>,
    /// The page shows it (false: derived by the page from other inputs).
    pub shown: bool,
}

/// The limits of a list of numbers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "ts", derive(tsify::Tsify))]
#[serde(rename_all = "camelCase")]
pub struct ListInfo {
    /// Fewest values.
    pub min_len: usize,
    /// Most values.
    pub max_len: usize,
    /// Zero is refused.
    pub nonzero: bool,
}

/// The flattened schema of a field table (module docs), paths under `path`.
pub fn describe(fields: &[Field], path: &str) -> Vec<FieldInfo> {
    describe_in(fields, path, "", true)
}

fn describe_in(fields: &[Field], path: &str, section: &str, shown: bool) -> Vec<FieldInfo> {
    let mut out = Vec::new();
    for f in fields {
        let p = join(path, f.key);
        if let Kind::Object(inner) = f.kind {
            out.extend(describe_in(inner, &p, f.label, shown && f.shown));
            continue;
        }
        let (kind, quantity, min, max, exclusive_min, choices) = match f.kind {
            Kind::Number {
                quantity,
                min,
                max,
                exclusive_min,
            } => (
                "number",
                Some(quantity),
                Some(min),
                Some(max),
                exclusive_min,
                vec![],
            ),
            Kind::Count { min, max } => (
                "count",
                Some(Quantity::Count),
                Some(min as f64),
                Some(max as f64),
                false,
                vec![],
            ),
            Kind::Flag => ("flag", None, None, None, false, vec![]),
            Kind::Choice(c) => ("choice", None, None, None, false, c.to_vec()),
            Kind::Text { max_len } => ("text", None, None, Some(max_len as f64), false, vec![]),
            Kind::Errors => ("errors", None, None, None, false, vec![]),
            Kind::ErrorNames => ("errorNames", None, None, None, false, vec![]),
            Kind::Motions => ("motions", None, None, None, false, vec![]),
            Kind::NumberList {
                quantity, min, max, ..
            } => (
                "numberList",
                Some(quantity),
                Some(min),
                Some(max),
                false,
                vec![],
            ),
            Kind::Object(_) => ("object", None, None, None, false, vec![]),
        };
        out.push(FieldInfo {
            path: p,
            label: f.label.to_string(),
            help: f.help.to_string(),
            kind: kind.to_string(),
            quantity,
            unit: quantity.map_or("", Quantity::api_unit).to_string(),
            min,
            max,
            exclusive_min,
            list: match f.kind {
                Kind::NumberList {
                    min_len,
                    max_len,
                    nonzero,
                    ..
                } => Some(ListInfo {
                    min_len,
                    max_len,
                    nonzero,
                }),
                _ => None,
            },
            default: match f.default {
                DefaultValue::Num(v) => json_number(v),
                DefaultValue::Flag(b) => Value::Bool(b),
                DefaultValue::Str(s) => Value::String(s.to_string()),
                DefaultValue::None | DefaultValue::Empty => Value::Null,
            },
            optional: f.optional,
            choices,
            group: f.group.to_string(),
            section: section.to_string(),
            kinds: f.kinds.iter().map(|k| k.to_string()).collect(),
            shown: shown && f.shown,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    crate::choices! {
        /// A test choice.
        pub enum Colour {
            /// Red.
            Red = "red" { label: "Red", help: "" },
            /// Green.
            Green = "green" { label: "Green", help: "" },
        }
    }

    crate::inputs! {
        /// Test inputs.
        pub struct Inner {
            /// A small angle.
            pub tilt: f64 = "tilt" optional {
                label: "Tilt", kind: number(Quantity::SmallAngle, -1.0, 1.0), default: DefaultValue::Num(0.5),
            },
        }
    }

    crate::inputs! {
        /// Test inputs.
        pub struct Outer {
            /// A positive length.
            pub size: f64 = "size" optional {
                label: "Size", kind: positive(Quantity::Length, 100.0), default: DefaultValue::Num(16.0),
            },
            /// A count.
            pub n: usize = "n" { label: "Points", kind: Kind::Count { min: 2, max: 9 }, },
            /// A choice.
            pub colour: Colour = "colour" optional {
                label: "Colour", kind: Kind::Choice(Colour::CHOICES), default: DefaultValue::Str("green"),
            },
            /// Nested.
            pub inner: Inner = "inner" optional { label: "Inner", kind: Kind::Object(Inner::FIELDS), default: DefaultValue::Empty, },
            /// An optional number without a default.
            pub extra: Option<f64> = "extra" optional { label: "Extra", kind: number(Quantity::Length, 0.0, 1.0), },
        }
    }

    #[test]
    fn defaults_units_and_nesting() {
        let o: Outer = Outer::from_value(&json!({ "n": 3 }), "").unwrap();
        assert_eq!(o.size, 16.0);
        assert_eq!(o.n, 3);
        assert_eq!(o.colour, Colour::Green);
        assert_eq!(Colour::Red.value(), "red");
        assert!((o.inner.tilt - 0.5f64.to_radians()).abs() < 1e-18);
        assert_eq!(o.extra, None);
        let o: Outer = Outer::from_value(
            &json!({ "n": 3, "inner": { "tilt": -1 }, "extra": 0.5 }),
            "",
        )
        .unwrap();
        assert!((o.inner.tilt + 1f64.to_radians()).abs() < 1e-18);
        assert_eq!(o.extra, Some(0.5));
    }

    #[test]
    fn messages_name_the_path() {
        let msg = |v: Value| Outer::from_value(&v, "case").unwrap_err().to_string();
        assert_eq!(msg(json!({})), "case.n: is required (Points)");
        assert!(msg(json!({ "n": 3, "sise": 1 })).starts_with("case.sise: unknown input"));
        assert!(msg(json!({ "n": 3, "sise": 1 })).contains("Did you mean \"size\"?"));
        assert!(msg(json!({ "n": 3, "inner": { "tlt": 1 } })).starts_with("case.inner.tlt: "));
        assert!(
            msg(json!({ "n": 3, "size": 0 })).starts_with("case.size: must be greater than 0 mm")
        );
        assert!(msg(json!({ "n": 3.5 })).starts_with("case.n: must be a whole number"));
        assert!(msg(json!({ "n": 3, "inner": { "tilt": 2 } }))
            .starts_with("case.inner.tilt: must be between -1 degrees and 1 degrees, got 2"));
        assert!(msg(json!({ "n": 3, "colour": "gren" })).contains("Did you mean \"green\"?"));
        assert!(msg(json!({ "n": "3" })).starts_with("case.n: expected a whole number, got \"3\""));
        assert!(msg(json!(5)).starts_with("case: expected an object"));
    }

    #[test]
    fn the_schema_flattens_nested_fields() {
        let d = describe(Outer::FIELDS, "");
        let paths: Vec<&str> = d.iter().map(|f| f.path.as_str()).collect();
        assert_eq!(paths, ["size", "n", "colour", "inner.tilt", "extra"]);
        assert_eq!(d[3].unit, "deg");
        assert_eq!(d[0].default, json!(16.0));
        assert!(d[0].exclusive_min);
    }

    #[test]
    fn closest_key() {
        assert_eq!(closest("zonesize", &["zoneSize", "pick"]), Some("zoneSize"));
        assert_eq!(closest("xyz", &["zoneSize", "pick"]), None);
    }
}
