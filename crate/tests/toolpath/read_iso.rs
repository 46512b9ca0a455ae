//! The ISO G-code reader (`fiveaxis::toolpath::read::iso`), construct by construct, on programs
//! written from the documentation each construct is defined in: FANUC Series 30i/300i-MODEL A
//! Descriptions (B-63942EN/02: G43.4/G43.5 p.411, G68.2 p.248), FANUC 15i-MB Connection manual
//! (B-63323EN-1/03 p.1053, G43.5's omitted I J K), the Haas NGC Mill Operator's Manual (G234
//! TCPC, G254 DWO, G68 "positive R is counter-clockwise"), and the LinuxCNC G-code reference
//! (`docs/src/gcode/g-code.adoc`: G2/G3 "as viewed from the positive end of the axis", R > 0 up
//! to half a turn, I J K from the start, G28's intermediate point, G52/G92; `o-code.adoc`).
//! Every expected point is computed by hand in the test (the arithmetic is in the comments), or
//! is a property of the construct (on the circle, in the quadrant).

#![allow(clippy::unwrap_used)]
use crate::common;

use common::toolpath::{
    at, caz, caz_head, chords, close_vec, error, note, read_all, read_with, skipped,
};
use fiveaxis::machine::Machine;
use fiveaxis::schema::Inputs;
use fiveaxis::toolpath::read::{Format, LengthUnit, Motion, NoteKind, ReadOptions, UnitChoice};
use nalgebra::Vector3;
use std::f64::consts::{FRAC_PI_2, PI};

const TOL: f64 = 1e-12;

fn machine(v: serde_json::Value) -> Machine {
    Machine::from_value(&v, "machine").unwrap()
}

#[test]
fn g0_g1_and_g3_give_rapid_feed_and_arc_points() {
    let m = caz_head();
    let text = "%\n\
                O1000 (G0 G1 G3)\n\
                N10 G90 G21 G17\n\
                N20 G0 X0 Y0 Z10\n\
                N30 G1 Z0 F500\n\
                N40 X10\n\
                N50 G3 X0 Y10 I-10 J0\n\
                N60 G0 Z50\n\
                N70 M30\n\
                %\n";
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    // A quarter circle of radius 10 within 1 µm: π/2 / (2·acos(1 − 1e-4)) = 55.5 → 56 chords.
    let n = chords(10.0, FRAC_PI_2, 0.001);
    assert_eq!(n, 56);
    assert_eq!(p.len(), 3 + n + 1);
    // The moves between the points: the first point is where the tool starts.
    assert_eq!((r.rapids, r.feeds, r.arc_points), (1, 2, n));
    assert_eq!((p[0].line, p[0].motion), (4, Motion::Rapid));
    assert_eq!(p[0].tip, Vector3::new(0.0, 0.0, 10.0));
    assert_eq!((p[1].motion, p[2].motion), (Motion::Feed, Motion::Feed));
    assert_eq!(p[2].tip, Vector3::new(10.0, 0.0, 0.0));
    // G3: counter-clockwise about +Z from (10, 0) to (0, 10): the first quadrant.
    for q in &p[3..3 + n] {
        assert_eq!((q.line, q.motion), (7, Motion::Arc));
        assert!((q.tip.norm() - 10.0).abs() < 1e-9 && q.tip.x > -1e-9 && q.tip.y > -1e-9);
    }
    close_vec(&p[2 + n].tip, &Vector3::new(0.0, 10.0, 0.0), TOL, "arc end");
    assert_eq!((p[3 + n].line, p[3 + n].motion), (8, Motion::Rapid));
    assert_eq!(r.format, Format::Nc);
    assert_eq!(r.unit, LengthUnit::Mm);
    assert!(r.unit_reason.contains("G21 on line 3"), "{}", r.unit_reason);
}

// Found by cargo-mutants: P never read as turns (its guard false) survived.
/// LinuxCNC: "P … the number of turns" of G2/G3. A full circle with P3 turns three times,
/// descending in a helix: 6π of radius 10 in the chords of 1 µm, Z from 0 to −3 (−1 a turn).
#[test]
fn p_gives_an_arc_s_number_of_turns() {
    let m = caz_head();
    let (p, _) = read_all(
        "G0 X10 Y0 Z0\nG2 X10 Y0 Z-3 I-10 J0 P3\n",
        Format::Nc,
        Some(&m),
    );
    assert_eq!(p.len() - 1, chords(10.0, 6.0 * PI, 0.001));
    assert!(p.iter().all(|q| (q.tip.xy().norm() - 10.0).abs() < 1e-9));
    close_vec(
        &p.last().unwrap().tip,
        &Vector3::new(10.0, 0.0, -3.0),
        1e-9,
        "end",
    );
}

#[test]
fn g2_turns_clockwise_and_r_picks_the_short_or_the_long_arc() {
    let m = caz_head();
    // From (0, 0) to (10, 0) with R10: the chord is 10, h = √(100 − 25) = 8.660. G2 (clockwise),
    // R > 0 (at most half a turn): centre (5, −8.660), the arc from 120° down to 60° about it,
    // over its top: up to y = 10 − 8.660 = 1.340. R < 0: centre (5, 8.660), clockwise from 240°
    // down to −60°, the long way over its top: up to y = 8.660 + 10 = 18.660.
    let h = 75f64.sqrt();
    for (r, cy, extreme) in [(10.0, -h, 10.0 - h), (-10.0, h, h + 10.0)] {
        let text = format!("G0 X0 Y0 Z0\nG2 X10 Y0 R{r}\n");
        let (p, _) = read_all(&text, Format::Nc, Some(&m));
        for q in &p[1..] {
            assert!(((q.tip - Vector3::new(5.0, cy, 0.0)).norm() - 10.0).abs() < 1e-9);
        }
        let ymax = p[1..].iter().map(|q| q.tip.y).fold(f64::MIN, f64::max);
        assert!((ymax - extreme).abs() <= 0.001, "R{r}: {ymax}");
    }
}

#[test]
fn arcs_in_g18_and_g19_turn_as_seen_from_the_positive_normal() {
    let m = caz_head();
    // G18, the ZX plane seen from +Y: Z to the right, X up. G2 (clockwise) from X = 0 to X = 10
    // about (5, 0, 0) starts at the bottom and turns to the left: through Z = −5.
    let (p, _) = read_all("G0 X0 Y0 Z0\nG18 G2 X10 Z0 I5 K0\n", Format::Nc, Some(&m));
    // (The chords' ends lie on the arc; the lowest is within the chord tolerance of −5.)
    let zmin = p.iter().map(|q| q.tip.z).fold(f64::MAX, f64::min);
    assert!((zmin + 5.0).abs() <= 0.001, "{zmin}");
    assert!(p.iter().all(|q| q.tip.y == 0.0));
    // G19, the YZ plane seen from +X: Y to the right, Z up. G3 (counter-clockwise) from Y = 0
    // to Y = 10 about (0, 5, 0) starts at the left and turns down: through Z = −5.
    let (p, _) = read_all("G0 X0 Y0 Z0\nG19 G3 Y10 Z0 J5 K0\n", Format::Nc, Some(&m));
    let zmin = p.iter().map(|q| q.tip.z).fold(f64::MAX, f64::min);
    assert!((zmin + 5.0).abs() <= 0.001, "{zmin}");
}

#[test]
fn a_helix_is_a_full_circle_descending_in_proportion() {
    let m = caz_head();
    // From (10, 0, 0) to (10, 0, −5) about (0, 0): a whole turn (start = end in the plane) and
    // 5 mm down, 2π / 0.028285 = 222.1 → 223 chords; half way round, at (−10, 0), z = −2.5.
    let (p, r) = read_all(
        "G0 X10 Y0 Z0\nG3 X10 Y0 Z-5 I-10 J0\n",
        Format::Nc,
        Some(&m),
    );
    let n = chords(10.0, 2.0 * PI, 0.001);
    assert_eq!(r.arc_points, n);
    for q in &p[1..] {
        let turned = q.tip.y.atan2(q.tip.x).rem_euclid(2.0 * PI);
        let u = if q.tip.z == -5.0 {
            1.0
        } else {
            turned / (2.0 * PI)
        };
        assert!((q.tip.z + 5.0 * u).abs() < 1e-9, "{q:?}");
        assert!((q.tip.xy().norm() - 10.0).abs() < 1e-9);
    }
}

#[test]
fn an_arc_whose_end_is_off_its_circle_is_refused_with_a_hint() {
    let m = caz_head();
    at(
        &error("G0 X0 Y0 Z0\nG3 X10 Y0 I3 J0\n", Format::Nc, Some(&m)),
        2,
        1,
        "the arc's end is not on its circle: 3 mm from the centre at the start, 7 mm",
    );
    // I J K written as absolute coordinates (Heidenhain's ISO programs): from (0, 10) to
    // (10, 0), the centre (1, 1) is √82 from both ends, while (0, 10) + (1, 1) = (1, 11) is √2
    // from the start and √202 from the end. The message says so.
    let msg = error("G0 X0 Y10 Z0\nG3 X10 Y0 I1 J1\n", Format::Nc, Some(&m));
    assert!(msg.contains("read as absolute coordinates"), "{msg}");
    // With G90.1 the centre is absolute: (0, 0), radius 10 at both ends.
    let (p, _) = read_all(
        "G90.1\nG0 X0 Y10 Z0\nG2 X10 Y0 I0 J0\n",
        Format::Nc,
        Some(&m),
    );
    assert!(p[1..].iter().all(|q| (q.tip.norm() - 10.0).abs() < 1e-9));
    // Found by cargo-mutants (the match arms of G17 and G91.1 deleted survived): no test went back.
    // G91.1 after G90.1, and G17 after G18, restore the centre from the start and the XY plane:
    // from (10, 0) about (10, 0) + (−10, 0) = (0, 0), a quarter of radius 10 in XY. (Read as
    // absolute, the centre (−10, 0) is 20 from the start; in ZX, the end is 0 from it.)
    for prefix in ["G90.1\nG91.1\n", "G18\nG17\n"] {
        let text = format!("{prefix}G0 X10 Y0 Z0\nG3 X0 Y10 I-10 J0\n");
        let (p, _) = read_all(&text, Format::Nc, Some(&m));
        assert!(p[1..]
            .iter()
            .all(|q| (q.tip.norm() - 10.0).abs() < 1e-9 && q.tip.z == 0.0));
    }
    at(
        &error("G0 X0 Y0 Z0\nG2 X10 Y0\n", Format::Nc, Some(&m)),
        2,
        1,
        "an arc needs its centre",
    );
}

#[test]
fn g20_is_inches_from_where_it_is_stated_and_an_unstated_file_takes_the_unit_chosen() {
    let m = caz_head();
    let (p, r) = read_all("G20\nG0 X1 Y2 Z3\n", Format::Nc, Some(&m));
    close_vec(&p[0].tip, &Vector3::new(25.4, 50.8, 76.2), 1e-12, "G20");
    assert_eq!(r.unit, LengthUnit::Inch);
    assert_eq!(r.unit_reason, "inches: G20 on line 1");
    let (p, r) = read_all("G0 X1 Y2 Z3\n", Format::Nc, Some(&m));
    assert_eq!(p[0].tip, Vector3::new(1.0, 2.0, 3.0));
    assert!(
        r.unit_reason
            .starts_with("millimetres: the file states no unit"),
        "{}",
        r.unit_reason
    );
    let inch = ReadOptions {
        unit: UnitChoice::Inch,
        ..ReadOptions::default()
    };
    let (p, r) = read_with("G0 X1 Y2 Z3\n", Format::Nc, Some(&m), inch);
    close_vec(
        &p[0].tip,
        &Vector3::new(25.4, 50.8, 76.2),
        1e-12,
        "inch chosen",
    );
    assert_eq!(r.unit, LengthUnit::Inch);
    // A unit the file states wins over the one chosen.
    let (p, _) = read_with("G21\nG0 X1 Y2 Z3\n", Format::Nc, Some(&m), inch);
    assert_eq!(p[0].tip, Vector3::new(1.0, 2.0, 3.0));
}

#[test]
fn tool_centre_point_control_is_reported_where_it_is_switched_on() {
    let m = caz_head();
    for (code, what) in [
        ("G43.4 H1", "G43.4 on line 1"),
        ("G234 H1", "G234 (Haas TCPC) on line 1"),
        ("G254", "G254 (Haas dynamic work offset) on line 1"),
        ("M128", "M128 on line 1"),
    ] {
        let (_, r) = read_all(
            &format!("{code}\nG0 X0 Y0 Z0 C0 A0\nG1 C10 A10\n"),
            Format::Nc,
            Some(&m),
        );
        assert_eq!(r.tcp.as_deref(), Some(what));
        assert!(
            r.notes.iter().all(|n| n.kind != NoteKind::Tcp),
            "{:?}",
            r.notes
        );
    }
    // Without it, rotary axes turning are noted: X Y Z are then the machine's positions.
    let (_, r) = read_all("G0 X0 Y0 Z0 C0 A0\nG1 C10 A10\n", Format::Nc, Some(&m));
    assert_eq!(r.tcp, None);
    assert_eq!(
        note(&r, "turn while tool-centre-point control is off").line,
        2
    );
    // Within 10⁻⁹° of a whole turn, either side, is the zero pose: no note.
    // Found by cargo-mutants: `turned`'s upper bound (`360 − 1e-9` as `360 + 1e-9`) survived.
    for c in ["C-0.0000000001", "C359.9999999999", "C0.0000000001"] {
        let (_, r) = read_all(
            &format!("G0 X0 Y0 Z0 C0 A0\nG1 {c} A0\n"),
            Format::Nc,
            Some(&m),
        );
        assert!(
            r.notes.iter().all(|n| n.kind != NoteKind::Tcp),
            "{c}: {:?}",
            r.notes
        );
    }
    // So is an arc whose chords turn C a whole turn, though it ends where C is at 0°.
    let (_, r) = read_all(
        "G0 X0 Y0 Z0 C0 A0\nG2 X10 Y0 I5 J0 C360\n",
        Format::Nc,
        Some(&m),
    );
    assert_eq!(
        note(&r, "turn while tool-centre-point control is off").line,
        2
    );
    // Turned where X Y Z are not known, the note waits for a point: none when tool-centre-point
    // control is switched on first (`G0 B-22.201 C1.05` then `G234`, as NX's Haas post writes
    // it), nor when the point is in a tilted plane; else it names the first turn's line.
    for (text, line) in [
        ("G28 X0 Y0 Z0\nG0 C10\nG0 A5\nG43.4 H1\nG0 X0 Y0 Z0\n", None),
        (
            "G28 X0 Y0 Z0\nG0 C10 A5\nG68.2 X0 Y0 Z0 I0 J5 K0\nG53.1\nG0 X0 Y0 Z0\n",
            None,
        ),
        ("G28 X0 Y0 Z0\nG0 C10\nG0 A5\nG0 X0 Y0 Z0\n", Some(2)),
    ] {
        let (p, r) = read_all(text, Format::Nc, Some(&m));
        assert_eq!(p.len(), 1, "{text:?}");
        let noted = r.notes.iter().find(|n| n.kind == NoteKind::Tcp);
        assert_eq!(noted.map(|n| n.line), line, "{text:?}: {:?}", r.notes);
    }
}

/// An arc in inches is cut within the chord tolerance in millimetres, and its two radii may
/// differ by the rounding allowed in millimetres (0.01 mm, more than 10⁻⁴ of a 1 in radius),
/// not by as much in inches: a quarter circle of 1 in = 25.4 mm within 1 µm takes
/// π/2 / (2·acos(1 − 0.001/25.4)) = 88.5 → 89 chords; an end 0.0003 in = 0.00762 mm off the
/// circle is rounding, 0.001 in = 0.0254 mm is not.
// Found by cargo-mutants: `Log::arc_tolerances`'s conversions to the file's unit (`/ mm` as
// `* mm` or `% mm`) survived: every arc tested was in millimetres.
#[test]
fn an_arc_in_inches_is_cut_and_checked_in_millimetres() {
    let m = caz_head();
    let n = chords(25.4, FRAC_PI_2, 0.001);
    assert_eq!(n, 89);
    let (p, r) = read_all("G20\nG0 X1 Y0 Z0\nG3 X0 Y1 I-1 J0\n", Format::Nc, Some(&m));
    assert_eq!(r.arc_points, n);
    for q in &p[1..] {
        assert!((q.tip.norm() - 25.4).abs() < 1e-9, "{:?}", q.tip);
    }
    close_vec(&p[n].tip, &Vector3::new(0.0, 25.4, 0.0), 1e-12, "end");
    let (p, _) = read_all(
        "G20\nG0 X1 Y0 Z0\nG3 X0 Y1.0003 I-1 J0\n",
        Format::Nc,
        Some(&m),
    );
    close_vec(
        &p[p.len() - 1].tip,
        &Vector3::new(0.0, 25.40762, 0.0),
        1e-9,
        "end",
    );
    at(
        &error(
            "G20\nG0 X1 Y0 Z0\nG3 X0 Y1.001 I-1 J0\n",
            Format::Nc,
            Some(&m),
        ),
        3,
        1,
        "the arc's end is not on its circle: 25.4 mm from the centre at the start, 25.4254 mm",
    );
}

/// Tool-centre-point control switched off (`G49`, `G43`, `G255`, `M129`) while the rotary axes
/// are turned: the control no longer keeps the tip on the part, so X Y Z of the blocks after it
/// are the machine's axis positions (FANUC 30i B-63942EN/02 p.411: G49 cancels G43.4). The
/// first point reached so is noted at the statement's line, with the angles it left the axes
/// at; not when the axes are back at 0° (the machine's frame is then the workpiece's, a whole
/// turn included) or the control is switched on again before the point, nor in a tilted plane.
#[test]
fn tool_centre_point_control_switched_off_with_the_axes_turned_is_noted() {
    let m = caz_head();
    let tcp_notes = |text: &str| {
        let (_, r) = read_all(text, Format::Nc, Some(&m));
        r.notes
            .into_iter()
            .filter(|n| n.kind == NoteKind::Tcp)
            .map(|n| (n.line, n.text))
            .collect::<Vec<_>>()
    };
    for off in ["G49", "G43 H2", "G255", "M129"] {
        let text = format!("G43.4 H1\nG0 X0 Y0 Z0 C30 A-20\n{off}\nG1 X10\n");
        let notes = tcp_notes(&text);
        assert_eq!(notes.len(), 1, "{text:?}: {notes:?}");
        let (line, said) = &notes[0];
        assert_eq!(*line, 3, "{said}");
        let code = off.split(' ').next().unwrap();
        assert!(
            said.starts_with(&format!(
                "line 3: {code} switches tool-centre-point control off"
            )) && said.contains("(C 30°, A -20°)")
                && said.contains("line 4 moves")
                && said.contains("machine's axis positions"),
            "{said}"
        );
    }
    for text in [
        // Back at 0° (or a whole turn) before the next point: the frames agree.
        "G43.4 H1\nG0 X0 Y0 Z0 C30 A-20\nG49\nG0 C0 A0\nG1 X10\n",
        "G43.4 H1\nG0 X0 Y0 Z0 C30 A-20\nG49\nG0 C360 A0\nG1 X10\n",
        // Switched on again first.
        "G43.4 H1\nG0 X0 Y0 Z0 C30 A-20\nG49\nG43.4 H2\nG1 X10\n",
        // Switched off at 0°, then a point.
        "G43.4 H1\nG0 X0 Y0 Z0 C0 A0\nG49\nG1 X10\n",
        // No point after it.
        "G43.4 H1\nG0 X0 Y0 Z0 C30 A-20\nG49\nM30\n",
        // In a tilted working plane the tilt sets the axes, turned by the rotary words or not.
        "G68.2 X0 Y0 Z0 I0 J30 K0\nG53.1\nG43.4 H1\nG0 X0 Y0 Z0\nG49\nG1 X10\n",
        "G68.2 X0 Y0 Z0 I0 J30 K0\nG53.1\nG43.4 H1\nG0 X0 Y0 Z0 C30 A-20\nG49\nG1 X10\n",
    ] {
        let notes = tcp_notes(text);
        assert!(
            notes.iter().all(|n| !n.1.contains("control off")),
            "{text:?}: {notes:?}"
        );
    }
    let only = |text: &str| {
        let notes = tcp_notes(text);
        let off: Vec<_> = notes
            .iter()
            .filter(|n| n.1.contains("control off"))
            .collect();
        assert_eq!(off.len(), 1, "{text:?}: {notes:?}");
        off[0].clone()
    };
    // Switched off in the tilted plane with the axes turned, the points after the plane's
    // cancel (G69) are the machine's: the note waits for the first of them.
    let (line, said) = only(
        "G68.2 X0 Y0 Z0 I0 J30 K0\nG53.1\nG43.4 H1\nG0 X0 Y0 Z0 C30 A-20\nG49\nG1 X10\nG69\n\
         G1 X20\n",
    );
    assert!(line == 5 && said.contains("line 8 moves"), "{line} {said}");
    // M129 acts at the end of its block (iTNC 530 DIN/ISO p.290): its block's move is still
    // under the control, the next one is not.
    let (line, said) = only("G43.4 H1\nG0 X0 Y0 Z0 C30 A-20\nG1 X5 M129\nG1 X10\n");
    assert!(line == 3 && said.contains("line 4 moves"), "{line} {said}");
    // LinuxCNC's M428 switches its tool-centre-point kinematics on, M429 off (a survivor of
    // toolpath/read/iso: M429's arm deleted).
    let (line, said) = only("M428\nG0 X0 Y0 Z0 C30 A-20\nM429\nG1 X10\n");
    assert!(line == 3 && said.contains("line 4 moves"), "{line} {said}");
    // An arc's chords carry the angles between its ends: one that turns from 30° to 0° after
    // the control is off is noted though it ends at 0°.
    let (line, said) = only("G43.4 H1\nG0 X0 Y0 Z0 C30 A0\nG49\nG2 X10 Y0 I5 J0 C0\n");
    assert!(line == 3 && said.contains("line 4 moves"), "{line} {said}");
    // Turned without the control and back at 0° before any point: the point is right, no note.
    assert_eq!(
        tcp_notes("G28 X0 Y0 Z0\nG0 C10 A5\nG0 C0 A0\nG0 X0 Y0 Z0\n"),
        []
    );
}

/// The program's first block may be its name, as NX's Haas posts write it where the control
/// reads an O number (`Omnf01_vx_0`, `OFinal ToolPath`), with or without a `%` before it; a
/// later block of O and a letter is no name and is refused.
#[test]
fn the_first_block_may_be_the_program_s_name() {
    let m = caz_head();
    for text in [
        "%\nOmnf01_vx_0\nG0 X1 Y2 Z3\nM30\n%\n",
        "%\n(PART: FINAL)\nOFinal ToolPath\nG0 X1 Y2 Z3\nM30\n%\n",
        "Omnf01_vx_0\nG0 X1 Y2 Z3\nM30\n%\n",
    ] {
        let (p, r) = read_all(text, Format::Nc, Some(&m));
        assert_eq!(p.len(), 1, "{text:?}");
        assert_eq!(p[0].tip, Vector3::new(1.0, 2.0, 3.0));
        assert_eq!(skipped(&r, "program numbers and names"), 1, "{text:?}");
    }
    at(
        &error("%\nO1000\nG0 X1 Y2 Z3\nOmnf\n", Format::Nc, Some(&m)),
        4,
        1,
        "\"Omnf\" is not ISO G-code",
    );
}

#[test]
fn g43_5_gives_the_tool_axis_by_i_j_k_and_keeps_or_zeroes_the_omitted() {
    let m = caz_head();
    // FANUC 15i-MB p.1053: all of I J K omitted keeps the vector; some omitted are 0.
    let text = "G43.5 H1\nG1 X0 Y0 Z0 I0 J0 K1\nX1 I1 J0 K1\nX2\nX3 I1\nG49\nX4\n";
    let (p, _) = read_all(text, Format::Nc, Some(&m));
    let s = 0.5f64.sqrt();
    for (q, axis) in p.iter().zip([
        Vector3::new(0.0, 0.0, 1.0),
        Vector3::new(s, 0.0, s),
        Vector3::new(s, 0.0, s),
        Vector3::new(1.0, 0.0, 0.0),
    ]) {
        close_vec(&q.axis, &axis, TOL, "G43.5 vector");
        assert_eq!(q.angles, None);
    }
    // After G49 the rotary axes (never commanded: 0°) give the axis again.
    close_vec(&p[4].axis, &Vector3::z(), TOL, "after G49");
    assert_eq!(p[4].angles, Some([0.0, 0.0]));
}

#[test]
fn g28_breaks_the_path_until_the_axes_are_given_and_returns_the_rotary_axes_to_zero() {
    let m = caz_head();
    let text = "G0 X0 Y0 Z10 C90 A30\nG91 G28 Z0\nG90 X5\nZ20\nG28 C0 A0\nX6\n";
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    // Line 3 leaves Z unknown: no point; line 4 gives it, reached across the break: a rapid.
    assert_eq!(p.iter().map(|q| q.line).collect::<Vec<_>>(), [1, 4, 6]);
    assert_eq!(p[1].tip, Vector3::new(5.0, 0.0, 20.0));
    assert_eq!(p[1].angles, Some([90.0, 30.0]));
    assert_eq!(note(&r, "reference position").line, 2);
    assert_eq!(note(&r, "reference position").kind, NoteKind::Break);
    // G28 C0 A0: the rotary axes go to their reference position, 0°.
    assert_eq!(p[2].angles, Some([0.0, 0.0]));
    // G91 G28: the distance mode of the block applies to it, and stays.
    let (p, _) = read_all(
        "G0 X1 Y1 Z1\nG28 G91 Z0\nX1\nG90 Z5\n",
        Format::Nc,
        Some(&m),
    );
    assert_eq!(p[1].tip, Vector3::new(2.0, 1.0, 5.0));
}

#[test]
fn g53_moves_in_machine_coordinates_and_breaks_the_path() {
    let m = caz_head();
    let (p, r) = read_all("G0 X0 Y0 Z10\nG53 Z0\nG0 X5 Z5\n", Format::Nc, Some(&m));
    assert_eq!(p.len(), 2);
    assert_eq!(
        (p[1].tip, p[1].motion),
        (Vector3::new(5.0, 0.0, 5.0), Motion::Rapid)
    );
    assert_eq!(note(&r, "machine coordinates").line, 2);
}

#[test]
fn g52_and_g92_shift_the_program_origin() {
    let m = caz_head();
    // G52 X100 Y50: the local origin is at (100, 50); X10 Y10 is (110, 60). G52 X0 Y0 cancels.
    let (p, r) = read_all(
        "G0 X0 Y0 Z0\nG52 X100 Y50\nG1 X10 Y10\nG52 X0 Y0\nX1\n",
        Format::Nc,
        Some(&m),
    );
    assert_eq!(p[1].tip, Vector3::new(110.0, 60.0, 0.0));
    assert_eq!(p[2].tip, Vector3::new(1.0, 10.0, 0.0));
    assert_eq!(note(&r, "G52").kind, NoteKind::Frame);
    // G92 X0 Y0 at (10, 20): the current point is now (0, 0), so X1 Y1 is (11, 21).
    let (p, _) = read_all("G0 X10 Y20 Z5\nG92 X0 Y0\nG1 X1 Y1\n", Format::Nc, Some(&m));
    assert_eq!(p[1].tip, Vector3::new(11.0, 21.0, 5.0));
    // G92.1 and G92.2 cancel it (a survivor: their arm deleted): X1 Y1 is (1, 1) again.
    for cancel in ["G92.1", "G92.2"] {
        let text = format!("G0 X10 Y20 Z5\nG92 X0 Y0\n{cancel}\nG1 X1 Y1\n");
        let (p, _) = read_all(&text, Format::Nc, Some(&m));
        assert_eq!(p[1].tip, Vector3::new(1.0, 1.0, 5.0), "{cancel}");
    }
    // Where the position is not known, G92 cannot be applied.
    at(
        &error("X1\nG92 X0 Y0\n", Format::Nc, Some(&m)),
        2,
        8,
        "does not say where the tool is in Y",
    );
    at(
        &error("G0 X0 Y0 Z0\nG92 C0\n", Format::Nc, Some(&m)),
        2,
        5,
        "G92 on a rotary axis",
    );
}

#[test]
fn g68_turns_the_program_counter_clockwise_about_its_centre() {
    let m = caz_head();
    // Haas: G17 G68 X Y R, positive R counter-clockwise. R90 about (0, 0): (10, 0) → (0, 10).
    let (p, r) = read_all(
        "G0 X0 Y0 Z0\nG68 X0 Y0 R90\nG1 X10 Y0\nG69\nX20\n",
        Format::Nc,
        Some(&m),
    );
    close_vec(&p[1].tip, &Vector3::new(0.0, 10.0, 0.0), TOL, "R90");
    close_vec(&p[2].tip, &Vector3::new(20.0, 0.0, 0.0), TOL, "after G69");
    assert_eq!(note(&r, "G68 turns").line, 2);
    // About (10, 10): (20, 10) is 10 along +X from the centre, turned to (10, 20).
    let (p, _) = read_all(
        "G0 X0 Y0 Z0\nG68 X10 Y10 R90\nG1 X20 Y10\n",
        Format::Nc,
        Some(&m),
    );
    close_vec(
        &p[1].tip,
        &Vector3::new(10.0, 20.0, 0.0),
        TOL,
        "about (10, 10)",
    );
    at(
        &error("G0 X0 Y0 Z0\nG68 X0 Y0\n", Format::Nc, Some(&m)),
        2,
        1,
        "G68 without R",
    );
}

// Found by cargo-mutants: the unit's scale in G52, G92 and G68.2 (`*` and `/` swapped), G92's
// `pos − value` made `+`, G52's note only for a zero shift, and G68 I J K's `centre − R·centre`
// made `+` survived: every test of them was in millimetres, set values of 0, or turned about
// the origin.
/// The frames of G52, G92, G68 and G68.2 in inches are placed in inches: X1 is 25.4 mm (the
/// notes give the file's numbers). G92 X5 at X10: the position is now 5, the origin 5 along
/// +X. G68 about the axis I J K through (10, 0, 0): that centre stays where it is.
#[test]
fn frames_set_in_inches_and_off_the_origin_are_placed_right() {
    let m = caz_head();
    let inch = |x: f64| x * 25.4;
    // G52 X1: X1 is 2 in from the origin; the note gives the shift (1, 0, 0).
    let (p, r) = read_all(
        "G20\nG0 X0 Y0 Z0\nG52 X1 Y0 Z0\nG1 X1\nG52 X0\n",
        Format::Nc,
        Some(&m),
    );
    close_vec(&p[1].tip, &Vector3::new(inch(2.0), 0.0, 0.0), 1e-9, "G52");
    assert!(note(&r, "G52").text.contains("(1, 0, 0)"), "{:?}", r.notes);
    // G92 X5 at X10 (inches): X5 is the tool's place, so X6 is 11 in, and the origin moved 5.
    let (p, r) = read_all("G20\nG0 X10 Y0 Z0\nG92 X5\nG1 X6\n", Format::Nc, Some(&m));
    close_vec(&p[1].tip, &Vector3::new(inch(11.0), 0.0, 0.0), 1e-9, "G92");
    assert!(note(&r, "G92").text.contains("(5, 0, 0)"), "{:?}", r.notes);
    // G68 about +Z through (10, 0, 0) by 90°: (10, 0) stays, (20, 0) goes to (10, 10).
    let (p, _) = read_all(
        "G0 X0 Y0 Z0\nG68 X10 Y0 Z0 I0 J0 K1 R90\nG1 X10 Y0\nX20\n",
        Format::Nc,
        Some(&m),
    );
    close_vec(
        &p[1].tip,
        &Vector3::new(10.0, 0.0, 0.0),
        1e-12,
        "the centre",
    );
    close_vec(&p[2].tip, &Vector3::new(10.0, 10.0, 0.0), 1e-12, "turned");
    // G68.2 X1 (inches) with no turn: the plane's origin is 1 in along +X.
    let (p, _) = read_all(
        "G20\nG68.2 X1 Y0 Z0 I0 J0 K0\nG0 X0 Y0 Z0\n",
        Format::Nc,
        Some(&m),
    );
    close_vec(&p[0].tip, &Vector3::new(inch(1.0), 0.0, 0.0), 1e-9, "G68.2");
}

#[test]
fn g68_2_tilts_the_plane_by_euler_angles_z_x_z() {
    let m = caz_head();
    // I0 J90 K0: R = R_X(90°), which takes z to (0, −1, 0): the tip (0, 0, 10) of the plane is
    // (100, −10, 0) with the origin X100, and the tool axis is (0, −1, 0).
    let text = "G0 X0 Y0 Z50\nG68.2 X100 Y0 Z0 I0 J90 K0\nG53.1\nG1 X0 Y0 Z10\n";
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    close_vec(
        &p[1].tip,
        &Vector3::new(100.0, -10.0, 0.0),
        1e-12,
        "G68.2 tip",
    );
    close_vec(
        &p[1].axis,
        &Vector3::new(0.0, -1.0, 0.0),
        1e-15,
        "G68.2 axis",
    );
    assert_eq!(p[1].angles, None);
    assert_eq!(note(&r, "G68.2 tilts").kind, NoteKind::Frame);
    // I90 J45 K0: R_Z(90°)·R_X(45°) takes z to R_Z(90°)·(0, −sin 45°, cos 45°) = (sin 45°, 0,
    // cos 45°); X first about Z then X would give (0, −sin 45°, cos 45°) instead.
    let (p, _) = read_all(
        "G68.2 X0 Y0 Z0 I90 J45 K0\nG1 X0 Y0 Z0\n",
        Format::Nc,
        Some(&m),
    );
    let s = 0.5f64.sqrt();
    close_vec(&p[0].axis, &Vector3::new(s, 0.0, s), 1e-15, "Z X′ Z″");
    at(
        &error("G68.2 P1 X0 Y0 Z0 I0 J0 K0\n", Format::Nc, Some(&m)),
        1,
        1,
        "G68.2 P1",
    );
}

#[test]
fn text_before_the_first_percent_and_after_the_second_is_not_read() {
    let m = caz_head();
    let text = "\u{feff}PROGRAM LISTING: part 12/3\nDate 2026-11-26\n%\nO1000 (TEST)\nN10 G0 X0 Y0 Z0\n%\nthis is not a block\n";
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    assert_eq!(p.len(), 1);
    assert_eq!(p[0].line, 5);
    assert_eq!(skipped(&r, "before the first %"), 2);
    assert_eq!(skipped(&r, "after the end"), 1);
    assert_eq!(skipped(&r, "program numbers"), 1);
    // Settings alone before a `%` (no point yet): that `%` starts the program after all (a
    // survivor: a block without a point counted as one).
    let (p, _) = read_all("G21 G90\n%\nG0 X1 Y2 Z3\n%\n", Format::Nc, Some(&m));
    assert_eq!(p.len(), 1);
    // Blocks before a closing % (no leader): read.
    let (p, _) = read_all("G0 X0 Y0 Z0\nG1 X1\n%\n", Format::Nc, Some(&m));
    assert_eq!(p.len(), 2);
    // A post's placeholder program name and nested comments.
    let (p, _) = read_all(
        "%\nO ENTER OP AND LAST 3 DIGITS\n(#508= (MILL_.25))\nG0 X0 Y0 Z0\n",
        Format::Nc,
        Some(&m),
    );
    assert_eq!(p.len(), 1);
}

// Found by cargo-mutants: `Iso::line`'s test of the lines before the first `%` (the program
// name's `&&`, and "only settings before it") survived: no test had a one-line listing header,
// nor blocks after a closing `%` that ends a program without a leader.
/// The lines before the first `%` are a listing header unless every one is a block (the first
/// may be the program's name, `OName`): a header of one line that is no block is skipped, not
/// read as a block; blocks ended by a `%` that moved the tool are the whole program, and what
/// follows that `%` is not read.
#[test]
fn a_header_line_is_skipped_and_blocks_closed_by_a_percent_end_the_program() {
    let m = caz_head();
    // "PART 7 ROUGHING" is no block (P, A, R letters with no numbers) and not a name (no O).
    let (p, r) = read_all(
        "PART 7 ROUGHING
%
G0 X1 Y2 Z3
",
        Format::Nc,
        Some(&m),
    );
    assert_eq!(p.len(), 1);
    assert_eq!(p[0].tip, Vector3::new(1.0, 2.0, 3.0));
    assert_eq!(skipped(&r, "before the first %"), 1);
    // The first line a name (NX's Haas posts): the lines are the program, the `%` its end.
    let (p, r) = read_all(
        "OFinal ToolPath
G0 X1 Y2 Z3
%
",
        Format::Nc,
        Some(&m),
    );
    assert_eq!(p.len(), 1);
    assert_eq!(skipped(&r, "before the first %"), 0);
    // Blocks that moved the tool, then `%`: the program ends there; the block after is text.
    let (p, r) = read_all("G0 X0 Y0 Z0\nG1 X1\n%\nG1 X5\n", Format::Nc, Some(&m));
    assert_eq!(p.iter().map(|q| q.tip.x).collect::<Vec<_>>(), [0.0, 1.0]);
    assert_eq!(skipped(&r, "after the end of the program"), 1);
}

// Found by cargo-mutants: G41/G42's arm deleted survived (no test wrote cutter compensation).
/// G41 and G42 offset the path by the tool radius, which the file does not state (Fanuc, Haas,
/// LinuxCNC "cutter radius compensation"): the points are read as programmed and the report says
/// so, on the line where it is switched on, as a partial reading (not as an unknown code).
#[test]
fn cutter_compensation_is_noted_and_the_points_are_as_programmed() {
    let m = caz_head();
    for g in ["G41", "G42"] {
        let text = format!("G0 X0 Y0 Z0\n{g} D1 G1 X10\nG40 X20\n");
        let (p, r) = read_all(&text, Format::Nc, Some(&m));
        assert_eq!(
            p.iter().map(|q| q.tip.x).collect::<Vec<_>>(),
            [0.0, 10.0, 20.0]
        );
        let n = note(&r, "cutter compensation");
        assert_eq!((n.line, n.kind), (2, NoteKind::Partial), "{g}");
        assert!(n.text.contains(g), "{}", n.text);
        assert!(r
            .notes
            .iter()
            .all(|n| !n.text.contains("not a code the reader knows")));
    }
}

#[test]
fn drilling_cycles_give_their_positions_as_rapids() {
    let m = caz_head();
    let text = "G0 X0 Y0 Z10\nG81 X5 Y5 Z-3 R2 F100\nX10\nG80\nG0 X0\n";
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    // Z and R of the cycle are its depth and plane: the tool's Z stays 10.
    let tips: Vec<_> = p.iter().map(|q| (q.tip, q.motion)).collect();
    assert_eq!(
        tips,
        [
            (Vector3::new(0.0, 0.0, 10.0), Motion::Rapid),
            (Vector3::new(5.0, 5.0, 10.0), Motion::Rapid),
            (Vector3::new(10.0, 5.0, 10.0), Motion::Rapid),
            (Vector3::new(0.0, 5.0, 10.0), Motion::Rapid),
        ]
    );
    assert_eq!(note(&r, "drilling cycle G81").kind, NoteKind::Partial);
    // Found by cargo-mutants (G80's arm deleted survived: the test's G0 after G80 also ends the
    // cycle). G80 alone ends it: the next block's Z is the tool's again, in the motion mode of
    // before the cycle (G0), and G80 is a known code.
    let text = "G0 X0 Y0 Z10\nG81 X5 Y5 Z-3 R2 F100\nG80\nX10 Z-1\n";
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    let last = p.last().unwrap();
    assert_eq!(
        (last.tip, last.motion),
        (Vector3::new(10.0, 5.0, -1.0), Motion::Rapid)
    );
    assert!(r
        .notes
        .iter()
        .all(|n| !n.text.contains("not a code the reader knows")));
}

#[test]
fn words_that_change_no_geometry_are_skipped_and_counted() {
    let m = caz_head();
    let text = "N10 T1 M6\nN20 S5000 M3\nN30 G0 X0 Y0 Z0 M8\nN40 G1 X1 F1000\nN50 G4 P500\nN60 G187 P3\nN70 M30\n";
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    assert_eq!(p.len(), 2);
    assert_eq!(skipped(&r, "block numbers"), 7);
    assert_eq!(skipped(&r, "feeds"), 1);
    assert_eq!(skipped(&r, "spindle speeds"), 1);
    assert_eq!(skipped(&r, "tool numbers"), 1);
    assert_eq!(skipped(&r, "tool changes"), 1);
    assert_eq!(skipped(&r, "coolant"), 1);
    assert_eq!(skipped(&r, "dwells"), 1);
    assert_eq!(skipped(&r, "look-ahead"), 1);
    assert_eq!(skipped(&r, "program ends"), 1);
    // A G-code the reader does not know is listed as such, with a note.
    let (_, r) = read_all("G0 X0 Y0 Z0\nG300\n", Format::Nc, Some(&m));
    assert_eq!(skipped(&r, "does not know"), 1);
    assert_eq!(note(&r, "G300").line, 2);
    // Found by cargo-mutants (their arms deleted survived): M5, M0, M1, G53.6 and M129 are known
    // codes, counted under their own kinds, not as other M-functions or unknown G-codes.
    let (_, r) = read_all(
        "G0 X0 Y0 Z0\nM5\nM0\nM1\nG53.6\nM129\n",
        Format::Nc,
        Some(&m),
    );
    assert_eq!(skipped(&r, "spindle (M3, M4, M5)"), 1);
    assert_eq!(skipped(&r, "program stops"), 2);
    assert_eq!(skipped(&r, "tool axis direction control"), 1);
    assert_eq!(skipped(&r, "other M-functions"), 0);
    assert_eq!(skipped(&r, "does not know"), 0);
    // In ISO (not DIN/ISO), M99 ends the program (Fanuc: the end of a subprogram, or the main
    // program's loop back, read as its end); only a HEIDENHAIN DIN/ISO program calls a cycle.
    let (p, r) = read_all("G0 X0 Y0 Z0\nM99\nG0 X5\n", Format::Nc, Some(&m));
    assert_eq!(p.len(), 1);
    assert_eq!(skipped(&r, "program ends"), 1);
    assert!(r.notes.iter().all(|n| !n.text.contains("calls the cycle")));
}

// Found by cargo-mutants: the block's position (`Block::at`, its first word) deleted survived:
// every refused arc started in column 1.
/// A refused arc names its block's first word: after two spaces of indent, column 3.
// Found by cargo-mutants: three `&&` of `Iso::block_words` made `||` survived (G43.5's I J K
// in an arc, the DIN/ISO modal centre in ISO and in a block without axes).
/// The centre of an arc is the arc's own: after G43.5 (whose I J K are the tool axis in a
/// line) an arc's I J K are still its centre; in ISO an arc without I J K or R has none (the
/// last centre stays only in DIN/ISO); in DIN/ISO a block with neither axes nor R (a feed alone)
/// makes no full circle about the last centre.
#[test]
fn an_arc_s_centre_is_its_own_in_iso_and_modal_only_where_it_moves_in_din_iso() {
    let m = caz_head();
    let (p, _) = read_all(
        "G43.5 H1\nG0 X10 Y0 Z0 I0 J0 K1\nG3 X0 Y10 I-10 J0\n",
        Format::Nc,
        Some(&m),
    );
    assert_eq!(p.len(), 1 + chords(10.0, FRAC_PI_2, 0.001));
    assert!(p.iter().all(|q| (q.tip.norm() - 10.0).abs() < 1e-9));
    // ISO: the second arc names no centre (from (0, 10), (−10, 10) would fit, r = 10).
    at(
        &error(
            "G0 X10 Y0 Z0\nG3 X0 Y10 I-10 J0\nG3 X-10 Y0\n",
            Format::Nc,
            Some(&m),
        ),
        3,
        1,
        "an arc needs its centre",
    );
    // DIN/ISO: the quarter about (0, 0), then a feed alone: no move.
    let text = "%T G71 *\nN10 G00 X10 Y0 Z0 *\nN20 G03 X0 Y10 I0 J0 *\nN30 F200 *\n";
    let (p, _) = read_all(text, Format::Nc, Some(&m));
    assert_eq!(p.len(), 1 + chords(10.0, FRAC_PI_2, 0.001));
    assert_eq!(p.last().unwrap().line, 3);
}

#[test]
fn a_refused_arc_points_at_its_block_s_first_word() {
    let m = caz_head();
    // From (0, 0) about (5, 0), r = 5, to (20, 0), 15 from the centre: not on the circle.
    let e = error("  G0 X0 Y0 Z0\n  G3 X20 Y0 I5 J0\n", Format::Nc, Some(&m));
    at(&e, 2, 3, "not on its circle");
}

#[test]
fn macros_subprograms_and_o_words_are_refused_with_their_construct() {
    let m = caz_head();
    for (text, line, column, part) in [
        ("#1=5\n", 1, 1, "macro variable"),
        ("G0 X0 Y0 Z#1\n", 1, 11, "macro variable"),
        ("G0 X[1+2]\n", 1, 5, "expression"),
        ("IF [#1 GT 0] GOTO 10\n", 1, 1, "IF is a macro statement"),
        ("o100 sub\n", 1, 1, "o-words (LinuxCNC"),
        ("O<probe> call\n", 1, 1, "o-words (LinuxCNC"),
        ("o101 if [#1 GT 0]\n", 1, 1, "o-words"),
        ("M98 P1000\n", 1, 1, "M98 calls a subprogram"),
        ("G65 P9000 A1\n", 1, 1, "G65/G66 call a macro"),
        ("G16\n", 1, 1, "polar coordinates"),
        ("G51 X0 Y0 P2\n", 1, 1, "scales or mirrors"),
        // FANUC 30i: G68.3 and G68.4 take the plane from the tool axis the machine holds.
        (
            "G68.3 X0 Y0 Z0\n",
            1,
            1,
            "G68.3/G68.4 define the working plane",
        ),
        (
            "G68.4 X0 Y0 Z0\n",
            1,
            1,
            "G68.3/G68.4 define the working plane",
        ),
        ("G10 L2 P1 X0\n", 1, 1, "G10 L2/L20"),
        ("G0 U5\n", 1, 4, "U is an axis the calculator does not read"),
        (
            "G0 X0 Y0 Z0 B10\n",
            1,
            13,
            "expected a rotary axis of this machine (C or A), got B",
        ),
        ("TRAORI\n", 1, 1, "is not ISO G-code"),
        // Found by cargo-mutants: a `[` not after a letter, and a `:` after the first word.
        ("G0 X1 [X+1]\n", 1, 7, "expression"),
        ("G0 X1 :5\n", 1, 7, "expected a word"),
    ] {
        at(&error(text, Format::Nc, Some(&m)), line, column, part);
    }
    // `:1000` opens a block as a program number (ISO 6983's `:`), and a comment left open runs
    // to the line's end.
    let (p, r) = read_all(":1000\nG0 X1 Y0 Z0 (open\n", Format::Nc, Some(&m));
    assert_eq!(p.len(), 1);
    assert_eq!(p[0].tip, Vector3::new(1.0, 0.0, 0.0));
    assert_eq!(r.blocks, 1);
}

#[test]
fn rollover_reads_k_the_shorter_way_and_a_long_turn_while_cutting_is_noted() {
    let text = "G0 X0 Y0 Z0 C180 A10\nC350\nG1 C10\n";
    // Read as written, C turns back 340° while cutting: the note says so.
    let (p, r) = read_all(text, Format::Nc, Some(&caz_head()));
    let c = |p: &[fiveaxis::toolpath::read::Point]| {
        p.iter().map(|q| q.angles.unwrap()[0]).collect::<Vec<_>>()
    };
    assert_eq!(c(&p), [180.0, 350.0, 10.0]);
    let n = note(&r, "turns C from 350° to 10°");
    assert_eq!((n.line, n.kind), (3, NoteKind::Rotary));
    // With rollover the control goes the shorter way: 180° → 350° (170°), 350° → 370° (20°),
    // no note.
    let m = machine(
        serde_json::json!({ "kind": "head-head", "type": "CAZ", "rotary": { "kRollover": true } }),
    );
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    assert_eq!(c(&p), [180.0, 350.0, 370.0]);
    close_vec(&p[2].axis, &caz(10.0, 10.0), 1e-15, "same axis");
    assert!(r.notes.iter().all(|n| n.kind != NoteKind::Rotary));
}

#[test]
fn a_work_offset_changed_later_breaks_the_path() {
    let m = caz_head();
    let (p, r) = read_all(
        "G54\nG0 X0 Y0 Z0\nG1 X1\nG55\nG1 X2\n",
        Format::Nc,
        Some(&m),
    );
    assert_eq!(p[2].motion, Motion::Rapid);
    assert_eq!(note(&r, "another work offset").line, 4);
}

/// G0 is modal (group 01) whatever non-modal code shares its block (LinuxCNC g-code.adoc, G53:
/// "G0 or G1 must be active"; FANUC group 00 codes are one-shot): after `G53 G0 Z0` or
/// `G0 G28 G91 Z0` the blocks without a G code are rapids, as Fusion's Haas and Fanuc posts
/// write them.
#[test]
fn g0_stays_in_force_after_a_block_with_g28_g53_or_g52() {
    let m = caz_head();
    for retract in [
        "G53 G0 Z0",
        "G0 G28 G91 Z0",
        "G28 G0 G91 Z0",
        "G0 G52 X0 Y0",
    ] {
        let text = format!(
            "G90 G21 G17 G54\nG1 X0 Y0 Z10 F500\nG1 Z0\nX10\n{retract}\nG90 X50 Y50\nZ5\nZ1\n"
        );
        let (p, _) = read_all(&text, Format::Nc, Some(&m));
        let last = p.last().unwrap();
        assert_eq!(last.tip.z, 1.0, "{retract}");
        assert_eq!(last.motion, Motion::Rapid, "{retract}: Z1 after it");
    }
}

/// Haas G154 P1…P99 are work offsets (Haas NGC manual: "G154 Select Work Coordinates P1-P99"),
/// like G54: another one breaks the path. G50.1 cancels mirroring (FANUC: G50.1 X0 Y0): a safe
/// start line with it is read, its X0 Y0 name axes and move nothing.
#[test]
fn g154_p_is_a_work_offset_and_g50_1_cancels() {
    let m = caz_head();
    let text = "G90 G21 G17 G40 G49 G80 G50.1 X0 Y0\nG54\nG0 X0 Y0 Z10\nG1 Z0 F500\nG154 P1\nG0 X0 Y0 Z10\nG1 Z0\n";
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    assert_eq!(p[0].line, 3, "G50.1's X0 Y0 is not a position");
    assert_eq!(
        note(&r, "G154 selects another work offset").kind,
        NoteKind::Break
    );
    assert_eq!(skipped(&r, "G50, G50.1"), 1);
    // The P word names the offset of G54.1 and G154 (a survivor: P read for neither): P2 after
    // P1 is another offset, P1 again the same.
    for g in ["G54.1", "G154"] {
        for (then, breaks) in [("P2", true), ("P1", false)] {
            let text = format!("{g} P1\nG0 X0 Y0 Z10\n{g} {then}\nG0 X1\n");
            let (_, r) = read_all(&text, Format::Nc, Some(&m));
            let said = r
                .notes
                .iter()
                .any(|n| n.text.contains("another work offset"));
            assert_eq!(said, breaks, "{text:?}");
        }
    }
    // G51.1 mirrors: still refused.
    at(&error("G51.1 X0\n", Format::Nc, Some(&m)), 1, 1, "mirrors");
}

/// A shift and a tilted plane defined in one unit stay where they are after the unit changes:
/// G52 X10 in mm, then G20: after G69 (which rebuilds the frame) X0 is still 10 mm from the
/// workpiece origin.
#[test]
fn a_shift_stays_where_it_is_when_the_unit_changes() {
    let m = caz_head();
    let text = "G21 G90\nG52 X10 Y0 Z0\nG20\nG69\nG0 X0 Y0 Z0\nX1\n";
    let (p, _) = read_all(text, Format::Nc, Some(&m));
    close_vec(
        &p[0].tip,
        &Vector3::new(10.0, 0.0, 0.0),
        1e-9,
        "G52 X10 mm in inches",
    );
    close_vec(&p[1].tip, &Vector3::new(35.4, 0.0, 0.0), 1e-9, "then X1 in");
}

/// G99 (FANUC: return to the R point level) ends a drilling cycle on its R plane, so the next
/// move starts there; G98 returns to the level it started from.
#[test]
fn a_g99_cycle_ends_on_its_r_plane() {
    let m = caz_head();
    let g99 = "G90 G21\nG0 X0 Y0 Z50\nG99 G81 X10 Y0 Z-5 R2 F100\nX20\nG80\nG0 Z50\n";
    let (p, _) = read_all(g99, Format::Nc, Some(&m));
    let zs: Vec<f64> = p.iter().map(|q| q.tip.z).collect();
    // (0,0,50); the hole at (10,0): reached at 50, up on R = 2; the next hole from R.
    assert_eq!(zs, [50.0, 50.0, 2.0, 2.0, 2.0, 50.0]);
    let g98 = g99.replace("G99", "G98");
    let (p, _) = read_all(&g98, Format::Nc, Some(&m));
    assert!(p.iter().all(|q| q.tip.z == 50.0));
    // The way up to R is a rapid even in feed mode (a survivor: the retract's rapid deleted).
    let (p, _) = read_all(
        "G90 G21\nG1 X0 Y0 Z50 F500\nG99 G81 X10 Y0 Z-5 R2 F100\n",
        Format::Nc,
        Some(&m),
    );
    let moves: Vec<_> = p.iter().map(|q| (q.tip.z, q.motion)).collect();
    assert_eq!(
        moves,
        [
            (50.0, Motion::Feed),
            (50.0, Motion::Rapid),
            (2.0, Motion::Rapid)
        ]
    );
}

/// In a tilted plane (G68.2) with G43.4 on, a block that turns the rotary axes gives the tool
/// axis from them (the control follows the commands), not the plane's z; a note says so.
#[test]
fn rotary_words_under_tcp_in_a_tilted_plane_give_the_tool_axis() {
    let m = caz_head();
    let text =
        "G21 G90\nG68.2 X0 Y0 Z0 I0 J30 K0\nG43.4 H1\nG0 X0 Y0 Z10 A30 C0\nG1 X10 A45 C0 F500\n";
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    // G68.2 I0 J30 K0: Rz(0)·Rx(30°)·Rz(0): z' = (0, −sin 30°, cos 30°).
    let plane_z = Vector3::new(0.0, -0.5, 3f64.sqrt() / 2.0);
    // The first block turns A and C too: from it on the commands give the axis.
    close_vec(&p[0].axis, &caz(0.0, 30.0), 1e-12, "A30 C0");
    close_vec(&p[1].axis, &caz(0.0, 45.0), 1e-12, "A45 C0");
    assert!((p[1].axis - plane_z).norm() > 0.1);
    assert_eq!(note(&r, "give the tool axis from here").line, 4);
}

/// A HEIDENHAIN DIN/ISO program (TNC 640 DIN/ISO User's Manual: a program opens with
/// `%NAME G71 *`, G71 millimetres, G70 inches; an arc's centre I J is given in absolute
/// coordinates and stays in force, like CC; cycles are defined by G200… with Q parameters and
/// called by M99; `N99999999 %NAME G71 *` ends it), as NX's post for a Mikron WF21D writes it.
#[test]
fn a_heidenhain_din_iso_program_reads_absolute_modal_centres_and_its_cycles() {
    let m = caz_head();
    let text = "% 123 G71\n\
                N0010 ; Start of Program\n\
                N0020 G90 G17 T1 S0\n\
                N0030 G0 X47.5 Y-10. Z100. M13\n\
                N0040 G3 X41.755 Y-13. Z100. I47.5 J-17.\n\
                N0050 G1 X57. Y-17. F250.\n\
                N0060 G2 X38. Y-17.\n\
                N0070 G0 X15. Y15. Z103.\n\
                N0080 G200 DRILLING\n\
                Q200=3.\n\
                Q201=-12.5\n\
                N0090 X15. Y85. M99\n\
                N9999 % 123 G71 *\n";
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    assert_eq!(r.unit, LengthUnit::Mm);
    // G3 about (47.5, −17) (absolute): from (47.5, −10), r = 7, to (41.755, −13), counter-clockwise.
    let arc1: Vec<_> = p.iter().filter(|q| q.line == 5).collect();
    assert!(!arc1.is_empty());
    for q in &arc1 {
        let r = (q.tip.xy() - nalgebra::Vector2::new(47.5, -17.0)).norm();
        assert!((r - 7.0).abs() < 1e-3, "{r}");
    }
    // G2 with no I J: the same centre, from (57, −17) to (38, −17), r = 9.5: half a turn
    // clockwise (from +x towards −y), through y = −17 − 9.5 = −26.5.
    let arc2: Vec<_> = p.iter().filter(|q| q.line == 7).collect();
    let low = arc2.iter().map(|q| q.tip.y).fold(f64::MAX, f64::min);
    assert!(
        (low + 26.5).abs() < 1e-3,
        "clockwise under the centre: {low}"
    );
    // The cycle's parameters change nothing; M99 moves there and calls it; the end is read.
    assert_eq!(
        p.last().map(|q| (q.tip.x, q.tip.y, q.line)),
        Some((15.0, 85.0, 12))
    );
    assert_eq!(skipped(&r, "cycle definitions and their Q parameters"), 3);
    assert_eq!(note(&r, "M99 calls the cycle").line, 12);
    assert_eq!(note(&r, "HEIDENHAIN DIN/ISO").line, 1);
    // A cycle's number alone (`G200`, no name after it) is a cycle definition too (found by
    // cargo-mutants: the length's `>` made `>=` survived, and `body[1..4]` sliced a character
    // in two: `G20é` panicked).
    let (_, r) = read_all(
        "%T G71 *\nN10 G200 *\nN20 G00 X0 Y0 Z0 *\n",
        Format::Nc,
        Some(&m),
    );
    assert_eq!(skipped(&r, "cycle definitions"), 1);
    assert_eq!(skipped(&r, "does not know"), 0);
    let e = error("%T G71 *\nN10 G20\u{e9} *\n", Format::Nc, Some(&m));
    at(&e, 2, 8, "expected a word");
    // M91 (iTNC 530 DIN/ISO: coordinates of the machine's datum) moves its axes off the part's
    // frame: the path breaks there (a survivor: M91's arm deleted).
    let text = "%T G71 *\nN10 G00 X0 Y0 Z0 *\nN20 G00 Z100 M91 *\nN30 G01 X5 Z0 *\n";
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    let n = note(&r, "M91 moves Z in machine coordinates");
    assert_eq!((n.line, n.kind), (3, NoteKind::Break));
    assert_eq!(p.iter().map(|q| q.line).collect::<Vec<_>>(), [2, 4]);
}

// Found by cargo-mutants: `Iso::heidenhain_header`'s G70 (its guards, the unit's reason) and the
// count of blocks in DIN/ISO and of a name survived: every DIN/ISO test program was in G71, and no
// test counted their blocks.
/// `%NAME G70 *` opens a DIN/ISO program in inches (TNC 640 DIN/ISO manual): X1 is 25.4 mm, and
/// the reason names G70. A cycle's definition, its Q parameters and the program's name (`OName`)
/// are blocks (the report's count of statements with something in them), the `%` lines are not;
/// a comment that holds `=` does not make its block a Q parameter.
#[test]
fn a_din_iso_program_in_inches_and_the_count_of_its_blocks() {
    let m = caz_head();
    let text = "%T G70 *\n\
                N10 G200 DRILLING *\n\
                N20 Q200=2 *\n\
                N30 G00 X1 Y2 Z0 (DEPTH=5) *\n";
    let (p, r) = read_all(text, Format::Nc, Some(&m));
    assert_eq!(r.unit, LengthUnit::Inch);
    assert!(r.unit_reason.contains("G70"), "{}", r.unit_reason);
    assert_eq!(p.len(), 1);
    close_vec(&p[0].tip, &Vector3::new(25.4, 50.8, 0.0), 1e-12, "inches");
    assert_eq!(r.blocks, 3);
    // In millimetres, the reason names G71.
    let (_, r) = read_all("%T G71 *\nN10 G00 X1 Y2 Z0 *\n", Format::Nc, Some(&m));
    assert_eq!(r.unit, LengthUnit::Mm);
    assert!(r.unit_reason.contains("G71"), "{}", r.unit_reason);
    // A `%` with a name and no unit opens no DIN/ISO program: its I J are from the start (ISO).
    let (p, r) = read_all(
        "%T\nG0 X10 Y0 Z0\nG3 X-10 Y0 I-10 J0\n",
        Format::Nc,
        Some(&m),
    );
    assert!(r.notes.iter().all(|n| !n.text.contains("DIN/ISO")));
    assert!(p.iter().all(|q| (q.tip.norm() - 10.0).abs() < 1e-9));
    let (_, r) = read_all("%\nOName\nG0 X0 Y0 Z0\n", Format::Nc, Some(&m));
    assert_eq!(r.blocks, 2);
}

// Found by cargo-mutants: `Nc::line`'s end of the program (the dialect test's `!` deleted, and
// the blank-line test's) survived: no test wrote blocks after M30.
/// After `M30` (end of program) nothing is read: a block after it gives no point, and each line
/// of text after it is counted as skipped, blank lines not; whether the lines come after a `%`
/// (read as they come) or without one (held until the file's end, then read), and in Siemens.
#[test]
fn nothing_after_the_program_s_end_is_read() {
    let m = caz_head();
    for (text, format) in [
        ("%\nG0 X1 Y2 Z3\nM30\nG0 X5 Y5 Z5\n\nG1 X6\n", Format::Nc),
        ("G0 X1 Y2 Z3\nM30\nG0 X5 Y5 Z5\n\nG1 X6\n", Format::Nc),
        (
            "N10 G0 X1 Y2 Z3\nN20 M30\nN30 G0 X5 Y5 Z5\n\nN40 G1 X6\n",
            Format::Siemens,
        ),
    ] {
        let (p, r) = read_all(text, format, Some(&m));
        assert_eq!(p.len(), 1, "{text:?}");
        assert_eq!(p[0].tip, Vector3::new(1.0, 2.0, 3.0));
        assert_eq!(
            skipped(&r, "text after the end of the program"),
            2,
            "{text:?}"
        );
    }
}
