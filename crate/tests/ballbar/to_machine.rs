//! The ball-bar's squareness as the machine's ISO 230-1 location error, its sign fixed by the one
//! kinematic chain: a machine is built with `E_C0Y`, `E_A0Z` or `E_B0Z` = `s`; the control
//! commands a circle of the plane (the tool tip relative to the workpiece, nominal inverse
//! kinematics); the chain with the error gives where the tool actually is; its distance from the
//! ball-bar's pivot (fixed on the table at the commanded centre) less the radius is the trace the
//! ball-bar records; that trace, evaluated, must propose the same error `s`.
//!
//! Nothing here uses the ball-bar module's fault models: the trace comes from the chain alone.
//! Tolerance: the squareness enters the radial deviation to first order (`R·α/2·sin 2θ`); what
//! is left is of order `R·s²`, a relative error of order `s` (below 2e-4 for the 0.01° used),
//! so `|proposed − s| ≤ 1e-3·|s|`.

#![allow(clippy::unwrap_used)]

use fiveaxis::api::ApiInput;
use fiveaxis::ballbar::{evaluate, Ballbar, BallbarInput};
use fiveaxis::chain::Setup;
use fiveaxis::machine::{Machine, Model};
use fiveaxis::schema::Inputs;
use nalgebra::Vector3;
use serde_json::{json, Value};

const R: f64 = 150.0;

/// The plane's name, `u`, `v` (unit vectors) and its squareness error.
const PLANES: [(&str, [f64; 3], [f64; 3], &str); 3] = [
    ("XY", [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], "E_C0Y"),
    ("YZ", [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], "E_A0Z"),
    ("ZX", [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], "E_B0Z"),
];

fn machine(kind: &str, linear: &str, errors: Value) -> Model {
    Machine::from_value(
        &json!({ "kind": kind, "linear": linear, "errors": errors }),
        "machine",
    )
    .unwrap()
    .build()
    .unwrap()
}

/// The ball-bar trace (every 1°, both ways, µm) of `model` interpolating a circle of radius `R`
/// in the plane `(u, v)` about `centre` (workpiece coordinates), the rotary axes at zero.
fn trace(
    model: &Model,
    u: Vector3<f64>,
    v: Vector3<f64>,
    centre: Vector3<f64>,
    setup: &Setup,
) -> String {
    let q0 = model.positions(0.0, 0.0);
    let mut out = format!("# radius: {R} mm\nangle (deg); deviation (µm); direction\n");
    for name in ["ccw", "cw"] {
        for k in 0..360 {
            let th = (k as f64 + 0.5).to_radians();
            let tip = centre + R * (th.cos() * u + th.sin() * v);
            // What the control commands for that tip (its own, error-free model) ...
            let q = model.nominal().solve_linear(&tip, &q0).unwrap();
            // ... and where the tool then is, relative to the workpiece.
            let actual = model.chain.tool_pose(&q, true, setup).unwrap().tip;
            let dr = (actual - centre).norm() - R;
            out.push_str(&format!("{}; {}; {name}\n", th.to_degrees(), dr * 1e3));
        }
    }
    out
}

fn run(csv: &str, plane: &str) -> Ballbar {
    evaluate(&BallbarInput::read(&json!({ "csv": csv, "plane": plane })).unwrap()).unwrap()
}

/// The result's errors as JavaScript sees them (API units: degrees).
fn proposed(b: &Ballbar) -> serde_json::Map<String, Value> {
    serde_json::to_value(b).unwrap()["errors"]
        .as_object()
        .unwrap()
        .clone()
}

#[test]
fn the_squareness_proposed_is_the_error_the_machine_was_built_with() {
    // 0.01° = 174.5 µm/m, either sign; every kind of machine and every layout of its linear axes
    // but the cross table (below); the workpiece set as the volumetric map sets it (none) and at
    // the pose (Li et al.'s set-up).
    let centre = Vector3::new(40.0, -25.0, 60.0);
    let mut checked = 0;
    for kind in ["table-table", "head-table", "head-head"] {
        for linear in ["spindle-xyz", "table-y", "table-x", "table-z", "table-xy"] {
            for (plane, u, v, name) in PLANES {
                if linear == "table-xy" && plane == "XY" {
                    continue;
                }
                for s in [0.01, -0.01] {
                    let model = machine(kind, linear, json!({ name: s }));
                    let setups = [Setup::None, Setup::AtPose(model.positions(0.0, 0.0))];
                    for setup in &setups {
                        let (u, v) = (Vector3::from(u), Vector3::from(v));
                        let b = run(&trace(&model, u, v, centre, setup), plane);
                        let e = proposed(&b);
                        let case = format!("{kind}, {linear}, {plane}, {name} = {s}°, {setup:?}");
                        assert_eq!(e.keys().collect::<Vec<_>>(), [name], "{case}");
                        let got = e[name].as_f64().unwrap();
                        assert!((got - s).abs() <= 1e-3 * s.abs(), "{case}: proposed {got}°");
                        checked += 1;
                    }
                }
            }
        }
    }
    assert_eq!(checked, 3 * (5 * 3 - 1) * 2 * 2);
}

/// The words for each plane, from the error table's descriptions: a positive `E_C0Y` opens X and
/// Y beyond 90°, so Y leans towards −X; a positive `E_A0Z` leans Z towards −Y; a positive
/// `E_B0Z` leans Z towards +X, which in ZX (u = Z, v = X) is X leaning towards +Z.
#[test]
fn the_words_say_which_way_the_axis_leans() {
    let model_centre = Vector3::new(0.0, 0.0, 50.0);
    let words = [
        ("XY", "Y leans towards −X", "further apart"),
        ("YZ", "Z leans towards −Y", "further apart"),
        ("ZX", "X leans towards +Z", "closer"),
    ];
    for ((plane, u, v, name), (_, lean, angle)) in PLANES.into_iter().zip(words) {
        let model = machine("table-table", "spindle-xyz", json!({ name: 0.002 }));
        let b = run(
            &trace(
                &model,
                Vector3::from(u),
                Vector3::from(v),
                model_centre,
                &Setup::None,
            ),
            plane,
        );
        let m = b.errors_meaning.unwrap();
        assert!(m.contains(lean) && m.contains(angle), "{plane}: {m}");
        assert_eq!(b.axes, [&plane[..1], &plane[1..]]);
    }
}

/// On a cross table with Y on the bed carrying X, `E_C0Y` turns X with Y: the table turns as a
/// whole, the circle stays round, and the XY test cannot see it (the module docs say so).
#[test]
fn on_a_cross_table_e_c0y_turns_x_with_y_and_the_circle_stays_round() {
    let model = machine("table-table", "table-xy", json!({ "E_C0Y": 0.01 }));
    let b = run(
        &trace(
            &model,
            Vector3::x(),
            Vector3::y(),
            Vector3::new(10.0, 20.0, 30.0),
            &Setup::None,
        ),
        "XY",
    );
    assert!(b.g < 1e-9, "G {} mm", b.g);
}

/// The errors proposed, entered into a machine as they are (JSON, degrees), make the trace they
/// came from: a trace of squareness alone, synthesised from the ball-bar's own definition (v
/// leans towards +u by α: the tool at `u + α·v` for the command `(u, v)`), gives an error whose
/// machine's trace has the same squareness.
#[test]
fn the_errors_proposed_entered_into_a_machine_give_the_same_squareness_back() {
    let alpha = 30e-6; // rad, 30 µm/m
    let mut csv = format!("# radius: {R} mm\nangle (deg); deviation (µm); direction\n");
    for name in ["ccw", "cw"] {
        for k in 0..360 {
            let th = (k as f64 + 0.5).to_radians();
            let (u, v) = (R * th.cos(), R * th.sin());
            let dr = (u + alpha * v).hypot(v) - R;
            csv.push_str(&format!("{}; {}; {name}\n", th.to_degrees(), dr * 1e3));
        }
    }
    for (plane, u, v, _) in PLANES {
        let first = run(&csv, plane);
        let sq = first.diagnostics.squareness.value.unwrap();
        assert!((sq - 30.0).abs() < 0.03, "{plane}: {sq} µm/m");
        let errors = proposed(&first);
        let model = machine("head-table", "spindle-xyz", Value::Object(errors.clone()));
        let again = run(
            &trace(
                &model,
                Vector3::from(u),
                Vector3::from(v),
                Vector3::new(0.0, 0.0, 80.0),
                &Setup::None,
            ),
            plane,
        );
        let sq2 = again.diagnostics.squareness.value.unwrap();
        assert!(
            (sq2 - sq).abs() < 0.03,
            "{plane}: {errors:?} gives {sq2} µm/m, not {sq}"
        );
    }
}

#[test]
fn one_direction_proposes_nothing_and_says_why() {
    let model = machine("table-table", "spindle-xyz", json!({ "E_C0Y": 0.002 }));
    let csv = trace(
        &model,
        Vector3::x(),
        Vector3::y(),
        Vector3::zeros(),
        &Setup::None,
    );
    let ccw: String = csv
        .lines()
        .filter(|l| !l.ends_with("cw") || l.ends_with("ccw"))
        .map(|l| format!("{l}\n"))
        .collect();
    let b = run(&ccw, "XY");
    assert!(proposed(&b).is_empty());
    assert_eq!(b.errors_meaning, None);
    assert!(
        b.not_sent[0].contains("one direction only"),
        "{:?}",
        b.not_sent
    );
    // Both ways: the other faults are listed as not sent, the squareness is not among them.
    let b = run(&csv, "XY");
    assert!(b.not_sent.iter().any(|l| l.starts_with("backlash")));
    assert!(b.not_sent.iter().all(|l| !l.starts_with("squareness")));
}

#[test]
fn a_plane_that_is_not_one_is_refused_with_its_path() {
    let e = BallbarInput::read(&json!({ "csv": "", "plane": "XZ" })).unwrap_err();
    assert_eq!(e.field, "plane");
}

/// A squareness beyond what the machine accepts (±5°) is not proposed, and the words say why: a
/// 1 mm bar with 50 µm of `sin 2θ` is α = 2·0.05/1 = 0.1 rad, 5.7°.
#[test]
fn a_squareness_beyond_the_machines_limit_is_not_proposed() {
    let mut csv = "# radius: 1 mm\nangle (deg); deviation (µm); direction\n".to_string();
    for name in ["ccw", "cw"] {
        for k in 0..360 {
            let th = (k as f64 + 0.5).to_radians();
            csv.push_str(&format!(
                "{}; {}; {name}\n",
                th.to_degrees(),
                50.0 * (2.0 * th).sin()
            ));
        }
    }
    let b = run(&csv, "XY");
    let sq = b.diagnostics.squareness.value.unwrap();
    assert!((sq - 1e5).abs() < 1.0, "{sq} µm/m");
    assert!(proposed(&b).is_empty());
    let m = b.errors_meaning.unwrap();
    assert!(
        m.contains("not sent: E_C0Y = -5.7296° is beyond the machine's limit of ±5°"),
        "{m}"
    );
}
