//! The machine definition against references built independently of it: chains written link by
//! link from the module docs' layout, the rotary-axis type's tool vector `R_K·R_M·e_H`
//! (eq 4 of Geng et al.), forward kinematics of inverse kinematics within the travel, and the
//! error table's names applied one at a time.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::{close, close3, machine, Rng};
use fiveaxis::chain::{Chain, Link, Setup};
use fiveaxis::geometry::{rotate, Axis};
use fiveaxis::machine::errors::TABLE;
use fiveaxis::machine::schematic::schematic;
use fiveaxis::machine::{fit, BranchRule, Machine, MachineKind};
use fiveaxis::rotary::{Pose, RotaryType};
use fiveaxis::schema::Inputs;
use nalgebra::Vector3;
use serde_json::{json, Value};
use std::f64::consts::{PI, TAU};

const KINDS: [&str; 3] = ["table-table", "head-table", "head-head"];
const LINEAR: [&str; 5] = ["spindle-xyz", "table-y", "table-x", "table-xy", "table-z"];

#[test]
fn the_tool_vector_is_r_k_r_m_e_h_for_every_kind_type_layout_and_sense() {
    let mut rng = Rng::new(7);
    for kind in KINDS {
        for t in RotaryType::ALL {
            for (i, linear) in LINEAR.iter().enumerate() {
                let (kr, mr) = (i % 2 == 1, i % 3 == 1);
                let m = machine(json!({
                    "kind": kind, "type": t.name(), "linear": linear,
                    "geometry": if kind == "head-table" { json!({ "tableHeight": 40 }) } else { json!({ "rotaryOffset": 25, "tableHeight": 40 }) },
                    "rotary": { "kReversed": kr, "mReversed": mr },
                }));
                let model = m.build().unwrap();
                let chain = model.nominal();
                assert_eq!(model.layout.rtype, t, "{kind} {}", t.name());
                for _ in 0..5 {
                    let (k, mm) = (rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
                    let q = model.positions(k, mm);
                    let axis = chain.tool_pose(&q, false, &Setup::None).unwrap().axis;
                    let sk = if kr { -1.0 } else { 1.0 };
                    let sm = if mr { -1.0 } else { 1.0 };
                    let v = rotate(
                        t.k.axis(),
                        sk * k,
                        &rotate(t.m.axis(), sm * mm, &t.home.unit()),
                    );
                    assert!((axis - v).norm() < 1e-12, "{kind} {} {linear}", t.name());
                }
            }
        }
    }
}

#[test]
fn the_papers_machines_are_the_chains_written_out_link_by_link() {
    let mut rng = Rng::new(3);
    // Li et al.: B on the bed, C on B (offset along X), X Y Z on the spindle, ISO 841 signs.
    let mut li = common::machine_preset("B/C tilting table, vertical spindle (Li et al.");
    li["geometry"] = json!({ "rotaryOffset": 12, "tableHeight": -30, "toolLength": 0 });
    let li = machine(li);
    let li_chain = Chain {
        work: vec![
            Link::rotary("B", Axis::Y).on_table(),
            Link::rotary("C", Axis::Z)
                .on_table()
                .at(Vector3::new(12.0, 0.0, 0.0)),
        ],
        tool: vec![
            Link::linear("X", Axis::X),
            Link::linear("Y", Axis::Y),
            Link::linear("Z", Axis::Z),
        ],
        work_origin: Vector3::new(0.0, 0.0, -30.0),
        tool_tip: Vector3::zeros(),
        tool_axis: Axis::Z,
    };
    // Chanal et al.: Y under the table, C on it turning by +C, X Z B on the spindle, the tip L0
    // below B.
    let chanal = machine(common::machine_preset("B swivel head, C rotary table"));
    let mut c_axis = Link::rotary("C", Axis::Z).on_table();
    c_axis.sign = 1.0;
    let chanal_chain = Chain {
        work: vec![Link::linear("Y", Axis::Y).on_table(), c_axis],
        tool: vec![
            Link::linear("X", Axis::X),
            Link::linear("Z", Axis::Z),
            Link::rotary("B", Axis::Y),
        ],
        work_origin: Vector3::zeros(),
        tool_tip: Vector3::new(0.0, 0.0, -499.889),
        tool_axis: Axis::Z,
    };
    for (m, reference) in [(li, li_chain), (chanal, chanal_chain)] {
        let chain = m.build().unwrap().chain;
        assert_eq!(chain.axis_names(), reference.axis_names());
        for _ in 0..20 {
            let q: Vec<f64> = (0..5).map(|_| rng.range(-300.0, 300.0) * 0.01).collect();
            let a = chain.tool_pose(&q, false, &Setup::None).unwrap();
            let b = reference.tool_pose(&q, false, &Setup::None).unwrap();
            assert!((a.tip - b.tip).norm() < 1e-9 && (a.axis - b.axis).norm() < 1e-14);
        }
    }
}

#[test]
fn every_error_of_the_table_moves_its_axis_frame_by_its_component() {
    // Each error alone on a machine that has its axis: the chain's location error of that
    // axis carries exactly that component, in engine units (degrees at the edge).
    for def in TABLE {
        let t = match def.axis {
            'A' => "CAZ",
            'B' | 'X' | 'Y' | 'Z' => "CBZ",
            _ => "BCY",
        };
        let value: f64 = if def.component < 3 { 0.0123 } else { 0.0456 };
        let m = machine(json!({ "type": t, "errors": { def.name: value } }));
        let model = m.build().unwrap();
        let link = model.chain.index_of(&def.axis.to_string()).unwrap();
        for (i, (_, l)) in model.chain.links().enumerate() {
            for c in 0..6 {
                let expected = if i == link && c == def.component {
                    if c < 3 {
                        value
                    } else {
                        value.to_radians()
                    }
                } else {
                    0.0
                };
                assert_eq!(l.location.get(c), expected, "{} on {}", def.name, l.name);
            }
        }
    }
}

#[test]
fn errors_of_axes_the_machine_lacks_and_misplaced_geometry_are_refused() {
    let err = |v: Value| {
        Machine::from_value(&v, "machine")
            .and_then(|m| m.build().map(|_| ()))
            .unwrap_err()
            .to_string()
    };
    assert!(err(json!({ "type": "CBZ", "errors": { "E_Y0A": 0.01 } }))
        .starts_with("machine.errors.E_Y0A: this machine has no A axis"));
    assert!(
        err(json!({ "kind": "table-table", "geometry": { "pivotLength": 200 } }))
            .starts_with("machine.geometry.pivotLength: does not apply to a table-table machine")
    );
    assert!(
        err(json!({ "kind": "head-table", "geometry": { "rotaryOffset": 2 } }))
            .starts_with("machine.geometry.rotaryOffset: does not apply to a head-table machine")
    );
    assert!(
        err(json!({ "rotary": { "mFrom": 30, "mTo": 10 } })).starts_with("machine.rotary.mTo: ")
    );
    assert!(err(json!({ "typ": "CBZ" })).starts_with("machine.typ: unknown input"));
    assert!(err(json!({ "type": "CBY" })).starts_with("machine.type: expected one of"));
}

/// Every direction and tip, every kind and type: the pose found is within the travel and the
/// nominal chain puts the tool there.
#[test]
fn inverse_kinematics_within_the_travel_round_trips() {
    let mut rng = Rng::new(11);
    for kind in KINDS {
        for t in RotaryType::ALL {
            let m = machine(json!({
                "kind": kind, "type": t.name(), "linear": "table-xy",
                "rotary": { "kFrom": -200, "kTo": 200, "mFrom": -110, "mTo": 110 },
            }));
            let model = m.build().unwrap();
            let chain = model.nominal();
            let mut previous: Option<Vec<f64>> = None;
            for i in 0..40 {
                let dir = rng.direction();
                let tip = Vector3::new(
                    rng.range(-80.0, 80.0),
                    rng.range(-80.0, 80.0),
                    rng.range(-80.0, 80.0),
                );
                let rule = if i % 2 == 0 {
                    BranchRule::SmallestTilt
                } else {
                    BranchRule::Nearest
                };
                let s = match model.inverse(&tip, &dir, rule, previous.as_deref()) {
                    Ok(s) => s,
                    Err(e) => {
                        // Only tilts beyond 110° are out of reach.
                        assert!(e.message.contains("outside the travel"), "{e}");
                        continue;
                    }
                };
                let pose = chain.tool_pose(&s.q, false, &Setup::None).unwrap();
                assert!((pose.tip - tip).norm() < 1e-9, "{kind} {}", t.name());
                assert!((pose.axis - dir).norm() < 1e-12, "{kind} {}", t.name());
                let [k, mm] = model.rotary_of(&s.q);
                assert!((-200f64.to_radians() - 1e-9..=200f64.to_radians() + 1e-9).contains(&k));
                assert!((-110f64.to_radians() - 1e-9..=110f64.to_radians() + 1e-9).contains(&mm));
                previous = Some(s.q);
            }
        }
    }
}

#[test]
fn the_smallest_tilt_rule_gives_li_et_al_s_table_2_and_an_unreachable_pose_is_reported() {
    let model = machine(json!({})).build().unwrap();
    // Tool leaning 30° towards +X (II-3 of the cubic test): B = 30°, C = 180°.
    let d = Vector3::new(-0.5, 0.0, 3f64.sqrt() / 2.0);
    let s = model
        .inverse(&Vector3::zeros(), &d, BranchRule::SmallestTilt, None)
        .unwrap();
    let [c, b] = model.rotary_of(&s.q);
    close(b.to_degrees(), 30.0, 1e-9, "B");
    close(c.to_degrees(), 180.0, 1e-9, "C");
    // The same with B limited to [-40°, 20°]: only B = −30°, C = 0° remains.
    let limited = machine(json!({ "rotary": { "mFrom": -40, "mTo": 20 } }))
        .build()
        .unwrap();
    let s = limited
        .inverse(&Vector3::zeros(), &d, BranchRule::SmallestTilt, None)
        .unwrap();
    let [c, b] = limited.rotary_of(&s.q);
    close(b.to_degrees(), -30.0, 1e-9, "B");
    close(c.to_degrees(), 0.0, 1e-9, "C");
    // And with B limited to [0°, 20°] the pose cannot be reached.
    let tight = machine(json!({ "rotary": { "mFrom": 0, "mTo": 20 } }))
        .build()
        .unwrap();
    let e = tight
        .inverse(&Vector3::zeros(), &d, BranchRule::SmallestTilt, None)
        .unwrap_err();
    assert!(
        e.message.contains("C = 180°, B = 30°") && e.message.contains("B from 0° to 20°"),
        "{e}"
    );
}

#[test]
fn fit_writes_an_angle_in_the_travel() {
    let d = f64::to_radians;
    close(
        fit(d(-90.0), d(-360.0), d(360.0), None).unwrap(),
        d(270.0),
        1e-12,
        "[0, 360)",
    );
    close(
        fit(d(-90.0), d(-120.0), d(120.0), None).unwrap(),
        d(-90.0),
        1e-12,
        "nearest 0",
    );
    close(
        fit(d(10.0), d(-720.0), d(720.0), Some(d(700.0))).unwrap(),
        d(730.0) - TAU,
        1e-12,
        "near",
    );
    assert!(fit(d(90.0), d(-30.0), d(30.0), None).is_none());
    assert!(fit(PI, d(-180.0), d(180.0), None).is_some());
}

#[test]
fn every_preset_of_the_page_is_a_machine() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../public/presets/machines.json"
    ))
    .unwrap();
    let all: Value = serde_json::from_str(&text).unwrap();
    let presets = all["presets"].as_array().unwrap();
    assert!(presets.len() >= 6);
    for p in presets {
        let m = machine(p["machine"].clone());
        m.build().unwrap_or_else(|e| panic!("{}: {e}", p["name"]));
    }
}

#[test]
fn swing_length_and_standard_machine() {
    let m = Machine::standard().unwrap();
    assert_eq!(m.kind, MachineKind::TableTable);
    assert_eq!(m.rotary_type.name(), "CBZ");
    close(m.swing_length().unwrap(), 100.0, 0.0, "table height");
    let h = machine(
        json!({ "kind": "head-head", "geometry": { "pivotLength": 250, "toolLength": 80 } }),
    );
    close(h.swing_length().unwrap(), 330.0, 1e-12, "pivot + tool");
    let _ = Pose::new(0.0, 0.0);
}

// Found by cargo-mutants: a mutant in `crate/src/machine/mod.rs` survived every other test.
#[test]
fn without_errors_drops_the_errors_and_error_motions_and_keeps_everything_else() {
    let m = machine(json!({
        "kind": "head-table", "type": "CBZ",
        "geometry": { "tableHeight": 40, "pivotLength": 250, "toolLength": 80 },
        "errors": { "E_X0B": 0.01, "E_A0C": 0.002 },
        "motions": { "E_XX": 0.002 },
    }));
    let bare = machine(json!({
        "kind": "head-table", "type": "CBZ",
        "geometry": { "tableHeight": 40, "pivotLength": 250, "toolLength": 80 },
    }));
    assert_ne!(
        m, bare,
        "the machine with errors differs from the one without"
    );
    assert_eq!(m.without_errors(), bare);
}

// Found by cargo-mutants: a mutant in `crate/src/machine/mod.rs` survived every other test.
/// The machine's axes in chain order with what each does: for a table-table A/C trunnion with
/// X, Y, Z on the spindle, A (M, the tilting axis) on the bed, C (K) on A, then X, Y, Z.
#[test]
fn the_axes_of_a_trunnion_are_a_then_c_on_the_table_and_x_y_z_on_the_spindle() {
    let m = machine(json!({ "kind": "table-table", "type": "CAZ" }));
    let axes = m.axes();
    let got: Vec<(&str, &str, &str, &str)> = axes
        .iter()
        .map(|a| (a.name.as_str(), a.motion, a.side, a.role))
        .collect();
    assert_eq!(
        got,
        [
            ("A", "rotary", "table", "M"),
            ("C", "rotary", "table", "K"),
            ("X", "linear", "spindle", ""),
            ("Y", "linear", "spindle", ""),
            ("Z", "linear", "spindle", ""),
        ]
    );
    let words: Vec<&str> = axes.iter().map(|a| a.description.as_str()).collect();
    assert_eq!(
        words,
        [
            "A (M): table axis on the bed, carries C",
            "C (K): table axis on A, carries the workpiece",
            "X: linear axis, moves the spindle",
            "Y: linear axis, moves the spindle",
            "Z: linear axis, moves the spindle",
        ]
    );
    // The drawing lists the same axes.
    let drawn: Vec<_> = schematic(&m, 0.3, 0.2, 10.0)
        .unwrap()
        .axes
        .into_iter()
        .map(|a| a.axis)
        .collect();
    assert_eq!(drawn, axes);
}

// Found by cargo-mutants: a mutant in `crate/src/machine/mod.rs` survived every other test.
/// One rotary axis on each side (head-table B/C on a cross table: Y on the bed, X on Y, as the
/// layout's help says): each rotary axis is alone
/// on its branch, so it sits on nothing named and carries the branch's end.
#[test]
fn the_axes_of_a_head_table_machine_each_carry_their_branchs_end() {
    let m = machine(json!({ "kind": "head-table", "type": "CBZ", "linear": "table-xy" }));
    let got: Vec<(String, &str, &str, String)> = m
        .axes()
        .into_iter()
        .map(|a| (a.name, a.side, a.role, a.description))
        .collect();
    let want = [
        ("Y", "table", "", "Y: linear axis, moves the table"),
        ("X", "table", "", "X: linear axis, moves the table"),
        (
            "C",
            "table",
            "K",
            "C (K): table axis, carries the workpiece",
        ),
        ("Z", "spindle", "", "Z: linear axis, moves the spindle"),
        ("B", "spindle", "M", "B (M): head axis, carries the spindle"),
    ];
    let want: Vec<(String, &str, &str, String)> = want
        .iter()
        .map(|(n, s, r, d)| (n.to_string(), *s, *r, d.to_string()))
        .collect();
    assert_eq!(got, want);
}

// Found by cargo-mutants: a mutant in `crate/src/machine/mod.rs` survived every other test.
/// Table-table CAZ, X Y Z on the spindle (module docs, "MachineGeometry"): with every axis at
/// zero the spindle nose is at the machine origin, the tool tip `toolLength` from it along −Z
/// and the table surface (the workpiece origin) `tableHeight` above it. So the nominal tip on
/// the workpiece at `X, Y, Z` (spindle moves by +q) is `(X, Y, Z − tableHeight − toolLength)`
/// turned with the table: C turns the table by −C (ISO 841), which turns what is fixed to the
/// machine by +C about Z as the workpiece sees it; the height stays.
#[test]
fn the_tool_tip_of_a_trunnion_lies_the_tool_length_below_the_spindle_nose() {
    let (h, tool) = (40.0, 120.0);
    let m = machine(json!({
        "kind": "table-table", "type": "CAZ",
        "geometry": { "tableHeight": h, "toolLength": tool },
    }));
    let chain = m.nominal_chain();
    close3(
        chain.tool_tip.into(),
        [0.0, 0.0, -tool],
        "tool tip in the spindle frame",
    );
    close3(chain.work_origin.into(), [0.0, 0.0, h], "table surface");
    for (c, [x, y, z]) in [
        (0.0_f64, [0.0, 0.0, 0.0]),
        (0.0, [15.0, -30.0, 200.0]),
        (0.8, [25.0, 10.0, 90.0]),
    ] {
        // Chain order: A, C, X, Y, Z.
        let pose = chain
            .tool_pose(&[0.0, c, x, y, z], false, &Setup::None)
            .unwrap();
        let (s, k) = c.sin_cos();
        close3(
            pose.tip.into(),
            [k * x - s * y, s * x + k * y, z - h - tool],
            "tool tip on the workpiece",
        );
        let built = m
            .build()
            .unwrap()
            .chain
            .tool_pose(&[0.0, c, x, y, z], true, &Setup::None)
            .unwrap();
        close3(
            built.tip.into(),
            pose.tip.into(),
            "the built machine without errors",
        );
    }
}
