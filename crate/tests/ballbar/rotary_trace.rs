//! The simulated ball-bar tests with a rotary axis moving (issue 32), checked pose by pose
//! against computations written out here:
//! * a closed form: the C axis line of a B/C table off by `e` along X (or Y) gives a radial
//!   bar `√(L² − 2·L·e·cos(φ − C) + e²) − L` (and a tangential bar `… + 2·L·e·sin(φ − C) …`),
//!   once per turn;
//! * the machine's chain composed by hand from its documented geometry (crate/src/machine's
//!   module docs): each table axis `T(offset)·D(error)·R(−q)`, each head axis `T(offset)·
//!   D(error)·R(+q)`, the linear axes translations, with `D = T(x, y, z)·R_X(a)·R_Y(b)·R_Z(c)`
//!   built here from nalgebra's rotations; the balls at `F_work·p` and `F_tool·0`, on three
//!   machines with errors of both rotary axes, for C tests (radial, tangential, axial) and tilt
//!   tests;
//! * the commanded pose keeps the ideal machine's bar at its length;
//! * the first-order length change is within the second order of the exact one;
//! * the study's building blocks at their documented edges: the default sweep of a moving
//!   axis, the travel test, the number of tests, the machine checked, the tool ball's
//!   displacement, and the first-order length change with error motions alone (found by
//!   cargo-mutants, scope `ballbar`: each was reached by no test at its edge).
#![allow(clippy::unwrap_used, clippy::needless_range_loop)]
use crate::probe_common;

use fiveaxis::api::{call, ApiInput};
use fiveaxis::ballbar::rotary::{default_sweep, BallbarRotaryInput, Study, MAX_TESTS};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use probe_common::{ac_trunnion, bc_table, head_table, numbers, with_errors};
use serde_json::{json, Value};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

const L: f64 = 100.0;

fn simulate(machine: &Value, tests: Value) -> Value {
    call(
        "ballbarRotarySimulate",
        &json!({ "machine": machine, "tests": tests }),
    )
    .unwrap()
}

/// A test's held angle and its sweep lie within their axes' travel (B −120° to 120° on the B/C
/// table): the ends are accepted, a degree beyond either is refused at the field, naming the
/// axis and its travel. A sweep of more than MAX_POINTS points is refused at its step.
// Found by cargo-mutants: the held angle's travel check and the points' limit (`place`) were
// untested.
#[test]
fn a_held_angle_or_a_sweep_beyond_the_travel_is_refused_at_its_field() {
    let machine = bc_table();
    let c_test = |hold: f64| json!([{ "ball": { "x": 150, "y": 0, "height": 50 }, "step": 30, "hold": hold }]);
    let b_test = |from: f64, to: f64, step: f64| json!([{ "axis": "m", "ball": { "x": 120, "y": -30, "height": 40 }, "step": step, "from": from, "to": to }]);
    let run = |tests: Value| {
        call(
            "ballbarRotarySimulate",
            &json!({ "machine": machine, "tests": tests }),
        )
        .map_err(|e| e.to_string())
    };
    // C turns endlessly: 500° in steps of 0.05° is 10 000 points each way, within MAX_POINTS
    // (20 000); 2000° is 40 000.
    let c_sweep = |from: f64, to: f64| json!([{ "ball": { "x": 150, "y": 0, "height": 50 }, "step": 0.05, "from": from, "to": to }]);
    let ok = [
        c_test(-120.0),
        c_test(120.0),
        b_test(-120.0, 120.0, 10.0),
        c_sweep(-250.0, 250.0),
    ];
    for t in ok {
        assert!(run(t.clone()).is_ok(), "{t}: {:?}", run(t.clone()).err());
    }
    let travel = "is outside its travel (-120° to 120°)";
    for (tests, want) in [
        (c_test(121.0), format!("tests[0].hold: B = 121° {travel}")),
        (c_test(-121.0), format!("tests[0].hold: B = -121° {travel}")),
        (
            b_test(-121.0, 120.0, 10.0),
            format!("tests[0].from: B = -121° {travel}"),
        ),
        (
            b_test(-120.0, 121.0, 10.0),
            format!("tests[0].to: B = 121° {travel}"),
        ),
        (
            c_sweep(-1000.0, 1000.0),
            "tests[0].step: 0.05° over 2000°: more than 20000 points; take a larger step".into(),
        ),
    ] {
        let e = run(tests).unwrap_err();
        assert!(e.starts_with(&want), "{e}");
    }
}

/// The table ball is where its test puts it: x, y on the face and its height along the spindle
/// (on the B/C table with a vertical spindle, the face's axes are X and Y, its normal Z), in
/// the frame the result reports it in.
// Found by cargo-mutants: the ball's position was only ever read back from the result.
#[test]
fn the_table_ball_is_at_its_x_y_and_height() {
    let s = simulate(
        &bc_table(),
        json!([{ "ball": { "x": 150, "y": 20, "height": 60 }, "step": 30 }]),
    );
    assert_eq!(numbers(&s["tests"][0]["ball"]), vec![150.0, 20.0, 60.0]);
}

#[test]
fn an_offset_of_the_c_axis_line_gives_the_closed_form_once_per_turn() {
    let (r, h) = (120.0_f64, 40.0);
    for (phi_deg, x, y) in [(0.0, r, 0.0), (30.0_f64, 0.0, 0.0)] {
        let (x, y) = if x == 0.0 {
            (
                r * phi_deg.to_radians().cos(),
                r * phi_deg.to_radians().sin(),
            )
        } else {
            (x, y)
        };
        let phi = phi_deg.to_radians();
        for (name, e) in [("E_X0C", 0.012), ("E_Y0C", -0.02)] {
            let m = with_errors(&bc_table(), json!({ name: e }));
            let s = simulate(
                &m,
                json!([
                    { "ball": { "x": x, "y": y, "height": h }, "length": L, "step": 5 },
                    { "ball": { "x": x, "y": y, "height": h }, "length": L, "step": 5, "direction": "tangential" }
                ]),
            );
            for (ti, tangential) in [(0, false), (1, true)] {
                let t = &s["tests"][ti];
                let angle = numbers(&t["angle"]);
                let dev = numbers(&t["deviation"]);
                assert_eq!(angle.len(), 2 * 73);
                let mut largest: f64 = 0.0;
                for (a, d) in angle.iter().zip(&dev) {
                    let c = a.to_radians();
                    // The offset's component along the bar, in the machine frame.
                    let (cx, sx) = ((phi - c).cos(), (phi - c).sin());
                    let along = match (name, tangential) {
                        ("E_X0C", false) => cx,
                        ("E_Y0C", false) => sx,
                        ("E_X0C", true) => -sx,
                        _ => cx,
                    };
                    let want = (L * L - 2.0 * L * e * along + e * e).sqrt() - L;
                    assert!(
                        (d - want).abs() < 1e-11,
                        "{name} {} φ {phi_deg} at C {a}: {d} vs {want}",
                        if tangential { "tangential" } else { "radial" }
                    );
                    largest = largest.max(d.abs());
                }
                // Once per turn with the offset's amplitude.
                assert!((largest - e.abs()).abs() < 1e-6, "{largest}");
            }
        }
    }
}

/// `D = T(x, y, z)·R_X(a)·R_Y(b)·R_Z(c)` of an axis's location errors (mm, rad).
fn d(e: [f64; 6]) -> Isometry3<f64> {
    let r = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), e[3])
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), e[4])
        * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), e[5]);
    Isometry3::from_parts(Translation3::new(e[0], e[1], e[2]), r)
}

fn turn(axis: char, q: f64) -> Isometry3<f64> {
    let a = match axis {
        'A' => Vector3::x_axis(),
        'B' => Vector3::y_axis(),
        _ => Vector3::z_axis(),
    };
    Isometry3::from_parts(
        Translation3::identity(),
        UnitQuaternion::from_axis_angle(&a, q),
    )
}

fn shift(v: Vector3<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(v), UnitQuaternion::identity())
}

/// The six location errors of axis `axis` in engine units from API `errors`.
fn loc(errors: &Value, axis: char) -> [f64; 6] {
    let mut out = [0.0; 6];
    for (k, c) in ['X', 'Y', 'Z', 'A', 'B', 'C'].iter().enumerate() {
        let v = errors
            .get(format!("E_{c}0{axis}"))
            .and_then(Value::as_f64)
            .unwrap_or(0.0);
        out[k] = if k >= 3 { v.to_radians() } else { v };
    }
    out
}

/// The balls in the machine frame by hand: `(table ball, tool ball)` at positions `q` (by axis
/// letter, mm and rad) for the three machines of the issue (geometry from their presets).
fn balls(
    kind: &str,
    errors: &Value,
    q: &dyn Fn(char) -> f64,
    p: Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>) {
    let lin = shift(Vector3::new(q('X'), q('Y'), q('Z')));
    match kind {
        // B on the bed carrying C, the table surface at the B axis, tool tip at the nose.
        "bc" => {
            let fw =
                d(loc(errors, 'B')) * turn('B', -q('B')) * d(loc(errors, 'C')) * turn('C', -q('C'));
            (
                (fw * Point3::from(p)).coords,
                (lin * Point3::origin()).coords,
            )
        }
        // A on the bed carrying C, table surface 100 mm above, tool tip 100 mm below the nose.
        "ac" => {
            let fw = d(loc(errors, 'A'))
                * turn('A', -q('A'))
                * d(loc(errors, 'C'))
                * turn('C', -q('C'))
                * shift(Vector3::new(0.0, 0.0, 100.0));
            let ft = lin * shift(Vector3::new(0.0, 0.0, -100.0));
            (
                (fw * Point3::from(p)).coords,
                (ft * Point3::origin()).coords,
            )
        }
        // C table; X, Y, Z then the B head, the tip 300 mm below B's axis.
        _ => {
            let fw = d(loc(errors, 'C')) * turn('C', -q('C'));
            let ft = lin
                * d(loc(errors, 'B'))
                * turn('B', q('B'))
                * shift(Vector3::new(0.0, 0.0, -300.0));
            (
                (fw * Point3::from(p)).coords,
                (ft * Point3::origin()).coords,
            )
        }
    }
}

#[test]
fn every_pose_matches_the_chain_composed_by_hand_on_three_machines() {
    let cases = [
        (
            "bc",
            bc_table(),
            json!({ "E_X0C": 0.012, "E_Y0C": -0.008, "E_Z0C": 0.005, "E_A0C": 0.003, "E_B0C": -0.002, "E_C0C": 0.004,
            "E_X0B": -0.006, "E_Z0B": 0.01, "E_A0B": 0.002, "E_B0B": 0.003, "E_C0B": -0.001 }),
        ),
        (
            "ac",
            ac_trunnion(),
            json!({ "E_X0C": -0.01, "E_Y0C": 0.007, "E_A0C": -0.002, "E_B0C": 0.004, "E_C0C": 0.002,
            "E_Y0A": 0.009, "E_Z0A": -0.011, "E_A0A": 0.003, "E_B0A": 0.001, "E_C0A": -0.002 }),
        ),
        (
            "ht",
            head_table(),
            json!({ "E_X0C": 0.015, "E_Y0C": 0.004, "E_A0C": 0.002, "E_B0C": -0.003,
            "E_X0B": 0.008, "E_Z0B": -0.005, "E_A0B": 0.002, "E_C0B": 0.003, "E_B0B": -0.002 }),
        ),
    ];
    let mut checked = 0;
    for (kind, machine, errors) in cases {
        let m = with_errors(&machine, errors.clone());
        let tests = json!([
            { "ball": { "x": 150, "y": 20, "height": 60 }, "step": 10 },
            { "ball": { "x": 150, "y": 20, "height": 60 }, "step": 10, "direction": "tangential", "hold": 20 },
            { "ball": { "x": 150, "y": 20, "height": 60 }, "step": 10, "direction": "axial" },
            { "axis": "m", "ball": { "x": 120, "y": -30, "height": 40 }, "step": 5, "from": -60, "to": 30 },
            { "axis": "m", "ball": { "x": 120, "y": -30, "height": 40 }, "step": 5, "from": -60, "to": 30, "direction": "axial", "hold": 45 }
        ]);
        let s = simulate(&m, tests.clone());
        let nominal = simulate(&machine, tests);
        for (ti, t) in s["tests"].as_array().unwrap().iter().enumerate() {
            let p = Vector3::from_iterator(numbers(&t["ball"]));
            let tool_w = Vector3::from_iterator(numbers(&t["toolBall"]));
            assert!(((tool_w - p).norm() - L).abs() < 1e-12);
            let cmd: Vec<(char, String, Vec<f64>)> = t["commanded"]
                .as_array()
                .unwrap()
                .iter()
                .map(|a| {
                    (
                        a["name"].as_str().unwrap().chars().next().unwrap(),
                        a["unit"].as_str().unwrap().to_string(),
                        numbers(&a["values"]),
                    )
                })
                .collect();
            let dev = numbers(&t["deviation"]);
            let tool = [0, 1, 2].map(|k| numbers(&t["tool"][k]));
            let table = [0, 1, 2].map(|k| numbers(&t["table"][k]));
            for i in 0..dev.len() {
                let q = |axis: char| -> f64 {
                    let (_, unit, v) = cmd.iter().find(|c| c.0 == axis).unwrap();
                    if unit == "deg" {
                        v[i].to_radians()
                    } else {
                        v[i]
                    }
                };
                // The ideal machine at the commanded pose: the bar at its length, the tool ball
                // where the table ball's frame puts tool_w.
                let (pn, tn) = balls(kind, &json!({}), &q, p);
                let (pw, _) = balls(kind, &json!({}), &q, tool_w);
                assert!(
                    ((tn - pn).norm() - L).abs() < 1e-9,
                    "{kind} test {ti}: nominal bar"
                );
                assert!(
                    (tn - pw).norm() < 1e-9,
                    "{kind} test {ti}: tool ball off its place"
                );
                // With the errors.
                let (pa, ta) = balls(kind, &errors, &q, p);
                let want = (ta - pa).norm() - L;
                assert!(
                    (dev[i] - want).abs() < 1e-10,
                    "{kind} test {ti} point {i}: {} vs {want}",
                    dev[i]
                );
                for k in 0..3 {
                    assert!((tool[k][i] - ta[k]).abs() < 1e-9);
                    assert!((table[k][i] - pa[k]).abs() < 1e-9);
                }
                checked += 1;
            }
            // Every test sees something of these errors (no vacuous check), and the ideal
            // machine's bar stays at its length.
            let spread = t["spread"].as_f64().unwrap();
            assert!(spread > 1e-3, "{kind} test {ti}: {spread}");
            let flat = numbers(&nominal["tests"][ti]["deviation"]);
            assert!(
                flat.iter().all(|d| d.abs() < 1e-11),
                "{kind} {ti}: {flat:?}"
            );
        }
    }
    // 3 machines × (3 C tests × 2 × 37 + 2 tilt tests × 2 × 19 points).
    assert_eq!(checked, 3 * (3 * 2 * 37 + 2 * 2 * 19));
}

#[test]
fn the_first_order_change_is_within_the_second_order_of_the_exact_one() {
    // Errors of 10 µm and 0.003°: the remainder is of order |δ|²/L plus the chain's own
    // products of errors and lever arms, far below 0.1 µm; the errors move the bar by tens of µm.
    for (machine, errors) in [
        (
            bc_table(),
            json!({ "E_X0C": 0.01, "E_A0C": 0.003, "E_Z0B": -0.01, "E_B0B": 0.003 }),
        ),
        (
            ac_trunnion(),
            json!({ "E_Y0C": 0.01, "E_B0C": -0.003, "E_Y0A": 0.01, "E_C0A": 0.003 }),
        ),
        (
            head_table(),
            json!({ "E_X0C": 0.01, "E_A0B": 0.003, "E_X0B": -0.01, "E_B0C": 0.003 }),
        ),
    ] {
        let s = simulate(
            &with_errors(&machine, errors),
            json!([
                { "ball": { "x": 150, "y": 0, "height": 60 }, "step": 5 },
                { "axis": "m", "ball": { "x": 120, "y": 30, "height": 40 }, "step": 5, "from": -60, "to": 30, "direction": "tangential" }
            ]),
        );
        for t in s["tests"].as_array().unwrap() {
            let (dev, first) = (numbers(&t["deviation"]), numbers(&t["firstOrder"]));
            let big = dev.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            assert!(big > 0.005, "{big}");
            for (a, b) in dev.iter().zip(&first) {
                assert!((a - b).abs() < 1e-4, "{a} vs {b}");
            }
        }
    }
}

fn rotary_study(input: Value) -> Study {
    Study::new(&BallbarRotaryInput::read(&input).unwrap()).unwrap()
}

#[test]
fn the_default_sweep_is_a_turn_from_zero_else_from_the_start_else_the_travel_within_90_degrees() {
    // A travel holding [0, 2π]: the turn from 0, also when it starts a hair below 0.
    assert_eq!(default_sweep(0.0, TAU), (0.0, TAU));
    assert_eq!(default_sweep(-2.0 * TAU, 2.0 * TAU), (0.0, TAU));
    assert_eq!(default_sweep(-1e-10, TAU), (0.0, TAU));
    assert_eq!(default_sweep(0.0, TAU - 1e-10), (0.0, TAU));
    // A full turn that does not hold 0 … 2π: one turn from its start.
    assert_eq!(default_sweep(-PI, PI), (-PI, PI));
    assert_eq!(default_sweep(0.5, 7.0), (0.5, 0.5 + TAU));
    // Less than a turn: the travel, cut to ±90°.
    assert_eq!(default_sweep(-2.0, 1.0), (-FRAC_PI_2, 1.0));
    assert_eq!(default_sweep(-0.3, 2.5), (-0.3, FRAC_PI_2));
    assert_eq!(default_sweep(-0.3, 0.4), (-0.3, 0.4));
}

#[test]
fn an_angle_is_within_the_travel_up_to_its_ends_and_a_nanoradian_beyond() {
    // The B/C table: B (the tilt, M) travels −120° … 120°.
    let s = rotary_study(json!({
        "machine": bc_table(),
        "tests": [{ "axis": "m", "ball": { "x": 0, "y": 0, "height": 50 }, "length": 100, "from": -90, "to": 90 }],
    }));
    let t = &s.tests[0];
    let (lo, hi) = ((-120f64).to_radians(), 120f64.to_radians());
    for a in [lo, hi, lo - 0.5e-9, hi + 0.5e-9, 0.0] {
        assert!(s.within(t, a), "{a} within");
    }
    for a in [lo - 2e-9, hi + 2e-9, -PI, PI] {
        assert!(!s.within(t, a), "{a} outside");
    }
}

#[test]
fn at_most_max_tests_tests_are_read() {
    let one = json!({ "ball": { "x": 100, "y": 0, "height": 50 }, "length": 100 });
    let tests = |n: usize| {
        (0..n)
            .map(|i| {
                let mut t = one.clone();
                t["name"] = json!(format!("test {i}"));
                t
            })
            .collect::<Vec<_>>()
    };
    let input = |n: usize| json!({ "machine": bc_table(), "tests": tests(n) });
    assert_eq!(
        BallbarRotaryInput::read(&input(MAX_TESTS))
            .unwrap()
            .tests
            .len(),
        MAX_TESTS
    );
    let e = BallbarRotaryInput::read(&input(MAX_TESTS + 1)).unwrap_err();
    assert_eq!(e.field, "tests");
    assert!(e.message.contains(&format!("at most {MAX_TESTS}")), "{e}");
}

#[test]
fn a_machine_whose_travel_ends_before_it_starts_is_refused_by_name() {
    let mut m = bc_table();
    m["rotary"]["mFrom"] = json!(30);
    m["rotary"]["mTo"] = json!(-30);
    let e = BallbarRotaryInput::read(&json!({ "machine": m })).unwrap_err();
    assert_eq!(e.field, "machine.rotary.mTo", "{e}");
    let e = call("ballbarRotarySimulate", &json!({ "machine": m })).unwrap_err();
    assert_eq!(e.field, "machine.rotary.mTo", "{e}");
}

#[test]
fn without_errors_the_tool_ball_is_where_it_was_commanded_and_the_bar_keeps_its_length() {
    let s = rotary_study(json!({
        "machine": bc_table(),
        "tests": [{ "ball": { "x": 120, "y": 30, "height": 40 }, "length": 100 }],
    }));
    let t = &s.tests[0];
    for deg in [0.0, 37.0, 145.0, 300.0] {
        let e = s.exact(t, f64::to_radians(deg)).unwrap();
        assert!(e.deviation.abs() < 1e-9, "{deg}°: {}", e.deviation);
        for d in e.displacement {
            assert!(d.abs() < 1e-9, "{deg}°: {:?}", e.displacement);
        }
    }
}

#[test]
fn the_first_order_change_follows_the_exact_one_with_error_motions_alone() {
    // Error motions only (no location error): C's radial run-out and its angular error, X's
    // positioning. Values of a few µm: the first order is within the second (|e|² / L).
    let mut m = with_errors(&bc_table(), json!({}));
    m["motions"] = json!({
        "E_XC": { "position": [0, 90, 180, 270, 360], "value": [0, 0.004, 0, -0.004, 0] },
        "E_CC": 0.002,
        "E_XX": { "poly": [0.003, 2e-5] },
    });
    let s = rotary_study(json!({
        "machine": m,
        "tests": [
            { "ball": { "x": 120, "y": 0, "height": 40 }, "length": 100 },
            { "ball": { "x": 80, "y": 40, "height": 40 }, "length": 100, "direction": "tangential", "name": "tangential" }
        ],
    }));
    let mut largest: f64 = 0.0;
    for t in &s.tests {
        for deg in (0..360).step_by(15) {
            let a = f64::from(deg).to_radians();
            let exact = s.exact(t, a).unwrap().deviation;
            let first = s.first_order(t, a).unwrap();
            largest = largest.max(exact.abs());
            assert!(
                (exact - first).abs() < 1e-6,
                "{} at {deg}°: exact {exact}, first order {first}",
                t.name
            );
        }
    }
    // The motions do move the bar (micrometres), so the comparison above is not of zeros.
    assert!(largest > 1e-3, "{largest}");
}

/// A test of a head axis is placed from the spindle: on the head-table machine (B head, the tip
/// `pivotLength + toolLength` = 300 mm below B's axis), a radial bar of B stands along the line
/// from B's axis to the tool tip, so the tool ball is right above the table ball (the bar
/// points up, from the table ball towards B's axis), the tool ball 300 mm from the line, and
/// the axis line 300 mm above the tool ball; a tangential bar lies along X, square to both B's
/// axis (Y) and that line.
// Found by cargo-mutants: a head axis's radial direction, its bar and its axis line (`place`)
// were reached by no test that checks them: every pose test derives them from the result.
#[test]
fn a_head_axis_test_is_placed_from_the_spindle() {
    // The table surface 50 mm above the machine origin (the C table's centre), so that B's line
    // is off the workpiece origin across the axis too.
    let mut machine = head_table();
    machine["geometry"]["tableHeight"] = json!(50);
    let s = rotary_study(json!({ "machine": machine, "tests": [
        { "axis": "m", "ball": { "x": 120, "y": -30, "height": 40 }, "step": 5, "from": -60, "to": 30 },
        { "axis": "m", "ball": { "x": 120, "y": -30, "height": 40 }, "step": 5, "from": -60, "to": 30, "direction": "tangential" }
    ] }));
    let (radial, tangential) = (&s.tests[0], &s.tests[1]);
    let near = |a: Vector3<f64>, b: Vector3<f64>| (a - b).norm() < 1e-9;
    assert!(!radial.table_side);
    assert!(near(radial.ball, Vector3::new(120.0, -30.0, 40.0)));
    assert!(near(radial.bar, Vector3::z()), "{}", radial.bar);
    assert!(near(radial.tool, radial.ball + Vector3::new(0.0, 0.0, L)));
    assert!((radial.radius - 300.0).abs() < 1e-9, "{}", radial.radius);
    let axis = radial.frame[2];
    assert!(near(axis.abs(), Vector3::y()), "{axis}");
    let up = radial.axis_point - radial.tool;
    let across = up - axis * up.dot(&axis);
    assert!(near(across, Vector3::new(0.0, 0.0, 300.0)), "{across}");
    assert!(
        near(tangential.bar.abs(), Vector3::x()),
        "{}",
        tangential.bar
    );
    assert!(near(tangential.tool - tangential.ball, tangential.bar * L));
}

/// An axial bar needs no radial direction, so its table ball may sit on the axis line: the
/// test's frame is then still three unit vectors square to each other, the third the axis.
// Found by cargo-mutants: the frame chosen for a ball on the line was reached by no test.
#[test]
fn an_axial_bar_over_the_axis_line_has_a_square_frame() {
    let s = rotary_study(json!({ "machine": bc_table(), "tests": [
        { "ball": { "x": 0, "y": 0, "height": 50 }, "step": 30, "direction": "axial" }
    ] }));
    let t = &s.tests[0];
    assert!(t.radius < 1e-9, "{}", t.radius);
    let [r, g, a] = t.frame;
    assert!((a.abs() - Vector3::z()).norm() < 1e-12, "{a}");
    for (u, w) in [(r, g), (g, a), (a, r)] {
        assert!(
            (u.norm() - 1.0).abs() < 1e-12 && u.dot(&w).abs() < 1e-12,
            "{u} {w}"
        );
    }
    assert!((t.tool - t.ball - a * L).norm() < 1e-9);
}

/// The commanded axes are given in their own units: the linear axes in mm, the rotary axes in
/// degrees, the moving one at the sweep's angles and the held one at its hold.
// Found by cargo-mutants: every pose test read each axis's unit and converted, so the units
// themselves were unchecked.
#[test]
fn the_commanded_rotary_axes_are_in_degrees_and_the_linear_in_mm() {
    let s = simulate(
        &bc_table(),
        json!([{ "ball": { "x": 150, "y": 0, "height": 50 }, "step": 90, "hold": 20 }]),
    );
    let axes = s["tests"][0]["commanded"].as_array().unwrap();
    let mut names: Vec<&str> = axes.iter().map(|a| a["name"].as_str().unwrap()).collect();
    names.sort_unstable();
    assert_eq!(names, ["B", "C", "X", "Y", "Z"]);
    for a in axes {
        let name = a["name"].as_str().unwrap();
        let values = numbers(&a["values"]);
        match name {
            "C" => {
                assert_eq!(a["unit"], "deg");
                let ccw = [0.0, 90.0, 180.0, 270.0, 360.0];
                for (v, w) in values.iter().zip(ccw) {
                    assert!((v - w).abs() < 1e-9, "C: {values:?}");
                }
            }
            "B" => {
                assert_eq!(a["unit"], "deg");
                assert!(
                    values.iter().all(|v| (v - 20.0).abs() < 1e-9),
                    "B: {values:?}"
                );
            }
            _ => assert_eq!(a["unit"], "mm", "{name}"),
        }
    }
}

/// The simulated file (module docs of `ballbar::rotary::simulate`, `trace_csv`) has a test column
/// only when it holds several tests: one test's lines are `angle;deviation;direction`, two
/// tests' `test;angle;deviation;direction`, the test named on each line.
// Found by cargo-mutants: the file was only ever read back, and the reader takes both forms.
#[test]
fn the_simulated_file_has_a_test_column_only_for_several_tests() {
    let one = json!({ "name": "one", "ball": { "x": 150, "y": 0, "height": 50 }, "step": 90 });
    let two = json!({ "name": "two", "ball": { "x": 150, "y": 0, "height": 50 }, "step": 90, "direction": "axial" });
    let data = |tests: Value| -> Vec<String> {
        let s = simulate(&bc_table(), tests);
        s["csv"]
            .as_str()
            .unwrap()
            .lines()
            .filter(|l| !l.starts_with('#'))
            .map(String::from)
            .collect()
    };
    let single = data(json!([one]));
    assert_eq!(single[0], "angle (deg);deviation (µm);direction");
    assert_eq!(single[1], "0;0.0000;ccw");
    let both = data(json!([one, two]));
    assert_eq!(both[0], "test;angle (deg);deviation (µm);direction");
    assert_eq!(both[1], "one;0;0.0000;ccw");
    assert!(both.last().unwrap().starts_with("two;0;"), "{both:?}");
}
