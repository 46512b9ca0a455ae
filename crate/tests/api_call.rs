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
