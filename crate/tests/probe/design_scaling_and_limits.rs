//! The sphere test's design in the units its docs give (`probe::design`: each unknown scaled by
//! a typical size, 10 µm or 10⁻⁴ rad, each centre coordinate by the probing noise), the poses it
//! counts as reachable at the very edges of the travel, the first-order deviation of errors that
//! are not fitted, and the two inputs checked as a whole (a travel that ends before it starts,
//! pose lists of unequal length).
//
// Found by cargo-mutants (scope `probe`): `Unknown::typical` as 1 or −1, `/ noise` as `* noise`
// in the scaled rows, the sensitivities' `* per` (per degree) as `+` or `/`, every comparison
// and `&&` of `Study::reachable`, the non-fitted errors' share of `first_order`, and
// `ProbeSimulateInput::check` as `Ok(())` changed no outcome of the tests before this file.
// (`ProbeInput::check` as `Ok(())` changes none either: the model's build validates the machine
// again, with the same message; listed as equivalent.)
#![allow(clippy::unwrap_used)]
use crate::probe_common;

use fiveaxis::api::call;
use fiveaxis::machine::TRAVEL_TOLERANCE;
use nalgebra::DMatrix;
use probe_common::{ac_trunnion, bc_table, machines, numbers, study, with_errors};
use serde_json::{json, Value};

/// The typical sizes the module docs of `probe::design` state: 10 µm, and 10⁻⁴ rad in degrees
/// (the sensitivities of `probeSimulate` are per mm and per degree).
const TYPICAL_MM: f64 = 0.01;
const TYPICAL_DEG: f64 = 1e-4 * 180.0 / std::f64::consts::PI;

#[test]
fn a_layouts_singular_values_are_its_centres_sensitivities_in_typical_errors_per_noise() {
    for (name, machine) in machines() {
        for noise in [0.001, 0.0025] {
            let input = json!({ "machine": machine, "sphere": { "x": 150, "y": 20, "height": 80 }, "noise": noise });
            let design = call("probeDesign", &input).unwrap();
            for layout in ["simple", "designed"] {
                let poses = design[layout]["poses"].as_array().unwrap();
                let k: Vec<f64> = poses.iter().map(|p| p["k"].as_f64().unwrap()).collect();
                let m: Vec<f64> = poses.iter().map(|p| p["m"].as_f64().unwrap()).collect();
                let mut sim_input = input.clone();
                sim_input["k"] = json!(k);
                sim_input["m"] = json!(m);
                let sim = call("probeSimulate", &sim_input).unwrap();
                // The sphere where it was placed (a vertical spindle: x, y, height are X, Y, Z).
                assert_eq!(sim["sphere"], json!([150.0, 20.0, 80.0]), "{name}");
                let sens = sim["sensitivities"].as_array().unwrap();
                // The scaled matrix written out: 3 rows per pose, one column per unknown.
                let s = DMatrix::from_fn(3 * k.len(), sens.len(), |r, c| {
                    let typical = match sens[c]["per"].as_str().unwrap() {
                        "deg" => TYPICAL_DEG,
                        "mm" => TYPICAL_MM,
                        other => panic!("per {other}"),
                    };
                    sens[c]["rows"][r / 3][r % 3].as_f64().unwrap() * typical / noise
                });
                let mut want: Vec<f64> = s.singular_values().iter().copied().collect();
                want.sort_by(|a, b| b.total_cmp(a));
                let got = numbers(&design[layout]["singularValues"]);
                assert_eq!(got.len(), want.len(), "{name} {layout}");
                // The designer works on the Gram matrix SᵀS: a singular value the poses do not
                // see comes out as rounding of σ₁ (≈ 1e-8·σ₁), below the rank threshold (1e-6
                // of σ₁) like the true 0; the others agree to rounding.
                let unseen = 1e-6 * want[0];
                for (g, w) in got.iter().zip(&want) {
                    let same = if *w < unseen {
                        g.abs() < unseen
                    } else {
                        (g - w).abs() <= 1e-9 * want[0]
                    };
                    assert!(same, "{name} {layout}, noise {noise}: {got:?} vs {want:?}");
                }
                assert!(want[0] > 1.0, "{name} {layout}: a real scale ({want:?})");
            }
        }
    }
}

#[test]
fn a_pose_at_the_edge_of_the_travel_is_reachable_and_one_just_beyond_is_not() {
    // K with a limited travel, M limited by its travel before the tilt limit (180°).
    let mut machine = ac_trunnion();
    machine["rotary"] =
        json!({ "kFrom": -100, "kTo": 100, "kContinuous": false, "mFrom": -50, "mTo": 30 });
    let s = study(json!({ "machine": machine, "maxTilt": 180 }));
    let r = f64::to_radians;
    let (inside, beyond) = (0.5 * TRAVEL_TOLERANCE, 4.0 * TRAVEL_TOLERANCE);
    let (k0, m0) = (r(10.0), r(-10.0));
    for (what, (k, m), edge) in [
        ("K at its start", (r(-100.0) - inside, m0), true),
        ("K before its start", (r(-100.0) - beyond, m0), false),
        ("K at its end", (r(100.0) + inside, m0), true),
        ("K past its end", (r(100.0) + beyond, m0), false),
        ("M at its start", (k0, r(-50.0) - inside), true),
        ("M before its start", (k0, r(-50.0) - beyond), false),
        ("M at its end", (k0, r(30.0) + inside), true),
        ("M past its end", (k0, r(30.0) + beyond), false),
    ] {
        assert_eq!(s.reachable(k, m).unwrap(), edge, "{what}");
    }
    // The tilt limit: M = 30° tilts the tool 30° from the table's normal.
    let tilted = study(json!({ "machine": machine, "maxTilt": 29.9 }));
    assert!(!tilted.reachable(k0, r(30.0)).unwrap());
    assert!(tilted.reachable(k0, r(29.8)).unwrap());
}

#[test]
fn the_first_order_deviation_counts_the_errors_that_are_not_fitted() {
    // One error fitted, two more on the machine: the first-order deviation is the sum of all
    // three, within the second-order terms of errors this small (≈ 1e-7 mm).
    let machine = with_errors(
        &bc_table(),
        json!({ "E_X0B": 0.01, "E_Y0C": 0.02, "E_A0C": 0.002 }),
    );
    let sim = call(
        "probeSimulate",
        &json!({ "machine": machine, "sphere": { "x": 150, "y": 0, "height": 50 },
            "parameters": ["E_X0B"], "fitSphere": false,
            "k": [0, 45, 90, 200, 300], "m": [0, -30, 60, 20, -75] }),
    )
    .unwrap();
    let mut largest = 0.0f64;
    for p in sim["poses"].as_array().unwrap() {
        let dev = numbers(&p["deviation"]);
        let first = numbers(&p["firstOrder"]);
        for a in 0..3 {
            assert!(
                (dev[a] - first[a]).abs() < 1e-5,
                "{p}: first order {first:?} vs exact {dev:?}"
            );
            largest = largest.max(dev[a].abs());
        }
    }
    assert!(largest > 0.01, "the errors move the centres ({largest} mm)");
}

#[test]
fn a_travel_that_ends_before_it_starts_and_unequal_pose_lists_are_refused_by_name() {
    let mut machine = bc_table();
    machine["rotary"]["mFrom"] = json!(30);
    machine["rotary"]["mTo"] = json!(10);
    let bad = json!({ "machine": machine });
    for export in ["probeDesign", "probeIdentify", "probeSimulate"] {
        let mut input = bad.clone();
        if export == "probeSimulate" {
            input["k"] = json!([0]);
            input["m"] = json!([0]);
        }
        if export == "probeIdentify" {
            input["csv"] = json!("C;B;X;Y;Z\n0;0;150;0;50\n");
        }
        let e = call(export, &input).unwrap_err().to_string();
        assert!(
            e.starts_with("machine.rotary.mTo: must be above where the travel of B starts"),
            "{export}: {e}"
        );
    }
    let e = call(
        "probeSimulate",
        &json!({ "machine": bc_table(), "k": [0, 30], "m": [0] }),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("m: expected as many values as k (2), got 1"),
        "{e}"
    );
}

// Found by cargo-mutants: the grid's edges (`lo / step − 1e-9`), the choice between a travel
// shorter than a turn and one turn from 0 (`hi − lo < 2π − 1e-9`), and the repeats modulo a turn
// changed no outcome of the tests before.
#[test]
fn the_candidates_are_every_multiple_of_the_step_in_the_travel_once_per_turn() {
    // M from −45° to 30° (both ends on the 15° grid): 6 angles; the tilt limit 180° keeps all.
    let with_k = |k_from: f64, k_to: f64, continuous: bool| {
        let mut machine = ac_trunnion();
        machine["rotary"] = json!({ "kFrom": k_from, "kTo": k_to, "kContinuous": continuous,
            "mFrom": -45, "mTo": 30 });
        let d = call(
            "probeDesign",
            &json!({ "machine": machine, "maxTilt": 180 }),
        )
        .unwrap();
        d["candidates"].as_u64().unwrap()
    };
    // K within less than a turn: −90° … 90°, 13 angles.
    assert_eq!(with_k(-100.0, 100.0, false), 13 * 6);
    // K over exactly one turn, either way round: 24 angles, −180° and 180° (0° and 360°) being
    // the same pose.
    assert_eq!(with_k(-180.0, 180.0, false), 24 * 6);
    assert_eq!(with_k(0.0, 360.0, false), 24 * 6);
    // A continuous K: one turn.
    assert_eq!(with_k(-360.0, 360.0, true), 24 * 6);
    // Ends on the grid are kept: K from −90° to 90° exactly.
    assert_eq!(with_k(-90.0, 90.0, false), 13 * 6);
}

/// The designer's objective (module docs of `probe::design`): with `r` the rank all the
/// candidates reach, a layout of rank `r` scores (r, σ_r), one of rank k < r scores
/// (k, Σ ln σ_i over its k singular values); ranks relative to σ₁ at 1e-6.
fn objective(sv: &[f64], r: usize) -> (usize, f64) {
    let top = sv[0];
    let k = sv
        .iter()
        .filter(|s| **s > 1e-6 * top && **s > 0.0)
        .count()
        .min(r);
    if k >= r {
        (r, sv[r - 1])
    } else {
        (k, sv[..k].iter().map(|s| s.ln()).sum())
    }
}

/// The singular values, descending, of the scaled rows of `poses` (each a list of 3 rows).
fn singular_values(rows: &[&Vec<[f64; 3]>], cols: usize) -> Vec<f64> {
    let n = rows.len();
    let s = DMatrix::from_fn(3 * n, cols, |r, c| rows[r / 3][c][r % 3]);
    let mut sv: Vec<f64> = s.singular_values().iter().copied().collect();
    sv.sort_by(|a, b| b.total_cmp(a));
    sv
}

// Found by cargo-mutants: the search's comparisons (`better`, `score`, `rank_of`) as their
// neighbours changed no outcome of the tests before (the designed layout was only compared
// with the simple one).
#[test]
fn no_single_swap_of_a_designed_pose_for_another_candidate_improves_the_design() {
    let noise = 0.001;
    // The rotary axes' errors and the three squarenesses: more than 4 poses can see (a layout
    // of 4 falls short of the rank and is scored by its log-sum).
    let more = json!([
        "E_X0B", "E_Y0B", "E_Z0B", "E_A0B", "E_B0B", "E_C0B", "E_X0C", "E_Y0C", "E_Z0C", "E_A0C",
        "E_B0C", "E_C0C", "E_C0Y", "E_A0Z", "E_B0Z"
    ]);
    for (name, machine, count, parameters) in [
        ("B/C tilting table", bc_table(), 4, Value::Null),
        ("B/C tilting table", bc_table(), 6, Value::Null),
        ("A/C trunnion", ac_trunnion(), 5, Value::Null),
        (
            "B/C tilting table, squareness too",
            bc_table(),
            4,
            more.clone(),
        ),
    ] {
        let input = json!({ "machine": machine, "sphere": { "x": 120, "y": -40, "height": 60 },
            "step": 90, "count": count, "noise": noise, "parameters": parameters });
        let design = call("probeDesign", &input).unwrap();
        // The candidates: the 90° grid within the travel and the tilt limit (90°), and the
        // simple layout's poses.
        let (m_from, m_to) = (
            machine["rotary"]["mFrom"].as_f64().unwrap(),
            machine["rotary"]["mTo"].as_f64().unwrap(),
        );
        let mut poses: Vec<(f64, f64)> = Vec::new();
        for m in [-90.0, 0.0, 90.0] {
            if m >= m_from && m <= m_to {
                for k in [0.0, 90.0, 180.0, 270.0] {
                    poses.push((k, m));
                }
            }
        }
        let pose_of = |p: &Value| (p["k"].as_f64().unwrap(), p["m"].as_f64().unwrap());
        let same = |a: (f64, f64), b: (f64, f64)| {
            (a.0 - b.0)
                .rem_euclid(360.0)
                .min((b.0 - a.0).rem_euclid(360.0))
                < 1e-6
                && (a.1 - b.1).abs() < 1e-6
        };
        for p in design["simple"]["poses"].as_array().unwrap() {
            let q = pose_of(p);
            if !poses.iter().any(|&c| same(c, q)) {
                poses.push(q);
            }
        }
        // Each candidate's scaled rows, from probeSimulate's sensitivities.
        let mut sim_input = input.clone();
        for key in ["step", "count"] {
            sim_input.as_object_mut().unwrap().remove(key);
        }
        sim_input["k"] = json!(poses.iter().map(|p| p.0).collect::<Vec<_>>());
        sim_input["m"] = json!(poses.iter().map(|p| p.1).collect::<Vec<_>>());
        let sim = call("probeSimulate", &sim_input).unwrap();
        let sens = sim["sensitivities"].as_array().unwrap();
        let cols = sens.len();
        let rows: Vec<Vec<[f64; 3]>> = (0..poses.len())
            .map(|i| {
                (0..cols)
                    .map(|c| {
                        let typical = if sens[c]["per"] == "deg" {
                            TYPICAL_DEG
                        } else {
                            TYPICAL_MM
                        };
                        let v = numbers(&sens[c]["rows"][i]);
                        [
                            v[0] * typical / noise,
                            v[1] * typical / noise,
                            v[2] * typical / noise,
                        ]
                    })
                    .collect()
            })
            .collect();
        // Rows per pose as 3 rows of `cols`: transpose the per-unknown triples.
        let pose_rows: Vec<Vec<[f64; 3]>> = rows;
        let layout_sv = |idx: &[usize]| {
            let sel: Vec<&Vec<[f64; 3]>> = idx.iter().map(|&i| &pose_rows[i]).collect();
            singular_values(&sel, cols)
        };
        let all: Vec<usize> = (0..poses.len()).collect();
        let sv_all = layout_sv(&all);
        let r = sv_all.iter().filter(|s| **s > 1e-6 * sv_all[0]).count();
        // The designed layout among the candidates.
        let chosen: Vec<usize> = design["designed"]["poses"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| {
                let q = pose_of(p);
                poses
                    .iter()
                    .position(|&c| same(c, q))
                    .unwrap_or_else(|| panic!("{name}: designed pose {q:?} is no candidate"))
            })
            .collect();
        assert_eq!(chosen.len(), count, "{name}");
        let here = objective(&layout_sv(&chosen), r);
        let smallest = design["designed"]["smallest"].as_f64().unwrap();
        if here.0 == r {
            assert!(
                (here.1 - smallest).abs() <= 1e-9 * sv_all[0],
                "{name}: σ_r {here:?} vs {smallest}"
            );
        }
        for slot in 0..count {
            for c in 0..poses.len() {
                if chosen.contains(&c) {
                    continue;
                }
                let mut other = chosen.clone();
                other[slot] = c;
                let there = objective(&layout_sv(&other), r);
                let improves = there.0 > here.0
                    || (there.0 == here.0 && there.1 > here.1 + 1e-6 * here.1.abs().max(1e-12));
                assert!(
                    !improves,
                    "{name}, {count} poses: {:?} in place of {:?} gives {there:?} > {here:?}",
                    poses[c], poses[chosen[slot]]
                );
            }
        }
    }
}

// Found while testing the search's mutants: with only errors no pose can see, the design said
// "rank 1" and "identifiable" from columns of the chain's rounding (1e-14 noise deviations).
#[test]
fn a_design_of_errors_no_pose_can_see_is_refused_by_name() {
    // E_C0C on a B/C table with the sphere on the C axis (its default place, 0, 0): C's zero
    // turns the sphere about its own centre.
    let e = call(
        "probeDesign",
        &json!({ "machine": bc_table(), "parameters": ["E_C0C"], "fitSphere": false }),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("parameters: no pose within the travel and the tilt limit sees E_C0C"),
        "{e}"
    );
    // A measurement of it cannot be identified either: refused at the file (the fit's own
    // refusal, named for the input it comes from). (Found by cargo-mutants: the fit's error
    // kept its own field name instead of the file's, and no test saw it.)
    let e = call(
        "probeIdentify",
        &json!({ "machine": bc_table(), "parameters": ["E_C0C"], "fitSphere": false,
            "csv": "C;B;X;Y;Z\n0;0;0;0;50\n90;0;0;0;50\n0;30;0;0;50\n" }),
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("csv: no parameter has any effect"), "{e}");
    // Off the axis it is seen, and identifiable.
    let d = call(
        "probeDesign",
        &json!({ "machine": bc_table(), "parameters": ["E_C0C"], "fitSphere": false,
            "sphere": { "x": 100, "y": 0, "height": 50 } }),
    )
    .unwrap();
    assert_eq!(d["visibility"]["identifiable"], json!(["E_C0C"]));
    assert!(
        d["designed"]["smallest"].as_f64().unwrap() > 1.0,
        "{}",
        d["designed"]
    );
}

// Found by cargo-mutants: the spread's divisions and products (`Spread::of`) and the "before"
// residuals' sign changed no outcome of the tests before (they checked only that the spread
// before is larger than after).
#[test]
fn the_wander_is_each_poses_distance_from_the_best_fixed_sphere_and_its_rms_per_coordinate() {
    let sphere = [120.0, -30.0, 80.0];
    let machine = bc_table();
    let measured = with_errors(
        &machine,
        json!({ "E_X0C": 0.02, "E_A0B": 0.004, "E_Z0B": -0.01 }),
    );
    let poses: Vec<(f64, f64)> = vec![
        (0.0, 0.0),
        (90.0, 0.0),
        (180.0, 0.0),
        (270.0, 0.0),
        (0.0, -60.0),
        (0.0, 60.0),
        (45.0, 30.0),
        (225.0, -45.0),
        (135.0, 75.0),
    ];
    let mut csv = String::from("pose,C_deg,B_deg,X_mm,Y_mm,Z_mm\n");
    for (i, &(k, m)) in poses.iter().enumerate() {
        let c = probe_common::centre(&measured, sphere, k.to_radians(), m.to_radians());
        // A fixed pattern of ±1 µm on top, so that "after" is not zero.
        let n = |a: usize| (((3 * i + a) * 7919) % 2001) as f64 * 1e-6 - 1e-3;
        csv.push_str(&format!(
            "{},{k},{m},{:.7},{:.7},{:.7}\n",
            i + 1,
            c[0] + n(0),
            c[1] + n(1),
            c[2] + n(2)
        ));
    }
    let base = json!({ "machine": machine, "sphere": { "x": sphere[0], "y": sphere[1], "height": sphere[2] },
        "parameters": ["E_X0B", "E_Z0B", "E_A0B", "E_X0C", "E_A0C"] });
    let mut input = base.clone();
    input["csv"] = json!(csv);
    let r = call("probeIdentify", &input).unwrap();
    let fitted = r["poses"].as_array().unwrap();
    assert_eq!(fitted.len(), poses.len());
    // The sphere's position's sensitivities at the same poses, from probeSimulate.
    let mut sim_input = base.clone();
    sim_input["k"] = json!(poses.iter().map(|p| p.0).collect::<Vec<_>>());
    sim_input["m"] = json!(poses.iter().map(|p| p.1).collect::<Vec<_>>());
    let sim = call("probeSimulate", &sim_input).unwrap();
    let sphere_cols: Vec<&Value> = sim["sensitivities"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["name"].as_str().unwrap().starts_with("sphere_"))
        .collect();
    assert_eq!(sphere_cols.len(), 3);
    for (key, what) in [
        ("before", "as measured, less the best fixed sphere"),
        ("after", "after correction"),
    ] {
        let res: Vec<Vec<f64>> = fitted.iter().map(|p| numbers(&p[key])).collect();
        // Spread: the rms of one coordinate over every pose, the largest 3-D distance.
        let sum2: f64 = res.iter().flatten().map(|v| v * v).sum();
        let sigma = (sum2 / (3 * res.len()) as f64).sqrt();
        let max = res
            .iter()
            .map(|v| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
            .fold(0.0, f64::max);
        let got = &r[key];
        assert!(
            (got["sigma"].as_f64().unwrap() - sigma).abs() < 1e-12,
            "{what}: {got} vs σ {sigma}"
        );
        assert!(
            (got["max"].as_f64().unwrap() - max).abs() < 1e-12,
            "{what}: {got} vs max {max}"
        );
        assert!(sigma > 1e-5, "{what}: a real spread ({sigma} mm)");
        // Least squares: the residuals are square to what a shift of the sphere does.
        for s in &sphere_cols {
            let dot: f64 = (0..poses.len())
                .map(|i| {
                    (0..3)
                        .map(|a| s["rows"][i][a].as_f64().unwrap() * res[i][a])
                        .sum::<f64>()
                })
                .sum();
            assert!(
                dot.abs() < 1e-9,
                "{what}: residuals · {} = {dot}",
                s["name"]
            );
        }
    }
    // Before is the measured centres less the expected ones less one fixed shift of the sphere:
    // the differences between poses of (measured − expected − before) are a shift's.
    let shift = |p: &Value| -> Vec<f64> {
        let (m, e, b) = (
            numbers(&p["measured"]),
            numbers(&p["expected"]),
            numbers(&p["before"]),
        );
        (0..3).map(|a| m[a] - e[a] - b[a]).collect()
    };
    let at_home = shift(&fitted[0]);
    assert!(
        at_home.iter().any(|v| v.abs() > 1e-4),
        "the errors shift the sphere: {at_home:?}"
    );
    // At C = 90°, B = 0 on a B/C table the sphere's shift is turned by C: its length is kept.
    let at_90 = shift(&fitted[1]);
    let len = |v: &[f64]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    assert!(
        (len(&at_home) - len(&at_90)).abs() < 1e-9,
        "{at_home:?} vs {at_90:?}"
    );
}

// Found by cargo-mutants: the numbers of the designed table (`num` as an empty text) changed no
// outcome of the tests before.
#[test]
fn the_designed_table_filled_in_reads_back_as_the_designed_poses() {
    let d = call(
        "probeDesign",
        &json!({ "machine": ac_trunnion(), "sphere": { "x": 80.5, "y": -12.25, "height": 60 } }),
    )
    .unwrap();
    let csv = d["designed"]["csv"].as_str().unwrap();
    assert!(csv.contains("sphere at 80.5, -12.25, 60 mm"), "{csv}");
    let filled = csv.replace(",,,\n", ",1,2,3\n");
    let m = fiveaxis::probe::measure::read(&filled, Some(['C', 'A'])).unwrap();
    let poses = d["designed"]["poses"].as_array().unwrap();
    assert_eq!(m.poses.len(), poses.len());
    for (got, want) in m.poses.iter().zip(poses) {
        assert!(
            (got.k.to_degrees() - want["k"].as_f64().unwrap()).abs() < 1e-6,
            "{want}"
        );
        assert!(
            (got.m.to_degrees() - want["m"].as_f64().unwrap()).abs() < 1e-6,
            "{want}"
        );
        assert_eq!(got.centre, [1.0, 2.0, 3.0]);
    }
}
