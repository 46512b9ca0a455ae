//! The binding's result writer (`output`, a tape read back by one JavaScript function) against
//! `serde_json`'s writer of the same value: every shape serde gives a result (structs with
//! fields left out, `None`, each kind of enum variant, maps with text and number keys, tuples,
//! texts with characters outside ASCII and of two UTF-16 units, the same field names again and
//! again) must arrive as the value `serde_json` writes, and each series as a `Float64Array` of
//! the same numbers. As WebAssembly in headless Node.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use fiveaxis_wasm::output;
use js_sys::{Array, Float64Array, Object, Reflect};
use serde::Serialize;
use serde_json::{Map, Value};
use std::collections::BTreeMap;
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::wasm_bindgen_test;

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
enum Kind {
    Plain,
    Newtype(f64),
    Tuple(u8, String),
    Shape { side_mm: f64, name: &'static str },
}

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct Item {
    name: String,
    value: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    left_out: Option<u32>,
    kind: Kind,
    #[serde(serialize_with = "fiveaxis::edge::series")]
    series: Vec<f64>,
}

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct Sample {
    items: Vec<Item>,
    by_name: BTreeMap<String, i64>,
    by_number: BTreeMap<u32, bool>,
    pair: (u64, Option<String>, ()),
    words: Vec<&'static str>,
    #[serde(serialize_with = "fiveaxis::edge::series3")]
    xyz: [Vec<f64>; 3],
    empty: Vec<Item>,
}

fn sample() -> Sample {
    let item = |i: usize, kind: Kind| Item {
        name: format!("E_X0{i} = −{i}.5 µm ± 0.2″"),
        value: (i % 2 == 0).then_some(i as f64 * 0.25),
        left_out: (i == 1).then_some(7),
        kind,
        series: (0..i * 3).map(|k| k as f64 / 3.0 - 1e-9).collect(),
    };
    Sample {
        items: vec![
            item(0, Kind::Plain),
            item(1, Kind::Newtype(-0.5)),
            item(2, Kind::Tuple(3, "Ω 𝜀 ✓".into())),
            item(
                3,
                Kind::Shape {
                    side_mm: 50.0,
                    name: "cube",
                },
            ),
        ],
        by_name: [("µ".to_string(), -3), ("a".to_string(), 1 << 40)].into(),
        by_number: [(2, true), (10, false)].into(),
        pair: (u64::from(u32::MAX) + 1, None, ()),
        words: vec!["", "𝜀 then text", "plain"],
        xyz: [vec![1.0, f64::MAX], vec![], vec![f64::MIN_POSITIVE]],
        empty: vec![],
    }
}

/// A JavaScript value as JSON, each `Float64Array` as a list (its path kept in `series`).
fn back(v: &JsValue, path: &str, series: &mut Vec<String>) -> Value {
    if v.is_null() {
        Value::Null
    } else if let Some(b) = v.as_bool() {
        Value::Bool(b)
    } else if let Some(x) = v.as_f64() {
        serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number)
    } else if let Some(s) = v.as_string() {
        Value::String(s)
    } else if let Some(a) = v.dyn_ref::<Float64Array>() {
        series.push(path.to_string());
        a.to_vec().into_iter().map(Value::from).collect()
    } else if Array::is_array(v) {
        let a: &Array = v.unchecked_ref();
        a.iter()
            .enumerate()
            .map(|(i, x)| back(&x, &format!("{path}[{i}]"), series))
            .collect()
    } else {
        let o: &Object = v.unchecked_ref();
        let mut m = Map::new();
        for k in Object::keys(o).iter() {
            let key = k.as_string().unwrap();
            let x = Reflect::get(o, &k).unwrap();
            m.insert(key.clone(), back(&x, &format!("{path}.{key}"), series));
        }
        Value::Object(m)
    }
}

/// Every number as a float: JavaScript has no integers, `serde_json` keeps them apart.
fn floats(v: Value) -> Value {
    match v {
        Value::Number(n) => n.as_f64().map_or(Value::Null, Value::from),
        Value::Array(a) => a.into_iter().map(floats).collect(),
        Value::Object(m) => Value::Object(m.into_iter().map(|(k, v)| (k, floats(v))).collect()),
        other => other,
    }
}

#[wasm_bindgen_test]
fn every_shape_of_a_result_arrives_as_serde_json_writes_it_with_series_as_float64_arrays() {
    let s = sample();
    let expected = floats(serde_json::to_value(&s).unwrap());
    let mut series = Vec::new();
    let got = back(&output(&s).unwrap(), "", &mut series);
    assert_eq!(got, expected);
    assert_eq!(
        series,
        [
            ".items[0].series",
            ".items[1].series",
            ".items[2].series",
            ".items[3].series",
            ".xyz[0]",
            ".xyz[1]",
            ".xyz[2]"
        ]
    );
    // The text with characters of two UTF-16 units, and what follows it, cut where it ends.
    assert_eq!(got["words"][1], "𝜀 then text");
    assert_eq!(got["items"][2]["kind"]["tuple"][1], "Ω 𝜀 ✓");
    assert!(got["items"][0].get("leftOut").is_none());
    assert_eq!(got["byNumber"]["10"], false);
}

#[wasm_bindgen_test]
fn a_result_that_cannot_be_written_is_an_error_not_a_wrong_value() {
    // A series holding something else than numbers.
    struct Bad;
    impl Serialize for Bad {
        fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            s.serialize_newtype_struct(fiveaxis::edge::SERIES, &["text"])
        }
    }
    assert!(output(&Bad).is_err());
    // A map keyed by lists.
    let m: BTreeMap<Vec<u8>, u8> = [(vec![1], 2)].into();
    assert!(output(&m).is_err());
}
