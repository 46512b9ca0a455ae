//! The choice of the orientation solution and `fit`'s writing of rotary angles in the travel: the
//! smallest tilt as written in the travel, angles just below zero and at either travel limit, a
//! rotary table whose travel starts below zero, and travel bounds that are not numbers.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::{close, machine};
use fiveaxis::machine::{fit, BranchRule};
use nalgebra::Vector3;
use serde_json::json;
use std::f64::consts::{PI, TAU};

// Found by cargo-mutants: a mutant in `crate/src/machine/mod.rs` survived every other test.
/// Smallest tilt compares the M commands as written in the travel (module docs, "Inverse
/// kinematics within the travel"): on a CAZ trunnion whose A travels 0°…360°, the direction
/// `R_Z(C)·R_X(A)·e_Z = (sin C sin A, −cos C sin A, cos A)` with A = 3 rad, C = 4 rad is also
/// reached by (C − π, −A); written in the travel (in [0, 2π) as both fit) the two are
/// (C, A) = (4, 3) and (4 − π, 2π − 3 ≈ 3.28). The smaller tilt is A = 3, although the other
/// solution has the smaller |C|.
#[test]
fn smallest_tilt_compares_the_tilts_as_written_in_the_travel() {
    let model = machine(json!({
        "kind": "table-table", "type": "CAZ",
        "rotary": { "kFrom": -360, "kTo": 360, "mFrom": 0, "mTo": 360 },
    }))
    .build()
    .unwrap();
    let (c, a) = (4.0_f64, 3.0_f64);
    let dir = Vector3::new(c.sin() * a.sin(), -c.cos() * a.sin(), a.cos());
    let o = model
        .orientations(&dir, BranchRule::SmallestTilt, None)
        .unwrap();
    assert_eq!(o.solutions.len(), 2, "{o:?}");
    assert!(o.solutions.iter().all(|s| s.in_travel), "{o:?}");
    let mut written: Vec<[f64; 2]> = o.solutions.iter().map(|s| [s.k, s.m]).collect();
    written.sort_by(|x, y| x[1].total_cmp(&y[1]));
    close(written[0][0], c, 1e-9, "K of the smaller tilt");
    close(written[0][1], a, 1e-9, "the smaller tilt");
    close(written[1][0], c - PI, 1e-9, "K of the larger tilt");
    close(written[1][1], TAU - a, 1e-9, "the larger tilt");
    let chosen = o.pick("").unwrap();
    close(chosen.k, c, 1e-9, "chosen K");
    close(chosen.m, a, 1e-9, "chosen M: the smaller tilt");
}

// Found by cargo-mutants: a mutant in `crate/src/machine/mod.rs` survived every other test.
/// `fit` gives `None` when no turn of the angle lies within `[lo, hi]` (its doc): a bound that
/// is not a number admits no angle (every comparison with NaN is false), on either side, with
/// or without a value to be near; nor does an angle that is not a number.
#[test]
fn fit_admits_no_angle_within_a_travel_bound_that_is_not_a_number() {
    for near in [None, Some(0.0), Some(2.0)] {
        assert_eq!(
            fit(1.0, f64::NAN, 10.0, near),
            None,
            "NaN lower bound, near {near:?}"
        );
        assert_eq!(
            fit(1.0, -10.0, f64::NAN, near),
            None,
            "NaN upper bound, near {near:?}"
        );
        assert_eq!(
            fit(f64::NAN, -10.0, 10.0, near),
            None,
            "NaN angle, near {near:?}"
        );
    }
    // The same angle within finite bounds does fit.
    assert_eq!(fit(1.0, -10.0, 10.0, None), Some(1.0));
}

// Found by cargo-mutants: a mutant in `crate/src/machine/mod.rs` survived every other test.
/// Without a value to be near, `fit` writes the angle in `[0, 2π)` when that is within the
/// travel (its doc; module docs: `[0°, 360°)`). An angle a rounding error below zero, whose
/// remainder modulo 2π rounds to 2π itself, is therefore written as 0, not as a whole turn.
#[test]
fn fit_writes_an_angle_just_below_zero_as_zero_not_a_whole_turn() {
    for a in [-1e-17, -1e-16, -TAU * f64::EPSILON / 4.0] {
        for (lo, hi) in [(-TAU, TAU), (0.0, TAU), (-PI, 2.0 * TAU)] {
            let got = fit(a, lo, hi, None).unwrap();
            assert!((0.0..TAU).contains(&got), "fit({a}, {lo}, {hi}) = {got}");
            close(got, 0.0, 1e-12, "written as 0");
        }
    }
}

// Found by cargo-mutants: a mutant in `crate/src/machine/mod.rs` survived every other test.
/// Without a value to be near, the angle is written in `[0, 2π)` whenever that lies within the
/// travel, its limits counted with `TRAVEL_TOLERANCE` (1e-9 rad) (doc of `fit`). At the upper
/// limit (a table from −360° to 270° at 270°, or a hair above it) that is the limit itself,
/// not the turn nearer 0 (−90°); at a lower limit at (or a hair above) 0, an angle a rounding
/// error below 0 is written as 0, not as a value below the travel's start.
#[test]
fn fit_keeps_the_angle_in_zero_to_a_turn_at_either_travel_limit() {
    let (lo, hi) = (-TAU, 1.5 * PI);
    for a in [hi, hi + 0.5e-9, hi - TAU] {
        let got = fit(a, lo, hi, None).unwrap();
        close(got, hi, 1e-9, &format!("fit({a}) at the upper limit"));
    }
    for lo in [0.0, 0.5e-9] {
        let got = fit(-1e-17, lo, 1.0, None).unwrap();
        assert!((0.0..TAU).contains(&got), "fit(-1e-17, {lo}, 1) = {got}");
        close(got, 0.0, 1e-12, "written as 0");
    }
}

// Found by cargo-mutants: a mutant in `crate/src/machine/mod.rs` survived every other test.
/// A measured table of a rotary axis that does not start at 0: from −1 rad over one turn to
/// 2π − 1. A position past its end is brought back by whole turns (6 rad is 6 − 2π ≈ −0.2832
/// rad) and interpolated linearly between −1 rad (0) and 0 rad (1 µm): 0.7168 µm. A linear
/// axis's table is never wrapped.
#[test]
fn a_rotary_table_that_starts_below_zero_wraps_by_whole_turns() {
    use fiveaxis::machine::motions::ErrorFunction;
    use std::f64::consts::TAU;
    let f = ErrorFunction::Table {
        position: vec![-1.0, 0.0, 2.0, 5.0, TAU - 1.0],
        value: vec![0.0, 1e-3, 2e-3, 3e-3, 0.0],
    };
    let want = 1e-3 * (6.0 - TAU + 1.0);
    close(f.at(6.0, "E_CC", true).unwrap(), want, 1e-15, "6 rad");
    close(
        f.at(6.0 - TAU, "E_CC", true).unwrap(),
        want,
        1e-15,
        "the same, within the table",
    );
    assert!(
        f.at(6.0, "E_XX", false).is_err(),
        "a linear axis's table is not wrapped"
    );
}
