//! Error motions given as constants, polynomials and measured tables; the volumetric map, its
//! worst point and its budget.

#![allow(clippy::unwrap_used)] // test helpers: a failure should stop the test

use fiveaxis::machine::motions::{read_table_csv, ErrorFunction};
use fiveaxis::machine::Machine;
use fiveaxis::schema::Inputs;
use fiveaxis::volumetric::{map, VolumetricInput, VolumetricMap, BUDGET_SIDE};
use serde_json::{json, Value};

fn input(motions: Value, errors: Value, region: Value) -> VolumetricInput {
    VolumetricInput::read(&json!({
        "machine": {
            "kind": "table-table", "type": "CAZ", "linear": "table-x",
            "geometry": { "rotaryOffset": 0, "tableHeight": 0, "toolLength": 100 },
            "errors": errors,
            "motions": motions,
        },
        "region": region,
    }))
    .unwrap()
}

fn function(v: Value, name: &str) -> ErrorFunction {
    let m = Machine::from_value(&json!({ "motions": { name: v } }), "machine").unwrap();
    m.motions.0[name].clone()
}

#[test]
fn a_table_is_interpolated_linearly_and_exactly_at_its_points() {
    let f = function(
        json!({ "position": [0, 100, 300], "value": [0.0, 0.004, -0.002] }),
        "E_XX",
    );
    let at = |p: f64| f.at(p, "E_XX", false).unwrap();
    assert_eq!(at(0.0), 0.0);
    assert_eq!(at(100.0), 0.004);
    assert_eq!(at(300.0), -0.002);
    // Midpoints: the mean of the neighbours; a quarter of the way: a quarter of the step.
    assert!((at(50.0) - 0.002).abs() < 1e-15);
    assert!((at(200.0) - 0.001).abs() < 1e-15);
    assert!((at(150.0) - 0.0025).abs() < 1e-15);
}

#[test]
fn outside_its_table_an_error_is_refused_not_extrapolated() {
    let f = function(
        json!({ "position": [-100, 100], "value": [0.001, 0.002] }),
        "E_YY",
    );
    let e = f.at(150.0, "E_YY", false).unwrap_err();
    assert_eq!(e.field, "machine.motions.E_YY");
    assert!(
        e.message.contains("-100 to 100 mm") && e.message.contains("150"),
        "{e}"
    );
    // In the map: the pose is named.
    let inp = input(
        json!({ "E_YY": { "position": [-100, 100], "value": [0.001, 0.002] } }),
        json!({}),
        json!({ "uFrom": -50, "uTo": 50, "vFrom": -50, "vTo": 150, "steps": 5 }),
    );
    let e = map(&inp).unwrap_err();
    assert!(e.message.contains("Y 150"), "{e}");
}

#[test]
fn a_rotary_table_over_one_turn_serves_every_angle() {
    // Degrees at the edge: 0..360 in steps of 90; −90° is 270°.
    let f = function(
        json!({ "position": [0, 90, 180, 270, 360], "value": [0, 0.001, 0, -0.001, 0] }),
        "E_XC",
    );
    let v = f.at((-90f64).to_radians(), "E_XC", true).unwrap();
    assert!((v + 0.001).abs() < 1e-15, "{v}");
    let v = f.at(405f64.to_radians(), "E_XC", true).unwrap();
    assert!((v - 0.0005).abs() < 1e-15, "{v}");
}

#[test]
fn bad_tables_are_refused_with_the_place() {
    for (v, field) in [
        (
            json!({ "position": [0, 0], "value": [1e-3, 2e-3] }),
            "machine.motions.E_XX.position[1]",
        ),
        (
            json!({ "position": [0, 1, 2], "value": [1e-3, 2e-3] }),
            "machine.motions.E_XX.value",
        ),
        (
            json!({ "position": [0, 1], "value": [1e-3, 6] }),
            "machine.motions.E_XX.value[1]",
        ),
        (json!({ "poly": [0], "value": [1] }), "machine.motions.E_XX"),
        (json!({ "slope": 1 }), "machine.motions.E_XX.slope"),
        (json!("1"), "machine.motions.E_XX"),
    ] {
        let e = Machine::from_value(&json!({ "motions": { "E_XX": v } }), "machine").unwrap_err();
        assert_eq!(e.field, field, "{e}");
    }
    let e = Machine::from_value(&json!({ "motions": { "E_X0B": 0.01 } }), "machine").unwrap_err();
    assert!(e.message.contains("location error"), "{e}");
    let e = Machine::from_value(&json!({ "errors": { "E_XX": 0.01 } }), "machine").unwrap_err();
    assert!(e.message.contains("machine.motions"), "{e}");
    let e = Machine::from_value(&json!({ "motions": { "dx(X)": 0.01 } }), "machine").unwrap_err();
    assert!(e.message.contains("E_XX = δx(X)"), "{e}");
    let e = Machine::from_value(&json!({ "motions": { "E_XXX": 0.01 } }), "machine").unwrap_err();
    assert!(e.message.contains("Did you mean E_XX?"), "{e}");
    // A machine without A refuses A's error motions (the standard machine is B/C).
    let m = Machine::from_value(&json!({ "motions": { "E_XA": 0.001 } }), "machine").unwrap();
    let e = m.validate("machine").unwrap_err();
    assert_eq!(e.field, "machine.motions.E_XA");
}

#[test]
fn csv_tables_read_units_from_the_header_and_name_bad_lines() {
    let t = read_table_csv(
        "# laser run 3\nX (mm), E_XX (µm)\n0, 0\n100, 2.5\n200, 4\n",
        "E_XX",
    )
    .unwrap();
    assert_eq!(t.position, vec![0.0, 100.0, 200.0]);
    assert!((t.value[1] - 0.0025).abs() < 1e-15 && (t.value[2] - 0.004).abs() < 1e-15);
    // Pitch in arc seconds: 3.6″ = 0.001°.
    let t = read_table_csv("X [mm];pitch [arcsec]\n0;0\n500;3,6\n", "E_BX").unwrap();
    assert!((t.value[1] - 0.001).abs() < 1e-15, "{:?}", t.value);
    // Rotary positions in degrees, values in µrad.
    let t = read_table_csv("C (deg)\tE_CC (µrad)\n0\t0\n90\t100\n", "E_CC").unwrap();
    assert!((t.value[1] - 1e-4f64.to_degrees()).abs() < 1e-15);
    for (text, line) in [
        ("X (mm), E_XX (um)\n0, 0\n100, abc\n", "line 3"),
        ("X (mm), E_XX (um)\n0, 0\n\n0, 1\n", "line 4"),
        ("X (furlong), E_XX (um)\n0, 0\n", "line 1"),
        ("X (mm), E_XX (um)\n0, 0, 1\n", "line 2"),
        ("X (mm), E_XX (deg)\n0, 0\n", "line 1"),
    ] {
        let e = read_table_csv(text, "E_XX").unwrap_err();
        assert!(e.message.starts_with(line), "{text:?}: {e}");
    }
    assert!(read_table_csv("X (mm), E_XX (um)\n0, 0\n", "E_XX")
        .unwrap_err()
        .message
        .contains("two rows"));
}

#[test]
fn zero_errors_give_a_zero_map_and_an_empty_budget() {
    let m = map(&input(json!({}), json!({}), json!({ "steps": 5 }))).unwrap();
    assert!(m.norm.iter().all(|&v| v == 0.0));
    assert!(m.budget.is_empty());
    assert!(m.summary(0).starts_with("No error is entered"));
    // An error entered that moves nothing here: the yaw of the spindle-side Y, the tool on
    // Y's line (no Abbe offset), at A and C zero.
    let m = map(&input(
        json!({ "E_CY": 0.01 }),
        json!({}),
        json!({ "steps": 5 }),
    ))
    .unwrap();
    assert!(m.norm.iter().all(|&v| v.abs() < 1e-12), "{:?}", m.worst);
}

#[test]
fn a_positioning_error_growing_with_x_is_worst_at_the_end_of_x() {
    // E_XX = 10 µm/m · X (poly [0, 1e-5] mm per mm): |Δ| = 1e-5·|X|, along X only.
    let m = map(&input(
        json!({ "E_XX": { "poly": [0, 1e-5] } }),
        json!({}),
        json!({ "uFrom": -100, "uTo": 300, "vFrom": 0, "vTo": 50, "steps": 9 }),
    ))
    .unwrap();
    assert_eq!(m.worst.position[0], 300.0);
    assert!((m.worst.norm - 0.003).abs() < 1e-12, "{}", m.worst.norm);
    assert!((m.worst.deviation[0] - 0.003).abs() < 1e-12);
    for (k, &n) in m.norm.iter().enumerate() {
        let x = m.u[k % m.u.len()];
        assert!((n - 1e-5 * x.abs()).abs() < 1e-12);
    }
    assert_eq!(m.budget.len(), 1);
    assert!((m.budget[0].share - 1.0).abs() < 1e-12);
    assert!(m.summary(1).contains("E_XX"));
}

#[test]
fn the_budget_adds_up_and_first_order_converges_quadratically() {
    let motions = |s: f64| {
        json!({
            "E_XX": { "poly": [0, 2e-5 * s] },
            "E_BX": { "position": [-300, 0, 300], "value": [-0.002 * s, 0.0, 0.003 * s] },
            "E_AY": 0.001 * s,
            "E_XC": 0.004 * s,
            "E_AA": 0.002 * s,
        })
    };
    let errors = |s: f64| json!({ "E_C0Y": 0.003 * s, "E_Y0A": 0.01 * s });
    let region = json!({ "plane": "XZ", "uFrom": -250, "uTo": 250, "vFrom": -100, "vTo": 200, "at": 40, "k": 30, "m": -20, "steps": 61 });
    let big = map(&input(motions(1.0), errors(1.0), region.clone())).unwrap();
    let small = map(&input(motions(0.1), errors(0.1), region)).unwrap();
    let total: f64 = big.budget.iter().map(|c| c.share).sum();
    assert!((total - 1.0).abs() < 1e-9, "{total}");
    let names: Vec<&str> = big.budget.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(big.budget.len(), 7, "{names:?}");
    assert!(big.budget_side[0] <= 42 && big.budget_side[0] >= 21);
    // Deviation scales by 1/10, the first-order gap by 1/100.
    let r = big.first_order_gap / small.first_order_gap;
    assert!((r - 100.0).abs() < 5.0, "gap ratio {r}");
    assert!(big.first_order_gap < 1e-2 * big.first_order_max);
    let r = big.worst.norm / small.worst.norm;
    assert!((r - 10.0).abs() < 0.1, "{r}");
}

#[test]
fn a_polynomial_beyond_the_accepted_range_is_refused_where_it_leaves_it() {
    // 1e-2 mm per mm: 5 mm at X = 500, beyond ±5 mm just after.
    let f = function(json!({ "poly": [0, 1e-2] }), "E_XX");
    assert!((f.at(400.0, "E_XX", false).unwrap() - 4.0).abs() < 1e-12);
    let e = f.at(600.0, "E_XX", false).unwrap_err();
    assert!(e.message.contains("gives 6 mm at 600 mm"), "{e}");
    let f = function(json!({ "poly": [0, -1e308, -1e308] }), "E_ZZ");
    assert!(f.at(-18.0, "E_ZZ", false).is_err());
}

#[test]
fn a_csv_whose_header_names_another_error_or_axis_is_refused() {
    let e = read_table_csv("X (mm), E_XX (µm)\n0, 0\n1, 1\n", "E_YY").unwrap_err();
    assert!(
        e.message.starts_with("line 1: the header names E_XX"),
        "{e}"
    );
    let e = read_table_csv("Y (mm), E_XX (µm)\n0, 0\n1, 1\n", "E_XX").unwrap_err();
    assert!(e.message.starts_with("line 1: the header names Y"), "{e}");
    // Other words are the program's own: accepted.
    assert!(read_table_csv("position (mm), deviation (µm)\n0, 0\n1, 1\n", "E_YY").is_ok());
}

/// Left out, the plane across the spindle puts the tool tip on the table surface. At Z 0 the
/// spindle nose is at the rotary centre. On an A/C trunnion (CAZ, the table 100 mm above A's
/// line, a 30 mm tool) a zero-position error of A turns the table about A's line: the tip on that
/// line (Z = 30, the tool length) does not move; on the table surface (Z = 130) it moves along Y
/// by 100 mm times the angle.
#[test]
fn the_default_plane_is_the_table_surface_and_z_0_puts_the_spindle_nose_at_the_rotary_centre() {
    let eps_deg: f64 = 0.001;
    let trunnion = |at: Option<f64>| {
        let mut region =
            json!({ "plane": "XY", "uFrom": -1, "uTo": 1, "vFrom": -1, "vTo": 1, "steps": 3 });
        if let Some(z) = at {
            region["at"] = json!(z);
        }
        VolumetricInput::read(&json!({
            "machine": { "kind": "table-table", "type": "CAZ",
                         "geometry": { "tableHeight": 100, "toolLength": 30 },
                         "errors": { "E_A0A": eps_deg } },
            "region": region,
        }))
        .unwrap()
    };
    const CENTRE: usize = 4; // (u 0, v 0) of the 3 × 3 grid
    let surface = map(&trunnion(None)).unwrap();
    assert_eq!(surface.at, 130.0);
    assert_eq!(surface.surface_at, 130.0);
    assert_eq!(surface.tip_offset, 30.0);
    assert_eq!(surface.table_height, 100.0);
    assert_eq!(surface.spindle_axis, 'Z');
    assert_eq!(surface.worst.position[2], 130.0);
    let want = 100.0 * eps_deg.to_radians();
    let got = surface.norm[CENTRE];
    assert!((got - want).abs() < 1e-9 * want.max(1.0), "{got} vs {want}");
    let on_axis = map(&trunnion(Some(30.0))).unwrap();
    assert!(on_axis.norm[CENTRE] < 1e-12, "{}", on_axis.norm[CENTRE]);
    // Z 0: the tip 30 mm below A's line.
    let zero = map(&trunnion(Some(0.0))).unwrap();
    assert!((zero.norm[CENTRE] - 30.0 * eps_deg.to_radians()).abs() < 1e-12);
    // Given explicitly, the same as the default.
    assert_eq!(map(&trunnion(Some(130.0))).unwrap().norm, surface.norm);
    // A head: the tip is pivot length plus tool length below the head's axis.
    let head = VolumetricInput::read(&json!({
        "machine": { "kind": "head-table", "type": "CBZ",
                     "geometry": { "tableHeight": 50, "pivotLength": 200, "toolLength": 80 } },
        "region": { "plane": "XY", "steps": 2 },
    }))
    .unwrap();
    assert_eq!(map(&head).unwrap().at, 330.0);
    // Across another axis than the spindle's: at 0.
    let xz = VolumetricInput::read(&json!({
        "machine": { "kind": "table-table", "type": "CAZ" },
        "region": { "plane": "XZ", "steps": 2 },
    }))
    .unwrap();
    assert_eq!(map(&xz).unwrap().at, 0.0);
}

/// A three-axis C/A double turntable on an X table (as in `crate/tests/volumetric/map.rs`), tool on the
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

// Found by cargo-mutants: a mutant in `crate/src/volumetric/` survived every other test.
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

// Found by cargo-mutants: a mutant in `crate/src/volumetric/` survived every other test.
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

// Found by cargo-mutants: a mutant in `crate/src/volumetric/` survived every other test.
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

// Found by cargo-mutants: a mutant in `crate/src/volumetric/` survived every other test.
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

// Found by cargo-mutants: a mutant in `crate/src/volumetric/` survived every other test.
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

// Found by cargo-mutants: a mutant in `crate/src/volumetric/` survived every other test.
/// An error entered that moves nothing in the region is left out of the budget (its docs: errors
/// that are zero everywhere): the yaw of the spindle-side Y with the tool on Y's line (no Abbe
/// offset), at A and C zero; next to it X positioning, the one listed.
#[test]
fn an_error_that_moves_nothing_here_is_not_in_the_budget() {
    let m = map_of(json!({ "E_CY": 0.01, "E_XX": 0.01 }), json!({ "steps": 5 }));
    let names: Vec<&str> = m.budget.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["E_XX"]);
}

// Found by cargo-mutants: a mutant in `crate/src/volumetric/` survived every other test.
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

// Found by cargo-mutants: a mutant in `crate/src/volumetric/` survived every other test.
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

// Found by cargo-mutants: a mutant in `crate/src/volumetric/` survived every other test.
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
