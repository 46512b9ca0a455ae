//! Two things an engineer reads in the probe identification's words: the model-fit check is made
//! against the probing noise stated once for the study when the decision's own noise is left
//! empty, and a group of errors the sphere cannot separate is written with its coefficients per
//! API unit (an angle per degree), as the designer writes the same group.
#![allow(clippy::unwrap_used)]
use crate::probe_common;

use fiveaxis::api::call;
use probe_common::{bc_table, centre, with_errors};
use serde_json::{json, Value};

/// The identification input of `machine`'s designed poses, measured on `measured` with a
/// deterministic disturbance `wobble` (mm) added to each coordinate of pose `i`.
fn input(base: &Value, measured: &Value, sphere: [f64; 3], wobble: impl Fn(usize) -> f64) -> Value {
    let design = call("probeDesign", base).unwrap();
    let mut csv = String::from("pose,C_deg,B_deg,X_mm,Y_mm,Z_mm\n");
    for (i, p) in design["designed"]["poses"]
        .as_array()
        .unwrap()
        .iter()
        .enumerate()
    {
        let (k, m) = (p["k"].as_f64().unwrap(), p["m"].as_f64().unwrap());
        let c = centre(measured, sphere, k.to_radians(), m.to_radians());
        let w = wobble(i);
        csv.push_str(&format!(
            "{},{k},{m},{:.7},{:.7},{:.7}\n",
            i + 1,
            c[0] + w,
            c[1] - w,
            c[2] + w
        ));
    }
    let mut input = base.clone();
    input["csv"] = json!(csv);
    input
}

#[test]
fn the_fit_is_checked_against_the_probing_noise_when_the_decision_states_none() {
    let sphere = [150.0, 0.0, 100.0];
    let machine = bc_table();
    let measured = with_errors(&machine, json!({ "E_X0C": 0.012, "E_A0B": 0.003 }));
    let base = json!({ "machine": machine, "sphere": { "x": 150, "y": 0, "height": 100 }, "noise": 0.001,
        "parameters": ["E_X0B", "E_Z0B", "E_A0B", "E_C0B", "E_X0C", "E_A0C"] });
    // Centres as the chain gives them: the errors explain them, checked against 1 µm.
    let r = call("probeIdentify", &input(&base, &measured, sphere, |_| 0.0)).unwrap();
    assert_eq!(
        r["goodness"]["noise"].as_f64(),
        Some(0.001),
        "{}",
        r["goodness"]
    );
    assert_eq!(r["goodness"]["explains"], json!(true), "{}", r["goodness"]);
    // ±20 µm alternating from pose to pose, twenty times the probing noise: no location error
    // of an axis does that, and the check says so.
    let bad = call(
        "probeIdentify",
        &input(&base, &measured, sphere, |i| {
            if i % 2 == 0 {
                0.02
            } else {
                -0.02
            }
        }),
    )
    .unwrap();
    assert_eq!(
        bad["goodness"]["explains"],
        json!(false),
        "{}",
        bad["goodness"]
    );
    // A noise stated in the decision is the one used.
    let mut own = input(&base, &measured, sphere, |_| 0.0);
    own["decision"] = json!({ "noise": 0.005 });
    let r = call("probeIdentify", &own).unwrap();
    assert_eq!(
        r["goodness"]["noise"].as_f64(),
        Some(0.005),
        "{}",
        r["goodness"]
    );
}

#[test]
fn a_group_the_sphere_cannot_separate_is_written_per_degree_as_the_designer_writes_it() {
    // The sphere on C's axis, 100 mm above the table, and the twelve location errors: C's
    // tilt about X moves the sphere as a shift of 100 mm × the tilt (in radians), so per degree
    // the coefficient is 100·π/180 = 1.7453 mm/deg, not 100.
    let sphere = [0.0, 0.0, 100.0];
    let machine = bc_table();
    let base = json!({ "machine": machine, "sphere": { "x": 0, "y": 0, "height": 100 } });
    let r = call("probeIdentify", &input(&base, &machine, sphere, |_| 0.0)).unwrap();
    let words: Vec<String> = r["groups"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|g| {
            g["words"]
                .as_array()
                .unwrap()
                .iter()
                .map(|w| w.as_str().unwrap().to_string())
        })
        .collect();
    let with_tilt: Vec<&String> = words.iter().filter(|w| w.contains("·E_A0C")).collect();
    assert!(
        !with_tilt.is_empty(),
        "no group with C's tilt about X: {words:?}"
    );
    let per_degree = format!("{:.4}·E_A0C", 100.0 * std::f64::consts::PI / 180.0);
    for w in &with_tilt {
        assert!(w.contains(&per_degree), "{w}: expected {per_degree}");
        assert!(!w.contains("100·E_A0C"), "{w}");
    }
    // The designer writes the same combination.
    let design = call("probeDesign", &base).unwrap();
    let designed: Vec<String> = design["visibility"]
        .to_string()
        .split('"')
        .filter(|s| s.contains("·E_A0C"))
        .map(str::to_string)
        .collect();
    assert!(
        designed
            .iter()
            .any(|d| with_tilt.iter().any(|w| w.contains(d.as_str()))),
        "design {designed:?} vs identification {with_tilt:?}"
    );
}
