//! The APT CL reader (`fiveaxis::toolpath::read::apt`), statement by statement, on CL data
//! written from what the CAM systems document: CATIA, "Syntax of Generated APT Instructions"
//! (GOTO with 3 or 6 numbers, TLAXIS, FROM, GODLTA, UNITS/MM|INCHES, FEDRAT/value,unit in either
//! order, `$$*CATIA0` matrix rows `a11 a12 a13 t1`); Creo, "CL Output for Circular
//! Interpolation" (`CIRCLE/x,y,z,i,j,k,r`, "(0,0,1) is counter-clockwise"); ICAM Post help,
//! "Matrix functions" (12 numbers, rows of `[R | t]`) and NX GRIP "Transformation matrix"
//! (elements 4, 8 and 12 the translation); the public NX CLSF sample and readers for `MSYS/`
//! (origin, x axis, y axis; GOTOs in that frame) and NX's clockwise arcs. Expected points are
//! computed by hand in the comments.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::toolpath::{at, chords, close_vec, error, note, read_all, read_with, skipped};
use fiveaxis::toolpath::read::{
    AptFrameChoice, Format, LengthUnit, Motion, NoteKind, ReadOptions, UnitChoice,
};
use nalgebra::Vector3;
use std::f64::consts::FRAC_PI_2;

const A: Format = Format::Apt;

#[test]
fn an_msys_with_z_down_maps_the_tool_axis_down_to_up() {
    // NX writes MSYS/origin, x axis, y axis; here x = (0, 1, 0), y = (1, 0, 0), so z = x × y =
    // (0, 0, −1). A GOTO (0, 222.6719, −177.5) with axis (0, 0, −1) in that frame is origin + R·p
    // = (−120.2591 + 222.6719, −1196.5, 142.5 + 177.5) = (102.4128, −1196.5, 320) with axis
    // R·(0, 0, −1) = (0, 0, 1).
    let text = "TOOL PATH/VARIABLE_CONTOUR,TOOL,T1\n\
                MSYS/-120.2591,-1196.5000,142.5000,0.0000000,1.0000000,0.0000000,1.0000000,0.0000000,0.0000000\n\
                RAPID\n\
                GOTO/0.0000,222.6719,-177.5000,0.0000000,0.0000000,-1.0000000\n";
    let (p, r) = read_all(text, A, None);
    close_vec(
        &p[0].tip,
        &Vector3::new(102.4128, -1196.5, 320.0),
        1e-9,
        "tip",
    );
    close_vec(&p[0].axis, &Vector3::z(), 1e-15, "axis up");
    let f = r.frame_choice.clone().unwrap();
    assert_eq!(
        (f.statement.as_str(), f.line, f.reading),
        ("MSYS/", 2, AptFrameChoice::Apply)
    );
    assert!(f.frame.contains("z axis (0, 0, -1)"), "{}", f.frame);
    assert_eq!(
        note(&r, "MSYS/ states the output frame").kind,
        NoteKind::Frame
    );
    // Read the other way: the points as written.
    let ignore = ReadOptions {
        apt_frame: AptFrameChoice::Ignore,
        ..ReadOptions::default()
    };
    let (p, r) = read_with(text, A, None, ignore);
    assert_eq!(p[0].tip, Vector3::new(0.0, 222.6719, -177.5));
    close_vec(&p[0].axis, &-Vector3::z(), 1e-15, "as written");
    assert_eq!(r.frame_choice.unwrap().reading, AptFrameChoice::Ignore);
}

#[test]
fn a_12_number_msys_csys_and_tracut_are_rows_of_r_and_t() {
    // R_Z(90°) with t = (10, 20, 30): rows (0, −1, 0, 10), (1, 0, 0, 20), (0, 0, 1, 30).
    // (1, 0, 0) → R·(1, 0, 0) + t = (0, 1, 0) + t = (10, 21, 30).
    let (p, _) = read_all("MSYS/0,-1,0,10,1,0,0,20,0,0,1,30\nGOTO/1,0,0\n", A, None);
    close_vec(&p[0].tip, &Vector3::new(10.0, 21.0, 30.0), 1e-12, "MSYS/12");
    // CSYS/: a 90° turn about Z and a 10° tilt about X, R = R_Z(90°)·R_X(10°) = rows
    // (0, −cos 10°, sin 10°), (1, 0, 0), (0, sin 10°, cos 10°), and t = (5, 0, 0). The point
    // (0, 0, 10) → (10 sin 10°, 0, 10 cos 10°) + t, the axis (0, 0, 1) → (sin 10°, 0, cos 10°).
    let (s, c) = 10f64.to_radians().sin_cos();
    let text = format!(
        "CSYS/0,{},{s},5,1,0,0,0,0,{s},{c},0\nGOTO/0,0,10,0,0,1\n",
        -c
    );
    let (p, r) = read_all(&text, A, None);
    close_vec(
        &p[0].tip,
        &Vector3::new(5.0 + 10.0 * s, 0.0, 10.0 * c),
        1e-12,
        "CSYS tip",
    );
    close_vec(&p[0].axis, &Vector3::new(s, 0.0, c), 1e-15, "CSYS axis");
    assert_eq!(r.frame_choice.unwrap().statement, "CSYS/");
    // TRACUT moves the points after it until TRACUT/NOMORE.
    let (p, _) = read_all(
        "TRACUT/1,0,0,5,0,1,0,0,0,0,1,0\nGOTO/1,2,3\nTRACUT/NOMORE\nGOTO/1,2,3\n",
        A,
        None,
    );
    assert_eq!(p[0].tip, Vector3::new(6.0, 2.0, 3.0));
    assert_eq!(p[1].tip, Vector3::new(1.0, 2.0, 3.0));
    // A mirror or a matrix that is not a rotation is refused.
    at(
        &error("CSYS/-1,0,0,0,0,1,0,0,0,0,1,0\n", A, None),
        1,
        6,
        "is not a frame",
    );
    at(
        &error("MSYS/0,0,0,1,0,0\n", A, None),
        1,
        6,
        "expected MSYS/ with 9 numbers",
    );
}

#[test]
fn catia_s_machining_axis_system_is_read_from_its_comment_lines() {
    // Rows a11 a12 a13 t1 …: R_Z(90°), t = (1, 2, 3); (1, 0, 0) → (0, 1, 0) + t = (1, 3, 3).
    let text = "$$*CATIA0\n$$ Axis System.1\n$$ 0 -1 0 1\n$$ 1 0 0 2\n$$ 0 0 1 3\nGOTO/1,0,0\n";
    let (p, r) = read_all(text, A, None);
    close_vec(&p[0].tip, &Vector3::new(1.0, 3.0, 3.0), 1e-12, "CATIA0");
    assert_eq!(r.frame_choice.unwrap().statement, "$$*CATIA0");
}

#[test]
fn units_stated_and_implied_by_the_feed() {
    let (p, r) = read_all("UNITS/INCHES\nGOTO/1,2,3\n", A, None);
    close_vec(
        &p[0].tip,
        &Vector3::new(25.4, 50.8, 76.2),
        1e-12,
        "UNITS/INCHES",
    );
    assert_eq!(r.unit_reason, "inches: UNITS/INCHES on line 1");
    let (p, r) = read_all("UNIT/MM\nGOTO/1,2,3\n", A, None);
    assert_eq!(p[0].tip, Vector3::new(1.0, 2.0, 3.0));
    assert_eq!(r.unit_reason, "millimetres: UNIT/MM on line 1");
    // NX writes no UNITS/; a feed in inches per minute after the first points makes them
    // inches, all of them (read before the hint and scaled at the end).
    let text = "RAPID\nGOTO/1,0,0\nFEDRAT/IPM,10.0000\nGOTO/2,0,0\n";
    let (p, r) = read_all(text, A, None);
    close_vec(
        &p[0].tip,
        &Vector3::new(25.4, 0.0, 0.0),
        1e-12,
        "before the hint",
    );
    close_vec(&p[1].tip, &Vector3::new(50.8, 0.0, 0.0), 1e-12, "after it");
    assert_eq!(r.unit, LengthUnit::Inch);
    assert!(
        r.unit_reason
            .starts_with("inches: FEDRAT/IPM (a feed in inches) on line 3"),
        "{}",
        r.unit_reason
    );
    // The unit word after the value (CATIA's other order) is the same hint.
    let (_, r) = read_all("GOTO/1,0,0\nFEDRAT/10,IPM\n", A, None);
    assert_eq!(r.unit, LengthUnit::Inch);
    // The user's pick wins over a hint, and the report says so.
    let mm = ReadOptions {
        unit: UnitChoice::Mm,
        ..ReadOptions::default()
    };
    let (p, r) = read_with(text, A, None, mm);
    assert_eq!(p[1].tip, Vector3::new(2.0, 0.0, 0.0));
    assert_eq!(
        r.unit_reason,
        "millimetres: the unit chosen for a file that states none"
    );
}

/// A frame stated before the feed that makes the file inches is described in the unit the
/// points are read in: `MSYS/3,3,0,…` then `FEDRAT/IPM` (as NX writes CL data) is an origin of
/// 76.2 mm, and the point `GOTO/1,0,0` is at (4 in, 3 in, 0) = (101.6, 76.2, 0) mm; the same
/// for `TRACUT/`. Where `UNITS/INCHES` is stated after the frame, the frame stays where it was
/// read (3 mm: a unit change keeps positions where they are), and the note says that.
#[test]
fn a_frame_before_the_unit_hint_is_described_in_the_unit_decided() {
    let msys = "MSYS/3,3,0,1,0,0,0,1,0\n";
    let (p, r) = read_all(&format!("{msys}FEDRAT/IPM,10\nGOTO/1,0,0\n"), A, None);
    close_vec(&p[0].tip, &Vector3::new(101.6, 76.2, 0.0), 1e-12, "tip");
    assert!(note(&r, "MSYS/").text.contains("origin (76.2, 76.2, 0) mm"));
    assert_eq!(r.frame_choice.unwrap().frame, "origin (76.2, 76.2, 0) mm");
    let (p, r) = read_all(
        "TRACUT/1,0,0,3,0,1,0,3,0,0,1,0\nFEDRAT/IPM,10\nGOTO/1,0,0\n",
        A,
        None,
    );
    close_vec(&p[0].tip, &Vector3::new(101.6, 76.2, 0.0), 1e-12, "tip");
    assert!(note(&r, "TRACUT/")
        .text
        .contains("by origin (76.2, 76.2, 0) mm"));
    let (p, r) = read_all(
        &format!("{msys}UNITS/INCHES\nFEDRAT/IPM,10\nGOTO/1,0,0\n"),
        A,
        None,
    );
    close_vec(&p[0].tip, &Vector3::new(28.4, 3.0, 0.0), 1e-12, "tip");
    assert!(note(&r, "MSYS/").text.contains("origin (3, 3, 0) mm"));
}

/// Two output frames before the unit hint: each applies to the points after it, both in the
/// unit decided (inches: `GOTO/1,0,0` after `MSYS/5,5,0,…` is (6 in, 5 in, 0) = (152.4, 127,
/// 0) mm), and the note, which describes its first occurrence and counts the rest, and the
/// frame choice are of the first frame, described in inches too.
// Found by cargo-mutants: `Log::frame_note` recorded the second frame for describing again
// (`&&` as `||`, `==` as `!=`), and the note then described the second.
#[test]
fn two_frames_before_the_unit_hint_are_noted_as_the_first_in_the_unit_decided() {
    let text = "MSYS/3,3,0,1,0,0,0,1,0\nGOTO/1,0,0\nMSYS/5,5,0,1,0,0,0,1,0\nFEDRAT/IPM,10\n\
                GOTO/1,0,0\n";
    let (p, r) = read_all(text, A, None);
    close_vec(&p[0].tip, &Vector3::new(101.6, 76.2, 0.0), 1e-12, "first");
    close_vec(&p[1].tip, &Vector3::new(152.4, 127.0, 0.0), 1e-12, "second");
    let n = note(&r, "MSYS/");
    assert_eq!((n.line, n.count), (1, 2));
    assert!(n.text.contains("origin (76.2, 76.2, 0) mm"), "{}", n.text);
    assert_eq!(r.frame_choice.unwrap().frame, "origin (76.2, 76.2, 0) mm");
}

/// Creo's CL header, as PTC Creo 9.0 wrote it (4r19415/5-axis-Rotation-tool-center-point-RTCP-,
/// `assets/finition.ncl` and `finition2.ncl`, commit 841acbb; no licence, so the files are not
/// stored and these lines are quoted): `REMARK` lines (comments, as `PPRINT`), the `PPWORD/`
/// vocabulary table of its post, and a `$$->` comment continued with `$` over two lines of
/// numbers. None is an unknown statement, and the `GOTO/` continued with `$` after them is read:
/// 351.7389525618 in = 8934.169 mm, the tool axis (0.9997838891, −0.0000009626, 0.0207888211)
/// normalised. A comment line ending in `$$` (a banner), or in `$` before a statement, leaves
/// the next line a statement.
#[test]
fn creo_s_remarks_vocabulary_and_continued_comments_are_comments() {
    let text = "$$*          Pro/CLfile  Version 9.0 - 9.0.3.0\n\
                PARTNO / MFG0001\n\
                REMARK *          PRO/CLFILE  VERSION 9.0 - 9.0.3.0\n\
                REMARK  GPOST MILL SYSTEM VOCABULARY TABLE\n\
                PPWORD/TLANGL,1\n\
                PPWORD/RETURN,7\n\
                REMARK -> CUTTER / 6.000000\n\
                UNITS / INCHES\n\
                $$-> CSYS / 1.0000000000, 0.0000000000, 0.0000000000, 0.0000000000,  $\n\
                \x20           0.0000000000, 1.0000000000, 0.0000000000, 0.0000000000,  $\n\
                \x20           0.0000000000, 0.0000000000, 1.0000000000, 0.0000000000\n\
                MULTAX / ON\n\
                RAPID \n\
                GOTO / 351.7389525618, 98.4998561102, 144.0966038928,  $\n\
                0.9997838891, -0.0000009626, 0.0207888211\n";
    assert_eq!(Format::detect(text), A);
    assert_eq!(Format::detect("REMARK made by hand\nGOTO/1,2,3\n"), A);
    let (p, r) = read_all(text, A, None);
    assert_eq!(p.len(), 1);
    close_vec(
        &p[0].tip,
        &(Vector3::new(351.7389525618, 98.4998561102, 144.0966038928) * 25.4),
        1e-9,
        "tip",
    );
    let axis = Vector3::new(0.9997838891, -0.0000009626, 0.0207888211);
    close_vec(&p[0].axis, &axis.normalize(), 1e-15, "axis");
    assert_eq!((p[0].line, p[0].motion), (14, Motion::Rapid));
    assert!(
        r.notes.iter().all(|n| n.kind != NoteKind::Partial),
        "{:?}",
        r.notes
    );
    assert_eq!(skipped(&r, "names and comments"), 4);
    assert_eq!(skipped(&r, "post-processor"), 2);
    assert_eq!(skipped(&r, "does not know"), 0);
    for text in [
        "$$ ---------- $$\nGOTO/1,2,3\n",
        "$$ to be continued $\nGOTO/1,2,3\n",
        "$$ to be continued $\n$$ and more\nGOTO/1,2,3\n",
    ] {
        let (p, _) = read_all(text, A, None);
        assert_eq!(p.len(), 1, "{text:?}");
        assert_eq!(p[0].tip, Vector3::new(1.0, 2.0, 3.0), "{text:?}");
    }
    // An indented comment, continued or not, is a comment.
    // Found by cargo-mutants: the comment's text taken from `p * 2` instead of `p + 2` survived.
    for text in [
        "          $$ x\nGOTO/1,2,3\n",
        "          $$ x $\n 1, 2\nGOTO/1,2,3\n",
    ] {
        let (p, _) = read_all(text, A, None);
        assert_eq!(p.len(), 1, "{text:?}");
    }
    // The lines of numbers after a comment ending in `$`, however many, are the comment's.
    let (p, _) = read_all("$$ CSYS / 1, 0, $\n 0, 1, $\n 0, 0\nGOTO/1,2,3\n", A, None);
    assert_eq!(p.len(), 1);
}

/// A `GOTO/` after `CIRCLE/` follows the arc when it lies within 10⁻³ of the radius (at least
/// 0.01) of the circle, measured from the axis: its height along the axis does not count (an
/// arc at z = 5 about a centre written at z = 0). Farther, it is a straight move that ends the
/// arc; nearer than that but farther than the rounding the two radii may differ by (0.01 mm or
/// 10⁻⁴ of the radius: 0.01 on a radius of 100), it is refused. A start off the radius is
/// refused. (In millimetres stated: while an APT file's unit may still become inches, arcs
/// are cut within the tolerance in inches, 25.4 times finer.)
// Found by cargo-mutants: the radial distance (`d − n(n·d)` as `d + n(n·d)`), the tolerance
// (`1e-3 · r` as `1e-3 / r`) and the start's check (`>` as `==`) survived.
#[test]
fn a_goto_follows_the_circle_within_its_tolerance_from_the_axis() {
    let n = chords(10.0, FRAC_PI_2, 0.001);
    let (p, r) = read_all(
        "UNITS/MM\nGOTO/10,0,5\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,10,5\n",
        A,
        None,
    );
    assert_eq!(r.arc_points, n);
    for q in &p[1..] {
        let radial = (q.tip.x.powi(2) + q.tip.y.powi(2)).sqrt();
        assert!(
            (radial - 10.0).abs() < 1e-9 && q.tip.z == 5.0,
            "{:?}",
            q.tip
        );
        // Counter-clockwise about +Z (Creo's sense): the first quadrant.
        assert!(q.tip.x > -1e-9 && q.tip.y > -1e-9, "{:?}", q.tip);
    }
    // Radius 100: 0.2 off is a straight move, 0.05 off is refused as not on the circle.
    let (p, r) = read_all(
        "UNITS/MM\nGOTO/100,0,0\nCIRCLE/0,0,0,0,0,1,100\nGOTO/0,100.2,0\n",
        A,
        None,
    );
    assert_eq!((r.arc_points, r.feeds), (0, 1));
    assert_eq!(p[1].tip, Vector3::new(0.0, 100.2, 0.0));
    at(
        &error(
            "UNITS/MM\nGOTO/100,0,0\nCIRCLE/0,0,0,0,0,1,100\nGOTO/0,100.05,0\n",
            A,
            None,
        ),
        4,
        6,
        "the arc's end is not on its circle (100 and 100.05",
    );
    at(
        &error(
            "UNITS/MM\nGOTO/12,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,10,0\n",
            A,
            None,
        ),
        4,
        6,
        "the arc of the CIRCLE/ before starts 12 from its axis, not on its radius 10",
    );
}

/// `UNITS/` keeps what the reader holds where it physically is: the FROM/ point `GOHOME`
/// returns to, the last position (a
/// `GODLTA/` after it moves from there: 25.4 mm = 1 in, + 1 in = 50.8 mm) and a circle not yet
/// followed (centre 25.4 mm = 1 in, radius 1 in: the `GOTO/1,1,0` in inches is on it, a quarter
/// turn of 89 chords). `FEDRAT/…,IPR` implies inches as `IPM` does, `MMPR` millimetres.
// Found by cargo-mutants: the position's, the home's and the circle's conversion (`* k` as
// `/ k`, `+ k`) and `IPR`, `MMPR` (`||` as `&&`) survived.
#[test]
fn units_keep_the_position_and_the_circle_held_and_ipr_is_inches() {
    let (p, _) = read_all("GOTO/25.4,0,0\nUNITS/INCHES\nGODLTA/1,0,0\n", A, None);
    close_vec(&p[1].tip, &Vector3::new(50.8, 0.0, 0.0), 1e-12, "GODLTA");
    let (p, r) = read_all(
        "GOTO/50.8,0,0\nCIRCLE/25.4,0,0,0,0,1,25.4\nUNITS/INCHES\nGOTO/1,1,0\n",
        A,
        None,
    );
    assert_eq!(r.arc_points, chords(25.4, FRAC_PI_2, 0.001));
    for q in &p[1..] {
        let d = q.tip - Vector3::new(25.4, 0.0, 0.0);
        assert!((d.norm() - 25.4).abs() < 1e-9, "{:?}", q.tip);
    }
    close_vec(
        &p[p.len() - 1].tip,
        &Vector3::new(25.4, 25.4, 0.0),
        1e-12,
        "end",
    );
    // GOHOME after a unit change returns to the FROM/ point where it physically is.
    let (p, _) = read_all("FROM/25.4,0,0\nGOTO/0,0,0\nUNITS/INCHES\nGOHOME\n", A, None);
    close_vec(&p[2].tip, &Vector3::new(25.4, 0.0, 0.0), 1e-12, "GOHOME");
    let (_, r) = read_all("GOTO/1,0,0\nFEDRAT/0.1,MMPR\n", A, None);
    assert_eq!(
        r.unit_reason,
        "millimetres: FEDRAT/MMPR (a feed in millimetres) on line 2 (the file states no length \
         unit; change it beside the file if this is wrong)"
    );
    let (p, r) = read_all("GOTO/1,0,0\nFEDRAT/0.004,IPR\n", A, None);
    assert_eq!(r.unit, LengthUnit::Inch);
    assert!(
        r.unit_reason
            .contains("FEDRAT/IPR (a feed in inches) on line 2"),
        "{}",
        r.unit_reason
    );
    close_vec(&p[0].tip, &Vector3::new(25.4, 0.0, 0.0), 1e-12, "tip");
}

/// The numbers of a statement and their limits: a point beyond ±100 000 mm is refused at its
/// line, after the output frame is applied (50 000 mm in an MSYS/ frame 60 000 mm along X is
/// 110 000 mm); 100 000 mm itself is within. A `CIRCLE/` radius must be above 0 and its centre
/// within the range. An error names the column of the field that is wrong (a `CIRCLE/`'s
/// radius or centre: the start of its arguments, column 8, as the circle is read whole), and a
/// 7th number of a `GOTO/` is one too many, whatever it is; a statement with no numbers where
/// one is needed names its empty field. A line of numbers after a comment that does not end in
/// a single `$` (none, or `$$` closing it) is no statement.
// Found by cargo-mutants: the range checks (`>` as `>=`, `==`; `||` as `&&`), the fields'
// offsets (`+` as `-`), the count of numbers read (`<` as `<=`) and a comment's continuation
// (`continues` always true) survived.
#[test]
fn numbers_ranges_and_columns() {
    let (p, _) = read_all("UNITS/MM\nGOTO/100000,0,-100000\n", A, None);
    assert_eq!(p[0].tip, Vector3::new(1e5, 0.0, -1e5));
    at(
        &error("UNITS/MM\nGOTO/200000,0,0\n", A, None),
        2,
        6,
        "expected x within ±100000 mm, got \"200000\"",
    );
    // In the output frame: checked where the frame puts the point.
    let e = error(
        "UNITS/MM\nMSYS/60000,0,0,1,0,0,0,1,0\nGOTO/50000,0,0\n",
        A,
        None,
    );
    assert_eq!(e, "line 3: expected x within ±100000 mm, got 110000 mm");
    let e = error(
        "UNITS/MM\nMSYS/0,0,-60000,1,0,0,0,1,0\nGOTO/0,0,-50000\n",
        A,
        None,
    );
    assert_eq!(e, "line 3: expected z within ±100000 mm, got -110000 mm");
    let (p, _) = read_all(
        "UNITS/MM\nMSYS/50000,0,0,1,0,0,0,1,0\nGOTO/50000,0,0\n",
        A,
        None,
    );
    assert_eq!(p[0].tip.x, 1e5);
    let (p, _) = read_all(
        "UNITS/MM\nGOTO/99990,0,0\nCIRCLE/100000,0,0,0,0,1,10\nGOTO/100000,-10,0\n",
        A,
        None,
    );
    assert!(p.iter().all(|q| q.tip.x <= 1e5 && q.tip.x >= 99990.0));
    for (args, col, what) in [
        (
            "0,0,0,0,0,1,-5",
            8,
            "expected a CIRCLE/ radius above 0, got -5",
        ),
        (
            "0,0,0,0,0,1,0",
            8,
            "expected a CIRCLE/ radius above 0, got 0",
        ),
        (
            "200000,0,0,0,0,1,10",
            8,
            "expected the CIRCLE/ centre within ±100000 mm",
        ),
    ] {
        at(
            &error(&format!("GOTO/1,0,0\nCIRCLE/{args}\n"), A, None),
            2,
            col,
            what,
        );
    }
    at(
        &error("GOTO/1,x,3\n", A, None),
        1,
        8,
        "expected a number after GOTO/, got \"x\"",
    );
    at(&error("GOTO/1, 2,  y\n", A, None), 1, 13, "got \"y\"");
    at(&error("GOTO/1,2,3,0,0,1,x\n", A, None), 1, 18, "got 7");
    at(
        &error("GOTO/1,0,0\nGODLTA/\n", A, None),
        2,
        8,
        "expected a number after GODLTA/, got \"\"",
    );
    // CIRCLE/'s fields (up to 12 numbers): each column, and a 13th.
    // Found by cargo-mutants: `all_numbers`'s offsets (`+`, `-` swapped) and the 13th field's
    // (`==` as `!=`) survived.
    for (args, col, what) in [
        ("0,0,x", 12, "expected a number after CIRCLE/, got \"x\""),
        ("0, 0,  y", 15, "got \"y\""),
        (
            "0,0,0,1,2",
            8,
            "or 7 and more (centre, axis, radius), got 5",
        ),
        ("0,0,0,0,0,1,10,0,0,0,0,0,7", 33, "got 13"),
    ] {
        at(
            &error(&format!("GOTO/1,0,0\nCIRCLE/{args}\n"), A, None),
            2,
            col,
            what,
        );
    }
    for text in ["$$ a comment\n10,20,30\n", "$$ --- $$\n10,20,30\n"] {
        at(
            &error(text, A, None),
            2,
            1,
            "expected an APT statement such as GOTO/x,y,z,i,j,k, got \"10\"",
        );
    }
}

#[test]
fn rapid_is_one_shot_and_from_godlta_move_the_tool() {
    let text =
        "FROM/0,0,50\nRAPID\nGOTO/0,0,10\nGOTO/0,0,0\nGODLTA/5,0,0\nTLAXIS/0,0,1\nGODLTA/2\n";
    let (p, _) = read_all(text, A, None);
    let got: Vec<_> = p.iter().map(|q| (q.tip, q.motion)).collect();
    assert_eq!(
        got,
        [
            (Vector3::new(0.0, 0.0, 50.0), Motion::Rapid),
            (Vector3::new(0.0, 0.0, 10.0), Motion::Rapid),
            (Vector3::new(0.0, 0.0, 0.0), Motion::Feed),
            (Vector3::new(5.0, 0.0, 0.0), Motion::Feed),
            // GODLTA/2: 2 along the tool axis.
            (Vector3::new(5.0, 0.0, 2.0), Motion::Feed),
        ]
    );
    at(
        &error("GODLTA/1,2,3\n", A, None),
        1,
        8,
        "but there is none yet",
    );
}

#[test]
fn circle_arcs_turn_counter_clockwise_about_their_axis_and_clockwise_in_nx() {
    // Creo: CIRCLE/0,0,0,0,0,1,10 then the end (0, 10): counter-clockwise, the first quadrant.
    let (p, r) = read_all(
        "UNITS/MM\nGOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,10,0\n",
        A,
        None,
    );
    assert_eq!(r.arc_points, chords(10.0, FRAC_PI_2, 0.001));
    assert!(p[1..].iter().all(|q| q.motion == Motion::Arc
        && q.tip.x > -1e-9
        && q.tip.y > -1e-9
        && (q.tip.norm() - 10.0).abs() < 1e-9));
    // NX (TOOL PATH/ present): clockwise about (0, 0, 1), three quarters through (0, −10); the
    // 11-number form with its last four numbers not used.
    let text = "UNITS/MM\nTOOL PATH/P,TOOL,T\nGOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10.0000,0.0600,0.5000,0.0000,0.0000\nGOTO/0,10,0\n";
    let (p, r) = read_all(text, A, None);
    assert_eq!(r.arc_points, chords(10.0, 3.0 * FRAC_PI_2, 0.001));
    assert!(p
        .iter()
        .any(|q| (q.tip - Vector3::new(0.0, -10.0, 0.0)).norm() < 0.2));
    // Several GOTOs on the circle follow it; one off it is a straight move.
    let (p, _) = read_all(
        "UNITS/MM\nGOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,10,0\nGOTO/-10,0,0\nGOTO/-20,0,0\n",
        A,
        None,
    );
    assert_eq!(
        p.iter().filter(|q| q.motion == Motion::Arc).count(),
        2 * chords(10.0, FRAC_PI_2, 0.001)
    );
    assert_eq!(p[p.len() - 1].motion, Motion::Feed);
    // 6 numbers: the radius is the start's distance from the axis; 4: about the tool axis.
    let (p, _) = read_all("GOTO/5,0,0\nCIRCLE/0,0,0,0,0,1\nGOTO/0,5,0\n", A, None);
    assert!(p[1..].iter().all(|q| (q.tip.norm() - 5.0).abs() < 1e-9));
    let (p, _) = read_all("GOTO/5,0,0\nCIRCLE/0,0,0,5\nGOTO/0,5,0\n", A, None);
    assert!(p[1..]
        .iter()
        .all(|q| (q.tip.norm() - 5.0).abs() < 1e-9 && q.motion == Motion::Arc));
}

/// An arc read before the file's unit is known (no UNITS/, the FEDRAT/IPM hint comes after it)
/// still keeps its chords within the tolerance once the points turn out to be inches: r = 1 in
/// = 25.4 mm, a quarter turn, 1 µm: ⌈(π/2) / (2·acos(1 − 0.001/25.4))⌉ = 89 chords.
#[test]
fn an_arc_before_the_unit_hint_keeps_the_tolerance_in_the_unit_decided_later() {
    let (p, r) = read_all(
        "GOTO/1,0,0\nCIRCLE/0,0,0,0,0,1,1\nGOTO/0,1,0\nFEDRAT/IPM,20\nGOTO/0,2,0\n",
        A,
        None,
    );
    assert_eq!(r.unit, LengthUnit::Inch);
    assert_eq!(chords(25.4, FRAC_PI_2, 0.001), 89);
    let arc: Vec<_> = p.iter().filter(|q| q.motion == Motion::Arc).collect();
    assert_eq!(arc.len(), 89);
    // Each chord's middle lies within 1 µm of the 25.4 mm circle.
    let mut last = p[0].tip;
    for q in &arc {
        let mid = (last + q.tip) / 2.0;
        assert!(
            25.4 - mid.norm() <= 0.001 + 1e-12,
            "sagitta {}",
            25.4 - mid.norm()
        );
        last = q.tip;
    }
    assert_eq!(p.last().map(|q| q.tip), Some(Vector3::new(0.0, 50.8, 0.0)));
}

/// A unit statement in the middle of the file: the last position stays where it physically is
/// (10 mm, then 1 inch more: 35.4 mm).
#[test]
fn a_unit_change_keeps_the_last_position_where_it_is() {
    let (p, _) = read_all(
        "UNITS/MM\nGOTO/10,0,0\nUNITS/INCHES\nGODLTA/1,0,0\n",
        A,
        None,
    );
    assert!((p[1].tip.x - 35.4).abs() < 1e-9, "{}", p[1].tip.x);
}

#[test]
fn cycles_are_rapid_positions_and_unknown_statements_are_listed() {
    let text = "RAPID\nGOTO/8,15,25\nCYCLE/DRILL,FEDTO,7.8,MMPM,326.8,RAPTO,3\nGOTO/8,15,0\nGOTO/27,15,0\nCYCLE/OFF\nFOO/1,2\nSPINDL/5000,RPM,CLW\nCOOLNT/FLOOD\n";
    let (p, r) = read_all(text, A, None);
    assert!(p.iter().all(|q| q.motion == Motion::Rapid));
    assert_eq!(note(&r, "CYCLE/DRILL").kind, NoteKind::Partial);
    assert_eq!(skipped(&r, "does not know"), 1);
    assert_eq!(note(&r, "FOO is not a statement the reader knows").line, 7);
    assert_eq!(skipped(&r, "spindle and coolant"), 2);
}

#[test]
fn undocumented_and_source_forms_are_refused() {
    for (text, column, part) in [
        (
            "GOTO/1,2,3,4,5\n",
            12,
            "got 5: no documentation defines that form",
        ),
        (
            "GOTO/1,2,3,0,0,1,7,8\n",
            18,
            "got 8: no documentation defines that form",
        ),
        ("NURBS/1,2,3\n", 1, "NURBS/ is a spline"),
        ("INDIRV/1,0,0\n", 1, "APT part-program (source) language"),
        ("ROTABL/90\n", 1, "turns the table"),
        ("MSYS/LAST\n", 6, "MSYS/LAST"),
        ("CIRCLE/0,0,0,0,0,0,5\n", 8, "must not be zero"),
        // NX's helix of seven turns, as in userFour/MECH491-postprocessor `APT_Project2.txt`
        // line 4641 (a helical bore): refused at TIMES, with what it is.
        (
            "CIRCLE/1.9949,3.6307,1.9391,0.0000000,-0.9922779,-0.1240347,0.1687,0.0060,0.5000,0.3750,0.0000,TIMES,7\n",
            96,
            "turns n times round",
        ),
    ] {
        at(&error(text, A, None), 1, column, part);
    }
}

#[test]
fn catia_spacing_multax_and_tlaxis() {
    // CATIA writes a blank after the slash and between the numbers; MULTAX/ ON switches to
    // six-number GOTOs (the count of numbers is read in any case), TLAXIS sets the axis of the
    // three-number ones.
    let text = "PARTNO PART1\n\
                MULTAX/ ON\n\
                TLAXIS/  0.000000,  0.000000,  1.000000\n\
                GOTO  /   10.00000,  20.00000,  30.00000\n\
                GOTO  /   10.00000,  20.00000,  25.00000,  0.000000, -0.600000,  0.800000\n\
                MULTAX/ OFF\n\
                GOTO  /   11.00000,  20.00000,  25.00000\n";
    let (p, r) = read_all(text, A, None);
    assert_eq!(
        p.iter().map(|q| q.tip).collect::<Vec<_>>(),
        [
            Vector3::new(10.0, 20.0, 30.0),
            Vector3::new(10.0, 20.0, 25.0),
            Vector3::new(11.0, 20.0, 25.0),
        ]
    );
    close_vec(&p[0].axis, &Vector3::z(), 1e-15, "TLAXIS");
    close_vec(
        &p[1].axis,
        &Vector3::new(0.0, -0.6, 0.8),
        1e-15,
        "six numbers",
    );
    close_vec(&p[2].axis, &Vector3::new(0.0, -0.6, 0.8), 1e-15, "kept");
    assert_eq!(skipped(&r, "MULTAX"), 2);
}

/// GOHOME returns to the FROM/ point at rapid (APT: "GOHOME, move to the FROM point"); without
/// a FROM/ the path breaks. Statements the reader does not know are each listed by name.
#[test]
fn gohome_returns_to_from_and_unknown_statements_are_named() {
    let (p, r) = read_all(
        "UNITS/MM\nFROM/0,0,100\nGOTO/10,0,0\nGOTO/20,0,0\nGOHOME\nTLCOMP/ON\nWPLANE/1\nGOTO/30,0,0\n",
        A,
        None,
    );
    let got: Vec<_> = p.iter().map(|q| (q.tip.x, q.tip.z, q.motion)).collect();
    assert_eq!(
        got,
        [
            (0.0, 100.0, Motion::Rapid),
            (10.0, 0.0, Motion::Feed),
            (20.0, 0.0, Motion::Feed),
            (0.0, 100.0, Motion::Rapid),
            (30.0, 0.0, Motion::Feed),
        ]
    );
    assert_eq!(
        skipped(&r, "TLCOMP: a statement the reader does not know"),
        1
    );
    assert_eq!(
        skipped(&r, "WPLANE: a statement the reader does not know"),
        1
    );
    let (p, r) = read_all("UNITS/MM\nGOTO/10,0,0\nGOHOME\nGOTO/30,0,0\n", A, None);
    assert_eq!(p[1].motion, Motion::Rapid, "across the break");
    assert_eq!(note(&r, "GOHOME returns").kind, NoteKind::Break);
}
