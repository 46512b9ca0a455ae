//! The NC readers' shared core (`fiveaxis::toolpath::read::nc`: the moves, the modal state and
//! the notes every dialect gives), through the dialects that reach each rule. Written for the
//! mutants of `nc.rs` that no dialect's tests killed; each expected value is counted by hand in
//! the comments.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::toolpath::{
    caz, caz_head, close_vec, heidenhain_program as heidenhain, note, read_all,
};
use fiveaxis::toolpath::read::{Format, NoteKind, Point, Report};
use nalgebra::Vector3;

const ISO: Format = Format::Nc;

fn read(text: &str, format: Format) -> (Vec<Point>, Report) {
    read_all(text, format, Some(&caz_head()))
}

/// The points of `line`, more than two, each `radius` from `centre` (to 10⁻⁹ mm).
fn on_circle(p: &[Point], line: u32, centre: Vector3<f64>, radius: f64) -> Vec<&Point> {
    let arc: Vec<_> = p.iter().filter(|q| q.line == line).collect();
    assert!(arc.len() > 2, "{} points on line {line}", arc.len());
    for q in &arc {
        let r = (q.tip - centre).norm();
        assert!(
            (r - radius).abs() < 1e-9,
            "line {line}: {:?} is {r} from the centre",
            q.tip
        );
    }
    arc
}

/// The notes of `kind`: (line, text).
fn notes(r: &Report, kind: NoteKind) -> Vec<(u32, String)> {
    r.notes
        .iter()
        .filter(|n| n.kind == kind)
        .map(|n| (n.line, n.text.clone()))
        .collect()
}

// Found by cargo-mutants: `set_tcp`'s `self.tcp && turned(…)` as `||` survived.
/// Switching the control off when it was never on changes nothing: the turn without it stays
/// what is noted, at the turn's line, not at the `G49`'s.
#[test]
fn switching_off_a_control_that_is_off_keeps_the_turn_s_note() {
    let (_, r) = read("G0 X0 Y0 Z0 C0 A0\nG1 C30 A-20\nG49\nG1 X10\n", ISO);
    let tcp = notes(&r, NoteKind::Tcp);
    assert_eq!(tcp.len(), 1, "{tcp:?}");
    assert_eq!(tcp[0].0, 2);
    assert!(tcp[0]
        .1
        .contains("turn while tool-centre-point control is off"));
}

// Found by cargo-mutants: the full circle's test (`&&` as `||` twice, `!b.moves()` as
// `b.moves()`) survived.
/// In arc mode a block that moves no axis is no arc (a feed alone, `F200`), unless it gives the
/// centre alone: then it is a full circle back to its start (FANUC 30i: the end point omitted,
/// a 360° arc). From (10, 0) about I−10 J0, the centre (0, 0): every chord point 10 mm from it,
/// the last back at (10, 0).
#[test]
fn in_arc_mode_a_block_of_the_centre_alone_is_a_full_circle_and_a_feed_alone_no_move() {
    let (p, _) = read("G0 X0 Y0 Z0\nG2 X10 Y0 I5 J0 F100\nF200\nG1 X20\n", ISO);
    assert!(p.iter().all(|q| q.line != 3));
    assert_eq!(p.last().unwrap().tip, Vector3::new(20.0, 0.0, 0.0));
    let (p, _) = read("G0 X10 Y0 Z0\nG2 I-10 J0 F100\n", ISO);
    let circle: Vec<_> = p.iter().filter(|q| q.line == 2).collect();
    assert!(circle.len() > 8, "{}", circle.len());
    for q in &circle {
        assert!((q.tip.norm() - 10.0).abs() < 1e-9, "{:?}", q.tip);
    }
    close_vec(
        &circle.last().unwrap().tip,
        &Vector3::new(10.0, 0.0, 0.0),
        1e-9,
        "end",
    );
    // Clockwise (G2) from (10, 0): the first chords go below the x axis.
    assert!(circle[0].tip.y < 0.0, "{:?}", circle[0].tip);
}

// Found by cargo-mutants: `rotary_moves` with `new[4] == start[4]` survived.
/// An arc that turns no rotary axis, with the axes at 0° and no tool-centre-point control, is
/// in the workpiece's frame: no note.
#[test]
fn an_arc_without_rotary_words_at_zero_degrees_is_not_noted() {
    let (_, r) = read("G0 X0 Y0 Z0 C0 A0\nG2 X10 Y0 I5 J0 F100\n", ISO);
    assert_eq!(notes(&r, NoteKind::Tcp), []);
}

// Found by cargo-mutants: the tool vector cleared only when both rotary words are given (`||`
// as `&&`) survived.
/// A rotary word after a tool vector gives the tool axis again, one word as well as two: after
/// `A3=0 B3=0.6 C3=0.8`, `C30` alone (A still 0°) turns the axis back to z.
#[test]
fn one_rotary_word_after_a_tool_vector_gives_the_axis() {
    let (p, _) = read(
        "TRAORI\nG1 X0 Y0 Z0 A0 C0 F100\nA3=0 B3=0.6 C3=0.8\nC30\n",
        Format::Siemens,
    );
    close_vec(&p[1].axis, &Vector3::new(0.0, 0.6, 0.8), 1e-15, "vector");
    close_vec(&p[2].axis, &caz(30.0, 0.0), 1e-15, "C30");
}

// Found by cargo-mutants: `orients` (`||` as `&&`, either) survived.
/// In a tilted plane under tool-centre-point control, one rotary word (C alone) gives the tool
/// axis from there, as both do.
#[test]
fn one_rotary_word_under_tcp_in_a_tilted_plane_gives_the_axis() {
    let (p, r) = read(
        "G68.2 X0 Y0 Z0 I0 J30 K0\nG43.4 H1\nG0 X0 Y0 Z10\nG1 X10 C90 F500\n",
        ISO,
    );
    assert_eq!(note(&r, "give the tool axis from here").line, 4);
    // A is 0°: the axis is z whatever C is.
    close_vec(&p[1].axis, &Vector3::z(), 1e-12, "C90 A0");
}

// Found by cargo-mutants: the k-jump's rules (a one-shot rapid and a cycle's position counted
// as cutting; |new − start| as |new + start|; more than half a turn as half a turn or more)
// survived.
/// A cutting block that turns K by more than half a turn is noted: C100 to C−100 is −200°; half
/// a turn exactly (C0 to C180) is either way round the same, not noted; nor a rapid, whether
/// modal (G0), one-shot (Heidenhain FMAX) or a canned cycle's position.
#[test]
fn a_cutting_turn_of_more_than_half_a_turn_is_noted() {
    let jumps = |text: &str, format| notes(&read(text, format).1, NoteKind::Rotary);
    let j = jumps("G0 X0 Y0 Z0 C100 A0\nG1 C-100 F500\n", ISO);
    assert_eq!(j.len(), 1, "{j:?}");
    assert!(j[0].1.contains("from 100° to -100° (-200°)"), "{}", j[0].1);
    assert_eq!(jumps("G0 X0 Y0 Z0 C0 A0\nG1 C180 F500\n", ISO), []);
    assert_eq!(jumps("G0 X0 Y0 Z0 C0 A0\nG0 C270\n", ISO), []);
    let fmax = heidenhain(&[
        "L X+0 Y+0 Z+0 C+0 A+0 R0 F500",
        "L C+270 R0 FMAX",
        "L X+10 F500",
    ]);
    assert_eq!(jumps(&fmax, Format::Heidenhain), []);
    let cycle = "G0 X0 Y0 Z10 C0 A0\nG1 Z5 F500\nG81 X0 Y0 Z-5 R2 F100\nX10 C270\nG80\n";
    assert_eq!(jumps(cycle, ISO), []);
}

// Found by cargo-mutants: the tangent kept after a move of zero length (`> 0` as `>= 0`, and
// `p1 − p0` as `p1 + p0` in the test) survived.
/// A move that goes nowhere has no direction: a `CT` after it is tangent to the move before.
/// After (0, 0) → (10, 0) and (10, 0) again, CT to (20, 10) is the quarter circle about
/// (10, 10) of radius 10 (ρ = |E − S|²/(2·n·(E − S)) = 200/20).
#[test]
fn a_move_of_zero_length_keeps_the_tangent() {
    let (p, _) = read(
        &heidenhain(&["L X+0 Y+0 Z+0 R0 F100", "L X+10", "L X+10", "CT X+20 Y+10"]),
        Format::Heidenhain,
    );
    on_circle(&p, 5, Vector3::new(10.0, 10.0, 0.0), 10.0);
}

// Found by cargo-mutants: the tangent of a line as `p1 + p0` survived (every CT test's line
// started at the origin).
/// CT after a line that does not start at the origin: from (0, 10) → (10, 10), along +X, CT to
/// (20, 20) is the quarter circle about (10, 20) of radius 10.
#[test]
fn ct_after_a_line_away_from_the_origin() {
    let (p, _) = read(
        &heidenhain(&["L X+0 Y+10 Z+0 R0 F100", "L X+10", "CT X+20 Y+20"]),
        Format::Heidenhain,
    );
    on_circle(&p, 4, Vector3::new(10.0, 20.0, 0.0), 10.0);
}

// Found by cargo-mutants: an arc's end tangent (its sign for a clockwise arc, the radial from
// the centre) survived.
/// CT after an arc continues along the arc's direction at its end: after a quarter circle
/// about (0, 0) of radius 10, clockwise or counter-clockwise, a CT to the next quarter's end
/// follows the same circle; so about a centre away from the origin, (20, 30).
#[test]
fn ct_after_an_arc_continues_its_direction() {
    // On the circle, and the quarter from the start to the end (the points on the side of the
    // chord away from the centre), not the three quarters the other way round.
    let quarter = |text: &str, line: u32, centre: Vector3<f64>, radius: f64| {
        let (p, _) = read(text, Format::Heidenhain);
        let arc = on_circle(&p, line, centre, radius);
        let (start, end) = (p[p.len() - arc.len() - 1].tip, arc.last().unwrap().tip);
        let middle = (start + end) / 2.0 - centre;
        for q in arc {
            assert!((q.tip - centre).dot(&middle) > 0.0, "{text}: {:?}", q.tip);
        }
    };
    // Clockwise about (0, 0) from (0, 10) to (10, 0): at the end heading −Y; CT to (0, −10):
    // the same circle.
    quarter(
        &heidenhain(&[
            "CC X+0 Y+0",
            "L X+0 Y+10 Z+0 R0 F100",
            "C X+10 Y+0 DR-",
            "CT X+0 Y-10",
        ]),
        5,
        Vector3::zeros(),
        10.0,
    );
    // Counter-clockwise about (0, 0) from (10, 0) to (0, 10): heading −X; CT to (−10, 0): the
    // same circle.
    quarter(
        &heidenhain(&[
            "CC X+0 Y+0",
            "L X+10 Y+0 Z+0 R0 F100",
            "C X+0 Y+10 DR+",
            "CT X-10 Y+0",
        ]),
        5,
        Vector3::zeros(),
        10.0,
    );
    // About a centre away from the origin: CC (20, 30), from (20, 40) clockwise to (30, 30),
    // then CT to (20, 20).
    quarter(
        &heidenhain(&[
            "CC X+20 Y+30",
            "L X+20 Y+40 Z+0 R0 F100",
            "C X+30 Y+30 DR-",
            "CT X+20 Y+20",
        ]),
        5,
        Vector3::new(20.0, 30.0, 0.0),
        10.0,
    );
}

// Found by cargo-mutants: the angles along an arc (`start + (new − start)·u`, each operator)
// survived: no test turned the rotary axes in an arc.
/// An arc that also turns the rotary axes carries them in proportion to the angle swept: G3
/// from (10, 0) to (−10, 0) about (0, 0), C10 A5 to C100 A35: at the point θ along the half
/// circle, C = 10 + 90·θ/π and A = 5 + 30·θ/π.
#[test]
fn an_arc_turns_the_rotary_axes_in_proportion_to_its_angle() {
    let (p, _) = read(
        "G43.4 H1\nG0 X10 Y0 Z0 C10 A5\nG3 X-10 Y0 I-10 J0 C100 A35 F100\n",
        ISO,
    );
    let arc: Vec<_> = p.iter().filter(|q| q.line == 3).collect();
    assert!(arc.len() > 4, "{}", arc.len());
    for q in arc {
        let u = q.tip.y.atan2(q.tip.x) / std::f64::consts::PI;
        let [c, a] = q.angles.unwrap();
        assert!((c - (10.0 + 90.0 * u)).abs() < 1e-9, "{u}: C {c}");
        assert!((a - (5.0 + 30.0 * u)).abs() < 1e-9, "{u}: A {a}");
    }
}

// Found by cargo-mutants: the message's hint (I J K read as absolute coordinates) given where
// they would not fit either (`&&` as `||`, twice) survived.
/// An arc whose end is off its circle names both radii, and adds that I J K read as absolute
/// coordinates would fit only when they would. G2 from (0, 0) to (10, 0) with I3 J0: the
/// centre (3, 0) is 3 and 7 mm away, and read as absolute it is (3, 0) again: no hint. From
/// (10, 0) to (−10, 0) with I0 J5: the centre (10, 5) is 5 and 20.6 mm away; read as absolute,
/// (0, 5) is √125 from both ends: the hint.
#[test]
fn the_absolute_centre_hint_is_given_only_where_it_fits() {
    let e = common::toolpath::error(
        "G0 X0 Y0 Z0\nG2 X10 Y0 I3 J0 F100\n",
        ISO,
        Some(&caz_head()),
    );
    assert_eq!(
        e,
        "line 2, column 1: the arc's end is not on its circle: 3 mm from the centre at the start, 7 mm at the end"
    );
    let e = common::toolpath::error(
        "G0 X10 Y0 Z0\nG2 X-10 Y0 I0 J5 F100\n",
        ISO,
        Some(&caz_head()),
    );
    assert!(e.contains("; read as absolute coordinates"), "{e}");
}

// Found by cargo-mutants: the tip's range check in the workpiece frame (`||` as `&&`) survived.
/// A point within ±100 000 mm in the program that a shift moves beyond it is refused at its
/// line: G52 X60000 then X50000 reaches x = 110 000 mm.
#[test]
fn a_tip_shifted_beyond_the_range_is_refused() {
    let e = common::toolpath::error(
        "G52 X60000 Y0 Z0\nG0 X50000 Y0 Z0\n",
        ISO,
        Some(&caz_head()),
    );
    assert!(
        e.starts_with("line 2: the tool tip reaches x = 110000 mm in the workpiece frame"),
        "{e}"
    );
}

// Found by cargo-mutants: `radius_centre`'s rules (the chord in the plane, a chord of zero
// length, the radius too short and its rounding allowance) survived.
/// An arc by its radius (R): the chord is measured in the arc's plane, so a helix (G17, Z
/// changing) from (0, 0, 0) to (10, 0, −5) with R5 is the half circle about (5, 0); an end
/// within 10⁻⁹ mm of the start is refused (a full circle needs its centre); a radius shorter
/// than half the chord is refused beyond the allowance for written numbers' rounding
/// (max(10⁻³ of half the chord, 0.005 mm)): R4.9 to an end 10 mm away is, R99.95 to an end
/// 200 mm away (0.05 short, within 0.1) is read as the half circle about the chord's middle.
#[test]
fn an_arc_by_its_radius_measures_its_chord_in_its_plane() {
    let (p, _) = read("G0 X0 Y0 Z0\nG2 X10 Y0 Z-5 R5 F100\n", ISO);
    let arc: Vec<_> = p.iter().filter(|q| q.line == 2).collect();
    assert!(arc.len() > 4);
    for q in &arc {
        let r = (q.tip.xy() - nalgebra::Vector2::new(5.0, 0.0)).norm();
        assert!((r - 5.0).abs() < 1e-9, "{:?}", q.tip);
    }
    close_vec(
        &arc.last().unwrap().tip,
        &Vector3::new(10.0, 0.0, -5.0),
        1e-9,
        "end",
    );
    let m = caz_head();
    let e = common::toolpath::error("G0 X0 Y0 Z0\nG2 X0.0000000001 Y0 R5 F100\n", ISO, Some(&m));
    assert!(e.contains("needs an end away from its start"), "{e}");
    let e = common::toolpath::error("G0 X0 Y0 Z0\nG2 X10 Y0 R4.9 F100\n", ISO, Some(&m));
    assert!(
        e.ends_with(
            "the radius 4.9 is shorter than half the distance to the end (5): no arc joins them"
        ),
        "{e}"
    );
    let (p, _) = read("G0 X0 Y0 Z0\nG2 X200 Y0 R99.95 F100\n", ISO);
    let arc: Vec<_> = p.iter().filter(|q| q.line == 2).collect();
    assert!(arc.len() > 4);
    for q in &arc {
        let r = (q.tip - Vector3::new(100.0, 0.0, 0.0)).norm();
        assert!((r - 100.0).abs() < 0.06, "{:?}", q.tip);
    }
}

// Found by cargo-mutants: the tangent taken from a move whose start was not known (`&&` as
// `||`) survived; the reader kept the move before's direction there, which is no better.
/// A move from a position the file does not state (after M91) has no known direction: a CT
/// after it is refused, not drawn tangent to a guess.
#[test]
fn ct_after_a_move_from_an_unknown_position_is_refused() {
    let e = common::toolpath::error(
        &heidenhain(&[
            "L X+0 Y+0 Z+0 R0 F100",
            "L X+10",
            "L Z+100 R0 FMAX M91",
            "L X+10 Y+10 Z+0 R0 F100",
            "CT X+20 Y+20",
        ]),
        Format::Heidenhain,
        Some(&caz_head()),
    );
    assert!(e.starts_with("line 6"), "{e}");
    assert!(e.contains("where the tool's position is not known"), "{e}");
}

// Found by cargo-mutants: a missing word of an absolute centre taken as 0 (the match guard as
// `false`) survived.
/// An absolute centre with a word missing (Siemens `I=AC(5)` alone: J is then 0 incremental,
/// 840D sl Programming Manual, "Circular interpolation") lies at the start's coordinate on that
/// axis: from (0, 5) to (10, 5) clockwise about (5, 5), radius 5 (about (5, 0) the ends are
/// √50 away too, so only the points tell).
#[test]
fn an_absolute_centre_s_missing_word_is_the_start_s_coordinate() {
    let (p, _) = read("G0 X0 Y5 Z0\nG2 X10 Y5 I=AC(5) F100\n", Format::Siemens);
    on_circle(&p, 2, Vector3::new(5.0, 5.0, 0.0), 5.0);
}
