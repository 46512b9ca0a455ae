//! The sphere test's poses and what a sphere cannot see (issue 31): the simple layout as the
//! issue defines it, the designed layout reachable, of full rank on what the sphere can see and
//! no worse than the simple one, NC blocks one per pose; every error declared invisible moves
//! no centre of the exact chain, and C's zero is exactly a turn of the sphere on the table.
#![allow(clippy::unwrap_used)]
use crate::probe_common;

use fiveaxis::probe::design::{self, ProbeDesign, ProbeDesignInput};
use fiveaxis::schema::Inputs;
use probe_common::{bc_table, centre, machines, rot, study, with_errors};
use serde_json::{json, Value};

fn designed(machine: &Value, sphere: [f64; 3]) -> ProbeDesign {
    let s = study(json!({ "machine": machine,
        "sphere": { "x": sphere[0], "y": sphere[1], "height": sphere[2] } }));
    design::design(&s, &ProbeDesignInput::from_value(&json!({}), "").unwrap()).unwrap()
}

fn deg(v: f64) -> f64 {
    (v.to_degrees() * 1e6).round() / 1e6
}

#[test]
fn the_simple_layout_is_k_every_30_degrees_at_m_0_then_m_every_30_degrees_at_k_0() {
    // Tilt limit 90° (the default): M from −90° to +90° within the travel.
    for (machine, ms) in [
        (
            probe_common::bc_table(),
            vec![-90.0, -60.0, -30.0, 30.0, 60.0, 90.0],
        ),
        (probe_common::ac_trunnion(), vec![-90.0, -60.0, -30.0, 30.0]),
        (
            probe_common::head_table(),
            vec![-90.0, -60.0, -30.0, 30.0, 60.0, 90.0],
        ),
    ] {
        let s = study(json!({ "machine": machine }));
        let got: Vec<(f64, f64)> = design::simple_poses(&s)
            .unwrap()
            .iter()
            .map(|&(k, m)| (deg(k), deg(m)))
            .collect();
        let mut want: Vec<(f64, f64)> = (0..12).map(|j| (30.0 * j as f64, 0.0)).collect();
        want.extend(ms.iter().map(|&m| (0.0, m)));
        let mut g = got.clone();
        g.sort_by(|a, b| a.partial_cmp(b).unwrap());
        want.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(g, want);
        assert_eq!(got[0], (0.0, 0.0), "the reference pose first");
    }
}

#[test]
fn the_designed_poses_are_reachable_of_full_rank_and_no_worse_than_the_simple_layout() {
    for (name, machine) in machines() {
        let d = designed(&machine, [150.0, 0.0, 100.0]);
        let (lo, hi) = (
            machine["rotary"]["mFrom"].as_f64().unwrap(),
            machine["rotary"]["mTo"].as_f64().unwrap(),
        );
        for p in &d.designed.poses {
            let m = p.m.to_degrees();
            // Within the travel and the 90° tilt limit (for these machines the tilt is |M|).
            assert!(
                m >= lo - 1e-9 && m <= hi + 1e-9 && m.abs() <= 90.0 + 1e-9,
                "{name}: M {m}"
            );
            assert!((p.tilt - p.m.abs()).abs() < 1e-9, "{name}: tilt {}", p.tilt);
        }
        let r = d.visibility.reachable_rank;
        assert_eq!(
            d.designed.rank, r,
            "{name}: full rank on what the sphere sees"
        );
        assert_eq!(d.designed.poses.len(), d.simple.poses.len());
        assert!(
            d.designed.smallest >= d.simple.smallest,
            "{name}: designed σ_r {} below the simple layout's {}",
            d.designed.smallest,
            d.simple.smallest
        );
        assert!((d.designed.smallest - d.designed.singular_values[r - 1]).abs() < 1e-12);
        println!(
            "{name}: σ_r designed {:.2}, simple {:.2} ({} poses, rank {r})",
            d.designed.smallest,
            d.simple.smallest,
            d.designed.poses.len()
        );
        // Poses with both axes turned are used where they help.
        assert!(
            d.designed.poses.iter().any(|p| p.k != 0.0 && p.m != 0.0),
            "{name}"
        );
    }
}

#[test]
fn the_nc_blocks_position_the_rotary_axes_one_pose_per_block_and_say_to_probe_there() {
    let d = designed(&bc_table(), [150.0, 0.0, 100.0]);
    let blocks: Vec<&str> = d
        .designed
        .nc
        .lines()
        .filter(|l| l.starts_with('N'))
        .collect();
    assert_eq!(blocks.len(), d.designed.poses.len());
    for (b, p) in blocks.iter().zip(&d.designed.poses) {
        let word = |letter: char| -> f64 {
            let w = b
                .split_whitespace()
                .find(|w| w.starts_with(letter) && w[1..].parse::<f64>().is_ok())
                .unwrap();
            w[1..].parse().unwrap()
        };
        assert!(b.contains(" G0 "), "{b}");
        assert!((word('C') - p.k.to_degrees()).abs() < 6e-4, "{b}");
        assert!((word('B') - p.m.to_degrees()).abs() < 6e-4, "{b}");
        assert!(
            b.contains("RUN THE CONTROL'S SPHERE-PROBING CYCLE HERE"),
            "{b}"
        );
    }
    // The pose table has as many rows, with empty measured columns.
    let rows = d
        .designed
        .csv
        .lines()
        .filter(|l| !l.starts_with('#'))
        .count();
    assert_eq!(rows, d.designed.poses.len() + 1);
}

#[test]
fn every_error_declared_invisible_moves_no_centre_of_the_exact_chain() {
    let mut seen = 0;
    for (name, machine) in machines() {
        // The sphere on the table axis: C's zero cannot be seen.
        let sphere = [0.0, 0.0, 100.0];
        let d = designed(&machine, sphere);
        assert!(
            d.visibility.invisible.iter().any(|u| u.name == "E_C0C"),
            "{name}: {:?}",
            d.visibility.invisible
        );
        let s = study(json!({ "machine": machine }));
        let poses = design::candidate_poses(&s, 30f64.to_radians()).unwrap();
        // 12 angles of K in a turn, and M at least at −30°, 0, 30°. (Found by cargo-mutants:
        // a list of one pose passed this test.)
        assert!(poses.len() >= 36, "{name}: {} candidate poses", poses.len());
        for u in &d.visibility.invisible {
            let def = fiveaxis::machine::errors::find(&u.name).unwrap();
            let size = 0.01; // mm or degrees
            let moved = with_errors(&machine, json!({ u.name.clone(): size }));
            for &(k, m) in &poses {
                let c = centre(&moved, sphere, k, m);
                let c0 = centre(&machine, sphere, k, m);
                assert!(
                    (c - c0).norm() < 1e-9,
                    "{name}: {} ({:?}) moves the centre at K {k} M {m} by {}",
                    u.name,
                    def.quantity,
                    (c - c0).norm()
                );
            }
            seen += 1;
        }
        // And each error it says it identifies moves some centre by more than 1 µm.
        for n in &d.visibility.identifiable {
            let moved = with_errors(&machine, json!({ n.clone(): 0.01 }));
            let most = poses
                .iter()
                .map(|&(k, m)| {
                    (centre(&moved, sphere, k, m) - centre(&machine, sphere, k, m)).norm()
                })
                .fold(0.0, f64::max);
            assert!(
                most > 1e-3,
                "{name}: {n} moves no centre by more than {most}"
            );
        }
    }
    assert!(seen >= 3);
}

#[test]
fn c_zero_is_exactly_the_sphere_turned_on_the_table_so_it_is_inseparable_from_its_position() {
    // E_C0C = ε turns everything C carries by ε about C's line (through the table centre):
    // exactly the sphere set at R_Z(ε)·s.
    let eps = 0.05f64;
    let s = nalgebra::Vector3::new(150.0, 20.0, 100.0);
    let turned = rot(2, eps.to_radians()) * s;
    let machine = bc_table();
    let moved = with_errors(&machine, json!({ "E_C0C": eps }));
    for (k, m) in [(0.0, 0.0), (1.0, 0.5), (2.5, -1.2)] {
        let a = centre(&moved, [s[0], s[1], s[2]], k, m);
        let b = centre(&machine, [turned[0], turned[1], turned[2]], k, m);
        assert!((a - b).norm() < 1e-9, "{a} vs {b}");
    }
    let d = designed(&machine, [150.0, 20.0, 100.0]);
    let g = d
        .visibility
        .inseparable
        .iter()
        .find(|g| g.members.iter().any(|m| m == "E_C0C"))
        .unwrap();
    assert!(g.members.iter().any(|m| m.starts_with("sphere_")), "{g:?}");
}

#[test]
fn a_c_tilt_and_an_offset_of_c_alike_on_the_axis_are_told_apart_by_a_second_sphere() {
    // On C's axis at height h a tilt ε of C moves the sphere as an offset of h·ε would: one
    // sphere there cannot identify E_A0C; a second one higher and off the axis can.
    let d = designed(&bc_table(), [0.0, 0.0, 100.0]);
    assert!(!d.visibility.identifiable.iter().any(|n| n == "E_A0C"));
    assert!(
        d.second_sphere.gained.iter().any(|n| n == "E_A0C"),
        "{:?}",
        d.second_sphere
    );
}

#[test]
fn the_second_sphere_is_where_its_fields_say_and_each_one_left_out_follows_the_first_sphere() {
    // The B/C table has a vertical spindle: the table's face frame is X, Y, Z, its surface at
    // the B axis (tableHeight 0), so a place (x, y, height) is the point (x, y, height).
    let s = study(json!({ "machine": bc_table(),
        "sphere": { "x": 150.0, "y": 20.0, "height": 100.0 } }));
    let second = |v: Value| {
        let own = ProbeDesignInput::from_value(&json!({ "step": 45, "second": v }), "").unwrap();
        design::design(&s, &own).unwrap().second_sphere.centre
    };
    let close = |a: [f64; 3], b: [f64; 3]| (0..3).all(|i| (a[i] - b[i]).abs() < 1e-9);
    // Left out: 100 mm further along X and 100 mm higher than the first.
    let c = second(json!({}));
    assert!(close(c, [250.0, 20.0, 200.0]), "{c:?}");
    let c = second(json!({ "y": -50.0 }));
    assert!(close(c, [250.0, -50.0, 200.0]), "{c:?}");
    let c = second(json!({ "x": 10.0, "y": 0.0, "height": 50.0 }));
    assert!(close(c, [10.0, 0.0, 50.0]), "{c:?}");
    // Its fields are labelled apart from the first sphere's (the page shows both).
    let f = fiveaxis::schema::describe(ProbeDesignInput::FIELDS, "");
    let label = |path: &str| f.iter().find(|i| i.path == path).unwrap().label.clone();
    assert_ne!(
        label("second.x"),
        "Sphere centre along the table's first axis"
    );
    assert!(f
        .iter()
        .filter(|i| i.path.starts_with("second."))
        .all(|i| i.default.is_null()));
}

#[test]
fn the_nc_blocks_write_no_negative_zero() {
    // The sphere on C's axis: the expected X and Y are zero but for rounding (±1e-15 mm).
    let d = designed(&bc_table(), [0.0, 0.0, 100.0]);
    for l in d.designed.nc.lines().chain(d.simple.nc.lines()) {
        assert!(!l.contains("-0.000 ") && !l.contains("-0.000)"), "{l}");
    }
}

#[test]
fn with_the_sphere_fitted_two_sphere_positions_reach_the_errors_rank_plus_six() {
    // Each sphere position is three unknowns of its own (its centre), seen fully at any pose (a
    // shift of the sphere shifts every centre by itself): two positions add six to the rank of
    // the errors they identify. So with errors all identifiable the second sphere's rank is
    // their number + 6, and one error alone gives 7.
    // (Found by cargo-mutants, scope `probe`: the stacked rows' width as ne × 6, or the second
    // sphere's columns at ne − 3 instead of ne + 3, changed no test's outcome before.)
    let mut checked = 0;
    for (name, machine) in machines() {
        for parameters in [
            json!(["E_X0C"]),
            json!(["E_X0C", "E_Y0C"]),
            json!(["E_X0C", "E_Y0C", "E_A0C", "E_B0C"]),
        ] {
            let input = json!({ "machine": machine, "sphere": { "x": 150, "y": 20, "height": 80 },
                "parameters": parameters, "step": 90 });
            let d = fiveaxis::api::call("probeDesign", &input).unwrap();
            let errors = parameters.as_array().unwrap().len();
            let one = &d["visibility"];
            if one["identifiable"].as_array().unwrap().len() < errors {
                continue; // a group or an unseen error: the rank is not a count then
            }
            let second = &d["secondSphere"];
            assert_eq!(
                second["identifiable"].as_array().unwrap().len(),
                errors,
                "{name} {parameters}: {second}"
            );
            assert_eq!(
                second["reachableRank"],
                json!(errors + 6),
                "{name} {parameters}"
            );
            checked += 1;
        }
    }
    // One error alone and two are seen on every machine.
    assert!(checked >= 6, "{checked}");
}

// Found by cargo-mutants (scope `probe`): the reasons given for invisible errors (a turn about
// the sphere's own axis line, or any error whose effect vanishes), the condition number, the
// simple layout as the design reports it, and a count of poses above the simple layout's
// changed no test's outcome before. Each mutant was checked by hand to fail one of these.
#[test]
fn with_the_sphere_where_both_axis_lines_meet_each_axis_own_turn_is_said_to_be_one() {
    // B/C table with no offsets: B's line (along Y) and C's (along Z) meet at the origin. A turn
    // about a line through the sphere's centre moves no centre: the zeros of B and C are their
    // own turns; the tilts of each axis (about lines through the same point) are invisible too,
    // for the general reason.
    let input =
        json!({ "machine": bc_table(), "sphere": { "x": 0, "y": 0, "height": 0 }, "step": 90 });
    let d = fiveaxis::api::call("probeDesign", &input).unwrap();
    let why = |name: &str| -> String {
        d["visibility"]["invisible"]
            .as_array()
            .unwrap()
            .iter()
            .find(|u| u["name"] == name)
            .map(|u| u["why"].as_str().unwrap().to_string())
            .unwrap_or_else(|| panic!("{name} not invisible: {}", d["visibility"]))
    };
    for (own, axis) in [("E_B0B", 'B'), ("E_C0C", 'C')] {
        assert!(
            why(own).starts_with(&format!(
                "the sphere lies on the {axis} axis line at every pose"
            )),
            "{own}: {}",
            why(own)
        );
    }
    for other in ["E_A0B", "E_C0B", "E_A0C", "E_B0C"] {
        assert!(
            why(other).starts_with("its effect on every measured centre is zero"),
            "{other}: {}",
            why(other)
        );
    }
}

#[test]
fn a_layouts_condition_is_its_largest_singular_value_over_the_rth_and_null_when_short() {
    let r_of = |d: &Value| d["visibility"]["reachableRank"].as_u64().unwrap() as usize;
    for (name, machine) in machines() {
        let input = json!({ "machine": machine, "sphere": { "x": 150, "y": 20, "height": 80 }, "step": 90 });
        let d = fiveaxis::api::call("probeDesign", &input).unwrap();
        let r = r_of(&d);
        for layout in ["simple", "designed"] {
            let l = &d[layout];
            let sv = probe_common::numbers(&l["singularValues"]);
            assert_eq!(l["rank"].as_u64().unwrap() as usize, r, "{name} {layout}");
            let want = sv[0] / sv[r - 1];
            let got = l["condition"].as_f64().unwrap();
            assert!(
                (got - want).abs() <= 1e-12 * want,
                "{name} {layout}: {got} vs {want}"
            );
            assert_eq!(
                l["smallest"].as_f64().unwrap(),
                sv[r - 1],
                "{name} {layout}"
            );
        }
    }
    // Four poses (the fewest) cannot reach the rank of the rotary axes' errors and three
    // squarenesses on a B/C table (as crate/tests/probe/design_scaling_and_limits.rs finds): no condition.
    let more = json!([
        "E_X0B", "E_Y0B", "E_Z0B", "E_A0B", "E_B0B", "E_C0B", "E_X0C", "E_Y0C", "E_Z0C", "E_A0C",
        "E_B0C", "E_C0C", "E_C0Y", "E_A0Z", "E_B0Z"
    ]);
    let input = json!({ "machine": bc_table(), "sphere": { "x": 120, "y": -40, "height": 60 },
        "step": 90, "count": 4, "parameters": more });
    let d = fiveaxis::api::call("probeDesign", &input).unwrap();
    assert!(
        d["designed"]["rank"].as_u64().unwrap() < r_of(&d) as u64,
        "{}",
        d["designed"]["rank"]
    );
    assert_eq!(d["designed"]["condition"], Value::Null);
}

#[test]
fn the_design_reports_the_simple_layout_and_as_many_poses_as_asked_beyond_it() {
    for (name, machine) in machines() {
        let s = study(json!({ "machine": machine }));
        let simple: Vec<(f64, f64)> = design::simple_poses(&s)
            .unwrap()
            .iter()
            .map(|&(k, m)| (deg(k), deg(m)))
            .collect();
        let input = json!({ "machine": machine, "step": 30 });
        let d = fiveaxis::api::call("probeDesign", &input).unwrap();
        let poses = |l: &Value| -> Vec<(f64, f64)> {
            l["poses"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| {
                    (
                        (p["k"].as_f64().unwrap() * 1e6).round() / 1e6,
                        (p["m"].as_f64().unwrap() * 1e6).round() / 1e6,
                    )
                })
                .collect()
        };
        // The simple layout as simple_poses gives it (degrees in the export), in its order.
        let mut got = poses(&d["simple"]);
        let mut want = simple.clone();
        assert_eq!(got.len(), want.len(), "{name}");
        got.sort_by(|a, b| a.partial_cmp(b).unwrap());
        want.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(got, want, "{name}");
        // On the 30° grid the simple poses are candidates already: none is added.
        let grid = design::candidate_poses(&s, 30f64.to_radians())
            .unwrap()
            .len();
        assert_eq!(d["candidates"].as_u64().unwrap() as usize, grid, "{name}");
        // Two more poses than the simple layout: that many, all distinct.
        let mut more = input.clone();
        more["count"] = json!(simple.len() + 2);
        let dm = fiveaxis::api::call("probeDesign", &more).unwrap();
        let p = poses(&dm["designed"]);
        assert_eq!(p.len(), simple.len() + 2, "{name}");
        for (i, a) in p.iter().enumerate() {
            assert!(p[..i].iter().all(|b| b != a), "{name}: {a:?} twice");
        }
    }
}
