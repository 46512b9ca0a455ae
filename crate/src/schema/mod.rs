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
//!
//! # Layers
//! `vocabulary` is plain data ([`Quantity`], [`Field`], [`Kind`], [`Choice`]); `read` and
//! `describe` sit on it. The schema names no study and not the machine: a kind only a module
//! above knows (the machine's errors and error motions) is a [`Kind::Custom`] carrying that
//! module's reader (`crate/tests/lib/module_graph.rs` checks the module graph).

mod describe;
mod read;
mod vocabulary;

pub use describe::{describe, FieldInfo, ListInfo};
pub use read::{check_number, closest, join, read, read_object, read_split, Inputs};
pub use vocabulary::{
    number, optional, positive, Choice, Custom, DefaultValue, Field, Kind, Quantity,
};

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

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::{json, Value};

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
