//! The identified errors are the machine's errors (issue 31): from noise-free centres of the
//! exact chain the identification, called through the declared export on JSON as the page does,
//! returns the true values (to the linearisation's error), and its `errors` object put into
//! `machine.errors` reproduces the measured centres; the corrections say where the axis is.
#![allow(clippy::unwrap_used)]
use crate::probe_common;

use fiveaxis::api::call;
use probe_common::{bc_table, centre, with_errors};
use serde_json::{json, Value};

#[test]
fn the_errors_found_reproduce_the_measured_centres_when_put_into_the_machine() {
    let sphere = [150.0, 0.0, 100.0];
    let truth = json!({ "E_X0C": 0.012, "E_A0B": 0.003, "E_C0B": -0.002, "E_Z0B": -0.008 });
    let machine = bc_table();
    let measured = with_errors(&machine, truth.clone());
    let base = json!({ "machine": machine, "sphere": { "x": 150, "y": 0, "height": 100 },
        "parameters": ["E_X0B", "E_Z0B", "E_A0B", "E_C0B", "E_X0C", "E_A0C"] });
    let design = call("probeDesign", &base).unwrap();
    let poses = design["designed"]["poses"].as_array().unwrap();
    // The measurement file, with a decimal comma and the reference pose first.
    let mut csv = String::from("pose;C_deg;B_deg;X_mm;Y_mm;Z_mm\r\n");
    for (i, p) in poses.iter().enumerate() {
        let (k, m) = (p["k"].as_f64().unwrap(), p["m"].as_f64().unwrap());
        let c = centre(&measured, sphere, k.to_radians(), m.to_radians());
        csv.push_str(
            &format!("{};{k};{m};{:.7};{:.7};{:.7}\r\n", i + 1, c[0], c[1], c[2]).replace('.', ","),
        );
    }
    let mut input = base.clone();
    input["csv"] = json!(csv);
    input["decision"] = json!({ "tolerance": 0.001 });
    let r = call("probeIdentify", &input).unwrap();
    let errors = r["errors"].as_object().unwrap();
    for (name, v) in truth.as_object().unwrap() {
        let got = errors[name].as_f64().unwrap();
        let want = v.as_f64().unwrap();
        assert!(
            (got - want).abs() < 2e-3 * want.abs() + 2e-7,
            "{name}: {got} vs {want}"
        );
    }
    // No error reported that is not there (noise-free: values at rounding level).
    for name in errors.keys() {
        assert!(truth.get(name).is_some(), "{name} reported: {r}");
    }
    // Into machine.errors as it is: the centres come out as measured (within 0.1 µm).
    let found = with_errors(&machine, Value::Object(errors.clone()));
    for p in poses {
        let (k, m) = (
            p["k"].as_f64().unwrap().to_radians(),
            p["m"].as_f64().unwrap().to_radians(),
        );
        let a = centre(&found, sphere, k, m);
        let b = centre(&measured, sphere, k, m);
        assert!((a - b).norm() < 1e-4, "{a} vs {b}");
    }
    // The spread before is that of the errors, after at the rounding of the file.
    assert!(
        r["before"]["max"].as_f64().unwrap() > 0.005,
        "{}",
        r["before"]
    );
    assert!(r["after"]["max"].as_f64().unwrap() < 1e-4, "{}", r["after"]);
    // In words: the C axis line 12 µm towards +X; the number to enter.
    let corr = r["corrections"].as_array().unwrap();
    let c = corr.iter().find(|c| c["name"] == "E_X0C").unwrap();
    let words = c["words"].as_str().unwrap();
    assert!(
        words.contains("C axis line lies 12.0 µm towards +X"),
        "{words}"
    );
    assert!(
        c["enter"].as_str().unwrap().contains("add +0.0120 mm"),
        "{}",
        c["enter"]
    );
}

#[test]
fn simulate_reports_the_exact_deviation_and_its_first_order_form() {
    let input = json!({ "machine": with_errors(&bc_table(), json!({ "E_X0C": 0.01, "E_B0C": 0.002 })),
        "sphere": { "x": 100, "y": 50, "height": 80 }, "k": [0, 90, 180], "m": [0, 30, -45] });
    let r = call("probeSimulate", &input).unwrap();
    for p in r["poses"].as_array().unwrap() {
        for i in 0..3 {
            let dev = p["deviation"][i].as_f64().unwrap();
            let first = p["firstOrder"][i].as_f64().unwrap();
            // Second-order terms: (ε·L)²/L ≈ (3.5e-5·150)²/150 mm.
            assert!((dev - first).abs() < 1e-6, "{p}");
        }
    }
    // Sensitivities per degree at the edge: E_B0C's is π/180 of its per-radian value.
    let s = r["sensitivities"].as_array().unwrap();
    assert!(s.iter().any(|c| c["name"] == "E_B0C" && c["per"] == "deg"));
    assert_eq!(r["poses"][1]["k"].as_f64().unwrap(), 90.0);
}

// Found by cargo-mutants: the sphere found (`+=` as `-=` or `*=`), each estimate's group (its
// name matched as `!=`) and each group's words (`== gi` as `!=`) changed no outcome of the tests
// before.
#[test]
fn the_sphere_is_found_where_it_is_and_inseparable_unknowns_share_their_group_and_its_words() {
    let stated = [120.0, -30.0, 80.0];
    let truth = [120.04, -30.03, 80.02];
    let machine = bc_table();
    let measured = with_errors(&machine, json!({ "E_X0B": 0.015, "E_A0C": 0.003 }));
    let poses = [
        (0.0, 0.0),
        (90.0, 0.0),
        (180.0, 0.0),
        (270.0, 0.0),
        (0.0, -60.0),
        (0.0, 60.0),
        (45.0, 30.0),
        (225.0, -45.0),
        (135.0, 75.0),
        (300.0, -20.0),
    ];
    let mut csv = String::from("C,B,X,Y,Z\n");
    for &(k, m) in &poses {
        let c = centre(&measured, truth, f64::to_radians(k), f64::to_radians(m));
        csv.push_str(&format!("{k},{m},{:.8},{:.8},{:.8}\n", c[0], c[1], c[2]));
    }
    // C's zero is one of the unknowns: a turn of the sphere about C, which the sphere's fitted
    // position takes too (crate/tests/probe/design_and_visibility.rs).
    let r = call(
        "probeIdentify",
        &json!({ "machine": machine,
        "sphere": { "x": stated[0], "y": stated[1], "height": stated[2] },
        "parameters": ["E_X0B", "E_A0C", "E_C0C"], "csv": csv }),
    )
    .unwrap();
    let found = r["sphere"].as_array().unwrap();
    // The fitted shift absorbs C's zero only within the group: along C's line (Z) it is the
    // sphere's alone, and its distance from C's line is kept by a turn.
    let (x, y, z) = (
        found[0].as_f64().unwrap(),
        found[1].as_f64().unwrap(),
        found[2].as_f64().unwrap(),
    );
    assert!((z - truth[2]).abs() < 1e-5, "{found:?}");
    assert!(
        (x.hypot(y) - truth[0].hypot(truth[1])).abs() < 1e-5,
        "{found:?} vs {truth:?}"
    );
    assert!(
        (z - stated[2]).abs() > 0.01,
        "the sphere is not where it was stated"
    );
    let groups = r["groups"].as_array().unwrap();
    assert!(!groups.is_empty(), "{r}");
    let mut grouped = 0;
    for e in r["estimates"].as_array().unwrap() {
        if let Some(g) = e["group"].as_u64() {
            let members = &groups[g as usize]["members"];
            assert!(
                members.as_array().unwrap().contains(&e["name"]),
                "{e} not in {members}"
            );
            grouped += 1;
        }
    }
    for (g, group) in groups.iter().enumerate() {
        let members = group["members"].as_array().unwrap();
        assert!(members.iter().any(|m| m == "E_C0C"), "{group}");
        for m in members {
            let e = r["estimates"]
                .as_array()
                .unwrap()
                .iter()
                .find(|e| &e["name"] == m)
                .unwrap();
            assert_eq!(e["group"].as_u64(), Some(g as u64), "{e}");
        }
        // Its words are the combinations of its own members that the poses measure.
        let words = group["words"].as_array().unwrap();
        assert!(!words.is_empty(), "{group}");
        for w in words {
            assert!(w.as_str().unwrap().contains("E_C0C"), "{w}");
        }
    }
    assert!(grouped >= 2, "{r}");
}
