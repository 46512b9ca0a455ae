//! Tests written for mutants of `crate/src/volumetric/` that the full mutation run let survive
//! (`npm run mutants -- volumetric`): the map's rms, its worst point, the budget's grid and each
//! error's rms, against values worked by hand from errors whose effect is known in closed form.

#![allow(clippy::unwrap_used)] // test helpers: a failure should stop the test

use fiveaxis::volumetric::{map, VolumetricInput, VolumetricMap, BUDGET_SIDE};
use serde_json::{json, Value};

/// A three-axis C/A double turntable on an X table (as in `volumetric_map.rs`), tool on the
/// axes' lines, with the given error motions and map region.
fn map_of(motions: Value, region: Value) -> VolumetricMap {
    map(&input_of(motions, region)).unwrap()
}

/// The input of [`map_of`].
fn input_of(motions: Value, region: Value) -> VolumetricInput {
    VolumetricInput::read(&json!({
        "machine": {
            "kind": "table-table", "type": "CAZ", "linear": "table-x",
            "geometry": { "rotaryOffset": 0, "tableHeight": 0, "toolLength": 100 },
            "motions": motions,
        },
        "region": region,
    }))
    .unwrap()
}

/// `E_XX = 1e-5·X` and `E_YY = 1e-5·Y`: |Δ| = 1e-5·√(X² + Y²) (each positioning error moves
/// the tip along its own axis by its value). On X = −100 … 300 by 50 and Y = −200 … 50 by 31.25
/// (9 × 9) the worst point is the corner (300, −200): the first column of rows is Y = −200.
/// The rms over the grid is 1e-5·√(mean X² + mean Y²), the means over the nine values of each.
#[test]
fn the_maps_rms_and_worst_point_are_those_of_the_grid() {
    let m = map_of(
        json!({ "E_XX": { "poly": [0, 1e-5] }, "E_YY": { "poly": [0, 1e-5] } }),
        json!({ "uFrom": -100, "uTo": 300, "vFrom": -200, "vTo": 50, "at": 0, "steps": 9 }),
    );
    assert_eq!(m.worst.position, [300.0, -200.0, 0.0]);
    let want = 1e-5 * (300.0_f64.powi(2) + 200.0_f64.powi(2)).sqrt();
    assert!((m.worst.norm - want).abs() < 1e-12, "{}", m.worst.norm);
    let xs: Vec<f64> = (0..9).map(|i| -100.0 + 50.0 * f64::from(i)).collect();
    let ys: Vec<f64> = (0..9).map(|j| -200.0 + 31.25 * f64::from(j)).collect();
    let mean2 = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64;
    let rms = 1e-5 * (mean2(&xs) + mean2(&ys)).sqrt();
    assert!(
        (m.rms - rms).abs() < 1e-12 * rms.max(1.0),
        "{} vs {rms}",
        m.rms
    );
}

/// With every error zero every point is as bad as the others (|Δ| = 0): the worst point named is
/// the first of the grid, where the region starts.
#[test]
fn of_equal_points_the_first_is_the_worst() {
    let m = map_of(
        json!({}),
        json!({ "uFrom": -40, "uTo": 60, "vFrom": 10, "vTo": 90, "at": 0, "steps": 4 }),
    );
    assert!(m.norm.iter().all(|&v| v == 0.0));
    assert_eq!(m.worst.position, [-40.0, 10.0, 0.0]);
}

/// The budget uses every k-th grid point along each side, k = ⌈steps / BUDGET_SIDE⌉, and the
/// last point when the stride does not land on it. For 41 sides: 100 points, stride 3: points
/// 0, 3, …, 99: 34, the last among them; 101 points: 0, 3, …, 99 and 100: 35; 41 points: all.
#[test]
fn the_budget_takes_every_kth_point_and_the_last() {
    assert_eq!(BUDGET_SIDE, 41);
    for (steps, side) in [(100, 34), (101, 35), (41, 41)] {
        let m = map_of(
            json!({ "E_XX": 0.01 }),
            json!({ "uFrom": 0, "uTo": 100, "vFrom": 0, "vTo": 100, "steps": steps }),
        );
        assert_eq!(m.budget_side, [side, side], "{steps} steps");
    }
}

/// A constant positioning error of X, 10 µm: the tip is 10 µm off along X at every point. The
/// map's rms and its one contribution's rms and largest value are all 10 µm, its share 1.
#[test]
fn a_constant_error_contributes_its_value_everywhere() {
    let m = map_of(
        json!({ "E_XX": 0.01 }),
        json!({ "uFrom": -50, "uTo": 50, "vFrom": 0, "vTo": 80, "steps": 5 }),
    );
    assert!((m.rms - 0.01).abs() < 1e-15);
    assert_eq!(m.budget.len(), 1);
    let c = &m.budget[0];
    assert_eq!(c.name, "E_XX");
    assert!((c.share - 1.0).abs() < 1e-12);
    assert!((c.rms - 0.01).abs() < 1e-15, "{}", c.rms);
    assert!((c.max - 0.01).abs() < 1e-15, "{}", c.max);
}

/// Two errors that cancel: X positioning and the X straightness of Y, both constant and 10 µm,
/// each move the tip 10 µm along X; with the sign that makes them cancel (the X slide carries
/// the table, Y the spindle) |Δ| = 0 everywhere. Each still has its own part (rms 10 µm) and
/// its share of a zero total is 0, not a division by zero.
#[test]
fn errors_that_cancel_have_shares_of_zero() {
    let region = json!({ "uFrom": -50, "uTo": 50, "vFrom": 0, "vTo": 80, "steps": 5 });
    let m = [0.01, -0.01]
        .into_iter()
        .map(|s| map_of(json!({ "E_XX": 0.01, "E_XY": s }), region.clone()))
        .find(|m| m.norm.iter().all(|&v| v == 0.0))
        .expect("one sign cancels");
    assert_eq!(m.budget.len(), 2);
    for c in &m.budget {
        assert_eq!(c.share, 0.0, "{}", c.name);
        assert!((c.rms - 0.01).abs() < 1e-15, "{}", c.name);
    }
}

/// An error entered that moves nothing in the region is left out of the budget (its docs: errors
/// that are zero everywhere): the yaw of the spindle-side Y with the tool on Y's line (no Abbe
/// offset), at A and C zero; next to it X positioning, the one listed.
#[test]
fn an_error_that_moves_nothing_here_is_not_in_the_budget() {
    let m = map_of(json!({ "E_CY": 0.01, "E_XX": 0.01 }), json!({ "steps": 5 }));
    let names: Vec<&str> = m.budget.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["E_XX"]);
}

/// The words of the summary: the worst deviation in µm below 1 mm (one decimal), in mm from
/// 1 mm on (three decimals). (Where it is: in the test of the worst point above.)
#[test]
fn the_summary_gives_the_worst_deviation_in_the_right_unit() {
    let region = json!({ "uFrom": -50, "uTo": 50, "vFrom": 0, "vTo": 80, "steps": 5 });
    let small = map_of(json!({ "E_XX": 0.0036 }), region.clone());
    let text = small.summary(1);
    assert!(
        text.starts_with("The tool tip is off by up to 3.6 µm (at X "),
        "{text}"
    );
    assert!(text.contains("; rms 3.6 µm over the plane."), "{text}");
    let one = map_of(json!({ "E_XX": 1.5 }), region.clone());
    assert!(
        one.summary(1)
            .starts_with("The tool tip is off by up to 1.500 mm"),
        "{}",
        one.summary(1)
    );
    let big = map_of(json!({ "E_XX": 2.5 }), region);
    assert!(
        big.summary(1).contains("up to 2.500 mm"),
        "{}",
        big.summary(1)
    );
}

/// Tan & Lim's loop is theirs alone: a C/A double turntable (A carrying C, intersecting, both
/// turning per ISO 841) on an X table, tool along Z. Their machine is accepted; changing any one
/// of those is refused.
#[test]
fn the_paper_comparison_refuses_a_machine_that_differs_in_any_one_way() {
    use fiveaxis::machine::Machine;
    use fiveaxis::schema::Inputs;
    let with = |change: Value| {
        let mut m = json!({
            "kind": "table-table", "type": "CAZ", "linear": "table-x",
            "geometry": { "rotaryOffset": 0, "tableHeight": 0, "toolLength": 100 },
            "rotary": {}
        });
        for (k, v) in change.as_object().unwrap() {
            match v {
                Value::Object(o) => {
                    for (kk, vv) in o {
                        m[k][kk] = vv.clone();
                    }
                }
                _ => m[k] = v.clone(),
            }
        }
        let machine = Machine::from_value(&m, "machine").unwrap();
        fiveaxis::volumetric::compare(&machine, [10.0, 20.0, 30.0], 0.0, 0.0)
    };
    assert!(with(json!({})).is_ok());
    for change in [
        json!({ "kind": "head-head", "linear": "spindle-xyz" }),
        json!({ "type": "CBZ" }),
        json!({ "type": "BAZ" }),
        json!({ "type": "CAY" }),
        json!({ "linear": "table-xy" }),
        json!({ "geometry": { "rotaryOffset": 5 } }),
        json!({ "rotary": { "kReversed": true } }),
        json!({ "rotary": { "mReversed": true } }),
    ] {
        let e = with(change.clone()).unwrap_err();
        assert!(e.message.contains("Tan & Lim"), "{change}: {e}");
    }
}

/// A measured table that does not reach the whole region: the error names the first pose of the
/// grid outside it, its coordinates rounded to 6 decimals (a micrometre's thousandth). X runs
/// −50, −50/3, 50/3, 50 over four steps; a table of E_XX over −100 … 10 mm stops at the third
/// column, X = 16.666667 on the first row, Y = −50.
#[test]
fn a_table_short_of_the_region_names_the_pose_rounded() {
    let input = input_of(
        json!({ "E_XX": { "position": [-100, 10], "value": [0.001, 0.002] } }),
        json!({ "uFrom": -50, "uTo": 50, "vFrom": -50, "vTo": 150, "at": 0, "steps": 4 }),
    );
    let e = map(&input).unwrap_err();
    assert!(
        e.message.ends_with("(at X 16.666667, Y -50, Z 0 mm)"),
        "{}",
        e.message
    );
}
