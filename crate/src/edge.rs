//! The conventions of the engine's JSON/JavaScript edge, the ground floor every study's inputs
//! and results use ([`crate::api`] declares the exports above them):
//! * an export's input is read by [`ApiInput`] (the `schema` reader, then [`Checked::check`]);
//! * results are the studies' own structs, `Serialize` (and `Tsify` behind the feature `ts`),
//!   with serde attributes on their fields: an angle held in radians is written in **degrees**
//!   (`#[serde(serialize_with = "crate::edge::degrees")]`, also [`degrees_opt`], [`degrees_vec`],
//!   [`degrees_series`]; its doc comment says "degrees": a test reads the `.d.ts` and fails on a
//!   field documented in radians); a long series crosses as a **`Float64Array`** in JavaScript
//!   ([`series`], [`series3`]; `#[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]`)
//!   and as an array in JSON; keys are camelCase; `None` is `null`.

use crate::schema::{describe, FieldInfo, Inputs};
use crate::Result;
use serde::ser::{SerializeSeq, SerializeTuple};
use serde::Serializer;
use serde_json::Value;

/// The input of an export: read from one JSON object, with the path of any fault in the message.
pub trait ApiInput: Sized {
    /// Reads the input (`schema::read`: unknown keys refused, ranges checked, degrees to
    /// radians), then [`Checked::check`]s it.
    fn read(value: &Value) -> Result<Self>;
    /// Its fields, for `schema()`.
    fn fields() -> Vec<FieldInfo>;
}

/// An input struct an export takes, with what is checked once its fields are read (the machine
/// as a whole, ranges that depend on each other). Most check nothing more: `impl Checked for
/// X {}`.
pub trait Checked: Inputs {
    /// Checks the input as a whole; the message names the field at fault.
    fn check(&self) -> Result<()> {
        Ok(())
    }
}

impl<T: Checked> ApiInput for T {
    fn read(value: &Value) -> Result<Self> {
        let t = T::from_value(value, "")?;
        t.check()?;
        Ok(t)
    }
    fn fields() -> Vec<FieldInfo> {
        describe(T::FIELDS, "")
    }
}

/// Two input structs read from one object (a shared case plus the export's own fields):
/// `schema::read_split`, then both checked.
impl<A: Checked, B: Checked> ApiInput for (A, B) {
    fn read(value: &Value) -> Result<Self> {
        let (a, b): (A, B) = crate::schema::read_split(value, "")?;
        a.check()?;
        b.check()?;
        Ok((a, b))
    }
    fn fields() -> Vec<FieldInfo> {
        let mut v = describe(A::FIELDS, "");
        v.extend(describe(B::FIELDS, ""));
        v
    }
}

/// An export that takes no input (`undefined` in JavaScript).
impl ApiInput for () {
    fn read(value: &Value) -> Result<Self> {
        match value {
            Value::Null => Ok(()),
            Value::Object(m) if m.is_empty() => Ok(()),
            Value::Object(m) => Err(crate::Error::field(
                m.keys().next().map_or("input", |k| k.as_str()),
                "this export takes no input",
            )),
            _ => Err(crate::Error::field("input", "this export takes no input")),
        }
    }
    fn fields() -> Vec<FieldInfo> {
        Vec::new()
    }
}

/// The name a series is written under (`serialize_newtype_struct`): the binding's writer makes
/// it a `Float64Array`; any other serializer (`serde_json`) writes the list of numbers.
pub const SERIES: &str = "Float64Array";

/// `values` as a series ([`SERIES`]).
fn float64<S: Serializer>(values: &[f64], s: S) -> std::result::Result<S::Ok, S::Error> {
    s.serialize_newtype_struct(SERIES, values)
}

/// A long series of numbers (mm, or as documented): a `Float64Array` in JavaScript.
pub fn series<S: Serializer>(values: &[f64], s: S) -> std::result::Result<S::Ok, S::Error> {
    float64(values, s)
}

/// Three series (X, Y, Z): three `Float64Array`s.
pub fn series3<S: Serializer>(
    values: &[Vec<f64>; 3],
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    struct One<'a>(&'a [f64]);
    impl serde::Serialize for One<'_> {
        fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
            float64(self.0, s)
        }
    }
    let mut t = s.serialize_tuple(3)?;
    for v in values {
        t.serialize_element(&One(v))?;
    }
    t.end()
}

/// An angle held in radians, written in degrees.
pub fn degrees<S: Serializer>(radians: &f64, s: S) -> std::result::Result<S::Ok, S::Error> {
    s.serialize_f64(radians.to_degrees())
}

/// An optional angle held in radians, written in degrees (`null` when absent).
pub fn degrees_opt<S: Serializer>(
    radians: &Option<f64>,
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    match radians {
        Some(r) => s.serialize_f64(r.to_degrees()),
        None => s.serialize_none(),
    }
}

/// A short list of angles held in radians, written in degrees as a plain array.
pub fn degrees_vec<S: Serializer>(radians: &[f64], s: S) -> std::result::Result<S::Ok, S::Error> {
    let mut seq = s.serialize_seq(Some(radians.len()))?;
    for r in radians {
        seq.serialize_element(&r.to_degrees())?;
    }
    seq.end()
}

/// A long series of angles held in radians, written in degrees (`Float64Array`).
pub fn degrees_series<S: Serializer>(
    radians: &[f64],
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    let d: Vec<f64> = radians.iter().map(|r| r.to_degrees()).collect();
    float64(&d, s)
}
