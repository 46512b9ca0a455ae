//! The ball-bar traces' one reader (issue 32) as the rotary-axis tests and the reversal study
//! use it: each kind of bad line named with its line (and the input's path), decimal commas,
//! units in the header, tabs, CRLF and a byte-order mark, the test column by name or number;
//! and one file going through both the rotary-axis identification and the reversal study's
//! reader, the reversal study's own sample file rewritten in this format fitting as before.
#![allow(clippy::unwrap_used)]
use crate::probe_common;

use fiveaxis::api::call;
use fiveaxis::reversal::fit::parse_trace;
use probe_common::{bc_table, with_errors};
use serde_json::{json, Value};

const SAMPLE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../public/samples/reversal-measured.csv"
);

/// One C test, radial, every 30°, 13 points each way.
fn one_test() -> Value {
    json!([{ "ball": { "x": 150, "y": 0, "height": 50 }, "step": 30 }])
}

/// A good file of the one test: `deviation (µm)` with a decimal comma, `;`.
fn good(machine: &Value) -> String {
    let s = call(
        "ballbarRotarySimulate",
        &json!({ "machine": machine, "tests": one_test() }),
    )
    .unwrap();
    let t = &s["tests"][0];
    let mut out = String::from("angle (deg);deviation (µm);direction\n");
    let a = t["angle"].as_array().unwrap();
    for i in 0..a.len() {
        let d = t["deviation"][i].as_f64().unwrap() * 1e3;
        let r = if t["run"][i].as_f64().unwrap() > 0.0 {
            "ccw"
        } else {
            "cw"
        };
        out.push_str(&format!("{};{d:.6};{r}\n", a[i].as_f64().unwrap()).replace('.', ","));
    }
    out
}

fn identify(input: Value) -> Result<Value, String> {
    call("ballbarRotaryIdentify", &input).map_err(|e| e.to_string())
}

#[test]
fn each_kind_of_bad_line_is_named() {
    let m = bc_table();
    let two = json!([
        { "ball": { "x": 150, "y": 0, "height": 50 } },
        { "ball": { "x": 150, "y": 0, "height": 50 }, "direction": "axial", "name": "ax" }
    ]);
    let tilt =
        json!([{ "axis": "m", "ball": { "x": 100, "y": 0, "height": 50 }, "from": -60, "to": 30 }]);
    let g = good(&m);
    let head = "angle (deg);deviation (µm);direction\n";
    let rows =
        "0;1;ccw\n30;2;ccw\n60;3;ccw\n90;4;ccw\n120;5;ccw\n150;6;ccw\n180;7;ccw\n210;8;ccw\n";
    let cases: Vec<(Value, Value, &str)> = vec![
        (one_test(), json!(""), "csv: give the measured traces"),
        (
            one_test(),
            json!("# only a comment\n"),
            "csv: the file is empty",
        ),
        (
            one_test(),
            json!("value (µm);direction\n1;ccw\n"),
            "csv: line 1: missing column 'angle_deg'",
        ),
        (
            one_test(),
            json!("angle (deg);direction\n1;ccw\n"),
            "csv: line 1: missing column 'deviation_mm'",
        ),
        (
            one_test(),
            json!("angle (deg);deviation;direction\n1;2;ccw\n"),
            "csv: line 1: give the unit of the deviation",
        ),
        (
            one_test(),
            json!("angle (deg);deviation (furlong);direction\n1;2;ccw\n"),
            "csv: line 1: give the unit of the deviation",
        ),
        (
            one_test(),
            json!("angle (grad);deviation (µm)\n1;2\n"),
            "csv: line 1: the angle's unit must be deg or rad",
        ),
        (
            one_test(),
            json!("angle (deg);c (deg);deviation (µm)\n1;1;2\n"),
            "csv: line 1: two columns for the angle",
        ),
        (
            one_test(),
            json!("angle (deg);ccw (µm)\n1;2\n"),
            "csv: line 1: one column per direction needs both",
        ),
        (
            one_test(),
            json!(format!("{head}0;1;ccw\n30;2\n")),
            "csv: line 3: expected 3 columns like the header, got 2",
        ),
        (
            one_test(),
            json!(format!("{head}0;1;ccw\n\n30;1,2,3;ccw\n")),
            "csv: line 4: deviation \"1,2,3\" is not a number",
        ),
        (
            one_test(),
            json!(format!("{head}0;1;ccw\nx;1;ccw\n")),
            "csv: line 3: angle \"x\" is not a number",
        ),
        (
            one_test(),
            json!(format!("{head}0;1;ccw\n30;1;sideways\n")),
            "csv: line 3: the direction must be ccw or cw",
        ),
        (
            one_test(),
            json!(format!("{head}0;1;ccw\n")),
            "csv: test 1 has 1 measured point: give at least 8",
        ),
        (
            one_test(),
            json!(format!("test;{head}1;0;1;ccw\n;30;1;ccw\n")),
            "csv: line 3: the test is empty",
        ),
        (
            one_test(),
            json!(format!("test;{head}1;0;1;ccw\n9;30;1;ccw\n")),
            "csv: line 3: test \"9\" is not one of the tests (1)",
        ),
        (
            two.clone(),
            json!(format!("{head}{rows}")),
            "csv: the file has no test column but 2 tests are defined",
        ),
        (
            tilt,
            json!(format!("{head}0;1;ccw\n150;1;ccw\n")),
            "csv: line 3: B = 150° is outside its travel",
        ),
        (
            json!([]),
            json!(format!("{head}0;1;ccw\n# a note\n30;1e400;ccw\n")),
            "csv: line 4: deviation \"1e400\" is not a number",
        ),
    ];
    for (tests, csv, want) in cases {
        let e = identify(json!({ "machine": m, "tests": tests, "csv": csv })).unwrap_err();
        assert!(e.starts_with(want), "got: {e}\nwant: {want}");
    }
    // A test's own file: its messages name its path.
    let mut tests = two.clone();
    tests[0]["csv"] = json!(g);
    tests[1]["csv"] = json!(format!("{head}0;1;ccw\n30;x;ccw\n"));
    let e = identify(json!({ "machine": m, "tests": tests })).unwrap_err();
    assert!(
        e.starts_with("tests[1].csv: line 3: deviation \"x\" is not a number"),
        "{e}"
    );
    tests[1]["csv"] = json!(format!("test;{head}1;0;1;ccw\n"));
    let e = identify(json!({ "machine": m, "tests": tests })).unwrap_err();
    assert!(
        e.starts_with("tests[1].csv: line 2: test \"1\" in the file of test ax"),
        "{e}"
    );
    tests[1]["csv"] = json!("");
    let e = identify(json!({ "machine": m, "tests": tests })).unwrap_err();
    assert!(
        e.starts_with("tests[1].csv: test ax has 0 measured points"),
        "{e}"
    );
    // A bad test definition names its path.
    let e = identify(json!({ "machine": m, "tests": [{ "lenght": 100 }], "csv": g })).unwrap_err();
    assert!(e.starts_with("tests[0].lenght: unknown input"), "{e}");
    let e = identify(json!({ "machine": m, "tests": [{ "ball": { "x": 0, "y": 0 } }], "csv": g }))
        .unwrap_err();
    assert!(
        e.starts_with("tests[0].ball: the table ball lies on the C axis line"),
        "{e}"
    );
}

#[test]
fn decimal_commas_units_tabs_crlf_and_the_test_column_read_alike() {
    let m = with_errors(&bc_table(), json!({ "E_X0C": 0.012, "E_Y0C": -0.004 }));
    let g = good(&m);
    // One radial test cannot tell the line's offset from its tilt at the ball's height: the
    // offsets alone are fitted.
    let only = json!(["E_X0C", "E_Y0C"]);
    let base = identify(json!({ "machine": m, "tests": one_test(), "csv": g, "parameters": only }))
        .unwrap();
    let value = |r: &Value| r["errors"]["E_X0C"].as_f64().unwrap();
    assert!((value(&base) - 0.012).abs() < 1e-5, "{}", base["errors"]);
    // The same in mm with points, commas; in rad; with tabs, CRLF, a BOM; as two columns.
    let mut variants: Vec<String> = Vec::new();
    let rows: Vec<(f64, f64, String)> = g
        .lines()
        .skip(1)
        .map(|l| {
            let c: Vec<&str> = l.split(';').collect();
            let n = |s: &str| s.replace(',', ".").parse::<f64>().unwrap();
            (n(c[0]), n(c[1]), c[2].to_string())
        })
        .collect();
    variants.push(
        std::iter::once("angle_deg,deviation_mm,dir,operator".to_string())
            .chain(
                rows.iter()
                    .map(|(a, d, r)| format!("{a},{},{r},somebody", d / 1e3)),
            )
            .collect::<Vec<_>>()
            .join("\n"),
    );
    variants.push(
        std::iter::once("\u{feff}Angle [rad]\tDeviation [um]\tSense".to_string())
            .chain(rows.iter().map(|(a, d, r)| {
                format!(
                    "{}\t{d}\t{}",
                    a.to_radians(),
                    if r == "ccw" { "+" } else { "-" }
                )
                .replace('.', ",")
            }))
            .collect::<Vec<_>>()
            .join("\r\n"),
    );
    let ccw: Vec<&(f64, f64, String)> = rows.iter().filter(|r| r.2 == "ccw").collect();
    variants.push(
        std::iter::once(
            "# the bar's length change both ways\nangle (deg); ccw (µm); cw (µm)".to_string(),
        )
        .chain(ccw.iter().map(|(a, d, _)| {
            let back = rows.iter().find(|r| r.2 == "cw" && r.0 == *a).unwrap();
            format!("{a}; {d}; {}", back.1)
        }))
        .collect::<Vec<_>>()
        .join("\n"),
    );
    for (i, v) in variants.iter().enumerate() {
        let r =
            identify(json!({ "machine": m, "tests": one_test(), "csv": v, "parameters": only }))
                .unwrap();
        assert!(
            (value(&r) - value(&base)).abs() < 1e-9,
            "variant {i}: {} vs {}",
            value(&r),
            value(&base)
        );
        assert_eq!(r["tests"][0]["points"], 26);
    }
    let r = identify(
        json!({ "machine": m, "tests": one_test(), "csv": variants[0], "parameters": only }),
    )
    .unwrap();
    assert_eq!(r["ignored"], json!(["operator"]));
    assert_eq!(r["tests"][0]["lines"][1], 3);
    // Two tests in one file by a test column, by name and by number; or each its own file.
    let m = with_errors(&bc_table(), json!({ "E_X0C": 0.012, "E_A0C": 0.002 }));
    let tests = json!([
        { "ball": { "x": 150, "y": 0, "height": 50 }, "step": 30 },
        { "ball": { "x": 150, "y": 0, "height": 50 }, "step": 30, "direction": "axial", "name": "Axial" }
    ]);
    let s = call(
        "ballbarRotarySimulate",
        &json!({ "machine": m, "tests": tests }),
    )
    .unwrap();
    let file = s["csv"].as_str().unwrap();
    assert!(
        file.contains("\ntest;angle (deg);deviation (µm);direction\n1;0;"),
        "{file}"
    );
    let by_name = identify(json!({ "machine": m, "tests": tests, "csv": file })).unwrap();
    let by_number =
        identify(json!({ "machine": m, "tests": tests, "csv": file.replace("\nAxial;", "\n2;") }))
            .unwrap();
    assert_eq!(by_name["identification"], by_number["identification"]);
    let mut own = tests.clone();
    for (i, name) in ["1", "Axial"].iter().enumerate() {
        let lines: String = file
            .lines()
            .filter(|l| l.starts_with(&format!("{name};")))
            .map(|l| format!("{}\n", &l[name.len() + 1..]))
            .collect();
        own[i]["csv"] = json!(format!("angle (deg);deviation (µm);direction\n{lines}"));
    }
    let separate = identify(json!({ "machine": m, "tests": own })).unwrap();
    assert_eq!(separate["identification"], by_name["identification"]);
    // The axial test sees the tilt: both errors found.
    for (n, v) in [("E_X0C", 0.012), ("E_A0C", 0.002)] {
        let got = by_name["errors"][n].as_f64().unwrap();
        assert!((got - v).abs() < 1e-3 * v, "{n}: {got}");
    }
}

#[test]
fn one_file_goes_through_the_rotary_identification_and_the_reversal_study() {
    // The C test's file (C once round each way, decimal comma, µm) ...
    let m = with_errors(&bc_table(), json!({ "E_X0C": 0.012 }));
    let tests = json!([{ "ball": { "x": 150, "y": 0, "height": 50 }, "step": 1 }]);
    let s = call(
        "ballbarRotarySimulate",
        &json!({ "machine": m, "tests": tests }),
    )
    .unwrap();
    let file = s["csv"].as_str().unwrap().replace('.', ",");
    let r = identify(
        json!({ "machine": m, "tests": tests, "csv": file, "parameters": ["E_X0C", "E_Y0C"] }),
    )
    .unwrap();
    assert!((r["errors"]["E_X0C"].as_f64().unwrap() - 0.012).abs() < 1e-5);
    // ... is read by the reversal study: its ccw run is the trace, the cw run counted unused,
    // and the dent measured (none: no friction here, the trace is the offset's cosine).
    let t = call("reversalTrace", &json!({ "csv": file })).unwrap();
    assert_eq!(t["points"], 361);
    assert_eq!(t["skipped"], 361);
    let dent = t["dent"]["depth"].as_f64().unwrap();
    // Falling from 170° to 190°: −e·cos C at most e·(1 − cos 10°) = 0.18 µm below its level.
    assert!(
        dent < 0.012 * (1.0 - 10f64.to_radians().cos()) + 1e-9,
        "{dent}"
    );
    let m = parse_trace(&file).unwrap();
    assert_eq!(m.angle.len(), 361);
    // Three comment lines, the header, then the first point.
    assert_eq!(m.lines[0], 5);
    // The reversal study's own sample, rewritten in the rotary tests' format (a test column,
    // µm, decimal comma, a direction column), reads point for point as the original and fits
    // as the sample test expects (the intervals hold the values it was made with).
    let text = std::fs::read_to_string(SAMPLE).unwrap();
    let mut rewritten = String::from("# machine: B/C tilting table, vertical spindle (Li et al. 2021)\ntest;angle (deg);deviation (µm);direction\n");
    for l in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let (a, d) = l.split_once(',').unwrap();
        let um = d.parse::<f64>().unwrap() * 1e3;
        rewritten.push_str(&format!("reversal;{a};{um:.4};ccw\n").replace('.', ","));
    }
    let (old, new) = (
        parse_trace(&text).unwrap(),
        parse_trace(&rewritten).unwrap(),
    );
    assert_eq!(old.angle.len(), new.angle.len());
    for i in 0..old.angle.len() {
        assert!((old.angle[i] - new.angle[i]).abs() < 1e-12);
        assert!((old.deviation[i] - new.deviation[i]).abs() < 1e-12);
    }
    let f = call("reversalFit", &json!({ "csv": rewritten })).unwrap();
    for (k, v) in [
        ("friction", 12.0),
        ("frictionSlope", 800.0),
        ("positionGain", 28.0),
    ] {
        let (lo, hi) = (
            f[k]["low"].as_f64().unwrap(),
            f[k]["high"].as_f64().unwrap(),
        );
        assert!(lo <= v && v <= hi, "{k}: {lo} to {hi} should hold {v}");
    }
    assert_eq!(f["skipped"], 0);
    // Several tests in one file are refused by the circular test (ISO 230-4) and the reversal
    // study, and a cw run alone by the reversal study.
    let two = format!("{rewritten}other;1;0;ccw\n");
    let e = call("ballbarEvaluate", &json!({ "csv": two, "radius": 50 }))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("csv: the file holds 2 tests (reversal, other)"),
        "{e}"
    );
    let e = parse_trace(&format!("{rewritten}other;1;0;ccw\n"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("the file holds 2 tests (reversal, other)"),
        "{e}"
    );
    let e = parse_trace("angle (deg);deviation (µm);direction\n1;0;cw\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("clockwise (cw) points only"), "{e}");
}
