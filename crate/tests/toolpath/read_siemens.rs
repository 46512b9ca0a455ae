//! The Siemens Sinumerik 840D reader (`fiveaxis::toolpath::read::siemens`), construct by
//! construct, on programs written from the SINUMERIK manuals: ONE / 840D sl Programming Manual
//! "NC programming" 12/2019 (6FC5398-2EP40-0BA0: `CR=` p.192, `TRANS`/`ATRANS` p.309 with its
//! example "TRANS X10 Y10 Z10 then ATRANS X5 Y5 gives X15 Y15 Z10", `ROT`/`AROT` pp.315–316,
//! `TRAORI` p.666), Job Planning 03/2006 (A3 B3 C3 "points towards the tool adapter; the length
//! is of no significance", p.7-20), 808D Programming Manual (`=AC()`/`=IC()` p.53, `TRANS`
//! alone clears p.56), 828D Job Planning (`DEF` p.23), Function Manual K2 (MD10600: ROT turns
//! "first about Z, then about the new Y′, then about the new X″"). Expected points are computed
//! by hand in the comments.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::toolpath::{at, caz, caz_head, close_vec, error, note, read_all, skipped};
use fiveaxis::toolpath::read::{Format, LengthUnit, Motion, NoteKind};
use nalgebra::Vector3;

const S: Format = Format::Siemens;

#[test]
fn traori_blocks_with_ic_ac_and_dc_words() {
    let m = caz_head();
    let text = "N10 G17 G90 G71 ; millimetres\n\
                N20 MSG(\"roughing\")\n\
                N30 TRAORI\n\
                N40 G0 X10 Y20 Z30 A0 C0\n\
                N50 G1 X=15 Y=IC(5) A=30 F1000\n\
                N60 Z=AC(12) C=DC(350)\n\
                N70 M30\n";
    let (p, r) = read_all(text, S, Some(&m));
    assert_eq!(r.format, Format::Siemens);
    assert_eq!(r.tcp.as_deref(), Some("TRAORI on line 3"));
    assert_eq!(r.unit, LengthUnit::Mm);
    assert_eq!(r.unit_reason, "millimetres: G71 on line 1");
    // Y=IC(5): 20 + 5. C=DC(350) from 0°: the shorter way, −10°.
    let expected = [
        (4, [10.0, 20.0, 30.0], [0.0, 0.0], Motion::Rapid),
        (5, [15.0, 25.0, 30.0], [0.0, 30.0], Motion::Feed),
        (6, [15.0, 25.0, 12.0], [-10.0, 30.0], Motion::Feed),
    ];
    assert_eq!(p.len(), expected.len());
    for (q, (line, tip, angles, motion)) in p.iter().zip(expected) {
        assert_eq!((q.line, q.motion), (line, motion));
        assert_eq!(q.tip, Vector3::from(tip));
        assert_eq!(q.angles, Some(angles));
        close_vec(&q.axis, &caz(angles[0], angles[1]), 1e-15, "axis");
    }
    assert_eq!(skipped(&r, "messages"), 1);
    assert_eq!(skipped(&r, "program ends"), 1);
}

/// `TRAFOOF` with the rotary axes turned switches the transformation off (840D sl Job Planning:
/// the axes are then moved as machine axes): the next point is the machine's position, noted at
/// TRAFOOF's line; a `TRAORI` before the point, or the axes back at 0°, leaves no note.
#[test]
fn trafoof_with_the_axes_turned_is_noted() {
    let m = caz_head();
    let (_, r) = read_all(
        "N10 TRAORI\nN20 G0 X0 Y0 Z0 A30 C45\nN30 TRAFOOF\nN40 G1 X10 F500\n",
        S,
        Some(&m),
    );
    let n = note(&r, "switches tool-centre-point control off");
    assert_eq!((n.kind, n.line), (NoteKind::Tcp, 3));
    assert!(
        n.text.starts_with("line 3: TRAFOOF switches")
            && n.text.contains("(C 45°, A 30°)")
            && n.text.contains("line 4 moves"),
        "{}",
        n.text
    );
    for text in [
        "N10 TRAORI\nN20 G0 X0 Y0 Z0 A30 C45\nN30 TRAFOOF\nN40 TRAORI\nN50 G1 X10 F500\n",
        "N10 TRAORI\nN20 G0 X0 Y0 Z0 A30 C45\nN30 TRAFOOF\nN40 G0 A0 C0\nN50 G1 X10 F500\n",
    ] {
        let (_, r) = read_all(text, S, Some(&m));
        assert!(
            r.notes.iter().all(|n| n.kind != NoteKind::Tcp),
            "{text:?}: {:?}",
            r.notes
        );
    }
}

#[test]
fn variables_defined_as_plain_numbers_are_read_and_expressions_are_refused() {
    let m = caz_head();
    let text = "DEF REAL DEPTH=-5, SAFE=50\nR1=10\nG0 X=R1 Y=-R1 Z=SAFE\nG1 Z=DEPTH\n";
    let (p, _) = read_all(text, S, Some(&m));
    assert_eq!(p[0].tip, Vector3::new(10.0, -10.0, 50.0));
    assert_eq!(p[1].tip, Vector3::new(10.0, -10.0, -5.0));
    at(
        &error("R1=10\nG0 X0 Y0 Z=R1+5\n", S, Some(&m)),
        2,
        12,
        "\"R1+5\" is an expression",
    );
    at(
        &error("R1=10\nR2=R1*2\nG0 X=R2\n", S, Some(&m)),
        3,
        6,
        "computed on line 2",
    );
    at(
        &error("G0 X0 Y0 Z=_Z_HOME\n", S, Some(&m)),
        1,
        12,
        "uses \"_Z_HOME\", which the file does not define",
    );
    at(
        &error("G0 Y=130+45+85+10\n", S, Some(&m)),
        1,
        6,
        "is an expression",
    );
}

#[test]
fn trans_and_atrans_shift_as_the_manual_s_example_says() {
    let m = caz_head();
    // TRANS X10 Y10 Z10, then ATRANS X5 Y5: the offset is X15 Y15 Z10.
    let text = "TRANS X10 Y10 Z10\nATRANS X5 Y5\nG0 X0 Y0 Z0\nTRANS\nG0 X1\n";
    let (p, r) = read_all(text, S, Some(&m));
    assert_eq!(p[0].tip, Vector3::new(15.0, 15.0, 10.0));
    // TRANS alone clears the programmable frame.
    assert_eq!(p[1].tip, Vector3::new(1.0, 0.0, 0.0));
    assert_eq!(note(&r, "programmable frame").kind, NoteKind::Frame);
}

#[test]
fn rot_turns_about_z_then_the_new_y_then_the_new_x() {
    let m = caz_head();
    // ROT Z90: (10, 0, 0) → (0, 10, 0).
    let (p, _) = read_all("ROT Z90\nG0 X10 Y0 Z0\n", S, Some(&m));
    close_vec(&p[0].tip, &Vector3::new(0.0, 10.0, 0.0), 1e-12, "ROT Z90");
    // ROT X90 Z90: R = R_Z(90°)·R_Y(0)·R_X(90°). (0, 0, 1) → R_X(90°): (0, −1, 0) → R_Z(90°):
    // (1, 0, 0). (X first about the fixed axes would give R_X(90°)·R_Z(90°)·(0, 0, 1) = (0, −1,
    // 0).)
    let (p, _) = read_all("ROT X90 Z90\nG0 X0 Y0 Z1\n", S, Some(&m));
    close_vec(
        &p[0].tip,
        &Vector3::new(1.0, 0.0, 0.0),
        1e-12,
        "ROT X90 Z90",
    );
    // AROT RPL=90 (G17: about Z) after TRANS X100: the shift stays, the turn is added in it:
    // (10, 0) → (0, 10) → (100, 10).
    let (p, _) = read_all("G17\nTRANS X100\nAROT RPL=90\nG0 X10 Y0 Z0\n", S, Some(&m));
    close_vec(
        &p[0].tip,
        &Vector3::new(100.0, 10.0, 0.0),
        1e-12,
        "AROT RPL",
    );
    at(
        &error("SCALE X2 Y2\n", S, Some(&m)),
        1,
        1,
        "scales or mirrors",
    );
}

#[test]
fn g70_is_inches_and_a3_b3_c3_give_the_tool_vector() {
    let m = caz_head();
    let (p, r) = read_all("G70\nG0 X1 Y0 Z0\n", S, Some(&m));
    assert_eq!(p[0].tip, Vector3::new(25.4, 0.0, 0.0));
    assert_eq!(r.unit_reason, "inches: G70 on line 1");
    // A3 B3 C3: the direction only counts.
    let (p, _) = read_all(
        "TRAORI\nG1 X0 Y0 Z0 A3=0 B3=0 C3=2\nX1 A3=1 C3=1\n",
        S,
        Some(&m),
    );
    close_vec(&p[0].axis, &Vector3::z(), 1e-15, "C3");
    let s = 0.5f64.sqrt();
    close_vec(&p[1].axis, &Vector3::new(s, 0.0, s), 1e-15, "A3 C3");
    assert_eq!(p[1].angles, None);
    // A block of a tool vector alone turns the tool about its tip: a point where it was.
    // Found by cargo-mutants: `Block::moves` with `vector && sweep` survived.
    let (p, _) = read_all(
        "TRAORI\nG1 X1 Y2 Z3 A3=0 B3=0 C3=1 F100\nA3=0 B3=0.6 C3=0.8\n",
        S,
        Some(&m),
    );
    assert_eq!(p.len(), 2);
    assert_eq!((p[1].line, p[1].tip), (3, Vector3::new(1.0, 2.0, 3.0)));
    close_vec(&p[1].axis, &Vector3::new(0.0, 0.6, 0.8), 1e-15, "B3 C3");
}

// Found by cargo-mutants: every operator of `Way::reach`'s positive and negative turns survived
// (no test had written ACP or ACN).
/// `ACP(a)` and `ACN(a)` go to the position `a` (modulo 360°) turning positively or negatively
/// from where the axis is (840D sl Programming Manual, "Absolute dimensions for rotary axes (DC,
/// ACP, ACN)"); already there, the axis stays. Each angle below is counted by hand along the
/// turn: from 350°, +20° to 10° is 370°; from 370°, 10° is already reached; +340° to 350° is
/// 710°; +20° to 10° is 730°. From 10°, −20° to 350° is −10°; there already; −340° to 10° is
/// −350°; −20° to 350° is −370°; then ACP(100): +110° is −260°.
#[test]
fn acp_and_acn_turn_positively_and_negatively_to_the_position() {
    let m = caz_head();
    let c_of = |blocks: &str| {
        let text = format!("N10 TRAORI\n{blocks}");
        let (p, _) = read_all(&text, S, Some(&m));
        p.iter().map(|q| q.angles.unwrap()[0]).collect::<Vec<_>>()
    };
    assert_eq!(
        c_of(
            "N20 G0 X0 Y0 Z0 A0 C350\nN30 C=ACP(10)\nN40 C=ACP(10)\nN50 C=ACP(350)\nN60 \
             C=ACP(10)\n"
        ),
        [350.0, 370.0, 370.0, 710.0, 730.0]
    );
    assert_eq!(
        c_of(
            "N20 G0 X0 Y0 Z0 A0 C10\nN30 C=ACN(350)\nN40 C=ACN(350)\nN50 C=ACN(10)\nN60 \
             C=ACN(350)\nN70 C=ACP(100)\n"
        ),
        [10.0, -10.0, -10.0, -350.0, -370.0, -260.0]
    );
}

#[test]
fn cr_and_absolute_centres_give_arcs() {
    let m = caz_head();
    // G2 from (0, 0) to (10, 0) with CR=5: the half circle about (5, 0), clockwise over the top.
    let (p, _) = read_all("G17 G0 X0 Y0 Z0\nG2 X10 Y0 CR=5\n", S, Some(&m));
    assert!(p[1..]
        .iter()
        .all(|q| ((q.tip - Vector3::new(5.0, 0.0, 0.0)).norm() - 5.0).abs() < 1e-9));
    assert!(p[1..]
        .iter()
        .all(|q| q.tip.y >= -1e-9 && q.motion == Motion::Arc));
    // I=AC(5) J=AC(0): the same centre, absolute.
    let (p, _) = read_all("G17 G0 X0 Y0 Z0\nG2 X10 Y0 I=AC(5) J=AC(0)\n", S, Some(&m));
    assert!(p[1..]
        .iter()
        .all(|q| ((q.tip - Vector3::new(5.0, 0.0, 0.0)).norm() - 5.0).abs() < 1e-9));
}

#[test]
fn supa_and_work_offsets_break_the_path_and_cycles_are_noted() {
    let m = caz_head();
    let (p, r) = read_all(
        "G54\nG0 X0 Y0 Z10\nSUPA G0 Z0\nG0 X5 Z5\nG55\nG1 X6\n",
        S,
        Some(&m),
    );
    assert_eq!(
        p.iter().map(|q| (q.line, q.motion)).collect::<Vec<_>>(),
        [(2, Motion::Rapid), (4, Motion::Rapid), (6, Motion::Rapid)]
    );
    assert_eq!(note(&r, "machine coordinates").line, 3);
    assert_eq!(note(&r, "another work offset").line, 5);
    let (_, r) = read_all(
        "G0 X0 Y0 Z10\nMCALL CYCLE81(10,0,2,-5)\nX5\nMCALL\n",
        S,
        Some(&m),
    );
    assert_eq!(note(&r, "drilling cycle CYCLE81").kind, NoteKind::Partial);
    // G4 F2: F is the dwell's time.
    let (p, r) = read_all("G0 X0 Y0 Z0\nG4 F2\nG1 X1\n", S, Some(&m));
    assert_eq!(p.len(), 2);
    assert_eq!(skipped(&r, "dwells"), 1);
}

#[test]
fn cycle800_resets_are_read_and_swivels_refused() {
    let m = caz_head();
    let (p, r) = read_all(
        "CYCLE800(0,\"TC1\",200000,57,0,0,0,0,0,0,0,0,0,1,100,1)\nG0 X0 Y0 Z0\n",
        S,
        Some(&m),
    );
    assert_eq!(p.len(), 1);
    assert_eq!(skipped(&r, "swivel resets"), 1);
    at(
        &error(
            "CYCLE800(1,\"TC1\",0,57,0,0,0,0,30,0,0,0,0,1)\n",
            S,
            Some(&m),
        ),
        1,
        1,
        "CYCLE800 swivels the working plane",
    );
}

#[test]
fn program_flow_calls_and_other_forms_are_refused() {
    let m = caz_head();
    for (text, column, part) in [
        ("IF R1>0 GOTOF END\n", 1, "program flow"),
        ("N10 GOTOB START\n", 5, "program flow"),
        ("L100\n", 1, "calls subprogram L100"),
        ("N12 L140(2)\n", 5, "calls a subprogram"),
        ("CALL \"PART2\"\n", 1, "calls a subprogram"),
        ("PROC PART(REAL A)\n", 1, "PROC starts a subprogram"),
        ("G0 X0 Y0 Z0\nCIP X10 Y10 I1=5 J1=5\n", 1, "CIP"),
        ("G0 AP=90 RP=10\n", 4, "polar coordinates"),
        ("TRAORI\nG1 A2=10 B2=20\n", 4, "orientation by angles"),
        ("G0 X0 Y0 Z0 B10\n", 13, "got B"),
    ] {
        let line = if text.starts_with("G0 X0 Y0 Z0\n") || text.starts_with("TRAORI\n") {
            2
        } else {
            1
        };
        at(&error(text, S, Some(&m)), line, column, part);
    }
}

/// `G74 X1=0 Z1=0` (reference point approach) and `G75 FP=2 X=0 Y=0 Z=0` (fixed point
/// approach: "the programmed position values … are ignored, but must still be written"; the
/// axes go to a point stored in machine data, MD30600) take the named axes where the file does
/// not say: the path breaks, and the moves after them start from unknown positions. `G0` in a
/// block with `SUPA` stays in force after it (modal group 1).
#[test]
fn g74_g75_break_the_path_and_g0_with_supa_stays_modal() {
    let m = caz_head();
    let text = "G71 G90\nG0 X0 Y0 Z10\nG1 Z0 F500\nX10\nG74 Z1=0\nG0 X50 Y50\nG1 Z-1\nG75 FP=2 X=0 Y=0 Z=0\nG1 X0\n";
    let (p, r) = read_all(text, S, Some(&m));
    assert_eq!(note(&r, "G74/G75 take Z").kind, NoteKind::Break);
    // After G74 Z is unknown: G0 X50 Y50 gives no point; G1 Z-1 does, reached across the break.
    let lines: Vec<u32> = p.iter().map(|q| q.line).collect();
    assert_eq!(lines, [2, 3, 4, 7]);
    assert_eq!(p[3].motion, Motion::Rapid);
    assert_eq!(skipped(&r, "variable"), 0, "X1= is not a variable");
    // G0 SUPA Z0 D0 then modal moves: rapids.
    let text = "G71 G90\nG1 X0 Y0 Z10 F500\nG1 Z0\nG0 SUPA Z0 D0\nX50 Y50\nZ5\nZ1\n";
    let (p, _) = read_all(text, S, Some(&m));
    assert_eq!(
        p.last().map(|q| (q.tip.z, q.motion)),
        Some((1.0, Motion::Rapid))
    );
}

/// `DEF` after a block number (posts number every block), and a call not closed on its line is
/// an error with its place, not a crash (a non-ASCII character at the end of it).
#[test]
fn def_after_a_block_number_and_an_unclosed_call() {
    let m = caz_head();
    let (p, _) = read_all(
        "N10 DEF REAL DEPTH=5\nN20 G71 G90 G0 X0 Y0 Z=DEPTH\n",
        S,
        Some(&m),
    );
    assert_eq!(p[0].tip, Vector3::new(0.0, 0.0, 5.0));
    // After a label or a skip mark, and names without values (0 until assigned), as NX's
    // posts write them (`DEF REAL _X_HOME, _Y_HOME`).
    let (p, _) = read_all(
        "START: DEF REAL DEPTH=5\n/N20 DEF REAL _X_HOME, _Y_HOME\nG71 G90 G0 X=_X_HOME Y=_Y_HOME Z=DEPTH\n",
        S,
        Some(&m),
    );
    assert_eq!(p[0].tip, Vector3::new(0.0, 0.0, 5.0));
    at(
        &error("G71\nMSG(\"Fräsen Ø\n", S, Some(&m)),
        2,
        1,
        "MSG( is not closed",
    );
    at(
        &error("CYCLE81(10,0,2,-5,Ø\n", S, Some(&m)),
        1,
        1,
        "CYCLE81( is not closed",
    );
}

/// A frame set in inches stays where it is when the program switches to millimetres: TRANS X1
/// (25.4 mm), then G71 and ATRANS Y10: the origin is (25.4, 10, 0) mm.
#[test]
fn a_frame_stays_where_it_is_when_the_unit_changes() {
    let m = caz_head();
    let (p, r) = read_all(
        "G70 G90\nTRANS X1\nG71\nATRANS Y10\nG0 X0 Y0 Z0\n",
        S,
        Some(&m),
    );
    close_vec(&p[0].tip, &Vector3::new(25.4, 10.0, 0.0), 1e-9, "origin");
    assert!(note(&r, "TRANS sets the programmable frame")
        .text
        .contains("origin (25.4, 0, 0) mm"));
}

/// Addresses with decimal numbers, as posts write them and as the manual's examples run them
/// together (`G1X-5.5`): a sign, digits and one decimal point, with the digits before or after the
/// point left out (`Y.25`, `Z+1.`). A second point ends the number, and the reader refuses what
/// follows it where it stands (column 8 of `G1 X1.2.3`) rather than guessing 1.2 or 1.23.
/// (From the mutants of `lex::number_len`: without these decimals every Siemens test read whole
/// numbers only.)
#[test]
fn decimal_numbers_with_a_sign_and_one_point() {
    let m = caz_head();
    let (p, _) = read_all("G1X-5.5Y.25Z+1. A-.5 C12.125 F1000\n", S, Some(&m));
    assert_eq!(p.len(), 1);
    assert_eq!(p[0].tip, Vector3::new(-5.5, 0.25, 1.0));
    assert_eq!(p[0].angles, Some([12.125, -0.5]));
    at(&error("G1 X1.2.3\n", S, Some(&m)), 1, 8, "got \".\"");
}

// Found by cargo-mutants: the comment rule of `siemens::is_statement` (its depth and its count
// of a name's leading letters) survived: no test decided a file by a call's parentheses.
/// Detection: an ISO comment `( … )` decides nothing, nested or not, and what follows its `)`
/// does; a `(` after a name of two or more letters (`MSG(`, `CYCLE800(`, `IC(`) is a Sinumerik
/// call, not a comment, and `MSG(` alone makes a file Sinumerik; so do `DEF REAL`/`DEF INT`, a
/// keyword as a whole word and an address followed by `=`.
#[test]
fn detection_reads_iso_comments_apart_from_sinumerik_calls() {
    let cases = [
        // A comment after a block number holds a Sinumerik keyword: still ISO.
        ("N1(CYCLE800 TRAORI)\nG1 X1\n", Format::Nc),
        // Nested parentheses: the keyword after the inner `)` is still in the comment.
        ("N1(SEE(1) TRAORI)\nG1 X1\n", Format::Nc),
        ("N1(X(1) TRAORI)\nG1 X1\n", Format::Nc),
        // After the comment's `)`, the keyword is code.
        ("N1 (NOTE) TRAORI\nG1 X1\n", Format::Siemens),
        ("N1 (A(B)) TRAORI\nG1 X1\n", Format::Siemens),
        // Sinumerik's message call, alone.
        ("N20 MSG(\"ROUGHING\")\nG1 X1\n", Format::Siemens),
        ("MSG(\"A\")\n", Format::Siemens),
        // A two-letter function's argument is code: `R1=` inside `IC(…)` decides.
        ("G1 Y IC(R1=5)\n", Format::Siemens),
        // MSG with a space before its `(` (which alone would open an ISO comment).
        ("N20 MSG (\"A\")\n", Format::Siemens),
        // Variable definitions, each alone.
        ("DEF REAL R_1\n", Format::Siemens),
        ("N5 DEF INT COUNT\n", Format::Siemens),
        // A keyword is a whole word, wherever it stands; `_` joins a word.
        ("N30 TRAORI\n", Format::Siemens),
        ("N30 G1 X1 MY_TRAORI\n", Format::Nc),
        // An address with `=`: before a sign, after a space.
        ("G1 X=-5\n", Format::Siemens),
        ("G1 X =5\n", Format::Siemens),
        // A line that starts with `=` names no address (and does not stop detection), first or
        // after an ISO line.
        ("=5\nG1 X1\n", Format::Nc),
        ("G1 X1\n=5\n", Format::Nc),
        // Fanuc macro B assignments are ISO: `#100=` and `#[#100] =` name no address.
        ("N10 #100=5\nG1 X1\n", Format::Nc),
        ("N10 #[#100] = 5\nG1 X1\n", Format::Nc),
        // A `)` that closes nothing is kept: what follows it is code.
        ("G1 X1 ) TRAORI\n", Format::Siemens),
    ];
    for (text, format) in cases {
        assert_eq!(Format::detect(text), format, "{text:?}");
    }
}

// Found by cargo-mutants: in `Siemens::line`, the block count (`+=` as `-=`, `*=`), the block's
// `at`, and the arms of TURN, AR and F S T D deleted survived.
/// A block's count, its error column, TURN's extra full circles, AR refused, and feeds given
/// as `F=`/`S=` skipped as feeds.
#[test]
fn block_count_arc_column_turn_ar_and_feeds_by_assignment() {
    let m = caz_head();
    // Blocks: the move, the DEF, the move, M30 (the comment and the blank line are none).
    let text =
        "N10 G0 X0 Y0 Z0\nN20 DEF REAL R_A=5\n; a comment\n\nN30 G1 X5 F=1000 S=2000\nN40 M30\n";
    let (_, r) = read_all(text, S, Some(&m));
    assert_eq!(r.blocks, 4);
    // One skip per word: F= and S=.
    assert_eq!(skipped(&r, "feeds, speeds and tools"), 2);
    // The arc's error is at its first word, after three blanks: column 4. From (10, 0) about
    // (0, 0) to (0, 20): 10 mm from the centre at the start, 20 at the end.
    let e = error(
        "G17 G0 X10 Y0 Z0\n   G2 X0 Y20 I=AC(0) J=AC(0)\n",
        S,
        Some(&m),
    );
    at(&e, 2, 4, "the arc's end is not on its circle");
    // TURN=1: one full circle more than the arc from (10, 0) back to (10, 0), so two turns of
    // radius 10: 4π·10 ≈ 125.66 mm of chords (each a little shorter than its arc).
    let (p, _) = read_all("G17 G0 X10 Y0 Z0\nG3 X10 Y0 I-10 J0 TURN=1\n", S, Some(&m));
    let length: f64 = p.windows(2).map(|w| (w[1].tip - w[0].tip).norm()).sum();
    assert!(
        length > 125.0 && length < 4.0 * std::f64::consts::PI * 10.0,
        "{length}"
    );
    let e = error("G17 G0 X10 Y0 Z0\nG3 X0 Y10 AR=90\n", S, Some(&m));
    at(&e, 2, 11, "AR= gives an arc by its opening angle");
}

// Found by cargo-mutants: the arms of RET and of program flow among a block's words deleted
// survived.
/// RET (a subprogram's end) ends the reading; a flow keyword after other words of its block is
/// refused as program flow, at its column.
#[test]
fn ret_ends_the_program_and_flow_after_other_words_is_refused() {
    let m = caz_head();
    let (p, _) = read_all("G0 X0 Y0 Z0\nRET\nG0 X5 Y0 Z0\n", S, Some(&m));
    assert_eq!(p.len(), 1, "{p:?}");
    let e = error("G0 X0 Y0 Z0 GOTOF END\nEND:\n", S, Some(&m));
    at(&e, 1, 13, "GOTOF is program flow");
}

// Found by cargo-mutants: the G-code arms of `Siemens::word` (G17 G18 G19, G90 G91, G53 G153,
// G41 G42, G110–G112), the work offset's `&&`, `any_point`'s `>`, and the refusing arms of
// words after the first (CIP, CT, PCALL, PROC) deleted survived.
/// The G codes that set the plane, the distance mode and machine coordinates; radius
/// compensation noted; polar poles refused; a work offset breaks the path only when it
/// changes after a point; CIP, CT, a call and PROC refused with their own reasons.
#[test]
fn plane_distance_machine_offset_and_refused_words() {
    let m = caz_head();
    // A quarter circle of radius 10 about the origin in each plane, the plane switched back
    // and forth: every chord point has its third coordinate 0 and lies 10 from the origin.
    let text = "G0 X10 Y0 Z0\nG18 G3 X0 Z-10 I-10 K0\nG0 X0 Y10 Z0\nG19 G3 Y0 Z10 J-10 K0\n\
                G0 X10 Y0 Z0\nG17 G3 X0 Y10 I-10 J0\n";
    let (p, _) = read_all(text, S, Some(&m));
    for (lines, third) in [(2, 1), (4, 0), (6, 2)] {
        let arc: Vec<_> = p.iter().filter(|q| q.line == lines).collect();
        assert!(arc.len() > 2, "line {lines}: {p:?}");
        for q in arc {
            assert!(q.tip[third].abs() < 1e-9, "line {lines}: {:?}", q.tip);
            assert!(
                (q.tip.norm() - 10.0).abs() < 1e-9,
                "line {lines}: {:?}",
                q.tip
            );
        }
    }
    // G91 adds, G90 states.
    let (p, _) = read_all("G0 X1 Y0 Z0\nG91 G0 X5\nG90 G0 X5\n", S, Some(&m));
    let x: Vec<f64> = p.iter().map(|q| q.tip.x).collect();
    assert_eq!(x, [1.0, 6.0, 5.0]);
    // G53 and G153: the block moves in machine coordinates, not a point of the part.
    for g in ["G53", "G153"] {
        let text = format!("G0 X0 Y0 Z0\n{g} G0 Z100\nG0 X5 Y0 Z0\n");
        let (p, _) = read_all(&text, S, Some(&m));
        assert!(p.iter().all(|q| q.tip.z == 0.0), "{g}: {p:?}");
    }
    for g in ["G41", "G42"] {
        let (_, r) = read_all(&format!("G0 X0 Y0 Z0\n{g} G1 X5\n"), S, Some(&m));
        assert_eq!(note(&r, "radius compensation").line, 2, "{g}");
    }
    for g in ["G110", "G111", "G112"] {
        let e = error(&format!("G0 X0 Y0 Z0\n{g} X0 Y0\n"), S, Some(&m));
        assert!(e.contains("sets a pole for polar coordinates"), "{g}: {e}");
    }
    // A work offset: the first one before any point, the same one again, and the first one
    // after points break nothing; another one after a point breaks the path.
    for (text, breaks) in [
        ("G54\nG17 G90\nG55\nG0 X0 Y0 Z0\n", false),
        ("G0 X0 Y0 Z0\nG54\nG0 X5 Y0 Z0\n", false),
        ("G54 G0 X0 Y0 Z0\nG54 G0 X5 Y0 Z0\n", false),
        ("G54 G0 X0 Y0 Z0\nG55 G0 X5 Y0 Z0\n", true),
    ] {
        let (_, r) = read_all(text, S, Some(&m));
        let noted = r
            .notes
            .iter()
            .any(|n| n.text.contains("selects another work offset"));
        assert_eq!(noted, breaks, "{text:?}");
    }
    for (block, part) in [
        ("CIP X10 Y10 I1=5 J1=5", "through an intermediate point"),
        ("CT X10 Y10", "tangential arc"),
        ("G0 X0 PCALL SUB", "PCALL calls a subprogram"),
        ("G0 X0 CALL SUB", "CALL calls a subprogram"),
        ("G0 X0 EXTCALL SUB", "EXTCALL calls a subprogram"),
        ("G0 X0 PROC", "PROC starts a subprogram"),
    ] {
        let e = error(&format!("G0 X0 Y0 Z0\n{block}\n"), S, Some(&m));
        assert!(e.starts_with("line 2") && e.contains(part), "{block}: {e}");
    }
}

// Found by cargo-mutants: an error's column inside `IC(…)` (`+` as `*`) and a variable
// assigned another's plain value (its match arm deleted) survived.
/// A variable assigned the value of a variable that holds a plain number holds that number;
/// an undefined variable inside `IC(…)` is named at its own column.
#[test]
fn a_variable_copies_a_plain_value_and_an_error_inside_ic_names_its_column() {
    let m = caz_head();
    let (p, _) = read_all("R1=5\nR2=R1\nG0 X=R2 Y0 Z0\n", S, Some(&m));
    assert_eq!(p[0].tip, Vector3::new(5.0, 0.0, 0.0));
    // `G1 X=IC(R9)`: R9 starts at column 9.
    let e = error("G0 X0 Y0 Z0\nG1 X=IC(R9)\n", S, Some(&m));
    at(&e, 2, 9, "R9");
}

// Found by cargo-mutants: the centre's `AC` test (`==` as `!=`) survived, the arcs above all
// starting at the origin, where a centre relative to the start is the absolute centre.
/// A centre written plainly or with `IC(…)` is relative to the arc's start; with `AC(…)` it is
/// absolute (808D Programming Manual p.53). From (10, 0) to (20, 0) about (15, 0), each way.
#[test]
fn a_centre_is_relative_to_the_start_unless_written_ac() {
    let m = caz_head();
    for arc in [
        "G2 X20 Y0 I5 J0",
        "G2 X20 Y0 I=IC(5) J=IC(0)",
        "G2 X20 Y0 I=AC(15) J=AC(0)",
    ] {
        let (p, _) = read_all(&format!("G17 G0 X10 Y0 Z0\n{arc}\n"), S, Some(&m));
        assert!(p.len() > 2, "{arc}: {} points", p.len());
        for q in &p[1..] {
            let r = (q.tip - Vector3::new(15.0, 0.0, 0.0)).norm();
            assert!(
                (r - 5.0).abs() < 1e-9,
                "{arc}: {:?} is {r} from (15, 0)",
                q.tip
            );
        }
    }
}

// Found by cargo-mutants: the rotary-axis arm's `&&` (as `||`) survived: with it, a name of
// two letters inside "ABC" (`AB`) was read as the axis of its first letter.
/// A single letter A, B or C is a rotary axis; `AB=30` is a variable, and the axes stay.
#[test]
fn a_two_letter_name_is_a_variable_not_a_rotary_axis() {
    let m = caz_head();
    let (p, r) = read_all("G0 X0 Y0 Z0 A0 C0\nAB=30\nBC=45\nG1 X1 F100\n", S, Some(&m));
    assert_eq!(p.len(), 2);
    assert_eq!(p[1].axis, p[0].axis);
    assert_eq!(p[1].angles, p[0].angles);
    assert_eq!(skipped(&r, "variable assignments"), 2);
}

// Found by cargo-mutants: `TRAORI(…)` written as a call (its match arm deleted) and the
// machining-cycle guard (made false, or one of its `||` as `&&`), the drilling cycle's length
// test (`&&` as `||`, `==` as `!=`) survived.
/// `TRAORI(1)` (the transformation's number, Programming Manual p.666) switches on
/// tool-centre-point control as `TRAORI` does. A drilling cycle (`CYCLE8…`, `CYCLE7n`) and a
/// machining cycle (`CYCLE…`, `POCKET…`, `SLOT…`, `LONGHOLE`, `HOLES…`) called directly are each
/// noted by their kind; a name of 7 letters is not a drilling cycle for its length.
#[test]
fn traori_with_a_number_and_cycles_noted_by_kind() {
    let m = caz_head();
    let (_, r) = read_all(
        "N10 TRAORI(1)\nN20 G1 X0 Y0 Z0 A3=0 B3=0 C3=1 F100\n",
        S,
        Some(&m),
    );
    assert_eq!(r.tcp.as_deref(), Some("TRAORI on line 1"));
    for (cycle, kind) in [
        ("CYCLE81", "drilling cycle"),
        ("CYCLE78", "drilling cycle"),
        ("CYCLE840", "drilling cycle"),
        ("CYCLE61", "machining cycle"),
        ("CYCLE7", "machining cycle"),
        ("POCKET3", "machining cycle"),
        ("SLOT1", "machining cycle"),
        ("LONGHOLE", "machining cycle"),
        ("HOLES1", "machining cycle"),
    ] {
        let (_, r) = read_all(
            &format!("G0 X0 Y0 Z10\n{cycle}(10,0,2,-5)\nG0 X5\n"),
            S,
            Some(&m),
        );
        let n = note(&r, &format!("cycle {cycle}:"));
        assert!(n.text.contains(kind), "{cycle}: {}", n.text);
        assert_eq!((n.line, n.kind), (2, NoteKind::Partial), "{cycle}");
    }
}

// Found by cargo-mutants: `RPL`'s test (`&&` as `||`) survived: with it, every assignment in
// a frame statement was taken as the plane's rotation.
/// A frame's axis words may be written as assignments (`TRANS X=10 Y=5`, the address form
/// `X=…` of any axis word): the shift is (10, 5, 0).
#[test]
fn frame_words_written_as_assignments_shift() {
    let m = caz_head();
    let (p, _) = read_all("TRANS X=10 Y=5\nG0 X0 Y0 Z0\n", S, Some(&m));
    assert_eq!(p[0].tip, Vector3::new(10.0, 5.0, 0.0));
}

// Found by cargo-mutants: the arm of `MCALL(…)` as a call deleted survived; it accepted a form
// Sinumerik does not have and set a state nothing read. Now `MCALL` (before a cycle, or alone
// to end the modal call) is counted, and `RPL=` outside ROT/AROT is refused (it was read as a
// variable).
/// `MCALL CYCLE81(…)` … `MCALL` (Programming Manual, "MCALL: modal subprogram call"): the
/// cycle is noted and both MCALLs are counted; `MCALL(1)` is a call the reader does not know;
/// `RPL=30` without ROT or AROT is refused at its column, `ROT RPL=90` turns the plane.
#[test]
fn mcall_is_counted_and_rpl_needs_rot() {
    let m = caz_head();
    let (p, r) = read_all(
        "G0 X0 Y0 Z10\nMCALL CYCLE81(10,0,2,-5)\nX5\nMCALL\n",
        S,
        Some(&m),
    );
    assert_eq!(p.len(), 2);
    assert_eq!(skipped(&r, "modal cycle calls (MCALL)"), 2);
    assert_eq!(note(&r, "drilling cycle CYCLE81").line, 2);
    let e = error("G0 X0 Y0 Z0\nMCALL(1)\n", S, Some(&m));
    assert!(
        e.starts_with("line 2") && e.contains("MCALL(…) calls a subprogram"),
        "{e}"
    );
    let e = error("G0 X0 Y0 Z0\nG1 X1 RPL=30\n", S, Some(&m));
    at(&e, 2, 7, "RPL= turns the plane in a ROT or AROT statement");
    let (p, _) = read_all("ROT RPL=90\nG0 X10 Y0 Z0\n", S, Some(&m));
    close_vec(
        &p[0].tip,
        &Vector3::new(0.0, 10.0, 0.0),
        1e-12,
        "ROT RPL=90",
    );
}

// Found by cargo-mutants: the end of the blanks after a block number or a skip mark (`<` as
// `<=`) and the lexer's step past the skip mark (`+=` as `-=` or `*=`) survived: no test had a
// line that ends there or a skip-marked block.
/// A line holding only a block number (`N20`) or only a skip mark (`/`) is a block without
/// words: the moves around it are read.
#[test]
fn a_block_number_or_skip_mark_alone() {
    let m = caz_head();
    for line in ["N20", "/", "N20 ", "/N20"] {
        let (p, _) = read_all(&format!("G0 X0 Y0 Z0\n{line}\nG1 X1 F100\n"), S, Some(&m));
        assert_eq!(p.len(), 2, "{line:?}");
    }
    // A skip-marked block is read, as if the skip level were off (as the other readers do).
    let (p, _) = read_all("G0 X0 Y0 Z0\n/G1 X1 F100\n/ N30 X2\n", S, Some(&m));
    assert_eq!(
        p.iter().map(|q| (q.line, q.tip.x)).collect::<Vec<_>>(),
        [(1, 0.0), (2, 1.0), (3, 2.0)]
    );
}

// Found by cargo-mutants: the block number's test (`&&` as `||`: any letter and a digit taken
// for a block number) and the label's non-empty name (`>` as `>=`) survived.
/// `DEF` starts its block, after a block number or a label (`N10 DEF …`, `MARKE1: DEF …`); after
/// a word (`G1 DEF …`), or after a `:` without a label's name, it is no definition and is
/// refused at its column.
#[test]
fn def_only_at_the_start_of_its_block() {
    let m = caz_head();
    for text in [
        "N10 DEF REAL A=5\nG0 X=A Y0 Z0\n",
        "MARKE1: DEF REAL A=5\nG0 X=A Y0 Z0\n",
    ] {
        let (p, _) = read_all(text, S, Some(&m));
        assert_eq!(p[0].tip, Vector3::new(5.0, 0.0, 0.0), "{text:?}");
    }
    at(
        &error("G0 X0 Y0 Z0\nG1 DEF REAL A\n", S, Some(&m)),
        2,
        4,
        "DEF",
    );
    at(
        &error("G0 X0 Y0 Z0\nN10 : DEF REAL A\n", S, Some(&m)),
        2,
        7,
        "DEF",
    );
}

/// The points of a program as (line, tip).
fn tips(text: &str) -> Vec<(u32, [f64; 3])> {
    let m = caz_head();
    let (p, _) = read_all(text, S, Some(&m));
    p.iter().map(|q| (q.line, q.tip.into())).collect()
}

/// An assignment's value runs to a blank outside brackets and quotes, or to a `;` outside
/// quotes (Programming Manual 12/2019 p.52: `"` marks a character string, `;` starts a
/// comment, a blank separates): blanks after `=` and inside `IC( 2)` belong to it, a `(` or `;`
/// inside a string does not end or open anything, and the words after the value are read.
/// `X= 5` is X 5; `Y=IC( 2)` is 0 + 2.
#[test]
fn an_assignment_value_with_blanks_brackets_quotes_and_a_comment() {
    // Found by cargo-mutants: the blank skip after `=`, the depth of ( and [, and the `"` and
    // `;` guards in lex were not tested.
    let text = "N05 DEF STRING[10] TXT\n\
                N10 G0 X0 Y0 Z0\n\
                N20 G1 X= 5 Y=IC( 2) Z=3;no blank before the comment\n\
                N30 TXT=\"a(\" Y5\n\
                N40 TXT=\"a;b\" X7\n\
                N50 TXT=SPRINT(\"R1 = %F)\", R1) Z9\n";
    assert_eq!(
        tips(text),
        [
            (2, [0.0, 0.0, 0.0]),
            (3, [5.0, 2.0, 3.0]),
            (4, [5.0, 5.0, 3.0]),
            (5, [7.0, 5.0, 3.0]),
            (6, [7.0, 5.0, 9.0]),
        ]
    );
}

/// `X=` with nothing after it, and `X==5` (`==` compares, in an `IF`; it assigns nothing), are
/// refused at their columns.
#[test]
fn an_empty_assignment_and_a_comparison_are_refused() {
    // Found by cargo-mutants: the end of the line after `=` and the `==` test in lex were not
    // tested.
    let m = caz_head();
    for (text, column, part) in [
        ("G1 X=\n", 4, "X= has no value"),
        ("G1 X= ;c\n", 4, "X= has no value"),
        ("G1 X==5\n", 5, "expected a word"),
    ] {
        at(&error(text, S, Some(&m)), 1, column, part);
    }
}

/// A call's arguments run to its own closing parenthesis: parentheses inside quotes do not
/// count, nested ones do, and the words after it are read (`MSG("x") G1 X5`). A `CYCLE800` of
/// 13 arguments (the trailing ones left out) with every offset and angle 0 is a reset.
#[test]
fn a_call_ends_at_its_own_parenthesis() {
    // Found by cargo-mutants: the depth and quote tests in a call's arguments, and the
    // argument slice, were not tested.
    let m = caz_head();
    let text = "N10 G0 X0 Y0 Z0\n\
                N20 MSG(\"a)b\")\n\
                N30 MSG(\"(\")\n\
                N40 MSG(\"Z \"<<(R1+2))\n\
                N50 MSG(\"x\") G1 X5\n\
                N60 CYCLE800(1,\"TC1\",0,57,0,0,0,0,0,0,0,0,0)\n";
    let (p, r) = read_all(text, S, Some(&m));
    let got: Vec<_> = p.iter().map(|q| (q.line, q.tip)).collect();
    assert_eq!(
        got,
        [(1, Vector3::zeros()), (5, Vector3::new(5.0, 0.0, 0.0))]
    );
    assert_eq!(skipped(&r, "messages"), 4);
    assert_eq!(skipped(&r, "swivel resets"), 1);
}

/// An address letter alone takes the number after it, blanks between or not (Programming
/// Manual 12/2019 p.44: the sign stands between the address and the digits); a letter with
/// no number after it is refused as such, at its column.
#[test]
fn an_address_and_its_number_with_blanks_between() {
    // Found by cargo-mutants: an address followed by a blank and its number (at the start of
    // a block, too) was not tested.
    assert_eq!(
        tips("X 10 Y  20 Z -5\nG1 X .5\n"),
        [(1, [10.0, 20.0, -5.0]), (2, [0.5, 20.0, -5.0])]
    );
    let m = caz_head();
    for (text, part) in [
        ("G1 X Y10\n", "X has no number: expected a number after X"),
        (
            "G1 TRAORX Y10\n",
            "\"TRAORX\" is not a word the reader knows",
        ),
    ] {
        at(&error(text, S, Some(&m)), 1, 4, part);
    }
}
