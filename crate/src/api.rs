//! The engine's API: every export declared once ([`for_each_export!`]), and the conventions its
//! results cross the JSON/JavaScript edge with.
//!
//! An export is a name, an input type, a result type and the engine function between them
//! (`fn(&Input) -> Result<Output>`). From that one line:
//! * the binding crate (`wasm/`) writes the `#[wasm_bindgen]` function and its `schema()` entry;
//! * [`call`] runs the same export natively on JSON (benches, tests, scripts);
//! * tsify writes the TypeScript declarations of the input and result types (feature `ts`).
//!
//! Result types are the engine's own structs, `Serialize` (and `Tsify` behind `ts`). The edge's
//! conventions are applied by serde attributes on their fields:
//! * **angles** are radians in Rust and **degrees** at the edge: `#[serde(serialize_with =
//!   "crate::api::degrees")]` (also [`degrees_series`], [`degrees_opt`], [`degrees_vec`]); their
//!   doc comments say "degrees" (a test reads the `.d.ts`: no result field is documented in
//!   radians);
//! * **long series** of numbers cross as a `Float64Array` in JavaScript ([`series`],
//!   [`series3`]; `#[cfg_attr(feature = "ts", tsify(type = "Float64Array"))]`), and as arrays
//!   in JSON;
//! * field names are camelCase (`#[serde(rename_all = "camelCase")]`), `None` is `null`.

use crate::machine::errors::{ErrorDef, TABLE};
use crate::machine::motions::MOTIONS;
use crate::machine::Machine;
use crate::schema::{describe, FieldInfo, Inputs};
use crate::Result;
use serde::ser::{SerializeSeq, SerializeTuple};
use serde::{Serialize, Serializer};
use serde_json::Value;
use std::collections::BTreeMap;

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

/// Every input the page renders and the engine reads (see `schema`).
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(
    feature = "ts",
    derive(tsify::Tsify),
    tsify(missing_as_null, hashmap_as_object)
)]
#[serde(rename_all = "camelCase")]
pub struct Schema {
    /// The machine's fields, paths under `machine.`.
    pub machine: Vec<FieldInfo>,
    /// The error table: every ISO 230-1 location error a machine can have.
    pub errors: Vec<ErrorDef>,
    /// The error motions of every axis (ISO 230-1 `E_XX` … `E_CC`), functions of its position.
    pub motions: Vec<ErrorDef>,
    /// Per export, every field of its input object (the machine's included).
    pub exports: BTreeMap<String, Vec<FieldInfo>>,
}

/// The schema of every input: the machine's fields, the error table and each export's fields
/// (the declared ones and `extra`, the binding's hand-written ones), with labels, plain-language
/// help, units (mm, deg), limits and defaults.
pub fn schema(extra: Vec<(&str, Vec<FieldInfo>)>) -> Schema {
    Schema {
        machine: describe(Machine::FIELDS, "machine"),
        errors: TABLE.to_vec(),
        motions: MOTIONS.to_vec(),
        exports: export_fields()
            .into_iter()
            .chain(extra)
            .map(|(n, f)| (n.to_string(), f))
            .collect(),
    }
}

/// Calls `f` on `S`'s serializer with `values` as a `Float64Array` when the serializer is
/// serde-wasm-bindgen's (feature `wasm` on wasm32), else as a sequence of numbers.
fn float64<S: Serializer>(values: &[f64], s: S) -> std::result::Result<S::Ok, S::Error> {
    #[cfg(all(feature = "wasm", target_arch = "wasm32"))]
    {
        serde_wasm_bindgen::preserve::serialize(&js_sys::Float64Array::from(values), s)
    }
    #[cfg(not(all(feature = "wasm", target_arch = "wasm32")))]
    {
        let mut seq = s.serialize_seq(Some(values.len()))?;
        for v in values {
            seq.serialize_element(v)?;
        }
        seq.end()
    }
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

/// Every export, declared once, handed to the macro `$then` as rows of
/// `$(#[doc = "…"])* jsName(Input as "TS input") -> "TS output" = engine::function;`
/// (`Input` implements [`ApiInput`]; the function is `fn(&Input) -> Result<impl Serialize>`).
/// The docs are `#[doc = "…"]` lines, not `///`: wasm-bindgen copies a `///` passed through a
/// macro into the `.d.ts` with its raw-string quotes.
#[macro_export]
macro_rules! for_each_export {
    ($then:ident) => {
        $then! {
            // machine
            #[doc = "The twelve rotary-axis types with their group and axes."]
            rotaryTypes(() as "undefined | void") -> "RotaryTypeInfo[]" = $crate::machine::api::rotary_types;
            #[doc = "The machine drawn from its chain at the commands `k`, `m` (degrees), and its axes in"]
            #[doc = "words: so that the user can see that the machine entered is theirs."]
            machineSchematic($crate::machine::SchematicInput as "SchematicInput")
                -> "MachineDrawing" = $crate::machine::api::drawing;
            #[doc = "The tool direction `(i, j, k)` in workpiece coordinates at the commands `k`, `m`"]
            #[doc = "(degrees), from the machine's nominal chain."]
            toolVector($crate::machine::ToolVectorInput as "ToolVectorInput")
                -> "[number, number, number]" = $crate::machine::api::tool_vector;
            #[doc = "The rotary commands that give a tool direction on this machine: every solution"]
            #[doc = "(degrees), whether it is within the travel, and `chosen`, the index of the one the"]
            #[doc = "rule picks (nearest `previous` by default; null when none is within the travel,"]
            #[doc = "with `unreachable` saying why)."]
            machineInverse($crate::machine::InverseInput as "InverseInput")
                -> "Orientations" = $crate::machine::api::inverse;
            // volumetric
            #[doc = "The tool tip's deviation over a plane of the working volume for all the machine's"]
            #[doc = "errors and error motions, its worst point and the error budget."]
            volumetricMap($crate::volumetric::VolumetricInput as "VolumetricInput")
                -> "VolumetricMap" = $crate::volumetric::map;
            #[doc = "Tan & Lim's RRTTT model (their loop and their printed first-order formulas) beside"]
            #[doc = "the machine's exact model at one pose of their machine."]
            volumetricPaper($crate::volumetric::VolumetricPaperInput as "VolumetricPaperInput")
                -> "PaperComparison" = $crate::volumetric::compare_input;
            #[doc = "Reads a measured table of one error motion from CSV (`{ name: \"E_XX\", text }`):"]
            #[doc = "positions in mm or degrees, values in mm or degrees, converted from the units in"]
            #[doc = "the header. Errors name the line: `csv: line 7: …`. The result's `position` and"]
            #[doc = "`value` go into `machine.motions[name]` as they are."]
            volumetricReadTable($crate::volumetric::MotionTableInput as "MotionTableInput")
                -> "CsvTable" = $crate::volumetric::read_table;
            // probe
            #[doc = "The sphere test of the rotary axes: the simple layout and the designed poses (the"]
            #[doc = "smallest scaled singular value maximised), their expected centres, CSV and NC blocks,"]
            #[doc = "what a single sphere cannot see and what a second sphere position would add."]
            probeDesign(($crate::probe::ProbeInput, $crate::probe::design::ProbeDesignInput)
                as "ProbeInput & ProbeDesignInput") -> "ProbeDesign" = $crate::probe::api::design;
            #[doc = "The sphere's centre at given poses (degrees) as the control expects it and as the"]
            #[doc = "probe measures it on the machine with its errors (linear-axis positions, mm), and"]
            #[doc = "the sensitivities of the centres to each error (per mm, per degree)."]
            probeSimulate(($crate::probe::ProbeInput, $crate::probe::api::ProbeSimulateInput)
                as "ProbeInput & ProbeSimulateInput") -> "ProbeSimulation" = $crate::probe::api::simulate;
            #[doc = "Reads measured sphere centres from CSV (one line per pose: K, M, X, Y, Z, units in"]
            #[doc = "the header); errors name the line: `csv: line 7: …`."]
            probeReadCsv($crate::probe::api::ProbeCsvInput as "ProbeCsvInput")
                -> "Measurements" = $crate::probe::api::read_csv;
            #[doc = "Identifies the rotary axes' location errors from measured sphere centres: values,"]
            #[doc = "intervals, Holm decisions, the spread before and after, the correction in words and"]
            #[doc = "`errors` to put into `machine.errors`."]
            probeIdentify(($crate::probe::ProbeInput, $crate::probe::fit::ProbeIdentifyInput)
                as "ProbeInput & ProbeIdentifyInput") -> "ProbeIdentification" = $crate::probe::api::identify;
        }
    };
}

macro_rules! native_call {
    ($( $(#[doc = $doc:tt])* $js:ident ($input:ty as $ts_in:tt) -> $ts_out:tt = $f:path; )*) => {
        /// Runs the export `name` natively on a JSON input and returns its result as JSON
        /// (angles in degrees, series as arrays): the same declaration the binding exports.
        pub fn call(name: &str, input: &Value) -> Result<Value> {
            match name {
                $(stringify!($js) => {
                    let i = <$input as ApiInput>::read(input)?;
                    let out = $f(&i)?;
                    serde_json::to_value(&out)
                        .map_err(|e| crate::Error::field(name, format!("cannot be written ({e})")))
                })*
                _ => Err(crate::Error::field(name, "no such export")),
            }
        }

        /// The names of every declared export, in declaration order.
        pub const EXPORTS: &[&str] = &[$(stringify!($js)),*];

        /// Each declared export's input fields, for `schema()`.
        pub fn export_fields() -> Vec<(&'static str, Vec<FieldInfo>)> {
            vec![$((stringify!($js), <$input as ApiInput>::fields())),*]
        }
    };
}

for_each_export!(native_call);
