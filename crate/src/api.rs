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
            // cubic and S-shape
            #[doc = "Zone heights and tilts (exact and first-order), sensitivities of every error of the"]
            #[doc = "machine on every zone, the exact effect of each error alone, and what the test cannot see."]
            cubicTest($crate::cubic::CubicInput as "CubicInput")
                -> "CubicResult" = $crate::cubic::results::test;
            #[doc = "The simulated machined face (Fig 16(b)): ball-end zig-zag passes, scallops included, on an"]
            #[doc = "`nx × ny` grid (`ny` automatic when left out), with each zone's average height."]
            cubicHeightMap(($crate::cubic::CubicInput, $crate::cubic::CubicGrid) as "CubicInput & CubicGrid")
                -> "HeightMap" = $crate::cubic::results::map;
            #[doc = "Identification of the machine's errors from measured zone heights (and slopes) of a cubic"]
            #[doc = "test piece, the paper's layout or a designed one (`csv`, see `fiveaxis::cubic::identify`)."]
            cubicIdentify(($crate::cubic::CubicInput, $crate::cubic::identify::CubicIdentifyInput) as "CubicInput & CubicIdentifyInput")
                -> "CubicIdentifyResult" = $crate::cubic::results::identify;
            #[doc = "The test designer: the zones' tool vectors (and optionally a second set-up) that make every"]
            #[doc = "error a face of this kind can reveal identifiable, beside the paper's layout."]
            cubicDesign(($crate::cubic::CubicInput, $crate::cubic::design::CubicDesignInput) as "CubicInput & CubicDesignInput")
                -> "CubicDesignResult" = $crate::cubic::results::design;
            #[doc = "The part for a 3D view: both surfaces on an `nu × nv` grid (default 131 × 7) and the 100"]
            #[doc = "measurement points, in the part's own frame (z up from its base)."]
            sshapePart($crate::sshape::study::SShapePartInput as "SShapePartInput | undefined")
                -> "SShapePartResult" = $crate::sshape::results::part;
            #[doc = "The overcut maps of both surfaces (eq 6 and the exact gouge) on an `nu × nv` grid."]
            sshapeOvercut($crate::sshape::study::SShapeOvercutInput as "SShapeOvercutInput")
                -> "SShapeOvercutResult" = $crate::sshape::results::overcut;
            #[doc = "The machining defect at the 100 points for the machine's errors (eq 14) and a tool-radius"]
            #[doc = "error, with the sensitivities of Fig 19 and the machine poses."]
            sshapeDefects(($crate::sshape::study::SShapeCase, $crate::sshape::study::SShapeDefectsInput) as "SShapeCase & SShapeDefectsInput")
                -> "SShapeDefectsResult" = $crate::sshape::results::defects;
            #[doc = "Identification of the machine's errors (all, or `parameters`) and the tool-radius error from"]
            #[doc = "a measurement CSV."]
            sshapeIdentify(($crate::sshape::study::SShapeCase, $crate::sshape::study::SShapeIdentifyInput) as "SShapeCase & SShapeIdentifyInput")
                -> "SShapeIdentifyResult" = $crate::sshape::results::identify;
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
