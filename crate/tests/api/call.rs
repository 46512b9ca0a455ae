//! The declared exports run natively through `api::call` on JSON, as the binding runs them: the
//! same reader (degrees in) and the same writer (degrees out).

#![allow(clippy::unwrap_used)] // a failure should stop the test

use fiveaxis::api::{call, EXPORTS};
use serde_json::json;

/// The tool direction of a CAZ machine (K = C about Z, M = A about X, tool along Z at zero)
/// at C = 30°, A = 50°: the table turned by A then C puts the tool at
/// `(sin C sin A, cos C sin A, cos A)` in workpiece coordinates (up to the sense of rotation,
/// checked by the length and the Z component, which are sign-free).
#[test]
fn tool_vector_takes_degrees() {
    let v = call(
        "toolVector",
        &json!({ "machine": { "type": "CAZ" }, "k": 30, "m": 50 }),
    )
    .unwrap();
    let v: Vec<f64> = serde_json::from_value(v).unwrap();
    let (c, a) = (30f64.to_radians(), 50f64.to_radians());
    assert!((v[2] - a.cos()).abs() < 1e-12, "{v:?}");
    assert!((v[0].abs() - c.sin() * a.sin()).abs() < 1e-12, "{v:?}");
    assert!((v[1].abs() - c.cos() * a.sin()).abs() < 1e-12, "{v:?}");
}

/// The inverse gives the commands back in degrees: the pose a direction came from is among its
/// solutions, and the pole angle is the tilt from K (Z), 50°.
#[test]
fn inverse_gives_degrees_back() {
    let machine = json!({ "type": "CAZ" });
    let v = call(
        "toolVector",
        &json!({ "machine": machine, "k": 30, "m": 50 }),
    )
    .unwrap();
    let r = call(
        "machineInverse",
        &json!({ "machine": machine, "vector": v, "previous": { "k": 29, "m": 49 } }),
    )
    .unwrap();
    let chosen = &r["solutions"][r["chosen"].as_u64().unwrap() as usize];
    assert!((chosen["k"].as_f64().unwrap() - 30.0).abs() < 1e-9, "{r}");
    assert!((chosen["m"].as_f64().unwrap() - 50.0).abs() < 1e-9, "{r}");
    assert!(
        (r["poleAngle"].as_f64().unwrap() - 50.0).abs() < 1e-9,
        "{r}"
    );
}

/// A fault names the input's path, and an unknown export names itself.
#[test]
fn faults_name_their_path() {
    let e = call("toolVector", &json!({ "k": 10 })).unwrap_err();
    assert!(e.to_string().starts_with("m: is required"), "{e}");
    let e = call("noSuchExport", &json!({})).unwrap_err();
    assert!(e.to_string().starts_with("noSuchExport"), "{e}");
}

/// Every declared export refuses a key it does not declare, by name (the readers are the
/// declared inputs, not a permissive parse).
#[test]
fn every_export_refuses_an_unknown_key() {
    assert!(EXPORTS.len() >= 7, "{EXPORTS:?}");
    for name in EXPORTS {
        let e = call(name, &json!({ "surelyNotAField": 1 }))
            .unwrap_err()
            .to_string();
        assert!(e.contains("surelyNotAField"), "{name}: {e}");
    }
}

/// What `schema()` lists for each declared export: a one-struct export's fields, both structs'
/// fields of a two-struct export (the shared case first), none for an export that takes no
/// input. Found by cargo-mutants: `fields` returning nothing survived, as no native test read
/// the declared fields (the Node suite compares them with the .d.ts).
#[test]
fn the_declared_fields_are_each_inputs_own() {
    let fields = fiveaxis::api::export_fields();
    let of = |name: &str| -> Vec<String> {
        fields
            .iter()
            .find(|(n, _)| *n == name)
            .unwrap()
            .1
            .iter()
            .map(|f| f.path.clone())
            .collect()
    };
    // One struct: ISO 230-2's runs and the axis.
    let positioning = of("positioningEvaluate");
    assert!(
        positioning.contains(&"csv".to_string()) && positioning.contains(&"axis".to_string()),
        "{positioning:?}"
    );
    // Two structs read from one object: the probe's case (the sphere) and its own (the file).
    let probe = of("probeIdentify");
    let sphere = probe.iter().position(|p| p == "sphere.x").unwrap();
    let csv = probe.iter().position(|p| p == "csv").unwrap();
    assert!(sphere < csv, "{probe:?}");
    // No input.
    assert!(of("rotaryTypes").is_empty());
}

/// An export that takes no input accepts nothing (JavaScript's `undefined` arrives as null) or an
/// empty object, and refuses anything else by the key it was given. Found by cargo-mutants: its
/// reader's arms survived, as no native test called such an export.
#[test]
fn an_export_without_input_refuses_any_input_by_name() {
    let types = call("rotaryTypes", &serde_json::Value::Null).unwrap();
    assert_eq!(types.as_array().unwrap().len(), 12);
    assert_eq!(call("rotaryTypes", &json!({})).unwrap(), types);
    let e = call("rotaryTypes", &json!({ "machine": {} }))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("machine: this export takes no input"), "{e}");
    let e = call("rotaryTypes", &json!(3)).unwrap_err().to_string();
    assert!(e.starts_with("input: this export takes no input"), "{e}");
}
