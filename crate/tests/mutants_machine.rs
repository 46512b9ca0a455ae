//! Tests for what mutation testing found unchecked in `machine/`: the machine the control knows
//! (`Machine::without_errors`) and the drawing of the machine (`schematic`). Expected values come
//! from the geometry of the machines below, worked by hand: a table-table A/C trunnion (CAZ,
//! spindle along Z, the rotary axes meeting at the origin) and a head-head fork head.

#![allow(clippy::unwrap_used)]
mod common;

use common::close;
use fiveaxis::chain::Setup;
use fiveaxis::machine::schematic::schematic;
use fiveaxis::machine::Machine;
use fiveaxis::schema::Inputs;
use serde_json::{json, Value};

fn machine(v: Value) -> Machine {
    Machine::from_value(&v, "machine").unwrap()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

fn close3(got: [f64; 3], want: [f64; 3], what: &str) {
    for i in 0..3 {
        close(got[i], want[i], 1e-9, &format!("{what}[{i}]"));
    }
}

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

/// Table-table CAZ, X Y Z on the spindle, the table surface `h` above the rotary centre, no
/// offset between the axes. Commanding A tilts the table about X: the table centre `(0, 0, h)`
/// turns to `(0, ∓h·sin A, h·cos A)` and its normal to `(0, ∓sin A, cos A)`; the tool stays
/// along +Z, its tip `standoff` above the table centre, the spindle nose the tool length above.
#[test]
fn the_drawing_of_a_trunnion_table_is_its_closed_form_geometry() {
    let (h, tool, standoff) = (70.0, 120.0, 30.0);
    let m = machine(json!({
        "kind": "table-table", "type": "CAZ",
        "geometry": { "tableHeight": h, "toolLength": tool },
    }));
    for (c, a) in [(0.0_f64, 0.0_f64), (0.7, 0.5), (-2.0, -1.1)] {
        let s = schematic(&m, c, a, standoff).unwrap();
        let centre = s.table_centre;
        close(centre[0], 0.0, 1e-9, "centre x");
        close(centre[1].abs(), h * a.sin().abs(), 1e-9, "centre |y|");
        close(centre[2], h * a.cos(), 1e-9, "centre z");
        let n = s.table_frame[2];
        close3(n, [0.0, centre[1] / h, a.cos()], "table normal");
        // The table's in-plane directions: unit, square to each other and to the normal.
        for (i, u) in s.table_frame.iter().enumerate() {
            close(norm(*u), 1.0, 1e-12, &format!("frame {i} unit"));
        }
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        close(dot(s.table_frame[0], s.table_frame[1]), 0.0, 1e-12, "u·v");
        close(dot(s.table_frame[0], n), 0.0, 1e-12, "u·n");
        // C turns the table's in-plane directions about the normal: at A = 0, u = (cos C,
        // ±sin C, 0) up to the face's own choice of u, so its angle to X is ±C.
        if a == 0.0 {
            close(
                s.table_frame[0][0].abs(),
                c.cos().abs(),
                1e-9,
                "u·X at A = 0",
            );
        }
        close3(s.tool_direction, [0.0, 0.0, 1.0], "tool direction");
        close3(
            s.tool_tip,
            [centre[0], centre[1], centre[2] + standoff],
            "tool tip",
        );
        close3(
            s.spindle_nose,
            [centre[0], centre[1], centre[2] + standoff + tool],
            "spindle nose",
        );
        // Axes in chain order: the table side from the bed (A, then C), then X, Y, Z.
        let names: Vec<&str> = s.axes.iter().map(|x| x.axis.name.as_str()).collect();
        assert_eq!(names, ["A", "C", "X", "Y", "Z"], "axis order");
        close3(
            s.axes[0].direction.map(f64::abs),
            [1.0, 0.0, 0.0],
            "A along X",
        );
        close3(s.axes[1].direction, n, "C along the table normal");
        // C's line passes through the table centre (the axes meet, no offset).
        let off = sub(centre, s.axes[1].origin);
        let along = dot(off, n);
        close(
            norm(sub(off, n.map(|v| v * along))),
            0.0,
            1e-9,
            "C's line through the table centre",
        );
        for (i, want) in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
            .iter()
            .enumerate()
        {
            close3(
                s.axes[2 + i].direction,
                *want,
                &format!("{} direction", names[2 + i]),
            );
        }
        // The scale: the largest distance from the table centre or the tool tip to any drawn
        // point, at least 100 mm. Here the nose is farthest from the centre: standoff + tool.
        close(s.scale, standoff + tool, 1e-9, "scale");
    }
    // A small machine: the drawing keeps its 100 mm minimum.
    let small = machine(json!({
        "kind": "table-table", "type": "CAZ",
        "geometry": { "tableHeight": 10, "toolLength": 20 },
    }));
    close(
        schematic(&small, 0.0, 0.0, 5.0).unwrap().scale,
        100.0,
        0.0,
        "minimum scale",
    );
}

/// Head-head: the workpiece does not move, the table centre is `h` above the origin whatever
/// the pose. The tool tip, the spindle nose and the head's pivot (on the tilting axis) lie on
/// one line from the table centre: the farthest drawn point is the pivot, standoff + tool +
/// pivot length away.
#[test]
fn the_drawing_of_a_fork_head_fits_the_head() {
    let (h, pivot, tool, standoff) = (50.0, 400.0, 150.0, 10.0);
    let m = machine(json!({
        "kind": "head-head", "type": "CAZ",
        "geometry": { "tableHeight": h, "pivotLength": pivot, "toolLength": tool },
    }));
    for (c, a) in [(0.0_f64, 0.0_f64), (0.4, 0.6)] {
        let s = schematic(&m, c, a, standoff).unwrap();
        close3(s.table_centre, [0.0, 0.0, h], "table centre");
        close3(s.table_frame[2], [0.0, 0.0, 1.0], "table normal");
        // The tool tilts by A about X, whatever C.
        close(s.tool_direction[2], a.cos(), 1e-9, "tool direction z");
        close(norm(s.tool_direction), 1.0, 1e-12, "tool direction unit");
        let tip = sub(s.tool_tip, s.table_centre);
        close3(
            tip,
            s.tool_direction.map(|v| v * standoff),
            "tip from the centre",
        );
        let nose = sub(s.spindle_nose, s.tool_tip);
        close3(
            nose,
            s.tool_direction.map(|v| v * tool),
            "nose from the tip",
        );
        close(
            s.scale,
            standoff + tool + pivot,
            1e-9,
            "scale: centre to pivot",
        );
    }
}

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
