//! The Heidenhain conversational reader (`fiveaxis::toolpath::read::heidenhain`), construct by
//! construct, on programs written from the HEIDENHAIN manuals: TNC 620 Conversational
//! Programming User's Manual 10/2017 (BEGIN PGM p.154; PLANE p.540; PLANE VECTOR p.548: "base
//! vector … normal vector"); iTNC 530 User's Manual 340 422 (CR p.239: "R+ … up to 180°";
//! PLANE SPATIAL pp.456–460: "first around the A axis, then B, and then C", all three angles
//! required; FUNCTION TCPM p.457); iTNC 530 DIN/ISO (M128 p.290); TNC 620 DIN/ISO (PLANE EULER:
//! precession about Z, nutation about the new X, rotation about the new Z, p.322); TNC 410
//! (C with DR+ counter-clockwise, DR− clockwise, p.79); TNC 426/430 (CP IPA with IZ, p.153);
//! TNC 320 (L p.128). Expected points are computed by hand in the comments.

#![allow(clippy::unwrap_used)]
use crate::common;

use common::toolpath::{
    at, caz, caz_head, chords, close_vec, error, heidenhain_program as program, note, read_all,
    skipped,
};
use fiveaxis::toolpath::read::{Format, LengthUnit, Motion, NoteKind};
use nalgebra::Vector3;
use std::f64::consts::{FRAC_PI_2, PI};

const H: Format = Format::Heidenhain;

#[test]
fn l_blocks_with_fmax_f_incremental_and_signed_words() {
    let m = caz_head();
    let text = program(&[
        "BLK FORM 0.1 Z X+0 Y+0 Z-20",
        "BLK FORM 0.2 X+100 Y+100 Z+0",
        "TOOL CALL 1 Z S5000",
        "L Z+100 R0 FMAX M3",
        "L X+10 Y-5 R0 FMAX",
        "L Z-2 R0 F200",
        "L IX+20 R0",
        "L X+30 Y-5 Z+5 A+30 C+90 R0 F MAX",
        "L Z+10 ; a comment",
    ]);
    let (p, r) = read_all(&text, H, Some(&m));
    assert_eq!(r.format, Format::Heidenhain);
    assert_eq!(
        (r.unit, r.unit_reason.as_str()),
        (LengthUnit::Mm, "millimetres: BEGIN PGM … MM on line 1")
    );
    // Line 5 leaves X and Y unknown (no point); FMAX this block only; F MAX with a space.
    let expected = [
        (6, [10.0, -5.0, 100.0], [0.0, 0.0], Motion::Rapid),
        (7, [10.0, -5.0, -2.0], [0.0, 0.0], Motion::Feed),
        (8, [30.0, -5.0, -2.0], [0.0, 0.0], Motion::Feed),
        (9, [30.0, -5.0, 5.0], [90.0, 30.0], Motion::Rapid),
        (10, [30.0, -5.0, 10.0], [90.0, 30.0], Motion::Feed),
    ];
    assert_eq!(p.len(), expected.len(), "{p:?}");
    for (q, (line, tip, angles, motion)) in p.iter().zip(expected) {
        assert_eq!((q.line, q.motion), (line, motion));
        assert_eq!(q.tip, Vector3::from(tip));
        assert_eq!(q.angles, Some(angles));
        close_vec(&q.axis, &caz(angles[0], angles[1]), 1e-15, "axis");
    }
    assert_eq!(skipped(&r, "BLK FORM"), 2);
    assert_eq!(skipped(&r, "TOOL CALL"), 1);
    let (p, r) = read_all(
        "0 BEGIN PGM T INCH\n1 L X+1 Y+0 Z+0 R0 FMAX\n2 END PGM T INCH\n",
        H,
        Some(&m),
    );
    assert_eq!(p[0].tip, Vector3::new(25.4, 0.0, 0.0));
    assert_eq!(r.unit_reason, "inches: BEGIN PGM … INCH on line 1");
}

#[test]
fn c_arcs_turn_about_the_pole_dr_plus_counter_clockwise() {
    let m = caz_head();
    let text = program(&[
        "CC X+0 Y+0",
        "L X+10 Y+0 Z+0 R0 F100",
        "C X+0 Y+10 DR+",
        "C X+10 Y+0 DR-",
        "C X+10 Y+0 DR+",
    ]);
    let (p, r) = read_all(&text, H, Some(&m));
    let quarter = chords(10.0, FRAC_PI_2, 0.001);
    let whole = chords(10.0, 2.0 * PI, 0.001);
    assert_eq!(r.arc_points, 2 * quarter + whole);
    assert!(p[1..]
        .iter()
        .all(|q| (q.tip.norm() - 10.0).abs() < 1e-9 && q.motion == Motion::Arc));
    // DR+ from (10, 0) to (0, 10): the first quadrant; DR− back the same way.
    let first = &p[1..1 + 2 * quarter];
    assert!(first.iter().all(|q| q.tip.x > -1e-9 && q.tip.y > -1e-9));
    // End = start: a whole turn, through (−10, 0) and (0, −10).
    let full = &p[1 + 2 * quarter..];
    assert!(full.iter().any(|q| q.tip.y < -9.99) && full.iter().any(|q| q.tip.x < -9.99));
}

#[test]
fn cr_ct_and_cp_arcs() {
    let m = caz_head();
    // CR from (0, 0) to (10, 0), R+5 DR−: the half circle about (5, 0), clockwise over the top.
    let (p, _) = read_all(
        &program(&["L X+0 Y+0 Z+0 R0 F100", "CR X+10 Y+0 R+5 DR-"]),
        H,
        Some(&m),
    );
    assert!(p[1..].iter().all(
        |q| ((q.tip - Vector3::new(5.0, 0.0, 0.0)).norm() - 5.0).abs() < 1e-9 && q.tip.y > -1e-9
    ));
    // CT after a move along +X from (0, 0) to (10, 0), to (20, 10): the centre lies on the left
    // normal at the start, (10, ρ), with ρ = |E − S|²/(2·n·(E − S)) = 200/20 = 10: (10, 10),
    // counter-clockwise; half way, at 45°, (10 + 10 sin 45°, 10 − 10 cos 45°) = (17.07, 2.93).
    let (p, _) = read_all(
        &program(&["L X+0 Y+0 Z+0 R0 F100", "L X+10", "CT X+20 Y+10"]),
        H,
        Some(&m),
    );
    assert!(p[2..]
        .iter()
        .all(|q| ((q.tip - Vector3::new(10.0, 10.0, 0.0)).norm() - 10.0).abs() < 1e-9));
    let s = 0.5f64.sqrt();
    assert!(p[2..]
        .iter()
        .any(|q| (q.tip - Vector3::new(10.0 + 10.0 * s, 10.0 - 10.0 * s, 0.0)).norm() < 0.2));
    // CP IPA+720 IZ−4 DR+ about CC (0, 0) from (5, 0, 0): two turns down to z = −4, each chord's
    // z in proportion to the angle turned: after one turn, back at (5, 0), z = −2.
    let (p, r) = read_all(
        &program(&["CC X+0 Y+0", "L X+5 Y+0 Z+0 R0 F100", "CP IPA+720 IZ-4 DR+"]),
        H,
        Some(&m),
    );
    assert_eq!(r.arc_points, chords(5.0, 4.0 * PI, 0.001));
    close_vec(
        &p[p.len() - 1].tip,
        &Vector3::new(5.0, 0.0, -4.0),
        1e-9,
        "CP end",
    );
    let half = p.len() / 2;
    assert!((p[half].tip.z + 2.0).abs() < 0.01, "{:?}", p[half].tip);
    // CC X Z: the pole's axes give the ZX plane; CP IPA+90 DR+ turns +X towards −Z (about +Y,
    // the polar angle counted from +Z towards +X): (10, 0, 0) → (0, 0, −10).
    let (p, _) = read_all(
        &program(&["CC X+0 Z+0", "L X+10 Y+0 Z+0 R0 F100", "CP IPA+90 DR+"]),
        H,
        Some(&m),
    );
    close_vec(
        &p[p.len() - 1].tip,
        &Vector3::new(0.0, 0.0, -10.0),
        1e-9,
        "CP in ZX",
    );
    at(
        &error(
            &program(&["L X+0 Y+0 Z+0 R0 F100", "C X+10 Y+0 DR+"]),
            H,
            Some(&m),
        ),
        3,
        3,
        "no CC comes before it",
    );
    at(
        &error(
            &program(&["CC X+0 Y+0", "L X+5 Y+0 Z+0 R0 F100", "C X+0 Y+5"]),
            H,
            Some(&m),
        ),
        4,
        3,
        "DR+ (counter-clockwise) or DR−",
    );
}

#[test]
fn datum_shift_and_rotation_cycles_move_the_points() {
    let m = caz_head();
    let text = program(&[
        "CYCL DEF 7.0 DATUM SHIFT",
        "CYCL DEF 7.1 X+100",
        "CYCL DEF 7.2 Y+50",
        "L X+10 Y+10 Z+0 R0 FMAX",
        "CYCL DEF 7.0 DATUM SHIFT",
        "CYCL DEF 7.1 IX+5",
        "L X+10 Y+10 Z+0 R0 FMAX",
        "CYCL DEF 7.0 DATUM SHIFT",
        "CYCL DEF 7.1 X+0",
        "CYCL DEF 7.2 Y+0",
        "CYCL DEF 10.0 ROTATION",
        "CYCL DEF 10.1 ROT+90",
        "L X+10 Y+0 Z+0 R0 FMAX",
    ]);
    let (p, r) = read_all(&text, H, Some(&m));
    assert_eq!(p[0].tip, Vector3::new(110.0, 60.0, 0.0));
    assert_eq!(p[1].tip, Vector3::new(115.0, 60.0, 0.0));
    close_vec(&p[2].tip, &Vector3::new(0.0, 10.0, 0.0), 1e-12, "ROT+90");
    assert_eq!(note(&r, "DATUM SHIFT").kind, NoteKind::Frame);
    assert_eq!(note(&r, "ROTATION").kind, NoteKind::Frame);
}

#[test]
fn plane_functions_tilt_the_working_plane_in_their_documented_order() {
    let m = caz_head();
    let s = 0.5f64.sqrt();
    // SPATIAL SPA+0 SPB+45 SPC+0: R = R_Y(45°); tool axis (sin 45°, 0, cos 45°); (0, 0, 10) of
    // the plane is (7.071, 0, 7.071).
    let text = program(&[
        "PLANE SPATIAL SPA+0 SPB+45 SPC+0 TURN MB MAX FMAX",
        "L X+0 Y+0 Z+10 R0 FMAX",
        "PLANE RESET STAY",
        "L Z+20 R0 FMAX",
    ]);
    let (p, r) = read_all(&text, H, Some(&m));
    close_vec(&p[0].axis, &Vector3::new(s, 0.0, s), 1e-15, "SPB+45");
    close_vec(
        &p[0].tip,
        &Vector3::new(10.0 * s, 0.0, 10.0 * s),
        1e-12,
        "tip",
    );
    assert_eq!(p[0].angles, None);
    assert_eq!(note(&r, "PLANE SPATIAL").kind, NoteKind::Frame);
    close_vec(&p[1].axis, &Vector3::z(), 1e-15, "after PLANE RESET");
    // SPA+90 SPB+0 SPC+90: first about X, then Y, then Z, all fixed: R = R_Z(90°)·R_X(90°)
    // takes z to R_Z(90°)·(0, −1, 0) = (1, 0, 0). (C first would give (0, −1, 0).)
    let (p, _) = read_all(
        &program(&[
            "PLANE SPATIAL SPA+90 SPB+0 SPC+90 STAY",
            "L X+0 Y+0 Z+0 R0 FMAX",
        ]),
        H,
        Some(&m),
    );
    close_vec(&p[0].axis, &Vector3::x(), 1e-15, "SPA+90 SPC+90");
    // EULER EULPR+90 EULNU+45 EULROT+0: R_Z(90°)·R_X(45°) takes z to (sin 45°, 0, cos 45°).
    let (p, _) = read_all(
        &program(&[
            "PLANE EULER EULPR+90 EULNU+45 EULROT+0 STAY",
            "L X+0 Y+0 Z+0 R0 FMAX",
        ]),
        H,
        Some(&m),
    );
    close_vec(&p[0].axis, &Vector3::new(s, 0.0, s), 1e-15, "EULER");
    // VECTOR: the normal is the tool axis.
    let (p, _) = read_all(
        &program(&[
            "PLANE VECTOR BX+1 BY+0 BZ+0 NX+0 NY-1 NZ+1 STAY",
            "L X+0 Y+0 Z+0 R0 FMAX",
        ]),
        H,
        Some(&m),
    );
    close_vec(&p[0].axis, &Vector3::new(0.0, -s, s), 1e-15, "VECTOR");
    at(
        &error(&program(&["PLANE AXIAL B+45 STAY"]), H, Some(&m)),
        2,
        3,
        "PLANE AXIAL",
    );
    at(
        &error(&program(&["PLANE SPATIAL SPA+0 SPB+45 STAY"]), H, Some(&m)),
        2,
        3,
        "needs SPC",
    );
}

#[test]
fn plane_stay_leaves_the_machine_s_angles_in_q120_to_q122() {
    let m = caz_head();
    // SPB+45 on a C/A machine: (sin a sin c, −sin a cos c, cos a) = (sin 45°, 0, cos 45°) takes
    // a = ±45°, sin c = ±1; the smallest tilt with A ≥ 0: A = 45°, C = 90°. Q120 is A, Q122 C.
    let text = program(&[
        "PLANE SPATIAL SPA+0 SPB+45 SPC+0 STAY SEQ+",
        "L A+Q120 C+Q122 R0 FMAX",
        "PLANE RESET STAY",
        "L X+0 Y+0 Z+0 R0 FMAX",
    ]);
    let (p, _) = read_all(&text, H, Some(&m));
    assert_eq!(p.len(), 1);
    let [c, a] = p[0].angles.unwrap();
    assert!(
        (c - 90.0).abs() < 1e-9 && (a - 45.0).abs() < 1e-9,
        "{c} {a}"
    );
}

/// `M129` (at the end of its block: iTNC 530 DIN/ISO p.290) or `FUNCTION RESET TCPM` with the
/// rotary axes turned: the blocks after it move the machine's axes, not the tip on the part,
/// so the first point reached so is noted at the statement's line; not once the axes are back
/// at 0°.
#[test]
fn tcp_switched_off_with_the_axes_turned_is_noted() {
    let m = caz_head();
    for (blocks, line, what, moved) in [
        (
            &[
                "L X+0 Y+0 Z+0 R0 FMAX",
                "M128",
                "L A+10 C+30 F500",
                "M129",
                "L X+10 F500",
            ][..],
            5,
            "M129",
            6,
        ),
        (
            &[
                "L X+0 Y+0 Z+0 R0 FMAX",
                "M128",
                "L A+10 C+30 F500 M129",
                "L X+10 F500",
            ][..],
            4,
            "M129",
            5,
        ),
        (
            &[
                "FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS",
                "L X+0 Y+0 Z+0 A+10 C+30 R0 FMAX",
                "FUNCTION RESET TCPM",
                "L X+10 F500",
            ][..],
            4,
            "FUNCTION RESET TCPM",
            5,
        ),
        // In a block that moves in machine coordinates (M91), M129 still acts.
        (
            &[
                "L X+0 Y+0 Z+0 R0 FMAX",
                "M128",
                "L A+10 C+30 F500",
                "L Z+100 R0 FMAX M91 M129",
                "L X+10 Y+0 Z+50 F500",
            ][..],
            5,
            "M129",
            6,
        ),
    ] {
        let (_, r) = read_all(&program(blocks), H, Some(&m));
        let n = note(&r, "switches tool-centre-point control off");
        assert_eq!((n.kind, n.line), (NoteKind::Tcp, line), "{blocks:?}");
        assert!(
            n.text.starts_with(&format!("line {line}: {what} switches"))
                && n.text.contains("(C 30°, A 10°)")
                && n.text.contains(&format!("line {moved} moves")),
            "{}",
            n.text
        );
    }
    // Switched off in a tilted plane with the axes turned: noted after PLANE RESET STAY (the
    // axes stay turned), not after PLANE RESET TURN or MOVE (the control turns them back to 0°:
    // TNC 640 User's Manual, PLANE RESET).
    let tilted = |reset: &str| {
        program(&[
            "L X+0 Y+0 Z+100 R0 FMAX",
            "M128",
            "PLANE SPATIAL SPA+30 SPB+0 SPC+0 STAY",
            "L A+30 C+0 F500",
            "M129",
            reset,
            "L X+10 Y+0 Z+100 R0 FMAX",
        ])
    };
    let (_, r) = read_all(&tilted("PLANE RESET STAY"), H, Some(&m));
    let n = note(&r, "switches tool-centre-point control off");
    assert!(n.line == 6 && n.text.contains("line 8 moves"), "{}", n.text);
    for text in [
        program(&[
            "L X+0 Y+0 Z+0 R0 FMAX",
            "M128",
            "L A+10 C+30 F500",
            "M129",
            "L A+0 C+0 R0 FMAX",
            "L X+10 F500",
        ]),
        tilted("PLANE RESET TURN FMAX"),
        tilted("PLANE RESET MOVE DIST50 FMAX"),
    ] {
        let (_, r) = read_all(&text, H, Some(&m));
        assert!(
            r.notes
                .iter()
                .all(|n| n.kind != NoteKind::Tcp || n.text.contains("tilted")),
            "{text}: {:?}",
            r.notes
        );
    }
    // From 0° after PLANE RESET TURN, an incremental turn starts at 0°.
    let (p, _) = read_all(
        &program(&[
            "L X+0 Y+0 Z+0 A+10 C+30 R0 FMAX",
            "PLANE SPATIAL SPA+30 SPB+0 SPC+0 STAY",
            "PLANE RESET TURN FMAX",
            "L IC+10 X+1 R0 FMAX",
        ]),
        H,
        Some(&m),
    );
    assert_eq!(p.last().unwrap().angles, Some([10.0, 0.0]));
}

#[test]
fn tcp_machine_coordinates_and_cycle_calls() {
    let m = caz_head();
    let (_, r) = read_all(
        &program(&["L X+0 Y+0 Z+0 R0 FMAX", "M128", "L A+10 C+10 F500"]),
        H,
        Some(&m),
    );
    assert_eq!(r.tcp.as_deref(), Some("M128 on line 3"));
    // `M128 F25000` on its own, as a post wrote it (a program for an A/C table, DigiLiner/
    // Heidenhain_Compile `xiaojiubei-123.H`): F is the largest feed of M128's compensating moves
    // (iTNC 530 DIN/ISO p.290), a feed, not another statement.
    let (p, r) = read_all(
        &program(&[
            "L X+0 Y+0 Z+0 R0 FMAX",
            "M128 F25000 ; TCPM ON",
            "L A+10 C+10 F500",
        ]),
        H,
        Some(&m),
    );
    assert_eq!(r.tcp.as_deref(), Some("M128 on line 3"));
    assert_eq!(p.len(), 2);
    assert_eq!(skipped(&r, "feeds"), 2);
    let (_, r) = read_all(
        &program(&[
            "FUNCTION TCPM F TCP AXIS POS PATHCTRL AXIS",
            "L X+0 Y+0 Z+0 A+10 R0 FMAX",
        ]),
        H,
        Some(&m),
    );
    assert_eq!(r.tcp.as_deref(), Some("FUNCTION TCPM on line 2"));
    // M91: machine coordinates, the path breaks; M140 MB MAX: retract, likewise.
    let (p, r) = read_all(
        &program(&[
            "L X+0 Y+0 Z+10 R0 FMAX",
            "L Z+0 R0 FMAX M91",
            "L X+5 R0 FMAX",
            "L Z+5 R0 F100",
        ]),
        H,
        Some(&m),
    );
    assert_eq!(
        p.iter().map(|q| (q.line, q.motion)).collect::<Vec<_>>(),
        [(2, Motion::Rapid), (5, Motion::Rapid)]
    );
    assert_eq!(note(&r, "M91/M92").kind, NoteKind::Break);
    let text = program(&[
        "CYCL DEF 200 DRILLING ~",
        "  Q200=2 ;SET-UP CLEARANCE ~",
        "  Q201=-5 ;DEPTH",
        "L X+10 Y+10 Z+10 R0 FMAX M99",
        "CYCL CALL",
    ]);
    // `~` joins the parameter lines to the block; the text is renumbered by program(), so the
    // continuation lines carry block numbers here, which the joined block ignores.
    let (p, r) = read_all(
        &text
            .replace("2   Q200", "  Q200")
            .replace("3   Q201", "  Q201"),
        H,
        Some(&m),
    );
    assert_eq!(p.len(), 1);
    let n = note(&r, "cycle 200 DRILLING");
    assert_eq!((n.kind, n.count), (NoteKind::Partial, 2));
}

#[test]
fn labels_are_called_and_repeated() {
    let m = caz_head();
    let text = "0 BEGIN PGM LBL MM\n\
                1 L X+0 Y+0 Z+10 R0 FMAX\n\
                2 CALL LBL 1\n\
                3 L X+50 R0 FMAX\n\
                4 LBL 2\n\
                5 L IX+1 R0 F100\n\
                6 CALL LBL 2 REP 2\n\
                7 M30\n\
                8 LBL 1\n\
                9 L X+10 R0 F100\n\
                10 L Y+10\n\
                11 LBL 0\n\
                12 END PGM LBL MM\n";
    let (p, r) = read_all(text, H, Some(&m));
    // Only LBL 2, met in order, is a skipped label: a call starts after its label (a survivor:
    // the subprogram's `at + 1` made `at`), and LBL 0 ends the subprogram.
    assert_eq!(skipped(&r, "labels (LBL)"), 1);
    // The subprogram (lines 10, 11), back to line 4, then line 6 three times (once in order,
    // twice repeated).
    let x: Vec<(u32, f64)> = p.iter().map(|q| (q.line, q.tip.x)).collect();
    assert_eq!(
        x,
        [
            (2, 0.0),
            (10, 10.0),
            (11, 10.0),
            (4, 50.0),
            (6, 51.0),
            (6, 52.0),
            (6, 53.0)
        ]
    );
    at(
        &error(&program(&["CALL LBL 5"]), H, Some(&m)),
        2,
        3,
        "no label 5",
    );
    // Found by cargo-mutants (`Heidenhain::run_from`'s end of a subprogram: `>` made `>=`, two
    // `&&` made `||`). LBL 0 ends a subprogram only when it is called: met in the main
    // program's own run it is a label like any other; a label inside the subprogram (LBL 2)
    // does not end it.
    let text = program(&[
        "L X+0 Y+0 Z+0 R0 FMAX",
        "LBL 0",
        "CALL LBL 1",
        "M30",
        "LBL 1",
        "L X+5",
        "LBL 2",
        "L X+6",
        "LBL 0",
    ]);
    let (p, _) = read_all(&text, H, Some(&m));
    let x: Vec<(u32, f64)> = p.iter().map(|q| (q.line, q.tip.x)).collect();
    assert_eq!(x, [(2, 0.0), (7, 5.0), (9, 6.0)]);
    // A subprogram calling another (survivors: the call's `depth + 1` made `- 1` or `* 1`).
    let text = program(&[
        "CALL LBL 1",
        "M30",
        "LBL 1",
        "CALL LBL 2",
        "LBL 0",
        "LBL 2",
        "L X+5 Y+0 Z+0 R0 FMAX",
        "LBL 0",
    ]);
    let (p, _) = read_all(&text, H, Some(&m));
    assert_eq!(p.iter().map(|q| q.tip.x).collect::<Vec<_>>(), [5.0]);
    // Sections repeated inside each other nine deep: LBL 1 … LBL 9, then CALL LBL 9 REP 1 …
    // CALL LBL 1 REP 1; the call of LBL 9 inside LBL 1's repeat is the ninth level, past the
    // eight the reader follows (a survivor: the repeat's `depth + 1` made `* 1`).
    let mut blocks: Vec<String> = vec!["L X+0 Y+0 Z+0 R0 FMAX".into()];
    blocks.extend((1..=9).map(|n| format!("LBL {n}")));
    blocks.push("L IX+1 F500".into());
    blocks.extend((1..=9).rev().map(|n| format!("CALL LBL {n} REP 1")));
    let blocks: Vec<&str> = blocks.iter().map(String::as_str).collect();
    let e = error(&program(&blocks), H, Some(&m));
    assert!(e.contains("labels call each other more than 8 deep"), "{e}");
    // Two repeats inside each other, 65 534 passes each, empty: 4.3·10⁹ passes, past the 5·10⁷
    // blocks a program may run; refused at the outer call, not run for minutes (a survivor:
    // `count_run` made `Ok(())`).
    let text = program(&[
        "L X+0 Y+0 Z+0 R0 FMAX",
        "LBL 1",
        "LBL 2",
        "CALL LBL 2 REP 65534",
        "CALL LBL 1 REP 65534",
    ]);
    let e = error(&text, H, Some(&m));
    assert!(e.contains("runs more than 50000000 blocks"), "{e}");
    // At the limit exactly: each block run counts once and each pass of a repeat once more.
    // BEGIN PGM, two L, two LBL and END PGM are 6; `CALL LBL 2 REP a` is 1 + a (its passes
    // are empty); `CALL LBL 1 REP b` is 1 + b·(3 + a) (a pass runs LBL 2 and the inner call).
    // With a = 1192, b = 41 840: 8 + 1192 + 41 840 · 1195 = 50 000 000, allowed; b = 41 841
    // is 1195 more, refused.
    for (b, refused) in [(41_840, false), (41_841, true)] {
        let rep = format!("CALL LBL 1 REP {b}");
        let blocks = [
            "L X+0 Y+0 Z+0 R0 FMAX",
            "L X+1",
            "LBL 1",
            "LBL 2",
            "CALL LBL 2 REP 1192",
            &rep,
        ];
        let r = fiveaxis::toolpath::read::read(&program(&blocks), H, Some(&m), Default::default());
        assert_eq!(r.is_err(), refused, "REP {b}");
    }
    // A program without END PGM ends with its last block.
    let (p, _) = read_all("0 BEGIN PGM T MM\n1 L X+1 Y+0 Z+0 R0 FMAX\n", H, Some(&m));
    assert_eq!(p.len(), 1);
}

#[test]
fn q_parameters_that_are_plain_numbers_are_read_and_others_refused() {
    let m = caz_head();
    let (p, _) = read_all(
        &program(&["FN 0: Q1 = +10", "Q2 = 5", "L X+Q1 Y-Q2 Z+0 R0 FMAX"]),
        H,
        Some(&m),
    );
    assert_eq!(p[0].tip, Vector3::new(10.0, -5.0, 0.0));
    at(
        &error(
            &program(&["FN 2: Q3 = +Q1 - +Q2", "L X+Q3 Y+0 Z+0 R0 FMAX"]),
            H,
            Some(&m),
        ),
        3,
        3,
        "computed on line 2",
    );
    at(
        &error(&program(&["L X+Q7 Y+0 Z+0 R0 FMAX"]), H, Some(&m)),
        2,
        3,
        "does not set to a number",
    );
}

#[test]
fn contours_the_control_builds_are_refused_when_run() {
    let m = caz_head();
    for (block, part) in [
        (
            "APPR LCT X+10 Y+0 R5 RL F100",
            "approaches or leaves the contour",
        ),
        ("RND R5", "rounds or chamfers"),
        ("CHF 2", "rounds or chamfers"),
        ("FPOL X+10 Y+10", "free contour programming"),
        ("LP PR+10 PA+45", "polar coordinates"),
        ("CYCL DEF 8.0 MIRROR IMAGE", "mirrors or scales"),
        ("FN 9: IF +Q1 EQU +0 GOTO LBL 1", "jumps on a condition"),
        ("CALL PGM OTHER.H", "calls another program"),
        ("L X+0 Y+0 Z+0 B+10 R0 FMAX", "got B"),
    ] {
        at(&error(&program(&[block]), H, Some(&m)), 2, 3, part);
    }
    // Blocks after M30 that are never called are never run: a jump there is not refused.
    let (p, _) = read_all("0 BEGIN PGM T MM\n1 L X+0 Y+0 Z+0 R0 FMAX\n2 M30\n3 LBL 9\n4 FN 9: IF +Q1 EQU +0 GOTO LBL 9\n5 LBL 0\n6 END PGM T MM\n", H, Some(&m));
    assert_eq!(p.len(), 1);
}

/// CYCL DEF 19 WORKING PLANE tilts by angles whose meaning depends on the machine: refused where
/// its angles are given (19.1). With no angle, or every angle 0, it tilts nothing: the reset a
/// post writes before it starts (NX's Heidenhain post: `CYCL DEF 19.0 WORKING PLANE`, `CYCL DEF
/// 19.1` before `M128`, in DigiLiner/Heidenhain_Compile `YL-02.h`), which is read.
#[test]
fn cycl_def_19_is_refused_where_it_tilts_and_read_where_it_resets() {
    let m = caz_head();
    at(
        &error(
            &program(&["CYCL DEF 19.0 WORKING PLANE", "CYCL DEF 19.1 A+0 B+45 C+0"]),
            H,
            Some(&m),
        ),
        3,
        3,
        "CYCL DEF 19 WORKING PLANE tilts",
    );
    // Angles of 0 with a feed: the control positions the rotary axes itself, to positions the
    // reader would have to guess.
    at(
        &error(
            &program(&["CYCL DEF 19.0 WORKING PLANE", "CYCL DEF 19.1 A+0 C+0 F5000"]),
            H,
            Some(&m),
        ),
        3,
        3,
        "CYCL DEF 19 WORKING PLANE tilts",
    );
    let (p, r) = read_all(
        &program(&[
            "CYCL DEF 19.0 WORKING PLANE",
            "CYCL DEF 19.1",
            "CYCL DEF 19.0 WORKING PLANE",
            "CYCL DEF 19.1 A+0 C+0",
            "L X+0 Y+0 Z+0 R0 FMAX",
        ]),
        H,
        Some(&m),
    );
    assert_eq!(p.len(), 1);
    assert_eq!(skipped(&r, "working plane resets"), 2);
}

/// `CYCL CALL POS X Y Z FMAX` moves to the position, then runs the cycle there (TNC 640
/// cycle programming manual, "CYCL CALL POS"): the moves after it start from the last hole.
#[test]
fn cycl_call_pos_moves_to_its_position() {
    let m = caz_head();
    let text = program(&[
        "CYCL DEF 200 DRILLING",
        "L X+0 Y+0 Z+10 R0 FMAX",
        "CYCL CALL POS X+20 Y+30 Z+0 FMAX",
        "CYCL CALL POS X+40 Y+30 Z+0 FMAX",
        "L Z+5 F500",
        "L X+60",
    ]);
    let (p, r) = read_all(&text, H, Some(&m));
    let got: Vec<_> = p.iter().map(|q| (q.tip, q.motion)).collect();
    assert_eq!(
        got,
        [
            (Vector3::new(0.0, 0.0, 10.0), Motion::Rapid),
            (Vector3::new(20.0, 30.0, 0.0), Motion::Rapid),
            (Vector3::new(40.0, 30.0, 0.0), Motion::Rapid),
            (Vector3::new(40.0, 30.0, 5.0), Motion::Feed),
            (Vector3::new(60.0, 30.0, 5.0), Motion::Feed),
        ]
    );
    assert!(
        note(
            &r,
            "cycle 200 DRILLING is called at the position the block gives"
        )
        .count
            == 2
    );
}

/// `CALL LBL 1 REP 2/2`, as the TNC stores and shows a repeat (remaining/total; the
/// repository's own real file `heid_handwritten_cut.h` line 49 has `REP 20/20`): the section
/// runs once, then twice more. A REP without a number is refused as such.
#[test]
fn call_lbl_rep_in_the_stored_form_n_slash_n() {
    let m = caz_head();
    for rep in ["REP 2/2", "REP2", "REP 2"] {
        let text = program(&[
            "L X+0 Y+0 Z+0 R0 FMAX",
            "LBL 1",
            "L IX+10 F500",
            &format!("CALL LBL 1 {rep}"),
        ]);
        let (p, r) = read_all(&text, H, Some(&m));
        let xs: Vec<f64> = p.iter().map(|q| q.tip.x).collect();
        assert_eq!(xs, [0.0, 10.0, 20.0, 30.0], "{rep}");
        // The repeats start after the label: LBL 1 is met once (a survivor: `at + 1` made `at`).
        assert_eq!(skipped(&r, "labels (LBL)"), 1, "{rep}");
    }
    // A repeated section that calls a subprogram: one level deeper, not past the limit (a
    // survivor: the repeat's `depth + 1` made `- 1`).
    let text = program(&[
        "L X+0 Y+0 Z+0 R0 FMAX",
        "LBL 1",
        "CALL LBL 2",
        "CALL LBL 1 REP 1",
        "M30",
        "LBL 2",
        "L IX+10 F500",
        "LBL 0",
    ]);
    let (p, _) = read_all(&text, H, Some(&m));
    let xs: Vec<f64> = p.iter().map(|q| q.tip.x).collect();
    assert_eq!(xs, [0.0, 10.0, 20.0]);
    // A repeat count is a whole number of 0 or more (a survivor: `&&` made `||` let 2.5 and
    // −1 through).
    for bad in ["REP X", "REP 2.5", "REP -1"] {
        let text = program(&["LBL 1", "L X+0 Y+0 Z+0 FMAX", &format!("CALL LBL 1 {bad}")]);
        let e = error(&text, H, Some(&m));
        assert!(
            e.contains("REP must be followed by the number of repeats"),
            "{bad}: {e}"
        );
    }
    // The refusal points at REP: block 3 is line 4, "3 CALL LBL 1 REP X" has R at column 14
    // (a survivor: each `+` of the column's sum).
    let text = program(&["LBL 1", "L X+0 Y+0 Z+0 FMAX", "CALL LBL 1 REP X"]);
    at(&error(&text, H, Some(&m)), 4, 14, "REP must be followed");
    // REP to a label after the call: there is no part before it to repeat; the label is run
    // once as a subprogram, to its LBL 0 (a survivor: the guard `at < i` made true).
    let text = program(&[
        "L X+0 Y+0 Z+0 R0 FMAX",
        "CALL LBL 1 REP 2",
        "M30",
        "LBL 1",
        "L IX+10 F500",
        "LBL 0",
        "LBL 2",
        "L X+99 FMAX",
        "LBL 0",
    ]);
    let (p, _) = read_all(&text, H, Some(&m));
    let xs: Vec<f64> = p.iter().map(|q| q.tip.x).collect();
    assert_eq!(xs, [0.0, 10.0]);
    // An empty section repeated 4 000 000 000 times: clamped to the TNC's 65 534 and ended.
    let text = program(&["L X+0 Y+0 Z+0 FMAX", "LBL 1", "CALL LBL 1 REP 4000000000"]);
    let (p, _) = read_all(&text, H, Some(&m));
    assert_eq!(p.len(), 1);
}

/// A datum shift programmed after PLANE acts along the tilted axes (TNC7 user's manual,
/// "working plane coordinate system WPL-CS": transformations programmed after tilting);
/// one programmed before is along the workpiece's. PLANE SPATIAL SPB+90: x' = (0, 0, −1),
/// so a shift X+10 after it moves the datum to (0, 0, −10).
#[test]
fn a_datum_shift_after_plane_is_along_the_tilted_axes() {
    let m = caz_head();
    let after = program(&[
        "PLANE SPATIAL SPA+0 SPB+90 SPC+0 TURN MB MAX FMAX SEQ+ TABLE ROT",
        "CYCL DEF 7.0 DATUM SHIFT",
        "CYCL DEF 7.1 X+10",
        "L X+0 Y+0 Z+0 R0 FMAX",
    ]);
    let (p, r) = read_all(&after, H, Some(&m));
    close_vec(
        &p[0].tip,
        &Vector3::new(0.0, 0.0, -10.0),
        1e-12,
        "after PLANE",
    );
    assert!(
        note(&r, "CYCL DEF 7 DATUM SHIFT moves the datum by (10, 0, 0)")
            .text
            .contains("along the tilted plane's axes")
    );
    let before = program(&[
        "TRANS DATUM AXIS X+10",
        "PLANE SPATIAL SPA+0 SPB+90 SPC+0 TURN MB MAX FMAX SEQ+ TABLE ROT",
        "L X+0 Y+0 Z+0 R0 FMAX",
    ]);
    let (p, _) = read_all(&before, H, Some(&m));
    close_vec(
        &p[0].tip,
        &Vector3::new(10.0, 0.0, 0.0),
        1e-12,
        "before PLANE",
    );
}

/// Under M128 in a tilted plane, rotary words give the tool axis (5-axis moves in the plane);
/// an LN vector is the tool direction in the tilted frame. Before M128 the plane's z holds.
#[test]
fn m128_in_a_tilted_plane_follows_the_rotary_words_and_vectors() {
    let m = caz_head();
    let text = program(&[
        "PLANE SPATIAL SPA+30 SPB+0 SPC+0 STAY",
        "L X+0 Y+0 Z+10 R0 FMAX",
        "M128",
        "L X+10 A+45 C+0 F500",
        "LN X+20 Y+0 Z+10 TX+0 TY+0 TZ+1 F500",
    ]);
    let (p, r) = read_all(&text, H, Some(&m));
    // SPA+30: Rx(30°), z' = (0, −0.5, 0.866); A30 C0 on this head gives the same.
    let plane_z = Vector3::new(0.0, -0.5, 3f64.sqrt() / 2.0);
    close_vec(&p[0].axis, &plane_z, 1e-12, "the plane's z");
    close_vec(&p[1].axis, &caz(0.0, 45.0), 1e-12, "A+45 under M128");
    close_vec(&p[2].axis, &plane_z, 1e-12, "TZ+1 in the tilted frame");
    assert_eq!(note(&r, "give the tool axis from here").line, 5);
}

/// Statements the TNC writes that the reader now reads: `M140 MB MAX` on its own (a retract:
/// the path breaks), `PRESET SELECT` (another preset: a break), `F MAX` (not a feed); and two
/// it refuses, naming them: `TRANS DATUM TABLE` (the shift is in a table) and
/// `FUNCTION TCPM … AXIS SPAT` (A B C are spatial angles there).
#[test]
fn m140_preset_select_f_max_and_what_is_refused() {
    let m = caz_head();
    let text = program(&[
        "L X+0 Y+0 Z+0 R0 FMAX",
        "L X+10 F500",
        "M140 MB MAX",
        "L X+20 Y+0 F MAX",
        "L Z+5 FMAX",
        "PRESET SELECT #5",
        "L X+0 Y+0 Z+0 F MAX",
    ]);
    let (p, r) = read_all(&text, H, Some(&m));
    assert_eq!(note(&r, "M140 retracts").kind, NoteKind::Break);
    assert_eq!(note(&r, "PRESET SELECT").kind, NoteKind::Break);
    // After M140 X Y Z are unknown until Z+5 (block 5): then (20, 0, 5).
    assert_eq!(p[2].tip, Vector3::new(20.0, 0.0, 5.0));
    assert_eq!(skipped(&r, "feeds (F)"), 1, "only F500");
    assert!(p[3].motion == Motion::Rapid && p[3].tip == Vector3::zeros());
    for (stmt, part) in [
        ("TRANS DATUM TABLE TABLINE 3", "TRANS DATUM TABLE"),
        ("FUNCTION TCPM F TCP AXIS SPAT PATHCTRL AXIS", "AXIS SPAT"),
    ] {
        let e = error(&program(&[stmt, "L X+0 Y+0 Z+0 FMAX"]), H, Some(&m));
        assert!(e.starts_with("line 2") && e.contains(part), "{e}");
    }
}

// Found by cargo-mutants: the arms of TCH and of SEL … settings deleted, and the guards of
// TRANS DATUM, of Q assignments (`&&` as `||`) and of M-functions made true, survived.
/// A touch-probe cycle is noted (its moves are not drawn); SEL and DECLARE are settings,
/// skipped and counted; a TRANS other than TRANS DATUM, a word the reader does not know, a
/// block of a feed alone (a feed is a word of a move, TOOL CALL or M block), a Q parameter
/// without `=` and an unknown word with one are refused as statements it does not know.
#[test]
fn probe_cycles_settings_and_unknown_statements() {
    let m = caz_head();
    let text = program(&[
        "TCH PROBE 400 BASIC ROTATION",
        "SEL TABLE \"TNC:\\T.D\"",
        "DECLARE STRING QS1 = \"A\"",
        "L X+0 Y+0 Z+0 R0 FMAX",
    ]);
    let (p, r) = read_all(&text, H, Some(&m));
    assert_eq!(p.len(), 1);
    let n = note(&r, "touch-probe cycle");
    assert_eq!((n.line, n.kind), (2, NoteKind::Partial));
    assert_eq!(skipped(&r, "settings (SEL, DECLARE"), 2);
    for stmt in ["TRANS MIRROR X", "FOO 5", "F500", "FMAX", "Q5", "FOO = 5"] {
        let e = error(&program(&[stmt, "L X+0 Y+0 Z+0 R0 FMAX"]), H, Some(&m));
        assert!(
            e.starts_with("line 2") && e.contains("is not a Heidenhain statement the reader knows"),
            "{stmt}: {e}"
        );
    }
}

// Found by cargo-mutants: the `!more` of an empty line survived (a lone `~` started a block
// on its own line, so a point's line was the `~`'s).
/// A block continued with `~` is one block on the line of its first words: a line holding only
/// a comment and `~` before it is not where the block is.
#[test]
fn a_block_continued_with_a_tilde_is_on_the_line_of_its_words() {
    let m = caz_head();
    // Line 2 a comment and `~`; block 1 on lines 3 and 4 (a continued line has no number).
    let text = "0 BEGIN PGM T MM\n; next~\n1 L X+5 Y+0~\nZ+0 R0 FMAX\n2 END PGM T MM\n";
    let (p, r) = read_all(text, H, Some(&m));
    assert_eq!(p.len(), 1);
    assert_eq!((p[0].line, p[0].tip), (3, Vector3::new(5.0, 0.0, 0.0)));
    // BEGIN PGM, the L block (over two lines) and END PGM.
    assert_eq!(r.blocks, 3);
}

/// Detection looks at statements, not comments: a Fanuc program with `(TOOL CALL T1 …)` and a
/// Sinumerik one starting `;TOOL CALL T1` are not Heidenhain.
#[test]
fn detection_ignores_keywords_in_comments() {
    assert_eq!(
        Format::detect("%\nO1000 (TOOL CALL T1 D10 FLAT)\nG90 G21 G17\nG0 X0 Y0 Z10\n"),
        Format::Nc
    );
    assert_ne!(
        Format::detect(";TOOL CALL T1\nG71 G90\nTRAORI\nG0 X0 Y0 Z10\n"),
        Format::Heidenhain
    );
    assert_eq!(
        Format::detect("1 TOOL CALL 5 Z S3000\n"),
        Format::Heidenhain
    );
}

// Found by cargo-mutants: `heidenhain::is_statement`'s `||`, `==` and `!` survived: no test
// detected a file by a CYCL DEF, an FMAX or a numbered block alone.
/// Each of the documented telling lines alone makes a file Heidenhain (`Format::detect`'s
/// doc): a numbered `CYCL DEF`, an unnumbered block with `FMAX`, a numbered `L` block with a feed.
/// A block's number is followed by a space (TNC: `12 L X+10`): `12L X+10` is no Heidenhain block.
#[test]
fn one_telling_line_makes_a_file_heidenhain() {
    for text in [
        "5 CYCL DEF 200 DRILLING\n",
        "L X+10 Y+0 R0 FMAX\n",
        "12 L X+10 Y+0 R0 F100\n",
    ] {
        assert_eq!(Format::detect(text), Format::Heidenhain, "{text:?}");
    }
    assert_ne!(Format::detect("12L X+10 Y+0\n"), Format::Heidenhain);
}

// Found by cargo-mutants: PRESET's guard made true and its `||` as `&&` survived.
/// The four preset functions of the NC program each break the path at their line (the preset
/// they select or change is in the preset table, not the file); any other PRESET word is
/// refused, named.
#[test]
fn each_preset_function_breaks_the_path_and_another_is_refused() {
    let m = caz_head();
    for f in [
        "SELECT #5",
        "COPY #1 TO #3",
        "SET #3 X+10",
        "CORRECT #3 X+0.1",
        "select #2",
    ] {
        let text = program(&[
            "L X+0 Y+0 Z+0 R0 FMAX",
            &format!("PRESET {f}"),
            "L X+5 F100",
        ]);
        let (p, r) = read_all(&text, H, Some(&m));
        let n = note(&r, "selects or changes a preset");
        assert_eq!((n.line, n.kind), (3, NoteKind::Break), "PRESET {f}");
        // The feed move after the break is reached across an unknown datum: drawn as a rapid.
        assert_eq!(p.len(), 2, "PRESET {f}: {p:?}");
        assert_eq!((p[1].line, p[1].motion), (4, Motion::Rapid), "PRESET {f}");
    }
    let e = error(
        &program(&["PRESET TABLE #5", "L X+0 Y+0 Z+0 R0 FMAX"]),
        H,
        Some(&m),
    );
    assert!(
        e.starts_with("line 2") && e.contains("is not a preset function the reader knows"),
        "{e}"
    );
}

// Found by cargo-mutants: the axis letters of TOOL CALL deleted survived (the tool axis set
// nothing the tests read).
/// Cycle 10 ROTATION turns about the tool axis of the last TOOL CALL: ROT+90 takes the first
/// axis of the working plane to the second (X to Y about Z, Y to Z about X, Z to X about Y).
#[test]
fn rotation_turns_about_the_tool_axis_of_the_last_tool_call() {
    let m = caz_head();
    // Each case: the tool calls, then the expected image of the point (10, 0, 0) and of
    // (0, 10, 0) under ROT+90 about that axis: R_Z(90°)(10,0,0) = (0,10,0);
    // R_X(90°)(0,10,0) = (0,0,10); R_Y(90°)(10,0,0) = (0,0,-10).
    for (calls, from, to) in [
        (
            vec!["TOOL CALL 1 Z S5000"],
            [10.0, 0.0, 0.0],
            [0.0, 10.0, 0.0],
        ),
        (
            vec!["TOOL CALL 1 X S5000"],
            [0.0, 10.0, 0.0],
            [0.0, 0.0, 10.0],
        ),
        (
            vec!["TOOL CALL 1 Y S5000"],
            [10.0, 0.0, 0.0],
            [0.0, 0.0, -10.0],
        ),
        (
            vec!["TOOL CALL 1 X", "TOOL CALL 2 Z"],
            [10.0, 0.0, 0.0],
            [0.0, 10.0, 0.0],
        ),
        (
            vec!["TOOL CALL 1 Z", "TOOL CALL \"MILL\" Y"],
            [10.0, 0.0, 0.0],
            [0.0, 0.0, -10.0],
        ),
    ] {
        let mv = format!("L X{:+} Y{:+} Z{:+} R0 FMAX", from[0], from[1], from[2]);
        let mut blocks = calls.clone();
        blocks.extend(["CYCL DEF 10.0 ROTATION", "CYCL DEF 10.1 ROT+90", &mv]);
        let (p, _) = read_all(&program(&blocks), H, Some(&m));
        close_vec(&p[0].tip, &Vector3::from(to), 1e-12, &format!("{calls:?}"));
    }
}

// Found by cargo-mutants: TRANS DATUM's `i < 3` as `i <= 3` survived (no axis has index 3:
// the rotary and parallel axes' words were dropped without a word).
/// A datum shift of a rotary axis is refused, named, by both datum shifts (a parallel axis, U V
/// W, is refused as an axis the calculator does not read); a shift of X, Y and Z is applied.
#[test]
fn a_datum_shift_of_a_rotary_axis_is_refused() {
    let m = caz_head();
    for (shift, word) in [
        (vec!["TRANS DATUM AXIS X+10 C+90"], "C+90"),
        (vec!["TRANS DATUM AXIS IA+5"], "IA+5"),
        (
            vec!["CYCL DEF 7.0 DATUM SHIFT", "CYCL DEF 7.1 B+30"],
            "B+30",
        ),
        (
            vec!["CYCL DEF 7.0 DATUM SHIFT", "CYCL DEF 7.1 IC-45"],
            "IC-45",
        ),
    ] {
        let mut blocks = shift.clone();
        blocks.push("L X+0 Y+0 Z+0 R0 FMAX");
        let e = error(&program(&blocks), H, Some(&m));
        let line = shift.len() + 1;
        assert!(
            e.starts_with(&format!("line {line}"))
                && e.contains(word)
                && e.contains("shifts a rotary axis"),
            "{shift:?}: {e}"
        );
    }
    let (p, _) = read_all(
        &program(&["TRANS DATUM AXIS X+10 Y-5 Z+2", "L X+0 Y+0 Z+0 R0 FMAX"]),
        H,
        Some(&m),
    );
    assert_eq!(p[0].tip, Vector3::new(10.0, -5.0, 2.0));
}

// Found by cargo-mutants: the `at` of the arc's block deleted survived (column 1 for every arc
// error).
/// An arc's error names the column of its statement, after the block number: here an arc
/// whose end is off its circle.
#[test]
fn an_arc_error_names_the_column_of_its_statement() {
    let m = caz_head();
    // From (10, 0) about (0, 0) to (0, 20): 10 mm from the centre at the start, 20 at the end.
    let text = program(&["L X+10 Y+0 Z+0 R0 FMAX", "CC X+0 Y+0", "C X+0 Y+20 DR+"]);
    at(
        &error(&text, H, Some(&m)),
        4,
        3,
        "the arc's end is not on its circle",
    );
}

// Found by cargo-mutants: the arm of U V W deleted survived (the word was then dropped from
// the L block without a word).
/// A parallel axis U, V or W in a straight line, absolute or incremental, is refused at its
/// line as an axis the calculator does not read, not dropped.
#[test]
fn a_parallel_axis_in_a_line_is_refused() {
    let m = caz_head();
    for word in ["U+5", "V-2", "W+0", "IW+1"] {
        let text = program(&["L X+0 Y+0 Z+0 R0 FMAX", &format!("L X+10 {word} F500")]);
        let e = error(&text, H, Some(&m));
        let letter = word.trim_start_matches('I').chars().next().unwrap();
        assert!(
            e.starts_with("line 3")
                && e.contains(&format!("{letter} is an axis the calculator does not read")),
            "{word}: {e}"
        );
    }
}

/// The commanded C and A angles of the last point.
fn last_angles(p: &[fiveaxis::toolpath::read::Point]) -> [f64; 2] {
    p.last().and_then(|q| q.angles).unwrap()
}

// Found by cargo-mutants: in an L block, the arms of M126, M127, M128, M30/M2, M140 and of RL/RR
// deleted survived (the tests gave these functions in blocks of their own), and M91's rotary
// words' update (`==` as `!=`, `+` as `-` or `*`).
/// M-functions written in a straight-line block act as in a block of their own (TNC 620
/// User's Manual, M126 "shortest-path traverse of rotary axes", M128, M140, M30): M126 turns
/// C from 0° to 350° the short way (to −10°), M127 the literal way; M128 switches on
/// tool-centre-point control at its line; M30 ends the program; M140 retracts and breaks the
/// path. RL or RR is noted as radius compensation. A rotary word in an M91 block is the
/// axis's position afterwards: C+90 from 10° is 90°, IC+90 is 100°.
#[test]
fn m_functions_in_a_line_block() {
    let m = caz_head();
    let start = "L X+0 Y+0 Z+0 A+0 C+0 R0 FMAX";
    // In the L block or in a block of its own, before the move.
    for (blocks, c) in [
        (vec!["L C+350 F500 M126"], -10.0),
        (vec!["M126", "L C+350 F500"], -10.0),
        (vec!["M126", "L C+350 F500 M127"], 350.0),
        (vec!["L C+0 F500 M126", "M127", "L C+350 F500"], 350.0),
    ] {
        let mut all = vec![start];
        all.extend(&blocks);
        let (p, _) = read_all(&program(&all), H, Some(&m));
        assert!(
            (last_angles(&p)[0] - c).abs() < 1e-9,
            "{blocks:?}: {:?}",
            last_angles(&p)
        );
    }
    let (_, r) = read_all(&program(&[start, "L X+10 F500 M128"]), H, Some(&m));
    assert_eq!(r.tcp.as_deref(), Some("M128 on line 3"));
    for end in ["M30", "M2"] {
        let (p, _) = read_all(
            &program(&[start, &format!("L X+10 F500 {end}"), "L X+20 F500"]),
            H,
            Some(&m),
        );
        assert_eq!(p.last().unwrap().tip, Vector3::new(10.0, 0.0, 0.0), "{end}");
    }
    let (p, r) = read_all(
        &program(&[start, "L X+10 R0 FMAX M140 MB MAX"]),
        H,
        Some(&m),
    );
    assert_eq!(p.len(), 1);
    assert_eq!(
        (
            note(&r, "M140 retracts").line,
            note(&r, "M140 retracts").kind
        ),
        (3, NoteKind::Break)
    );
    for comp in ["RL", "RR"] {
        let (_, r) = read_all(
            &program(&[start, &format!("L X+10 {comp} F500")]),
            H,
            Some(&m),
        );
        assert_eq!(note(&r, "radius compensation").line, 3, "{comp}");
    }
    for (rotary, c) in [("C+90", 90.0), ("IC+90", 100.0)] {
        let text = program(&[
            "L X+0 Y+0 Z+0 A+0 C+10 R0 FMAX",
            &format!("L Z+0 {rotary} R0 FMAX M91"),
            "L X+5 Y+0 Z+0 F500",
        ]);
        let (p, _) = read_all(&text, H, Some(&m));
        assert!(
            (last_angles(&p)[0] - c).abs() < 1e-9,
            "{rotary}: {:?}",
            last_angles(&p)
        );
    }
}

// Found by cargo-mutants: the guard of `F MAX` (a MAX after F) made true survived.
/// `F MAX` with a space is the rapid FMAX; a MAX after another word leaves the block a feed.
#[test]
fn max_is_a_rapid_only_after_f() {
    let m = caz_head();
    let start = "L X+0 Y+0 Z+0 R0 FMAX";
    let (p, _) = read_all(&program(&[start, "L X+10 R0 F MAX"]), H, Some(&m));
    assert_eq!(p.last().unwrap().motion, Motion::Rapid);
    let (p, _) = read_all(&program(&[start, "L X+10 R0 F500 MAX"]), H, Some(&m));
    assert_eq!(p.last().unwrap().motion, Motion::Feed);
}

// Found by cargo-mutants: M140's own words' guard (`&&` as `||`) survived: with it, MB and MAX
// were passed over in any M block, and every word after M140.
/// In a block of M-functions, `MB` and `MAX` belong to M140 (TNC 620 User's Manual, "M140 MB
/// MAX"): after M140 they are its words and an M-function after them still acts (M30 ends the
/// program); without M140 they are refused as statements the reader does not know.
#[test]
fn mb_and_max_belong_to_m140() {
    let m = caz_head();
    let start = "L X+0 Y+0 Z+0 R0 FMAX";
    let (p, r) = read_all(
        &program(&[start, "M140 MB MAX M30", "L X+10 Y+0 Z+0 R0 FMAX"]),
        H,
        Some(&m),
    );
    assert_eq!(p.len(), 1);
    assert_eq!(note(&r, "M140 retracts").line, 3);
    for block in ["M3 MB+10", "M3 MAX"] {
        let e = error(&program(&[start, block]), H, Some(&m));
        assert!(
            e.starts_with("line 3") && e.contains("is not a Heidenhain statement"),
            "{block}: {e}"
        );
    }
}

// Found by cargo-mutants: in a block of M-functions only, the arm of M99/M89 deleted and the
// feed's length test (`>` as `>=`) survived.
/// M99 or M89 in a block of its own calls the cycle last defined at the current position (a
/// note: its moves are not drawn); a feed there is `F` with a value (`M128 F25000`), and a
/// lone `F` is refused.
#[test]
fn a_cycle_called_by_m99_alone_and_a_lone_f_refused() {
    let m = caz_head();
    for call in ["M99", "M89"] {
        let text = program(&[
            "CYCL DEF 200 DRILLING Q200=2 Q201=-5",
            "L X+10 Y+10 Z+10 R0 FMAX",
            call,
        ]);
        let (_, r) = read_all(&text, H, Some(&m));
        let n = note(&r, "is called at the current position");
        assert_eq!((n.line, n.kind), (4, NoteKind::Partial), "{call}");
        assert!(
            n.text.contains("cycle 200 DRILLING is called"),
            "{call}: {}",
            n.text
        );
    }
    let e = error(&program(&["L X+0 Y+0 Z+0 R0 FMAX", "M128 F"]), H, Some(&m));
    assert!(
        e.starts_with("line 3") && e.contains("is not a Heidenhain statement"),
        "{e}"
    );
}

// Found by cargo-mutants: in an arc block, FMAX's arm, F MAX's guard (true and false), the
// lone R's length test, the polar radius's `||`, and the arms of M128, M129 and M30/M2
// survived (the tests wrote these words in L blocks only).
/// The words an arc block shares with a line (TNC 620 User's Manual, C with DR±, CR with R±):
/// FMAX and `F MAX` make the arc a rapid, `F500 MAX` leaves it cut; M128 switches on
/// tool-centre-point control at its line and M129 off at the end of its block; M30 and M2 end
/// the program. A lone `R` in CR is no radius (CR then needs one); a polar radius PR or IPR is
/// refused.
#[test]
fn an_arc_block_reads_fmax_and_m_functions() {
    let m = caz_head();
    let arc = |words: &str| {
        program(&[
            "L X+10 Y+0 Z+0 R0 FMAX",
            "CC X+0 Y+0",
            &format!("C X+0 Y+10 DR+ {words}"),
            "L X+20 Y+0 F500",
        ])
    };
    for (words, motion) in [
        ("FMAX", Motion::Rapid),
        ("F MAX", Motion::Rapid),
        ("F500 MAX", Motion::Arc),
        ("F500", Motion::Arc),
    ] {
        let (p, _) = read_all(&arc(words), H, Some(&m));
        let on_arc: Vec<_> = p.iter().filter(|q| q.line == 4).collect();
        assert!(
            !on_arc.is_empty() && on_arc.iter().all(|q| q.motion == motion),
            "{words}"
        );
    }
    let (_, r) = read_all(&arc("F500 M128"), H, Some(&m));
    assert_eq!(r.tcp.as_deref(), Some("M128 on line 4"));
    for end in ["M30", "M2"] {
        let (p, _) = read_all(&arc(&format!("F500 {end}")), H, Some(&m));
        close_vec(
            &p.last().unwrap().tip,
            &Vector3::new(0.0, 10.0, 0.0),
            1e-9,
            end,
        );
    }
    let text = program(&[
        "L X+10 Y+0 Z+0 R0 FMAX",
        "M128",
        "L A+10 C+30 F500",
        "CC X+0 Y+0",
        "C X+0 Y+10 DR+ F500 M129",
        "L X+10 F500",
    ]);
    let (_, r) = read_all(&text, H, Some(&m));
    let n = note(&r, "switches tool-centre-point control off");
    assert_eq!((n.kind, n.line), (NoteKind::Tcp, 6));
    let start = ["L X+10 Y+0 Z+0 R0 FMAX"];
    let e = error(&program(&[start[0], "CR X+0 Y+10 R DR+"]), H, Some(&m));
    assert!(
        e.starts_with("line 3") && e.contains("CR needs its radius"),
        "{e}"
    );
    for pr in ["PR+10", "IPR+5"] {
        let e = error(
            &program(&[start[0], "CC X+0 Y+0", &format!("C X+0 Y+10 DR+ {pr}")]),
            H,
            Some(&m),
        );
        assert!(
            e.starts_with("line 4") && e.contains("with a polar radius"),
            "{pr}: {e}"
        );
    }
}

// Found by cargo-mutants: the incremental pole's `+` (as `-` or `*`) and the arms of the XY
// and YZ planes deleted survived (without a TOOL CALL the default plane is XY).
/// `CC IX-10 IY+0` from (10, 0) puts the pole at (0, 0); CC's two axes give the arc's plane
/// whatever the tool axis: X Y after `TOOL CALL 1 X`, Y Z without a TOOL CALL. Each arc's
/// points are 10 mm from the pole, in its plane.
#[test]
fn the_pole_incremental_and_its_plane_from_its_axes() {
    let m = caz_head();
    for (blocks, normal) in [
        (
            vec![
                "L X+10 Y+0 Z+0 R0 FMAX",
                "CC IX-10 IY+0",
                "C X+0 Y+10 DR+ F500",
            ],
            2,
        ),
        (
            vec![
                "TOOL CALL 1 X S5000",
                "L X+10 Y+0 Z+0 R0 FMAX",
                "CC X+0 Y+0",
                "C X+0 Y+10 DR+ F500",
            ],
            2,
        ),
        (
            vec![
                "L X+0 Y+10 Z+0 R0 FMAX",
                "CC Y+0 Z+0",
                "C Y+0 Z+10 DR+ F500",
            ],
            0,
        ),
    ] {
        let (p, _) = read_all(&program(&blocks), H, Some(&m));
        let arc_line = blocks.len() as u32 + 1;
        let on_arc: Vec<_> = p.iter().filter(|q| q.line == arc_line).collect();
        assert!(!on_arc.is_empty(), "{blocks:?}");
        for q in on_arc {
            assert!(
                (q.tip.norm() - 10.0).abs() < 1e-9 && q.tip[normal].abs() < 1e-12,
                "{blocks:?}: {:?}",
                q.tip
            );
        }
    }
}

// Found by cargo-mutants: CP's absolute angle (its match arm deleted, and the start's angle
// about the pole, `-` as `+` or `/`) survived: the tests gave CP an incremental IPA only.
/// `CP PA+180` turns about the pole to the absolute polar angle 180° (TNC 426/430 User's
/// Manual, CP): about CC (5, 5) from (11, 13), at atan2(8, 6) = 53.13° about the pole, DR+
/// turns 126.87° counter-clockwise to (−5, 5); DR− turns 233.13° clockwise to the same end,
/// through (5, −5).
#[test]
fn cp_turns_to_an_absolute_polar_angle() {
    let m = caz_head();
    for (dr, below) in [("DR+", false), ("DR-", true)] {
        let text = program(&[
            "CC X+5 Y+5",
            "L X+11 Y+13 Z+0 R0 FMAX",
            &format!("CP PA+180 {dr} F500"),
        ]);
        let (p, _) = read_all(&text, H, Some(&m));
        let pole = Vector3::new(5.0, 5.0, 0.0);
        let on_arc: Vec<_> = p.iter().filter(|q| q.line == 4).collect();
        for q in &on_arc {
            assert!(
                ((q.tip - pole).norm() - 10.0).abs() < 1e-9,
                "{dr}: {:?}",
                q.tip
            );
        }
        close_vec(
            &on_arc.last().unwrap().tip,
            &Vector3::new(-5.0, 5.0, 0.0),
            1e-9,
            dr,
        );
        assert_eq!(on_arc.iter().any(|q| q.tip.y < -4.9), below, "{dr}");
    }
}

// Found by cargo-mutants: CP's check of its angle against its direction (`||` as `&&`), CT's
// incremental end (`+` as `-` or `*`), the parts of the end and of the tangent normal to the
// plane (`-=` as `+=`, `-` as `+`) and the straight case's tolerance (`<` as `==`, `*` as `/`)
// survived.
/// CP refuses an angle whose sign disagrees with DR±. CT (TNC 320 User's Manual, "CT: circular
/// path with tangential connection") from (10, 0) after a move along +X to (20, 10) turns about
/// (10, 10) (ρ = |E − S|²/(2·n·(E − S)) = 200/20 = 10), whether the end is incremental, the end
/// or the move before climbs along Z (a helix: the part in the plane is the same), and an end
/// 5·10⁻⁹ mm off the tangent (under its 10⁻⁹ of the chord) is a straight move.
#[test]
fn cp_s_direction_and_ct_in_its_plane() {
    let m = caz_head();
    for cp in ["CP IPA-90 DR+", "CP IPA+90 DR-"] {
        let e = error(
            &program(&["CC X+0 Y+0", "L X+10 Y+0 Z+0 R0 FMAX", cp]),
            H,
            Some(&m),
        );
        assert!(
            e.starts_with("line 4") && e.contains("disagree"),
            "{cp}: {e}"
        );
    }
    for (before, ct, z) in [
        ("L X+10 Y+0 Z+0 F100", "CT IX+10 IY+10", 0.0),
        ("L X+10 Y+0 Z+0 F100", "CT X+20 Y+10 Z+5", 5.0),
        ("L X+10 Y+0 Z+10 F100", "CT X+20 Y+10", 10.0),
    ] {
        let (p, _) = read_all(
            &program(&["L X+0 Y+0 Z+0 R0 FMAX", before, ct]),
            H,
            Some(&m),
        );
        let on_arc: Vec<_> = p.iter().filter(|q| q.line == 4).collect();
        assert!(on_arc.len() > 1, "{ct}");
        for q in &on_arc {
            let r = (q.tip.xy() - nalgebra::Vector2::new(10.0, 10.0)).norm();
            assert!((r - 10.0).abs() < 1e-9, "{before} {ct}: {:?}", q.tip);
        }
        close_vec(
            &on_arc.last().unwrap().tip,
            &Vector3::new(20.0, 10.0, z),
            1e-9,
            ct,
        );
    }
    let (p, _) = read_all(
        &program(&[
            "L X+0 Y+0 Z+0 R0 FMAX",
            "L X+10 F100",
            "CT X+20 Y+0.000000005",
        ]),
        H,
        Some(&m),
    );
    let last = p.last().unwrap();
    assert_eq!((last.line, last.motion), (4, Motion::Feed));
}

// Found by cargo-mutants: the `||` of "neither M91/M92 nor M140" (as `&&`) survived; the
// condition itself dropped a cycle call in such a block without a word, and is gone.
/// M99 in a block that moves in machine coordinates (M91) or retracts (M140) still calls the
/// cycle: it is noted at its line, like M99 in any line block.
#[test]
fn m99_with_m91_or_m140_is_noted() {
    let m = caz_head();
    for block in [
        "L X+10 Y+10 Z+100 R0 FMAX M91 M99",
        "L Z+100 R0 FMAX M140 MB MAX M99",
        "L X+10 Y+10 Z+10 R0 FMAX M99",
    ] {
        let text = program(&["CYCL DEF 200 DRILLING", "L X+0 Y+0 Z+0 R0 FMAX", block]);
        let (_, r) = read_all(&text, H, Some(&m));
        let n = note(&r, "is called at the block's end point");
        assert_eq!((n.line, n.kind), (4, NoteKind::Partial), "{block}");
    }
}

// Found by cargo-mutants: the arms of CYCL DEF 247 and of the settings cycles deleted, and
// IROT's `+=` (as `-=` or `*=`), survived.
/// CYCL DEF 247 DATUM SETTING selects another preset: the path breaks there (a note). CYCL
/// DEF 32 TOLERANCE is a setting, counted as one. CYCL DEF 10 IROT adds to the rotation:
/// ROT+30 then IROT+60 is 90°, which takes (10, 0, 0) to (0, 10, 0).
#[test]
fn datum_setting_tolerance_and_an_incremental_rotation() {
    let m = caz_head();
    let start = "L X+0 Y+0 Z+0 R0 FMAX";
    let (p, r) = read_all(
        &program(&[start, "CYCL DEF 247 DATUM SETTING", "L X+10 Y+0 Z+0 F500"]),
        H,
        Some(&m),
    );
    let n = note(&r, "CYCL DEF 247");
    assert_eq!((n.line, n.kind), (3, NoteKind::Break));
    assert_eq!(p.last().unwrap().motion, Motion::Rapid);
    for def in ["CYCL DEF 32.0 TOLERANCE", "CYCL DEF 9.0 DWELL TIME"] {
        let (_, r) = read_all(&program(&[start, def]), H, Some(&m));
        assert_eq!(skipped(&r, "settings cycles"), 1, "{def}");
        assert_eq!(skipped(&r, "cycle definitions"), 0, "{def}");
    }
    let text = program(&[
        "CYCL DEF 10.0 ROTATION",
        "CYCL DEF 10.1 ROT+30",
        "CYCL DEF 10.0 ROTATION",
        "CYCL DEF 10.1 IROT+60",
        "L X+10 Y+0 Z+0 R0 FMAX",
    ]);
    let (p, _) = read_all(&text, H, Some(&m));
    close_vec(
        &p[0].tip,
        &Vector3::new(0.0, 10.0, 0.0),
        1e-12,
        "ROT+30 IROT+60",
    );
}

// Found by cargo-mutants: PLANE RELATIV (its arm, each angle's arm, and the product with the
// plane before as a sum) and the datum shift kept when the plane changes (`!=` as `==`, `+=`
// as `-=`) survived.
/// PLANE RELATIV turns the working plane about one axis of the current one (TNC 620 User's
/// Manual, PLANE RELATIV: "incremental spatial angle"): SPA+90 alone is R_X(90°) (tool axis
/// (0, −1, 0), (0, 10, 0) of the plane at (0, 0, 10)); SPB+90 is R_Y(90°) (axis (1, 0, 0),
/// (0, 0, 10) at (10, 0, 0)); SPC+90 is R_Z(90°) ((10, 0, 0) at (0, 10, 0)); after SPB+45,
/// SPC+90 gives R_Y(45°)·R_Z(90°): axis (sin 45°, 0, cos 45°), (10, 0, 0) at (0, 10, 0).
/// A datum shift programmed in a tilted plane stays where it is when the plane changes:
/// X+10 in R_Y(90°) is (0, 0, −10) of the workpiece, after PLANE RESET too (a note); a new
/// plane without such a shift makes no such note.
#[test]
fn plane_relativ_and_a_tilted_shift_kept() {
    let m = caz_head();
    let s = 0.5f64.sqrt();
    for (planes, point, tip, axis) in [
        (
            vec!["PLANE RELATIV SPA+90 STAY"],
            "L X+0 Y+10 Z+0 R0 FMAX",
            [0.0, 0.0, 10.0],
            [0.0, -1.0, 0.0],
        ),
        (
            vec!["PLANE RELATIV SPB+90 STAY"],
            "L X+0 Y+0 Z+10 R0 FMAX",
            [10.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
        ),
        (
            vec!["PLANE RELATIV SPC+90 STAY"],
            "L X+10 Y+0 Z+0 R0 FMAX",
            [0.0, 10.0, 0.0],
            [0.0, 0.0, 1.0],
        ),
        (
            vec![
                "PLANE SPATIAL SPA+0 SPB+45 SPC+0 STAY",
                "PLANE RELATIV SPC+90 STAY",
            ],
            "L X+10 Y+0 Z+0 R0 FMAX",
            [0.0, 10.0, 0.0],
            [s, 0.0, s],
        ),
    ] {
        let mut blocks = planes.clone();
        blocks.push(point);
        let (p, _) = read_all(&program(&blocks), H, Some(&m));
        close_vec(
            &p[0].tip,
            &Vector3::from(tip),
            1e-12,
            planes.last().unwrap(),
        );
        close_vec(
            &p[0].axis,
            &Vector3::from(axis),
            1e-15,
            planes.last().unwrap(),
        );
    }
    let text = program(&[
        "PLANE SPATIAL SPA+0 SPB+90 SPC+0 STAY",
        "TRANS DATUM AXIS X+10",
        "PLANE RESET STAY",
        "L X+0 Y+0 Z+0 R0 FMAX",
    ]);
    let (p, r) = read_all(&text, H, Some(&m));
    close_vec(&p[0].tip, &Vector3::new(0.0, 0.0, -10.0), 1e-12, "kept");
    assert_eq!(note(&r, "the datum is kept where it is").line, 4);
    let text = program(&[
        "PLANE SPATIAL SPA+0 SPB+90 SPC+0 STAY",
        "PLANE RESET STAY",
        "L X+0 Y+0 Z+0 R0 FMAX",
    ]);
    let (_, r) = read_all(&text, H, Some(&m));
    assert!(
        r.notes
            .iter()
            .all(|n| !n.text.contains("the datum is kept")),
        "{:#?}",
        r.notes
    );
}

// Found by cargo-mutants: the arc's plane from its end words (the three arms deleted), the
// plane's polar axes (always X and Y), and CT's tangent in the plane (`-` as `+`) survived.
/// An arc's plane comes from its two end words whatever the tool axis (TNC 320 User's Manual,
/// CR): CR X+10 Y+0 after `TOOL CALL 1 X` is in XY, about (5, 0, 0); CR X+10 Z+0 in ZX, about
/// (5, 0, 0); CR Y+10 Z+0 in YZ, about (0, 5, 0). In the ZX plane CP's polar angle runs from
/// Z towards X: from (10, 0, 0), at 90°, `CP PA+180 DR+` ends at (0, 0, −10). CT after a move
/// along the plane's normal has no tangent in the plane: refused.
#[test]
fn an_arc_s_plane_from_its_words_and_polar_angles_in_zx() {
    let m = caz_head();
    for (blocks, centre, normal) in [
        (
            vec![
                "TOOL CALL 1 X S5000",
                "L X+0 Y+0 Z+0 R0 FMAX",
                "CR X+10 Y+0 R+5 DR- F500",
            ],
            [5.0, 0.0, 0.0],
            2,
        ),
        (
            vec!["L X+0 Y+0 Z+0 R0 FMAX", "CR X+10 Z+0 R+5 DR- F500"],
            [5.0, 0.0, 0.0],
            1,
        ),
        (
            vec!["L X+0 Y+0 Z+0 R0 FMAX", "CR Y+10 Z+0 R+5 DR- F500"],
            [0.0, 5.0, 0.0],
            0,
        ),
    ] {
        let (p, _) = read_all(&program(&blocks), H, Some(&m));
        let arc_line = blocks.len() as u32 + 1;
        let on_arc: Vec<_> = p.iter().filter(|q| q.line == arc_line).collect();
        assert!(on_arc.len() > 2, "{blocks:?}");
        for q in &on_arc {
            let r = (q.tip - Vector3::from(centre)).norm();
            assert!((r - 5.0).abs() < 1e-9, "{blocks:?}: {:?}", q.tip);
            assert!(
                q.tip[normal].abs() < 1e-12,
                "{blocks:?}: {:?} off the plane",
                q.tip
            );
        }
    }
    let text = program(&["CC X+0 Z+0", "L X+10 Y+0 Z+0 R0 FMAX", "CP PA+180 DR+ F500"]);
    let (p, _) = read_all(&text, H, Some(&m));
    close_vec(
        &p.last().unwrap().tip,
        &Vector3::new(0.0, 0.0, -10.0),
        1e-9,
        "PA+180 in ZX",
    );
    let e = error(
        &program(&["L X+0 Y+0 Z+0 R0 FMAX", "L Z+10 F100", "CT X+10 Y+10"]),
        H,
        Some(&m),
    );
    assert!(
        e.starts_with("line 4") && e.contains("normal to the plane of the arc"),
        "{e}"
    );
}

// Found by cargo-mutants: the quotes of `strip_comment` (the arm of `"` deleted, its `!`
// deleted, the `;` guard made true) survived: no test had a `;` inside quotes.
/// A `;` inside quotes is text, not the start of a comment: the tool named "T;1" is called
/// along X, so cycle 10's rotation of 90° turns about X and takes (0, 10, 0) to (0, 0, 10).
#[test]
fn a_semicolon_inside_quotes_is_not_a_comment() {
    let m = caz_head();
    let text = program(&[
        "TOOL CALL \"T;1\" X S5000 ; a comment",
        "CYCL DEF 10.0 ROTATION",
        "CYCL DEF 10.1 ROT+90",
        "L X+0 Y+10 Z+0 R0 FMAX",
    ]);
    let (p, _) = read_all(&text, H, Some(&m));
    close_vec(&p[0].tip, &Vector3::new(0.0, 0.0, 10.0), 1e-12, "about X");
}
