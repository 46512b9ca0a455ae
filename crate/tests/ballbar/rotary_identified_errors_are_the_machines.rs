//! The errors identified from ball-bar tests of the rotary axes are the machine's errors (issue
//! 32): from noise-free traces of the exact chain (four tests in one file with a test column,
//! decimal comma), the identification called through the declared export on JSON as the page
//! does returns the true values (to the linearisation's error and the file's rounding), reports
//! no error that is not there, and its `errors` object put into `machine.errors` reproduces the
//! measured traces; the corrections say where the axis is and what to enter.
#![allow(clippy::unwrap_used)]
use crate::probe_common;

use fiveaxis::api::call;
use probe_common::{bc_table, numbers, strings, with_errors};
use serde_json::{json, Value};

#[test]
fn the_errors_found_reproduce_the_measured_traces_when_put_into_the_machine() {
    let truth = json!({ "E_X0C": 0.012, "E_A0B": 0.003, "E_C0B": -0.002, "E_Z0B": -0.008 });
    let machine = bc_table();
    let measured = with_errors(&machine, truth.clone());
    let tests = json!([
        { "name": "C radial", "ball": { "x": 150, "y": 0, "height": 50 }, "step": 5 },
        { "name": "C axial", "ball": { "x": 150, "y": 0, "height": 50 }, "step": 5, "direction": "axial" },
        { "name": "B radial", "axis": "m", "ball": { "x": 100, "y": 0, "height": 50 }, "step": 5, "from": -60, "to": 30 },
        { "name": "B axial", "axis": "m", "ball": { "x": 100, "y": 0, "height": 50 }, "step": 5, "from": -60, "to": 30, "direction": "axial" }
    ]);
    let sim = call(
        "ballbarRotarySimulate",
        &json!({ "machine": measured, "tests": tests }),
    )
    .unwrap();
    let csv = sim["csv"]
        .as_str()
        .unwrap()
        .replace('.', ",")
        .replace('\n', "\r\n");
    let params = ["E_X0B", "E_Z0B", "E_A0B", "E_C0B", "E_X0C", "E_A0C"];
    let r = call(
        "ballbarRotaryIdentify",
        &json!({ "machine": machine, "tests": tests, "parameters": params, "csv": csv,
                 "decision": { "tolerance": 0.001 } }),
    )
    .unwrap();
    let errors = r["errors"].as_object().unwrap();
    for (name, v) in truth.as_object().unwrap() {
        let got = errors[name].as_f64().unwrap();
        let want = v.as_f64().unwrap();
        assert!(
            (got - want).abs() < 2e-3 * want.abs() + 2e-7,
            "{name}: {got} vs {want}"
        );
    }
    for name in errors.keys() {
        assert!(
            truth.get(name).is_some(),
            "{name} reported: {}",
            r["summary"]
        );
    }
    // Into machine.errors as it is: the traces come out as measured, within 0.1 µm.
    let found = with_errors(&machine, Value::Object(errors.clone()));
    let again = call(
        "ballbarRotarySimulate",
        &json!({ "machine": found, "tests": tests }),
    )
    .unwrap();
    for (a, b) in sim["tests"]
        .as_array()
        .unwrap()
        .iter()
        .zip(again["tests"].as_array().unwrap())
    {
        for (x, y) in numbers(&a["deviation"])
            .iter()
            .zip(numbers(&b["deviation"]))
        {
            assert!((x - y).abs() < 1e-4, "{}: {x} vs {y}", a["name"]);
        }
    }
    // Before: the errors' trace; after: the file's rounding.
    for t in r["tests"].as_array().unwrap() {
        assert!(t["after"].as_f64().unwrap() < 1e-5, "{}", t["name"]);
    }
    assert!(r["tests"][0]["before"].as_f64().unwrap() > 0.005);
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
    let a = corr.iter().find(|c| c["name"] == "E_A0B").unwrap();
    assert_eq!(a["unit"], "deg");
    assert!((a["value"].as_f64().unwrap() - 0.003).abs() < 1e-5);
    // What the four tests see: the C test alone cannot tell B's offset from C's; together
    // they can.
    let together = &r["together"];
    assert!(together["gained"]
        .as_array()
        .unwrap()
        .iter()
        .any(|n| n == "E_X0C"));
    // … and say so in a sentence that starts as one.
    let words = together["words"].as_str().unwrap();
    assert!(
        words.starts_with("Together the tests also identify") && words.contains("E_X0C"),
        "{words}"
    );
}

#[test]
fn a_tests_range_is_twice_the_offset_of_the_axis_line_for_a_radial_bar() {
    // C's line e off along X, a radial bar of length L: the table ball is at distance
    // √(L² − 2·L·e·cos(C − φ) + e²) from the tool ball (module docs of ballbar::rotary), which
    // runs from L − e (at C = φ) to L + e (at C = φ + 180°): the range is 2·e exactly. Both
    // angles are on a 1° sweep (φ = 0). The residual's range once E_X0C is identified is the
    // file's rounding (0.1 nm) and the first-order model's remainder (e²/(2L) ≈ 0.5 nm here).
    let e = 0.01;
    let machine = bc_table();
    let tests = json!([{ "ball": { "x": 100, "y": 0, "height": 50 } }]);
    let sim = call(
        "ballbarRotarySimulate",
        &json!({ "machine": with_errors(&machine, json!({ "E_X0C": e })), "tests": tests }),
    )
    .unwrap();
    let r = call(
        "ballbarRotaryIdentify",
        &json!({ "machine": machine, "tests": tests, "parameters": ["E_X0C", "E_Y0C"],
                 "csv": sim["csv"] }),
    )
    .unwrap();
    let t = &r["tests"][0];
    let range = t["range"].as_f64().unwrap();
    assert!((range - 2.0 * e).abs() < 2e-7, "range {range}");
    let after = t["rangeAfter"].as_f64().unwrap();
    assert!(after < 2e-6, "range after {after}");
    assert!(after > 0.0);
}

#[test]
fn a_machine_without_errors_is_said_to_leave_the_bar_alone_and_one_with_an_offset_is_not() {
    // The exact chain leaves picometres of rounding on an ideal machine: the summary must not
    // report them as a length change; with C's line 10 µm off, the range is 2·e = 20 µm.
    let tests = json!([{ "ball": { "x": 100, "y": 0, "height": 50 } }]);
    let say = |machine: Value| {
        let r = call(
            "ballbarRotarySimulate",
            &json!({ "machine": machine, "tests": tests }),
        )
        .unwrap();
        r["summary"][0].as_str().unwrap().to_string()
    };
    let ideal = say(bc_table());
    assert!(
        ideal.ends_with(
            "the bar's length does not change (no error of the machine moves it in this test)."
        ),
        "{ideal}"
    );
    let off = say(with_errors(&bc_table(), json!({ "E_X0C": 0.01 })));
    assert!(off.contains("changes by 20.0 µm"), "{off}");
}

#[test]
fn an_error_the_bar_cannot_see_is_explained_once_in_the_summary() {
    // E_C0C (C's zero) turns the ball along its circle about C, square to a radial bar: the
    // summary says why, once, rather than also the generic "cannot see it at all".
    let machine = bc_table();
    let tests = json!([{ "ball": { "x": 100, "y": 0, "height": 50 }, "step": 5 }]);
    let sim = call(
        "ballbarRotarySimulate",
        &json!({ "machine": with_errors(&machine, json!({ "E_X0C": 0.01 })), "tests": tests }),
    )
    .unwrap();
    let r = call(
        "ballbarRotaryIdentify",
        &json!({ "machine": machine, "tests": tests, "parameters": ["E_X0C", "E_Y0C", "E_C0C"],
                 "csv": sim["csv"] }),
    )
    .unwrap();
    let lines = strings(&r["summary"]);
    let about: Vec<&&str> = lines.iter().filter(|l| l.contains("E_C0C")).collect();
    assert_eq!(about.len(), 1, "{lines:#?}");
    assert!(
        about[0].starts_with("E_C0C: a turn about the C axis's own line"),
        "{}",
        about[0]
    );
}

/// A trace written here, not simulated: the C axis line `e` off along X seen by a radial bar,
/// `d(φ) = −e·cos φ` (the closed form's first order, as the simulated file above shows at 0°),
/// plus a constant of its own in each direction (the bar's set-up: `a` counter-clockwise, `b`
/// clockwise). The identification finds `e` and one offset per direction, each named for its test
/// and direction; the spread before is the rms of each point less its own direction's mean,
/// computed here from the values written. The offsets follow the errors, counter-clockwise
/// first, whatever the file's order.
// Found by cargo-mutants: the spread before (each direction's mean, the rms), the offsets'
// names, order and labels (one test, two errors), and the summary's carrying of the
// identification's lines were reached by no test.
#[test]
fn each_direction_has_its_own_offset_and_the_spread_before_is_about_its_own_mean() {
    let (e, a, b) = (10.0, 2.0, -3.0); // µm
    let mut csv = String::from("angle (deg);deviation (µm);direction\n");
    // (direction, value) of each line written. The clockwise run first: the offsets are still
    // listed counter-clockwise first.
    let mut values: Vec<(f64, f64)> = Vec::new();
    for (dir, word, shift) in [(-1.0, "cw", b), (1.0, "ccw", a)] {
        for k in 0..=12 {
            let phi = 30.0 * f64::from(if dir > 0.0 { k } else { 12 - k });
            let d = -e * phi.to_radians().cos() + shift;
            csv += &format!("{phi};{d:.6};{word}\n");
            values.push((dir, d));
        }
    }
    let tests = json!([{ "ball": { "x": 100, "y": 0, "height": 50 }, "step": 30 }]);
    let r = call(
        "ballbarRotaryIdentify",
        &json!({ "machine": bc_table(), "tests": tests, "parameters": ["E_X0C", "E_Y0C"],
                 "csv": csv }),
    )
    .unwrap();
    let estimates = r["identification"]["estimates"].as_array().unwrap();
    let estimate = |name: &str| {
        estimates
            .iter()
            .find(|x| x["name"] == name)
            .unwrap_or_else(|| panic!("no {name} in {estimates:#?}"))
    };
    // The model's second order (e²/L ≈ 1 nm) and the file's 1 pm rounding.
    let near = |name: &str, want_um: f64| {
        let got = estimate(name)["value"].as_f64().unwrap() * 1e3;
        assert!(
            (got - want_um).abs() < 0.01,
            "{name}: {got} µm vs {want_um}"
        );
    };
    let names: Vec<&str> = estimates
        .iter()
        .map(|x| x["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["E_X0C", "E_Y0C", "offset_1_ccw", "offset_1_cw"]);
    near("E_X0C", e);
    near("E_Y0C", 0.0);
    near("offset_1_ccw", a);
    near("offset_1_cw", b);
    for dir in ["ccw", "cw"] {
        let words = estimate(&format!("offset_1_{dir}"))["words"]
            .as_str()
            .unwrap();
        assert!(
            words.contains(&format!("in test 1 ({dir}) differ")),
            "{words}"
        );
    }
    // The result's summary carries the identification's own lines.
    let summary = strings(&r["summary"]);
    let x_words = estimate("E_X0C")["words"].as_str().unwrap();
    assert!(summary.contains(&x_words), "{summary:#?}");
    // Before: about each direction's own mean.
    let mean = |dir: f64| {
        let v: Vec<f64> = values.iter().filter(|p| p.0 == dir).map(|p| p.1).collect();
        v.iter().sum::<f64>() / v.len() as f64
    };
    let (mc, mw) = (mean(1.0), mean(-1.0));
    let ss: f64 = values
        .iter()
        .map(|&(dir, d)| (d - if dir > 0.0 { mc } else { mw }).powi(2))
        .sum();
    let want = (ss / values.len() as f64).sqrt() * 1e-3;
    let t = &r["tests"][0];
    let before = t["before"].as_f64().unwrap();
    assert!((before - want).abs() < 1e-9, "before {before} mm vs {want}");
    // In closed form: the 13 angles 0°, 30°, … 360° of each direction have Σcos φ = 1 and
    // Σcos²φ = 7, so the spread is e·√((7 − 1/13)/13) = 7.298 µm; about one mean of both
    // directions it would be √(7.298² + 2.5²) = 7.71 µm.
    let closed = e * ((7.0 - 1.0 / 13.0) / 13.0_f64).sqrt() * 1e-3;
    assert!((before - closed).abs() < 1e-8, "{before} vs {closed}");
    assert!(t["after"].as_f64().unwrap() < 2e-6, "{}", t["after"]);
}

/// A test needs MIN_POINTS (8) measured points: 8 are fitted, 7 refused naming the count. Eight
/// points of one direction at 10°, 50° … 290° (no sensitivity exactly 0) see E_X0C (`cos C`)
/// and E_Y0C (`sin C`) apart from the one offset.
// Found by cargo-mutants: the count's edge was reached by no test, nor a test alone whose every
// sensitivity is non-zero (`together`).
#[test]
fn eight_points_of_a_test_are_enough_and_seven_are_not() {
    let tests = json!([{ "ball": { "x": 100, "y": 0, "height": 50 }, "step": 30 }]);
    let run = |n: usize| {
        let mut csv = String::from("angle (deg);deviation (µm);direction\n");
        for k in 0..n {
            let phi = 10.0 + 40.0 * k as f64;
            csv += &format!("{phi};{:.4};ccw\n", -10.0 * phi.to_radians().cos());
        }
        call(
            "ballbarRotaryIdentify",
            &json!({ "machine": bc_table(), "tests": tests, "parameters": ["E_X0C", "E_Y0C"],
                     "csv": csv }),
        )
        .map_err(|e| e.to_string())
    };
    let r = run(8).unwrap();
    assert_eq!(r["tests"][0]["points"], 8);
    assert_eq!(
        r["together"]["alone"][0]["identifiable"],
        json!(["E_X0C", "E_Y0C"])
    );
    let e = run(7).unwrap_err();
    assert!(
        e.starts_with("csv: test 1 has 7 measured points: give at least 8"),
        "{e}"
    );
}
