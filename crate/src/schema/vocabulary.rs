//! The ground floor: what a field is ([`Field`], [`Kind`], [`Quantity`], [`Choice`]) as plain
//! data, with no reader in it.

use serde::Serialize;
use serde_json::Value;

use crate::error::Result;

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
    /// A kind the schema does not know, read by a reader its owner supplies (the machine's
    /// errors, error names and error motions).
    Custom(&'static Custom),
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

/// A kind declared above the schema: its name in the exported schema and its reader.
#[derive(Clone, Copy)]
pub struct Custom {
    /// The kind in the exported schema, e.g. `"errors"`.
    pub name: &'static str,
    /// Reads a given value at `path`, checked and in engine units.
    pub read: fn(&Value, &str) -> Result<Value>,
    /// Left out with [`DefaultValue::Empty`], it is `[]` (else `{}`).
    pub list: bool,
}

impl PartialEq for Custom {
    /// Two custom kinds are the same when their names are.
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl std::fmt::Debug for Custom {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Custom").field("name", &self.name).finish()
    }
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
