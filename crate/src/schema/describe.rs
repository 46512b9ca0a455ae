//! The schema the binding exports: a field table flattened into dotted paths.

use serde::Serialize;
use serde_json::Value;

use super::read::{join, json_number};
use super::vocabulary::{Choice, DefaultValue, Field, Kind, Quantity};

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
    /// `"number"`, `"count"`, `"flag"`, `"choice"`, `"text"`, `"numberList"`, or a custom kind's
    /// name (`"errors"`, `"errorNames"`, `"motions"`).
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
            Kind::Custom(c) => (c.name, None, None, None, false, vec![]),
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
