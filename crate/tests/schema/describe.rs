//! The schema the page renders its forms from (`fiveaxis::api::schema`, flattened by
//! `schema::describe`): a field inside an object the page does not show is not shown either,
//! whatever its own declaration says, and the fields of a shown object are; a list's items are
//! described with paths relative to the item.
// Found by cargo-mutants: `shown && f.shown` as `||` in `describe_in` changed no outcome of the
// tests before this file (no declaration of the engine hides an object around a shown field).
#![allow(clippy::unwrap_used)]

use fiveaxis::api::schema;
use fiveaxis::schema::{describe, DefaultValue, Field, FieldInfo, Kind, Quantity};

fn field<'a>(fields: &'a [FieldInfo], path: &str) -> &'a FieldInfo {
    fields
        .iter()
        .find(|f| f.path == path)
        .unwrap_or_else(|| panic!("no field {path}"))
}

#[test]
fn the_fields_of_a_hidden_object_are_hidden_and_those_of_a_shown_one_shown() {
    let s = schema(Vec::new());
    // machineInverse's `previous` (the pose before, which the page fills in itself) is declared
    // not shown; its `k` and `m` are declared as any angle, shown.
    let inverse = &s.exports["machineInverse"];
    for p in ["previous.k", "previous.m"] {
        let f = field(inverse, p);
        assert!(!f.shown, "{p} is inside a hidden object");
        assert_eq!(f.section, "Previous pose");
    }
    // nonlinearMove's `start` is shown, and so are its fields.
    let nl = &s.exports["nonlinearMove"];
    assert!(field(nl, "start.k").shown);
    assert!(field(nl, "end.m").shown);
}

/// A number field `key`, shown or not.
const fn number(key: &'static str, shown: bool) -> Field {
    Field {
        key,
        label: "a number",
        help: "",
        kind: Kind::Number {
            quantity: Quantity::Length,
            min: 0.0,
            max: 1.0,
            exclusive_min: false,
        },
        default: DefaultValue::Num(0.5),
        optional: true,
        group: "",
        kinds: &[],
        shown,
    }
}

const INNER: [Field; 2] = [number("a", true), number("b", false)];

/// An object field `key` holding INNER, shown or not.
const fn object(key: &'static str, shown: bool) -> Field {
    Field {
        key,
        label: "An object",
        help: "",
        kind: Kind::Object(&INNER),
        default: DefaultValue::Empty,
        optional: true,
        group: "",
        kinds: &[],
        shown,
    }
}

#[test]
fn a_field_is_shown_only_when_it_and_every_object_around_it_are() {
    // (The engine's own declarations hide no object around a shown field, so a table is made.)
    let table = [object("hidden", false), object("open", true)];
    let f = describe(&table, "");
    let shown = |p: &str| field(&f, p).shown;
    assert!(!shown("hidden.a"), "a shown field in a hidden object");
    assert!(!shown("hidden.b"));
    assert!(shown("open.a"));
    assert!(!shown("open.b"), "a hidden field in a shown object");
    assert_eq!(field(&f, "open.a").section, "An object");
}

#[test]
fn a_lists_items_are_described_relative_to_the_item() {
    let s = schema(Vec::new());
    let tests = &s.lists["ballbarTests"];
    for p in [
        "name",
        "axis",
        "ball.x",
        "ball.height",
        "length",
        "direction",
        "from",
        "step",
    ] {
        assert!(field(tests, p).shown, "{p}");
    }
    assert_eq!(field(tests, "ball.x").section, "Table ball");
}

#[test]
fn a_list_of_numbers_says_how_many_values_it_takes() {
    let s = schema(Vec::new());
    // machineInverse's tool vector: three numbers, zero allowed.
    let v = field(&s.exports["machineInverse"], "vector");
    let list = v.list.unwrap();
    assert_eq!((list.min_len, list.max_len, list.nonzero), (3, 3, false));
    // A plain number has none.
    assert!(field(&s.exports["nonlinearMove"], "length").list.is_none());
}

// Found by cargo-mutants: `PartialEq for Custom` as `!=` or `false`, and its `Debug` writing
// nothing, changed no outcome (no test compared two kinds declared above the schema).
#[test]
fn kinds_declared_above_the_schema_are_the_same_when_their_names_are_and_print_their_name() {
    use fiveaxis::machine::errors::{NAMES, VALUES};
    use fiveaxis::schema::Custom;
    assert_eq!(VALUES, VALUES);
    assert_ne!(VALUES, NAMES);
    // Another declaration of the same name is the same kind, whatever its reader.
    static AGAIN: Custom = Custom {
        name: "errors",
        read: |v, _| Ok(v.clone()),
        list: true,
    };
    assert_eq!(VALUES, Kind::Custom(&AGAIN));
    let shown = format!("{VALUES:?}");
    assert!(shown.contains("\"errors\""), "{shown}");
}
