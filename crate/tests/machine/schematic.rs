//! The drawing of the machine (`schematic`) against closed-form geometry worked by hand: a
//! table-table A/C trunnion (CAZ, spindle along Z, the rotary axes meeting at the origin) and a
//! head-head fork head.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::{close, close3, machine, norm, sub};
use fiveaxis::machine::schematic::schematic;
use serde_json::json;

// Found by cargo-mutants: a mutant in `crate/src/machine/schematic.rs` survived every other test.
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

// Found by cargo-mutants: a mutant in `crate/src/machine/schematic.rs` survived every other test.
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
