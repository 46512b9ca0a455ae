//! Tests for what mutation testing found unchecked in `machine/`: the machine the control knows
//! (`Machine::without_errors`), the drawing of the machine (`schematic`), its axes, the tool tip
//! of the nominal chain, the choice of the orientation solution and `fit`'s writing of angles in
//! the travel, and the reading of error motions (CSV units and headers, polynomials, paper
//! symbols). Expected values come from the geometry of the machines below, worked by hand (a
//! table-table A/C trunnion: CAZ, spindle along Z, the rotary axes meeting at the origin; a
//! head-head fork head), from the definitions of the units, and from the documented rules.

#![allow(clippy::unwrap_used)]
mod common;

use common::close;
use fiveaxis::chain::Setup;
use fiveaxis::machine::motions::{self, read_table_csv};
use fiveaxis::machine::schematic::schematic;
use fiveaxis::machine::{fit, BranchRule, Machine};
use fiveaxis::schema::Inputs;
use nalgebra::Vector3;
use serde_json::{json, Value};
use std::f64::consts::{PI, TAU};

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

/// The units a CSV header may give (the doc of `read_table_csv`: lengths mm, µm, nm, m, in;
/// angles deg, rad, mrad, µrad, arcsec, µm/m, with the usual other spellings), each converted
/// to the API unit by its definition: 1 µm = 1e-3 mm, 1 nm = 1e-6 mm, 1 m = 1000 mm, 1 in =
/// 25.4 mm; 1 rad = 180/π °, 1 mrad = 0.18/π °, 1 µrad (and 1 µm/m, a slope) = 1.8e-4/π °,
/// 1″ = 1/3600 °.
#[test]
fn csv_headers_give_every_documented_unit_its_factor() {
    let lengths: [(&str, f64); 11] = [
        ("mm", 1.0),
        ("MM", 1.0),
        ("µm", 1e-3),
        ("\u{3bc}m", 1e-3),
        ("um", 1e-3),
        ("micron", 1e-3),
        ("microns", 1e-3),
        ("nm", 1e-6),
        ("m", 1e3),
        ("in", 25.4),
        ("inch", 25.4),
    ];
    for (unit, f) in lengths {
        // The value: 0.002 of the unit; the positions 0 and 2 of the unit.
        let t = read_table_csv(
            &format!("X ({unit}), E_XX ({unit})\n0, 0\n2, 0.002\n"),
            "E_XX",
        )
        .unwrap_or_else(|e| panic!("{unit}: {e}"));
        close(
            t.position[1],
            2.0 * f,
            1e-12 * f,
            &format!("position in {unit}"),
        );
        close(
            t.value[1],
            0.002 * f,
            1e-12 * f,
            &format!("value in {unit}"),
        );
        assert_eq!(t.units, [unit.to_string(), unit.to_string()]);
    }
    let angles: [(&str, f64); 15] = [
        ("deg", 1.0),
        ("°", 1.0),
        ("degree", 1.0),
        ("degrees", 1.0),
        ("rad", 180.0 / PI),
        ("mrad", 1e-3 * 180.0 / PI),
        ("µrad", 1e-6 * 180.0 / PI),
        ("urad", 1e-6 * 180.0 / PI),
        ("arcsec", 1.0 / 3600.0),
        ("″", 1.0 / 3600.0),
        ("\"", 1.0 / 3600.0),
        ("sec", 1.0 / 3600.0),
        ("as", 1.0 / 3600.0),
        ("µm/m", 1e-6 * 180.0 / PI),
        ("um/m", 1e-6 * 180.0 / PI),
    ];
    for (unit, f) in angles {
        // E_CC: positions of C (an angle) and values (an angle); E_BX: a length position.
        let t = read_table_csv(
            &format!("C [{unit}]; E_CC [{unit}]\n0; 0\n3; 0,03\n"),
            "E_CC",
        )
        .unwrap_or_else(|e| panic!("{unit}: {e}"));
        close(t.position[1], 3.0 * f, 1e-12 * f, &format!("C in {unit}"));
        close(t.value[1], 0.03 * f, 1e-12 * f, &format!("E_CC in {unit}"));
        let t = read_table_csv(&format!("X (mm), E_BX ({unit})\n0, 0\n1, 0.01\n"), "E_BX")
            .unwrap_or_else(|e| panic!("{unit}: {e}"));
        close(t.value[1], 0.01 * f, 1e-12 * f, &format!("E_BX in {unit}"));
        // An angle is not a length, nor the other way round.
        let e = read_table_csv(&format!("X (mm), E_XX ({unit})\n0, 0\n1, 1\n"), "E_XX");
        assert!(e.is_err(), "{unit} taken for a length");
    }
    for (unit, _) in lengths {
        let e = read_table_csv(&format!("X (mm), E_BX ({unit})\n0, 0\n1, 1\n"), "E_BX");
        assert!(e.is_err(), "{unit} taken for an angle");
    }
}

/// The header (doc of `read_table_csv` and `header_unit`): the unit is the text in `( )` or
/// `[ ]`; a `)` before the last `(` is no pair, so the `[ ]` count. A header word that is
/// neither another error motion's name (four letters such as `E_YX`) nor another axis letter is
/// the program's own and accepted, whatever its length.
#[test]
fn csv_headers_take_the_unit_from_a_pair_and_accept_their_own_words() {
    let t = read_table_csv("X [mm] )(, E_XX [µm]\n0, 0\n10, 4\n", "E_XX").unwrap();
    assert_eq!(t.units, ["mm".to_string(), "µm".to_string()]);
    close(t.value[1], 0.004, 1e-15, "4 µm");
    for header in ["dist (mm), devn (µm)", "p (mm), e (µm)", "mm, µm"] {
        let t = read_table_csv(&format!("{header}\n0, 0\n10, 4\n"), "E_XX")
            .unwrap_or_else(|e| panic!("{header}: {e}"));
        close(t.value[1], 0.004, 1e-15, header);
    }
}

/// A CSV value is accepted up to the error motion's limit (`ErrorDef::limit`, in the API unit)
/// inclusive and refused beyond it, with the line named.
#[test]
fn csv_values_are_accepted_up_to_the_limit_and_refused_beyond() {
    let limit = motions::find("E_XX").unwrap().limit;
    let at = format!("X (mm), E_XX (mm)\n0, {limit}\n1, -{limit}\n");
    let t = read_table_csv(&at, "E_XX").unwrap();
    assert_eq!(t.value, vec![limit, -limit]);
    let over = format!("X (mm), E_XX (mm)\n0, 0\n1, {}\n", limit * 1.001);
    let e = read_table_csv(&over, "E_XX").unwrap_err();
    assert!(e.message.starts_with("line 3"), "{e}");
}

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

/// Error motions as entered (module docs of `machine::motions`, "Values"): a constant of either
/// sign within the error's limit, a polynomial of one coefficient (a constant) up to eight
/// (degree 7, the most the reader takes), each kept in mm for a linear axis.
#[test]
fn error_motions_take_negative_constants_and_polynomials_of_one_to_eight_coefficients() {
    let read = |v: Value| Machine::from_value(&json!({ "motions": { "E_YX": v } }), "machine");
    let m = read(json!(-0.003)).unwrap();
    assert_eq!(
        m.motions.0["E_YX"].at(100.0, "E_YX", false).unwrap(),
        -0.003
    );
    let m = read(json!({ "poly": [-0.002] })).unwrap();
    assert_eq!(
        m.motions.0["E_YX"].at(250.0, "E_YX", false).unwrap(),
        -0.002
    );
    // 0.001·(1 + p + p² + … + p⁷) at p = 1 mm: 0.008 mm.
    let m = read(json!({ "poly": vec![0.001; 8] })).unwrap();
    close(
        m.motions.0["E_YX"].at(1.0, "E_YX", false).unwrap(),
        0.008,
        1e-15,
        "degree 7",
    );
    let e = read(json!({ "poly": vec![0.001; 9] })).unwrap_err();
    assert_eq!(e.field, "machine.motions.E_YX.poly", "{e}");
    let e = read(json!({ "poly": [] })).unwrap_err();
    assert_eq!(e.field, "machine.motions.E_YX.poly", "{e}");
}

/// A Tan & Lim symbol entered as an error motion is refused with the ISO name it stands for and
/// the sign (`ISO = sign · symbol`): their X moves the table, so X's straightness along Y and its
/// rotations change sign (δy(X) = −E_YX, Ez(X) = −E_CX), its positioning does not (δx(X) =
/// E_XX); their rotary-table rotations keep the sign convention of the loop, γ_C = −E_CC (the
/// doc of `motions::MOTIONS`). Either spelling, the symbol or its ASCII form, is recognised.
#[test]
fn a_papers_motion_symbol_is_refused_with_its_own_iso_name_and_sign() {
    for (entered, want) in [
        ("dy(X)", "E_YX = −δy(X)"),
        ("δy(X)", "E_YX = −δy(X)"),
        ("dx(X)", "E_XX = δx(X)"),
        ("Ez(X)", "E_CX = −Ez(X)"),
        ("gammaC", "E_CC = −γ_C"),
        ("γ_C", "E_CC = −γ_C"),
    ] {
        let e =
            Machine::from_value(&json!({ "motions": { entered: 0.001 } }), "machine").unwrap_err();
        assert!(e.message.contains(want), "{entered}: {e}");
    }
}

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

/// Error motions set by ISO name are kept under that name (the X axis then lists its
/// positioning error E_XX with its value); an unknown name is refused and nothing is set.
#[test]
fn error_motions_are_set_by_iso_name_and_unknown_names_refused() {
    use fiveaxis::machine::motions::{ErrorFunction, ErrorMotions};
    let mut m = ErrorMotions::default();
    assert!(m.of_axis('X').is_none(), "nothing set yet");
    m.set("E_XX", ErrorFunction::Constant(0.002)).unwrap();
    let list = m.of_axis('X').unwrap();
    assert_eq!(list.len(), 1);
    assert_eq!(list[0].1, "E_XX");
    assert_eq!(list[0].2, ErrorFunction::Constant(0.002));
    assert!(m.set("E_QX", ErrorFunction::Constant(0.001)).is_err());
    assert!(m.of_axis('Y').is_none(), "the refused name set nothing");
}
