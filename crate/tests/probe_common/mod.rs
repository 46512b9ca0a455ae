//! Helpers of the probing study's tests: the three machines of the issue (presets of
//! `public/presets/machines.json`) and the study built from JSON as the page sends it.
#![allow(dead_code, clippy::unwrap_used)]

use fiveaxis::probe::{ProbeInput, SpherePlace, Study};
use fiveaxis::schema::Inputs;
use nalgebra::Vector3;
use serde_json::{json, Value};

/// A B/C tilting table (preset "B/C tilting table, vertical spindle (Li et al. 2021)").
pub fn bc_table() -> Value {
    json!({
        "kind": "table-table", "type": "CBZ", "linear": "spindle-xyz",
        "geometry": { "rotaryOffset": 0, "tableHeight": 0, "toolLength": 0 },
        "rotary": { "kFrom": -360, "kTo": 360, "kContinuous": true, "mFrom": -120, "mTo": 120 }
    })
}

/// An A/C trunnion (preset "A/C trunnion table, vertical spindle").
pub fn ac_trunnion() -> Value {
    json!({
        "kind": "table-table", "type": "CAZ", "linear": "spindle-xyz",
        "geometry": { "rotaryOffset": 0, "tableHeight": 100, "toolLength": 100 },
        "rotary": { "kFrom": -360, "kTo": 360, "kContinuous": true, "mFrom": -120, "mTo": 30 }
    })
}

/// A head-table machine (preset "B swivel head with C table (mill-turn)").
pub fn head_table() -> Value {
    json!({
        "kind": "head-table", "type": "CBZ", "linear": "spindle-xyz",
        "geometry": { "tableHeight": 0, "pivotLength": 200, "toolLength": 100 },
        "rotary": { "kFrom": -360, "kTo": 360, "kContinuous": true, "mFrom": -110, "mTo": 110 }
    })
}

/// The three machines with their names.
pub fn machines() -> Vec<(&'static str, Value)> {
    vec![
        ("B/C tilting table", bc_table()),
        ("A/C trunnion", ac_trunnion()),
        ("B head, C table", head_table()),
    ]
}

/// `machine` with `errors` (API units: mm, degrees).
pub fn with_errors(machine: &Value, errors: Value) -> Value {
    let mut m = machine.clone();
    m["errors"] = errors;
    m
}

/// The study of a JSON input.
pub fn study(input: Value) -> Study {
    Study::new(&ProbeInput::from_value(&input, "").unwrap()).unwrap()
}

/// The sphere place of `[x, y, height]`.
pub fn place(p: [f64; 3]) -> SpherePlace {
    SpherePlace {
        x: p[0],
        y: p[1],
        height: p[2],
    }
}

/// The exact measured centre at `(k, m)` (rad) on `machine` (with its errors) with the sphere
/// at `sphere` (`[x, y, height]`).
pub fn centre(machine: &Value, sphere: [f64; 3], k: f64, m: f64) -> Vector3<f64> {
    let s = study(
        json!({ "machine": machine, "sphere": { "x": sphere[0], "y": sphere[1], "height": sphere[2] } }),
    );
    s.measured(k, m).unwrap()
}

/// Rotation about X, Y or Z (0, 1, 2) by `a` rad, written out.
pub fn rot(axis: usize, a: f64) -> nalgebra::Matrix3<f64> {
    let (s, c) = a.sin_cos();
    match axis {
        0 => nalgebra::Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
        1 => nalgebra::Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c),
        _ => nalgebra::Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
    }
}

/// A JSON list of numbers (an export's series or triple) as numbers.
pub fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not a list: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap_or_else(|| panic!("not a number: {x}")))
        .collect()
}

/// A JSON list of strings.
pub fn strings(v: &Value) -> Vec<&str> {
    v.as_array()
        .unwrap_or_else(|| panic!("not a list: {v}"))
        .iter()
        .map(|x| x.as_str().unwrap_or_else(|| panic!("not a string: {x}")))
        .collect()
}
