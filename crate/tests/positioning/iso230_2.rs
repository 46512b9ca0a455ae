//! ISO 230-2:2014 positioning evaluation: a worked example done by hand, a real test report
//! re-evaluated, a rotary axis in arc seconds, and the reader's layouts and faults.

#![allow(clippy::unwrap_used)] // test helpers: a failure should stop the test

use fiveaxis::api::ApiInput;
use fiveaxis::positioning::{evaluate, read_runs, PositioningInput};
use serde_json::json;

fn input(csv: &str, axis: &str) -> PositioningInput {
    PositioningInput::read(&json!({ "csv": csv, "axis": axis })).unwrap()
}

fn close(got: f64, want: f64, tol: f64, what: &str) {
    assert!((got - want).abs() <= tol, "{what}: got {got}, want {want}");
}

/// Two targets, five runs each way, deviations in µm chosen so that every intermediate is
/// worked out by hand:
///
/// target 0 mm:   up 1, 2, 3, 4, 5      → x̄↑ = 3,  s↑ = √(10/4) = 1.58114
///                down −1, 0, 1, 2, 3   → x̄↓ = 1,  s↓ = 1.58114
///                B = 2; R↑ = R↓ = 4·1.58114 = 6.32456;
///                R = max(2·1.58114 + 2·1.58114 + 2, 6.32456) = 8.32456
///                (the bidirectional R exceeds both directional repeatabilities)
/// target 100 mm: up 5, 5, 6, 6, 8      → x̄↑ = 6,  s↑ = √(6/4) = 1.22474
///                down 4, 4, 4, 4, 4    → x̄↓ = 4,  s↓ = 0
///                B = 2; R↑ = 4.89898, R↓ = 0; R = max(2.44949 + 0 + 2, 4.89898) = 4.89898
/// axis: B = 2, B̄ = 2; R↑ = R↓ = 6.32456, R = 8.32456;
///       E↑ = 6 − 3 = 3, E↓ = 4 − 1 = 3, E = max(3, 1, 6, 4) − min(…) = 5;
///       x̄ = 2 and 5 → M = 3;
///       A↑ = max(3 + 3.16228, 6 + 2.44949) − min(3 − 3.16228, 6 − 2.44949) = 8.44949 + 0.16228
///          = 8.61177;
///       A↓ = max(1 + 3.16228, 4) − min(1 − 3.16228, 4) = 4.16228 + 2.16228 = 6.32456;
///       A = max(8.44949, 4.16228) − min(−0.16228, −2.16228) = 10.61177.
const WORKED: &str = "target (mm); direction; run; deviation (µm)
0; up; 1; 1
0; up; 2; 2
0; up; 3; 3
0; up; 4; 4
0; up; 5; 5
0; down; 1; -1
0; down; 2; 0
0; down; 3; 1
0; down; 4; 2
0; down; 5; 3
100; up; 1; 5
100; up; 2; 5
100; up; 3; 6
100; up; 4; 6
100; up; 5; 8
100; down; 1; 4
100; down; 2; 4
100; down; 3; 4
100; down; 4; 4
100; down; 5; 4
";

#[test]
fn worked_example_every_intermediate_by_hand() {
    let p = evaluate(&input(WORKED, "X")).unwrap();
    let um = 1e-3;
    let tol = 1e-5 * um;
    let s1 = 2.5f64.sqrt();
    let s2 = 1.5f64.sqrt();
    assert_eq!(p.unit, "mm");
    assert_eq!(p.runs, 5);
    let [t0, t1] = [&p.targets[0], &p.targets[1]];
    close(t0.mean_up, 3.0 * um, tol, "x̄↑_1");
    close(t0.mean_down, 1.0 * um, tol, "x̄↓_1");
    close(t0.s_up, s1 * um, tol, "s↑_1");
    close(t0.s_down, s1 * um, tol, "s↓_1");
    close(t0.b, 2.0 * um, tol, "B_1");
    close(t0.r_up, 4.0 * s1 * um, tol, "R↑_1");
    close(t0.r, (4.0 * s1 + 2.0) * um, tol, "R_1");
    assert!(
        t0.r > t0.r_up && t0.r > t0.r_down,
        "bidirectional R_1 exceeds both"
    );
    close(t1.mean_up, 6.0 * um, tol, "x̄↑_2");
    close(t1.s_up, s2 * um, tol, "s↑_2");
    close(t1.s_down, 0.0, tol, "s↓_2");
    close(t1.r, 4.0 * s2 * um, tol, "R_2");
    // The bands x̄ ± 2s the accuracy spans (the plot's): target 0 up 3 ± 2·1.58114, target 100
    // down 4 ± 0.
    close(t0.band_up[0], (3.0 - 2.0 * s1) * um, tol, "x̄↑_1 − 2s↑_1");
    close(t0.band_up[1], (3.0 + 2.0 * s1) * um, tol, "x̄↑_1 + 2s↑_1");
    close(t1.band_down[0], 4.0 * um, tol, "x̄↓_2 − 2s↓_2");
    close(t1.band_down[1], 4.0 * um, tol, "x̄↓_2 + 2s↓_2");
    close(p.b, 2.0 * um, tol, "B");
    close(p.b_mean, 2.0 * um, tol, "B̄");
    close(p.r_up, 4.0 * s1 * um, tol, "R↑");
    close(p.r, (4.0 * s1 + 2.0) * um, tol, "R");
    close(p.e_up, 3.0 * um, tol, "E↑");
    close(p.e_down, 3.0 * um, tol, "E↓");
    close(p.e, 5.0 * um, tol, "E");
    close(p.m, 3.0 * um, tol, "M");
    close(p.a_up, (6.0 + 2.0 * s2 - 3.0 + 2.0 * s1) * um, tol, "A↑");
    close(
        p.a_down,
        (1.0 + 2.0 * s1 - (1.0 - 2.0 * s1)) * um,
        tol,
        "A↓",
    );
    close(p.a, (6.0 + 2.0 * s2 - (1.0 - 2.0 * s1)) * um, tol, "A");
    // Into the machine: X's positioning error motion, the mean bidirectional deviation.
    assert_eq!(p.motion.name, "E_XX");
    assert_eq!(p.motion.position, vec![0.0, 100.0]);
    close(p.motion.value[1], 5.0 * um, tol, "E_XX at 100");
}

/// The PSI ecmc test report (crate/tests/data/iso230-2-psi-ecmc.csv, cited there): its
/// per-target values follow the standard and are printed to 4 digits; its axis E and R do not.
/// E is the range of all ten means x̄↑_i, x̄↓_i: from the report's own table,
/// −8.482e-5 − (−12.162e-5) = 3.680e-5 mm, not the 2.46e-5 printed (E↑ alone). R is the largest
/// R_i, 6.882e-5 mm in the report's own table, not the 6.29e-5 printed (max of R↑, R↓).
#[test]
fn a_published_report_re_evaluated_to_the_standard() {
    let csv = std::fs::read_to_string("tests/data/iso230-2-psi-ecmc.csv").unwrap();
    let p = evaluate(&input(&csv, "X")).unwrap();
    assert_eq!(p.targets.len(), 5);
    assert_eq!(p.runs, 5);
    // The report's per-target table (rounded as printed).
    let printed_mean_up = [-9.242e-05, -9.162e-05, -8.482e-05, -8.902e-05, -10.942e-05];
    let printed_b = [-4e-07, 9.6e-06, 6e-06, -4e-07, 1.22e-05];
    let printed_r = [3.517e-05, 3.772e-05, 4.17e-05, 4.871e-05, 6.882e-05];
    let printed_s_up = [8.79e-06, 6.77e-06, 7.26e-06, 9e-06, 1.258e-05];
    for (i, t) in p.targets.iter().enumerate() {
        close(t.mean_up, printed_mean_up[i], 1e-10, "x̄↑_i");
        close(t.b, printed_b[i], 1e-10, "B_i");
        close(t.r, printed_r[i], 1e-8, "R_i");
        close(t.s_up, printed_s_up[i], 1e-8, "s↑_i");
    }
    close(p.b, 1.22e-05, 1e-10, "B (as printed)");
    close(p.b_mean, 5.4e-06, 1e-10, "B̄ (as printed)");
    close(p.m, 2.77e-05, 1e-10, "M (as printed)");
    close(p.a, 8.881e-05, 1e-8, "A (as printed)");
    close(p.r_up, 5.033e-05, 1e-8, "R↑ (as printed)");
    close(p.r_down, 6.29e-05, 1e-8, "R↓ (as printed)");
    close(p.e_up, 2.46e-05, 1e-10, "E↑ (as printed)");
    close(p.e, 3.680e-05, 1e-10, "E: range of both directions' means");
    close(p.r, 6.882e-05, 1e-8, "R: the largest R_i");
}

/// A rotary axis with its deviations in arc seconds: the same numbers as the worked example,
/// in degrees (÷ 3600), targets in degrees.
#[test]
fn rotary_axis_in_arc_seconds() {
    let csv = WORKED
        .replace("target (mm)", "target (deg)")
        .replace("deviation (µm)", "deviation (arcsec)");
    let p = evaluate(&input(&csv, "C")).unwrap();
    assert_eq!(p.unit, "deg");
    close(p.e, 5.0 / 3600.0, 1e-12, "E");
    close(p.b, 2.0 / 3600.0, 1e-12, "B");
    assert_eq!(p.motion.name, "E_CC");
    // A linear axis named for angular targets is refused, and the reverse.
    let e = evaluate(&input(&csv, "X")).unwrap_err().to_string();
    assert!(e.starts_with("axis: X is a linear axis"), "{e}");
    let e = evaluate(&input(WORKED, "B")).unwrap_err().to_string();
    assert!(e.starts_with("axis: B is a rotary axis"), "{e}");
}

/// The same runs in the three layouts, with a decimal comma, `+` signs, CRLF and whitespace,
/// read to the same deviations.
#[test]
fn three_layouts_read_alike() {
    let long = read_runs(WORKED).unwrap();
    let per_target = "target (mm);up 1 (µm);up 2 (µm);up 3 (µm);up 4 (µm);up 5 (µm);down 1 (µm);down 2 (µm);down 3 (µm);down 4 (µm);down 5 (µm)\r\n\
        0;+1;2;3;4;5;-1;0;1;2;3\r\n\
        100;5;5;6;6;8;4;4;4;4;4\r\n";
    let per_run = "direction\trun (µm)\t0 mm\t100 mm\n\
        up\t1\t1,0\t5\n↑\t2\t2\t5\nfwd\t3\t3\t6\n+\t4\t4\t6\nup\t5\t5\t8\n\
        down\t1\t-1\t4\n↓\t2\t0\t4\nbwd\t3\t1\t4\n−\t4\t2\t4\ndown\t5\t3\t4\n";
    let spaces = "target(mm) direction deviation(µm)\n0 up 1\n0 up 2\n0 down 3\n0 down 4\n5 up 0,5\n5 up 1\n5 down 2\n5 down 2\n";
    for (what, text) in [("per target", per_target), ("per run", per_run)] {
        let r = read_runs(text).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!(r.targets, long.targets, "{what}");
        for (a, b) in
            r.up.iter()
                .flatten()
                .chain(r.down.iter().flatten())
                .zip(long.up.iter().flatten().chain(long.down.iter().flatten()))
        {
            close(*a, *b, 1e-15, what);
        }
    }
    let s = read_runs(spaces).unwrap();
    assert_eq!(s.targets, vec![0.0, 5.0]);
    close(s.up[0][1], 0.5e-3, 1e-15, "decimal comma between spaces");
}

/// Positions reached instead of deviations, and targets in other units, read to the same
/// deviations in mm: the reached position less the target, each converted by its own header
/// unit, in each of the three layouts. Found by cargo-mutants: `target * unit` as
/// `target / unit` and `reached − target` as `reached + target` survived, as every file tested
/// gave targets in mm and deviations.
#[test]
fn reached_positions_and_target_units_give_the_deviations() {
    // Target 0,1 m = 100 mm reached at 100,004 mm: +4 µm; 0 m reached at −0,002 mm: −2 µm.
    let long = "target (m);direction;run;actual (mm)\n\
        0;up;1;-0,002\n0,1;up;1;100,004\n0;down;1;0,001\n0,1;down;1;100,003\n\
        0;up;2;-0,002\n0,1;up;2;100,004\n0;down;2;0,001\n0,1;down;2;100,003\n";
    let r = read_runs(long).unwrap();
    assert_eq!(r.targets, vec![0.0, 100.0]);
    close(r.up[0][0], -0.002, 1e-12, "up at 0");
    close(r.up[0][1], 0.004, 1e-12, "up at 100 mm");
    close(r.down[0][0], 0.001, 1e-12, "down at 0");
    close(r.down[0][1], 0.003, 1e-12, "down at 100 mm");
    // One line per run, the targets in columns in m, the positions reached in mm (named on the
    // run column): the same deviations.
    let per_run = "direction;run reached (mm);0 m;0,1 m\n\
        up;1;-0,002;100,004\nup;2;-0,002;100,004\ndown;1;0,001;100,003\ndown;2;0,001;100,003\n";
    let p = read_runs(per_run).unwrap();
    assert_eq!(p.targets, r.targets);
    for (a, b) in
        p.up.iter()
            .flatten()
            .chain(p.down.iter().flatten())
            .zip(r.up.iter().flatten().chain(r.down.iter().flatten()))
    {
        close(*a, *b, 1e-12, "one line per run");
    }
    // One line per target, the target in inches (25.4 mm), deviations in µm.
    let per_target =
        "target (in), up 1 (µm), up 2 (µm), down 1 (µm), down 2 (µm)\n0, 1, 1, -1, -1\n4, 2, 2, 3, 3\n";
    let r = read_runs(per_target).unwrap();
    close(r.targets[1], 101.6, 1e-12, "4 in");
    close(r.up[0][1], 0.002, 1e-15, "up at 4 in");
    close(r.down[0][0], -0.001, 1e-15, "down at 0");
    // One line per target, positions reached (mm) at targets in mm.
    let reached =
        "target (mm), actual up 1 (mm), actual up 2 (mm), actual down 1 (mm), actual down 2 (mm)\n\
        0, 0.001, 0.001, -0.002, -0.002\n50, 50.003, 50.003, 49.999, 49.999\n";
    let r = read_runs(reached).unwrap();
    close(r.up[0][1], 0.003, 1e-12, "reached up at 50");
    close(r.down[0][1], -0.001, 1e-12, "reached down at 50");
}

/// Each kind of bad file, with its line.
#[test]
fn bad_files_name_their_line() {
    let cases = [
        ("target (mm); direction; deviation (µm)\n0; up; 1\n0; sideways; 2\n", "csv: line 3: the direction must be up"),
        ("target (mm); direction; deviation (µm)\n0; up; 1\n0; up; x\n", "csv: line 3: the value is not a number"),
        ("target; direction; deviation (µm)\n0; up; 1\n", "csv: line 1: give the unit of the targets"),
        ("target (mm); direction; deviation (µm)\n0; up; 1\n0; up\n", "csv: line 3: expected 3 cells"),
        ("target (mm); direction; deviation (arcsec)\n0; up; 1\n", "csv: line 1: the targets and the values must both be lengths or both angles"),
        ("x; y; z\n1; 2; 3\n", "csv: line 1: the header names no target column"),
        ("target (mm); direction; deviation (µm)\n", "csv: has a header but no measurements"),
        ("target (mm); direction; deviation (µm)\n0; up; 1\n0; up; 2\n0; down; 1\n0; down; 1\n", "csv: needs at least 2 targets"),
        ("target (mm); direction; deviation (µm)\n0; up; 1\n0; down; 2\n5; up; 1\n5; down; 1\n", "csv: line 2: target 0: needs at least 2 runs each way"),
        // Two runs up but one down: too few one way is enough (found by cargo-mutants: `||` as
        // `&&` survived, the file then refused for unequal counts instead).
        ("target (mm); direction; deviation (µm)\n0; up; 1\n0; up; 1\n0; down; 2\n5; up; 1\n5; up; 1\n5; down; 1\n", "csv: line 2: target 0: needs at least 2 runs each way (ISO 230-2 asks for 5), got 2 up and 1 down"),
        ("target (mm); direction; deviation (µm)\n0; up; 1\n0; up; 1\n0; down; 2\n0; down; 2\n5; up; 1\n5; up; 1\n5; up; 1\n5; down; 1\n5; down; 1\n", "csv: line 6: target 5: 3 runs up and 2 down"),
        ("target (mm);up 1 (µm);up 2 (µm)\n0;1;2\n", "csv: line 1: name the run columns"),
        ("direction; run (µm); 0; 100\nup; 1; 1; 2\n", "csv: line 1: give the target's unit"),
    ];
    for (text, want) in cases {
        let e = read_runs(text).unwrap_err().to_string();
        assert!(e.starts_with(want), "{text:?}\n got: {e}\nwant: {want}");
    }
}

/// Tolerances: each result at or under its tolerance passes, the next larger double fails
/// (`≤`), and a result left without one is not judged.
#[test]
fn tolerances_judge_at_or_under() {
    let p = evaluate(&input(WORKED, "X")).unwrap();
    let judged = |tol: serde_json::Value| {
        evaluate(&PositioningInput::read(&json!({ "csv": WORKED, "tolerance": tol })).unwrap())
            .unwrap()
            .checks
    };
    let c = judged(json!({ "e": p.e }));
    assert_eq!(c.len(), 1);
    assert!(c[0].name == "E" && c[0].pass);
    let below = f64::from_bits(p.e.to_bits() - 1);
    assert!(!judged(json!({ "e": below }))[0].pass);
    assert_eq!(judged(json!({})).len(), 0);
}

/// A rotary axis is judged against `rotaryTolerance`, given in degrees at the edge: the worked
/// example in arc seconds has E = 5″ = 5/3600°, so 5″ passes and 4.99″ fails; a linear axis's
/// `tolerance` (mm) is refused for it, naming the field and where to put it, and the reverse.
#[test]
fn rotary_tolerances_in_degrees_and_the_wrong_set_refused() {
    let csv = WORKED
        .replace("target (mm)", "target (deg)")
        .replace("deviation (µm)", "deviation (arcsec)");
    let judged = |e_arcsec: f64| {
        let i = PositioningInput::read(
            &json!({ "csv": csv, "axis": "C", "rotaryTolerance": { "e": e_arcsec / 3600.0 } }),
        )
        .unwrap();
        evaluate(&i).unwrap().checks
    };
    let c = judged(5.0);
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].name, "E");
    close(
        c[0].tolerance,
        5.0 / 3600.0,
        1e-15,
        "E's tolerance, degrees",
    );
    assert!(c[0].pass);
    assert!(!judged(4.99)[0].pass);
    let e =
        PositioningInput::read(&json!({ "csv": csv, "axis": "C", "tolerance": { "r": 0.004 } }))
            .unwrap_err()
            .to_string();
    assert!(
        e.starts_with("tolerance.r: C is a rotary axis: give its tolerances under rotaryTolerance"),
        "{e}"
    );
    let e = PositioningInput::read(
        &json!({ "csv": WORKED, "axis": "Y", "rotaryTolerance": { "a": 0.001 } }),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("rotaryTolerance.a: Y is a linear axis: give its tolerances under tolerance"),
        "{e}"
    );
    // The axis is one of six.
    let e = PositioningInput::read(&json!({ "csv": WORKED, "axis": "Q" }))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("axis: expected one of"), "{e}");
}
