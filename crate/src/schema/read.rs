//! The reader: a JSON value checked against a field table and converted to engine units
//! (module docs of [`crate::schema`]).

use serde::de::DeserializeOwned;
use serde_json::{Map, Value};

use super::vocabulary::{DefaultValue, Field, Kind, Quantity};
use crate::error::{Error, Result};

/// A struct of inputs declared with [`inputs!`](crate::inputs): its field table.
pub trait Inputs: DeserializeOwned {
    /// The fields, in the order the page shows them.
    const FIELDS: &'static [Field];

    /// Reads the struct from a JSON value (module docs); `path` prefixes every message.
    fn from_value(value: &Value, path: &str) -> Result<Self> {
        read(Self::FIELDS, value, path)
    }
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
        (Kind::Custom(c), DefaultValue::Empty) if c.list => Value::Array(Vec::new()),
        (_, DefaultValue::Empty) => Value::Object(Map::new()),
    })
}

/// A number as JSON (`null` when not finite).
pub(super) fn json_number(v: f64) -> Value {
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
        Kind::Custom(custom) => (custom.read)(v, path),
    }
}
